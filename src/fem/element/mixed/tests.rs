use super::*;
use crate::fem::element::displacement::{self, tests::assert_consistent_derivatives, tests::distorted};
use crate::fem::element::{Hex27, Quad9, ReferenceElement, DOFS, ELEMENT_DOFS, NODES};
use crate::material::{add_pressure, cofactor, jacobian, Bilayer};
use crate::mesh::DofMap;
use crate::parameters::Parameters;
use nalgebra::{DMatrix, SymmetricEigen};

/// Row-major numbering of a plane tensor's components `iJ`.
const PLANE_TENSOR: DofMap = DofMap::PLANE;

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

fn mixed_on_distorted(
    tissue: &Tissue,
    constraint: Option<Volumetric>,
) -> (ElementGeometry, MixedElement, ElementVector) {
    let (nodes, u) = distorted();
    let geometry = ElementGeometry::new::<Quad9>(&nodes).unwrap();
    let mixed = <MixedElement>::new(&geometry, tissue, constraint);
    (geometry, mixed, u)
}

/// The element's state under the method of multipliers with the penalty scaled by `scale`, as a
/// function of the displacements (for the derivative checks).
fn augmented<'a, const D: usize, const N: usize, const Q: usize, const U: usize, const P: usize>(
    mixed: &'a MixedElement<D, Q, P>,
    geometry: &'a ElementGeometry<D, N, Q>,
    lambda: &'a Pressures,
    scale: f64,
) -> impl Fn(&ElementVector<U>, Option<&mut ElementMatrix<U>>) -> ElementState<U> + 'a {
    move |v, k| {
        mixed
            .evaluate(geometry, v, lambda, Penalty::Augmentation(scale), k)
            .unwrap()
            .state
    }
}

#[test]
fn condensed_force_and_tangent_are_the_derivatives_of_the_energy() {
    let (geometry, mixed, u) = mixed_on_distorted(&substrate(), None);
    assert_consistent_derivatives(&u, augmented(&mixed, &geometry, &[0.0; MAX_PRESSURES], 1.0));
}

