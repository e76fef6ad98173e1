//! The bearing pressure of a contact face (a contact group, or the part of
//! one between two blocks: a footing pad on the ground), as a foundation
//! engineer reads it: the compressive normal force and where it acts, its
//! eccentricity about the face's centroid, the length (2D) or area in
//! contact, the largest and mean pressure, and a design pressure averaged
//! over a stated width, which a singular corner does not set.
//!
//! Over the face's pairs i, with p_i = max(-sigma_n, 0) the pressure and
//! A_i the area a pair controls (times the thickness in 2D):
//!
//! ```text
//! P     = Σ p_i A_i                    the normal force, compression positive
//! x_P   = Σ p_i A_i x_i / P            where it acts (the pressure's centroid)
//! c     = Σ A_i x_i / Σ A_i            the face's centroid
//! e     = x_P - c                      the eccentricity (2D: along the face's tangent t)
//! p_d   = max over windows W of width d: Σ_W p_i A_i / Σ_W A_i
//! ```
//!
//! In 2D the face runs along t = n turned +90 degrees from its first pair
//! to its last (width B; the middle third: |e| <= B/6), and W is a stretch
//! [s, s + d] that starts at a pair; in 3D t1 is x (else y) across n, t2 =
//! n × t1, B1 and B2 the face's extents along them (the kern of a
//! rectangle: |e1|/B1 + |e2|/B2 <= 1/6), and W a disc of diameter d
//! about a pair. Plain data in, plain data out.

use std::collections::HashMap;

use crate::fem::vec3::{cross, dot, normalized, sub};

/// One pair of a face.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BearingPair {
    pub x: [f64; 3],
    /// Its unit normal (outward of side I).
    pub normal: [f64; 3],
    pub area: f64,
    pub sigma_n: f64,
    /// Whether it is open (no contact).
    pub open: bool,
}

/// The bearing pressure of one face.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Bearing {
    pub pairs: usize,
    /// The mean unit normal, and the face's axes across it (t1, t2 = n × t1;
    /// in 2D t1 = n turned +90 degrees).
    pub normal: [f64; 3],
    pub axes: [[f64; 3]; 2],
    /// The face's area, and the area in contact (not open); in 2D divide by
    /// the thickness for lengths.
    pub area: f64,
    pub contact_area: f64,
    /// The face's centroid and its extents along t1 and t2 (from the first
    /// pair to the last), the ends along t1 (2D: the face's two ends).
    pub centroid: [f64; 3],
    pub widths: [f64; 2],
    pub ends: [[f64; 3]; 2],
    /// The compressive normal force, where it acts (the centroid when
    /// nothing presses), its eccentricity along t1 and t2.
    pub force: f64,
    pub at: [f64; 3],
    pub eccentricity: [f64; 2],
    /// The largest pressure and where; the mean over the area in contact.
    pub max_pressure: f64,
    pub max_at: [f64; 3],
    pub mean_pressure: f64,
    /// The largest pressure averaged over a window of width `window`, and
    /// where that window starts (2D) or is centred (3D).
    pub design_pressure: f64,
    pub window: f64,
    pub design_at: [f64; 3],
}

impl Bearing {
    /// The resultant's distance from the face's two ends along t1.
    pub fn from_ends(&self) -> [f64; 2] {
        let t = self.axes[0];
        [dot(sub(self.at, self.ends[0]), t), dot(sub(self.ends[1], self.at), t)]
    }

    /// Whether the resultant lies in the kern: the middle third in 2D,
    /// |e1|/B1 + |e2|/B2 <= 1/6 in 3D (a rectangle's).
    pub fn in_kern(&self, plane: bool) -> bool {
        let r = |k: usize| if self.widths[k] > 0.0 { (self.eccentricity[k] / self.widths[k]).abs() } else { 0.0 };
        if plane {
            r(0) <= 1.0 / 6.0 + 1e-12
        } else {
            r(0) + r(1) <= 1.0 / 6.0 + 1e-12
        }
    }
}

