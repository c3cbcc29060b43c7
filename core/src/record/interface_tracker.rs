//! The interfaces' key numbers over a run (maximum force, pull-off, areas, work of the flat,
//! viscous share) and their events (contact gained or lost, jumps, limit points), updated from
//! their typed observables at each committed increment.

use super::cycles::{InterfaceSample, cycles, released, resistance_hysteresis};
use super::plastic_drawing::trailing_drawing;
use super::summary::{Fold, InterfaceSummary, Units};
use crate::model::Model;
use crate::observables::InterfaceObservables;

/// One row of `events.csv`.
#[derive(Debug, Clone, PartialEq)]
pub struct InterfaceEvent {
    pub time: f64,
    pub approach: f64,
    pub interface: String,
    /// contact_gained, contact_lost, jump, limit_point, increment_cut, viscous_share_exceeded.
    pub kind: &'static str,
    pub n_contact_before: usize,
    pub n_contact_after: usize,
    pub force_before: f64,
    pub force_after: f64,
    pub cuts_before: usize,
}

/// How the increment just committed was reached.
#[derive(Debug, Clone, Copy, Default)]
pub struct CommitContext {
    /// Failed attempts since the last commit.
    pub cuts_since_commit: usize,
    /// The load parameter turned (arc length passed a limit point).
    pub limit_point: bool,
    pub by_arc_length: bool,
    /// The plastic dissipation at the committed state (the whole model's).
    pub plastic_dissipation: f64,
    /// Its part in the interfaces' footprint sliders ([`Model::subscale_dissipation`]).
    pub footprint_dissipation: f64,
    /// The snaps' dissipation so far ([`super::CommittedIncrement::snap_dissipation`]).
    pub snap_dissipation: f64,
}

/// What an interface needs besides its observables: its kind and viscous-share limit.
#[derive(Debug, Clone)]
pub struct InterfaceInfo {
    pub kind: String,
    pub max_viscous_share: f64,
}

#[derive(Clone, serde::Serialize, serde::Deserialize)]
pub struct InterfaceTracker {
    summaries: Vec<InterfaceSummary>,
    observed: Vec<InterfaceObservables>,
    had_contact: Vec<bool>,
    /// Every committed state of each interface with a flat, for cycles and hysteresis.
    samples: Vec<Vec<InterfaceSample>>,
}

/// The state of an interface with a flat, with the model's plastic and snap dissipation then.
fn sample(o: &InterfaceObservables, context: CommitContext) -> Option<InterfaceSample> {
    Some(InterfaceSample {
        approach: o.approach?,
        force: o.force,
        contact_area: o.contact_area,
        n_contact: o.n_contact,
        resistance: o.contact_resistance,
        plastic_dissipation: context.plastic_dissipation,
        footprint_dissipation: context.footprint_dissipation,
        snap_dissipation: context.snap_dissipation,
    })
}

/// (approach or 0, force, area, n, viscous or 0) of an observable set (0 for no observables).
fn observe(model: &Model, k: usize) -> InterfaceObservables {
    model.contributions[k].observables().unwrap_or_default()
}

/// The fold between three committed states around a turn of the approach: the vertex of the
/// parabola approach(force) through them (Newton's divided differences,
/// a = a0 + d01 (F - F0) + c (F - F0)(F - F1), da/dF = 0); the middle state when they do not
/// define one (equal forces, no curvature, or a vertex outside them).
fn fold_between(time: f64, s0: &InterfaceSample, s1: &InterfaceSample, s2: &InterfaceSample) -> Fold {
    let (f0, f1, f2) = (s0.force, s1.force, s2.force);
    let (a0, a1, a2) = (s0.approach, s1.approach, s2.approach);
    let middle = Fold { time, approach: a1, force: f1 };
    if f1 == f0 || f2 == f1 || f2 == f0 {
        return middle;
    }
    let d01 = (a1 - a0) / (f1 - f0);
    let c = ((a2 - a1) / (f2 - f1) - d01) / (f2 - f0);
    if c == 0.0 {
        return middle;
    }
    let force = 0.5 * (f0 + f1) - d01 / (2.0 * c);
    // a vertex outside the three states is an extrapolation: keep the middle state
    let (low, high) = (f0.min(f1).min(f2), f0.max(f1).max(f2));
    if !(low..=high).contains(&force) {
        return middle;
    }
    Fold { time, approach: a0 + d01 * (force - f0) + c * (force - f0) * (force - f1), force }
}

