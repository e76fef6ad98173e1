//! Local frames of contact pairs, `T = [n; t; b]` (rows), and their
//! alignment with supports.
//!
//! 2D: t is n rotated +90 degrees about z. 3D: t = normalize(e_z x n) unless
//! n is within ~25 degrees of z, then t = normalize(n x e_x), so the frame
//! varies smoothly with n over each side of that cone; b = n x t.
//!
//! An interface node that is also supported (a roller face or a symmetry
//! plane that the interface meets) has its supported global directions
//! along local axes when that costs the normal no more than a few degrees:
//! the support is then a prescribed local DOF of a lone pair. n is snapped
//! onto a supported axis c when |n_c| > [`SNAP`] (the interface lies in the
//! supported plane), or projected off the supported directions when they
//! hold less than [`PROJECT`] of it (an interface crossing a symmetry line
//! at right angles, its nodal normal a little off), and in 3D b is taken
//! along a supported direction perpendicular to n.
//!
//! Between the two the pair keeps its true frame, and `layout` writes it as
//! a junction of one pair in global axes (its supports cannot be local
//! axes). Both of its copies held along c, its relative motion has no c
//! part; a snap would read the motion that changes its gap (a 70 degree
//! joint against a vertical roller: n = (0.94, 0.34), gap = 0.34 dy) as a
//! free slip at zero pressure, and a projection would judge its strength on
//! a plane turned by up to 64 degrees. In its true frame the gap is
//! unilateral, the slip the supports leave (none in 2D) is judged by
//! Coulomb on the joint itself, and the force the rigid limit leaves
//! undecided between the joint and the support is the junction's least-norm
//! one within the pair's Coulomb cone (equal joint springs, what a penalty
//! contact next to a support gives).

use crate::fem::vec3::{cross, normalized};

pub type Frame = [[f64; 3]; 3];

/// n is snapped onto a supported axis past this cosine (5.7 degrees).
pub const SNAP: f64 = 0.995;

/// n is projected off the supported directions when their part of it is
/// below this (the projection turns it by less than 5.7 degrees).
pub const PROJECT: f64 = 0.1;

/// The global axes as a frame.
pub const IDENTITY: Frame = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

/// The frame of a pair with normal `n` whose nodes have the global
/// directions `fixed` supported; `nd` is 2 or 3.
pub fn frame(nd: usize, n: [f64; 3], fixed: [bool; 3]) -> Frame {
    let axes = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let mut n = n;
    let mut fixed: Vec<usize> = (0..nd).filter(|&c| fixed[c]).collect();
    let held = fixed.iter().map(|&c| n[c] * n[c]).sum::<f64>().sqrt();
    if let Some(&c) = fixed.iter().find(|&&c| n[c].abs() > SNAP) {
        // the interface lies in a supported plane: n along that axis
        let sign = n[c].signum();
        n = [0.0; 3];
        n[c] = sign;
    } else if !fixed.is_empty() && held < PROJECT {
        for &c in &fixed {
            n[c] = 0.0;
        }
        n = normalized(n);
    } else if !fixed.is_empty() {
        // the true frame: the supports stay in global axes (a junction)
        fixed.clear();
    }
    if nd == 2 {
        return [[n[0], n[1], 0.0], [-n[1], n[0], 0.0], [0.0, 0.0, 1.0]];
    }
    let perp = fixed.iter().copied().find(|&c| n[c].abs() < 0.5);
    let (t, b) = match perp {
        Some(c) => {
            let b = axes[c];
            (cross(b, n), b)
        }
        None => {
            let t = if n[2].abs() < 0.9 { normalized(cross(axes[2], n)) } else { normalized(cross(n, axes[0])) };
            (t, cross(n, t))
        }
    };
    [n, t, b]
}

/// For each supported global direction c, the local axis it lies along and
/// the sign (`T[a][c] = sign`), or None when the frame does not align.
pub fn aligned_axis(frame: &Frame, nd: usize, c: usize) -> Option<(usize, f64)> {
    (0..nd).find(|&a| (frame[a][c].abs() - 1.0).abs() < 1e-9).map(|a| (a, frame[a][c].signum()))
}

/// The tangential part of a vector in a pair's local axes (n, t, b).
pub(crate) fn tangential(v: [f64; 3]) -> [f64; 3] {
    [0.0, v[1], v[2]]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::vec3::dot;

    fn orthonormal(f: &Frame) {
        for i in 0..3 {
            for j in 0..3 {
                let want = if i == j { 1.0 } else { 0.0 };
                assert!((dot(f[i], f[j]) - want).abs() < 1e-12);
            }
        }
        // right-handed: n x t = b
        let b = cross(f[0], f[1]);
        for i in 0..3 {
            assert!((b[i] - f[2][i]).abs() < 1e-12);
        }
    }

    #[test]
    fn frames_are_right_handed_and_orthonormal() {
        let s = 0.5f64.sqrt();
        for n in [[s, s, 0.0], [0.0, 0.0, 1.0], [0.3, -0.4, (1.0f64 - 0.25).sqrt()], [-1.0, 0.0, 0.0]] {
            orthonormal(&frame(3, n, [false; 3]));
        }
        let f = frame(2, [s, -s, 0.0], [false; 3]);
        orthonormal(&f);
        assert!((f[1][0] - s).abs() < 1e-15 && (f[1][1] - s).abs() < 1e-15);
    }

    #[test]
    fn supported_directions_become_local_axes() {
        // a radial interface at 45 degrees in a slab held in z
        let s = 0.5f64.sqrt();
        let f = frame(3, [-s, s, 0.0], [false, false, true]);
        orthonormal(&f);
        assert_eq!(aligned_axis(&f, 3, 2), Some((2, 1.0)));
        // a curved interface ending on the symmetry line y = 0 (uy held)
        let f = frame(2, [0.998, 0.06, 0.0], [false, true, false]);
        assert_eq!(f[0], [1.0, 0.0, 0.0]);
        assert_eq!(aligned_axis(&f, 2, 1), Some((1, 1.0)));
        // an interface lying in the symmetry plane x = 0 (ux held)
        let f = frame(2, [-0.998, 0.06, 0.0], [true, false, false]);
        assert_eq!(f[0], [-1.0, 0.0, 0.0]);
        assert_eq!(aligned_axis(&f, 2, 0), Some((0, -1.0)));
    }

    /// A joint dipping 70 degrees meets a vertical roller (ux held): n =
    /// (0.94, 0.34). Snapped onto x (as it was), its pressure went into
    /// the support and its motion along y, which changes its gap by
    /// 0.34 dy, was read as a free slip; projected onto y, its strength
    /// would be judged on a plane turned by 70 degrees. It keeps its own
    /// frame, which no support lies along (a junction of one pair).
    #[test]
    fn a_steep_joint_at_a_roller_keeps_its_frame() {
        let a = 70f64.to_radians();
        let n = [a.sin(), a.cos(), 0.0];
        let f = frame(2, n, [true, false, false]);
        assert_eq!(f, frame(2, n, [false; 3]));
        assert_eq!(aligned_axis(&f, 2, 0), None);
        // 3D: a joint at 70 degrees to a roller face x = const
        let n3 = [a.sin(), a.cos() * 0.6, a.cos() * 0.8];
        let f = frame(3, n3, [true, false, false]);
        assert_eq!(f[0], n3);
        assert_eq!(aligned_axis(&f, 3, 0), None);
    }
}
