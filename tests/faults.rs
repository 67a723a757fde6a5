//! Faults of a cluster's file systems: a disk that fills up during `simulate` and `map`, and a
//! read-only output folder. Each gives a one-line error naming the file and a non-zero exit,
//! leaves no partial file under a final name, and, once space is freed, the next run succeeds
//! (`map` resuming from the points it had written, `simulate --resume` from its last
//! checkpoint, which the full disk left whole). They mount file systems (a small tmpfs, a
//! read-only bind mount), so they need root: ignored by a plain `cargo test`, run by `.ci/run`
//! with `--ignored`.

mod common;

use common::files::check_complete;
use common::resume::{assert_same_files, rows, run_args};
use common::{fiberfold, map_points, quick_simulate, scratch, tiny_map_of};
use std::path::Path;
use std::process::{Command, Output, Stdio};

/// A file system mounted on a scratch folder, unmounted when dropped.
struct Mounted(common::Scratch);

impl Mounted {
    /// A tmpfs of `kib` KiB.
    fn tmpfs(name: &str, kib: usize) -> Self {
        let dir = scratch(name);
        std::fs::create_dir_all(&dir).unwrap();
        mount(&["-t", "tmpfs", "-o", &format!("size={kib}k"), "tmpfs"], &dir);
        Mounted(dir)
    }

    /// `source` again, read-only.
    fn read_only(name: &str, source: &Path) -> Self {
        let dir = scratch(name);
        std::fs::create_dir_all(&dir).unwrap();
        mount(&["--bind", source.to_str().unwrap()], &dir);
        let remounted = Mounted(dir);
        mount(&["-o", "remount,bind,ro"], &remounted.0);
        remounted
    }

    /// Resizes a tmpfs (its files stay).
    fn resize(&self, kib: usize) {
        mount(&["-o", &format!("remount,size={kib}k")], &self.0);
    }
}

