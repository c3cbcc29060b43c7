//! The `stiction` command-line program.

use clap::{Parser, Subcommand};
use std::io::{IsTerminal, Write};
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use stiction::case;
use stiction::run::RunOptions;

#[derive(Parser)]
#[command(name = "stiction", version, about = "Implicit finite elements for adhesive and cohesive contact")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

/// A case file, where its output goes, and overrides of its keys.
#[derive(clap::Args)]
struct CaseInput {
    /// The case file (TOML).
    case: PathBuf,
    /// Output directory (default: the case's output.directory, else out/<name>).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Override any case key, e.g. --set steps.0.end_time=2 --set materials.ru.yield_stress=3.42
    #[arg(long = "set", value_name = "KEY=VALUE")]
    sets: Vec<String>,
}

#[derive(Subcommand)]
enum Command {
    /// Solve a case: writes history.csv (one row per converged increment, flushed as it goes),
    /// VTK files (<name>_NNNNN.vtu + <name>.pvd for ParaView) and summary.json.
    #[command(after_help = stiction::case::reference::defaults_list())]
    Run {
        #[command(flatten)]
        input: CaseInput,
        /// Never show progress, even on a terminal.
        #[arg(long)]
        quiet: bool,
        /// Replace an earlier run in the output folder (a non-empty folder is refused otherwise).
        #[arg(long, conflicts_with = "resume")]
        overwrite: bool,
        /// Go on with the run in the output folder from its checkpoint (restart.bin, written
        /// every output.checkpoint_minutes and when a run fails or is stopped). The case must
        /// describe the same problem; its [solver] settings, step increments, output spacing,
        /// output folder and checkpoint interval may change.
        #[arg(long)]
        resume: bool,
        /// Stop, as if interrupted (with a checkpoint), once this many increments are committed
        /// in all (at the first point between increments after that, no crossing under way): to
        /// split a long run into parts.
        #[arg(long, value_name = "N")]
        stop_after: Option<usize>,
    },
    /// Run the N members of a case's [ensemble] (each in DIR/member-NNN/) and aggregate them:
    /// mean, standard deviation and 95% confidence interval of every summary quantity
    /// (ensemble.json, ensemble.csv), mean force and area curves with bands, and the interval's
    /// width against N (plots). Running it again resumes, skipping completed members. Under
    /// `mpirun -n P` (a build with the cargo feature `mpi`) the members spread over the ranks.
    Ensemble {
        /// The case (its [ensemble] table), the output folder and overrides for every member.
        #[command(flatten)]
        input: CaseInput,
        /// Threads per member (default: the case's ensemble.threads_per_member; 0 = automatic).
        #[arg(long)]
        threads_per_member: Option<usize>,
        /// Members run at once on this machine (default: ensemble.concurrent_members; 0 = automatic).
        #[arg(long)]
        concurrent_members: Option<usize>,
        /// Report failed members only.
        #[arg(long)]
        quiet: bool,
    },
    /// Fit numeric case keys (law parameters, material constants, ...) to measured curves and
    /// summary numbers, with the FE model in the loop (Levenberg-Marquardt, finite-difference
    /// Jacobians whose runs go concurrently). Writes fit.json (values, 95% intervals, residuals
    /// per target), fit_history.csv, fit_<k>.png/.svg and fitted-<case>.toml to DIR. The fit
    /// file is described in docs/fitting.md. Under `mpirun -n P` (a build with the cargo feature
    /// `mpi`) the runs spread over the ranks.
    Fit {
        /// The fit file (TOML): cases, parameters, targets, optimizer.
        fit: PathBuf,
        /// The fit's folder (default: out/fit-<name>).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Go on with the fit in the folder: its completed runs are reused.
        #[arg(long, conflicts_with = "overwrite")]
        resume: bool,
        /// Replace an earlier fit in the folder.
        #[arg(long)]
        overwrite: bool,
        /// Do not report each run.
        #[arg(long)]
        quiet: bool,
    },
    /// Validate a case (schema, mesh, groups, materials, boundary conditions) without solving.
    Check {
        /// The case file (TOML)
        case: PathBuf,
        /// Override any case key before checking, as `stiction run --set` does, e.g.
        /// --set mesh.parameters.h_contact=10
        #[arg(long = "set", value_name = "KEY=VALUE")]
        sets: Vec<String>,
    },
    /// List the interface laws: built in, and plugins found on the search path (directories
    /// given here, then STICTION_PLUGIN_PATH, then the directory of this program).
    Plugins {
        /// Extra directories to search.
        #[arg(long = "plugin-path", value_name = "DIR")]
        dirs: Vec<PathBuf>,
    },
    /// Fit an asperity calibration (loading and unloading polynomials) from a table of
    /// distance, force, area, branch and maximum distance (e.g. an MD run's output), report the
    /// fit quality and write the calibration TOML.
    Calibrate {
        /// CSV table: header distance,force,area,branch,max_distance; '# key: value' comment lines
        /// may give work_of_adhesion, description, provenance.
        table: PathBuf,
        /// Output calibration file.
        #[arg(short, long)]
        output: PathBuf,
        /// Order of the loading polynomials.
        #[arg(long, default_value_t = 4)]
        loading_order: usize,
        /// Order of the unloading polynomials.
        #[arg(long, default_value_t = 5)]
        unloading_order: usize,
        /// Work of adhesion (J/m^2) if the table does not state it.
        #[arg(long)]
        work_of_adhesion: Option<f64>,
    },
    /// Overlay the force and contact-area histories of several runs (e.g. rough vs smooth) in
    /// PNG and SVG plots.
    Plot {
        /// Run output directories (each with a history.csv that has interface columns).
        runs: Vec<PathBuf>,
        /// Directory for the plots.
        #[arg(short, long)]
        output: PathBuf,
        /// Plot title.
        #[arg(long, default_value = "comparison")]
        title: String,
    },
    /// Write the documented SURROGATE nano-asperity table (not MD) for a work of adhesion.
    SurrogateTable {
        /// Work of adhesion in J/m^2.
        #[arg(long)]
        work_of_adhesion: f64,
        /// Output CSV.
        #[arg(short, long)]
        output: PathBuf,
        /// Samples per branch.
        #[arg(long, default_value_t = 60)]
        samples: usize,
    },
    /// Print a reference generated from the program itself (docs/reference/ holds the same).
    Reference {
        #[command(subcommand)]
        what: ReferenceCommand,
    },
    /// Plugin tools.
    Plugin {
        #[command(subcommand)]
        command: PluginCommand,
    },
    /// Rough surfaces as height maps: make a synthetic one, measure one.
    Surface {
        #[command(subcommand)]
        command: SurfaceCommand,
    },
    /// Run the nano-asperity experiment with LAMMPS (an fcc asperity on a substrate pressed by
    /// a flat counter-body to each maximum approach and pulled back), measure the work of
    /// adhesion across the interface (scaled as the file asks), and write the force and contact
    /// area against the approach as the table `stiction calibrate` reads (force-distance.csv:
    /// nm, nN, nm^2), beside the LAMMPS input, data file, log and atom dumps. Needs `lmp`
    /// (Debian: lammps lammps-data) or STICTION_LAMMPS. The MD file's keys: docs/md.md.
    Md {
        /// The MD file (TOML: [lattice], [substrate], [asperity], [counter], [potential],
        /// optional [adhesion], [run]).
        file: PathBuf,
        /// Output folder (default: out/md-<file stem>).
        #[arg(long)]
        out: Option<PathBuf>,
    },
}

