//! A rigid flat plane against a body: over a surface (traction laws integrated with surface
//! quadrature) or at discrete points on the surface (force-per-point laws, e.g. asperities).
//!
//! The plane has unit normal n pointing from the flat toward the body and sits at
//! s(t) = s0 + approach(t) along n. A point with reference position x on the body and offset h
//! toward the flat (an asperity's height; 0 for surface points) has the gap
//! g = x . n - h + u(x) . n - s(t), with u interpolated from its face's nodes (for a discrete
//! point with a footprint: u averaged over the disc of its footprint, N_a below then being the
//! footprint's node weights c_a, see [`crate::footprint`]). s0 is a reference
//! level minus `initial_gap`: over a surface, the lowest point of the surface (approach 0 is
//! first touch); at discrete points, the lowest point of the surface minus the mean height
//! (approach 0: the flat at asperity height above the undeformed pole, as in the reference
//! paper; with scattered heights or no asperity at the pole, first touch comes later or earlier). The law's value (positive pushes apart) acts on the body along +n with
//! weight w (the quadrature area for traction laws, 1 for force laws):
//! f_a = N_a value w n, as internal force -f_a, tangent K_ab = -N_a N_b (d value/d g) w n x n.
//! Reported: `approach`, `force` (total normal force of the flat on the body, positive
//! compressive, law force only), `contact_area`, `n_contact`, `viscous_dissipation`.
//!
//! Optional viscous regularisation (`viscosity` zeta > 0, a pseudo-time) for crossing adhesive
//! instabilities (jump-in, jump-out): each point adds -zeta |k_c| (g - g_c) / dt to its value
//! (resisting the change of gap), with tangent -zeta |k_c| / dt, where g_c and k_c are the gap and the law's tangent at the last
//! converged increment and dt the pseudo-time increment. It acts only where the law is active
//! (k_c != 0); away from instabilities it is a fraction zeta / dt of the law's own incremental
//! response, and when an instability cuts the increment it stiffens, so the path stays
//! continuous in pseudo-time. Its dissipated energy, sum zeta |k_c| (g - g_c)^2 / dt w, is
//! accumulated and reported so it can be kept small.

use crate::contact_resistance::{ContactSpot, ResistanceModel};
use crate::damage_dissipation::{PointState, damages_secantly, point_dissipation};
use crate::point_law::{evaluate_point, initial_states};
use crate::point_placement::{DiscretePoint, place_points};
use std::sync::Arc;
use stiction_core::CoreError;
use stiction_core::amplitude::Amplitude;
use stiction_core::checkpoint::SavedNumbers;
use stiction_core::element::Kinematics;
use stiction_core::interface_law::{InterfaceLaw, LawKind};
use stiction_core::mesh::Mesh;
use stiction_core::model::Contribution;
use stiction_core::observables::InterfaceObservables;
use stiction_core::output::vtk::Field;
use stiction_core::tangent_sink::TangentSink;
use stiction_elements::FaceIntegrator;

/// Where the flat is and how it moves.
pub struct RigidFlatSpec {
    pub name: String,
    /// Surface group of the body (dimension model_dim - 1).
    pub surface: String,
    /// Unit normal from the flat toward the body (axisymmetric: x = r, y = z).
    pub normal: [f64; 3],
    /// approach(t) = scale * amplitude(t).
    pub approach_scale: f64,
    pub approach_amplitude: Arc<Amplitude>,
    pub initial_gap: f64,
    /// Extra Gauss points per face direction (surface interfaces).
    pub extra_order: usize,
    /// Viscous regularisation zeta (0: none), a pseudo-time: see the module documentation.
    pub viscosity: f64,
    /// Electrical contact resistance, computed at every commit when given.
    pub resistance: Option<ResistanceModel>,
}

#[derive(Debug, Clone)]
struct InterfacePoint {
    nodes: Vec<usize>,
    shape: Vec<f64>,
    /// Area (traction laws) or 1 (force laws).
    weight: f64,
    /// x . n - h
    level: f64,
    position: [f64; 3],
    /// Mean corner area of the faces under a discrete point (0 for surface quadrature points).
    face_area: f64,
}

