//! `cohesive-zone`: cohesive-zone laws for adhesive contact and fracture, mixed mode
//! (law ABI gap dimension 3: normal opening and two tangential slips; value positive pushes
//! the sides apart, a shear value opposes the slip).
//!
//! * `shape = 0`, bilinear with damage and secant unloading (Camanho & Davila 2002): quadratic
//!   onset between sigma_max and tau_max, Benzeggagh-Kenane propagation between G_c (mode I)
//!   and G_IIc with exponent eta; energy G_c(B) = G_c + (G_IIc - G_c) B^eta exactly under
//!   proportional opening (B = G_shear / G_total). See `bilinear.rs`.
//! * `shape = 1`, exponential (Xu & Needleman 1993 potential with phi_t = phi_n = G_c):
//!   normal peak sigma_max, shear peak tau_max; reversible. See `exponential.rs`.
//! Compression (normal opening < 0): penalty contact, value -k delta_n. A point that never
//! touched carries no traction, unless `initially_bonded = 1` (an uncracked ligament, e.g. a
//! double cantilever beam's). Interfaces that measure only a normal gap (a frictionless rigid
//! flat) see the pure mode-I law. State: [bonded, largest equivalent opening, damage].
//! Parameters: G_c, sigma_max, penalty k (0: chosen by the host, 100 E / h), shape,
//! initially_bonded, G_IIc (0: equal to G_c), tau_max (0: equal to sigma_max), eta.

pub mod bilinear;
pub mod exponential;

use bilinear::Bilinear;
use exponential::Exponential;
use stiction_law_sdk::{Law, LawKind, MixedResponse, Parameter, Response};

pub struct CohesiveZone {
    pub shape: Shape,
    pub k: f64,
    pub initially_bonded: bool,
}

/// The traction-opening curve.
pub enum Shape {
    Bilinear(Bilinear),
    Exponential(Exponential),
}

impl CohesiveZone {
    /// Parameters in `parameters()` order: G_c, sigma_max, penalty, shape, initially_bonded,
    /// G_IIc, tau_max, eta.
    pub fn from_parameters(p: &[f64]) -> Result<Self, String> {
        let (g_1c, normal_strength, k) = (p[0], p[1], p[2]);
        if !(k > 0.0) {
            return Err("penalty must be positive".into());
        }
        if p[3] != 0.0 && p[3] != 1.0 {
            return Err(format!("shape must be 0 (bilinear) or 1 (exponential), got {}", p[3]));
        }
        let g_2c = if p[5] == 0.0 { g_1c } else { p[5] };
        let shear_strength = if p[6] == 0.0 { normal_strength } else { p[6] };
        let shape = if p[3] == 1.0 {
            if g_2c != g_1c {
                return Err(format!(
                    "the exponential law (Xu-Needleman, q = 1) has equal normal and shear work of separation: G_IIc must be 0 or equal G_c = {g_1c}, got {g_2c}"
                ));
            }
            Shape::Exponential(Exponential::new(g_1c, normal_strength, shear_strength, k))
        } else {
            let law = Bilinear { k, g_1c, g_2c, normal_strength, shear_strength, eta: p[7] };
            if normal_strength / k >= 2.0 * g_1c / normal_strength {
                return Err(format!(
                    "penalty {k} is too small: the bilinear law needs k > sigma_max^2 / (2 G_c) = {}",
                    normal_strength * normal_strength / (2.0 * g_1c)
                ));
            }
            law.check()?;
            Shape::Bilinear(law)
        };
        Ok(Self { shape, k, initially_bonded: p[4] >= 0.5 })
    }
}

impl Law for CohesiveZone {
    const NAME: &'static std::ffi::CStr = c"cohesive-zone";
    const VERSION: &'static std::ffi::CStr = c"0.2.0";
    const KIND: LawKind = LawKind::TractionPerArea;
    const N_STATE: usize = 3;
    const GAP_DIMENSION: usize = 3;

