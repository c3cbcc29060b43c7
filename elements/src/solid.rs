//! Small-strain solid kernels: 3D tetrahedra (tet4, tet10) and axisymmetric triangles
//! (tri3, tri6 in the r-z plane, hoop strain u_r / r).
//!
//! f = sum_q B_q^T sigma_q w_q |J_q| (x 2 pi r_q axisymmetric), K = sum_q B_q^T C_q B_q w_q |J_q|.

use crate::shape;
use stiction_core::element::{ElementBuffers, ElementFailure, ElementKernel, Kinematics};
use stiction_core::material::Material;
use stiction_core::mesh::CellType;
use stiction_core::quadrature::{self, QuadratureRule};
use stiction_core::voigt::{Strain, Stress, Tangent};

/// Which quadrature a kernel uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum QuadratureChoice {
    /// The standard rule: tet4 1 point, tet10 4 points (C3D10), tri3 axisymmetric 3 points,
    /// tri6 axisymmetric 6 points.
    Standard,
    /// A higher rule (collapsed Gauss, degree >= 5) for accuracy studies.
    High,
}

/// Shape data at one integration point, precomputed once per kernel.
#[derive(Debug, Clone)]
struct PointData {
    weight: f64,
    n: Vec<f64>,
    dn: Vec<[f64; 3]>,
}

/// A small-strain solid element for one cell type and kinematics.
#[derive(Debug, Clone)]
pub struct SolidKernel {
    cell: CellType,
    kinematics: Kinematics,
    points: Vec<PointData>,
    /// Points of a rule exact for the mass integrand N_a N_b (x r axisymmetric): degree 4 for
    /// tet10, 5 for tri6 in r-z.
    mass_points: Vec<PointData>,
}

impl SolidKernel {
    /// Creates the kernel; the cell type must suit the kinematics (tets in 3D, triangles in
    /// axisymmetric models).
    pub fn new(cell: CellType, kinematics: Kinematics, choice: QuadratureChoice) -> Result<Self, String> {
        let rule = match (kinematics, cell, choice) {
            (Kinematics::Solid3D, CellType::Tet4, QuadratureChoice::Standard) => quadrature::tetrahedron_1(),
            (Kinematics::Solid3D, CellType::Tet10, QuadratureChoice::Standard) => quadrature::tetrahedron_4(),
            (Kinematics::Solid3D, CellType::Tet4 | CellType::Tet10, QuadratureChoice::High) => {
                quadrature::tetrahedron_collapsed(4)
            }
            (Kinematics::Axisymmetric, CellType::Tri3, QuadratureChoice::Standard) => quadrature::triangle_3(),
            (Kinematics::Axisymmetric, CellType::Tri6, QuadratureChoice::Standard) => quadrature::triangle_6(),
            (Kinematics::Axisymmetric, CellType::Tri3 | CellType::Tri6, QuadratureChoice::High) => {
                quadrature::triangle_collapsed(5)
            }
            _ => {
                return Err(format!(
                    "a {} cannot be used in a {} analysis (3d: 4- or 10-node tetrahedra; axisymmetric: 3- or 6-node triangles)",
                    cell.name(),
                    kinematics.name()
                ));
            }
        };
        Ok(Self::with_rule(cell, kinematics, &rule))
    }

    /// Creates the kernel with an explicit rule.
    pub fn with_rule(cell: CellType, kinematics: Kinematics, rule: &QuadratureRule) -> Self {
        let mass_rule = match kinematics {
            Kinematics::Solid3D => quadrature::tetrahedron_collapsed(4),
            Kinematics::Axisymmetric => quadrature::triangle_collapsed(4),
        };
        Self { cell, kinematics, points: point_data(cell, rule), mass_points: point_data(cell, &mass_rule) }
    }

