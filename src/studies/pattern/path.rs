//! The pattern past the onset: the patch seeded with every wave vector critical at the
//! onset (an imperfection of the reference geometry, [`PatchImperfection`]: the first at
//! `A_init`, the others at a fraction of it) and followed in `d`
//! ([`PatchPath::follow`]), leaving for a stable state wherever the followed branch turns
//! unstable; at each state the deformed surface's spectrum, its directions of wave vectors and
//! what they make ([`classify`]).
//!
//! Writes `pattern.csv` (one row per state, flushed as it is reached), and at the last state
//! `state.vtu` (the patch, cut open along periodic sides, with the displacement) and
//! `state_top.png/svg` (its surface relief seen from above, with the fibres' projection).

use super::checkpoint::{self, PathMemory};
use super::figure;
use super::frame::PatchFrame;
use crate::error::{Error, Result};
use crate::fem::element::{Hex27, ReferenceElement};
use crate::mesh::{Mesh, TOP, Y};
use crate::output::checkpoint::{remove_checkpoint, Request};
use crate::output::table::Cell;
use crate::output::vtu::{write_vtu, CellType, DataArray};
use crate::output::CsvWriter;
use crate::protocol::patch::{
    classify, height_spectrum, surface_crosses_itself, BiaxialPatch, Direction, PatchImperfection, PatchPath,
    PatchProtocol, SurfacePattern,
};
use crate::protocol::stages::Resumption;
use crate::protocol::{CheckpointInterval, Event};
use crate::stability::oblique::BoxMode;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;
use std::path::{Path, PathBuf};

/// How the path past the onset is followed.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct PathStudy {
    /// `A_init`, the amplitude of the first seeded wave.
    pub imperfection: f64,
    /// The amplitude of every further seeded wave relative to the first's, in `[0, 1]`: below
    /// 1 the seed favours none of the patterns the critical waves make together (their equal
    /// superposition, a checkerboard, is a symmetric path that the tissue may leave).
    pub seed_ratio: f64,
    /// Where the path starts.
    pub d_start: f64,
    /// Where it ends.
    pub end: PathEnd,
}

/// Where a path past the onset ends.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PathEnd {
    /// At this `d` (`--follow-to`).
    At(f64),
    /// This far in `d` past the exact theory's onset `d_c` of the tissue (`--follow-past`):
    /// every point of a map of patterns then ends as far past its own onset.
    PastOnset(f64),
}

impl Default for PathStudy {
    /// Waves of amplitude 0.01 H, from the strip's first state `d = 0.005` to 0.2.
    fn default() -> Self {
        PathStudy {
            imperfection: 0.01,
            seed_ratio: 0.5,
            d_start: crate::protocol::STAGE_ONE_COMPRESSION,
            end: PathEnd::At(0.2),
        }
    }
}

impl PathStudy {
    /// Checks `A_init` in `(0, 1)`, the seed ratio in `[0, 1]`, and the path's end, given the
    /// theory's onset `d_c`, in `(d_start, 0.95)`: that end.
    pub fn validate(&self, d_c: f64) -> Result<f64> {
        if !(self.imperfection.is_finite() && self.imperfection > 0.0 && self.imperfection < 1.0) {
            return Err(Error::invalid("imperfection", self.imperfection, "(0, 1)"));
        }
        if !(0.0..=1.0).contains(&self.seed_ratio) {
            return Err(Error::invalid("seed-ratio", self.seed_ratio, "[0, 1]"));
        }
        let d_end = match self.end {
            PathEnd::At(d_end) => {
                if !(d_end.is_finite() && d_end < 0.95) {
                    return Err(Error::invalid("follow-to", d_end, "(d-start, 0.95)"));
                }
                d_end
            }
            PathEnd::PastOnset(past) => {
                let d_end = d_c + past;
                if !(past.is_finite() && past > 0.0 && d_end < 0.95) {
                    return Err(Error::invalid(
                        "follow-past",
                        past,
                        &format!("(0, {:.4}): the onset d_c = {d_c:.4} plus it below 0.95", 0.95 - d_c),
                    ));
                }
                d_end
            }
        };
        if !(self.d_start.is_finite() && self.d_start > 0.0 && self.d_start < d_end) {
            return Err(Error::invalid(
                "d-start",
                self.d_start,
                &format!("(0, {d_end}), the path's end"),
            ));
        }
        Ok(d_end)
    }
}

