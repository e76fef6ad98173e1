//! Condensation against the dense Schur complement of the same assembled
//! matrix: `S = K_cc - K_ci K_ii^-1 K_ic`, `G = F_c - K_ci K_ii^-1 F_i` and the
//! recovery `d_i = K_ii^-1 (F_i - K_ic d_c)`, computed with nalgebra from the
//! full stiffness of a small two-body model built in code.
//!
//! ```text
//!   y                        body 1 (no support: held only by contact,
//!   1 +-----+-----+  +-----+  S singular), traction on its right edge
//!     |  0  |  0  |  |  1  |
//!     +-----+-----+  +-----+   interface x = 1.2: three node pairs, the
//!     |  0  |  0  |  |  1  |   lower pair supported in y
//!   0 +-----+-----+  +-----+--- x
//!     0    (x = 0: ux held, one node moved by a prescribed uy)
//! ```
//! Both bodies have gravity; the grid is distorted so no entry is special.

use nalgebra::{DMatrix, DVector};

use faer::Par;

use super::ordering::Ordering;
use super::schur::PartialCholesky;
use super::{assembly, condense, condense_parts, interior_nodes, numbering, parts, Condensation};
use crate::fem::sparse::{SymMatrix, NONE};
use crate::fem::Analysis;
use crate::mesh::{Cell, CellKind};
use crate::model::{Body, FacetLoad, Interface, LoadKind, Material, Model, Pair};

/// Node `(i, j)` of a grid of `nx + 1` by `ny + 1` nodes starting at `first`.
fn quads(first: usize, nx: usize, ny: usize, tag0: u64) -> Vec<Cell> {
    let id = |i: usize, j: usize| first + j * (nx + 1) + i;
    let mut cells = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            cells.push(Cell {
                kind: CellKind::Quad4,
                nodes: vec![id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)],
                tag: tag0 + cells.len() as u64,
            });
        }
    }
    cells
}

/// Two bodies joined by one interface (`body_i` 0, `body_ii` 1), with a
/// gravity case and an initial case and no loads, supports, water or
/// seismic.
fn joined(
    iface: &str,
    (analysis, nd, gravity): (Analysis, usize, [f64; 3]),
    coords: Vec<[f64; 3]>,
    bodies: Vec<Body>,
    prescribed: Vec<Option<f64>>,
    pairs: Vec<Pair>,
) -> Model {
    Model {
        analysis,
        nd,
        thickness: 1.0,
        gravity,
        mesh_node: (0..coords.len()).collect(),
        coords,
        bodies,
        loads: Vec::new(),
        nodal_loads: Vec::new(),
        supports: Vec::new(),
        prescribed,
        pairs,
        interfaces: vec![Interface {
            name: iface.into(),
            body_i: 0,
            body_ii: 1,
            side_i: vec![0],
            facets: Vec::new(),
            sides: Vec::new(),
        }],
        cases: vec![vec![1.0], vec![1.0]],
        load_cases: Vec::new(),
        gravity_case: 0,
        initial_case: 1,
        hold_case: None,
        water: Vec::new(),
        seismic: Vec::new(),
    }
}

/// A body of the condensation tests: no block, no initial stress.
fn body(name: &str, group: usize, material: Material, cells: Vec<Cell>) -> Body {
    Body { name: name.into(), group, block: None, material, cells, initial: None }
}

/// The nodes of the two-body model (sketch in the header): body 0's 3 x 3
/// grid, then body 1's 2 x 3 grid from the returned index, whose left
/// column copies body 0's right one.
fn two_body_coords(ny: usize, h: f64) -> (Vec<[f64; 3]>, usize) {
    let wobble = |x: f64, y: f64| {
        [x + 0.05 * (3.0 * y).sin() * (x * (1.2 - x)), y + 0.04 * (2.0 * x).cos() * (y * (h - y)), 0.0]
    };
    let mut coords = Vec::new();
    // body 0: 3 x 3 nodes on [0, 1.2] x [0, 1]; its right column is the interface
    for j in 0..=ny {
        for i in 0..=2 {
            coords.push(wobble(0.6 * i as f64, h * j as f64 / ny as f64));
        }
    }
    // body 1: 2 x 3 nodes on [1.2, 2.0] x [0, 1]; its left column is a copy of the interface
    let first1 = coords.len();
    for j in 0..=ny {
        for i in 0..=1 {
            let x = 1.2 + 0.8 * i as f64;
            let p = wobble(x.min(1.2), h * j as f64 / ny as f64);
            coords.push([if i == 0 { p[0] } else { x }, p[1], 0.0]);
        }
    }
    (coords, first1)
}

