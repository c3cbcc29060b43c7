//! Dissipation control (`solver.continuation = "dissipation"`) against closed forms.
//!
//! `cases/validation/cohesive-bar-snap-back.toml`: an elastic bar (E = 10, L = 1, unit section,
//! uniaxial strain) bonded to a rigid flat by the bilinear cohesive-zone law (k = 100,
//! sigma_max = 1, G_c = 0.02; onset opening 0.01, final opening 0.04), pulled by the flat. The
//! state is uniform, so every equilibrium has the flat's travel d = delta + s L / E with the
//! ligament traction s and opening delta on the law's curve: elastic s = k delta up to the
//! onset, s = sigma_max (0.04 - delta) / 0.03 on the softening branch, 0 once separated. The
//! softening branch snaps back (d falls from 0.11 to 0.04 while the crack opens). Followed, the
//! flat's net work over the whole path is exactly G_c (the bar ends unstressed); a run that
//! snaps loses the bar's elastic energy at the snap instead.
//!
//! Measured: every state within 2e-10 of the closed form; 16 states on the softening branch,
//! down to d = 0.040000; net work 0.019988 (G_c 0.02); load control and the spherical arc length both
//! snap (work 0.0537, one state on the softening branch).

use stiction_core::model::Model;
use stiction_tests::{Tolerance, build_case, history_columns, run_case, validate};

const CASE: &str = "cases/validation/cohesive-bar-snap-back.toml";
const L_OVER_E: f64 = 0.1;
const K: f64 = 100.0;
const SIGMA_MAX: f64 = 1.0;
const DELTA_0: f64 = 0.01;
const DELTA_F: f64 = 0.04;
const G_C: f64 = 0.02;

/// (travel d, tension s) per converged increment, the initial row included.
fn path(dir: &std::path::Path) -> Vec<(f64, f64)> {
    history_columns(dir, &["approach", "force"]).iter().map(|r| (-r[0], -r[1])).collect()
}

/// The ligament's opening at travel d and tension s, and the tension the law gives there.
fn closed_form(d: f64, s: f64) -> (f64, f64) {
    let delta = d - s * L_OVER_E;
    let law = if delta <= DELTA_0 {
        K * delta
    } else if delta < DELTA_F {
        SIGMA_MAX * (DELTA_F - delta) / (DELTA_F - DELTA_0)
    } else {
        0.0
    };
    (delta, law)
}

/// The flat's net work over the path (trapezoids: exact on each linear branch).
fn net_work(p: &[(f64, f64)]) -> f64 {
    p.windows(2).map(|w| 0.5 * (w[0].1 + w[1].1) * (w[1].0 - w[0].0)).sum()
}

/// States strictly on the softening branch.
fn softening_states(p: &[(f64, f64)]) -> Vec<(f64, f64)> {
    p.iter().copied().filter(|&(d, s)| (DELTA_0 + 1e-9..DELTA_F - 1e-9).contains(&closed_form(d, s).0)).collect()
}

