//! Polynomials p(x) = sum_k c_k x^k (coefficients lowest order first).

/// p(x) by Horner's rule.
pub fn value(c: &[f64], x: f64) -> f64 {
    c.iter().rev().fold(0.0, |acc, &ck| acc * x + ck)
}

/// p'(x) = sum_k k c_k x^(k-1).
pub fn derivative(c: &[f64], x: f64) -> f64 {
    c.iter().enumerate().skip(1).rev().fold(0.0, |acc, (k, &ck)| acc * x + k as f64 * ck)
}

#[cfg(test)]
mod tests {
    #[test]
    fn value_and_derivative() {
        let c = [1.0, -2.0, 0.5, 3.0];
        let x: f64 = 0.7;
        assert!((super::value(&c, x) - (1.0 - 2.0 * x + 0.5 * x * x + 3.0 * x.powi(3))).abs() < 1e-15);
        assert!((super::derivative(&c, x) - (-2.0 + x + 9.0 * x * x)).abs() < 1e-14);
    }
}
