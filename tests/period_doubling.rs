//! The period doubling of a stiff layer's wrinkles, against the literature: a stiff film's
//! wrinkles double their period at a compressive strain of about 0.17-0.2 (Cao and Hutchinson,
//! J. Appl. Mech. 2012, finite elements; Cai and Fu, Int. J. Non-Linear Mech. 2019, 0.17 for an
//! incompressible neo-Hookean bilayer whose layer is much stiffer than the substrate; observed by
//! Brau et al., Nature Physics 2011). Here an isotropic bilayer of contrast 100, nearly
//! incompressible (K = 100 mu), on a half domain two natural wavelengths long with a trough on
//! each symmetry plane: the only domain between symmetry planes on which every other trough can
//! deepen (with a crest on each plane, the doubled period alternates the crests instead).
//!
//! The periodic wrinkle's first secondary bifurcation is a mode of two half waves across the
//! domain (the doubled period) in that range of strain; seeded with it, the path's troughs
//! alternate deep and shallow.

mod common;

use common::isotropic;
use fiberfold::material::Bilayer;
use fiberfold::parameters::Parameters;
use fiberfold::protocol::secondary::{inertia_changes, BranchKind, InertiaChange};
use fiberfold::protocol::{stages, Event};
use fiberfold::stability::{Method, Onset, StabilityAnalysis};
use fiberfold::studies::simulate::{solve, solve_to_secondary, MeshChoice, SimulateOptions, ToSecondary};

/// Two natural wavelengths of the contrast-100 bilayer, 20 elements each, troughs on the
/// planes, steps of at most 0.001 to `d = 0.25`.
fn two_wavelengths() -> SimulateOptions {
    let onset = StabilityAnalysis::new(&isotropic(100.0), Method::Exact)
        .unwrap()
        .onset()
        .unwrap();
    let wavelength = 2.0 * std::f64::consts::PI / onset.k0;
    println!(
        "k0 = {:.5}, d_c = {:.5}, wavelength {wavelength:.3}",
        onset.k0, onset.d_c
    );
    SimulateOptions {
        mesh: MeshChoice {
            nx: Some(40),
            length: Some(2.0 * wavelength),
            ..MeshChoice::default()
        },
        waves: Some(2.0),
        imperfection: -0.05,
        max_step: 0.001,
        d_max: 0.25,
        ..SimulateOptions::default()
    }
}

/// The isotropic bilayer of contrast 1000 (`K = 100 mu`), its onset, and two natural
/// wavelengths of it, 20 elements each, troughs on the planes, seeded at half the onset's
/// compression, steps of at most 0.001 to `d_max(d_start)`.
fn thousand_times_stiffer(d_max: impl Fn(f64) -> f64) -> (Parameters, Onset, SimulateOptions) {
    let params = isotropic(1000.0);
    let onset = StabilityAnalysis::new(&params, Method::Exact).unwrap().onset().unwrap();
    let length = 2.0 * 2.0 * std::f64::consts::PI / onset.k0;
    let d_start = 0.5 * onset.d_c;
    let options = SimulateOptions {
        mesh: MeshChoice {
            nx: Some(40),
            length: Some(length),
            depth: Some(length),
            ..MeshChoice::default()
        },
        waves: Some(2.0),
        imperfection: -0.05,
        d_start,
        d_max: d_max(d_start),
        max_step: 0.001,
        ..SimulateOptions::default()
    };
    (params, onset, options)
}

#[test]
fn a_stiff_layers_wrinkles_double_their_period_near_a_fifth_compression() {
    let options = two_wavelengths();
    let params = isotropic(100.0);
    let study = options.study().unwrap();
    let ToSecondary::Changed(mode) = solve_to_secondary(&params, &study).unwrap() else {
        panic!("the periodic wrinkle stays stable to d = 0.25");
    };
    println!(
        "first secondary bifurcation at d = {:.4}: {} half waves",
        mode.d, mode.half_waves
    );
    assert_eq!(mode.half_waves, 2, "the doubled period");
    assert!((0.15..0.25).contains(&mode.d), "{}", mode.d);

    let seeded = SimulateOptions {
        imperfection2: 0.01,
        imperfection2_waves: 1.0,
        ..options
    };
    let solution = solve(&params, &seeded.study().unwrap(), &|_| Ok(())).unwrap();
    assert!(solution.curve.stopped.is_none(), "{:?}", solution.curve.stopped);
    let branch = solution.secondary.branch;
    println!("seeded: {:?} {:?}", branch.kind, branch.trough_depths);
    // The troughs on the planes (which the seed lowers) against the one between them.
    let [plane, middle, far_plane] = branch.trough_depths[..] else {
        panic!("three troughs: {:?}", branch.trough_depths);
    };
    assert_eq!(branch.kind, BranchKind::Modulated);
    assert!(plane > middle && far_plane > middle);
}

