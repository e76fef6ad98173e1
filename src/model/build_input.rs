//! What every step of [`Model::build`](super::Model::build) reads (the mesh
//! and the description), and the messages that name the input's key and the
//! mesh when a physical group is missing, empty or of the wrong dimension.

use super::errors::{dim_name, ModelError};
use super::spec::ModelSpec;
use crate::mesh::{Group, Mesh};

/// What every step reads, and the messages that name the input and the mesh.
pub(super) struct Builder<'a> {
    pub(super) mesh: &'a Mesh,
    pub(super) spec: &'a ModelSpec,
}

impl<'a> Builder<'a> {
    pub(super) fn group(&self, key: &str, name: &str, dims: &[usize]) -> Result<&'a Group, ModelError> {
        let g = self.mesh.group(name).ok_or_else(|| ModelError::UnknownGroup {
            key: key.to_string(),
            group: name.to_string(),
            mesh: self.spec.mesh.clone(),
            known: self
                .mesh
                .groups
                .iter()
                .map(|g| format!("\"{}\" ({})", g.name, dim_name(g.dim)))
                .collect::<Vec<_>>()
                .join(", "),
        })?;
        if !dims.contains(&g.dim) {
            return Err(ModelError::WrongDimension {
                key: key.to_string(),
                group: name.to_string(),
                found: dim_name(g.dim).to_string(),
                wanted: dims.iter().map(|&d| dim_name(d)).collect::<Vec<_>>().join(" or "),
            });
        }
        if g.cells.is_empty() {
            return Err(ModelError::EmptyGroup {
                key: key.to_string(),
                group: name.to_string(),
                dim: dim_name(g.dim).to_string(),
                mesh: self.spec.mesh.clone(),
            });
        }
        Ok(g)
    }
}
