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
//! point only when another step follows.
//!
//! With [`Reuse::Definite`], the last factorisation (of an earlier iterate, or of an earlier
//! solve of the same pattern) is kept as the iteration matrix while it contracts the residual by
//! at least `contraction` per step and is positive definite (modified Newton): such a step
//! costs one residual assembly and one solve instead of a tangent assembly and a
//! factorisation. With [`Reuse::AlsoIndefinite`], an indefinite factorisation made in this
//! solve is kept too, while it contracts by `contraction^2` (about as a fresh tangent would). A
//! step that contracts less, or does not decrease `|r|`, falls back to the consistent tangent at
//! the current iterate, so the iteration is never worse than full Newton's; the converged state
//! is the same to the tolerances.
//!
//! With `factorise_start`, the tangent at the starting iterate (the predictor of a load step)
//! is factorised first, and the iteration starts with that factor: from a good predictor it
//! converges in two or three steps. Its inertia is reported (`start_negative_pivots`): the
//! caller may take it for the solution's where the predictor was close (the contact loop of a
//! path to a crease does).
//!
//! This is the iteration alone, a function of the equations, the start and a
//! [`NewtonPolicy`] passed per call; the solver keeps only its factorisation between calls. The
//! outer loops that update what the equations depend on (the mixed element's multipliers,
//! contact) and the inertia at the solution are [`crate::fem::equilibrium`]'s.

use super::added::AddedEnergy;
use super::assembly::{norm, Assembled, System};
use super::boundary::Dirichlet;
use super::element::Registry;
use super::linear_solver::{multiply, Factorisation, SparseLdlt};
use crate::error::Error;
use crate::mesh::ElementKind;

mod equations;
mod policy;
mod report;
mod trust_region;
pub use equations::{EnergyEquations, Equations, SystemEquations};
pub use policy::{NewtonPolicy, Precision, Reuse, Stall};
pub use report::{NewtonError, NewtonReport, Timings, Updates};

