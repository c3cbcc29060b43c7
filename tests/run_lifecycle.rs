//! The life of a run as the `stiction` program lives it: Ctrl-C (SIGINT) stops after the
//! increment in progress with status "interrupted" and exit 130; SIGKILL leaves consistent
//! files; an earlier run is never overwritten without `--overwrite`; a plugin that panics is
//! reported once per distinct failure with a count; two plugins declaring one law name are
//! refused.

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn scratch(name: &str) -> PathBuf {
    let dir = root().join("target").join("test-out").join("lifecycle").join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.parent().unwrap()).unwrap();
    dir
}

fn stiction(args: &[&str]) -> Command {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_stiction"));
    cmd.args(args).current_dir(root());
    cmd
}

/// Exit status and stderr of a finished command.
fn outcome(cmd: &mut Command) -> (Option<i32>, String) {
    let out = cmd.output().unwrap();
    (out.status.code(), String::from_utf8_lossy(&out.stderr).to_string())
}

/// Data rows in `out/history.csv` (0 while it does not exist).
fn history_rows(out: &Path) -> usize {
    std::fs::read_to_string(out.join("history.csv")).map_or(0, |t| t.lines().count().saturating_sub(1))
}

/// Starts the quick rough-sphere case into `out` (with `extra` arguments) and waits until it
/// has committed `rows` increments.
fn start_quick_case(out: &Path, rows: usize, extra: &[&str]) -> Child {
    let mut child = stiction(&["run", "cases/ru-rough-sphere/rough-w6-quick.toml", "--quiet", "--out"])
        .arg(out)
        .args(extra)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    while history_rows(out) < rows {
        assert!(child.try_wait().unwrap().is_none(), "the run ended before {rows} increments");
        assert!(start.elapsed() < Duration::from_secs(300), "no {rows} increments within 300 s");
        std::thread::sleep(Duration::from_millis(50));
    }
    child
}

fn signal(child: &Child, name: &str) {
    let status = Command::new("kill").args([format!("-{name}"), child.id().to_string()]).status().unwrap();
    assert!(status.success());
}

/// Every file a stopped run left is whole: each history row has the header's columns of
/// numbers, every frame a `.pvd` lists exists and reads as VTK, and no temporary file is left
/// in place of a final one. Returns the history's rows and the last row's time.
fn check_files_whole(out: &Path) -> (usize, f64) {
    let text = std::fs::read_to_string(out.join("history.csv")).unwrap();
    let mut lines = text.lines();
    let columns = lines.next().unwrap().split(',').count();
    let mut last_time = f64::NAN;
    let mut rows = 0;
    for line in lines {
        let values: Vec<f64> = line.split(',').map(|v| v.parse().unwrap()).collect();
        assert_eq!(values.len(), columns, "a partial history row: {line}");
        last_time = values[2];
        rows += 1;
    }
    assert!(text.ends_with('\n'), "history.csv ends inside a row");
    let mut frames = 0;
    for entry in std::fs::read_dir(out).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "pvd") {
            let pvd = std::fs::read_to_string(&path).unwrap();
            assert!(pvd.trim_end().ends_with("</VTKFile>"), "{} is cut short", path.display());
            for file in pvd.split("file=\"").skip(1).map(|s| &s[..s.find('"').unwrap()]) {
                vtkio::Vtk::import(out.join(file)).unwrap_or_else(|e| panic!("{file} does not read: {e}"));
                frames += 1;
            }
        }
    }
    assert!(frames > rows, "the .pvd files list {frames} frames for {rows} increments");
    (rows, last_time)
}

fn summary(out: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap()
}

/// Whether a gmsh process given `-clscale <scale>` is running (by its command line).
fn gmsh_running_with(scale: &str) -> bool {
    std::fs::read_dir("/proc").unwrap().flatten().any(|p| {
        std::fs::read(p.path().join("cmdline")).is_ok_and(|c| {
            let args: Vec<&[u8]> = c.split(|&b| b == 0).collect();
            args.first().is_some_and(|a| a.ends_with(b"gmsh"))
                && args.windows(2).any(|w| w == [b"-clscale", scale.as_bytes()])
        })
    })
}

