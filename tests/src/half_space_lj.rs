//! An independent reference for an elastic sphere with Lennard-Jones adhesion against a rigid
//! flat: Greenwood's axisymmetric model (J. A. Greenwood, Proc. R. Soc. A 453, 1277, 1997; also
//! Feng, J. Colloid Interface Sci. 225, 2000). It shares no code with the finite-element model.
//!
//! The sphere is an elastic half-space of plane-strain modulus E* whose surface carries the
//! Derjaguin Lennard-Jones traction of the local gap,
//!   p(h) = (8 w / (3 z0)) [ (z0/h)^3 - (z0/h)^9 ]   (positive = attraction),
//! and the gap of the deformed surface is
//!   h(r) = h_c + s(r) - s(0) - (u(r) - u(0)),   s(r) = R - sqrt(R^2 - r^2),
//! with u the surface displacement towards the flat. The traction is piecewise constant on rings
//! r_j < r < r_j+1, so u = C p exactly, with C from Boussinesq's closed form for a uniformly
//! loaded disc (Johnson, Contact Mechanics, 1985, eqs. 3.29-3.30):
//!   r <= a:  u = (4 p a / (pi E*)) E(r/a)
//!   r >  a:  u = (4 p r / (pi E*)) [ E(a/r) - (1 - a^2/r^2) K(a/r) ]
//! collocated at the ring midpoints. As Greenwood did, the central gap h_c is the load parameter:
//! the load-approach curve is S-shaped above Tabor parameter ~1, but it is single valued in h_c.
//! The approach of the flat is alpha = h_start - h_c - u(0) (zero where the undeformed pole is
//! `h_start` from the flat). The pull-off force is the most tensile force on the curve.
//!
//! The dense influence matrix is the nature of this boundary-element reference (a few hundred
//! rings); it is not part of the finite-element code.

use faer::Mat;
use faer::linalg::solvers::Solve;
use std::f64::consts::PI;

/// Complete elliptic integrals of the first and second kind, K(k) and E(k), of modulus k < 1, by
/// the arithmetic-geometric mean: K = pi / (2 AGM(1, sqrt(1 - k^2))),
/// E = K (1 - sum_n 2^(n-1) c_n^2) with c_0 = k, c_n+1 = (a_n - b_n) / 2.
pub fn elliptic_k_e(k: f64) -> (f64, f64) {
    assert!((0.0..1.0).contains(&k), "modulus {k} outside [0, 1)");
    let (mut a, mut b, mut c) = (1.0f64, (1.0 - k * k).sqrt(), k);
    let mut sum = 0.5 * c * c;
    let mut power = 0.5;
    // AGM converges quadratically: 8 rounds reach rounding for k < 1 - 1e-12
    for _ in 0..40 {
        if c.abs() <= 1e-15 * a {
            break;
        }
        let next = (0.5 * (a + b), (a * b).sqrt(), 0.5 * (a - b));
        (a, b, c) = next;
        power *= 2.0;
        sum += power * c * c;
    }
    let big_k = PI / (2.0 * a);
    (big_k, big_k * (1.0 - sum))
}

/// Normal surface displacement at radius r of an elastic half-space (modulus E*) under a unit
/// uniform pressure on the disc of radius a (Johnson eqs. 3.29-3.30, see the module doc).
pub fn disc_displacement(r: f64, a: f64, e_star: f64) -> f64 {
    if a == 0.0 {
        return 0.0;
    }
    if r == a {
        // E(1) = 1
        4.0 * a / (PI * e_star)
    } else if r < a {
        4.0 * a / (PI * e_star) * elliptic_k_e(r / a).1
    } else {
        let (big_k, big_e) = elliptic_k_e(a / r);
        4.0 * r / (PI * e_star) * (big_e - (1.0 - a * a / (r * r)) * big_k)
    }
}

/// The sphere, its elastic modulus and the Lennard-Jones law.
#[derive(Clone, Copy, Debug)]
pub struct SphereLj {
    /// Sphere radius R.
    pub radius: f64,
    /// Plane-strain modulus E* = E / (1 - nu^2) (rigid flat).
    pub e_star: f64,
    /// Work of adhesion w.
    pub w: f64,
    /// Equilibrium separation z0.
    pub z0: f64,
}

