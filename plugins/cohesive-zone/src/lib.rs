//! `cohesive-zone`: normal cohesive-zone laws for adhesive contact (value positive pushes apart).
//!
//! Compression (g < 0): penalty contact, sigma = -k g.
//! Opening (g >= 0) of a point that has touched (bonded on first contact, g <= 0):
//! * `shape = 0`, bilinear with damage (Camanho & Davila 2002, mode I): initial stiffness k,
//!   onset d0 = sigma_max / k, final d_f = 2 G_c / sigma_max; damage from the largest opening
//!   m: D = d_f (m - d0) / (m (d_f - d0)) in [0, 1]; sigma = -(1 - D) k g (secant unloading
//!   and reloading to the origin); the energy under the curve is G_c exactly.
//! * `shape = 1`, exponential (Xu & Needleman 1993, normal part): sigma = -(G_c/d_c)(g/d_c)
//!   exp(-g/d_c) with d_c = G_c / (e sigma_max) (peak sigma_max at g = d_c; energy G_c);
//!   reversible, no damage.
//! A point that never touched carries no adhesion, unless `initially_bonded = 1` (an uncracked
//! ligament, e.g. a double cantilever beam's). State: [bonded, largest opening m].
//! Parameters: G_c (energy per area), sigma_max (stress), penalty k (0: chosen by the host,
//! 100 E / h), shape, initially_bonded. k must exceed sigma_max^2 / (2 G_c) (onset before failure).

use stiction_law_sdk::{Law, LawKind, Parameter, Response};

pub struct CohesiveZone {
    pub g_c: f64,
    pub sigma_max: f64,
    pub k: f64,
    pub exponential: bool,
    pub initially_bonded: bool,
}

impl CohesiveZone {
    fn d0(&self) -> f64 {
        self.sigma_max / self.k
    }
    fn d_f(&self) -> f64 {
        2.0 * self.g_c / self.sigma_max
    }
    /// Bilinear damage for the largest opening m.
    pub fn damage(&self, m: f64) -> f64 {
        let (d0, df) = (self.d0(), self.d_f());
        if m <= d0 { 0.0 } else { (df * (m - d0) / (m * (df - d0))).min(1.0) }
    }
}

impl Law for CohesiveZone {
    const NAME: &'static std::ffi::CStr = c"cohesive-zone";
    const VERSION: &'static std::ffi::CStr = c"0.1.0";
    const KIND: LawKind = LawKind::TractionPerArea;
    const N_STATE: usize = 2;

    fn parameters() -> Vec<Parameter> {
        vec![
            Parameter::required(
                c"G_c",
                c"energy/area (J/m^2 = nN/nm)",
                c"fracture energy (work of adhesion)",
                1e-12,
                f64::INFINITY,
            ),
            Parameter::required(c"sigma_max", c"stress", c"cohesive strength", 1e-12, f64::INFINITY),
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
        ]
    }

    fn create(p: &[f64], _config: &str) -> Result<Self, String> {
        let law = Self { g_c: p[0], sigma_max: p[1], k: p[2], exponential: p[3] >= 0.5, initially_bonded: p[4] >= 0.5 };
        if !(law.k > 0.0) {
            return Err("penalty must be positive".into());
        }
        if p[3] != 0.0 && p[3] != 1.0 {
            return Err(format!("shape must be 0 (bilinear) or 1 (exponential), got {}", p[3]));
        }
        if !law.exponential && law.d0() >= law.d_f() {
            return Err(format!(
                "penalty {} is too small: the bilinear law needs k > sigma_max^2 / (2 G_c) = {}",
                law.k,
                law.sigma_max * law.sigma_max / (2.0 * law.g_c)
            ));
        }
        Ok(law)
    }

    fn initialize_state(&self, state: &mut [f64]) {
        state[0] = if self.initially_bonded { 1.0 } else { 0.0 };
        state[1] = 0.0;
    }

