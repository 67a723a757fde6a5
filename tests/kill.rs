//! `kill -9` at random moments: every file a run leaves behind is complete (or absent), and the
//! next `reproduce` reuses the pieces that finished and redoes the interrupted one.

mod common;

use common::files::check_complete;
use common::{scratch, Rng};
use std::process::{Command, Stdio};
use std::time::Duration;

/// Starts `fiberfold args`, kills it (SIGKILL) after `seconds`; whether it had already ended.
fn kill_after(args: &[&str], seconds: f64) -> bool {
    let mut child = Command::new(env!("CARGO_BIN_EXE_fiberfold"))
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .expect("binary runs");
    std::thread::sleep(Duration::from_secs_f64(seconds));
    let ended = child.try_wait().expect("status").is_some();
    let _ = child.kill();
    child.wait().expect("reaped");
    ended
}

#[test]
fn a_killed_simulate_leaves_only_complete_files() {
    let dir = scratch("killed-simulate");
    let out = dir.to_str().unwrap();
    let args = [
        "simulate",
        "--waves",
        "4.5",
        "--nx",
        "40",
        "--layer-elements",
        "1",
        "--substrate-elements",
        "10",
        "--d-max",
        "0.24",
        "--vtu-every",
        "0.02",
        // This crude mesh snaps near d = 0.25 (with the displacement element; the mixed one
        // earlier), where the stabilisation's budget ends the run: the files are tested, not
        // the path, which ends before.
        "--element",
        "displacement",
        "--out",
        out,
    ];
    let mut rng = Rng(0x2545F4914F6CDD1D);
    let mut checked = 0;
    for _ in 0..6 {
        kill_after(&args, rng.uniform(0.05, 1.5));
        if dir.exists() {
            checked += check_complete(&dir);
        }
    }
    assert!(
        checked > 10,
        "the kills came too early to test anything ({checked} files)"
    );
    // The folder is usable again: the dead run's lock is taken over.
    let out = common::fiberfold(&args);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    check_complete(&dir);
}

#[test]
fn a_killed_reproduce_leaves_only_complete_files_and_resumes() {
    let dir = scratch("killed-reproduce");
    let out = dir.to_str().unwrap();
    let args = ["reproduce", "--quick", "--jobs", "2", "--out", out];
    let mut rng = Rng(0x9E3779B97F4A7C15);
    for _ in 0..2 {
        kill_after(&args, rng.uniform(1.0, 8.0));
        if dir.exists() {
            check_complete(&dir);
        }
    }
    let done = common::fiberfold(&args);
    assert!(done.status.success(), "{}", String::from_utf8_lossy(&done.stderr));
    let stdout = String::from_utf8_lossy(&done.stdout);
    let reused = stdout.lines().filter(|l| l.ends_with("already done, reused")).count();
    let redone = stdout.lines().filter(|l| l.ends_with(" s  done")).count();
    assert!(reused >= 1, "finished pieces are reused: {stdout}");
    assert!(redone >= 1, "the interrupted pieces are redone: {stdout}");
    assert!(check_complete(&dir) > 20);
}
