//! Materials and sections: each section's volume group gets element sets (one per cell block)
//! with its material.

use crate::case::{LoadedCase, MaterialSpec, QuadratureSpec};
use crate::error::Result;
use std::collections::BTreeMap;
use std::sync::Arc;
use stiction_core::element::Kinematics;
use stiction_core::material::Material;
use stiction_core::mesh::Mesh;
use stiction_core::model::{ElementSet, Model};
use stiction_elements::{QuadratureChoice, SolidKernel};
use stiction_materials::{J2Plasticity, LinearElastic};

fn material(case: &LoadedCase, name: &str, spec: &MaterialSpec) -> Result<Arc<dyn Material>> {
    if spec.tangent_hardening != 0.0 && spec.model != "j2-plasticity" {
        return Err(case.error(
            format!("materials.{name}.tangent_hardening"),
            format!("applies to model 'j2-plasticity' only, not '{}'", spec.model),
        ));
    }
    Ok(match spec.model.as_str() {
        "linear-elastic" => Arc::new(LinearElastic::new(name, spec.youngs_modulus, spec.poissons_ratio)?),
        "j2-plasticity" => {
            let y = spec.yield_stress.ok_or_else(|| {
                case.error(format!("materials.{name}.yield_stress"), "required for model 'j2-plasticity'")
            })?;
            Arc::new(
                J2Plasticity::new(
                    name,
                    spec.youngs_modulus,
                    spec.poissons_ratio,
                    y,
                    spec.isotropic_hardening,
                    spec.kinematic_hardening,
                )?
                .with_tangent_hardening(spec.tangent_hardening)?,
            )
        }
        other => {
            return Err(case.error(
                format!("materials.{name}.model"),
                format!("unknown material model '{other}' (known: linear-elastic, j2-plasticity)"),
            ));
        }
    })
}

/// The case's materials by name.
pub fn materials(case: &LoadedCase) -> Result<BTreeMap<String, Arc<dyn Material>>> {
    case.case.materials.iter().map(|(name, spec)| Ok((name.clone(), material(case, name, spec)?))).collect()
}

/// Adds one element set per cell block of each section's group.
pub fn add_sections(
    case: &LoadedCase,
    mesh: &Mesh,
    kin: Kinematics,
    materials: &BTreeMap<String, Arc<dyn Material>>,
    model: &mut Model,
) -> Result<()> {
    let model_dim = if kin == Kinematics::Solid3D { 3 } else { 2 };
    if case.case.sections.is_empty() {
        return Err(case.error("sections", "at least one section (group + material) is needed"));
    }
    for (i, s) in case.case.sections.iter().enumerate() {
        let key = format!("sections[{i}]");
        let group = mesh.group(&s.group).map_err(|e| case.error(format!("{key}.group"), e.to_string()))?;
        if group.dim != model_dim {
            return Err(case.error(
                format!("{key}.group"),
                format!(
                    "group '{}' has dimension {}, a {} model needs a dimension-{model_dim} group",
                    s.group,
                    group.dim,
                    kin.name()
                ),
            ));
        }
        let mat = materials.get(&s.material).ok_or_else(|| {
            case.error(
                format!("{key}.material"),
                format!(
                    "no material '{}' (defined: {})",
                    s.material,
                    materials.keys().cloned().collect::<Vec<_>>().join(", ")
                ),
            )
        })?;
        let choice = match s.quadrature {
            QuadratureSpec::Standard => QuadratureChoice::Standard,
            QuadratureSpec::High => QuadratureChoice::High,
        };
        let mut any = false;
        for block in mesh.blocks_of(group) {
            let kernel =
                SolidKernel::new(block.cell_type, kin, choice).map_err(|m| case.error(format!("{key}.group"), m))?;
            model.sets.push(ElementSet::new(
                s.group.clone(),
                Box::new(kernel),
                mat.clone(),
                block.connectivity.clone(),
            ));
            any = true;
        }
        if !any {
            return Err(case.error(format!("{key}.group"), format!("group '{}' has no cells", s.group)));
        }
    }
    Ok(())
}
