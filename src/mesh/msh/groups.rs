//! From what the sections hold to a [`Mesh`]: node tags become 0-based
//! indices ([`NodeIndex`]), and each physical group becomes one [`Group`]
//! with every element of every entity of the group's dimension that carries
//! the group's physical tag. An entity with several physical tags gives its
//! cells to each of those groups; a name in `$PhysicalNames` that no entity
//! carries is kept as an empty group. Groups come sorted by dimension, then
//! tag. A group without a name in `$PhysicalNames` is named by its tag.

use std::collections::{BTreeMap, HashMap};
use std::path::Path;

use super::msh_error::MshError;
use super::sections::{group_name, Block};
use crate::mesh::cells::{Cell, Group, Mesh};

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

/// The mesh of the file: node indices for tags, cells gathered by physical group.
pub(super) fn build_mesh(
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
        groups.entry((dim, tag)).or_insert_with(|| new_group(dim, tag));
    }
    let mut keys: Vec<_> = entities.iter().collect();
    keys.sort_by_key(|(k, _)| **k);
    for (&(dim, _), phys) in keys {
        for &p in phys {
            groups.entry((dim, p)).or_insert_with(|| new_group(dim, p));
        }
    }
    if groups.is_empty() {
        return Err(MshError::NoPhysicalGroups { path: path.to_path_buf() });
    }

    for block in &blocks {
        let phys = entities.get(&(block.dim, block.entity)).map(|p| p.as_slice()).unwrap_or(&[]);
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
            let cell = Cell { kind: block.kind, nodes, tag: etag };
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

    Ok(Mesh { coords, node_tags, groups: groups.into_values().collect() })
}
