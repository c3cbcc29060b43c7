//! A corpus of broken inputs, each tried as a new user would with the `stiction` program: every
//! one must end with the stated exit status and a message containing the stated phrase (the
//! culprit: a key, a file, a line), never a panic and never a silent success.
//!
//! Cases: the shipped rough-w6-quick, hertz-axisym, lame-sphere-axisym, cantilever and
//! afm-hemisphere cases, broken with `--set` or by a scratch copy; `stiction calibrate` on
//! broken tables.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

const ROUGH: &str = "cases/ru-rough-sphere/rough-w6-quick.toml";
const HERTZ: &str = "cases/validation/hertz-axisym.toml";
const LAME: &str = "cases/validation/lame-sphere-axisym.toml";
const CANTILEVER: &str = "cases/validation/cantilever.toml";
const AFM: &str = "cases/rough-surface/afm-hemisphere.toml";

/// One broken input: the program's arguments (`{scratch}` stands for the scratch folder), the
/// exit status and a phrase the message must contain.
struct Broken {
    args: &'static [&'static str],
    exit: i32,
    phrase: &'static str,
}

const fn bad(args: &'static [&'static str], phrase: &'static str) -> Broken {
    Broken { args, exit: 2, phrase }
}

/// Numbers out of range or not finite, in every part of a case; `check` and `run` must agree.
const NUMBERS: &[Broken] = &[
    bad(
        &["run", ROUGH, "--set", "interfaces.0.points.density=inf", "--set", "interfaces.0.points.min_spacing=0.0"],
        "key 'interfaces[0].points.density': must be a finite number > 0",
    ),
    bad(&["check", ROUGH, "--set", "interfaces.0.points.density=1e3"], "at most 1000000 are generated"),
    bad(&["check", ROUGH, "--set", "interfaces.0.points.height=nan"], "key 'interfaces[0].points.height'"),
    bad(
        &["check", ROUGH, "--set", "interfaces.0.points.region_radius=0.0"],
        "key 'interfaces[0].points.region_radius'",
    ),
    bad(&["check", ROUGH, "--set", "interfaces.0.points.height_std=-1.0"], "key 'interfaces[0].points.height_std'"),
    bad(&["check", ROUGH, "--set", "interfaces.0.points.min_spacing=100.0"], "min_spacing 100 is too large"),
    bad(
        &["check", ROUGH, "--set", "solver.tol_residual=inf"],
        "key 'solver.tol_residual': must be a finite number > 0, got inf",
    ),
    bad(&["check", ROUGH, "--set", "solver.tol_residual=-1.0"], "key 'solver.tol_residual'"),
    bad(&["run", ROUGH, "--set", "solver.tol_residual=-1.0"], "key 'solver.tol_residual'"),
    bad(&["check", ROUGH, "--set", "solver.tol_displacement=nan"], "key 'solver.tol_displacement'"),
    bad(&["check", ROUGH, "--set", "solver.max_iterations=0"], "key 'solver.max_iterations'"),
    bad(&["check", ROUGH, "--set", "solver.cut_factor=1.5"], "key 'solver.cut_factor': must be in (0, 1)"),
    bad(&["check", ROUGH, "--set", "solver.growth_factor=nan"], "key 'solver.growth_factor'"),
    bad(&["check", ROUGH, "--set", "interfaces.0.initial_gap=inf"], "key 'interfaces[0].initial_gap'"),
    bad(&["check", ROUGH, "--set", "interfaces.0.approach=nan"], "key 'interfaces[0].approach'"),
    bad(&["check", ROUGH, "--set", "interfaces.0.viscosity=-1.0"], "key 'interfaces[0].viscosity'"),
    bad(&["check", ROUGH, "--set", "interfaces.0.max_viscous_share=2.0"], "key 'interfaces[0].max_viscous_share'"),
    bad(
        &["check", ROUGH, "--set", "interfaces.0.parameters.expected_work_of_adhesion=nan"],
        "interfaces[0].parameters.expected_work_of_adhesion",
    ),
    bad(&["check", ROUGH, "--set", "steps.0.end_time=-5.0"], "key 'steps[0].end_time'"),
    bad(&["run", ROUGH, "--set", "steps.0.end_time=-5.0"], "key 'steps[0].end_time'"),
    bad(&["check", ROUGH, "--set", "steps.0.end_time=inf"], "key 'steps[0].end_time': must be a finite number"),
    bad(&["check", ROUGH, "--set", "steps.0.initial_increment=nan"], "key 'steps[0].initial_increment'"),
    bad(&["check", ROUGH, "--set", "steps.0.max_increment=inf"], "key 'steps[0].max_increment'"),
    bad(&["check", ROUGH, "--set", "steps.0.min_increment=0.0"], "key 'steps[0].min_increment'"),
    bad(&["check", ROUGH, "--set", "steps.0.until_separated=\"nobody\""], "no interface named 'nobody'"),
    bad(&["check", ROUGH, "--set", "materials.ru.yield_stress=-3.0"], "yield_stress"),
    bad(&["check", ROUGH, "--set", "materials.ru.youngs_modulus=0.0"], "youngs_modulus"),
    bad(&["check", ROUGH, "--set", "materials.ru.poissons_ratio=0.5"], "poissons_ratio"),
    bad(&["check", HERTZ, "--set", "materials.ru.poissons_ratio=nan"], "poissons_ratio"),
    bad(&["check", CANTILEVER, "--set", "loads.0.vector=[0.0, 0.0, nan]"], "key 'loads[0].vector[2]'"),
    bad(&["check", ROUGH, "--set", "amplitudes.cycle.value=[0.0, inf, 0.0]"], "key 'amplitudes.cycle.value[1]'"),
    bad(&["check", ROUGH, "--set", "amplitudes.cycle.time=[0.0, 2.0, 1.0]"], "amplitudes"),
    bad(&["check", LAME, "--set", "loads.0.value=nan"], "key 'loads[0].value'"),
];

