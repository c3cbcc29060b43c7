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

/// Maxima at which unloading branches are tabulated (nm).
pub const MAXIMA: [f64; 4] = [0.5, 1.0, 1.5, 2.0];
const D0: f64 = -0.25;
const P: f64 = 250.0;
const L: f64 = 0.5;
const K: f64 = 50.0;
const AB: f64 = 12.2;
const LA: f64 = 0.4;

fn pull_off_scale(w: f64) -> f64 {
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

pub fn loading_force(w: f64, d: f64) -> f64 {
    -(1.0 + 0.5 * w) + P * ((d - D0) / L).tanh() + K * (d - D0)
}
pub fn loading_area(d: f64) -> f64 {
    AB * ((d - D0) / LA).tanh()
}
pub fn separation(w: f64, m: f64) -> f64 {
    D0 - (0.15 + 0.12 * w) * (0.4 + 0.6 * loading_area(m) / AB)
}
pub fn unloading(w: f64, m: f64, d: f64) -> (f64, f64) {
    let e = separation(w, m);
    let s = (d - e) / (m - e);
    let ppo = pull_off_scale(w) * (loading_area(m) / AB).powf(1.5);
    (loading_force(w, m) * s.powi(3) - ppo * 6.75 * s * (1.0 - s).powi(2), loading_area(m) * s * (2.0 - s))
}

/// The table (CSV text with metadata comments) for work of adhesion w (J/m^2).
pub fn table(w: f64, samples: usize) -> String {
    let mut out = String::new();
    out.push_str(&format!("# work_of_adhesion: {w}\n"));
    out.push_str(&format!(
        "# description: SURROGATE Ru nano-asperity force/area-distance table for w = {w} J/m^2 (not molecular dynamics)\n"
    ));
    out.push_str("# provenance: stiction surrogate-table (plugins/ru-asperity/src/surrogate.rs); a documented surrogate, NOT MD data: the reference paper's MD tables are not public\n");
    out.push_str("distance,force,area,branch,max_distance\n");
    let d_end = MAXIMA[MAXIMA.len() - 1];
    for i in 0..=samples {
        let d = D0 + (d_end - D0) * i as f64 / samples as f64;
        out.push_str(&format!("{d:.6},{:.6},{:.6},loading,0\n", loading_force(w, d), loading_area(d)));
    }
    for m in MAXIMA {
        let e = separation(w, m);
        for i in 0..=samples {
            let d = m - (m - e) * i as f64 / samples as f64;
            let (f, a) = unloading(w, m, d);
            out.push_str(&format!("{d:.6},{f:.6},{a:.6},unloading,{m}\n"));
        }
    }
    out
}
