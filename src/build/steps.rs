//! The case's steps and solver settings as the core's step plans and Newton settings (the
//! numbers were validated when the case was loaded).

use crate::case::LoadedCase;
use stiction_core::model::Model;
use stiction_core::nonlinear::NewtonSettings;
use stiction_core::path::{Incrementation, StepPlan};

/// One plan per step: default increments are fractions of the step's span.
pub fn step_plans(case: &LoadedCase, model: &Model) -> Vec<StepPlan> {
    let solver = &case.case.solver;
    let mut previous_end = 0.0;
    let mut plans = Vec::with_capacity(case.case.steps.len());
    for (i, s) in case.case.steps.iter().enumerate() {
        let span = s.end_time - previous_end;
        let incrementation = Incrementation {
            initial: s.initial_increment.unwrap_or(0.1 * span).min(span),
            minimum: s.min_increment.unwrap_or(1e-6 * span),
            maximum: s.max_increment.unwrap_or(span),
            cut_factor: solver.cut_factor,
            growth_factor: solver.growth_factor,
            easy_iterations: Incrementation::EASY_ITERATIONS,
        };
        let until_separated =
            s.until_separated.as_ref().and_then(|name| model.contributions.iter().position(|c| c.name() == name));
        plans.push(StepPlan {
            name: s.name.clone().unwrap_or_else(|| format!("step {}", i + 1)),
            end_time: s.end_time,
            incrementation,
            output_every: s.output_every,
            until_separated,
        });
        previous_end = s.end_time;
    }
    plans
}

/// The Newton settings of the case's `[solver]`.
pub fn newton_settings(case: &LoadedCase) -> NewtonSettings {
    let s = &case.case.solver;
    NewtonSettings {
        max_iterations: s.max_iterations,
        tol_residual: s.tol_residual,
        tol_displacement: s.tol_displacement,
        line_search: s.line_search,
        stagnation_iterations: s.stagnation_iterations,
        ..NewtonSettings::default()
    }
}
