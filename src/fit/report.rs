//! What a fit reports: each parameter's 95% interval from the Jacobian at the solution, the
//! parameters the targets cannot determine, and the residual of each target.
//!
//! With J the Jacobian of the weighted residuals r in the fitted coordinates v (ln x or x), the
//! covariance of v is s^2 (J^T J)^-1: s^2 = 1 when every target gives its standard deviation
//! (the residuals are then in standard deviations), else the residual variance
//! r.r / (m - n). The interval is v +- q sigma_v with q the normal 0.975 quantile (1.960) or
//! Student's t with m - n degrees of freedom, mapped back to x (asymmetric for `log`). A
//! linearisation: honest where the model is close to linear over the interval.
//!
//! Identifiability: the columns of J are scaled to unit length and the eigenvalues of the
//! scaled J^T J examined; one below 1e-10 of the largest marks a direction the targets do not
//! see, and the parameters with a large share in it are named (their intervals are then null).
//! A column of zeros (a parameter that changes nothing) is named as such.

use super::problem::Coordinate;
use super::spec::{FitSpec, TargetKind};
use nalgebra_lm::DMatrix;
use serde::Serialize;
use statrs::distribution::{ContinuousCDF, StudentsT};

/// Relative eigenvalue below which a direction is undetermined.
const UNDETERMINED: f64 = 1e-10;

/// One parameter in fit.json.
#[derive(Debug, Clone, Serialize)]
pub struct FittedParameter {
    pub key: String,
    pub start: f64,
    pub value: f64,
    /// The 95% interval (null when the targets do not determine the parameter).
    pub interval_95: Option<[f64; 2]>,
    /// Standard error in the fitted coordinate (of ln x for `log` parameters).
    pub standard_error: Option<f64>,
    pub log: bool,
    pub bounds: [f64; 2],
    /// Within 1% of the range from a bound: the interval may be cut off there.
    pub near_bound: bool,
    /// The value the targets were made with, in a twin experiment.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub true_value: Option<f64>,
}

/// One target in fit.json.
#[derive(Debug, Clone, Serialize)]
pub struct TargetResidual {
    pub name: String,
    pub case: String,
    /// Measured values compared.
    pub points: usize,
    /// Root mean square of model - measured, in the measured quantity's unit.
    pub rms_difference: f64,
    /// Sum of the squared weighted residuals, at the start and at the fit.
    pub cost_at_start: f64,
    pub cost: f64,
}

/// The statistics at the solution.
#[derive(Debug, Clone, Serialize)]
pub struct Uncertainty {
    /// "absolute" (every target has a sigma) or "scaled by the residual variance".
    pub sigma: &'static str,
    pub degrees_of_freedom: usize,
    /// s^2 above.
    pub residual_variance: f64,
    /// Standard errors in v, and the correlations, per parameter (null where undetermined).
    pub standard_errors: Vec<Option<f64>>,
    pub correlation: Vec<Vec<Option<f64>>>,
    /// Parameters the targets cannot determine, each with why.
    pub undetermined: Vec<String>,
    /// q of the intervals.
    pub quantile: f64,
}

