//! The nano-asperity law against its definitions: the surrogate table is fitted back within
//! stated errors, force is continuous across every branch change of a multi-cycle path, the
//! tangent is the derivative of the force, pull-off magnitudes follow the surrogate's stated
//! targets, and bad calibrations are refused with the key named.

use stiction_law_ru_asperity::calibration::Calibration;
use stiction_law_ru_asperity::law::{AsperityModel, N_STATE};
use stiction_law_ru_asperity::{fit, surrogate};

fn model(w: f64) -> AsperityModel {
    let table = fit::parse_table(&surrogate::table(w, 60)).unwrap();
    AsperityModel { calibration: fit::fit(&table, 4, 5).unwrap(), ramp: 0.05 }
}

#[test]
fn fits_reproduce_the_surrogate_table() {
    for w in [1.0, 3.0, 6.0] {
        let c = model(w).calibration;
        let q = c.fit.clone().unwrap();
        println!(
            "w = {w}: loading force rms {:.3} nN (max {:.3}), unloading force rms {:?}",
            q.loading_force_rms, q.loading_force_max, q.unloading_force_rms
        );
        // 4th-order loading fit of the tanh surrogate: within 3% of the 360 nN range
        assert!(q.loading_force_max < 0.03 * 360.0, "w = {w}: {}", q.loading_force_max);
        // the unloading surrogate is a cubic in d, so a 5th-order fit is exact up to the table's
        // rounding: distances written to 6 decimals x slopes up to ~1e3 nN/nm = 5e-4 nN
        assert!(q.unloading_force_rms.iter().all(|&r| r < 1e-3), "{:?}", q.unloading_force_rms);
        assert_eq!(c.unloading.len(), surrogate::MAXIMA.len());
        assert_eq!(c.work_of_adhesion, w);
    }
}

/// Walks a distance path through the law, committing every step; returns (d, force, stiffness).
fn walk(m: &AsperityModel, path: &[f64]) -> Vec<(f64, f64, f64, [f64; N_STATE])> {
    let mut state = [0.0; N_STATE];
    path.iter()
        .map(|&d| {
            let mut new = [0.0; N_STATE];
            let e = m.evaluate(d, &state, &mut new);
            state = new;
            (d, e.force, e.stiffness, new)
        })
        .collect()
}

fn leg(a: f64, b: f64, n: usize) -> Vec<f64> {
    (1..=n).map(|i| a + (b - a) * i as f64 / n as f64).collect()
}

#[test]
fn force_is_continuous_across_all_branch_changes_over_several_cycles() {
    let m = model(6.0);
    // approach, partial unload, reload past the old maximum (between fitted maxima), unload to
    // separation, re-contact, load beyond the largest fitted maximum, unload to separation
    let mut path = vec![-1.0];
    for (a, b) in [(-1.0, 1.2), (1.2, 0.3), (0.3, 1.7), (1.7, -2.0), (-2.0, 2.6), (2.6, -2.5)] {
        path.extend(leg(a, b, 4000));
    }
    let w = walk(&m, &path);
    let step = 3.5 / 4000.0;
    let mut worst: f64 = 0.0;
    for p in w.windows(2) {
        let (df, k) = ((p[1].1 - p[0].1).abs(), p[0].2.abs().max(p[1].2.abs()));
        // a jump would exceed the largest local slope times the step by far
        worst = worst.max(df / (k * step + 1e-9));
    }
    println!("largest |dF| / (|k| dd) between steps: {worst:.3}");
    assert!(worst < 3.0, "force jump along the path: {worst}");
    let pull_offs = w.last().unwrap().3[2];
    assert_eq!(pull_offs, 2.0, "two separations expected");
}

