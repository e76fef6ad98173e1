//! The deformed picture cut to a box ([`super::framing`]): surface pieces
//! clipped to the box (Sutherland–Hodgman, plane by plane, the field and
//! the displacement interpolated linearly along the clipped edges), and in
//! 3D the sections of the bodies by the box's faces, so that the cut shows
//! the inside of the solid instead of elements sticking out of it. A
//! section is taken cell by cell: each cell split into tetrahedra over its
//! corners, each tetrahedron cut by the plane into a triangle or a
//! quadrilateral.

use super::surface::Patch;
use crate::mesh::{Cell, CellKind};
use crate::model::Model;

/// A point of a clipped piece: where it is undeformed, its displacement
/// and the field there.
#[derive(Clone, Copy, Debug)]
pub(super) struct Vertex {
    pub(super) x: [f64; 3],
    pub(super) u: [f64; 3],
    pub(super) v: f32,
}

fn lerp(a: &Vertex, b: &Vertex, t: f64) -> Vertex {
    Vertex {
        x: std::array::from_fn(|d| a.x[d] + t * (b.x[d] - a.x[d])),
        u: std::array::from_fn(|d| a.u[d] + t * (b.u[d] - a.u[d])),
        v: (a.v as f64 + t * (b.v as f64 - a.v as f64)) as f32,
    }
}

/// The box a picture is cut to, in the model's `dim` directions.
#[derive(Clone, Copy, Debug)]
pub(super) struct Cut {
    pub(super) lo: [f64; 3],
    pub(super) hi: [f64; 3],
    pub(super) dim: usize,
}

impl Cut {
    pub(super) fn contains(&self, x: [f64; 3]) -> bool {
        (0..self.dim).all(|d| x[d] >= self.lo[d] && x[d] <= self.hi[d])
    }

    /// A convex polygon clipped to the box (empty when nothing is left).
    pub(super) fn clip(&self, mut poly: Vec<Vertex>) -> Vec<Vertex> {
        for d in 0..self.dim {
            for (side, at) in [(1.0, self.lo[d]), (-1.0, self.hi[d])] {
                if poly.is_empty() {
                    return poly;
                }
                // keep side * (x_d - at) >= 0
                let inside = |p: &Vertex| side * (p.x[d] - at) >= 0.0;
                let mut out = Vec::with_capacity(poly.len() + 2);
                for i in 0..poly.len() {
                    let (a, b) = (&poly[i], &poly[(i + 1) % poly.len()]);
                    if inside(a) {
                        out.push(*a);
                    }
                    if inside(a) != inside(b) {
                        let t = (at - a.x[d]) / (b.x[d] - a.x[d]);
                        out.push(lerp(a, b, t));
                    }
                }
                poly = out;
            }
        }
        if poly.len() < 3 {
            poly.clear();
        }
        poly
    }

    /// Whether all of a patch's corners lie in the box, some of them, or
    /// none on one side of one of its planes (then it is left out).
    pub(super) fn classify(&self, p: &Patch, coords: &[[f64; 3]]) -> Place {
        let nodes = p.nodes();
        if nodes.iter().all(|&k| self.contains(coords[k])) {
            return Place::Inside;
        }
        for d in 0..self.dim {
            if nodes.iter().all(|&k| coords[k][d] < self.lo[d]) || nodes.iter().all(|&k| coords[k][d] > self.hi[d]) {
                return Place::Outside;
            }
        }
        Place::Across
    }

    /// The sections of every body's cells by the box's faces that cut the
    /// model (3D only), each piece clipped to the box: (body, polygon, unit
    /// normal of the face). `value(body, node)` is the field.
    pub(super) fn sections(
        &self,
        model: &Model,
        u: &dyn Fn(usize) -> [f64; 3],
        value: &dyn Fn(usize, usize) -> f32,
    ) -> Vec<(usize, Vec<Vertex>, [f64; 3])> {
        let mut out = Vec::new();
        if self.dim != 3 {
            return out;
        }
        let (mlo, mhi) = super::view::model_box(model);
        for d in 0..3 {
            for at in [self.lo[d], self.hi[d]] {
                if at <= mlo[d] || at >= mhi[d] {
                    continue;
                }
                let mut normal = [0.0; 3];
                normal[d] = 1.0;
                for (b, body) in model.bodies.iter().enumerate() {
                    for cell in &body.cells {
                        let (mut below, mut above) = (false, false);
                        for &k in &cell.nodes {
                            below |= model.coords[k][d] < at;
                            above |= model.coords[k][d] > at;
                        }
                        if !(below && above) {
                            continue;
                        }
                        for tet in tets(cell) {
                            let vert = |k: usize| Vertex { x: model.coords[k], u: u(k), v: value(b, k) };
                            let poly = slice(tet.map(vert), d, at);
                            let poly = self.clip(poly);
                            if !poly.is_empty() {
                                out.push((b, poly, normal));
                            }
                        }
                    }
                }
            }
        }
        out
    }
}