    fn parameters() -> Vec<Parameter> {
        vec![
            Parameter::required(
                c"G_c",
                c"energy/area (J/m^2 = nN/nm)",
                c"mode-I fracture energy (work of adhesion)",
                1e-12,
                f64::INFINITY,
            ),
            Parameter::required(c"sigma_max", c"stress", c"normal (mode-I) cohesive strength", 1e-12, f64::INFINITY),
            Parameter::optional(
                c"penalty",
                c"stress/length",
                c"contact and initial stiffness k; 0 = chosen by the host (100 E / h)",
                0.0,
                0.0,
                f64::INFINITY,
            ),
            Parameter::optional(c"shape", c"-", c"0: bilinear with damage, 1: exponential", 0.0, 0.0, 1.0),
            Parameter::optional(
                c"initially_bonded",
                c"-",
                c"1: bonded from the start (an uncracked ligament); 0: bonds on first contact",
                0.0,
                0.0,
                1.0,
            ),
            Parameter::optional(
                c"G_IIc",
                c"energy/area (J/m^2 = nN/nm)",
                c"mode-II fracture energy; 0 = equal to G_c",
                0.0,
                0.0,
                f64::INFINITY,
            ),
            Parameter::optional(
                c"tau_max",
                c"stress",
                c"shear cohesive strength; 0 = equal to sigma_max",
                0.0,
                0.0,
                f64::INFINITY,
            ),
            Parameter::optional(
                c"eta",
                c"-",
                c"Benzeggagh-Kenane exponent of the bilinear law's mixed-mode fracture energy",
                2.0,
                1.0,
                10.0,
            ),
        ]
    }

    fn create(p: &[f64], _config: &str) -> Result<Self, String> {
        Self::from_parameters(p)
    }

    fn initialize_state(&self, state: &mut [f64]) {
        state.fill(0.0);
        state[0] = if self.initially_bonded { 1.0 } else { 0.0 };
    }

    fn evaluate(&self, g: f64, old: &[f64], new: &mut [f64]) -> Result<Response, String> {
        let r = self.evaluate_mixed([g, 0.0, 0.0], old, new)?;
        Ok(Response { value: r.value[0], tangent: r.tangent[0][0], in_contact: r.in_contact, area: r.area })
    }

    fn evaluate_mixed(&self, delta: [f64; 3], old: &[f64], new: &mut [f64]) -> Result<MixedResponse, String> {
        new.copy_from_slice(old);
        let in_contact = delta[0] < 0.0;
        if in_contact {
            new[0] = 1.0;
        }
        if new[0] == 0.0 {
            return Ok(MixedResponse::default());
        }
        let (value, tangent) = match &self.shape {
            Shape::Bilinear(law) => {
                let r = law.evaluate(delta, old[2]);
                new[1] = old[1].max(r.equivalent_opening);
                new[2] = r.damage;
                (r.value, r.tangent)
            }
            Shape::Exponential(law) => {
                let open = delta[0].max(0.0);
                new[1] = old[1].max((open * open + delta[1] * delta[1] + delta[2] * delta[2]).sqrt());
                law.evaluate(delta)
            }
        };
        Ok(MixedResponse { value, tangent, in_contact, area: 0.0 })
    }

    fn state_names() -> Vec<&'static std::ffi::CStr> {
        vec![c"bonded", c"largest_opening", c"damage"]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Parameters: G_c, sigma_max, penalty, shape, bonded, G_IIc, tau_max, eta.
    fn law(p: [f64; 8]) -> CohesiveZone {
        CohesiveZone::create(&p, "").unwrap()
    }

    /// Work of the traction along the proportional opening lambda * direction, lambda 0 -> l_max,
    /// from a bonded point: integral of -value . d delta (midpoint rule).
    fn work_along(law: &CohesiveZone, direction: [f64; 3], l_max: f64) -> f64 {
        let n = 200_000;
        let mut state = [1.0, 0.0, 0.0];
        let h = l_max / n as f64;
        let mut w = 0.0;
        for i in 0..n {
            let l = (i as f64 + 0.5) * h;
            let mut new = [0.0; 3];
            let r = law.evaluate_mixed(direction.map(|d| d * l), &state, &mut new).unwrap();
            state = new;
            w -= (0..3).map(|k| r.value[k] * direction[k]).sum::<f64>() * h;
        }
        w
    }