#[test]
fn tangent_is_the_derivative_of_the_force_on_every_branch() {
    let m = model(3.0);
    let h = 1e-6;
    // committed states: fresh, loaded to 0.8 (between fitted maxima), loaded to 2.4 (beyond)
    for (max, ds) in [(0.8, vec![-0.28, 0.0, 0.5, 0.79, 0.85]), (2.4, vec![-0.9, -0.2, 1.0, 2.3, 2.6])] {
        let mut state = [0.0; N_STATE];
        for d in leg(-0.3, max, 200) {
            let mut new = [0.0; N_STATE];
            m.evaluate(d, &state, &mut new);
            state = new;
        }
        for d in ds {
            let mut s = [0.0; N_STATE];
            let e = m.evaluate(d, &state, &mut s);
            let fp = m.evaluate(d + h, &state, &mut s).force;
            let fm = m.evaluate(d - h, &state, &mut s).force;
            let fd = (fp - fm) / (2.0 * h);
            assert!(
                (fd - e.stiffness).abs() < 1e-5 * e.stiffness.abs().max(1.0),
                "max {max}, d = {d}: {} vs fd {fd}",
                e.stiffness
            );
        }
    }
}

#[test]
fn pull_off_and_stretching_follow_the_surrogate_targets() {
    let (m1, m3, m6) = (model(1.0), model(3.0), model(6.0));
    let dmax = *surrogate::MAXIMA.last().unwrap();
    let (p1, p3, p6) = (m1.pull_off(dmax).0, m3.pull_off(dmax).0, m6.pull_off(dmax).0);
    println!("single-asperity pull-off at d_max = {dmax}: w=1 {p1:.1}, w=3 {p3:.1}, w=6 {p6:.1} nN");
    assert!(p6 < 0.0 && p6 > -420.0 && p6 < -350.0, "w = 6 pull-off should be ~400 nN at most: {p6}");
    assert!(p3 < 0.0 && p1 < 0.0 && p1 > p3 && p3 > p6);
    // more plastic stretching (more negative separation distance) for larger w
    let (e1, e3, e6) = (m1.separation_distance(dmax), m3.separation_distance(dmax), m6.separation_distance(dmax));
    assert!(e6 < e3 && e3 < e1 && e1 < -0.25, "{e1} {e3} {e6}");
    // loading nearly the same for all w: within 1% of the peak force at d = 1.5
    let mut s = [0.0; N_STATE];
    let f = |m: &AsperityModel, s: &mut [f64; N_STATE]| m.evaluate(1.5, &[0.0; N_STATE], s).force;
    let (f1, f6) = (f(&m1, &mut s), f(&m6, &mut s));
    assert!((f1 - f6).abs() < 0.01 * f1, "{f1} vs {f6}");
    // starts at a slightly negative distance with a small attraction
    let c = &m6.calibration.loading;
    let f0 = stiction_law_ru_asperity::polynomial::value(&c.force, c.d_start);
    assert!(c.d_start < 0.0 && f0 < 0.0 && f0 > -20.0, "jump-in force {f0} at {}", c.d_start);
}

#[test]
fn bad_calibrations_are_refused_naming_the_key() {
    let good = model(1.0).calibration.to_toml("test");
    assert!(Calibration::parse(&good).is_ok());
    let e = Calibration::parse(&good.replace("length = \"nm\"", "length = \"um\"")).unwrap_err();
    assert!(e.contains("units"), "{e}");
    let mut c = model(1.0).calibration;
    c.unloading.swap(1, 2);
    let e = Calibration::parse(&c.to_toml("x")).unwrap_err();
    assert!(e.contains("unloading[2].d_max") && e.contains("increase"), "{e}");
    let mut c = model(1.0).calibration;
    c.unloading.clear();
    let e = c.validate().unwrap_err();
    assert!(e.contains("unloading"), "{e}");
    let e = Calibration::parse("format = \"x\"").unwrap_err();
    assert!(e.contains("missing field") || e.contains("format"), "{e}");
}

/// The law's parameters in declaration order: expected_work_of_adhesion, ramp, then the
/// surrogate's loading scale, length, stiffness, pull-off scale (0: by w) and stretch.
fn parameters(surrogate: [f64; 5]) -> Vec<f64> {
    let mut p = vec![0.0, 0.05];
    p.extend(surrogate);
    p
}

