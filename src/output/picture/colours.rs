//! The pictures' colours: the contact states, pairs without a state, the
//! undeformed ghost, text and frames.

use crate::contact::law::ContactState;

/// Colours: the contact states, pairs without a state, the undeformed
/// ghost, text and frames.
pub(super) const STICK: [u8; 3] = [20, 170, 60];
pub(super) const SLIP: [u8; 3] = [255, 140, 0];
pub(super) const OPEN: [u8; 3] = [225, 20, 30];
pub(super) const NO_PAIR: [u8; 3] = [120, 120, 120];
pub(super) const GHOST: [u8; 3] = [228, 228, 228];
pub(super) const INK: [u8; 3] = [40, 40, 40];

/// The colour of a contact state in both pictures.
pub(super) fn state_colour(s: ContactState) -> [u8; 3] {
    match s {
        ContactState::Stick => STICK,
        ContactState::Slip => SLIP,
        ContactState::Open => OPEN,
    }
}
