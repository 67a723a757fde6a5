//! The continuation's steps taken by minimising the energy at fixed `d` instead of by Newton's
//! iteration ([`crate::fem::equilibrium::minimise`], a trust-region Newton method that ends at a
//! local minimum):
//!
//! - a snap ([`Continuation::snap`]), where the followed branch has no nearby equilibrium: from
//!   the last equilibrium with the boundary moved to `d`;
//! - a step on a stable branch in contact whose Newton correction failed
//!   ([`Continuation::attempt_by_minimisation`]): from the predictor. Where a contact pair
//!   closes or opens within a step, the equations have a kink (the pair's pressure switches
//!   on), on which Newton's iteration, whose line search measures the residual, may cycle
//!   while the energy, smooth to first order, still has its minimum next to the predictor.
//!   Measured on the fine Fig. 7 run: 36 of its 39 snaps had released between -3e-6 and 6e-6
//!   with `A` unchanged to 1e-4, each after the step had been cut five or six times down to
//!   `1e-6`.

use super::{Augmenting, Continuation, Event, Followed, Solved};
use crate::error::{Error, Result};
use crate::fem::newton::largest_move;
use crate::fem::{Dirichlet, NewtonPolicy, NewtonReport};
use crate::protocol::augmentation::AugmentedRecord;
use crate::protocol::snap::SnapRecord;
use std::time::Instant;

/// Most restarts of a minimisation from a minimum that the last contact update left with a
/// negative eigenvalue.
const MAX_RESTARTS: usize = 4;

/// Most steps of a minimisation standing in for a failed Newton correction: one that needs
/// more is leaving the branch (measured: the minima next to the predictor took 2 to 19 steps,
/// one 50; the fold's snap 403).
const CORRECTOR_STEPS: usize = 30;

/// Largest move of a minimisation standing in for a failed Newton correction from the
/// predictor, relative to the predictor's own move from the last state: beyond it, the
/// minimum reached is not the branch's continuation but a snap, to be located by the step
/// control and taken from the branch's last equilibrium.
const CORRECTOR_REACH: f64 = 1.0;

/// Smallest reach of that minimisation, in units of the layer thickness: right after a snap
/// the predictor is the last state itself, whose move is the boundary's alone.
const CORRECTOR_FLOOR: f64 = 1e-3;

impl<S: Followed> Continuation<S> {
    /// The snap at `d`: the stable equilibrium there reached by minimising the energy from the
    /// last equilibrium with the boundary moved to `d` ([`crate::protocol::snap`]); fails if the
    /// minimum reached is not stable (after the outer loops' updates).
    pub(super) fn snap(&mut self, d: f64) -> Result<(Solved, SnapRecord)> {
        self.minimum_from_last(d, None)
    }

    /// The stable minimum of the energy at `d` from the last equilibrium with the boundary moved
    /// to `d` and, if given, moved by `perturbation` too; recorded as a snap from it (the energy
    /// released is measured from the unperturbed start).
    fn minimum_from_last(&mut self, d: f64, perturbation: Option<&[f64]>) -> Result<(Solved, SnapRecord)> {
        let started = Instant::now();
        let (d0, u0) = self.history.back().expect("never empty").clone();
        let before = self.system.load_to(d0)?;
        let energy_before = self.energy(&u0, &before)?;
        let bc = self.system.load_to(d)?;
        let mut u = u0.clone();
        bc.impose(&mut u);
        let energy_start = self.energy(&u, &bc)?;
        if let Some(perturbation) = perturbation {
            u.iter_mut().zip(perturbation).for_each(|(a, b)| *a += b);
            bc.impose(&mut u);
        }
        let policy = NewtonPolicy {
            inertia_at_solution: true,
            ..self.policy
        };
        let (report, augmented) = self.stable_minimum(&mut u, (&bc, d), &policy)?;
        let energy_after = self.energy(&u, &bc)?;
        let snap = SnapRecord {
            d,
            d_before: d0,
            amplitude_before: self.system.amplitude(&u0),
            energy_before,
            energy_start,
            amplitude_after: self.system.amplitude(&u),
            energy_after,
            energy_released: energy_start - energy_after,
            negative_pivots_after: report.negative_pivots,
            steps: report.iterations,
            factorisations: report.timings.factorisations,
            seconds: started.elapsed().as_secs_f64(),
        };
        Ok(((report, u, augmented), snap))
    }

