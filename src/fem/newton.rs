//! Full Newton's method with the consistent tangent and a backtracking line search.
//!
//! A call moves the prescribed unknowns from their current values to `bc`'s: the first steps
//! solve `K_ff du_f = -(r_f + K_fc du_c)` (the lifted, linearised system) and move both
//! `u_f` and `u_c`, halving the step only while it inverts an element; once `u_c` has reached its
//! values, steps must decrease `|r_f|` by the factor `1 - c alpha` (Armijo on the residual norm).
//! The line search starts at `alpha = 1`, or where the first term of an added energy switches on
//! along the step ([`AddedEnergy::switch_on_fraction`]): a contact pair that closes within the
//! step is not in the tangent, so the full step overshoots it by up to the step's length, and
//! halving back from 1 would cost several residual evaluations and a crawl of short steps.
//! Convergence: `|r_f| <= s (rtol |f| + atol)`, where `|f|` is the internal force on all unknowns
//! (reactions included) and `s` the factor on a raised incompressibility penalty (1 otherwise),
//! or an update `|alpha du|_inf <= utol (1 + |u|_inf)`. Trial points are
//! assembled without the tangent (first-order AD only); the tangent is assembled at an accepted
//! point only when another step follows (or its inertia is asked for).
//!
//! With `reuse_factorisation`, the last factorisation (of an earlier iterate, or of an earlier
//! solve of the same pattern) is kept as the iteration matrix while it contracts the residual by
//! at least `contraction` per step and is positive definite (modified Newton): such a step
//! costs one residual assembly and one solve instead of a tangent assembly and a
//! factorisation. With `reuse_indefinite`, an indefinite factorisation made in this solve is
//! kept too, while it contracts by `contraction^2` (about as a fresh tangent would). A step
//! that contracts less, or does not decrease `|r|`, falls back to the consistent tangent at the
//! current iterate, so the iteration is never worse than full Newton's; the converged state is
//! the same to the tolerances.
//!
//! With `factorise_start`, the tangent at the starting iterate (the predictor of a load step)
//! is factorised first, and the iteration starts with that factor: from a good predictor it
//! converges in two or three steps. Its inertia is reported (`start_negative_pivots`): the
//! caller may take it for the solution's where the predictor was close
//! ([`crate::protocol::augmentation`]).

use super::added::{AddedEnergy, NoAddedEnergy};
use super::assembly::{norm, Assembled, System};
use super::boundary::Dirichlet;
use super::linear_solver::{multiply, Factorisation, SparseLdlt};
use crate::error::Error;

mod multipliers;
mod report;
pub use multipliers::CONSTRAINT_TOLERANCE;
pub use report::{NewtonError, NewtonReport, Timings};

/// Tolerances and limits of Newton's method.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NewtonSettings {
    /// Largest number of Newton steps.
    pub max_iterations: usize,
    /// `rtol`: residual relative to the internal-force norm (keep it above the residual's round-off).
    pub residual_tolerance: f64,
    /// `atol`: absolute residual floor, for nearly unloaded states.
    pub absolute_tolerance: f64,
    /// `utol`: update relative to `1 + |u|_inf` below which the iterate no longer changes.
    pub update_tolerance: f64,
    /// Largest number of step halvings in one line search.
    pub max_backtracks: usize,
    /// Armijo constant `c` of the sufficient decrease `|r(u + alpha du)| <= (1 - c alpha) |r(u)|`.
    pub sufficient_decrease: f64,
    /// Relative residual of a linear solve above which `L B L^T` replaces `L D L^T`.
    pub solve_tolerance: f64,
    /// Whether to factorise the tangent at the solution to report its inertia.
    pub inertia_at_solution: bool,
    /// Whether to factorise the tangent at the starting iterate (the predictor) and start with it.
    pub factorise_start: bool,
    /// Whether a factorisation made in this solve is reused even if indefinite (for a step on
    /// a smooth stretch of an unstable path; not near a fold, where every step needs a fresh
    /// tangent).
    pub reuse_indefinite: bool,
    /// Whether to keep iterating with the last factorisation while it contracts the residual.
    pub reuse_factorisation: bool,
    /// Largest ratio `|r_(n+1)| / |r_n|` of a step with a reused factorisation for the next step to
    /// reuse it too; above it the tangent is refactorised.
    pub contraction: f64,
    /// Give up (as not converged) when, after this many tangent steps, `|r|` is still above
    /// both `stall_reduction` times its start and the geometric mean of its start and the
    /// tolerance: a converging iteration from a good predictor is far below by then, and a load
    /// step that stalls is cheaper to cut than to grind through.
    pub stall_steps: usize,
    pub stall_reduction: f64,
    /// Give up when, after this many tangent steps, `|r|` has not fallen tenfold from its
    /// start, or after the first it has not halved (`usize::MAX`: never): an iteration from a
    /// usable predictor has by then, and one that has not is stagnating on a fold (measured on
    /// the fine benchmark: every such attempt failed after three to five more steps, and the
    /// first step of the undamped ones that converged there cut `|r|` 20-90-fold).
    pub diverging_steps: usize,
}

