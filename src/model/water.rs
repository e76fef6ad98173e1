//! Water in a joint: the pressure u it puts on both faces of a contact
//! group, pushing the faces apart (into each body), in every state of the
//! pairs, open ones included. The contact law then judges the solid-to-solid
//! force, i.e. the effective normal stress `sigma_n' = sigma_n + u` (tension
//! positive, u >= 0).
//!
//! The pressure at a point x of the joint, per unit load factor:
//!
//! ```text
//! uniform:      u = u0
//! piezometric:  u = gamma_w (h(s) - z)  where positive, 0 above the level
//!               s = x . along  (the horizontal position along the flow),
//!               z the height (y in 2D, z in 3D)
//! ```
//!
//! The piezometric level h(s) is linear between the points of its diagram
//! and constant beyond them: one point is a flat phreatic level; two are the
//! dam's uplift diagram from the heel's head to the toe's. Or it is an
//! inclined plane, `h = h0 + a x + b y` (3D; `h0 + a x` in 2D). A drain line at
//! s_d of efficiency E lowers the diagram there to (USACE EM 1110-2-2100,
//! USBR):
//!
//! ```text
//! h_d = h_toe + (1 - E) (h(s_d) - h_toe)        h_toe the diagram's last head
//! ```
//!
//! **A crack that fills** (the USACE / USBR rule): when the joint has opened
//! from the face in contact with the free water (a reservoir, a tension
//! crack's water) to s_tip, the crack takes that water's full pressure,
//! `gamma_w (H - z)` with H its level, and the diagram restarts at the tip:
//! the points up to s_tip are replaced by (s_tip, H), and the drain counts
//! only when it lies beyond the tip. Where the crack is is the contact
//! iteration's business (`contact::water`); here is the pressure for a
//! given tip.

/// The water in one contact group, as the description gives it.
#[derive(Debug, Clone, PartialEq)]
pub struct JointWater {
    pub pressure: WaterPressure,
    /// The free water the joint connects to, whose cracks fill with it.
    pub face: Option<WaterFace>,
    /// Load factor at each load step; None: the connected face's load
    /// case, or the ramp k / load_steps.
    pub factors: Option<Vec<f64>>,
}

/// How the water pressure varies over the joint.
#[derive(Debug, Clone, PartialEq)]
pub enum WaterPressure {
    /// A uniform pressure.
    Uniform(f64),
    /// `gamma_w (h(s) - z)` below a piezometric level h(s).
    Level { unit_weight: f64, along: [f64; 3], levels: Levels, drain: Option<Drain> },
}

/// The piezometric level as given.
#[derive(Debug, Clone, PartialEq)]
pub enum Levels {
    /// A flat (phreatic) level.
    Flat(f64),
    /// Points (s, h), s strictly increasing.
    Table(Vec<[f64; 2]>),
    /// From `upstream` at the joint's upstream end (its smallest s) to
    /// `downstream` at its downstream end: the builder reads the ends off
    /// the joint.
    Ends { upstream: f64, downstream: f64 },
    /// An inclined plane `h = c[0] + c[1] x + c[2] y` (`c[2] = 0` in 2D).
    Plane([f64; 3]),
}

/// A drain line at s = `at` of efficiency `efficiency` (0 to 1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Drain {
    pub at: f64,
    pub efficiency: f64,
}

/// The free water a joint connects to: a face loaded by a hydrostatic
/// `[[loads]]` entry, its level and unit weight.
#[derive(Debug, Clone, PartialEq)]
pub struct WaterFace {
    pub group: String,
    /// Its `[[loads]]` entry (index in the description's loads).
    pub load: usize,
    pub surface: f64,
    pub unit_weight: f64,
}

/// The water of one contact group of the model: its pressure with the
/// diagram's ends resolved, the crack's water, and its load case.
#[derive(Debug, Clone)]
pub struct GroupWater {
    /// The contact group (index in `Model::interfaces`).
    pub contact: usize,
    pub field: Field,
    pub fill: Option<Fill>,
    /// Its load case (index into `Model::cases`).
    pub case: usize,
    /// The sign that makes each facet's natural normal outward of side I.
    pub signs: Vec<f64>,
    /// The height axis: 1 (y) in 2D, 2 (z) in 3D.
    pub vertical: usize,
}

/// The pressure field of a group (per unit load factor).
#[derive(Debug, Clone, PartialEq)]
pub enum Field {
    Uniform(f64),
    Level {
        unit_weight: f64,
        along: [f64; 3],
        diagram: Diagram,
    },
    /// Below an inclined plane `h = c[0] + c[1] x + c[2] y`.
    Plane {
        unit_weight: f64,
        along: [f64; 3],
        plane: [f64; 3],
    },
}

