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

/// The table's rows: distance, force, branch, area, max_distance.
fn table_rows(table: &str) -> Vec<(f64, f64, String, f64, f64)> {
    table
        .lines()
        .skip_while(|l| l.starts_with('#'))
        .skip(1)
        .map(|l| {
            let v: Vec<&str> = l.split(',').collect();
            (
                v[0].parse().unwrap(),
                v[1].parse().unwrap(),
                v[3].to_string(),
                v[2].parse().unwrap(),
                v[4].parse().unwrap(),
            )
        })
        .collect()
}

/// The `# work_of_adhesion:` line's value.
fn table_work(table: &str) -> f64 {
    let line = table.lines().find_map(|l| l.strip_prefix("# work_of_adhesion:")).expect("a work_of_adhesion line");
    line.trim().parse().unwrap()
}

/// Twice the relaxed (001) surface energy of the Au_u3 potential, 918 mJ/m^2 in Foiles, Baskes
/// and Daw, Phys. Rev. B 33, 7983 (1986), Table IV: the work of adhesion of two (001) flats of
/// the one crystal (J/m^2).
const AU_001_WORK_OF_ADHESION: f64 = 2.0 * 0.918;

#[test]
fn a_tiny_au_asperity_repels_on_contact_and_holds_on_in_a_neck() {
    let dir = scratch("tiny");
    let file = md_file(&dir, POTENTIAL, &[("max_approach = 2.0", "max_approach = [1.0, 2.0]\npull_back = -12.0")]);
    let out = dir.join("out");
    let (code, stdout, stderr) = stiction(&[file.as_os_str(), "--out".as_ref(), out.as_os_str()], None);
    assert_eq!(code, Some(0), "{stdout}\n{stderr}");
    let table = std::fs::read_to_string(out.join("force-distance.csv")).unwrap();
    let rows = table_rows(&table);
    let loading: Vec<_> = rows.iter().filter(|r| r.2 == "loading").collect();
    assert!(!loading.is_empty());
    // the loading starts at the jump-in, the row before the first with a neck, after the start
    // a / 2 - gap = -0.196 nm, and runs to 0.2 nm; a row averages 50 steps (0.01 nm), at steps
    // that are multiples of 50, so the last ends within two windows of the maximum
    let (first, last) = (loading[0].0, loading[loading.len() - 1].0);
    assert!((-0.196..0.0).contains(&first) && (0.18..=0.2).contains(&last), "{first} .. {last}");
    assert!(loading[0].3 == 0.0 && loading[1].3 > 0.0, "the jump-in: {:?}", &loading[..2]);
    let at_max = loading[loading.len() - 1].1;
    assert!(at_max > 5.0, "repulsion at 0.2 nm: {at_max} nN");
    // the neck at the maximum approach: more than a few atoms' (a^2 / 2 each), and
    // less than twice the cap's base (21 atoms, 1.75 nm^2: the crushed cap spreads)
    let pressed = loading[loading.len() - 1].3;
    let base = 21.0 * 0.408f64.powi(2) / 2.0;
    assert!(pressed > 0.5 && pressed < 2.0 * base, "area at 0.2 nm: {pressed} nm^2");
    // an unloading branch from each maximum: it starts within two averaging windows of its
    // maximum, pulls on a neck, and ends where the neck broke (its area zero)
    for m in [0.1, 0.2] {
        let branch: Vec<_> = rows.iter().filter(|r| r.2 == "unloading" && r.4 == m).collect();
        assert!(branch.len() > 10, "a branch from {m} nm: {} rows", branch.len());
        let start = branch[0].0;
        assert!(start < m && start > m - 0.02, "the branch from {m} nm starts at {start} nm");
        let most_tensile = branch.iter().map(|r| r.1).fold(f64::INFINITY, f64::min);
        println!(
            "unloading from {m} nm: most tensile {most_tensile:.2} nN, ends at {:.3} nm",
            branch[branch.len() - 1].0
        );
        assert!(most_tensile < -5.0, "a neck on unloading from {m} nm: {most_tensile} nN");
        assert_eq!(branch[branch.len() - 1].3, 0.0, "the branch from {m} nm ends where the neck broke");
        assert!(branch[..branch.len() - 1].iter().all(|r| r.3 > 0.0), "and no later");
        assert!(stdout.contains(&format!("unloading from {m:.3} nm: the neck broke at")), "{stdout}");
    }
    // the work of adhesion, measured on (001) flats at cross scale 1: the potential's own
    let w = table_work(&table);
    println!("work of adhesion {w} J/m^2, published {AU_001_WORK_OF_ADHESION}");
    assert!((w / AU_001_WORK_OF_ADHESION - 1.0).abs() < 0.01, "{w} J/m^2");
    for f in [
        "atoms.data",
        "in.stiction",
        "log.lammps",
        "loading.lammpstrj",
        "unloading-1.lammpstrj",
        "unloading-2.lammpstrj",
    ] {
        assert!(out.join(f).exists(), "{f}");
    }
    // the table is one `stiction calibrate` reads, the measured work of adhesion with it
    let calibration = dir.join("calibration.toml");
    let status = Command::new(env!("CARGO_BIN_EXE_stiction"))
        .args(["calibrate", "-o"])
        .arg(&calibration)
        .arg(out.join("force-distance.csv"))
        .output()
        .unwrap();
    assert!(status.status.success(), "{}", String::from_utf8_lossy(&status.stderr));
    let text = std::fs::read_to_string(&calibration).unwrap();
    assert!(text.contains("stiction md with LAMMPS"), "the provenance travels: {text}");
    assert!(text.contains(&format!("work_of_adhesion = {w}")), "{text}");
    assert_eq!(text.matches("[[unloading]]").count(), 2, "{text}");
}