impl Default for NewtonSettings {
    /// `rtol = 1e-10`, `atol = 1e-12`, `utol = 1e-13`, 30 steps, 12 halvings, full Newton.
    fn default() -> Self {
        NewtonSettings {
            max_iterations: 30,
            residual_tolerance: 1e-10,
            absolute_tolerance: 1e-12,
            update_tolerance: 1e-13,
            max_backtracks: 12,
            sufficient_decrease: 1e-4,
            solve_tolerance: 1e-8,
            inertia_at_solution: true,
            factorise_start: false,
            reuse_indefinite: false,
            reuse_factorisation: false,
            contraction: 0.25,
            stall_steps: usize::MAX,
            stall_reduction: 1e-3,
            diverging_steps: usize::MAX,
        }
    }
}

/// Newton's method, keeping the symbolic factorisation between calls with the same pattern.
pub struct Newton {
    /// Tolerances and limits.
    pub settings: NewtonSettings,
    solver: Option<Held>,
}

/// The held factorisation.
struct Held {
    /// The layout id of the assembly it factorised, while the next solves may reuse it.
    reusable_for: Option<usize>,
    /// The structure id of the matrices its analysis is for.
    structure: usize,
    solver: SparseLdlt,
}

impl Newton {
    /// A solver with the given settings.
    pub fn new(settings: NewtonSettings) -> Self {
        Newton { settings, solver: None }
    }

    /// Frees the held factorisation and its analysis (the next solve starts afresh).
    pub fn release_factorisation(&mut self) {
        self.solver = None;
    }

    /// The linear solver of the last pattern (its last factorisation and timings).
    pub fn linear_solver(&self) -> Option<&SparseLdlt> {
        self.solver.as_ref().map(|held| &held.solver)
    }

    /// Keeps the held factorisation from being reused by the next solve (its analysis stays).
    pub fn forget_factorisation(&mut self) {
        if let Some(held) = &mut self.solver {
            held.reusable_for = None;
        }
    }

    /// A new solver sharing the held solver's analysis, if that is of the given structure.
    pub fn sibling_solver(&self, structure: usize) -> Option<SparseLdlt> {
        self.solver
            .as_ref()
            .filter(|held| held.structure == structure)
            .map(|held| held.solver.sibling())
    }

    /// Solves equilibrium with `bc` prescribed, starting from `u` (full vector); on success `u`
    /// holds the solution, on failure it is unchanged.
    pub fn solve(&mut self, system: &mut System, u: &mut [f64], bc: &Dirichlet) -> Result<NewtonReport, NewtonError> {
        self.solve_with(system, u, bc, &NoAddedEnergy)
    }

