//! The laws besides the paper's against independent facts: their reductions to neo-Hookean
//! and to isotropy, and closed-form stress-stretch curves derived by hand. (Finite-difference,
//! automatic-differentiation and objectivity checks of every law are in `tests.rs`.)

use super::*;
use crate::parameters::Parameters;
use std::f64::consts::FRAC_PI_3;

/// A few gradients: identity, equal stretches, shear, strong compression and stretch.
fn gradients() -> Vec<Tensor2> {
    vec![
        [1.0, 0.0, 0.0, 1.0],
        [0.8, 0.0, 0.0, 0.8],
        [1.0, 0.3, 0.0, 1.0],
        [0.55, 0.1, -0.05, 1.6],
        [1.4, -0.2, 0.3, 0.9],
    ]
}

fn assert_same_response(a: &Response, b: &Response, tolerance: f64, what: &str) {
    let scale = b.tangent.iter().flatten().fold(1.0f64, |s, x| s.max(x.abs()));
    assert!(
        (a.energy - b.energy).abs() <= tolerance * scale,
        "{what}: W {} vs {}",
        a.energy,
        b.energy
    );
    for i in 0..4 {
        assert!((a.stress[i] - b.stress[i]).abs() <= tolerance * scale, "{what}: P[{i}]");
        for j in 0..4 {
            let (x, y) = (a.tangent[i][j], b.tangent[i][j]);
            assert!((x - y).abs() <= tolerance * scale, "{what}: A[{i}][{j}] {x} vs {y}");
        }
    }
}

#[test]
fn one_term_ogden_with_alpha_2_mooney_rivlin_without_c2_and_gent_without_limit_are_neo_hookean() {
    let neo = NeoHookean { mu: 10.0, bulk: 30.0 };
    let ogden = Ogden::new(&[(10.0, 2.0)], 30.0);
    let mooney = MooneyRivlin {
        c1: 5.0,
        c2: 0.0,
        bulk: 30.0,
    };
    let gent = Gent {
        mu: 10.0,
        jm: 1e9,
        bulk: 30.0,
    };
    for f in gradients() {
        let expected = neo.response(&f).unwrap();
        assert_same_response(&ogden.response(&f).unwrap(), &expected, 1e-13, "Ogden alpha = 2");
        assert_same_response(&mooney.response(&f).unwrap(), &expected, 1e-13, "Mooney-Rivlin c2 = 0");
        // Gent differs from neo-Hookean by O((Ibar1 - 3) / Jm).
        assert_same_response(&gent.response(&f).unwrap(), &expected, 1e-8, "Gent Jm = 1e9");
    }
}

#[test]
fn hgo_fibres_with_kappa_one_third_are_isotropic_and_stiffen_as_4_k1_along_the_fibre() {
    let family = |beta: f64, kappa: f64| HgoFamily {
        k1: 5.0,
        k2: 2.0,
        kappa,
        direction: [beta.cos(), beta.sin(), 0.0],
        tension_only: false,
    };
    for f in gradients() {
        let reference = family(0.0, 1.0 / 3.0).response(&f).unwrap();
        for beta in [0.4, FRAC_PI_3, 2.0] {
            assert_same_response(
                &family(beta, 1.0 / 3.0).response(&f).unwrap(),
                &reference,
                1e-13,
                "kappa = 1/3",
            );
        }
    }
    // At F = I, E = 0: A = k1 dE/dF (x) dE/dF, dE/dF = 2 N (x) N; along N = e1, A_1111 = 4 k1.
    let a = family(0.0, 0.0).response(&[1.0, 0.0, 0.0, 1.0]).unwrap().tangent;
    for (i, row) in a.iter().enumerate() {
        for (j, &x) in row.iter().enumerate() {
            let expected = if i == 0 && j == 0 { 4.0 * 5.0 } else { 0.0 };
            assert!((x - expected).abs() < 1e-12, "A[{i}][{j}] = {x}");
        }
    }
    // Tension-only fibres carry nothing while E < 0.
    let slack = HgoFamily {
        tension_only: true,
        ..family(0.0, 0.1)
    };
    assert_eq!(slack.energy(&[0.9, 0.0, 0.0, 1.0]).unwrap(), 0.0);
    assert!(slack.energy(&[1.1, 0.0, 0.0, 1.0]).unwrap() > 0.0);
}

