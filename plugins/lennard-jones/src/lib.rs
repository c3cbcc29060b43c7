//! `lennard-jones` (the law; `plugin/` exports it as a shared library): adhesive traction between two half-spaces (Derjaguin approximation;
//! Greenwood 1997):
//! p(h) = (8 w / (3 z0)) [ (z0/h)^3 - (z0/h)^9 ], positive = attraction, h = local gap.
//! Our normal value (positive pushes apart) is sigma(h) = -p(h).
//! Integral of p from z0 to infinity = w; peak attraction 16 w / (9 sqrt 3 z0) at h = 3^(1/6) z0.
//!
//! Below h_min = 0.5 z0 the repulsive branch continues linearly with the slope at h_min, so a
//! Newton iterate that overshoots into h <= 0 gets a large but finite restoring traction instead
//! of an overflow. Physical solutions stay above h_min (there sigma is already ~500x the peak
//! adhesive stress).

use stiction_law_sdk::{Law, LawKind, Parameter, Response};

#[derive(Debug, Clone)]
pub struct LennardJones {
    pub w: f64,
    pub z0: f64,
}

impl LennardJones {
    /// sigma(h) = -(8 w / (3 z0)) [ (z0/h)^3 - (z0/h)^9 ] and its derivative, for h > 0.
    fn exact(&self, h: f64) -> (f64, f64) {
        let c = 8.0 * self.w / (3.0 * self.z0);
        let s = self.z0 / h;
        let (s3, s9) = (s.powi(3), s.powi(9));
        (-c * (s3 - s9), c * (3.0 * s3 - 9.0 * s9) / h)
    }

    /// Peak adhesive stress 16 w / (9 sqrt 3 z0).
    pub fn peak_stress(&self) -> f64 {
        16.0 * self.w / (9.0 * 3f64.sqrt() * self.z0)
    }
}

impl Law for LennardJones {
    const NAME: &'static std::ffi::CStr = c"lennard-jones";
    const VERSION: &'static std::ffi::CStr = c"0.1.0";
    const KIND: LawKind = LawKind::TractionPerArea;
    const N_STATE: usize = 0;

    fn parameters() -> Vec<Parameter> {
        vec![
            Parameter::required(c"w", c"energy/area (J/m^2 = nN/nm)", c"work of adhesion", 1e-12, f64::INFINITY),
            Parameter::required(c"z0", c"length", c"equilibrium separation", 1e-12, f64::INFINITY),
        ]
    }

    fn create(p: &[f64], _config: &str) -> Result<Self, String> {
        let (w, z0) = (p[0], p[1]);
        if !(w > 0.0 && z0 > 0.0 && w.is_finite() && z0.is_finite()) {
            return Err(format!("w and z0 must be positive, got w = {w}, z0 = {z0}"));
        }
        Ok(Self { w, z0 })
    }

    fn evaluate(&self, gap: f64, _old: &[f64], _new: &mut [f64]) -> Result<Response, String> {
        let h_min = 0.5 * self.z0;
        let (value, tangent) = if gap >= h_min {
            self.exact(gap)
        } else {
            let (v, t) = self.exact(h_min);
            (v + t * (gap - h_min), t)
        };
        // In contact where the surfaces repel (h < z0), as in Greenwood's and Feng's analyses.
        Ok(Response { value, tangent, in_contact: gap < self.z0, area: 0.0 })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integral_of_attraction_is_the_work_of_adhesion() {
        let law = LennardJones::create(&[1.0, 0.169], "").unwrap();
        // integral_z0^inf p dh with p = -sigma, substitution h = z0 / s: integral_0^1 p z0/s^2 ds
        let g = stiction_core::quadrature::gauss_legendre(40);
        let mut total = 0.0;
        for (x, w) in g.points.iter().zip(&g.weights) {
            let s = 0.5 * (x[0] + 1.0);
            let h = law.z0 / s;
            total += 0.5 * w * (-law.evaluate(h, &[], &mut []).unwrap().value) * law.z0 / (s * s);
        }
        assert!((total - 1.0).abs() < 1e-10, "{total}");
    }

    #[test]
    fn peak_attraction_and_tangent() {
        let law = LennardJones::create(&[3.0, 0.169], "").unwrap();
        let h_peak = 3f64.powf(1.0 / 6.0) * law.z0;
        let r = law.evaluate(h_peak, &[], &mut []).unwrap();
        assert!((-r.value - law.peak_stress()).abs() < 1e-12 * law.peak_stress());
        assert!(r.tangent.abs() < 1e-9 * law.peak_stress() / law.z0);
        for h in [0.3 * law.z0, 0.9 * law.z0, 1.3 * law.z0, 4.0 * law.z0] {
            let d = 1e-7 * law.z0;
            let f = |x: f64| law.evaluate(x, &[], &mut []).unwrap().value;
            let fd = (f(h + d) - f(h - d)) / (2.0 * d);
            let t = law.evaluate(h, &[], &mut []).unwrap().tangent;
            assert!((fd - t).abs() < 1e-6 * t.abs().max(1.0), "h = {h}: {fd} vs {t}");
        }
    }
}
