//! Waves in any direction of the surface from the command line: `onset --biaxial`, its files,
//! and one-line errors (exit code 2) for bad directions and loads.

mod common;

use common::{fiberfold, map_points, rejected, scratch, tiny_map};
use std::f64::consts::FRAC_PI_2;

fn onset_json(args: &[&str]) -> serde_json::Value {
    let dir = scratch(&format!("orientation-{}", args.join("_").replace(['=', '.', '-'], "")));
    let mut all = vec!["onset", "--out", dir.to_str().unwrap()];
    all.extend_from_slice(args);
    let out = fiberfold(&all);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_str(&std::fs::read_to_string(dir.join("onset.json")).unwrap()).unwrap()
}

#[test]
fn bad_directions_and_loads_are_named_with_their_range() {
    rejected(&["onset", "--biaxial", "1.5"], &["biaxial", "[0, 1]"]);
    rejected(&["onset", "--biaxial", "-0.1"], &["biaxial", "[0, 1]"]);
    rejected(&["onset", "--theta", "nan"], &["theta", "finite"]);
    rejected(&["dispersion", "--theta", "inf"], &["theta", "finite"]);
    rejected(&["onset", "--biaxial", "1", "--set", "psi=nan"], &["psi"]);
    let map = tiny_map(&scratch("orientation-bad-map"), &["--biaxial", "2"]);
    rejected(
        &map.iter().map(String::as_str).collect::<Vec<_>>(),
        &["biaxial", "[0, 1]"],
    );
}

/// Plane strain reports `theta0 = 0` and no biaxial ratio. Under equibiaxial compression
/// fibres inclined at pi/4 in the X-Y plane make the wave vector run along Z (crests along the
/// fibres' projection), and vertical fibres (beta = pi/2) leave no direction preferred; the
/// polar figure and its table are written.
#[test]
fn onset_reports_the_direction_of_the_first_wrinkles() {
    let plane = onset_json(&[]);
    assert_eq!(plane["theta0"], 0.0);
    assert!(plane["biaxial"].is_null());
    let inclined = onset_json(&["--biaxial", "1", "--set", "beta=0.785398"]);
    let theta0 = inclined["theta0"].as_f64().unwrap();
    assert!((theta0 - FRAC_PI_2).abs() < 1e-4, "theta0 = {theta0}");
    assert!(inclined["direction_spread"].as_f64().unwrap() > 1e-3);
    let vertical = onset_json(&["--biaxial", "1", "--set", "beta=1.570796"]);
    assert!(vertical["theta0"].is_null(), "{}", vertical["theta0"]);
    let dir = scratch("orientation-files");
    let out = fiberfold(&[
        "onset",
        "--biaxial",
        "1",
        "--set",
        "psi=0.5",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(out.status.success());
    for file in ["onset.json", "orientation.csv", "orientation.png", "orientation.svg"] {
        assert!(dir.join(file).exists(), "{file} missing");
    }
    let table = std::fs::read_to_string(dir.join("orientation.csv")).unwrap();
    assert!(table.starts_with("theta,d_c"));
    assert_eq!(table.lines().count(), 73);
}

/// `sweep --biaxial` over the fibres' azimuth: the wave vector turns with the fibres'
/// projection, `theta0 = psi + 90 degrees` (mod 180), and the sweep draws a theta0 panel.
#[test]
fn sweep_over_the_azimuth_turns_the_wrinkles_with_the_fibres() {
    let dir = scratch("orientation-sweep");
    let out = fiberfold(&[
        "sweep",
        "--param",
        "psi",
        "--from",
        "0",
        "--to",
        "1.5707963",
        "--points",
        "4",
        "--set",
        "beta=0.785398",
        "--biaxial",
        "1",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let table = std::fs::read_to_string(dir.join("sweep.csv")).unwrap();
    let mut lines = table.lines();
    assert_eq!(lines.next(), Some("series,value,k0,d_c,minimum,theta0"));
    for line in lines {
        let cells: Vec<&str> = line.split(',').collect();
        let (psi, theta0): (f64, f64) = (cells[1].parse().unwrap(), cells[5].parse().unwrap());
        let expected = (psi + FRAC_PI_2).rem_euclid(std::f64::consts::PI);
        let gap = (theta0 - expected).abs();
        assert!(
            gap < 1e-4 || (gap - std::f64::consts::PI).abs() < 1e-4,
            "psi {psi}: theta0 {theta0}"
        );
    }
    assert!(dir.join("sweep.png").exists());
}

/// `map --biaxial 1` gives each point the direction of `onset --biaxial 1` at its parameters
/// (fibres in the surface, at the map's beta = 0, swung to psi = 0.6 from X), and none without
/// fibres; the columns are in `map.csv`.
#[test]
fn map_points_carry_the_direction_of_the_onset_over_the_surface() {
    let dir = scratch("orientation-map");
    let fibres = ["--set", "phi_m=0.9", "--set", "phi_f=0.1", "--set", "psi=0.6"];
    let mut args = tiny_map(&dir, &fibres);
    args.extend(["--biaxial", "1"].map(String::from));
    let out = fiberfold(&args);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let csv = std::fs::read_to_string(dir.join("map.csv")).unwrap();
    assert!(
        csv.lines().next().unwrap().contains(",d_wrinkle_biaxial,theta0,"),
        "{csv}"
    );
    let points = map_points(&dir);
    let stiff = &points[1];
    let onset = onset_json(&["--biaxial", "1", "--set", "mu_l=10", "--set", "psi=0.6"]);
    for (key, from_map) in [("d_c", "d_wrinkle_biaxial"), ("theta0", "theta0")] {
        let (a, b) = (onset[key].as_f64().unwrap(), stiff[from_map].as_f64().unwrap());
        assert!((a - b).abs() < 1e-9, "{key}: onset {a}, map {b}");
    }

    let isotropic = scratch("orientation-map-isotropic");
    let mut args = tiny_map(&isotropic, &[]);
    args.extend(["--biaxial", "1"].map(String::from));
    let out = fiberfold(&args);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    for point in map_points(&isotropic) {
        assert!(
            point["d_wrinkle_biaxial"].is_f64() && point["theta0"].is_null(),
            "{point:?}"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
    let _ = std::fs::remove_dir_all(&isotropic);
}

/// A Gent layer under equibiaxial compression reaches its limiting extensibility: the search
/// ends there (as in plane strain), with the onset before it, not with a non-finite energy.
#[test]
fn a_gent_layer_under_biaxial_compression_ends_the_search_at_its_domain() {
    let onset = onset_json(&["--biaxial", "1", "--set", "layer.law=gent", "--set", "layer.jm=0.05"]);
    let (d_c, end) = (onset["d_c"].as_f64().unwrap(), onset["d_domain_end"].as_f64().unwrap());
    assert!(d_c > 0.0 && d_c < end && end < 0.95, "d_c {d_c}, domain end {end}");
}
