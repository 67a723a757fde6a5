//! Finite-element core against independent references: exact unknown counts, the patch test,
//! finite differences of the residual, Newton's quadratic convergence, the closed-form
//! homogeneous state (eq. 4), dense eigenvalues for the inertia, and the O(h^3) L2 convergence
//! of Q2 elements.

mod common;

use common::{boundary_values, distortion, error_norms, homogeneous_material, worst_nodal_error};
use fiberfold::fem::added::{AddedEnergy, Block, Diagonal};
use fiberfold::fem::linear_solver::multiply;
use fiberfold::fem::ElementKind;
use fiberfold::fem::{equilibrium, Newton, NewtonError, NewtonPolicy, Reuse, System};
use fiberfold::homogeneous::homogeneous_state;
use fiberfold::material::Bilayer;
use fiberfold::mesh::{Mesh, MeshSpec, X, Y};
use fiberfold::protocol::model_conditions;
use fiberfold::Parameters;

/// Numbers in scientific notation, for messages.
fn list(values: &[f64]) -> String {
    values.iter().map(|v| format!("{v:.3e}")).collect::<Vec<_>>().join(", ")
}

#[test]
fn unknown_counts_and_grading_of_the_presets() {
    for (spec, dofs, free, bottom) in [
        (MeshSpec::coarse(), 22_110, 21_799, 5.0),
        (MeshSpec::fine(), 79_398, 78_799, 2.97),
    ] {
        let mesh = Mesh::new(spec).unwrap();
        assert_eq!(mesh.num_dofs(), dofs);
        assert_eq!(spec.num_dofs(), dofs);
        assert_eq!(mesh.num_dofs() - model_conditions(&mesh, 0.1).unwrap().len(), free);
        let h = spec.substrate_thicknesses();
        assert_eq!(h.len(), spec.substrate_elements);
        assert_eq!(h[0], spec.top_substrate_thickness);
        assert!((h.iter().sum::<f64>() - spec.depth).abs() < 1e-12);
        assert!(
            (h[h.len() - 1] / bottom - 1.0).abs() < 0.02,
            "bottom element {}",
            h[h.len() - 1]
        );
        let r = spec.grading_ratio();
        assert!(h.windows(2).all(|w| (w[1] / w[0] - r).abs() < 1e-9));
        assert_eq!(mesh.coordinates()[mesh.bottom()[0]], [0.0, -spec.depth]);
        assert_eq!(mesh.coordinates()[*mesh.top().last().unwrap()], [spec.length, 1.0]);
    }
}

#[test]
fn patch_test_reproduces_an_affine_deformation_on_a_distorted_mesh() {
    for element in [ElementKind::Displacement, ElementKind::Mixed] {
        let spec = MeshSpec::new(3, 2, 2, 0.8, 3.0, 2.0).with_element(element);
        let mesh = Mesh::new(spec).unwrap().perturbed(distortion(0.08));
        let g = [[0.1, 0.2], [-0.15, 0.05]];
        let affine = |[x, y]: [f64; 2]| [g[0][0] * x + g[0][1] * y, g[1][0] * x + g[1][1] * y];
        let bc = boundary_values(&mesh, affine);
        let mut system = System::new(mesh.clone(), &homogeneous_material()).unwrap();
        let mut u = vec![0.0; mesh.num_dofs()];
        let report =
            equilibrium::solve(&mut Newton::new(), &mut system, &mut u, &bc, &NewtonPolicy::default()).unwrap();
        let worst = worst_nodal_error(&mesh, &u, affine);
        assert!(worst < 1e-12, "{element:?}: patch test error {worst:e} ({report:?})");
    }
}

