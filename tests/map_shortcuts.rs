//! The map's nonlinear run ends where a fold or a doubled period closes on itself (in contact,
//! one trough well ahead of the others, or deep troughs alternating with shallow ones) without
//! changing what the wrinkle becomes: over a 2 x 2 map of Table 1's tissue (contrast 3 and 10,
//! fibres along and across the compression) the shortcut and the run followed to its end
//! (`follow_closed_folds`) give every point the same `first` and `becomes`, the folds' and the
//! doubled periods' runs end in contact, and the others are the same run.

use fiberfold::studies::map::{compute_point, MapPoint, MapSettings, PostBuckling};
use fiberfold::Parameters;
use std::f64::consts::FRAC_PI_2;

/// The map's settings on a coarser nonlinear mesh and one crease mesh (the comparison is of two
/// ways of running the same point).
fn settings(follow_closed_folds: bool) -> MapSettings {
    MapSettings {
        elements_per_wave: 12,
        substrate_elements: 15,
        crease_refinement: None,
        fold_lengths: vec![1.0],
        follow_closed_folds,
        ..MapSettings::default()
    }
}

fn point(settings: &MapSettings, mu_l: f64, beta: f64) -> MapPoint {
    let parameters = Parameters {
        mu_l,
        K_l: 3.0 * mu_l,
        beta,
        ..Parameters::default()
    };
    compute_point(settings, &settings.crease_study(), (0, 0, 0, mu_l, beta), parameters).unwrap()
}

#[test]
fn ending_at_the_closed_fold_or_doubled_period_keeps_every_category_of_a_2_by_2_map() {
    let (shortcut, whole) = (settings(false), settings(true));
    let (mut folds, mut doublings) = (0, 0);
    for (mu_l, beta) in [(3.0, 0.0), (10.0, 0.0), (3.0, FRAC_PI_2), (10.0, FRAC_PI_2)] {
        let fast = point(&shortcut, mu_l, beta);
        let slow = point(&whole, mu_l, beta);
        println!(
            "mu_l {mu_l}, beta {beta:.4}: {:?} / {:?}, reached {:?} in {:.1} s against {:?} / {:?}, reached {:?} in \
             {:.1} s; troughs {:?} against {:?}",
            fast.first,
            fast.becomes,
            fast.d_reached,
            fast.seconds[2],
            slow.first,
            slow.becomes,
            slow.d_reached,
            slow.seconds[2],
            fast.trough_depths,
            slow.trough_depths
        );
        assert_eq!((fast.first, fast.becomes), (slow.first, slow.becomes));
        assert_eq!(fast.d_secondary, slow.d_secondary);
        assert_eq!(fast.d_first_contact, slow.d_first_contact);
        let ended_as = |what: &str| {
            fast.notes
                .iter()
                .any(|n| n.contains(&format!("where {what} closed on itself")))
        };
        let (fold, doubled) = (ended_as("a fold"), ended_as("a doubled period"));
        match fast.becomes {
            Some(PostBuckling::Fold) => {
                folds += 1;
                assert!(fold && !doubled, "{:?}", fast.notes);
            }
            Some(PostBuckling::PeriodDoubling) if doubled => doublings += 1,
            _ => assert!(!fold && !doubled, "{:?}", fast.notes),
        }
        if fold || doubled {
            assert!(
                fast.d_reached >= fast.d_first_contact,
                "the closed trough ends the run in contact"
            );
            assert!(fast.d_reached < slow.d_reached);
        } else {
            assert_eq!(fast.d_reached, slow.d_reached);
            assert_eq!(fast.trough_depths, slow.trough_depths);
        }
    }
    assert!(folds >= 1, "the map holds a fold");
    assert!(doublings >= 1, "the map holds a period doubling that closes");
}
