//! Exponential cohesive law from the Xu & Needleman (1993) potential with q = phi_t / phi_n = 1
//! (equal normal and shear work of separation, G_c):
//!   psi(delta_n, delta_s) = G_c [1 - (1 + x) exp(-x) exp(-y^2)], x = delta_n / d_n,
//!   y = |delta_s| / d_t,
//! with d_n = G_c / (e sigma_max) (normal peak sigma_max at x = 1) and
//! d_t = G_c / (sqrt(e / 2) tau_max) (shear peak tau_max at y = 1 / sqrt 2). Values are
//! value_i = -d psi / d delta_i, so pure normal opening gives -(G_c / d_n) x exp(-x).
//! Reversible (elastic). In compression the normal part is penalty contact (value -K delta_n)
//! and the shear part is the potential at x = 0.

/// The law's constants.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Exponential {
    pub g_c: f64,
    pub d_n: f64,
    pub d_t: f64,
    pub k: f64,
}

impl Exponential {
    pub fn new(g_c: f64, normal_strength: f64, shear_strength: f64, k: f64) -> Self {
        Self {
            g_c,
            d_n: g_c / (std::f64::consts::E * normal_strength),
            d_t: g_c / ((std::f64::consts::E / 2.0).sqrt() * shear_strength),
            k,
        }
    }

    /// Value and tangent at opening `delta`.
    pub fn evaluate(&self, delta: [f64; 3]) -> ([f64; 3], [[f64; 3]; 3]) {
        let x = delta[0].max(0.0) / self.d_n;
        let ex = (-x).exp();
        // P(x) = (1 + x) e^-x and its derivatives with respect to x
        let (p, dp, ddp) = ((1.0 + x) * ex, -x * ex, (x - 1.0) * ex);
        let dt2 = self.d_t * self.d_t;
        let e = (-(delta[1] * delta[1] + delta[2] * delta[2]) / dt2).exp();
        // dE/ds_i and d2E/ds_i ds_j for i, j in the shear components 1, 2
        let de = |i: usize| -2.0 * delta[i] / dt2 * e;
        let dde =
            |i: usize, j: usize| (if i == j { -2.0 / dt2 } else { 0.0 } + 4.0 * delta[i] * delta[j] / (dt2 * dt2)) * e;
        let g = self.g_c;
        let mut value = [g * dp / self.d_n * e, g * p * de(1), g * p * de(2)];
        let mut tangent = [[0.0; 3]; 3];
        tangent[0][0] = g * ddp / (self.d_n * self.d_n) * e;
        for i in 1..3 {
            tangent[0][i] = g * dp / self.d_n * de(i);
            tangent[i][0] = tangent[0][i];
            for j in 1..3 {
                tangent[i][j] = g * p * dde(i, j);
            }
        }
        if delta[0] < 0.0 {
            value[0] = -self.k * delta[0];
            tangent[0][0] = -self.k;
        }
        (value, tangent)
    }
}
