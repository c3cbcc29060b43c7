//! Turns a case into a core model: mesh, element sets with materials, amplitudes, boundary
//! conditions and distributed loads.

use crate::case::{Analysis, LoadedCase, MaterialSpec, QuadratureSpec};
use crate::error::{Result, StictionError};
use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::Arc;
use stiction_core::amplitude::Amplitude;
use stiction_core::element::Kinematics;
use stiction_core::material::Material;
use stiction_core::mesh::Mesh;
use stiction_core::model::{ElementSet, ExternalLoad, Model, Prescribed};
use stiction_elements::{BoundaryFinder, FaceIntegrator, QuadratureChoice, SolidKernel};
use stiction_materials::{J2Plasticity, LinearElastic};
use stiction_meshes::{GeoOptions, mesh_geo, read_msh};

/// A model ready to run, with what the driver reports on.
pub struct BuiltModel {
    pub model: Model,
    /// Groups whose reactions go to `history.csv` (name, nodes).
    pub reaction_groups: Vec<(String, Vec<usize>)>,
    /// Discrete point layouts per interface name (written to the output as CSV).
    pub layouts: Vec<(String, Vec<stiction_interfaces::DiscretePoint>)>,
    pub mesh_path: PathBuf,
}

/// The discrete points of an interface: read from `file`, or generated.
fn discrete_points(
    case: &LoadedCase,
    key: &str,
    spec: &crate::case::PointsSpec,
) -> Result<(Vec<stiction_interfaces::DiscretePoint>, String)> {
    use stiction_interfaces::DiscretePoint;
    if let Some(file) = &spec.file {
        let path = case.base_dir().join(file);
        let text = std::fs::read_to_string(&path)
            .map_err(|e| case.error(format!("{key}.file"), format!("cannot read '{}': {e}", path.display())))?;
        let bad = |line: usize, m: String| {
            case.error(format!("{key}.file"), format!("'{}' line {line}: {m}", path.display()))
        };
        let mut lines =
            text.lines().enumerate().filter(|(_, l)| !l.trim().is_empty() && !l.trim_start().starts_with('#'));
        let (hl, header) = lines.next().ok_or_else(|| bad(1, "empty file".into()))?;
        if header.split(',').map(str::trim).collect::<Vec<_>>() != ["x", "y", "height"] {
            return Err(bad(hl + 1, format!("expected the header 'x,y,height', found '{header}'")));
        }
        let mut points = Vec::new();
        for (i, l) in lines {
            let v: Vec<f64> = l
                .split(',')
                .map(|x| x.trim().parse::<f64>())
                .collect::<std::result::Result<_, _>>()
                .map_err(|_| bad(i + 1, format!("expected three numbers, found '{l}'")))?;
            if v.len() != 3 {
                return Err(bad(i + 1, format!("expected three numbers, found '{l}'")));
            }
            points.push(DiscretePoint { in_plane: [v[0], v[1]], height: v[2] });
        }
        if points.is_empty() {
            return Err(bad(hl + 1, "no points".into()));
        }
        return Ok((points, format!("'{}'", path.display())));
    }
    let need = |v: Option<f64>, k: &str| {
        v.ok_or_else(|| case.error(format!("{key}.{k}"), "required to generate points (or give 'file')"))
    };
    let layout = stiction_interfaces::asperity_layout::LayoutSpec {
        density: need(spec.density, "density")?,
        region_radius: need(spec.region_radius, "region_radius")?,
        min_spacing: spec.min_spacing,
        height: need(spec.height, "height")?,
        height_std: spec.height_std,
        seed: spec.seed,
    };
    let placed = stiction_interfaces::asperity_layout::generate(&layout).map_err(|m| case.error(key, m))?;
    let points = placed.iter().map(|p| DiscretePoint { in_plane: p.in_plane, height: p.height }).collect();
    Ok((points, format!("the generated layout (seed {})", spec.seed)))
}

