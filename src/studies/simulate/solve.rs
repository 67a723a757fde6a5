//! A run kept in memory instead of written to files (the Python package): the path, its
//! summaries and the fields of the last state, from the same protocol as [`super::run`].

use super::{ContactReport, Curve, Monitor, OnsetReport, Recorder, SimulateStudy};
use crate::error::Error;
use crate::error::Result;
use crate::fem::fields::{cell_fields, CellFields};
use crate::material::Bilayer;
#[cfg(doc)]
use crate::output::vtu::vtk_cell;
use crate::parameters::Parameters;
use crate::protocol::secondary::{branch, inertia_changes, secondary_mode, Branch, InertiaChange, SecondaryMode};
use crate::protocol::Event;
use crate::protocol::{stages, surface_profile};

/// A mesh state ready for a viewer: reference points, 9-node cells (the local node order of
/// [`crate::mesh`]; [`vtk_cell`] gives VTK's), the nodal displacement and the element-centre
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
    pub onset: OnsetReport,
    pub contact: ContactReport,
    /// Every change of the tangent's inertia (secondary bifurcations).
    pub inertia_changes: Vec<InertiaChange>,
    /// The branch the path ended on (depths of the seeded troughs at the last state).
    pub branch: Branch,
    /// Deformed `(x, y)` of the top surface at the last state, by reference `X`.
    pub surface: Vec<(f64, f64)>,
    /// The last converged state.
    pub state: StateFields,
}

/// Runs `study` as `simulate` does and keeps everything in memory. A failure in stages 1-2 is
/// an error; a stop in stage 3 (solver failure, or the monitor's error) is kept in
/// `curve.stopped` with the path up to it.
pub fn solve(params: &Parameters, study: &SimulateStudy, monitor: Monitor) -> Result<Solution> {
    params.validate()?;
    study.validate()?;
    let materials = Bilayer::new(params);
    let mut recorder = Recorder::new(monitor);
    let outcome = stages::run(&materials, study.mesh, &study.protocol, &mut |event| {
        recorder.note(&event)
    })?;
    finish(params, study, &materials, recorder, outcome)
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
        }
        recorder.note(&event)
    })?;
    match changed {
        Some(mode) => Ok(ToSecondary::Changed(mode?)),
        None => Ok(ToSecondary::Whole(Box::new(finish(
            params, study, &materials, recorder, outcome,
        )?))),
    }
}

/// The [`Solution`] of a finished run.
fn finish(
    params: &Parameters,
    study: &SimulateStudy,
    materials: &Bilayer,
    recorder: Recorder<'_>,
    outcome: stages::Outcome,
) -> Result<Solution> {
    let continuation = &outcome.continuation;
    let (system, u) = (continuation.system(), continuation.displacement());
    let mesh = system.mesh();
    let branch = branch(mesh, u, study.protocol.k);
    let surface = surface_profile(mesh, u);
    let state = StateFields {
        points: mesh.coordinates().to_vec(),
        cells: mesh.elements().to_vec(),
        displacement: u[..mesh.num_dofs()].chunks(2).map(|c| [c[0], c[1]]).collect(),
        cell: cell_fields(system, materials, u)?,
    };
    let curve = recorder.into_curve(outcome.stopped);
    let onset = OnsetReport::new(params, study.protocol.k, study.mesh.length, &curve)?;
    let contact = ContactReport::new(&curve.records);
    let inertia_changes = inertia_changes(&curve.records);
    Ok(Solution {
        curve,
        onset,
        contact,
        inertia_changes,
        branch,
        surface,
        state,
    })
}
