//! The sections of an MSH 4.1 file that the reader needs, each read by its
//! own function: `$MeshFormat` (version, encoding, size of `size_t`, byte
//! order), `$PhysicalNames`, `$Entities` (the physical tags of each entity),
//! `$Nodes` (coordinates and tags in file order) and `$Elements` (the blocks
//! of supported kinds that some physical group uses). What each returns is
//! raw: tags, not indices; [`super::groups`] turns it into a [`super::Mesh`].
//!
//! A count read from the file never sizes an allocation beyond what the rest
//! of the file can hold ([`Reader::capacity`]).

use std::collections::HashMap;

use super::msh_error::MshError;
use super::reader::Reader;
use crate::mesh::cell_kind::CellKind;

/// A group's name from `$PhysicalNames`, or its tag when it has none.
pub(super) fn group_name(names: &[(i32, i32, String)], dim: i32, tag: i32) -> String {
    names.iter().find(|(d, t, _)| *d == dim && *t == tag).map(|(_, _, n)| n.clone()).unwrap_or_else(|| tag.to_string())
}

/// Name and node count of gmsh element types (codes of the MSH format), for
/// messages and for skipping blocks that belong to no physical group.
fn gmsh_type(code: i32) -> Option<(&'static str, usize)> {
    if let Some(k) = CellKind::from_gmsh(code) {
        return Some((k.name(), k.n_nodes()));
    }
    Some(match code {
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
        90 => ("prism40", 40),
        92 => ("hex64", 64),
        93 => ("hex125", 125),
        118 => ("pyramid30", 30),
        _ => return None,
    })
}

/// Parsed `$Elements` block of a supported kind.
pub(super) struct Block {
    pub(super) dim: i32,
    pub(super) entity: i32,
    pub(super) kind: CellKind,
    pub(super) tags: Vec<u64>,
    /// `kind.n_nodes()` node tags per element.
    pub(super) nodes: Vec<u64>,
}

/// `$MeshFormat`: version, ASCII/binary, size of `size_t`, endianness.
pub(super) fn read_header(r: &mut Reader) -> Result<(), MshError> {
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
        return Err(r.malformed(format!("expected the format version 4.1, found `{version}`")));
    }
    let file_type: i32 = r.parse_word("the file type (0 ASCII, 1 binary)")?;
    let data_size: usize = r.parse_word("the size of size_t")?;
    if r.at_end() {
        return Err(r.malformed("expected the end of the format line"));
    }
    if version != "4.1" {
        return Err(MshError::Version { path: r.path.to_path_buf(), version });
    }
    if !(file_type == 0 || file_type == 1) {
        return Err(r.malformed(format!("file type {file_type} is neither 0 (ASCII) nor 1 (binary)")));
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
pub(super) fn read_physical_names(r: &mut Reader) -> Result<Vec<(i32, i32, String)>, MshError> {
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
pub(super) fn read_entities(r: &mut Reader) -> Result<HashMap<(i32, i32), Vec<i32>>, MshError> {
    let mut counts = [0usize; 4];
    for (dim, c) in counts.iter_mut().enumerate() {
        *c = r.count(
            ["the number of points", "the number of curves", "the number of surfaces", "the number of volumes"][dim],
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
pub(super) fn read_nodes(r: &mut Reader) -> Result<(Vec<[f64; 3]>, Vec<u64>), MshError> {
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
        return Err(r.malformed(format!("the header announces {n_nodes} nodes, the blocks hold {}", tags.len())));
    }
    Ok((coords, tags))
}

/// `$Elements`: blocks of supported kinds whose entity carries a physical tag.
/// Blocks of entities without physical tags are skipped; an unsupported kind in
/// a physical group is an error.
pub(super) fn read_elements(
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
        let phys = entities.get(&(dim, entity)).map(|p| p.as_slice()).unwrap_or(&[]);
        let kind = CellKind::from_gmsh(code);
        let n_per = match (kind, gmsh_type(code)) {
            (Some(k), _) if phys.is_empty() || k.dim() as i32 == dim => k.n_nodes(),
            (Some(k), _) => return Err(r.malformed(format!("{} elements in an entity of dimension {dim}", k.name()))),
            (None, known) if !phys.is_empty() => {
                return Err(MshError::UnsupportedElement {
                    path: r.path.to_path_buf(),
                    code,
                    name: known.map(|(name, _)| name).unwrap_or("unknown type").to_string(),
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
            let len = n.checked_mul(per_elem).and_then(|v| v.checked_mul(r.size_t));
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
            blocks.push(Block { dim, entity, kind, tags, nodes });
        }
    }
    Ok(blocks)
}
