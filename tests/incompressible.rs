//! Exactly incompressible tissue (`incompressible = true`) in the finite elements, against
//! independent facts: the closed-form homogeneous state with its pressure, the patch test,
//! Biot's half-space, the linear theory of the bilayer, Hong, Zhao and Suo's crease, and
//! one-line refusals of what cannot work.

mod common;

use common::{boundary_values, distortion, fiberfold, mixed_bifurcation, scratch, worst_nodal_error};
use fiberfold::fem::ElementKind;
use fiberfold::fem::{equilibrium, Newton, NewtonPolicy, System};
use fiberfold::homogeneous::constraint_pressure;
use fiberfold::material::Bilayer;
use fiberfold::mesh::{Mesh, MeshSpec, Y};
use fiberfold::protocol::bifurcation::homogeneous_inertia;
use fiberfold::protocol::model_conditions;
use fiberfold::stability::{biot_compression, Method, StabilityAnalysis};
use fiberfold::studies::crease::{crease, CreaseMesh, CreaseStudy, Scan};
use fiberfold::Parameters;

/// An incompressible neo-Hookean solid throughout (no fibres, layer = substrate when `mu_l = 1`).
fn incompressible(mu_l: f64) -> Parameters {
    Parameters {
        mu_l,
        phi_m: 1.0,
        phi_f: 0.0,
        incompressible: true,
        ..Parameters::default()
    }
}

/// From rest, Newton's method with the multiplier updates reaches the closed-form state:
/// `lambda_2 = 1 / lambda_1` in both layers and the pressure that frees `sigma_22`.
#[test]
fn compressed_incompressible_bilayer_reaches_the_closed_form_state() {
    let params = Parameters {
        incompressible: true,
        ..Parameters::default()
    };
    let materials = Bilayer::new(&params);
    let mesh = Mesh::new(MeshSpec::new(4, 2, 4, 0.5, 4.0, 6.0).with_element(ElementKind::Mixed)).unwrap();
    let mut system = System::new(mesh.clone(), &materials).unwrap();
    let d = 0.2;
    let mut u = vec![0.0; system.num_dofs()];
    let report = equilibrium::solve(
        &mut Newton::new(),
        &mut system,
        &mut u,
        &model_conditions(&mesh, d).unwrap(),
        &NewtonPolicy::default(),
    )
    .unwrap();
    assert!(report.updates.pressure > 0, "{report:?}");
    let depth = mesh.spec().depth;
    for (n, &[_, y]) in mesh.coordinates().iter().enumerate() {
        let expected = (1.0 / (1.0 - d) - 1.0) * (y + depth);
        assert!(
            (u[mesh.dofs().dof(n, Y)] - expected).abs() < 1e-7,
            "node {n}: {} vs {expected}",
            u[mesh.dofs().dof(n, Y)]
        );
    }
    let f = [1.0 - d, 0.0, 0.0, 1.0 / (1.0 - d)];
    let p_layer = constraint_pressure(&materials.layer, &f).unwrap();
    let p_substrate = constraint_pressure(&materials.substrate, &f).unwrap();
    for (e, region) in mesh.regions().iter().enumerate() {
        let lambda = system.element_multipliers(e, &u);
        let p = match region {
            fiberfold::mesh::Region::Layer => p_layer,
            fiberfold::mesh::Region::Substrate => p_substrate,
        };
        // The multipliers stop within penalty x tolerance of their limit: 1e3 x 1e-7.
        assert!((lambda[0] - p).abs() < 2e-4, "element {e}: {lambda:?} vs {p}");
        assert!(
            lambda[1].abs() < 2e-4 && lambda[2].abs() < 2e-4,
            "element {e}: {lambda:?}"
        );
    }
}

