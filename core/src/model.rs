//! The assembled model: degrees of freedom, prescribed displacements, external loads, element
//! sets (kernel + material + cells), extra contributions (interfaces), and assembly of the
//! residual and tangent into a sparsity pattern built once.
//!
//! Equilibrium solved: r(u) = f_int(u) + f_iface(u) - f_ext(t) = 0 on the free dofs, with the
//! prescribed dofs set to u_p(t) = scale * amplitude(t).

use crate::amplitude::Amplitude;
use crate::element::{ElementBuffers, ElementFailure, ElementKernel, Kinematics};
use crate::error::{CoreError, Result};
use crate::material::Material;
use crate::mesh::Mesh;
use crate::sparse::{NO_SLOT, SparsityPattern};
use crate::tangent_sink::{BlockSlots, ConvexSink, SlotSink, TangentSink};
use crate::vector::norm;
use crate::voigt::Stress;
use rayon::prelude::*;
use std::sync::Arc;

pub use crate::checkpoint::ModelState;

/// Cells that share one kernel and one material.
pub struct ElementSet {
    /// Name (the physical group) for messages and output.
    pub name: String,
    pub kernel: Box<dyn ElementKernel>,
    pub material: Arc<dyn Material>,
    /// The material's stabilized twin ([`Material::stabilized`]), if it has one.
    stabilized: Option<Arc<dyn Material>>,
    /// Whether assembly uses the stabilized twin's tangent.
    use_stabilized: bool,
    /// Flattened connectivity (gmsh local order), `kernel.n_nodes()` per cell.
    pub connectivity: Vec<usize>,
    state_committed: Vec<f64>,
    state_trial: Vec<f64>,
    stress: Vec<Stress>,
    slots: Vec<u32>,
    /// Each cell's reference geometry as the kernel precomputes it
    /// ([`ElementKernel::geometry`], `geometry_len` per cell), made at the first assembly.
    geometry: Vec<f64>,
}

impl ElementSet {
    pub fn new(
        name: impl Into<String>,
        kernel: Box<dyn ElementKernel>,
        material: Arc<dyn Material>,
        connectivity: Vec<usize>,
    ) -> Self {
        let n_cells = connectivity.len() / kernel.n_nodes();
        let n_points = n_cells * kernel.n_points();
        let ns = material.n_state();
        let mut state = vec![0.0; n_points * ns];
        if ns > 0 {
            for s in state.chunks_exact_mut(ns) {
                material.initialize_state(s);
            }
        }
        let stabilized = material.stabilized();
        debug_assert!(stabilized.as_ref().is_none_or(|twin| twin.n_state() == ns));
        Self {
            name: name.into(),
            kernel,
            material,
            stabilized,
            use_stabilized: false,
            connectivity,
            state_trial: state.clone(),
            state_committed: state,
            stress: vec![[0.0; 6]; n_points],
            slots: Vec::new(),
            geometry: Vec::new(),
        }
    }
    pub fn n_cells(&self) -> usize {
        self.connectivity.len() / self.kernel.n_nodes()
    }
    pub fn cell(&self, i: usize) -> &[usize] {
        let n = self.kernel.n_nodes();
        &self.connectivity[i * n..(i + 1) * n]
    }
    /// Stress at the integration points of the last assembly (trial or committed).
    pub fn stresses(&self) -> &[Stress] {
        &self.stress
    }
    /// Committed material state, `n_points * n_state` numbers.
    pub fn committed_state(&self) -> &[f64] {
        &self.state_committed
    }

    /// Replaces the committed (and trial) material state by `saved`, which must have the
    /// length of [`Self::committed_state`]; Err names both lengths.
    fn restore_committed_state(&mut self, saved: &[f64]) -> std::result::Result<(), String> {
        if saved.len() != self.state_committed.len() {
            return Err(format!(
                "element set '{}' has {} material state values, the checkpoint {}",
                self.name,
                self.state_committed.len(),
                saved.len()
            ));
        }
        self.state_committed.copy_from_slice(saved);
        self.state_trial.copy_from_slice(saved);
        Ok(())
    }
}

impl ElementSet {
    /// Fills [`Self::geometry`] once (the reference geometry is fixed under small strain); an
    /// inverted cell fails as its evaluation would, and nothing is kept.
    fn precompute_geometry(&mut self, nodes: &[[f64; 3]]) -> Result<()> {
        let len = self.kernel.geometry_len();
        if len == 0 || self.geometry.len() == self.n_cells() * len {
            return Ok(());
        }
        let mut geometry = vec![0.0; self.n_cells() * len];
        let mut coords = vec![[0.0; 3]; self.kernel.n_nodes()];
        for (cell, out) in geometry.chunks_exact_mut(len).enumerate() {
            self.gather_coordinates(cell, nodes, &mut coords);
            self.kernel.geometry(&coords, out).map_err(|f| element_error(&self.name, self.material.name(), cell, f))?;
        }
        self.geometry = geometry;
        Ok(())
    }

