//! The safety search in words, shared by report.md and summary.json: what
//! F is, the other strength's factor where it differs, the warnings, and
//! factors written as the report writes them.

use crate::results::{OtherFactor, Run, SafetyRun, SearchKind};

/// Factors that differ by more than this are both reported.
pub const DIFFER: f64 = 0.01;

/// What F is, for a reader: "factor of safety (strength reduction, peak
/// strength)" or "load factor (raising \"water\")".
pub fn label(run: &Run, s: &SafetyRun) -> String {
    match s.kind {
        SearchKind::Strength(st) => format!("factor of safety (strength reduction, {} strength)", st.key()),
        SearchKind::Load => format!("load factor (raising {})", raised(run)),
    }
}

/// The loads a load factor search raises, quoted.
pub(super) fn raised(run: &Run) -> String {
    let Some(r) = run.about.safety.as_ref().and_then(|o| o.raise.as_ref()) else { return String::new() };
    let mut names: Vec<String> = r.loads.iter().map(|&i| format!("\"{}\"", run.about.loads[i])).collect();
    if r.gravity {
        names.push("gravity".into());
    }
    names.join(", ")
}

/// What a strength convention means.
fn meaning(st: crate::contact::safety::Strengths) -> &'static str {
    match st {
        crate::contact::safety::Strengths::Peak => {
            "each joint keeps its peak cohesion where its pairs slip or open, as limit equilibrium assumes"
        }
        crate::contact::safety::Strengths::Residual => {
            "a pair that slips or opens keeps only its residual_cohesion, as in the load steps"
        }
    }
}

/// Whether two factors differ by more than [`DIFFER`].
pub(super) fn differ(a: Option<f64>, b: Option<f64>) -> bool {
    match (a, b) {
        (Some(a), Some(b)) => (a / b - 1.0).abs() > DIFFER,
        (None, None) => false,
        _ => true,
    }
}

/// The line on the other strength's factor, where it differs from the
/// headline by more than 1 %.
pub fn other_factor_line(_run: &Run, s: &SafetyRun, o: &OtherFactor) -> Option<String> {
    if !differ(s.factor, o.factor) {
        return None;
    }
    let f = match (o.factor, o.decided) {
        (Some(f), true) => format!("F = {}", fmt_f(f)),
        (Some(f), false) => format!("F not decided (holds at {})", fmt_g(f)),
        (None, _) => "no factor held".into(),
    };
    Some(format!("with {} strength ({}): {f}", o.strengths.key(), meaning(o.strengths)))
}

/// Warnings on the search: a headline the scene's silence chose where the
/// conventions differ, and a residual strength taken from a default.
pub fn warnings(run: &Run) -> Vec<String> {
    let (Some(s), Some(o)) = (&run.safety, &run.about.safety) else { return Vec::new() };
    let SearchKind::Strength(st) = s.kind else { return Vec::new() };
    let silent: Vec<String> = (run.about.contacts.iter().enumerate())
        .filter(|(_, c)| !c.residual_given && c.strength.cohesion > 0.0)
        .map(|(i, _)| format!("\"{}\"", run.model.interfaces[i].name))
        .collect();
    let mut out = Vec::new();
    if let (Some(other), false) = (&s.other, o.strength_given) {
        if differ(s.factor, other.factor) {
            let residual = if silent.is_empty() {
                "the scene's residual_cohesion".to_string()
            } else {
                format!("residual_cohesion, 0 by default and not given for {}", silent.join(", "))
            };
            out.push(format!(
                "{}: the factor of safety F = {} keeps each joint's {} strength ([safety] strength = \"{}\" by default: {}); with {} strength ({residual}) F = {}. The scene does not say which holds for its joints: set [safety] strength = \"peak\" or \"residual\" (and residual_cohesion where joints keep some cohesion once they slip)",
                run.about.path.display(),
                s.factor.map_or("-".into(), fmt_f),
                st.key(),
                st.key(),
                meaning(st),
                other.strengths.key(),
                other.factor.map_or("-".into(), fmt_f),
            ));
        }
    }
    if st == crate::contact::safety::Strengths::Residual && !silent.is_empty() {
        out.push(format!("{}: [safety] strength = \"residual\", and {} give no residual_cohesion: 0 by default, so their cohesion is lost wherever a pair slips or opens", run.about.path.display(), silent.join(", ")));
    }
    out
}

/// A factor as the report writes it: four decimals, trailing zeros kept short.
pub(super) fn fmt_f(v: f64) -> String {
    let t = format!("{v:.4}");
    t.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// A factor of the bracket: six decimals, trailing zeros dropped.
pub(super) fn fmt_g(v: f64) -> String {
    let t = format!("{v:.6}");
    t.trim_end_matches('0').trim_end_matches('.').to_string()
}
