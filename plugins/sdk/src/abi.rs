//! The versioned C ABI between the Stiction host and interface-law plugins.
//!
//! A plugin exports `extern "C" fn stiction_law_descriptor() -> *const LawDescriptor`. The host
//! reads `abi_version` and `struct_size` (the first two fields, fixed for every version) before
//! touching anything else, and refuses a mismatch. All functions return 0 on success, 1 on an
//! error (message written to the caller's buffer) and 2 when the law panicked (the panic is
//! caught here, never unwinds into the host).

use crate::panic_guard::guarded;
use crate::{Law, MixedResponse, Response};
use std::ffi::{CStr, c_char, c_void};

/// Version of this ABI. Bump on any change of the structs or function signatures below.
/// Version 2 added mixed-mode laws: `gap_dimension` and `evaluate_mixed`.
pub const ABI_VERSION: u32 = 2;

pub const STATUS_OK: i32 = 0;
pub const STATUS_ERROR: i32 = 1;
pub const STATUS_PANIC: i32 = 2;

/// A parameter as seen through the ABI.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct AbiParameter {
    pub name: *const c_char,
    pub unit: *const c_char,
    pub description: *const c_char,
    /// 1 if `default_value` is meaningful, 0 if the parameter is required.
    pub has_default: u32,
    pub default_value: f64,
    pub min: f64,
    pub max: f64,
}

/// The result of one evaluation as seen through the ABI.
#[repr(C)]
#[derive(Debug, Clone, Copy, Default)]
pub struct AbiResponse {
    pub value: f64,
    pub tangent: f64,
    pub in_contact: u32,
    pub area: f64,
}

/// The result of one mixed-mode evaluation as seen through the ABI (local frame: normal,
/// tangential 1, tangential 2; `tangent` row-major, tangent[3 i + j] = d value_i / d gap_j).
#[repr(C)]
#[derive(Debug, Clone, Copy, Default)]
pub struct AbiMixedResponse {
    pub value: [f64; 3],
    pub tangent: [f64; 9],
    pub in_contact: u32,
    pub area: f64,
}

pub type CreateFn = unsafe extern "C" fn(
    parameters: *const f64,
    n_parameters: u32,
    config: *const c_char,
    instance: *mut *mut c_void,
    message: *mut c_char,
    message_len: usize,
) -> i32;
pub type DestroyFn = unsafe extern "C" fn(instance: *mut c_void);
pub type InitializeStateFn = unsafe extern "C" fn(instance: *const c_void, state: *mut f64) -> i32;
pub type EvaluateFn = unsafe extern "C" fn(
    instance: *const c_void,
    gap: f64,
    state_committed: *const f64,
    state_trial: *mut f64,
    response: *mut AbiResponse,
    message: *mut c_char,
    message_len: usize,
) -> i32;

pub type EvaluateMixedFn = unsafe extern "C" fn(
    instance: *const c_void,
    gap: *const f64,
    state_committed: *const f64,
    state_trial: *mut f64,
    response: *mut AbiMixedResponse,
    message: *mut c_char,
    message_len: usize,
) -> i32;

/// Everything the host needs to use a law.
#[repr(C)]
#[derive(Debug)]
pub struct LawDescriptor {
    /// Always first: [`ABI_VERSION`] of the plugin's SDK.
    pub abi_version: u32,
    /// Always second: `size_of::<LawDescriptor>()` in the plugin.
    pub struct_size: u32,
    pub name: *const c_char,
    pub version: *const c_char,
    /// 0: traction per area, 1: force per point.
    pub kind: u32,
    pub n_state: u32,
    /// 1: normal gap only; 3: mixed mode (`evaluate_mixed` gives a traction vector).
    pub gap_dimension: u32,
    pub n_parameters: u32,
    pub parameters: *const AbiParameter,
    /// `n_state` names (may be null when the law gives none).
    pub state_names: *const *const c_char,
    /// What the configuration text passed to `create` is; null when the law takes none.
    pub config_description: *const c_char,
    pub create: CreateFn,
    pub destroy: DestroyFn,
    pub initialize_state: InitializeStateFn,
    pub evaluate: EvaluateFn,
    /// Gap: 3 values (normal, tangential 1, tangential 2). Normal-only laws answer with the
    /// normal law and zero tangential value.
    pub evaluate_mixed: EvaluateMixedFn,
}

