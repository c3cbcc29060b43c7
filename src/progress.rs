//! A progress bar on the terminal (indicatif), as an observer of the run.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use stiction_core::model::Model;
use stiction_core::record::{CommittedIncrement, Observer, RunSummary};

pub struct ProgressDisplay {
    bar: ProgressBar,
}

impl ProgressDisplay {
    /// A bar on stderr.
    pub fn new() -> Self {
        let bar = ProgressBar::with_draw_target(Some(1000), ProgressDrawTarget::stderr());
        bar.set_style(
            ProgressStyle::with_template("{spinner} [{elapsed_precise}] {bar:30} {msg}")
                .unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
        Self { bar }
    }
}

impl Default for ProgressDisplay {
    fn default() -> Self {
        Self::new()
    }
}

impl Observer for ProgressDisplay {
    fn committed(&mut self, _model: &Model, increment: &CommittedIncrement) -> stiction_core::error::Result<()> {
        self.bar.set_position((1000.0 * increment.fraction_done) as u64);
        self.bar.set_message(increment.description.clone());
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
