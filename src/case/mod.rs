//! The case file: a TOML description of a problem. Unknown keys are rejected with their path;
//! every key's default, unit and range is declared here, once: [`reference`] generates the
//! case-file reference and `stiction run --help`'s list of defaults from these declarations.

mod base;
pub mod ensemble_spec;
pub mod overrides;
pub mod reference;
mod validate;
pub use ensemble_spec::{EnsembleSpec, VarySpec};
pub use validate::metres_per_length_unit;

use crate::error::{Result, StictionError};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use stiction_core::nonlinear::NewtonSettings;
use stiction_core::nonlinear::damped_flow::FlowSettings;
use stiction_core::path::Incrementation;

/// A whole case.
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Case {
    /// Name of the case (default: the file stem); output goes to `out/<name>/` by default.
    pub name: Option<String>,
    /// "3d" (default) or "axisymmetric" (r = x, z = y, mesh in the x-y plane with x >= 0).
    #[serde(default)]
    pub analysis: Analysis,
    pub mesh: MeshSpec,
    /// Materials by name.
    pub materials: BTreeMap<String, MaterialSpec>,
    /// Which material each volume group uses.
    pub sections: Vec<SectionSpec>,
    /// Named piecewise-linear amplitudes; "ramp" (0 -> 1 over t in [0, 1]) always exists.
    #[serde(default)]
    pub amplitudes: BTreeMap<String, AmplitudeSpec>,
    #[serde(default)]
    pub boundary: Vec<BoundarySpec>,
    #[serde(default)]
    pub loads: Vec<LoadSpec>,
    /// Extra directories searched for interface-law plugins (relative to the case file).
    #[serde(default)]
    pub plugin_path: Vec<PathBuf>,
    /// Interfaces: a geometry plus an interface law.
    #[serde(default)]
    pub interfaces: Vec<InterfaceSpec>,
    pub steps: Vec<StepSpec>,
    #[serde(default)]
    pub solver: SolverSpec,
    #[serde(default)]
    pub output: OutputSpec,
    /// The units the case's numbers are in (reports only; the solver is unit-agnostic).
    pub units: Option<UnitsSpec>,
    /// Run the case once per value of one key (e.g. several maximum approaches); each run gets
    /// its own folder and the histories a combined plot.
    pub sweep: Option<SweepSpec>,
    /// N realizations of the case with some keys varied (`stiction ensemble`); `stiction run`
    /// runs the case as written, once.
    pub ensemble: Option<EnsembleSpec>,
}

/// The units of a case's numbers, e.g. length = "nm", force = "nN" (the Ru cases).
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct UnitsSpec {
    /// Length unit, e.g. "nm", "um", "mm", "m" (SI prefixes are read: areas, energies and
    /// stresses in reports are named from it and `force`).
    pub length: String,
    /// Force unit, e.g. "nN", "uN", "N".
    pub force: String,
}

/// One run per value of one case key.
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SweepSpec {
    /// Any case key, written as for --set (e.g. "amplitudes.cycle.value.1").
    pub key: String,
    /// The values, one run each.
    pub values: Vec<f64>,
    /// Name of the swept quantity in folder names and plot legends (default: the key).
    pub label: Option<String>,
}

#[derive(Debug, Clone, Copy, Default, Deserialize, Serialize, PartialEq, Eq, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum Analysis {
    #[default]
    #[serde(rename = "3d")]
    ThreeD,
    Axisymmetric,
}

/// The mesh: a `.msh` file, or a `.geo` file meshed by gmsh (cached).
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct MeshSpec {
    /// gmsh MSH 4.1 file, relative to the case file.
    pub file: Option<PathBuf>,
    /// gmsh `.geo` file, relative to the case file (meshed with `gmsh`, cached in `.stiction-cache/`
    /// next to the `.geo`).
    pub geo: Option<PathBuf>,
    /// Element order for `.geo` meshing.
    #[serde(default = "default_order")]
    #[schemars(range(min = 1, max = 2))]
    #[schemars(extend("x-applies" = ".geo meshes"))]
    pub order: usize,
    /// gmsh `-clscale` factor for `.geo` meshing.
    #[serde(default = "one")]
    #[schemars(extend("exclusiveMinimum" = 0.0))]
    #[schemars(extend("x-applies" = ".geo meshes"))]
    pub size_factor: f64,
    /// Numbers passed to the `.geo` with `-setnumber`; each must be declared by the `.geo`'s
    /// `DefineConstant` and lie within its `Min`/`Max`.
    #[serde(default)]
    #[schemars(extend("x-applies" = ".geo meshes"))]
    pub parameters: BTreeMap<String, f64>,
    /// Longest gmsh may take to mesh the `.geo`, in seconds.
    #[serde(default = "default_mesh_time_limit")]
    #[schemars(extend("exclusiveMinimum" = 0.0))]
    #[schemars(extend("x-unit" = "s (wall)"))]
    #[schemars(extend("x-applies" = ".geo meshes"))]
    pub time_limit: f64,
    /// Most memory the run may count on, in GiB: gmsh is stopped when it passes a third of it
    /// (the model of a mesh needs at least three times what gmsh takes to make it), and a mesh
    /// file, a model or a sparse factor estimated to need more is refused before it is read,
    /// assembled or factored. By default: the memory the machine has available when the run
    /// starts. A smaller value keeps room for other work (e.g. ensemble members run side by
    /// side).
    #[schemars(extend("exclusiveMinimum" = 0.0))]
    #[schemars(extend("x-unit" = "GiB"))]
    pub memory_limit: Option<f64>,
}

