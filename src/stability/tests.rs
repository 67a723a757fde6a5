//! The stability analysis against independent facts: Biot's half-space, thin-film wrinkling
//! asymptotics, the paper's fibre-free check, and agreement of the two solvers.

use super::discrete::DiscreteOptions;
use super::*;
use crate::parameters::Parameters;
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4};

/// A fibre-free bilayer with shear moduli `mu_l`, `mu_s` and bulk/shear ratio `bulk_ratio`.
fn plain_bilayer(mu_l: f64, mu_s: f64, bulk_ratio: f64) -> Parameters {
    Parameters {
        mu_l,
        K_l: bulk_ratio * mu_l,
        mu_s,
        K_s: bulk_ratio * mu_s,
        phi_m: 1.0,
        phi_f: 0.0,
        mu_f: 0.0,
        ..Parameters::default()
    }
}

/// No contrast and no fibres: `d_c(k)` is flat at the half-space value, and the onset says so.
#[test]
fn without_contrast_the_onset_is_flat_at_the_half_space_value() {
    let onset = StabilityAnalysis::new(&plain_bilayer(1.0, 1.0, 3.0), Method::Exact)
        .unwrap()
        .onset()
        .unwrap();
    assert_eq!(onset.minimum, Minimum::Flat, "{onset:?}");
    assert!(onset.k0.is_nan() && onset.wavelength().is_none());
    // The compressible (K = 3 mu) half-space value.
    assert!((onset.d_c - 0.46866).abs() < 1e-5, "{}", onset.d_c);
    let json = serde_json::to_string(&onset).unwrap();
    assert!(
        json.contains(r#""k0":null"#) && json.contains(r#""minimum":"flat""#),
        "{json}"
    );
}

#[test]
fn biot_half_space_is_independent_of_k_and_tends_to_0_5437() {
    // Biot (1963): an incompressible neo-Hookean half-space wrinkles at lambda_1 = 0.5437.
    let analysis = StabilityAnalysis::new(&plain_bilayer(1.0, 1.0, 1e4), Method::Exact).unwrap();
    let values: Vec<f64> = [0.1, 0.5, 1.0, 3.0]
        .iter()
        .map(|&k| analysis.critical_compression(k).unwrap())
        .collect();
    for d in &values {
        assert!((d - values[0]).abs() < 1e-8, "d_c depends on k: {values:?}");
    }
    assert!(
        (1.0 - values[0] - 0.5437).abs() < 2e-3,
        "lambda_c = {}",
        1.0 - values[0]
    );
    // Compressible: still independent of k, and later than the incompressible value.
    let compressible = StabilityAnalysis::new(&plain_bilayer(1.0, 1.0, 3.0), Method::Exact).unwrap();
    let (a, b) = (
        compressible.critical_compression(0.2).unwrap(),
        compressible.critical_compression(2.0).unwrap(),
    );
    assert!((a - b).abs() < 1e-8 && a > values[0], "{a} {b}");
}

#[test]
fn thin_stiff_film_follows_the_asymptotic_wrinkling_law() {
    // Allen; Chen & Hutchinson: k0 H = (3 mu_s/mu_l)^(1/3), d_c = (1/4)(3 mu_s/mu_l)^(2/3).
    let mut previous_error = f64::INFINITY;
    for ratio in [1e3, 1e4] {
        let mut analysis = StabilityAnalysis::new(&plain_bilayer(ratio, 1.0, 3.0), Method::Exact).unwrap();
        analysis.k_range = (0.005, 2.0);
        let onset = analysis.onset().unwrap();
        let k_theory = (3.0 / ratio).cbrt();
        let d_theory = 0.25 * (3.0 / ratio).powf(2.0 / 3.0);
        let (k_err, d_err) = ((onset.k0 / k_theory - 1.0).abs(), (onset.d_c / d_theory - 1.0).abs());
        assert!(k_err < 0.05, "ratio {ratio}: k0 = {} vs {k_theory}", onset.k0);
        assert!(d_err < 0.10, "ratio {ratio}: d_c = {} vs {d_theory}", onset.d_c);
        assert!(k_err + d_err < previous_error, "no improvement with ratio {ratio}");
        previous_error = k_err + d_err;
    }
}

#[test]
fn unloaded_fibres_give_the_papers_onset_wavenumber() {
    // Paper, section 3.1: mu_f = 0 with phi_m = 0.9 gives k0 = 0.5515.
    let p = Parameters {
        mu_f: 0.0,
        ..Parameters::default()
    };
    let onset = StabilityAnalysis::new(&p, Method::Exact).unwrap().onset().unwrap();
    assert!((onset.k0 - 0.5515).abs() < 5e-5, "k0 = {}", onset.k0);
}

#[test]
fn stiff_fibres_across_compression_delay_wrinkling_by_about_half() {
    // Paper, section 3.1: at mu_f = 10, d_c grows by about 50 % from beta = 0 to pi/2.
    let onset = |beta: f64| {
        let p = Parameters {
            beta,
            ..Parameters::default()
        };
        StabilityAnalysis::new(&p, Method::Exact).unwrap().onset().unwrap().d_c
    };
    let growth = onset(FRAC_PI_2) / onset(0.0) - 1.0;
    assert!((0.35..0.65).contains(&growth), "growth {growth}");
}

fn fine_discrete() -> Method {
    Method::Discrete(DiscreteOptions::default())
}

#[test]
fn exact_and_discrete_solvers_agree() {
    for beta in [0.0, 0.3846, FRAC_PI_4, 1.18, FRAC_PI_2] {
        for mu_f in [10.0, 50.0] {
            let p = Parameters {
                beta,
                mu_f,
                ..Parameters::default()
            };
            let exact = StabilityAnalysis::new(&p, Method::Exact).unwrap();
            let discrete = StabilityAnalysis::new(&p, fine_discrete()).unwrap();
            for k in [0.3, 0.55, 1.2] {
                match (exact.critical_compression(k), discrete.critical_compression(k)) {
                    (Ok(a), Ok(b)) => assert!((a - b).abs() < 1e-6 * a, "beta {beta} mu_f {mu_f} k {k}: {a} vs {b}"),
                    // Both find no wrinkling before the loss of ellipticity.
                    (Err(crate::Error::NoRoot { .. }), Err(crate::Error::NoRoot { .. })) => {}
                    (a, b) => panic!("beta {beta} mu_f {mu_f} k {k}: exact {a:?} discrete {b:?}"),
                }
            }
        }
    }
}

#[test]
fn stroh_roots_solve_the_characteristic_quartic() {
    let analysis = StabilityAnalysis::new(
        &Parameters {
            beta: 0.6,
            ..Parameters::default()
        },
        Method::Exact,
    )
    .unwrap();
    for d in [0.0, 0.1, 0.2] {
        let (layer, substrate) = analysis.moduli(d).unwrap();
        for m in [layer, substrate] {
            let n = m.stroh_matrix().map(|x| nalgebra::Complex::new(x, 0.0));
            for p in m.decaying_roots() {
                assert!(p.re > 0.0);
                let shifted = n - nalgebra::Matrix4::identity() * p;
                assert!(
                    shifted.determinant().norm() < 1e-9 * (1.0 + n.norm().powi(4)),
                    "d {d}: p = {p}"
                );
            }
        }
    }
}

#[test]
fn discrete_solver_converges_under_refinement() {
    let p = Parameters {
        beta: FRAC_PI_4,
        ..Parameters::default()
    };
    let exact = StabilityAnalysis::new(&p, Method::Exact)
        .unwrap()
        .critical_compression(0.55)
        .unwrap();
    let errors: Vec<f64> = [(2, 20), (4, 40), (8, 80)]
        .iter()
        .map(|&(layer_elements, substrate_elements)| {
            let options = DiscreteOptions {
                layer_elements,
                substrate_elements,
                depth_decay_lengths: 30.0,
            };
            let analysis = StabilityAnalysis::new(&p, Method::Discrete(options)).unwrap();
            (analysis.critical_compression(0.55).unwrap() - exact).abs()
        })
        .collect();
    // Quadratic elements: the eigenvalue error falls like h^4; demand at least h^3.
    for pair in errors.windows(2) {
        assert!(pair[1] < pair[0] / 8.0, "errors {errors:?}");
    }
}

#[test]
fn dispersion_curve_is_smooth_at_its_minimum() {
    let analysis = StabilityAnalysis::new(&Parameters::default(), Method::Exact).unwrap();
    let onset = analysis.onset().unwrap();
    let h = 1e-3;
    let d = |k: f64| analysis.critical_compression(k).unwrap();
    let (left, mid, right) = (d(onset.k0 - h), d(onset.k0), d(onset.k0 + h));
    assert!((mid - onset.d_c).abs() < 1e-12);
    assert!(left > mid && right > mid, "k0 is not a minimum");
    // Smooth minimum: first difference vanishes to O(h^2), second difference is O(h^2).
    assert!(
        (right - left).abs() < 1e-3 * (left + right - 2.0 * mid).abs().max(1e-12) / h,
        "kink at k0"
    );
    assert!((left + right - 2.0 * mid) / (h * h) < 10.0);
}

#[test]
fn ellipticity_loss_is_reported_for_compressed_stiff_fibres() {
    // Very stiff fibres along the compression: the substrate's fibre energy becomes concave.
    let p = Parameters {
        mu_f: 50.0,
        beta: 0.0,
        ..Parameters::default()
    };
    let analysis = StabilityAnalysis::new(&p, Method::Exact).unwrap();
    if let Some(d) = analysis.ellipticity_loss() {
        let (layer, substrate) = analysis.moduli(d * 0.999).unwrap();
        assert!(ellipticity::ellipticity_margin(&layer).min(ellipticity::ellipticity_margin(&substrate)) > 0.0);
        let (layer, substrate) = analysis.moduli((d * 1.001).min(0.949)).unwrap();
        assert!(ellipticity::ellipticity_margin(&layer).min(ellipticity::ellipticity_margin(&substrate)) <= 0.0);
    }
    // Table 1 defaults stay elliptic up to the onset.
    let onset = StabilityAnalysis::new(&Parameters::default(), Method::Exact)
        .unwrap()
        .onset()
        .unwrap();
    assert!(onset.d_ellipticity_loss.is_none_or(|d| d > onset.d_c));
}

#[test]
fn continued_onset_matches_the_cold_search() {
    let previous = StabilityAnalysis::new(
        &Parameters {
            beta: 0.5,
            ..Parameters::default()
        },
        Method::Exact,
    )
    .unwrap()
    .onset()
    .unwrap();
    let analysis = StabilityAnalysis::new(
        &Parameters {
            beta: 0.55,
            ..Parameters::default()
        },
        Method::Exact,
    )
    .unwrap();
    let (cold, warm) = (analysis.onset().unwrap(), analysis.onset_near(&previous).unwrap());
    assert!(
        (cold.k0 - warm.k0).abs() < 1e-5 && (cold.d_c - warm.d_c).abs() < 1e-12,
        "{cold:?} {warm:?}"
    );
}

#[test]
fn wrinkling_beyond_the_loss_of_ellipticity_is_refused() {
    // Stiff fibres along the compression lose ellipticity at d ~ 0.047: short waves find no
    // bifurcation before it and say so instead of returning a number.
    let p = Parameters {
        mu_f: 50.0,
        ..Parameters::default()
    };
    let analysis = StabilityAnalysis::new(&p, Method::Exact).unwrap();
    let limit = analysis.ellipticity_loss().expect("ellipticity is lost");
    match analysis.critical_compression(1.5) {
        Err(crate::Error::NoRoot { what, .. }) => assert!(what.contains("ellipticity"), "{what}"),
        other => panic!("expected no root before d = {limit}, got {other:?}"),
    }
}

/// The onset of a layer no stiffer than the substrate is the long-wave limit, the substrate's
/// own surface instability: the same value whatever the (soft) layer, as `kH -> 0` makes the
/// layer irrelevant.
#[test]
fn a_soft_layer_has_no_interior_minimum_and_the_substrate_limit() {
    let onset_of = |mu_l: f64| {
        let p = Parameters {
            mu_l,
            K_l: 3.0 * mu_l,
            ..Parameters::default()
        };
        StabilityAnalysis::new(&p, Method::Exact).unwrap().onset().unwrap()
    };
    let (a, b) = (onset_of(1.2), onset_of(1.5));
    for o in [&a, &b] {
        assert_eq!(o.minimum, Minimum::LongWave, "{o:?}");
        assert_eq!(o.k0, 0.0);
        assert_eq!(o.wavelength(), None);
    }
    assert!((a.d_c - b.d_c).abs() < 1e-5, "{} vs {}", a.d_c, b.d_c);
    // The stiff layer of Table 1 sets a wavelength.
    let table1 = StabilityAnalysis::new(&Parameters::default(), Method::Exact)
        .unwrap()
        .onset()
        .unwrap();
    assert_eq!(table1.minimum, Minimum::Interior);
    assert!(table1.d_c < a.d_c);
}

/// A soft, nearly incompressible layer on a compressible substrate: the layer's own surface
/// instability at short waves, i.e. Biot's lambda = 0.5437 of the layer material.
#[test]
fn a_soft_nearly_incompressible_layer_buckles_at_short_waves_at_biot() {
    let p = Parameters {
        mu_l: 0.5,
        K_l: 500.0,
        phi_m: 1.0,
        phi_f: 0.0,
        ..Parameters::default()
    };
    let onset = StabilityAnalysis::new(&p, Method::Exact).unwrap().onset().unwrap();
    assert_eq!(onset.minimum, Minimum::ShortWave, "{onset:?}");
    assert!(onset.k0.is_infinite());
    // K/mu = 1000: within 2e-4 of the incompressible 0.5437.
    assert!((onset.lambda1_c - 0.5437).abs() < 2e-4, "{}", onset.lambda1_c);
}

/// `plain_bilayer` made exactly incompressible.
fn incompressible_bilayer(mu_l: f64, mu_s: f64) -> Parameters {
    Parameters {
        incompressible: true,
        ..plain_bilayer(mu_l, mu_s, 3.0)
    }
}

/// Biot (1963): an incompressible neo-Hookean half-space in plane strain wrinkles at
/// [`biot_compression`] (the root of Biot's cubic), at every `k`.
#[test]
fn exactly_incompressible_half_space_is_biot_at_every_k_with_both_solvers() {
    let d_biot = biot_compression();
    let exact = StabilityAnalysis::new(&incompressible_bilayer(1.0, 1.0), Method::Exact).unwrap();
    for k in [0.1, 0.5, 1.0, 3.0] {
        let d = exact.critical_compression(k).unwrap();
        assert!((d - d_biot).abs() < 1e-7, "k = {k}: {d} vs Biot {d_biot}");
    }
    assert_eq!(exact.onset().unwrap().minimum, Minimum::Flat);
    assert_eq!(
        exact.ellipticity_loss(),
        None,
        "incompressible neo-Hookean stays elliptic"
    );
    let discrete = StabilityAnalysis::new(&incompressible_bilayer(1.0, 1.0), fine_discrete()).unwrap();
    let d = discrete.critical_compression(1.0).unwrap();
    assert!((d - d_biot).abs() < 1e-4, "discrete {d} vs Biot {d_biot}");
}

/// The same law as the compressible film, `k0 H = (3 mu_s/mu_l)^(1/3)` and
/// `d_c = (1/4)(3 mu_s/mu_l)^(2/3)`, within 2 % at `mu_l / mu_s = 10^3`, by both solvers.
#[test]
fn incompressible_thin_film_follows_the_wrinkling_law() {
    let ratio: f64 = 1e3;
    let (k_theory, d_theory) = ((3.0 / ratio).cbrt(), 0.25 * (3.0 / ratio).powf(2.0 / 3.0));
    let mut analysis = StabilityAnalysis::new(&incompressible_bilayer(ratio, 1.0), Method::Exact).unwrap();
    analysis.k_range = (0.005, 2.0);
    let onset = analysis.onset().unwrap();
    assert!(
        (onset.k0 / k_theory - 1.0).abs() < 0.02,
        "k0 = {} vs {k_theory}",
        onset.k0
    );
    assert!(
        (onset.d_c / d_theory - 1.0).abs() < 0.02,
        "d_c = {} vs {d_theory}",
        onset.d_c
    );
    let discrete = StabilityAnalysis::new(&incompressible_bilayer(ratio, 1.0), fine_discrete()).unwrap();
    let d = discrete.critical_compression(onset.k0).unwrap();
    assert!(
        (d / onset.d_c - 1.0).abs() < 1e-3,
        "discrete {d} vs exact {}",
        onset.d_c
    );
}

/// The incompressible formulation is the limit of the compressible one as `K / mu -> inf`
/// (Table 1's contrast and fibres at 45 degrees).
#[test]
fn compressible_moduli_tend_to_the_incompressible_ones() {
    let base = Parameters {
        beta: FRAC_PI_4,
        ..Parameters::default()
    };
    let exact = |p: &Parameters| {
        StabilityAnalysis::new(p, Method::Exact)
            .unwrap()
            .critical_compression(0.6)
            .unwrap()
    };
    let incompressible = exact(&Parameters {
        incompressible: true,
        ..base.clone()
    });
    let gaps: Vec<f64> = [1e3, 1e5]
        .iter()
        .map(|&ratio| {
            let nearly = Parameters {
                K_l: ratio * base.mu_l,
                K_s: ratio * base.mu_s,
                ..base.clone()
            };
            (exact(&nearly) - incompressible).abs()
        })
        .collect();
    assert!(gaps[1] < 1e-4 && gaps[1] < 0.05 * gaps[0], "{gaps:?}");
}

/// Table 1's tissue made nearly incompressible: `K/mu` of both layers `ratio`, contrast `mu_l`,
/// fibres at `beta`.
fn nearly_incompressible(ratio: f64, mu_l: f64, beta: f64) -> Parameters {
    Parameters {
        mu_l,
        K_l: ratio * mu_l,
        K_s: ratio,
        beta,
        ..Parameters::default()
    }
}

/// On a grid of nearly incompressible tissues (K/mu 1e3 to 1e8, contrast 1.2 to 100, fibres
/// along, across and between) the exact method answers everywhere, and its answer is that of
/// independent references: at K/mu = 1e8 the exactly incompressible formulation (another Stroh
/// matrix, with a pressure), at K/mu = 1e3 the discrete method (which locks beyond), and for a
/// short-wave onset Biot's half-space. A sweep's continued search classifies as the cold one.
#[test]
fn the_exact_method_answers_nearly_incompressible_tissues_at_any_contrast() {
    for ratio in [1e3, 1e5, 1e8] {
        for mu_l in [1.2, 10.0, 100.0] {
            for beta in [0.0, 0.5, 1.0, FRAC_PI_2] {
                let p = nearly_incompressible(ratio, mu_l, beta);
                let case = format!("K/mu = {ratio:e}, mu_l = {mu_l}, beta = {beta}");
                let exact = StabilityAnalysis::new(&p, Method::Exact).unwrap().onset().unwrap();
                if ratio == 1e8 {
                    let incompressible = Parameters {
                        incompressible: true,
                        ..p.clone()
                    };
                    let reference = StabilityAnalysis::new(&incompressible, Method::Exact)
                        .unwrap()
                        .onset()
                        .unwrap();
                    assert_eq!(exact.minimum, reference.minimum, "{case}");
                    assert!(
                        (exact.d_c - reference.d_c).abs() < 1e-6,
                        "{case}: {exact:?} vs {reference:?}"
                    );
                }
                if ratio == 1e3 && exact.minimum == Minimum::Interior {
                    let discrete = StabilityAnalysis::new(&p, Method::Discrete(DiscreteOptions::default()))
                        .unwrap()
                        .onset()
                        .unwrap();
                    assert!(
                        (exact.d_c - discrete.d_c).abs() < 1e-5,
                        "{case}: {exact:?} vs {discrete:?}"
                    );
                }
                if exact.minimum == Minimum::ShortWave && ratio >= 1e5 {
                    assert!((exact.d_c - biot_compression()).abs() < 1e-5, "{case}: {exact:?}");
                }
                // As `sweep` reaches it: continued from the onset at a neighbouring beta.
                let neighbour = StabilityAnalysis::new(&nearly_incompressible(ratio, mu_l, beta + 0.05), Method::Exact)
                    .unwrap()
                    .onset()
                    .unwrap();
                let continued = StabilityAnalysis::new(&p, Method::Exact)
                    .unwrap()
                    .onset_near(&neighbour)
                    .unwrap();
                assert_eq!(continued.minimum, exact.minimum, "{case}");
                assert!(
                    (continued.d_c - exact.d_c).abs() < 1e-7,
                    "{case}: {continued:?} vs {exact:?}"
                );
            }
        }
    }
}

/// Where the transfer matrix of the layer as a whole overflowed (K_l = 1e8: `non-finite value
/// in the bifurcation determinant`), both methods agree.
#[test]
fn a_stiff_nearly_incompressible_layer_has_the_discrete_methods_onset() {
    let p = Parameters {
        mu_l: 100.0,
        K_l: 1e8,
        K_s: 1e6,
        beta: 0.5,
        ..Parameters::default()
    };
    let exact = StabilityAnalysis::new(&p, Method::Exact).unwrap().onset().unwrap();
    let discrete = StabilityAnalysis::new(&p, Method::Discrete(DiscreteOptions::default()))
        .unwrap()
        .onset()
        .unwrap();
    assert_eq!(exact.minimum, Minimum::Interior);
    assert!((exact.d_c - discrete.d_c).abs() < 1e-5, "{exact:?} vs {discrete:?}");
    assert!(
        (exact.k0 - discrete.k0).abs() < 1e-2 * exact.k0,
        "{exact:?} vs {discrete:?}"
    );
}