/// Writes discrete points as a CSV that a case can read back with `points.file`.
pub fn write_points_csv(path: &std::path::Path, points: &[stiction_interfaces::DiscretePoint]) -> std::io::Result<()> {
    let mut text = String::from("x,y,height\n");
    for p in points {
        text.push_str(&format!("{:.9},{:.9},{:.9}\n", p.in_plane[0], p.in_plane[1], p.height));
    }
    std::fs::write(path, text)
}

/// Mean corner-to-corner edge length of the faces of a group (None if it has none).
fn mean_edge_length(mesh: &Mesh, group: &stiction_core::mesh::PhysicalGroup) -> Option<f64> {
    let (mut sum, mut count) = (0.0, 0usize);
    for block in mesh.blocks_of(group) {
        let nc = block.cell_type.n_corners();
        for face in block.cells() {
            for a in 0..nc {
                let (p, q) = (mesh.nodes[face[a]], mesh.nodes[face[(a + 1) % nc]]);
                sum += ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt();
                count += 1;
                if nc == 2 {
                    break;
                }
            }
        }
    }
    (count > 0).then(|| sum / count as f64)
}

/// Reads (or meshes) the case's mesh.
pub fn load_mesh(case: &LoadedCase) -> Result<(Mesh, PathBuf)> {
    let spec = &case.case.mesh;
    let base = case.base_dir();
    let path = match (&spec.file, &spec.geo) {
        (Some(file), None) => base.join(file),
        (None, Some(geo)) => {
            if !(spec.order == 1 || spec.order == 2) {
                return Err(case.error("mesh.order", format!("must be 1 or 2, got {}", spec.order)));
            }
            if !(spec.size_factor > 0.0) {
                return Err(case.error("mesh.size_factor", "must be positive"));
            }
            let geo = base.join(geo);
            let options = GeoOptions {
                dimension: if case.case.analysis == Analysis::Axisymmetric { 2 } else { 3 },
                order: spec.order,
                size_factor: spec.size_factor,
                parameters: spec.parameters.iter().map(|(k, v)| (k.clone(), *v)).collect(),
            };
            let cache = geo.parent().unwrap_or(base).join(".stiction-cache");
            mesh_geo(&geo, &options, &cache)?
        }
        _ => {
            return Err(case.error("mesh", "give exactly one of 'file' (a .msh) or 'geo' (a .geo meshed by gmsh)"));
        }
    };
    Ok((read_msh(&path)?, path))
}

fn material(case: &LoadedCase, name: &str, spec: &MaterialSpec) -> Result<Arc<dyn Material>> {
    Ok(match spec.model.as_str() {
        "linear-elastic" => Arc::new(LinearElastic::new(name, spec.youngs_modulus, spec.poissons_ratio)?),
        "j2-plasticity" => {
            let y = spec.yield_stress.ok_or_else(|| {
                case.error(format!("materials.{name}.yield_stress"), "required for model 'j2-plasticity'")
            })?;
            Arc::new(J2Plasticity::new(
                name,
                spec.youngs_modulus,
                spec.poissons_ratio,
                y,
                spec.isotropic_hardening,
                spec.kinematic_hardening,
            )?)
        }
        other => {
            return Err(case.error(
                format!("materials.{name}.model"),
                format!("unknown material model '{other}' (known: linear-elastic, j2-plasticity)"),
            ));
        }
    })
}

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

/// Builds the model of a case.
pub fn build(case: &LoadedCase) -> Result<BuiltModel> {
    let (mesh, mesh_path) = load_mesh(case)?;
    build_with_mesh(case, mesh, mesh_path)
}

