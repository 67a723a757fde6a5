//! Every example command of README.md and of the user guide (`docs/guide/src/**/*.md`) is run
//! here (at a small size where it is long) and checked against one number from an independent
//! source, so the documentation cannot rot.

mod common;

use common::{fiberfold, scratch};
use std::f64::consts::{FRAC_PI_2, PI};
use std::path::{Path, PathBuf};

/// The `fiberfold ...` lines of the shell blocks (```sh) of a Markdown text.
fn shell_commands(text: &str) -> Vec<String> {
    let mut in_shell = false;
    let mut commands = Vec::new();
    for line in text.lines() {
        if line.starts_with("```") {
            in_shell = line == "```sh";
            continue;
        }
        let command = line.split('#').next().unwrap().trim();
        if in_shell && command.starts_with("fiberfold ") {
            commands.push(command.to_string());
        }
    }
    commands
}

/// The Markdown files under `dir`, recursively, sorted.
fn markdown_files(dir: &Path) -> Vec<PathBuf> {
    let mut files = Vec::new();
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            files.extend(markdown_files(&path));
        } else if path.extension().is_some_and(|e| e == "md") {
            files.push(path);
        }
    }
    files.sort();
    files
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The `fiberfold ...` lines of README's shell blocks.
fn readme_commands() -> Vec<String> {
    shell_commands(&read(&Path::new(env!("CARGO_MANIFEST_DIR")).join("README.md")))
}

/// The `fiberfold ...` lines of the shell blocks of README and of every guide page, each once.
fn documented_commands() -> Vec<String> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = vec![root.join("README.md")];
    files.extend(markdown_files(&root.join("docs/guide/src")));
    let mut commands: Vec<String> = Vec::new();
    for file in &files {
        for command in shell_commands(&read(file)) {
            if !commands.contains(&command) {
                commands.push(command);
            }
        }
    }
    commands
}

/// Runs a documented command with its `--out` redirected to a scratch folder and the `(flag, value)`
/// pairs of `extra` replacing or extending its own (to shrink long runs); returns the output
/// folder and stdout.
fn run(command: &str, extra: &[(&str, &str)]) -> (common::Scratch, String) {
    let name: String = command.replace([' ', '/', '=', ','], "_").chars().take(200).collect();
    let dir = scratch(&name);
    let mut args: Vec<String> = command.split_whitespace().skip(1).map(String::from).collect();
    let out = dir.display().to_string();
    for (flag, value) in [("--out", out.as_str())].iter().chain(extra) {
        match args.iter().position(|a| a == flag) {
            Some(_) if value.is_empty() => {}
            Some(i) => args[i + 1] = value.to_string(),
            None if *flag == "--out" => {}
            None if value.is_empty() => args.push(flag.to_string()),
            None => args.extend([flag.to_string(), value.to_string()]),
        }
    }
    let out = fiberfold(&args);
    assert!(
        out.status.success(),
        "{command}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    (dir, String::from_utf8(out.stdout).unwrap())
}

/// A map's small meshes, for the documented `map` commands.
const SMALL_MAP: &[(&str, &str)] = &[
    ("--waves", "2"),
    ("--elements-per-wave", "12"),
    ("--substrate-elements", "10"),
    ("--post-buckling-range", "0.04"),
    ("--fold", "1"),
    ("--crease-nx", "24"),
    ("--crease-layer-elements", "2"),
    ("--crease-substrate-elements", "10"),
    ("--no-crease-convergence", ""),
];

fn json(path: PathBuf) -> serde_json::Value {
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    serde_json::from_str(&text).unwrap()
}

fn csv_column(path: PathBuf, column: &str) -> Vec<f64> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let index = lines.next().unwrap().split(',').position(|c| c == column).unwrap();
    lines
        .map(|l| l.split(',').nth(index).unwrap().parse().unwrap())
        .collect()
}

/// The linear theory's onset `d_c` of a parameter set written by a command.
fn theory_d_c(parameters: &serde_json::Value) -> f64 {
    let p: fiberfold::Parameters = serde_json::from_value(parameters.clone()).unwrap();
    fiberfold::stability::StabilityAnalysis::new(&p, fiberfold::stability::Method::Exact)
        .unwrap()
        .onset()
        .unwrap()
        .d_c
}

