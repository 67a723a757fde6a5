//! What a Newton solve reports: the converged state's data and the wall times of its phases,
//! or why it failed.

use crate::error::Error;
use std::time::Duration;

impl std::ops::Add for Timings {
    type Output = Timings;

    /// The times and counts of two solves together.
    fn add(self, other: Timings) -> Timings {
        Timings {
            assembly: self.assembly + other.assembly,
            analysis: self.analysis + other.analysis,
            factorisation: self.factorisation + other.factorisation,
            solve: self.solve + other.solve,
            assemblies: self.assemblies + other.assemblies,
            factorisations: self.factorisations + other.factorisations,
            solves: self.solves + other.solves,
        }
    }
}

/// Accumulated wall times of the phases of one solve, and how often each ran.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Timings {
    /// Assemblies (residual and tangent).
    pub assembly: Duration,
    /// Symbolic analyses (once per sparsity pattern).
    pub analysis: Duration,
    /// Numeric factorisations.
    pub factorisation: Duration,
    /// Triangular solves.
    pub solve: Duration,
    /// Number of assemblies.
    pub assemblies: usize,
    /// Number of numeric factorisations.
    pub factorisations: usize,
    /// Number of solves.
    pub solves: usize,
}

/// A converged solve.
#[derive(Clone, Debug)]
pub struct NewtonReport {
    /// Newton steps taken (with a reused factorisation or a new one).
    pub iterations: usize,
    /// Of those, steps with a newly factorised tangent.
    pub tangent_steps: usize,
    /// `|r_f|` at the start and after every step (lifted while the prescribed values are reached).
    pub residual_history: Vec<f64>,
    /// Internal-force norm `|f|` at the solution (the scale of the relative residual).
    pub force_norm: f64,
    /// Strain energy at the solution.
    pub energy: f64,
    /// Smallest `J` at the solution.
    pub min_jacobian: f64,
    /// Reactions on the prescribed unknowns, in the order of `Dirichlet::dofs`.
    pub reactions: Vec<f64>,
    /// Negative eigenvalues of `K_ff` at the solution, if the policy asked for them.
    pub negative_pivots: Option<usize>,
    /// Negative eigenvalues of `K_ff` at the starting iterate, if it was factorised.
    pub start_negative_pivots: Option<usize>,
    /// Total number of step halvings.
    pub backtracks: usize,
    /// Updates of the outer loops, each followed by another Newton solve.
    pub updates: Updates,
    /// Wall times of the phases.
    pub timings: Timings,
    /// A minimisation that stopped after its largest move ([`super::NewtonPolicy::max_pass_move`]):
    /// lower in energy than its start but not yet a minimum, nor an equilibrium.
    pub unfinished: bool,
    /// The shift `sigma` a minimisation ended with (see [`super::NewtonPolicy::initial_shift`]);
    /// zero for Newton's iteration.
    pub final_shift: f64,
}

/// How often each outer loop around Newton's iteration updated its unknowns and solved again
/// ([`crate::fem::equilibrium`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Updates {
    /// Updates of the mixed element's multipliers (the incompressibility pressure).
    pub pressure: usize,
    /// Updates of the contact pairs and their multipliers.
    pub contact: usize,
}

impl NewtonReport {
    /// This solve continued by `next`, another solve after an update: counts and times add
    /// up, the residual histories join, and the solution is `next`'s.
    pub fn followed_by(self, next: NewtonReport) -> NewtonReport {
        let mut residual_history = self.residual_history;
        residual_history.extend(next.residual_history);
        NewtonReport {
            iterations: self.iterations + next.iterations,
            tangent_steps: self.tangent_steps + next.tangent_steps,
            residual_history,
            backtracks: self.backtracks + next.backtracks,
            updates: Updates {
                pressure: self.updates.pressure + next.updates.pressure,
                contact: self.updates.contact + next.updates.contact,
            },
            start_negative_pivots: self.start_negative_pivots,
            timings: self.timings + next.timings,
            ..next
        }
    }
}

/// Why Newton's method failed; the displacement is then left as it was.
#[derive(Debug, thiserror::Error)]
pub enum NewtonError {
    /// The state, or every step tried, has no finite energy: an element inverted (`J <= 0`)
    /// or a law beyond its domain.
    #[error("Newton iteration {iteration}: {reason}")]
    Inadmissible { iteration: usize, reason: String },
    /// No step length down to `2^-max_backtracks` decreases the residual.
    #[error("Newton iteration {iteration}: line search found no decrease of the residual {residual:.3e}")]
    LineSearch { iteration: usize, residual: f64 },
    /// The iteration limit was reached.
    #[error("Newton did not converge in {iterations} iterations (residual {residual:.3e}, tolerance {tolerance:.3e})")]
    NotConverged {
        iterations: usize,
        residual: f64,
        tolerance: f64,
        residual_history: Vec<f64>,
    },
    /// Any other failure (bad input, singular tangent).
    #[error(transparent)]
    Model(#[from] Error),
}

impl From<NewtonError> for Error {
    /// Model errors pass through; convergence failures become [`Error::Solver`].
    fn from(e: NewtonError) -> Self {
        match e {
            NewtonError::Model(inner) => inner,
            other => Error::Solver(other.to_string()),
        }
    }
}
