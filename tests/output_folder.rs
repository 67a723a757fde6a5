//! One writer per output folder, and an output folder that can be written: every command that
//! writes takes the folder's lock before it computes, and a folder that is a file or cannot be
//! created or written is refused as bad input.

mod common;

use common::{fiberfold, rejected, scratch};

#[test]
fn a_second_run_into_a_folder_being_written_is_refused() {
    let dir = scratch("locked");
    let out = dir.to_str().unwrap();
    let args = ["simulate", "--waves", "4.5", "--d-max", "0.3", "--out", out];
    let mut first = std::process::Command::new(env!("CARGO_BIN_EXE_fiberfold"))
        .args(args)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    // Wait until the first run holds the folder.
    let lock = dir.join(".fiberfold.lock");
    let start = std::time::Instant::now();
    while !lock.exists() && start.elapsed().as_secs() < 10 {
        std::thread::sleep(std::time::Duration::from_millis(10));
    }
    let message = rejected(&args, &["`out`", "no other running fiberfold", &first.id().to_string()]);
    assert_eq!(message.lines().filter(|l| l.starts_with("error: ")).count(), 1);
    // Every command that writes is refused there, before it computes.
    for command in [
        &["onset"][..],
        &["homogeneous"],
        &["dispersion", "--points", "3"],
        &["sweep", "--param", "beta", "--from", "0", "--to", "1", "--points", "2"],
        &["params"],
        &["bifurcation"],
        &["crease"],
        &["pattern"],
        &["bench", "stability"],
        &["map", "--x", "mu_l", "--x-from", "3", "--x-to", "4", "--x-points", "1"],
        &["reproduce"],
    ] {
        let mut other = command.to_vec();
        other.extend(["--out", out]);
        rejected(&other, &["`out`", "no other running fiberfold"]);
    }
    first.kill().unwrap();
    first.wait().unwrap();
    // The dead run's lock is taken over.
    let again = fiberfold(&["simulate", "--waves", "4.5", "--d-max", "0.01", "--out", out]);
    assert!(again.status.success(), "{}", String::from_utf8_lossy(&again.stderr));
}

/// An output folder that is a file, or that cannot be created or written, is refused as bad
/// input before anything is computed.
#[test]
fn an_output_folder_that_cannot_be_written_is_refused() {
    let file = scratch("out-file");
    std::fs::write(&file, "not a folder").unwrap();
    let map = ["map", "--x", "mu_l", "--x-from", "3", "--x-to", "4", "--x-points", "1"];
    for command in [&["onset"][..], &["simulate", "--waves", "4.5"], &["pattern"], &map] {
        let mut args = command.to_vec();
        args.extend(["--out", file.to_str().unwrap()]);
        rejected(&args, &["`out`", "a folder (this is a file)"]);
    }
    rejected(
        &["onset", "--out", "/proc/fiberfold"],
        &["`out`", "a folder that can be created"],
    );
    rejected(
        &["homogeneous", "--out", "/proc"],
        &["`out`", "a folder that can be written"],
    );
}