/// The mesh: parameters checked against the `.geo`'s declarations before gmsh runs; gmsh's own
/// failures name the `.geo`.
const MESHES: &[Broken] = &[
    bad(
        &["check", ROUGH, "--set", "mesh.parameters.h_contact=0.0"],
        "key 'mesh.parameters.h_contact': 0 is outside the range [0.5, inf)",
    ),
    bad(&["check", ROUGH, "--set", "mesh.parameters.R=nan"], "key 'mesh.parameters.R'"),
    bad(&["check", ROUGH, "--set", "mesh.parameters.R=-1.0"], "key 'mesh.parameters.R': -1 is outside the range"),
    bad(
        &["check", ROUGH, "--set", "mesh.parameters.hh=5.0"],
        "declares no parameter 'hh' in a DefineConstant (it declares: R, h_contact, r_fine, growth, h_far, layer)",
    ),
    bad(&["check", LAME, "--set", "mesh.parameters.h=-0.2"], "key 'mesh.parameters.h'"),
    bad(&["check", HERTZ, "--set", "mesh.parameters.R=0.0"], "key 'mesh.parameters.R'"),
    bad(&["check", ROUGH, "--set", "mesh.size_factor=0.0"], "key 'mesh.size_factor'"),
    bad(&["check", ROUGH, "--set", "mesh.order=3"], "key 'mesh.order'"),
    bad(&["check", ROUGH, "--set", "mesh.time_limit=0.0"], "key 'mesh.time_limit'"),
    bad(
        &["check", ROUGH, "--set", "mesh.parameters.h_contact=0.6", "--set", "mesh.time_limit=1.0"],
        "did not finish meshing",
    ),
    bad(&["check", ROUGH, "--set", "mesh.memory_limit=0.0"], "key 'mesh.memory_limit'"),
    bad(
        &["check", HERTZ, "--set", "mesh.size_factor=0.01", "--set", "mesh.memory_limit=0.25"],
        "key 'mesh.size_factor, mesh.parameters.",
    ),
    bad(&["check", HERTZ, "--set", "mesh.memory_limit=0.001"], "its model needs at least"),
    bad(&["check", "{scratch}/large-msh/case.toml"], "key 'mesh.file': mesh file"),
    // the model (~350 MiB) fits the estimate before assembly; its factor (~36 M entries) does not
    bad(
        &["run", "cases/validation/lj-sphere-3d.toml", "--set", "mesh.memory_limit=0.3", "--out", "{scratch}/no-room"],
        "the sparse factor of this model",
    ),
    bad(&["check", ROUGH, "--set", "mesh.geo=\"no-such.geo\""], "no-such.geo"),
    bad(&["check", "{scratch}/empty-geo/case.toml"], "is the .geo empty or truncated?"),
    bad(&["check", "{scratch}/truncated-geo/case.toml"], "truncated-geo/cantilever.geo', line"),
    bad(&["check", HERTZ, "--set", "sections.0.group=\"bodyy\""], "'bodyy'"),
    bad(&["check", HERTZ, "--set", "interfaces.0.surface=\"surfac\""], "surfac"),
];

