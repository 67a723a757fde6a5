//! `fiberfold crease`: the crease onset of the bilayer by the energy criterion of Hong, Zhao &
//! Suo (2009), generalised to the layer on the fibre-reinforced substrate. At a compression `d`
//! of the homogeneous state, a crease is seeded by folding the top surface over the reference
//! length `a` onto the symmetry plane `X = 0` ([`crate::protocol::crease_seed`]); it pays off
//! when `U_crease - U_flat < 0`. A half-space has no length scale, so there the threshold is the
//! same for every `a`; the layer of thickness `H` brings one, so the threshold `d(a)` is found
//! for several fold lengths ([`threshold`]) and `d_crease = min_a d(a)`, reported with the `a`
//! it takes.
//!
//! The crease tip is a singularity of the strain, so `d(a)` depends on the mesh (by 1-2 % from
//! the default mesh to one twice as fine). Each `d(a)` is therefore computed on the base mesh
//! with its element counts multiplied by 1, 2, 3, ... until it changes by less than the
//! refinement's tolerance, and extrapolated to a zero mesh size with the observed order
//! ([`convergence`]): `d_crease` comes with an uncertainty `d_crease_error`.
//!
//! The fold held on the plane over its whole length is not an equilibrium crease: the plane
//! pulls on some of its nodes. Under the released criterion ([`Criterion::Released`],
//! `released`) the state compared is the crease the fold closes to once let go to
//! frictionless contact, an equilibrium.

pub mod convergence;
mod first;
mod fold;
mod options;
mod released;
mod sequence;
pub mod threshold;
mod write;

pub use first::First;
pub use fold::FoldThreshold;
pub use options::CreaseOptions;
pub use threshold::fold_threshold;
pub use write::run;

use super::Tick;
use crate::error::{Error, Result};
use crate::fem::ellipticity::EllipticityReport;
use crate::fem::ElementKind;
use crate::material::Bilayer;
use crate::mesh::{MeshSpec, XRefinement};
use crate::parameters::{Load, Parameters};
use crate::stability::{Method, StabilityAnalysis};
use convergence::{extrapolate, Extrapolated};
use sequence::{next_scan, refine, refined_threshold};
use serde::{Deserialize, Serialize};

/// The square block `[0, size] x [-size, 1]` around the crease at `X = 0`: `nx` elements in X
/// refined `ratio` times near the crease, `layer` elements through the layer, `substrate`
/// below (graded from the layer's element size).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct CreaseMesh {
    pub size: f64,
    pub nx: usize,
    pub layer: usize,
    pub substrate: usize,
    pub ratio: f64,
    /// Ratio of consecutive layer elements from the surface down (1: uniform), so that the
    /// elements are smallest at the crease tip (the substrate starts at the layer's mean size).
    #[serde(default = "uniform_layer")]
    pub layer_grading: f64,
    /// The element (displacement unless given, as in files written before it existed).
    #[serde(default = "ElementKind::of_older_files")]
    pub element: ElementKind,
}

/// The layer of files written before the layer grading existed.
fn uniform_layer() -> f64 {
    1.0
}

impl CreaseMesh {
    /// The mesh for folds up to `longest`, refined over `1.5 longest` at the crease.
    pub fn spec(&self, longest: f64) -> MeshSpec {
        MeshSpec::new(
            self.nx,
            self.layer,
            self.substrate,
            1.0 / self.layer as f64,
            self.size,
            self.size,
        )
        .with_layer_grading(self.layer_grading)
        .refined(XRefinement {
            ratio: self.ratio,
            width: 1.5 * longest,
            offset: 0.0,
            period: 4.0 * self.size,
        })
        .with_element(self.element)
    }

    /// The mesh of the sequence with `factor` times the elements in every direction: the same
    /// grading (the layer's ratio per element is `layer_grading^(1 / factor)`), so that every
    /// element size scales as `1 / factor`.
    pub fn scaled(&self, factor: usize) -> Self {
        CreaseMesh {
            nx: factor * self.nx,
            layer: factor * self.layer,
            substrate: factor * self.substrate,
            layer_grading: self.layer_grading.powf(1.0 / factor as f64),
            ..*self
        }
    }
}

