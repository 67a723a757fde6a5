//! Compressible Gent solid: `W = -mu Jm/2 ln(1 - (Ibar1 - 3)/Jm) + K/2 (ln J)^2`, with
//! `Ibar1 = J^(-2/3) I1`; `mu` is the shear modulus and `Jm` bounds `Ibar1 - 3` (the chains'
//! limiting extensibility). It tends to neo-Hookean as `Jm -> inf`.

use super::isotropic::{Invariants, IsotropicEnergy};
use crate::error::{Error, Result};
use num_dual::DualNum;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Gent {
    pub mu: f64,
    pub jm: f64,
    pub bulk: f64,
}

impl Gent {
    /// `(Ibar1 - 3) / Jm`, which must stay below 1.
    fn extension<D: DualNum<Primitive = f64> + Copy>(&self, inv: &Invariants<D>) -> D {
        (inv.i1 * (inv.j.ln() * (-2.0 / 3.0)).exp() - 3.0) / self.jm
    }

    /// An error at a deformation beyond the limiting extensibility (where `W` is infinite).
    fn check_extensibility(&self, f: &[f64; 9]) -> Result<()> {
        let x = self.extension(&Invariants::of_gradient(f));
        if x < 1.0 {
            Ok(())
        } else {
            Err(Error::BeyondExtensibility { ratio: x })
        }
    }
}

impl IsotropicEnergy for Gent {
    fn admissible(&self, f: &[f64; 9]) -> Result<()> {
        self.check_extensibility(f)
    }

    fn bounded_domain(&self) -> bool {
        true
    }

    fn isotropic_density<D: DualNum<Primitive = f64> + Copy>(&self, inv: &Invariants<D>) -> D {
        let ln_j = inv.j.ln();
        let x = self.extension(inv);
        (-x).ln_1p() * (-0.5 * self.mu * self.jm) + ln_j * ln_j * (0.5 * self.bulk)
    }
}

super::isotropic::strain_energy_by_invariants!(Gent);
