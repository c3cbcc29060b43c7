//! The run driver: steps through pseudo-time with cut-and-grow incrementation, commits each
//! converged increment, appends it to `history.csv`, writes VTK step by step, and writes
//! `summary.json` at the end (also after a failure).

use crate::build::{BuiltModel, build};
use crate::case::LoadedCase;
use crate::error::{Result, StictionError};
use crate::fields::{solid_cells, solid_fields};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::time::Instant;
use stiction_core::arc_length::{PreviousIncrement, solve_arc_length_increment};
use stiction_core::linear_solver::SparseSolver;
use stiction_core::newton::{Incrementation, NewtonSettings, ReferenceScales, solve_increment};
use stiction_core::output::vtk::{CellList, PvdSeries, write_points_vtu, write_vtu};
use stiction_core::output::{HistoryWriter, write_atomically};

/// Options of `stiction run` beyond the case file.
#[derive(Debug, Clone, Default)]
pub struct RunOptions {
    /// Output directory (overrides the case's `output.directory`).
    pub out: Option<PathBuf>,
    /// Show progress (normally: stderr is a terminal).
    pub progress: bool,
}

/// What `summary.json` holds.
#[derive(Debug, Clone, Serialize)]
pub struct RunSummary {
    pub case: String,
    pub status: String,
    pub message: Option<String>,
    pub final_time: f64,
    pub increments: usize,
    pub cut_increments: usize,
    /// Increments solved by arc-length continuation, and the limit points (turns of the load
    /// parameter) they passed.
    pub arc_length_increments: usize,
    pub limit_points: usize,
    pub newton_iterations: usize,
    pub n_nodes: usize,
    pub n_cells: usize,
    pub n_free_dofs: usize,
    pub nnz: usize,
    pub factor_nnz: usize,
    pub wall_seconds: f64,
    pub assembly_seconds: f64,
    pub factorization_seconds: f64,
    pub solve_seconds: f64,
    pub plastic_dissipation: f64,
    pub output_directory: PathBuf,
    /// Warnings about the results (e.g. a viscous share above its limit).
    pub warnings: Vec<String>,
    /// Per interface: the load cycle's key numbers.
    pub interfaces: Vec<InterfaceSummary>,
}

/// Key numbers of one interface over the run (forces positive compressive).
#[derive(Debug, Clone, Serialize, Default)]
pub struct InterfaceSummary {
    pub name: String,
    /// "rigid-flat" or "cohesive".
    pub kind: String,
    pub max_force: f64,
    pub approach_at_max_force: f64,
    pub n_contact_at_max_force: f64,
    pub contact_area_at_max_force: f64,
    /// Largest compression (-gap) of any interface point at the maximum force: for asperities,
    /// the deformation of the most loaded asperity.
    pub max_point_compression_at_max_force: f64,
    /// max_point_compression_at_max_force / approach_at_max_force: the share of the approach
    /// taken by the most compressed asperity (the rest is the continuum's deformation).
    pub point_share_of_approach_at_max_force: f64,
    /// Most tensile force (negative; 0 if never adhesive) and where it occurred.
    pub pull_off_force: f64,
    pub approach_at_pull_off: f64,
    pub contact_area_at_pull_off: f64,
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
}

/// Output directory of a case: `--out`, else `output.directory`, else `out/<name>`.
pub fn output_directory(case: &LoadedCase, options: &RunOptions) -> PathBuf {
    options
        .out
        .clone()
        .or_else(|| case.case.output.directory.clone())
        .unwrap_or_else(|| PathBuf::from("out").join(&case.name))
}

/// Builds and runs a case.
pub fn run(case: &LoadedCase, options: &RunOptions) -> Result<RunSummary> {
    let mut built = build(case)?;
    run_model(case, &mut built, options)
}

fn settings(case: &LoadedCase) -> Result<NewtonSettings> {
    let s = &case.case.solver;
    if !(s.tol_residual > 0.0) || !(s.tol_displacement > 0.0) || s.max_iterations == 0 {
        return Err(case.error("solver", "tolerances must be positive and max_iterations at least 1"));
    }
    Ok(NewtonSettings {
        max_iterations: s.max_iterations,
        tol_residual: s.tol_residual,
        tol_displacement: s.tol_displacement,
        line_search: s.line_search,
        ..NewtonSettings::default()
    })
}

