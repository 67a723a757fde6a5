//! Minimisation of the total potential energy at fixed prescribed displacements by a
//! trust-region Newton method, for the equilibrium a structure snaps to where the followed
//! branch has no nearby equilibrium (a limit point in `d`, a closing trough).
//!
//! Each step solves `(K + sigma D) p = -r` with `D` the diagonal of the reference stiffness
//! ([`crate::fem::System::reference_stiffness_diagonal`], relative to its mean) and the shift
//! `sigma >= 0` the smallest of the tried ones whose `L D L^T` factor has no negative pivot
//! (Levenberg and Marquardt's form of the trust region: `|p|_D` shrinks as `sigma` grows). No
//! nodal move exceeds [`MAX_MOVE`] (the step is scaled down), so that no surface passes another
//! between two contact searches. The step is taken by the ratio `rho` of the actual decrease of
//! the energy `E` to the decrease `-(r.p + p.K.p / 2)` of its quadratic model: accepted if
//! `rho > RHO_ACCEPT`; `sigma` is raised fourfold if `rho < 1/4`, sixteenfold while the factor
//! has negative pivots, and lowered if `rho > 3/4` (to zero, pure Newton, below `SIGMA_MIN`):
//! fourfold, and fourfold more at each further such step in a row ([`Shift`]).
//!
//! Where the unshifted tangent has negative pivots and the shifted step would lower `E` by
//! almost nothing (the start lies on an unstable branch, whose residual is small), or the
//! residual is already within Newton's tolerance (a saddle), the step follows the direction of
//! negative curvature instead: the lowest mode of `K v = lambda D v` (inverse iteration with the
//! factor of `K + sigma D` for a shift that makes it definite), whose curvature is negative, along the
//! sign that lowers `E`, as far as `E` keeps falling. It ends at a residual within Newton's
//! tolerance with an unshifted factor without negative pivots: a local minimum. The energy never
//! increases from step to step. With [`NewtonPolicy::max_pass_move`] it stops, unfinished, once a
//! node has moved that far from the start, for the outer loops to search the contact pairs again
//! (a snap onto a closing trough moves the surface by more than the pairs found at its start
//! can follow).

use super::{
    largest_move, max_abs, EnergyEquations, Newton, NewtonError, NewtonPolicy, NewtonReport, Problem, Updates,
};
use crate::error::Error;
use crate::fem::assembly::Assembled;

/// Smallest non-zero shift; below it the step is Newton's.
const SIGMA_MIN: f64 = 1e-6;

/// Largest shift: a step that needs more is too short to make progress.
const SIGMA_MAX: f64 = 1e8;

/// Smallest ratio of actual to predicted decrease for which a step is taken.
const RHO_ACCEPT: f64 = 1e-4;

/// Largest factor by which `sigma` falls after one step.
const MAX_FALL: f64 = 256.0;

/// The shift `sigma` of the trust region and the factor by which it falls after a step whose
/// model predicted the energy well (`rho > 3/4`). That factor grows fourfold with every such
/// step in a row (up to [`MAX_FALL`]): from a start where the shift had to be large (a tangent
/// with strongly negative curvature) `sigma` reaches Newton's zero in a few steps instead of
/// one step per fourfold fall. Measured on the coarse Fig. 7 case with snaps: corrections in
/// contact had taken 16 to 59 steps, each a fourfold fall of `sigma` from about 1e3 with
/// `rho` within 1 % of one.
#[derive(Clone, Copy, Debug)]
struct Shift {
    sigma: f64,
    fall: f64,
}

impl Shift {
    /// `sigma` first (Newton's step if it is below `SIGMA_MIN`).
    fn starting_at(sigma: f64) -> Self {
        Shift {
            sigma: if sigma < SIGMA_MIN { 0.0 } else { sigma.min(SIGMA_MAX) },
            fall: 4.0,
        }
    }

    /// Raised `factor`-fold (at least to `SIGMA_MIN`), its fall back to fourfold.
    fn raise(&mut self, factor: f64) {
        self.sigma = (factor * self.sigma).max(SIGMA_MIN);
        self.fall = 4.0;
    }

    /// After a step with ratio `rho` of actual to predicted decrease.
    fn adapt(&mut self, rho: f64) {
        if rho < 0.25 {
            self.raise(4.0);
        } else if rho > 0.75 {
            self.sigma = if self.sigma / self.fall < SIGMA_MIN {
                0.0
            } else {
                self.sigma / self.fall
            };
            self.fall = (4.0 * self.fall).min(MAX_FALL);
        } else {
            self.fall = 4.0;
        }
    }
}

