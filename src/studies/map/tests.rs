//! The map's axes, grid, shards and folder claims.

use super::*;
use crate::studies::grid::claim_folder;

fn axis(name: &str, from: f64, to: f64, log: bool) -> Axis {
    Axis {
        name: name.into(),
        from,
        to,
        points: 3,
        log,
    }
}

#[test]
fn a_law_constant_is_an_axis_when_its_law_is_in_use() {
    let mut ogden = Parameters::default();
    ogden.set("layer.law=ogden").unwrap();
    ogden.set("layer.alpha=-25").unwrap();
    axis("layer.alpha", -25.0, -2.0, false).validate("x", &ogden).unwrap();
    let message = axis("layer.alpha", -25.0, -2.0, false)
        .validate("x", &Parameters::default())
        .unwrap_err()
        .to_string();
    assert!(message.contains("layer.alpha") && message.contains("mu_l"), "{message}");
    let mut p = ogden.clone();
    p.set_number("layer.alpha", -5.0).unwrap();
    assert_eq!(
        p.layer,
        crate::parameters::MatrixLaw::Ogden {
            mu: vec![10.0],
            alpha: vec![-5.0]
        }
    );
}

#[test]
fn axes_are_spaced_as_asked_and_bad_ones_name_their_flag() {
    assert_eq!(axis("mu_l", 1.0, 100.0, true).values(), vec![1.0, 10.0, 100.0]);
    assert_eq!(axis("beta", 0.0, 1.0, false).values(), vec![0.0, 0.5, 1.0]);
    let message = |a: Axis| a.validate("x", &Parameters::default()).unwrap_err().to_string();
    assert!(message(axis("tension_only", 0.0, 1.0, false)).contains("`x`: allowed range is a numeric parameter"));
    assert!(message(axis("mu_l", f64::NAN, 1.0, false)).contains("`x-from`"));
    assert!(message(axis("mu_l", 2.0, 1.0, false)).contains("`x-to`"));
    assert!(message(axis("mu_l", 0.0, 1.0, true)).contains("with --x-log"));
}

#[test]
fn shards_that_start_together_all_claim_the_folder() {
    let study = MapStudy {
        base: Parameters::default(),
        x: axis("mu_l", 1.0, 30.0, true),
        y: axis("beta", 0.0, 1.0, false),
        settings: MapSettings::default(),
    };
    for round in 0..20 {
        let out = std::env::temp_dir().join(format!("fiberfold-claim-{}-{round}", std::process::id()));
        let _ = std::fs::remove_dir_all(&out);
        std::thread::scope(|scope| {
            let claims: Vec<_> = (0..8).map(|_| scope.spawn(|| claim_folder(&study, &out))).collect();
            for claim in claims {
                claim.join().unwrap().unwrap();
            }
        });
        let stray: Vec<_> = std::fs::read_dir(&out)
            .unwrap()
            .filter_map(|e| e.ok())
            .map(|e| e.file_name())
            .collect();
        assert_eq!(stray.len(), 2, "{stray:?}"); // map-spec.json and points/
        std::fs::remove_dir_all(&out).unwrap();
    }
}

#[test]
fn a_mapped_shear_modulus_keeps_the_base_poisson_ratio_unless_asked_not_to() {
    let mut study = MapStudy {
        base: Parameters::default(),
        x: axis("mu_l", 1.0, 30.0, true),
        y: axis("beta", 0.0, 1.0, false),
        settings: MapSettings::default(),
    };
    let grid = study.grid().unwrap();
    let ((index, ix, iy, x, y), p) = &grid[5];
    assert_eq!((*index, *ix, *iy), (5, 2, 1));
    assert_eq!((p.mu_l, p.beta), (*x, *y));
    assert!((p.K_l / p.mu_l - 3.0).abs() < 1e-12, "{p:?}");
    study.settings.keep_poisson = false;
    assert_eq!(study.grid().unwrap()[5].1.K_l, 30.0);
    assert_eq!(Shard::parse("1/4").unwrap(), Shard { index: 1, count: 4 });
    for bad in ["4/4", "1/0", "a/2", "3"] {
        assert!(Shard::parse(bad).is_err(), "{bad}");
    }
}
