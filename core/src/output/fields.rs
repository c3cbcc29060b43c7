//! Output fields of the solid: displacement, stress tensor, von Mises stress and material
//! outputs (e.g. equivalent plastic strain), as cell averages and as nodal values
//! (volume-weighted averages of the cell averages around each node).

use crate::element::Kinematics;
use crate::mesh::CellType;
use crate::model::Model;
use crate::output::vtk::Field;
use crate::voigt::von_mises;

/// The cells of the solid (type, flattened gmsh connectivity) in the order of the cell fields.
pub fn solid_cells(model: &Model) -> Vec<(CellType, &[usize])> {
    model.sets.iter().map(|s| (s.kernel.cell_type(), s.connectivity.as_slice())).collect()
}

/// Point and cell fields at the current (committed) state.
pub fn solid_fields(model: &Model) -> (Vec<Field>, Vec<Field>) {
    let n_nodes = model.mesh.nodes.len();
    let dpn = model.dofs_per_node();
    let mut displacement = vec![0.0; n_nodes * 3];
    for n in 0..n_nodes {
        for k in 0..dpn {
            displacement[n * 3 + k] = model.displacement[n * dpn + k];
        }
    }
    // union of material output names
    let mut names: Vec<&'static str> = Vec::new();
    for s in &model.sets {
        for n in s.material.output_names() {
            if !names.contains(&n) {
                names.push(n);
            }
        }
    }
    let nm = names.len();
    let n_cells: usize = model.sets.iter().map(|s| s.n_cells()).sum();
    let mut cell_stress = Vec::with_capacity(n_cells * 6);
    let mut cell_vm = Vec::with_capacity(n_cells);
    let mut cell_mat = vec![0.0; n_cells * nm];
    let mut node_acc = vec![0.0; n_nodes * (7 + nm)];
    let mut node_w = vec![0.0; n_nodes];
    let mut cell_index = 0;
    for set in &model.sets {
        let nq = set.kernel.n_points();
        let ns = set.material.n_state();
        let mine = set.material.output_names();
        let map: Vec<usize> = mine.iter().map(|n| names.iter().position(|m| m == n).unwrap()).collect();
        let mut vols = vec![0.0; nq];
        let mut coords = vec![[0.0; 3]; set.kernel.n_nodes()];
        let mut out = vec![0.0; mine.len()];
        for c in 0..set.n_cells() {
            for (a, &n) in set.cell(c).iter().enumerate() {
                coords[a] = model.mesh.nodes[n];
            }
            set.kernel.point_volumes(&coords, &mut vols);
            let vol: f64 = vols.iter().sum::<f64>().max(1e-300);
            let mut s_avg = [0.0; 6];
            let mut vm = 0.0;
            let mut m_avg = vec![0.0; nm];
            for q in 0..nq {
                let w = vols[q] / vol;
                let s = &set.stresses()[c * nq + q];
                for k in 0..6 {
                    s_avg[k] += w * s[k];
                }
                vm += w * von_mises(s);
                if ns > 0 {
                    set.material.outputs(&set.committed_state()[(c * nq + q) * ns..(c * nq + q + 1) * ns], &mut out);
                    for (i, &j) in map.iter().enumerate() {
                        m_avg[j] += w * out[i];
                    }
                }
            }
            cell_stress.extend_from_slice(&s_avg);
            cell_vm.push(vm);
            cell_mat[cell_index * nm..(cell_index + 1) * nm].copy_from_slice(&m_avg);
            for &n in set.cell(c) {
                let acc = &mut node_acc[n * (7 + nm)..(n + 1) * (7 + nm)];
                for k in 0..6 {
                    acc[k] += vol * s_avg[k];
                }
                acc[6] += vol * vm;
                for j in 0..nm {
                    acc[7 + j] += vol * m_avg[j];
                }
                node_w[n] += vol;
            }
            cell_index += 1;
        }
    }
    let mut node_stress = vec![0.0; n_nodes * 6];
    let mut node_vm = vec![0.0; n_nodes];
    let mut node_mat = vec![vec![0.0; n_nodes]; nm];
    for n in 0..n_nodes {
        if node_w[n] > 0.0 {
            let acc = &node_acc[n * (7 + nm)..(n + 1) * (7 + nm)];
            for k in 0..6 {
                node_stress[n * 6 + k] = acc[k] / node_w[n];
            }
            node_vm[n] = acc[6] / node_w[n];
            for j in 0..nm {
                node_mat[j][n] = acc[7 + j] / node_w[n];
            }
        }
    }
    let mut point = vec![
        Field::new("displacement", 3, displacement),
        Field::new("stress", 6, node_stress),
        Field::new("von_mises", 1, node_vm),
    ];
    let mut cell = vec![Field::new("stress", 6, cell_stress), Field::new("von_mises", 1, cell_vm)];
    for (j, name) in names.iter().enumerate() {
        point.push(Field::new(*name, 1, node_mat[j].clone()));
        cell.push(Field::new(*name, 1, (0..n_cells).map(|c| cell_mat[c * nm + j]).collect()));
    }
    if model.kinematics == Kinematics::Axisymmetric {
        // ParaView users expect a note on the components: r, z, theta.
        for f in point.iter_mut().chain(cell.iter_mut()) {
            if f.name == "stress" {
                f.name = "stress_rr_zz_tt_rz".into();
            }
        }
    }
    (point, cell)
}
