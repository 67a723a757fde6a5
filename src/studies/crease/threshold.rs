//! `d(a)` on one mesh: `U_crease - U_flat` of the held fold is scanned upwards in `d` until it
//! changes sign, then Brent's method locates the root inside that first bracket, from the two
//! values the scan already has. Past the threshold the seeded fold may snap to a deeper crease
//! (no quasi-static path): a failed fold halves the interval from the last good `d` up to three
//! times, and otherwise ends the scan of that `a`, saying where. Under the released criterion
//! the search goes on from the held fold's threshold (`super::released`).

use super::fold::FoldThreshold;
use super::{released::released_threshold, Criterion, Scan};
use crate::error::{Error, Result};
use crate::material::Bilayer;
use crate::mesh::MeshSpec;
use crate::numerics::roots::brent_from;
use crate::protocol::crease_seed::{crease_energy, released_crease, CreaseEnergy};
use crate::studies::Tick;

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
        seconds: 0.0,
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
