//! Contact of the top surface against independent facts: the gradient and Hessian of the
//! contact energy against central differences, the patch test (a flat surface pressed on a
//! rigid plane, i.e. on its mirror image across a symmetry plane, carries a uniform pressure
//! equal to the Cauchy stress below it), and the augmented-Lagrangian loop driving a soft
//! penalty's penetration below the tolerance.

use fiberfold::fem::added::AddedEnergy;
mod common;

use common::homogeneous_material;
use fiberfold::fem::contact::{Contact, ContactSettings, End, Pair, Plane};
use fiberfold::fem::equilibrium::solve_with_contact;
use fiberfold::fem::fields::cell_fields;
use fiberfold::fem::{Dirichlet, Newton, NewtonPolicy, System};
use fiberfold::mesh::{Mesh, MeshSpec, X, Y};

/// Energy and gradient (all unknowns) of an added energy at `u`.
fn energy_and_gradient(added: &dyn AddedEnergy, u: &[f64]) -> (f64, Vec<f64>) {
    let mut gradient = vec![0.0; u.len()];
    let mut energy = 0.0;
    for (g, dofs) in added.groups().iter().enumerate() {
        let block = added.block(g, u, false);
        energy += block.energy;
        for (&d, v) in dofs.iter().zip(&block.gradient) {
            gradient[d] += v;
        }
    }
    (energy, gradient)
}

/// `H v` of an added energy at `u`.
fn hessian_times(added: &dyn AddedEnergy, u: &[f64], v: &[f64]) -> Vec<f64> {
    let mut hv = vec![0.0; u.len()];
    for (g, dofs) in added.groups().iter().enumerate() {
        let h = added.block(g, u, true).hessian;
        let n = dofs.len();
        for (a, &da) in dofs.iter().enumerate() {
            hv[da] += (0..n).map(|b| h[a * n + b] * v[dofs[b]]).sum::<f64>();
        }
    }
    hv
}

#[test]
fn contact_force_and_tangent_match_central_differences() {
    // A V-shaped trough at X = 1.5 whose flanks cross near the tip, and a node pushed through
    // the left symmetry plane: both kinds of pair, penetrating, with non-zero multipliers.
    let mesh = Mesh::new(MeshSpec::new(6, 1, 2, 0.5, 3.0, 2.0)).unwrap();
    let mut u = vec![0.0; mesh.num_dofs()];
    for &n in &mesh.top() {
        let x = mesh.coordinates()[n][0];
        let s = (x - 1.5).abs();
        let side = (x - 1.5).signum();
        if s < 1.2 {
            u[mesh.dofs().dof(n, X)] = 1.5 + side * (0.1 * s - 0.04 + 0.003 * x * x) - x;
            u[mesh.dofs().dof(n, Y)] = -2.0 * (1.2 - s) + 0.01 * x;
        }
    }
    u[mesh.dofs().dof(mesh.top()[1], X)] = -0.26;
    let settings = ContactSettings {
        penalty: 50.0,
        tolerance: 1e-3,
        search_distance: 0.5,
        max_augmentations: 10,
        self_contact: true,
    };
    let mut contact = Contact::new(&mesh, vec![Plane::left(0.0)], settings);
    contact.search(&u);
    let pairs = contact.pairs().to_vec();
    assert!(
        pairs.iter().any(|p| matches!(p, Pair::Plane { slave: 1, .. })),
        "{pairs:?}"
    );
    assert!(
        pairs.iter().filter(|p| matches!(p, Pair::Segment { .. })).count() >= 4,
        "{pairs:?}"
    );
    assert!(contact.penetration(&u) > 0.01);
    contact.augment(&u);
    assert!(!contact.loaded_pairs(&u).is_empty());

    let (_, gradient) = energy_and_gradient(&contact, &u);
    let v: Vec<f64> = (0..u.len()).map(|i| ((i as f64) * 0.618).sin()).collect();
    let h = 1e-6;
    let shifted = |s: f64| -> Vec<f64> { u.iter().zip(&v).map(|(a, b)| a + s * h * b).collect() };
    let (plus, minus) = (
        energy_and_gradient(&contact, &shifted(1.0)),
        energy_and_gradient(&contact, &shifted(-1.0)),
    );
    let slope: f64 = gradient.iter().zip(&v).map(|(g, w)| g * w).sum();
    let fd_slope = (plus.0 - minus.0) / (2.0 * h);
    assert!(
        (fd_slope - slope).abs() < 1e-6 * slope.abs().max(1.0),
        "{fd_slope} vs {slope}"
    );
    let hv = hessian_times(&contact, &u, &v);
    let scale = hv.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    for (i, value) in hv.iter().enumerate() {
        let fd = (plus.1[i] - minus.1[i]) / (2.0 * h);
        assert!((fd - value).abs() < 1e-6 * scale, "unknown {i}: {fd} vs {value}");
    }
}

