//! Tests of the MSH reader. Files written by gmsh 4.8.4 (order 1 and 2,
//! ASCII and binary, triangles, quadrangles, hexahedra, prisms, pyramids,
//! parametric nodes; committed in tests/fixtures/msh/, made by its
//! `make.sh`, which tests/gmsh_cli.rs re-runs against the installed gmsh)
//! are read and every cell is checked against mshio's reading of the same
//! file; a hand-written file covers what gmsh does not write (node tags out
//! of file order, an entity with several physical tags, sparse tags, CRLF);
//! and every failure (a missing file, old formats, no physical groups,
//! unsupported elements, files cut or corrupted anywhere) gives its message,
//! never a panic.

use super::*;
use crate::mesh::{Cell, CellKind, Group};
use std::path::PathBuf;

/// A mesh of tests/fixtures/msh/ by name (without `.msh`).
fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/msh").join(format!("{name}.msh"))
}

/// `bin` or `ascii`, as the fixtures are named.
fn encoding(binary: bool) -> &'static str {
    if binary {
        "bin"
    } else {
        "ascii"
    }
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
    for order in [1, 2] {
        let mut by_format = Vec::new();
        for binary in [true, false] {
            let path = fixture(&format!("two-o{order}-{}", encoding(binary)));
            assert_eq!(std::fs::read(&path).unwrap()[12..19] == *b"4.1 1 8", binary);
            let mesh = read_msh(&path).unwrap();
            check_against_mshio(&path, &mesh);

            let summary: Vec<(&str, usize, i32)> =
                mesh.groups.iter().map(|g| (g.name.as_str(), g.dim, g.tag)).collect();
            assert_eq!(
                summary,
                [("corner", 0, 5), ("shared", 1, 3), ("bottom", 1, 4), ("left", 2, 1), ("right", 2, 2)]
            );
            assert_eq!(mesh.dim(), 2);
            let (line, tri) =
                if order == 1 { (CellKind::Line2, CellKind::Tri3) } else { (CellKind::Line3, CellKind::Tri6) };
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
            let common: Vec<usize> = left.iter().copied().filter(|n| right.binary_search(n).is_ok()).collect();
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
        assert_eq!((&bin.node_tags, &bin.groups), (&ascii.node_tags, &ascii.groups));
        assert_eq!(bin.coords.len(), ascii.coords.len());
        for (a, b) in bin.coords.iter().zip(&ascii.coords) {
            assert!((0..3).all(|d| (a[d] - b[d]).abs() < 1e-14), "{a:?} {b:?}");
        }
    }
}