#[test]
fn assembled_tangent_and_lifting_match_central_differences() {
    let p = Parameters {
        beta: 0.5,
        lambda_f: 0.95,
        ..Parameters::default()
    };
    let mesh = Mesh::new(MeshSpec::new(2, 1, 1, 1.5, 2.0, 1.5))
        .unwrap()
        .perturbed(distortion(0.05));
    let mut system = System::new(mesh.clone(), &Bilayer::new(&p)).unwrap();
    let bc = model_conditions(&mesh, 0.05).unwrap();
    let u: Vec<f64> = (0..mesh.num_dofs())
        .map(|i| {
            let [x, y] = mesh.coordinates()[mesh.dofs().node(i)];
            if mesh.dofs().component(i) == X {
                0.05 * (x + 2.0 * y).sin()
            } else {
                0.04 * (1.3 * x - y).cos()
            }
        })
        .collect();
    let at = |system: &mut System, v: &[f64]| system.assemble(v, &bc, None, false).unwrap().residual;
    let assembled = system.assemble(&u, &bc, None, true).unwrap();
    let k = assembled.tangent.unwrap();
    let free = system.free_dofs(&bc).unwrap().to_vec();
    let h = 1e-6;
    let (mut worst, mut scale) = (0.0f64, 0.0f64);
    for (j, &dof_j) in free.iter().enumerate() {
        let mut v = u.clone();
        v[dof_j] += h;
        let plus = at(&mut system, &v);
        v[dof_j] -= 2.0 * h;
        let minus = at(&mut system, &v);
        let mut unit = vec![0.0; free.len()];
        unit[j] = 1.0;
        let column = multiply(k.as_ref(), &unit);
        for i in 0..free.len() {
            worst = worst.max(((plus[i] - minus[i]) / (2.0 * h) - column[i]).abs());
            scale = scale.max(column[i].abs());
        }
    }
    assert!(worst <= 1e-6 * scale, "tangent error {worst:e} of {scale:e}");

    // The lifting K_fc du_c is the derivative of r_f along the prescribed unknowns.
    let direction: Vec<f64> = (0..bc.len()).map(|c| (c as f64 * 0.7).sin()).collect();
    let lifted = system.assemble(&u, &bc, Some(&direction), false).unwrap().residual;
    let mut moved = |s: f64| {
        let mut v = u.clone();
        for (&d, &l) in bc.dofs().iter().zip(&direction) {
            v[d] += s * h * l;
        }
        at(&mut system, &v)
    };
    let (plus, minus) = (moved(1.0), moved(-1.0));
    for i in 0..free.len() {
        let fd = (plus[i] - minus[i]) / (2.0 * h);
        let analytic = lifted[i] - assembled.residual[i];
        assert!((fd - analytic).abs() <= 1e-6 * scale, "lifting {i}: {fd} vs {analytic}");
    }
}

/// A quadratic `sum_i c_i (u_i - r_i)^2 / 2` on every unknown, as an added energy.
struct Quadratic {
    curvature: Vec<f64>,
    centre: Vec<f64>,
}

impl AddedEnergy for Quadratic {
    fn groups(&self) -> &[Vec<usize>] {
        &[]
    }

    fn block(&self, g: usize, _: &[f64], _: bool) -> Block {
        unreachable!("no group {g}")
    }

    fn diagonal(&self, u: &[f64]) -> Option<Diagonal> {
        Some(Diagonal::quadratic(self.curvature.clone(), u, &self.centre))
    }
}

#[test]
fn a_diagonal_added_to_an_assembly_is_the_assembly_of_the_quadratic_centred_there() {
    let (p, mesh) = wavy_problem();
    let mut system = System::new(mesh.clone(), &Bilayer::new(&p)).unwrap();
    let bc = model_conditions(&mesh, 0.05).unwrap();
    let u: Vec<f64> = (0..mesh.num_dofs()).map(|i| 0.01 * (0.37 * i as f64).sin()).collect();
    let curvature: Vec<f64> = (0..mesh.num_dofs()).map(|i| 0.5 + (0.61 * i as f64).cos()).collect();
    let quadratic = Quadratic {
        curvature: curvature.clone(),
        centre: u.clone(),
    };
    let assembled = system.assemble(&u, &bc, None, true).unwrap();
    let expected = system.assemble_with(&u, &bc, None, true, &quadratic).unwrap();
    let shifted = system.with_diagonal_added(&assembled, &curvature);
    assert_eq!(shifted.residual, expected.residual);
    assert_eq!(
        (shifted.energy, shifted.added_energy),
        (expected.energy, expected.added_energy)
    );
    let (a, b) = (shifted.tangent.unwrap(), expected.tangent.unwrap());
    assert_eq!(a.as_ref().val(), b.as_ref().val());
    // The assembly it came from is unchanged, and the two differ by the curvature alone.
    let base = assembled.tangent.unwrap();
    let free = system.free_dofs(&bc).unwrap().to_vec();
    for (j, &dof) in free.iter().enumerate() {
        let mut unit = vec![0.0; free.len()];
        unit[j] = 1.0;
        let difference: Vec<f64> = multiply(a.as_ref(), &unit)
            .iter()
            .zip(multiply(base.as_ref(), &unit))
            .map(|(x, y)| x - y)
            .collect();
        for (i, x) in difference.iter().enumerate() {
            let want = if i == j { curvature[dof] } else { 0.0 };
            assert!(
                (x - want).abs() <= 1e-12 * (1.0 + want.abs()),
                "entry ({i}, {j}): {x} vs {want}"
            );
        }
    }
}

