//! Boundary conditions by physical group (fixed, prescribed displacement histories, symmetry
//! planes) and u_r = 0 on the axis of axisymmetric models; the groups whose reactions are
//! recorded.

use super::amplitudes::Amplitudes;
use crate::case::{BoundarySpec, LoadedCase};
use crate::error::Result;
use std::sync::Arc;
use stiction_core::amplitude::Amplitude;
use stiction_core::element::Kinematics;
use stiction_core::mesh::Mesh;
use stiction_core::model::{Model, Prescribed};

fn component_index(case: &LoadedCase, key: &str, name: &str, kin: Kinematics) -> Result<usize> {
    let idx = match (kin, name) {
        (_, "x") | (Kinematics::Axisymmetric, "r") => 0,
        (_, "y") | (Kinematics::Axisymmetric, "z") => 1,
        (Kinematics::Solid3D, "z") => 2,
        _ => {
            return Err(
                case.error(key, format!("unknown component '{name}' (3d: x, y, z; axisymmetric: r or x, z or y)"))
            );
        }
    };
    Ok(idx)
}

/// Components, scale and amplitude that boundary condition `b` (case key `key`) prescribes.
fn prescription(
    case: &LoadedCase,
    key: &str,
    b: &BoundarySpec,
    kin: Kinematics,
    amplitudes: &Amplitudes,
) -> Result<(Vec<usize>, f64, Arc<Amplitude>)> {
    let all: Vec<usize> = (0..kin.dofs_per_node()).collect();
    let listed = |components: &Option<Vec<String>>| -> Result<Vec<usize>> {
        match components {
            None => Ok(all.clone()),
            Some(list) if list.is_empty() => Err(case.error(format!("{key}.components"), "must not be empty")),
            Some(list) => list.iter().map(|n| component_index(case, &format!("{key}.components"), n, kin)).collect(),
        }
    };
    Ok(match b.kind.as_str() {
        "fixed" => (listed(&b.components)?, 0.0, amplitudes.ramp()),
        "displacement" => {
            let v = b.value.ok_or_else(|| case.error(format!("{key}.value"), "required for type 'displacement'"))?;
            if !v.is_finite() {
                return Err(case.error(format!("{key}.value"), "must be a finite number"));
            }
            (listed(&b.components)?, v, amplitudes.get(case, format!("{key}.amplitude"), &b.amplitude)?)
        }
        "symmetry" => {
            let n = b
                .normal
                .as_deref()
                .ok_or_else(|| case.error(format!("{key}.normal"), "required for type 'symmetry' (x, y or z)"))?;
            (vec![component_index(case, &format!("{key}.normal"), n, kin)?], 0.0, amplitudes.ramp())
        }
        other => {
            return Err(case.error(
                format!("{key}.type"),
                format!("unknown boundary type '{other}' (known: fixed, displacement, symmetry)"),
            ));
        }
    })
}

/// Prescribes the case's boundary conditions; returns the groups whose reactions are recorded.
pub fn add_boundaries(
    case: &LoadedCase,
    mesh: &Mesh,
    kin: Kinematics,
    amplitudes: &Amplitudes,
    model: &mut Model,
) -> Result<Vec<(String, Vec<usize>)>> {
    let dpn = kin.dofs_per_node();
    let mut reaction_groups: Vec<(String, Vec<usize>)> = Vec::new();
    for (i, b) in case.case.boundary.iter().enumerate() {
        let key = format!("boundary[{i}]");
        let group = mesh.group(&b.group).map_err(|e| case.error(format!("{key}.group"), e.to_string()))?;
        let nodes = mesh.group_nodes(group);
        if nodes.is_empty() {
            return Err(case.error(format!("{key}.group"), format!("group '{}' has no nodes", b.group)));
        }
        let (components, scale, amp) = prescription(case, &key, b, kin, amplitudes)?;
        for &node in &nodes {
            for &comp in &components {
                model
                    .prescribe(Prescribed {
                        dof: node * dpn + comp,
                        scale,
                        amplitude: amp.clone(),
                        source: key.clone(),
                    })
                    .map_err(|e| case.error(&key, e.to_string()))?;
            }
        }
        if !reaction_groups.iter().any(|(n, _)| n == &b.group) {
            reaction_groups.push((b.group.clone(), nodes));
        }
    }
    if kin == Kinematics::Axisymmetric {
        fix_axis(mesh, amplitudes, model)?;
    }
    Ok(reaction_groups)
}

/// u_r = 0 on the axis of symmetry (nodes at r = 0).
fn fix_axis(mesh: &Mesh, amplitudes: &Amplitudes, model: &mut Model) -> Result<()> {
    let dpn = model.dofs_per_node();
    let (lo, hi) = mesh.bounding_box();
    let tol = 1e-9 * (hi[0] - lo[0]).max(hi[1] - lo[1]);
    let ramp = amplitudes.ramp();
    for (n, x) in mesh.nodes.iter().enumerate() {
        if x[0].abs() <= tol {
            model.prescribe(Prescribed {
                dof: n * dpn,
                scale: 0.0,
                amplitude: ramp.clone(),
                source: "symmetry axis r = 0".into(),
            })?;
        }
    }
    Ok(())
}
