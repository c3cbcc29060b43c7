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

/// `surface generate` then `surface stats --periodic`: the map read back has the rms height
/// asked for and, from its spectrum, the Hurst exponent, within 5%; the summits file and the
/// statistics are written.
#[test]
fn a_generated_surface_measures_back_to_its_rms_height_and_hurst_exponent() {
    let exe = env!("CARGO_BIN_EXE_stiction");
    let out = root().join("target").join("test-out").join("surface");
    let _ = std::fs::remove_dir_all(&out);
    std::fs::create_dir_all(&out).unwrap();
    let map = out.join("map.gsf");
    let made = Command::new(exe)
        .args(["surface", "generate", "-o", map.to_str().unwrap(), "--hurst", "0.7", "--rms-height", "2.5"])
        .args(["--size", "2048", "--pixels", "512", "--rolloff", "512", "--cutoff", "16", "--seed", "11"])
        .output()
        .unwrap();
    assert_eq!(made.status.code(), Some(0), "{}", String::from_utf8_lossy(&made.stderr));
    let stats = Command::new(exe)
        .args(["surface", "stats", map.to_str().unwrap(), "--periodic", "--out", out.to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(stats.status.code(), Some(0), "{}", String::from_utf8_lossy(&stats.stderr));
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("surface-stats.json")).unwrap()).unwrap();
    let rms = report["statistics"]["rms_height"].as_f64().unwrap();
    let hurst = report["hurst"]["hurst"].as_f64().unwrap();
    assert!((rms / 2.5 - 1.0).abs() < 0.05, "rms height {rms}");
    assert!((hurst / 0.7 - 1.0).abs() < 0.05, "Hurst exponent {hurst}");
    let summits = std::fs::read_to_string(out.join("summits.csv")).unwrap();
    assert_eq!(summits.lines().count() - 1, report["statistics"]["summits"].as_u64().unwrap() as usize);
    assert!(
        ["top-view.png", "top-view.svg", "summit-heights.png", "summit-heights.svg"]
            .iter()
            .all(|f| out.join(f).exists())
    );
}

/// Bad height maps: exit 2 naming the file and what is wrong, never a panic.
#[test]
fn a_bad_height_map_is_refused_naming_the_file_and_the_fault() {
    let exe = env!("CARGO_BIN_EXE_stiction");
    let out = root().join("target").join("test-out").join("surface-bad");
    let _ = std::fs::remove_dir_all(&out);
    std::fs::create_dir_all(&out).unwrap();
    let write = |name: &str, bytes: &[u8]| {
        let path = out.join(name);
        std::fs::write(&path, bytes).unwrap();
        path.to_str().unwrap().to_string()
    };
    let gsf = |x_real: &str| {
        let mut bytes = format!("Gwyddion Simple Field 1.0\nXRes = 4\nYRes = 4\nXReal = {x_real}\n").into_bytes();
        bytes.extend(std::iter::repeat_n(0u8, 4 - bytes.len() % 4));
        bytes.extend((0..16).flat_map(|k| (k as f32).to_le_bytes()));
        bytes
    };
    let full = gsf("4");
    let cases: Vec<(String, Vec<&str>, &str)> = vec![
        (write("truncated.gsf", &full[..full.len() - 6]), vec![], "truncated: 4 x 4 heights take 64 bytes"),
        (write("zero.gsf", &gsf("0")), vec![], "the pixel size along x is 0"),
        (write("nan.txt", b"1 2 3\n4 nan 6\n7 8 9\n"), vec!["--pixel-size", "1"], "line 2: NaN is not a finite number"),
        (
            write("grid.xyz", b"0 0 1\n1 0 1\n3 0 1\n0 1 1\n1 1 1\n3 1 1\n0 2 1\n1 2 1\n3 2 1\n"),
            vec!["--columns"],
            "the grid is not regular",
        ),
        (
            write("flat.txt", b"1 1 1\n1 1 1\n1 1 1\n"),
            vec!["--pixel-size", "1"],
            "no pixel is higher than its 8 neighbours",
        ),
        (write("layout.txt", b"1 2 3\n"), vec![], "a text map needs its layout"),
        (write("zero-pixel.txt", b"1 2 3\n4 9 6\n7 8 9\n"), vec!["--pixel-size", "0"], "pixel size along x is 0"),
    ];
    for (file, extra, expected) in cases {
        let run = Command::new(exe).args(["surface", "stats", &file]).args(&extra).output().unwrap();
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert_eq!(run.status.code(), Some(2), "{file}: {stderr}");
        assert!(
            stderr.contains(&file) && stderr.contains(expected) && !stderr.contains("panicked"),
            "{file}: {stderr}"
        );
    }
    let missing = Command::new(exe).args(["surface", "stats", "no-such-map.gsf"]).output().unwrap();
    assert_eq!(missing.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&missing.stderr).contains("no-such-map.gsf"));
}

/// A reader that stops early (`stiction plugins | head -1`) ends the program by SIGPIPE, the
/// default for a command-line tool, not by a panic printing to a closed pipe.
#[cfg(unix)]
#[test]
fn a_closed_pipe_ends_the_program_without_a_panic() {
    use std::os::unix::process::ExitStatusExt;
    let exe = env!("CARGO_BIN_EXE_stiction");
    let mut child = Command::new(exe)
        .arg("plugins")
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take()); // the reader is gone before the first line
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_eq!(out.status.signal(), Some(13), "ended by SIGPIPE: {:?} {stderr}", out.status);
}