/// The case file itself, laws and plugins.
const CASES: &[Broken] = &[
    bad(&["check", "no-such-case.toml"], "no-such-case.toml"),
    bad(&["check", "{scratch}/syntax/case.toml"], "line"),
    bad(&["check", ROUGH, "--set", "solver.max_iteration=3"], "max_iteration"),
    bad(&["check", ROUGH, "--set", "solver.tol_residual"], "KEY=VALUE"),
    bad(&["check", ROUGH, "--set", "analysis=\"4d\""], "analysis"),
    bad(&["check", HERTZ, "--set", "boundary.0.type=\"glued\""], "glued"),
    bad(&["check", HERTZ, "--set", "interfaces.0.law=\"no-such-law\""], "no interface law 'no-such-law'"),
    bad(&["check", HERTZ, "--set", "interfaces.0.law=\"/no/such/lib.so\""], "'/no/such/lib.so': no such file"),
    bad(&["check", HERTZ, "--set", "interfaces.0.law=\"{scratch}/not-a-library.so\""], "dlopen failed: "),
    bad(&["check", HERTZ, "--set", "interfaces.0.parameters.penalty=-1.0"], "penalty"),
    bad(&["check", ROUGH, "--set", "interfaces.0.config_file=\"no-such.toml\""], "no-such.toml"),
    bad(
        &["check", ROUGH, "--set", "interfaces.0.parameters.expected_work_of_adhesion=3.0"],
        "the calibration has 6 J/m^2 but the case expects 3 J/m^2",
    ),
    bad(&["check", ROUGH, "--set", "interfaces.0.points.file=\"no-such.csv\""], "no-such.csv"),
    bad(&["check", ROUGH, "--set", "plugin_path=[\"rough-w6.toml\"]"], "plugin_path[0]"),
    bad(&["plugins", "--plugin-path", "Cargo.toml"], "--plugin-path 'Cargo.toml' is a file"),
];

/// A case's height map (`points.surface`): broken files, units, regions and summits.
const HEIGHT_MAPS: &[Broken] = &[
    bad(&["check", AFM, "--set", "interfaces.0.points.region_radius=200.0"], "is smaller than the case's region"),
    bad(&["check", AFM, "--set", "interfaces.0.points.surface.centre=[10.0, 10.0]"], "around (10.0000, 10.0000) needs"),
    bad(&["check", AFM, "--set", "interfaces.0.points.surface.threshold=50.0"], "no summit of"),
    bad(
        &["check", AFM, "--set", "interfaces.0.points.surface.pixel_size=1.0"],
        "is a .gsf file, which states its own size",
    ),
    bad(&["check", AFM, "--set", "interfaces.0.points.surface.threshold=-1.0"], "points.surface.threshold': must be"),
    bad(&["check", AFM, "--set", "interfaces.0.points.density=0.0079"], "points.density': the points come from"),
    bad(&["check", AFM, "--set", "interfaces.0.points.surface.file=\"no-such.gsf\""], "no-such.gsf': No such file"),
    bad(
        &["check", AFM, "--set", "interfaces.0.points.surface.file=\"{scratch}/truncated.gsf\""],
        "truncated: 256 x 256",
    ),
    bad(
        &["check", AFM, "--set", "interfaces.0.points.surface.file=\"{scratch}/heights.txt\""],
        "is a text map: give its pixel_size",
    ),
    bad(
        &["check", AFM, "--set", "interfaces.0.points.surface={ file = \"{scratch}/heights.txt\", pixel_size = 1.0 }"],
        "states no unit for its lengths",
    ),
    bad(
        &[
            "check",
            AFM,
            "--set",
            "interfaces.0.points.surface={ file = \"{scratch}/heights.txt\", pixel_size = 1.0, unit = \"furlong\" }",
        ],
        "in 'furlong', which is not one of",
    ),
    bad(
        &[
            "check",
            AFM,
            "--set",
            "interfaces.0.points.surface={ file = \"{scratch}/heights.txt\", pixel_size = 0.0, unit = \"nm\" }",
        ],
        "points.surface.pixel_size': must be a finite number > 0",
    ),
    bad(
        &[
            "check",
            AFM,
            "--set",
            "interfaces.0.points.surface={ file = \"{scratch}/nan.txt\", pixel_size = 1.0, unit = \"nm\" }",
        ],
        "nan.txt': line 2: NaN is not a finite number",
    ),
    bad(
        &[
            "check",
            AFM,
            "--set",
            "interfaces.0.points.surface={ file = \"{scratch}/irregular.txt\", columns = true, unit = \"nm\" }",
        ],
        "irregular.txt': the grid is not regular",
    ),
];

