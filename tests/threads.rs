//! The number of threads does not change a result: `simulate` (the parallel assembly and
//! ellipticity margins) and a tiny `map` (points in parallel) with `RAYON_NUM_THREADS` = 1 and 2
//! give the same files, bit for bit, apart from wall times.

mod common;

use common::{map_points, quick_simulate, scratch, tiny_map};
use std::path::Path;
use std::process::Command;

fn run_with_threads(threads: usize, args: &[String]) {
    let out = Command::new(env!("CARGO_BIN_EXE_fiberfold"))
        .args(args)
        .env("RAYON_NUM_THREADS", threads.to_string())
        .output()
        .expect("binary runs");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
}

/// The rows of `amplitude.csv` without its timing column.
fn amplitude_without_times(dir: &Path) -> Vec<Vec<String>> {
    let text = std::fs::read_to_string(dir.join("amplitude.csv")).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let timing = header
        .iter()
        .position(|c| *c == "step_seconds")
        .expect("a timing column");
    lines
        .map(|l| {
            l.split(',')
                .enumerate()
                .filter(|(i, _)| *i != timing)
                .map(|(_, c)| c.to_string())
                .collect()
        })
        .collect()
}

#[test]
fn one_thread_and_two_give_the_same_path_and_the_same_map() {
    let mut paths = Vec::new();
    let mut maps = Vec::new();
    for threads in [1, 2] {
        let dir = scratch(&format!("threads-simulate-{threads}"));
        run_with_threads(threads, &quick_simulate(&dir));
        paths.push(amplitude_without_times(&dir));
        let map = scratch(&format!("threads-map-{threads}"));
        run_with_threads(threads, &tiny_map(&map, &[]));
        maps.push(map_points(&map));
        let _ = std::fs::remove_dir_all(&dir);
        let _ = std::fs::remove_dir_all(&map);
    }
    assert!(paths[0].len() > 10, "{} states", paths[0].len());
    assert_eq!(paths[0], paths[1], "simulate differs between 1 and 2 threads");
    assert_eq!(maps[0], maps[1], "the map differs between 1 and 2 threads");
}
