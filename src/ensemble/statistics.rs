//! Sample statistics of one quantity over the members: mean, standard deviation and the 95%
//! confidence interval of the mean from Student's t distribution.

use serde::Serialize;
use statrs::distribution::{ContinuousCDF, StudentsT};

/// The confidence level of the intervals.
pub const CONFIDENCE: f64 = 0.95;

/// Statistics of n samples.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Statistic {
    pub quantity: String,
    pub n: usize,
    pub mean: f64,
    /// Sample standard deviation s = sqrt(sum (x - mean)^2 / (n - 1)) (None for n < 2).
    pub std: Option<f64>,
    /// Half width of the 95% confidence interval of the mean, t_{0.975, n-1} s / sqrt(n).
    pub ci95_half_width: Option<f64>,
    pub ci95_low: Option<f64>,
    pub ci95_high: Option<f64>,
    pub min: f64,
    pub max: f64,
}

/// The two-sided Student t quantile t_{(1+CONFIDENCE)/2, dof}.
pub fn t_quantile(dof: usize) -> f64 {
    StudentsT::new(0.0, 1.0, dof as f64).expect("dof >= 1").inverse_cdf(0.5 + CONFIDENCE / 2.0)
}

impl Statistic {
    /// Statistics of `samples` (None when there are none). Sums run in the samples' order, so
    /// the same samples give the same digits.
    pub fn of(quantity: &str, samples: &[f64]) -> Option<Self> {
        let n = samples.len();
        if n == 0 {
            return None;
        }
        let mean = samples.iter().sum::<f64>() / n as f64;
        let std = (n >= 2).then(|| (samples.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1) as f64).sqrt());
        let half = std.map(|s| t_quantile(n - 1) * s / (n as f64).sqrt());
        Some(Self {
            quantity: quantity.to_string(),
            n,
            mean,
            std,
            ci95_half_width: half,
            ci95_low: half.map(|h| mean - h),
            ci95_high: half.map(|h| mean + h),
            min: samples.iter().copied().fold(f64::INFINITY, f64::min),
            max: samples.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two-sided 95% quantiles of Student's t, from the standard table (e.g. NIST/SEMATECH
    /// e-Handbook, Table 1.3.6.7.2, column 0.975), to the table's 3 decimals.
    #[test]
    fn t_quantiles_match_the_published_table() {
        for (dof, table) in [(1, 12.706), (2, 4.303), (3, 3.182), (5, 2.571), (10, 2.228), (15, 2.131), (30, 2.042)] {
            assert!((t_quantile(dof) - table).abs() < 6e-4, "dof {dof}: {} vs {table}", t_quantile(dof));
        }
    }

    #[test]
    fn mean_std_and_interval_of_a_small_sample() {
        let s = Statistic::of("x", &[1.0, 2.0, 3.0, 4.0]).unwrap();
        assert_eq!(s.mean, 2.5);
        // s^2 = (2.25 + 0.25 + 0.25 + 2.25) / 3 = 5/3
        assert!((s.std.unwrap() - (5.0f64 / 3.0).sqrt()).abs() < 1e-15);
        let half = 3.182446305284263 * (5.0f64 / 3.0).sqrt() / 2.0;
        assert!((s.ci95_half_width.unwrap() - half).abs() < 1e-9);
        assert_eq!((s.min, s.max), (1.0, 4.0));
        let one = Statistic::of("x", &[7.0]).unwrap();
        assert_eq!((one.mean, one.std, one.ci95_half_width), (7.0, None, None));
        assert!(Statistic::of("x", &[]).is_none());
    }
}
