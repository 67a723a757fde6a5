//! `fiberfold pattern` as a user runs it: a coarse patch's files, and bad input.

mod common;

use common::{fiberfold, scratch};

/// `fiberfold pattern` with `args` into a scratch folder named `name`, which must succeed: the
/// folder and `pattern.json`.
fn pattern(name: &str, args: &[&str]) -> (common::Scratch, serde_json::Value) {
    let out = scratch(name);
    let output = fiberfold(&[&["pattern"][..], args, &["--out", out.to_str().unwrap()]].concat());
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&output.stderr)
    );
    assert!(stdout.contains("admissible wave vectors nearest the onset"), "{stdout}");
    let report = serde_json::from_str(&std::fs::read_to_string(out.join("pattern.json")).unwrap()).unwrap();
    (out, report)
}

#[test]
fn a_coarse_patch_writes_its_summary_tables_figure_and_vtu() {
    let args = [
        "--set",
        "beta=0.785398",
        "--set",
        "psi=0.5235988",
        "--elements-per-wavelength",
        "3",
    ];
    let (out, report) = pattern("pattern", &[&args[..], &["--follow-to", "0.13"]].concat());
    // Inclined fibres at psi = 30 deg: one critical wave vector, whose crests run along the
    // fibres' projection (the wave vector at 120 deg from X), a cosine and a sine mode.
    assert_eq!(report["negative_pivots"], 2, "{report}");
    let wave = &report["mode_wave_vectors"][0];
    assert!((wave["theta_degrees"].as_f64().unwrap() - 120.0).abs() < 0.5, "{wave}");
    let relative = report["relative_difference"].as_f64().unwrap();
    assert!(relative > 0.0 && relative < 0.05, "{relative}");
    for (file, header) in [
        ("wave_vectors.csv", "m,n,k,theta_degrees,d_c"),
        ("inertia.csv", "d,negative_pivots"),
        ("mode_spectrum.csv", "m,n,k,theta_degrees,amplitude"),
    ] {
        let text = std::fs::read_to_string(out.join(file)).unwrap();
        assert_eq!(text.lines().next(), Some(header), "{file}");
    }
    let vtu = std::fs::read_to_string(out.join("mode.vtu")).unwrap();
    assert!(vtu.contains("<VTKFile type=\"UnstructuredGrid\"") && vtu.contains("Name=\"mode\""));
    assert!(std::fs::metadata(out.join("mode_top.png")).unwrap().len() > 1000);
    // The path past the onset, seeded with the one critical wave: stripes along the fibres'
    // projection, growing from the imperfection (0.01) to many times it.
    let text = std::fs::read_to_string(out.join("pattern.csv")).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let column = |name: &str| header.iter().position(|c| *c == name).unwrap();
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert!(rows.len() >= 20, "{text}");
    let last = rows.last().unwrap();
    assert_eq!(last[column("d")], "0.13", "{text}");
    assert_eq!(last[column("pattern")], "stripes", "{text}");
    let theta: f64 = last[column("theta1_degrees")].parse().unwrap();
    assert!((theta - 120.0).abs() < 0.5, "{theta}");
    let amplitude: f64 = last[column("A")].parse().unwrap();
    assert!(amplitude > 0.3, "{text}");
    assert_eq!(report["path"]["stopped"], serde_json::Value::Null, "{report}");
    assert_eq!(report["path"]["last"]["pattern"], "stripes", "{report}");
    let vtu = std::fs::read_to_string(out.join("state.vtu")).unwrap();
    assert!(vtu.contains("Name=\"displacement\""));
    assert!(std::fs::metadata(out.join("state_top.png")).unwrap().len() > 1000);
}

/// A path that stops before its end (here a fold of a patch with symmetry sides closing
/// through its mirror image, where self-contact is not modelled; it once panicked there, the
/// stop coming while the path left an unstable state) is a failure, exit 1, with one line saying
/// where, after every state up to there is written.
#[test]
fn a_path_that_stops_early_fails_and_keeps_what_it_computed() {
    let out = scratch("pattern-stopped");
    let output = fiberfold(&[
        "pattern",
        "--set",
        "beta=0.785398",
        "--sides",
        "symmetry",
        "--elements-per-wavelength",
        "3",
        "--follow-to",
        "0.5",
        "--out",
        out.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("the path past the onset stopped at d = ")
            && stderr.contains("the surface touches itself")
            && stderr.lines().count() == 1,
        "{stderr}"
    );
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("pattern.json")).unwrap()).unwrap();
    let reached = report["path"]["d_reached"].as_f64().unwrap();
    assert!(
        reached > report["d_bifurcation"].as_f64().unwrap() && reached < 0.5,
        "{report}"
    );
    let rows = std::fs::read_to_string(out.join("pattern.csv"))
        .unwrap()
        .lines()
        .count()
        - 1;
    assert_eq!(rows, report["path"]["states"].as_u64().unwrap() as usize);
    assert!(out.join("state.vtu").exists() && out.join("state_top.png").exists() && out.join("state_3d.png").exists());
}

