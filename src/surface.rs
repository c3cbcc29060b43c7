//! `stiction surface`: make a synthetic self-affine surface (`generate`), and measure a height
//! map's roughness, spectrum and summits (`stats`). The maths is in
//! [`stiction_interfaces::height_map`]; this module reads and writes the files and reports.

use plotters::prelude::*;
use std::path::{Path, PathBuf};
use stiction_interfaces::height_map::generate::{SelfAffine, generate as make};
use stiction_interfaces::height_map::spectrum::{HurstFit, Window, hurst_exponent};
use stiction_interfaces::height_map::summits::{Summit, SummitRule, SummitStatistics, find, statistics};
use stiction_interfaces::height_map::text::TextLayout;
use stiction_interfaces::height_map::{HeightMap, HeightMapError, gsf, text};

/// Why a surface command stopped: bad input (exit 2) or a file it could not write (exit 1).
#[derive(Debug, thiserror::Error)]
pub enum SurfaceError {
    #[error("{0}")]
    Input(String),
    #[error(transparent)]
    Map(#[from] HeightMapError),
    #[error("cannot write '{}': {message}", path.display())]
    Output { path: PathBuf, message: String },
}

impl SurfaceError {
    /// 1 for an output that could not be written, 2 for bad input (a map that cannot be read
    /// included).
    pub fn exit_code(&self) -> u8 {
        match self {
            SurfaceError::Output { .. } => 1,
            SurfaceError::Input(_) | SurfaceError::Map(_) => 2,
        }
    }
}

fn written(path: &Path) -> impl Fn(String) -> SurfaceError + '_ {
    move |message| SurfaceError::Output { path: path.to_path_buf(), message }
}

/// Makes the surface `spec` describes and writes it to `output` (`.gsf`).
pub fn generate(spec: &SelfAffine, output: &Path) -> Result<HeightMap, SurfaceError> {
    let map = make(spec).map_err(SurfaceError::Input)?;
    let title = format!(
        "self-affine surface: H = {}, roll-off {} {u}, cutoff {} {u}, seed {}",
        spec.hurst,
        spec.rolloff,
        spec.cutoff,
        spec.seed,
        u = spec.unit
    );
    let bytes = gsf::to_bytes(&map, &title);
    stiction_core::output::write_atomically(output, &bytes).map_err(|e| written(output)(e.to_string()))?;
    Ok(map)
}

/// How `stats` reads a map and picks its summits.
#[derive(Debug, Clone, PartialEq)]
pub struct StatsOptions {
    /// For a text map: its layout (a `.gsf` file says its own).
    pub layout: Option<TextLayout>,
    /// For a text map: the unit of its lengths and heights.
    pub unit: String,
    pub rule: SummitRule,
    /// The wavelengths the Hurst exponent is fitted between (None: 8 pixels to an eighth of
    /// the map's shorter side).
    pub fit_wavelengths: Option<(f64, f64)>,
    pub window: Window,
}

/// What `stats` measured.
#[derive(Debug, Clone, serde::Serialize)]
pub struct StatsReport {
    pub file: PathBuf,
    pub pixels: (usize, usize),
    pub pixel_size: (f64, f64),
    pub length_unit: String,
    pub height_unit: String,
    /// None: every summit counts.
    pub threshold: Option<f64>,
    pub min_spacing: f64,
    pub statistics: Option<SummitStatistics>,
    pub hurst: Option<HurstFit>,
    /// McCool's value of density x summit-height std x mean radius, for comparison.
    pub mccool_product: f64,
}

/// Reads the map at `path`: `.gsf` by its header, anything else as text laid out as `options`
/// says.
pub fn read_map(path: &Path, options: &StatsOptions) -> Result<HeightMap, SurfaceError> {
    if path.extension().is_some_and(|e| e.eq_ignore_ascii_case("gsf")) {
        return Ok(gsf::read(path)?);
    }
    let layout = options.layout.ok_or_else(|| {
        SurfaceError::Input(format!(
            "height map '{}': a text map needs its layout: --columns (x y z rows) or --pixel-size (a matrix of heights)",
            path.display()
        ))
    })?;
    Ok(text::read(path, layout, &options.unit)?)
}

