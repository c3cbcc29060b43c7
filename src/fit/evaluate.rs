//! Running the cases at parameter vectors and turning their outputs into weighted residuals.
//!
//! A batch of parameter vectors (a trial point, or a Jacobian's steps) becomes one run per
//! vector and case, each in `runs/<case>-<hash of its --set assignments>/` of the fit's folder,
//! run concurrently by the ensemble's runner ([`crate::ensemble::local::run_jobs`]). A run whose
//! folder says it completed with the same assignments is read back instead of run again: a
//! resumed fit replays the optimizer's path from these folders until it reaches the point where
//! it stopped. This module does not know the optimizer.

use super::spec::{Differences, FitSpec, TargetKind};
use super::targets::RunOutputs;
use crate::ensemble::local::{ThreadBudget, available_cores, run_jobs};
use crate::ensemble::member::{MemberContext, MemberOutcome, earlier_completion};
use crate::ensemble::plan::Member;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use stiction_core::output::write_atomically;

/// The refactorization cost ratio a fit's runs get where their case measures costs: runs must
/// be reproducible for the finite differences and the resumption (the quick Ru case's value).
pub const FIXED_COST_RATIO: f64 = 10.0;

/// Why a batch's point was evaluated (fit_history.csv's `purpose`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Purpose {
    Start,
    Trial,
    Jacobian,
}

impl Purpose {
    fn as_str(self) -> &'static str {
        match self {
            Purpose::Start => "start",
            Purpose::Trial => "trial",
            Purpose::Jacobian => "jacobian",
        }
    }
}

/// The residuals at one parameter vector.
#[derive(Debug, Clone)]
pub struct Point {
    /// sqrt(weight) (model - measured) / scale, target after target.
    pub residuals: Vec<f64>,
    /// The model's values at each target's measured points (one for a summary target).
    pub model: Vec<Vec<f64>>,
}

impl Point {
    /// The weighted sum of squares.
    pub fn cost(&self) -> f64 {
        self.residuals.iter().map(|r| r * r).sum()
    }
}

/// What became of one parameter vector.
#[derive(Debug, Clone)]
pub enum Outcome {
    Done(Point),
    /// A run failed, or did not produce what a target compares: the message names the case and
    /// the parameter values.
    Failed(String),
    /// Ctrl-C: a run was stopped or not started.
    Interrupted,
}

/// Where a batch's runs go: this machine's cores ([`LocalRuns`]), or MPI ranks
/// (`super::mpi`). The outcomes come back in the order of the jobs, None for a job that never
/// started (Ctrl-C).
pub trait Runs: Sync {
    fn run(
        &self,
        jobs: &[(&MemberContext, &Member)],
        report: &(dyn Fn(&MemberOutcome) + Sync),
    ) -> Vec<Option<MemberOutcome>>;
}

/// The runs of a batch on this machine, concurrently under one thread budget for the whole fit:
/// each run gets the same number of threads, so a run's result does not depend on the batch it
/// was in.
pub struct LocalRuns(pub ThreadBudget);

impl LocalRuns {
    /// The budget for `spec`: sized for its largest batch (a Jacobian's runs).
    pub fn for_fit(spec: &FitSpec) -> Self {
        let o = &spec.optimizer;
        let batch = spec.cases.len() * spec.parameters.len() * if o.jacobian == Differences::Central { 2 } else { 1 };
        Self(ThreadBudget::choose(available_cores(), batch, o.concurrent_runs, o.threads_per_run))
    }
}

impl Runs for LocalRuns {
    fn run(
        &self,
        jobs: &[(&MemberContext, &Member)],
        report: &(dyn Fn(&MemberOutcome) + Sync),
    ) -> Vec<Option<MemberOutcome>> {
        run_jobs(jobs, self.0, report)
    }
}

/// One line of fit_history.csv.
#[derive(Debug, Clone)]
struct Record {
    purpose: Purpose,
    x: Vec<f64>,
    cost: Option<f64>,
    status: &'static str,
    message: String,
}

/// Runs the fit's cases at parameter vectors.
pub struct Evaluator<'a> {
    spec: &'a FitSpec,
    out: PathBuf,
    contexts: Vec<MemberContext>,
    interrupt: Option<Arc<AtomicBool>>,
    quiet: bool,
    runner: &'a dyn Runs,
    known: Mutex<HashMap<Vec<u64>, Outcome>>,
    records: Mutex<Vec<Record>>,
    /// Runs started by this process, and runs read back from an earlier invocation's folders.
    pub runs: AtomicUsize,
    pub runs_reused: AtomicUsize,
}

