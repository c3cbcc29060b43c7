//! The interface-law trait: a law maps a gap (and its history) to a traction or a force, with
//! its tangent, the way a material maps strain to stress.
//!
//! Sign conventions: the gap g is positive when the surfaces are apart; the normal value is
//! positive when it pushes the surfaces apart (compressive contact), negative when it pulls them
//! together (adhesion). State follows the same trial/commit/roll-back lifecycle as materials.

/// The law's kind and its responses are the plugin SDK's own types (one definition for the C
/// ABI, the SDK and the host): `LawResponse` is [`stiction_law_sdk::Response`] and
/// `MixedLawResponse` is [`stiction_law_sdk::MixedResponse`] (value_i = -d psi / d gap_i in the
/// point's local frame, tangent[i][j] = d value_i / d gap_j).
pub use stiction_law_sdk::{LawKind, MixedResponse as MixedLawResponse, Response as LawResponse};

/// A parameter a law accepts, so hosts can validate case files generically.
#[derive(Debug, Clone, PartialEq)]
pub struct ParameterSpec {
    pub name: String,
    pub unit: String,
    pub description: String,
    /// `None`: the parameter is required.
    pub default: Option<f64>,
    /// Inclusive bounds.
    pub min: f64,
    pub max: f64,
}

/// Why a law could not be evaluated.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{0}")]
pub struct LawError(pub String);

/// A normal interface law.
pub trait InterfaceLaw: Send + Sync {
    fn name(&self) -> &str;
    fn kind(&self) -> LawKind;
    fn n_state(&self) -> usize {
        0
    }
    fn initialize_state(&self, state: &mut [f64]) {
        state.fill(0.0);
    }
    /// Value and tangent at gap `gap` from the committed state; writes the trial state.
    fn evaluate(&self, gap: f64, state_committed: &[f64], state_trial: &mut [f64]) -> Result<LawResponse, LawError>;
    /// Names of the state variables, for output.
    fn state_names(&self) -> Vec<String> {
        Vec::new()
    }
    /// 1: the law sees the normal gap only; 3: mixed mode (normal and two tangential openings).
    fn gap_dimension(&self) -> usize {
        1
    }
    /// Mixed-mode value and tangent at the local opening (normal, tangential 1, tangential 2).
    /// The default is the normal-only law. `evaluate(g)` is the normal part of
    /// `evaluate_mixed([g, 0, 0])`.
    fn evaluate_mixed(
        &self,
        gap: [f64; 3],
        state_committed: &[f64],
        state_trial: &mut [f64],
    ) -> Result<MixedLawResponse, LawError> {
        self.evaluate(gap[0], state_committed, state_trial).map(MixedLawResponse::normal_only)
    }
}

/// Checks `given` (name, value) pairs against `specs`: unknown names, missing required values
/// and out-of-range values are errors naming the parameter. Returns values in `specs` order.
pub fn resolve_parameters(law: &str, specs: &[ParameterSpec], given: &[(String, f64)]) -> Result<Vec<f64>, String> {
    for (name, _) in given {
        if !specs.iter().any(|s| &s.name == name) {
            let known: Vec<&str> = specs.iter().map(|s| s.name.as_str()).collect();
            return Err(format!("law '{law}' has no parameter '{name}' (known: {})", known.join(", ")));
        }
    }
    specs
        .iter()
        .map(|s| {
            let v = given.iter().find(|(n, _)| *n == s.name).map(|(_, v)| *v).or(s.default);
            let v = v.ok_or_else(|| {
                format!("law '{law}' needs parameter '{}' ({}, in {})", s.name, s.description, s.unit)
            })?;
            if !(v >= s.min && v <= s.max) {
                return Err(format!(
                    "law '{law}': parameter '{}' = {v} is outside its range [{}, {}] ({})",
                    s.name, s.min, s.max, s.unit
                ));
            }
            Ok(v)
        })
        .collect()
}
