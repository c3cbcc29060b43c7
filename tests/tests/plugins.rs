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

/// The mixed-mode cohesive-zone law through the C ABI (the plugin shared library): bit for bit
/// the statically linked law along a mixed opening path, and conformant.
#[test]
fn the_mixed_mode_cohesive_plugin_matches_the_built_in_law_and_passes_conformance() {
    cargo_build(&["-p", "stiction-plugin-cohesive-zone"]);
    let path = build_dir().join("debug").join("libstiction_plugin_cohesive_zone.so");
    let registry = LawRegistry::new(&[]);
    let ctx = LawContext { modulus: 1.0, face_size: 1.0 };
    let params: Vec<(String, f64)> = [
        ("G_c", 0.8),
        ("sigma_max", 6.0),
        ("penalty", 2e4),
        ("G_IIc", 2.4),
        ("tau_max", 9.0),
        ("initially_bonded", 1.0),
    ]
    .iter()
    .map(|(k, v)| (k.to_string(), *v))
    .collect();
    let dynamic = make_law(&registry, path.to_str().unwrap(), &workspace_root(), &params, None, &ctx).unwrap();
    let builtin = make_law(&registry, "cohesive-zone", &workspace_root(), &params, None, &ctx).unwrap();
    assert_eq!((dynamic.gap_dimension(), builtin.gap_dimension()), (3, 3));
    let (mut sa, mut sb) = (vec![0.0; 3], vec![0.0; 3]);
    dynamic.initialize_state(&mut sa);
    builtin.initialize_state(&mut sb);
    let mut grew = false;
    for k in 0..200 {
        let s = k as f64 / 200.0;
        let delta = [6e-4 * (8.0 * s).sin(), 8e-4 * s, -3e-4 * s * s];
        let (mut ta, mut tb) = (vec![0.0; 3], vec![0.0; 3]);
        let a = dynamic.evaluate_mixed(delta, &sa, &mut ta).unwrap();
        let b = builtin.evaluate_mixed(delta, &sb, &mut tb).unwrap();
        assert_eq!((a, &ta), (b, &tb), "opening {delta:?}");
        grew |= tb[2] > sb[2];
        (sa, sb) = (ta, tb);
    }
    assert!(grew, "the path damages the interface");
    for r in stiction::plugin_check::check(&dynamic, 2e-4) {
        println!("{}: {} ({})", if r.passed { "PASS" } else { "FAIL" }, r.name, r.detail);
        assert!(r.passed, "{}: {}", r.name, r.detail);
    }
}

/// The conformance check catches a mixed-mode law whose shear tangent is 10% off, and one whose
/// normal-only evaluation disagrees with its mixed evaluation.
#[test]
fn plugin_check_fails_a_wrong_mixed_mode_tangent() {
    use stiction_law_sdk::abi::DescriptorHolder;
    use stiction_law_sdk::{Law, LawKind, MixedResponse, Parameter, Response};
    /// A quadratic interface energy psi = k/2 (g_n^2 + g_s^2) with a wrong shear tangent; its
    /// normal-only evaluation doubles the stiffness when `inconsistent` is set.
    struct WrongShear {
        inconsistent: bool,
    }
    impl Law for WrongShear {
        const NAME: &'static std::ffi::CStr = c"wrong-shear";
        const VERSION: &'static std::ffi::CStr = c"0.0.1";
        const KIND: LawKind = LawKind::TractionPerArea;
        const N_STATE: usize = 0;
        const GAP_DIMENSION: usize = 3;
        fn parameters() -> Vec<Parameter> {
            vec![Parameter::optional(c"inconsistent", c"-", c"1: normal-only evaluation disagrees", 0.0, 0.0, 1.0)]
        }
        fn create(p: &[f64], _: &str) -> Result<Self, String> {
            Ok(Self { inconsistent: p[0] == 1.0 })
        }
        fn evaluate(&self, g: f64, _: &[f64], _: &mut [f64]) -> Result<Response, String> {
            let k = if self.inconsistent { 2.0 } else { 1.0 };
            Ok(Response { value: -k * g, tangent: -k, in_contact: g < 0.0, area: 0.0 })
        }
        fn evaluate_mixed(&self, d: [f64; 3], _: &[f64], _: &mut [f64]) -> Result<MixedResponse, String> {
            let mut tangent = [[0.0; 3]; 3];
            tangent[0][0] = -1.0;
            tangent[1][1] = -1.1;
            tangent[2][2] = -1.0;
            Ok(MixedResponse { value: d.map(|x| -x), tangent, in_contact: d[0] < 0.0, area: 0.0 })
        }
    }
    static HOLDER: std::sync::OnceLock<DescriptorHolder> = std::sync::OnceLock::new();
    let holder = HOLDER.get_or_init(DescriptorHolder::new::<WrongShear>);
    let lib = Arc::new(unsafe { LawLibrary::from_static(holder.descriptor()) }.unwrap());
    for (flag, failing) in [(0.0, "mixed-mode tangent"), (1.0, "normal-only evaluation")] {
        let law: Arc<dyn InterfaceLaw> = Arc::new(lib.instantiate(&[flag], "").unwrap());
        let results = stiction::plugin_check::check(&law, 1.0);
        let r = results.iter().find(|r| r.name.starts_with(failing)).unwrap();
        assert!(!r.passed, "{failing} should fail: {}", r.detail);
    }
}
