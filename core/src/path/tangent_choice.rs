//! Which material tangent the solvers see: the consistent one, or a material's stabilized twin
//! ([`crate::material::Material::stabilized`]: the same stresses and states, a tangent kept
//! regular where the consistent one loses rank). Both give the same converged solutions; they
//! differ in which increments Newton converges on. The consistent tangent converges
//! quadratically but is singular along the flow direction of a perfectly plastic point, so
//! Newton can cycle on an adhesive neck at its limit load; the stabilized one converges there,
//! linearly, and can fail where the consistent one converges.
//!
//! With [`TangentChoice::SwitchOnFailure`] (the default) the run starts on the consistent
//! tangent, and an attempt that fails to converge from a state where some point flows (where
//! the two tangents differ; [`crate::material::Material::flowing`]) switches to the other
//! tangent for the attempts after it (the cut increment), at most once per committed
//! increment, and a snap
//! that fails (which would end the run) is retried on the other tangent; the tangent that
//! converged is kept until an attempt fails on it.

use crate::model::Model;
use crate::nonlinear::IncrementFailure;

/// Which material tangent the solvers see.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum TangentChoice {
    /// The consistent tangent throughout.
    Consistent,
    /// The consistent tangent, switched to the other one after a failed attempt (see the
    /// module documentation).
    #[default]
    SwitchOnFailure,
    /// The stabilized tangent throughout (where a material has one).
    Stabilized,
}

/// The tangent switch of a run.
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct TangentSwitch {
    choice: TangentChoice,
    /// Set by a switch, cleared by a commit.
    switched_since_commit: bool,
    /// Switches so far.
    pub switches: usize,
}

impl TangentSwitch {
    /// Sets the model's tangent at the start of a run.
    pub fn start(choice: TangentChoice, model: &mut Model) -> Self {
        model.stabilize_tangent(choice == TangentChoice::Stabilized);
        Self { choice, switched_since_commit: false, switches: 0 }
    }

    /// After a failed attempt, the model rolled back: switches the model to the other tangent
    /// if the choice allows, a point of a material with a stabilized twin flows in the state
    /// the attempt started from (elsewhere the tangents are the same), the failure is one of
    /// convergence (not of a law or of the path constraint) and no switch was made since the
    /// last commit. Returns what was done, for the run's messages.
    pub fn after_failure(&mut self, model: &mut Model, failure: &IncrementFailure) -> Option<String> {
        if self.switched_since_commit {
            return None;
        }
        self.switch(model, failure)
    }

    /// After a failed snap (which would end the run): [`TangentSwitch::after_failure`], also
    /// when a switch was made since the last commit.
    pub fn after_failed_snap(&mut self, model: &mut Model, failure: &IncrementFailure) -> Option<String> {
        self.switch(model, failure)
    }

    fn switch(&mut self, model: &mut Model, failure: &IncrementFailure) -> Option<String> {
        let convergence = failure.is_no_convergence() || matches!(failure, IncrementFailure::FlowUnsettled { .. });
        if self.choice != TangentChoice::SwitchOnFailure || !convergence || !model.flowing_where_stabilizable() {
            return None;
        }
        let stabilize = !model.tangent_stabilized();
        model.stabilize_tangent(stabilize);
        self.switched_since_commit = true;
        self.switches += 1;
        Some(if stabilize { "switched to the stabilized tangent" } else { "switched to the consistent tangent" }.into())
    }

    /// The switch of a run resumed from a checkpoint with `choice`: where the choice is the
    /// checkpointed run's, the model gets the tangent it had then (`stabilized`) and the
    /// switch goes on as it was; otherwise the new choice starts, counting the earlier switches.
    pub fn resumed(self, choice: TangentChoice, model: &mut Model, stabilized: bool) -> Self {
        if choice != self.choice {
            return Self { switches: self.switches, ..Self::start(choice, model) };
        }
        model.stabilize_tangent(stabilized);
        self
    }

    /// A committed increment: the next failure may switch again.
    pub fn committed(&mut self) {
        self.switched_since_commit = false;
    }
}
