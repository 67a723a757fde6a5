//! Checkpoint files: what a run needs to go on where it was, in a compact binary form. A file
//! is a header (the format's magic and version, the writing program's version), a body in
//! `postcard`'s encoding of the value, and a CRC-32 of everything before it. It is written to
//! a temporary sibling, synced and renamed over the previous checkpoint, so that a kill or a full
//! disk leaves the previous one whole.

use super::atomic::write_atomically;
use crate::error::{Error, Result};
use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use std::io::Write;
use std::path::Path;

/// The first bytes of every checkpoint.
const MAGIC: &[u8; 8] = b"FFCHKPT\n";
/// The layout of the header and body; a file of another layout is refused.
const FORMAT: u32 = 1;
/// The program that wrote a checkpoint must be the one that reads it: the path it continues is
/// then the one the uninterrupted run takes.
const PROGRAM: &str = concat!("fiberfold ", env!("CARGO_PKG_VERSION"));

/// What a run was asked, as text: its parameters (JSON) and its options (`Debug`, one setting
/// a line). A run resumes only a checkpoint of the same request.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Request {
    parameters: String,
    options: String,
}

impl Request {
    /// The request of `parameters` and `options`.
    pub fn of(parameters: &impl Serialize, options: &impl std::fmt::Debug) -> Result<Self> {
        let parameters =
            serde_json::to_string_pretty(parameters).map_err(|e| Error::NonFinite(format!("the parameters: {e}")))?;
        Ok(Request {
            parameters,
            options: format!("{options:#?}"),
        })
    }

    /// Refuses the checkpoint `path` of a run asked `self` for a run asked `asked`, naming the
    /// first setting that differs.
    pub fn check(&self, asked: &Request, path: &Path) -> Result<()> {
        let differing = |kind: &str, theirs: &str, ours: &str| {
            let (theirs, ours) = theirs
                .lines()
                .zip(ours.lines())
                .find(|(a, b)| a != b)
                .unwrap_or(("(shorter)", "(longer)"));
            Error::Resume(format!(
                "{}: it is of a run with other {kind} (`{}` there, `{}` here); resume with the run's own \
                 settings, or give another --out",
                path.display(),
                theirs.trim().trim_end_matches(','),
                ours.trim().trim_end_matches(',')
            ))
        };
        if self.parameters != asked.parameters {
            return Err(differing("parameters", &self.parameters, &asked.parameters));
        }
        if self.options != asked.options {
            return Err(differing("options", &self.options, &asked.options));
        }
        Ok(())
    }
}

/// Writes `value` as the checkpoint `path`, atomically and synced to disk; its size in bytes.
pub fn write_checkpoint<T: Serialize>(path: &Path, value: &T) -> Result<u64> {
    let body = postcard::to_stdvec(value).map_err(|e| Error::Solver(format!("checkpoint {}: {e}", path.display())))?;
    let mut bytes = Vec::with_capacity(body.len() + 64);
    bytes.extend_from_slice(MAGIC);
    bytes.extend_from_slice(&FORMAT.to_le_bytes());
    bytes.extend_from_slice(&(PROGRAM.len() as u32).to_le_bytes());
    bytes.extend_from_slice(PROGRAM.as_bytes());
    bytes.extend_from_slice(&(body.len() as u64).to_le_bytes());
    bytes.extend_from_slice(&body);
    bytes.extend_from_slice(&crc32fast::hash(&bytes).to_le_bytes());
    write_atomically(path, |temporary| {
        let mut file = std::fs::File::create(temporary).map_err(|e| Error::io(path, e))?;
        file.write_all(&bytes).map_err(|e| Error::io(path, e))?;
        file.sync_all().map_err(|e| Error::io(path, e))
    })?;
    Ok(bytes.len() as u64)
}

/// Removes the checkpoint at `path`, if there is one (a new path in its folder).
pub fn remove_checkpoint(path: &Path) -> Result<()> {
    match std::fs::remove_file(path) {
        Err(e) if e.kind() != std::io::ErrorKind::NotFound => Err(Error::io(path, e)),
        _ => Ok(()),
    }
}

