//! `simulate --resume`: a run killed (SIGKILL) at an accepted state and resumed from its last
//! checkpoint leaves the files of the uninterrupted run, bit for bit but for timings, with
//! either element, whether killed on a smooth stretch, inside a damped stretch or after the
//! first contact. A checkpoint of another run, of another version, or damaged, is refused
//! with one line and exit 2, and the folder is left as it was.

mod common;

use common::resume::{assert_same_files, kill_at_row, rows, run_args};
use common::{fiberfold, rejected, scratch};
use std::path::{Path, PathBuf};

fn column(rows: &[Vec<String>], name: &str) -> Vec<f64> {
    let i = rows[0].iter().position(|c| c == name).unwrap();
    rows[1..].iter().map(|r| r[i].parse().unwrap()).collect()
}

#[test]
fn a_run_killed_anywhere_and_resumed_leaves_the_uninterrupted_files_with_either_element() {
    for element in ["mixed", "displacement"] {
        let whole = scratch(&format!("checkpoint-whole-{element}"));
        let run = fiberfold(&run_args(element, &whole));
        assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
        let table = rows(&whole);
        let first = |name: &str| column(&table, name).iter().position(|&x| x > 0.0);
        let contact = first("in_contact").expect("a contact");
        // States (header first): on a smooth stretch; inside the damped stretch or just after
        // the snap; well after the first contact.
        let crossing = match element {
            "mixed" => (
                "damped",
                first("stabilisation_energy_fraction").expect("a damped stretch") + 4,
            ),
            _ => ("just after the snap", first("snap").expect("a snap") + 1),
        };
        assert!(
            crossing.1 < contact + 20 && contact + 20 < table.len() - 5,
            "{element}: {crossing:?}, {contact}"
        );
        for (where_, rows_wanted) in [("smooth", 12), crossing, ("in contact", contact + 20)] {
            let what = format!("{element}, killed {where_} (at about state {rows_wanted})");
            let resumed = scratch(&format!("checkpoint-resumed-{element}-{rows_wanted}"));
            let args = run_args(element, &resumed);
            kill_at_row(&args, &resumed, rows_wanted + 1);
            assert!(
                rows(&resumed).len() < table.len(),
                "{what}: the run ended before it was killed"
            );
            let again = fiberfold(&[args, vec!["--resume".into()]].concat());
            let said = String::from_utf8_lossy(&again.stdout).to_string() + &String::from_utf8_lossy(&again.stderr);
            assert!(again.status.success(), "{what}: {said}");
            assert!(said.contains("resuming at d = "), "{what}: not resumed: {said}");
            assert_same_files(&whole, &resumed, &what);
            common::files::check_complete(&resumed);
        }
    }
}

/// A file's bytes and modification time, for every file in `dir`.
fn snapshot(dir: &Path) -> Vec<(PathBuf, Vec<u8>, std::time::SystemTime)> {
    let mut all: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .map(|p| {
            (
                p.clone(),
                std::fs::read(&p).unwrap(),
                p.metadata().unwrap().modified().unwrap(),
            )
        })
        .collect();
    all.sort_by(|a, b| a.0.cmp(&b.0));
    all
}

#[test]
fn a_checkpoint_of_another_run_or_damaged_is_refused_and_the_folder_left_as_it_was() {
    let dir = scratch("checkpoint-refused");
    let out = dir.to_str().unwrap();
    let base = ["simulate", "--waves", "5", "--out", out];
    let run = fiberfold(&[&base[..], &["--d-max", "0.05", "--checkpoint-every", "2"]].concat());
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    assert!(dir.join("checkpoint.bin").is_file());
    let before = snapshot(&dir);
    fn with<'a>(base: &[&'a str], extra: &[&'a str]) -> Vec<&'a str> {
        [base, extra, &["--resume"]].concat()
    }
    rejected(
        &with(&base, &["--d-max", "0.05", "--set", "mu_l=30"]),
        &["checkpoint.bin", "parameters", "mu_l"],
    );
    rejected(
        &with(&base, &["--d-max", "0.06"]),
        &["checkpoint.bin", "options", "d_max: 0.05", "d_max: 0.06"],
    );
    rejected(
        &with(&base, &["--d-max", "0.05", "--element", "displacement"]),
        &["checkpoint.bin", "options", "Displacement"],
    );
    assert_eq!(snapshot(&dir), before, "a refusal touched the folder");
    // Damaged: truncated, or one byte changed.
    let whole = std::fs::read(dir.join("checkpoint.bin")).unwrap();
    for damaged in [whole[..whole.len() - 9].to_vec(), {
        let mut edited = whole.clone();
        edited[whole.len() / 3] ^= 0x10;
        edited
    }] {
        std::fs::write(dir.join("checkpoint.bin"), &damaged).unwrap();
        let before = snapshot(&dir);
        rejected(&with(&base, &["--d-max", "0.05"]), &["checkpoint.bin", "damaged"]);
        assert_eq!(snapshot(&dir), before, "a refusal touched the folder");
    }
    // The checkpoint's own interval may change: it does not change the path.
    std::fs::write(dir.join("checkpoint.bin"), &whole).unwrap();
    let resumed = fiberfold(&with(&base, &["--d-max", "0.05", "--checkpoint-every", "7"]));
    assert!(resumed.status.success(), "{}", String::from_utf8_lossy(&resumed.stderr));
    // Arc length keeps none; resuming one is refused.
    rejected(
        &with(
            &base,
            &[
                "--d-max",
                "0.05",
                "--continuation",
                "arc-length",
                "--no-contact",
                "--stabilisation",
                "none",
            ],
        ),
        &["resume", "arc-length"],
    );
}

