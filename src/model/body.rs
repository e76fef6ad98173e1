//! A body of the model (a block of a `[[bodies]]` entry) and where a block
//! sits in its body group.

use super::spec::{InitialStress, Material};
use crate::fem::Analysis;
use crate::mesh::Cell;

/// A body of the model (a block of a `[[bodies]]` entry): cells in model
/// node numbering.
#[derive(Clone, Debug)]
pub struct Body {
    /// The body group's name.
    pub name: String,
    /// Its `[[bodies]]` entry, and when the group's contact facets cut it
    /// into several blocks: which, of how many, and where (the mean of its
    /// cells' nodes), to name it in messages.
    pub group: usize,
    pub block: Option<Block>,
    pub material: Material,
    pub cells: Vec<Cell>,
    /// In-situ stress the body carries before any load.
    pub initial: Option<InitialStress>,
}

/// Where a block sits in its body group.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Block {
    pub index: usize,
    pub of: usize,
    pub centre: [f64; 3],
}

impl Body {
    /// `"rock"`, or `"rock" block 3 of 8` for a block of a group cut into several.
    pub fn label(&self) -> String {
        match self.block {
            None => format!("\"{}\"", self.name),
            Some(b) => {
                let c = b.centre;
                format!(
                    "\"{}\" block {} of {} (centre at ({:.4}, {:.4}, {:.4}))",
                    self.name,
                    b.index + 1,
                    b.of,
                    c[0],
                    c[1],
                    c[2]
                )
            }
        }
    }

    /// The initial stress at x (zero without one).
    pub fn initial_at(&self, x: [f64; 3], analysis: Analysis, gravity: [f64; 3]) -> [f64; 6] {
        self.initial.map_or([0.0; 6], |i| i.at(x, analysis, self.material.density, gravity))
    }
}