/// Newton's method: the factorisation it keeps between solves (and the symbolic analysis
/// between solves with the same pattern). How each solve iterates is the policy passed to it.
#[derive(Default)]
pub struct Newton {
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
    /// A solver holding no factorisation yet.
    pub fn new() -> Self {
        Newton::default()
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

    /// A new solver sharing the held solver's analysis, with the structure id that analysis is
    /// for (no factor of its own yet), if a solver is held.
    pub fn analysed_solver(&self) -> Option<(usize, SparseLdlt)> {
        self.solver.as_ref().map(|held| (held.structure, held.solver.sibling()))
    }

    /// A new solver sharing the held solver's analysis, if that is of the given structure.
    pub fn sibling_solver(&self, structure: usize) -> Option<SparseLdlt> {
        self.solver
            .as_ref()
            .filter(|held| held.structure == structure)
            .map(|held| held.solver.sibling())
    }

    /// Negative eigenvalues of the tangent of the strain energy plus `added` at `u` (with `bc`
    /// prescribed) whose inertia is the state's stability ([`System::assemble_for_stability`]),
    /// factorised with the cached analysis when the pattern is the same.
    pub fn inertia<const D: usize, const N: usize, const Q: usize, const U: usize>(
        &mut self,
        system: &mut System<D, N, Q, U>,
        u: &[f64],
        bc: &Dirichlet,
        added: &dyn AddedEnergy,
        timings: &mut Timings,
    ) -> Result<Option<usize>, NewtonError>
    where
        ElementKind: Registry<D, N, Q, U>,
    {
        let start = std::time::Instant::now();
        let assembled = system.assemble_for_stability(u, bc, added)?;
        timings.assembly += start.elapsed();
        timings.assemblies += 1;
        Ok(self.factorize(&assembled, timings).negative_pivots())
    }

    /// Newton's iteration on `equations` from `u` (full vector) with `policy`: on success `u`
    /// holds the solution (whose inertia this does not count: [`crate::fem::equilibrium`]
    /// does), on failure it is left at the last iterate.
    pub fn iterate<E: Equations + ?Sized>(
        &mut self,
        equations: &mut E,
        u: &mut [f64],
        policy: &NewtonPolicy,
    ) -> Result<NewtonReport, NewtonError> {
        let s = *policy;
        let mut problem = Problem::new(equations)?;
        let bc = problem.equations.prescribed();
        let pending: Vec<f64> = bc.dofs().iter().zip(bc.values()).map(|(&d, &g)| g - u[d]).collect();
        let lifting = pending.iter().any(|&p| p != 0.0);
        let factorise_start = s.factorise_start && !lifting;
        let assembled = problem
            .assemble(
                u,
                &pending,
                lifting,
                lifting || s.reuse == Reuse::Never || factorise_start,
            )
            .map_err(|e| inverted(e, 0))?;
        // Whether the held factorisation is that of the current iterate's tangent.
        let mut factorised = factorise_start && !problem.free.is_empty();
        let start_negative_pivots = if factorised {
            self.factorize(&assembled, &mut problem.timings).negative_pivots()
        } else {
            None
        };
        let mut reuse = s.reuse != Reuse::Never
            && !lifting
            && self.holds(assembled.pattern, s.reuse == Reuse::AlsoIndefinite && factorised);
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
            let tolerance = s.tolerance(state.assembled.force_norm(), problem.equations.tolerance_scale());
            // The displacements' scale (not the multipliers' that may follow them).
            let scale = 1.0 + max_abs(&u[..problem.equations.scaled_unknowns()]);
            if !state.lifting && (residual <= tolerance || last_update <= s.update_tolerance * scale) {
                return Ok(NewtonReport {
                    iterations: iteration,
                    tangent_steps,
                    residual_history: history,
                    force_norm: state.assembled.force_norm(),
                    energy: state.assembled.energy,
                    min_jacobian: state.assembled.min_jacobian,
                    reactions: state.assembled.reactions,
                    negative_pivots: None,
                    start_negative_pivots,
                    backtracks,
                    updates: Updates::default(),
                    timings: problem.timings,
                    unfinished: false,
                    final_shift: 0.0,
                });
            }
            // Reused steps each contract |r| by `contraction`, so they are few; bound them anyway.
            // Stalled: short of both a `stall_reduction` decrease and half the decrease (in
            // orders of magnitude) that convergence needs.
            let halfway = (history[0] * tolerance).sqrt();
            // Diverging: where a tangent step must show convergence, |r| not halved by the
            // first, or not down tenfold after `diverging_steps`.
            let diverging = s.diverging_after.is_some_and(|steps| {
                (tangent_steps == 1 && residual > 0.5 * history[0])
                    || (tangent_steps >= steps && residual > 0.1 * history[0])
            });
            let stalled = s.stall.is_some_and(|stall| {
                tangent_steps >= stall.steps && residual > halfway.max(stall.reduction * history[0])
            }) || diverging;
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
                match self.reused_step(&mut problem, u, &state, (residual, &s))? {
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
            let du = self.newton_step(&state.assembled, factorised, s.solve_tolerance, &mut problem.timings)?;
            factorised = false;
            tangent_steps += 1;
            let (next, next_u, alpha, halvings) = line_search(&mut problem, u, &state, &du, (iteration, &s))?;
            backtracks += halvings;
            last_update = alpha * max_abs(&du);
            u.copy_from_slice(&next_u);
            state = next;
            history.push(state.assembled.residual_norm());
            reuse = s.reuse != Reuse::Never
                && !state.lifting
                && self.holds(state.assembled.pattern, s.reuse == Reuse::AlsoIndefinite);
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
    fn reused_step<E: Equations + ?Sized>(
        &mut self,
        problem: &mut Problem<'_, E>,
        u: &[f64],
        state: &Iterate,
        (residual, policy): (f64, &NewtonPolicy),
    ) -> Result<Option<ReusedStep>, NewtonError> {
        let solver = &mut self.solver.as_mut().expect("held, checked by the caller").solver;
        let mut du: Vec<f64> = state.assembled.residual.iter().map(|r| -r).collect();
        match policy.reused_precision {
            Precision::Single => solver.solve_in_place_single(&mut du)?,
            Precision::Double => solver.solve_in_place(&mut du)?,
        }
        problem.timings.solve += solver.solve_time();
        problem.timings.solves += 1;
        let trial_u = problem.step(u, &du, &state.pending, 1.0);
        match problem.assemble(&trial_u, &state.pending, false, false) {
            Ok(assembled) if assembled.residual_norm() <= (1.0 - policy.sufficient_decrease) * residual => {
                let ratio = assembled.residual_norm() / residual;
                let next = Iterate {
                    assembled,
                    pending: state.pending.clone(),
                    lifting: false,
                };
                Ok(Some((next, trial_u, max_abs(&du), ratio)))
            }
            Ok(_) | Err(Error::NonPositiveJacobian { .. } | Error::BeyondExtensibility { .. }) => Ok(None),
            Err(e) => Err(e.into()),
        }
    }

    /// `du_f = -K_ff^-1 r_f` (with the held factorisation if it is `current`'s, `factorised`),
    /// retried with `L B L^T` if the `L D L^T` solve's relative residual is above `tolerance`.
    fn newton_step(
        &mut self,
        current: &Assembled,
        factorised: bool,
        tolerance: f64,
        timings: &mut Timings,
    ) -> Result<Vec<f64>, NewtonError> {
        let minus_residual = current.residual.iter().map(|r| -r).collect();
        let [du] = self.solve_tangent(current, [minus_residual], factorised, tolerance, timings)?;
        Ok(du)
    }

    /// `K_ff^-1 b` for each right-hand side `b`, with `current`'s tangent `K_ff`: with the held
    /// factorisation if it is `current`'s (`factorised`), otherwise factorised now (its inertia
    /// is then [`Newton::linear_solver`]'s). An indefinite `L D L^T` whose solve leaves a
    /// relative residual above `tolerance` is replaced by `L B L^T` and every `b` solved again.
    /// A positive definite `L D L^T` (no negative pivot) is backward stable without pivoting,
    /// as Cholesky's is, so its solve is not checked (the check is a product with `K`).
    pub fn solve_tangent<const M: usize>(
        &mut self,
        current: &Assembled,
        right_hand_sides: [Vec<f64>; M],
        factorised: bool,
        tolerance: f64,
        timings: &mut Timings,
    ) -> Result<[Vec<f64>; M], NewtonError> {
        let k = current.tangent.as_ref().expect("assembled with the tangent").as_ref();
        if !factorised || self.solver.is_none() {
            self.factorize(current, timings);
        }
        let solver = &mut self.solver.as_mut().expect("factorised").solver;
        'factorisation: loop {
            let mut solutions = right_hand_sides.clone();
            for (x, b) in solutions.iter_mut().zip(&right_hand_sides) {
                solver.solve_in_place(x)?;
                timings.solve += solver.solve_time();
                timings.solves += 1;
                if solver.factorisation() == Some(Factorisation::Lblt) || solver.negative_pivots() == Some(0) {
                    continue;
                }
                let mismatch: Vec<f64> = multiply(k, x).iter().zip(b).map(|(a, b)| a - b).collect();
                if norm(&mismatch) > tolerance * norm(b) {
                    solver.factorize_pivoted(k);
                    timings.factorisation += solver.factorisation_time();
                    timings.factorisations += 1;
                    continue 'factorisation;
                }
            }
            return Ok(solutions);
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

/// Halves `alpha` until `u + alpha du` is admissible (and, once the prescribed values are
/// reached, decreases `|r|`), starting from 1 or from where the first term of the added
/// energy switches on ([`AddedEnergy::switch_on_fraction`]); returns the new iterate, its
/// displacement, `alpha` and the number of halvings.
fn line_search<E: Equations + ?Sized>(
    problem: &mut Problem<'_, E>,
    u: &[f64],
    state: &Iterate,
    du: &[f64],
    (iteration, s): (usize, &NewtonPolicy),
) -> Result<(Iterate, Vec<f64>, f64, usize), NewtonError> {
    let residual = state.assembled.residual_norm();
    let full = problem.step(u, du, &state.pending, 1.0);
    let mut alpha = problem.equations.switch_on_fraction(u, &full);
    for halvings in 0.. {
        let trial_u = problem.step(u, du, &state.pending, alpha);
        let pending: Vec<f64> = state.pending.iter().map(|p| (1.0 - alpha) * p).collect();
        let lifting = state.lifting && alpha < 1.0;
        let failure = match problem.assemble(&trial_u, &pending, lifting, false) {
            Ok(assembled)
                if state.lifting || assembled.residual_norm() <= (1.0 - s.sufficient_decrease * alpha) * residual =>
            {
                let next = Iterate {
                    assembled,
                    pending,
                    lifting,
                };
                return Ok((next, trial_u, alpha, halvings));
            }
            Ok(_) => NewtonError::LineSearch { iteration, residual },
            Err(e @ (Error::NonPositiveJacobian { .. } | Error::BeyondExtensibility { .. })) => {
                NewtonError::Inadmissible {
                    iteration,
                    reason: e.to_string(),
                }
            }
            Err(e) => return Err(e.into()),
        };
        if halvings == s.max_backtracks {
            return Err(failure);
        }
        alpha *= 0.5;
    }
    unreachable!("the loop returns")
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

/// The largest nodal move between two states: the largest difference of their displacements
/// (the first `n` unknowns, before the multipliers).
pub(crate) fn largest_move(a: &[f64], b: &[f64], n: usize) -> f64 {
    a[..n].iter().zip(&b[..n]).fold(0.0, |m, (x, y)| m.max((x - y).abs()))
}

/// The equations being solved, with their free unknowns and the wall times a solve accumulates.
struct Problem<'a, E: Equations + ?Sized> {
    equations: &'a mut E,
    free: Vec<usize>,
    timings: Timings,
}

impl<'a, E: Equations + ?Sized> Problem<'a, E> {
    /// The problem of `equations`; no time spent yet.
    fn new(equations: &'a mut E) -> crate::Result<Self> {
        let free = equations.free_unknowns()?;
        Ok(Problem {
            equations,
            free,
            timings: Timings::default(),
        })
    }

    /// Residual (and tangent when `with_tangent`) at `u`, lifted by `K_fc pending` when
    /// `lifting`; timed.
    fn assemble(&mut self, u: &[f64], pending: &[f64], lifting: bool, with_tangent: bool) -> crate::Result<Assembled> {
        let assembled = self.equations.assemble(u, lifting.then_some(pending), with_tangent)?;
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
        let bc = self.equations.prescribed();
        for ((&dof, &g), &p) in bc.dofs().iter().zip(bc.values()).zip(pending) {
            next[dof] = if alpha == 1.0 { g } else { next[dof] + alpha * p };
        }
        next
    }
}

/// A starting state where the energy is not finite (`J <= 0`, or beyond a law's domain) as a
/// Newton failure.
fn inverted(e: Error, iteration: usize) -> NewtonError {
    match e {
        e @ (Error::NonPositiveJacobian { .. } | Error::BeyondExtensibility { .. }) => NewtonError::Inadmissible {
            iteration,
            reason: e.to_string(),
        },
        other => NewtonError::Model(other),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::Tangent;

    /// The gradient of `Phi(x, y) = x^4/4 + x^2/2 - 2x + (y - x)^2/2`, stationary at
    /// `x = y = 1` (`x^3 + x = 2`): equations with no mesh behind them.
    struct Quartic {
        prescribed: Dirichlet,
    }

    impl Equations for Quartic {
        fn prescribed(&self) -> &Dirichlet {
            &self.prescribed
        }

        fn free_unknowns(&mut self) -> crate::Result<Vec<usize>> {
            Ok(vec![0, 1])
        }

        fn assemble(&mut self, u: &[f64], _lift: Option<&[f64]>, with_tangent: bool) -> crate::Result<Assembled> {
            let (x, y) = (u[0], u[1]);
            let energy = x.powi(4) / 4.0 + x * x / 2.0 - 2.0 * x + (y - x).powi(2) / 2.0;
            let tangent = with_tangent
                .then(|| Tangent::from_lower_entries(2, &[(0, 0, 3.0 * x * x + 2.0), (1, 0, -1.0), (1, 1, 1.0)]))
                .transpose()?;
            Ok(Assembled {
                residual: vec![x.powi(3) + x - 2.0 - (y - x), y - x],
                tangent,
                reactions: Vec::new(),
                energy,
                potential: energy,
                added_energy: 0.0,
                min_jacobian: 1.0,
                pattern: 0,
                structure: 0,
                elapsed: std::time::Duration::ZERO,
            })
        }

        fn scaled_unknowns(&self) -> usize {
            2
        }
    }

    #[test]
    fn newton_solves_equations_that_are_not_a_mesh_s() {
        let mut equations = Quartic {
            prescribed: Dirichlet::new(Vec::new()).unwrap(),
        };
        let mut u = vec![3.0, -2.0];
        let policy = NewtonPolicy {
            reuse: Reuse::Never,
            ..NewtonPolicy::default()
        };
        let report = Newton::new().iterate(&mut equations, &mut u, &policy).unwrap();
        assert!((u[0] - 1.0).abs() < 1e-9 && (u[1] - 1.0).abs() < 1e-9, "{u:?}");
        assert!(report.iterations > 2, "from afar: {}", report.iterations);
    }
}