/// Plane-strain uniaxial tension and compression of the incompressible Ogden and Gent laws,
/// `F = diag(lambda, 1/lambda)`: on this isochoric path
/// `sigma_11 - sigma_22 = lambda P_11 - P_22 / lambda` equals, by hand,
/// `sum_p 2 mu_p / alpha_p (lambda^alpha_p - lambda^-alpha_p)` (Ogden) and
/// `mu (lambda^2 - lambda^-2) / (1 - (lambda^2 + lambda^-2 - 2) / Jm)` (Gent).
#[test]
fn plane_strain_stress_stretch_curves_of_ogden_and_gent_are_their_formulas() {
    let pairs = [(0.6, -25.0), (0.3, 5.0), (0.1, 2.0)];
    let ogden = Ogden::new(&pairs, 0.0);
    let gent = Gent {
        mu: 1.0,
        jm: 5.0,
        bulk: 0.0,
    };
    for lambda in [0.45, 0.6, 0.8, 0.97, 1.0, 1.03, 1.3, 1.7] {
        let f = [lambda, 0.0, 0.0, 1.0 / lambda];
        let difference = |p: Tensor2| lambda * p[0] - p[3] / lambda;
        let expected: f64 = pairs
            .iter()
            .map(|&(mu, alpha)| 2.0 * mu / alpha * (lambda.powf(alpha) - lambda.powf(-alpha)))
            .sum();
        let got = difference(ogden.first_piola(&f).unwrap());
        assert!(
            (got - expected).abs() < 1e-11 * expected.abs().max(1.0),
            "Ogden lambda = {lambda}: {got} vs {expected}"
        );
        let l2 = lambda * lambda;
        let expected = (l2 - 1.0 / l2) / (1.0 - (l2 + 1.0 / l2 - 2.0) / gent.jm);
        let got = difference(gent.first_piola(&f).unwrap());
        assert!(
            (got - expected).abs() < 1e-12 * expected.abs().max(1.0),
            "Gent lambda = {lambda}: {got} vs {expected}"
        );
    }
}

#[test]
fn gent_beyond_its_limit_is_an_error_not_a_nan() {
    let gent = Gent {
        mu: 1.0,
        jm: 0.5,
        bulk: 3.0,
    };
    let f = [2.0, 0.0, 0.0, 0.5];
    assert!(matches!(gent.energy(&f), Err(Error::BeyondExtensibility { .. })));
    assert!(gent.response(&f).is_err() && gent.cauchy(&f).is_err());
    assert!(gent.energy(&[1.1, 0.0, 0.0, 1.0]).unwrap().is_finite());
}

#[test]
fn parameters_build_the_laws_they_name_and_keep_table_1_by_default() {
    let table_1 = Bilayer::new(&Parameters::default());
    assert!(matches!(
        table_1.layer.energy,
        Matrix::NeoHookean(NeoHookean { mu: 10.0, bulk: 30.0 })
    ));
    assert!(matches!(table_1.substrate.energy.fibres[0], Fibre::Quadratic(_)));
    for (name, settings) in super::tests::other_laws() {
        let mut p = Parameters::default();
        for s in &settings {
            p.set(s).unwrap();
        }
        p.validate().unwrap();
        let b = Bilayer::new(&p);
        // The flat shear moduli are the laws' own.
        assert!((b.layer.energy.shear_modulus() - p.mu_l).abs() < 1e-12, "{name}");
        assert!(
            (b.substrate.energy.matrix.shear_modulus() - p.mu_s).abs() < 1e-12,
            "{name}"
        );
        let round_trip = Parameters::from_toml_str(&p.to_toml()).unwrap();
        assert_eq!(round_trip, p, "{name}: {}", p.to_toml());
    }
}