/// Which creased state the energy criterion compares with the flat state.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, clap::ValueEnum)]
#[serde(rename_all = "lowercase")]
pub enum Criterion {
    /// The fold held on the plane over its whole reference length `a` (Hong, Zhao & Suo's
    /// construction).
    #[default]
    #[value(help = "The fold held on the symmetry plane over its whole length a (Hong, Zhao & Suo's)")]
    Held,
    /// The fold released to frictionless contact with the plane: the equilibrium crease it
    /// closes to (or the flat state, where it reopens).
    #[value(
        help = "The fold released to frictionless contact with the plane: the equilibrium crease it closes to (a search from the held fold's threshold, each step a fold and a release)"
    )]
    Released,
}

/// How `d(a)` is searched: scan `from` upwards by `step` to `to`, then locate the sign change
/// to `tolerance` in `d`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Scan {
    pub from: f64,
    pub to: f64,
    pub step: f64,
    pub tolerance: f64,
}

/// One `crease` computation.
#[derive(Clone, Debug, PartialEq)]
pub struct CreaseStudy {
    pub mesh: CreaseMesh,
    /// Reference fold lengths `a` (units of `H`).
    pub fold_lengths: Vec<f64>,
    pub scan: Scan,
    /// Which creased state is compared with the flat one.
    pub criterion: Criterion,
    /// The mesh sequence that converges each threshold (None: the base mesh alone).
    pub refinement: Option<Refinement>,
    /// Scan each fold only up to the lowest threshold found before it, and refine only the
    /// fold of the lowest: the minimum over the folds is the same, the thresholds above it are
    /// not located, nor refined the folds that ended early above it. Under
    /// the released criterion the held scan is capped there: a shortcut that holds where the
    /// released crease forgets its fold length, as it is seen to (the folds that close give
    /// the same released crease and threshold).
    pub lowest_only: bool,
    /// End the scan [`BEYOND_WRINKLE`] past the wrinkling onset of the linear theory (plane
    /// strain): past it the wrinkle comes first, whatever the crease does. A fold whose scan
    /// ends early (a fold that snapped) past that point is not refined either.
    pub stop_past_wrinkle: bool,
}

/// How far past the wrinkling onset `d_wrinkle` a scan that stops there goes: a few times the
/// uncertainty of a converged crease onset, so that a threshold just past it is located (and
/// too close to call).
pub const BEYOND_WRINKLE: f64 = 0.01;

impl Default for CreaseStudy {
    /// A 12 H block, 24 x (3 + 10) elements refined 8 times at the crease in X, the layer's
    /// elements halving towards the surface (1/7, 2/7, 4/7 H); folds of 0.5, 1, 2 H;
    /// `d` scanned from 0.05 to 0.7 by 0.05, located to 1e-5; the held criterion; converged in
    /// the mesh ([`Refinement::default`]), only the lowest threshold located on the finer
    /// meshes, the scan ending just past the wrinkle's onset.
    fn default() -> Self {
        CreaseStudy {
            mesh: CreaseMesh {
                size: 12.0,
                nx: 24,
                layer: 3,
                substrate: 10,
                ratio: 8.0,
                layer_grading: 2.0,
                element: ElementKind::default(),
            },
            fold_lengths: vec![0.5, 1.0, 2.0],
            scan: Scan {
                from: 0.05,
                to: 0.7,
                step: 0.05,
                tolerance: 1e-5,
            },
            criterion: Criterion::default(),
            refinement: Some(Refinement::default()),
            lowest_only: true,
            stop_past_wrinkle: true,
        }
    }
}