/// The traction on body 1's right edge (nodes from `first1`).
fn two_body_loads(first1: usize) -> Vec<FacetLoad> {
    let right = Cell { kind: CellKind::Line2, nodes: vec![first1 + 1, first1 + 3], tag: 900 };
    let right2 = Cell { kind: CellKind::Line2, nodes: vec![first1 + 3, first1 + 5], tag: 901 };
    [right, right2]
        .into_iter()
        .map(|cell| FacetLoad {
            cell,
            sign: 1.0,
            kind: LoadKind::Traction([0.7, -0.3, 0.0]),
            body: 1,
            element: 0,
            case: 0,
        })
        .collect()
}

fn two_body_model() -> Model {
    let (ny, h, nd) = (2usize, 1.0, 2);
    // 1. the nodes and the interface's node pairs
    let (coords, first1) = two_body_coords(ny, h);
    let n = coords.len();
    let iface0: Vec<usize> = (0..=ny).map(|j| j * 3 + 2).collect();
    let iface1: Vec<usize> = (0..=ny).map(|j| first1 + j * 2).collect();
    // 2. the prescribed displacements
    let mut prescribed = vec![None; n * nd];
    for j in 0..=ny {
        prescribed[(j * 3) * nd] = Some(0.0); // x = 0: ux held
    }
    prescribed[1] = Some(0.0); // the origin: uy held
    prescribed[(2 * 3) * nd + 1] = Some(-2e-3); // top left node moved down
    prescribed[iface0[0] * nd + 1] = Some(0.0); // the lower pair held in y
    prescribed[iface1[0] * nd + 1] = Some(0.0);
    // 3. the pairs and the bodies
    let pairs = iface0
        .iter()
        .zip(&iface1)
        .map(|(&k, &l)| Pair { k, l, contact: 0, normal: [1.0, 0.0, 0.0], area: 0.5, shares: Vec::new() })
        .collect();
    let bodies = vec![
        body("left", 0, Material { e: 1000.0, nu: 0.3, density: 0.02 }, quads(0, 2, ny, 1)),
        body("right", 0, Material { e: 3000.0, nu: 0.2, density: 0.01 }, quads(first1, 1, ny, 100)),
    ];
    // 4. the model, with the traction on the right edge
    let kind = (Analysis::PlaneStrain, nd, [0.0, -9.81, 0.0]);
    let model = joined("cut", kind, coords, bodies, prescribed, pairs);
    Model { loads: two_body_loads(first1), ..model }
}

/// The dense reference of one part: interior DOFs numbered in reverse
/// node order (not the condensation's own numbering), interface DOFs in the
/// order of `part.interface`.
struct Dense {
    s: DMatrix<f64>,
    g: DVector<f64>,
    k_ii: DMatrix<f64>,
    k_ic: DMatrix<f64>,
    f_i: DVector<f64>,
    /// model DOF of each interior equation
    interior: Vec<usize>,
}