#[derive(Subcommand)]
enum SurfaceCommand {
    /// Make a self-affine rough surface by the random-phase spectral method (a spectrum flat
    /// below the roll-off wavelength, falling as q^(-2 (1 + H)) to the cutoff wavelength, zero
    /// beyond; random phases from the seed) and write it as a Gwyddion Simple Field file.
    Generate {
        /// The `.gsf` file to write.
        #[arg(short, long)]
        output: PathBuf,
        /// The Hurst exponent H (0 < H < 1).
        #[arg(long)]
        hurst: f64,
        /// The rms height (give this or --rms-slope).
        #[arg(long, required_unless_present = "rms_slope", conflicts_with = "rms_slope")]
        rms_height: Option<f64>,
        /// The rms slope |grad z| (by central differences).
        #[arg(long)]
        rms_slope: Option<f64>,
        /// The side of the square map.
        #[arg(long)]
        size: f64,
        /// Pixels along each side (even, at least 8).
        #[arg(long)]
        pixels: usize,
        /// The roll-off wavelength (default: a quarter of the size).
        #[arg(long)]
        rolloff: Option<f64>,
        /// The shortest wavelength (default: four pixels).
        #[arg(long)]
        cutoff: Option<f64>,
        /// The seed of the random phases.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// The unit of the lengths and heights, written in the file.
        #[arg(long, default_value = "nm")]
        unit: String,
    },
    /// Measure a height map (`.gsf`, or text with --columns or --pixel-size): rms height and
    /// slope, the Hurst exponent from its spectrum, and its summits (pixels higher than their 8
    /// neighbours) with their density, height spread and radii; with --out, summits.csv,
    /// surface-stats.json, top-view.png/.svg and summit-heights.png/.svg.
    Stats {
        /// The height map.
        file: PathBuf,
        /// A text map of x y z rows on a regular grid.
        #[arg(long, conflicts_with = "pixel_size")]
        columns: bool,
        /// A text map of rows of heights, with this pixel size.
        #[arg(long)]
        pixel_size: Option<f64>,
        /// The unit of a text map's lengths and heights.
        #[arg(long, default_value = "nm")]
        unit: String,
        /// Summits lower than this above the mean height are left out (default: none).
        #[arg(long, allow_negative_numbers = true)]
        threshold: Option<f64>,
        /// Of two summits closer than this, the lower is left out.
        #[arg(long, default_value_t = 0.0)]
        min_spacing: f64,
        /// The wavelengths the Hurst exponent is fitted between, "shortest,longest" (default: 8
        /// pixels to an eighth of the map's side).
        #[arg(long, value_delimiter = ',', num_args = 2)]
        fit_wavelengths: Option<Vec<f64>>,
        /// No window before the transform: for a periodic map (a generated one); a measured
        /// map takes the Hann window (the default).
        #[arg(long)]
        periodic: bool,
        /// Folder for summits.csv, surface-stats.json and the plots.
        #[arg(long)]
        out: Option<PathBuf>,
    },
}

