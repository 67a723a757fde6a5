//! `pattern`: a patch of tissue in three dimensions under biaxial compression. The patch is
//! sized by the exact 3D linear theory (an integer number of the onset mode's periods along X
//! and Z, so that its critical wave vectors, both members of a mirror pair, are admissible),
//! meshed with 27-node hexahedra, and its first bifurcation found from the tangent's inertia
//! along the homogeneous path ([`crate::protocol::patch`]), against the theory's smallest
//! `d_c(|k|, theta)` over the wave vectors the patch admits. The bifurcation mode's surface
//! spectrum says which wave vectors it holds.
//!
//! Writes `pattern.json`, `wave_vectors.csv` (the admissible wave vectors and their `d_c`),
//! `inertia.csv` (negative pivots along the homogeneous path), `mode_spectrum.csv`, `mode.vtu`
//! (the patch, cut open along periodic sides, with the mode) and `mode_top.png/svg` (the mode's
//! surface seen from above, with the fibres' projection).
//! Asked to, it follows the path past the onset (`path`): `pattern.csv`, `state.vtu`,
//! `state_top.png/svg`.

mod checkpoint;
mod figure;
mod frame;
mod map;
mod map_figure;
mod map_files;
mod options;
mod path;
mod sizing;

pub use frame::PatchFrame;
pub use map::{compute_map, PatternMap, PatternMapOptions, PatternMapReport, PatternPoint};
pub use map_files::collect as collect_map;
pub use options::PatternOptions;
pub use path::{PathEnd, PathStudy, PathSummary, PatternState};
use sizing::default_max_side;
pub use sizing::{size_patch, CappedSide};

use crate::error::{Error, Result};
use crate::fem::element::{Hex27, ReferenceElement};
use crate::fem::memory::{available_bytes, MemoryEstimate};
use crate::mesh::{ElementKind, Mesh, PatchSpec, Sides, Y};
use crate::output::lock::OutputLock;
use crate::output::vtu::{write_vtu, CellType, DataArray};
use crate::output::{write_json, CsvWriter};
use crate::parameters::Parameters;
use crate::protocol::patch::{surface_spectrum, PatchBifurcation, PatchPath, WaveVector};
use crate::protocol::{BifurcationSettings, CheckpointInterval};
use crate::stability::oblique::{box_modes, BoxMode};
use crate::stability::Method;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Wave vectors listed from the theory (the nearest the onset first).
const LISTED_WAVE_VECTORS: usize = 8;

/// How the patch is sized and meshed, and the search's settings.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct PatternStudy {
    /// `R = d_3 / d` in `[0, 1]`.
    pub biaxial: f64,
    /// Periods of the onset mode along each side.
    pub periods: usize,
    /// Elements per onset wavelength along X and Z.
    pub elements_per_wavelength: usize,
    /// The longest side, in onset wavelengths per period. Where the onset mode's period along a
    /// side (`lambda / |cos theta0|` along X, `lambda / |sin theta0|` along Z) is longer, an
    /// onset direction within `asin(1 / max_side)` of the other axis, that side is one
    /// wavelength per period and holds the mode's nearest wave vector along the other axis.
    #[serde(default = "default_max_side")]
    pub max_side: f64,
    pub layer_elements: usize,
    pub substrate_elements: usize,
    /// Thickness `h0` of the top substrate element.
    pub top_substrate_thickness: f64,
    /// Depth of the substrate, in onset wavelengths.
    pub depth_wavelengths: f64,
    pub sides: Sides,
    /// The hexahedra: the displacement element by default (the mixed one finds a spurious
    /// mode at the element scale on a nearly incompressible half-space: the guide's "Patterns in three dimensions").
    pub element: ElementKind,
    pub settings: BifurcationSettings,
    /// The path past the onset, if it is followed.
    pub path: Option<PathStudy>,
    /// Run even when the memory estimate exceeds the memory available.
    pub force: bool,
    /// How often the path past the onset writes its checkpoint (never if `None`); not part of
    /// what a map's points are computed with.
    #[serde(skip)]
    pub checkpoints: Option<CheckpointInterval>,
    /// Whether the path continues from the checkpoint in the output folder (from the start if
    /// there is none).
    #[serde(skip)]
    pub resume: bool,
}

