//! Validation of a parsed case's numbers and cross-references: one place, run by
//! [`super::load`], so `stiction check` and `stiction run` accept and reject the same inputs.
//! Errors name the case key.

use super::{LimitPressure, LoadedCase, VON_MISES_DISC};
use crate::error::Result;

/// A finite number.
fn finite(case: &LoadedCase, key: &str, v: f64) -> Result<()> {
    if v.is_finite() { Ok(()) } else { Err(case.error(key, format!("must be a finite number, got {v}"))) }
}

/// A finite number > 0.
fn positive(case: &LoadedCase, key: &str, v: f64) -> Result<()> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(case.error(key, format!("must be a finite number > 0, got {v}")))
    }
}

pub fn validate(case: &LoadedCase) -> Result<()> {
    let minutes = case.case.output.checkpoint_minutes;
    if !(minutes.is_finite() && minutes >= 0.0) {
        return Err(case.error("output.checkpoint_minutes", format!("must be a finite number >= 0, got {minutes}")));
    }
    for (i, dir) in case.case.plugin_path.iter().enumerate() {
        let full = case.base_dir().join(dir);
        if full.exists() && !full.is_dir() {
            return Err(case.error(
                format!("plugin_path[{i}]"),
                format!(
                    "'{}' is a file; a plugin search path names folders that hold plugin libraries",
                    full.display()
                ),
            ));
        }
    }
    solver(case)?;
    steps(case)?;
    mesh(case)?;
    loads_and_boundaries(case)?;
    interfaces(case)
}

/// Every number of the loads, the boundary conditions, the amplitudes and a sweep is finite.
fn loads_and_boundaries(case: &LoadedCase) -> Result<()> {
    let c = &case.case;
    for (i, l) in c.loads.iter().enumerate() {
        if let Some(v) = l.value {
            finite(case, &format!("loads[{i}].value"), v)?;
        }
        for (k, v) in l.vector.iter().flatten().enumerate() {
            finite(case, &format!("loads[{i}].vector[{k}]"), *v)?;
        }
    }
    for (i, b) in c.boundary.iter().enumerate() {
        if let Some(v) = b.value {
            finite(case, &format!("boundary[{i}].value"), v)?;
        }
    }
    for (name, a) in &c.amplitudes {
        for (k, v) in a.time.iter().enumerate() {
            finite(case, &format!("amplitudes.{name}.time[{k}]"), *v)?;
        }
        for (k, v) in a.value.iter().enumerate() {
            finite(case, &format!("amplitudes.{name}.value[{k}]"), *v)?;
        }
    }
    for (i, f) in c.interfaces.iter().enumerate() {
        for (k, v) in f.normal.iter().flatten().enumerate() {
            finite(case, &format!("interfaces[{i}].normal[{k}]"), *v)?;
        }
    }
    if let Some(sweep) = &c.sweep {
        for (k, v) in sweep.values.iter().enumerate() {
            finite(case, &format!("sweep.values[{k}]"), *v)?;
        }
    }
    Ok(())
}

fn solver(case: &LoadedCase) -> Result<()> {
    let s = &case.case.solver;
    positive(case, "solver.tol_residual", s.tol_residual)?;
    positive(case, "solver.tol_displacement", s.tol_displacement)?;
    if s.max_iterations == 0 {
        return Err(case.error("solver.max_iterations", "must be at least 1"));
    }
    if !(s.cut_factor > 0.0 && s.cut_factor < 1.0) {
        return Err(case.error("solver.cut_factor", format!("must be in (0, 1), got {}", s.cut_factor)));
    }
    if !(s.growth_factor >= 1.0 && s.growth_factor.is_finite()) {
        return Err(
            case.error("solver.growth_factor", format!("must be a finite number >= 1, got {}", s.growth_factor))
        );
    }
    if s.arc_length_after_cuts == 0 {
        return Err(case.error("solver.arc_length_after_cuts", "must be at least 1"));
    }
    if !(s.refactorization_cost_ratio >= 0.0 && s.refactorization_cost_ratio.is_finite()) {
        return Err(case.error(
            "solver.refactorization_cost_ratio",
            format!("must be 0 (measured costs) or a finite ratio > 0, got {}", s.refactorization_cost_ratio),
        ));
    }
    if !(s.snap_tolerance > 0.0 && s.snap_tolerance < 1.0) {
        return Err(case.error("solver.snap_tolerance", format!("must be in (0, 1), got {}", s.snap_tolerance)));
    }
    if s.snap_max_steps == 0 {
        return Err(case.error("solver.snap_max_steps", "must be at least 1"));
    }
    Ok(())
}

