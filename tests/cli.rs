//! The `stiction` program end to end: exit status 0 on success, 2 on bad input with a message
//! naming the key and no panic. (An integration test of the root package, so Cargo builds the
//! binary and tells us where it is.)

use std::path::PathBuf;
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn exits_with_status_2_on_bad_input_and_0_on_success() {
    let exe = env!("CARGO_BIN_EXE_stiction");
    let out = root().join("target").join("test-out").join("cli");
    let _ = std::fs::remove_dir_all(&out);
    let case = root().join("cases/validation/lame-sphere-axisym.toml");
    let ok = Command::new(exe).arg("check").arg(&case).output().unwrap();
    assert_eq!(ok.status.code(), Some(0), "{}", String::from_utf8_lossy(&ok.stderr));
    let bad = Command::new(exe)
        .args([
            "run",
            case.to_str().unwrap(),
            "--set",
            "materials.steel.youngs_modulus=0",
            "--out",
            out.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert_eq!(bad.status.code(), Some(2));
    let msg = String::from_utf8_lossy(&bad.stderr);
    assert!(msg.contains("youngs_modulus") && !msg.contains("panicked"), "{msg}");
    let missing = Command::new(exe).args(["run", "no-such-case.toml"]).output().unwrap();
    assert_eq!(missing.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&missing.stderr).contains("no-such-case.toml"));
    let run = Command::new(exe)
        .args(["run", case.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"])
        .output()
        .unwrap();
    assert_eq!(run.status.code(), Some(0), "{}", String::from_utf8_lossy(&run.stderr));
    assert!(out.join("summary.json").exists() && out.join("lame-sphere-axisym.pvd").exists());
}
