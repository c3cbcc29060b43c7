//! Gwyddion Simple Field files (`.gsf`, Gwyddion's user guide, "Simple Field Files"): the magic
//! line `Gwyddion Simple Field 1.0`, a text header of `name = value` lines (`XRes` and `YRes`
//! required; `XReal`, `YReal` the physical sizes, 1 when absent; `XYUnits`, `ZUnits`), one to
//! four NUL bytes aligning the data to a multiple of 4, then `XRes * YRes` little-endian 32-bit
//! floats, row by row.

use super::{HeightMap, HeightMapError};
use std::collections::BTreeMap;
use std::path::Path;

const MAGIC: &str = "Gwyddion Simple Field 1.0\n";

/// Reads a `.gsf` file.
pub fn read(path: &Path) -> Result<HeightMap, HeightMapError> {
    let bytes = std::fs::read(path).map_err(|source| HeightMapError::Io { path: path.into(), source })?;
    parse(&bytes).map_err(|what| HeightMapError::Format { path: path.into(), what })
}

/// The map a `.gsf` file's bytes hold, or what is wrong with them.
pub fn parse(bytes: &[u8]) -> Result<HeightMap, String> {
    if !bytes.starts_with(MAGIC.as_bytes()) {
        return Err(format!("does not start with the line '{}'", MAGIC.trim_end()));
    }
    let header_end = bytes.iter().position(|&b| b == 0).ok_or("the header ends with no NUL byte")?;
    let header = std::str::from_utf8(&bytes[MAGIC.len()..header_end]).map_err(|_| "the header is not UTF-8 text")?;
    let mut fields = BTreeMap::new();
    for (k, line) in header.lines().enumerate().filter(|(_, l)| !l.trim().is_empty()) {
        let (name, value) =
            line.split_once('=').ok_or_else(|| format!("header line {}: '{line}' is not 'name = value'", k + 2))?;
        fields.insert(name.trim().to_string(), value.trim().to_string());
    }
    let count = |name: &str| -> Result<usize, String> {
        let value = fields.get(name).ok_or_else(|| format!("the header has no {name}"))?;
        value
            .parse::<usize>()
            .ok()
            .filter(|&n| n > 0)
            .ok_or_else(|| format!("{name} = {value}: expected a positive integer"))
    };
    let (nx, ny) = (count("XRes")?, count("YRes")?);
    let real = |name: &str| -> Result<f64, String> {
        match fields.get(name) {
            None => Ok(1.0),
            Some(v) => v.parse::<f64>().map_err(|_| format!("{name} = {v}: expected a number")),
        }
    };
    let (x_real, y_real) = (real("XReal")?, real("YReal")?);
    let padding = 4 - header_end % 4;
    let data_start = header_end + padding;
    if bytes.len() < data_start || bytes[header_end..data_start].iter().any(|&b| b != 0) {
        return Err(format!("the header must end with {padding} NUL bytes aligning the data to a multiple of 4"));
    }
    let expected = nx * ny * 4;
    let data = &bytes[data_start..];
    if data.len() != expected {
        let how = if data.len() < expected { "truncated" } else { "too long" };
        return Err(format!(
            "{how}: {nx} x {ny} heights take {expected} bytes after the header, the file has {}",
            data.len()
        ));
    }
    let z = data.chunks_exact(4).map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]) as f64).collect();
    let unit = |name: &str| fields.get(name).cloned().unwrap_or_default();
    HeightMap::new((nx, ny), (x_real / nx as f64, y_real / ny as f64), z, (&unit("XYUnits"), &unit("ZUnits")))
}

/// The bytes of `map` as a `.gsf` file (heights rounded to 32-bit floats), titled `title`.
pub fn to_bytes(map: &HeightMap, title: &str) -> Vec<u8> {
    let (x_real, y_real) = map.size();
    let mut header = format!(
        "{MAGIC}XRes = {}\nYRes = {}\nXReal = {x_real:e}\nYReal = {y_real:e}\nXYUnits = {}\nZUnits = {}\nTitle = {title}\n",
        map.nx, map.ny, map.xy_unit, map.z_unit
    )
    .into_bytes();
    let padding = 4 - header.len() % 4;
    header.extend(std::iter::repeat_n(0u8, padding));
    header.extend(map.z.iter().flat_map(|&h| (h as f32).to_le_bytes()));
    header
}

/// Writes `map` to `path` as a `.gsf` file.
pub fn write(path: &Path, map: &HeightMap, title: &str) -> Result<(), HeightMapError> {
    std::fs::write(path, to_bytes(map, title)).map_err(|source| HeightMapError::Io { path: path.into(), source })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn map() -> HeightMap {
        let z = (0..12).map(|k| 0.25 * k as f64 - 1.0).collect();
        HeightMap::new((4, 3), (2.0, 0.5), z, ("nm", "nm")).unwrap()
    }

    #[test]
    fn a_map_written_reads_back_with_its_size_units_and_heights() {
        let bytes = to_bytes(&map(), "test");
        let header_end = bytes.iter().position(|&b| b == 0).unwrap();
        assert_eq!((bytes.len() - 12 * 4) % 4, 0, "the data start on a multiple of 4");
        assert!(bytes.len() - 12 * 4 - header_end >= 1);
        assert_eq!(parse(&bytes).unwrap(), map());
    }

    /// A file of `header` lines and `data`, padded as the format asks.
    fn file(header: &str, data: &[f32]) -> Vec<u8> {
        let mut bytes = format!("{MAGIC}{header}").into_bytes();
        let padding = 4 - bytes.len() % 4;
        bytes.extend(std::iter::repeat_n(0u8, padding));
        bytes.extend(data.iter().flat_map(|h| h.to_le_bytes()));
        bytes
    }

    #[test]
    fn a_bad_magic_a_missing_size_a_truncation_a_zero_pixel_and_a_nan_are_named() {
        let data = [0.5f32; 12];
        let header = "XRes = 4\nYRes = 3\nXReal = 8\nYReal = 1.5\n";
        assert_eq!(parse(&file(header, &data)).unwrap().dx, 2.0);
        assert!(parse(b"Gwyddion Simple Field 2.0\n").unwrap_err().contains("does not start"));
        assert_eq!(parse(&file("XRes = 4\nXReal = 8\n", &data)).unwrap_err(), "the header has no YRes");
        let e = parse(&file(header, &data[..11])).unwrap_err();
        assert_eq!(e, "truncated: 4 x 3 heights take 48 bytes after the header, the file has 44");
        let mut nan = data;
        nan[5] = f32::NAN;
        assert!(parse(&file(header, &nan)).unwrap_err().contains("pixel (x 1, y 1) is NaN"));
        let zero = "XRes = 4\nYRes = 3\nXReal = 0\n";
        assert!(parse(&file(zero, &data)).unwrap_err().contains("pixel size along x is 0"));
        let words = "XRes = four\nYRes = 3\n";
        assert_eq!(parse(&file(words, &data)).unwrap_err(), "XRes = four: expected a positive integer");
        let no_equals = "XRes = 4\nYRes 3\n";
        assert!(parse(&file(no_equals, &data)).unwrap_err().contains("line 3: 'YRes 3' is not 'name = value'"));
    }
}