#[test]
fn resume_without_a_checkpoint_starts_from_the_beginning() {
    let dir = scratch("checkpoint-none");
    let out = dir.to_str().unwrap();
    let run = fiberfold(&["simulate", "--waves", "5", "--d-max", "0.02", "--resume", "--out", out]);
    let said = String::from_utf8_lossy(&run.stdout).to_string() + &String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{said}");
    assert!(said.contains("no checkpoint"), "{said}");
    assert_eq!(rows(&dir).len(), 5, "header and the states at d = 0.005, ..., 0.02");
}

/// The lines of `file` in `dir` (none if it is absent).
fn lines(dir: &Path, file: &str) -> Vec<String> {
    std::fs::read_to_string(dir.join(file))
        .unwrap_or_default()
        .lines()
        .map(str::to_string)
        .collect()
}

#[test]
fn a_pattern_path_killed_and_resumed_gives_the_uninterrupted_states() {
    // The checkerboard of Table 1's fibres in the surface turns unstable and is left at
    // d = 0.1: killed a few states after it was left.
    let args = |out: &Path| -> Vec<String> {
        let flags = [
            "pattern",
            "--set",
            "beta=0",
            "--elements-per-wavelength",
            "4",
            "--substrate-elements",
            "8",
            "--follow-to",
            "0.12",
            "--checkpoint-every",
            "1",
            "--out",
            out.to_str().unwrap(),
        ];
        flags.iter().map(|s| s.to_string()).collect()
    };
    let whole = scratch("checkpoint-pattern-whole");
    let run = fiberfold(&args(&whole));
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let table = lines(&whole, "pattern.csv");
    let left = table
        .iter()
        .position(|l| l.split(',').nth(4) == Some("1"))
        .expect("a state left");
    let rows_wanted = left + 3;
    let what = format!("pattern, killed at about state {rows_wanted}");
    let resumed = scratch(&format!("checkpoint-pattern-{rows_wanted}"));
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_fiberfold"))
        .args(args(&resumed))
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    while child.try_wait().unwrap().is_none() && lines(&resumed, "pattern.csv").len() <= rows_wanted {
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    let _ = child.kill();
    child.wait().unwrap();
    assert!(
        lines(&resumed, "pattern.csv").len() < table.len(),
        "{what}: ended before the kill"
    );
    let again = fiberfold(&[args(&resumed), vec!["--resume".into()]].concat());
    let said = String::from_utf8_lossy(&again.stdout).to_string();
    assert!(
        again.status.success(),
        "{what}: {said}{}",
        String::from_utf8_lossy(&again.stderr)
    );
    assert!(
        said.contains("resuming the path at d = "),
        "{what}: not resumed: {said}"
    );
    assert_eq!(lines(&resumed, "pattern.csv"), table, "{what}: pattern.csv");
    for file in ["state.vtu", "mode.vtu", "inertia.csv", "wave_vectors.csv"] {
        assert!(
            std::fs::read(whole.join(file)).unwrap() == std::fs::read(resumed.join(file)).unwrap(),
            "{what}: {file}"
        );
    }
    let json = |dir: &Path| common::resume::json_without_timings(&dir.join("pattern.json"), dir);
    assert_eq!(json(&whole), json(&resumed), "{what}: pattern.json");
}
