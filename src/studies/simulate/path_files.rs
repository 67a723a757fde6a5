//! The files of a `simulate` run written as its path goes (`amplitude.csv`, the VTU snapshots,
//! the states around each snap, the states of Fig. 7, the checkpoints), and those written at its
//! end.

use super::checkpoint::{self, SolveMemory, CHECKPOINT_FILE};
use super::snapshots::Snapshots;
use super::{amplitude_header, amplitude_row, fig3, write_state, CreaseSnapshots, SimulateStudy, Solution};
use crate::error::Result;
use crate::fem::System;
use crate::material::Bilayer;
use crate::output::checkpoint::{remove_checkpoint, Request};
use crate::output::{write_json, CsvWriter};
use crate::parameters::Parameters;
use crate::protocol::Event;
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The checkpoints a run wrote: how many, the size of the last, and the time spent writing them.
#[derive(Clone, Copy, Debug, Default, Serialize)]
pub struct CheckpointTotals {
    pub written: usize,
    pub bytes: u64,
    pub seconds: f64,
}

/// The files of a run written as its path goes (`amplitude.csv`, the VTU snapshots, the states
/// around each snap, the states of Fig. 7), and at its end.
pub(super) struct PathFiles {
    dir: PathBuf,
    table: CsvWriter,
    snapshots: Snapshots,
    snap_files: Vec<PathBuf>,
    last_state: Vec<f64>,
    crease: Option<CreaseSnapshots>,
    checkpoints: CheckpointTotals,
}

impl PathFiles {
    /// The files of a new path (a checkpoint of an earlier run in `out` is removed).
    pub(super) fn create(out: &Path, study: &SimulateStudy) -> Result<Self> {
        remove_checkpoint(&out.join(CHECKPOINT_FILE))?;
        Ok(PathFiles {
            dir: out.to_path_buf(),
            table: CsvWriter::create(&out.join("amplitude.csv"), &amplitude_header())?,
            snapshots: Snapshots::new(out, study.vtu_every),
            snap_files: Vec::new(),
            last_state: Vec::new(),
            crease: study
                .protocol
                .contact
                .then(|| CreaseSnapshots::new(study.protocol.d_max)),
            checkpoints: CheckpointTotals::default(),
        })
    }

    /// The files of a path resumed from a checkpoint: `amplitude.csv` rewritten with the states
    /// so far, the snapshots collected so far, the states kept for the figures.
    pub(super) fn resumed(
        out: &Path,
        study: &SimulateStudy,
        files: checkpoint::FilesMemory,
        solve: &SolveMemory,
    ) -> Result<Self> {
        let mut table = CsvWriter::create(&out.join("amplitude.csv"), &amplitude_header())?;
        for record in &solve.records {
            table.append(&amplitude_row(record))?;
        }
        let last_state = solve.path.history.last().map(|(_, u)| u.clone()).unwrap_or_default();
        Ok(PathFiles {
            dir: out.to_path_buf(),
            table,
            snapshots: Snapshots::resumed(out, study.vtu_every, files.snapshots)?,
            snap_files: files.snap_files,
            last_state,
            crease: files.crease.map(CreaseSnapshots::resumed),
            checkpoints: CheckpointTotals::default(),
        })
    }

    /// Writes the checkpoint of the path's state `solve` with what these files need to go on.
    pub(super) fn checkpoint(&mut self, request: &Request, solve: &SolveMemory) -> Result<()> {
        let started = Instant::now();
        let files = checkpoint::FilesMemory {
            snapshots: self.snapshots.memory()?,
            snap_files: self.snap_files.clone(),
            crease: self.crease.as_ref().map(CreaseSnapshots::memory),
        };
        let bytes = checkpoint::write(&self.dir, request, solve, &files)?;
        self.checkpoints.written += 1;
        self.checkpoints.bytes = bytes;
        self.checkpoints.seconds += started.elapsed().as_secs_f64();
        Ok(())
    }

    /// The checkpoints written so far.
    pub(super) fn checkpoint_totals(&self) -> CheckpointTotals {
        self.checkpoints
    }

    /// Writes what one event of the path adds.
    pub(super) fn note(&mut self, event: &Event<'_>, materials: &Bilayer) -> Result<()> {
        let Event::Step { record, system, u } = event else {
            return Ok(());
        };
        self.table.append(&amplitude_row(record))?;
        self.snapshots.maybe_write(record, system, materials, u)?;
        if record.snap.is_some() {
            for (when, state) in [("before", &self.last_state[..]), ("after", u)] {
                let path = self.dir.join(format!("snap_{}_{when}.vtu", self.snap_files.len() / 2));
                write_state(&path, system, materials, state, Vec::new())?;
                self.snap_files.push(path);
            }
        }
        self.last_state.clear();
        self.last_state.extend_from_slice(u);
        if let Some(crease) = &mut self.crease {
            crease.note(record, u);
        }
        Ok(())
    }

    /// Writes the files of the finished path: the last snapshot, `surface.csv`, `onset_estimates.json`,
    /// `contact.json`, `snaps.json`, Fig. 3 and Fig. 7; every file of the run so far.
    pub(super) fn finish(
        mut self,
        solution: &Solution,
        system: &System,
        materials: &Bilayer,
        u: &[f64],
        params: &Parameters,
    ) -> Result<Vec<PathBuf>> {
        let out = &self.dir;
        let curve = &solution.curve;
        self.snapshots
            .write_final(curve.records.last(), solution.d_reached, system, materials, u)?;
        let mut surface = CsvWriter::create(&out.join("surface.csv"), &["x", "y"])?;
        for &(x, y) in &solution.surface {
            surface.append(&[x, y])?;
        }
        write_json(&out.join("onset_estimates.json"), &solution.onset)?;
        write_json(&out.join("contact.json"), &solution.contact)?;
        write_json(&out.join("snaps.json"), &solution.snaps)?;
        let mut files: Vec<PathBuf> = [
            "amplitude.csv",
            "surface.csv",
            "onset_estimates.json",
            "contact.json",
            "snaps.json",
            "simulate.pvd",
        ]
        .iter()
        .map(|f| out.join(f))
        .collect();
        files.append(&mut self.snap_files);
        files.extend(crate::output::plot::save_panels(
            &fig3(curve, &solution.onset, params.load),
            out,
            "fig3",
        )?);
        if let Some(crease) = self.crease {
            files.extend(crease.draw(system, materials, params.beta, out)?.1);
        }
        Ok(files)
    }
}
