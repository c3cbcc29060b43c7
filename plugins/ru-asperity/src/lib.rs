//! `ru-asperity`: the hysteretic force-distance law of one nano-asperity (a force per point),
//! from polynomial fits of molecular-dynamics loading and unloading curves: a 4th-order loading
//! polynomial, a family of 5th-order unloading polynomials (one per MD maximum distance), and
//! contact-area fits of the same form. See [`law`] for every branch rule, [`calibration`] for the
//! file format, [`fit`] for `stiction calibrate`, and [`surrogate`] for the shipped default
//! calibrations (a documented surrogate of the Ru asperity, not MD data).
//!
//! As a Stiction law: gap = -d; value = force (positive compressive); tangent = d force / d gap.
//! Parameters: `expected_work_of_adhesion` (0: no check; otherwise the calibration's must match
//! within 1e-9), `ramp` (width of the jump-in ramp before first contact, nm).

pub mod calibration;
pub mod fit;
pub mod law;
pub mod polynomial;
pub mod surrogate;

use law::AsperityModel;
use stiction_law_sdk::{Law, LawKind, Parameter, Response};

pub struct RuAsperity {
    pub model: AsperityModel,
}

impl Law for RuAsperity {
    const NAME: &'static std::ffi::CStr = c"ru-asperity";
    const VERSION: &'static std::ffi::CStr = c"0.1.0";
    const KIND: LawKind = LawKind::ForcePerPoint;
    const N_STATE: usize = law::N_STATE;

    fn parameters() -> Vec<Parameter> {
        vec![
            Parameter::optional(
                c"expected_work_of_adhesion",
                c"J/m^2",
                c"work of adhesion the case expects the calibration to have (0: no check)",
                0.0,
                0.0,
                f64::INFINITY,
            ),
            Parameter::optional(
                c"ramp",
                c"nm",
                c"width of the jump-in force ramp before first contact",
                0.05,
                1e-6,
                1.0,
            ),
        ]
    }

    fn config_description() -> Option<&'static std::ffi::CStr> {
        Some(c"asperity calibration file (TOML, format stiction-asperity-calibration-1)")
    }

    fn create(p: &[f64], config: &str) -> Result<Self, String> {
        let calibration = calibration::Calibration::parse(config)?;
        if p[0] > 0.0 && (calibration.work_of_adhesion - p[0]).abs() > 1e-9 * p[0] {
            return Err(format!(
                "key 'work_of_adhesion': the calibration has {} J/m^2 but the case expects {} J/m^2",
                calibration.work_of_adhesion, p[0]
            ));
        }
        Ok(Self { model: AsperityModel { calibration, ramp: p[1] } })
    }

    fn evaluate(&self, gap: f64, old: &[f64], new: &mut [f64]) -> Result<Response, String> {
        let e = self.model.evaluate(-gap, old, new);
        Ok(Response { value: e.force, tangent: -e.stiffness, in_contact: e.in_contact, area: e.area })
    }

    fn state_names() -> Vec<&'static std::ffi::CStr> {
        vec![c"max_distance", c"phase", c"pull_offs"]
    }
}