fn steps(case: &LoadedCase) -> Result<()> {
    let c = &case.case;
    if c.steps.is_empty() {
        return Err(case.error("steps", "at least one step is needed"));
    }
    let mut previous_end = 0.0;
    for (i, s) in c.steps.iter().enumerate() {
        let key = |k: &str| format!("steps[{i}].{k}");
        finite(case, &key("end_time"), s.end_time)?;
        let span = s.end_time - previous_end;
        if !(span > 0.0) {
            return Err(case.error(key("end_time"), format!("must be after the previous step's end ({previous_end})")));
        }
        for (k, v) in [
            ("initial_increment", s.initial_increment),
            ("min_increment", s.min_increment),
            ("max_increment", s.max_increment),
        ] {
            if let Some(v) = v {
                positive(case, &key(k), v)?;
            }
        }
        let minimum = s.min_increment.unwrap_or(1e-6 * span);
        let initial = s.initial_increment.unwrap_or(0.1 * span).min(span);
        let maximum = s.max_increment.unwrap_or(span);
        if initial < minimum {
            return Err(case.error(key("initial_increment"), format!("{initial} is below min_increment {minimum}")));
        }
        if maximum < initial {
            return Err(case.error(key("max_increment"), format!("{maximum} is below initial_increment {initial}")));
        }
        if let Some(name) = &s.until_separated {
            if !c.interfaces.iter().any(|f| &f.name == name) {
                return Err(case.error(key("until_separated"), format!("no interface named '{name}'")));
            }
        }
        previous_end = s.end_time;
    }
    Ok(())
}

fn mesh(case: &LoadedCase) -> Result<()> {
    let m = &case.case.mesh;
    positive(case, "mesh.size_factor", m.size_factor)?;
    positive(case, "mesh.time_limit", m.time_limit)?;
    if let Some(limit) = m.memory_limit {
        positive(case, "mesh.memory_limit", limit)?;
    }
    if m.geo.is_some() && !(m.order == 1 || m.order == 2) {
        return Err(case.error("mesh.order", format!("must be 1 or 2, got {}", m.order)));
    }
    for (k, v) in &m.parameters {
        finite(case, &format!("mesh.parameters.{k}"), *v)?;
    }
    Ok(())
}

fn interfaces(case: &LoadedCase) -> Result<()> {
    for (i, f) in case.case.interfaces.iter().enumerate() {
        let key = |k: &str| format!("interfaces[{i}].{k}");
        finite(case, &key("approach"), f.approach)?;
        finite(case, &key("initial_gap"), f.initial_gap)?;
        if !(f.viscosity >= 0.0 && f.viscosity.is_finite()) {
            return Err(case.error(key("viscosity"), "must be a finite number >= 0"));
        }
        if !(f.max_viscous_share > 0.0 && f.max_viscous_share <= 1.0) {
            return Err(case.error(key("max_viscous_share"), "must be a fraction in (0, 1]"));
        }
        if let Some(v) = f.shear_stiffness.filter(|v| !(v.is_finite() && *v >= 0.0)) {
            return Err(case.error(key("shear_stiffness"), format!("must be a finite number >= 0, got {v}")));
        }
        for (k, v) in &f.parameters {
            finite(case, &format!("interfaces[{i}].parameters.{k}"), *v)?;
        }
        if let Some(p) = &f.points {
            points(case, &key("points"), p)?;
        }
        if let Some(r) = &f.resistance {
            if f.kind != "rigid-flat" {
                return Err(
                    case.error(key("resistance"), "the contact resistance is computed for rigid-flat interfaces only")
                );
            }
            positive(case, &key("resistance.resistivity"), r.resistivity)?;
            for (k, v) in
                [("mean_free_path", r.mean_free_path), ("film_specific_resistance", r.film_specific_resistance)]
            {
                if !(v.is_finite() && v >= 0.0) {
                    return Err(
                        case.error(key(&format!("resistance.{k}")), format!("must be a finite number >= 0, got {v}"))
                    );
                }
            }
            if let Some(v) = r.counter_resistivity {
                positive(case, &key("resistance.counter_resistivity"), v)?;
            }
            if let Some(v) = r.counter_mean_free_path.filter(|v| !(v.is_finite() && *v >= 0.0)) {
                return Err(case.error(
                    key("resistance.counter_mean_free_path"),
                    format!("must be a finite number >= 0, got {v}"),
                ));
            }
            metres_per_length_unit(case, &key("resistance"))?;
        }
    }
    Ok(())
}