/// Starts `stiction ARGS --set mesh.size_factor=SCALE` (a size factor no other test uses, so
/// that its gmsh is known by its command line), sends SIGTERM once gmsh runs, and returns the
/// exit status and standard error; gmsh must have stopped with it.
fn sigterm_while_gmsh_runs(args: &[&str], scale: &str) -> (Option<i32>, String) {
    let mut child = stiction(args)
        .args(["--set", &format!("mesh.size_factor={scale}")])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    while !gmsh_running_with(scale) {
        assert!(child.try_wait().unwrap().is_none(), "stiction ended before gmsh started");
        assert!(start.elapsed() < Duration::from_secs(60), "gmsh did not start within 60 s");
        std::thread::sleep(Duration::from_millis(50));
    }
    std::thread::sleep(Duration::from_millis(500));
    signal(&child, "TERM");
    let result = child.wait_with_output().unwrap();
    assert!(!gmsh_running_with(scale), "gmsh outlived stiction");
    (result.status.code(), String::from_utf8_lossy(&result.stderr).to_string())
}

/// SIGTERM (a batch system's stop) while gmsh meshes: gmsh is stopped with the run, nothing is
/// cached, no output folder is made, and the exit status is 130.
#[test]
fn sigterm_while_meshing_stops_gmsh_too() {
    let out = scratch("sigterm-meshing");
    let out_arg = out.display().to_string();
    let args = ["run", "cases/ru-sphere/smooth-lj-w1.toml", "--quiet", "--out", out_arg.as_str()];
    let (code, stderr) = sigterm_while_gmsh_runs(&args, "0.0301");
    assert_eq!(code, Some(130), "{stderr}");
    assert!(stderr.contains("interrupted after") && stderr.contains("gmsh was stopped"), "{stderr}");
    assert!(!out.exists(), "an interrupted meshing made the output folder");
}

/// `stiction check` meshes too: a SIGTERM then stops gmsh with it, exit 130.
#[test]
fn sigterm_while_a_check_meshes_stops_gmsh_too() {
    let (code, stderr) = sigterm_while_gmsh_runs(&["check", "cases/ru-sphere/smooth-lj-w1.toml"], "0.0302");
    assert_eq!(code, Some(130), "{stderr}");
    assert!(stderr.contains("stopping the check") && stderr.contains("gmsh was stopped"), "{stderr}");
}

#[test]
fn ctrl_c_finishes_the_increment_writes_an_interrupted_summary_and_exits_130() {
    let out = scratch("sigint");
    let child = start_quick_case(&out, 8, &[]);
    signal(&child, "INT");
    let result = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert_eq!(result.status.code(), Some(130), "{stderr}");
    assert!(stderr.contains("interrupted at t = ") && !stderr.contains("panicked"), "{stderr}");
    let (rows, last_time) = check_files_whole(&out);
    let s = summary(&out);
    assert_eq!(s["status"], "interrupted", "{s}");
    assert_eq!(s["increments"].as_u64().unwrap() as usize + 1, rows, "summary and history disagree");
    assert!((s["final_time"].as_f64().unwrap() - last_time).abs() < 1e-9, "{s}");
    assert!(last_time > 0.0 && last_time < 2.0, "t = {last_time}");
    println!("SIGINT after {rows} history rows: stopped at t = {last_time}, exit 130");
}

#[test]
fn sigkill_leaves_whole_files_and_a_summary_that_says_the_run_did_not_end() {
    let out = scratch("sigkill");
    let mut child = start_quick_case(&out, 12, &[]);
    signal(&child, "KILL");
    let status = child.wait().unwrap();
    assert_eq!(status.code(), None, "killed by a signal");
    let (rows, _) = check_files_whole(&out);
    let s = summary(&out);
    assert_eq!(s["status"], "running", "{s}");
    assert!(s["message"].as_str().unwrap().contains("has not ended (or was killed)"), "{s}");
    println!("SIGKILL after {rows} history rows: files whole");
}

