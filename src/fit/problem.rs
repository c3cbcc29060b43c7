//! The fit as a least-squares problem for the `levenberg-marquardt` crate (a port of MINPACK's
//! `lmder`), with bounds by a change of variable and a finite-difference Jacobian whose runs go
//! in one batch.
//!
//! Coordinates. A parameter x is fitted in v = ln x (`log`) or v = x, and v in the unbounded
//! u with v = lo + (hi - lo)(1 + sin u)/2 (MINUIT's and lmfit's transform): every u is inside
//! the bounds, and the optimizer needs none. The Jacobian is differenced in v, with steps
//! h = `fd_step` (times |x| for a linear parameter), away from the nearer bound, and chained
//! to u by dv/du = (hi - lo) cos(u)/2. Its v-form at the solution gives the covariance
//! ([`super::report`]).
//!
//! A trial point whose run fails, or that does not produce a target (no pull-off), is given a
//! residual far above the current one: the optimizer rejects it and shortens its step, as for
//! any step that makes the fit worse. A Jacobian step that fails is taken from the other side;
//! when both fail, or on Ctrl-C, the fit stops with what it has.

use super::evaluate::{Evaluator, Outcome, Purpose};
use super::spec::{Differences, Parameter};
use levenberg_marquardt::LeastSquaresProblem;
use nalgebra_lm::{DMatrix, DVector, Dyn, Owned};
use std::cell::{Cell, RefCell};

/// A residual that makes the optimizer reject a step: far above any cost a fit meets, yet
/// finite (the optimizer stops on a non-finite one).
const REJECTED: f64 = 1e100;

/// One parameter's coordinates.
#[derive(Debug, Clone, Copy)]
pub struct Coordinate {
    pub log: bool,
    lo: f64,
    hi: f64,
}

impl Coordinate {
    pub fn of(p: &Parameter) -> Self {
        let v = |x: f64| if p.log { x.ln() } else { x };
        Self { log: p.log, lo: v(p.lower), hi: v(p.upper) }
    }
    pub fn v_of_x(&self, x: f64) -> f64 {
        if self.log { x.ln() } else { x }
    }
    pub fn x_of_v(&self, v: f64) -> f64 {
        if self.log { v.exp() } else { v }
    }
    pub fn u_of_v(&self, v: f64) -> f64 {
        (2.0 * (v - self.lo) / (self.hi - self.lo) - 1.0).clamp(-1.0, 1.0).asin()
    }
    pub fn v_of_u(&self, u: f64) -> f64 {
        self.lo + (self.hi - self.lo) * (1.0 + u.sin()) / 2.0
    }
    pub fn dv_du(&self, u: f64) -> f64 {
        (self.hi - self.lo) * u.cos() / 2.0
    }
    /// The finite-difference step in v at v: away from the nearer bound.
    pub fn step(&self, v: f64, fd_step: f64) -> f64 {
        let h = if self.log { fd_step } else { fd_step * v.abs().max(1e-3 * (self.hi - self.lo)) };
        if v + h <= self.hi { h } else { -h }
    }
    /// Whether v is within `fraction` of the range from a bound.
    pub fn near_bound(&self, v: f64, fraction: f64) -> bool {
        let d = (self.hi - self.lo) * fraction;
        v - self.lo < d || self.hi - v < d
    }
}

/// Why the optimizer was stopped from inside.
#[derive(Debug, Clone)]
pub enum Stop {
    Interrupted,
    Failed(String),
}

/// The fit for the optimizer.
pub struct FitProblem<'e, 'a> {
    evaluator: &'e Evaluator<'a>,
    pub coordinates: Vec<Coordinate>,
    fd_step: f64,
    differences: Differences,
    u: DVector<f64>,
    /// u and x at the start.
    start: (DVector<f64>, Vec<f64>),
    residual_count: usize,
    pub stop: RefCell<Option<Stop>>,
    /// Jacobians computed (the optimizer's iterations).
    pub iterations: Cell<usize>,
    /// Residual evaluations (trial points, the start included).
    pub evaluations: Cell<usize>,
}

impl<'e, 'a> FitProblem<'e, 'a> {
    pub fn new(
        evaluator: &'e Evaluator<'a>,
        parameters: &[Parameter],
        fd_step: f64,
        differences: Differences,
        residual_count: usize,
    ) -> Self {
        let coordinates: Vec<Coordinate> = parameters.iter().map(Coordinate::of).collect();
        let u = DVector::from_iterator(
            parameters.len(),
            parameters.iter().zip(&coordinates).map(|(p, c)| c.u_of_v(c.v_of_x(p.start))),
        );
        let start = (u.clone(), parameters.iter().map(|p| p.start).collect());
        Self {
            evaluator,
            coordinates,
            fd_step,
            differences,
            u,
            start,
            residual_count,
            stop: RefCell::new(None),
            iterations: Cell::new(0),
            evaluations: Cell::new(0),
        }
    }

    /// The parameter values at the optimizer's current point (the start values exactly at the
    /// start, not their round trip through u, so the start's runs are not made twice).
    pub fn x(&self) -> Vec<f64> {
        if self.u == self.start.0 {
            return self.start.1.clone();
        }
        self.coordinates.iter().zip(self.u.iter()).map(|(c, &u)| c.x_of_v(c.v_of_u(u))).collect()
    }

