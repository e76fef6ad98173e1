//! Section forces: the resultant force and moment that the material on
//! one side of a cut passes to the other, from the cells' internal nodal
//! forces `r_e = ∫ B̄ᵀ σ dV` (stresses at the stiffness's quadrature
//! points, [`super::forces::cell_internal`]), never from averaged nodal
//! stresses. Here: the sections a scene asks for and their cuts (a line or
//! plane, or a beam or ring body cut at stations); `sections/cut.rs`: the
//! forces at one cut, which balance the loads on one side to round-off
//! where the cut follows the cells' edges, and are interpolated between
//! the two such cuts around it where it passes through cells.
//!
//! In the cut's axes (the beam convention when n runs along a beam and e2
//! up through it): N = F·n (tension positive), V = -F·e2, V3 = -F·e3,
//! T = M·n, M = M·e3 (positive when the fibre at -e2 is in tension:
//! sagging), M2 = M·e2. A ring's cut at angle θ has n along the hoop
//! (θ growing), e2 inward, e3 along the axis: N = -thrust, M > 0 in
//! tension outside. c, where moments are taken, is the middle of the cut's
//! extent across the member (along e2, and e3 in 3D; a ring: the middle
//! radius on the cut's ray).

mod cut;
mod station;

pub use station::{SectionForces, Sides, Station};

use crate::fem::vec3::{cross, dot, normalized, sub};
use crate::model::Model;
use cut::{station, Plane};

/// Where a `[[sections]]` entry cuts.
#[derive(Clone, Debug, PartialEq)]
pub enum Cut {
    /// 2D: the line from `from` to `to` across a member; the bodies it cuts
    /// (group names; empty: every body).
    Line { from: [f64; 3], to: [f64; 3], bodies: Vec<String> },
    /// 3D: the plane through `point` normal to `normal`.
    Plane { point: [f64; 3], normal: [f64; 3], bodies: Vec<String> },
    /// A body cut across its axis at `stations` equally spaced cuts from
    /// end to end (`axis` None: its longest extent along x, y or z).
    Beam { body: String, stations: usize, axis: Option<[f64; 3]> },
    /// A ring body cut on rays from `centre` at `stations` angles over the
    /// arc it covers (every 360/stations degrees round a whole ring),
    /// about `axis` (z in 2D).
    Ring { body: String, stations: usize, centre: [f64; 3], axis: [f64; 3] },
}

/// A `[[sections]]` entry.
#[derive(Clone, Debug, PartialEq)]
pub struct SectionSpec {
    pub name: String,
    pub cut: Cut,
}

/// The forces of every section of the model at displacements `u`.
pub fn section_forces(model: &Model, u: &[f64], specs: &[SectionSpec]) -> Vec<SectionForces> {
    specs.iter().map(|s| section(model, u, s)).collect()
}

fn section(model: &Model, u: &[f64], spec: &SectionSpec) -> SectionForces {
    let (bodies, kind) = match &spec.cut {
        Cut::Line { bodies, .. } => (bodies.clone(), "line"),
        Cut::Plane { bodies, .. } => (bodies.clone(), "plane"),
        Cut::Beam { body, .. } => (vec![body.clone()], "beam"),
        Cut::Ring { body, .. } => (vec![body.clone()], "ring"),
    };
    let cells: Vec<(usize, usize)> = (model.bodies.iter().enumerate())
        .filter(|(_, b)| bodies.is_empty() || bodies.contains(&b.name))
        .flat_map(|(b, body)| (0..body.cells.len()).map(move |c| (b, c)))
        .collect();
    let planes = planes(model, &spec.cut, &cells);
    let n = planes.len();
    let stations: Vec<Station> = planes.iter().filter_map(|p| station(model, u, &cells, p)).collect();
    SectionForces { name: spec.name.clone(), kind, missed: n - stations.len(), stations }
}

/// The unit vector of the global axis `c`.
fn axis(c: usize) -> [f64; 3] {
    std::array::from_fn(|i| if i == c { 1.0 } else { 0.0 })
}