#[derive(Subcommand)]
enum ReferenceCommand {
    /// Every case-file key: its value type, default, unit, allowed range, what it applies to and
    /// what it means (Markdown; docs/reference/case-keys.md).
    CaseKeys,
    /// Every fit-file key (`stiction fit`), likewise (Markdown; docs/reference/fit-keys.md).
    FitKeys,
}

#[derive(Subcommand)]
enum PluginCommand {
    /// Conformance run for a law (a name or a library path): tangent vs finite differences along
    /// a load-unload-reload path, determinism, state round trip, zero and extreme gaps.
    Check {
        /// Law name or path to a plugin library.
        law: String,
        /// Parameter values (required ones that have no default must be given).
        #[arg(long = "param", value_name = "NAME=VALUE")]
        params: Vec<String>,
        /// Configuration file for laws that take one (e.g. a calibration).
        #[arg(long = "config-file")]
        config_file: Option<PathBuf>,
        /// Gap scale of the test path (the law's length scale, e.g. z0).
        #[arg(long, default_value_t = 1.0)]
        gap_scale: f64,
        /// Extra directories to search.
        #[arg(long = "plugin-path", value_name = "DIR")]
        dirs: Vec<PathBuf>,
    },
}

fn describe(l: &stiction_interfaces::plugin::LawLibrary, origin: Option<&str>) {
    use stiction::case::reference::number;
    let gap = if l.gap_dimension == 3 { "mixed mode: normal and tangential opening" } else { "normal gap" };
    let kind = match l.kind {
        stiction_core::interface_law::LawKind::TractionPerArea => "traction per area",
        stiction_core::interface_law::LawKind::ForcePerPoint => "force per point",
    };
    let origin = origin.map(|o| format!(" [{o}]")).unwrap_or_default();
    println!("  {} {} ({kind}, {gap}, {} state variables){origin}", l.name, l.version, l.n_state);
    if let Some(c) = &l.config_description {
        println!("      config_file: {c}");
    }
    let bound = |x: f64| if x.is_infinite() { "inf".to_string() } else { number(x) };
    for p in &l.parameters {
        let default = p.default.map(|d| format!("default {}", number(d))).unwrap_or_else(|| "required".into());
        println!(
            "      {} [{}]: {}; {default}; range [{}, {}]",
            p.name,
            p.unit,
            p.description,
            bound(p.min),
            bound(p.max)
        );
    }
}