/// A small perturbed bilayer mesh with fibres at beta = 0.3, for the Newton tests.
fn wavy_problem() -> (Parameters, Mesh) {
    let p = Parameters {
        beta: 0.3,
        ..Parameters::default()
    };
    let mesh = Mesh::new(MeshSpec::new(6, 2, 4, 0.5, 6.0, 6.0))
        .unwrap()
        .perturbed(|[x, y]| [0.0, 0.05 * (std::f64::consts::PI * x / 3.0).cos() * (1.0 + y / 6.0)]);
    (p, mesh)
}

#[test]
fn newton_converges_quadratically() {
    let (p, mesh) = wavy_problem();
    let mut system = System::new(mesh.clone(), &Bilayer::new(&p)).unwrap();
    let bc = model_conditions(&mesh, 0.1).unwrap();
    let mut u = vec![0.0; mesh.num_dofs()];
    let report = equilibrium::solve(&mut Newton::new(), &mut system, &mut u, &bc, &NewtonPolicy::default()).unwrap();
    let scaled: Vec<f64> = report.residual_history.iter().map(|r| r / report.force_norm).collect();
    println!("iterations {}, scaled residuals {}", report.iterations, list(&scaled));
    assert!(report.iterations <= 8);
    assert_eq!(report.negative_pivots, Some(0));
    // Past the first (lifted) step: e_{n+1} <= C e_n^2 once e_n is small, above round-off.
    let pairs: Vec<f64> = scaled[1..]
        .windows(2)
        .filter(|w| w[0] < 1e-2 && w[1] > 1e-14)
        .map(|w| w[1] / (w[0] * w[0]))
        .collect();
    assert!(!pairs.is_empty(), "{scaled:?}");
    assert!(pairs.iter().all(|&c| c < 10.0), "ratios {pairs:?}");
}

/// From a predictor (the prescribed values already set), the tangent there is factorised first
/// and reused by the iteration: one factorisation for the solve, whose inertia (of the start)
/// is the solution's here, as a factorisation at the solution shows.
#[test]
fn the_factorisation_at_the_predictor_serves_the_solve_and_gives_its_inertia() {
    let (p, mesh) = wavy_problem();
    let mut system = System::new(mesh.clone(), &Bilayer::new(&p)).unwrap();
    let mut newton = Newton::new();
    let policy = NewtonPolicy {
        reuse: Reuse::Definite,
        factorise_start: true,
        inertia_at_solution: false,
        ..NewtonPolicy::default()
    };
    let mut path = vec![vec![0.0; mesh.num_dofs()]; 2];
    for (u, d) in path.iter_mut().zip([0.1, 0.11]) {
        equilibrium::solve(
            &mut newton,
            &mut system,
            u,
            &model_conditions(&mesh, d).unwrap(),
            &policy,
        )
        .unwrap();
    }
    // The secant predictor: u(0.12) ~ 2 u(0.11) - u(0.1).
    let bc = model_conditions(&mesh, 0.12).unwrap();
    let mut u: Vec<f64> = path[1].iter().zip(&path[0]).map(|(b, a)| 2.0 * b - a).collect();
    for (&dof, &value) in bc.dofs().iter().zip(bc.values()) {
        u[dof] = value;
    }
    let report = equilibrium::solve(&mut newton, &mut system, &mut u, &bc, &policy).unwrap();
    println!(
        "{} iterations, {} factorisations, residuals {}",
        report.iterations,
        report.timings.factorisations,
        list(&report.residual_history)
    );
    assert_eq!(report.timings.factorisations, 1);
    assert_eq!(report.start_negative_pivots, Some(0));
    let exact = Newton::new()
        .inertia(
            &mut system,
            &u,
            &bc,
            &fiberfold::fem::added::NoAddedEnergy,
            &mut Default::default(),
        )
        .unwrap();
    assert_eq!(report.start_negative_pivots, exact);
}

