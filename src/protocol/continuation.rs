//! Displacement control in `d` with adaptive steps and an extrapolating predictor.
//!
//! Each step tries `d + h`: the predictor extrapolates the displacement through the last (up
//! to four) converged states (cubic Lagrange polynomial in `d`; the prescribed unknowns are set
//! exactly; from a single state, along a given slope `du/dd` if there is one, otherwise
//! Newton's lifted first step is the tangent predictor), then
//! Newton's method corrects it. A step that converges in at most `easy_iterations` grows
//! `h` by `grow`; a failure (no convergence, line search, `J <= 0` anywhere) discards the trial
//! and cuts `h` by `cut`. A failure at the minimum step stops the continuation.
//!
//! Where a step of at most [`SnapSettings::below`] (or the minimum step) fails, the
//! continuation instead minimises the energy at that `d` (`Continuation::snap`,
//! [`super::snap`]): the stable state the structure snaps to, from which the path goes on (its
//! predictor restarts from that state).
//!
//! [`Continuation::advance_to`] reads as the algorithm: `Continuation::attempt` (predict,
//! correct), then `Continuation::accept` (record, grow), or a snap, or `Continuation::cut`.

use super::augmentation::AugmentedRecord;
use super::measures::{measure_all, Measure};
use super::predictor::{extrapolate, PREDICTOR_POINTS};
use super::record::StepRecord;
use super::snap::{SnapRecord, SnapSettings};
use crate::error::{Error, Result};
use crate::fem::{Newton, NewtonPolicy, NewtonReport, Reuse, SparseLdlt, System};
use serde::{Deserialize, Serialize};
use std::collections::VecDeque;
use std::time::Instant;

mod arc_length;
mod followed;
mod method;
mod minimised;
mod resumable;
pub use arc_length::ArcLength;
pub(crate) use followed::plain_linearised;
pub use followed::{Augmenting, Followed, NoAugmentation};
pub use method::{ContinuationMethod, PathFollowing};
pub use resumable::{CheckpointInterval, PathState};

/// Step-size control.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct StepControl {
    /// First step.
    pub initial: f64,
    /// Largest step: also the largest gap in `d` between recorded states.
    pub max: f64,
    /// Smallest step; a failure at this step stops the continuation.
    pub min: f64,
    /// Factor applied after an easy step (> 1).
    pub grow: f64,
    /// Factor applied after a failure (in (0, 1)).
    pub cut: f64,
    /// A step converged with at most this many newly factorised tangents is easy.
    pub easy_iterations: usize,
}

impl Default for StepControl {
    /// Steps of 0.005 (the recording interval), cut by 4 down to 1e-5, grown by 1.5 after <= 3 iterations.
    fn default() -> Self {
        StepControl {
            initial: 0.005,
            max: 0.005,
            min: 1e-5,
            grow: 1.5,
            cut: 0.25,
            easy_iterations: 3,
        }
    }
}

impl StepControl {
    /// Checks that the steps lie in `(0, 1)` with `min <= max`, `grow >= 1` and `cut` in `(0, 1)`.
    pub fn validate(&self) -> Result<()> {
        let in_unit_interval = |name: &str, v: f64| {
            if v.is_finite() && v > 0.0 && v < 1.0 {
                Ok(())
            } else {
                Err(Error::invalid(name, v, "(0, 1)"))
            }
        };
        in_unit_interval("max-step", self.max)?;
        in_unit_interval("min-step", self.min)?;
        in_unit_interval("initial step", self.initial)?;
        in_unit_interval("step cut factor", self.cut)?;
        if self.min > self.max {
            return Err(Error::invalid(
                "min-step",
                self.min,
                &format!("(0, max-step = {}]", self.max),
            ));
        }
        if !(self.grow.is_finite() && self.grow >= 1.0) {
            return Err(Error::invalid("step growth factor", self.grow, "[1, inf)"));
        }
        Ok(())
    }
}

/// A failed attempt that was discarded.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Cut {
    /// The `d` tried.
    pub d: f64,
    /// The step tried.
    pub step: f64,
    /// Why it failed.
    pub reason: String,
}

