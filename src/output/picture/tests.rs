//! Tests of the pictures: the PNG round trip, number formats, font
//! metrics, and pictures of real runs (cylinder, the paper's 3D mesh,
//! stacked blocks in every element kind) checked for the colours they must
//! show; the pictures are kept in the temporary directory to look at. The
//! runs solve committed meshes (tests/fixtures/msh/picture-*.msh, made by
//! its make.sh from the scenes' .geo with the parameters named here), so
//! these tests call no gmsh; tests/pictures.rs meshes with the gmsh CLI.

use super::colours::{OPEN, SLIP, STICK};
use super::deformed::{deformed_canvas, H, W};
use super::interfaces::{along, interface_plot_png};
use super::label_numbers::{num, sig2};
use super::legend::nice_step;
use super::legend::PANEL_X;
use super::raster::{encode_png, register_font, Canvas, FontMetrics};
use super::*;
use crate::contact::law::ContactState;
use crate::driver::{self, RunOptions};
use crate::fem::vec3::{dot, sub};
use crate::results::{state_counts, Run};
use crate::scene::{GmshOptions, MeshSource, Scene};
use plotters::style::IntoFont;
use std::path::{Path, PathBuf};

/// Decodes a PNG to (width, height, rgb) with the `png` crate.
fn decode(bytes: &[u8]) -> (usize, usize, Vec<u8>) {
    let mut reader = png::Decoder::new(bytes).read_info().expect("a PNG header");
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).expect("the PNG's pixels");
    assert_eq!((info.color_type, info.bit_depth), (png::ColorType::Rgb, png::BitDepth::Eight));
    buf.truncate(info.buffer_size());
    (info.width as usize, info.height as usize, buf)
}

#[test]
fn png_decodes_to_the_pixels_it_was_given() {
    let (w, h) = (97, 61);
    let mut rgb = vec![255u8; w * h * 3];
    for y in 0..h {
        for x in 0..w {
            let i = (y * w + x) * 3;
            rgb[i] = if x < 30 { 10 } else { (x * 2) as u8 };
            rgb[i + 1] = ((x * y) % 251) as u8;
            rgb[i + 2] = if y > 40 { ((x * 7919 + y * 104729) % 256) as u8 } else { 200 };
        }
    }
    let bytes = encode_png(w, h, &rgb).expect("PNG");
    let (dw, dh, back) = decode(&bytes);
    assert_eq!((dw, dh), (w, h));
    assert!(back == rgb, "pixels survive the round trip");
}

#[test]
fn numbers_read_well() {
    assert_eq!(num(0.15000000000000002), "0.15");
    assert_eq!(num(-2125.0), "-2125");
    assert_eq!(num(1.2345e-5), "1.23e-5");
    assert_eq!(sig2(23456.0), "2.3e4");
    assert_eq!(sig2(234.5), "230");
    assert_eq!(sig2(96.0 * 0.1), "9.6");
    assert_eq!(nice_step(0.037), 0.05);
    assert_eq!(Field::parse("sxy"), Some(Field::Sxy));
}

#[test]
fn font_metrics_give_plotters_string_widths() {
    register_font();
    let m = FontMetrics::get().expect("metrics");
    for text in ["contact pairs", "open (6)", "σθθ (hoop stress) × 2.3e4"] {
        let ours: f64 = text.chars().map(|c| m.glyph(c).0).sum::<f64>() * 40.0 / m.height;
        let (w, _) = ("sans-serif", 40.0).into_font().box_size(text).expect("layout");
        assert!((ours - w as f64).abs() <= 2.0, "{text}: {ours} vs {w}");
    }
}

fn out_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("subcontact_picture_{name}"));
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

/// Where the pictures go for a person to look at.
fn keep(name: &str, bytes: &[u8]) {
    let d = std::env::temp_dir().join("subcontact_pictures");
    std::fs::create_dir_all(&d).expect("picture dir");
    std::fs::write(d.join(name), bytes).expect("write picture");
}

/// Pixels of colour `c` where the model is drawn (not in the legend).
fn count(cv: &Canvas, c: [u8; 3]) -> usize {
    cv.rgb.chunks_exact(3).enumerate().filter(|(i, p)| (i % cv.w) < PANEL_X as usize - 10 && p == &c).count()
}

/// The columns of the pixels of colour `c` inside box `b` (x0, y0, x1, y1).
fn in_box(cv: &Canvas, b: [f64; 4], c: [u8; 3]) -> Vec<usize> {
    (b[1] as usize..b[3] as usize)
        .flat_map(|y| (b[0] as usize..b[2] as usize).map(move |x| (x, y)))
        .filter(|&(x, y)| cv.rgb[(y * cv.w + x) * 3..][..3] == c)
        .map(|(x, _)| x)
        .collect()
}

/// The last state of a run, to draw.
fn snap(run: &Run) -> Snapshot<'_> {
    Snapshot {
        title: &run.about.title,
        model: &run.model,
        u: &run.last().u,
        stresses: &run.last().stresses,
        contact: run.contact(),
        region: run.about.output.frame.as_ref(),
        one_scale: false,
    }
}

fn contact(run: &Run) -> &crate::results::ContactRun {
    run.contact().expect("a run with contact")
}

/// A committed mesh of tests/fixtures/msh/ by name (without `.msh`).
fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/msh").join(format!("{name}.msh"))
}

/// `scene` solved on the fixture mesh `msh` in place of its .geo (no
/// gmsh), without result files.
fn run_on(mut scene: Scene, msh: &str) -> Run {
    scene.mesh = MeshSource::Msh(fixture(msh));
    scene.gmsh = GmshOptions::default();
    let opts = RunOptions { out: Some(out_dir(msh)), skip_output: true, ..Default::default() };
    driver::run_scene(scene, &opts).expect("run")
}

/// geo/cylinder.toml on `picture-cylinder-lc<lc>-o<order>.msh`: lc 0.25
/// order 2 (quad9) or lc 0.5 order 1 (quad4).
fn cylinder(lc: f64, order: usize) -> Run {
    let scene = Scene::load(Path::new("geo/cylinder.toml")).expect("scene");
    run_on(scene, &format!("picture-cylinder-lc{lc}-o{order}"))
}