/// The potential rewritten with the cross terms at scale 1 is the funcfl potential: LAMMPS's
/// energy of the tiny assembly under `pair_style eam` with the original file and under
/// `eam/fs` with the rewritten one agree to round-off.
#[test]
fn the_cross_scaled_potential_at_scale_one_is_the_potential() {
    let dir = scratch("scale-one");
    let out = dir.join("out");
    let file = md_file(&dir, POTENTIAL, &[("max_approach = 2.0", "max_approach = 0.0")]);
    let (code, stdout, stderr) = stiction(&[file.as_os_str(), "--out".as_ref(), out.as_os_str()], None);
    assert_eq!(code, Some(0), "{stdout}\n{stderr}");
    let input = format!(
        "units metal\natom_style atomic\nboundary p p f\nread_data atoms.data\npair_style eam\n\
         pair_coeff * * \"{POTENTIAL}\"\nthermo_style custom step pe\nrun 0\nvariable funcfl equal $(pe:%.12f)\n\
         pair_style eam/fs\npair_coeff * * cross.eam.fs Au Au Au_counter\nrun 0\n\
         print \"${{funcfl}} $(pe:%.12f)\" file energies.txt screen no\n"
    );
    std::fs::write(out.join("in.energies"), input).unwrap();
    let status = Command::new("lmp")
        .args(["-in", "in.energies", "-log", "log.energies", "-screen", "none"])
        .current_dir(&out)
        .status()
        .unwrap();
    assert!(status.success());
    let text = std::fs::read_to_string(out.join("energies.txt")).unwrap();
    let e: Vec<f64> = text.split_whitespace().map(|v| v.parse().unwrap()).collect();
    println!("energy with eam {} eV, with the rewritten eam/fs {} eV", e[0], e[1]);
    assert!(e[0] < -1000.0 && ((e[1] - e[0]) / e[0]).abs() < 1e-10, "{e:?}");
}