    /// Adds the set's consistent unit-density mass ([`ElementKernel::mass`]) to `values` (on
    /// the pattern, through the slot maps).
    fn add_mass(&self, nodes: &[[f64; 3]], values: &mut [f64]) {
        let (nn, nd) = (self.kernel.n_nodes(), self.kernel.n_dofs());
        let mut coords = vec![[0.0; 3]; nn];
        let mut me = vec![0.0; nd * nd];
        for cell in 0..self.n_cells() {
            self.gather_coordinates(cell, nodes, &mut coords);
            self.kernel.mass(&coords, &mut me);
            self.add_cell_matrix(cell, &me, values);
        }
    }

    /// The coordinates of cell `cell`'s nodes, in its local order, into `coords`.
    fn gather_coordinates(&self, cell: usize, nodes: &[[f64; 3]], coords: &mut [[f64; 3]]) {
        for (a, &node) in self.cell(cell).iter().enumerate() {
            coords[a] = nodes[node];
        }
    }

    /// Adds cell `cell`'s matrix `local` (n_dofs x n_dofs) to `values` on the pattern, through
    /// the cell's slot map (entries of prescribed dofs have no slot).
    fn add_cell_matrix(&self, cell: usize, local: &[f64], values: &mut [f64]) {
        let nd = self.kernel.n_dofs();
        for (&s, m) in self.slots[cell * nd * nd..(cell + 1) * nd * nd].iter().zip(local) {
            if s != NO_SLOT {
                values[s as usize] += m;
            }
        }
    }

    /// Adds the set's initial stiffness K_0 = sum_e integral B^T D_0 B dV to `values` (on the
    /// pattern): each cell's tangent at zero displacement from the material's initial state
    /// (for an elastic-plastic law its elastic stiffness), whatever the set's current state.
    fn add_initial_stiffness(&self, nodes: &[[f64; 3]], values: &mut [f64]) -> Result<()> {
        let (nn, nd, nq, ns) =
            (self.kernel.n_nodes(), self.kernel.n_dofs(), self.kernel.n_points(), self.material.n_state());
        let mut coords = vec![[0.0; 3]; nn];
        let zero = vec![0.0; nd];
        let mut initial = vec![0.0; nq * ns];
        if ns > 0 {
            initial.chunks_mut(ns).for_each(|point| self.material.initialize_state(point));
        }
        let mut trial = initial.clone();
        let (mut fe, mut ke, mut stress) = (vec![0.0; nd], vec![0.0; nd * nd], vec![[0.0; 6]; nq]);
        for cell in 0..self.n_cells() {
            self.gather_coordinates(cell, nodes, &mut coords);
            let buffers = ElementBuffers { force: &mut fe, stiffness: Some(&mut ke), stress: &mut stress };
            self.kernel
                .evaluate(&coords, &zero, self.material.as_ref(), &initial, &mut trial, buffers)
                .map_err(|f| element_error(&self.name, self.material.name(), cell, f))?;
            self.add_cell_matrix(cell, &ke, values);
        }
        Ok(())
    }

