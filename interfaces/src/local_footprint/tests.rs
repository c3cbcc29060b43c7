use super::*;

/// f(x) = -k x: a bonded linear spring (pushes apart when x < 0, pulls when x > 0).
struct BondedSpring {
    k: f64,
}

impl InterfaceLaw for BondedSpring {
    fn name(&self) -> &str {
        "bonded-spring"
    }
    fn kind(&self) -> LawKind {
        LawKind::ForcePerPoint
    }
    fn evaluate(&self, gap: f64, _: &[f64], _: &mut [f64]) -> Result<LawResponse, LawError> {
        Ok(LawResponse { value: -self.k * gap, tangent: -self.k, in_contact: true, area: 0.0 })
    }
}

/// The Morse force f(x) = 2 D a (e^{-2 a x} - e^{-a x}): repulsive for x < 0, attractive for
/// x > 0 with its peak at x = ln 2 / a.
struct Morse {
    d: f64,
    a: f64,
}

impl Morse {
    fn force(&self, x: f64) -> (f64, f64) {
        let (e1, e2) = ((-self.a * x).exp(), (-2.0 * self.a * x).exp());
        (2.0 * self.d * self.a * (e2 - e1), 2.0 * self.d * self.a * self.a * (e1 - 2.0 * e2))
    }
}

impl InterfaceLaw for Morse {
    fn name(&self) -> &str {
        "morse"
    }
    fn kind(&self) -> LawKind {
        LawKind::ForcePerPoint
    }
    fn evaluate(&self, gap: f64, _: &[f64], _: &mut [f64]) -> Result<LawResponse, LawError> {
        let (value, tangent) = self.force(gap);
        Ok(LawResponse { value, tangent, in_contact: gap < 0.0, area: 0.0 })
    }
}

fn series(inner: Arc<dyn InterfaceLaw>, compliance: f64, limit_force: f64) -> (SeriesWithFootprint, Vec<f64>) {
    let law = SeriesWithFootprint::new(inner, LocalFootprint { compliance, limit_force }).unwrap();
    let mut state = vec![0.0; law.n_state()];
    law.initialize_state(&mut state);
    (law, state)
}

/// Evaluates at `g` and commits.
fn step(law: &SeriesWithFootprint, state: &mut Vec<f64>, g: f64) -> LawResponse {
    let mut trial = state.clone();
    let r = law.evaluate(g, state, &mut trial).unwrap();
    *state = trial;
    r
}

#[test]
fn an_elastic_spring_in_series_gives_the_series_stiffness() {
    // F = -k (g + c F)  =>  F = -k g / (1 + k c), dF/dg = -k / (1 + k c)
    let (k, c) = (1800.0, 5.6e-4);
    let (law, state) = series(Arc::new(BondedSpring { k }), c, 1e9);
    for g in [-0.3, -0.01, 0.2] {
        let r = law.evaluate(g, &state, &mut state.clone()).unwrap();
        let exact = -k * g / (1.0 + k * c);
        assert!((r.value - exact).abs() <= 1e-12 * exact.abs(), "g {g}: {} vs {exact}", r.value);
        assert!((r.tangent + k / (1.0 + k * c)).abs() <= 1e-12 * k);
    }
}

#[test]
fn tangents_match_finite_differences_elastic_and_plastic() {
    let morse = Arc::new(Morse { d: 20.0, a: 8.0 });
    // peak attraction of this law: D a / 2 = 80; stiffness at x = 0: -2 D a^2 = -2560
    for (c, limit) in [(2e-4, 1e9), (2e-4, 60.0), (0.0, 60.0)] {
        let (law, state) = series(morse.clone(), c, limit);
        for i in 0..40 {
            let g = -0.15 + 0.2 * i as f64 / 40.0;
            let f = |g: f64| law.evaluate(g, &state, &mut state.clone()).unwrap().value;
            let r = law.evaluate(g, &state, &mut state.clone()).unwrap();
            let h = 1e-7;
            let fd = (f(g + h) - f(g - h)) / (2.0 * h);
            if r.value.abs() > limit * (1.0 - 1e-6) && r.value.abs() < limit * (1.0 + 1e-6) {
                assert_eq!(r.tangent, 0.0);
                continue;
            }
            let scale = r.tangent.abs().max(1.0);
            assert!(
                (fd - r.tangent).abs() <= 1e-6 * scale,
                "c {c}, limit {limit}, g {g}: tangent {} vs fd {fd}",
                r.tangent
            );
        }
    }
}

