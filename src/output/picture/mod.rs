//! Pictures of a run, for a person to look at rather than read: the deformed
//! model coloured by a field, with the contact states drawn on the interfaces
//! (PNG, [`deformed`]), the contact stresses along each interface (SVG,
//! [`interfaces`]) and, in 3D, each contact surface laid flat (PNG, one per
//! plane or unrolled surface, [`plan`]) and all of them together by state
//! (PNG, [`joints`]); with joints by orientation, their stereonet (PNG,
//! [`stereonet`]). This file chooses which pictures a run gets and holds
//! what they share: the field names, the state colours, number formats and
//! the error type.
//!
//! The pictures are rasterised by this module itself ([`raster`]: filled
//! triangles, anti-aliased lines, plotters only for the text in the
//! embedded DejaVu Sans) and encoded by the `png` crate, so no external
//! program is needed. [`surface`] cuts the mesh into the patches it fills,
//! [`sheets`] cuts a 3D interface into planes and unrolled surfaces,
//! [`framing`] chooses the region the deformed picture frames, [`view`] the
//! oblique view of 3D models, and [`legend`] draws the colour bars and the
//! contact legend beside it.
//!
//! Displacements are magnified by `m = 0.05 L / max|u|` (L the drawn
//! region's largest extent) unless a scale is given; the title states `m`.
//! Colours: viridis for magnitudes, blue (compression) to red (tension)
//! through grey for stress components; stick green, slip orange, open red.

mod cutaway;
mod deformed;
mod framing;
mod interfaces;
mod joints;
mod legend;
mod plan;
mod raster;
mod sheets;
mod stereonet;
mod surface;
#[cfg(test)]
mod tests;
mod view;

pub use deformed::{deformed_png, mechanism_png};
pub use interfaces::interface_plot_svg;
pub use joints::{joints_file, joints_png};
pub use plan::{plan_files, plan_png, plan_pngs, PlanFile};
pub use stereonet::{stereonet_file, stereonet_png};

use crate::contact::law::ContactState;
use crate::fem::Analysis;
use crate::model::Model;
use crate::recover::BodyStress;
use crate::results::ContactRun;
use crate::scene::Region;

/// Why a picture could not be drawn.
#[derive(Debug, thiserror::Error)]
pub enum PictureError {
    /// The results handed over do not belong to the model (a caller's bug).
    #[error("the run's {what} do not match its model")]
    Mismatch { what: &'static str },
    /// Nothing to draw.
    #[error("{0}")]
    Empty(String),
    #[error("the embedded font has no readable metrics")]
    Font,
    #[error("writing \"{text}\" on the picture: {reason}")]
    Text { text: String, reason: String },
    #[error("encoding the PNG: {0}")]
    Png(#[from] png::EncodingError),
    #[error("drawing the interface plot: {0}")]
    Plot(#[from] crate::output::plot::PlotError),
}

/// The quantity that colours the deformed picture.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Field {
    VonMises,
    /// Magnitude of the displacement.
    Displacement,
    Sxx,
    Syy,
    Szz,
    Sxy,
    Syz,
    Sxz,
}

impl Field {
    pub const ALL: [Field; 8] =
        [Field::VonMises, Field::Displacement, Field::Sxx, Field::Syy, Field::Szz, Field::Sxy, Field::Syz, Field::Sxz];

    /// Spelling for file names and command lines (`von_mises`, `sxx`, ...).
    pub fn key(self) -> &'static str {
        match self {
            Field::VonMises => "von_mises",
            Field::Displacement => "displacement",
            Field::Sxx => "sxx",
            Field::Syy => "syy",
            Field::Szz => "szz",
            Field::Sxy => "sxy",
            Field::Syz => "syz",
            Field::Sxz => "sxz",
        }
    }

    pub fn parse(s: &str) -> Option<Field> {
        Field::ALL.into_iter().find(|f| f.key() == s)
    }

    /// Name for a reader; axisymmetric models have x = r and y = z (the axis).
    pub fn label(self, analysis: Analysis) -> &'static str {
        let axi = analysis == Analysis::Axisymmetric;
        match self {
            Field::VonMises => "von Mises stress",
            Field::Displacement => "displacement |u|",
            Field::Sxx if axi => "σrr (radial stress)",
            Field::Syy if axi => "σzz (axial stress)",
            Field::Szz if axi => "σθθ (hoop stress)",
            Field::Sxy if axi => "σrz (shear stress)",
            Field::Sxx => "σxx (normal stress)",
            Field::Syy => "σyy (normal stress)",
            Field::Szz => "σzz (normal stress)",
            Field::Sxy => "σxy (shear stress)",
            Field::Syz => "σyz (shear stress)",
            Field::Sxz => "σxz (shear stress)",
        }
    }

    /// Index in the stress vector `[xx, yy, zz, xy, yz, xz]`.
    fn component(self) -> Option<usize> {
        match self {
            Field::VonMises | Field::Displacement => None,
            Field::Sxx => Some(0),
            Field::Syy => Some(1),
            Field::Szz => Some(2),
            Field::Sxy => Some(3),
            Field::Syz => Some(4),
            Field::Sxz => Some(5),
        }
    }
}

/// One state of a model to draw: its displacements, nodal stresses (empty
/// when they were not recovered) and contact states and stresses, and the
/// region the scene asks the deformed picture to frame.
pub struct Snapshot<'a> {
    /// The picture's title.
    pub title: &'a str,
    pub model: &'a Model,
    pub u: &'a [f64],
    pub stresses: &'a [BodyStress],
    pub contact: Option<&'a ContactRun>,
    pub region: Option<&'a Region>,
    /// One colour scale for every body (`[output] colour_scale = "one"`).
    pub one_scale: bool,
}

