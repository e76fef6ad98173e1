//! 5. Units: the same model in MPa and in Pa (E, loads, cohesion and
//!    tensile strength scaled by 1e6) gives equal displacements and stresses
//!    scaled by 1e6, on the bent stack and on the compound cylinder's curved
//!    joint.

use std::time::Instant;

use crate::contrast::{compound_scene, Ring, STUCK_JOINT};
use crate::map::compare_moved;
use crate::stack::{map_stack, traction_line, MAP_TRACTION};
use crate::table::Suite;
use crate::{converged, solve, states_note};

pub fn units_case(s: &mut Suite, kind: &str, nx: usize, ny: usize) {
    let t = Instant::now();
    let mut mpa = map_stack(kind, nx, ny);
    mpa.load = traction_line(MAP_TRACTION, 0.0, 1.0);
    let mut pa = mpa.clone();
    pa.e *= 1e6;
    pa.contact = "friction = 0.6\ncohesion = 2.0e6\ntensile_strength = 0.0".into();
    pa.load = traction_line(MAP_TRACTION, 0.0, 1e6);
    let a = solve(&s.case, &format!("units_{kind}_{nx}x{ny}_mpa"), &mpa.text(), false);
    let b = solve(&s.case, &format!("units_{kind}_{nx}x{ny}_pa"), &pa.text(), false);
    let secs = t.elapsed().as_secs_f64();
    let (du, ds, dc, same) = compare_moved(&a, &b, 0.0, 0.0, 0.0, 1e6);
    s.check(
        &format!("units {kind} {nx}x{ny}"),
        "MPa vs Pa: u equal, sigma and contact stresses / 1e6 equal, same states",
        if same { du.max(ds).max(dc) } else { f64::INFINITY },
        1e-10,
        Some(a.stats.residuals.interface.max(b.stats.residuals.interface)),
        "E = 2e4 MPa / 2e10 Pa",
        secs,
        &format!(
            "u {du:.1e}, sigma {ds:.1e}, contact {dc:.1e}; {}; residual Pa {:.1e}",
            states_note(converged(&b)),
            b.stats.residuals.interface
        ),
    );
}

/// Units on the compound cylinder (curved joint, contrast 1e3).
pub fn units_compound_case(s: &mut Suite) {
    let t = Instant::now();
    let m = Ring { kind: "quad9", order: 2, quad: true, serendipity: false, lc: 0.25 };
    let ta = compound_scene(m, 2.0e4, 2.0e7, STUCK_JOINT, false);
    let tb = compound_scene(m, 2.0e10, 2.0e13, "friction = 0.8\ncohesion = 1.0e12\ntensile_strength = 1.0e12", false)
        .replace("pressure = 1.0", "pressure = 1.0e6");
    let a = solve(&s.case, "units_compound_mpa", &ta, false);
    let b = solve(&s.case, "units_compound_pa", &tb, false);
    let secs = t.elapsed().as_secs_f64();
    let (du, ds, dc, same) = compare_moved(&a, &b, 0.0, 0.0, 0.0, 1e6);
    s.check(
        "units compound quad9",
        "MPa vs Pa on the curved joint (E2/E1 = 1e3): u equal, stresses / 1e6 equal",
        if same { du.max(ds).max(dc) } else { f64::INFINITY },
        1e-10,
        Some(a.stats.residuals.interface.max(b.stats.residuals.interface)),
        "E2 = 2e7 MPa / 2e13 Pa",
        secs,
        &format!("u {du:.1e}, sigma {ds:.1e}, contact {dc:.1e}"),
    );
}
