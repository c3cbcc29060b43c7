//! The energy one interface point dissipates by damage over an increment, for laws that
//! unload secantly to their origin (the trait-level equation is in
//! [`stiction_core::model::Contribution::damage_dissipation`]).
//!
//! With the value v (positive pushing the sides apart) and the opening g, the stored energy is
//! -v . g / 2, and the trapezoidal work minus its change from the committed state (c) is
//!   dD = w/2 (v . g_c - v_c . g),   d(dD)/dg = w/2 (K^T g_c - v_c)   (K = dv/dg),
//! exact along a straight softening segment. A point that fails completely within the increment
//! (v = 0 and K = 0 at the trial state) would be charged the trapezoid beyond its final opening
//! too: its opening is capped where the committed tangent's line reaches zero traction,
//! g_f = g_c + s (g - g_c) with s = -|v_c|^2 / (v_c . K_c (g - g_c)), which makes dD exactly
//! the energy it had left on a linear softening branch; it then no longer depends on g.

/// Whether a law's points dissipate by damage with secant unloading, the behaviour
/// [`point_dissipation`] assumes: by contract, the law declares a state named `damage`
/// (as `cohesive-zone` does). Interfaces with other laws report no damage dissipation.
pub fn damages_secantly(law: &dyn stiction_core::interface_law::InterfaceLaw) -> bool {
    law.state_names().iter().any(|n| n == "damage")
}

/// One point's committed state: value, tangent and opening (normal, tangential 1, 2).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PointState {
    pub value: [f64; 3],
    pub tangent: [[f64; 3]; 3],
    pub opening: [f64; 3],
}

/// dD of one point of weight `weight` from `committed` to `trial`, and d(dD)/d opening.
pub fn point_dissipation(trial: &PointState, committed: &PointState, weight: f64) -> (f64, [f64; 3]) {
    let dot = |a: &[f64; 3], b: &[f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let (v, k, g) = (&trial.value, &trial.tangent, &trial.opening);
    let (vc, kc, gc) = (&committed.value, &committed.tangent, &committed.opening);
    let failed = v.iter().chain(k.iter().flatten()).all(|&x| x == 0.0) && vc.iter().any(|&x| x != 0.0);
    if failed {
        let step: [f64; 3] = std::array::from_fn(|i| g[i] - gc[i]);
        let kc_step: [f64; 3] = std::array::from_fn(|i| dot(&kc[i], &step));
        let along = dot(vc, &kc_step);
        if along < 0.0 {
            let s = -dot(vc, vc) / along;
            if s < 1.0 {
                let g_final: [f64; 3] = std::array::from_fn(|i| gc[i] + s * step[i]);
                return (-0.5 * weight * dot(vc, &g_final), [0.0; 3]);
            }
        }
    }
    let energy = 0.5 * weight * (dot(v, gc) - dot(vc, g));
    let gradient = std::array::from_fn(|j| 0.5 * weight * ((0..3).map(|i| k[i][j] * gc[i]).sum::<f64>() - vc[j]));
    (energy, gradient)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A linear softening law in one component: v = -sigma(g), sigma = s_max (g_f - g)/(g_f - g_0)
    /// between g_0 and g_f, elastic -k g below g_0 (undamaged), 0 beyond g_f.
    fn softening(g: f64) -> PointState {
        let (k, g0, gf) = (100.0, 0.01, 0.04);
        let s_max = k * g0;
        let (value, slope) = if g <= g0 {
            (-k * g, -k)
        } else if g < gf {
            (-s_max * (gf - g) / (gf - g0), s_max / (gf - g0))
        } else {
            (0.0, 0.0)
        };
        PointState {
            value: [value, 0.0, 0.0],
            tangent: [[slope, 0.0, 0.0], [0.0; 3], [0.0; 3]],
            opening: [g, 0.0, 0.0],
        }
    }

    /// Dissipated energy at largest opening kappa on the envelope: the work under the
    /// envelope minus the energy stored at the secant, s_max g_f / 2 at full failure.
    fn dissipated(kappa: f64) -> f64 {
        let (k, g0, gf) = (100.0, 0.01, 0.04);
        let s_max = k * g0;
        if kappa <= g0 {
            return 0.0;
        }
        let kappa = kappa.min(gf);
        let s = s_max * (gf - kappa) / (gf - g0);
        let work = 0.5 * s_max * g0 + 0.5 * (s_max + s) * (kappa - g0);
        work - 0.5 * s * kappa
    }

    #[test]
    fn on_the_softening_branch_and_through_complete_failure_the_energy_is_exact() {
        for (a, b) in [(0.015, 0.02), (0.02, 0.039), (0.03, 0.04), (0.03, 0.07), (0.012, 0.5)] {
            let (e, _) = point_dissipation(&softening(b), &softening(a), 2.0);
            let exact = 2.0 * (dissipated(b) - dissipated(a));
            assert!((e - exact).abs() < 1e-14, "{a} -> {b}: {e} vs {exact}");
        }
        // elastic and secant unloading dissipate nothing
        assert_eq!(point_dissipation(&softening(0.005), &softening(0.002), 1.0).0, 0.0);
    }

    #[test]
    fn the_gradient_matches_central_differences() {
        let committed = softening(0.02);
        let (g, h) = (0.03, 1e-7);
        let (_, gradient) = point_dissipation(&softening(g), &committed, 1.5);
        let fd = (point_dissipation(&softening(g + h), &committed, 1.5).0
            - point_dissipation(&softening(g - h), &committed, 1.5).0)
            / (2.0 * h);
        assert!((gradient[0] - fd).abs() < 1e-7 * fd.abs(), "{} vs {fd}", gradient[0]);
    }
}