/// The file name of the deformed picture of [`pictures`]: coloured by von
/// Mises stress when stresses were recovered, else by the displacement.
pub fn deformed_file(stresses: &[BodyStress]) -> &'static str {
    if stresses.is_empty() {
        "deformed_displacement.png"
    } else {
        "deformed_von_mises.png"
    }
}

/// The pictures of a snapshot under their file names: the deformed model
/// coloured by von Mises stress (or the displacement magnitude), and with
/// contact the interface stresses and, in 3D, each sheet of each interface
/// laid flat ([`plan_files`]) and, when there are several, all of them by
/// state ([`joints_file`]). A picture that cannot be drawn is left out
/// with a warning ([`Drawn`]).
pub fn pictures(snap: &Snapshot) -> Drawn {
    let field = if snap.stresses.is_empty() { Field::Displacement } else { Field::VonMises };
    let mut d = Drawn::default();
    d.draw(deformed_file(snap.stresses), || deformed_png(snap, field, None));
    if let Some(c) = snap.contact.filter(|_| !snap.model.interfaces.is_empty()) {
        d.draw("interfaces.svg", || Ok(interface_plot_svg(snap.model, c)?.into_bytes()));
        let plans = d.plans(snap.model);
        for p in &plans {
            d.draw(&p.file, || plan_png(snap.title, snap.model, c, p));
        }
        if let Some(f) = joints_file(&plans) {
            d.draw(f, || joints_png(snap.title, snap.model, c, &plans));
        }
    }
    d
}

/// Pictures drawn, and why any was not: a picture is the least important
/// output, and one that fails (an error, or a panic in the drawing code)
/// is skipped with a warning while every other result file is written.
#[derive(Default)]
pub struct Drawn {
    /// (file name, bytes) of each picture drawn.
    pub files: Vec<(String, Vec<u8>)>,
    /// One warning per picture left out.
    pub skipped: Vec<String>,
}

impl Drawn {
    /// Draws picture `file` with `f`, or says why it could not.
    pub fn draw(&mut self, file: &str, f: impl FnOnce() -> Result<Vec<u8>, PictureError>) {
        match quietly(f) {
            Ok(Ok(bytes)) => self.files.push((file.to_string(), bytes)),
            Ok(Err(e)) => self.skipped.push(format!("{file} was not drawn: {e}; the other result files are written")),
            Err(why) => self.skipped.push(format!(
                "{file} was not drawn: the drawing code failed ({why}); the other result files are written. Please report it with the scene"
            )),
        }
    }

    /// The plan views of `model`'s interfaces (none, with a warning, when
    /// they cannot be laid out).
    pub fn plans(&mut self, model: &Model) -> Vec<PlanFile> {
        quietly(|| plan_files(model)).unwrap_or_else(|why| {
            self.skipped.push(format!("the plan views were not drawn: the drawing code failed ({why})"));
            Vec::new()
        })
    }
}

/// Drawing code that panicked: the panic's message and place, on one line.
#[derive(Debug, thiserror::Error)]
#[error("{said}")]
struct Panicked {
    said: String,
}

/// Runs `f`, turning a panic into its message (and place) instead of
/// printing it: the caller reports it as a warning.
fn quietly<T>(f: impl FnOnce() -> T) -> Result<T, Panicked> {
    use std::sync::{Arc, Mutex};
    let said: Arc<Mutex<String>> = Arc::default();
    let slot = Arc::clone(&said);
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        if let Ok(mut s) = slot.lock() {
            *s = info.to_string().replace('\n', " ");
        }
    }));
    let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(f));
    std::panic::set_hook(hook);
    r.map_err(|_| Panicked { said: said.lock().map(|s| s.clone()).unwrap_or_default() })
}

/// Colours: the contact states, pairs without a state, the undeformed
/// ghost, text and frames.
const STICK: [u8; 3] = [20, 170, 60];
const SLIP: [u8; 3] = [255, 140, 0];
const OPEN: [u8; 3] = [225, 20, 30];
const NO_PAIR: [u8; 3] = [120, 120, 120];
const GHOST: [u8; 3] = [228, 228, 228];
const INK: [u8; 3] = [40, 40, 40];

/// The colour of a contact state in both pictures.
fn state_colour(s: ContactState) -> [u8; 3] {
    match s {
        ContactState::Stick => STICK,
        ContactState::Slip => SLIP,
        ContactState::Open => OPEN,
    }
}

/// A number with four significant digits, scientific outside [1e-3, 1e5).
fn num(v: f64) -> String {
    if !v.is_finite() {
        return "n/a".into();
    }
    let a = v.abs();
    if a == 0.0 {
        return "0".into();
    }
    if (1e-3..1e5).contains(&a) {
        let decimals = (3 - a.log10().floor() as i32).clamp(0, 6) as usize;
        let s = format!("{v:.decimals$}");
        if s.contains('.') {
            return s.trim_end_matches('0').trim_end_matches('.').to_string();
        }
        return s;
    }
    format!("{v:.2e}")
}

/// A magnification with two significant digits.
fn sig2(v: f64) -> String {
    if (1.0..1e4).contains(&v) {
        // 9.6, not 96 × 0.1 = 9.600000000000001
        return crate::output::number::sig(v, 2);
    }
    if (0.01..1.0).contains(&v) {
        return num((v * 100.0).round() / 100.0);
    }
    format!("{v:.1e}")
}
