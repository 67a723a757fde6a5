//! One point of the instability map: the wrinkling onset of the linear theory, the crease onset
//! of the energy criterion, which comes first, and what the wrinkle becomes in a nonlinear run.

use super::MapSettings;
use crate::error::{Error, Result};
use crate::fem::ellipticity::EllipticityReport;
use crate::parameters::Parameters;
use crate::protocol::secondary::{branch, branch_kind, BranchKind};
use crate::protocol::{Event, SnapCrossing};
use crate::stability::{Method, Minimum, StabilityAnalysis};
pub use crate::studies::crease::First;
use crate::studies::crease::{crease, CreaseStudy};
use crate::studies::orientation::{directed_onset, Modes};
use crate::studies::simulate::{
    solve_observed, solve_to_secondary, MeshChoice, Observed, Progress, SimulateOptions, SimulateStudy, Solution,
    ToSecondary,
};
use serde::{Deserialize, Serialize};
use std::sync::Mutex;
use std::time::Instant;

/// What the wrinkle becomes in the nonlinear run ([`post_buckling`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PostBuckling {
    /// The troughs stay equally deep (within 20 %) and open: a periodic wrinkle to the end.
    Wrinkle,
    /// Deep troughs alternate with shallow ones, or alternate peaks grow: a period doubling (or
    /// the longer modulation nearest to it that the domain admits).
    PeriodDoubling,
    /// One trough leads all others by more than 20 % of its depth: a localised fold.
    Fold,
    /// The troughs stay equally deep but close on themselves: every trough becomes a crease.
    Crease,
    /// The path stayed periodic, but its last state is unstable (negative pivots): the seed did
    /// not excite the mode that took over, so what the wrinkle becomes is not resolved.
    Unresolved,
}

/// A surface whose component at half the seeded wavenumber is at least this fraction of the
/// seeded one has doubled its period.
pub const DOUBLING_RATIO: f64 = 0.2;

/// The rule, on the last state of the run: one seeded trough deeper than all others by more
/// than 20 % of its depth (the "localised" branch of [`crate::protocol::secondary`]) is a
/// fold; otherwise deep troughs alternating with shallow ones (the "modulated" branch: the
/// shallowest more than 20 % above the deepest), or a surface whose `k / 2` component is at
/// least `DOUBLING_RATIO` of its `k` component ([`doubling`]: alternate peaks), have doubled
/// their period; otherwise a last state whose tangent has
/// negative pivots is an unstable periodic path (unresolved); otherwise troughs that closed on
/// themselves are a row of creases, and open ones a wrinkle. The tangent's inertia also dates
/// the change (`d_secondary`: its first change along the run).
pub fn post_buckling(trough_depths: &[f64], doubling: f64, unstable: bool, self_contact: bool) -> PostBuckling {
    let kind = branch_kind(trough_depths);
    if kind == BranchKind::Localised {
        PostBuckling::Fold
    } else if kind == BranchKind::Modulated || doubling >= DOUBLING_RATIO {
        PostBuckling::PeriodDoubling
    } else if unstable {
        PostBuckling::Unresolved
    } else if self_contact {
        PostBuckling::Crease
    } else {
        PostBuckling::Wrinkle
    }
}

/// `|c(k / 2)| / |c(k)|`, with `c(q)` the cosine component of the surface height `y` over the
/// reference abscissa `X = x / (1 - d)` (the trapezoidal rule on the deformed surface points
/// `(x, y)` of a half domain with symmetry planes at both ends).
pub fn doubling(surface: &[(f64, f64)], k: f64, d: f64) -> f64 {
    let component = |q: f64| {
        surface
            .windows(2)
            .map(|w| {
                let (xa, xb) = (w[0].0 / (1.0 - d), w[1].0 / (1.0 - d));
                0.5 * (xb - xa) * (w[0].1 * (q * xa).cos() + w[1].1 * (q * xb).cos())
            })
            .sum::<f64>()
    };
    let seeded = component(k).abs();
    if seeded > 0.0 {
        component(0.5 * k).abs() / seeded
    } else {
        0.0
    }
}