/// A run killed at an arbitrary moment goes on with `--resume` from its last checkpoint (here
/// written at every commit), cutting back what it wrote after it, and ends with the history of
/// the same run done in one go, byte for byte (the solver's decisions are fixed-cost ones).
#[test]
fn a_killed_run_resumes_from_its_last_checkpoint_and_ends_as_one_that_ran_through() {
    // unloaded to 0.65 nm, before the pull-offs (the restart through a whole cycle with its
    // snaps is tests/tests/restart.rs)
    let settings = [
        "--set",
        "steps.1.end_time=1.3",
        "--set",
        "output.checkpoint_minutes=0",
        "--set",
        "solver.refactorization_cost_ratio=20",
        "--set",
        "solver.threads=1",
    ];
    let out = scratch("killed-and-resumed");
    let mut child = start_quick_case(&out, 15, &settings);
    signal(&child, "KILL");
    child.wait().unwrap();
    let (killed_rows, _) = check_files_whole(&out);
    // what a kill during an atomic write leaves behind: removed on resume, a user's file kept
    std::fs::write(out.join("rough-w6-quick_00099.vtu.tmp"), "half a frame").unwrap();
    let case = "cases/ru-rough-sphere/rough-w6-quick.toml";
    let resume: Vec<&str> =
        ["run", case, "--quiet", "--resume", "--out", out.to_str().unwrap()].into_iter().chain(settings).collect();
    let (code, stderr) = outcome(&mut stiction(&resume));
    assert_eq!(code, Some(0), "{stderr}");
    let straight = scratch("killed-and-resumed-straight");
    let once: Vec<&str> =
        ["run", case, "--quiet", "--out", straight.to_str().unwrap()].into_iter().chain(settings).collect();
    let (code, stderr) = outcome(&mut stiction(&once));
    assert_eq!(code, Some(0), "{stderr}");
    for file in ["history.csv", "events.csv", "rough-w6-quick.pvd"] {
        let (a, b) = (std::fs::read(straight.join(file)).unwrap(), std::fs::read(out.join(file)).unwrap());
        assert!(a == b, "{file} of the killed and resumed run differs from the straight run's");
    }
    assert_eq!(summary(&out)["increments"], summary(&straight)["increments"]);
    assert!(!out.join("restart.bin").exists(), "the completed run removed its checkpoint");
    assert!(!out.join("rough-w6-quick_00099.vtu.tmp").exists(), "a temporary file of the killed run was left");
    println!("SIGKILL after {killed_rows} history rows, resumed: the same history as one run");
}

#[test]
fn an_earlier_run_is_replaced_only_with_overwrite() {
    let out = scratch("overwrite");
    let out_arg = out.to_str().unwrap();
    let case = "cases/validation/lame-sphere-axisym.toml";
    let (code, stderr) = outcome(&mut stiction(&["run", case, "--quiet", "--out", out_arg]));
    assert_eq!(code, Some(0), "{stderr}");
    std::fs::write(out.join("stale.vtu"), "from an older run").unwrap();
    let (code, stderr) = outcome(&mut stiction(&["run", case, "--quiet", "--out", out_arg]));
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("holds an earlier run; give --overwrite"), "{stderr}");
    assert!(out.join("stale.vtu").exists() && summary(&out)["status"] == "completed");
    let (code, stderr) = outcome(&mut stiction(&["run", case, "--quiet", "--overwrite", "--out", out_arg]));
    assert_eq!(code, Some(0), "{stderr}");
    assert!(!out.join("stale.vtu").exists(), "files of the earlier run must go");
    // a folder of other files is never emptied, even with --overwrite
    let foreign = scratch("foreign");
    std::fs::create_dir_all(&foreign).unwrap();
    std::fs::write(foreign.join("notes.txt"), "mine").unwrap();
    let (code, stderr) =
        outcome(&mut stiction(&["run", case, "--quiet", "--overwrite", "--out", foreign.to_str().unwrap()]));
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("holds no earlier run") && foreign.join("notes.txt").exists(), "{stderr}");
    // nor is a user's file that happens to have a run's name
    let named = scratch("named-like-a-run");
    std::fs::create_dir_all(&named).unwrap();
    std::fs::write(named.join("history.csv"), "time,force\n0,1\n").unwrap();
    let (code, stderr) =
        outcome(&mut stiction(&["run", case, "--quiet", "--overwrite", "--out", named.to_str().unwrap()]));
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("holds no earlier run") && named.join("history.csv").exists(), "{stderr}");
    // an earlier run beside the user's own files: --overwrite refuses, naming them, and removes nothing
    std::fs::write(out.join("notes.txt"), "mine").unwrap();
    std::fs::create_dir_all(out.join("data")).unwrap();
    std::fs::write(out.join("data").join("measured.csv"), "mine").unwrap();
    let (code, stderr) = outcome(&mut stiction(&["run", case, "--quiet", "--overwrite", "--out", out_arg]));
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("notes.txt") && stderr.contains("data/measured.csv"), "{stderr}");
    assert!(out.join("notes.txt").exists() && out.join("data/measured.csv").exists());
    assert!(out.join("history.csv").exists() && summary(&out)["status"] == "completed", "the earlier run is kept");
}

