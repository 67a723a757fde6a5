//! A path between two steps, whole: what a checkpoint keeps ([`PathState`]) and a resumed path
//! continues from. Each step is a function of the last few states (the predictor's), the step
//! control, the first step's slope, what is known of the last state's stability, and the
//! augmentation's contact pairs, multipliers and dissipated energy, and the entries the
//! tangents' sparsity has stored so far (which set their ordering, and so their round-off). No
//! factorisation is carried: every accepted state forgets Newton's. A path resumed from its
//! state therefore takes the steps the uninterrupted path takes, bit for bit, whenever its
//! checkpoints were written.

use super::{Augmenting, Continuation, Event, Followed, LastState};
use crate::error::{Error, Result};
use crate::fem::StoredEntries;
use crate::protocol::augmentation::AugmentationMemory;
use serde::{Deserialize, Serialize};
use std::collections::VecDeque;
use std::time::Instant;

/// The state of a path after an accepted step, with nothing pending.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PathState {
    /// The last (up to four) converged `(d, u)`, newest last.
    pub history: Vec<(f64, Vec<f64>)>,
    /// The step the next attempt tries.
    pub step: f64,
    /// `du/dd` for the predictor while only one state is known.
    pub slope: Option<Vec<f64>>,
    last: LastState,
    /// Contact and stabilisation, if the path has them.
    pub augmentation: Option<AugmentationMemory>,
    /// The stored entries of the tangents' sparsity.
    pub stored_entries: Option<StoredEntries>,
    /// Unstable states the path has left.
    pub unstable_states_left: usize,
}

impl PathState {
    /// The `d` of the newest state.
    pub fn d(&self) -> f64 {
        self.history.last().map_or(0.0, |(d, _)| *d)
    }
}

/// How often a path reports its whole state ([`Event::Checkpoint`]): after every `states`
/// accepted states or `seconds` of wall time, whichever comes first.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct CheckpointInterval {
    pub states: usize,
    pub seconds: f64,
}

impl CheckpointInterval {
    /// Every 25 accepted states or 300 s: on the fine Fig. 7 run, a few milliseconds per
    /// checkpoint against steps of about a second.
    pub const DEFAULT: CheckpointInterval = CheckpointInterval {
        states: 25,
        seconds: 300.0,
    };

    /// Checks `states >= 1` and `seconds > 0`.
    pub fn validate(&self) -> Result<()> {
        if self.states == 0 {
            return Err(Error::invalid(
                "checkpoint-every",
                self.states,
                "[1, inf) accepted states",
            ));
        }
        if !(self.seconds.is_finite() && self.seconds > 0.0) {
            return Err(Error::invalid("checkpoint-seconds", self.seconds, "(0, inf) seconds"));
        }
        Ok(())
    }
}

/// The checkpoints of one path: the interval, and the states and time since the last one.
pub(super) struct Checkpoints {
    interval: CheckpointInterval,
    states: usize,
    since: Instant,
}

impl Checkpoints {
    pub(super) fn new(interval: CheckpointInterval) -> Self {
        Checkpoints {
            interval,
            states: 0,
            since: Instant::now(),
        }
    }

    /// Counts an accepted state; whether a checkpoint is due after it.
    fn due(&mut self) -> bool {
        self.states += 1;
        self.states >= self.interval.states || self.since.elapsed().as_secs_f64() >= self.interval.seconds
    }

    fn written(&mut self) {
        self.states = 0;
        self.since = Instant::now();
    }
}

impl<S: Followed> Continuation<S> {
    /// The same continuation reporting its whole state every `interval` ([`Event::Checkpoint`]).
    pub fn with_checkpoints(mut self, interval: CheckpointInterval) -> Self {
        self.checkpoints = Some(Checkpoints::new(interval));
        self
    }

    /// Unstable states the path has left ([`Continuation::leave_unstable_state`]).
    pub fn unstable_states_left(&self) -> usize {
        self.unstable_states_left
    }

    /// The whole state after the last accepted step (whose inertia must not be pending).
    pub fn path_state(&self) -> PathState {
        debug_assert!(self.pending.is_none(), "a checkpoint waits for the pending inertia");
        PathState {
            history: self.history.iter().cloned().collect(),
            step: self.step,
            slope: self.slope.clone(),
            last: self.last,
            augmentation: self.augmentation.as_ref().map(Augmenting::memory),
            stored_entries: self.system.stored_entries(),
            unstable_states_left: self.unstable_states_left,
        }
    }

    /// Continues from `state`, a [`Continuation::path_state`] of a path of the same system and
    /// settings: the system is put at its load.
    pub fn resume(&mut self, state: PathState) -> Result<()> {
        let unknowns = self.displacement().len();
        if state.history.is_empty() || state.history.iter().any(|(_, u)| u.len() != unknowns) {
            return Err(Error::invalid(
                "checkpoint",
                "its states",
                &format!("states of {unknowns} unknowns, as this run's mesh has"),
            ));
        }
        match (&mut self.augmentation, state.augmentation) {
            (Some(augmentation), Some(memory)) => augmentation.recall(memory)?,
            (None, None) => {}
            _ => return Err(Error::invalid("checkpoint", "its contact", "the contact this run has")),
        }
        self.history = VecDeque::from(state.history);
        self.step = state.step;
        self.slope = state.slope;
        self.last = state.last;
        self.pending = None;
        self.unstable_states_left = state.unstable_states_left;
        self.system.recall_stored_entries(state.stored_entries)?;
        self.system.load_to(self.d())?;
        Ok(())
    }

    /// After an accepted state: when a checkpoint is due, the pending inertia is waited for and
    /// the whole state reported.
    pub(super) fn checkpoint_if_due(&mut self, observer: &mut dyn FnMut(Event<'_, S>) -> Result<()>) -> Result<()> {
        if !self.checkpoints.as_mut().is_some_and(Checkpoints::due) {
            return Ok(());
        }
        self.report_pending(observer, false)?;
        observer(Event::Checkpoint(&self.path_state()))?;
        if let Some(checkpoints) = &mut self.checkpoints {
            checkpoints.written();
        }
        Ok(())
    }
}
