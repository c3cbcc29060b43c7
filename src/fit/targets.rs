//! Targets against a run: a measured curve (CSV) interpolated on the run's `history.csv`, or a
//! number of its `summary.json`.
//!
//! A curve is compared on the measured points: the run's loading branch (from the start to its
//! first largest approach) or unloading branch (from there to the smallest approach after it),
//! interpolated linearly in approach. Past the end of the unloading branch of an interface that
//! separated, force and area are zero (the run stopped because the body let go).

use crate::ensemble::curves;
use crate::error::{Result, StictionError};
use std::path::{Path, PathBuf};

/// The history columns a curve target may compare.
pub const CURVE_COLUMNS: [&str; 3] = ["force", "contact_area", "contact_resistance"];

/// Which branch of the run a measured point lies on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Branch {
    Loading,
    Unloading,
}

/// One measured point.
#[derive(Debug, Clone, Copy)]
pub struct MeasuredPoint {
    pub approach: f64,
    pub value: f64,
    pub branch: Branch,
    pub sigma: Option<f64>,
    /// Its line in the file (1-based).
    pub line: usize,
}

/// A measured curve.
#[derive(Debug, Clone)]
pub struct CurveTarget {
    pub path: PathBuf,
    /// The history column compared (one of [`CURVE_COLUMNS`]).
    pub column: String,
    pub points: Vec<MeasuredPoint>,
}

/// Reads a measured curve: a header naming `approach`, one of [`CURVE_COLUMNS`], and optionally
/// `branch` and `sigma`; `#` lines are comments. Returns the curve and the file's text.
pub fn read_curve(path: &Path) -> Result<(CurveTarget, String)> {
    let bad = |line: usize, message: String| StictionError::TargetFile { path: path.to_path_buf(), line, message };
    let text = std::fs::read_to_string(path).map_err(|e| bad(0, format!("cannot read it: {e}")))?;
    let mut rows =
        text.lines().enumerate().map(|(i, l)| (i + 1, l.trim())).filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
    let Some((header_line, header)) = rows.next() else {
        return Err(bad(0, "is empty: expected a header such as `approach,force` and measured rows".into()));
    };
    let names: Vec<&str> = header.split(',').map(str::trim).collect();
    let find = |n: &str| names.iter().position(|h| *h == n);
    let Some(ia) = find("approach") else {
        return Err(bad(header_line, format!("the header '{header}' has no `approach` column")));
    };
    let measured: Vec<&str> = CURVE_COLUMNS.iter().copied().filter(|c| names.contains(c)).collect();
    let column = match measured.as_slice() {
        [one] => one.to_string(),
        _ => {
            return Err(bad(
                header_line,
                format!(
                    "the header '{header}' must name exactly one of {} (a file per quantity)",
                    CURVE_COLUMNS.join(", ")
                ),
            ));
        }
    };
    if let Some(unknown) = names.iter().find(|n| !["approach", "branch", "sigma", column.as_str()].contains(n)) {
        return Err(bad(
            header_line,
            format!("unknown column '{unknown}' (expected approach, {column}, and optionally branch and sigma)"),
        ));
    }
    let iv = find(&column).expect("found above");
    let (ib, is) = (find("branch"), find("sigma"));
    let mut points = Vec::new();
    for (line, row) in rows {
        let cells: Vec<&str> = row.split(',').map(str::trim).collect();
        if cells.len() != names.len() {
            return Err(bad(line, format!("has {} fields, the header {}", cells.len(), names.len())));
        }
        let number = |i: usize, what: &str| -> Result<f64> {
            match cells[i].parse::<f64>() {
                Ok(v) if v.is_finite() => Ok(v),
                _ => Err(bad(line, format!("{what} '{}' is not a finite number", cells[i]))),
            }
        };
        let branch = match ib.map(|i| cells[i]) {
            None | Some("loading") => Branch::Loading,
            Some("unloading") => Branch::Unloading,
            Some(other) => return Err(bad(line, format!("branch '{other}': expected loading or unloading"))),
        };
        let sigma = match is {
            Some(i) => {
                let s = number(i, "sigma")?;
                if !(s > 0.0) {
                    return Err(bad(line, format!("sigma {s} must be positive")));
                }
                Some(s)
            }
            None => None,
        };
        points.push(MeasuredPoint {
            approach: number(ia, "approach")?,
            value: number(iv, &column)?,
            branch,
            sigma,
            line,
        });
    }
    if points.is_empty() {
        return Err(bad(header_line, "has a header but no measured rows".into()));
    }
    Ok((CurveTarget { path: path.to_path_buf(), column, points }, text))
}