impl Drop for Mounted {
    fn drop(&mut self) {
        let _ = Command::new("umount").arg("-l").arg(self.0.as_os_str()).status();
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn mount(args: &[&str], target: &Path) {
    let status = Command::new("mount")
        .args(args)
        .arg(target)
        .status()
        .expect("mount runs");
    assert!(status.success(), "mount {args:?} {} (root is needed)", target.display());
}

/// Fills the file system of `dir` up to `free_kib` KiB with `dir/filler` (tmpfs counts whole
/// 4 KiB pages).
fn fill_leaving(dir: &Path, free_kib: u64) {
    use std::io::Write;
    let path = dir.join("filler");
    let mut file = std::fs::File::create(&path).unwrap();
    let chunk = vec![0u8; 4096];
    while file.write_all(&chunk).is_ok() {}
    let written = file.metadata().unwrap().len() / 4096 * 4096;
    file.set_len(written.saturating_sub(free_kib * 1024)).unwrap();
}

/// The run's error: one line, naming a file under `dir`, the cause `cause`, exit code `code` (1
/// for a fault of the machine, 2 for an output folder that cannot be written).
fn assert_one_line_error(out: &Output, dir: &Path, cause: &str, code: i32) {
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "the run succeeded: {stderr}");
    assert_eq!(out.status.code(), Some(code), "{stderr}");
    assert_eq!(stderr.trim_end().lines().count(), 1, "not one line: {stderr}");
    assert!(
        stderr.starts_with("error: ") && stderr.contains(dir.to_str().unwrap()) && stderr.contains(cause),
        "{stderr}"
    );
}

#[test]
#[ignore = "mounts a tmpfs as root: run by .ci/run with --ignored"]
fn a_disk_that_fills_during_simulate_is_named_and_leaves_complete_files() {
    // Each VTU snapshot is ~1.5 MB: 6 MiB hold a few of the eleven.
    let disk = Mounted::tmpfs("full-simulate", 6 * 1024);
    let out = disk.0.join("run");
    let failed = fiberfold(&quick_simulate(&out));
    assert_one_line_error(&failed, &out, "No space left on device", 1);
    let stdout = String::from_utf8_lossy(&failed.stdout);
    assert!(
        stdout.contains("d = 0.0"),
        "the disk filled before the first step: {stdout}"
    );
    let left = check_complete(&out);
    assert!(left >= 3, "the steps before the fault stay on disk ({left} files)");
    assert!(out.join("amplitude.csv").is_file());

    disk.resize(64 * 1024);
    let again = fiberfold(&quick_simulate(&out));
    assert!(again.status.success(), "{}", String::from_utf8_lossy(&again.stderr));
    assert!(out.join("simulate.json").is_file());
    check_complete(&out);
}

#[test]
#[ignore = "mounts a tmpfs as root: run by .ci/run with --ignored"]
fn a_disk_that_fills_while_a_checkpoint_is_written_keeps_the_last_one_and_the_run_resumes() {
    let with_few_snapshots = |out: &Path| [run_args("mixed", out), vec!["--vtu-every".into(), "0.5".into()]].concat();
    let whole = scratch("full-checkpoint-whole");
    assert!(fiberfold(&with_few_snapshots(&whole)).status.success());

    let disk = Mounted::tmpfs("full-checkpoint", 64 * 1024);
    let out = disk.0.join("run");
    let run = std::process::Command::new(env!("CARGO_BIN_EXE_fiberfold"))
        .args(with_few_snapshots(&out))
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Once the checkpoints are under way, the disk is filled but for room for rows, not for a
    // checkpoint (about 2 MB) beside the last one.
    while !(out.join("checkpoint.bin").is_file() && rows(&out).len() > 20) {
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    fill_leaving(&disk.0, 256);
    let failed = run.wait_with_output().unwrap();
    assert_one_line_error(&failed, &out, "No space left on device", 1);
    let stderr = String::from_utf8_lossy(&failed.stderr);
    assert!(stderr.contains("checkpoint.bin"), "the disk filled elsewhere: {stderr}");
    check_complete(&out);
    assert!(
        rows(&out).len() < rows(&whole).len(),
        "the disk filled after the run's end"
    );

    std::fs::remove_file(disk.0.join("filler")).unwrap();
    let resumed = fiberfold(&[with_few_snapshots(&out), vec!["--resume".into()]].concat());
    let said = String::from_utf8_lossy(&resumed.stdout);
    assert!(resumed.status.success(), "{}", String::from_utf8_lossy(&resumed.stderr));
    assert!(said.contains("resuming at d = "), "{said}");
    assert_same_files(&whole, &out, "resumed after a full disk");
    let _ = std::fs::remove_dir_all(&whole);
}

#[test]
#[ignore = "mounts a tmpfs as root: run by .ci/run with --ignored"]
fn a_disk_that_fills_during_map_is_named_and_the_next_run_resumes() {
    let whole = scratch("full-map-reference");
    assert!(fiberfold(&tiny_map_of(6, &whole, &[])).status.success());

    let disk = Mounted::tmpfs("full-map", 1024);
    let out = disk.0.join("map");
    // Room for the study, the lock and a few point files (one page each), not for all six and
    // the figures.
    std::fs::create_dir_all(out.join("points")).unwrap();
    fill_leaving(&disk.0, 16);
    let failed = fiberfold(&tiny_map_of(6, &out, &[]));
    assert_one_line_error(&failed, &out, "No space left on device", 1);
    check_complete(&out);
    let written = std::fs::read_dir(out.join("points")).unwrap().count();
    assert!(
        (1..6).contains(&written),
        "the disk filled during the points ({written} of 6 written)"
    );

    std::fs::remove_file(disk.0.join("filler")).unwrap();
    let resumed = fiberfold(&tiny_map_of(6, &out, &[]));
    let stdout = String::from_utf8_lossy(&resumed.stdout);
    assert!(resumed.status.success(), "{}", String::from_utf8_lossy(&resumed.stderr));
    assert!(
        stdout.contains(&format!("{} points computed, {written} reused", 6 - written)),
        "{stdout}"
    );
    assert_eq!(map_points(&out), map_points(&whole));
    let _ = std::fs::remove_dir_all(&whole);
}

#[test]
#[ignore = "bind-mounts a folder read-only as root: run by .ci/run with --ignored"]
fn a_read_only_output_folder_is_named() {
    let source = scratch("read-only-source");
    std::fs::create_dir_all(source.join("existing")).unwrap();
    let read_only = Mounted::read_only("read-only", &source);
    for out in [read_only.0.join("existing"), read_only.0.join("new")] {
        let simulate = fiberfold(&quick_simulate(&out));
        assert_one_line_error(&simulate, &out, "Read-only file system", 2);
        let map = fiberfold(&tiny_map_of(2, &out, &[]));
        assert_one_line_error(&map, &out, "Read-only file system", 2);
    }
    drop(read_only);
    let _ = std::fs::remove_dir_all(&source);
}