impl SphereLj {
    /// Tabor parameter mu = (R w^2 / (E*^2 z0^3))^(1/3).
    pub fn tabor(&self) -> f64 {
        (self.radius * self.w * self.w / (self.e_star * self.e_star * self.z0.powi(3))).cbrt()
    }

    /// JKR contact radius at zero load, a0 = (9 pi w R^2 / (2 E*))^(1/3): the grid's scale.
    pub fn jkr_radius(&self) -> f64 {
        (9.0 * PI * self.w * self.radius * self.radius / (2.0 * self.e_star)).cbrt()
    }

    /// Traction p(h) (positive = attraction) and its derivative dp/dh.
    pub fn traction(&self, h: f64) -> (f64, f64) {
        let s = self.z0 / h;
        let (s3, s9) = (s.powi(3), s.powi(9));
        let scale = 8.0 * self.w / (3.0 * self.z0);
        (scale * (s3 - s9), scale * (-3.0 * s3 + 9.0 * s9) / h)
    }
}

/// The radial grid: uniform rings of width `spacing` out to `fine_radius`, then rings growing by
/// `growth` per ring out to `outer_radius`.
#[derive(Clone, Copy, Debug)]
pub struct RingGrid {
    pub spacing: f64,
    pub fine_radius: f64,
    pub growth: f64,
    pub outer_radius: f64,
}

impl RingGrid {
    /// The ring edges r_0 = 0 < r_1 < ... < r_N.
    pub fn edges(&self) -> Vec<f64> {
        let mut edges = vec![0.0];
        let mut width = self.spacing;
        while *edges.last().unwrap() < self.outer_radius {
            let last = *edges.last().unwrap();
            if last >= self.fine_radius {
                width *= self.growth;
            }
            edges.push(last + width);
        }
        edges
    }
}

/// A sphere's cap on rings: their edges, midpoints and areas, the sphere's profile
/// s = R - sqrt(R^2 - r^2) at the midpoints, and the half-space's influence matrix C (the
/// displacement at midpoint i of a unit pressure on ring j).
pub struct Rings {
    pub edges: Vec<f64>,
    pub mid: Vec<f64>,
    pub ring_area: Vec<f64>,
    pub profile: Vec<f64>,
    pub influence: Mat<f64>,
}

impl Rings {
    /// The rings of `grid` on a sphere of radius `radius` and modulus `e_star`.
    pub fn new(radius: f64, e_star: f64, grid: RingGrid) -> Self {
        assert!(grid.outer_radius < 0.5 * radius, "the grid must stay on the cap of the sphere");
        let edges = grid.edges();
        let n = edges.len() - 1;
        let mid: Vec<f64> = (0..n).map(|j| 0.5 * (edges[j] + edges[j + 1])).collect();
        let ring_area = (0..n).map(|j| PI * (edges[j + 1].powi(2) - edges[j].powi(2))).collect();
        let profile = mid.iter().map(|&x| radius - (radius * radius - x * x).sqrt()).collect();
        let influence = Mat::from_fn(n, n, |i, j| {
            disc_displacement(mid[i], edges[j + 1], e_star) - disc_displacement(mid[i], edges[j], e_star)
        });
        Self { edges, mid, ring_area, profile, influence }
    }
}

/// One equilibrium on the load-approach curve.
#[derive(Clone, Copy, Debug)]
pub struct CurvePoint {
    /// The gap at the pole h_c.
    pub central_gap: f64,
    /// The approach of the flat from where the undeformed pole is `h_start` away.
    pub approach: f64,
    /// The force on the flat, positive = compressive (the finite-element sign).
    pub force: f64,
}

/// What the traced curve gives.
#[derive(Clone, Debug)]
pub struct CurveSummary {
    pub points: Vec<CurvePoint>,
    /// Most tensile force on the curve (negative), refined by a parabola through its neighbours.
    pub pull_off_force: f64,
    /// The limit points of the approach (jump-in: its first local maximum; jump-out: the local
    /// minimum after it), as (approach, force), when the curve is S-shaped.
    pub jump_in: Option<(f64, f64)>,
    pub jump_out: Option<(f64, f64)>,
}

