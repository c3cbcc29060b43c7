//! `frictionless-contact` (the law; `plugin/` exports it as a shared library): non-adhesive hard contact enforced by a penalty,
//! sigma(g) = k max(0, -g), d sigma / d g = -k for g < 0.
//!
//! Optional `smoothing` eps > 0 rounds the kink at g = 0 (C1 instead of C0, which keeps Newton
//! from cycling when many points sit at zero gap, e.g. the faces of a pre-crack under shear):
//! sigma = k g^2 / (2 eps) for -eps < g < 0 and k (-g - eps / 2) for g <= -eps.
//!
//! Optional `no_separation = 1` (ABAQUS's NO SEPARATION surface behaviour): once the surfaces
//! touch they stay together normally, sigma = -k g on both sides of zero, while sliding stays
//! free; e.g. the faces of an end-notched-flexure pre-crack.
//!
//! Parameter `penalty` (stress per length). 0 (the default) asks the host to choose
//! k = 100 E / h from the stiffest material's modulus E and the interface's face size h.

use stiction_law_sdk::{Law, LawKind, Parameter, Response};

pub struct FrictionlessContact {
    pub penalty: f64,
    pub no_separation: bool,
    pub smoothing: f64,
}

impl Law for FrictionlessContact {
    const NAME: &'static std::ffi::CStr = c"frictionless-contact";
    const VERSION: &'static std::ffi::CStr = c"0.1.0";
    const KIND: LawKind = LawKind::TractionPerArea;
    const N_STATE: usize = 0;

    fn parameters() -> Vec<Parameter> {
        vec![
            Parameter::optional(
                c"penalty",
                c"stress/length",
                c"normal penalty stiffness k; 0 = chosen by the host (100 E / h)",
                0.0,
                0.0,
                f64::INFINITY,
            ),
            Parameter::optional(
                c"no_separation",
                c"-",
                c"1: the surfaces cannot separate (linear penalty in tension too), sliding stays free",
                0.0,
                0.0,
                1.0,
            ),
            Parameter::optional(
                c"smoothing",
                c"length",
                c"gap over which the penalty is rounded off (C1 at first contact); 0 = a sharp kink",
                0.0,
                0.0,
                f64::INFINITY,
            ),
        ]
    }

    fn create(p: &[f64], _config: &str) -> Result<Self, String> {
        if !(p[0] > 0.0 && p[0].is_finite()) {
            return Err(format!("penalty must be positive and finite, got {}", p[0]));
        }
        if p[1] != 0.0 && p[1] != 1.0 {
            return Err(format!("no_separation must be 0 or 1, got {}", p[1]));
        }
        Ok(Self { penalty: p[0], no_separation: p[1] == 1.0, smoothing: p[2] })
    }

    fn evaluate(&self, gap: f64, _old: &[f64], _new: &mut [f64]) -> Result<Response, String> {
        let (k, eps) = (self.penalty, self.smoothing);
        Ok(if self.no_separation {
            Response { value: -k * gap, tangent: -k, in_contact: true, area: 0.0 }
        } else if gap >= 0.0 {
            Response::default()
        } else if gap > -eps {
            Response { value: k * gap * gap / (2.0 * eps), tangent: k * gap / eps, in_contact: true, area: 0.0 }
        } else {
            Response { value: -k * (gap + 0.5 * eps), tangent: -k, in_contact: true, area: 0.0 }
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn tangent_matches_finite_differences_away_from_the_kink() {
        for smoothing in [0.0, 0.05] {
            let law = FrictionlessContact::create(&[50.0, 0.0, smoothing], "").unwrap();
            for g in [-0.3, -0.04, -0.01, 0.02, 0.5] {
                let h = 1e-7;
                let f = |x: f64| law.evaluate(x, &[], &mut []).unwrap().value;
                let fd = (f(g + h) - f(g - h)) / (2.0 * h);
                assert!((fd - law.evaluate(g, &[], &mut []).unwrap().tangent).abs() < 1e-6, "g {g}");
            }
        }
        // the smoothed law is C1: value and slope continuous at -eps and 0
        let law = FrictionlessContact::create(&[50.0, 0.0, 0.05], "").unwrap();
        let at = |g: f64| law.evaluate(g, &[], &mut []).unwrap();
        for g in [-0.05, 0.0] {
            let (a, b) = (at(g - 1e-12), at(g + 1e-12));
            assert!((a.value - b.value).abs() < 1e-9 && (a.tangent - b.tangent).abs() < 1e-8, "g {g}: {a:?} {b:?}");
        }
        assert!(FrictionlessContact::create(&[0.0, 0.0, 0.0], "").is_err());
        // no separation: the same penalty in tension
        let tie = FrictionlessContact::create(&[50.0, 1.0, 0.0], "").unwrap();
        let r = tie.evaluate(0.1, &[], &mut []).unwrap();
        assert_eq!((r.value, r.tangent), (-5.0, -50.0));
    }
}