    /// Adds the set's internal force to `force` (all dofs) and its tangent to `values` (on the
    /// pattern, through the slot maps); cells are split over the rayon threads, each with its
    /// own accumulators, when the set is large.
    fn assemble(
        &mut self,
        nodes: &[[f64; 3]],
        displacement: &[f64],
        dpn: usize,
        nnz: usize,
        force_total: &mut [f64],
        mut values_total: Option<&mut [f64]>,
    ) -> Result<()> {
        self.precompute_geometry(nodes)?;
        let with_tangent = values_total.is_some();
        let n_dofs = displacement.len();
        let threads = rayon::current_num_threads().max(1);
        let n_cells = self.n_cells();
        let nn = self.kernel.n_nodes();
        let nd = self.kernel.n_dofs();
        let nq = self.kernel.n_points();
        let ns = self.material.n_state();
        let n_chunks = if n_cells >= 512 { threads } else { 1 };
        let jobs = cell_ranges(n_cells, n_chunks, nq, ns, &mut self.state_trial, &mut self.stress);
        let kernel = self.kernel.as_ref();
        let material = match (&self.stabilized, self.use_stabilized) {
            (Some(twin), true) => twin.as_ref(),
            _ => self.material.as_ref(),
        };
        let connectivity = &self.connectivity;
        let (geometry, geometry_len) = (&self.geometry, self.kernel.geometry_len());
        let committed = &self.state_committed;
        let slots = &self.slots;
        let set_name = &self.name;
        let run = |(first, last, state_trial, stress): (usize, usize, &mut [f64], &mut [Stress]),
                   force: &mut [f64],
                   values: &mut [f64]|
         -> Result<()> {
            let mut coords = vec![[0.0; 3]; nn];
            let mut u = vec![0.0; nd];
            let mut fe = vec![0.0; nd];
            let mut ke = vec![0.0; nd * nd];
            for cell in first..last {
                let conn = &connectivity[cell * nn..(cell + 1) * nn];
                for (a, &node) in conn.iter().enumerate() {
                    coords[a] = nodes[node];
                    for c in 0..dpn {
                        u[a * dpn + c] = displacement[node * dpn + c];
                    }
                }
                let local = cell - first;
                let buffers = ElementBuffers {
                    force: &mut fe,
                    stiffness: if with_tangent { Some(&mut ke) } else { None },
                    stress: &mut stress[local * nq..(local + 1) * nq],
                };
                kernel
                    .evaluate_on_geometry(
                        &geometry[cell * geometry_len..(cell + 1) * geometry_len],
                        &coords,
                        &u,
                        material,
                        &committed[cell * nq * ns..(cell + 1) * nq * ns],
                        &mut state_trial[local * nq * ns..(local + 1) * nq * ns],
                        buffers,
                    )
                    .map_err(|f| element_error(set_name, material.name(), cell, f))?;
                for (a, &node) in conn.iter().enumerate() {
                    for c in 0..dpn {
                        force[node * dpn + c] += fe[a * dpn + c];
                    }
                }
                if with_tangent {
                    let cell_slots = &slots[cell * nd * nd..(cell + 1) * nd * nd];
                    for (k, &s) in cell_slots.iter().enumerate() {
                        if s != NO_SLOT {
                            values[s as usize] += ke[k];
                        }
                    }
                }
            }
            Ok(())
        };
        // the first chunk accumulates straight into the totals; the others into their own
        // buffers, added afterwards (one buffer fewer than chunks: less peak memory)
        let mut jobs = jobs.into_iter();
        let first_job = jobs.next().expect("at least one chunk");
        let rest: Vec<_> = jobs.collect();
        let (first, partials) = rayon::join(
            || run(first_job, &mut *force_total, values_total.as_deref_mut().unwrap_or(&mut [])),
            || -> Vec<Result<(Vec<f64>, Vec<f64>)>> {
                rest.into_par_iter()
                    .map(|job| {
                        let mut force = vec![0.0; n_dofs];
                        let mut values = if with_tangent { vec![0.0; nnz] } else { Vec::new() };
                        run(job, &mut force, &mut values).map(|_| (force, values))
                    })
                    .collect()
            },
        );
        first?;
        for part in partials {
            let (force, values) = part?;
            for (a, b) in force_total.iter_mut().zip(&force) {
                *a += b;
            }
            if let Some(total) = values_total.as_deref_mut() {
                total.par_iter_mut().zip(values.par_iter()).for_each(|(a, b)| *a += b);
            }
        }
        Ok(())
    }
}

/// Splits `n_cells` cells into `n_chunks` ranges (first, last) with their parts of the trial
/// states (`nq * ns` per cell; empty for ns == 0) and of the stresses (`nq` per cell).
fn cell_ranges<'a>(
    n_cells: usize,
    n_chunks: usize,
    nq: usize,
    ns: usize,
    mut state_rest: &'a mut [f64],
    mut stress_rest: &'a mut [Stress],
) -> Vec<(usize, usize, &'a mut [f64], &'a mut [Stress])> {
    let per_chunk = n_cells.div_ceil(n_chunks).max(1);
    let mut jobs = Vec::with_capacity(n_chunks);
    let mut first = 0;
    while first < n_cells {
        let last = (first + per_chunk).min(n_cells);
        let (s, r) = std::mem::take(&mut state_rest).split_at_mut((last - first) * nq * ns);
        state_rest = r;
        let (t, r2) = std::mem::take(&mut stress_rest).split_at_mut((last - first) * nq);
        stress_rest = r2;
        jobs.push((first, last, s, t));
        first = last;
    }
    jobs
}

