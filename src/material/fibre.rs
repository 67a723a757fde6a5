//! One family of fibres (eq. 3): `f(I4) = mu_f/4 (I4 - lambda_f^2)^2`, `I4 = N . C N`.

use super::{FullResponse, Response, StrainEnergy, Tensor2};
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

    /// The plane closed form on a full 3x3 `F`: `M_iJ = (F N)_i N_J`,
    /// `A_iJkL = mu_f (2 M_iJ M_kL + (I4 - lambda_f^2) delta_ik N_J N_L)`.
    fn response_3d(&self, f: &[f64; 9]) -> FullResponse {
        let n = self.direction;
        let fn_: [f64; 3] = std::array::from_fn(|i| f[3 * i] * n[0] + f[3 * i + 1] * n[1] + f[3 * i + 2] * n[2]);
        let strain = fn_.iter().map(|x| x * x).sum::<f64>() - self.prestretch * self.prestretch;
        if self.tension_only && strain < 0.0 {
            return FullResponse {
                energy: 0.0,
                stress: [0.0; 9],
                tangent: [[0.0; 9]; 9],
            };
        }
        let m: [f64; 9] = std::array::from_fn(|p| fn_[p / 3] * n[p % 3]);
        let tangent = std::array::from_fn(|p| {
            std::array::from_fn(|q| {
                let same_row = if p / 3 == q / 3 { n[p % 3] * n[q % 3] } else { 0.0 };
                self.stiffness * (2.0 * m[p] * m[q] + strain * same_row)
            })
        });
        FullResponse {
            energy: 0.25 * self.stiffness * strain * strain,
            stress: m.map(|x| self.stiffness * strain * x),
            tangent,
        }
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
