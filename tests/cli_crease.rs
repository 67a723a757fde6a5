//! `fiberfold crease` on the command line: its files, its verdict beside the wrinkle, where its
//! scan ends, and its refusals.

mod common;

use common::{fiberfold, rejected, scratch};

#[test]
fn crease_writes_its_onset_and_refuses_bad_folds() {
    let dir = scratch("crease");
    let out = dir.to_str().unwrap();
    rejected(
        &["crease", "--fold", "0", "--out", out],
        &["`fold`", "(0, size / 4 = 3]"],
    );
    rejected(
        &[
            "crease", "--fold", "1", "--d-from", "0.5", "--d-to", "0.4", "--out", out,
        ],
        &["d-from"],
    );
    // A soft layer (mu_l = 1.5) on Table 1's substrate, one fold, a coarse block.
    let soft = |more: &[&str]| {
        let mut flags = vec![
            "crease",
            "--set",
            "mu_l=1.5",
            "--set",
            "K_l=4.5",
            "--fold",
            "1",
            "--d-from",
            "0.2",
            "--d-to",
            "0.3",
            "--nx",
            "24",
            "--substrate-elements",
            "12",
            "--layer-elements",
            "2",
            "--no-convergence",
            "--out",
            out,
        ];
        flags.extend(more);
        let run = fiberfold(&flags);
        assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
        let report: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join("crease.json")).unwrap()).unwrap();
        (String::from_utf8_lossy(&run.stdout).to_string(), report)
    };
    // Its wrinkle (d = 0.2208) comes first: the scan ends 0.01 past it, and says so.
    let (printed, report) = soft(&[]);
    let d_wrinkle = report["d_wrinkle"].as_f64().unwrap();
    assert_eq!(report["first"], "wrinkle", "{printed}");
    assert_eq!(report["scan_ends_past_wrinkle"], true);
    assert!((report["scan"]["to"].as_f64().unwrap() - (d_wrinkle + 0.01)).abs() < 1e-12);
    assert!(
        printed.contains("the wrinkle comes first") && printed.contains("--beyond-wrinkle"),
        "{printed}"
    );
    // Past it, the crease's own threshold.
    let (_, report) = soft(&["--beyond-wrinkle"]);
    assert_eq!(report["scan_ends_past_wrinkle"], false);
    let d = report["d_crease"].as_f64().expect("a crease onset");
    assert!((0.2..0.3).contains(&d), "{d}");
    assert_eq!(report["fold_length"].as_f64(), Some(1.0));
    for file in ["crease_energy.csv", "crease.png", "crease.svg"] {
        assert!(dir.join(file).is_file(), "{file}");
    }
    // One mesh: no panel of the mesh sequence.
    let svg = std::fs::read_to_string(dir.join("crease.svg")).unwrap();
    assert!(svg.contains("Energy of a seeded crease") && !svg.contains("against the mesh size"));
    // The creased states' strong-ellipticity margins, per layer.
    assert!(
        report["ellipticity"]["smallest_substrate"].is_f64(),
        "{}",
        report["ellipticity"]
    );
    let table = std::fs::read_to_string(dir.join("crease_energy.csv")).unwrap();
    assert!(table
        .starts_with("fold_length,mesh,d,difference,scaled_difference,depth,min_J,tensile_nodes,ellipticity_layer,ellipticity_substrate"));
}
