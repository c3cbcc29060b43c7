//! Quadrature rules as plain data: points in reference coordinates and weights.
//!
//! Reference cells: line [-1, 1]; triangle {x, y >= 0, x + y <= 1} (area 1/2);
//! tetrahedron {x, y, z >= 0, x + y + z <= 1} (volume 1/6).

/// A quadrature rule: `points[i]` (unused coordinates are 0) with weight `weights[i]`.
#[derive(Debug, Clone, PartialEq)]
pub struct QuadratureRule {
    pub points: Vec<[f64; 3]>,
    pub weights: Vec<f64>,
}

impl QuadratureRule {
    pub fn len(&self) -> usize {
        self.weights.len()
    }
    pub fn is_empty(&self) -> bool {
        self.weights.is_empty()
    }
}

/// n-point Gauss-Legendre rule on [-1, 1] (exact to degree 2n - 1); nodes by Newton iteration
/// on the Legendre polynomial P_n, weights w = 2 / ((1 - x^2) P_n'(x)^2).
pub fn gauss_legendre(n: usize) -> QuadratureRule {
    assert!(n >= 1, "a Gauss rule needs at least one point");
    let mut points = Vec::with_capacity(n);
    let mut weights = Vec::with_capacity(n);
    for i in 0..n {
        let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut dp = 0.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0, x);
            for k in 2..=n {
                let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                p0 = p1;
                p1 = p2;
            }
            let pn = if n == 1 { x } else { p1 };
            let pnm1 = if n == 1 { 1.0 } else { p0 };
            dp = n as f64 * (x * pn - pnm1) / (x * x - 1.0);
            let dx = pn / dp;
            x -= dx;
            if dx.abs() < 1e-16 {
                break;
            }
        }
        points.push([x, 0.0, 0.0]);
        weights.push(2.0 / ((1.0 - x * x) * dp * dp));
    }
    QuadratureRule { points, weights }
}

/// Triangle rule by collapsing an n x n Gauss square (Duffy): x = u, y = v (1 - u) with
/// u, v in [0, 1]; Jacobian (1 - u). Exact to degree 2n - 2.
pub fn triangle_collapsed(n: usize) -> QuadratureRule {
    let g = gauss_legendre(n);
    let mut rule = QuadratureRule { points: vec![], weights: vec![] };
    for (pu, wu) in g.points.iter().zip(&g.weights) {
        let u = 0.5 * (pu[0] + 1.0);
        for (pv, wv) in g.points.iter().zip(&g.weights) {
            let v = 0.5 * (pv[0] + 1.0);
            rule.points.push([u, v * (1.0 - u), 0.0]);
            rule.weights.push(0.25 * wu * wv * (1.0 - u));
        }
    }
    rule
}

/// Tetrahedron rule by collapsing an n^3 Gauss cube: x = u, y = v (1 - u),
/// z = w (1 - u)(1 - v); Jacobian (1 - u)^2 (1 - v). Exact to degree 2n - 3.
pub fn tetrahedron_collapsed(n: usize) -> QuadratureRule {
    let g = gauss_legendre(n);
    let mut rule = QuadratureRule { points: vec![], weights: vec![] };
    for (pu, wu) in g.points.iter().zip(&g.weights) {
        let u = 0.5 * (pu[0] + 1.0);
        for (pv, wv) in g.points.iter().zip(&g.weights) {
            let v = 0.5 * (pv[0] + 1.0);
            for (pw, ww) in g.points.iter().zip(&g.weights) {
                let w = 0.5 * (pw[0] + 1.0);
                rule.points.push([u, v * (1.0 - u), w * (1.0 - u) * (1.0 - v)]);
                rule.weights.push(0.125 * wu * wv * ww * (1.0 - u) * (1.0 - u) * (1.0 - v));
            }
        }
    }
    rule
}

/// One-point centroid rule of the triangle (degree 1).
pub fn triangle_1() -> QuadratureRule {
    QuadratureRule { points: vec![[1.0 / 3.0, 1.0 / 3.0, 0.0]], weights: vec![0.5] }
}

/// Three-point interior rule of the triangle (degree 2): points (1/6, 1/6), (2/3, 1/6), (1/6, 2/3).
pub fn triangle_3() -> QuadratureRule {
    let (a, b) = (1.0 / 6.0, 2.0 / 3.0);
    QuadratureRule { points: vec![[a, a, 0.0], [b, a, 0.0], [a, b, 0.0]], weights: vec![1.0 / 6.0; 3] }
}