/// Admissible wave vectors whose `d_c` is within this fraction of the smallest are critical
/// together (a mirror pair, or the waves of an isotropic surface), and all are seeded.
const CRITICAL_TOGETHER: f64 = 1e-6;

/// A state of the path, as `pattern.csv` has it.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct PatternState {
    pub d: f64,
    /// `A = (max y - min y) / 2` of the top surface.
    pub amplitude: f64,
    pub strain_energy: f64,
    pub negative_pivots: Option<usize>,
    /// Whether the state was reached by leaving an unstable one at the same `d` (the energy
    /// minimised from it, moved along its unstable direction), not by a step along the path.
    pub left_unstable: bool,
    pub pattern: SurfacePattern,
    /// The directions of wave vectors with at least 1 % of the surface's spectral energy.
    pub directions: Vec<Direction>,
}

/// What the path showed (`pattern.json`'s `path`).
#[derive(Debug, Serialize)]
pub struct PathSummary {
    pub imperfection: f64,
    pub seed_ratio: f64,
    /// The seeded wave vectors `(m, n)`.
    pub seeded: Vec<(i64, i64)>,
    pub d_start: f64,
    pub d_end: f64,
    /// The last `d` reached.
    pub d_reached: f64,
    pub states: usize,
    /// Why the path stopped before `d_end`, if it did.
    pub stopped: Option<String>,
    /// Where the path turned unstable and was left for a stable state: `(d, energy released)`.
    pub branches_left: Vec<(f64, f64)>,
    /// Where the pattern changed: the first state of each new pattern.
    pub changes: Vec<(f64, SurfacePattern)>,
    /// The last state.
    pub last: Option<PatternState>,
}

/// Every column of `pattern.csv`: the state, then the two leading directions (empty where there
/// is none).
const COLUMNS: [&str; 17] = [
    "d",
    "A",
    "strain_energy",
    "negative_pivots",
    "left_unstable",
    "pattern",
    "directions",
    "m1",
    "n1",
    "theta1_degrees",
    "amplitude1",
    "share1",
    "m2",
    "n2",
    "theta2_degrees",
    "amplitude2",
    "share2",
];

/// The checkpoints of a path: how often, what the run was asked, and the checkpoint it resumes
/// from, if any.
pub(super) struct Checkpoints<'a> {
    pub interval: Option<CheckpointInterval>,
    pub request: &'a Request,
    pub resumed: Option<PathMemory<PatternState>>,
}

