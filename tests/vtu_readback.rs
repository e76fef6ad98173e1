//! The written VTU files read back: by meshio through python3 (and by
//! VTK's own reader, the one ParaView uses, when `SUBCONTACT_VTK_PYTHON`
//! names a Python with `vtk`) for every kind and a mixed mesh, large and
//! odd arrays, non-finite values; and the PVD collection, by Python's XML
//! parser. The VTU writer's unit tests (node order, header, errors) are in
//! src/output/vtu/tests.rs, whose oracle this file shares.

use std::path::{Path, PathBuf};
use std::process::Command;

use subcontact::mesh::{Cell, CellKind};
use subcontact::output::files::Staged;
use subcontact::output::vtu::{pvd_bytes, vtk_n_nodes, vtu_bytes, Field, IntField};

/// The unit tests' oracle (reference cells, VTK's node positions) and test mesh.
#[path = "../src/output/vtu/tests/reference.rs"]
mod reference;

use reference::{gmsh_reference, vtk_geometry_error, TestMesh};

#[test]
fn tet10_swaps_nodes_8_and_9() {
    let cell = Cell { kind: CellKind::Tet10, nodes: (0..10).collect(), tag: 1 };
    let bytes = vtu_bytes(&gmsh_reference(CellKind::Tet10), &[cell], &[], &[], &[]).unwrap();
    let m = meshio_read_bytes(&bytes, "tet10-order");
    assert_eq!(m.cells, vec![("tetra10".to_string(), vec![0, 1, 2, 3, 4, 5, 6, 7, 9, 8])]);
}

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
# meshio 5.3 maps VTK types 26 and 27 to "wedge15" and "pyramid13" but
# misses them in its table of dimensions, and then fails on reading them
import meshio._mesh
for t in ("wedge15", "pyramid13"):
    meshio._mesh.topological_dimension.setdefault(t, 3)
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
         25: "hexahedron20", 29: "hexahedron27", 13: "wedge", 26: "wedge15", 32: "wedge18",
         14: "pyramid", 27: "pyramid13"}
# every 3D cell must be one VTK itself calls valid (faces outward, convex)
from vtkmodules.vtkFiltersGeneral import vtkCellValidator
v = vtkCellValidator()
v.SetInputData(g)
v.Update()
state = v.GetOutput().GetCellData().GetArray("ValidityState")
bad = [c for c in range(g.GetNumberOfCells()) if g.GetCell(c).GetCellDimension() == 3 and state.GetValue(c) != 0]
if bad:
    sys.exit("vtkCellValidator: cells %s are not valid" % bad)
dtypes = {"double": "float64", "int": "int32"}
out = ["V vtk-" + vtkVersion.GetVTKVersion()]
for i in range(g.GetNumberOfPoints()):
    out.append("P " + " ".join(repr(float(x)) for x in g.GetPoint(i)))
for c in range(g.GetNumberOfCells()):
    cell = g.GetCell(c)
    ids = [cell.GetPointId(k) for k in range(cell.GetNumberOfPoints())]
    if g.GetCellType(c) == 13:
        # as meshio reports a linear wedge: in gmsh's orientation
        ids = [ids[k] for k in (0, 2, 1, 3, 5, 4)]
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

