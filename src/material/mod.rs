//! Hyperelastic materials in plane strain: one strain-energy function per law (one file each),
//! written once and generic over dual numbers. The first Piola-Kirchhoff stress `P = dW/dF` and the tangent
//! `A = d2W/dF dF` of each law are closed forms derived from that energy
//! ([`StrainEnergy::plane_response`]); automatic differentiation (`num-dual`) of the same energy
//! is the default for a law without them and the independent check of them in the tests. The
//! homogeneous state, the stability analysis and the finite elements all call this one code path.
//!
//! Conventions: every energy is written on the full 3x3 `F` (row-major, index `3 i + J` for
//! `F_iJ`); plane strain is its restriction `F = [[F2, 0], [0, 1]]`, with `F2` stored row-major
//! as `[F11, F12, F21, F22]` (index `2 i + J`) and the 3D invariants (`J = det F`,
//! `I1 = tr C + 1`). The plane stress and tangent, which the finite elements call, have their
//! own fast evaluations; [`full_response`] gives the 3D ones.

pub mod ellipticity;
mod fibre;
mod gent;
mod growth;
mod hgo;
pub mod isotropic;
mod laws;
mod mooney_rivlin;
mod neo_hookean;
mod ogden;
mod point;
mod tissue;

pub use fibre::FibreFamily;
pub use gent::Gent;
pub use growth::{Grown, Growth};
pub use hgo::HgoFamily;
pub use laws::{Fibre, Matrix};
pub use mooney_rivlin::MooneyRivlin;
pub use neo_hookean::NeoHookean;
pub use ogden::{Ogden, MAX_TERMS as OGDEN_MAX_TERMS};
pub use point::{
    flat, full_gradient, inverse_transpose_of, nested, point_cauchy, point_response, point_stress, pressured_response,
    pressured_stress, PointResponse,
};
pub use tissue::{Bilayer, FibreReinforced, Tissue, VolumetricSplit};

use crate::error::{Error, Result};
use nalgebra::SVector;
use num_dual::{gradient, hessian, Dual2SVec64, DualNum, DualSVec64};

/// A plane deformation gradient `[F11, F12, F21, F22]`.
pub type Tensor2 = [f64; 4];
/// A fourth-order tensor in plane strain, `A[2i+J][2k+L] = d2W / dF_iJ dF_kL`.
pub type Tensor4 = [[f64; 4]; 4];

/// A strain-energy density on the full 3x3 deformation gradient.
pub trait StrainEnergy: Send + Sync {
    fn density<D: DualNum<Primitive = f64> + Copy>(&self, f: &[D; 9]) -> D;

    /// `W`, `P` and `A` in plane strain (`F33 = 1`) at a gradient with `J > 0`: by second-order
    /// automatic differentiation of [`StrainEnergy::density`] unless a law overrides it with
    /// its closed form.
    fn plane_response(&self, f: &Tensor2) -> Response {
        differentiated_response(self, f)
    }

    /// `W` and `P` in plane strain (`F33 = 1`) at a gradient with `J > 0`, without the tangent.
    fn plane_stress(&self, f: &Tensor2) -> (f64, Tensor2) {
        differentiated_stress(self, f)
    }

    /// `W`, `P` and `A` of a full 3x3 `F` (with `J > 0`): by hyper-dual differentiation of
    /// [`StrainEnergy::density`] unless a law overrides it with its closed form. The checked
    /// entry point is [`full_response`].
    fn response_3d(&self, f: &[f64; 9]) -> FullResponse {
        differentiated_full_response(self, f)
    }

    /// An error at a full 3x3 gradient (with `J > 0`) outside the law's domain, where its
    /// energy is infinite; every gradient is admissible unless a law says otherwise.
    fn admissible(&self, _f: &[f64; 9]) -> Result<()> {
        Ok(())
    }

    /// Whether some gradient with `J > 0` lies outside the law's domain (a limiting
    /// extensibility); analyses look for the end of the domain only then.
    fn bounded_domain(&self) -> bool {
        false
    }
}