#[test]
fn reused_factorisation_reaches_the_full_newton_solution_with_fewer_factorisations() {
    let (p, mesh) = wavy_problem();
    // A path of load steps from the same start, by full Newton and by Newton reusing the last
    // factorisation (the one at the previous solution, as in a continuation).
    let path = |reuse: bool| {
        let mut system = System::new(mesh.clone(), &Bilayer::new(&p)).unwrap();
        let mut newton = Newton::new();
        let policy = NewtonPolicy {
            reuse: if reuse { Reuse::Definite } else { Reuse::Never },
            ..NewtonPolicy::default()
        };
        let mut u = vec![0.0; mesh.num_dofs()];
        let mut factorisations = 0;
        for step in 1..=6 {
            let d = 0.02 * step as f64;
            let bc = model_conditions(&mesh, d).unwrap();
            let report = equilibrium::solve(&mut newton, &mut system, &mut u, &bc, &policy).unwrap();
            assert_eq!(report.negative_pivots, Some(0), "d = {d}");
            factorisations += report.timings.factorisations;
        }
        (u, factorisations)
    };
    let ((full, full_count), (reused, reused_count)) = (path(false), path(true));
    let scale = full.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let difference = full.iter().zip(&reused).fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    println!(
        "factorisations: full {full_count}, reused {reused_count}; |u_full - u_reused| = {difference:e} of {scale:e}"
    );
    assert!(difference <= 1e-9 * scale, "{difference:e}");
    assert!(reused_count < full_count, "{reused_count} vs {full_count}");
}

#[test]
fn perfect_mesh_reproduces_the_homogeneous_state() {
    let mesh = Mesh::new(MeshSpec::new(4, 1, 2, 1.0, 4.0, 3.0)).unwrap();
    let depth = mesh.spec().depth;
    // The paper's beta = 0.785398 is pi/4 to six digits.
    for beta in [0.0, std::f64::consts::FRAC_PI_4] {
        let materials = Bilayer::new(&Parameters {
            beta,
            ..Parameters::default()
        });
        let mut system = System::new(mesh.clone(), &materials).unwrap();
        let mut newton = Newton::new();
        let mut u = vec![0.0; mesh.num_dofs()];
        for d in [0.1, 0.3] {
            let exact = homogeneous_state(&materials, d).unwrap();
            let bc = model_conditions(&mesh, d).unwrap();
            equilibrium::solve(&mut newton, &mut system, &mut u, &bc, &NewtonPolicy::default()).unwrap();
            for (&top, &interface) in mesh.top().iter().zip(&mesh.interface()) {
                let lambda2_layer = 1.0 + (u[mesh.dofs().dof(top, Y)] - u[mesh.dofs().dof(interface, Y)]);
                let lambda2_substrate = 1.0 + u[mesh.dofs().dof(interface, Y)] / depth;
                assert!((lambda2_layer - exact.lambda2_layer).abs() < 1e-10, "beta {beta} d {d}");
                assert!(
                    (lambda2_substrate - exact.lambda2_substrate).abs() < 1e-10,
                    "beta {beta} d {d}"
                );
            }
            for (n, &[x, _]) in mesh.coordinates().iter().enumerate() {
                assert!(
                    (u[mesh.dofs().dof(n, X)] + d * x).abs() < 1e-10,
                    "u_x = -d X at node {n}"
                );
            }
        }
    }
}

