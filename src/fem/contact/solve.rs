//! Equilibrium with contact at fixed prescribed displacements (augmented Lagrangian, Uzawa):
//! Newton's method with the current pairs and multipliers; then a new search on the deformed
//! surface and the update `lambda <- <lambda - eps g>_+`. The state is accepted when the
//! penetration is within tolerance and the search found no change among the loaded pairs (so
//! the forces the state balances are the ones reported); otherwise Newton runs again.

use super::Contact;
use crate::error::Error;
use crate::fem::added::{AddedEnergy, Sum};
use crate::fem::{Dirichlet, Newton, NewtonError, NewtonReport, System};

/// A converged state with contact.
#[derive(Clone, Debug)]
pub struct ContactSolve {
    /// The last Newton solve.
    pub report: NewtonReport,
    /// Newton iterations over all solves.
    pub iterations: usize,
    /// Of those, the steps with a newly factorised tangent.
    pub tangent_steps: usize,
    /// Newton solves (one per multiplier update).
    pub augmentations: usize,
    /// Largest penetration of the accepted state.
    pub penetration: f64,
    /// Whether any pair was loaded at the start (then the first tangent held contact terms).
    pub loaded_at_start: bool,
}

/// Solves equilibrium of the strain energy plus `contact` plus `other` (e.g. damping) with
/// `bc` prescribed, from `u`. On failure `u` and `contact` are restored.
pub fn solve_with_contact(
    newton: &mut Newton,
    system: &mut System,
    u: &mut [f64],
    bc: &Dirichlet,
    contact: &mut Contact,
    other: &dyn AddedEnergy,
) -> Result<ContactSolve, NewtonError> {
    let (start, saved) = (u.to_vec(), contact.clone());
    let result = augmented_lagrangian(newton, system, u, bc, contact, other);
    if result.is_err() {
        u.copy_from_slice(&start);
        *contact = saved;
    }
    result
}

fn augmented_lagrangian(
    newton: &mut Newton,
    system: &mut System,
    u: &mut [f64],
    bc: &Dirichlet,
    contact: &mut Contact,
    other: &dyn AddedEnergy,
) -> Result<ContactSolve, NewtonError> {
    contact.search(u);
    let loaded_at_start = !contact.loaded_pairs(u).is_empty();
    let (mut iterations, mut tangent_steps, mut penetration) = (0, 0, f64::INFINITY);
    for augmentation in 1..=contact.settings.max_augmentations {
        let report = newton.solve_with(system, u, bc, &Sum::new(vec![&*contact, other]))?;
        iterations += report.iterations;
        tangent_steps += report.tangent_steps;
        let loaded = contact.loaded_pairs(u);
        contact.search(u);
        let unchanged = contact.loaded_pairs(u) == loaded;
        penetration = contact.penetration(u);
        contact.augment(u);
        if penetration <= contact.settings.tolerance && unchanged {
            return Ok(ContactSolve {
                report,
                iterations,
                tangent_steps,
                augmentations: augmentation,
                penetration,
                loaded_at_start,
            });
        }
    }
    Err(NewtonError::Model(Error::Solver(format!(
        "contact: penetration {penetration:.2e} (tolerance {:.1e}) or pairs still changing after {} multiplier updates",
        contact.settings.tolerance, contact.settings.max_augmentations
    ))))
}
