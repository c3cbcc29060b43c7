//! Greenwood-Williamson surfaces as height maps, for the validation tests: paraboloid summits of
//! one radius on a square grid, their heights the N quantiles of a Gaussian laid out so that
//! every disc around the middle holds an even sample (samples that stand for the Gaussian
//! without a random draw's scatter, in the whole map and in a sphere's contact alike).

use stiction_interfaces::height_map::HeightMap;

/// The standard normal quantile (Acklam's rational approximation, relative error < 1.2e-9).
pub fn normal_quantile(p: f64) -> f64 {
    const A: [f64; 6] = [
        -3.969683028665376e1,
        2.209460984245205e2,
        -2.759285104469687e2,
        1.383577518672690e2,
        -3.066479806614716e1,
        2.506628277459239,
    ];
    const B: [f64; 5] =
        [-5.447609879822406e1, 1.615858368580409e2, -1.556989798598866e2, 6.680131188771972e1, -1.328068155288572e1];
    const C: [f64; 6] = [
        -7.784894002430293e-3,
        -3.223964580411365e-1,
        -2.400758277161838,
        -2.549732539343734,
        4.374664141464968,
        2.938163982698783,
    ];
    const D: [f64; 4] = [7.784695709041462e-3, 3.224671290700398e-1, 2.445134137142996, 3.754408661907416];
    let tail = |q: f64| {
        (((((C[0] * q + C[1]) * q + C[2]) * q + C[3]) * q + C[4]) * q + C[5])
            / ((((D[0] * q + D[1]) * q + D[2]) * q + D[3]) * q + 1.0)
    };
    if p < 0.02425 {
        tail((-2.0 * p.ln()).sqrt())
    } else if p > 1.0 - 0.02425 {
        -tail((-2.0 * (1.0 - p).ln()).sqrt())
    } else {
        let q = p - 0.5;
        let r = q * q;
        (((((A[0] * r + A[1]) * r + A[2]) * r + A[3]) * r + A[4]) * r + A[5]) * q
            / (((((B[0] * r + B[1]) * r + B[2]) * r + B[3]) * r + B[4]) * r + 1.0)
    }
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
