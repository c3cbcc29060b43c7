//! A documented SURROGATE of the Ru nano-asperity force-distance behaviour, used to generate
//! the default calibration tables because the reference paper's MD data are not public.
//! It is not molecular dynamics. Every number below is our estimate from the orders of
//! magnitude in shared/spec/ru-rough-sphere.md, chosen to honour what the paper states:
//! loading nearly the same for all w, starting at a slightly negative distance with a small
//! attraction; strong hysteresis; unloading depending on the maximum distance and on w;
//! single-asperity pull-off at most ~400 nN (w = 6, largest maximum); plastic stretching before
//! separation, more for larger w.
//!
//! Loading (d in nm, forces in nN, areas in nm^2):
//!   F_L(d) = -f0(w) + P tanh((d - d0)/l) + k (d - d0), A_L(d) = A_b tanh((d - d0)/l_A),
//!   d0 = -0.25, f0 = 1 + 0.5 w, P = 250, l = 0.5, k = 50, A_b = 12.2 (the base area), l_A = 0.4.
//!   (P ~ flow stress ~20 GPa x base area; F ~ 360 nN at d = 2 nm.)
//! Unloading from the maximum m, s = (d - e)/(m - e) in [0, 1]:
//!   F_U = F_L(m) s^3 - P_po 6.75 s (1 - s)^2,  A_U = A_L(m) s (2 - s),
//!   separation e = d0 - (0.15 + 0.12 w)(0.4 + 0.6 A_L(m)/A_b) (the neck stretches),
//!   P_po = P_w(w) (A_L(m)/A_b)^1.5 with P_w = 60, 120, 400 nN at w = 1, 3, 6 (linear between).
//! The 6.75 s (1 - s)^2 bump peaks at 1 for s = 1/3.
//!
//! The free parameters ([`Surrogate`]): the loading scale P, length l and stiffness k, the
//! pull-off scale P_w, and a stretch factor multiplying the neck's stretch (0.15 + 0.12 w). The
//! defaults are the numbers above; the `ru-asperity` law takes them as parameters with a config
//! file of format [`FORMAT`], so that a case (and `stiction fit`) can set them.

/// The config-file format that asks the law to build its calibration from the surrogate (its
/// parameters from the law's `surrogate_*` parameters).
pub const FORMAT: &str = "stiction-asperity-surrogate-1";

/// Maxima at which unloading branches are tabulated (nm).
pub const MAXIMA: [f64; 4] = [0.5, 1.0, 1.5, 2.0];
const D0: f64 = -0.25;
/// Defaults of the free parameters.
pub const LOADING_SCALE: f64 = 250.0;
pub const LOADING_LENGTH: f64 = 0.5;
pub const STIFFNESS: f64 = 50.0;
const AB: f64 = 12.2;
const LA: f64 = 0.4;

/// P_w by w: 60, 120, 400 nN at w = 1, 3, 6 J/m^2, linear between, proportional to w outside.
pub fn pull_off_scale(w: f64) -> f64 {
    let table = [(1.0, 60.0), (3.0, 120.0), (6.0, 400.0)];
    if w <= table[0].0 {
        return table[0].1 * w / table[0].0;
    }
    for p in table.windows(2) {
        if w <= p[1].0 {
            return p[0].1 + (p[1].1 - p[0].1) * (w - p[0].0) / (p[1].0 - p[0].0);
        }
    }
    table[2].1 * w / table[2].0
}

/// The surrogate's free parameters (nm, nN).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Surrogate {
    /// w (J/m^2): the loading's small attraction f0 = 1 + 0.5 w and the stretch.
    pub work_of_adhesion: f64,
    /// P (nN).
    pub loading_scale: f64,
    /// l (nm).
    pub loading_length: f64,
    /// k (nN/nm).
    pub stiffness: f64,
    /// P_w (nN).
    pub pull_off_scale: f64,
    /// Multiplies the neck's stretch (0.15 + 0.12 w).
    pub stretch: f64,
}

