//! The mesh's cells as one body of material cut by contact facets: which
//! cells a facet bounds, which cells touch through a face, the blocks
//! (connected pieces of a body between its contact facets) and, at every
//! node of a contact facet, its fans (the cells around the node that touch
//! through faces no contact facet separates).
//!
//! Two cells touch through a face when they share at least `dim` corners
//! (2 in a plane model, 3 in a solid): in a conforming mesh those corners
//! are the face, whatever the cell kinds. No face tables are needed, so
//! every element kind gmsh writes takes part.
//!
//! A node of a contact facet gets one model node per fan: where joints
//! cross, every block around the node keeps its own copy; at the tip of a
//! joint that ends inside a body the cells around the node form one fan,
//! and the node stays shared (the joint is closed there). Bodies that share
//! a face without a contact between them are in one fan: they stay bonded.

use std::collections::HashMap;

use crate::mesh::Cell;

/// The sorted corner nodes of a face or facet: its key.
pub(super) type FaceKey = Vec<usize>;

/// Corner nodes of a cell or facet, sorted.
pub(super) fn corner_key(c: &Cell) -> FaceKey {
    let mut k = c.nodes[..c.kind.n_corners()].to_vec();
    k.sort_unstable();
    k
}

/// Disjoint sets over `0..n` with path halving.
pub(crate) struct UnionFind(Vec<usize>);

impl UnionFind {
    /// Every element of `0..n` alone.
    pub(crate) fn new(n: usize) -> UnionFind {
        UnionFind((0..n).collect())
    }
    /// The root of i's set: its smallest element (see [`UnionFind::join`]).
    pub(crate) fn root(&mut self, mut i: usize) -> usize {
        while self.0[i] != i {
            self.0[i] = self.0[self.0[i]];
            i = self.0[i];
        }
        i
    }
    /// Joins the sets of a and b; the smaller root becomes the root.
    pub(crate) fn join(&mut self, a: usize, b: usize) {
        let (x, y) = (self.root(a), self.root(b));
        if x != y {
            self.0[x.max(y)] = x.min(y);
        }
    }
    /// The sets, each ascending, in order of their smallest element.
    pub(crate) fn groups(&mut self) -> Vec<Vec<usize>> {
        let mut at = vec![usize::MAX; self.0.len()];
        let mut groups: Vec<Vec<usize>> = Vec::new();
        for i in 0..self.0.len() {
            let r = self.root(i);
            if at[r] == usize::MAX {
                at[r] = groups.len();
                groups.push(Vec::new());
            }
            groups[at[r]].push(i);
        }
        groups
    }
}

/// Every cell of the model's bodies, in body order, with node incidence.
pub(super) struct Topology<'a> {
    /// The cells, and the body (index of the description's bodies) of each.
    pub cells: Vec<&'a Cell>,
    pub body: Vec<usize>,
    /// Spatial dimension: corners two cells must share to touch through a face.
    dim: usize,
    /// Node -> cells containing it (any node of the cell), CSR.
    start: Vec<usize>,
    list: Vec<usize>,
}

