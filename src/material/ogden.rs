//! Compressible Ogden solid of up to three terms, in the convention of Budday et al. (2017):
//! `W = sum_p 2 mu_p / alpha_p^2 (Lbar1^alpha_p + Lbar2^alpha_p + Lbar3^alpha_p - 3) + K/2 (ln J)^2`,
//! with `Lbar_i = J^(-1/3) lambda_i` the isochoric principal stretches. Each `mu_p > 0` and the
//! shear modulus is `sum_p mu_p`; one term with `alpha = 2` is the neo-Hookean solid.
//! The stretches enter only through `lambda_1^a + lambda_2^a + lambda_3^a`, a symmetric function
//! evaluated smoothly where they coincide ([`Invariants::stretch_power_sum`]).

use super::isotropic::{Invariants, IsotropicEnergy};
use num_dual::DualNum;

/// The most terms an Ogden law may have (the parameters' limit).
pub const MAX_TERMS: usize = crate::parameters::OGDEN_TERMS;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ogden {
    /// `(mu_p, alpha_p)`; only the first `terms` are used.
    pub coefficients: [(f64, f64); MAX_TERMS],
    pub terms: usize,
    pub bulk: f64,
}

impl Ogden {
    /// An Ogden law of the given `(mu_p, alpha_p)` pairs (at most [`MAX_TERMS`]).
    pub fn new(pairs: &[(f64, f64)], bulk: f64) -> Self {
        let mut coefficients = [(0.0, 1.0); MAX_TERMS];
        coefficients[..pairs.len()].copy_from_slice(pairs);
        Ogden {
            coefficients,
            terms: pairs.len(),
            bulk,
        }
    }

    pub fn pairs(&self) -> &[(f64, f64)] {
        &self.coefficients[..self.terms]
    }
}

impl IsotropicEnergy for Ogden {
    fn isotropic_density<D: DualNum<Primitive = f64> + Copy>(&self, inv: &Invariants<D>) -> D {
        let ln_j = inv.j.ln();
        let mut w = ln_j * ln_j * (0.5 * self.bulk);
        for &(mu, alpha) in self.pairs() {
            let stretches = inv.stretch_power_sum(alpha);
            let isochoric = (ln_j * (-alpha / 3.0)).exp();
            w += (stretches * isochoric - 3.0) * (2.0 * mu / (alpha * alpha));
        }
        w
    }
}

super::isotropic::strain_energy_by_invariants!(Ogden);