impl MeshSpec {
    /// The memory a run may count on, in bytes: `memory_limit`, or what the machine has
    /// available now, whichever is smaller (None when neither is known).
    pub fn memory_budget(&self) -> Option<u64> {
        match (self.memory_limit_bytes(), crate::resources::available_memory()) {
            (Some(d), Some(a)) => Some(d.min(a)),
            (d, a) => d.or(a),
        }
    }

    /// `memory_limit` in bytes.
    pub fn memory_limit_bytes(&self) -> Option<u64> {
        self.memory_limit.map(|g| (g * f64::from(1u32 << 30)) as u64)
    }
}

fn default_mesh_time_limit() -> f64 {
    stiction_meshes::DEFAULT_TIME_LIMIT_SECONDS
}

fn default_order() -> usize {
    2
}
fn one() -> f64 {
    1.0
}

/// A material. `model` selects the law; the other keys are its parameters.
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct MaterialSpec {
    /// "linear-elastic" or "j2-plasticity".
    pub model: String,
    /// Young's modulus.
    #[schemars(extend("exclusiveMinimum" = 0.0))]
    #[schemars(extend("x-unit" = "stress"))]
    pub youngs_modulus: f64,
    /// Poisson's ratio.
    #[schemars(extend("exclusiveMinimum" = -1.0, "exclusiveMaximum" = 0.5))]
    pub poissons_ratio: f64,
    /// J2: initial yield stress.
    #[schemars(extend("exclusiveMinimum" = 0.0))]
    #[schemars(extend("x-unit" = "stress"))]
    #[schemars(extend("x-applies" = "j2-plasticity"))]
    pub yield_stress: Option<f64>,
    /// J2: linear isotropic hardening modulus.
    #[serde(default)]
    #[schemars(extend("x-unit" = "stress"))]
    #[schemars(extend("x-applies" = "j2-plasticity"))]
    pub isotropic_hardening: f64,
    /// J2: linear kinematic hardening modulus.
    #[serde(default)]
    #[schemars(extend("x-unit" = "stress"))]
    #[schemars(extend("x-applies" = "j2-plasticity"))]
    pub kinematic_hardening: f64,
    /// J2: tangent-only hardening modulus: stiffens the tangent of flowing points
    /// along the flow direction without changing the stresses, for perfectly plastic necks at
    /// their limit load (Newton then converges linearly there).
    #[serde(default)]
    #[schemars(range(min = 0.0))]
    #[schemars(extend("x-unit" = "stress"))]
    #[schemars(extend("x-applies" = "j2-plasticity"))]
    pub tangent_hardening: f64,
}

/// A section: a volume group and its material.
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SectionSpec {
    /// Physical group (name or tag) of volume cells (3d) or surface cells (axisymmetric).
    pub group: String,
    /// Name of a `[materials.<name>]` table.
    pub material: String,
    /// "standard" (default: tet10 4 points like C3D10) or "high".
    #[serde(default)]
    pub quadrature: QuadratureSpec,
}

#[derive(Debug, Clone, Copy, Default, Deserialize, Serialize, PartialEq, Eq, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum QuadratureSpec {
    #[default]
    Standard,
    High,
}

/// A piecewise-linear amplitude of pseudo-time, which boundary values, loads and approaches
/// are multiplied by.
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct AmplitudeSpec {
    /// Pseudo-times, increasing.
    #[schemars(extend("x-unit" = "pseudo-time"))]
    pub time: Vec<f64>,
    /// Values at those times (as many as `time`); linear between them, constant beyond.
    pub value: Vec<f64>,
}

