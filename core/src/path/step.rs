//! A step of the analysis as the driver runs it: its end, incrementation and output schedule.

use crate::error::{CoreError, Result};

/// Incrementation: initial, minimum and maximum increments in pseudo-time, with cutting on
/// failure and growth after easy increments.
#[derive(Debug, Clone)]
pub struct Incrementation {
    pub initial: f64,
    pub minimum: f64,
    pub maximum: f64,
    /// Factor applied after a failed increment.
    pub cut_factor: f64,
    /// Factor applied after an increment that converged in at most `easy_iterations`.
    pub growth_factor: f64,
    pub easy_iterations: usize,
}

impl Incrementation {
    /// Default of `cut_factor` (case key `solver.cut_factor`).
    pub const DEFAULT_CUT_FACTOR: f64 = 0.25;
    /// Default of `growth_factor` (case key `solver.growth_factor`).
    pub const DEFAULT_GROWTH_FACTOR: f64 = 1.5;
    /// Increments converged in at most this many iterations let the next one grow.
    pub const EASY_ITERATIONS: usize = 5;

    /// The incrementation the path's unit tests share: initial 0.1, minimum 1e-3, maximum 0.2,
    /// and the default factors.
    #[cfg(test)]
    pub(crate) fn for_tests() -> Self {
        Self {
            initial: 0.1,
            minimum: 1e-3,
            maximum: 0.2,
            cut_factor: Self::DEFAULT_CUT_FACTOR,
            growth_factor: Self::DEFAULT_GROWTH_FACTOR,
            easy_iterations: Self::EASY_ITERATIONS,
        }
    }

    pub fn validate(&self) -> Result<()> {
        let finite = [self.initial, self.minimum, self.maximum, self.cut_factor, self.growth_factor]
            .iter()
            .all(|v| v.is_finite());
        let ok = finite
            && self.minimum > 0.0
            && self.initial >= self.minimum
            && self.maximum >= self.initial
            && self.cut_factor > 0.0
            && self.cut_factor < 1.0
            && self.growth_factor >= 1.0;
        if ok {
            Ok(())
        } else {
            Err(CoreError::Invalid(format!(
                "incrementation needs finite 0 < minimum <= initial <= maximum, 0 < cut < 1, growth >= 1 (got {self:?})"
            )))
        }
    }
}

/// One step: pseudo-time runs from the previous step's end to `end_time`.
#[derive(Debug, Clone)]
pub struct StepPlan {
    pub name: String,
    pub end_time: f64,
    pub incrementation: Incrementation,
    /// A field frame every this many increments (0: only at the step end).
    pub output_every: usize,
    /// End the step once this contribution (by index) has separated.
    pub until_separated: Option<usize>,
}