    /// Spatial derivatives dN/dx at a point; returns (|J| * weight * [2 pi r]).
    fn spatial_derivatives(
        &self,
        p: &PointData,
        coords: &[[f64; 3]],
        dndx: &mut [[f64; 3]],
    ) -> Result<(f64, f64), f64> {
        let d = self.cell.dim();
        // J[i][k] = d x_i / d xi_k (the loops unrolled for the two dimensions)
        let mut j = [[0.0; 3]; 3];
        if d == 3 {
            for (x, dn) in coords.iter().zip(&p.dn) {
                for (ji, xi) in j.iter_mut().zip(x) {
                    ji[0] += xi * dn[0];
                    ji[1] += xi * dn[1];
                    ji[2] += xi * dn[2];
                }
            }
        } else {
            for (x, dn) in coords.iter().zip(&p.dn) {
                j[0][0] += x[0] * dn[0];
                j[0][1] += x[0] * dn[1];
                j[1][0] += x[1] * dn[0];
                j[1][1] += x[1] * dn[1];
            }
        }
        let (det, inv) = if d == 3 {
            let det = j[0][0] * (j[1][1] * j[2][2] - j[1][2] * j[2][1])
                - j[0][1] * (j[1][0] * j[2][2] - j[1][2] * j[2][0])
                + j[0][2] * (j[1][0] * j[2][1] - j[1][1] * j[2][0]);
            let inv = [
                [
                    (j[1][1] * j[2][2] - j[1][2] * j[2][1]) / det,
                    (j[0][2] * j[2][1] - j[0][1] * j[2][2]) / det,
                    (j[0][1] * j[1][2] - j[0][2] * j[1][1]) / det,
                ],
                [
                    (j[1][2] * j[2][0] - j[1][0] * j[2][2]) / det,
                    (j[0][0] * j[2][2] - j[0][2] * j[2][0]) / det,
                    (j[0][2] * j[1][0] - j[0][0] * j[1][2]) / det,
                ],
                [
                    (j[1][0] * j[2][1] - j[1][1] * j[2][0]) / det,
                    (j[0][1] * j[2][0] - j[0][0] * j[2][1]) / det,
                    (j[0][0] * j[1][1] - j[0][1] * j[1][0]) / det,
                ],
            ];
            (det, inv)
        } else {
            let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
            let inv = [[j[1][1] / det, -j[0][1] / det, 0.0], [-j[1][0] / det, j[0][0] / det, 0.0], [0.0; 3]];
            (det, inv)
        };
        if !(det > 0.0) {
            return Err(det);
        }
        // dN/dx_i = sum_k dN/dxi_k (J^-1)[k][i]
        for (g, dn) in dndx.iter_mut().zip(&p.dn) {
            if d == 3 {
                *g = std::array::from_fn(|i| dn[0] * inv[0][i] + dn[1] * inv[1][i] + dn[2] * inv[2][i]);
            } else {
                *g = [dn[0] * inv[0][0] + dn[1] * inv[1][0], dn[0] * inv[0][1] + dn[1] * inv[1][1], 0.0];
            }
        }
        let mut dv = det * p.weight;
        let mut r = 0.0;
        if self.kinematics == Kinematics::Axisymmetric {
            r = coords.iter().zip(&p.n).map(|(x, n)| x[0] * n).sum::<f64>();
            dv *= 2.0 * std::f64::consts::PI * r;
        }
        Ok((dv, r))
    }

    /// The small strain at a point, eps = B u, from dN/dx without forming B. 3D, Voigt order
    /// (xx, yy, zz, 2xy, 2yz, 2zx): eps_ii = sum_a dN_a/dx_i u_ai, 2 eps_ij = sum_a (dN_a/dx_j
    /// u_ai + dN_a/dx_i u_aj). Axisymmetric (rr, zz, tt, 2rz): eps_tt = sum_a N_a u_ar / r.
    fn strain(&self, p: &PointData, dndx: &[[f64; 3]], r: f64, u: &[f64]) -> Strain {
        let mut e: Strain = [0.0; 6];
        match self.kinematics {
            Kinematics::Solid3D => {
                for (g, ua) in dndx.iter().zip(u.chunks_exact(3)) {
                    e[0] += g[0] * ua[0];
                    e[1] += g[1] * ua[1];
                    e[2] += g[2] * ua[2];
                    e[3] += g[1] * ua[0] + g[0] * ua[1];
                    e[4] += g[2] * ua[1] + g[1] * ua[2];
                    e[5] += g[2] * ua[0] + g[0] * ua[2];
                }
            }
            Kinematics::Axisymmetric => {
                for ((g, ua), n) in dndx.iter().zip(u.chunks_exact(2)).zip(&p.n) {
                    e[0] += g[0] * ua[0];
                    e[1] += g[1] * ua[1];
                    e[2] += n * ua[0];
                    e[3] += g[1] * ua[0] + g[0] * ua[1];
                }
                e[2] /= r;
            }
        }
        e
    }