#[test]
fn cylinder_picture_shows_the_field_and_every_contact_state() {
    let mut run = cylinder(0.25, 2);
    let bytes = deformed_png(&snap(&run), Field::VonMises, None).expect("picture");
    let (w, h, _) = decode(&bytes);
    assert_eq!((w, h), (W, H));
    keep("cylinder_von_mises.png", &bytes);
    let cv = deformed_canvas(&snap(&run), Field::VonMises, None).expect("canvas");
    // the cut sticks everywhere (the paper's data)
    assert!(count(&cv, STICK) > 300, "stick line drawn: {}", count(&cv, STICK));
    assert_eq!(count(&cv, OPEN) + count(&cv, SLIP), 0);
    keep("cylinder_szz.png", &deformed_png(&snap(&run), Field::Szz, None).expect("picture"));
    keep("cylinder_sxy.png", &deformed_png(&snap(&run), Field::Sxy, None).expect("picture"));

    // every state, in thirds along the cut
    let c = run.steps.last_mut().and_then(|s| s.contact.as_mut()).expect("contact");
    let n = c.states.len();
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| {
        let r = |p: usize| run.model.coords[run.model.pairs[p].k][0];
        r(a).total_cmp(&r(b))
    });
    for (i, &p) in order.iter().enumerate() {
        c.states[p] = [ContactState::Open, ContactState::Slip, ContactState::Stick][3 * i / n];
    }
    let cv = deformed_canvas(&snap(&run), Field::Displacement, Some(2.0e3)).expect("canvas");
    for (name, colour) in [("stick", STICK), ("slip", SLIP), ("open", OPEN)] {
        assert!(count(&cv, colour) > 100, "{name}: {} pixels", count(&cv, colour));
    }
    keep("cylinder_states_displacement.png", &encode_png(cv.w, cv.h, &cv.rgb).expect("PNG"));
    let svg = interface_plot_svg(&run.model, contact(&run)).expect("interface plot");
    for want in ["A-A", "stick", "slip", "open", "σn", "distance along the interface from (2.121, 2.121)"] {
        assert!(svg.contains(want), "{want}");
    }
    keep("cylinder_states_interfaces.svg", svg.as_bytes());
    let bytes = interface_plot_png(&run.model, contact(&run)).expect("interface plot");
    assert_eq!(decode(&bytes).0, 1000);
    keep("cylinder_states_interfaces.png", &bytes);
}

#[test]
fn interface_pairs_are_ordered_by_arc_length_from_the_inner_end() {
    let run = cylinder(0.25, 2);
    let al = along(&run.model, 0);
    assert_eq!(al.runs.len(), 1);
    let r = &al.runs[0];
    assert_eq!(r.len(), run.model.pairs.len());
    for &(p, s) in r {
        let x = run.model.coords[run.model.pairs[p].k];
        let radius = x[0].hypot(x[1]);
        assert!((s - (radius - 3.0)).abs() < 1e-9, "s = {s} at r = {radius}");
    }
    keep("cylinder_interfaces.png", &interface_plot_png(&run.model, contact(&run)).expect("plot"));
}

/// Regression: an interface whose two ends lie equally far from the
/// model's corner (the quarter tunnel's lining, from (R + t/2, 0) to
/// (0, R + t/2)) was walked from either end by the hash map's order, so
/// the plot's axis flipped from run to run.
#[test]
fn interface_walk_starts_at_the_same_end_every_time() {
    // D = 20, R = 5, lc = 0.5, nl = 1, nr = 8, t = 0.125
    let run = run_on(Scene::load(Path::new("geo/tunnel_slip.toml")).expect("scene"), "picture-tunnel-slip");
    let first = along(&run.model, 0);
    for _ in 0..12 {
        let again = along(&run.model, 0);
        assert_eq!(again.axis, first.axis);
        assert_eq!(again.runs, first.runs);
    }
}

#[test]
fn paper_mesh_picture_in_3d() {
    let run = run_on(Scene::load(Path::new("geo/cylinder_paper.toml")).expect("scene"), "picture-cylinder-paper");
    let cv = deformed_canvas(&snap(&run), Field::VonMises, None).expect("canvas");
    assert!(count(&cv, STICK) > 50, "stick dots: {}", count(&cv, STICK));
    let bytes = encode_png(cv.w, cv.h, &cv.rgb).expect("PNG");
    assert_eq!(decode(&bytes).0, W);
    keep("paper_von_mises.png", &bytes);
    let svg = interface_plot_svg(&run.model, contact(&run)).expect("plot");
    assert!(svg.contains("12 stick"));
    keep("paper_interfaces.svg", svg.as_bytes());
    keep("paper_interfaces.png", &interface_plot_png(&run.model, contact(&run)).expect("plot"));
    // the 45-degree cut is vertical: seen along its normal, z up
    let (cv, boxes) = super::plan::plan_canvas(&run.about.title, &run.model, contact(&run), &plan_files(&run.model)[0])
        .expect("plan view");
    let stick = in_box(&cv, boxes[0], STICK).len();
    assert!(stick > 20_000, "the cut sticks: {stick} pixels");
    keep("paper_plan.png", &encode_png(cv.w, cv.h, &cv.rgb).expect("PNG"));
}

