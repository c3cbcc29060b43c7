//! Dissipation control for crossing the limit points and snap-backs of damage: started from
//! the last converged load-controlled increment, each increment dissipates an energy tau
//! ([`crate::nonlinear::dissipation`]); tau is first the dissipation of a step like the last
//! one, halves on failure and grows after easy increments. Where nothing damages within
//! reach of the first increment (the instability is not a crack's, e.g. an adhesive jump of a
//! reversible law), the crossing goes on as a spherical arc length instead. An increment
//! that finds nothing damaging asked for more energy than the cracks have left: tau is
//! quartered, and once it is below [`EXHAUSTED_FRACTION`] of its first value damage has run
//! its course (the last points have failed) and load control takes over, or, if no increment
//! had converged yet, the arc length crosses.

use super::arc_length_control::ArcLengthControl;
use super::step::Incrementation;
use super::{Attempt, AttemptFailure, Crossing, CrossingOutcome, Cut, CutRefused, PathControl, Solvers, StepWindow};
use crate::model::Model;
use crate::nonlinear::arc_length::PreviousIncrement;
use crate::nonlinear::dissipation::{DissipationRequest, dissipation_of, solve_dissipation_increment};
use crate::nonlinear::{IncrementFailure, ReferenceScales};

pub struct DissipationControl {
    /// Energy per increment (None until the first attempt measures it), its first value.
    energy: Option<f64>,
    energy_initial: f64,
    /// The last converged increment and the energy it dissipated (None: load-controlled).
    previous: PreviousIncrement,
    previous_energy: Option<f64>,
    /// Load control resumes once the load parameter moves forward past this value.
    resume_after: f64,
    /// The increment of the last converged attempt and its energy, until it is accepted.
    pending: Option<(PreviousIncrement, f64)>,
    /// Set when no damage was within reach of the first increment: an arc length crosses.
    fallback: Option<ArcLengthControl>,
}

/// Growth of tau is capped at this multiple of its first value.
const MAX_ENERGY_GROWTH: f64 = 10.0;

/// Below this fraction of its first value, a tau that still finds nothing damaging means
/// damage has run its course.
pub const EXHAUSTED_FRACTION: f64 = 1e-3;

impl DissipationControl {
    /// A crossing from the last converged load-controlled increment `previous`; None when it
    /// did not move.
    pub fn start(previous: PreviousIncrement, resume_after: f64) -> Option<Self> {
        previous.moved_forward().then_some(Self {
            energy: None,
            energy_initial: 0.0,
            previous,
            previous_energy: None,
            resume_after,
            pending: None,
            fallback: None,
        })
    }

    /// The increment to start Newton from: the previous one, scaled to the energy asked for
    /// when it was itself dissipation-controlled.
    fn predictor(&self, energy: f64) -> PreviousIncrement {
        let scale = match self.previous_energy {
            Some(e) if e > 0.0 => energy / e,
            _ => 1.0,
        };
        PreviousIncrement { du: self.previous.du.iter().map(|x| x * scale).collect(), dt: self.previous.dt * scale }
    }

    /// tau, measured at the first attempt as the dissipation of a step like the last one;
    /// None (and the arc-length fallback set up) when that step dissipates nothing.
    fn energy(&mut self, model: &mut Model, t0: f64) -> Result<Option<f64>, IncrementFailure> {
        if let Some(e) = self.energy {
            return Ok(Some(e));
        }
        let measured = dissipation_of(model, t0, &self.previous);
        model.rollback();
        model.apply_time(t0);
        match measured {
            Ok(e) if e > 0.0 => {
                (self.energy, self.energy_initial) = (Some(e), e);
                Ok(Some(e))
            }
            Ok(_) | Err(IncrementFailure::NoDissipation) => {
                self.fallback = ArcLengthControl::start(self.previous.clone(), self.resume_after);
                Ok(None)
            }
            Err(e) => Err(e),
        }
    }
}