/// Measures the map at `path`; with `out`, writes `summits.csv`, `surface-stats.json` and the
/// plots there. A map with no summit is refused before anything is written.
pub fn stats(path: &Path, options: &StatsOptions, out: Option<&Path>) -> Result<StatsReport, SurfaceError> {
    let map = read_map(path, options)?;
    let summits = find(&map, options.rule);
    let (lx, ly) = map.size();
    if let Some((shortest, longest)) = options.fit_wavelengths
        && !(shortest > 0.0 && longest > shortest)
    {
        return Err(SurfaceError::Input(format!(
            "--fit-wavelengths {shortest},{longest}: expected a positive shortest and a longer longest wavelength"
        )));
    }
    // by default 8 pixels to an eighth of the side: none on a map smaller than 64 pixels
    let range = options.fit_wavelengths.unwrap_or((8.0 * map.dx.max(map.dy), lx.min(ly) / 8.0));
    let report = StatsReport {
        file: path.to_path_buf(),
        pixels: (map.nx, map.ny),
        pixel_size: (map.dx, map.dy),
        length_unit: map.xy_unit.clone(),
        height_unit: map.z_unit.clone(),
        threshold: options.rule.threshold.is_finite().then_some(options.rule.threshold),
        min_spacing: options.rule.min_spacing,
        statistics: (!summits.is_empty()).then(|| statistics(&map, &summits)),
        hurst: (range.1 > range.0).then(|| hurst_exponent(&map, range, options.window)).flatten(),
        mccool_product: 0.019,
    };
    if summits.is_empty() {
        return Err(SurfaceError::Input(format!(
            "height map '{}': no pixel is higher than its 8 neighbours{}",
            path.display(),
            if options.rule.threshold.is_finite() {
                format!(" and {} {} above the mean (--threshold)", options.rule.threshold, map.z_unit)
            } else {
                String::new()
            }
        )));
    }
    if let Some(dir) = out {
        std::fs::create_dir_all(dir).map_err(|e| written(dir)(e.to_string()))?;
        write_summits(&dir.join("summits.csv"), &summits)?;
        let json = serde_json::to_string_pretty(&report).expect("the report serializes");
        let file = dir.join("surface-stats.json");
        stiction_core::output::write_atomically(&file, json.as_bytes()).map_err(|e| written(&file)(e.to_string()))?;
        for ext in ["png", "svg"] {
            let file = dir.join(format!("top-view.{ext}"));
            plot_top_view(&file, &map, &summits).map_err(written(&file))?;
            let file = dir.join(format!("summit-heights.{ext}"));
            plot_histogram(&file, &map, &summits).map_err(written(&file))?;
        }
    }
    Ok(report)
}

fn write_summits(path: &Path, summits: &[Summit]) -> Result<(), SurfaceError> {
    let mut text = String::from("x,y,height,radius\n");
    for s in summits {
        text.push_str(&format!("{:.9e},{:.9e},{:.9e},{:.9e}\n", s.x, s.y, s.height, s.radius));
    }
    stiction_core::output::write_atomically(path, text.as_bytes()).map_err(|e| written(path)(e.to_string()))
}

/// The map in grey levels with its summits as red dots: the PNG with at most 512 x 512 cells,
/// the SVG (a rectangle per cell) with at most 128 x 128; larger maps are sampled.
fn plot_top_view(path: &Path, map: &HeightMap, summits: &[Summit]) -> Result<(), String> {
    if path.extension().is_some_and(|e| e == "svg") {
        draw_top_view(SVGBackend::new(path, (720, 660)).into_drawing_area(), map, summits, 128)
    } else {
        draw_top_view(BitMapBackend::new(path, (720, 660)).into_drawing_area(), map, summits, 512)
    }
}