#[test]
fn inertia_of_the_tangent_matches_dense_eigenvalues() {
    use faer::sparse::{SparseColMat, Triplet};
    use fiberfold::fem::SparseLdlt;
    let mesh = Mesh::new(MeshSpec::new(4, 1, 2, 1.0, 4.0, 3.0)).unwrap();
    let mut system = System::new(mesh.clone(), &Bilayer::new(&Parameters::default())).unwrap();
    let bc = model_conditions(&mesh, 0.3).unwrap();
    let u: Vec<f64> = (0..mesh.num_dofs())
        .map(|i| {
            let [x, y] = mesh.coordinates()[mesh.dofs().node(i)];
            if mesh.dofs().component(i) == X {
                -0.3 * x + 0.1 * (2.0 * x).sin()
            } else {
                0.2 * (y + 3.0) * (x + 0.5 * y).cos()
            }
        })
        .collect();
    let tangent = system.assemble(&u, &bc, None, true).unwrap().tangent.unwrap();
    let k = tangent.as_ref();
    let n = k.nrows();
    let mut triplets = Vec::new();
    let mut dense = nalgebra::DMatrix::<f64>::zeros(n, n);
    for j in 0..n {
        for (&i, &v) in k.row_idx_of_col_raw(j).iter().zip(k.val_of_col(j)) {
            // The lower triangle is stored.
            assert!(i >= j, "entry ({i}, {j}) above the diagonal");
            triplets.push(Triplet::new(i, j, v));
            dense[(i, j)] = v;
            dense[(j, i)] = v;
        }
    }
    let eigenvalues = dense.symmetric_eigen().eigenvalues;
    let mut solver = SparseLdlt::new(k.symbolic());
    let mut sorted: Vec<f64> = eigenvalues.iter().copied().collect();
    sorted.sort_by(f64::total_cmp);
    // Shifts between consecutive eigenvalues, so that round-off cannot blur the count.
    for m in [0, 3, 10, n / 2] {
        let sigma = if m == 0 {
            sorted[0] - 1.0
        } else {
            0.5 * (sorted[m - 1] + sorted[m])
        };
        let shifted: Vec<_> = triplets
            .iter()
            .map(|t| Triplet::new(t.row, t.col, t.val - if t.row == t.col { sigma } else { 0.0 }))
            .collect();
        let a = SparseColMat::<usize, f64>::try_new_from_triplets(n, n, &shifted).unwrap();
        solver.factorize(a.as_ref());
        assert_eq!(solver.negative_pivots(), Some(m), "LDLT below sigma = {sigma}");
        solver.factorize_pivoted(a.as_ref());
        assert_eq!(solver.negative_pivots(), Some(m), "LBLT below sigma = {sigma}");
    }
}

/// `u = eps grad phi` with `phi = e^X sin Y` harmonic: a body-force-free solution of linear
/// elasticity for any Lame constants, hence of the hyperelastic problem as `eps -> 0`.
fn small_strain_solution(eps: f64) -> impl Fn([f64; 2]) -> [f64; 2] {
    move |[x, y]| [eps * x.exp() * y.sin(), eps * x.exp() * y.cos()]
}

#[test]
fn q2_displacement_converges_at_third_order_in_l2() {
    let exact = small_strain_solution(1e-7);
    let settings = NewtonPolicy {
        absolute_tolerance: 0.0,
        update_tolerance: 0.0,
        // Round-off of P at strains of 1e-7 limits the attainable relative residual.
        residual_tolerance: 1e-8,
        ..NewtonPolicy::default()
    };
    for element in [ElementKind::Displacement, ElementKind::Mixed] {
        let errors: Vec<f64> = [2, 4, 8, 16]
            .iter()
            .map(|&n| {
                // Unit square elements of size 1/n over [0, 1] x [-1, 1], both regions alike.
                let spec = MeshSpec::new(n, n, n, 1.0 / n as f64, 1.0, 1.0).with_element(element);
                let mesh = Mesh::new(spec).unwrap();
                let bc = boundary_values(&mesh, &exact);
                let mut system = System::new(mesh, &homogeneous_material()).unwrap();
                let mut u = vec![0.0; system.num_dofs()];
                equilibrium::solve(&mut Newton::new(), &mut system, &mut u, &bc, &settings).unwrap();
                error_norms(&system, &u, &exact, &|_| [0.0; 4]).relative_l2()
            })
            .collect();
        let rates: Vec<f64> = errors.windows(2).map(|w| (w[0] / w[1]).log2()).collect();
        println!("{element:?}: relative L2 errors {}, rates {rates:?}", list(&errors));
        assert!(rates.iter().all(|&r| r > 2.9), "{element:?}: rates {rates:?}");
    }
}