/// The checkpoint at `path`, or `None` if there is none; a file that is not a whole checkpoint
/// of this program is an [`Error::Resume`] saying why.
pub fn read_checkpoint<T: DeserializeOwned>(path: &Path) -> Result<Option<T>> {
    let bytes = match std::fs::read(path) {
        Ok(bytes) => bytes,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(e) => return Err(Error::io(path, e)),
    };
    let refuse = |why: &str| Error::Resume(format!("{}: {why}", path.display()));
    let damaged = "it is damaged or was edited (its checksum does not match); delete it to start afresh";
    let Some((content, checksum)) = bytes.split_last_chunk::<4>() else {
        return Err(refuse(damaged));
    };
    if !content.starts_with(MAGIC) {
        return Err(refuse("it is not a fiberfold checkpoint"));
    }
    if crc32fast::hash(content) != u32::from_le_bytes(*checksum) {
        return Err(refuse(damaged));
    }
    let mut rest = &content[MAGIC.len()..];
    let mut take = |n: usize| -> Result<&[u8]> {
        let (head, tail) = rest.split_at_checked(n).ok_or_else(|| refuse(damaged))?;
        rest = tail;
        Ok(head)
    };
    let format = u32::from_le_bytes(take(4)?.try_into().expect("four bytes"));
    let program_length = u32::from_le_bytes(take(4)?.try_into().expect("four bytes")) as usize;
    let program = String::from_utf8_lossy(take(program_length)?).into_owned();
    if format != FORMAT || program != PROGRAM {
        return Err(refuse(&format!(
            "it was written by {program} (checkpoint format {format}), this is {PROGRAM} (format {FORMAT}); \
             run that version to resume, or delete the checkpoint to start afresh"
        )));
    }
    let body_length = u64::from_le_bytes(take(8)?.try_into().expect("eight bytes")) as usize;
    let body = take(body_length)?;
    postcard::from_bytes(body).map(Some).map_err(|_| refuse(damaged))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("fiberfold-checkpoint-{}-{name}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        dir.join("checkpoint.bin")
    }

    #[test]
    fn a_checkpoint_reads_back_bit_for_bit() {
        let path = scratch("roundtrip");
        let value = (
            vec![0.1, -0.0, f64::MIN_POSITIVE, 1.0 / 3.0],
            Some(7_usize),
            "x".to_string(),
        );
        write_checkpoint(&path, &value).unwrap();
        let back: (Vec<f64>, Option<usize>, String) = read_checkpoint(&path).unwrap().unwrap();
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&back.0), bits(&value.0));
        assert_eq!((back.1, back.2), (value.1, value.2));
        assert!(read_checkpoint::<u8>(&path.with_file_name("absent.bin"))
            .unwrap()
            .is_none());
        std::fs::remove_dir_all(path.parent().unwrap()).unwrap();
    }

    #[test]
    fn a_truncated_edited_or_foreign_checkpoint_is_refused_saying_why() {
        let path = scratch("damaged");
        write_checkpoint(&path, &vec![1.0_f64; 100]).unwrap();
        let whole = std::fs::read(&path).unwrap();
        let refused = |bytes: &[u8]| {
            std::fs::write(&path, bytes).unwrap();
            let error = read_checkpoint::<Vec<f64>>(&path).unwrap_err();
            assert!(error.is_user_input(), "{error}");
            error.to_string()
        };
        assert!(refused(&whole[..whole.len() / 2]).contains("damaged"));
        let mut edited = whole.clone();
        edited[whole.len() / 2] ^= 1;
        assert!(refused(&edited).contains("damaged"));
        assert!(refused(b"a text file").contains("not a fiberfold checkpoint"));
        let mut other_version = whole.clone();
        other_version[8] = 2;
        let body = other_version.len() - 4;
        let checksum = crc32fast::hash(&other_version[..body]).to_le_bytes();
        other_version[body..].copy_from_slice(&checksum);
        assert!(refused(&other_version).contains("format 2"));
        std::fs::remove_dir_all(path.parent().unwrap()).unwrap();
    }
}
