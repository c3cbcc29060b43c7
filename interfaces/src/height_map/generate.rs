//! Synthetic self-affine surfaces by the random-phase spectral method (e.g. Jacobs, Junge and
//! Pastewka, Surf. Topogr.: Metrol. Prop. 5 (2017) 013001): on a periodic square of side L and
//! n x n pixels, each Fourier mode q = 2 pi k / L has the amplitude sqrt(C(q)) of the isotropic
//! spectrum
//!   C(q) = C0                         for 0 < q < q_r   (the roll-off),
//!   C(q) = C0 (q / q_r)^(-2 (1 + H))  for q_r <= q <= q_s,
//!   C(q) = 0                          beyond q_s        (the short-wavelength cutoff),
//! with q_r = 2 pi / roll-off wavelength, q_s = 2 pi / cutoff wavelength, and a phase drawn at
//! random (seeded), mirrored so that the inverse transform is real. The heights are then scaled
//! to the rms height, or the rms slope, asked for.

use super::HeightMap;
use super::spectrum::{fft2, signed};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rustfft::num_complex::Complex;

/// What sets the heights' scale.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Amplitude {
    RmsHeight(f64),
    /// The rms of |grad z| by central differences ([`HeightMap::rms_slope`]).
    RmsSlope(f64),
}

/// A self-affine surface to make.
#[derive(Debug, Clone, PartialEq)]
pub struct SelfAffine {
    /// The Hurst exponent H, 0 < H < 1.
    pub hurst: f64,
    pub amplitude: Amplitude,
    /// The side L of the square.
    pub size: f64,
    /// Pixels along each side (even).
    pub pixels: usize,
    /// The roll-off wavelength (at most L).
    pub rolloff: f64,
    /// The shortest wavelength (at least two pixels).
    pub cutoff: f64,
    pub seed: u64,
    /// The unit of lengths and heights.
    pub unit: String,
}

impl SelfAffine {
    /// What is wrong with these settings, naming the setting.
    pub fn check(&self) -> Result<(), String> {
        let dx = self.size / self.pixels as f64;
        if !(self.hurst > 0.0 && self.hurst < 1.0) {
            return Err(format!("hurst = {}: expected 0 < H < 1", self.hurst));
        }
        if !(self.size > 0.0 && self.size.is_finite()) {
            return Err(format!("size = {}: expected a positive length", self.size));
        }
        if self.pixels < 8 || !self.pixels.is_multiple_of(2) {
            return Err(format!("pixels = {}: expected an even number of at least 8", self.pixels));
        }
        if !(self.cutoff >= 2.0 * dx * (1.0 - 1e-12)) {
            return Err(format!("cutoff = {}: expected at least two pixels ({})", self.cutoff, 2.0 * dx));
        }
        if !(self.rolloff > self.cutoff && self.rolloff <= self.size * (1.0 + 1e-12)) {
            return Err(format!(
                "rolloff = {}: expected a wavelength longer than the cutoff ({}) and at most the size ({})",
                self.rolloff, self.cutoff, self.size
            ));
        }
        let (name, value) = match self.amplitude {
            Amplitude::RmsHeight(h) => ("rms_height", h),
            Amplitude::RmsSlope(s) => ("rms_slope", s),
        };
        if !(value > 0.0 && value.is_finite()) {
            return Err(format!("{name} = {value}: expected a positive number"));
        }
        Ok(())
    }
}

/// The surface `spec` describes.
pub fn generate(spec: &SelfAffine) -> Result<HeightMap, String> {
    spec.check()?;
    let n = spec.pixels;
    let two_pi = 2.0 * std::f64::consts::PI;
    let (q_r, q_s) = (two_pi / spec.rolloff, two_pi / spec.cutoff);
    let amplitude = |i: usize, j: usize| {
        let q = two_pi * (signed(i, n).powi(2) + signed(j, n).powi(2)).sqrt() / spec.size;
        if q == 0.0 || q > q_s * (1.0 + 1e-12) {
            0.0
        } else if q < q_r {
            1.0
        } else {
            (q / q_r).powf(-(1.0 + spec.hurst))
        }
    };
    let mut rng = ChaCha8Rng::seed_from_u64(spec.seed);
    let mut modes = vec![Complex::new(0.0, 0.0); n * n];
    for j in 0..n {
        for i in 0..n {
            let (k, partner) = (j * n + i, ((n - j) % n) * n + (n - i) % n);
            let phase = two_pi * rng.random::<f64>();
            if partner == k {
                // its own mirror image: a real amplitude
                modes[k] = Complex::new(amplitude(i, j) * phase.cos().signum(), 0.0);
            } else if k < partner {
                let z = Complex::from_polar(amplitude(i, j), phase);
                (modes[k], modes[partner]) = (z, z.conj());
            }
        }
    }
    fft2(&mut modes, n, n, true);
    let dx = spec.size / n as f64;
    let z = modes.iter().map(|c| c.re).collect();
    let map = HeightMap::new((n, n), (dx, dx), z, (&spec.unit, &spec.unit))?;
    let factor = match spec.amplitude {
        Amplitude::RmsHeight(h) => h / map.rms_height(),
        Amplitude::RmsSlope(s) => s / map.rms_slope(),
    };
    Ok(map.scaled(factor))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec() -> SelfAffine {
        SelfAffine {
            hurst: 0.8,
            amplitude: Amplitude::RmsHeight(2.0),
            size: 256.0,
            pixels: 64,
            rolloff: 64.0,
            cutoff: 8.0,
            seed: 3,
            unit: "nm".into(),
        }
    }

    #[test]
    fn the_surface_has_the_rms_asked_for_and_the_same_seed_gives_the_same_surface() {
        let map = generate(&spec()).unwrap();
        assert!((map.rms_height() - 2.0).abs() < 1e-12);
        assert!(map.mean().abs() < 1e-12, "no q = 0 mode");
        assert_eq!(map, generate(&spec()).unwrap());
        assert_ne!(map, generate(&SelfAffine { seed: 4, ..spec() }).unwrap());
        let sloped = generate(&SelfAffine { amplitude: Amplitude::RmsSlope(0.1), ..spec() }).unwrap();
        assert!((sloped.rms_slope() - 0.1).abs() < 1e-12);
        assert_eq!((map.nx, map.dx, map.xy_unit.as_str()), (64, 4.0, "nm"));
    }

    #[test]
    fn settings_out_of_range_are_named() {
        let e = |s: SelfAffine| s.check().unwrap_err();
        assert!(e(SelfAffine { hurst: 1.0, ..spec() }).starts_with("hurst = 1"));
        assert!(e(SelfAffine { pixels: 63, ..spec() }).starts_with("pixels = 63"));
        assert!(e(SelfAffine { cutoff: 4.0, ..spec() }).starts_with("cutoff = 4: expected at least two pixels (8)"));
        assert!(e(SelfAffine { rolloff: 512.0, ..spec() }).starts_with("rolloff = 512"));
        assert!(e(SelfAffine { amplitude: Amplitude::RmsSlope(0.0), ..spec() }).starts_with("rms_slope = 0"));
    }
}
