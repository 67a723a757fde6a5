//! Compressible Mooney-Rivlin solid: `W = C1 (Ibar1 - 3) + C2 (Ibar2 - 3) + K/2 (ln J)^2`, with
//! `Ibar1 = J^(-2/3) I1`, `Ibar2 = J^(-4/3) I2`; its shear modulus is `2 (C1 + C2)`.

use super::isotropic::{Invariants, IsotropicEnergy};
use num_dual::DualNum;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MooneyRivlin {
    pub c1: f64,
    pub c2: f64,
    pub bulk: f64,
}

impl IsotropicEnergy for MooneyRivlin {
    fn isotropic_density<D: DualNum<Primitive = f64> + Copy>(&self, inv: &Invariants<D>) -> D {
        let ln_j = inv.j.ln();
        let a = (ln_j * (-2.0 / 3.0)).exp();
        (inv.i1 * a - 3.0) * self.c1 + (inv.i2 * a * a - 3.0) * self.c2 + ln_j * ln_j * (0.5 * self.bulk)
    }
}

super::isotropic::strain_energy_by_invariants!(MooneyRivlin);