/// Something besides the solid elements that adds forces and stiffness: interfaces, contact.
pub trait Contribution: Send {
    fn name(&self) -> &str;
    /// The node lists (blocks) whose dofs this contribution couples: they are added to the
    /// sparsity pattern, and every tangent entry is given within one of them (their slots are
    /// computed once, at [`Model::finalize`]).
    fn coupled_nodes(&self) -> Vec<Vec<usize>> {
        Vec::new()
    }
    /// Adds this contribution's force to `force` (full dof vector) and, if given, its tangent
    /// entries to `tangent`, each as (block of `coupled_nodes`, local index, global dof).
    fn assemble(
        &mut self,
        time: f64,
        displacement: &[f64],
        force: &mut [f64],
        tangent: Option<&mut dyn TangentSink>,
    ) -> Result<()>;
    fn commit(&mut self) {}
    fn rollback(&mut self) {}
    /// Whether this contribution's response depends on the path to its state (a law with
    /// state: damage, hysteresis, a plastic footprint), so that how a jump is crossed matters.
    fn path_dependent(&self) -> bool {
        false
    }
    /// The energy dissipated by damage from the committed state to the trial state of the
    /// last assembly, for laws that unload secantly to their origin (damage, penalty contact):
    /// per point the stored energy is -v g / 2 (v the law's value, positive pushing apart, g
    /// the gap), and the trapezoidal work minus its change is
    ///   dD = 1/2 sum_p w_p (v_p g_c,p - v_c,p g_p)   (c: committed),
    /// exact on a piecewise-linear softening envelope, zero for a secant or reversible linear
    /// response. Adds d(dD)/du = sum_p w_p (k_p g_c,p - v_c,p)/2 dg_p/du (k = dv/dg) to
    /// `gradient` (all dofs) and returns (dD, d(dD)/dt at fixed u). None: the contribution
    /// has no damage to report.
    fn damage_dissipation(&self, _gradient: &mut [f64]) -> Option<(f64, f64)> {
        None
    }
    /// Plastic work dissipated at the committed state by the continuum below the mesh scale
    /// that this contribution models (e.g. the local flow under asperity footprints), counted
    /// with the elements' plastic dissipation.
    fn plastic_dissipation(&self) -> f64 {
        0.0
    }
    /// Amplitudes this contribution follows (their breakpoints are landed on exactly).
    fn amplitudes(&self) -> Vec<Arc<Amplitude>> {
        Vec::new()
    }
    /// Interface quantities at the committed state (for `history.csv`, the summary and the
    /// events); None for contributions that are not interfaces.
    fn observables(&self) -> Option<crate::observables::InterfaceObservables> {
        None
    }
    /// Warnings about how the contribution is set up (e.g. a mesh too coarse for it); the run
    /// reports them on stderr and in summary.json.
    fn warnings(&self) -> Vec<String> {
        Vec::new()
    }
    /// Points with fields at the committed state, written as VTK vertices (e.g. interface
    /// integration points with gap and traction).
    fn point_output(&self) -> Option<(Vec<[f64; 3]>, Vec<crate::output::vtk::Field>)> {
        None
    }
    /// Everything committed that the contribution's next assembly, observables and point
    /// output depend on, as numbers, for a checkpoint (empty for one without state). Required,
    /// so that no contribution with state is checkpointed without it.
    fn saved_state(&self) -> Vec<f64>;
    /// Makes `saved` (from [`Self::saved_state`] of a contribution built the same way) the
    /// committed and trial state; Err says why it does not fit
    /// ([`crate::checkpoint::SavedNumbers`] reads it back).
    fn restore_state(&mut self, saved: &[f64]) -> std::result::Result<(), String>;
}

/// A prescribed displacement component: u[dof] = scale * amplitude(t).
#[derive(Debug, Clone)]
pub struct Prescribed {
    pub dof: usize,
    pub scale: f64,
    pub amplitude: Arc<Amplitude>,
    /// The boundary condition it came from, for messages.
    pub source: String,
}

/// An external nodal load vector scaled by an amplitude: f_ext(t) += amplitude(t) * vector.
#[derive(Debug, Clone)]
pub struct ExternalLoad {
    pub name: String,
    pub vector: Vec<f64>,
    pub amplitude: Arc<Amplitude>,
}

/// Timing of one assembly, for benchmarks.
#[derive(Debug, Clone, Copy, Default)]
pub struct AssemblyStats {
    pub seconds: f64,
}

/// The model: mesh, kinematics, element sets, boundary conditions and the assembled system.
pub struct Model {
    pub mesh: Arc<Mesh>,
    pub kinematics: Kinematics,
    pub sets: Vec<ElementSet>,
    pub contributions: Vec<Box<dyn Contribution>>,
    pub loads: Vec<ExternalLoad>,
    prescribed: Vec<Prescribed>,
    /// Global dof (node * dofs_per_node + component) -> free index, or usize::MAX.
    free_index: Vec<usize>,
    free_dofs: Vec<usize>,
    pattern: Option<SparsityPattern>,
    /// The slots of each contribution's blocks (its `coupled_nodes`), in contribution order.
    contribution_slots: Vec<BlockSlots>,
    /// Current displacement (all dofs) and the last committed one.
    pub displacement: Vec<f64>,
    displacement_committed: Vec<f64>,
    /// Internal force of the last assembly (all dofs), elements plus contributions.
    pub internal_force: Vec<f64>,
    /// External force at the last assembled time (all dofs).
    pub external_force: Vec<f64>,
    /// Tangent values on the pattern from the last assembly with tangent.
    pub tangent_values: Vec<f64>,
    /// Residual on the free dofs from the last assembly.
    pub residual: Vec<f64>,
    pub time: f64,
    pub time_committed: f64,
}

