//! The stress suite's table: every case records rows (what is checked, the
//! error measured, the bound asserted or `report`, the interface residual,
//! a condition figure, the time), a case that panics becomes a failed row,
//! and `finish` writes `results/stress/stress.md`, prints it, and fails the
//! test when a row failed, after the table is written.

use std::fmt::Write as _;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::PathBuf;
use std::time::Instant;

use crate::common::Case;

/// One measured line of the table.
struct Row {
    case: String,
    checks: String,
    /// The error measured (relative, see `checks`).
    error: f64,
    /// The bound asserted; None: reported only.
    tol: Option<f64>,
    pass: bool,
    /// Largest relative residual of the interface solve (None: no contact).
    residual: Option<f64>,
    /// Condition figure: contrast, aspect ratio, coordinates, nu.
    condition: String,
    seconds: f64,
    note: String,
}

pub struct Suite {
    name: &'static str,
    pub case: Case,
    rows: Vec<Row>,
    t0: Instant,
}

impl Suite {
    pub fn new(name: &'static str) -> Suite {
        let case = Case::new(&format!("stress-{name}"));
        case.copy("tests/geo/stress_stack.geo");
        case.copy("tests/geo/stress_annulus.geo");
        case.copy("tests/geo/lame_slice.geo");
        case.copy("geo/cylinder.geo");
        Suite { name, case, rows: Vec::new(), t0: Instant::now() }
    }

    /// Records a checked row: passes when `error <= tol` (NaN fails).
    #[allow(clippy::too_many_arguments)]
    pub fn check(
        &mut self,
        case: &str,
        checks: &str,
        error: f64,
        tol: f64,
        residual: Option<f64>,
        condition: &str,
        seconds: f64,
        note: &str,
    ) {
        let pass = error <= tol;
        self.push(Row {
            case: case.into(),
            checks: checks.into(),
            error,
            tol: Some(tol),
            pass,
            residual,
            condition: condition.into(),
            seconds,
            note: note.into(),
        });
    }

    /// Records a reported-only row (no bound; NaN still fails).
    #[allow(clippy::too_many_arguments)]
    pub fn report(
        &mut self,
        case: &str,
        checks: &str,
        error: f64,
        residual: Option<f64>,
        condition: &str,
        seconds: f64,
        note: &str,
    ) {
        let pass = error.is_finite();
        self.push(Row {
            case: case.into(),
            checks: checks.into(),
            error,
            tol: None,
            pass,
            residual,
            condition: condition.into(),
            seconds,
            note: note.into(),
        });
    }

    /// Records a yes/no check.
    #[allow(clippy::too_many_arguments)]
    pub fn boolean(
        &mut self,
        case: &str,
        checks: &str,
        ok: bool,
        residual: Option<f64>,
        condition: &str,
        seconds: f64,
        note: &str,
    ) {
        self.push(Row {
            case: case.into(),
            checks: checks.into(),
            error: if ok { 0.0 } else { 1.0 },
            tol: Some(0.0),
            pass: ok,
            residual,
            condition: condition.into(),
            seconds,
            note: note.into(),
        });
    }

    fn push(&mut self, row: Row) {
        eprintln!(
            "[{}] {:<34} {:<8} error {:.3e}  tol {}  {}  ({:.2} s) {}",
            self.name,
            row.case,
            if row.pass { "pass" } else { "FAIL" },
            row.error,
            row.tol.map(|t| format!("{t:.1e}")).unwrap_or_else(|| "report".into()),
            row.condition,
            row.seconds,
            row.note
        );
        self.rows.push(row);
    }

    /// Runs one case; a panic (an unexpected run error, a missing value)
    /// becomes a failed row instead of losing the table.
    pub fn run_case(&mut self, name: &str, f: impl FnOnce(&mut Suite)) {
        let t = Instant::now();
        let result = catch_unwind(AssertUnwindSafe(|| f(self)));
        if let Err(e) = result {
            let msg = e
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| e.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_default();
            let first = msg.lines().next().unwrap_or("").chars().take(300).collect::<String>();
            self.push(Row {
                case: name.into(),
                checks: "the case ran to the end".into(),
                error: f64::NAN,
                tol: Some(0.0),
                pass: false,
                residual: None,
                condition: String::new(),
                seconds: t.elapsed().as_secs_f64(),
                note: format!("panicked: {first}"),
            });
        }
    }

