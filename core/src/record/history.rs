//! `history.csv`: one row per committed state: step, increment, time, iterations, reactions
//! per boundary group, mean displacements per loaded group, plastic dissipation, the snaps'
//! dissipation so far, and each interface's observables. With one interface its columns are
//! named plainly (`approach`, `force`, ...); with several, each is prefixed by its interface's
//! name (`flat_force`, `bond_force`), so that no two columns share a name.

use super::{CommittedIncrement, Observer, ObserverState, RunSummary};
use crate::element::Kinematics;
use crate::error::Result;
use crate::model::Model;
use crate::observables::Value;
use crate::output::HistoryWriter;
use std::path::Path;

pub struct HistoryRecorder {
    writer: HistoryWriter,
    reaction_groups: Vec<(String, Vec<usize>)>,
    displacement_groups: Vec<(String, Vec<usize>)>,
}

impl HistoryRecorder {
    /// Writes `path` (from the run's start) with the header for `model`; reactions are summed over the nodes of each
    /// of `reaction_groups`, displacements averaged over those of each of `displacement_groups`.
    pub fn new(
        path: &Path,
        model: &Model,
        reaction_groups: Vec<(String, Vec<usize>)>,
        displacement_groups: Vec<(String, Vec<usize>)>,
    ) -> Self {
        let dpn = model.dofs_per_node();
        let component = |k: usize| {
            if model.kinematics == Kinematics::Axisymmetric { ["r", "z"][k] } else { ["x", "y", "z"][k] }
        };
        let mut columns: Vec<String> =
            ["step", "increment", "time", "iterations"].iter().map(|s| s.to_string()).collect();
        for (g, _) in &reaction_groups {
            for k in 0..dpn {
                columns.push(format!("reaction_{g}_{}", component(k)));
            }
        }
        for (g, _) in &displacement_groups {
            for k in 0..dpn {
                columns.push(format!("displacement_{g}_{}", component(k)));
            }
        }
        columns.push("plastic_dissipation".into());
        columns.push("snap_dissipation".into());
        let reporting = model.contributions.iter().filter(|c| c.observables().is_some()).count();
        for c in &model.contributions {
            if let Some(o) = c.observables() {
                columns.extend(
                    o.columns()
                        .into_iter()
                        .map(|(name, _)| if reporting > 1 { format!("{}_{name}", c.name()) } else { name.to_string() }),
                );
            }
        }
        Self { writer: HistoryWriter::new(path, columns), reaction_groups, displacement_groups }
    }
}

impl Observer for HistoryRecorder {
    fn started(&mut self, _model: &Model, _summary: &RunSummary) -> Result<()> {
        self.writer.start()
    }

    fn saved_state(&mut self) -> Result<Option<ObserverState>> {
        self.writer.saved_state().map(Some)
    }

    fn resumed(&mut self, _model: &Model, _summary: &RunSummary, saved: &[ObserverState]) -> Result<()> {
        self.writer.resume(saved)
    }

    fn committed(&mut self, model: &Model, increment: &CommittedIncrement) -> Result<()> {
        let mut row = vec![
            Value::Count(increment.step),
            Value::Count(increment.increment),
            Value::Real(model.time),
            Value::Count(increment.iterations),
        ];
        for (_, nodes) in &self.reaction_groups {
            row.extend(model.reaction(nodes).into_iter().map(Value::Real));
        }
        let dpn = model.dofs_per_node();
        for (_, nodes) in &self.displacement_groups {
            for k in 0..dpn {
                let sum: f64 = nodes.iter().map(|&n| model.displacement[n * dpn + k]).sum();
                row.push(Value::Real(sum / nodes.len().max(1) as f64));
            }
        }
        row.push(Value::Real(increment.plastic_dissipation));
        row.push(Value::Real(increment.snap_dissipation));
        for c in &model.contributions {
            if let Some(o) = c.observables() {
                row.extend(o.columns().into_iter().map(|(_, v)| v));
            }
        }
        self.writer.append(&row)
    }
}