/// A second run into a folder a running Stiction writes is refused with the holder named, with
/// or without --overwrite, and the first run completes with its files; once it has ended the
/// folder is free again.
#[test]
fn a_folder_in_use_is_refused_to_a_second_run() {
    let out = scratch("in-use");
    let first = start_quick_case(&out, 3, &["--set", "steps.1.end_time=1.3"]);
    let other = "cases/validation/lame-sphere-axisym.toml";
    for extra in [&[][..], &["--overwrite"][..]] {
        let mut args = vec!["run", other, "--quiet", "--out", out.to_str().unwrap()];
        args.extend_from_slice(extra);
        let (code, stderr) = outcome(&mut stiction(&args));
        assert_eq!(code, Some(2), "{stderr}");
        assert!(stderr.contains(&format!("in use by a running Stiction (process {}", first.id())), "{stderr}");
    }
    let done = first.wait_with_output().unwrap();
    assert_eq!(done.status.code(), Some(0), "{}", String::from_utf8_lossy(&done.stderr));
    assert_eq!(summary(&out)["status"], "completed");
    assert!(out.join("history.csv").exists() && out.join("rough-w6-quick.pvd").exists());
    assert!(!out.join(".stiction-lock").exists(), "the lock goes with the run");
}

/// Builds a copy of the template law that panics whenever the surfaces overlap, and returns
/// the library's path.
fn panicking_plugin() -> PathBuf {
    let dir = root().join("target").join("test-out").join("lifecycle-plugin");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("src")).unwrap();
    let template = root().join("plugins").join("template");
    let manifest = std::fs::read_to_string(template.join("Cargo.toml"))
        .unwrap()
        .replace("name = \"my-stiction-law\"", "name = \"panicking-law\"")
        .replace("path = \"../sdk\"", &format!("path = \"{}\"", root().join("plugins/sdk").display()));
    std::fs::write(dir.join("Cargo.toml"), manifest).unwrap();
    let source = std::fs::read_to_string(template.join("src/lib.rs"))
        .unwrap()
        .replace("c\"exponential-adhesion\"", "c\"panicking-adhesion\"")
        .replace(
            "        // Cap the exponential",
            "        if gap < 0.0 {\n            panic!(\"the surfaces overlap\");\n        }\n        // Cap the exponential",
        );
    std::fs::write(dir.join("src/lib.rs"), source).unwrap();
    let build = root().join("target").join("plugin-build");
    let out = Command::new(option_env!("CARGO").unwrap_or("cargo"))
        .args(["build", "--quiet", "--manifest-path"])
        .arg(dir.join("Cargo.toml"))
        .arg("--target-dir")
        .arg(&build)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    build.join("debug").join("libpanicking_law.so")
}

#[test]
fn a_panicking_plugin_is_reported_once_with_a_count_and_duplicate_law_names_are_refused() {
    let library = panicking_plugin();
    let plugins = scratch("plugins");
    std::fs::create_dir_all(&plugins).unwrap();
    std::fs::copy(&library, plugins.join("libpanicking_law.so")).unwrap();
    let out = scratch("panicking");
    let plugin_path = format!("plugin_path=[\"{}\"]", plugins.display());
    let args = [
        "run",
        "cases/validation/hertz-axisym.toml",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
        "--set",
        &plugin_path,
        "--set",
        "interfaces.0.law=\"panicking-adhesion\"",
        "--set",
        "interfaces.0.parameters={ w = 0.5 }",
        "--set",
        "mesh.parameters.h_contact=8.0",
    ];
    let (code, stderr) = outcome(&mut stiction(&args));
    assert_eq!(code, Some(1), "{stderr}");
    assert!(!stderr.contains("panicked at"), "the plugin panics must not reach stderr:\n{stderr}");
    let reports = stderr.matches("panic in evaluate: the surfaces overlap (at src/lib.rs:").count();
    let counted = stderr.lines().find(|l| l.contains("law 'panicking-adhesion' on interface 'flat' failed"));
    let times: usize = counted
        .and_then(|l| l.split(" failed ").nth(1))
        .and_then(|rest| rest.split(' ').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("no counted report:\n{stderr}"));
    assert!(times >= 2 && reports <= 2, "{times} failures, reported {reports} times:\n{stderr}");
    assert_eq!(summary(&out)["status"], "failed");
    // a second library declaring the same law name in the same folder
    std::fs::copy(&library, plugins.join("libpanicking_law_copy.so")).unwrap();
    let (code, stderr) =
        outcome(&mut stiction(&[&["check", "cases/validation/hertz-axisym.toml"], &args[5..]].concat()));
    assert_eq!(code, Some(2), "{stderr}");
    assert!(
        stderr.contains("2 libraries declare the law 'panicking-adhesion'")
            && stderr.contains("libpanicking_law.so")
            && stderr.contains("libpanicking_law_copy.so"),
        "{stderr}"
    );
}

