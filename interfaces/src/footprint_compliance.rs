//! The footprint's elastic compliance that a mesh coarser than the footprints misses,
//! computed per point from the mesh itself (the compliance of
//! [`crate::local_footprint::SeriesWithFootprint`]):
//!   c_i = K / a - c_h(a) + (w_b . K_h^-1 w_a - u_b),   K = 16 (1 - nu^2) / (3 pi^2 E),
//! with a the footprint's radius, w_a its node weights times the normal (the uniform load
//! over the footprint), c_h(a) = w_a . K_h^-1 w_a the mesh's compliance for it (K_h the
//! body's elastic stiffness with its boundary conditions, factored once:
//! [`ElasticFlexibility`]), and w_b the weights of a concentric disc of radius b that the mesh
//! resolves (three face edges, at least three footprint radii). On a half-space the
//! footprint's compliance is K / a exactly (Johnson, Contact Mechanics, 3.4); a finite body
//! adds its global compliance, which the bracket measures: by reciprocity w_b . K_h^-1 w_a is
//! the mean over the footprint of the mesh's displacement under the resolved disc b of unit
//! force, and on a half-space that mean is
//!   u_b = 2 (1 - nu^2) / (pi E b) (1 - a^2 / (8 b^2) - a^4 / (64 b^4))
//! (the disc's displacement 4 (1 - nu^2) p b E(r / b) / (pi E), E the complete elliptic
//! integral, averaged over r < a). One solve per point (in blocks of 32 right-hand sides);
//! c_i tends to zero as the mesh resolves the footprint.
//!
//! It does not know the case file: the caller builds the body's model (its sections and
//! boundary conditions, no interfaces), checks that the factor fits, and names the keys in its
//! errors.

use crate::local_footprint::{compliance_state_index, disc_compliance};
use crate::point_placement::{DiscretePoint, place_points};
use crate::rigid_flat::RigidFlat;
use stiction_core::CoreError;
use stiction_core::linear_solver::{FaerCholesky, LinearSolver};
use stiction_core::mesh::Mesh;
use stiction_core::model::{Contribution, Model};

/// The body's elastic stiffness at rest with its boundary conditions, factored once: the
/// compliance of any load pattern by one solve.
pub struct ElasticFlexibility {
    model: Model,
    solver: FaerCholesky,
    free_index: Vec<usize>,
}

/// Why the body's flexibility could not be had.
#[derive(Debug)]
pub enum FlexibilityError<E> {
    /// Assembling or factoring the body's stiffness failed.
    Core(CoreError),
    /// The caller's check of the symbolic factor refused it.
    Refused(E),
}

impl ElasticFlexibility {
    /// The flexibility of `model` (the body alone: its sections and boundary conditions, no
    /// interfaces), assembled at rest. `fits` sees the symbolic factor and the free dofs before
    /// the numeric factorization (a caller's memory check).
    pub fn new<E>(
        mut model: Model,
        fits: impl FnOnce(&FaerCholesky, usize) -> Result<(), E>,
    ) -> Result<Self, FlexibilityError<E>> {
        model.finalize().map_err(FlexibilityError::Core)?;
        model.apply_time(0.0);
        model.assemble(true).map_err(FlexibilityError::Core)?;
        let mut solver = FaerCholesky::analyse(model.pattern()).map_err(FlexibilityError::Core)?;
        fits(&solver, model.free_dofs().len()).map_err(FlexibilityError::Refused)?;
        solver.factorize(model.pattern(), &model.tangent_values).map_err(|e| {
            FlexibilityError::Core(CoreError::Invalid(format!(
                "{e}: is the body held by its boundary conditions without the interfaces?"
            )))
        })?;
        let mut free_index = vec![usize::MAX; model.n_dofs()];
        for (k, &g) in model.free_dofs().iter().enumerate() {
            free_index[g] = k;
        }
        Ok(Self { model, solver, free_index })
    }

