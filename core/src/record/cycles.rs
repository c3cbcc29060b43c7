//! Load cycles of a rigid-flat interface: the committed history split at each reversal from
//! unloading back to loading, with each cycle's key numbers (`cycles.csv`, and in summary.json),
//! and the contact resistance's hysteresis: its value at the same force on loading and on
//! unloading.

use super::summary::{CycleSummary, ResistanceAtForce, RunSummary};
use super::{CommittedIncrement, Observer};
use crate::error::Result;
use crate::model::Model;
use crate::output::write_atomically;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// One committed state of an interface.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct InterfaceSample {
    pub approach: f64,
    /// Positive compressive.
    pub force: f64,
    pub contact_area: f64,
    /// Points (or integration points) in contact.
    pub n_contact: usize,
    /// Ohm; infinite without contact; None where not modelled.
    pub resistance: Option<f64>,
    /// The plastic dissipation (the whole model's: continuum and footprint sliders) at this
    /// state.
    pub plastic_dissipation: f64,
    /// The part of it in the interfaces' footprint sliders.
    pub footprint_dissipation: f64,
    /// The snaps' dissipation so far (the whole model's,
    /// [`super::CommittedIncrement::snap_dissipation`]).
    pub snap_dissipation: f64,
}

/// An interface has let go at a state with `n_contact` points in contact and `force`, after a
/// most tensile force `most_tensile`: no point is in contact and the force no longer holds
/// half the most tensile one (a long-range law's tail, a few percent of it, is past the
/// pull-off).
pub fn released(n_contact: usize, force: f64, most_tensile: f64) -> bool {
    n_contact == 0 && !(most_tensile < 0.0 && force < 0.5 * most_tensile)
}

/// Share of the whole approach range a reversal must exceed to count: smaller turns (an
/// arc-length path turning back through a snap) stay inside their cycle.
pub const REVERSAL_SHARE: f64 = 0.2;

/// Index ranges [start, end] (inclusive) of the cycles: a new cycle starts at the lowest
/// approach of a retraction once the approach has risen from it again by more than
/// [`REVERSAL_SHARE`] of the whole approach range (and has fallen by as much before).
pub fn cycle_ranges(samples: &[InterfaceSample]) -> Vec<(usize, usize)> {
    if samples.len() < 2 {
        return Vec::new();
    }
    let (lo, hi) =
        samples.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), s| (l.min(s.approach), h.max(s.approach)));
    let turn = REVERSAL_SHARE * (hi - lo);
    let mut ranges = Vec::new();
    let (mut start, mut falling) = (0, false);
    let (mut peak, mut valley, mut valley_at) = (samples[0].approach, samples[0].approach, 0);
    for (i, s) in samples.iter().enumerate() {
        let a = s.approach;
        if !falling {
            peak = peak.max(a);
            if a < peak - turn {
                falling = true;
                (valley, valley_at) = (a, i);
            }
        } else if a < valley {
            (valley, valley_at) = (a, i);
        } else if a > valley + turn {
            ranges.push((start, valley_at));
            start = valley_at;
            falling = false;
            peak = a;
        }
    }
    ranges.push((start, samples.len() - 1));
    ranges
}

/// The key numbers of every cycle.
pub fn cycles(samples: &[InterfaceSample]) -> Vec<CycleSummary> {
    cycle_ranges(samples)
        .into_iter()
        .enumerate()
        .map(|(k, (start, end))| {
            let part = &samples[start..=end];
            let mut c = CycleSummary { cycle: k + 1, max_approach: f64::NEG_INFINITY, ..Default::default() };
            let mut max_force = f64::NEG_INFINITY;
            for (i, s) in part.iter().enumerate() {
                c.max_approach = c.max_approach.max(s.approach);
                if s.force > max_force {
                    max_force = s.force;
                    c.contact_resistance_at_max_force = s.resistance;
                }
                c.most_tensile_force = c.most_tensile_force.min(s.force);
                c.max_contact_area = c.max_contact_area.max(s.contact_area);
                if i > 0 {
                    let p = &part[i - 1];
                    let da = s.approach - p.approach;
                    c.work_of_flat += 0.5 * (s.force + p.force) * da;
                    if da < 0.0 {
                        c.opening_work += 0.5 * ((-s.force).max(0.0) + (-p.force).max(0.0)) * (-da);
                    }
                }
            }
            c.max_force = max_force.max(0.0);
            let (first, last) = (&part[0], &part[part.len() - 1]);
            let touched = part.iter().any(|s| s.n_contact > 0 || s.force != 0.0);
            c.separated = touched && released(last.n_contact, last.force, c.most_tensile_force);
            c.pull_off_force = c.separated.then_some(c.most_tensile_force);
            c.plastic_dissipation = last.plastic_dissipation - first.plastic_dissipation;
            c.snap_dissipation = last.snap_dissipation - first.snap_dissipation;
            c
        })
        .collect()
}

