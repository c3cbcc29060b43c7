//! Summits of a height map, the asperities of a Greenwood-Williamson model: pixels higher than
//! their eight neighbours (the 8-neighbour rule), above a height threshold (from the mean
//! plane's level, the map's mean), at least a minimum spacing apart (the higher kept). Each
//! summit's radius is 1 / kappa with kappa = -(z_xx + z_yy) / 2 its mean curvature by central
//! differences, the summit curvature of Greenwood's analysis of profiles and maps; at a pixel
//! higher than its neighbours both second differences are negative.
//!
//! The statistics: summit density eta (summits per area of the interior pixels), rms height
//! sigma of the map, mean and standard deviation sigma_s of the summit heights, the mean radius
//! R (1 / mean curvature), and the product eta sigma_s R, which McCool (Wear 107 (1986) 37)
//! found near 0.019 on measured surfaces (a check of the summit identification's scale).

use super::HeightMap;

/// One summit: its position (from the map's corner), height (from the map's mean) and radius.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Summit {
    pub x: f64,
    pub y: f64,
    pub height: f64,
    pub radius: f64,
}

/// How summits are picked.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SummitRule {
    /// Summits lower than this above the mean are left out.
    pub threshold: f64,
    /// Of two summits closer than this, the lower is left out.
    pub min_spacing: f64,
}

/// The statistics of a map's summits (lengths and heights in the map's units).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct SummitStatistics {
    pub summits: usize,
    /// Per unit area.
    pub density: f64,
    pub rms_height: f64,
    pub rms_slope: f64,
    pub mean_summit_height: f64,
    pub summit_height_std: f64,
    /// 1 / mean curvature.
    pub mean_radius: f64,
    /// density x summit_height_std x mean_radius (McCool's 0.019).
    pub density_std_radius: f64,
}

/// The summits of `map` by `rule`, highest first.
pub fn find(map: &HeightMap, rule: SummitRule) -> Vec<Summit> {
    let mean = map.mean();
    let mut candidates = Vec::new();
    for j in 1..map.ny - 1 {
        for i in 1..map.nx - 1 {
            let z = map.at(i, j);
            let higher = (-1i64..=1).all(|b| {
                (-1i64..=1).all(|a| (a == 0 && b == 0) || z > map.at((i as i64 + a) as usize, (j as i64 + b) as usize))
            });
            if !higher || z - mean < rule.threshold {
                continue;
            }
            let zxx = (map.at(i + 1, j) - 2.0 * z + map.at(i - 1, j)) / (map.dx * map.dx);
            let zyy = (map.at(i, j + 1) - 2.0 * z + map.at(i, j - 1)) / (map.dy * map.dy);
            let curvature = -(zxx + zyy) / 2.0;
            candidates.push(Summit {
                x: i as f64 * map.dx,
                y: j as f64 * map.dy,
                height: z - mean,
                radius: 1.0 / curvature,
            });
        }
    }
    candidates.sort_by(|a, b| b.height.total_cmp(&a.height));
    if rule.min_spacing <= 0.0 {
        return candidates;
    }
    // keep the higher of two too close: a grid of cells of the spacing's size
    let cell = rule.min_spacing;
    let key = |s: &Summit| ((s.x / cell).floor() as i64, (s.y / cell).floor() as i64);
    let mut kept: std::collections::HashMap<(i64, i64), Vec<Summit>> = std::collections::HashMap::new();
    let mut out = Vec::new();
    for s in candidates {
        let (cx, cy) = key(&s);
        let near = (-1..=1).any(|a| {
            (-1..=1).any(|b| {
                kept.get(&(cx + a, cy + b))
                    .is_some_and(|v| v.iter().any(|o| (o.x - s.x).powi(2) + (o.y - s.y).powi(2) < cell * cell))
            })
        });
        if !near {
            kept.entry((cx, cy)).or_default().push(s);
            out.push(s);
        }
    }
    out
}

/// The statistics of `summits` found on `map`.
pub fn statistics(map: &HeightMap, summits: &[Summit]) -> SummitStatistics {
    let n = summits.len() as f64;
    let area = (map.nx - 2) as f64 * map.dx * (map.ny - 2) as f64 * map.dy;
    let mean_height = summits.iter().map(|s| s.height).sum::<f64>() / n;
    let std = (summits.iter().map(|s| (s.height - mean_height).powi(2)).sum::<f64>() / n).sqrt();
    let mean_curvature = summits.iter().map(|s| 1.0 / s.radius).sum::<f64>() / n;
    let density = n / area;
    SummitStatistics {
        summits: summits.len(),
        density,
        rms_height: map.rms_height(),
        rms_slope: map.rms_slope(),
        mean_summit_height: mean_height,
        summit_height_std: std,
        mean_radius: 1.0 / mean_curvature,
        density_std_radius: density * std * (1.0 / mean_curvature),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Paraboloid caps z = h - r^2 / (2 R) on a flat floor: each a summit of radius R (the
    /// second differences of a parabola are exact), at its centre.
    #[test]
    fn paraboloid_caps_are_found_with_their_radii_and_heights() {
        let (n, dx, radius) = (40usize, 0.5, 3.0);
        let caps = [(5.0, 5.0, 2.0), (15.0, 12.0, 1.0), (6.0, 14.0, 1.5)];
        let z = (0..n * n)
            .map(|k| {
                let (x, y) = ((k % n) as f64 * dx, (k / n) as f64 * dx);
                caps.iter()
                    .map(|&(cx, cy, h)| h - ((x - cx).powi(2) + (y - cy).powi(2)) / (2.0 * radius))
                    .fold(0.0, f64::max)
            })
            .collect();
        let map = HeightMap::new((n, n), (dx, dx), z, ("nm", "nm")).unwrap();
        let mean = map.mean();
        let found = find(&map, SummitRule { threshold: 0.0, min_spacing: 0.0 });
        assert_eq!(found.len(), 3, "{found:?}");
        for (s, &(cx, cy, h)) in found.iter().zip(&[caps[0], caps[2], caps[1]]) {
            assert_eq!((s.x, s.y), (cx, cy));
            assert!((s.height - (h - mean)).abs() < 1e-12);
            assert!((s.radius - radius).abs() < 1e-9, "{}", s.radius);
        }
        // the threshold leaves the lowest out; a spacing of 11 the one 9.06 from the highest
        let high = find(&map, SummitRule { threshold: 1.2 - mean, min_spacing: 0.0 });
        assert_eq!(high.len(), 2);
        let spaced = find(&map, SummitRule { threshold: 0.0, min_spacing: 11.0 });
        assert_eq!(spaced.iter().map(|s| (s.x, s.y)).collect::<Vec<_>>(), [(5.0, 5.0), (15.0, 12.0)]);
        let stats = statistics(&map, &found);
        assert!((stats.mean_radius - radius).abs() < 1e-9);
        assert!((stats.density - 3.0 / (38.0 * 0.5 * 38.0 * 0.5)).abs() < 1e-15);
    }
}
