//! Fitting calibrations from a force/area-vs-distance table (the shape of an MD run's output):
//! least-squares polynomials for the loading branch and for each unloading branch.
//!
//! Table: CSV with the header `distance,force,area,branch,max_distance`; `branch` is `loading`
//! or `unloading`; `max_distance` groups the unloading rows (ignored on loading rows). Lines
//! starting with `#` may carry `# key: value` metadata: `work_of_adhesion`, `description`,
//! `provenance`. Units nm, nN, nm^2.
//! The loading range is [min, max] of its distances; an unloading branch's d_max is its group
//! key and its separation distance d_end the smallest distance in the group.

use crate::calibration::{Calibration, FORMAT, FitQuality, LoadingFit, Units, UnloadingFit};
use crate::polynomial;
use nalgebra::{DMatrix, DVector};

/// One table row.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Row {
    pub distance: f64,
    pub force: f64,
    pub area: f64,
    pub loading: bool,
    pub max_distance: f64,
    /// The row's line in the table (from 1), for messages.
    pub line: usize,
}

/// The largest magnitude a table's number may have: the least-squares fit squares the
/// powers of the distances and the values, which must stay finite.
pub const LARGEST_VALUE: f64 = 1e100;

/// A parsed table with its metadata.
#[derive(Debug, Clone, Default)]
pub struct Table {
    pub rows: Vec<Row>,
    pub work_of_adhesion: Option<f64>,
    pub description: Option<String>,
    pub provenance: Option<String>,
}

/// Parses the CSV text; errors name the line.
pub fn parse_table(text: &str) -> Result<Table, String> {
    let mut table = Table::default();
    let mut header_seen = false;
    for (i, line) in text.lines().enumerate() {
        let n = i + 1;
        let line = line.trim();
        if line.is_empty() {
            continue;
        }
        if let Some(meta) = line.strip_prefix('#') {
            if let Some((k, v)) = meta.split_once(':') {
                let v = v.trim().to_string();
                match k.trim() {
                    "work_of_adhesion" => {
                        table.work_of_adhesion =
                            Some(v.parse::<f64>().ok().filter(|w| w.is_finite() && *w > 0.0).ok_or_else(|| {
                                format!("line {n}: work_of_adhesion '{v}' is not a finite number > 0")
                            })?)
                    }
                    "description" => table.description = Some(v),
                    "provenance" => table.provenance = Some(v),
                    _ => {}
                }
            }
            continue;
        }
        if !header_seen {
            let cols: Vec<&str> = line.split(',').map(str::trim).collect();
            if cols != ["distance", "force", "area", "branch", "max_distance"] {
                return Err(format!(
                    "line {n}: expected the header 'distance,force,area,branch,max_distance', found '{line}'"
                ));
            }
            header_seen = true;
            continue;
        }
        let f: Vec<&str> = line.split(',').map(str::trim).collect();
        if f.len() != 5 {
            return Err(format!("line {n}: expected 5 columns, found {}", f.len()));
        }
        let num = |k: usize, name: &str| match f[k].parse::<f64>() {
            Ok(v) if v.is_finite() && v.abs() <= LARGEST_VALUE => Ok(v),
            Ok(v) if v.is_finite() => Err(format!(
                "line {n}, column {} ({name}): {v:e} is too large to fit (at most {LARGEST_VALUE:e} in magnitude)",
                k + 1
            )),
            _ => Err(format!("line {n}, column {} ({name}): expected a finite number, found '{}'", k + 1, f[k])),
        };
        let loading = match f[3] {
            "loading" => true,
            "unloading" => false,
            other => return Err(format!("line {n}: branch must be 'loading' or 'unloading', found '{other}'")),
        };
        table.rows.push(Row {
            distance: num(0, "distance")?,
            force: num(1, "force")?,
            area: num(2, "area")?,
            loading,
            max_distance: if loading { 0.0 } else { num(4, "max_distance")? },
            line: n,
        });
    }
    if !header_seen {
        return Err("no header line 'distance,force,area,branch,max_distance'".into());
    }
    Ok(table)
}

/// Least-squares polynomial of `order` through (x, y): minimises sum (p(x_i) - y_i)^2 (SVD).
pub fn least_squares(x: &[f64], y: &[f64], order: usize) -> Result<Vec<f64>, String> {
    if x.len() <= order {
        return Err(format!("{} points cannot determine a polynomial of order {order}", x.len()));
    }
    // Scale x to [-1, 1] for conditioning, then expand back to powers of x.
    let (lo, hi) = x.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| (a.min(v), b.max(v)));
    let (mid, half) = (0.5 * (lo + hi), 0.5 * (hi - lo).max(1e-300));
    let a = DMatrix::from_fn(x.len(), order + 1, |i, k| ((x[i] - mid) / half).powi(k as i32));
    let b = DVector::from_column_slice(y);
    let svd = a.svd(true, true);
    let t = svd.solve(&b, 1e-13).map_err(|e| e.to_string())?;
    // p(x) = sum_k t_k ((x - mid)/half)^k  ->  coefficients of x^j
    let mut c = vec![0.0; order + 1];
    for (k, tk) in t.iter().enumerate() {
        // ((x - mid)/half)^k = sum_j binom(k, j) x^j (-mid)^(k-j) / half^k
        let mut binom = 1.0;
        for j in 0..=k {
            c[j] += tk * binom * (-mid).powi((k - j) as i32) / half.powi(k as i32);
            binom = binom * (k - j) as f64 / (j + 1) as f64;
        }
    }
    Ok(c)
}

