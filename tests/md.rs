//! `stiction md` with LAMMPS (installed by the test script): a tiny Au asperity (33 atoms on a
//! 537-atom cell, EAM `Au_u3.eam`) pressed by a flat to 0.2 nm and pulled back at 100 m/s. The
//! atoms repel on contact and, coming apart, hold on in a neck: the force on the asperity is
//! compressive at the maximum approach and tensile on unloading; the neck has no area apart and
//! some at the maximum; `stiction calibrate` reads the table. And the MD file's faults, and a
//! LAMMPS that fails, are named.

use std::path::{Path, PathBuf};
use std::process::Command;

const POTENTIAL: &str = "/usr/share/lammps/potentials/Au_u3.eam";

fn scratch(label: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("target").join("test-out").join("md").join(label);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn md_file(dir: &Path, potential: &str, changes: &[(&str, &str)]) -> PathBuf {
    let mut text = format!(
        "[lattice]\nconstant = 4.08\n[substrate]\nwidth_cells = 6\nthickness = 8.0\n[asperity]\nbase_radius = 8.0\nheight = 6.0\n\
         [counter]\nthickness = 6.0\ngap = 4.0\n[potential]\nfile = \"{potential}\"\nelement = \"Au\"\n\
         [run]\ntemperature = 300.0\ntimestep = 0.002\nspeed = 100.0\nmax_approach = 2.0\n"
    );
    for (from, to) in changes {
        assert!(text.contains(from), "{from}");
        text = text.replace(from, to);
    }
    let path = dir.join("tiny.toml");
    std::fs::write(&path, text).unwrap();
    path
}

fn stiction(args: &[&std::ffi::OsStr], lammps: Option<&str>) -> (Option<i32>, String, String) {
    let mut command = Command::new(env!("CARGO_BIN_EXE_stiction"));
    command.arg("md").args(args);
    if let Some(l) = lammps {
        command.env("STICTION_LAMMPS", l);
    }
    let out = command.output().unwrap();
    (out.status.code(), String::from_utf8_lossy(&out.stdout).into(), String::from_utf8_lossy(&out.stderr).into())
}

#[test]
fn a_tiny_au_asperity_repels_on_contact_and_holds_on_in_a_neck() {
    let dir = scratch("tiny");
    let file = md_file(&dir, POTENTIAL, &[]);
    let out = dir.join("out");
    let (code, stdout, stderr) = stiction(&[file.as_os_str(), "--out".as_ref(), out.as_os_str()], None);
    assert_eq!(code, Some(0), "{stdout}\n{stderr}");
    let table = std::fs::read_to_string(out.join("force-distance.csv")).unwrap();
    let rows: Vec<(f64, f64, String, f64)> = table
        .lines()
        .skip_while(|l| l.starts_with('#'))
        .skip(1)
        .map(|l| {
            let v: Vec<&str> = l.split(',').collect();
            (v[0].parse().unwrap(), v[1].parse().unwrap(), v[3].to_string(), v[2].parse().unwrap())
        })
        .collect();
    let loading: Vec<_> = rows.iter().filter(|r| r.2 == "loading").collect();
    let unloading: Vec<_> = rows.iter().filter(|r| r.2 == "unloading").collect();
    assert!(!loading.is_empty() && !unloading.is_empty());
    // the approach runs from a / 2 - gap = -0.196 nm to 0.2 nm (averages over 50 steps)
    let (first, last) = (loading[0].0, loading[loading.len() - 1].0);
    assert!((-0.196..-0.15).contains(&first) && (0.19..=0.2).contains(&last), "{first} .. {last}");
    let at_max = loading[loading.len() - 1].1;
    let most_tensile = unloading.iter().map(|r| r.1).fold(f64::INFINITY, f64::min);
    println!("force at the maximum approach {at_max:.2} nN, most tensile on unloading {most_tensile:.2} nN");
    assert!(at_max > 5.0, "repulsion at 0.2 nm: {at_max} nN");
    assert!(most_tensile < -5.0, "a neck on unloading: {most_tensile} nN");
    // the neck: no area apart; at the maximum approach more than a few atoms' (a^2 / 2 each), and
    // less than twice the cap's base (21 atoms, 1.75 nm^2: the crushed cap spreads)
    let (apart, pressed) = (loading[0].3, loading[loading.len() - 1].3);
    assert_eq!(apart, 0.0);
    let base = 21.0 * 0.408f64.powi(2) / 2.0;
    assert!(pressed > 0.5 && pressed < 2.0 * base, "area at 0.2 nm: {pressed} nm^2");
    for f in ["atoms.data", "in.stiction", "log.lammps", "loading.lammpstrj", "unloading.lammpstrj"] {
        assert!(out.join(f).exists(), "{f}");
    }
    // the table is one `stiction calibrate` reads
    let calibration = dir.join("calibration.toml");
    let status = Command::new(env!("CARGO_BIN_EXE_stiction"))
        .args(["calibrate", "--work-of-adhesion", "1.0", "-o"])
        .arg(&calibration)
        .arg(out.join("force-distance.csv"))
        .output()
        .unwrap();
    assert!(status.status.success(), "{}", String::from_utf8_lossy(&status.stderr));
    let text = std::fs::read_to_string(&calibration).unwrap();
    assert!(text.contains("stiction md with LAMMPS"), "the provenance travels: {text}");
}

#[test]
fn md_files_and_failed_lammps_runs_are_named() {
    let dir = scratch("bad");
    let cases: [(&[(&str, &str)], &str); 5] = [
        (&[(POTENTIAL, "no-such.eam")], "key 'potential.file': cannot read"),
        (&[("element = \"Au\"", "element = \"Cu\"")], "key 'potential.element': 'Cu' (Z = 29) is not the element"),
        (
            &[("constant = 4.08", "constant = 3.61")],
            "key 'lattice.constant': 3.61 Angstrom does not match the potential's 4.08",
        ),
        (&[("timestep = 0.002", "timestep = 0.01")], "key 'run.timestep': at 100 m/s the counter moves"),
        (&[("base_radius = 8.0", "base_radius = 30.0")], "key 'asperity.base_radius'"),
    ];
    for (changes, phrase) in cases {
        let file = md_file(&dir, POTENTIAL, changes);
        let (code, _, stderr) = stiction(&[file.as_os_str(), "--out".as_ref(), dir.join("out").as_os_str()], None);
        assert_eq!(code, Some(2), "{changes:?}: {stderr}");
        assert!(stderr.contains(phrase) && stderr.contains("tiny.toml"), "{changes:?}: {stderr}");
    }
    // a relative potential path with a space, from an MD file given by a relative path: found
    std::fs::create_dir_all(dir.join("my potentials")).unwrap();
    std::fs::copy(POTENTIAL, dir.join("my potentials").join("Au.eam")).unwrap();
    md_file(&dir, POTENTIAL, &[(POTENTIAL, "my potentials/Au.eam")]);
    let out = Command::new(env!("CARGO_BIN_EXE_stiction"))
        .args(["md", "tiny.toml", "--out", "relative-out"])
        .current_dir(&dir)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let file = md_file(&dir, POTENTIAL, &[]);
    let (code, _, stderr) =
        stiction(&[file.as_os_str(), "--out".as_ref(), dir.join("out").as_os_str()], Some("/no/such/lmp"));
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("cannot run LAMMPS ('/no/such/lmp'"), "{stderr}");
    // a potential whose header is right and whose tables are cut short: LAMMPS fails reading it
    let text = std::fs::read_to_string(POTENTIAL).unwrap();
    let cut: String = text.lines().take(6).map(|l| format!("{l}\n")).collect();
    std::fs::write(dir.join("cut.eam"), cut).unwrap();
    let file = md_file(&dir, POTENTIAL, &[(POTENTIAL, "cut.eam")]);
    let out = dir.join("failed");
    let (code, _, stderr) = stiction(&[file.as_os_str(), "--out".as_ref(), out.as_os_str()], None);
    assert_eq!(code, Some(1), "{stderr}");
    assert!(stderr.contains("LAMMPS failed") && stderr.contains("log.lammps") && stderr.contains("ERROR"), "{stderr}");
    assert!(out.join("log.lammps").exists() && out.join("in.stiction").exists(), "the failed run's files are kept");
}