impl Surrogate {
    /// The documented surrogate for w: every parameter at its default.
    pub fn for_work_of_adhesion(w: f64) -> Self {
        Self {
            work_of_adhesion: w,
            loading_scale: LOADING_SCALE,
            loading_length: LOADING_LENGTH,
            stiffness: STIFFNESS,
            pull_off_scale: pull_off_scale(w),
            stretch: 1.0,
        }
    }

    pub fn loading_force(&self, d: f64) -> f64 {
        -(1.0 + 0.5 * self.work_of_adhesion)
            + self.loading_scale * ((d - D0) / self.loading_length).tanh()
            + self.stiffness * (d - D0)
    }

    pub fn separation(&self, m: f64) -> f64 {
        D0 - self.stretch * (0.15 + 0.12 * self.work_of_adhesion) * (0.4 + 0.6 * loading_area(m) / AB)
    }

    pub fn unloading(&self, m: f64, d: f64) -> (f64, f64) {
        let e = self.separation(m);
        let s = (d - e) / (m - e);
        let ppo = self.pull_off_scale * (loading_area(m) / AB).powf(1.5);
        (self.loading_force(m) * s.powi(3) - ppo * 6.75 * s * (1.0 - s).powi(2), loading_area(m) * s * (2.0 - s))
    }

    /// The table (CSV text with metadata comments), `samples` intervals per branch.
    pub fn table(&self, samples: usize) -> String {
        let w = self.work_of_adhesion;
        let mut out = String::new();
        out.push_str(&format!("# work_of_adhesion: {w}\n"));
        let defaults = *self == Self::for_work_of_adhesion(w);
        let varied = if defaults {
            String::new()
        } else {
            format!(
                " with P = {} nN, l = {} nm, k = {} nN/nm, P_w = {} nN, stretch x {}",
                self.loading_scale, self.loading_length, self.stiffness, self.pull_off_scale, self.stretch
            )
        };
        out.push_str(&format!(
            "# description: SURROGATE Ru nano-asperity force/area-distance table for w = {w} J/m^2{varied} (not molecular dynamics)\n"
        ));
        out.push_str("# provenance: stiction surrogate-table (plugins/ru-asperity/src/surrogate.rs); a documented surrogate, NOT MD data: the reference paper's MD tables are not public\n");
        out.push_str("distance,force,area,branch,max_distance\n");
        let d_end = MAXIMA[MAXIMA.len() - 1];
        for i in 0..=samples {
            let d = D0 + (d_end - D0) * i as f64 / samples as f64;
            out.push_str(&format!("{d:.6},{:.6},{:.6},loading,0\n", self.loading_force(d), loading_area(d)));
        }
        for m in MAXIMA {
            let e = self.separation(m);
            for i in 0..=samples {
                let d = m - (m - e) * i as f64 / samples as f64;
                let (f, a) = self.unloading(m, d);
                out.push_str(&format!("{d:.6},{f:.6},{a:.6},unloading,{m}\n"));
            }
        }
        out
    }

    /// The calibration the law uses: the table fitted as `stiction calibrate` does (4th-order
    /// loading, 5th-order unloading polynomials, 60 samples per branch).
    pub fn calibration(&self) -> Result<crate::calibration::Calibration, String> {
        let table = crate::fit::parse_table(&self.table(60))?;
        crate::fit::fit(&table, 4, 5)
    }
}

pub fn loading_area(d: f64) -> f64 {
    AB * ((d - D0) / LA).tanh()
}

/// The documented surrogate's loading force for w (every parameter at its default).
pub fn loading_force(w: f64, d: f64) -> f64 {
    Surrogate::for_work_of_adhesion(w).loading_force(d)
}

/// The documented surrogate's table for w (CSV text with metadata comments).
pub fn table(w: f64, samples: usize) -> String {
    Surrogate::for_work_of_adhesion(w).table(samples)
}
