//! The footprint correction of discrete points on a mesh coarser than their footprints
//! (`points.footprint_correction`): each point's law in series with the footprint's own elastic
//! compliance and, where the case declares one, its limit force
//! ([`stiction_interfaces::local_footprint`]).
//!
//! The compliance, when not given, is computed per point as what the mesh misses
//! ([`stiction_interfaces::footprint_compliance`], which has the formulas).

use super::amplitudes::Amplitudes;
use crate::case::{FootprintCorrectionSpec, LimitPressure, LoadedCase, MaterialSpec, VON_MISES_DISC};
use crate::error::Result;
use std::collections::BTreeMap;
use std::sync::Arc;
use stiction_core::element::Kinematics;
use stiction_core::interface_law::InterfaceLaw;
use stiction_core::linear_solver::FaerCholesky;
use stiction_core::material::Material;
use stiction_core::mesh::Mesh;
use stiction_core::model::Model;
pub use stiction_interfaces::footprint_compliance::{CompliancesSet, ElasticFlexibility};
use stiction_interfaces::footprint_compliance::{FlexibilityError, FootprintBody};
use stiction_interfaces::local_footprint::{DISC_LIMIT_PRESSURE_OVER_YIELD, LocalFootprint, SeriesWithFootprint};
use stiction_interfaces::{DiscretePoint, RigidFlat};

/// The body's elastic flexibility for the footprint compliances
/// ([`stiction_interfaces::footprint_compliance::ElasticFlexibility`]): the body alone, its
/// sections and boundary conditions, its factor checked against the memory the run may use.
pub fn body_flexibility(
    case: &LoadedCase,
    mesh: &Arc<Mesh>,
    kin: Kinematics,
    materials: &BTreeMap<String, Arc<dyn Material>>,
    amplitudes: &Amplitudes,
) -> Result<ElasticFlexibility> {
    let mut model = Model::new(mesh.clone(), kin);
    super::sections::add_sections(case, mesh, kin, materials, &mut model)?;
    super::boundaries::add_boundaries(case, mesh, kin, amplitudes, &mut model)?;
    let fits = |solver: &FaerCholesky, dofs: usize| super::size::check_factor_fits(case, solver, dofs, 8);
    ElasticFlexibility::new(model, fits).map_err(|e| match e {
        FlexibilityError::Refused(e) => e,
        FlexibilityError::Core(e) => case.error(
            "interfaces.points.footprint_correction.compliance",
            format!("computing it needs the body's elastic stiffness, which failed ({e}); give the compliance instead"),
        ),
    })
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

/// Computes each point's compliance and sets it in the flat's states
/// ([`stiction_interfaces::footprint_compliance::set_compliances`]), with the body's one
/// material's elastic constants.
#[allow(clippy::too_many_arguments)]
pub fn set_compliances(
    case: &LoadedCase,
    key: &str,
    flat: &mut RigidFlat,
    on: (&Mesh, &str),
    discrete: &[DiscretePoint],
    area: f64,
    n_inner_state: usize,
    flexibility: &mut ElasticFlexibility,
) -> Result<CompliancesSet> {
    let material = body_material(case, &format!("{key}.compliance"))?;
    let body = FootprintBody { young: material.youngs_modulus, poisson: material.poissons_ratio, area };
    stiction_interfaces::footprint_compliance::set_compliances(flat, on, discrete, body, n_inner_state, flexibility)
        .map_err(|e| case.error(format!("{key}.compliance"), e.to_string()))
}
