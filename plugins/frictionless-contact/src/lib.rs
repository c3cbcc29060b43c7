//! `frictionless-contact`: non-adhesive hard contact enforced by a penalty,
//! sigma(g) = k max(0, -g), d sigma / d g = -k for g < 0.
//!
//! Parameter `penalty` (stress per length). When it is 0 (the default) the host chooses
//! k = 100 E / h from the stiffest material's modulus E and the interface's face size h.

use stiction_core::interface_law::{InterfaceLaw, LawError, LawKind, LawResponse, ParameterSpec};

pub const NAME: &str = "frictionless-contact";

pub fn parameters() -> Vec<ParameterSpec> {
    vec![ParameterSpec {
        name: "penalty",
        unit: "stress/length",
        description: "normal penalty stiffness k; 0 = chosen from the mesh and modulus (100 E / h)",
        default: Some(0.0),
        min: 0.0,
        max: f64::INFINITY,
    }]
}

#[derive(Debug, Clone)]
pub struct FrictionlessContact {
    pub penalty: f64,
}

impl FrictionlessContact {
    pub fn new(penalty: f64) -> Result<Self, LawError> {
        if !(penalty > 0.0 && penalty.is_finite()) {
            return Err(LawError(format!("{NAME}: penalty must be positive and finite, got {penalty}")));
        }
        Ok(Self { penalty })
    }
}

impl InterfaceLaw for FrictionlessContact {
    fn name(&self) -> &str {
        NAME
    }
    fn kind(&self) -> LawKind {
        LawKind::TractionPerArea
    }
    fn evaluate(&self, gap: f64, _old: &[f64], _new: &mut [f64]) -> Result<LawResponse, LawError> {
        Ok(if gap < 0.0 {
            LawResponse { value: -self.penalty * gap, tangent: -self.penalty, in_contact: true, area: 0.0 }
        } else {
            LawResponse::default()
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn tangent_matches_finite_differences_away_from_the_kink() {
        let law = FrictionlessContact::new(50.0).unwrap();
        for g in [-0.3, -0.01, 0.02, 0.5] {
            let h = 1e-7;
            let f = |x: f64| law.evaluate(x, &[], &mut []).unwrap().value;
            let fd = (f(g + h) - f(g - h)) / (2.0 * h);
            assert!((fd - law.evaluate(g, &[], &mut []).unwrap().tangent).abs() < 1e-6);
        }
        assert!(FrictionlessContact::new(0.0).is_err());
    }
}