/// The resistance where the force first reaches `level` along `branch` (linear in force, of
/// log R between the samples that bracket it); None if it never does or R is not finite there.
fn resistance_at(branch: &[InterfaceSample], level: f64, rising: bool) -> Option<f64> {
    branch.windows(2).find_map(|w| {
        let (a, b) = (&w[0], &w[1]);
        let crosses = if rising { a.force <= level && b.force >= level } else { a.force >= level && b.force <= level };
        if !crosses {
            return None;
        }
        let (ra, rb) = (a.resistance?, b.resistance?);
        let s = if b.force == a.force { 1.0 } else { (level - a.force) / (b.force - a.force) };
        match (ra.is_finite(), rb.is_finite()) {
            (true, true) => Some((ra.ln() + s * (rb.ln() - ra.ln())).exp()),
            (true, false) => Some(ra),
            (false, true) => Some(rb),
            (false, false) => None,
        }
    })
}

/// The first cycle's resistance at 25, 50 and 75% of its maximum force, on loading (up to the
/// maximum) and on unloading (after it); empty without a resistance or a compressive force.
pub fn resistance_hysteresis(samples: &[InterfaceSample]) -> Vec<ResistanceAtForce> {
    let Some(&(start, end)) = cycle_ranges(samples).first() else { return Vec::new() };
    let part = &samples[start..=end];
    if part.iter().all(|s| s.resistance.is_none()) {
        return Vec::new();
    }
    let (peak, max_force) =
        part.iter().enumerate().fold((0, f64::NEG_INFINITY), |m, (i, s)| if s.force > m.1 { (i, s.force) } else { m });
    if !(max_force > 0.0) {
        return Vec::new();
    }
    [0.25, 0.5, 0.75]
        .into_iter()
        .map(|fraction| {
            let force = fraction * max_force;
            ResistanceAtForce {
                fraction_of_max_force: fraction,
                force,
                loading: resistance_at(&part[..=peak], force, true),
                unloading: resistance_at(&part[peak..], force, false),
            }
        })
        .collect()
}

/// Writes `cycles.csv` when the run ends: one row per interface and load cycle.
pub struct CyclesWriter {
    path: PathBuf,
}

impl CyclesWriter {
    pub fn new(directory: &Path) -> Self {
        Self { path: directory.join("cycles.csv") }
    }
}

impl Observer for CyclesWriter {
    fn committed(&mut self, _model: &Model, _increment: &CommittedIncrement) -> Result<()> {
        Ok(())
    }

