//! `[ensemble]`: N realizations of a case (`stiction ensemble`), each a whole run with some case
//! keys varied (the asperity layout's seed, the height spread, the density, the calibration,
//! the maximum approach), and the statistics over them.

use super::LoadedCase;
use crate::error::Result;
use schemars::JsonSchema;
use serde::Deserialize;

/// The largest ensemble accepted (a guard against a typo such as `members = 10000000`).
pub const MAX_MEMBERS: usize = 100_000;

/// N realizations of the case with some keys varied, run by `stiction ensemble`.
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct EnsembleSpec {
    /// Number of realizations.
    #[schemars(range(min = 1, max = 100000))]
    pub members: usize,
    /// Seed of the random draws of `uniform` and `normal` variations (default 1). Member i
    /// always gets the i-th draw, so a larger ensemble extends a smaller one.
    #[serde(default = "default_seed")]
    pub seed: u64,
    /// Threads per member (0 = automatic: the cores shared among the members run at once).
    #[serde(default)]
    pub threads_per_member: usize,
    /// Members run at once on one machine (0 = automatic: one per core, at most the members
    /// left to run).
    #[serde(default)]
    pub concurrent_members: usize,
    /// What varies from member to member.
    pub vary: Vec<VarySpec>,
}

fn default_seed() -> u64 {
    1
}

/// One varied case key and how its value is chosen for member i (exactly one of `start`,
/// `values`, `uniform`, `normal`).
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct VarySpec {
    /// Any case key, written as for --set (e.g. "interfaces.0.points.seed").
    pub key: String,
    /// An integer sequence: member i gets start + i (layout seeds).
    pub start: Option<i64>,
    /// Explicit values, one per member (numbers, or strings such as calibration files).
    #[schemars(with = "Option<Vec<serde_json::Value>>")]
    pub values: Option<Vec<toml::Value>>,
    /// Uniformly distributed in [low, high].
    pub uniform: Option<[f64; 2]>,
    /// Normally distributed with [mean, standard deviation].
    pub normal: Option<[f64; 2]>,
}

/// How a varied key's values are chosen.
#[derive(Debug, Clone, PartialEq)]
pub enum Variation {
    Sequence(i64),
    Values(Vec<toml::Value>),
    Uniform(f64, f64),
    Normal(f64, f64),
}

impl VarySpec {
    /// The one way of choosing values this entry gives.
    pub fn variation(&self) -> Option<Variation> {
        let mut given = Vec::new();
        if let Some(s) = self.start {
            given.push(Variation::Sequence(s));
        }
        if let Some(v) = &self.values {
            given.push(Variation::Values(v.clone()));
        }
        if let Some([a, b]) = self.uniform {
            given.push(Variation::Uniform(a, b));
        }
        if let Some([m, s]) = self.normal {
            given.push(Variation::Normal(m, s));
        }
        if given.len() == 1 { given.pop() } else { None }
    }
}

/// Checks `[ensemble]`: a member count in range, at least one varied key, and for each exactly
/// one way of choosing values, with values for every member and finite bounds.
pub fn validate(case: &LoadedCase) -> Result<()> {
    let Some(e) = &case.case.ensemble else {
        return Ok(());
    };
    if e.members == 0 || e.members > MAX_MEMBERS {
        return Err(case.error("ensemble.members", format!("must be in [1, {MAX_MEMBERS}], got {}", e.members)));
    }
    if e.vary.is_empty() {
        return Err(case.error(
            "ensemble.vary",
            "needs at least one varied key, e.g. [[ensemble.vary]] key = \"interfaces.0.points.seed\", start = 1",
        ));
    }
    for (i, v) in e.vary.iter().enumerate() {
        let key = format!("ensemble.vary[{i}]");
        if v.key.trim().is_empty() || v.key.starts_with("ensemble") || v.key.starts_with("sweep") {
            return Err(case.error(format!("{key}.key"), format!("must name a case key to vary, got '{}'", v.key)));
        }
        match v.variation() {
            None => {
                return Err(case.error(
                    key,
                    "needs exactly one of start (an integer sequence), values (one per member), uniform = [low, high] \
                     or normal = [mean, std]",
                ));
            }
            Some(Variation::Values(values)) if values.len() < e.members => {
                return Err(case.error(
                    format!("{key}.values"),
                    format!("has {} values for {} members; give one per member", values.len(), e.members),
                ));
            }
            Some(Variation::Uniform(a, b)) if !(a.is_finite() && b.is_finite() && a < b) => {
                return Err(case.error(
                    format!("{key}.uniform"),
                    format!("must be [low, high] with finite low < high, got [{a}, {b}]"),
                ));
            }
            Some(Variation::Normal(m, s)) if !(m.is_finite() && s.is_finite() && s >= 0.0) => {
                return Err(case.error(
                    format!("{key}.normal"),
                    format!("must be [mean, std] with finite mean and std >= 0, got [{m}, {s}]"),
                ));
            }
            Some(_) => {}
        }
    }
    if case.case.sweep.is_some() {
        return Err(case.error(
            "ensemble",
            "a case cannot have both [sweep] and [ensemble]; run one ensemble per swept value with --set",
        ));
    }
    Ok(())
}
