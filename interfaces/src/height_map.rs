//! Measured or synthetic rough surfaces as height maps: a regular grid of heights z(x, y), read
//! from Gwyddion Simple Field files ([`gsf`]) or plain text ([`text`]), made by the
//! random-phase spectral method ([`generate`]), and analysed for their spectrum ([`spectrum`])
//! and their summits ([`summits`]), the asperities of a Greenwood-Williamson model.
//!
//! A map knows its pixel size and its units, never the case's: the caller converts.

pub mod generate;
pub mod gsf;
pub mod spectrum;
pub mod summits;
pub mod text;

use std::path::PathBuf;

/// A regular grid of heights: `nx` x `ny` pixels of size `dx` x `dy`, row by row (y outer, x
/// inner), with the units of the lengths in the plane and of the heights as the file gave them.
#[derive(Debug, Clone, PartialEq)]
pub struct HeightMap {
    pub nx: usize,
    pub ny: usize,
    pub dx: f64,
    pub dy: f64,
    pub z: Vec<f64>,
    pub xy_unit: String,
    pub z_unit: String,
}

/// Why a height map could not be read or written: the file and what is wrong.
#[derive(Debug, thiserror::Error)]
pub enum HeightMapError {
    #[error("height map '{}': {source}", path.display())]
    Io { path: PathBuf, source: std::io::Error },
    #[error("height map '{}': {what}", path.display())]
    Format { path: PathBuf, what: String },
}

impl HeightMap {
    /// A map of `z` (row by row) after checking its size, pixel sizes and heights; `what`
    /// names the map in errors.
    pub fn new(
        (nx, ny): (usize, usize),
        (dx, dy): (f64, f64),
        z: Vec<f64>,
        (xy_unit, z_unit): (&str, &str),
    ) -> Result<Self, String> {
        if nx < 3 || ny < 3 {
            return Err(format!("{nx} x {ny} pixels: a map needs at least 3 x 3"));
        }
        if z.len() != nx * ny {
            return Err(format!("{} heights for {nx} x {ny} pixels", z.len()));
        }
        for (name, d) in [("x", dx), ("y", dy)] {
            if !(d > 0.0 && d.is_finite()) {
                return Err(format!("the pixel size along {name} is {d}: expected a positive number"));
            }
        }
        if let Some(k) = z.iter().position(|h| !h.is_finite()) {
            return Err(format!("the height at pixel (x {}, y {}) is {}: expected a number", k % nx, k / nx, z[k]));
        }
        Ok(Self { nx, ny, dx, dy, z, xy_unit: xy_unit.into(), z_unit: z_unit.into() })
    }

    /// The height at pixel column `i`, row `j`.
    pub fn at(&self, i: usize, j: usize) -> f64 {
        self.z[j * self.nx + i]
    }

    /// The extent along x and y.
    pub fn size(&self) -> (f64, f64) {
        (self.nx as f64 * self.dx, self.ny as f64 * self.dy)
    }

    pub fn mean(&self) -> f64 {
        self.z.iter().sum::<f64>() / self.z.len() as f64
    }

    /// Root mean square of the height about the mean.
    pub fn rms_height(&self) -> f64 {
        let mean = self.mean();
        (self.z.iter().map(|h| (h - mean).powi(2)).sum::<f64>() / self.z.len() as f64).sqrt()
    }

    /// Root mean square of the slope |grad z| by central differences over the interior pixels
    /// (heights and lengths in the same unit).
    pub fn rms_slope(&self) -> f64 {
        let (mut sum, mut count) = (0.0, 0usize);
        for j in 1..self.ny - 1 {
            for i in 1..self.nx - 1 {
                let gx = (self.at(i + 1, j) - self.at(i - 1, j)) / (2.0 * self.dx);
                let gy = (self.at(i, j + 1) - self.at(i, j - 1)) / (2.0 * self.dy);
                sum += gx * gx + gy * gy;
                count += 1;
            }
        }
        (sum / count as f64).sqrt()
    }

    /// The map with its heights times `factor`.
    pub fn scaled(mut self, factor: f64) -> Self {
        self.z.iter_mut().for_each(|h| *h *= factor);
        self
    }
}