/// A piezometric diagram: points (s, h), s strictly increasing (one point:
/// a flat level), and its drain.
#[derive(Debug, Clone, PartialEq)]
pub struct Diagram {
    pub points: Vec<[f64; 2]>,
    pub drain: Option<Drain>,
}

/// Where a crack of the group fills from: the free water's level and unit
/// weight, and where on the joint a crack starts and how it runs. A crack
/// stays in the sheet it starts in (a smooth piece of the group: a crease
/// or a crossing joint ends it), so a group of many faces, a dam's base
/// with the sides of its foundation's steps, has one crack per sheet.
#[derive(Debug, Clone, PartialEq)]
pub struct Fill {
    pub surface: f64,
    pub unit_weight: f64,
    /// Every pair of the group (model pair indices).
    pub pairs: Vec<usize>,
    /// The sheet of each facet of the group (indices into `sheets`).
    pub facet_sheet: Vec<usize>,
    pub sheets: Vec<Sheet>,
}

/// One sheet of a group whose cracks fill: its pairs, where a crack starts
/// in it and how it runs through it.
#[derive(Debug, Clone, PartialEq)]
pub struct Sheet {
    /// Its pairs (indices into [`Fill::pairs`]).
    pub pairs: Vec<usize>,
    /// Those on the face the joint connects to (indices into `pairs` here).
    pub seeds: Vec<usize>,
    /// The pairs that share one of the sheet's facets with each (indices
    /// into `pairs` here).
    pub neighbours: Vec<Vec<usize>>,
    /// Its mean unit normal (the sign of its largest component positive).
    pub normal: [f64; 3],
}

/// A crack that has filled: it reaches `tip` (in s) with the free water at
/// `level`, of unit weight `unit_weight`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Crack {
    pub tip: f64,
    pub level: f64,
    pub unit_weight: f64,
}

impl Diagram {
    /// The level at s, without a crack.
    pub fn head(&self, s: f64) -> f64 {
        with_drain(&self.points, self.drain, s)
    }

    /// The level at s with the diagram restarted at a crack's tip at the
    /// free water's level (constant up to the tip).
    pub fn head_cracked(&self, s: f64, tip: f64, level: f64) -> f64 {
        if s <= tip {
            return level;
        }
        let mut points = vec![[tip, level]];
        points.extend(self.points.iter().copied().filter(|p| p[0] > tip));
        let drain = self.drain.filter(|d| d.at > tip);
        with_drain(&points, drain, s)
    }
}

/// Linear interpolation of `points` at s, constant beyond the ends.
fn interpolate(points: &[[f64; 2]], s: f64) -> f64 {
    let (first, last) = (points[0], points[points.len() - 1]);
    if s <= first[0] {
        return first[1];
    }
    if s >= last[0] {
        return last[1];
    }
    let i = points.partition_point(|p| p[0] <= s);
    let (a, b) = (points[i - 1], points[i]);
    a[1] + (b[1] - a[1]) * (s - a[0]) / (b[0] - a[0])
}

/// `points` with the drain's point put in (where it lies inside them), at s.
fn with_drain(points: &[[f64; 2]], drain: Option<Drain>, s: f64) -> f64 {
    let last = points[points.len() - 1];
    match drain {
        Some(d) if d.at > points[0][0] && d.at < last[0] => {
            let h_d = last[1] + (1.0 - d.efficiency) * (interpolate(points, d.at) - last[1]);
            let mut with: Vec<[f64; 2]> = points.iter().copied().filter(|p| p[0] < d.at).collect();
            with.push([d.at, h_d]);
            with.extend(points.iter().copied().filter(|p| p[0] > d.at));
            interpolate(&with, s)
        }
        _ => interpolate(points, s),
    }
}

impl GroupWater {
    /// The position along the flow a crack is measured by: `along`, or x
    /// for a uniform pressure (whose crack still fills from its face).
    pub fn along(&self) -> [f64; 3] {
        match &self.field {
            Field::Uniform(_) => [1.0, 0.0, 0.0],
            Field::Level { along, .. } | Field::Plane { along, .. } => *along,
        }
    }

    /// The position of x along the flow, `x . along`.
    pub fn s(&self, x: [f64; 3]) -> f64 {
        dot(x, self.along())
    }

