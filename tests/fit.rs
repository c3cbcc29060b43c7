//! `stiction fit` end to end on the tutorial sphere (a run takes about half a second): twin
//! experiments whose targets were computed with known parameters (cases/fit/), the resumption
//! of a finished and of an interrupted fit, a parameter the targets cannot see, and bad input.

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn scratch(name: &str) -> PathBuf {
    let dir = root().join("target").join("test-out").join("fit").join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.parent().unwrap()).unwrap();
    dir
}

fn stiction(args: &[&str]) -> Command {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_stiction"));
    cmd.args(args).current_dir(root());
    cmd
}

fn fit(file: &Path, out: &Path, extra: &[&str]) -> (Option<i32>, String, String) {
    let mut args = vec!["fit", file.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"];
    args.extend_from_slice(extra);
    let o = stiction(&args).output().unwrap();
    (o.status.code(), String::from_utf8_lossy(&o.stdout).into(), String::from_utf8_lossy(&o.stderr).into())
}

fn report(out: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(out.join("fit.json")).unwrap()).unwrap()
}

/// The fitted values, as the JSON numbers written (bit for bit).
fn values(report: &serde_json::Value) -> Vec<f64> {
    report["parameters"].as_array().unwrap().iter().map(|p| p["value"].as_f64().unwrap()).collect()
}

/// Targets computed with w = 1 J/m^2 and E = 410 GPa; the fit starts 30% away from both
/// (w = 1.3, E = 287) and must return them within 1%. Resumed on its finished folder, the fit
/// replays from the runs there: no new run, the same values bit for bit.
#[test]
fn a_twin_fit_recovers_the_true_parameters_within_one_percent_and_resumes_without_running() {
    let out = scratch("twin");
    let file = root().join("cases/fit/twin-tutorial.toml");
    let (code, stdout, stderr) = fit(&file, &out, &[]);
    assert_eq!(code, Some(0), "{stdout}{stderr}");
    let r = report(&out);
    assert_eq!(r["status"], "converged", "{r}");
    for p in r["parameters"].as_array().unwrap() {
        let (value, truth) = (p["value"].as_f64().unwrap(), p["true_value"].as_f64().unwrap());
        assert!((value / truth - 1.0).abs() < 0.01, "{}: {value} against {truth}", p["key"]);
    }
    assert!(r["cost"].as_f64().unwrap() < 1e-3 * r["cost_at_start"].as_f64().unwrap(), "{r}");
    for file in ["fit_history.csv", "fit_0.png", "fit_0.svg", "fitted-sphere.toml"] {
        assert!(out.join(file).is_file(), "{file} missing");
    }
    // the fitted case runs as it is: `stiction check` reads it, mesh and all
    let check = stiction(&["check", out.join("fitted-sphere.toml").to_str().unwrap()]).output().unwrap();
    assert_eq!(check.status.code(), Some(0), "{}", String::from_utf8_lossy(&check.stderr));

    let (code, stdout, stderr) = fit(&file, &out, &["--resume"]);
    assert_eq!(code, Some(0), "{stdout}{stderr}");
    let again = report(&out);
    assert_eq!(again["runs"], 0, "a finished fit resumed runs nothing: {again}");
    assert_eq!(again["runs_reused"], r["runs"]);
    assert_eq!(values(&again), values(&r));
}

/// The same twin with Gaussian noise of 1% on every target and the sigmas stated: the 95%
/// intervals are absolute and hold the true values.
#[test]
fn a_noisy_twin_fit_brackets_the_true_values_in_its_intervals() {
    let out = scratch("noisy");
    let (code, stdout, stderr) = fit(&root().join("cases/fit/twin-tutorial-noisy.toml"), &out, &[]);
    assert_eq!(code, Some(0), "{stdout}{stderr}");
    let r = report(&out);
    assert_eq!(r["uncertainty"]["sigma"], "absolute");
    for p in r["parameters"].as_array().unwrap() {
        let [lo, hi] = [0, 1].map(|k| p["interval_95"][k].as_f64().unwrap());
        let truth = p["true_value"].as_f64().unwrap();
        assert!(lo < truth && truth < hi, "{}: {truth} outside [{lo}, {hi}]", p["key"]);
        // and the interval is informative: narrower than 5% of the value
        assert!(hi - lo < 0.05 * truth, "{}: [{lo}, {hi}]", p["key"]);
    }
    // chi-square per degree of freedom near 1 (22 degrees of freedom: 0.3 to 2 holds 99.8%)
    let chi2 = r["cost"].as_f64().unwrap() / r["uncertainty"]["degrees_of_freedom"].as_f64().unwrap();
    assert!((0.3..2.0).contains(&chi2), "{chi2}");
}

fn history_lines(out: &Path) -> usize {
    std::fs::read_to_string(out.join("fit_history.csv")).map_or(0, |t| t.lines().count())
}