/// Builds the model of a case on an already loaded mesh.
pub fn build_with_mesh(case: &LoadedCase, mesh: Mesh, mesh_path: PathBuf) -> Result<BuiltModel> {
    let c = &case.case;
    let kin = match c.analysis {
        Analysis::ThreeD => Kinematics::Solid3D,
        Analysis::Axisymmetric => Kinematics::Axisymmetric,
    };
    let model_dim = if kin == Kinematics::Solid3D { 3 } else { 2 };
    if kin == Kinematics::Axisymmetric {
        let (lo, hi) = mesh.bounding_box();
        let tol = 1e-9 * (hi[0] - lo[0]).abs().max(hi[1] - lo[1]).max(1e-300);
        if lo[0] < -tol {
            return Err(case.error(
                "analysis",
                format!("axisymmetric models need the mesh in x = r >= 0, but '{}' reaches x = {}", mesh.source, lo[0]),
            ));
        }
        if (hi[2] - lo[2]).abs() > tol {
            return Err(case.error(
                "analysis",
                format!("axisymmetric models need a planar mesh (z = 0); '{}' is not", mesh.source),
            ));
        }
    }
    // Zero-thickness cohesive interfaces: split the mesh along their surfaces first.
    let mut splits: Vec<(usize, stiction_core::mesh::Mesh, std::collections::HashMap<usize, usize>)> = Vec::new();
    let mut mesh = mesh;
    for (i, spec) in c.interfaces.iter().enumerate().filter(|(_, s)| s.kind == "cohesive") {
        let key = format!("interfaces[{i}]");
        let side = spec.side.as_deref().ok_or_else(|| {
            case.error(
                format!("{key}.side"),
                "required for type 'cohesive': the volume group that gets the duplicated nodes",
            )
        })?;
        // a surface already split by an earlier cohesive interface (same side, no split list of
        // its own) shares that split, e.g. contact on a pre-crack next to a cohesive ligament
        let earlier = splits.iter().find(|(j, ..)| {
            let other: &crate::case::InterfaceSpec = &c.interfaces[*j];
            let other_surfaces = other.split.clone().unwrap_or_else(|| vec![other.surface.clone()]);
            spec.split.is_none() && other.side.as_deref() == Some(side) && other_surfaces.contains(&spec.surface)
        });
        if let Some((_, original, pairs)) = earlier {
            let shared = (i, original.clone(), pairs.clone());
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
        splits.push((i, original, split.pairs));
    }
    let mesh = Arc::new(mesh);
    let mut model = Model::new(mesh.clone(), kin);

    // Materials and sections.
    let mut materials = BTreeMap::new();
    for (name, spec) in &c.materials {
        materials.insert(name.clone(), material(case, name, spec)?);
    }
    if c.sections.is_empty() {
        return Err(case.error("sections", "at least one section (group + material) is needed"));
    }
    for (i, s) in c.sections.iter().enumerate() {
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
        let mut any = false;
        for block in mesh.blocks_of(group) {
            let choice = match s.quadrature {
                QuadratureSpec::Standard => QuadratureChoice::Standard,
                QuadratureSpec::High => QuadratureChoice::High,
            };
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

    // Amplitudes.
    let mut amplitudes: BTreeMap<String, Arc<Amplitude>> = BTreeMap::new();
    amplitudes.insert("ramp".into(), Arc::new(Amplitude::ramp()));
    for (name, a) in &c.amplitudes {
        let amp = Amplitude::new(a.time.clone(), a.value.clone())
            .map_err(|e| case.error(format!("amplitudes.{name}"), e.to_string()))?;
        amplitudes.insert(name.clone(), Arc::new(amp));
    }
    let amplitude = |key: String, name: &Option<String>| -> Result<Arc<Amplitude>> {
        let n = name.as_deref().unwrap_or("ramp");
        amplitudes.get(n).cloned().ok_or_else(|| {
            case.error(
                key,
                format!("no amplitude '{n}' (defined: {})", amplitudes.keys().cloned().collect::<Vec<_>>().join(", ")),
            )
        })
    };

    // Boundary conditions.
    let dpn = kin.dofs_per_node();
    let mut reaction_groups: Vec<(String, Vec<usize>)> = Vec::new();
    for (i, b) in c.boundary.iter().enumerate() {
        let key = format!("boundary[{i}]");
        let group = mesh.group(&b.group).map_err(|e| case.error(format!("{key}.group"), e.to_string()))?;
        let nodes = mesh.group_nodes(group);
        if nodes.is_empty() {
            return Err(case.error(format!("{key}.group"), format!("group '{}' has no nodes", b.group)));
        }
        let all: Vec<usize> = (0..dpn).collect();
        let listed = |components: &Option<Vec<String>>| -> Result<Vec<usize>> {
            match components {
                None => Ok(all.clone()),
                Some(list) if list.is_empty() => Err(case.error(format!("{key}.components"), "must not be empty")),
                Some(list) => {
                    list.iter().map(|n| component_index(case, &format!("{key}.components"), n, kin)).collect()
                }
            }
        };
        let (components, scale, amp) = match b.kind.as_str() {
            "fixed" => (listed(&b.components)?, 0.0, amplitudes["ramp"].clone()),
            "displacement" => {
                let v =
                    b.value.ok_or_else(|| case.error(format!("{key}.value"), "required for type 'displacement'"))?;
                if !v.is_finite() {
                    return Err(case.error(format!("{key}.value"), "must be a finite number"));
                }
                (listed(&b.components)?, v, amplitude(format!("{key}.amplitude"), &b.amplitude)?)
            }
            "symmetry" => {
                let n = b
                    .normal
                    .as_deref()
                    .ok_or_else(|| case.error(format!("{key}.normal"), "required for type 'symmetry' (x, y or z)"))?;
                (vec![component_index(case, &format!("{key}.normal"), n, kin)?], 0.0, amplitudes["ramp"].clone())
            }
            other => {
                return Err(case.error(
                    format!("{key}.type"),
                    format!("unknown boundary type '{other}' (known: fixed, displacement, symmetry)"),
                ));
            }
        };
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
        // u_r = 0 on the axis of symmetry.
        let (lo, hi) = mesh.bounding_box();
        let tol = 1e-9 * (hi[0] - lo[0]).max(hi[1] - lo[1]);
        let ramp = amplitudes["ramp"].clone();
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
    }

    // Distributed loads.
    if !c.loads.is_empty() {
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
            let traction: Box<dyn Fn([f64; 3], [f64; 3]) -> [f64; 3]> = match l.kind.as_str() {
                "pressure" => {
                    let p =
                        l.value.ok_or_else(|| case.error(format!("{key}.value"), "required for type 'pressure'"))?;
                    Box::new(move |_x, n| [-p * n[0], -p * n[1], -p * n[2]])
                }
                "traction" => {
                    let v = l
                        .vector
                        .clone()
                        .ok_or_else(|| case.error(format!("{key}.vector"), "required for type 'traction'"))?;
                    if v.len() != dpn {
                        return Err(case.error(format!("{key}.vector"), format!("needs {dpn} components")));
                    }
                    let t = [v[0], v[1], if dpn == 3 { v[2] } else { 0.0 }];
                    Box::new(move |_x, _n| t)
                }
                other => {
                    return Err(case.error(
                        format!("{key}.type"),
                        format!("unknown load type '{other}' (known: pressure, traction)"),
                    ));
                }
            };
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
                amplitude: amplitude(format!("{key}.amplitude"), &l.amplitude)?,
            });
        }
    }

    // Interfaces.
    let modulus = materials.values().map(|m| m.stiffness_scale()).fold(0.0, f64::max);
    let plugin_dirs: Vec<PathBuf> = c.plugin_path.iter().map(|p| case.base_dir().join(p)).collect();
    let registry = crate::laws::LawRegistry::new(&plugin_dirs);
    let mut layouts = Vec::new();
    for (i, spec) in c.interfaces.iter().enumerate() {
        let key = format!("interfaces[{i}]");
        if spec.kind != "rigid-flat" && spec.kind != "cohesive" {
            return Err(case.error(
                format!("{key}.type"),
                format!("unknown interface type '{}' (known: rigid-flat, cohesive)", spec.kind),
            ));
        }
        let group = mesh.group(&spec.surface).map_err(|e| case.error(format!("{key}.surface"), e.to_string()))?;
        let face_size = mean_edge_length(&mesh, group)
            .ok_or_else(|| case.error(format!("{key}.surface"), format!("group '{}' has no faces", spec.surface)))?;
        let given: Vec<(String, f64)> = spec.parameters.iter().map(|(k, v)| (k.clone(), *v)).collect();
        let config_file = spec.config_file.as_ref().map(|f| case.base_dir().join(f));
        let law = crate::laws::make_law(
            &registry,
            &spec.law,
            case.base_dir(),
            &given,
            config_file.as_deref(),
            &crate::laws::LawContext { modulus, face_size },
        )
        .map_err(|m| case.error(format!("{key}.law"), m))?;
        let normal = match (&spec.normal, kin) {
            (None, Kinematics::Solid3D) => [0.0, 0.0, 1.0],
            (None, Kinematics::Axisymmetric) => [0.0, 1.0, 0.0],
            (Some(v), _) if v.len() == dpn => [v[0], v[1], if dpn == 3 { v[2] } else { 0.0 }],
            (Some(_), _) => return Err(case.error(format!("{key}.normal"), format!("needs {dpn} components"))),
        };
        if spec.kind == "cohesive" {
            let (_, original, pairs) = splits.iter().find(|(j, ..)| *j == i).expect("split above");
            let side = mesh
                .group(spec.side.as_deref().unwrap_or_default())
                .map_err(|e| case.error(format!("{key}.side"), e.to_string()))?;
            let finder = BoundaryFinder::new(
                &mesh.nodes,
                mesh.blocks_of(side).flat_map(|b| b.cells().map(move |c| (b.cell_type, c))),
            );
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
            let shear = spec.shear_stiffness.unwrap_or(100.0 * modulus / face_size);
            if !(shear >= 0.0 && shear.is_finite()) {
                return Err(case.error(format!("{key}.shear_stiffness"), "must be a finite number >= 0"));
            }
            let elements = stiction_interfaces::cohesive::CohesiveElements::new(
                &spec.name,
                original,
                &spec.surface,
                pairs,
                |b| finder.cell_centroid(&b[..nc]),
                kin,
                law,
                shear,
                spec.quadrature_order,
            )
            .map_err(|e| case.error(&key, e.to_string()))?;
            model.contributions.push(Box::new(elements));
            continue;
        }
        let flat_spec = stiction_interfaces::RigidFlatSpec {
            name: spec.name.clone(),
            surface: spec.surface.clone(),
            normal,
            approach_scale: spec.approach,
            approach_amplitude: amplitude(format!("{key}.amplitude"), &spec.amplitude)?,
            initial_gap: spec.initial_gap,
            extra_order: spec.quadrature_order,
            viscosity: spec.viscosity,
        };
        if spec.viscosity > 0.0 && c.solver.continuation == crate::case::ContinuationSpec::ArcLength {
            return Err(case.error(
                format!("{key}.viscosity"),
                "a viscous regularisation cannot be combined with solver.continuation = \"arc-length\" (the viscous term needs time to move forward; arc length may turn it back): use one of them",
            ));
        }
        if !(spec.max_viscous_share > 0.0 && spec.max_viscous_share <= 1.0) {
            return Err(case.error(format!("{key}.max_viscous_share"), "must be a fraction in (0, 1]"));
        }
        if !(spec.viscosity >= 0.0 && spec.viscosity.is_finite()) {
            return Err(case.error(format!("{key}.viscosity"), "must be a finite number >= 0"));
        }
        let flat = match &spec.points {
            None => stiction_interfaces::RigidFlat::over_surface(&mesh, kin, flat_spec, law),
            Some(points) => {
                let (list, source) = discrete_points(case, &format!("{key}.points"), points)?;
                let flat = stiction_interfaces::RigidFlat::at_points(&mesh, kin, flat_spec, law, &list, &source);
                layouts.push((spec.name.clone(), list));
                flat
            }
        }
        .map_err(|e| case.error(&key, e.to_string()))?;
        model.contributions.push(Box::new(flat));
    }

    model.finalize().map_err(|e| StictionError::Case { path: case.path.clone(), message: e.to_string() })?;
    Ok(BuiltModel { model, reaction_groups, layouts, mesh_path })
}