pub struct RigidFlat {
    name: String,
    law: Arc<dyn InterfaceLaw>,
    dpn: usize,
    normal: [f64; 3],
    base_level: f64,
    approach_scale: f64,
    approach_amplitude: Arc<Amplitude>,
    points: Vec<InterfacePoint>,
    state_committed: Vec<f64>,
    state_trial: Vec<f64>,
    /// Per point (trial): gap, value, area, in contact.
    gap: Vec<f64>,
    value: Vec<f64>,
    area: Vec<f64>,
    contact: Vec<bool>,
    committed_summary: [f64; 4],
    trial_summary: [f64; 4],
    committed_fields: Vec<Vec<f64>>,
    viscosity: f64,
    gap_committed: Vec<f64>,
    slope_committed: Vec<f64>,
    slope: Vec<f64>,
    time_committed: f64,
    viscous_committed: f64,
    viscous_trial: f64,
    trial_time: f64,
    resistance: Option<ResistanceModel>,
    resistance_committed: f64,
    footprint: Option<FootprintResolution>,
    /// The law damages with secant unloading ([`crate::damage_dissipation::damages_secantly`]).
    damages: bool,
    /// The state index of the footprints' slider work, when the law is corrected for its
    /// footprint ([`crate::local_footprint`]).
    slider_work_state: Option<usize>,
}

/// How finely the mesh resolves the points' footprints.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FootprintResolution {
    pub footprint_area: f64,
    /// Mean area of the surface faces the footprints touch.
    pub mean_face_area: f64,
}

fn unit_normal(spec: &RigidFlatSpec, kinematics: Kinematics) -> Result<[f64; 3], CoreError> {
    let len = spec.normal.iter().map(|x| x * x).sum::<f64>().sqrt();
    if !(len > 0.0) {
        return Err(CoreError::Invalid(format!("interface '{}': the normal must be non-zero", spec.name)));
    }
    let normal = spec.normal.map(|x| x / len);
    if kinematics == Kinematics::Axisymmetric && (normal[0].abs() > 1e-12 || normal[2].abs() > 1e-12) {
        return Err(CoreError::Invalid(format!(
            "interface '{}': in an axisymmetric model the flat must be normal to the axis (normal [0, 1] or [0, -1])",
            spec.name
        )));
    }
    Ok(normal)
}

impl RigidFlat {
    /// A flat against a surface group, with a traction law integrated over the faces.
    pub fn over_surface(
        mesh: &Mesh,
        kinematics: Kinematics,
        spec: RigidFlatSpec,
        law: Arc<dyn InterfaceLaw>,
    ) -> Result<Self, CoreError> {
        if law.kind() != LawKind::TractionPerArea {
            return Err(CoreError::Invalid(format!(
                "interface '{}': law '{}' gives forces per point; a flat over a surface needs a traction law (or give discrete points)",
                spec.name,
                law.name()
            )));
        }
        let normal = unit_normal(&spec, kinematics)?;
        let group = mesh.group(&spec.surface)?;
        let model_dim = if kinematics == Kinematics::Solid3D { 3 } else { 2 };
        if group.dim + 1 != model_dim {
            return Err(CoreError::Invalid(format!(
                "interface '{}': surface group '{}' has dimension {}, expected {}",
                spec.name,
                spec.surface,
                group.dim,
                model_dim - 1
            )));
        }
        let mut points = Vec::new();
        let mut lowest_node = f64::INFINITY;
        for block in mesh.blocks_of(group) {
            let integrator =
                FaceIntegrator::new(block.cell_type, kinematics, spec.extra_order).map_err(CoreError::Invalid)?;
            for face in block.cells() {
                let coords: Vec<[f64; 3]> = face.iter().map(|&n| mesh.nodes[n]).collect();
                for c in &coords {
                    lowest_node = lowest_node.min(c[0] * normal[0] + c[1] * normal[1] + c[2] * normal[2]);
                }
                for p in integrator.points(&coords, 1.0) {
                    let level = (0..3).map(|k| p.position[k] * normal[k]).sum();
                    points.push(InterfacePoint {
                        nodes: face.to_vec(),
                        shape: p.shape,
                        weight: p.area,
                        level,
                        position: p.position,
                        face_area: 0.0,
                    });
                }
            }
        }
        if points.is_empty() {
            return Err(CoreError::EmptyGroup { name: spec.surface.clone(), what: "faces".into() });
        }
        // nodes (the pole) can sit lower than any integration point
        let reference = points.iter().map(|p| p.level).fold(lowest_node, f64::min);
        Self::assemble_new(spec, kinematics, law, normal, points, reference)
    }