/// Everything computed at one point (a file `points/point-<index>.json`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MapPoint {
    /// Position in the map: `index = iy * x_points + ix`.
    pub index: usize,
    pub ix: usize,
    pub iy: usize,
    pub x: f64,
    pub y: f64,
    pub parameters: Parameters,
    /// Linear theory: the minimum of `d_c(k)` and where it lies (None: no wrinkling before the
    /// loss of ellipticity or d = 0.95).
    pub d_wrinkle: Option<f64>,
    pub k0: Option<f64>,
    pub minimum: Option<Minimum>,
    /// Energy criterion: the crease onset, its fold length and depth (units of H). Searched up
    /// to `d_wrinkle` only: beyond it the flat state the criterion compares with is unstable.
    pub d_crease: Option<f64>,
    /// Its uncertainty from the mesh sequence ([`crate::studies::crease::convergence`]).
    #[serde(default)]
    pub d_crease_error: Option<f64>,
    pub crease_fold_length: Option<f64>,
    pub crease_depth: Option<f64>,
    pub first: First,
    /// Nonlinear run (only where the wrinkle has a wavelength, `minimum = interior`).
    pub becomes: Option<PostBuckling>,
    pub trough_depths: Vec<f64>,
    /// [`doubling`] of the last state.
    pub doubling: Option<f64>,
    pub d_secondary: Option<f64>,
    /// Half wavelengths across the domain of the mode at `d_secondary`.
    pub secondary_half_waves: Option<usize>,
    pub d_first_contact: Option<f64>,
    pub d_reached: Option<f64>,
    /// With [`MapSettings::biaxial`]: the onset over wavenumbers and directions of the surface
    /// under that biaxial compression, and its wave vector's direction in `[0, pi)` (None
    /// where no direction is preferred).
    #[serde(default)]
    pub d_wrinkle_biaxial: Option<f64>,
    #[serde(default)]
    pub theta0: Option<f64>,
    /// The first `d` at which a state of the nonlinear run has a Gauss point without strong
    /// ellipticity (beyond it the answer depends on the mesh; `simulate` reports each layer).
    #[serde(default)]
    pub d_ellipticity_loss_fe: Option<f64>,
    /// The same in the crease search's states, whose seeded fold has a tip singular by
    /// construction: a loss there is the fold's, not the tissue's.
    #[serde(default)]
    pub d_ellipticity_loss_fold: Option<f64>,
    /// Why a part is missing or ended early.
    pub notes: Vec<String>,
    /// Wall time of the linear theory, the crease search and the nonlinear run (s).
    pub seconds: [f64; 3],
}

/// The nonlinear run's mesh: `waves` wavelengths `2 pi / k0` across the half domain, `elements`
/// per wavelength, and the coarse mesh's layers and depth.
fn wave_mesh(settings: &MapSettings, k0: f64) -> MeshChoice {
    MeshChoice {
        nx: Some((settings.elements_per_wave as f64 * settings.waves).ceil() as usize),
        layer_elements: Some(settings.layer_elements),
        substrate_elements: Some(settings.substrate_elements),
        h0: Some(1.0 / settings.layer_elements as f64),
        element: settings.crease_mesh.element,
        length: Some(settings.waves * 2.0 * std::f64::consts::PI / k0),
        depth: Some(settings.depth),
        ..MeshChoice::default()
    }
}

