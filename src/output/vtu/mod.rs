//! VTK XML files for ParaView: one UnstructuredGrid (`.vtu`) per result and a
//! collection (`.pvd`) that makes a series of them a time series.
//!
//! The rest of the program keeps cells in gmsh's node order; this module is
//! the only place that reorders gmsh→VTK node order (tet10, hex20, hex27,
//! the prisms and pyramid13/14 differ, every other kind is the same in both
//! programs). The prisms' orders are those VTK 9.2's `vtkCellValidator`
//! accepts as valid (outward faces) and gmsh 4.8.4's own VTK export writes:
//! VTK's linear wedge turns the other way round from gmsh's prism6 (its
//! triangle (0,1,2) faces away from (3,4,5)), its quadratic wedges do not.
//! (VTK is not consistent there: its Cell Size and Integrate Variables
//! filters give a quadratic wedge (type 26) so oriented a negative volume,
//! and a biquadratic one (32) a sixth of its volume, whichever way round.)
//! A pyramid14 is written as VTK's quadratic pyramid (type 27, its first 13
//! nodes): VTK's triquadratic pyramid (type 37) needs 19 nodes, which
//! neither vtkio 0.7 nor meshio know; the base centre stays a point of the
//! file with its values, only no cell interpolates through it. Data arrays are
//! written as ZLib-compressed (level 1) base64 inline binary, the way vtkio
//! 0.7 writes them, which ParaView and meshio both read. Building the bytes
//! never touches the file system; `super::files::Staged` writes them.

use vtkio::model::{
    Attribute, Attributes, ByteOrder, CellType, Cells, DataSet, UnstructuredGridPiece, Version, VertexNumbers, Vtk,
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
        CellKind::Prism6 => CellType::Wedge,
        CellKind::Prism15 => CellType::QuadraticWedge,
        CellKind::Prism18 => CellType::BiquadraticQuadraticWedge,
        CellKind::Pyramid5 => CellType::Pyramid,
        CellKind::Pyramid13 | CellKind::Pyramid14 => CellType::QuadraticPyramid,
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

/// vtkWedge: the triangle (0,1,2) turned the other way, so that its
/// right-hand normal points away from (3,4,5).
const PRISM6_VTK_FROM_GMSH: [usize; 6] = [0, 2, 1, 3, 5, 4];

/// vtkQuadraticWedge: corners as gmsh's, mid-edge nodes on (0,1) (1,2)
/// (2,0) (3,4) (4,5) (5,3) (0,3) (1,4) (2,5), which gmsh numbers 6 9 7 12 14
/// 13 8 10 11.
const PRISM15_VTK_FROM_GMSH: [usize; 15] = [0, 1, 2, 3, 4, 5, 6, 9, 7, 12, 14, 13, 8, 10, 11];

/// vtkBiQuadraticQuadraticWedge: as prism15, then the centres of the faces
/// (0,1,4,3) (1,2,5,4) (2,0,3,5), gmsh's 15 17 16.
const PRISM18_VTK_FROM_GMSH: [usize; 18] = [0, 1, 2, 3, 4, 5, 6, 9, 7, 12, 14, 13, 8, 10, 11, 15, 17, 16];

/// vtkQuadraticPyramid: mid-edge nodes on (0,1) (1,2) (2,3) (3,0) (0,4)
/// (1,4) (2,4) (3,4), gmsh's 5 8 10 6 7 9 11 12. Also pyramid14's first 13
/// (its base centre 13 has no place in a VTK type vtkio writes).
const PYRAMID13_VTK_FROM_GMSH: [usize; 13] = [0, 1, 2, 3, 4, 5, 8, 10, 6, 7, 9, 11, 12];

/// For kinds whose node order differs: entry `i` is the gmsh position of
/// VTK node `i`. `None` means both programs use the same order. For
/// pyramid14 the list has 13 entries: the VTK cell leaves out the base centre.
pub(crate) fn vtk_from_gmsh(kind: CellKind) -> Option<&'static [usize]> {
    match kind {
        CellKind::Tet10 => Some(&TET10_VTK_FROM_GMSH),
        CellKind::Hex20 => Some(&HEX20_VTK_FROM_GMSH),
        CellKind::Hex27 => Some(&HEX27_VTK_FROM_GMSH),
        CellKind::Prism6 => Some(&PRISM6_VTK_FROM_GMSH),
        CellKind::Prism15 => Some(&PRISM15_VTK_FROM_GMSH),
        CellKind::Prism18 => Some(&PRISM18_VTK_FROM_GMSH),
        CellKind::Pyramid13 | CellKind::Pyramid14 => Some(&PYRAMID13_VTK_FROM_GMSH),
        _ => None,
    }
}

