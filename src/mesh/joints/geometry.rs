//! The geometry of joints, free of gmsh: normals from orientations, the
//! planes of a set that cross a box, the patches a plane is made of (one
//! polygon covering the box, or finite joints with rock bridges between
//! them), and how far a plane passes from the corners of the bodies.
//!
//! 3D: x east, y north, z up; a plane of dip δ and dip direction α has the
//! upward unit normal n = (sin δ sin α, sin δ cos α, cos δ). 2D: a trace at
//! angle θ from +x has the normal n = (-sin θ, cos θ). Plane k of a set is
//! n . x = offset + k spacing.

/// `[xmin, ymin, zmin, xmax, ymax, zmax]`.
pub type Bbox = [f64; 6];

pub fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

fn unit(a: [f64; 3]) -> [f64; 3] {
    let l = dot(a, a).sqrt();
    [a[0] / l, a[1] / l, a[2] / l]
}

fn axpy(x: [f64; 3], s: f64, v: [f64; 3]) -> [f64; 3] {
    [x[0] + s * v[0], x[1] + s * v[1], x[2] + s * v[2]]
}

/// The upward unit normal of a plane of dip and dip direction (degrees).
pub fn normal_3d(dip: f64, dip_direction: f64) -> [f64; 3] {
    let (d, a) = (dip.to_radians(), dip_direction.to_radians());
    [d.sin() * a.sin(), d.sin() * a.cos(), d.cos()]
}

/// The unit normal of a 2D trace at `angle` degrees from +x.
pub fn normal_2d(angle: f64) -> [f64; 3] {
    let a = angle.to_radians();
    [-a.sin(), a.cos(), 0.0]
}

/// Dip and dip direction (degrees) of the plane with normal `n` (either sign).
pub fn dip_of(n: [f64; 3]) -> (f64, f64) {
    let n = if n[2] < 0.0 { [-n[0], -n[1], -n[2]] } else { n };
    let dip = n[2].clamp(-1.0, 1.0).acos().to_degrees();
    let dd = n[0].atan2(n[1]).to_degrees().rem_euclid(360.0);
    (dip, if dip < 1e-9 { 0.0 } else { dd })
}

/// The corners of a box: 8, or 4 in the plane z = zmin when `dim` is 2.
pub fn corners(b: &Bbox, dim: usize) -> Vec<[f64; 3]> {
    let zs: &[f64] = if dim == 2 { &[b[2]] } else { &[b[2], b[5]] };
    let mut out = Vec::new();
    for &z in zs {
        for y in [b[1], b[4]] {
            for x in [b[0], b[3]] {
                out.push([x, y, z]);
            }
        }
    }
    out
}

/// The range of n . x over the box.
pub fn range_over(n: [f64; 3], b: &Bbox, dim: usize) -> (f64, f64) {
    corners(b, dim)
        .iter()
        .map(|&c| dot(n, c))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| (lo.min(v), hi.max(v)))
}

/// The planes n . x = offset + k spacing strictly inside (lo, hi): (k, offset + k spacing),
/// leaving out those within `tol` of either end (they would only touch the box).
pub fn offsets(offset: f64, spacing: f64, (lo, hi): (f64, f64), tol: f64) -> Vec<(i64, f64)> {
    let k0 = ((lo + tol - offset) / spacing).ceil();
    let k1 = ((hi - tol - offset) / spacing).floor();
    if !(k0.is_finite() && k1.is_finite()) || k1 < k0 {
        return Vec::new();
    }
    (k0 as i64..=k1 as i64)
        .map(|k| (k, offset + k as f64 * spacing))
        .filter(|&(_, d)| d > lo + tol && d < hi - tol)
        .collect()
}

/// An orthonormal basis (s, u) of the plane with unit normal n, with
/// (s, u, n) right-handed: s along the strike (horizontal), u = n x s down
/// the dip; for a horizontal plane s = +x, u = +y. In 2D (n in the xy
/// plane) s is the trace's direction.
pub fn in_plane(n: [f64; 3]) -> ([f64; 3], [f64; 3]) {
    let h = (n[0] * n[0] + n[1] * n[1]).sqrt();
    let s = if h < 1e-12 { [1.0, 0.0, 0.0] } else { unit([n[1], -n[0], 0.0]) };
    (s, cross(n, s))
}

/// The point of the plane n . x = d nearest to `p`.
pub fn project(n: [f64; 3], d: f64, p: [f64; 3]) -> [f64; 3] {
    axpy(p, d - dot(n, p), n)
}

/// The centre and half diagonal of a box (2D: in its z = zmin plane).
fn centre_radius(b: &Bbox, dim: usize) -> ([f64; 3], f64) {
    let z = if dim == 2 { (b[2], b[2]) } else { (b[2], b[5]) };
    let c = [(b[0] + b[3]) / 2.0, (b[1] + b[4]) / 2.0, (z.0 + z.1) / 2.0];
    let r = ((b[3] - b[0]).powi(2) + (b[4] - b[1]).powi(2) + (z.1 - z.0).powi(2)).sqrt() / 2.0;
    (c, r)
}

