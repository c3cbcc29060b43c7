//! Zero-thickness cohesive elements between the two sides of a split surface.
//!
//! At each surface integration point, with face shape functions N_k, the opening is
//! du = sum_k N_k (u_B,k - u_A,k) (side B holds the duplicated nodes), the normal gap
//! g = du . n (n the face normal from side A toward side B) and the tangential slip
//! s = du - g n. The law gives the normal value sigma(g) (positive pushes the sides apart); the
//! slip meets an elastic shear penalty k_s (the law is normal-only). Forces: on B
//! f = N (sigma n - k_s s) w, on A the opposite; tangent from d sigma / d g and k_s.

use crate::point_law::evaluate_point;
use std::collections::HashMap;
use std::sync::Arc;
use stiction_core::CoreError;
use stiction_core::element::Kinematics;
use stiction_core::interface_law::{InterfaceLaw, LawKind};
use stiction_core::mesh::Mesh;
use stiction_core::model::Contribution;
use stiction_core::output::vtk::Field;
use stiction_elements::FaceIntegrator;

struct Point {
    a: Vec<usize>,
    b: Vec<usize>,
    shape: Vec<f64>,
    weight: f64,
    normal: [f64; 3],
    position: [f64; 3],
}

pub struct CohesiveElements {
    name: String,
    law: Arc<dyn InterfaceLaw>,
    shear_stiffness: f64,
    dpn: usize,
    points: Vec<Point>,
    state_committed: Vec<f64>,
    state_trial: Vec<f64>,
    gap: Vec<f64>,
    value: Vec<f64>,
    trial_summary: [f64; 3],
    committed_summary: [f64; 3],
    committed_fields: [Vec<f64>; 2],
}

impl CohesiveElements {
    /// Cohesive elements on the faces of `surface` of the unsplit mesh `original`, whose nodes
    /// were duplicated (`pairs`: original -> duplicate) for side B; `side_centroid` gives the
    /// centroid of the side-B cell bounded by a face (its duplicated nodes), to orient the
    /// normal from A toward B.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        name: &str,
        original: &Mesh,
        surface: &str,
        pairs: &HashMap<usize, usize>,
        side_centroid: impl Fn(&[usize]) -> Option<[f64; 3]>,
        kinematics: Kinematics,
        law: Arc<dyn InterfaceLaw>,
        shear_stiffness: f64,
        extra_order: usize,
    ) -> Result<Self, CoreError> {
        if law.kind() != LawKind::TractionPerArea {
            return Err(CoreError::Invalid(format!("interface '{name}': cohesive elements need a traction law")));
        }
        let group = original.group(surface)?;
        let mut points = Vec::new();
        for block in original.blocks_of(group) {
            let integrator =
                FaceIntegrator::new(block.cell_type, kinematics, extra_order).map_err(CoreError::Invalid)?;
            for face in block.cells() {
                let b: Vec<usize> =
                    face.iter().map(|n| pairs.get(n).copied()).collect::<Option<_>>().ok_or_else(|| {
                        CoreError::Invalid(format!("interface '{name}': a face of '{surface}' was not split"))
                    })?;
                let coords: Vec<[f64; 3]> = face.iter().map(|&n| original.nodes[n]).collect();
                let probe = integrator.points(&coords, 1.0);
                let c = side_centroid(&b).ok_or_else(|| {
                    CoreError::Invalid(format!(
                        "interface '{name}': a face of '{surface}' bounds no cell of the split side"
                    ))
                })?;
                let d: f64 = (0..3).map(|k| (c[k] - probe[0].position[k]) * probe[0].normal[k]).sum();
                let sign = if d >= 0.0 { 1.0 } else { -1.0 };
                for p in integrator.points(&coords, sign) {
                    points.push(Point {
                        a: face.to_vec(),
                        b: b.clone(),
                        shape: p.shape,
                        weight: p.area,
                        normal: p.normal,
                        position: p.position,
                    });
                }
            }
        }
        let ns = law.n_state();
        let mut state = vec![0.0; points.len() * ns];
        if ns > 0 {
            for s in state.chunks_exact_mut(ns) {
                law.initialize_state(s);
            }
        }
        let n = points.len();
        Ok(Self {
            name: name.to_string(),
            law,
            shear_stiffness,
            dpn: kinematics.dofs_per_node(),
            points,
            state_trial: state.clone(),
            state_committed: state,
            gap: vec![0.0; n],
            value: vec![0.0; n],
            trial_summary: [0.0; 3],
            committed_summary: [0.0; 3],
            committed_fields: [vec![0.0; n], vec![0.0; n]],
        })
    }
}