/// A boundary condition on the nodes of a physical group.
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct BoundarySpec {
    /// Physical group (name or tag) of the nodes it holds.
    pub group: String,
    /// "fixed" (u = 0), "displacement" (u = value * amplitude(t)) or "symmetry" (u . n = 0 on a
    /// coordinate plane with normal `normal`).
    #[serde(rename = "type")]
    pub kind: String,
    /// Components: any of "x", "y", "z" ("r", "z" in axisymmetric models). Default: all.
    pub components: Option<Vec<String>>,
    /// Displacement value (type "displacement").
    #[schemars(extend("x-unit" = "length"))]
    #[schemars(extend("x-applies" = "type = \"displacement\""))]
    pub value: Option<f64>,
    /// Amplitude name (default "ramp").
    pub amplitude: Option<String>,
    /// Symmetry plane normal: "x", "y" or "z" (type "symmetry").
    #[schemars(extend("x-applies" = "type = \"symmetry\""))]
    pub normal: Option<String>,
}

/// A distributed load on a boundary group.
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct LoadSpec {
    /// Physical group (name or tag) of boundary faces (3d) or lines (axisymmetric).
    pub group: String,
    /// "pressure" (value acts against the outward normal) or "traction" (vector per area).
    #[serde(rename = "type")]
    pub kind: String,
    /// Pressure (type "pressure").
    #[schemars(extend("x-unit" = "stress"))]
    #[schemars(extend("x-applies" = "type = \"pressure\""))]
    pub value: Option<f64>,
    /// Traction vector, force per area (type "traction").
    #[schemars(extend("x-unit" = "stress"))]
    #[schemars(extend("x-applies" = "type = \"traction\""))]
    pub vector: Option<Vec<f64>>,
    /// Amplitude name (default "ramp").
    pub amplitude: Option<String>,
}

/// An interface. Type "rigid-flat": the surface group against a rigid plane that approaches
/// the body along `normal` by `approach * amplitude(t)`.
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct InterfaceSpec {
    /// Name of the interface in outputs (history.csv columns, file names) and in `until_separated`.
    pub name: String,
    /// "rigid-flat", or "cohesive" (zero-thickness cohesive elements on an interior surface).
    #[serde(rename = "type")]
    pub kind: String,
    /// Surface group of the body (faces: triangles in 3d, lines in axisymmetric models).
    pub surface: String,
    /// Unit normal from the flat toward the body (default [0, 0, 1] in 3d, [0, 1] axisymmetric).
    #[schemars(extend("x-applies" = "rigid-flat interfaces"))]
    pub normal: Option<Vec<f64>>,
    /// Approach of the flat toward the body: approach * amplitude(t) (positive presses; rigid
    /// flats only, default 0).
    #[serde(default)]
    #[schemars(extend("x-unit" = "length"))]
    #[schemars(extend("x-applies" = "rigid-flat interfaces"))]
    pub approach: f64,
    /// Cohesive: interior surfaces along which the mesh is split (default: `surface` only; add
    /// pre-cracked faces here to open them without cohesion).
    #[schemars(extend("x-applies" = "cohesive interfaces"))]
    pub split: Option<Vec<String>>,
    /// Cohesive: the volume group whose cells get the duplicated nodes.
    #[schemars(extend("x-applies" = "cohesive interfaces"))]
    pub side: Option<String>,
    /// Cohesive: elastic stiffness against tangential slip (the law is normal-only; default:
    /// the law's `penalty` choice, 100 E / h).
    #[schemars(range(min = 0.0))]
    #[schemars(extend("x-unit" = "stress per length"))]
    #[schemars(extend("x-applies" = "cohesive interfaces"))]
    pub shear_stiffness: Option<f64>,
    /// Amplitude name (default "ramp").
    pub amplitude: Option<String>,
    /// Gap between the flat and the closest point of the undeformed surface at approach 0
    /// (default 0: approach 0 is first touch).
    #[serde(default)]
    #[schemars(extend("x-unit" = "length"))]
    #[schemars(extend("x-applies" = "rigid-flat interfaces"))]
    pub initial_gap: f64,
    /// Law: a built-in name ("frictionless-contact", "lennard-jones"), a plugin's name found on
    /// the plugin search path, or a path to a plugin library.
    pub law: String,
    /// Law parameters (validated against the law's parameter list).
    #[serde(default)]
    pub parameters: BTreeMap<String, f64>,
    /// Configuration file for laws that take one (e.g. an asperity calibration), relative to the
    /// case file.
    pub config_file: Option<PathBuf>,
    /// Extra Gauss points per face direction (default 0; short-range laws want 2 or more).
    #[serde(default)]
    pub quadrature_order: usize,
    /// Viscous regularisation zeta (a pseudo-time) for crossing adhesive instabilities (default
    /// 0: none): adds -zeta |k_c| (g - g_c) / dt per point (resisting the change of gap), k_c the law's tangent at the last
    /// converged increment; its dissipated energy is reported as `viscous_dissipation`.
    #[serde(default)]
    #[schemars(range(min = 0.0))]
    #[schemars(extend("x-unit" = "pseudo-time"))]
    pub viscosity: f64,
    /// Largest acceptable share of the viscous regularisation's dissipation in the gross work
    /// of the flat (integral of |force| |d approach|); above it the run reports a warning in
    /// summary.json, on stderr and as a `viscous_share_exceeded` event.
    #[serde(default = "default_max_viscous_share")]
    #[schemars(extend("exclusiveMinimum" = 0.0, "maximum" = 1.0))]
    pub max_viscous_share: f64,
    /// Discrete points (e.g. asperities) instead of the whole surface; needs a force law.
    pub points: Option<PointsSpec>,
    /// Electrical contact resistance of a rigid-flat interface (a `contact_resistance` column
    /// in history.csv); needs `[units] length`.
    pub resistance: Option<ResistanceSpec>,
}