/// An isochoric affine deformation on a curved mesh is reproduced exactly.
#[test]
fn patch_test_with_the_constraint() {
    let mesh = Mesh::new(MeshSpec::new(3, 2, 2, 0.8, 3.0, 2.0).with_element(ElementKind::Mixed))
        .unwrap()
        .perturbed(distortion(0.08));
    // det(I + G) = 1.
    let g = [[0.1, 0.2], [-0.15, 0.0]];
    let g11 = (1.0 + g[0][1] * g[1][0]) / (1.0 + g[0][0]) - 1.0;
    let affine = |[x, y]: [f64; 2]| [g[0][0] * x + g[0][1] * y, g[1][0] * x + g11 * y];
    let mut system = System::new(mesh.clone(), &Bilayer::new(&incompressible(1.0))).unwrap();
    let mut u = vec![0.0; system.num_dofs()];
    equilibrium::solve(
        &mut Newton::new(),
        &mut system,
        &mut u,
        &boundary_values(&mesh, affine),
        &NewtonPolicy::default(),
    )
    .unwrap();
    let worst = worst_nodal_error(&mesh, &u, affine);
    assert!(worst < 1e-10, "patch test error {worst:e}");
}

/// Coarse mesh, no fibres, `mu_l = 10`: within 2e-4 of the linear theory.
#[test]
fn incompressible_bilayer_bifurcation_agrees_with_the_linear_theory() {
    let summary = mixed_bifurcation(
        "incompressible-bilayer",
        &["--set", "phi_m=1", "--set", "phi_f=0", "--set", "incompressible=true"],
    );
    assert_eq!(summary["mesh"]["element"], "mixed");
    let difference = summary["relative_difference"].as_f64().unwrap();
    assert!(difference.abs() < 2e-4, "FE vs theory {difference:e}");
}

/// A homogeneous incompressible half-space (the coarse mesh, 50 H deep): Biot's value within
/// 0.5 %.
#[test]
fn incompressible_half_space_bifurcates_at_biot_compression() {
    let summary = mixed_bifurcation(
        "incompressible-half-space",
        &[
            "--set",
            "mu_l=1",
            "--set",
            "phi_m=1",
            "--set",
            "phi_f=0",
            "--set",
            "incompressible=true",
        ],
    );
    let d = summary["d_bifurcation"].as_f64().unwrap();
    assert!(
        (d / biot_compression() - 1.0).abs() < 5e-3,
        "{d} vs Biot {}",
        biot_compression()
    );
}

/// Hong, Zhao and Suo: a crease in an incompressible neo-Hookean half-space pays off at a
/// compressive strain of about 0.354, well below Biot's 0.456. Converged in the mesh on the
/// default mesh sequence, the extrapolated threshold lies in [0.345, 0.360], and the sequence
/// does not rise (within the root's tolerance).
#[test]
fn incompressible_half_space_creases_at_hong_zhao_suo() {
    let defaults = CreaseStudy::default();
    let study = CreaseStudy {
        mesh: CreaseMesh {
            element: ElementKind::Mixed,
            ..defaults.mesh
        },
        fold_lengths: vec![1.0],
        scan: Scan {
            from: 0.32,
            to: 0.37,
            step: 0.05,
            ..defaults.scan
        },
        ..defaults
    };
    let report = crease(&incompressible(1.0), &study, &|| {}).unwrap();
    let thresholds: Vec<f64> = report.folds[0].thresholds.iter().map(|d| d.unwrap()).collect();
    let (d, error) = (report.d_crease.unwrap(), report.d_crease_error.unwrap());
    println!(
        "thresholds {thresholds:?}: d_crease {d} +- {error}, order {:?}",
        report.order
    );
    assert!((0.345..=0.360).contains(&d), "d_crease {d}");
    assert!(report.converged && thresholds.len() >= 3);
    let root = study.scan.tolerance;
    assert!(
        thresholds.windows(2).all(|w| w[1] <= w[0] + 2.0 * root),
        "{thresholds:?}"
    );
    assert!(error < 1e-3 && d < biot_compression() - 0.09);
    // Released at each threshold (with the pressure multipliers in the unknowns), the fold
    // goes to an equilibrium that the plane only pushes.
    for mesh in &report.folds[0].meshes {
        let released = mesh
            .released
            .as_ref()
            .unwrap_or_else(|| panic!("{:?}", mesh.release_error));
        assert_eq!(released.pulling_nodes, 0, "{released:?}");
    }
}