fn dense(model: &Model, part: &super::Part) -> Dense {
    let nd = model.nd;
    let interface = &part.interface;
    let used = part.nodes(model);
    let mut dof_of = vec![NONE; model.n_nodes() * nd];
    let mut interior = Vec::new();
    for &n in used.iter().rev() {
        if interface.contains(&n) {
            continue;
        }
        for c in 0..nd {
            if model.prescribed[n * nd + c].is_none() {
                dof_of[n * nd + c] = interior.len();
                interior.push(n * nd + c);
            }
        }
    }
    let ni = interior.len();
    for (q, &n) in interface.iter().enumerate() {
        for c in 0..nd {
            dof_of[n * nd + c] = ni + q * nd + c;
        }
    }
    let nc = interface.len() * nd;
    let a = assembly::assemble(model, &part.cells, &dof_of, ni + nc).expect("assemble");
    let k = DMatrix::from_fn(ni + nc, ni + nc, |r, c| a.k.get(r, c));
    let f = DVector::from_vec(a.f[0].clone());
    let k_ii = k.view((0, 0), (ni, ni)).into_owned();
    let k_ic = k.view((0, ni), (ni, nc)).into_owned();
    let k_cc = k.view((ni, ni), (nc, nc)).into_owned();
    let f_i = f.rows(0, ni).into_owned();
    let f_c = f.rows(ni, nc).into_owned();
    let chol = k_ii.clone().cholesky().expect("K_ii is positive definite");
    let x = chol.solve(&k_ic);
    let y = chol.solve(&f_i);
    let s = &k_cc - k_ic.transpose() * x;
    let g = f_c - k_ic.transpose() * y;
    Dense { s, g, k_ii, k_ic, f_i, interior }
}

fn rel(a: impl Iterator<Item = f64>, b: impl Iterator<Item = f64>) -> f64 {
    let (mut diff, mut scale) = (0.0f64, 0.0f64);
    for (x, y) in a.zip(b) {
        diff = diff.max((x - y).abs());
        scale = scale.max(y.abs());
    }
    diff / scale
}

#[test]
fn condensation_equals_the_dense_schur_complement() {
    let model = two_body_model();
    let parts = parts(&model);
    assert_eq!(parts.len(), 2);
    let mut checked = 0;
    for part in parts {
        let dense = dense(&model, &part);
        let name = model.body_names(&part.bodies);
        let c = condense(&model, part, Condensation::Dense).expect("condense");
        let nc = c.nc;
        assert_eq!(nc, 3 * model.nd, "{name}: every component of the three interface nodes");
        assert_eq!(c.ni, dense.interior.len(), "{name}");
        let es = rel((0..nc * nc).map(|i| c.s()[i]), (0..nc * nc).map(|i| dense.s[(i % nc, i / nc)]));
        let eg = rel(c.g[0].iter().copied(), dense.g.iter().copied());
        assert!(es < 1e-12, "{name}: S differs by {es:.3e} (relative)");
        assert!(eg < 1e-12, "{name}: G differs by {eg:.3e} (relative)");
        assert!(dense.g.amax() > 0.0 && dense.s.amax() > 0.0);

        // recovery of the interior for an arbitrary interface displacement
        let d_c: Vec<f64> = (0..nc).map(|i| 1e-3 * ((i as f64) * 0.7).sin()).collect();
        let mut u = vec![0.0; model.n_nodes() * model.nd];
        c.recover(&model, &d_c, &[1.0], &mut u);
        let d_i = dense
            .k_ii
            .clone()
            .cholesky()
            .expect("K_ii")
            .solve(&(&dense.f_i - &dense.k_ic * DVector::from_column_slice(&d_c)));
        let eu = rel(dense.interior.iter().map(|&dof| u[dof]), d_i.iter().copied());
        assert!(eu < 1e-12, "{name}: recovered interior differs by {eu:.3e} (relative)");
        eprintln!("{name}: S {es:.1e}, G {eg:.1e}, d_i {eu:.1e} (max relative difference to dense)");
        // condensed for the iterative interface: no S, but S applied, the
        // same G and the same recovery
        let applied = condense(&model, c.part.clone(), Condensation::Applied).expect("condense");
        assert!(applied.s().is_empty() && applied.is_applied());
        let cols = 2;
        let x: Vec<f64> = (0..nc * cols).map(|i| ((i as f64) * 1.3).cos()).collect();
        let sx = applied.apply(&x, cols);
        let want: Vec<f64> = (0..cols)
            .flat_map(|k| {
                (&dense.s * DVector::from_column_slice(&x[k * nc..(k + 1) * nc])).iter().copied().collect::<Vec<_>>()
            })
            .collect();
        let ea = rel(sx.iter().copied(), want.iter().copied());
        let eg = rel(applied.g[0].iter().copied(), dense.g.iter().copied());
        let mut ua = vec![0.0; u.len()];
        applied.recover(&model, &d_c, &[1.0], &mut ua);
        let eu = rel(dense.interior.iter().map(|&dof| ua[dof]), d_i.iter().copied());
        eprintln!("{name}, applied: S x {ea:.1e}, G {eg:.1e}, d_i {eu:.1e}");
        assert!(ea < 1e-12 && eg < 1e-12 && eu < 1e-12, "{name}, applied: S x {ea:.1e}, G {eg:.1e}, d_i {eu:.1e}");
        // a part whose factor was freed is factorised again to recover: the same numbers
        let mut c = c;
        c.drop_factor();
        let mut again = vec![0.0; u.len()];
        c.recover(&model, &d_c, &[1.0], &mut again);
        assert_eq!(u, again, "{name}: recovery after the factor was freed");
        for (q, &n) in c.part.interface.iter().enumerate() {
            for k in 0..model.nd {
                assert_eq!(u[n * model.nd + k], d_c[q * model.nd + k]);
            }
        }
        // the part's prescribed DOFs off the interface carry their values
        // (times the ramp's factor): the left body's top left node its -2e-3
        let fixed: Vec<usize> = (c.part.nodes(&model).into_iter().flat_map(|n| n * model.nd..(n + 1) * model.nd))
            .filter(|i| model.prescribed[*i].is_some() && !c.part.interface.contains(&(i / model.nd)))
            .collect();
        let mut half = vec![f64::NAN; u.len()];
        c.recover(&model, &d_c, &[0.5], &mut half);
        for i in fixed {
            assert_eq!(half[i], 0.5 * model.prescribed[i].unwrap_or(f64::NAN), "{name}: DOF {i}");
            checked += usize::from(model.prescribed[i] != Some(0.0));
        }
    }
    assert_eq!(checked, 1, "the one DOF moved by a prescribed value is checked");
}

