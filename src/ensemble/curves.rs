//! Force and real contact area against approach over the members: each member's first loading
//! (up to its largest approach) and the unloading after it, interpolated linearly on a common
//! approach grid (the range every member covers), with statistics at every grid point.

use super::statistics::Statistic;
use serde::Serialize;

/// Grid points per branch.
pub const GRID_POINTS: usize = 101;

/// (approach, force, contact area) samples of one branch, in the order of the run.
pub type Branch = Vec<(f64, f64, f64)>;

/// The loading branch (start to the first largest approach) and the unloading branch (from
/// there to the first smallest approach after it) of one member's history.
pub fn branches(points: &[(f64, f64, f64)]) -> Option<(Branch, Branch)> {
    let first_extreme = |pts: &[(f64, f64, f64)], better: fn(f64, f64) -> bool| {
        let mut best = 0;
        for (i, p) in pts.iter().enumerate() {
            if better(p.0, pts[best].0) {
                best = i;
            }
        }
        best
    };
    if points.len() < 2 {
        return None;
    }
    let top = first_extreme(points, |a, b| a > b);
    let after = &points[top..];
    let bottom = first_extreme(after, |a, b| a < b);
    Some((points[..=top].to_vec(), after[..=bottom].to_vec()))
}

/// Force and area at `approach` on `branch`, interpolated linearly in the first segment that
/// spans it (None outside the branch).
pub fn at(branch: &[(f64, f64, f64)], approach: f64) -> Option<(f64, f64)> {
    branch.windows(2).find_map(|w| {
        let (a0, a1) = (w[0].0, w[1].0);
        let (lo, hi) = if a0 <= a1 { (a0, a1) } else { (a1, a0) };
        if !(lo <= approach && approach <= hi) {
            return None;
        }
        let s = if a1 == a0 { 0.0 } else { (approach - a0) / (a1 - a0) };
        Some((w[0].1 + s * (w[1].1 - w[0].1), w[0].2 + s * (w[1].2 - w[0].2)))
    })
}

/// Statistics of force and area at one approach.
#[derive(Debug, Clone, Serialize)]
pub struct CurvePoint {
    pub approach: f64,
    pub force: Statistic,
    pub contact_area: Statistic,
}

/// The statistics along a common grid from `start` to `end` (either direction) over `branches`.
pub fn on_grid(branches: &[&Branch], start: f64, end: f64) -> Vec<CurvePoint> {
    (0..GRID_POINTS)
        .filter_map(|k| {
            let a = start + (end - start) * k as f64 / (GRID_POINTS - 1) as f64;
            let values: Vec<(f64, f64)> = branches.iter().filter_map(|b| at(b, a)).collect();
            let force: Vec<f64> = values.iter().map(|v| v.0).collect();
            let area: Vec<f64> = values.iter().map(|v| v.1).collect();
            Some(CurvePoint {
                approach: a,
                force: Statistic::of("force", &force)?,
                contact_area: Statistic::of("contact_area", &area)?,
            })
        })
        .collect()
}

/// Loading and unloading statistics over the members' histories (each (approach, force, area)
/// per converged increment): loading on the approaches every member reached from its start,
/// unloading from the smallest of the members' largest approaches down to the largest of
/// their smallest ones.
pub fn ensemble_curves(histories: &[Vec<(f64, f64, f64)>]) -> (Vec<CurvePoint>, Vec<CurvePoint>) {
    let split: Vec<(Branch, Branch)> = histories.iter().filter_map(|h| branches(h)).collect();
    if split.is_empty() {
        return (Vec::new(), Vec::new());
    }
    let first = |b: &Branch| b.first().map_or(f64::NAN, |p| p.0);
    let last = |b: &Branch| b.last().map_or(f64::NAN, |p| p.0);
    let loading: Vec<&Branch> = split.iter().map(|s| &s.0).collect();
    let unloading: Vec<&Branch> = split.iter().map(|s| &s.1).collect();
    let start = loading.iter().map(|b| first(b)).fold(f64::NEG_INFINITY, f64::max);
    let top = loading.iter().map(|b| last(b)).fold(f64::INFINITY, f64::min);
    let bottom = unloading.iter().map(|b| last(b)).fold(f64::NEG_INFINITY, f64::max);
    (on_grid(&loading, start, top), on_grid(&unloading, top, bottom))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn branches_split_at_the_largest_approach_and_interpolate_linearly() {
        let h = vec![(0.0, 0.0, 0.0), (1.0, 10.0, 2.0), (2.0, 30.0, 4.0), (1.0, 5.0, 3.0), (-1.0, -2.0, 0.0)];
        let (load, unload) = branches(&h).unwrap();
        assert_eq!(load.len(), 3);
        assert_eq!(unload.len(), 3);
        assert_eq!(at(&load, 1.5), Some((20.0, 3.0)));
        assert_eq!(at(&unload, 0.0), Some((1.5, 1.5)));
        assert_eq!(at(&load, 2.5), None);
    }

    #[test]
    fn the_mean_curve_of_two_linear_members_is_their_average() {
        let member = |k: f64| vec![(0.0, 0.0, 0.0), (2.0, 2.0 * k, k), (0.0, -k, 0.0)];
        let (load, unload) = ensemble_curves(&[member(1.0), member(3.0)]);
        assert_eq!(load.len(), GRID_POINTS);
        let mid = &load[GRID_POINTS / 2];
        assert!((mid.approach - 1.0).abs() < 1e-12);
        assert!((mid.force.mean - 2.0).abs() < 1e-12, "mean of 1 and 3");
        assert!((unload.last().unwrap().force.mean + 2.0).abs() < 1e-12);
    }
}
