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

mod colours;
mod cutaway;
mod deformed;
mod field;
mod framing;
mod interfaces;
mod joints;
mod label_numbers;
mod legend;
mod picture_error;
mod plan;
mod raster;
mod sheets;
mod snapshot;
mod stereonet;
mod surface;
#[cfg(test)]
mod tests;
mod view;

pub use deformed::{deformed_png, mechanism_png};
pub use field::Field;
pub use interfaces::interface_plot_svg;
pub use joints::{joints_file, joints_png};
pub use picture_error::PictureError;
pub use plan::{plan_files, plan_png, plan_pngs, PlanFile};
pub use snapshot::Snapshot;
pub use stereonet::{stereonet_file, stereonet_png};

use crate::model::Model;
use crate::recover::BodyStress;

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
    let deformed = || deformed_png(snap, field, None);
    let Some(c) = snap.contact.filter(|_| !snap.model.interfaces.is_empty()) else {
        d.draw(deformed_file(snap.stresses), deformed);
        return d;
    };
    let plans = d.plans(snap.model);
    // the plan views' second half and the joints' picture in a thread of
    // their own, in the order they are listed (the 86k tunnel's 19 plan
    // views took 0.37 s of its pictures' 0.64, all in one thread)
    let (first, second) = plans.split_at(plans.len() / 2);
    let rest = std::thread::scope(|scope| {
        let rest = scope.spawn(|| {
            let mut r = Drawn::default();
            for p in second {
                r.draw(&p.file, || plan_png(snap.title, snap.model, c, p));
            }
            if let Some(f) = joints_file(&plans) {
                r.draw(f, || joints_png(snap.title, snap.model, c, &plans));
            }
            r
        });
        d.draw(deformed_file(snap.stresses), deformed);
        d.draw("interfaces.svg", || Ok(interface_plot_svg(snap.model, c)?.into_bytes()));
        for p in first {
            d.draw(&p.file, || plan_png(snap.title, snap.model, c, p));
        }
        rest.join().unwrap_or_else(|e| std::panic::resume_unwind(e))
    });
    d.files.extend(rest.files);
    d.skipped.extend(rest.skipped);
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

thread_local! {
    /// The message of a panic on this thread while [`quietly`] runs there;
    /// None elsewhere (a panic is then printed as usual).
    static SAID: std::cell::RefCell<Option<String>> = const { std::cell::RefCell::new(None) };
}

/// Runs `f`, turning a panic into its message (and place) instead of
/// printing it: the caller reports it as a warning. Threads may draw at
/// once: the panic hook, set once, keeps a message on the thread that
/// panicked (a hook swapped per call, as before, could be restored by one
/// thread while another's was in place, and silence every later panic).
fn quietly<T>(f: impl FnOnce() -> T) -> Result<T, Panicked> {
    static HOOK: std::sync::Once = std::sync::Once::new();
    HOOK.call_once(|| {
        let usual = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            let kept = SAID.with(|s| s.borrow_mut().as_mut().map(|said| *said = info.to_string().replace('\n', " ")));
            if kept.is_none() {
                usual(info);
            }
        }));
    });
    let outer = SAID.with(|s| s.replace(Some(String::new())));
    let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(f));
    let said = SAID.with(|s| s.replace(outer)).unwrap_or_default();
    r.map_err(|_| Panicked { said })
}
