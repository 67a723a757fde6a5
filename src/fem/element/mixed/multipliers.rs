//! The method of multipliers for the mixed element's augmented mode ([`super`]), as an outer
//! loop around Newton's iteration ([`crate::fem::equilibrium`]): after each converged solve the
//! multipliers move to the elements' pressures, until the constraint holds to
//! [`CONSTRAINT_TOLERANCE`].
//!
//! The updates are relaxed by Irons and Tuck's form of Aitken's acceleration: the iteration
//! converges linearly, slowly where the pressure is weakly controlled (elongated or strongly
//! distorted elements), and one extrapolation removes that slow mode. An update that does not
//! halve the violation raises the penalty tenfold instead (up to [`MAX_PENALTY_SCALE`]), and
//! Newton's tolerance with it, since the residual's round-off grows in proportion.

use crate::error::Error;
use crate::fem::element::Registry;
use crate::fem::equilibrium::{Check, Update};
use crate::fem::newton::{NewtonError, Updates};
use crate::fem::System;
use crate::mesh::ElementKind;

/// Violation `|M^-1 g - lambda / K|` (the element-mean `ln J` and its gradient under the
/// constraint `K = inf`; [`super`]) at which the multipliers have converged. The state's error
/// goes with it, and the stability tangent's smallest eigenvalues with that: at 1e-7 the count
/// of negative pivots of a contrast-100 bilayer flickered 0/1 over 0.005 in d about its period
/// doubling, and the path found a false secondary mode; at 1e-10 it changes once, in the same
/// step as the nearly incompressible bilayer's.
pub const CONSTRAINT_TOLERANCE: f64 = 1e-10;

/// Largest violation accepted where the updates stop gaining (an update at the largest
/// penalty that does not halve it, or [`POLISHING_UPDATES`] updates below it): round-off and
/// contact can hold the iteration above [`CONSTRAINT_TOLERANCE`], where failing the solve would
/// cut the step for nothing.
pub const ACCEPTED_VIOLATION: f64 = 1e-7;

/// Most updates of the multipliers once the violation is below [`ACCEPTED_VIOLATION`].
const POLISHING_UPDATES: usize = 10;

/// Most updates of the multipliers in one solve.
const MULTIPLIER_UPDATES: usize = 30;

/// Largest relaxation of a multiplier update.
const MAX_RELAXATION: f64 = 100.0;

/// Largest factor on the incompressibility penalty while the multipliers converge.
const MAX_PENALTY_SCALE: f64 = 1e3;

/// The state of the method of multipliers during one equilibrium solve.
pub struct PressureUpdate {
    /// The factor on the constraint's penalty of the next solve.
    penalty_scale: f64,
    /// The last update's violation and change of the multipliers.
    previous: Option<(f64, Vec<f64>)>,
    /// Aitken's relaxation of the next update.
    relaxation: f64,
    /// The violation at the last converged state.
    violation: f64,
    /// Updates made with the violation below [`ACCEPTED_VIOLATION`].
    polishing: usize,
}

impl PressureUpdate {
    /// The start of a solve: the penalty as the element sets it, no update yet.
    pub fn new() -> Self {
        PressureUpdate {
            penalty_scale: 1.0,
            previous: None,
            relaxation: 1.0,
            violation: 0.0,
            polishing: 0,
        }
    }

    /// The factor on the constraint's penalty for the next Newton solve.
    pub fn penalty_scale(&self) -> f64 {
        self.penalty_scale
    }
}

impl Default for PressureUpdate {
    fn default() -> Self {
        PressureUpdate::new()
    }
}

impl<const D: usize, const N: usize, const Q: usize, const U: usize> Update<System<D, N, Q, U>> for PressureUpdate
where
    ElementKind: Registry<D, N, Q, U>,
{
    fn max_updates(&self) -> usize {
        MULTIPLIER_UPDATES
    }

    /// Accepted without multipliers, once the violation is within tolerance, or within the
    /// accepted violation where updates stop gaining; otherwise the multipliers take the relaxed
    /// step towards the pressures (or, if the last update did not halve the violation, the
    /// penalty is raised tenfold and the relaxation restarts).
    fn update(&mut self, system: &System<D, N, Q, U>, u: &mut [f64]) -> Result<Check, NewtonError> {
        let Some((violation, change)) = system.multiplier_step(u, self.penalty_scale)? else {
            return Ok(Check::Accepted);
        };
        self.violation = violation;
        if violation <= CONSTRAINT_TOLERANCE {
            return Ok(Check::Accepted);
        }
        let slow = self.previous.as_ref().is_some_and(|(last, _)| violation > 0.5 * last);
        if violation <= ACCEPTED_VIOLATION {
            if (slow && self.penalty_scale >= MAX_PENALTY_SCALE) || self.polishing == POLISHING_UPDATES {
                return Ok(Check::Accepted);
            }
            self.polishing += 1;
        }
        match &self.previous {
            Some(_) if slow && self.penalty_scale < MAX_PENALTY_SCALE => {
                // Slow: a stiffer penalty, and Aitken's relaxation restarts.
                self.penalty_scale *= 10.0;
                self.relaxation = 1.0;
            }
            Some((_, last_change)) => {
                // omega_(n+1) = -omega_n (D_n . (D_(n+1) - D_n)) / |D_(n+1) - D_n|^2.
                let difference: Vec<f64> = change.iter().zip(last_change).map(|(a, b)| a - b).collect();
                let denominator = difference.iter().map(|x| x * x).sum::<f64>();
                if denominator > 0.0 {
                    let numerator = last_change.iter().zip(&difference).map(|(a, b)| a * b).sum::<f64>();
                    self.relaxation = (-self.relaxation * numerator / denominator).clamp(0.5, MAX_RELAXATION);
                }
            }
            None => {}
        }
        let offset = system.mesh().num_dofs();
        for (lambda, delta) in u[offset..].iter_mut().zip(&change) {
            *lambda += self.relaxation * delta;
        }
        self.previous = Some((violation, change));
        Ok(Check::Updated)
    }

    fn count(&self, updates: &mut Updates) {
        updates.pressure += 1;
    }

    fn exhausted(&self) -> NewtonError {
        NewtonError::Model(Error::Solver(format!(
            "incompressibility: |ln J| = {:.1e} after {MULTIPLIER_UPDATES} updates of the pressure",
            self.violation
        )))
    }
}
