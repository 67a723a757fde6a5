//! The three loading stages of section 2.1: (1) homogeneous compression of the perfect bilayer
//! to `d = 0.005`; (2) the imperfection [`Imperfection`] is put into the reference geometry, the
//! nodal displacements of stage 1 are kept, and equilibrium is restored at the same `d`;
//! (3) displacement control to `d_max` ([`Continuation`]). `A_init = 0` runs the perfect system.
//! Stage 3 may report its whole state now and then, and start from such a state
//! ([`Resumption`]).

use super::augmentation::Augmentation;
use super::basic_state::homogeneous_unknowns;
use super::continuation::{
    ArcLength, CheckpointInterval, Continuation, ContinuationMethod, Event, PathFollowing, PathState, StepControl,
};
use super::imperfection::{mode_number, wavenumber_of_waves, Imperfection};
use super::measures::{bilayer_measures, measure_all};
use super::record::StepRecord;
use super::snap::SnapCrossing;
use super::stabilisation::StabilisationSettings;
use crate::error::{Error, Result};
use crate::fem::equilibrium;
use crate::fem::{Newton, NewtonPolicy, Reuse, Stall, System};
use crate::homogeneous::homogeneous_state;
use crate::material::Bilayer;
use crate::mesh::{Mesh, MeshSpec};
use crate::protocol::Loading;
use std::f64::consts::PI;
use std::time::Instant;

/// End-shortening of stage 1, the paper's (and [`Protocol::new`]'s).
pub const STAGE_ONE_COMPRESSION: f64 = 0.005;

/// The fractions of the imperfection stage 2 grows it by where one solve does not reach it.
const IMPERFECTION_RAMP: [f64; 5] = [0.0625, 0.125, 0.25, 0.5, 1.0];

/// A loading protocol: the seeded mode, its amplitude, the final compression and the solver.
#[derive(Clone, Copy, Debug)]
pub struct Protocol {
    /// Referential wavenumber of the seeded mode (`m pi / L`).
    pub k: f64,
    /// `A_init`, the amplitude of the imperfection `A_init cos(k X)` of the top surface:
    /// positive puts a crest on each symmetry plane, negative a trough.
    pub imperfection: f64,
    /// Final end-shortening.
    pub d_max: f64,
    /// End-shortening of stage 1 (homogeneous), where the imperfection is seeded: below the
    /// onset, or the imperfect equilibrium there is a wrinkle grown too far for one solve.
    pub d_start: f64,
    /// Adaptive steps of stage 3.
    pub control: StepControl,
    /// Newton's policy in every stage.
    pub newton: NewtonPolicy,
    /// Contact of the top surface with the symmetry planes and with itself in stage 3.
    pub contact: bool,
    /// How stage 3 crosses a snap ([`super::snap`]).
    pub crossing: SnapCrossing,
    /// `A_2` of the long-wave imperfection `-A_2 cos(2 pi N_2 X / L)` added in stage 2 (it
    /// lowers the surface at `X = 0` and wherever the cosine is positive, deepening the troughs
    /// there: a seed for a modulated or localised pattern).
    pub imperfection2: f64,
    /// `N_2`, the waves of the long-wave imperfection across the domain (`2 N_2` a positive
    /// integer; `1/2` by default: one half wave). `N / 2` seeds a period doubling: of the
    /// troughs when the seeded mode has its troughs on the planes (`A_init < 0`), of the
    /// crests otherwise.
    pub imperfection2_waves: f64,
    /// How stage 3 follows the path: displacement control, or arc length (which goes round a
    /// limit point in `d` instead of crossing it, and so has neither contact nor a crossing).
    pub method: ContinuationMethod,
}

impl Protocol {
    /// The paper's protocol to `d_max` with default steps and [`simulation_newton`].
    pub fn new(k: f64, imperfection: f64, d_max: f64) -> Self {
        Protocol {
            k,
            imperfection,
            d_max,
            d_start: STAGE_ONE_COMPRESSION,
            control: StepControl::default(),
            newton: simulation_newton(),
            contact: false,
            crossing: SnapCrossing::None,
            imperfection2: 0.0,
            imperfection2_waves: 0.5,
            method: ContinuationMethod::Displacement,
        }
    }

    /// The same protocol carried on to a crease: contact and default stabilisation in stage 3,
    /// steps down to `1e-7` (where the damping `eta / h` of a snap is ten times the stiffness)
    /// and up to 25 Newton iterations per step (contact changes cost a few).
    pub fn with_crease_path(mut self) -> Self {
        self.contact = true;
        self.crossing = SnapCrossing::Viscous(StabilisationSettings::default());
        self.control.min = 1e-7;
        self.newton.max_iterations = 25;
        self
    }