/// Greenwood's half-space model of one sphere on one grid.
pub struct HalfSpaceLj {
    pub sphere: SphereLj,
    edges: Vec<f64>,
    mid: Vec<f64>,
    ring_area: Vec<f64>,
    profile: Vec<f64>,
    influence: Mat<f64>,
}

impl HalfSpaceLj {
    pub fn new(sphere: SphereLj, grid: RingGrid) -> Self {
        let Rings { edges, mid, ring_area, profile, influence } = Rings::new(sphere.radius, sphere.e_star, grid);
        Self { sphere, edges, mid, ring_area, profile, influence }
    }

    /// Number of rings.
    pub fn rings(&self) -> usize {
        self.mid.len()
    }

    /// The outer edge of the grid.
    pub fn outer_radius(&self) -> f64 {
        *self.edges.last().unwrap()
    }

    /// The gaps h_j of the displacement u at central gap h_c.
    fn gaps(&self, u: &[f64], central_gap: f64) -> Vec<f64> {
        (0..self.rings()).map(|j| central_gap + self.profile[j] - self.profile[0] - (u[j] - u[0])).collect()
    }

    /// Force on the flat (positive = compressive) of the gaps h.
    fn force(&self, h: &[f64]) -> f64 {
        -h.iter().zip(&self.ring_area).map(|(&g, &a)| self.sphere.traction(g).0 * a).sum::<f64>()
    }

    /// Newton's method for u = C p(h(u)) at fixed central gap, from `u` (overwritten). The
    /// Jacobian is J = I + C diag(p') - (C p') e_0^T; steps are scaled so that no gap changes by
    /// more than z0 / 4 at once. Returns false if it does not converge in 40 iterations or a gap
    /// closes.
    fn solve(&self, u: &mut [f64], central_gap: f64) -> bool {
        let n = self.rings();
        let c = &self.influence;
        for _ in 0..40 {
            let h = self.gaps(u, central_gap);
            if h.iter().any(|&g| g <= 0.0) {
                return false;
            }
            let (p, dp): (Vec<f64>, Vec<f64>) = h.iter().map(|&g| self.sphere.traction(g)).unzip();
            let cp: Vec<f64> = (0..n).map(|i| (0..n).map(|j| c[(i, j)] * p[j]).sum()).collect();
            let residual: Vec<f64> = (0..n).map(|i| u[i] - cp[i]).collect();
            let scale = u.iter().fold(self.sphere.z0, |m, &x| m.max(x.abs()));
            if residual.iter().all(|r| r.abs() < 1e-11 * scale) {
                return true;
            }
            let c_dp: Vec<f64> = (0..n).map(|i| (0..n).map(|j| c[(i, j)] * dp[j]).sum()).collect();
            let jacobian = Mat::from_fn(n, n, |i, k| {
                let identity = if i == k { 1.0 } else { 0.0 };
                let pinned = if k == 0 { c_dp[i] } else { 0.0 };
                identity + c[(i, k)] * dp[k] - pinned
            });
            let mut step = Mat::from_fn(n, 1, |i, _| -residual[i]);
            jacobian.partial_piv_lu().solve_in_place(&mut step);
            let largest = (0..n).map(|j| (step[(j, 0)] - step[(0, 0)]).abs()).fold(0.0, f64::max);
            let damping = (0.25 * self.sphere.z0 / largest).min(1.0);
            if !damping.is_finite() {
                return false;
            }
            for (x, j) in u.iter_mut().zip(0..n) {
                *x += damping * step[(j, 0)];
            }
        }
        false
    }

