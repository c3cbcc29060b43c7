//! Boundary-face integration: 3- and 6-node triangles on 3D surfaces, 2- and 3-node lines on
//! axisymmetric boundaries (surface element dA = 2 pi r ds).
//!
//! Nodal forces of a traction t(x, n): f_a = integral N_a t dA.

use crate::shape;
use stiction_core::element::Kinematics;
use stiction_core::mesh::CellType;
use stiction_core::quadrature::{self, QuadratureRule};

/// One integration point of a face: position, outward unit normal, area weight, shape values.
#[derive(Debug, Clone)]
pub struct FacePoint {
    pub position: [f64; 3],
    pub normal: [f64; 3],
    pub area: f64,
    pub shape: Vec<f64>,
}

/// Integrates over boundary faces of one type.
#[derive(Debug, Clone)]
pub struct FaceIntegrator {
    cell: CellType,
    kinematics: Kinematics,
    rule: QuadratureRule,
    shapes: Vec<(Vec<f64>, Vec<[f64; 3]>)>,
}

impl FaceIntegrator {
    /// The standard rule for the face type; `extra_order` adds Gauss points per direction
    /// (short-range interface laws want more).
    pub fn new(cell: CellType, kinematics: Kinematics, extra_order: usize) -> Result<Self, String> {
        let rule = match (kinematics, cell) {
            (Kinematics::Solid3D, CellType::Tri3) if extra_order == 0 => quadrature::triangle_3(),
            (Kinematics::Solid3D, CellType::Tri6) if extra_order == 0 => quadrature::triangle_6(),
            (Kinematics::Solid3D, CellType::Tri3 | CellType::Tri6) => quadrature::triangle_collapsed(3 + extra_order),
            (Kinematics::Axisymmetric, CellType::Line2) => quadrature::gauss_legendre(2 + extra_order),
            (Kinematics::Axisymmetric, CellType::Line3) => quadrature::gauss_legendre(3 + extra_order),
            _ => {
                return Err(format!(
                    "a {} is not a boundary face of a {} model (3d: 3- or 6-node triangles; axisymmetric: 2- or 3-node lines)",
                    cell.name(),
                    kinematics.name()
                ));
            }
        };
        let nn = cell.n_nodes();
        let shapes = rule
            .points
            .iter()
            .map(|xi| {
                let mut n = vec![0.0; nn];
                let mut dn = vec![[0.0; 3]; nn];
                shape::evaluate(cell, xi, &mut n, &mut dn);
                (n, dn)
            })
            .collect();
        Ok(Self { cell, kinematics, rule, shapes })
    }

    pub fn cell_type(&self) -> CellType {
        self.cell
    }
    pub fn n_points(&self) -> usize {
        self.rule.len()
    }

    /// Integration points of one face. `sign` (+1 or -1) orients the normal outward.
    pub fn points(&self, coords: &[[f64; 3]], sign: f64) -> Vec<FacePoint> {
        let mut out = Vec::with_capacity(self.rule.len());
        for ((n, dn), &w) in self.shapes.iter().zip(&self.rule.weights) {
            let mut x = [0.0; 3];
            let mut t1 = [0.0; 3];
            let mut t2 = [0.0; 3];
            for (a, c) in coords.iter().enumerate() {
                for k in 0..3 {
                    x[k] += n[a] * c[k];
                    t1[k] += dn[a][0] * c[k];
                    t2[k] += dn[a][1] * c[k];
                }
            }
            let (normal, da) = match self.kinematics {
                Kinematics::Solid3D => {
                    let m =
                        [t1[1] * t2[2] - t1[2] * t2[1], t1[2] * t2[0] - t1[0] * t2[2], t1[0] * t2[1] - t1[1] * t2[0]];
                    let len = (m[0] * m[0] + m[1] * m[1] + m[2] * m[2]).sqrt();
                    ([sign * m[0] / len, sign * m[1] / len, sign * m[2] / len], len * w)
                }
                Kinematics::Axisymmetric => {
                    let len = (t1[0] * t1[0] + t1[1] * t1[1]).sqrt();
                    // normal to the right of the tangent: (t_z, -t_r)
                    ([sign * t1[1] / len, -sign * t1[0] / len, 0.0], len * w * 2.0 * std::f64::consts::PI * x[0])
                }
            };
            out.push(FacePoint { position: x, normal, area: da, shape: n.clone() });
        }
        out
    }

    /// Area of a face (axisymmetric: of the surface of revolution).
    pub fn area(&self, coords: &[[f64; 3]]) -> f64 {
        self.points(coords, 1.0).iter().map(|p| p.area).sum()
    }

    /// Adds f_a += integral N_a t(x, n) dA to `out` (n_nodes x dofs_per_node).
    pub fn integrate_traction(
        &self,
        coords: &[[f64; 3]],
        sign: f64,
        traction: impl Fn([f64; 3], [f64; 3]) -> [f64; 3],
        out: &mut [f64],
    ) {
        let dpn = self.kinematics.dofs_per_node();
        for p in self.points(coords, sign) {
            let t = traction(p.position, p.normal);
            for (a, na) in p.shape.iter().enumerate() {
                for k in 0..dpn {
                    out[a * dpn + k] += na * t[k] * p.area;
                }
            }
        }
    }
}
