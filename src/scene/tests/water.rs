//! The water keys of a contact and the seismic keys of a load: what they
//! become, and one message per bad input naming its key (issue 30's list:
//! a negative unit weight, a drain efficiency outside [0, 1], an uplift
//! table out of order, a face that is no hydrostatic load).

use super::{load, minimal, rejects};
use crate::scene::{Drain, JointWater, Levels, LoadKind, WaterFace, WaterPressure};

/// A scene with a contact "j" whose `water` is `water`, and `loads`.
fn with_water(water: &str, loads: &str) -> String {
    minimal(&format!("[[contacts]]\ngroup = \"j\"\nwater = {water}\n{loads}"))
}

const FACE: &str = "[[loads]]\ngroup = \"up\"\npressure = { surface = 50.0, unit_weight = 0.01 }\nfactors = [1.0]\n";

#[test]
fn water_keys_become_the_joint_water() {
    let s = load(&with_water("{ pressure = 0.2 }", "")).expect("uniform");
    assert_eq!(
        s.contacts[0].water,
        Some(JointWater { pressure: WaterPressure::Uniform(0.2), face: None, factors: None })
    );
    let s = load(&with_water(
        "{ face = \"up\", downstream = 5.0, drain = { at = 6.0, efficiency = 0.5 }, along = [-2.0, 0.0] }",
        FACE,
    ))
    .expect("an uplift diagram from the face");
    let w = s.contacts[0].water.clone().expect("water");
    assert_eq!(w.face, Some(WaterFace { group: "up".into(), load: 0, surface: 50.0, unit_weight: 0.01 }));
    assert_eq!(
        w.pressure,
        WaterPressure::Level {
            unit_weight: 0.01,
            along: [-1.0, 0.0, 0.0],
            levels: Levels::Ends { upstream: 50.0, downstream: 5.0 },
            drain: Some(Drain { at: 6.0, efficiency: 0.5 }),
        }
    );
    let s = load(&with_water("{ unit_weight = 9.81, levels = [[0, 10], [5, 4], [9, 1]] }", "")).expect("a table");
    let Some(WaterPressure::Level { levels, .. }) = s.contacts[0].water.as_ref().map(|w| w.pressure.clone()) else {
        panic!("a level")
    };
    assert_eq!(levels, Levels::Table(vec![[0.0, 10.0], [5.0, 4.0], [9.0, 1.0]]));
    let s = load(&with_water("{ unit_weight = 9.81, plane = [10.0, -0.5] }", "")).expect("a plane");
    let Some(WaterPressure::Level { levels, .. }) = s.contacts[0].water.as_ref().map(|w| w.pressure.clone()) else {
        panic!("a level")
    };
    assert_eq!(levels, Levels::Plane([10.0, -0.5, 0.0]));
}

#[test]
fn bad_water_is_named_by_its_key() {
    rejects(
        &with_water("{ unit_weight = -9.81, level = 3.0 }", ""),
        &["contacts[0].water.unit_weight", "-9.81", ">= 0"],
    );
    rejects(
        &with_water("{ unit_weight = 9.81, levels = [[0, 10], [5, 4]], drain = { at = 2.0, efficiency = 1.5 } }", ""),
        &["contacts[0].water.drain.efficiency", "1.5", "0 (no effect) to 1"],
    );
    rejects(
        &with_water("{ unit_weight = 9.81, levels = [[0, 10], [5, 4], [3, 1]] }", ""),
        &["contacts[0].water.levels[2]", "out of order", "s = 3"],
    );
    rejects(
        &with_water("{ face = \"nowhere\", downstream = 0.0 }", FACE),
        &["contacts[0].water.face", "\"nowhere\"", "no [[loads]] entry"],
    );
    let traction = "[[loads]]\ngroup = \"up\"\ntraction = [1.0, 0.0]\n";
    rejects(
        &with_water("{ face = \"up\", downstream = 0.0 }", traction),
        &["contacts[0].water.face", "not hydrostatic"],
    );
    rejects(&with_water("{ pressure = 0.2, level = 3.0 }", ""), &["contacts[0].water", "one way"]);
    rejects(&with_water("{ pressure = -0.2 }", ""), &["contacts[0].water.pressure", ">= 0"]);
    rejects(&with_water("{ level = 3.0 }", ""), &["contacts[0].water.unit_weight", "missing"]);
    rejects(
        &with_water("{ unit_weight = 1.0, level = 3.0, along = [0.0, 1.0] }", ""),
        &["contacts[0].water.along", "horizontal"],
    );
    rejects(
        &with_water("{ unit_weight = 1.0, level = 3.0, drain = { at = 1.0, efficiency = 0.5 } }", ""),
        &["contacts[0].water.drain", "a level (flat or a plane) has none"],
    );
    rejects(&with_water("{ unit_weight = 1.0, upstream = 3.0 }", ""), &["contacts[0].water.downstream", "missing"]);
    rejects(
        &with_water("{ pressure = 0.2, factors = [1.0, 2.0] }", ""),
        &["contacts[0].water.factors", "load_steps = 1"],
    );
    rejects(&with_water("{ pressure = 0.2, uplift = 1.0 }", ""), &["uplift"]);
    rejects(
        &with_water("{ unit_weight = 1.0, plane = [3.0, 0.1, 0.2] }", ""),
        &["contacts[0].water.plane", "[h0, dh/dx]"],
    );
}

#[test]
fn seismic_and_westergaard_loads() {
    let s = load(&minimal("[[loads]]\nseismic = { kh = 0.1, kv = 0.05, direction = [-3.0, 0.0] }\n")).expect("seismic");
    assert_eq!(s.loads[0].kind, LoadKind::Seismic { kh: 0.1, kv: 0.05, direction: [-1.0, 0.0, 0.0] });
    let s = load(&minimal(
        "[[loads]]\ngroup = \"up\"\npressure = { westergaard = 0.1, surface = 50.0, base = 0.0, unit_weight = 0.01 }\n",
    ))
    .expect("Westergaard");
    let kind = &s.loads[0].kind;
    assert_eq!(*kind, LoadKind::Westergaard { kh: 0.1, surface: 50.0, base: 0.0, unit_weight: 0.01 });
    // 7/8 kh gw sqrt(H (H - y)): at the base, 7/8 0.1 0.01 50
    assert!((kind.pressure_at([0.0, 0.0, 0.0], 1).unwrap() - 0.04375).abs() < 1e-15);
    assert_eq!(kind.pressure_at([0.0, 60.0, 0.0], 1), Some(0.0));
    rejects(&minimal("[[loads]]\ngroup = \"g\"\nseismic = { kh = 0.1 }\n"), &["loads[0]", "names no group"]);
    rejects(
        &minimal("[[loads]]\nseismic = { kh = 0.1, direction = [0.0, 1.0] }\n"),
        &["loads[0].seismic.direction", "horizontal"],
    );
    rejects(
        &minimal("[[loads]]\ngroup = \"up\"\npressure = { westergaard = 0.1, surface = 50.0, unit_weight = 0.01 }\n"),
        &["loads[0].pressure.base", "missing"],
    );
}
