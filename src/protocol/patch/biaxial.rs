//! The patch under biaxial load as a system that a continuation in `d` follows: at `d` the
//! tissues at the load's strains `(d, d_3 = R d)` (grown under a growth load), the conditions of
//! [`patch_conditions`] (the sides moved in by `d` and `d_3` under compression, held under
//! growth) with the average gradient they carry across periodic sides, and plain equilibrium
//! (no contact: the patch's surface wrinkles without touching itself).

use super::patch_conditions;
use crate::error::Result;
use crate::fem::added::NoAddedEnergy;
use crate::fem::equilibrium;
use crate::fem::{Assembled, Dirichlet, Newton, NewtonPolicy, NewtonReport, PatchSystem};
use crate::protocol::augmentation::AugmentedRecord;
use crate::protocol::continuation::{plain_linearised, Followed, NoAugmentation};
use crate::protocol::surface::amplitude;

/// A patch whose load's strains are `d` along X and `d_3 = biaxiality d` along Z.
pub struct BiaxialPatch {
    system: PatchSystem,
    biaxiality: f64,
    /// Unknowns held at zero besides the conditions (a plane-strain slab's `u_Z`).
    held: Vec<usize>,
}

impl BiaxialPatch {
    /// `system` under `d_3 = biaxiality d`, with the unknowns `held` at zero.
    pub fn new(system: PatchSystem, biaxiality: f64, held: Vec<usize>) -> Self {
        BiaxialPatch {
            system,
            biaxiality,
            held,
        }
    }

    /// The system.
    pub fn system(&self) -> &PatchSystem {
        &self.system
    }

    /// The system, to be assembled or factorised.
    pub fn system_mut(&mut self) -> &mut PatchSystem {
        &mut self.system
    }

    /// Holds the unknowns `held` at zero besides the conditions.
    pub fn hold(&mut self, held: Vec<usize>) {
        self.held = held;
    }

    /// The system, `d_3 / d` and the held unknowns.
    pub fn into_parts(self) -> (PatchSystem, f64, Vec<usize>) {
        (self.system, self.biaxiality, self.held)
    }

    /// `d_3 / d`.
    pub fn biaxiality(&self) -> f64 {
        self.biaxiality
    }
}

impl Followed for BiaxialPatch {
    type Augmentation = NoAugmentation;

    fn load_to(&mut self, d: f64) -> Result<Dirichlet> {
        let (d3, load) = (self.biaxiality * d, self.system.unloaded_materials().load);
        let (bc, h) = patch_conditions(self.system.mesh(), load.end_shortening(d), load.end_shortening(d3))?;
        self.system.set_average_gradient(h);
        self.system.set_biaxial_load(d, d3);
        if self.held.is_empty() {
            return Ok(bc);
        }
        let mut pairs: Vec<(usize, f64)> = bc.dofs().iter().copied().zip(bc.values().iter().copied()).collect();
        pairs.extend(self.held.iter().map(|&dof| (dof, 0.0)));
        Dirichlet::new(pairs)
    }

    fn load(&self) -> f64 {
        self.system.load()
    }

    fn stored_entries(&self) -> Option<crate::fem::StoredEntries> {
        self.system.stored_entries()
    }

    fn recall_stored_entries(&mut self, entries: Option<crate::fem::StoredEntries>) -> Result<()> {
        self.system.recall_stored_entries(entries)
    }

    fn displacement_unknowns(&self) -> usize {
        self.system.mesh().num_dofs()
    }

    fn amplitude(&self, u: &[f64]) -> f64 {
        amplitude(self.system.mesh(), u)
    }

    fn correct(
        &mut self,
        newton: &mut Newton,
        policy: &NewtonPolicy,
        u: &mut [f64],
        bc: &Dirichlet,
        augmentation: Option<&mut NoAugmentation>,
        _from: (f64, &[f64]),
        _to: (f64, f64),
    ) -> Result<(NewtonReport, Option<AugmentedRecord>)> {
        if let Some(never) = augmentation {
            match *never {}
        }
        Ok((equilibrium::solve(newton, &mut self.system, u, bc, policy)?, None))
    }

    fn minimise(
        &mut self,
        newton: &mut Newton,
        policy: &NewtonPolicy,
        u: &mut [f64],
        (bc, _): (&Dirichlet, f64),
        augmentation: Option<&mut NoAugmentation>,
    ) -> Result<(NewtonReport, Option<AugmentedRecord>)> {
        if let Some(never) = augmentation {
            match *never {}
        }
        let report = equilibrium::minimise(newton, (&mut self.system, u, bc), None, &NoAddedEnergy, policy)?;
        Ok((report, None))
    }

    fn energy(&mut self, u: &[f64], bc: &Dirichlet, augmentation: Option<&NoAugmentation>) -> Result<f64> {
        if let Some(never) = augmentation {
            match *never {}
        }
        Ok(self.system.assemble(u, bc, None, false)?.energy)
    }

    fn linearised(&mut self, u: &[f64], bc: &Dirichlet, with_tangent: bool) -> Result<Assembled> {
        plain_linearised(&mut self.system, u, bc, with_tangent)
    }
}
