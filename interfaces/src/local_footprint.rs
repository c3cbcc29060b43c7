//! The footprint's own response below the mesh scale, in series with a point law: a local
//! correction that lets a mesh coarser than an asperity's base carry the asperity.
//!
//! A mesh whose faces are larger than a footprint misses two things under it: the elastic
//! compliance of the footprint's own area (the continuum under a small disc is softer than the
//! mesh can show) and the local limit load (the continuum under a small disc flows plastically
//! at a force the coarse mesh, which spreads it over a whole face, does not reach). Both act in
//! series with the law: the law sees the local surface, which is displaced from the coarse
//! mesh's surface by an elastic spring of compliance c and a rigid-perfectly plastic slider of
//! limit F_lim (the local permanent indentation s, growing under compression at F = F_lim,
//! drawn back toward the flat at F = -F_lim):
//!
//!   F = f(x),   x = g + c F + s,   |F| <= F_lim,
//!
//! with g the gap the mesh gives (positive apart; F positive pushes apart), x the law's own gap
//! and f the law from its committed state. Elastic (|F| < F_lim, s fixed): x solves
//! phi(x) = x - c f(x) - s - g = 0, and dF/dg = f'/(1 - c f') (the law's stiffness in series
//! with the spring 1/c). Plastic: F = +-F_lim, x is where the law reaches it and
//! s = x - g - c F, dF/dg = 0; the slider dissipates F_lim |ds|.
//!
//! The root of phi taken is the first one met from the committed x, moving downhill; since
//! phi -> -inf as x -> -inf (compression) and phi -> +inf as x -> +inf (apart), it exists and
//! phi' > 0 there. Where the law softens faster than the spring (f' > 1/c) the branch folds and
//! the point snaps to the next root: the footprint's local jump-out (or jump-in).

use std::sync::Arc;
use stiction_core::interface_law::{InterfaceLaw, LawError, LawKind, LawResponse};
use stiction_core::observables::LAW_GAP_FIELD;

/// The local response under one footprint: elastic compliance and limit force.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LocalFootprint {
    /// Length per force (e.g. nm/nN): the footprint's compliance the mesh does not resolve.
    pub compliance: f64,
    /// Force magnitude at which the continuum under the footprint flows (compression and
    /// tension alike, von Mises being symmetric); infinite where no limit is modelled (the
    /// footprint elastic: the compliance alone).
    pub limit_force: f64,
}

/// The name of the state variable holding a point's slider work (summed by the interfaces
/// into the run's plastic dissipation).
pub const PLASTIC_WORK_STATE: &str = "footprint_plastic_work";

/// The limit pressure of a uniform pressure on a disc over an elastic-perfectly plastic
/// von Mises half-space, in units of the yield stress: 2.99, from the axisymmetric limit
/// analysis `cases/validation/disc-limit-axisym.toml` (3.01 with 20 elements across the disc's
/// radius, 2.99 with 40). It lies between Shield's punch limit 5.69 k with the Tresca
/// k = Y / 2 (2.85) and with the von Mises k = Y / sqrt(3) (3.29).
pub const DISC_LIMIT_PRESSURE_OVER_YIELD: f64 = 2.99;

/// Mean surface displacement per unit force of a uniform pressure on a disc of radius `a` on
/// an elastic half-space (Johnson, Contact Mechanics, 3.4): u = 16 (1 - nu^2) F / (3 pi^2 E a).
pub fn disc_compliance(young: f64, poisson: f64, radius: f64) -> f64 {
    16.0 * (1.0 - poisson * poisson) / (3.0 * std::f64::consts::PI.powi(2) * young * radius)
}

/// A law in series with its footprint's local response (see the module documentation).
/// State: the law's own, then the law's gap x, the slider s and the slider's work.
pub struct SeriesWithFootprint {
    inner: Arc<dyn InterfaceLaw>,
    local: LocalFootprint,
}

