//! A body surface against a rigid flat plane.
//!
//! The plane has unit normal n pointing from the flat toward the body and sits at
//! s(t) = s0 + approach(t) along n, where s0 = min over the surface of x . n plus
//! `initial_gap` (so approach 0 is first touch of the undeformed surface when initial_gap = 0).
//! Gap at a surface point: g = (x + u) . n - s(t).
//! A traction law sigma(g) (positive pushes apart) acts on the body along +n:
//! f_a = integral N_a sigma(g) n dA; as internal force f_int,a = -f_a, with tangent
//! K_ab = -integral N_a N_b (d sigma / d g) n x n dA.
//! Reported: `approach`, `force` (total normal force of the flat on the body, positive
//! compressive), `contact_area` (area of points in contact), `n_contact`.

use std::sync::Arc;
use stiction_core::CoreError;
use stiction_core::amplitude::Amplitude;
use stiction_core::element::Kinematics;
use stiction_core::interface_law::{InterfaceLaw, LawKind};
use stiction_core::mesh::Mesh;
use stiction_core::model::Contribution;
use stiction_core::output::vtk::Field;
use stiction_elements::FaceIntegrator;

/// How to build a rigid flat.
pub struct RigidFlatSpec {
    pub name: String,
    /// Surface group (dimension model_dim - 1).
    pub surface: String,
    /// Unit normal from the flat toward the body (3 components; axisymmetric uses x = r, y = z).
    pub normal: [f64; 3],
    /// Approach history: approach(t) = scale * amplitude(t).
    pub approach_scale: f64,
    pub approach_amplitude: Arc<Amplitude>,
    pub initial_gap: f64,
    /// Extra Gauss points per face direction (short-range laws want more).
    pub extra_order: usize,
}

/// One integration point of the interface surface.
#[derive(Debug, Clone)]
struct SurfacePoint {
    nodes: Vec<usize>,
    shape: Vec<f64>,
    area: f64,
    /// x0 . n
    level: f64,
    position: [f64; 3],
}

pub struct RigidFlat {
    name: String,
    law: Arc<dyn InterfaceLaw>,
    dpn: usize,
    normal: [f64; 3],
    base_level: f64,
    approach_scale: f64,
    approach_amplitude: Arc<Amplitude>,
    points: Vec<SurfacePoint>,
    state_committed: Vec<f64>,
    state_trial: Vec<f64>,
    /// Per point: gap, value, in contact (trial).
    gap: Vec<f64>,
    value: Vec<f64>,
    contact: Vec<bool>,
    committed_summary: [f64; 4],
    trial_summary: [f64; 4],
    committed_fields: (Vec<f64>, Vec<f64>, Vec<f64>),
}

impl RigidFlat {
    pub fn new(
        mesh: &Mesh,
        kinematics: Kinematics,
        spec: RigidFlatSpec,
        law: Arc<dyn InterfaceLaw>,
    ) -> Result<Self, CoreError> {
        if law.kind() != LawKind::TractionPerArea {
            return Err(CoreError::Invalid(format!(
                "interface '{}': law '{}' gives forces per point; a rigid flat over a surface needs a traction law",
                spec.name,
                law.name()
            )));
        }
        let nn = (spec.normal.iter().map(|x| x * x).sum::<f64>()).sqrt();
        if !(nn > 0.0) {
            return Err(CoreError::Invalid(format!("interface '{}': the normal must be non-zero", spec.name)));
        }
        let mut normal = spec.normal.map(|x| x / nn);
        if kinematics == Kinematics::Axisymmetric {
            if normal[0].abs() > 1e-12 || normal[2].abs() > 1e-12 {
                return Err(CoreError::Invalid(format!(
                    "interface '{}': in an axisymmetric model the flat must be normal to the axis (normal [0, 1] or [0, -1])",
                    spec.name
                )));
            }
            normal = [0.0, normal[1].signum(), 0.0];
        }
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
        for block in mesh.blocks_of(group) {
            let integrator =
                FaceIntegrator::new(block.cell_type, kinematics, spec.extra_order).map_err(CoreError::Invalid)?;
            for face in block.cells() {
                let coords: Vec<[f64; 3]> = face.iter().map(|&n| mesh.nodes[n]).collect();
                for p in integrator.points(&coords, 1.0) {
                    let level = (0..3).map(|k| p.position[k] * normal[k]).sum();
                    points.push(SurfacePoint {
                        nodes: face.to_vec(),
                        shape: p.shape,
                        area: p.area,
                        level,
                        position: p.position,
                    });
                }
            }
        }
        if points.is_empty() {
            return Err(CoreError::EmptyGroup { name: spec.surface.clone(), what: "faces".into() });
        }
        let min_level = points.iter().map(|p| p.level).fold(f64::INFINITY, f64::min);
        // nodes can sit lower than integration points (the pole): use nodes too
        let node_min = points
            .iter()
            .flat_map(|p| p.nodes.iter())
            .map(|&n| (0..3).map(|k| mesh.nodes[n][k] * normal[k]).sum::<f64>())
            .fold(f64::INFINITY, f64::min);
        let base_level = min_level.min(node_min) - spec.initial_gap;
        let ns = law.n_state();
        let mut state = vec![0.0; points.len() * ns];
        if ns > 0 {
            for s in state.chunks_exact_mut(ns) {
                law.initialize_state(s);
            }
        }
        let n = points.len();
        Ok(Self {
            name: spec.name,
            law,
            dpn: kinematics.dofs_per_node(),
            normal,
            base_level,
            approach_scale: spec.approach_scale,
            approach_amplitude: spec.approach_amplitude,
            points,
            state_trial: state.clone(),
            state_committed: state,
            gap: vec![0.0; n],
            value: vec![0.0; n],
            contact: vec![false; n],
            committed_summary: [0.0; 4],
            trial_summary: [0.0; 4],
            committed_fields: (vec![0.0; n], vec![0.0; n], vec![0.0; n]),
        })
    }