/// The metal's electrical data for the contact resistance (the body and the flat are taken to
/// be the same metal; see `stiction_interfaces::contact_resistance`).
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ResistanceSpec {
    /// Bulk resistivity in ohm m (Ru: 7.1e-8).
    #[schemars(extend("exclusiveMinimum" = 0.0))]
    #[schemars(extend("x-unit" = "ohm m"))]
    pub resistivity: f64,
    /// Electron mean free path, in the case's length unit (Ru: 6.59 nm).
    #[schemars(range(min = 0.0))]
    #[schemars(extend("x-unit" = "length"))]
    pub mean_free_path: f64,
    /// Specific resistance of a film on each spot, in ohm m^2 (default 0: clean metal).
    #[serde(default)]
    #[schemars(range(min = 0.0))]
    #[schemars(extend("x-unit" = "ohm m^2"))]
    pub film_specific_resistance: f64,
    /// The counter body's (the flat's) resistivity in ohm m (default: the same metal).
    #[schemars(extend("exclusiveMinimum" = 0.0))]
    #[schemars(extend("x-unit" = "ohm m"))]
    pub counter_resistivity: Option<f64>,
    /// The counter body's electron mean free path, in the case's length unit (default: the
    /// same metal).
    #[schemars(range(min = 0.0))]
    #[schemars(extend("x-unit" = "length"))]
    pub counter_mean_free_path: Option<f64>,
}

/// Discrete points on the interface surface: generated, or read from a file.
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PointsSpec {
    /// CSV with header `x,y,height` or `x,y,height,radius`: in-plane coordinates from the
    /// surface's lowest point along two directions normal to the flat, the height toward the
    /// flat, and the point's radius for laws that keep one. Relative to the case.
    pub file: Option<PathBuf>,
    /// Points per unit area (generator).
    #[schemars(extend("exclusiveMinimum" = 0.0))]
    #[schemars(extend("x-unit" = "1/length^2"))]
    #[schemars(extend("x-applies" = "generated layouts"))]
    pub density: Option<f64>,
    /// A measured or generated height map whose summits (as `stiction surface stats` finds
    /// them) are the points: the map's mean plane is the body's surface, a summit's height above
    /// it offsets its law's distance, and its radius goes to laws that keep one (a state named
    /// `radius`, as `hertz-asperity` does); the map's lengths are converted to `[units] length`.
    pub surface: Option<SurfaceMapSpec>,
    /// Radius of the region around the lowest point, projected on the flat (generator; for a
    /// height map, the summits within this distance of `surface.centre`).
    #[schemars(extend("exclusiveMinimum" = 0.0))]
    #[schemars(extend("x-unit" = "length"))]
    #[schemars(extend("x-applies" = "generated layouts, height maps"))]
    pub region_radius: Option<f64>,
    /// Minimum distance between points (generator, default 0; for a height map: of two
    /// summits closer than this, the lower is left out).
    #[serde(default)]
    #[schemars(range(min = 0.0))]
    #[schemars(extend("x-unit" = "length"))]
    pub min_spacing: f64,
    /// Height of the points toward the flat (generator; e.g. the asperity height).
    #[schemars(extend("exclusiveMinimum" = 0.0))]
    #[schemars(extend("x-unit" = "length"))]
    #[schemars(extend("x-applies" = "generated layouts"))]
    pub height: Option<f64>,
    /// Standard deviation of heights (generator, default 0: identical heights).
    #[serde(default)]
    #[schemars(range(min = 0.0))]
    #[schemars(extend("x-unit" = "length"))]
    #[schemars(extend("x-applies" = "generated layouts"))]
    pub height_std: f64,
    /// Random seed (generator, default 1).
    #[serde(default = "default_seed")]
    #[schemars(extend("x-applies" = "generated layouts"))]
    pub seed: u64,
    /// Area of each point's footprint (an asperity's base): its force acts as a uniform
    /// traction over a disc of this area and its distance is the mean over the disc (default 0:
    /// a point force, as for springs).
    #[serde(default)]
    #[schemars(range(min = 0.0))]
    #[schemars(extend("x-unit" = "length^2"))]
    pub footprint_area: f64,
    /// The footprint's own response below the mesh scale, in series with each point's law (for
    /// meshes coarser than the footprint; needs `footprint_area`): see
    /// `stiction_interfaces::local_footprint`.
    pub footprint_correction: Option<FootprintCorrectionSpec>,
}

