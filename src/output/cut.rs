//! What the joints made, in words: each joint's planes and area, the
//! blocks, the smallest and thinnest of them, and the planes that pass so
//! close to a corner that they cut off a sliver (with the `snap` that
//! cures it). `check` prints it, report.md carries it.

use crate::mesh::joints::{trim, CutReport, JointSpec, Placement};

/// A point as `(x, y, z)` (2D: `(x, y)`), to 4 significant digits.
fn at(p: [f64; 3], dim: usize) -> String {
    let f = |v: f64| {
        if v == 0.0 {
            "0".to_string()
        } else {
            trim(format!("{v:.4e}").parse::<f64>().unwrap_or(v))
        }
    };
    format!("({})", p[..dim].iter().map(|&v| f(v)).collect::<Vec<_>>().join(", "))
}

/// Four significant digits.
fn g4(v: f64) -> String {
    trim(format!("{v:.3e}").parse::<f64>().unwrap_or(v))
}

/// One line per joint, then the blocks: what `check` prints (indented by
/// the caller) and report.md lists.
pub fn summary(report: &CutReport, joints: &[JointSpec], dim: usize) -> Vec<String> {
    let (area, faces) = if dim == 3 { ("area", "faces") } else { ("length", "traces") };
    let mut out = Vec::new();
    for (r, j) in report.joints.iter().zip(joints) {
        let how = match j.placement {
            Placement::Set { spacing, offset } => format!("spacing {}, offset {}", trim(spacing), trim(offset)),
            Placement::Single { point } => format!("through {}", at(point, dim)),
        };
        let ks: Vec<i64> = r.planes.iter().filter_map(|p| p.k).collect();
        let range = match (ks.first(), ks.last()) {
            (Some(a), Some(b)) if a != b => format!(" (k = {a}..{b})"),
            (Some(a), _) => format!(" (k = {a})"),
            _ => String::new(),
        };
        let finite = j.persistence.as_ref().map_or(String::new(), |p| {
            format!(
                ", finite: {} {} with {} between",
                trim(p.size),
                if dim == 3 { "wide" } else { "long" },
                trim(p.gap)
            )
        });
        out.push(format!(
            "{} ({}) {}, {how}{finite}: {} plane(s){range}, {area} {} in {} {faces}",
            r.name,
            r.key,
            r.label,
            r.planes.len(),
            g4(r.area()),
            r.faces
        ));
        for p in r.planes.iter().filter(|p| p.snapped.is_some()) {
            if let Some((c, d)) = p.snapped {
                out.push(format!("  plane{} snapped by {} onto the corner {}", k_of(p.k), g4(d), at(c, dim)));
            }
        }
    }
    if report.blocks.is_empty() {
        return out;
    }
    let (vol, n) = (if dim == 3 { "volume" } else { "area" }, report.blocks.len());
    let total: f64 = report.blocks.iter().map(|b| b.volume).sum();
    let mut bodies: Vec<&str> = report.blocks.iter().map(|b| b.body.as_str()).collect();
    bodies.sort_unstable();
    bodies.dedup();
    out.push(format!(
        "{n} blocks ({}), {vol} {} in all, {} on average",
        bodies.join(", "),
        g4(total),
        g4(total / n as f64)
    ));
    let smallest = report.blocks.iter().min_by(|a, b| a.volume.total_cmp(&b.volume));
    let thinnest = report.blocks.iter().min_by(|a, b| a.thickness.total_cmp(&b.thickness));
    if let (Some(s), Some(t)) = (smallest, thinnest) {
        out.push(format!(
            "smallest block: {vol} {} at {}; thinnest: {} thick (6 V / A) at {}",
            g4(s.volume),
            at(s.centre, dim),
            g4(t.thickness),
            at(t.centre, dim)
        ));
    }
    if report.merged > 0 {
        out.push(format!(
            "merge_slivers: {} sliver block(s) bonded to a neighbour across their largest joint face",
            report.merged
        ));
    }
    if report.straightened > 0 {
        out.push(format!(
            "Mesh.HighOrderOptimize: {} quadratic element(s) that folded or distorted on a curved face made straight",
            report.straightened
        ));
    }
    out
}

fn k_of(k: Option<i64>) -> String {
    k.map_or(String::new(), |k| format!(" k = {k}"))
}

/// One warning per plane that passes close to a corner of its bodies, and
/// one for the blocks that are slivers.
pub fn warnings(report: &CutReport, dim: usize) -> Vec<String> {
    let slivers: Vec<_> = report.blocks.iter().filter(|b| b.is_sliver()).collect();
    let sliver = slivers.iter().min_by(|a, b| a.thickness.total_cmp(&b.thickness)).map(|b| {
        format!(
            "{} block(s) are slivers, thinner than a tenth of the mesh size there: the thinnest is {} thick (6 V / A) at {} where the mesh size is {}. Two joints meet close to a face or to each other there; move the offset of a set that cuts it (check lists the planes){}",
            slivers.len(),
            g4(b.thickness),
            at(b.centre, dim),
            g4(b.size),
            if report.merged > 0 {
                format!("; {} are bonded to a neighbour (merge_slivers)", report.merged)
            } else {
                ", or give merge_slivers = true to bond each to a neighbour".to_string()
            }
        )
    });
    report
        .near_misses
        .iter()
        .map(|m| {
            format!(
                "{} (\"{}\"): plane{} (n . x = {}) passes {} from the corner {} of its bodies, where the mesh size is {}: the sliver it cuts off makes flat elements. Add snap = {} to {} to move such planes onto the corner (or change offset)",
                m.key,
                m.name,
                k_of(m.k),
                g4(m.offset),
                g4(m.distance),
                at(m.corner, dim),
                g4(m.size),
                g4(m.distance * 2.0),
                m.key
            )
        })
        .chain(sliver)
        .collect()
}
