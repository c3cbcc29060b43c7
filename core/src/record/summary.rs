//! `summary.json`: how the run went and each interface's key numbers; written when the run
//! starts (status "running") and again when it ends, failed and interrupted runs included.

use super::{CommittedIncrement, Observer};
use crate::error::Result;
use crate::model::Model;
use crate::output::write_atomically;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// The key numbers of one load cycle.
#[derive(Debug, Clone, Serialize, Deserialize, Default, PartialEq)]
pub struct CycleSummary {
    /// 1-based.
    pub cycle: usize,
    pub max_approach: f64,
    pub max_force: f64,
    /// Most tensile force of the cycle (negative; 0 if never adhesive).
    pub most_tensile_force: f64,
    /// The interface let go by the cycle's end ([`super::cycles::released`]).
    pub separated: bool,
    /// The most tensile force when the cycle separated, else None.
    pub pull_off_force: Option<f64>,
    pub max_contact_area: f64,
    pub contact_resistance_at_max_force: Option<f64>,
    /// Work the flat does against adhesion to open the contact: the integral of -force over the
    /// retraction where the force is tensile, sum of max(-F, 0) |d approach| while the approach
    /// decreases (the adhesion energy of the cycle).
    pub opening_work: f64,
    /// Net work of the flat over the cycle, integral of force d(approach).
    pub work_of_flat: f64,
    /// The continuum's plastic dissipation over the cycle (the whole model's).
    pub plastic_dissipation: f64,
    /// The snaps' dissipation over the cycle (the whole model's). With the plastic dissipation
    /// and the laws' own (hysteresis, viscosity) it balances the flat's work over a cycle that
    /// ends in the state it started from: for an elastic body with a conservative law, the
    /// work of the flat is the snaps' dissipation.
    pub snap_dissipation: f64,
}

/// The resistance at one force level on loading and on unloading of the first cycle.
#[derive(Debug, Clone, Serialize, Deserialize, Default, PartialEq)]
pub struct ResistanceAtForce {
    /// The level as a fraction of the cycle's maximum force.
    pub fraction_of_max_force: f64,
    pub force: f64,
    pub loading: Option<f64>,
    pub unloading: Option<f64>,
}

/// How a run stands: "running" from its start until it ends "completed", "failed" (with the
/// reason in `message`) or "interrupted".
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum RunStatus {
    #[default]
    Running,
    Completed,
    Failed,
    Interrupted,
}

impl RunStatus {
    /// The name `summary.json` gives it.
    pub fn as_str(&self) -> &'static str {
        match self {
            RunStatus::Running => "running",
            RunStatus::Completed => "completed",
            RunStatus::Failed => "failed",
            RunStatus::Interrupted => "interrupted",
        }
    }
}

impl std::fmt::Display for RunStatus {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

impl PartialEq<&str> for RunStatus {
    fn eq(&self, other: &&str) -> bool {
        self.as_str() == *other
    }
}

/// How the run's snaps were solved (`summary.json`'s `snap_method`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum SnapSolve {
    /// By descent ([`crate::nonlinear::settle`]).
    #[default]
    #[serde(rename = "settle")]
    Settle,
    /// Along the damped flow ([`crate::nonlinear::damped_flow`]).
    #[serde(rename = "damped-flow")]
    DampedFlow,
    /// By descent, and along the damped flow where a descent found no stable state.
    #[serde(rename = "settle, the damped flow where a descent failed")]
    SettleThenFlow,
}

impl SnapSolve {
    /// The name `summary.json` gives it.
    pub fn as_str(&self) -> &'static str {
        match self {
            SnapSolve::Settle => "settle",
            SnapSolve::DampedFlow => "damped-flow",
            SnapSolve::SettleThenFlow => "settle, the damped flow where a descent failed",
        }
    }
}