/// Covariance and identifiability from the Jacobian `j` (m x n, in v) and the cost r.r.
pub fn uncertainty(spec: &FitSpec, j: &DMatrix<f64>, cost: f64) -> Uncertainty {
    let (m, n) = j.shape();
    let keys: Vec<&str> = spec.parameters.iter().map(|p| p.key.as_str()).collect();
    let absolute = spec.absolute_sigma();
    let dof = m.saturating_sub(n);
    let residual_variance = if absolute {
        1.0
    } else if dof > 0 {
        cost / dof as f64
    } else {
        f64::NAN
    };
    let quantile = if absolute || dof == 0 {
        1.959_963_984_540_054
    } else {
        StudentsT::new(0.0, 1.0, dof as f64).map_or(f64::NAN, |t| t.inverse_cdf(0.975))
    };
    let norms: Vec<f64> = (0..n).map(|k| j.column(k).norm()).collect();
    let mut undetermined = Vec::new();
    let mut blind = vec![false; n];
    for k in 0..n {
        if norms[k] == 0.0 || !norms[k].is_finite() {
            blind[k] = true;
            undetermined.push(format!("{}: the targets do not change with it (a zero Jacobian column)", keys[k]));
        }
    }
    let mut scaled = j.clone();
    for k in 0..n {
        let s = if blind[k] { 0.0 } else { 1.0 / norms[k] };
        scaled.column_mut(k).scale_mut(s);
    }
    let normal = scaled.transpose() * &scaled;
    let eigen = normal.clone().symmetric_eigen();
    let largest = eigen.eigenvalues.iter().cloned().fold(0.0, f64::max);
    for (e, value) in eigen.eigenvalues.iter().enumerate() {
        if largest > 0.0 && *value < UNDETERMINED * largest {
            let vector = eigen.eigenvectors.column(e);
            let involved: Vec<usize> = (0..n).filter(|&k| !blind[k] && vector[k].abs() > 0.3).collect();
            if involved.is_empty() {
                continue;
            }
            for &k in &involved {
                blind[k] = true;
            }
            let names: Vec<&str> = involved.iter().map(|&k| keys[k]).collect();
            undetermined.push(format!(
                "{}: the targets determine only a combination (the normal matrix is singular along it)",
                names.join(" and ")
            ));
        }
    }
    // covariance of the determined parameters
    let kept: Vec<usize> = (0..n).filter(|&k| !blind[k]).collect();
    let mut standard_errors = vec![None; n];
    let mut correlation = vec![vec![None; n]; n];
    if !kept.is_empty() && residual_variance.is_finite() {
        let sub = DMatrix::from_fn(kept.len(), kept.len(), |a, b| normal[(kept[a], kept[b])]);
        if let Some(inverse) = sub.try_inverse() {
            for (a, &ka) in kept.iter().enumerate() {
                let variance = residual_variance * inverse[(a, a)] / (norms[ka] * norms[ka]);
                standard_errors[ka] = (variance >= 0.0).then(|| variance.sqrt());
                for (b, &kb) in kept.iter().enumerate() {
                    let r = inverse[(a, b)] / (inverse[(a, a)] * inverse[(b, b)]).sqrt();
                    correlation[ka][kb] = r.is_finite().then_some(r);
                }
            }
        }
    }
    Uncertainty {
        sigma: if absolute { "absolute" } else { "scaled by the residual variance" },
        degrees_of_freedom: dof,
        residual_variance,
        standard_errors,
        correlation,
        undetermined,
        quantile,
    }
}

/// The parameters in fit.json, at `x`, with the intervals of `u`.
pub fn fitted_parameters(spec: &FitSpec, x: &[f64], u: &Uncertainty) -> Vec<FittedParameter> {
    spec.parameters
        .iter()
        .zip(x)
        .zip(&u.standard_errors)
        .map(|((p, &value), se)| {
            let c = Coordinate::of(p);
            let v = c.v_of_x(value);
            let interval_95 = se.map(|s| [c.x_of_v(v - u.quantile * s), c.x_of_v(v + u.quantile * s)]);
            FittedParameter {
                key: p.key.clone(),
                start: p.start,
                value,
                interval_95,
                standard_error: *se,
                log: p.log,
                bounds: [p.lower, p.upper],
                near_bound: c.near_bound(v, 0.01),
                true_value: p.true_value,
            }
        })
        .collect()
}