/// A block `[0, 2] x [-2, 1]` with rollers on both sides and the bottom, pressed down by the
/// rigid plane `y <= 1 - 0.02` (its normal `(0, -1)` points into the open side): the exact
/// solution is a uniform uniaxial strain, so the contact pressure must be uniform.
fn pressed_block(penalty: f64) -> (System, Vec<f64>, Contact, usize, Newton) {
    let mesh = Mesh::new(MeshSpec::new(4, 2, 3, 0.5, 2.0, 2.0)).unwrap();
    let materials = homogeneous_material();
    let mut pairs: Vec<(usize, f64)> = mesh
        .left()
        .into_iter()
        .chain(mesh.right())
        .map(|n| (mesh.dofs().dof(n, X), 0.0))
        .collect();
    pairs.extend(mesh.bottom().into_iter().map(|n| (mesh.dofs().dof(n, Y), 0.0)));
    let bc = Dirichlet::new(pairs).unwrap();
    let plane = Plane {
        normal: [0.0, -1.0],
        offset: -(1.0 - 0.02),
        holds: None::<End>,
    };
    let settings = ContactSettings {
        penalty,
        tolerance: 1e-3,
        search_distance: 0.5,
        max_augmentations: 20,
        self_contact: false,
    };
    let contact = Contact::new(&mesh, vec![plane], settings);
    let mut system = System::new(mesh, &materials).unwrap();
    let mut u = vec![0.0; system.num_dofs()];
    let mut newton = Newton::new();
    let mut contact = contact;
    let solved = solve_with_contact(
        &mut newton,
        &mut system,
        &mut u,
        &bc,
        &mut contact,
        &fiberfold::fem::added::NoAddedEnergy,
        &NewtonPolicy::default(),
    )
    .unwrap();
    (system, u, contact, solved.updates.contact + 1, newton)
}

#[test]
fn a_surface_pressed_on_a_plane_carries_a_uniform_pressure_equal_to_the_stress_below() {
    let (system, u, contact, _, _) = pressed_block(1e4);
    let state = contact.state(&u);
    let p = &state.pressure;
    let mean = p.iter().sum::<f64>() / p.len() as f64;
    let spread = p.iter().fold(0.0f64, |m, x| m.max((x - mean).abs()));
    println!(
        "pressure {mean:.8} (spread {spread:.2e}), penetration {:.2e}",
        state.penetration
    );
    assert!(mean > 0.01, "the plane presses: {mean}");
    assert!(spread <= 1e-6 * mean, "uniform to 1e-6: spread {spread:e}");
    assert!(state.penetration <= 1e-3);
    // The surface does not stretch (rollers), so the nominal pressure is the Cauchy -sigma_22.
    let fields = cell_fields(&system, &homogeneous_material(), &u).unwrap();
    for sigma in &fields.cauchy {
        assert!(
            (sigma[2] + mean).abs() <= 1e-8 * mean,
            "sigma_22 {} vs -p {}",
            sigma[2],
            -mean
        );
    }
    assert!(state.in_contact && (state.contact_length - 2.0).abs() < 1e-12 && state.zones == 1);
}

#[test]
fn multiplier_updates_bring_a_soft_penalty_within_the_tolerance() {
    // eps = 2: the pure penalty would let the surface sink by p / eps ~ 0.01 >> 1e-3.
    let (_, u, contact, augmentations, _) = pressed_block(2.0);
    let penetration = contact.penetration(&u);
    println!("{augmentations} Newton solves, penetration {penetration:.2e}");
    assert!(augmentations > 2, "Uzawa's updates were needed: {augmentations}");
    assert!(penetration <= 1e-3);
    // The multiplier converged to the pressure of the stiff-penalty solution.
    let (_, stiff_u, stiff, _, _) = pressed_block(1e4);
    let (soft_p, stiff_p) = (contact.state(&u).pressure[3], stiff.state(&stiff_u).pressure[3]);
    assert!((soft_p - stiff_p).abs() < 0.05 * stiff_p, "{soft_p} vs {stiff_p}");
}

#[test]
fn the_line_search_starts_where_the_first_open_pair_closes() {
    // Top node 1 (X = 0.25) faces the left plane x >= 0; its gap x is linear in u, so the
    // fraction of a move at which the pressure argument s = lambda - eps g reaches 0 is exact.
    let mesh = Mesh::new(MeshSpec::new(6, 1, 2, 0.5, 3.0, 2.0)).unwrap();
    let node = mesh.top()[1];
    let settings = ContactSettings {
        penalty: 50.0,
        tolerance: 1e-3,
        search_distance: 0.5,
        max_augmentations: 10,
        self_contact: false,
    };
    let mut contact = Contact::new(&mesh, vec![Plane::left(0.0)], settings);
    let at = |x: f64| {
        let mut u = vec![0.0; mesh.num_dofs()];
        u[mesh.dofs().dof(node, X)] = x - 0.25;
        u
    };
    contact.search(&at(0.01));
    assert!(contact.pairs().contains(&Pair::Plane { slave: 1, plane: 0 }));
    // Open at x = 0.01, through the plane at x = -0.03: closes a quarter of the way.
    let fraction = contact.switch_on_fraction(&at(0.01), &at(-0.03));
    assert!((fraction - 0.25).abs() < 1e-14, "{fraction}");
    // The same through a sum of energies.
    let sum = fiberfold::fem::added::Sum::new(vec![&contact, &fiberfold::fem::added::NoAddedEnergy]);
    assert_eq!(sum.switch_on_fraction(&at(0.01), &at(-0.03)), fraction);
    // Opening further, or stopping short of the plane: the full step.
    assert_eq!(contact.switch_on_fraction(&at(0.01), &at(0.2)), 1.0);
    assert_eq!(contact.switch_on_fraction(&at(0.01), &at(0.001)), 1.0);
    // A pair already pressed at the start is in the tangent: no limit.
    assert_eq!(contact.switch_on_fraction(&at(-0.001), &at(-0.03)), 1.0);
    // With a multiplier lambda the pair switches on at g = lambda / eps: here at x = 0.002.
    contact.augment(&at(-0.002));
    let fraction = contact.switch_on_fraction(&at(0.01), &at(-0.03));
    assert!((fraction - 0.008 / 0.04).abs() < 1e-14, "{fraction}");
}