impl<'a> Evaluator<'a> {
    /// `measured_costs[c]`: case c refactorizes on measured times (solver.refactorization_cost_ratio
    /// = 0), so its runs would depend on the machine's load: the fit gives it a fixed ratio of
    /// [`FIXED_COST_RATIO`].
    pub fn new(
        spec: &'a FitSpec,
        out: &Path,
        runs: &'a dyn Runs,
        measured_costs: &[bool],
        interrupt: Option<Arc<AtomicBool>>,
        quiet: bool,
    ) -> Self {
        let contexts = spec
            .cases
            .iter()
            .zip(measured_costs)
            .map(|(c, &measured)| {
                // no VTK series per run unless a case's own sets ask for it
                let mut sets = vec!["output.vtk=false".to_string()];
                if measured {
                    sets.push(format!("solver.refactorization_cost_ratio={FIXED_COST_RATIO:e}"));
                }
                sets.extend(c.set.iter().cloned());
                MemberContext { case_path: c.file.clone(), sets, root: out.to_path_buf(), interrupt: interrupt.clone() }
            })
            .collect();

        Self {
            spec,
            out: out.to_path_buf(),
            contexts,
            interrupt,
            quiet,
            runner: runs,
            known: Mutex::new(HashMap::new()),
            records: Mutex::new(Vec::new()),
            runs: AtomicUsize::new(0),
            runs_reused: AtomicUsize::new(0),
        }
    }

    /// The `--set` assignments of the parameters for `case` at `x`.
    pub fn sets(&self, case: usize, x: &[f64]) -> Vec<String> {
        self.spec
            .parameters
            .iter()
            .zip(x)
            .filter(|(p, _)| p.cases.contains(&case))
            .map(|(p, v)| format!("{}={v:e}", p.key))
            .collect()
    }

    fn member(&self, case: usize, x: &[f64]) -> Member {
        use sha2::Digest;
        let sets = self.sets(case, x);
        let mut hash = sha2::Sha256::new();
        for s in self.contexts[case].sets.iter().chain(&sets) {
            hash.update(s.as_bytes());
            hash.update(b"\n");
        }
        let digest = format!("{:x}", hash.finalize());
        Member { index: 0, folder: format!("runs/{}-{}", self.spec.cases[case].name, &digest[..16]), sets }
    }

    /// The outcome at each of `points` (parameter values), running what no earlier run holds.
    pub fn evaluate(&self, points: &[Vec<f64>], purpose: Purpose) -> Vec<Outcome> {
        let key = |x: &[f64]| x.iter().map(|v| v.to_bits()).collect::<Vec<u64>>();
        let n_cases = self.spec.cases.len();
        // the runs this batch needs and no earlier batch or invocation completed
        let mut wanted: Vec<(usize, Member)> = Vec::new();
        let mut done: HashMap<String, MemberOutcome> = HashMap::new();
        for x in points {
            if self.known.lock().expect("known points").contains_key(&key(x)) {
                continue;
            }
            for c in 0..n_cases {
                let m = self.member(c, x);
                if done.contains_key(&m.folder) || wanted.iter().any(|(_, w)| w.folder == m.folder) {
                    continue;
                }
                match earlier_completion(&self.out, &m) {
                    Some(outcome) => {
                        self.runs_reused.fetch_add(1, Ordering::SeqCst);
                        done.insert(m.folder.clone(), outcome);
                    }
                    None => wanted.push((c, m)),
                }
            }
        }
        if !wanted.is_empty() {
            let jobs: Vec<(&MemberContext, &Member)> = wanted.iter().map(|(c, m)| (&self.contexts[*c], m)).collect();
            let finished = AtomicUsize::new(0);
            let total = jobs.len();
            let report = |outcome: &MemberOutcome| {
                let k = finished.fetch_add(1, Ordering::SeqCst) + 1;
                if !self.quiet {
                    eprintln!("  {} run {k} of {total}: {} {}", purpose.as_str(), outcome.folder, outcome.status);
                }
            };
            self.runs.fetch_add(total, Ordering::SeqCst);
            for ((_, m), outcome) in wanted.iter().zip(self.runner.run(&jobs, &report)) {
                if let Some(outcome) = outcome {
                    done.insert(m.folder.clone(), outcome);
                }
            }
        }
        let outcomes: Vec<Outcome> = points
            .iter()
            .map(|x| {
                if let Some(known) = self.known.lock().expect("known points").get(&key(x)) {
                    return known.clone();
                }
                let outcome = self.outcome_at(x, &done);
                if !matches!(outcome, Outcome::Interrupted) {
                    self.known.lock().expect("known points").insert(key(x), outcome.clone());
                }
                self.record(purpose, x, &outcome);
                outcome
            })
            .collect();
        self.write_history();
        outcomes
    }

