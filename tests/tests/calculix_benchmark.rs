//! The CalculiX side-by-side benchmark, reduced to its first four increments (approach 0.5 nm
//! of 2.5): the plastic hemisphere on 8,663 table springs
//! (`benches/calculix-hemisphere/case.toml`, the same mesh as CalculiX's, from the same .geo)
//! against CalculiX 2.20's forces (`ccx_results_plastic.csv`, 7 printed digits). The spring law
//! is the `table-spring` plugin, built as a shared library and found through the case's
//! plugin path, as a user would. The run uses the default solver (quasi-Newton on a reused
//! single-precision factor) and full Newton.

use std::path::PathBuf;
use stiction_tests::{Tolerance, run_case, validate, workspace_root};

fn plugin_dir() -> PathBuf {
    let target = workspace_root().join("target").join("plugin-build-bench");
    let status = std::process::Command::new(env!("CARGO"))
        .args(["build", "--quiet", "-p", "stiction-plugin-table-spring", "--target-dir"])
        .arg(&target)
        .current_dir(workspace_root())
        .status()
        .expect("cargo runs");
    assert!(status.success(), "building the table-spring plugin failed");
    target.join("debug")
}

/// CalculiX's force at each approach (nN), from the shipped reference table.
fn calculix_forces() -> Vec<(f64, f64)> {
    let path = workspace_root().join("benches/calculix-hemisphere/ccx_results_plastic.csv");
    let text = std::fs::read_to_string(path).unwrap();
    text.lines()
        .skip(1)
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
            (v[0], v[1])
        })
        .collect()
}

#[test]
fn forces_match_calculix_over_the_first_four_increments() {
    let dir = plugin_dir().display().to_string();
    let reference = calculix_forces();
    for method in ["quasi-newton", "newton"] {
        let sets = [
            "steps.0.end_time=0.2".to_string(),
            format!("plugin_path=[\"{dir}\"]"),
            format!("solver.method=\"{method}\""),
        ];
        let sets: Vec<&str> = sets.iter().map(|s| s.as_str()).collect();
        let (built, summary) = run_case("benches/calculix-hemisphere/case.toml", &sets, &format!("ccx-bench-{method}"));
        assert_eq!(summary.increments, 4, "{method}");
        assert_eq!(built.model.n_free(), 99_945, "the mesh is CalculiX's: 99,945 equations");
        let history = std::fs::read_to_string(summary.output_directory.join("history.csv")).unwrap();
        let mut lines = history.lines();
        let header: Vec<&str> = lines.next().unwrap().split(',').collect();
        let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
        let (ia, i_f) = (col("approach"), col("force"));
        for (row, &(approach, force)) in lines.skip(1).zip(&reference[1..]) {
            let v: Vec<f64> = row.split(',').map(|x| x.parse().unwrap()).collect();
            assert!((v[ia] - approach).abs() < 1e-9, "{method}: approach {} vs {approach}", v[ia]);
            // CalculiX prints 7 digits (e.g. 415.351): half a unit of the last one, at least 1e-6
            let printed = 0.5 * 10f64.powi(force.abs().log10().floor() as i32 - 6);
            let tolerance = (1e-6 * force.abs()).max(printed);
            println!("{method}: approach {approach}: {} vs CalculiX {force} (tolerance {tolerance:.2e})", v[i_f]);
            validate(
                &format!("CalculiX hemisphere ({method}): force at approach {approach}"),
                "nN",
                v[i_f],
                force,
                "CalculiX 2.20 on the same mesh and law",
                Tolerance::Absolute(tolerance),
            );
        }
    }
}