/// Two blocks stacked on a frictional joint (f = 0.8) without cohesion
/// or tensile strength, the top face pushed down and sideways: the push
/// tips the top block, so the joint opens at one end, slips in the
/// middle and sticks where it is pressed hardest. Every 2D kind and
/// hex20 (the boxes clamped at the base and held in z, the top one held
/// by the joint); tet4 under a joint too strong to give (pushed, the
/// unstructured tetrahedra make the contact iteration cycle).
#[test]
fn stacked_blocks_pushed_sideways_show_the_states_they_reach() {
    let dir = out_dir("stack");
    for geo in ["contact_stack.geo", "contact_stack3d.geo"] {
        std::fs::copy(format!("tests/geo/{geo}"), dir.join(geo)).expect("copy geo");
    }
    let weak = "friction = 0.8\ncohesion = 0.0\ntensile_strength = 0.0";
    let strong = "friction = 0.5\ncohesion = 100.0\ntensile_strength = 100.0";
    let plane = (
        "contact_stack.geo",
        "plane_stress",
        "[[supports]]\ngroup = \"base\"\nfix = [\"y\"]\n[[supports]]\ngroup = \"corner\"\nfix = [\"x\"]\n",
        "[0.5, -1.0]",
        weak,
    );
    let solid = ("contact_stack3d.geo", "solid", "[[supports]]\ngroup = \"base\"\nfix = [\"x\", \"y\", \"z\"]\n[[supports]]\ngroup = \"z_faces\"\nfix = [\"z\"]\n", "[0.5, -1.0, 0.0]", weak);
    let cases = [
        ("tri6", 2, "n = 8, quad = 0", plane),
        ("tri3", 1, "n = 10, quad = 0", plane),
        ("quad4", 1, "n = 10, quad = 1", plane),
        ("quad8", 2, "n = 6, quad = 1, serendipity = 1", plane),
        ("hex20", 2, "n = 4, nz = 2, hex = 1, serendipity = 1", solid),
        (
            "tet4",
            1,
            "n = 6, hex = 0",
            (
                solid.0,
                solid.1,
                "[[supports]]\ngroup = \"base\"\nfix = [\"x\", \"y\", \"z\"]\n",
                "[0.3, -1.0, 0.2]",
                strong,
            ),
        ),
    ];
    for (name, order, set, case) in cases {
        // 1. the scene, run on the mesh gmsh makes of it (committed)
        let path = dir.join(format!("stack_{name}.toml"));
        std::fs::write(&path, stack_scene(name, order, set, case)).expect("scene");
        let run = run_on(Scene::load(&path).expect("scene"), &format!("picture-stack-{name}"));
        // 2. the states it reaches
        let c = run.contact().expect("contact");
        let counts = state_counts(&c.states);
        eprintln!(
            "{name}: {} stick, {} slip, {} open after {} iterations",
            counts[2], counts[1], counts[0], c.summary.iterations
        );
        assert!(c.summary.converged, "{name}");
        if case.4 == weak {
            assert!(
                counts[0] > 0 && counts[2] > 0,
                "{name}: the joint opens at one end and sticks at the other: {counts:?}"
            );
        }
        // 3. every state drawn exactly when present
        stack_pictures(name, &run, counts, case.1 == "solid");
    }
}

/// The scene of a stacked-blocks case: `(geo, analysis, supports,
/// traction, joint)` meshed at `order` with the `set` numbers.
fn stack_scene(name: &str, order: usize, set: &str, case: (&str, &str, &str, &str, &str)) -> String {
    let (geo, analysis, supports, traction, joint) = case;
    format!(
        "title = \"Two blocks, the top one pushed sideways ({name})\"\nmesh = \"{geo}\"\nanalysis = \"{analysis}\"\n\
         [gmsh]\norder = {order}\nsetnumber = {{ {set} }}\n[materials.m]\nE = 1000.0\nnu = 0.25\n\
         [[bodies]]\ngroup = \"bottom\"\nmaterial = \"m\"\n[[bodies]]\ngroup = \"top\"\nmaterial = \"m\"\n\
         [[contacts]]\ngroup = \"joint\"\n{joint}\n\
         {supports}[[loads]]\ngroup = \"top_face\"\ntraction = {traction}\n"
    )
}

/// The pictures of a stacked-blocks run (deformed, plan view in 3D,
/// interface plots) show each state exactly when it has pairs.
fn stack_pictures(name: &str, run: &Run, counts: [usize; 3], solid: bool) {
    let c = run.contact().expect("contact");
    let t = std::time::Instant::now();
    let cv = deformed_canvas(&snap(run), Field::VonMises, None).expect("canvas");
    eprintln!("{name}: rendered in {:.3} s", t.elapsed().as_secs_f64());
    for (state, colour, n) in [("open", OPEN, counts[0]), ("slip", SLIP, counts[1]), ("stick", STICK, counts[2])] {
        assert_eq!(count(&cv, colour) > 0, n > 0, "{name}: {state} drawn exactly when present ({n} pairs)");
    }
    keep(&format!("stack_{name}_von_mises.png"), &encode_png(cv.w, cv.h, &cv.rgb).expect("PNG"));
    if solid {
        let (cv, boxes) =
            super::plan::plan_canvas(&run.about.title, &run.model, c, &plan_files(&run.model)[0]).expect("plan view");
        for (state, colour, n) in [("open", OPEN, counts[0]), ("slip", SLIP, counts[1]), ("stick", STICK, counts[2])] {
            assert_eq!(
                !in_box(&cv, boxes[0], colour).is_empty(),
                n > 0,
                "{name}: {state} in plan exactly when present ({n} pairs)"
            );
        }
        keep(&format!("stack_{name}_plan.png"), &encode_png(cv.w, cv.h, &cv.rgb).expect("PNG"));
    }
    keep(&format!("stack_{name}_syy.png"), &deformed_png(&snap(run), Field::Syy, None).expect("picture"));
    keep(&format!("stack_{name}_interfaces.png"), &interface_plot_png(&run.model, contact(run)).expect("plot"));
    let svg = interface_plot_svg(&run.model, contact(run)).expect("plot");
    assert!(svg.contains(&format!("{} stick, {} slip, {} open", counts[2], counts[1], counts[0])));
}

/// Regression: thin triangles sharing edges left unpainted pixels
/// between them (white specks over a fine mesh) when the barycentric
/// weights were taken in f32 about the image origin.
#[test]
fn triangles_sharing_edges_leave_no_gaps() {
    let mut cv = Canvas::new(400, 300);
    let n = 60;
    // a jittered grid over [50, 350] x [40, 260], two triangles per square
    let pt = |i: usize, j: usize| -> [f32; 2] {
        let jitter = |k: usize| {
            if i == 0 || j == 0 || i == n || j == n {
                0.0
            } else {
                ((k * 7919 % 101) as f32 / 101.0 - 0.5) * 2.0
            }
        };
        [
            50.0 + 300.0 * i as f32 / n as f32 + jitter(i * 31 + j),
            40.0 + 220.0 * j as f32 / n as f32 + jitter(j * 17 + i * 3),
        ]
    };
    for i in 0..n {
        for j in 0..n {
            let (a, b, c, d) = (pt(i, j), pt(i + 1, j), pt(i + 1, j + 1), pt(i, j + 1));
            cv.triangle([a, b, c], [0.0; 3], &|_| [0, 0, 0]);
            cv.triangle([a, c, d], [0.0; 3], &|_| [0, 0, 0]);
        }
    }
    let white = (41..259)
        .flat_map(|y| (51..349).map(move |x| (x, y)))
        .filter(|&(x, y)| cv.rgb[(y * 400 + x) * 3] == 255)
        .count();
    assert_eq!(white, 0, "unpainted pixels inside the mesh");
}

