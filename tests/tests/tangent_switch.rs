//! The tangent switch of `solver.tangent` ([`TangentSwitch`]): which failures switch the
//! model's material tangent between the consistent and the stabilized one, and how often.
//! The runs it enables are in `perfectly_plastic_neck.rs`.

use stiction_core::error::CoreError;
use stiction_core::model::Model;
use stiction_core::nonlinear::IncrementFailure;
use stiction_core::path::TangentChoice;
use stiction_core::path::tangent_choice::TangentSwitch;
use stiction_core::problem::NonlinearProblem;
use stiction_tests::build_case;

fn diverged() -> IncrementFailure {
    IncrementFailure::Diverged { iterations: 25, residual: 1.0 }
}

/// Commits a displacement field that strains the body far beyond yield (free values of 0 to
/// 0.6 nm, dof by dof, over elements a few nm across): points flow.
fn commit_a_flowing_state(model: &mut Model) {
    let n = model.free_values().len();
    let values: Vec<f64> = (0..n).map(|k| 0.1 * (k % 7) as f64).collect();
    model.set_free_values(&values);
    model.assemble(false).unwrap();
    model.commit();
}

#[test]
fn a_failure_to_converge_switches_the_tangent_once_per_committed_increment() {
    let (_, mut built) = build_case("cases/validation/jackson-green.toml", &[]);
    let model = &mut built.model;
    assert!(model.can_stabilize_tangent(), "a perfectly plastic J2 material has a stabilized twin");
    let mut switch = TangentSwitch::start(TangentChoice::SwitchOnFailure, model);
    assert_eq!(switch.after_failure(model, &diverged()), None, "nothing flows: the tangents are the same");
    commit_a_flowing_state(model);
    assert!(model.flowing_where_stabilizable());
    assert!(!model.tangent_stabilized(), "the run starts on the consistent tangent");
    let law = IncrementFailure::Error(CoreError::Invalid("a law failed".into()));
    assert_eq!(switch.after_failure(model, &law), None, "a law failure is no failure to converge");
    assert_eq!(switch.after_failure(model, &IncrementFailure::NoDissipation), None);
    assert!(switch.after_failure(model, &diverged()).is_some_and(|m| m.contains("stabilized")));
    assert!(model.tangent_stabilized());
    assert_eq!(switch.after_failure(model, &diverged()), None, "once per committed increment");
    assert!(switch.after_failed_snap(model, &diverged()).is_some_and(|m| m.contains("consistent")));
    assert!(!model.tangent_stabilized(), "a failed snap switches back even before a commit");
    switch.committed();
    let unsettled = IncrementFailure::FlowUnsettled { steps: 5000, residual: 1.0 };
    assert!(switch.after_failure(model, &unsettled).is_some());
    assert!(model.tangent_stabilized());
    assert_eq!(switch.switches, 3);
}

#[test]
fn a_fixed_choice_or_an_elastic_model_never_switches() {
    let (_, mut built) = build_case("cases/validation/jackson-green.toml", &[]);
    commit_a_flowing_state(&mut built.model);
    for (choice, stabilized) in [(TangentChoice::Consistent, false), (TangentChoice::Stabilized, true)] {
        let mut switch = TangentSwitch::start(choice, &mut built.model);
        assert_eq!(built.model.tangent_stabilized(), stabilized);
        assert_eq!(switch.after_failure(&mut built.model, &diverged()), None);
        assert_eq!(switch.after_failed_snap(&mut built.model, &diverged()), None);
        assert_eq!(built.model.tangent_stabilized(), stabilized);
    }
    let (_, mut elastic) = build_case("cases/validation/hertz-axisym.toml", &[]);
    assert!(!elastic.model.can_stabilize_tangent());
    commit_a_flowing_state(&mut elastic.model);
    let mut switch = TangentSwitch::start(TangentChoice::SwitchOnFailure, &mut elastic.model);
    assert_eq!(switch.after_failure(&mut elastic.model, &diverged()), None);
    assert_eq!(switch.switches, 0);
}

#[test]
fn a_case_names_the_tangent_choices_it_accepts() {
    let path = stiction_tests::workspace_root().join("cases/validation/jackson-green.toml");
    let error = stiction::case::load(&path, &["solver.tangent=\"secant\"".to_string()]).unwrap_err().to_string();
    for expected in ["tangent", "secant", "switch-on-failure", "consistent", "stabilized"] {
        assert!(error.contains(expected), "{error}");
    }
}
