//! One writer per output folder: a run takes `DIR/.fiberfold.lock`, which names its host and
//! pid, and releases it when it ends. A second run into a folder whose lock belongs to a live
//! process is refused. A lock left by a dead process of this host (a killed run) is taken over;
//! a lock from another host (a shared file system on a cluster) never is, since no process
//! there can be checked: it is refused with the way to clear it. A folder that is a file, cannot be
//! created or cannot be written is refused as bad input, before anything is computed.

use crate::error::{Error, Result};
use std::path::{Path, PathBuf};

/// The lock of one output folder, released on drop; a folder the lock created and nothing else
/// wrote into (the command was refused after all) is removed with it.
#[derive(Debug)]
pub struct OutputLock {
    path: PathBuf,
    /// The folder, if the lock created it.
    created: Option<PathBuf>,
}

impl OutputLock {
    /// Takes the lock of `dir` (created if needed).
    pub fn acquire(dir: &Path) -> Result<Self> {
        Self::acquire_named(dir, ".fiberfold.lock")
    }

    /// Takes the lock file `name` of `dir`: writers of disjoint parts of one folder (the shards
    /// of a map) hold one each.
    pub fn acquire_named(dir: &Path, name: &str) -> Result<Self> {
        if dir.exists() && !dir.is_dir() {
            return Err(Error::invalid("out", dir.display(), "a folder (this is a file)"));
        }
        let created = (!dir.exists()).then(|| dir.to_path_buf());
        if let Err(e) = std::fs::create_dir_all(dir) {
            return Err(Error::invalid(
                "out",
                dir.display(),
                &format!("a folder that can be created ({e})"),
            ));
        }
        let path = dir.join(name);
        for _ in 0..3 {
            // The lock appears whole or not at all: written aside, then hard-linked to its name
            // (which fails if the name exists), so no reader ever sees it empty.
            let staged = dir.join(format!("{name}.{}", std::process::id()));
            if let Err(e) = std::fs::write(&staged, format!("{} {}", host(), std::process::id())) {
                let _ = std::fs::remove_file(&staged); // a full disk may have created it empty
                                                       // A full disk is a fault of the machine; any other failure, of the folder asked for.
                return Err(match e.kind() {
                    std::io::ErrorKind::StorageFull => Error::io(&path, e),
                    _ => Error::invalid("out", dir.display(), &format!("a folder that can be written ({e})")),
                });
            }
            let linked = std::fs::hard_link(&staged, &path);
            let _ = std::fs::remove_file(&staged);
            match linked {
                Ok(()) => return Ok(OutputLock { path, created }),
                Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {
                    let text = std::fs::read_to_string(&path).unwrap_or_default();
                    match Holder::parse(&text) {
                        Some(Holder { host: Some(other), pid }) if other != host() => {
                            return Err(Error::invalid(
                                "out",
                                dir.display(),
                                &format!(
                                    "a folder no other fiberfold writes to (process {pid} on host {other} holds {}; \
                                     if that run has ended, delete the file)",
                                    path.display()
                                ),
                            ))
                        }
                        Some(Holder { pid, .. }) if pid != std::process::id() && alive(pid) => {
                            return Err(Error::invalid(
                                "out",
                                dir.display(),
                                &format!(
                                    "a folder no other running fiberfold writes to (process {pid} holds {})",
                                    path.display()
                                ),
                            ))
                        }
                        // A stale lock (a dead writer of this host, or unreadable): take it over.
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
        if let Some(dir) = &self.created {
            let _ = std::fs::remove_dir(dir); // only if empty
        }
    }
}

/// What a lock file says: `host pid` (a bare `pid` from older versions has no host).
struct Holder {
    host: Option<String>,
    pid: u32,
}

impl Holder {
    fn parse(text: &str) -> Option<Self> {
        match text.split_whitespace().collect::<Vec<_>>()[..] {
            [pid] => Some(Holder {
                host: None,
                pid: pid.parse().ok()?,
            }),
            [host, pid] => Some(Holder {
                host: Some(host.to_string()),
                pid: pid.parse().ok()?,
            }),
            _ => None,
        }
    }
}

/// This machine's name (Linux: `/proc/sys/kernel/hostname`), without spaces.
fn host() -> String {
    std::fs::read_to_string("/proc/sys/kernel/hostname")
        .map(|h| h.trim().replace(char::is_whitespace, "_"))
        .ok()
        .filter(|h| !h.is_empty())
        .unwrap_or_else(|| "unknown-host".into())
}

/// Whether process `pid` is alive (Linux: `/proc/<pid>/stat` exists and its state is not zombie
/// or dead: a killed run whose parent has not reaped it holds nothing; elsewhere assumed alive).
fn alive(pid: u32) -> bool {
    if !cfg!(target_os = "linux") {
        return true;
    }
    match std::fs::read_to_string(format!("/proc/{pid}/stat")) {
        // The state is the first field after the command's name, which is in parentheses.
        Ok(stat) => !matches!(
            stat.rsplit_once(')')
                .and_then(|(_, rest)| rest.trim_start().chars().next()),
            Some('Z' | 'X' | 'x')
        ),
        Err(_) => Path::new(&format!("/proc/{pid}")).exists(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_folder_the_lock_created_goes_with_it_unless_something_was_written() {
        let root = std::env::temp_dir().join(format!("fiberfold-lock-created-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&root);
        let (empty, written) = (root.join("refused"), root.join("written"));
        drop(OutputLock::acquire(&empty).unwrap());
        assert!(!empty.exists());
        let lock = OutputLock::acquire(&written).unwrap();
        std::fs::write(written.join("result.csv"), "x\n").unwrap();
        drop(lock);
        assert!(written.join("result.csv").exists() && !written.join(".fiberfold.lock").exists());
        // A folder that was there before stays, empty or not.
        std::fs::create_dir_all(&empty).unwrap();
        drop(OutputLock::acquire(&empty).unwrap());
        assert!(empty.is_dir());
        std::fs::remove_dir_all(&root).unwrap();
    }

    #[test]
    fn a_killed_process_not_yet_reaped_holds_nothing() {
        let mut child = std::process::Command::new("true").spawn().expect("true runs");
        let pid = child.id();
        // Exited but not waited for: a zombie, as a killed run is until its parent reaps it.
        let start = std::time::Instant::now();
        while alive(pid) && start.elapsed() < std::time::Duration::from_secs(10) {
            std::thread::sleep(std::time::Duration::from_millis(10));
        }
        assert!(Path::new(&format!("/proc/{pid}")).exists(), "not yet reaped");
        assert!(!alive(pid));
        child.wait().unwrap();
        assert!(alive(std::process::id()));
    }

    #[test]
    fn a_live_lock_refuses_and_a_stale_one_is_taken_over() {
        let dir = std::env::temp_dir().join(format!("fiberfold-lock-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
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
        assert_eq!(holder, format!("{} {}", host(), std::process::id()));
        drop(taken);
        // Another host's lock, even of a pid that is dead here, is never taken over.
        std::fs::write(dir.join(".fiberfold.lock"), "node-17-elsewhere 4294967295").unwrap();
        let err = OutputLock::acquire(&dir).unwrap_err().to_string();
        assert!(
            err.contains("on host node-17-elsewhere") && err.contains("delete the file"),
            "{err}"
        );
        // This host's lock of a dead pid is.
        std::fs::write(dir.join(".fiberfold.lock"), format!("{} 4294967295", host())).unwrap();
        drop(OutputLock::acquire(&dir).unwrap());
        assert!(!dir.join(".fiberfold.lock").exists());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
