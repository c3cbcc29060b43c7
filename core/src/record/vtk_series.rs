//! The VTK series: `<name>_NNNNN.vtu` (the solid's fields) and `<name>_<interface>_NNNNN.vtu`
//! (interface points), each listed in its `.pvd`, written when the step's output schedule says
//! a frame is due.

use super::{CommittedIncrement, Observer, ObserverState, RunSummary};
use crate::error::Result;
use crate::model::Model;
use crate::output::fields::{solid_cells, solid_fields};
use crate::output::vtk::{CellList, PvdSeries, write_points_vtu, write_vtu};
use std::path::{Path, PathBuf};

pub struct VtkRecorder {
    directory: PathBuf,
    name: String,
    solid: PvdSeries,
    points: Vec<PvdSeries>,
    frame: usize,
}

impl VtkRecorder {
    /// A series named `name` in `directory`, with one point series per contribution of `model`.
    pub fn new(directory: &Path, name: &str, model: &Model) -> Self {
        Self {
            directory: directory.to_path_buf(),
            name: name.to_string(),
            solid: PvdSeries::new(directory.join(format!("{name}.pvd"))),
            points: model
                .contributions
                .iter()
                .map(|c| PvdSeries::new(directory.join(format!("{name}_{}.pvd", c.name()))))
                .collect(),
            frame: 0,
        }
    }

    fn write_frame(&mut self, model: &Model) -> Result<()> {
        let frame = self.frame;
        for (c, series) in model.contributions.iter().zip(self.points.iter_mut()) {
            if let Some((points, fields)) = c.point_output() {
                let file = format!("{}_{}_{frame:05}.vtu", self.name, c.name());
                write_points_vtu(&self.directory.join(&file), &points, &fields)?;
                series.add(model.time, &file)?;
            }
        }
        let file = format!("{}_{frame:05}.vtu", self.name);
        let (point, cell) = solid_fields(model);
        let cells = solid_cells(model);
        let lists: Vec<CellList> = cells.iter().map(|(t, c)| CellList { cell_type: *t, connectivity: c }).collect();
        write_vtu(&self.directory.join(&file), &model.mesh.nodes, &lists, &point, &cell)?;
        self.solid.add(model.time, &file)?;
        self.frame += 1;
        Ok(())
    }
}

/// The name of the VTK series' record in a checkpoint.
const NAME: &str = "vtk series";

/// What a checkpoint keeps of the series: the frames written, and each collection's list of
/// (time, file) (file names are relative, so a moved output folder resumes too).
#[derive(serde::Serialize, serde::Deserialize)]
struct Saved {
    frame: usize,
    solid: Vec<(f64, String)>,
    points: Vec<Vec<(f64, String)>>,
}

impl Observer for VtkRecorder {
    fn committed(&mut self, model: &Model, increment: &CommittedIncrement) -> Result<()> {
        if increment.frame_due { self.write_frame(model) } else { Ok(()) }
    }

    fn saved_state(&mut self) -> Result<Option<ObserverState>> {
        let saved = Saved {
            frame: self.frame,
            solid: self.solid.entries().to_vec(),
            points: self.points.iter().map(|p| p.entries().to_vec()).collect(),
        };
        Ok(Some(ObserverState::new(NAME, &saved)))
    }

    /// Goes on from the checkpoint's frame: the collections list the frames written up to it
    /// again, and the frames the interrupted run wrote after it are removed.
    fn resumed(&mut self, model: &Model, _summary: &RunSummary, saved: &[ObserverState]) -> Result<()> {
        let Saved { frame, solid, points } = ObserverState::find(saved, NAME)?;
        if points.len() != self.points.len() {
            return Err(crate::error::CoreError::Invalid(format!(
                "the checkpoint's VTK series has {} interface collections, this model {}",
                points.len(),
                self.points.len()
            )));
        }
        self.frame = frame;
        self.solid.replace_entries(solid)?;
        for (series, entries) in self.points.iter_mut().zip(points) {
            series.replace_entries(entries)?;
        }
        let stems: Vec<String> = std::iter::once(self.name.clone())
            .chain(model.contributions.iter().map(|c| format!("{}_{}", self.name, c.name())))
            .collect();
        for later in frame.. {
            let files: Vec<PathBuf> =
                stems.iter().map(|stem| self.directory.join(format!("{stem}_{later:05}.vtu"))).collect();
            if !files.iter().any(|f| f.exists()) {
                break;
            }
            for f in files.iter().filter(|f| f.exists()) {
                std::fs::remove_file(f).map_err(|source| crate::error::CoreError::Write { path: f.clone(), source })?;
            }
        }
        Ok(())
    }
}
