//! Load (or displacement) control: the load parameter t is prescribed increment by increment.
//! The next target is t + dt, clipped to the step end and to the first amplitude breakpoint
//! (so load reversals are exact), and snapped to the step end when within 1e-3 dt of it. A
//! failed increment is cut by `cut_factor`; one that converged in few iterations lets the next
//! grow by `growth_factor`.
//!
//! The predictor (where the solve starts): the last converged increment extrapolated,
//! u += du_last (t_target - t) / dt_last; where there is no rate to extrapolate (a run's first
//! increment, the first after a load reversal) the tangent predictor
//! ([`crate::nonlinear::tangent_predictor`], unless [`StartPredictor::None`] is asked); after
//! a failed attempt or a snap, none (the committed state).

use super::step::Incrementation;
use super::{Attempt, AttemptFailure, Cut, CutRefused, PathControl, Solvers, StepWindow};
use crate::model::Model;
use crate::nonlinear::{IncrementReport, ReferenceScales};

/// The predictor of the increments that have no earlier rate to extrapolate.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum StartPredictor {
    /// Along the tangent at the committed state.
    #[default]
    Tangent,
    /// None: the solve starts from the committed state.
    None,
}

/// Where the next attempt starts.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
enum Predictor {
    /// The committed state.
    None,
    /// Along the tangent at the committed state.
    Tangent,
    /// The last converged increment (free-dof displacement increment, dt), scaled.
    Extrapolate(Vec<f64>, f64),
}

/// The state of a [`LoadControl`] a checkpoint keeps ([`LoadControl::saved`]).
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct LoadControlState {
    dt: f64,
    predictor: Predictor,
    first_failed_target: Option<f64>,
}

impl LoadControlState {
    /// The state to go on from after a failure: increment `dt`, no failed target (the
    /// predictor was already forgotten by the failure).
    pub fn restart_at(&mut self, dt: f64) {
        (self.dt, self.first_failed_target) = (dt, None);
    }
}

pub struct LoadControl {
    /// The next increment of the load parameter.
    pub dt: f64,
    incrementation: Incrementation,
    /// Where the next attempt starts.
    predictor: Predictor,
    /// The predictor where there is no rate to extrapolate.
    start_predictor: StartPredictor,
    /// The target of the first failed attempt since the last commit (where a limit point lies).
    pub first_failed_target: Option<f64>,
}

impl LoadControl {
    pub fn new(incrementation: &Incrementation, start_predictor: StartPredictor) -> Self {
        let mut control = Self {
            dt: incrementation.initial,
            incrementation: incrementation.clone(),
            predictor: Predictor::None,
            start_predictor,
            first_failed_target: None,
        };
        control.predictor = control.at_start();
        control
    }

    /// The predictor where there is no rate to extrapolate.
    fn at_start(&self) -> Predictor {
        match self.start_predictor {
            StartPredictor::Tangent => Predictor::Tangent,
            StartPredictor::None => Predictor::None,
        }
    }

    /// A new step with its own incrementation (the predictor carries over).
    pub fn start_step(&mut self, incrementation: &Incrementation) {
        self.incrementation = incrementation.clone();
        self.dt = incrementation.initial;
    }

    /// The pseudo-time the next attempt aims at.
    pub fn target(&self, window: &StepWindow<'_>) -> f64 {
        let t = window.t;
        let mut target = (t + self.dt).min(window.step_end);
        for &b in window.breakpoints {
            if b > t + 1e-12 * window.t_end && b < target {
                target = b;
            }
        }
        if window.step_end - target < 1e-3 * self.dt {
            target = window.step_end;
        }
        target
    }

    /// Remembers a converged increment for the predictor: extrapolated, except when the load
    /// parameter did not move forward (a snap: none) or turns at a reversal (the start
    /// predictor).
    pub fn remember(&mut self, du: Vec<f64>, dt: f64, reversal: bool) {
        self.predictor = if dt <= 0.0 {
            Predictor::None
        } else if reversal {
            self.at_start()
        } else {
            Predictor::Extrapolate(du, dt)
        };
        self.first_failed_target = None;
    }

    /// Forgets the predictor (after a failed attempt): the next attempt starts from the
    /// committed state.
    pub fn forget(&mut self) {
        self.predictor = Predictor::None;
    }

    /// The next increment grows after an easy one.
    pub fn grow(&mut self) {
        self.dt = (self.dt * self.incrementation.growth_factor).min(self.incrementation.maximum);
    }

    /// Sets the next increment, kept within the incrementation's bounds.
    pub fn set_increment(&mut self, dt: f64) {
        self.dt = dt.clamp(self.incrementation.minimum, self.incrementation.maximum);
    }

    /// What a checkpoint keeps: the next increment, the predictor and the failed target.
    pub fn saved(&self) -> LoadControlState {
        LoadControlState {
            dt: self.dt,
            predictor: self.predictor.clone(),
            first_failed_target: self.first_failed_target,
        }
    }

