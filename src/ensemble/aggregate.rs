//! The aggregate of an ensemble: statistics of every summary quantity over the completed
//! members, the mean curves with their bands, and the confidence interval's width against the
//! number of members; written as `ensemble.json`, `ensemble.csv`, `ensemble_loading.csv` and
//! `ensemble_unloading.csv`. Everything is computed in member order from the members' own files
//! (summary.json, history.csv), so the same members give the same digits however they were run
//! (serially, concurrently or over MPI ranks) as long as each member ran with the same threads.

use super::curves::{CurvePoint, ensemble_curves};
use super::member::MemberOutcome;
use super::statistics::{CONFIDENCE, Statistic};
use crate::error::Result;
use serde::Serialize;
use std::fmt::Write as _;
use std::path::Path;
use stiction_core::output::write_atomically;

/// Per-interface quantities of summary.json that the ensemble summarises.
/// The pull-off's quantities are null in the summary of a member that did not separate, so
/// their statistics are over the members that separated (n says how many).
pub const INTERFACE_QUANTITIES: [&str; 13] = [
    "max_force",
    "approach_at_max_force",
    "n_contact_at_max_force",
    "contact_area_at_max_force",
    "max_contact_area",
    "most_tensile_force",
    "approach_at_most_tensile_force",
    "contact_area_at_most_tensile_force",
    "pull_off_force",
    "approach_at_pull_off",
    "contact_area_at_pull_off",
    "work_of_flat",
    "contact_resistance_at_max_force",
];

/// Run-level quantities of summary.json that the ensemble summarises.
pub const RUN_QUANTITIES: [&str; 2] = ["plastic_dissipation", "max_equivalent_plastic_strain"];

/// Quantities whose confidence interval is followed against the number of members.
pub const CONVERGENCE_QUANTITIES: [&str; 4] = ["max_force", "most_tensile_force", "pull_off_force", "max_contact_area"];

/// The width of a quantity's confidence interval with the first n completed members.
#[derive(Debug, Clone, Serialize)]
pub struct ConvergencePoint {
    pub quantity: String,
    pub n: usize,
    pub mean: f64,
    pub ci95_half_width: f64,
}

/// What `ensemble.json` holds.
#[derive(Debug, Clone, Serialize)]
pub struct EnsembleAggregate {
    pub case: String,
    /// The case's units as it states them (empty when it does not).
    pub length_unit: String,
    pub force_unit: String,
    pub members: usize,
    pub completed: usize,
    /// The varied keys.
    pub varied: Vec<String>,
    pub confidence: f64,
    /// Every member: its varied values, status and (failed ones) the error; only completed
    /// members enter the statistics.
    pub outcomes: Vec<MemberOutcome>,
    pub statistics: Vec<Statistic>,
    pub convergence: Vec<ConvergencePoint>,
    /// Force and contact area of the first interface against approach, on loading and on
    /// unloading.
    pub loading: Vec<CurvePoint>,
    pub unloading: Vec<CurvePoint>,
}

/// Samples of every quantity, in member order: (quantity name, values).
fn samples(root: &Path, completed: &[&MemberOutcome]) -> Vec<(String, Vec<f64>)> {
    let summaries: Vec<serde_json::Value> = completed
        .iter()
        .filter_map(|o| std::fs::read_to_string(root.join(&o.folder).join("summary.json")).ok())
        .filter_map(|t| serde_json::from_str(&t).ok())
        .collect();
    let mut out: Vec<(String, Vec<f64>)> = Vec::new();
    let mut collect = |name: String, get: &dyn Fn(&serde_json::Value) -> Option<f64>| {
        let values: Vec<f64> = summaries.iter().filter_map(get).filter(|v| v.is_finite()).collect();
        if !values.is_empty() {
            out.push((name, values));
        }
    };
    let interfaces: Vec<String> = summaries
        .first()
        .and_then(|s| s["interfaces"].as_array())
        .map(|a| a.iter().filter_map(|i| i["name"].as_str().map(String::from)).collect())
        .unwrap_or_default();
    for (k, name) in interfaces.iter().enumerate() {
        for q in INTERFACE_QUANTITIES {
            collect(format!("{name}.{q}"), &|s| s["interfaces"][k][q].as_f64());
        }
    }
    for q in RUN_QUANTITIES {
        collect(q.to_string(), &|s| s[q].as_f64());
    }
    out
}