impl InterfaceTracker {
    /// One summary per contribution of `model`, with `infos` aligned to them.
    pub fn new(model: &Model, infos: &[InterfaceInfo]) -> Self {
        let summaries = model
            .contributions
            .iter()
            .zip(infos)
            .map(|(c, info)| InterfaceSummary {
                name: c.name().to_string(),
                kind: info.kind.clone(),
                max_viscous_share: info.max_viscous_share,
                ..Default::default()
            })
            .collect();
        let n = model.contributions.len();
        let observed: Vec<InterfaceObservables> = (0..n).map(|k| observe(model, k)).collect();
        let context = CommitContext {
            plastic_dissipation: model.dissipation(),
            footprint_dissipation: model.subscale_dissipation(),
            ..Default::default()
        };
        let samples = observed.iter().map(|o| sample(o, context).into_iter().collect()).collect();
        Self { summaries, observed, had_contact: vec![false; n], samples }
    }

    pub fn summaries(&self) -> &[InterfaceSummary] {
        &self.summaries
    }

    /// Updates every interface from the committed state and returns the events of this
    /// increment, and whether interface `until_separated` has separated: it had contact and
    /// now has none, with |force| <= 1e-3 of the largest force magnitude so far (adhesive laws
    /// pull after compressive contact is lost).
    pub fn update(
        &mut self,
        model: &Model,
        context: CommitContext,
        until_separated: Option<usize>,
    ) -> (Vec<InterfaceEvent>, bool) {
        let mut events = Vec::new();
        let mut separated = false;
        for k in 0..self.summaries.len() {
            let now = observe(model, k);
            let before = self.observed[k];
            self.update_summary(model, k, &now, &before);
            if let Some(e) = self.event(model, k, &now, &before, context) {
                events.push(e);
            }
            if context.limit_point
                && let (Some(x), [.., a, b]) = (sample(&now, context), self.samples[k].as_slice())
            {
                self.summaries[k].folds.push(fold_between(model.time, a, b, &x));
            }
            self.had_contact[k] |= now.n_contact > 0;
            if let Some(x) = sample(&now, context) {
                self.samples[k].push(x);
            }
            self.observed[k] = now;
            if until_separated == Some(k) && self.is_separated(k) {
                separated = true;
            }
        }
        (events, separated)
    }

    /// Interface `k` has separated: it had contact and now has none, with |force| <= 1e-3 of
    /// the largest force magnitude so far.
    fn is_separated(&self, k: usize) -> bool {
        let (s, now) = (&self.summaries[k], &self.observed[k]);
        let force_scale = s.max_force.max(-s.most_tensile_force);
        self.had_contact[k] && now.n_contact == 0 && now.force.abs() <= 1e-3 * force_scale
    }

    /// A warning when interface `k`, which the step was to unload until separated, is still
    /// attached at its end: points still in contact, or a tensile force still above half the
    /// most tensile one ([`released`]). Its most tensile force so far is then not a pull-off.
    /// When the flat's work over the trailing retraction went mostly into plastic flow, the
    /// warning says the body is being drawn out under the attached points ([`trailing_drawing`])
    /// and where that work went: the footprint sliders, the mesh's continuum, the snaps.
    pub fn still_attached(&self, model: &Model, k: usize, units: &Units) -> Option<String> {
        let now = &self.observed[k];
        if self.is_separated(k) || released(now.n_contact, now.force, self.summaries[k].most_tensile_force) {
            return None;
        }
        let with =
            |value: f64, unit: &str| if unit.is_empty() { format!("{value:.4}") } else { format!("{value:.4} {unit}") };
        // a smooth law's tail (or a drawn-out neck) can hold with no point in contact
        let holding = match now.n_contact {
            0 => "no point in contact but a tensile force still above half the most tensile".to_string(),
            n => format!("{n} points in contact"),
        };
        let state = format!(
            "interface '{}' had not separated by the end of its unloading step (t = {}): force {} at approach {} with {holding}, so its most tensile force ({}) is not a pull-off",
            model.contributions[k].name(),
            model.time,
            with(now.force, &units.force),
            with(now.approach.unwrap_or(0.0), &units.length),
            with(self.summaries[k].most_tensile_force, &units.force)
        );
        Some(match trailing_drawing(&self.samples[k]) {
            Some(d) if d.is_drawing() => {
                let share = |part: f64| format!("{} ({:.0}%)", with(part, &units.energy), 100.0 * part / d.work);
                format!(
                    "{state}. The body under the attached points is being drawn out plastically: over the last {} of retraction the flat did {} of work, of which {} went into the footprint sliders, {} into plastic flow of the mesh's continuum and {} into snaps. A point lets go only when its law's own peak is reached, which under perfect plasticity may take much further retraction or never happen (a cold weld); how much the body can carry under a point depends on the contact mesh (a point force's limit load falls as the mesh is refined), the footprint's declared limit and hardening",
                    with(d.retraction, &units.length),
                    with(d.work, &units.energy),
                    share(d.footprint_dissipation),
                    share(d.plastic_dissipation - d.footprint_dissipation),
                    share(d.snap_dissipation)
                )
            }
            _ => format!("{state}; unload further to reach it"),
        })
    }

