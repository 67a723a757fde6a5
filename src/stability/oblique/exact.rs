//! The exact solver for modes in any direction of the surface: the plane method
//! ([`crate::stability::exact`]) on the 6x6 complex Stroh matrix of [`SurfaceModuli`].
//!
//! * The solutions `exp(k mu Y)` with `Re mu > 0` (growing with `Y`) and with `Re mu < 0` span
//!   two invariant subspaces, the kernels of `(I -+ sign M) / 2`; on each `s = Z U`, the
//!   subspace's impedance (3x3). The substrate's decaying solutions are its growing ones: `Z_s`.
//! * Layer: `y(Y) = (I; Z_+) E_+(Y - 1) w_+ + (I; Z_-) E_-(Y) w_-` with `E_+-(t) = exp(k A_+- t)`,
//!   `A_+- = M_11 + M_12 Z_+-`, each exponential anchored at the face where it is largest (the
//!   transfer matrix `exp(k M)` of the whole layer overflows at large `k` or strong compression).
//! * Continuity at `Y = 0` and a free top give `F (w_+, w_-) = 0` with
//!   `F = [(Z_+ - Z_s) E_+(-1), Z_- - Z_s; Z_+, Z_- E_-(1)]`; a held top (`U(1) = 0`) gives
//!   `H = [(Z_+ - Z_s) E_+(-1), Z_- - Z_s; I, E_-(1)]`. With `D = Z_- - Z_s` and
//!   `W = E_-(1) D^-1 (Z_s - Z_+) E_+(-1)`, Schur's formula gives `det F = det D det(Z_+ + Z_- W)`
//!   and `det H = det D det(I + W)`, whose ratio is `det G` for the top impedance
//!   `G = (Z_+ + Z_- W) (I + W)^-1`, Hermitian (the increment's energy is the work of its surface
//!   tractions). The condition used, `det F conj(det H) = |det D|^2 |det(I + W)|^2 det G`, is
//!   therefore real and continuous, and changes sign where an eigenvalue of `G` crosses zero; it
//!   also vanishes where the top held fixed would bifurcate, which by the inclusion of spaces
//!   comes only after the free top.

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
    // Rounding limits the last digits relative to the size of `S`.
    if (s * s - Matrix6::identity()).norm() < 1e-8 * s.norm_squared().max(1.0) {
        Ok(s)
    } else {
        Err(not_elliptic())
    }
}

fn not_elliptic() -> Error {
    Error::NonFinite("Stroh roots on the imaginary axis (ellipticity lost)".into())
}

/// The impedances `(Z_+, Z_-)` of the solutions of `y' = k M y` growing and decaying with `Y`.
fn impedances(m: &Matrix6<C>) -> Result<(Matrix3<C>, Matrix3<C>)> {
    // Tractions in units of the moduli, so that the blocks of `M` are of one size.
    let sigma = (m.fixed_view::<3, 3>(3, 0).norm() / m.fixed_view::<3, 3>(0, 3).norm()).sqrt();
    if !(sigma.is_finite() && sigma > 0.0) {
        return Err(not_elliptic());
    }
    let mut balanced = *m;
    balanced.fixed_view_mut::<3, 3>(0, 3).scale_mut(sigma);
    balanced.fixed_view_mut::<3, 3>(3, 0).unscale_mut(sigma);
    let sign = matrix_sign(&balanced)?;
    let impedance_on_kernel = |projector: Matrix6<C>| -> Result<Matrix3<C>> {
        let on_traction: SMatrix<C, 6, 3> = projector.fixed_view::<6, 3>(0, 3).into_owned();
        let on_displacement: SMatrix<C, 6, 3> = projector.fixed_view::<6, 3>(0, 0).into_owned();
        let normal = on_traction.adjoint() * on_traction;
        let rhs = -(on_traction.adjoint() * on_displacement);
        let z = normal.try_inverse().map(|inv| inv * rhs).ok_or_else(not_elliptic)?;
        Ok(z * C::from(sigma))
    };
    let half = C::from(0.5);
    Ok((
        impedance_on_kernel((Matrix6::identity() - sign) * half)?,
        impedance_on_kernel((Matrix6::identity() + sign) * half)?,
    ))
}

/// The substrate's surface impedance `s = Z U` at `Y = 0` for a mode along `theta`.
pub fn surface_impedance(substrate: &SurfaceModuli, theta: f64) -> Result<Matrix3<C>> {
    impedances(&substrate.stroh_matrix(theta)).map(|(growing, _)| growing)
}

/// The layer's solutions along one direction split by their growth through the thickness.
#[derive(Clone, Copy, Debug)]
pub struct LayerSolutions {
    growing: Matrix3<C>,
    decaying: Matrix3<C>,
    growing_rate: Matrix3<C>,
    decaying_rate: Matrix3<C>,
}

impl LayerSolutions {
    /// The split of `layer`'s solutions along `theta`.
    pub fn of(layer: &SurfaceModuli, theta: f64) -> Result<Self> {
        let m = layer.stroh_matrix(theta);
        let (growing, decaying) = impedances(&m)?;
        let m11: Matrix3<C> = m.fixed_view::<3, 3>(0, 0).into_owned();
        let m12: Matrix3<C> = m.fixed_view::<3, 3>(0, 3).into_owned();
        Ok(LayerSolutions {
            growing,
            decaying,
            growing_rate: m11 + m12 * growing,
            decaying_rate: m11 + m12 * decaying,
        })
    }
}

/// The real bifurcation condition `Re(det F conj(det H))` at wavenumber `k` (module docs),
/// divided by the products of the row norms of `F` and `H` (Hadamard's bound): in `[-1, 1]`,
/// with its sign unchanged.
pub fn bifurcation_condition(layer: &LayerSolutions, impedance: &Matrix3<C>, k: f64) -> f64 {
    let base = (layer.growing_rate * C::from(-k)).exp();
    let top = (layer.decaying_rate * C::from(k)).exp();
    let mut free = Matrix6::<C>::zeros();
    free.fixed_view_mut::<3, 3>(0, 0)
        .copy_from(&((layer.growing - impedance) * base));
    free.fixed_view_mut::<3, 3>(0, 3)
        .copy_from(&(layer.decaying - impedance));
    let mut held = free;
    free.fixed_view_mut::<3, 3>(3, 0).copy_from(&layer.growing);
    free.fixed_view_mut::<3, 3>(3, 3).copy_from(&(layer.decaying * top));
    held.fixed_view_mut::<3, 3>(3, 0).copy_from(&Matrix3::identity());
    held.fixed_view_mut::<3, 3>(3, 3).copy_from(&top);
    let rows = |m: &Matrix6<C>| -> f64 { m.row_iter().map(|row| row.norm()).product() };
    (free.determinant() * held.determinant().conj()).re / (rows(&free) * rows(&held))
}
