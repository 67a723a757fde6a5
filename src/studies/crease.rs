//! `fiberfold crease`: the crease onset of the bilayer by the energy criterion of Hong, Zhao &
//! Suo (2009), generalised to the layer on the fibre-reinforced substrate. At a compression `d`
//! of the homogeneous state, a crease is seeded by folding the top surface over the reference
//! length `a` onto the symmetry plane `X = 0` ([`crate::protocol::crease_seed`]); it pays off
//! when `U_crease - U_flat < 0`. A half-space has no length scale, so there the threshold is the
//! same for every `a`; the layer of thickness `H` brings one, so the threshold `d(a)` is found
//! for several fold lengths and `d_crease = min_a d(a)`, reported with the `a` it takes. The
//! smallest is then recomputed on a mesh refined twice in every direction (mesh convergence).
//!
//! `d(a)`: `U_crease - U_flat` is scanned upwards in `d` until it changes sign, then Brent's
//! method brackets the root. Past the threshold the seeded fold may snap to a deeper crease
//! (no quasi-static path): a failed evaluation ends the scan of that `a`, and says where.

use super::Tick;
use crate::error::{Error, Result};
use crate::fem::ellipticity::EllipticityReport;
use crate::material::Bilayer;
use crate::mesh::{ElementKind, MeshSpec, XRefinement};
use crate::numerics::roots::brent;
use crate::output::{ensure_dir, plot::save_panels, write_json, CsvWriter, Figure, LineStyle, Series};
use crate::parameters::Parameters;
use crate::protocol::crease_seed::{crease_energy, CreaseEnergy};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

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
    /// The element (displacement unless given, as in files written before it existed).
    #[serde(default = "ElementKind::of_older_files")]
    pub element: ElementKind,
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
        .refined(XRefinement {
            ratio: self.ratio,
            width: 1.5 * longest,
            offset: 0.0,
            period: 4.0 * self.size,
        })
        .with_element(self.element)
    }

    /// Twice the elements in every direction.
    pub fn refined(&self) -> Self {
        CreaseMesh {
            nx: 2 * self.nx,
            layer: 2 * self.layer,
            substrate: 2 * self.substrate,
            ..*self
        }
    }
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
    /// Recompute the smallest threshold on [`CreaseMesh::refined`].
    pub convergence: bool,
    /// Scan each fold only up to the lowest threshold found before it: the minimum over the
    /// folds is the same, the thresholds above it are not located (the map's shortcut).
    pub lowest_only: bool,
}

