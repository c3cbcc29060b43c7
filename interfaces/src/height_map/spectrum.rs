//! The power spectrum of a height map and the Hurst exponent of its self-affine range.
//!
//! The map, less its mean plane and times a window ([`Window`]), is Fourier transformed;
//! |Z(q)|^2 is averaged over rings of width 2 pi / L in |q|. A measured map is not periodic:
//! without a window its edges would leak power across the spectrum, so the Hann window is the
//! default. The window mixes each mode with its neighbours, so a ring's power scatters from
//! one surface to the next (on generated surfaces with H = 0.3 to 0.8 and 512 x 512 pixels,
//! the fitted H scattered by about +-0.05 over seeds); a periodic map (a generated one) needs
//! none, and then each ring gives its spectrum exactly. Over a self-affine range the isotropic spectrum goes as
//! C(q) ~ q^(-2 (1 + H)) (Persson, J. Phys.: Condens. Matter 17 (2005) R1), so a least-squares
//! line through log C against log q over the rings in a range of wavelengths gives
//! H = -slope / 2 - 1.

use super::HeightMap;
use rustfft::FftPlanner;
use rustfft::num_complex::Complex;

/// The 2D discrete Fourier transform of `data` (`nx` x `ny`, row by row), in place: forward, or
/// inverse (unnormalized).
pub(super) fn fft2(data: &mut [Complex<f64>], nx: usize, ny: usize, inverse: bool) {
    let mut planner = FftPlanner::new();
    let (row, column) = if inverse {
        (planner.plan_fft_inverse(nx), planner.plan_fft_inverse(ny))
    } else {
        (planner.plan_fft_forward(nx), planner.plan_fft_forward(ny))
    };
    for r in data.chunks_exact_mut(nx) {
        row.process(r);
    }
    let mut buffer = vec![Complex::new(0.0, 0.0); ny];
    for i in 0..nx {
        for j in 0..ny {
            buffer[j] = data[j * nx + i];
        }
        column.process(&mut buffer);
        for j in 0..ny {
            data[j * nx + i] = buffer[j];
        }
    }
}

/// The signed wavenumber of index `k` of an `n`-point transform.
pub(super) fn signed(k: usize, n: usize) -> f64 {
    if k <= n / 2 { k as f64 } else { k as f64 - n as f64 }
}

/// One ring of the radially averaged spectrum: its mean |q| and mean power (arbitrary scale).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ring {
    pub q: f64,
    pub power: f64,
    pub modes: usize,
}

/// The window the map is multiplied by before its transform.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Window {
    /// None: for a periodic map.
    None,
    /// 0.5 - 0.5 cos(2 pi i / n) along each axis: for a measured map.
    #[default]
    Hann,
}

/// The radially averaged power spectrum of `map` (mean plane removed, times `window`).
pub fn radial_spectrum(map: &HeightMap, window: Window) -> Vec<Ring> {
    let (nx, ny) = (map.nx, map.ny);
    let plane = mean_plane(map);
    let weight = |k: usize, n: usize| match window {
        Window::None => 1.0,
        Window::Hann => 0.5 - 0.5 * (2.0 * std::f64::consts::PI * k as f64 / n as f64).cos(),
    };
    let mut data: Vec<Complex<f64>> = (0..nx * ny)
        .map(|k| {
            let (i, j) = (k % nx, k / nx);
            Complex::new((map.z[k] - plane(i, j)) * weight(i, nx) * weight(j, ny), 0.0)
        })
        .collect();
    fft2(&mut data, nx, ny, false);
    let (lx, ly) = map.size();
    let dq = 2.0 * std::f64::consts::PI / lx.max(ly);
    let n_rings = (nx.min(ny) / 2) + 1;
    let mut rings = vec![(0.0, 0.0, 0usize); n_rings];
    for j in 0..ny {
        for i in 0..nx {
            let qx = 2.0 * std::f64::consts::PI * signed(i, nx) / lx;
            let qy = 2.0 * std::f64::consts::PI * signed(j, ny) / ly;
            let q = (qx * qx + qy * qy).sqrt();
            let ring = (q / dq).round() as usize;
            if ring == 0 || ring >= n_rings {
                continue;
            }
            let r = &mut rings[ring];
            (r.0, r.1, r.2) = (r.0 + q, r.1 + data[j * nx + i].norm_sqr(), r.2 + 1);
        }
    }
    rings
        .into_iter()
        .filter(|r| r.2 > 0)
        .map(|(q, power, modes)| Ring { q: q / modes as f64, power: power / modes as f64, modes })
        .collect()
}

