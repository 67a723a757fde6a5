//! What `simulate` computes, in memory: the path, its summaries, the secondary modes and the
//! fields of the last state. [`super::run`] is this followed by writing (its files stream from
//! an observer of every step, so that a crash keeps the path so far); the Python package takes
//! the [`Solution`] as it is.

use super::checkpoint::SolveMemory;
use super::secondary::{ModeState, SecondaryTracker};
use super::{ContactReport, Curve, EllipticityReport, Monitor, OnsetReport, Recorder, SecondaryReport, SimulateStudy};
use crate::error::Error;
use crate::error::Result;
use crate::fem::fields::{cell_fields, CellFields};
use crate::fem::System;
use crate::material::Bilayer;
use crate::mesh::{X, Y};
use crate::parameters::Parameters;
use crate::protocol::secondary::{branch, secondary_mode, SecondaryMode};
use crate::protocol::Loading;
use crate::protocol::{stages, surface_profile, Event, SnapRecord};
use stages::Resumption;

/// A mesh state ready for a viewer: reference points, 9-node cells (the local node order of
/// [`crate::mesh`]; [`super::CELL_TYPE`] gives VTK's), the nodal displacement and the element-centre
/// fields of the VTU files.
#[derive(Clone, Debug)]
pub struct StateFields {
    pub points: Vec<[f64; 2]>,
    pub cells: Vec<[usize; 9]>,
    /// `[u_x, u_y]` per point.
    pub displacement: Vec<[f64; 2]>,
    pub cell: CellFields,
}

/// What `simulate` computes, without files.
pub struct Solution {
    /// Accepted steps, cuts, and why the path stopped early (if it did).
    pub curve: Curve,
    /// The `d` of the last converged state.
    pub d_reached: f64,
    pub onset: OnsetReport,
    pub contact: ContactReport,
    /// Every snap of the path.
    pub snaps: Vec<SnapRecord>,
    /// Every change of the tangent's inertia (secondary bifurcations), the modes of the first
    /// few, and the branch the path ended on.
    pub secondary: SecondaryReport,
    /// Where the finite-element states lose strong ellipticity.
    pub ellipticity: EllipticityReport,
    /// Deformed `(x, y)` of the top surface at the last state, by reference `X`.
    pub surface: Vec<(f64, f64)>,
    /// The last converged state.
    pub state: StateFields,
}

/// A [`Solution`] with what writing its files needs: the materials, the system at the last
/// state, that state, and the states and vectors of the secondary modes.
pub struct Solved {
    pub solution: Solution,
    pub materials: Bilayer,
    pub system: System,
    pub u: Vec<f64>,
    pub modes: Vec<ModeState>,
}

/// Runs `study` as `simulate` does and keeps everything in memory. A failure in stages 1-2 is
/// an error; a stop in stage 3 (solver failure, or the monitor's error) is kept in
/// `curve.stopped` with the path up to it.
pub fn solve(params: &Parameters, study: &SimulateStudy, monitor: Monitor) -> Result<Solution> {
    Ok(solve_observed(params, study, monitor, None, &mut |_, _| Ok(()))?.solution)
}

/// What [`solve_observed`] shows its observer: an event of the path, or, when a checkpoint is
/// due, everything kept in memory that a resumed run needs.
pub enum Observed<'a> {
    Event(&'a Event<'a>),
    Checkpoint(&'a SolveMemory),
}

