//! One writer per output folder: a run takes `DIR/.fiberfold.lock` (holding its pid) and
//! releases it when it ends; a second run into a folder whose lock belongs to a live process is
//! refused, and a lock left by a dead one (a killed run) is taken over.

use crate::error::{Error, Result};
use std::io::Write;
use std::path::{Path, PathBuf};

/// The lock of one output folder, released on drop.
#[derive(Debug)]
pub struct OutputLock {
    path: PathBuf,
}

impl OutputLock {
    /// Takes the lock of `dir` (created if needed).
    pub fn acquire(dir: &Path) -> Result<Self> {
        Self::acquire_named(dir, ".fiberfold.lock")
    }

    /// Takes the lock file `name` of `dir`: writers of disjoint parts of one folder (the shards
    /// of a map) hold one each.
    pub fn acquire_named(dir: &Path, name: &str) -> Result<Self> {
        super::ensure_dir(dir)?;
        let path = dir.join(name);
        for _ in 0..3 {
            match std::fs::OpenOptions::new().write(true).create_new(true).open(&path) {
                Ok(mut file) => {
                    write!(file, "{}", std::process::id()).map_err(|e| Error::io(&path, e))?;
                    return Ok(OutputLock { path });
                }
                Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {
                    let holder = std::fs::read_to_string(&path)
                        .ok()
                        .and_then(|t| t.trim().parse::<u32>().ok());
                    match holder {
                        Some(pid) if pid != std::process::id() && alive(pid) => {
                            return Err(Error::invalid(
                                "out",
                                dir.display(),
                                &format!(
                                    "a folder no other running fiberfold writes to (process {pid} holds {})",
                                    path.display()
                                ),
                            ))
                        }
                        // A stale lock (dead writer, or unreadable): take it over.
                        _ => {
                            let _ = std::fs::remove_file(&path);
                        }
                    }
                }
                Err(e) => return Err(Error::io(&path, e)),
            }
        }
        Err(Error::io(
            &path,
            std::io::Error::other("the lock file keeps reappearing"),
        ))
    }
}

impl Drop for OutputLock {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.path);
    }
}

/// Whether process `pid` exists (Linux: `/proc/<pid>`; elsewhere assumed alive).
fn alive(pid: u32) -> bool {
    if cfg!(target_os = "linux") {
        Path::new(&format!("/proc/{pid}")).exists()
    } else {
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_live_lock_refuses_and_a_stale_one_is_taken_over() {
        let dir = std::env::temp_dir().join(format!("fiberfold-lock-{}", std::process::id()));
        let lock = OutputLock::acquire(&dir).unwrap();
        // pid 1 is alive on Linux: a folder it holds is refused.
        std::fs::write(dir.join(".fiberfold.lock"), "1").unwrap();
        let err = OutputLock::acquire(&dir).unwrap_err();
        assert!(err.is_user_input() && err.to_string().contains("process 1"), "{err}");
        // A pid that cannot exist: stale, taken over.
        std::fs::write(dir.join(".fiberfold.lock"), "4294967295").unwrap();
        drop(lock);
        std::fs::write(dir.join(".fiberfold.lock"), "4294967295").unwrap();
        let taken = OutputLock::acquire(&dir).unwrap();
        let holder = std::fs::read_to_string(dir.join(".fiberfold.lock")).unwrap();
        assert_eq!(holder, std::process::id().to_string());
        drop(taken);
        assert!(!dir.join(".fiberfold.lock").exists());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
