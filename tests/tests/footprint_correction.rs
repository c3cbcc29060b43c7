//! The footprint correction: one asperity at the pole of the Ru hemisphere on meshes coarser
//! than its footprint (12.2 nm^2, radius 1.97 nm), with the footprint's own compliance and
//! (declared here, as in the bulk-limit sensitivity study) its limit force in series with its
//! law (`points.footprint_correction`).
//! - Compliance: the mesh's own compliance under the footprint grows as the mesh is refined;
//!   with the correction the total is the half-space disc's, u_bar / F = 16 (1 - nu^2) /
//!   (3 pi^2 a E) (Johnson, Contact Mechanics, 3.4), on any mesh (the hemisphere's own global
//!   compliance, with R = 1000 nm, adds under 1%).
//! - Response: with the correction the force-approach cycle and the plastic dissipation are the
//!   same on a coarse and a five times finer contact mesh (without it the coarse mesh's limit
//!   load is twice the fine one's: docs/ru-rough-sphere.md).

use stiction_tests::{build_case, history_columns, one_asperity_at_the_pole, run_case, workspace_root};

const E: f64 = 410.0;
const NU: f64 = 0.3;
const AREA: f64 = 12.2;

/// The overrides for one corrected asperity at the pole on a contact mesh of `h` (nm) within
/// `r_fine`, growing by `growth` beyond.
fn corrected(h: f64, r_fine: f64, growth: f64) -> Vec<String> {
    vec![
        format!(
            "interfaces.0.points={{ file = \"{}\", footprint_area = {AREA}, footprint_correction = {{ limit_pressure = \"von-mises-disc\" }} }}",
            one_asperity_at_the_pole("footprint-correction-input").display()
        ),
        format!("mesh.parameters.h_contact={h}"),
        format!("mesh.parameters.r_fine={r_fine}"),
        format!("mesh.parameters.growth={growth}"),
        "amplitudes.cycle.value=[-0.5, 2.0, -3.0]".into(),
        "output.vtk=false".into(),
    ]
}

#[test]
fn the_corrected_footprint_compliance_is_the_half_space_discs_on_any_mesh() {
    let radius = (AREA / std::f64::consts::PI).sqrt();
    let exact = 16.0 * (1.0 - NU * NU) / (3.0 * std::f64::consts::PI.powi(2) * radius * E);
    let mut mesh_only = Vec::new();
    for (h, r_fine, growth) in [(20.0, 40.0, 0.5), (2.0, 6.0, 0.3)] {
        let sets = corrected(h, r_fine, growth);
        let sets: Vec<&str> = sets.iter().map(String::as_str).collect();
        let (_, built) = build_case("cases/ru-rough-sphere/rough-w6-quick.toml", &sets);
        let c = &built.footprint_compliances[0];
        let total = c.mesh_median + c.median;
        assert!(
            (total - exact).abs() <= 0.015 * exact,
            "h {h}: mesh {:.4e} + correction {:.4e} = {total:.4e}, half-space disc {exact:.4e}",
            c.mesh_median,
            c.median
        );
        mesh_only.push(c.mesh_median);
    }
    // the correction matters: the coarse mesh alone gives under half, the fine one over 90%
    assert!(mesh_only[0] < 0.5 * exact && mesh_only[1] > 0.9 * exact, "mesh alone: {mesh_only:?} of {exact:.4e}");
}

#[test]
fn a_corrected_asperity_cycles_alike_on_coarse_and_fine_meshes() {
    let mut histories = Vec::new();
    for (h, r_fine, growth, label) in [(20.0, 40.0, 0.5, "fc-coarse"), (4.0, 6.0, 0.3, "fc-fine")] {
        let sets = corrected(h, r_fine, growth);
        let sets: Vec<&str> = sets.iter().map(String::as_str).collect();
        let (_, summary) = run_case("cases/ru-rough-sphere/rough-w6-quick.toml", &sets, label);
        assert_eq!(summary.status, "completed");
        let dir = workspace_root().join("target").join("test-out").join(label);
        histories.push(history_columns(&dir, &["time", "force", "plastic_dissipation"]));
    }
    // the limit force: 2.99 Y A (the disc on a von Mises half-space)
    let limit = stiction_interfaces::local_footprint::DISC_LIMIT_PRESSURE_OVER_YIELD * 3.42 * AREA;
    let (coarse, fine) = (&histories[0], &histories[1]);
    assert_eq!(coarse.len(), fine.len(), "the same increments");
    let max = |h: &Vec<Vec<f64>>| h.iter().map(|r| r[1]).fold(f64::MIN, f64::max);
    let min = |h: &Vec<Vec<f64>>| h.iter().map(|r| r[1]).fold(f64::MAX, f64::min);
    for h in [coarse, fine] {
        assert!((max(h) - limit).abs() <= 1e-6 * limit && (min(h) + limit).abs() <= 1e-6 * limit);
    }
    // 2.5%: next to the limit the finer mesh's continuum starts to yield under the footprint
    // by itself (first yield comes before the limit load), which the coarse one cannot show
    // (measured: 1.9% at one increment, below 0.6% elsewhere)
    for (a, b) in coarse.iter().zip(fine) {
        assert_eq!(a[0], b[0]);
        assert!((a[1] - b[1]).abs() <= 0.025 * limit, "t {}: force {} coarse, {} fine", a[0], a[1], b[1]);
    }
    let (dc, df) = (coarse.last().unwrap()[2], fine.last().unwrap()[2]);
    assert!((dc - df).abs() <= 0.01 * df, "plastic dissipation {dc} coarse, {df} fine");
}