/// The series used for nearly equal stretches and the closed form agree, with their first and
/// second derivatives, on both sides of the switch between them (`delta^2 / m^2 = 1e-2`).
#[test]
fn ogden_stretch_sum_is_smooth_across_the_switch_to_its_series() {
    use nalgebra::SVector;
    use num_dual::{hessian, Dual2SVec64};
    let closed = |t: Dual2SVec64<2>, q: Dual2SVec64<2>, a: f64| {
        let m = t * 0.5;
        let delta = (m * m - q * q).sqrt();
        (m + delta).powf(a) + (m - delta).powf(a)
    };
    for a in [-12.5, -2.5, 0.65, 2.5, 50.0] {
        for gap in [0.5e-2, 0.99e-2, 1.01e-2, 2e-2] {
            // m = 1, delta^2 = gap: t = 2, q = sqrt(1 - gap).
            let x = SVector::from([2.0, (1.0 - gap).sqrt()]);
            let (w, g, h) = hessian(
                |v: SVector<Dual2SVec64<2>, 2>| isotropic::principal_power_sum(v[0], v[1], a),
                &x,
            );
            let (w0, g0, h0) = hessian(|v: SVector<Dual2SVec64<2>, 2>| closed(v[0], v[1], a), &x);
            // To the closed form's own rounding: its second derivatives cancel to eps (m/delta)^2.
            let rounding = 100.0 * f64::EPSILON / gap;
            let close = |x: f64, y: f64, scale: f64| (x - y).abs() <= rounding * scale.max(y.abs());
            assert!(close(w, w0, 1.0), "a = {a}, gap = {gap}: {w} vs {w0}");
            for i in 0..2 {
                assert!(close(g[i], g0[i], g0.abs().max()), "a = {a}, gap = {gap}: dS[{i}]");
                for j in 0..2 {
                    assert!(
                        close(h[(i, j)], h0[(i, j)], h0.abs().max()),
                        "a = {a}, gap = {gap}: d2S[{i}][{j}] {} vs {}",
                        h[(i, j)],
                        h0[(i, j)]
                    );
                }
            }
        }
    }
}

/// Full 3x3 gradients: general, equibiaxial (two stretches equal), isotropic (three equal),
/// nearly isotropic, each rotated so that no principal axis is a coordinate axis.
fn full_gradients() -> Vec<[f64; 9]> {
    let rotation = |a: f64, b: f64| {
        let (ca, sa, cb, sb) = (a.cos(), a.sin(), b.cos(), b.sin());
        // R_z(a) R_x(b).
        [ca, -sa * cb, sa * sb, sa, ca * cb, -ca * sb, 0.0, sb, cb]
    };
    let times = |p: &[f64; 9], q: &[f64; 9]| -> [f64; 9] {
        std::array::from_fn(|k| (0..3).map(|l| p[3 * (k / 3) + l] * q[3 * l + k % 3]).sum())
    };
    let diagonal = |a: f64, b: f64, c: f64| [a, 0.0, 0.0, 0.0, b, 0.0, 0.0, 0.0, c];
    let r = rotation(0.4, 1.1);
    let r2 = rotation(-0.7, 0.3);
    let mut list = vec![
        times(&r, &times(&diagonal(0.7, 1.3, 1.05), &r2)),
        times(&r, &times(&diagonal(0.8, 1.45, 0.8), &r2)),
        times(&r, &diagonal(0.9, 0.9, 0.9)),
        times(&r, &times(&diagonal(1.0, 1.0 + 1e-4, 1.0 - 2e-4), &r2)),
        times(&r, &times(&diagonal(1.0, 1.0 + 3e-3, 1.0 - 1e-3), &r2)),
        [0.9, 0.2, -0.1, 0.05, 1.2, 0.15, -0.2, 0.1, 0.85],
    ];
    list.push(diagonal(0.6, 1.5, 0.6));
    list
}

