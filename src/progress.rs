//! A progress bar on the terminal (indicatif), as an observer of the run: which run of a sweep,
//! the step and pseudo-time, the first interface's approach, force and points in contact, the
//! share of pseudo-time done and indicatif's estimate of the time left (from the pace so far;
//! snaps make the pace uneven, so it is an estimate).

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use stiction_core::model::Model;
use stiction_core::record::{CommittedIncrement, Observer, RunSummary};

pub struct ProgressDisplay {
    bar: ProgressBar,
    length_unit: String,
    force_unit: String,
}

impl ProgressDisplay {
    /// A bar on stderr, prefixed by `label` (e.g. "run 2 of 3: max_approach_nm = 2").
    pub fn new(label: Option<&str>) -> Self {
        let bar = ProgressBar::with_draw_target(Some(1000), ProgressDrawTarget::stderr());
        bar.set_style(
            ProgressStyle::with_template("{prefix}[{elapsed_precise}] {bar:25} {percent:>3}% ETA {eta:<4} {msg}")
                .unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
        if let Some(l) = label {
            bar.set_prefix(format!("{l} "));
        }
        Self { bar, length_unit: String::new(), force_unit: String::new() }
    }

    /// "approach 0.8240 nm, force 12.31 uN, 85 in contact" for the model's first interface.
    fn interface_state(&self, model: &Model) -> Option<String> {
        let o = model.contributions.iter().find_map(|c| c.observables())?;
        let approach = o
            .approach
            .map(|a| format!("approach {} {}, ", crate::report::significant(a), self.length_unit).replace(" ,", ","))
            .unwrap_or_default();
        Some(format!("{approach}force {}, {} in contact", crate::report::force(o.force, &self.force_unit), o.n_contact))
    }
}

impl Observer for ProgressDisplay {
    fn started(&mut self, _model: &Model, summary: &RunSummary) -> stiction_core::error::Result<()> {
        self.length_unit = summary.units.length.clone();
        self.force_unit = summary.units.force.clone();
        Ok(())
    }

    fn committed(&mut self, model: &Model, increment: &CommittedIncrement) -> stiction_core::error::Result<()> {
        self.bar.set_position((1000.0 * increment.fraction_done) as u64);
        let state = self.interface_state(model).map(|s| format!(" | {s}")).unwrap_or_default();
        self.bar.set_message(format!("{}{state}", increment.description));
        Ok(())
    }

    fn message(&mut self, text: &str) {
        self.bar.set_message(text.to_string());
    }

    fn finished(&mut self, _model: &Model, _summary: &RunSummary) -> stiction_core::error::Result<()> {
        self.bar.finish_and_clear();
        Ok(())
    }
}
