//! subcontact: contact between elastic bodies by the substructure interface
//! method (condense every body onto its contact interface once, iterate the
//! contact states on the small interface system).
//!
//! Data flows one way: [`mesh`] → [`fem`] (elements, assembly) →
//! [`substructure`] (condensation) → [`contact`] (pairs, frames, law,
//! iteration) → [`recover`] → [`output`]; [`driver`] strings the stages
//! together into a [`results::Run`], which the writers read, and [`scene`]
//! and [`cli`] turn user input into a validated run. [`analytic`] holds the
//! closed forms and the checks a scene's `[analytic]` asks for.

pub mod analytic;
pub mod bench;
pub mod cli;
pub mod commands;
pub mod contact;
pub mod driver;
pub mod error;
pub mod fem;
pub mod memory;
pub mod mesh;
pub mod model;
pub mod output;
pub mod parallel;
pub mod recover;
pub mod results;
pub mod scene;
pub mod substructure;
#[cfg(test)]
mod test_rng;

pub use error::{Error, Result};
