//! Small-strain J2 plasticity, radial return (Simo & Hughes, Computational Inelasticity, 3.3).
//!
//! Yield: f = ||xi|| - sqrt(2/3) (sigma_y + H eqps), xi = dev(sigma) - alpha.
//! Flow: d eps_p = dgamma n, n = xi / ||xi||; d eqps = sqrt(2/3) dgamma;
//! kinematic (Prager): d alpha = (2/3) H_k dgamma n.
//! Return: dgamma = f_trial / (2 mu + (2/3)(H + H_k)).
//! Consistent tangent:
//! C_ep = C - 2 mu / (1 + (H + H_k)/(3 mu)) n x n - 2 mu (2 mu dgamma / ||xi_trial||) (I_dev - n x n).
//!
//! An optional tangent-only hardening H_t (`with_tangent_hardening`) replaces H + H_k by
//! H + H_k + H_t in the n x n term of the tangent alone: stresses and states stay those of H and
//! H_k, so the converged solution does not change, but the tangent of a perfectly plastic
//! point keeps the stiffness 2 mu (H_t/3mu)/(1 + H_t/3mu) along n instead of losing rank there.
//! Newton then converges linearly, not quadratically, at flowing points; it is meant for
//! perfectly plastic necks at their limit load, where the exact tangent is singular and Newton
//! cycles.
//!
//! The stabilized twin ([`Material::stabilized`]), which a solver switches to where Newton fails
//! on the consistent tangent, is this law with H + H_k + H_t raised to
//! [`STABILIZING_HARDENING_FRACTION`] E in the tangent; a law that hardens at least that much
//! has none.
//!
//! State per point (15 numbers): plastic strain (6, engineering shears), back stress (6),
//! equivalent plastic strain, plastic dissipation density (integral sigma : d eps_p), and a flag
//! that is 1 when the last update yielded.

use crate::error::MaterialsError;
use crate::linear_elastic::check_elastic;
use std::sync::Arc;
use stiction_core::material::{Material, MaterialError};
use stiction_core::voigt::{Strain, Stress, Tangent, isotropic_elasticity};

/// The tangent hardening H + H_k + H_t of the stabilized twin, as a fraction of E. With E/100
/// a flowing point keeps about 0.9% of its elastic stiffness along n. Measured on the 4 nm
/// adhesive necks of the Ru spheres (docs/ru-rough-sphere.md): switching to E/100 where Newton
/// fails completes the 3D w = 3 cycle on which the consistent tangent alone stalls, while a
/// fixed E/10 stopped the 3D w = 6 quarter at a snap the consistent tangent passed.
pub const STABILIZING_HARDENING_FRACTION: f64 = 0.01;

const EPS_P: usize = 0;
const BACK: usize = 6;
const EQPS: usize = 12;
const DISS: usize = 13;
const ACTIVE: usize = 14;

#[derive(Debug, Clone)]
pub struct J2Plasticity {
    name: String,
    youngs_modulus: f64,
    shear_modulus: f64,
    yield_stress: f64,
    isotropic_hardening: f64,
    kinematic_hardening: f64,
    tangent_hardening: f64,
    c: Tangent,
}

impl J2Plasticity {
    /// E, nu, initial yield stress, linear isotropic hardening modulus H, linear kinematic
    /// hardening modulus H_k (both 0: perfectly plastic).
    pub fn new(
        name: impl Into<String>,
        youngs_modulus: f64,
        poissons_ratio: f64,
        yield_stress: f64,
        isotropic_hardening: f64,
        kinematic_hardening: f64,
    ) -> Result<Self, MaterialsError> {
        let name = name.into();
        check_elastic(&name, youngs_modulus, poissons_ratio)?;
        if !(yield_stress > 0.0 && yield_stress.is_finite()) {
            return Err(MaterialsError::Parameter {
                material: name,
                key: "yield_stress",
                value: yield_stress,
                expected: "a positive number",
            });
        }
        let mu = youngs_modulus / (2.0 * (1.0 + poissons_ratio));
        for (key, h) in [("isotropic_hardening", isotropic_hardening), ("kinematic_hardening", kinematic_hardening)] {
            if !h.is_finite() || h <= -3.0 * mu / 2.0 {
                return Err(MaterialsError::Parameter {
                    material: name,
                    key,
                    value: h,
                    expected: "a finite modulus above -3 G / 2 (softening beyond that makes the tangent singular)",
                });
            }
        }
        if 2.0 * mu + 2.0 / 3.0 * (isotropic_hardening + kinematic_hardening) <= 0.0 {
            return Err(MaterialsError::Parameter {
                material: name,
                key: "isotropic_hardening",
                value: isotropic_hardening,
                expected: "H + H_k > -3 G (otherwise the return-map denominator 2G + 2(H + H_k)/3 vanishes)",
            });
        }
        Ok(Self {
            name,
            youngs_modulus,
            shear_modulus: mu,
            yield_stress,
            isotropic_hardening,
            kinematic_hardening,
            tangent_hardening: 0.0,
            c: isotropic_elasticity(youngs_modulus, poissons_ratio),
        })
    }

