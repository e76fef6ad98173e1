//! The pictures of real runs, end to end: scenes written as a user would,
//! meshed by the gmsh CLI, solved by the library's driver, and the picture
//! files read back from the result directory. Two blocks stacked on a
//! frictional joint and pushed sideways, in every 2D element kind, hex20
//! and tet4 (tests/geo/contact_stack*.geo): each run writes the deformed
//! picture, interfaces.svg with the state counts of the run, a plan view of
//! the joint in 3D, and report.md embedding them all. The pixels of these
//! pictures are checked by the unit tests of src/output/picture/ on
//! committed meshes.

mod common;

use std::path::Path;

use common::{read, Case};
use subcontact::results::state_counts;

/// A joint without cohesion or tensile strength: the push tips the top
/// block, so the joint opens at one end and sticks where it is pressed.
const WEAK: &str = "friction = 0.8\ncohesion = 0.0\ntensile_strength = 0.0";
/// A joint too strong to give (tet4: pushed, the unstructured tetrahedra
/// make the contact iteration cycle).
const STRONG: &str = "friction = 0.5\ncohesion = 100.0\ntensile_strength = 100.0";

/// One stacked-blocks scene: its name, element order, gmsh parameters,
/// whether it is 3D, its supports, the traction on the top face and the
/// joint's strength.
struct Stack {
    name: &'static str,
    order: usize,
    set: &'static str,
    solid: bool,
    supports: &'static str,
    traction: &'static str,
    joint: &'static str,
}

const PLANE_SUPPORTS: &str =
    "[[supports]]\ngroup = \"base\"\nfix = [\"y\"]\n[[supports]]\ngroup = \"corner\"\nfix = [\"x\"]\n";
const SOLID_SUPPORTS: &str =
    "[[supports]]\ngroup = \"base\"\nfix = [\"x\", \"y\", \"z\"]\n[[supports]]\ngroup = \"z_faces\"\nfix = [\"z\"]\n";

fn plane(name: &'static str, order: usize, set: &'static str) -> Stack {
    Stack { name, order, set, solid: false, supports: PLANE_SUPPORTS, traction: "[0.5, -1.0]", joint: WEAK }
}

fn cases() -> Vec<Stack> {
    vec![
        plane("tri6", 2, "n = 8, quad = 0"),
        plane("tri3", 1, "n = 10, quad = 0"),
        plane("quad4", 1, "n = 10, quad = 1"),
        plane("quad8", 2, "n = 6, quad = 1, serendipity = 1"),
        Stack {
            name: "hex20",
            order: 2,
            set: "n = 4, nz = 2, hex = 1, serendipity = 1",
            solid: true,
            supports: SOLID_SUPPORTS,
            traction: "[0.5, -1.0, 0.0]",
            joint: WEAK,
        },
        Stack {
            name: "tet4",
            order: 1,
            set: "n = 6, hex = 0",
            solid: true,
            supports: "[[supports]]\ngroup = \"base\"\nfix = [\"x\", \"y\", \"z\"]\n",
            traction: "[0.3, -1.0, 0.2]",
            joint: STRONG,
        },
    ]
}

/// The scene file of `s` in `case`, next to its .geo.
fn write_scene(case: &Case, s: &Stack) -> std::path::PathBuf {
    let (geo, analysis) =
        if s.solid { ("contact_stack3d.geo", "solid") } else { ("contact_stack.geo", "plane_stress") };
    let toml = format!(
        "title = \"Two blocks, the top one pushed sideways ({name})\"\nmesh = \"{geo}\"\nanalysis = \"{analysis}\"\n\
         [gmsh]\norder = {order}\nsetnumber = {{ {set} }}\n[materials.m]\nE = 1000.0\nnu = 0.25\n\
         [[bodies]]\ngroup = \"bottom\"\nmaterial = \"m\"\n[[bodies]]\ngroup = \"top\"\nmaterial = \"m\"\n\
         [[contacts]]\ngroup = \"joint\"\n{joint}\n{supports}[[loads]]\ngroup = \"top_face\"\ntraction = {traction}\n",
        name = s.name,
        order = s.order,
        set = s.set,
        joint = s.joint,
        supports = s.supports,
        traction = s.traction,
    );
    case.write(&format!("stack_{}.toml", s.name), &toml)
}