const LAW_GAP: usize = 0;
const SLIDER: usize = 1;
const SLIDER_WORK: usize = 2;
/// The point's own compliance (initialised to the law's; an interface may set it per point,
/// as initial conditions of a state variable).
const COMPLIANCE: usize = 3;
const N_OWN: usize = 4;

/// Index of the compliance among the state variables of a law of `n_inner` states.
pub fn compliance_state_index(n_inner: usize) -> usize {
    n_inner + COMPLIANCE
}

impl SeriesWithFootprint {
    /// `inner` must give forces per point along the normal only.
    pub fn new(inner: Arc<dyn InterfaceLaw>, local: LocalFootprint) -> Result<Self, String> {
        if inner.kind() != LawKind::ForcePerPoint || inner.gap_dimension() != 1 {
            return Err(format!("law '{}': a footprint correction needs a normal force-per-point law", inner.name()));
        }
        if !(local.compliance >= 0.0 && local.compliance.is_finite()) {
            return Err(format!("the footprint compliance must be >= 0, not {}", local.compliance));
        }
        if !(local.limit_force > 0.0) {
            return Err(format!("the footprint limit force must be > 0, not {}", local.limit_force));
        }
        Ok(Self { inner, local })
    }

    /// The law at its own gap `x` from the committed state `old` (the law's part).
    fn law(&self, x: f64, old: &[f64], new: &mut [f64]) -> Result<LawResponse, LawError> {
        self.inner.evaluate(x, old, new)
    }

    /// The first root of phi(x) = x - c f(x) - s - g met from `x0` moving downhill.
    fn elastic_gap(&self, (g, s, c): (f64, f64, f64), x0: f64, old: &[f64], new: &mut [f64]) -> Result<f64, LawError> {
        let mut phi = |x: f64| -> Result<(f64, f64), LawError> {
            let r = self.law(x, old, new)?;
            Ok((x - c * r.value - s - g, 1.0 - c * r.tangent))
        };
        let (p0, _) = phi(x0)?;
        if p0 == 0.0 {
            return Ok(x0);
        }
        // march downhill with doubling steps until phi changes sign
        let direction = -p0.signum();
        let mut step = p0.abs().max(1e-12 * (1.0 + x0.abs()));
        let (mut a, mut pa) = (x0, p0);
        let (mut b, mut pb);
        let mut marches = 0;
        loop {
            b = a + direction * step;
            pb = phi(b)?.0;
            if pb == 0.0 {
                return Ok(b);
            }
            if pb.signum() != pa.signum() {
                break;
            }
            (a, pa) = (b, pb);
            step *= 2.0;
            marches += 1;
            if marches > 200 {
                return Err(LawError(format!("footprint correction: no root of the series equation from gap {g:e}")));
            }
        }
        // safeguarded Newton in the bracket [a, b]
        let mut x = if pa.abs() < pb.abs() { a } else { b };
        for _ in 0..100 {
            let (p, dp) = phi(x)?;
            if p == 0.0 {
                return Ok(x);
            }
            if p.signum() == pa.signum() {
                (a, pa) = (x, p);
            } else {
                b = x;
            }
            let newton = x - p / dp;
            let inside = (newton - a) * (newton - b) < 0.0 && dp > 0.0;
            let next = if inside { newton } else { 0.5 * (a + b) };
            if (next - x).abs() <= 1e-14 * (1.0 + x.abs()) || (a - b).abs() <= 1e-14 * (1.0 + x.abs()) {
                return Ok(next);
            }
            x = next;
        }
        Ok(x)
    }