/// Follows `path` (whose first bifurcation is found) to `d_end`, seeded with the critical ones
/// of the admissible wave vectors `modes` (sorted by `d_c`), with its checkpoints; writes the
/// files (module docs) into `out` and tells `progress` every state.
pub(super) fn follow(
    frame: &PatchFrame,
    (path, modes): (PatchPath<'_>, &[BoxMode]),
    (study, d_end, checkpoints): (&PathStudy, f64, Checkpoints<'_>),
    out: &Path,
    progress: &mut dyn FnMut(&PatternState),
) -> Result<(PathSummary, Vec<PathBuf>)> {
    let mesh = path.system().mesh().clone();
    // Periodic sides admit `k = 2 pi (m / Lx, n / Lz)`; symmetry sides the products of cosines
    // of `pi (m / Lx, n / Lz)`, one for a mirror pair `(m, +-n)`.
    let spec = mesh.patch_spec();
    let (symmetric, wave) = match mesh.is_periodic() {
        true => (false, 2.0 * PI),
        false => (true, PI),
    };
    let first = modes.first().map_or(f64::NAN, |m| m.d_c);
    let mut seeded: Vec<&BoxMode> = Vec::new();
    for mode in modes.iter().filter(|m| m.d_c <= first * (1.0 + CRITICAL_TOGETHER)) {
        if !(symmetric && seeded.iter().any(|s| (s.m, s.n.abs()) == (mode.m, mode.n.abs()))) {
            seeded.push(mode);
        }
    }
    let imperfection = PatchImperfection {
        waves: seeded
            .iter()
            .enumerate()
            .map(|(i, m)| {
                let k = [wave * m.m as f64 / spec.length_x, wave * m.n as f64 / spec.length_z];
                (k, study.imperfection * if i == 0 { 1.0 } else { study.seed_ratio })
            })
            .collect(),
        depth: spec.depth,
        symmetric,
    };
    let csv = out.join("pattern.csv");
    let mut table = CsvWriter::create(&csv, &COLUMNS)?;
    let (mut states, mut branches_left, mut last_u, from) = match checkpoints.resumed {
        Some(memory) => {
            let last_u = memory.path.history.last().map(|(_, u)| u.clone()).unwrap_or_default();
            (memory.states, memory.branches_left, last_u, Some(memory.path))
        }
        None => {
            // A new path: a checkpoint of an earlier run in the folder is removed.
            remove_checkpoint(&out.join(checkpoint::CHECKPOINT_FILE))?;
            (Vec::new(), Vec::new(), Vec::new(), None)
        }
    };
    for state in &states {
        append_row(&mut table, state)?;
    }
    let resumption = Resumption {
        from,
        checkpoints: checkpoints.interval,
    };
    let protocol = PatchProtocol::new(study.d_start, d_end);
    let observer = &mut |event: Event<'_, BiaxialPatch>| {
        let (record, system, u) = match event {
            Event::Step { record, system, u } => (record, system, u),
            Event::Checkpoint(path) => {
                return checkpoint::write(out, checkpoints.request, path, (&states, &branches_left));
            }
            _ => return Ok(()),
        };
        let patch = system.system();
        if surface_crosses_itself(patch.mesh(), u, patch.average_gradient()) {
            let before = states
                .last()
                .map_or(String::from("the start"), |s| format!("d = {:.6}", s.d));
            return Err(Error::Solver(format!(
                "the surface touches itself between {before} and d = {:.6} (self-contact is not modelled in three dimensions)",
                record.d
            )));
        }
        let (pattern, directions) = classify(&height_spectrum(patch.mesh(), u));
        let directions = directions.into_iter().map(|d| frame.direction(d)).collect();
        let state = PatternState {
            d: record.d,
            amplitude: record.amplitude,
            strain_energy: record.strain_energy,
            negative_pivots: record.negative_pivots,
            left_unstable: record.snap.is_some(),
            pattern,
            directions,
        };
        append_row(&mut table, &state)?;
        progress(&state);
        if let Some(snap) = &record.snap {
            branches_left.push((snap.d, snap.energy_released));
        }
        states.push(state);
        last_u = u.to_vec();
        Ok(())
    };
    let (continuation, stopped) = path.follow_resumable(&imperfection, &protocol, resumption, observer)?;
    let mut files = vec![csv];
    let patch = continuation.system();
    let d = states.last().map_or(study.d_start, |s| s.d);
    let gradient = *patch.system().average_gradient();
    files.push(write_state(out, patch.system().mesh(), &last_u, gradient)?);
    let relief = surface_relief(patch.system().mesh(), &last_u);
    let view = figure::TopView {
        title: format!(
            "Surface relief at d = {d:.4} (blue down, red up); lines: the fibres{}",
            frame.caption()
        ),
        mesh: patch.system().mesh(),
        field: &relief,
        fibres: frame.fibres(),
    };
    files.extend(figure::top_view(&view, out, "state_top")?);
    let title = format!("Surface relief at d = {d:.4} (height exaggerated), X and Z in H");
    files.extend(figure::perspective(&view, &title, out, "state_3d")?);
    let mut changes: Vec<(f64, SurfacePattern)> = Vec::new();
    for state in &states {
        if changes.last().is_none_or(|&(_, p)| p != state.pattern) {
            changes.push((state.d, state.pattern));
        }
    }
    let summary = PathSummary {
        imperfection: study.imperfection,
        seed_ratio: study.seed_ratio,
        seeded: seeded.iter().map(|m| (m.m, m.n)).collect(),
        d_start: study.d_start,
        d_end,
        d_reached: d,
        states: states.len(),
        stopped: stopped.map(|e| e.to_string()),
        branches_left,
        changes,
        last: states.pop(),
    };
    Ok((summary, files))
}

/// One row of `pattern.csv`.
fn append_row(table: &mut CsvWriter, state: &PatternState) -> Result<()> {
    let name = crate::output::table::variant_name(&state.pattern);
    let mut cells = vec![
        Cell::Number(state.d),
        Cell::Number(state.amplitude),
        Cell::Number(state.strain_energy),
        state.negative_pivots.map_or(Cell::Empty, |n| Cell::Number(n as f64)),
        Cell::Number(f64::from(u8::from(state.left_unstable))),
        Cell::Text(&name),
        Cell::Number(state.directions.len() as f64),
    ];
    for i in 0..2 {
        match state.directions.get(i) {
            Some(direction) => {
                let w = direction.wave;
                cells.extend([
                    Cell::Number(w.m as f64),
                    Cell::Number(w.n as f64),
                    Cell::Number(w.theta_degrees),
                    Cell::Number(w.amplitude),
                    Cell::Number(direction.share),
                ]);
            }
            None => cells.extend([Cell::Empty; 5]),
        }
    }
    table.append_cells(&cells)
}

/// A field of the mesh's unknowns holding, at the top nodes' `Y` entries, the deformed height
/// `Y + u_Y` less its mean: the relief the figure draws.
fn surface_relief(mesh: &Mesh<3, 27>, u: &[f64]) -> Vec<f64> {
    let (top, dofs) = (mesh.node_set(TOP), mesh.dofs());
    let height = |n: usize| mesh.coordinates()[n][Y] + u[dofs.dof(n, Y)];
    let mean = top.iter().map(|&n| height(n)).sum::<f64>() / top.len() as f64;
    let mut relief = vec![0.0; mesh.num_dofs()];
    for &n in top {
        relief[dofs.dof(n, Y)] = height(n) - mean;
    }
    relief
}

/// `state.vtu`: the patch (cut open along periodic sides) at the last state `u` (on periodic
/// sides the periodic part of the displacement), with the displacement `H X + u` as point
/// vectors (`H` the average gradient periodic sides carry, zero on symmetry sides).
fn write_state(out: &Path, mesh: &Mesh<3, 27>, u: &[f64], gradient: [[f64; 3]; 3]) -> Result<PathBuf> {
    let (points, cells, source) = mesh.unwrapped();
    let dofs = mesh.dofs();
    let displacement = DataArray::vectors(
        "displacement",
        points.iter().zip(&source).map(|(x, &n)| {
            std::array::from_fn(|c| u[dofs.dof(n, c)] + (0..3).map(|j| gradient[c][j] * x[j]).sum::<f64>())
        }),
    );
    let cell_type = CellType {
        vtk: <Hex27 as ReferenceElement<3, 27, 27>>::VTK_CELL_TYPE,
        order: <Hex27 as ReferenceElement<3, 27, 27>>::VTK_ORDER,
    };
    let path = out.join("state.vtu");
    write_vtu(&path, &points, &cell_type, &cells, &[displacement], &[])?;
    Ok(path)
}
