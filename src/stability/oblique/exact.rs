//! The exact solver for modes in any direction of the surface: the plane method
//! ([`crate::stability::exact`]) on the 6x6 complex Stroh matrix of [`SurfaceModuli`].
//!
//! * Substrate: solutions `exp(k mu Y)` decaying as `Y -> -inf` have `Re mu > 0`; they span the
//!   kernel of `(I - sign M_s) / 2`, on which `s = Z U` at `Y = 0` (the surface impedance, 3x3).
//! * Layer: `T = exp(k M_l)` carries `y(0) = (U, Z U)` to `y(1)`.
//! * At the traction-free top `s(1) = (T_21 + T_22 Z) U(0) = 0`. The top impedance
//!   `G = (T_21 + T_22 Z) (T_11 + T_12 Z)^-1` is Hermitian (the increment's energy is the work
//!   of its surface tractions), so `det G` is real and changes sign where one eigenvalue of `G`
//!   crosses zero. The condition used, `det(T_21 + T_22 Z) conj(det(T_11 + T_12 Z)) =
//!   det G |det(T_11 + T_12 Z)|^2`, is real and continuous; it also vanishes where the top held
//!   fixed would bifurcate, which by the inclusion of spaces comes only after the free top.

use super::moduli::SurfaceModuli;
use crate::error::{Error, Result};
use nalgebra::{Complex, Matrix3, Matrix6, SMatrix};

type C = Complex<f64>;

/// Matrix sign function by the scaled Newton iteration `S <- (mu S + (mu S)^-1) / 2`,
/// `mu = |det S|^(-1/6)`; fails when `M` has eigenvalues on the imaginary axis.
fn matrix_sign(m: &Matrix6<C>) -> Result<Matrix6<C>> {
    let mut s = *m;
    for _ in 0..100 {
        // One LU factorisation gives both the determinant and the inverse.
        let lu = s.lu();
        let det = lu.determinant().norm();
        let inverse = lu
            .try_inverse()
            .filter(|_| det.is_finite() && det != 0.0)
            .ok_or_else(not_elliptic)?;
        let mu = det.powf(-1.0 / 6.0);
        let next = (s * C::from(mu) + inverse * C::from(1.0 / mu)) * C::from(0.5);
        let change = (next - s).norm();
        s = next;
        if change <= 1e-12 * s.norm() {
            break;
        }
    }
    if (s * s - Matrix6::identity()).norm() < 1e-8 {
        Ok(s)
    } else {
        Err(not_elliptic())
    }
}

fn not_elliptic() -> Error {
    Error::NonFinite("substrate impedance: Stroh roots on the imaginary axis (ellipticity lost)".into())
}

/// The substrate's surface impedance `s = Z U` at `Y = 0` for a mode along `theta`.
pub fn surface_impedance(substrate: &SurfaceModuli, theta: f64) -> Result<Matrix3<C>> {
    let sign = matrix_sign(&substrate.stroh_matrix(theta))?;
    let minus = (Matrix6::<C>::identity() - sign) * C::from(0.5);
    let on_traction: SMatrix<C, 6, 3> = minus.fixed_view::<6, 3>(0, 3).into_owned();
    let on_displacement: SMatrix<C, 6, 3> = minus.fixed_view::<6, 3>(0, 0).into_owned();
    let normal = on_traction.adjoint() * on_traction;
    let rhs = -(on_traction.adjoint() * on_displacement);
    normal.try_inverse().map(|inv| inv * rhs).ok_or_else(not_elliptic)
}

/// The real bifurcation condition `Re(det(T_21 + T_22 Z) conj(det(T_11 + T_12 Z)))` at
/// wavenumber `k`, normalised by the size of its blocks so that it stays O(1).
pub fn bifurcation_condition(layer: &SurfaceModuli, impedance: &Matrix3<C>, k: f64, theta: f64) -> f64 {
    let (free, held) = top_blocks(layer, impedance, k, theta);
    let scale = (1.0 + free.norm_squared()).powf(1.5) * (1.0 + held.norm_squared()).powf(1.5);
    (free.determinant() * held.determinant().conj()).re / scale
}

/// `(T_21 + T_22 Z, T_11 + T_12 Z)`: the tractions and the displacements at the top of the
/// layer per unit displacement at its base.
pub fn top_blocks(layer: &SurfaceModuli, impedance: &Matrix3<C>, k: f64, theta: f64) -> (Matrix3<C>, Matrix3<C>) {
    let transfer = (layer.stroh_matrix(theta) * C::from(k)).exp();
    let block = |r: usize, c: usize| -> Matrix3<C> { transfer.fixed_view::<3, 3>(r, c).into_owned() };
    (
        block(3, 0) + block(3, 3) * impedance,
        block(0, 0) + block(0, 3) * impedance,
    )
}