impl Model {
    pub fn new(mesh: Arc<Mesh>, kinematics: Kinematics) -> Self {
        let n = mesh.nodes.len() * kinematics.dofs_per_node();
        Self {
            mesh,
            kinematics,
            sets: Vec::new(),
            contributions: Vec::new(),
            loads: Vec::new(),
            prescribed: Vec::new(),
            free_index: Vec::new(),
            free_dofs: Vec::new(),
            pattern: None,
            contribution_slots: Vec::new(),
            displacement: vec![0.0; n],
            displacement_committed: vec![0.0; n],
            internal_force: vec![0.0; n],
            external_force: vec![0.0; n],
            tangent_values: Vec::new(),
            residual: Vec::new(),
            time: 0.0,
            time_committed: 0.0,
        }
    }

    pub fn dofs_per_node(&self) -> usize {
        self.kinematics.dofs_per_node()
    }
    pub fn n_dofs(&self) -> usize {
        self.displacement.len()
    }
    pub fn n_free(&self) -> usize {
        self.free_dofs.len()
    }
    pub fn pattern(&self) -> &SparsityPattern {
        self.pattern.as_ref().expect("Model::finalize must be called before assembly")
    }
    pub fn free_dofs(&self) -> &[usize] {
        &self.free_dofs
    }
    pub fn prescribed(&self) -> &[Prescribed] {
        &self.prescribed
    }

    /// Prescribes a dof. A dof prescribed twice must get the same history.
    pub fn prescribe(&mut self, p: Prescribed) -> Result<()> {
        if let Some(old) = self.prescribed.iter().find(|q| q.dof == p.dof) {
            let same = (old.scale == p.scale && Arc::ptr_eq(&old.amplitude, &p.amplitude))
                || (old.scale == 0.0 && p.scale == 0.0);
            if !same {
                let dpn = self.dofs_per_node();
                return Err(CoreError::Invalid(format!(
                    "node {} component {} is prescribed by both '{}' and '{}' with different values",
                    p.dof / dpn + 1,
                    p.dof % dpn,
                    old.source,
                    p.source
                )));
            }
            return Ok(());
        }
        self.prescribed.push(p);
        Ok(())
    }

    /// Numbers the free dofs, fixes nodes that no element uses, builds the sparsity pattern and
    /// the element slot maps. Call once after adding sets, contributions and constraints.
    pub fn finalize(&mut self) -> Result<()> {
        let dpn = self.dofs_per_node();
        let n_nodes = self.mesh.nodes.len();
        if self.sets.is_empty() {
            return Err(CoreError::Invalid("the model has no elements to solve for".into()));
        }
        let mut used = vec![false; n_nodes];
        for set in &self.sets {
            for &n in &set.connectivity {
                used[n] = true;
            }
        }
        let mut constrained = vec![false; n_nodes * dpn];
        for p in &self.prescribed {
            constrained[p.dof] = true;
        }
        self.free_index = vec![usize::MAX; n_nodes * dpn];
        self.free_dofs.clear();
        for node in 0..n_nodes {
            for c in 0..dpn {
                let g = node * dpn + c;
                if used[node] && !constrained[g] {
                    self.free_index[g] = self.free_dofs.len();
                    self.free_dofs.push(g);
                }
            }
        }
        if self.free_dofs.is_empty() {
            return Err(CoreError::Invalid("every degree of freedom is prescribed: nothing to solve".into()));
        }
        let blocks: Vec<Vec<Vec<usize>>> = self.contributions.iter().map(|c| c.coupled_nodes()).collect();
        let free_index = &self.free_index;
        let dof_of = |node: usize, c: usize| {
            let f = free_index[node * dpn + c];
            (f != usize::MAX).then_some(f)
        };
        let cells = self
            .sets
            .iter()
            .flat_map(|s| s.connectivity.chunks_exact(s.kernel.n_nodes()))
            .chain(blocks.iter().flatten().map(|v| v.as_slice()));
        let pattern = SparsityPattern::from_cells(self.free_dofs.len(), n_nodes, dpn, cells, dof_of);
        self.contribution_slots = blocks.iter().map(|b| BlockSlots::new(b, dpn, &pattern, dof_of)).collect();
        let mut dofs = Vec::new();
        let mut slots = Vec::new();
        for set in &mut self.sets {
            let nn = set.kernel.n_nodes();
            let nd = set.kernel.n_dofs();
            set.slots = Vec::with_capacity(set.n_cells() * nd * nd);
            for cell in set.connectivity.chunks_exact(nn) {
                dofs.clear();
                for &node in cell {
                    for c in 0..dpn {
                        dofs.push(dof_of(node, c));
                    }
                }
                pattern.element_slots(&dofs, &mut slots);
                set.slots.extend_from_slice(&slots);
            }
        }
        self.tangent_values = vec![0.0; pattern.nnz()];
        self.residual = vec![0.0; self.free_dofs.len()];
        self.pattern = Some(pattern);
        Ok(())
    }

