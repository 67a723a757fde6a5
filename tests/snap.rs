//! A snap with a known answer, by the machinery of the snaps of a simulation: a bistable
//! element `(x^2 - 1)^2 / 4` on one unknown `x` in series with a linear spring of stiffness `k`
//! to a prescribed unknown `g`, `E(x; g) = (x^2 - 1)^2 / 4 + k (x - g)^2 / 2`, added to the
//! strain energy of a mesh whose boundary is held and whose moduli are negligible (`1e-9`, so
//! that the elastic energy of the moves below is below `1e-8`).
//!
//! Equilibrium is `x^3 - x + k (x - g) = 0`. The branch through `x = -1` at `g = -1` ends at
//! the limit point where also `3 x^2 - 1 + k = 0`: `x* = -sqrt((1 - k) / 3)`,
//! `g* = x* + (x*^3 - x*) / k`. Beyond `g*` the only equilibrium is on the far branch, the
//! largest root of the cubic; the structure snaps there, releasing `E(x*; g) - E(x_far; g)`.

mod common;

use fiberfold::fem::added::{AddedEnergy, Block};
use fiberfold::fem::{equilibrium, Dirichlet, Newton, NewtonPolicy, System};
use fiberfold::material::Bilayer;
use fiberfold::mesh::{Mesh, MeshSpec, X};
use fiberfold::Parameters;

/// The bistable element and its spring: one group, `[x, g]`.
struct BistableChain {
    groups: Vec<Vec<usize>>,
    k: f64,
}

impl BistableChain {
    fn energy(&self, x: f64, g: f64) -> f64 {
        (x * x - 1.0).powi(2) / 4.0 + self.k * (x - g).powi(2) / 2.0
    }
}

impl AddedEnergy for BistableChain {
    fn groups(&self) -> &[Vec<usize>] {
        &self.groups
    }

    fn block(&self, _: usize, u: &[f64], with_tangent: bool) -> Block {
        let (x, g, k) = (u[self.groups[0][0]], u[self.groups[0][1]], self.k);
        Block {
            energy: self.energy(x, g),
            gradient: vec![x * x * x - x + k * (x - g), -k * (x - g)],
            hessian: if with_tangent {
                vec![3.0 * x * x - 1.0 + k, -k, -k, k]
            } else {
                Vec::new()
            },
        }
    }
}

/// The largest root of `x^3 - x + k (x - g)` by bisection (an independent scalar solve).
fn far_root(k: f64, g: f64) -> f64 {
    let f = |x: f64| x * x * x - x + k * (x - g);
    let (mut a, mut b) = (0.0, 10.0);
    assert!(f(a) < 0.0 && f(b) > 0.0);
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        if f(m) > 0.0 {
            b = m
        } else {
            a = m
        }
    }
    0.5 * (a + b)
}

/// A mesh of negligible stiffness, large enough that moving its middle node by up to 2 keeps
/// every Jacobian positive: `x` is that node's `u_x`, and the spring's prescribed end `g` is
/// the `u_x` of a corner node.
fn chain(k: f64) -> (System, BistableChain, usize, usize) {
    let soft = Parameters {
        mu_l: 1e-9,
        K_l: 1e-9,
        mu_s: 1e-9,
        K_s: 1e-9,
        mu_f: 0.0,
        ..Parameters::default()
    };
    let mesh = Mesh::new(MeshSpec::new(4, 1, 4, 25.0, 100.0, 100.0)).unwrap();
    let centre = (0..mesh.coordinates().len())
        .min_by(|&a, &b| {
            let distance = |n: usize| (mesh.coordinates()[n][0] - 50.0).hypot(mesh.coordinates()[n][1] + 50.0);
            distance(a).total_cmp(&distance(b))
        })
        .unwrap();
    let corner = mesh.top()[0];
    let (x, g) = (mesh.dofs().dof(centre, X), mesh.dofs().dof(corner, X));
    let system = System::new(mesh, &Bilayer::new(&soft)).unwrap();
    let added = BistableChain {
        groups: vec![vec![x, g]],
        k,
    };
    (system, added, x, g)
}