/// A target work of adhesion is met by the cross scale: the table's measured work within the
/// tolerance (1%) of the target, a scale below 1 for a target below the potential's own; the
/// neck then breaks at the interface.
#[test]
fn a_target_work_of_adhesion_is_met_by_the_cross_scale() {
    let dir = scratch("target");
    let out = dir.join("out");
    let file = md_file(
        &dir,
        POTENTIAL,
        &[("max_approach = 2.0", "max_approach = 2.0\npull_back = -12.0\n[adhesion]\nwork_of_adhesion = 1.0")],
    );
    let (code, stdout, stderr) = stiction(&[file.as_os_str(), "--out".as_ref(), out.as_os_str()], None);
    assert_eq!(code, Some(0), "{stdout}\n{stderr}");
    let w = table_work(&std::fs::read_to_string(out.join("force-distance.csv")).unwrap());
    let scale: f64 =
        stdout.split("cross scale ").nth(1).unwrap().split(',').next().unwrap().trim_end_matches(')').parse().unwrap();
    println!("work of adhesion {w} J/m^2 at cross scale {scale}");
    assert!((w - 1.0).abs() < 0.01, "{w} J/m^2");
    assert!(scale > 0.2 && scale < 1.0, "{scale}");
    assert!(std::fs::read_to_string(out.join("cross.eam.fs")).unwrap().contains(&format!("scaled by {scale}")));
    // an interface weaker than the metal (whose own is 1.83 J/m^2) breaks at the interface: no
    // atom goes with the counter-body
    assert!(
        stdout.contains("the neck broke at") && stdout.contains("; 0 atoms went with the counter-body"),
        "{stdout}"
    );
}

#[test]
fn md_files_and_failed_lammps_runs_are_named() {
    let dir = scratch("bad");
    let cases: [(&[(&str, &str)], &str); 10] = [
        (&[(POTENTIAL, "no-such.eam")], "key 'potential.file': cannot read"),
        (&[("element = \"Au\"", "element = \"Cu\"")], "key 'potential.element': 'Cu' (Z = 29) is not the element"),
        (
            &[("constant = 4.08", "constant = 3.61")],
            "key 'lattice.constant': 3.61 Angstrom does not match the potential's 4.08",
        ),
        (&[("timestep = 0.002", "timestep = 0.01")], "key 'run.timestep': at 100 m/s the counter moves"),
        (&[("base_radius = 8.0", "base_radius = 30.0")], "key 'asperity.base_radius'"),
        (
            &[("max_approach = 2.0", "max_approach = [2.0, 1.0]")],
            "key 'run.max_approach': expected a finite number or a list",
        ),
        (
            &[("max_approach = 2.0", "max_approach = -3.0")],
            "key 'run.max_approach': -3 Angstrom is not past the start's approach",
        ),
        (&[("max_approach = 2.0", "max_approach = 2.0\npull_back = 2.5")], "key 'run.pull_back'"),
        (
            &[("max_approach = 2.0", "max_approach = 2.0\n[adhesion]\ncross_scale = 0.5\nwork_of_adhesion = 1.0")],
            "key 'adhesion.work_of_adhesion': give cross_scale or work_of_adhesion, not both",
        ),
        (&[("max_approach = 2.0", "max_approach = 2.0\n[adhesion]\ncross_scale = -1.0")], "key 'adhesion.cross_scale'"),
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
    // a potential whose header is right and whose tables are cut short
    let text = std::fs::read_to_string(POTENTIAL).unwrap();
    let cut: String = text.lines().take(6).map(|l| format!("{l}\n")).collect();
    std::fs::write(dir.join("cut.eam"), cut).unwrap();
    let file = md_file(&dir, POTENTIAL, &[(POTENTIAL, "cut.eam")]);
    let (code, _, stderr) = stiction(&[file.as_os_str(), "--out".as_ref(), dir.join("cut-out").as_os_str()], None);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("key 'potential.file'") && stderr.contains("table values"), "{stderr}");
    // a work of adhesion beyond the cross scale's reach: named with what the largest scale gives
    let file =
        md_file(&dir, POTENTIAL, &[("max_approach = 2.0", "max_approach = 2.0\n[adhesion]\nwork_of_adhesion = 50.0")]);
    let (code, _, stderr) = stiction(&[file.as_os_str(), "--out".as_ref(), dir.join("far-out").as_os_str()], None);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(
        stderr.contains("key 'adhesion.work_of_adhesion'") && stderr.contains("beyond this potential's reach"),
        "{stderr}"
    );
    // a run LAMMPS cannot finish (a bath at a million kelvin boils the atoms off): it fails
    let file = md_file(&dir, POTENTIAL, &[("temperature = 300.0", "temperature = 1.0e6")]);
    let out = dir.join("failed");
    let (code, _, stderr) = stiction(&[file.as_os_str(), "--out".as_ref(), out.as_os_str()], None);
    assert_eq!(code, Some(1), "{stderr}");
    assert!(stderr.contains("LAMMPS failed") && stderr.contains("log.lammps") && stderr.contains("ERROR"), "{stderr}");
    assert!(out.join("log.lammps").exists() && out.join("in.stiction").exists(), "the failed run's files are kept");
}

