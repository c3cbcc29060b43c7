//! Interfaces: zero-thickness cohesive elements on interior surfaces (the mesh is split first)
//! and rigid flats against a body surface or at discrete points; each with its interface law.

use super::footprint_correction;
use super::mesh::mean_edge_length;
use super::points::discrete_points;
use crate::case::{InterfaceSpec, LoadedCase};
use crate::error::Result;
use crate::laws::{LawContext, LawRegistry, make_law};
use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::Arc;
use stiction_core::element::Kinematics;
use stiction_core::interface_law::InterfaceLaw;
use stiction_core::mesh::Mesh;
use stiction_core::model::Contribution;
use stiction_elements::BoundaryFinder;
use stiction_interfaces::DiscretePoint;

use super::amplitudes::Amplitudes;

/// A cohesive interface's split: its index in the case, the mesh before the split and the
/// duplicated node pairs.
pub struct Split {
    pub interface: usize,
    pub original: Mesh,
    pub pairs: HashMap<usize, usize>,
}

/// Splits `mesh` along the surfaces of the case's cohesive interfaces (duplicating their nodes
/// for the cells of `side`). A surface already split by an earlier cohesive interface (same
/// side, no split list of its own) shares that split, e.g. contact on a pre-crack next to a
/// cohesive ligament.
pub fn split_for_cohesive(case: &LoadedCase, mut mesh: Mesh) -> Result<(Mesh, Vec<Split>)> {
    let c = &case.case;
    let mut splits: Vec<Split> = Vec::new();
    for (i, spec) in c.interfaces.iter().enumerate().filter(|(_, s)| s.kind == "cohesive") {
        let key = format!("interfaces[{i}]");
        let side = spec.side.as_deref().ok_or_else(|| {
            case.error(
                format!("{key}.side"),
                "required for type 'cohesive': the volume group that gets the duplicated nodes",
            )
        })?;
        let earlier = splits.iter().find(|s| {
            let other: &InterfaceSpec = &c.interfaces[s.interface];
            let other_surfaces = other.split.clone().unwrap_or_else(|| vec![other.surface.clone()]);
            spec.split.is_none() && other.side.as_deref() == Some(side) && other_surfaces.contains(&spec.surface)
        });
        if let Some(s) = earlier {
            let shared = Split { interface: i, original: s.original.clone(), pairs: s.pairs.clone() };
            splits.push(shared);
            continue;
        }
        let surfaces = spec.split.clone().unwrap_or_else(|| vec![spec.surface.clone()]);
        if !surfaces.contains(&spec.surface) {
            return Err(
                case.error(format!("{key}.split"), format!("must include the cohesive surface '{}'", spec.surface))
            );
        }
        let split = stiction_interfaces::mesh_split::split_mesh(&mesh, &surfaces, side)
            .map_err(|e| case.error(&key, e.to_string()))?;
        let original = std::mem::replace(&mut mesh, split.mesh);
        splits.push(Split { interface: i, original, pairs: split.pairs });
    }
    Ok((mesh, splits))
}

/// What every interface of a case is built with.
pub struct InterfaceContext<'a> {
    pub mesh: &'a Arc<Mesh>,
    pub kin: Kinematics,
    pub amplitudes: &'a Amplitudes,
    pub splits: &'a [Split],
    /// Largest stiffness scale of the materials (penalty defaults).
    pub modulus: f64,
    /// The body's factored elastic stiffness, when a footprint correction computes its
    /// compliance.
    pub flexibility: Option<&'a std::cell::RefCell<super::footprint_correction::ElasticFlexibility>>,
}

/// What the interfaces of a case are built into.
#[derive(Default)]
pub struct BuiltInterfaces {
    pub contributions: Vec<Box<dyn Contribution>>,
    /// Discrete point layouts by interface name.
    pub layouts: Vec<(String, Vec<DiscretePoint>)>,
    /// The footprint compliances computed (interfaces with `points.footprint_correction`).
    pub footprint_compliances: Vec<footprint_correction::CompliancesSet>,
}

