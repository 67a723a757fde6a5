//! `reproduce`: every figure of the paper (Figs. 2-7 and the exact FE bifurcation), into one
//! folder, with a report.
//!
//! Each piece writes into its own sub-folder and copies its figures to the top folder. A piece
//! whose `done.json` records the same parameters is skipped, so an interrupted run resumes.

mod pieces;
mod report;

pub use pieces::pieces;
pub use report::write_report;

use super::Tick;
use crate::error::{Error, Result};
use crate::output::{ensure_dir, write_json};
use crate::parameters::Parameters;
use serde::{Deserialize, Serialize};
use std::path::Path;
use std::time::Instant;

/// Options of a reproduction run.
#[derive(Clone, Copy, Debug, Default)]
pub struct ReproduceOptions {
    /// Coarser meshes and fewer points.
    pub quick: bool,
}

/// One independent part of the reproduction.
pub struct Piece {
    pub name: &'static str,
    /// Figures (stems) this piece produces.
    pub figures: &'static [&'static str],
    /// Rows for the report's table of claims.
    pub run: fn(&Parameters, &ReproduceOptions, &Path, Tick) -> Result<Vec<Claim>>,
}

/// One claim of the paper set beside ours.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Claim {
    pub what: String,
    pub paper: String,
    pub ours: String,
    pub note: String,
    pub command: String,
}

#[derive(Serialize, Deserialize)]
struct Done {
    parameters: Parameters,
    quick: bool,
    claims: Vec<Claim>,
    seconds: f64,
}

/// What one piece reported when it finished (or was found finished).
pub struct PieceOutcome {
    pub name: &'static str,
    pub seconds: f64,
    pub skipped: bool,
    pub claims: Vec<Claim>,
}

/// Runs (or resumes) one piece inside `out/<name>` and copies its figures to `out`.
pub fn run_piece(
    piece: &Piece,
    params: &Parameters,
    options: &ReproduceOptions,
    out: &Path,
    tick: Tick,
) -> Result<PieceOutcome> {
    let dir = out.join(piece.name);
    let done_path = dir.join("done.json");
    if let Some(done) = read_done(&done_path) {
        if done.parameters == *params && done.quick == options.quick {
            return Ok(PieceOutcome {
                name: piece.name,
                seconds: done.seconds,
                skipped: true,
                claims: done.claims,
            });
        }
    }
    ensure_dir(&dir)?;
    let start = Instant::now();
    let claims = (piece.run)(params, options, &dir, tick)?;
    for stem in piece.figures {
        for ext in ["png", "svg"] {
            let from = dir.join(format!("{stem}.{ext}"));
            let to = out.join(format!("{stem}.{ext}"));
            crate::output::atomic::write_atomically(&to, |temporary| {
                std::fs::copy(&from, temporary)
                    .map(|_| ())
                    .map_err(|e| Error::io(&from, e))
            })?;
        }
    }
    let seconds = start.elapsed().as_secs_f64();
    let done = Done {
        parameters: params.clone(),
        quick: options.quick,
        claims: claims.clone(),
        seconds,
    };
    write_json(&done_path, &done)?;
    Ok(PieceOutcome {
        name: piece.name,
        seconds,
        skipped: false,
        claims,
    })
}

fn read_done(path: &Path) -> Option<Done> {
    serde_json::from_str(&std::fs::read_to_string(path).ok()?).ok()
}