/// What a completed run left for the targets: its summary and its history's columns.
#[derive(Debug, Clone)]
pub struct RunOutputs {
    pub summary: serde_json::Value,
    header: Vec<String>,
    rows: Vec<Vec<f64>>,
}

impl RunOutputs {
    /// Reads `summary.json` and `history.csv` from a run's folder.
    pub fn read(folder: &Path) -> std::result::Result<Self, String> {
        let read = |name: &str| {
            std::fs::read_to_string(folder.join(name)).map_err(|e| format!("{}: {e}", folder.join(name).display()))
        };
        let summary: serde_json::Value =
            serde_json::from_str(&read("summary.json")?).map_err(|e| format!("summary.json: {e}"))?;
        let history = read("history.csv")?;
        let mut lines = history.lines();
        let header: Vec<String> = lines.next().unwrap_or_default().split(',').map(String::from).collect();
        let rows = lines
            .map(|l| l.split(',').filter_map(|x| x.parse().ok()).collect::<Vec<f64>>())
            .filter(|v| v.len() == header.len())
            .collect();
        Ok(Self { summary, header, rows })
    }

    /// The interface's summary: the one named, else the first with a flat, else the first.
    fn interface(&self, name: Option<&str>) -> std::result::Result<&serde_json::Value, String> {
        let list = self.summary["interfaces"].as_array().map(Vec::as_slice).unwrap_or_default();
        match name {
            Some(n) => list.iter().find(|i| i["name"] == n).ok_or_else(|| {
                let known: Vec<&str> = list.iter().filter_map(|i| i["name"].as_str()).collect();
                format!("the case has no interface '{n}' (it has: {})", known.join(", "))
            }),
            None => list
                .iter()
                .find(|i| i["kind"] == "rigid-flat")
                .or(list.first())
                .ok_or_else(|| "the case has no interface".to_string()),
        }
    }

    /// A number of summary.json: at the top level where it is one, else the interface's. Err
    /// when the run did not produce it (null: e.g. no pull-off because it never separated).
    pub fn summary_value(&self, field: &str, interface: Option<&str>) -> std::result::Result<f64, String> {
        let value = match self.summary.get(field) {
            Some(top) => top,
            None => &self.interface(interface)?[field],
        };
        value.as_f64().ok_or_else(|| {
            let why = if field.contains("pull_off") { " (the interface did not separate)" } else { "" };
            format!("the run gives no {field}{why}")
        })
    }

