//! What a junction's ties give that depends only on which rows are tied
//! (the states of its pairs), kept for the last set of tied rows: the rows
//! of C and their constants, the free directions Z, the map from the rows'
//! targets to r0, the split of the force they carry, and the pairs' room
//! to slip. Each is an SVD (the rooms
//! one per pair), asked for two or three times per contact iteration
//! (the relations, the solve, the judgement), while most junctions of a
//! rock mass keep their states from one contact iteration to the next:
//! the 512-block cube of `make bench-blocks` spent a tenth of its run in
//! these SVDs before they were kept.
//!
//! Beside it, whatever rows were tied: whether the last solve's loops
//! carried part of a slipping pair's pressure (see [`super::pressure`]).

use std::sync::Mutex;

use nalgebra::DMatrix;

use super::room::Room;
use super::row::Row;
use super::split::Split;
use super::tangent::Tangent;
use super::Junction;

/// The last [`Tying`] of a junction, whether its last solve's loops
/// carried part of a slipping pair's pressure, and the [`Tangent`] of that
/// solve's share where it met a limit (empty, false, none, when cloned).
#[derive(Default)]
pub(super) struct Memo(Mutex<Option<Tying>>, Mutex<bool>, Mutex<Option<Tangent>>);

impl Clone for Memo {
    fn clone(&self) -> Memo {
        Memo::default()
    }
}

impl std::fmt::Debug for Memo {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("Memo")
    }
}

/// A junction with `rows` tied.
pub(super) struct Tying {
    rows: Vec<Row>,
    /// The rows of C over r of the tied rows, and their constants per unit ramp.
    c_rows: Vec<Vec<f64>>,
    pub consts: Vec<f64>,
    /// The free directions of r, and the map from the rows' targets to r0
    /// (see [`Junction::null_space`]).
    pub z: DMatrix<f64>,
    pub pinv: DMatrix<f64>,
    split: Option<Split>,
    rooms: Option<Vec<Room>>,
}

impl Tying {
    /// How the tied rows share the force they carry (the pairs' `areas`
    /// are the junction's own: the same at every call).
    pub fn split(&mut self, areas: &[f64], n_r: usize) -> &Split {
        let (rows, c_rows) = (&self.rows, &self.c_rows);
        self.split.get_or_insert_with(|| Split::new(c_rows, rows, areas, n_r))
    }

    /// How far each pair can slip (see [`Junction::rooms`]).
    pub fn rooms(&mut self, jn: &Junction) -> &[Room] {
        let z = &self.z;
        self.rooms.get_or_insert_with(|| jn.rooms_along(z))
    }
}

impl Memo {
    /// Whether the loops carried part of a slipping pair's pressure in a
    /// solve since the last [`Memo::reset_looped`], whichever rows it tied
    /// (see [`super::pressure`]).
    pub fn looped(&self) -> bool {
        *self.1.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Notes that the loops carried part of a pressure, if `looped`; it
    /// stays noted until [`Memo::reset_looped`].
    pub fn set_looped(&self, looped: bool) {
        *self.1.lock().unwrap_or_else(|e| e.into_inner()) |= looped;
    }

    pub fn reset_looped(&self) {
        *self.1.lock().unwrap_or_else(|e| e.into_inner()) = false;
        *self.2.lock().unwrap_or_else(|e| e.into_inner()) = None;
    }

    /// The last solve's share's tangent, if it met a limit.
    pub fn set_tangent(&self, tangent: Option<Tangent>) {
        *self.2.lock().unwrap_or_else(|e| e.into_inner()) = tangent;
    }

    /// The last solve's share's tangent, if it tied `rows` and met a limit.
    pub fn tangent(&self, rows: &[Row]) -> Option<Tangent> {
        let last = self.2.lock().unwrap_or_else(|e| e.into_inner());
        last.as_ref().filter(|t| t.rows == rows).cloned()
    }

    /// `f` of the junction `jn` with `rows` tied, from the last call's if
    /// it tied the same rows.
    pub fn with<R>(&self, jn: &Junction, rows: &[Row], f: impl FnOnce(&mut Tying) -> R) -> R {
        let mut last = self.0.lock().unwrap_or_else(|e| e.into_inner());
        let tying = match last.take() {
            Some(t) if t.rows == rows => t,
            _ => {
                let (c_rows, consts): (Vec<Vec<f64>>, Vec<f64>) = rows.iter().map(|&row| jn.c_row(row)).unzip();
                let (z, pinv) = jn.null_space(&c_rows);
                Tying { rows: rows.to_vec(), c_rows, consts, z, pinv, split: None, rooms: None }
            }
        };
        f(last.insert(tying))
    }
}
