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
    /// Contact resistance (ohm) per converged increment, when the run models it.
    pub resistance: Option<Vec<f64>>,
}

/// Reads approach, force and contact_area from a `history.csv` (None if it has no interface
/// with a flat). With several interfaces (columns prefixed by the interface's name) the first
/// one with a flat is read.
pub fn read_history(path: &Path, label: &str) -> Option<Curve> {
    let text = std::fs::read_to_string(path).ok()?;
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next()?.split(',').collect();
    let prefix = if header.contains(&"approach") {
        ""
    } else {
        header.iter().find_map(|h| h.strip_suffix("approach").filter(|p| p.ends_with('_')))?
    };
    let col = |n: &str| header.iter().position(|h| *h == format!("{prefix}{n}"));
    let (ia, i_f, iarea) = (col("approach")?, col("force")?, col("contact_area")?);
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').filter_map(|x| x.parse().ok()).collect::<Vec<f64>>())
        .filter(|v| v.len() == header.len())
        .collect();
    let points = rows.iter().map(|v| (v[ia], v[i_f], v[iarea])).collect();
    let resistance = col("contact_resistance").map(|ir| rows.iter().map(|v| v[ir]).collect());
    Some(Curve { label: label.to_string(), points, resistance })
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

type Chart<'a, DB> =
    ChartContext<'a, DB, Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>>;

/// Draws the series labels in the upper left corner and writes the picture.
pub(crate) fn legend_and_present<'a, DB: DrawingBackend + 'a>(
    chart: &mut Chart<'a, DB>,
    root: &DrawingArea<DB, plotters::coord::Shift>,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .position(SeriesLabelPosition::UpperLeft)
        .draw()
        .map_err(|e| e.to_string())?;
    root.present().map_err(|e| e.to_string())
}

/// A chart on `root` whose axes span the points (x, y_low, y_high) with a 5% margin, labelled.
pub(crate) fn padded_chart<'a, DB: DrawingBackend + 'a>(
    root: &'a DrawingArea<DB, plotters::coord::Shift>,
    title: &str,
    (x_label, y_label): (&str, &str),
    points: impl Iterator<Item = (f64, f64, f64)>,
) -> Result<Chart<'a, DB>, String>
where
    DB::ErrorType: 'static,
{
    let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
    for (x, lo, hi) in points {
        (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(lo), y1.max(hi));
    }
    let pad = |a: f64, b: f64| 0.05 * (b - a).abs().max(1e-12);
    let (px, py) = (pad(x0, x1), pad(y0, y1));
    let mut chart = ChartBuilder::on(root)
        .caption(title, ("sans-serif", 22))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d((x0 - px)..(x1 + px), (y0 - py)..(y1 + py))
        .map_err(|e| e.to_string())?;
    chart.configure_mesh().x_desc(x_label).y_desc(y_label).draw().map_err(|e| e.to_string())?;
    Ok(chart)
}

/// Lines with a marker at each point, one colour per series, on fixed axis ranges.
pub(crate) fn draw_marked_lines<DB: DrawingBackend>(
    root: DrawingArea<DB, plotters::coord::Shift>,
    title: &str,
    (x_label, y_label): (&str, &str),
    (x_range, y_range): (std::ops::Range<f64>, std::ops::Range<f64>),
    series: &[(String, Vec<(f64, f64)>)],
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE).map_err(|e| e.to_string())?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 22))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d(x_range, y_range)
        .map_err(|e| e.to_string())?;
    chart.configure_mesh().x_desc(x_label).y_desc(y_label).draw().map_err(|e| e.to_string())?;
    for (i, (label, points)) in series.iter().enumerate() {
        let color = Palette99::pick(i).to_rgba();
        chart
            .draw_series(LineSeries::new(points.clone(), color.stroke_width(2)))
            .map_err(|e| e.to_string())?
            .label(label.as_str())
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2)));
        chart.draw_series(points.iter().map(|p| Circle::new(*p, 4, color.filled()))).map_err(|e| e.to_string())?;
    }
    legend_and_present(&mut chart, &root)
}

fn draw<DB: DrawingBackend>(
    root: DrawingArea<DB, plotters::coord::Shift>,
    title: &str,
    (x_label, y_label): (&str, &str),
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
    let mut chart = padded_chart(&root, title, (x_label, y_label), all.iter().map(|&(x, y)| (x, y, y)))?;
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
    legend_and_present(&mut chart, &root)
}

