//! Results on disk: CSV tables flushed row by row, JSON summaries, PNG/SVG figures.

pub mod atomic;
pub mod checkpoint;
pub mod lock;
pub mod plot;
pub mod table;
pub mod ticks;
pub mod vtu;

use crate::error::{Error, Result};
use serde::Serialize;
use std::path::Path;

pub use plot::{Figure, Legend, LineStyle, Series};
pub use table::CsvWriter;

/// Creates the output directory (and parents).
pub fn ensure_dir(dir: &Path) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))
}

/// Writes a pretty-printed JSON summary (atomically: complete or absent).
pub fn write_json<T: Serialize>(path: &Path, value: &T) -> Result<()> {
    atomic::write_file(path, json_text(path, value)?)
}

/// [`write_json`] for a file other processes may be writing at the same time with the same
/// contents ([`atomic::write_file_shared`]).
pub fn write_json_shared<T: Serialize>(path: &Path, value: &T) -> Result<()> {
    atomic::write_file_shared(path, json_text(path, value)?)
}

fn json_text<T: Serialize>(path: &Path, value: &T) -> Result<String> {
    let text = serde_json::to_string_pretty(value).map_err(|e| Error::NonFinite(format!("{}: {e}", path.display())))?;
    Ok(text + "\n")
}