/// `v` without its component along unit `a`, normalised (None when nothing is left).
fn across(v: [f64; 3], a: [f64; 3]) -> Option<[f64; 3]> {
    let w: [f64; 3] = std::array::from_fn(|i| v[i] - dot(v, a) * a[i]);
    (dot(w, w) > 0.25).then(|| normalized(w))
}

/// The "up" direction across unit `n`: z in 3D (x when n is vertical);
/// in 2D e2 = n turned +90 degrees about z.
fn up(n: [f64; 3], plane: bool) -> [f64; 3] {
    if plane {
        return [-n[1], n[0], 0.0];
    }
    across(axis(2), n).or_else(|| across(axis(0), n)).unwrap_or(axis(1))
}

fn frame(n: [f64; 3], e2: [f64; 3]) -> [[f64; 3]; 3] {
    [n, e2, cross(n, e2)]
}

/// The cuts of a section.
fn planes(model: &Model, cut: &Cut, cells: &[(usize, usize)]) -> Vec<Plane> {
    let plane = model.analysis.dim() == 2;
    let nodes = || cells.iter().flat_map(|&(b, c)| model.bodies[b].cells[c].nodes.iter().map(|&n| model.coords[n]));
    match cut {
        Cut::Line { from, to, .. } => {
            let len = dot(sub(*to, *from), sub(*to, *from)).sqrt();
            let d = normalized(sub(*to, *from));
            let n = [d[1], -d[0], 0.0];
            vec![Plane { o: *from, frame: frame(n, d), window: Some((d, 0.0, len)), ring: false, position: 0.0 }]
        }
        Cut::Plane { point, normal, .. } => {
            let n = normalized(*normal);
            vec![Plane { o: *point, frame: frame(n, up(n, false)), window: None, ring: false, position: 0.0 }]
        }
        Cut::Beam { stations, axis: a, .. } => {
            let a = a.map(normalized).unwrap_or_else(|| longest(nodes(), model.analysis.dim()));
            let e2 = up(a, plane);
            let o = nodes().next().unwrap_or([0.0; 3]);
            let (lo, hi) = nodes().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
                let s = dot(sub(x, o), a);
                (lo.min(s), hi.max(s))
            });
            spaced(lo, hi, *stations, true)
                .map(|s| {
                    let at = std::array::from_fn(|i| o[i] + s * a[i]);
                    Plane { o: at, frame: frame(a, e2), window: None, ring: false, position: s - lo }
                })
                .collect()
        }
        Cut::Ring { stations, centre, axis: ax, .. } => {
            let (e_ref, e_up) = ring_axes(normalized(*ax));
            let turn = cross(e_ref, e_up);
            let angles: Vec<f64> = nodes()
                .map(|x| {
                    let r = sub(x, *centre);
                    dot(r, e_up).atan2(dot(r, e_ref))
                })
                .collect();
            arc(angles, *stations)
                .into_iter()
                .map(|th| {
                    let e_r: [f64; 3] = std::array::from_fn(|i| th.cos() * e_ref[i] + th.sin() * e_up[i]);
                    let n = cross(turn, e_r);
                    let e2 = e_r.map(|v| -v);
                    let window = Some((e2, f64::NEG_INFINITY, 0.0));
                    Plane { o: *centre, frame: frame(n, e2), window, ring: true, position: th.to_degrees() }
                })
                .collect()
        }
    }
}

/// The reference direction (angle 0) and the direction at +90 degrees of a
/// ring about unit axis `a`: horizontal (x, else y) and up (z, else a × x).
fn ring_axes(a: [f64; 3]) -> ([f64; 3], [f64; 3]) {
    let e_ref = across(axis(0), a).or_else(|| across(axis(1), a)).unwrap_or(axis(2));
    let e_up = across(axis(2), a).filter(|v| dot(*v, e_ref).abs() < 0.5).unwrap_or_else(|| cross(a, e_ref));
    // e_up square to e_ref
    let e_up = normalized(std::array::from_fn(|i| e_up[i] - dot(e_up, e_ref) * e_ref[i]));
    (e_ref, e_up)
}