/// `stiction calibrate` on broken tables: each names the file, the line and the column.
const TABLES: &[Broken] = &[
    bad(
        &["calibrate", "{scratch}/nan-distance.csv", "-o", "{scratch}/out.toml"],
        "nan-distance.csv': line 4, column 1 (distance): expected a finite number, found 'nan'",
    ),
    bad(
        &["calibrate", "{scratch}/nan-force.csv", "-o", "{scratch}/out.toml"],
        "nan-force.csv': line 3, column 2 (force): expected a finite number, found 'NaN'",
    ),
    bad(&["calibrate", "{scratch}/no-header.csv", "-o", "{scratch}/out.toml"], "line 1: expected the header"),
    bad(
        &["calibrate", "{scratch}/bad-branch.csv", "-o", "{scratch}/out.toml"],
        "line 3: branch must be 'loading' or 'unloading'",
    ),
    bad(&["calibrate", "{scratch}/no-such-table.csv", "-o", "{scratch}/out.toml"], "no-such-table.csv"),
    bad(
        &["calibrate", "{scratch}/huge-force.csv", "-o", "{scratch}/out.toml"],
        "huge-force.csv': line 3, column 2 (force): 1e308 is too large to fit",
    ),
    bad(
        &["calibrate", "{scratch}/one-distance.csv", "-o", "{scratch}/out.toml"],
        "the loading rows (lines 2 to 7) all have the distance 0.5: a fit needs distinct distances",
    ),
];

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The scratch inputs the corpus refers to.
fn scratch() -> PathBuf {
    let dir = root().join("target").join("test-out").join("bad-input-corpus");
    let _ = std::fs::remove_dir_all(&dir);
    let cantilever = std::fs::read_to_string(root().join(CANTILEVER)).unwrap();
    let cantilever = cantilever.lines().filter(|l| !l.starts_with("parameters")).collect::<Vec<_>>().join("\n");
    for (folder, geo) in [("empty-geo", ""), ("truncated-geo", "SetFactory(\"OpenCASCADE\");\nBox(1) = {0, 0, 0, 10")] {
        std::fs::create_dir_all(dir.join(folder)).unwrap();
        std::fs::write(dir.join(folder).join("cantilever.geo"), geo).unwrap();
        std::fs::write(dir.join(folder).join("case.toml"), &cantilever).unwrap();
    }
    // only the size of a mesh file too large to read is looked at, before any of it is read
    std::fs::create_dir_all(dir.join("large-msh")).unwrap();
    std::fs::write(dir.join("large-msh").join("body.msh"), vec![b'0'; 1 << 20]).unwrap();
    let large = cantilever.replace("geo = \"cantilever.geo\"", "file = \"body.msh\"\nmemory_limit = 0.001");
    std::fs::write(dir.join("large-msh").join("case.toml"), large).unwrap();
    std::fs::create_dir_all(dir.join("syntax")).unwrap();
    std::fs::write(dir.join("syntax").join("case.toml"), "name = \"x\"\n[mesh\ngeo = \"a.geo\"\n").unwrap();
    std::fs::write(dir.join("not-a-library.so"), "not a shared library\n").unwrap();
    std::fs::write(dir.join("heights.txt"), "0 1 2\n3 4 5\n6 7 8\n").unwrap();
    std::fs::write(dir.join("nan.txt"), "0 1 2\n3 nan 5\n6 7 8\n").unwrap();
    std::fs::write(dir.join("irregular.txt"), "0 0 1\n1 0 1\n3 0 1\n0 1 1\n1 1 1\n3 1 1\n0 2 1\n1 2 1\n3 2 1\n")
        .unwrap();
    let map = std::fs::read(root().join("cases/rough-surface/ru-film-256nm.gsf")).unwrap();
    std::fs::write(dir.join("truncated.gsf"), &map[..100_000]).unwrap();
    let header = "distance,force,area,branch,max_distance\n";
    let tables = [
        ("nan-distance.csv", format!("{header}0.1,1.0,1.0,loading,0\n0.2,2.0,2.0,loading,0\nnan,3.0,3.0,loading,0\n")),
        ("nan-force.csv", format!("{header}0.1,1.0,1.0,loading,0\n0.2,NaN,2.0,loading,0\n")),
        ("no-header.csv", "0.1,1.0,1.0,loading,0\n".to_string()),
        ("bad-branch.csv", format!("{header}0.1,1.0,1.0,loading,0\n0.2,1.0,1.0,sideways,0\n")),
        ("huge-force.csv", format!("{header}0.1,1.0,1.0,loading,0\n0.2,1e308,2.0,loading,0\n")),
        ("one-distance.csv", format!("{header}{}", "0.5,1.0,1.0,loading,0\n".repeat(6))),
    ];
    for (name, text) in tables {
        std::fs::write(dir.join(name), text).unwrap();
    }
    dir
}

