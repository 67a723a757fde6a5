//! `simulate`: the paper's loading protocol (section 2.1) on one mesh. Writes, into the output
//! folder, `amplitude.csv` (a row per converged state, flushed at once), VTU snapshots with
//! `simulate.pvd`, `surface.csv` (final top surface), `onset_estimates.json`, `contact.json`,
//! `secondary.json` with its modes, `snaps.json` with the states before and after every snap
//! (`snap_N_before.vtu`, `snap_N_after.vtu`), Fig. 3, Fig. 7's panels at the compressions it
//! reaches (when contact is on) and `simulate.json`.
//! A run that stops early keeps all of this for the path so far and then returns the error.

mod checkpoint;
mod columns;
mod crease;
mod fig3;
mod fig4a;
mod fig7;
mod options;
mod path_files;
mod secondary;
mod snapshots;
mod solve;
mod state_vtu;

pub use checkpoint::{SolveMemory, CHECKPOINT_FILE};
pub use columns::{amplitude_header, amplitude_row, AMPLITUDE_COLUMNS};
pub use crease::ContactReport;
pub use fig3::fig3;
pub use fig4a::{fig4a, Fig4aOptions, Fig4aRow};
pub use fig7::{fig7, CreaseSnapshots, Fig7Facts, Fig7State, FIG7_D};
pub use options::{Crossing, MeshChoice, SimulateOptions};
pub use path_files::CheckpointTotals;
pub use secondary::{write_secondary, ModeState, SecondaryReport, SecondaryTracker, MODES};
pub use solve::{solve, solve_observed, solve_to_secondary, Observed, Solution, Solved, StateFields, ToSecondary};
pub use state_vtu::{nodal_array, write_state, CELL_TYPE};

use crate::error::{Error, Result};
pub use crate::fem::ellipticity::EllipticityReport;
use crate::fem::Timings;
use crate::material::Bilayer;
use crate::mesh::MeshSpec;
use crate::output::write_json;
use crate::parameters::{Load, Parameters};
use crate::protocol::onset::A2_FIT_WINDOW;
use crate::protocol::{
    mode_number, stages, CheckpointInterval, ContinuationMethod, Cut, Event, OnsetEstimates, Protocol, SnapRecord,
    StepRecord,
};
use crate::stability::{Method, StabilityAnalysis};
use path_files::PathFiles;
use serde::Serialize;
use std::path::Path;
use std::time::Instant;

