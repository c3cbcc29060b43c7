//! The element-kernel trait: an element maps nodal coordinates and displacements to internal
//! forces and a tangent, calling a [`Material`] at each integration point.
//!
//! Kernels fill caller-owned buffers; they allocate nothing per call.

use crate::material::{Material, MaterialError};
use crate::mesh::CellType;
use crate::voigt::Stress;

/// Analysis kinematics.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kinematics {
    /// Three-dimensional solid, 3 displacement components per node.
    Solid3D,
    /// Axisymmetric solid in the (r, z) plane (x = r >= 0, y = z), 2 components per node.
    Axisymmetric,
}

impl Kinematics {
    pub fn dofs_per_node(self) -> usize {
        match self {
            Kinematics::Solid3D => 3,
            Kinematics::Axisymmetric => 2,
        }
    }
    pub fn name(self) -> &'static str {
        match self {
            Kinematics::Solid3D => "3d",
            Kinematics::Axisymmetric => "axisymmetric",
        }
    }
}

/// Caller-owned buffers for one element evaluation.
pub struct ElementBuffers<'a> {
    /// Internal force vector f = integral B^T sigma dV, length n_nodes * dofs_per_node.
    pub force: &'a mut [f64],
    /// Tangent K = integral B^T C B dV, row-major, (n_dofs)^2; `None` when only forces are needed.
    pub stiffness: Option<&'a mut [f64]>,
    /// Stress at each integration point.
    pub stress: &'a mut [Stress],
}

/// A small-strain solid element formulation for one cell type.
pub trait ElementKernel: Send + Sync {
    fn cell_type(&self) -> CellType;
    fn kinematics(&self) -> Kinematics;
    fn n_nodes(&self) -> usize {
        self.cell_type().n_nodes()
    }
    fn n_dofs(&self) -> usize {
        self.n_nodes() * self.kinematics().dofs_per_node()
    }
    /// Number of integration points.
    fn n_points(&self) -> usize;

    /// Evaluates the element: `coords` are the nodal positions, `displacement` the nodal
    /// displacements (node-major), states are `n_points * material.n_state()` long.
    /// Returns the element volume (axisymmetric: 2 pi integral r dA).
    #[allow(clippy::too_many_arguments)]
    fn evaluate(
        &self,
        coords: &[[f64; 3]],
        displacement: &[f64],
        material: &dyn Material,
        state_committed: &[f64],
        state_trial: &mut [f64],
        buffers: ElementBuffers<'_>,
    ) -> Result<f64, ElementFailure>;

    /// How many numbers of a cell's reference geometry the kernel can precompute once and
    /// then evaluate from ([`Self::geometry`], [`Self::evaluate_on_geometry`]); 0 when it
    /// precomputes nothing. Under small strain the geometry is fixed, so a kernel may keep
    /// there what does not depend on the displacement (the spatial shape gradients and the
    /// volume weight at each point).
    fn geometry_len(&self) -> usize {
        0
    }

    /// Writes the cell's reference geometry, [`Self::geometry_len`] numbers, to `out`; fails as
    /// [`Self::evaluate`] does on an inverted or degenerate cell.
    fn geometry(&self, _coords: &[[f64; 3]], _out: &mut [f64]) -> Result<(), ElementFailure> {
        Ok(())
    }

    /// [`Self::evaluate`] from the cell's precomputed `geometry` ([`Self::geometry`]; empty when
    /// the kernel keeps none, and then the default evaluates from `coords`), with the same
    /// result.
    #[allow(clippy::too_many_arguments)]
    fn evaluate_on_geometry(
        &self,
        _geometry: &[f64],
        coords: &[[f64; 3]],
        displacement: &[f64],
        material: &dyn Material,
        state_committed: &[f64],
        state_trial: &mut [f64],
        buffers: ElementBuffers<'_>,
    ) -> Result<f64, ElementFailure> {
        self.evaluate(coords, displacement, material, state_committed, state_trial, buffers)
    }

    /// Weight (volume share) of each integration point, for averages.
    fn point_volumes(&self, coords: &[[f64; 3]], out: &mut [f64]);

    /// The consistent mass of unit density, M_(ai)(bj) = delta_ij integral N_a N_b dV
    /// (axisymmetric: dV = 2 pi r dA), integrated exactly, written row-major (n_dofs)^2 to
    /// `out`: the L2 metric of displacement fields, which a damped (viscous) flow moves in.
    fn mass(&self, coords: &[[f64; 3]], out: &mut [f64]);
}

/// An element evaluation failed.
#[derive(Debug, Clone, PartialEq)]
pub enum ElementFailure {
    /// The material failed at this integration point.
    Material { point: usize, error: MaterialError },
    /// The element is inverted or degenerate (Jacobian determinant <= 0).
    BadJacobian { point: usize, det: f64 },
}
