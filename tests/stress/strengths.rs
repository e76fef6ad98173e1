//! 6. Contact strengths at their limits: friction 0 and cohesion 0 in
//!    compression (stick or slip, with zero shear either way; also on the
//!    curved joint), very high cohesion (stays stuck: the bonded answer), and
//!    f_t = 0 under bending (the pairs in tension open, the rest carry the
//!    load: complementarity and equilibrium of the contact forces).

use std::time::Instant;

use subcontact::contact::law::ContactState;

use crate::common::measure::{count, diff_to_bonded, force_on_body_i, max_abs};
use crate::contrast::{compound_scene, Ring, E_SOFT, STUCK_JOINT};
use crate::map::compare_moved;
use crate::stack::{map_stack, traction_line, uniform_errors, Stack, MAP_TRACTION};
use crate::table::Suite;
use crate::{converged, fmt_e, solve, states_note};

pub fn strengths_case(s: &mut Suite) {
    // friction 0, cohesion 0, uniform compression, both blocks held in x on
    // the left: the pairs carry no shear, whether they stick or slip
    for slip in ["coulomb", "frictionless"] {
        for kind in ["quad4", "quad9"] {
            let mut st = Stack::kind(kind);
            st.contact = format!("friction = 0.0\ncohesion = 0.0\ntensile_strength = 0.0\nslip = \"{slip}\"");
            st.supports =
                "[[supports]]\ngroup = \"base\"\nfix = [\"y\"]\n\n[[supports]]\ngroup = \"left\"\nfix = [\"x\"]\n"
                    .into();
            let t = Instant::now();
            let run = solve(&s.case, &format!("f0c0_{kind}_{slip}"), &st.text(), false);
            let secs = t.elapsed().as_secs_f64();
            let c = converged(&run);
            let uniform =
                count(c, ContactState::Stick) == c.states.len() || count(c, ContactState::Slip) == c.states.len();
            let (eu, es, ec) = uniform_errors(&run, &st, 1.0);
            s.check(
                &format!("f = 0, c = 0 {kind} {slip}"),
                "compression, no shear: all stick or all slip; u, sigma, sigma_n = -p, tau = 0 exact",
                if uniform { eu.max(es).max(ec) } else { f64::INFINITY },
                1e-9,
                Some(run.stats.residuals.interface),
                "f = c = f_t = 0",
                secs,
                &states_note(c),
            );
        }
    }
    // very high cohesion and tensile strength: everything sticks, the bonded answer
    for (kind, coh) in [("quad9", 1.0e30), ("tri3", 1.0e30), ("quad9", 1.0e300)] {
        let mut st = map_stack(kind, 8, 4);
        st.load = traction_line(MAP_TRACTION, 0.0, 1.0);
        st.contact = format!("friction = 0.0\ncohesion = {coh:e}\ntensile_strength = {coh:e}");
        let t = Instant::now();
        let text = st.text();
        let run = solve(&s.case, &format!("cohesive_{kind}_{coh:e}"), &text, false);
        let bonded = solve(&s.case, &format!("cohesive_{kind}_{coh:e}"), &text, true);
        let secs = t.elapsed().as_secs_f64();
        let c = converged(&run);
        let all_stick = count(c, ContactState::Stick) == c.states.len();
        let d = diff_to_bonded(&run, &bonded);
        s.check(
            &format!("high cohesion {kind}"),
            "c = f_t huge under bending and shear: every pair sticks; u = bonded solve",
            if all_stick { d } else { f64::INFINITY },
            1e-10,
            Some(run.stats.residuals.interface),
            &format!("c = f_t = {coh:.0e}"),
            secs,
            &states_note(c),
        );
    }

    // f_t = 0 under bending: the pairs in tension open, the rest carry the load
    for kind in ["quad4", "quad9", "tri6"] {
        let mut st = map_stack(kind, 8, 4);
        st.load = traction_line(MAP_TRACTION, 0.0, 1.0);
        st.contact = "friction = 0.6\ncohesion = 10.0\ntensile_strength = 0.0".into();
        let t = Instant::now();
        let run = solve(&s.case, &format!("ft0_{kind}"), &st.text(), false);
        let secs = t.elapsed().as_secs_f64();
        let c = converged(&run);
        let open = count(c, ContactState::Open);
        let closed = c.states.len() - open;
        // complementarity: open pairs carry nothing and do not overlap; closed ones are in compression
        let smax = max_abs(c.pairs.iter().map(|r| r.sigma_n));
        let gmax = max_abs(c.pairs.iter().map(|r| r.gap));
        let mut viol = 0.0f64;
        for (st_, r) in c.states.iter().zip(&c.pairs) {
            match st_ {
                ContactState::Open => {
                    viol = viol.max(r.sigma_n.abs() / smax).max(r.tau() / smax).max((-r.gap).max(0.0) / gmax)
                }
                _ => viol = viol.max(r.sigma_n.max(0.0) / smax),
            }
        }
        // equilibrium of the top block, held only by the contact: the
        // contact forces on body I (bottom) sum to the applied traction times w
        let f = force_on_body_i(&run, c, |_| true);
        let applied = [MAP_TRACTION[0] * st.w, MAP_TRACTION[1] * st.w];
        let eq = (f[0] - applied[0]).abs().max((f[1] - applied[1]).abs()) / applied[0].hypot(applied[1]);
        let ok = open > 0 && closed > 0 && count(c, ContactState::Slip) == 0;
        s.check(
            &format!("f_t = 0 {kind}"),
            "bending: tension side opens; open pairs carry 0 and gap >= 0, closed ones sigma_n <= 0; contact forces balance the load",
            if ok { viol.max(eq) } else { f64::INFINITY },
            1e-9,
            Some(run.stats.residuals.interface),
            "f_t = 0",
            secs,
            &format!("complementarity {viol:.1e}, equilibrium {eq:.1e}; {}", states_note(c)),
        );
    }
}

