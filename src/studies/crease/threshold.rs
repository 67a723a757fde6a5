//! `d(a)` on one mesh: `U_crease - U_flat` is scanned upwards in `d` until it changes sign, then
//! Brent's method locates the root inside that first bracket, from the two values the scan
//! already has. Past the threshold the seeded fold may snap to a deeper crease (no quasi-static
//! path): a failed fold halves the interval from the last good `d` up to three times, and
//! otherwise ends the scan of that `a`, saying where.

use super::Scan;
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
    /// Where `U_crease - U_flat` changes sign (None: not within the scan).
    pub d_threshold: Option<f64>,
    pub evaluations: Vec<CreaseEnergy>,
    /// Why the scan ended early, if it did (e.g. the fold snapped).
    pub stopped: Option<String>,
    /// The fold at the threshold let go to contact with the plane: whether it stays closed,
    /// over what length, and with the plane pushing everywhere it touches.
    pub released: Option<ReleasedCrease>,
    /// Why the release at the threshold failed, if it did.
    pub release_error: Option<String>,
}

impl FoldThreshold {
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

/// `d(a)` on `spec`: the scan, then Brent within its first sign change, to `scan.tolerance`.
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
    let (mut released, mut release_error) = (None, None);
    if let Some(d) = d_threshold {
        match released_crease(materials, spec, d, a) {
            Ok(r) => released = Some(r),
            Err(Error::Solver(m)) => release_error = Some(m),
            Err(e) => return Err(e),
        }
        tick();
    }
    Ok(FoldThreshold {
        fold_length: a,
        d_threshold,
        evaluations,
        stopped,
        released,
        release_error,
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
