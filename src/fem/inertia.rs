//! The inertia of tangents counted on a second thread: the factorisation that only counts the
//! negative pivots of an accepted state (where Newton's own factorisation is of another
//! matrix, e.g. the damped one) runs while the main thread goes on with the next load step.
//!
//! At most one count runs at a time (a new one first waits for the running one), so a run
//! holds at most two factors, Newton's and this one, and this one only while it counts. Its
//! solver shares the symbolic analysis of Newton's and is kept from count to count without its
//! factor (freed after each count) until [`BackgroundInertia::release`]. Counts come back in the
//! order the tangents were given.

use super::{Assembled, SparseLdlt};
use std::collections::VecDeque;
use std::thread::JoinHandle;

/// A solver with the structure id of the matrices it was made for.
type Keyed = (usize, SparseLdlt);

/// Counts of negative pivots, computed in the background, returned in order.
#[derive(Default)]
pub struct BackgroundInertia {
    running: Option<JoinHandle<(usize, Keyed)>>,
    done: VecDeque<usize>,
    kept: Option<Keyed>,
}

impl std::fmt::Debug for BackgroundInertia {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("BackgroundInertia")
            .field("running", &self.running.is_some())
            .field("done", &self.done)
            .finish()
    }
}

impl BackgroundInertia {
    /// Starts counting the negative eigenvalues of `assembled`'s tangent (which must hold
    /// one), after the running count if any. `sibling` gives a solver sharing an analysis of
    /// the given structure, if one is at hand (otherwise the count analyses the pattern).
    pub fn start(&mut self, assembled: Assembled, sibling: impl FnOnce(usize) -> Option<SparseLdlt>) {
        self.finish();
        let structure = assembled.structure;
        let tangent = assembled.tangent.expect("assembled with the tangent");
        // A kept solver of another structure is freed before another one is made.
        let kept = match self.kept.take() {
            Some((id, solver)) if id == structure => Some(solver),
            _ => None,
        };
        let solver = kept.or_else(|| sibling(structure));
        self.running = Some(std::thread::spawn(move || {
            let mut solver = solver.unwrap_or_else(|| SparseLdlt::new(tangent.symbolic()));
            solver.factorize(tangent.as_ref());
            let count = solver.negative_pivots().expect("just factorised");
            solver.free_factor();
            (count, (structure, solver))
        }));
    }

    /// The oldest count not yet taken (waiting for it if it is still running), or `None` if
    /// none was started.
    pub fn next_count(&mut self) -> Option<usize> {
        if self.done.is_empty() {
            self.finish();
        }
        self.done.pop_front()
    }

    /// Waits for the running count, if any.
    pub fn finish(&mut self) {
        if let Some(running) = self.running.take() {
            let (count, kept) = running.join().expect("the inertia thread does not panic");
            self.done.push_back(count);
            self.kept = Some(kept);
        }
    }

    /// Waits for the running count and frees the kept solver (before a new analysis, or once
    /// the path is done).
    pub fn release(&mut self) {
        self.finish();
        self.kept = None;
    }
}
