//! Independent facts for modes in any direction of the surface.

use super::*;
use crate::parameters::{Load, Parameters};
use crate::stability::discrete::DiscreteOptions;
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, FRAC_PI_6};

fn surface(biaxial: f64, theta: f64) -> Option<Surface> {
    Some(Surface { biaxial, theta })
}

/// With `theta = 0`, `R = 0` and `psi = 0` the Z displacement decouples: `d_c(k)` is the
/// plane-strain one, for fibres at any inclination.
#[test]
fn plane_strain_modes_along_x_are_the_plane_analysis() {
    for beta in [0.0, FRAC_PI_4, FRAC_PI_2] {
        let p = Parameters {
            beta,
            ..Parameters::default()
        };
        let plane = StabilityAnalysis::new(&p, Method::Exact).unwrap();
        let oblique = StabilityAnalysis::with_surface(&p, Method::Exact, surface(0.0, 0.0)).unwrap();
        for k in [0.2, 0.6, 1.5] {
            let (a, b) = (
                plane.critical_compression(k).unwrap(),
                oblique.critical_compression(k).unwrap(),
            );
            assert!((a - b).abs() < 1e-11, "beta {beta}, k {k}: plane {a} vs oblique {b}");
        }
    }
}

/// Under a growth load the same holds: with `theta = 0` and `R = 0` the surface's growth is the
/// plane one (`g3 = 1`), so `d_c(k)` is the plane-strain growth's, compressible or not, with
/// the thickness growing or not.
#[test]
fn plane_growth_modes_along_x_are_the_plane_analysis() {
    for (load, incompressible, area_growth) in [
        (Load::Growth, false, false),
        (Load::Growth, true, true),
        (Load::UniformGrowth, false, true),
    ] {
        let p = Parameters {
            beta: 0.5,
            load,
            incompressible,
            area_growth,
            ..Parameters::default()
        };
        let plane = StabilityAnalysis::new(&p, Method::Exact).unwrap();
        let oblique = StabilityAnalysis::with_surface(&p, Method::Exact, surface(0.0, 0.0)).unwrap();
        for k in [0.3, 1.2] {
            let (a, b) = (
                plane.critical_compression(k).unwrap(),
                oblique.critical_compression(k).unwrap(),
            );
            assert!(
                (a - b).abs() < 1e-11,
                "{load:?} {incompressible}: k {k}: plane {a} vs oblique {b}"
            );
        }
    }
}

/// Both layers growing in the surface by `diag(g, 1, g3)` with the sides held are elastically
/// the bilayer compressed to `lambda_1 = 1/g`, `lambda_3 = 1/g3`: the same `Fe`, the same
/// current configuration, only the reference differs (the grown body's is the current one in
/// the surface). So `d_c` in the strain `1 - 1/g` is the compression's, for the wave whose
/// current wave vector is the same: the compression's referential `k (cos theta, sin theta)`
/// divided by `(lambda_1, lambda_3)` component by component.
#[test]
fn uniform_growth_in_the_surface_is_biaxial_compression_of_the_grown_body() {
    for (biaxial, theta, incompressible) in [(1.0, 0.6, false), (0.5, 1.2, false), (1.0, 0.3, true)] {
        let compression = Parameters {
            beta: 0.4,
            psi: 0.3,
            incompressible,
            ..Parameters::default()
        };
        let growth = Parameters {
            load: Load::UniformGrowth,
            ..compression.clone()
        };
        let compressed = StabilityAnalysis::with_surface(&compression, Method::Exact, surface(biaxial, theta)).unwrap();
        for k in [0.4, 1.0] {
            let d_c = compressed.critical_compression(k).unwrap();
            let current = [k * theta.cos() / (1.0 - d_c), k * theta.sin() / (1.0 - biaxial * d_c)];
            let theta_grown = current[1].atan2(current[0]);
            let grown = StabilityAnalysis::with_surface(&growth, Method::Exact, surface(biaxial, theta_grown)).unwrap();
            let d_grown = grown.critical_compression(current[0].hypot(current[1])).unwrap();
            assert!(
                (d_grown - d_c).abs() < 1e-9,
                "R {biaxial} theta {theta}: compression {d_c}, growth {d_grown}"
            );
        }
    }
}