    /// Sets the prescribed dofs and the external force for pseudo-time `t`.
    pub fn apply_time(&mut self, t: f64) {
        self.time = t;
        for p in &self.prescribed {
            self.displacement[p.dof] = p.scale * p.amplitude.value(t);
        }
        self.external_force.fill(0.0);
        for load in &self.loads {
            let a = load.amplitude.value(t);
            for (f, v) in self.external_force.iter_mut().zip(&load.vector) {
                *f += a * v;
            }
        }
    }

    /// Adds `du` (free dofs) times `alpha` to the displacement.
    pub fn update_free(&mut self, du: &[f64], alpha: f64) {
        for (k, &g) in self.free_dofs.iter().enumerate() {
            self.displacement[g] += alpha * du[k];
        }
    }

    /// Assembles internal force, residual and (optionally) the tangent at the current
    /// displacement; material states are written to the trial copies.
    pub fn assemble(&mut self, with_tangent: bool) -> Result<AssemblyStats> {
        self.assemble_with(with_tangent, false)
    }

    /// [`Model::assemble`] with the tangent, whose contribution blocks (interface points) with a
    /// negative diagonal are left out ([`ConvexSink`]): the solid's tangent and the interfaces'
    /// positive curvature.
    pub fn assemble_convex(&mut self) -> Result<AssemblyStats> {
        self.assemble_with(true, true)
    }

    fn assemble_with(&mut self, with_tangent: bool, convex: bool) -> Result<AssemblyStats> {
        let start = std::time::Instant::now();
        let pattern = self.pattern.as_ref().expect("Model::finalize must be called before assembly");
        self.internal_force.fill(0.0);
        if with_tangent {
            self.tangent_values.fill(0.0);
        }
        let nodes = &self.mesh.nodes;
        for set in &mut self.sets {
            set.assemble(
                nodes,
                &self.displacement,
                self.kinematics.dofs_per_node(),
                pattern.nnz(),
                &mut self.internal_force,
                with_tangent.then_some(&mut self.tangent_values[..]),
            )?;
        }
        // Interfaces and other contributions, through their precomputed block slots.
        for (contribution, blocks) in self.contributions.iter_mut().zip(&self.contribution_slots) {
            let mut sink = SlotSink { values: &mut self.tangent_values, blocks, pattern, free_index: &self.free_index };
            if convex {
                let mut convex_sink = ConvexSink::new(&mut sink);
                contribution.assemble(
                    self.time,
                    &self.displacement,
                    &mut self.internal_force,
                    Some(&mut convex_sink),
                )?;
                convex_sink.finish();
            } else {
                contribution.assemble(
                    self.time,
                    &self.displacement,
                    &mut self.internal_force,
                    if with_tangent { Some(&mut sink) } else { None },
                )?;
            }
        }
        for (k, &g) in self.free_dofs.iter().enumerate() {
            self.residual[k] = self.internal_force[g] - self.external_force[g];
        }
        if self.residual.iter().any(|r| !r.is_finite()) {
            return Err(CoreError::NonFinite("residual force vector".into()));
        }
        Ok(AssemblyStats { seconds: start.elapsed().as_secs_f64() })
    }

    /// Whether some material has a stabilized tangent ([`Material::stabilized`]) to switch to.
    pub fn can_stabilize_tangent(&self) -> bool {
        self.sets.iter().any(|s| s.stabilized.is_some())
    }

    /// Whether a point of a material with a stabilized tangent flows in the trial state
    /// ([`Material::flowing`]): where the two tangents differ.
    pub fn flowing_where_stabilizable(&self) -> bool {
        self.sets.iter().filter(|s| s.stabilized.is_some()).any(|s| {
            let ns = s.material.n_state();
            ns > 0 && s.state_trial.chunks_exact(ns).any(|state| s.material.flowing(state))
        })
    }

    /// Whether assembly uses the stabilized tangents.
    pub fn tangent_stabilized(&self) -> bool {
        self.sets.iter().any(|s| s.use_stabilized && s.stabilized.is_some())
    }

    /// Switches assembly to the materials' stabilized tangents (where they have one) or back
    /// to the consistent ones. Residuals and states do not change, only the tangent.
    pub fn stabilize_tangent(&mut self, on: bool) {
        for set in &mut self.sets {
            set.use_stabilized = on;
        }
    }

    /// Accepts the current state as converged.
    pub fn commit(&mut self) {
        for set in &mut self.sets {
            set.state_committed.copy_from_slice(&set.state_trial);
        }
        for c in &mut self.contributions {
            c.commit();
        }
        self.displacement_committed.copy_from_slice(&self.displacement);
        self.time_committed = self.time;
    }

    /// Returns to the last committed state (a cut step).
    pub fn rollback(&mut self) {
        for set in &mut self.sets {
            set.state_trial.copy_from_slice(&set.state_committed);
        }
        for c in &mut self.contributions {
            c.rollback();
        }
        self.displacement.copy_from_slice(&self.displacement_committed);
        self.time = self.time_committed;
    }

