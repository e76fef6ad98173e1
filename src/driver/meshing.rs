//! Step 1 of a run: the scene's mesh, read from its .msh or made by gmsh
//! from its .geo (or taken from the result directory's mesh cache).

use std::path::{Path, PathBuf};

use super::progress::say;
use crate::error::{Error, Result};
use crate::mesh::{gmsh, msh, Mesh};
use crate::output;
use crate::output::files::{Stage, Staged};
use crate::scene::{MeshSource, Scene};

/// Reads the mesh of a scene, running gmsh when it is a .geo: into the
/// result directory `out`'s mesh cache, committed alone (`check`).
pub fn load_mesh(scene: &Scene, out: &Path, allow_geo_commands: bool) -> Result<(Mesh, PathBuf, bool)> {
    let mut stage = match scene.mesh {
        MeshSource::Msh(_) => None,
        MeshSource::Geo(_) => Some(Stage::begin(out, &mut |m| say(m))?),
    };
    let meshed = mesh_into(scene, stage.as_mut(), allow_geo_commands)?;
    if let Some(stage) = stage {
        stage.commit(Staged::amend(out, &scene.name), &mut |m| say(m))?;
    }
    Ok(meshed)
}

/// The gmsh job of a scene whose mesh is a .geo, its mesh at `msh`.
pub fn gmsh_job(scene: &Scene, geo: &Path, msh: PathBuf, allow_geo_commands: bool) -> gmsh::GmshJob {
    gmsh::GmshJob {
        geo: geo.to_path_buf(),
        msh,
        dim: scene.analysis.dim(),
        order: scene.gmsh.order,
        setnumber: scene.gmsh.setnumber.clone(),
        clscale: scene.gmsh.clscale,
        timeout: std::time::Duration::from_secs_f64(scene.gmsh.timeout),
        allow_commands: allow_geo_commands,
        cut: scene.cut_job(),
    }
}

/// Reads the mesh of a scene: the .msh, or, for a .geo, the cached mesh
/// of the result directory when its key matches, else gmsh's, made in
/// `stage` (the run's staging directory: committed with the results).
/// The mesh, its path in the result directory, and whether it was cached.
pub fn mesh_into(scene: &Scene, stage: Option<&mut Stage>, allow_geo_commands: bool) -> Result<(Mesh, PathBuf, bool)> {
    let (MeshSource::Geo(geo), Some(stage)) = (&scene.mesh, stage) else {
        let MeshSource::Msh(p) = &scene.mesh else { return Err(Error::NoStage) };
        return Ok((msh::read_msh(p)?, p.clone(), false));
    };
    let file = format!("{}.msh", scene.name);
    let shown = stage.out().join(output::files::MESH_DIR).join(&file);
    let job = gmsh_job(scene, geo, shown.clone(), allow_geo_commands);
    let key = gmsh::cache_key(&job)?;
    let cached = stage.reuse_mesh(&file, &key);
    if !cached {
        gmsh::run_in(&job, stage.mesh_dir()?.fd()).map_err(|e| match e {
            gmsh::GmshError::Joints(j) if j.is_about_scene() => Error::Joint(Box::new(j)).in_scene(&scene.path),
            e => e.into(),
        })?;
        stage.keep_mesh(&file, &key)?;
    }
    let rel = format!("{}/{file}", output::files::MESH_DIR);
    let bytes = stage.read(&rel).map_err(|source| Error::ReadMesh { geo: geo.clone(), source })?;
    let mesh = msh::parse_msh(&shown, &bytes).map_err(|e| no_mesh(geo, e))?;
    Ok((mesh, shown, cached))
}

/// A mesh gmsh made of a .geo that cannot be used: the .geo is to blame.
fn no_mesh(geo: &Path, e: msh::MshError) -> Error {
    match e {
        msh::MshError::NoPhysicalGroups { .. } | msh::MshError::Malformed { .. } => {
            Error::NoMesh { geo: geo.to_path_buf() }
        }
        source => Error::BadMesh { geo: geo.to_path_buf(), source },
    }
}