impl Default for PatternStudy {
    /// Equibiaxial compression, one period, 6 elements per wavelength, 2 + 12 elements through
    /// the thickness (`h0 = 0.35`) down to two wavelengths, periodic sides, displacement
    /// hexahedra.
    fn default() -> Self {
        PatternStudy {
            biaxial: 1.0,
            periods: 1,
            elements_per_wavelength: 6,
            max_side: default_max_side(),
            layer_elements: 2,
            substrate_elements: 12,
            top_substrate_thickness: 0.35,
            depth_wavelengths: 2.0,
            sides: Sides::Periodic,
            element: ElementKind::Displacement,
            settings: BifurcationSettings {
                scan_step: 0.02,
                ..BifurcationSettings::default()
            },
            path: None,
            force: false,
            checkpoints: Some(CheckpointInterval::DEFAULT),
            resume: false,
        }
    }
}

/// What a patch too large for the memory can lower.
const TOO_LARGE: &str = "fewer --periods or --elements-per-wavelength; ";

/// The theory's onset in the surface.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct TheoryOnset {
    pub k0: f64,
    /// The wave vector's direction from X towards Z; null where every direction is critical.
    pub theta0_degrees: Option<f64>,
    pub d_c: f64,
}

/// `pattern.json`.
#[derive(Debug, Serialize)]
pub struct PatternReport {
    pub command: &'static str,
    pub parameters: Parameters,
    /// `R = d_3 / d`.
    pub biaxial: f64,
    pub patch: PatchSpec,
    /// Its sides one onset wavelength per period because the mode's period along them was
    /// longer than `max_side` wavelengths ([`PatternStudy::max_side`]): the theory's wave
    /// vector is then not admissible, and `d_c_admissible` is the nearest ones'.
    pub capped_sides: Vec<CappedSide>,
    /// The patch's X axis from the load's X axis towards Z (degrees): `psi` where the load is
    /// the same in every direction of the surface and the patch is built along the fibres'
    /// projection ([`PatchFrame`]), else 0. Every `theta` reported is in the load's frame;
    /// `(m, n)` count periods along the patch's sides.
    pub patch_azimuth_degrees: f64,
    /// Free unknowns of the tangent.
    pub unknowns: usize,
    pub onset_theory: TheoryOnset,
    /// The first change of the tangent's inertia along the homogeneous path (under a growth
    /// load the strain `1 - 1/g`).
    pub d_bifurcation: f64,
    /// The layer's growth `g = 1 / (1 - d_bifurcation)` along X there, under a growth load
    /// (null under compression).
    pub g_bifurcation: Option<f64>,
    pub bracket: (f64, f64),
    /// Negative pivots just past it: two per critical wave vector (a cosine and a sine mode).
    pub negative_pivots: usize,
    pub smallest_eigenvalue_before: f64,
    /// The theory's smallest `d_c` over the patch's admissible wave vectors.
    pub d_c_admissible: f64,
    /// `d_bifurcation / d_c_admissible - 1`.
    pub relative_difference: f64,
    /// The admissible wave vectors nearest the onset, by increasing `d_c` (`(m, n)` of
    /// `k = 2 pi (m / Lx, n / Lz)` on periodic sides, `k = pi (m / Lx, n / Lz)` on symmetry sides).
    pub admissible_wave_vectors: Vec<BoxMode>,
    /// The wave vectors of the bifurcation mode's top-surface `u_Y` (largest amplitude 1 over
    /// the surface), by decreasing amplitude (periodic sides only).
    pub mode_wave_vectors: Vec<WaveVector>,
    pub inertia_evaluations: usize,
    /// The path past the onset, if it was followed.
    pub path: Option<PathSummary>,
    pub wall_seconds: f64,
    pub files: Vec<String>,
}

/// Sizes the patch, finds its first bifurcation against the theory and writes the files (module
/// docs); a path past the onset that stops before its end is an error, returned once every file
/// is written; `progress` is told the patch with its admissible wave vectors once, then every
/// `(d, negative pivots)` evaluated.
pub fn run(
    params: &Parameters,
    study: &PatternStudy,
    out: &Path,
    progress: &mut dyn FnMut(Progress),
) -> Result<PatternReport> {
    let report = compute(params, study, out, progress)?;
    // A path that stopped early is a failure, reported once everything up to it is written.
    if let Some(path) = report.path.as_ref().filter(|p| p.stopped.is_some()) {
        return Err(Error::Solver(format!(
            "the path past the onset stopped at d = {:.6} (asked: {}): {}; every state up to there is in {}",
            path.d_reached,
            path.d_end,
            path.stopped.as_deref().unwrap_or_default(),
            out.display()
        )));
    }
    Ok(report)
}

