//! VTK XML files for ParaView: one UnstructuredGrid (`.vtu`) per result and a
//! collection (`.pvd`) that makes a series of them a time series.
//!
//! The rest of the program keeps cells in gmsh's node order; this module is
//! the only place that reorders gmsh→VTK node order (tet10, hex20 and hex27
//! differ, every other kind is the same in both programs). Data arrays are
//! written as ZLib-compressed (level 1) base64 inline binary, the way vtkio
//! 0.7 writes them, which ParaView and meshio both read. Building the bytes
//! never touches the file system; `super::files::Staged` writes them.

use vtkio::model::{
    Attribute, Attributes, ByteOrder, CellType, Cells, DataSet, UnstructuredGridPiece, Version,
    VertexNumbers, Vtk,
};
use vtkio::xml::Compressor;

use super::files::OutputError;
use crate::mesh::{Cell, CellKind};

/// ZLib level 1: nearly the size of the higher levels at a fraction of the time.
const ZLIB_LEVEL: u32 = 1;

/// A floating-point data array: `n_comp` components per point (or cell),
/// stored point after point: `values.len() == n_comp * count`.
#[derive(Clone, Copy, Debug)]
pub struct Field<'a> {
    pub name: &'a str,
    pub n_comp: usize,
    pub values: &'a [f64],
}

/// An integer scalar per cell (for instance the body a cell belongs to).
#[derive(Clone, Copy, Debug)]
pub struct IntField<'a> {
    pub name: &'a str,
    pub values: &'a [i32],
}

/// VTK cell type number of a gmsh cell kind.
pub fn vtk_cell_type(kind: CellKind) -> u8 {
    vtkio_cell_type(kind) as u8
}

fn vtkio_cell_type(kind: CellKind) -> CellType {
    match kind {
        CellKind::Point1 => CellType::Vertex,
        CellKind::Line2 => CellType::Line,
        CellKind::Line3 => CellType::QuadraticEdge,
        CellKind::Tri3 => CellType::Triangle,
        CellKind::Tri6 => CellType::QuadraticTriangle,
        CellKind::Quad4 => CellType::Quad,
        CellKind::Quad8 => CellType::QuadraticQuad,
        CellKind::Quad9 => CellType::BiquadraticQuad,
        CellKind::Tet4 => CellType::Tetra,
        CellKind::Tet10 => CellType::QuadraticTetra,
        CellKind::Hex8 => CellType::Hexahedron,
        CellKind::Hex20 => CellType::QuadraticHexahedron,
        CellKind::Hex27 => CellType::TriquadraticHexahedron,
    }
}

/// gmsh mid-edge nodes 8 (edge 2–3) and 9 (edge 1–3) are VTK's 9 and 8.
const TET10_VTK_FROM_GMSH: [usize; 10] = [0, 1, 2, 3, 4, 5, 6, 7, 9, 8];

/// VTK's mid-edge nodes on edges (0,1) (1,2) (2,3) (3,0) (4,5) (5,6) (6,7)
/// (7,4) (0,4) (1,5) (2,6) (3,7), taken from gmsh's numbering of the same
/// edges: gmsh numbers them (0,1)=8 (0,3)=9 (0,4)=10 (1,2)=11 (1,5)=12
/// (2,3)=13 (2,6)=14 (3,7)=15 (4,5)=16 (4,7)=17 (5,6)=18 (6,7)=19.
const HEX20_VTK_FROM_GMSH: [usize; 20] = [
    0, 1, 2, 3, 4, 5, 6, 7, //
    8, 11, 13, 9, 16, 18, 19, 17, 10, 12, 14, 15,
];

/// As hex20, then VTK's face centres x=-1, x=+1, y=-1, y=+1, z=-1, z=+1
/// (gmsh: 20 z=-1, 21 y=-1, 22 x=-1, 23 x=+1, 24 y=+1, 25 z=+1) and the
/// centre (26 in both).
const HEX27_VTK_FROM_GMSH: [usize; 27] = [
    0, 1, 2, 3, 4, 5, 6, 7, //
    8, 11, 13, 9, 16, 18, 19, 17, 10, 12, 14, 15, //
    22, 23, 21, 24, 20, 25, 26,
];

/// For kinds whose node order differs: entry `i` is the gmsh position of
/// VTK node `i`. `None` means both programs use the same order.
pub(crate) fn vtk_from_gmsh(kind: CellKind) -> Option<&'static [usize]> {
    match kind {
        CellKind::Tet10 => Some(&TET10_VTK_FROM_GMSH),
        CellKind::Hex20 => Some(&HEX20_VTK_FROM_GMSH),
        CellKind::Hex27 => Some(&HEX27_VTK_FROM_GMSH),
        _ => None,
    }
}

/// Checks that a field has `n_comp * count` values.
fn check_len(
    location: &'static str,
    name: &str,
    n_comp: usize,
    count: usize,
    len: usize,
) -> Result<(), OutputError> {
    if n_comp == 0 {
        return Err(OutputError::NoComponents {
            location,
            field: name.to_string(),
        });
    }
    if u32::try_from(n_comp).is_err() || n_comp.checked_mul(count) != Some(len) {
        return Err(OutputError::FieldLength {
            location,
            field: name.to_string(),
            n_comp,
            count,
            len,
        });
    }
    Ok(())
}