    /// Number of integration points on the surface.
    pub fn n_points(&self) -> usize {
        self.points.len()
    }

    /// approach(t) = scale * amplitude(t).
    pub fn approach(&self, t: f64) -> f64 {
        self.approach_scale * self.approach_amplitude.value(t)
    }

    /// Typical face size: sqrt of the mean area per point (3D) or per point / (2 pi r) (axisym).
    pub fn mean_point_area(&self) -> f64 {
        self.points.iter().map(|p| p.area).sum::<f64>() / self.points.len() as f64
    }
}

impl Contribution for RigidFlat {
    fn name(&self) -> &str {
        &self.name
    }

    fn assemble(
        &mut self,
        time: f64,
        displacement: &[f64],
        force: &mut [f64],
        mut tangent: Option<&mut dyn FnMut(usize, usize, f64)>,
    ) -> Result<(), CoreError> {
        let dpn = self.dpn;
        let ns = self.law.n_state();
        let level = self.base_level + self.approach(time);
        let n = self.normal;
        let (mut total, mut area, mut count) = (0.0, 0.0, 0.0);
        for (i, p) in self.points.iter().enumerate() {
            let mut un = 0.0;
            for (a, &node) in p.nodes.iter().enumerate() {
                for k in 0..dpn {
                    un += p.shape[a] * displacement[node * dpn + k] * n[k];
                }
            }
            let g = p.level + un - level;
            let r = self
                .law
                .evaluate(g, &self.state_committed[i * ns..(i + 1) * ns], &mut self.state_trial[i * ns..(i + 1) * ns])
                .map_err(|e| {
                    CoreError::Invalid(format!(
                        "interface '{}', law '{}', point {i}: {}",
                        self.name,
                        self.law.name(),
                        e.0
                    ))
                })?;
            if !r.value.is_finite() || !r.tangent.is_finite() {
                return Err(CoreError::NonFinite(format!(
                    "traction of law '{}' at point {i} of interface '{}' (gap {g:e})",
                    self.law.name(),
                    self.name
                )));
            }
            self.gap[i] = g;
            self.value[i] = r.value;
            self.contact[i] = r.in_contact;
            total += r.value * p.area;
            if r.in_contact {
                area += p.area;
                count += 1.0;
            }
            for (a, &node) in p.nodes.iter().enumerate() {
                for k in 0..dpn {
                    force[node * dpn + k] -= p.shape[a] * r.value * n[k] * p.area;
                }
            }
            if let Some(add) = tangent.as_deref_mut() {
                if r.tangent != 0.0 {
                    for (a, &na) in p.nodes.iter().enumerate() {
                        for (b, &nb) in p.nodes.iter().enumerate() {
                            let s = -p.shape[a] * p.shape[b] * r.tangent * p.area;
                            for i in 0..dpn {
                                for j in 0..dpn {
                                    if n[i] != 0.0 && n[j] != 0.0 {
                                        add(na * dpn + i, nb * dpn + j, s * n[i] * n[j]);
                                    }
                                }
                            }
                        }
                    }
                }
            }
        }
        self.trial_summary = [self.approach(time), total, area, count];
        Ok(())
    }

    fn amplitudes(&self) -> Vec<Arc<Amplitude>> {
        vec![self.approach_amplitude.clone()]
    }

    fn commit(&mut self) {
        self.state_committed.copy_from_slice(&self.state_trial);
        self.committed_summary = self.trial_summary;
        self.committed_fields =
            (self.gap.clone(), self.value.clone(), self.contact.iter().map(|&c| c as u8 as f64).collect());
    }

    fn rollback(&mut self) {
        self.state_trial.copy_from_slice(&self.state_committed);
    }

    fn history(&self) -> Vec<(String, f64)> {
        let [approach, force, area, count] = self.committed_summary;
        vec![
            ("approach".into(), approach),
            ("force".into(), force),
            ("contact_area".into(), area),
            ("n_contact".into(), count),
        ]
    }

    fn point_output(&self) -> Option<(Vec<[f64; 3]>, Vec<Field>)> {
        let positions = self.points.iter().map(|p| p.position).collect();
        let (g, v, c) = &self.committed_fields;
        Some((
            positions,
            vec![
                Field::new("gap", 1, g.clone()),
                Field::new("traction", 1, v.clone()),
                Field::new("in_contact", 1, c.clone()),
            ],
        ))
    }
}