    /// The same law with a tangent-only hardening modulus H_t >= 0 (see the module doc): the
    /// tangent's n x n coefficient becomes 2 mu / (1 + (H + H_k + H_t)/(3 mu)), the stresses do
    /// not change.
    pub fn with_tangent_hardening(mut self, tangent_hardening: f64) -> Result<Self, MaterialsError> {
        if !(tangent_hardening >= 0.0 && tangent_hardening.is_finite()) {
            return Err(MaterialsError::Parameter {
                material: self.name,
                key: "tangent_hardening",
                value: tangent_hardening,
                expected: "a finite modulus >= 0",
            });
        }
        self.tangent_hardening = tangent_hardening;
        Ok(self)
    }
}

/// Tensor norm of a stress-like Voigt vector: sqrt(s_ii s_ii + 2 s_ij s_ij (i < j)).
fn norm(s: &[f64; 6]) -> f64 {
    (s[0] * s[0] + s[1] * s[1] + s[2] * s[2] + 2.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5])).sqrt()
}

impl Material for J2Plasticity {
    fn name(&self) -> &str {
        &self.name
    }
    fn n_state(&self) -> usize {
        15
    }
    fn update(
        &self,
        strain: &Strain,
        old: &[f64],
        new: &mut [f64],
        stress: &mut Stress,
        tangent: &mut Tangent,
    ) -> Result<(), MaterialError> {
        let mu = self.shear_modulus;
        new.copy_from_slice(old);
        let mut elastic = [0.0; 6];
        for i in 0..6 {
            elastic[i] = strain[i] - old[EPS_P + i];
        }
        let mut trial = [0.0; 6];
        for i in 0..6 {
            trial[i] = (0..6).map(|j| self.c[i][j] * elastic[j]).sum();
        }
        let p = (trial[0] + trial[1] + trial[2]) / 3.0;
        let mut xi = [0.0; 6];
        for i in 0..6 {
            xi[i] = trial[i] - if i < 3 { p } else { 0.0 } - old[BACK + i];
        }
        let xi_norm = norm(&xi);
        let eqps = old[EQPS];
        let radius = (2.0f64 / 3.0).sqrt() * (self.yield_stress + self.isotropic_hardening * eqps);
        let f_trial = xi_norm - radius;
        *stress = trial;
        *tangent = self.c;
        new[ACTIVE] = 0.0;
        if f_trial <= 1e-12 * self.yield_stress {
            return Ok(());
        }
        let h_sum = self.isotropic_hardening + self.kinematic_hardening;
        let dgamma = f_trial / (2.0 * mu + 2.0 / 3.0 * h_sum);
        if !dgamma.is_finite() || dgamma < 0.0 {
            return Err(MaterialError(format!("return map produced plastic multiplier {dgamma}")));
        }
        let n: [f64; 6] = std::array::from_fn(|i| xi[i] / xi_norm);
        let mut dissipation = 0.0;
        for i in 0..6 {
            stress[i] -= 2.0 * mu * dgamma * n[i];
            new[BACK + i] += 2.0 / 3.0 * self.kinematic_hardening * dgamma * n[i];
            // engineering shear components of the plastic strain carry a factor 2
            let deps = dgamma * n[i] * if i < 3 { 1.0 } else { 2.0 };
            new[EPS_P + i] += deps;
            dissipation += stress[i] * deps;
        }
        new[EQPS] = eqps + (2.0f64 / 3.0).sqrt() * dgamma;
        new[DISS] = old[DISS] + dissipation;
        new[ACTIVE] = 1.0;
        let beta = 2.0 * mu * dgamma / xi_norm;
        let gamma_bar = 1.0 / (1.0 + (h_sum + self.tangent_hardening) / (3.0 * mu)) - beta;
        for i in 0..6 {
            for j in 0..6 {
                let idev = if i < 3 && j < 3 {
                    (if i == j { 1.0 } else { 0.0 }) - 1.0 / 3.0
                } else if i == j {
                    0.5
                } else {
                    0.0
                };
                tangent[i][j] -= 2.0 * mu * (beta * idev + gamma_bar * n[i] * n[j]);
            }
        }
        Ok(())
    }
    fn output_names(&self) -> Vec<&'static str> {
        vec!["equivalent_plastic_strain", "yielding"]
    }
    fn outputs(&self, state: &[f64], out: &mut [f64]) {
        out[0] = state[EQPS];
        out[1] = state[ACTIVE];
    }
    fn dissipation_density(&self, state: &[f64]) -> f64 {
        state[DISS]
    }
    fn stiffness_scale(&self) -> f64 {
        self.youngs_modulus
    }
    fn stabilized(&self) -> Option<Arc<dyn Material>> {
        let hardening = self.isotropic_hardening + self.kinematic_hardening;
        let target = STABILIZING_HARDENING_FRACTION * self.youngs_modulus;
        if hardening + self.tangent_hardening >= target {
            return None;
        }
        let twin = self.clone().with_tangent_hardening(target - hardening).ok()?;
        Some(Arc::new(twin))
    }
    fn flowing(&self, state: &[f64]) -> bool {
        state[ACTIVE] == 1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(m: &J2Plasticity, path: &[Strain]) -> Vec<(Stress, Tangent, Vec<f64>)> {
        let mut state = vec![0.0; m.n_state()];
        let mut out = vec![];
        for e in path {
            let mut new = vec![0.0; m.n_state()];
            let mut s = [0.0; 6];
            let mut c = [[0.0; 6]; 6];
            m.update(e, &state, &mut new, &mut s, &mut c).unwrap();
            state = new.clone();
            out.push((s, c, new));
        }
        out
    }

    /// Central differences of the stress update from the same committed state.
    fn fd_tangent(m: &J2Plasticity, old: &[f64], e: &Strain) -> Tangent {
        let h = 1e-7;
        let mut c = [[0.0; 6]; 6];
        for j in 0..6 {
            let (mut ep, mut em) = (*e, *e);
            ep[j] += h;
            em[j] -= h;
            let mut sp = [0.0; 6];
            let mut sm = [0.0; 6];
            let mut t = [[0.0; 6]; 6];
            let mut new = vec![0.0; m.n_state()];
            m.update(&ep, old, &mut new, &mut sp, &mut t).unwrap();
            m.update(&em, old, &mut new, &mut sm, &mut t).unwrap();
            for i in 0..6 {
                c[i][j] = (sp[i] - sm[i]) / (2.0 * h);
            }
        }
        c
    }

    #[test]
    fn consistent_tangent_matches_finite_differences() {
        for (h, hk) in [(0.0, 0.0), (20.0, 0.0), (0.0, 15.0), (10.0, 5.0)] {
            let m = J2Plasticity::new("ru", 410.0, 0.3, 3.42, h, hk).unwrap();
            // a committed plastic state, then a multiaxial plastic increment
            let first = [0.012, -0.004, -0.003, 0.006, 0.002, -0.001];
            let r = run(&m, &[first]);
            let old = r[0].2.clone();
            let e = [0.015, -0.002, -0.006, 0.009, -0.003, 0.004];
            let mut new = vec![0.0; 15];
            let mut s = [0.0; 6];
            let mut c = [[0.0; 6]; 6];
            m.update(&e, &old, &mut new, &mut s, &mut c).unwrap();
            assert_eq!(new[ACTIVE], 1.0, "the test increment must be plastic");
            let fd = fd_tangent(&m, &old, &e);
            let scale = 410.0;
            for i in 0..6 {
                for j in 0..6 {
                    assert!(
                        (fd[i][j] - c[i][j]).abs() < 1e-6 * scale,
                        "H={h} Hk={hk} C[{i}][{j}] {} vs fd {}",
                        c[i][j],
                        fd[i][j]
                    );
                }
            }
        }
    }

    /// The flow direction n = dev(sigma)/||dev(sigma)|| of a perfectly plastic point (no back
    /// stress) and the engineering strain d along it (shears doubled).
    fn flow_direction(stress: &Stress) -> ([f64; 6], [f64; 6]) {
        let p = (stress[0] + stress[1] + stress[2]) / 3.0;
        let dev: [f64; 6] = std::array::from_fn(|i| stress[i] - if i < 3 { p } else { 0.0 });
        let n: [f64; 6] = std::array::from_fn(|i| dev[i] / norm(&dev));
        let d: [f64; 6] = std::array::from_fn(|i| n[i] * if i < 3 { 1.0 } else { 2.0 });
        (n, d)
    }

    /// Tangent-only hardening leaves stresses and states bit for bit those of the perfectly
    /// plastic law; its tangent differs by the rank-one term 2 mu (1 - 1/(1 + H_t/(3 mu))) n x n,
    /// so along the flow direction (engineering strain d = n) the perfectly plastic tangent gives
    /// C d = 0 (the lost rank) and the stiffened one C d = 2 mu (H_t/3mu)/(1 + H_t/3mu) n.
    #[test]
    fn tangent_hardening_stiffens_the_flow_direction_only() {
        let (e_mod, nu, h_t) = (410.0, 0.3, 41.0);
        let mu = e_mod / (2.0 * (1.0 + nu));
        let perfect = J2Plasticity::new("ru", e_mod, nu, 3.42, 0.0, 0.0).unwrap();
        let stiffened = perfect.clone().with_tangent_hardening(h_t).unwrap();
        let path = [[0.012, -0.004, -0.003, 0.006, 0.002, -0.001], [0.015, -0.002, -0.006, 0.009, -0.003, 0.004]];
        let (a, b) = (run(&perfect, &path), run(&stiffened, &path));
        for ((sa, ca, state_a), (sb, cb, state_b)) in a.iter().zip(&b) {
            assert_eq!(sa, sb);
            assert_eq!(state_a, state_b);
            assert_eq!(state_a[ACTIVE], 1.0, "the path must be plastic");
            let (n, d) = flow_direction(sa);
            let k = h_t / (3.0 * mu);
            for i in 0..6 {
                let ca_d: f64 = (0..6).map(|j| ca[i][j] * d[j]).sum();
                let cb_d: f64 = (0..6).map(|j| cb[i][j] * d[j]).sum();
                assert!(ca_d.abs() < 1e-9 * e_mod, "perfectly plastic C d [{i}] = {ca_d}");
                let expected = 2.0 * mu * k / (1.0 + k) * n[i];
                assert!((cb_d - expected).abs() < 1e-9 * e_mod, "C_t d [{i}] = {cb_d}, expected {expected}");
            }
        }
        assert!(perfect.with_tangent_hardening(-1.0).is_err());
    }

    /// The stabilized twin of a perfectly plastic law is the law with a tangent hardening of
    /// E/100 (same stresses and states; along the flow direction C d = 2 mu k/(1 + k) n with
    /// k = (E/100)/(3 mu), in closed form); one that hardens by E/100 or more has none.
    #[test]
    fn the_stabilized_twin_hardens_the_tangent_to_a_hundredth_of_e() {
        let (e_mod, nu) = (410.0, 0.3);
        let mu = e_mod / (2.0 * (1.0 + nu));
        let perfect = J2Plasticity::new("ru", e_mod, nu, 3.42, 0.0, 0.0).unwrap();
        let twin = perfect.stabilized().expect("a perfectly plastic law has a stabilized twin");
        let (e1, e2) = ([0.012, -0.004, -0.003, 0.006, 0.002, -0.001], [0.015, -0.002, -0.006, 0.009, -0.003, 0.004]);
        let (mut state, mut state_twin) = (vec![0.0; 15], vec![0.0; 15]);
        for e in [e1, e2] {
            let (mut new, mut new_twin) = (vec![0.0; 15], vec![0.0; 15]);
            let (mut s, mut s_twin, mut c, mut c_twin) = ([0.0; 6], [0.0; 6], [[0.0; 6]; 6], [[0.0; 6]; 6]);
            perfect.update(&e, &state, &mut new, &mut s, &mut c).unwrap();
            twin.update(&e, &state_twin, &mut new_twin, &mut s_twin, &mut c_twin).unwrap();
            assert_eq!(s, s_twin);
            assert_eq!(new, new_twin);
            assert_eq!(new[ACTIVE], 1.0, "the path must be plastic");
            let (n, d) = flow_direction(&s);
            let k = STABILIZING_HARDENING_FRACTION * e_mod / (3.0 * mu);
            for i in 0..6 {
                let c_d: f64 = (0..6).map(|j| c_twin[i][j] * d[j]).sum();
                let expected = 2.0 * mu * k / (1.0 + k) * n[i];
                assert!((c_d - expected).abs() < 1e-9 * e_mod, "C d [{i}] = {c_d}, expected {expected}");
            }
            (state, state_twin) = (new, new_twin);
        }
        let hardening = J2Plasticity::new("ru", e_mod, nu, 3.42, 2.0, 2.1).unwrap();
        assert!(hardening.stabilized().is_none(), "H + H_k = E/100: no twin needed");
        let stiffened = perfect.with_tangent_hardening(4.1).unwrap();
        assert!(stiffened.stabilized().is_none(), "a tangent hardening of E/100 already stabilizes");
    }
}
