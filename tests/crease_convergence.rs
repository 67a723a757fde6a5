//! The crease onset converged in the mesh, against independent facts: near the crossover of an
//! isotropic bilayer (mu_l / mu_s = 3, K = 100 mu) the crease comes before the wrinkle of the
//! linear theory once the mesh resolves the crease tip, and a mesh sequence that refines
//! uniformly from a uniform layer extrapolates to the same threshold as the graded default,
//! within the uncertainty each reports.

use fiberfold::stability::{Method, StabilityAnalysis};
use fiberfold::studies::crease::{crease, CreaseMesh, CreaseReport, CreaseStudy, Criterion, Refinement, Scan};
use fiberfold::Parameters;

mod common;

/// mu_l / mu_s = 3, K = 100 mu in both layers, no fibres.
fn contrast_three() -> Parameters {
    common::isotropic(3.0)
}

/// The fold `a = 0.5` scanned over `[0.2, 0.26]`, on `mesh` and its multiples.
fn study(mesh: CreaseMesh, max_meshes: usize) -> CreaseStudy {
    CreaseStudy {
        mesh,
        fold_lengths: vec![0.5],
        scan: Scan {
            from: 0.2,
            to: 0.26,
            step: 0.02,
            ..CreaseStudy::default().scan
        },
        criterion: Criterion::Held,
        refinement: Some(Refinement {
            max_meshes,
            ..Refinement::default()
        }),
        lowest_only: false,
        stop_past_wrinkle: false,
    }
}

fn describe(report: &CreaseReport) -> String {
    let fold = &report.folds[0];
    format!(
        "thresholds {:?} on {:?} unknowns; d_crease {:?} +- {:?}, order {:?}, converged {}",
        fold.thresholds,
        report.meshes.iter().map(|m| m.unknowns).collect::<Vec<_>>(),
        report.d_crease,
        report.d_crease_error,
        report.order,
        report.converged
    )
}

#[test]
fn at_contrast_three_the_converged_crease_comes_before_the_wrinkle() {
    let params = contrast_three();
    let d_wrinkle = StabilityAnalysis::new(&params, Method::Exact)
        .unwrap()
        .onset()
        .unwrap()
        .d_c;
    let report = crease(&params, &study(CreaseStudy::default().mesh, 4), &|| {}).unwrap();
    println!("d_wrinkle {d_wrinkle}; {}", describe(&report));
    let (d, error) = (report.d_crease.unwrap(), report.d_crease_error.unwrap());
    assert!(d + error < d_wrinkle, "{d} +- {error} against {d_wrinkle}");
    assert!(report.converged && report.order.is_some());
    // Refinement lowers the threshold, monotonically, towards the extrapolated value.
    let found: Vec<f64> = report.folds[0].thresholds.iter().flatten().copied().collect();
    assert!(found.len() >= 3, "{found:?}");
    assert!(found.windows(2).all(|w| w[1] < w[0]), "{found:?}");
    assert!(d < found[found.len() - 1]);
    assert!(error < 1e-3);
}

/// Two mesh families (several minutes): the graded default and a uniform layer refined
/// uniformly, `cargo test --release --test crease_convergence -- --ignored --nocapture`.
#[test]
#[ignore]
fn graded_and_uniform_mesh_families_extrapolate_to_the_same_threshold() {
    let params = contrast_three();
    let graded = crease(&params, &study(CreaseStudy::default().mesh, 4), &|| {}).unwrap();
    let uniform_mesh = CreaseMesh {
        nx: 24,
        layer: 2,
        substrate: 10,
        layer_grading: 1.0,
        ..CreaseStudy::default().mesh
    };
    let uniform = crease(&params, &study(uniform_mesh, 5), &|| {}).unwrap();
    println!("graded: {}\nuniform: {}", describe(&graded), describe(&uniform));
    let (g, u) = (graded.d_crease.unwrap(), uniform.d_crease.unwrap());
    let band = graded.d_crease_error.unwrap() + uniform.d_crease_error.unwrap();
    assert!((g - u).abs() <= band, "{g} against {u}, band {band}");
}
