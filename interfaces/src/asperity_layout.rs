//! Asperity layouts: points scattered over the region of a surface that faces the flat.
//!
//! Random sequential addition in the plane normal to the flat: candidate positions uniform in
//! a disk of radius `region_radius` around the axis through the surface's lowest point, kept
//! when farther than `min_spacing` from every kept point, until density x pi region_radius^2
//! points are placed (the projected area; for a sphere of radius R the curved area is larger
//! by about (region_radius / R)^2 / 4). Heights are identical or normally distributed.
//! The same seed gives the same layout.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};

/// How to generate a layout.
#[derive(Debug, Clone, PartialEq)]
pub struct LayoutSpec {
    /// Asperities per unit area.
    pub density: f64,
    /// Radius of the region (projected on the flat).
    pub region_radius: f64,
    /// Minimum distance between asperity centres (projected).
    pub min_spacing: f64,
    /// Mean asperity height.
    pub height: f64,
    /// Standard deviation of heights (0: identical heights, as in the reference paper).
    pub height_std: f64,
    pub seed: u64,
}

/// One asperity: its position in the plane (2 coordinates along the flat) and its height.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlacedAsperity {
    pub in_plane: [f64; 2],
    pub height: f64,
}

/// The largest layout the generator makes (a guard against a mistyped density).
pub const MAX_POINTS: usize = 1_000_000;

/// Generates the layout; errors name the parameter that makes it impossible.
pub fn generate(spec: &LayoutSpec) -> Result<Vec<PlacedAsperity>, String> {
    let checks = [
        ("density", spec.density, spec.density > 0.0, "> 0"),
        ("region_radius", spec.region_radius, spec.region_radius > 0.0, "> 0"),
        ("min_spacing", spec.min_spacing, spec.min_spacing >= 0.0, ">= 0"),
        ("height", spec.height, spec.height > 0.0, "> 0"),
        ("height_std", spec.height_std, spec.height_std >= 0.0, ">= 0"),
    ];
    for (key, value, in_range, range) in checks {
        if !(value.is_finite() && in_range) {
            return Err(format!("{key} must be a finite number {range}, got {value}"));
        }
    }
    let expected = spec.density * std::f64::consts::PI * spec.region_radius.powi(2);
    if expected > MAX_POINTS as f64 {
        return Err(format!(
            "density {} over a region of radius {} asks for {expected:.3e} asperities; at most {MAX_POINTS} are generated",
            spec.density, spec.region_radius
        ));
    }
    let target = expected.round() as usize;
    if target == 0 {
        return Err(format!(
            "a region of radius {} at density {} holds no asperity (need density x pi r^2 >= 0.5)",
            spec.region_radius, spec.density
        ));
    }
    // Random sequential addition jams near a covered fraction of ~0.547 of the disk area.
    let coverage = target as f64 * std::f64::consts::PI * (spec.min_spacing / 2.0).powi(2)
        / (std::f64::consts::PI * spec.region_radius.powi(2));
    if coverage > 0.5 {
        return Err(format!(
            "min_spacing {} is too large for density {}: discs would cover {:.0}% of the region (random addition jams near 55%)",
            spec.min_spacing,
            spec.density,
            100.0 * coverage
        ));
    }
    let mut rng = ChaCha8Rng::seed_from_u64(spec.seed);
    let heights = Normal::new(spec.height, spec.height_std).map_err(|e| e.to_string())?;
    let mut placed: Vec<PlacedAsperity> = Vec::with_capacity(target);
    let mut attempts = 0usize;
    while placed.len() < target {
        attempts += 1;
        if attempts > 2000 * target {
            return Err(format!(
                "could place only {} of {target} asperities with min_spacing {}",
                placed.len(),
                spec.min_spacing
            ));
        }
        let r = spec.region_radius * rng.random::<f64>().sqrt();
        let phi = 2.0 * std::f64::consts::PI * rng.random::<f64>();
        let p = [r * phi.cos(), r * phi.sin()];
        let d2 = spec.min_spacing * spec.min_spacing;
        if placed.iter().any(|q| (q.in_plane[0] - p[0]).powi(2) + (q.in_plane[1] - p[1]).powi(2) < d2) {
            continue;
        }
        let h = if spec.height_std > 0.0 { heights.sample(&mut rng).max(0.0) } else { spec.height };
        placed.push(PlacedAsperity { in_plane: p, height: h });
    }
    Ok(placed)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn paper() -> LayoutSpec {
        // 7,900 per um^2, region radius 117.6 nm (1.5 x the max nominal contact area).
        LayoutSpec { density: 0.0079, region_radius: 117.6, min_spacing: 3.5, height: 2.786, height_std: 0.0, seed: 7 }
    }

    #[test]
    fn the_paper_layout_has_about_340_asperities_with_the_minimum_spacing() {
        let a = generate(&paper()).unwrap();
        assert_eq!(a.len(), (0.0079 * std::f64::consts::PI * 117.6f64.powi(2)).round() as usize);
        assert!((a.len() as f64 - 343.0).abs() < 2.0, "{}", a.len());
        for (i, p) in a.iter().enumerate() {
            assert!(p.in_plane[0].hypot(p.in_plane[1]) <= 117.6);
            for q in &a[i + 1..] {
                assert!((p.in_plane[0] - q.in_plane[0]).hypot(p.in_plane[1] - q.in_plane[1]) >= 3.5);
            }
        }
        assert_eq!(generate(&paper()).unwrap(), a, "same seed, same layout");
        assert_ne!(generate(&LayoutSpec { seed: 8, ..paper() }).unwrap(), a);
    }

    #[test]
    fn impossible_layouts_are_refused_with_the_reason() {
        let e = generate(&LayoutSpec { min_spacing: 12.0, ..paper() }).unwrap_err();
        assert!(e.contains("min_spacing"), "{e}");
        let e = generate(&LayoutSpec { region_radius: 1.0, ..paper() }).unwrap_err();
        assert!(e.contains("holds no asperity"), "{e}");
    }
}
