//! Piecewise-linear histories in pseudo-time: one table describes a load-unload schedule.

use crate::error::{CoreError, Result};

/// A piecewise-linear function of pseudo-time, held constant beyond its ends.
#[derive(Debug, Clone, PartialEq)]
pub struct Amplitude {
    times: Vec<f64>,
    values: Vec<f64>,
}

impl Amplitude {
    /// Builds a table; times must be strictly increasing and both columns the same length.
    pub fn new(times: Vec<f64>, values: Vec<f64>) -> Result<Self> {
        if times.is_empty() || times.len() != values.len() {
            return Err(CoreError::Invalid(format!(
                "an amplitude needs equal, non-zero numbers of times and values (got {} and {})",
                times.len(),
                values.len()
            )));
        }
        if times.windows(2).any(|w| !(w[1] > w[0])) {
            return Err(CoreError::Invalid("amplitude times must be strictly increasing".into()));
        }
        if times.iter().chain(values.iter()).any(|v| !v.is_finite()) {
            return Err(CoreError::Invalid("amplitude entries must be finite numbers".into()));
        }
        Ok(Self { times, values })
    }

    /// The ramp 0 -> 1 over t in [0, 1], constant after.
    pub fn ramp() -> Self {
        Self { times: vec![0.0, 1.0], values: vec![0.0, 1.0] }
    }

    /// Linear interpolation: a(t) = v_i + (v_{i+1} - v_i)(t - t_i)/(t_{i+1} - t_i).
    pub fn value(&self, t: f64) -> f64 {
        let n = self.times.len();
        if t <= self.times[0] {
            return self.values[0];
        }
        if t >= self.times[n - 1] {
            return self.values[n - 1];
        }
        let i = self.times.partition_point(|&ti| ti <= t) - 1;
        let s = (t - self.times[i]) / (self.times[i + 1] - self.times[i]);
        self.values[i] + s * (self.values[i + 1] - self.values[i])
    }

    /// da/dt on the segment that contains t (the later one at a breakpoint); 0 beyond the ends.
    pub fn slope(&self, t: f64) -> f64 {
        let n = self.times.len();
        if n < 2 || t < self.times[0] || t >= self.times[n - 1] {
            return 0.0;
        }
        let i = self.times.partition_point(|&ti| ti <= t) - 1;
        (self.values[i + 1] - self.values[i]) / (self.times[i + 1] - self.times[i])
    }

    /// Breakpoints strictly inside (t0, t1): steps land on them so kinks are resolved exactly.
    pub fn breakpoints_between(&self, t0: f64, t1: f64) -> impl Iterator<Item = f64> + '_ {
        self.times.iter().copied().filter(move |&t| t > t0 && t < t1)
    }

    pub fn end_time(&self) -> f64 {
        *self.times.last().unwrap()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn interpolates_load_unload_table() {
        let a = Amplitude::new(vec![0.0, 1.0, 3.0], vec![0.0, 2.0, -2.0]).unwrap();
        assert_eq!(a.value(-1.0), 0.0);
        assert!((a.value(0.5) - 1.0).abs() < 1e-15);
        assert!((a.value(2.0) - 0.0).abs() < 1e-15);
        assert_eq!(a.value(5.0), -2.0);
        assert_eq!(a.slope(0.5), 2.0);
        assert_eq!(a.slope(1.0), -2.0);
        assert_eq!(a.slope(3.5), 0.0);
        assert!(Amplitude::new(vec![0.0, 0.0], vec![1.0, 2.0]).is_err());
    }
}
