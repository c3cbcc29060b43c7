//! Height maps in plain text: a matrix of heights (one row of pixels per line, the pixel size
//! given by the caller), or `x y z` columns on a regular grid (the pixel size read from it).
//! Lines that are empty or start with `#` are skipped; numbers are separated by spaces, tabs or
//! commas.

use super::{HeightMap, HeightMapError};
use std::path::Path;

/// What a text file holds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TextLayout {
    /// Rows of heights; the pixel size along x and y.
    Matrix { dx: f64, dy: f64 },
    /// `x y z` columns on a regular grid.
    Columns,
}

/// Reads a text height map laid out as `layout`, in `unit` (lengths and heights alike).
pub fn read(path: &Path, layout: TextLayout, unit: &str) -> Result<HeightMap, HeightMapError> {
    let text = std::fs::read_to_string(path).map_err(|source| HeightMapError::Io { path: path.into(), source })?;
    parse(&text, layout, unit).map_err(|what| HeightMapError::Format { path: path.into(), what })
}

/// The rows of numbers of `text`, each with its line number.
fn rows(text: &str) -> Result<Vec<(usize, Vec<f64>)>, String> {
    let mut out = Vec::new();
    for (k, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let numbers: Result<Vec<f64>, _> =
            line.split(|c: char| c.is_whitespace() || c == ',').filter(|s| !s.is_empty()).map(str::parse).collect();
        let numbers = numbers.map_err(|_| format!("line {}: '{line}' is not a row of numbers", k + 1))?;
        if let Some(bad) = numbers.iter().find(|x| !x.is_finite()) {
            return Err(format!("line {}: {bad} is not a finite number", k + 1));
        }
        out.push((k + 1, numbers));
    }
    Ok(out)
}

/// The map `text` holds, or what is wrong with it.
pub fn parse(text: &str, layout: TextLayout, unit: &str) -> Result<HeightMap, String> {
    let rows = rows(text)?;
    if rows.is_empty() {
        return Err("holds no numbers".into());
    }
    match layout {
        TextLayout::Matrix { dx, dy } => {
            let nx = rows[0].1.len();
            if let Some((line, row)) = rows.iter().find(|(_, r)| r.len() != nx) {
                return Err(format!("line {line}: {} heights where the first row has {nx}", row.len()));
            }
            let z = rows.iter().flat_map(|(_, r)| r.iter().copied()).collect();
            HeightMap::new((nx, rows.len()), (dx, dy), z, (unit, unit))
        }
        TextLayout::Columns => columns(&rows, unit),
    }
}

/// `x y z` rows on a regular grid: its distinct x and y values evenly spaced, every grid point
/// given once.
fn columns(rows: &[(usize, Vec<f64>)], unit: &str) -> Result<HeightMap, String> {
    if let Some((line, row)) = rows.iter().find(|(_, r)| r.len() != 3) {
        return Err(format!("line {line}: {} numbers where x y z columns have 3", row.len()));
    }
    let axis = |k: usize, name: &str| -> Result<(f64, f64, usize), String> {
        let mut values: Vec<f64> = rows.iter().map(|(_, r)| r[k]).collect();
        values.sort_by(f64::total_cmp);
        let span = values[values.len() - 1] - values[0];
        let tolerance = 1e-9 * span.max(1e-300);
        values.dedup_by(|a, b| (*a - *b).abs() <= tolerance);
        if values.len() < 2 {
            return Err(format!("all {name} are the same: a grid needs distinct values along both axes"));
        }
        let step = span / (values.len() - 1) as f64;
        if let Some(w) = values.windows(2).find(|w| ((w[1] - w[0]) - step).abs() > 1e-6 * step) {
            return Err(format!(
                "the grid is not regular: {name} steps from {} to {} where the mean step is {step}",
                w[0], w[1]
            ));
        }
        Ok((values[0], step, values.len()))
    };
    let ((x0, dx, nx), (y0, dy, ny)) = (axis(0, "x")?, axis(1, "y")?);
    if rows.len() != nx * ny {
        return Err(format!(
            "{} rows for a grid of {nx} x {ny} points: some points are missing or repeated",
            rows.len()
        ));
    }
    let mut z = vec![f64::NAN; nx * ny];
    for (line, r) in rows {
        let (i, j) = (((r[0] - x0) / dx).round() as usize, ((r[1] - y0) / dy).round() as usize);
        let cell = &mut z[j * nx + i];
        if !cell.is_nan() {
            return Err(format!("line {line}: the point ({}, {}) is given twice", r[0], r[1]));
        }
        *cell = r[2];
    }
    HeightMap::new((nx, ny), (dx, dy), z, (unit, unit))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_matrix_and_its_columns_give_the_same_map() {
        let matrix = "# heights\n1 2 3\n4, 5, 6\n\n7\t8\t9\n";
        let a = parse(matrix, TextLayout::Matrix { dx: 0.5, dy: 0.5 }, "nm").unwrap();
        let mut columns = String::new();
        for j in (0..3).rev() {
            for i in 0..3 {
                columns.push_str(&format!("{} {} {}\n", 10.0 + 0.5 * i as f64, -1.0 + 0.5 * j as f64, 3 * j + i + 1));
            }
        }
        let b = parse(&columns, TextLayout::Columns, "nm").unwrap();
        assert_eq!(a, b);
        assert_eq!(a.at(2, 1), 6.0);
    }

    #[test]
    fn ragged_rows_words_a_nan_an_irregular_grid_and_a_missing_point_are_named() {
        let m = TextLayout::Matrix { dx: 1.0, dy: 1.0 };
        assert_eq!(parse("1 2 3\n4 5\n1 2 3\n", m, "nm").unwrap_err(), "line 2: 2 heights where the first row has 3");
        assert_eq!(parse("1 2 x\n", m, "nm").unwrap_err(), "line 1: '1 2 x' is not a row of numbers");
        assert_eq!(parse("1 2 3\nNaN 1 1\n", m, "nm").unwrap_err(), "line 2: NaN is not a finite number");
        assert_eq!(parse("# nothing\n", m, "nm").unwrap_err(), "holds no numbers");
        let irregular = "0 0 1\n1 0 1\n3 0 1\n0 1 1\n1 1 1\n3 1 1\n0 2 1\n1 2 1\n3 2 1\n";
        let e = parse(irregular, TextLayout::Columns, "nm").unwrap_err();
        assert_eq!(e, "the grid is not regular: x steps from 0 to 1 where the mean step is 1.5");
        let missing = "0 0 1\n1 0 1\n2 0 1\n0 1 1\n1 1 1\n2 1 1\n0 2 1\n1 2 1\n";
        let e = parse(missing, TextLayout::Columns, "nm").unwrap_err();
        assert_eq!(e, "8 rows for a grid of 3 x 3 points: some points are missing or repeated");
    }
}