/// Runs an already built model.
/// The model keeps the final converged state for inspection.
pub fn run_model(case: &LoadedCase, built: &mut BuiltModel, options: &RunOptions) -> Result<RunSummary> {
    let wall = Instant::now();
    let BuiltModel { model, reaction_groups, layouts, .. } = &mut *built;
    let reaction_groups = &*reaction_groups;
    let newton = settings(case)?;
    if case.case.steps.is_empty() {
        return Err(case.error("steps", "at least one step is needed"));
    }
    let mut previous_end = 0.0;
    let mut incrementations = Vec::new();
    for (i, s) in case.case.steps.iter().enumerate() {
        let span = s.end_time - previous_end;
        if !(span > 0.0) {
            return Err(case.error(
                format!("steps[{i}].end_time"),
                format!("must be after the previous step's end ({previous_end})"),
            ));
        }
        let inc = Incrementation {
            initial: s.initial_increment.unwrap_or(0.1 * span).min(span),
            minimum: s.min_increment.unwrap_or(1e-6 * span),
            maximum: s.max_increment.unwrap_or(span),
            cut_factor: case.case.solver.cut_factor,
            growth_factor: case.case.solver.growth_factor,
            easy_iterations: 5,
        };
        inc.validate().map_err(|e| case.error(format!("steps[{i}]"), e.to_string()))?;
        if let Some(name) = &s.until_separated {
            if !model.contributions.iter().any(|c| c.name() == name) {
                return Err(case.error(format!("steps[{i}].until_separated"), format!("no interface named '{name}'")));
            }
        }
        incrementations.push(inc);
        previous_end = s.end_time;
    }
    if case.case.solver.threads > 0 {
        // Ignored if a global pool exists already (e.g. several runs in one process).
        let _ = rayon::ThreadPoolBuilder::new().num_threads(case.case.solver.threads).build_global();
    }

    let out = output_directory(case, options);
    std::fs::create_dir_all(&out).map_err(|source| stiction_core::CoreError::Write { path: out.clone(), source })?;
    let dpn = model.dofs_per_node();
    let comp = |k: usize| {
        if model.kinematics == stiction_core::element::Kinematics::Axisymmetric {
            ["r", "z"][k]
        } else {
            ["x", "y", "z"][k]
        }
    };
    let mut columns: Vec<String> = ["step", "increment", "time", "iterations"].iter().map(|s| s.to_string()).collect();
    for (g, _) in reaction_groups {
        for k in 0..dpn {
            columns.push(format!("reaction_{g}_{}", comp(k)));
        }
    }
    columns.push("plastic_dissipation".into());
    let contribution_columns: Vec<String> =
        model.contributions.iter().flat_map(|c| c.history().into_iter().map(|(n, _)| n)).collect();
    columns.extend(contribution_columns);
    let mut history = HistoryWriter::create(&out.join("history.csv"), columns)?;
    for (name, points) in layouts.iter() {
        let path = out.join(format!("{name}_points.csv"));
        crate::build::write_points_csv(&path, points)
            .map_err(|source| stiction_core::CoreError::Write { path, source })?;
    }
    let mut pvd = PvdSeries::new(out.join(format!("{}.pvd", case.name)));
    let mut point_series: Vec<PvdSeries> = model
        .contributions
        .iter()
        .map(|c| PvdSeries::new(out.join(format!("{}_{}.pvd", case.name, c.name()))))
        .collect();
    let write_vtk = case.case.output.vtk;

    let mut solver = SparseSolver::new(model.pattern())?;
    let mut summary = RunSummary {
        case: case.name.clone(),
        status: "running".into(),
        message: None,
        final_time: 0.0,
        increments: 0,
        cut_increments: 0,
        arc_length_increments: 0,
        limit_points: 0,
        newton_iterations: 0,
        n_nodes: model.mesh.nodes.len(),
        n_cells: model.sets.iter().map(|s| s.n_cells()).sum(),
        n_free_dofs: model.n_free(),
        nnz: model.pattern().nnz(),
        factor_nnz: solver.factor_nnz(),
        wall_seconds: 0.0,
        assembly_seconds: 0.0,
        factorization_seconds: 0.0,
        solve_seconds: 0.0,
        plastic_dissipation: 0.0,
        output_directory: out.clone(),
        warnings: Vec::new(),
        interfaces: model
            .contributions
            .iter()
            .map(|c| {
                let spec = case.case.interfaces.iter().find(|i| i.name == c.name());
                InterfaceSummary {
                    name: c.name().to_string(),
                    kind: spec.map_or_else(String::new, |i| i.kind.clone()),
                    max_viscous_share: spec.map_or(default_share(), |i| i.max_viscous_share),
                    ..Default::default()
                }
            })
            .collect(),
    };
    let mut events = HistoryWriter::create(
        &out.join("events.csv"),
        [
            "time",
            "approach",
            "interface",
            "event",
            "n_contact_before",
            "n_contact_after",
            "force_before",
            "force_after",
            "cuts_before",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect(),
    )?;
    // per interface: (approach, force, contact_area, n_contact, viscous_dissipation) last committed
    let observe = |c: &dyn stiction_core::model::Contribution| -> [f64; 5] {
        let h = c.history();
        let get = |k: &str| h.iter().find(|(n, _)| n == k).map(|(_, v)| *v).unwrap_or(0.0);
        [get("approach"), get("force"), get("contact_area"), get("n_contact"), get("viscous_dissipation")]
    };
    let mut observed: Vec<[f64; 5]> = model.contributions.iter().map(|c| observe(c.as_ref())).collect();
    let mut had_contact = vec![false; model.contributions.len()];
    let mut cuts_since_commit = 0usize;
    let bar = if options.progress {
        let b = ProgressBar::with_draw_target(Some(1000), ProgressDrawTarget::stderr());
        b.set_style(
            ProgressStyle::with_template("{spinner} [{elapsed_precise}] {bar:30} {msg}")
                .unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
        b
    } else {
        ProgressBar::hidden()
    };
    let t_end = previous_end;

    // Initial state (t = 0) so the series starts undeformed.
    model.apply_time(0.0);
    model.assemble(false)?;
    model.commit();
    let mut frame = 0usize;
    let record = |model: &stiction_core::model::Model,
                  history: &mut HistoryWriter,
                  step: usize,
                  inc: usize,
                  its: usize|
     -> Result<()> {
        let mut row = vec![step as f64, inc as f64, model.time, its as f64];
        for (_, nodes) in reaction_groups {
            row.extend(model.reaction(nodes));
        }
        row.push(model.dissipation());
        for c in &model.contributions {
            row.extend(c.history().into_iter().map(|(_, v)| v));
        }
        history.append(&row)?;
        Ok(())
    };
    let vtk_frame = |model: &stiction_core::model::Model,
                     pvd: &mut PvdSeries,
                     series: &mut Vec<PvdSeries>,
                     frame: usize|
     -> Result<()> {
        for (c, s) in model.contributions.iter().zip(series.iter_mut()) {
            if let Some((points, fields)) = c.point_output() {
                let file = format!("{}_{}_{frame:05}.vtu", case.name, c.name());
                write_points_vtu(&out.join(&file), &points, &fields)?;
                s.add(model.time, &file)?;
            }
        }
        let file = format!("{}_{frame:05}.vtu", case.name);
        let (point, cell) = solid_fields(model);
        let cells = solid_cells(model);
        let lists: Vec<CellList> = cells.iter().map(|(t, c)| CellList { cell_type: *t, connectivity: c }).collect();
        write_vtu(&out.join(&file), &model.mesh.nodes, &lists, &point, &cell)?;
        pvd.add(model.time, &file)?;
        Ok(())
    };
    record(model, &mut history, 0, 0, 0)?;
    if write_vtk {
        vtk_frame(model, &mut pvd, &mut point_series, frame)?;
        frame += 1;
    }

    let mut t = 0.0;
    let mut failure: Option<(f64, String)> = None;
    let mut last_increment: Option<(Vec<f64>, f64)> = None;
    let breakpoints: Vec<f64> = model
        .prescribed()
        .iter()
        .map(|p| p.amplitude.clone())
        .chain(model.loads.iter().map(|l| l.amplitude.clone()))
        .chain(model.contributions.iter().flat_map(|c| c.amplitudes()))
        .flat_map(|a| a.breakpoints_between(0.0, f64::INFINITY).collect::<Vec<_>>())
        .chain(case.case.steps.iter().map(|s| s.end_time))
        .collect();
    let mut force_average = RunningMean::default();
    let arc_length_enabled = case.case.solver.continuation == crate::case::ContinuationSpec::ArcLength;
    // The last converged increment (free dofs, time), kept through cuts to start arc length.
    let mut last_converged: Option<PreviousIncrement> = None;
    let mut crossing: Option<ArcCrossing> = None;
    let mut first_failed_target: Option<f64> = None;
    // set when arc length had to hand back to load control; cleared by the next commit
    let mut arc_blocked = false;
    let mut step_start = 0.0;
    'steps: for (si, (step, inc)) in case.case.steps.iter().zip(&incrementations).enumerate() {
        let mut dt = inc.initial;
        let mut since_output = 0;
        let step_name = step.name.clone().unwrap_or_else(|| format!("step {}", si + 1));
        while t < step.end_time - 1e-12 * t_end {
            let u_norm = model.displacement.iter().map(|x| x * x).sum::<f64>().sqrt();
            let scales = ReferenceScales { displacement: u_norm, force: force_average.mean() };
            let attempt = if let Some(arc) = &crossing {
                match solve_arc_length_increment(
                    model,
                    &mut solver,
                    t,
                    arc.ds,
                    &arc.previous,
                    arc.time_weight,
                    1e-6 * t_end,
                    &newton,
                    scales,
                ) {
                    Ok((report, increment)) => {
                        let t_new = t + increment.dt;
                        // arc length stays between breakpoints and inside the step; past them
                        // load control resumes from the committed state
                        let crosses = breakpoints.iter().any(|&b| (b - t) * (b - t_new) < 0.0);
                        if crosses || t_new > step.end_time || t_new < step_start {
                            model.rollback();
                            crossing = None;
                            arc_blocked = true;
                            dt = (step.end_time - t).min(inc.maximum).min(dt.max(inc.minimum * 4.0));
                            continue;
                        }
                        Ok((report, Some(increment)))
                    }
                    Err(e) => Err(e),
                }
            } else {
                let mut target = (t + dt).min(step.end_time);
                // land on amplitude breakpoints so load reversals are exact
                for &b in &breakpoints {
                    if b > t + 1e-12 * t_end && b < target {
                        target = b;
                    }
                }
                if step.end_time - target < 1e-3 * dt {
                    target = step.end_time;
                }
                // Predictor: extrapolate the last converged increment (not across a reversal).
                if let Some((du, dt_last)) = &last_increment {
                    model.update_free(du, (target - t) / dt_last);
                }
                let result = solve_increment(model, &mut solver, target, &newton, scales).map(|r| (r, None));
                if result.is_err() && first_failed_target.is_none() {
                    first_failed_target = Some(target);
                }
                result
            };
            match attempt {
                Ok((report, arc_increment)) => {
                    let target = model.time;
                    let mut limit_point = false;
                    let mut resume = false;
                    if let (Some(increment), Some(arc)) = (&arc_increment, crossing.as_mut()) {
                        limit_point = increment.dt.signum() != arc.previous.dt.signum();
                        resume = increment.dt > 0.0 && target > arc.resume_after;
                        if report.iterations <= inc.easy_iterations {
                            arc.ds = (arc.ds * inc.growth_factor).min(arc.ds_max);
                        }
                        arc.previous = increment.clone();
                        summary.arc_length_increments += 1;
                        if limit_point {
                            summary.limit_points += 1;
                        }
                    }
                    let du: Vec<f64> =
                        model.free_dofs().iter().map(|&g| model.displacement[g] - committed_free(model, g)).collect();
                    // With continuation on, a load-controlled increment whose displacements moved
                    // far more than the last one's rate predicts has jumped over a limit point to
                    // another branch: go back and follow the path by arc length instead.
                    if arc_length_enabled && arc_increment.is_none() && !arc_blocked {
                        if let Some(previous) = last_converged.clone().filter(|p| p.dt > 0.0 && target > t) {
                            let previous_norm = norm(&previous.du);
                            let predicted = previous_norm * (target - t) / previous.dt;
                            if predicted > 0.0 && norm(&du) > JUMP_RATIO * predicted {
                                model.rollback();
                                summary.cut_increments += 1;
                                cuts_since_commit += 1;
                                crossing = ArcCrossing::start(previous, target);
                                continue;
                            }
                        }
                    }
                    force_average.add(norm(&model.internal_force).max(norm(&model.external_force)));
                    let reversal = breakpoints.iter().any(|&b| (b - target).abs() <= 1e-12 * t_end.max(1.0));
                    last_converged = Some(PreviousIncrement { du: du.clone(), dt: target - t });
                    last_increment = if reversal || target <= t { None } else { Some((du, target - t)) };
                    first_failed_target = None;
                    arc_blocked = false;
                    if resume {
                        // past the point where load control failed, moving forward again
                        crossing = None;
                        dt = (target - t).clamp(inc.minimum, inc.maximum);
                    }
                    model.commit();
                    t = target;
                    summary.increments += 1;
                    summary.newton_iterations += report.iterations;
                    summary.assembly_seconds += report.assembly_seconds;
                    summary.factorization_seconds += report.factorization_seconds;
                    summary.solve_seconds += report.solve_seconds;
                    record(model, &mut history, si + 1, summary.increments, report.iterations)?;
                    let mut separated = false;
                    for (k, c) in model.contributions.iter().enumerate() {
                        let now = observe(c.as_ref());
                        let before = observed[k];
                        let s = &mut summary.interfaces[k];
                        // work of the flat: trapezoid in approach
                        s.work_of_flat += 0.5 * (now[1] + before[1]) * (now[0] - before[0]);
                        s.gross_work_of_flat += 0.5 * (now[1].abs() + before[1].abs()) * (now[0] - before[0]).abs();
                        if now[1] > s.max_force {
                            s.max_force = now[1];
                            s.approach_at_max_force = now[0];
                            s.n_contact_at_max_force = now[3];
                            s.contact_area_at_max_force = now[2];
                            if let Some((_, fields)) = c.point_output() {
                                let compression = fields[0].values.iter().fold(0.0f64, |m, g| m.max(-g));
                                s.max_point_compression_at_max_force = compression;
                                s.point_share_of_approach_at_max_force =
                                    if now[0] > 0.0 { compression / now[0] } else { 0.0 };
                            }
                        }
                        if now[1] < s.pull_off_force {
                            s.pull_off_force = now[1];
                            s.approach_at_pull_off = now[0];
                            s.contact_area_at_pull_off = now[2];
                        }
                        s.max_contact_area = s.max_contact_area.max(now[2]);
                        s.viscous_dissipation = now[4];
                        s.viscous_share_of_work =
                            if s.gross_work_of_flat > 0.0 { now[4] / s.gross_work_of_flat } else { 0.0 };
                        if now[3] != before[3] || cuts_since_commit > 0 || limit_point {
                            // a jump: the increment had to be cut and the force changed by more
                            // than 5% of the largest force magnitude seen so far
                            let scale = s.max_force.max(-s.pull_off_force).max(now[1].abs());
                            let kind = if limit_point {
                                // the load parameter turned: a load-controlled run jumps here
                                "limit_point"
                            } else if arc_increment.is_none()
                                && cuts_since_commit > 0
                                && (now[1] - before[1]).abs() > 0.05 * scale
                            {
                                "jump"
                            } else if now[3] < before[3] {
                                "contact_lost"
                            } else if now[3] > before[3] {
                                "contact_gained"
                            } else {
                                "increment_cut"
                            };
                            if now[3] != before[3] {
                                s.contact_events += 1;
                            }
                            events.append_fields(&[
                                format!("{:.10e}", model.time),
                                format!("{:.10e}", now[0]),
                                c.name().to_string(),
                                kind.to_string(),
                                format!("{}", before[3]),
                                format!("{}", now[3]),
                                format!("{:.10e}", before[1]),
                                format!("{:.10e}", now[1]),
                                format!("{cuts_since_commit}"),
                            ])?;
                        }
                        had_contact[k] |= now[3] > 0.0;
                        // separated: nothing in contact and no force left (adhesive laws pull
                        // after compressive contact is lost)
                        let force_scale = s.max_force.max(-s.pull_off_force);
                        if step.until_separated.as_deref() == Some(c.name())
                            && had_contact[k]
                            && now[3] == 0.0
                            && now[1].abs() <= 1e-3 * force_scale
                        {
                            separated = true;
                        }
                        observed[k] = now;
                    }
                    cuts_since_commit = 0;
                    since_output += 1;
                    let at_end = t >= step.end_time - 1e-12 * t_end;
                    if write_vtk && ((step.output_every > 0 && since_output >= step.output_every) || at_end) {
                        vtk_frame(model, &mut pvd, &mut point_series, frame)?;
                        frame += 1;
                        since_output = 0;
                    }
                    bar.set_position((1000.0 * t / t_end) as u64);
                    let last = report.residual_norms.last().copied().unwrap_or(0.0);
                    bar.set_message(format!(
                        "{step_name}: t = {t:.4} dt = {dt:.2e}, {} Newton its, |r| = {last:.2e}",
                        report.iterations
                    ));
                    if report.iterations <= inc.easy_iterations && crossing.is_none() && !resume {
                        dt = (dt * inc.growth_factor).min(inc.maximum);
                    }
                    if separated {
                        // every point has left the flat: this step (and its schedule) ends here
                        if vtk_needed_at_step_end(write_vtk, at_end, since_output) {
                            vtk_frame(model, &mut pvd, &mut point_series, frame)?;
                            frame += 1;
                        }
                        break;
                    }
                }
                Err(e) => {
                    model.rollback();
                    last_increment = None;
                    summary.cut_increments += 1;
                    cuts_since_commit += 1;
                    if let Some(arc) = crossing.as_mut() {
                        arc.ds *= 0.5;
                        bar.set_message(format!("{step_name}: arc length cut to {:.2e} at t = {t:.4} ({e})", arc.ds));
                        if arc.ds < 1e-4 * arc.ds_initial {
                            failure = Some((
                                t,
                                format!("arc-length continuation stalled (arc length {:.3e}) after: {e}", arc.ds),
                            ));
                            break 'steps;
                        }
                        continue;
                    }
                    if arc_length_enabled && !arc_blocked && cuts_since_commit >= case.case.solver.arc_length_after_cuts
                    {
                        crossing = last_converged
                            .clone()
                            .and_then(|previous| ArcCrossing::start(previous, first_failed_target.unwrap_or(t)));
                        if crossing.is_some() {
                            continue;
                        }
                    }
                    dt *= inc.cut_factor;
                    bar.set_message(format!("{step_name}: cut to dt = {dt:.2e} at t = {t:.4} ({e})"));
                    if dt < inc.minimum {
                        failure = Some((t, format!("increment below the minimum {:.3e} after: {e}", inc.minimum)));
                        break 'steps;
                    }
                }
            }
        }
        step_start = step.end_time;
        crossing = None;
    }
    bar.finish_and_clear();
    summary.final_time = t;
    summary.plastic_dissipation = model.dissipation();
    summary.wall_seconds = wall.elapsed().as_secs_f64();
    summary.status = if failure.is_some() { "failed".into() } else { "completed".into() };
    summary.message = failure.as_ref().map(|f| f.1.clone());
    for (i, now) in summary.interfaces.iter().zip(&observed) {
        if i.viscous_dissipation > 0.0 && i.viscous_share_of_work >= i.max_viscous_share {
            events.append_fields(&[
                format!("{:.10e}", t),
                format!("{:.10e}", now[0]),
                i.name.clone(),
                "viscous_share_exceeded".to_string(),
                format!("{}", now[3]),
                format!("{}", now[3]),
                format!("{:.10e}", now[1]),
                format!("{:.10e}", now[1]),
                "0".to_string(),
            ])?;
            summary.warnings.push(format!(
                "interface '{}': the viscous regularisation dissipated {:.4e} = {:.1}% of the gross work of the flat, above the limit max_viscous_share = {}; lower its viscosity or use solver.continuation = \"arc-length\"",
                i.name,
                i.viscous_dissipation,
                100.0 * i.viscous_share_of_work,
                i.max_viscous_share
            ));
        }
    }
    for w in &summary.warnings {
        eprintln!("warning: {w}");
    }
    write_summary(&out, &summary)?;
    if !summary.interfaces.is_empty() {
        if let Some(curve) = crate::plots::read_history(&out.join("history.csv"), &case.name) {
            if let Err(e) = crate::plots::plot_curves(&out, "", &case.name, &[curve]) {
                eprintln!("warning: plots of '{}' not written: {e}", case.name);
            }
        }
    }
    if let Some((time, message)) = failure {
        return Err(StictionError::RunFailed { time, message, out });
    }
    Ok(summary)
}

fn write_summary(out: &Path, summary: &RunSummary) -> Result<()> {
    let json = serde_json::to_string_pretty(summary).expect("summary serializes");
    write_atomically(&out.join("summary.json"), json.as_bytes())?;
    Ok(())
}

/// The committed value of global dof `g` (the model keeps it for roll-back).
fn committed_free(model: &stiction_core::model::Model, g: usize) -> f64 {
    model.committed_displacement()[g]
}

/// A frame is written when a step ends early unless the last increment already wrote one.
fn vtk_needed_at_step_end(write_vtk: bool, at_end: bool, since_output: usize) -> bool {
    write_vtk && !at_end && since_output > 0
}

/// Runs a case once per value of its `[sweep]` (or once if it has none). Each run writes to
/// `<out>/<label>=<value>/`; the combined plots and `sweep.json` go to `<out>/`.
pub fn run_sweep(path: &Path, sets: &[String], options: &RunOptions) -> Result<Vec<RunSummary>> {
    let base = crate::case::load(path, sets)?;
    let Some(sweep) = base.case.sweep.clone() else {
        return Ok(vec![run(&base, options)?]);
    };
    if sweep.values.is_empty() {
        return Err(base.error("sweep.values", "needs at least one value"));
    }
    let out = output_directory(&base, options);
    let label = sweep.label.clone().unwrap_or_else(|| sweep.key.clone());
    let mut summaries = Vec::new();
    let mut curves = Vec::new();
    for v in &sweep.values {
        let mut run_sets = sets.to_vec();
        run_sets.push(format!("{}={v}", sweep.key));
        let case = crate::case::load(path, &run_sets)?;
        let folder = out.join(format!("{}={v}", label.replace(['/', ' '], "_")));
        let run_options = RunOptions { out: Some(folder.clone()), ..options.clone() };
        let summary = run(&case, &run_options)?;
        if let Some(c) = crate::plots::read_history(&folder.join("history.csv"), &format!("{label} = {v}")) {
            curves.push(c);
        }
        summaries.push(summary);
    }
    if !curves.is_empty() {
        if let Err(e) = crate::plots::plot_curves(&out, "combined_", &base.name, &curves) {
            eprintln!("warning: combined plots not written: {e}");
        }
    }
    let json = serde_json::to_string_pretty(&summaries).expect("summaries serialize");
    write_atomically(&out.join("sweep.json"), json.as_bytes())?;
    Ok(summaries)
}

/// A load-controlled increment whose displacement increment exceeds this multiple of the one
/// the previous increment's rate predicts counts as a jump over a limit point (continuation on).
const JUMP_RATIO: f64 = 5.0;

/// An arc-length crossing of a limit point in progress.
struct ArcCrossing {
    /// Current arc length (displacement units), its first value and its cap.
    ds: f64,
    /// Displacement per unit load parameter weighting t in the arc length (the rate of the
    /// last load-controlled increment).
    time_weight: f64,
    ds_initial: f64,
    ds_max: f64,
    previous: PreviousIncrement,
    /// Load control resumes once the load parameter moves forward past this value (the
    /// target that failed).
    resume_after: f64,
}

fn default_share() -> f64 {
    crate::case::InterfaceSpec::default_max_viscous_share()
}

impl ArcCrossing {
    /// A crossing that starts from the last converged load-controlled increment `previous`:
    /// the first arc length is that increment's length in the (du, c dt) norm with c its
    /// displacement rate (so sqrt 2 |du|), capped at 10 |du|. None when it did not move.
    fn start(previous: PreviousIncrement, resume_after: f64) -> Option<Self> {
        let length = norm(&previous.du);
        (length > 0.0 && previous.dt > 0.0).then(|| Self {
            ds: length * std::f64::consts::SQRT_2,
            ds_initial: length * std::f64::consts::SQRT_2,
            ds_max: 10.0 * length,
            time_weight: length / previous.dt,
            previous,
            resume_after,
        })
    }
}

/// Mean of the force norms of the converged increments (the Newton reference force).
#[derive(Default)]
struct RunningMean {
    sum: f64,
    count: usize,
}

impl RunningMean {
    fn add(&mut self, value: f64) {
        self.sum += value;
        self.count += 1;
    }
    fn mean(&self) -> f64 {
        if self.count == 0 { 0.0 } else { self.sum / self.count as f64 }
    }
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}