impl<'a> Topology<'a> {
    pub(super) fn new(n_nodes: usize, dim: usize, bodies: &[&'a [Cell]]) -> Topology<'a> {
        let mut cells = Vec::new();
        let mut body = Vec::new();
        for (b, cs) in bodies.iter().enumerate() {
            for c in cs.iter() {
                cells.push(c);
                body.push(b);
            }
        }
        let mut start = vec![0usize; n_nodes + 1];
        for c in &cells {
            for &n in &c.nodes {
                start[n + 1] += 1;
            }
        }
        for i in 0..n_nodes {
            start[i + 1] += start[i];
        }
        let mut fill = start.clone();
        let mut list = vec![0; start[n_nodes]];
        for (ci, c) in cells.iter().enumerate() {
            for &n in &c.nodes {
                list[fill[n]] = ci;
                fill[n] += 1;
            }
        }
        Topology { cells, body, dim, start, list }
    }

    /// Cells containing node n.
    pub(super) fn at(&self, n: usize) -> &[usize] {
        &self.list[self.start[n]..self.start[n + 1]]
    }

    /// Cells containing every corner of `facet` (the cells it bounds).
    pub(super) fn bounding(&self, facet: &Cell) -> Vec<usize> {
        let corners = &facet.nodes[..facet.kind.n_corners()];
        self.at(corners[0])
            .iter()
            .copied()
            .filter(|&c| corners[1..].iter().all(|n| self.cells[c].nodes.contains(n)))
            .collect()
    }

    /// The model node mesh node `n` became in cell `c`, read from the cells
    /// in model nodes (`cells`, as the contact split left them): where a
    /// node was copied, each cell knows its own copy.
    pub(super) fn node_in(&self, cells: &[Cell], c: usize, n: usize) -> usize {
        let at = self.cells[c].nodes.iter().position(|&x| x == n).expect("the node is in the cell");
        cells[c].nodes[at]
    }

    /// The corners cells a and b share, sorted, when they touch through a face.
    fn shared_face(&self, a: usize, b: usize) -> Option<FaceKey> {
        let (ca, cb) = (self.cells[a], self.cells[b]);
        let mut shared: Vec<usize> = ca.nodes[..ca.kind.n_corners()]
            .iter()
            .copied()
            .filter(|n| cb.nodes[..cb.kind.n_corners()].contains(n))
            .collect();
        (shared.len() >= self.dim).then(|| {
            shared.sort_unstable();
            shared
        })
    }

    /// The blocks: connected pieces of each body through faces that are
    /// not in `cut` (the contact facets). Returns the block of every cell,
    /// numbered in order of each block's first cell.
    pub(super) fn blocks(&self, cut: &HashMap<FaceKey, usize>) -> Vec<usize> {
        let n = self.cells.len();
        let mut sets = UnionFind::new(n);
        // cells sharing a corner, counted per neighbour: dim shared corners make a face
        let mut count: HashMap<usize, usize> = HashMap::new();
        for a in 0..n {
            count.clear();
            let ca = self.cells[a];
            for &v in &ca.nodes[..ca.kind.n_corners()] {
                for &b in self.at(v) {
                    if b > a
                        && self.body[b] == self.body[a]
                        && self.cells[b].nodes[..self.cells[b].kind.n_corners()].contains(&v)
                    {
                        *count.entry(b).or_insert(0) += 1;
                    }
                }
            }
            for (&b, &k) in &count {
                if k >= self.dim {
                    if let Some(face) = self.shared_face(a, b) {
                        if !cut.contains_key(&face) {
                            sets.join(a, b);
                        }
                    }
                }
            }
        }
        let mut number: HashMap<usize, usize> = HashMap::new();
        (0..n)
            .map(|c| {
                let r = sets.root(c);
                let next = number.len();
                *number.entry(r).or_insert(next)
            })
            .collect()
    }

    /// The fans of node n: its cells grouped by touching through faces
    /// that are not in `cut`, each fan's cells ascending, fans in order of
    /// their first cell.
    pub(super) fn fans(&self, n: usize, cut: &HashMap<FaceKey, usize>) -> Vec<Vec<usize>> {
        let cells = self.at(n);
        let mut sets = UnionFind::new(cells.len());
        for i in 0..cells.len() {
            for j in i + 1..cells.len() {
                if let Some(face) = self.shared_face(cells[i], cells[j]) {
                    if !cut.contains_key(&face) {
                        sets.join(i, j);
                    }
                }
            }
        }
        let mut fans: Vec<Vec<usize>> = Vec::new();
        let mut fan_of_root: HashMap<usize, usize> = HashMap::new();
        for i in 0..cells.len() {
            let r = sets.root(i);
            let f = *fan_of_root.entry(r).or_insert_with(|| {
                fans.push(Vec::new());
                fans.len() - 1
            });
            fans[f].push(cells[i]);
        }
        for f in &mut fans {
            f.sort_unstable();
        }
        fans.sort_by_key(|f| f[0]);
        fans
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::CellKind;

    fn quad(nodes: [usize; 4], tag: u64) -> Cell {
        Cell { kind: CellKind::Quad4, nodes: nodes.to_vec(), tag }
    }

    /// Joined in any order, every set's root is its smallest element and
    /// the sets come in order of it.
    #[test]
    fn groups_come_in_order_of_their_smallest_element() {
        let mut sets = UnionFind::new(7);
        for (a, b) in [(5, 3), (6, 1), (3, 6), (4, 2)] {
            sets.join(a, b);
        }
        assert_eq!(sets.groups(), vec![vec![0], vec![1, 3, 5, 6], vec![2, 4]]);
        assert_eq!((0..7).map(|i| sets.root(i)).collect::<Vec<_>>(), vec![0, 1, 2, 1, 2, 1, 1]);
    }

    /// A 2 x 2 square of quads (nodes 0..9, row-major from the bottom left)
    /// cut along x = 1 and y = 1: four blocks, four fans at the centre node.
    #[test]
    fn crossing_cuts_make_four_blocks_and_four_fans() {
        let cells = vec![quad([0, 1, 4, 3], 1), quad([1, 2, 5, 4], 2), quad([3, 4, 7, 6], 3), quad([4, 5, 8, 7], 4)];
        let topo = Topology::new(9, 2, &[&cells]);
        let line = |a: usize, b: usize| Cell { kind: CellKind::Line2, nodes: vec![a, b], tag: 0 };
        let mut cut = HashMap::new();
        for (i, f) in [line(1, 4), line(4, 7), line(3, 4), line(4, 5)].iter().enumerate() {
            cut.insert(corner_key(f), i);
        }
        assert_eq!(topo.blocks(&cut), vec![0, 1, 2, 3]);
        assert_eq!(topo.fans(4, &cut), vec![vec![0], vec![1], vec![2], vec![3]]);
        // a cut along y = 1 alone: two blocks; the cut's middle node splits in two
        let mut half = HashMap::new();
        half.insert(corner_key(&line(3, 4)), 0);
        half.insert(corner_key(&line(4, 5)), 1);
        assert_eq!(topo.blocks(&half), vec![0, 0, 1, 1]);
        assert_eq!(topo.fans(4, &half), vec![vec![0, 1], vec![2, 3]]);
        // a joint ending inside (only x = 1 below the centre): one block, the tip not split
        let mut tip = HashMap::new();
        tip.insert(corner_key(&line(1, 4)), 0);
        assert_eq!(topo.blocks(&tip), vec![0, 0, 0, 0]);
        assert_eq!(topo.fans(4, &tip), vec![vec![0, 1, 2, 3]]);
        assert_eq!(topo.fans(1, &tip), vec![vec![0], vec![1]]);
        assert_eq!(topo.bounding(&line(4, 5)), vec![1, 3]);
    }
}