/// Biot: an incompressible neo-Hookean half-space under equibiaxial compression wrinkles at
/// `lambda = x^(1/3)`, `x` the root in (0, 1) of `x^3 + x^2 + 3 x - 1 = 0`, at every `k` and
/// `theta`; a bilayer of one material is that half-space.
#[test]
fn equibiaxial_incompressible_half_space_is_biot() {
    let x =
        crate::numerics::roots::brent("Biot", |x: f64| Ok(x * x * x + x * x + 3.0 * x - 1.0), 0.0, 1.0, 1e-15).unwrap();
    let expected = 1.0 - x.cbrt();
    assert!((expected - 0.33386).abs() < 1e-5, "{expected}");
    let p = Parameters {
        mu_l: 1.0,
        mu_f: 0.0,
        phi_m: 1.0,
        phi_f: 0.0,
        incompressible: true,
        ..Parameters::default()
    };
    for theta in [0.0, 0.7, FRAC_PI_2] {
        let analysis = StabilityAnalysis::with_surface(&p, Method::Exact, surface(1.0, theta)).unwrap();
        for k in [0.3, 2.0] {
            let d_c = analysis.critical_compression(k).unwrap();
            assert!(
                (d_c - expected).abs() < 1e-9,
                "theta {theta}, k {k}: {d_c} vs {expected}"
            );
        }
    }
}

/// A thin stiff incompressible film on a compliant incompressible substrate: the plane-strain
/// critical stress with an equibiaxial strain `eps` giving `sigma = 6 mu eps` (plane strain:
/// 4 mu eps), so `d_c = (1/6) (3 mu_s / mu_l)^(2/3)` and `k0 H = (3 mu_s / mu_l)^(1/3)`.
#[test]
fn equibiaxial_thin_film_law() {
    let ratio = 1000.0;
    let p = Parameters {
        mu_l: ratio,
        mu_f: 0.0,
        phi_m: 1.0,
        phi_f: 0.0,
        incompressible: true,
        ..Parameters::default()
    };
    let mut analysis = StabilityAnalysis::with_surface(&p, Method::Exact, surface(1.0, 0.0)).unwrap();
    analysis.k_range = (0.02, 2.0);
    let onset = analysis.onset().unwrap();
    let (d_c, k0) = ((3.0 / ratio).powf(2.0 / 3.0) / 6.0, (3.0 / ratio).cbrt());
    assert!((onset.d_c / d_c - 1.0).abs() < 0.02, "d_c {} vs {d_c}", onset.d_c);
    assert!((onset.k0 / k0 - 1.0).abs() < 0.02, "k0 {} vs {k0}", onset.k0);
}

/// Without fibres and with equal in-plane compressions nothing sets a direction.
#[test]
fn isotropic_bilayer_under_equibiaxial_compression_has_no_direction() {
    let p = Parameters {
        mu_f: 0.0,
        ..Parameters::default()
    };
    let reference = StabilityAnalysis::with_surface(&p, Method::Exact, surface(1.0, 0.0)).unwrap();
    let d0 = reference.critical_compression(0.5).unwrap();
    for theta in [0.3, 1.1, FRAC_PI_2, 2.5] {
        let d = reference.along(theta).critical_compression(0.5).unwrap();
        assert!((d - d0).abs() < 1e-10, "theta {theta}: {d} vs {d0}");
    }
}

/// The exact and discrete methods agree at an oblique direction with fibres at an oblique
/// azimuth, compressible and incompressible.
#[test]
fn exact_and_discrete_agree_at_oblique_directions_and_fibres() {
    for incompressible in [false, true] {
        let p = Parameters {
            beta: 0.5,
            psi: FRAC_PI_6,
            incompressible,
            ..Parameters::default()
        };
        let s = surface(0.6, 1.0);
        let exact = StabilityAnalysis::with_surface(&p, Method::Exact, s).unwrap();
        let discrete = StabilityAnalysis::with_surface(&p, Method::Discrete(DiscreteOptions::default()), s).unwrap();
        for k in [0.4, 1.2] {
            let (a, b) = (
                exact.critical_compression(k).unwrap(),
                discrete.critical_compression(k).unwrap(),
            );
            assert!(
                (a - b).abs() < 1e-6,
                "incompressible {incompressible}, k {k}: exact {a} vs discrete {b}"
            );
        }
    }
}

/// Continued from a neighbouring parameter set, the onset over directions is the fresh one,
/// or its mirror image about the fibres' projection (`theta -> 2 psi - theta`: the fibre pair
/// is symmetric about the vertical plane through it, and the equibiaxial load in every plane).
#[test]
fn continued_onset_over_directions_matches_a_fresh_search() {
    let analysis = |beta: f64| {
        let p = Parameters {
            beta,
            psi: 0.3,
            ..Parameters::default()
        };
        StabilityAnalysis::with_surface(&p, Method::Exact, surface(1.0, 0.0)).unwrap()
    };
    let previous = analysis(0.2).surface_onset().unwrap();
    for beta in [0.22, 0.26] {
        let fresh = analysis(beta).surface_onset().unwrap();
        let near = analysis(beta).surface_onset_near(&previous).unwrap();
        assert!(
            (fresh.onset.d_c - near.onset.d_c).abs() < 1e-9,
            "beta {beta}: {fresh:?} vs {near:?}"
        );
        let mirror = (2.0 * 0.3 - near.theta0).rem_euclid(std::f64::consts::PI);
        let same = |a: f64, b: f64| (a - b).abs() < 1e-4 || ((a - b).abs() - std::f64::consts::PI).abs() < 1e-4;
        assert!(
            same(fresh.theta0, near.theta0) || same(fresh.theta0, mirror),
            "beta {beta}: {fresh:?} vs {near:?}"
        );
    }
}

