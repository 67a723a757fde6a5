//! `fiberfold map` end to end on a tiny map: shards collected equal the unsharded map, finished
//! points are reused, and a folder of another map or with missing points is refused.

mod common;

use common::{fiberfold, map_points as points, scratch, tiny_map};

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
