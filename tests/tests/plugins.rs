//! Interface-law plugins end to end: the template crate (outside the workspace) and the shipped
//! Lennard-Jones plugin are compiled as shared libraries, loaded through the C ABI, checked,
//! compared with closed forms / the statically linked law, and used in a case.

use std::path::PathBuf;
use std::process::Command;
use std::sync::Arc;
use stiction::laws::{LawContext, LawRegistry, make_law};
use stiction_core::interface_law::InterfaceLaw;
use stiction_interfaces::plugin::LawLibrary;
use stiction_tests::{run_case, workspace_root};

fn build_dir() -> PathBuf {
    workspace_root().join("target").join("plugin-build")
}

/// Builds with cargo into a separate target directory (the test's own cargo holds the main one).
fn cargo_build(args: &[&str]) {
    let cargo = option_env!("CARGO").unwrap_or("cargo");
    let out = Command::new(cargo)
        .args(["build", "--quiet", "--target-dir"])
        .arg(build_dir())
        .args(args)
        .current_dir(workspace_root())
        .output()
        .expect("cargo runs");
    assert!(out.status.success(), "cargo build {args:?} failed:\n{}", String::from_utf8_lossy(&out.stderr));
}

fn template_library() -> PathBuf {
    cargo_build(&["--manifest-path", "plugins/template/Cargo.toml"]);
    build_dir().join("debug").join("libmy_stiction_law.so")
}

#[test]
fn the_template_law_builds_loads_passes_conformance_and_runs_in_a_case() {
    let path = template_library();
    let lib = Arc::new(LawLibrary::open(&path).unwrap_or_else(|e| panic!("{e}")));
    assert_eq!(lib.name, "exponential-adhesion");
    let names: Vec<&str> = lib.parameters.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(names, ["w", "delta"]);
    // closed form: sigma = -(w/delta)(g/delta) exp(-g/delta)
    let (w, delta): (f64, f64) = (0.5, 0.3);
    let law = lib.instantiate(&[w, delta], "").unwrap();
    for g in [-0.2f64, 0.0, 0.1, 0.3, 1.0] {
        let r = law.evaluate(g, &[], &mut []).unwrap();
        let exact = -(w / delta) * (g / delta) * (-g / delta).exp();
        assert!((r.value - exact).abs() < 1e-14, "g = {g}: {} vs {exact}", r.value);
    }
    let shared: Arc<dyn InterfaceLaw> = Arc::new(law);
    for r in stiction::plugin_check::check(&shared, delta) {
        assert!(r.passed, "{}: {}", r.name, r.detail);
    }
    // a case that names the plugin by name through plugin_path
    let dir = path.parent().unwrap().display().to_string();
    let (_, summary) = run_case(
        "cases/validation/hertz-axisym.toml",
        &[
            &format!("plugin_path=[\"{dir}\"]"),
            "interfaces.0.law=\"exponential-adhesion\"",
            "interfaces.0.parameters={ w = 0.5, delta = 0.3 }",
            "interfaces.0.approach=0.2",
            "mesh.parameters.h_contact=8.0",
        ],
        "plugin-template-case",
    );
    assert_eq!(summary.status, "completed");
    let text = std::fs::read_to_string(summary.output_directory.join("history.csv")).unwrap();
    let last: Vec<f64> = text.lines().last().unwrap().split(',').map(|x| x.parse().unwrap()).collect();
    assert!(last.iter().all(|v| v.is_finite()));
}

#[test]
fn the_lennard_jones_plugin_library_matches_the_built_in_law_bit_for_bit() {
    cargo_build(&["-p", "stiction-plugin-lennard-jones"]);
    let path = build_dir().join("debug").join("libstiction_plugin_lennard_jones.so");
    let registry = LawRegistry::new(&[]);
    let ctx = LawContext { modulus: 1.0, face_size: 1.0 };
    let params = [("w".to_string(), 3.0), ("z0".to_string(), 0.169)];
    let dynamic = make_law(&registry, path.to_str().unwrap(), &workspace_root(), &params, None, &ctx).unwrap();
    let builtin = make_law(&registry, "lennard-jones", &workspace_root(), &params, None, &ctx).unwrap();
    for k in 0..200 {
        let g = -0.1 + 0.01 * k as f64;
        let a = dynamic.evaluate(g, &[], &mut []).unwrap();
        let b = builtin.evaluate(g, &[], &mut []).unwrap();
        assert_eq!(a, b, "gap {g}");
    }
}

#[test]
fn a_missing_law_says_where_it_looked_and_bad_parameters_name_the_key() {
    let registry = LawRegistry::new(&[PathBuf::from("/nonexistent/plugins")]);
    let ctx = LawContext { modulus: 1.0, face_size: 1.0 };
    let e = make_law(&registry, "no-such-law", &workspace_root(), &[], None, &ctx).err().unwrap();
    assert!(
        e.contains("no-such-law") && e.contains("/nonexistent/plugins") && e.contains("STICTION_PLUGIN_PATH"),
        "{e}"
    );
    let e = make_law(&registry, "lennard-jones", &workspace_root(), &[("w".into(), 1.0)], None, &ctx).err().unwrap();
    assert!(e.contains("z0") && e.contains("needs parameter"), "{e}");
    let e =
        make_law(&registry, "lennard-jones", &workspace_root(), &[("w".into(), -1.0), ("z0".into(), 0.1)], None, &ctx)
            .err()
            .unwrap();
    assert!(e.contains("'w'") && e.contains("outside its range"), "{e}");
    let e =
        make_law(&registry, "lennard-jones", &workspace_root(), &[("gamma".into(), 1.0)], None, &ctx).err().unwrap();
    assert!(e.contains("no parameter 'gamma'"), "{e}");
    let e = make_law(&registry, "target/nothing/libx.so", &workspace_root(), &[], None, &ctx).err().unwrap();
    assert!(e.contains("libx.so"), "{e}");
}