    /// The run's values at the measured points of `curve`.
    pub fn curve_values(&self, curve: &CurveTarget, interface: Option<&str>) -> std::result::Result<Vec<f64>, String> {
        let prefix = match interface {
            Some(n) if !self.header.iter().any(|h| h == "approach") => format!("{n}_"),
            _ if self.header.iter().any(|h| h == "approach") => String::new(),
            _ => self
                .header
                .iter()
                .find_map(|h| h.strip_suffix("approach").filter(|p| p.ends_with('_')))
                .ok_or("history.csv has no approach column (the case has no rigid flat)")?
                .to_string(),
        };
        let col = |n: &str| {
            self.header
                .iter()
                .position(|h| *h == format!("{prefix}{n}"))
                .ok_or_else(|| format!("history.csv has no column {prefix}{n}"))
        };
        let (ia, iv) = (col("approach")?, col(&curve.column)?);
        let samples: Vec<(f64, f64, f64)> = self.rows.iter().map(|r| (r[ia], r[iv], 0.0)).collect();
        let (loading, unloading) = curves::branches(&samples).ok_or("history.csv has fewer than two increments")?;
        let separated = self.interface(interface).map(|i| i["separated"] == true).unwrap_or(false);
        curve
            .points
            .iter()
            .map(|p| {
                let branch = if p.branch == Branch::Loading { &loading } else { &unloading };
                if let Some((v, _)) = curves::at(branch, p.approach) {
                    return Ok(v);
                }
                let end = branch.last().map_or(f64::NAN, |s| s.0);
                let start = branch.first().map_or(f64::NAN, |s| s.0);
                if p.branch == Branch::Unloading
                    && separated
                    && p.approach < end
                    && curve.column != "contact_resistance"
                {
                    return Ok(0.0);
                }
                Err(format!(
                    "{} line {}: approach {} is outside the run's {} branch ({start} to {end})",
                    curve.path.display(),
                    p.line,
                    p.approach,
                    if p.branch == Branch::Loading { "loading" } else { "unloading" },
                ))
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn folder(history: &str, summary: serde_json::Value) -> tempdir::Dir {
        let dir = tempdir::Dir::new();
        std::fs::write(dir.0.join("history.csv"), history).unwrap();
        std::fs::write(dir.0.join("summary.json"), summary.to_string()).unwrap();
        dir
    }

    mod tempdir {
        pub struct Dir(pub std::path::PathBuf);
        impl Dir {
            pub fn new() -> Self {
                use std::sync::atomic::{AtomicUsize, Ordering};
                static N: AtomicUsize = AtomicUsize::new(0);
                let p = std::env::temp_dir().join(format!(
                    "stiction-fit-targets-{}-{}",
                    std::process::id(),
                    N.fetch_add(1, Ordering::SeqCst)
                ));
                std::fs::create_dir_all(&p).unwrap();
                Self(p)
            }
        }
        impl Drop for Dir {
            fn drop(&mut self) {
                let _ = std::fs::remove_dir_all(&self.0);
            }
        }
    }

    /// A load-unload history f = 10 a on loading and 5 a - 1 on unloading (a: 0 -> 1 -> -0.5),
    /// which separated: the targets read exactly these lines between the increments, and zero
    /// past the unloading branch's end.
    #[test]
    fn curve_targets_interpolate_each_branch_and_are_zero_after_separation() {
        let mut history = String::from("approach,force,contact_area\n");
        for k in 0..=10 {
            let a = k as f64 / 10.0;
            history.push_str(&format!("{a},{},{}\n", 10.0 * a, a));
        }
        for k in 1..=15 {
            let a = 1.0 - k as f64 / 10.0;
            history.push_str(&format!("{a},{},{}\n", 5.0 * a - 1.0, 0.0));
        }
        let summary = serde_json::json!({"interfaces": [{"name": "flat", "kind": "rigid-flat", "separated": true,
                                          "pull_off_force": -3.5, "max_force": 10.0}], "plastic_dissipation": 2.0});
        let dir = folder(&history, summary);
        let outputs = RunOutputs::read(&dir.0).unwrap();
        let csv = dir.0.join("target.csv");
        std::fs::write(
            &csv,
            "# measured\napproach,force,branch\n0.25,0,loading\n0.75,0,unloading\n-0.45,0,unloading\n-2,0,unloading\n",
        )
        .unwrap();
        let (curve, _) = read_curve(&csv).unwrap();
        let v = outputs.curve_values(&curve, None).unwrap();
        let expected = [2.5, 2.75, -3.25, 0.0];
        for (got, want) in v.iter().zip(expected) {
            assert!((got - want).abs() < 1e-12, "{v:?}");
        }
        assert_eq!(outputs.summary_value("pull_off_force", None).unwrap(), -3.5);
        assert_eq!(outputs.summary_value("plastic_dissipation", None).unwrap(), 2.0);
        // a loading point past the largest approach is outside the run
        std::fs::write(&csv, "approach,force\n1.5,0\n").unwrap();
        let (curve, _) = read_curve(&csv).unwrap();
        let e = outputs.curve_values(&curve, None).unwrap_err();
        assert!(e.contains("line 2") && e.contains("outside the run's loading branch"), "{e}");
    }

    #[test]
    fn malformed_curve_files_name_their_line() {
        let dir = tempdir::Dir::new();
        let csv = dir.0.join("t.csv");
        let cases = [
            ("", "is empty"),
            ("approach,force\n", "no measured rows"),
            ("approach,force,contact_area\n1,2,3\n", "exactly one of"),
            ("distance,force\n1,2\n", "no `approach` column"),
            ("approach,force\n1,2\n2,x\n", "line 3"),
            ("approach,force,branch\n1,2,up\n", "branch 'up'"),
            ("approach,force,sigma\n1,2,0\n", "sigma 0 must be positive"),
            ("approach,force,colour\n1,2,3\n", "unknown column 'colour'"),
            ("approach,force\n1,2,3\n", "has 3 fields"),
        ];
        for (text, expected) in cases {
            std::fs::write(&csv, text).unwrap();
            let e = read_curve(&csv).unwrap_err().to_string();
            assert!(e.contains(expected) && e.contains("t.csv"), "{text:?}: {e}");
        }
    }
}
