//! The library's error ([`Error`]): what a run, `check`, `bench` or `paper`
//! ends with when it fails. Each stage keeps its own typed error (the
//! scene's, the mesh's, the model's, the contact iteration's, the result
//! files', ...), which comes through whole as a variant; the variants of
//! their own say what the driver adds: which file it was reading or
//! writing. The stages' errors about the scene (the model's, the memory
//! check's) do not name its file: the driver adds it once, at the end of a
//! run ([`Error::in_scene`]). `Display` is the one paragraph a user reads, its source
//! included (`context: source`), so a caller that prints the chain of
//! sources leaves out the causes the message already quotes.
//!
//! Between MPI ranks an error travels as [`Wire`]: the variants that are
//! plain data (the model's, the contact iteration's, the memory check's,
//! ...) arrive as the same variant; those that hold an operating-system
//! error (reading and writing files, running gmsh: rank 0's work) arrive
//! as their message, [`Error::Remote`].

use std::path::{Path, PathBuf};

use crate::driver::messages::{ContactError, PlanError, SafetyError};
use crate::fem::sparse::FactorError;
use crate::memory::TooLarge;
use crate::mesh::gmsh::GmshError;
use crate::mesh::joints::JointError;
use crate::mesh::msh::MshError;
use crate::model::ModelError;
use crate::output::files::OutputError;
use crate::output::picture::PictureError;
use crate::output::plot::PlotError;
use crate::scene::SceneError;

