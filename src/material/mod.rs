//! Hyperelastic materials in plane strain: one strain-energy function per law, written once and
//! generic over dual numbers, so that the first Piola-Kirchhoff stress `P = dW/dF` and the
//! tangent `A = d2W/dF dF` follow by automatic differentiation (`num-dual`). The homogeneous
//! state, the stability analysis and the finite elements all call this one code path.
//!
//! Conventions: `F` is stored row-major as `[F11, F12, F21, F22]` (index `2 i + J` for `F_iJ`),
//! with `F33 = 1`; invariants are the 3D ones (`J = det F`, `I1 = tr C + 1`).

mod fibre;
mod neo_hookean;
mod tissue;

pub use fibre::FibreFamily;
pub use neo_hookean::NeoHookean;
pub use tissue::{Bilayer, FibreReinforced, Tissue};

use crate::error::{Error, Result};
use nalgebra::SVector;
use num_dual::{gradient, hessian, Dual2SVec64, DualNum, DualSVec64};

/// A plane deformation gradient `[F11, F12, F21, F22]`.
pub type Tensor2 = [f64; 4];
/// A fourth-order tensor in plane strain, `A[2i+J][2k+L] = d2W / dF_iJ dF_kL`.
pub type Tensor4 = [[f64; 4]; 4];

/// A strain-energy density. `f33` is the out-of-plane stretch: 1 in plane strain; it is a
/// variable only so that the out-of-plane stress `sigma_33` follows by differentiation too.
pub trait StrainEnergy: Send + Sync {
    fn density<D: DualNum<Primitive = f64> + Copy>(&self, f: &[D; 4], f33: D) -> D;
}

/// Energy, stress and tangent at one deformation.
#[derive(Clone, Copy, Debug)]
pub struct Response {
    pub energy: f64,
    /// First Piola-Kirchhoff stress `P_iJ`.
    pub stress: Tensor2,
    /// `A_iJkL = dP_iJ / dF_kL`.
    pub tangent: Tensor4,
}

/// Cauchy stress `[sigma_11, sigma_12, sigma_22, sigma_33]` (symmetric, in-plane plus normal).
pub type CauchyStress = [f64; 4];

/// Determinant of a plane deformation gradient (`F33 = 1`).
pub fn jacobian(f: &Tensor2) -> f64 {
    f[0] * f[3] - f[1] * f[2]
}

fn check_jacobian(f: &Tensor2) -> Result<f64> {
    let j = jacobian(f);
    if j > 0.0 && j.is_finite() {
        Ok(j)
    } else {
        Err(Error::NonPositiveJacobian { jacobian: j })
    }
}

/// Energy, stress and tangent of any strain energy; `J <= 0` is an error, never a NaN.
pub trait Hyperelastic: StrainEnergy {
    /// `W(F)`.
    fn energy(&self, f: &Tensor2) -> Result<f64> {
        check_jacobian(f)?;
        Ok(self.density(f, 1.0))
    }

    /// First Piola-Kirchhoff stress `P = dW/dF`.
    fn first_piola(&self, f: &Tensor2) -> Result<Tensor2> {
        check_jacobian(f)?;
        let (_, g) = gradient(
            |x: SVector<DualSVec64<4>, 4>| self.density(&[x[0], x[1], x[2], x[3]], DualSVec64::from_re(1.0)),
            &SVector::from(*f),
        );
        Ok([g[0], g[1], g[2], g[3]])
    }

    /// Energy, `P` and the tangent `A = d2W/dF dF` in one pass.
    fn response(&self, f: &Tensor2) -> Result<Response> {
        check_jacobian(f)?;
        let (w, g, h) = hessian(
            |x: SVector<Dual2SVec64<4>, 4>| self.density(&[x[0], x[1], x[2], x[3]], Dual2SVec64::from_re(1.0)),
            &SVector::from(*f),
        );
        let mut tangent = [[0.0; 4]; 4];
        for (a, row) in tangent.iter_mut().enumerate() {
            for (b, entry) in row.iter_mut().enumerate() {
                *entry = h[(a, b)];
            }
        }
        Ok(Response {
            energy: w,
            stress: [g[0], g[1], g[2], g[3]],
            tangent,
        })
    }

    /// Cauchy stress `sigma = P F^T / J`, with `sigma_33 = P_33 / J` from `dW/dF33`.
    fn cauchy(&self, f: &Tensor2) -> Result<CauchyStress> {
        let j = check_jacobian(f)?;
        let (_, p) = gradient(
            |x: SVector<DualSVec64<5>, 5>| self.density(&[x[0], x[1], x[2], x[3]], x[4]),
            &SVector::from([f[0], f[1], f[2], f[3], 1.0]),
        );
        Ok([
            (p[0] * f[0] + p[1] * f[1]) / j,
            (p[0] * f[2] + p[1] * f[3]) / j,
            (p[2] * f[2] + p[3] * f[3]) / j,
            p[4] / j,
        ])
    }
}

impl<M: StrainEnergy> Hyperelastic for M {}

/// Von Mises equivalent stress of a Cauchy stress `[s11, s12, s22, s33]`.
pub fn von_mises(s: &CauchyStress) -> f64 {
    let [s11, s12, s22, s33] = *s;
    (0.5 * ((s11 - s22).powi(2) + (s22 - s33).powi(2) + (s33 - s11).powi(2)) + 3.0 * s12 * s12).sqrt()
}

#[cfg(test)]
mod tests;