    /// Adds a point's internal force, f_a += B_a^T sigma dv, to `force` without forming B
    /// ([`Self::node_force`] of sigma dv at every node).
    fn add_internal_force(&self, p: &PointData, dndx: &[[f64; 3]], r: f64, sigma: &Stress, dv: f64, force: &mut [f64]) {
        let dpn = self.kinematics.dofs_per_node();
        let s: Stress = std::array::from_fn(|i| sigma[i] * dv);
        for ((g, fa), n) in dndx.iter().zip(force.chunks_exact_mut(dpn)).zip(&p.n) {
            let f = self.node_force(g, *n, r, &s);
            for (x, y) in fa.iter_mut().zip(f) {
                *x += y;
            }
        }
    }

    /// B_a^T s for a node with shape function value `n` and derivatives `g`: 3D, f_i = sum_j
    /// s_ij dN/dx_j; axisymmetric, f_r = s_rr dN/dr + s_rz dN/dz + s_tt N / r and f_z = s_rz
    /// dN/dr + s_zz dN/dz (the third entry 0).
    fn node_force(&self, g: &[f64; 3], n: f64, r: f64, s: &Stress) -> [f64; 3] {
        match self.kinematics {
            Kinematics::Solid3D => [
                g[0] * s[0] + g[1] * s[3] + g[2] * s[5],
                g[1] * s[1] + g[0] * s[3] + g[2] * s[4],
                g[2] * s[2] + g[1] * s[4] + g[0] * s[5],
            ],
            Kinematics::Axisymmetric => [g[0] * s[0] + g[1] * s[3] + n * s[2] / r, g[1] * s[1] + g[0] * s[3], 0.0],
        }
    }

    /// The strain of a unit displacement of component `j` of a node (shape function value
    /// `n`, derivatives `g`), as its (up to) three nonzero Voigt entries (index, value): the
    /// node's column j of B.
    fn unit_strain(&self, g: &[f64; 3], n: f64, r: f64, j: usize) -> [(usize, f64); 3] {
        match (self.kinematics, j) {
            (Kinematics::Solid3D, 0) => [(0, g[0]), (3, g[1]), (5, g[2])],
            (Kinematics::Solid3D, 1) => [(1, g[1]), (3, g[0]), (4, g[2])],
            (Kinematics::Solid3D, _) => [(2, g[2]), (4, g[1]), (5, g[0])],
            (Kinematics::Axisymmetric, 0) => [(0, g[0]), (2, n / r), (3, g[1])],
            (Kinematics::Axisymmetric, _) => [(1, g[1]), (3, g[0]), (0, 0.0)],
        }
    }

    /// Adds a point's stiffness, K_ab += B_a^T C B_b dv, to the row-major `k` without forming
    /// B: column j of C B_b dv is the stress of a unit displacement j of node b
    /// ([`Self::unit_strain`]), and K_ab's column j is the force on node a of that stress
    /// ([`Self::node_force`]). With C symmetric (entry by entry) so is the point's K: only the
    /// blocks with a >= b are added, and [`Self::mirror_stiffness`] adds their transposes to
    /// the blocks a < b once all points are in. A point with C not symmetric adds its blocks
    /// a < b less the transposes of its blocks a > b, so the mirroring leaves exactly its own.
    fn add_stiffness(&self, p: &PointData, dndx: &[[f64; 3]], r: f64, c: &Tangent, dv: f64, k: &mut [f64]) {
        let nd = self.n_dofs();
        let dpn = self.kinematics.dofs_per_node();
        let symmetric = (0..6).all(|i| (0..i).all(|j| c[i][j] == c[j][i]));
        for (b, gb) in dndx.iter().enumerate() {
            for j in 0..dpn {
                let unit = self.unit_strain(gb, p.n[b], r, j);
                let s: Stress = std::array::from_fn(|m| unit.iter().map(|&(l, e)| c[m][l] * e).sum::<f64>() * dv);
                let col = b * dpn + j;
                let first = if symmetric { b } else { 0 };
                for (a, ga) in dndx.iter().enumerate().skip(first) {
                    let f = self.node_force(ga, p.n[a], r, &s);
                    for (i, fi) in f.iter().enumerate().take(dpn) {
                        let row = a * dpn + i;
                        k[row * nd + col] += fi;
                        if !symmetric && a > b {
                            k[col * nd + row] -= fi;
                        }
                    }
                }
            }
        }
    }

