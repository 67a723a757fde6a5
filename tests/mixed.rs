//! The mixed Q2/P1disc element against independent facts: optimal convergence on a manufactured
//! isochoric solution, with error constants that do not grow from K/mu = 3 to 10^6 (the
//! displacement element's do: it locks), and the coarse-mesh FE bifurcation of a nearly
//! incompressible bilayer within 2e-4 of the linear theory (7.4e-3 with the displacement element).

mod common;

use common::{boundary_values, distortion, error_norms, mixed_bifurcation, ErrorNorms};
use fiberfold::fem::added::{AddedEnergy, Block, Diagonal};
use fiberfold::fem::element::{PlaneElement, ReferenceElement};
use fiberfold::fem::ElementKind;
use fiberfold::fem::{equilibrium, Newton, NewtonPolicy, System};
use fiberfold::material::{Bilayer, Hyperelastic, NeoHookean, Tensor2};
use fiberfold::mesh::{Mesh, MeshSpec, X, Y};
use fiberfold::Parameters;
use std::f64::consts::PI;

/// Amplitude of the two shears composing the exact solution in the convergence study: small,
/// since locking is a property of the linearised problem.
const SMALL: f64 = 1e-4;

/// `x = X + a sin(pi Y)`, then `y = Y + a sin(pi x)`: two shears, so `J = 1` exactly and the
/// solution, its stress and its body force are the same for every bulk modulus.
fn exact(a: f64, [x, y]: [f64; 2]) -> [f64; 2] {
    let sheared = x + a * (PI * y).sin();
    [a * (PI * y).sin(), a * (PI * sheared).sin()]
}

/// `Grad u = F - I` of [`exact`], row-major.
fn exact_gradient(a: f64, [x, y]: [f64; 2]) -> Tensor2 {
    let sheared = x + a * (PI * y).sin();
    let (dx_dy, dy_dx) = (a * PI * (PI * y).cos(), a * PI * (PI * sheared).cos());
    [0.0, dx_dy, dy_dx, dy_dx * dx_dy]
}

/// `b = -Div P(F)`, by central differences of the stress (`ln J = 0`, so only the shear part).
fn body_force(a: f64, point: [f64; 2]) -> [f64; 2] {
    let shear_part = NeoHookean { mu: 1.0, bulk: 0.0 };
    let stress = |p: [f64; 2]| {
        let g = exact_gradient(a, p);
        shear_part.first_piola(&[1.0 + g[0], g[1], g[2], 1.0 + g[3]]).unwrap()
    };
    let h = 1e-5;
    let mut divergence = [0.0; 2];
    for along in 0..2 {
        let (mut plus, mut minus) = (point, point);
        plus[along] += h;
        minus[along] -= h;
        let (sp, sm) = (stress(plus), stress(minus));
        for (i, d) in divergence.iter_mut().enumerate() {
            *d += (sp[2 * i + along] - sm[2 * i + along]) / (2.0 * h);
        }
    }
    divergence.map(|d| -d)
}

/// The potential `-f . u` of fixed nodal forces `f`.
struct NodalLoad(Vec<f64>);

impl AddedEnergy for NodalLoad {
    fn groups(&self) -> &[Vec<usize>] {
        &[]
    }

    fn block(&self, g: usize, _: &[f64], _: bool) -> Block {
        unreachable!("a nodal load has no group {g}")
    }

    fn diagonal(&self, u: &[f64]) -> Option<Diagonal> {
        Some(Diagonal {
            energy: -self.0.iter().zip(u).map(|(f, u)| f * u).sum::<f64>(),
            gradient: self.0.iter().map(|f| -f).collect(),
            curvature: vec![0.0; self.0.len()],
        })
    }
}

/// `int N_a b dV` on every displacement unknown.
fn nodal_load(system: &System, a: f64) -> NodalLoad {
    let mut load = vec![0.0; system.mesh().num_dofs()];
    for (nodes, geometry) in system.mesh().elements().iter().zip(system.geometry()) {
        for (g, (xi, _)) in PlaneElement::quadrature().into_iter().enumerate() {
            let (b, w) = (body_force(a, geometry.points()[g]), geometry.weights()[g]);
            for (&node, n) in nodes.iter().zip(PlaneElement::shape_functions(xi)) {
                load[system.mesh().dofs().dof(node, X)] += w * n * b[0];
                load[system.mesh().dofs().dof(node, Y)] += w * n * b[1];
            }
        }
    }
    NodalLoad(load)
}

