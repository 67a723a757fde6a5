use super::*;
use crate::fem::element::{self, tests::distorted, NODES};
use crate::material::Bilayer;
use crate::parameters::Parameters;
use nalgebra::{DMatrix, SymmetricEigen};

/// A nearly incompressible fibre-reinforced substrate (`K_s = 50 mu_s`).
fn substrate() -> Tissue {
    let p = Parameters {
        beta: 0.6,
        lambda_f: 0.9,
        K_s: 50.0,
        ..Parameters::default()
    };
    Bilayer::new(&p).substrate_tissue()
}

fn mixed_on_distorted(tissue: &Tissue) -> (ElementGeometry, MixedElement, ElementVector) {
    let (nodes, u) = distorted();
    let geometry = ElementGeometry::new(&nodes).unwrap();
    let mixed = MixedElement::new(&geometry, tissue);
    (geometry, mixed, u)
}

#[test]
fn condensed_tangent_matches_central_differences_of_the_force() {
    let (geometry, mixed, u) = mixed_on_distorted(&substrate());
    let mut k = [[0.0; DOFS]; DOFS];
    mixed.evaluate(&geometry, &u, Some(&mut k)).unwrap();
    let h = 1e-6;
    let (mut worst, mut scale) = (0.0f64, 0.0f64);
    for j in 0..DOFS {
        let force_at = |s: f64| {
            let mut v = u;
            v[j] += s * h;
            mixed.evaluate(&geometry, &v, None).unwrap().state.force
        };
        let (plus, minus) = (force_at(1.0), force_at(-1.0));
        for i in 0..DOFS {
            worst = worst.max(((plus[i] - minus[i]) / (2.0 * h) - k[i][j]).abs());
            scale = scale.max(k[i][j].abs());
        }
    }
    assert!(worst <= 1e-7 * scale, "{worst} vs {scale}");
}

#[test]
fn force_is_the_gradient_of_the_condensed_energy() {
    let (geometry, mixed, u) = mixed_on_distorted(&substrate());
    let force = mixed.evaluate(&geometry, &u, None).unwrap().state.force;
    let h = 1e-6;
    for j in 0..DOFS {
        let energy_at = |s: f64| {
            let mut v = u;
            v[j] += s * h;
            mixed.evaluate(&geometry, &v, None).unwrap().state.energy
        };
        let fd = (energy_at(1.0) - energy_at(-1.0)) / (2.0 * h);
        assert!(
            (fd - force[j]).abs() < 1e-6 * (1.0 + force[j].abs()),
            "{j}: {fd} vs {}",
            force[j]
        );
    }
}

/// Under a uniform `F` the projection of `ln J` is exact, so the mixed element's energy, force
/// and pressure are the displacement element's and `K ln J`.
#[test]
fn homogeneous_deformation_gives_the_displacement_element_s_energy_and_pressure() {
    let tissue = substrate();
    let (nodes, _) = distorted();
    let geometry = ElementGeometry::new(&nodes).unwrap();
    let mixed = MixedElement::new(&geometry, &tissue);
    let f = [0.83, 0.11, -0.07, 1.12];
    let u: ElementVector = std::array::from_fn(|i| {
        let (x, c) = (nodes[i / 2], i % 2);
        (f[2 * c] - if c == 0 { 1.0 } else { 0.0 }) * x[0] + (f[2 * c + 1] - if c == 1 { 1.0 } else { 0.0 }) * x[1]
    });
    let displacement = element::evaluate(&geometry, &tissue, &u, None).unwrap();
    let condensed = mixed.evaluate(&geometry, &u, None).unwrap();
    assert!((displacement.energy - condensed.state.energy).abs() < 1e-12 * displacement.energy.abs());
    for (a, b) in displacement.force.iter().zip(&condensed.state.force) {
        assert!((a - b).abs() < 1e-11, "{a} vs {b}");
    }
    let (_, bulk) = tissue.volumetric_split();
    let expected = bulk * jacobian(&f).ln();
    assert!((condensed.pressure[0] - expected).abs() < 1e-12 * expected.abs());
    assert!(condensed.pressure[1].abs() < 1e-10 && condensed.pressure[2].abs() < 1e-10);
}