/// A length unit in metres: m, mm, um (or µm), nm, pm, A (or Å, angstrom); `None` for any
/// other name.
pub fn metres_per_unit(unit: &str) -> Option<f64> {
    match unit.trim() {
        "m" => Some(1.0),
        "mm" => Some(1e-3),
        "um" | "µm" | "μm" => Some(1e-6),
        "nm" => Some(1e-9),
        "pm" => Some(1e-12),
        "A" | "Å" | "angstrom" => Some(1e-10),
        _ => None,
    }
}

/// The length units [`metres_per_unit`] knows, for messages.
pub const LENGTH_UNITS: &str = "m, mm, um, nm, pm, A";

impl HeightMap {
    /// The map in other units: lengths in the plane times `in_plane`, heights times `height`.
    pub fn converted(mut self, in_plane: f64, height: f64, (xy_unit, z_unit): (&str, &str)) -> Self {
        self.dx *= in_plane;
        self.dy *= in_plane;
        self.z.iter_mut().for_each(|h| *h *= height);
        self.xy_unit = xy_unit.into();
        self.z_unit = z_unit.into();
        self
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_map_refuses_a_wrong_size_a_zero_pixel_and_a_nan_height() {
        let ok = HeightMap::new((3, 3), (1.0, 1.0), vec![0.0; 9], ("nm", "nm"));
        assert!(ok.is_ok());
        let e = HeightMap::new((3, 3), (1.0, 1.0), vec![0.0; 8], ("nm", "nm")).unwrap_err();
        assert_eq!(e, "8 heights for 3 x 3 pixels");
        let e = HeightMap::new((3, 3), (0.0, 1.0), vec![0.0; 9], ("nm", "nm")).unwrap_err();
        assert!(e.contains("pixel size along x is 0"), "{e}");
        let mut z = vec![0.0; 9];
        z[5] = f64::NAN;
        let e = HeightMap::new((3, 3), (1.0, 1.0), z, ("nm", "nm")).unwrap_err();
        assert!(e.contains("pixel (x 2, y 1) is NaN"), "{e}");
    }

    /// A generated surface, written as `.gsf` and read back, gives the generator's rms height
    /// and, from its spectrum's slope over wavelengths between the cutoff and the roll-off
    /// (with a margin of 2 and 2: 8 pixels to L / 8; no window: the map is periodic), its Hurst
    /// exponent, within 5%.
    #[test]
    fn a_generated_surface_read_back_recovers_its_rms_height_and_hurst_exponent() {
        for (hurst, seed) in [(0.8, 1), (0.5, 2), (0.3, 3)] {
            let spec = generate::SelfAffine {
                hurst,
                amplitude: generate::Amplitude::RmsHeight(1.5),
                size: 1024.0,
                pixels: 512,
                rolloff: 256.0,
                cutoff: 8.0,
                seed,
                unit: "nm".into(),
            };
            let map = gsf::parse(&gsf::to_bytes(&generate::generate(&spec).unwrap(), "test")).unwrap();
            assert!((map.rms_height() / 1.5 - 1.0).abs() < 0.05, "H = {hurst}: rms {}", map.rms_height());
            let fit = spectrum::hurst_exponent(&map, (16.0, 128.0), spectrum::Window::None).unwrap();
            let (measured, rings) = (fit.hurst, fit.rings);
            assert!(rings >= 20, "{rings} rings");
            assert!(fit.standard_error < 0.01, "{fit:?}");
            assert!((measured / hurst - 1.0).abs() < 0.05, "H = {hurst}: measured {measured}");
        }
    }

    /// z = a x: rms slope a; heights uniform over [0, a (n - 1) dx]: rms (n^2 - 1)^(1/2) a dx / sqrt 12.
    #[test]
    fn rms_height_and_slope_of_a_ramp() {
        let (n, a, dx) = (11usize, 0.5, 2.0);
        let z = (0..n * n).map(|k| a * (k % n) as f64 * dx).collect();
        let map = HeightMap::new((n, n), (dx, dx), z, ("nm", "nm")).unwrap();
        assert!((map.rms_slope() - a).abs() < 1e-12);
        let expected = ((n * n - 1) as f64).sqrt() * a * dx / 12f64.sqrt();
        assert!((map.rms_height() - expected).abs() < 1e-12, "{} against {expected}", map.rms_height());
    }
}