    /// Leaves the current state, an unstable equilibrium, for the stable one the structure
    /// goes to at the same `d`: the energy minimised from the state moved by `perturbation`
    /// (all unknowns; along an unstable direction of its tangent), reported like a snap, from
    /// which the path goes on (its predictor restarts there). Fails if the minimum reached is
    /// not stable.
    pub fn leave_unstable_state(
        &mut self,
        perturbation: &[f64],
        observer: &mut dyn FnMut(Event<'_, S>) -> Result<()>,
    ) -> Result<()> {
        let d = self.d();
        let ((report, u, augmented), snap) = self.minimum_from_last(d, Some(perturbation))?;
        let clock = super::StepClock::start();
        self.unstable_states_left += 1;
        self.accept(
            (d, 0.0),
            ((report, u, augmented), super::Reached::Snap(snap)),
            &clock,
            observer,
        )
    }

    /// The step to `d` whose Newton correction failed, corrected by minimising the energy
    /// from the predictor instead, when the last state is stable and in contact: the minimum
    /// reached if it is stable, took at most [`CORRECTOR_STEPS`] steps, and lies within
    /// [`CORRECTOR_REACH`] times the predictor's move (at least [`CORRECTOR_FLOOR`]) of the
    /// predictor. `None` otherwise (the step is then cut as before).
    pub(super) fn attempt_by_minimisation(&mut self, d: f64) -> Option<Solved> {
        if !(self.last.stable && self.last.in_contact) {
            return None;
        }
        let bc = self.system.load_to(d).ok()?;
        let mut u = self.predict(d);
        bc.impose(&mut u);
        let predictor = u.clone();
        let saved = self.augmentation.as_ref().map(Augmenting::save);
        let n = self.system.displacement_unknowns();
        let u0 = &self.history.back().expect("never empty").1;
        let reach = (CORRECTOR_REACH * largest_move(&predictor, u0, n)).max(CORRECTOR_FLOOR);
        // A minimisation heading beyond the reach stops there (it would be discarded).
        let policy = NewtonPolicy {
            inertia_at_solution: true,
            max_minimisation_steps: CORRECTOR_STEPS,
            max_move: Some(reach),
            ..self.policy
        };
        let (report, augmented) = self.stable_minimum(&mut u, (&bc, d), &policy).ok()?;
        if largest_move(&u, &predictor, n) > reach {
            if let (Some(augmentation), Some(saved)) = (&mut self.augmentation, saved) {
                augmentation.restore(saved);
            }
            return None;
        }
        Some((report, u, augmented))
    }

    /// A minimum of the energy at `d` (prescribed by `bc`) from `u`, with contact if the
    /// continuation has it, minimised on (at most [`MAX_RESTARTS`] times) while the last
    /// contact update leaves it with a negative eigenvalue; fails unless it ends stable.
    fn stable_minimum(
        &mut self,
        u: &mut [f64],
        (bc, d): (&Dirichlet, f64),
        policy: &NewtonPolicy,
    ) -> Result<(NewtonReport, Option<AugmentedRecord>)> {
        let (mut report, mut augmented) = self.minimise(u, (bc, d), policy)?;
        // The last contact update (the multipliers at the minimum) may leave a barely stable
        // minimum with a negative eigenvalue: the minimisation goes on from there.
        for _ in 0..MAX_RESTARTS {
            if report.negative_pivots == Some(0) {
                break;
            }
            let (again, record) = self.minimise(u, (bc, d), policy)?;
            report = report.followed_by(again);
            augmented = record;
        }
        if report.negative_pivots != Some(0) {
            return Err(Error::Solver(format!(
                "the minimum reached at d = {d:.6} has {:?} negative eigenvalues after the contact updates",
                report.negative_pivots
            )));
        }
        Ok((report, augmented))
    }

    /// One minimisation of the energy at `d` from `u`, with contact if the continuation has it.
    fn minimise(
        &mut self,
        u: &mut [f64],
        (bc, d): (&Dirichlet, f64),
        policy: &NewtonPolicy,
    ) -> Result<(NewtonReport, Option<AugmentedRecord>)> {
        self.system
            .minimise(&mut self.newton, policy, u, (bc, d), self.augmentation.as_mut())
    }

    /// The total energy (strain plus contact) at `u` with `bc` prescribed.
    fn energy(&mut self, u: &[f64], bc: &Dirichlet) -> Result<f64> {
        self.system.energy(u, bc, self.augmentation.as_ref())
    }
}