/// Computes the point `(ix, iy)` with `parameters`: [`first_instability`], then the nonlinear
/// run where the wrinkle has a wavelength. Solver failures become notes, other errors (bad
/// input) are returned.
pub fn compute(
    settings: &MapSettings,
    crease_study: &CreaseStudy,
    (index, ix, iy, x, y): (usize, usize, usize, f64, f64),
    parameters: Parameters,
) -> Result<MapPoint> {
    let mut point = first_instability(crease_study, parameters.clone())?;
    (point.index, point.ix, point.iy, point.x, point.y) = (index, ix, iy, x, y);
    if let Some(biaxial) = settings.biaxial {
        let clock = Instant::now();
        orientation(biaxial, &parameters, &mut point)?;
        point.seconds[0] += clock.elapsed().as_secs_f64();
    }
    let clock = Instant::now();
    match (point.k0, point.d_wrinkle) {
        _ if point.first == First::Crease => point
            .notes
            .push("no nonlinear run: the crease comes first, the wrinkle is not followed".into()),
        (Some(k0), Some(d_wrinkle)) => match nonlinear(settings, &parameters, k0, d_wrinkle, &mut point) {
            Err(Error::Solver(why)) => point.notes.push(format!("nonlinear run failed: {why}")),
            other => other?,
        },
        _ => point
            .notes
            .push("no nonlinear run: the wrinkle has no finite wavelength".into()),
    }
    point.seconds[2] = clock.elapsed().as_secs_f64();
    if let Some(d) = point.d_ellipticity_loss_fe {
        point.notes.push(format!(
            "the nonlinear run loses strong ellipticity at a Gauss point from d = {d:.4}: beyond it the answer \
             depends on the mesh"
        ));
    }
    Ok(point)
}

/// The onset over the directions of the surface under `d_3 = biaxial d`, and its direction.
fn orientation(biaxial: f64, parameters: &Parameters, point: &mut MapPoint) -> Result<()> {
    let modes = Modes {
        biaxial: Some(biaxial),
        theta: None,
    };
    match directed_onset(parameters, Method::Exact, &modes) {
        Ok(found) => {
            point.d_wrinkle_biaxial = Some(found.onset.d_c);
            point.theta0 = Some(found.theta0).filter(|t| t.is_finite());
            if point.theta0.is_none() {
                point.notes.push(format!(
                    "under d_3 = {biaxial} d no direction of the surface is preferred (spread {:.1e})",
                    found.direction_spread.unwrap_or(0.0)
                ));
            }
            Ok(())
        }
        Err(Error::NoRoot { .. }) => {
            point.notes.push(format!(
                "under d_3 = {biaxial} d no wrinkling before the loss of ellipticity or d = 0.95"
            ));
            Ok(())
        }
        Err(e) => Err(e),
    }
}

/// The wrinkling onset (linear theory), the crease onset (energy criterion) and which comes
/// first, as a point at position 0 without its nonlinear run.
pub fn first_instability(crease_study: &CreaseStudy, parameters: Parameters) -> Result<MapPoint> {
    let mut notes = Vec::new();
    let clock = Instant::now();
    let onset = StabilityAnalysis::new(&parameters, Method::Exact)?.onset();
    let onset = match onset {
        Ok(o) => Some(o),
        Err(Error::NoRoot { .. }) => {
            notes.push("no wrinkling before the loss of ellipticity or d = 0.95".into());
            None
        }
        Err(e) => return Err(e),
    };
    let linear_seconds = clock.elapsed().as_secs_f64();

    let d_wrinkle = onset.map(|o| o.d_c);
    let clock = Instant::now();
    // The crease search ends just past d_wrinkle ([`CreaseStudy::stop_past_wrinkle`]).
    let report = crease(&parameters, crease_study, &|| {})?;
    let crease_seconds = clock.elapsed().as_secs_f64();
    if report.d_crease.is_none() {
        let why = report
            .folds
            .iter()
            .flat_map(|f| f.meshes.iter().filter_map(|m| m.stopped.as_deref()))
            .next();
        notes.push(format!(
            "no crease pays off up to d = {:.4} (the search ends at d_wrinkle){}",
            report.scan.to,
            why.map(|w| format!(" ({w})")).unwrap_or_default()
        ));
    }
    let first = report.first;

    Ok(MapPoint {
        index: 0,
        ix: 0,
        iy: 0,
        x: 0.0,
        y: 0.0,
        parameters,
        d_wrinkle,
        k0: onset.filter(|o| o.minimum == Minimum::Interior).map(|o| o.k0),
        minimum: onset.map(|o| o.minimum),
        d_crease: report.d_crease,
        d_crease_error: report.d_crease_error,
        crease_fold_length: report.fold_length,
        crease_depth: report.depth,
        first,
        becomes: None,
        trough_depths: Vec::new(),
        doubling: None,
        d_secondary: None,
        secondary_half_waves: None,
        d_first_contact: None,
        d_reached: None,
        d_wrinkle_biaxial: None,
        theta0: None,
        d_ellipticity_loss_fe: None,
        d_ellipticity_loss_fold: report.ellipticity.d_loss(),
        notes,
        seconds: [linear_seconds, crease_seconds, 0.0],
    })
}

