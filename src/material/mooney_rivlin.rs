//! Compressible Mooney-Rivlin solid: `W = C1 (Ibar1 - 3) + C2 (Ibar2 - 3) + K/2 (ln J)^2`, with
//! `Ibar1 = J^(-2/3) I1`, `Ibar2 = J^(-4/3) I2`; its shear modulus is `2 (C1 + C2)`.

use super::isotropic::{invariant_response, invariant_stress, Invariants, IsotropicEnergy};
use super::{Response, StrainEnergy, Tensor2};
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

impl StrainEnergy for MooneyRivlin {
    fn density<D: DualNum<Primitive = f64> + Copy>(&self, f: &[D; 9]) -> D {
        self.isotropic_density(&Invariants::of_gradient(f))
    }

    fn plane_response(&self, f: &Tensor2) -> Response {
        invariant_response(self, f)
    }

    fn plane_stress(&self, f: &Tensor2) -> (f64, Tensor2) {
        invariant_stress(self, f)
    }
}