/// Largest nodal move of one step, in units of the layer thickness: below the contact search
/// distance (`H / 2`), so that a surface cannot pass through another unseen.
const MAX_MOVE: f64 = 0.1;

/// First nodal move of a step along negative curvature, in units of the layer thickness.
const CURVATURE_STEP: f64 = 0.02;

/// A shifted step whose predicted decrease is below this fraction of `|E|` makes no progress
/// where negative curvature is at hand.
const NEGLIGIBLE_PROGRESS: f64 = 1e-7;

/// A residual within this factor of the tolerance, where no step lowers the energy at a
/// definite tangent, is the round-off floor of a converged minimum.
const ROUND_OFF_FLOOR: f64 = 10.0;

/// Steps of the inverse iteration for the lowest mode.
const MODE_ITERATIONS: usize = 200;

/// The lowest mode of `K v = lambda D v` by inverse iteration with the factor of the definite
/// `K + shift D` held in `solver` (whose tangent is `shifted`): `x <- (K + shift D)^-1 D x`,
/// normalised in `D`, converges to the eigenvector of the smallest `lambda` (the one nearest
/// `-shift`, all lying above it). Returns the mode (unit in `D`), its curvature
/// `x.K.x = x.(K + shift D).x - shift` (negative where `K` is indefinite) and the solves made.
fn lowest_generalised_mode(
    solver: &mut crate::fem::SparseLdlt,
    shifted: faer::sparse::SparseColMatRef<'_, usize, f64>,
    d: &[f64],
    shift: f64,
) -> crate::Result<(Vec<f64>, f64, usize)> {
    let d_norm = |x: &[f64]| x.iter().zip(d).map(|(a, w)| w * a * a).sum::<f64>().sqrt();
    let mut x: Vec<f64> = (0..d.len())
        .map(|i| ((i as f64 + 1.0) * 0.754_877_666).fract() - 0.5)
        .collect();
    let (mut curvature, mut solves) = (f64::INFINITY, 0);
    for _ in 0..MODE_ITERATIONS {
        let norm = d_norm(&x);
        x.iter_mut().for_each(|a| *a /= norm);
        let kx = crate::fem::linear_solver::multiply(shifted, &x);
        let next = x.iter().zip(&kx).map(|(a, b)| a * b).sum::<f64>() - shift;
        let converged = (next - curvature).abs() <= 1e-8 * next.abs().max(shift);
        curvature = next;
        if converged {
            break;
        }
        let mut y: Vec<f64> = x.iter().zip(d).map(|(a, w)| a * w).collect();
        solver.solve_in_place(&mut y)?;
        solves += 1;
        x = y;
    }
    let norm = d_norm(&x);
    x.iter_mut().for_each(|a| *a /= norm);
    Ok((x, curvature, solves))
}

/// The energy being minimised (Newton's [`Problem`]) and the scale `D` of its shifts.
struct Landscape<'a, E: EnergyEquations + ?Sized> {
    problem: Problem<'a, E>,
    /// `D`, relative to its mean over the free unknowns, on every displacement unknown (the
    /// multipliers are updated outside Newton and take no shift).
    scale: Vec<f64>,
}

impl<'a, E: EnergyEquations + ?Sized> Landscape<'a, E> {
    /// The landscape of `equations`, with `D` from their stiffness scale.
    fn new(equations: &'a mut E) -> crate::Result<Self> {
        let problem = Problem::new(equations)?;
        let mut scale = problem.equations.stiffness_scale()?;
        let free = &problem.free;
        let mean = free.iter().map(|&dof| scale[dof].abs()).sum::<f64>() / free.len().max(1) as f64;
        scale
            .iter_mut()
            .for_each(|d| *d = d.abs() / mean.max(f64::MIN_POSITIVE));
        Ok(Landscape { problem, scale })
    }

    /// Energy, residual and tangent at `u`.
    fn assemble(&mut self, u: &[f64]) -> crate::Result<Assembled> {
        let problem = &mut self.problem;
        let assembled = problem.equations.assemble(u, None, true)?;
        problem.timings.assembly += assembled.elapsed;
        problem.timings.assemblies += 1;
        Ok(assembled)
    }

    /// `current` (the assembly at its state `u`, with the tangent) shifted by `sigma D`: the
    /// energy `sigma D (v - u)^2 / 2` added, centred at `u`, leaves the energy and the residual
    /// there and adds `sigma D` to the tangent.
    fn shifted(&mut self, current: &Assembled, sigma: f64) -> Assembled {
        let curvature: Vec<f64> = self.scale.iter().map(|d| sigma * d).collect();
        let shifted = self.problem.equations.with_diagonal_added(current, &curvature);
        self.problem.timings.assembly += shifted.elapsed;
        shifted
    }