#[test]
fn hex_box_order_1_and_2() {
    let cases = [
        ("o1", CellKind::Hex8, CellKind::Quad4, 27),
        ("o2", CellKind::Hex27, CellKind::Quad9, 125),
        ("o2i", CellKind::Hex20, CellKind::Quad8, 125 - 8 - 36),
    ];
    for (order, hex, quad, n_nodes) in cases {
        for binary in [true, false] {
            let path = fixture(&format!("box-{order}-{}", encoding(binary)));
            let mesh = read_msh(&path).unwrap();
            check_against_mshio(&path, &mesh);
            let summary: Vec<(&str, usize)> = mesh.groups.iter().map(|g| (g.name.as_str(), g.dim)).collect();
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
    let cases = [
        ("o1", CellKind::Quad4, CellKind::Line2),
        ("o2", CellKind::Quad9, CellKind::Line3),
        ("o2i", CellKind::Quad8, CellKind::Line3),
    ];
    for (order, quad, line) in cases {
        let path = fixture(&format!("quad-{order}"));
        let mesh = read_msh(&path).unwrap();
        check_against_mshio(&path, &mesh);
        assert_eq!(kinds(mesh.group("square").unwrap()), [quad]);
        assert_eq!(kinds(mesh.group("edges").unwrap()), [line]);
        assert_eq!(mesh.group("square").unwrap().cells.len(), 4);
    }
}

#[test]
fn parametric_nodes_are_read() {
    for binary in [true, false] {
        let plain_path = fixture(&format!("two-o2-{}", encoding(binary)));
        let plain = read_msh(&plain_path).unwrap();
        let path = fixture(&format!("param-{}", encoding(binary)));
        assert!(std::fs::read(&path).unwrap().len() > std::fs::read(&plain_path).unwrap().len());
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
    assert_eq!(mesh.coords, [[1.0, 0.0, 0.0], [0.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]]);
    let summary: Vec<(&str, usize, i32, usize)> =
        mesh.groups.iter().map(|g| (g.name.as_str(), g.dim, g.tag, g.cells.len())).collect();
    assert_eq!(summary, [("an edge", 1, 7, 1), ("plate", 2, 3, 2), ("9", 2, 9, 2), ("11", 2, 11, 2)]);
    let edge = &mesh.groups[0].cells[0];
    assert_eq!((edge.kind, edge.nodes.as_slice(), edge.tag), (CellKind::Line2, &[1usize, 0][..], 1));
    let plate = &mesh.groups[1].cells;
    assert_eq!(plate[0], Cell { kind: CellKind::Tri3, nodes: vec![1, 0, 2], tag: 2 });
    assert_eq!(plate[1], Cell { kind: CellKind::Tri3, nodes: vec![1, 2, 3], tag: 3 });
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
    assert!(m.data.nodes.unwrap().node_blocks.iter().all(|b| b.node_tags.is_none()));
}

#[test]
fn missing_file() {
    let p = fixture("nothere");
    let e = read_msh(&p).unwrap_err();
    assert!(matches!(e, MshError::NotFound { .. }));
    assert_eq!(e.to_string(), format!("mesh file `{}` does not exist: check `mesh =` in the scene", p.display()));
}

fn assert_malformed(r: Result<Mesh, MshError>, detail: &str) {
    match r {
        Err(e @ MshError::Malformed { .. }) => {
            let msg = e.to_string();
            assert!(msg.starts_with("`test.msh` is not a complete MSH 4.1 file (truncated?): "), "{msg}");
            assert!(msg.contains(detail), "{msg} lacks {detail:?}");
        }
        other => panic!("expected Malformed ({detail}), got {other:?}"),
    }
}

#[test]
fn empty_garbage_and_inconsistent_files() {
    assert_malformed(parse(b""), "the file is empty");
    assert_malformed(parse(b"  \n"), "the file is empty");
    assert_malformed(parse(b"Point(1) = {0, 0, 0};\n"), "does not start with `$MeshFormat`");
    assert_malformed(parse(&[0xff, 0x00, 0x13, 0x37]), "does not start with `$MeshFormat`");
    assert_malformed(parse(b"$MeshFormat\nabc 0 8\n$EndMeshFormat\n"), "found `abc`");
    assert_malformed(parse(b"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"), "no $Nodes section");
    assert_malformed(
        parse(b"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n0 0 1 0\n$EndNodes\n"),
        "no $Elements section",
    );
    assert_malformed(parse(b"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Foo\n1 2 3\n"), "no `$EndFoo`");
    assert_malformed(parse(HAND.replace("1 1 3\n", "1 1 x\n").as_bytes()), "found `x`");
    assert_malformed(parse(HAND.replace("2 4 1 4", "2 5 1 4").as_bytes()), "announces 5 nodes");
    assert_malformed(parse(HAND.replace("\n4\n1 1 0", "\n3\n1 1 0").as_bytes()), "node tag 3 appears twice");
    assert_malformed(parse(HAND.replace("$EndNodes", "$EndNode").as_bytes()), "expected `$EndNodes`");
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
    assert!(matches!(e, MshError::MissingNode { element: 3, node: 99, .. }), "{e:?}");
    let msg = e.to_string();
    assert!(msg.contains("`test.msh`") && msg.contains("element 3") && msg.contains("node 99"), "{msg}");
    assert!(msg.contains("`plate`"), "{msg}");
}

#[test]
fn old_formats_are_named() {
    for (name, version) in [("old-msh22", "2.2"), ("old-msh22-bin", "2.2"), ("old-msh40", "4")] {
        let path = fixture(name);
        let e = read_msh(&path).unwrap_err();
        assert!(matches!(&e, MshError::Version { version: v, .. } if v == version), "{e:?}");
        assert_eq!(
            e.to_string(),
            format!("`{}` is MSH {version}: re-export it with gmsh -format msh41", path.display())
        );
    }
}

#[test]
fn no_physical_groups() {
    let path = fixture("nophys");
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

/// Every node of every cell sits where the cell's corners put its
/// reference node (straight-sided meshes): checks the node tables against
/// the order gmsh writes.
fn check_nodes_on_reference_positions(mesh: &Mesh, kind: CellKind) -> usize {
    use crate::fem::shape;
    let lin = shape::linear_sibling(kind);
    let mut n = vec![0.0; lin.n_nodes()];
    let mut dn = vec![[0.0; 3]; lin.n_nodes()];
    let mut count = 0;
    for c in mesh.groups.iter().flat_map(|g| &g.cells).filter(|c| c.kind == kind) {
        for (a, xi) in shape::reference_nodes(kind).iter().enumerate() {
            shape::eval(lin, *xi, &mut n, &mut dn);
            let want: [f64; 3] =
                std::array::from_fn(|i| (0..lin.n_nodes()).map(|b| n[b] * mesh.coords[c.nodes[b]][i]).sum());
            let got = mesh.coords[c.nodes[a]];
            // gmsh places the nodes to ~1e-12 of the unit cells' size
            assert!(
                (0..3).all(|i| (got[i] - want[i]).abs() < 1e-9),
                "{} {}: node {a} at {got:?}, expected {want:?}",
                kind.name(),
                c.tag
            );
        }
        count += 1;
    }
    count
}

#[test]
fn prisms_and_pyramids_of_order_1_and_2_are_read_in_gmsh_order() {
    let cases: [(&str, usize, &[CellKind]); 6] = [
        ("prism-o1", 1, &[CellKind::Prism6]),
        ("prism-o2", 2, &[CellKind::Prism18]),
        ("prism-o2i", 2, &[CellKind::Prism15]),
        ("pyramid-o1", 1, &[CellKind::Tet4, CellKind::Hex8, CellKind::Pyramid5]),
        ("pyramid-o2", 2, &[CellKind::Tet10, CellKind::Hex27, CellKind::Pyramid14]),
        ("pyramid-o2i", 2, &[CellKind::Tet10, CellKind::Hex20, CellKind::Pyramid13]),
    ];
    for (i, (name, order, want)) in cases.into_iter().enumerate() {
        for binary in [true, false] {
            let path = fixture(&format!("{name}-{}", encoding(binary)));
            let mesh = read_msh(&path).unwrap_or_else(|e| panic!("case {i}: {e}"));
            let mut found: Vec<CellKind> = mesh.groups.iter().filter(|g| g.dim == 3).flat_map(kinds).collect();
            found.sort();
            let mut want = want.to_vec();
            want.sort();
            assert_eq!(found, want, "case {i}");
            let special = want.iter().copied().find(|k| k.name().starts_with('p')).unwrap();
            assert!(check_nodes_on_reference_positions(&mesh, special) > 0, "case {i}");
            // mshio reads the first-order files (it miscounts order-2 prisms)
            if order == 1 {
                check_against_mshio(&path, &mesh);
            }
        }
    }
}

#[test]
fn unsupported_elements_name_type_and_group() {
    for binary in [true, false] {
        let path = fixture(&format!("prism-o3-{}", encoding(binary)));
        let e = read_msh(&path).unwrap_err();
        // the first block of a physical group met: the base's order-3 triangles
        assert!(matches!(&e, MshError::UnsupportedElement { code: 21, .. }), "{e:?}");
        let msg = e.to_string();
        assert!(msg.contains("gmsh type 21 (tri10)"), "{msg}");
        assert!(msg.contains("order 1 or 2") && msg.contains("prisms or pyramids"), "{msg}");
        assert!(msg.contains("`base`") && msg.contains(&path.display().to_string()), "{msg}");
        // the volume alone: its order-3 prisms
        let path = fixture(&format!("prism-volume-o3-{}", encoding(binary)));
        let msg = read_msh(&path).unwrap_err().to_string();
        assert!(msg.contains("gmsh type 90 (prism40)") && msg.contains("`wedge`"), "{msg}");
    }
    // Unsupported elements outside any physical group are skipped.
    let text = HAND
        .replace("$Elements\n2 3 1 3\n", "$Elements\n3 4 1 4\n2 2 21 1\n4 1 2 3 4 1 2 3 4 1 2\n")
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
    let mut files = vec![HAND.as_bytes().to_vec()];
    for binary in [true, false] {
        for name in ["two", "box"] {
            files.push(std::fs::read(fixture(&format!("{name}-o2-{}", encoding(binary)))).unwrap());
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
                assert!(matches!(r, Err(MshError::Malformed { .. })), "cut at {len}: {r:?}");
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
