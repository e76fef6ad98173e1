//! The rigid-body motions of a body, or of several moving as one:
//! `u(x) = R(x) alpha` with, in plane analyses, the translations in x and y
//! and the rotation about z; in axisymmetry the translation along the axis
//! (y) only, since moving in r strains the hoops; in 3D three translations
//! and three rotations. Rotations are about a centre and lengths are
//! measured in a size, so that every entry is O(1).
//!
//! A set of held directions (supports, tied contact axes) stops every rigid
//! motion exactly when the Gram matrix `sum r r^T` of its rows
//! `r = dir . R(x)` is regular: decided from the geometry, never from the
//! pivots of a factorisation. [`crate::model`] asks it of the supports with
//! every contact closed, [`crate::contact::mobility`] of the parts under a set
//! of contact states.
//!
//! A motion nothing stops is named as a person would ([`RigidMotion`]): a
//! rotation about a point (an axis through it in 3D), or, when that point
//! lies far outside the part, a translation along the direction it moves.

use nalgebra::DMatrix;

use super::vec3::{cross, norm, unit};
use super::Analysis;

/// The number of rigid motions.
pub fn n_modes(analysis: Analysis) -> usize {
    names(analysis).len()
}

/// The rigid motions by name, in the order of [`RigidModes::along`].
pub fn names(analysis: Analysis) -> &'static [&'static str] {
    match analysis {
        Analysis::PlaneStrain | Analysis::PlaneStress => &["translation in x", "translation in y", "rotation about z"],
        Analysis::Axisymmetric => &["translation along the axis (y)"],
        Analysis::Solid => &[
            "translation in x",
            "translation in y",
            "translation in z",
            "rotation about x",
            "rotation about y",
            "rotation about z",
        ],
    }
}

/// A rotation about a point further than this many part sizes from the
/// part's centre is named a translation.
const FAR: f64 = 10.0;

/// A rigid motion of a part, named: what [`RigidModes::motion`] makes of
/// amplitudes along its modes (their sign is arbitrary: so is the sense).
/// Geometry only; what a failing block does (sliding, toppling, ...) is
/// [`crate::contact::mechanism::BlockState`].
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum RigidMotion {
    /// Along a unit direction (`solid`: in 3D, else in the plane).
    Translation { dir: [f64; 3], solid: bool },
    /// In a plane analysis: about a point (about z).
    Turn { point: [f64; 3] },
    /// In 3D: about the unit axis through `point`.
    Rotation { axis: [f64; 3], point: [f64; 3] },
}

impl std::fmt::Display for RigidMotion {
    /// "translation along (1.0000, 0.0000)", "rotation about (0.0000,
    /// 0.0000)" in a plane, "rotation about the axis (..) through (..)" in 3D.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let xyz = |v: [f64; 3], n: usize| {
            // rounded first, so that a hair below zero is not "-0.0000"
            let c: Vec<String> = v[..n].iter().map(|x| format!("{:.4}", (x * 1e4).round() / 1e4 + 0.0)).collect();
            format!("({})", c.join(", "))
        };
        match *self {
            RigidMotion::Translation { dir, solid } => {
                write!(f, "translation along {}", xyz(dir, if solid { 3 } else { 2 }))
            }
            RigidMotion::Turn { point } => write!(f, "rotation about {}", xyz(point, 2)),
            RigidMotion::Rotation { axis, point } => {
                write!(f, "rotation about the axis {} through {}", xyz(axis, 3), xyz(point, 3))
            }
        }
    }
}

/// The rigid motions about a centre, with lengths in units of a size.
#[derive(Clone, Debug)]
pub struct RigidModes {
    analysis: Analysis,
    center: [f64; 3],
    scale: f64,
}

impl RigidModes {
    /// The motions about `center`, lengths divided by `scale` (> 0).
    pub fn new(analysis: Analysis, center: [f64; 3], scale: f64) -> RigidModes {
        RigidModes { analysis, center, scale }
    }

    pub fn analysis(&self) -> Analysis {
        self.analysis
    }

    /// `dir . R(x)`: how much each motion moves the point x along `dir`
    /// (entries past [`n_modes`] are zero).
    pub fn along(&self, x: [f64; 3], dir: [f64; 3]) -> [f64; 6] {
        let d = [
            (x[0] - self.center[0]) / self.scale,
            (x[1] - self.center[1]) / self.scale,
            (x[2] - self.center[2]) / self.scale,
        ];
        match self.analysis {
            // u = t + theta e_z x d
            Analysis::PlaneStrain | Analysis::PlaneStress => {
                [dir[0], dir[1], -d[1] * dir[0] + d[0] * dir[1], 0.0, 0.0, 0.0]
            }
            Analysis::Axisymmetric => [dir[1], 0.0, 0.0, 0.0, 0.0, 0.0],
            // u = t + w x d: (w x d) . dir = w . (d x dir)
            Analysis::Solid => {
                let c = cross(d, dir);
                [dir[0], dir[1], dir[2], c[0], c[1], c[2]]
            }
        }
    }

