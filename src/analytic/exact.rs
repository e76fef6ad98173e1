//! A closed form's fields: displacement and stress at any point, which
//! the error norms compare the computed fields against.

/// Displacement and stress `[xx, yy, zz, xy, yz, xz]` of a closed form at a point.
pub trait Exact {
    fn displacement(&self, x: [f64; 3]) -> [f64; 3];
    fn stress(&self, x: [f64; 3]) -> [f64; 6];
}