/// The contributions of the case's interfaces, and the discrete point layouts by interface.
pub fn build_interfaces(case: &LoadedCase, ctx: &InterfaceContext<'_>) -> Result<BuiltInterfaces> {
    let c = &case.case;
    let plugin_dirs: Vec<PathBuf> = c.plugin_path.iter().map(|p| case.base_dir().join(p)).collect();
    let registry = LawRegistry::new(&plugin_dirs);
    let mut built = BuiltInterfaces::default();
    let mut laws = Vec::new();
    for (i, spec) in c.interfaces.iter().enumerate() {
        let key = format!("interfaces[{i}]");
        if spec.kind != "rigid-flat" && spec.kind != "cohesive" {
            return Err(case.error(
                format!("{key}.type"),
                format!("unknown interface type '{}' (known: rigid-flat, cohesive)", spec.kind),
            ));
        }
        let group = ctx.mesh.group(&spec.surface).map_err(|e| case.error(format!("{key}.surface"), e.to_string()))?;
        let face_size = mean_edge_length(ctx.mesh, group)
            .ok_or_else(|| case.error(format!("{key}.surface"), format!("group '{}' has no faces", spec.surface)))?;
        let given: Vec<(String, f64)> = spec.parameters.iter().map(|(k, v)| (k.clone(), *v)).collect();
        let config_file = spec.config_file.as_ref().map(|f| case.base_dir().join(f));
        let law_context = LawContext { modulus: ctx.modulus, face_size };
        let law = make_law(&registry, &spec.law, case.base_dir(), &given, config_file.as_deref(), &law_context)
            .map_err(|m| case.error(format!("{key}.law"), m))?;
        laws.push(law.clone());
        if spec.kind == "cohesive" {
            built.contributions.push(cohesive(case, &key, i, spec, ctx, law, face_size)?);
        } else {
            let (flat, layout, compliances) = rigid_flat(case, &key, spec, ctx, law)?;
            built.contributions.push(flat);
            built.layouts.extend(layout.map(|l| (spec.name.clone(), l)));
            built.footprint_compliances.extend(compliances);
        }
    }
    let dissipation = c.solver.continuation == crate::case::ContinuationSpec::Dissipation;
    if dissipation && !laws.iter().any(|l| stiction_interfaces::damage_dissipation::damages_secantly(l.as_ref())) {
        let names: Vec<&str> = laws.iter().map(|l| l.name()).collect();
        return Err(case.error(
            "solver.continuation",
            format!(
                "\"dissipation\" follows the energy that damage dissipates, but no interface law damages (laws: {}; a damage law declares a state named 'damage' and unloads secantly, as cohesive-zone does): use \"arc-length\"",
                if names.is_empty() { "none".to_string() } else { names.join(", ") }
            ),
        ));
    }
    Ok(built)
}

/// Zero-thickness cohesive elements of interface `i` on its split.
fn cohesive(
    case: &LoadedCase,
    key: &str,
    i: usize,
    spec: &InterfaceSpec,
    ctx: &InterfaceContext<'_>,
    law: Arc<dyn InterfaceLaw>,
    face_size: f64,
) -> Result<Box<dyn Contribution>> {
    let mesh = ctx.mesh;
    let split = ctx.splits.iter().find(|s| s.interface == i).expect("every cohesive interface was split");
    let side = mesh
        .group(spec.side.as_deref().unwrap_or_default())
        .map_err(|e| case.error(format!("{key}.side"), e.to_string()))?;
    let finder =
        BoundaryFinder::new(&mesh.nodes, mesh.blocks_of(side).flat_map(|b| b.cells().map(move |c| (b.cell_type, c))));
    let nc = mesh.blocks_of(side).next().and_then(|b| b.cell_type.facet()).map(|f| f.n_corners()).unwrap_or(3);
    if law.gap_dimension() == 3 && spec.shear_stiffness.is_some() {
        return Err(case.error(
            format!("{key}.shear_stiffness"),
            format!(
                "law '{}' is mixed mode and resists slip itself; shear_stiffness applies to normal-only laws",
                law.name()
            ),
        ));
    }
    let shear = spec.shear_stiffness.unwrap_or(100.0 * ctx.modulus / face_size);
    if !(shear >= 0.0 && shear.is_finite()) {
        return Err(case.error(format!("{key}.shear_stiffness"), "must be a finite number >= 0"));
    }
    let elements = stiction_interfaces::cohesive::CohesiveElements::new(
        &spec.name,
        &split.original,
        &spec.surface,
        &split.pairs,
        |b| finder.cell_centroid(&b[..nc]),
        ctx.kin,
        law,
        shear,
        spec.quadrature_order,
    )
    .map_err(|e| case.error(key, e.to_string()))?;
    Ok(Box::new(elements))
}

