//! The default crease search takes work away (only the lowest threshold is located and
//! refined, a fold that snapped past where the question is decided is not refined) without
//! changing the answer: on a bilayer where the crease comes first (contrast 3) and one where the
//! wrinkle does (contrast 5), the shortcut search and the whole one (every fold converged, every
//! fold that ended early refined, on the same scan) give the same onset within its uncertainty
//! and the same verdict, from fewer creased states. (The scan's end just past the wrinkle's
//! onset decides by itself: past it the wrinkle comes first whatever the crease does.)

use fiberfold::studies::crease::{crease, CreaseMesh, CreaseReport, CreaseStudy, First, Refinement};

mod common;

/// The default study on a mesh half as fine, with three meshes at most.
fn shortcut() -> CreaseStudy {
    let default = CreaseStudy::default();
    CreaseStudy {
        mesh: CreaseMesh {
            nx: 12,
            layer: 2,
            substrate: 5,
            ..default.mesh
        },
        refinement: Some(Refinement {
            max_meshes: 3,
            ..Refinement::default()
        }),
        ..default
    }
}

fn states(report: &CreaseReport) -> usize {
    report.meshes.iter().map(|m| m.states).sum()
}

fn compare(contrast: f64, expected: First) {
    let params = common::isotropic(contrast);
    let fast = crease(&params, &shortcut(), &|| {}).unwrap();
    // The shortcut's own scan (ending just past the wrinkle, where it decides), every fold and
    // every fold that ended early refined.
    let whole_study = CreaseStudy {
        lowest_only: false,
        stop_past_wrinkle: false,
        scan: fast.scan,
        ..shortcut()
    };
    let whole = crease(&params, &whole_study, &|| {}).unwrap();
    println!(
        "contrast {contrast}: d_wrinkle {:?}; shortcut d_crease {:?} +- {:?} ({:?}, {} states, {:.1} s); whole {:?} \
         +- {:?} ({:?}, {} states, {:.1} s)",
        fast.d_wrinkle,
        fast.d_crease,
        fast.d_crease_error,
        fast.first,
        states(&fast),
        fast.seconds,
        whole.d_crease,
        whole.d_crease_error,
        whole.first,
        states(&whole),
        whole.seconds
    );
    assert_eq!(fast.first, whole.first);
    assert_eq!(
        fast.first, expected,
        "the verdict of the literature's crossover near contrast 3-4"
    );
    match (fast.d_crease, whole.d_crease) {
        (Some(a), Some(b)) => {
            let error = fast.d_crease_error.unwrap().max(whole.d_crease_error.unwrap());
            assert!((a - b).abs() <= error, "{a} against {b} +- {error}");
            assert_eq!(fast.fold_length, whole.fold_length);
        }
        (None, None) => assert!(fast.scan_ends_past_wrinkle),
        (a, b) => panic!("the shortcut found {a:?}, the whole search {b:?}"),
    }
    assert!(states(&fast) < states(&whole));
}

#[test]
fn where_the_crease_comes_first_the_shortcut_finds_the_same_onset() {
    compare(3.0, First::Crease);
}

#[test]
fn where_the_wrinkle_comes_first_the_shortcut_says_so_from_fewer_states() {
    compare(5.0, First::Wrinkle);
}