    /// Traces the curve from central gap `h_start` (u = 0 as the first guess) towards contact
    /// until the force is compressive by `stop_force`. Central-gap steps are at most `max_step`
    /// and are halved where Newton fails or where the force would change by more than
    /// `max_force_step` (the force is steep in h_c once in contact); a secant predictor starts
    /// each solve.
    pub fn trace(&self, h_start: f64, max_step: f64, max_force_step: f64, stop_force: f64) -> CurveSummary {
        let mut u = vec![0.0; self.rings()];
        assert!(self.solve(&mut u, h_start), "no equilibrium at the start");
        let mut points = vec![self.point(&u, h_start, h_start)];
        let (mut previous_u, mut previous_gap) = (u.clone(), h_start);
        let mut step = max_step;
        while points.last().unwrap().force < stop_force {
            let last = *points.last().unwrap();
            assert!(step > 1e-10 * self.sphere.z0, "central-gap step collapsed at {}", last.central_gap);
            let target = last.central_gap - step;
            let ratio = if previous_gap != last.central_gap { step / (previous_gap - last.central_gap) } else { 0.0 };
            let mut trial: Vec<f64> = u.iter().zip(&previous_u).map(|(x, y)| x + ratio * (x - y)).collect();
            if !self.solve(&mut trial, target) {
                step *= 0.5;
                continue;
            }
            let point = self.point(&trial, target, h_start);
            let force_step = (point.force - last.force).abs();
            if force_step > max_force_step {
                step *= 0.5;
                continue;
            }
            (previous_u, previous_gap) = (std::mem::replace(&mut u, trial), last.central_gap);
            points.push(point);
            if force_step < 0.5 * max_force_step {
                step = (step * 1.5).min(max_step);
            }
        }
        summarize(points)
    }

    fn point(&self, u: &[f64], central_gap: f64, h_start: f64) -> CurvePoint {
        let h = self.gaps(u, central_gap);
        CurvePoint { central_gap, approach: h_start - central_gap - u[0], force: self.force(&h) }
    }
}

