//! How far a junction pair's shear can move under a set of states.

/// How far a junction pair's shear can move under a set of states (see
/// [`super::Junction::rooms`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Room {
    /// The junction's ties lock it.
    None,
    /// Along one direction only (local axes `[0, t, b]`), as on a crease
    /// whose other face is closed, or on a crossing line (3D).
    Line([f64; 3]),
    /// Along its whole shear plane (its one shear axis in 2D).
    Free,
}

impl Room {
    /// The direction of a [`Room::Line`].
    pub fn line(self) -> Option<[f64; 3]> {
        match self {
            Room::Line(d) => Some(d),
            Room::None | Room::Free => None,
        }
    }
}