/// Runs a dump script (which reads the file `sys.argv[1]`) on each of
/// `paths` in one Python (importing meshio takes a second), and parses each
/// output.
fn dump_all(python: &str, script: &str, paths: &[PathBuf]) -> Vec<ReadBack> {
    const EACH: &str = r#"
import sys
script, paths = sys.argv[1], sys.argv[2:]
for p in paths:
    sys.argv = [sys.argv[0], p]
    exec(compile(script, "dump", "exec"), {"__name__": "__main__"})
    print("END", flush=True)
"#;
    let out = Command::new(python)
        .arg("-c")
        .arg(EACH)
        .arg(script)
        .args(paths)
        .output()
        .unwrap_or_else(|e| panic!("cannot run {python}: {e}"));
    assert!(out.status.success(), "{python} could not read {paths:?}: {}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8(out.stdout).unwrap();
    let mut chunks = vec![String::new()];
    for line in text.lines() {
        if line == "END" {
            chunks.push(String::new());
        } else if let Some(c) = chunks.last_mut() {
            c.extend([line, "\n"]);
        }
    }
    assert_eq!(chunks.pop().as_deref(), Some(""), "{python}'s output ends with END");
    assert_eq!(chunks.len(), paths.len(), "{python} read every file");
    chunks.iter().map(|c| parse(python, c)).collect()
}

/// One file's dump, as [`ReadBack`].
fn parse(python: &str, text: &str) -> ReadBack {
    let mut m = ReadBack::default();
    let nums = |it: std::str::SplitWhitespace<'_>| -> Vec<f64> { it.map(|x| x.parse().unwrap()).collect() };
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

/// VTK's reading of the files, when `SUBCONTACT_VTK_PYTHON` names a Python
/// with the `vtk` package (an optional cross-check: the tests need only meshio).
fn vtk_read_all(paths: &[PathBuf]) -> Option<Vec<ReadBack>> {
    let python = std::env::var("SUBCONTACT_VTK_PYTHON").ok().filter(|p| !p.is_empty())?;
    Some(dump_all(&python, VTK_DUMP, paths))
}

fn vtk_read(path: &Path) -> Option<ReadBack> {
    vtk_read_all(&[path.to_path_buf()]).map(|mut v| v.remove(0))
}

/// meshio's reading of the files (and, if available, the same from VTK).
fn meshio_read_all(paths: &[PathBuf]) -> Vec<ReadBack> {
    let read = dump_all("python3", MESHIO_DUMP, paths);
    for (v, (m, path)) in vtk_read_all(paths).unwrap_or_default().iter().zip(read.iter().zip(paths)) {
        // Compared as text so that NaN equals NaN.
        assert_eq!(
            format!("{:?}", (&v.points, &v.cells, &v.point_data, &v.cell_data)),
            format!("{:?}", (&m.points, &m.cells, &m.point_data, &m.cell_data)),
            "VTK and meshio read {} differently",
            path.display()
        );
    }
    read
}

fn meshio_read_bytes(bytes: &[u8], tag: &str) -> ReadBack {
    let dir = scratch_dir(tag);
    let mut staged = Staged::new(&dir, "readback");
    staged.add("mesh.vtu", bytes.to_vec());
    let paths = staged.commit().unwrap();
    let m = meshio_read_all(&paths).remove(0);
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
        CellKind::Prism6 => "wedge",
        CellKind::Prism15 => "wedge15",
        CellKind::Prism18 => "wedge18",
        CellKind::Pyramid5 => "pyramid",
        CellKind::Pyramid13 | CellKind::Pyramid14 => "pyramid13",
    }
}

impl TestMesh {
    /// Checks what meshio read against what was written.
    fn check(&self, m: &ReadBack) {
        assert_eq!(m.points.len(), self.points.len(), "point count");
        assert_eq!(m.points, self.points, "points");
        assert_eq!(m.cells.len(), self.cells.len(), "cell count");
        for (c, (cell, (ty, conn))) in self.cells.iter().zip(&m.cells).enumerate() {
            assert_eq!(ty, meshio_name(cell.kind), "type of {:?}", cell.kind);
            // What meshio read, in VTK order, is where VTK wants it
            // (cell c was moved by 3c along x). meshio hands a linear wedge
            // back turned to gmsh's orientation (its vtk_to_meshio_order).
            let conn: Vec<usize> = match cell.kind {
                CellKind::Prism6 => [0, 2, 1, 3, 5, 4].iter().map(|&i| conn[i]).collect(),
                _ => conn.clone(),
            };
            let vtk: Vec<[f64; 3]> =
                conn.iter().map(|&i| m.points[i]).map(|p| [p[0] - 3.0 * c as f64, p[1], p[2]]).collect();
            assert_eq!(vtk_geometry_error(cell.kind, &vtk), None, "read back {:?}", cell.kind);
            // And it is the same set of nodes (pyramid14: but its base centre).
            let mut a = conn.clone();
            let mut b = cell.nodes[..vtk_n_nodes(cell.kind)].to_vec();
            a.sort_unstable();
            b.sort_unstable();
            assert_eq!(a, b);
        }
        let rows = |v: &[f64], n: usize| v.chunks(n).map(|r| r.to_vec()).collect::<Vec<_>>();
        let point = |name: &str| {
            &m.point_data.iter().find(|(n, _)| n == name).unwrap_or_else(|| panic!("no point field {name}")).1
        };
        assert_eq!(m.point_data.len(), 3);
        assert_eq!(point("displacement"), &rows(&self.displacement, 3));
        assert_eq!(point("stress"), &rows(&self.stress, 6));
        assert_eq!(point("von_mises"), &rows(&self.von_mises, 1));
        let cell = |name: &str| {
            m.cell_data.iter().find(|(n, _, _)| n == name).unwrap_or_else(|| panic!("no cell field {name}"))
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

/// Every kind with cells of their own (not the point).
fn kinds() -> Vec<CellKind> {
    CellKind::ALL.into_iter().filter(|&k| k != CellKind::Point1).collect()
}

#[test]
fn each_kind_round_trips_through_meshio() {
    let dir = scratch_dir("kinds");
    let mut staged = Staged::new(&dir, "readback");
    let meshes: Vec<(CellKind, TestMesh)> = CellKind::ALL.iter().map(|&k| (k, TestMesh::new(&[k]))).collect();
    for (kind, mesh) in &meshes {
        staged.add(&format!("{}.vtu", kind.name()), mesh.bytes());
    }
    let paths = staged.commit().unwrap();
    let mut version = String::new();
    for ((kind, mesh), m) in meshes.iter().zip(meshio_read_all(&paths)) {
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
    let twice: Vec<CellKind> = kinds().into_iter().chain(kinds().into_iter().rev()).collect();
    let mesh = TestMesh::new(&twice);
    let m = meshio_read_bytes(&mesh.bytes(), "mixed");
    mesh.check(&m);
}

#[test]
fn large_arrays_round_trip() {
    // Several ZLib blocks (vtkio's block is 32768 bytes), one array an
    // exact multiple of the block size (4096 f64), one not.
    let n = 4096;
    let points: Vec<[f64; 3]> = (0..n).map(|i| [i as f64 * 0.1, (i % 7) as f64, (i as f64).sqrt()]).collect();
    let cells: Vec<Cell> =
        (0..n - 1).map(|i| Cell { kind: CellKind::Line2, nodes: vec![i, i + 1], tag: i as u64 }).collect();
    let scalar: Vec<f64> = (0..n).map(|i| (i as f64).cos()).collect();
    let body: Vec<i32> = (0..n as i32 - 1).collect();
    let bytes = vtu_bytes(
        &points,
        &cells,
        &[Field { name: "s", n_comp: 1, values: &scalar }],
        &[],
        &[IntField { name: "body", values: &body }],
    )
    .unwrap();
    let m = meshio_read_bytes(&bytes, "large");
    assert_eq!(m.points, points);
    assert_eq!(m.cells.len(), n - 1);
    assert!(m.cells.iter().enumerate().all(|(i, (t, c))| t == "line" && *c == vec![i, i + 1]));
    assert_eq!(m.point_data[0].1, scalar.iter().map(|&x| vec![x]).collect::<Vec<_>>());
    assert_eq!(m.cell_data[0].2, body.iter().map(|&x| vec![x as f64]).collect::<Vec<_>>());
}

#[test]
fn empty_grid_and_odd_names_are_readable() {
    // meshio cannot read a grid without cells; VTK can, if it is there.
    let bytes = vtu_bytes(&[], &[], &[], &[], &[]).unwrap();
    let text = String::from_utf8(bytes.clone()).unwrap();
    assert!(text.contains("<Piece NumberOfPoints=\"0\" NumberOfCells=\"0\">"), "{text}");
    let pts = [[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]];
    let no_cells = vtu_bytes(&pts, &[], &[Field { name: "v", n_comp: 1, values: &[7.0, 8.0] }], &[], &[]).unwrap();
    let text = String::from_utf8(no_cells.clone()).unwrap();
    assert!(text.contains("<Piece NumberOfPoints=\"2\" NumberOfCells=\"0\">"), "{text}");
    let dir = scratch_dir("empty");
    let mut staged = Staged::new(&dir, "readback");
    staged.add("empty.vtu", bytes);
    staged.add("no-cells.vtu", no_cells);
    let paths = staged.commit().unwrap();
    if let Some(v) = vtk_read(&paths[0]) {
        assert!(v.points.is_empty() && v.cells.is_empty());
    }
    if let Some(v) = vtk_read(&paths[1]) {
        assert_eq!(v.points, pts);
        assert!(v.cells.is_empty());
        assert_eq!(v.point_data, vec![("v".to_string(), vec![vec![7.0], vec![8.0]])]);
    }
    std::fs::remove_dir_all(&dir).unwrap();

    let mesh = TestMesh::new(&[CellKind::Tri3]);
    let bytes = vtu_bytes(
        &mesh.points,
        &mesh.cells,
        &[Field { name: "a&b<c>\"d'", n_comp: 2, values: &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0] }],
        &[],
        &[],
    )
    .unwrap();
    let m = meshio_read_bytes(&bytes, "names");
    assert_eq!(m.point_data[0].0, "a&b<c>\"d'");
    assert_eq!(m.point_data[0].1, vec![vec![1.0, 2.0], vec![3.0, 4.0], vec![5.0, 6.0]]);
}

#[test]
fn non_finite_values_are_written_as_they_are() {
    // A diverged solution must still open, NaNs and all.
    let mesh = TestMesh::new(&[CellKind::Tri3]);
    let values = [f64::NAN, 1.0, f64::INFINITY, f64::NEG_INFINITY, -0.0, f64::MIN_POSITIVE];
    let bytes =
        vtu_bytes(&mesh.points, &mesh.cells, &[Field { name: "u", n_comp: 2, values: &values }], &[], &[]).unwrap();
    let m = meshio_read_bytes(&bytes, "nan");
    let got: Vec<f64> = m.point_data[0].1.concat();
    assert_eq!(got.len(), values.len());
    for (g, v) in got.iter().zip(&values) {
        assert!(g.to_bits() == v.to_bits() || (g.is_nan() && v.is_nan()), "{g} != {v}");
    }
}

#[test]
fn pvd_lists_the_steps_in_order() {
    let steps = vec![
        (0.0, "result_0000.vtu".to_string()),
        (0.5, "result_0001.vtu".to_string()),
        (1e-7, "a&b \"c\".vtu".to_string()),
    ];
    let dir = scratch_dir("pvd");
    let mut staged = Staged::new(&dir, "readback");
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
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
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
