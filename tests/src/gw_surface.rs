//! Greenwood-Williamson surfaces as height maps, for the validation tests: paraboloid summits of
//! one radius on a square grid, their heights the N quantiles of a Gaussian laid out so that
//! every disc around the middle holds an even sample (samples that stand for the Gaussian
//! without a random draw's scatter, in the whole map and in a sphere's contact alike).

use stiction_interfaces::height_map::HeightMap;

/// The standard normal quantile.
pub fn normal_quantile(p: f64) -> f64 {
    use statrs::distribution::{ContinuousCDF, Normal};
    Normal::standard().inverse_cdf(p)
}

/// How a summit map is laid out (lengths and heights in nm).
#[derive(Clone, Copy, Debug)]
pub struct SummitGrid {
    /// The summits' radius.
    pub radius: f64,
    /// The standard deviation of their heights.
    pub sigma: f64,
    /// The grid's spacing.
    pub spacing: f64,
    /// Summits lie within this distance of the map's middle.
    pub region: f64,
    /// The map's side.
    pub size: f64,
    /// The pixel size.
    pub pixel: f64,
}

/// The map: summits on a square grid (spacing apart, within `region` of the middle, centred on
/// pixels) over a base at 0; returns the map and the number N of summits. Each summit is a cap
/// of apex height 5 sigma + z_k: the paraboloid of its radius out to two pixels from its apex
/// (where its curvature is measured), then a cone of slope 10 down to the base, so the caps
/// stay narrow and the map's mean plane lies below every summit. The map is the caps' maximum;
/// as each cap is concave, its only local maxima are the apexes.
///
/// The heights z_k are the N quantiles of the Gaussian, (j + 1/2) / N, dealt so that every disc
/// around the middle holds an even sample: ranked by distance from the middle, the k-th summit
/// takes the j-th quantile, j the rank of b(k) among b(0..N), b(k) the bit reversal of k (van
/// der Corput's sequence). The whole map has exactly the N quantiles, down to the tails; the
/// summits within any distance of the middle have nearly evenly spread ones.
pub fn summit_map(g: SummitGrid) -> (HeightMap, usize) {
    let middle = g.size / 2.0;
    let half = (g.region / g.spacing).floor() as i64;
    let mut centres = Vec::new();
    for j in -half..=half {
        for i in -half..=half {
            let (x, y) = (i as f64 * g.spacing, j as f64 * g.spacing);
            if x.hypot(y) <= g.region - g.pixel {
                centres.push((middle + x, middle + y));
            }
        }
    }
    let distance = |c: &(f64, f64)| (c.0 - middle).hypot(c.1 - middle);
    centres.sort_by(|a, b| distance(a).total_cmp(&distance(b)));
    let n = centres.len();
    let bits = n.next_power_of_two().trailing_zeros().max(1);
    let reversed = |k: usize| (k as u64).reverse_bits() >> (64 - bits);
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by_key(|&k| reversed(k));
    let mut quantile_of = vec![0usize; n];
    for (rank, &k) in order.iter().enumerate() {
        quantile_of[k] = rank;
    }
    let heights: Vec<f64> =
        (0..n).map(|k| g.sigma * normal_quantile((quantile_of[k] as f64 + 0.5) / n as f64)).collect();
    let pixels = (g.size / g.pixel).round() as usize + 1;
    let mut z = vec![0.0f64; pixels * pixels];
    let (r0, slope) = (2.0 * g.pixel, 10.0);
    for (&(cx, cy), &h) in centres.iter().zip(&heights) {
        let (ci, cj) = ((cx / g.pixel).round() as i64, (cy / g.pixel).round() as i64);
        let apex = 5.0 * g.sigma + h;
        let cap = |r: f64| {
            if r <= r0 { apex - r * r / (2.0 * g.radius) } else { apex - r0 * r0 / (2.0 * g.radius) - slope * (r - r0) }
        };
        let reach = ((r0 + apex / slope) / g.pixel) as i64 + 1;
        for j in (cj - reach).max(0)..=(cj + reach).min(pixels as i64 - 1) {
            for i in (ci - reach).max(0)..=(ci + reach).min(pixels as i64 - 1) {
                let r = (((i - ci).pow(2) + (j - cj).pow(2)) as f64).sqrt() * g.pixel;
                let k = j as usize * pixels + i as usize;
                z[k] = z[k].max(cap(r));
            }
        }
    }
    (HeightMap::new((pixels, pixels), (g.pixel, g.pixel), z, ("nm", "nm")).unwrap(), n)
}