/// The right body has no support: its S keeps the three rigid-body modes
/// of the interface (translations and the rotation about the origin).
#[test]
fn condensed_floating_body_keeps_its_rigid_body_modes() {
    let model = two_body_model();
    let part = parts(&model).into_iter().find(|p| p.bodies == [1]).expect("the right body");
    let c = condense(&model, part, Condensation::Dense).expect("condense");
    let nc = c.nc;
    let s = DMatrix::from_column_slice(nc, nc, c.s());
    let nodes = &c.part.interface;
    let modes = [
        DVector::from_fn(nc, |i, _| if i % 2 == 0 { 1.0 } else { 0.0 }),
        DVector::from_fn(nc, |i, _| if i % 2 == 1 { 1.0 } else { 0.0 }),
        DVector::from_fn(nc, |i, _| {
            let x = model.coords[nodes[i / 2]];
            if i % 2 == 0 {
                -x[1]
            } else {
                x[0]
            }
        }),
    ];
    for (m, v) in modes.iter().enumerate() {
        let r = (&s * v).amax() / (s.amax() * v.amax());
        assert!(r < 1e-12, "mode {m}: |S v| / (|S| |v|) = {r:.3e}");
    }
    // and nothing else: exactly three eigenvalues vanish
    let eig = s.symmetric_eigenvalues();
    let big = eig.amax();
    assert_eq!(eig.iter().filter(|&&e| e.abs() < 1e-10 * big).count(), 3, "{eig}");
}

/// Two hex8 blocks of `m x m x h` elements stacked in z and joined by a
/// contact plane of `(m + 1)^2` node pairs; the lower block's base is held,
/// the upper block floats (S singular). Slightly skewed, under gravity.
fn stacked_blocks(m: usize, h: usize) -> Model {
    let nx = m + 1;
    // 1. the two blocks, lower (0) then upper (1)
    let mut coords = Vec::new();
    let bodies = (0..2).map(|b| hex_block(b, m, h, &mut coords)).collect();
    // 2. the lower base held
    let mut prescribed = vec![None; coords.len() * 3];
    for q in 0..nx * nx {
        for c in 0..3 {
            prescribed[q * 3 + c] = Some(0.0); // the lower base
        }
    }
    // 3. the lower block's top paired with the upper block's base
    let per = nx * nx * (h + 1);
    let pairs = (0..nx * nx)
        .map(|q| Pair {
            k: h * nx * nx + q,
            l: per + q,
            contact: 0,
            normal: [0.0, 0.0, 1.0],
            area: 1.0,
            shares: Vec::new(),
        })
        .collect();
    let kind = (Analysis::Solid, 3, [0.0, 0.0, -9.81]);
    joined("joint", kind, coords, bodies, prescribed, pairs)
}

