//! A law at one material point in `D` dimensions, the way the finite elements of either
//! dimension call it: plane strain for `D = 2` ([`Hyperelastic::response`], `F33 = 1`) and the
//! full response for `D = 3` ([`Hyperelastic::full`]). `F`, `P` and `A` are indexed by their
//! components, `F[i][J]`, `P[i][J]`, `A[i][J][k][L] = d2W / dF_iJ dF_kL`.

use super::{Hyperelastic, ResponseOf, StrainEnergy, Tensor2};
use crate::error::Result;

/// `W`, `P` and `A` at one point of a `D`-dimensional deformation.
#[derive(Clone, Copy, Debug)]
pub struct PointResponse<const D: usize> {
    pub energy: f64,
    pub stress: [[f64; D]; D],
    pub tangent: [[[[f64; D]; D]; D]; D],
}

impl<const D: usize> PointResponse<D> {
    /// The response stored row-major (`P` at `D i + J`, `A` at `[D i + J][D k + L]`).
    #[inline(always)]
    pub fn from_flat<const G: usize>(r: &ResponseOf<G>) -> Self {
        debug_assert_eq!(G, D * D, "D x D components");
        let at = |i: usize, j: usize| D * i + j;
        PointResponse {
            energy: r.energy,
            stress: std::array::from_fn(|i| std::array::from_fn(|j| r.stress[at(i, j)])),
            tangent: std::array::from_fn(|i| {
                std::array::from_fn(|j| std::array::from_fn(|k| std::array::from_fn(|l| r.tangent[at(i, j)][at(k, l)])))
            }),
        }
    }
}

/// `F` stored row-major (`F_iJ` at `D i + J`).
#[inline(always)]
pub fn flat<const D: usize, const G: usize>(f: &[[f64; D]; D]) -> [f64; G] {
    debug_assert_eq!(G, D * D, "D x D components");
    std::array::from_fn(|c| f[c / D][c % D])
}

/// `F` (or `P`) stored row-major, by components.
#[inline(always)]
pub fn nested<const D: usize, const G: usize>(f: &[f64; G]) -> [[f64; D]; D] {
    debug_assert_eq!(G, D * D, "D x D components");
    std::array::from_fn(|i| std::array::from_fn(|j| f[D * i + j]))
}

/// `W`, `P` and `A` of `m` at `F`; `J <= 0`, or a gradient outside the law's domain, is an error.
#[inline(always)]
pub fn point_response<const D: usize, M: Hyperelastic + ?Sized>(m: &M, f: &[[f64; D]; D]) -> Result<PointResponse<D>> {
    match D {
        2 => Ok(PointResponse::from_flat(&m.response(&flat(f))?)),
        3 => Ok(PointResponse::from_flat(&m.full(&flat(f))?)),
        _ => unreachable!("material points are in two or three dimensions"),
    }
}

/// `W` and `P` of `m` at `F` (in three dimensions through the full response, tangent unused).
#[inline(always)]
pub fn point_stress<const D: usize, M: Hyperelastic + ?Sized>(
    m: &M,
    f: &[[f64; D]; D],
) -> Result<(f64, [[f64; D]; D])> {
    match D {
        2 => {
            let (energy, stress) = m.energy_and_stress(&flat(f))?;
            Ok((energy, nested(&stress)))
        }
        3 => {
            let response = m.full(&flat(f))?;
            Ok((response.energy, nested(&response.stress)))
        }
        _ => unreachable!("material points are in two or three dimensions"),
    }
}

/// The Cauchy stress `sigma = P F^T / J` of `m` at `F`, as a full symmetric 3x3 tensor (in
/// plane strain with `sigma_33` from `dW/dF33` and no out-of-plane shear).
pub fn point_cauchy<const D: usize, M: Hyperelastic + ?Sized>(m: &M, f: &[[f64; D]; D]) -> Result<[[f64; 3]; 3]> {
    match D {
        2 => {
            let [s11, s12, s22, s33] = m.cauchy(&flat(f))?;
            Ok([[s11, s12, 0.0], [s12, s22, 0.0], [0.0, 0.0, s33]])
        }
        3 => {
            let f: [f64; 9] = flat(f);
            let p = m.full(&f)?.stress;
            let j = super::determinant(&f);
            Ok(std::array::from_fn(|i| {
                std::array::from_fn(|k| (0..3).map(|l| p[3 * i + l] * f[3 * k + l]).sum::<f64>() / j)
            }))
        }
        _ => unreachable!("material points are in two or three dimensions"),
    }
}

/// `W_rest` of `rest` at `F` with the pressure `p` conjugate to `ln J` added to its stress and
/// tangent ([`super::add_pressure`], [`super::add_pressure_full`]); `F` is not checked (the
/// mixed element checks `J` and the domain first).
#[inline(always)]
pub fn pressured_response<const D: usize, M: StrainEnergy + ?Sized>(
    rest: &M,
    f: &[[f64; D]; D],
    p: f64,
) -> PointResponse<D> {
    match D {
        2 => {
            let f: Tensor2 = flat(f);
            let mut response = rest.plane_response(&f);
            super::add_pressure(&mut response.stress, Some(&mut response.tangent), &f, p);
            PointResponse::from_flat(&response)
        }
        3 => {
            let f: [f64; 9] = flat(f);
            let mut response = rest.response_3d(&f);
            super::add_pressure_full(&mut response.stress, Some(&mut response.tangent), &f, p);
            PointResponse::from_flat(&response)
        }
        _ => unreachable!("material points are in two or three dimensions"),
    }
}

/// [`pressured_response`] without the tangent: `W_rest` and `P_rest + p F^-T`.
#[inline(always)]
pub fn pressured_stress<const D: usize, M: StrainEnergy + ?Sized>(
    rest: &M,
    f: &[[f64; D]; D],
    p: f64,
) -> (f64, [[f64; D]; D]) {
    match D {
        2 => {
            let f: Tensor2 = flat(f);
            let (energy, mut stress) = rest.plane_stress(&f);
            super::add_pressure(&mut stress, None, &f, p);
            (energy, nested(&stress))
        }
        3 => {
            let f: [f64; 9] = flat(f);
            let mut response = rest.response_3d(&f);
            super::add_pressure_full(&mut response.stress, None, &f, p);
            (response.energy, nested(&response.stress))
        }
        _ => unreachable!("material points are in two or three dimensions"),
    }
}

/// `F^-T` of `F` whose determinant is `j` (in two dimensions `cof F / j`, as the plane
/// formulas have it).
#[inline(always)]
pub fn inverse_transpose_of<const D: usize>(f: &[[f64; D]; D], j: f64) -> [[f64; D]; D] {
    match D {
        2 => nested(&super::cofactor(&flat(f)).map(|c| c / j)),
        3 => nested(&super::inverse_transpose(&flat(f))),
        _ => unreachable!("material points are in two or three dimensions"),
    }
}

/// The full 3x3 gradient of `F` (plane strain: `F33 = 1`).
#[inline(always)]
pub fn full_gradient<const D: usize>(f: &[[f64; D]; D]) -> [f64; 9] {
    match D {
        2 => super::plane_gradient(&flat(f), 1.0),
        3 => flat(f),
        _ => unreachable!("material points are in two or three dimensions"),
    }
}
