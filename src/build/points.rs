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
        let columns = header.split(',').map(str::trim).collect::<Vec<_>>();
        let with_radius = match columns[..] {
            ["x", "y", "height"] => false,
            ["x", "y", "height", "radius"] => true,
            _ => {
                return Err(bad(
                    hl + 1,
                    format!("expected the header 'x,y,height' or 'x,y,height,radius', found '{header}'"),
                ));
            }
        };
        let n = columns.len();
        let mut points = Vec::new();
        let mut line_of = Vec::new();
        for (i, l) in lines {
            let v: Vec<f64> = l
                .split(',')
                .map(|x| x.trim().parse::<f64>())
                .collect::<std::result::Result<_, _>>()
                .map_err(|_| bad(i + 1, format!("expected {n} numbers, found '{l}'")))?;
            if v.len() != n || v.iter().any(|x| !x.is_finite()) {
                return Err(bad(i + 1, format!("expected {n} finite numbers, found '{l}'")));
            }
            if with_radius && v[3] <= 0.0 {
                return Err(bad(i + 1, format!("the radius {} is not positive", v[3])));
            }
            points.push(DiscretePoint { in_plane: [v[0], v[1]], height: v[2], radius: with_radius.then(|| v[3]) });
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
    if let Some(map) = &spec.surface {
        return surface_summits(case, key, spec, map);
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
    let points =
        placed.iter().map(|p| DiscretePoint { in_plane: p.in_plane, height: p.height, radius: None }).collect();
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
    let with_radius = points.iter().any(|p| p.radius.is_some());
    let mut text = String::from(if with_radius { "x,y,height,radius\n" } else { "x,y,height\n" });
    for p in points {
        text.push_str(&format!("{:.9},{:.9},{:.9}", p.in_plane[0], p.in_plane[1], p.height));
        if with_radius {
            text.push_str(&format!(",{:.9e}", p.radius.unwrap_or(f64::NAN)));
        }
        text.push('\n');
    }
    stiction_core::output::write_atomically(path, text.as_bytes())
}

/// The summits of a height map (`points.surface`) within `region_radius` of the map point at
/// the pole, in the case's length unit: their offsets from that point, their heights above the
/// map's mean plane and their radii.
fn surface_summits(
    case: &LoadedCase,
    key: &str,
    spec: &crate::case::PointsSpec,
    surface: &crate::case::SurfaceMapSpec,
) -> Result<(Vec<stiction_interfaces::DiscretePoint>, String)> {
    use stiction_interfaces::DiscretePoint;
    use stiction_interfaces::height_map::{HeightMap, LENGTH_UNITS, gsf, metres_per_unit, summits, text};
    let file_key = format!("{key}.surface.file");
    let path = case.base_dir().join(&surface.file);
    let shown = path.display().to_string();
    let map: HeightMap = if path.extension().is_some_and(|e| e.eq_ignore_ascii_case("gsf")) {
        if surface.pixel_size.is_some() || surface.columns {
            return Err(case.error(
                format!("{key}.surface.{}", if surface.columns { "columns" } else { "pixel_size" }),
                format!(
                    "'{shown}' is a .gsf file, which states its own size: pixel_size and columns are for text maps"
                ),
            ));
        }
        gsf::read(&path).map_err(|e| case.error(&file_key, e.to_string()))?
    } else {
        let unit = surface.unit.clone().unwrap_or_default();
        let layout = match (surface.columns, surface.pixel_size) {
            (true, None) => text::TextLayout::Columns,
            (false, Some(d)) => text::TextLayout::Matrix { dx: d, dy: d },
            (true, Some(_)) => {
                return Err(case.error(
                    format!("{key}.surface.pixel_size"),
                    "x y z columns give their own pixel size: give columns = true or pixel_size, not both",
                ));
            }
            (false, None) => {
                return Err(case.error(
                    &file_key,
                    format!("'{shown}' is a text map: give its pixel_size (a matrix of heights) or columns = true (x y z rows)"),
                ));
            }
        };
        text::read(&path, layout, &unit).map_err(|e| case.error(&file_key, e.to_string()))?
    };
    // the map's units: the file's, else the case's `unit` key; then in the case's length unit
    let case_metres = crate::case::metres_per_length_unit(case, &format!("{key}.surface"))?;
    let factor = |stated: &str, what: &str| -> Result<f64> {
        let unit = if stated.trim().is_empty() { surface.unit.as_deref().unwrap_or("") } else { stated };
        if unit.is_empty() {
            return Err(case.error(
                format!("{key}.surface.unit"),
                format!("'{shown}' states no unit for its {what}: give unit = one of {LENGTH_UNITS}"),
            ));
        }
        let metres = metres_per_unit(unit).ok_or_else(|| {
            case.error(
                format!("{key}.surface.unit"),
                format!("'{shown}' gives its {what} in '{unit}', which is not one of {LENGTH_UNITS}"),
            )
        })?;
        Ok(metres / case_metres)
    };
    let case_unit = case.case.units.as_ref().map(|u| u.length.clone()).unwrap_or_default();
    let (in_plane, height) = (factor(&map.xy_unit, "lengths")?, factor(&map.z_unit, "heights")?);
    let centre = surface.centre.map(|c| [c[0] * in_plane, c[1] * in_plane]);
    let map = map.converted(in_plane, height, (&case_unit, &case_unit));
    let region = spec.region_radius.ok_or_else(|| {
        case.error(format!("{key}.region_radius"), "required with a height map: the summits within it are the points")
    })?;
    // the region must lie on the interior pixels (summits are found there)
    let (width, depth) = ((map.nx - 1) as f64 * map.dx, (map.ny - 1) as f64 * map.dy);
    let centre = centre.unwrap_or([width / 2.0, depth / 2.0]);
    let (lo, hi) = ([map.dx, map.dy], [width - map.dx, depth - map.dy]);
    if (0..2).any(|k| centre[k] - region < lo[k] || centre[k] + region > hi[k]) {
        return Err(case.error(
            &file_key,
            format!(
                "the map '{shown}' is smaller than the case's region: its interior spans x {:.4} to {:.4} and y {:.4} to {:.4} {case_unit}; the region of radius {region} around ({:.4}, {:.4}) needs x {:.4} to {:.4} and y {:.4} to {:.4}",
                lo[0],
                hi[0],
                lo[1],
                hi[1],
                centre[0],
                centre[1],
                centre[0] - region,
                centre[0] + region,
                centre[1] - region,
                centre[1] + region
            ),
        ));
    }
    let rule = summits::SummitRule { threshold: surface.threshold, min_spacing: spec.min_spacing };
    let found = summits::find(&map, rule);
    let points: Vec<DiscretePoint> = found
        .iter()
        .map(|s| ([s.x - centre[0], s.y - centre[1]], s))
        .filter(|(p, _)| p[0].hypot(p[1]) <= region)
        .map(|(p, s)| DiscretePoint { in_plane: p, height: s.height, radius: Some(s.radius) })
        .collect();
    if points.is_empty() {
        return Err(case.error(
            &file_key,
            format!(
                "no summit of '{shown}' lies within {region} {case_unit} of ({:.4}, {:.4}) at least {} {case_unit} above the mean plane ({} summits on the whole map)",
                centre[0],
                centre[1],
                surface.threshold,
                found.len()
            ),
        ));
    }
    let source = format!("the summits of height map '{shown}' ({} within the region)", points.len());
    Ok((points, source))
}
