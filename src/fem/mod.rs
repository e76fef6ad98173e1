//! Finite elements: shape functions and quadrature per cell kind, isotropic
//! elasticity, element kernels and sparse symmetric matrices.

pub mod element;
pub mod material;
pub mod quadrature;
pub mod shape;
pub mod sparse;