/// A rigid flat against the interface's surface, or at its discrete points (returned too, with
/// the footprint compliances computed for them).
fn rigid_flat(
    case: &LoadedCase,
    key: &str,
    spec: &InterfaceSpec,
    ctx: &InterfaceContext<'_>,
    law: Arc<dyn InterfaceLaw>,
) -> Result<FlatAndLayout> {
    let dpn = ctx.kin.dofs_per_node();
    let normal = match (&spec.normal, ctx.kin) {
        (None, Kinematics::Solid3D) => [0.0, 0.0, 1.0],
        (None, Kinematics::Axisymmetric) => [0.0, 1.0, 0.0],
        (Some(v), _) if v.len() == dpn => [v[0], v[1], if dpn == 3 { v[2] } else { 0.0 }],
        (Some(_), _) => return Err(case.error(format!("{key}.normal"), format!("needs {dpn} components"))),
    };
    if spec.viscosity > 0.0 && case.case.solver.continuation != crate::case::ContinuationSpec::None {
        return Err(case.error(
            format!("{key}.viscosity"),
            "a viscous regularisation cannot be combined with solver.continuation = \"arc-length\" or \"dissipation\" (the viscous term needs time to move forward; path following may turn it back): use one of them",
        ));
    }
    let flat_spec = stiction_interfaces::RigidFlatSpec {
        name: spec.name.clone(),
        surface: spec.surface.clone(),
        normal,
        approach_scale: spec.approach,
        approach_amplitude: ctx.amplitudes.get(case, format!("{key}.amplitude"), &spec.amplitude)?,
        initial_gap: spec.initial_gap,
        extra_order: spec.quadrature_order,
        viscosity: spec.viscosity,
        resistance: match &spec.resistance {
            None => None,
            Some(r) => {
                let metre = crate::case::metres_per_length_unit(case, &format!("{key}.resistance"))?;
                Some(stiction_interfaces::contact_resistance::ResistanceModel {
                    resistivity: r.resistivity / metre,
                    mean_free_path: r.mean_free_path,
                    film_specific_resistance: r.film_specific_resistance / (metre * metre),
                    counter_resistivity: r.counter_resistivity.unwrap_or(r.resistivity) / metre,
                    counter_mean_free_path: r.counter_mean_free_path.unwrap_or(r.mean_free_path),
                })
            }
        },
    };
    let (flat, layout, compliances) = match &spec.points {
        None => (stiction_interfaces::RigidFlat::over_surface(ctx.mesh, ctx.kin, flat_spec, law), None, None),
        Some(points) => {
            let (list, source) = discrete_points(case, &format!("{key}.points"), points)?;
            let correction_key = format!("{key}.points.footprint_correction");
            let n_inner_state = law.n_state();
            let law = match &points.footprint_correction {
                None => law,
                Some(c) => {
                    let limit = footprint_correction::limit_force(case, &correction_key, c, points.footprint_area)?;
                    eprintln!(
                        "interface '{}': footprint limit force: {}",
                        spec.name,
                        limit.map_or("none (the footprint is elastic: compliance only)".to_string(), |f| format!(
                            "{f:.4}{} (declared by {correction_key}.{})",
                            case.case.units.as_ref().map_or(String::new(), |u| format!(" {}", u.force)),
                            if c.limit_force.is_some() { "limit_force" } else { "limit_pressure" }
                        ))
                    );
                    footprint_correction::corrected_law(case, &correction_key, c, limit, law)?
                }
            };
            let mut flat = stiction_interfaces::RigidFlat::at_points(
                ctx.mesh,
                ctx.kin,
                flat_spec,
                law,
                &list,
                &source,
                points.footprint_area,
            )
            .map_err(|e| case.error(key, e.to_string()))?;
            per_point_radii(&mut flat, &list, spec);
            let computed = points.footprint_correction.as_ref().is_some_and(|c| c.compliance.is_none());
            let mut compliances = None;
            if let (true, Some(flexibility)) = (computed, ctx.flexibility) {
                let set = footprint_correction::set_compliances(
                    case,
                    &correction_key,
                    &mut flat,
                    (ctx.mesh, &spec.surface),
                    &list,
                    points.footprint_area,
                    n_inner_state,
                    &mut flexibility.borrow_mut(),
                )?;
                eprintln!(
                    "interface '{}': footprint compliance (length per force): the mesh gives {:.3e}, the correction adds {:.3e} (min {:.3e}, max {:.3e}; medians over the points)",
                    spec.name, set.mesh_median, set.median, set.min, set.max
                );
                compliances = Some(set);
            }
            (Ok(flat), Some(list), compliances)
        }
    };
    Ok((Box::new(flat.map_err(|e| case.error(key, e.to_string()))?), layout, compliances))
}

/// Gives each point its layout's radius (a height map's summit) where the law keeps a
/// per-point radius; says so where it keeps none.
fn per_point_radii(flat: &mut stiction_interfaces::RigidFlat, list: &[DiscretePoint], spec: &InterfaceSpec) {
    if list.iter().all(|p| p.radius.is_none()) {
        return;
    }
    match flat.state_index(stiction_interfaces::point_placement::RADIUS_STATE) {
        Some(k) => flat.set_point_states(|i, state| {
            if let Some(r) = list[i].radius {
                state[k] = r;
            }
        }),
        None => eprintln!(
            "interface '{}': law '{}' keeps no per-point radius (a state named '{}'): the layout's radii are written to the points file but not used",
            spec.name,
            spec.law,
            stiction_interfaces::point_placement::RADIUS_STATE
        ),
    }
}

type FlatAndLayout = (Box<dyn Contribution>, Option<Vec<DiscretePoint>>, Option<footprint_correction::CompliancesSet>);