/// Aggregates the completed members of `outcomes` (all members, in order) found in `root`.
pub fn aggregate(
    (case, units): (&str, (String, String)),
    varied: Vec<String>,
    outcomes: Vec<MemberOutcome>,
    root: &Path,
) -> EnsembleAggregate {
    let completed: Vec<&MemberOutcome> = outcomes.iter().filter(|o| o.completed()).collect();
    let samples = samples(root, &completed);
    let statistics: Vec<Statistic> = samples.iter().filter_map(|(q, v)| Statistic::of(q, v)).collect();
    let mut convergence = Vec::new();
    for (q, values) in &samples {
        if !CONVERGENCE_QUANTITIES.iter().any(|c| q.ends_with(&format!(".{c}"))) {
            continue;
        }
        for n in 2..=values.len() {
            let s = Statistic::of(q, &values[..n]).expect("n >= 2");
            let half = s.ci95_half_width.expect("n >= 2");
            convergence.push(ConvergencePoint { quantity: q.clone(), n, mean: s.mean, ci95_half_width: half });
        }
    }
    let histories: Vec<Vec<(f64, f64, f64)>> = completed
        .iter()
        .filter_map(|o| crate::plots::read_history(&root.join(&o.folder).join("history.csv"), &o.folder))
        .map(|c| c.points)
        .collect();
    let (loading, unloading) = ensemble_curves(&histories);
    EnsembleAggregate {
        case: case.to_string(),
        length_unit: units.0,
        force_unit: units.1,
        members: outcomes.len(),
        completed: completed.len(),
        varied,
        confidence: CONFIDENCE,
        outcomes,
        statistics,
        convergence,
        loading,
        unloading,
    }
}

fn opt(x: Option<f64>) -> String {
    x.map_or_else(String::new, |v| format!("{v:?}"))
}

/// The statistics table: one row per quantity.
fn statistics_csv(statistics: &[Statistic]) -> String {
    let mut s = String::from("quantity,n,mean,std,ci95_low,ci95_high,min,max\n");
    for q in statistics {
        let _ = writeln!(
            s,
            "{},{},{:?},{},{},{},{:?},{:?}",
            q.quantity,
            q.n,
            q.mean,
            opt(q.std),
            opt(q.ci95_low),
            opt(q.ci95_high),
            q.min,
            q.max
        );
    }
    s
}

/// A curve table: approach, members covering it, and force and area statistics.
fn curve_csv(points: &[CurvePoint]) -> String {
    let mut s = String::from(
        "approach,n,force_mean,force_std,force_ci95_low,force_ci95_high,contact_area_mean,contact_area_std,\
         contact_area_ci95_low,contact_area_ci95_high\n",
    );
    for p in points {
        let (f, a) = (&p.force, &p.contact_area);
        let _ = writeln!(
            s,
            "{:?},{},{:?},{},{},{},{:?},{},{},{}",
            p.approach,
            f.n,
            f.mean,
            opt(f.std),
            opt(f.ci95_low),
            opt(f.ci95_high),
            a.mean,
            opt(a.std),
            opt(a.ci95_low),
            opt(a.ci95_high)
        );
    }
    s
}

/// Writes ensemble.json, ensemble.csv, ensemble_loading.csv and ensemble_unloading.csv into
/// `root`, each atomically.
pub fn write(root: &Path, aggregate: &EnsembleAggregate) -> Result<()> {
    let json = serde_json::to_string_pretty(aggregate).expect("aggregate serializes");
    write_atomically(&root.join("ensemble.json"), json.as_bytes())?;
    write_atomically(&root.join("ensemble.csv"), statistics_csv(&aggregate.statistics).as_bytes())?;
    write_atomically(&root.join("ensemble_loading.csv"), curve_csv(&aggregate.loading).as_bytes())?;
    write_atomically(&root.join("ensemble_unloading.csv"), curve_csv(&aggregate.unloading).as_bytes())?;
    Ok(())
}