/// Where a patch lies against the box.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Place {
    Inside,
    Across,
    Outside,
}

/// A cell's corners split into tetrahedra (none for kinds without a
/// split, e.g. 2D cells).
fn tets(cell: &Cell) -> Vec<[usize; 4]> {
    let c = &cell.nodes;
    match cell.kind {
        CellKind::Tet4 | CellKind::Tet10 => vec![[c[0], c[1], c[2], c[3]]],
        CellKind::Hex8 | CellKind::Hex20 | CellKind::Hex27 => {
            // six about the diagonal 0-6
            [[0, 1, 2, 6], [0, 2, 3, 6], [0, 3, 7, 6], [0, 7, 4, 6], [0, 4, 5, 6], [0, 5, 1, 6]]
                .iter()
                .map(|t| t.map(|i| c[i]))
                .collect()
        }
        _ => Vec::new(),
    }
}

/// The section of a tetrahedron by the plane `x_d = at`: a triangle, a
/// quadrilateral (in order round it) or nothing.
fn slice(t: [Vertex; 4], d: usize, at: f64) -> Vec<Vertex> {
    let s: Vec<f64> = t.iter().map(|p| p.x[d] - at).collect();
    let mut pts = Vec::with_capacity(4);
    for (i, j) in [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)] {
        if (s[i] < 0.0) != (s[j] < 0.0) {
            pts.push(lerp(&t[i], &t[j], s[i] / (s[i] - s[j])));
        }
    }
    if pts.len() == 4 {
        // order the quadrilateral round its centre, in the plane
        let (a, b) = ((d + 1) % 3, (d + 2) % 3);
        let c: [f64; 2] =
            [pts.iter().map(|p| p.x[a]).sum::<f64>() / 4.0, pts.iter().map(|p| p.x[b]).sum::<f64>() / 4.0];
        pts.sort_by(|p, q| (p.x[b] - c[1]).atan2(p.x[a] - c[0]).total_cmp(&(q.x[b] - c[1]).atan2(q.x[a] - c[0])));
    }
    if pts.len() < 3 {
        pts.clear();
    }
    pts
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(x: [f64; 3]) -> Vertex {
        Vertex { x, u: [0.0; 3], v: (x[0] + 2.0 * x[1]) as f32 }
    }

    #[test]
    fn a_square_clipped_to_a_box_keeps_the_linear_field() {
        let cut = Cut { lo: [0.25, -1.0, -1.0], hi: [0.75, 0.5, 1.0], dim: 2 };
        let sq = vec![v([0.0, 0.0, 0.0]), v([1.0, 0.0, 0.0]), v([1.0, 1.0, 0.0]), v([0.0, 1.0, 0.0])];
        let p = cut.clip(sq);
        assert_eq!(p.len(), 4);
        let area =
            0.5 * (0..4).map(|i| p[i].x[0] * p[(i + 1) % 4].x[1] - p[(i + 1) % 4].x[0] * p[i].x[1]).sum::<f64>().abs();
        assert!((area - 0.25).abs() < 1e-12, "{area}");
        assert!(p.iter().all(|q| (q.v as f64 - (q.x[0] + 2.0 * q.x[1])).abs() < 1e-6));
        assert!(cut.clip(vec![v([2.0, 0.0, 0.0]), v([3.0, 0.0, 0.0]), v([3.0, 1.0, 0.0])]).is_empty());
    }

    #[test]
    fn a_tetrahedron_cut_in_the_middle_gives_a_quadrilateral_in_order() {
        let t = [v([0.0, 0.0, 0.0]), v([1.0, 0.0, 0.0]), v([0.0, 1.0, 0.0]), v([1.0, 1.0, 1.0])];
        // x = 0.5 separates {0, 2} from {1, 3}
        let p = slice(t, 0, 0.5);
        assert_eq!(p.len(), 4);
        assert!(p.iter().all(|q| (q.x[0] - 0.5).abs() < 1e-12));
        // in order round it: no two successive edges cross (a convex polygon's signed area is its full area)
        let area = 0.5 * (0..4).map(|i| p[i].x[1] * p[(i + 1) % 4].x[2] - p[(i + 1) % 4].x[1] * p[i].x[2]).sum::<f64>();
        let hull = 0.5
            * ((p[2].x[1] - p[0].x[1]) * (p[3].x[2] - p[1].x[2]) - (p[3].x[1] - p[1].x[1]) * (p[2].x[2] - p[0].x[2]))
                .abs();
        assert!((area.abs() - hull).abs() < 1e-12, "{area} vs {hull}");
        assert_eq!(slice(t, 0, 2.0).len(), 0);
    }
}