fn draw_top_view<DB: DrawingBackend>(
    root: DrawingArea<DB, plotters::coord::Shift>,
    map: &HeightMap,
    summits: &[Summit],
    max_cells: usize,
) -> Result<(), String> {
    let (lx, ly) = map.size();
    root.fill(&WHITE).map_err(|e| e.to_string())?;
    let mut chart = ChartBuilder::on(&root)
        .caption(format!("height map and its {} summits", summits.len()), ("sans-serif", 20))
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d(0.0..lx, 0.0..ly)
        .map_err(|e| e.to_string())?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc(format!("x ({})", map.xy_unit))
        .y_desc(format!("y ({})", map.xy_unit))
        .draw()
        .map_err(|e| e.to_string())?;
    let (lo, hi) = map.z.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &z| (a.min(z), b.max(z)));
    let step = map.nx.max(map.ny).div_ceil(max_cells);
    let cells = (0..map.ny).step_by(step).flat_map(|j| (0..map.nx).step_by(step).map(move |i| (i, j)));
    chart
        .draw_series(cells.map(|(i, j)| {
            let level = ((map.at(i, j) - lo) / (hi - lo).max(f64::MIN_POSITIVE) * 255.0) as u8;
            let (x, y) = (i as f64 * map.dx, j as f64 * map.dy);
            Rectangle::new(
                [(x, y), (x + step as f64 * map.dx, y + step as f64 * map.dy)],
                RGBColor(level, level, level).filled(),
            )
        }))
        .map_err(|e| e.to_string())?;
    chart.draw_series(summits.iter().map(|s| Circle::new((s.x, s.y), 2, RED.filled()))).map_err(|e| e.to_string())?;
    root.present().map_err(|e| e.to_string())
}

/// Histograms of the map's heights and of its summits' heights (each normalized to a density).
fn plot_histogram(path: &Path, map: &HeightMap, summits: &[Summit]) -> Result<(), String> {
    let mean = map.mean();
    let heights: Vec<f64> = map.z.iter().map(|z| z - mean).collect();
    let (lo, hi) = heights.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &z| (a.min(z), b.max(z)));
    let bins = 40;
    let width = (hi - lo).max(f64::MIN_POSITIVE) / bins as f64;
    let density = |values: &mut dyn Iterator<Item = f64>| {
        let mut counts = vec![0.0; bins];
        let mut n = 0.0;
        for v in values {
            counts[(((v - lo) / width) as usize).min(bins - 1)] += 1.0;
            n += 1.0;
        }
        counts.iter().map(|c| c / (n * width).max(f64::MIN_POSITIVE)).collect::<Vec<f64>>()
    };
    let all = density(&mut heights.iter().copied());
    let tops = density(&mut summits.iter().map(|s| s.height));
    let top = all.iter().chain(&tops).fold(0.0f64, |a, &b| a.max(b)) * 1.1;
    let data = Histograms { lo, width, top, all, tops, unit: &map.z_unit };
    if path.extension().is_some_and(|e| e == "svg") {
        draw_histograms(SVGBackend::new(path, (720, 480)).into_drawing_area(), &data)
    } else {
        draw_histograms(BitMapBackend::new(path, (720, 480)).into_drawing_area(), &data)
    }
}

struct Histograms<'a> {
    lo: f64,
    width: f64,
    top: f64,
    all: Vec<f64>,
    tops: Vec<f64>,
    unit: &'a str,
}

fn draw_histograms<DB: DrawingBackend>(
    root: DrawingArea<DB, plotters::coord::Shift>,
    h: &Histograms<'_>,
) -> Result<(), String> {
    root.fill(&WHITE).map_err(|e| e.to_string())?;
    let hi = h.lo + h.width * h.all.len() as f64;
    let mut chart = ChartBuilder::on(&root)
        .caption("heights and summit heights", ("sans-serif", 20))
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d(h.lo..hi, 0.0..h.top.max(f64::MIN_POSITIVE))
        .map_err(|e| e.to_string())?;
    chart
        .configure_mesh()
        .x_desc(format!("height above the mean ({})", h.unit))
        .y_desc(format!("probability density (1/{})", h.unit))
        .draw()
        .map_err(|e| e.to_string())?;
    for (values, colour, label) in [(&h.all, BLUE, "all pixels"), (&h.tops, RED, "summits")] {
        let line = values.iter().enumerate().map(|(k, &d)| (h.lo + (k as f64 + 0.5) * h.width, d));
        chart
            .draw_series(LineSeries::new(line, colour.stroke_width(2)))
            .map_err(|e| e.to_string())?
            .label(label)
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(2)));
    }
    chart.configure_series_labels().background_style(WHITE).border_style(BLACK).draw().map_err(|e| e.to_string())?;
    root.present().map_err(|e| e.to_string())
}