/// `W`, `P = dW/dF` and `A = d2W/dF dF` of `density` by hyper-dual numbers (`F33 = 1`).
pub fn differentiated_response<M: StrainEnergy + ?Sized>(m: &M, f: &Tensor2) -> Response {
    let (w, g, h) = hessian(
        |x: SVector<Dual2SVec64<4>, 4>| {
            m.density(&plane_gradient(&[x[0], x[1], x[2], x[3]], Dual2SVec64::from_re(1.0)))
        },
        &SVector::from(*f),
    );
    Response {
        energy: w,
        stress: [g[0], g[1], g[2], g[3]],
        tangent: std::array::from_fn(|a| std::array::from_fn(|b| h[(a, b)])),
    }
}

/// `W` and `P = dW/dF` of `density` by dual numbers (`F33 = 1`).
pub fn differentiated_stress<M: StrainEnergy + ?Sized>(m: &M, f: &Tensor2) -> (f64, Tensor2) {
    let (w, g) = gradient(
        |x: SVector<DualSVec64<4>, 4>| m.density(&plane_gradient(&[x[0], x[1], x[2], x[3]], DualSVec64::from_re(1.0))),
        &SVector::from(*f),
    );
    (w, [g[0], g[1], g[2], g[3]])
}

/// The full gradient `[[F2, 0], [0, F33]]` of a plane one.
pub fn plane_gradient<D: DualNum<Primitive = f64> + Copy>(f: &[D; 4], f33: D) -> [D; 9] {
    let zero = D::zero();
    [f[0], f[1], zero, f[2], f[3], zero, zero, zero, f33]
}

/// `det F` of a full gradient.
pub fn determinant<D: DualNum<Primitive = f64> + Copy>(f: &[D; 9]) -> D {
    f[0] * (f[4] * f[8] - f[5] * f[7]) - f[1] * (f[3] * f[8] - f[5] * f[6]) + f[2] * (f[3] * f[7] - f[4] * f[6])
}

/// `I4 = |F N|^2` of a full gradient along the unit direction `N = (n1, n2, n3)`.
pub fn stretch_invariant<D: DualNum<Primitive = f64> + Copy>(f: &[D; 9], n: [f64; 3]) -> D {
    (0..3).fold(D::zero(), |s, i| {
        let a = f[3 * i] * n[0] + f[3 * i + 1] * n[1] + f[3 * i + 2] * n[2];
        s + a * a
    })
}

/// Energy, stress and tangent of a full 3x3 `F`: `P_iJ` at index `3 i + J`, `A_iJkL =
/// d2W / dF_iJ dF_kL` at `[3 i + J][3 k + L]`.
pub type FullResponse = ResponseOf<9>;

/// `W`, `P` and `A` of a full 3x3 `F` (with `J > 0`): the moduli of any law at any state, for
/// analyses beyond plane strain. A closed form where the law has one
/// ([`StrainEnergy::response_3d`]), hyper-dual differentiation of its energy otherwise.
pub fn full_response<M: StrainEnergy + ?Sized>(m: &M, f: &[f64; 9]) -> Result<FullResponse> {
    let j = determinant(f);
    if !(j > 0.0 && j.is_finite()) {
        return Err(Error::NonPositiveJacobian { jacobian: j });
    }
    m.admissible(f)?;
    let response = m.response_3d(f);
    if !response.energy.is_finite() {
        return Err(Error::NonFinite("the energy of a full deformation gradient".into()));
    }
    Ok(response)
}

/// `W`, `P = dW/dF` and `A = d2W/dF dF` of `density` on a full 3x3 `F` by hyper-dual numbers.
pub fn differentiated_full_response<M: StrainEnergy + ?Sized>(m: &M, f: &[f64; 9]) -> FullResponse {
    let (energy, g, h) = hessian(
        |x: SVector<Dual2SVec64<9>, 9>| m.density(&std::array::from_fn(|i| x[i])),
        &SVector::from(*f),
    );
    FullResponse {
        energy,
        stress: std::array::from_fn(|a| g[a]),
        tangent: std::array::from_fn(|a| std::array::from_fn(|b| h[(a, b)])),
    }
}

