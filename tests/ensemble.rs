//! `stiction ensemble` as a user runs it: the shipped four-member quick ensemble, one test at a
//! time (each uses both cores). The aggregate is checked against statistics
//! computed here from the members' own summary.json files with Student's t from the published
//! table; a re-run resumes (only a removed member runs again, the aggregate is the same to the
//! last digit); a member that fails is excluded and reported; and, with the cargo feature
//! `mpi`, `mpirun -n 2` gives the serial run's ensemble.json byte for byte.

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn scratch(name: &str) -> PathBuf {
    let dir = root().join("target").join("test-out").join("ensemble").join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.parent().unwrap()).unwrap();
    dir
}

const CASE: &str = "cases/ru-rough-sphere/ensemble-quick.toml";

/// One ensemble at a time: each runs two members at once.
static ONE_AT_A_TIME: std::sync::Mutex<()> = std::sync::Mutex::new(());

fn one_at_a_time() -> std::sync::MutexGuard<'static, ()> {
    ONE_AT_A_TIME.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// The unloading cut short at approach 0.65 nm (t = 1.3), before the asperities' pull-offs:
/// these tests are of the ensemble's machinery, and the members' pull-off (small snaps under the
/// footprints' compliance) is what takes their time.
const SHORT_UNLOADING: &str = "steps.1.end_time=1.3";

/// The shipped ensemble with one thread per member and two members at once, unloading to
/// 0.65 nm ([`SHORT_UNLOADING`]).
fn ensemble_args(out: &Path, extra: &[&str]) -> Vec<String> {
    let mut args: Vec<String> = [
        "ensemble",
        CASE,
        "--quiet",
        "--threads-per-member",
        "1",
        "--concurrent-members",
        "2",
        "--set",
        SHORT_UNLOADING,
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    args.extend(["--out".into(), out.display().to_string()]);
    args.extend(extra.iter().map(|s| s.to_string()));
    args
}

fn run(program: &str, args: &[String]) -> (Option<i32>, String, String) {
    let out = Command::new(program).args(args).current_dir(root()).output().unwrap();
    (out.status.code(), String::from_utf8_lossy(&out.stdout).into(), String::from_utf8_lossy(&out.stderr).into())
}

fn stiction(args: &[String]) -> (Option<i32>, String, String) {
    run(env!("CARGO_BIN_EXE_stiction"), args)
}

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))).unwrap()
}

fn statistic<'a>(ensemble: &'a serde_json::Value, quantity: &str) -> &'a serde_json::Value {
    ensemble["statistics"].as_array().unwrap().iter().find(|s| s["quantity"] == quantity).unwrap()
}

/// Two-sided 95% Student t quantile for 3 degrees of freedom (NIST/SEMATECH e-Handbook of
/// Statistical Methods, table 1.3.6.7.2: 3.182).
const T_975_3: f64 = 3.182;

#[test]
fn aggregate_matches_the_members_and_a_rerun_resumes() {
    let _turn = one_at_a_time();
    let out = scratch("serial");
    let (code, stdout, stderr) = stiction(&ensemble_args(&out, &[]));
    assert_eq!(code, Some(0), "{stderr}");
    assert!(stdout.contains("4 of 4 members completed"), "{stdout}");
    // the cost of the members left, from the first one done, even when quiet
    assert!(stderr.contains("estimate from member-00") && stderr.contains("the 3 members left need about"), "{stderr}");
    let ensemble = json(&out.join("ensemble.json"));
    for quantity in ["max_force", "most_tensile_force", "max_contact_area", "work_of_flat"] {
        let values: Vec<f64> = (0..4)
            .map(|i| json(&out.join(format!("member-00{i}/summary.json")))["interfaces"][0][quantity].as_f64().unwrap())
            .collect();
        let mean = values.iter().sum::<f64>() / 4.0;
        let std = (values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / 3.0).sqrt();
        let s = statistic(&ensemble, &format!("asperities.{quantity}"));
        let close = |a: f64, b: f64, tol: f64| (a - b).abs() <= tol * b.abs().max(1e-300);
        assert!(close(s["mean"].as_f64().unwrap(), mean, 1e-12), "{quantity}: {s} vs mean {mean}");
        assert!(close(s["std"].as_f64().unwrap(), std, 1e-12), "{quantity}: {s} vs std {std}");
        // the table's 3 decimals: 3.182 vs 3.18245
        assert!(close(s["ci95_half_width"].as_f64().unwrap(), T_975_3 * std / 2.0, 2e-4), "{quantity}: {s}");
        assert_eq!(s["n"], 4);
    }
    // unloaded to 0.65 nm no member separated: no pull-off, so no statistic of it
    for i in 0..4 {
        let member = json(&out.join(format!("member-00{i}/summary.json")));
        assert!(member["interfaces"][0]["pull_off_force"].is_null(), "member {i} has a pull-off");
    }
    assert!(ensemble["statistics"].as_array().unwrap().iter().all(|s| s["quantity"] != "asperities.pull_off_force"));
    // the loading curve's last grid point is the largest approach every member reached (2.0),
    // where the mean force is the mean of the members' maximum forces
    let loading = ensemble["loading"].as_array().unwrap();
    let last = loading.last().unwrap();
    assert!((last["approach"].as_f64().unwrap() - 2.0).abs() < 1e-12, "{last}");
    let max_force = statistic(&ensemble, "asperities.max_force")["mean"].as_f64().unwrap();
    assert!((last["force"]["mean"].as_f64().unwrap() - max_force).abs() < 1e-9 * max_force, "{last}");
    for plot in ["ensemble_force.png", "ensemble_area.svg", "ensemble_convergence.png", "ensemble.csv"] {
        assert!(out.join(plot).is_file(), "{plot} missing");
    }

    // resume: a removed member runs again, the others are skipped, and the aggregate is the same
    let before = std::fs::read(out.join("ensemble.json")).unwrap();
    let modified =
        |i: usize| std::fs::metadata(out.join(format!("member-00{i}/summary.json"))).unwrap().modified().unwrap();
    let kept: Vec<_> = [0, 1, 3].iter().map(|&i| modified(i)).collect();
    std::fs::remove_dir_all(out.join("member-002")).unwrap();
    let (code, _, stderr) = stiction(&ensemble_args(&out, &[]));
    assert_eq!(code, Some(0), "{stderr}");
    assert_eq!(kept, [0, 1, 3].iter().map(|&i| modified(i)).collect::<Vec<_>>(), "completed members ran again");
    assert!(out.join("member-002/summary.json").is_file());
    assert!(std::fs::read(out.join("ensemble.json")).unwrap() == before, "the resumed aggregate differs");
}

