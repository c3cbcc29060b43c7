//! The closing lines `stiction run` prints: plain numbers with 4 significant figures, forces
//! with the SI prefix that keeps them between 1 and 1000 (the Ru cases: uN), areas in the
//! case's length unit squared, and the case's units stated.

use stiction_core::record::RunSummary;

/// `value` with 4 significant figures, without an exponent for magnitudes 1e-3 .. 1e6.
pub fn significant(value: f64) -> String {
    if value == 0.0 || !value.is_finite() {
        return format!("{value}");
    }
    let magnitude = value.abs().log10().floor() as i32;
    if !(-3..6).contains(&magnitude) {
        return format!("{value:.3e}");
    }
    let decimals = (3 - magnitude).max(0) as usize;
    format!("{value:.decimals$}")
}

const PREFIXES: [(&str, f64); 7] =
    [("f", 1e-15), ("p", 1e-12), ("n", 1e-9), ("u", 1e-6), ("m", 1e-3), ("", 1.0), ("k", 1e3)];

/// A force in `unit` (e.g. "nN"), rescaled to the prefix that puts it in [1, 1000).
pub fn force(value: f64, unit: &str) -> String {
    let Some(base) = unit.strip_suffix('N') else {
        return format!("{} {unit}", significant(value)).trim_end().to_string();
    };
    let Some(&(_, factor)) = PREFIXES.iter().find(|(p, _)| *p == base) else {
        return format!("{} {unit}", significant(value));
    };
    let si = value * factor;
    let best = PREFIXES.iter().rev().find(|(_, f)| si.abs() >= *f).unwrap_or(&PREFIXES[0]);
    let shown = if value == 0.0 { (unit.to_string(), value) } else { (format!("{}N", best.0), si / best.1) };
    format!("{} {}", significant(shown.1), shown.0)
}

