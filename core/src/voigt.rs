//! Voigt notation used everywhere in Stiction.
//!
//! Stress `[s_xx, s_yy, s_zz, s_xy, s_yz, s_zx]`; strain `[e_xx, e_yy, e_zz, g_xy, g_yz, g_zx]` with
//! engineering shear strains `g = 2 e`. In axisymmetric analyses x = r, y = z and the third
//! component is the hoop direction: `[rr, zz, tt, rz, 0, 0]`.

/// Stress vector in Voigt order.
pub type Stress = [f64; 6];
/// Strain vector in Voigt order (engineering shears).
pub type Strain = [f64; 6];
/// Material tangent d(stress)/d(strain).
pub type Tangent = [[f64; 6]; 6];

/// von Mises equivalent stress: sqrt(3/2 s:s) with s the deviator.
pub fn von_mises(s: &Stress) -> f64 {
    let p = (s[0] + s[1] + s[2]) / 3.0;
    let (a, b, c) = (s[0] - p, s[1] - p, s[2] - p);
    (1.5 * (a * a + b * b + c * c + 2.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]))).sqrt()
}

/// Isotropic linear-elastic tangent from Young's modulus and Poisson's ratio.
pub fn isotropic_elasticity(e: f64, nu: f64) -> Tangent {
    let lambda = e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
    let mu = e / (2.0 * (1.0 + nu));
    let mut c = [[0.0; 6]; 6];
    for i in 0..3 {
        for j in 0..3 {
            c[i][j] = lambda;
        }
        c[i][i] += 2.0 * mu;
        c[i + 3][i + 3] = mu;
    }
    c
}
