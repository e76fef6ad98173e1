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
//! physical group becomes one [`Group`]: every element of every entity of the
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

use std::collections::{BTreeMap, HashMap};
use std::path::{Path, PathBuf};

use super::{Cell, CellKind, Group, Mesh};

/// Why a mesh file could not be read.
#[derive(Debug, thiserror::Error)]
pub enum MshError {
    #[error("mesh file `{}` does not exist: check `mesh =` in the scene", path.display())]
    NotFound { path: PathBuf },

    #[error("cannot read mesh file `{}`: {source}", path.display())]
    Io {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },

    #[error(
        "`{}` is not a complete MSH 4.1 file (truncated?): {detail}. Mesh the .geo again \
         with gmsh (-format msh41), or point `mesh =` in the scene at a complete file",
        path.display()
    )]
    Malformed { path: PathBuf, detail: String },

    #[error("`{}` is MSH {version}: re-export it with gmsh -format msh41", path.display())]
    Version { path: PathBuf, version: String },

    #[error(
        "`{}` has no physical groups: add Physical Surface/Volume/Curve to the .geo, \
         gmsh saves only elements of physical groups",
        path.display()
    )]
    NoPhysicalGroups { path: PathBuf },

    #[error(
        "`{}` is a partitioned mesh: re-export it unpartitioned (gmsh -format msh41, \
         without -part)",
        path.display()
    )]
    Partitioned { path: PathBuf },

    #[error(
        "`{}`: physical group `{group}` has elements of gmsh type {code} ({name}), which \
         subcontact cannot use: mesh with triangles or quadrangles in 2D, tetrahedra or \
         hexahedra in 3D (supported: {supported})",
        path.display(),
        supported = supported_kinds()
    )]
    UnsupportedElement {
        path: PathBuf,
        code: i32,
        name: String,
        group: String,
    },

    #[error(
        "`{}`: element {element} of physical group `{group}` uses node {node}, which is not \
         in the $Nodes section: the file is inconsistent, mesh the .geo again with gmsh",
        path.display()
    )]
    MissingNode {
        path: PathBuf,
        element: u64,
        node: u64,
        group: String,
    },
}

fn supported_kinds() -> String {
    CellKind::ALL
        .iter()
        .map(|k| k.name())
        .collect::<Vec<_>>()
        .join(", ")
}

/// Reads an MSH 4.1 file (ASCII or binary) written by gmsh.
pub fn read_msh(path: &Path) -> Result<Mesh, MshError> {
    let bytes = match std::fs::read(path) {
        Ok(b) => b,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            return Err(MshError::NotFound {
                path: path.to_path_buf(),
            })
        }
        Err(e) => {
            return Err(MshError::Io {
                path: path.to_path_buf(),
                source: e,
            })
        }
    };
    parse_msh(path, &bytes)
}

/// Name and node count of gmsh element types (codes of the MSH format), for
/// messages and for skipping blocks that belong to no physical group.
fn gmsh_type(code: i32) -> Option<(&'static str, usize)> {
    if let Some(k) = CellKind::from_gmsh(code) {
        return Some((k.name(), k.n_nodes()));
    }
    Some(match code {
        6 => ("prism6", 6),
        7 => ("pyramid5", 5),
        13 => ("prism18", 18),
        14 => ("pyramid14", 14),
        18 => ("prism15", 15),
        19 => ("pyramid13", 13),
        20 => ("tri9", 9),
        21 => ("tri10", 10),
        22 => ("tri12", 12),
        23 => ("tri15", 15),
        24 => ("tri15i", 15),
        25 => ("tri21", 21),
        26 => ("line4", 4),
        27 => ("line5", 5),
        28 => ("line6", 6),
        29 => ("tet20", 20),
        30 => ("tet35", 35),
        31 => ("tet56", 56),
        36 => ("quad16", 16),
        37 => ("quad25", 25),
        38 => ("quad36", 36),
        92 => ("hex64", 64),
        93 => ("hex125", 125),
        _ => return None,
    })
}

/// Parsed `$Elements` block of a supported kind.
struct Block {
    dim: i32,
    entity: i32,
    kind: CellKind,
    tags: Vec<u64>,
    /// `kind.n_nodes()` node tags per element.
    nodes: Vec<u64>,
}

/// A cursor over the file's bytes that reads the MSH value types in ASCII or
/// binary form.
struct Reader<'a> {
    path: &'a Path,
    buf: &'a [u8],
    pos: usize,
    binary: bool,
    size_t: usize,
    little: bool,
    section: &'static str,
}

impl<'a> Reader<'a> {
    fn malformed(&self, what: impl std::fmt::Display) -> MshError {
        let place = if self.section.is_empty() {
            format!("at byte {}", self.pos)
        } else {
            format!("in section ${} at byte {}", self.section, self.pos)
        };
        let end = if self.pos >= self.buf.len() {
            " (end of file)"
        } else {
            ""
        };
        MshError::Malformed {
            path: self.path.to_path_buf(),
            detail: format!("{what} {place}{end}"),
        }
    }

    fn at_end(&self) -> bool {
        self.pos >= self.buf.len()
    }

    fn remaining(&self) -> usize {
        self.buf.len().saturating_sub(self.pos)
    }

    fn skip_ws(&mut self) {
        while self.pos < self.buf.len() && self.buf[self.pos].is_ascii_whitespace() {
            self.pos += 1;
        }
    }

