//! The released criterion's `d(a)` on one mesh: where the crease that a fold of length `a`
//! closes to, once its nodes are let go to frictionless contact with the plane
//! ([`crate::protocol::crease_seed::held_and_released`]), has less energy than the flat state.
//! That crease is an equilibrium, the plane pushing wherever it touches, so the state compared
//! at the threshold is one the solid can rest in.
//!
//! The search starts at the held fold's threshold `d_h` and steps away from it, down if the
//! released crease pays off there and up if it does not, first by the scan's step (at most
//! [`FIRST_STEP`]), each step twice the last, until the verdict changes (not below
//! [`LOWEST`], not above [`HIGHEST`]: the scan's range bounds the held fold's search, not this
//! one, since on a finer mesh it is a window around the last threshold). Below the threshold the fold may reopen to
//! the flat state, where `U_released - U_flat` has no crease to measure: the bracket is halved
//! while its lower end reopens, then Brent's method locates the sign change of
//! `U_released - U_flat` between two closed creases to the scan's tolerance. If the lower end
//! still reopens at that width, the crease appears already paying off: the threshold is the
//! bracket's upper end.

use super::fold::FoldThreshold;
use super::Scan;
use crate::error::{Error, Result};
use crate::material::Bilayer;
use crate::mesh::MeshSpec;
use crate::numerics::roots::brent_from;
use crate::protocol::crease_seed::{held_and_released, CreaseEnergy, ReleasedCrease};
use crate::studies::Tick;

/// The largest first step of the search away from the held fold's threshold.
const FIRST_STEP: f64 = 0.01;

/// The lowest `d` the search may reach.
const LOWEST: f64 = 0.01;

/// The highest `d` the search may reach.
const HIGHEST: f64 = 0.95;

/// Whether the released crease pays off: it stayed closed, below the flat state's energy.
fn pays(r: &ReleasedCrease) -> bool {
    !r.reopened && r.difference < 0.0
}

/// The evaluations of one search.
struct Search<'a> {
    materials: &'a Bilayer,
    spec: MeshSpec,
    a: f64,
    held: Vec<CreaseEnergy>,
    released: Vec<ReleasedCrease>,
    tick: Tick<'a>,
}

impl Search<'_> {
    /// The fold of `a` at `d`, held then released; `Err(why)` where it cannot be folded or
    /// released (a snap).
    fn at(&mut self, d: f64) -> Result<std::result::Result<ReleasedCrease, String>> {
        let evaluated = held_and_released(self.materials, self.spec, d, self.a);
        (self.tick)();
        match evaluated {
            Ok((held, released)) => {
                self.held.push(held);
                self.released.push(released.clone());
                Ok(Ok(released))
            }
            Err(Error::Solver(why)) => Ok(Err(why)),
            Err(e) => Err(e),
        }
    }
}

/// A bracket end: `d` and the released crease there.
type End = (f64, ReleasedCrease);

/// Replaces `fold`'s threshold (the held fold's, `fold.d_held`) with the released crease's,
/// searched as the module says; adds the evaluations to `fold`. A search that cannot finish
/// leaves no threshold and says why in `fold.stopped`.
pub(super) fn released_threshold(
    materials: &Bilayer,
    spec: MeshSpec,
    scan: Scan,
    fold: &mut FoldThreshold,
    tick: Tick,
) -> Result<()> {
    let d_held = fold.d_held.expect("a held threshold to start from");
    let mut search = Search {
        materials,
        spec,
        a: fold.fold_length,
        held: Vec::new(),
        released: Vec::new(),
        tick,
    };
    let outcome = locate(&mut search, scan, d_held)?;
    fold.evaluations.append(&mut search.held);
    fold.evaluations.sort_by(|x, y| x.strain.total_cmp(&y.strain));
    search.released.sort_by(|x, y| x.strain.total_cmp(&y.strain));
    fold.released_evaluations = search.released;
    match outcome {
        Ok((d, appears_paying)) => {
            fold.d_threshold = Some(d);
            fold.appears_paying = appears_paying;
            fold.released = fold
                .released_evaluations
                .iter()
                .min_by(|x, y| (x.strain - d).abs().total_cmp(&(y.strain - d).abs()))
                .cloned();
        }
        Err(why) => {
            fold.d_threshold = None;
            fold.stopped = Some(why);
        }
    }
    Ok(())
}

/// The threshold and whether the crease appears already paying off; `Err(why)` if the search
/// cannot finish.
fn locate(search: &mut Search, scan: Scan, d_held: f64) -> Result<std::result::Result<(f64, bool), String>> {
    let mut step = scan.step.min(FIRST_STEP);
    let released = |d: f64, r: std::result::Result<ReleasedCrease, String>| {
        r.map(|r| (d, r))
            .map_err(|why| format!("the fold released at d = {d:.5} has no quasi-static path: {why}"))
    };
    let start = match released(d_held, search.at(d_held)?) {
        Ok(start) => start,
        Err(why) => return Ok(Err(why)),
    };
    let (mut lo, mut hi): (End, End);
    if pays(&start.1) {
        hi = start;
        loop {
            if hi.0 <= LOWEST {
                return Ok(Err(format!("the released crease already pays off at d = {LOWEST}")));
            }
            let d = (hi.0 - step).max(LOWEST);
            step *= 2.0;
            match released(d, search.at(d)?) {
                Ok(end) if pays(&end.1) => hi = end,
                Ok(end) => {
                    lo = end;
                    break;
                }
                Err(why) => return Ok(Err(why)),
            }
        }
    } else {
        lo = start;
        loop {
            if lo.0 >= HIGHEST {
                return Ok(Err(format!(
                    "the released crease does not pay off up to d = {HIGHEST} (the held fold does from {d_held:.5})"
                )));
            }
            let d = (lo.0 + step).min(HIGHEST);
            step *= 2.0;
            match released(d, search.at(d)?) {
                Ok(end) if pays(&end.1) => {
                    hi = end;
                    break;
                }
                Ok(end) => lo = end,
                Err(why) => return Ok(Err(why)),
            }
        }
    }
    while lo.1.reopened && hi.0 - lo.0 > scan.tolerance {
        let d = 0.5 * (lo.0 + hi.0);
        match released(d, search.at(d)?) {
            Ok(end) if pays(&end.1) => hi = end,
            Ok(end) => lo = end,
            Err(why) => return Ok(Err(why)),
        }
    }
    if lo.1.reopened {
        return Ok(Ok((hi.0, true)));
    }
    let root = brent_from(
        "the energy of the released crease minus that of the flat state",
        |d| match search.at(d)? {
            Ok(r) if r.reopened => Err(Error::Solver(format!(
                "the released crease reopens at d = {d:.5}, between closed creases"
            ))),
            Ok(r) => Ok(r.difference),
            Err(why) => Err(Error::Solver(why)),
        },
        (lo.0, lo.1.difference),
        (hi.0, hi.1.difference),
        scan.tolerance,
    );
    Ok(match root {
        Ok(d) => Ok((d, false)),
        Err(e) => Err(format!(
            "locating the released crease's sign change in [{:.5}, {:.5}]: {e}",
            lo.0, hi.0
        )),
    })
}
