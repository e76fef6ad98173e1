//! What a closed-form check reads of a solved run: the model, the
//! displacements, the stresses at the probe points and the contact pairs.

use crate::contact::law::PairResult;
use crate::model::Model;

/// What a check reads of a solved run (its last load step).
pub struct Solution<'a> {
    pub model: &'a Model,
    pub u: &'a [f64],
    /// The probe points inside the model: position and stress
    /// `[xx, yy, zz, xy, yz, xz]`, probe after probe.
    pub probed: Vec<([f64; 3], [f64; 6])>,
    /// The contact pairs' results (None without contact).
    pub pairs: Option<&'a [PairResult]>,
}