    fn finished(&mut self, _model: &Model, summary: &RunSummary) -> Result<()> {
        let mut text = String::from(
            "interface,cycle,max_approach,max_force,most_tensile_force,separated,pull_off_force,max_contact_area,contact_resistance_at_max_force,opening_work,work_of_flat,plastic_dissipation,snap_dissipation\n",
        );
        let mut rows = 0;
        for i in &summary.interfaces {
            for c in &i.cycles {
                let resistance = c.contact_resistance_at_max_force.map_or(String::new(), |r| format!("{r:.10e}"));
                let pull_off = c.pull_off_force.map_or(String::new(), |f| format!("{f:.10e}"));
                text.push_str(&format!(
                    "{},{},{:.10e},{:.10e},{:.10e},{},{pull_off},{:.10e},{resistance},{:.10e},{:.10e},{:.10e},{:.10e}\n",
                    i.name,
                    c.cycle,
                    c.max_approach,
                    c.max_force,
                    c.most_tensile_force,
                    c.separated,
                    c.max_contact_area,
                    c.opening_work,
                    c.work_of_flat,
                    c.plastic_dissipation,
                    c.snap_dissipation
                ));
                rows += 1;
            }
        }
        if rows == 0 {
            return Ok(());
        }
        write_atomically(&self.path, text.as_bytes())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample(approach: f64, force: f64, resistance: f64) -> InterfaceSample {
        InterfaceSample {
            approach,
            force,
            contact_area: force.max(0.0),
            n_contact: usize::from(force > 0.0),
            resistance: Some(resistance),
            plastic_dissipation: 0.0,
            footprint_dissipation: 0.0,
            snap_dissipation: 0.0,
        }
    }

    /// Two triangle cycles, 0 -> 2 -> -1 -> 2 -> -1, with F = 10 a on loading and F = 10 a - 5
    /// on unloading (an adhesive offset), R = exp(-F / 10) where F > 0.
    fn two_cycles() -> Vec<InterfaceSample> {
        let mut s = Vec::new();
        let r = |f: f64| if f > 0.0 { (-f / 10.0).exp() } else { f64::INFINITY };
        for cycle in 0..2 {
            let start = if cycle == 0 { 0.0 } else { -1.0 };
            for k in 0..=8 {
                let a = start + (2.0 - start) * k as f64 / 8.0;
                if !(cycle == 1 && k == 0) {
                    s.push(sample(a, 10.0 * a, r(10.0 * a)));
                }
            }
            for k in 1..=12 {
                let a = 2.0 - 3.0 * k as f64 / 12.0;
                let f = if a > 0.5 { 10.0 * a - 5.0 } else { (10.0 * a - 5.0).max(-8.0) };
                s.push(sample(a, f, r(f)));
            }
        }
        s
    }

    #[test]
    fn cycles_split_at_reversals_with_their_numbers() {
        let s = two_cycles();
        let ranges = cycle_ranges(&s);
        assert_eq!(ranges.len(), 2, "{ranges:?}");
        let c = cycles(&s);
        assert_eq!((c[0].cycle, c[1].cycle), (1, 2));
        for k in &c {
            assert_eq!(k.max_approach, 2.0);
            assert_eq!(k.max_force, 20.0);
            assert_eq!(k.most_tensile_force, -8.0);
            // each cycle ends at a = -1 with F = -8, still holding its most tensile force
            assert!(!k.separated && k.pull_off_force.is_none());
            assert!((k.contact_resistance_at_max_force.unwrap() - (-2.0f64).exp()).abs() < 1e-15);
        }
        // opening work: integral of max(-F, 0) over the retraction from a = 2 to -1, with
        // F = 10 a - 5 down to -8 (at a = -0.3): -F > 0 below a = 0.5; the integral is
        // int_{-0.3}^{0.5} (5 - 10 a) da + 8 * 0.7 = 3.2 + 5.6 = 8.8 (trapezoids exact on the
        // linear pieces; the kink at a = -0.3 falls between samples, so allow the quadrature
        // error of one step)
        assert!((c[0].opening_work - 8.8).abs() < 0.2, "{}", c[0].opening_work);
    }

    #[test]
    fn a_cycle_separates_only_when_nothing_holds_at_its_end() {
        // a = 2 -> -1 with F = 10 a - 5 down to -8, then back to 0 (the neck broken) below a = -0.6
        let mut s: Vec<InterfaceSample> = (0..=8).map(|k| sample(2.0 * k as f64 / 8.0, 2.5 * k as f64, 1.0)).collect();
        for k in 1..=12 {
            let a = 2.0 - 3.0 * k as f64 / 12.0;
            let f = if a > -0.6 { (10.0 * a - 5.0).max(-8.0) } else { 0.0 };
            s.push(sample(a, f, 1.0));
        }
        let c = &cycles(&s)[0];
        assert!(c.separated);
        assert_eq!((c.most_tensile_force, c.pull_off_force), (-8.0, Some(-8.0)));
        // a tail of a long-range law (5% of the most tensile force) has let go; a hold at 60% has not
        assert!(released(0, -0.4, -8.0) && !released(0, -4.8, -8.0) && !released(1, 0.0, -8.0));
    }

    #[test]
    fn a_small_turn_of_the_approach_stays_inside_its_cycle() {
        // an arc-length path turning back by 0.1 (of a 3.0 range) through a snap on loading
        let mut s = two_cycles();
        s.insert(4, sample(0.85, 8.5, 0.4));
        s.insert(5, sample(0.75, 7.5, 0.45));
        assert_eq!(cycle_ranges(&s).len(), 2);
        assert_eq!(cycles(&s)[0].max_force, 20.0);
    }

    #[test]
    fn resistance_hysteresis_reads_both_branches_at_the_same_force() {
        let h = resistance_hysteresis(&two_cycles());
        assert_eq!(h.len(), 3);
        for r in &h {
            // R = exp(-F / 10) on both branches here: the same at the same force, and log R
            // is linear in F, so the interpolation is exact
            let expected = (-r.force / 10.0).exp();
            assert!((r.loading.unwrap() / expected - 1.0).abs() < 1e-12, "{r:?}");
            assert!((r.unloading.unwrap() / expected - 1.0).abs() < 1e-12, "{r:?}");
        }
        assert_eq!(h[1].force, 10.0);
    }
}