/// Haynsworth: the saddle-point matrix `[[K_uu, B^T], [B, -M/kappa]]` of the uncondensed form has
/// as many negative eigenvalues as the condensed tangent plus one per pressure unknown, here in
/// a state compressed far enough to have negative ones.
#[test]
fn saddle_point_inertia_is_the_condensed_plus_pressures() {
    let tissue = Bilayer::new(&Parameters::default()).layer_tissue();
    let (nodes, _) = distorted();
    let geometry = ElementGeometry::new(&nodes).unwrap();
    let mixed = MixedElement::new(&geometry, &tissue);
    // A strong lateral compression with a wrinkle-like shear, nodes 0 and 1 held (no rigid modes).
    let u: ElementVector = std::array::from_fn(|i| {
        let x = nodes[i / 2];
        if i % 2 == 0 {
            -0.45 * (x[0] + 1.3)
        } else {
            0.3 * (x[0] * 1.7).sin() + 0.2 * x[1]
        }
    });
    let mut condensed = [[0.0; DOFS]; DOFS];
    let evaluated = mixed.evaluate(&geometry, &u, Some(&mut condensed)).unwrap();
    // The uncondensed blocks at the same state, built here from their definitions.
    let (mut k_uu, mut b) = (DMatrix::zeros(DOFS, DOFS), DMatrix::zeros(PRESSURES, DOFS));
    for g in 0..GAUSS_POINTS {
        let f = geometry.deformation_gradient(g, &u);
        let inverse_transpose = cofactor(&f).map(|c| c / jacobian(&f));
        let p = dot3(mixed.basis(g), &evaluated.pressure);
        let mut response = mixed.rest().plane_response(&f);
        add_pressure(&mut response.stress, Some(&mut response.tangent), &f, p);
        let a = response.tangent;
        let w = geometry.weights()[g];
        let grads = geometry.gradients(g);
        let dfdu = |r: usize, ij: usize| {
            let (a_node, i) = (r / 2, r % 2);
            if ij / 2 == i {
                grads[a_node][ij % 2]
            } else {
                0.0
            }
        };
        for r in 0..DOFS {
            for c in 0..DOFS {
                let mut sum = 0.0;
                for (ij, row) in a.iter().enumerate() {
                    for (kl, &entry) in row.iter().enumerate() {
                        sum += dfdu(r, ij) * entry * dfdu(c, kl);
                    }
                }
                k_uu[(r, c)] += w * sum;
            }
            let dlnj: f64 = (0..4).map(|ij| inverse_transpose[ij] * dfdu(r, ij)).sum();
            for i in 0..PRESSURES {
                b[(i, r)] += w * mixed.basis(g)[i] * dlnj;
            }
        }
    }
    let held = 2 * 2;
    let free = DOFS - held;
    let (_, bulk) = tissue.volumetric_split();
    let mass = {
        let inverse = DMatrix::from_fn(PRESSURES, PRESSURES, |i, j| mixed.mass_inverse[i][j]);
        inverse.try_inverse().unwrap()
    };
    let saddle = DMatrix::from_fn(free + PRESSURES, free + PRESSURES, |r, c| match (r < free, c < free) {
        (true, true) => k_uu[(r + held, c + held)],
        (true, false) => b[(c - free, r + held)],
        (false, true) => b[(r - free, c + held)],
        (false, false) => -mass[(r - free, c - free)] / bulk,
    });
    let reduced = DMatrix::from_fn(free, free, |r, c| condensed[r + held][c + held]);
    let negatives = |m: DMatrix<f64>| {
        let eigenvalues = SymmetricEigen::new(m).eigenvalues;
        let scale = eigenvalues.amax();
        assert!(eigenvalues.iter().all(|l| l.abs() > 1e-9 * scale), "{eigenvalues}");
        eigenvalues.iter().filter(|&&l| l < 0.0).count()
    };
    let condensed_negatives = negatives(reduced);
    assert!(condensed_negatives > 0, "the test state should be unstable");
    assert_eq!(negatives(saddle), condensed_negatives + PRESSURES);
    assert_eq!(NODES * 2, DOFS);
}