    /// The motion `u(x) = R(x) a` named: a rotation about the point it
    /// leaves in place (the axis's point nearest the centre in 3D, where a
    /// slide along the axis is left unsaid), or a translation when that
    /// point is further than [`FAR`] sizes away or there is no rotation.
    pub fn motion(&self, a: &[f64]) -> RigidMotion {
        let (c, s) = (self.center, self.scale);
        let t = match self.analysis {
            Analysis::PlaneStrain | Analysis::PlaneStress => [a[0], a[1], 0.0],
            Analysis::Axisymmetric => [0.0, a[0], 0.0],
            Analysis::Solid => [a[0], a[1], a[2]],
        };
        // the rotation (per unit of the scaled length) and, from u(p) = 0
        // (in 3D: u(p) along the axis), the point p - c in scaled lengths
        let (w, p) = match self.analysis {
            Analysis::PlaneStrain | Analysis::PlaneStress => ([0.0, 0.0, a[2]], [-a[1] / a[2], a[0] / a[2], 0.0]),
            Analysis::Axisymmetric => ([0.0; 3], [0.0; 3]),
            Analysis::Solid => {
                let w = [a[3], a[4], a[5]];
                let ww = w.iter().map(|x| x * x).sum::<f64>();
                (w, cross(w, t).map(|x| x / ww))
            }
        };
        let (wn, tn, solid) = (norm(w), norm(t), self.analysis == Analysis::Solid);
        if wn == 0.0 || norm(p) > FAR || !p.iter().all(|x| x.is_finite()) {
            return RigidMotion::Translation { dir: if tn > 0.0 { t.map(|x| x / tn) } else { unit(1) }, solid };
        }
        let point = std::array::from_fn(|i| c[i] + s * p[i]);
        if !solid {
            return RigidMotion::Turn { point };
        }
        let mut axis = w.map(|x| x / wn);
        // one sense for the axis: its largest component positive
        let big = (0..3).fold(0, |b, i| if axis[i].abs() > axis[b].abs() { i } else { b });
        if axis[big] < 0.0 {
            axis = axis.map(|x| -x);
        }
        RigidMotion::Rotation { axis, point }
    }

    /// The length the rotations' amplitudes are measured in.
    pub fn scale(&self) -> f64 {
        self.scale
    }

    /// The centre the rotations are about.
    pub fn center(&self) -> [f64; 3] {
        self.center
    }

    /// The motion of amplitudes `a` (in the order of [`RigidModes::along`])
    /// as vectors: the translation of the centre, and the rotation
    /// (radians); [`RigidModes::motion`] names it.
    pub fn velocity(&self, a: &[f64; 6]) -> ([f64; 3], [f64; 3]) {
        let s = self.scale;
        match self.analysis {
            Analysis::PlaneStrain | Analysis::PlaneStress => ([a[0], a[1], 0.0], [0.0, 0.0, a[2] / s]),
            Analysis::Axisymmetric => ([0.0, a[0], 0.0], [0.0; 3]),
            Analysis::Solid => ([a[0], a[1], a[2]], [a[3] / s, a[4] / s, a[5] / s]),
        }
    }

    /// `sum r r^T` over the held directions, `r = dir . R(x)` for each
    /// (point, direction): singular exactly when some rigid motion moves
    /// none of them.
    pub fn gram(&self, held: impl IntoIterator<Item = ([f64; 3], [f64; 3])>) -> DMatrix<f64> {
        let nm = n_modes(self.analysis);
        let mut g = DMatrix::<f64>::zeros(nm, nm);
        for (x, dir) in held {
            let r = self.along(x, dir);
            for j in 0..nm {
                for i in 0..nm {
                    g[(i, j)] += r[i] * r[j];
                }
            }
        }
        g
    }

