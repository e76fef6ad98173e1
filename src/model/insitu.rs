//! The in-situ stress against the joints' strength, before anything is
//! solved: a body's initial stress (`initial_stress` or `k0` with
//! `surface`) puts a traction `σ0 n` on every contact pair of its faces,
//! and where that traction is beyond the joint's strength (Coulomb's
//! `|τ| > c + f σn'`, or tension beyond `f_t`) the rock mass cannot be in
//! equilibrium with its joints as given: the first load step then slips
//! and opens them under the in-situ stress alone, and a report that ranks
//! stuck faces by mobilised friction reads nonsense. Each contact group
//! with pairs beyond gets one warning: how many pairs, how far beyond (the
//! largest mobilisation `|τ| / (c + f σn')`), and what to do.
//!
//! Judged pair by pair at node k's body (side I); a pair whose body carries
//! no initial stress is not judged, nor a frictionless contact (it carries
//! no shear by definition), nor one with water in it (its effective stress
//! depends on the water the check does not read).

use super::mechanical::Model;
use super::spec::stress_times as traction;

/// What a contact group can carry, from its `[[contacts]]` entry.
#[derive(Clone, Copy, Debug)]
pub struct JointStrength {
    pub friction: f64,
    pub cohesion: f64,
    pub tensile_strength: f64,
    /// Skip the group (frictionless, or water in it).
    pub skip: bool,
}

/// The pairs of one contact group beyond its strength under the in-situ stress.
#[derive(Clone, Debug, PartialEq)]
pub struct Beyond {
    pub contact: usize,
    /// Pairs judged (their body carries an initial stress), and of them
    /// those beyond in shear and in tension.
    pub judged: usize,
    pub shear: usize,
    pub tension: usize,
    /// The largest `|τ| / (c + f σn')` over the pairs judged (infinite
    /// where the strength is zero and the shear is not).
    pub mobilised: f64,
}

/// Relative allowance on the strength before a pair counts as beyond (the
/// geostatic stress puts some joints exactly at their limit).
const ALLOWANCE: f64 = 1e-9;

/// The in-situ traction `σ0 n` on body I at every pair (global axes;
/// zero where that body carries no initial stress): what a joint that
/// deforms carries before anything moves.
pub fn tractions(model: &Model) -> Vec<[f64; 3]> {
    let body = model.body_of_node();
    (model.pairs.iter())
        .map(|pair| {
            let Some(b) = model.bodies.get(body[pair.k]) else { return [0.0; 3] };
            let Some(initial) = b.initial else { return [0.0; 3] };
            let sigma = initial.at(model.coords[pair.k], model.analysis, b.material.density, model.gravity);
            traction(&sigma, pair.normal)
        })
        .collect()
}

/// Every contact group with pairs beyond its strength (by `strengths`,
/// indexed as the model's interfaces), in contact order.
pub fn beyond(model: &Model, strengths: &[JointStrength]) -> Vec<Beyond> {
    let body = model.body_of_node();
    let mut out: Vec<Beyond> = Vec::new();
    for pair in &model.pairs {
        let Some(s) = strengths.get(pair.contact).filter(|s| !s.skip) else { continue };
        let Some(b) = model.bodies.get(body[pair.k]) else { continue };
        let Some(initial) = b.initial else { continue };
        let sigma = initial.at(model.coords[pair.k], model.analysis, b.material.density, model.gravity);
        let t = traction(&sigma, pair.normal);
        let n = pair.normal;
        let sn = t[0] * n[0] + t[1] * n[1] + t[2] * n[2];
        let tau = (0..3).map(|a| (t[a] - sn * n[a]).powi(2)).sum::<f64>().sqrt();
        let strength = s.cohesion + s.friction * (-sn).max(0.0);
        let entry = match out.iter_mut().find(|e| e.contact == pair.contact) {
            Some(e) => e,
            None => {
                out.push(Beyond { contact: pair.contact, judged: 0, shear: 0, tension: 0, mobilised: 0.0 });
                out.last_mut().expect("just pushed")
            }
        };
        entry.judged += 1;
        if sn > s.tensile_strength * (1.0 + ALLOWANCE) + f64::MIN_POSITIVE {
            entry.tension += 1;
        } else if tau > strength * (1.0 + ALLOWANCE) + 1e-12 * sn.abs() {
            entry.shear += 1;
        }
        let m = if strength > 0.0 {
            tau / strength
        } else if tau > 0.0 {
            f64::INFINITY
        } else {
            0.0
        };
        entry.mobilised = entry.mobilised.max(m);
    }
    out.retain(|e| e.shear + e.tension > 0);
    out
}

/// One paragraph per contact group beyond its strength (the caller puts
/// the scene file's name in front).
pub fn warnings(model: &Model, strengths: &[JointStrength]) -> Vec<String> {
    beyond(model, strengths)
        .iter()
        .map(|e| {
            let name = &model.interfaces[e.contact].name;
            let mut what = Vec::new();
            if e.shear > 0 {
                what.push(format!("{} beyond Coulomb's c + f sigma_n (mobilised up to {:.3} of it)", e.shear, e.mobilised));
            }
            if e.tension > 0 {
                what.push(format!("{} in tension beyond f_t", e.tension));
            }
            let then = if model.hold_case.is_some() {
                "The initial equilibrium stage ([solver] initial_stage) slips or opens it under the in-situ stress alone, before the loads, and the displacements it makes are taken off every load step's (summary.json initial_stage says how far it moved). Check k0 / initial_stress against the joint's friction and cohesion if the joint is not meant to move in situ"
            } else {
                "The rock mass is not in equilibrium with this joint as given, so the first load step slips or opens it under the in-situ stress alone, mixed with the loads. Check k0 / initial_stress against the joint's friction and cohesion, give the joint the strength it has in situ, or let [solver] initial_stage = true bring the rock mass to equilibrium with its joints before the loads (its displacements then reset)"
            };
            format!(
                "the in-situ stress puts {} of the {} pairs of contact \"{name}\" beyond its strength: {}. {then}",
                e.shear + e.tension,
                e.judged,
                what.join(", ")
            )
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::traction;

    #[test]
    fn the_traction_of_a_geostatic_stress_on_a_dipping_plane() {
        // sigma_v = -1, k0 = 0.5, a plane dipping 45 degrees in x-z
        let s = [-0.5, -0.5, -1.0, 0.0, 0.0, 0.0];
        let r = 0.5f64.sqrt();
        let n = [r, 0.0, r];
        let t = traction(&s, n);
        let sn = t[0] * n[0] + t[2] * n[2];
        let tau = ((t[0] - sn * n[0]).powi(2) + (t[2] - sn * n[2]).powi(2)).sqrt();
        // Mohr: sigma_n = (s1 + s3) / 2 = -0.75, tau = (s1 - s3) / 2 = 0.25
        assert!((sn + 0.75).abs() < 1e-15 && (tau - 0.25).abs() < 1e-15, "{sn} {tau}");
    }
}