    /// `u` moved by `t p` on the free unknowns.
    fn moved(&self, u: &[f64], p: &[f64], t: f64) -> Vec<f64> {
        let mut next = u.to_vec();
        for (&dof, &x) in self.problem.free.iter().zip(p) {
            next[dof] += t * x;
        }
        next
    }

    /// `p . D p` over the free unknowns.
    fn d_norm(&self, p: &[f64]) -> f64 {
        self.problem
            .free
            .iter()
            .zip(p)
            .map(|(&dof, x)| self.scale[dof] * x * x)
            .sum()
    }
}

/// The report of a minimisation ended at `current` after `(steps, factorisations, rejected)`.
fn minimum(
    current: Assembled,
    history: Vec<f64>,
    (steps, factorisations, rejected): (usize, usize, usize),
    negative_pivots: Option<usize>,
    timings: super::Timings,
    unfinished: bool,
    final_shift: f64,
) -> NewtonReport {
    NewtonReport {
        iterations: steps,
        tangent_steps: factorisations,
        residual_history: history,
        force_norm: current.force_norm(),
        energy: current.energy,
        min_jacobian: current.min_jacobian,
        reactions: current.reactions,
        negative_pivots,
        start_negative_pivots: None,
        backtracks: rejected,
        updates: Updates::default(),
        timings,
        unfinished,
        final_shift,
    }
}

/// The total potential (strain plus added) of an assembly: the energy whose gradient its
/// residual is (with the mixed element's multipliers held fixed).
fn total(a: &Assembled) -> f64 {
    a.potential + a.added_energy
}

impl Newton {
    /// A local minimum of the energy of `equations` from `u` (whose prescribed unknowns must
    /// hold their values): on success `u` holds it, and the report its unshifted inertia (no
    /// negative pivot), or, past `policy.max_pass_move`, the last accepted iterate and
    /// `unfinished`; on failure `u` is the last accepted iterate. `policy` gives the
    /// tolerances (Newton's), not the step rules.
    pub fn minimise<E: EnergyEquations + ?Sized>(
        &mut self,
        equations: &mut E,
        u: &mut [f64],
        policy: &NewtonPolicy,
    ) -> Result<NewtonReport, NewtonError> {
        let penalty_scale = equations.tolerance_scale();
        let mut land = Landscape::new(equations)?;
        let mut current = land.assemble(u).map_err(|e| super::inverted(e, 0))?;
        let mut history = vec![current.residual_norm()];
        let (mut shift, mut rejected, mut factorisations) = (Shift::starting_at(policy.initial_shift), 0, 0);
        let tolerance_at = |a: &Assembled| policy.tolerance(a.force_norm(), penalty_scale);
        let (start, n) = (u.to_vec(), land.problem.equations.scaled_unknowns());
        // Whether the steps ran out of shifts (rather than of the pass's step limit).
        let mut stalled = false;
        for iteration in 0..policy.max_minimisation_steps {
            let residual = current.residual_norm();
            let tolerance = tolerance_at(&current);
            let unfinished = policy
                .max_pass_move
                .is_some_and(|limit| largest_move(u, &start, n) > limit);
            // The unshifted factor is needed for a Newton step (`sigma = 0`) and for the test of
            // a minimum; a shifted step makes its own, so the inertia waits until it decides.
            let mut negative = None;
            if !unfinished && (shift.sigma == 0.0 || residual <= tolerance) {
                factorisations += 1;
                negative = Some(self.factorize(&current, &mut land.problem.timings).negative_pivots());
            }
            if unfinished || (negative == Some(Some(0)) && residual <= tolerance) {
                self.forget_factorisation();
                let counts = (iteration, factorisations, rejected);
                return Ok(minimum(
                    current,
                    history,
                    counts,
                    negative.flatten(),
                    land.problem.timings,
                    unfinished,
                    shift.sigma,
                ));
            }
            let next = match negative.is_some_and(|n| n != Some(0)) && residual <= tolerance {
                true => None,
                false => self.shifted_step(&mut land, u, &current, &mut shift, (&mut rejected, &mut factorisations))?,
            };
            let progress = |predicted: f64| predicted > NEGLIGIBLE_PROGRESS * total(&current).abs().max(1.0);
            let decided = next.as_ref().is_some_and(|(_, _, predicted)| progress(*predicted));
            let indefinite = !decided
                && *negative.get_or_insert_with(|| {
                    factorisations += 1;
                    self.factorize(&current, &mut land.problem.timings).negative_pivots()
                }) != Some(0);
            let (trial, assembled) = match next {
                Some((trial, assembled, _)) if !indefinite => (trial, assembled),
                None if !indefinite => {
                    stalled = true;
                    break;
                }
                _ => {
                    let step = self.curvature_step(&mut land, u, &current, shift.sigma, &mut factorisations)?;
                    // A shift of at least SIGMA_MIN for the next step, falling fourfold again.
                    shift.raise(1.0);
                    step.ok_or(NewtonError::LineSearch { iteration, residual })?
                }
            };
            u.copy_from_slice(&trial);
            current = assembled;
            history.push(current.residual_norm());
            if shift.sigma > SIGMA_MAX {
                stalled = true;
                break;
            }
        }
        // Where no step lowers the energy any more, at a definite tangent and a residual within
        // ROUND_OFF_FLOOR of the tolerance, the minimum is reached as far as round-off lets a
        // step tell: the tolerance sits at the residual's floor there.
        if stalled && current.residual_norm() <= ROUND_OFF_FLOOR * tolerance_at(&current) {
            factorisations += 1;
            let negative = self.factorize(&current, &mut land.problem.timings).negative_pivots();
            self.forget_factorisation();
            if negative == Some(0) {
                let counts = (history.len() - 1, factorisations, rejected);
                return Ok(minimum(
                    current,
                    history,
                    counts,
                    negative,
                    land.problem.timings,
                    false,
                    shift.sigma,
                ));
            }
        }
        // Said as what it is: a snap's failure read "Newton did not converge" before.
        let why = match stalled {
            true => format!("no shift up to {SIGMA_MAX:.0e} gives a step that lowers the energy"),
            false => format!("the limit of {} steps in one pass", policy.max_minimisation_steps),
        };
        Err(NewtonError::Model(Error::Solver(format!(
            "energy minimisation stopped after {} steps with the residual at {:.3e} (tolerance {:.3e}): {why}",
            history.len() - 1,
            current.residual_norm(),
            tolerance_at(&current),
        ))))
    }

