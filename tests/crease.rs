//! The path to a crease against independent facts: the creasing threshold of a homogeneous
//! neo-Hookean half-space (Hong, Zhao & Suo 2009: ~0.35, far below Biot's 0.456), and a run
//! through first contact that never inverts an element, never penetrates beyond `1e-3 H`, and
//! dissipates less than 1 % of the strain energy in its stabilisation.

mod common;

use common::scratch;
use fiberfold::fem::ElementKind;
use fiberfold::mesh::MeshSpec;
use fiberfold::protocol::{Protocol, StepControl, StepRecord};
use fiberfold::stability::biot_compression;
use fiberfold::studies::crease_threshold::{crease_threshold, CreaseThresholdStudy};
use fiberfold::studies::simulate;
use fiberfold::Parameters;
use std::f64::consts::{FRAC_PI_4, PI};

#[test]
fn a_seeded_crease_pays_off_near_the_creasing_strain_far_below_biot() {
    // K = 100 mu (Poisson's ratio 0.495); a 12 x 12 block, 48 elements across refined 8 times
    // at the crease, fold length 1: 11,058 unknowns, about 10 s. Refined studies (twice the
    // elements in each direction, or the whole problem scaled by two) move the threshold by
    // 1e-3; this small mesh lands at 0.360. The band of the test is [0.33, 0.38], looser
    // than Hong, Zhao & Suo's 0.35 by the coarse mesh, the finite domain and K / mu = 100.
    let study = CreaseThresholdStudy::new(100.0, 12.0, 48, 8, 20, 8.0);
    let threshold = crease_threshold(&study).unwrap();
    for e in &threshold.evaluations {
        println!(
            "eps {:.4}: (U_crease - U_flat) / (mu a^2) = {:+.5}, depth {:.3}, min J {:.3}",
            e.strain, e.scaled_difference, e.depth, e.min_jacobian
        );
        assert!(e.min_jacobian > 0.0);
    }
    println!("threshold {:.4} in {:.1} s", threshold.strain, threshold.seconds);
    assert!((0.33..=0.38).contains(&threshold.strain), "{}", threshold.strain);
    assert!(threshold.strain < biot_compression() - 0.07);
    let first = &threshold.evaluations[0];
    assert!(
        first.strain == 0.30 && first.difference > 0.0,
        "no crease at eps = 0.30"
    );
}

/// Every accepted state of a run on the short domain `L = D = 10` (20 x (2 + 8) elements, one
/// wave: a trough at `X = 5`) carried to a crease with contact and stabilisation.
fn crease_run(d_max: f64) -> Vec<StepRecord> {
    let params = Parameters {
        beta: FRAC_PI_4,
        ..Parameters::default()
    };
    let mut protocol = Protocol::new(2.0 * PI / 10.0, 0.05, d_max).with_crease_path();
    protocol.control = StepControl {
        min: 1e-7,
        ..StepControl::default()
    };
    protocol.newton.max_iterations = 40;
    let curve = simulate::curve(
        &params,
        MeshSpec::new(20, 2, 8, 0.5, 10.0, 10.0),
        &protocol,
        &|_| Ok(()),
    )
    .unwrap();
    assert!(curve.stopped.is_none(), "{:?}", curve.stopped);
    curve.records
}

#[test]
fn a_run_through_contact_never_inverts_nor_penetrates_and_dissipates_little() {
    let records = crease_run(0.45);
    let first = records
        .iter()
        .find(|r| r.augmented.as_ref().is_some_and(|a| a.in_contact));
    let last = records.last().unwrap();
    println!(
        "{} steps to d = {}, first contact at {:?}, final contact length {:.3}",
        records.len(),
        last.d,
        first.map(|r| r.d),
        last.augmented.as_ref().unwrap().contact_length
    );
    assert!(first.is_some(), "the trough closes before d = 0.45");
    for r in &records[1..] {
        let a = r.augmented.as_ref().unwrap();
        assert!(r.min_jacobian > 0.0, "J = {} at d = {}", r.min_jacobian, r.d);
        assert!(a.penetration <= 1e-3, "penetration {} at d = {}", a.penetration, r.d);
        assert!(a.stabilisation_energy_fraction <= 0.01, "at d = {}", r.d);
    }
    assert!(last.augmented.as_ref().unwrap().contact_length > 0.0);
}