/// A result of the library's surface.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// Why a run (or `check`, `bench`, `paper`) failed.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    #[error(transparent)]
    Scene(#[from] SceneError),
    #[error(transparent)]
    Mesh(#[from] MshError),
    #[error(transparent)]
    Gmsh(#[from] GmshError),
    /// A `[[joints]]` key of the scene the cutter cannot follow.
    #[error(transparent)]
    Joint(Box<JointError>),
    /// gmsh meshed the .geo `geo` into nothing a run can use: the .geo
    /// names no physical group with elements.
    #[error("gmsh made no mesh of `{}`: the .geo defines no physical groups with elements to mesh. Define the bodies, contacts, supports and loads with Physical Surface/Volume/Curve/Point in the .geo", geo.display())]
    NoMesh { geo: PathBuf },
    /// The mesh gmsh made of `geo` is not one a run can read.
    #[error("the mesh gmsh made of `{}`: {source}", geo.display())]
    BadMesh {
        geo: PathBuf,
        #[source]
        source: MshError,
    },
    /// The mesh gmsh made of `geo` could not be read back.
    #[error("reading the mesh gmsh made of {}: {source}", geo.display())]
    ReadMesh {
        geo: PathBuf,
        #[source]
        source: std::io::Error,
    },
    /// A .geo scene meshed with no result directory to mesh into (a
    /// caller's mistake).
    #[error("a .geo scene is meshed into a result directory")]
    NoStage,
    /// Rank 0 meshed the scene but said nowhere to read the mesh (a bug).
    #[error("rank 0 sent no mesh to read")]
    NoMeshSent,
    #[error(transparent)]
    Model(Box<ModelError>),
    #[error(transparent)]
    Plan(#[from] PlanError),
    #[error(transparent)]
    Memory(#[from] TooLarge),
    #[error(transparent)]
    Factor(#[from] FactorError),
    #[error(transparent)]
    Contact(Box<ContactError>),
    #[error(transparent)]
    Safety(Box<SafetyError>),
    /// Results that are not finite numbers (an overflow), at load step
    /// `step`: `what` and where.
    #[error("the results are not finite numbers at load step {step}: {what}. The loads or prescribed displacements are too large for double precision (stresses above ~1e154 overflow the von Mises stress): give them in other units (kN or MPa instead of N or Pa). No result files were written")]
    NotFinite { step: usize, what: String },
    /// summary.json could not be encoded.
    #[error(transparent)]
    Summary(#[from] serde_json::Error),
    #[error(transparent)]
    Output(#[from] OutputError),
    #[error(transparent)]
    Picture(#[from] PictureError),
    /// The result files of a run could not be written into `out`.
    #[error("writing results to {}: {source}", out.display())]
    Results {
        out: PathBuf,
        #[source]
        source: OutputError,
    },
    /// A file the command reads, `path`, could not be.
    #[error("reading {}: {source}", path.display())]
    Read {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    /// A file the command writes, `path`, could not be.
    #[error("writing {}: {source}", path.display())]
    Write {
        path: PathBuf,
        #[source]
        source: OutputError,
    },
    /// `bench` options out of their range.
    #[error("bench: --orders takes 1 and/or 2, --levels at least 1, --ratio above 1")]
    BenchOptions,
    /// `bench` refines the mesh with gmsh: the scene `scene` must mesh a .geo.
    #[error("{}: bench needs `mesh = \"<file>.geo\"` so that gmsh can refine it", scene.display())]
    BenchNeedsGeo { scene: PathBuf },
    /// A plot, `file`, could not be drawn.
    #[error("drawing {file}: {source}")]
    Drawing {
        file: &'static str,
        #[source]
        source: PlotError,
    },
    /// An error of the run with joints that deform, `normal` and `shear`
    /// on every contact, that a run whose rigid joints did not converge
    /// fell back to (`[solver] rigid_fallback`; see [`Error::in_fallback`]).
    #[error("{source} (in the run with joints that deform, normal_stiffness = {normal} and shear_stiffness = {shear} on every contact, that this run fell back to when its rigid joints did not converge; [solver] rigid_fallback = false stops with the rigid joints' last iterate instead)")]
    InFallback { source: Box<Error>, normal: f64, shear: f64 },
    /// An error about the scene `scene` (see [`Error::in_scene`]),
    /// with the scene's file name in front.
    #[error("{}: {source}", scene.display())]
    InScene { scene: PathBuf, source: Box<Error> },
    /// The error of another MPI rank, `rank`, that travels only as its
    /// message (it holds an operating-system error).
    #[error("{message}")]
    Remote { rank: usize, message: String },
}

/// The errors large enough to be boxed (an error is rare, a `Result` of
/// every stage carries its size).
macro_rules! boxed {
    ($($variant:ident($error:ty)),*) => {$(
        impl From<$error> for Error {
            fn from(e: $error) -> Error {
                Error::$variant(Box::new(e))
            }
        }
    )*};
}

boxed!(Model(ModelError), Contact(ContactError), Safety(SafetyError));

/// An [`Error`] as it travels between MPI ranks.
#[derive(Debug, serde::Serialize, serde::Deserialize)]
pub enum Wire {
    Model(ModelError),
    Plan(PlanError),
    Memory(TooLarge),
    Factor(FactorError),
    Contact(ContactError),
    Safety(SafetyError),
    NotFinite {
        step: usize,
        what: String,
    },
    /// Any other error, of rank `rank`, as its message.
    Message {
        rank: usize,
        message: String,
    },
}

impl Error {
    /// The error with the file context of the scene `scene` when it is
    /// about the scene and does not name it: the model's errors about the
    /// input, the memory check's, the plan's, the contact iteration's, the
    /// safety search's, results that are not numbers and the joints' keys.
    /// Others come back as they were.
    pub fn in_scene(self, scene: &Path) -> Error {
        match self {
            Error::Model(ref m) if !m.about_input() => self,
            Error::Model(_)
            | Error::Memory(_)
            | Error::Plan(_)
            | Error::Contact(_)
            | Error::Safety(_)
            | Error::NotFinite { .. }
            | Error::InFallback { .. }
            | Error::Joint(_) => Error::InScene { scene: scene.to_path_buf(), source: Box::new(self) },
            e => e,
        }
    }

    /// The error without the scene's file context ([`Error::in_scene`]):
    /// the variant a caller matches.
    pub fn without_scene(self) -> Error {
        match self {
            Error::InScene { source, .. } => source.without_scene(),
            Error::InFallback { source, .. } => *source,
            e => e,
        }
    }

    /// The error of the run with joints that deform, stiffness `k`, that
    /// rigid joints which did not converge fell back to, saying so; a
    /// step that does not converge says it itself
    /// (`ContactError::NotConverged`'s `fell_back`).
    pub fn in_fallback(self, k: crate::contact::law::Stiffness) -> Error {
        match self {
            Error::Contact(ref c) if matches!(**c, ContactError::NotConverged { .. }) => self,
            e => Error::InFallback { source: Box::new(e), normal: k.normal, shear: k.shear },
        }
    }

    /// The error to send from rank `rank` to the others.
    pub fn to_wire(&self, rank: usize) -> Wire {
        match self {
            Error::Model(e) => Wire::Model(e.as_ref().clone()),
            Error::Plan(e) => Wire::Plan(e.clone()),
            Error::Memory(e) => Wire::Memory(e.clone()),
            Error::Factor(e) => Wire::Factor(e.clone()),
            Error::Contact(e) => Wire::Contact(e.as_ref().clone()),
            Error::Safety(e) => Wire::Safety(e.as_ref().clone()),
            Error::NotFinite { step, what } => Wire::NotFinite { step: *step, what: what.clone() },
            Error::Remote { rank, message } => Wire::Message { rank: *rank, message: message.clone() },
            e => Wire::Message { rank, message: e.to_string() },
        }
    }
}

impl From<Wire> for Error {
    fn from(w: Wire) -> Error {
        match w {
            Wire::Model(e) => e.into(),
            Wire::Plan(e) => Error::Plan(e),
            Wire::Memory(e) => Error::Memory(e),
            Wire::Factor(e) => Error::Factor(e),
            Wire::Contact(e) => e.into(),
            Wire::Safety(e) => e.into(),
            Wire::NotFinite { step, what } => Error::NotFinite { step, what },
            Wire::Message { rank, message } => Error::Remote { rank, message },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::driver::messages::At;

    /// The error after a trip through the bytes that go between ranks.
    fn sent(e: &Error) -> Error {
        let bytes = bincode::serialize(&e.to_wire(2)).expect("encodes");
        bincode::deserialize::<Wire>(&bytes).expect("decodes").into()
    }

    #[test]
    fn an_error_of_the_fallback_says_so_and_a_step_that_did_not_converge_keeps_its_own() {
        let k = crate::contact::law::Stiffness { normal: 13880.0, shear: 1388.0 };
        let at = At { step: Some(1), iteration: 22, states: [39, 329, 516], rounds: None };
        let held = ContactError::NotHeld { at, bodies: vec!["rock #9".into()], places: vec![None], apex: vec![] };
        let e = Error::from(held.clone()).in_fallback(k).in_scene(Path::new("tunnel.toml"));
        let text = e.to_string();
        assert!(text.starts_with("tunnel.toml: body \"rock #9\" is held by nothing"), "{text}");
        assert!(
            text.contains("(in the run with joints that deform, normal_stiffness = 13880 and shear_stiffness = 1388 on every contact, that this run fell back to"),
            "{text}"
        );
        assert!(matches!(e.without_scene(), Error::Contact(c) if *c == held));
        let not_converged = ContactError::NotConverged {
            step: Some(1),
            iterations: 20,
            stop: crate::contact::Stop::MaxIterations,
            slipping_back: 0,
            rigid_joints: None,
            fell_back: true,
            cuts: 0,
            scaled: false,
            rule: crate::scene::StateRule::Robust,
            results: None,
        };
        let e = Error::from(not_converged.clone()).in_fallback(k);
        assert!(matches!(e, Error::Contact(ref c) if **c == not_converged), "{e}");
    }

    #[test]
    fn plain_data_errors_travel_as_the_same_variant_with_the_same_text() {
        let at = At { step: Some(2), iteration: 7, states: [1, 2, 3], rounds: Some([4, 31]) };
        let contact = ContactError::NotHeld { at, bodies: vec!["block".into()], places: vec![None], apex: vec![] };
        let e: Error = contact.clone().into();
        let in_scene = Error::from(contact.clone()).in_scene(Path::new("dam.toml"));
        assert!(in_scene.to_string().starts_with("dam.toml: body \"block\" is held by nothing at"), "{in_scene}");
        let rounds =
            "contact iteration 7 (3 stick, 2 slip, 1 open; 31 of the iterations in 4 augmented Lagrangian round(s))";
        assert!(in_scene.to_string().contains(rounds), "{in_scene}");
        assert!(matches!(in_scene.without_scene(), Error::Contact(c) if *c == contact));
        let back = sent(&e);
        assert!(matches!(&back, Error::Contact(c) if **c == contact), "{back:?}");
        assert_eq!(back.to_string(), e.to_string());

        let folded =
            ModelError::Folded { body: "b".into(), tag: 12, kind: "tet10".into(), node: Some(3), det_j: -1e-3 };
        let e: Error = folded.into();
        let back = sent(&e);
        assert!(
            matches!(&back, Error::Model(m) if matches!(**m, ModelError::Folded { tag: 12, node: Some(3), .. })),
            "{back:?}"
        );
        assert_eq!(back.to_string(), e.to_string());

        let e: Error = PlanError::TooManyRanks { ranks: 4, parts: 2, substructures: 1 }.into();
        assert!(matches!(sent(&e), Error::Plan(PlanError::TooManyRanks { ranks: 4, parts: 2, .. })));
        assert!(matches!(
            sent(&FactorError::NotPositiveDefinite.into()),
            Error::Factor(FactorError::NotPositiveDefinite)
        ));
    }

    #[test]
    fn an_error_holding_an_os_error_travels_as_its_text() {
        let source = std::io::Error::from_raw_os_error(13);
        let e: Error = SceneError::Read { path: "s.toml".into(), source }.into();
        let back = sent(&e);
        assert!(matches!(&back, Error::Remote { rank: 2, message } if *message == e.to_string()), "{back:?}");
        // and travels on as it came
        assert!(matches!(sent(&back), Error::Remote { rank: 2, .. }));
    }

    #[test]
    fn the_scene_is_named_once_in_front_of_the_errors_about_it() {
        let scene = Path::new("geo/dam.toml");
        let weightless = ModelError::Weightless { key: "bodies[0].k0".into(), body: "rock".into() };
        let e = Error::from(weightless.clone()).in_scene(scene);
        assert!(
            matches!(&e, Error::InScene { source, .. } if matches!(&**source, Error::Model(m) if matches!(**m, ModelError::Weightless { .. }))),
            "{e:?}"
        );
        assert_eq!(e.to_string(), format!("geo/dam.toml: {weightless}"));
        assert!(e
            .to_string()
            .starts_with("geo/dam.toml: bodies[0].k0: a geostatic initial stress needs the weight of body \"rock\""));
        // the mesh's own faults name the element, not the scene
        let folded = ModelError::Folded { body: "b".into(), tag: 12, kind: "tet10".into(), node: None, det_j: -1e-3 };
        let e = Error::from(folded).in_scene(scene);
        assert!(matches!(&e, Error::Model(_)) && e.to_string().starts_with("element 12 (tet10) of body b"), "{e}");
        // errors that name their own file are left as they were
        let e = Error::NoMesh { geo: "x.geo".into() }.in_scene(scene);
        assert!(matches!(e, Error::NoMesh { .. }));
    }

    #[test]
    fn a_context_variant_says_the_context_then_its_source() {
        let source = std::io::Error::from_raw_os_error(2);
        let e = Error::Read { path: "results/x/report.md".into(), source };
        assert_eq!(e.to_string(), "reading results/x/report.md: No such file or directory (os error 2)");
        assert_eq!(
            std::error::Error::source(&e).map(|s| s.to_string()).as_deref(),
            Some("No such file or directory (os error 2)")
        );
    }
}