/// The face's axes across the mean normal n: 2D, n turned +90 degrees
/// (and z); 3D, x (else y) across n, and n × it.
fn axes(n: [f64; 3], plane: bool) -> [[f64; 3]; 2] {
    if plane {
        return [[-n[1], n[0], 0.0], [0.0, 0.0, 1.0]];
    }
    let across = |a: [f64; 3]| -> [f64; 3] { std::array::from_fn(|i| a[i] - dot(a, n) * n[i]) };
    let x = across([1.0, 0.0, 0.0]);
    let t1 = if dot(x, x) > 0.25 { normalized(x) } else { normalized(across([0.0, 1.0, 0.0])) };
    [t1, cross(n, t1)]
}

/// The bearing pressure of the pairs of one face (None without pairs or
/// area); `window`: the design pressure's width (None: a tenth of the
/// face's width B in 2D, of sqrt(area) in 3D).
pub fn bearing(pairs: &[BearingPair], plane: bool, window: Option<f64>) -> Option<Bearing> {
    let area: f64 = pairs.iter().map(|p| p.area).sum();
    if pairs.is_empty() || area <= 0.0 {
        return None;
    }
    let o = pairs[0].x;
    let mut wn = [0.0; 3];
    let mut c = [0.0; 3];
    for p in pairs {
        let r = sub(p.x, o);
        (0..3).for_each(|i| {
            wn[i] += p.area * p.normal[i];
            c[i] += p.area * r[i] / area;
        });
    }
    let normal = normalized(wn);
    let centroid: [f64; 3] = std::array::from_fn(|i| o[i] + c[i]);
    let axes = axes(normal, plane);
    let along = |x: [f64; 3], k: usize| dot(sub(x, centroid), axes[k]);
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    let (mut first, mut last) = (centroid, centroid);
    for p in pairs {
        for k in 0..2 {
            let s = along(p.x, k);
            if k == 0 && s < lo[0] {
                first = p.x;
            }
            if k == 0 && s > hi[0] {
                last = p.x;
            }
            lo[k] = lo[k].min(s);
            hi[k] = hi[k].max(s);
        }
    }
    let pressure = |p: &BearingPair| (-p.sigma_n).max(0.0);
    let force: f64 = pairs.iter().map(|p| pressure(p) * p.area).sum();
    let mut at = centroid;
    if force > 0.0 {
        let mut r = [0.0; 3];
        for p in pairs {
            let d = sub(p.x, centroid);
            (0..3).for_each(|i| r[i] += pressure(p) * p.area * d[i] / force);
        }
        at = std::array::from_fn(|i| centroid[i] + r[i]);
    }
    let max = pairs.iter().max_by(|a, b| pressure(a).total_cmp(&pressure(b))).copied().unwrap_or(pairs[0]);
    let contact_area: f64 = pairs.iter().filter(|p| !p.open).map(|p| p.area).sum();
    let widths = [hi[0] - lo[0], if plane { 0.0 } else { hi[1] - lo[1] }];
    let d = window.unwrap_or(0.1 * if plane { widths[0] } else { area.sqrt() });
    let (design_pressure, design_at) = design(pairs, plane, d, (lo, hi), &along);
    Some(Bearing {
        pairs: pairs.len(),
        normal,
        axes,
        area,
        contact_area,
        centroid,
        widths,
        ends: [first, last],
        force,
        at,
        eccentricity: [along(at, 0), if plane { 0.0 } else { along(at, 1) }],
        max_pressure: pressure(&max),
        max_at: max.x,
        mean_pressure: if contact_area > 0.0 { force / contact_area } else { 0.0 },
        design_pressure,
        window: d,
        design_at,
    })
}