#[test]
fn dissipation_control_follows_the_snap_back_of_a_cohesive_bar_and_dissipates_exactly_g_c() {
    let (_, run) = run_case(CASE, &[], "cohesive-bar-snap-back");
    assert_eq!(run.status, "completed", "{:?}", run.message);
    let p = path(&run.output_directory);
    let worst = p.iter().map(|&(d, s)| (s - closed_form(d, s).1).abs()).fold(0.0f64, f64::max);
    let snap_back = softening_states(&p);
    let lowest = snap_back.iter().map(|q| q.0).fold(f64::INFINITY, f64::min);
    let work = net_work(&p);
    println!(
        "dissipation control: {} increments ({} path-following), largest distance from the closed form {worst:.1e}, {} states on the softening branch down to d = {lowest:.6}, net work {work:.6} (G_c {G_C})",
        run.increments,
        run.arc_length_increments,
        snap_back.len()
    );
    assert!(worst < 1e-8 * SIGMA_MAX, "{worst}");
    // the branch is followed back from the peak (d = 0.11) to the end of softening (d = 0.04)
    assert!(snap_back.len() >= 5 && lowest < DELTA_F + 1e-3, "{snap_back:?}");
    assert_eq!(run.snaps, 0, "the path is followed, not jumped");
    validate(
        "dissipation control, cohesive bar snap-back: net work of the flat",
        "-",
        work,
        G_C,
        "the law's G_c",
        Tolerance::Relative(0.01),
    );

    // without it the run snaps at the peak and the bar's elastic energy is lost there
    for (continuation, label) in [("none", "cohesive-bar-load-control"), ("arc-length", "cohesive-bar-arc-length")] {
        let (_, other) = run_case(CASE, &[&format!("solver.continuation=\"{continuation}\"")], label);
        let q = path(&other.output_directory);
        let other_work = net_work(&q);
        println!(
            "{continuation}: {} snaps, {} states on the softening branch, net work {other_work:.4}",
            other.snaps,
            softening_states(&q).len()
        );
        assert!(softening_states(&q).len() <= 1 && other_work > 2.0 * G_C);
        // the damage law keeps state, so the default snap ("auto") follows the damped flow
        assert!(
            other.snaps >= 1 && other.snap_method == "damped-flow",
            "{} snaps by {}",
            other.snaps,
            other.snap_method
        );
    }
}

/// A peak passed inside one load-controlled increment: with increments of 0.3 in time (flat
/// travel 0.06) the second one (travel 0.06 -> 0.12) steps over the peak at 0.11 and converges
/// on the separated bar, which moved back against the first increment. The driver counts that
/// turn as a jump over a limit point, rolls it back and follows the snap-back from the last
/// bonded state. Measured: the states lie on the closed form, the first after the bonded one
/// at tension 0.970 just past the peak, 23 on the softening branch down to d = 0.040000, net
/// work 0.019725 (the trapezoid from the bonded state to the first softening one cuts the
/// corner at the peak: 1.4% under G_c); before, the path went from tension 0.545 to 0.
#[test]
fn a_peak_passed_inside_one_large_increment_is_followed_not_stepped_over() {
    let sets = ["steps.0.initial_increment=0.3", "steps.0.max_increment=0.3"];
    let (_, run) = run_case(CASE, &sets, "cohesive-bar-large-increments");
    assert_eq!(run.status, "completed", "{:?}", run.message);
    let p = path(&run.output_directory);
    let worst = p.iter().map(|&(d, s)| (s - closed_form(d, s).1).abs()).fold(0.0f64, f64::max);
    let snap_back = softening_states(&p);
    let lowest = snap_back.iter().map(|q| q.0).fold(f64::INFINITY, f64::min);
    let highest = p.iter().map(|q| q.1).fold(0.0f64, f64::max);
    let work = net_work(&p);
    println!(
        "increments of 0.3: {} increments ({} cut, {} path-following), largest distance from the closed form {worst:.1e}, highest tension {highest:.4}, {} states on the softening branch down to d = {lowest:.6}, net work {work:.6}",
        run.increments,
        run.cut_increments,
        run.arc_length_increments,
        snap_back.len()
    );
    assert!(worst < 1e-8 * SIGMA_MAX, "{worst}");
    assert_eq!(run.snaps, 0, "the path is followed, not jumped");
    // the peak (tension 1 at d = 0.11) is approached, not stepped over from 0.545 to 0
    assert!(highest > 0.9 * SIGMA_MAX, "{p:?}");
    assert!(snap_back.len() >= 5 && lowest < DELTA_F + 1e-3, "{snap_back:?}");
    // the trapezoid across the peak cuts its corner: the work falls short by that corner only
    assert!((work / G_C - 1.0).abs() < 0.02, "net work {work} vs G_c {G_C}");
}