/// Ctrl-C stops the running members with their checkpoints; running the command again goes on
/// with them from there (not from the start), and a resumed member ends where the same member
/// run alone in one go ends (its maximum and most tensile forces to 1e-6: the stop's point and the
/// solver's measured costs may move the path by round-off).
#[test]
fn a_stopped_ensemble_goes_on_with_its_members_from_their_checkpoints() {
    let _turn = one_at_a_time();
    let out = scratch("stopped");
    let mut child = Command::new(env!("CARGO_BIN_EXE_stiction"))
        .args(ensemble_args(&out, &[]))
        .current_dir(root())
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let rows = |member: &str| {
        std::fs::read_to_string(out.join(member).join("history.csv")).map_or(0, |t| t.lines().count().saturating_sub(1))
    };
    let start = std::time::Instant::now();
    while rows("member-000") < 10 {
        assert!(child.try_wait().unwrap().is_none(), "the ensemble ended before member 0 had 10 increments");
        assert!(start.elapsed().as_secs() < 300, "member 0 had no 10 increments within 300 s");
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
    assert!(Command::new("kill").args(["-INT", &child.id().to_string()]).status().unwrap().success());
    let stopped_run = child.wait_with_output().unwrap();
    assert_eq!(stopped_run.status.code(), Some(130), "{}", String::from_utf8_lossy(&stopped_run.stderr));
    let stopped: Vec<String> =
        (0..4).map(|i| format!("member-00{i}")).filter(|m| out.join(m).join("restart.bin").exists()).collect();
    assert!(stopped.contains(&"member-000".to_string()), "member 0 was stopped with a checkpoint");
    let rows_at_stop: Vec<usize> = stopped.iter().map(|m| rows(m)).collect();

    let (code, stdout, stderr) = stiction(&ensemble_args(&out, &[]));
    assert_eq!(code, Some(0), "{stderr}");
    assert!(stdout.contains("4 of 4 members completed"), "{stdout}");
    for (member, rows_then) in stopped.iter().zip(&rows_at_stop) {
        let log = std::fs::read_to_string(out.join(member).join("messages.log")).unwrap();
        assert!(log.contains("resumed from its checkpoint"), "{member} started over instead of going on");
        assert!(!out.join(member).join("restart.bin").exists(), "{member} completed and removed its checkpoint");
        assert!(rows(member) > *rows_then);
    }
    // member 0 alone, in one go, with the member's own values
    let outcome = json(&out.join("member-000/member.json"));
    let alone = scratch("stopped-member-alone");
    let mut args: Vec<String> = ["run", CASE, "--quiet", "--out"].iter().map(|s| s.to_string()).collect();
    args.push(alone.display().to_string());
    for set in outcome["sets"].as_array().unwrap() {
        args.extend(["--set".to_string(), set.as_str().unwrap().to_string()]);
    }
    args.extend([
        "--set".to_string(),
        "solver.threads=1".to_string(),
        "--set".to_string(),
        SHORT_UNLOADING.to_string(),
    ]);
    let (code, _, stderr) = stiction(&args);
    assert_eq!(code, Some(0), "{stderr}");
    let (resumed, one_go) = (json(&out.join("member-000/summary.json")), json(&alone.join("summary.json")));
    for quantity in ["max_force", "most_tensile_force"] {
        let (a, b) =
            (resumed["interfaces"][0][quantity].as_f64().unwrap(), one_go["interfaces"][0][quantity].as_f64().unwrap());
        assert!((a - b).abs() <= 1e-6 * b.abs(), "{quantity}: resumed {a}, in one go {b}");
    }
}

#[test]
fn a_failed_member_is_excluded_and_reported() {
    let _turn = one_at_a_time();
    let out = scratch("failed");
    // member 1 asks gmsh for a contact mesh size below the .geo's declared minimum
    let (code, stdout, stderr) = stiction(&ensemble_args(
        &out,
        &[
            "--set",
            "ensemble.members=3",
            "--set",
            "ensemble.vary.1={ key = \"mesh.parameters.h_contact\", values = [20.0, 0.1, 20.0] }",
        ],
    ));
    assert_eq!(code, Some(0), "{stderr}");
    assert!(stdout.contains("2 of 3 members completed"), "{stdout}");
    assert!(stderr.contains("member-001") && stderr.contains("h_contact"), "{stderr}");
    let ensemble = json(&out.join("ensemble.json"));
    let failed = &ensemble["outcomes"][1];
    assert_eq!(failed["status"], "failed");
    assert!(failed["error"].as_str().unwrap().contains("h_contact"), "{failed}");
    assert_eq!(statistic(&ensemble, "asperities.max_force")["n"], 2);
}

#[test]
fn bad_ensembles_are_input_errors() {
    let _turn = one_at_a_time();
    let out = scratch("bad");
    let (code, _, stderr) = stiction(&[
        "ensemble".into(),
        "cases/ru-rough-sphere/rough-w6-quick.toml".into(),
        "--out".into(),
        out.display().to_string(),
    ]);
    assert_eq!(code, Some(2));
    assert!(stderr.contains("rough-w6-quick.toml") && stderr.contains("'ensemble'"), "{stderr}");
    let (code, _, stderr) = stiction(&ensemble_args(&out, &["--set", "ensemble.vary.0.values=[1, 2]"]));
    assert_eq!(code, Some(2));
    assert!(stderr.contains("ensemble.vary[0]") && stderr.contains("exactly one of"), "{stderr}");
    // a varied value that makes a member's case invalid is refused before anything runs
    let (code, _, stderr) = stiction(&ensemble_args(
        &out,
        &[
            "--set",
            "ensemble.vary.1={ key = \"interfaces.0.points.density\", values = [0.0079, -1.0, 0.0079, 0.0079] }",
        ],
    ));
    assert_eq!(code, Some(2));
    assert!(stderr.contains("ensemble member 1") && stderr.contains("density"), "{stderr}");
    assert!(!out.join("member-000").exists(), "nothing may run before every member is valid");
    std::fs::create_dir_all(&out).unwrap();
    std::fs::write(out.join("notes.txt"), "mine").unwrap();
    let (code, _, stderr) = stiction(&ensemble_args(&out, &[]));
    assert_eq!(code, Some(2));
    assert!(stderr.contains("holds no earlier ensemble"), "{stderr}");
}

/// `mpirun -n 2` over the same members gives the serial run's ensemble.json to the last digit.
#[cfg(feature = "mpi")]
#[test]
fn mpi_ranks_give_the_serial_aggregate_to_the_last_digit() {
    let _turn = one_at_a_time();
    let serial = scratch("mpi-serial");
    let (code, _, stderr) = stiction(&ensemble_args(&serial, &[]));
    assert_eq!(code, Some(0), "{stderr}");
    let parallel = scratch("mpi-parallel");
    let mut args: Vec<String> =
        ["-n", "2", "--oversubscribe", env!("CARGO_BIN_EXE_stiction")].iter().map(|s| s.to_string()).collect();
    args.extend(ensemble_args(&parallel, &[]));
    let mut cmd = Command::new("mpirun");
    cmd.args(&args).current_dir(root()).env("OMPI_ALLOW_RUN_AS_ROOT", "1").env("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1");
    let output = cmd.output().expect("mpirun (OpenMPI) must be installed to test the mpi feature");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{stderr}");
    assert!(stderr.contains("2 MPI ranks"), "the members did not spread over the ranks: {stderr}");
    assert!(
        stderr.contains("estimate from member-00") && stderr.contains("members left need about"),
        "rank 0 gives no estimate of the members left: {stderr}"
    );
    let a = std::fs::read(serial.join("ensemble.json")).unwrap();
    let b = std::fs::read(parallel.join("ensemble.json")).unwrap();
    assert!(a == b, "ensemble.json differs between the serial and the MPI run");
}
