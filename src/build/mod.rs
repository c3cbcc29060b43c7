//! Turns a case into a core model, one concern per file: the mesh ([`mesh`]), materials and
//! sections ([`sections`]), amplitudes, boundary conditions ([`boundaries`]) and distributed
//! loads ([`loads`]), interfaces and point layouts ([`interfaces`], [`points`]), and the steps
//! ([`steps`]), and whether the model fits in memory ([`size`]). Each reports errors naming the case key.

mod amplitudes;
pub mod boundaries;
pub mod footprint_correction;
pub mod interfaces;
pub mod loads;
pub mod mesh;
pub mod points;
pub mod sections;
pub mod size;
pub mod steps;

pub use mesh::load_mesh;
pub use points::write_points_csv;

use crate::case::{Analysis, LoadedCase};
use crate::error::{Result, StictionError};
use std::path::PathBuf;
use std::sync::Arc;
use stiction_core::element::Kinematics;
use stiction_core::mesh::Mesh;
use stiction_core::model::Model;
use stiction_core::nonlinear::NewtonSettings;
use stiction_core::path::StepPlan;
use stiction_core::record::interface_tracker::InterfaceInfo;

/// A model ready to run, with what the driver needs and reports on.
pub struct BuiltModel {
    pub model: Model,
    /// Groups whose reactions go to `history.csv` (name, nodes).
    pub reaction_groups: Vec<(String, Vec<usize>)>,
    /// Loaded groups whose mean displacement goes to `history.csv` (name, nodes).
    pub load_groups: Vec<(String, Vec<usize>)>,
    /// Discrete point layouts per interface name (written to the output as CSV).
    pub layouts: Vec<(String, Vec<stiction_interfaces::DiscretePoint>)>,
    /// The footprint compliances computed by interfaces with a footprint correction.
    pub footprint_compliances: Vec<footprint_correction::CompliancesSet>,
    pub mesh_path: PathBuf,
    /// The steps as the driver runs them.
    pub steps: Vec<StepPlan>,
    pub newton: NewtonSettings,
    /// Per contribution of the model: kind and viscous-share limit.
    pub interfaces: Vec<InterfaceInfo>,
}

/// Builds the model of a case.
pub fn build(case: &LoadedCase) -> Result<BuiltModel> {
    let (mesh, mesh_path) = load_mesh(case)?;
    build_with_mesh(case, mesh, mesh_path)
}

/// Builds the model of a case on an already loaded mesh.
pub fn build_with_mesh(case: &LoadedCase, mesh: Mesh, mesh_path: PathBuf) -> Result<BuiltModel> {
    let kin = match case.case.analysis {
        Analysis::ThreeD => Kinematics::Solid3D,
        Analysis::Axisymmetric => Kinematics::Axisymmetric,
    };
    if kin == Kinematics::Axisymmetric {
        mesh::check_axisymmetric(case, &mesh)?;
    }
    size::check_model_fits(case, &mesh)?;
    let (mesh, splits) = interfaces::split_for_cohesive(case, mesh)?;
    let mesh = Arc::new(mesh);
    let mut model = Model::new(mesh.clone(), kin);
    let materials = sections::materials(case)?;
    sections::add_sections(case, &mesh, kin, &materials, &mut model)?;
    let amplitudes = amplitudes::Amplitudes::new(case)?;
    let reaction_groups = boundaries::add_boundaries(case, &mesh, kin, &amplitudes, &mut model)?;
    let load_groups = loads::add_loads(case, &mesh, kin, &amplitudes, &mut model)?;
    let computes_compliance = case.case.interfaces.iter().any(|i| {
        i.points.as_ref().and_then(|p| p.footprint_correction.as_ref()).is_some_and(|c| c.compliance.is_none())
    });
    let flexibility = if computes_compliance {
        Some(std::cell::RefCell::new(footprint_correction::body_flexibility(
            case,
            &mesh,
            kin,
            &materials,
            &amplitudes,
        )?))
    } else {
        None
    };
    let context = interfaces::InterfaceContext {
        mesh: &mesh,
        kin,
        amplitudes: &amplitudes,
        splits: &splits,
        modulus: materials.values().map(|m| m.stiffness_scale()).fold(0.0, f64::max),
        flexibility: flexibility.as_ref(),
    };
    let built_interfaces = interfaces::build_interfaces(case, &context)?;
    model.contributions = built_interfaces.contributions;
    model.finalize().map_err(|e| StictionError::Case { path: case.path.clone(), message: e.to_string() })?;
    let interfaces = model
        .contributions
        .iter()
        .map(|c| {
            let spec = case.case.interfaces.iter().find(|i| i.name == c.name());
            InterfaceInfo {
                kind: spec.map_or_else(String::new, |i| i.kind.clone()),
                max_viscous_share: spec
                    .map_or(crate::case::InterfaceSpec::default_max_viscous_share(), |i| i.max_viscous_share),
            }
        })
        .collect();
    Ok(BuiltModel {
        steps: steps::step_plans(case, &model),
        newton: steps::newton_settings(case),
        interfaces,
        model,
        reaction_groups,
        load_groups,
        layouts: built_interfaces.layouts,
        footprint_compliances: built_interfaces.footprint_compliances,
        mesh_path,
    })
}
