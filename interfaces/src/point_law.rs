//! Evaluating a law at one interface point, shared by every interface geometry: the law's
//! error and any non-finite result become errors naming the interface, the point and the gap.

use stiction_core::CoreError;
use stiction_core::interface_law::{InterfaceLaw, LawResponse, MixedLawResponse};

/// Initial states of `n_points` points (`law.n_state()` numbers each), from the law.
pub fn initial_states(law: &dyn InterfaceLaw, n_points: usize) -> Vec<f64> {
    let ns = law.n_state();
    let mut state = vec![0.0; n_points * ns];
    if ns > 0 {
        for s in state.chunks_exact_mut(ns) {
            law.initialize_state(s);
        }
    }
    state
}

/// The law's own error (or caught panic) at point `index` (0-based) of `interface`.
/// `at` says where: the gap or the opening.
fn law_failure(law: &dyn InterfaceLaw, interface: &str, index: usize, at: String, message: String) -> CoreError {
    let (law, interface) = (law.name().to_string(), interface.to_string());
    CoreError::LawFailure { law, interface, point: index + 1, at, message }
}

/// The law at gap `g` for point `index` (0-based) of `interface`, from its committed state
/// (`ns` numbers per point) into the trial state.
pub fn evaluate_point(
    law: &dyn InterfaceLaw,
    interface: &str,
    index: usize,
    g: f64,
    committed: &[f64],
    trial: &mut [f64],
) -> Result<LawResponse, CoreError> {
    let ns = law.n_state();
    let r = law
        .evaluate(g, &committed[index * ns..(index + 1) * ns], &mut trial[index * ns..(index + 1) * ns])
        .map_err(|e| law_failure(law, interface, index, format!("gap {g:e}"), e.0))?;
    if !r.value.is_finite() || !r.tangent.is_finite() {
        return Err(CoreError::NonFinite(format!(
            "value of law '{}' at point {} of interface '{interface}' (gap {g:e})",
            law.name(),
            index + 1
        )));
    }
    Ok(r)
}

/// The mixed-mode law at the local opening `gap` (normal, tangential 1, tangential 2) for point
/// `index` of `interface`; errors as in [`evaluate_point`].
pub fn evaluate_point_mixed(
    law: &dyn InterfaceLaw,
    interface: &str,
    index: usize,
    gap: [f64; 3],
    committed: &[f64],
    trial: &mut [f64],
) -> Result<MixedLawResponse, CoreError> {
    let ns = law.n_state();
    let r = law
        .evaluate_mixed(gap, &committed[index * ns..(index + 1) * ns], &mut trial[index * ns..(index + 1) * ns])
        .map_err(|e| law_failure(law, interface, index, format!("opening {gap:?}"), e.0))?;
    if r.value.iter().chain(r.tangent.iter().flatten()).any(|v| !v.is_finite()) {
        return Err(CoreError::NonFinite(format!(
            "value of law '{}' at point {} of interface '{interface}' (opening {gap:?})",
            law.name(),
            index + 1
        )));
    }
    Ok(r)
}
