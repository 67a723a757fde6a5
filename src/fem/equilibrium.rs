//! Equilibrium at fixed prescribed displacements: Newton's iteration ([`crate::fem::newton`])
//! inside the outer loops that update what its equations depend on, each of one shape, *solve,
//! update, check* ([`Update`], [`repeat`]):
//!
//! - contact ([`crate::fem::contact::solve`]): a new search on the deformed surface and Uzawa's
//!   multiplier update, until the penetration is within tolerance and the loaded pairs no
//!   longer change;
//! - inside it, the mixed element's incompressibility multipliers ([`crate::fem::element::mixed`]): the
//!   method of multipliers, until the constraint holds.
//!
//! The inner solver is Newton's iteration, or, for a snap, the minimisation of the energy
//! ([`Newton::minimise`], a trust-region Newton method that ends at a local minimum). One save
//! and restore covers the whole solve (a failure leaves the state and the contact as they
//! were), one report sums its passes, and the inertia at the solution is counted once, after
//! the last update.

use super::added::{AddedEnergy, Sum};
use super::assembly::System;
use super::boundary::Dirichlet;
use super::contact::{Contact, ContactUpdate};
use super::element::{PressureUpdate, Registry};
use super::newton::{
    largest_move, Newton, NewtonError, NewtonPolicy, NewtonReport, Precision, SystemEquations, Updates,
};
use crate::mesh::ElementKind;

/// What an outer loop does between two converged solves of the system `S`.
pub trait Update<S> {
    /// Most updates, each followed by another solve.
    fn max_updates(&self) -> usize;

    /// Checks the converged state `u` and updates: [`Check::Accepted`] if the state passes the
    /// loop's check (the update may still have refreshed estimates that do not change the
    /// state), otherwise [`Check::Updated`] with `u` or the loop's own unknowns changed.
    fn update(&mut self, system: &S, u: &mut [f64]) -> Result<Check, NewtonError>;

    /// Counts one update into `updates`.
    fn count(&self, updates: &mut Updates);

    /// After an unfinished pass of a minimisation ([`NewtonReport::unfinished`]), at a state
    /// that is not an equilibrium: refreshes what follows the configuration (the contact pairs,
    /// not their multipliers) and says whether it did; a loop that does not (`false`) passes
    /// such a pass up unchanged.
    fn refresh(&mut self, _u: &[f64]) -> bool {
        false
    }

    /// Why the loop failed after its last update.
    fn exhausted(&self) -> NewtonError;
}

/// The verdict of an [`Update`] on a converged state.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Check {
    Accepted,
    Updated,
}

/// Most passes of a minimisation stopped unfinished, each followed by an update.
const MAX_UNFINISHED_PASSES: usize = 200;

/// Solve, update, check: `solve` (which sees the loop's current state), then `update`, again
/// until the check passes or the updates run out; the report of all solves together. An
/// unfinished pass of a minimisation is followed by a refresh ([`Update::refresh`]) and another
/// pass, without a check and outside the updates' count, or passed up if the loop has nothing
/// to refresh.
pub fn repeat<S, L: Update<S>>(
    update: &mut L,
    system: &mut S,
    u: &mut [f64],
    mut solve: impl FnMut(&L, &mut S, &mut [f64]) -> Result<NewtonReport, NewtonError>,
) -> Result<NewtonReport, NewtonError> {
    let mut report = solve(update, system, u)?;
    let (mut updates, mut unfinished_passes) = (0, 0);
    loop {
        if report.unfinished {
            if !update.refresh(u) {
                return Ok(report);
            }
            unfinished_passes += 1;
            if unfinished_passes > MAX_UNFINISHED_PASSES {
                return Err(NewtonError::Model(crate::Error::Solver(format!(
                    "energy minimisation: still moving after {MAX_UNFINISHED_PASSES} passes"
                ))));
            }
        } else {
            if update.update(system, u)? == Check::Accepted {
                return Ok(report);
            }
            if updates == update.max_updates() {
                return Err(update.exhausted());
            }
            updates += 1;
        }
        report = report.followed_by(solve(update, system, u)?);
        update.count(&mut report.updates);
    }
}

/// The solver inside the outer loops.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Inner {
    /// Newton's iteration: the equilibrium nearest the start.
    Newton,
    /// The trust-region minimisation of the energy: a local minimum, reached by steps that
    /// never raise the energy.
    Minimise,
}

/// Equilibrium of the strain energy with `bc` prescribed, from `u`; on failure `u` is unchanged.
pub fn solve<const D: usize, const N: usize, const Q: usize, const U: usize>(
    newton: &mut Newton,
    system: &mut System<D, N, Q, U>,
    u: &mut [f64],
    bc: &Dirichlet,
    policy: &NewtonPolicy,
) -> Result<NewtonReport, NewtonError>
where
    ElementKind: Registry<D, N, Q, U>,
{
    let loads = (None, &super::added::NoAddedEnergy as &dyn AddedEnergy);
    solve_equilibrium(newton, (system, u, bc), loads, (Inner::Newton, policy))
}

/// [`solve`] for the strain energy plus `added` (e.g. damping).
pub fn solve_with<const D: usize, const N: usize, const Q: usize, const U: usize>(
    newton: &mut Newton,
    system: &mut System<D, N, Q, U>,
    u: &mut [f64],
    bc: &Dirichlet,
    added: &dyn AddedEnergy,
    policy: &NewtonPolicy,
) -> Result<NewtonReport, NewtonError>
where
    ElementKind: Registry<D, N, Q, U>,
{
    solve_equilibrium(newton, (system, u, bc), (None, added), (Inner::Newton, policy))
}

