//! Arc-length control for crossing a limit point: started from the last converged
//! load-controlled increment, it solves increments of length ds in the (du, c dt) norm
//! ([`crate::nonlinear::arc_length`]), halves ds on failure, grows it after easy increments, and
//! stays inside its step window; load control resumes once t moves forward past the target
//! that failed.

use super::step::Incrementation;
use super::{Attempt, AttemptFailure, Crossing, CrossingOutcome, Cut, CutRefused, PathControl, Solvers, StepWindow};
use crate::model::Model;
use crate::nonlinear::ReferenceScales;
use crate::nonlinear::arc_length::{ArcLengthRequest, PreviousIncrement, solve_arc_length_increment};
use crate::vector::norm;

pub struct ArcLengthControl {
    /// Current arc length (displacement units), its first value and its cap.
    pub ds: f64,
    ds_initial: f64,
    ds_max: f64,
    /// Displacement per unit load parameter weighting t in the arc length (the rate of the
    /// last load-controlled increment).
    time_weight: f64,
    previous: PreviousIncrement,
    /// Load control resumes once the load parameter moves forward past this value.
    resume_after: f64,
    /// The increment of the last converged attempt, until it is accepted.
    pending: Option<PreviousIncrement>,
}

impl ArcLengthControl {
    /// A crossing that starts from the last converged load-controlled increment `previous`:
    /// the first arc length is that increment's length in the (du, c dt) norm with c its
    /// displacement rate (so sqrt 2 |du|), capped at 10 |du|. None when it did not move.
    pub fn start(previous: PreviousIncrement, resume_after: f64) -> Option<Self> {
        let length = norm(&previous.du);
        previous.moved_forward().then(|| Self {
            ds: length * std::f64::consts::SQRT_2,
            ds_initial: length * std::f64::consts::SQRT_2,
            ds_max: 10.0 * length,
            time_weight: length / previous.dt,
            previous,
            resume_after,
            pending: None,
        })
    }
}

impl Crossing for ArcLengthControl {
    fn accept(&mut self, t_new: f64, iterations: usize, incrementation: &Incrementation) -> CrossingOutcome {
        let increment = self.pending.take().expect("accept follows a converged attempt");
        let outcome = CrossingOutcome::of(&self.previous, &increment, t_new, self.resume_after);
        if iterations <= incrementation.easy_iterations {
            self.ds = (self.ds * incrementation.growth_factor).min(self.ds_max);
        }
        self.previous = increment;
        outcome
    }
}

impl PathControl for ArcLengthControl {
    fn attempt(
        &mut self,
        model: &mut Model,
        solvers: Solvers<'_>,
        window: &StepWindow<'_>,
        scales: ReferenceScales,
    ) -> Attempt {
        let request = ArcLengthRequest {
            t0: window.t,
            ds: self.ds,
            previous: &self.previous,
            time_weight: self.time_weight,
            rate_step: 1e-6 * window.t_end,
        };
        match solve_arc_length_increment(model, solvers.linear, request, solvers.nonlinear.settings(), scales) {
            Ok((report, increment)) => {
                // arc length stays between breakpoints and inside the step; past them load
                // control resumes from the committed state
                if window.excludes(window.t + increment.dt) {
                    model.rollback();
                    return Attempt::OutsideWindow;
                }
                self.pending = Some(increment);
                Attempt::Converged(report)
            }
            Err(e) => Attempt::Failed(e),
        }
    }

    fn cut(&mut self, _failure: &AttemptFailure) -> Result<Cut, CutRefused> {
        self.ds *= 0.5;
        if self.ds < 1e-4 * self.ds_initial {
            Err(CutRefused::ArcLengthStalled { arc_length: self.ds })
        } else {
            Ok(Cut::ArcLength(self.ds))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_crossing_starts_from_the_last_increment_and_stalls_after_halving_to_1e_4() {
        let previous = PreviousIncrement { du: vec![3.0, 4.0], dt: 0.5 };
        let mut arc = ArcLengthControl::start(previous, 1.0).unwrap();
        assert!((arc.ds - 5.0 * std::f64::consts::SQRT_2).abs() < 1e-12);
        assert!((arc.time_weight - 10.0).abs() < 1e-12);
        let failure =
            AttemptFailure::Solver(crate::nonlinear::IncrementFailure::Diverged { iterations: 25, residual: 1.0 });
        let halvings = std::iter::from_fn(|| arc.cut(&failure).ok()).count();
        // 0.5^k >= 1e-4 for k = 1..13
        assert_eq!(halvings, 13);
        assert!(ArcLengthControl::start(PreviousIncrement { du: vec![0.0], dt: 0.5 }, 1.0).is_none());
    }

    #[test]
    fn accepting_a_turned_increment_is_a_limit_point_and_forward_past_the_failure_resumes() {
        let inc = Incrementation::for_tests();
        let mut arc = ArcLengthControl::start(PreviousIncrement { du: vec![1.0], dt: 0.1 }, 0.5).unwrap();
        arc.pending = Some(PreviousIncrement { du: vec![1.0], dt: -0.01 });
        let turned = arc.accept(0.39, 10, &inc);
        assert!(turned.limit_point && !turned.resume);
        arc.pending = Some(PreviousIncrement { du: vec![1.0], dt: 0.02 });
        let forward = arc.accept(0.51, 3, &inc);
        assert!(forward.limit_point && forward.resume);
    }
}