    /// Sets each interface's separation, pull-off and end state ([`InterfaceSummary`]).
    fn close(&mut self) {
        for (k, s) in self.summaries.iter_mut().enumerate() {
            let now = &self.observed[k];
            s.final_force = now.force;
            s.final_approach = now.approach.unwrap_or(0.0);
            s.final_n_contact = now.n_contact;
            // engaged: touched, or carried a force (a bond pulled from the start is never "in contact")
            let engaged = self.had_contact[k] || s.max_force > 0.0 || s.most_tensile_force < 0.0;
            s.separated = engaged && released(now.n_contact, now.force, s.most_tensile_force);
            (s.pull_off_force, s.approach_at_pull_off, s.contact_area_at_pull_off) = if s.separated {
                (
                    Some(s.most_tensile_force),
                    Some(s.approach_at_most_tensile_force),
                    Some(s.contact_area_at_most_tensile_force),
                )
            } else {
                (None, None, None)
            };
        }
    }

    /// Maximum and pull-off forces, areas, work and viscous share of interface `k`.
    fn update_summary(&mut self, model: &Model, k: usize, now: &InterfaceObservables, before: &InterfaceObservables) {
        let s = &mut self.summaries[k];
        let (a_now, a_before) = (now.approach.unwrap_or(0.0), before.approach.unwrap_or(0.0));
        // work of the flat: trapezoid in approach
        s.work_of_flat += 0.5 * (now.force + before.force) * (a_now - a_before);
        s.gross_work_of_flat += 0.5 * (now.force.abs() + before.force.abs()) * (a_now - a_before).abs();
        if now.force > s.max_force {
            s.max_force = now.force;
            s.approach_at_max_force = a_now;
            s.n_contact_at_max_force = now.n_contact as f64;
            s.contact_area_at_max_force = now.contact_area;
            if let Some((_, fields)) = model.contributions[k].point_output() {
                // the law's own gap: with a footprint correction the gap at the mesh also holds
                // the footprint's compliance and indentation, which are not the asperity's
                let gap = fields.iter().find(|f| f.name == crate::observables::LAW_GAP_FIELD).unwrap_or(&fields[0]);
                let compression = gap.values.iter().fold(0.0f64, |m, g| m.max(-g));
                s.max_point_compression_at_max_force = compression;
                s.point_share_of_approach_at_max_force = if a_now > 0.0 { compression / a_now } else { 0.0 };
            }
        }
        if now.force < s.most_tensile_force {
            s.most_tensile_force = now.force;
            s.approach_at_most_tensile_force = a_now;
            s.contact_area_at_most_tensile_force = now.contact_area;
        }
        s.max_contact_area = s.max_contact_area.max(now.contact_area);
        if let Some(r) = now.contact_resistance {
            if now.force >= s.max_force {
                s.contact_resistance_at_max_force = Some(r);
            }
            s.min_contact_resistance = Some(s.min_contact_resistance.map_or(r, |m: f64| m.min(r)));
        }
        let viscous = now.viscous_dissipation.unwrap_or(0.0);
        s.viscous_dissipation = viscous;
        s.viscous_share_of_work = if s.gross_work_of_flat > 0.0 { viscous / s.gross_work_of_flat } else { 0.0 };
    }