/// What a loading protocol reports as it goes (of a system `S`).
pub enum Event<'a, S = System> {
    /// The start of a stage, described.
    Stage(&'a str),
    /// A converged state, with its system and displacement.
    Step {
        record: &'a StepRecord,
        system: &'a S,
        u: &'a [f64],
    },
    /// A discarded attempt; the step is cut.
    Cut(&'a Cut),
    /// The whole state after an accepted step, when a checkpoint is due
    /// ([`Continuation::with_checkpoints`]): the state is reported before it.
    Checkpoint(&'a PathState),
}

/// The solution path in `d` of a system `S`: the current converged state and the last few for
/// the predictor.
pub struct Continuation<S: Followed = System> {
    system: S,
    newton: Newton,
    /// Newton's policy of every step (its reuse set per step, see [`Continuation::attempt`]).
    policy: NewtonPolicy,
    control: StepControl,
    step: f64,
    /// Up to four converged `(d, u)`, newest last.
    history: VecDeque<(f64, Vec<f64>)>,
    /// Contact and stabilisation, if any.
    augmentation: Option<S::Augmentation>,
    /// When a failed step is retried as a snap (never if `None`).
    snaps: Option<SnapSettings>,
    /// `du/dd` for the predictor while only one state is known.
    slope: Option<Vec<f64>>,
    /// The record of the last accepted state (the newest in `history`) while its inertia is
    /// still being counted: reported once it is known.
    pending: Option<StepRecord>,
    /// What is recorded of each accepted state.
    measures: Vec<Box<dyn Measure<S>>>,
    /// What is known of the last accepted state.
    last: LastState,
    /// Whether the path halts at the first accepted state that is unstable
    /// ([`Continuation::halting_where_unstable`]).
    halt_where_unstable: bool,
    /// When the whole state is reported, if ever.
    checkpoints: Option<resumable::Checkpoints>,
    /// Unstable states the path has left ([`Continuation::leave_unstable_state`]).
    unstable_states_left: usize,
}

/// Whether the last accepted state is stable (its inertia counted, none negative) and in
/// contact: where a step from it may be corrected by minimisation
/// ([`Continuation::attempt_by_minimisation`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
struct LastState {
    stable: bool,
    /// Its inertia is counted, with a negative pivot.
    unstable: bool,
    in_contact: bool,
}

/// A converged attempt: Newton's report, the displacement, and what contact and
/// stabilisation report.
type Solved = (NewtonReport, Vec<f64>, Option<AugmentedRecord>);

/// How an accepted state was reached.
enum Reached {
    /// Newton's iteration from the predictor.
    Newton,
    /// Minimising the energy from the predictor, after Newton's iteration failed
    /// ([`Continuation::attempt_by_minimisation`]).
    Minimisation,
    /// A snap from the last equilibrium ([`Continuation::snap`]).
    Snap(SnapRecord),
}

/// The wall time of the step being tried, and of its attempts discarded so far.
struct StepClock {
    started: Instant,
    failed_seconds: f64,
}

impl StepClock {
    fn start() -> Self {
        StepClock {
            started: Instant::now(),
            failed_seconds: 0.0,
        }
    }
}

impl<S: Followed> Continuation<S> {
    /// Starts at the converged state `u` at `d`, solving with `newton` (and its cached factor)
    /// by `policy`.
    pub fn new(
        (system, newton, policy): (S, Newton, NewtonPolicy),
        control: StepControl,
        d: f64,
        u: Vec<f64>,
    ) -> Result<Self> {
        control.validate()?;
        Ok(Continuation {
            system,
            newton,
            policy,
            step: control.initial.min(control.max),
            control,
            history: VecDeque::from([(d, u)]),
            augmentation: None,
            snaps: None,
            slope: None,
            pending: None,
            measures: Vec::new(),
            last: LastState::default(),
            halt_where_unstable: false,
            checkpoints: None,
            unstable_states_left: 0,
        })
    }

    /// The same continuation recording `measures` of every accepted state.
    pub fn with_measures(mut self, measures: Vec<Box<dyn Measure<S>>>) -> Self {
        self.measures = measures;
        self
    }

    /// The same continuation with contact and stabilisation.
    pub fn with_augmentation(mut self, augmentation: S::Augmentation) -> Self {
        self.augmentation = Some(augmentation);
        self
    }

    /// The same continuation retrying failed short steps as snaps, and counting the inertia
    /// of every accepted state: a failed step is corrected by minimisation only from a state
    /// known to be stable (`Continuation::attempt_by_minimisation`). Without the count every
    /// contact pair that closed or opened within a step was cut down to a snap of its own:
    /// measured on the small mesh of `tests/sweep.rs` (beta = pi/4, mu_l / mu_s = 3), 716
    /// snaps and 2987 states to d = 0.48 in 108 s at K/mu = 100, and no end in 18 minutes at
    /// K/mu = 1e4, against 2 snaps in 2 s and 15 snaps in 8 s with it.
    pub fn with_snaps(mut self, snaps: SnapSettings) -> Self {
        self.snaps = Some(snaps);
        self.policy.inertia_at_solution = true;
        self
    }

    /// The same continuation halting, before its target, at the first accepted state whose
    /// tangent has a negative eigenvalue ([`Continuation::is_unstable`]): a branch the
    /// structure would leave, which it may then do ([`Continuation::leave_unstable_state`]).
    /// The inertia of every state is counted.
    pub fn halting_where_unstable(mut self) -> Self {
        self.halt_where_unstable = true;
        self.policy.inertia_at_solution = true;
        self
    }

    /// Whether the current state is known to be unstable (a negative eigenvalue of its tangent).
    pub fn is_unstable(&self) -> bool {
        self.last.unstable
    }

    /// The same continuation predicting its first step along `du/dd = slope` (all unknowns),
    /// e.g. that of the homogeneous path: then the surface moves with the compressed domain
    /// from the start, instead of lagging the moved boundary as the lifted step does.
    pub fn with_first_slope(mut self, slope: Vec<f64>) -> Self {
        self.slope = Some(slope);
        self
    }

    /// Contact and stabilisation, if any.
    pub fn augmentation(&self) -> Option<&S::Augmentation> {
        self.augmentation.as_ref()
    }

    /// The current end-shortening.
    pub fn d(&self) -> f64 {
        self.history.back().expect("never empty").0
    }

    /// The current converged displacement.
    pub fn displacement(&self) -> &[f64] {
        &self.history.back().expect("never empty").1
    }

    /// A solver sharing the analysis of the path's tangents, and the structure id it is for
    /// ([`Newton::analysed_solver`]): post-processing on the same pattern skips its own.
    pub fn analysed_solver(&self) -> Option<(usize, SparseLdlt)> {
        self.newton.analysed_solver()
    }

    /// Frees the factorisation Newton keeps between steps (before post-processing a finished
    /// path, so that two factors are never held at once).
    pub fn release_factorisation(&mut self) {
        self.newton.release_factorisation();
        if let Some(augmentation) = &mut self.augmentation {
            augmentation.release_factorisation();
        }
        crate::fem::memory::return_free_pages();
    }

    /// The system being solved.
    pub fn system(&self) -> &S {
        &self.system
    }

    /// The system at the current state's load, for post-processing of that state (an
    /// assembly, a factorisation); the path goes on from the current state whatever is done
    /// with it.
    pub fn system_mut(&mut self) -> &mut S {
        &mut self.system
    }

    /// The system and the current converged displacement, for post-processing.
    pub fn into_state(self) -> (S, Vec<f64>) {
        let (_, u) = self.history.into_iter().next_back().expect("never empty");
        (self.system, u)
    }

    /// Advances to `target`, reporting every accepted step and every cut; stops with
    /// [`Error::Solver`] naming `d` and the reason when the minimum step fails. A state whose
    /// inertia is counted in the background is reported once the count is in, before anything
    /// that follows it.
    pub fn advance_to(&mut self, target: f64, observer: &mut dyn FnMut(Event<'_, S>) -> Result<()>) -> Result<()> {
        let result = self.advance(target, observer);
        let reported = self.report_pending(observer, false);
        result.and(reported)
    }

    fn advance(&mut self, target: f64, observer: &mut dyn FnMut(Event<'_, S>) -> Result<()>) -> Result<()> {
        let mut clock = StepClock::start();
        while target - self.d() > 1e-12 && !(self.halt_where_unstable && self.last.unstable) {
            let step = self.step.min(target - self.d());
            let d = self.d() + step;
            let attempt_started = Instant::now();
            let attempt = self.attempt(d, step);
            let attempt_seconds = attempt_started.elapsed().as_secs_f64();
            self.report_pending(observer, true)?;
            // Time of the tries a cut discards: the attempt, and its minimisation and snap if any.
            let mut discarded_seconds = attempt_seconds;
            let attempt = match attempt {
                Err(reason) if self.snaps.is_some() => {
                    let started = Instant::now();
                    let minimised = self.attempt_by_minimisation(d);
                    discarded_seconds += started.elapsed().as_secs_f64();
                    match minimised {
                        Some(solved) => {
                            clock.failed_seconds += attempt_seconds;
                            Ok((solved, Reached::Minimisation))
                        }
                        None => Err(reason),
                    }
                }
                attempt => attempt.map(|solved| (solved, Reached::Newton)),
            };
            let reason = match attempt {
                Ok(reached) => {
                    self.accept((d, step), reached, &clock, observer)?;
                    clock = StepClock::start();
                    continue;
                }
                Err(reason) => reason,
            };
            let reason = match self.snaps {
                Some(snaps) if step <= snaps.below.max(self.control.min) * (1.0 + 1e-9) => {
                    let started = Instant::now();
                    match self.snap(d) {
                        Ok((solved, snap)) => {
                            clock.failed_seconds += discarded_seconds;
                            self.accept((d, step), (solved, Reached::Snap(snap)), &clock, observer)?;
                            clock = StepClock::start();
                            continue;
                        }
                        Err(e) => {
                            discarded_seconds += started.elapsed().as_secs_f64();
                            Error::Solver(format!("{reason}; the snap at this d failed too: {e}"))
                        }
                    }
                }
                _ => reason,
            };
            self.cut(d, step, reason, observer)?;
            clock.failed_seconds += discarded_seconds;
        }
        Ok(())
    }

    /// Records the converged state at `d` (now, or once its inertia is counted), keeps it for
    /// the predictor, and grows the step if Newton's iteration found it easily. After a snap,
    /// the predictor restarts from the new state alone.
    fn accept(
        &mut self,
        (d, step): (f64, f64),
        ((report, u, augmented), reached): (Solved, Reached),
        clock: &StepClock,
        observer: &mut dyn FnMut(Event<'_, S>) -> Result<()>,
    ) -> Result<()> {
        let mut record = StepRecord::new((d, step), &report, clock.started.elapsed().as_secs_f64());
        measure_all(&self.measures, &self.system, &u, &mut record)?;
        let pending = augmented.as_ref().is_some_and(|a| a.inertia_pending);
        self.last = LastState {
            stable: report.negative_pivots == Some(0),
            unstable: report.negative_pivots.is_some_and(|n| n > 0),
            in_contact: augmented.as_ref().is_some_and(|a| a.in_contact),
        };
        record.augmented = augmented;
        if let Some(augmentation) = &mut self.augmentation {
            augmentation.note_accepted(if pending { None } else { report.negative_pivots });
        }
        record.failed_seconds = clock.failed_seconds;
        let by_newton = matches!(reached, Reached::Newton);
        record.minimised = matches!(reached, Reached::Minimisation);
        // After a snap the predictor restarts from the new state; the history is cleared only
        // once the observer has taken it, so that a path the observer stops keeps its last state.
        let snapped = matches!(reached, Reached::Snap(_));
        if let Reached::Snap(snap) = reached {
            self.slope = None;
            record.snap = Some(snap);
        }
        if pending {
            self.pending = Some(record);
        } else {
            observer(Event::Step {
                record: &record,
                system: &self.system,
                u: &u,
            })?;
        }
        if snapped {
            self.history.clear();
        }
        // Each step starts without a factorisation of an earlier one: a step is then a function
        // of the path's state alone, which a checkpoint holds ([`PathState`]). Only a damped or
        // contact step after one whose factor was kept loses a reuse.
        self.newton.forget_factorisation();
        self.history.push_back((d, u));
        if self.history.len() > PREDICTOR_POINTS {
            self.history.pop_front();
        }
        // A pass after an update of the multipliers takes a step or so of its own.
        let c = self.control;
        if by_newton && report.tangent_steps <= c.easy_iterations + report.updates.pressure {
            self.step = (self.step * c.grow).min(c.max);
        }
        self.checkpoint_if_due(observer)
    }

    /// Discards the failed attempt at `d` and cuts the step; at the minimum step, stops.
    fn cut(
        &mut self,
        d: f64,
        step: f64,
        reason: Error,
        observer: &mut dyn FnMut(Event<'_, S>) -> Result<()>,
    ) -> Result<()> {
        let c = self.control;
        if step <= c.min * (1.0 + 1e-9) {
            // The system stays at the last equilibrium's load, for what is written of it.
            self.system.load_to(self.d())?;
            return Err(Error::Solver(format!(
                "continuation stopped at d = {d:.6} (last converged d = {:.6}) with the minimum step {step:.3e}: {reason}",
                self.d()
            )));
        }
        observer(Event::Cut(&Cut {
            d,
            step,
            reason: reason.to_string(),
        }))?;
        self.step = (step * c.cut).max(c.min);
        Ok(())
    }

    /// Reports the state whose inertia was pending, with its count (waiting for it; the wait
    /// is booked as that state's inertia time if `within_step`, i.e. inside the next step's
    /// wall time). The observer sees the system at that state's load, not the next attempt's
    /// (under growth the tissues depend on it).
    fn report_pending(
        &mut self,
        observer: &mut dyn FnMut(Event<'_, S>) -> Result<()>,
        within_step: bool,
    ) -> Result<()> {
        let Some(mut record) = self.pending.take() else {
            return Ok(());
        };
        let augmentation = self.augmentation.as_mut().expect("only augmented steps are pending");
        let waited = std::time::Instant::now();
        record.negative_pivots = augmentation.next_inertia();
        augmentation.note_accepted(record.negative_pivots);
        self.last.stable = record.negative_pivots == Some(0);
        self.last.unstable = record.negative_pivots.is_some_and(|n| n > 0);
        if let Some(augmented) = &mut record.augmented {
            augmented.inertia_pending = false;
            if within_step {
                augmented.inertia_seconds += waited.elapsed().as_secs_f64();
            }
        }
        let load = self.system.load();
        self.system.load_to(record.d)?;
        let (_, u) = self.history.back().expect("never empty");
        observer(Event::Step {
            record: &record,
            system: &self.system,
            u,
        })?;
        self.system.load_to(load)?;
        Ok(())
    }

    /// Predictor and Newton corrector at `d`, reached by a step of `step`; the converged
    /// displacement, or why it failed. From a single state, Newton's first (lifted) step is
    /// the predictor: the tangent one.
    fn attempt(&mut self, d: f64, step: f64) -> Result<Solved> {
        let bc = self.system.load_to(d)?;
        let mut u = self.predict(d);
        if self.history.len() > 1 || self.slope.is_some() {
            bc.impose(&mut u);
        }
        // A full-length step lies on a smooth stretch of the path: Newton may keep a fresh
        // indefinite tangent there; a cut step is near a fold, where it may not.
        let policy = match self.policy.reuse {
            Reuse::Never => self.policy,
            _ if step >= self.control.max * (1.0 - 1e-9) => NewtonPolicy {
                reuse: Reuse::AlsoIndefinite,
                ..self.policy
            },
            _ => NewtonPolicy {
                reuse: Reuse::Definite,
                ..self.policy
            },
        };
        let (d0, u0) = self.history.back().expect("never empty");
        let (report, record) = self.system.correct(
            &mut self.newton,
            &policy,
            &mut u,
            &bc,
            self.augmentation.as_mut(),
            (*d0, u0),
            (d, self.step),
        )?;
        Ok((report, u, record))
    }

    /// The predictor at `d` from the stored states (see [`extrapolate`]).
    fn predict(&self, d: f64) -> Vec<f64> {
        extrapolate(&self.history, self.slope.as_deref(), d)
    }
}
