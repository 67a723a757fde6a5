//! Waves in any direction of the surface from the command line: `onset --biaxial`, its files,
//! and one-line errors (exit code 2) for bad directions and loads.

mod common;

use common::{fiberfold, rejected, scratch};
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