impl Contribution for CohesiveElements {
    fn name(&self) -> &str {
        &self.name
    }

    fn coupled_nodes(&self) -> Vec<Vec<usize>> {
        self.points.iter().map(|p| p.a.iter().chain(&p.b).copied().collect()).collect()
    }

    fn assemble(
        &mut self,
        _time: f64,
        u: &[f64],
        force: &mut [f64],
        mut tangent: Option<&mut dyn FnMut(usize, usize, f64)>,
    ) -> Result<(), CoreError> {
        let dpn = self.dpn;
        let (mut total, mut area, mut count) = (0.0, 0.0, 0.0);
        for (i, p) in self.points.iter().enumerate() {
            let n = p.normal;
            let mut du = [0.0; 3];
            for (k, (&na, &nb)) in p.a.iter().zip(&p.b).enumerate() {
                for c in 0..dpn {
                    du[c] += p.shape[k] * (u[nb * dpn + c] - u[na * dpn + c]);
                }
            }
            let g: f64 = (0..3).map(|c| du[c] * n[c]).sum();
            let slip: [f64; 3] = std::array::from_fn(|c| du[c] - g * n[c]);
            let r = evaluate_point(self.law.as_ref(), &self.name, i, g, &self.state_committed, &mut self.state_trial)?;
            self.gap[i] = g;
            self.value[i] = r.value;
            total += r.value * p.weight;
            if r.in_contact {
                area += p.weight;
                count += 1.0;
            }
            // traction on side B
            let t: [f64; 3] = std::array::from_fn(|c| r.value * n[c] - self.shear_stiffness * slip[c]);
            for (k, (&na, &nb)) in p.a.iter().zip(&p.b).enumerate() {
                for c in 0..dpn {
                    let f = p.shape[k] * t[c] * p.weight;
                    force[nb * dpn + c] -= f;
                    force[na * dpn + c] += f;
                }
            }
            if let Some(add) = tangent.as_deref_mut() {
                // d t_c / d du_e = dsigma/dg n_c n_e - k_s (delta_ce - n_c n_e)
                let dt = |c: usize, e: usize| {
                    let nn = n[c] * n[e];
                    r.tangent * nn - self.shear_stiffness * (if c == e { 1.0 } else { 0.0 } - nn)
                };
                for (k, (&ak, &bk)) in p.a.iter().zip(&p.b).enumerate() {
                    for (l, (&al, &bl)) in p.a.iter().zip(&p.b).enumerate() {
                        let s = p.shape[k] * p.shape[l] * p.weight;
                        for c in 0..dpn {
                            for e in 0..dpn {
                                let v = -s * dt(c, e);
                                if v != 0.0 {
                                    // force on B (-t) w.r.t. u_B (+) and u_A (-); on A the opposite
                                    add(bk * dpn + c, bl * dpn + e, v);
                                    add(bk * dpn + c, al * dpn + e, -v);
                                    add(ak * dpn + c, bl * dpn + e, -v);
                                    add(ak * dpn + c, al * dpn + e, v);
                                }
                            }
                        }
                    }
                }
            }
        }
        self.trial_summary = [total, area, count];
        Ok(())
    }

    fn commit(&mut self) {
        self.state_committed.copy_from_slice(&self.state_trial);
        self.committed_summary = self.trial_summary;
        self.committed_fields = [self.gap.clone(), self.value.clone()];
    }

    fn rollback(&mut self) {
        self.state_trial.copy_from_slice(&self.state_committed);
    }

    fn history(&self) -> Vec<(String, f64)> {
        let [force, area, count] = self.committed_summary;
        vec![("force".into(), force), ("contact_area".into(), area), ("n_contact".into(), count)]
    }

    fn point_output(&self) -> Option<(Vec<[f64; 3]>, Vec<Field>)> {
        Some((
            self.points.iter().map(|p| p.position).collect(),
            vec![
                Field::new("gap", 1, self.committed_fields[0].clone()),
                Field::new("traction", 1, self.committed_fields[1].clone()),
            ],
        ))
    }
}