/// Writes `<prefix>force_approach.{png,svg}` and `<prefix>area_approach.{png,svg}` in `dir`.
pub fn plot_curves(dir: &Path, prefix: &str, title: &str, curves: &[Curve]) -> Result<(), String> {
    let force: Vec<(String, Vec<(f64, f64)>)> =
        curves.iter().map(|c| (c.label.clone(), c.points.iter().map(|p| (p.0, p.1 * 1e-3)).collect())).collect();
    let area: Vec<(String, Vec<(f64, f64)>)> =
        curves.iter().map(|c| (c.label.clone(), c.points.iter().map(|p| (p.0, p.2)).collect())).collect();
    let approach = "approach (nm)";
    let mut plots = vec![
        ("force_approach", force, (approach, "force (uN, + compressive)")),
        ("area_approach", area, (approach, "real contact area (nm^2)")),
    ];
    if curves.iter().any(|c| c.resistance.is_some()) {
        // log10 R where there is contact (R finite)
        let log_r = |by_force: bool| -> Vec<(String, Vec<(f64, f64)>)> {
            curves
                .iter()
                .filter_map(|c| {
                    let r = c.resistance.as_ref()?;
                    let points = c
                        .points
                        .iter()
                        .zip(r)
                        .filter(|(_, r)| r.is_finite() && **r > 0.0)
                        .map(|(p, r)| (if by_force { p.1 * 1e-3 } else { p.0 }, r.log10()))
                        .collect();
                    Some((c.label.clone(), points))
                })
                .collect()
        };
        let log_label = "log10 contact resistance (ohm)";
        plots.push(("resistance_approach", log_r(false), (approach, log_label)));
        plots.push(("resistance_force", log_r(true), ("force (uN, + compressive)", log_label)));
    }
    for (name, data, axes) in &plots {
        let png = dir.join(format!("{prefix}{name}.png"));
        let svg = dir.join(format!("{prefix}{name}.svg"));
        draw(BitMapBackend::new(&png, (900, 600)).into_drawing_area(), title, *axes, data)?;
        draw(SVGBackend::new(&svg, (900, 600)).into_drawing_area(), title, *axes, data)?;
    }
    Ok(())
}

/// Writes `cycles.{png,svg}` in `dir`: the change of each cycle's maximum force, pull-off
/// force (cycles that separated), maximum real area and contact resistance at the maximum force from the first cycle's,
/// in percent, on one axis of at least +-1%, so a drift over the cycles (or its absence) shows at
/// a glance; the values themselves are in cycles.csv.
pub fn plot_cycles(dir: &Path, title: &str, cycles: &[stiction_core::record::CycleSummary]) -> Result<(), String> {
    type Quantity = fn(&stiction_core::record::CycleSummary) -> Option<f64>;
    let quantities: [(&str, Quantity); 4] = [
        ("max force", |c| Some(c.max_force)),
        ("pull-off force", |c| c.pull_off_force),
        ("max real area", |c| Some(c.max_contact_area)),
        ("resistance at max force", |c| c.contact_resistance_at_max_force),
    ];
    let mut series = Vec::new();
    for (label, value) in quantities {
        let Some(first) = cycles.first().and_then(value).filter(|v| v.is_finite() && *v != 0.0) else { continue };
        let points: Vec<(f64, f64)> = cycles
            .iter()
            .filter_map(|c| Some((c.cycle as f64, 100.0 * (value(c)? / first - 1.0))))
            .filter(|p| p.1.is_finite())
            .collect();
        series.push((label.to_string(), points));
    }
    let span = series.iter().flat_map(|(_, p)| p.iter().map(|q| q.1.abs())).fold(1.0f64, f64::max) * 1.1;
    let last = cycles.len().max(2) as f64;
    let png = dir.join("cycles.png");
    let svg = dir.join("cycles.svg");
    let axes = ("cycle", "change from cycle 1 (%)");
    let ranges = (0.8..(last + 0.2), -span..span);
    draw_marked_lines(BitMapBackend::new(&png, (900, 600)).into_drawing_area(), title, axes, ranges.clone(), &series)?;
    draw_marked_lines(SVGBackend::new(&svg, (900, 600)).into_drawing_area(), title, axes, ranges, &series)
}

type Branch = (String, Vec<(f64, f64, f64)>, Vec<f64>, Vec<f64>, (f64, f64));

