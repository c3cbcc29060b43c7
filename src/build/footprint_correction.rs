//! The footprint correction of discrete points on a mesh coarser than their footprints
//! (`points.footprint_correction`): each point's law in series with the footprint's own elastic
//! compliance and, where the case declares one, its limit force
//! ([`stiction_interfaces::local_footprint`]).
//!
//! The compliance, when not given, is computed per point as what the mesh misses:
//!   c_i = K / a - c_h(a) + (w_b . K_h^-1 w_a - u_b),   K = 16 (1 - nu^2) / (3 pi^2 E),
//! with a the footprint's radius, w_a its node weights times the normal (the uniform load
//! over the footprint), c_h(a) = w_a . K_h^-1 w_a the mesh's compliance for it (K_h the
//! body's elastic stiffness with its boundary conditions, factored once), and w_b the weights
//! of a concentric disc of radius b that the mesh resolves (three face edges, at least three
//! footprint radii). On a half-space the footprint's compliance is K / a exactly (Johnson,
//! Contact Mechanics, 3.4); a finite body adds its global compliance, which the bracket
//! measures: by reciprocity w_b . K_h^-1 w_a is the mean over the footprint of the mesh's
//! displacement under the resolved disc b of unit force, and on a half-space that mean is
//!   u_b = 2 (1 - nu^2) / (pi E b) (1 - a^2 / (8 b^2) - a^4 / (64 b^4))
//! (the disc's displacement 4 (1 - nu^2) p b E(r / b) / (pi E), E the complete elliptic
//! integral, averaged over r < a). One solve per point (in blocks of 32 right-hand sides);
//! c_i tends to zero as the mesh resolves the footprint.

use super::amplitudes::Amplitudes;
use crate::case::{FootprintCorrectionSpec, LimitPressure, LoadedCase, MaterialSpec, VON_MISES_DISC};
use crate::error::Result;
use std::collections::BTreeMap;
use std::sync::Arc;
use stiction_core::element::Kinematics;
use stiction_core::interface_law::InterfaceLaw;
use stiction_core::linear_solver::{FaerCholesky, LinearSolver};
use stiction_core::material::Material;
use stiction_core::mesh::Mesh;
use stiction_core::model::{Contribution, Model};
use stiction_interfaces::local_footprint::{
    DISC_LIMIT_PRESSURE_OVER_YIELD, LocalFootprint, SeriesWithFootprint, compliance_state_index, disc_compliance,
};
use stiction_interfaces::point_placement::place_points;
use stiction_interfaces::{DiscretePoint, RigidFlat};

/// The body's elastic stiffness at rest with its boundary conditions, factored once: the
/// compliance of any load pattern by one solve.
pub struct ElasticFlexibility {
    model: Model,
    solver: FaerCholesky,
    free_index: Vec<usize>,
}