#[test]
fn every_documented_example_runs_and_gives_an_independently_known_number() {
    let readme = readme_commands();
    assert!(readme.len() >= 2, "README lost its examples: {readme:?}");
    let commands = documented_commands();
    assert!(commands.len() >= 30, "the guide lost its examples: {commands:?}");
    for command in &commands {
        let verb = command.split_whitespace().nth(1).unwrap();
        match verb {
            "params" => {
                let (dir, stdout) = run(command, &[]);
                assert!(stdout.contains("mu_f = 20.0"));
                assert!(dir.join("params.toml").exists());
            }
            "homogeneous" => {
                // At d = 0 the reference state is unloaded: lambda_2 = 1 in both layers.
                let (dir, _) = run(command, &[("--points", "11")]);
                let l2 = csv_column(dir.join("homogeneous.csv"), "lambda2_layer");
                assert_eq!(l2[0], 1.0);
            }
            "onset" if command.contains("--biaxial") && command.contains("psi=") => {
                // Inclined fibres under equibiaxial compression: crests along the fibres'
                // projection, the wave vector at psi + 90 degrees (psi = 30 degrees here).
                let (dir, _) = run(command, &[]);
                let theta0 = json(dir.join("onset.json"))["theta0"].as_f64().unwrap();
                assert!((theta0.to_degrees() - 120.0).abs() < 0.01, "theta0 {theta0}");
                assert!(dir.join("orientation.png").exists());
            }
            "onset" if command.contains("--biaxial") => {
                // Fibres in the surface along the compression, equibiaxial: the crests are
                // oblique to the fibres (a mirror pair; the member in [0, pi/2] is reported).
                let (dir, _) = run(command, &[]);
                let theta0 = json(dir.join("onset.json"))["theta0"].as_f64().unwrap().to_degrees();
                assert!(theta0 > 10.0 && theta0 < 80.0, "theta0 {theta0} degrees");
            }
            "onset" if command.contains("incompressible=true") => {
                // An incompressible stiff film (mu_l = 1000): the thin-film law within 2 %.
                let (dir, _) = run(command, &[]);
                let k0 = json(dir.join("onset.json"))["k0"].as_f64().unwrap();
                assert!((k0 / (3.0f64 / 1000.0).cbrt() - 1.0).abs() < 0.02, "k0 {k0}");
            }
            "onset" if command.contains("--load growth") => {
                // A growing layer: the discrete solver, from the same grown moduli, agrees, and
                // g_c is the growth of the strain d_c = 1 - 1/g_c.
                let onset = |dir: common::Scratch| json(dir.join("onset.json"));
                let exact = onset(run(command, &[]).0);
                let discrete = onset(run(command, &[("--method", "discrete")]).0);
                let g_c = |o: &serde_json::Value| o["g_c"].as_f64().unwrap();
                assert!((g_c(&exact) - g_c(&discrete)).abs() < 1e-4, "{exact} vs {discrete}");
                assert!((g_c(&exact) - 1.0 / (1.0 - exact["d_c"].as_f64().unwrap())).abs() < 1e-12);
            }
            "onset" if command.contains("mu_f=0") => {
                // Paper, section 3.1: unloaded fibres (mu_f = 0) give k0 = 0.5515.
                let (dir, _) = run(command, &[]);
                assert!((json(dir.join("onset.json"))["k0"].as_f64().unwrap() - 0.5515).abs() < 5e-5);
            }
            "onset" => {
                // Any other tissue (laws, fibres, prestress): the discrete solver, from the same
                // moduli, agrees with the exact one. (Both runs share one scratch folder: read
                // each before the next.)
                let d_c = |dir: common::Scratch| json(dir.join("onset.json"))["d_c"].as_f64().unwrap();
                let exact = d_c(run(command, &[]).0);
                let discrete = d_c(run(command, &[("--method", "discrete")]).0);
                assert!((exact - discrete).abs() < 1e-4, "{exact} vs {discrete}");
                assert!(exact > 0.0 && exact < 0.95, "d_c {exact}");
            }
            "dispersion" => {
                // Default parameters: the minimum of the curve is the onset; d_c > 0 everywhere.
                let (dir, _) = run(command, &[("--points", "30")]);
                let d_c = csv_column(dir.join("dispersion.csv"), "d_c");
                let k0 = json(dir.join("dispersion.json"))["onset"]["k0"].as_f64().unwrap();
                assert!(d_c.iter().all(|d| *d > 0.0) && (0.3..0.8).contains(&k0));
            }
            "sweep" if command.contains("--biaxial") && command.contains("--param psi") => {
                // Inclined fibres, equibiaxial: the wave vector turns with the fibres'
                // projection, theta0 = psi + 90 degrees (mod 180).
                let (dir, _) = run(command, &[("--points", "3")]);
                let (psi, theta0) = (
                    csv_column(dir.join("sweep.csv"), "value"),
                    csv_column(dir.join("sweep.csv"), "theta0"),
                );
                for (psi, theta0) in psi.iter().zip(&theta0) {
                    let gap = (theta0 - (psi + FRAC_PI_2).rem_euclid(PI)).abs();
                    assert!(gap < 1e-4 || (gap - PI).abs() < 1e-4, "psi {psi}: theta0 {theta0}");
                }
            }
            "sweep" if command.contains("--biaxial") => {
                // Fibres turned from the surface towards its normal stiffen the substrate
                // against compression along the surface: the onset comes later.
                let (dir, _) = run(command, &[("--points", "3")]);
                let d_c = csv_column(dir.join("sweep.csv"), "d_c");
                assert!(d_c[0] > 0.0 && d_c[2] > d_c[0], "{d_c:?}");
            }
            "sweep" => {
                // Fibres at beta = 0 are compressed: stiffer fibres destabilise (paper, Fig. 5a).
                let (dir, _) = run(command, &[("--points", "3")]);
                let text = std::fs::read_to_string(dir.join("sweep.csv")).unwrap();
                let d_at_zero = |series: &str| -> f64 {
                    let line = text.lines().find(|l| l.starts_with(&format!("{series},0,"))).unwrap();
                    line.split(',').nth(3).unwrap().parse().unwrap()
                };
                assert!(d_at_zero("mu_f=50") < d_at_zero("mu_f=1"));
            }
            "bench" if command.ends_with("stability") => {
                let (_, stdout) = run(command, &[("--orientation-map", "3")]);
                assert!(stdout.contains("Fig. 4b sweep") && stdout.contains("orientation map"));
            }
            "bench" if command.contains("patch") => {
                // Table 1's 1 x 1 box: 8 x 14 x 11 hexahedra, nodes 16 x 29 x 22 on periodic
                // sides; free: all their unknowns but u_Y at the 16 x 22 bottom nodes and the
                // anchor's u_X, u_Z.
                let (_, stdout) = run(command, &[("--periods", "1")]);
                let free = 3 * 16 * 29 * 22 - 16 * 22 - 2;
                assert!(stdout.contains(&format!("| 1 x 1 | {free} |")), "{stdout}");
            }
            "bench" => {
                let (_, stdout) = run(command, &[("--coarse-only", "")]);
                assert!(stdout.contains("coarse") && stdout.contains("22110"), "{stdout}");
            }
            "simulate" if command.contains("--imperfection -") => {
                // A stiff layer on two natural wavelengths with a trough on each symmetry plane:
                // the periodic wrinkle loses stability to its doubled period near d = 0.19 (the
                // literature's 0.17-0.2 for stiff films).
                let (dir, _) = run(command, &[("--d-max", "0.2")]);
                let change = &json(dir.join("secondary.json"))["changes"][0];
                let d = change["d_after"].as_f64().unwrap();
                assert!((0.15..0.2).contains(&d) && change["mode_half_waves"] == 2, "{change}");
            }
            "simulate" if command.contains("law=") => {
                // Another tissue law on the coarse mesh: the path reaches its end without
                // inverting an element.
                let (dir, _) = run(command, &[("--mesh", "coarse"), ("--d-max", "0.25")]);
                assert_eq!(json(dir.join("simulate.json"))["completed"], true);
                let min_j = json(dir.join("contact.json"))["min_jacobian"].as_f64().unwrap();
                assert!(min_j > 0.0 && min_j <= 1.0, "min J {min_j}");
            }
            "simulate" if command.contains("growth_layer") => {
                // A prestressed layer: the steepest point of A(d) against the linear theory's
                // d_c(k) of the same prestressed bilayer, on the coarse mesh.
                let (dir, _) = run(command, &[("--mesh", "coarse"), ("--d-max", "0.12")]);
                let onset = json(dir.join("onset_estimates.json"));
                let (fe, theory) = (
                    onset["d_steepest"].as_f64().unwrap(),
                    onset["d_linear_theory"].as_f64().unwrap(),
                );
                assert!((fe / theory - 1.0).abs() < 0.02, "FE {fe} vs theory {theory}");
            }
            "simulate" => {
                // The steepest point of A(d) against the linear theory's d_c(k) (a second,
                // independent method), on the coarse mesh.
                let (dir, _) = run(command, &[("--mesh", "coarse"), ("--d-max", "0.2")]);
                let onset = json(dir.join("onset_estimates.json"));
                let (fe, theory) = (
                    onset["d_steepest"].as_f64().unwrap(),
                    onset["d_linear_theory"].as_f64().unwrap(),
                );
                assert!((fe / theory - 1.0).abs() < 0.02, "FE {fe} vs theory {theory}");
                assert!(dir.join("amplitude.csv").exists() && dir.join("simulate.pvd").exists());
                // Fig. 3 marks the steepest point's onset beside the paper's rule.
                let fig3 = std::fs::read_to_string(dir.join("fig3.svg")).unwrap();
                assert!(
                    fig3.contains("(steepest A)"),
                    "fig3 of `{command}` without the steepest point"
                );
            }
            "bifurcation" => {
                // The inertia of the FE tangent against the linear theory over admissible k.
                let (dir, _) = run(command, &[("--mesh", "coarse")]);
                let report = json(dir.join("bifurcation.json"));
                let (fe, theory) = (
                    report["d_bifurcation"].as_f64().unwrap(),
                    report["d_linear_theory_min"].as_f64().unwrap(),
                );
                assert!((fe / theory - 1.0).abs() < 1e-3, "FE {fe} vs theory {theory}");
            }
            "pattern" if command.contains("--x ") => {
                // A map of patterns, shrunk to two points in the surface: each point's path ends
                // as far past its own theory onset as asked, its patch's bifurcation near that
                // onset.
                let small = [
                    ("--x-points", "2"),
                    ("--y-points", "1"),
                    ("--elements-per-wavelength", "3"),
                    ("--substrate-elements", "4"),
                    ("--follow-past", "0.02"),
                ];
                let (dir, _) = run(command, &small);
                let report = json(dir.join("map.json"));
                let points = report["points"].as_array().unwrap();
                assert_eq!(points.len(), 2, "{report}");
                for point in points {
                    let past = point["d"].as_f64().unwrap() - point["d_c"].as_f64().unwrap();
                    assert!((past - 0.02).abs() < 1e-9, "{point}");
                    let difference = point["relative_difference"].as_f64().unwrap();
                    assert!(difference > 0.0 && difference < 0.05, "{point}");
                }
                assert!(dir.join("map.png").exists());
            }
            "pattern" if command.contains("--load growth") => {
                // The layer's growth in the surface (fibres along X): the exact theory's first
                // wave vector is along Z (crests along the fibres), and so are the coarse
                // patch's mode and the stripes the path makes past it.
                let (dir, _) = run(command, &[("--elements-per-wavelength", "4"), ("--follow-to", "0.09")]);
                let report = json(dir.join("pattern.json"));
                let theta = report["onset_theory"]["theta0_degrees"].as_f64().unwrap();
                assert!((theta - 90.0).abs() < 1e-9, "{theta}");
                let mode = report["mode_wave_vectors"][0]["theta_degrees"].as_f64().unwrap();
                assert!((mode - 90.0).abs() < 0.5, "{mode}");
                let (d, g) = (
                    report["d_bifurcation"].as_f64().unwrap(),
                    report["g_bifurcation"].as_f64().unwrap(),
                );
                assert!((g * (1.0 - d) - 1.0).abs() < 1e-12, "g {g} at d {d}");
                let difference = report["relative_difference"].as_f64().unwrap();
                assert!(difference > 0.0 && difference < 0.03, "{difference}");
                let last = &report["path"]["last"];
                assert_eq!(last["pattern"], "stripes", "{last}");
                assert!((last["directions"][0]["wave"]["theta_degrees"].as_f64().unwrap() - 90.0).abs() < 0.5);
            }
            "pattern" if command.contains("--biaxial 0.5") => {
                // An onset 1 deg from X: Z, which would take the mode's period of about 60
                // wavelengths, is one wavelength long, and the patch holds the wave along X, the
                // theory's d_c there barely above the onset's.
                let (dir, _) = run(command, &[("--elements-per-wavelength", "3")]);
                let report = json(dir.join("pattern.json"));
                let capped = &report["capped_sides"][0];
                assert_eq!(capped["side"], "Z", "{report}");
                let wavelength = 2.0 * std::f64::consts::PI / report["onset_theory"]["k0"].as_f64().unwrap();
                assert!(capped["period"].as_f64().unwrap() > 50.0 * wavelength, "{capped}");
                let excess =
                    report["d_c_admissible"].as_f64().unwrap() - report["onset_theory"]["d_c"].as_f64().unwrap();
                assert!((0.0..1e-4).contains(&excess), "{excess}");
                let mode = report["mode_wave_vectors"][0]["theta_degrees"].as_f64().unwrap();
                assert!(mode.abs() < 0.5 || (mode - 180.0).abs() < 0.5, "{mode}");
                let difference = report["relative_difference"].as_f64().unwrap();
                assert!(difference > 0.0 && difference < 0.05, "{difference}");
            }
            "pattern" if command.contains("--follow-to") => {
                // Fibres in the surface: the seeded mirror pair's checkerboard turns unstable
                // past the onset and the path leaves it for a stable state, releasing energy.
                let (dir, _) = run(command, &[("--follow-to", "0.12")]);
                let report = json(dir.join("pattern.json"));
                let path = &report["path"];
                assert_eq!(path["d_reached"].as_f64().unwrap(), 0.12, "{path}");
                let left = path["branches_left"].as_array().unwrap();
                assert!(!left.is_empty() && left[0][1].as_f64().unwrap() > 0.0, "{path}");
                assert_eq!(path["last"]["negative_pivots"], 0, "{path}");
            }
            "pattern" => {
                // A coarse patch: the theory's wave vector (crests along the fibres' projection,
                // the wave vector at 90 + 30 deg) is the mode's, near the theory's onset.
                let (dir, _) = run(command, &[("--elements-per-wavelength", "3")]);
                let report = json(dir.join("pattern.json"));
                let theta = report["onset_theory"]["theta0_degrees"].as_f64().unwrap();
                assert!((theta - 120.0).abs() < 0.1, "{theta}");
                let mode = report["mode_wave_vectors"][0]["theta_degrees"].as_f64().unwrap();
                assert!((mode - theta).abs() < 0.5, "{mode} vs {theta}");
                let difference = report["relative_difference"].as_f64().unwrap();
                assert!(difference > 0.0 && difference < 0.05, "{difference}");
            }
            "reproduce" => {
                // The report carries the paper's fibre-free check k0 = 0.5515 beside ours.
                let (dir, _) = run(command, &[("--only", "fig4b")]);
                let report = std::fs::read_to_string(dir.join("report.md")).unwrap();
                assert!(report.contains("| 0.5515 | 0.551513 |"), "{report}");
                assert!(dir.join("report.html").exists() && dir.join("fig4b.png").exists());
            }
            "crease" if !command.contains("mu_l=1 ") => {
                // A bilayer near its crossover (on the base mesh): the crease onset lies close
                // to the wrinkling onset of the linear theory of the same bilayer.
                let (dir, _) = run(command, &[("--fold", "0.5"), ("--no-convergence", "")]);
                let report = json(dir.join("crease.json"));
                let d = report["d_crease"].as_f64().unwrap();
                let theory = theory_d_c(&report["parameters"]);
                assert!((d - theory).abs() < 0.02, "d_crease {d} vs d_wrinkle {theory}");
            }
            "crease" => {
                // One solid: Hong, Zhao and Suo's creasing strain, far below Biot's 0.456 (on a
                // small mesh when incompressible).
                let small = [
                    ("--nx", "24"),
                    ("--layer-elements", "2"),
                    ("--substrate-elements", "10"),
                    ("--no-convergence", ""),
                ];
                let extra: &[(&str, &str)] = if command.contains("incompressible=true") {
                    &small
                } else {
                    &[]
                };
                let (dir, _) = run(command, extra);
                let d = json(dir.join("crease.json"))["d_crease"].as_f64().unwrap();
                assert!((0.33..0.38).contains(&d), "d_crease {d}");
            }
            "map" if command.contains("--biaxial") => {
                // Fibres in the surface (beta = 0) at psi = 0 and pi/2 on small meshes: under
                // equibiaxial compression the whole problem turns with the fibres, so the onset is
                // the same and the direction turns with them, to its mirror image in [0, pi/2].
                let small = [("--x-points", "2"), ("--y-to", "0"), ("--y-points", "1")];
                let (dir, _) = run(command, &[&small[..], SMALL_MAP].concat());
                let points = &json(dir.join("map.json"))["points"];
                let value = |i: usize, key: &str| points[i][key].as_f64().unwrap();
                assert!((value(0, "d_wrinkle_biaxial") - value(1, "d_wrinkle_biaxial")).abs() < 1e-9);
                let (along_x, along_z) = (value(0, "theta0"), value(1, "theta0"));
                assert!(
                    (along_x + along_z - FRAC_PI_2).abs() < 1e-4,
                    "theta0 {along_x}, {along_z}"
                );
                assert!(dir.join("map.png").exists());
            }
            "map" if command.contains("growth_layer") => {
                // A layer prestressed by growth wrinkles earlier; without prestress the map's
                // onset is the linear theory's of the same bilayer.
                let (dir, _) = run(command, &[&[("--x-points", "2")][..], SMALL_MAP].concat());
                let points = &json(dir.join("map.json"))["points"];
                let d = |i: usize| points[i]["d_wrinkle"].as_f64().unwrap();
                let plain: fiberfold::Parameters = serde_json::from_value(points[0]["parameters"].clone()).unwrap();
                let theory = fiberfold::stability::StabilityAnalysis::new(&plain, fiberfold::stability::Method::Exact)
                    .unwrap()
                    .onset()
                    .unwrap()
                    .d_c;
                assert!(
                    (d(0) - theory).abs() < 1e-9 && d(1) < d(0),
                    "{} {} {theory}",
                    d(0),
                    d(1)
                );
            }
            "map" if command.contains("layer.alpha") => {
                // A map over a law constant: each point's onset is the linear theory's of its
                // parameters, and the stiff layer wrinkles first.
                let (dir, _) = run(command, SMALL_MAP);
                let points = json(dir.join("map.json"))["points"].as_array().unwrap().clone();
                for point in &points {
                    let d = point["d_wrinkle"].as_f64().unwrap();
                    let theory = theory_d_c(&point["parameters"]);
                    assert!((d - theory).abs() < 1e-9, "{d} vs {theory}");
                    assert_eq!(point["first"], "wrinkle", "{point}");
                }
            }
            "map" => {
                // One point, the stiffest layer at beta = 0, on small meshes: it wrinkles first,
                // near the thin-film law d_c = (1/4) (3 mu_s / mu_l)^(2/3) = 0.054.
                let small = [
                    ("--x-from", "30"),
                    ("--x-points", "1"),
                    ("--y-to", "0"),
                    ("--y-points", "1"),
                ];
                let (dir, _) = run(command, &[&small[..], SMALL_MAP].concat());
                let point = &json(dir.join("map.json"))["points"][0];
                assert_eq!(point["first"], "wrinkle", "{point}");
                let d = point["d_wrinkle"].as_f64().unwrap();
                assert!((d / 0.054 - 1.0).abs() < 0.1, "d_wrinkle {d}");
                assert!(dir.join("map.csv").exists() && dir.join("map.png").exists());
            }
            other => panic!("the documentation shows `{command}` but no test runs `{other}`"),
        }
    }
}
