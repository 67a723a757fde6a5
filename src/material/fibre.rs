//! One family of fibres (eq. 3): `f(I4) = mu_f/4 (I4 - lambda_f^2)^2`, `I4 = N . C N`.

use super::StrainEnergy;
use num_dual::DualNum;

/// A family of fibres along the unit reference direction `direction`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FibreFamily {
    pub stiffness: f64,
    pub prestretch: f64,
    pub direction: [f64; 2],
    /// Fibres carry no load while `I4 < prestretch^2`.
    pub tension_only: bool,
}

impl FibreFamily {
    /// `I4 = |F N|^2` for a plain `F`.
    pub fn stretch_invariant(&self, f: &[f64; 4]) -> f64 {
        let [c, s] = self.direction;
        let (a, b) = (f[0] * c + f[1] * s, f[2] * c + f[3] * s);
        a * a + b * b
    }
}

impl StrainEnergy for FibreFamily {
    fn density<D: DualNum<Primitive = f64> + Copy>(&self, f: &[D; 4], _f33: D) -> D {
        let [c, s] = self.direction;
        let (a, b) = (f[0] * c + f[1] * s, f[2] * c + f[3] * s);
        let i4 = a * a + b * b;
        let lf2 = self.prestretch * self.prestretch;
        if self.tension_only && i4.re() < lf2 {
            return D::from(0.0);
        }
        let strain = i4 - lf2;
        strain * strain * (0.25 * self.stiffness)
    }
}
