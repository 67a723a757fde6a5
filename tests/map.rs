//! `fiberfold map` end to end on a tiny map: shards collected equal the unsharded map, finished
//! points are reused, a folder of another map or with missing points is refused, and of two runs
//! given the same shard one computes it and the other is refused.

mod common;

use common::files::check_complete;
use common::{fiberfold, map_points as points, scratch, tiny_map, tiny_map_of};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

fn run(args: &[String]) -> (bool, String, String) {
    let out = fiberfold(args);
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn shards_collected_equal_the_whole_map_and_finished_points_are_reused() {
    let whole = scratch("map-whole");
    let (ok, stdout, stderr) = run(&tiny_map(&whole, &[]));
    assert!(ok, "{stdout}\n{stderr}");
    assert!(stdout.contains("2 points computed, 0 reused"), "{stdout}");
    let csv = std::fs::read_to_string(whole.join("map.csv")).unwrap();
    assert!(
        csv.starts_with("index,mu_l,beta,d_wrinkle,k0,minimum,d_crease"),
        "{csv}"
    );
    for file in ["map.png", "map.svg", "map-spec.json", "points/point-00000.json"] {
        assert!(whole.join(file).exists(), "{file}");
    }
    let reference = points(&whole);
    assert_eq!(reference.len(), 2);
    // The soft layer creases first, the stiff one wrinkles first (independent of the mesh here).
    assert_eq!(reference[0]["first"], "crease", "{:?}", reference[0]);
    assert_eq!(reference[1]["first"], "wrinkle", "{:?}", reference[1]);
    assert!(reference[1]["becomes"].is_string(), "{:?}", reference[1]);

    // Again: nothing is recomputed.
    let (ok, stdout, _) = run(&tiny_map(&whole, &[]));
    assert!(ok && stdout.contains("0 points computed, 2 reused"), "{stdout}");

    // Two shards into another folder, then the collection.
    let sharded = scratch("map-sharded");
    let (ok, stdout, stderr) = run(&tiny_map(&sharded, &["--shard", "1/2"]));
    assert!(ok && stdout.contains("shard 1/2: 1 points"), "{stdout}\n{stderr}");
    assert!(!sharded.join("map.csv").exists(), "a shard does not collect");
    let (ok, _, stderr) = run(&tiny_map(&sharded, &["--collect"]));
    assert!(
        !ok && stderr.contains("1 are missing") && stderr.contains("point-00000.json"),
        "{stderr}"
    );
    let (ok, _, stderr) = run(&tiny_map(&sharded, &["--shard", "0/2"]));
    assert!(ok, "{stderr}");
    let (ok, _, stderr) = run(&tiny_map(&sharded, &["--collect"]));
    assert!(ok, "{stderr}");
    assert_eq!(points(&sharded), reference, "sharded and whole maps differ");

    // Other settings into the same folder are refused, with exit code 2.
    let out = fiberfold(&tiny_map(&sharded, &["--collect", "--seed", "0.02"]));
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("`out`") && stderr.contains("another"), "{stderr}");
    for bad in [["--shard", "2/2"], ["--shard", "1/0"], ["--set", "mu_s=-1"]] {
        let out = fiberfold(&tiny_map(&scratch("map-bad"), &bad));
        assert_eq!(out.status.code(), Some(2), "{bad:?}");
    }
    let _ = std::fs::remove_dir_all(&whole);
    let _ = std::fs::remove_dir_all(&sharded);
}

#[test]
fn of_two_runs_given_the_same_shard_one_computes_it_and_the_other_says_so() {
    let dir = scratch("map-same-shard");
    let args = tiny_map_of(8, &dir, &["--shard", "0/2"]);
    // One thread: the first run's 4 points take a few seconds, long enough to be caught at work.
    let mut first = Command::new(env!("CARGO_BIN_EXE_fiberfold"))
        .args(&args)
        .env("RAYON_NUM_THREADS", "1")
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("binary runs");
    let lock = dir.join(".fiberfold-shard-0-of-2.lock");
    let start = Instant::now();
    while !lock.exists() {
        assert!(
            start.elapsed() < Duration::from_secs(60),
            "the first run never took its lock"
        );
        std::thread::sleep(Duration::from_millis(10));
    }
    let second = fiberfold(&args);
    let refused_while_running = first.try_wait().unwrap().is_none();
    let stderr = String::from_utf8_lossy(&second.stderr);
    assert_eq!(second.status.code(), Some(2), "{stderr}");
    assert_eq!(stderr.trim_end().lines().count(), 1, "{stderr}");
    assert!(
        stderr.contains(&format!("process {}", first.id())) && stderr.contains(".fiberfold-shard-0-of-2.lock"),
        "{stderr}"
    );
    let first = first.wait_with_output().unwrap();
    assert!(first.status.success(), "{}", String::from_utf8_lossy(&first.stderr));
    assert!(
        refused_while_running,
        "the first run ended before the second was refused: a slower map is needed"
    );
    assert!(String::from_utf8_lossy(&first.stdout).contains("4 points computed, 0 reused"));
    let mut written: Vec<_> = std::fs::read_dir(dir.join("points"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    written.sort();
    assert_eq!(
        written,
        [
            "point-00000.json",
            "point-00002.json",
            "point-00004.json",
            "point-00006.json"
        ],
        "the shard's points and no temporary left"
    );
    assert_eq!(check_complete(&dir), 5, "map-spec.json and the 4 points, each complete");
    let _ = std::fs::remove_dir_all(&dir);
}
