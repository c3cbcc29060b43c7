//! When the quasi-Newton solver refactorizes: a cost model in seconds (or in a fixed ratio of a
//! refactorization to an iteration).
//!
//! Refactorize when the iterations left at the observed residual ratio `rate`,
//! ln(target / ||r||) / ln(rate), cost more than a refactorization and the iterations a fresh
//! factor needs after it, or do not fit in the iterations left. A time integrator's step (a
//! damped flow's) converges on its correction instead, ||du||_inf below its tolerance, so there
//! ||du|| and that tolerance take the places of ||r|| and the target (linear convergence shrinks
//! both at the same rate).
//!
//! When the rate is trusted: the first steps on a factor are plain H0 steps, often several
//! times slower than those once the BFGS update holds a few pairs (its superlinear phase). On a
//! factor made in the last increment, judging by them refactorizes where BFGS would have
//! converged soon (the CalculiX benchmark, whose every increment brings new springs into
//! contact: 15 factorizations and 212 iterations judged from the first step, 11 and 231 with
//! the rule below, 9% less time); so there the rate counts once the step used two pairs. A
//! factor that has served two increments or more is judged from the first step: it has aged
//! with the path, and a new one serves the increments after it too (the rough cases'
//! unloading: waiting for the pairs there cost 2-11% more iterations).
//!
//! A rule across increments (refactorize at an increment's start once the iterations the stale
//! factor wasted in earlier increments add up to a refactorization, a ski-rental rule) was
//! tried and dropped: on the rough quick case a new factor is as stale as the old one after one
//! increment (new asperities touch each time), so the rule took 9 factorizations where 2 do.

/// Iterations a refactorized (Newton-like) increment is expected to need.
pub(super) const ITERATIONS_AFTER_REFACTORIZATION: f64 = 4.0;

/// BFGS pairs a step on a young factor must have used before its rate predicts the iterations left.
const PAIRS_BEFORE_RATE_COUNTS: usize = 2;

/// Increments a factor has served after which its first step's rate is trusted.
const INCREMENTS_BEFORE_FACTOR_IS_OLD: usize = 2;

/// Whether the rate of a step predicts the iterations left: the step used `pairs_in_step`
/// BFGS pairs on a factor that has served `increments_on_factor` converged increments.
pub(super) fn rate_is_trusted(pairs_in_step: usize, increments_on_factor: usize) -> bool {
    pairs_in_step >= PAIRS_BEFORE_RATE_COUNTS || increments_on_factor >= INCREMENTS_BEFORE_FACTOR_IS_OLD
}

/// Weight of the newest measurement in the running mean of the iteration time.
const NEWEST_WEIGHT: f64 = 0.2;

/// The costs that decide when refactorizing pays: measured (seconds), or a fixed ratio.
#[derive(Debug, Clone, Copy, Default, serde::Serialize, serde::Deserialize)]
pub(super) struct Costs {
    /// A tangent assembly plus a numeric factorization.
    refactorization: f64,
    /// A quasi-Newton iteration: a solve with the factor and a residual assembly.
    iteration: f64,
    /// When set, refactorization / iteration is this ratio instead of the measured one, so the
    /// solver's choices depend on the residuals only and a run is reproducible to the last digit
    /// (for a given number of threads).
    fixed_ratio: Option<f64>,
}

/// A running mean: the first value as is, then weighted towards the newest.
fn running_mean(mean: f64, newest: f64) -> f64 {
    if mean > 0.0 { (1.0 - NEWEST_WEIGHT) * mean + NEWEST_WEIGHT * newest } else { newest }
}

impl Costs {
    /// Costs priced in the fixed ratio `ratio` of a refactorization to an iteration.
    pub fn with_fixed_ratio(ratio: f64) -> Self {
        Self { fixed_ratio: Some(ratio), ..Self::default() }
    }

    /// These costs with the means measured by `saved` (a checkpointed solver's), the fixed
    /// ratio (if any) this solver's own.
    pub fn resumed(self, saved: Costs) -> Self {
        Self { fixed_ratio: self.fixed_ratio, ..saved }
    }

    /// A refactorization took `seconds` (tangent assembly and numeric factorization).
    pub fn refactorized(&mut self, seconds: f64) {
        self.refactorization = seconds;
    }

    /// A quasi-Newton iteration took `seconds`.
    pub fn iterated(&mut self, seconds: f64) {
        self.iteration = running_mean(self.iteration, seconds);
    }

    /// (refactorization, iteration), in seconds or in the fixed ratio.
    fn prices(&self) -> (f64, f64) {
        match self.fixed_ratio {
            Some(ratio) => (ratio, 1.0),
            None => (self.refactorization, self.iteration),
        }
    }

    /// Whether to refactorize now: the iterations left at the observed rate `rate` (residual
    /// ratio per iteration) to bring `distance` (the residual's norm, or a time integrator
    /// step's last correction) to `target` (its test) cost more than a refactorization and the
    /// iterations after it, or would not fit in the `budget` of iterations left.
    pub fn refactorize_pays(&self, rate: f64, distance: f64, target: f64, budget: usize) -> bool {
        if distance <= target {
            return false;
        }
        if !(rate < 1.0) {
            return true;
        }
        let remaining = (target / distance).ln() / rate.ln();
        let (refactorization, iteration) = self.prices();
        remaining > budget as f64
            || remaining * iteration > refactorization + ITERATIONS_AFTER_REFACTORIZATION * iteration
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// At a fixed ratio 10 and 4 fresh iterations: residual 1, target 1e-8, rate 0.1 leaves 8
    /// iterations (8 < 10 + 4: go on); rate 0.5 leaves 26.6 (> 14: refactorize, and > budget).
    #[test]
    fn refactorizes_when_the_iterations_left_cost_more() {
        let costs = Costs::with_fixed_ratio(10.0);
        assert!(!costs.refactorize_pays(0.1, 1.0, 1e-8, 20));
        assert!(costs.refactorize_pays(0.5, 1.0, 1e-8, 100));
        assert!(costs.refactorize_pays(0.1, 1.0, 1e-8, 7), "8 iterations left do not fit in 7");
        assert!(costs.refactorize_pays(1.0, 1.0, 1e-8, 100));
        assert!(!costs.refactorize_pays(0.99, 1e-9, 1e-8, 0), "already converged");
    }

    /// On a factor from the last increment the rate of a plain H0 step (0 or 1 pairs) is not
    /// trusted; on one that has served two increments it is.
    #[test]
    fn a_young_factor_is_judged_once_the_steps_use_two_pairs() {
        assert!(!rate_is_trusted(0, 0));
        assert!(!rate_is_trusted(1, 1));
        assert!(rate_is_trusted(2, 0));
        assert!(rate_is_trusted(0, 2));
    }
}
