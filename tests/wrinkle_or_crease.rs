//! Wrinkle or crease first, and what the wrinkle becomes, against independent facts: a bilayer
//! without contrast is a half-space, which creases (Hong, Zhao & Suo ~0.35) long before it
//! wrinkles (Biot 0.456); a stiff layer wrinkles first at any fibre angle (its wrinkles come
//! at a few per cent, a crease must fold the layer); and a crease is never dearer than one
//! confined to the layer, so below the ratio at which the layer's wrinkles reach the
//! half-space crease strain a crease comes first. Nearly incompressible (K = 100 mu), no fibres.

mod common;

use common::isotropic;
use fiberfold::stability::{Method, StabilityAnalysis};
use fiberfold::studies::crease::CreaseStudy;
use fiberfold::studies::map::{compute_point, first_instability, First, MapSettings, PostBuckling};
use fiberfold::Parameters;

fn d_wrinkle(ratio: f64) -> f64 {
    StabilityAnalysis::new(&isotropic(ratio), Method::Exact)
        .unwrap()
        .onset()
        .unwrap()
        .d_c
}

#[test]
fn a_soft_bilayer_creases_first_a_stiff_one_wrinkles_first() {
    // The decision on the base mesh alone: the convergence of the onset has its own tests
    // (crease_convergence.rs), and the half-space's threshold moves by about 1e-3 from one
    // mesh to the next, well inside the bounds below.
    let settings = MapSettings {
        crease_refinement: None,
        crease_mesh: CreaseStudy::default().mesh,
        ..MapSettings::default()
    };
    let crease = settings.crease_study();
    let first = |ratio: f64| first_instability(&crease, isotropic(ratio)).unwrap();

    let same = first(1.0);
    println!("ratio 1: d_wrinkle {:?}, d_crease {:?}", same.d_wrinkle, same.d_crease);
    assert_eq!(same.first, First::Crease);
    let half_space_crease = same.d_crease.unwrap();
    assert!((0.34..0.38).contains(&half_space_crease), "{half_space_crease}");
    let stiff = first(10.0);
    println!(
        "ratio 10: d_wrinkle {:?}, d_crease {:?}, {:?}",
        stiff.d_wrinkle, stiff.d_crease, stiff.notes
    );
    assert_eq!(stiff.first, First::Wrinkle);

    // The ratio at which the layer's wrinkles come at the half-space crease strain: below it a
    // crease, which costs no more than one confined to the layer, must come first.
    let (mut lo, mut hi) = (1.0f64, 10.0f64);
    for _ in 0..40 {
        let mid = 0.5 * (lo + hi);
        if d_wrinkle(mid) > half_space_crease {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let below = first(0.9 * lo);
    println!(
        "wrinkles reach the half-space crease strain at {lo:.3}; at {:.3}: {:?} (d_wrinkle {:?}, d_crease {:?})",
        0.9 * lo,
        below.first,
        below.d_wrinkle,
        below.d_crease
    );
    assert_eq!(below.first, First::Crease, "{:?}", below.notes);
}

#[test]
fn a_stiff_layer_goes_on_to_a_period_doubling_or_a_fold() {
    let settings = MapSettings {
        post_buckling_range: 0.3,
        fold_lengths: vec![1.0],
        crease_refinement: None,
        ..MapSettings::default()
    };
    let parameters = Parameters {
        K_l: 90.0,
        K_s: 3.0,
        ..isotropic(30.0)
    };
    let point = compute_point(&settings, &settings.crease_study(), (0, 0, 0, 30.0, 0.0), parameters).unwrap();
    println!(
        "becomes {:?}: troughs {:?}, doubling {:?}, secondary at {:?} (mode {:?}), notes {:?}",
        point.becomes, point.trough_depths, point.doubling, point.d_secondary, point.secondary_half_waves, point.notes
    );
    assert_eq!(point.first, First::Wrinkle);
    assert!(
        matches!(point.becomes, Some(PostBuckling::PeriodDoubling | PostBuckling::Fold)),
        "{:?}",
        point.becomes
    );
    // The wrinkle loses stability after its onset and before it ends.
    let d = point.d_secondary.unwrap();
    assert!(d > point.d_wrinkle.unwrap() && d < point.d_reached.unwrap(), "{d}");
}

/// A layer 30 times stiffer than a nearly incompressible substrate (`K = 100 mu`): the crease
/// search's seeded fold loses strong ellipticity at its tip (singular by construction) well
/// before the wrinkle's onset. That is the fold's, reported apart (`d_ellipticity_loss_fold`);
/// the tissue's, from the nonlinear run, is not before the onset.
#[test]
fn the_crease_search_s_fold_tip_is_not_the_tissue_s_loss_of_ellipticity() {
    let settings = MapSettings {
        post_buckling_range: 0.02,
        ..MapSettings::default()
    };
    let point = compute_point(
        &settings,
        &settings.crease_study(),
        (0, 0, 0, 30.0, 0.0),
        isotropic(30.0),
    )
    .unwrap();
    println!(
        "d_wrinkle {:?}; ellipticity lost: nonlinear run {:?}, crease search {:?}",
        point.d_wrinkle, point.d_ellipticity_loss_fe, point.d_ellipticity_loss_fold
    );
    let d_wrinkle = point.d_wrinkle.unwrap();
    assert!(point.d_ellipticity_loss_fold.unwrap() < d_wrinkle);
    assert!(point.d_ellipticity_loss_fe.is_none_or(|d| d > d_wrinkle));
    assert!(point.d_reached.unwrap() > d_wrinkle);
}