/// [`run`], with a path that stops early reported in `pattern.json`'s `path.stopped` rather
/// than as an error.
pub fn compute(
    params: &Parameters,
    study: &PatternStudy,
    out: &Path,
    progress: &mut dyn FnMut(Progress),
) -> Result<PatternReport> {
    params.validate()?;
    let start = Instant::now();
    // The patch's frame: turned along the fibres' projection under a load the same in every
    // direction of the surface, where the tissue is computed with psi = 0 ([`PatchFrame`]).
    let frame = PatchFrame::of(params, study.biaxial);
    let (onset, spec, capped) = size_patch(&frame.parameters, study)?;
    let d_end = study.path.map(|path| path.validate(onset.onset.d_c)).transpose()?;
    // A checkpoint of another run is refused before anything in the folder is touched.
    let request = checkpoint::request(params, study)?;
    let resumed = match (study.resume, d_end) {
        (true, Some(_)) => checkpoint::read(out, &request)?,
        (true, None) => {
            return Err(Error::invalid(
                "resume",
                "without a path",
                "with --follow-to or --follow-past (the path past the onset is what resumes)",
            ))
        }
        (false, _) => None,
    };
    if study.resume {
        progress(Progress::Resume(resumed.as_ref().map(|memory| memory.path.d())));
    }
    // The elements and the tangent alone, before anything is allocated for the exact estimate:
    // about 97 stored entries per unknown in the lower triangle of 27-node hexahedra (64 nodes
    // coupled to each on average).
    let available = available_bytes();
    if !study.force {
        let n = spec.num_dofs();
        MemoryEstimate::of_factor(n, spec.num_elements(), 95 * n, 0).check_named(available, "patch", TOO_LARGE)?;
    }
    let _lock = OutputLock::acquire(out)?;
    let k_max = 3.0 * onset.onset.k0;
    // Symmetry sides admit the waves `cos(m pi X / Lx) cos(n pi Z / Lz)`: the wave vectors of
    // a periodic patch twice as long each way.
    let periods = match spec.sides {
        Sides::Periodic => (spec.length_x, spec.length_z),
        Sides::Symmetry => (2.0 * spec.length_x, 2.0 * spec.length_z),
    };
    let mut modes = box_modes(&frame.parameters, Method::Exact, study.biaxial, periods, k_max)?;
    let first = *modes.first().ok_or_else(|| Error::NoRoot {
        what: "a bifurcation of the linear theory at the patch's wave vectors".into(),
        lower: 0.0,
        upper: 1.0,
    })?;
    let admissible = modes.clone();
    modes.truncate(LISTED_WAVE_VECTORS);
    // Listed with their directions in the load's frame.
    let modes: Vec<BoxMode> = modes.into_iter().map(|m| frame.mode(m)).collect();
    let materials = crate::material::Bilayer::new(&frame.parameters);
    let mut path = PatchPath::new(&materials, spec, study.biaxial)?;
    let mesh = path.system().mesh().clone();
    let memory = path.memory_estimate()?;
    progress(Progress::Patch {
        spec: &spec,
        azimuth: frame.azimuth,
        capped: &capped,
        unknowns: mesh.num_dofs(),
        modes: &modes,
        memory: (&memory, available),
    });
    if !study.force {
        memory.check_named(available, "patch", TOO_LARGE)?;
    }
    let found = path.bifurcation(&study.settings, &mut |d, negative| {
        progress(Progress::Inertia { d, negative })
    })?;
    let spectrum: Vec<WaveVector> = surface_spectrum(&mesh, &found.mode)
        .into_iter()
        .map(|w| frame.wave(w))
        .collect();
    let mut files = write_wave_vectors(out, &modes)?;
    files.extend(super::bifurcation::write_inertia(out, &found.path)?);
    files.extend(write_spectrum(out, &spectrum)?);
    let view = figure::TopView {
        title: format!(
            "Bifurcation mode at d = {:.5}: surface u_Y from above; lines: the fibres{}",
            found.d,
            frame.caption()
        ),
        mesh: &mesh,
        field: &found.mode,
        fibres: frame.fibres(),
    };
    files.extend(figure::top_view(&view, out, "mode_top")?);
    let title = format!("Bifurcation mode at d = {:.5}: surface u_Y, X and Z in H", found.d);
    files.extend(figure::perspective(&view, &title, out, "mode_3d")?);
    files.push(write_mode(out, &mesh, &found)?);
    let followed = match (&study.path, d_end) {
        (Some(path_study), Some(d_end)) => {
            let checkpoints = path::Checkpoints {
                interval: study.checkpoints,
                request: &request,
                resumed,
            };
            let (summary, written) = path::follow(
                &frame,
                (path, &admissible),
                (path_study, d_end, checkpoints),
                out,
                &mut |state| progress(Progress::State(state)),
            )?;
            files.extend(written);
            Some(summary)
        }
        _ => None,
    };
    let json = out.join("pattern.json");
    files.push(json.clone());
    let report = PatternReport {
        command: "pattern",
        parameters: params.clone(),
        biaxial: study.biaxial,
        patch: spec,
        capped_sides: capped,
        patch_azimuth_degrees: frame.azimuth.to_degrees(),
        unknowns: found.unknowns,
        onset_theory: TheoryOnset {
            k0: onset.onset.k0,
            theta0_degrees: (!onset.theta0.is_nan()).then(|| frame.angle(onset.theta0).to_degrees()),
            d_c: onset.onset.d_c,
        },
        d_bifurcation: found.d,
        g_bifurcation: params.load.is_growth().then(|| params.load.parameter(found.d)),
        bracket: found.bracket,
        negative_pivots: found.negative_pivots,
        smallest_eigenvalue_before: found.eigenvalue,
        d_c_admissible: first.d_c,
        relative_difference: found.d / first.d_c - 1.0,
        admissible_wave_vectors: modes,
        mode_wave_vectors: spectrum.into_iter().take(4).collect(),
        inertia_evaluations: found.path.len(),
        path: followed,
        wall_seconds: start.elapsed().as_secs_f64(),
        files: files.iter().map(|f| f.display().to_string()).collect(),
    };
    write_json(&json, &report)?;
    Ok(report)
}