/// Every law once: the built-in ones, then the plugins found; a plugin library of a built-in
/// law's name (the built-in laws' own plugin builds sit in target/release) is named under it,
/// since a case that names the law gets the built-in one.
fn list_plugins(dirs: &[PathBuf]) {
    let registry = stiction::laws::LawRegistry::new(dirs);
    let found = registry.discover();
    let builtin_names: Vec<&str> = registry.builtin().iter().map(|l| l.name.as_str()).collect();
    println!("built-in laws (a case names them with law = \"NAME\"):");
    for l in registry.builtin() {
        describe(l, None);
        for (path, r) in &found {
            if r.as_ref().is_ok_and(|p| p.name == l.name) {
                println!(
                    "      also found as a plugin library: {} (used only when a case gives its path)",
                    path.display()
                );
            }
        }
    }
    let dirs: Vec<String> = registry.search_dirs().iter().map(|d| d.display().to_string()).collect();
    println!("plugins on the search path [{}]:", dirs.join(", "));
    let mut any = false;
    for (path, r) in &found {
        match r {
            Ok(l) if builtin_names.contains(&l.name.as_str()) => {}
            Ok(l) => {
                any = true;
                describe(l, Some(&path.display().to_string()));
            }
            Err(e) => {
                any = true;
                println!("  {}: not usable: {e}", path.display());
            }
        }
    }
    if !any {
        println!("  (none besides the built-in laws)");
    }
}