/// Owns a descriptor and the arrays it points into (for the `export_law!` macro).
pub struct DescriptorHolder {
    descriptor: LawDescriptor,
    _parameters: Vec<AbiParameter>,
    _state_names: Vec<*const c_char>,
}

// SAFETY: the holder is immutable after construction and its pointers refer to 'static C
// strings and to vectors it owns (heap storage that never moves).
unsafe impl Send for DescriptorHolder {}
unsafe impl Sync for DescriptorHolder {}

impl DescriptorHolder {
    pub fn new<L: Law>() -> Self {
        let parameters: Vec<AbiParameter> = L::parameters()
            .iter()
            .map(|p| AbiParameter {
                name: p.name.as_ptr(),
                unit: p.unit.as_ptr(),
                description: p.description.as_ptr(),
                has_default: p.default.is_some() as u32,
                default_value: p.default.unwrap_or(0.0),
                min: p.min,
                max: p.max,
            })
            .collect();
        let state_names: Vec<*const c_char> = L::state_names().iter().map(|s| s.as_ptr()).collect();
        let descriptor = LawDescriptor {
            abi_version: ABI_VERSION,
            struct_size: size_of::<LawDescriptor>() as u32,
            name: L::NAME.as_ptr(),
            version: L::VERSION.as_ptr(),
            kind: L::KIND as u32,
            n_state: L::N_STATE as u32,
            gap_dimension: L::GAP_DIMENSION as u32,
            n_parameters: parameters.len() as u32,
            parameters: parameters.as_ptr(),
            state_names: if state_names.len() == L::N_STATE && !state_names.is_empty() {
                state_names.as_ptr()
            } else {
                std::ptr::null()
            },
            config_description: L::config_description().map_or(std::ptr::null(), |c| c.as_ptr()),
            create: create::<L>,
            destroy: destroy::<L>,
            initialize_state: initialize_state::<L>,
            evaluate: evaluate::<L>,
            evaluate_mixed: evaluate_mixed::<L>,
        };
        Self { descriptor, _parameters: parameters, _state_names: state_names }
    }

    pub fn descriptor(&self) -> *const LawDescriptor {
        &self.descriptor
    }
}

/// Writes `text` into a caller buffer, truncated and NUL-terminated.
fn write_message(text: &str, buffer: *mut c_char, len: usize) {
    if buffer.is_null() || len == 0 {
        return;
    }
    let bytes = text.as_bytes();
    let n = bytes.len().min(len - 1);
    // SAFETY: the caller gives a writable buffer of `len` bytes.
    unsafe {
        std::ptr::copy_nonoverlapping(bytes.as_ptr() as *const c_char, buffer, n);
        *buffer.add(n) = 0;
    }
}

unsafe extern "C" fn create<L: Law>(
    parameters: *const f64,
    n_parameters: u32,
    config: *const c_char,
    instance: *mut *mut c_void,
    message: *mut c_char,
    message_len: usize,
) -> i32 {
    let result = guarded(|| {
        // SAFETY: the host passes n_parameters values.
        let p = if n_parameters == 0 {
            &[][..]
        } else {
            unsafe { std::slice::from_raw_parts(parameters, n_parameters as usize) }
        };
        // SAFETY: null or a NUL-terminated UTF-8 string owned by the host for this call.
        let text = if config.is_null() { "" } else { unsafe { CStr::from_ptr(config) }.to_str().unwrap_or("") };
        L::create(p, text)
    });
    let write = |law: L| {
        // SAFETY: `instance` is a valid out-pointer.
        unsafe { *instance = Box::into_raw(Box::new(law)) as *mut c_void };
    };
    finish("create", result, write, message, message_len)
}

unsafe extern "C" fn destroy<L: Law>(instance: *mut c_void) {
    if !instance.is_null() {
        let _ = guarded(|| {
            // SAFETY: created by `create::<L>` through Box::into_raw.
            drop(unsafe { Box::from_raw(instance as *mut L) });
        });
    }
}