/// The shape of one finite joint.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Shape {
    /// A square of side `size` (2D: a trace of length `size`).
    Square,
    /// A disc of diameter `size` (2D: a trace of length `size`).
    Disc,
}

/// A patch of a plane the cutter makes: a polygon, a disc or (2D) a segment.
#[derive(Clone, Debug, PartialEq)]
pub enum Patch {
    Polygon(Vec<[f64; 3]>),
    Disc { centre: [f64; 3], radius: f64, normal: [f64; 3] },
    Segment([f64; 3], [f64; 3]),
}

/// A square (2D: a segment) of half side `half` centred at `c` in the plane of n.
pub fn square(c: [f64; 3], n: [f64; 3], half: f64, dim: usize) -> Patch {
    let (s, u) = in_plane(n);
    if dim == 2 {
        return Patch::Segment(axpy(c, -half, s), axpy(c, half, s));
    }
    let corner = |a: f64, b: f64| axpy(axpy(c, a * half, s), b * half, u);
    Patch::Polygon(vec![corner(-1.0, -1.0), corner(1.0, -1.0), corner(1.0, 1.0), corner(-1.0, 1.0)])
}

/// The patch of plane n . x = d that covers the box: a square (2D: a
/// segment) centred where the plane is nearest the box's centre, wider than
/// the box's diagonal.
pub fn covering(n: [f64; 3], d: f64, b: &Bbox, dim: usize) -> Patch {
    let (c, r) = centre_radius(b, dim);
    square(project(n, d, c), n, 1.1 * r + 1e-9, dim)
}

/// One finite joint of `size` centred at `c` in the plane of n.
pub fn one(c: [f64; 3], n: [f64; 3], size: f64, shape: Shape, dim: usize) -> Patch {
    match shape {
        Shape::Disc if dim == 3 => Patch::Disc { centre: c, radius: size / 2.0, normal: n },
        _ => square(c, n, size / 2.0, dim),
    }
}

/// How finite joints tile a plane: joints of `size` with `gap` between
/// them, one centred where the plane is nearest `centre`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tiling {
    pub size: f64,
    pub gap: f64,
    pub shape: Shape,
    pub centre: [f64; 3],
}

/// Finite joints on plane n . x = d: a square grid of pitch size + gap
/// (2D: a row) in the plane's (s, u) axes, as far as the box reaches.
pub fn finite(n: [f64; 3], d: f64, t: &Tiling, b: &Bbox, dim: usize) -> Vec<Patch> {
    let Tiling { size, gap, shape, centre } = *t;
    let (s, u) = in_plane(n);
    let (bc, r) = centre_radius(b, dim);
    let o = project(n, d, centre);
    let pitch = size + gap;
    // the box's reach along s and u, measured from o
    let (ps, pu) = (dot(axpy(bc, -1.0, o), s), dot(axpy(bc, -1.0, o), u));
    let span = |mid: f64| (((mid - r - size) / pitch).ceil() as i64, ((mid + r + size) / pitch).floor() as i64);
    let (is, iu) = (span(ps), if dim == 2 { (0, 0) } else { span(pu) });
    let mut out = Vec::new();
    for i in is.0..=is.1 {
        for j in iu.0..=iu.1 {
            let c = axpy(axpy(o, i as f64 * pitch, s), j as f64 * pitch, u);
            // joints that cannot reach the box are left out
            let far = dot(axpy(c, -1.0, bc), axpy(c, -1.0, bc)).sqrt();
            if far > r + size {
                continue;
            }
            out.push(one(c, n, size, shape, dim));
        }
    }
    out
}

