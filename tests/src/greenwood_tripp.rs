//! An independent reference for a rough elastic sphere against a rigid flat: Greenwood and
//! Tripp's model (J. A. Greenwood, J. H. Tripp, J. Appl. Mech. 34 (1967) 153; Johnson, Contact
//! Mechanics, 1985, section 13.3). It shares no code with the finite-element model.
//!
//! The asperities are Greenwood and Williamson's: summits of radius beta, density eta per area,
//! heights Gaussian with standard deviation sigma about their mean plane, each a Hertzian contact
//! of modulus E*_a. Where the flat lies u above the summits' mean plane they press with the
//! nominal pressure
//!   p(u) = eta 4/3 E*_a beta^(1/2) int_u^inf (z - u)^(3/2) phi(z) dz,
//! phi the N(0, sigma^2) density. The sphere (radius R) is an elastic half-space of plane-strain
//! modulus E*, its surface pushed back by w = C p (Boussinesq for rings of uniform pressure,
//! [`crate::half_space_lj::disc_displacement`]), so with the flat at approach alpha
//!   u(r) = -alpha + s(r) + w(r),   s(r) = R - sqrt(R^2 - r^2):
//! approach 0 puts the flat on the summits' mean plane at the undeformed pole. The force is
//! P = int p 2 pi r dr. Newton's method solves w = C p(u(w)) ring by ring (Jacobian
//! I - C diag(p'), p' <= 0, well conditioned). The displacement is the half-space's, relative to
//! infinity.

use crate::half_space_lj::{RingGrid, Rings};
use faer::Mat;
use faer::linalg::solvers::Solve;
use std::f64::consts::PI;

