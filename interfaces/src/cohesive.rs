//! Zero-thickness cohesive elements between the two sides of a split surface.
//!
//! At each surface integration point, with face shape functions N_k, the opening is
//! du = sum_k N_k (u_B,k - u_A,k) (side B holds the duplicated nodes), expressed in the local
//! frame e_0 = n (the face normal from side A toward side B), e_1, e_2 (tangential):
//! delta_i = du . e_i. A mixed-mode law (gap dimension 3) maps delta to the value vector v
//! (force per area on side B along e_i) with tangent dv_i/d delta_j; a normal-only law gives
//! v_0 = sigma(delta_0) and the slip meets an elastic shear penalty k_s: v_1,2 = -k_s delta_1,2.
//! Forces: on B f = N t w with t = sum_i v_i e_i, on A the opposite; tangent
//! dt_c / d du_e = sum_ij e_i,c (dv_i / d delta_j) e_j,e.

use crate::damage_dissipation::{PointState, damages_secantly, point_dissipation};
use crate::point_law::{evaluate_point, evaluate_point_mixed, initial_states};
use std::collections::HashMap;
use std::sync::Arc;
use stiction_core::CoreError;
use stiction_core::checkpoint::SavedNumbers;
use stiction_core::element::Kinematics;
use stiction_core::interface_law::{InterfaceLaw, LawKind};
use stiction_core::mesh::Mesh;
use stiction_core::model::Contribution;
use stiction_core::observables::InterfaceObservables;
use stiction_core::output::vtk::Field;
use stiction_core::tangent_sink::TangentSink;
use stiction_elements::FaceIntegrator;

struct Point {
    a: Vec<usize>,
    b: Vec<usize>,
    shape: Vec<f64>,
    weight: f64,
    /// Local frame: normal (A toward B), tangential 1, tangential 2.
    frame: [[f64; 3]; 3],
    position: [f64; 3],
}

/// An orthonormal frame whose first axis is the unit normal `n`: the first tangent is the
/// coordinate axis least aligned with n, made orthogonal to it (for an axisymmetric meridian
/// normal (n_r, n_z, 0) that is the hoop axis, whose slip is zero, and the second tangent lies
/// in the meridian plane).
fn local_frame(n: [f64; 3]) -> [[f64; 3]; 3] {
    let axis = (0..3).min_by(|&a, &b| n[a].abs().total_cmp(&n[b].abs())).unwrap_or(0);
    let mut t1 = [0.0; 3];
    t1[axis] = 1.0;
    let d = n[axis];
    for c in 0..3 {
        t1[c] -= d * n[c];
    }
    let len = (t1[0] * t1[0] + t1[1] * t1[1] + t1[2] * t1[2]).sqrt();
    t1 = t1.map(|v| v / len);
    let t2 = [n[1] * t1[2] - n[2] * t1[1], n[2] * t1[0] - n[0] * t1[2], n[0] * t1[1] - n[1] * t1[0]];
    [n, t1, t2]
}

pub struct CohesiveElements {
    name: String,
    law: Arc<dyn InterfaceLaw>,
    shear_stiffness: f64,
    dpn: usize,
    points: Vec<Point>,
    state_committed: Vec<f64>,
    state_trial: Vec<f64>,
    /// Opening and value per point in the local frame (trial, then committed for output).
    opening: Vec<[f64; 3]>,
    value: Vec<[f64; 3]>,
    /// d value_i / d delta_j per point (trial).
    slope: Vec<[[f64; 3]; 3]>,
    trial_summary: [f64; 3],
    committed_summary: [f64; 3],
    committed_fields: (Vec<[f64; 3]>, Vec<[f64; 3]>),
    /// Value, tangent and opening per point at the committed state (for the dissipation).
    committed_points: Vec<PointState>,
    /// The law damages with secant unloading ([`crate::damage_dissipation::damages_secantly`]).
    damages: bool,
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
                        frame: local_frame(p.normal),
                        position: p.position,
                    });
                }
            }
        }
        let state = initial_states(law.as_ref(), points.len());
        let n = points.len();
        let damages = damages_secantly(law.as_ref());
        Ok(Self {
            name: name.to_string(),
            law,
            shear_stiffness,
            dpn: kinematics.dofs_per_node(),
            points,
            state_trial: state.clone(),
            state_committed: state,
            opening: vec![[0.0; 3]; n],
            value: vec![[0.0; 3]; n],
            slope: vec![[[0.0; 3]; 3]; n],
            trial_summary: [0.0; 3],
            committed_summary: [0.0; 3],
            committed_fields: (vec![[0.0; 3]; n], vec![[0.0; 3]; n]),
            committed_points: vec![PointState::default(); n],
            damages,
        })
    }
}