/// The global axis (x, y or z, among the first `dim`) of the largest extent.
fn longest(xs: impl Iterator<Item = [f64; 3]>, dim: usize) -> [f64; 3] {
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for x in xs {
        for i in 0..3 {
            lo[i] = lo[i].min(x[i]);
            hi[i] = hi[i].max(x[i]);
        }
    }
    let c = (0..dim).max_by(|&a, &b| (hi[a] - lo[a]).total_cmp(&(hi[b] - lo[b]))).unwrap_or(0);
    axis(c)
}

/// `n` values from lo to hi, both ends included (or, `ends` false, not
/// repeating the start at the end of a whole turn).
fn spaced(lo: f64, hi: f64, n: usize, ends: bool) -> impl Iterator<Item = f64> {
    let div = if ends { (n.max(2) - 1) as f64 } else { n.max(1) as f64 };
    (0..n).map(move |k| lo + (hi - lo) * k as f64 / div)
}

/// The angles of a ring's cuts: every 360/n degrees from 0 when the nodes
/// go all round (no gap over 45 degrees), else n from one end of the arc
/// they cover to the other.
fn arc(mut angles: Vec<f64>, n: usize) -> Vec<f64> {
    use std::f64::consts::PI;
    if angles.is_empty() {
        return Vec::new();
    }
    angles.sort_by(f64::total_cmp);
    let mut gap = (angles[0] + 2.0 * PI - angles[angles.len() - 1], angles[0]);
    for w in angles.windows(2) {
        if w[1] - w[0] > gap.0 {
            gap = (w[1] - w[0], w[1]);
        }
    }
    if gap.0 < 45f64.to_radians() {
        return spaced(0.0, 2.0 * PI, n, false).collect();
    }
    // the arc starts where the gap ends, and runs 2 pi - gap
    let start = gap.1;
    let span = 2.0 * PI - gap.0;
    // the start written in (-pi, pi], the arc as it reads (0..90, not 360..450)
    let start = if start > PI { start - 2.0 * PI } else { start };
    spaced(start, start + span, n, true).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A whole ring is cut every 360/n degrees from 0; a quarter from its
    /// one end to the other, ends included, whichever way atan2 wraps.
    #[test]
    fn ring_stations_cover_the_arc() {
        let deg = |v: Vec<f64>| v.iter().map(|a| (a.to_degrees() * 1e6).round() / 1e6).collect::<Vec<_>>();
        let all: Vec<f64> = (0..72).map(|k| (k as f64 * 5.0 - 180.0).to_radians()).collect();
        assert_eq!(deg(arc(all, 4)), vec![0.0, 90.0, 180.0, 270.0]);
        let quarter: Vec<f64> = (0..=18).map(|k| (k as f64 * 5.0).to_radians()).collect();
        assert_eq!(deg(arc(quarter, 4)), vec![0.0, 30.0, 60.0, 90.0]);
        // an arc across the wrap of atan2: 150 .. 210 degrees
        let back: Vec<f64> =
            (0..=12).map(|k| (150.0 + k as f64 * 5.0 - 360.0 * f64::from(k > 6)).to_radians()).collect();
        assert_eq!(deg(arc(back, 3)), vec![150.0, 180.0, 210.0]);
    }

    /// The axes of a ring: x then up (z), turning from x towards the crown;
    /// about z (a plane model) from x to y.
    #[test]
    fn ring_axes_turn_from_the_springline_to_the_crown() {
        assert_eq!(ring_axes([0.0, 0.0, 1.0]), ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0]));
        assert_eq!(ring_axes([0.0, 1.0, 0.0]), ([1.0, 0.0, 0.0], [0.0, 0.0, 1.0]));
        let (r, u) = ring_axes([1.0, 0.0, 0.0]);
        assert_eq!((r, u), ([0.0, 1.0, 0.0], [0.0, 0.0, 1.0]));
    }
}