/// `points.surface`: a measured or generated height map whose summits (8-neighbour rule, radius
/// from the mean curvature; see `stiction surface stats`) become the points. The map's mean
/// plane is the body's surface: a summit's height above it is the point's height toward the
/// flat, and its radius goes to laws that keep a per-point radius (a state named `radius`, as
/// `hertz-asperity` does). The map's lengths and heights are converted to the case's
/// `[units] length`.
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SurfaceMapSpec {
    /// The map, relative to the case: a Gwyddion Simple Field file (`.gsf`), or text: a matrix
    /// of heights (with `pixel_size`) or `x y z` columns on a regular grid (with `columns`).
    pub file: PathBuf,
    /// The unit of the map's lengths and heights where the file states none (text files): m,
    /// mm, um, nm, pm or A. A `.gsf` file's `XYUnits` and `ZUnits` come first.
    pub unit: Option<String>,
    /// A text matrix's pixel size, in the map's unit.
    #[schemars(extend("exclusiveMinimum" = 0.0))]
    pub pixel_size: Option<f64>,
    /// A text file of `x y z` columns (default false: a matrix of heights).
    #[serde(default)]
    pub columns: bool,
    /// The map point put at the surface's pole, from the map's corner in the map's unit
    /// (default: the map's middle).
    pub centre: Option<[f64; 2]>,
    /// Summits lower than this above the map's mean plane are left out (default 0: the
    /// summits above the mean plane).
    #[serde(default)]
    #[schemars(range(min = 0.0))]
    #[schemars(extend("x-unit" = "length"))]
    pub threshold: f64,
}

/// The local correction of a footprint the mesh does not resolve: an elastic compliance in
/// series with the law, and, only where the case declares one, a rigid-plastic slider that
/// limits the force the continuum under the footprint carries.
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FootprintCorrectionSpec {
    /// Length per force. Absent: computed per point, as the half-space compliance of the
    /// footprint's disc minus what the mesh gives it (an elastic solve of the body, once).
    #[schemars(range(min = 0.0))]
    #[schemars(extend("x-unit" = "length/force"))]
    pub compliance: Option<f64>,
    /// Force at which the continuum under a footprint flows (opt-in; absent with
    /// `limit_pressure` absent: no limit, the footprint is elastic).
    #[schemars(extend("exclusiveMinimum" = 0.0))]
    #[schemars(extend("x-unit" = "force"))]
    pub limit_force: Option<f64>,
    /// The same limit as a pressure over `footprint_area` (opt-in): a number, or
    /// "von-mises-disc", the limit pressure of a uniform pressure on a disc over a von Mises
    /// half-space, 2.99 Y (`cases/validation/disc-limit-axisym.toml`), Y the yield stress of
    /// the body's perfectly plastic material.
    #[schemars(extend("exclusiveMinimum" = 0.0))]
    #[schemars(extend("x-unit" = "stress"))]
    pub limit_pressure: Option<LimitPressure>,
}

/// `points.footprint_correction.limit_pressure`: a value, or a named limit derived from the
/// body's material.
#[derive(Debug, Clone, Deserialize, PartialEq, JsonSchema)]
#[serde(untagged)]
pub enum LimitPressure {
    Value(f64),
    Named(String),
}

/// The one named limit pressure.
pub const VON_MISES_DISC: &str = "von-mises-disc";

fn default_seed() -> u64 {
    1
}