impl std::fmt::Display for SnapSolve {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

impl PartialEq<&str> for SnapSolve {
    fn eq(&self, other: &&str) -> bool {
        self.as_str() == *other
    }
}

/// What `summary.json` holds.
#[derive(Debug, Clone, Serialize, Deserialize, Default)]
pub struct RunSummary {
    pub case: String,
    /// The unit of every number below, from the case's length and force units.
    pub units: Units,
    pub status: RunStatus,
    pub message: Option<String>,
    pub final_time: f64,
    pub increments: usize,
    pub cut_increments: usize,
    /// Increments solved by path following (arc length or dissipation control; the name is
    /// the file format's), and the limit points (turns of the load parameter) they passed.
    pub arc_length_increments: usize,
    pub limit_points: usize,
    /// Increments where the path had no nearby equilibrium and the model snapped to a stable
    /// one (jump-in, pull-off under displacement control), by `snap_method`.
    pub snaps: usize,
    /// How snaps are solved.
    pub snap_method: SnapSolve,
    pub newton_iterations: usize,
    /// Numeric factorizations of the tangent.
    pub factorizations: usize,
    /// Tangents the single-precision factor could not solve to double precision by iterative
    /// refinement (cond(K) eps_f32 near 1: a nearly singular or indefinite tangent), which
    /// were refactored in double precision.
    pub double_precision_refactorizations: usize,
    /// Switches between the consistent and the stabilized material tangent after failed
    /// attempts (`solver.tangent`, [`crate::path::TangentChoice`]).
    pub tangent_switches: usize,
    pub n_nodes: usize,
    pub n_cells: usize,
    pub n_free_dofs: usize,
    pub nnz: usize,
    pub factor_nnz: usize,
    pub wall_seconds: f64,
    /// The threads the run's assembly and factorization ran on (its rayon pool's size:
    /// `solver.threads`, or all cores for 0; a resumed run's last part's); 0 in a summary
    /// written before this was recorded.
    #[serde(default)]
    pub threads: usize,
    pub assembly_seconds: f64,
    pub factorization_seconds: f64,
    pub solve_seconds: f64,
    /// Wall seconds of the attempts that were not committed: those that failed and were cut,
    /// converged ones rolled back as jumps, snaps that failed, and the solves that did not
    /// converge inside a damped-flow snap (the assembly, factorization and solve seconds above
    /// are those of the committed increments only).
    pub discarded_attempt_seconds: f64,
    pub plastic_dissipation: f64,
    /// The energy the snaps dissipated besides plastic flow
    /// ([`super::CommittedIncrement::snap_dissipation`]), over the whole run.
    pub snap_dissipation: f64,
    /// The largest equivalent plastic strain of any integration point at the end (None without
    /// a plastic material).
    pub max_equivalent_plastic_strain: Option<f64>,
    pub output_directory: PathBuf,
    /// Warnings about the results (e.g. a viscous share above its limit).
    pub warnings: Vec<String>,
    /// Per interface: the load cycle's key numbers.
    pub interfaces: Vec<InterfaceSummary>,
}

/// The units of the numbers in `summary.json`: the case's length and force, and those they
/// make (empty strings where the case states no units).
#[derive(Debug, Clone, Serialize, Deserialize, Default, PartialEq)]
pub struct Units {
    pub length: String,
    pub force: String,
    /// length^2: contact areas.
    pub area: String,
    /// force x length: works and dissipations.
    pub energy: String,
    /// force / length^2.
    pub stress: String,
    /// Contact resistances are in ohm whatever the case's units.
    pub resistance: String,
}

/// SI prefixes and their powers of ten, for the case's units and those they make.
const SI_PREFIXES: [(&str, i32); 13] = [
    ("G", 9),
    ("M", 6),
    ("k", 3),
    ("", 0),
    ("c", -2),
    ("m", -3),
    ("u", -6),
    ("µ", -6),
    ("n", -9),
    ("p", -12),
    ("f", -15),
    ("a", -18),
    ("z", -21),
];

impl Units {
    /// The units a case's `length` and `force` make; SI names where the pair has one
    /// (nm and nN: aJ and GPa).
    pub fn of(length: &str, force: &str) -> Self {
        let prefix = |unit: &str, base: &str| -> Option<i32> {
            let p = unit.strip_suffix(base)?;
            SI_PREFIXES.iter().find(|(q, _)| *q == p).map(|&(_, e)| e)
        };
        // named with a prefix only for multiples of 3 (no "cJ"), "u" before "µ"
        let named = |exponent: i32, base: &str| -> Option<String> {
            let (p, _) = SI_PREFIXES.iter().find(|&&(_, e)| e == exponent && e % 3 == 0)?;
            Some(format!("{p}{base}"))
        };
        if length.is_empty() && force.is_empty() {
            return Self { resistance: "ohm".into(), ..Default::default() };
        }
        let (l, f) = (prefix(length, "m"), prefix(force, "N"));
        let energy = l.zip(f).and_then(|(l, f)| named(l + f, "J")).unwrap_or_else(|| format!("{force} {length}"));
        let stress =
            l.zip(f).and_then(|(l, f)| named(f - 2 * l, "Pa")).unwrap_or_else(|| format!("{force}/{length}^2"));
        Self {
            length: length.into(),
            force: force.into(),
            area: format!("{length}^2"),
            energy,
            stress,
            resistance: "ohm".into(),
        }
    }
}

/// Key numbers of one interface over the run (forces positive compressive).
#[derive(Debug, Clone, Serialize, Deserialize, Default)]
pub struct InterfaceSummary {
    pub name: String,
    /// "rigid-flat" or "cohesive".
    pub kind: String,
    pub max_force: f64,
    pub approach_at_max_force: f64,
    pub n_contact_at_max_force: f64,
    pub contact_area_at_max_force: f64,
    /// Largest compression (-gap) of any interface point at the maximum force: for asperities,
    /// the deformation of the most loaded asperity (with a footprint correction, its law's own
    /// gap, without the footprint's compliance and indentation).
    pub max_point_compression_at_max_force: f64,
    /// max_point_compression_at_max_force / approach_at_max_force: the share of the approach
    /// taken by the most compressed asperity (the rest is the continuum's deformation).
    pub point_share_of_approach_at_max_force: f64,
    /// Most tensile force over the run (negative; 0 if never adhesive), where it occurred and
    /// the contact area then: always, separated or not.
    pub most_tensile_force: f64,
    pub approach_at_most_tensile_force: f64,
    pub contact_area_at_most_tensile_force: f64,
    /// The interface separated by the end of the run: it had contact or carried a force, and
    /// at the end no point is in contact and the force no longer holds half the most tensile
    /// one ([`super::cycles::released`]).
    pub separated: bool,
    /// The pull-off: the most tensile force, where and with what area, when the interface
    /// separated; None (null) when it did not (then it is only the most tensile force).
    pub pull_off_force: Option<f64>,
    pub approach_at_pull_off: Option<f64>,
    pub contact_area_at_pull_off: Option<f64>,
    /// The interface at the end of the run: force, approach and points in contact.
    pub final_force: f64,
    pub final_approach: f64,
    pub final_n_contact: usize,
    pub max_contact_area: f64,
    /// Work done by the flat on the body over the run, integral of force d(approach)
    /// (trapezoidal): over a closed load-unload cycle, the energy dissipated (plus any elastic
    /// energy locked in by plasticity).
    pub work_of_flat: f64,
    /// Increments where points came into or out of contact (see events.csv).
    pub contact_events: usize,
    /// Gross work of the flat: integral of |force| |d approach| (the energy that went through
    /// the interface, either way).
    pub gross_work_of_flat: f64,
    /// Energy dissipated by the viscous regularisation and its share of `gross_work_of_flat`
    /// (kept below the interface's `max_viscous_share`: it measures how far the crossing of
    /// instabilities is from quasi-static).
    pub viscous_dissipation: f64,
    pub viscous_share_of_work: f64,
    /// The share at or above which a warning is issued.
    pub max_viscous_share: f64,
    /// Electrical contact resistance (ohm) at the maximum force, its smallest value, and the
    /// first cycle's values at 25, 50 and 75% of its maximum force on loading and unloading (the
    /// hysteresis); absent where the interface does not model resistance.
    pub contact_resistance_at_max_force: Option<f64>,
    pub min_contact_resistance: Option<f64>,
    pub contact_resistance_at_force: Vec<ResistanceAtForce>,
    /// Each load cycle's key numbers (interfaces with a flat), as in cycles.csv.
    pub cycles: Vec<CycleSummary>,
    /// The limit points the path crossed by arc length (jump-in and jump-out folds), each
    /// located between the committed increments around it (interfaces with a flat).
    pub folds: Vec<Fold>,
}

/// A limit point of the approach: where it is stationary along the path. Located as the vertex
/// of the parabola approach(force) through the two committed increments before the turn and
/// the one after (the approach is stationary there, so it is located to second order in the
/// increment, the force to first order).
#[derive(Debug, Clone, Copy, Serialize, Deserialize, Default, PartialEq)]
pub struct Fold {
    /// Pseudo-time of the increment that turned.
    pub time: f64,
    pub approach: f64,
    pub force: f64,
}

/// Writes `summary.json` (atomically) when the run ends.
pub struct SummaryWriter {
    path: PathBuf,
}

impl SummaryWriter {
    pub fn new(directory: &Path) -> Self {
        Self { path: directory.join("summary.json") }
    }
}

impl SummaryWriter {
    fn write(&self, summary: &RunSummary) -> Result<()> {
        let json = serde_json::to_string_pretty(summary).expect("summary serializes");
        write_atomically(&self.path, json.as_bytes())
    }
}

impl Observer for SummaryWriter {
    /// A summary that says "running" until the run ends, so a killed run never leaves one that
    /// claims more than history.csv holds.
    fn started(&mut self, _model: &Model, summary: &RunSummary) -> Result<()> {
        let mut running = summary.clone();
        running.message =
            Some("the run has not ended (or was killed): history.csv holds its committed increments".into());
        self.write(&running)
    }

