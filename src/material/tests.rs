//! Stress and tangent against central finite differences, symmetry, objectivity.

use super::*;
use crate::parameters::Parameters;

/// A small deterministic generator (xorshift) so the tests need no extra crate.
struct Rng(u64);
impl Rng {
    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        lo + (hi - lo) * (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Random deformation gradients with J > 0, including strong compression.
fn sample_gradients() -> Vec<Tensor2> {
    let mut rng = Rng(0x9e3779b97f4a7c15);
    let (c, s) = (0.3f64.cos(), 0.3f64.sin());
    let rotated = |a: f64, b: f64| [c * a, -s * b, s * a, c * b];
    let mut out = vec![
        [0.55, 0.0, 0.0, 1.6],
        [0.5, 0.3, -0.2, 1.9],
        [1.0, 0.0, 0.0, 1.0],
        // In-plane stretches equal, nearly equal, and either side of the series' threshold.
        [0.7, 0.0, 0.0, 0.7],
        [1.0 + 1e-6, 0.0, 0.0, 1.0],
        rotated(1.01, 1.0),
        rotated(1.0, 1.05),
        [0.8, 1e-4, 0.0, 0.8],
    ];
    while out.len() < 40 {
        let f = [
            rng.uniform(0.4, 1.4),
            rng.uniform(-0.5, 0.5),
            rng.uniform(-0.5, 0.5),
            rng.uniform(0.4, 2.0),
        ];
        if jacobian(&f) > 0.2 {
            out.push(f);
        }
    }
    out
}

pub(super) fn materials() -> Vec<(String, Tissue)> {
    let mut list = Vec::new();
    for beta in [0.0, std::f64::consts::FRAC_PI_4, std::f64::consts::FRAC_PI_2, 1.1] {
        for (lambda_f, tension_only) in [(1.0, false), (0.9, false), (1.0, true)] {
            let p = Parameters {
                beta,
                lambda_f,
                tension_only,
                ..Parameters::default()
            };
            let b = Bilayer::new(&p);
            list.push((
                format!("substrate beta={beta} lambda_f={lambda_f} tension_only={tension_only}"),
                b.substrate_tissue(),
            ));
            list.push(("layer".into(), b.layer_tissue()));
        }
    }
    let oblique = Bilayer::new(&Parameters {
        beta: 0.5,
        psi: 0.7,
        ..Parameters::default()
    });
    list.push(("substrate beta=0.5 psi=0.7".into(), oblique.substrate_tissue()));
    for (name, settings) in other_laws() {
        let mut p = Parameters {
            beta: 0.6,
            ..Parameters::default()
        };
        for s in settings {
            p.set(s).unwrap();
        }
        p.validate().unwrap();
        let b = Bilayer::new(&p);
        list.push((format!("{name} substrate"), b.substrate_tissue()));
        list.push((format!("{name} layer"), b.layer_tissue()));
    }
    list
}

/// Laws besides the paper's, as `--set` would give them (to layer and substrate alike).
pub(super) fn other_laws() -> Vec<(&'static str, Vec<&'static str>)> {
    vec![
        (
            "Mooney-Rivlin",
            vec![
                "layer.law=mooney_rivlin",
                "layer.c1=3",
                "layer.c2=2",
                "substrate.law=mooney_rivlin",
                "substrate.c1=0.3",
                "substrate.c2=0.2",
            ],
        ),
        (
            "Ogden alpha=-25",
            vec![
                "layer.law=ogden",
                "layer.alpha=-25",
                "substrate.law=ogden",
                "substrate.alpha=-25",
            ],
        ),
        (
            "Ogden alpha=5",
            vec![
                "layer.law=ogden",
                "layer.alpha=5",
                "substrate.law=ogden",
                "substrate.alpha=5",
            ],
        ),
        (
            "Ogden 3 terms",
            vec![
                "layer.law=ogden",
                "layer.mu=[6, 3, 1]",
                "layer.alpha=[1.3, 5, -2]",
                "substrate.law=ogden",
                "substrate.mu=[0.5,0.5]",
                "substrate.alpha=[-20, 3]",
            ],
        ),
        (
            "Gent",
            vec!["layer.law=gent", "layer.jm=20", "substrate.law=gent", "substrate.jm=20"],
        ),
        (
            "HGO",
            vec!["fibres.law=hgo", "fibres.k1=5", "fibres.k2=2", "fibres.kappa=0.1"],
        ),
        (
            "HGO tension-only",
            vec![
                "fibres.law=hgo",
                "fibres.k1=5",
                "fibres.k2=0.5",
                "fibres.kappa=0.05",
                "tension_only=true",
            ],
        ),
        ("HGO k2=0", vec!["fibres.law=hgo", "fibres.k1=5", "fibres.k2=0"]),
    ]
}

/// Whether a tension-only fibre sits at its kink `I4 = lambda_f^2`, where `A` jumps.
fn at_fibre_kink(m: &Tissue, f: &Tensor2) -> bool {
    match m {
        Tissue::Substrate(s) => s.energy.fibres.iter().any(|fam| fam.near_kink(f, 1e-4)),
        Tissue::Layer(_) => false,
    }
}

fn relative_error(a: f64, b: f64, scale: f64) -> f64 {
    (a - b).abs() / scale.max(1e-300)
}

#[test]
fn stress_is_the_derivative_of_the_energy() {
    let h = 1e-6;
    for (name, m) in materials() {
        for f in sample_gradients() {
            let p = m.first_piola(&f).unwrap();
            let scale = p.iter().fold(1.0f64, |s, x| s.max(x.abs()));
            for a in 0..4 {
                let (mut fp, mut fm) = (f, f);
                fp[a] += h;
                fm[a] -= h;
                let fd = (m.energy(&fp).unwrap() - m.energy(&fm).unwrap()) / (2.0 * h);
                let err = relative_error(p[a], fd, scale);
                assert!(err < 1e-6, "{name} F={f:?} component {a}: P={} fd={fd} err={err}", p[a]);
            }
        }
    }
}

#[test]
fn tangent_is_the_derivative_of_the_stress_and_major_symmetric() {
    let h = 1e-6;
    for (name, m) in materials() {
        for f in sample_gradients().into_iter().filter(|f| !at_fibre_kink(&m, f)) {
            let r = m.response(&f).unwrap();
            let scale = r.tangent.iter().flatten().fold(1.0f64, |s, x| s.max(x.abs()));
            assert_eq!(r.stress, m.first_piola(&f).unwrap().map(|x| x), "{name}");
            for b in 0..4 {
                let (mut fp, mut fm) = (f, f);
                fp[b] += h;
                fm[b] -= h;
                let (pp, pm) = (m.first_piola(&fp).unwrap(), m.first_piola(&fm).unwrap());
                for a in 0..4 {
                    let fd = (pp[a] - pm[a]) / (2.0 * h);
                    let err = relative_error(r.tangent[a][b], fd, scale);
                    assert!(err < 1e-6, "{name} F={f:?} A[{a}][{b}]={} fd={fd}", r.tangent[a][b]);
                    let asym = relative_error(r.tangent[a][b], r.tangent[b][a], scale);
                    assert!(asym < 1e-12, "{name}: A not major symmetric");
                }
            }
        }
    }
}

#[test]
fn energy_is_frame_indifferent() {
    for (name, m) in materials() {
        for f in sample_gradients() {
            for angle in [0.3, 1.7, -2.5] {
                let (c, s) = (f64::cos(angle), f64::sin(angle));
                let qf = [
                    c * f[0] - s * f[2],
                    c * f[1] - s * f[3],
                    s * f[0] + c * f[2],
                    s * f[1] + c * f[3],
                ];
                let (w, wq) = (m.energy(&f).unwrap(), m.energy(&qf).unwrap());
                assert!((w - wq).abs() <= 1e-12 * w.abs().max(1.0), "{name}: W(QF) != W(F)");
            }
        }
    }
}

#[test]
fn reference_state_is_stress_free_without_prestretch() {
    let identity = [1.0, 0.0, 0.0, 1.0];
    for (name, m) in materials().into_iter().filter(|(n, _)| !n.contains("lambda_f=0.9")) {
        let p = m.first_piola(&identity).unwrap();
        let sigma = m.cauchy(&identity).unwrap();
        assert!(
            p.iter().chain(sigma.iter()).all(|x| x.abs() < 1e-14),
            "{name}: {p:?} {sigma:?}"
        );
        assert!(m.energy(&identity).unwrap().abs() < 1e-14);
    }
}

#[test]
fn neo_hookean_cauchy_stress_matches_closed_form() {
    // sigma = mu J^(-5/3) (b - I1/3 I) + K ln J / J I for W = mu/2 (Ibar1 - 3) + K/2 (ln J)^2.
    let m = NeoHookean { mu: 1.3, bulk: 4.1 };
    for f in sample_gradients() {
        let j = jacobian(&f);
        let b = [
            f[0] * f[0] + f[1] * f[1],
            f[0] * f[2] + f[1] * f[3],
            f[2] * f[2] + f[3] * f[3],
            1.0,
        ];
        let i1 = b[0] + b[2] + 1.0;
        let pressure = m.bulk * j.ln() / j;
        let expected = [
            m.mu * j.powf(-5.0 / 3.0) * (b[0] - i1 / 3.0) + pressure,
            m.mu * j.powf(-5.0 / 3.0) * b[1],
            m.mu * j.powf(-5.0 / 3.0) * (b[2] - i1 / 3.0) + pressure,
            m.mu * j.powf(-5.0 / 3.0) * (1.0 - i1 / 3.0) + pressure,
        ];
        let sigma = m.cauchy(&f).unwrap();
        for a in 0..4 {
            assert!(
                (sigma[a] - expected[a]).abs() < 1e-12 * (1.0 + expected[a].abs()),
                "{sigma:?} {expected:?}"
            );
        }
    }
}

#[test]
fn inverted_deformation_is_an_error_not_a_nan() {
    let m = Bilayer::new(&Parameters::default()).substrate_tissue();
    for f in [[1.0, 0.0, 0.0, -0.5], [0.0, 0.0, 0.0, 1.0], [1.0, 2.0, 1.0, 2.0]] {
        assert!(matches!(m.energy(&f), Err(Error::NonPositiveJacobian { .. })));
        assert!(m.response(&f).is_err());
        assert!(m.first_piola(&f).is_err());
        assert!(m.cauchy(&f).is_err());
    }
}

#[test]
fn tension_only_fibres_are_unloaded_in_compression() {
    let p = Parameters {
        tension_only: true,
        mu_f: 50.0,
        ..Parameters::default()
    };
    let Fibre::Quadratic(fibres) = Bilayer::new(&p).substrate.energy.fibres[0] else {
        panic!("the paper's fibres are quadratic")
    };
    assert_eq!(fibres.energy(&[0.8, 0.0, 0.0, 1.2]).unwrap(), 0.0);
    assert!(fibres.energy(&[1.1, 0.0, 0.0, 0.9]).unwrap() > 0.0);
}

#[test]
fn closed_forms_equal_automatic_differentiation_of_the_energy() {
    let mut list = materials();
    let stiff = Parameters {
        K_l: 1e6 * Parameters::default().mu_l,
        K_s: 1e6,
        ..Parameters::default()
    };
    list.push((
        "nearly incompressible substrate".into(),
        Bilayer::new(&stiff).substrate_tissue(),
    ));
    list.push((
        "nearly incompressible layer".into(),
        Bilayer::new(&stiff).layer_tissue(),
    ));
    for (name, m) in list {
        for f in sample_gradients().into_iter().filter(|f| !at_fibre_kink(&m, f)) {
            let (closed, ad) = (m.plane_response(&f), differentiated_response(&m, &f));
            let scale = ad.tangent.iter().flatten().fold(1.0f64, |s, x| s.max(x.abs()));
            assert!(
                relative_error(closed.energy, ad.energy, ad.energy.abs().max(1.0)) < 1e-13,
                "{name}: W"
            );
            for a in 0..4 {
                assert!(
                    relative_error(closed.stress[a], ad.stress[a], scale) < 1e-13,
                    "{name}: P[{a}]"
                );
                for b in 0..4 {
                    let err = relative_error(closed.tangent[a][b], ad.tangent[a][b], scale);
                    assert!(
                        err < 1e-13,
                        "{name} F={f:?}: A[{a}][{b}] {} vs {}",
                        closed.tangent[a][b],
                        ad.tangent[a][b]
                    );
                }
            }
            let (w, p) = m.plane_stress(&f);
            assert_eq!((w, p), (closed.energy, closed.stress), "{name}: stress-only path");
        }
    }
}