fn errors(c: &[f64], x: &[f64], y: &[f64]) -> (f64, f64) {
    let r: Vec<f64> = x.iter().zip(y).map(|(x, y)| polynomial::value(c, *x) - y).collect();
    let rms = (r.iter().map(|v| v * v).sum::<f64>() / r.len() as f64).sqrt();
    (rms, r.iter().fold(0.0f64, |m, v| m.max(v.abs())))
}

/// Err when the rows of a branch do not span distinct distances (a polynomial in the distance
/// needs them), naming the branch and its lines.
fn distinct_distances(rows: &[&Row], branch: &str) -> Result<(), String> {
    if x_max(rows) > x_min(rows) {
        return Ok(());
    }
    let (first, last) = (rows[0].line, rows[rows.len() - 1].line);
    Err(format!(
        "the {branch} rows (lines {first} to {last}) all have the distance {}: a fit needs distinct distances",
        rows[0].distance
    ))
}

/// Fits a calibration (loading order, unloading order).
pub fn fit(table: &Table, loading_order: usize, unloading_order: usize) -> Result<Calibration, String> {
    let load: Vec<&Row> = table.rows.iter().filter(|r| r.loading).collect();
    if load.is_empty() {
        return Err("the table has no loading rows".into());
    }
    distinct_distances(&load, "loading")?;
    let x: Vec<f64> = load.iter().map(|r| r.distance).collect();
    let lf = least_squares(&x, &load.iter().map(|r| r.force).collect::<Vec<_>>(), loading_order)
        .map_err(|e| format!("loading force: {e}"))?;
    let la = least_squares(&x, &load.iter().map(|r| r.area).collect::<Vec<_>>(), loading_order)
        .map_err(|e| format!("loading area: {e}"))?;
    let (lf_rms, lf_max) = errors(&lf, &x, &load.iter().map(|r| r.force).collect::<Vec<_>>());
    let (la_rms, _) = errors(&la, &x, &load.iter().map(|r| r.area).collect::<Vec<_>>());
    let mut maxima: Vec<f64> = table.rows.iter().filter(|r| !r.loading).map(|r| r.max_distance).collect();
    maxima.sort_by(f64::total_cmp);
    maxima.dedup();
    if maxima.is_empty() {
        return Err("the table has no unloading rows".into());
    }
    let mut unloading = Vec::new();
    let mut quality = FitQuality {
        loading_force_rms: lf_rms,
        loading_force_max: lf_max,
        loading_area_rms: la_rms,
        ..Default::default()
    };
    for m in maxima {
        let rows: Vec<&Row> = table.rows.iter().filter(|r| !r.loading && r.max_distance == m).collect();
        distinct_distances(&rows, &format!("unloading (max_distance {m})"))?;
        let x: Vec<f64> = rows.iter().map(|r| r.distance).collect();
        let f: Vec<f64> = rows.iter().map(|r| r.force).collect();
        let a: Vec<f64> = rows.iter().map(|r| r.area).collect();
        let uf = least_squares(&x, &f, unloading_order).map_err(|e| format!("unloading from {m}: {e}"))?;
        let ua = least_squares(&x, &a, unloading_order).map_err(|e| format!("unloading area from {m}: {e}"))?;
        let (rms, max) = errors(&uf, &x, &f);
        quality.unloading_force_rms.push(rms);
        quality.unloading_force_max.push(max);
        quality.unloading_area_rms.push(errors(&ua, &x, &a).0);
        let d_end = x.iter().copied().fold(f64::INFINITY, f64::min);
        unloading.push(UnloadingFit { d_max: m, d_end, force: uf, area: ua });
    }
    let c = Calibration {
        format: FORMAT.into(),
        description: table.description.clone().unwrap_or_else(|| "fitted by stiction calibrate".into()),
        provenance: table.provenance.clone().unwrap_or_else(|| "unknown (the table gave no provenance)".into()),
        work_of_adhesion: table
            .work_of_adhesion
            .ok_or("the table gives no '# work_of_adhesion: VALUE' line (or use --work-of-adhesion)")?,
        units: Units { length: "nm".into(), force: "nN".into(), area: "nm^2".into() },
        loading: LoadingFit { d_start: x_min(&load), d_end: x_max(&load), force: lf, area: la },
        unloading,
        fit: Some(quality),
    };
    c.validate()?;
    Ok(c)
}

fn x_min(rows: &[&Row]) -> f64 {
    rows.iter().map(|r| r.distance).fold(f64::INFINITY, f64::min)
}
fn x_max(rows: &[&Row]) -> f64 {
    rows.iter().map(|r| r.distance).fold(f64::NEG_INFINITY, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn least_squares_recovers_an_exact_polynomial() {
        let c = [3.0, -1.0, 0.5, 0.25, -0.125, 0.0625];
        let x: Vec<f64> = (0..40).map(|i| -1.2 + 0.08 * i as f64).collect();
        let y: Vec<f64> = x.iter().map(|&v| polynomial::value(&c, v)).collect();
        let fit = least_squares(&x, &y, 5).unwrap();
        for (a, b) in fit.iter().zip(&c) {
            assert!((a - b).abs() < 1e-9, "{fit:?}");
        }
    }

    #[test]
    fn table_errors_name_the_line() {
        let e = parse_table("distance,force,area,branch,max_distance\n0.1,2,3,sideways,0\n").unwrap_err();
        assert!(e.contains("line 2") && e.contains("sideways"), "{e}");
        let e = parse_table("d,f\n").unwrap_err();
        assert!(e.contains("line 1"), "{e}");
    }
}
