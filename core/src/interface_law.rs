//! The interface-law trait: a law maps a gap (and its history) to a traction or a force, with
//! its tangent, the way a material maps strain to stress.
//!
//! Sign conventions: the gap g is positive when the surfaces are apart; the normal value is
//! positive when it pushes the surfaces apart (compressive contact), negative when it pulls them
//! together (adhesion). State follows the same trial/commit/roll-back lifecycle as materials.

/// What the law's value means.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LawKind {
    /// A traction (force per area), integrated over the interface surface.
    TractionPerArea,
    /// A force per discrete point (e.g. one nano-asperity).
    ForcePerPoint,
}

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

/// The result of one evaluation.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct LawResponse {
    /// Normal traction or force (positive pushes apart).
    pub value: f64,
    /// d value / d gap.
    pub tangent: f64,
    /// Whether the point counts as in contact.
    pub in_contact: bool,
    /// Contact area carried by this point (force-per-point laws; 0 for traction laws, whose
    /// area is the integration weight of the point when in contact).
    pub area: f64,
}

/// The result of one mixed-mode evaluation, in the interface point's local frame (normal,
/// tangential 1, tangential 2): value_i is the force per area on the moving side along axis i
/// (value_i = -d psi / d gap_i for a law with energy psi), tangent[i][j] = d value_i / d gap_j.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct MixedLawResponse {
    pub value: [f64; 3],
    pub tangent: [[f64; 3]; 3],
    pub in_contact: bool,
    pub area: f64,
}

impl From<LawResponse> for MixedLawResponse {
    /// A normal-only law seen as mixed mode: no tangential value, no coupling.
    fn from(r: LawResponse) -> Self {
        let mut tangent = [[0.0; 3]; 3];
        tangent[0][0] = r.tangent;
        Self { value: [r.value, 0.0, 0.0], tangent, in_contact: r.in_contact, area: r.area }
    }
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
        self.evaluate(gap[0], state_committed, state_trial).map(MixedLawResponse::from)
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