    /// Checks `k` against the domain of `spec`, `A_init` in `(-1, 1)`, `A_2` in `[0, 1)`, `d_max` in `(0.005, 1)`,
    /// and that the mesh resolves the seeded waves ([`MIN_ELEMENTS_PER_WAVELENGTH`]).
    pub fn validate(&self, spec: &MeshSpec) -> Result<()> {
        mode_number(self.k, spec.length)?;
        let k2 = wavenumber_of_waves(self.imperfection2_waves, spec.length).map_err(|_| {
            Error::invalid(
                "imperfection2-waves",
                self.imperfection2_waves,
                "N2 with 2 N2 a positive integer",
            )
        })?;
        resolves(spec, "waves", 2.0 * PI / self.k)?;
        if self.imperfection2 > 0.0 {
            resolves(spec, "imperfection2-waves", 2.0 * PI / k2)?;
        }
        if !(self.imperfection.is_finite() && self.imperfection.abs() < 1.0) {
            return Err(Error::invalid(
                "imperfection",
                self.imperfection,
                "(-1, 1): negative puts a trough on each symmetry plane",
            ));
        }
        if !(self.imperfection2.is_finite() && (0.0..1.0).contains(&self.imperfection2)) {
            return Err(Error::invalid("imperfection2", self.imperfection2, "[0, 1)"));
        }
        if !(self.d_start.is_finite() && self.d_start > 0.0 && self.d_start < 1.0) {
            return Err(Error::invalid("d-start", self.d_start, "(0, 1)"));
        }
        if !(self.d_max.is_finite() && self.d_max > self.d_start && self.d_max < 1.0) {
            return Err(Error::invalid(
                "d-max",
                self.d_max,
                &format!("({}, 1): beyond stage 1's d = {}", self.d_start, self.d_start),
            ));
        }
        if self.method == ContinuationMethod::ArcLength && (self.contact || self.crossing != SnapCrossing::None) {
            return Err(Error::invalid(
                "continuation",
                "arc-length",
                "displacement, or arc-length without contact or a way across a snap (--no-contact --stabilisation none)",
            ));
        }
        self.control.validate()
    }
}

/// Fewest Q2 elements per wavelength of a seeded wave (8 node spacings, a Q2 element spans
/// two): below it the mesh cannot carry the mode, and the run would report a meaningless `A`.
pub const MIN_ELEMENTS_PER_WAVELENGTH: f64 = 4.0;

/// An error naming what to change when the widest element of `spec` is wider than a quarter of
/// `wavelength` (the wave named `what`): `--nx` on a uniform mesh, `--refine-troughs` when the
/// refinement coarsens the elements between troughs.
fn resolves(spec: &MeshSpec, what: &str, wavelength: f64) -> Result<()> {
    let widest = spec.widest_column();
    if wavelength / widest >= MIN_ELEMENTS_PER_WAVELENGTH * (1.0 - 1e-9) {
        return Ok(());
    }
    let needed = (MIN_ELEMENTS_PER_WAVELENGTH * spec.length / wavelength - 1e-9).ceil();
    let rule = format!(
        "at least {MIN_ELEMENTS_PER_WAVELENGTH} Q2 elements per wavelength {wavelength:.4} H of the seeded {what}"
    );
    match spec.x_refinement {
        Some(r) if spec.nx as f64 >= needed => Err(Error::invalid(
            "refine-troughs",
            r.ratio,
            &format!(
                "a ratio that keeps every element below {:.4} H wide ({rule}; the widest is {widest:.4} H)",
                wavelength / MIN_ELEMENTS_PER_WAVELENGTH
            ),
        )),
        _ => Err(Error::invalid("nx", spec.nx, &format!(">= {needed} ({rule})"))),
    }
}

/// Newton's settings for load steps: at most 8 tangent iterations, 5 when they have not
/// reduced the residual 1000-fold, 2 when they have not reduced it tenfold and 1 when it has
/// not halved (a step that needs more is cut rather than ground through), the tangent at the
/// predictor factorised first and reused while it contracts the residual, and no inertia at
/// the solution of its own (the protocol asks for it). Factorising at the predictor pays even
/// where no inertia is asked for: from the cubic predictor it converges in two steps, where a
/// factorisation kept from the step before contracts the residual only about fourfold per step
/// (measured: 42 smooth states on the fine mesh in 5.0 s instead of 5.8 s).
pub fn simulation_newton() -> NewtonPolicy {
    NewtonPolicy {
        max_iterations: 8,
        inertia_at_solution: false,
        factorise_start: true,
        reuse: Reuse::Definite,
        stall: Some(Stall {
            steps: 5,
            reduction: 1e-3,
        }),
        diverging_after: Some(2),
        ..NewtonPolicy::default()
    }
}