/// Block `b` of the stacked blocks: its skewed nodes appended to `coords`
/// and its `m x m x h` hex8 cells.
fn hex_block(b: usize, m: usize, h: usize, coords: &mut Vec<[f64; 3]>) -> Body {
    let (nx, nz) = (m + 1, h + 1);
    let first = coords.len();
    for k in 0..nz {
        for j in 0..nx {
            for i in 0..nx {
                let (x, y, z) = (i as f64 / m as f64, j as f64 / m as f64, (b * h + k) as f64 / h as f64);
                coords.push([x + 0.03 * (2.0 * y).sin() * z, y + 0.02 * (3.0 * x).cos() * z, z + 0.01 * x * y]);
            }
        }
    }
    let id = |i: usize, j: usize, k: usize| first + (k * nx + j) * nx + i;
    let mut cells = Vec::new();
    for k in 0..h {
        for j in 0..m {
            for i in 0..m {
                let nodes = vec![
                    id(i, j, k),
                    id(i + 1, j, k),
                    id(i + 1, j + 1, k),
                    id(i, j + 1, k),
                    id(i, j, k + 1),
                    id(i + 1, j, k + 1),
                    id(i + 1, j + 1, k + 1),
                    id(i, j + 1, k + 1),
                ];
                cells.push(Cell { kind: CellKind::Hex8, nodes, tag: (b * 10_000 + cells.len()) as u64 });
            }
        }
    }
    let material = Material { e: 1000.0 * (b + 1) as f64, nu: 0.25, density: 0.01 };
    body(&format!("block{b}"), b, material, cells)
}

/// Both orderings give the dense Schur complement, in
/// 2D (the two-body model) and 3D (stacked blocks with 190 interior nodes
/// per block, so METIS dissects rather than falling back to minimum degree
/// on a small graph).
#[test]
fn every_ordering_gives_the_dense_schur_complement() {
    for (label, model) in [("two_body_model", two_body_model()), ("stacked_blocks", stacked_blocks(6, 5))] {
        for part in parts(&model) {
            let dense = dense(&model, &part);
            let (dof_of, ni, nc) = numbering(&model, &part);
            let a = assembly::assemble(&model, &part.cells, &dof_of, ni + nc).expect("assemble");
            let node_of = interior_nodes(&dof_of, model.nd, ni);
            for ordering in [Ordering::Amd, Ordering::NestedDissection] {
                let chol = PartialCholesky::factor(&a.k, ni, &node_of, ordering, Par::Seq).expect("factor");
                let s = chol.schur(Par::Seq);
                let es = rel((0..nc * nc).map(|i| s[i]), (0..nc * nc).map(|i| dense.s[(i % nc, i / nc)]));
                let name = format!("{label} {}: {ordering:?}", model.body_names(&part.bodies));
                assert!(es < 1e-11, "{name}: S differs by {es:.3e} (relative)");
                assert!((0..nc).all(|i| (0..nc).all(|j| s[i + j * nc] == s[j + i * nc])), "{name}: S is not symmetric");
            }
        }
    }
}

/// Nested dissection cuts the fill of a 3D block against AMD (the reason
/// it is used in 3D), and both orderings factor the same matrix.
#[test]
fn nested_dissection_cuts_3d_fill() {
    let model = stacked_blocks(10, 8);
    let part = parts(&model).into_iter().find(|p| p.bodies == [0]).expect("the lower block");
    let (dof_of, ni, _) = numbering(&model, &part);
    let a = assembly::assemble(&model, &part.cells, &dof_of, dof_of.iter().filter(|&&d| d != NONE).count())
        .expect("assemble");
    let node_of = interior_nodes(&dof_of, model.nd, ni);
    let flops = |o| PartialCholesky::factor(&a.k, ni, &node_of, o, Par::Seq).expect("factor").stats().flops;
    let (amd, nd) = (flops(Ordering::Amd), flops(Ordering::NestedDissection));
    eprintln!("10 x 10 x 8 hex8, {ni} interior equations: factor flops AMD {amd:.3e}, nested dissection {nd:.3e}");
    assert!(nd < amd, "nested dissection {nd:.3e} flops against AMD {amd:.3e}");
}