/// A checkpoint with a few changed bytes in its numbers (the displacements of the record) is
/// refused with exit 2 and the file named, and the stopped run's files are left as they were:
/// never resumed with other numbers.
#[test]
fn a_corrupted_checkpoint_is_refused_and_the_run_left_as_it_was() {
    let out = scratch("corrupted-checkpoint");
    let case = "cases/validation/hertz-axisym.toml";
    let dir = out.to_str().unwrap();
    let (code, err) = outcome(&mut stiction(&["run", case, "--out", dir, "--quiet", "--stop-after", "3"]));
    assert_eq!(code, Some(130), "{err}");
    let checkpoint = out.join("restart.bin");
    let mut bytes = std::fs::read(&checkpoint).unwrap();
    let history = std::fs::read_to_string(out.join("history.csv")).unwrap();
    // the record follows the magic line, the version and the checksum; change 8 bytes in its middle
    let middle = bytes.len() / 2;
    for b in &mut bytes[middle..middle + 8] {
        *b ^= 0x5a;
    }
    std::fs::write(&checkpoint, &bytes).unwrap();
    let (code, err) = outcome(&mut stiction(&["run", case, "--out", dir, "--quiet", "--resume"]));
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("restart.bin") && err.contains("is corrupted"), "{err}");
    assert_eq!(std::fs::read_to_string(out.join("history.csv")).unwrap(), history, "history.csv untouched");
    assert_eq!(std::fs::read(&checkpoint).unwrap(), bytes, "the checkpoint is kept for inspection");
}

/// A failure found after the run started (an inverted element, met at the first assembly):
/// exit 2 with the element named, and `summary.json` says "failed" with the same reason,
/// never "running".
#[test]
fn a_failure_after_the_start_leaves_a_failed_summary_with_the_reason() {
    let out = scratch("inverted-element");
    let input = scratch("inverted-element-input");
    std::fs::create_dir_all(&input).unwrap();
    std::fs::write(input.join("inverted.msh"), INVERTED_MESH).unwrap();
    std::fs::write(input.join("case.toml"), INVERTED_CASE).unwrap();
    let case = input.join("case.toml");
    let (code, stderr) =
        outcome(&mut stiction(&["run", case.to_str().unwrap(), "--quiet", "--out", out.to_str().unwrap()]));
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("element 1 of set 'body' is inverted or degenerate"), "{stderr}");
    let s = summary(&out);
    assert_eq!(s["status"], "failed");
    assert!(s["message"].as_str().unwrap().contains("inverted or degenerate"), "{s}");
}

/// Two triangles in the r-z plane, the second numbered clockwise (inverted).
const INVERTED_MESH: &str = "$MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
2
1 1 \"base\"
2 2 \"body\"
$EndPhysicalNames
$Entities
0 1 1 0
1 0 0 0 1 0 0 1 1 0
1 0 0 0 1 1 0 1 2 0
$EndEntities
$Nodes
2 4 1 4
1 1 0 2
1
2
0 0 0
1 0 0
2 1 0 2
3
4
1 1 0
0 1 0
$EndNodes
$Elements
2 3 1 3
1 1 1 1
1 1 2
2 1 2 2
2 1 2 3
3 1 4 3
$EndElements
";

const INVERTED_CASE: &str = "analysis = \"axisymmetric\"
[mesh]
file = \"inverted.msh\"
[materials.steel]
model = \"linear-elastic\"
youngs_modulus = 200.0
poissons_ratio = 0.3
[[sections]]
group = \"body\"
material = \"steel\"
[[boundary]]
group = \"base\"
type = \"displacement\"
components = [\"z\"]
value = 0.01
[[steps]]
end_time = 1.0
";