fn wait_for(child: &mut Child, out: &Path, lines: usize) {
    for _ in 0..1200 {
        if history_lines(out) >= lines || child.try_wait().unwrap().is_some() {
            return;
        }
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
}

/// Ctrl-C in the middle of a fit: exit 130 with the runs kept; `--resume` then ends with the
/// values of a fit that ran through, bit for bit, reusing the runs made before the stop.
#[test]
fn an_interrupted_fit_resumes_to_the_values_of_one_that_ran_through() {
    let file = root().join("cases/fit/twin-tutorial.toml");
    let whole = scratch("whole");
    let (code, stdout, stderr) = fit(&file, &whole, &[]);
    assert_eq!(code, Some(0), "{stdout}{stderr}");

    let out = scratch("interrupted");
    let mut child = stiction(&["fit", file.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    wait_for(&mut child, &out, 8);
    let status = Command::new("kill").args(["-INT", &child.id().to_string()]).status().unwrap();
    assert!(status.success());
    let o = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(130), "{stderr}");
    assert!(stderr.contains("--resume"), "{stderr}");
    assert!(!out.join("fit.json").exists());

    let (code, stdout, stderr) = fit(&file, &out, &["--resume"]);
    assert_eq!(code, Some(0), "{stdout}{stderr}");
    let r = report(&out);
    assert!(r["runs_reused"].as_u64().unwrap() >= 3, "{r}");
    assert_eq!(values(&r), values(&report(&whole)));
}

/// A parameter the targets do not depend on (how often a run writes its checkpoint) is named
/// as undetermined, with no interval, while the other one is fitted.
#[test]
fn a_parameter_the_targets_cannot_see_is_named() {
    let dir = scratch("blind");
    std::fs::create_dir_all(&dir).unwrap();
    let text = std::fs::read_to_string(root().join("cases/fit/twin-tutorial.toml")).unwrap();
    let text = text
        .replace("../../docs/tutorial/sphere.toml", root().join("docs/tutorial/sphere.toml").to_str().unwrap())
        .replace("targets/", &format!("{}/", root().join("cases/fit/targets").display()))
        .replace("materials.ru.youngs_modulus\"", "output.checkpoint_minutes\"")
        .replace("start = 287.0", "start = 30.0")
        .replace("bounds = [50.0, 2000.0]", "bounds = [1.0, 100.0]")
        .replace("true_value = 410.0", "");
    let file = dir.join("blind.toml");
    std::fs::write(&file, text).unwrap();
    let out = dir.join("out");
    let (code, stdout, stderr) = fit(&file, &out, &[]);
    assert_eq!(code, Some(0), "{stdout}{stderr}");
    let r = report(&out);
    let undetermined = r["uncertainty"]["undetermined"].as_array().unwrap();
    assert_eq!(undetermined.len(), 1, "{r}");
    assert!(undetermined[0].as_str().unwrap().starts_with("output.checkpoint_minutes"), "{r}");
    assert!(r["parameters"][1]["interval_95"].is_null() && !r["parameters"][0]["interval_95"].is_null());
    assert!(stdout.contains("warning: output.checkpoint_minutes"), "{stdout}");
}

/// Bad fit files and target files: exit 2, naming the key or the file's line, before any run.
#[test]
fn bad_fit_input_exits_2_naming_the_key_or_line() {
    let dir = scratch("bad");
    std::fs::create_dir_all(&dir).unwrap();
    let case = root().join("docs/tutorial/sphere.toml");
    let good_curve = root().join("cases/fit/targets/tutorial-sphere-force.csv");
    let write = |name: &str, text: &str| {
        let p = dir.join(name);
        std::fs::write(&p, text).unwrap();
        p
    };
    let fit_file = |parameter: &str, target: &str| {
        format!(
            "[[cases]]\nname = \"s\"\nfile = \"{}\"\n\n[[parameters]]\n{parameter}\n\n[[targets]]\ncase = \"s\"\n{target}\n",
            case.display()
        )
    };
    let w = "key = \"interfaces.0.parameters.w\"\nstart = 1.3\nbounds = [0.2, 5.0]";
    let curve = |p: &Path| format!("curve = \"{}\"", p.display());
    let empty = write("empty.csv", "");
    let malformed = write("malformed.csv", "approach,force\n0.1,-200\n0.2,minus three\n");
    let beyond = write("beyond.csv", "approach,force\n0.5,100\n5.0,200\n");
    let cases: Vec<(String, &str)> = vec![
        (fit_file(w, &curve(&good_curve)) + "colour = 1\n", "colour"),
        (
            fit_file("key = \"interfaces.0.parameters.w\"\nstart = 1.3\nbounds = [5.0, 0.2]", &curve(&good_curve)),
            "parameters.0.bounds",
        ),
        (
            fit_file("key = \"interfaces.0.parameters.w\"\nstart = 7.0\nbounds = [0.2, 5.0]", &curve(&good_curve)),
            "parameters.0.start",
        ),
        (
            fit_file(
                "key = \"interfaces.0.parameters.w\"\nstart = 1.3\nbounds = [-1.0, 5.0]\nlog = true",
                &curve(&good_curve),
            ),
            "positive lower bound",
        ),
        (fit_file(w, &curve(&empty)), "is empty"),
        (fit_file(w, &curve(&malformed)), "line 3"),
        (fit_file(w, "summary = \"pull_of_force\"\nvalue = -1100.0"), "targets.0.summary"),
        (fit_file(w, "summary = \"pull_off_force\""), "targets.0.value"),
        (fit_file(w, &(curve(&good_curve) + "\nsigma = -1")), "targets.0.sigma"),
        (
            fit_file(w, "case = \"t\"\nsummary = \"max_force\"\nvalue = 1.0").replacen("case = \"s\"\n", "", 1),
            "targets.0.case",
        ),
        (
            fit_file(
                "key = \"materials.ru.youngs_modulos\"\nstart = 300.0\nbounds = [50.0, 2000.0]",
                &curve(&good_curve),
            ),
            "key 'parameters.0.key'",
        ),
        (fit_file(w, &curve(&beyond)), "outside the run's loading branch"),
    ];
    // --resume on a folder that holds no fit, or a fit of something else
    let good = write("good.toml", &fit_file(w, &curve(&good_curve)));
    let (code, _, stderr) = fit(&good, &dir.join("no-such-fit"), &["--resume"]);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("holds no fit to resume"), "{stderr}");
    let other = dir.join("other-fit");
    std::fs::create_dir_all(&other).unwrap();
    std::fs::write(other.join("fit-plan.json"), r#"{"fingerprint": "0123", "fit_file": "x.toml"}"#).unwrap();
    let (code, _, stderr) = fit(&good, &other, &["--resume"]);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("holds a fit of another fit file"), "{stderr}");
    for (k, (text, expected)) in cases.iter().enumerate() {
        let file = write(&format!("bad-{k}.toml"), text);
        let (code, stdout, stderr) = fit(&file, &dir.join(format!("out-{k}")), &[]);
        assert_eq!(code, Some(2), "case {k} ({expected}): {stdout}{stderr}");
        assert!(
            stderr.contains(expected) && !stderr.contains("panicked"),
            "case {k}: expected '{expected}' in: {stderr}"
        );
    }
}

/// A Jacobian step that leaves the material's valid range (Poisson's ratio 0.49 + 3% > 0.5):
/// its run fails, fit_history.csv records it with the parameter value and the reason, the step
/// is taken from the other side, and the fit goes on to the end.
#[test]
fn a_run_that_fails_during_the_fit_is_recorded_and_stepped_around() {
    let dir = scratch("failing-step");
    std::fs::create_dir_all(&dir).unwrap();
    let text = format!(
        "[[cases]]\nname = \"sphere\"\nfile = \"{}\"\n\n[[parameters]]\nkey = \"materials.ru.poissons_ratio\"\n\
         start = 0.49\nbounds = [0.05, 0.6]\n\n[[targets]]\ncase = \"sphere\"\ncurve = \"{}\"\n\n[optimizer]\nmax_evaluations = 4\n",
        root().join("docs/tutorial/sphere.toml").display(),
        root().join("cases/fit/targets/tutorial-sphere-force.csv").display()
    );
    let file = dir.join("nu.toml");
    std::fs::write(&file, text).unwrap();
    let out = dir.join("out");
    let (code, stdout, stderr) = fit(&file, &out, &[]);
    assert_eq!(code, Some(0), "{stdout}{stderr}");
    let history = std::fs::read_to_string(out.join("fit_history.csv")).unwrap();
    let failed: Vec<&str> = history.lines().filter(|l| l.contains(",failed,")).collect();
    assert_eq!(failed.len(), 1, "{history}");
    assert!(failed[0].contains("poissons_ratio=5.047e-1") && failed[0].contains("(-1, 0.5)"), "{}", failed[0]);
    // the fit moved on from the start, towards the 0.3 the targets were made with
    let nu = report(&out)["parameters"][0]["value"].as_f64().unwrap();
    assert!(nu < 0.4, "{nu}");
}

/// `mpirun -n 2 stiction fit` spreads the runs over the ranks and ends with the values of the
/// fit on one machine, bit for bit (each run with one thread in both).
#[cfg(feature = "mpi")]
#[test]
fn mpi_ranks_give_the_fit_of_one_machine_to_the_last_digit() {
    let file = root().join("cases/fit/twin-tutorial.toml");
    let serial = scratch("mpi-serial");
    let (code, stdout, stderr) = fit(&file, &serial, &[]);
    assert_eq!(code, Some(0), "{stdout}{stderr}");
    let parallel = scratch("mpi-parallel");
    let output = Command::new("mpirun")
        .args(["-n", "2", "--oversubscribe", env!("CARGO_BIN_EXE_stiction"), "fit", file.to_str().unwrap(), "--out"])
        .arg(&parallel)
        .current_dir(root())
        .env("OMPI_ALLOW_RUN_AS_ROOT", "1")
        .env("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
        .output()
        .expect("mpirun (OpenMPI) must be installed to test the mpi feature");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{stderr}");
    assert!(stderr.contains("fit over 2 MPI ranks, 1 thread per run"), "{stderr}");
    let (a, b) = (report(&serial), report(&parallel));
    assert_eq!(values(&a), values(&b));
    assert_eq!(a["runs"], b["runs"]);
}