    /// A flat against discrete points placed on a surface group (3D), with a force law.
    /// `source` names where the points came from, for messages. `footprint_area` > 0 spreads
    /// each point's force over a disc of that area and averages the displacement over it
    /// (see [`crate::footprint`]); 0 applies it at the point.
    pub fn at_points(
        mesh: &Mesh,
        kinematics: Kinematics,
        spec: RigidFlatSpec,
        law: Arc<dyn InterfaceLaw>,
        discrete: &[DiscretePoint],
        source: &str,
        footprint_area: f64,
    ) -> Result<Self, CoreError> {
        if law.kind() != LawKind::ForcePerPoint {
            return Err(CoreError::Invalid(format!(
                "interface '{}': law '{}' gives tractions; discrete points need a force-per-point law",
                spec.name,
                law.name()
            )));
        }
        if kinematics != Kinematics::Solid3D {
            return Err(CoreError::Invalid(format!("interface '{}': discrete points need a 3d model", spec.name)));
        }
        if discrete.is_empty() {
            return Err(CoreError::Invalid(format!("interface '{}': no points ({source})", spec.name)));
        }
        let normal = unit_normal(&spec, kinematics)?;
        let (placed, pole_level) =
            place_points(mesh, &spec.name, &spec.surface, normal, discrete, source, |_| footprint_area)?;
        let points: Vec<InterfacePoint> = placed
            .into_iter()
            .map(|p| InterfacePoint {
                nodes: p.nodes,
                shape: p.weights,
                weight: 1.0,
                level: p.level,
                position: p.position,
                face_area: p.face_area,
            })
            .collect();
        let mean_height = discrete.iter().map(|d| d.height).sum::<f64>() / discrete.len() as f64;
        let mut flat = Self::assemble_new(spec, kinematics, law, normal, points, pole_level - mean_height)?;
        if footprint_area > 0.0 {
            let mean_face_area = flat.points.iter().map(|p| p.face_area).sum::<f64>() / flat.points.len() as f64;
            flat.footprint = Some(FootprintResolution { footprint_area, mean_face_area });
        }
        Ok(flat)
    }

    fn assemble_new(
        spec: RigidFlatSpec,
        kinematics: Kinematics,
        law: Arc<dyn InterfaceLaw>,
        normal: [f64; 3],
        points: Vec<InterfacePoint>,
        reference_level: f64,
    ) -> Result<Self, CoreError> {
        let ns = law.n_state();
        let state = initial_states(law.as_ref(), points.len());
        let n = points.len();
        let n_fields = 4 + ns;
        Ok(Self {
            name: spec.name,
            dpn: kinematics.dofs_per_node(),
            normal,
            base_level: reference_level - spec.initial_gap,
            approach_scale: spec.approach_scale,
            approach_amplitude: spec.approach_amplitude,
            points,
            state_trial: state.clone(),
            state_committed: state,
            gap: vec![0.0; n],
            value: vec![0.0; n],
            area: vec![0.0; n],
            contact: vec![false; n],
            committed_summary: [0.0; 4],
            trial_summary: [0.0; 4],
            committed_fields: vec![vec![0.0; n]; n_fields],
            viscosity: spec.viscosity,
            gap_committed: Vec::new(),
            slope_committed: Vec::new(),
            slope: vec![0.0; n],
            time_committed: 0.0,
            viscous_committed: 0.0,
            viscous_trial: 0.0,
            trial_time: 0.0,
            resistance: spec.resistance,
            resistance_committed: f64::INFINITY,
            footprint: None,
            damages: damages_secantly(law.as_ref()),
            slider_work_state: law.state_names().iter().position(|n| n == crate::local_footprint::PLASTIC_WORK_STATE),
            law,
        })
    }

    /// Sets each point's initial state (committed and trial): `f(point, state)` may overwrite
    /// what the law initialised, e.g. a per-point parameter the law keeps as a state variable.
    pub fn set_point_states(&mut self, mut f: impl FnMut(usize, &mut [f64])) {
        let ns = self.law.n_state();
        if ns == 0 {
            return;
        }
        for (i, state) in self.state_committed.chunks_exact_mut(ns).enumerate() {
            f(i, state);
        }
        self.state_trial.copy_from_slice(&self.state_committed);
    }