    #[test]
    fn the_mode_i_energy_under_each_law_is_g_c() {
        let bilinear = law([1.0, 6.0, 2e4, 0.0, 0.0, 0.0, 0.0, 2.0]);
        let w = work_along(&bilinear, [1.0, 0.0, 0.0], 2.0 / 6.0 * 1.01);
        assert!((w - 1.0).abs() < 1e-6, "bilinear {w}");
        let exponential = law([1.0, 6.0, 2e4, 1.0, 0.0, 0.0, 0.0, 2.0]);
        let dc = 1.0 / (std::f64::consts::E * 6.0);
        let w = work_along(&exponential, [1.0, 0.0, 0.0], 60.0 * dc);
        assert!((w - 1.0).abs() < 1e-6, "exponential {w}");
    }

    /// Benzeggagh-Kenane: the energy of a proportional mixed-mode opening is
    /// G_Ic + (G_IIc - G_Ic) B^eta with B = G_shear / G_total = sin^2(theta) (equal penalties).
    #[test]
    fn the_mixed_mode_energy_follows_benzeggagh_kenane() {
        let (g1, g2, eta) = (0.8, 2.4, 2.284);
        let l = law([g1, 6.0, 2e4, 0.0, 0.0, g2, 9.0, eta]);
        for theta_deg in [0.0f64, 20.0, 45.0, 70.0, 90.0] {
            let t = theta_deg.to_radians();
            // the second slip component too: the law must depend on |slip| only
            let dir = [t.cos(), t.sin() * 0.6, t.sin() * 0.8];
            let b = t.sin().powi(2);
            let expected = g1 + (g2 - g1) * b.powf(eta);
            let w = work_along(&l, dir, 0.6); // beyond every final opening (0.27 .. 0.53)
            assert!((w - expected).abs() < 1e-6 * expected, "theta {theta_deg}: work {w}, BK {expected}");
        }
    }

    /// Onset: under proportional opening the damage starts where the undamaged tractions meet
    /// the quadratic criterion (t_n / N)^2 + (t_s / S)^2 = 1.
    #[test]
    fn damage_starts_on_the_quadratic_stress_criterion() {
        let (n, s, k) = (6.0, 9.0, 2e4);
        let l = law([0.8, n, k, 0.0, 0.0, 2.4, s, 2.0]);
        for theta_deg in [10.0f64, 45.0, 80.0] {
            let t = theta_deg.to_radians();
            // the criterion in closed form for this direction: lambda^2 k^2 (c^2/N^2 + s^2/S^2) = 1
            let lambda = 1.0 / (k * ((t.cos() / n).powi(2) + (t.sin() / s).powi(2)).sqrt());
            let mut st = [0.0; 3];
            let below = [t.cos(), t.sin(), 0.0].map(|d| d * lambda * (1.0 - 1e-9));
            l.evaluate_mixed(below, &[1.0, 0.0, 0.0], &mut st).unwrap();
            assert_eq!(st[2], 0.0, "theta {theta_deg}: no damage just below the onset");
            let above = [t.cos(), t.sin(), 0.0].map(|d| d * lambda * (1.0 + 1e-6));
            l.evaluate_mixed(above, &[1.0, 0.0, 0.0], &mut st).unwrap();
            assert!(st[2] > 0.0, "theta {theta_deg}: damage just above the onset");
        }
    }

    /// Tangent vs central differences of the value vector along a mixed load-unload-reload path.
    /// Returns the worst relative error and how many points were checked while damage grew.
    fn check_tangent(l: &CohesiveZone, scale: f64) -> (f64, usize) {
        let mut state = [1.0, 0.0, 0.0];
        let mut worst = 0.0f64;
        let mut softening = 0;
        let h = 1e-7 * scale;
        for i in 0..300 {
            let s = i as f64 / 300.0;
            // a path that opens, shears, unloads, closes into compression and reopens
            let a = 2.0 * (6.0 * s).sin() + 0.3;
            let delta = [scale * a * (1.0 + s), scale * (3.0 * s).cos() * 1.5 * s, -scale * 0.7 * s * s];
            let mut new = [0.0; 3];
            let r = l.evaluate_mixed(delta, &state, &mut new).unwrap();
            let norm = r.tangent.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
            for j in 0..3 {
                let mut dp = delta;
                let mut dm = delta;
                dp[j] += h;
                dm[j] -= h;
                let mut scratch = [0.0; 3];
                let vp = l.evaluate_mixed(dp, &state, &mut scratch).unwrap().value;
                let vm = l.evaluate_mixed(dm, &state, &mut scratch).unwrap().value;
                let mut dp2 = delta;
                let mut dm2 = delta;
                dp2[j] += 10.0 * h;
                dm2[j] -= 10.0 * h;
                let vp2 = l.evaluate_mixed(dp2, &state, &mut scratch).unwrap().value;
                let vm2 = l.evaluate_mixed(dm2, &state, &mut scratch).unwrap().value;
                for k in 0..3 {
                    let fd = (vp[k] - vm[k]) / (2.0 * h);
                    let fd_wide = (vp2[k] - vm2[k]) / (20.0 * h);
                    if (fd - fd_wide).abs() > 1e-4 * norm {
                        continue; // a kink (onset, full damage, contact) within the stencil
                    }
                    worst = worst.max((r.tangent[k][j] - fd).abs() / norm);
                    if new[2] > state[2] && new[2] < 1.0 && k == 0 && j == 1 {
                        softening += 1;
                    }
                }
            }
            state = new;
        }
        (worst, softening)
    }

