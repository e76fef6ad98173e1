//! Which way is up, and the oblique view of 3D models that the deformed
//! picture and the joints' overview share: up against gravity, else y for
//! slices thin in z (a plane section extruded), else z; the eye turned to
//! the right of the viewer's axis and raised above it.

use crate::fem::vec3::{cross, dot, normalized, sub};

/// A model at most this thick in z, relative to the smaller of its x and y
/// extents, is a slice: a plane section extruded along z.
const SLICE: f64 = 0.25;

/// Which way is up in a 3D model of this extent: against gravity when there
/// is some; else y, as in the plane pictures, for slices (at most
/// [`SLICE`] of their section thick in z: the paper's cylinder, a tunnel
/// slice along z); else z, the vertical of 3D scenes (the README's depth
/// for k0 and water pressure), so that a footing on ground wider than deep
/// stands upright.
pub(super) fn up_of(extent: [f64; 3], gravity: [f64; 3]) -> [f64; 3] {
    let g = dot(gravity, gravity).sqrt();
    if g > 0.0 {
        gravity.map(|x| -x / g)
    } else if extent[2] <= SLICE * extent[0].min(extent[1]) {
        [0.0, 1.0, 0.0]
    } else {
        [0.0, 0.0, 1.0]
    }
}

/// Oblique view of 3D models: the eye's direction, right and up on screen.
pub(super) struct View {
    pub(super) eye: [f64; 3],
    pub(super) right: [f64; 3],
    pub(super) up: [f64; 3],
}

impl View {
    /// Which way is up: [`up_of`]. The eye is turned 30 degrees to the
    /// right and raised 25 degrees (20 and 20 for the extrusions seen mostly
    /// from +z, so that their section dominates).
    pub(super) fn new(extent: [f64; 3], gravity: [f64; 3]) -> View {
        let up = up_of(extent, gravity);
        let (toward, az, el) = if dot(gravity, gravity) > 0.0 {
            // the world axis least along up faces the viewer
            let k = (0..3).min_by(|&a, &b| up[a].abs().total_cmp(&up[b].abs())).unwrap_or(0);
            let mut t = [0.0; 3];
            t[k] = if k == 1 { -1.0 } else { 1.0 };
            (normalized(sub(t, up.map(|x| x * dot(t, up)))), 30.0f64, 25.0f64)
        } else if up[1] == 1.0 {
            ([0.0, 0.0, 1.0], 20.0, 20.0)
        } else {
            ([0.0, -1.0, 0.0], 30.0, 25.0)
        };
        let right = cross(up, toward);
        let (sa, ca, se, ce) =
            (az.to_radians().sin(), az.to_radians().cos(), el.to_radians().sin(), el.to_radians().cos());
        let eye: [f64; 3] = std::array::from_fn(|i| ce * (ca * toward[i] + sa * right[i]) + se * up[i]);
        let r: [f64; 3] = std::array::from_fn(|i| ca * right[i] - sa * toward[i]);
        View { eye, right: r, up: cross(eye, r) }
    }

    /// A point on the screen's plane (right, up) and its depth (larger is
    /// nearer the eye).
    pub(super) fn project(&self, x: [f64; 3]) -> ([f64; 2], f64) {
        ([dot(x, self.right), dot(x, self.up)], dot(x, self.eye))
    }
}

/// The bounding box of the nodes of every body's cells (the model as
/// drawn, without nodes no cell uses).
pub(super) fn model_box(model: &crate::model::Model) -> ([f64; 3], [f64; 3]) {
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for &k in model.bodies.iter().flat_map(|b| &b.cells).flat_map(|c| &c.nodes) {
        for d in 0..3 {
            lo[d] = lo[d].min(model.coords[k][d]);
            hi[d] = hi[d].max(model.coords[k][d]);
        }
    }
    (lo, hi)
}

/// Which way is up in `model` ([`up_of`] of its box and gravity).
pub(super) fn model_up(model: &crate::model::Model) -> [f64; 3] {
    let (lo, hi) = model_box(model);
    up_of(std::array::from_fn(|d| (hi[d] - lo[d]).max(0.0)), model.gravity)
}

#[cfg(test)]
mod tests {
    use super::up_of;

    /// Issue 19: the footing on two layers (8 x 8 in plan, 4.5 deep, no
    /// gravity) was drawn with y up, seen from above, since it is thinner
    /// in z than across; z is the vertical of a 3D scene unless the model
    /// is a slice.
    #[test]
    fn a_footing_on_wide_ground_stands_upright_and_a_slice_keeps_y_up() {
        let (y, z) = ([0.0, 1.0, 0.0], [0.0, 0.0, 1.0]);
        assert_eq!(up_of([8.0, 8.0, 4.5], [0.0; 3]), z, "the footing on layers");
        assert_eq!(up_of([4.0, 2.0, 2.0], [0.0; 3]), z, "a wedge in a groove");
        assert_eq!(up_of([5.0, 5.0, 1.0], [0.0; 3]), y, "the paper's cylinder, 1 m thick");
        assert_eq!(up_of([50.0, 50.0, 2.0], [0.0; 3]), y, "a tunnel slice along z");
        assert_eq!(up_of([5.0, 5.0, 1.0], [0.0, -9.81, 0.0]), y, "against gravity");
        assert_eq!(up_of([50.0, 2.0, 50.0], [0.0, 0.0, -9.81]), z, "against gravity");
    }
}