fn plugin_check(law: &str, params: &[String], config: Option<PathBuf>, gap_scale: f64, dirs: &[PathBuf]) -> ExitCode {
    let registry = stiction::laws::LawRegistry::new(dirs);
    let mut given = Vec::new();
    for p in params {
        match p.split_once('=').map(|(k, v)| (k.trim(), v.trim().parse::<f64>())) {
            Some((k, Ok(v))) => given.push((k.to_string(), v)),
            _ => {
                eprintln!("error: --param {p}: expected NAME=NUMBER");
                return ExitCode::from(2);
            }
        }
    }
    if !(gap_scale > 0.0) {
        eprintln!("error: --gap-scale must be positive");
        return ExitCode::from(2);
    }
    let context = stiction::laws::LawContext { modulus: 1.0, face_size: 1.0 };
    let instance = match stiction::laws::make_law(
        &registry,
        law,
        std::path::Path::new("."),
        &given,
        config.as_deref(),
        &context,
    ) {
        Ok(l) => l,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    println!("checking law '{}' (gap scale {gap_scale})", instance.name());
    let results = stiction::plugin_check::check(&instance, gap_scale);
    let failed = results.iter().filter(|r| !r.passed && !r.informative).count();
    let checks = results.iter().filter(|r| !r.informative).count();
    for r in &results {
        let tag = if r.informative {
            "INFO"
        } else if r.passed {
            "PASS"
        } else {
            "FAIL"
        };
        println!("  {tag} {}: {}", r.name, r.detail);
    }
    println!("{} passed, {} failed", checks - failed, failed);
    if failed == 0 { ExitCode::SUCCESS } else { ExitCode::from(1) }
}

/// `stiction plot`: the force and area curves of several runs overlaid.
fn plot_runs(runs: &[PathBuf], output: &std::path::Path, title: &str) -> ExitCode {
    let mut curves = Vec::new();
    for r in runs {
        let label = r.file_name().and_then(|s| s.to_str()).unwrap_or("run").to_string();
        match stiction::plots::read_history(&r.join("history.csv"), &label) {
            Some(c) => curves.push(c),
            None => {
                eprintln!("error: '{}' has no history.csv with approach, force and contact_area columns", r.display());
                return ExitCode::from(2);
            }
        }
    }
    if let Err(e) = std::fs::create_dir_all(output)
        .map_err(|e| e.to_string())
        .and_then(|_| stiction::plots::plot_curves(output, "", title, &curves))
    {
        eprintln!("error: {e}");
        return ExitCode::from(1);
    }
    println!("wrote {}/force_approach.png/.svg and area_approach.png/.svg", output.display());
    ExitCode::SUCCESS
}

/// `stiction md`.
fn md(file: &std::path::Path, out: Option<PathBuf>) -> ExitCode {
    let stem = file.file_stem().map_or("md".into(), |s| s.to_string_lossy().to_string());
    let out = out.unwrap_or_else(|| PathBuf::from("out").join(format!("md-{stem}")));
    match stiction::md::run(file, &out) {
        Ok(r) => {
            println!(
                "{}: {} atoms ({} in the asperity, {} in its base plane); work of adhesion {:.3} J/m^2 (cross scale {:.4}, (001) flats at 0 K)",
                file.display(),
                r.atoms,
                r.asperity_atoms,
                r.base_atoms,
                r.work_of_adhesion,
                r.cross_scale,
            );
            for b in &r.branches {
                match b.separated_at {
                    Some(d) => println!(
                        "unloading from {:.3} nm: the neck broke at {d:.3} nm; {} atoms went with the counter-body",
                        b.max_distance, b.detached
                    ),
                    None if !b.touched => {
                        println!("unloading from {:.3} nm: no neck at all (no contact on the branch)", b.max_distance)
                    }
                    None => println!(
                        "unloading from {:.3} nm: not separated at {:.3} nm (neck {:.3} nm^2, force {:.3} nN): pull back farther (run.pull_back)",
                        b.max_distance, b.last.0, b.last.1, b.last.2
                    ),
                }
            }
            println!(
                "force on the asperity from {:.3} to {:.3} nN; table in {}",
                r.min_force,
                r.max_force,
                out.join("force-distance.csv").display()
            );
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(e.exit_code())
        }
    }
}

/// `stiction surface generate` and `stats`.
fn surface(command: SurfaceCommand) -> ExitCode {
    use stiction::surface::{StatsOptions, SurfaceError};
    use stiction_interfaces::height_map::generate::{Amplitude, SelfAffine};
    use stiction_interfaces::height_map::spectrum::Window;
    use stiction_interfaces::height_map::summits::SummitRule;
    use stiction_interfaces::height_map::text::TextLayout;
    let result = match command {
        SurfaceCommand::Generate {
            output,
            hurst,
            rms_height,
            rms_slope,
            size,
            pixels,
            rolloff,
            cutoff,
            seed,
            unit,
        } => {
            let amplitude = match (rms_height, rms_slope) {
                (Some(h), _) => Amplitude::RmsHeight(h),
                (None, Some(s)) => Amplitude::RmsSlope(s),
                (None, None) => unreachable!("clap asks for one"),
            };
            let spec = SelfAffine {
                hurst,
                amplitude,
                size,
                pixels,
                rolloff: rolloff.unwrap_or(size / 4.0),
                cutoff: cutoff.unwrap_or(4.0 * size / pixels.max(1) as f64),
                seed,
                unit,
            };
            stiction::surface::generate(&spec, &output).map(|map| {
                println!(
                    "wrote {}: {} x {} pixels of {} {u}, rms height {:.4} {u}, rms slope {:.4}",
                    output.display(),
                    map.nx,
                    map.ny,
                    map.dx,
                    map.rms_height(),
                    map.rms_slope(),
                    u = spec.unit
                );
            })
        }
        SurfaceCommand::Stats {
            file,
            columns,
            pixel_size,
            unit,
            threshold,
            min_spacing,
            fit_wavelengths,
            periodic,
            out,
        } => {
            let layout = match (columns, pixel_size) {
                (true, _) => Some(TextLayout::Columns),
                (false, Some(d)) => Some(TextLayout::Matrix { dx: d, dy: d }),
                (false, None) => None,
            };
            let options = StatsOptions {
                layout,
                unit,
                rule: SummitRule { threshold: threshold.unwrap_or(f64::NEG_INFINITY), min_spacing },
                fit_wavelengths: fit_wavelengths.map(|w| (w[0], w[1])),
                window: if periodic { Window::None } else { Window::Hann },
            };
            stiction::surface::stats(&file, &options, out.as_deref()).map(|r| print_stats(&r))
        }
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            let e: SurfaceError = e;
            eprintln!("error: {e}");
            ExitCode::from(e.exit_code())
        }
    }
}

