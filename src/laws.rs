//! The interface laws a case can name, with their parameter lists. Laws are linked statically
//! here; the plugin ABI (dynamic loading of users' laws) is tracked in the interfaces issue.

use std::sync::Arc;
use stiction_core::interface_law::{InterfaceLaw, ParameterSpec, resolve_parameters};

/// Context a law may need for defaults.
pub struct LawContext {
    /// Largest stiffness scale (Young's modulus) of the materials.
    pub modulus: f64,
    /// Typical face size of the interface surface.
    pub face_size: f64,
}

/// Names and parameter lists of the known laws.
pub fn known_laws() -> Vec<(&'static str, Vec<ParameterSpec>)> {
    vec![
        (stiction_law_frictionless_contact::NAME, stiction_law_frictionless_contact::parameters()),
        (stiction_law_lennard_jones::NAME, stiction_law_lennard_jones::parameters()),
    ]
}

/// Creates a law from its name and parameters (validated against its parameter list).
pub fn make_law(name: &str, given: &[(String, f64)], context: &LawContext) -> Result<Arc<dyn InterfaceLaw>, String> {
    let laws = known_laws();
    let Some((_, specs)) = laws.iter().find(|(n, _)| *n == name) else {
        let names: Vec<&str> = laws.iter().map(|(n, _)| *n).collect();
        return Err(format!("unknown interface law '{name}' (known: {})", names.join(", ")));
    };
    let values = resolve_parameters(name, specs, given)?;
    Ok(match name {
        stiction_law_frictionless_contact::NAME => {
            let k = if values[0] > 0.0 { values[0] } else { 100.0 * context.modulus / context.face_size };
            Arc::new(stiction_law_frictionless_contact::FrictionlessContact::new(k).map_err(|e| e.0)?)
        }
        stiction_law_lennard_jones::NAME => {
            Arc::new(stiction_law_lennard_jones::LennardJones::new(values[0], values[1]).map_err(|e| e.0)?)
        }
        _ => unreachable!("listed above"),
    })
}