    /// The consistent mass of unit density of the solid elements on the pattern (free dofs):
    /// M = sum_e integral N^T N dV, the L2 metric of displacement fields.
    pub fn mass_matrix(&self) -> Vec<f64> {
        let pattern = self.pattern.as_ref().expect("Model::finalize must be called before assembly");
        let mut values = vec![0.0; pattern.nnz()];
        for set in &self.sets {
            set.add_mass(&self.mesh.nodes, &mut values);
        }
        values
    }

    /// The initial elastic stiffness of the solid elements on the pattern (free dofs), each
    /// set's tangent at zero displacement from its material's initial state, interfaces and
    /// other contributions left out: the drag of a stiffness-proportional damped flow
    /// ([`crate::nonlinear::damped_flow::FlowDamping::Stiffness`]).
    pub fn initial_stiffness_matrix(&self) -> Result<Vec<f64>> {
        let pattern = self.pattern.as_ref().expect("Model::finalize must be called before assembly");
        let mut values = vec![0.0; pattern.nnz()];
        for set in &self.sets {
            set.add_initial_stiffness(&self.mesh.nodes, &mut values)?;
        }
        Ok(values)
    }

    /// The committed state, everything a run needs to go on from it: time, displacement, the
    /// element sets' material states and the contributions' states
    /// ([`Contribution::saved_state`]).
    pub fn saved_state(&self) -> ModelState {
        ModelState {
            time: self.time_committed,
            displacement: self.displacement_committed.clone(),
            sets: self.sets.iter().map(|s| s.state_committed.clone()).collect(),
            contributions: self.contributions.iter().map(|c| c.saved_state()).collect(),
        }
    }

    /// Makes `saved` (of a model built the same way) the committed and trial state, then
    /// assembles the residual there so that everything derived from the last assembly (internal
    /// force, reactions, stresses) is that of the committed state. Err says which part does not
    /// fit this model.
    pub fn restore_state(&mut self, saved: &ModelState) -> std::result::Result<(), String> {
        if saved.displacement.len() != self.displacement.len() {
            return Err(format!(
                "the model has {} displacement values, the checkpoint {}",
                self.displacement.len(),
                saved.displacement.len()
            ));
        }
        if saved.sets.len() != self.sets.len() || saved.contributions.len() != self.contributions.len() {
            return Err(format!(
                "the model has {} element sets and {} interfaces, the checkpoint {} and {}",
                self.sets.len(),
                self.contributions.len(),
                saved.sets.len(),
                saved.contributions.len()
            ));
        }
        for (set, state) in self.sets.iter_mut().zip(&saved.sets) {
            set.restore_committed_state(state)?;
        }
        for (c, state) in self.contributions.iter_mut().zip(&saved.contributions) {
            c.restore_state(state).map_err(|e| format!("interface '{}': {e}", c.name()))?;
        }
        self.displacement_committed.clone_from(&saved.displacement);
        self.displacement.clone_from(&saved.displacement);
        self.apply_time(saved.time);
        self.time_committed = saved.time;
        self.assemble(false).map_err(|e| format!("the restored state does not assemble: {e}"))?;
        self.rollback();
        Ok(())
    }

    /// Displacement at the last commit.
    pub fn committed_displacement(&self) -> &[f64] {
        &self.displacement_committed
    }

    /// Reaction (internal minus external force) summed over `nodes`, per component.
    pub fn reaction(&self, nodes: &[usize]) -> Vec<f64> {
        let dpn = self.dofs_per_node();
        let mut r = vec![0.0; dpn];
        for &n in nodes {
            for c in 0..dpn {
                r[c] += self.internal_force[n * dpn + c] - self.external_force[n * dpn + c];
            }
        }
        r
    }

    /// The largest value of the material output `name` (e.g. "equivalent_plastic_strain") over
    /// the integration points at the committed state; None if no material gives it.
    pub fn max_material_output(&self, name: &str) -> Option<f64> {
        let mut largest: Option<f64> = None;
        for set in &self.sets {
            let names = set.material.output_names();
            let Some(k) = names.iter().position(|n| *n == name) else { continue };
            let ns = set.material.n_state();
            let mut out = vec![0.0; names.len()];
            for state in set.state_committed.chunks_exact(ns.max(1)).take(set.n_cells() * set.kernel.n_points()) {
                set.material.outputs(state, &mut out);
                largest = Some(largest.map_or(out[k], |m| m.max(out[k])));
            }
        }
        largest
    }