fn print_stats(r: &stiction::surface::StatsReport) {
    let (l, h) = (&r.length_unit, &r.height_unit);
    println!(
        "{}: {} x {} pixels of {} x {} {l}",
        r.file.display(),
        r.pixels.0,
        r.pixels.1,
        r.pixel_size.0,
        r.pixel_size.1
    );
    if let Some(s) = &r.statistics {
        println!("  rms height {:.4} {h}, rms slope {:.4}", s.rms_height, s.rms_slope);
        println!(
            "  {} summits: density {:.4e} per {l}^2, height {:.4} +- {:.4} {h} above the mean, mean radius {:.4} {l}",
            s.summits, s.density, s.mean_summit_height, s.summit_height_std, s.mean_radius
        );
        println!(
            "  density x summit-height std x mean radius: {:.4} (McCool's {})",
            s.density_std_radius, r.mccool_product
        );
    }
    match &r.hurst {
        Some(f) => println!(
            "  Hurst exponent {:.3} +- {:.3} (spectrum over wavelengths {} to {} {l}, {} rings)",
            f.hurst, f.standard_error, f.shortest, f.longest, f.rings
        ),
        None => println!("  Hurst exponent: fewer than 3 spectrum rings between the fit's wavelengths"),
    }
}

fn calibrate(table: &std::path::Path, output: &std::path::Path, lo: usize, uo: usize, w: Option<f64>) -> ExitCode {
    use stiction_law_ru_asperity::fit;
    let text = match std::fs::read_to_string(table) {
        Ok(t) => t,
        Err(e) => {
            eprintln!("error: cannot read '{}': {e}", table.display());
            return ExitCode::from(2);
        }
    };
    let mut parsed = match fit::parse_table(&text) {
        Ok(t) => t,
        Err(e) => {
            eprintln!("error: '{}': {e}", table.display());
            return ExitCode::from(2);
        }
    };
    if w.is_some() {
        parsed.work_of_adhesion = w;
    }
    let calibration = match fit::fit(&parsed, lo, uo) {
        Ok(c) => c,
        Err(e) => {
            eprintln!("error: '{}': {e}", table.display());
            return ExitCode::from(2);
        }
    };
    let q = calibration.fit.clone().unwrap_or_default();
    println!(
        "loading (order {lo}, d in [{:.3}, {:.3}] nm): force rms {:.4} nN, max {:.4} nN; area rms {:.4} nm^2",
        calibration.loading.d_start,
        calibration.loading.d_end,
        q.loading_force_rms,
        q.loading_force_max,
        q.loading_area_rms
    );
    for (i, u) in calibration.unloading.iter().enumerate() {
        println!(
            "unloading from d_max = {:.3} nm (order {uo}, separation at {:.3} nm): force rms {:.4} nN, max {:.4} nN; area rms {:.4} nm^2",
            u.d_max, u.d_end, q.unloading_force_rms[i], q.unloading_force_max[i], q.unloading_area_rms[i]
        );
    }
    let header = format!(
        "Asperity calibration written by `stiction calibrate {}`.\n{}\nProvenance: {}",
        table.display(),
        calibration.description,
        calibration.provenance
    );
    if let Err(e) = stiction_core::output::write_atomically(output, calibration.to_toml(&header).as_bytes()) {
        eprintln!("error: cannot write '{}': {e}", output.display());
        return ExitCode::from(1);
    }
    println!("wrote {}", output.display());
    match stiction::plots::plot_calibration(output, &parsed, &calibration) {
        Ok(()) => println!(
            "plots of data vs fits: {}_force.png/.svg, {}_area.png/.svg",
            output.with_extension("").display(),
            output.with_extension("").display()
        ),
        Err(e) => eprintln!("warning: plots not written: {e}"),
    }
    ExitCode::SUCCESS
}

