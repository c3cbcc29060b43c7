//! The blockwise stiffness (symmetric tangents filled half and mirrored) against the force path:
//! for a linear material, sigma = C eps, the force of a unit displacement of dof j is column j
//! of the stiffness, exactly.

use super::*;
use stiction_core::material::MaterialError;

/// sigma = C eps with C chosen per point by its committed state: 0, a symmetric C; 1, one that
/// is not.
struct TwoTangents;

fn tangent(symmetric: bool) -> Tangent {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let base = if i == j { 5.0 } else { 1.0 / (1.0 + (i + j) as f64) };
            if symmetric || i <= j { base } else { base + 0.3 * (i as f64 - j as f64) }
        })
    })
}

impl Material for TwoTangents {
    fn name(&self) -> &str {
        "two-tangents"
    }
    fn n_state(&self) -> usize {
        1
    }
    fn update(
        &self,
        strain: &Strain,
        state_committed: &[f64],
        state_trial: &mut [f64],
        stress: &mut Stress,
        c: &mut Tangent,
    ) -> Result<(), MaterialError> {
        state_trial.copy_from_slice(state_committed);
        *c = tangent(state_committed[0] == 0.0);
        *stress = std::array::from_fn(|i| (0..6).map(|j| c[i][j] * strain[j]).sum());
        Ok(())
    }
    fn stiffness_scale(&self) -> f64 {
        5.0
    }
}

/// The reference nodes of `cell` moved to a distorted element (off the axis for axisymmetric
/// cells: r >= 1).
fn distorted_nodes(cell: CellType) -> Vec<[f64; 3]> {
    crate::shape::reference_nodes(cell)
        .iter()
        .map(|x| {
            [
                1.0 + x[0] + 0.2 * x[1] + 0.05 * x[1] * x[1],
                0.3 * x[0] + 1.1 * x[1] + 0.1 * x[2],
                0.1 * x[0] + 0.9 * x[2],
            ]
        })
        .collect()
}

/// Every cell type the solid kernel takes, with its kinematics.
const EVERY_CELL: [(CellType, Kinematics); 4] = [
    (CellType::Tet4, Kinematics::Solid3D),
    (CellType::Tet10, Kinematics::Solid3D),
    (CellType::Tri3, Kinematics::Axisymmetric),
    (CellType::Tri6, Kinematics::Axisymmetric),
];

#[test]
fn stiffness_columns_are_the_forces_of_unit_displacements() {
    for (cell, kinematics) in EVERY_CELL {
        let kernel = SolidKernel::new(cell, kinematics, QuadratureChoice::Standard).unwrap();
        let coords = distorted_nodes(cell);
        let (nd, nq) = (kernel.n_dofs(), kernel.n_points());
        // every point symmetric, none, and alternating (both kinds in one element)
        let patterns: [Vec<f64>; 3] = [vec![0.0; nq], vec![1.0; nq], (0..nq).map(|q| (q % 2) as f64).collect()];
        for committed in patterns {
            let mut trial = vec![0.0; nq];
            let mut stress = vec![[0.0; 6]; nq];
            let mut force = vec![0.0; nd];
            let mut k = vec![0.0; nd * nd];
            let u = vec![0.0; nd];
            let buffers = ElementBuffers { force: &mut force, stiffness: Some(&mut k), stress: &mut stress };
            kernel.evaluate(&coords, &u, &TwoTangents, &committed, &mut trial, buffers).unwrap();
            let largest = k.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            let mut worst = 0.0f64;
            for col in 0..nd {
                let mut unit = vec![0.0; nd];
                unit[col] = 1.0;
                let buffers = ElementBuffers { force: &mut force, stiffness: None, stress: &mut stress };
                kernel.evaluate(&coords, &unit, &TwoTangents, &committed, &mut trial, buffers).unwrap();
                for row in 0..nd {
                    worst = worst.max((k[row * nd + col] - force[row]).abs());
                }
            }
            assert!(largest > 1.0, "{cell:?}: an empty stiffness");
            assert!(worst < 1e-12 * largest, "{cell:?}, point kinds {committed:?}: {worst:e} against {largest:e}");
            let asymmetry = (0..nd)
                .flat_map(|i| (0..nd).map(move |j| (i, j)))
                .fold(0.0f64, |m, (i, j)| m.max((k[i * nd + j] - k[j * nd + i]).abs()));
            let any_unsymmetric = committed.contains(&1.0);
            assert_eq!(asymmetry > 1e-9 * largest, any_unsymmetric, "{cell:?}, {committed:?}: asymmetry {asymmetry:e}");
        }
    }
}

/// An element evaluated from its precomputed geometry ([`ElementKernel::geometry`]) gives the
/// force, stiffness, stresses and volume of the evaluation from its coordinates bit for bit
/// (the same numbers, stored once), for every cell type, both tangent kinds and a displacement
/// that strains every component; an inverted (mirrored) cell fails when its geometry is made,
/// as its evaluation does.
#[test]
fn an_element_evaluated_from_its_precomputed_geometry_is_the_one_evaluated_from_its_coordinates() {
    for (cell, kinematics) in EVERY_CELL {
        let kernel = SolidKernel::new(cell, kinematics, QuadratureChoice::Standard).unwrap();
        let coords = distorted_nodes(cell);
        let (nd, nq) = (kernel.n_dofs(), kernel.n_points());
        let mut geometry = vec![0.0; kernel.geometry_len()];
        kernel.geometry(&coords, &mut geometry).unwrap();
        let u: Vec<f64> = (0..nd).map(|i| 0.01 * ((i * 7 % 11) as f64 - 5.0)).collect();
        let committed: Vec<f64> = (0..nq).map(|q| (q % 2) as f64).collect();
        let evaluate = |precomputed: bool| {
            let (mut force, mut k, mut stress, mut trial) =
                (vec![0.0; nd], vec![0.0; nd * nd], vec![[0.0; 6]; nq], vec![0.0; nq]);
            let buffers = ElementBuffers { force: &mut force, stiffness: Some(&mut k), stress: &mut stress };
            let volume = if precomputed {
                kernel.evaluate_on_geometry(&geometry, &coords, &u, &TwoTangents, &committed, &mut trial, buffers)
            } else {
                kernel.evaluate(&coords, &u, &TwoTangents, &committed, &mut trial, buffers)
            }
            .unwrap();
            (volume, force, k, stress)
        };
        let (from_coordinates, from_geometry) = (evaluate(false), evaluate(true));
        assert!(from_coordinates.1.iter().any(|f| f.abs() > 1e-3), "{cell:?}: no force to compare");
        assert_eq!(from_coordinates, from_geometry, "{cell:?}");
        // mirrored in z (y in the r-z plane): every point's Jacobian determinant changes sign
        let inverted: Vec<[f64; 3]> = coords.iter().map(|x| [x[0], -x[1], x[2]]).collect();
        let failure = kernel.geometry(&inverted, &mut geometry).unwrap_err();
        assert!(matches!(failure, ElementFailure::BadJacobian { .. }), "{cell:?}: {failure:?}");
    }
}