    /// The next whitespace-delimited word (ASCII mode), after skipping whitespace.
    fn word(&mut self) -> Option<&'a [u8]> {
        self.skip_ws();
        let start = self.pos;
        while self.pos < self.buf.len() && !self.buf[self.pos].is_ascii_whitespace() {
            self.pos += 1;
        }
        if self.pos > start {
            Some(&self.buf[start..self.pos])
        } else {
            None
        }
    }

    /// The rest of the current line without its end (`\n` or `\r\n`), consuming the end.
    fn line(&mut self) -> &'a [u8] {
        let start = self.pos;
        while self.pos < self.buf.len() && self.buf[self.pos] != b'\n' {
            self.pos += 1;
        }
        let mut line = &self.buf[start..self.pos];
        if self.pos < self.buf.len() {
            self.pos += 1;
        }
        if let Some((&b'\r', rest)) = line.split_last() {
            line = rest;
        }
        line
    }

    fn bytes(&mut self, n: usize, what: &str) -> Result<&'a [u8], MshError> {
        if self.remaining() < n {
            return Err(self.malformed(format!("expected {what}")));
        }
        let b = &self.buf[self.pos..self.pos + n];
        self.pos += n;
        Ok(b)
    }

    fn parse_word<T: std::str::FromStr>(&mut self, what: &str) -> Result<T, MshError> {
        let before = self.pos;
        match self.word() {
            None => Err(self.malformed(format!("expected {what}"))),
            Some(w) => match std::str::from_utf8(w)
                .ok()
                .and_then(|s| s.parse::<T>().ok())
            {
                Some(v) => Ok(v),
                None => {
                    self.pos = before;
                    self.skip_ws();
                    let shown: String = String::from_utf8_lossy(&w[..w.len().min(40)]).into();
                    Err(self.malformed(format!("expected {what}, found `{shown}`")))
                }
            },
        }
    }

    /// An MSH `size_t` value.
    fn size_t(&mut self, what: &str) -> Result<u64, MshError> {
        if !self.binary {
            return self.parse_word(what);
        }
        let b = self.bytes(self.size_t, what)?;
        Ok(if self.size_t == 4 {
            let a = [b[0], b[1], b[2], b[3]];
            u64::from(if self.little {
                u32::from_le_bytes(a)
            } else {
                u32::from_be_bytes(a)
            })
        } else {
            let a = [b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7]];
            if self.little {
                u64::from_le_bytes(a)
            } else {
                u64::from_be_bytes(a)
            }
        })
    }

    /// A `size_t` count, as usize.
    fn count(&mut self, what: &str) -> Result<usize, MshError> {
        let v = self.size_t(what)?;
        usize::try_from(v).map_err(|_| self.malformed(format!("{what} {v} is too large")))
    }

    /// An MSH `int` (4 bytes in binary files).
    fn int(&mut self, what: &str) -> Result<i32, MshError> {
        if !self.binary {
            return self.parse_word(what);
        }
        let b = self.bytes(4, what)?;
        let a = [b[0], b[1], b[2], b[3]];
        Ok(if self.little {
            i32::from_le_bytes(a)
        } else {
            i32::from_be_bytes(a)
        })
    }

    /// An MSH `double`.
    fn double(&mut self, what: &str) -> Result<f64, MshError> {
        if !self.binary {
            return self.parse_word(what);
        }
        let b = self.bytes(8, what)?;
        let a = [b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7]];
        Ok(if self.little {
            f64::from_le_bytes(a)
        } else {
            f64::from_be_bytes(a)
        })
    }

    /// A capacity for `count` items of at least `min_bytes` bytes each that the
    /// rest of the file can actually hold.
    fn capacity(&self, count: usize, min_bytes: usize) -> usize {
        count.min(self.remaining() / min_bytes.max(1))
    }

    /// Smallest size of one value in the file (a digit and a separator in ASCII).
    fn min_value_bytes(&self, binary_size: usize) -> usize {
        if self.binary {
            binary_size
        } else {
            2
        }
    }

    /// Consumes a section's end marker `$End<name>` (after whitespace).
    fn end_section(&mut self, name: &str) -> Result<(), MshError> {
        self.skip_ws();
        let marker = format!("$End{name}");
        let line = self.line();
        if line.trim_ascii_end() != marker.as_bytes() {
            return Err(self.malformed(format!("expected `{marker}`")));
        }
        Ok(())
    }
}

/// Parses the bytes of an MSH file; `path` is only used in messages.
fn parse_msh(path: &Path, bytes: &[u8]) -> Result<Mesh, MshError> {
    let mut r = Reader {
        path,
        buf: bytes,
        pos: 0,
        binary: false,
        size_t: 8,
        little: true,
        section: "",
    };
    if bytes.iter().all(|b| b.is_ascii_whitespace()) {
        return Err(r.malformed("the file is empty"));
    }
    read_header(&mut r)?;

    let mut names: Vec<(i32, i32, String)> = Vec::new();
    // (dim, entity tag) -> physical tags
    let mut entities: Option<HashMap<(i32, i32), Vec<i32>>> = None;
    let mut nodes: Option<(Vec<[f64; 3]>, Vec<u64>)> = None;
    let mut blocks: Option<Vec<Block>> = None;

    loop {
        r.section = "";
        r.skip_ws();
        if r.at_end() {
            break;
        }
        let line = r.line();
        let name = match line.trim_ascii().strip_prefix(b"$") {
            Some(n) if !n.is_empty() && !n.starts_with(b"End") => {
                String::from_utf8_lossy(n).into_owned()
            }
            _ => {
                return Err(r.malformed("expected the start of a section such as `$Nodes`"));
            }
        };
        match name.as_str() {
            "PhysicalNames" => {
                r.section = "PhysicalNames";
                names = read_physical_names(&mut r)?;
                r.end_section("PhysicalNames")?;
            }
            "Entities" => {
                r.section = "Entities";
                if entities.is_some() {
                    return Err(r.malformed("a second $Entities section"));
                }
                if blocks.is_some() {
                    return Err(r.malformed("$Entities after $Elements"));
                }
                entities = Some(read_entities(&mut r)?);
                r.end_section("Entities")?;
            }
            "PartitionedEntities" => {
                return Err(MshError::Partitioned {
                    path: path.to_path_buf(),
                });
            }
            "Nodes" => {
                r.section = "Nodes";
                if nodes.is_some() {
                    return Err(r.malformed("a second $Nodes section"));
                }
                nodes = Some(read_nodes(&mut r)?);
                r.end_section("Nodes")?;
            }
            "Elements" => {
                r.section = "Elements";
                if blocks.is_some() {
                    return Err(r.malformed("a second $Elements section"));
                }
                let empty = HashMap::new();
                let ents = entities.as_ref().unwrap_or(&empty);
                blocks = Some(read_elements(&mut r, ents, &names)?);
                r.end_section("Elements")?;
            }
            other => {
                // Skip an unknown section up to its end marker.
                let marker = format!("$End{other}");
                match find(&bytes[r.pos..], marker.as_bytes()) {
                    Some(at) => {
                        r.pos += at;
                        r.end_section(other)?;
                    }
                    None => return Err(r.malformed(format!("no `{marker}` after `${other}`"))),
                }
            }
        }
    }

    let Some((coords, node_tags)) = nodes else {
        return Err(r.malformed("no $Nodes section"));
    };
    let Some(blocks) = blocks else {
        return Err(r.malformed("no $Elements section"));
    };
    let entities = entities.unwrap_or_default();
    build_mesh(path, coords, node_tags, &names, &entities, blocks)
}

fn find(haystack: &[u8], needle: &[u8]) -> Option<usize> {
    if needle.is_empty() || haystack.len() < needle.len() {
        return None;
    }
    haystack.windows(needle.len()).position(|w| w == needle)
}