    /// The pressure at x per unit load factor, with the crack `crack` (when
    /// one has filled).
    pub fn pressure(&self, x: [f64; 3], crack: Option<Crack>) -> f64 {
        let z = x[self.vertical];
        let s = self.s(x);
        if let Some(c) = crack {
            if s <= c.tip {
                return (c.unit_weight * (c.level - z)).max(0.0);
            }
        }
        match &self.field {
            Field::Uniform(u) => *u,
            Field::Level { unit_weight, diagram, .. } => {
                let h = match crack {
                    Some(c) => diagram.head_cracked(s, c.tip, c.level),
                    None => diagram.head(s),
                };
                (unit_weight * (h - z)).max(0.0)
            }
            Field::Plane { unit_weight, plane, .. } => {
                (unit_weight * (plane[0] + plane[1] * x[0] + plane[2] * x[1] - z)).max(0.0)
            }
        }
    }
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dam(drain: Option<Drain>) -> GroupWater {
        GroupWater {
            contact: 0,
            field: Field::Level {
                unit_weight: 10.0,
                along: [1.0, 0.0, 0.0],
                diagram: Diagram { points: vec![[0.0, 50.0], [30.0, 5.0]], drain },
            },
            fill: None,
            case: 0,
            signs: Vec::new(),
            vertical: 1,
        }
    }

    /// The uplift diagram of a dam's base (y = 0): heel 50 m, toe 5 m.
    #[test]
    fn uplift_is_linear_from_heel_to_toe() {
        let w = dam(None);
        assert_eq!(w.pressure([0.0, 0.0, 0.0], None), 500.0);
        assert_eq!(w.pressure([30.0, 0.0, 0.0], None), 50.0);
        assert!((w.pressure([10.0, 0.0, 0.0], None) - 350.0).abs() < 1e-12);
        // beyond the ends, the ends' heads; above the level, nothing
        assert_eq!(w.pressure([-5.0, 0.0, 0.0], None), 500.0);
        assert_eq!(w.pressure([10.0, 40.0, 0.0], None), 0.0);
    }

    /// USACE's drain: at X = 6 from the heel, E = 2/3, the head there is
    /// H3 + (1 - E) (H1 - H3) (L - X) / L.
    #[test]
    fn a_drain_lowers_the_diagram_at_its_line() {
        let w = dam(Some(Drain { at: 6.0, efficiency: 2.0 / 3.0 }));
        let h_d = 5.0 + (1.0 / 3.0) * 45.0 * (24.0 / 30.0);
        assert!((w.pressure([6.0, 0.0, 0.0], None) - 10.0 * h_d).abs() < 1e-12);
        assert!((w.pressure([3.0, 0.0, 0.0], None) - 10.0 * (50.0 + h_d) / 2.0).abs() < 1e-12);
        assert!((w.pressure([18.0, 0.0, 0.0], None) - 10.0 * (h_d + 5.0) / 2.0).abs() < 1e-12);
    }

    /// An inclined level in 3D: h = 10 + 0.5 x - 0.25 y.
    #[test]
    fn below_an_inclined_plane() {
        let w = GroupWater {
            field: Field::Plane { unit_weight: 2.0, along: [1.0, 0.0, 0.0], plane: [10.0, 0.5, -0.25] },
            vertical: 2,
            ..dam(None)
        };
        assert_eq!(w.pressure([2.0, 4.0, 3.0], None), 2.0 * (10.0 + 1.0 - 1.0 - 3.0));
        assert_eq!(w.pressure([0.0, 0.0, 11.0], None), 0.0);
    }

    /// A crack to s = 12 from the heel: the reservoir's full head up to
    /// the tip, then linear to the toe (drain ineffective beyond the tip,
    /// restarted before it).
    #[test]
    fn a_crack_takes_the_full_head_and_restarts_the_diagram() {
        let crack = Some(Crack { tip: 12.0, level: 50.0, unit_weight: 10.0 });
        let w = dam(None);
        assert_eq!(w.pressure([11.0, 0.0, 0.0], crack), 500.0);
        assert!((w.pressure([21.0, 0.0, 0.0], crack) - 10.0 * 27.5).abs() < 1e-12);
        let drained = dam(Some(Drain { at: 6.0, efficiency: 2.0 / 3.0 }));
        assert!((drained.pressure([21.0, 0.0, 0.0], crack) - 10.0 * 27.5).abs() < 1e-12);
        // a drain beyond the tip: H3 + (1 - E)(H1 - H3)(L - X)/(L - T)
        let drained = dam(Some(Drain { at: 18.0, efficiency: 0.5 }));
        let h_d = 5.0 + 0.5 * 45.0 * 12.0 / 18.0;
        assert!((drained.pressure([18.0, 0.0, 0.0], crack) - 10.0 * h_d).abs() < 1e-12);
    }
}
