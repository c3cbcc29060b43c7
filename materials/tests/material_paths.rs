//! J2 material-point paths against closed forms (small strain):
//! * uniaxial stress beyond yield: sigma = Y + E H_t/(E + H_t) (eps - Y/E), with plastic modulus
//!   H_t = H (isotropic) or H_k (kinematic); perfectly plastic: sigma = Y;
//! * pure shear: tau = G gamma up to Y / sqrt 3, then constant (perfect plasticity);
//! * reverse loading: kinematic hardening re-yields at sigma_max - 2 Y (Bauschinger),
//!   isotropic at -(Y + H eqps).
//! Lateral stresses are driven to zero by Newton on the lateral strains with the material's own
//! tangent (a mixed stress/strain-controlled driver).

use stiction_core::material::Material;
use stiction_materials::J2Plasticity;

const E: f64 = 200.0;
const NU: f64 = 0.3;
const Y: f64 = 0.25;

/// Uniaxial stress path in x: returns sigma_xx at each axial strain.
fn uniaxial(m: &J2Plasticity, path: &[f64]) -> Vec<f64> {
    let mut state = vec![0.0; m.n_state()];
    let mut lateral = 0.0;
    let mut out = Vec::new();
    for &e in path {
        let mut trial = vec![0.0; m.n_state()];
        let mut s = [0.0; 6];
        let mut c = [[0.0; 6]; 6];
        for _ in 0..50 {
            let strain = [e, lateral, lateral, 0.0, 0.0, 0.0];
            m.update(&strain, &state, &mut trial, &mut s, &mut c).unwrap();
            if s[1].abs() < 1e-13 * E {
                break;
            }
            // d s_yy / d lateral = C11 + C12 (both lateral strains move together)
            lateral -= s[1] / (c[1][1] + c[1][2]);
        }
        assert!(s[1].abs() < 1e-10 && s[2].abs() < 1e-10, "lateral stress not zero: {s:?}");
        state = trial;
        out.push(s[0]);
    }
    out
}

fn linspace(a: f64, b: f64, n: usize) -> Vec<f64> {
    (0..=n).map(|i| a + (b - a) * i as f64 / n as f64).collect()
}

#[test]
fn uniaxial_tension_perfect_and_hardening() {
    let ey = Y / E;
    let path = linspace(0.0, 5.0 * ey, 40);
    for (h, hk) in [(0.0, 0.0), (20.0, 0.0), (0.0, 20.0)] {
        let m = J2Plasticity::new("m", E, NU, Y, h, hk).unwrap();
        let s = uniaxial(&m, &path);
        let ht: f64 = h + hk;
        for (e, sig) in path.iter().zip(&s) {
            let exact = if *e <= ey { E * e } else { Y + E * ht / (E + ht) * (e - ey) };
            assert!((sig - exact).abs() < 1e-9 * Y, "H={h} Hk={hk} eps={e}: {sig} vs {exact}");
        }
    }
}

#[test]
fn pure_shear_saturates_at_the_shear_yield_stress() {
    let m = J2Plasticity::new("m", E, NU, Y, 0.0, 0.0).unwrap();
    let g = E / (2.0 * (1.0 + NU));
    let gamma_y = Y / 3f64.sqrt() / g;
    let mut state = vec![0.0; m.n_state()];
    for gamma in linspace(0.0, 4.0 * gamma_y, 20) {
        let mut trial = vec![0.0; m.n_state()];
        let mut s = [0.0; 6];
        let mut c = [[0.0; 6]; 6];
        m.update(&[0.0, 0.0, 0.0, gamma, 0.0, 0.0], &state, &mut trial, &mut s, &mut c).unwrap();
        state = trial;
        let exact = (g * gamma).min(Y / 3f64.sqrt());
        assert!((s[3] - exact).abs() < 1e-12, "gamma {gamma}: {} vs {exact}", s[3]);
        assert!(s[0].abs() < 1e-12 && s[1].abs() < 1e-12, "normal stresses in pure shear: {s:?}");
    }
}

#[test]
fn reverse_loading_shows_the_bauschinger_effect_with_kinematic_hardening() {
    let ey = Y / E;
    let hk = 30.0;
    // load to 4 eps_y, unload and compress to -4 eps_y
    let mut path = linspace(0.0, 4.0 * ey, 40);
    path.extend(linspace(4.0 * ey, -4.0 * ey, 400).into_iter().skip(1));
    let kin = J2Plasticity::new("kin", E, NU, Y, 0.0, hk).unwrap();
    let iso = J2Plasticity::new("iso", E, NU, Y, hk, 0.0).unwrap();
    let sk = uniaxial(&kin, &path);
    let si = uniaxial(&iso, &path);
    let s_max = Y + E * hk / (E + hk) * (4.0 * ey - ey);
    assert!((sk[40] - s_max).abs() < 1e-9 && (si[40] - s_max).abs() < 1e-9);
    // first strain after the peak where the response leaves the elastic unloading line
    let reyield = |s: &[f64]| -> f64 {
        for i in 41..path.len() {
            let elastic = s_max + E * (path[i] - path[40]);
            if (s[i] - elastic).abs() > 1e-9 {
                return s[i - 1];
            }
        }
        f64::NAN
    };
    let step = E * (path[41] - path[40]).abs();
    let (rk, ri) = (reyield(&sk), reyield(&si));
    println!(
        "peak {s_max:.4}; re-yield: kinematic {rk:.4} (closed form {:.4}), isotropic {ri:.4} (closed form {:.4})",
        s_max - 2.0 * Y,
        -s_max
    );
    assert!((rk - (s_max - 2.0 * Y)).abs() <= step, "kinematic re-yield {rk}");
    assert!((ri + s_max).abs() <= step, "isotropic re-yield {ri}");
}

#[test]
fn invalid_parameters_name_the_key() {
    let e = J2Plasticity::new("ru", 410.0, 0.3, 0.0, 0.0, 0.0).unwrap_err().to_string();
    assert!(e.contains("yield_stress") && e.contains("ru"), "{e}");
    let e = J2Plasticity::new("ru", 410.0, 0.3, 3.42, -1000.0, 0.0).unwrap_err().to_string();
    assert!(e.contains("isotropic_hardening"), "{e}");
    let e = J2Plasticity::new("ru", 410.0, 0.6, 3.42, 0.0, 0.0).unwrap_err().to_string();
    assert!(e.contains("poissons_ratio"), "{e}");
}