#[test]
fn a_run_to_a_crease_writes_contact_secondary_and_pressure() {
    use fiberfold::studies::simulate::{Progress, SimulateStudy};
    let dir = scratch("crease");
    let mut protocol = Protocol::new(2.0 * PI / 10.0, 0.05, 0.36).with_crease_path();
    protocol.newton.inertia_at_solution = true;
    let study = SimulateStudy {
        vtu_every: 0.1,
        ..SimulateStudy::new(MeshSpec::new(20, 2, 8, 0.5, 10.0, 10.0), protocol)
    };
    let params = Parameters {
        beta: FRAC_PI_4,
        ..Parameters::default()
    };
    let summary = simulate::run(&params, &study, &dir, &|_: Progress<'_>| Ok(())).unwrap();
    let contact: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("contact.json")).unwrap()).unwrap();
    let first = contact["d_first_contact"].as_f64().unwrap();
    assert!(first > 0.2 && first < 0.36, "{contact}");
    assert_eq!(contact["d_reached"].as_f64().unwrap(), 0.36);
    assert!(contact["contact_length_final"].as_f64().unwrap() > 0.0);
    let secondary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("secondary.json")).unwrap()).unwrap();
    assert!(
        secondary.get("d_secondary").is_some() && secondary["inertia_tracked"] == true,
        "{secondary}"
    );
    assert_eq!(
        secondary["branch"]["kind"], "periodic",
        "one trough is always 'periodic'"
    );
    let csv = std::fs::read_to_string(dir.join("amplitude.csv")).unwrap();
    let last: Vec<f64> = csv
        .lines()
        .last()
        .unwrap()
        .split(',')
        .map(|x| x.parse().unwrap())
        .collect();
    assert_eq!(last[7], 1.0, "in contact at the end: {csv}");
    let vtu = std::fs::read_to_string(dir.join("simulate_0004.vtu")).unwrap();
    assert!(vtu.contains(r#"Name="contact_pressure""#));
    assert_eq!(summary.contact.d_first_contact, Some(first));
    // Fig. 7's panel at d = 0.24, the only one of its compressions this run reaches.
    let png = dir.join("fig7.png");
    assert!(summary.files.iter().any(|f| f == &png.display().to_string()));
    let (width, height) = png_size(&png);
    assert_eq!((width, height), (1400, 350));
    // The stress map has its colour bar, in units of mu_s.
    let svg = std::fs::read_to_string(dir.join("fig7.svg")).unwrap();
    assert!(svg.contains("/ mu_s") && svg.contains("99th percentile"));
}

#[test]
fn fig7_shows_the_wrinkle_the_contact_and_the_crease() {
    use simulate::{fig7, FIG7_D};
    let dir = scratch("fig7");
    let params = Parameters {
        beta: FRAC_PI_4,
        ..Parameters::default()
    };
    // The paper's domain on a very coarse mesh (4,242 unknowns): five elements per half wave.
    let facts = fig7(&params, MeshSpec::new(50, 1, 10, 1.0, 50.0, 50.0), true, &dir, &|| {}).unwrap();
    println!("{facts:#?}");
    assert_eq!(facts.states.len(), 3);
    for (state, target) in facts.states.iter().zip(FIG7_D) {
        assert!((state.d - target).abs() <= 0.005, "{} for {target}", state.d);
        assert!(state.max_von_mises > 0.0);
    }
    assert!(!facts.states[0].in_contact && facts.states[2].in_contact);
    assert!(facts.states[2].amplitude > facts.states[0].amplitude);
    for file in &facts.files {
        assert!(std::fs::metadata(file).unwrap().len() > 500, "{}", file.display());
    }
}

/// The refined threshold studies quoted in the closing note (several minutes):
/// `cargo test --release --test crease -- --ignored --nocapture`.
#[test]
#[ignore]
fn refined_crease_thresholds() {
    for (label, study) in [
        (
            "K = 100, 12 x 12, 48 x (8 + 20), x8",
            CreaseThresholdStudy::new(100.0, 12.0, 48, 8, 20, 8.0),
        ),
        (
            "K = 100, 12 x 12, 96 x (16 + 30), x8",
            CreaseThresholdStudy::new(100.0, 12.0, 96, 16, 30, 8.0),
        ),
        (
            "K = 100, 24 x 24, 96 x (8 + 30), x8",
            CreaseThresholdStudy::new(100.0, 24.0, 96, 8, 30, 8.0),
        ),
        (
            "K = 300, 12 x 12, 48 x (8 + 20), x8",
            CreaseThresholdStudy::new(300.0, 12.0, 48, 8, 20, 8.0),
        ),
        (
            "K = 300, 12 x 12, 96 x (16 + 30), x8",
            CreaseThresholdStudy::new(300.0, 12.0, 96, 16, 30, 8.0),
        ),
    ] {
        match crease_threshold(&study) {
            Ok(t) => println!(
                "{label}: threshold {:.4} ({} unknowns, {} evaluations, {:.1} s)",
                t.strain,
                t.unknowns,
                t.evaluations.len(),
                t.seconds
            ),
            Err(e) => println!("{label}: {e}"),
        }
    }
}

/// Width and height from a PNG's IHDR chunk.
fn png_size(path: &std::path::Path) -> (u32, u32) {
    let bytes = std::fs::read(path).unwrap();
    assert_eq!(&bytes[1..4], b"PNG");
    let be = |i: usize| u32::from_be_bytes(bytes[i..i + 4].try_into().unwrap());
    (be(16), be(20))
}

/// `fiberfold crease` on one solid (layer = substrate, K = 100 mu): Hong, Zhao and Suo's
/// threshold (~0.35, far below Biot's 0.456) whatever the fold length, since a half-space has
/// no length scale; the report names the smallest.
#[test]
fn the_crease_onset_of_a_half_space_is_the_same_for_every_fold_length() {
    use fiberfold::studies::crease::{crease, CreaseMesh, CreaseStudy, Criterion, Scan};
    let params = Parameters {
        mu_l: 1.0,
        K_l: 100.0,
        mu_s: 1.0,
        K_s: 100.0,
        phi_m: 1.0,
        phi_f: 0.0,
        ..Parameters::default()
    };
    let study = CreaseStudy {
        mesh: CreaseMesh {
            size: 12.0,
            nx: 48,
            layer: 8,
            substrate: 20,
            ratio: 8.0,
            layer_grading: 1.0,
            element: ElementKind::Displacement,
        },
        fold_lengths: vec![0.5, 1.0],
        scan: Scan {
            from: 0.30,
            to: 0.38,
            step: 0.04,
            tolerance: 1e-3,
        },
        criterion: Criterion::Held,
        refinement: None,
        lowest_only: false,
        stop_past_wrinkle: false,
    };
    let report = crease(&params, &study, &|| {}).unwrap();
    let thresholds: Vec<f64> = report.folds.iter().map(|f| f.thresholds[0].unwrap()).collect();
    println!(
        "thresholds {thresholds:?}, d_crease {:?} at a = {:?}",
        report.d_crease, report.fold_length
    );
    for fold in &report.folds {
        // At each threshold the released fold is an equilibrium: the plane pulls nowhere.
        let released = fold.meshes[0].released.as_ref().expect("released at the threshold");
        println!("released {released:?}");
        assert_eq!(released.pulling_nodes, 0);
        assert!(released.difference <= released.held_difference);
    }
    for &d in &thresholds {
        assert!((0.33..=0.38).contains(&d), "{d}");
        assert!(d < biot_compression() - 0.07);
    }
    assert!(
        (thresholds[0] - thresholds[1]).abs() < 0.01,
        "scale-free: {thresholds:?}"
    );
    let d_crease = report.d_crease.unwrap();
    assert_eq!(d_crease, thresholds.iter().copied().fold(f64::INFINITY, f64::min));
    assert!(report.depth.unwrap() > 0.0);
}

/// A creased state's strong-ellipticity margins (`crease`'s flag) against the homogeneous
/// state's: the block's far field is homogeneous, so the smallest margin over its Gauss points
/// lies at or below the homogeneous one, in both layers, at every compression.
#[test]
fn a_creased_state_carries_the_ellipticity_margins_of_its_far_field() {
    use fiberfold::material::Bilayer;
    use fiberfold::protocol::crease_seed::crease_energy;
    use fiberfold::stability::{ellipticity::ellipticity_margin, Method, StabilityAnalysis};
    use fiberfold::studies::crease::{CreaseMesh, CreaseStudy};
    let params = Parameters {
        mu_l: 1.5,
        K_l: 4.5,
        ..Parameters::default()
    };
    let analysis = StabilityAnalysis::new(&params, Method::Exact).unwrap();
    let mesh = CreaseMesh {
        nx: 24,
        layer: 2,
        substrate: 10,
        layer_grading: 1.0,
        ..CreaseStudy::default().mesh
    };
    let materials = Bilayer::new(&params);
    for d in [0.05, 0.15, 0.25] {
        let creased = crease_energy(&materials, mesh.spec(0.5), d, 0.5).unwrap();
        let (layer, substrate) = analysis.moduli(d).unwrap();
        let homogeneous = [ellipticity_margin(&layer), ellipticity_margin(&substrate)];
        let fe = [creased.ellipticity.layer, creased.ellipticity.substrate];
        for (f, h) in fe.iter().zip(&homogeneous) {
            assert!(
                *f <= h + 1e-9 * h.abs().max(1.0),
                "d = {d}: FE margin {f} above the homogeneous {h}"
            );
        }
    }
}

/// A fold let go to frictionless contact with the plane (the held fold's flaw: the plane pulls
/// on some of its nodes). Isotropic bilayer, mu_l/mu_s = 3, K = 100 mu, a = 0.5 H, base crease
/// mesh. Just below the crease onset the released fold is an equilibrium: it stays closed over
/// part of its length, and the elastic force on every node the plane presses, computed apart
/// from the contact, pushes into the plane. Its energy is below the held fold's (the release
/// minimises from it). Further below, the fold opens back to the flat state and its energy.
#[test]
fn a_released_crease_is_pushed_by_the_plane_wherever_it_touches() {
    use fiberfold::material::Bilayer;
    use fiberfold::protocol::crease_seed::{crease_energy, released_crease};
    use fiberfold::studies::crease::CreaseStudy;
    let params = Parameters {
        mu_l: 3.0,
        K_l: 300.0,
        K_s: 100.0,
        phi_m: 1.0,
        phi_f: 0.0,
        ..Parameters::default()
    };
    let materials = Bilayer::new(&params);
    let spec = CreaseStudy::default().mesh.spec(2.0);
    let held = crease_energy(&materials, spec, 0.2295, 0.5).unwrap();
    let released = released_crease(&materials, spec, 0.2295, 0.5).unwrap();
    println!("held {held:?}\nreleased {released:?}");
    assert!(
        held.tensile_nodes > 0,
        "the held fold is pulled: {}",
        held.tensile_nodes
    );
    assert!(!released.reopened && released.pressed_nodes >= 2);
    assert_eq!(released.pulling_nodes, 0);
    assert!(released.closed_length > 0.0 && released.closed_length <= 0.5 + 1e-12);
    assert_eq!(released.held_difference, held.difference);
    assert!(
        released.difference < held.difference,
        "{} {}",
        released.difference,
        held.difference
    );
    let open = released_crease(&materials, spec, 0.2, 0.5).unwrap();
    assert!(open.reopened && open.depth == 0.0 && open.contact_length == 0.0);
    let flat = crease_energy(&materials, spec, 0.2, 0.5).unwrap().flat_energy;
    assert!(
        open.difference.abs() < 1e-9 * flat,
        "{} against {flat}",
        open.difference
    );
}

/// The released criterion's threshold is a sign change of the equilibrium crease's energy,
/// checked apart from the search: isotropic bilayer, mu_l/mu_s = 3, K = 100 mu, a = 0.5 H, on
/// the base crease mesh refined twice (the base mesh's block turns unstable before any fold
/// pays off). Just above the threshold the released crease stays closed below the flat state's
/// energy; just below it, it does not pay off. At the threshold the plane pulls nowhere.
#[test]
fn the_released_threshold_is_where_the_equilibrium_crease_pays_off() {
    use fiberfold::material::Bilayer;
    use fiberfold::protocol::crease_seed::released_crease;
    use fiberfold::studies::crease::{fold_threshold, CreaseStudy, Criterion, Scan};
    let params = common::isotropic(3.0);
    let materials = Bilayer::new(&params);
    let spec = CreaseStudy::default().mesh.scaled(2).spec(0.5);
    let scan = Scan {
        from: 0.225,
        to: 0.235,
        step: 0.005,
        tolerance: 1e-4,
    };
    let fold = fold_threshold(&materials, spec, 0.5, scan, Criterion::Released, &|| {}).unwrap();
    let (d, held) = (fold.d_threshold.unwrap(), fold.d_held.unwrap());
    println!("released threshold {d}, held {held}; at it {:?}", fold.released);
    let at = fold.released.as_ref().unwrap();
    assert!(!at.reopened && at.pulling_nodes == 0, "{at:?}");
    let above = released_crease(&materials, spec, d + 3.0 * scan.tolerance, 0.5).unwrap();
    let below = released_crease(&materials, spec, d - 3.0 * scan.tolerance, 0.5).unwrap();
    println!("above {above:?}\nbelow {below:?}");
    assert!(!above.reopened && above.difference < 0.0, "{above:?}");
    assert!(below.reopened || below.difference > 0.0, "{below:?}");
    assert!(fold.released_evaluations.windows(2).all(|w| w[0].strain <= w[1].strain));
}

/// A fold's threshold is computed on its own mesh (refined over `1.5 a` at the crease): the
/// same, to the last digit, whatever other folds are asked for beside it.
#[test]
fn a_folds_threshold_does_not_depend_on_the_other_folds_asked_for() {
    let threshold = |folds: &str| -> f64 {
        let out = scratch(&format!("crease-folds-{folds}"));
        let run = common::fiberfold(&[
            "crease",
            "--set",
            "mu_l=2",
            "--set",
            "K_l=6",
            "--set",
            "beta=1.0",
            "--fold",
            folds,
            "--d-from",
            "0.3",
            "--d-to",
            "0.42",
            "--d-step",
            "0.02",
            "--no-convergence",
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
        let report: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("crease.json")).unwrap()).unwrap();
        let fold = &report["folds"][0];
        assert_eq!(fold["fold_length"], 0.5);
        fold["thresholds"][0].as_f64().unwrap()
    };
    let alone = threshold("0.5");
    assert_eq!(alone, threshold("0.5,2"));
    assert!((0.3..0.42).contains(&alone), "{alone}");
}