    #[test]
    fn mixed_mode_tangents_match_finite_differences() {
        let bilinear = law([0.8, 6.0, 2e4, 0.0, 0.0, 2.4, 9.0, 2.284]);
        let (e, softening) = check_tangent(&bilinear, 2e-4);
        eprintln!("bilinear mixed-mode tangent: max error {e:.2e}, {softening} points checked while damage grew");
        assert!(e < 1e-6 && softening > 20, "bilinear: {e}, {softening} softening points");
        let exponential = law([1.0, 6.0, 2e4, 1.0, 0.0, 0.0, 4.0, 2.0]);
        let (e, _) = check_tangent(&exponential, 0.03);
        assert!(e < 1e-6, "exponential: {e}");
    }

    #[test]
    fn the_exponential_shear_peak_and_energy_are_tau_max_and_g_c() {
        let l = law([1.0, 6.0, 2e4, 1.0, 0.0, 0.0, 4.0, 2.0]);
        let mut st = [0.0; 3];
        let dt = 1.0 / ((std::f64::consts::E / 2.0).sqrt() * 4.0);
        let peak = l.evaluate_mixed([0.0, dt / 2f64.sqrt(), 0.0], &[1.0, 0.0, 0.0], &mut st).unwrap();
        assert!((peak.value[1] + 4.0).abs() < 1e-12, "shear peak {}", peak.value[1]);
        let w = work_along(&l, [0.0, 1.0, 0.0], 12.0 * dt);
        assert!((w - 1.0).abs() < 1e-6, "shear work of separation {w}");
        assert!(
            CohesiveZone::create(&[1.0, 6.0, 2e4, 1.0, 0.0, 2.0, 0.0, 2.0], "").is_err(),
            "exponential with G_IIc != G_c"
        );
    }

    #[test]
    fn secant_unloading_and_no_adhesion_before_first_contact() {
        let l = law([1.0, 6.0, 2e4, 0.0, 0.0, 0.0, 0.0, 2.0]);
        let mut s = [0.0; 3];
        assert_eq!(l.evaluate(0.01, &[0.0, 0.0, 0.0], &mut s).unwrap().value, 0.0, "never touched: no adhesion");
        // bond, open (mixed) to half the final opening, unload along the same direction
        let m = [0.1, 0.05, 0.0];
        let r = l.evaluate_mixed(m, &[1.0, 0.0, 0.0], &mut s).unwrap();
        let committed = s;
        assert!(committed[2] > 0.0 && committed[2] < 1.0, "damage {}", committed[2]);
        let back = l.evaluate_mixed(m.map(|v| 0.25 * v), &committed, &mut s).unwrap();
        for k in 0..2 {
            assert!((back.value[k] - 0.25 * r.value[k]).abs() < 1e-9 * r.value[k].abs(), "secant to the origin");
        }
        assert_eq!(s[2], committed[2], "no damage growth while unloading");
        assert!(
            CohesiveZone::create(&[1.0, 6.0, 10.0, 0.0, 0.0, 0.0, 0.0, 2.0], "").is_err(),
            "k below sigma_max^2 / 2 G_c"
        );
        // a shear strength the mode-II energy cannot honour
        assert!(
            CohesiveZone::create(&[1.0, 6.0, 100.0, 0.0, 0.0, 0.1, 9.0, 2.0], "").is_err(),
            "k below tau_max^2 / 2 G_IIc"
        );
    }
}