    /// [`Newton::solve`] for the strain energy plus `added` (contact, damping).
    pub fn solve_with(
        &mut self,
        system: &mut System,
        u: &mut [f64],
        bc: &Dirichlet,
        added: &dyn AddedEnergy,
    ) -> Result<NewtonReport, NewtonError> {
        let (start, scale) = (u.to_vec(), system.penalty_scale());
        let result = self.iterate_with_multipliers(system, u, bc, added);
        system.set_penalty_scale(scale);
        if result.is_err() {
            u.copy_from_slice(&start);
        }
        result
    }

    /// Negative eigenvalues of the tangent of the strain energy plus `added` at `u` (with `bc`
    /// prescribed), factorised with the cached analysis when the pattern is the same.
    pub fn inertia(
        &mut self,
        system: &mut System,
        u: &[f64],
        bc: &Dirichlet,
        added: &dyn AddedEnergy,
    ) -> Result<Option<usize>, NewtonError> {
        let assembled = system.assemble_for_stability(u, bc, added)?;
        Ok(self.factorize(&assembled, &mut Timings::default()).negative_pivots())
    }

    fn iterate(
        &mut self,
        system: &mut System,
        u: &mut [f64],
        bc: &Dirichlet,
        added: &dyn AddedEnergy,
    ) -> Result<NewtonReport, NewtonError> {
        let s = self.settings;
        let mut problem = Problem::new(system, bc, added)?;
        let pending: Vec<f64> = bc.dofs().iter().zip(bc.values()).map(|(&d, &g)| g - u[d]).collect();
        let lifting = pending.iter().any(|&p| p != 0.0);
        // Not with multipliers: their inertia is that of another matrix ([`System::assemble_for_stability`]).
        let factorise_start = s.factorise_start && !lifting && !problem.system.has_multipliers();
        let assembled = problem
            .assemble(
                u,
                &pending,
                lifting,
                lifting || !s.reuse_factorisation || factorise_start,
            )
            .map_err(|e| inverted(e, 0))?;
        // Whether the held factorisation is that of the current iterate's tangent.
        let mut factorised = factorise_start && !problem.free.is_empty();
        let start_negative_pivots = if factorised {
            self.factorize(&assembled, &mut problem.timings).negative_pivots()
        } else {
            None
        };
        let mut reuse =
            s.reuse_factorisation && !lifting && self.holds(assembled.pattern, s.reuse_indefinite && factorised);
        let mut state = Iterate {
            assembled,
            pending,
            lifting,
        };
        let mut history = vec![state.assembled.residual_norm()];
        let (mut last_update, mut backtracks, mut tangent_steps) = (f64::INFINITY, 0, 0);
        for iteration in 0.. {
            let residual = state.assembled.residual_norm();
            // A penalty raised by the multiplier updates raises the residual's round-off with it
            // (measured: in proportion), so the tolerance follows; at the largest raise the
            // equilibrium then holds to 1e-7 relative, as the constraint does.
            let tolerance = (s.residual_tolerance * state.assembled.force_norm() + s.absolute_tolerance)
                * problem.system.penalty_scale();
            // The displacements' scale (not the multipliers' that may follow them).
            let scale = 1.0 + max_abs(&u[..problem.system.mesh().num_dofs()]);
            if !state.lifting && (residual <= tolerance || last_update <= s.update_tolerance * scale) {
                return self.report(
                    problem,
                    u,
                    state.assembled,
                    (iteration, tangent_steps, start_negative_pivots),
                    history,
                    backtracks,
                );
            }
            // Reused steps each contract |r| by `contraction`, so they are few; bound them anyway.
            // Stalled: short of both a `stall_reduction` decrease and half the decrease (in
            // orders of magnitude) that convergence needs.
            let halfway = (history[0] * tolerance).sqrt();
            // Diverging: where a tangent step must show convergence, |r| not halved by the
            // first, or not down tenfold after `diverging_steps`.
            let diverging = s.diverging_steps != usize::MAX
                && ((tangent_steps == 1 && residual > 0.5 * history[0])
                    || (tangent_steps >= s.diverging_steps && residual > 0.1 * history[0]));
            let stalled =
                (tangent_steps >= s.stall_steps && residual > halfway.max(s.stall_reduction * history[0])) || diverging;
            if stalled || tangent_steps == s.max_iterations || iteration == 2 * s.max_iterations {
                return Err(NewtonError::NotConverged {
                    iterations: iteration,
                    residual,
                    tolerance,
                    residual_history: history,
                });
            }
            if reuse {
                // A reused step rounds the held factor to single precision: a full step refactorises.
                factorised = false;
                match self.reused_step(&mut problem, u, &state, residual)? {
                    Some((next, next_u, update, ratio)) => {
                        last_update = update;
                        u.copy_from_slice(&next_u);
                        state = next;
                        history.push(state.assembled.residual_norm());
                        // An indefinite factor is kept only while it contracts about as a
                        // fresh tangent would (otherwise a slow linear iteration may stall).
                        let definite = self
                            .solver
                            .as_ref()
                            .is_some_and(|held| held.solver.negative_pivots() == Some(0));
                        reuse = ratio <= if definite { s.contraction } else { s.contraction.powi(2) };
                    }
                    None => reuse = false,
                }
                continue;
            }
            if state.assembled.tangent.is_none() {
                state.assembled = problem.assemble(u, &state.pending, state.lifting, true)?;
            }
            let du = self.newton_step(&state.assembled, factorised, &mut problem.timings)?;
            factorised = false;
            tangent_steps += 1;
            let (next, next_u, alpha, halvings) = self.line_search(&mut problem, u, &state, &du, iteration)?;
            backtracks += halvings;
            last_update = alpha * max_abs(&du);
            u.copy_from_slice(&next_u);
            state = next;
            history.push(state.assembled.residual_norm());
            reuse = s.reuse_factorisation && !state.lifting && self.holds(state.assembled.pattern, s.reuse_indefinite);
        }
        unreachable!("the loop returns")
    }

