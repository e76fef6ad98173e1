//! Finite elements: shape functions and quadrature per cell kind, isotropic
//! elasticity, element kernels and sparse symmetric matrices, the kind of
//! analysis they are written for, the rigid-body motions of a body, and the
//! small 3-vector algebra they all use.

pub mod analysis;
pub mod bounded;
pub mod element;
pub mod material;
pub mod quadrature;
pub mod rigid;
pub mod shape;
pub mod sparse;
pub mod vec3;

pub use analysis::Analysis;
