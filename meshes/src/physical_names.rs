//! Reads the `$PhysicalNames` section (mshio skips it). The section is text in both ASCII and
//! binary MSH 4.1 files:
//! ```text
//! $PhysicalNames
//! numPhysicalNames
//! dimension physicalTag "name"
//! $EndPhysicalNames
//! ```

use crate::error::MeshError;
use std::path::Path;
use stiction_core::mesh::PhysicalGroup;

/// Parses the physical names of a MSH file's bytes (empty if the file has none).
pub fn parse_physical_names(path: &Path, bytes: &[u8]) -> Result<Vec<PhysicalGroup>, MeshError> {
    let marker = b"$PhysicalNames";
    let Some(start) = bytes.windows(marker.len()).position(|w| w == marker) else {
        return Ok(Vec::new());
    };
    let first_line = bytes[..start].iter().filter(|&&b| b == b'\n').count() + 1;
    let rest = &bytes[start..];
    let end_marker = b"$EndPhysicalNames";
    let end = rest.windows(end_marker.len()).position(|w| w == end_marker).ok_or_else(|| MeshError::ParseLine {
        path: path.to_path_buf(),
        line: first_line,
        message: "$PhysicalNames has no $EndPhysicalNames".into(),
    })?;
    let text = String::from_utf8_lossy(&rest[..end]);
    let mut lines = text.lines().enumerate().skip(1);
    let bad = |line: usize, message: String| MeshError::ParseLine {
        path: path.to_path_buf(),
        line: first_line + line,
        message,
    };
    let (ln, count_line) = lines.next().ok_or_else(|| bad(1, "missing the number of physical names".into()))?;
    let count: usize = count_line
        .trim()
        .parse()
        .map_err(|_| bad(ln, format!("expected the number of physical names, found '{}'", count_line.trim())))?;
    let mut groups = Vec::with_capacity(count);
    for _ in 0..count {
        let (ln, line) = lines.next().ok_or_else(|| bad(count + 2, format!("expected {count} physical names")))?;
        let mut parts = line.trim().splitn(3, char::is_whitespace);
        let dim = parts.next().and_then(|s| s.parse::<usize>().ok());
        let tag = parts.next().and_then(|s| s.parse::<i32>().ok());
        let name = parts.next().map(|s| s.trim().trim_matches('"').to_string());
        match (dim, tag, name) {
            (Some(dim), Some(tag), Some(name)) if dim <= 3 => groups.push(PhysicalGroup { name, dim, tag }),
            _ => {
                return Err(bad(ln, format!("expected 'dimension tag \"name\"', found '{}'", line.trim())));
            }
        }
    }
    Ok(groups)
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn reads_names_and_reports_bad_lines() {
        let ok = b"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n2\n2 1 \"flat face\"\n3 7 \"body\"\n$EndPhysicalNames\n";
        let g = parse_physical_names(Path::new("a.msh"), ok).unwrap();
        assert_eq!(g[0], PhysicalGroup { name: "flat face".into(), dim: 2, tag: 1 });
        assert_eq!(g[1].tag, 7);
        let bad = b"$PhysicalNames\n1\nx 1 \"a\"\n$EndPhysicalNames\n";
        let e = parse_physical_names(Path::new("b.msh"), bad).unwrap_err().to_string();
        assert!(e.contains("b.msh") && e.contains("line 3"), "{e}");
    }
}