/// A step: pseudo-time runs from the end of the previous step to `end_time`.
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct StepSpec {
    /// Name of the step in messages.
    pub name: Option<String>,
    /// Pseudo-time at the step's end (after the previous step's end).
    #[schemars(extend("x-unit" = "pseudo-time"))]
    pub end_time: f64,
    /// First increment (default: a tenth of the step).
    #[schemars(extend("exclusiveMinimum" = 0.0))]
    #[schemars(extend("x-unit" = "pseudo-time"))]
    pub initial_increment: Option<f64>,
    /// Smallest increment before the run gives up (default: 1e-6 of the step).
    #[schemars(extend("exclusiveMinimum" = 0.0))]
    #[schemars(extend("x-unit" = "pseudo-time"))]
    pub min_increment: Option<f64>,
    /// Largest increment (default: the step).
    #[schemars(extend("exclusiveMinimum" = 0.0))]
    #[schemars(extend("x-unit" = "pseudo-time"))]
    pub max_increment: Option<f64>,
    /// Write VTK every this many converged increments (default 1; 0 = only at the step end).
    #[serde(default = "one_usize")]
    pub output_every: usize,
    /// End the step (and the run, if it is the last) once this interface has had contact and
    /// has none left with its force below 1e-3 of the largest force magnitude so far, e.g. when
    /// every asperity has pulled off.
    #[schemars(extend("x-applies" = "rigid-flat interfaces"))]
    pub until_separated: Option<String>,
}

fn one_usize() -> usize {
    1
}

/// The nonlinear solver, the increment control and how unstable paths are crossed
/// (docs/solver.md says when to change what).
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SolverSpec {
    /// Nonlinear iterations (Newton or quasi-Newton) per increment.
    #[serde(default = "default_iterations")]
    #[schemars(range(min = 1))]
    pub max_iterations: usize,
    /// Relative residual tolerance.
    #[serde(default = "default_tol_r")]
    #[schemars(extend("exclusiveMinimum" = 0.0))]
    pub tol_residual: f64,
    /// Relative displacement-correction tolerance.
    #[serde(default = "default_tol_u")]
    #[schemars(extend("exclusiveMinimum" = 0.0))]
    pub tol_displacement: f64,
    /// Backtracking line search.
    #[serde(default = "default_line_search")]
    pub line_search: bool,
    /// An increment whose residual fell by less than 5% over its last 3 iterations is abandoned
    /// (and cut) from this iteration on, instead of running to `max_iterations` (0: never).
    #[serde(default = "default_stagnation_iterations")]
    pub stagnation_iterations: usize,
    /// Threads of the run: assembly, and the factorization of a factor of at least 50M entries
    /// (a smaller factor, and every one-column solve, runs on one thread: faster); 0 = all cores.
    #[serde(default)]
    pub threads: usize,
    /// Increment cut factor after a failure.
    #[serde(default = "default_cut")]
    #[schemars(extend("exclusiveMinimum" = 0.0, "exclusiveMaximum" = 1.0))]
    pub cut_factor: f64,
    /// Increment growth factor after an easy increment.
    #[serde(default = "default_growth")]
    #[schemars(range(min = 1.0))]
    pub growth_factor: f64,
    /// How to cross a limit point where the increment keeps failing: "none" (default: cut
    /// until the minimum increment, then snap to a stable state), "arc-length" (Crisfield's
    /// spherical arc-length continuation in the load parameter, which may turn the approach
    /// back) or "dissipation" (each increment dissipates a set energy by damage: cohesive
    /// cracks and their snap-backs, for laws that unload secantly; an arc length where nothing
    /// damages). Load control resumes beyond the point that failed.
    #[serde(default)]
    pub continuation: ContinuationSpec,
    /// Nonlinear solver: "quasi-newton" (default: BFGS on a reused factorization, refactorized
    /// when convergence slows) or "newton" (full Newton: a factorization every iteration).
    #[serde(default)]
    pub method: MethodSpec,
    /// Precision of the numeric factor: "single" (default: an f32 factor, half the memory;
    /// exact solves by iterative refinement, and the quasi-Newton method uses it as it is) or
    /// "double".
    #[serde(default)]
    pub factor_precision: PrecisionSpec,
    /// Fill-reducing ordering of the sparse factorization: "nested-dissection" (default, METIS
    /// on the node graph) or "amd" (approximate minimum degree).
    #[serde(default)]
    pub ordering: OrderingSpec,
    /// The quasi-Newton solver refactorizes when the iterations it expects still to need cost
    /// more than a refactorization; with 0 (default) it compares measured times, with a number
    /// it takes a refactorization (tangent assembly and numeric factorization) to cost that many
    /// quasi-Newton iterations (residual assembly and solve), so its choices depend on the
    /// residuals only and a run is reproducible to the last digit for a given thread count.
    #[serde(default)]
    #[schemars(range(min = 0.0))]
    #[schemars(extend("x-applies" = "method = \"quasi-newton\""))]
    pub refactorization_cost_ratio: f64,
    /// Where an increment with no earlier rate to extrapolate (a run's first, the first after a
    /// load reversal) starts: "tangent" (default: the committed state moved along the tangent,
    /// K du/dt = -dR/dt, so a bonded ligament follows the moving flat instead of being torn by
    /// it in the first residual) or "none" (the committed state). Other increments extrapolate
    /// the last one.
    #[serde(default)]
    pub start_predictor: StartPredictorSpec,
    /// Which material tangent the solvers see: "switch-on-failure" (default: the consistent
    /// tangent until an attempt fails to converge from a state where a point flows, then the
    /// other one, at most once per committed increment; a failed snap is retried on the other
    /// one), "consistent" or "stabilized". The stabilized tangent of a material with one
    /// (`j2-plasticity` hardening less than E/100) stiffens the flow direction of a flowing
    /// point to a hardening of E/100 in the tangent alone: the same converged solutions,
    /// reached where the consistent tangent of a perfectly plastic neck at its limit load
    /// makes Newton cycle.
    #[serde(default)]
    pub tangent: TangentSpec,
    /// Consecutive cuts after which arc-length continuation takes over.
    #[serde(default = "default_arc_length_after_cuts")]
    #[schemars(range(min = 1))]
    #[schemars(extend("x-applies" = "continuation = \"arc-length\" or \"dissipation\""))]
    pub arc_length_after_cuts: usize,
    /// How a snap (a jump at fixed load, where the path has no nearby equilibrium) finds the
    /// state it reaches: "settle" (a descent from the committed state; the state of an
    /// elastic body, but for a yielding body a one-step plastic update whose state depends on
    /// how the descent went), "damped-flow" (the body's overdamped motion against a uniform
    /// viscous drag, M du/dtau = -r(u) with the unit-density mass, integrated to
    /// `snap_tolerance` with every step committed, so a yielding body or a hysteretic law
    /// follows the snap's path: the same state whatever the solver, at tens to hundreds of
    /// times the cost) or "auto" (default: "damped-flow" when a material or an interface law
    /// keeps state, i.e. the model is path dependent, "settle" otherwise).
    #[serde(default)]
    pub snap: SnapSpec,
    /// The drag the damped flow moves against: "mass" (default: M du/dtau = -r, the
    /// unit-density mass, a uniform viscous drag) or "stiffness" (K_0 du/dtau = -r, the
    /// solid's initial elastic stiffness: stiffness-proportional damping, under which every
    /// elastic mode relaxes at the same rate, so a snap of a large 3D body takes far fewer
    /// steps; its path, and so the plastic work along it, differs).
    #[serde(default)]
    pub snap_damping: SnapDampingSpec,
    /// The damped flow's local error per step relative to the step's move.
    #[serde(default = "default_snap_tolerance")]
    #[schemars(extend("exclusiveMinimum" = 0.0, "exclusiveMaximum" = 1.0))]
    pub snap_tolerance: f64,
    /// The damped flow's steps at most per snap; then the run stops with the
    /// reason.
    #[serde(default = "default_snap_max_steps")]
    #[schemars(range(min = 1))]
    pub snap_max_steps: usize,
}