    /// A step of the shifted Newton method from `u` (with `current` its assembly), its shift
    /// raised until the factor is positive definite and the step lowers the energy as its
    /// model predicts: the new state, its assembly and the predicted decrease; `None` if the
    /// shift exceeds [`SIGMA_MAX`]. Leaves the factor of the last shifted tangent held.
    fn shifted_step<E: EnergyEquations + ?Sized>(
        &mut self,
        land: &mut Landscape<'_, E>,
        u: &[f64],
        current: &Assembled,
        shift: &mut Shift,
        (rejected, factorisations): (&mut usize, &mut usize),
    ) -> Result<Option<(Vec<f64>, Assembled, f64)>, NewtonError> {
        let energy = total(current);
        let residual = current.residual_norm();
        while shift.sigma <= SIGMA_MAX {
            let sigma = shift.sigma;
            if sigma > 0.0 {
                let shifted = land.shifted(current, sigma);
                *factorisations += 1;
                if self.factorize(&shifted, &mut land.problem.timings).negative_pivots() != Some(0) {
                    shift.raise(16.0);
                    continue;
                }
            } else if self.solver.as_ref().and_then(|h| h.solver.negative_pivots()) != Some(0) {
                // The unshifted factor (held) is indefinite.
                shift.raise(16.0);
                continue;
            }
            let mut p: Vec<f64> = current.residual.iter().map(|r| -r).collect();
            let solver = &mut self.solver.as_mut().expect("factorised above").solver;
            solver.solve_in_place(&mut p)?;
            land.problem.timings.solve += solver.solve_time();
            land.problem.timings.solves += 1;
            // The model m(t p) = t r.p + t^2 p.K.p / 2, with p.K.p = -r.p - sigma p.D.p.
            let r_dot_p: f64 = current.residual.iter().zip(&p).map(|(r, x)| r * x).sum();
            let p_k_p = -r_dot_p - sigma * land.d_norm(&p);
            let t = (MAX_MOVE / max_abs(&p)).min(1.0);
            let predicted = -(t * r_dot_p + 0.5 * t * t * p_k_p);
            let trial = land.moved(u, &p, t);
            let (rho, assembled) = match land.assemble(&trial) {
                Ok(a) => {
                    let actual = energy - total(&a);
                    // Within round-off of the energy, the residual decides.
                    let rho = match predicted <= 1e-13 * energy.abs().max(1.0) {
                        true if a.residual_norm() < residual => 1.0,
                        true => 0.0,
                        false => actual / predicted,
                    };
                    (rho, Some(a))
                }
                Err(Error::NonPositiveJacobian { .. } | Error::BeyondExtensibility { .. }) => (f64::NEG_INFINITY, None),
                Err(e) => return Err(e.into()),
            };
            shift.adapt(rho);
            match assembled {
                Some(a) if rho > RHO_ACCEPT => return Ok(Some((trial, a, predicted))),
                _ => *rejected += 1,
            }
        }
        Ok(None)
    }