/// [`solve`], from `resume` if given, showing every event (and every checkpoint the study asks
/// for) to `observer` with the materials as it happens (an error it returns stops the path like
/// a solver failure), and keeping the final system for writing.
pub fn solve_observed(
    params: &Parameters,
    study: &SimulateStudy,
    monitor: Monitor,
    resume: Option<SolveMemory>,
    observer: &mut dyn FnMut(Observed<'_>, &Bilayer) -> Result<()>,
) -> Result<Solved> {
    params.validate()?;
    study.validate()?;
    let materials = Bilayer::new(params);
    let (mut recorder, mut tracker, from) = match resume {
        Some(memory) => (
            Recorder::resumed(monitor, memory.records, memory.cuts),
            memory.tracker,
            Some(memory.path),
        ),
        None => (
            Recorder::new(monitor),
            SecondaryTracker::new(study.secondary_modes),
            None,
        ),
    };
    let resumption = Resumption {
        from,
        checkpoints: study.checkpoints,
    };
    let outcome = stages::run_resumable(&materials, study.mesh, &study.protocol, resumption, &mut |event| {
        if let Event::Checkpoint(path) = &event {
            let memory = SolveMemory {
                path: (*path).clone(),
                records: recorder.records.clone(),
                cuts: recorder.cuts.clone(),
                tracker: tracker.clone(),
            };
            return observer(Observed::Checkpoint(&memory), &materials);
        }
        if let Event::Step { record, u, .. } = &event {
            tracker.note(record, u);
        }
        observer(Observed::Event(&event), &materials)?;
        recorder.note(&event)
    })?;
    finish(params, study, materials, recorder, tracker, outcome)
}

/// How [`solve_to_secondary`] ended.
pub enum ToSecondary {
    /// The inertia never changed: the whole run.
    Whole(Box<Solution>),
    /// It first changed at the state `d`: the mode nearest zero there.
    Changed(SecondaryMode),
}

/// Runs `study` like [`solve`], but stops at the first change of the tangent's inertia and
/// returns the mode that takes over there instead of the path.
pub fn solve_to_secondary(params: &Parameters, study: &SimulateStudy) -> Result<ToSecondary> {
    params.validate()?;
    study.validate()?;
    let materials = Bilayer::new(params);
    let mut recorder = Recorder::new(&|_| Ok(()));
    let mut tracker = SecondaryTracker::new(study.secondary_modes);
    let mut last = None;
    let mut changed = None;
    let outcome = stages::run(&materials, study.mesh, &study.protocol, &mut |event| {
        if let Event::Step { record, system, u } = &event {
            if let Some(negative) = record.negative_pivots {
                if last.is_some_and(|l| l != negative) {
                    changed = Some(secondary_mode(&materials, system.mesh(), u, record.d));
                    return Err(Error::Interrupted("the inertia changed".into()));
                }
                last = Some(negative);
            }
            tracker.note(record, u);
        }
        recorder.note(&event)
    })?;
    match changed {
        Some(mode) => Ok(ToSecondary::Changed(mode?)),
        None => Ok(ToSecondary::Whole(Box::new(
            finish(params, study, materials, recorder, tracker, outcome)?.solution,
        ))),
    }
}

/// The [`Solved`] run of a finished path.
fn finish(
    params: &Parameters,
    study: &SimulateStudy,
    materials: Bilayer,
    recorder: Recorder<'_>,
    tracker: SecondaryTracker,
    mut outcome: stages::Outcome,
) -> Result<Solved> {
    // No two factors at once: the path's is freed before the modes factorise their tangents
    // (its analysis is kept for them).
    let analysed = outcome.continuation.analysed_solver();
    outcome.continuation.release_factorisation();
    let d_reached = outcome.continuation.d();
    let (mut system, u) = outcome.continuation.into_state();
    let mesh = system.mesh().clone();
    let state = StateFields {
        points: mesh.coordinates().to_vec(),
        cells: mesh.elements().to_vec(),
        displacement: (0..mesh.num_nodes())
            .map(|n| [u[mesh.dofs().dof(n, X)], u[mesh.dofs().dof(n, Y)]])
            .collect(),
        cell: cell_fields(&system, &materials, &u)?,
    };
    let curve = recorder.into_curve(outcome.stopped);
    let p = &study.protocol;
    let (secondary, modes) = tracker.finish(
        &curve.records,
        &mut system,
        branch(&mesh, &u, p.k, p.imperfection),
        (p.imperfection2, p.imperfection2_waves),
        analysed,
    )?;
    // The modes load the system to their states; it is handed back at the last one.
    system.load_to(d_reached)?;
    Ok(Solved {
        solution: Solution {
            d_reached,
            onset: OnsetReport::new(params, p.k, study.mesh.length, &curve)?,
            contact: ContactReport::new(&curve.records),
            snaps: curve.records.iter().filter_map(|r| r.snap.clone()).collect(),
            secondary,
            ellipticity: EllipticityReport::new(curve.records.iter().map(|r| (r.d, r.ellipticity))),
            surface: surface_profile(&mesh, &u),
            state,
            curve,
        },
        materials,
        system,
        u,
        modes,
    })
}