/// Friction 0 and cohesion 0 on the curved joint in compression (Coulomb
/// law, the default): every pair may slip, and by symmetry there is nothing
/// to slip along, so the answer is the stuck one and tau = 0.
pub fn f0_compound_case(s: &mut Suite, lc: f64, ratios: &[f64]) {
    let m = Ring { kind: "quad9", order: 2, quad: true, serendipity: false, lc };
    for &ratio in ratios {
        let t = Instant::now();
        let stuck = solve(
            &s.case,
            &format!("f0c0_compound_{lc}_{ratio:e}_stuck"),
            &compound_scene(m, E_SOFT, E_SOFT * ratio, STUCK_JOINT, false),
            false,
        );
        let free = solve(
            &s.case,
            &format!("f0c0_compound_{lc}_{ratio:e}"),
            &compound_scene(m, E_SOFT, E_SOFT * ratio, "friction = 0.0\ncohesion = 0.0\ntensile_strength = 0.0", false),
            false,
        );
        let secs = t.elapsed().as_secs_f64();
        let c = free.contact().expect("a contact run");
        let note = format!("{} pairs, {}", c.pairs.len(), states_note(c));
        let label = format!("f = 0, c = 0 compound quad9 lc {lc}");
        let cond = format!("E2/E1 = {}", fmt_e(ratio));
        s.boolean(
            &label,
            "the contact iteration converges (max_iterations = 100)",
            c.summary.converged,
            Some(free.stats.residuals.interface),
            &cond,
            secs,
            &note,
        );
        if !c.summary.converged {
            continue;
        }
        let uniform = count(c, ContactState::Stick) == c.states.len() || count(c, ContactState::Slip) == c.states.len();
        let (du, _, dc, _) = compare_moved(&stuck, &free, 0.0, 0.0, 0.0, 1.0);
        let tau = max_abs(c.pairs.iter().map(|r| r.tau()));
        s.check(
            &label,
            "curved joint in compression (Coulomb law): all stick or all slip, tau = 0, the stuck answer",
            if uniform { du.max(dc).max(tau) } else { f64::INFINITY },
            1e-9,
            Some(free.stats.residuals.interface),
            &cond,
            0.0,
            &format!("u {du:.1e}, contact {dc:.1e}, tau {tau:.1e}"),
        );
    }
}