    /// The residuals at `x` from the runs in `done`.
    fn outcome_at(&self, x: &[f64], done: &HashMap<String, MemberOutcome>) -> Outcome {
        let mut outputs = Vec::new();
        for c in 0..self.spec.cases.len() {
            let m = self.member(c, x);
            let at = || format!("case '{}' at {}", self.spec.cases[c].name, self.sets(c, x).join(", "));
            match done.get(&m.folder) {
                None => return Outcome::Interrupted,
                Some(o) if o.status == "interrupted" => return Outcome::Interrupted,
                Some(o) if !o.completed() => {
                    return Outcome::Failed(format!("{}: {}", at(), o.error.clone().unwrap_or_default()));
                }
                Some(_) => match RunOutputs::read(&self.out.join(&m.folder)) {
                    Ok(read) => outputs.push(read),
                    Err(e) => return Outcome::Failed(format!("{}: {e}", at())),
                },
            }
        }
        match weighted_residuals(self.spec, &outputs) {
            Ok(point) => Outcome::Done(point),
            Err(e) => Outcome::Failed(format!("at {}: {e}", self.sets_text(x))),
        }
    }

    fn sets_text(&self, x: &[f64]) -> String {
        self.spec.parameters.iter().zip(x).map(|(p, v)| format!("{}={v:e}", p.key)).collect::<Vec<_>>().join(", ")
    }

    fn record(&self, purpose: Purpose, x: &[f64], outcome: &Outcome) {
        let (cost, status, message) = match outcome {
            Outcome::Done(p) => (Some(p.cost()), "completed", String::new()),
            Outcome::Failed(e) => (None, "failed", e.clone()),
            Outcome::Interrupted => (None, "interrupted", String::new()),
        };
        self.records.lock().expect("records").push(Record { purpose, x: x.to_vec(), cost, status, message });
    }

    /// Writes fit_history.csv: one line per parameter vector evaluated, in order.
    fn write_history(&self) {
        let mut text = String::from("evaluation,purpose");
        for p in &self.spec.parameters {
            text.push_str(&format!(",{}", p.key));
        }
        text.push_str(",cost,status,message\n");
        for (i, r) in self.records.lock().expect("records").iter().enumerate() {
            text.push_str(&format!("{i},{}", r.purpose.as_str()));
            for v in &r.x {
                text.push_str(&format!(",{v:e}"));
            }
            let cost = r.cost.map_or(String::new(), |c| format!("{c:e}"));
            text.push_str(&format!(",{cost},{},\"{}\"\n", r.status, r.message.replace('"', "'")));
        }
        if let Err(e) = write_atomically(&self.out.join("fit_history.csv"), text.as_bytes()) {
            eprintln!("warning: fit_history.csv not written: {e}");
        }
    }

    /// The key of parameter `j`.
    pub fn spec_key(&self, j: usize) -> &str {
        &self.spec.parameters[j].key
    }

    /// Whether Ctrl-C was pressed.
    pub fn interrupted(&self) -> bool {
        self.interrupt.as_ref().is_some_and(|f| f.load(Ordering::SeqCst))
    }
}

