//! Tissue laws from the command line: a parameters file with law tables, dotted `--set` keys,
//! and one-line errors (exit code 2) naming the key and its range.

mod common;

use common::{fiberfold, rejected, scratch};

#[test]
fn bad_laws_and_constants_are_named_with_their_range() {
    rejected(
        &["params", "--set", "layer.law=rubber"],
        &["layer.law", "neo_hookean", "ogden", "gent"],
    );
    rejected(
        &["params", "--set", "fibres.law=spring"],
        &["fibres.law", "quadratic", "hgo"],
    );
    rejected(&["params", "--set", "layer.law=ogden"], &["layer.alpha", "missing"]);
    rejected(
        &["params", "--set", "layer.law=ogden", "--set", "layer.alpha=0"],
        &["layer.alpha", "without 0"],
    );
    rejected(
        &["params", "--set", "layer.law=ogden", "--set", "layer.alpha=[2, 4]"],
        &["layer.alpha", "as long as"],
    );
    rejected(&["params", "--set", "layer.law=gent"], &["layer.jm", "missing"]);
    rejected(
        &["params", "--set", "layer.law=gent", "--set", "layer.jm=-1"],
        &["layer.jm", "(0, 1e12]"],
    );
    rejected(
        &[
            "params",
            "--set",
            "substrate.law=mooney_rivlin",
            "--set",
            "substrate.c1=1",
        ],
        &["substrate.c2", "missing"],
    );
    rejected(
        &[
            "params",
            "--set",
            "fibres.law=hgo",
            "--set",
            "fibres.k1=1",
            "--set",
            "fibres.k2=1",
            "--set",
            "fibres.kappa=0.4",
        ],
        &["fibres.kappa", "[0, 1/3]"],
    );
    rejected(
        &["params", "--set", "layer.c1=1"],
        &["layer.c1", "not a constant of the neo_hookean law"],
    );
    rejected(
        &["params", "--set", "fibres.law=hgo", "--set", "mu_f=3"],
        &["mu_f", "hgo"],
    );
    rejected(
        &["map", "--x", "layer.alpha", "--x-from", "1", "--x-to", "2"],
        &["layer.alpha"],
    );
}

#[test]
fn law_tables_round_trip_and_order_does_not_matter_in_a_file() {
    let dir = scratch("laws-roundtrip");
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("p.toml");
    // Constants before the law inside a table, and a flat key after the tables.
    std::fs::write(
        &file,
        "[layer]\nalpha = -25\nlaw = \"ogden\"\n\n[fibres]\nk2 = 1.5\nk1 = 2\nlaw = \"hgo\"\n",
    )
    .unwrap();
    let out = fiberfold(&[
        "params",
        "--params",
        file.to_str().unwrap(),
        "--out",
        dir.to_str().unwrap(),
    ]);
    let printed = String::from_utf8_lossy(&out.stdout).to_string();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    for line in [
        "law = \"ogden\"",
        "alpha = [-25.0]",
        "mu = [10.0]",
        "law = \"hgo\"",
        "kappa = 0.0",
    ] {
        assert!(printed.contains(line), "`{line}` missing from:\n{printed}");
    }
    let again = fiberfold(&["params", "--params", dir.join("params.toml").to_str().unwrap()]);
    assert_eq!(String::from_utf8(again.stdout).unwrap(), printed);
}

/// A one-term Ogden law with alpha = -25 (Budday et al.'s brain tissue) for both layers.
const OGDEN_BOTH: [&str; 8] = [
    "--set",
    "layer.law=ogden",
    "--set",
    "layer.alpha=-25",
    "--set",
    "substrate.law=ogden",
    "--set",
    "substrate.alpha=-25",
];

#[test]
fn onset_runs_with_every_law() {
    let laws: [&[&str]; 4] = [
        &[
            "--set",
            "layer.law=mooney_rivlin",
            "--set",
            "layer.c1=3",
            "--set",
            "layer.c2=2",
        ],
        &OGDEN_BOTH,
        &[
            "--set",
            "layer.law=gent",
            "--set",
            "layer.jm=5",
            "--set",
            "substrate.law=gent",
            "--set",
            "substrate.jm=5",
        ],
        &[
            "--set",
            "fibres.law=hgo",
            "--set",
            "fibres.k1=5",
            "--set",
            "fibres.k2=1",
            "--set",
            "tension_only=true",
        ],
    ];
    for (i, law) in laws.iter().enumerate() {
        let dir = scratch(&format!("laws-onset-{i}"));
        let mut args = vec!["onset", "--out", dir.to_str().unwrap()];
        args.extend_from_slice(law);
        let out = fiberfold(&args);
        assert!(
            out.status.success(),
            "{law:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let summary: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join("onset.json")).unwrap()).unwrap();
        let d_c = summary["d_c"].as_f64().unwrap();
        assert!(d_c > 0.0 && d_c < 1.0, "{law:?}: {summary}");
    }
}

/// The exact bifurcation of the discretised perfect bilayer with Ogden layers (mixed element,
/// fine mesh) against the linear theory at the mode's wavenumber, as for neo-Hookean.
#[test]
fn ogden_fe_bifurcation_agrees_with_the_linear_theory_on_the_fine_mesh() {
    let mut args = vec!["--mesh", "fine", "--set", "beta=0.785398"];
    args.extend_from_slice(&OGDEN_BOTH);
    let summary = common::mixed_bifurcation("laws-ogden-bifurcation", &args);
    let difference = summary["relative_difference"].as_f64().unwrap();
    println!("Ogden alpha = -25, fine mesh: FE vs theory {difference:e}");
    assert!(difference.abs() < 1e-4, "FE vs theory {difference:e}");
}

/// A Gent substrate that reaches its limiting extensibility before `d_max`: the table ends
/// there, the rows before it are written, and the summary says where.
#[test]
fn the_homogeneous_table_ends_at_a_gent_limit() {
    let dir = scratch("laws-gent-homogeneous");
    let out = fiberfold(&[
        "homogeneous",
        "--set",
        "substrate.law=gent",
        "--set",
        "substrate.jm=0.2",
        "--out",
        dir.to_str().unwrap(),
    ]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(stdout.contains("the table ends before d = "), "{stdout}");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("homogeneous.json")).unwrap()).unwrap();
    let stopped = summary["stopped_at"].as_f64().unwrap();
    let rows = std::fs::read_to_string(dir.join("homogeneous.csv"))
        .unwrap()
        .lines()
        .count()
        - 1;
    assert!(
        stopped < 0.5 && rows == (stopped / 0.005).round() as usize,
        "{stopped} {rows}"
    );
}
