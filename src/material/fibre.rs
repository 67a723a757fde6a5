//! One family of fibres (eq. 3): `f(I4) = mu_f/4 (I4 - lambda_f^2)^2`, `I4 = N . C N`.

use super::{Response, StrainEnergy, Tensor2};
use num_dual::DualNum;

/// A family of fibres along the unit reference direction `direction` (`N3` out of the plane of
/// a plane-strain cut, where `F N = (F11 N1 + F12 N2, F21 N1 + F22 N2, N3)`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FibreFamily {
    pub stiffness: f64,
    pub prestretch: f64,
    pub direction: [f64; 3],
    /// Fibres carry no load while `I4 < prestretch^2`.
    pub tension_only: bool,
}

impl FibreFamily {
    /// `I4 = |F N|^2` for a plane `F`.
    pub fn stretch_invariant(&self, f: &[f64; 4]) -> f64 {
        let [c, s, out] = self.direction;
        let (a, b) = (f[0] * c + f[1] * s, f[2] * c + f[3] * s);
        a * a + b * b + out * out
    }
}

impl StrainEnergy for FibreFamily {
    fn density<D: DualNum<Primitive = f64> + Copy>(&self, f: &[D; 9]) -> D {
        let i4 = super::stretch_invariant(f, self.direction);
        let lf2 = self.prestretch * self.prestretch;
        if self.tension_only && i4.re() < lf2 {
            return D::from(0.0);
        }
        let strain = i4 - lf2;
        strain * strain * (0.25 * self.stiffness)
    }

    /// `P = mu_f (I4 - lambda_f^2) M` and `A = mu_f (2 M (x) M + (I4 - lambda_f^2) I (x) N N)`,
    /// with `M = F N (x) N = dI4/dF / 2`.
    fn plane_response(&self, f: &Tensor2) -> Response {
        let (energy, stress, m, strain) = self.closed_stress(f);
        let n = self.direction;
        let tangent = std::array::from_fn(|p| {
            std::array::from_fn(|q| {
                // dM_iJ/dF_kL = delta_ik N_L N_J.
                let same_row = if p / 2 == q / 2 { n[p % 2] * n[q % 2] } else { 0.0 };
                self.stiffness * (2.0 * m[p] * m[q] + strain * same_row)
            })
        });
        Response {
            energy,
            stress,
            tangent,
        }
    }

    fn plane_stress(&self, f: &Tensor2) -> (f64, Tensor2) {
        let (energy, stress, _, _) = self.closed_stress(f);
        (energy, stress)
    }
}

impl FibreFamily {
    /// `W`, `P`, `M = F N (x) N` and `I4 - lambda_f^2` (all zero for a slack tension-only fibre).
    fn closed_stress(&self, f: &Tensor2) -> (f64, Tensor2, Tensor2, f64) {
        let [c, s, out] = self.direction;
        let (a, b) = (f[0] * c + f[1] * s, f[2] * c + f[3] * s);
        let lf2 = self.prestretch * self.prestretch;
        let strain = a * a + b * b + out * out - lf2;
        if self.tension_only && strain < 0.0 {
            return (0.0, [0.0; 4], [0.0; 4], 0.0);
        }
        let m = [a * c, a * s, b * c, b * s];
        let energy = 0.25 * self.stiffness * strain * strain;
        (energy, m.map(|x| self.stiffness * strain * x), m, strain)
    }
}