/// The bytes of a VTU (XML UnstructuredGrid) file: points (3D; 2D meshes have z = 0), cells with gmsh node order
/// (indices into points) written in VTK order and type, point data, cell data.
///
/// Every field must have `n_comp * points.len()` (point data) or
/// `n_comp * cells.len()` (cell data) values, every cell `kind.n_nodes()`
/// nodes, each below `points.len()`; otherwise the error names the field or
/// the cell and nothing is built.
pub fn vtu_bytes(
    points: &[[f64; 3]],
    cells: &[Cell],
    point_data: &[Field<'_>],
    cell_data: &[Field<'_>],
    cell_int_data: &[IntField<'_>],
) -> Result<Vec<u8>, OutputError> {
    let n_points = points.len();
    let n_cells = cells.len();
    // vtkio writes NumberOfPoints and NumberOfCells as u32.
    if u32::try_from(n_points).is_err() {
        return Err(OutputError::TooLarge {
            what: "points",
            count: n_points,
        });
    }
    if u32::try_from(n_cells).is_err() {
        return Err(OutputError::TooLarge {
            what: "cells",
            count: n_cells,
        });
    }

    for f in point_data {
        check_len("point", f.name, f.n_comp, n_points, f.values.len())?;
    }
    for f in cell_data {
        check_len("cell", f.name, f.n_comp, n_cells, f.values.len())?;
    }
    for f in cell_int_data {
        check_len("cell", f.name, 1, n_cells, f.values.len())?;
    }

    let n_conn: usize = cells.iter().map(|c| c.nodes.len()).sum();
    let mut connectivity = Vec::with_capacity(n_conn);
    let mut offsets = Vec::with_capacity(n_cells);
    let mut types = Vec::with_capacity(n_cells);
    for (index, cell) in cells.iter().enumerate() {
        let expected = cell.kind.n_nodes();
        if cell.nodes.len() != expected {
            return Err(OutputError::CellNodes {
                index,
                tag: cell.tag,
                kind: cell.kind.name(),
                expected,
                actual: cell.nodes.len(),
            });
        }
        let push = |node: usize, connectivity: &mut Vec<u64>| {
            if node >= n_points {
                return Err(OutputError::NodeOutOfRange {
                    index,
                    tag: cell.tag,
                    node,
                    n_points,
                });
            }
            connectivity.push(node as u64);
            Ok(())
        };
        match vtk_from_gmsh(cell.kind) {
            Some(perm) => {
                for &g in perm {
                    push(cell.nodes[g], &mut connectivity)?;
                }
            }
            None => {
                for &node in &cell.nodes {
                    push(node, &mut connectivity)?;
                }
            }
        }
        offsets.push(connectivity.len() as u64);
        types.push(vtkio_cell_type(cell.kind));
    }

    let coords: Vec<f64> = points.iter().flatten().copied().collect();
    let attribute = |f: &Field<'_>| {
        // n_comp fits in u32: checked above.
        Attribute::generic(f.name, f.n_comp as u32).with_data(f.values.to_vec())
    };
    let data = Attributes {
        point: point_data.iter().map(attribute).collect(),
        cell: cell_data
            .iter()
            .map(attribute)
            .chain(
                cell_int_data
                    .iter()
                    .map(|f| Attribute::generic(f.name, 1).with_data(f.values.to_vec())),
            )
            .collect(),
    };

    let vtk = Vtk {
        version: Version::new_xml(1, 0),
        title: String::new(),
        byte_order: ByteOrder::LittleEndian,
        file_path: None,
        data: DataSet::inline(UnstructuredGridPiece {
            points: coords.into(),
            cells: Cells {
                cell_verts: VertexNumbers::XML {
                    connectivity,
                    offsets,
                },
                types,
            },
            data,
        }),
    };
    let file = vtk
        .try_into_xml_format(Compressor::ZLib, ZLIB_LEVEL)
        .map_err(|e| OutputError::Vtk(e.to_string()))?;
    let mut bytes = Vec::new();
    file.write(&mut bytes)
        .map_err(|e| OutputError::Vtk(e.to_string()))?;
    with_piece_counts(bytes, n_points, n_cells)
}

/// vtkio leaves out `NumberOfPoints` and `NumberOfCells` when they are zero,
/// and VTK (so ParaView) and meshio then refuse the file: write the `<Piece>`
/// tag with both. An unstructured grid's piece has no other attributes.
fn with_piece_counts(
    bytes: Vec<u8>,
    n_points: usize,
    n_cells: usize,
) -> Result<Vec<u8>, OutputError> {
    let missing = || OutputError::Vtk("vtkio wrote no <Piece> element".to_string());
    let start = bytes
        .windows(6)
        .position(|w| w == b"<Piece")
        .ok_or_else(missing)?;
    let len = bytes[start..]
        .iter()
        .position(|&b| b == b'>')
        .ok_or_else(missing)?;
    let tag = format!("<Piece NumberOfPoints=\"{n_points}\" NumberOfCells=\"{n_cells}\"");
    let end = if bytes[start + len - 1] == b'/' {
        start + len - 1
    } else {
        start + len
    };
    let mut out = Vec::with_capacity(bytes.len() + 40);
    out.extend_from_slice(&bytes[..start]);
    out.extend_from_slice(tag.as_bytes());
    out.extend_from_slice(&bytes[end..]);
    Ok(out)
}

/// Escapes text for an XML attribute value in double quotes.
fn xml_attr(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            '\t' => out.push_str("&#9;"),
            '\n' => out.push_str("&#10;"),
            '\r' => out.push_str("&#13;"),
            _ => out.push(c),
        }
    }
    out
}