impl ElasticFlexibility {
    /// The body alone: its sections and boundary conditions, no interfaces.
    pub fn new(
        case: &LoadedCase,
        mesh: &Arc<Mesh>,
        kin: Kinematics,
        materials: &BTreeMap<String, Arc<dyn Material>>,
        amplitudes: &Amplitudes,
    ) -> Result<Self> {
        let mut model = Model::new(mesh.clone(), kin);
        super::sections::add_sections(case, mesh, kin, materials, &mut model)?;
        super::boundaries::add_boundaries(case, mesh, kin, amplitudes, &mut model)?;
        let failed = |e: stiction_core::CoreError| {
            case.error(
                "interfaces.points.footprint_correction.compliance",
                format!(
                    "computing it needs the body's elastic stiffness, which failed ({e}); give the compliance instead"
                ),
            )
        };
        model.finalize().map_err(failed)?;
        model.apply_time(0.0);
        model.assemble(true).map_err(failed)?;
        let mut solver = FaerCholesky::analyse(model.pattern()).map_err(failed)?;
        super::size::check_factor_fits(case, &solver, model.free_dofs().len(), 8)?;
        solver.factorize(model.pattern(), &model.tangent_values).map_err(|e| {
            failed(stiction_core::CoreError::Invalid(format!(
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
    ) -> std::result::Result<Vec<(f64, f64)>, stiction_core::CoreError> {
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

/// The one material of the body's sections, for the automatic values.
fn body_material<'a>(case: &'a LoadedCase, key: &str) -> Result<&'a MaterialSpec> {
    let mut used: Vec<&String> = case.case.sections.iter().map(|s| &s.material).collect();
    used.sort();
    used.dedup();
    match used[..] {
        [name] => case.case.materials.get(name).ok_or_else(|| case.error(key, format!("no material '{name}'"))),
        _ => Err(case.error(
            key,
            format!(
                "the body has {} materials ({}): give this value explicitly",
                used.len(),
                used.iter().map(|s| s.as_str()).collect::<Vec<_>>().join(", ")
            ),
        )),
    }
}

/// `law` in series with the footprint; the compliance, if not given, starts at 0 and is set
/// per point by [`set_compliances`]. The footprint carries any force unless the case declares
/// a limit (`limit`, from [`limit_force`]).
pub fn corrected_law(
    case: &LoadedCase,
    key: &str,
    spec: &FootprintCorrectionSpec,
    limit: Option<f64>,
    law: Arc<dyn InterfaceLaw>,
) -> Result<Arc<dyn InterfaceLaw>> {
    let local =
        LocalFootprint { compliance: spec.compliance.unwrap_or(0.0), limit_force: limit.unwrap_or(f64::INFINITY) };
    Ok(Arc::new(SeriesWithFootprint::new(law, local).map_err(|m| case.error(key, m))?))
}

/// The footprint's limit force where the case declares one: `limit_force`, or `limit_pressure`
/// times the footprint's area, the named "von-mises-disc" pressure being 2.99 Y of the body's
/// perfectly plastic material.
pub fn limit_force(case: &LoadedCase, key: &str, spec: &FootprintCorrectionSpec, area: f64) -> Result<Option<f64>> {
    let pressure = match &spec.limit_pressure {
        None => return Ok(spec.limit_force),
        Some(LimitPressure::Value(p)) => *p,
        Some(LimitPressure::Named(_)) => {
            let key = format!("{key}.limit_pressure");
            let material = body_material(case, &key)?;
            if material.isotropic_hardening != 0.0 || material.kinematic_hardening != 0.0 {
                return Err(case.error(
                    key,
                    format!("\"{VON_MISES_DISC}\" is the limit of a perfectly plastic body and the body's material hardens: give the limit's value (limit_pressure = a number, or limit_force)"),
                ));
            }
            match (material.model.as_str(), material.yield_stress) {
                ("j2-plasticity", Some(y)) => DISC_LIMIT_PRESSURE_OVER_YIELD * y,
                _ => {
                    return Err(case.error(
                        key,
                        format!("\"{VON_MISES_DISC}\" needs a body that yields (model = \"j2-plasticity\" with yield_stress): give the limit's value instead"),
                    ));
                }
            }
        }
    };
    Ok(Some(pressure * area))
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

/// Computes each point's compliance (module documentation) and sets it in the flat's states.
#[allow(clippy::too_many_arguments)]
pub fn set_compliances(
    case: &LoadedCase,
    key: &str,
    flat: &mut RigidFlat,
    (mesh, surface): (&Mesh, &str),
    discrete: &[DiscretePoint],
    area: f64,
    n_inner_state: usize,
    flexibility: &mut ElasticFlexibility,
) -> Result<CompliancesSet> {
    let material = body_material(case, &format!("{key}.compliance"))?;
    let (young, poisson) = (material.youngs_modulus, material.poissons_ratio);
    let radius = (area / std::f64::consts::PI).sqrt();
    let normal = flat.normal();
    let error = |e: stiction_core::CoreError| case.error(format!("{key}.compliance"), e.to_string());
    let small: Vec<(&[usize], &[f64])> = flat.point_weights().map(|(n, w, _)| (n, w)).collect();
    // a disc the mesh resolves: three face edges (edge ~ 1.52 sqrt(corner area)), >= 3 radii
    let big_radius: Vec<f64> =
        flat.point_weights().map(|(.., face_area)| (3.0 * 1.52 * face_area.sqrt()).max(3.0 * radius)).collect();
    let (big, _) = place_points(mesh, flat.name(), surface, normal, discrete, "the points", |i| {
        std::f64::consts::PI * big_radius[i].powi(2)
    })
    .map_err(error)?;
    let mut compliances = Vec::with_capacity(small.len());
    let mut mesh_compliances = Vec::with_capacity(small.len());
    // the solves in blocks of right-hand sides
    for block in (0..small.len()).collect::<Vec<_>>().chunks(32) {
        let loads: Vec<(&[usize], &[f64])> = block.iter().map(|&i| small[i]).collect();
        let partners: Vec<(&[usize], &[f64])> =
            block.iter().map(|&i| (&big[i].nodes[..], &big[i].weights[..])).collect();
        let results = flexibility.compliances(&loads, &partners, normal).map_err(error)?;
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