/// `$MeshFormat`: version, ASCII/binary, size of `size_t`, endianness.
fn read_header(r: &mut Reader) -> Result<(), MshError> {
    r.skip_ws();
    if r.line().trim_ascii() != b"$MeshFormat" {
        r.pos = 0;
        return Err(r.malformed("the file does not start with `$MeshFormat`"));
    }
    r.section = "MeshFormat";
    let version = r.word().map(|w| String::from_utf8_lossy(w).into_owned());
    let Some(version) = version else {
        return Err(r.malformed("expected the format version"));
    };
    if version.parse::<f64>().is_err() {
        return Err(r.malformed(format!(
            "expected the format version 4.1, found `{version}`"
        )));
    }
    let file_type: i32 = r.parse_word("the file type (0 ASCII, 1 binary)")?;
    let data_size: usize = r.parse_word("the size of size_t")?;
    if r.at_end() {
        return Err(r.malformed("expected the end of the format line"));
    }
    if version != "4.1" {
        return Err(MshError::Version {
            path: r.path.to_path_buf(),
            version,
        });
    }
    if !(file_type == 0 || file_type == 1) {
        return Err(r.malformed(format!(
            "file type {file_type} is neither 0 (ASCII) nor 1 (binary)"
        )));
    }
    if !(data_size == 4 || data_size == 8) {
        return Err(r.malformed(format!("size_t of {data_size} bytes (expected 4 or 8)")));
    }
    r.size_t = data_size;
    // The rest of the version line.
    let rest = r.line();
    if !rest.trim_ascii().is_empty() {
        return Err(r.malformed("unexpected text after the format line"));
    }
    if file_type == 1 {
        r.binary = true;
        let b = r.bytes(4, "the binary integer 1 that gives the byte order")?;
        let a = [b[0], b[1], b[2], b[3]];
        if i32::from_le_bytes(a) == 1 {
            r.little = true;
        } else if i32::from_be_bytes(a) == 1 {
            r.little = false;
        } else {
            return Err(r.malformed("the binary integer 1 that gives the byte order is not 1"));
        }
    }
    r.end_section("MeshFormat")
}

/// `$PhysicalNames` (ASCII even in binary files): `dim tag "name"` lines.
fn read_physical_names(r: &mut Reader) -> Result<Vec<(i32, i32, String)>, MshError> {
    let binary = std::mem::replace(&mut r.binary, false);
    let result = (|| {
        let n: usize = r.parse_word("the number of physical names")?;
        let mut names = Vec::with_capacity(r.capacity(n, 8));
        for _ in 0..n {
            let dim: i32 = r.parse_word("the dimension of a physical name")?;
            if !(0..=3).contains(&dim) {
                return Err(r.malformed(format!("physical name of dimension {dim}")));
            }
            let tag: i32 = r.parse_word("the tag of a physical name")?;
            r.skip_ws();
            if r.buf.get(r.pos) != Some(&b'"') {
                return Err(r.malformed("expected a quoted physical name"));
            }
            r.pos += 1;
            let start = r.pos;
            while r.pos < r.buf.len() && r.buf[r.pos] != b'"' && r.buf[r.pos] != b'\n' {
                r.pos += 1;
            }
            if r.buf.get(r.pos) != Some(&b'"') {
                return Err(r.malformed("expected the closing quote of a physical name"));
            }
            let name = String::from_utf8_lossy(&r.buf[start..r.pos]).into_owned();
            r.pos += 1;
            names.push((dim, tag, name));
        }
        Ok(names)
    })();
    r.binary = binary;
    result
}

/// `$Entities`: the physical tags of each point, curve, surface and volume.
fn read_entities(r: &mut Reader) -> Result<HashMap<(i32, i32), Vec<i32>>, MshError> {
    let mut counts = [0usize; 4];
    for (dim, c) in counts.iter_mut().enumerate() {
        *c = r.count(
            [
                "the number of points",
                "the number of curves",
                "the number of surfaces",
                "the number of volumes",
            ][dim],
        )?;
    }
    let mut map = HashMap::new();
    for (dim, &n) in counts.iter().enumerate() {
        for _ in 0..n {
            let tag = r.int("an entity tag")?;
            // A point has its coordinates, other entities their bounding box.
            let n_doubles = if dim == 0 { 3 } else { 6 };
            for _ in 0..n_doubles {
                r.double("an entity coordinate")?;
            }
            let n_phys = r.count("the number of physical tags of an entity")?;
            let mut phys = Vec::with_capacity(r.capacity(n_phys, r.min_value_bytes(4)));
            for _ in 0..n_phys {
                phys.push(r.int("a physical tag")?);
            }
            if dim > 0 {
                let n_bound = r.count("the number of bounding entities")?;
                for _ in 0..n_bound {
                    r.int("a bounding entity tag")?;
                }
            }
            map.insert((dim as i32, tag), phys);
        }
    }
    Ok(map)
}

/// `$Nodes`: coordinates and tags in file order.
fn read_nodes(r: &mut Reader) -> Result<(Vec<[f64; 3]>, Vec<u64>), MshError> {
    let n_blocks = r.count("the number of node blocks")?;
    let n_nodes = r.count("the number of nodes")?;
    r.size_t("the smallest node tag")?;
    r.size_t("the largest node tag")?;
    let cap = r.capacity(n_nodes, 4 * r.min_value_bytes(8));
    let mut coords: Vec<[f64; 3]> = Vec::with_capacity(cap);
    let mut tags: Vec<u64> = Vec::with_capacity(cap);
    for _ in 0..n_blocks {
        let dim = r.int("the dimension of a node block")?;
        r.int("the entity tag of a node block")?;
        let parametric = r.int("the parametric flag of a node block")?;
        let n = r.count("the number of nodes in a block")?;
        if !(0..=3).contains(&dim) {
            return Err(r.malformed(format!("node block of dimension {dim}")));
        }
        let extra = match parametric {
            0 => 0,
            1 => dim as usize,
            p => return Err(r.malformed(format!("parametric flag {p} (expected 0 or 1)"))),
        };
        let first = tags.len();
        tags.reserve(r.capacity(n, r.min_value_bytes(r.size_t)));
        for _ in 0..n {
            let t = r.size_t("a node tag")?;
            tags.push(t);
        }
        coords.reserve(r.capacity(n, 3 * r.min_value_bytes(8)));
        for _ in first..tags.len() {
            let x = r.double("a node's x coordinate")?;
            let y = r.double("a node's y coordinate")?;
            let z = r.double("a node's z coordinate")?;
            for _ in 0..extra {
                r.double("a node's parametric coordinate")?;
            }
            coords.push([x, y, z]);
        }
    }
    if tags.len() != n_nodes {
        return Err(r.malformed(format!(
            "the header announces {n_nodes} nodes, the blocks hold {}",
            tags.len()
        )));
    }
    Ok((coords, tags))
}

