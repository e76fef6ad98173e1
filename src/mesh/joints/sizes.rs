//! Mesh sizes for the points the cut makes. OpenCASCADE gives a point that
//! a boolean operation creates no mesh size, and gmsh then meshes the
//! curves through it as coarsely as it may (measured: a 4 m edge of a box
//! meshed at lc = 1 became one element). So before the cut the tool meshes
//! the uncut model's boundary (curves in 2D, surfaces in 3D) with the
//! user's own sizes, fields and options, and measures at every node the
//! mean length of the mesh edges there; after the cut each new point takes
//! the size measured at the nearest such node: what the user's `.geo`
//! asked for at that place.

use std::collections::HashMap;

/// Measured sizes at the nodes of the uncut model's boundary mesh, with a
/// uniform grid for nearest-node queries.
pub(super) struct Sizes {
    nodes: Vec<([f64; 3], f64)>,
    cell: f64,
    lo: [f64; 3],
    grid: HashMap<[i64; 3], Vec<usize>>,
    /// The highest cell index along each axis.
    span: [i64; 3],
}

impl Sizes {
    /// From node coordinates and elements (node indices into `coords`,
    /// by kind: `per` nodes each, 2 for lines, 3 for triangles, 4 for
    /// quadrangles): each node's size is the mean length of the element
    /// edges at it.
    pub(super) fn measure(coords: &[[f64; 3]], elements: &[(usize, Vec<usize>)]) -> Sizes {
        let mut sum = vec![(0.0, 0usize); coords.len()];
        for (per, s) in elements.iter().flat_map(|(per, nodes)| nodes.chunks_exact(*per).map(move |s| (*per, s))) {
            for a in 0..per {
                let b = (a + 1) % per;
                if per == 2 && a == 1 {
                    break;
                }
                let (p, q) = (coords[s[a]], coords[s[b]]);
                let l = ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt();
                for n in [s[a], s[b]] {
                    sum[n].0 += l;
                    sum[n].1 += 1;
                }
            }
        }
        let nodes: Vec<([f64; 3], f64)> =
            sum.iter().enumerate().filter(|(_, s)| s.1 > 0).map(|(i, s)| (coords[i], s.0 / s.1 as f64)).collect();
        Sizes::index(nodes)
    }

    fn index(nodes: Vec<([f64; 3], f64)>) -> Sizes {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for (p, _) in &nodes {
            for d in 0..3 {
                lo[d] = lo[d].min(p[d]);
                hi[d] = hi[d].max(p[d]);
            }
        }
        let extent = (0..3).map(|d| hi[d] - lo[d]).fold(0.0, f64::max);
        // about one node per cell along the model's largest extent squared
        let cell = (extent / (nodes.len() as f64).sqrt().max(1.0)).max(extent * 1e-9).max(f64::MIN_POSITIVE);
        let mut s = Sizes { nodes, cell, lo, grid: HashMap::new(), span: [0; 3] };
        s.span = s.key(hi);
        for i in 0..s.nodes.len() {
            let k = s.key(s.nodes[i].0);
            s.grid.entry(k).or_default().push(i);
        }
        s
    }

    fn key(&self, p: [f64; 3]) -> [i64; 3] {
        let k = |d: usize| ((p[d] - self.lo[d]) / self.cell).floor() as i64;
        [k(0), k(1), k(2)]
    }

    /// The size measured at the node nearest `p` (None without nodes).
    pub(super) fn at(&self, p: [f64; 3]) -> Option<f64> {
        if self.nodes.is_empty() {
            return None;
        }
        let c = self.key(p);
        let dist = |i: usize| {
            let q = self.nodes[i].0;
            ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt()
        };
        let nearest = |is: &mut dyn Iterator<Item = usize>, best: &mut Option<(f64, usize)>| {
            for i in is {
                let d = dist(i);
                if best.is_none_or(|b| d < b.0) {
                    *best = Some((d, i));
                }
            }
        };
        let mut best: Option<(f64, usize)> = None;
        let outside = (0..3).map(|d| (-c[d]).max(c[d] - self.span[d])).max().unwrap_or(0);
        if outside > 4 {
            // far outside the model: every node
            nearest(&mut (0..self.nodes.len()), &mut best);
            return best.map(|(_, i)| self.nodes[i].1);
        }
        // rings of cells around p; after ring r every node not yet seen is
        // at least r cells away
        for r in 0i64.. {
            for dx in -r..=r {
                for dy in -r..=r {
                    for dz in -r..=r {
                        if dx.abs().max(dy.abs()).max(dz.abs()) != r {
                            continue;
                        }
                        if let Some(v) = self.grid.get(&[c[0] + dx, c[1] + dy, c[2] + dz]) {
                            nearest(&mut v.iter().copied(), &mut best);
                        }
                    }
                }
            }
            if best.is_some_and(|(d, _)| d <= r as f64 * self.cell)
                || r > self.span.iter().max().copied().unwrap_or(0) + 8
            {
                break;
            }
        }
        best.map(|(_, i)| self.nodes[i].1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A square's boundary meshed at 1 along y = 0 and at 0.25 along y = 4:
    /// a point near each side takes that side's size, a corner the mean of
    /// its two edges.
    #[test]
    fn nearest_node_size() {
        let mut coords = Vec::new();
        let mut lines = Vec::new();
        for i in 0..=4 {
            coords.push([i as f64, 0.0, 0.0]);
        }
        for i in 0..4 {
            lines.extend([i, i + 1]);
        }
        let base = coords.len();
        for i in 0..=16 {
            coords.push([i as f64 * 0.25, 4.0, 0.0]);
        }
        for i in 0..16 {
            lines.extend([base + i, base + i + 1]);
        }
        let s = Sizes::measure(&coords, &[(2, lines)]);
        assert_eq!(s.at([2.1, 0.3, 0.0]), Some(1.0));
        assert_eq!(s.at([1.1, 3.8, 0.0]), Some(0.25));
        assert_eq!(s.at([0.0, 0.0, 0.0]), Some(1.0));
        assert_eq!(s.at([100.0, -50.0, 0.0]), Some(1.0));
        // triangles: an equilateral one of side 2
        let tri = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [1.0, 3f64.sqrt(), 0.0]];
        let s = Sizes::measure(&tri, &[(3, vec![0, 1, 2])]);
        assert!((s.at([1.0, 0.5, 0.0]).unwrap_or(0.0) - 2.0).abs() < 1e-12);
        assert_eq!(Sizes::measure(&[], &[]).at([0.0; 3]), None);
    }
}