impl PathControl for DissipationControl {
    fn attempt(
        &mut self,
        model: &mut Model,
        solvers: Solvers<'_>,
        window: &StepWindow<'_>,
        scales: ReferenceScales,
    ) -> Attempt {
        let energy = match self.fallback {
            Some(_) => None,
            None => match self.energy(model, window.t) {
                Ok(energy) => energy,
                Err(e) => return Attempt::Failed(e),
            },
        };
        // (None: the arc-length fallback crosses)
        if let Some(energy) = energy {
            let predictor = self.predictor(energy);
            let request =
                DissipationRequest { t0: window.t, energy, predictor: &predictor, rate_step: 1e-6 * window.t_end };
            let settings = solvers.nonlinear.settings();
            match solve_dissipation_increment(model, &mut *solvers.linear, request, settings, scales) {
                Ok((report, increment, dissipated)) => {
                    if window.excludes(window.t + increment.dt) {
                        model.rollback();
                        return Attempt::OutsideWindow;
                    }
                    self.pending = Some((increment, dissipated));
                    return Attempt::Converged(report);
                }
                Err(IncrementFailure::NoDissipation) if energy < EXHAUSTED_FRACTION * self.energy_initial => {
                    model.rollback();
                    if self.previous_energy.is_some() {
                        // damage has run its course: load control goes on
                        return Attempt::OutsideWindow;
                    }
                    // nothing damaged within reach even of a small step: cross by arc length
                    self.fallback = ArcLengthControl::start(self.previous.clone(), self.resume_after);
                }
                Err(e) => return Attempt::Failed(e),
            }
        }
        match self.fallback.as_mut() {
            Some(arc) => arc.attempt(model, solvers, window, scales),
            None => Attempt::Failed(IncrementFailure::NoDissipation),
        }
    }

    fn cut(&mut self, failure: &AttemptFailure) -> Result<Cut, CutRefused> {
        if let Some(arc) = self.fallback.as_mut() {
            return arc.cut(failure);
        }
        let Some(energy) = self.energy.as_mut() else {
            return Err(CutRefused::DissipationNotStarted);
        };
        if matches!(failure, AttemptFailure::Solver(IncrementFailure::NoDissipation)) {
            // more than the cracks have left: see the module documentation
            *energy *= 0.25;
            return Ok(Cut::Energy { energy: *energy, emptied: true });
        }
        *energy *= 0.5;
        if *energy < 1e-4 * self.energy_initial {
            Err(CutRefused::DissipationStalled { energy: *energy })
        } else {
            Ok(Cut::Energy { energy: *energy, emptied: false })
        }
    }
}

impl Crossing for DissipationControl {
    fn accept(&mut self, t_new: f64, iterations: usize, incrementation: &Incrementation) -> CrossingOutcome {
        if let Some(arc) = self.fallback.as_mut() {
            return arc.accept(t_new, iterations, incrementation);
        }
        let (increment, dissipated) = self.pending.take().expect("accept follows a converged attempt");
        let outcome = CrossingOutcome::of(&self.previous, &increment, t_new, self.resume_after);
        if let Some(energy) = self.energy.as_mut()
            && iterations <= incrementation.easy_iterations
        {
            *energy = (*energy * incrementation.growth_factor).min(MAX_ENERGY_GROWTH * self.energy_initial);
        }
        self.previous = increment;
        self.previous_energy = Some(dissipated);
        outcome
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_predictor_is_the_last_increment_scaled_to_the_energy_asked_for() {
        let mut control = DissipationControl::start(PreviousIncrement { du: vec![1.0, 2.0], dt: 0.1 }, 0.5).unwrap();
        // from load control: the last increment as it was
        let p = control.predictor(3.0);
        assert_eq!((p.du, p.dt), (vec![1.0, 2.0], 0.1));
        // after a dissipation-controlled increment that dissipated 2: scaled by 3 / 2
        control.previous_energy = Some(2.0);
        let p = control.predictor(3.0);
        assert_eq!((p.du, p.dt), (vec![1.5, 3.0], 0.15000000000000002));
        assert!(DissipationControl::start(PreviousIncrement { du: vec![0.0], dt: 0.1 }, 0.5).is_none());
    }

    #[test]
    fn cuts_halve_the_energy_and_stall_below_1e_4_of_the_first() {
        let mut control = DissipationControl::start(PreviousIncrement { du: vec![1.0], dt: 0.1 }, 0.5).unwrap();
        let failure = AttemptFailure::Solver(IncrementFailure::Diverged { iterations: 25, residual: 1.0 });
        assert!(control.cut(&failure).is_err(), "no energy measured yet: cannot cut");
        (control.energy, control.energy_initial) = (Some(1.0), 1.0);
        let halvings = std::iter::from_fn(|| control.cut(&failure).ok()).count();
        assert_eq!(halvings, 13);
    }
}