/// A layer a thousand times stiffer than the substrate wrinkles at `d_c = 0.0052`, next to
/// stage 1's default `d = 0.005`. Seeded at `d_c / 2` instead, its imperfection is beyond one
/// Newton solve from the flat state, and stage 2 grows it in steps. The equilibrium reached is
/// the imperfect bilayer's below its onset: the seeded mode amplified by `1 / (1 - d / d_c)`
/// (the classical amplification of an imperfection in the buckling mode).
#[test]
fn a_layer_a_thousand_times_stiffer_is_seeded_below_its_onset_in_steps() {
    let (params, onset, options) = thousand_times_stiffer(|d_start| d_start + 0.001);
    let d_start = options.d_start;
    let study = options.study().unwrap();
    let mut stages = Vec::new();
    let mut first = None;
    stages::run(&Bilayer::new(&params), study.mesh, &study.protocol, &mut |event| {
        match event {
            Event::Stage(text) => stages.push(text.to_string()),
            Event::Step { record, .. } if first.is_none() => first = Some(record.clone()),
            _ => {}
        }
        Ok(())
    })
    .unwrap();
    println!("{stages:#?}");
    assert!(stages.iter().any(|s| s.contains("grown in")), "{stages:?}");
    let first = first.unwrap();
    let amplified = 0.05 / (1.0 - d_start / onset.d_c);
    println!(
        "A = {} at d = {}, amplified imperfection {amplified}",
        first.amplitude, first.d
    );
    assert_eq!(first.d, d_start);
    assert!((first.amplitude / amplified - 1.0).abs() < 0.05);
}

/// A path asked for short steps throughout is not damped where it is smooth: the viscous
/// damper engages only on steps the control has cut. (It used to engage on every step shorter
/// than 0.001: with steps of 0.0002 it held this wrinkle flat past its onset, A = 0.066 at
/// d = 0.027 against 0.50 undamped, the dissipated energy a small fraction of the strain
/// energy of the compression.)
#[test]
fn short_steps_are_not_damped_where_the_path_is_smooth() {
    let params = isotropic(100.0);
    let path = |max_step: f64| {
        let options = SimulateOptions {
            max_step,
            d_max: 0.03,
            ..two_wavelengths()
        };
        solve(&params, &options.study().unwrap(), &|_| Ok(()))
            .unwrap()
            .curve
            .records
    };
    let (short, usual) = (path(0.0002), path(0.001));
    let damped = short
        .iter()
        .filter(|r| {
            r.augmented
                .as_ref()
                .is_some_and(|a| a.stabilisation_energy_fraction > 0.0)
        })
        .count();
    let (a, b) = (short.last().unwrap(), usual.last().unwrap());
    println!(
        "{damped} damped states; A at d = {}: {} and {}",
        a.d, a.amplitude, b.amplitude
    );
    assert_eq!(damped, 0);
    assert!((a.d - b.d).abs() < 1e-12);
    assert!((a.amplitude / b.amplitude - 1.0).abs() < 1e-6);
}

/// The default steps (0.005) follow the stable wrinkle through its onset to the period doubling
/// too. Just past the onset a step is cut there because Newton's iteration needs a closer
/// start, not because the path snaps: that step is not damped (a damped one held the wrinkle
/// back and the path went on along an unstable branch, with changes of the inertia from
/// d = 0.03), and the inertia of a step whose predictor's count differs from the last state's
/// is the solution's (a predictor a hundredth of a step off had five negative pivots where its
/// solution had none).
#[test]
fn the_default_steps_follow_the_stable_wrinkle_to_its_period_doubling() {
    let options = SimulateOptions {
        max_step: SimulateOptions::default().max_step,
        d_max: 0.22,
        ..two_wavelengths()
    };
    let ToSecondary::Changed(mode) = solve_to_secondary(&isotropic(100.0), &options.study().unwrap()).unwrap() else {
        panic!("the periodic wrinkle stays stable to d = 0.22");
    };
    println!(
        "first secondary bifurcation at d = {:.4}: {} half waves",
        mode.d, mode.half_waves
    );
    assert_eq!(mode.half_waves, 2);
    assert!((0.15..0.22).contains(&mode.d), "{}", mode.d);
}