/// The shipped 3D partial-slip scene (`geo/blocks3d.toml`: a tet10 block
/// pressed onto a block and pushed along +x, f = 0.5), coarser (lc = 0.2):
/// the plan view of the joint shows the trailing edge (x = 0) slipping and
/// the leading edge sticking, as regions in proportion to the pairs in each
/// state, the slip arrows pointing +x, and sigma_n most compressive at the
/// leading edge.
#[test]
fn plan_view_of_a_3d_joint_shows_where_it_slips() {
    // tet10: lc = 0.2, hex = 0
    let run = run_on(Scene::load(Path::new("geo/blocks3d.toml")).expect("scene"), "picture-blocks3d-tet10");
    let c = contact(&run);
    let counts = state_counts(&c.states);
    eprintln!(
        "blocks3d, lc = 0.2: {} pairs, {} stick, {} slip, {} open",
        c.states.len(),
        counts[2],
        counts[1],
        counts[0]
    );
    assert!(c.summary.converged && counts[1] > 0 && counts[2] > 0 && counts[0] == 0, "partial slip: {counts:?}");
    let plans: Vec<(usize, String)> = plan_files(&run.model).into_iter().map(|p| (p.interface, p.file)).collect();
    assert_eq!(plans, vec![(0, "plan_joint.png".to_string())]);

    let t = std::time::Instant::now();
    let (cv, boxes) =
        super::plan::plan_canvas(&run.about.title, &run.model, c, &plan_files(&run.model)[0]).expect("plan view");
    eprintln!("plan view drawn in {:.3} s", t.elapsed().as_secs_f64());
    keep("blocks3d_plan_joint.png", &encode_png(cv.w, cv.h, &cv.rgb).expect("PNG"));
    let pixels = |b: [f64; 4], colour: [u8; 3]| in_box(&cv, b, colour);
    let (slip, stick) = (pixels(boxes[0], SLIP), pixels(boxes[0], STICK));
    assert!(pixels(boxes[0], OPEN).is_empty(), "no pair opens");
    let area = slip.len() as f64 / (slip.len() + stick.len()) as f64;
    let pairs = counts[1] as f64 / (counts[1] + counts[2]) as f64;
    eprintln!("slip: {:.3} of the painted joint, {:.3} of the pairs", area, pairs);
    assert!(stick.len() > 20_000 && (area - pairs).abs() < 0.1, "slip area {area:.3} against slip pairs {pairs:.3}");
    let mean = |v: &[usize]| v.iter().sum::<usize>() as f64 / v.len() as f64;
    assert!(mean(&slip) + 100.0 < mean(&stick), "the trailing edge (left) slips, the leading edge (right) sticks");
    assert!(pixels(boxes[1], SLIP).is_empty() && pixels(boxes[1], STICK).is_empty(), "sigma_n has no state colours");
    // sigma_n: the leading edge (right) is pressed hardest, the bluest
    let b = boxes[1];
    let mid = (0.5 * (b[1] + b[3])) as usize;
    let rgb_at = |x: f64| -> [u8; 3] {
        let i = (mid * cv.w + x as usize) * 3;
        [cv.rgb[i], cv.rgb[i + 1], cv.rgb[i + 2]]
    };
    let (left, right) = (rgb_at(b[0] + 30.0), rgb_at(b[2] - 30.0));
    assert!(
        right[0] + 60 < left[0] && right[2] > right[0] + 60,
        "grey at the trailing edge, blue at the leading one: left {left:?}, right {right:?}"
    );

    // the arrows: the shear on "lower" from "upper" along +x, the way the
    // upper block slips over the lower one (its relative displacement)
    let nd = run.model.nd;
    for (p, pair) in run.model.pairs.iter().enumerate().filter(|&(p, _)| c.states[p] == ContactState::Slip) {
        let t = c.shear(p);
        let u = &run.last().u;
        let rel: [f64; 3] = std::array::from_fn(|d| u[pair.l * nd + d] - u[pair.k * nd + d]);
        let slip = sub(rel, pair.normal.map(|x| x * dot(rel, pair.normal)));
        assert!(
            (dot(t, t).sqrt() - c.pairs[p].tau()).abs() <= 1e-9 * c.pairs[p].tau().max(1e-12),
            "pair {p}: the frame is orthonormal"
        );
        assert!(t[0] > 0.9 * dot(t, t).sqrt(), "pair {p}: shear {t:?} along +x");
        assert!(
            dot(t, slip) > 0.99 * dot(t, t).sqrt() * dot(slip, slip).sqrt(),
            "pair {p}: shear {t:?} along the slip {slip:?}"
        );
    }

    // in report.md, under the contact pictures
    let report = crate::output::report::report(&run, &crate::output::Derived::of(&run));
    assert!(report.contains("![plan view of joint: where it sticks, slips and opens; sigma_n](plan_joint.png)"));
}

/// Plane and axisymmetric runs get no plan view; a stale one is removed.
#[test]
fn no_plan_view_in_2d_and_stale_ones_are_removed() {
    let run = cylinder(0.25, 2);
    assert!(plan_files(&run.model).is_empty());
    let files: Vec<String> = drawn(&snap(&run)).into_iter().map(|(f, _)| f).collect();
    assert_eq!(files, ["deformed_von_mises.png", "interfaces.svg"]);
    assert!(!crate::output::report::report(&run, &crate::output::Derived::of(&run)).contains("plan_"));
    // an earlier run's plan views go with the next commit (the manifest
    // lists them); a user's picture stays
    let dir = out_dir("stale_plans").join("out");
    let mut earlier = crate::output::files::Staged::new(&dir, "cylinder");
    for f in ["plan_joint.png", "plan_old_face.png", "deformed_displacement.png"] {
        earlier.add(f, b"x".to_vec());
    }
    earlier.commit().expect("commit");
    std::fs::write(dir.join("notes.png"), b"x").expect("file");
    let mut now = crate::output::files::Staged::new(&dir, "cylinder");
    for (f, bytes) in drawn(&snap(&run)) {
        now.add(&f, bytes);
    }
    now.commit().expect("commit");
    let mut left: Vec<String> = std::fs::read_dir(&dir)
        .expect("dir")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    left.sort();
    assert_eq!(left, [crate::output::files::MANIFEST, "deformed_von_mises.png", "interfaces.svg", "notes.png"]);
}