/// `$Elements`: blocks of supported kinds whose entity carries a physical tag.
/// Blocks of entities without physical tags are skipped; an unsupported kind in
/// a physical group is an error.
fn read_elements(
    r: &mut Reader,
    entities: &HashMap<(i32, i32), Vec<i32>>,
    names: &[(i32, i32, String)],
) -> Result<Vec<Block>, MshError> {
    let n_blocks = r.count("the number of element blocks")?;
    r.size_t("the number of elements")?;
    r.size_t("the smallest element tag")?;
    r.size_t("the largest element tag")?;
    let mut blocks = Vec::new();
    for _ in 0..n_blocks {
        let dim = r.int("the dimension of an element block")?;
        let entity = r.int("the entity tag of an element block")?;
        let code = r.int("the element type of an element block")?;
        let n = r.count("the number of elements in a block")?;
        let phys = entities
            .get(&(dim, entity))
            .map(|p| p.as_slice())
            .unwrap_or(&[]);
        let kind = CellKind::from_gmsh(code);
        let n_per = match (kind, gmsh_type(code)) {
            (Some(k), _) if phys.is_empty() || k.dim() as i32 == dim => k.n_nodes(),
            (Some(k), _) => {
                return Err(r.malformed(format!(
                    "{} elements in an entity of dimension {dim}",
                    k.name()
                )))
            }
            (None, known) if !phys.is_empty() => {
                return Err(MshError::UnsupportedElement {
                    path: r.path.to_path_buf(),
                    code,
                    name: known
                        .map(|(name, _)| name)
                        .unwrap_or("unknown type")
                        .to_string(),
                    group: group_name(names, dim, phys[0]),
                });
            }
            (None, Some((_, n_per))) => n_per,
            (None, None) => {
                return Err(r.malformed(format!("unknown gmsh element type {code}")));
            }
        };
        let keep = kind.is_some() && !phys.is_empty();
        let per_elem = 1 + n_per;
        if !keep && r.binary {
            let len = n
                .checked_mul(per_elem)
                .and_then(|v| v.checked_mul(r.size_t));
            match len {
                Some(len) if len <= r.remaining() => r.pos += len,
                _ => return Err(r.malformed("expected the elements of a block")),
            }
            continue;
        }
        let mut tags = Vec::new();
        let mut nodes = Vec::new();
        if keep {
            let v = r.min_value_bytes(r.size_t);
            tags.reserve(r.capacity(n, per_elem * v));
            nodes.reserve(r.capacity(n, per_elem * v).saturating_mul(n_per));
        }
        for _ in 0..n {
            let t = r.size_t("an element tag")?;
            if keep {
                tags.push(t);
            }
            for _ in 0..n_per {
                let node = r.size_t("a node tag of an element")?;
                if keep {
                    nodes.push(node);
                }
            }
        }
        if let Some(kind) = kind.filter(|_| keep) {
            blocks.push(Block {
                dim,
                entity,
                kind,
                tags,
                nodes,
            });
        }
    }
    Ok(blocks)
}

fn group_name(names: &[(i32, i32, String)], dim: i32, tag: i32) -> String {
    names
        .iter()
        .find(|(d, t, _)| *d == dim && *t == tag)
        .map(|(_, _, n)| n.clone())
        .unwrap_or_else(|| tag.to_string())
}

/// Node tag -> index: a table when the tags are compact (gmsh numbers nodes
/// 1..n), a hash map otherwise.
enum NodeIndex {
    Dense(Vec<usize>),
    Sparse(HashMap<u64, usize>),
}

impl NodeIndex {
    /// Fails with the first tag that appears twice.
    fn new(tags: &[u64]) -> Result<Self, u64> {
        let max = tags.iter().copied().max().unwrap_or(0);
        let compact = usize::try_from(max).is_ok_and(|m| m <= 2 * tags.len() + 1024);
        if compact {
            let mut table = vec![usize::MAX; max as usize + 1];
            for (i, &t) in tags.iter().enumerate() {
                let slot = &mut table[t as usize];
                if *slot != usize::MAX {
                    return Err(t);
                }
                *slot = i;
            }
            Ok(NodeIndex::Dense(table))
        } else {
            let mut map = HashMap::with_capacity(tags.len());
            for (i, &t) in tags.iter().enumerate() {
                if map.insert(t, i).is_some() {
                    return Err(t);
                }
            }
            Ok(NodeIndex::Sparse(map))
        }
    }

    fn get(&self, tag: u64) -> Option<usize> {
        match self {
            NodeIndex::Dense(table) => {
                let i = *table.get(usize::try_from(tag).ok()?)?;
                (i != usize::MAX).then_some(i)
            }
            NodeIndex::Sparse(map) => map.get(&tag).copied(),
        }
    }
}

fn build_mesh(
    path: &Path,
    coords: Vec<[f64; 3]>,
    node_tags: Vec<u64>,
    names: &[(i32, i32, String)],
    entities: &HashMap<(i32, i32), Vec<i32>>,
    blocks: Vec<Block>,
) -> Result<Mesh, MshError> {
    let index = NodeIndex::new(&node_tags).map_err(|t| MshError::Malformed {
        path: path.to_path_buf(),
        detail: format!("node tag {t} appears twice in $Nodes"),
    })?;

    let mut groups: BTreeMap<(i32, i32), Group> = BTreeMap::new();
    let new_group = |dim: i32, tag: i32| Group {
        name: group_name(names, dim, tag),
        dim: dim.max(0) as usize,
        tag,
        cells: Vec::new(),
    };
    for &(dim, tag, _) in names {
        groups
            .entry((dim, tag))
            .or_insert_with(|| new_group(dim, tag));
    }
    let mut keys: Vec<_> = entities.iter().collect();
    keys.sort_by_key(|(k, _)| **k);
    for (&(dim, _), phys) in keys {
        for &p in phys {
            groups.entry((dim, p)).or_insert_with(|| new_group(dim, p));
        }
    }
    if groups.is_empty() {
        return Err(MshError::NoPhysicalGroups {
            path: path.to_path_buf(),
        });
    }

    for block in &blocks {
        let phys = entities
            .get(&(block.dim, block.entity))
            .map(|p| p.as_slice())
            .unwrap_or(&[]);
        let n_per = block.kind.n_nodes();
        for (i, &etag) in block.tags.iter().enumerate() {
            let Some(node_tags) = block.nodes.get(i * n_per..(i + 1) * n_per) else {
                continue;
            };
            let mut nodes = Vec::with_capacity(n_per);
            for &nt in node_tags {
                match index.get(nt) {
                    Some(k) => nodes.push(k),
                    None => {
                        return Err(MshError::MissingNode {
                            path: path.to_path_buf(),
                            element: etag,
                            node: nt,
                            group: group_name(names, block.dim, phys.first().copied().unwrap_or(0)),
                        })
                    }
                }
            }
            let cell = Cell {
                kind: block.kind,
                nodes,
                tag: etag,
            };
            // Each group of the entity gets the cell (the last one without a copy).
            if let Some((&last, rest)) = phys.split_last() {
                for &p in rest {
                    if let Some(g) = groups.get_mut(&(block.dim, p)) {
                        g.cells.push(cell.clone());
                    }
                }
                if let Some(g) = groups.get_mut(&(block.dim, last)) {
                    g.cells.push(cell);
                }
            }
        }
    }

    Ok(Mesh {
        coords,
        node_tags,
        groups: groups.into_values().collect(),
    })
}

