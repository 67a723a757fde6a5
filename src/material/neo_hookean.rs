//! Compressible neo-Hookean solid (layer, and matrix of the substrate; NOTES.md form of eqs. 1-2):
//! `W = mu/2 (Ibar1 - 3) + K/2 (ln J)^2`, `Ibar1 = J^(-2/3) I1`.

use super::StrainEnergy;
use num_dual::DualNum;

/// Compressible neo-Hookean solid with shear modulus `mu` and bulk modulus `bulk`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NeoHookean {
    pub mu: f64,
    pub bulk: f64,
}

impl StrainEnergy for NeoHookean {
    fn density<D: DualNum<Primitive = f64> + Copy>(&self, f: &[D; 4], f33: D) -> D {
        let j = (f[0] * f[3] - f[1] * f[2]) * f33;
        let i1 = f[0] * f[0] + f[1] * f[1] + f[2] * f[2] + f[3] * f[3] + f33 * f33;
        let isochoric_i1 = i1 * j.powf(-2.0 / 3.0);
        let ln_j = j.ln();
        (isochoric_i1 - 3.0) * (0.5 * self.mu) + ln_j * ln_j * (0.5 * self.bulk)
    }
}
