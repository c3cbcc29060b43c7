//! The case-to-model builder on a small case (two blocks joined by a cohesive interface): the
//! step plans it derives, the solver settings, the interfaces' bookkeeping, and validation
//! that `stiction check` and `stiction run` share (both call `case::load`).

use stiction_tests::{build_case, workspace_root};

const CASE: &str = "cases/validation/two-blocks-cohesive.toml";

#[test]
fn step_plans_take_their_defaults_from_each_step_span() {
    let (_, built) =
        build_case(CASE, &["steps.0.end_time=2.0", "steps.1={ end_time = 2.5, until_separated = \"interface\" }"]);
    assert_eq!(built.steps.len(), 2);
    let (first, second) = (&built.steps[0].incrementation, &built.steps[1].incrementation);
    // the case gives initial_increment = 1; otherwise initial = span / 10, minimum = 1e-6 span,
    // maximum = span; cut and growth from [solver]
    assert_eq!((first.initial, first.minimum, first.maximum), (1.0, 2e-6, 2.0));
    assert!((second.initial - 0.05).abs() < 1e-15 && (second.maximum - 0.5).abs() < 1e-15);
    assert_eq!((first.cut_factor, first.growth_factor), (0.25, 1.5));
    assert_eq!(built.steps[1].name, "step 2");
    // until_separated names the interface: resolved to its contribution
    assert_eq!(built.steps[1].until_separated, Some(0));
    assert_eq!(built.model.contributions[0].name(), "interface");
    assert_eq!(built.interfaces[0].kind, "cohesive");
    assert_eq!(built.newton.tol_residual, 1e-8);
    assert_eq!(built.newton.max_iterations, 25);
}

#[test]
fn bad_numbers_are_refused_when_the_case_is_loaded_naming_the_key() {
    let path = workspace_root().join(CASE);
    for (set, key) in [
        ("solver.tol_residual=-1.0", "solver.tol_residual"),
        ("steps.0.end_time=-5.0", "steps[0].end_time"),
        ("steps.0.end_time=inf", "steps[0].end_time"),
        ("solver.cut_factor=1.5", "solver.cut_factor"),
        ("solver.growth_factor=nan", "solver.growth_factor"),
        ("steps.0.initial_increment=nan", "steps[0].initial_increment"),
        ("steps.0.max_increment=inf", "steps[0].max_increment"),
        ("interfaces.0.initial_gap=inf", "interfaces[0].initial_gap"),
        ("steps.0.until_separated=\"nothing\"", "steps[0].until_separated"),
    ] {
        let e = stiction::case::load(&path, &[set.to_string()]).err().unwrap_or_else(|| panic!("{set} accepted"));
        let message = e.to_string();
        assert!(message.contains(key), "{set}: {message}");
        assert_eq!(e.exit_code(), 2, "{set}");
    }
}

/// `solver.snap = "auto"` (the default) crosses a jump along the damped flow when the state it
/// lands on depends on the path: when a material (plasticity) or an interface law (damage,
/// hysteresis) keeps state. An elastic body with a reversible law is not path dependent.
#[test]
fn a_model_is_path_dependent_when_a_material_or_an_interface_law_keeps_state() {
    let lj = "cases/validation/lj-sphere.toml";
    let coarse = "mesh.parameters.h_contact=8.0";
    let (_, elastic) = build_case(lj, &[coarse]);
    assert!(!elastic.model.path_dependent(), "linear elastic body, Lennard-Jones law");
    let (_, plastic) =
        build_case(lj, &[coarse, "materials.ru.model=\"j2-plasticity\"", "materials.ru.yield_stress=3.42"]);
    assert!(plastic.model.path_dependent(), "J2 plasticity keeps the plastic strain");
    let (_, bonded) = build_case(CASE, &[]);
    assert!(bonded.model.path_dependent(), "elastic blocks, but the cohesive law keeps its damage");
}