    /// The damage dissipation of the contributions from the committed state to the trial state
    /// of the last assembly (see [`Contribution::damage_dissipation`]), with its gradient on
    /// the free dofs written to `gradient` and its rate in pseudo-time (the contributions' own
    /// plus that of the prescribed displacements they touch). None when no contribution reports
    /// damage.
    pub fn damage_dissipation(&self, gradient: &mut [f64]) -> Option<(f64, f64)> {
        let mut full = vec![0.0; self.n_dofs()];
        let mut total: Option<(f64, f64)> = None;
        for c in &self.contributions {
            if let Some((energy, rate)) = c.damage_dissipation(&mut full) {
                let (e, r) = total.unwrap_or((0.0, 0.0));
                total = Some((e + energy, r + rate));
            }
        }
        let (energy, mut rate) = total?;
        // prescribed dofs move with t on the segment between the committed and trial times
        let middle = 0.5 * (self.time + self.time_committed);
        for p in &self.prescribed {
            rate += full[p.dof] * p.scale * p.amplitude.slope(middle);
        }
        for (g, &dof) in gradient.iter_mut().zip(&self.free_dofs) {
            *g = full[dof];
        }
        Some((energy, rate))
    }

    /// Whether any material or contribution keeps state that depends on the path (plasticity,
    /// damage, hysteresis): then the state a jump lands on depends on how it is crossed.
    pub fn path_dependent(&self) -> bool {
        self.sets.iter().any(|s| s.material.n_state() > 0) || self.contributions.iter().any(|c| c.path_dependent())
    }

    /// The part of [`Model::dissipation`] that the contributions model below the mesh scale
    /// (the footprint sliders under asperities), without the elements' plastic dissipation.
    pub fn subscale_dissipation(&self) -> f64 {
        self.contributions.iter().map(|c| c.plastic_dissipation()).sum()
    }

    /// Total plastic (or other material) dissipation at the committed state:
    /// sum over points of D(state) * point volume, plus what contributions dissipate
    /// plastically below the mesh scale (footprint corrections).
    pub fn dissipation(&self) -> f64 {
        let mut total = self.subscale_dissipation();
        let mut vols = Vec::new();
        for set in &self.sets {
            let nq = set.kernel.n_points();
            let ns = set.material.n_state();
            if ns == 0 {
                continue;
            }
            vols.resize(nq, 0.0);
            let mut coords = vec![[0.0; 3]; set.kernel.n_nodes()];
            for cell in 0..set.n_cells() {
                for (a, &n) in set.cell(cell).iter().enumerate() {
                    coords[a] = self.mesh.nodes[n];
                }
                set.kernel.point_volumes(&coords, &mut vols);
                for q in 0..nq {
                    let s = &set.state_committed[(cell * nq + q) * ns..(cell * nq + q + 1) * ns];
                    total += set.material.dissipation_density(s) * vols[q];
                }
            }
        }
        total
    }
}

fn element_error(set: &str, material: &str, cell: usize, failure: ElementFailure) -> CoreError {
    match failure {
        ElementFailure::Material { point, error } => CoreError::MaterialFailure {
            material: material.to_string(),
            element: cell,
            point,
            message: format!("{} (element set '{set}')", error.0),
        },
        ElementFailure::BadJacobian { point, det } => CoreError::Invalid(format!(
            "element {cell} of set '{set}' is inverted or degenerate: Jacobian determinant {det:.3e} at point {point}"
        )),
    }
}

impl crate::problem::NonlinearProblem for Model {
    fn n_free(&self) -> usize {
        self.free_dofs.len()
    }
    fn pattern(&self) -> &SparsityPattern {
        Model::pattern(self)
    }
    fn set_time(&mut self, t: f64) {
        self.apply_time(t);
    }
    fn time(&self) -> f64 {
        self.time
    }
    fn assemble(&mut self, with_tangent: bool) -> Result<()> {
        Model::assemble(self, with_tangent).map(|_| ())
    }
    fn assemble_convex(&mut self) -> Result<()> {
        Model::assemble_convex(self).map(|_| ())
    }
    fn residual(&self) -> &[f64] {
        &self.residual
    }
    fn tangent(&self) -> &[f64] {
        &self.tangent_values
    }
    fn force_norm(&self) -> f64 {
        norm(&self.internal_force).max(norm(&self.external_force))
    }
    fn solution(&self) -> &[f64] {
        &self.displacement
    }
    fn add_to_free(&mut self, du: &[f64], alpha: f64) {
        self.update_free(du, alpha);
    }
    fn free_values(&self) -> Vec<f64> {
        self.free_dofs.iter().map(|&g| self.displacement[g]).collect()
    }
    fn set_free_values(&mut self, values: &[f64]) {
        for (k, &g) in self.free_dofs.iter().enumerate() {
            self.displacement[g] = values[k];
        }
    }
    fn increment_since_commit(&self) -> Vec<f64> {
        self.free_dofs.iter().map(|&g| self.displacement[g] - self.displacement_committed[g]).collect()
    }
    fn commit(&mut self) {
        Model::commit(self);
    }
    fn rollback(&mut self) {
        Model::rollback(self);
    }
    fn damage_dissipation(&self, gradient: &mut [f64]) -> Option<(f64, f64)> {
        Model::damage_dissipation(self, gradient)
    }
    fn mass(&self) -> Option<Vec<f64>> {
        Some(self.mass_matrix())
    }
}
