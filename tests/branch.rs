//! Leaving the unstable periodic wrinkle: on a domain of four waves the periodic path loses
//! stability (the tangent gains a negative eigenvalue). A small long-wave imperfection of the
//! reference geometry (`A_2 = 0.01`, 1.5 waves across the domain) breaks the symmetry: the run
//! ends with one trough much deeper than the others, and with less strain energy than the
//! periodic path at the same compression (an unstable state is not a minimum).
//! Along both paths, the inertia a step reports (read from the factorisation at its predictor
//! wherever that is the same energy's) is the exact inertia of the converged state's tangent.

use fiberfold::fem::added::NoAddedEnergy;
use fiberfold::fem::{ElementKind, Newton, System};
use fiberfold::material::Bilayer;
use fiberfold::mesh::MeshSpec;
use fiberfold::protocol::model_conditions;
use fiberfold::protocol::secondary::{branch, BranchKind};
use fiberfold::protocol::{stages, Event, Protocol, StepRecord};
use fiberfold::Parameters;
use std::f64::consts::{FRAC_PI_4, PI};

/// The records, branch kind and trough depths of a run to `d_max` on `L = D = 40`
/// (80 x (2 + 12) displacement elements) seeded with four waves, beta = pi/4, and the long-wave
/// imperfection `(A_2, N_2)`. (With the mixed element the inertia is read at the predictor at
/// 34 of 200 states, against the quarter asserted below.)
fn four_wave_run(d_max: f64, (a2, n2): (f64, f64)) -> (Vec<StepRecord>, BranchKind, Vec<f64>) {
    let params = Parameters {
        beta: FRAC_PI_4,
        ..Parameters::default()
    };
    four_wave_run_of(&params, d_max, (a2, n2))
}

/// [`four_wave_run`] of the bilayer `params`.
fn four_wave_run_of(params: &Parameters, d_max: f64, (a2, n2): (f64, f64)) -> (Vec<StepRecord>, BranchKind, Vec<f64>) {
    let k = 2.0 * PI * 4.0 / 40.0;
    let mut protocol = Protocol::new(k, 0.05, d_max).with_crease_path();
    protocol.newton.inertia_at_solution = true;
    protocol.imperfection2 = a2;
    protocol.imperfection2_waves = n2;
    let (mut records, mut exact) = (Vec::new(), Newton::new());
    let materials = Bilayer::new(params);
    let outcome = stages::run(
        &materials,
        MeshSpec::new(80, 2, 12, 0.5, 40.0, 40.0).with_element(ElementKind::Displacement),
        &protocol,
        &mut |event| {
            if let Event::Step { record, system, u } = event {
                // Away from contact the tangent of the inertia is the elastic one.
                if !record.augmented.as_ref().is_some_and(|a| a.in_contact) {
                    let mut elastic = System::new(system.mesh().clone(), &materials)?;
                    let bc = model_conditions(system.mesh(), record.d)?;
                    let count = exact
                        .inertia(&mut elastic, u, &bc, &NoAddedEnergy, &mut Default::default())
                        .unwrap();
                    assert_eq!(record.negative_pivots, count, "inertia at d = {}", record.d);
                }
                records.push(record.clone());
            }
            Ok(())
        },
    )
    .unwrap();
    assert!(outcome.stopped.is_none(), "{:?}", outcome.stopped);
    let from_predictor = records
        .iter()
        .filter(|r| r.augmented.as_ref().is_some_and(|a| a.inertia_seconds == 0.0))
        .count();
    // Every undamped step without contact forces: most of the smooth path before the snap.
    println!(
        "inertia read at the predictor at {from_predictor} of {} states",
        records.len()
    );
    assert!(
        4 * from_predictor > records.len(),
        "{from_predictor} of {}",
        records.len()
    );
    let c = &outcome.continuation;
    let b = branch(c.system().mesh(), c.displacement(), k, protocol.imperfection);
    (records, b.kind, b.trough_depths)
}

#[test]
fn a_long_wave_imperfection_leaves_the_unstable_periodic_path_for_a_lower_energy() {
    let d_max = 0.26;
    let (periodic, kind, depths) = four_wave_run(d_max, (0.0, 0.5));
    let unstable_from = periodic.iter().find(|r| r.negative_pivots.unwrap() > 0).map(|r| r.d);
    println!("periodic: {kind:?} {depths:?}, unstable from d = {unstable_from:?}");
    assert_eq!(kind, BranchKind::Periodic);
    assert!(
        unstable_from.is_some_and(|d| d < d_max - 0.02),
        "the periodic path loses stability"
    );

    let (seeded, kind, depths) = four_wave_run(d_max, (0.01, 1.5));
    println!("seeded: {kind:?} {depths:?}");
    assert_eq!(kind, BranchKind::Localised);
    let (a, b) = (periodic.last().unwrap(), seeded.last().unwrap());
    assert_eq!(a.d, b.d);
    println!(
        "strain energy at d = {}: periodic {}, seeded {}",
        a.d, a.strain_energy, b.strain_energy
    );
    assert!(b.strain_energy < a.strain_energy);
    assert!(seeded.iter().all(|r| r.min_jacobian > 0.0));
}

/// A soft layer (mu_l = 3 mu_s) wrinkles near a limit point, where one step's predictor lies a
/// tenth of a step from its solution and an eigenvalue changes sign in between: the inertia is
/// then that of the solution (counted again), not the predictor's.
#[test]
fn the_inertia_is_the_solutions_where_the_predictor_was_far() {
    let params = Parameters {
        beta: FRAC_PI_4,
        mu_l: 3.0,
        K_l: 9.0,
        ..Parameters::default()
    };
    let (records, _, _) = four_wave_run_of(&params, 0.33, (0.0, 0.5));
    let unstable_from = records.iter().find(|r| r.negative_pivots.unwrap() > 0).map(|r| r.d);
    println!("unstable from d = {unstable_from:?} ({} states)", records.len());
    assert!(unstable_from.is_some());
}