#[test]
fn the_slider_keeps_the_indentation_and_dissipates_the_limit_times_its_travel() {
    let (k, c, limit) = (1800.0, 5.6e-4, 137.0);
    let (law, mut state) = series(Arc::new(BondedSpring { k }), c, limit);
    let ns = 0;
    // yield at g_y = -limit (1/k + c); press to g1 beyond it
    let g_yield = -limit * (1.0 / k + c);
    let r = step(&law, &mut state, 0.99 * g_yield);
    assert!(r.value < limit && r.tangent < 0.0);
    let g1 = 3.0 * g_yield;
    let r = step(&law, &mut state, g1);
    assert_eq!((r.value, r.tangent), (limit, 0.0));
    // indentation s = x* - g1 - c limit with x* = -limit / k
    let s1 = -limit / k - g1 - c * limit;
    assert!((state[ns + SLIDER] - s1).abs() <= 1e-12, "{} vs {s1}", state[ns + SLIDER]);
    // unloading is elastic about the indentation: zero force at g = -s1
    let r = law.evaluate(-s1, &state, &mut state.clone()).unwrap();
    assert!(r.value.abs() <= 1e-9 * limit, "force {} at g = -s", r.value);
    // pulled beyond the tensile limit the slider is drawn back
    let g2 = -s1 + 2.0 * limit * (1.0 / k + c);
    let r = step(&law, &mut state, g2);
    assert_eq!((r.value, r.tangent), (-limit, 0.0));
    let s2 = limit / k - g2 + c * limit;
    assert!((state[ns + SLIDER] - s2).abs() <= 1e-12);
    let work = limit * (s1.abs() + (s1 - s2).abs());
    assert!((state[ns + SLIDER_WORK] - work).abs() <= 1e-9 * work, "{} vs {work}", state[ns + SLIDER_WORK]);
}

#[test]
fn a_branch_steeper_than_the_spring_folds_where_one_minus_c_f_prime_vanishes() {
    let morse = Morse { d: 20.0, a: 8.0 };
    // beyond the peak the attraction softens with f' up to 2 D a^2 / 8 = 320 (at x = ln 4 / a);
    // a compliance of 1/160 makes 1 - c f' vanish twice there: the branch folds
    let c = 1.0 / 160.0;
    let (law, mut state) = series(Arc::new(Morse { d: 20.0, a: 8.0 }), c, 1e9);
    // fold: the first x past the peak with 1 - c f'(x) = 0, by bisection
    let (mut lo, mut hi) = ((2f64).ln() / 8.0, (4f64).ln() / 8.0);
    for _ in 0..100 {
        let m = 0.5 * (lo + hi);
        if 1.0 - c * morse.force(m).1 > 0.0 { lo = m } else { hi = m }
    }
    let x_fold = 0.5 * (lo + hi);
    let g_fold = x_fold - c * morse.force(x_fold).0;
    let mut previous: Option<(f64, f64)> = None;
    let mut snap = None;
    for i in 0..=400 {
        let g = 1.0 * i as f64 / 400.0;
        let r = step(&law, &mut state, g);
        if let Some((gp, fp)) = previous {
            // a jump far larger than the smooth change over one step
            if (r.value - fp).abs() > 5.0 && snap.is_none() {
                snap = Some((gp, g));
            }
        }
        previous = Some((g, r.value));
    }
    let (before, after) = snap.expect("the branch snaps");
    assert!(before <= g_fold && g_fold <= after, "snap between {before} and {after}, fold at {g_fold}");
}

#[test]
fn a_first_evaluation_already_past_the_limit_lands_on_it() {
    // a fresh point pressed beyond the limit at once: the law's gap is where f = F_lim
    let (k, c, limit) = (1800.0, 5.6e-4, 137.0);
    let (law, mut state) = series(Arc::new(BondedSpring { k }), c, limit);
    let g = -1.0;
    let r = step(&law, &mut state, g);
    assert_eq!((r.value, r.tangent), (limit, 0.0));
    let x = state[LAW_GAP];
    assert!((x + limit / k).abs() <= 1e-12, "law gap {x}, expected {}", -limit / k);
    assert!((state[SLIDER] - (x - g - c * limit)).abs() <= 1e-12);
}
