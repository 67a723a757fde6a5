//! What a continuation in `d` needs of the system it follows ([`Followed`]): to be put at a load,
//! its equilibrium corrected from a predictor (by Newton's iteration or by minimising the
//! energy), and its energy. The bilayer strip follows with contact and stabilisation
//! ([`Augmentation`]); the three-dimensional patch ([`crate::protocol::patch::BiaxialPatch`]) without.

use crate::error::{Error, Result};
use crate::fem::added::NoAddedEnergy;
use crate::fem::contact::Contact;
use crate::fem::element::Registry;
use crate::fem::equilibrium;
use crate::fem::{Assembled, Dirichlet, Newton, NewtonPolicy, NewtonReport, StoredEntries, System};
use crate::mesh::ElementKind;
use crate::protocol::augmentation::{Augmentation, AugmentationMemory, AugmentedRecord};
use crate::protocol::surface::amplitude;
use crate::protocol::Loading;

/// A system that a continuation in `d` follows.
pub trait Followed {
    /// What the path adds to plain equilibrium (contact, stabilisation), if the system has any.
    type Augmentation: Augmenting;

    /// Puts the system at the load `d` and returns the boundary conditions there.
    fn load_to(&mut self, d: f64) -> Result<Dirichlet>;

    /// The load the system is at.
    fn load(&self) -> f64;

    /// What rebuilds its tangents' sparsity with the same stored entries (which decide their
    /// ordering, and so their round-off): part of a path's state ([`super::PathState`]).
    fn stored_entries(&self) -> Option<StoredEntries>;

    /// Back to stored entries it had ([`Followed::stored_entries`]).
    fn recall_stored_entries(&mut self, entries: Option<StoredEntries>) -> Result<()>;

    /// The displacement unknowns (the leading entries of a state; multipliers may follow).
    fn displacement_unknowns(&self) -> usize;

    /// The wrinkle amplitude `A = (max y - min y) / 2` of the top surface of the state `u`.
    fn amplitude(&self, u: &[f64]) -> f64;

    /// Equilibrium at `d` (prescribed by `bc`) from the predictor `u`, stepping from the
    /// converged `from` with the step control at `control_step`, with the augmentation if
    /// there is one; on failure `u` is the predictor again.
    #[allow(clippy::too_many_arguments)]
    fn correct(
        &mut self,
        newton: &mut Newton,
        policy: &NewtonPolicy,
        u: &mut [f64],
        bc: &Dirichlet,
        augmentation: Option<&mut Self::Augmentation>,
        from: (f64, &[f64]),
        to: (f64, f64),
    ) -> Result<(NewtonReport, Option<AugmentedRecord>)>;

    /// A local minimum of the energy at `d` (prescribed by `bc`) from `u`, with the
    /// augmentation's contact if there is one.
    fn minimise(
        &mut self,
        newton: &mut Newton,
        policy: &NewtonPolicy,
        u: &mut [f64],
        at: (&Dirichlet, f64),
        augmentation: Option<&mut Self::Augmentation>,
    ) -> Result<(NewtonReport, Option<AugmentedRecord>)>;

    /// The total energy at `u` with `bc` prescribed: the strain energy plus the augmentation's
    /// contact terms.
    fn energy(&mut self, u: &[f64], bc: &Dirichlet, augmentation: Option<&Self::Augmentation>) -> Result<f64>;

    /// The residual of plain equilibrium (no augmentation) on the free unknowns at `u` with
    /// `bc` prescribed, and its tangent `K_ff` if `with_tangent`: what a continuation that moves
    /// `d` with the unknowns corrects with ([`super::ArcLength`]).
    fn linearised(&mut self, u: &[f64], bc: &Dirichlet, with_tangent: bool) -> Result<Assembled>;
}

/// [`Followed::linearised`] of a finite-element system: its assembly, refused for the mixed
/// element's multipliers, whose outer loop only [`equilibrium::solve`] runs.
pub(crate) fn plain_linearised<const D: usize, const N: usize, const Q: usize, const U: usize>(
    system: &mut crate::fem::System<D, N, Q, U>,
    u: &[f64],
    bc: &Dirichlet,
    with_tangent: bool,
) -> Result<Assembled>
where
    ElementKind: Registry<D, N, Q, U>,
{
    if system.has_multipliers() {
        return Err(Error::invalid(
            "continuation",
            "arc-length",
            "displacement (arc length follows nearly incompressible tissue, not exactly incompressible)",
        ));
    }
    system.assemble(u, bc, None, with_tangent)
}