/// The time of attempts that were not committed (here the increment over the peak, converged
/// and rolled back as a jump, and the cuts after it) is reported apart from the committed
/// increments' assembly, factorization and solve times, and all of them fit in the wall time.
#[test]
fn attempts_not_committed_are_timed_apart_from_the_committed_increments() {
    let sets = ["steps.0.initial_increment=0.3", "steps.0.max_increment=0.3"];
    let (_, run) = run_case(CASE, &sets, "cohesive-bar-attempt-times");
    assert_eq!(run.status, "completed", "{:?}", run.message);
    let committed = run.assembly_seconds + run.factorization_seconds + run.solve_seconds;
    println!(
        "{} cut, attempts not committed {:.2e} s, committed increments {committed:.2e} s, wall {:.2e} s",
        run.cut_increments, run.discarded_attempt_seconds, run.wall_seconds
    );
    assert!(run.cut_increments > 0, "the jump over the peak is rolled back");
    assert!(run.discarded_attempt_seconds > 0.0);
    assert!(committed + run.discarded_attempt_seconds <= run.wall_seconds);
    // messages.log: the start, every committed increment in order, the rollback, the end
    let log = std::fs::read_to_string(run.output_directory.join("messages.log")).unwrap();
    let texts: Vec<&str> = log.lines().map(|l| l.split_once("] ").map_or("", |(_, text)| text)).collect();
    assert!(texts[0].starts_with("run 'cohesive-bar-snap-back'"), "{log}");
    let increments: Vec<&str> = texts.iter().copied().filter(|t| t.starts_with("increment ")).collect();
    assert_eq!(increments.len(), run.increments + 1, "the initial state and each increment: {log}");
    for (k, line) in increments.iter().enumerate() {
        assert!(line.starts_with(&format!("increment {k}:")), "{line}");
    }
    assert!(texts.iter().any(|t| t.contains("jumped") && t.contains("rolled back")), "{log}");
    assert!(texts.last().unwrap().starts_with("completed at t = "), "{log}");
}

/// Central-difference check of the model's damage dissipation: its gradient along a direction
/// in the free dofs and its rate in pseudo-time (at fixed free dofs), at a trial state
/// `trial` (all dofs) and time `t` after committing `committed` at `t_c`.
fn dissipation_derivative_errors(
    model: &mut Model,
    (committed, t_c): (&[f64], f64),
    (trial, t): (&[f64], f64),
    h: f64,
) -> (f64, f64) {
    model.apply_time(t_c);
    model.displacement.copy_from_slice(committed);
    model.assemble(false).unwrap();
    model.commit();
    let free = model.free_dofs().to_vec();
    let direction: Vec<f64> = (0..free.len()).map(|i| ((i * 7919) % 13) as f64 / 13.0 - 0.5).collect();
    let energy_at = |model: &mut Model, s: f64, time: f64| {
        model.apply_time(time);
        model.displacement.copy_from_slice(trial);
        for (k, &g) in free.iter().enumerate() {
            model.displacement[g] += s * direction[k];
        }
        model.assemble(false).unwrap();
        let mut gradient = vec![0.0; free.len()];
        let (energy, rate) = model.damage_dissipation(&mut gradient).expect("an interface reports damage");
        (energy, rate, gradient)
    };
    let (energy, rate, gradient) = energy_at(model, 0.0, t);
    assert!(energy > 0.0, "the trial state damages: {energy}");
    let along: f64 = gradient.iter().zip(&direction).map(|(g, d)| g * d).sum();
    let fd = (energy_at(model, h, t).0 - energy_at(model, -h, t).0) / (2.0 * h);
    let fd_t = (energy_at(model, 0.0, t + h).0 - energy_at(model, 0.0, t - h).0) / (2.0 * h);
    println!(
        "gradient . p = {along:.8e}, central difference {fd:.8e}; rate in t {rate:.8e}, central difference {fd_t:.8e}"
    );
    ((along - fd).abs() / fd.abs(), (rate - fd_t).abs() / fd_t.abs().max(1e-300))
}

