//! Distributed loads (pressure, traction) on boundary groups, integrated once into nodal load
//! vectors scaled by their amplitudes.

use super::amplitudes::Amplitudes;
use crate::case::{LoadSpec, LoadedCase};
use crate::error::Result;
use stiction_core::element::Kinematics;
use stiction_core::mesh::Mesh;
use stiction_core::model::{ExternalLoad, Model};
use stiction_elements::{BoundaryFinder, FaceIntegrator};

/// Traction t(x, n) per unit area of load `l` (case key `key`).
type Traction = Box<dyn Fn([f64; 3], [f64; 3]) -> [f64; 3]>;

fn traction_of(case: &LoadedCase, key: &str, l: &LoadSpec, dpn: usize) -> Result<Traction> {
    Ok(match l.kind.as_str() {
        "pressure" => {
            let p = l.value.ok_or_else(|| case.error(format!("{key}.value"), "required for type 'pressure'"))?;
            Box::new(move |_x, n| [-p * n[0], -p * n[1], -p * n[2]])
        }
        "traction" => {
            let v =
                l.vector.clone().ok_or_else(|| case.error(format!("{key}.vector"), "required for type 'traction'"))?;
            if v.len() != dpn {
                return Err(case.error(format!("{key}.vector"), format!("needs {dpn} components")));
            }
            let t = [v[0], v[1], if dpn == 3 { v[2] } else { 0.0 }];
            Box::new(move |_x, _n| t)
        }
        other => {
            return Err(
                case.error(format!("{key}.type"), format!("unknown load type '{other}' (known: pressure, traction)"))
            );
        }
    })
}

/// Adds the case's distributed loads to `model`; returns each loaded group once with its
/// nodes (their mean displacement goes to `history.csv`).
pub fn add_loads(
    case: &LoadedCase,
    mesh: &Mesh,
    kin: Kinematics,
    amplitudes: &Amplitudes,
    model: &mut Model,
) -> Result<Vec<(String, Vec<usize>)>> {
    let c = &case.case;
    let mut load_groups: Vec<(String, Vec<usize>)> = Vec::new();
    if c.loads.is_empty() {
        return Ok(load_groups);
    }
    let dpn = kin.dofs_per_node();
    let model_dim = if kin == Kinematics::Solid3D { 3 } else { 2 };
    let finder = BoundaryFinder::new(
        &mesh.nodes,
        model.sets.iter().flat_map(|s| {
            let ct = s.kernel.cell_type();
            s.connectivity.chunks_exact(ct.n_nodes()).map(move |conn| (ct, conn))
        }),
    );
    for (i, l) in c.loads.iter().enumerate() {
        let key = format!("loads[{i}]");
        let group = mesh.group(&l.group).map_err(|e| case.error(format!("{key}.group"), e.to_string()))?;
        if group.dim + 1 != model_dim {
            return Err(case.error(
                format!("{key}.group"),
                format!(
                    "group '{}' has dimension {}; loads act on boundary groups of dimension {}",
                    l.group,
                    group.dim,
                    model_dim - 1
                ),
            ));
        }
        let traction = traction_of(case, &key, l, dpn)?;
        let mut vector = vec![0.0; model.n_dofs()];
        let mut any = false;
        for block in mesh.blocks_of(group) {
            let integrator =
                FaceIntegrator::new(block.cell_type, kin, 0).map_err(|m| case.error(format!("{key}.group"), m))?;
            let nn = block.cell_type.n_nodes();
            let mut fe = vec![0.0; nn * dpn];
            for face in block.cells() {
                let coords: Vec<[f64; 3]> = face.iter().map(|&n| mesh.nodes[n]).collect();
                let pts = integrator.points(&coords, 1.0);
                let centroid = pts[0].position;
                let nc = block.cell_type.n_corners();
                let sign = finder.outward_sign(&face[..nc], centroid, pts[0].normal).ok_or_else(|| {
                    case.error(
                        format!("{key}.group"),
                        format!("a face of group '{}' is not on the boundary of any section's cells", l.group),
                    )
                })?;
                fe.fill(0.0);
                integrator.integrate_traction(&coords, sign, &traction, &mut fe);
                for (a, &node) in face.iter().enumerate() {
                    for k in 0..dpn {
                        vector[node * dpn + k] += fe[a * dpn + k];
                    }
                }
                any = true;
            }
        }
        if !any {
            return Err(case.error(format!("{key}.group"), format!("group '{}' has no faces", l.group)));
        }
        model.loads.push(ExternalLoad {
            name: l.group.clone(),
            vector,
            amplitude: amplitudes.get(case, format!("{key}.amplitude"), &l.amplitude)?,
        });
        if !load_groups.iter().any(|(n, _)| n == &l.group) {
            load_groups.push((l.group.clone(), mesh.group_nodes(group)));
        }
    }
    Ok(load_groups)
}