/// The bytes of a ParaView collection (.pvd) listing (time, file name) datasets, so ParaView opens them as a time series.
///
/// File names are written as given (relative names are resolved by ParaView
/// against the `.pvd`'s directory). Times use Rust's shortest round-trip
/// form (`1.0`, `0.25`, `1e-7`).
pub fn pvd_bytes(steps: &[(f64, String)]) -> Vec<u8> {
    let mut s = String::from(
        "<?xml version=\"1.0\"?>\n\
         <VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n  <Collection>\n",
    );
    for (time, file) in steps {
        s.push_str(&format!(
            "    <DataSet timestep=\"{}\" group=\"\" part=\"0\" file=\"{}\"/>\n",
            xml_attr(&format!("{time:?}")),
            xml_attr(file)
        ));
    }
    s.push_str("  </Collection>\n</VTKFile>\n");
    s.into_bytes()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::files::Staged;
    use std::path::{Path, PathBuf};
    use std::process::Command;

    // ---- reference elements in gmsh's order, built from gmsh's tables ----

    /// gmsh's edges of the tetrahedron, in gmsh's mid-edge node order (4..9).
    const GMSH_TET_EDGES: [[usize; 2]; 6] = [[0, 1], [1, 2], [2, 0], [3, 0], [3, 2], [3, 1]];
    /// gmsh's edges of the hexahedron, in gmsh's mid-edge node order (8..19).
    const GMSH_HEX_EDGES: [[usize; 2]; 12] = [
        [0, 1],
        [0, 3],
        [0, 4],
        [1, 2],
        [1, 5],
        [2, 3],
        [2, 6],
        [3, 7],
        [4, 5],
        [4, 7],
        [5, 6],
        [6, 7],
    ];
    /// gmsh's faces of the hexahedron, in gmsh's face-centre order (20..25).
    const GMSH_HEX_FACES: [[usize; 4]; 6] = [
        [0, 3, 2, 1],
        [0, 1, 5, 4],
        [0, 4, 7, 3],
        [1, 2, 6, 5],
        [2, 3, 7, 6],
        [4, 5, 6, 7],
    ];

    /// VTK's edges of the tetrahedron (vtkQuadraticTetra, nodes 4..9).
    const VTK_TET_EDGES: [[usize; 2]; 6] = [[0, 1], [1, 2], [2, 0], [0, 3], [1, 3], [2, 3]];
    /// VTK's edges of the hexahedron (vtkQuadraticHexahedron, nodes 8..19).
    const VTK_HEX_EDGES: [[usize; 2]; 12] = [
        [0, 1],
        [1, 2],
        [2, 3],
        [3, 0],
        [4, 5],
        [5, 6],
        [6, 7],
        [7, 4],
        [0, 4],
        [1, 5],
        [2, 6],
        [3, 7],
    ];
    /// VTK's face centres of vtkTriQuadraticHexahedron (nodes 20..25):
    /// x=-1, x=+1, y=-1, y=+1, z=-1, z=+1.
    const VTK_HEX_FACES: [[usize; 4]; 6] = [
        [0, 3, 7, 4],
        [1, 2, 6, 5],
        [0, 1, 5, 4],
        [3, 2, 6, 7],
        [0, 1, 2, 3],
        [4, 5, 6, 7],
    ];

    fn mean(pts: &[[f64; 3]], ids: &[usize]) -> [f64; 3] {
        let mut m = [0.0; 3];
        for &i in ids {
            for d in 0..3 {
                m[d] += pts[i][d];
            }
        }
        m.map(|x| x / ids.len() as f64)
    }

    /// Node coordinates of the reference element of `kind`, in gmsh order.
    fn gmsh_reference(kind: CellKind) -> Vec<[f64; 3]> {
        let tri = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let quad = vec![
            [-1.0, -1.0, 0.0],
            [1.0, -1.0, 0.0],
            [1.0, 1.0, 0.0],
            [-1.0, 1.0, 0.0],
        ];
        let tet = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
        ];
        let hex = vec![
            [-1.0, -1.0, -1.0],
            [1.0, -1.0, -1.0],
            [1.0, 1.0, -1.0],
            [-1.0, 1.0, -1.0],
            [-1.0, -1.0, 1.0],
            [1.0, -1.0, 1.0],
            [1.0, 1.0, 1.0],
            [-1.0, 1.0, 1.0],
        ];
        let with_edges = |mut p: Vec<[f64; 3]>, edges: &[[usize; 2]]| {
            for e in edges {
                let m = mean(&p, e);
                p.push(m);
            }
            p
        };
        let ring = |n: usize| (0..n).map(|i| [i, (i + 1) % n]).collect::<Vec<_>>();
        match kind {
            CellKind::Point1 => vec![[0.0, 0.0, 0.0]],
            CellKind::Line2 => vec![[-1.0, 0.0, 0.0], [1.0, 0.0, 0.0]],
            CellKind::Line3 => vec![[-1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 0.0]],
            CellKind::Tri3 => tri,
            CellKind::Tri6 => with_edges(tri, &ring(3)),
            CellKind::Quad4 => quad,
            CellKind::Quad8 => with_edges(quad, &ring(4)),
            CellKind::Quad9 => {
                let mut p = with_edges(quad, &ring(4));
                p.push([0.0, 0.0, 0.0]);
                p
            }
            CellKind::Tet4 => tet,
            CellKind::Tet10 => with_edges(tet, &GMSH_TET_EDGES),
            CellKind::Hex8 => hex,
            CellKind::Hex20 => with_edges(hex, &GMSH_HEX_EDGES),
            CellKind::Hex27 => {
                let mut p = with_edges(hex, &GMSH_HEX_EDGES);
                for f in &GMSH_HEX_FACES {
                    let m = mean(&p, f);
                    p.push(m);
                }
                p.push([0.0, 0.0, 0.0]);
                p
            }
        }
    }

    fn close(a: [f64; 3], b: [f64; 3]) -> bool {
        (0..3).all(|d| (a[d] - b[d]).abs() < 1e-12)
    }

    /// Checks VTK-ordered coordinates against VTK's definition of the kind:
    /// corners where the reference puts them, every mid-edge node at the
    /// midpoint of the corners VTK expects, face centres at the mean of their
    /// corners, the centre at the mean of all, no two nodes together.
    fn vtk_geometry_error(kind: CellKind, vtk: &[[f64; 3]]) -> Option<String> {
        let (edges, faces): (Vec<[usize; 2]>, &[[usize; 4]]) = match kind {
            CellKind::Line3 => (vec![[0, 1]], &[]),
            CellKind::Tri6 => (vec![[0, 1], [1, 2], [2, 0]], &[]),
            CellKind::Quad8 | CellKind::Quad9 => (vec![[0, 1], [1, 2], [2, 3], [3, 0]], &[]),
            CellKind::Tet10 => (VTK_TET_EDGES.to_vec(), &[]),
            CellKind::Hex20 => (VTK_HEX_EDGES.to_vec(), &[]),
            CellKind::Hex27 => (VTK_HEX_EDGES.to_vec(), &VTK_HEX_FACES),
            _ => (vec![], &[]),
        };
        if vtk.len() != kind.n_nodes() {
            return Some(format!("{} nodes, expected {}", vtk.len(), kind.n_nodes()));
        }
        let nc = kind.n_corners();
        let gmsh = gmsh_reference(kind);
        for i in 0..nc {
            if !close(vtk[i], gmsh[i]) {
                return Some(format!(
                    "corner {i} at {:?}, expected {:?}",
                    vtk[i], gmsh[i]
                ));
            }
        }
        for (k, e) in edges.iter().enumerate() {
            let i = nc + k;
            if !close(vtk[i], mean(vtk, e)) {
                return Some(format!(
                    "VTK node {i} at {:?} is not the midpoint of corners {e:?}",
                    vtk[i]
                ));
            }
        }
        for (k, f) in faces.iter().enumerate() {
            let i = nc + edges.len() + k;
            if !close(vtk[i], mean(vtk, f)) {
                return Some(format!(
                    "VTK node {i} at {:?} is not the centre of face {f:?}",
                    vtk[i]
                ));
            }
        }
        let n_known = nc + edges.len() + faces.len();
        if kind.n_nodes() > n_known {
            let corners: Vec<usize> = (0..nc).collect();
            if kind.n_nodes() != n_known + 1 || !close(vtk[n_known], mean(vtk, &corners)) {
                return Some(format!("VTK node {n_known} is not the centre"));
            }
        }
        for i in 0..vtk.len() {
            for j in 0..i {
                if close(vtk[i], vtk[j]) {
                    return Some(format!("nodes {i} and {j} coincide"));
                }
            }
        }
        None
    }

    #[test]
    fn cell_type_numbers() {
        let expected = [
            (CellKind::Point1, 1),
            (CellKind::Line2, 3),
            (CellKind::Line3, 21),
            (CellKind::Tri3, 5),
            (CellKind::Tri6, 22),
            (CellKind::Quad4, 9),
            (CellKind::Quad8, 23),
            (CellKind::Quad9, 28),
            (CellKind::Tet4, 10),
            (CellKind::Tet10, 24),
            (CellKind::Hex8, 12),
            (CellKind::Hex20, 25),
            (CellKind::Hex27, 29),
        ];
        assert_eq!(expected.len(), CellKind::ALL.len());
        for (kind, code) in expected {
            assert_eq!(vtk_cell_type(kind), code, "{kind:?}");
        }
    }

    #[test]
    fn permutations_put_nodes_where_vtk_expects_them() {
        for kind in CellKind::ALL {
            let gmsh = gmsh_reference(kind);
            assert_eq!(gmsh.len(), kind.n_nodes(), "{kind:?}");
            let vtk: Vec<[f64; 3]> = match vtk_from_gmsh(kind) {
                Some(perm) => {
                    // A permutation of 0..n.
                    let mut sorted = perm.to_vec();
                    sorted.sort_unstable();
                    assert_eq!(sorted, (0..kind.n_nodes()).collect::<Vec<_>>(), "{kind:?}");
                    perm.iter().map(|&g| gmsh[g]).collect()
                }
                None => gmsh.clone(),
            };
            assert_eq!(vtk_geometry_error(kind, &vtk), None, "{kind:?}");
        }
        // The check has teeth: in gmsh order these three kinds fail it.
        for kind in [CellKind::Tet10, CellKind::Hex20, CellKind::Hex27] {
            assert!(
                vtk_geometry_error(kind, &gmsh_reference(kind)).is_some(),
                "{kind:?}"
            );
        }
    }

    #[test]
    fn tet10_swaps_nodes_8_and_9() {
        let cell = Cell {
            kind: CellKind::Tet10,
            nodes: (0..10).collect(),
            tag: 1,
        };
        let bytes = vtu_bytes(&gmsh_reference(CellKind::Tet10), &[cell], &[], &[], &[]).unwrap();
        let m = meshio_read_bytes(&bytes, "tet10-order");
        assert_eq!(
            m.cells,
            vec![("tetra10".to_string(), vec![0, 1, 2, 3, 4, 5, 6, 7, 9, 8])]
        );
    }

    // ---- reading back with meshio ----

    #[derive(Debug, Default)]
    struct ReadBack {
        version: String,
        points: Vec<[f64; 3]>,
        /// (meshio type name, connectivity) per cell, in file order.
        cells: Vec<(String, Vec<usize>)>,
        /// name -> rows (one per point)
        point_data: Vec<(String, Vec<Vec<f64>>)>,
        /// name -> (dtype, rows, one per cell over all blocks)
        cell_data: Vec<(String, String, Vec<Vec<f64>>)>,
    }

    const MESHIO_DUMP: &str = r#"
