//! `secondary.json`: every change of the tangent's inertia along the run (the secondary
//! bifurcations of the wrinkled path, [`crate::protocol::secondary`]), the mode of the first few
//! (`secondary_mode_<i>.vtu`, and the top-surface `u_y` of the first in `secondary_mode.png`),
//! and the branch the run ended on.

use super::{nodal_array, write_state};
use crate::error::Result;
use crate::fem::{SparseLdlt, System};
use crate::material::Bilayer;
use crate::mesh::Mesh;
use crate::output::{write_json, Figure, LineStyle, Series};
use crate::protocol::bifurcation::{dominant_cosine, top_uy};
use crate::protocol::secondary::{inertia_changes, modes_nearest_zero, Branch, InertiaChange};
use crate::protocol::Loading;
use crate::protocol::StepRecord;
use serde::Serialize;
use std::path::{Path, PathBuf};

/// How many modes `simulate` computes and writes by default (the first changes).
pub const MODES: usize = 3;
/// Largest number of solves (Lanczos steps on `K^-1`) per mode.
const MODE_SOLVES: usize = 60;

/// Keeps the states just after the first few changes of the inertia.
#[derive(Clone, Debug, Serialize, serde::Deserialize)]
pub struct SecondaryTracker {
    modes: usize,
    last: Option<usize>,
    states: Vec<(f64, Vec<f64>)>,
}

impl SecondaryTracker {
    /// Keeps the states of the first `modes` changes.
    pub fn new(modes: usize) -> Self {
        SecondaryTracker {
            modes,
            last: None,
            states: Vec::new(),
        }
    }

    /// Looks at one accepted state.
    pub fn note(&mut self, record: &StepRecord, u: &[f64]) {
        let Some(negative) = record.negative_pivots else { return };
        if self.last.is_some_and(|last| last != negative) && self.states.len() < self.modes {
            self.states.push((record.d, u.to_vec()));
        }
        self.last = Some(negative);
    }
}

/// The state just after a change and the mode nearest zero there.
pub struct ModeState {
    pub d: f64,
    pub u: Vec<f64>,
    pub mode: Vec<f64>,
}

/// One change with its mode.
#[derive(Clone, Debug, Serialize)]
pub struct SecondaryChange {
    #[serde(flatten)]
    pub change: InertiaChange,
    /// Eigenvalue nearest zero of the elastic tangent after the change, and its mode's dominant
    /// number of half wavelengths across the domain (`None` past the first few changes).
    pub eigenvalue: Option<f64>,
    pub mode_half_waves: Option<usize>,
    pub mode_file: Option<String>,
}

/// `secondary.json`.
#[derive(Clone, Debug, Serialize)]
pub struct SecondaryReport {
    /// First `d` with a changed inertia (`None`: none, or inertia not tracked).
    pub d_secondary: Option<f64>,
    pub changes: Vec<SecondaryChange>,
    pub inertia_tracked: bool,
    pub imperfection2: f64,
    pub imperfection2_waves: f64,
    /// The branch the run ended on, from the depths of the seeded troughs.
    pub branch: Branch,
    pub note: &'static str,
}

const SECONDARY_NOTE: &str = "The inertia is the number of negative pivots of the undamped tangent (elastic plus \
    contact) at every accepted state; a change between d_before and d_after brackets a bifurcation or limit point \
    of the computed path, and d_secondary is the d_after of the first change. Modes come from the Lanczos method on \
    the inverse of the elastic tangent (contact stiffness left out) at d_after. branch compares the depths of the seeded troughs \
    at the last state: 'periodic' if all are within 20 % of the deepest, 'localised' if the deepest leads the next \
    by more than that, 'modulated' otherwise (several deep troughs between shallow ones).";

impl SecondaryTracker {
    /// The report of the path `records` ending on `branch`, with the modes of the first changes
    /// (their eigenvalues and half waves in the report, their vectors returned).
    pub fn finish(
        self,
        records: &[StepRecord],
        system: &mut System,
        branch: Branch,
        (imperfection2, imperfection2_waves): (f64, f64),
        analysed: Option<(usize, SparseLdlt)>,
    ) -> Result<(SecondaryReport, Vec<ModeState>)> {
        let mut changes: Vec<SecondaryChange> = inertia_changes(records)
            .into_iter()
            .map(|change| SecondaryChange {
                change,
                eigenvalue: None,
                mode_half_waves: None,
                mode_file: None,
            })
            .collect();
        // The path's system: its pattern (and so its memory) serves the modes too.
        let states: Vec<(f64, &[f64])> = self.states.iter().map(|(d, u)| (*d, &u[..])).collect();
        let found = modes_nearest_zero(system, &states, MODE_SOLVES, analysed)?;
        let mesh = system.mesh();
        let mut modes = Vec::with_capacity(found.len());
        for (((d, u), change), (mode, eigenvalue)) in self.states.into_iter().zip(changes.iter_mut()).zip(found) {
            change.eigenvalue = Some(eigenvalue);
            change.mode_half_waves = Some(dominant_cosine(&top_uy(mesh, &mode), mesh.spec().length, mesh));
            modes.push(ModeState { d, u, mode });
        }
        let report = SecondaryReport {
            d_secondary: changes.first().map(|c| c.change.d_after),
            changes,
            inertia_tracked: records.iter().any(|r| r.negative_pivots.is_some()),
            imperfection2,
            imperfection2_waves,
            branch,
            note: SECONDARY_NOTE,
        };
        Ok((report, modes))
    }
}

/// Writes each mode (`secondary_mode_<i>.vtu`, the first one's top surface in
/// `secondary_mode.png`), names its file in `report`, and writes `secondary.json` into `out`.
/// The system is left loaded to the last mode's state.
pub fn write_secondary(
    report: &mut SecondaryReport,
    modes: &[ModeState],
    system: &mut System,
    materials: &Bilayer,
    out: &Path,
) -> Result<Vec<PathBuf>> {
    let mut files = Vec::new();
    for (i, (state, change)) in modes.iter().zip(report.changes.iter_mut()).enumerate() {
        system.load_to(state.d)?; // the fields of a grown state need its growth
        let mesh = system.mesh();
        let path = out.join(format!("secondary_mode_{i}.vtu"));
        let array = nodal_array("mode", mesh, &state.mode);
        write_state(&path, system, materials, &state.u, vec![array])?;
        if i == 0 {
            files.extend(mode_figure(mesh, &top_uy(mesh, &state.mode), state.d).save(out, "secondary_mode")?);
        }
        change.mode_file = Some(path.display().to_string());
        files.push(path);
    }
    let json = out.join("secondary.json");
    write_json(&json, report)?;
    files.push(json);
    Ok(files)
}

/// The top-surface `u_y` of a mode against the reference `X`.
fn mode_figure(mesh: &Mesh, uy: &[f64], d: f64) -> Figure {
    let x = mesh.top().into_iter().map(|n| mesh.coordinates()[n][0]);
    Figure::new(
        format!("First secondary bifurcation mode, d = {d:.4}"),
        "reference X / H",
        "mode u_y on the top surface (largest = 1)",
    )
    .with(Series::new(
        "",
        x.zip(uy.iter().copied()).collect(),
        LineStyle::Solid,
        0,
    ))
}