/// What a run, an ensemble or a fit does on a first Ctrl-C.
const INCREMENT: &str = "finishing the current increment";

/// A flag set by the first Ctrl-C (SIGINT, or SIGTERM as a batch system sends): a run stops
/// after the increment in progress and writes its summary; gmsh, while it meshes, is stopped.
/// A second Ctrl-C ends the program at once (exit status 130); the files of every committed
/// increment are complete either way, as each is written atomically. `then` says what the
/// program does next.
fn interrupt_on_ctrl_c(then: &'static str) -> Arc<AtomicBool> {
    let flag = stiction::resources::interrupt_flag();
    let seen = flag.clone();
    let installed = ctrlc::set_handler(move || {
        if seen.swap(true, Ordering::SeqCst) {
            std::process::exit(130);
        }
        eprintln!("\nstiction: interrupted; {then} (Ctrl-C again to stop at once)");
    });
    if let Err(e) = installed {
        eprintln!("warning: Ctrl-C will end the run without a summary: {e}");
    }
    flag
}

/// `stiction ensemble`: over MPI ranks when an MPI launcher started this program (a build with
/// the `mpi` feature), else on this machine; rank 0 (or the only process) prints the table.
fn run_ensemble(
    case: &std::path::Path,
    sets: &[String],
    options: &stiction::ensemble::EnsembleOptions,
) -> Result<(), stiction::StictionError> {
    #[cfg(feature = "mpi")]
    let aggregate = if stiction::ensemble::mpi::launched_under_mpi() {
        stiction::ensemble::mpi::run_ensemble_mpi(case, sets, options)?
    } else {
        Some(stiction::ensemble::run_ensemble(case, sets, options)?)
    };
    #[cfg(not(feature = "mpi"))]
    let aggregate = Some(stiction::ensemble::run_ensemble(case, sets, options)?);
    if let Some(a) = aggregate {
        for line in stiction::ensemble::lines(&a) {
            println!("{line}");
        }
    }
    Ok(())
}

type Outcome = Result<(), stiction::StictionError>;

/// `stiction run`: the case (or its sweep), a summary per run on standard output.
fn run_command(input: CaseInput, quiet: bool, overwrite: bool, resume: bool, stop_after: Option<usize>) -> Outcome {
    let CaseInput { case, out, sets } = input;
    let options = RunOptions {
        out,
        progress: !quiet && std::io::stderr().is_terminal(),
        progress_label: None,
        overwrite,
        interrupt: Some(interrupt_on_ctrl_c(INCREMENT)),
        resume,
        stop_after_increments: stop_after,
        stop_after_flow_steps: None,
    };
    for summary in stiction::sweep::run_sweep(&case, &sets, &options)? {
        // a closed stdout (e.g. `| head -1`) is not an error of the run
        let mut out = std::io::stdout().lock();
        for line in stiction::report::summary_lines(&summary) {
            if writeln!(out, "{line}").is_err() {
                break;
            }
        }
    }
    Ok(())
}

/// `stiction fit`: over MPI ranks when an MPI launcher started this program (a build with the
/// `mpi` feature), else on this machine; rank 0 (or the only process) prints the report.
fn fit_command(fit: &std::path::Path, options: stiction::fit::FitOptions) -> Outcome {
    #[cfg(feature = "mpi")]
    let report = if stiction::ensemble::mpi::launched_under_mpi() {
        stiction::fit::mpi::run_fit_mpi(fit, &options)?
    } else {
        Some(stiction::fit::run_fit(fit, &options)?)
    };
    #[cfg(not(feature = "mpi"))]
    let report = Some(stiction::fit::run_fit(fit, &options)?);
    for line in report.iter().flat_map(stiction::fit::lines) {
        println!("{line}");
    }
    Ok(())
}