#[test]
fn the_damage_dissipation_gradients_match_central_differences() {
    // a rigid flat (the bar): committed on the softening branch (opening 0.02 at t = 0.1),
    // trial further open with a non-uniform displacement
    let (_, mut built) = build_case(CASE, &[]);
    let model = &mut built.model;
    let zero = vec![0.0; model.n_dofs()];
    let mut trial = zero.clone();
    for (n, x) in model.mesh.nodes.clone().iter().enumerate() {
        trial[n * 3 + 2] = -1e-3 * (1.0 - x[2]) * (1.0 + 0.5 * x[0] * x[1]);
    }
    let (gradient, rate) = dissipation_derivative_errors(model, (&zero, 0.1), (&trial, 0.125), 1e-7);
    println!("rigid flat: gradient error {gradient:.1e}, rate error {rate:.1e}");
    assert!(gradient < 1e-6 && rate < 1e-6);

    // cohesive elements between two blocks, in mixed mode (opening and slip)
    let sets = ["interfaces.0.parameters.penalty=1e4", "interfaces.0.parameters.G_c=5.0"];
    let (_, mut built) = build_case("cases/validation/two-blocks-cohesive.toml", &sets);
    let model = &mut built.model;
    // the upper block (the second section) moves up and sideways: its split interface nodes
    // open the elements
    let upper: std::collections::BTreeSet<usize> = model.sets[1].connectivity.iter().copied().collect();
    let opened = |c: f64| -> Vec<f64> {
        let mut u = vec![0.0; model.n_dofs()];
        for &n in &upper {
            let x = model.mesh.nodes[n];
            u[n * 3] = 0.3 * c * (1.0 + 0.2 * x[1]);
            u[n * 3 + 2] = c * (1.0 + 0.1 * x[0]);
        }
        u
    };
    let (committed, trial) = (opened(0.015), opened(0.02));
    let (gradient, _) = dissipation_derivative_errors(model, (&committed, 0.5), (&trial, 0.5), 1e-7);
    println!("cohesive elements: gradient error {gradient:.1e}");
    assert!(gradient < 1e-6);
}

/// (approach, force, contact area) per row of a run's history.csv.
fn flat_history(dir: &std::path::Path) -> Vec<(f64, f64, f64)> {
    history_columns(dir, &["approach", "force", "contact_area"]).iter().map(|r| (r[0], r[1], r[2])).collect()
}

/// An elastic sphere (R = 1000 nm, Ru, axisymmetric, 4 nm contact mesh) bonds to the flat
/// wherever it is pressed (bilinear cohesive zone, G_c = 1 J/m^2, no viscosity) and is pulled
/// off. The body stores nothing once it has separated, so the flat's net work over the cycle
/// is the energy the cracks dissipated: G_c times the bonded area (the largest contact area).
/// Followed by dissipation control the balance closes (measured +0.06%); the run crosses the
/// pull-off instability by jumps under load control (+0.44%) and by the arc length (+0.74%):
/// the elastic energy released in a jump is lost to the balance.
#[test]
fn a_cohesive_sphere_is_pulled_off_along_its_path_and_its_cycle_work_is_g_c_times_the_bonded_area() {
    let sets = |continuation: &str| {
        vec![
            "materials.ru.model=\"linear-elastic\"".to_string(),
            "interfaces.0.viscosity=0".to_string(),
            "mesh.parameters.h_contact=4.0".to_string(),
            format!("solver.continuation=\"{continuation}\""),
        ]
    };
    let balance = |continuation: &str| {
        let sets = sets(continuation);
        let sets: Vec<&str> = sets.iter().map(|s| s.as_str()).collect();
        let (_, run) =
            run_case("cases/ru-sphere/smooth-cohesive-w1.toml", &sets, &format!("cohesive-sphere-{continuation}"));
        assert_eq!(run.status, "completed", "{:?}", run.message);
        let h = flat_history(&run.output_directory);
        let work: f64 = h.windows(2).map(|w| 0.5 * (w[0].1 + w[1].1) * (w[1].0 - w[0].0)).sum();
        let bonded = h.iter().map(|r| r.2).fold(0.0f64, f64::max);
        let error = work / (1.0 * bonded) - 1.0;
        println!(
            "{continuation}: net work {work:.2} nN nm, G_c x bonded area {bonded:.2} ({:+.3}%), {} snaps, {} limit points, final force {:.2} nN",
            100.0 * error,
            run.snaps,
            run.limit_points,
            h.last().unwrap().1
        );
        (run, error)
    };
    let (run, error) = balance("dissipation");
    assert_eq!(run.snaps, 0);
    assert!(run.limit_points >= 2, "the pull-off's snap-back is followed: {}", run.limit_points);
    assert!(error.abs() < 2e-3, "{error}");
    let (_, jumped) = balance("none");
    assert!(jumped > 2.0 * error.abs(), "load control loses the jump's energy: {jumped} vs {error}");
}

