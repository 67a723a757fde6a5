//! `pattern`'s checkpoint of the path past the onset, `checkpoint.bin` in the output folder: the
//! path's whole state ([`PathState`]), the states of `pattern.csv` so far and the branches
//! left, with what the run was asked. A resumed run redoes what precedes the path (the sizing
//! and the bifurcation search, the same each time) and continues the path from it.

use super::PatternStudy;
use crate::error::Result;
use crate::output::checkpoint::{read_checkpoint, write_checkpoint, Request};
use crate::parameters::Parameters;
use crate::protocol::PathState;
use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// The checkpoint's name in the output folder.
pub const CHECKPOINT_FILE: &str = "checkpoint.bin";

/// What the path past the onset needs to go on, with its states of type `T` (`pattern.csv`'s
/// rows).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct PathMemory<T> {
    pub path: PathState,
    pub states: Vec<T>,
    /// `(d, energy released)` of every unstable state left.
    pub branches_left: Vec<(f64, f64)>,
}

/// The file's layout for writing (borrowed).
#[derive(Serialize)]
struct Written<'a, T> {
    request: &'a Request,
    path: &'a PathState,
    states: &'a [T],
    branches_left: &'a [(f64, f64)],
}

/// The file's layout for reading.
#[derive(Deserialize)]
struct Read<T> {
    request: Request,
    path: PathState,
    states: Vec<T>,
    branches_left: Vec<(f64, f64)>,
}

/// What a run was asked: its parameters, and its study but for how often it checkpoints and
/// whether it resumes.
pub(super) fn request(params: &Parameters, study: &PatternStudy) -> Result<Request> {
    let options = PatternStudy {
        checkpoints: None,
        resume: false,
        ..*study
    };
    Request::of(params, &options)
}

/// Writes the checkpoint of the path at `path` with its states so far into `out`.
pub(super) fn write<T: Serialize>(
    out: &Path,
    request: &Request,
    path: &PathState,
    (states, branches_left): (&[T], &[(f64, f64)]),
) -> Result<()> {
    let written = Written {
        request,
        path,
        states,
        branches_left,
    };
    write_checkpoint(&out.join(CHECKPOINT_FILE), &written).map(|_| ())
}

/// The checkpoint in `out`, if there is one, refused unless it is of a run asked `request`.
pub(super) fn read<T: DeserializeOwned>(out: &Path, request: &Request) -> Result<Option<PathMemory<T>>> {
    let file = out.join(CHECKPOINT_FILE);
    let Some(read) = read_checkpoint::<Read<T>>(&file)? else {
        return Ok(None);
    };
    read.request.check(request, &file)?;
    Ok(Some(PathMemory {
        path: read.path,
        states: read.states,
        branches_left: read.branches_left,
    }))
}
