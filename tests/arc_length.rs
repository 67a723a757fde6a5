//! Pseudo-arc-length continuation against displacement control (a second method), on the
//! coarse mesh of Fig. 7 without contact (Table 1, five waves seeded). Where `d` rises along
//! the path, both reach the same equilibrium at the same `d`. Where displacement control stops
//! (its step cut to the minimum, as at a limit point in `d`), arc length goes round the fold:
//! the largest `d` it passes is where displacement control stopped, and there the tangent's
//! inertia changes by exactly one (its determinant changes sign at a simple limit point).

use fiberfold::material::Bilayer;
use fiberfold::protocol::{stages, ContinuationMethod, Event, StepRecord};
use fiberfold::studies::simulate::SimulateOptions;
use fiberfold::{Error, Parameters};

/// The records of Fig. 7's run without contact on the coarse mesh to `d_max`, followed by
/// `method`, until `stop` says so; the final unknowns, and what stopped the path early.
fn run(
    method: ContinuationMethod,
    d_max: f64,
    stop: impl Fn(&[StepRecord]) -> bool,
) -> (Vec<StepRecord>, Vec<f64>, Option<Error>) {
    let options = SimulateOptions {
        waves: Some(5.0),
        d_max,
        contact: false,
        crossing: fiberfold::studies::simulate::Crossing::None,
        continuation: method,
        ..SimulateOptions::default()
    };
    let study = options.study().unwrap();
    let materials = Bilayer::new(&Parameters::default());
    let mut records = Vec::new();
    let outcome = stages::run(&materials, study.mesh, &study.protocol, &mut |event| {
        if let Event::Step { record, .. } = event {
            records.push(record.clone());
            if stop(&records) {
                return Err(Error::Interrupted("turned back".into()));
            }
        }
        Ok(())
    })
    .unwrap();
    let u = outcome.continuation.displacement().to_vec();
    (records, u, outcome.stopped)
}

#[test]
fn arc_length_reaches_displacement_controls_equilibrium_where_d_rises() {
    let d_max = 0.15;
    let (control, u_control, stopped) = run(ContinuationMethod::Displacement, d_max, |_| false);
    assert!(stopped.is_none(), "{stopped:?}");
    let (arc, u_arc, stopped) = run(ContinuationMethod::ArcLength, d_max, |_| false);
    assert!(stopped.is_none(), "{stopped:?}");
    assert!(arc.windows(2).all(|pair| pair[1].d > pair[0].d));
    let (last_control, last_arc) = (control.last().unwrap(), arc.last().unwrap());
    assert_eq!(last_arc.d, d_max);
    let scale = u_control.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    let difference = u_control
        .iter()
        .zip(&u_arc)
        .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
    println!(
        "A = {} (displacement control) and {} (arc length); largest difference of u {difference:.2e} of {scale:.2}",
        last_control.amplitude, last_arc.amplitude
    );
    assert!(difference <= 1e-10 * scale, "{difference:e}");
    assert!(last_arc.amplitude > 0.3, "wrinkled: {}", last_arc.amplitude);
    // The periodic wrinkle has lost stability by then: both count the same unstable directions.
    assert_eq!(last_arc.negative_pivots, last_control.negative_pivots);
    assert!(last_arc.negative_pivots.is_some());
}

#[test]
fn arc_length_goes_round_the_limit_point_where_displacement_control_stops() {
    let (control, _, stopped) = run(ContinuationMethod::Displacement, 0.3, |_| false);
    let stopped = stopped.expect("displacement control stops at the fold").to_string();
    assert!(stopped.contains("minimum step"), "{stopped}");
    let d_stopped = control.last().unwrap().d;
    // Until the path has turned back by 0.005 in d.
    let turned_back = |records: &[StepRecord]| {
        let largest = records.iter().fold(0.0_f64, |m, r| m.max(r.d));
        records.last().unwrap().d < largest - 0.005
    };
    let (arc, _, stopped) = run(ContinuationMethod::ArcLength, 0.3, turned_back);
    assert!(matches!(stopped, Some(Error::Interrupted(_))), "{stopped:?}");
    let fold = (0..arc.len()).max_by(|&i, &j| arc[i].d.total_cmp(&arc[j].d)).unwrap();
    let d_fold = arc[fold].d;
    println!("displacement control stopped at {d_stopped}; the arc-length path turns at {d_fold}");
    assert!(
        d_stopped <= d_fold + 1e-9 && d_fold - d_stopped < 1e-5,
        "{d_stopped} {d_fold}"
    );
    let (before, after) = (&arc[fold - 1], &arc[fold + 1]);
    let (n_before, n_after) = (before.negative_pivots.unwrap(), after.negative_pivots.unwrap());
    assert_eq!(
        n_after,
        n_before + 1,
        "inertia {n_before} before the fold, {n_after} after"
    );
    assert!(arc.iter().all(|r| r.relative_residual <= 1e-9));
}