/// The pull-off (most tensile force, refined by a parabola in the central gap through the
/// smallest sample and its neighbours) and the limit points of the approach.
fn summarize(points: Vec<CurvePoint>) -> CurveSummary {
    let i = (0..points.len()).min_by(|&a, &b| points[a].force.total_cmp(&points[b].force)).unwrap();
    let mut pull_off_force = points[i].force;
    if i > 0 && i + 1 < points.len() {
        let (x0, x1, x2) = (points[i - 1].central_gap, points[i].central_gap, points[i + 1].central_gap);
        let (f0, f1, f2) = (points[i - 1].force, points[i].force, points[i + 1].force);
        // the parabola's vertex through three points (divided differences)
        let d01 = (f1 - f0) / (x1 - x0);
        let d12 = (f2 - f1) / (x2 - x1);
        let curvature = (d12 - d01) / (x2 - x0);
        if curvature > 0.0 {
            let slope_at_x1 = d01 + curvature * (x1 - x0);
            pull_off_force = f1 - slope_at_x1 * slope_at_x1 / (4.0 * curvature);
        }
    }
    let turning = |from: usize, up: bool| {
        (from.max(1)..points.len().saturating_sub(1)).find(|&k| {
            let (a, b, c) = (points[k - 1].approach, points[k].approach, points[k + 1].approach);
            if up { b > a && b >= c } else { b < a && b <= c }
        })
    };
    let jump_in = turning(1, true);
    let jump_out = jump_in.and_then(|k| turning(k + 1, false));
    let at = |k: usize| (points[k].approach, points[k].force);
    CurveSummary { pull_off_force, jump_in: jump_in.map(at), jump_out: jump_out.map(at), points }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Tabulated values (Abramowitz & Stegun, table 17.1, m = k^2 = 0.5): K = 1.8540747,
    /// E = 1.3506439; k = 0: both pi/2.
    #[test]
    fn elliptic_integrals_match_the_table() {
        let (k, e) = elliptic_k_e(0.5f64.sqrt());
        assert!((k - 1.854_074_677).abs() < 1e-8 && (e - 1.350_643_881).abs() < 1e-8, "{k} {e}");
        let (k0, e0) = elliptic_k_e(0.0);
        assert!((k0 - PI / 2.0).abs() < 1e-14 && (e0 - PI / 2.0).abs() < 1e-14);
    }

    /// The displacement under a uniformly loaded disc: 2 p a / E* at the centre, 4 p a / (pi E*)
    /// at the edge (Johnson 3.29), and p a^2 / (E* r) far away (Boussinesq: a point force
    /// P = pi a^2 p gives P / (pi E* r)).
    #[test]
    fn disc_displacement_matches_the_closed_forms() {
        let (a, e) = (2.0, 100.0);
        assert!((disc_displacement(0.0, a, e) - 2.0 * a / e).abs() < 1e-14);
        assert!((disc_displacement(a, a, e) - 4.0 * a / (PI * e)).abs() < 1e-12);
        let far = 1000.0 * a;
        let point_force = a * a / (e * far);
        assert!((disc_displacement(far, a, e) / point_force - 1.0).abs() < 1e-5);
    }

    /// The Lennard-Jones law: its integral from z0 to infinity is w, its peak is 16 w / (9 sqrt 3 z0)
    /// at 3^(1/6) z0, and dp/dh matches central differences.
    #[test]
    fn traction_law_integrates_to_w() {
        let s = SphereLj { radius: 1000.0, e_star: 450.5, w: 3.0, z0: 0.169 };
        let (mut integral, n) = (0.0, 2_000_000);
        let top = 200.0 * s.z0;
        let dh = (top - s.z0) / n as f64;
        for i in 0..n {
            integral += s.traction(s.z0 + (i as f64 + 0.5) * dh).0 * dh;
        }
        assert!((integral / s.w - 1.0).abs() < 1e-4, "{integral}");
        let peak = s.traction(3f64.powf(1.0 / 6.0) * s.z0).0;
        assert!((peak / (16.0 * s.w / (9.0 * 3f64.sqrt() * s.z0)) - 1.0).abs() < 1e-12);
        for h in [0.9 * s.z0, 1.3 * s.z0, 2.5 * s.z0] {
            let d = 1e-6 * s.z0;
            let fd = (s.traction(h + d).0 - s.traction(h - d).0) / (2.0 * d);
            assert!((s.traction(h).1 / fd - 1.0).abs() < 1e-7);
        }
    }

    /// The rigid limit (E* x 1e4, Tabor parameter 5e-3): Bradley's 2 pi w R, to 2e-3 (the exact
    /// sphere profile and the grid's outer edge differ from Derjaguin's parabola by less).
    #[test]
    fn pull_off_tends_to_bradley_for_small_tabor_parameter() {
        let rigid = SphereLj { radius: 1000.0, e_star: 450.5e4, w: 1.0, z0: 0.169 };
        let grid = RingGrid { spacing: 0.5, fine_radius: 30.0, growth: 1.05, outer_radius: 400.0 };
        let scale = PI * rigid.w * rigid.radius;
        let curve = HalfSpaceLj::new(rigid, grid).trace(3.0 * rigid.z0, 0.05 * rigid.z0, 0.01 * scale, 0.5 * scale);
        let ratio = -curve.pull_off_force / (2.0 * PI * rigid.w * rigid.radius);
        assert!((ratio - 1.0).abs() < 2e-3, "rigid: {ratio}");
        assert!(curve.jump_in.is_none(), "a rigid sphere has no jump");
    }

    /// The reference is converged on its grid: halving the ring width (0.4 -> 0.2 nm) and the
    /// force step moves the pull-off at Tabor parameter 2.1 by less than 1e-3 (measured 4e-4;
    /// 0.2 -> 0.1 nm moved it by 1e-5 at w = 1, 3 and 6).
    #[test]
    fn pull_off_is_converged_on_the_grid() {
        let sphere = SphereLj { radius: 1000.0, e_star: 450.5, w: 3.0, z0: 0.169 };
        let scale = PI * sphere.w * sphere.radius;
        let pull_off = |spacing: f64, force_step: f64| {
            let grid = RingGrid { spacing, fine_radius: 1.3 * sphere.jkr_radius(), growth: 1.05, outer_radius: 300.0 };
            HalfSpaceLj::new(sphere, grid)
                .trace(3.0 * sphere.z0, 0.02 * sphere.z0, force_step * scale, 0.3 * scale)
                .pull_off_force
        };
        let (coarse, fine) = (pull_off(0.4, 0.02), pull_off(0.2, 0.01));
        assert!((coarse / fine - 1.0).abs() < 1e-3, "{coarse} vs {fine}");
    }
}
