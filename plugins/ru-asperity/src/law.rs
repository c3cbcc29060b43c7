//! The hysteretic nano-asperity law (force per asperity), in the asperity's MD distance
//! d = -gap (positive pressing). Forces positive compressive.
//!
//! Branches and the rules we define beyond the fitted data:
//! * Fresh (never touched, or separated): no force for d < d_start - ramp; on
//!   [d_start - ramp, d_start] the force ramps linearly from 0 to F_L(d_start) (the small
//!   jump-in attraction), without area; at d >= d_start the asperity is loaded.
//! * Loading (d at or above its maximum so far, m = d): F_L(d), A_L(d) (the loading fits);
//!   beyond the fitted range (d > loading.d_end) continued linearly with the end slope.
//! * Unloading / partial reloading (d < m): the unloading curve of maximum m, both down and back
//!   up (the branch is reversible below m); above m the asperity is on the loading curve again.
//!   For m between two fitted maxima m_i < m < m_{i+1}, theta = (m - m_i)/(m_{i+1} - m_i), the
//!   force is the linear interpolation of the two neighbouring curves' forces at the same
//!   normalised position s = (d - e)/(m - e) along the branch, e = (1 - theta) e_i + theta e_{i+1}
//!   the interpolated separation distance. Outside the fitted maxima the nearest curve is
//!   translated in d so its maximum is m. A linear correction in s makes the branch meet the
//!   loading curve exactly at s = 1 and zero force exactly at s = 0, so the force is continuous
//!   at every branch change; the tangent is the exact derivative of this force.
//! * Separation (d < e(m)): zero force and area, the asperity counts a pull-off and is fresh
//!   again: re-contact follows the loading curve from d_start (the data have no reloading after
//!   pull-off; this is our rule, so that any number of load-unload cycles runs).

use crate::calibration::{Calibration, UnloadingFit};
use crate::polynomial as poly;

/// Asperity state: [maximum distance m, phase (0 fresh, 1 in contact, 2 separated), pull-offs].
pub const N_STATE: usize = 3;
const M: usize = 0;
const PHASE: usize = 1;
const PULLOFFS: usize = 2;

/// Value and derivative of force and area at one distance.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Evaluation {
    pub force: f64,
    /// dF/dd
    pub stiffness: f64,
    pub area: f64,
    pub in_contact: bool,
}

#[derive(Debug, Clone)]
pub struct AsperityModel {
    pub calibration: Calibration,
    pub ramp: f64,
}

/// A fitted or translated unloading curve.
struct Curve<'a> {
    fit: &'a UnloadingFit,
    shift: f64,
}

impl Curve<'_> {
    fn d_max(&self) -> f64 {
        self.fit.d_max + self.shift
    }
    fn d_end(&self) -> f64 {
        self.fit.d_end + self.shift
    }
    fn at(&self, s: f64) -> (f64, f64, f64, f64) {
        // position on the curve, force, dF/dd, area, at normalised s
        let d = self.fit.d_end + s * (self.fit.d_max - self.fit.d_end);
        (
            poly::value(&self.fit.force, d),
            poly::derivative(&self.fit.force, d),
            poly::value(&self.fit.area, d),
            poly::derivative(&self.fit.area, d),
        )
    }
}

impl AsperityModel {
    /// Loading force, stiffness, area, darea at d (linear beyond the fitted end).
    fn loading(&self, d: f64) -> (f64, f64, f64, f64) {
        let l = &self.calibration.loading;
        let x = d.min(l.d_end);
        let (f, k, a, da) = (
            poly::value(&l.force, x),
            poly::derivative(&l.force, x),
            poly::value(&l.area, x),
            poly::derivative(&l.area, x),
        );
        if d > l.d_end { (f + k * (d - l.d_end), k, a + da * (d - l.d_end), da) } else { (f, k, a, da) }
    }