    fn committed(&mut self, _model: &Model, _increment: &CommittedIncrement) -> Result<()> {
        Ok(())
    }

    fn finished(&mut self, _model: &Model, summary: &RunSummary) -> Result<()> {
        self.write(summary)
    }
}

#[cfg(test)]
mod tests {
    use super::{RunStatus, SnapSolve, Units};

    /// The names `summary.json` gives the status and the snap method, read back.
    #[test]
    fn status_and_snap_method_keep_their_json_names() {
        for (status, name) in [
            (RunStatus::Running, "running"),
            (RunStatus::Completed, "completed"),
            (RunStatus::Failed, "failed"),
            (RunStatus::Interrupted, "interrupted"),
        ] {
            assert_eq!(serde_json::to_string(&status).unwrap(), format!("\"{name}\""));
            assert_eq!(serde_json::from_str::<RunStatus>(&format!("\"{name}\"")).unwrap(), status);
            assert_eq!(status, name);
        }
        for method in [SnapSolve::Settle, SnapSolve::DampedFlow, SnapSolve::SettleThenFlow] {
            let json = serde_json::to_string(&method).unwrap();
            assert_eq!(json, format!("\"{}\"", method.as_str()));
            assert_eq!(serde_json::from_str::<SnapSolve>(&json).unwrap(), method);
        }
        assert!(serde_json::from_str::<RunStatus>("\"done\"").is_err());
    }

    #[test]
    fn units_follow_from_length_and_force() {
        let nm = Units::of("nm", "nN");
        assert_eq!((nm.area.as_str(), nm.energy.as_str(), nm.stress.as_str()), ("nm^2", "aJ", "GPa"));
        let mm = Units::of("mm", "N");
        assert_eq!((mm.energy.as_str(), mm.stress.as_str()), ("mJ", "MPa"));
        let um = Units::of("um", "uN");
        assert_eq!((um.energy.as_str(), um.stress.as_str()), ("pJ", "MPa"));
        let cm = Units::of("cm", "N");
        // 10^-2 J and 10^4 Pa have no prefix: written as the product and the quotient
        assert_eq!((cm.energy.as_str(), cm.stress.as_str()), ("N cm", "N/cm^2"));
        let odd = Units::of("in", "lbf");
        assert_eq!((odd.energy.as_str(), odd.stress.as_str()), ("lbf in", "lbf/in^2"));
        assert_eq!(Units::of("", "").energy, "");
    }
}
