//! Runs killed and resumed: their files against an uninterrupted run's, timings aside.

use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::Duration;

/// The runs: the mixed element on the coarse mesh, five waves to d = 0.29, which snaps into a
/// damped stretch near d = 0.28 and then touches itself; the displacement element on a crude
/// mesh, crossing its snap near d = 0.257 by minimisation, into contact.
pub fn run_args(element: &str, out: &Path) -> Vec<String> {
    let case: &[&str] = match element {
        "mixed" => &["--waves", "5", "--d-max", "0.29"],
        _ => &[
            "--waves",
            "4.5",
            "--nx",
            "40",
            "--layer-elements",
            "1",
            "--substrate-elements",
            "10",
            "--d-max",
            "0.3",
            "--stabilisation",
            "snap",
        ],
    };
    let common = [
        "--element",
        element,
        "--checkpoint-every",
        "1",
        "--out",
        out.to_str().unwrap(),
    ];
    ["simulate"]
        .iter()
        .chain(case)
        .chain(&common)
        .map(|s| s.to_string())
        .collect()
}

pub fn rows(dir: &Path) -> Vec<Vec<String>> {
    let text = std::fs::read_to_string(dir.join("amplitude.csv")).unwrap_or_default();
    text.lines()
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect()
}

/// `amplitude.csv` without its timing column.
pub fn rows_without_timings(dir: &Path) -> Vec<Vec<String>> {
    let rows = rows(dir);
    let timing = rows[0]
        .iter()
        .position(|c| c.contains("seconds"))
        .expect("a timing column");
    rows.into_iter()
        .map(|mut row| {
            row.remove(timing);
            row
        })
        .collect()
}

/// A JSON file with every timing and the checkpoints' count dropped, and the folder's name replaced.
pub fn json_without_timings(path: &Path, dir: &Path) -> Value {
    fn strip(value: &mut Value) {
        match value {
            Value::Object(map) => {
                // The checkpoints written are the run's own bookkeeping (and their size the
                // records' timings').
                map.retain(|key, _| !key.contains("seconds") && key != "checkpoints");
                map.values_mut().for_each(strip);
            }
            Value::Array(items) => items.iter_mut().for_each(strip),
            _ => {}
        }
    }
    let text = std::fs::read_to_string(path)
        .unwrap()
        .replace(dir.to_str().unwrap(), "OUT");
    let mut value: Value = serde_json::from_str(&text).unwrap();
    strip(&mut value);
    value
}

/// Runs `args` until `amplitude.csv` has `rows` rows, then kills it (SIGKILL).
pub fn kill_at_row(args: &[String], out: &Path, rows_wanted: usize) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_fiberfold"))
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .expect("binary runs");
    while child.try_wait().unwrap().is_none() && rows(out).len() < rows_wanted {
        std::thread::sleep(Duration::from_millis(5));
    }
    let _ = child.kill();
    child.wait().unwrap();
}

pub fn files(dir: &Path, extension: &str) -> Vec<PathBuf> {
    let mut found: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == extension))
        .collect();
    found.sort();
    found
}

/// Every file the uninterrupted run in `whole` wrote, compared with the resumed run's in `resumed`.
pub fn assert_same_files(whole: &Path, resumed: &Path, what: &str) {
    assert_eq!(
        rows_without_timings(whole),
        rows_without_timings(resumed),
        "{what}: amplitude.csv"
    );
    for extension in ["vtu", "pvd"] {
        let names = |dir| {
            files(dir, extension)
                .iter()
                .map(|p| p.file_name().unwrap().to_owned())
                .collect::<Vec<_>>()
        };
        assert_eq!(names(whole), names(resumed), "{what}: the {extension} files");
        for path in files(whole, extension) {
            let other = resumed.join(path.file_name().unwrap());
            assert!(
                std::fs::read(&path).unwrap() == std::fs::read(&other).unwrap(),
                "{what}: {}",
                other.display()
            );
        }
    }
    assert_eq!(
        std::fs::read(whole.join("surface.csv")).unwrap(),
        std::fs::read(resumed.join("surface.csv")).unwrap()
    );
    for json in [
        "simulate.json",
        "secondary.json",
        "snaps.json",
        "contact.json",
        "onset_estimates.json",
    ] {
        let (a, b) = (
            json_without_timings(&whole.join(json), whole),
            json_without_timings(&resumed.join(json), resumed),
        );
        assert_eq!(a, b, "{what}: {json}");
    }
}