    /// Whether a reusable factorisation with pattern `pattern` is held: one of a positive
    /// definite matrix, or one made in this solve (`own`, of an iterate of this very
    /// iteration). An older indefinite one is not reused, since on an unstable path several
    /// equilibria lie close together and an iteration with an old matrix may settle on another.
    fn holds(&self, pattern: usize, own: bool) -> bool {
        self.solver
            .as_ref()
            .is_some_and(|held| held.reusable_for == Some(pattern) && (own || held.solver.negative_pivots() == Some(0)))
    }

    /// A full step with the held factorisation: the new iterate, its displacement, the update
    /// and the residual ratio, or `None` when the step does not decrease `|r|` (or inverts an
    /// element), leaving the iterate as it was.
    fn reused_step(
        &mut self,
        problem: &mut Problem,
        u: &[f64],
        state: &Iterate,
        residual: f64,
    ) -> Result<Option<ReusedStep>, NewtonError> {
        let solver = &mut self.solver.as_mut().expect("held, checked by the caller").solver;
        let mut du: Vec<f64> = state.assembled.residual.iter().map(|r| -r).collect();
        // Single precision (the next residual checks the step), except with the
        // incompressibility penalty, whose conditioning leaves it too few digits.
        if problem.system.has_multipliers() {
            solver.solve_in_place(&mut du)?;
        } else {
            solver.solve_in_place_single(&mut du)?;
        }
        problem.timings.solve += solver.solve_time();
        problem.timings.solves += 1;
        let trial_u = problem.step(u, &du, &state.pending, 1.0);
        match problem.assemble(&trial_u, &state.pending, false, false) {
            Ok(assembled) if assembled.residual_norm() <= (1.0 - self.settings.sufficient_decrease) * residual => {
                let ratio = assembled.residual_norm() / residual;
                let next = Iterate {
                    assembled,
                    pending: state.pending.clone(),
                    lifting: false,
                };
                Ok(Some((next, trial_u, max_abs(&du), ratio)))
            }
            Ok(_) | Err(Error::NonPositiveJacobian { .. }) => Ok(None),
            Err(e) => Err(e.into()),
        }
    }