/// The lines printed after a run.
pub fn summary_lines(summary: &RunSummary) -> Vec<String> {
    let mut arc = if summary.arc_length_increments > 0 {
        format!(
            "; {} by path following (arc length or dissipation) through {} limit points",
            summary.arc_length_increments, summary.limit_points
        )
    } else {
        String::new()
    };
    if summary.snaps > 0 {
        arc.push_str(&format!("; {} snapped to a stable state ({})", summary.snaps, summary.snap_method));
    }
    let mut lines = vec![format!(
        "{}: {} increments ({} cut{arc}), {} iterations (Newton or quasi-Newton), {} factorizations, {} s on {} thread{} ({} s in attempts not committed); {} free dofs; output in {}",
        summary.case,
        summary.increments,
        summary.cut_increments,
        summary.newton_iterations,
        summary.factorizations,
        significant(summary.wall_seconds),
        summary.threads,
        if summary.threads == 1 { "" } else { "s" },
        significant(summary.discarded_attempt_seconds),
        summary.n_free_dofs,
        summary.output_directory.display()
    )];
    let (length, force_unit) = (summary.units.length.as_str(), summary.units.force.as_str());
    let area = if length.is_empty() { String::new() } else { format!(" {length}^2") };
    let at =
        |a: f64| format!("{}{}", significant(a), if length.is_empty() { String::new() } else { format!(" {length}") });
    let units = if length.is_empty() && force_unit.is_empty() {
        "(case units; state them with [units] length and force)".to_string()
    } else {
        format!("(case units: length {length}, force {force_unit}; compressive positive)")
    };
    lines.push(format!("  interfaces {units}"));
    for i in &summary.interfaces {
        if i.kind == "cohesive" {
            // zero-thickness elements: no approach; separated or still carrying its force
            let state = if i.separated {
                "separated".to_string()
            } else {
                format!("not separated: force {} at the end", force(i.final_force, force_unit))
            };
            lines.push(format!(
                "  {}: most compressive force {}; most tensile force {}; {state}; max contact area {}{area}",
                i.name,
                force(i.max_force, force_unit),
                force(i.most_tensile_force, force_unit),
                significant(i.max_contact_area)
            ));
        } else {
            // "pull-off" only where the interface separated; otherwise where it held at the end
            let tensile = if i.separated {
                format!(
                    "pull-off {} at {}",
                    force(i.most_tensile_force, force_unit),
                    at(i.approach_at_most_tensile_force)
                )
            } else if i.contact_events == 0 && i.final_n_contact == 0 {
                format!(
                    "never in contact; most tensile force {} at {}",
                    force(i.most_tensile_force, force_unit),
                    at(i.approach_at_most_tensile_force)
                )
            } else {
                // a smooth law's tail (or a drawn-out neck) can hold with no point in contact
                let holding = match i.final_n_contact {
                    0 => "no point in contact but still pulling".to_string(),
                    n => format!("{n} points in contact"),
                };
                format!(
                    "not separated: {holding}, force {} at approach {} at the end; most tensile force {} at {}",
                    force(i.final_force, force_unit),
                    at(i.final_approach),
                    force(i.most_tensile_force, force_unit),
                    at(i.approach_at_most_tensile_force)
                )
            };
            lines.push(format!(
                "  {}: max force {} at approach {}; {tensile}; max real area {}{area}; {} in contact at max",
                i.name,
                force(i.max_force, force_unit),
                at(i.approach_at_max_force),
                significant(i.max_contact_area),
                i.n_contact_at_max_force
            ));
            if let Some(r) = i.contact_resistance_at_max_force {
                let half = i.contact_resistance_at_force.iter().find(|h| h.fraction_of_max_force == 0.5);
                let ohm = |r: Option<f64>| r.map_or("-".to_string(), |r| format!("{} ohm", significant(r)));
                let hysteresis = half.map_or(String::new(), |h| {
                    format!("; at half the max force {} loading, {} unloading", ohm(h.loading), ohm(h.unloading))
                });
                lines.push(format!("  {}: contact resistance {} at max force{hysteresis}", i.name, ohm(Some(r))));
            }
            if !i.folds.is_empty() {
                let folds: Vec<String> =
                    i.folds.iter().map(|f| format!("{} ({})", at(f.approach), force(f.force, force_unit))).collect();
                lines.push(format!("  {}: folds (limit points) at approach {}", i.name, folds.join(", ")));
            }
        }
    }
    if summary.interfaces.is_empty() {
        lines.pop();
    }
    lines
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn forces_get_a_readable_prefix_and_four_significant_figures() {
        assert_eq!(force(22386.0, "nN"), "22.39 uN");
        assert_eq!(force(-28489.0, "nN"), "-28.49 uN");
        assert_eq!(force(5.2437, "nN"), "5.244 nN");
        assert_eq!(force(1.5e7, "nN"), "15.00 mN");
        assert_eq!(force(0.5, "N"), "500.0 mN");
        assert_eq!(force(12.0, ""), "12.00");
        assert_eq!(significant(974.79), "974.8");
        assert_eq!(significant(0.0250), "0.02500");
    }

    /// A body drawn out under a smooth law's tail holds with no point in contact: the line says
    /// so rather than "0 points in contact" beside "not separated".
    #[test]
    fn an_attached_interface_with_no_point_in_contact_says_it_still_pulls() {
        let interface = |final_n_contact| stiction_core::record::InterfaceSummary {
            name: "flat".into(),
            kind: "rigid-flat".into(),
            max_force: 31170.0,
            most_tensile_force: -90852.0,
            final_force: -90852.0,
            final_approach: -3.0,
            final_n_contact,
            contact_events: 4,
            ..Default::default()
        };
        for (n, expected) in [
            (0, "not separated: no point in contact but still pulling, force -90.85 uN at approach -3.000 nm"),
            (103, "not separated: 103 points in contact, force -90.85 uN at approach -3.000 nm"),
        ] {
            let mut summary = RunSummary { interfaces: vec![interface(n)], ..Default::default() };
            summary.units.length = "nm".into();
            summary.units.force = "nN".into();
            let lines = summary_lines(&summary).join("\n");
            assert!(lines.contains(expected), "{lines}");
        }
    }
}