const DEFAULTS: [f64; 5] = [surrogate::LOADING_SCALE, surrogate::LOADING_LENGTH, surrogate::STIFFNESS, 0.0, 1.0];

fn shipped(name: &str) -> String {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../cases/ru-rough-sphere/calibrations");
    std::fs::read_to_string(dir.join(name)).unwrap()
}

/// A surrogate config file with the parameters at their defaults gives the shipped calibration
/// (`stiction calibrate` of `stiction surrogate-table`) to the last digit.
#[test]
fn the_surrogate_config_with_default_parameters_is_the_shipped_calibration() {
    use stiction_law_sdk::Law;
    for w in [1, 3, 6] {
        let law = stiction_law_ru_asperity::RuAsperity::create(
            &parameters(DEFAULTS),
            &shipped(&format!("ru-surrogate-model-w{w}.toml")),
        )
        .unwrap();
        let fitted = Calibration::parse(&shipped(&format!("ru-surrogate-w{w}.toml"))).unwrap();
        assert_eq!(law.model.calibration.loading, fitted.loading, "w = {w}");
        assert_eq!(law.model.calibration.unloading, fitted.unloading, "w = {w}");
    }
}

/// Changed surrogate parameters change the law as the surrogate's formulas say: the unloading
/// (a cubic in d, fitted by 5th-order polynomials) within 0.01 nN of the formula with twice
/// the pull-off scale and a longer stretch, the loading within 3% of its range with another
/// scale, length and stiffness.
#[test]
fn surrogate_parameters_change_the_law_as_the_formulas_say() {
    use stiction_law_ru_asperity::polynomial;
    use stiction_law_sdk::Law;
    let given = [300.0, 0.6, 40.0, 800.0, 1.5];
    let law = stiction_law_ru_asperity::RuAsperity::create(&parameters(given), &shipped("ru-surrogate-model-w6.toml"))
        .unwrap();
    let s = surrogate::Surrogate {
        work_of_adhesion: 6.0,
        loading_scale: 300.0,
        loading_length: 0.6,
        stiffness: 40.0,
        pull_off_scale: 800.0,
        stretch: 1.5,
    };
    let c = &law.model.calibration;
    for u in &c.unloading {
        let e = s.separation(u.d_max);
        assert!((u.d_end - e).abs() < 1e-6, "{} against {e}", u.d_end);
        for k in 0..=20 {
            let d = e + (u.d_max - e) * k as f64 / 20.0;
            let (f, _) = s.unloading(u.d_max, d);
            assert!((polynomial::value(&u.force, d) - f).abs() < 1e-2, "from {} at {d}", u.d_max);
        }
    }
    let range = s.loading_force(2.0) - s.loading_force(-0.25);
    for k in 0..=20 {
        let d = -0.25 + 2.25 * k as f64 / 20.0;
        assert!((polynomial::value(&c.loading.force, d) - s.loading_force(d)).abs() < 0.03 * range, "{d}");
    }
    // and the pull-off from the largest maximum is about twice the default's
    let default = surrogate::Surrogate::for_work_of_adhesion(6.0);
    let most_tensile = |s: &surrogate::Surrogate| {
        let e = s.separation(2.0);
        (0..=400).map(|k| s.unloading(2.0, e + (2.0 - e) * k as f64 / 400.0).0).fold(f64::INFINITY, f64::min)
    };
    let ratio = most_tensile(&s) / most_tensile(&default);
    assert!((1.6..2.4).contains(&ratio), "{ratio}");
}

/// A surrogate parameter with a fitted calibration (which it cannot change) is refused by name.
#[test]
fn a_surrogate_parameter_with_a_fitted_calibration_is_refused() {
    use stiction_law_sdk::Law;
    let mut given = DEFAULTS;
    given[3] = 500.0;
    let e = stiction_law_ru_asperity::RuAsperity::create(&parameters(given), &shipped("ru-surrogate-w6.toml"))
        .err()
        .unwrap();
    assert!(e.contains("surrogate_pull_off_scale") && e.contains("stiction-asperity-surrogate-1"), "{e}");
}