impl Contribution for CohesiveElements {
    fn name(&self) -> &str {
        &self.name
    }

    /// A law with state (damage, hysteresis, footprint sliders) remembers its path.
    fn path_dependent(&self) -> bool {
        self.law.n_state() > 0
    }

    /// One block per point: the nodes of side A, then those of side B.
    fn coupled_nodes(&self) -> Vec<Vec<usize>> {
        self.points.iter().map(|p| p.a.iter().chain(&p.b).copied().collect()).collect()
    }

    fn assemble(
        &mut self,
        _time: f64,
        u: &[f64],
        force: &mut [f64],
        mut tangent: Option<&mut dyn TangentSink>,
    ) -> Result<(), CoreError> {
        let dpn = self.dpn;
        let (mut total, mut area, mut count) = (0.0, 0.0, 0.0);
        let mixed = self.law.gap_dimension() == 3;
        for (i, p) in self.points.iter().enumerate() {
            let e = p.frame;
            let mut du = [0.0; 3];
            for (k, (&na, &nb)) in p.a.iter().zip(&p.b).enumerate() {
                for c in 0..dpn {
                    du[c] += p.shape[k] * (u[nb * dpn + c] - u[na * dpn + c]);
                }
            }
            let delta: [f64; 3] = std::array::from_fn(|i| (0..3).map(|c| du[c] * e[i][c]).sum());
            let (v, dv, in_contact) = if mixed {
                let r = evaluate_point_mixed(
                    self.law.as_ref(),
                    &self.name,
                    i,
                    delta,
                    &self.state_committed,
                    &mut self.state_trial,
                )?;
                (r.value, r.tangent, r.in_contact)
            } else {
                let r = evaluate_point(
                    self.law.as_ref(),
                    &self.name,
                    i,
                    delta[0],
                    &self.state_committed,
                    &mut self.state_trial,
                )?;
                let ks = self.shear_stiffness;
                let v = [r.value, -ks * delta[1], -ks * delta[2]];
                (v, [[r.tangent, 0.0, 0.0], [0.0, -ks, 0.0], [0.0, 0.0, -ks]], r.in_contact)
            };
            self.opening[i] = delta;
            self.value[i] = v;
            self.slope[i] = dv;
            total += v[0] * p.weight;
            if in_contact {
                area += p.weight;
                count += 1.0;
            }
            // traction on side B in global components
            let t: [f64; 3] = std::array::from_fn(|c| (0..3).map(|i| v[i] * e[i][c]).sum());
            for (k, (&na, &nb)) in p.a.iter().zip(&p.b).enumerate() {
                for c in 0..dpn {
                    let f = p.shape[k] * t[c] * p.weight;
                    force[nb * dpn + c] -= f;
                    force[na * dpn + c] += f;
                }
            }
            if let Some(add) = tangent.as_deref_mut() {
                // dt_c / d du_d = sum_ij e_i,c dv_i/d delta_j e_j,d
                let dt: [[f64; 3]; 3] = std::array::from_fn(|c| {
                    std::array::from_fn(|d| {
                        let mut sum = 0.0;
                        for i in 0..3 {
                            for j in 0..3 {
                                sum += e[i][c] * dv[i][j] * e[j][d];
                            }
                        }
                        sum
                    })
                });
                let n_a = p.a.len();
                for (k, (&ak, &bk)) in p.a.iter().zip(&p.b).enumerate() {
                    for (l, (&al, &bl)) in p.a.iter().zip(&p.b).enumerate() {
                        let s = p.shape[k] * p.shape[l] * p.weight;
                        for c in 0..dpn {
                            for d in 0..dpn {
                                let v = -s * dt[c][d];
                                if v != 0.0 {
                                    // force on B (-t) w.r.t. u_B (+) and u_A (-); on A the opposite;
                                    // block i lists the A nodes, then the B nodes
                                    let (ra, rb) = (k * dpn + c, (n_a + k) * dpn + c);
                                    let (ca, cb) = (l * dpn + d, (n_a + l) * dpn + d);
                                    add.add(i, (rb, cb), (bk * dpn + c, bl * dpn + d), v);
                                    add.add(i, (rb, ca), (bk * dpn + c, al * dpn + d), -v);
                                    add.add(i, (ra, cb), (ak * dpn + c, bl * dpn + d), -v);
                                    add.add(i, (ra, ca), (ak * dpn + c, al * dpn + d), v);
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

    /// dD of each point ([`crate::damage_dissipation`]), with d delta_j / d u_B = N e_j =
    /// -d delta_j / d u_A; the opening does not depend on t.
    fn damage_dissipation(&self, gradient: &mut [f64]) -> Option<(f64, f64)> {
        if !self.damages {
            return None;
        }
        let dpn = self.dpn;
        let mut energy = 0.0;
        for (i, p) in self.points.iter().enumerate() {
            let trial = PointState { value: self.value[i], tangent: self.slope[i], opening: self.opening[i] };
            let (e, local) = point_dissipation(&trial, &self.committed_points[i], p.weight);
            energy += e;
            let global: [f64; 3] = std::array::from_fn(|c| (0..3).map(|j| local[j] * p.frame[j][c]).sum());
            if global.iter().all(|&g| g == 0.0) {
                continue;
            }
            for (k, (&na, &nb)) in p.a.iter().zip(&p.b).enumerate() {
                for c in 0..dpn {
                    gradient[nb * dpn + c] += p.shape[k] * global[c];
                    gradient[na * dpn + c] -= p.shape[k] * global[c];
                }
            }
        }
        Some((energy, 0.0))
    }

    fn commit(&mut self) {
        self.state_committed.copy_from_slice(&self.state_trial);
        self.committed_summary = self.trial_summary;
        self.committed_fields = (self.opening.clone(), self.value.clone());
        for (i, c) in self.committed_points.iter_mut().enumerate() {
            *c = PointState { value: self.value[i], tangent: self.slope[i], opening: self.opening[i] };
        }
    }

    fn rollback(&mut self) {
        self.state_trial.copy_from_slice(&self.state_committed);
    }

    /// The law's states, the summary, and per point the committed value, tangent and opening.
    fn saved_state(&self) -> Vec<f64> {
        let mut saved = self.state_committed.clone();
        saved.extend(self.committed_summary);
        for p in &self.committed_points {
            saved.extend(p.value);
            saved.extend(p.tangent.iter().flatten());
            saved.extend(p.opening);
        }
        saved
    }

    fn restore_state(&mut self, saved: &[f64]) -> Result<(), String> {
        let n = self.points.len();
        let mut saved = SavedNumbers::new(saved, self.state_committed.len() + 3 + 15 * n)?;
        let ns = self.state_committed.len();
        self.state_committed.copy_from_slice(saved.take(ns));
        self.state_trial.clone_from(&self.state_committed);
        self.committed_summary.copy_from_slice(saved.take(3));
        self.trial_summary = self.committed_summary;
        let three = |s: &[f64]| [s[0], s[1], s[2]];
        for (i, p) in self.committed_points.iter_mut().enumerate() {
            let value = three(saved.take(3));
            let t = saved.take(9);
            let tangent = [three(&t[0..3]), three(&t[3..6]), three(&t[6..9])];
            let opening = three(saved.take(3));
            *p = PointState { value, tangent, opening };
            (self.value[i], self.slope[i], self.opening[i]) = (value, tangent, opening);
        }
        self.committed_fields = (self.opening.clone(), self.value.clone());
        Ok(())
    }

    fn observables(&self) -> Option<InterfaceObservables> {
        let [force, area, count] = self.committed_summary;
        Some(InterfaceObservables {
            approach: None,
            force,
            contact_area: area,
            n_contact: count as usize,
            viscous_dissipation: None,
            contact_resistance: None,
        })
    }

    fn point_output(&self) -> Option<(Vec<[f64; 3]>, Vec<Field>)> {
        let (opening, value) = &self.committed_fields;
        let slip = |v: &[f64; 3]| (v[1] * v[1] + v[2] * v[2]).sqrt();
        // opening and traction vectors in global components, for glyphs
        let global = |x: &[[f64; 3]]| -> Vec<f64> {
            x.iter()
                .zip(&self.points)
                .flat_map(|(v, p)| (0..3).map(move |c| (0..3).map(|i| v[i] * p.frame[i][c]).sum::<f64>()))
                .collect()
        };
        let mut fields = vec![
            Field::new("gap", 1, opening.iter().map(|o| o[0]).collect()),
            Field::new("slip", 1, opening.iter().map(slip).collect()),
            Field::new("traction", 1, value.iter().map(|v| v[0]).collect()),
            Field::new("shear_traction", 1, value.iter().map(slip).collect()),
            Field::new("opening_vector", 3, global(opening)),
            Field::new("traction_vector", 3, global(value)),
        ];
        let ns = self.law.n_state();
        for (k, name) in self.law.state_names().into_iter().enumerate() {
            fields.push(Field::new(
                &name,
                1,
                (0..self.points.len()).map(|i| self.state_committed[i * ns + k]).collect(),
            ));
        }
        Some((self.points.iter().map(|p| p.position).collect(), fields))
    }
}