    /// Completes a stiffness [`Self::add_stiffness`] filled: K_ab += K_ba^T for every block
    /// a < b.
    fn mirror_stiffness(&self, k: &mut [f64]) {
        let nd = self.n_dofs();
        let dpn = self.kinematics.dofs_per_node();
        for row in 0..nd {
            for col in (row / dpn + 1) * dpn..nd {
                k[row * nd + col] += k[col * nd + row];
            }
        }
    }

    /// Numbers of one point's geometry: dN/dx (3 per node), dv and r.
    fn point_geometry_len(&self) -> usize {
        3 * self.cell.n_nodes() + 2
    }

    /// f = sum_q B_q^T sigma_q dv_q and, when asked, K = sum_q B_q^T C_q B_q dv_q, with each
    /// point's dN/dx, dv and r from `geometry(q, dndx)` (computed from the coordinates, or
    /// read from a precomputed copy: the same numbers); returns the volume sum_q dv_q.
    fn evaluate_points(
        &self,
        geometry: impl Fn(usize, &mut [[f64; 3]]) -> Result<(f64, f64), ElementFailure>,
        displacement: &[f64],
        material: &dyn Material,
        state_committed: &[f64],
        state_trial: &mut [f64],
        buffers: ElementBuffers<'_>,
    ) -> Result<f64, ElementFailure> {
        let nn = self.cell.n_nodes();
        let ns = material.n_state();
        let ElementBuffers { force, mut stiffness, stress } = buffers;
        force.fill(0.0);
        if let Some(k) = stiffness.as_deref_mut() {
            k.fill(0.0);
        }
        let mut dndx = [[0.0; 3]; 10];
        let mut volume = 0.0;
        for (q, p) in self.points.iter().enumerate() {
            let (dv, r) = geometry(q, &mut dndx)?;
            volume += dv;
            let strain = self.strain(p, &dndx[..nn], r, displacement);
            let mut sigma: Stress = [0.0; 6];
            let mut c: Tangent = [[0.0; 6]; 6];
            material
                .update(
                    &strain,
                    &state_committed[q * ns..(q + 1) * ns],
                    &mut state_trial[q * ns..(q + 1) * ns],
                    &mut sigma,
                    &mut c,
                )
                .map_err(|error| ElementFailure::Material { point: q, error })?;
            stress[q] = sigma;
            self.add_internal_force(p, &dndx[..nn], r, &sigma, dv, force);
            if let Some(k) = stiffness.as_deref_mut() {
                self.add_stiffness(p, &dndx[..nn], r, &c, dv, k);
            }
        }
        if let Some(k) = stiffness {
            self.mirror_stiffness(k);
        }
        Ok(volume)
    }
}

/// Shape values and reference derivatives at the points of `rule`.
fn point_data(cell: CellType, rule: &QuadratureRule) -> Vec<PointData> {
    let nn = cell.n_nodes();
    rule.points
        .iter()
        .zip(&rule.weights)
        .map(|(xi, &weight)| {
            let mut n = vec![0.0; nn];
            let mut dn = vec![[0.0; 3]; nn];
            shape::evaluate(cell, xi, &mut n, &mut dn);
            PointData { weight, n, dn }
        })
        .collect()
}

impl ElementKernel for SolidKernel {
    fn cell_type(&self) -> CellType {
        self.cell
    }
    fn kinematics(&self) -> Kinematics {
        self.kinematics
    }
    fn n_points(&self) -> usize {
        self.points.len()
    }