/// What the study reports while it runs.
pub enum Progress<'a> {
    /// A stage starts.
    Stage(&'a str),
    /// A converged state.
    Step(&'a StepRecord),
    /// A failed attempt; the step is cut.
    Cut(&'a Cut),
}

/// Receives [`Progress`] (prints, drives a progress bar, or ignores it); an error it returns
/// (e.g. [`Error::Interrupted`]) stops the run as a solver failure would, keeping the path.
pub type Monitor<'a> = &'a (dyn Fn(Progress<'_>) -> Result<()> + Sync);

/// One simulation: mesh, protocol and how often to write a VTU snapshot.
#[derive(Clone, Copy, Debug)]
pub struct SimulateStudy {
    pub mesh: MeshSpec,
    pub protocol: Protocol,
    /// Spacing in `d` of the VTU snapshots (the first and the last state are always written).
    pub vtu_every: f64,
    /// How many secondary modes are computed (those of the first changes of the inertia).
    pub secondary_modes: usize,
    /// How often the path's whole state is written to `checkpoint.bin` in the output folder
    /// (never if `None`; a path of arc length writes none).
    pub checkpoints: Option<CheckpointInterval>,
    /// Whether [`run`] continues from the checkpoint in the output folder (from the start if
    /// there is none).
    pub resume: bool,
}

impl SimulateStudy {
    /// `protocol` on `mesh`, a VTU snapshot every 0.01 in `d`, the modes of the first
    /// [`MODES`] changes of the inertia.
    pub fn new(mesh: MeshSpec, protocol: Protocol) -> Self {
        SimulateStudy {
            mesh,
            protocol,
            vtu_every: 0.01,
            secondary_modes: MODES,
            checkpoints: None,
            resume: false,
        }
    }

    pub fn validate(&self) -> Result<()> {
        self.mesh.validate()?;
        self.protocol.validate(&self.mesh)?;
        if !(self.vtu_every.is_finite() && self.vtu_every > 0.0) {
            return Err(Error::invalid("vtu-every", self.vtu_every, "(0, inf)"));
        }
        if let Some(interval) = self.checkpoints {
            interval.validate()?;
        }
        if self.resume && self.protocol.method == ContinuationMethod::ArcLength {
            return Err(Error::invalid(
                "resume",
                "with --continuation arc-length",
                "displacement control (a path of arc length keeps no checkpoints)",
            ));
        }
        Ok(())
    }
}

/// The converged states of a protocol run, with what stopped it (if anything).
pub struct Curve {
    pub records: Vec<StepRecord>,
    pub cuts: Vec<Cut>,
    pub stopped: Option<Error>,
    pub seconds: f64,
}

impl Curve {
    /// `(d_i, A_i)` of the converged states.
    pub fn points(&self) -> (Vec<f64>, Vec<f64>) {
        self.records.iter().map(|r| (r.d, r.amplitude)).unzip()
    }

    /// `(d_i, A_i)` of the states of the first branch, up to its last equilibrium before the
    /// first snap or the first limit point in `d` (where an arc-length path turns back): a
    /// snap's jump of `A` within a step of `1e-6`, or a vertical tangent, makes the slope
    /// millions, which would drown the onset's peaks of `A'` and of the curvature
    /// ([`OnsetEstimates`]).
    pub fn first_branch(&self) -> (Vec<f64>, Vec<f64>) {
        let rising = self
            .records
            .windows(2)
            .take_while(|pair| pair[1].d >= pair[0].d)
            .count()
            + 1;
        self.records
            .iter()
            .take(rising)
            .take_while(|r| r.snap.is_none())
            .map(|r| (r.d, r.amplitude))
            .unzip()
    }
}

/// Keeps the converged states and cuts of a run and passes every event on to a monitor.
struct Recorder<'m> {
    monitor: Monitor<'m>,
    records: Vec<StepRecord>,
    cuts: Vec<Cut>,
    start: Instant,
}

impl<'m> Recorder<'m> {
    fn new(monitor: Monitor<'m>) -> Self {
        Self::resumed(monitor, Vec::new(), Vec::new())
    }

    /// A recorder holding the states and cuts of a path so far.
    fn resumed(monitor: Monitor<'m>, records: Vec<StepRecord>, cuts: Vec<Cut>) -> Self {
        Recorder {
            monitor,
            records,
            cuts,
            start: Instant::now(),
        }
    }

    fn note(&mut self, event: &Event<'_>) -> Result<()> {
        match event {
            Event::Stage(text) => (self.monitor)(Progress::Stage(text)),
            Event::Step { record, .. } => {
                self.records.push((*record).clone());
                (self.monitor)(Progress::Step(record))
            }
            Event::Cut(cut) => {
                self.cuts.push((*cut).clone());
                (self.monitor)(Progress::Cut(cut))
            }
            Event::Checkpoint(_) => Ok(()),
        }
    }

    fn into_curve(self, stopped: Option<Error>) -> Curve {
        Curve {
            records: self.records,
            cuts: self.cuts,
            stopped,
            seconds: self.start.elapsed().as_secs_f64(),
        }
    }
}

/// Runs the protocol without writing files; stage 1-2 failures are errors, a stop in stage 3 is
/// kept in [`Curve::stopped`].
pub fn curve(params: &Parameters, spec: MeshSpec, protocol: &Protocol, monitor: Monitor) -> Result<Curve> {
    let mut recorder = Recorder::new(monitor);
    let outcome = stages::run(&Bilayer::new(params), spec, protocol, &mut |event| {
        recorder.note(&event)
    })?;
    Ok(recorder.into_curve(outcome.stopped))
}

/// `onset_estimates.json`: the three estimates beside the linear theory.
#[derive(Clone, Debug, Serialize)]
pub struct OnsetReport {
    pub k: f64,
    pub waves: f64,
    #[serde(flatten)]
    pub estimates: OnsetEstimates,
    pub d_linear_theory: f64,
    /// Where the homogeneously compressed bilayer loses strong ellipticity, if before d = 1.
    pub d_ellipticity_loss: Option<f64>,
    pub a2_fit_window: f64,
    pub note: &'static str,
}

const ONSET_NOTE: &str = "All three are read off the states before the first snap (the branch the path starts on). \
    d_max_curvature is the first peak (largest within +-0.01 in d) of \
    kappa = A''/(1 + A'^2)^(3/2), the paper's rule; kappa, and so this estimate, depends on the relative scaling \
    of A (in units of H) and d, and on the imperfection. d_steepest is the first peak of A'. d_a2_fit is where a \
    straight line fitted to A^2 against d over [d_steepest, d_steepest + a2_fit_window] crosses zero (null if that \
    lies outside the recorded d). \
    d_linear_theory is the exact linear theory's d_c(k) for the seeded k. d_ellipticity_loss is the compression at \
    which the homogeneous state loses strong ellipticity (null if it does not): beyond it the continuum admits \
    shear bands (e.g. compressed fibres at small beta) and the solution depends on the mesh.";

impl OnsetReport {
    /// The estimates of `curve` and the linear theory's `d_c(k)`.
    pub fn new(params: &Parameters, k: f64, length: f64, curve: &Curve) -> Result<Self> {
        let (d, a) = curve.first_branch();
        let theory = StabilityAnalysis::new(params, Method::Exact)?;
        Ok(OnsetReport {
            k,
            waves: mode_number(k, length)? as f64 / 2.0,
            estimates: OnsetEstimates::from_curve(&d, &a),
            d_linear_theory: theory.critical_compression(k)?,
            d_ellipticity_loss: theory.ellipticity_loss(),
            a2_fit_window: A2_FIT_WINDOW,
            note: ONSET_NOTE,
        })
    }
}

/// Summed wall times and counts of the Newton phases over the accepted steps.
#[derive(Clone, Copy, Debug, Default, Serialize)]
pub struct PhaseTotals {
    pub assembly_seconds: f64,
    pub analysis_seconds: f64,
    pub factorisation_seconds: f64,
    pub solve_seconds: f64,
    pub assemblies: usize,
    pub factorisations: usize,
    pub solves: usize,
    pub newton_iterations: usize,
    /// Inertia of the accepted states (an extra assembly and factorisation each).
    pub inertia_seconds: f64,
    /// Attempts discarded (steps cut).
    pub failed_attempt_seconds: f64,
    /// All steps: the phases above plus contact search, multiplier updates and prediction.
    pub step_seconds: f64,
}

impl PhaseTotals {
    pub fn of(records: &[StepRecord]) -> Self {
        let timings = records.iter().fold(Timings::default(), |t, r| t + r.timings);
        let sum = |f: &dyn Fn(&StepRecord) -> f64| records.iter().map(f).sum::<f64>();
        PhaseTotals {
            assembly_seconds: timings.assembly.as_secs_f64(),
            analysis_seconds: timings.analysis.as_secs_f64(),
            factorisation_seconds: timings.factorisation.as_secs_f64(),
            solve_seconds: timings.solve.as_secs_f64(),
            assemblies: timings.assemblies,
            factorisations: timings.factorisations,
            solves: timings.solves,
            newton_iterations: records.iter().map(|r| r.iterations).sum(),
            inertia_seconds: sum(&|r| r.augmented.as_ref().map_or(0.0, |a| a.inertia_seconds)),
            failed_attempt_seconds: sum(&|r| r.failed_seconds),
            step_seconds: sum(&|r| r.seconds),
        }
    }
}

/// `simulate.json`.
#[derive(Debug, Serialize)]
pub struct SimulationSummary {
    pub command: &'static str,
    pub parameters: Parameters,
    /// What loads the bilayer; under growth every `d` is the strain `1 - 1/g`.
    pub load: Load,
    /// The layer's growth reached (null under compression).
    pub g_reached: Option<f64>,
    pub mesh: MeshSummary,
    pub k: f64,
    pub imperfection: f64,
    pub d_max: f64,
    /// How the path was followed: displacement control, or arc length (`d` then falls and
    /// rises again along `amplitude.csv`, and `d_reached` is the last state's).
    pub continuation: ContinuationMethod,
    pub d_reached: f64,
    pub completed: bool,
    pub stopped: Option<String>,
    pub accepted_steps: usize,
    pub cuts: usize,
    pub totals: PhaseTotals,
    pub wall_seconds: f64,
    pub onset: OnsetReport,
    pub contact: ContactReport,
    pub secondary: SecondaryReport,
    /// Every snap of the path ([`crate::protocol::snap`]).
    pub snaps: Vec<SnapRecord>,
    /// Where the finite-element states lose strong ellipticity.
    pub ellipticity: EllipticityReport,
    /// The checkpoints this run wrote (none in memory; after `--resume`, those since).
    pub checkpoints: CheckpointTotals,
    pub files: Vec<String>,
}

/// The mesh of a run as written to JSON: its spec and number of unknowns.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct MeshSummary {
    #[serde(flatten)]
    pub spec: MeshSpec,
    pub unknowns: usize,
}

impl From<&MeshSpec> for MeshSummary {
    fn from(spec: &MeshSpec) -> Self {
        MeshSummary {
            spec: *spec,
            unknowns: spec.num_dofs(),
        }
    }
}

impl SimulationSummary {
    /// The summary of `solution` (its files `files`, `wall_seconds` from the start).
    pub fn new(
        params: &Parameters,
        study: &SimulateStudy,
        solution: &Solution,
        files: Vec<String>,
        wall_seconds: f64,
    ) -> Self {
        let curve = &solution.curve;
        SimulationSummary {
            command: "simulate",
            parameters: params.clone(),
            load: params.load,
            g_reached: params
                .load
                .is_growth()
                .then(|| params.load.parameter(solution.d_reached)),
            mesh: MeshSummary::from(&study.mesh),
            k: study.protocol.k,
            imperfection: study.protocol.imperfection,
            d_max: study.protocol.d_max,
            continuation: study.protocol.method,
            d_reached: solution.d_reached,
            completed: curve.stopped.is_none(),
            stopped: curve.stopped.as_ref().map(|e| e.to_string()),
            accepted_steps: curve.records.len(),
            cuts: curve.cuts.len(),
            totals: PhaseTotals::of(&curve.records),
            wall_seconds,
            onset: solution.onset.clone(),
            contact: solution.contact.clone(),
            secondary: solution.secondary.clone(),
            snaps: solution.snaps.clone(),
            ellipticity: solution.ellipticity,
            checkpoints: CheckpointTotals::default(),
            files,
        }
    }
}

/// Runs the study ([`solve_observed`]) and writes its files (module docs): `amplitude.csv`, the
/// VTU snapshots, the snaps' states and the checkpoints as the path goes, the rest once it ends
/// (from the checkpoint in `out` if `study.resume`). A stop in stage 3 is returned as an error
/// after everything computed so far has been written.
pub fn run(params: &Parameters, study: &SimulateStudy, out: &Path, monitor: Monitor) -> Result<SimulationSummary> {
    let (summary, solution) = run_keeping(params, study, out, monitor)?;
    let d_reached = solution.d_reached;
    match solution.curve.stopped {
        Some(Error::Interrupted(_)) => Err(Error::Interrupted(format!(
            "at d = {d_reached:.6}; the path so far is in {}",
            out.display()
        ))),
        Some(e) => {
            // Measured: a damped crawl through a closing trough (mu_l = 3, K/mu = 1e4, beta
            // 1.5707961) stalled at the smallest step where the minimisation crossed it.
            let hint = match study.protocol.crossing.minimisation() {
                Some(_) => "",
                None => "; where the path snaps, stabilisation = snap crosses by minimising the energy",
            };
            Err(Error::Solver(format!(
                "{e}; the path up to d = {d_reached:.6} is in {}{hint}",
                out.display()
            )))
        }
        None => Ok(summary),
    }
}

/// [`run`], returning the summary and the solution, whose `curve.stopped` says whether and
/// why the path stopped early, instead of an error for that stop.
pub fn run_keeping(
    params: &Parameters,
    study: &SimulateStudy,
    out: &Path,
    monitor: Monitor,
) -> Result<(SimulationSummary, Solution)> {
    params.validate()?;
    study.validate()?;
    study.mesh.element.check_for(params.incompressible)?;
    let request = checkpoint::request(params, study)?;
    // A checkpoint of another run is refused before anything in the folder is touched.
    let resumed = match study.resume {
        true => checkpoint::read(out, &request)?,
        false => None,
    };
    let _lock = crate::output::lock::OutputLock::acquire(out)?;
    let start = Instant::now();
    let (mut path, resume) = match resumed {
        Some((solve, files)) => (PathFiles::resumed(out, study, files, &solve)?, Some(solve)),
        None => {
            if study.resume {
                monitor(Progress::Stage(&format!(
                    "no checkpoint in {}: starting from the beginning",
                    out.display()
                )))?;
            }
            (PathFiles::create(out, study)?, None)
        }
    };
    let solved = solve_observed(
        params,
        study,
        monitor,
        resume,
        &mut |observed, materials| match observed {
            Observed::Event(event) => path.note(event, materials),
            Observed::Checkpoint(solve) => path.checkpoint(&request, solve),
        },
    );
    let Solved {
        mut solution,
        materials,
        mut system,
        u,
        modes,
    } = solved?;
    let checkpoints = path.checkpoint_totals();
    let written = path
        .finish(&solution, &system, &materials, &u, params)
        .and_then(|mut files| {
            files.extend(write_secondary(
                &mut solution.secondary,
                &modes,
                &mut system,
                &materials,
                out,
            )?);
            Ok(files)
        });
    // A path stopped by a fault (a full disk) may fail its last files too: the first fault is
    // the one to name.
    let files = match (written, &solution.curve.stopped) {
        (Ok(files), _) => files,
        (Err(e), Some(stopped)) => {
            return Err(Error::Solver(format!(
                "{stopped}; the files of the path's end were not written either: {e}"
            )))
        }
        (Err(e), None) => return Err(e),
    };
    let files = files.iter().map(|f| f.display().to_string()).collect();
    let summary = SimulationSummary {
        checkpoints,
        ..SimulationSummary::new(params, study, &solution, files, start.elapsed().as_secs_f64())
    };
    write_json(&out.join("simulate.json"), &summary)?;
    Ok((summary, solution))
}
