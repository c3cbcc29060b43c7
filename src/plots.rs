//! Plots of interface histories (PNG and SVG): force and real contact area against approach,
//! with loading (approach increasing) and unloading (decreasing) drawn in different styles, one
//! colour per run. Units as in the case (the Ru cases: nm, nN -> shown in uN, nm^2).

use plotters::prelude::*;
use std::path::Path;

/// One run's interface history.
pub struct Curve {
    pub label: String,
    /// (approach, force, contact area) per converged increment.
    pub points: Vec<(f64, f64, f64)>,
}

/// Reads approach, force and contact_area from a `history.csv` (None if it has no interface).
pub fn read_history(path: &Path, label: &str) -> Option<Curve> {
    let text = std::fs::read_to_string(path).ok()?;
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next()?.split(',').collect();
    let col = |n: &str| header.iter().position(|h| *h == n);
    let (ia, i_f, iarea) = (col("approach")?, col("force")?, col("contact_area")?);
    let points = lines
        .filter_map(|l| {
            let v: Vec<f64> = l.split(',').filter_map(|x| x.parse().ok()).collect();
            (v.len() == header.len()).then(|| (v[ia], v[i_f], v[iarea]))
        })
        .collect();
    Some(Curve { label: label.to_string(), points })
}

/// Splits a curve into monotone legs: (is_loading, points).
fn legs(points: &[(f64, f64)]) -> Vec<(bool, Vec<(f64, f64)>)> {
    let mut out: Vec<(bool, Vec<(f64, f64)>)> = Vec::new();
    for w in points.windows(2) {
        let loading = w[1].0 >= w[0].0;
        match out.last_mut() {
            Some((l, pts)) if *l == loading => pts.push(w[1]),
            _ => out.push((loading, vec![w[0], w[1]])),
        }
    }
    out
}

fn draw<DB: DrawingBackend>(
    root: DrawingArea<DB, plotters::coord::Shift>,
    title: &str,
    y_label: &str,
    curves: &[(String, Vec<(f64, f64)>)],
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE).map_err(|e| e.to_string())?;
    let all: Vec<(f64, f64)> = curves.iter().flat_map(|(_, p)| p.iter().copied()).collect();
    if all.is_empty() {
        return Ok(());
    }
    let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
    for (x, y) in &all {
        x0 = x0.min(*x);
        x1 = x1.max(*x);
        y0 = y0.min(*y);
        y1 = y1.max(*y);
    }
    let pad = |a: f64, b: f64| 0.05 * (b - a).abs().max(1e-12);
    let (px, py) = (pad(x0, x1), pad(y0, y1));
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 22))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d((x0 - px)..(x1 + px), (y0 - py)..(y1 + py))
        .map_err(|e| e.to_string())?;
    chart.configure_mesh().x_desc("approach (nm)").y_desc(y_label).draw().map_err(|e| e.to_string())?;
    for (i, (label, pts)) in curves.iter().enumerate() {
        let color = Palette99::pick(i).to_rgba();
        let mut first = true;
        for (loading, leg) in legs(pts) {
            let style = if loading { color.stroke_width(2) } else { color.mix(0.6).stroke_width(1) };
            let series = chart.draw_series(LineSeries::new(leg, style)).map_err(|e| e.to_string())?;
            if first {
                let l = format!("{label} (thick: loading, thin: unloading)");
                series
                    .label(l)
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2)));
                first = false;
            }
        }
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .position(SeriesLabelPosition::UpperLeft)
        .draw()
        .map_err(|e| e.to_string())?;
    root.present().map_err(|e| e.to_string())
}

/// Writes `<prefix>force_approach.{png,svg}` and `<prefix>area_approach.{png,svg}` in `dir`.
pub fn plot_curves(dir: &Path, prefix: &str, title: &str, curves: &[Curve]) -> Result<(), String> {
    let force: Vec<(String, Vec<(f64, f64)>)> =
        curves.iter().map(|c| (c.label.clone(), c.points.iter().map(|p| (p.0, p.1 * 1e-3)).collect())).collect();
    let area: Vec<(String, Vec<(f64, f64)>)> =
        curves.iter().map(|c| (c.label.clone(), c.points.iter().map(|p| (p.0, p.2)).collect())).collect();
    for (name, data, y) in
        [("force_approach", &force, "force (uN, + compressive)"), ("area_approach", &area, "real contact area (nm^2)")]
    {
        let png = dir.join(format!("{prefix}{name}.png"));
        let svg = dir.join(format!("{prefix}{name}.svg"));
        draw(BitMapBackend::new(&png, (900, 600)).into_drawing_area(), title, y, data)?;
        draw(SVGBackend::new(&svg, (900, 600)).into_drawing_area(), title, y, data)?;
    }
    Ok(())
}
