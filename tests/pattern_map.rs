//! A map of patterns (`fiberfold pattern --x ... --y ...`) as a user runs it: every point is
//! the single `pattern` run of its parameters, the shards assemble into the unsharded map, and
//! a path followed past each point's own onset ends there.

mod common;

use common::{fiberfold, rejected, scratch};
use std::path::Path;

/// A small patch: three hexahedra per wavelength, four through the substrate.
const SMALL: [&str; 4] = ["--elements-per-wavelength", "3", "--substrate-elements", "4"];

/// Fibres in the surface and vertical ones, at two contrasts.
const AXES: [&str; 12] = [
    "--x",
    "beta",
    "--x-from",
    "0",
    "--x-to",
    "1.5707963",
    "--x-points",
    "2",
    "--y",
    "mu_l",
    "--y-from",
    "8",
];

/// Runs `fiberfold pattern` with `args` into `out`, which must succeed: its standard output.
fn run(out: &Path, args: &[&str]) -> String {
    let output = fiberfold(&[&["pattern"][..], args, &["--out", out.to_str().unwrap()]].concat());
    let stdout = String::from_utf8_lossy(&output.stdout).to_string();
    assert!(
        output.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&output.stderr)
    );
    stdout
}

/// `map.csv` without its last column (the points' wall times).
fn table(out: &Path) -> Vec<String> {
    let text = std::fs::read_to_string(out.join("map.csv")).unwrap();
    text.lines()
        .map(|l| l.rsplit_once(',').unwrap().0.to_string())
        .collect()
}

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

#[test]
fn every_point_is_its_own_pattern_run_and_shards_assemble_into_the_whole_map() {
    let axes = [&AXES[..], &["--y-to", "12", "--y-points", "2"], &SMALL[..]].concat();
    let whole = scratch("pattern-map-whole");
    let stdout = run(&whole, &axes);
    assert!(
        stdout.contains("map of patterns: 2 x 2 points over beta in [0, 1.5707963] and mu_l in [8, 12]"),
        "{stdout}"
    );
    let rows = table(&whole);
    assert_eq!(rows.len(), 5, "{rows:?}");
    assert!(
        rows[0].starts_with("index,beta,mu_l,d_c,theta0_degrees,d_bifurcation"),
        "{}",
        rows[0]
    );
    // Each point against `pattern` run alone on its parameters (Poisson's ratio kept: K_l
    // scales with mu_l), and against the exact theory's onset.
    let report = json(&whole.join("map.json"));
    for point in report["points"].as_array().unwrap() {
        let (beta, mu_l) = (point["x"].as_f64().unwrap(), point["y"].as_f64().unwrap());
        let alone = scratch(&format!("pattern-map-alone-{}", point["index"]));
        let set = |key: &str, value: f64| format!("{key}={value}");
        run(
            &alone,
            &[
                &[
                    "--set",
                    &set("beta", beta),
                    "--set",
                    &set("mu_l", mu_l),
                    "--set",
                    &set("K_l", 3.0 * mu_l),
                ],
                &SMALL[..],
            ]
            .concat(),
        );
        let single = json(&alone.join("pattern.json"));
        for key in ["d_bifurcation", "relative_difference", "unknowns"] {
            assert_eq!(point[key], single[key], "{key} at {point}");
        }
        assert_eq!(point["d_c"], single["onset_theory"]["d_c"], "{point}");
        // The point's own files are the single run's.
        let files = json(&whole.join(format!(
            "points/point-{:05}/pattern.json",
            point["index"].as_u64().unwrap()
        )));
        assert_eq!(files["d_bifurcation"], single["d_bifurcation"]);
        assert!(point["relative_difference"].as_f64().unwrap().abs() < 0.05, "{point}");
    }
    assert!(std::fs::metadata(whole.join("map.png")).unwrap().len() > 1000);

    let sharded = scratch("pattern-map-shards");
    for shard in ["0/2", "1/2"] {
        let stdout = run(&sharded, &[&axes[..], &["--shard", shard]].concat());
        assert!(stdout.contains("assemble the shards"), "{stdout}");
    }
    run(&sharded, &[&axes[..], &["--collect"]].concat());
    assert_eq!(table(&sharded), rows);
    // A second run reuses every point; another map in the same folder is refused.
    let stdout = run(&sharded, &axes);
    assert!(stdout.contains("0 points computed, 4 reused"), "{stdout}");
    let other = [
        &AXES[..],
        &["--y-to", "13", "--y-points", "2"],
        &SMALL[..],
        &["--out", sharded.to_str().unwrap()],
    ]
    .concat();
    rejected(
        &[&["pattern"][..], &other].concat(),
        &["`out`", "a map of the same parameters"],
    );
}

#[test]
fn a_path_followed_past_the_onset_ends_as_far_past_each_points_own_onset() {
    let out = scratch("pattern-map-followed");
    let axes = [
        "--x",
        "beta",
        "--x-from",
        "1.5707963",
        "--x-points",
        "1",
        "--y",
        "mu_l",
        "--y-from",
        "8",
        "--y-to",
        "12",
        "--y-points",
        "2",
        "--follow-past",
        "0.02",
    ];
    run(&out, &[&axes[..], &SMALL[..]].concat());
    let report = json(&out.join("map.json"));
    let points = report["points"].as_array().unwrap();
    let onsets: Vec<f64> = points.iter().map(|p| p["d_c"].as_f64().unwrap()).collect();
    assert!(
        onsets[0] > onsets[1] + 0.01,
        "a stiffer layer wrinkles earlier: {onsets:?}"
    );
    for point in points {
        let end = point["d"].as_f64().unwrap();
        assert!((end - point["d_c"].as_f64().unwrap() - 0.02).abs() < 1e-9, "{point}");
        // Vertical fibres: no direction of the surface preferred, the two waves of the
        // square patch superposed (with their harmonics).
        let directions = point["directions"].as_array().unwrap();
        let mut leading: Vec<f64> = directions[..2]
            .iter()
            .map(|d| d["wave"]["theta_degrees"].as_f64().unwrap())
            .collect();
        leading.sort_by(f64::total_cmp);
        assert_eq!(leading, [0.0, 90.0], "{point}");
        assert!(
            directions[..2].iter().all(|d| d["share"].as_f64().unwrap() > 0.2),
            "{point}"
        );
        let single = json(&out.join(format!(
            "points/point-{:05}/pattern.json",
            point["index"].as_u64().unwrap()
        )));
        assert_eq!(single["path"]["d_reached"], point["d"]);
    }
    let text = std::fs::read_to_string(out.join("map.csv")).unwrap();
    assert!(text.lines().skip(1).all(|l| l.contains(",followed,")), "{text}");
}

/// Flags that do not go together: exit 2, naming the one missing or in conflict.
fn refused_flags(args: &[&str], must_mention: &str) {
    let out = fiberfold(args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
    assert!(stderr.contains(must_mention), "{args:?}: {stderr}");
}

#[test]
fn a_map_of_patterns_names_its_bad_flags() {
    refused_flags(&["pattern", "--x", "beta"], "--y");
    refused_flags(&["pattern", "--collect"], "--x");
    refused_flags(
        &["pattern", "--follow-to", "0.2", "--follow-past", "0.1"],
        "--follow-past",
    );
    rejected(
        &["pattern", "--x", "beta", "--y", "beta"],
        &["`y`", "a parameter other than --x"],
    );
    rejected(&["pattern", "--x", "nope", "--y", "psi"], &["`x`", "numeric parameter"]);
    rejected(
        &["pattern", "--x", "beta", "--y", "psi", "--follow-past", "0.95"],
        &["`follow-past`"],
    );
}
