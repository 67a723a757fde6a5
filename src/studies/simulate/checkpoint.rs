//! `simulate`'s checkpoint, `checkpoint.bin` in the output folder: the path's whole state
//! ([`PathState`]), the states and cuts recorded so far, the secondary-bifurcation tracker and
//! what the files written as the path goes need to go on, with what the run was asked: a run
//! resumes only its own checkpoint.

use super::fig7::CreaseMemory;
use super::snapshots::SnapshotsMemory;
use super::{SecondaryTracker, SimulateStudy};
use crate::error::Result;
use crate::output::checkpoint::{read_checkpoint, write_checkpoint, Request};
use crate::parameters::Parameters;
use crate::protocol::{Cut, PathState, StepRecord};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// The checkpoint's name in the output folder.
pub const CHECKPOINT_FILE: &str = "checkpoint.bin";

/// What the path and the records kept in memory need to go on.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct SolveMemory {
    pub path: PathState,
    pub records: Vec<StepRecord>,
    pub cuts: Vec<Cut>,
    pub tracker: SecondaryTracker,
}

/// What the files written as the path goes need to go on.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub(super) struct FilesMemory {
    pub snapshots: SnapshotsMemory,
    pub snap_files: Vec<PathBuf>,
    pub crease: Option<CreaseMemory>,
}

/// The file's layout for writing: borrowed, so that a checkpoint copies nothing.
#[derive(Serialize)]
struct Written<'a> {
    request: &'a Request,
    solve: &'a SolveMemory,
    files: &'a FilesMemory,
}

/// The file's layout for reading (the same fields, owned).
#[derive(Deserialize)]
struct Read {
    request: Request,
    solve: SolveMemory,
    files: FilesMemory,
}

/// Writes the checkpoint into `out`; its size in bytes.
pub(super) fn write(out: &Path, request: &Request, solve: &SolveMemory, files: &FilesMemory) -> Result<u64> {
    write_checkpoint(&out.join(CHECKPOINT_FILE), &Written { request, solve, files })
}

/// The checkpoint in `out`, if there is one, refused unless it is of a run asked `request`.
pub(super) fn read(out: &Path, request: &Request) -> Result<Option<(SolveMemory, FilesMemory)>> {
    let path = out.join(CHECKPOINT_FILE);
    let Some(read) = read_checkpoint::<Read>(&path)? else {
        return Ok(None);
    };
    read.request.check(request, &path)?;
    Ok(Some((read.solve, read.files)))
}

/// What a run was asked: its parameters, and its options but for how often it checkpoints and
/// whether it resumes (which do not change the path).
pub(super) fn request(params: &Parameters, study: &SimulateStudy) -> Result<Request> {
    let options = SimulateStudy {
        checkpoints: None,
        resume: false,
        ..*study
    };
    Request::of(params, &options)
}
