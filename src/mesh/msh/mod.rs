//! Reading gmsh MSH 4.1 files (ASCII and binary) into a [`Mesh`].
//!
//! The reader is our own small parser of the sections we need —
//! `$MeshFormat`, `$PhysicalNames`, `$Entities`, `$Nodes`, `$Elements` —
//! and skips every other section. (mshio 0.4.2 was the first choice, but it
//! forgets node tags whenever the tags of the whole file are contiguous, with no
//! way to tell which tag a node had; it does not read `$PhysicalNames`; and it
//! miscounts the nodes of order-2 prisms, so such files fail as if garbled. The
//! tests use mshio as an independent check of this reader.)
//!
//! Nodes are kept in file order; cells refer to them by 0-based index. Each
//! physical group becomes one [`Group`](super::Group): every element of every entity of the
//! group's dimension that carries the group's physical tag. An entity with
//! several physical tags gives its cells to each of those groups. A group named
//! in `$PhysicalNames` that no entity carries (gmsh 4.8.4 writes one, without a
//! word, for `Physical Surface("x") = {99};` when surface 99 does not exist) is
//! kept with no cells. Groups come sorted by dimension, then tag. gmsh saves only
//! elements of physical groups (when there is at least one), but it saves the
//! nodes of every entity, so not every node is used by a group.
//!
//! Every failure is an [`MshError`] whose message names the file and says what
//! to do; no byte input makes the reader panic, and no count read from the file
//! is trusted for an allocation beyond what the file's length can hold.
//!
//! Here: [`read_msh`], the section dispatcher and the errors. The cursor that
//! reads one value in ASCII or binary form is in `reader.rs` (the only place
//! the two encodings differ: every section is read by the same code in both,
//! so there is no ASCII reader and binary reader to keep in step), the
//! sections themselves in `sections.rs`, and the step from tags to indices
//! and physical groups in `groups.rs`.

mod groups;
mod msh_error;
mod reader;
mod sections;
#[cfg(test)]
mod tests;

use std::collections::HashMap;
use std::path::Path;

use crate::mesh::cells::Mesh;
use groups::build_mesh;
pub use msh_error::MshError;
use reader::Reader;
use sections::{read_elements, read_entities, read_header, read_nodes, read_physical_names, Block};

/// The largest coordinate a mesh may have: beyond it, the squares and
/// cubes of lengths (areas, volumes, stiffnesses) leave double precision.
pub const MAX_COORDINATE: f64 = 1e100;

/// Reads an MSH 4.1 file (ASCII or binary) written by gmsh.
pub fn read_msh(path: &Path) -> Result<Mesh, MshError> {
    let bytes = match std::fs::read(path) {
        Ok(b) => b,
        Err(e) if e.kind() == std::io::ErrorKind::IsADirectory => {
            return Err(MshError::Io {
                path: path.to_path_buf(),
                source: std::io::Error::other(
                    "it is a directory, not a mesh file; point `mesh =` in the scene at the .msh file",
                ),
            })
        }
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            return Err(MshError::NotFound { path: path.to_path_buf() })
        }
        Err(e) => return Err(MshError::Io { path: path.to_path_buf(), source: e }),
    };
    parse_msh(path, &bytes)
}

/// Parses the bytes of an MSH file; `path` is only used in messages.
pub fn parse_msh(path: &Path, bytes: &[u8]) -> Result<Mesh, MshError> {
    let mut r = Reader::new(path, bytes);
    if bytes.iter().all(|b| b.is_ascii_whitespace()) {
        return Err(r.malformed("the file is empty"));
    }
    // 1. the header
    read_header(&mut r)?;
    // 2. the sections, in the file's order
    let mut read = Sections::default();
    while let Some(name) = next_section(&mut r)? {
        read.section(&mut r, &name)?;
    }
    // 3. nodes and elements there, every coordinate in range
    let Some((coords, node_tags)) = read.nodes else {
        return Err(r.malformed("no $Nodes section"));
    };
    let Some(blocks) = read.blocks else {
        return Err(r.malformed("no $Elements section"));
    };
    let entities = read.entities.unwrap_or_default();
    if let Some((i, x)) = coords.iter().enumerate().find(|(_, x)| x.iter().any(|v| !(v.abs() <= MAX_COORDINATE))) {
        return Err(MshError::NotFinite {
            path: path.to_path_buf(),
            node: node_tags.get(i).copied().unwrap_or(i as u64 + 1),
            x: *x,
        });
    }
    // 4. the mesh, its cells grouped by physical group
    build_mesh(path, coords, node_tags, &read.names, &entities, blocks)
}