/// The shipped Au calibration is the documented fit of the shipped MD table: refitting
/// `au-quick.csv` with 6th-order loading and 7th-order unloading polynomials (as
/// `regenerate.sh` does) gives its coefficients. The rough gold hemisphere run with it
/// separates on unloading, and its most compressed asperity stays inside the calibrated
/// maxima (0.6 nm), as the case says.
#[test]
fn the_shipped_au_calibration_is_its_tables_fit_and_drives_the_rough_hemisphere() {
    let dir = scratch("au-rough-sphere");
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let calibrations = root.join("cases/md/calibrations");
    let refit = dir.join("refit.toml");
    let out = Command::new(env!("CARGO_BIN_EXE_stiction"))
        .args(["calibrate", "au-quick.csv", "--loading-order", "6", "--unloading-order", "7", "-o"])
        .arg(&refit)
        .current_dir(&calibrations)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let parse = |p: &Path| std::fs::read_to_string(p).unwrap().parse::<toml::Table>().unwrap();
    let (shipped, refitted) = (parse(&calibrations.join("au-quick.toml")), parse(&refit));
    let numbers = |t: &toml::Table| -> Vec<f64> {
        let mut v = Vec::new();
        let mut branches = vec![t["loading"].as_table().unwrap().clone()];
        branches.extend(t["unloading"].as_array().unwrap().iter().map(|u| u.as_table().unwrap().clone()));
        for b in branches {
            for key in ["force", "area"] {
                v.extend(b[key].as_array().unwrap().iter().map(|x| x.as_float().unwrap()));
            }
        }
        v
    };
    let (a, b) = (numbers(&shipped), numbers(&refitted));
    assert_eq!(a.len(), b.len());
    for (x, y) in a.iter().zip(&b) {
        assert!((x - y).abs() <= 1e-9 * x.abs().max(1.0), "{x} against {y}");
    }
    let sphere = dir.join("sphere");
    let out = Command::new(env!("CARGO_BIN_EXE_stiction"))
        .args(["run", "cases/md/au-rough-sphere.toml", "--set", "output.vtk=false", "--quiet", "--out"])
        .arg(&sphere)
        .current_dir(&root)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(sphere.join("summary.json")).unwrap()).unwrap();
    let i = &summary["interfaces"][0];
    println!(
        "max force {} nN, pull-off {} nN, most compressed asperity {} nm, {} in contact",
        i["max_force"], i["pull_off_force"], i["max_point_compression_at_max_force"], i["n_contact_at_max_force"]
    );
    assert_eq!(i["separated"], true);
    let deepest = i["max_point_compression_at_max_force"].as_f64().unwrap();
    assert!(deepest > 0.0 && deepest < 0.6, "{deepest} nm");
    assert!(i["n_contact_at_max_force"].as_f64().unwrap() >= 10.0);
}