    /// Writes `results/stress/stress.md`, prints it, and fails when a row failed.
    pub fn finish(self) {
        let total = self.t0.elapsed().as_secs_f64();
        let mut s = String::new();
        let _ = writeln!(s, "# Numerical stress tests ({} suite)\n", self.name);
        let _ = writeln!(
            s,
            "Written by `cargo test --release --test stress{}` (tests/stress.rs). Each row: what is checked, the error measured, the bound asserted (`report`: measured and shown, not asserted), the largest relative residual of the dense interface solve `|K_c d_c - R_c| / |R_c|` over the runs of the row (`-`: no contact solve), a condition figure, and the run time (meshing included). {} rows, {} failed, {:.1} s in all.\n",
            if self.name == "full" { " -- --ignored" } else { "" },
            self.rows.len(),
            self.rows.iter().filter(|r| !r.pass).count(),
            total
        );
        let _ = writeln!(
            s,
            "| case | checks | error | tolerance | pass | interface residual | condition | time (s) | notes |"
        );
        let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|");
        let cell = |t: &str| t.replace('|', "\\|");
        for r in &self.rows {
            let _ = writeln!(
                s,
                "| {} | {} | {:.2e} | {} | {} | {} | {} | {:.2} | {} |",
                cell(&r.case),
                cell(&r.checks),
                r.error,
                r.tol
                    .map(|t| if t == 0.0 { "0".to_string() } else { format!("{t:.0e}") })
                    .unwrap_or_else(|| "report".into()),
                if r.pass { "pass" } else { "**FAIL**" },
                r.residual.map(|v| format!("{v:.1e}")).unwrap_or_else(|| "-".into()),
                cell(&r.condition),
                r.seconds,
                cell(&r.note)
            );
        }
        s += NOTES;
        let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("results").join("stress");
        std::fs::create_dir_all(&dir).expect("results/stress");
        let tmp = dir.join(".stress.md.tmp");
        std::fs::write(&tmp, &s).expect("write the table");
        std::fs::rename(&tmp, dir.join("stress.md")).expect("write the table");
        println!("{s}");
        eprintln!("{s}");
        let failed: Vec<String> = self
            .rows
            .iter()
            .filter(|r| !r.pass)
            .map(|r| format!("{}: {} (error {:.3e}) {}", r.case, r.checks, r.error, r.note))
            .collect();
        assert!(failed.is_empty(), "{} stress case(s) failed:\n{}", failed.len(), failed.join("\n"));
    }
}

const NOTES: &str = "
Notes.
- Errors are relative: stresses to the load p, displacements to the largest displacement, contact stresses to p or to the largest contact stress, as each row says.
- Contrast: `E2/E1` is the outer ring's modulus over the inner ring's. Each contrast is also solved monolithically (`--bonded`, same mesh): the difference is what condensation and the interface system lose to round-off. The closed-form errors are discretisation errors of the mesh (they fall with lc in the full suite), not of the contrast.
- Sign convention: sigma_n is the normal traction on body I, tension positive; n . sigma . n does not depend on which body is I, so sigma_n = sigma_r(c) with either ring listed first, while n flips from +e_r to -e_r.
- Locking: no remedy (B-bar, selective reduced integration, mixed u-p elements) is implemented. Linear rows are reported, not asserted: their displacement error grows ~100x from nu = 0.3 to 0.499. Quadratic displacement errors are asserted. The stresses of every element degrade as lambda/mu (the pressure lambda div u amplifies the discretisation error of div u): reported.
- Aspect ratio: element size along the joint over the size across it (flat) or its inverse (tall), with the blocks' shape fixed; the exact solution (uniform stress) lies in every element space, so the error is round-off. Bounds: `aspect_tols` in tests/stress/aspect.rs. Contact stresses of elements stretched across the joint lose about one more power of AR than displacements (they are read off S d - G). The slender-column row (AR 1000 elements in a 1 x 2000 column held at one corner) shows what the structure's own slenderness costs: reported.
- Map coordinates: per move, two rows. Asserted: the mesh of the model at the origin moved by the test (x' = x0 + R x, rounded once to a double), so only the solver is measured; its error grows as eps |x| / h, from arithmetic on absolute coordinates (the shift-only rows have exactly representable coordinates). Reported: gmsh meshing the moved .geo itself, which places nodes of the rotated model at |x| ~ 4e6 up to ~1e-6 m off (see the notes column) and so changes the answer by more than the solver does.
- Units: Pa against MPa, E, loads, cohesion and tensile strength scaled by 1e6.
- f = 0, c = 0: with the Coulomb law the criterion tau >= c - f sigma_n = 0 holds at every pair, so pairs may slip; nothing may change but the state names.
";