unsafe extern "C" fn initialize_state<L: Law>(instance: *const c_void, state: *mut f64) -> i32 {
    let r = guarded(|| {
        // SAFETY: a live instance and a state buffer of N_STATE values.
        let law = unsafe { &*(instance as *const L) };
        let s =
            if L::N_STATE == 0 { &mut [][..] } else { unsafe { std::slice::from_raw_parts_mut(state, L::N_STATE) } };
        law.initialize_state(s);
    });
    if r.is_ok() { STATUS_OK } else { STATUS_PANIC }
}

/// Runs `f` on the instance and the state slices behind the C pointers, catching panics.
///
/// # Safety
/// `instance` is a live instance of `L`; each state pointer addresses `L::N_STATE` values.
unsafe fn with_states<L: Law, R>(
    instance: *const c_void,
    state_committed: *const f64,
    state_trial: *mut f64,
    f: impl FnOnce(&L, &[f64], &mut [f64]) -> Result<R, String>,
) -> Result<Result<R, String>, String> {
    guarded(|| {
        // SAFETY: guaranteed by the caller.
        let law = unsafe { &*(instance as *const L) };
        let (old, new) = if L::N_STATE == 0 {
            (&[][..], &mut [][..])
        } else {
            unsafe {
                (
                    std::slice::from_raw_parts(state_committed, L::N_STATE),
                    std::slice::from_raw_parts_mut(state_trial, L::N_STATE),
                )
            }
        };
        f(law, old, new)
    })
}

/// Writes the outcome of the call `what`: the result through `write`, or the error or panic
/// text into the caller's message buffer; returns the status.
fn finish<R>(
    what: &str,
    result: Result<Result<R, String>, String>,
    write: impl FnOnce(R),
    message: *mut c_char,
    message_len: usize,
) -> i32 {
    match result {
        Ok(Ok(r)) => {
            write(r);
            STATUS_OK
        }
        Ok(Err(e)) => {
            write_message(&e, message, message_len);
            STATUS_ERROR
        }
        Err(p) => {
            write_message(&format!("panic in {what}: {p}"), message, message_len);
            STATUS_PANIC
        }
    }
}

unsafe extern "C" fn evaluate<L: Law>(
    instance: *const c_void,
    gap: f64,
    state_committed: *const f64,
    state_trial: *mut f64,
    response: *mut AbiResponse,
    message: *mut c_char,
    message_len: usize,
) -> i32 {
    // SAFETY: the host passes a live instance and N_STATE values in each state buffer.
    let result = unsafe {
        with_states::<L, _>(instance, state_committed, state_trial, |law, old, new| law.evaluate(gap, old, new))
    };
    let write = |Response { value, tangent, in_contact, area }: Response| {
        // SAFETY: `response` is a valid out-pointer.
        unsafe { *response = AbiResponse { value, tangent, in_contact: in_contact as u32, area } };
    };
    finish("evaluate", result, write, message, message_len)
}

unsafe extern "C" fn evaluate_mixed<L: Law>(
    instance: *const c_void,
    gap: *const f64,
    state_committed: *const f64,
    state_trial: *mut f64,
    response: *mut AbiMixedResponse,
    message: *mut c_char,
    message_len: usize,
) -> i32 {
    // SAFETY: the host passes 3 gap values, a live instance and N_STATE values per state buffer.
    let gap = unsafe { [*gap, *gap.add(1), *gap.add(2)] };
    let result = unsafe {
        with_states::<L, _>(instance, state_committed, state_trial, |law, old, new| law.evaluate_mixed(gap, old, new))
    };
    let write = |MixedResponse { value, tangent, in_contact, area }: MixedResponse| {
        let flat = std::array::from_fn(|k| tangent[k / 3][k % 3]);
        // SAFETY: `response` is a valid out-pointer.
        unsafe { *response = AbiMixedResponse { value, tangent: flat, in_contact: in_contact as u32, area } };
    };
    finish("evaluate", result, write, message, message_len)
}

/// Reads a C string from a descriptor field ("" when null).
///
/// # Safety
/// `p` is null or a NUL-terminated string that outlives the returned reference.
pub unsafe fn c_str<'a>(p: *const c_char) -> &'a str {
    if p.is_null() { "" } else { unsafe { CStr::from_ptr(p) }.to_str().unwrap_or("<not UTF-8>") }
}