/// Parts condensed in threads come back in order, equal to one after the
/// other; a part that cannot be held is the error either way.
#[test]
fn parts_condensed_in_threads_equal_one_after_the_other() {
    let model = stacked_blocks(4, 3);
    let one = condense_parts(&model, parts(&model), 1, Condensation::Dense).expect("condense");
    let two = condense_parts(&model, parts(&model), 2, Condensation::Dense).expect("condense");
    assert_eq!(one.len(), 2);
    for (a, b) in one.iter().zip(&two) {
        assert_eq!(a.part.bodies, b.part.bodies);
        assert_eq!(a.s(), b.s());
        assert_eq!(a.g, b.g);
    }
    // with no support and no contact both blocks float: block0, the first,
    // is the error
    let mut free = stacked_blocks(4, 3);
    free.prescribed.iter_mut().for_each(|p| *p = None);
    free.pairs.clear();
    for threads in [1, 2] {
        let e =
            condense_parts(&free, parts(&free), threads, Condensation::Dense).err().expect("a free part is refused");
        assert!(e.to_string().contains("block0"), "{e}");
    }
}

/// `subcontact check` counts the DOFs without numbering the parts: the
/// same interior and interface counts as `numbering` part by part (the
/// two-body model with prescribed and supported nodes, and the stacked
/// blocks cut into pieces that share bonded joins).
#[test]
fn dof_counts_equal_the_numbering_of_the_parts() {
    for (model, k) in [(two_body_model(), 1), (stacked_blocks(4, 3), 1), (stacked_blocks(4, 3), 3)] {
        let cut = super::cut(&model, parts(&model), k);
        let counts = super::parts::dof_counts(&model, &cut);
        let interior: usize = cut.iter().map(|p| numbering(&model, p).1).sum();
        let mut shared: Vec<usize> = cut.iter().flat_map(|p| p.interface.iter().copied()).collect();
        shared.sort_unstable();
        shared.dedup();
        let in_pair = |n: usize| model.pairs.iter().any(|p| p.k == n || p.l == n);
        let iface: usize = shared
            .iter()
            .map(|&n| {
                if in_pair(n) {
                    model.nd
                } else {
                    (0..model.nd).filter(|&c| model.prescribed[n * model.nd + c].is_none()).count()
                }
            })
            .sum();
        assert!(iface > 0, "the model has an interface");
        assert_eq!(
            counts,
            super::parts::DofCounts { total: interior + iface, interface: iface },
            "{} pieces",
            cut.len()
        );
    }
}

/// A block whose every node lies on its contacts has no interior: its
/// interior factor is empty (faer makes it simplicial, forced supernodal
/// or not), and the iterative interface applies its S = K_cc. The 44k-DOF
/// tet10 tunnel through three sets panicked here with `--interface
/// iterative`.
#[test]
fn a_part_with_no_interior_applies_its_own_stiffness() {
    use super::interior::InteriorSolve;
    // K = [[2, -1], [-1, 3]], lower triangle by columns; both on the interface
    let k = SymMatrix { n: 2, col_ptr: vec![0, 2, 3], row_idx: vec![0, 1, 1], values: vec![2.0, -1.0, 3.0] };
    for ordering in [Ordering::Amd, Ordering::NestedDissection] {
        let solve = InteriorSolve::factor(&k, 0, &[], ordering, Par::Seq).expect("factor");
        assert_eq!(solve.factor_bytes(), 0, "{ordering:?}");
        assert_eq!(solve.apply(&[1.0, 0.0, 0.0, 1.0], 2), vec![2.0, -1.0, -1.0, 3.0], "{ordering:?}");
    }
}
