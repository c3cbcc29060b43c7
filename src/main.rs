//! The `stiction` command-line program.

use clap::{Parser, Subcommand};
use std::io::IsTerminal;
use std::path::PathBuf;
use std::process::ExitCode;
use stiction::case;
use stiction::run::{RunOptions, output_directory};

#[derive(Parser)]
#[command(name = "stiction", version, about = "Implicit finite elements for adhesive and cohesive contact")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Solve a case: writes history.csv (one row per converged increment, flushed as it goes),
    /// VTK files (<name>_NNNNN.vtu + <name>.pvd for ParaView) and summary.json.
    ///
    /// Defaults (case file keys): analysis = "3d"; mesh.order = 2; mesh.size_factor = 1;
    /// sections[].quadrature = "standard" (tet10: 4 points); boundary amplitude = "ramp"
    /// (0 -> 1 over t in [0, 1]); steps[].initial_increment = step/10, min_increment =
    /// 1e-6 step, max_increment = step, output_every = 1; solver.max_iterations = 25,
    /// tol_residual = 1e-8, tol_displacement = 1e-6, line_search = true, threads = 0 (all
    /// cores), cut_factor = 0.25, growth_factor = 1.5; output.directory = out/<name>,
    /// output.vtk = true.
    Run {
        /// The case file (TOML).
        case: PathBuf,
        /// Output directory (default: the case's output.directory, else out/<name>).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Override any case key, e.g. --set steps.0.end_time=2 --set materials.ru.yield_stress=3.42
        #[arg(long = "set", value_name = "KEY=VALUE")]
        sets: Vec<String>,
        /// Never show progress, even on a terminal.
        #[arg(long)]
        quiet: bool,
    },
    /// Validate a case (schema, mesh, groups, materials, boundary conditions) without solving.
    Check {
        case: PathBuf,
        #[arg(long = "set", value_name = "KEY=VALUE")]
        sets: Vec<String>,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Run { case, out, sets, quiet } => (|| {
            let loaded = case::load(&case, &sets)?;
            let options = RunOptions { out, progress: !quiet && std::io::stderr().is_terminal() };
            let dir = output_directory(&loaded, &options);
            let summary = stiction::run::run(&loaded, &options)?;
            println!(
                "{}: {} increments ({} cut), {} Newton iterations, {:.2} s; {} free dofs; output in {}",
                summary.case,
                summary.increments,
                summary.cut_increments,
                summary.newton_iterations,
                summary.wall_seconds,
                summary.n_free_dofs,
                dir.display()
            );
            Ok(())
        })(),
        Command::Check { case, sets } => (|| {
            let loaded = case::load(&case, &sets)?;
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
            Ok(())
        })(),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            let e: stiction::StictionError = e;
            eprintln!("error: {e}");
            ExitCode::from(e.exit_code() as u8)
        }
    }
}
