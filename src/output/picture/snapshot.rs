//! One state of a model to draw.

use crate::model::Model;
use crate::recover::BodyStress;
use crate::results::about::Region;
use crate::results::ContactRun;

/// One state of a model to draw: its displacements, nodal stresses (empty
/// when they were not recovered) and contact states and stresses, and the
/// region the scene asks the deformed picture to frame.
pub struct Snapshot<'a> {
    /// The picture's title.
    pub title: &'a str,
    pub model: &'a Model,
    pub u: &'a [f64],
    pub stresses: &'a [BodyStress],
    pub contact: Option<&'a ContactRun>,
    pub region: Option<&'a Region>,
    /// One colour scale for every body (`[output] colour_scale = "one"`).
    pub one_scale: bool,
}