impl CreaseStudy {
    /// Checks the ranges (names as the CLI's flags).
    pub fn validate(&self) -> Result<()> {
        let s = self.scan;
        if !(s.from.is_finite() && s.from > 0.0 && s.to < 1.0 && s.from < s.to) {
            return Err(Error::invalid("d-from", s.from, "(0, d-to) with d-to < 1"));
        }
        // A step of exactly d-to - d-from as typed (0.37 - 0.32 is 0.0499...9 in binary) is allowed.
        if !(s.step.is_finite() && s.step > 0.0 && s.step <= (s.to - s.from) * (1.0 + 1e-12)) {
            return Err(Error::invalid("d-step", s.step, "(0, d-to - d-from]"));
        }
        if !(s.tolerance.is_finite() && s.tolerance > 0.0 && s.tolerance < s.step) {
            return Err(Error::invalid("tolerance", s.tolerance, "(0, d-step)"));
        }
        let m = &self.mesh;
        if !(m.size.is_finite() && m.size >= 4.0) {
            return Err(Error::invalid("size", m.size, "[4, inf) (units of H)"));
        }
        if self.fold_lengths.is_empty() {
            return Err(Error::invalid("fold", "none", "at least one fold length"));
        }
        for &a in &self.fold_lengths {
            if !(a.is_finite() && a > 0.0 && a <= m.size / 4.0) {
                return Err(Error::invalid(
                    "fold",
                    a,
                    &format!("(0, size / 4 = {}] (units of H)", m.size / 4.0),
                ));
            }
        }
        if let Some(r) = self.refinement {
            if !(r.tolerance.is_finite() && r.tolerance > 0.0) {
                return Err(Error::invalid("mesh-tolerance", r.tolerance, "(0, inf) (in d)"));
            }
            if !(3..=6).contains(&r.max_meshes) {
                return Err(Error::invalid("max-meshes", r.max_meshes, "[3, 6]"));
            }
        }
        self.fold_lengths.iter().try_for_each(|&a| self.mesh.spec(a).validate())
    }

    fn longest(&self) -> f64 {
        self.fold_lengths.iter().copied().fold(0.0, f64::max)
    }
}

/// The mesh sequence of a converged onset: the base mesh times 1, 2, ... up to `max_meshes`,
/// stopped once every refined threshold changes by less than `tolerance` in `d` (and at least
/// three meshes gave one, so that an order can be observed).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Refinement {
    pub tolerance: f64,
    pub max_meshes: usize,
}

impl Default for Refinement {
    /// Changes below 1e-3 in `d`, at most four meshes.
    fn default() -> Self {
        Refinement {
            tolerance: 1e-3,
            max_meshes: 4,
        }
    }
}

/// One fold length over the mesh sequence.
#[derive(Clone, Debug, Serialize)]
pub struct FoldConvergence {
    pub fold_length: f64,
    /// `d(a)` on each mesh of the sequence (None where none was found, or not computed).
    pub thresholds: Vec<Option<f64>>,
    /// `d(a)` extrapolated to a zero mesh size, with its uncertainty and observed order.
    pub extrapolated: Option<Extrapolated>,
    /// Whether the last two thresholds differ by less than the refinement's tolerance.
    pub converged: bool,
    /// The scan on each mesh computed (the base mesh first).
    pub meshes: Vec<FoldThreshold>,
}

impl FoldConvergence {
    /// The scan on the finest mesh that found a threshold.
    pub fn finest(&self) -> Option<&FoldThreshold> {
        self.meshes.iter().rev().find(|m| m.d_threshold.is_some())
    }

    /// The thresholds `of` each mesh of the last run of consecutive meshes that found one, with
    /// their sizes `1 / s` (a fold that failed on one mesh may find a threshold on the finer
    /// ones).
    fn last_run(&self, of: impl Fn(&FoldThreshold) -> Option<f64>) -> (Vec<f64>, Vec<f64>) {
        let mut run = Vec::new();
        for (i, d) in self.meshes.iter().map(of).enumerate().rev() {
            match d {
                Some(d) => run.push((1.0 / (i + 1) as f64, d)),
                None if run.is_empty() => continue,
                None => break,
            }
        }
        run.reverse();
        run.into_iter().unzip()
    }

    fn update(&mut self, refinement: Option<Refinement>) {
        self.thresholds = self.meshes.iter().map(|m| m.d_threshold).collect();
        let (sizes, values) = self.last_run(|m| m.d_threshold);
        self.extrapolated = extrapolate(&sizes, &values);
        let n = values.len();
        self.converged = n >= 3
            && refinement.is_some_and(|r| (values[n - 1] - values[n - 2]).abs() < r.tolerance)
            && self.thresholds.last().is_some_and(|d| d.is_some());
    }
}