/// How snaps are solved.
#[derive(Debug, Clone, Copy, Default, Deserialize, Serialize, PartialEq, Eq, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum SnapSpec {
    #[default]
    Auto,
    Settle,
    DampedFlow,
}

/// The damped flow's drag.
#[derive(Debug, Clone, Copy, Default, Deserialize, Serialize, PartialEq, Eq, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum SnapDampingSpec {
    #[default]
    Mass,
    Stiffness,
}

fn default_snap_tolerance() -> f64 {
    FlowSettings::default().tolerance
}

fn default_snap_max_steps() -> usize {
    FlowSettings::default().max_steps
}

/// Nonlinear solver.
#[derive(Debug, Clone, Copy, Default, Deserialize, Serialize, PartialEq, Eq, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum MethodSpec {
    #[default]
    QuasiNewton,
    Newton,
}

/// Precision of the numeric factor.
#[derive(Debug, Clone, Copy, Default, Deserialize, Serialize, PartialEq, Eq, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum PrecisionSpec {
    #[default]
    Single,
    Double,
}

/// The predictor of the increments with no earlier rate to extrapolate.
#[derive(Debug, Clone, Copy, Default, Deserialize, Serialize, PartialEq, Eq, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum StartPredictorSpec {
    #[default]
    Tangent,
    None,
}

/// Which material tangent the solvers see.
#[derive(Debug, Clone, Copy, Default, Deserialize, Serialize, PartialEq, Eq, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum TangentSpec {
    #[default]
    SwitchOnFailure,
    Consistent,
    Stabilized,
}

/// Fill-reducing ordering.
#[derive(Debug, Clone, Copy, Default, Deserialize, Serialize, PartialEq, Eq, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum OrderingSpec {
    #[default]
    NestedDissection,
    Amd,
}