/// What [`run`] reports while it works.
pub enum Progress<'a> {
    /// The patch it built, its unknowns and the admissible wave vectors nearest the onset.
    Patch {
        spec: &'a PatchSpec,
        /// The patch's X axis from the load's (radians; [`PatchFrame`]).
        azimuth: f64,
        /// Its sides shorter than the onset mode's period along them.
        capped: &'a [CappedSide],
        unknowns: usize,
        modes: &'a [BoxMode],
        /// What its factorisations will need, and the memory available (bytes), if known.
        memory: (&'a MemoryEstimate, Option<f64>),
    },
    /// The tangent's negative pivots at the homogeneous state `d`.
    Inertia { d: f64, negative: usize },
    /// A state of the path past the onset.
    State(&'a PatternState),
    /// Asked to resume: the `d` of the checkpoint the path continues from, or none.
    Resume(Option<f64>),
}

/// `wave_vectors.csv`: the admissible wave vectors nearest the onset and their `d_c`.
fn write_wave_vectors(out: &Path, modes: &[BoxMode]) -> Result<Vec<PathBuf>> {
    let path = out.join("wave_vectors.csv");
    let mut table = CsvWriter::create(&path, &["m", "n", "k", "theta_degrees", "d_c"])?;
    for mode in modes {
        table.append(&[mode.m as f64, mode.n as f64, mode.k, mode.theta.to_degrees(), mode.d_c])?;
    }
    Ok(vec![path])
}

/// `mode_spectrum.csv`: the mode's surface spectrum, by decreasing amplitude.
fn write_spectrum(out: &Path, waves: &[WaveVector]) -> Result<Vec<PathBuf>> {
    let path = out.join("mode_spectrum.csv");
    let mut table = CsvWriter::create(&path, &["m", "n", "k", "theta_degrees", "amplitude"])?;
    for w in waves {
        table.append(&[w.m as f64, w.n as f64, w.k, w.theta_degrees, w.amplitude])?;
    }
    Ok(vec![path])
}

/// `mode.vtu`: the patch cut open along its periodic sides, with the mode as point vectors and
/// its top-surface `u_Y` as a scalar.
fn write_mode(out: &Path, mesh: &Mesh<3, 27>, found: &PatchBifurcation) -> Result<PathBuf> {
    let (points, cells, source) = mesh.unwrapped();
    let dofs = mesh.dofs();
    let mode = DataArray::vectors(
        "mode",
        source
            .iter()
            .map(|&n| std::array::from_fn(|c| found.mode[dofs.dof(n, c)])),
    );
    let height = DataArray::scalars("mode_uy", source.iter().map(|&n| found.mode[dofs.dof(n, Y)]).collect());
    let cell_type = CellType {
        vtk: <Hex27 as ReferenceElement<3, 27, 27>>::VTK_CELL_TYPE,
        order: <Hex27 as ReferenceElement<3, 27, 27>>::VTK_ORDER,
    };
    let path = out.join("mode.vtu");
    write_vtu(&path, &points, &cell_type, &cells, &[mode, height], &[])?;
    Ok(path)
}