    /// Goes on from a checkpoint with this control's incrementation (the resumed run's: its
    /// bounds may have changed) and the saved increment, kept within them.
    pub fn restore(&mut self, saved: LoadControlState) {
        self.predictor = saved.predictor;
        self.first_failed_target = saved.first_failed_target;
        self.set_increment(saved.dt);
    }

    /// The increment to go on with after a path-following detour that had to stop `remaining`
    /// before the step end: no more than the remaining span or the maximum, at least 4 minimum.
    pub fn after_detour(&mut self, remaining: f64) {
        let inc = &self.incrementation;
        self.dt = remaining.min(inc.maximum).min(self.dt.max(inc.minimum * 4.0));
    }
}

impl PathControl for LoadControl {
    fn attempt(
        &mut self,
        model: &mut Model,
        solvers: Solvers<'_>,
        window: &StepWindow<'_>,
        scales: ReferenceScales,
    ) -> Attempt {
        let target = self.target(window);
        let mut predictor_costs = IncrementReport::default();
        match &self.predictor {
            Predictor::None => {}
            Predictor::Extrapolate(du, dt_last) => model.update_free(du, (target - window.t) / dt_last),
            Predictor::Tangent => {
                let times = (window.t, target);
                let rate_step = 1e-6 * window.t_end;
                let predicted = solvers.nonlinear.predict_along_tangent(
                    model,
                    solvers.linear,
                    times,
                    rate_step,
                    &mut predictor_costs,
                );
                if predicted.is_err() {
                    // a singular committed tangent: start from the committed state
                    model.rollback();
                }
            }
        }
        match solvers.nonlinear.solve(model, solvers.linear, target, scales) {
            Ok(mut report) => {
                report.add_costs(&predictor_costs);
                Attempt::Converged(report)
            }
            Err(e) => {
                self.first_failed_target.get_or_insert(target);
                Attempt::Failed(e)
            }
        }
    }

    fn cut(&mut self, _failure: &AttemptFailure) -> Result<Cut, CutRefused> {
        self.dt *= self.incrementation.cut_factor;
        if self.dt < self.incrementation.minimum {
            Err(CutRefused::BelowMinimum { minimum: self.incrementation.minimum })
        } else {
            Ok(Cut::Increment(self.dt))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nonlinear::IncrementFailure;

    fn incrementation() -> Incrementation {
        Incrementation::for_tests()
    }

    fn window(t: f64, breakpoints: &[f64]) -> StepWindow<'_> {
        StepWindow { t, step_start: 0.0, step_end: 1.0, t_end: 2.0, breakpoints }
    }

    #[test]
    fn targets_land_on_breakpoints_and_the_step_end() {
        let mut control = LoadControl::new(&incrementation(), StartPredictor::Tangent);
        assert_eq!(control.target(&window(0.0, &[])), 0.1);
        assert_eq!(control.target(&window(0.0, &[0.05, 0.5])), 0.05, "clipped to the first breakpoint ahead");
        assert_eq!(control.target(&window(0.05, &[0.05])), 0.15000000000000002, "a breakpoint behind is ignored");
        assert_eq!(control.target(&window(0.95, &[])), 1.0, "clipped to the step end");
        assert_eq!(control.target(&window(0.89995, &[])), 1.0, "within 1e-3 dt of the end: snapped to it");
        control.grow();
        control.grow();
        assert_eq!(control.dt, 0.2, "growth stops at the maximum");
    }

    #[test]
    fn cuts_shrink_the_increment_until_the_minimum_then_stop_with_the_reason() {
        let mut control = LoadControl::new(&incrementation(), StartPredictor::Tangent);
        let failure = AttemptFailure::Solver(IncrementFailure::Diverged { iterations: 25, residual: 1.0 });
        let mut cuts = 0;
        let message = loop {
            match control.cut(&failure) {
                Ok(_) => cuts += 1,
                Err(refused) => break refused.reason(&failure),
            }
        };
        // 0.1 * 0.25^k >= 1e-3 for k = 0..3
        assert_eq!(cuts, 3);
        assert!(message.contains("below the minimum") && message.contains("no convergence"), "{message}");
    }

    #[test]
    fn extrapolation_stops_at_a_reversal_a_snap_and_a_failure() {
        for (start, at_start) in
            [(StartPredictor::Tangent, Predictor::Tangent), (StartPredictor::None, Predictor::None)]
        {
            let mut control = LoadControl::new(&incrementation(), start);
            assert_eq!(control.predictor, at_start, "the first increment");
            control.remember(vec![1.0], 0.1, false);
            assert_eq!(control.predictor, Predictor::Extrapolate(vec![1.0], 0.1));
            control.remember(vec![1.0], 0.1, true);
            assert_eq!(control.predictor, at_start, "after a reversal");
            control.remember(vec![1.0], 0.0, true);
            assert_eq!(control.predictor, Predictor::None, "after a snap");
            control.remember(vec![1.0], 0.1, false);
            control.forget();
            assert_eq!(control.predictor, Predictor::None, "after a failure");
        }
    }
}