    /// A step along the direction of negative curvature from `u`: the lowest mode of
    /// `K v = lambda D v`, by inverse iteration with the factor of `K + s D` for a shift `s`
    /// within a factor four of the smallest that makes it definite (from `sigma`, raised or
    /// lowered fourfold, not below `SIGMA_MIN`), along the sign that lowers `E`, lengthened
    /// (doubled) while `E` keeps falling and shortened (halved) until it falls. `None` if no
    /// length lowers `E`.
    fn curvature_step<E: EnergyEquations + ?Sized>(
        &mut self,
        land: &mut Landscape<'_, E>,
        u: &[f64],
        current: &Assembled,
        sigma: f64,
        factorisations: &mut usize,
    ) -> Result<Option<(Vec<f64>, Assembled)>, NewtonError> {
        let mut shift = sigma.max(SIGMA_MIN);
        let mut raised = false;
        let mut shifted = loop {
            let shifted = land.shifted(current, shift);
            *factorisations += 1;
            if self.factorize(&shifted, &mut land.problem.timings).negative_pivots() == Some(0) {
                break shifted;
            }
            (shift, raised) = (4.0 * shift, true);
            if shift > SIGMA_MAX {
                return Err(Error::Solver(format!(
                    "energy minimisation: no shift up to {SIGMA_MAX:.0e} makes the tangent definite"
                ))
                .into());
            }
        };
        // Definite at the first try: lowered fourfold while it stays definite, so that the shift
        // lies within a factor four of the lowest eigenvalue's magnitude and the inverse iteration
        // contracts by at most 3/4 per step (from a large trust-region shift it barely moves).
        while !raised && shift / 4.0 >= SIGMA_MIN {
            let lower = land.shifted(current, shift / 4.0);
            *factorisations += 1;
            if self.factorize(&lower, &mut land.problem.timings).negative_pivots() != Some(0) {
                *factorisations += 1;
                self.factorize(&shifted, &mut land.problem.timings);
                break;
            }
            (shift, shifted) = (shift / 4.0, lower);
        }
        let k = shifted.tangent.as_ref().expect("assembled with the tangent");
        let solver = &mut self.solver.as_mut().expect("factorised above").solver;
        let d: Vec<f64> = land.problem.free.iter().map(|&dof| land.scale[dof]).collect();
        let (mut mode, curvature, solves) = lowest_generalised_mode(solver, k.as_ref(), &d, shift)?;
        land.problem.timings.solves += solves;
        if curvature >= 0.0 {
            return Err(Error::Solver(format!(
                "energy minimisation: the tangent is indefinite but its lowest mode has a positive curvature \
                 ({curvature:.3e})"
            ))
            .into());
        }
        // Downhill along the mode: r.v <= 0.
        if current.residual.iter().zip(&mode).map(|(r, v)| r * v).sum::<f64>() > 0.0 {
            mode.iter_mut().for_each(|v| *v = -*v);
        }
        let energy = |land: &mut Landscape<'_, E>, t: f64| -> Option<(Vec<f64>, Assembled)> {
            let trial = land.moved(u, &mode, t);
            land.assemble(&trial).ok().map(|a| (trial, a))
        };
        let mut length = CURVATURE_STEP / max_abs(&mode);
        let mut best: Option<(Vec<f64>, Assembled)> = None;
        let start = total(current);
        for _ in 0..40 {
            let candidate = energy(land, length);
            let lower = candidate.as_ref().is_some_and(|(_, a)| {
                total(a) < best.as_ref().map_or(start, |(_, b)| total(b)) && length * max_abs(&mode) <= 1.0
            });
            match (lower, best.is_some()) {
                (true, _) => {
                    best = candidate;
                    length *= 2.0;
                }
                (false, true) => break,
                (false, false) => {
                    length *= 0.5;
                    if length * max_abs(&mode) < 1e-12 {
                        break;
                    }
                }
            }
        }
        Ok(best)
    }
}
