//! Benchmark (not a test): the faer side of `benches/linear-solvers/compare.sh`, and the export
//! of the matrix all three solvers factor.
//!
//! ```text
//! cargo bench --bench linear_solvers -- export CASE OUT_DIR [--set KEY=VALUE]...
//! cargo bench --bench linear_solvers -- factor MATRIX.mtx ORDERING PRECISION REPEATS
//! ```
//!
//! `export` runs the case to its end (the model keeps its last converged state), assembles the
//! tangent there and writes its lower triangle as a symmetric Matrix Market file,
//! `OUT_DIR/tangent.mtx`, the file CHOLMOD's and MUMPS's drivers read too.
//!
//! `factor` reads such a file and factors it with [`FaerCholesky`] as the nonlinear solver uses
//! it: the symbolic analysis once (ORDERING `nd`, METIS nested dissection on the node graph,
//! the default, or `amd`), then REPEATS numeric factorizations (PRECISION `single`, the default
//! f32 factor, or `double`), and a solve of A x = b with b = A 1 (refined to double precision
//! where the factor is single). It prints one JSON line: the times (the factorization's best of
//! REPEATS), the factor's entries, the relative residual ||A x - b|| / ||b||, the error against
//! the exact solution 1, and the process's peak resident memory. Threads: rayon's pool
//! (`RAYON_NUM_THREADS`) where a run would use it (a factor of at least
//! [`PARALLEL_FACTOR_ENTRIES`] entries), else one.

use std::path::Path;
use std::time::Instant;
use stiction_core::linear_solver::{FaerCholesky, LinearSolver, Ordering, PARALLEL_FACTOR_ENTRIES, Precision};
use stiction_core::sparse::SparsityPattern;

fn main() {
    // cargo bench passes `--bench` to a harness-less bench: it is not ours
    let args: Vec<String> = std::env::args().skip(1).filter(|a| a != "--bench").collect();
    let outcome = match args.first().map(String::as_str) {
        Some("export") if args.len() >= 3 => export(Path::new(&args[1]), Path::new(&args[2]), &args[3..]),
        Some("factor") if args.len() == 5 => factor(Path::new(&args[1]), &args[2], &args[3], &args[4]),
        _ => {
            Err("usage: export CASE OUT_DIR [--set KEY=VALUE]... | factor MATRIX.mtx nd|amd single|double REPEATS"
                .into())
        }
    };
    if let Err(message) = outcome {
        eprintln!("error: {message}");
        std::process::exit(2);
    }
}

/// Runs the case to its end and writes the tangent at its last state.
fn export(case: &Path, out: &Path, rest: &[String]) -> Result<(), String> {
    let mut sets = Vec::new();
    let mut words = rest.iter();
    while let Some(word) = words.next() {
        match (word.as_str(), words.next()) {
            ("--set", Some(assignment)) => sets.push(assignment.clone()),
            _ => return Err(format!("expected `--set KEY=VALUE`, found `{word}`")),
        }
    }
    let loaded = stiction::case::load(case, &sets).map_err(|e| e.to_string())?;
    let mut built = stiction::build::build(&loaded).map_err(|e| e.to_string())?;
    let options = stiction::run::RunOptions { out: Some(out.join("run")), overwrite: true, ..Default::default() };
    let t = Instant::now();
    let summary = stiction::run::run_model(&loaded, &mut built, &options).map_err(|e| e.to_string())?;
    eprintln!("ran {} to its end in {:.1} s ({:?})", case.display(), t.elapsed().as_secs_f64(), summary.status);
    let model = &mut built.model;
    model.assemble(true).map_err(|e| e.to_string())?;
    let path = out.join("tangent.mtx");
    model
        .pattern()
        .write_matrix_market_symmetric(&model.tangent_values, &path)
        .map_err(|e| format!("{}: {e}", path.display()))?;
    let pattern = model.pattern();
    println!(
        "{}: {} equations, {} entries in the lower triangle",
        path.display(),
        pattern.n,
        (pattern.nnz() + pattern.n) / 2
    );
    Ok(())
}

/// Factors the file's matrix as a run does and prints the measurements as JSON.
fn factor(path: &Path, ordering: &str, precision: &str, repeats: &str) -> Result<(), String> {
    let ordering = match ordering {
        "nd" => Ordering::NestedDissection,
        "amd" => Ordering::Amd,
        other => return Err(format!("ordering `{other}`: expected nd or amd")),
    };
    let precision = match precision {
        "single" => Precision::Single,
        "double" => Precision::Double,
        other => return Err(format!("precision `{other}`: expected single or double")),
    };
    let repeats: usize = repeats.parse().map_err(|_| format!("repeats `{repeats}`: expected a count"))?;
    let t = Instant::now();
    let (pattern, values) =
        SparsityPattern::read_matrix_market(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let read = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let mut solver = FaerCholesky::analyse_with_precision(&pattern, ordering, precision).map_err(|e| e.to_string())?;
    let analyse = t.elapsed().as_secs_f64();
    let mut factorize = f64::INFINITY;
    let mut kind = None;
    for _ in 0..repeats.max(1) {
        let t = Instant::now();
        kind = Some(solver.factorize(&pattern, &values).map_err(|e| e.to_string())?);
        factorize = factorize.min(t.elapsed().as_secs_f64());
    }
    let ones = vec![1.0; pattern.n];
    let mut b = vec![0.0; pattern.n];
    pattern.multiply(&values, &ones, &mut b);
    let mut x = b.clone();
    let t = Instant::now();
    solver.solve_in_place(&mut x).map_err(|e| e.to_string())?;
    let solve = t.elapsed().as_secs_f64();
    let mut ax = vec![0.0; pattern.n];
    pattern.multiply(&values, &x, &mut ax);
    let norm = |v: &mut dyn Iterator<Item = f64>| v.map(|a| a * a).sum::<f64>().sqrt();
    let residual = norm(&mut ax.iter().zip(&b).map(|(a, b)| a - b)) / norm(&mut b.iter().copied());
    let error = x.iter().map(|x| (x - 1.0).abs()).fold(0.0, f64::max);
    println!(
        "{}",
        serde_json::json!({
            "solver": "faer",
            "equations": pattern.n,
            "ordering": format!("{ordering:?}"),
            "precision": format!("{precision:?}"),
            "kind": format!("{kind:?}"),
            // Stiction factors a smaller factor on one thread
            "factor_threads": if solver.factor_nnz() >= PARALLEL_FACTOR_ENTRIES { rayon::current_num_threads() } else { 1 },
            "read_s": read,
            "analyse_s": analyse,
            "factorize_s": factorize,
            "solve_s": solve,
            "factor_entries": solver.factor_nnz(),
            "precision_fallbacks": solver.precision_fallbacks(),
            "residual": residual,
            "max_error": error,
            "peak_rss_mb": peak_rss_mb(),
        })
    );
    Ok(())
}

/// This process's peak resident memory in MB (getrusage; Linux reports kilobytes).
fn peak_rss_mb() -> f64 {
    let mut usage = std::mem::MaybeUninit::<libc::rusage>::zeroed();
    // SAFETY: getrusage fills the struct it is given; RUSAGE_SELF is always valid
    let usage = unsafe {
        libc::getrusage(libc::RUSAGE_SELF, usage.as_mut_ptr());
        usage.assume_init()
    };
    usage.ru_maxrss as f64 / 1024.0
}