impl Default for CreaseStudy {
    /// A 12 H block, 48 x (4 + 20) elements refined 8 times at the crease; folds of 0.5, 1, 2 H;
    /// `d` scanned from 0.05 to 0.7 by 0.05, located to 1e-3; the mesh check on.
    fn default() -> Self {
        CreaseStudy {
            mesh: CreaseMesh {
                size: 12.0,
                nx: 48,
                layer: 4,
                substrate: 20,
                ratio: 8.0,
                element: ElementKind::default(),
            },
            fold_lengths: vec![0.5, 1.0, 2.0],
            scan: Scan {
                from: 0.05,
                to: 0.7,
                step: 0.05,
                tolerance: 1e-3,
            },
            convergence: true,
            lowest_only: false,
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
        self.mesh.spec(self.longest()).validate()
    }

    fn longest(&self) -> f64 {
        self.fold_lengths.iter().copied().fold(0.0, f64::max)
    }
}

/// `d(a)` for one fold length, with every energy evaluated on the way.
#[derive(Clone, Debug, Serialize)]
pub struct FoldThreshold {
    pub fold_length: f64,
    /// Where `U_crease - U_flat` changes sign (None: not within the scan).
    pub d_threshold: Option<f64>,
    pub evaluations: Vec<CreaseEnergy>,
    /// Why the scan ended early, if it did (e.g. the fold snapped).
    pub stopped: Option<String>,
}

/// `crease.json`.
#[derive(Clone, Debug, Serialize)]
pub struct CreaseReport {
    pub command: &'static str,
    pub parameters: Parameters,
    pub mesh: CreaseMesh,
    pub unknowns: usize,
    /// `min_a d(a)`: the crease onset (None if no fold paid off within the scan).
    pub d_crease: Option<f64>,
    /// The fold length `a` of that minimum, and the deformed depth of its crease (units of H).
    pub fold_length: Option<f64>,
    pub depth: Option<f64>,
    pub folds: Vec<FoldThreshold>,
    /// `d_crease` of the same fold on the refined mesh, and the relative change.
    pub d_crease_refined: Option<f64>,
    pub refined_unknowns: Option<usize>,
    pub mesh_change: Option<f64>,
    /// Strong ellipticity over the creased states evaluated (all folds, first mesh): where a
    /// margin is negative the continuum admits shear bands and the threshold depends on the mesh.
    pub ellipticity: EllipticityReport,
    pub scan: Scan,
    pub seconds: f64,
}

/// `d(a)` on `spec`: the scan, then Brent within its first sign change.
pub fn fold_threshold(materials: &Bilayer, spec: MeshSpec, a: f64, scan: Scan, tick: Tick) -> Result<FoldThreshold> {
    let mut evaluations: Vec<CreaseEnergy> = Vec::new();
    let mut stopped = None;
    let mut bracket = None;
    let grid = (0..)
        .map(|i| scan.from + i as f64 * scan.step)
        .take_while(|&d| d < scan.to - 1e-9)
        .chain(std::iter::once(scan.to));
    for d in grid {
        match crease_energy(materials, spec, d, a) {
            Ok(e) => {
                let pays = e.difference <= 0.0;
                let previous = evaluations.last().map(|p| p.strain);
                evaluations.push(e);
                tick();
                if pays {
                    bracket = previous.map(|lo| (lo, d));
                    break;
                }
            }
            Err(Error::Solver(m)) => {
                // The fold snapped: look for the sign change between the last good d and here.
                let (found, why) = halve_towards(materials, spec, a, &mut evaluations, d, m, tick)?;
                bracket = found;
                if bracket.is_none() {
                    stopped = Some(why);
                }
                break;
            }
            Err(e) => return Err(e),
        }
    }
    let mut d_threshold = None;
    if let Some((lo, hi)) = bracket {
        let root = brent(
            "the energy of a seeded crease minus that of the flat state",
            |d| {
                let e = crease_energy(materials, spec, d, a)?;
                let difference = e.difference;
                evaluations.push(e);
                tick();
                Ok(difference)
            },
            lo,
            hi,
            scan.tolerance,
        );
        match root {
            Ok(root) => d_threshold = Some(root),
            Err(e) => stopped = Some(format!("locating the sign change in [{lo:.3}, {hi:.3}]: {e}")),
        }
    } else if stopped.is_none() && evaluations.first().is_some_and(|e| e.difference <= 0.0) {
        stopped = Some(format!(
            "the crease already pays off at d = {}: lower --d-from",
            scan.from
        ));
    }
    evaluations.sort_by(|x, y| x.strain.total_cmp(&y.strain));
    Ok(FoldThreshold {
        fold_length: a,
        d_threshold,
        evaluations,
        stopped,
    })
}

/// After a failed fold at `failed`: up to three halvings of the interval from the last good
/// evaluation; a bracket `(lo, hi)` if one of them pays off, else why the scan ends.
fn halve_towards(
    materials: &Bilayer,
    spec: MeshSpec,
    a: f64,
    evaluations: &mut Vec<CreaseEnergy>,
    mut failed: f64,
    mut why: String,
    tick: Tick,
) -> Result<(Option<(f64, f64)>, String)> {
    let Some(mut lo) = evaluations.last().map(|e| e.strain) else {
        return Ok((None, format!("no quasi-static fold at d = {failed:.3}: {why}")));
    };
    for _ in 0..3 {
        let mid = 0.5 * (lo + failed);
        match crease_energy(materials, spec, mid, a) {
            Ok(e) => {
                let pays = e.difference <= 0.0;
                evaluations.push(e);
                tick();
                if pays {
                    return Ok((Some((lo, mid)), String::new()));
                }
                lo = mid;
            }
            Err(Error::Solver(m)) => (failed, why) = (mid, m),
            Err(e) => return Err(e),
        }
    }
    Ok((
        None,
        format!("no quasi-static fold at d = {failed:.3} (the crease has not paid off below it): {why}"),
    ))
}

/// Computes the crease onset of `params` (no files).
pub fn crease(params: &Parameters, study: &CreaseStudy, tick: Tick) -> Result<CreaseReport> {
    params.validate()?;
    study.validate()?;
    study.mesh.element.check_for(params.incompressible)?;
    let start = std::time::Instant::now();
    let materials = Bilayer::new(params);
    let spec = study.mesh.spec(study.longest());
    let mut folds: Vec<FoldThreshold> = Vec::with_capacity(study.fold_lengths.len());
    for &a in &study.fold_lengths {
        let mut scan = study.scan;
        if study.lowest_only {
            let lowest = folds.iter().filter_map(|f| f.d_threshold).fold(scan.to, f64::min);
            if lowest <= scan.from {
                continue;
            }
            scan.to = lowest;
        }
        folds.push(fold_threshold(&materials, spec, a, scan, tick)?);
    }
    let best = folds
        .iter()
        .enumerate()
        .filter_map(|(i, f)| f.d_threshold.map(|d| (d, i)))
        .min_by(|x, y| x.0.total_cmp(&y.0));
    let (mut d_crease_refined, mut refined_unknowns) = (None, None);
    if let (true, Some((d, i))) = (study.convergence, best) {
        // The same fold on the refined mesh, scanned from just below the coarse threshold.
        let refined = study.mesh.refined().spec(study.longest());
        let scan = Scan {
            from: (d - 2.0 * study.scan.step).max(study.scan.from),
            ..study.scan
        };
        let fold = fold_threshold(&materials, refined, folds[i].fold_length, scan, tick)?;
        d_crease_refined = fold.d_threshold;
        refined_unknowns = Some(refined.num_dofs());
    }
    Ok(CreaseReport {
        command: "crease",
        parameters: params.clone(),
        mesh: study.mesh,
        unknowns: spec.num_dofs(),
        d_crease: best.map(|(d, _)| d),
        fold_length: best.map(|(_, i)| folds[i].fold_length),
        depth: best.and_then(|(d, i)| folds[i].nearest(d)).map(|e| e.depth),
        mesh_change: best.and_then(|(d, _)| d_crease_refined.map(|r| (r - d).abs() / d)),
        d_crease_refined,
        refined_unknowns,
        scan: study.scan,
        ellipticity: EllipticityReport::new(
            folds
                .iter()
                .flat_map(|f| f.evaluations.iter().map(|e| (e.strain, e.ellipticity))),
        ),
        folds,
        seconds: start.elapsed().as_secs_f64(),
    })
}

impl FoldThreshold {
    /// The evaluation closest to `d`.
    fn nearest(&self, d: f64) -> Option<&CreaseEnergy> {
        self.evaluations
            .iter()
            .min_by(|x, y| (x.strain - d).abs().total_cmp(&(y.strain - d).abs()))
    }
}

/// Runs the study and writes `crease.json`, `crease_energy.csv` and `crease.png/svg` (the
/// energy difference against `d` for every fold, and the crease at the onset).
pub fn run(params: &Parameters, study: &CreaseStudy, out: &Path, tick: Tick) -> Result<(CreaseReport, Vec<PathBuf>)> {
    let report = crease(params, study, tick)?;
    ensure_dir(out)?;
    let csv = out.join("crease_energy.csv");
    let mut table = CsvWriter::create(
        &csv,
        &[
            "fold_length",
            "d",
            "difference",
            "scaled_difference",
            "depth",
            "min_J",
            "ellipticity_layer",
            "ellipticity_substrate",
        ],
    )?;
    let mut energy = Figure::new(
        "Energy of a seeded crease against the flat state",
        "end-shortening d = 1 - lambda_1",
        "(U_crease - U_flat) / (mu_l a^2)",
    );
    for (i, fold) in report.folds.iter().enumerate() {
        for e in &fold.evaluations {
            table.append(&[
                fold.fold_length,
                e.strain,
                e.difference,
                e.scaled_difference,
                e.depth,
                e.min_jacobian,
                e.ellipticity.layer,
                e.ellipticity.substrate,
            ])?;
        }
        let label = match fold.d_threshold {
            Some(d) => format!("a = {} H: d = {d:.4}", fold.fold_length),
            None => format!("a = {} H: no crease in the scan", fold.fold_length),
        };
        let points = fold
            .evaluations
            .iter()
            .map(|e| (e.strain, e.scaled_difference))
            .collect();
        energy
            .series
            .push(Series::new(label, points, LineStyle::DotsAndLine, i));
    }
    let mut panels = vec![energy];
    let onset = report.d_crease.zip(report.fold_length);
    if let Some((d, a)) = onset {
        let fold = report.folds.iter().find(|f| f.fold_length == a).expect("the best fold");
        let nearest = fold.nearest(d).expect("evaluated");
        let window = 4.0 * a;
        let surface: Vec<(f64, f64)> = nearest.surface.iter().copied().filter(|p| p.0 <= window).collect();
        panels.push(
            Figure::new(
                format!("crease at d = {:.3} (a = {a} H), mirrored", nearest.strain),
                "current x / H",
                "current y / H",
            )
            .with(Series::new("surface", surface.clone(), LineStyle::Solid, 0))
            .with(Series::new(
                "",
                surface.iter().map(|&(x, y)| (-x, y)).collect(),
                LineStyle::Solid,
                0,
            )),
        );
    }
    let mut files = vec![csv];
    files.extend(save_panels(&panels, out, "crease")?);
    let json = out.join("crease.json");
    write_json(&json, &report)?;
    files.push(json);
    Ok((report, files))
}