/// Runs the program with `args` in the workspace root, at most `limit`; (exit status, stderr).
pub fn run_program(args: &[String], limit: Duration) -> (Option<i32>, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_stiction"))
        .args(args)
        .current_dir(root())
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > limit {
            let _ = child.kill();
            panic!("stiction {} did not finish within {limit:?}", args.join(" "));
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    let out = child.wait_with_output().unwrap();
    (out.status.code(), String::from_utf8_lossy(&out.stderr).to_string())
}

fn check_corpus(corpus: &[Broken]) {
    let dir = scratch_once();
    let mut failures = Vec::new();
    for b in corpus {
        let args: Vec<String> = b.args.iter().map(|a| a.replace("{scratch}", dir.to_str().unwrap())).collect();
        let (code, stderr) = run_program(&args, Duration::from_secs(120));
        let clean = code == Some(b.exit)
            && stderr.contains(b.phrase)
            && !stderr.contains("panicked")
            && !stderr.contains("RUST_BACKTRACE");
        if !clean {
            failures.push(format!(
                "stiction {}\n  exit {code:?} (expected {}), stderr:\n{stderr}",
                args.join(" "),
                b.exit
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {} broken inputs misreported:\n{}",
        failures.len(),
        corpus.len(),
        failures.join("\n")
    );
}

/// The scratch folder, made once per test process (the tests share it).
fn scratch_once() -> &'static Path {
    static DIR: std::sync::OnceLock<PathBuf> = std::sync::OnceLock::new();
    DIR.get_or_init(scratch)
}

#[test]
fn numbers_out_of_range_name_their_key_in_check_and_run() {
    check_corpus(NUMBERS);
}

#[test]
fn mesh_problems_name_the_key_or_the_geo() {
    check_corpus(MESHES);
    // a run refused for its size leaves no output folder behind
    assert!(!scratch_once().join("no-room").exists(), "a run refused before it started made its output folder");
}

#[test]
fn case_files_laws_and_plugins_name_the_culprit() {
    check_corpus(CASES);
}

#[test]
fn height_maps_name_the_file_the_key_and_the_fault() {
    check_corpus(HEIGHT_MAPS);
}

#[test]
fn calibration_tables_name_file_line_and_column() {
    check_corpus(TABLES);
}