/// The boundary held at zero, `g` at its value; the interior (with `x`) free.
fn held(system: &System, g: (usize, f64)) -> Dirichlet {
    let on_boundary = |[x, y]: [f64; 2]| x == 0.0 || x == 100.0 || y == -100.0 || y == 1.0;
    let pairs = (0..system.num_dofs())
        .filter(|&d| on_boundary(system.mesh().coordinates()[system.mesh().dofs().node(d)]))
        .map(|d| (d, if d == g.0 { g.1 } else { 0.0 }))
        .collect();
    Dirichlet::new(pairs).unwrap()
}

#[test]
fn a_bistable_chain_snaps_past_its_limit_point_to_the_far_branch_releasing_the_closed_form_energy() {
    let k = 0.2;
    let x_star = -((1.0 - k) / 3.0f64).sqrt();
    let g_star = x_star + (x_star.powi(3) - x_star) / k;
    let (mut system, added, x, g) = chain(k);
    let mut u = vec![0.0; system.num_dofs()];
    u[x] = -1.0;
    let mut newton = Newton::new();
    let policy = NewtonPolicy::default();
    // Along the near branch by Newton's method, to just short of the limit point: stable.
    let mut load = -1.0;
    while load < g_star - 1e-3 {
        load = (load + 0.05).min(g_star - 1e-3);
        u[g] = load;
        let bc = held(&system, (g, load));
        let report = equilibrium::solve_with(&mut newton, &mut system, &mut u, &bc, &added, &policy).unwrap();
        assert_eq!(report.negative_pivots, Some(0), "near branch at g = {load}");
        assert!(u[x] < x_star, "still on the near branch at g = {load}: x = {}", u[x]);
    }
    // Past it, the minimisation from the last state lands on the far branch.
    let beyond = g_star + 1e-3;
    let before = u[x];
    u[g] = beyond;
    let bc = held(&system, (g, beyond));
    let start_energy = added.energy(before, beyond);
    let report = equilibrium::minimise(&mut newton, (&mut system, &mut u, &bc), None, &added, &policy).unwrap();
    let far = far_root(k, beyond);
    println!(
        "g* = {g_star:.6}: x {before:.6} -> {:.9} (far root {far:.9}), {} steps",
        u[x], report.iterations
    );
    assert!((u[x] - far).abs() < 1e-6, "x = {} against the far root {far}", u[x]);
    assert_eq!(report.negative_pivots, Some(0), "a stable state");
    let released = start_energy - added.energy(u[x], beyond);
    let exact = added.energy(before, beyond) - added.energy(far, beyond);
    assert!(released > 0.1, "a snap releases energy: {released}");
    assert!(
        (released - exact).abs() < 1e-6,
        "released {released} against the closed form {exact}"
    );
    // The energy never rose along the minimisation: its residual history ends within
    // tolerance and the state is the far branch's, whose energy is below the start's.
    assert!(added.energy(u[x], beyond) < start_energy);
}

/// A minimisation with a largest move (`NewtonPolicy::max_move`, what a continuation's
/// correction of a failed step allows) gives up once it has moved that far, and leaves the
/// state as it was; with room enough it reaches the same far branch as without a limit.
#[test]
fn a_minimisation_gives_up_beyond_its_largest_move_and_leaves_the_state() {
    let k = 0.2;
    let x_star = -((1.0 - k) / 3.0f64).sqrt();
    let beyond = x_star + (x_star.powi(3) - x_star) / k + 1e-3;
    let (mut system, added, x, g) = chain(k);
    let bc = held(&system, (g, beyond));
    let mut start = vec![0.0; system.num_dofs()];
    (start[x], start[g]) = (x_star, beyond);
    let far = far_root(k, beyond);
    for (limit, reaches) in [(0.3, false), (10.0, true)] {
        let policy = NewtonPolicy {
            max_move: Some(limit),
            ..NewtonPolicy::default()
        };
        let mut u = start.clone();
        let result = equilibrium::minimise(&mut Newton::new(), (&mut system, &mut u, &bc), None, &added, &policy);
        println!(
            "limit {limit}: {:?}, x = {}",
            result.as_ref().map(|r| r.iterations),
            u[x]
        );
        match reaches {
            true => {
                assert!(result.is_ok());
                assert!((u[x] - far).abs() < 1e-6, "x = {} against the far root {far}", u[x]);
            }
            false => {
                let message = result.expect_err("the far root lies beyond the limit").to_string();
                assert!(message.contains("moved beyond"), "{message}");
                assert_eq!(u, start, "the state is left as it was");
            }
        }
    }
    assert!((far - x_star).abs() > 0.3, "the far root lies beyond the small limit");
}