/// int_t^inf (z - t)^n phi(z) dz for the standard normal phi, n = 1/2 or 3/2: with z = t + v^2 the
/// integrand 2 v^(2n + 1) phi(t + v^2) is smooth; Simpson's rule over v up to where phi is
/// below 1e-16 of its peak.
pub fn gaussian_moment(n: f64, t: f64) -> f64 {
    let phi = |z: f64| (-0.5 * z * z).exp() / (2.0 * PI).sqrt();
    let top = (-t).max(0.0).sqrt() + 9f64.sqrt();
    let steps = 2000;
    let h = top / steps as f64;
    let f = |v: f64| 2.0 * v.powf(2.0 * n + 1.0) * phi(t + v * v);
    let mut sum = f(0.0) + f(top);
    for i in 1..steps {
        sum += f(i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
    }
    sum * h / 3.0
}

/// The rough sphere: the continuum and its asperities.
#[derive(Clone, Copy, Debug)]
pub struct RoughSphere {
    /// Sphere radius R.
    pub radius: f64,
    /// The sphere's plane-strain modulus E* = E / (1 - nu^2) (rigid flat).
    pub e_star: f64,
    /// The asperities' contact modulus E*_a.
    pub asperity_modulus: f64,
    /// The summits' radius beta.
    pub asperity_radius: f64,
    /// Summits per area eta.
    pub density: f64,
    /// Standard deviation sigma of the summit heights.
    pub sigma: f64,
}

impl RoughSphere {
    /// GW's nominal pressure p(u) and dp/du with the flat u above the summits' mean plane.
    pub fn pressure(&self, u: f64) -> (f64, f64) {
        let t = u / self.sigma;
        let scale = self.density * self.asperity_modulus * self.asperity_radius.sqrt();
        let p = scale * 4.0 / 3.0 * self.sigma.powf(1.5) * gaussian_moment(1.5, t);
        let dp = -scale * 2.0 * self.sigma.sqrt() * gaussian_moment(0.5, t);
        (p, dp)
    }
}

/// Greenwood and Tripp's model on a ring grid.
pub struct GreenwoodTripp {
    pub sphere: RoughSphere,
    ring_area: Vec<f64>,
    profile: Vec<f64>,
    influence: Mat<f64>,
}

impl GreenwoodTripp {
    pub fn new(sphere: RoughSphere, grid: RingGrid) -> Self {
        let Rings { ring_area, profile, influence, .. } = Rings::new(sphere.radius, sphere.e_star, grid);
        Self { sphere, ring_area, profile, influence }
    }

    /// The force on the flat (positive compressive) at `approach`, from `w` (the surface's
    /// displacement away from the flat, ring by ring; overwritten by the solution).
    pub fn force(&self, approach: f64, w: &mut [f64]) -> f64 {
        let n = self.ring_area.len();
        let c = &self.influence;
        for _ in 0..60 {
            let (p, dp): (Vec<f64>, Vec<f64>) =
                (0..n).map(|j| self.sphere.pressure(-approach + self.profile[j] + w[j])).unzip();
            let residual: Vec<f64> = (0..n).map(|i| w[i] - (0..n).map(|j| c[(i, j)] * p[j]).sum::<f64>()).collect();
            let scale = w.iter().fold(self.sphere.sigma, |m, &x| m.max(x.abs()));
            if residual.iter().all(|r| r.abs() < 1e-12 * scale) {
                return p.iter().zip(&self.ring_area).map(|(p, a)| p * a).sum();
            }
            let jacobian = Mat::from_fn(n, n, |i, k| if i == k { 1.0 } else { 0.0 } - c[(i, k)] * dp[k]);
            let mut step = Mat::from_fn(n, 1, |i, _| -residual[i]);
            jacobian.partial_piv_lu().solve_in_place(&mut step);
            for (j, x) in w.iter_mut().enumerate() {
                *x += step[(j, 0)];
            }
        }
        panic!("Greenwood-Tripp: no equilibrium at approach {approach} in 60 Newton iterations");
    }

    /// Number of rings.
    pub fn rings(&self) -> usize {
        self.ring_area.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The moments against closed forms: int_0^inf z^(3/2) phi dz = Gamma(5/4) 2^(3/4) / (2 sqrt pi)
    /// (= 0.4299...), and far below the plane int (z - t)^(1/2) phi ~ (-t)^(1/2) (1 - 1/(8 t^2)).
    #[test]
    fn gaussian_moments_match_closed_forms() {
        let gamma_5_4 = 0.906_402_477_055_477;
        let exact = gamma_5_4 * 2f64.powf(0.75) / (2.0 * PI.sqrt());
        assert!((gaussian_moment(1.5, 0.0) / exact - 1.0).abs() < 1e-9, "{}", gaussian_moment(1.5, 0.0));
        let t: f64 = -30.0;
        let asymptotic = (-t).sqrt() * (1.0 - 1.0 / (8.0 * t * t));
        assert!((gaussian_moment(0.5, t) / asymptotic - 1.0).abs() < 1e-6);
    }

    /// Very smooth (sigma -> 0, dense stiff summits), the rough sphere is Hertz's:
    /// P = 4/3 E* R^(1/2) alpha^(3/2) within the grid's discretisation.
    #[test]
    fn a_nearly_smooth_sphere_is_hertzian() {
        let sphere = RoughSphere {
            radius: 1000.0,
            e_star: 100.0,
            asperity_modulus: 100.0,
            asperity_radius: 1e4,
            density: 10.0,
            sigma: 1e-3,
        };
        let grid = RingGrid { spacing: 0.5, fine_radius: 60.0, growth: 1.1, outer_radius: 200.0 };
        let model = GreenwoodTripp::new(sphere, grid);
        let mut w = vec![0.0; model.rings()];
        let alpha: f64 = 2.0;
        let force = model.force(alpha, &mut w);
        let hertz = 4.0 / 3.0 * 100.0 * 1000f64.sqrt() * alpha.powf(1.5);
        assert!((force / hertz - 1.0).abs() < 0.01, "{force} against Hertz {hertz}");
    }
}