    /// The converged state `u`, with the inertia of its tangent if requested.
    fn report(
        &mut self,
        mut problem: Problem,
        u: &[f64],
        mut assembled: Assembled,
        (iterations, tangent_steps, start_negative_pivots): (usize, usize, Option<usize>),
        residual_history: Vec<f64>,
        backtracks: usize,
    ) -> Result<NewtonReport, NewtonError> {
        let negative_pivots = if !self.settings.inertia_at_solution || problem.free.is_empty() {
            None
        } else {
            if problem.system.has_multipliers() {
                let start = std::time::Instant::now();
                assembled = problem.system.assemble_for_stability(u, problem.bc, problem.added)?;
                problem.timings.assembly += start.elapsed();
            } else if assembled.tangent.is_none() {
                assembled = problem.assemble(u, &[], false, true)?;
            }
            self.factorize(&assembled, &mut problem.timings).negative_pivots()
        };
        Ok(NewtonReport {
            iterations,
            tangent_steps,
            residual_history,
            force_norm: assembled.force_norm(),
            energy: assembled.energy,
            min_jacobian: assembled.min_jacobian,
            reactions: assembled.reactions,
            negative_pivots,
            start_negative_pivots,
            backtracks,
            multiplier_updates: 0,
            timings: problem.timings,
        })
    }

    /// Halves `alpha` until `u + alpha du` is admissible (and, once the prescribed values are
    /// reached, decreases `|r|`), starting from 1 or from where the first term of the added
    /// energy switches on ([`AddedEnergy::switch_on_fraction`]); returns the new iterate, its
    /// displacement, `alpha` and the number of halvings.
    fn line_search(
        &self,
        problem: &mut Problem,
        u: &[f64],
        state: &Iterate,
        du: &[f64],
        iteration: usize,
    ) -> Result<(Iterate, Vec<f64>, f64, usize), NewtonError> {
        let s = self.settings;
        let residual = state.assembled.residual_norm();
        let full = problem.step(u, du, &state.pending, 1.0);
        let mut alpha = problem.added.switch_on_fraction(u, &full);
        for halvings in 0.. {
            let trial_u = problem.step(u, du, &state.pending, alpha);
            let pending: Vec<f64> = state.pending.iter().map(|p| (1.0 - alpha) * p).collect();
            let lifting = state.lifting && alpha < 1.0;
            let failure = match problem.assemble(&trial_u, &pending, lifting, false) {
                Ok(assembled)
                    if state.lifting
                        || assembled.residual_norm() <= (1.0 - s.sufficient_decrease * alpha) * residual =>
                {
                    let next = Iterate {
                        assembled,
                        pending,
                        lifting,
                    };
                    return Ok((next, trial_u, alpha, halvings));
                }
                Ok(_) => NewtonError::LineSearch { iteration, residual },
                Err(Error::NonPositiveJacobian { jacobian }) => NewtonError::Inverted { iteration, jacobian },
                Err(e) => return Err(e.into()),
            };
            if halvings == s.max_backtracks {
                return Err(failure);
            }
            alpha *= 0.5;
        }
        unreachable!("the loop returns")
    }

    /// `du_f = -K_ff^-1 r_f` (with the held factorisation if it is `current`'s, `factorised`),
    /// retried with `L B L^T` if the `L D L^T` solve is inaccurate.
    fn newton_step(
        &mut self,
        current: &Assembled,
        factorised: bool,
        timings: &mut Timings,
    ) -> Result<Vec<f64>, NewtonError> {
        let tolerance = self.settings.solve_tolerance;
        let k = current.tangent.as_ref().expect("assembled with the tangent").as_ref();
        if !factorised || self.solver.is_none() {
            self.factorize(current, timings);
        }
        let solver = &mut self.solver.as_mut().expect("factorised").solver;
        loop {
            let mut du: Vec<f64> = current.residual.iter().map(|r| -r).collect();
            solver.solve_in_place(&mut du)?;
            timings.solve += solver.solve_time();
            timings.solves += 1;
            let mismatch: Vec<f64> = multiply(k, &du)
                .iter()
                .zip(&current.residual)
                .map(|(a, r)| a + r)
                .collect();
            if norm(&mismatch) <= tolerance * current.residual_norm()
                || solver.factorisation() == Some(Factorisation::Lblt)
            {
                return Ok(du);
            }
            solver.factorize_pivoted(k);
            timings.factorisation += solver.factorisation_time();
            timings.factorisations += 1;
        }
    }

