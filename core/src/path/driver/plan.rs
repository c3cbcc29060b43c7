//! What a run is asked to do, besides the model, the solvers and the observers: the steps, how
//! limit points are crossed, how snaps are solved, which tangent, and when to checkpoint or
//! stop ([`RunPlan`]). The driver ([`super`]) reads it; nothing here runs anything.

use super::super::Crossing;
use super::super::arc_length_control::ArcLengthControl;
use super::super::dissipation_control::DissipationControl;
use super::super::load_control::StartPredictor;
use super::super::step::StepPlan;
use super::super::tangent_choice::TangentChoice;
use crate::checkpoint::CheckpointPlan;
use crate::nonlinear::arc_length::PreviousIncrement;
use crate::nonlinear::damped_flow::FlowSettings;
use crate::record::interface_tracker::InterfaceInfo;
use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::AtomicBool;

/// Everything the driver needs besides the model, the solvers and the observers.
#[derive(Debug, Clone)]
pub struct RunPlan {
    pub name: String,
    /// The case's length and force units (for reports; empty when not stated).
    pub units: (String, String),
    pub output_directory: PathBuf,
    pub steps: Vec<StepPlan>,
    /// How limit points are crossed (None: they are not; load control cuts, then snaps).
    pub continuation: Option<Continuation>,
    /// Per contribution of the model: kind and viscous-share limit.
    pub interfaces: Vec<InterfaceInfo>,
    /// Set (e.g. by a Ctrl-C handler) to stop the run after the increment in progress (inside
    /// a damped-flow snap: after its step in progress): the run ends with status "interrupted".
    pub interrupt: Option<Arc<AtomicBool>>,
    /// The predictor of the increments with no earlier rate to extrapolate.
    pub start_predictor: StartPredictor,
    /// How a snap finds the state it reaches.
    pub snap: SnapMethod,
    /// Which material tangent the solvers see.
    pub tangent: TangentChoice,
    /// Where and how often the run writes checkpoints (None: never).
    pub checkpoint: Option<CheckpointPlan>,
    /// Stop the run (as if interrupted, with a checkpoint) once this many increments are
    /// committed in all, at the first point between increments after that (no crossing under
    /// way): a run split in parts, e.g. to test that resuming it changes nothing.
    pub stop_after_increments: Option<usize>,
    /// Stop the run (as if interrupted, with a checkpoint) inside a damped-flow snap, after
    /// this many flow steps of this process in all: a run split in the middle of a snap.
    pub stop_after_flow_steps: Option<usize>,
}

/// How a snap (a jump at a fixed load to the stable state the system reaches) is solved.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SnapMethod {
    /// Along the overdamped motion M du/dtau = -r(u) ([`crate::nonlinear::damped_flow::damped_flow`]): the state depends
    /// on the path where the body yields or a law is hysteretic, and this path has no free
    /// parameter and converges with the mesh. Problems without a mass settle instead.
    DampedFlow(FlowSettings),
    /// By descent from the committed state ([`crate::nonlinear::settle::settle`]): cheaper, the same state for an
    /// elastic body with one stable state in reach, a one-step plastic update otherwise.
    Settle,
    /// By descent, and along the damped flow with these settings where the descent finds no
    /// stable state (it may stall where the body's energy is nearly flat: a surface node
    /// hovering at the edge of an adhesive contact); the flow, which only needs each of its short
    /// steps solved, then finds one. The default for path-independent bodies.
    SettleOrFlow(FlowSettings),
}

/// Path following at limit points.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Continuation {
    pub method: ContinuationMethod,
    /// Consecutive cuts after which the crossing takes over.
    pub after_cuts: usize,
}

/// The constraint a crossing follows the path on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ContinuationMethod {
    /// [`ArcLengthControl`]: an arc length in (u, t).
    ArcLength,
    /// [`DissipationControl`]: the energy damage dissipates per increment.
    Dissipation,
}

impl Continuation {
    /// A crossing from the last converged increment `previous`, handing back past
    /// `resume_after`; None when that increment did not move.
    pub(super) fn start(&self, previous: PreviousIncrement, resume_after: f64) -> Option<Box<dyn Crossing>> {
        match self.method {
            ContinuationMethod::ArcLength => {
                ArcLengthControl::start(previous, resume_after).map(|c| Box::new(c) as Box<dyn Crossing>)
            }
            ContinuationMethod::Dissipation => {
                DissipationControl::start(previous, resume_after).map(|c| Box::new(c) as Box<dyn Crossing>)
            }
        }
    }
}