    fn evaluate(&self, g: f64, old: &[f64], new: &mut [f64]) -> Result<Response, String> {
        new.copy_from_slice(old);
        if g < 0.0 {
            new[0] = 1.0;
            return Ok(Response { value: -self.k * g, tangent: -self.k, in_contact: true, area: 0.0 });
        }
        if old[0] == 0.0 {
            return Ok(Response::default());
        }
        if self.exponential {
            let dc = self.g_c / (std::f64::consts::E * self.sigma_max);
            let x = g / dc;
            let e = (-x).exp();
            let value = -(self.g_c / dc) * x * e;
            let tangent = -(self.g_c / (dc * dc)) * (1.0 - x) * e;
            return Ok(Response { value, tangent, in_contact: false, area: 0.0 });
        }
        let m_old = old[1];
        if g > m_old {
            // softening (or still elastic before onset): damage grows with the opening
            new[1] = g;
            let (d0, df) = (self.d0(), self.d_f());
            let (value, tangent) = if g <= d0 {
                (-self.k * g, -self.k)
            } else if g < df {
                (-self.sigma_max * (df - g) / (df - d0), self.sigma_max / (df - d0))
            } else {
                (0.0, 0.0)
            };
            return Ok(Response { value, tangent, in_contact: false, area: 0.0 });
        }
        // unloading / reloading below the largest opening: secant to the origin
        let d = self.damage(m_old);
        Ok(Response { value: -(1.0 - d) * self.k * g, tangent: -(1.0 - d) * self.k, in_contact: false, area: 0.0 })
    }

    fn state_names() -> Vec<&'static std::ffi::CStr> {
        vec![c"bonded", c"largest_opening"]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn work_of_separation(law: &CohesiveZone, g_max: f64) -> f64 {
        // integral of the adhesive traction from 0 to g_max along monotonic opening (bonded)
        let n = 200_000;
        let mut state = [1.0, 0.0];
        let mut w = 0.0;
        let h = g_max / n as f64;
        for i in 0..n {
            let g = (i as f64 + 0.5) * h;
            let mut new = [0.0; 2];
            let r = law.evaluate(g, &state, &mut new).unwrap();
            state = new;
            w += -r.value * h;
        }
        w
    }

    #[test]
    fn the_energy_under_each_law_is_g_c() {
        let bilinear = CohesiveZone::create(&[1.0, 6.0, 2e4, 0.0, 0.0], "").unwrap();
        let w = work_of_separation(&bilinear, bilinear.d_f() * 1.01);
        assert!((w - 1.0).abs() < 1e-6, "bilinear {w}");
        let exponential = CohesiveZone::create(&[1.0, 6.0, 2e4, 1.0, 0.0], "").unwrap();
        let dc = 1.0 / (std::f64::consts::E * 6.0);
        let w = work_of_separation(&exponential, 60.0 * dc);
        assert!((w - 1.0).abs() < 1e-6, "exponential {w}");
    }

    #[test]
    fn secant_unloading_and_no_adhesion_before_first_contact() {
        let law = CohesiveZone::create(&[1.0, 6.0, 2e4, 0.0, 0.0], "").unwrap();
        let mut s = [0.0; 2];
        assert_eq!(law.evaluate(0.01, &[0.0, 0.0], &mut s).unwrap().value, 0.0, "never touched: no adhesion");
        // bond, open to half the final opening, unload to a quarter of that
        let m = 0.5 * law.d_f();
        let r = law.evaluate(m, &[1.0, 0.0], &mut s).unwrap();
        let committed = s;
        let back = law.evaluate(0.25 * m, &committed, &mut s).unwrap();
        assert!((back.value - 0.25 * r.value).abs() < 1e-9 * r.value.abs(), "secant to the origin");
        assert!(CohesiveZone::create(&[1.0, 6.0, 10.0, 0.0, 0.0], "").is_err(), "k below sigma_max^2 / 2 G_c");
    }
}
