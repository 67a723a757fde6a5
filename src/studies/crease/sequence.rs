//! The mesh sequence of a converged onset: which folds go on to the next mesh, and the local
//! scan each finer mesh makes around the previous threshold.

use super::{fold_threshold, CreaseStudy, FoldConvergence, FoldThreshold, Scan, BEYOND_WRINKLE};
use crate::error::Result;
use crate::material::Bilayer;
use crate::mesh::MeshSpec;
use crate::studies::Tick;

/// The smallest step of a finer mesh's scan around the previous mesh's threshold.
const LOCAL_STEP: f64 = 2.5e-3;

/// Times a finer mesh's scan lowers its start where its first point already pays off.
const LOWERINGS: usize = 4;

/// The scan of a fold on the next mesh: steps `delta` (twice the last change of its held
/// threshold, at least [`LOCAL_STEP`]) from `delta` below its previous held threshold to
/// `2 delta` above it; without a previous threshold, the whole scan. (The held fold is scanned
/// first under either criterion; the released search starts from its threshold.)
pub(super) fn next_scan(study: &CreaseStudy, fold: &FoldConvergence) -> Scan {
    let scan = study.scan;
    let (_, values) = fold.last_run(|m| m.d_held);
    let Some(&d) = values.last() else { return scan };
    let change = match values.len() {
        1 => 2.0 * LOCAL_STEP,
        n => (values[n - 1] - values[n - 2]).abs(),
    };
    let delta = (2.0 * change).max(LOCAL_STEP);
    let from = (d - delta).max(scan.from);
    let to = (d + 2.0 * delta).min(scan.to);
    Scan {
        from,
        to,
        step: delta.min(to - from),
        tolerance: scan.tolerance.min(0.5 * delta),
    }
}

/// [`fold_threshold`] on a finer mesh: where the scan's first point already pays off, its start
/// is lowered (by four times its step each time, at most [`LOWERINGS`] times, not below the
/// study's `from`).
pub(super) fn refined_threshold(
    materials: &Bilayer,
    spec: MeshSpec,
    a: f64,
    mut scan: Scan,
    study: &CreaseStudy,
    tick: Tick,
) -> Result<FoldThreshold> {
    let mut earlier = Vec::new();
    for lowering in 0..=LOWERINGS {
        let mut fold = fold_threshold(materials, spec, a, scan, study.criterion, tick)?;
        let first_pays = fold.d_threshold.is_none() && fold.evaluations.first().is_some_and(|e| e.difference <= 0.0);
        if !first_pays || scan.from <= study.scan.from || lowering == LOWERINGS {
            fold.evaluations.extend(earlier);
            fold.evaluations.sort_by(|x, y| x.strain.total_cmp(&y.strain));
            return Ok(fold);
        }
        earlier.append(&mut fold.evaluations);
        let to = scan.from;
        scan.from = (scan.from - 4.0 * scan.step).max(study.scan.from);
        scan.to = to;
        scan.step = scan.step.min(to - scan.from);
    }
    unreachable!("the last lowering returns")
}

impl CreaseStudy {
    /// The study with its scan ending [`BEYOND_WRINKLE`] past `d_wrinkle` where it stops there
    /// and `d_wrinkle` lies inside the scan, in steps (no longer than the scan's) that land on
    /// `d_wrinkle`: the fold is evaluated there, so that a fold snapping just past it leaves
    /// the question decided.
    pub(super) fn bounded(&self, d_wrinkle: Option<f64>) -> CreaseStudy {
        let mut study = self.clone();
        let s = &mut study.scan;
        if let Some(w) = d_wrinkle.filter(|&w| self.stop_past_wrinkle && w > s.from && w < s.to) {
            s.step = (w - s.from) / ((w - s.from) / s.step).ceil();
            s.to = (w + BEYOND_WRINKLE).min(s.to);
            s.tolerance = s.tolerance.min(0.5 * s.step);
        }
        study
    }

    /// Where the question is decided: a fold that ended early past it needs no finer mesh. The
    /// wrinkling onset where the scan stops there; the lowest threshold so far where only the
    /// lowest is located.
    fn decided_at(&self, folds: &[FoldConvergence], d_wrinkle: Option<f64>) -> f64 {
        let wrinkle = d_wrinkle.filter(|_| self.stop_past_wrinkle);
        let lowest = folds
            .iter()
            .filter_map(|f| f.extrapolated.map(|e| e.value))
            .filter(|_| self.lowest_only)
            .fold(f64::INFINITY, f64::min);
        wrinkle.map_or(lowest, |w| w.min(lowest))
    }
}

/// Whether fold `i` goes on to the next mesh: with a refinement, while it is not converged,
/// if it found a threshold or its scan ended early below where the question is decided on some
/// mesh (a fold that cleared the whole scan, or that point, on every mesh so far has no
/// threshold to converge). With `lowest_only`, only the fold of the lowest threshold so far
/// goes on (or every fold while none has one).
pub(super) fn refine(study: &CreaseStudy, folds: &[FoldConvergence], i: usize, d_wrinkle: Option<f64>) -> bool {
    let Some(refinement) = study.refinement else {
        return false;
    };
    let fold = &folds[i];
    let decided = study.decided_at(folds, d_wrinkle);
    let candidate = !fold.converged
        && fold.meshes.len() < refinement.max_meshes
        && fold
            .meshes
            .iter()
            .any(|m| m.d_threshold.is_some() || m.stopped.is_some() && m.cleared() < decided);
    if !study.lowest_only || !candidate {
        return candidate;
    }
    let lowest = folds
        .iter()
        .enumerate()
        .filter_map(|(j, f)| f.extrapolated.map(|e| (e.value, j)))
        .min_by(|x, y| x.0.total_cmp(&y.0));
    lowest.is_none_or(|(_, j)| j == i)
}
