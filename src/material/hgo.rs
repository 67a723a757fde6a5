//! One family of Holzapfel-Gasser-Ogden fibres with dispersion (Gasser, Ogden and Holzapfel
//! 2006): `W = k1 / (2 k2) (exp(k2 E^2) - 1)`, `E = kappa (I1 - 3) + (1 - 3 kappa) (I4 - 1)`,
//! `I4 = N . C N`. `kappa = 0` is a perfectly aligned family, `kappa = 1/3` an isotropic one;
//! `k2 = 0` is the limit `k1/2 E^2`. Tension-only fibres carry no load while `E < 0`.

use super::{Response, StrainEnergy, Tensor2};
use num_dual::DualNum;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HgoFamily {
    pub k1: f64,
    pub k2: f64,
    pub kappa: f64,
    pub direction: [f64; 3],
    pub tension_only: bool,
}

impl HgoFamily {
    /// The strain-like invariant `E` of a full `F` (generic over dual numbers).
    pub fn strain<D: DualNum<Primitive = f64> + Copy>(&self, f: &[D; 9]) -> D {
        let i4 = super::stretch_invariant(f, self.direction);
        let i1 = f.iter().fold(D::zero(), |s, x| s + *x * *x);
        (i1 - 3.0) * self.kappa + (i4 - 1.0) * (1.0 - 3.0 * self.kappa)
    }

    /// `E` of a plane `F` (`F33 = 1`).
    pub fn plane_strain(&self, f: &Tensor2) -> f64 {
        self.strain(&super::plane_gradient(f, 1.0))
    }
}

impl StrainEnergy for HgoFamily {
    fn density<D: DualNum<Primitive = f64> + Copy>(&self, f: &[D; 9]) -> D {
        let e = self.strain(f);
        if self.tension_only && e.re() < 0.0 {
            return D::from(0.0);
        }
        let x = e * e;
        if self.k2 == 0.0 {
            return x * (0.5 * self.k1);
        }
        (x * self.k2).exp_m1() * (0.5 * self.k1 / self.k2)
    }

    fn plane_response(&self, f: &Tensor2) -> Response {
        self.closed_response(f)
    }

    fn plane_stress(&self, f: &Tensor2) -> (f64, Tensor2) {
        let response = self.closed_response(f);
        (response.energy, response.stress)
    }
}

impl HgoFamily {
    /// With `g = dE/dF = 2 kappa F + 2 (1 - 3 kappa) F N (x) N` and `s = k1 E exp(k2 E^2)`:
    /// `P = s g` and `A = k1 exp(k2 E^2) (1 + 2 k2 E^2) g (x) g + s dg/dF`.
    fn closed_response(&self, f: &Tensor2) -> Response {
        let e = self.plane_strain(f);
        if self.tension_only && e < 0.0 {
            return Response {
                energy: 0.0,
                stress: [0.0; 4],
                tangent: [[0.0; 4]; 4],
            };
        }
        let n = self.direction;
        let aligned = 1.0 - 3.0 * self.kappa;
        let fn_ = [f[0] * n[0] + f[1] * n[1], f[2] * n[0] + f[3] * n[1]];
        let g: Tensor2 = std::array::from_fn(|a| 2.0 * self.kappa * f[a] + 2.0 * aligned * fn_[a / 2] * n[a % 2]);
        let growth = (self.k2 * e * e).exp();
        let s = self.k1 * e * growth;
        let curvature = self.k1 * growth * (1.0 + 2.0 * self.k2 * e * e);
        let tangent = std::array::from_fn(|a| {
            std::array::from_fn(|b| {
                // dg_iJ/dF_kL = 2 kappa delta_ik delta_JL + 2 (1 - 3 kappa) delta_ik N_J N_L.
                let same_row = if a / 2 == b / 2 {
                    2.0 * aligned * n[a % 2] * n[b % 2] + if a == b { 2.0 * self.kappa } else { 0.0 }
                } else {
                    0.0
                };
                curvature * g[a] * g[b] + s * same_row
            })
        });
        let energy = if self.k2 == 0.0 {
            0.5 * self.k1 * e * e
        } else {
            0.5 * self.k1 / self.k2 * (self.k2 * e * e).exp_m1()
        };
        Response {
            energy,
            stress: g.map(|x| s * x),
            tangent,
        }
    }
}