/// `cases/validation/dcb-force.toml` shortened to L = 60 (ligament 30 to 60, all finely
/// meshed): the double cantilever beam of dcb.toml under a force P = 0.3 t at its end. Past
/// the peak the force must fall while the crack grows; dissipation control follows that branch
/// against beam theory + LEFM, P = sqrt(2/3) (G_c B)^(3/4) (E I)^(1/4) / sqrt(d), with d twice
/// the end's mean deflection. Once the ligament has failed, the arm (clamped at x = L) carries
/// P = 0.3 at t = 1 as a cantilever: d = 2 P (L^3 / (3 E I) + L / (k G A)), k = 5/6.
/// Measured: peak 0.1552 (LEFM initiation 0.1619 at a0 + 0.67 H), 24 states within 0.34% of
/// LEFM for d = 3.0-7.0 (the crack tip then nears the clamp and the ratio rises: 1.013 at
/// d = 7.6), final opening 29.586 against 29.783; 35 s in the test profile.
#[test]
fn a_force_loaded_dcb_follows_the_lefm_branch_past_its_peak_and_ends_as_a_cantilever() {
    let sets = ["mesh.parameters.L=60.0", "mesh.parameters.x_fine=60.0"];
    let (_, run) = run_case("cases/validation/dcb-force.toml", &sets, "dcb-force");
    assert_eq!(run.status, "completed", "{:?}", run.message);
    assert_eq!(run.snaps, 0);
    let (e, nu, b, h, g_c, a0, chi, l) = (70.0f64, 0.3f64, 2.0f64, 5.0f64, 0.01f64, 30.0f64, 0.67f64, 60.0f64);
    let ei = e * b * h.powi(3) / 12.0;
    let c = (2.0f64 / 3.0).sqrt() * (g_c * b).powf(0.75) * ei.powf(0.25);
    let states: Vec<(f64, f64)> = history_columns(&run.output_directory, &["time", "displacement_load_end_z"])
        .iter()
        .map(|r| (0.3 * r[0], 2.0 * r[1]))
        .collect();
    // the peak of crack growth (the cantilever at the end carries more)
    let peak = states.iter().filter(|s| s.1 < 10.0).map(|s| s.0).fold(0.0f64, f64::max);
    let p_init = (g_c * b * ei).sqrt() / (a0 + chi * h);
    let branch: Vec<f64> =
        states.iter().filter(|s| (3.0..=7.0).contains(&s.1)).map(|&(p, d)| p / (c / d.sqrt())).collect();
    let worst = branch.iter().map(|r| (r - 1.0).abs()).fold(0.0f64, f64::max);
    let (p_end, d_end) = *states.last().unwrap();
    let shear_modulus = e / (2.0 * (1.0 + nu));
    let cantilever = 2.0 * p_end * (l.powi(3) / (3.0 * ei) + l / (5.0 / 6.0 * shear_modulus * b * h));
    println!(
        "peak {peak:.4} (LEFM initiation {p_init:.4}); {} states on the branch d = 3-7, largest |P / P_LEFM - 1| {worst:.4}; final opening {d_end:.3} at P = {p_end:.3}, cantilever {cantilever:.3}; {} increments, {} path-following, {} factorizations",
        branch.len(),
        run.increments,
        run.arc_length_increments,
        run.factorizations
    );
    assert!((peak / p_init - 1.0).abs() < 0.08);
    assert!(branch.len() >= 8 && worst < 0.01, "{branch:?}");
    assert!((p_end - 0.3).abs() < 1e-9 && (d_end / cantilever - 1.0).abs() < 0.02);
}
