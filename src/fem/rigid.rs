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
//! every contact closed, [`crate::contact::rigid`] of the parts under a set
//! of contact states.

use nalgebra::DMatrix;

use super::vec3::{cross, unit};
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
    fn rotation_mode_is_a_rigid_motion() {
        // a rotation about z moves (1, 0) along y and (0, 1) along -x
        let rm = RigidModes::new(Analysis::Solid, [0.0; 3], 1.0);
        assert_eq!(rm.along([1.0, 0.0, 0.0], [0.0, 1.0, 0.0])[5], 1.0);
        assert_eq!(rm.along([0.0, 1.0, 0.0], [1.0, 0.0, 0.0])[5], -1.0);
        assert_eq!(rm.along([0.0, 1.0, 0.0], [0.0, 0.0, 1.0])[3], 1.0);
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