/// The least-squares plane through the map, as a function of the pixel indices.
fn mean_plane(map: &HeightMap) -> impl Fn(usize, usize) -> f64 {
    let (nx, ny) = (map.nx as f64, map.ny as f64);
    let (ci, cj) = ((nx - 1.0) / 2.0, (ny - 1.0) / 2.0);
    let (mut si, mut sj, mut sii, mut sjj) = (0.0, 0.0, 0.0, 0.0);
    for (k, &z) in map.z.iter().enumerate() {
        let (i, j) = ((k % map.nx) as f64 - ci, (k / map.nx) as f64 - cj);
        (si, sj, sii, sjj) = (si + i * z, sj + j * z, sii + i * i, sjj + j * j);
    }
    let (mean, a, b) = (map.mean(), si / sii, sj / sjj);
    move |i, j| mean + a * (i as f64 - ci) + b * (j as f64 - cj)
}

/// A Hurst exponent fitted to a spectrum's slope.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct HurstFit {
    pub hurst: f64,
    /// The standard error of H from the line's residuals.
    pub standard_error: f64,
    /// The rings fitted.
    pub rings: usize,
    /// The wavelengths fitted between.
    pub shortest: f64,
    pub longest: f64,
}

/// The Hurst exponent of `map` over the wavelengths between `shortest` and `longest` (in the
/// map's length unit): H = -slope / 2 - 1 of the least-squares line through log C against
/// log q over the rings in that range. None with fewer than 3 rings in the range.
pub fn hurst_exponent(map: &HeightMap, (shortest, longest): (f64, f64), window: Window) -> Option<HurstFit> {
    let two_pi = 2.0 * std::f64::consts::PI;
    let (q_min, q_max) = (two_pi / longest, two_pi / shortest);
    let points: Vec<(f64, f64)> = radial_spectrum(map, window)
        .into_iter()
        .filter(|r| r.q >= q_min && r.q <= q_max && r.power > 0.0)
        .map(|r| (r.q.ln(), r.power.ln()))
        .collect();
    if points.len() < 3 {
        return None;
    }
    let n = points.len() as f64;
    let (mx, my) = (points.iter().map(|p| p.0).sum::<f64>() / n, points.iter().map(|p| p.1).sum::<f64>() / n);
    let sxy: f64 = points.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = points.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let slope = sxy / sxx;
    let residuals: f64 = points.iter().map(|p| (p.1 - my - slope * (p.0 - mx)).powi(2)).sum();
    let slope_error = (residuals / (n - 2.0) / sxx).sqrt();
    Some(HurstFit {
        hurst: -slope / 2.0 - 1.0,
        standard_error: slope_error / 2.0,
        rings: points.len(),
        shortest,
        longest,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// z = cos(2 pi k0 x / L) cos(2 pi k0 y / L) (no mean plane): its power lies in the ring of
    /// |k| = k0 sqrt 2 and, through the window's +-1 bins, its neighbours, nowhere else.
    #[test]
    fn a_product_of_cosines_puts_its_power_in_its_ring() {
        let (n, k0) = (64usize, 5.0);
        let c = |i: usize| (2.0 * std::f64::consts::PI * k0 * i as f64 / n as f64).cos();
        let z = (0..n * n).map(|k| c(k % n) * c(k / n)).collect();
        let map = HeightMap::new((n, n), (1.0, 1.0), z, ("nm", "nm")).unwrap();
        let rings = radial_spectrum(&map, Window::Hann);
        let k_of = |r: &Ring| r.q * n as f64 / (2.0 * std::f64::consts::PI);
        let peak = rings.iter().max_by(|a, b| a.power.total_cmp(&b.power)).unwrap();
        assert!((k_of(peak) - k0 * 2f64.sqrt()).abs() < 0.6, "{peak:?}");
        let far: f64 = rings.iter().filter(|r| (k_of(r) - k0 * 2f64.sqrt()).abs() > 2.5).map(|r| r.power).sum();
        assert!(far < 1e-12 * peak.power, "{far} against {}", peak.power);
    }
}