/// What a continuation asks of its augmentation besides the solves.
pub trait Augmenting {
    /// What [`Augmenting::save`] keeps: the state a discarded trial restores.
    type Saved;
    /// The inertia counted in the background for the last accepted state.
    fn next_inertia(&mut self) -> Option<usize>;
    /// Notes the negative pivots of the state the path accepted (`None` where not yet known).
    fn note_accepted(&mut self, _negative_pivots: Option<usize>) {}
    /// Frees the factorisations it holds.
    fn release_factorisation(&mut self);
    /// The state a trial may change.
    fn save(&self) -> Self::Saved;
    /// Back to a saved state.
    fn restore(&mut self, saved: Self::Saved);
    /// What a resumed path needs of it ([`super::PathState`]).
    fn memory(&self) -> AugmentationMemory;
    /// Back to a state it had ([`Augmenting::memory`]).
    fn recall(&mut self, memory: AugmentationMemory) -> Result<()>;
}

impl Augmenting for Augmentation {
    type Saved = Option<Contact>;

    fn next_inertia(&mut self) -> Option<usize> {
        Augmentation::next_inertia(self)
    }

    fn note_accepted(&mut self, negative_pivots: Option<usize>) {
        Augmentation::note_accepted(self, negative_pivots)
    }

    fn release_factorisation(&mut self) {
        Augmentation::release_factorisation(self)
    }

    fn save(&self) -> Option<Contact> {
        self.contact.clone()
    }

    fn restore(&mut self, saved: Option<Contact>) {
        self.contact = saved;
    }

    fn memory(&self) -> AugmentationMemory {
        Augmentation::memory(self)
    }

    fn recall(&mut self, memory: AugmentationMemory) -> Result<()> {
        Augmentation::recall(self, memory)
    }
}

/// No augmentation: a system followed by plain equilibrium. It has no value, so a path of such
/// a system never holds one.
pub enum NoAugmentation {}

impl Augmenting for NoAugmentation {
    type Saved = ();

    fn next_inertia(&mut self) -> Option<usize> {
        match *self {}
    }

    fn release_factorisation(&mut self) {
        match *self {}
    }

    fn save(&self) {
        match *self {}
    }

    fn restore(&mut self, _: ()) {
        match *self {}
    }

    fn memory(&self) -> AugmentationMemory {
        match *self {}
    }

    fn recall(&mut self, _: AugmentationMemory) -> Result<()> {
        match *self {}
    }
}

impl Followed for System {
    type Augmentation = Augmentation;

    fn load_to(&mut self, d: f64) -> Result<Dirichlet> {
        Loading::load_to(self, d)
    }

    fn load(&self) -> f64 {
        System::load(self)
    }

    fn stored_entries(&self) -> Option<StoredEntries> {
        System::stored_entries(self)
    }

    fn recall_stored_entries(&mut self, entries: Option<StoredEntries>) -> Result<()> {
        System::recall_stored_entries(self, entries)
    }

    fn displacement_unknowns(&self) -> usize {
        self.mesh().num_dofs()
    }

    fn amplitude(&self, u: &[f64]) -> f64 {
        amplitude(self.mesh(), u)
    }

    fn correct(
        &mut self,
        newton: &mut Newton,
        policy: &NewtonPolicy,
        u: &mut [f64],
        bc: &Dirichlet,
        augmentation: Option<&mut Augmentation>,
        from: (f64, &[f64]),
        to: (f64, f64),
    ) -> Result<(NewtonReport, Option<AugmentedRecord>)> {
        match augmentation {
            Some(augmentation) => {
                let (report, record) = augmentation.solve(newton, policy, self, u, bc, from, to)?;
                Ok((report, Some(record)))
            }
            None => Ok((equilibrium::solve(newton, self, u, bc, policy)?, None)),
        }
    }

    fn minimise(
        &mut self,
        newton: &mut Newton,
        policy: &NewtonPolicy,
        u: &mut [f64],
        (bc, d): (&Dirichlet, f64),
        augmentation: Option<&mut Augmentation>,
    ) -> Result<(NewtonReport, Option<AugmentedRecord>)> {
        match augmentation {
            Some(augmentation) => {
                let (report, record) = augmentation.minimise(newton, policy, self, u, (bc, d))?;
                Ok((report, Some(record)))
            }
            None => {
                let report = equilibrium::minimise(newton, (self, u, bc), None, &NoAddedEnergy, policy)?;
                Ok((report, None))
            }
        }
    }

    fn energy(&mut self, u: &[f64], bc: &Dirichlet, augmentation: Option<&Augmentation>) -> Result<f64> {
        match augmentation {
            Some(augmentation) => augmentation.energy(self, u, bc),
            None => Ok(self.assemble(u, bc, None, false)?.energy),
        }
    }

    fn linearised(&mut self, u: &[f64], bc: &Dirichlet, with_tangent: bool) -> Result<Assembled> {
        plain_linearised(self, u, bc, with_tangent)
    }
}
