//! `fiberfold pattern` as a user runs it: a coarse patch's files, and bad input.

mod common;

use common::{fiberfold, scratch};

#[test]
fn a_coarse_patch_writes_its_summary_tables_figure_and_vtu() {
    let out = scratch("pattern");
    let output = fiberfold(&[
        "pattern",
        "--set",
        "beta=0.785398",
        "--set",
        "psi=0.5235988",
        "--elements-per-wavelength",
        "3",
        "--out",
        out.to_str().unwrap(),
    ]);
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&output.stderr)
    );
    assert!(stdout.contains("admissible wave vectors nearest the onset"), "{stdout}");
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("pattern.json")).unwrap()).unwrap();
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
}

#[test]
fn bad_input_is_refused_with_exit_code_2_naming_the_flag() {
    for (args, word) in [
        (&["--periods", "0"][..], "`periods`"),
        (&["--biaxial", "1.5"][..], "`biaxial`"),
        (&["--elements-per-wavelength", "1"][..], "`elements-per-wavelength`"),
        (&["--h0", "500"][..], "`h0`"),
        (&["--d-max", "2"][..], "`d-max`"),
        (&["--sides", "symmetry", "--set", "psi=0.3"][..], "`sides`"),
        (&["--load", "growth"][..], "`load`"),
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