/// [`solve_with`] with contact: the strain energy plus `contact` plus `other`; on failure `u`
/// and `contact` are restored.
pub fn solve_with_contact<const D: usize, const N: usize, const Q: usize, const U: usize>(
    newton: &mut Newton,
    system: &mut System<D, N, Q, U>,
    u: &mut [f64],
    bc: &Dirichlet,
    contact: &mut Contact,
    other: &dyn AddedEnergy,
    policy: &NewtonPolicy,
) -> Result<NewtonReport, NewtonError>
where
    ElementKind: Registry<D, N, Q, U>,
{
    solve_equilibrium(newton, (system, u, bc), (Some(contact), other), (Inner::Newton, policy))
}

/// A local minimum of the strain energy plus `contact` (if any) plus `other` with `bc`
/// prescribed, from `u` (whose prescribed unknowns must hold their values), with the outer
/// loops around the minimisation; the inertia of a stable state is counted (none negative)
/// if `policy` asks for it. On failure `u` and `contact` are restored.
pub fn minimise<const D: usize, const N: usize, const Q: usize, const U: usize>(
    newton: &mut Newton,
    (system, u, bc): (&mut System<D, N, Q, U>, &mut [f64], &Dirichlet),
    contact: Option<&mut Contact>,
    other: &dyn AddedEnergy,
    policy: &NewtonPolicy,
) -> Result<NewtonReport, NewtonError>
where
    ElementKind: Registry<D, N, Q, U>,
{
    solve_equilibrium(newton, (system, u, bc), (contact, other), (Inner::Minimise, policy))
}

fn solve_equilibrium<const D: usize, const N: usize, const Q: usize, const U: usize>(
    newton: &mut Newton,
    (system, u, bc): (&mut System<D, N, Q, U>, &mut [f64], &Dirichlet),
    (mut contact, other): (Option<&mut Contact>, &dyn AddedEnergy),
    (inner, policy): (Inner, &NewtonPolicy),
) -> Result<NewtonReport, NewtonError>
where
    ElementKind: Registry<D, N, Q, U>,
{
    let policy = for_system(policy, system);
    let (start, saved) = (u.to_vec(), contact.as_deref().cloned());
    // The shift a minimisation's pass ended with, for the next pass to start from.
    let mut shift = policy.initial_shift;
    let mut pressure_passes = |added: &dyn AddedEnergy, system: &mut System<D, N, Q, U>, u: &mut [f64]| {
        repeat(&mut PressureUpdate::new(), system, u, |pressure, system, u| {
            let mut equations = SystemEquations {
                system,
                bc,
                added,
                penalty_scale: pressure.penalty_scale(),
            };
            match inner {
                Inner::Newton => newton.iterate(&mut equations, u, &policy),
                Inner::Minimise => {
                    let pass = NewtonPolicy {
                        initial_shift: shift,
                        max_pass_move: [policy.max_pass_move, policy.max_move]
                            .into_iter()
                            .flatten()
                            .reduce(f64::min),
                        ..policy
                    };
                    let report = newton.minimise(&mut equations, u, &pass)?;
                    shift = report.final_shift;
                    match policy.max_move {
                        Some(limit) if largest_move(u, &start, system.mesh().num_dofs()) > limit => {
                            Err(NewtonError::Model(crate::Error::Solver(format!(
                                "energy minimisation: moved beyond {limit:.3e} from its start"
                            ))))
                        }
                        _ => Ok(report),
                    }
                }
            }
        })
    };
    let solved = match contact.as_deref_mut() {
        Some(contact) => repeat(&mut ContactUpdate::new(contact, u), system, u, |update, system, u| {
            pressure_passes(&Sum::new(vec![update.contact(), other]), system, u)
        }),
        None => pressure_passes(other, system, u),
    };
    let result = solved.and_then(|mut report| {
        if report.unfinished {
            return Err(NewtonError::Model(crate::Error::Solver(
                "energy minimisation stopped unfinished with no contact to search again".into(),
            )));
        }
        if policy.inertia_at_solution && !system.free_dofs(bc)?.is_empty() {
            let with_contact;
            let added: &dyn AddedEnergy = match contact.as_deref() {
                Some(contact) => {
                    with_contact = Sum::new(vec![contact, other]);
                    &with_contact
                }
                None => other,
            };
            report.negative_pivots = newton.inertia(system, u, bc, added, &mut report.timings)?;
        }
        Ok(report)
    });
    if result.is_err() {
        u.copy_from_slice(&start);
        if let (Some(contact), Some(saved)) = (contact, saved) {
            *contact = saved;
        }
    }
    result
}

/// `policy` for `system`'s equations. With multipliers, the iteration's tangent is not the one
/// whose inertia is the state's ([`System::assemble_for_stability`]), so the start is not
/// factorised for its inertia, and the penalty's conditioning leaves a reused factor too few
/// digits in single precision.
fn for_system<const D: usize, const N: usize, const Q: usize, const U: usize>(
    policy: &NewtonPolicy,
    system: &System<D, N, Q, U>,
) -> NewtonPolicy
where
    ElementKind: Registry<D, N, Q, U>,
{
    match system.has_multipliers() {
        true => NewtonPolicy {
            factorise_start: false,
            reused_precision: Precision::Double,
            ..*policy
        },
        false => *policy,
    }
}