    /// Factorises `current`'s tangent, redoing the symbolic analysis when the structure changed.
    fn factorize(&mut self, current: &Assembled, timings: &mut Timings) -> &mut SparseLdlt {
        let k = current.tangent.as_ref().expect("assembled with the tangent");
        if self
            .solver
            .as_ref()
            .is_none_or(|held| held.structure != current.structure)
        {
            self.solver = None; // free the old factor before analysing the new structure
            let solver = SparseLdlt::new(k.symbolic());
            timings.analysis += solver.symbolic_time();
            self.solver = Some(Held {
                reusable_for: None,
                structure: current.structure,
                solver,
            });
        }
        let held = self.solver.as_mut().expect("set above");
        held.reusable_for = Some(current.pattern);
        let solver = &mut held.solver;
        solver.factorize(k.as_ref());
        timings.factorisation += solver.factorisation_time();
        timings.factorisations += 1;
        solver
    }
}

/// A step with the held factorisation: the new iterate, its displacement, `|du|_inf` and the
/// residual ratio.
type ReusedStep = (Iterate, Vec<f64>, f64, f64);

/// One Newton iterate: its assembly, and how far the prescribed unknowns still have to move.
struct Iterate {
    assembled: Assembled,
    /// `g - u_c` for each prescribed unknown.
    pending: Vec<f64>,
    /// Whether `pending` is non-zero (the residual is then lifted by `K_fc pending`).
    lifting: bool,
}

/// Largest absolute entry.
fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |m, x| m.max(x.abs()))
}

/// The system being solved, with the wall times a solve accumulates.
struct Problem<'a> {
    system: &'a mut System,
    bc: &'a Dirichlet,
    added: &'a dyn AddedEnergy,
    free: Vec<usize>,
    timings: Timings,
}

impl<'a> Problem<'a> {
    /// The problem of `system` with `bc` prescribed and `added` energy; no time spent yet.
    fn new(system: &'a mut System, bc: &'a Dirichlet, added: &'a dyn AddedEnergy) -> crate::Result<Self> {
        let free = system.free_dofs(bc)?.to_vec();
        Ok(Problem {
            system,
            bc,
            added,
            free,
            timings: Timings::default(),
        })
    }

    /// Residual (and tangent when `with_tangent`) at `u`, lifted by `K_fc pending` when
    /// `lifting`; timed.
    fn assemble(&mut self, u: &[f64], pending: &[f64], lifting: bool, with_tangent: bool) -> crate::Result<Assembled> {
        let assembled = self
            .system
            .assemble_with(u, self.bc, lifting.then_some(pending), with_tangent, self.added)?;
        self.timings.assembly += assembled.elapsed;
        self.timings.assemblies += 1;
        Ok(assembled)
    }

    /// `u + alpha (du_f, pending)`, landing exactly on the prescribed values when `alpha = 1`.
    fn step(&self, u: &[f64], du: &[f64], pending: &[f64], alpha: f64) -> Vec<f64> {
        let mut next = u.to_vec();
        for (&dof, &d) in self.free.iter().zip(du) {
            next[dof] += alpha * d;
        }
        for ((&dof, &g), &p) in self.bc.dofs().iter().zip(self.bc.values()).zip(pending) {
            next[dof] = if alpha == 1.0 { g } else { next[dof] + alpha * p };
        }
        next
    }
}

/// The starting state's `J <= 0` as a Newton failure.
fn inverted(e: Error, iteration: usize) -> NewtonError {
    match e {
        Error::NonPositiveJacobian { jacobian } => NewtonError::Inverted { iteration, jacobian },
        other => NewtonError::Model(other),
    }
}
