//! Why cutting the bodies by their joints failed.

use std::path::PathBuf;

use super::ffi::LoadError;

/// Why the joints could not be cut.
#[derive(Debug, thiserror::Error)]
pub enum JointError {
    #[error("the scene has joints, which the tool cuts with gmsh's library libgmsh.so.4.8 (Debian package libgmsh4.8, installed with the gmsh package: `apt-get install -y gmsh`, or `make deps`), but it could not be loaded: {why}")]
    Library { why: LoadError },

    #[error("gmsh failed on `{}` while cutting the joints: {detail}; fix the .geo (open it in the gmsh GUI to see the problem)", geo.display())]
    Gmsh { geo: PathBuf, detail: String },

    #[error("`{}` is not an OpenCASCADE model: the joints are cut by OpenCASCADE, so start the .geo with `SetFactory(\"OpenCASCADE\");` and build the bodies with it", geo.display())]
    NotOcc { geo: PathBuf },

    #[error("{key}.bodies: `{}` has no physical {what} \"{group}\"; name a body group of the .geo", geo.display())]
    NoBody { key: String, geo: PathBuf, what: &'static str, group: String },

    #[error("{key}: the joint name \"{name}\" is already a physical group of `{}`; the joint's faces become a contact group of that name, so give the joint another name", geo.display())]
    NameTaken { key: String, name: String, geo: PathBuf },

    #[error("{key} (\"{name}\", {label}) cuts nothing: {why}")]
    CutsNothing { key: String, name: String, label: String, why: String },

    #[error("the joints cut the bodies into {count} blocks, more than max_blocks = {max}: a mesh and a contact solve of that many blocks take long. Widen the spacing, limit sets with `bodies` or `extent`, or raise the top-level `max_blocks` to at least {count} if you mean it")]
    TooManyBlocks { count: usize, max: usize },

    #[error("cutting the joints into `{}` lost every entity of its physical group \"{group}\", which the cutter should have kept on the pieces: please report it with the .geo and the scene; meanwhile build the joints in the .geo and name them in [[contacts]]", geo.display())]
    LostGroup { geo: PathBuf, group: String },

    #[error("{what} `{}`: {source}", path.display())]
    Io {
        what: &'static str,
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
}

impl JointError {
    /// Whether the error is about a key of the scene (the caller names the
    /// scene file), rather than about gmsh, the .geo or a file.
    pub fn is_about_scene(&self) -> bool {
        matches!(
            self,
            JointError::NoBody { .. }
                | JointError::NameTaken { .. }
                | JointError::CutsNothing { .. }
                | JointError::TooManyBlocks { .. }
        )
    }
}