    fn evaluate(
        &self,
        coords: &[[f64; 3]],
        displacement: &[f64],
        material: &dyn Material,
        state_committed: &[f64],
        state_trial: &mut [f64],
        buffers: ElementBuffers<'_>,
    ) -> Result<f64, ElementFailure> {
        let nn = self.cell.n_nodes();
        let geometry = |q: usize, dndx: &mut [[f64; 3]]| {
            self.spatial_derivatives(&self.points[q], coords, &mut dndx[..nn])
                .map_err(|det| ElementFailure::BadJacobian { point: q, det })
        };
        self.evaluate_points(geometry, displacement, material, state_committed, state_trial, buffers)
    }

    /// Per point, dN/dx (3 per node), dv and r ([`Self::spatial_derivatives`]).
    fn geometry_len(&self) -> usize {
        self.points.len() * self.point_geometry_len()
    }

    fn geometry(&self, coords: &[[f64; 3]], out: &mut [f64]) -> Result<(), ElementFailure> {
        let nn = self.cell.n_nodes();
        let mut dndx = [[0.0; 3]; 10];
        for (q, (p, point)) in self.points.iter().zip(out.chunks_exact_mut(self.point_geometry_len())).enumerate() {
            let (dv, r) = self
                .spatial_derivatives(p, coords, &mut dndx[..nn])
                .map_err(|det| ElementFailure::BadJacobian { point: q, det })?;
            for (x, g) in point.chunks_exact_mut(3).zip(&dndx[..nn]) {
                x.copy_from_slice(g);
            }
            point[3 * nn] = dv;
            point[3 * nn + 1] = r;
        }
        Ok(())
    }

    fn evaluate_on_geometry(
        &self,
        geometry: &[f64],
        coords: &[[f64; 3]],
        displacement: &[f64],
        material: &dyn Material,
        state_committed: &[f64],
        state_trial: &mut [f64],
        buffers: ElementBuffers<'_>,
    ) -> Result<f64, ElementFailure> {
        if geometry.len() != self.geometry_len() {
            return self.evaluate(coords, displacement, material, state_committed, state_trial, buffers);
        }
        let nn = self.cell.n_nodes();
        let per_point = self.point_geometry_len();
        let stored = |q: usize, dndx: &mut [[f64; 3]]| {
            let point = &geometry[q * per_point..(q + 1) * per_point];
            for (g, x) in dndx[..nn].iter_mut().zip(point.chunks_exact(3)) {
                *g = [x[0], x[1], x[2]];
            }
            Ok((point[3 * nn], point[3 * nn + 1]))
        };
        self.evaluate_points(stored, displacement, material, state_committed, state_trial, buffers)
    }

    fn point_volumes(&self, coords: &[[f64; 3]], out: &mut [f64]) {
        let mut dndx = [[0.0; 3]; 10];
        for (q, p) in self.points.iter().enumerate() {
            out[q] = self.spatial_derivatives(p, coords, &mut dndx[..self.cell.n_nodes()]).map(|v| v.0).unwrap_or(0.0);
        }
    }

    fn mass(&self, coords: &[[f64; 3]], out: &mut [f64]) {
        let (nn, nd, dpn) = (self.cell.n_nodes(), self.n_dofs(), self.kinematics.dofs_per_node());
        out.fill(0.0);
        let mut dndx = [[0.0; 3]; 10];
        for p in &self.mass_points {
            // an inverted cell has no mass (its stiffness evaluation reports it)
            let Ok((dv, _)) = self.spatial_derivatives(p, coords, &mut dndx[..nn]) else { continue };
            for a in 0..nn {
                for b in 0..nn {
                    let m = p.n[a] * p.n[b] * dv;
                    for c in 0..dpn {
                        out[(a * dpn + c) * nd + b * dpn + c] += m;
                    }
                }
            }
        }
    }
}

impl SolidKernel {
    /// Physical positions of the integration points of one cell.
    pub fn point_positions(&self, coords: &[[f64; 3]]) -> Vec<[f64; 3]> {
        self.points
            .iter()
            .map(|p| {
                let mut x = [0.0; 3];
                for (a, c) in coords.iter().enumerate() {
                    for k in 0..3 {
                        x[k] += p.n[a] * c[k];
                    }
                }
                x
            })
            .collect()
    }
}

#[cfg(test)]
mod tests;