/// A mesh of the sequence.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct MeshUsed {
    /// Element counts relative to the base mesh.
    pub factor: usize,
    pub mesh: CreaseMesh,
    /// Unknowns of the mesh of the longest fold (each fold's mesh is refined over `1.5 a` at the
    /// crease, so that its threshold is the same whatever other folds are asked for).
    pub unknowns: usize,
    /// Folds searched on this mesh, the creased states they solved (held and released), and
    /// the wall time they took (s): where a run's time goes.
    pub folds: usize,
    pub states: usize,
    pub seconds: f64,
}

/// `crease.json`.
#[derive(Clone, Debug, Serialize)]
pub struct CreaseReport {
    pub command: &'static str,
    pub parameters: Parameters,
    /// The base mesh, and its unknowns.
    pub mesh: CreaseMesh,
    pub unknowns: usize,
    /// What loads the bilayer; under growth every `d` is the strain `1 - 1/g`.
    pub load: Load,
    /// The wrinkling onset of the linear theory (plane strain; None: none before the loss of
    /// ellipticity).
    pub d_wrinkle: Option<f64>,
    /// Whether the scan ended just past `d_wrinkle` ([`CreaseStudy::stop_past_wrinkle`]) rather
    /// than at the `to` asked for: a crease that pays off only later is not located.
    pub scan_ends_past_wrinkle: bool,
    /// Wall time of the linear theory's onset (s).
    pub wrinkle_seconds: f64,
    /// Which comes first: the wrinkle, the crease, or too close to call within `d_crease_error`
    /// ([`First::decide`]).
    pub first: First,
    /// Which creased state the thresholds compare with the flat one.
    pub criterion: Criterion,
    /// `min_a d(a)`, extrapolated in the mesh: the crease onset (None if no fold paid off).
    pub d_crease: Option<f64>,
    /// The growth of the layer at the crease onset under a growth load (None otherwise).
    pub g_crease: Option<f64>,
    /// Its uncertainty (None from a single mesh).
    pub d_crease_error: Option<f64>,
    /// The order of convergence observed for that fold.
    pub order: Option<f64>,
    /// Whether that fold's threshold changed by less than the tolerance on the last mesh.
    pub converged: bool,
    /// The fold length `a` of that minimum, and the deformed depth of its crease on the finest
    /// mesh (units of H; the released crease's under the released criterion).
    pub fold_length: Option<f64>,
    pub depth: Option<f64>,
    /// The meshes used, coarsest first.
    pub meshes: Vec<MeshUsed>,
    pub folds: Vec<FoldConvergence>,
    /// Strong ellipticity over the creased states evaluated (all folds, all meshes): where a
    /// margin is negative the continuum admits shear bands and the threshold depends on the mesh.
    pub ellipticity: EllipticityReport,
    pub scan: Scan,
    pub refinement: Option<Refinement>,
    pub seconds: f64,
}

impl CreaseReport {
    /// The highest `d` below which no fold paid off on any mesh of its last scan.
    pub fn cleared(&self) -> f64 {
        self.folds
            .iter()
            .filter_map(|f| f.meshes.last().map(FoldThreshold::cleared))
            .fold(self.scan.to, f64::min)
    }
}

