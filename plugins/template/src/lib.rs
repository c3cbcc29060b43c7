//! Template interface law: exponential adhesion (a universal-binding-energy form),
//! sigma(g) = -(w / delta) (g / delta) exp(-g / delta),
//! positive (repulsive) for g < 0, adhesive for g > 0 with peak w / (e delta) at g = delta;
//! the work of separation from g = 0 to infinity is w. d sigma / d g =
//! -(w / delta^2) (1 - g / delta) exp(-g / delta).
//!
//! Edit NAME, the parameters, `create` and `evaluate`. Conventions (see stiction-law-sdk):
//! gap positive when open; value positive when it pushes the surfaces apart; `tangent` is
//! d value / d gap; `evaluate` must not mutate `self` and must write the whole trial state.
//! A mixed-mode law (normal and tangential opening, e.g. for cohesive elements) also sets
//! `const GAP_DIMENSION: usize = 3` and implements `evaluate_mixed` (value vector and 3 x 3
//! tangent in the local frame; see the `cohesive-zone` law for an example).

use stiction_law_sdk::{Law, LawKind, Parameter, Response, export_law};

pub struct ExponentialAdhesion {
    w: f64,
    delta: f64,
}

impl Law for ExponentialAdhesion {
    const NAME: &'static std::ffi::CStr = c"exponential-adhesion";
    const VERSION: &'static std::ffi::CStr = c"0.1.0";
    const KIND: LawKind = LawKind::TractionPerArea;
    const N_STATE: usize = 0;

    fn parameters() -> Vec<Parameter> {
        vec![
            Parameter::required(c"w", c"energy/area", c"work of separation", 0.0, f64::INFINITY),
            Parameter::optional(c"delta", c"length", c"characteristic length", 0.2, 1e-9, f64::INFINITY),
        ]
    }

    fn create(p: &[f64], _config: &str) -> Result<Self, String> {
        Ok(Self { w: p[0], delta: p[1] })
    }

    fn evaluate(&self, gap: f64, _old: &[f64], _new: &mut [f64]) -> Result<Response, String> {
        // Cap the exponential far inside the body so extreme iterates stay finite.
        let x = (gap / self.delta).max(-30.0);
        let e = (-x).exp();
        let c = self.w / self.delta;
        let value = -c * x * e;
        let tangent = if gap / self.delta > -30.0 { -c / self.delta * (1.0 - x) * e } else { 0.0 };
        Ok(Response { value, tangent, in_contact: gap < 0.0, area: 0.0 })
    }
}

export_law!(ExponentialAdhesion);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tangent_is_the_derivative_of_the_traction() {
        let law = ExponentialAdhesion::create(&[2.0, 0.3], "").unwrap();
        for g in [-0.4, -0.05, 0.1, 0.3, 1.5] {
            let h = 1e-7;
            let f = |x: f64| law.evaluate(x, &[], &mut []).unwrap().value;
            let fd = (f(g + h) - f(g - h)) / (2.0 * h);
            assert!((fd - law.evaluate(g, &[], &mut []).unwrap().tangent).abs() < 1e-6);
        }
    }
}
