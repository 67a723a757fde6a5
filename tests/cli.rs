//! The command line as a user meets it: bad input gives a one-line error naming the parameter
//! and its allowed range with exit code 2; good input writes the promised files.

mod common;

use common::{fiberfold, rejected, scratch};

#[test]
fn volume_fraction_out_of_range() {
    let out = scratch("phi-f");
    rejected(
        &["homogeneous", "--set", "phi_f=1.5", "--out", out.to_str().unwrap()],
        &["phi_f", "[0, 1]"],
    );
    rejected(&["homogeneous", "--set", "phi_m=-0.1"], &["phi_m", "[0, 1]"]);
}

#[test]
fn non_positive_modulus() {
    for key in ["mu_l", "K_l", "mu_s", "K_s"] {
        rejected(&["params", "--set", &format!("{key}=0")], &[key, "[1e-12, 1e12]"]);
        rejected(&["params", "--set", &format!("{key}=1e308")], &[key, "[1e-12, 1e12]"]);
    }
    rejected(&["params", "--set", "lambda_f=0"], &["lambda_f", "(0, 10]"]);
    rejected(&["params", "--set", "mu_f=-1"], &["mu_f", "[0, 1e12]"]);
    rejected(&["params", "--set", "mu_f=1e308"], &["mu_f", "[0, 1e12]"]);
    rejected(&["dispersion", "--k-max", "378"], &["k-max", "10]"]);
}

#[test]
fn non_finite_and_malformed_values() {
    rejected(&["params", "--set", "mu_l=nan"], &["mu_l", "finite"]);
    rejected(&["params", "--set", "beta=inf"], &["beta", "finite"]);
    rejected(&["params", "--set", "mu_l=ten"], &["mu_l"]);
    rejected(
        &["params", "--set", "tension_only=maybe"],
        &["tension_only", "true or false"],
    );
    rejected(&["params", "--set", "mu_l"], &["KEY=VALUE"]);
}

#[test]
fn unknown_key_lists_the_known_ones() {
    rejected(&["params", "--set", "gamma=1"], &["gamma", "mu_l", "tension_only"]);
    let dir = scratch("unknown-toml");
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("p.toml");
    std::fs::write(&file, "mu_l = 5\nmu_x = 1\n").unwrap();
    rejected(&["params", "--params", file.to_str().unwrap()], &["mu_x", "mu_l"]);
}

#[test]
fn unreadable_or_malformed_parameter_file() {
    rejected(
        &["params", "--params", "/nonexistent/params.toml"],
        &["/nonexistent/params.toml"],
    );
    let dir = scratch("bad-toml");
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("p.toml");
    std::fs::write(&file, "mu_l = = 5\n").unwrap();
    rejected(
        &["params", "--params", file.to_str().unwrap()],
        &["cannot read parameters"],
    );
    std::fs::write(&file, "mu_l = \"stiff\"\n").unwrap();
    rejected(&["params", "--params", file.to_str().unwrap()], &["mu_l", "number"]);
}

#[test]
fn compression_and_points_out_of_range() {
    let dir = scratch("bad-d");
    let out = dir.to_str().unwrap();
    rejected(&["homogeneous", "--d-max", "1.0", "--out", out], &["d-max", "[0, 1)"]);
    rejected(&["homogeneous", "--d-max", "-0.2", "--out", out], &["d-max", "[0, 1)"]);
    rejected(&["homogeneous", "--points", "1", "--out", out], &["points", "[2,"]);
    assert!(
        !dir.join("homogeneous.csv").exists(),
        "no file may be written for bad input"
    );
}

