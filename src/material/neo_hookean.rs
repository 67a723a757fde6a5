//! Compressible neo-Hookean solid (layer, and matrix of the substrate; eqs. 1-2 as corrected in
//! `docs/model.md`, "Strain energies"): `W = mu/2 (Ibar1 - 3) + K/2 (ln J)^2`, `Ibar1 = J^(-2/3) I1`.

use super::{cofactor, inverse_transpose, FullResponse, Response, StrainEnergy, Tensor2};
use num_dual::DualNum;

/// Compressible neo-Hookean solid with shear modulus `mu` and bulk modulus `bulk`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NeoHookean {
    pub mu: f64,
    pub bulk: f64,
}

impl StrainEnergy for NeoHookean {
    fn density<D: DualNum<Primitive = f64> + Copy>(&self, f: &[D; 9]) -> D {
        let j = super::determinant(f);
        let i1 = f.iter().fold(D::zero(), |s, x| s + *x * *x);
        let isochoric_i1 = i1 * j.powf(-2.0 / 3.0);
        let ln_j = j.ln();
        (isochoric_i1 - 3.0) * (0.5 * self.mu) + ln_j * ln_j * (0.5 * self.bulk)
    }

    fn plane_response(&self, f: &Tensor2) -> Response {
        self.closed_response(f)
    }

    fn plane_stress(&self, f: &Tensor2) -> (f64, Tensor2) {
        let (energy, stress, _) = self.closed_stress(f);
        (energy, stress)
    }

    fn response_3d(&self, f: &[f64; 9]) -> FullResponse {
        self.closed_full_response(f)
    }
}

impl NeoHookean {
    /// `W` and `P = mu a F + (K ln J - mu a I1 / 3) cof F / J`, `a = J^(-2/3)`, `F33 = 1`.
    fn closed_stress(&self, f: &Tensor2) -> (f64, Tensor2, Invariants) {
        let inv = Invariants::of(f);
        let energy = 0.5 * self.mu * (inv.a * inv.i1 - 3.0) + 0.5 * self.bulk * inv.ln_j * inv.ln_j;
        let g = (self.bulk * inv.ln_j - self.mu * inv.a * inv.i1 / 3.0) / inv.j;
        let stress = std::array::from_fn(|i| self.mu * inv.a * f[i] + g * inv.cof[i]);
        (energy, stress, inv)
    }
}

/// What `W` of the neo-Hookean solid depends on, at one plane `F` with `F33 = 1`.
struct Invariants {
    j: f64,
    ln_j: f64,
    /// `I1 = F : F + 1`.
    i1: f64,
    /// `a = J^(-2/3)`.
    a: f64,
    /// `cof F = dJ/dF`.
    cof: Tensor2,
}

impl Invariants {
    fn of(f: &Tensor2) -> Self {
        let j = f[0] * f[3] - f[1] * f[2];
        let ln_j = j.ln();
        Invariants {
            j,
            ln_j,
            i1: f.iter().map(|x| x * x).sum::<f64>() + 1.0,
            a: (-2.0 / 3.0 * ln_j).exp(),
            cof: cofactor(f),
        }
    }
}

impl NeoHookean {
    /// Closed-form `W`, `P` and `A = dP/dF` (differentiating [`NeoHookean::closed_stress`]):
    /// `A = mu a I - 2 mu a / (3 J) (F (x) cof + cof (x) F)
    ///      + (K (1 - ln J) + 5 mu a I1 / 9) / J^2 cof (x) cof + g dcof/dF`,
    /// with `g = (K ln J - mu a I1 / 3) / J` and `dcof/dF` the constant map of `cofactor`.
    fn closed_response(&self, f: &Tensor2) -> Response {
        let (energy, stress, inv) = self.closed_stress(f);
        let Invariants { j, ln_j, i1, a, cof } = inv;
        let g = (self.bulk * ln_j - self.mu * a * i1 / 3.0) / j;
        let mixed = -2.0 * self.mu * a / (3.0 * j);
        let cc = (self.bulk * (1.0 - ln_j) + 5.0 * self.mu * a * i1 / 9.0) / (j * j);
        let mut tangent = [[0.0; 4]; 4];
        for (p, row) in tangent.iter_mut().enumerate() {
            for (q, entry) in row.iter_mut().enumerate() {
                *entry = mixed * (f[p] * cof[q] + cof[p] * f[q]) + cc * cof[p] * cof[q];
            }
            row[p] += self.mu * a;
        }
        // dcof/dF: cof = [F22, -F21, -F12, F11].
        tangent[0][3] += g;
        tangent[3][0] += g;
        tangent[1][2] -= g;
        tangent[2][1] -= g;
        Response {
            energy,
            stress,
            tangent,
        }
    }
}

impl NeoHookean {
    /// The closed form on a full 3x3 `F`, with `H = F^-T`, `a = J^(-2/3)`, `I1 = F : F` and
    /// `g = K ln J - mu a I1 / 3`: `P = mu a F + g H` and
    /// `A_iJkL = mu a delta_ik delta_JL - 2 mu a / 3 (F_iJ H_kL + H_iJ F_kL)
    ///           + (K + 2 mu a I1 / 9) H_iJ H_kL - g H_iL H_kJ`
    /// (`dH_iJ / dF_kL = -H_iL H_kJ`).
    fn closed_full_response(&self, f: &[f64; 9]) -> FullResponse {
        let h = inverse_transpose(f);
        let ln_j = super::determinant(f).ln();
        let a = (-2.0 / 3.0 * ln_j).exp();
        let i1: f64 = f.iter().map(|x| x * x).sum();
        let g = self.bulk * ln_j - self.mu * a * i1 / 3.0;
        let mixed = -2.0 * self.mu * a / 3.0;
        let hh = self.bulk + 2.0 * self.mu * a * i1 / 9.0;
        let mut tangent = [[0.0; 9]; 9];
        for (p, row) in tangent.iter_mut().enumerate() {
            let (i, jj) = (p / 3, p % 3);
            for (q, entry) in row.iter_mut().enumerate() {
                let (k, l) = (q / 3, q % 3);
                *entry = mixed * (f[p] * h[q] + h[p] * f[q]) + hh * h[p] * h[q] - g * h[3 * i + l] * h[3 * k + jj];
            }
            row[p] += self.mu * a;
        }
        FullResponse {
            energy: 0.5 * self.mu * (a * i1 - 3.0) + 0.5 * self.bulk * ln_j * ln_j,
            stress: std::array::from_fn(|p| self.mu * a * f[p] + g * h[p]),
            tangent,
        }
    }
}
