//! The Stiction interface-law SDK: write a law as safe Rust, export it through the versioned C
//! ABI with one macro, and the host (the `stiction` program) loads it at run time.
//!
//! ```
//! use stiction_law_sdk::{Law, LawKind, Parameter, Response, export_law};
//! pub struct Spring { k: f64 }
//! impl Law for Spring {
//!     const NAME: &'static std::ffi::CStr = c"my-spring";
//!     const VERSION: &'static std::ffi::CStr = c"0.1.0";
//!     const KIND: LawKind = LawKind::TractionPerArea;
//!     const N_STATE: usize = 0;
//!     fn parameters() -> Vec<Parameter> { vec![Parameter::required(c"k", c"GPa/nm", c"stiffness", 0.0, f64::INFINITY)] }
//!     fn create(p: &[f64], _config: &str) -> Result<Self, String> { Ok(Spring { k: p[0] }) }
//!     fn evaluate(&self, gap: f64, _old: &[f64], _new: &mut [f64]) -> Result<Response, String> {
//!         Ok(Response { value: -self.k * gap.min(0.0), tangent: if gap < 0.0 { -self.k } else { 0.0 }, in_contact: gap < 0.0, area: 0.0 })
//!     }
//! }
//! export_law!(Spring);
//! ```
//! Build the crate with `crate-type = ["cdylib", "rlib"]`; the `cdylib` is the plugin, the
//! `rlib` lets the same law be linked statically (tests need no dynamic loading).
//!
//! Conventions: gap positive when open; value positive when it pushes the surfaces apart
//! (compressive), negative when it pulls them together (adhesive); `tangent` = d value / d gap.
//! `evaluate` must not mutate the instance (it is called from several threads) and writes the
//! whole trial state from the committed one.
//!
//! Mixed-mode laws (`GAP_DIMENSION = 3`) also implement [`Law::evaluate_mixed`]: the gap is the
//! opening in a local frame (normal, tangential 1, tangential 2) and the value is the force
//! per area on the moving side along those directions, value_i = -d psi / d gap_i for a law
//! with an energy psi (so the normal component keeps the sign convention above, and a shear
//! value opposes the slip), with the 3 x 3 tangent d value_i / d gap_j. `evaluate(g)` must equal
//! the normal part of `evaluate_mixed([g, 0, 0])`: interfaces that measure only a normal gap
//! (a frictionless rigid flat) call `evaluate`. Normal-only laws keep the defaults.

pub mod abi;
pub mod panic_guard;

pub use abi::{ABI_VERSION, LawDescriptor};
use std::ffi::CStr;

/// What a law's value means.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u32)]
pub enum LawKind {
    /// Traction (force per area), integrated over a surface.
    TractionPerArea = 0,
    /// Force per discrete point (e.g. a nano-asperity).
    ForcePerPoint = 1,
}

/// One evaluation's result.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Response {
    pub value: f64,
    pub tangent: f64,
    pub in_contact: bool,
    /// Contact area of the point (force-per-point laws).
    pub area: f64,
}

/// One mixed-mode evaluation's result (local frame: normal, tangential 1, tangential 2).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct MixedResponse {
    /// Force per area on the moving side along the frame (positive normal pushes apart).
    pub value: [f64; 3],
    /// tangent[i][j] = d value_i / d gap_j.
    pub tangent: [[f64; 3]; 3],
    pub in_contact: bool,
    pub area: f64,
}

impl MixedResponse {
    /// A normal-only response: no tangential value, no coupling.
    pub fn normal_only(r: Response) -> Self {
        let mut tangent = [[0.0; 3]; 3];
        tangent[0][0] = r.tangent;
        Self { value: [r.value, 0.0, 0.0], tangent, in_contact: r.in_contact, area: r.area }
    }
}

/// A parameter the law accepts; the host validates case files against these.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Parameter {
    pub name: &'static CStr,
    pub unit: &'static CStr,
    pub description: &'static CStr,
    pub default: Option<f64>,
    pub min: f64,
    pub max: f64,
}

impl Parameter {
    pub const fn required(
        name: &'static CStr,
        unit: &'static CStr,
        description: &'static CStr,
        min: f64,
        max: f64,
    ) -> Self {
        Self { name, unit, description, default: None, min, max }
    }
    pub const fn optional(
        name: &'static CStr,
        unit: &'static CStr,
        description: &'static CStr,
        default: f64,
        min: f64,
        max: f64,
    ) -> Self {
        Self { name, unit, description, default: Some(default), min, max }
    }
}

/// An interface law written in safe Rust.
pub trait Law: Sized + Send + Sync {
    const NAME: &'static CStr;
    const VERSION: &'static CStr;
    const KIND: LawKind;
    /// State variables per point.
    const N_STATE: usize;
    /// 1: normal gap only; 3: mixed mode (normal and two tangential components).
    const GAP_DIMENSION: usize = 1;
    fn parameters() -> Vec<Parameter>;
    /// What the law's configuration text is (e.g. "calibration file (TOML)"), or `None` when
    /// the law takes no configuration text.
    fn config_description() -> Option<&'static CStr> {
        None
    }
    /// Creates an instance from parameter values in `parameters()` order (already range-checked
    /// by the host; check relations between parameters here) and the configuration text
    /// (empty when none was given).
    fn create(parameters: &[f64], config: &str) -> Result<Self, String>;
    /// Initial state of a point.
    fn initialize_state(&self, state: &mut [f64]) {
        state.fill(0.0);
    }
    /// Value and tangent at `gap` from the committed state; writes the whole trial state.
    fn evaluate(&self, gap: f64, state_committed: &[f64], state_trial: &mut [f64]) -> Result<Response, String>;
    /// Mixed-mode value and tangent at the local opening `gap` = (normal, tangential 1,
    /// tangential 2); laws with `GAP_DIMENSION = 3` override this. The default is the
    /// normal-only law: value (evaluate(gap[0]), 0, 0).
    fn evaluate_mixed(
        &self,
        gap: [f64; 3],
        state_committed: &[f64],
        state_trial: &mut [f64],
    ) -> Result<MixedResponse, String> {
        self.evaluate(gap[0], state_committed, state_trial).map(MixedResponse::normal_only)
    }
    /// Names of the state variables (for output), `N_STATE` of them.
    fn state_names() -> Vec<&'static CStr> {
        Vec::new()
    }
}

/// Exports `$law` as this library's plugin: defines the `stiction_law_descriptor` symbol.
#[macro_export]
macro_rules! export_law {
    ($law:ty) => {
        /// The plugin entry point read by the Stiction host.
        #[unsafe(no_mangle)]
        pub extern "C" fn stiction_law_descriptor() -> *const $crate::abi::LawDescriptor {
            static HOLDER: ::std::sync::OnceLock<$crate::abi::DescriptorHolder> = ::std::sync::OnceLock::new();
            HOLDER.get_or_init(|| $crate::abi::DescriptorHolder::new::<$law>()).descriptor()
        }
    };
}
