//! Interface-law plugins: loading a law through the C ABI of `stiction-law-sdk`, either from a
//! shared library (dlopen through libloading) or from a statically linked descriptor, and
//! using it as a core [`InterfaceLaw`].
//!
//! Safety of the boundary: the host reads only `abi_version` and `struct_size` until both
//! match; every call's status is checked; plugin panics are caught on the plugin side; non-finite
//! results are errors naming the law.

use libloading::Library;
use std::ffi::{c_char, c_void};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use stiction_core::interface_law::{InterfaceLaw, LawError, LawKind, LawResponse, MixedLawResponse, ParameterSpec};
use stiction_law_sdk::abi::{self, ABI_VERSION, AbiMixedResponse, AbiResponse, LawDescriptor, STATUS_OK, STATUS_PANIC};

/// The symbol every plugin exports.
pub const ENTRY_POINT: &[u8] = b"stiction_law_descriptor\0";

/// Plugin failures; each names the library and what was expected.
#[derive(Debug, thiserror::Error)]
pub enum PluginError {
    #[error("cannot load plugin '{path}': {message}")]
    Load { path: PathBuf, message: String },
    #[error("'{path}' is not a Stiction law plugin: it has no symbol 'stiction_law_descriptor'")]
    NoEntryPoint { path: PathBuf },
    #[error(
        "plugin '{path}' was built for law ABI version {found}; this Stiction speaks version {expected}. Rebuild the plugin against stiction-law-sdk {expected}"
    )]
    AbiVersion { path: PathBuf, found: u32, expected: u32 },
    #[error(
        "plugin '{path}' has a descriptor of {found} bytes, expected at least {expected} for ABI version {version}"
    )]
    StructSize { path: PathBuf, found: u32, expected: u32, version: u32 },
    #[error("law '{law}' ({path}): {message}")]
    Create { law: String, path: String, message: String },
}

/// A law's descriptor plus the library that holds it (None when statically linked).
pub struct LawLibrary {
    descriptor: *const LawDescriptor,
    _library: Option<Library>,
    /// Where it came from ("built in" for static laws).
    pub origin: String,
    pub name: String,
    pub version: String,
    pub kind: LawKind,
    pub n_state: usize,
    /// 1: normal gap only; 3: mixed mode.
    pub gap_dimension: usize,
    pub parameters: Vec<ParameterSpec>,
    pub state_names: Vec<String>,
    /// What the law's configuration text is, if it takes one.
    pub config_description: Option<String>,
}

// SAFETY: the descriptor is immutable static data of the library, which this struct keeps loaded;
// the ABI requires its functions to be callable from any thread.
unsafe impl Send for LawLibrary {}
unsafe impl Sync for LawLibrary {}

/// libloading's error with the loader's own reason (dlerror), which its `Display` leaves out.
fn loader_reason(e: &libloading::Error) -> String {
    match std::error::Error::source(e) {
        Some(reason) => format!("{e}: {reason}"),
        None => e.to_string(),
    }
}

impl LawLibrary {
    /// Opens a plugin shared library and checks its ABI before using it.
    pub fn open(path: &Path) -> Result<Self, PluginError> {
        // SAFETY: loading a library runs its initialisers; plugins are trusted code chosen by
        // the user, as with any dlopen-based plugin system.
        if !path.is_file() {
            let message = if path.exists() { "not a file" } else { "no such file" };
            return Err(PluginError::Load { path: path.to_path_buf(), message: message.into() });
        }
        let library = unsafe { Library::new(path) }
            .map_err(|e| PluginError::Load { path: path.to_path_buf(), message: loader_reason(&e) })?;
        let descriptor = {
            // SAFETY: the symbol's type is fixed by the ABI.
            let entry = unsafe { library.get::<unsafe extern "C" fn() -> *const LawDescriptor>(ENTRY_POINT) }
                .map_err(|_| PluginError::NoEntryPoint { path: path.to_path_buf() })?;
            unsafe { entry() }
        };
        // SAFETY: checked by `from_descriptor` before any field past the first two is read.
        unsafe { Self::from_descriptor(descriptor, Some(library), path.display().to_string()) }
    }

