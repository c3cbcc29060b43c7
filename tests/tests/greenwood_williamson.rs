//! A nominally flat rough surface against the Greenwood-Williamson integral (Greenwood and
//! Williamson, Proc. R. Soc. A 295 (1966) 300). A height map holds N >= 500 paraboloid summits
//! of radius R on a square grid, their heights the N quantiles of a Gaussian (standard deviation
//! sigma; `stiction_tests::gw_surface`); the case reads it through `points.surface` onto the
//! bottom of a stiff block, each summit a `hertz-asperity` point with the summit's own radius
//! (the law's parameter is a deliberately wrong 1 nm, so the test fails unless the map's radii
//! reach the law). With the flat at separation d from the summits' mean plane, GW give
//!
//!   F(d) = N int_d^inf 4/3 E* R^(1/2) (z - d)^(3/2) phi(z) dz,   phi the N(0, sigma^2) density,
//!
//! and the block (10^3 times stiffer than the asperities' E*) barely deforms. N quantiles stand
//! for the Gaussian down to its tail: at d = 1.5 sigma, 33 of 517 summits touch and their sum
//! falls 1.6% short of the integral, at 2 sigma 5% (11 summits); the comparison is made where
//! d <= 1.5 sigma, to 2%.

use stiction_interfaces::height_map::gsf;
use stiction_tests::greenwood_tripp::gaussian_moment;
use stiction_tests::gw_surface::{SummitGrid, summit_map};
use stiction_tests::{Tolerance, claim_output_dir, run_case_file, validate, workspace_root};

const SIGMA: f64 = 1.0;
const RADIUS: f64 = 20.0;
const MODULUS: f64 = 100.0;
const REGION: f64 = 520.0;
const SIZE: f64 = 1200.0;

/// GW's force per summit at separation `d`: int_d^inf 4/3 E* R^(1/2) (z - d)^(3/2) phi(z) dz.
fn gw_force_per_summit(d: f64) -> f64 {
    4.0 / 3.0 * MODULUS * RADIUS.sqrt() * SIGMA.powf(1.5) * gaussian_moment(1.5, d / SIGMA)
}

#[test]
fn hertzian_summits_of_a_height_map_on_a_stiff_block_follow_greenwood_williamson() {
    let dir = claim_output_dir("greenwood-williamson");
    std::fs::create_dir_all(&dir).unwrap();
    let grid = SummitGrid { radius: RADIUS, sigma: SIGMA, spacing: 40.0, region: REGION, size: SIZE, pixel: 4.0 };
    let (map, n) = summit_map(grid);
    assert!(n >= 500, "{n} summits");
    gsf::write(&dir.join("gw-summits.gsf"), &map, "GW test surface").unwrap();
    let geo = workspace_root().join("cases/validation/lj-block.geo");
    let case = format!(
        r#"name = "greenwood-williamson"
analysis = "3d"
[units]
length = "nm"
force = "nN"
[mesh]
geo = "{geo}"
order = 1
parameters = {{ L = 200.0, W = {SIZE}, h = 150.0 }}
[materials.stiff]
model = "linear-elastic"
youngs_modulus = 1.0e5
poissons_ratio = 0.3
[[sections]]
group = "body"
material = "stiff"
[[boundary]]
group = "top"
type = "fixed"
[[interfaces]]
name = "flat"
type = "rigid-flat"
surface = "bottom"
approach = 5.0
initial_gap = 3.5
law = "hertz-asperity"
parameters = {{ modulus = {MODULUS}, radius = 1.0 }}
points = {{ region_radius = {REGION}, surface = {{ file = "gw-summits.gsf" }} }}
[[steps]]
name = "approach"
end_time = 1.0
initial_increment = 0.1
max_increment = 0.1
"#,
        geo = geo.display()
    );
    let case_path = dir.join("greenwood-williamson.toml");
    std::fs::write(&case_path, case).unwrap();
    let summary = run_case_file(&case_path, dir.join("out"));
    assert_eq!(summary.status, "completed");
    let points = std::fs::read_to_string(dir.join("out").join("flat_points.csv")).unwrap();
    assert_eq!(points.lines().next(), Some("x,y,height,radius"));
    assert_eq!(points.lines().count() - 1, n, "every summit in the region is a point");
    let history = std::fs::read_to_string(dir.join("out").join("history.csv")).unwrap();
    let header: Vec<&str> = history.lines().next().unwrap().split(',').collect();
    let column = |name: &str| header.iter().position(|h| *h == name).unwrap_or_else(|| panic!("{name} in {header:?}"));
    let (approach, force) = (column("approach"), column("force"));
    let mut compared = 0;
    for line in history.lines().skip(1) {
        let v: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        let d = 3.5 - v[approach];
        if d > 1.5 * SIGMA + 1e-9 {
            continue;
        }
        validate(
            &format!("Greenwood-Williamson: force of {n} Hertzian summits at d = {d:.2} sigma"),
            "nN",
            v[force],
            n as f64 * gw_force_per_summit(d),
            "Greenwood and Williamson (1966)",
            Tolerance::Relative(0.02),
        );
        compared += 1;
    }
    assert_eq!(compared, 7, "separations 1.5 sigma down to -1.5 sigma");
}