/// The closed-form full 3x3 responses (neo-Hookean, quadratic fibres and the tissues built of
/// them) against hyper-dual differentiation of the same energy.
#[test]
fn closed_full_responses_match_the_differentiated_energy() {
    for (name, m) in super::tests::materials() {
        for f in full_gradients() {
            let (closed, differentiated) = (m.response_3d(&f), differentiated_full_response(&m, &f));
            let scale = differentiated
                .tangent
                .iter()
                .flatten()
                .fold(1.0f64, |s, x| s.max(x.abs()));
            assert!(
                (closed.energy - differentiated.energy).abs() < 1e-13 * scale,
                "{name}: W"
            );
            for a in 0..9 {
                let (x, y) = (closed.stress[a], differentiated.stress[a]);
                assert!((x - y).abs() < 1e-13 * scale, "{name} F={f:?}: P[{a}] {x} vs {y}");
                for b in 0..9 {
                    let (x, y) = (closed.tangent[a][b], differentiated.tangent[a][b]);
                    assert!((x - y).abs() < 1e-12 * scale, "{name} F={f:?}: A[{a}][{b}] {x} vs {y}");
                }
            }
        }
    }
}

/// Every law on the full 3x3 gradient: its hyper-dual stress and tangent against central
/// differences of its energy and stress, frame indifference, and plane strain as its
/// restriction (the plane fast path against the full tangent's in-plane block).
#[test]
fn every_law_on_the_full_gradient_is_differentiable_objective_and_restricts_to_plane_strain() {
    let h = 1e-6;
    for (name, m) in super::tests::materials() {
        for f in full_gradients() {
            let r = full_response(&m, &f).unwrap();
            let scale = r.tangent.iter().flatten().fold(1.0f64, |s, x| s.max(x.abs()));
            for b in 0..9 {
                let (mut fp, mut fm) = (f, f);
                fp[b] += h;
                fm[b] -= h;
                let (rp, rm) = (full_response(&m, &fp).unwrap(), full_response(&m, &fm).unwrap());
                let fd = (rp.energy - rm.energy) / (2.0 * h);
                assert!(
                    (r.stress[b] - fd).abs() < 1e-6 * scale,
                    "{name} F={f:?}: P[{b}] {} vs {fd}",
                    r.stress[b]
                );
                for a in 0..9 {
                    let fd = (rp.stress[a] - rm.stress[a]) / (2.0 * h);
                    assert!(
                        (r.tangent[a][b] - fd).abs() < 1e-6 * scale,
                        "{name} F={f:?}: A[{a}][{b}] {} vs {fd}",
                        r.tangent[a][b]
                    );
                }
            }
            // W(Q F) = W(F) for a rotation about a skew axis.
            let (c, s) = (0.8f64.cos(), 0.8f64.sin());
            let q = [c, 0.0, s, 0.0, 1.0, 0.0, -s, 0.0, c];
            let qf: [f64; 9] = std::array::from_fn(|k| (0..3).map(|l| q[3 * (k / 3) + l] * f[3 * l + k % 3]).sum());
            let w = full_response(&m, &qf).unwrap().energy;
            assert!(
                (w - r.energy).abs() <= 1e-12 * r.energy.abs().max(1.0),
                "{name}: W(QF) {w} vs {}",
                r.energy
            );
        }
        for f in [[1.0, 0.0, 0.0, 1.0], [0.8, 0.0, 0.0, 0.8], [0.7, 0.2, -0.1, 1.3]] {
            let plane = m.response(&f).unwrap();
            let full = m.full(&plane_gradient(&f, 1.0)).unwrap();
            let index = [0, 1, 3, 4];
            let scale = plane.tangent.iter().flatten().fold(1.0f64, |s, x| s.max(x.abs()));
            assert!((plane.energy - full.energy).abs() < 1e-13 * scale, "{name}: W");
            for a in 0..4 {
                assert!(
                    (plane.stress[a] - full.stress[index[a]]).abs() < 1e-12 * scale,
                    "{name}: P[{a}]"
                );
                for b in 0..4 {
                    let (x, y) = (plane.tangent[a][b], full.tangent[index[a]][index[b]]);
                    assert!((x - y).abs() < 1e-12 * scale, "{name} F={f:?}: A[{a}][{b}] {x} vs {y}");
                }
            }
        }
    }
}