    /// Wraps a statically linked law's descriptor (the law crate's `stiction_law_descriptor`
    /// function, or `DescriptorHolder::new::<L>()`).
    ///
    /// # Safety
    /// `descriptor` must point to a descriptor that lives for the whole program.
    pub unsafe fn from_static(descriptor: *const LawDescriptor) -> Result<Self, PluginError> {
        unsafe { Self::from_descriptor(descriptor, None, "built in".into()) }
    }

    unsafe fn from_descriptor(
        descriptor: *const LawDescriptor,
        library: Option<Library>,
        origin: String,
    ) -> Result<Self, PluginError> {
        let path = PathBuf::from(&origin);
        if descriptor.is_null() {
            return Err(PluginError::Load { path, message: "the entry point returned a null descriptor".into() });
        }
        // Read the two fixed leading fields only.
        let header = descriptor as *const u32;
        let (abi_version, struct_size) = unsafe { (*header, *header.add(1)) };
        if abi_version != ABI_VERSION {
            return Err(PluginError::AbiVersion { path, found: abi_version, expected: ABI_VERSION });
        }
        let expected = size_of::<LawDescriptor>() as u32;
        if struct_size < expected {
            return Err(PluginError::StructSize { path, found: struct_size, expected, version: abi_version });
        }
        let d = unsafe { &*descriptor };
        let kind = match d.kind {
            0 => LawKind::TractionPerArea,
            1 => LawKind::ForcePerPoint,
            k => return Err(PluginError::Load { path, message: format!("unknown law kind {k}") }),
        };
        if d.gap_dimension != 1 && d.gap_dimension != 3 {
            return Err(PluginError::Load {
                path,
                message: format!("gap dimension {} (expected 1, normal only, or 3, mixed mode)", d.gap_dimension),
            });
        }
        let parameters = (0..d.n_parameters as usize)
            .map(|i| {
                let p = unsafe { &*d.parameters.add(i) };
                unsafe {
                    ParameterSpec {
                        name: abi::c_str(p.name).to_string(),
                        unit: abi::c_str(p.unit).to_string(),
                        description: abi::c_str(p.description).to_string(),
                        default: (p.has_default != 0).then_some(p.default_value),
                        min: p.min,
                        max: p.max,
                    }
                }
            })
            .collect();
        let state_names = if d.state_names.is_null() {
            (0..d.n_state).map(|i| format!("state_{i}")).collect()
        } else {
            (0..d.n_state as usize).map(|i| unsafe { abi::c_str(*d.state_names.add(i)) }.to_string()).collect()
        };
        Ok(Self {
            descriptor,
            _library: library,
            origin,
            name: unsafe { abi::c_str(d.name) }.to_string(),
            version: unsafe { abi::c_str(d.version) }.to_string(),
            kind,
            n_state: d.n_state as usize,
            gap_dimension: d.gap_dimension as usize,
            parameters,
            state_names,
            config_description: (!d.config_description.is_null())
                .then(|| unsafe { abi::c_str(d.config_description) }.to_string()),
        })
    }

    /// Creates an instance with parameter values in `self.parameters` order and the law's
    /// configuration text (empty when none).
    pub fn instantiate(self: &Arc<Self>, values: &[f64], config: &str) -> Result<AbiLaw, PluginError> {
        let d = unsafe { &*self.descriptor };
        let mut instance: *mut c_void = std::ptr::null_mut();
        let mut message = [0 as c_char; 1024];
        let config = std::ffi::CString::new(config).map_err(|_| PluginError::Create {
            law: self.name.clone(),
            path: self.origin.clone(),
            message: "the configuration text contains a NUL byte".into(),
        })?;
        let status = unsafe {
            (d.create)(
                values.as_ptr(),
                values.len() as u32,
                config.as_ptr(),
                &mut instance,
                message.as_mut_ptr(),
                message.len(),
            )
        };
        if status != STATUS_OK || instance.is_null() {
            let text = unsafe { abi::c_str(message.as_ptr()) }.to_string();
            return Err(PluginError::Create { law: self.name.clone(), path: self.origin.clone(), message: text });
        }
        Ok(AbiLaw { library: self.clone(), instance })
    }
}

/// A law instance behind the C ABI, usable as a core [`InterfaceLaw`].
pub struct AbiLaw {
    library: Arc<LawLibrary>,
    instance: *mut c_void,
}