    /// The Jacobian of the weighted residuals in v (the fitted coordinates: ln x or x) at `x`,
    /// whose residuals are `base`: one batch of runs (two for central differences), a failed
    /// step retried from the other side.
    pub fn jacobian_in_v(&self, x: &[f64], base: &[f64]) -> Result<DMatrix<f64>, Stop> {
        let n = x.len();
        let v: Vec<f64> = self.coordinates.iter().zip(x).map(|(c, &x)| c.v_of_x(x)).collect();
        let steps: Vec<f64> = self.coordinates.iter().zip(&v).map(|(c, &v)| c.step(v, self.fd_step)).collect();
        let shifted = |j: usize, h: f64| -> Vec<f64> {
            let mut p = x.to_vec();
            p[j] = self.coordinates[j].x_of_v(v[j] + h);
            p
        };
        let central = self.differences == Differences::Central;
        let mut points: Vec<Vec<f64>> = (0..n).map(|j| shifted(j, steps[j])).collect();
        if central {
            points.extend((0..n).map(|j| shifted(j, -steps[j])));
        }
        let outcomes = self.evaluator.evaluate(&points, Purpose::Jacobian);
        let mut jacobian = DMatrix::zeros(base.len(), n);
        for j in 0..n {
            let forward = &outcomes[j];
            let column: Vec<f64> = match (forward, central.then(|| &outcomes[n + j])) {
                (Outcome::Done(a), Some(Outcome::Done(b))) => {
                    a.residuals.iter().zip(&b.residuals).map(|(a, b)| (a - b) / (2.0 * steps[j])).collect()
                }
                (Outcome::Done(a), _) => a.residuals.iter().zip(base).map(|(a, r)| (a - r) / steps[j]).collect(),
                (_, Some(Outcome::Done(b))) => b.residuals.iter().zip(base).map(|(b, r)| (r - b) / steps[j]).collect(),
                (Outcome::Interrupted, _) => return Err(Stop::Interrupted),
                (Outcome::Failed(first), _) => {
                    // the other side, once
                    let other = shifted(j, -steps[j]);
                    match self.evaluator.evaluate(&[other], Purpose::Jacobian).remove(0) {
                        Outcome::Done(b) => b.residuals.iter().zip(base).map(|(b, r)| (r - b) / steps[j]).collect(),
                        Outcome::Interrupted => return Err(Stop::Interrupted),
                        Outcome::Failed(second) => {
                            return Err(Stop::Failed(format!(
                                "the Jacobian's step in {} failed on both sides: {first}; {second}",
                                self.evaluator.spec_key(j)
                            )));
                        }
                    }
                }
            };
            jacobian.set_column(j, &DVector::from_vec(column));
        }
        Ok(jacobian)
    }
}

impl LeastSquaresProblem<f64, Dyn, Dyn> for FitProblem<'_, '_> {
    type ResidualStorage = Owned<f64, Dyn>;
    type JacobianStorage = Owned<f64, Dyn, Dyn>;
    type ParameterStorage = Owned<f64, Dyn>;

    fn set_params(&mut self, u: &DVector<f64>) {
        self.u.copy_from(u);
    }

    fn params(&self) -> DVector<f64> {
        self.u.clone()
    }

    fn residuals(&self) -> Option<DVector<f64>> {
        let purpose = if self.evaluations.get() == 0 { Purpose::Start } else { Purpose::Trial };
        self.evaluations.set(self.evaluations.get() + 1);
        match self.evaluator.evaluate(&[self.x()], purpose).remove(0) {
            Outcome::Done(p) => Some(DVector::from_vec(p.residuals)),
            Outcome::Failed(e) => {
                eprintln!("  trial point rejected: {e}");
                Some(DVector::from_element(self.residual_count, REJECTED))
            }
            Outcome::Interrupted => {
                *self.stop.borrow_mut() = Some(Stop::Interrupted);
                None
            }
        }
    }

    fn jacobian(&self) -> Option<DMatrix<f64>> {
        self.iterations.set(self.iterations.get() + 1);
        let x = self.x();
        let base = match self.evaluator.evaluate(std::slice::from_ref(&x), Purpose::Trial).remove(0) {
            Outcome::Done(p) => p.residuals,
            _ => {
                *self.stop.borrow_mut() = Some(Stop::Failed("the accepted point has no residuals".into()));
                return None;
            }
        };
        match self.jacobian_in_v(&x, &base) {
            Ok(mut j) => {
                for (k, (c, &u)) in self.coordinates.iter().zip(self.u.iter()).enumerate() {
                    let d = c.dv_du(u);
                    j.column_mut(k).scale_mut(d);
                }
                Some(j)
            }
            Err(stop) => {
                *self.stop.borrow_mut() = Some(stop);
                None
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parameter(log: bool) -> Parameter {
        Parameter { key: "k".into(), start: 2.0, lower: 0.5, upper: 8.0, log, cases: vec![0], true_value: None }
    }

    /// The change of variable maps u back to the same x, stays inside the bounds for every u,
    /// and its derivative matches central differences.
    #[test]
    fn coordinates_round_trip_stay_inside_and_differentiate() {
        for log in [false, true] {
            let c = Coordinate::of(&parameter(log));
            for x in [0.6, 2.0, 7.9] {
                let u = c.u_of_v(c.v_of_x(x));
                assert!((c.x_of_v(c.v_of_u(u)) - x).abs() < 1e-12 * x, "{log} {x}");
                let h = 1e-6;
                let fd = (c.v_of_u(u + h) - c.v_of_u(u - h)) / (2.0 * h);
                assert!((fd - c.dv_du(u)).abs() < 1e-6 * c.dv_du(u).abs().max(1.0), "{log} {x}");
            }
            for u in [-100.0, -1.0, 0.0, 2.5, 1e3] {
                let x = c.x_of_v(c.v_of_u(u));
                assert!((0.5..=8.0).contains(&x), "{log} {u}: {x}");
            }
            // the step points away from the upper bound near it
            assert!(c.step(c.v_of_x(7.99), 0.01) < 0.0 && c.step(c.v_of_x(1.0), 0.01) > 0.0);
        }
    }
}