#[test]
fn params_round_trip_through_a_file() {
    let dir = scratch("roundtrip");
    let out = fiberfold(&[
        "params",
        "--set",
        "beta=0.5",
        "--set",
        "mu_f=20",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(out.status.success());
    let printed = String::from_utf8(out.stdout).unwrap();
    let file = dir.join("params.toml");
    assert_eq!(std::fs::read_to_string(&file).unwrap().trim(), printed.trim());
    let again = fiberfold(&["params", "--params", file.to_str().unwrap()]);
    assert_eq!(String::from_utf8(again.stdout).unwrap(), printed);
}

#[test]
fn homogeneous_writes_table_summary_and_figure() {
    let dir = scratch("homog");
    let out = fiberfold(&[
        "homogeneous",
        "--set",
        "beta=0.75",
        "--points",
        "11",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let csv = std::fs::read_to_string(dir.join("homogeneous.csv")).unwrap();
    let mut lines = csv.lines();
    assert!(lines
        .next()
        .unwrap()
        .starts_with("d,lambda1,lambda2_layer,lambda2_substrate"));
    assert_eq!(lines.count(), 11);
    assert!(!csv.to_lowercase().contains("nan"));
    for f in ["homogeneous.json", "fig2.png", "fig2.svg"] {
        assert!(dir.join(f).metadata().unwrap().len() > 0, "{f} missing");
    }
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("homogeneous.json")).unwrap()).unwrap();
    assert_eq!(summary["parameters"]["beta"], 0.75);
}

#[test]
fn bench_writes_its_tables_where_asked() {
    let help = String::from_utf8(fiberfold(&["bench", "--help"]).stdout).unwrap();
    for flag in ["--out", "default: results/bench", "--params", "--set"] {
        assert!(help.contains(flag), "`{flag}` missing from help:\n{help}");
    }
    let dir = scratch("bench");
    let out = fiberfold(&[
        "bench",
        "stability",
        "--orientation-map",
        "3",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let table = std::fs::read_to_string(dir.join("bench_stability.md")).unwrap();
    assert!(table.contains("d_c(k)"), "{table}");
    assert_eq!(
        table,
        String::from_utf8_lossy(&out.stdout)
            .lines()
            .skip(1)
            .take_while(|l| !l.contains("wrote"))
            .map(|l| format!("{l}\n"))
            .collect::<String>()
    );
}

#[test]
fn help_documents_flags_with_defaults() {
    let out = fiberfold(&["homogeneous", "--help"]);
    let help = String::from_utf8(out.stdout).unwrap();
    for flag in [
        "--d-max",
        "--points",
        "--out",
        "--set",
        "--params",
        "default: 0.5",
        "default: 101",
    ] {
        assert!(help.contains(flag), "`{flag}` missing from help:\n{help}");
    }
}

#[test]
fn onset_reports_k0_d_c_and_ellipticity() {
    let dir = scratch("onset");
    let out = fiberfold(&["onset", "--set", "mu_f=0", "--out", dir.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("onset.json")).unwrap()).unwrap();
    // The paper's fibre-free check (section 3.1): k0 = 0.5515.
    assert!((json["k0"].as_f64().unwrap() - 0.5515).abs() < 5e-5);
    let d_c = json["d_c"].as_f64().unwrap();
    assert!((json["lambda1_c"].as_f64().unwrap() - (1.0 - d_c)).abs() < 1e-12);
    assert!(json.get("d_ellipticity_loss").is_some() && json["parameters"]["mu_f"] == 0.0);
}

#[test]
fn dispersion_writes_its_curve() {
    let dir = scratch("dispersion");
    let out = fiberfold(&[
        "dispersion",
        "--points",
        "20",
        "--set",
        "beta=1.5707963",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let csv = std::fs::read_to_string(dir.join("dispersion.csv")).unwrap();
    assert!(csv.starts_with("k,theta,d_c,lambda1_c\n"));
    assert_eq!(csv.lines().count(), 21);
    for f in ["dispersion.png", "dispersion.svg", "dispersion.json"] {
        assert!(dir.join(f).exists(), "{f}");
    }
    // A short title, with the fibre angle in degrees.
    let svg = std::fs::read_to_string(dir.join("dispersion.svg")).unwrap();
    assert!(
        svg.contains("d_c(k), beta = 90.0 deg, plane strain"),
        "dispersion title"
    );
    rejected(
        &["dispersion", "--k-min", "-1", "--out", dir.to_str().unwrap()],
        &["k-min"],
    );
    rejected(&["dispersion", "--k-min", "2", "--k-max", "1"], &["k-max"]);
}

#[test]
fn sweep_over_a_parameter_with_series() {
    let dir = scratch("sweep");
    let out = fiberfold(&[
        "sweep",
        "--param",
        "beta",
        "--from",
        "0",
        "--to",
        "1.5707963",
        "--points",
        "5",
        "--series",
        "mu_f=1,20",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let csv = std::fs::read_to_string(dir.join("sweep.csv")).unwrap();
    assert!(csv.starts_with("series,value,k0,d_c,minimum,theta0\n"));
    assert!(csv.lines().skip(1).all(|l| l.contains(",interior,")), "{csv}");
    assert_eq!(csv.lines().filter(|l| l.starts_with("mu_f=20,")).count(), 5);
    rejected(
        &["sweep", "--param", "gamma", "--from", "0", "--to", "1"],
        &["param", "gamma"],
    );
    rejected(
        &["sweep", "--param", "phi_f", "--from", "0", "--to", "2", "--points", "3"],
        &["phi_f", "[0, 1]"],
    );
    rejected(
        &[
            "sweep", "--param", "beta", "--from", "0", "--to", "1", "--series", "mu_f",
        ],
        &["series"],
    );
}

#[test]
fn a_mesh_that_cannot_carry_the_seeded_wave_is_refused() {
    let dir = scratch("unresolved");
    let out = dir.to_str().unwrap();
    // 4 waves over 50 H: wavelength 12.5 H needs 16 elements at 4 per wavelength.
    rejected(
        &["simulate", "--waves", "4", "--nx", "1", "--d-max", "0.01", "--out", out],
        &["`nx`", ">= 16", "4 Q2 elements per wavelength 12.5000 H"],
    );
    rejected(
        &[
            "simulate",
            "--waves",
            "4",
            "--nx",
            "20",
            "--refine-troughs",
            "8",
            "--d-max",
            "0.01",
            "--out",
            out,
        ],
        &["`refine-troughs`", "below 3.1250 H"],
    );
    rejected(
        &[
            "simulate",
            "--waves",
            "4",
            "--nx",
            "16",
            "--imperfection2",
            "0.01",
            "--imperfection2-waves",
            "8",
            "--d-max",
            "0.01",
            "--out",
            out,
        ],
        &["`nx`", ">= 32", "imperfection2-waves"],
    );
    assert!(!dir.join("amplitude.csv").exists(), "nothing is written for bad input");
    // Exactly 4 per wavelength runs.
    let ok = fiberfold(&[
        "simulate", "--waves", "4", "--nx", "16", "--d-max", "0.01", "--out", out,
    ]);
    assert!(ok.status.success(), "{}", String::from_utf8_lossy(&ok.stderr));
}

#[test]
fn a_mesh_that_cannot_fit_in_memory_is_refused_at_once() {
    let dir = scratch("huge");
    let out = dir.to_str().unwrap();
    let start = std::time::Instant::now();
    let message = rejected(
        &[
            "simulate", "--waves", "4", "--nx", "100000", "--d-max", "0.01", "--out", out,
        ],
        &["`mesh`", "22000110 unknowns", "MB of memory available", "--force"],
    );
    rejected(
        &[
            "simulate",
            "--waves",
            "4",
            "--layer-elements",
            "100000",
            "--substrate-elements",
            "100000",
            "--d-max",
            "0.01",
            "--out",
            out,
        ],
        &["`mesh`", "unknowns", "MB"],
    );
    assert!(start.elapsed().as_secs_f64() < 5.0, "refused without assembling");
    assert_eq!(message.lines().count(), 1, "one line: {message}");
}

#[test]
fn the_two_readings_of_phi_f_are_documented_and_reported_side_by_side() {
    let params = fiberfold(&["params"]);
    let text = String::from_utf8_lossy(&params.stdout);
    assert!(
        text.contains("EACH of the two fibre families") && text.contains("0.05"),
        "{text}"
    );
    let help = String::from_utf8_lossy(&fiberfold(&["params", "--help"]).stdout).to_string();
    assert!(help.contains("EACH of the two fibre families"), "{help}");
    let dir = scratch("phi-f-readings");
    let out = fiberfold(&["reproduce", "--quick", "--only", "fig5", "--out", dir.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let report = std::fs::read_to_string(dir.join("report.md")).unwrap();
    let rows: Vec<&str> = report.lines().filter(|l| l.contains("growth of d_c")).collect();
    assert_eq!(rows.len(), 2, "{report}");
    assert!(rows[0].contains("[phi_f = 0.1 per family]") && rows[1].contains("[phi_f = 0.05 per family]"));
    assert!(rows[1].contains("closer to the paper: phi_f = "), "{}", rows[1]);
}

/// Small things a new user met: the seed's two flags in the usage line, the d-max range as the
/// check applies it, `dispersion --biaxial` saying which direction it takes, warnings of a
/// negative Poisson ratio, a short `--set` help pointing to the table, and a sweep of a shear
/// modulus that keeps Poisson's ratio as a map does.
#[test]
fn what_a_new_user_met_is_mended() {
    let help = String::from_utf8(fiberfold(&["simulate", "--help"]).stdout).unwrap();
    assert!(help.contains("<--waves <WAVES>|--k <K>>"), "{help}");
    rejected(
        &["simulate", "--waves", "4.5", "--d-max", "1.5"],
        &["`d-max`", "(0.005, 1)"],
    );
    let onset_help = String::from_utf8(fiberfold(&["onset", "--help"]).stdout).unwrap();
    assert!(
        onset_help.contains("fiberfold params --help") && !onset_help.contains("mu_l = 10"),
        "{onset_help}"
    );
    let params_help = String::from_utf8(fiberfold(&["params", "--help"]).stdout).unwrap();
    assert!(params_help.contains("  mu_l = 10, in [1e-12, 1e12]: "), "{params_help}");
    let dir = scratch("new-user");
    let out = dir.to_str().unwrap();
    let dispersion = fiberfold(&["dispersion", "--biaxial", "1", "--points", "3", "--out", out]);
    let stdout = String::from_utf8_lossy(&dispersion.stdout);
    assert!(
        stdout.contains("theta = 0 rad") && stdout.contains("onset --biaxial 1"),
        "{stdout}"
    );
    let warned = fiberfold(&["onset", "--set", "K_l=5", "--out", out]);
    let stderr = String::from_utf8_lossy(&warned.stderr);
    assert!(
        warned.status.success() && stderr.contains("warning: the layer has a negative Poisson ratio"),
        "{stderr}"
    );
    // The sweep's last point, mu_l = 100 with K_l = 300 (Table 1's K/mu = 3), is the onset of
    // that bilayer asked for directly.
    let swept = fiberfold(&[
        "sweep", "--param", "mu_l", "--from", "10", "--to", "100", "--points", "2", "--out", out,
    ]);
    assert!(swept.status.success(), "{}", String::from_utf8_lossy(&swept.stderr));
    let sweep: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("sweep.json")).unwrap()).unwrap();
    assert_eq!(sweep["keep_poisson"], true);
    let last = sweep["points"][1]["onset"]["d_c"].as_f64().unwrap();
    let direct = fiberfold(&["onset", "--set", "mu_l=100", "--set", "K_l=300", "--out", out]);
    assert!(direct.status.success());
    let onset: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("onset.json")).unwrap()).unwrap();
    assert!(
        (last - onset["d_c"].as_f64().unwrap()).abs() < 1e-9,
        "{last} vs {onset}"
    );
}

#[test]
fn growth_is_a_load_of_the_linear_theory_and_bad_growth_is_refused() {
    let dir = scratch("growth");
    let out = fiberfold(&["onset", "--load", "growth", "--out", dir.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("onset.json")).unwrap()).unwrap();
    assert_eq!(json["load"], "growth");
    let (d_c, g_c) = (json["d_c"].as_f64().unwrap(), json["g_c"].as_f64().unwrap());
    assert!(
        g_c > 1.0 && (g_c - 1.0 / (1.0 - d_c)).abs() < 1e-12,
        "g_c {g_c}, d_c {d_c}"
    );
    assert!(String::from_utf8_lossy(&out.stdout).contains("g_c = "));
    let out = fiberfold(&[
        "dispersion",
        "--points",
        "5",
        "--load",
        "growth",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let csv = std::fs::read_to_string(dir.join("dispersion.csv")).unwrap();
    assert!(csv.starts_with("k,theta,d_c,lambda1_c,g_c\n"), "{csv}");

    for bad in [
        "growth_layer=0",
        "growth_layer=-1",
        "growth_substrate=inf",
        "growth_layer=nan",
        "growth_layer=11",
    ] {
        let name = bad.split('=').next().unwrap();
        rejected(&["onset", "--set", bad], &[name, "[0.1, 10]"]);
    }
    rejected(
        &["onset", "--load", "growth", "--set", "growth_layer=1.2"],
        &["growth_layer", "load = growth"],
    );
    rejected(
        &["onset", "--load", "uniform_growth", "--set", "growth_substrate=1.1"],
        &["growth_substrate"],
    );
    rejected(
        &["onset", "--load", "grow"],
        &["load", "compression, growth, uniform_growth"],
    );
}

/// `simulate` and `map` under growth: the layer's growth is the load, written beside `d = 1 - 1/g`.
#[test]
fn simulate_and_map_follow_a_growth_of_the_layer() {
    let dir = scratch("simulate-growth");
    let out = fiberfold(&[
        "simulate",
        "--waves",
        "5",
        "--load",
        "growth",
        "--d-max",
        "0.2",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("simulate.json")).unwrap()).unwrap();
    assert_eq!(summary["load"], "growth");
    assert!(
        (summary["g_reached"].as_f64().unwrap() - 1.25).abs() < 1e-12,
        "{}",
        summary["g_reached"]
    );
    let csv = std::fs::read_to_string(dir.join("amplitude.csv")).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let column = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let (d, a, g) = (column("d"), column("A"), column("growth_layer"));
    let rows: Vec<Vec<f64>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    for row in &rows {
        assert!(
            (row[g] - 1.0 / (1.0 - row[d])).abs() < 1e-12,
            "g {} at d {}",
            row[g],
            row[d]
        );
    }
    // The map follows a growth load too: its wrinkle onset is the linear theory's strain.
    let map_dir = scratch("map-growth");
    let out = fiberfold(&common::tiny_map(&map_dir, &["--load", "growth"]));
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    for point in common::map_points(&map_dir) {
        let p: fiberfold::Parameters = serde_json::from_value(point["parameters"].clone()).unwrap();
        assert_eq!(p.load, fiberfold::parameters::Load::Growth);
        let theory = fiberfold::stability::StabilityAnalysis::new(&p, fiberfold::stability::Method::Exact)
            .unwrap()
            .onset()
            .unwrap()
            .d_c;
        assert!((point["d_wrinkle"].as_f64().unwrap() - theory).abs() < 1e-9, "{point}");
    }
    // Wrinkles grow past the linear theory's g_c(k = 0.628) = 1.1415: A at g = 1.25 is of order H.
    let last = rows.last().unwrap();
    assert!(
        last[a] > 0.5 && rows[0][a] < 0.1,
        "A from {} to {}",
        rows[0][a],
        last[a]
    );
}