/// The manufactured problem of amplitude `a` on `n x 2n` elements over `[0, 1] x [-1, 1]`,
/// smoothly distorted (curved edges make locking visible), solved by Newton's method from rest
/// in one load step: the error norms of the solution.
fn manufactured_errors(element: ElementKind, bulk: f64, n: usize, a: f64) -> ErrorNorms {
    let material = Bilayer::new(&Parameters {
        mu_l: 1.0,
        K_l: bulk,
        mu_s: 1.0,
        K_s: bulk,
        phi_m: 1.0,
        phi_f: 0.0,
        ..Parameters::default()
    });
    let spec = MeshSpec::new(n, n, n, 1.0 / n as f64, 1.0, 1.0).with_element(element);
    let mesh = Mesh::new(spec).unwrap().perturbed(distortion(0.05));
    let mut system = System::new(mesh.clone(), &material).unwrap();
    let mut u = vec![0.0; system.num_dofs()];
    let (bc, load) = (boundary_values(&mesh, |x| exact(a, x)), nodal_load(&system, a));
    equilibrium::solve_with(
        &mut Newton::new(),
        &mut system,
        &mut u,
        &bc,
        &load,
        &NewtonPolicy::default(),
    )
    .unwrap_or_else(|e| panic!("{element:?}, K = {bulk}, n = {n}: {e}"));
    error_norms(&system, &u, &|x| exact(a, x), &|x| exact_gradient(a, x))
}

fn list(values: &[f64]) -> String {
    values.iter().map(|v| format!("{v:.3e}")).collect::<Vec<_>>().join(", ")
}

/// Convergence rates `log2(e_n / e_2n)` of successive halvings.
fn rates(errors: &[f64]) -> Vec<f64> {
    errors.windows(2).map(|w| (w[0] / w[1]).log2()).collect()
}

#[test]
fn mixed_element_converges_optimally_without_locking() {
    let sizes = [4, 8, 16];
    let errors = |element, bulk| -> (Vec<f64>, Vec<f64>) {
        let norms: Vec<ErrorNorms> = sizes
            .iter()
            .map(|&n| manufactured_errors(element, bulk, n, SMALL))
            .collect();
        (
            norms.iter().map(|e| e.l2).collect(),
            norms.iter().map(|e| e.h1).collect(),
        )
    };
    let (mixed_l2, mixed_h1) = errors(ElementKind::Mixed, 3.0);
    let (stiff_l2, stiff_h1) = errors(ElementKind::Mixed, 1e6);
    let (locked_l2, locked_h1) = errors(ElementKind::Displacement, 1e6);
    let (plain_l2, _) = errors(ElementKind::Displacement, 3.0);
    for (name, l2, h1) in [
        ("mixed, K = 3", &mixed_l2, &mixed_h1),
        ("mixed, K = 1e6", &stiff_l2, &stiff_h1),
        ("displacement, K = 1e6", &locked_l2, &locked_h1),
    ] {
        println!(
            "{name}: L2 {} rates {:.2?}; H1 {} rates {:.2?}",
            list(l2),
            rates(l2),
            list(h1),
            rates(h1)
        );
    }
    println!("displacement, K = 3: L2 {}", list(&plain_l2));
    for (l2, h1) in [(&mixed_l2, &mixed_h1), (&stiff_l2, &stiff_h1)] {
        assert!(rates(l2).iter().all(|&r| r > 2.8), "L2 rates {:?}", rates(l2));
        assert!(rates(h1).iter().all(|&r| r > 1.9), "H1 rates {:?}", rates(h1));
    }
    // No locking: at K/mu = 10^6 the errors are those at K/mu = 3 ...
    for (stiff, soft) in stiff_l2.iter().chain(&stiff_h1).zip(mixed_l2.iter().chain(&mixed_h1)) {
        assert!(*stiff <= 1.1 * soft, "{stiff:e} at K = 1e6 vs {soft:e} at K = 3");
    }
    // ... while the displacement element's grow many times on the same meshes.
    assert!(locked_l2[0] > 10.0 * stiff_l2[0], "{locked_l2:?} vs {stiff_l2:?}");
}

/// A finite deformation (shears of 0.1) at `K / mu = 10^6`: Newton's method with the
/// multipliers (`fem::mixed`) converges from rest in one load step, and the error is that of
/// `K / mu = 3`.
#[test]
fn mixed_element_solves_a_large_nearly_incompressible_deformation() {
    let (soft, stiff) = (
        manufactured_errors(ElementKind::Mixed, 3.0, 8, 0.1),
        manufactured_errors(ElementKind::Mixed, 1e6, 8, 0.1),
    );
    println!(
        "K = 3: L2 {:.3e} H1 {:.3e}; K = 1e6: L2 {:.3e} H1 {:.3e}",
        soft.l2, soft.h1, stiff.l2, stiff.h1
    );
    assert!(stiff.l2 <= 1.1 * soft.l2 && stiff.h1 <= 1.1 * soft.h1);
    assert!(stiff.relative_l2() < 1e-3, "{}", stiff.relative_l2());
}

/// Coarse mesh, no fibres, K = 10^4 mu in both layers (`K_l = 10 K_s`, as `mu_l = 10 mu_s`).
#[test]
fn nearly_incompressible_bifurcation_agrees_with_the_linear_theory() {
    let summary = mixed_bifurcation(
        "mixed-bifurcation",
        &[
            "--set",
            "phi_m=1",
            "--set",
            "phi_f=0",
            "--set",
            "K_s=10000",
            "--set",
            "K_l=100000",
        ],
    );
    assert_eq!(summary["mesh"]["element"], "mixed");
    let difference = summary["relative_difference"].as_f64().unwrap();
    assert!(difference < 2e-4, "FE vs theory {difference:e}");
}