/// The corner of `points` nearest the plane n . x = d and its distance.
pub fn nearest(n: [f64; 3], d: f64, points: &[[f64; 3]]) -> Option<([f64; 3], f64)> {
    points.iter().map(|&p| (p, (dot(n, p) - d).abs())).min_by(|a, b| a.1.total_cmp(&b.1))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: [f64; 3], b: [f64; 3], tol: f64) -> bool {
        (0..3).all(|i| (a[i] - b[i]).abs() < tol)
    }

    /// DESIGN.md §4: n = (sin dip sin dd, sin dip cos dd, cos dip); a plane
    /// dipping 30 degrees to the east (dd 90) rises towards the west, its
    /// upward normal leans east; dip_of inverts it.
    #[test]
    fn normals_follow_dip_and_dip_direction() {
        let n = normal_3d(30.0, 90.0);
        assert!(close(n, [0.5, 0.0, 3f64.sqrt() / 2.0], 1e-15));
        assert!(close(normal_3d(90.0, 0.0), [0.0, 1.0, 0.0], 1e-15));
        assert!(close(normal_3d(0.0, 123.0), [0.0, 0.0, 1.0], 1e-15));
        for (dip, dd) in [(60.0, 30.0), (70.0, 150.0), (10.0, 270.0), (45.0, 359.0)] {
            let (a, b) = dip_of(normal_3d(dip, dd));
            assert!((a - dip).abs() < 1e-12 && (b - dd).abs() < 1e-9, "{dip}/{dd} -> {a}/{b}");
            let n = normal_3d(dip, dd);
            let (a, b) = dip_of([-n[0], -n[1], -n[2]]);
            assert!((a - dip).abs() < 1e-12 && (b - dd).abs() < 1e-9);
        }
        assert!(close(normal_2d(0.0), [0.0, 1.0, 0.0], 1e-15));
        assert!(close(normal_2d(90.0), [-1.0, 0.0, 0.0], 1e-15));
    }

    /// A 10 m cube cut every 2.5 m along x, offset 0: three planes inside,
    /// none on the faces; an offset that puts a plane 1e-9 from a face
    /// leaves it out.
    #[test]
    fn offsets_inside_the_box() {
        let b = [0.0, 0.0, 0.0, 10.0, 10.0, 10.0];
        let r = range_over([1.0, 0.0, 0.0], &b, 3);
        assert_eq!(r, (0.0, 10.0));
        let o = offsets(0.0, 2.5, r, 1e-9);
        assert_eq!(o, vec![(1, 2.5), (2, 5.0), (3, 7.5)]);
        assert_eq!(offsets(1.0, 2.5, r, 1e-9), vec![(0, 1.0), (1, 3.5), (2, 6.0), (3, 8.5)]);
        assert!(offsets(20.0, 100.0, r, 1e-9).is_empty());
        // an oblique set: n . x over the cube spans 0 .. 10 (sin + cos) at 45 degrees
        let n = normal_3d(90.0, 45.0);
        let (lo, hi) = range_over(n, &b, 3);
        assert!((lo - 0.0).abs() < 1e-12 && (hi - 10.0 * 2f64.sqrt()).abs() < 1e-12);
    }

    /// The strike is horizontal and (s, u, n) is right-handed and orthonormal.
    #[test]
    fn in_plane_basis() {
        for (dip, dd) in [(60.0, 30.0), (0.0, 0.0), (90.0, 270.0), (10.0, 270.0)] {
            let n = normal_3d(dip, dd);
            let (s, u) = in_plane(n);
            assert!(s[2].abs() < 1e-15);
            assert!(dot(s, n).abs() < 1e-15 && dot(u, n).abs() < 1e-15 && dot(s, u).abs() < 1e-15);
            assert!(close(cross(s, u), n, 1e-15));
        }
    }

    /// A covering square holds the whole section of the box; finite joints
    /// repeat at size + gap, one centred on the projection of the centre.
    #[test]
    fn patches_cover_and_repeat() {
        let b = [0.0, 0.0, 0.0, 10.0, 10.0, 10.0];
        let n = normal_3d(60.0, 30.0);
        let d = dot(n, [5.0, 5.0, 5.0]);
        let Patch::Polygon(c) = covering(n, d, &b, 3) else { panic!("a square") };
        for p in &c {
            assert!((dot(n, *p) - d).abs() < 1e-12);
            // every corner lies beyond the box's circumscribed sphere
            assert!(dot(axpy(*p, -1.0, [5.0; 3]), axpy(*p, -1.0, [5.0; 3])).sqrt() > 75f64.sqrt());
        }
        let tiling = Tiling { size: 2.0, gap: 1.0, shape: Shape::Square, centre: [5.0, 5.0, 5.0] };
        let joints = finite([0.0, 0.0, 1.0], 5.0, &tiling, &b, 3);
        let centres: Vec<[f64; 3]> = joints
            .iter()
            .map(|p| match p {
                Patch::Polygon(c) => [(c[0][0] + c[2][0]) / 2.0, (c[0][1] + c[2][1]) / 2.0, c[0][2]],
                _ => panic!("squares"),
            })
            .collect();
        assert!(centres.iter().any(|c| close(*c, [5.0, 5.0, 5.0], 1e-12)));
        assert!(centres.iter().any(|c| close(*c, [8.0, 5.0, 5.0], 1e-12)));
        assert!(centres.iter().any(|c| close(*c, [2.0, 2.0, 5.0], 1e-12)));
        assert!(!centres.iter().any(|c| close(*c, [6.5, 5.0, 5.0], 1e-9)));
        let tiling = Tiling { size: 4.0, gap: 2.0, shape: Shape::Square, centre: [0.0; 3] };
        let traces = finite(normal_2d(0.0), 0.0, &tiling, &[-10.0, -10.0, 0.0, 10.0, 10.0, 0.0], 2);
        assert!(traces.contains(&Patch::Segment([-2.0, 0.0, 0.0], [2.0, 0.0, 0.0])));
        assert!(traces.contains(&Patch::Segment([4.0, 0.0, 0.0], [8.0, 0.0, 0.0])));
    }
}