/// Six-point rule of the triangle (Dunavant, degree 4).
pub fn triangle_6() -> QuadratureRule {
    let (a1, w1) = (0.445_948_490_915_965, 0.223_381_589_678_011 / 2.0);
    let (a2, w2) = (0.091_576_213_509_771, 0.109_951_743_655_322 / 2.0);
    let (b1, b2) = (1.0 - 2.0 * a1, 1.0 - 2.0 * a2);
    QuadratureRule {
        points: vec![[a1, a1, 0.0], [b1, a1, 0.0], [a1, b1, 0.0], [a2, a2, 0.0], [b2, a2, 0.0], [a2, b2, 0.0]],
        weights: vec![w1, w1, w1, w2, w2, w2],
    }
}

/// One-point centroid rule of the tetrahedron (degree 1).
pub fn tetrahedron_1() -> QuadratureRule {
    QuadratureRule { points: vec![[0.25, 0.25, 0.25]], weights: vec![1.0 / 6.0] }
}

/// Four-point rule of the tetrahedron (degree 2), the C3D10 rule:
/// a = (5 + 3 sqrt 5)/20, b = (5 - sqrt 5)/20, weights 1/24.
pub fn tetrahedron_4() -> QuadratureRule {
    let s5 = 5f64.sqrt();
    let a = (5.0 + 3.0 * s5) / 20.0;
    let b = (5.0 - s5) / 20.0;
    QuadratureRule { points: vec![[b, b, b], [a, b, b], [b, a, b], [b, b, a]], weights: vec![1.0 / 24.0; 4] }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Exact integral of x^i y^j over the reference triangle: i! j! / (i + j + 2)!.
    fn tri_monomial(i: u32, j: u32) -> f64 {
        let f = |n: u32| (1..=n).map(|k| k as f64).product::<f64>();
        f(i) * f(j) / f(i + j + 2)
    }
    /// Exact integral of x^i y^j z^k over the reference tetrahedron: i! j! k! / (i + j + k + 3)!.
    fn tet_monomial(i: u32, j: u32, k: u32) -> f64 {
        let f = |n: u32| (1..=n).map(|k| k as f64).product::<f64>();
        f(i) * f(j) * f(k) / f(i + j + k + 3)
    }

    #[test]
    fn gauss_legendre_is_exact_to_degree_2n_minus_1() {
        for n in 1..8 {
            let g = gauss_legendre(n);
            for p in 0..(2 * n) as i32 {
                let q: f64 = g.points.iter().zip(&g.weights).map(|(x, w)| w * x[0].powi(p)).sum();
                let exact = if p % 2 == 1 { 0.0 } else { 2.0 / (p as f64 + 1.0) };
                assert!((q - exact).abs() < 1e-13, "n={n} p={p}: {q} vs {exact}");
            }
        }
    }

    #[test]
    fn triangle_rules_are_exact_to_their_degree() {
        for (rule, deg) in [(triangle_1(), 1), (triangle_3(), 2), (triangle_6(), 4), (triangle_collapsed(4), 6)] {
            for i in 0..=deg {
                for j in 0..=(deg - i) {
                    let q: f64 = rule
                        .points
                        .iter()
                        .zip(&rule.weights)
                        .map(|(p, w)| w * p[0].powi(i as i32) * p[1].powi(j as i32))
                        .sum();
                    let e = tri_monomial(i, j);
                    assert!((q - e).abs() < 1e-12 * e.max(1e-3), "deg {deg} x^{i}y^{j}: {q} vs {e}");
                }
            }
        }
    }

    #[test]
    fn tetrahedron_rules_are_exact_to_their_degree() {
        for (rule, deg) in [(tetrahedron_1(), 1), (tetrahedron_4(), 2), (tetrahedron_collapsed(4), 5)] {
            for i in 0..=deg {
                for j in 0..=(deg - i) {
                    for k in 0..=(deg - i - j) {
                        let q: f64 = rule
                            .points
                            .iter()
                            .zip(&rule.weights)
                            .map(|(p, w)| w * p[0].powi(i as i32) * p[1].powi(j as i32) * p[2].powi(k as i32))
                            .sum();
                        let e = tet_monomial(i, j, k);
                        assert!((q - e).abs() < 1e-12, "deg {deg} {i}{j}{k}: {q} vs {e}");
                    }
                }
            }
        }
    }
}