/// `F^-T` of a full gradient (`cof F / J`).
pub(crate) fn inverse_transpose(f: &[f64; 9]) -> [f64; 9] {
    let cofactor = [
        f[4] * f[8] - f[5] * f[7],
        f[5] * f[6] - f[3] * f[8],
        f[3] * f[7] - f[4] * f[6],
        f[2] * f[7] - f[1] * f[8],
        f[0] * f[8] - f[2] * f[6],
        f[1] * f[6] - f[0] * f[7],
        f[1] * f[5] - f[2] * f[4],
        f[2] * f[3] - f[0] * f[5],
        f[0] * f[4] - f[1] * f[3],
    ];
    let j = determinant(f);
    cofactor.map(|c| c / j)
}

/// Adds the terms of a pressure `p` conjugate to `ln J` (an energy `p ln J`, the multiplier of
/// incompressibility or the mixed element's pressure): `P += p F^-T` and, when given,
/// `A += p d(F^-T)/dF = p ((d cof/dF) / J - F^-T (x) F^-T)`.
#[inline(always)]
pub fn add_pressure(stress: &mut Tensor2, tangent: Option<&mut Tensor4>, f: &Tensor2, p: f64) {
    let j = jacobian(f);
    let inverse_transpose = cofactor(f).map(|c| c / j);
    for (s, it) in stress.iter_mut().zip(&inverse_transpose) {
        *s += p * it;
    }
    if let Some(tangent) = tangent {
        for (row, &a) in tangent.iter_mut().zip(&inverse_transpose) {
            for (entry, &b) in row.iter_mut().zip(&inverse_transpose) {
                *entry -= p * a * b;
            }
        }
        // d cof/dF of cof = [F22, -F21, -F12, F11].
        tangent[0][3] += p / j;
        tangent[3][0] += p / j;
        tangent[1][2] -= p / j;
        tangent[2][1] -= p / j;
    }
}

/// [`add_pressure`] on a full 3x3 gradient: `P += p F^-T` and, when given,
/// `A_iJkL += p (e_ikm e_JLN F_mN / J - F^-T_iJ F^-T_kL)`, with `d cof(F)_iJ / dF_kL =
/// e_ikm e_JLN F_mN` (`e` the permutation symbol).
pub fn add_pressure_full(stress: &mut [f64; 9], tangent: Option<&mut [[f64; 9]; 9]>, f: &[f64; 9], p: f64) {
    let j = determinant(f);
    let it = inverse_transpose(f);
    for (s, a) in stress.iter_mut().zip(&it) {
        *s += p * a;
    }
    if let Some(tangent) = tangent {
        let epsilon = |a: usize, b: usize, c: usize| -> f64 {
            match (a, b, c) {
                (0, 1, 2) | (1, 2, 0) | (2, 0, 1) => 1.0,
                (0, 2, 1) | (2, 1, 0) | (1, 0, 2) => -1.0,
                _ => 0.0,
            }
        };
        for (i, cap_j, k, cap_l) in (0..81).map(|n| (n / 27, (n / 9) % 3, (n / 3) % 3, n % 3)) {
            let mut cofactor_derivative = 0.0;
            for (m, cap_n) in (0..9).map(|n| (n / 3, n % 3)) {
                cofactor_derivative += epsilon(i, k, m) * epsilon(cap_j, cap_l, cap_n) * f[3 * m + cap_n];
            }
            // d(cof_iJ / J) / dF_kL = (d cof_iJ / dF_kL) / J - F^-T_iJ F^-T_kL.
            tangent[3 * i + cap_j][3 * k + cap_l] +=
                p * (cofactor_derivative / j - it[3 * i + cap_j] * it[3 * k + cap_l]);
        }
    }
}

/// `dJ/dF`, the cofactor of a plane `F`: `[F22, -F21, -F12, F11]`.
pub(crate) fn cofactor(f: &Tensor2) -> Tensor2 {
    [f[3], -f[2], -f[1], f[0]]
}

