//! 7. A body held only by contact: stuck, it gives the bonded answer;
//!    pulled off, the binary stops with a message naming the body (no panic,
//!    no result files), also at map coordinates and in Pa.

use std::time::Instant;

use subcontact::contact::law::ContactState;

use crate::common::measure::{count, diff_to_bonded};
use crate::stack::{map_stack, traction_line};
use crate::table::Suite;
use crate::{converged, solve, states_note};

pub fn held_by_contact_case(s: &mut Suite) {
    // stuck: the top block has no support; the joint holds it in shear and bending
    for kind in ["quad4", "quad9", "tri6"] {
        let mut st = map_stack(kind, 8, 4);
        st.load = traction_line([0.3, 0.2], 0.0, 1.0);
        st.contact = "friction = 0.6\ncohesion = 5.0\ntensile_strength = 5.0".into();
        let t = Instant::now();
        let text = st.text();
        let run = solve(&s.case, &format!("held_{kind}"), &text, false);
        let bonded = solve(&s.case, &format!("held_{kind}"), &text, true);
        let secs = t.elapsed().as_secs_f64();
        let c = converged(&run);
        let all_stick = count(c, ContactState::Stick) == c.states.len();
        let d = diff_to_bonded(&run, &bonded);
        let tension = c.pairs.iter().any(|r| r.sigma_n > 0.0);
        s.check(
            &format!("held by contact {kind}"),
            "top block without supports, joint in tension and shear, stuck: u = bonded solve",
            if all_stick && tension { d } else { f64::INFINITY },
            1e-10,
            Some(run.stats.residuals.interface),
            "no support on the top body",
            secs,
            &states_note(c),
        );
    }
    // pulled off: the binary names the free body
    for (what, x0, y0, angle, scale) in [
        ("MPa", 0.0, 0.0, 0.0, 1.0),
        ("map coordinates, 30 deg", 5.0e5, 4.2e6, 30.0, 1.0),
        ("Pa", 0.0, 0.0, 0.0, 1.0e6),
    ] {
        for kind in ["quad4", "quad9"] {
            let mut st = map_stack(kind, 4, 2);
            st.x0 = x0;
            st.y0 = y0;
            st.angle = angle;
            st.e *= scale;
            st.contact = format!("friction = 0.6\ncohesion = {:e}\ntensile_strength = {:e}", 2.0 * scale, 0.1 * scale);
            st.load = traction_line([0.0, 0.5], angle, scale);
            let name = format!("pulled_{kind}_{}", what.replace([' ', ','], ""));
            s.case.write(&format!("{name}.toml"), &st.text());
            let t = Instant::now();
            let out = s.case.cli(&["solve", &format!("{name}.toml"), "--quiet"]);
            let secs = t.elapsed().as_secs_f64();
            let stderr = String::from_utf8_lossy(&out.stderr).to_string();
            let no_files = !s.case.out(&name).join("summary.json").exists()
                && !s.case.out(&name).join(format!("{name}.vtu")).exists();
            let ok = !out.status.success()
                && stderr.contains("body \"top\"")
                && !stderr.contains("\"bottom\"")
                && stderr.contains(&format!("{name}.toml"))
                && !stderr.contains("panicked")
                && !stderr.contains("NaN")
                && no_files;
            let first = stderr.trim().chars().take(160).collect::<String>();
            s.boolean(
                &format!("pulled off {kind} ({what})"),
                "binary: non-zero exit, message names body \"top\" and the scene, no panic, no result files",
                ok,
                None,
                &format!("pull 0.5 > f_t = 0.1 (x{scale:e})"),
                secs,
                &format!("exit {:?}: {first}...", out.status.code()),
            );
        }
    }
}
