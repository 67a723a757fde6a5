//! Files that a killed run leaves complete or absent: each is written to a hidden temporary
//! sibling (`.name.partial.ext`, same extension so that format-sniffing writers work), then
//! renamed over its path in one step. A kill leaves at most that hidden file, which the next
//! write of the same path replaces. A path several processes may write at once (with the same
//! contents) takes a temporary per writer instead ([`write_file_shared`]).

use crate::error::{Error, Result};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

/// The temporary sibling of `path`.
fn partial(path: &Path) -> PathBuf {
    let stem = path
        .file_stem()
        .map_or_else(String::new, |s| s.to_string_lossy().into_owned());
    let name = match path.extension() {
        Some(ext) => format!(".{stem}.partial.{}", ext.to_string_lossy()),
        None => format!(".{stem}.partial"),
    };
    path.with_file_name(name)
}

/// The temporary sibling of `path` owned by this writer: `partial` with the process id and a
/// per-process count, so writers in other processes and threads never share it.
fn own_partial(path: &Path) -> PathBuf {
    static WRITES: AtomicUsize = AtomicUsize::new(0);
    let writer = format!("{}-{}", std::process::id(), WRITES.fetch_add(1, Ordering::Relaxed));
    let shared = partial(path);
    let name = shared
        .file_name()
        .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
    path.with_file_name(name.replacen(".partial", &format!(".partial-{writer}"), 1))
}

/// Runs `write` on a temporary path, then renames the result to `path`; on failure the
/// temporary file is removed and `path` is untouched.
pub fn write_atomically(path: &Path, write: impl FnOnce(&Path) -> Result<()>) -> Result<()> {
    write_through(path, &partial(path), write)
}

/// `write` into `temporary`, then the rename over `path` (or the temporary removed).
fn write_through(path: &Path, temporary: &Path, write: impl FnOnce(&Path) -> Result<()>) -> Result<()> {
    let result = write(temporary).and_then(|()| std::fs::rename(temporary, path).map_err(|e| Error::io(path, e)));
    if result.is_err() {
        let _ = std::fs::remove_file(temporary);
    }
    result
}

/// `std::fs::write`, atomically.
pub fn write_file(path: &Path, contents: impl AsRef<[u8]>) -> Result<()> {
    write_atomically(path, |temporary| {
        std::fs::write(temporary, contents).map_err(|e| Error::io(path, e))
    })
}

/// [`write_file`] for a path that other processes may be writing with the same contents at the
/// same time (the shards of a map): each writer renames its own temporary, and renames of
/// identical files over one another are harmless.
pub fn write_file_shared(path: &Path, contents: impl AsRef<[u8]>) -> Result<()> {
    write_through(path, &own_partial(path), |temporary| {
        std::fs::write(temporary, contents).map_err(|e| Error::io(path, e))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_failed_write_leaves_the_old_file_and_no_temporary() {
        let dir = std::env::temp_dir().join(format!("fiberfold-atomic-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("a.json");
        write_file(&path, "old").unwrap();
        let failed = write_atomically(&path, |temporary| {
            std::fs::write(temporary, "half").unwrap();
            Err(Error::Solver("stopped".into()))
        });
        assert!(failed.is_err());
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "old");
        assert!(!partial(&path).exists());
        assert_eq!(partial(&path).file_name().unwrap(), ".a.partial.json");
        let (mine, next) = (own_partial(&path), own_partial(&path));
        let name = mine.file_name().unwrap().to_string_lossy().into_owned();
        assert!(
            name.starts_with(".a.partial-") && name.ends_with(".json") && mine != next,
            "{name}"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
