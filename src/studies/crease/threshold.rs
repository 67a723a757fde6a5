//! `d(a)` on one mesh: `U_crease - U_flat` of the held fold is scanned upwards in `d` until it
//! changes sign, then Brent's method locates the root inside that first bracket, from the two
//! values the scan already has. Past the threshold the seeded fold may snap to a deeper crease
//! (no quasi-static path): a failed fold halves the interval from the last good `d` up to three
//! times, and otherwise ends the scan of that `a`, saying where. Under the released criterion
//! the search goes on from the held fold's threshold ([`super::released`]).

use super::{released::released_threshold, Criterion, Scan};
use crate::error::{Error, Result};
use crate::material::Bilayer;
use crate::mesh::MeshSpec;
use crate::numerics::roots::brent_from;
use crate::protocol::crease_seed::{crease_energy, released_crease, CreaseEnergy, ReleasedCrease};
use crate::studies::Tick;
use serde::Serialize;

/// `d(a)` for one fold length on one mesh, with every energy evaluated on the way.
#[derive(Clone, Debug, Serialize)]
pub struct FoldThreshold {
    pub fold_length: f64,
    /// The threshold by the study's criterion (None: not within the scan).
    pub d_threshold: Option<f64>,
    /// Where the held fold's `U_crease - U_flat` changes sign (the held criterion's threshold).
    pub d_held: Option<f64>,
    /// The held fold at every `d` evaluated.
    pub evaluations: Vec<CreaseEnergy>,
    /// Why the scan ended early, if it did (e.g. the fold snapped).
    pub stopped: Option<String>,
    /// The fold at the threshold let go to contact with the plane: whether it stays closed,
    /// over what length, and with the plane pushing everywhere it touches.
    pub released: Option<ReleasedCrease>,
    /// Why the release at the threshold failed, if it did.
    pub release_error: Option<String>,
    /// Every release evaluated, by increasing `d` (the one at the threshold under the held
    /// criterion, the whole search under the released one).
    pub released_evaluations: Vec<ReleasedCrease>,
    /// Under the released criterion: whether just below the threshold the fold reopens to the
    /// flat state, so that the equilibrium crease appears already paying off (rather than
    /// passing through `U = U_flat`).
    pub appears_paying: bool,
}

impl FoldThreshold {
    /// The entry of a fold that was not computed on a mesh of the sequence.
    pub fn not_computed(fold_length: f64) -> Self {
        FoldThreshold {
            fold_length,
            d_threshold: None,
            d_held: None,
            evaluations: Vec::new(),
            stopped: Some("not computed on this mesh".into()),
            released: None,
            release_error: None,
            released_evaluations: Vec::new(),
            appears_paying: false,
        }
    }

    /// The deformed depth of the crease at the threshold: the held fold's, or the released
    /// crease's under the released criterion.
    pub fn depth_at_threshold(&self, criterion: Criterion) -> Option<f64> {
        match criterion {
            Criterion::Held => self.at_threshold().map(|e| e.depth),
            Criterion::Released => self.released.as_ref().map(|r| r.depth),
        }
    }

    /// The evaluation closest to `d`.
    pub fn nearest(&self, d: f64) -> Option<&CreaseEnergy> {
        self.evaluations
            .iter()
            .min_by(|x, y| (x.strain - d).abs().total_cmp(&(y.strain - d).abs()))
    }

    /// The evaluation at the threshold (the nearest one).
    pub fn at_threshold(&self) -> Option<&CreaseEnergy> {
        self.d_threshold.and_then(|d| self.nearest(d))
    }

    /// The largest `d` at which the fold was evaluated (the crease does not pay off below it
    /// when no threshold was found).
    pub fn cleared(&self) -> f64 {
        self.evaluations.iter().map(|e| e.strain).fold(0.0, f64::max)
    }
}

/// `d(a)` on `spec` by `criterion`: the held fold's scan, then Brent within its first sign
/// change, to `scan.tolerance`; then the fold released at that threshold, or the released
/// crease's own threshold searched from there.
pub fn fold_threshold(
    materials: &Bilayer,
    spec: MeshSpec,
    a: f64,
    scan: Scan,
    criterion: Criterion,
    tick: Tick,
) -> Result<FoldThreshold> {
    let mut fold = held_threshold(materials, spec, a, scan, tick)?;
    let Some(d) = fold.d_held else { return Ok(fold) };
    match criterion {
        Criterion::Held => {
            match released_crease(materials, spec, d, a) {
                Ok(r) => {
                    fold.released_evaluations.push(r.clone());
                    fold.released = Some(r);
                }
                Err(Error::Solver(m)) => fold.release_error = Some(m),
                Err(e) => return Err(e),
            }
            tick();
        }
        Criterion::Released => released_threshold(materials, spec, scan, &mut fold, tick)?,
    }
    Ok(fold)
}

/// The held fold's threshold on `spec` (nothing released yet).
fn held_threshold(materials: &Bilayer, spec: MeshSpec, a: f64, scan: Scan, tick: Tick) -> Result<FoldThreshold> {
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
                let previous = evaluations.last().map(|p| (p.strain, p.difference));
                let here = (d, e.difference);
                evaluations.push(e);
                tick();
                if pays {
                    bracket = previous.map(|lo| (lo, here));
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
        let root = brent_from(
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
            Err(e) => stopped = Some(format!("locating the sign change in [{:.4}, {:.4}]: {e}", lo.0, hi.0)),
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
        d_held: d_threshold,
        evaluations,
        stopped,
        released: None,
        release_error: None,
        released_evaluations: Vec::new(),
        appears_paying: false,
    })
}

/// A bracket of `d` with the energy difference at both ends.
type Bracket = ((f64, f64), (f64, f64));

/// After a failed fold at `failed`: up to three halvings of the interval from the last good
/// evaluation; a bracket if one of them pays off, else why the scan ends.
fn halve_towards(
    materials: &Bilayer,
    spec: MeshSpec,
    a: f64,
    evaluations: &mut Vec<CreaseEnergy>,
    mut failed: f64,
    mut why: String,
    tick: Tick,
) -> Result<(Option<Bracket>, String)> {
    let Some(mut lo) = evaluations.last().map(|e| (e.strain, e.difference)) else {
        return Ok((None, format!("no quasi-static fold at d = {failed:.4}: {why}")));
    };
    for _ in 0..3 {
        let mid = 0.5 * (lo.0 + failed);
        match crease_energy(materials, spec, mid, a) {
            Ok(e) => {
                let here = (mid, e.difference);
                let pays = e.difference <= 0.0;
                evaluations.push(e);
                tick();
                if pays {
                    return Ok((Some((lo, here)), String::new()));
                }
                lo = here;
            }
            Err(Error::Solver(m)) => (failed, why) = (mid, m),
            Err(e) => return Err(e),
        }
    }
    Ok((
        None,
        format!("no quasi-static fold at d = {failed:.4} (the crease has not paid off below it): {why}"),
    ))
}