/// Limit-point crossing method.
#[derive(Debug, Clone, Copy, Default, Deserialize, Serialize, PartialEq, Eq, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum ContinuationSpec {
    #[default]
    None,
    ArcLength,
    Dissipation,
}

fn default_max_viscous_share() -> f64 {
    InterfaceSpec::default_max_viscous_share()
}

impl InterfaceSpec {
    /// Default of `max_viscous_share`.
    pub fn default_max_viscous_share() -> f64 {
        0.05
    }
}

/// Default of `arc_length_after_cuts`.
pub const DEFAULT_ARC_LENGTH_AFTER_CUTS: usize = 2;

fn default_arc_length_after_cuts() -> usize {
    DEFAULT_ARC_LENGTH_AFTER_CUTS
}

impl Default for SolverSpec {
    fn default() -> Self {
        toml::from_str("").expect("solver defaults")
    }
}

// The solver defaults are the core's (one place for each fact).
fn default_iterations() -> usize {
    NewtonSettings::default().max_iterations
}
fn default_tol_r() -> f64 {
    NewtonSettings::default().tol_residual
}
fn default_tol_u() -> f64 {
    NewtonSettings::default().tol_displacement
}
fn yes() -> bool {
    true
}
fn default_line_search() -> bool {
    NewtonSettings::default().line_search
}
fn default_stagnation_iterations() -> usize {
    NewtonSettings::default().stagnation_iterations
}
fn default_cut() -> f64 {
    Incrementation::DEFAULT_CUT_FACTOR
}
fn default_growth() -> f64 {
    Incrementation::DEFAULT_GROWTH_FACTOR
}

/// Where and what a run writes, and how often it checkpoints.
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct OutputSpec {
    /// Output directory (default `out/<name>`, relative to the working directory).
    pub directory: Option<PathBuf>,
    /// Write VTK files.
    #[serde(default = "yes")]
    pub vtk: bool,
    /// Wall minutes between checkpoints (`restart.bin` in the output folder, to go on with
    /// `stiction run --resume`); 0 writes one at every commit. A failed or stopped run always
    /// writes one; a completed run removes it.
    #[serde(default = "default_checkpoint_minutes")]
    #[schemars(range(min = 0.0))]
    #[schemars(extend("x-unit" = "min (wall)"))]
    pub checkpoint_minutes: f64,
}

/// Default of `output.checkpoint_minutes`.
fn default_checkpoint_minutes() -> f64 {
    10.0
}

impl Default for OutputSpec {
    fn default() -> Self {
        toml::from_str("").expect("output defaults")
    }
}

/// A parsed case with the file it came from.
#[derive(Debug, Clone)]
pub struct LoadedCase {
    pub case: Case,
    pub path: PathBuf,
    pub name: String,
    /// The case as read, merged over its base and with the `--set` overrides applied.
    pub value: toml::Value,
}

impl LoadedCase {
    /// Directory that relative paths in the case are relative to.
    pub fn base_dir(&self) -> &Path {
        self.path.parent().unwrap_or(Path::new("."))
    }
    pub fn error(&self, key: impl Into<String>, message: impl Into<String>) -> StictionError {
        StictionError::CaseKey { path: self.path.clone(), key: key.into(), message: message.into() }
    }
}

/// Reads a case file, applies `--set key=value` overrides, checks the schema and validates the
/// numbers (the same checks for `stiction check` and `stiction run`).
pub fn load(path: &Path, sets: &[String]) -> Result<LoadedCase> {
    let bad = |message: String| StictionError::Case { path: path.to_path_buf(), message };
    let (text, merged) = base::read(path)?;
    let (case, value): (Case, toml::Value) = if sets.is_empty() && merged.is_none() {
        // parsed from the text, so errors keep their line numbers
        let case = toml::from_str(&text).map_err(|e| bad(e.to_string()))?;
        (case, toml::from_str(&text).map_err(|e| bad(e.to_string()))?)
    } else {
        let mut value = match merged {
            Some(v) => v,
            None => toml::from_str(&text).map_err(|e| bad(e.to_string()))?,
        };
        for set in sets {
            overrides::apply(&mut value, set).map_err(|m| bad(format!("--set {set}: {m}")))?;
        }
        let after = if sets.is_empty() { " (merged over its base)" } else { " (after --set overrides)" };
        (Case::deserialize(value.clone()).map_err(|e| bad(format!("{e}{after}")))?, value)
    };
    let name =
        case.name.clone().unwrap_or_else(|| path.file_stem().and_then(|s| s.to_str()).unwrap_or("case").to_string());
    let loaded = LoadedCase { case, path: path.to_path_buf(), name, value };
    validate::validate(&loaded)?;
    ensemble_spec::validate(&loaded)?;
    Ok(loaded)
}