/// Computes the crease onset of `params` (no files).
pub fn crease(params: &Parameters, study: &CreaseStudy, tick: Tick) -> Result<CreaseReport> {
    params.validate()?;
    study.validate()?;
    study.mesh.element.check_for(params.incompressible)?;
    let start = std::time::Instant::now();
    let d_wrinkle = wrinkle_onset(params)?;
    let wrinkle_seconds = start.elapsed().as_secs_f64();
    let requested_to = study.scan.to;
    let study = &study.bounded(d_wrinkle);
    let materials = Bilayer::new(params);
    let longest = study.longest();
    let mut folds: Vec<FoldConvergence> = Vec::with_capacity(study.fold_lengths.len());
    let mut meshes = Vec::new();
    let max_meshes = study.refinement.map_or(1, |r| r.max_meshes);
    for factor in 1..=max_meshes {
        let mesh = study.mesh.scaled(factor);
        meshes.push(MeshUsed {
            factor,
            mesh,
            unknowns: mesh.spec(longest).num_dofs(),
            folds: 0,
            states: 0,
            seconds: 0.0,
        });
        let mut lowest = study.scan.to;
        for (i, &a) in study.fold_lengths.iter().enumerate() {
            if factor == 1 {
                folds.push(FoldConvergence {
                    fold_length: a,
                    thresholds: Vec::new(),
                    extrapolated: None,
                    converged: false,
                    meshes: Vec::new(),
                });
            } else if !refine(study, &folds, i, d_wrinkle) {
                continue;
            }
            let mut scan = next_scan(study, &folds[i]);
            if study.lowest_only {
                if lowest <= scan.from {
                    continue;
                }
                scan.to = scan.to.min(lowest);
            }
            // Each fold on its own mesh: its threshold does not depend on the others asked for.
            let spec = mesh.spec(a);
            let clock = std::time::Instant::now();
            let mut fold = match factor {
                1 => fold_threshold(&materials, spec, a, scan, study.criterion, tick)?,
                _ => refined_threshold(&materials, spec, a, scan, study, tick)?,
            };
            fold.seconds = clock.elapsed().as_secs_f64();
            let used = meshes.last_mut().expect("this mesh");
            used.folds += 1;
            used.states += fold.evaluations.len() + fold.released_evaluations.len();
            used.seconds += fold.seconds;
            lowest = fold.d_threshold.map_or(lowest, |d| d.min(lowest));
            let fold_convergence = &mut folds[i];
            // Keep the meshes aligned with the sequence: a fold skipped on a mesh has no entry.
            while fold_convergence.meshes.len() + 1 < factor {
                fold_convergence.meshes.push(FoldThreshold::not_computed(a));
            }
            fold_convergence.meshes.push(fold);
            fold_convergence.update(study.refinement);
        }
        let done = (0..folds.len()).all(|i| !refine(study, &folds, i, d_wrinkle));
        if factor >= 3 && done {
            break;
        }
    }
    let best = folds
        .iter()
        .enumerate()
        .filter_map(|(i, f)| f.extrapolated.map(|e| (e, i)))
        .min_by(|x, y| x.0.value.total_cmp(&y.0.value));
    let mut report = CreaseReport {
        command: "crease",
        parameters: params.clone(),
        mesh: study.mesh,
        unknowns: meshes[0].unknowns,
        load: params.load,
        criterion: study.criterion,
        d_wrinkle,
        scan_ends_past_wrinkle: study.scan.to < requested_to,
        wrinkle_seconds,
        first: First::None,
        d_crease: best.map(|(e, _)| e.value),
        g_crease: best
            .filter(|_| params.load.is_growth())
            .map(|(e, _)| params.load.parameter(e.value)),
        d_crease_error: best.and_then(|(e, _)| e.error),
        order: best.and_then(|(e, _)| e.order),
        converged: best.is_some_and(|(_, i)| folds[i].converged),
        fold_length: best.map(|(_, i)| folds[i].fold_length),
        depth: best
            .and_then(|(_, i)| folds[i].finest())
            .and_then(|fold| fold.depth_at_threshold(study.criterion)),
        meshes,
        scan: study.scan,
        refinement: study.refinement,
        ellipticity: EllipticityReport::new(folds.iter().flat_map(|f| {
            f.meshes
                .iter()
                .flat_map(|m| m.evaluations.iter().map(|e| (e.strain, e.ellipticity)))
        })),
        folds,
        seconds: start.elapsed().as_secs_f64(),
    };
    let error = report.d_crease_error.unwrap_or(0.0);
    report.first = First::decide((d_wrinkle, report.d_crease), error, report.cleared());
    Ok(report)
}

/// The wrinkling onset of the linear theory (plane strain), if there is one before the loss
/// of ellipticity.
fn wrinkle_onset(params: &Parameters) -> Result<Option<f64>> {
    match StabilityAnalysis::new(params, Method::Exact)?.onset() {
        Ok(onset) => Ok(Some(onset.d_c)),
        Err(Error::NoRoot { .. }) => Ok(None),
        Err(e) => Err(e),
    }
}