/// The Table 1 path of incompressible layers goes on through the closing of its troughs, where
/// the multiplier updates raise the penalty (and with it the residual's round-off); before
/// Newton's tolerance followed the raise, this run stopped at d = 0.2375.
#[test]
fn incompressible_path_goes_through_the_closing_troughs() {
    let out = scratch("incompressible-closing");
    let run = fiberfold(&[
        "simulate",
        "--set",
        "incompressible=true",
        "--element",
        "mixed",
        "--set",
        "beta=0.785398",
        "--waves",
        "4.5",
        "--nx",
        "48",
        "--layer-elements",
        "2",
        "--substrate-elements",
        "10",
        "--d-max",
        "0.27",
        "--vtu-every",
        "1",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let contact: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("contact.json")).unwrap()).unwrap();
    let first = contact["d_first_contact"].as_f64().expect("the troughs close");
    assert!(first > 0.2 && first < 0.26, "first contact at {first}");
    assert_eq!(contact["d_reached"].as_f64(), Some(0.27));
    assert!(contact["penetration_max"].as_f64().unwrap() < 1e-3);
}

/// What cannot work is refused in one line with exit code 2, before anything is written.
#[test]
fn incompressibility_with_a_contradictory_setting_is_refused() {
    let out = scratch("incompressible-refusals");
    let target = out.join("run");
    let cases: [(&[&str], &str); 4] = [
        (
            &["reproduce", "--quick", "--set", "incompressible=true"],
            "incompressible",
        ),
        (
            &[
                "simulate",
                "--waves",
                "4",
                "--set",
                "incompressible=true",
                "--element",
                "displacement",
            ],
            "element",
        ),
        (
            &["crease", "--set", "incompressible=true", "--element", "displacement"],
            "element",
        ),
        (
            &[
                "map",
                "--x",
                "K_l",
                "--x-from",
                "10",
                "--x-to",
                "100",
                "--x-points",
                "2",
                "--y",
                "mu_l",
                "--y-from",
                "1",
                "--y-to",
                "10",
                "--y-points",
                "2",
                "--set",
                "incompressible=true",
                "--element",
                "mixed",
            ],
            "`x`",
        ),
    ];
    for (args, names) in cases {
        let mut all: Vec<&str> = args.to_vec();
        all.extend(["--out", target.to_str().unwrap()]);
        let output = fiberfold(&all);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(2), "{args:?}: {stderr}");
        assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
        assert!(stderr.contains(names), "{stderr}");
        assert!(!target.exists(), "{args:?} wrote {}", target.display());
    }
}

/// The stability of the exactly incompressible mixed element is that of its displacements
/// under the constraint: at the homogeneous states of a bilayer whose layer is a hundred times
/// stiffer than its substrate, the tangent has one negative pivot per admissible wave
/// (`k = n pi / L`, `n >= 1`) whose onset by the exact linear theory lies below `d`. The fine
/// mesh puts the onsets within about 4e-7 in `d` of the theory's (1.4e-5 relative at the
/// critical wave), so every state lies at least 1e-5 from an onset: `d = 0.025` is 1.4e-5 past
/// the sixth wave's. Counted with the constraint's penalty scaled by the largest shear modulus
/// (a hundred times the substrate's own), that wave was missed there.
#[test]
fn incompressible_inertia_at_high_contrast_counts_the_unstable_waves() {
    let params = incompressible(100.0);
    let spec = MeshSpec::fine().with_element(ElementKind::Mixed);
    let theory = StabilityAnalysis::new(&params, Method::Exact).unwrap();
    let onsets: Vec<f64> = (1..=20)
        .map(|n| {
            theory
                .critical_compression(n as f64 * std::f64::consts::PI / spec.length)
                .unwrap()
        })
        .collect();
    assert!(onsets[19] > 0.1, "{onsets:?}");
    let ds = [0.02, 0.025, 0.026, 0.03, 0.034, 0.039, 0.045];
    let counts = homogeneous_inertia(&Bilayer::new(&params), spec, &ds).unwrap();
    for (&d, count) in ds.iter().zip(counts) {
        let margin = onsets.iter().map(|o| (o - d).abs()).fold(f64::INFINITY, f64::min);
        assert!(margin > 1e-5, "d = {d} lies {margin:e} from an onset");
        let unstable = onsets.iter().filter(|&&o| o < d).count();
        assert_eq!(count, unstable, "d = {d}: onsets {onsets:?}");
    }
}