/// A layer a thousand times stiffer than its substrate (`K = 100 mu`) loses stability near
/// `d = 0.19`, where it does at Table 1's Poisson ratio: the viscous damper does not engage just
/// past the onset (`d_c = 0.0052`), where a cut step fails once and the shorter ones converge
/// as the wrinkle's amplitude shoots up, and the path is undamped to that first change (damped
/// from the first failure, the path was held near the flat state, the count of negative pivots
/// climbing from 1 at d = 0.0054 to 26 at 0.08).
#[test]
fn a_layer_a_thousand_times_stiffer_doubles_its_period_undamped_from_its_onset() {
    let (params, _, options) = thousand_times_stiffer(|_| 0.21);
    let study = options.study().unwrap();
    let mut records = Vec::new();
    stages::run(&Bilayer::new(&params), study.mesh, &study.protocol, &mut |event| {
        if let Event::Step { record, .. } = event {
            records.push(record.clone());
        }
        Ok(())
    })
    .unwrap();
    let damped_at = records
        .iter()
        .find(|r| r.augmented.as_ref().is_some_and(|a| a.dissipated_energy > 0.0))
        .map(|r| r.d);
    let changes = inertia_changes(&records);
    println!("first damped state at {damped_at:?}; changes of the inertia {changes:?}");
    let first = changes
        .first()
        .expect("the periodic wrinkle loses stability before d = 0.21");
    assert!((0.18..0.2).contains(&first.d_before), "{first:?}");
    assert!(damped_at.is_none_or(|d| d >= first.d_before), "{damped_at:?}");
}

/// An exactly incompressible bilayer of contrast 100 (the mixed element's multipliers), seeded
/// with one half wave of the domain as a new user seeds the doubled period: it reaches d = 0.3
/// with its tangent's count of negative pivots zero along the stable wrinkle and changing only
/// near the path's end, never back. (Its stability was once counted with the iteration's
/// pressure at the stability tangent's large penalty, `lambda + kappa M^-1 g`: the constraint's
/// 1e-7 residual made that pressure wrong by up to 10 in the layer, and the count went
/// 1 -> 4 -> 0 just past the onset and flickered later.)
#[test]
fn an_incompressible_stiff_layer_reaches_a_third_compression_with_a_sane_inertia() {
    let params = Parameters {
        incompressible: true,
        ..isotropic(100.0)
    };
    let options = SimulateOptions {
        waves: Some(2.0),
        imperfection2: 0.05,
        imperfection2_waves: 1.0,
        d_max: 0.3,
        ..SimulateOptions::default()
    };
    let solution = solve(&params, &options.study().unwrap(), &|_| Ok(())).unwrap();
    assert!(solution.curve.stopped.is_none(), "{:?}", solution.curve.stopped);
    assert_eq!(solution.d_reached, 0.3);
    let changes = inertia_changes(&solution.curve.records);
    println!("{changes:#?}");
    assert_lasting(&changes, 0.2);
}

/// The count of negative pivots is zero before `stable_to` and, once it has changed, never
/// returns to zero.
fn assert_lasting(changes: &[InertiaChange], stable_to: f64) {
    let Some(first) = changes.first() else { return };
    assert!(
        first.d_before > stable_to,
        "a change at d = {} < {stable_to}",
        first.d_before
    );
    assert!(changes.iter().all(|c| c.negative_after > 0), "{changes:?}");
}

/// The period doubling of the nearly incompressible bilayer above, exactly incompressible: one
/// change of the inertia, to the doubled period, at the same d (the two bulk moduli differ by
/// a Poisson ratio of 0.495 against 0.5).
#[test]
fn an_incompressible_stiff_layer_doubles_its_period_with_one_change_of_the_inertia() {
    let params = Parameters {
        incompressible: true,
        ..isotropic(100.0)
    };
    let solution = solve(&params, &two_wavelengths().study().unwrap(), &|_| Ok(())).unwrap();
    assert!(solution.curve.stopped.is_none(), "{:?}", solution.curve.stopped);
    let changes = inertia_changes(&solution.curve.records);
    println!("{changes:#?}");
    assert_lasting(&changes, 0.15);
    let [change] = &solution.secondary.changes[..] else {
        panic!("one change: {changes:?}");
    };
    assert_eq!(change.change.negative_after, 1);
    assert!(change.change.d_before < 0.25);
    assert_eq!(change.mode_half_waves, Some(2), "the doubled period");
}