    /// For each unit load w_a = sum_a c_a n (nodes and weights c_a in `loads`), by one solve
    /// for all of them: its compliance w_a . K^-1 w_a (the mean normal displacement of the
    /// pattern per unit force) and the cross term w_b . K^-1 w_a with its partner load
    /// pattern in `partners`.
    pub fn compliances(
        &mut self,
        loads: &[(&[usize], &[f64])],
        partners: &[(&[usize], &[f64])],
        normal: [f64; 3],
    ) -> Result<Vec<(f64, f64)>, CoreError> {
        let n = self.model.n_free();
        let mut columns: Vec<f64> = loads.iter().flat_map(|(nodes, w)| self.load(nodes, w, normal)).collect();
        let right = columns.clone();
        self.solver.solve_columns_in_place(&mut columns, loads.len())?;
        let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(a, b)| a * b).sum::<f64>();
        Ok((0..loads.len())
            .map(|i| {
                let x = &columns[i * n..(i + 1) * n];
                let partner = self.load(partners[i].0, partners[i].1, normal);
                (dot(&right[i * n..(i + 1) * n], x), dot(&partner, x))
            })
            .collect())
    }

    /// sum_a c_a n on the free dofs of `nodes`.
    fn load(&self, nodes: &[usize], weights: &[f64], normal: [f64; 3]) -> Vec<f64> {
        let dpn = self.model.dofs_per_node();
        let mut rhs = vec![0.0; self.model.n_free()];
        for (&node, &c) in nodes.iter().zip(weights) {
            for (k, n_k) in normal.iter().take(dpn).enumerate() {
                let f = self.free_index[node * dpn + k];
                if f != usize::MAX {
                    rhs[f] += c * n_k;
                }
            }
        }
        rhs
    }
}

/// What a footprint correction computed, for the log and for checks: the range of the
/// per-point compliances set (the part the mesh misses) and the median of the mesh's own
/// compliance under a footprint.
#[derive(Debug, Clone, PartialEq)]
pub struct CompliancesSet {
    pub interface: String,
    pub min: f64,
    pub median: f64,
    pub max: f64,
    pub mesh_median: f64,
}

/// The body's elastic constants and the footprint's area, for [`set_compliances`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FootprintBody {
    pub young: f64,
    pub poisson: f64,
    /// The footprint's area.
    pub area: f64,
}

/// Computes each point's compliance (module documentation) and sets it in the flat's states
/// (a law of `n_inner_state` states in series with its footprint).
pub fn set_compliances(
    flat: &mut RigidFlat,
    (mesh, surface): (&Mesh, &str),
    discrete: &[DiscretePoint],
    body: FootprintBody,
    n_inner_state: usize,
    flexibility: &mut ElasticFlexibility,
) -> Result<CompliancesSet, CoreError> {
    let FootprintBody { young, poisson, area } = body;
    let radius = (area / std::f64::consts::PI).sqrt();
    let normal = flat.normal();
    let small: Vec<(&[usize], &[f64])> = flat.point_weights().map(|(n, w, _)| (n, w)).collect();
    // a disc the mesh resolves: three face edges (edge ~ 1.52 sqrt(corner area)), >= 3 radii
    let big_radius: Vec<f64> =
        flat.point_weights().map(|(.., face_area)| (3.0 * 1.52 * face_area.sqrt()).max(3.0 * radius)).collect();
    let (big, _) = place_points(mesh, flat.name(), surface, normal, discrete, "the points", |i| {
        std::f64::consts::PI * big_radius[i].powi(2)
    })?;
    let mut compliances = Vec::with_capacity(small.len());
    let mut mesh_compliances = Vec::with_capacity(small.len());
    // the solves in blocks of right-hand sides
    for block in (0..small.len()).collect::<Vec<_>>().chunks(32) {
        let loads: Vec<(&[usize], &[f64])> = block.iter().map(|&i| small[i]).collect();
        let partners: Vec<(&[usize], &[f64])> =
            block.iter().map(|&i| (&big[i].nodes[..], &big[i].weights[..])).collect();
        let results = flexibility.compliances(&loads, &partners, normal)?;
        for (&i, (c_small, cross)) in block.iter().zip(results) {
            let q = (radius / big_radius[i]).powi(2);
            let cross_half_space = 2.0 * (1.0 - poisson * poisson) / (std::f64::consts::PI * young * big_radius[i])
                * (1.0 - q / 8.0 - q * q / 64.0);
            let missing = disc_compliance(young, poisson, radius) - c_small + (cross - cross_half_space);
            compliances.push(missing.max(0.0));
            mesh_compliances.push(c_small);
        }
    }
    let index = compliance_state_index(n_inner_state);
    flat.set_point_states(|i, state| state[index] = compliances[i]);
    let median = |mut v: Vec<f64>| {
        v.sort_by(f64::total_cmp);
        (v[0], v[v.len() / 2], v[v.len() - 1])
    };
    let (min, median_missing, max) = median(compliances);
    Ok(CompliancesSet {
        interface: flat.name().to_string(),
        min,
        median: median_missing,
        max,
        mesh_median: median(mesh_compliances).1,
    })
}