/// The numbers of a generated layout of discrete points.
fn points(case: &LoadedCase, key: &str, p: &super::PointsSpec) -> Result<()> {
    for (k, v) in [("density", p.density), ("region_radius", p.region_radius), ("height", p.height)] {
        if let Some(v) = v {
            positive(case, &format!("{key}.{k}"), v)?;
        }
    }
    for (k, v) in [("min_spacing", p.min_spacing), ("height_std", p.height_std), ("footprint_area", p.footprint_area)] {
        if !(v.is_finite() && v >= 0.0) {
            return Err(case.error(format!("{key}.{k}"), format!("must be a finite number >= 0, got {v}")));
        }
    }
    if let Some(map) = &p.surface {
        let generator = [("file", p.file.is_some()), ("density", p.density.is_some()), ("height", p.height.is_some())];
        if let Some((k, _)) = generator.iter().find(|(_, given)| *given) {
            return Err(case.error(
                format!("{key}.{k}"),
                "the points come from the height map (surface): give the map or this key, not both",
            ));
        }
        if p.height_std != 0.0 {
            return Err(case.error(format!("{key}.height_std"), "the heights come from the height map (surface)"));
        }
        if !(map.threshold.is_finite() && map.threshold >= 0.0) {
            return Err(case.error(
                format!("{key}.surface.threshold"),
                format!(
                    "must be a finite number >= 0, got {}: the map's mean plane is the body's surface, and a summit below it would lie inside the body",
                    map.threshold
                ),
            ));
        }
        if let Some(d) = map.pixel_size {
            positive(case, &format!("{key}.surface.pixel_size"), d)?;
        }
        if let Some(c) = map.centre.filter(|c| !c.iter().all(|x| x.is_finite())) {
            return Err(case.error(format!("{key}.surface.centre"), format!("must be two finite numbers, got {c:?}")));
        }
    }
    if let Some(c) = &p.footprint_correction {
        if !(p.footprint_area > 0.0) {
            return Err(case.error(
                format!("{key}.footprint_correction"),
                "corrects a footprint the mesh does not resolve: give footprint_area (> 0) too",
            ));
        }
        if let Some(v) = c.compliance.filter(|v| !(v.is_finite() && *v >= 0.0)) {
            return Err(case.error(
                format!("{key}.footprint_correction.compliance"),
                format!("must be a finite number >= 0, got {v}"),
            ));
        }
        if let Some(v) = c.limit_force.filter(|v| !(v.is_finite() && *v > 0.0)) {
            return Err(case.error(
                format!("{key}.footprint_correction.limit_force"),
                format!("must be a finite number > 0, got {v}"),
            ));
        }
        let pressure_key = format!("{key}.footprint_correction.limit_pressure");
        match &c.limit_pressure {
            Some(_) if c.limit_force.is_some() => {
                return Err(case.error(
                    pressure_key,
                    "the footprint's limit is given twice (limit_force and limit_pressure): give one of them",
                ));
            }
            Some(LimitPressure::Value(v)) if !(v.is_finite() && *v > 0.0) => {
                return Err(case.error(pressure_key, format!("must be a finite number > 0, got {v}")));
            }
            Some(LimitPressure::Named(name)) if name != VON_MISES_DISC => {
                return Err(case.error(
                    pressure_key,
                    format!("must be a pressure (a number > 0) or \"{VON_MISES_DISC}\", got \"{name}\""),
                ));
            }
            _ => {}
        }
    }
    Ok(())
}

/// The case's length unit in metres, for keys given in SI (the contact resistance's
/// resistivity).
pub fn metres_per_length_unit(case: &LoadedCase, key: &str) -> Result<f64> {
    use stiction_interfaces::height_map::{LENGTH_UNITS, metres_per_unit};
    match case.case.units.as_ref().map(|u| u.length.as_str()) {
        Some(unit) => metres_per_unit(unit).ok_or_else(|| {
            case.error(
                key,
                format!(
                    "needs the case's length unit in metres, but units.length = '{unit}' is not one of {LENGTH_UNITS}"
                ),
            )
        }),
        None => {
            Err(case.error(key, format!("needs [units] length (one of {LENGTH_UNITS}) to convert its SI or map units")))
        }
    }
}