import sys
try:
    import meshio
except ImportError:
    sys.exit("meshio is not installed: pip install meshio")
m = meshio.read(sys.argv[1])
out = ["V " + meshio.__version__]
for p in m.points:
    out.append("P " + " ".join(repr(float(x)) for x in p))
for b in m.cells:
    for c in b.data:
        out.append("C " + b.type + " " + " ".join(str(int(i)) for i in c))
for name, a in m.point_data.items():
    for row in a.reshape(len(a), -1):
        out.append("PD " + name + " " + " ".join(repr(float(x)) for x in row))
for name, blocks in m.cell_data.items():
    for a in blocks:
        for row in a.reshape(len(a), -1):
            out.append("CD " + name + " " + str(a.dtype) + " " + " ".join(repr(float(x)) for x in row))
print("\n".join(out))
"#;

    fn scratch_dir(tag: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("subcontact-vtu-{}-{tag}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        d
    }

    /// The same dump as `MESHIO_DUMP`, made by VTK's own reader (the one
    /// ParaView uses); any message VTK reports is a failure.
    const VTK_DUMP: &str = r#"
import sys
from vtkmodules.vtkCommonCore import vtkStringOutputWindow, vtkOutputWindow, vtkVersion
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
w = vtkStringOutputWindow()
vtkOutputWindow.SetInstance(w)
r = vtkXMLUnstructuredGridReader()
r.SetFileName(sys.argv[1])
r.Update()
if w.GetOutput():
    sys.exit("VTK reported: " + w.GetOutput())
g = r.GetOutput()
names = {1: "vertex", 3: "line", 21: "line3", 5: "triangle", 22: "triangle6", 9: "quad",
         23: "quad8", 28: "quad9", 10: "tetra", 24: "tetra10", 12: "hexahedron",
         25: "hexahedron20", 29: "hexahedron27"}
dtypes = {"double": "float64", "int": "int32"}
out = ["V vtk-" + vtkVersion.GetVTKVersion()]
for i in range(g.GetNumberOfPoints()):
    out.append("P " + " ".join(repr(float(x)) for x in g.GetPoint(i)))
for c in range(g.GetNumberOfCells()):
    cell = g.GetCell(c)
    ids = [cell.GetPointId(k) for k in range(cell.GetNumberOfPoints())]
    out.append("C " + names[g.GetCellType(c)] + " " + " ".join(str(i) for i in ids))
for tag, data in (("PD", g.GetPointData()), ("CD", g.GetCellData())):
    for a in range(data.GetNumberOfArrays()):
        arr = data.GetAbstractArray(a)
        head = tag + " " + arr.GetName() + " "
        if tag == "CD":
            head += dtypes[arr.GetDataTypeAsString()] + " "
        for t in range(arr.GetNumberOfTuples()):
            out.append(head + " ".join(repr(float(x)) for x in arr.GetTuple(t)))
print("\n".join(out))
"#;

    /// Runs a dump script and parses its output.
    fn dump(python: &str, script: &str, path: &Path) -> ReadBack {
        let out = Command::new(python)
            .arg("-c")
            .arg(script)
            .arg(path)
            .output()
            .unwrap_or_else(|e| panic!("cannot run {python}: {e}"));
        assert!(
            out.status.success(),
            "{python} could not read {}: {}",
            path.display(),
            String::from_utf8_lossy(&out.stderr)
        );
        let text = String::from_utf8(out.stdout).unwrap();
        let mut m = ReadBack::default();
        let nums = |it: std::str::SplitWhitespace<'_>| -> Vec<f64> {
            it.map(|x| x.parse().unwrap()).collect()
        };
        for line in text.lines() {
            let mut it = line.split_whitespace();
            match it.next() {
                Some("V") => m.version = it.next().unwrap().to_string(),
                Some("P") => {
                    let v = nums(it);
                    m.points.push([v[0], v[1], v[2]]);
                }
                Some("C") => {
                    let ty = it.next().unwrap().to_string();
                    m.cells.push((ty, it.map(|x| x.parse().unwrap()).collect()));
                }
                Some("PD") => {
                    let name = it.next().unwrap().to_string();
                    let row = nums(it);
                    match m.point_data.iter_mut().find(|(n, _)| *n == name) {
                        Some((_, rows)) => rows.push(row),
                        None => m.point_data.push((name, vec![row])),
                    }
                }
                Some("CD") => {
                    let name = it.next().unwrap().to_string();
                    let dtype = it.next().unwrap().to_string();
                    let row = nums(it);
                    match m.cell_data.iter_mut().find(|(n, _, _)| *n == name) {
                        Some((_, _, rows)) => rows.push(row),
                        None => m.cell_data.push((name, dtype, vec![row])),
                    }
                }
                _ => panic!("unexpected line from {python}: {line}"),
            }
        }
        m
    }

    /// VTK's reading of the file, when `SUBCONTACT_VTK_PYTHON` names a Python
    /// with the `vtk` package (an optional cross-check: the tests need only meshio).
    fn vtk_read(path: &Path) -> Option<ReadBack> {
        let python = std::env::var("SUBCONTACT_VTK_PYTHON")
            .ok()
            .filter(|p| !p.is_empty())?;
        Some(dump(&python, VTK_DUMP, path))
    }

    /// meshio's reading of the file (and, if available, the same from VTK).
    fn meshio_read(path: &Path) -> ReadBack {
        let m = dump("python3", MESHIO_DUMP, path);
        if let Some(v) = vtk_read(path) {
            // Compared as text so that NaN equals NaN.
            assert_eq!(
                format!("{:?}", (&v.points, &v.cells, &v.point_data, &v.cell_data)),
                format!("{:?}", (&m.points, &m.cells, &m.point_data, &m.cell_data)),
                "VTK and meshio read {} differently",
                path.display()
            );
        }
        m
    }

    fn meshio_read_bytes(bytes: &[u8], tag: &str) -> ReadBack {
        let dir = scratch_dir(tag);
        let mut staged = Staged::new(&dir);
        staged.add("mesh.vtu", bytes.to_vec());
        let paths = staged.commit().unwrap();
        let m = meshio_read(&paths[0]);
        std::fs::remove_dir_all(&dir).unwrap();
        m
    }

    fn meshio_name(kind: CellKind) -> &'static str {
        match kind {
            CellKind::Point1 => "vertex",
            CellKind::Line2 => "line",
            CellKind::Line3 => "line3",
            CellKind::Tri3 => "triangle",
            CellKind::Tri6 => "triangle6",
            CellKind::Quad4 => "quad",
            CellKind::Quad8 => "quad8",
            CellKind::Quad9 => "quad9",
            CellKind::Tet4 => "tetra",
            CellKind::Tet10 => "tetra10",
            CellKind::Hex8 => "hexahedron",
            CellKind::Hex20 => "hexahedron20",
            CellKind::Hex27 => "hexahedron27",
        }
    }

    /// A mesh of the given kinds, one reference cell each, moved apart, and
    /// its fields: point `displacement` (3), `stress` (6), `von_mises` (1);
    /// cell `stress` (6), `von_mises` (1) and int `body`.
    struct TestMesh {
        points: Vec<[f64; 3]>,
        cells: Vec<Cell>,
        displacement: Vec<f64>,
        stress: Vec<f64>,
        von_mises: Vec<f64>,
        cell_stress: Vec<f64>,
        cell_von_mises: Vec<f64>,
        body: Vec<i32>,
    }

    impl TestMesh {
        fn new(kinds: &[CellKind]) -> Self {
            let mut points = Vec::new();
            let mut cells = Vec::new();
            for (c, &kind) in kinds.iter().enumerate() {
                let first = points.len();
                for p in gmsh_reference(kind) {
                    points.push([p[0] + 3.0 * c as f64, p[1], p[2]]);
                }
                cells.push(Cell {
                    kind,
                    nodes: (first..points.len()).collect(),
                    tag: 100 + c as u64,
                });
            }
            let np = points.len();
            let nc = cells.len();
            let displacement = (0..3 * np).map(|i| 1e-3 * i as f64 - 0.1).collect();
            let stress = (0..6 * np).map(|i| (i as f64).sin() * 1e8).collect();
            let von_mises = (0..np).map(|i| 1.0 / (i as f64 + 3.0)).collect();
            let cell_stress = (0..6 * nc)
                .map(|i| -(i as f64) * 0.5e6 + 1.0 / 3.0)
                .collect();
            let cell_von_mises = (0..nc).map(|i| 2.5e7 * (i as f64 + 1.0)).collect();
            let body = (0..nc as i32).map(|i| i % 2 - 7).collect();
            TestMesh {
                points,
                cells,
                displacement,
                stress,
                von_mises,
                cell_stress,
                cell_von_mises,
                body,
            }
        }

        fn bytes(&self) -> Vec<u8> {
            vtu_bytes(
                &self.points,
                &self.cells,
                &[
                    Field {
                        name: "displacement",
                        n_comp: 3,
                        values: &self.displacement,
                    },
                    Field {
                        name: "stress",
                        n_comp: 6,
                        values: &self.stress,
                    },
                    Field {
                        name: "von_mises",
                        n_comp: 1,
                        values: &self.von_mises,
                    },
                ],
                &[
                    Field {
                        name: "stress",
                        n_comp: 6,
                        values: &self.cell_stress,
                    },
                    Field {
                        name: "von_mises",
                        n_comp: 1,
                        values: &self.cell_von_mises,
                    },
                ],
                &[IntField {
                    name: "body",
                    values: &self.body,
                }],
            )
            .unwrap()
        }

        /// Checks what meshio read against what was written.
        fn check(&self, m: &ReadBack) {
            assert_eq!(m.points.len(), self.points.len(), "point count");
            assert_eq!(m.points, self.points, "points");
            assert_eq!(m.cells.len(), self.cells.len(), "cell count");
            for (c, (cell, (ty, conn))) in self.cells.iter().zip(&m.cells).enumerate() {
                assert_eq!(ty, meshio_name(cell.kind), "type of {:?}", cell.kind);
                // What meshio read, in VTK order, is where VTK wants it
                // (cell c was moved by 3c along x).
                let vtk: Vec<[f64; 3]> = conn
                    .iter()
                    .map(|&i| m.points[i])
                    .map(|p| [p[0] - 3.0 * c as f64, p[1], p[2]])
                    .collect();
                assert_eq!(
                    vtk_geometry_error(cell.kind, &vtk),
                    None,
                    "read back {:?}",
                    cell.kind
                );
                // And it is the same set of nodes.
                let mut a = conn.clone();
                let mut b = cell.nodes.clone();
                a.sort_unstable();
                b.sort_unstable();
                assert_eq!(a, b);
            }
            let rows = |v: &[f64], n: usize| v.chunks(n).map(|r| r.to_vec()).collect::<Vec<_>>();
            let point = |name: &str| {
                &m.point_data
                    .iter()
                    .find(|(n, _)| n == name)
                    .unwrap_or_else(|| panic!("no point field {name}"))
                    .1
            };
            assert_eq!(m.point_data.len(), 3);
            assert_eq!(point("displacement"), &rows(&self.displacement, 3));
            assert_eq!(point("stress"), &rows(&self.stress, 6));
            assert_eq!(point("von_mises"), &rows(&self.von_mises, 1));
            let cell = |name: &str| {
                m.cell_data
                    .iter()
                    .find(|(n, _, _)| n == name)
                    .unwrap_or_else(|| panic!("no cell field {name}"))
            };
            assert_eq!(m.cell_data.len(), 3);
            assert_eq!(cell("stress").1, "float64");
            assert_eq!(cell("stress").2, rows(&self.cell_stress, 6));
            assert_eq!(cell("von_mises").2, rows(&self.cell_von_mises, 1));
            assert_eq!(cell("body").1, "int32");
            let body: Vec<Vec<f64>> = self.body.iter().map(|&b| vec![b as f64]).collect();
            assert_eq!(cell("body").2, body);
        }
    }

    const KINDS: [CellKind; 12] = [
        CellKind::Line2,
        CellKind::Line3,
        CellKind::Tri3,
        CellKind::Tri6,
        CellKind::Quad4,
        CellKind::Quad8,
        CellKind::Quad9,
        CellKind::Tet4,
        CellKind::Tet10,
        CellKind::Hex8,
        CellKind::Hex20,
        CellKind::Hex27,
    ];

    #[test]
    fn each_kind_round_trips_through_meshio() {
        let dir = scratch_dir("kinds");
        let mut staged = Staged::new(&dir);
        let meshes: Vec<(CellKind, TestMesh)> = KINDS
            .iter()
            .chain([CellKind::Point1].iter())
            .map(|&k| (k, TestMesh::new(&[k])))
            .collect();
        for (kind, mesh) in &meshes {
            staged.add(&format!("{}.vtu", kind.name()), mesh.bytes());
        }
        let paths = staged.commit().unwrap();
        let mut version = String::new();
        for ((kind, mesh), path) in meshes.iter().zip(&paths) {
            let m = meshio_read(path);
            mesh.check(&m);
            assert_eq!(m.cells[0].0, meshio_name(*kind));
            version = m.version;
        }
        assert!(!version.is_empty());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn mixed_mesh_round_trips_through_meshio() {
        // Every kind in one file, twice, so meshio sees several blocks.
        let kinds: Vec<CellKind> = KINDS.iter().chain(KINDS.iter().rev()).copied().collect();
        let mesh = TestMesh::new(&kinds);
        let m = meshio_read_bytes(&mesh.bytes(), "mixed");
        mesh.check(&m);
    }

    #[test]
    fn large_arrays_round_trip() {
        // Several ZLib blocks (vtkio's block is 32768 bytes), one array an
        // exact multiple of the block size (4096 f64), one not.
        let n = 4096;
        let points: Vec<[f64; 3]> = (0..n)
            .map(|i| [i as f64 * 0.1, (i % 7) as f64, (i as f64).sqrt()])
            .collect();
        let cells: Vec<Cell> = (0..n - 1)
            .map(|i| Cell {
                kind: CellKind::Line2,
                nodes: vec![i, i + 1],
                tag: i as u64,
            })
            .collect();
        let scalar: Vec<f64> = (0..n).map(|i| (i as f64).cos()).collect();
        let body: Vec<i32> = (0..n as i32 - 1).collect();
        let bytes = vtu_bytes(
            &points,
            &cells,
            &[Field {
                name: "s",
                n_comp: 1,
                values: &scalar,
            }],
            &[],
            &[IntField {
                name: "body",
                values: &body,
            }],
        )
        .unwrap();
        let m = meshio_read_bytes(&bytes, "large");
        assert_eq!(m.points, points);
        assert_eq!(m.cells.len(), n - 1);
        assert!(m
            .cells
            .iter()
            .enumerate()
            .all(|(i, (t, c))| t == "line" && *c == vec![i, i + 1]));
        assert_eq!(
            m.point_data[0].1,
            scalar.iter().map(|&x| vec![x]).collect::<Vec<_>>()
        );
        assert_eq!(
            m.cell_data[0].2,
            body.iter().map(|&x| vec![x as f64]).collect::<Vec<_>>()
        );
    }

    #[test]
    fn empty_grid_and_odd_names_are_readable() {
        // meshio cannot read a grid without cells; VTK can, if it is there.
        let bytes = vtu_bytes(&[], &[], &[], &[], &[]).unwrap();
        let text = String::from_utf8(bytes.clone()).unwrap();
        assert!(
            text.contains("<Piece NumberOfPoints=\"0\" NumberOfCells=\"0\">"),
            "{text}"
        );
        let pts = [[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]];
        let no_cells = vtu_bytes(
            &pts,
            &[],
            &[Field {
                name: "v",
                n_comp: 1,
                values: &[7.0, 8.0],
            }],
            &[],
            &[],
        )
        .unwrap();
        let text = String::from_utf8(no_cells.clone()).unwrap();
        assert!(
            text.contains("<Piece NumberOfPoints=\"2\" NumberOfCells=\"0\">"),
            "{text}"
        );
        let dir = scratch_dir("empty");
        let mut staged = Staged::new(&dir);
        staged.add("empty.vtu", bytes);
        staged.add("no-cells.vtu", no_cells);
        let paths = staged.commit().unwrap();
        if let Some(v) = vtk_read(&paths[0]) {
            assert!(v.points.is_empty() && v.cells.is_empty());
        }
        if let Some(v) = vtk_read(&paths[1]) {
            assert_eq!(v.points, pts);
            assert!(v.cells.is_empty());
            assert_eq!(
                v.point_data,
                vec![("v".to_string(), vec![vec![7.0], vec![8.0]])]
            );
        }
        std::fs::remove_dir_all(&dir).unwrap();

        let mesh = TestMesh::new(&[CellKind::Tri3]);
        let bytes = vtu_bytes(
            &mesh.points,
            &mesh.cells,
            &[Field {
                name: "a&b<c>\"d'",
                n_comp: 2,
                values: &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0],
            }],
            &[],
            &[],
        )
        .unwrap();
        let m = meshio_read_bytes(&bytes, "names");
        assert_eq!(m.point_data[0].0, "a&b<c>\"d'");
        assert_eq!(
            m.point_data[0].1,
            vec![vec![1.0, 2.0], vec![3.0, 4.0], vec![5.0, 6.0]]
        );
    }

    #[test]
    fn non_finite_values_are_written_as_they_are() {
        // A diverged solution must still open, NaNs and all.
        let mesh = TestMesh::new(&[CellKind::Tri3]);
        let values = [
            f64::NAN,
            1.0,
            f64::INFINITY,
            f64::NEG_INFINITY,
            -0.0,
            f64::MIN_POSITIVE,
        ];
        let bytes = vtu_bytes(
            &mesh.points,
            &mesh.cells,
            &[Field {
                name: "u",
                n_comp: 2,
                values: &values,
            }],
            &[],
            &[],
        )
        .unwrap();
        let m = meshio_read_bytes(&bytes, "nan");
        let got: Vec<f64> = m.point_data[0].1.concat();
        assert_eq!(got.len(), values.len());
        for (g, v) in got.iter().zip(&values) {
            assert!(
                g.to_bits() == v.to_bits() || (g.is_nan() && v.is_nan()),
                "{g} != {v}"
            );
        }
    }

    #[test]
    fn file_is_zlib_compressed_vtu() {
        let bytes = TestMesh::new(&[CellKind::Hex27]).bytes();
        let text = String::from_utf8(bytes).unwrap();
        assert!(text.contains("type=\"UnstructuredGrid\""), "{text}");
        assert!(
            text.contains("compressor=\"vtkZLibDataCompressor\""),
            "{text}"
        );
        assert!(text.contains("header_type=\"UInt64\""), "{text}");
        assert!(
            text.contains("<Piece NumberOfPoints=\"27\" NumberOfCells=\"1\">"),
            "{text}"
        );
    }

    #[test]
    fn inconsistent_input_is_an_error_naming_it() {
        let mesh = TestMesh::new(&[CellKind::Quad4]);
        let short = [0.0; 11];
        let err = vtu_bytes(
            &mesh.points,
            &mesh.cells,
            &[Field {
                name: "displacement",
                n_comp: 3,
                values: &short,
            }],
            &[],
            &[],
        )
        .unwrap_err();
        let msg = err.to_string();
        assert!(
            msg.contains("displacement") && msg.contains("11") && msg.contains("12"),
            "{msg}"
        );

        let err = vtu_bytes(
            &mesh.points,
            &mesh.cells,
            &[],
            &[Field {
                name: "stress",
                n_comp: 6,
                values: &[0.0; 7],
            }],
            &[],
        )
        .unwrap_err();
        assert!(err.to_string().contains("stress"), "{err}");

        let err = vtu_bytes(
            &mesh.points,
            &mesh.cells,
            &[],
            &[],
            &[IntField {
                name: "body",
                values: &[],
            }],
        )
        .unwrap_err();
        assert!(err.to_string().contains("body"), "{err}");

        let err = vtu_bytes(
            &mesh.points,
            &mesh.cells,
            &[Field {
                name: "nothing",
                n_comp: 0,
                values: &[],
            }],
            &[],
            &[],
        )
        .unwrap_err();
        assert!(err.to_string().contains("nothing"), "{err}");

        let err = vtu_bytes(
            &mesh.points,
            &mesh.cells,
            &[Field {
                name: "huge",
                n_comp: usize::MAX,
                values: &[0.0; 4],
            }],
            &[],
            &[],
        )
        .unwrap_err();
        assert!(err.to_string().contains("huge"), "{err}");

        let mut bad = mesh.cells.clone();
        bad[0].nodes.pop();
        let err = vtu_bytes(&mesh.points, &bad, &[], &[], &[]).unwrap_err();
        assert!(
            err.to_string().contains("quad4") && err.to_string().contains("100"),
            "{err}"
        );

        let mut bad = mesh.cells.clone();
        bad[0].nodes[2] = 4;
        let err = vtu_bytes(&mesh.points, &bad, &[], &[], &[]).unwrap_err();
        assert!(err.to_string().contains("node 4"), "{err}");
    }

    #[test]
    fn pvd_lists_the_steps_in_order() {
        let steps = vec![
            (0.0, "result_0000.vtu".to_string()),
            (0.5, "result_0001.vtu".to_string()),
            (1e-7, "a&b \"c\".vtu".to_string()),
        ];
        let dir = scratch_dir("pvd");
        let mut staged = Staged::new(&dir);
        staged.add("series.pvd", pvd_bytes(&steps));
        let path = staged.commit().unwrap().remove(0);
        let out = Command::new("python3")
            .arg("-c")
            .arg(
                "import sys, xml.etree.ElementTree as ET\n\
                 r = ET.parse(sys.argv[1]).getroot()\n\
                 assert r.tag == 'VTKFile' and r.get('type') == 'Collection'\n\
                 for d in r.find('Collection'): print(d.get('timestep') + '|' + d.get('file'))",
            )
            .arg(&path)
            .output()
            .unwrap();
        std::fs::remove_dir_all(&dir).unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let text = String::from_utf8(out.stdout).unwrap();
        let got: Vec<(f64, String)> = text
            .lines()
            .map(|l| {
                let (t, f) = l.split_once('|').unwrap();
                (t.parse().unwrap(), f.to_string())
            })
            .collect();
        assert_eq!(got, steps);
    }
}