/// `stiction check`: loads and builds the case (meshing it if needed) and prints its size.
fn check_command(case_file: &std::path::Path, sets: &[String]) -> Outcome {
    // a check meshes too: interrupted, it stops gmsh rather than leaving it running
    interrupt_on_ctrl_c("stopping the check");
    let loaded = case::load(case_file, sets)?;
    let built = stiction::build::build(&loaded)?;
    let m = &built.model;
    println!(
        "{}: ok ({} nodes, {} cells in {} element sets, {} free dofs, {} matrix entries, mesh {})",
        loaded.name,
        m.mesh.nodes.len(),
        m.sets.iter().map(|s| s.n_cells()).sum::<usize>(),
        m.sets.len(),
        m.n_free(),
        m.pattern().nnz(),
        built.mesh_path.display()
    );
    for w in m.contributions.iter().flat_map(|c| c.warnings()) {
        eprintln!("warning: {w}");
    }
    Ok(())
}

/// `stiction surrogate-table`: the surrogate asperity table for one work of adhesion.
fn surrogate_table(work_of_adhesion: f64, output: &std::path::Path, samples: usize) -> ExitCode {
    if !(work_of_adhesion > 0.0) || samples < 10 {
        eprintln!("error: --work-of-adhesion must be positive and --samples at least 10");
        return ExitCode::from(2);
    }
    let text = stiction_law_ru_asperity::surrogate::table(work_of_adhesion, samples);
    if let Err(e) = std::fs::write(output, text) {
        eprintln!("error: cannot write '{}': {e}", output.display());
        return ExitCode::from(1);
    }
    println!("wrote the SURROGATE (not MD) asperity table for w = {work_of_adhesion} J/m^2 to {}", output.display());
    ExitCode::SUCCESS
}

/// `stiction plugins`: the laws built in and found on the search path.
fn plugins_command(dirs: &[PathBuf]) -> ExitCode {
    if let Some(file) = dirs.iter().find(|d| d.exists() && !d.is_dir()) {
        eprintln!("error: --plugin-path '{}' is a file; give folders that hold plugin libraries", file.display());
        return ExitCode::from(2);
    }
    list_plugins(dirs);
    ExitCode::SUCCESS
}

fn main() -> ExitCode {
    // Rust ignores SIGPIPE, so printing to a closed pipe (`stiction plugins | head`) panics;
    // the default action ends the program quietly, as other command-line tools do
    #[cfg(unix)]
    // SAFETY: sets a signal's action to the default before any thread starts
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    let result = match Cli::parse().command {
        Command::Run { input, quiet, overwrite, resume, stop_after } => {
            run_command(input, quiet, overwrite, resume, stop_after)
        }
        Command::Ensemble { input: CaseInput { case, out, sets }, threads_per_member, concurrent_members, quiet } => {
            let interrupt = Some(interrupt_on_ctrl_c(INCREMENT));
            let options =
                stiction::ensemble::EnsembleOptions { out, threads_per_member, concurrent_members, interrupt, quiet };
            run_ensemble(&case, &sets, &options)
        }
        Command::Fit { fit, out, resume, overwrite, quiet } => {
            let interrupt = Some(interrupt_on_ctrl_c(INCREMENT));
            fit_command(&fit, stiction::fit::FitOptions { out, resume, overwrite, interrupt, quiet })
        }
        Command::Check { case, sets } => check_command(&case, &sets),
        Command::Calibrate { table, output, loading_order, unloading_order, work_of_adhesion } => {
            return calibrate(&table, &output, loading_order, unloading_order, work_of_adhesion);
        }
        Command::Plot { runs, output, title } => return plot_runs(&runs, &output, &title),
        Command::SurrogateTable { work_of_adhesion, output, samples } => {
            return surrogate_table(work_of_adhesion, &output, samples);
        }
        Command::Reference { what: ReferenceCommand::CaseKeys } => {
            print!("{}", case::reference::case_keys_markdown());
            Ok(())
        }
        Command::Reference { what: ReferenceCommand::FitKeys } => {
            print!("{}", stiction::fit::spec::fit_keys_markdown());
            Ok(())
        }
        Command::Plugins { dirs } => return plugins_command(&dirs),
        Command::Plugin { command: PluginCommand::Check { law, params, config_file, gap_scale, dirs } } => {
            return plugin_check(&law, &params, config_file, gap_scale, &dirs);
        }
        Command::Surface { command } => return surface(command),
        Command::Md { file, out } => return md(&file, out),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(e.exit_code() as u8)
        }
    }
}
