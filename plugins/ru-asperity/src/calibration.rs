//! The calibration file of the nano-asperity law (TOML), validated on load.
//!
//! ```toml
//! format = "stiction-asperity-calibration-1"
//! description = "..."
//! provenance = "..."            # where the data came from (MD run, surrogate, ...)
//! work_of_adhesion = 6.0        # J/m^2
//! units = { length = "nm", force = "nN", area = "nm^2" }
//! [loading]                     # F(d) = sum c_k d^k on [d_start, d_end]
//! d_start = -0.25               # first contact (jump-in) distance
//! d_end = 2.0                   # largest fitted distance
//! force = [c0, c1, c2, c3, c4]
//! area = [a0, a1, a2, a3, a4]
//! [[unloading]]                 # one per MD maximum distance, in increasing d_max
//! d_max = 0.5
//! d_end = -0.6                  # separation: the force is back to zero, the neck broken
//! force = [c0, ..., c5]
//! area = [a0, ..., a5]
//! ```
//! Distances are the MD approach of the asperity (positive pressing), forces positive
//! compressive.

use serde::Deserialize;

#[derive(Debug, Clone, Deserialize, serde::Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Units {
    pub length: String,
    pub force: String,
    pub area: String,
}

#[derive(Debug, Clone, Deserialize, serde::Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct LoadingFit {
    pub d_start: f64,
    pub d_end: f64,
    pub force: Vec<f64>,
    pub area: Vec<f64>,
}

#[derive(Debug, Clone, Deserialize, serde::Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct UnloadingFit {
    pub d_max: f64,
    pub d_end: f64,
    pub force: Vec<f64>,
    pub area: Vec<f64>,
}

/// Fit quality, informative (written by `stiction calibrate`).
#[derive(Debug, Clone, Deserialize, serde::Serialize, PartialEq, Default)]
#[serde(deny_unknown_fields)]
pub struct FitQuality {
    pub loading_force_rms: f64,
    pub loading_force_max: f64,
    pub loading_area_rms: f64,
    pub unloading_force_rms: Vec<f64>,
    pub unloading_force_max: Vec<f64>,
    pub unloading_area_rms: Vec<f64>,
}

#[derive(Debug, Clone, Deserialize, serde::Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Calibration {
    pub format: String,
    pub description: String,
    pub provenance: String,
    pub work_of_adhesion: f64,
    pub units: Units,
    pub loading: LoadingFit,
    pub unloading: Vec<UnloadingFit>,
    #[serde(default)]
    pub fit: Option<FitQuality>,
}

pub const FORMAT: &str = "stiction-asperity-calibration-1";

impl Calibration {
    /// Parses and validates; errors name the key.
    pub fn parse(text: &str) -> Result<Self, String> {
        let c: Calibration = toml::from_str(text).map_err(|e| e.to_string())?;
        c.validate()?;
        Ok(c)
    }

    /// Checks everything the law relies on.
    pub fn validate(&self) -> Result<(), String> {
        if self.format != FORMAT {
            return Err(format!("key 'format': expected \"{FORMAT}\", found \"{}\"", self.format));
        }
        if (self.units.length.as_str(), self.units.force.as_str(), self.units.area.as_str()) != ("nm", "nN", "nm^2") {
            return Err(format!(
                "key 'units': the law works in nm, nN and nm^2 (the Ru cases' units); this calibration has length = \"{}\", force = \"{}\", area = \"{}\"",
                self.units.length, self.units.force, self.units.area
            ));
        }
        if !(self.work_of_adhesion > 0.0) {
            return Err(format!("key 'work_of_adhesion': must be positive, found {}", self.work_of_adhesion));
        }
        let l = &self.loading;
        if l.force.is_empty() || l.area.is_empty() {
            return Err("key 'loading': needs 'force' and 'area' coefficients".into());
        }
        if !(l.d_end > l.d_start) {
            return Err(format!(
                "keys 'loading.d_start' / 'loading.d_end': need d_start < d_end, found {} and {}",
                l.d_start, l.d_end
            ));
        }
        if self.unloading.is_empty() {
            return Err("key 'unloading': at least one unloading branch ([[unloading]]) is needed".into());
        }
        for (i, u) in self.unloading.iter().enumerate() {
            if u.force.is_empty() || u.area.is_empty() {
                return Err(format!("key 'unloading[{i}]': needs 'force' and 'area' coefficients"));
            }
            if !(u.d_max > u.d_end) {
                return Err(format!(
                    "key 'unloading[{i}]': needs d_end < d_max, found d_end = {} and d_max = {}",
                    u.d_end, u.d_max
                ));
            }
            if !(u.d_max > l.d_start) {
                return Err(format!(
                    "key 'unloading[{i}].d_max': {} is not beyond the first contact distance {}",
                    u.d_max, l.d_start
                ));
            }
            if i > 0 && !(u.d_max > self.unloading[i - 1].d_max) {
                return Err(format!(
                    "key 'unloading[{i}].d_max': maximum distances must increase, found {} after {}",
                    u.d_max,
                    self.unloading[i - 1].d_max
                ));
            }
        }
        let all =
            l.force.iter().chain(&l.area).chain(self.unloading.iter().flat_map(|u| u.force.iter().chain(&u.area)));
        if all.clone().any(|v| !v.is_finite()) {
            return Err("a coefficient is not a finite number".into());
        }
        Ok(())
    }

    /// The file text, with a header comment.
    pub fn to_toml(&self, header: &str) -> String {
        let mut out = String::new();
        for line in header.lines() {
            out.push_str(&format!("# {line}\n"));
        }
        out.push_str(&toml::to_string_pretty(self).expect("calibrations serialize"));
        out
    }
}
