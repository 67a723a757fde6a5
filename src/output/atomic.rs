//! Files that a killed run leaves complete or absent: each is written to a hidden temporary
//! sibling (`.name.partial.ext`, same extension so that format-sniffing writers work), then
//! renamed over its path in one step. A kill leaves at most that hidden file, which the next
//! write of the same path replaces.

use crate::error::{Error, Result};
use std::path::{Path, PathBuf};

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

/// Runs `write` on a temporary path, then renames the result to `path`; on failure the
/// temporary file is removed and `path` is untouched.
pub fn write_atomically(path: &Path, write: impl FnOnce(&Path) -> Result<()>) -> Result<()> {
    let temporary = partial(path);
    let result = write(&temporary).and_then(|()| std::fs::rename(&temporary, path).map_err(|e| Error::io(path, e)));
    if result.is_err() {
        let _ = std::fs::remove_file(&temporary);
    }
    result
}

/// `std::fs::write`, atomically.
pub fn write_file(path: &Path, contents: impl AsRef<[u8]>) -> Result<()> {
    write_atomically(path, |temporary| {
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
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