// SAFETY: the ABI requires `evaluate` to be callable concurrently (it does not mutate the
// instance); create/destroy happen once, on the owning thread.
unsafe impl Send for AbiLaw {}
unsafe impl Sync for AbiLaw {}

impl Drop for AbiLaw {
    fn drop(&mut self) {
        let d = unsafe { &*self.library.descriptor };
        unsafe { (d.destroy)(self.instance) };
    }
}

impl AbiLaw {
    pub fn library(&self) -> &LawLibrary {
        &self.library
    }
}

/// The text a failed call wrote into `message`: the law's own error, or "panic in <call>: ..."
/// for a panic the plugin caught. The caller adds the law, the point and the gap.
fn failure_text(status: i32, message: &[c_char]) -> String {
    // SAFETY: the plugin writes a NUL-terminated string into the buffer (zeroed before the call).
    let text = unsafe { abi::c_str(message.as_ptr()) }.to_string();
    if status == STATUS_PANIC && !text.starts_with("panic") { format!("panic: {text}") } else { text }
}

impl InterfaceLaw for AbiLaw {
    fn name(&self) -> &str {
        &self.library.name
    }
    fn kind(&self) -> LawKind {
        self.library.kind
    }
    fn n_state(&self) -> usize {
        self.library.n_state
    }
    fn initialize_state(&self, state: &mut [f64]) {
        let d = unsafe { &*self.library.descriptor };
        // A panicking initializer leaves zeros, which every law accepts as a fresh state.
        state.fill(0.0);
        let _ = unsafe { (d.initialize_state)(self.instance, state.as_mut_ptr()) };
    }
    fn evaluate(&self, gap: f64, state_committed: &[f64], state_trial: &mut [f64]) -> Result<LawResponse, LawError> {
        let d = unsafe { &*self.library.descriptor };
        debug_assert_eq!(state_committed.len(), self.library.n_state);
        let mut response = AbiResponse::default();
        let mut message = [0 as c_char; 512];
        let status = unsafe {
            (d.evaluate)(
                self.instance,
                gap,
                state_committed.as_ptr(),
                state_trial.as_mut_ptr(),
                &mut response,
                message.as_mut_ptr(),
                message.len(),
            )
        };
        if status != STATUS_OK {
            return Err(LawError(failure_text(status, &message)));
        }
        if !response.value.is_finite() || !response.tangent.is_finite() || !response.area.is_finite() {
            return Err(LawError(format!(
                "a non-finite result (value {}, tangent {}, area {})",
                response.value, response.tangent, response.area
            )));
        }
        if state_trial.iter().any(|s| !s.is_finite()) {
            return Err(LawError("a non-finite state".into()));
        }
        Ok(LawResponse {
            value: response.value,
            tangent: response.tangent,
            in_contact: response.in_contact != 0,
            area: response.area,
        })
    }
    fn state_names(&self) -> Vec<String> {
        self.library.state_names.clone()
    }
    fn gap_dimension(&self) -> usize {
        self.library.gap_dimension
    }
    fn evaluate_mixed(
        &self,
        gap: [f64; 3],
        state_committed: &[f64],
        state_trial: &mut [f64],
    ) -> Result<MixedLawResponse, LawError> {
        let d = unsafe { &*self.library.descriptor };
        debug_assert_eq!(state_committed.len(), self.library.n_state);
        let mut response = AbiMixedResponse::default();
        let mut message = [0 as c_char; 512];
        let status = unsafe {
            (d.evaluate_mixed)(
                self.instance,
                gap.as_ptr(),
                state_committed.as_ptr(),
                state_trial.as_mut_ptr(),
                &mut response,
                message.as_mut_ptr(),
                message.len(),
            )
        };
        if status != STATUS_OK {
            return Err(LawError(failure_text(status, &message)));
        }
        if response.value.iter().chain(&response.tangent).any(|v| !v.is_finite()) || !response.area.is_finite() {
            return Err(LawError(format!("a non-finite result (value {:?})", response.value)));
        }
        if state_trial.iter().any(|s| !s.is_finite()) {
            return Err(LawError("a non-finite state".into()));
        }
        Ok(MixedLawResponse {
            value: response.value,
            tangent: std::array::from_fn(|i| std::array::from_fn(|j| response.tangent[3 * i + j])),
            in_contact: response.in_contact != 0,
            area: response.area,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use stiction_law_sdk::abi::DescriptorHolder;
    use stiction_law_sdk::{Law, Parameter, Response};

    /// A test law: a linear spring that panics for gaps above 1 and returns NaN below -1.
    struct Spring {
        k: f64,
    }
    impl Law for Spring {
        const NAME: &'static std::ffi::CStr = c"spring";
        const VERSION: &'static std::ffi::CStr = c"1.2.3";
        const KIND: stiction_law_sdk::LawKind = stiction_law_sdk::LawKind::TractionPerArea;
        const N_STATE: usize = 1;
        fn parameters() -> Vec<Parameter> {
            vec![Parameter::optional(c"k", c"GPa/nm", c"stiffness", 2.0, 0.0, 10.0)]
        }
        fn create(p: &[f64], _config: &str) -> Result<Self, String> {
            if p[0] == 0.0 { Err("k must not be zero".into()) } else { Ok(Self { k: p[0] }) }
        }
        fn evaluate(&self, gap: f64, old: &[f64], new: &mut [f64]) -> Result<Response, String> {
            if gap > 1.0 {
                panic!("gap too large");
            }
            new[0] = old[0].max(-gap);
            let value = if gap < -1.0 { f64::NAN } else { -self.k * gap };
            Ok(Response { value, tangent: -self.k, in_contact: gap < 0.0, area: 0.0 })
        }
        fn state_names() -> Vec<&'static std::ffi::CStr> {
            vec![c"max_penetration"]
        }
    }

    fn holder() -> &'static DescriptorHolder {
        static H: std::sync::OnceLock<DescriptorHolder> = std::sync::OnceLock::new();
        H.get_or_init(DescriptorHolder::new::<Spring>)
    }

    #[test]
    fn a_law_round_trips_through_the_c_abi() {
        let lib = Arc::new(unsafe { LawLibrary::from_static(holder().descriptor()) }.unwrap());
        assert_eq!((lib.name.as_str(), lib.version.as_str(), lib.n_state), ("spring", "1.2.3", 1));
        assert_eq!(lib.parameters[0].name, "k");
        assert_eq!(lib.parameters[0].default, Some(2.0));
        assert_eq!(lib.state_names, vec!["max_penetration".to_string()]);
        let law = lib.instantiate(&[3.0], "").unwrap();
        let mut state = [0.0];
        let r = law.evaluate(-0.5, &[0.1], &mut state).unwrap();
        assert_eq!((r.value, r.tangent, r.in_contact, state[0]), (1.5, -3.0, true, 0.5));
        let e = lib.instantiate(&[0.0], "").err().unwrap().to_string();
        assert!(e.contains("spring") && e.contains("k must not be zero"), "{e}");
    }

    #[test]
    fn panics_and_non_finite_results_become_errors() {
        let lib = Arc::new(unsafe { LawLibrary::from_static(holder().descriptor()) }.unwrap());
        let law = lib.instantiate(&[1.0], "").unwrap();
        let mut s = [0.0];
        let e = law.evaluate(2.0, &[0.0], &mut s).unwrap_err().0;
        assert!(e.starts_with("panic in evaluate: ") && e.contains("gap too large"), "{e}");
        let e = law.evaluate(-2.0, &[0.0], &mut s).unwrap_err().0;
        assert!(e.contains("non-finite"), "{e}");
    }

    #[test]
    fn version_and_size_mismatches_are_refused_before_use() {
        // A descriptor from a "future" SDK: only the two leading fields may be read.
        let mut fake: [u32; 2] = [ABI_VERSION + 1, 16];
        let e =
            unsafe { LawLibrary::from_static(fake.as_mut_ptr() as *const LawDescriptor) }.err().unwrap().to_string();
        assert!(
            e.contains(&format!("version {}", ABI_VERSION + 1)) && e.contains(&format!("version {ABI_VERSION}")),
            "{e}"
        );
        let mut small: [u32; 2] = [ABI_VERSION, 16];
        let e =
            unsafe { LawLibrary::from_static(small.as_mut_ptr() as *const LawDescriptor) }.err().unwrap().to_string();
        assert!(e.contains("16 bytes"), "{e}");
    }
}