/// The largest pressure averaged over a window of width d inside the face
/// (`lo`, `hi`: its extents along t1, t2): stretches [s, s + d] starting
/// at a pair (2D), discs of diameter d about a pair at least d/2 inside
/// (3D); the whole face when it is narrower than d.
fn design(
    pairs: &[BearingPair],
    plane: bool,
    d: f64,
    (lo, hi): ([f64; 2], [f64; 2]),
    along: &dyn Fn([f64; 3], usize) -> f64,
) -> (f64, [f64; 3]) {
    let tol = 1e-9 * d.max(f64::MIN_POSITIVE);
    let fits = |s: f64, k: usize| {
        if plane {
            s + d <= hi[k] + tol || hi[k] - lo[k] < d
        } else if hi[k] - lo[k] < d {
            true
        } else {
            s >= lo[k] + 0.5 * d - tol && s <= hi[k] - 0.5 * d + tol
        }
    };
    let at: Vec<[f64; 2]> = pairs.iter().map(|p| [along(p.x, 0), along(p.x, 1)]).collect();
    let grid = Grid::new(&at, plane, d);
    let (mut near, mut marks) = (Vec::new(), vec![0u64; pairs.len().div_ceil(64)]);
    let mut best: Option<(f64, [f64; 3])> = None;
    for (p, &[s1, s2]) in pairs.iter().zip(&at) {
        if !fits(s1, 0) || (!plane && !fits(s2, 1)) {
            continue;
        }
        let inside = |[q1, q2]: [f64; 2]| {
            if plane {
                q1 >= s1 - tol && q1 <= s1 + d + tol
            } else {
                (q1 - s1).powi(2) + (q2 - s2).powi(2) <= (0.5 * d).powi(2) + tol * d
            }
        };
        // the cells the window reaches: [s1, s1 + d] in 2D, r = d/2 about
        // the pair in 3D (sqrt(r^2 + tol d) <= r + tol), with a margin
        let (r, m) = (0.5 * d, 2.0 * tol);
        let along_t1 = if plane { [s1 - m, s1 + d + m] } else { [s1 - r - m, s1 + r + m] };
        grid.near(along_t1, [s2 - r - m, s2 + r + m], |q| inside(at[q]), &mut marks, &mut near);
        let (mut f, mut a) = (0.0, 0.0);
        for &q in &near {
            f += (-pairs[q].sigma_n).max(0.0) * pairs[q].area;
            a += pairs[q].area;
        }
        if a > 0.0 && best.is_none_or(|b| f / a > b.0) {
            best = Some((f / a, p.x));
        }
    }
    best.unwrap_or((0.0, pairs[0].x))
}

/// The pairs of a face in square cells of the window's width on (t1, t2)
/// (on t1 alone in 2D), so that a window reads the pairs of the cells it
/// reaches, not the whole face: a joint set of the 1,000-block cube has
/// 18,900 pairs. One cell without a width.
struct Grid {
    cells: HashMap<(i64, i64), Vec<usize>>,
    h: f64,
    plane: bool,
}

impl Grid {
    fn new(at: &[[f64; 2]], plane: bool, d: f64) -> Grid {
        let h = if d > 0.0 && d.is_finite() { d } else { f64::INFINITY };
        let mut grid = Grid { cells: HashMap::new(), h, plane };
        for (i, &[s1, s2]) in at.iter().enumerate() {
            let key = (grid.cell(s1), if plane { 0 } else { grid.cell(s2) });
            grid.cells.entry(key).or_default().push(i);
        }
        grid
    }

    fn cell(&self, s: f64) -> i64 {
        (s / self.h).floor() as i64
    }

