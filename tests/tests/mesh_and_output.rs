//! gmsh input (ASCII and binary MSH 4.1 read to the same mesh; .geo meshing is cached) and run
//! output (an interrupted run keeps every converged increment).

use std::process::Command;
use stiction_meshes::{DEFAULT_TIME_LIMIT_SECONDS, GeoOptions, GmshLimits, mesh_geo, read_msh};
use stiction_tests::{claim_output_dir, workspace_root};

fn scratch(name: &str) -> std::path::PathBuf {
    let d = claim_output_dir(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn ascii_and_binary_msh41_give_the_same_mesh_and_geo_meshing_is_cached() {
    let dir = scratch("msh-formats");
    let geo = workspace_root().join("cases/validation/cantilever.geo");
    let opts = GeoOptions { dimension: 3, order: 2, size_factor: 2.0, parameters: vec![] };
    let (_, cached) = mesh_geo(&geo, &opts, &dir, &mut GmshLimits::time(DEFAULT_TIME_LIMIT_SECONDS)).unwrap();
    let stamp = std::fs::metadata(&cached).unwrap().modified().unwrap();
    assert_eq!(
        mesh_geo(&geo, &opts, &dir, &mut GmshLimits::time(DEFAULT_TIME_LIMIT_SECONDS)).unwrap().1,
        cached,
        "same inputs, same cache file"
    );
    assert_eq!(std::fs::metadata(&cached).unwrap().modified().unwrap(), stamp, "cache hit must not re-mesh");
    let binary = dir.join("binary.msh");
    let status = Command::new("gmsh")
        .arg(&cached)
        .arg("-0")
        .arg("-bin")
        .arg("-format")
        .arg("msh41")
        .arg("-o")
        .arg(&binary)
        .output()
        .unwrap();
    assert!(status.status.success());
    let a = read_msh(&cached).unwrap();
    let b = read_msh(&binary).unwrap();
    assert_eq!(a.nodes.len(), b.nodes.len());
    assert!(a.nodes.iter().zip(&b.nodes).all(|(p, q)| (0..3).all(|k| (p[k] - q[k]).abs() < 1e-12)));
    assert_eq!(a.groups, b.groups);
    let names: Vec<&str> = a.groups.iter().map(|g| g.name.as_str()).collect();
    assert!(names.contains(&"body") && names.contains(&"clamp") && names.contains(&"tip"), "{names:?}");
    assert_eq!(a.blocks.len(), b.blocks.len());
    for (x, y) in a.blocks.iter().zip(&b.blocks) {
        assert_eq!((x.cell_type, x.physical_tag, &x.connectivity), (y.cell_type, y.physical_tag, &y.connectivity));
    }
    // 10-node tets with positive volume in gmsh order
    assert!(a.blocks.iter().any(|b| b.cell_type == stiction_core::mesh::CellType::Tet10));
}

#[test]
fn a_failed_run_keeps_its_converged_increments() {
    // Yield stress so low and increments so few that the run must give up part way: the
    // minimum increment equals the initial one, so the first failure ends the run.
    let out = scratch("failed-run");
    let case = workspace_root().join("cases/validation/jackson-green.toml");
    let sets: Vec<String> = [
        "mesh.parameters.h_contact=8.0",
        "solver.max_iterations=3",
        "steps.0.initial_increment=0.05",
        "steps.0.min_increment=0.05",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    let loaded = stiction::case::load(&case, &sets).unwrap();
    let options = stiction::run::RunOptions { out: Some(out.clone()), overwrite: true, ..Default::default() };
    let err = stiction::run::run(&loaded, &options).unwrap_err();
    assert_eq!(err.exit_code(), 1, "{err}");
    let text = std::fs::read_to_string(out.join("history.csv")).unwrap();
    let rows = text.lines().count() - 1;
    let summary = std::fs::read_to_string(out.join("summary.json")).unwrap();
    assert!(summary.contains("\"status\": \"failed\""), "{summary}");
    let vtus = std::fs::read_dir(&out)
        .unwrap()
        .filter(|e| e.as_ref().unwrap().path().extension().is_some_and(|x| x == "vtu"))
        .count();
    let pvd = std::fs::read_to_string(out.join("jackson-green.pvd")).unwrap();
    println!("failed run kept {rows} history rows and {vtus} vtu files: {err}");
    assert!(rows >= 2, "the converged increments before the failure must stay: {rows}");
    assert_eq!(pvd.matches("<DataSet").count() * 2, vtus, "the .pvd lists exactly the written solid frames");
    assert!(!std::fs::read_dir(&out).unwrap().any(|e| e.unwrap().path().to_string_lossy().ends_with(".tmp")));
}

#[test]
fn a_sweep_runs_each_value_in_its_own_folder_with_combined_plots() {
    let out = scratch("sweep");
    let case = workspace_root().join("cases/validation/hertz-axisym.toml");
    let sets: Vec<String> = [
        "mesh.parameters.h_contact=10.0",
        "sweep={ key = \"interfaces.0.approach\", values = [0.5, 1.0], label = \"approach\" }",
        "steps.0.initial_increment=0.25",
        "steps.0.max_increment=0.25",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    let options = stiction::run::RunOptions { out: Some(out.clone()), overwrite: true, ..Default::default() };
    let summaries = stiction::sweep::run_sweep(&case, &sets, &options).unwrap();
    assert_eq!(summaries.len(), 2);
    // the second run presses twice as far: Hertz F ~ d^1.5 -> ratio 2^1.5 = 2.83 (within 5%)
    let ratio = summaries[1].interfaces[0].max_force / summaries[0].interfaces[0].max_force;
    assert!((ratio / 2f64.powf(1.5) - 1.0).abs() < 0.05, "force ratio {ratio}");
    for v in ["approach=0.5", "approach=1"] {
        let dir = out.join(v);
        assert!(dir.join("history.csv").exists() && dir.join("summary.json").exists(), "{}", dir.display());
        let png = std::fs::read(dir.join("force_approach.png")).unwrap();
        assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
        // one load cycle (loading only): cycles.csv holds it with the summary's maximum force
        let cycles = std::fs::read_to_string(dir.join("cycles.csv")).unwrap();
        assert_eq!(cycles.lines().count(), 2, "{cycles}");
    }
    for s in &summaries {
        let i = &s.interfaces[0];
        assert_eq!(i.cycles.len(), 1);
        assert_eq!(i.cycles[0].max_force, i.max_force);
        assert!(i.contact_resistance_at_max_force.is_none(), "no [interfaces.resistance] given");
    }
    for f in ["combined_force_approach.png", "combined_area_approach.svg", "sweep.json"] {
        assert!(out.join(f).exists(), "{f}");
    }
    let svg = std::fs::read_to_string(out.join("combined_force_approach.svg")).unwrap();
    assert!(svg.contains("<svg") && svg.contains("approach = 0.5") && svg.contains("approach = 1"));
}