/// Number of nodes of a cell kind in the VTK file (pyramid14: 13).
pub fn vtk_n_nodes(kind: CellKind) -> usize {
    vtk_from_gmsh(kind).map_or(kind.n_nodes(), |p| p.len())
}

/// Checks that a field has `n_comp * count` values.
fn check_len(location: &'static str, name: &str, n_comp: usize, count: usize, len: usize) -> Result<(), OutputError> {
    if n_comp == 0 {
        return Err(OutputError::NoComponents { location, field: name.to_string() });
    }
    if u32::try_from(n_comp).is_err() || n_comp.checked_mul(count) != Some(len) {
        return Err(OutputError::FieldLength { location, field: name.to_string(), n_comp, count, len });
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
    let (n_points, n_cells) = (points.len(), cells.len());
    // 1. the counts fit vtkio and every field has its length
    check_sizes(n_points, n_cells, point_data, cell_data, cell_int_data)?;
    // 2. the cells in VTK order and type
    let cells = vtk_cells(cells, n_points)?;
    // 3. the grid with its fields, written compressed
    let coords: Vec<f64> = points.iter().flatten().copied().collect();
    let vtk = Vtk {
        version: Version::new_xml(1, 0),
        title: String::new(),
        byte_order: ByteOrder::LittleEndian,
        file_path: None,
        data: DataSet::inline(UnstructuredGridPiece {
            points: coords.into(),
            cells,
            data: attributes(point_data, cell_data, cell_int_data),
        }),
    };
    let file = vtk.try_into_xml_format(Compressor::ZLib, ZLIB_LEVEL).map_err(|e| OutputError::Vtk(e.to_string()))?;
    let mut bytes = Vec::new();
    file.write(&mut bytes).map_err(|e| OutputError::Vtk(e.to_string()))?;
    with_piece_counts(bytes, n_points, n_cells)
}

/// The counts fit the u32 vtkio writes `NumberOfPoints` and
/// `NumberOfCells` as, and every field has `n_comp` values per point or
/// cell.
fn check_sizes(
    n_points: usize,
    n_cells: usize,
    point_data: &[Field<'_>],
    cell_data: &[Field<'_>],
    cell_int_data: &[IntField<'_>],
) -> Result<(), OutputError> {
    if u32::try_from(n_points).is_err() {
        return Err(OutputError::TooLarge { what: "points", count: n_points });
    }
    if u32::try_from(n_cells).is_err() {
        return Err(OutputError::TooLarge { what: "cells", count: n_cells });
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
    Ok(())
}

/// The cells' connectivity in VTK node order, offsets and types; an error
/// names a cell with the wrong number of nodes or a node out of range.
fn vtk_cells(cells: &[Cell], n_points: usize) -> Result<Cells, OutputError> {
    let n_conn: usize = cells.iter().map(|c| c.nodes.len()).sum();
    let mut connectivity = Vec::with_capacity(n_conn);
    let mut offsets = Vec::with_capacity(cells.len());
    let mut types = Vec::with_capacity(cells.len());
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
                return Err(OutputError::NodeOutOfRange { index, tag: cell.tag, node, n_points });
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
    Ok(Cells { cell_verts: VertexNumbers::XML { connectivity, offsets }, types })
}

/// The point data, then the cell data and the integer cell data.
fn attributes(point_data: &[Field<'_>], cell_data: &[Field<'_>], cell_int_data: &[IntField<'_>]) -> Attributes {
    let attribute = |f: &Field<'_>| {
        // n_comp fits in u32: checked in check_sizes.
        Attribute::generic(f.name, f.n_comp as u32).with_data(f.values.to_vec())
    };
    Attributes {
        point: point_data.iter().map(attribute).collect(),
        cell: cell_data
            .iter()
            .map(attribute)
            .chain(cell_int_data.iter().map(|f| Attribute::generic(f.name, 1).with_data(f.values.to_vec())))
            .collect(),
    }
}

/// vtkio leaves out `NumberOfPoints` and `NumberOfCells` when they are zero,
/// and VTK (so ParaView) and meshio then refuse the file: write the `<Piece>`
/// tag with both. An unstructured grid's piece has no other attributes.
fn with_piece_counts(bytes: Vec<u8>, n_points: usize, n_cells: usize) -> Result<Vec<u8>, OutputError> {
    let missing = || OutputError::Vtk("vtkio wrote no <Piece> element".to_string());
    let start = bytes.windows(6).position(|w| w == b"<Piece").ok_or_else(missing)?;
    let len = bytes[start..].iter().position(|&b| b == b'>').ok_or_else(missing)?;
    let tag = format!("<Piece NumberOfPoints=\"{n_points}\" NumberOfCells=\"{n_cells}\"");
    let end = if bytes[start + len - 1] == b'/' { start + len - 1 } else { start + len };
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
mod tests;