/// The nonlinear analysis to `d_wrinkle + post_buckling_range`. The unseeded path is followed
/// to the first change of the tangent's inertia; its mode there (`m` half wavelengths across
/// the domain) seeds, as `seed cos(m pi X / L)`, the run that is classified. Without a change
/// the unseeded run is classified.
fn nonlinear(
    settings: &MapSettings,
    parameters: &Parameters,
    k0: f64,
    d_wrinkle: f64,
    point: &mut MapPoint,
) -> Result<()> {
    let options = SimulateOptions {
        mesh: wave_mesh(settings, k0),
        waves: Some(settings.waves),
        d_max: (d_wrinkle + settings.post_buckling_range).min(settings.d_limit),
        imperfection: settings.imperfection,
        ..SimulateOptions::default()
    };
    let mut study = options.study()?;
    study.secondary_modes = 0; // the branch decides; the modes are not drawn
    if let SnapCrossing::Viscous(damper) = &mut study.protocol.crossing {
        damper.budget = settings.snap_budget;
    }
    let (solution, closed) = match solve_to_secondary(parameters, &study)? {
        ToSecondary::Whole(solution) => (*solution, None),
        ToSecondary::Changed(mode) => {
            point.d_secondary = Some(mode.d);
            point.secondary_half_waves = Some(mode.half_waves);
            let mut seeded = study;
            seeded.protocol.imperfection2 = settings.seed;
            seeded.protocol.imperfection2_waves = 0.5 * mode.half_waves as f64;
            if let Err(why) = seeded.validate() {
                point.notes.push(format!("the secondary mode is not seeded: {why}"));
                seeded = study;
            }
            seeded_run(parameters, &seeded, !settings.follow_closed_folds)?
        }
    };
    match &solution.curve.stopped {
        Some(_) if closed.is_some() => point.notes.push(format!(
            "the nonlinear run ends at d = {:.4}, where {} closed on itself (--follow-closed-folds follows it on)",
            solution.d_reached,
            match closed {
                Some(BranchKind::Modulated) => "a doubled period",
                _ => "a fold",
            }
        )),
        Some(why) => point.notes.push(format!("nonlinear run stopped early: {why}")),
        None => {}
    }
    let depths = solution.secondary.branch.trough_depths;
    let d = solution.contact.d_reached;
    let doubled = doubling(&solution.surface, study.protocol.k, d);
    let unstable = solution
        .curve
        .records
        .last()
        .and_then(|r| r.negative_pivots)
        .is_some_and(|n| n > 0);
    point.becomes = Some(post_buckling(
        &depths,
        doubled,
        unstable,
        solution.contact.d_first_contact.is_some(),
    ));
    point.doubling = Some(doubled);
    point.trough_depths = depths;
    point.d_first_contact = solution.contact.d_first_contact;
    point.d_ellipticity_loss_fe =
        EllipticityReport::new(solution.curve.records.iter().map(|r| (r.d, r.ellipticity))).d_loss();
    point.d_reached = Some(d);
    Ok(())
}

