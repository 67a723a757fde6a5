//! Newton's method with the multipliers of the mixed element's augmented mode
//! ([`crate::fem::mixed`]): the method of multipliers around Newton's iteration.

use super::{Newton, NewtonError, NewtonReport};
use crate::error::Error;
use crate::fem::added::AddedEnergy;
use crate::fem::assembly::System;
use crate::fem::boundary::Dirichlet;

/// Largest violation `|M^-1 g - lambda / K|` accepted (the element-mean `ln J` and its
/// gradient under the constraint `K = inf`; [`crate::fem::mixed`]).
pub const CONSTRAINT_TOLERANCE: f64 = 1e-7;

/// Most updates of the multipliers in one solve.
const MULTIPLIER_UPDATES: usize = 30;

/// Largest relaxation of a multiplier update.
const MAX_RELAXATION: f64 = 100.0;

/// Largest factor on the incompressibility penalty while the multipliers converge.
const MAX_PENALTY_SCALE: f64 = 1e3;

impl NewtonReport {
    /// This solve continued by `next` (after an update of the multipliers): counts and times
    /// add up, the solution is `next`'s.
    fn followed_by(self, next: NewtonReport) -> NewtonReport {
        let mut residual_history = self.residual_history;
        residual_history.extend(next.residual_history);
        NewtonReport {
            iterations: self.iterations + next.iterations,
            tangent_steps: self.tangent_steps + next.tangent_steps,
            residual_history,
            backtracks: self.backtracks + next.backtracks,
            multiplier_updates: self.multiplier_updates + 1,
            start_negative_pivots: self.start_negative_pivots,
            timings: self.timings + next.timings,
            ..next
        }
    }
}

impl Newton {
    /// Newton's iteration; for exactly incompressible tissue, repeated after each update of the
    /// multipliers (the method of multipliers, [`crate::fem::mixed`]) until the constraint holds
    /// to [`CONSTRAINT_TOLERANCE`]. The updates are relaxed by Irons and Tuck's form of
    /// Aitken's acceleration: the iteration converges linearly, slowly where the pressure is
    /// weakly controlled (elongated or strongly distorted elements), and one extrapolation
    /// removes that slow mode; an update that does not halve the violation raises the penalty
    /// tenfold instead (up to [`MAX_PENALTY_SCALE`], reset by [`Newton::solve_with`]), and
    /// Newton's tolerance with it, since the residual's round-off grows in proportion.
    pub(super) fn iterate_with_multipliers(
        &mut self,
        system: &mut System,
        u: &mut [f64],
        bc: &Dirichlet,
        added: &dyn AddedEnergy,
    ) -> Result<NewtonReport, NewtonError> {
        let mut report = self.iterate(system, u, bc, added)?;
        let offset = system.mesh().num_dofs();
        let (mut previous, mut relaxation): (Option<(f64, Vec<f64>)>, f64) = (None, 1.0);
        for _ in 0..MULTIPLIER_UPDATES {
            let Some((violation, change)) = system.multiplier_step(u)? else {
                return Ok(report);
            };
            if violation <= CONSTRAINT_TOLERANCE {
                return Ok(report);
            }
            match &previous {
                Some((last, _)) if violation > 0.5 * last && system.penalty_scale() < MAX_PENALTY_SCALE => {
                    // Slow: a stiffer penalty, and Aitken's relaxation restarts.
                    system.set_penalty_scale(10.0 * system.penalty_scale());
                    relaxation = 1.0;
                }
                Some((_, last_change)) => {
                    // omega_(n+1) = -omega_n (D_n . (D_(n+1) - D_n)) / |D_(n+1) - D_n|^2.
                    let difference: Vec<f64> = change.iter().zip(last_change).map(|(a, b)| a - b).collect();
                    let denominator = difference.iter().map(|x| x * x).sum::<f64>();
                    if denominator > 0.0 {
                        let numerator = last_change.iter().zip(&difference).map(|(a, b)| a * b).sum::<f64>();
                        relaxation = (-relaxation * numerator / denominator).clamp(0.5, MAX_RELAXATION);
                    }
                }
                None => {}
            }
            for (lambda, delta) in u[offset..].iter_mut().zip(&change) {
                *lambda += relaxation * delta;
            }
            previous = Some((violation, change));
            let next = self.iterate(system, u, bc, added)?;
            report = report.followed_by(next);
        }
        let violation = system.multiplier_step(u)?.map_or(0.0, |(v, _)| v);
        Err(NewtonError::Model(Error::Solver(format!(
            "incompressibility: |ln J| = {violation:.1e} after {MULTIPLIER_UPDATES} updates of the pressure"
        ))))
    }
}