/// The name of the next section (`Nodes` of `$Nodes`), or None at the end
/// of the file.
fn next_section(r: &mut Reader<'_>) -> Result<Option<String>, MshError> {
    r.section = "";
    r.skip_ws();
    if r.at_end() {
        return Ok(None);
    }
    let line = r.line();
    match line.trim_ascii().strip_prefix(b"$") {
        Some(n) if !n.is_empty() && !n.starts_with(b"End") => Ok(Some(String::from_utf8_lossy(n).into_owned())),
        _ => Err(r.malformed("expected the start of a section such as `$Nodes`")),
    }
}

/// The sections read so far.
#[derive(Default)]
struct Sections {
    names: Vec<(i32, i32, String)>,
    /// (dim, entity tag) -> physical tags
    entities: Option<HashMap<(i32, i32), Vec<i32>>>,
    nodes: Option<(Vec<[f64; 3]>, Vec<u64>)>,
    blocks: Option<Vec<Block>>,
}

impl Sections {
    /// Reads section `name` up to its end marker; an unknown one is
    /// skipped, a repeated or misplaced one is an error.
    fn section(&mut self, r: &mut Reader<'_>, name: &str) -> Result<(), MshError> {
        match name {
            "PhysicalNames" => {
                r.section = "PhysicalNames";
                self.names = read_physical_names(r)?;
                r.end_section("PhysicalNames")?;
            }
            "Entities" => {
                r.section = "Entities";
                if self.entities.is_some() {
                    return Err(r.malformed("a second $Entities section"));
                }
                if self.blocks.is_some() {
                    return Err(r.malformed("$Entities after $Elements"));
                }
                self.entities = Some(read_entities(r)?);
                r.end_section("Entities")?;
            }
            "PartitionedEntities" => {
                return Err(MshError::Partitioned { path: r.path.to_path_buf() });
            }
            "Nodes" => {
                r.section = "Nodes";
                if self.nodes.is_some() {
                    return Err(r.malformed("a second $Nodes section"));
                }
                self.nodes = Some(read_nodes(r)?);
                r.end_section("Nodes")?;
            }
            "Elements" => {
                r.section = "Elements";
                if self.blocks.is_some() {
                    return Err(r.malformed("a second $Elements section"));
                }
                let empty = HashMap::new();
                let ents = self.entities.as_ref().unwrap_or(&empty);
                self.blocks = Some(read_elements(r, ents, &self.names)?);
                r.end_section("Elements")?;
            }
            other => skip_section(r, other)?,
        }
        Ok(())
    }
}

/// Skips an unknown section up to its end marker.
fn skip_section(r: &mut Reader<'_>, name: &str) -> Result<(), MshError> {
    let marker = format!("$End{name}");
    match find(&r.buf[r.pos..], marker.as_bytes()) {
        Some(at) => {
            r.pos += at;
            r.end_section(name)
        }
        None => Err(r.malformed(format!("no `{marker}` after `${name}`"))),
    }
}

/// Where `needle` first occurs in `haystack`.
fn find(haystack: &[u8], needle: &[u8]) -> Option<usize> {
    if needle.is_empty() || haystack.len() < needle.len() {
        return None;
    }
    haystack.windows(needle.len()).position(|w| w == needle)
}