    /// The event of interface `k` at this increment, if any: a limit point; a jump (the
    /// increment had to be cut and the force changed by more than 5% of the largest force
    /// magnitude so far); contact lost or gained; or a plain cut.
    fn event(
        &mut self,
        model: &Model,
        k: usize,
        now: &InterfaceObservables,
        before: &InterfaceObservables,
        context: CommitContext,
    ) -> Option<InterfaceEvent> {
        let contact_changed = now.n_contact != before.n_contact;
        if !(contact_changed || context.cuts_since_commit > 0 || context.limit_point) {
            return None;
        }
        let s = &mut self.summaries[k];
        let scale = s.max_force.max(-s.most_tensile_force).max(now.force.abs());
        let kind = if context.limit_point {
            "limit_point"
        } else if !context.by_arc_length
            && context.cuts_since_commit > 0
            && (now.force - before.force).abs() > 0.05 * scale
        {
            "jump"
        } else if now.n_contact < before.n_contact {
            "contact_lost"
        } else if now.n_contact > before.n_contact {
            "contact_gained"
        } else {
            "increment_cut"
        };
        if contact_changed {
            s.contact_events += 1;
        }
        Some(InterfaceEvent {
            time: model.time,
            approach: now.approach.unwrap_or(0.0),
            interface: model.contributions[k].name().to_string(),
            kind,
            n_contact_before: before.n_contact,
            n_contact_after: now.n_contact,
            force_before: before.force,
            force_after: now.force,
            cuts_before: context.cuts_since_commit,
        })
    }

    /// At the end of the run (pseudo-time `t`): a `viscous_share_exceeded` event and a warning
    /// for each interface whose viscous regularisation dissipated too large a share of the
    /// gross work of the flat.
    pub fn finish(&mut self, t: f64, units: &Units) -> (Vec<InterfaceEvent>, Vec<String>) {
        self.close();
        for (s, samples) in self.summaries.iter_mut().zip(&self.samples) {
            s.cycles = cycles(samples);
            s.contact_resistance_at_force = resistance_hysteresis(samples);
        }
        let (mut events, mut warnings) = (Vec::new(), Vec::new());
        for (i, now) in self.summaries.iter().zip(&self.observed) {
            if i.viscous_dissipation > 0.0 && i.viscous_share_of_work >= i.max_viscous_share {
                events.push(InterfaceEvent {
                    time: t,
                    approach: now.approach.unwrap_or(0.0),
                    interface: i.name.clone(),
                    kind: "viscous_share_exceeded",
                    n_contact_before: now.n_contact,
                    n_contact_after: now.n_contact,
                    force_before: now.force,
                    force_after: now.force,
                    cuts_before: 0,
                });
                warnings.push(format!(
                    "interface '{}': the viscous regularisation dissipated {:.4e}{} = {:.1}% of the gross work of the flat, above the limit max_viscous_share = {}; lower its viscosity or use solver.continuation = \"arc-length\"",
                    i.name,
                    i.viscous_dissipation,
                    if units.energy.is_empty() { String::new() } else { format!(" {}", units.energy) },
                    100.0 * i.viscous_share_of_work,
                    i.max_viscous_share
                ));
            }
        }
        (events, warnings)
    }
}

#[cfg(test)]
mod fold_tests {
    use super::*;

    fn at(force: f64, approach: f64) -> InterfaceSample {
        InterfaceSample {
            approach,
            force,
            contact_area: 0.0,
            n_contact: 0,
            resistance: None,
            plastic_dissipation: 0.0,
            footprint_dissipation: 0.0,
            snap_dissipation: 0.0,
        }
    }

    /// On a parabolic fold a(F) = 1 - (F - 3)^2 the vertex (F = 3, a = 1) is recovered exactly
    /// from any three states around it; unequal spacing included.
    #[test]
    fn the_fold_of_a_parabolic_path_is_located_exactly() {
        let path = |f: f64| 1.0 - (f - 3.0) * (f - 3.0);
        let fold = fold_between(1.5, &at(1.0, path(1.0)), &at(2.5, path(2.5)), &at(3.2, path(3.2)));
        assert!((fold.force - 3.0).abs() < 1e-12 && (fold.approach - 1.0).abs() < 1e-12, "{fold:?}");
        assert_eq!(fold.time, 1.5);
        // a straight line has no vertex: the middle state is kept
        let flat = fold_between(1.0, &at(1.0, 1.0), &at(2.0, 2.0), &at(3.0, 3.0));
        assert_eq!((flat.force, flat.approach), (2.0, 2.0));
    }
}