/// Each target's residuals at the start and at the fit, from the weighted residuals and the
/// model values of both points.
pub fn target_residuals(
    spec: &FitSpec,
    start: &super::evaluate::Point,
    end: &super::evaluate::Point,
) -> Vec<TargetResidual> {
    let mut offset = 0;
    spec.targets
        .iter()
        .enumerate()
        .map(|(i, t)| {
            let measured: Vec<f64> = match &t.kind {
                TargetKind::Curve(c) => c.points.iter().map(|p| p.value).collect(),
                TargetKind::Summary { value, .. } => vec![*value],
            };
            let k = measured.len();
            let cost = |p: &super::evaluate::Point| p.residuals[offset..offset + k].iter().map(|r| r * r).sum::<f64>();
            let rms = (end.model[i].iter().zip(&measured).map(|(a, b)| (a - b).powi(2)).sum::<f64>() / k as f64).sqrt();
            let row = TargetResidual {
                name: t.name.clone(),
                case: spec.cases[t.case].name.clone(),
                points: k,
                rms_difference: rms,
                cost_at_start: cost(start),
                cost: cost(end),
            };
            offset += k;
            row
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fit::spec::{Differences, FitCase, OptimizerSettings, Parameter, Target};

    fn spec(n: usize, sigma: Option<f64>) -> FitSpec {
        let p = |k: usize| Parameter {
            key: format!("p{k}"),
            start: 1.0,
            lower: 0.1,
            upper: 10.0,
            log: false,
            cases: vec![0],
            true_value: None,
        };
        FitSpec {
            path: "f.toml".into(),
            name: "f".into(),
            cases: vec![FitCase { name: "c".into(), file: "c.toml".into(), set: vec![] }],
            parameters: (0..n).map(p).collect(),
            targets: vec![Target {
                name: "t".into(),
                case: 0,
                interface: None,
                kind: TargetKind::Summary { field: "max_force".into(), value: 1.0, ratio_to: None },
                sigma,
                weight: 1.0,
            }],
            optimizer: OptimizerSettings { jacobian: Differences::Forward, ..Default::default() },
            fingerprint: String::new(),
        }
    }

    /// A straight line y = a + b t fitted to m points with unit sigma: the standard errors are
    /// those of ordinary least squares in closed form, sigma_b^2 = 1 / sum (t - mean)^2 and
    /// sigma_a^2 = sum t^2 / (m sum (t - mean)^2), and the correlation
    /// -mean / sqrt(sum t^2 / m).
    #[test]
    fn standard_errors_of_a_line_are_the_closed_form() {
        let t: Vec<f64> = (0..7).map(|k| k as f64 * 0.5).collect();
        let m = t.len() as f64;
        let j = DMatrix::from_fn(t.len(), 2, |i, k| if k == 0 { 1.0 } else { t[i] });
        let u = uncertainty(&spec(2, Some(1.0)), &j, 3.0);
        let mean = t.iter().sum::<f64>() / m;
        let sxx: f64 = t.iter().map(|t| (t - mean).powi(2)).sum();
        let st2: f64 = t.iter().map(|t| t * t).sum();
        assert_eq!(u.sigma, "absolute");
        assert!((u.standard_errors[1].unwrap() - (1.0 / sxx).sqrt()).abs() < 1e-12);
        assert!((u.standard_errors[0].unwrap() - (st2 / (m * sxx)).sqrt()).abs() < 1e-12);
        let r = u.correlation[0][1].unwrap();
        assert!((r + mean / (st2 / m).sqrt()).abs() < 1e-12, "{r}");
        // without sigmas, scaled by cost / (m - n) and Student's t with 5 degrees of freedom
        let scaled = uncertainty(&spec(2, None), &j, 10.0);
        let s2 = 10.0 / 5.0;
        assert!((scaled.standard_errors[1].unwrap() - (s2 / sxx).sqrt()).abs() < 1e-12);
        assert!((scaled.quantile - 2.570_581_835_636_314).abs() < 1e-9, "{}", scaled.quantile);
        assert!(u.undetermined.is_empty());
    }

    /// Two parameters that enter only as their sum, and one that enters not at all, are named.
    #[test]
    fn undetermined_parameters_are_named() {
        let j = DMatrix::from_fn(5, 3, |i, k| match k {
            0 | 1 => 1.0 + i as f64,
            _ => 0.0,
        });
        let u = uncertainty(&spec(3, Some(1.0)), &j, 1.0);
        assert_eq!(u.undetermined.len(), 2, "{:?}", u.undetermined);
        assert!(u.undetermined[0].starts_with("p2: the targets do not change with it"));
        assert!(u.undetermined[1].starts_with("p0 and p1: the targets determine only a combination"));
        assert!(u.standard_errors.iter().all(Option::is_none));
    }
}