/// The 3D margin of an unstrained neo-Hookean layer is its shear modulus (as in plane strain);
/// strongly compressed fibres along X make it negative.
#[test]
fn surface_ellipticity_margin_of_rest_and_of_compressed_fibres() {
    let solid = crate::material::NeoHookean { mu: 1.7, bulk: 40.0 };
    let rest = moduli::SurfaceModuli::at(&solid, [1.0; 3]).unwrap();
    assert!(
        (rest.ellipticity_margin() - 1.7).abs() < 1e-10,
        "{}",
        rest.ellipticity_margin()
    );
    let p = Parameters {
        mu_f: 200.0,
        ..Parameters::default()
    };
    let fibres = crate::material::Bilayer::new(&p).substrate;
    let compressed = moduli::SurfaceModuli::at(&fibres, [0.5, 1.2, 1.0]).unwrap();
    assert!(compressed.ellipticity_margin() < 0.0);
}

/// The closed-form smallest eigenvalue against the iterative symmetric eigensolver: general,
/// diagonal, exactly and nearly double (both the smaller and the larger pair), and triple.
#[test]
fn smallest_eigenvalue_in_closed_form_matches_the_eigensolver() {
    use nalgebra::{Matrix3, Rotation3, Unit, Vector3};
    let rotation = Rotation3::from_axis_angle(&Unit::new_normalize(Vector3::new(0.3, -1.1, 0.7)), 0.9).into_inner();
    for spectrum in [
        [1.0f64, 2.5, -0.7],
        [3.0, 3.0, 7.0],
        [3.0, 3.0 + 1e-9, 7.0],
        [3.0, 3.0 + 1e-5, 7.0],
        [-2.0, 5.0, 5.0],
        [-2.0, 5.0, 5.0 + 1e-8],
        [1.7, 1.7, 1.7 + 1e-12],
        [0.0, 1e-3, 40.0],
    ] {
        let matrix = rotation * Matrix3::from_diagonal(&Vector3::from(spectrum)) * rotation.transpose();
        let matrix = (matrix + matrix.transpose()) * 0.5;
        let expected = matrix.symmetric_eigenvalues().min();
        let scale = spectrum.iter().fold(0.0f64, |s, x| s.max(x.abs()));
        let found = moduli::smallest_eigenvalue(&matrix);
        assert!(
            (found - expected).abs() < 1e-13 * scale,
            "{spectrum:?}: {found} vs {expected}"
        );
        let diagonal = Matrix3::from_diagonal(&Vector3::from(spectrum));
        assert_eq!(
            moduli::smallest_eigenvalue(&diagonal),
            spectrum.iter().copied().fold(f64::INFINITY, f64::min)
        );
    }
}

/// Nearly incompressible tissues, where the transfer matrix of the layer as a whole overflowed:
/// plane-strain modes along X are still the plane analysis, and a soft layer's short waves under
/// equibiaxial compression are Biot's equibiaxial half-space (`1 - x^(1/3)`, as above) in every
/// direction.
#[test]
fn nearly_incompressible_layers_are_answered_in_every_direction() {
    let stiff = Parameters {
        mu_l: 100.0,
        K_l: 1e8,
        K_s: 1e6,
        beta: 0.5,
        ..Parameters::default()
    };
    let plane = StabilityAnalysis::new(&stiff, Method::Exact).unwrap();
    let oblique = StabilityAnalysis::with_surface(&stiff, Method::Exact, surface(0.0, 0.0)).unwrap();
    for k in [0.3, 2.0, 8.0] {
        let (a, b) = (
            plane.critical_compression(k).unwrap(),
            oblique.critical_compression(k).unwrap(),
        );
        assert!((a - b).abs() < 1e-9, "k {k}: plane {a} vs oblique {b}");
    }
    let x =
        crate::numerics::roots::brent("Biot", |x: f64| Ok(x * x * x + x * x + 3.0 * x - 1.0), 0.0, 1.0, 1e-15).unwrap();
    let biot = 1.0 - x.cbrt();
    let soft = Parameters {
        mu_l: 1.2,
        K_l: 1.2e6,
        K_s: 1e6,
        beta: 0.5,
        ..Parameters::default()
    };
    for theta in [0.0, 0.7, FRAC_PI_2] {
        let analysis = StabilityAnalysis::with_surface(&soft, Method::Exact, surface(1.0, theta)).unwrap();
        let d_c = analysis.critical_compression(8.0).unwrap();
        assert!((d_c - biot).abs() < 1e-5, "theta {theta}: {d_c} vs {biot}");
    }
}