    /// The two curves (and weight of the second) that define the unloading branch of maximum m.
    fn bracket(&self, m: f64) -> (Curve<'_>, Curve<'_>, f64) {
        let u = &self.calibration.unloading;
        let n = u.len();
        if m <= u[0].d_max {
            let c = || Curve { fit: &u[0], shift: m - u[0].d_max };
            return (c(), c(), 0.0);
        }
        if m >= u[n - 1].d_max {
            let c = || Curve { fit: &u[n - 1], shift: m - u[n - 1].d_max };
            return (c(), c(), 0.0);
        }
        let i = u.partition_point(|f| f.d_max <= m) - 1;
        let theta = (m - u[i].d_max) / (u[i + 1].d_max - u[i].d_max);
        (Curve { fit: &u[i], shift: 0.0 }, Curve { fit: &u[i + 1], shift: 0.0 }, theta)
    }

    /// Separation distance e(m) of the unloading branch from maximum m.
    pub fn separation_distance(&self, m: f64) -> f64 {
        let (a, b, t) = self.bracket(m);
        (1.0 - t) * a.d_end() + t * b.d_end()
    }

    /// Force, dF/dd and area on the unloading branch of maximum m at distance d (e(m) <= d <= m).
    pub fn unloading(&self, m: f64, d: f64) -> Evaluation {
        let (a, b, t) = self.bracket(m);
        let e = (1.0 - t) * a.d_end() + t * b.d_end();
        let span = m - e;
        let s = ((d - e) / span).clamp(0.0, 1.0);
        let interp = |s: f64| {
            let (fa, ka, aa, _) = a.at(s);
            let (fb, kb, ab, _) = b.at(s);
            let f = (1.0 - t) * fa + t * fb;
            // dF/dd through s: d(d_curve)/ds = (d_max - d_end) of each curve, ds/dd = 1/span
            let k = ((1.0 - t) * ka * (a.d_max() - a.d_end()) + t * kb * (b.d_max() - b.d_end())) / span;
            let ar = (1.0 - t) * aa + t * ab;
            (f, k, ar)
        };
        let (f, k, ar) = interp(s);
        let (f1, _, a1) = interp(1.0);
        let (f0, _, a0) = interp(0.0);
        let (fl, _, al, _) = self.loading(m);
        // F = F_interp(s) + (F_L(m) - F_interp(1)) s - F_interp(0) (1 - s)
        let (c1, c0) = (fl - f1, f0);
        let force = f + c1 * s - c0 * (1.0 - s);
        let stiffness = k + (c1 + c0) / span;
        let area = (ar + (al - a1) * s - a0 * (1.0 - s)).max(0.0);
        Evaluation { force, stiffness, area, in_contact: true }
    }

    /// The law at distance d from the committed state; writes the trial state.
    pub fn evaluate(&self, d: f64, old: &[f64], new: &mut [f64]) -> Evaluation {
        new.copy_from_slice(old);
        let l = &self.calibration.loading;
        let in_contact = old[PHASE] == 1.0;
        if !in_contact {
            if d < l.d_start - self.ramp {
                return Evaluation::default();
            }
            if d < l.d_start {
                let (f0, ..) = self.loading(l.d_start);
                let w = (d - (l.d_start - self.ramp)) / self.ramp;
                return Evaluation { force: f0 * w, stiffness: f0 / self.ramp, area: 0.0, in_contact: false };
            }
            let (f, k, a, _) = self.loading(d);
            new[M] = d;
            new[PHASE] = 1.0;
            return Evaluation { force: f, stiffness: k, area: a.max(0.0), in_contact: true };
        }
        let m = old[M];
        if d >= m {
            let (f, k, a, _) = self.loading(d);
            new[M] = d;
            return Evaluation { force: f, stiffness: k, area: a.max(0.0), in_contact: true };
        }
        if d < self.separation_distance(m) {
            new[PHASE] = 2.0;
            new[PULLOFFS] = old[PULLOFFS] + 1.0;
            return Evaluation::default();
        }
        self.unloading(m, d)
    }

    /// The largest tensile (most negative) force on the unloading branch of maximum m, and the
    /// distance where it occurs (sampled; for reports and tests).
    pub fn pull_off(&self, m: f64) -> (f64, f64) {
        let e = self.separation_distance(m);
        (0..=2000)
            .map(|i| e + (m - e) * i as f64 / 2000.0)
            .map(|d| (self.unloading(m, d).force, d))
            .fold((f64::INFINITY, 0.0), |acc, x| if x.0 < acc.0 { x } else { acc })
    }
}
