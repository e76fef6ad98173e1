//! The two stacked blocks of tests/geo/stress_stack.geo that the aspect
//! ratio, map coordinates, units, strengths and held-by-contact cases load:
//! [`Stack`] (its mesh parameters, material, joint, supports and load, and
//! the scene text), the exact answer under uniform compression
//! ([`uniform_errors`]), and the bent 20 x 10 stack of the map and units
//! cases ([`map_stack`]).

use subcontact::driver::Run;

use crate::common::measure::{body_nodes, max_abs};
use crate::common::scenes::two_blocks;
use crate::converged;

/// A scene on tests/geo/stress_stack.geo.
#[derive(Clone)]
pub struct Stack {
    pub order: usize,
    pub quad: bool,
    pub serendipity: bool,
    pub w: f64,
    pub h: f64,
    pub nx: usize,
    pub ny: usize,
    pub x0: f64,
    pub y0: f64,
    pub angle: f64,
    pub e: f64,
    pub nu: f64,
    pub contact: String,
    pub supports: String,
    pub load: String,
}

impl Stack {
    pub fn kind(kind: &str) -> Stack {
        let (order, quad, serendipity) = match kind {
            "quad4" => (1, true, false),
            "tri3" => (1, false, false),
            "quad9" => (2, true, false),
            "quad8" => (2, true, true),
            "tri6" => (2, false, false),
            _ => panic!("kind {kind}"),
        };
        Stack {
            order,
            quad,
            serendipity,
            w: 2.0,
            h: 1.0,
            nx: 4,
            ny: 4,
            x0: 0.0,
            y0: 0.0,
            angle: 0.0,
            e: 1000.0,
            nu: 0.25,
            contact: "friction = 0.5\ncohesion = 0.0\ntensile_strength = 0.0".into(),
            supports:
                "[[supports]]\ngroup = \"base\"\nfix = [\"y\"]\n\n[[supports]]\ngroup = \"corner\"\nfix = [\"x\"]\n"
                    .into(),
            load: "pressure = 1.0".into(),
        }
    }
    /// `gmsh -setnumber` values of the scene.
    pub fn setnumber(&self) -> Vec<(&'static str, f64)> {
        vec![
            ("w", self.w),
            ("h", self.h),
            ("nx", self.nx as f64),
            ("ny", self.ny as f64),
            ("quad", self.quad as i32 as f64),
            ("serendipity", self.serendipity as i32 as f64),
            ("x0", self.x0),
            ("y0", self.y0),
            ("angle", self.angle),
        ]
    }
    /// The scene, meshed from stress_stack.geo.
    pub fn text(&self) -> String {
        let set: Vec<String> = self.setnumber().iter().map(|(k, v)| format!("{k} = {v:?}")).collect();
        self.text_on(&format!(
            "mesh = \"stress_stack.geo\"\n\n[gmsh]\norder = {}\nsetnumber = {{ {} }}",
            self.order,
            set.join(", ")
        ))
    }
    /// The scene on a ready mesh (a .msh of the case).
    pub fn text_msh(&self, msh: &str) -> String {
        self.text_on(&format!("mesh = \"{msh}\""))
    }
    pub fn text_on(&self, mesh: &str) -> String {
        let head = format!("title = \"two stacked blocks\"\nanalysis = \"plane_stress\"\n{mesh}");
        let rest = format!("{}\n\n[[loads]]\ngroup = \"top_face\"\n{}\n", self.supports, self.load);
        two_blocks(&head, self.e, self.nu, &self.contact, &rest)
    }
}

/// Error of a stack under uniform compression p (plane stress, base held
/// in y, the corner in x, the origin at the corner, no rotation) against
/// u = (nu p x / E, -p y / E), sigma_yy = -p: (u / max u, nodal sigma / p,
/// contact / p).
pub fn uniform_errors(run: &Run, st: &Stack, p: f64) -> (f64, f64, f64) {
    let ex = |x: [f64; 3]| [st.nu * p * x[0] / st.e, -p * x[1] / st.e];
    let umax = max_abs([ex([st.w, 2.0 * st.h, 0.0])[0], ex([st.w, 2.0 * st.h, 0.0])[1]]);
    let mut eu = 0.0f64;
    for (_, n) in body_nodes(run) {
        let e = ex(run.model.coords[n]);
        eu = eu.max((run.last().u[2 * n] - e[0]).abs()).max((run.last().u[2 * n + 1] - e[1]).abs());
    }
    let mut es = 0.0f64;
    for bs in &run.last().stresses {
        for s in &bs.stress {
            let want = [0.0, -p, 0.0, 0.0, 0.0, 0.0];
            for c in 0..6 {
                es = es.max((s[c] - want[c]).abs());
            }
        }
    }
    let c = converged(run);
    let ec = max_abs(c.pairs.iter().flat_map(|r| [r.sigma_n + p, r.tau()]));
    (eu / umax, es / p, ec / p)
}

/// Blocks 10 x 1 (flat: elements stretched along the joint, dx/dy = AR)
/// clamped, an inclined traction on the top face that bends the joint so
/// that part of it opens (f_t = 0) while the rest sticks.
pub fn map_stack(kind: &str, nx: usize, ny: usize) -> Stack {
    let mut st = Stack::kind(kind);
    st.w = 20.0;
    st.h = 10.0;
    st.nx = nx;
    st.ny = ny;
    st.e = 2.0e4;
    st.nu = 0.2;
    st.contact = "friction = 0.6\ncohesion = 2.0\ntensile_strength = 0.0".into();
    st.supports = "[[supports]]\ngroup = \"base\"\nfix = [\"x\", \"y\"]\n".into();
    st
}

/// The inclined traction on the top face of the map, units and strengths cases.
pub const MAP_TRACTION: [f64; 2] = [0.3, -0.5];

/// The `traction = [..]` line of the top face: `t` turned by `angle_deg`, times `scale`.
pub fn traction_line(t: [f64; 2], angle_deg: f64, scale: f64) -> String {
    let th = angle_deg.to_radians();
    let (c, s) = if angle_deg == 0.0 { (1.0, 0.0) } else { (th.cos(), th.sin()) };
    format!("traction = [{:e}, {:e}]", scale * (c * t[0] - s * t[1]), scale * (s * t[0] + c * t[1]))
}