/// The end of a protocol: the path so far, and why it stopped early, if it did.
pub struct Outcome {
    pub continuation: Box<dyn PathFollowing<System>>,
    pub stopped: Option<Error>,
}

/// Where stage 3 starts, and whether it reports its whole state as it goes.
#[derive(Clone, Debug, Default)]
pub struct Resumption {
    /// A state of stage 3 of the same protocol to continue from: stages 1 and 2 are redone to
    /// rebuild the system, without reporting their states.
    pub from: Option<PathState>,
    /// How often stage 3 reports its whole state ([`Event::Checkpoint`]); displacement control
    /// only.
    pub checkpoints: Option<CheckpointInterval>,
}

/// Runs the three stages, reporting each converged state (from the end of stage 2 on) and each
/// cut to `observer`. A failure in stages 1-2 is an error; one in stage 3 ends up in
/// [`Outcome::stopped`] with the path so far.
pub fn run(
    materials: &Bilayer,
    spec: MeshSpec,
    protocol: &Protocol,
    observer: &mut dyn FnMut(Event<'_>) -> Result<()>,
) -> Result<Outcome> {
    run_resumable(materials, spec, protocol, Resumption::default(), observer)
}

/// [`run`] from a state of stage 3 and with checkpoints, as `resumption` asks.
pub fn run_resumable(
    materials: &Bilayer,
    spec: MeshSpec,
    protocol: &Protocol,
    resumption: Resumption,
    observer: &mut dyn FnMut(Event<'_>) -> Result<()>,
) -> Result<Outcome> {
    protocol.validate(&spec)?;
    if resumption.from.is_some() && protocol.method == ContinuationMethod::ArcLength {
        return Err(Error::invalid(
            "resume",
            "an arc-length path",
            "a path of displacement control (arc-length paths keep no checkpoints)",
        ));
    }
    // A resumed run rebuilds stages 1 and 2 without reporting them again.
    let resuming = resumption.from.as_ref().map(PathState::d);
    if let Some(d) = resuming {
        observer(Event::Stage(&format!(
            "resuming at d = {d:.6} from a checkpoint (stages 1 and 2 rebuilt)"
        )))?;
    }
    let quiet = std::cell::Cell::new(resuming.is_some());
    let mut observer = |event: Event<'_>| match event {
        Event::Stage(_) | Event::Step { .. } if quiet.get() => Ok(()),
        _ => observer(event),
    };
    let d0 = protocol.d_start;
    let mut newton = Newton::new();
    let start = Instant::now();
    observer(Event::Stage(&format!(
        "stage 1: homogeneous compression of the perfect bilayer to d = {d0}"
    )))?;
    let perfect = Mesh::new(spec)?;
    let mut system = System::new(perfect.clone(), materials)?;
    // From the homogeneous state itself (eq. 4), which the perfect mesh reproduces to round-off.
    let bc = system.load_to(d0)?;
    let mut u = homogeneous_unknowns(&system, materials, &homogeneous_state(materials, d0)?)?;
    let imperfect = protocol.imperfection != 0.0 || protocol.imperfection2 > 0.0;
    // Stages 1 and 2 are single solves, which no step cut can rescue: they iterate without
    // the load steps' early give-ups (a layer prestressed by growth near its own onset needs
    // a few more steps on the imperfect geometry). Stage 2 reports the inertia of its own
    // state (stage 1's is not reported then).
    let single_solve = NewtonPolicy {
        stall: None,
        diverging_after: None,
        ..protocol.newton
    };
    let stage_one = NewtonPolicy {
        inertia_at_solution: protocol.newton.inertia_at_solution && !imperfect,
        ..single_solve
    };
    let mut report = equilibrium::solve(&mut newton, &mut system, &mut u, &bc, &stage_one)
        .map_err(|e| stage_failure(1, d0, e.into()))?;
    if imperfect {
        observer(Event::Stage(&format!(
            "stage 2: imperfection {} cos({:.6} X){} of the reference geometry, equilibrium at d = {d0}",
            protocol.imperfection,
            protocol.k,
            if protocol.imperfection2 > 0.0 {
                format!(
                    " - {} cos(2 pi {} X / L)",
                    protocol.imperfection2, protocol.imperfection2_waves
                )
            } else {
                String::new()
            }
        )))?;
        let imperfection = Imperfection {
            amplitude: protocol.imperfection,
            k: protocol.k,
            depth: spec.depth,
        };
        let long_wave = Imperfection {
            amplitude: -protocol.imperfection2,
            k: wavenumber_of_waves(protocol.imperfection2_waves, spec.length)?,
            depth: spec.depth,
        };
        let seeded = |fraction: f64| {
            perfect.clone().perturbed(move |x| {
                let ([_, a], [_, b]) = (imperfection.displacement(x), long_wave.displacement(x));
                [0.0, fraction * (a + b)]
            })
        };
        system = system.with_moved_nodes(seeded(1.0), materials)?;
        report = match equilibrium::solve(&mut newton, &mut system, &mut u, &bc, &single_solve) {
            Ok(report) => report,
            // A stiff layer's response to the whole imperfection at once may lie beyond Newton's
            // reach from the flat state: the imperfection is then grown from a small fraction,
            // each equilibrium solved from the one before (a failed solve leaves `u` as it was).
            Err(_) => {
                observer(Event::Stage(&format!(
                    "stage 2: the imperfection grown in {} steps",
                    IMPERFECTION_RAMP.len()
                )))?;
                let mut solved = None;
                for fraction in IMPERFECTION_RAMP {
                    system = system.with_moved_nodes(seeded(fraction), materials)?;
                    solved = Some(
                        equilibrium::solve(&mut newton, &mut system, &mut u, &bc, &single_solve)
                            .map_err(|e| stage_failure(2, d0, e.into()))?,
                    );
                }
                solved.expect("the ramp ends at the whole imperfection")
            }
        };
    }
    let mut record = StepRecord::new((d0, d0), &report, start.elapsed().as_secs_f64());
    measure_all(&bilayer_measures(), &system, &u, &mut record)?;
    observer(Event::Step {
        record: &record,
        system: &system,
        u: &u,
    })?;
    quiet.set(false);
    observer(Event::Stage(&format!(
        "stage 3: {} to d = {}",
        match protocol.method {
            ContinuationMethod::Displacement => "displacement control",
            ContinuationMethod::ArcLength => "arc-length continuation",
        },
        protocol.d_max
    )))?;
    let mut continuation: Box<dyn PathFollowing<System>> = match protocol.method {
        ContinuationMethod::ArcLength => Box::new(
            ArcLength::new((system, newton, protocol.newton), protocol.control, d0, u)?
                .with_measures(bilayer_measures()),
        ),
        ContinuationMethod::Displacement => {
            let mut path = displacement_control(system, newton, (d0, u), materials, protocol)?;
            if let Some(interval) = resumption.checkpoints {
                interval.validate()?;
                path = path.with_checkpoints(interval);
            }
            if let Some(state) = resumption.from {
                path.resume(state)?;
            }
            Box::new(path)
        }
    };
    let stopped = continuation.advance_to(protocol.d_max, &mut observer).err();
    Ok(Outcome { continuation, stopped })
}

/// Stage 3's displacement control from the state `u` at `d0`, with contact and the way across
/// a snap the protocol asks for.
fn displacement_control(
    system: System,
    newton: Newton,
    (d0, u): (f64, Vec<f64>),
    materials: &Bilayer,
    protocol: &Protocol,
) -> Result<Continuation> {
    let damping = protocol
        .crossing
        .damping()
        .map(|settings| settings.for_largest_step(protocol.control.max));
    let augmentation = (protocol.contact || damping.is_some())
        .then(|| Augmentation::new(&system, materials, protocol.contact, damping))
        .transpose()?;
    // The first step is predicted along the homogeneous path's du/dd (central difference).
    let homogeneous =
        |d: f64| -> Result<Vec<f64>> { homogeneous_unknowns(&system, materials, &homogeneous_state(materials, d)?) };
    let h = 1e-3;
    let (ahead, behind) = (homogeneous(d0 + h)?, homogeneous(d0 - h)?);
    let slope = ahead.iter().zip(&behind).map(|(a, b)| (a - b) / (2.0 * h)).collect();
    let mut continuation = Continuation::new((system, newton, protocol.newton), protocol.control, d0, u)?
        .with_first_slope(slope)
        .with_measures(bilayer_measures());
    if let Some(augmentation) = augmentation {
        continuation = continuation.with_augmentation(augmentation);
    }
    if let Some(snaps) = protocol.crossing.minimisation() {
        continuation = continuation.with_snaps(snaps);
    }
    Ok(continuation)
}

/// A failure of stage 1 or 2 at `d`, named.
fn stage_failure(stage: usize, d: f64, e: Error) -> Error {
    let hint = match stage {
        2 => " (an onset near this d, as of a very stiff layer, needs a lower --d-start or a smaller imperfection)",
        _ => "",
    };
    Error::Solver(format!("stage {stage} at d = {d} failed: {e}{hint}"))
}
