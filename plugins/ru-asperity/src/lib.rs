//! `ru-asperity`: the hysteretic force-distance law of one nano-asperity (a force per point),
//! from polynomial fits of molecular-dynamics loading and unloading curves: a 4th-order loading
//! polynomial, a family of 5th-order unloading polynomials (one per MD maximum distance), and
//! contact-area fits of the same form. See [`law`] for every branch rule, [`calibration`] for the
//! file format, [`fit`] for `stiction calibrate`, and [`surrogate`] for the shipped default
//! calibrations (a documented surrogate of the Ru asperity, not MD data).
//!
//! As a Stiction law: gap = -d; value = force (positive compressive); tangent = d force / d gap.
//! Parameters: `expected_work_of_adhesion` (0: no check; otherwise the calibration's must match
//! within 1e-9), `ramp` (width of the jump-in ramp before first contact, nm), and the
//! surrogate's free parameters `surrogate_*` ([`surrogate::Surrogate`]), read only with a config
//! file of format `stiction-asperity-surrogate-1` (`work_of_adhesion = W` its only other key):
//! the law then fits its calibration to the surrogate with them, as `stiction calibrate` would.

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

/// The calibration a config file gives: a fitted calibration as it is, or one fitted to the
/// surrogate with the law's `surrogate_*` parameters (`p[2..7]`), which no other config takes.
fn from_config(p: &[f64], config: &str) -> Result<calibration::Calibration, String> {
    let format = toml::from_str::<toml::Table>(config)
        .ok()
        .and_then(|t| t.get("format").and_then(|f| f.as_str()).map(String::from));
    let names = ["loading_scale", "loading_length", "stiffness", "pull_off_scale", "stretch"];
    if format.as_deref() != Some(surrogate::FORMAT) {
        let defaults = [surrogate::LOADING_SCALE, surrogate::LOADING_LENGTH, surrogate::STIFFNESS, 0.0, 1.0];
        if let Some(k) = (0..5).find(|&k| p[2 + k] != defaults[k]) {
            return Err(format!(
                "parameter 'surrogate_{}' applies only with a surrogate config file (format = \"{}\"); this \
                 config file is a fitted calibration",
                names[k],
                surrogate::FORMAT
            ));
        }
        return calibration::Calibration::parse(config);
    }
    #[derive(serde::Deserialize)]
    #[serde(deny_unknown_fields)]
    struct SurrogateConfig {
        #[allow(dead_code)]
        format: String,
        work_of_adhesion: f64,
    }
    let c: SurrogateConfig = toml::from_str(config).map_err(|e| e.to_string())?;
    if !(c.work_of_adhesion > 0.0 && c.work_of_adhesion.is_finite()) {
        return Err(format!("key 'work_of_adhesion': must be positive, found {}", c.work_of_adhesion));
    }
    let mut s = surrogate::Surrogate::for_work_of_adhesion(c.work_of_adhesion);
    (s.loading_scale, s.loading_length, s.stiffness, s.stretch) = (p[2], p[3], p[4], p[6]);
    if p[5] > 0.0 {
        s.pull_off_scale = p[5];
    }
    s.calibration()
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
            Parameter::optional(
                c"surrogate_loading_scale",
                c"nN",
                c"surrogate only (config format stiction-asperity-surrogate-1): loading scale P",
                surrogate::LOADING_SCALE,
                1e-3,
                1e6,
            ),
            Parameter::optional(
                c"surrogate_loading_length",
                c"nm",
                c"surrogate only: loading length l",
                surrogate::LOADING_LENGTH,
                1e-3,
                10.0,
            ),
            Parameter::optional(
                c"surrogate_stiffness",
                c"nN/nm",
                c"surrogate only: loading stiffness k",
                surrogate::STIFFNESS,
                0.0,
                1e6,
            ),
            Parameter::optional(
                c"surrogate_pull_off_scale",
                c"nN",
                c"surrogate only: pull-off scale P_w (0: 60, 120, 400 nN at w = 1, 3, 6, linear between)",
                0.0,
                0.0,
                1e6,
            ),
            Parameter::optional(
                c"surrogate_stretch",
                c"-",
                c"surrogate only: factor on the neck's stretch before separation, (0.15 + 0.12 w) nm",
                1.0,
                1e-3,
                100.0,
            ),
        ]
    }

    fn config_description() -> Option<&'static std::ffi::CStr> {
        Some(c"asperity calibration file (TOML): fitted, format stiction-asperity-calibration-1, or the surrogate's model, format stiction-asperity-surrogate-1")
    }

    fn create(p: &[f64], config: &str) -> Result<Self, String> {
        let calibration = from_config(p, config)?;
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
