//! The material trait: a stress update with consistent tangent and explicit state lifecycle.
//!
//! State lives in caller-owned flat arrays, `n_state()` numbers per integration point. The solver
//! keeps two copies: *committed* (end of the last converged step) and *trial* (written by every
//! call to [`Material::update`] from the committed copy). Committing copies trial to committed;
//! rolling back (a cut step) simply discards trial. A material never mutates committed state.

use crate::voigt::{Strain, Stress, Tangent};
use std::sync::Arc;

/// Why a stress update failed (reported with element, point and step by the caller).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{0}")]
pub struct MaterialError(pub String);

/// A small-strain constitutive law.
pub trait Material: Send + Sync {
    /// Name used in messages and output.
    fn name(&self) -> &str;

    /// Number of state variables per integration point.
    fn n_state(&self) -> usize {
        0
    }

    /// Initial state at an integration point (zeros unless overridden).
    fn initialize_state(&self, state: &mut [f64]) {
        state.fill(0.0);
    }

    /// Stress update: given the total strain at the end of the increment and the committed state,
    /// compute the stress, the consistent (algorithmic) tangent d(stress)/d(strain) and the trial
    /// state.
    fn update(
        &self,
        strain: &Strain,
        state_committed: &[f64],
        state_trial: &mut [f64],
        stress: &mut Stress,
        tangent: &mut Tangent,
    ) -> Result<(), MaterialError>;

    /// Names of scalar integration-point outputs derived from the state (e.g. equivalent
    /// plastic strain).
    fn output_names(&self) -> Vec<&'static str> {
        Vec::new()
    }

    /// Values of [`Material::output_names`] for one point, written into `out`.
    fn outputs(&self, _state: &[f64], _out: &mut [f64]) {}

    /// Energy dissipated per unit volume up to this state (plastic work), for energy balances.
    fn dissipation_density(&self, _state: &[f64]) -> f64 {
        0.0
    }

    /// A stiffness scale (e.g. Young's modulus) used to choose penalties and tolerances.
    fn stiffness_scale(&self) -> f64;

    /// A twin of this law with a *stabilized tangent*, for a solver whose iterations fail on
    /// the consistent one: the same stress update, states and dissipation (so the converged
    /// solutions are this law's), with a tangent kept regular where the consistent one loses
    /// rank (the flow direction of a perfectly plastic point). None (the default): the law's
    /// tangent needs no stabilizing.
    fn stabilized(&self) -> Option<Arc<dyn Material>> {
        None
    }

    /// Whether a point with this state flows, i.e. whether the stabilized twin's tangent
    /// differs from this law's there (a solver switches tangents only where one does). False
    /// by default.
    fn flowing(&self, _state: &[f64]) -> bool {
        false
    }
}
