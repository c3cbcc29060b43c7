//! Discrete interface points (e.g. asperities): read from a CSV file or generated, and written
//! back as CSV for reuse.

use crate::case::LoadedCase;
use crate::error::Result;

/// The discrete points of an interface: read from `file`, or generated.
pub(crate) fn discrete_points(
    case: &LoadedCase,
    key: &str,
    spec: &crate::case::PointsSpec,
) -> Result<(Vec<stiction_interfaces::DiscretePoint>, String)> {
    use stiction_interfaces::DiscretePoint;
    if let Some(file) = &spec.file {
        let path = case.base_dir().join(file);
        let text = std::fs::read_to_string(&path)
            .map_err(|e| case.error(format!("{key}.file"), format!("cannot read '{}': {e}", path.display())))?;
        let bad = |line: usize, m: String| {
            case.error(format!("{key}.file"), format!("'{}' line {line}: {m}", path.display()))
        };
        let mut lines =
            text.lines().enumerate().filter(|(_, l)| !l.trim().is_empty() && !l.trim_start().starts_with('#'));
        let (hl, header) = lines.next().ok_or_else(|| bad(1, "empty file".into()))?;
        if header.split(',').map(str::trim).collect::<Vec<_>>() != ["x", "y", "height"] {
            return Err(bad(hl + 1, format!("expected the header 'x,y,height', found '{header}'")));
        }
        let mut points = Vec::new();
        for (i, l) in lines {
            let v: Vec<f64> = l
                .split(',')
                .map(|x| x.trim().parse::<f64>())
                .collect::<std::result::Result<_, _>>()
                .map_err(|_| bad(i + 1, format!("expected three numbers, found '{l}'")))?;
            if v.len() != 3 {
                return Err(bad(i + 1, format!("expected three numbers, found '{l}'")));
            }
            points.push(DiscretePoint { in_plane: [v[0], v[1]], height: v[2] });
        }
        if points.is_empty() {
            return Err(bad(hl + 1, "no points".into()));
        }
        return Ok((points, format!("'{}'", path.display())));
    }
    let need = |v: Option<f64>, k: &str| {
        v.ok_or_else(|| case.error(format!("{key}.{k}"), "required to generate points (or give 'file')"))
    };
    let layout = stiction_interfaces::asperity_layout::LayoutSpec {
        density: need(spec.density, "density")?,
        region_radius: need(spec.region_radius, "region_radius")?,
        min_spacing: spec.min_spacing,
        height: need(spec.height, "height")?,
        height_std: spec.height_std,
        seed: spec.seed,
    };
    let placed = stiction_interfaces::asperity_layout::generate(&layout).map_err(|m| case.error(key, m))?;
    let points = placed.iter().map(|p| DiscretePoint { in_plane: p.in_plane, height: p.height }).collect();
    Ok((points, format!("the generated layout (seed {})", spec.seed)))
}

/// Writes discrete points as a CSV that a case can read back with `points.file`.
pub fn write_points_csv(path: &std::path::Path, points: &[stiction_interfaces::DiscretePoint]) -> std::io::Result<()> {
    let mut text = String::from("x,y,height\n");
    for p in points {
        text.push_str(&format!("{:.9},{:.9},{:.9}\n", p.in_plane[0], p.in_plane[1], p.height));
    }
    std::fs::write(path, text)
}
