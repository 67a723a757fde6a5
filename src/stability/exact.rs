//! The exact solver (Appendix A, Stroh formalism).
//!
//! In each layer `y = (a, b, s1/k, s2/k)` obeys `y' = k N y` ([`IncrementalModuli::stroh_matrix`]);
//! `N` has eigenvalues `+-p1, +-p2`, the roots of the characteristic quartic in the Y-exponent.
//! * Substrate: the solutions decaying as `Y -> -inf` span the invariant subspace of the roots
//!   with `Re p > 0`, obtained from the matrix sign function of `N_s` (no eigenvector, hence no
//!   arbitrary phase). On it the tractions are a linear function of the displacements, the
//!   surface impedance `(s1, s2)/k = Z (a, b)` at `Y = 0`.
//! * Layer: the transfer matrix `T = exp(k N_l)` carries `y(0)` to `y(1)`.
//! * Continuity at `Y = 0` and zero traction at `Y = 1` leave `(T_21 + T_22 Z) (a, b)(0) = 0`:
//!   the bifurcation condition is the real determinant `det(T_21 + T_22 Z) = 0`, continuous in
//!   `d` while both layers are strongly elliptic, so its sign changes exactly at a root.

use super::IncrementalModuli;
use crate::error::{Error, Result};
use nalgebra::{Matrix2, Matrix4, Matrix4x2};

/// Matrix sign function by the scaled Newton iteration `S <- (mu S + (mu S)^-1) / 2`.
/// Fails when `N` has eigenvalues on the imaginary axis (loss of ellipticity).
fn matrix_sign(n: &Matrix4<f64>) -> Result<Matrix4<f64>> {
    let mut s = *n;
    for _ in 0..100 {
        let det = s.determinant();
        let inverse = s
            .try_inverse()
            .filter(|_| det.is_finite() && det != 0.0)
            .ok_or_else(not_elliptic)?;
        let mu = det.abs().powf(-0.25);
        let next = 0.5 * (s * mu + inverse / mu);
        let change = (next - s).norm();
        s = next;
        if change <= 1e-12 * s.norm() {
            break;
        }
    }
    // A sign matrix squares to the identity; near a double root rounding limits the last digits.
    if (s * s - Matrix4::identity()).norm() < 1e-8 {
        Ok(s)
    } else {
        Err(not_elliptic())
    }
}

fn not_elliptic() -> Error {
    Error::NonFinite("substrate impedance: Stroh roots on the imaginary axis (ellipticity lost)".into())
}

/// Surface impedance of the substrate half-space: `(s1, s2)/k = Z (a, b)` at `Y = 0` for the
/// solutions decaying as `Y -> -inf`. Independent of `k`.
pub fn surface_impedance(substrate: &IncrementalModuli) -> Result<Matrix2<f64>> {
    let sign = matrix_sign(&substrate.stroh_matrix())?;
    // Decaying subspace = kernel of P_- = (I - sign)/2, i.e. [M11 M12; M21 M22] (U; s) = 0.
    let minus = (Matrix4::identity() - sign) * 0.5;
    let on_traction: Matrix4x2<f64> = minus.fixed_view::<4, 2>(0, 2).into_owned();
    let on_displacement: Matrix4x2<f64> = minus.fixed_view::<4, 2>(0, 0).into_owned();
    // Least squares of the consistent 4x2 system  on_traction * Z = -on_displacement.
    let normal = on_traction.transpose() * on_traction;
    let rhs = -(on_traction.transpose() * on_displacement);
    normal.try_inverse().map(|inv| inv * rhs).ok_or_else(not_elliptic)
}

/// The bifurcation determinant `det(T_21 + T_22 Z)` at wavenumber `k` (normalised by the
/// size of the transfer blocks so that it stays O(1)).
pub fn bifurcation_determinant(layer: &IncrementalModuli, impedance: &Matrix2<f64>, k: f64) -> f64 {
    let transfer = (layer.stroh_matrix() * k).exp();
    let t21: Matrix2<f64> = transfer.fixed_view::<2, 2>(2, 0).into_owned();
    let t22: Matrix2<f64> = transfer.fixed_view::<2, 2>(2, 2).into_owned();
    let condition = t21 + t22 * impedance;
    condition.determinant() / (1.0 + t21.norm_squared() + (t22 * impedance).norm_squared())
}