/// Energy, stress and tangent at one deformation, of `N` gradient components.
#[derive(Clone, Copy, Debug)]
pub struct ResponseOf<const N: usize> {
    pub energy: f64,
    /// First Piola-Kirchhoff stress `P_iJ`.
    pub stress: [f64; N],
    /// `A_iJkL = dP_iJ / dF_kL`.
    pub tangent: [[f64; N]; N],
}

/// Energy, stress and tangent in plane strain.
pub type Response = ResponseOf<4>;

impl<const N: usize> ResponseOf<N> {
    /// `self + weight other` (a mixture of energies).
    pub(crate) fn plus(self, other: Self, weight: f64) -> Self {
        ResponseOf {
            energy: self.energy + weight * other.energy,
            stress: std::array::from_fn(|a| self.stress[a] + weight * other.stress[a]),
            tangent: std::array::from_fn(|a| {
                std::array::from_fn(|b| self.tangent[a][b] + weight * other.tangent[a][b])
            }),
        }
    }

    /// This response times `weight`.
    pub(crate) fn scaled(self, weight: f64) -> Self {
        ResponseOf {
            energy: 0.0,
            stress: [0.0; N],
            tangent: [[0.0; N]; N],
        }
        .plus(self, weight)
    }
}

/// Cauchy stress `[sigma_11, sigma_12, sigma_22, sigma_33]` (symmetric, in-plane plus normal).
pub type CauchyStress = [f64; 4];

/// Determinant of a plane deformation gradient (`F33 = 1`).
pub fn jacobian(f: &Tensor2) -> f64 {
    f[0] * f[3] - f[1] * f[2]
}

/// `J`, or an error where the law has no finite energy (`J <= 0`, or outside its domain).
fn check_state<M: StrainEnergy + ?Sized>(m: &M, f: &Tensor2) -> Result<f64> {
    let j = jacobian(f);
    if !(j > 0.0 && j.is_finite()) {
        return Err(Error::NonPositiveJacobian { jacobian: j });
    }
    m.admissible(&plane_gradient(f, 1.0))?;
    Ok(j)
}

/// Energy, stress and tangent of any strain energy; `J <= 0`, or a gradient outside the law's
/// domain, is an error, never a NaN.
pub trait Hyperelastic: StrainEnergy {
    /// `W(F)`.
    fn energy(&self, f: &Tensor2) -> Result<f64> {
        check_state(self, f)?;
        Ok(self.density(&plane_gradient(f, 1.0)))
    }

    /// First Piola-Kirchhoff stress `P = dW/dF`.
    fn first_piola(&self, f: &Tensor2) -> Result<Tensor2> {
        Ok(self.energy_and_stress(f)?.1)
    }

    /// `W` and `P = dW/dF` in one pass.
    fn energy_and_stress(&self, f: &Tensor2) -> Result<(f64, Tensor2)> {
        check_state(self, f)?;
        Ok(self.plane_stress(f))
    }

    /// Energy, `P` and the tangent `A = d2W/dF dF` in one pass.
    fn response(&self, f: &Tensor2) -> Result<Response> {
        check_state(self, f)?;
        Ok(self.plane_response(f))
    }

    /// Energy, `P` and `A` at a full 3x3 `F` ([`full_response`]): the same energy in three
    /// dimensions, of which the plane methods above are the restriction `F33 = 1`.
    fn full(&self, f: &[f64; 9]) -> Result<FullResponse> {
        full_response(self, f)
    }

    /// Cauchy stress `sigma = P F^T / J`, with `sigma_33 = P_33 / J` from `dW/dF33`.
    fn cauchy(&self, f: &Tensor2) -> Result<CauchyStress> {
        let j = check_state(self, f)?;
        let (_, p) = gradient(
            |x: SVector<DualSVec64<5>, 5>| self.density(&plane_gradient(&[x[0], x[1], x[2], x[3]], x[4])),
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
mod law_tests;
#[cfg(test)]
mod tests;
