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
        let mut line_of = Vec::new();
        for (i, l) in lines {
            let v: Vec<f64> = l
                .split(',')
                .map(|x| x.trim().parse::<f64>())
                .collect::<std::result::Result<_, _>>()
                .map_err(|_| bad(i + 1, format!("expected three numbers, found '{l}'")))?;
            if v.len() != 3 || v.iter().any(|x| !x.is_finite()) {
                return Err(bad(i + 1, format!("expected three finite numbers, found '{l}'")));
            }
            points.push(DiscretePoint { in_plane: [v[0], v[1]], height: v[2] });
            line_of.push(i + 1);
        }
        if points.is_empty() {
            return Err(bad(hl + 1, "no points".into()));
        }
        if let Some((a, b, distance, limit)) = closest_pair_below(&points, spec.min_spacing) {
            let what = if spec.min_spacing > 0.0 {
                format!("closer than the case's min_spacing = {}", spec.min_spacing)
            } else {
                format!("the same point (closer than {limit:.3e}, a billionth of the layout's extent)")
            };
            return Err(bad(
                line_of[b],
                format!("this point is {distance:.3e} from the one on line {}: {what}", line_of[a]),
            ));
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

/// The first pair of points (indices a < b, their in-plane distance and the limit) closer than
/// `min_spacing`, or, where that is 0, closer than a billionth of the layout's extent (a
/// duplicated row): sorted by x, each point against those within the limit in x.
fn closest_pair_below(
    points: &[stiction_interfaces::DiscretePoint],
    min_spacing: f64,
) -> Option<(usize, usize, f64, f64)> {
    let extent = points.iter().flat_map(|p| p.in_plane).fold(0.0f64, |m, x| m.max(x.abs()));
    // (a written layout's 9 decimals may put a pair at the spacing a hair below it)
    let limit = if min_spacing > 0.0 { min_spacing * (1.0 - 1e-6) } else { 1e-9 * extent.max(f64::MIN_POSITIVE) };
    let mut order: Vec<usize> = (0..points.len()).collect();
    order.sort_by(|&i, &j| points[i].in_plane[0].total_cmp(&points[j].in_plane[0]));
    let mut found: Option<(usize, usize, f64, f64)> = None;
    for (k, &i) in order.iter().enumerate() {
        for &j in &order[k + 1..] {
            let (p, q) = (points[i].in_plane, points[j].in_plane);
            if q[0] - p[0] >= limit {
                break;
            }
            let distance = (q[0] - p[0]).hypot(q[1] - p[1]);
            let pair = (i.min(j), i.max(j));
            if distance < limit && found.is_none_or(|f| pair < (f.0, f.1)) {
                found = Some((pair.0, pair.1, distance, limit));
            }
        }
    }
    found
}

/// Writes discrete points (atomically) as a CSV that a case can read back with `points.file`.
pub fn write_points_csv(
    path: &std::path::Path,
    points: &[stiction_interfaces::DiscretePoint],
) -> stiction_core::error::Result<()> {
    let mut text = String::from("x,y,height\n");
    for p in points {
        text.push_str(&format!("{:.9},{:.9},{:.9}\n", p.in_plane[0], p.in_plane[1], p.height));
    }
    stiction_core::output::write_atomically(path, text.as_bytes())
}
