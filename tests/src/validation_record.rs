//! One validation at a time: a number the model computed against an independent reference
//! (closed form, published table, another code, finite differences), within a stated tolerance.
//! [`validate`] asserts it, prints it, and, when `STICTION_VALIDATION_RECORD` names a file,
//! appends it there as a JSON line; `scripts/validation-report.sh` runs the validation tests so
//! and turns the lines into the table of `docs/validation-report.md`. The test that made a line
//! is the one the harness runs it in (its thread's name, `module::test`).

use std::io::Write;

/// How far a measured number may lie from its reference.
#[derive(Debug, Clone, Copy)]
pub enum Tolerance {
    /// |measured / reference - 1| at most this.
    Relative(f64),
    /// |measured - reference| at most this, in the quantity's unit.
    Absolute(f64),
}

impl Tolerance {
    /// The deviation measured against this kind of tolerance (relative or absolute).
    fn deviation(self, measured: f64, reference: f64) -> f64 {
        match self {
            Tolerance::Relative(_) => measured / reference - 1.0,
            Tolerance::Absolute(_) => measured - reference,
        }
    }

    fn bound(self) -> f64 {
        match self {
            Tolerance::Relative(t) | Tolerance::Absolute(t) => t,
        }
    }

    fn describe(self, value: f64, unit: &str) -> String {
        match self {
            Tolerance::Relative(_) => format!("{:+.3}%", 100.0 * value),
            Tolerance::Absolute(_) => format!("{value:+.3e} {unit}").trim_end().to_string(),
        }
    }
}

/// Asserts that `measured` lies within `tolerance` of `reference` (what the quantity is, its
/// unit, and the reference's source named), prints the comparison, and records it.
pub fn validate(quantity: &str, unit: &str, measured: f64, reference: f64, source: &str, tolerance: Tolerance) {
    let deviation = tolerance.deviation(measured, reference);
    let line = format!(
        "{quantity}: {measured:.6e} {unit} against {reference:.6e} ({source}): {} (tolerance {})",
        tolerance.describe(deviation, unit),
        tolerance.describe(tolerance.bound(), unit).trim_start_matches('+'),
    );
    println!("validation: {line}");
    record(quantity, unit, measured, reference, source, tolerance, deviation);
    assert!(deviation.abs() <= tolerance.bound() && measured.is_finite(), "{line}");
}

fn record(quantity: &str, unit: &str, measured: f64, reference: f64, source: &str, tolerance: Tolerance, dev: f64) {
    let Some(path) = std::env::var_os("STICTION_VALIDATION_RECORD") else {
        return;
    };
    let (kind, bound) = match tolerance {
        Tolerance::Relative(t) => ("relative", t),
        Tolerance::Absolute(t) => ("absolute", t),
    };
    let test = std::thread::current().name().unwrap_or("?").to_string();
    let entry = serde_json::json!({
        "test": test, "quantity": quantity, "unit": unit, "measured": measured, "reference": reference,
        "source": source, "tolerance": kind, "bound": bound, "deviation": dev,
        "passed": dev.abs() <= bound,
    });
    // one write per line, appended: the tests of a binary run on several threads
    let mut file = std::fs::OpenOptions::new().create(true).append(true).open(&path).expect("the record file");
    file.write_all(format!("{entry}\n").as_bytes()).expect("the record file");
}