/// Under a uniform `F` the projection of `ln J` is exact, so the mixed element's energy, force
/// and pressure are the displacement element's and `K ln J`.
#[test]
fn homogeneous_deformation_gives_the_displacement_element_s_energy_and_pressure() {
    let tissue = substrate();
    let (nodes, _) = distorted();
    let geometry = ElementGeometry::new::<Quad9>(&nodes).unwrap();
    let mixed = <MixedElement>::new(&geometry, &tissue, None);
    let f = [0.83, 0.11, -0.07, 1.12];
    let u: ElementVector = std::array::from_fn(|i| {
        let (x, c) = (nodes[ELEMENT_DOFS.node(i)], ELEMENT_DOFS.component(i));
        (f[PLANE_TENSOR.dof(c, 0)] - if c == 0 { 1.0 } else { 0.0 }) * x[0]
            + (f[PLANE_TENSOR.dof(c, 1)] - if c == 1 { 1.0 } else { 0.0 }) * x[1]
    });
    let displacement = displacement::evaluate(&geometry, &tissue, &u, None).unwrap();
    let condensed = mixed
        .evaluate(&geometry, &u, &[0.0; MAX_PRESSURES], Penalty::Augmentation(1.0), None)
        .unwrap();
    assert!((displacement.energy - condensed.state.energy).abs() < 1e-12 * displacement.energy.abs());
    for (a, b) in displacement.force.iter().zip(&condensed.state.force) {
        assert!((a - b).abs() < 1e-11, "{a} vs {b}");
    }
    let bulk = tissue.volumetric_split().bulk;
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
    let geometry = ElementGeometry::new::<Quad9>(&nodes).unwrap();
    let mixed = <MixedElement>::new(&geometry, &tissue, None);
    // A strong lateral compression with a wrinkle-like shear, nodes 0 and 1 held (no rigid modes).
    let u: ElementVector = std::array::from_fn(|i| {
        let x = nodes[ELEMENT_DOFS.node(i)];
        if ELEMENT_DOFS.component(i) == 0 {
            -0.45 * (x[0] + 1.3)
        } else {
            0.3 * (x[0] * 1.7).sin() + 0.2 * x[1]
        }
    });
    let mut condensed = [[0.0; DOFS]; DOFS];
    let evaluated = mixed
        .evaluate(
            &geometry,
            &u,
            &[0.0; MAX_PRESSURES],
            Penalty::Augmentation(1.0),
            Some(&mut condensed),
        )
        .unwrap();
    // The uncondensed blocks at the same state, built here from their definitions.
    let (mut k_uu, mut b) = (DMatrix::zeros(DOFS, DOFS), DMatrix::zeros(PRESSURES, DOFS));
    for g in 0..GAUSS_POINTS {
        let f = geometry.deformation_gradient(g, &u);
        let inverse_transpose = cofactor(&f).map(|c| c / jacobian(&f));
        let p = dot(mixed.basis(g), &evaluated.pressure);
        let mut response = mixed.rest().plane_response(&f);
        add_pressure(&mut response.stress, Some(&mut response.tangent), &f, p);
        let a = response.tangent;
        let w = geometry.weights()[g];
        let grads = geometry.gradients(g);
        let dfdu = |r: usize, ij: usize| {
            let (a_node, i) = (ELEMENT_DOFS.node(r), ELEMENT_DOFS.component(r));
            if PLANE_TENSOR.node(ij) == i {
                grads[a_node][PLANE_TENSOR.component(ij)]
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
    let bulk = tissue.volumetric_split().bulk;
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

/// The constraint mode (multipliers `lambda`, penalty `kappa`): force and tangent are the
/// derivatives of its energy `int W_rest + lambda . g + kappa/2 g^T M^-1 g`, and the pressure is
/// `lambda + kappa M^-1 g`.
#[test]
fn constraint_mode_derivatives_match_central_differences() {
    let constraint = Volumetric::Augmented {
        penalty: 40.0,
        bulk: f64::INFINITY,
    };
    let (geometry, mixed, u) = mixed_on_distorted(&substrate(), Some(constraint));
    let lambda = [0.7, -0.3, 0.2, 0.0];
    let state = mixed
        .evaluate(&geometry, &u, &lambda, Penalty::Augmentation(2.5), None)
        .unwrap();
    let expected: [f64; PRESSURES] = std::array::from_fn(|i| lambda[i] + 2.5 * 40.0 * state.violation[i]);
    assert!(state.pressure.iter().zip(&expected).all(|(a, b)| (a - b).abs() < 1e-12));
    assert_consistent_derivatives(&u, augmented(&mixed, &geometry, &lambda, 2.5));
}

/// The stability tangent at a state that meets the constraint only approximately: the
/// Hessian of the Lagrangian `int W_rest + lambda . g` at the multipliers (the pressure is
/// `lambda` whatever the penalty), plus `kappa B^T M^-1 B`, positive semi-definite of rank
/// `P`. Were the pressure `lambda + kappa M^-1 g`, raising `kappa` would add the indefinite
/// `kappa (M^-1 g) . d2g` as well.
#[test]
fn the_stability_tangent_is_the_lagrangian_s_hessian_plus_the_constraint_s_stiffness() {
    let constraint = Volumetric::Augmented {
        penalty: 40.0,
        bulk: f64::INFINITY,
    };
    let (geometry, mixed, u) = mixed_on_distorted(&substrate(), Some(constraint));
    let lambda = [0.7, -0.3, 0.2, 0.0];
    let met = mixed
        .evaluate(&geometry, &u, &lambda, Penalty::Augmentation(1.0), None)
        .unwrap();
    assert!(
        met.violation.iter().any(|v| v.abs() > 1e-4),
        "the constraint is not met"
    );
    let tangent = |scale: f64| {
        let mut k = [[0.0; DOFS]; DOFS];
        let state = mixed
            .evaluate(&geometry, &u, &lambda, Penalty::Stability(scale), Some(&mut k))
            .unwrap();
        assert_eq!(&state.pressure[..], &lambda[..PRESSURES]);
        DMatrix::from_fn(DOFS, DOFS, |i, j| k[i][j])
    };
    let (k_1, k_2) = (tangent(1e3), tangent(2e3));
    let scale = k_2.amax();
    // K(2s) - K(s) = kappa(s) B^T M^-1 B.
    let constraint_stiffness = SymmetricEigen::new(&k_2 - &k_1).eigenvalues;
    assert!(constraint_stiffness.min() > -1e-12 * scale, "{constraint_stiffness}");
    let positive = constraint_stiffness.iter().filter(|&&e| e > 1e-9 * scale).count();
    assert_eq!(positive, PRESSURES);
    // 2 K(s) - K(2s), the Lagrangian's Hessian: the derivative of the force at the multipliers.
    let hessian = 2.0 * &k_1 - &k_2;
    let h = 1e-6;
    for j in 0..DOFS {
        let force = |s: f64| {
            let mut v = u;
            v[j] += s * h;
            mixed
                .evaluate(&geometry, &v, &lambda, Penalty::Stability(1e3), None)
                .unwrap()
                .state
                .force
        };
        let (plus, minus) = (force(1.0), force(-1.0));
        for i in 0..DOFS {
            let difference = (plus[i] - minus[i]) / (2.0 * h);
            assert!(
                (difference - hessian[(i, j)]).abs() < 1e-6 * (1.0 + difference.abs()),
                "({i}, {j}): {difference} vs {}",
                hessian[(i, j)]
            );
        }
    }
}

/// A finite bulk modulus above the penalty (`K / mu = 1e4`): for fixed multipliers the force and
/// tangent are the derivatives of the augmented potential
/// `int W_rest + (1 - kappa/K) lambda . g + kappa/2 g^T M^-1 g`, not of the energy reported
/// (`int W_rest + K/2 g^T M^-1 g`, the condensed element's, right only at the multipliers'
/// fixed point): away from it the two differ, and their gradients too.
#[test]
fn augmented_mode_with_a_finite_bulk_has_the_force_of_its_potential() {
    let constraint = Volumetric::Augmented {
        penalty: 40.0,
        bulk: 1e4,
    };
    let (geometry, mixed, u) = mixed_on_distorted(&substrate(), Some(constraint));
    let lambda = [0.7, -0.3, 0.2, 0.0];
    assert_consistent_derivatives(&u, augmented(&mixed, &geometry, &lambda, 1.0));
    // The reported energy's own derivative is not the force there.
    let state = mixed
        .evaluate(&geometry, &u, &lambda, Penalty::Augmentation(1.0), None)
        .unwrap()
        .state;
    let h = 1e-6;
    let worst = (0..DOFS)
        .map(|j| {
            let energy = |s: f64| {
                let mut v = u;
                v[j] += s * h;
                mixed
                    .evaluate(&geometry, &v, &lambda, Penalty::Augmentation(1.0), None)
                    .unwrap()
                    .state
                    .energy
            };
            ((energy(1.0) - energy(-1.0)) / (2.0 * h) - state.force[j]).abs()
        })
        .fold(0.0, f64::max);
    assert!(worst > 1e-3, "the energy's gradient differs from the force: {worst:e}");
}

/// A curved, distorted hexahedron and a displacement with some volume change.
fn distorted_hexahedron() -> ([[f64; 3]; 27], ElementVector<81>) {
    let nodes = std::array::from_fn(|a| {
        let [x, y, z] = <Hex27 as ReferenceElement<3, 27, 27>>::node_coordinates(a);
        [
            1.2 * x + 0.15 * y + 0.05 * y * y,
            0.9 * y + 0.1 * x * z - 0.06 * x * x,
            1.1 * z + 0.07 * x * y,
        ]
    });
    let u = std::array::from_fn(|i| 0.05 * ((i as f64) * 1.3).sin());
    (nodes, u)
}

/// The hexahedron's mixed element, condensed and under multipliers (four pressures: a linear
/// polynomial in X, Y, Z): force and tangent are the derivatives of its potential.
#[test]
fn the_mixed_hexahedron_s_force_and_tangent_are_the_derivatives_of_its_potential() {
    let (nodes, u) = distorted_hexahedron();
    let geometry = ElementGeometry::new::<Hex27>(&nodes).unwrap();
    let tissue = substrate();
    for constraint in [
        None,
        Some(Volumetric::Augmented {
            penalty: 40.0,
            bulk: f64::INFINITY,
        }),
    ] {
        let mixed = MixedElement::<3, 27, 4>::new(&geometry, &tissue, constraint);
        let lambda = [0.7, -0.3, 0.2, 0.4];
        assert_consistent_derivatives(&u, augmented(&mixed, &geometry, &lambda, 2.5));
    }
}

/// Under a uniform 3D `F` the projection of `ln J` is exact: the mixed hexahedron's energy and
/// force are the displacement element's, and its pressure `K ln J`, constant.
#[test]
fn a_homogeneous_3d_deformation_gives_the_displacement_hexahedron_s_energy_and_pressure() {
    let tissue = substrate();
    let (nodes, _) = distorted_hexahedron();
    let geometry = ElementGeometry::new::<Hex27>(&nodes).unwrap();
    let mixed = MixedElement::<3, 27, 4>::new(&geometry, &tissue, None);
    let f = [[0.83, 0.11, 0.05], [-0.07, 1.12, 0.02], [0.04, -0.03, 0.95]];
    let dofs = DofMap::SPACE;
    let u: ElementVector<81> = std::array::from_fn(|i| {
        let (x, c) = (nodes[dofs.node(i)], dofs.component(i));
        (0..3).map(|l| (f[c][l] - if c == l { 1.0 } else { 0.0 }) * x[l]).sum()
    });
    let displacement = displacement::evaluate(&geometry, &tissue, &u, None).unwrap();
    let condensed = mixed
        .evaluate(&geometry, &u, &[0.0; MAX_PRESSURES], Penalty::Augmentation(1.0), None)
        .unwrap();
    assert!((displacement.energy - condensed.state.energy).abs() < 1e-12 * displacement.energy.abs());
    for (a, b) in displacement.force.iter().zip(&condensed.state.force) {
        assert!((a - b).abs() < 1e-11, "{a} vs {b}");
    }
    let j = crate::fem::element::determinant(&f);
    let expected = tissue.volumetric_split().bulk * j.ln();
    assert!((condensed.pressure[0] - expected).abs() < 1e-12 * expected.abs());
    assert!(
        condensed.pressure[1..].iter().all(|p| p.abs() < 1e-10),
        "{:?}",
        condensed.pressure
    );
}

#[test]
#[ignore]
fn explore_hex_eigenvalues() {
    let (nodes, _) = distorted_hexahedron();
    let geometry = ElementGeometry::new::<Hex27>(&nodes).unwrap();
    let p = Parameters {
        mu_l: 1.0,
        K_l: 100.0,
        phi_m: 1.0,
        phi_f: 0.0,
        ..Parameters::default()
    };
    let tissue = Bilayer::new(&p).layer_tissue();
    for mixed in [true, false] {
        let mut k = [[0.0; 81]; 81];
        if mixed {
            let element = MixedElement::<3, 27, 4>::new(&geometry, &tissue, None);
            element
                .evaluate(
                    &geometry,
                    &[0.0; 81],
                    &[0.0; MAX_PRESSURES],
                    Penalty::Augmentation(1.0),
                    Some(&mut k),
                )
                .unwrap();
        } else {
            displacement::evaluate(&geometry, &tissue, &[0.0; 81], Some(&mut k)).unwrap();
        }
        let m = DMatrix::from_fn(81, 81, |i, j| k[i][j]);
        let mut e: Vec<f64> = SymmetricEigen::new(m).eigenvalues.iter().copied().collect();
        e.sort_by(|a, b| a.total_cmp(b));
        eprintln!("mixed {mixed}: {:?}", &e[..10]);
    }
}