/// From a saddle (the maximum of the bistable element between its wells, `x = 0` at `g = 0`,
/// where the residual is zero), the minimisation leaves along the negative curvature and
/// ends in a well: a minimum with the closed-form energy `E(x_well; 0)`.
#[test]
fn the_minimisation_leaves_a_saddle_along_its_negative_curvature() {
    let k = 0.2;
    let (mut system, added, x, g) = chain(k);
    let mut u = vec![0.0; system.num_dofs()];
    let bc = held(&system, (g, 0.0));
    let report = equilibrium::minimise(
        &mut Newton::new(),
        (&mut system, &mut u, &bc),
        None,
        &added,
        &NewtonPolicy::default(),
    )
    .unwrap();
    // Wells of x^3 - x + k x = 0: x = +-sqrt(1 - k).
    let well = (1.0 - k).sqrt();
    assert!((u[x].abs() - well).abs() < 1e-6, "x = {} against +-{well}", u[x]);
    assert_eq!(report.negative_pivots, Some(0));
    assert!(added.energy(u[x], 0.0) < added.energy(0.0, 0.0));
}

/// The coarse compare case with the mixed element follows the periodic branch to its fold near
/// d = 0.2402 and snaps there, onto a closed trough. Every recorded state is checked by an
/// independent assembly on a fresh system: its undamped elastic residual is within Newton's
/// tolerance off the nodes the contact pushes, and, without contact, the inertia of a fresh
/// factorisation is the one reported. Every snap releases energy and ends on a stable state
/// in contact.
#[test]
fn every_state_of_a_run_through_a_snap_is_an_undamped_equilibrium_with_the_reported_inertia() {
    use fiberfold::fem::added::NoAddedEnergy;
    use fiberfold::fem::ElementKind;
    use fiberfold::protocol::model_conditions;
    use fiberfold::protocol::{stages, Event};
    use fiberfold::studies::simulate::{Crossing, MeshChoice, SimulateOptions};

    let params = Parameters {
        beta: std::f64::consts::FRAC_PI_4,
        ..Parameters::default()
    };
    let study = SimulateOptions {
        mesh: MeshChoice {
            element: ElementKind::Mixed,
            ..MeshChoice::default()
        },
        waves: Some(4.5),
        d_max: 0.25,
        crossing: Crossing::Snap,
        ..SimulateOptions::default()
    }
    .study()
    .unwrap();
    let materials = Bilayer::new(&params);
    let policy = NewtonPolicy::default();
    let (mut checked, mut snaps, mut worst, mut in_contact) = (0, Vec::new(), 0.0f64, 0);
    let outcome = stages::run(&materials, study.mesh, &study.protocol, &mut |event| {
        let Event::Step { record, system, u } = event else {
            return Ok(());
        };
        // The nodes the contact pushes carry its force: the elastic residual balances it there,
        // and vanishes everywhere else.
        let pushed = record
            .augmented
            .as_ref()
            .is_some_and(|a| a.pressure.iter().any(|(_, p)| *p != 0.0));
        in_contact += usize::from(pushed);
        let (residual, tolerance) = common::undamped_residual(&materials, (record, system, u), &policy);
        worst = worst.max(residual / tolerance);
        assert!(
            residual <= tolerance,
            "d = {}: undamped residual {residual:.3e} off the contact above the tolerance {tolerance:.3e}",
            record.d,
        );
        // Without contact the tangent is the elastic one, whose inertia is counted afresh.
        if let (Some(reported), false) = (record.negative_pivots, pushed) {
            let mut fresh = System::new(system.mesh().clone(), &materials)?;
            let bc = model_conditions(system.mesh(), record.d)?;
            let counted = Newton::new().inertia(&mut fresh, u, &bc, &NoAddedEnergy, &mut Default::default())?;
            assert_eq!(counted, Some(reported), "inertia at d = {}", record.d);
        }
        if let Some(snap) = &record.snap {
            snaps.push(snap.clone());
        }
        checked += 1;
        Ok(())
    })
    .unwrap();
    assert!(outcome.stopped.is_none(), "{:?}", outcome.stopped);
    println!("{checked} states ({in_contact} in contact), largest residual / tolerance {worst:.2}; snaps {snaps:#?}");
    assert!(!snaps.is_empty(), "the fold is crossed by a snap");
    for snap in &snaps {
        assert!(snap.energy_released > 0.0, "{snap:?}");
        assert_eq!(snap.negative_pivots_after, Some(0));
        assert!(snap.amplitude_after > snap.amplitude_before);
    }
    assert!(in_contact > 0, "the snap closes a trough");
}

