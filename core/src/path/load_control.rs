//! Load (or displacement) control: the load parameter t is prescribed increment by increment.
//! The next target is t + dt, clipped to the step end and to the first amplitude breakpoint
//! (so load reversals are exact), and snapped to the step end when within 1e-3 dt of it. The
//! predictor extrapolates the last converged increment, u += du_last (t_target - t) / dt_last,
//! except across a reversal. A failed increment is cut by `cut_factor`; one that converged in
//! few iterations lets the next grow by `growth_factor`.

use super::step::Incrementation;
use super::{Attempt, PathControl, Solvers, StepWindow};
use crate::model::Model;
use crate::nonlinear::{IncrementFailure, ReferenceScales};

pub struct LoadControl {
    /// The next increment of the load parameter.
    pub dt: f64,
    incrementation: Incrementation,
    /// The last converged increment (free-dof displacement increment, dt) for the predictor.
    last_increment: Option<(Vec<f64>, f64)>,
    /// The target of the first failed attempt since the last commit (where a limit point lies).
    pub first_failed_target: Option<f64>,
}

impl LoadControl {
    pub fn new(incrementation: &Incrementation) -> Self {
        Self {
            dt: incrementation.initial,
            incrementation: incrementation.clone(),
            last_increment: None,
            first_failed_target: None,
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

    /// Remembers a converged increment for the predictor (forgotten across a reversal or when
    /// the load parameter did not move forward).
    pub fn remember(&mut self, du: Vec<f64>, dt: f64, reversal: bool) {
        self.last_increment = if reversal || dt <= 0.0 { None } else { Some((du, dt)) };
        self.first_failed_target = None;
    }

    /// Forgets the predictor (after a failed attempt).
    pub fn forget(&mut self) {
        self.last_increment = None;
    }

    /// The next increment grows after an easy one.
    pub fn grow(&mut self) {
        self.dt = (self.dt * self.incrementation.growth_factor).min(self.incrementation.maximum);
    }

    /// Sets the next increment, kept within the incrementation's bounds.
    pub fn set_increment(&mut self, dt: f64) {
        self.dt = dt.clamp(self.incrementation.minimum, self.incrementation.maximum);
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
        if let Some((du, dt_last)) = &self.last_increment {
            model.update_free(du, (target - window.t) / dt_last);
        }
        match solvers.nonlinear.solve(model, solvers.linear, target, scales) {
            Ok(report) => Attempt::Converged(report),
            Err(e) => {
                self.first_failed_target.get_or_insert(target);
                Attempt::Failed(e)
            }
        }
    }

    fn cut(&mut self, failure: &IncrementFailure) -> Result<String, String> {
        self.dt *= self.incrementation.cut_factor;
        if self.dt < self.incrementation.minimum {
            Err(format!("increment below the minimum {:.3e} after: {failure}", self.incrementation.minimum))
        } else {
            Ok(format!("cut to dt = {:.2e}", self.dt))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nonlinear::IncrementFailure;

    fn incrementation() -> Incrementation {
        Incrementation {
            initial: 0.1,
            minimum: 1e-3,
            maximum: 0.2,
            cut_factor: 0.25,
            growth_factor: 1.5,
            easy_iterations: 5,
        }
    }

    fn window(t: f64, breakpoints: &[f64]) -> StepWindow<'_> {
        StepWindow { t, step_start: 0.0, step_end: 1.0, t_end: 2.0, breakpoints }
    }

    #[test]
    fn targets_land_on_breakpoints_and_the_step_end() {
        let mut control = LoadControl::new(&incrementation());
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
        let mut control = LoadControl::new(&incrementation());
        let failure = IncrementFailure::Diverged { iterations: 25, residual: 1.0 };
        let mut cuts = 0;
        let message = loop {
            match control.cut(&failure) {
                Ok(_) => cuts += 1,
                Err(m) => break m,
            }
        };
        // 0.1 * 0.25^k >= 1e-3 for k = 0..3
        assert_eq!(cuts, 3);
        assert!(message.contains("below the minimum") && message.contains("no convergence"), "{message}");
    }

    #[test]
    fn the_predictor_is_forgotten_across_a_reversal() {
        let mut control = LoadControl::new(&incrementation());
        control.remember(vec![1.0], 0.1, false);
        assert!(control.last_increment.is_some());
        control.remember(vec![1.0], 0.1, true);
        assert!(control.last_increment.is_none());
    }
}