    /// The index of the law's state variable named `name` (the point's own value of a
    /// per-point parameter, e.g. [`crate::point_placement::RADIUS_STATE`]).
    pub fn state_index(&self, name: &str) -> Option<usize> {
        self.law.state_names().iter().position(|n| n == name)
    }

    /// Each point's nodes, their weights in its displacement (shape functions or footprint)
    /// and the mean corner area of the faces under it (discrete points; 0 otherwise).
    pub fn point_weights(&self) -> impl Iterator<Item = (&[usize], &[f64], f64)> {
        self.points.iter().map(|p| (&p.nodes[..], &p.shape[..], p.face_area))
    }

    /// Unit normal from the flat toward the body.
    pub fn normal(&self) -> [f64; 3] {
        self.normal
    }

    /// Number of interface points (quadrature points or discrete points).
    pub fn n_points(&self) -> usize {
        self.points.len()
    }

    /// approach(t) = scale * amplitude(t).
    pub fn approach(&self, t: f64) -> f64 {
        self.approach_scale * self.approach_amplitude.value(t)
    }

    /// Reference positions of the points on the body.
    pub fn positions(&self) -> Vec<[f64; 3]> {
        self.points.iter().map(|p| p.position).collect()
    }

    /// The committed contact spots: with a force-per-point law (asperities) each point in
    /// contact, of radius sqrt(area / pi), centred at its position projected on the flat; with a
    /// traction law (a smooth surface) one spot of the whole real contact area.
    pub fn contact_spots(&self) -> Vec<ContactSpot> {
        let radius = |area: f64| (area / std::f64::consts::PI).sqrt();
        if self.law.kind() == LawKind::TractionPerArea {
            let area = self.committed_summary[2];
            return if area > 0.0 { vec![ContactSpot { center: [0.0; 3], radius: radius(area) }] } else { Vec::new() };
        }
        let n = self.normal;
        let (contact, area) = (&self.committed_fields[3], &self.committed_fields[2]);
        (0..self.points.len())
            .filter(|&i| contact[i] > 0.0 && area[i] > 0.0)
            .map(|i| {
                let p = self.points[i].position;
                let h = p[0] * n[0] + p[1] * n[1] + p[2] * n[2];
                ContactSpot { center: [p[0] - h * n[0], p[1] - h * n[1], p[2] - h * n[2]], radius: radius(area[i]) }
            })
            .collect()
    }
}

impl Contribution for RigidFlat {
    fn name(&self) -> &str {
        &self.name
    }

    /// A law with state (damage, hysteresis, footprint sliders) remembers its path.
    fn path_dependent(&self) -> bool {
        self.law.n_state() > 0
    }

    fn assemble(
        &mut self,
        time: f64,
        displacement: &[f64],
        force: &mut [f64],
        mut tangent: Option<&mut dyn TangentSink>,
    ) -> Result<(), CoreError> {
        let dpn = self.dpn;
        let traction_law = self.law.kind() == LawKind::TractionPerArea;
        let level = self.base_level + self.approach(time);
        let n = self.normal;
        let (mut total, mut area, mut count) = (0.0, 0.0, 0.0);
        let dt = time - self.time_committed;
        let viscous = self.viscosity > 0.0 && dt > 0.0 && self.slope_committed.len() == self.points.len();
        let mut dissipated = 0.0;
        // the normal's nonzero components: the gap and the force have no others (a flat
        // normal to an axis has one of three)
        let components: Vec<usize> = (0..dpn).filter(|&k| n[k] != 0.0).collect();
        for (i, p) in self.points.iter().enumerate() {
            let mut un = 0.0;
            for (a, &node) in p.nodes.iter().enumerate() {
                for &k in &components {
                    un += p.shape[a] * displacement[node * dpn + k] * n[k];
                }
            }
            let g = p.level + un - level;
            let r = evaluate_point(self.law.as_ref(), &self.name, i, g, &self.state_committed, &mut self.state_trial)?;
            let point_area = if traction_law { p.weight } else { r.area };
            self.gap[i] = g;
            self.value[i] = r.value;
            self.area[i] = if r.in_contact { point_area } else { 0.0 };
            self.contact[i] = r.in_contact;
            total += r.value * p.weight;
            if r.in_contact {
                area += point_area;
                count += 1.0;
            }
            self.slope[i] = r.tangent;
            let (mut value, mut slope) = (r.value, r.tangent);
            if viscous {
                let eta = self.viscosity * self.slope_committed[i].abs();
                let dg = g - self.gap_committed[i];
                // resists the change of gap: opening pulls back, closing pushes back
                value -= eta * dg / dt;
                slope -= eta / dt;
                dissipated += eta * dg * dg / dt * p.weight;
            }
            for (a, &node) in p.nodes.iter().enumerate() {
                for &k in &components {
                    force[node * dpn + k] -= p.shape[a] * value * n[k] * p.weight;
                }
            }
            if let Some(add) = tangent.as_deref_mut() {
                if slope != 0.0 {
                    for (a, &na) in p.nodes.iter().enumerate() {
                        for (b, &nb) in p.nodes.iter().enumerate() {
                            let s = -p.shape[a] * p.shape[b] * slope * p.weight;
                            for &k in &components {
                                for &l in &components {
                                    let local = (a * dpn + k, b * dpn + l);
                                    add.add(i, local, (na * dpn + k, nb * dpn + l), s * n[k] * n[l]);
                                }
                            }
                        }
                    }
                }
            }
        }
        self.trial_summary = [self.approach(time), total, area, count];
        self.trial_time = time;
        self.viscous_trial = self.viscous_committed + dissipated;
        Ok(())
    }