/// The weighted residuals of every target against the cases' outputs (in the order of the
/// fit's cases): sqrt(weight) (model - measured) / scale, where the scale is the point's or the
/// target's sigma, else the rms of the measured curve or the measured number's magnitude.
pub fn weighted_residuals(spec: &FitSpec, outputs: &[RunOutputs]) -> Result<Point, String> {
    let mut residuals = Vec::new();
    let mut model = Vec::new();
    for t in &spec.targets {
        let sqrt_w = t.weight.sqrt();
        let interface = t.interface.as_deref();
        let named = |e: String| format!("target '{}': {e}", t.name);
        match &t.kind {
            TargetKind::Curve(curve) => {
                let values = outputs[t.case].curve_values(curve, interface).map_err(named)?;
                let rms =
                    (curve.points.iter().map(|p| p.value * p.value).sum::<f64>() / curve.points.len() as f64).sqrt();
                for (p, v) in curve.points.iter().zip(&values) {
                    let scale = p.sigma.or(t.sigma).unwrap_or(rms);
                    residuals.push(sqrt_w * (v - p.value) / scale);
                }
                model.push(values);
            }
            TargetKind::Summary { field, value, ratio_to } => {
                let mut v = outputs[t.case].summary_value(field, interface).map_err(named)?;
                if let Some(j) = ratio_to {
                    let d = outputs[*j].summary_value(field, interface).map_err(named)?;
                    if d == 0.0 {
                        return Err(named(format!("{field} of case '{}' is 0: no ratio", spec.cases[*j].name)));
                    }
                    v /= d;
                }
                let scale = t.sigma.unwrap_or(value.abs());
                residuals.push(sqrt_w * (v - value) / scale);
                model.push(vec![v]);
            }
        }
    }
    Ok(Point { residuals, model })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fit::spec::{FitCase, OptimizerSettings, Parameter, Target};

    fn outputs(name: &str, pull_off: f64, max_force: f64) -> RunOutputs {
        let dir = std::env::temp_dir().join(format!("stiction-fit-residuals-{}-{name}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("history.csv"), "approach,force,contact_area\n0,0,0\n1,1,1\n").unwrap();
        let summary = serde_json::json!({"plastic_dissipation": 3.0, "interfaces": [{"name": "flat",
            "kind": "rigid-flat", "separated": true, "pull_off_force": pull_off, "max_force": max_force}]});
        std::fs::write(dir.join("summary.json"), summary.to_string()).unwrap();
        let read = RunOutputs::read(&dir).unwrap();
        std::fs::remove_dir_all(&dir).unwrap();
        read
    }

    fn target(
        case: usize,
        field: &str,
        value: f64,
        ratio_to: Option<usize>,
        sigma: Option<f64>,
        weight: f64,
    ) -> Target {
        Target {
            name: field.into(),
            case,
            interface: None,
            kind: TargetKind::Summary { field: field.into(), value, ratio_to },
            sigma,
            weight,
        }
    }

    /// The residuals of summary targets, by hand: a ratio between two cases, a number scaled by
    /// its magnitude and weighted, and one scaled by its sigma.
    #[test]
    fn summary_residuals_are_weighted_scaled_and_take_ratios() {
        let case = |n: &str| FitCase { name: n.into(), file: "c.toml".into(), set: vec![] };
        let spec = FitSpec {
            path: "f.toml".into(),
            name: "f".into(),
            cases: vec![case("w1"), case("w3")],
            parameters: vec![Parameter {
                key: "k".into(),
                start: 1.0,
                lower: 0.1,
                upper: 10.0,
                log: false,
                cases: vec![0, 1],
                true_value: None,
            }],
            targets: vec![
                target(1, "pull_off_force", 2.0, Some(0), None, 1.0),
                target(0, "max_force", -50.0, None, None, 4.0),
                target(0, "plastic_dissipation", 2.0, None, Some(0.5), 1.0),
            ],
            optimizer: OptimizerSettings::default(),
            fingerprint: String::new(),
        };
        let runs = [outputs("a", -10.0, 40.0), outputs("b", -25.0, 60.0)];
        let p = weighted_residuals(&spec, &runs).unwrap();
        let expected = [(2.5 - 2.0) / 2.0, 2.0 * (40.0 + 50.0) / 50.0, (3.0 - 2.0) / 0.5];
        for (got, want) in p.residuals.iter().zip(expected) {
            assert!((got - want).abs() < 1e-15, "{:?}", p.residuals);
        }
        assert_eq!(p.model, vec![vec![2.5], vec![40.0], vec![3.0]]);
        assert!((p.cost() - expected.iter().map(|r| r * r).sum::<f64>()).abs() < 1e-12);
    }
}