    /// `gram` over the supported components of `nodes`: (node, component)
    /// pairs whose coordinates are `coords[node]`.
    pub fn gram_of_supports(
        &self,
        coords: &[[f64; 3]],
        supported: impl IntoIterator<Item = (usize, usize)>,
    ) -> DMatrix<f64> {
        self.gram(supported.into_iter().map(|(n, c)| (coords[n], unit(c))))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_motions_amplitudes_give_its_translation_and_rotation_in_radians() {
        // a rotation of 0.01 rad about z, about (1, 2) with lengths in 4: the
        // scaled mode moves (1 + 4, 2) by 0.04 along y, so its amplitude is 0.04
        let rm = RigidModes::new(Analysis::PlaneStrain, [1.0, 2.0, 0.0], 4.0);
        assert_eq!(rm.along([5.0, 2.0, 0.0], [0.0, 1.0, 0.0])[2], 1.0);
        let (t, w) = rm.velocity(&[0.5, 0.0, 0.04, 0.0, 0.0, 0.0]);
        assert_eq!((t, w), ([0.5, 0.0, 0.0], [0.0, 0.0, 0.01]));
        let rm = RigidModes::new(Analysis::Solid, [0.0; 3], 2.0);
        assert_eq!(rm.velocity(&[1.0, 2.0, 3.0, 0.2, 0.0, -0.4]), ([1.0, 2.0, 3.0], [0.1, 0.0, -0.2]));
    }

    #[test]
    fn rotation_mode_is_a_rigid_motion() {
        // a rotation about z moves (1, 0) along y and (0, 1) along -x
        let rm = RigidModes::new(Analysis::Solid, [0.0; 3], 1.0);
        assert_eq!(rm.along([1.0, 0.0, 0.0], [0.0, 1.0, 0.0])[5], 1.0);
        assert_eq!(rm.along([0.0, 1.0, 0.0], [1.0, 0.0, 0.0])[5], -1.0);
        assert_eq!(rm.along([0.0, 1.0, 0.0], [0.0, 0.0, 1.0])[3], 1.0);
    }

    #[test]
    fn motions_are_named_by_the_point_they_turn_about_or_the_way_they_go() {
        // a plane part centred at (2, 1), size 4: u = (a0 - a2 dy, a1 + a2 dx)
        let rm = RigidModes::new(Analysis::PlaneStrain, [2.0, 1.0, 0.0], 4.0);
        // turning about (0, 0): d = (-0.5, -0.25), so a0 = -0.25 a2, a1 = 0.5 a2
        let m = rm.motion(&[-0.25 * 3.0, 0.5 * 3.0, 3.0]);
        let RigidMotion::Turn { point } = m else { panic!("{m:?}") };
        assert!(point.iter().all(|x| x.abs() < 1e-15), "{point:?}");
        assert_eq!(m.to_string(), "rotation about (0.0000, 0.0000)");
        // a translation, and a rotation about a point 100 sizes away
        assert_eq!(rm.motion(&[0.6, -0.8, 0.0]), RigidMotion::Translation { dir: [0.6, -0.8, 0.0], solid: false });
        assert_eq!(rm.motion(&[0.6, -0.8, 0.01]).to_string(), "translation along (0.6000, -0.8000)");
        // in 3D about the axis x = 1, y = 2 (along z), with a slide along it
        let rm = RigidModes::new(Analysis::Solid, [0.0; 3], 2.0);
        // u = t + w x d, w = (0, 0, -1): at d = (0.5, 1, 0) u = (0, 0, t_z)
        let m = rm.motion(&[-1.0, 0.5, 0.3, 0.0, 0.0, -1.0]);
        let RigidMotion::Rotation { axis, point } = m else { panic!("{m:?}") };
        assert_eq!(axis, [0.0, 0.0, 1.0]);
        assert!((point[0] - 1.0).abs() < 1e-15 && (point[1] - 2.0).abs() < 1e-15 && point[2].abs() < 1e-15);
        assert_eq!(m.to_string(), "rotation about the axis (0.0000, 0.0000, 1.0000) through (1.0000, 2.0000, 0.0000)");
        let ax = RigidModes::new(Analysis::Axisymmetric, [3.0, 0.0, 0.0], 1.0);
        assert_eq!(ax.motion(&[-2.0]), RigidMotion::Translation { dir: [0.0, -1.0, 0.0], solid: false });
    }

    #[test]
    fn an_axisymmetric_body_has_no_radial_rigid_motion() {
        let r = RigidModes::new(Analysis::Axisymmetric, [4.0, 0.5, 0.0], 1.0);
        assert_eq!(r.along([3.0, 0.0, 0.0], [1.0, 0.0, 0.0])[0], 0.0);
        assert_eq!(r.along([3.0, 0.0, 0.0], [0.0, 1.0, 0.0])[0], 1.0);
    }

    #[test]
    fn three_plane_supports_not_on_one_line_stop_every_motion() {
        let rm = RigidModes::new(Analysis::PlaneStrain, [1.0, 0.5, 0.0], 1.0);
        let coords = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]];
        let rank = |g: DMatrix<f64>| g.symmetric_eigen().eigenvalues.iter().filter(|&&l| l > 1e-12).count();
        assert_eq!(
            rank(rm.gram_of_supports(&coords, [(0, 1), (1, 1)])),
            2,
            "two vertical supports: x translation free"
        );
        assert_eq!(rank(rm.gram_of_supports(&coords, [(0, 1), (1, 1), (0, 0)])), 3);
    }
}