/// A scene written from `toml` (its `mesh` key left out), solved on the
/// fixture mesh `msh`, without result files.
fn run_msh(msh: &str, toml: &str) -> Run {
    // a file per call: tests side by side write different scenes
    static CALLS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let n = CALLS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let path = out_dir(msh).join(format!("{msh}_{n}.toml"));
    let toml = format!("mesh = \"{}\"\n{toml}", fixture(msh).display());
    std::fs::write(&path, toml).expect("scene");
    run_on(Scene::load(&path).expect("scene"), msh)
}

/// The lining of `tests/geo/tunnel3d.geo` (R = 5, t = 0.4, a 2 m slice of
/// a 50 m block; the axis along y, z up; lc = 0.8, tet4) in rock with an
/// in-situ stress (sigma_v = 1, K = 0.5), friction 0.4: slip between crown
/// and springline.
fn tunnel3d(full: bool, output: &str) -> Run {
    let toml = format!(
        "title = \"Lining in rock, 3D\"\nanalysis = \"solid\"\n\
         [materials.rock]\nE = 2000.0\nnu = 0.3\n[materials.concrete]\nE = 25000.0\nnu = 0.15\n\
         [[bodies]]\ngroup = \"lining\"\nmaterial = \"concrete\"\n[[bodies]]\ngroup = \"rock\"\nmaterial = \"rock\"\ninitial_stress = [-0.5, -0.45, -1.0, 0.0, 0.0, 0.0]\n\
         [[contacts]]\ngroup = \"interface\"\nfriction = 0.4\n\
         [[supports]]\ngroup = \"ends\"\nfix = [\"y\"]\n[[supports]]\ngroup = \"far_x\"\nfix = [\"x\"]\n[[supports]]\ngroup = \"far_z\"\nfix = [\"z\"]\n{output}"
    );
    run_msh(if full { "picture-tunnel3d-ring" } else { "picture-tunnel3d-quarter" }, &toml)
}