/// The onset is read off the branch the path starts on, before its first snap: a snap's jump of
/// `A` within a step of `1e-6` gives a slope of millions, which drowned the peak of `A'` near the
/// onset (the coarse Fig. 7 case had reported `d_steepest` at its snap, 0.2567). A run through
/// the snap gives the estimates of the same run stopped well before it.
#[test]
fn a_run_through_a_snap_reads_its_onset_off_the_branch_before_the_snap() {
    let onset = |d_max: &str| -> serde_json::Value {
        let out = common::scratch(&format!("onset-snap-{d_max}"));
        let args = [
            "simulate",
            "--set",
            "beta=0.785398",
            "--waves",
            "5",
            "--mesh",
            "coarse",
            "--stabilisation",
            "snap",
            "--d-max",
            d_max,
            "--out",
            out.to_str().unwrap(),
        ];
        let run = common::fiberfold(&args);
        assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
        let snaps: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("snaps.json")).unwrap_or("[]".into())).unwrap();
        let onset: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("onset_estimates.json")).unwrap()).unwrap();
        serde_json::json!({ "onset": onset, "snaps": snaps })
    };
    let (through, before) = (onset("0.26"), onset("0.2"));
    println!("{through:#}");
    assert!(
        through["snaps"].to_string().contains("energy_released"),
        "the run to 0.26 snaps: {}",
        through["snaps"]
    );
    for estimate in ["d_max_curvature", "d_steepest", "d_a2_fit"] {
        let (a, b) = (through["onset"][estimate].as_f64(), before["onset"][estimate].as_f64());
        assert!(
            a.zip(b).is_some_and(|(a, b)| (a - b).abs() < 1e-12),
            "{estimate}: {a:?} through the snap, {b:?} before it"
        );
    }
    let steepest = through["onset"]["d_steepest"].as_f64().unwrap();
    let theory = through["onset"]["d_linear_theory"].as_f64().unwrap();
    assert!(
        (steepest - theory).abs() < 0.01,
        "{steepest} against the linear theory's {theory}"
    );
}

/// A minimisation that no step can take further, at a definite tangent and a residual within
/// ten times its tolerance, has reached the round-off floor of a minimum: it is accepted. Far
/// above the floor's tolerance (a tolerance no arithmetic reaches) it is a failure that says
/// why.
#[test]
fn a_minimisation_stalled_at_the_round_off_floor_of_its_residual_is_a_minimum() {
    let k = 0.2;
    let (mut system, added, x, g) = chain(k);
    let bc = held(&system, (g, 0.0));
    let strict = NewtonPolicy {
        residual_tolerance: 0.0,
        absolute_tolerance: 1e-300,
        ..NewtonPolicy::default()
    };
    let mut u = vec![0.0; system.num_dofs()];
    let message = equilibrium::minimise(&mut Newton::new(), (&mut system, &mut u, &bc), None, &added, &strict)
        .expect_err("no arithmetic reaches 1e-300")
        .to_string();
    assert!(message.contains("no shift up to"), "{message}");
    let floor: f64 = message
        .split("residual at ")
        .nth(1)
        .and_then(|rest| rest.split(' ').next())
        .and_then(|r| r.parse().ok())
        .expect("the residual in the message");
    // The same steps stall at the same residual, now within ten times the tolerance.
    let policy = NewtonPolicy {
        absolute_tolerance: floor / 5.0,
        ..strict
    };
    let mut u = vec![0.0; system.num_dofs()];
    let report = equilibrium::minimise(&mut Newton::new(), (&mut system, &mut u, &bc), None, &added, &policy)
        .expect("a minimum at the round-off floor");
    assert_eq!(report.negative_pivots, Some(0));
    assert!((u[x].abs() - (1.0 - k).sqrt()).abs() < 1e-6, "x = {}", u[x]);
}
