//! A junction's tied rows: each a pair and a direction in the pair's frame
//! ([`NORMAL`] its normal axis).

/// A tied row: a pair of the junction (its index there) and a unit
/// direction in its local axes, `[1, 0, 0]` its normal.
pub(super) type Row = (usize, [f64; 3]);

/// A pair's normal axis in its local frame.
pub(super) const NORMAL: [f64; 3] = [1.0, 0.0, 0.0];
