//! The VTU snapshots of a path: every `every` in `d`, collected in `simulate.pvd`, each encoded
//! and written on a thread of its own while the path goes on.

use super::crease;
use super::state_vtu::{state_arrays, CELL_TYPE};
use crate::error::Result;
use crate::fem::System;
use crate::material::Bilayer;
use crate::output::vtu::{write_vtu, Collection};
use crate::protocol::StepRecord;
use std::path::{Path, PathBuf};
use std::thread::JoinHandle;

/// VTU snapshots every `every` in `d`, collected in `simulate.pvd`. Each is encoded and written
/// on a thread of its own while the path goes on (one at a time); the collection names it once
/// it is complete, and a run that ends or stops waits for it.
pub(super) struct Snapshots {
    dir: PathBuf,
    every: f64,
    collection: Collection,
    next_mark: f64,
    last_written: Option<f64>,
    /// The snapshot being written: its `d`, its path and the writing thread.
    writing: Option<(f64, PathBuf, JoinHandle<Result<()>>)>,
}

/// What the snapshots of a path need to go on: the next mark, the last `d` written and the
/// files collected.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub(super) struct SnapshotsMemory {
    next_mark: f64,
    last_written: Option<f64>,
    entries: Vec<(f64, String)>,
}

impl Snapshots {
    /// Waits for the snapshot being written; what a resumed path needs to go on.
    pub(super) fn memory(&mut self) -> Result<SnapshotsMemory> {
        self.finish_writing()?;
        Ok(SnapshotsMemory {
            next_mark: self.next_mark,
            last_written: self.last_written,
            entries: self.collection.entries().to_vec(),
        })
    }

    /// The snapshots of a path resumed from `memory` (the collection is rewritten to list them).
    pub(super) fn resumed(dir: &Path, every: f64, memory: SnapshotsMemory) -> Result<Self> {
        Ok(Snapshots {
            dir: dir.to_path_buf(),
            every,
            collection: Collection::with_entries(&dir.join("simulate.pvd"), memory.entries)?,
            next_mark: memory.next_mark,
            last_written: memory.last_written,
            writing: None,
        })
    }

    pub(super) fn new(dir: &Path, every: f64) -> Self {
        Snapshots {
            dir: dir.to_path_buf(),
            every,
            collection: Collection::new(&dir.join("simulate.pvd")),
            next_mark: 0.0,
            last_written: None,
            writing: None,
        }
    }

    /// Writes the state when `d` has reached the next mark of `every` (and the first state).
    pub(super) fn maybe_write(
        &mut self,
        record: &StepRecord,
        system: &System,
        materials: &Bilayer,
        u: &[f64],
    ) -> Result<()> {
        let d = record.d;
        if self.last_written.is_none() || d >= self.next_mark - 1e-9 {
            self.write(Some(record), d, system, materials, u)?;
            self.next_mark = ((d / self.every + 1e-9).floor() + 1.0) * self.every;
        }
        Ok(())
    }

    /// Writes the final state unless it was just written, and waits for the last write.
    pub(super) fn write_final(
        &mut self,
        record: Option<&StepRecord>,
        d: f64,
        system: &System,
        materials: &Bilayer,
        u: &[f64],
    ) -> Result<()> {
        match self.last_written {
            Some(last) if last == d => {}
            _ => self.write(record, d, system, materials, u)?,
        }
        self.finish_writing()
    }

    /// Starts writing one snapshot, with the contact pressure of `record` as point data: its
    /// arrays are made here, their encoding and writing go to a thread once the previous
    /// snapshot is complete.
    fn write(
        &mut self,
        record: Option<&StepRecord>,
        d: f64,
        system: &System,
        materials: &Bilayer,
        u: &[f64],
    ) -> Result<()> {
        let mesh = system.mesh();
        let pressure = crease::pressure_array(record, mesh.num_nodes());
        let (point_data, cell_data) = state_arrays(system, materials, u, vec![pressure])?;
        let (points, cells) = (mesh.coordinates().to_vec(), mesh.elements().to_vec());
        self.finish_writing()?;
        let path = self.dir.join(format!("simulate_{:04}.vtu", self.collection.len()));
        let target = path.clone();
        let writer =
            std::thread::spawn(move || write_vtu(&target, &points, &CELL_TYPE, &cells, &point_data, &cell_data));
        self.writing = Some((d, path, writer));
        self.last_written = Some(d);
        Ok(())
    }

    /// Waits for the snapshot being written, if any, and adds it to the collection.
    fn finish_writing(&mut self) -> Result<()> {
        let Some((d, path, writer)) = self.writing.take() else {
            return Ok(());
        };
        writer.join().expect("the snapshot writer does not panic")?;
        self.collection.add(d, &path)
    }
}

impl Drop for Snapshots {
    /// A run that stops on an error still completes the snapshot being written.
    fn drop(&mut self) {
        let _ = self.finish_writing();
    }
}