    /// The pairs of the cells that meet `[r1] x [r2]` that `keep` keeps, in
    /// the face's order (the window's sums then add them as the whole
    /// face's loop did): marked in `marks` (a bit per pair, all clear, and
    /// left clear), then read off in order, which a window of thousands of
    /// pairs does in a sweep of the words where sorting them took most of
    /// the output stage of the 1,000-block cube.
    fn near(&self, r1: [f64; 2], r2: [f64; 2], keep: impl Fn(usize) -> bool, marks: &mut [u64], out: &mut Vec<usize>) {
        out.clear();
        let (i0, i1) = (self.cell(r1[0]), self.cell(r1[1]));
        let (j0, j1) = if self.plane { (0, 0) } else { (self.cell(r2[0]), self.cell(r2[1])) };
        let (mut w0, mut w1) = (marks.len(), 0);
        for i in i0..=i1 {
            for j in j0..=j1 {
                for &q in self.cells.get(&(i, j)).into_iter().flatten().filter(|&&q| keep(q)) {
                    marks[q / 64] |= 1 << (q % 64);
                    (w0, w1) = (w0.min(q / 64), w1.max(q / 64 + 1));
                }
            }
        }
        for (w, word) in marks.iter_mut().enumerate().take(w1).skip(w0) {
            let mut bits = std::mem::take(word);
            while bits != 0 {
                out.push(64 * w + bits.trailing_zeros() as usize);
                bits &= bits - 1;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 2D base of width 2 on 21 pairs with a linear (trapezoid) pressure
    /// p = 1 + x / 2: by hand, P = 2, e = (1/2) ∫x² dx / ∫p dx over [-1, 1]
    /// = 1/6 (the trapezoid rule's sum a little more), inside the middle
    /// third |e| <= 1/3.
    #[test]
    fn trapezoid_by_hand() {
        let n = 21;
        let pairs: Vec<BearingPair> = (0..n)
            .map(|i| {
                let x = -1.0 + 2.0 * i as f64 / (n - 1) as f64;
                // trapezoid rule areas: halves at the ends
                let a = if i == 0 || i == n - 1 { 0.05 } else { 0.1 };
                BearingPair {
                    x: [x, 0.0, 0.0],
                    normal: [0.0, 1.0, 0.0],
                    area: a,
                    sigma_n: -(1.0 + x / 2.0),
                    open: false,
                }
            })
            .collect();
        let b = bearing(&pairs, true, Some(0.2)).expect("bearing");
        // t1 = n turned +90: -x; the face's ends from x = 1 down to x = -1
        assert_eq!(b.axes[0], [-1.0, 0.0, 0.0]);
        assert!((b.force - 2.0).abs() < 1e-12, "{}", b.force);
        let e = b.at[0] - b.centroid[0];
        // trapezoid rule of ∫x p / ∫p: (x/2)·x summed with the end halves
        let exact: f64 = pairs.iter().map(|p| p.area * p.x[0] * (1.0 + p.x[0] / 2.0)).sum::<f64>() / 2.0;
        assert!((e - exact).abs() < 1e-12 && (e - 1.0 / 6.0).abs() < 2e-3, "e {e}");
        assert!((b.eccentricity[0] + e).abs() < 1e-12);
        assert!((b.widths[0] - 2.0).abs() < 1e-12 && b.in_kern(true));
        let ends = b.from_ends();
        assert!((ends[0] - (1.0 - e)).abs() < 1e-12 && (ends[1] - (1.0 + e)).abs() < 1e-12, "{ends:?}");
        assert!((b.max_pressure - 1.5).abs() < 1e-12 && b.max_at[0] == 1.0);
        assert!((b.mean_pressure - 1.0).abs() < 1e-12);
        // the window [0.8, 1] (pairs at 0.8, 0.9, 1.0): (1.4 + 1.45 + 1.5/2) / 0.25
        assert!(
            (b.design_pressure - (0.1 * 1.4 + 0.1 * 1.45 + 0.05 * 1.5) / 0.25).abs() < 1e-12,
            "{}",
            b.design_pressure
        );
    }

    /// A singular corner pair does not set the design pressure; open pairs
    /// count in the area but not in contact.
    #[test]
    fn a_singular_corner_stays_in_the_maximum_only() {
        let mut pairs: Vec<BearingPair> = (0..11)
            .map(|i| BearingPair {
                x: [i as f64 * 0.1, 0.0, 0.0],
                normal: [0.0, 1.0, 0.0],
                area: 0.1,
                sigma_n: -1.0,
                open: false,
            })
            .collect();
        pairs[0].sigma_n = -4.0;
        pairs[10].sigma_n = 0.0;
        pairs[10].open = true;
        let b = bearing(&pairs, true, Some(0.5)).expect("bearing");
        assert_eq!(b.max_pressure, 4.0);
        assert!(b.design_pressure < 1.6, "{}", b.design_pressure);
        assert!((b.contact_area - 1.0).abs() < 1e-12 && (b.area - 1.1).abs() < 1e-12);
    }

    /// The window read from the grid's cells is the window of the whole
    /// face, to the bit: 2D and 3D faces of scattered pairs with a rough
    /// pressure, against every pair tried with every pair.
    #[test]
    fn the_grid_reads_the_windows_the_whole_face_does() {
        let mut rng = crate::test_rng::Lcg::new(12_345);
        for plane in [true, false] {
            let pairs: Vec<BearingPair> = (0..600)
                .map(|_| {
                    let (u, v) = (rng.unit() * 7.0 - 2.0, if plane { 0.0 } else { rng.unit() * 3.0 + 1.0 });
                    // a face in the plane y = 0.3 x + 1 (3D: tilted about x too)
                    let x = if plane { [u, 0.3 * u + 1.0, 0.0] } else { [u, 0.3 * u + 0.2 * v, v] };
                    let normal = normalized(if plane { [-0.3, 1.0, 0.0] } else { [-0.3, 1.0, -0.2] });
                    BearingPair {
                        x,
                        normal,
                        area: 0.01 + rng.unit() * 0.02,
                        sigma_n: 1.0 - 5.0 * rng.unit(),
                        open: false,
                    }
                })
                .collect();
            for window in [0.05, 0.4, 2.5, 50.0] {
                let b = bearing(&pairs, plane, Some(window)).expect("bearing");
                let along = |x: [f64; 3], k: usize| dot(sub(x, b.centroid), b.axes[k]);
                let s: Vec<[f64; 2]> = pairs.iter().map(|p| [along(p.x, 0), along(p.x, 1)]).collect();
                let (lo, hi) = (0..2).fold(([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]), |(mut lo, mut hi), k| {
                    s.iter().for_each(|q| (lo[k], hi[k]) = (lo[k].min(q[k]), hi[k].max(q[k])));
                    (lo, hi)
                });
                let (d, tol) = (window, 1e-9 * window);
                let fits = |v: f64, k: usize| {
                    if plane {
                        v + d <= hi[k] + tol || hi[k] - lo[k] < d
                    } else {
                        hi[k] - lo[k] < d || (v >= lo[k] + 0.5 * d - tol && v <= hi[k] - 0.5 * d + tol)
                    }
                };
                let mut best: Option<(f64, [f64; 3])> = None;
                for (p, &[s1, s2]) in pairs.iter().zip(&s) {
                    if !fits(s1, 0) || (!plane && !fits(s2, 1)) {
                        continue;
                    }
                    let (mut f, mut a) = (0.0, 0.0);
                    for (q, &[q1, q2]) in pairs.iter().zip(&s) {
                        let inside = if plane {
                            q1 >= s1 - tol && q1 <= s1 + d + tol
                        } else {
                            (q1 - s1).powi(2) + (q2 - s2).powi(2) <= (0.5 * d).powi(2) + tol * d
                        };
                        if inside {
                            f += (-q.sigma_n).max(0.0) * q.area;
                            a += q.area;
                        }
                    }
                    if a > 0.0 && best.is_none_or(|b| f / a > b.0) {
                        best = Some((f / a, p.x));
                    }
                }
                let (pressure, at) = best.expect("a window");
                assert_eq!((b.design_pressure, b.design_at), (pressure, at), "plane {plane}, window {window}");
            }
        }
    }
}