#[test]
fn bad_input_is_refused_with_exit_code_2_naming_the_flag() {
    for (args, word) in [
        (&["--periods", "0"][..], "`periods`"),
        (&["--biaxial", "1.5"][..], "`biaxial`"),
        (&["--elements-per-wavelength", "1"][..], "`elements-per-wavelength`"),
        (&["--h0", "500"][..], "`h0`"),
        (&["--d-max", "2"][..], "`d-max`"),
        // Symmetry sides with the fibres turned under an unequal load (an equal one turns the
        // patch with them).
        (
            &["--sides", "symmetry", "--set", "psi=0.3", "--biaxial", "0.5"][..],
            "`sides`",
        ),
        (&["--follow-to", "0.99"][..], "`follow-to`"),
        (&["--follow-to", "0.2", "--imperfection", "0"][..], "`imperfection`"),
        (&["--follow-to", "0.2", "--d-start", "0.3"][..], "`d-start`"),
        (&["--resume"][..], "`resume`"),
        (
            &["--follow-to", "0.2", "--checkpoint-seconds", "0"][..],
            "`checkpoint-seconds`",
        ),
        // Some 190 million unknowns: refused by its memory estimate before anything is built.
        (&["--periods", "60"][..], "`patch`"),
    ] {
        let out = scratch("pattern-bad");
        let output = fiberfold(&[&["pattern"][..], args, &["--out", out.to_str().unwrap()]].concat());
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(
            stderr.contains(word) && stderr.lines().count() == 1,
            "{args:?}: {stderr}"
        );
    }
}

/// Fibres in the surface under equibiaxial compression: the two critical waves of a mirror pair
/// are seeded (the second at half the first's amplitude). Their superposition, a rhombic
/// checkerboard, turns unstable past the onset; the path leaves it for a stable state at the
/// same `d`, releasing energy, and goes on from there.
#[test]
fn a_checkerboard_that_turns_unstable_is_left_for_a_stable_pattern() {
    let args = [
        "--set",
        "beta=0",
        "--elements-per-wavelength",
        "4",
        "--substrate-elements",
        "8",
    ];
    let (out, report) = pattern("pattern-left", &[&args[..], &["--follow-to", "0.12"]].concat());
    let path = &report["path"];
    assert_eq!(path["seeded"].as_array().unwrap().len(), 2, "{path}");
    assert_eq!(path["stopped"], serde_json::Value::Null, "{path}");
    let left = path["branches_left"].as_array().unwrap();
    assert!(!left.is_empty(), "{path}");
    let (d_left, released) = (left[0][0].as_f64().unwrap(), left[0][1].as_f64().unwrap());
    assert!(
        d_left > report["d_bifurcation"].as_f64().unwrap() && released > 0.0,
        "{path}"
    );
    let text = std::fs::read_to_string(out.join("pattern.csv")).unwrap();
    let header: Vec<&str> = text.lines().next().unwrap().split(',').collect();
    let column = |name: &str| header.iter().position(|c| *c == name).unwrap();
    let rows: Vec<Vec<&str>> = text.lines().skip(1).map(|l| l.split(',').collect()).collect();
    let at = rows.iter().position(|r| r[column("left_unstable")] == "1").unwrap();
    // The state left had a negative pivot; the one reached at the same d has none.
    assert_eq!(rows[at - 1][column("d")], rows[at][column("d")], "{text}");
    assert_ne!(rows[at - 1][column("negative_pivots")], "0", "{text}");
    assert_eq!(rows[at][column("negative_pivots")], "0", "{text}");
    assert_eq!(rows[at - 1][column("pattern")], "checkerboard", "{text}");
    assert_eq!(rows.last().unwrap()[column("d")], "0.12", "{text}");
}

/// Under a load the same in every direction of the surface, turning the fibres' projection by
/// `psi` turns the answer with it: the patch is built along the projection, holds both members
/// of the theory's mirror pair at `psi +- theta_f` (the patch sized in the load's axes held only
/// the first), and bifurcates where the patch of `psi = 0` does, to the last digit, with its
/// directions turned by `psi` (which loads turn the patch: `PatchFrame`'s unit test).
#[test]
fn fibres_turned_in_the_surface_turn_the_patch_under_an_equal_load() {
    let fibres_in_the_surface = ["--set", "beta=0", "--elements-per-wavelength", "3"];
    let (_, straight) = pattern("pattern-psi0", &fibres_in_the_surface);
    let turn = format!("psi={}", std::f64::consts::FRAC_PI_6);
    let (out, turned) = pattern(
        "pattern-psi30",
        &[&fibres_in_the_surface[..], &["--set", &turn]].concat(),
    );
    let psi = 30.0;
    assert!((turned["patch_azimuth_degrees"].as_f64().unwrap() - psi).abs() < 1e-9);
    assert_eq!(straight["patch_azimuth_degrees"], 0.0);
    for key in ["d_bifurcation", "d_c_admissible", "negative_pivots", "unknowns"] {
        assert_eq!(turned[key], straight[key], "{key}");
    }
    assert_eq!(turned["negative_pivots"], 4);
    let degrees = |report: &serde_json::Value, i: usize| {
        report["admissible_wave_vectors"][i]["theta"]
            .as_f64()
            .unwrap()
            .to_degrees()
    };
    let pair: Vec<f64> = (0..2).map(|i| degrees(&turned, i)).collect();
    let theta_f = degrees(&straight, 0);
    for expected in [psi + theta_f, psi - theta_f + 180.0] {
        assert!(pair.iter().any(|t| (t - expected).abs() < 1e-6), "{pair:?}, {expected}");
    }
    let onset = |r: &serde_json::Value| r["onset_theory"]["theta0_degrees"].as_f64().unwrap();
    assert!((onset(&turned) - (onset(&straight) + psi)).abs() < 1e-6);
    let spectrum = std::fs::read_to_string(out.join("mode_spectrum.csv")).unwrap();
    let theta: f64 = spectrum
        .lines()
        .nth(1)
        .unwrap()
        .split(',')
        .nth(3)
        .unwrap()
        .parse()
        .unwrap();
    assert!(pair.iter().any(|t| (t - theta).abs() < 1e-6), "{spectrum}");
}