    fn amplitudes(&self) -> Vec<Arc<Amplitude>> {
        vec![self.approach_amplitude.clone()]
    }

    /// dD of each point ([`crate::damage_dissipation`]); the gap moves with the nodes
    /// (dg/du_a = N_a n) and against the flat (dg/dt = -d approach/dt).
    fn damage_dissipation(&self, gradient: &mut [f64]) -> Option<(f64, f64)> {
        if !self.damages {
            return None;
        }
        let (gap_c, value_c) = (&self.committed_fields[0], &self.committed_fields[1]);
        let middle = 0.5 * (self.time_committed + self.trial_time);
        let approach_rate = self.approach_scale * self.approach_amplitude.slope(middle);
        let (dpn, n) = (self.dpn, self.normal);
        let normal_only = |value: f64, slope: f64, gap: f64| PointState {
            value: [value, 0.0, 0.0],
            tangent: [[slope, 0.0, 0.0], [0.0; 3], [0.0; 3]],
            opening: [gap, 0.0, 0.0],
        };
        let (mut energy, mut rate) = (0.0, 0.0);
        for (i, p) in self.points.iter().enumerate() {
            let trial = normal_only(self.value[i], self.slope[i], self.gap[i]);
            let committed = normal_only(value_c[i], self.slope_committed.get(i).copied().unwrap_or(0.0), gap_c[i]);
            let (e, d) = point_dissipation(&trial, &committed, p.weight);
            energy += e;
            if d[0] == 0.0 {
                continue;
            }
            rate -= d[0] * approach_rate;
            for (a, &node) in p.nodes.iter().enumerate() {
                for k in 0..dpn {
                    gradient[node * dpn + k] += d[0] * p.shape[a] * n[k];
                }
            }
        }
        Some((energy, rate))
    }

    /// The committed plastic work of the footprints' local sliders, when the law keeps it
    /// (a state named `footprint_plastic_work`, see [`crate::local_footprint`]).
    fn plastic_dissipation(&self) -> f64 {
        match self.slider_work_state {
            Some(k) => self.state_committed.chunks_exact(self.law.n_state()).map(|s| s[k]).sum(),
            None => 0.0,
        }
    }

    fn commit(&mut self) {
        self.state_committed.copy_from_slice(&self.state_trial);
        self.gap_committed.clone_from(&self.gap);
        self.slope_committed.clone_from(&self.slope);
        self.time_committed = self.trial_time;
        self.viscous_committed = self.viscous_trial;
        self.committed_summary = self.trial_summary;
        let ns = self.law.n_state();
        self.committed_fields[0].copy_from_slice(&self.gap);
        self.committed_fields[1].copy_from_slice(&self.value);
        self.committed_fields[2].copy_from_slice(&self.area);
        for (f, &c) in self.committed_fields[3].iter_mut().zip(&self.contact) {
            *f = c as u8 as f64;
        }
        for k in 0..ns {
            for (i, f) in self.committed_fields[4 + k].iter_mut().enumerate() {
                *f = self.state_committed[i * ns + k];
            }
        }
        if let Some(model) = self.resistance {
            self.resistance_committed = model.total(&self.contact_spots());
        }
    }

