//! Bad input gives errors that name the file, the key or line, and what was expected, with exit
//! status 2, never a panic.

use std::path::PathBuf;
use stiction::case;
use stiction_tests::workspace_root;

fn scratch(name: &str, text: &str) -> PathBuf {
    let dir = workspace_root().join("target").join("test-out").join("bad-input");
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

fn base_case(mesh_line: &str) -> String {
    format!(
        r#"
[mesh]
{mesh_line}
[materials.steel]
model = "linear-elastic"
youngs_modulus = 200.0
poissons_ratio = 0.3
[[sections]]
group = "body"
material = "steel"
[[boundary]]
group = "clamp"
type = "fixed"
[[steps]]
end_time = 1.0
"#
    )
}

fn cantilever_geo() -> String {
    format!("geo = \"{}\"", workspace_root().join("cases/validation/cantilever.geo").display())
}

/// Loads and builds; returns the error text and its exit code.
fn failure(path: &PathBuf, sets: &[&str]) -> (String, i32) {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    let err = match case::load(path, &sets) {
        Err(e) => e,
        Ok(c) => match stiction::build::build(&c) {
            Err(e) => e,
            Ok(_) => panic!("{} was accepted", path.display()),
        },
    };
    (err.to_string(), err.exit_code())
}

#[test]
fn unknown_key_names_the_key_and_line() {
    let p = scratch("unknown-key.toml", &base_case(&cantilever_geo()).replace("poissons_ratio", "poisson_ratio"));
    let (msg, code) = failure(&p, &[]);
    assert_eq!(code, 2);
    assert!(msg.contains("unknown-key.toml") && msg.contains("poisson_ratio") && msg.contains("line"), "{msg}");
}

#[test]
fn unknown_key_from_set_is_rejected() {
    let p = scratch("set-key.toml", &base_case(&cantilever_geo()));
    let (msg, code) = failure(&p, &["solver.max_iteration=3"]);
    assert_eq!(code, 2);
    assert!(msg.contains("max_iteration") && msg.contains("--set"), "{msg}");
}

#[test]
fn a_snap_method_or_tolerance_out_of_range_names_the_key_and_the_choices() {
    let p = scratch("snap.toml", &base_case(&cantilever_geo()));
    let (msg, code) = failure(&p, &["solver.snap=\"dynamic\""]);
    assert_eq!(code, 2);
    assert!(msg.contains("snap") && msg.contains("settle") && msg.contains("damped-flow"), "{msg}");
    let (msg, code) = failure(&p, &["solver.snap_tolerance=1.5"]);
    assert_eq!(code, 2);
    assert!(msg.contains("solver.snap_tolerance") && msg.contains("(0, 1)") && msg.contains("1.5"), "{msg}");
    let (msg, code) = failure(&p, &["solver.snap_damping=\"viscous\""]);
    assert_eq!(code, 2);
    assert!(msg.contains("snap_damping") && msg.contains("mass") && msg.contains("stiffness"), "{msg}");
}

#[test]
fn a_negative_checkpoint_interval_names_the_key_and_a_checkpoint_of_another_kind_is_refused_by_name() {
    let p = scratch("checkpoint.toml", &base_case(&cantilever_geo()));
    let (msg, code) = failure(&p, &["output.checkpoint_minutes=-1.0"]);
    assert_eq!(code, 2);
    assert!(msg.contains("output.checkpoint_minutes") && msg.contains(">= 0") && msg.contains("-1"), "{msg}");
    // a restart.bin that is not a checkpoint: the run names the file and says so
    let out = p.with_extension("out");
    let _ = std::fs::remove_dir_all(&out);
    std::fs::create_dir_all(&out).unwrap();
    std::fs::write(out.join("restart.bin"), "step,time\n").unwrap();
    let options = stiction::run::RunOptions { out: Some(out.clone()), resume: true, ..Default::default() };
    let err = stiction::run::run(&case::load(&p, &[]).unwrap(), &options).unwrap_err();
    let msg = err.to_string();
    assert_eq!(err.exit_code(), 2, "{msg}");
    assert!(msg.contains("restart.bin") && msg.contains("is not a Stiction checkpoint"), "{msg}");
}

#[test]
fn missing_group_lists_the_known_groups() {
    let p =
        scratch("missing-group.toml", &base_case(&cantilever_geo()).replace("group = \"clamp\"", "group = \"clmp\""));
    let (msg, code) = failure(&p, &[]);
    assert_eq!(code, 2);
    assert!(msg.contains("boundary[0].group") && msg.contains("'clmp'") && msg.contains("'clamp'"), "{msg}");
}

#[test]
fn non_positive_modulus_names_the_parameter() {
    let p = scratch(
        "modulus.toml",
        &base_case(&cantilever_geo()).replace("youngs_modulus = 200.0", "youngs_modulus = -1.0"),
    );
    let (msg, code) = failure(&p, &[]);
    assert_eq!(code, 2);
    assert!(msg.contains("youngs_modulus") && msg.contains("positive"), "{msg}");
}

#[test]
fn tangent_hardening_is_refused_for_an_elastic_material_and_below_zero() {
    let p = scratch("tangent-hardening.toml", &base_case(&cantilever_geo()));
    let (msg, code) = failure(&p, &["materials.steel.tangent_hardening=2.0"]);
    assert_eq!(code, 2);
    assert!(msg.contains("materials.steel.tangent_hardening") && msg.contains("j2-plasticity"), "{msg}");
    let plastic = ["materials.steel.model=\"j2-plasticity\"", "materials.steel.yield_stress=1.0"];
    let (msg, code) = failure(&p, &[plastic[0], plastic[1], "materials.steel.tangent_hardening=-2.0"]);
    assert_eq!(code, 2);
    assert!(msg.contains("tangent_hardening") && msg.contains(">= 0") && msg.contains("-2"), "{msg}");
}

#[test]
fn missing_mesh_file_names_the_file() {
    let p = scratch("missing-mesh.toml", &base_case("file = \"does-not-exist.msh\""));
    let (msg, code) = failure(&p, &[]);
    assert_eq!(code, 2);
    assert!(msg.contains("does-not-exist.msh"), "{msg}");
}

#[test]
fn wrong_element_type_for_the_analysis() {
    // a 3D tet mesh used in an axisymmetric analysis: the mesh is not planar
    let p = scratch("wrong-analysis.toml", &format!("analysis = \"axisymmetric\"\n{}", base_case(&cantilever_geo())));
    let (msg, code) = failure(&p, &[]);
    assert_eq!(code, 2);
    assert!(msg.contains("axisymmetric"), "{msg}");
}

#[test]
fn msh22_and_malformed_files_are_explained() {
    let dir = workspace_root().join("target").join("test-out").join("bad-input");
    std::fs::create_dir_all(&dir).unwrap();
    let old = dir.join("old.msh");
    std::fs::write(&old, "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n").unwrap();
    let e = stiction_meshes::read_msh(&old).unwrap_err().to_string();
    assert!(e.contains("old.msh") && e.contains("2.2") && e.contains("-format msh41"), "{e}");
    let junk = dir.join("junk.msh");
    std::fs::write(&junk, "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 2 1\n").unwrap();
    let e = stiction_meshes::read_msh(&junk).unwrap_err().to_string();
    assert!(e.contains("junk.msh"), "{e}");
    let none = dir.join("not-a-mesh.msh");
    std::fs::write(&none, "hello").unwrap();
    let e = stiction_meshes::read_msh(&none).unwrap_err().to_string();
    assert!(e.contains("not-a-mesh.msh") && e.contains("$MeshFormat"), "{e}");
}

/// Dissipation control needs a damage law; with only a reversible one (Lennard-Jones) the
/// error names the key, the laws and the alternative.
#[test]
fn dissipation_control_without_a_damage_law_is_refused() {
    let path = workspace_root().join("cases/validation/lj-block-arc-length.toml");
    let (msg, code) = failure(&path, &["solver.continuation=\"dissipation\""]);
    assert_eq!(code, 2);
    assert!(
        msg.contains("solver.continuation") && msg.contains("lennard-jones") && msg.contains("arc-length"),
        "{msg}"
    );
}

#[test]
fn a_footprint_correction_needs_a_footprint_and_a_limit_is_declared_once_with_a_valid_value() {
    let path = workspace_root().join("cases/ru-rough-sphere/rough-w6-quick.toml");
    let (msg, code) =
        failure(&path, &["interfaces.0.points.footprint_area=0.0", "interfaces.0.points.footprint_correction={}"]);
    assert_eq!(code, 2);
    assert!(msg.contains("interfaces[0].points.footprint_correction") && msg.contains("footprint_area"), "{msg}");
    let correction = |c: &str| format!("interfaces.0.points.footprint_correction={c}");
    // the named limit is the perfectly plastic body's: a hardening body needs a value
    let (msg, code) = failure(
        &path,
        &[
            &correction("{ compliance = 0.0, limit_pressure = \"von-mises-disc\" }"),
            "materials.ru.isotropic_hardening=10.0",
        ],
    );
    assert_eq!(code, 2);
    assert!(msg.contains("footprint_correction.limit_pressure") && msg.contains("hardens"), "{msg}");
    // ... and a body that yields
    let (msg, code) = failure(
        &path,
        &[
            &correction("{ compliance = 0.0, limit_pressure = \"von-mises-disc\" }"),
            "materials.ru.model=\"linear-elastic\"",
        ],
    );
    assert_eq!(code, 2);
    assert!(msg.contains("footprint_correction.limit_pressure") && msg.contains("yields"), "{msg}");
    for (given, key, expected) in [
        ("{ limit_force = -1.0 }", "limit_force", "> 0"),
        ("{ limit_force = inf }", "limit_force", "finite"),
        ("{ limit_pressure = 0.0 }", "limit_pressure", "> 0"),
        ("{ limit_pressure = nan }", "limit_pressure", "finite"),
        ("{ limit_pressure = \"bulk\" }", "limit_pressure", "von-mises-disc"),
        ("{ limit_force = 100.0, limit_pressure = 8.0 }", "limit_pressure", "given twice"),
    ] {
        let (msg, code) = failure(&path, &[&correction(given)]);
        assert_eq!(code, 2, "{given}: {msg}");
        assert!(msg.contains(&format!("footprint_correction.{key}")) && msg.contains(expected), "{given}: {msg}");
    }
}

/// A points file with a duplicated row, a point closer than the case's min_spacing, or a
/// number that is not finite is refused with the file and line (a duplicate would carry twice
/// the force at one place).
#[test]
fn a_points_file_with_a_duplicate_a_too_close_or_a_non_finite_point_names_its_line() {
    let path = workspace_root().join("cases/ru-rough-sphere/rough-w6-quick.toml");
    let points = |name: &str, rows: &str| scratch(name, &format!("x,y,height\n0.0,0.0,2.786\n{rows}"));
    let file = |p: &PathBuf| format!("interfaces.0.points.file=\"{}\"", p.display());
    let duplicate = points("duplicate-point.csv", "10.0,0.0,2.786\n0.0,0.0,2.786\n");
    let (msg, code) = failure(&path, &[&file(&duplicate), "interfaces.0.points.min_spacing=0.0"]);
    assert_eq!(code, 2);
    assert!(
        msg.contains("duplicate-point.csv' line 4") && msg.contains("line 2") && msg.contains("same point"),
        "{msg}"
    );
    let close = points("close-points.csv", "3.0,0.0,2.786\n");
    let (msg, code) = failure(&path, &[&file(&close)]);
    assert_eq!(code, 2);
    assert!(msg.contains("close-points.csv' line 3") && msg.contains("min_spacing = 3.5"), "{msg}");
    let not_finite = points("nan-point.csv", "10.0,nan,2.786\n");
    let (msg, code) = failure(&path, &[&file(&not_finite)]);
    assert_eq!(code, 2);
    assert!(msg.contains("nan-point.csv' line 3") && msg.contains("finite"), "{msg}");
}
