//! `frictionless-contact` (the law; `plugin/` exports it as a shared library): non-adhesive hard contact enforced by a penalty,
//! sigma(g) = k max(0, -g), d sigma / d g = -k for g < 0.
//!
//! Parameter `penalty` (stress per length). 0 (the default) asks the host to choose
//! k = 100 E / h from the stiffest material's modulus E and the interface's face size h.

use stiction_law_sdk::{Law, LawKind, Parameter, Response};

pub struct FrictionlessContact {
    pub penalty: f64,
}

impl Law for FrictionlessContact {
    const NAME: &'static std::ffi::CStr = c"frictionless-contact";
    const VERSION: &'static std::ffi::CStr = c"0.1.0";
    const KIND: LawKind = LawKind::TractionPerArea;
    const N_STATE: usize = 0;

    fn parameters() -> Vec<Parameter> {
        vec![Parameter::optional(
            c"penalty",
            c"stress/length",
            c"normal penalty stiffness k; 0 = chosen by the host (100 E / h)",
            0.0,
            0.0,
            f64::INFINITY,
        )]
    }

    fn create(p: &[f64], _config: &str) -> Result<Self, String> {
        if !(p[0] > 0.0 && p[0].is_finite()) {
            return Err(format!("penalty must be positive and finite, got {}", p[0]));
        }
        Ok(Self { penalty: p[0] })
    }

    fn evaluate(&self, gap: f64, _old: &[f64], _new: &mut [f64]) -> Result<Response, String> {
        Ok(if gap < 0.0 {
            Response { value: -self.penalty * gap, tangent: -self.penalty, in_contact: true, area: 0.0 }
        } else {
            Response::default()
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn tangent_matches_finite_differences_away_from_the_kink() {
        let law = FrictionlessContact::create(&[50.0], "").unwrap();
        for g in [-0.3, -0.01, 0.02, 0.5] {
            let h = 1e-7;
            let f = |x: f64| law.evaluate(x, &[], &mut []).unwrap().value;
            let fd = (f(g + h) - f(g - h)) / (2.0 * h);
            assert!((fd - law.evaluate(g, &[], &mut []).unwrap().tangent).abs() < 1e-6);
        }
        assert!(FrictionlessContact::create(&[0.0], "").is_err());
    }
}