#[cfg(test)]
mod tests {
    use super::super::gmsh::tests::{TestDir, BOX_GEO, QUAD_GEO, TWO_RECT_GEO};
    use super::super::gmsh::{mesh_with, GmshJob};
    use super::*;

    /// `-setnumber` pairs.
    type Set<'a> = &'a [(&'a str, f64)];

    /// Meshes `geo` with the real gmsh CLI and returns the .msh path.
    fn gmsh(
        dir: &TestDir,
        geo: &str,
        name: &str,
        dim: usize,
        order: usize,
        binary: bool,
        set: Set,
    ) -> PathBuf {
        let geo_path = dir.write(&format!("{name}.geo"), geo);
        let job = GmshJob {
            geo: geo_path,
            msh: dir.0.join(format!("{name}.msh")),
            dim,
            order,
            setnumber: set.iter().map(|(k, v)| (k.to_string(), *v)).collect(),
            clscale: None,
        };
        mesh_with(&job, binary).unwrap();
        job.msh
    }

    /// Runs gmsh with arbitrary arguments (for formats `mesh` does not write).
    fn gmsh_raw(dir: &TestDir, geo: &str, name: &str, args: &[&str]) -> PathBuf {
        let geo_path = dir.write(&format!("{name}.geo"), geo);
        let msh = dir.0.join(format!("{name}.msh"));
        let out = std::process::Command::new("gmsh")
            .arg(&geo_path)
            .args(args)
            .arg("-o")
            .arg(&msh)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        msh
    }

    /// Checks every cell against mshio's reading of the same file: same element
    /// tags, same node coordinates. (Only valid where mshio's node tags are right:
    /// gmsh's own files, whose tags run in file order.)
    fn check_against_mshio(path: &Path, mesh: &Mesh) {
        let bytes = std::fs::read(path).unwrap();
        let m = mshio::parse_msh_bytes(&bytes).unwrap();
        let nodes = m.data.nodes.unwrap();
        let mut coords: HashMap<u64, [f64; 3]> = HashMap::new();
        let mut next = nodes.min_node_tag;
        for b in &nodes.node_blocks {
            let mut tags = vec![0u64; b.nodes.len()];
            match &b.node_tags {
                Some(map) => map.iter().for_each(|(&t, &i)| tags[i] = t),
                None => tags.iter_mut().for_each(|t| {
                    *t = next;
                    next += 1;
                }),
            }
            for (t, n) in tags.iter().zip(&b.nodes) {
                coords.insert(*t, [n.x, n.y, n.z]);
            }
        }
        let mut elements: HashMap<u64, (i32, Vec<u64>)> = HashMap::new();
        for b in &m.data.elements.unwrap().element_blocks {
            for e in &b.elements {
                elements.insert(e.element_tag, (b.element_type as i32, e.nodes.clone()));
            }
        }
        let mut n_cells = 0;
        for g in &mesh.groups {
            for c in &g.cells {
                let (code, tags) = &elements[&c.tag];
                assert_eq!(*code, c.kind.gmsh_code());
                let theirs: Vec<[f64; 3]> = tags.iter().map(|t| coords[t]).collect();
                let ours: Vec<[f64; 3]> = c.nodes.iter().map(|&i| mesh.coords[i]).collect();
                assert_eq!(ours, theirs, "element {}", c.tag);
                n_cells += 1;
            }
        }
        assert!(n_cells > 0);
        assert_eq!(mesh.coords.len(), coords.len());
    }

    fn kinds(g: &Group) -> Vec<CellKind> {
        let mut k: Vec<CellKind> = g.cells.iter().map(|c| c.kind).collect();
        k.sort();
        k.dedup();
        k
    }

    fn tri_area(mesh: &Mesh, g: &Group) -> f64 {
        g.cells
            .iter()
            .map(|c| {
                let [a, b, p] = [0, 1, 2].map(|i| mesh.coords[c.nodes[i]]);
                0.5 * ((b[0] - a[0]) * (p[1] - a[1]) - (p[0] - a[0]) * (b[1] - a[1]))
            })
            .sum()
    }

    #[test]
    fn two_rectangles_order_1_and_2_ascii_and_binary() {
        let dir = TestDir::new("two");
        for order in [1, 2] {
            let mut by_format = Vec::new();
            for binary in [true, false] {
                let name = format!("two-o{order}-{}", if binary { "bin" } else { "ascii" });
                let path = gmsh(&dir, TWO_RECT_GEO, &name, 2, order, binary, &[]);
                assert_eq!(std::fs::read(&path).unwrap()[12..19] == *b"4.1 1 8", binary);
                let mesh = read_msh(&path).unwrap();
                check_against_mshio(&path, &mesh);

                let summary: Vec<(&str, usize, i32)> = mesh
                    .groups
                    .iter()
                    .map(|g| (g.name.as_str(), g.dim, g.tag))
                    .collect();
                assert_eq!(
                    summary,
                    [
                        ("corner", 0, 5),
                        ("shared", 1, 3),
                        ("bottom", 1, 4),
                        ("left", 2, 1),
                        ("right", 2, 2)
                    ]
                );
                assert_eq!(mesh.dim(), 2);
                let (line, tri) = if order == 1 {
                    (CellKind::Line2, CellKind::Tri3)
                } else {
                    (CellKind::Line3, CellKind::Tri6)
                };
                let g = |n: &str| mesh.group(n).unwrap();
                assert_eq!(kinds(g("corner")), [CellKind::Point1]);
                assert_eq!(kinds(g("shared")), [line]);
                assert_eq!(kinds(g("bottom")), [line]);
                assert_eq!(kinds(g("left")), [tri]);
                assert_eq!(kinds(g("right")), [tri]);

                // lc = 0.5: two segments per unit edge; "bottom" spans two curves.
                assert_eq!(g("shared").cells.len(), 2);
                assert_eq!(g("bottom").cells.len(), 4);
                assert_eq!(g("corner").nodes().len(), 1);
                assert_eq!(mesh.coords[g("corner").nodes()[0]], [0.0, 0.0, 0.0]);

                // The shared curve's nodes are nodes of both surfaces, all at x = 1.
                let shared = g("shared").nodes();
                assert_eq!(shared.len(), 2 * order + 1);
                let (left, right) = (g("left").nodes(), g("right").nodes());
                for n in &shared {
                    assert!(left.binary_search(n).is_ok() && right.binary_search(n).is_ok());
                    assert!((mesh.coords[*n][0] - 1.0).abs() < 1e-12);
                }
                // The surfaces meet only there.
                let common: Vec<usize> = left
                    .iter()
                    .copied()
                    .filter(|n| right.binary_search(n).is_ok())
                    .collect();
                assert_eq!(common, shared);

                // Counter-clockwise cells tile each unit square.
                assert!((tri_area(&mesh, g("left")) - 1.0).abs() < 1e-12);
                assert!((tri_area(&mesh, g("right")) - 1.0).abs() < 1e-12);
                assert!((mesh.size() - 5f64.sqrt()).abs() < 1e-12);
                for c in g("left").cells.iter().chain(&g("right").cells) {
                    let mut n = c.nodes.clone();
                    n.sort();
                    n.dedup();
                    assert_eq!(n.len(), c.kind.n_nodes());
                }
                assert_eq!(mesh.node_tags.len(), mesh.coords.len());
                by_format.push(mesh);
            }
            // ASCII and binary files of the same mesh read the same (ASCII
            // coordinates have 16 significant digits).
            let (bin, ascii) = (&by_format[0], &by_format[1]);
            assert_eq!(
                (&bin.node_tags, &bin.groups),
                (&ascii.node_tags, &ascii.groups)
            );
            assert_eq!(bin.coords.len(), ascii.coords.len());
            for (a, b) in bin.coords.iter().zip(&ascii.coords) {
                assert!((0..3).all(|d| (a[d] - b[d]).abs() < 1e-14), "{a:?} {b:?}");
            }
        }
    }

    #[test]
    fn hex_box_order_1_and_2() {
        let dir = TestDir::new("box");
        let cases: [(usize, Set, CellKind, CellKind, usize); 3] = [
            (1, &[], CellKind::Hex8, CellKind::Quad4, 27),
            (2, &[], CellKind::Hex27, CellKind::Quad9, 125),
            (
                2,
                &[("Mesh.SecondOrderIncomplete", 1.0)],
                CellKind::Hex20,
                CellKind::Quad8,
                125 - 8 - 36,
            ),
        ];
        for (i, (order, set, hex, quad, n_nodes)) in cases.into_iter().enumerate() {
            for binary in [true, false] {
                let path = gmsh(
                    &dir,
                    BOX_GEO,
                    &format!("box{i}-{binary}"),
                    3,
                    order,
                    binary,
                    set,
                );
                let mesh = read_msh(&path).unwrap();
                check_against_mshio(&path, &mesh);
                let summary: Vec<(&str, usize)> = mesh
                    .groups
                    .iter()
                    .map(|g| (g.name.as_str(), g.dim))
                    .collect();
                assert_eq!(summary, [("bottom", 2), ("top", 2), ("box", 3)]);
                assert_eq!(mesh.dim(), 3);
                let b = mesh.group("box").unwrap();
                assert_eq!(kinds(b), [hex]);
                assert_eq!(b.cells.len(), 8);
                assert_eq!(b.nodes().len(), n_nodes);
                for s in ["bottom", "top"] {
                    let g = mesh.group(s).unwrap();
                    assert_eq!(kinds(g), [quad]);
                    assert_eq!(g.cells.len(), 4);
                    let z = if s == "top" { 1.0 } else { 0.0 };
                    assert!(g.nodes().iter().all(|&n| mesh.coords[n][2] == z));
                    // Face nodes are nodes of the volume.
                    assert!(g.nodes().iter().all(|n| b.nodes().binary_search(n).is_ok()));
                }
            }
        }
    }

    #[test]
    fn quads_order_1_and_2() {
        let dir = TestDir::new("quad");
        let cases: [(usize, Set, CellKind, CellKind); 3] = [
            (1, &[], CellKind::Quad4, CellKind::Line2),
            (2, &[], CellKind::Quad9, CellKind::Line3),
            (
                2,
                &[("Mesh.SecondOrderIncomplete", 1.0)],
                CellKind::Quad8,
                CellKind::Line3,
            ),
        ];
        for (i, (order, set, quad, line)) in cases.into_iter().enumerate() {
            let path = gmsh(&dir, QUAD_GEO, &format!("quad{i}"), 2, order, true, set);
            let mesh = read_msh(&path).unwrap();
            check_against_mshio(&path, &mesh);
            assert_eq!(kinds(mesh.group("square").unwrap()), [quad]);
            assert_eq!(kinds(mesh.group("edges").unwrap()), [line]);
            assert_eq!(mesh.group("square").unwrap().cells.len(), 4);
        }
    }

    #[test]
    fn parametric_nodes_are_read() {
        let dir = TestDir::new("param");
        for binary in [true, false] {
            let plain = read_msh(&gmsh(
                &dir,
                TWO_RECT_GEO,
                &format!("plain{binary}"),
                2,
                2,
                binary,
                &[],
            ))
            .unwrap();
            let path = gmsh(
                &dir,
                TWO_RECT_GEO,
                &format!("param{binary}"),
                2,
                2,
                binary,
                &[("Mesh.SaveParametric", 1.0)],
            );
            assert!(
                std::fs::read(&path).unwrap().len()
                    > std::fs::read(dir.0.join(format!("plain{binary}.msh")))
                        .unwrap()
                        .len()
            );
            assert_eq!(read_msh(&path).unwrap(), plain);
        }
    }

    /// Tags 1..4 but in the file order 3 1 2 4; a surface with three physical
    /// tags, two of them unnamed.
    const HAND: &str = r#"$MeshFormat
4.1 0 8
$EndMeshFormat
$Comments
anything $Nodes here is skipped
$EndComments
$PhysicalNames
2
1 7 "an edge"
2 3 "plate"
$EndPhysicalNames
$Entities
0 1 1 0
5 0 0 0 1 0 0 1 7 0
1 0 0 0 1 1 0 3 3 9 11 0
$EndEntities
$Nodes
2 4 1 4
1 5 0 2
3
1
1 0 0
0 0 0
2 1 0 2
2
4
1 1 0
0 1 0
$EndNodes
$Elements
2 3 1 3
1 5 1 1
1 1 3
2 1 2 2
2 1 3 2
3 1 2 4
$EndElements
"#;

    fn parse(text: &[u8]) -> Result<Mesh, MshError> {
        parse_msh(Path::new("test.msh"), text)
    }

    #[test]
    fn node_tags_out_of_order_and_several_physical_tags() {
        let mesh = parse(HAND.as_bytes()).unwrap();
        assert_eq!(mesh.node_tags, [3, 1, 2, 4]);
        assert_eq!(
            mesh.coords,
            [
                [1.0, 0.0, 0.0],
                [0.0, 0.0, 0.0],
                [1.0, 1.0, 0.0],
                [0.0, 1.0, 0.0]
            ]
        );
        let summary: Vec<(&str, usize, i32, usize)> = mesh
            .groups
            .iter()
            .map(|g| (g.name.as_str(), g.dim, g.tag, g.cells.len()))
            .collect();
        assert_eq!(
            summary,
            [
                ("an edge", 1, 7, 1),
                ("plate", 2, 3, 2),
                ("9", 2, 9, 2),
                ("11", 2, 11, 2)
            ]
        );
        let edge = &mesh.groups[0].cells[0];
        assert_eq!(
            (edge.kind, edge.nodes.as_slice(), edge.tag),
            (CellKind::Line2, &[1usize, 0][..], 1)
        );
        let plate = &mesh.groups[1].cells;
        assert_eq!(
            plate[0],
            Cell {
                kind: CellKind::Tri3,
                nodes: vec![1, 0, 2],
                tag: 2
            }
        );
        assert_eq!(
            plate[1],
            Cell {
                kind: CellKind::Tri3,
                nodes: vec![1, 2, 3],
                tag: 3
            }
        );
        assert_eq!(mesh.groups[2].cells, *plate);
        assert_eq!(mesh.groups[3].cells, *plate);

        // A named group that no entity carries (a typo in the .geo, say) is kept, empty.
        let text = HAND.replace("2\n1 7 \"an edge\"", "3\n2 12 \"ghost\"\n1 7 \"an edge\"");
        let with_ghost = parse(text.as_bytes()).unwrap();
        assert_eq!(with_ghost.groups.len(), 5);
        let ghost = with_ghost.group("ghost").unwrap();
        assert_eq!((ghost.dim, ghost.tag, ghost.cells.len()), (2, 12, 0));

        // Sparse tags (looked up through a hash map rather than a table).
        let sparse = HAND
            .replace("2 4 1 4\n", "2 4 1 4000000\n")
            .replace("\n2\n4\n1 1 0", "\n2\n4000000\n1 1 0")
            .replace("3 1 2 4\n", "3 1 2 4000000\n");
        let m = parse(sparse.as_bytes()).unwrap();
        assert_eq!(m.node_tags, [3, 1, 2, 4000000]);
        assert_eq!((&m.coords, &m.groups), (&mesh.coords, &mesh.groups));
        let twice = sparse.replace("\n2\n4000000\n1 1 0", "\n3\n4000000\n1 1 0");
        assert!(
            matches!(parse(twice.as_bytes()), Err(MshError::Malformed { detail, .. }) if detail.contains("node tag 3 appears twice"))
        );

        // CRLF line ends read the same.
        assert_eq!(parse(HAND.replace('\n', "\r\n").as_bytes()).unwrap(), mesh);
    }

    #[test]
    fn mshio_would_misplace_these_nodes() {
        // Why this module has its own reader: mshio drops contiguous node tags.
        let m = mshio::parse_msh_bytes(HAND.as_bytes()).unwrap();
        assert!(m
            .data
            .nodes
            .unwrap()
            .node_blocks
            .iter()
            .all(|b| b.node_tags.is_none()));
    }

    #[test]
    fn missing_file() {
        let dir = TestDir::new("missing");
        let p = dir.0.join("nothere.msh");
        let e = read_msh(&p).unwrap_err();
        assert!(matches!(e, MshError::NotFound { .. }));
        assert_eq!(
            e.to_string(),
            format!(
                "mesh file `{}` does not exist: check `mesh =` in the scene",
                p.display()
            )
        );
    }

    fn assert_malformed(r: Result<Mesh, MshError>, detail: &str) {
        match r {
            Err(e @ MshError::Malformed { .. }) => {
                let msg = e.to_string();
                assert!(
                    msg.starts_with("`test.msh` is not a complete MSH 4.1 file (truncated?): "),
                    "{msg}"
                );
                assert!(msg.contains(detail), "{msg} lacks {detail:?}");
            }
            other => panic!("expected Malformed ({detail}), got {other:?}"),
        }
    }

    #[test]
    fn empty_garbage_and_inconsistent_files() {
        assert_malformed(parse(b""), "the file is empty");
        assert_malformed(parse(b"  \n"), "the file is empty");
        assert_malformed(
            parse(b"Point(1) = {0, 0, 0};\n"),
            "does not start with `$MeshFormat`",
        );
        assert_malformed(
            parse(&[0xff, 0x00, 0x13, 0x37]),
            "does not start with `$MeshFormat`",
        );
        assert_malformed(
            parse(b"$MeshFormat\nabc 0 8\n$EndMeshFormat\n"),
            "found `abc`",
        );
        assert_malformed(
            parse(b"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"),
            "no $Nodes section",
        );
        assert_malformed(
            parse(b"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n0 0 1 0\n$EndNodes\n"),
            "no $Elements section",
        );
        assert_malformed(
            parse(b"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Foo\n1 2 3\n"),
            "no `$EndFoo`",
        );
        assert_malformed(
            parse(HAND.replace("1 1 3\n", "1 1 x\n").as_bytes()),
            "found `x`",
        );
        assert_malformed(
            parse(HAND.replace("2 4 1 4", "2 5 1 4").as_bytes()),
            "announces 5 nodes",
        );
        assert_malformed(
            parse(HAND.replace("\n4\n1 1 0", "\n3\n1 1 0").as_bytes()),
            "node tag 3 appears twice",
        );
        assert_malformed(
            parse(HAND.replace("$EndNodes", "$EndNode").as_bytes()),
            "expected `$EndNodes`",
        );
        // Huge counts fail fast, without allocating for them.
        let huge = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 1000000000000000000 1 1000000000000000000\n\
                    2 1 0 1000000000000000000\n1\n";
        assert_malformed(parse(huge.as_bytes()), "expected a node tag");
        let huge = HAND.replace("2 1 2 2\n", "2 1 2 1000000000000000000\n");
        assert_malformed(parse(huge.as_bytes()), "");
    }

    #[test]
    fn missing_node() {
        let text = HAND.replace("3 1 2 4\n", "3 1 2 99\n");
        let e = parse(text.as_bytes()).unwrap_err();
        assert!(
            matches!(
                e,
                MshError::MissingNode {
                    element: 3,
                    node: 99,
                    ..
                }
            ),
            "{e:?}"
        );
        let msg = e.to_string();
        assert!(
            msg.contains("`test.msh`") && msg.contains("element 3") && msg.contains("node 99"),
            "{msg}"
        );
        assert!(msg.contains("`plate`"), "{msg}");
    }

    #[test]
    fn old_formats_are_named() {
        let dir = TestDir::new("old");
        for (args, version) in [
            (&["-2", "-format", "msh22"][..], "2.2"),
            (&["-2", "-format", "msh22", "-bin"][..], "2.2"),
            (&["-2", "-format", "msh40"][..], "4"),
        ] {
            let path = gmsh_raw(&dir, TWO_RECT_GEO, "old", args);
            let e = read_msh(&path).unwrap_err();
            assert!(
                matches!(&e, MshError::Version { version: v, .. } if v == version),
                "{e:?}"
            );
            assert_eq!(
                e.to_string(),
                format!(
                    "`{}` is MSH {version}: re-export it with gmsh -format msh41",
                    path.display()
                )
            );
        }
    }

    #[test]
    fn no_physical_groups() {
        let dir = TestDir::new("nophys");
        let geo: String = TWO_RECT_GEO
            .lines()
            .filter(|l| !l.starts_with("Physical"))
            .collect::<Vec<_>>()
            .join("\n");
        let path = gmsh(&dir, &geo, "nophys", 2, 1, true, &[]);
        let e = read_msh(&path).unwrap_err();
        assert!(matches!(e, MshError::NoPhysicalGroups { .. }), "{e:?}");
        assert_eq!(
            e.to_string(),
            format!(
                "`{}` has no physical groups: add Physical Surface/Volume/Curve to the .geo, \
                 gmsh saves only elements of physical groups",
                path.display()
            )
        );
    }

    const PRISM_GEO: &str = r#"
Point(1) = {0, 0, 0, 0.5}; Point(2) = {1, 0, 0, 0.5}; Point(3) = {0, 1, 0, 0.5};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 1};
Curve Loop(1) = {1, 2, 3}; Plane Surface(1) = {1};
out[] = Extrude {0, 0, 1} { Surface{1}; Layers{2}; Recombine; };
Physical Volume("wedge") = {out[1]};
Physical Surface("base") = {1};
"#;

    #[test]
    fn unsupported_elements_name_type_and_group() {
        let dir = TestDir::new("prism");
        for (order, code, name) in [(1, 6, "prism6"), (2, 13, "prism18")] {
            for binary in [true, false] {
                let path = gmsh(
                    &dir,
                    PRISM_GEO,
                    &format!("prism{order}{binary}"),
                    3,
                    order,
                    binary,
                    &[],
                );
                let e = read_msh(&path).unwrap_err();
                assert!(
                    matches!(&e, MshError::UnsupportedElement { code: c, .. } if *c == code),
                    "{e:?}"
                );
                let msg = e.to_string();
                assert!(msg.contains(&format!("gmsh type {code} ({name})")), "{msg}");
                assert!(
                    msg.contains("`wedge`") && msg.contains(&path.display().to_string()),
                    "{msg}"
                );
            }
        }
        // Unsupported elements outside any physical group are skipped.
        let text = HAND
            .replace(
                "$Elements\n2 3 1 3\n",
                "$Elements\n3 4 1 4\n2 2 6 1\n4 1 2 3 4 1 2\n",
            )
            .replace("0 1 1 0\n", "0 1 2 0\n")
            .replace("$EndEntities", "2 0 0 0 1 1 0 0 0\n$EndEntities");
        let mesh = parse(text.as_bytes()).unwrap();
        assert_eq!(mesh, parse(HAND.as_bytes()).unwrap());
    }

    const FUZZ: usize = 300;

    /// Lengths to cut `n` bytes at: a spread, plus every length near both ends.
    fn cut_lengths(n: usize) -> Vec<usize> {
        let mut v: Vec<usize> = (0..n).step_by((n / 400).max(1)).collect();
        v.extend(0..n.min(80));
        v.extend(n.saturating_sub(80)..n);
        v.sort();
        v.dedup();
        v
    }

    #[test]
    fn truncated_and_corrupted_files_never_panic() {
        let dir = TestDir::new("trunc");
        let mut files = vec![HAND.as_bytes().to_vec()];
        for binary in [true, false] {
            for (geo, dim, name) in [(TWO_RECT_GEO, 2, "two"), (BOX_GEO, 3, "box")] {
                let path = gmsh(&dir, geo, &format!("{name}{binary}"), dim, 2, binary, &[]);
                files.push(std::fs::read(path).unwrap());
            }
        }
        for bytes in &files {
            let whole = parse(bytes).unwrap();
            // Cut before the end marker of $Elements: always a clear error.
            let complete = find(bytes, b"$EndElements").unwrap() + b"$EndElements".len();
            for len in cut_lengths(bytes.len()) {
                let r = parse(&bytes[..len]);
                if len >= complete {
                    assert_eq!(r.unwrap(), whole);
                } else {
                    assert!(
                        matches!(r, Err(MshError::Malformed { .. })),
                        "cut at {len}: {r:?}"
                    );
                }
            }
            // Random byte changes: any result but a panic.
            let mut seed: u64 = 0x2545_f491_4f6c_dd1d;
            let mut next = move || {
                seed ^= seed << 13;
                seed ^= seed >> 7;
                seed ^= seed << 17;
                seed
            };
            for _ in 0..FUZZ {
                let mut b = bytes.clone();
                for _ in 0..1 + next() % 4 {
                    let i = (next() % b.len() as u64) as usize;
                    b[i] = match next() % 4 {
                        0 => 0xff,
                        1 => b'\n',
                        2 => b'9',
                        _ => next() as u8,
                    };
                }
                let _ = parse(&b);
            }
        }
    }
}