#[test]
fn inverting_load_is_an_error_and_leaves_the_state_unchanged() {
    let mesh = Mesh::new(MeshSpec::new(2, 1, 1, 2.0, 2.0, 2.0)).unwrap();
    let mut system = System::new(mesh.clone(), &Bilayer::new(&Parameters::default())).unwrap();
    // The boundary reflected (F = diag(-1/2, 1)): no deformation with J > 0 matches it.
    let bc = boundary_values(&mesh, |[x, _]| [-1.5 * x, 0.0]);
    let mut u = vec![0.0; mesh.num_dofs()];
    let settings = NewtonPolicy {
        max_iterations: 15,
        ..NewtonPolicy::default()
    };
    let error = equilibrium::solve(&mut Newton::new(), &mut system, &mut u, &bc, &settings).unwrap_err();
    println!("{error}");
    assert!(matches!(
        error,
        NewtonError::Inadmissible { .. } | NewtonError::NotConverged { .. } | NewtonError::LineSearch { .. }
    ));
    assert!(!error.to_string().contains("NaN"));
    assert!(u.iter().all(|&v| v == 0.0));
}

/// Wall times of one Newton iteration's phases on the coarse and fine meshes (a benchmark,
/// not a check): `cargo test --release --test fem -- --ignored --nocapture`.
#[test]
#[ignore]
fn timing_of_one_newton_iteration() {
    use fiberfold::fem::SparseLdlt;
    use std::time::Instant;
    let median = |mut t: Vec<f64>| {
        t.sort_by(f64::total_cmp);
        t[t.len() / 2]
    };
    for (name, spec) in [("coarse", MeshSpec::coarse()), ("fine", MeshSpec::fine())] {
        let mesh = Mesh::new(spec).unwrap();
        let mut system = System::new(mesh.clone(), &Bilayer::new(&Parameters::default())).unwrap();
        let bc = model_conditions(&mesh, 0.02).unwrap();
        let u: Vec<f64> = (0..mesh.num_dofs())
            .map(|i| {
                if mesh.dofs().component(i) == X {
                    -0.02 * mesh.coordinates()[mesh.dofs().node(i)][0]
                } else {
                    0.0
                }
            })
            .collect();
        let start = Instant::now();
        let first = system.assemble(&u, &bc, None, true).unwrap();
        let with_pattern = start.elapsed().as_secs_f64();
        let k = first.tangent.unwrap();
        let mut solver = SparseLdlt::new(k.symbolic());
        let (mut assembly, mut factor, mut solve) = (vec![], vec![], vec![]);
        for _ in 0..5 {
            let a = system.assemble(&u, &bc, None, true).unwrap();
            assembly.push(a.elapsed.as_secs_f64());
            solver.factorize(a.tangent.as_ref().unwrap().as_ref());
            factor.push(solver.factorisation_time().as_secs_f64());
            let mut x = a.residual.clone();
            solver.solve_in_place(&mut x).unwrap();
            solve.push(solver.solve_time().as_secs_f64());
        }
        println!(
            "{name}: {} free unknowns, nnz(K) {}, factor values {}; first assembly with pattern {with_pattern:.3} s, \
             symbolic {:.3} s; median of 5: assembly {:.3} s, LDLT {:.3} s, solve {:.4} s; negative pivots {:?}",
            k.nrows(),
            k.compute_nnz(),
            solver.factor_size(),
            solver.symbolic_time().as_secs_f64(),
            median(assembly),
            median(factor),
            median(solve),
            solver.negative_pivots(),
        );
        let mut u = vec![0.0; mesh.num_dofs()];
        let report =
            equilibrium::solve(&mut Newton::new(), &mut system, &mut u, &bc, &NewtonPolicy::default()).unwrap();
        println!(
            "{name}: Newton at d = 0.02 from rest: {} iterations, residuals {}, {:?}",
            report.iterations,
            list(&report.residual_history),
            report.timings
        );
    }
}