/// The seeded run of `study`; with `stop_at_closed_fold` it ends at the first state whose
/// surface is in contact and whose troughs are no longer alike: one trough more than
/// [`crate::protocol::secondary::LOCALISED_SPREAD`] deeper than all others (a fold), or deep
/// troughs alternating with shallower ones by more than that (a doubled period), and returns
/// which. The deep troughs are then closed on themselves, and a closed trough only deepens: that
/// state is classified by [`post_buckling`] as any later one is (checked against the whole run
/// by the tests).
fn seeded_run(
    parameters: &Parameters,
    study: &SimulateStudy,
    stop_at_closed_fold: bool,
) -> Result<(Solution, Option<BranchKind>)> {
    let closed: Mutex<Option<BranchKind>> = Mutex::new(None);
    let (k, imperfection) = (study.protocol.k, study.protocol.imperfection);
    let mut observer = |observed: Observed<'_>, _: &_| {
        if let Observed::Event(Event::Step { record, system, u }) = observed {
            let in_contact = record.augmented.as_ref().is_some_and(|a| a.in_contact);
            if stop_at_closed_fold && in_contact {
                let kind = branch(system.mesh(), u, k, imperfection).kind;
                if kind != BranchKind::Periodic {
                    *closed.lock().expect("the observer does not panic") = Some(kind);
                }
            }
        }
        Ok(())
    };
    // The monitor sees the state after it is recorded: the path ends with the closed trough.
    let monitor = |_: Progress<'_>| match *closed.lock().expect("the observer does not panic") {
        Some(_) => Err(Error::Interrupted("a fold or a doubled period closed on itself".into())),
        None => Ok(()),
    };
    let solution = solve_observed(parameters, study, &monitor, None, &mut observer)?.solution;
    let closed = *closed.lock().expect("the observer does not panic");
    Ok((solution, closed))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::protocol::secondary::{first_trough, trough_depths};

    #[test]
    fn the_rule_names_constructed_surfaces() {
        let (k, length) = (std::f64::consts::PI / 2.0, 16.0); // four waves of length 4
                                                              // The surface as the run gives it: deformed x = (1 - d) X, at d = 0.2.
        let surface = |y: &dyn Fn(f64) -> f64| -> Vec<(f64, f64)> {
            (0..=2000)
                .map(|i| length * i as f64 / 2000.0)
                .map(|x| (0.8 * x, y(x)))
                .collect()
        };
        let classify = |y: &dyn Fn(f64) -> f64, contact: bool| {
            let s = surface(y);
            let xs: Vec<f64> = s.iter().map(|p| p.0 / 0.8).collect();
            post_buckling(
                &trough_depths(&xs, &s, k, first_trough(k, 1.0), length),
                doubling(&s, k, 0.2),
                false,
                contact,
            )
        };
        let wrinkle = |x: f64| 0.3 * (k * x).cos();
        assert_eq!(
            trough_depths(&[0.0, 2.0, 4.0], &[(0.0, 1.0), (1.6, -1.0), (3.2, 1.0)], k, 2.0, 4.0),
            vec![2.0]
        );
        assert!(doubling(&surface(&wrinkle), k, 0.2) < 1e-6);
        assert_eq!(classify(&wrinkle, false), PostBuckling::Wrinkle);
        assert_eq!(classify(&wrinkle, true), PostBuckling::Crease);
        let depths = [1.0, 1.0, 1.0];
        assert_eq!(post_buckling(&depths, 0.0, true, true), PostBuckling::Unresolved);
        // Period doubling, even about both symmetry planes: alternate peaks (cos(k X / 2)) ...
        let peaks = |x: f64| 0.3 * (k * x).cos() + 0.1 * (0.5 * k * x).cos();
        assert!((doubling(&surface(&peaks), k, 0.2) - 1.0 / 3.0).abs() < 1e-3);
        assert_eq!(classify(&peaks, false), PostBuckling::PeriodDoubling);
        assert_eq!(classify(&peaks, true), PostBuckling::PeriodDoubling);
        // ... not a monotone drift of the trough depths from a long-wave seed.
        let drift = |x: f64| 0.3 * (k * x).cos() * (1.0 + 0.15 * x / length);
        assert_eq!(classify(&drift, false), PostBuckling::Wrinkle);
        // ... or alternate troughs deepen (the modulation a symmetric domain of 4 waves admits).
        let troughs = |x: f64| 0.3 * (k * x).cos() - 0.1 * (3.0 * std::f64::consts::PI * x / length).cos();
        assert_eq!(classify(&troughs, false), PostBuckling::PeriodDoubling);
        // A fold: one trough (at X = 6) far deeper than the rest, closed or not.
        let fold = |x: f64| 0.2 * (k * x).cos() - 1.5 * (-((x - 6.0) / 1.0).powi(2)).exp();
        assert_eq!(classify(&fold, false), PostBuckling::Fold);
        assert_eq!(classify(&fold, true), PostBuckling::Fold);
        // A 5 % modulation is still a periodic wrinkle.
        let mild = |x: f64| 0.3 * (k * x).cos() + 0.015 * (0.5 * k * x).cos();
        assert_eq!(classify(&mild, false), PostBuckling::Wrinkle);
    }

    #[test]
    fn a_wrinkle_seeded_with_troughs_on_the_symmetry_planes_has_its_alternate_troughs_measured() {
        // Four waves of length 4 with a trough at X = 0: troughs at X = 0, 4, 8, 12, 16, those
        // on the planes included. The period doubling cos(k X / 2) then deepens every other one:
        // y = -0.3 cos(k X) + 0.1 cos(k X / 2) is 0.2 low at X = 0, 8, 16 and 0.4 low at 4, 12.
        let (k, length) = (std::f64::consts::PI / 2.0, 16.0);
        let xs: Vec<f64> = (0..=1600).map(|i| length * i as f64 / 1600.0).collect();
        let surface: Vec<(f64, f64)> = xs
            .iter()
            .map(|&x| (x, -0.3 * (k * x).cos() + 0.1 * (0.5 * k * x).cos()))
            .collect();
        let top = surface.iter().fold(f64::NEG_INFINITY, |m, p| m.max(p.1));
        let depths = trough_depths(&xs, &surface, k, first_trough(k, -1.0), length);
        let expected = [top + 0.2, top + 0.4, top + 0.2, top + 0.4, top + 0.2];
        assert_eq!(depths.len(), expected.len());
        for (depth, expected) in depths.iter().zip(expected) {
            assert!((depth - expected).abs() < 1e-9, "{depths:?}");
        }
        assert_eq!(post_buckling(&depths, 0.0, false, false), PostBuckling::PeriodDoubling);
    }

    #[test]
    fn the_first_instability_is_too_close_to_call_within_the_crease_uncertainty() {
        let (w, u) = (0.2305, 5e-4);
        assert_eq!(First::decide((Some(w), Some(w - 2.0 * u)), u, 0.0), First::Crease);
        assert_eq!(First::decide((Some(w), Some(w + 2.0 * u)), u, 0.0), First::Wrinkle);
        assert_eq!(
            First::decide((Some(w), Some(w - 0.5 * u)), u, 0.0),
            First::TooCloseToCall
        );
        assert_eq!(
            First::decide((Some(w), Some(w + 0.5 * u)), u, 0.0),
            First::TooCloseToCall
        );
        // An unconverged threshold (no uncertainty) decides by its sign alone.
        assert_eq!(First::decide((Some(w), Some(w - 1e-6)), 0.0, 0.0), First::Crease);
        // No fold paid off up to `cleared`: the wrinkle first only if it comes before.
        assert_eq!(First::decide((Some(w), None), u, w + 0.01), First::Wrinkle);
        assert_eq!(First::decide((Some(w), None), u, w - 0.01), First::Undecided);
        assert_eq!(First::decide((None, Some(0.35)), u, 0.0), First::Crease);
        assert_eq!(First::decide((None, None), u, 0.0), First::None);
    }
}
