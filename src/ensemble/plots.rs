//! Plots of an ensemble (PNG and SVG): mean force and real contact area against approach with
//! their 95% confidence bands, loading and unloading; and the confidence interval's half width
//! (in % of the mean) against the number of members.

use super::aggregate::EnsembleAggregate;
use super::curves::CurvePoint;
use super::statistics::Statistic;
use plotters::prelude::*;
use std::path::Path;

/// One mean curve with its band: (x, mean, low, high).
struct Band {
    label: String,
    points: Vec<(f64, f64, f64, f64)>,
}

fn band(label: &str, curve: &[CurvePoint], pick: fn(&CurvePoint) -> &Statistic, scale: f64) -> Band {
    let points = curve
        .iter()
        .map(|p| {
            let s = pick(p);
            let (lo, hi) = (s.ci95_low.unwrap_or(s.mean), s.ci95_high.unwrap_or(s.mean));
            (p.approach, s.mean * scale, lo * scale, hi * scale)
        })
        .collect();
    Band { label: label.to_string(), points }
}

fn draw_bands<DB: DrawingBackend>(
    root: DrawingArea<DB, plotters::coord::Shift>,
    title: &str,
    (x_label, y_label): (&str, &str),
    bands: &[Band],
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE).map_err(|e| e.to_string())?;
    if bands.iter().all(|b| b.points.is_empty()) {
        return Ok(());
    }
    let points = bands.iter().flat_map(|b| b.points.iter().map(|&(x, _, lo, hi)| (x, lo, hi)));
    let mut chart = crate::plots::padded_chart(&root, title, (x_label, y_label), points)?;
    for (i, b) in bands.iter().enumerate() {
        let color = Palette99::pick(i).to_rgba();
        let outline: Vec<(f64, f64)> =
            b.points.iter().map(|p| (p.0, p.3)).chain(b.points.iter().rev().map(|p| (p.0, p.2))).collect();
        chart
            .draw_series(std::iter::once(Polygon::new(outline, color.mix(0.25).filled())))
            .map_err(|e| e.to_string())?;
        chart
            .draw_series(LineSeries::new(b.points.iter().map(|p| (p.0, p.1)), color.stroke_width(2)))
            .map_err(|e| e.to_string())?
            .label(b.label.as_str())
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2)));
    }
    crate::plots::legend_and_present(&mut chart, &root)
}

/// Writes `ensemble_force.{png,svg}`, `ensemble_area.{png,svg}` and
/// `ensemble_convergence.{png,svg}` into `dir`. Forces are shown in uN (the case's nN / 1000),
/// as in the single-run plots.
pub fn plot(dir: &Path, aggregate: &EnsembleAggregate) -> Result<(), String> {
    let n = aggregate.completed;
    let title = format!("{} ensemble, {n} members (mean, 95% confidence band)", aggregate.case);
    let force = [
        band("loading", &aggregate.loading, |p| &p.force, 1e-3),
        band("unloading", &aggregate.unloading, |p| &p.force, 1e-3),
    ];
    let area = [
        band("loading", &aggregate.loading, |p| &p.contact_area, 1.0),
        band("unloading", &aggregate.unloading, |p| &p.contact_area, 1.0),
    ];
    let approach = "approach (nm)";
    for (name, bands, y) in
        [("ensemble_force", &force, "force (uN, + compressive)"), ("ensemble_area", &area, "real contact area (nm^2)")]
    {
        let png = dir.join(format!("{name}.png"));
        let svg = dir.join(format!("{name}.svg"));
        draw_bands(BitMapBackend::new(&png, (900, 600)).into_drawing_area(), &title, (approach, y), bands)?;
        draw_bands(SVGBackend::new(&svg, (900, 600)).into_drawing_area(), &title, (approach, y), bands)?;
    }
    let mut series: Vec<(String, Vec<(f64, f64)>)> = Vec::new();
    for c in &aggregate.convergence {
        let value = 100.0 * c.ci95_half_width / c.mean.abs().max(f64::MIN_POSITIVE);
        match series.last_mut() {
            Some((q, pts)) if *q == c.quantity => pts.push((c.n as f64, value)),
            _ => series.push((c.quantity.clone(), vec![(c.n as f64, value)])),
        }
    }
    let title = format!("{}: confidence interval against ensemble size", aggregate.case);
    let n_max = series.iter().flat_map(|s| s.1.iter().map(|p| p.0)).fold(2.0, f64::max);
    let y_max = series.iter().flat_map(|s| s.1.iter().map(|p| p.1)).fold(1.0, f64::max) * 1.1;
    let axes = ("members N", "95% confidence half width (% of |mean|)");
    let ranges = (1.5..(n_max + 0.5), 0.0..y_max);
    let png = dir.join("ensemble_convergence.png");
    let svg = dir.join("ensemble_convergence.svg");
    use crate::plots::draw_marked_lines as draw;
    draw(BitMapBackend::new(&png, (900, 600)).into_drawing_area(), &title, axes, ranges.clone(), &series)?;
    draw(SVGBackend::new(&svg, (900, 600)).into_drawing_area(), &title, axes, ranges, &series)
}