fn draw_calibration<DB: DrawingBackend>(
    root: DrawingArea<DB, plotters::coord::Shift>,
    branches: &[Branch],
    idx: usize,
    title: &str,
    y_label: &str,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    use stiction_law_ru_asperity::polynomial::value;
    root.fill(&WHITE).map_err(|e| e.to_string())?;
    let pick = |p: &(f64, f64, f64)| if idx == 1 { p.1 } else { p.2 };
    let all: Vec<(f64, f64)> = branches.iter().flat_map(|b| b.1.iter().map(|p| (p.0, pick(p)))).collect();
    let (x0, x1) = all.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |a, p| (a.0.min(p.0), a.1.max(p.0)));
    let (y0, y1) = all.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |a, p| (a.0.min(p.1), a.1.max(p.1)));
    let (px, py) = (0.05 * (x1 - x0).max(1e-9), 0.05 * (y1 - y0).max(1e-9));
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 20))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d((x0 - px)..(x1 + px), (y0 - py)..(y1 + py))
        .map_err(|e| e.to_string())?;
    chart.configure_mesh().x_desc("distance (nm)").y_desc(y_label).draw().map_err(|e| e.to_string())?;
    for (i, (label, rows, fforce, farea, (a, b))) in branches.iter().enumerate() {
        let color = Palette99::pick(i).to_rgba();
        let coeffs = if idx == 1 { fforce } else { farea };
        chart
            .draw_series(rows.iter().map(|p| Circle::new((p.0, pick(p)), 2, color.filled())))
            .map_err(|e| e.to_string())?;
        let line: Vec<(f64, f64)> =
            (0..=200).map(|k| a + (b - a) * k as f64 / 200.0).map(|x| (x, value(coeffs, x))).collect();
        chart
            .draw_series(LineSeries::new(line, color.stroke_width(2)))
            .map_err(|e| e.to_string())?
            .label(label.clone())
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2)));
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()
        .map_err(|e| e.to_string())?;
    root.present().map_err(|e| e.to_string())
}

/// Plots a calibration table against its fitted polynomials: force and area vs distance, one
/// colour per branch (loading, and each unloading maximum); points are data, lines the fits.
/// Writes `<stem>_force.{png,svg}` and `<stem>_area.{png,svg}` next to `stem`.
pub fn plot_calibration(
    stem: &Path,
    table: &stiction_law_ru_asperity::fit::Table,
    calibration: &stiction_law_ru_asperity::calibration::Calibration,
) -> Result<(), String> {
    let mut branches: Vec<Branch> = Vec::new();
    let load: Vec<(f64, f64, f64)> =
        table.rows.iter().filter(|r| r.loading).map(|r| (r.distance, r.force, r.area)).collect();
    let l = &calibration.loading;
    branches.push(("loading".into(), load, l.force.clone(), l.area.clone(), (l.d_start, l.d_end)));
    for u in &calibration.unloading {
        let rows = table
            .rows
            .iter()
            .filter(|r| !r.loading && r.max_distance == u.d_max)
            .map(|r| (r.distance, r.force, r.area))
            .collect();
        branches.push((
            format!("unloading from {}", u.d_max),
            rows,
            u.force.clone(),
            u.area.clone(),
            (u.d_end, u.d_max),
        ));
    }
    let base = stem.file_stem().and_then(|s| s.to_str()).unwrap_or("calibration").to_string();
    for (what, idx, y_label) in [("force", 1usize, "force (nN, + compressive)"), ("area", 2usize, "area (nm^2)")] {
        let title = format!("{what} (w = {} J/m^2): data (points) and fits (lines)", calibration.work_of_adhesion);
        let png = stem.with_file_name(format!("{base}_{what}.png"));
        let svg = stem.with_file_name(format!("{base}_{what}.svg"));
        draw_calibration(BitMapBackend::new(&png, (900, 600)).into_drawing_area(), &branches, idx, &title, y_label)?;
        draw_calibration(SVGBackend::new(&svg, (900, 600)).into_drawing_area(), &branches, idx, &title, y_label)?;
    }
    Ok(())
}

/// Plots a run's force and area against approach when it ends (runs with an interface), as an
/// observer of the run. A plot that cannot be drawn is a warning, not a failed run.
pub struct RunPlots {
    directory: std::path::PathBuf,
    name: String,
}

impl RunPlots {
    pub fn new(directory: &Path, name: &str) -> Self {
        Self { directory: directory.to_path_buf(), name: name.to_string() }
    }
}

impl stiction_core::record::Observer for RunPlots {
    fn committed(
        &mut self,
        _model: &stiction_core::model::Model,
        _increment: &stiction_core::record::CommittedIncrement,
    ) -> stiction_core::error::Result<()> {
        Ok(())
    }

    fn finished(
        &mut self,
        _model: &stiction_core::model::Model,
        summary: &stiction_core::record::RunSummary,
    ) -> stiction_core::error::Result<()> {
        if summary.interfaces.is_empty() {
            return Ok(());
        }
        if let Some(curve) = read_history(&self.directory.join("history.csv"), &self.name) {
            if let Err(e) = plot_curves(&self.directory, "", &self.name, &[curve]) {
                eprintln!("warning: plots of '{}' not written: {e}", self.name);
            }
        }
        if let Some(i) = summary.interfaces.iter().find(|i| i.cycles.len() > 1) {
            let title = format!("{}: {} per load cycle", self.name, i.name);
            if let Err(e) = plot_cycles(&self.directory, &title, &i.cycles) {
                eprintln!("warning: cycle plot of '{}' not written: {e}", self.name);
            }
        }
        Ok(())
    }
}
