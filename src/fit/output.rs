//! The fit's files besides fit.json and fit_history.csv: the fitted case files, ready to run,
//! and the plots of each measured curve against the model at the start and at the fit.

use super::evaluate::Point;
use super::spec::{FitSpec, TargetKind};
use super::targets::Branch;
use crate::error::{Result, StictionError};
use plotters::prelude::*;
use std::path::{Path, PathBuf};
use stiction_core::output::write_atomically;
use stiction_core::record::summary::Units;

/// The file name of case `name`'s fitted case in the fit's folder.
pub fn fitted_case_name(name: &str) -> String {
    format!("fitted-{name}.toml")
}

/// Writes `fitted-<case>.toml` for every case: the case as the fit ran it (its base merged,
/// its sets applied) with the fitted values, its relative paths rewritten for the fit's
/// folder, and a header that says where the values came from.
pub fn write_fitted_cases(spec: &FitSpec, out: &Path, x: &[f64], header: &str) -> Result<Vec<PathBuf>> {
    let mut written = Vec::new();
    for (c, case) in spec.cases.iter().enumerate() {
        let mut sets = case.set.clone();
        for (p, v) in spec.parameters.iter().zip(x) {
            if p.cases.contains(&c) {
                sets.push(format!("{}={v:e}", p.key));
            }
        }
        let loaded = crate::case::load(&case.file, &sets)?;
        let mut value = loaded.value.clone();
        let from = loaded.base_dir().to_path_buf();
        relocate_paths(&mut value, &from, out);
        if let Some(t) = value.as_table_mut() {
            t.insert("name".into(), toml::Value::String(format!("{}-fitted", loaded.name)));
            if let Some(output) = t.get_mut("output").and_then(|o| o.as_table_mut()) {
                output.remove("directory");
            }
        }
        let body = toml::to_string(&value).map_err(|e| StictionError::Output {
            path: out.to_path_buf(),
            message: format!("cannot write the fitted case '{}': {e}", case.name),
        })?;
        let path = out.join(fitted_case_name(&case.name));
        write_atomically(&path, format!("{header}{body}").as_bytes())?;
        written.push(path);
    }
    Ok(written)
}

/// Rewrites the case's relative file paths (mesh, plugin folders, law configurations, point
/// files), which are relative to the folder `from`, to be relative to `to`.
fn relocate_paths(value: &mut toml::Value, from: &Path, to: &Path) {
    // both folders exist: canonical, so the relative path has no detours through `..`
    let absolute = |p: &Path| std::fs::canonicalize(p).or_else(|_| std::path::absolute(p)).unwrap_or(p.to_path_buf());
    let (from, to) = (absolute(from), absolute(to));
    let moved = |s: &str| -> String {
        let p = Path::new(s);
        if p.is_absolute() {
            return s.to_string();
        }
        pathdiff::diff_paths(from.join(p), &to).unwrap_or_else(|| from.join(p)).to_string_lossy().into_owned()
    };
    let fix = |v: Option<&mut toml::Value>| {
        if let Some(toml::Value::String(s)) = v {
            *s = moved(s);
        }
    };
    let Some(t) = value.as_table_mut() else { return };
    if let Some(mesh) = t.get_mut("mesh").and_then(|m| m.as_table_mut()) {
        fix(mesh.get_mut("file"));
        fix(mesh.get_mut("geo"));
    }
    if let Some(toml::Value::Array(dirs)) = t.get_mut("plugin_path") {
        for d in dirs {
            fix(Some(d));
        }
    }
    if let Some(toml::Value::Array(interfaces)) = t.get_mut("interfaces") {
        for i in interfaces.iter_mut().filter_map(|i| i.as_table_mut()) {
            fix(i.get_mut("config_file"));
            if let Some(points) = i.get_mut("points").and_then(|p| p.as_table_mut()) {
                fix(points.get_mut("file"));
            }
        }
    }
}

/// One series of a fit plot: its label, points, and whether it is drawn as markers only.
type Series = (String, Vec<(f64, f64)>, RGBAColor, bool);

/// Writes `fit_<k>.png` and `.svg` for each curve target k: the measured points (black), and
/// the model's values at them at the start (grey) and at the fit (coloured), per branch.
pub fn plot_curves(
    spec: &FitSpec,
    out: &Path,
    units: &[Units],
    start: &Point,
    end: &Point,
) -> std::result::Result<(), String> {
    for (k, t) in spec.targets.iter().enumerate() {
        let TargetKind::Curve(curve) = &t.kind else { continue };
        let measured: Vec<f64> = curve.points.iter().map(|p| p.value).collect();
        let mut series: Vec<Series> = Vec::new();
        for (branch, name, colour) in [(Branch::Loading, "loading", BLUE), (Branch::Unloading, "unloading", RED)] {
            let on = |values: &[f64]| -> Vec<(f64, f64)> {
                curve
                    .points
                    .iter()
                    .zip(values)
                    .filter(|(p, _)| p.branch == branch)
                    .map(|(p, v)| (p.approach, *v))
                    .collect()
            };
            if on(&measured).is_empty() {
                continue;
            }
            series.push((format!("start, {name}"), on(&start.model[k]), colour.mix(0.3), false));
            series.push((format!("fit, {name}"), on(&end.model[k]), colour.to_rgba(), false));
            series.push((format!("measured, {name}"), on(&measured), BLACK.to_rgba(), true));
        }
        let u = &units[t.case];
        let unit = match curve.column.as_str() {
            "force" => u.force.as_str(),
            "contact_area" => u.area.as_str(),
            _ => u.resistance.as_str(),
        };
        let labels = (format!("approach ({})", u.length), format!("{} ({unit})", curve.column));
        for ext in ["png", "svg"] {
            let path = out.join(format!("fit_{k}.{ext}"));
            if ext == "png" {
                draw(BitMapBackend::new(&path, (900, 600)).into_drawing_area(), &t.name, &labels, &series)?;
            } else {
                draw(SVGBackend::new(&path, (900, 600)).into_drawing_area(), &t.name, &labels, &series)?;
            }
        }
    }
    Ok(())
}

fn draw<DB: DrawingBackend>(
    root: DrawingArea<DB, plotters::coord::Shift>,
    title: &str,
    (x_label, y_label): &(String, String),
    series: &[Series],
) -> std::result::Result<(), String>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE).map_err(|e| e.to_string())?;
    let all = series.iter().flat_map(|s| s.1.iter().map(|&(x, y)| (x, y, y)));
    let mut chart = crate::plots::padded_chart(&root, title, (x_label, y_label), all)?;
    for (label, points, colour, markers_only) in series {
        let colour = *colour;
        if *markers_only {
            chart
                .draw_series(points.iter().map(|&p| Circle::new(p, 4, colour.filled())))
                .map_err(|e| e.to_string())?
                .label(label.as_str())
                .legend(move |(x, y)| Circle::new((x + 10, y), 4, colour.filled()));
        } else {
            chart
                .draw_series(LineSeries::new(points.clone(), colour.stroke_width(2)))
                .map_err(|e| e.to_string())?
                .label(label.as_str())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(2)));
        }
    }
    crate::plots::legend_and_present(&mut chart, &root)
}
