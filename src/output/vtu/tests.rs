//! The gmsh→VTK node order against VTK's own definition of each kind:
//! reference cells built from gmsh's edge and face tables, reordered, must
//! put every mid-edge and face node where VTK expects it; the file's
//! header, and errors naming the inconsistent input. The files read back
//! by meshio (and VTK) are in tests/vtu_readback.rs.

use super::*;

mod reference;

use reference::{gmsh_reference, vtk_geometry_error, TestMesh};

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
        (CellKind::Prism6, 13),
        (CellKind::Prism15, 26),
        (CellKind::Prism18, 32),
        (CellKind::Pyramid5, 14),
        (CellKind::Pyramid13, 27),
        (CellKind::Pyramid14, 27),
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
                // A permutation of 0..n (pyramid14: of its first 13 nodes).
                let mut sorted = perm.to_vec();
                sorted.sort_unstable();
                assert_eq!(sorted, (0..vtk_n_nodes(kind)).collect::<Vec<_>>(), "{kind:?}");
                perm.iter().map(|&g| gmsh[g]).collect()
            }
            None => gmsh.clone(),
        };
        assert_eq!(vtk_geometry_error(kind, &vtk), None, "{kind:?}");
    }
    // The check has teeth: in gmsh order these kinds fail it.
    for kind in [
        CellKind::Tet10,
        CellKind::Hex20,
        CellKind::Hex27,
        CellKind::Prism6,
        CellKind::Prism15,
        CellKind::Prism18,
        CellKind::Pyramid13,
    ] {
        assert!(vtk_geometry_error(kind, &gmsh_reference(kind)).is_some(), "{kind:?}");
    }
}

#[test]
fn file_is_zlib_compressed_vtu() {
    let bytes = TestMesh::new(&[CellKind::Hex27]).bytes();
    let text = String::from_utf8(bytes).unwrap();
    assert!(text.contains("type=\"UnstructuredGrid\""), "{text}");
    assert!(text.contains("compressor=\"vtkZLibDataCompressor\""), "{text}");
    assert!(text.contains("header_type=\"UInt64\""), "{text}");
    assert!(text.contains("<Piece NumberOfPoints=\"27\" NumberOfCells=\"1\">"), "{text}");
}

#[test]
fn inconsistent_input_is_an_error_naming_it() {
    let mesh = TestMesh::new(&[CellKind::Quad4]);
    let short = [0.0; 11];
    let err =
        vtu_bytes(&mesh.points, &mesh.cells, &[Field { name: "displacement", n_comp: 3, values: &short }], &[], &[])
            .unwrap_err();
    let msg = err.to_string();
    assert!(msg.contains("displacement") && msg.contains("11") && msg.contains("12"), "{msg}");

    let err = vtu_bytes(&mesh.points, &mesh.cells, &[], &[Field { name: "stress", n_comp: 6, values: &[0.0; 7] }], &[])
        .unwrap_err();
    assert!(err.to_string().contains("stress"), "{err}");

    let err = vtu_bytes(&mesh.points, &mesh.cells, &[], &[], &[IntField { name: "body", values: &[] }]).unwrap_err();
    assert!(err.to_string().contains("body"), "{err}");

    let err = vtu_bytes(&mesh.points, &mesh.cells, &[Field { name: "nothing", n_comp: 0, values: &[] }], &[], &[])
        .unwrap_err();
    assert!(err.to_string().contains("nothing"), "{err}");

    let err = vtu_bytes(
        &mesh.points,
        &mesh.cells,
        &[Field { name: "huge", n_comp: usize::MAX, values: &[0.0; 4] }],
        &[],
        &[],
    )
    .unwrap_err();
    assert!(err.to_string().contains("huge"), "{err}");

    let mut bad = mesh.cells.clone();
    bad[0].nodes.pop();
    let err = vtu_bytes(&mesh.points, &bad, &[], &[], &[]).unwrap_err();
    assert!(err.to_string().contains("quad4") && err.to_string().contains("100"), "{err}");

    let mut bad = mesh.cells.clone();
    bad[0].nodes[2] = 4;
    let err = vtu_bytes(&mesh.points, &bad, &[], &[], &[]).unwrap_err();
    assert!(err.to_string().contains("node 4"), "{err}");
}