    fn rollback(&mut self) {
        self.state_trial.copy_from_slice(&self.state_committed);
    }

    /// The law's states, the gaps and slopes (for the viscous term), the output fields, the
    /// summary, and the time, viscous work and resistance, all committed.
    fn saved_state(&self) -> Vec<f64> {
        let mut saved = self.state_committed.clone();
        saved.extend(&self.gap_committed);
        saved.extend(&self.slope_committed);
        self.committed_fields.iter().for_each(|f| saved.extend(f));
        saved.extend(self.committed_summary);
        saved.extend([self.time_committed, self.viscous_committed, self.resistance_committed]);
        saved
    }

    fn restore_state(&mut self, saved: &[f64]) -> Result<(), String> {
        let n = self.points.len();
        let expected = self.state_committed.len() + (2 + self.committed_fields.len()) * n + 4 + 3;
        let mut saved = SavedNumbers::new(saved, expected)?;
        let ns = self.state_committed.len();
        self.state_committed.copy_from_slice(saved.take(ns));
        self.state_trial.clone_from(&self.state_committed);
        self.gap_committed = saved.take(n).to_vec();
        self.slope_committed = saved.take(n).to_vec();
        for f in &mut self.committed_fields {
            f.copy_from_slice(saved.take(n));
        }
        self.committed_summary.copy_from_slice(saved.take(4));
        (self.time_committed, self.viscous_committed, self.resistance_committed) =
            (saved.scalar(), saved.scalar(), saved.scalar());
        // the trial copies, as a commit leaves them
        self.gap.clone_from(&self.committed_fields[0]);
        self.value.clone_from(&self.committed_fields[1]);
        self.area.clone_from(&self.committed_fields[2]);
        self.contact = self.committed_fields[3].iter().map(|&c| c != 0.0).collect();
        self.slope.clone_from(&self.slope_committed);
        (self.trial_summary, self.trial_time, self.viscous_trial) =
            (self.committed_summary, self.time_committed, self.viscous_committed);
        Ok(())
    }

    /// A footprint spans several faces: its nodes are coupled beyond any one element.
    /// One block per point: the nodes its force is spread over (a face's, or a footprint's).
    fn coupled_nodes(&self) -> Vec<Vec<usize>> {
        self.points.iter().map(|p| p.nodes.clone()).collect()
    }

    fn warnings(&self) -> Vec<String> {
        match self.footprint {
            Some(f) if f.mean_face_area > f.footprint_area && self.slider_work_state.is_none() => vec![format!(
                "interface '{}': the surface faces under the points (mean area {:.3}) are {:.1} times the footprint ({:.3}): the footprint is not resolved and acts close to a point force spread over a face; refine the contact mesh to faces no larger than the footprint for a mesh-converged continuum response, or give the points a footprint_correction",
                self.name,
                f.mean_face_area,
                f.mean_face_area / f.footprint_area,
                f.footprint_area
            )],
            _ => Vec::new(),
        }
    }

    fn observables(&self) -> Option<InterfaceObservables> {
        let [approach, force, area, count] = self.committed_summary;
        Some(InterfaceObservables {
            approach: Some(approach),
            force,
            contact_area: area,
            n_contact: count as usize,
            viscous_dissipation: Some(self.viscous_committed),
            contact_resistance: self.resistance.map(|_| self.resistance_committed),
        })
    }

    fn point_output(&self) -> Option<(Vec<[f64; 3]>, Vec<Field>)> {
        let value_name = if self.law.kind() == LawKind::TractionPerArea { "traction" } else { "force" };
        let mut fields = vec![
            Field::new("gap", 1, self.committed_fields[0].clone()),
            Field::new(value_name, 1, self.committed_fields[1].clone()),
            Field::new("area", 1, self.committed_fields[2].clone()),
            Field::new("in_contact", 1, self.committed_fields[3].clone()),
        ];
        for (k, name) in self.law.state_names().into_iter().enumerate() {
            fields.push(Field::new(name, 1, self.committed_fields[4 + k].clone()));
        }
        Some((self.positions(), fields))
    }
}