#[test]
fn angle_ticks_name_the_crown_springlines_and_invert() {
    use super::plan::angle_ticks;
    let (zero, side) = ([0.0, 0.0, 1.0], [1.0, 0.0, 0.0]);
    let pi = std::f64::consts::PI;
    // a ring on 1300 px: every 15 degrees, the quarter turns named
    let ring = angle_ticks(-pi, pi, 1300.0, true, zero, side);
    let named: Vec<(f64, String)> = ring.iter().filter_map(|(d, n)| n.clone().map(|n| (*d, n))).collect();
    assert_eq!(
        named,
        [
            (-180.0, "invert".to_string()),
            (-90.0, "springline (−x)".into()),
            (0.0, "crown".into()),
            (90.0, "springline (+x)".into()),
            (180.0, "invert".into())
        ]
    );
    assert_eq!(ring.len(), 25);
    // a quarter on 200 px: every 30 degrees (15 would be 33 px apart)
    let quarter: Vec<f64> = angle_ticks(0.0, pi / 2.0, 200.0, true, zero, side).into_iter().map(|t| t.0).collect();
    assert_eq!(quarter, [0.0, 30.0, 60.0, 90.0]);
    // a shaft (vertical axis): directions, not tunnel words
    let shaft = angle_ticks(0.0, pi, 800.0, false, [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
    let names: Vec<String> = shaft.into_iter().filter_map(|t| t.1).collect();
    assert_eq!(names, ["+x", "+y", "−x"]);
}

/// Issue 19: the 3D lining's plan was a flat projection (a ring drew its
/// front and back on top of each other, nothing named the crown). It is
/// unrolled: the angle from the crown across (crown, springline, invert
/// named), the axis up, each pair once.
#[test]
fn a_3d_lining_is_unrolled_from_the_crown() {
    for full in [false, true] {
        let run = tunnel3d(full, "");
        let c = contact(&run);
        let counts = state_counts(&c.states);
        assert!(c.summary.converged && counts[1] > 0 && counts[2] > 0, "slip and stick: {counts:?}");
        let plans = plan_files(&run.model);
        assert_eq!(plans.len(), 1);
        assert_eq!(plans[0].file, "plan_interface.png");
        let super::sheets::Shape::Cylinder { a, radius, crown, ring, .. } = plans[0].sheet.shape else {
            panic!("unrolled")
        };
        assert!(
            crown && ring == full && a == [0.0, 1.0, 0.0] && (radius - 5.2).abs() < 0.05,
            "axis {a:?}, r = {radius}"
        );
        let flat = plans[0].sheet.flat(&run.model);
        let deg = |x: f64| (x / radius).to_degrees();
        let (lo, hi) = (deg(flat.lo[0]), deg(flat.hi[0]));
        if full {
            assert_eq!((lo.round(), hi.round()), (-180.0, 180.0));
        } else {
            assert!(
                lo.abs() < 0.5 && (hi - 90.0).abs() < 0.5,
                "the quarter from the crown to the springline: {lo} .. {hi}"
            );
        }
        let (cv, boxes) = super::plan::plan_canvas(&run.about.title, &run.model, c, &plans[0]).expect("plan");
        for (state, colour, n) in [("open", OPEN, counts[0]), ("slip", SLIP, counts[1]), ("stick", STICK, counts[2])] {
            assert_eq!(!in_box(&cv, boxes[0], colour).is_empty(), n > 0, "{state} drawn exactly when present");
        }
        keep(
            &format!("tunnel3d_{}_plan.png", if full { "ring" } else { "quarter" }),
            &encode_png(cv.w, cv.h, &cv.rgb).expect("PNG"),
        );
        // interfaces.svg: sigma_n varies round the ring, not along the axis
        let al = super::interfaces::Along::of_sheet(&run.model, &plans[0].sheet, c);
        assert_eq!(al.axis, "angle about the axis from the crown (degrees)");
        keep(
            &format!("tunnel3d_{}_interfaces.png", if full { "ring" } else { "quarter" }),
            &interface_plot_png(&run.model, c).expect("plot"),
        );
    }
}

/// Issue 19: the tunnel's deformed picture was the 50 m block with the
/// lining a small arc in one corner, coloured by the lining's stresses. It
/// frames the structure (the lining, stiffer than the rock), cut to a box
/// with its sections, and gives the lining and the rock a colour scale
/// each; `[output] frame` names another region.
#[test]
fn a_3d_tunnel_is_framed_on_its_lining_with_a_scale_per_body() {
    let run = tunnel3d(true, "");
    let s = snap(&run);
    let focus = super::framing::focus(&run.model, None);
    let cut = focus.cut.expect("framed");
    assert!(
        focus.note.as_deref().is_some_and(|n| n.starts_with("Framed on the structure \"lining\"")),
        "{:?}",
        focus.note
    );
    // the lining's box (r = 5.2) grown by half its size on each side, the slice whole
    assert!(
        (cut.hi[0] - 10.4).abs() < 0.1 && (cut.lo[2] + 10.4).abs() < 0.1 && cut.lo[1] == 0.0 && cut.hi[1] == 2.0,
        "{cut:?}"
    );
    let values: Vec<Vec<f32>> = run
        .last()
        .stresses
        .iter()
        .map(|bs| {
            let mut v = vec![f32::NAN; run.model.n_nodes()];
            for (&k, st) in bs.nodes.iter().zip(&bs.stress) {
                v[k] = crate::fem::material::von_mises(st) as f32;
            }
            v
        })
        .collect();
    let ids: Vec<usize> = (0..values.len()).collect();
    let scales = super::deformed::scales(Field::VonMises, &values, &ids, false);
    assert_eq!(
        scales.iter().map(|s| s.bodies.clone()).collect::<Vec<_>>(),
        vec![vec![0], vec![1]],
        "the lining's scale first, then the rock's"
    );
    assert!(scales[0].lim.hi > 3.0 * scales[1].lim.hi);
    let cv = deformed_canvas(&s, Field::VonMises, None).expect("picture");
    keep("tunnel3d_ring_von_mises.png", &encode_png(cv.w, cv.h, &cv.rgb).expect("PNG"));
    // the lining's colours and the rock's
    let viridis_end = cv.rgb.chunks_exact(3).any(|p| p[2] > 100 && p[0] < 90 && p[1] < 60);
    assert!(viridis_end, "the lining's dark purple shows");
    assert!(count(&cv, SLIP) > 0 && count(&cv, STICK) > 0);

    // the scene names the lining: its box and a quarter of its size round it
    let run = tunnel3d(true, "[output]\nframe = { bodies = [\"lining\"] }\n");
    let focus = super::framing::focus(&run.model, run.about.output.frame.as_ref());
    assert!(
        focus.note.as_deref().is_some_and(|n| n.starts_with("Framed on \"lining\" ([output] frame)")),
        "{:?}",
        focus.note
    );
    let cut = focus.cut.expect("framed");
    assert!((cut.hi[0] - 7.8).abs() < 0.1, "{cut:?}");
    keep("tunnel3d_ring_lining_von_mises.png", &deformed_png(&snap(&run), Field::VonMises, None).expect("picture"));
}

/// The colour bar stops at a quantile when a few nodes stand far out (a
/// singular corner), and bodies get a scale each when their stresses are
/// far apart, one when they are alike; the displacement keeps one.
#[test]
fn colour_scales_leave_out_hot_spots_and_part_bodies_far_apart() {
    let mut v: Vec<f32> = (0..2000).map(|i| i as f32 / 2000.0).collect();
    v.push(100.0);
    let lim = super::legend::Limits::of(false, &[v.clone()]);
    assert!(lim.hi < 1.01 && lim.max == 100.0, "the bar ends at {}, max {}", lim.hi, lim.max);
    let lim = super::legend::Limits::of(false, &[v[..2000].to_vec()]);
    assert!((lim.hi - 0.9995).abs() < 1e-3, "no outlier, no cut: {}", lim.hi);
    let body = |scale: f32| (0..500).map(|i| scale * (1.0 + i as f32 / 500.0)).collect::<Vec<f32>>();
    let groups = |vals: &[Vec<f32>], field| {
        super::deformed::scales(field, vals, &(0..vals.len()).collect::<Vec<_>>(), false)
            .into_iter()
            .map(|s| s.bodies)
            .collect::<Vec<_>>()
    };
    assert_eq!(groups(&[body(1.0), body(20.0), body(3.0)], Field::VonMises), vec![vec![1], vec![0, 2]]);
    assert_eq!(groups(&[body(1.0), body(4.0)], Field::VonMises), vec![vec![0, 1]]);
    assert_eq!(
        groups(&[body(1.0), body(20.0), body(400.0), body(8000.0)], Field::Sxx),
        vec![vec![3], vec![2], vec![0, 1]],
        "at most three"
    );
    assert_eq!(groups(&[body(1.0), body(20.0)], Field::Displacement), vec![vec![0, 1]]);
}

/// One contact group on two planes (a wedge in a V-groove): a plan view per
/// face, the overview of both, a panel per face in interfaces.svg.
#[test]
fn a_contact_on_two_planes_gets_a_plan_per_plane_and_an_overview() {
    // tests/geo/vgroove.geo, lc = 0.25, tet4
    let toml = "title = \"A wedge in a V-groove\"\nanalysis = \"solid\"\n\
                [materials.rock]\nE = 1000.0\nnu = 0.25\n[[bodies]]\ngroup = \"rock\"\nmaterial = \"rock\"\n[[bodies]]\ngroup = \"wedge\"\nmaterial = \"rock\"\n\
                [[contacts]]\ngroup = \"groove\"\nfriction = 0.6\n[[supports]]\ngroup = \"bottom\"\nfix = [\"x\", \"y\", \"z\"]\n[[supports]]\ngroup = \"ends\"\nfix = [\"y\"]\n[[supports]]\ngroup = \"wedge_ends\"\nfix = [\"y\"]\n\
                [[loads]]\ngroup = \"top\"\ntraction = [0.15, 0.0, -1.0]\n";
    let run = run_msh("picture-vgroove", toml);
    let plans = plan_files(&run.model);
    let files: Vec<&str> = plans.iter().map(|p| p.file.as_str()).collect();
    assert_eq!(files, ["plan_groove_1.png", "plan_groove_2.png"]);
    for p in &plans {
        assert!(p.describe(&run.model).contains("dip 45°"), "{}", p.describe(&run.model));
    }
    let pics: Vec<(String, Vec<u8>)> = drawn(&snap(&run));
    let names: Vec<&str> = pics.iter().map(|p| p.0.as_str()).collect();
    assert_eq!(
        names,
        ["deformed_von_mises.png", "interfaces.svg", "plan_groove_1.png", "plan_groove_2.png", "joints.png"]
    );
    for (f, bytes) in &pics {
        keep(&format!("vgroove_{f}"), bytes);
    }
    let svg = String::from_utf8(pics[1].1.clone()).expect("svg");
    assert!(
        svg.contains("groove 1 of 2, dip 45°/090°") && svg.contains("groove 2 of 2, dip 45°/270°"),
        "one panel per face"
    );
    keep("vgroove_interfaces.png", &interface_plot_png(&run.model, contact(&run)).expect("plot"));
    let report = crate::output::report::report(&run, &crate::output::Derived::of(&run));
    assert!(report.contains("![every contact surface by state](joints.png)") && report.contains("(plan_groove_2.png)"));
}

/// Issue 19: a wall's base plotted against the direction along the wall
/// (the pairs' longest spread) made columns of dots. The block on block of
/// geo/blocks3d.toml stretched to 6 along y and pushed along x: the
/// stresses vary along x, and the plot is against x.
#[test]
fn a_wall_is_plotted_across_its_length() {
    // hex8: b = 6, hex = 1, lc = 0.25
    let run = run_on(Scene::load(Path::new("geo/blocks3d.toml")).expect("scene"), "picture-blocks3d-wall");
    let plans = plan_files(&run.model);
    assert_eq!(plans.len(), 1);
    let al = super::interfaces::Along::of_sheet(&run.model, &plans[0].sheet, contact(&run));
    assert_eq!(al.axis, "x");
    assert!(al.left < 0.05, "x explains the stresses: {} left", al.left);
    keep("wall_interfaces.png", &interface_plot_png(&run.model, contact(&run)).expect("plot"));
}

/// A joint set as the lead's contact groups will hold it (issue 17): one
/// interface whose facets lie on five horizontal planes and two vertical
/// ones crossing them, pairs on every facet node, states set by position
/// (open where x < 1, slip where 1 <= x < 2, else stick). One plan per
/// plane, each showing exactly its states; joints.png with all seven;
/// interfaces.svg with a panel per plane. Built from the model's facets and
/// pairs alone.
#[test]
fn a_joint_set_of_many_planes_gets_a_plan_per_plane_and_one_overview() {
    use super::sheets::tests::{grid, model_of};
    let (mut coords, mut quads) = (Vec::new(), Vec::new());
    for z in 0..5 {
        grid(&mut coords, &mut quads, [6, 3], |s, t| [3.0 * s, 2.0 * t, z as f64]);
    }
    for x in [0.5, 2.5] {
        grid(&mut coords, &mut quads, [3, 8], |s, t| [x, 2.0 * s, 4.0 * t]);
    }
    let mut model = model_of(coords, quads);
    let n = model.n_nodes();
    model.pairs = (0..n)
        .map(|k| crate::model::Pair {
            k,
            l: k,
            contact: 0,
            normal: if k < 5 * 28 { [0.0, 0.0, 1.0] } else { [1.0, 0.0, 0.0] },
            area: 0.1,
            shares: Vec::new(),
        })
        .collect();
    let states: Vec<ContactState> = (0..n)
        .map(|k| match model.coords[k][0] {
            x if x < 1.0 => ContactState::Open,
            x if x < 2.0 => ContactState::Slip,
            _ => ContactState::Stick,
        })
        .collect();
    let c = crate::results::ContactRun {
        pairs: model.coords.iter().map(|x| joint_set_pair(*x)).collect(),
        frames: vec![[[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]; n],
        areas: vec![0.1; n],
        states,
        water: None,
        summary: crate::contact::Summary { iterations: 1, converged: true, ..Default::default() },
        law_residual: Vec::new(),
        cracked: Vec::new(),
        locked_off: Vec::new(),
    };
    let plans = plan_files(&model);
    let files: Vec<&str> = plans.iter().map(|p| p.file.as_str()).collect();
    assert_eq!(files, (1..=7).map(|k| format!("plan_joints_{k}.png")).collect::<Vec<_>>());
    let described: Vec<String> = plans.iter().map(|p| p.describe(&model)).collect();
    assert_eq!(
        described[..5],
        ["the plane z = 0", "the plane z = 1", "the plane z = 2", "the plane z = 3", "the plane z = 4"]
    );
    assert_eq!(described[5..], ["the plane x = 0.5", "the plane x = 2.5"]);
    for (i, p) in plans.iter().enumerate() {
        let (cv, boxes) = super::plan::plan_canvas("a joint set", &model, &c, p).expect("plan");
        let (open, slip, stick) =
            (in_box(&cv, boxes[0], OPEN).len(), in_box(&cv, boxes[0], SLIP).len(), in_box(&cv, boxes[0], STICK).len());
        match i {
            // a horizontal plane has all three, in x order
            0..=4 => assert!(open > 0 && slip > 0 && stick > 0, "plane {i}: {open} {slip} {stick}"),
            // x = 0.5 opens, x = 2.5 sticks
            5 => assert!(open > 0 && slip + stick == 0, "x = 0.5: {open} {slip} {stick}"),
            _ => assert!(stick > 0 && open + slip == 0, "x = 2.5: {open} {slip} {stick}"),
        }
        if i == 0 || i == 6 {
            keep(&format!("jointset_{}", p.file), &encode_png(cv.w, cv.h, &cv.rgb).expect("PNG"));
        }
    }
    assert_eq!(joints_file(&plans), Some("joints.png"));
    let png = joints_png("a joint set", &model, &c, &plans).expect("overview");
    let (w, h, rgb) = decode(&png);
    let has = |c: [u8; 3]| rgb.chunks_exact(3).any(|p| p == c);
    assert!(w <= 1600 && h <= 2500 && has(OPEN) && has(SLIP) && has(STICK));
    keep("jointset_joints.png", &png);
    let svg = interface_plot_svg(&model, &c).expect("plot");
    assert!(svg.contains("joints 1 of 7, z = 0") && svg.contains("joints 7 of 7, x = 2.5"));
    keep("jointset_interfaces.png", &interface_plot_png(&model, &c).expect("plot"));
}

/// The stresses of the joint-set test's pair at `x`: the pressure grows
/// with depth, the shear along x.
fn joint_set_pair(x: [f64; 3]) -> crate::contact::law::PairResult {
    crate::contact::law::PairResult { sigma_n: -1.0 - x[2], tau_t: 0.1 * x[0], tau_b: 0.0, gap: 0.0, slip: 0.0 }
}

/// Issue 21: the pictures' errors are typed, and a caller tells them apart
/// by variant: results that are not the model's (a caller's bug), and a
/// model with nothing to plot.
#[test]
fn picture_errors_are_told_apart_by_variant() {
    let run = cylinder(0.5, 1);
    let c = contact(&run);
    let u = &run.last().u[1..];
    let wrong = Snapshot { u, ..snap(&run) };
    assert!(matches!(
        deformed_png(&wrong, Field::VonMises, None),
        Err(PictureError::Mismatch { what: "displacements or stresses" })
    ));
    let mut fewer = c.clone();
    fewer.states.pop();
    assert!(matches!(
        joints_png("t", &run.model, &fewer, &[]),
        Err(PictureError::Mismatch { what: "contact results" })
    ));
    let mut bare = run.model.clone();
    bare.interfaces.clear();
    match interface_plot_svg(&bare, c) {
        Err(PictureError::Empty(why)) => assert!(why.contains("no contact interface"), "{why}"),
        other => panic!("nothing to plot, not {:?}", other.map(|s| s.len())),
    }
}

/// Every picture of a snapshot; none may be skipped.
fn drawn(snap: &Snapshot) -> Vec<(String, Vec<u8>)> {
    let d = pictures(snap);
    assert!(d.skipped.is_empty(), "{:?}", d.skipped);
    d.files
}

/// The 3D tunnel through three joint sets panicked here with exit 101
/// and no result written (issue 32: index 258 into a 256-colour table,
/// the bar's top pixel being fractional).
#[test]
fn a_colour_bar_at_fractional_pixels_stays_in_its_table() {
    let lut = super::legend::colour_map(false, 0.0, 1.0);
    let lim = super::legend::Limits { lo: 0.0, hi: 1.0, min: -1.0, max: 2.0 };
    let mut cv = Canvas::new(400, 400);
    for top in [100.0, 100.25, 100.5, 100.999] {
        let mut labels = Vec::new();
        super::legend::colour_bar(&mut cv, &mut labels, &lut, &lim, &["σ".into()], [20.0, top, top + 200.3]);
    }
    assert_eq!(super::legend::lut_colour(&lut, 1.02), lut[255]);
    assert_eq!(super::legend::lut_colour(&lut, -3.0), lut[0]);
    assert_eq!(super::legend::lut_colour(&[], 0.5), [150, 150, 150]);
}

#[test]
fn a_picture_that_fails_is_skipped_with_a_warning_and_the_others_drawn() {
    let mut d = Drawn::default();
    d.draw("a.png", || Ok(b"a".to_vec()));
    d.draw("b.png", || {
        let v: Vec<u8> = Vec::new();
        Ok(vec![v[3]])
    });
    d.draw("c.png", || Err(PictureError::Empty("nothing to draw".into())));
    d.draw("d.png", || Ok(b"d".to_vec()));
    let names: Vec<&str> = d.files.iter().map(|(f, _)| f.as_str()).collect();
    assert_eq!(names, ["a.png", "d.png"]);
    assert_eq!(d.skipped.len(), 2);
    assert!(
        d.skipped[0].starts_with("b.png was not drawn") && d.skipped[0].contains("index out of bounds"),
        "{:?}",
        d.skipped
    );
    assert!(d.skipped[0].contains("tests.rs"), "where it failed: {:?}", d.skipped);
    assert!(d.skipped[1].contains("nothing to draw"), "{:?}", d.skipped);
}

/// A 1 GB title was still being drawn into the PNG after 12 minutes.
#[test]
fn a_huge_title_is_cut_where_it_is_drawn() {
    let l = super::raster::label(
        "é".repeat(1_000_000),
        (0.0, 0.0),
        24.0,
        (plotters::style::text_anchor::HPos::Left, plotters::style::text_anchor::VPos::Top),
    );
    assert_eq!(l.text.chars().count(), super::raster::MAX_LABEL + 1);
    assert!(l.text.ends_with('…'));
    let short = super::raster::label(
        "dam",
        (0.0, 0.0),
        24.0,
        (plotters::style::text_anchor::HPos::Left, plotters::style::text_anchor::VPos::Top),
    );
    assert_eq!(short.text, "dam");
}

/// Two threads drawing at once each get their own panic's message, and
/// drawing that does not panic gives its answer after them.
#[test]
fn pictures_drawn_in_two_threads_each_keep_their_own_panic() {
    let said = |name: &'static str| {
        move || {
            (0..40).all(|_| {
                let drawn = super::quietly(|| -> u8 {
                    // (long enough for the other thread's drawing to overlap)
                    std::thread::sleep(std::time::Duration::from_millis(1));
                    panic!("drawing {name} failed")
                });
                drawn.is_err_and(|p| p.to_string().contains(&format!("drawing {name} failed")))
            })
        }
    };
    let (a, b) = std::thread::scope(|s| {
        let a = s.spawn(said("a"));
        let b = s.spawn(said("b"));
        (a.join().unwrap(), b.join().unwrap())
    });
    assert!(a && b, "a thread read another's panic, or none");
    assert_eq!(super::quietly(|| 7).ok(), Some(7));
}
