//! Equilibrium with contact at fixed prescribed displacements (augmented Lagrangian, Uzawa), as
//! an outer loop around Newton's iteration ([`crate::fem::equilibrium`]): a solve with the
//! current pairs and multipliers; then a new search on the deformed surface and the update
//! `lambda <- <lambda - eps g>_+`. The state is accepted when the penetration is within
//! tolerance and the search found no change among the loaded pairs (so the forces the state
//! balances are the ones reported); otherwise Newton runs again.

use super::Contact;
use crate::error::Error;
use crate::fem::equilibrium::{Check, Update};
use crate::fem::newton::{NewtonError, Updates};

/// The contact of one equilibrium solve, and the penetration of its last converged state.
pub struct ContactUpdate<'c> {
    contact: &'c mut Contact,
    penetration: f64,
}

impl<'c> ContactUpdate<'c> {
    /// The loop on `contact`, its pairs searched at the starting state `u`.
    pub fn new(contact: &'c mut Contact, u: &[f64]) -> Self {
        contact.search(u);
        ContactUpdate {
            contact,
            penetration: f64::INFINITY,
        }
    }

    /// The contact energy of the next solve.
    pub fn contact(&self) -> &Contact {
        self.contact
    }
}

impl<S> Update<S> for ContactUpdate<'_> {
    /// `max_augmentations` solves in all.
    fn max_updates(&self) -> usize {
        self.contact.settings.max_augmentations.saturating_sub(1)
    }

    fn update(&mut self, _: &S, u: &mut [f64]) -> Result<Check, NewtonError> {
        let contact = &mut *self.contact;
        let loaded = contact.loaded_pairs(u);
        contact.search(u);
        let unchanged = contact.loaded_pairs(u) == loaded;
        self.penetration = contact.penetration(u);
        contact.augment(u);
        Ok(match self.penetration <= contact.settings.tolerance && unchanged {
            true => Check::Accepted,
            false => Check::Updated,
        })
    }

    fn count(&self, updates: &mut Updates) {
        updates.contact += 1;
    }

    /// A new search on the deformed surface; the multipliers stay (they are updated at
    /// equilibria only).
    fn refresh(&mut self, u: &[f64]) -> bool {
        self.contact.search(u);
        true
    }

    fn exhausted(&self) -> NewtonError {
        NewtonError::Model(Error::Solver(format!(
            "contact: penetration {:.2e} (tolerance {:.1e}) or pairs still changing after {} multiplier updates",
            self.penetration, self.contact.settings.tolerance, self.contact.settings.max_augmentations
        )))
    }
}
