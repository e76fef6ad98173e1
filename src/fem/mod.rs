//! Finite elements: shape functions and quadrature per cell kind, isotropic
//! elasticity, element kernels and sparse symmetric matrices, and the kind
//! of analysis they are written for.

pub mod analysis;
pub mod element;
pub mod material;
pub mod quadrature;
pub mod shape;
pub mod sparse;

pub use analysis::Analysis;