/// A PNG's width and height, decoded.
fn png_size(path: &Path) -> (u32, u32) {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut reader = png::Decoder::new(bytes.as_slice()).read_info().expect("a PNG header");
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).expect("the PNG's pixels");
    (info.width, info.height)
}

#[test]
fn stacked_blocks_pushed_sideways_write_pictures_of_the_states_they_reach() {
    let case = Case::new("pictures-stack");
    case.copy("tests/geo/contact_stack.geo");
    case.copy("tests/geo/contact_stack3d.geo");
    for s in cases() {
        let run = case.run(&write_scene(&case, &s)).unwrap_or_else(|e| panic!("{}: {e:#}", s.name));
        let c = run.contact().expect("contact");
        let counts = state_counts(&c.states);
        eprintln!(
            "{}: {} stick, {} slip, {} open after {} iterations",
            s.name, counts[2], counts[1], counts[0], c.summary.iterations
        );
        assert!(c.summary.converged, "{}", s.name);
        if s.joint == WEAK {
            assert!(counts[0] > 0 && counts[2] > 0, "{}: opens at one end, sticks at the other: {counts:?}", s.name);
        }
        let out = case.out(&format!("stack_{}", s.name));
        let (w, h) = png_size(&out.join("deformed_von_mises.png"));
        assert!(w >= 800 && h >= 600, "{}: deformed picture {w} x {h}", s.name);
        let svg = read(&out.join("interfaces.svg"));
        let said = format!("{} stick, {} slip, {} open", counts[2], counts[1], counts[0]);
        assert!(svg.contains(&said), "{}: interfaces.svg says {said}", s.name);
        let report = read(&out.join("report.md"));
        assert!(report.contains("(deformed_von_mises.png)") && report.contains("(interfaces.svg)"), "{}", s.name);
        let plan = out.join("plan_joint.png");
        assert_eq!(plan.exists(), s.solid, "{}: a plan view in 3D only", s.name);
        if s.solid {
            let (w, h) = png_size(&plan);
            assert!(w >= 800 && h >= 300, "{}: plan view {w} x {h}", s.name);
            assert!(report.contains("(plan_joint.png)"), "{}", s.name);
        }
    }
}

/// About 1e5 nodes (the shipped cylinder, quad9, meshed by gmsh at lc =
/// 0.022): prints the time to draw the deformed picture and the interface
/// plot; run with `cargo test --release --test pictures -- --ignored
/// --nocapture`.
#[test]
#[ignore = "a timing, not a check: about 1e5 nodes"]
fn render_time_of_a_fine_mesh() {
    use subcontact::driver::{self, RunOptions};
    use subcontact::output::picture::{deformed_png, interface_plot_svg, Field, Snapshot};
    let case = Case::new("pictures-fine");
    let mut scene = subcontact::scene::Scene::load(Path::new("geo/cylinder.toml")).expect("scene");
    scene.gmsh.setnumber = vec![("lc".into(), 0.022)];
    let opts = RunOptions { out: Some(case.out("cylinder_fine")), skip_output: true, ..Default::default() };
    let run = driver::run_scene(scene, &opts).expect("cylinder run");
    eprintln!("{} nodes, {} cells", run.model.n_nodes(), run.model.bodies.iter().map(|b| b.cells.len()).sum::<usize>());
    let (last, contact) = (run.last(), run.contact().expect("a run with contact"));
    let snap = Snapshot {
        title: &run.about.title,
        model: &run.model,
        u: &last.u,
        stresses: &last.stresses,
        contact: Some(contact),
        region: None,
        one_scale: false,
    };
    for _ in 0..2 {
        let t = std::time::Instant::now();
        let png = deformed_png(&snap, Field::VonMises, None).expect("deformed picture");
        let deformed = t.elapsed().as_secs_f64();
        let t = std::time::Instant::now();
        let svg = interface_plot_svg(&run.model, contact).expect("interface plot");
        eprintln!(
            "deformed (PNG): {deformed:.3} s ({} kB); interfaces: {:.3} s",
            png.len() / 1024,
            t.elapsed().as_secs_f64()
        );
        assert!(png.starts_with(b"\x89PNG") && svg.starts_with("<svg"));
    }
}