    /// Where the law reaches `target` between `from` (short of it, the committed point) and
    /// `to` (beyond it). If `from` is beyond it too (a point's first evaluation, already past
    /// the limit), the crossing is sought from `to` along the law's slope toward the target.
    fn plastic_gap(&self, target: f64, from: f64, to: f64, old: &[f64], new: &mut [f64]) -> Result<f64, LawError> {
        let excess = |x: f64, new: &mut [f64]| -> Result<(f64, f64), LawError> {
            let r = self.law(x, old, new)?;
            Ok((r.value - target, r.tangent))
        };
        let (ea, _) = excess(from, new)?;
        // already at the limit (the committed point of a flowing slider)
        if ea == 0.0 {
            return Ok(from);
        }
        let (eb, slope) = excess(to, new)?;
        let (mut a, mut b) = (from, to);
        if ea.signum() == eb.signum() {
            if slope == 0.0 {
                return Err(LawError(format!(
                    "footprint correction: the law does not reach the limit {target:e} from gap {to:e}"
                )));
            }
            // march from `to` toward the target along the slope, with doubling steps
            let direction = -(eb / slope).signum();
            let mut step = (eb / slope).abs().max(1e-12 * (1.0 + to.abs()));
            a = to;
            let mut found = false;
            for _ in 0..100 {
                b = a + direction * step;
                if excess(b, new)?.0.signum() != eb.signum() {
                    found = true;
                    break;
                }
                a = b;
                step *= 2.0;
            }
            if !found {
                return Err(LawError(format!(
                    "footprint correction: the law does not reach the limit {target:e} from gap {to:e}"
                )));
            }
        }
        let sign_a = excess(a, new)?.0.signum();
        for _ in 0..200 {
            let m = 0.5 * (a + b);
            if excess(m, new)?.0.signum() == sign_a {
                a = m;
            } else {
                b = m;
            }
            if (b - a).abs() <= 1e-15 * (1.0 + a.abs()) {
                break;
            }
        }
        Ok(0.5 * (a + b))
    }
}

impl InterfaceLaw for SeriesWithFootprint {
    fn name(&self) -> &str {
        self.inner.name()
    }
    fn kind(&self) -> LawKind {
        self.inner.kind()
    }
    fn n_state(&self) -> usize {
        self.inner.n_state() + N_OWN
    }
    fn initialize_state(&self, state: &mut [f64]) {
        let ns = self.inner.n_state();
        self.inner.initialize_state(&mut state[..ns]);
        state[ns + LAW_GAP] = f64::NAN;
        state[ns + SLIDER] = 0.0;
        state[ns + SLIDER_WORK] = 0.0;
        state[ns + COMPLIANCE] = self.local.compliance;
    }
    fn state_names(&self) -> Vec<String> {
        let mut names = self.inner.state_names();
        names.extend(
            [LAW_GAP_FIELD, "footprint_indentation", PLASTIC_WORK_STATE, "footprint_compliance"].map(String::from),
        );
        names
    }
    /// F = f(x) with x = g + c F + s (see the module documentation).
    fn evaluate(&self, gap: f64, committed: &[f64], trial: &mut [f64]) -> Result<LawResponse, LawError> {
        let ns = self.inner.n_state();
        let (old, old_own) = committed.split_at(ns);
        let (new, new_own) = trial.split_at_mut(ns);
        let (s, c) = (old_own[SLIDER], old_own[COMPLIANCE]);
        let x0 = if old_own[LAW_GAP].is_finite() { old_own[LAW_GAP] } else { gap + s };
        let x = self.elastic_gap((gap, s, c), x0, old, new)?;
        let r = self.law(x, old, new)?;
        let limit = self.local.limit_force;
        new_own.copy_from_slice(old_own);
        new_own[LAW_GAP] = x;
        if r.value.abs() <= limit {
            let tangent = r.tangent / (1.0 - c * r.tangent);
            return Ok(LawResponse { tangent, ..r });
        }
        let force = limit.copysign(r.value);
        let x = self.plastic_gap(force, x0, x, old, new)?;
        let r = self.law(x, old, new)?;
        let slider = x - gap - c * force;
        new_own[LAW_GAP] = x;
        new_own[SLIDER] = slider;
        new_own[SLIDER_WORK] = old_own[SLIDER_WORK] + limit * (slider - s).abs();
        Ok(LawResponse { value: force, tangent: 0.0, ..r })
    }
}

#[cfg(test)]
mod tests;
