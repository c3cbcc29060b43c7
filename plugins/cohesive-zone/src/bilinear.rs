//! Bilinear mixed-mode cohesive law with damage (Camanho & Davila 2002, NASA/TM-2002-211737).
//!
//! Opening delta = (delta_n, delta_s1, delta_s2) in the local frame; only a positive normal
//! opening damages: delta_m = sqrt(<delta_n>^2 + |delta_s|^2) is the equivalent opening and
//! B = |delta_s|^2 / delta_m^2 the mode mixity (G_shear / G_total under proportional opening;
//! B = 1 in compression).
//! * onset (quadratic stress criterion), with d_n0 = N / K and d_s0 = S / K:
//!   delta_0(B) = d_n0 d_s0 / sqrt((1 - B) d_s0^2 + B d_n0^2);
//! * propagation (Benzeggagh-Kenane): G_c(B) = G_Ic + (G_IIc - G_Ic) B^eta, and the final
//!   opening delta_f(B) = 2 G_c(B) / (K delta_0(B)), so the triangle under the traction-opening
//!   curve of a proportional opening has area G_c(B) exactly;
//! * damage d(delta_m, B) = delta_f (delta_m - delta_0) / (delta_m (delta_f - delta_0)) clipped
//!   to [0, 1], irreversible: D = max(D_committed, d);
//! * traction value_i = -(1 - D) K delta_i on the shear components and on a positive normal
//!   opening (secant unloading to the origin), value_n = -K delta_n in compression.

/// The law's constants.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bilinear {
    pub k: f64,
    pub g_1c: f64,
    pub g_2c: f64,
    pub normal_strength: f64,
    pub shear_strength: f64,
    pub eta: f64,
}

/// One evaluation: value, tangent and the damage reached.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BilinearResponse {
    pub value: [f64; 3],
    pub tangent: [[f64; 3]; 3],
    pub damage: f64,
    pub equivalent_opening: f64,
}

impl Bilinear {
    /// Onset opening delta_0(B) and its derivative d delta_0 / d B.
    pub fn onset(&self, b: f64) -> (f64, f64) {
        let (dn, ds) = (self.normal_strength / self.k, self.shear_strength / self.k);
        let q = (1.0 - b) * ds * ds + b * dn * dn;
        let d0 = dn * ds / q.sqrt();
        (d0, -0.5 * dn * ds * q.powf(-1.5) * (dn * dn - ds * ds))
    }

    /// Fracture energy G_c(B) (Benzeggagh-Kenane) and d G_c / d B.
    pub fn fracture_energy(&self, b: f64) -> (f64, f64) {
        let g = self.g_1c + (self.g_2c - self.g_1c) * b.powf(self.eta);
        let dg =
            if b > 0.0 || self.eta == 1.0 { (self.g_2c - self.g_1c) * self.eta * b.powf(self.eta - 1.0) } else { 0.0 };
        (g, dg)
    }

    /// Final opening delta_f(B) and d delta_f / d B.
    pub fn final_opening(&self, b: f64) -> (f64, f64) {
        let (d0, dd0) = self.onset(b);
        let (g, dg) = self.fracture_energy(b);
        let df = 2.0 * g / (self.k * d0);
        (df, 2.0 * dg / (self.k * d0) - df * dd0 / d0)
    }

    /// Checks that every mode mixity fails after its onset (delta_f > delta_0), sampling B.
    pub fn check(&self) -> Result<(), String> {
        for i in 0..=1000 {
            let b = i as f64 / 1000.0;
            let (d0, _) = self.onset(b);
            let (df, _) = self.final_opening(b);
            if !(df > d0) {
                return Err(format!(
                    "at mode mixity G_shear/G_total = {b}: the final opening {df:e} does not exceed the onset opening {d0:e}; raise the penalty above max(sigma_max^2 / (2 G_c), tau_max^2 / (2 G_IIc)) or lower the strengths"
                ));
            }
        }
        Ok(())
    }

    /// The law at opening `delta` with committed damage `damage_committed`.
    pub fn evaluate(&self, delta: [f64; 3], damage_committed: f64) -> BilinearResponse {
        let k = self.k;
        let open = delta[0].max(0.0);
        let s2 = delta[1] * delta[1] + delta[2] * delta[2];
        let dm = (open * open + s2).sqrt();
        // the damaging part of the opening
        let active = [open, delta[1], delta[2]];
        let (mut damage, mut grad) = (damage_committed, [0.0; 3]);
        if dm > 0.0 {
            let b = s2 / (dm * dm);
            let (d0, dd0) = self.onset(b);
            let (df, ddf) = self.final_opening(b);
            let trial = if dm <= d0 {
                0.0
            } else if dm >= df {
                1.0
            } else {
                df * (dm - d0) / (dm * (df - d0))
            };
            if trial > damage_committed {
                damage = trial;
                if trial < 1.0 && dm > d0 {
                    let den = dm * (df - d0) * (df - d0);
                    let dd_dm = df * d0 / (dm * dm * (df - d0));
                    let dd_d0 = df * (dm - df) / den;
                    let dd_df = -(dm - d0) * d0 / den;
                    let dd_db = dd_d0 * dd0 + dd_df * ddf;
                    // d delta_m / d delta = active / delta_m; d B / d delta = 2 shear / dm^2 - 2 B active / dm^2
                    for j in 0..3 {
                        let shear_j = if j == 0 { 0.0 } else { delta[j] };
                        let dm_j = active[j] / dm;
                        let db_j = 2.0 * shear_j / (dm * dm) - 2.0 * b * active[j] / (dm * dm);
                        grad[j] = dd_dm * dm_j + dd_db * db_j;
                    }
                }
            }
        }
        let mut value = [0.0; 3];
        let mut tangent = [[0.0; 3]; 3];
        for i in 0..3 {
            value[i] = -(1.0 - damage) * k * active[i];
            tangent[i][i] = -(1.0 - damage) * k;
            for j in 0..3 {
                tangent[i][j] += k * active[i] * grad[j];
            }
        }
        if delta[0] < 0.0 {
            // compression: penalty contact, undamaged
            value[0] = -k * delta[0];
            tangent[0][0] = -k;
        }
        BilinearResponse { value, tangent, damage, equivalent_opening: dm }
    }
}
