//! The exact solver (Appendix A, Stroh formalism).
//!
//! In each layer `y = (a, b, s1/k, s2/k)` obeys `y' = k N y` ([`IncrementalModuli::stroh_matrix`]);
//! `N` has eigenvalues `+-p1, +-p2`, the roots of the characteristic quartic in the Y-exponent.
//! The solutions with `Re p > 0` (growing with `Y`) and those with `Re p < 0` span two invariant
//! subspaces, obtained from the matrix sign function of `N` (no eigenvector, hence no arbitrary
//! phase, and no trouble where two roots meet, as they do in a nearly incompressible solid). On
//! each the tractions are a linear function of the displacements: `(s1, s2)/k = Z (a, b)`, the
//! subspace's impedance.
//! * Substrate: the solutions decaying as `Y -> -inf` are the growing ones; their impedance at
//!   `Y = 0` is the surface impedance `Z_s`.
//! * Layer: `y(Y) = (I; Z_+) E_+(Y - 1) w_+ + (I; Z_-) E_-(Y) w_-`, where `E_+-(t) = exp(k A_+- t)`
//!   and `A_+- = N_11 + N_12 Z_+-` is `N` on each subspace. Each exponential is anchored at the face
//!   where it is largest, so that it is at most of order one across the layer: the transfer
//!   matrix `exp(k N)` of the layer as a whole grows as `exp(k p)` and overflows, and loses the
//!   decaying solutions to rounding long before, at large `k` or strong compression.
//! * Continuity at `Y = 0` (`s = Z_s u`) and zero traction at `Y = 1` leave the 4x4 system
//!   `M (w_+, w_-) = 0`,
//!   `M = [(Z_+ - Z_s) E_+(-1), Z_- - Z_s; Z_+, Z_- E_-(1)]`: the bifurcation condition is
//!   `det M = 0`. `M` is continuous in `d` while both layers are strongly elliptic, so the sign of
//!   its determinant changes exactly at a root.

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
    // A sign matrix squares to the identity. Rounding limits the last digits relative to the
    // size of `S` (large where the roots differ by orders of magnitude, or nearly meet).
    if (s * s - Matrix4::identity()).norm() < 1e-8 * s.norm_squared().max(1.0) {
        Ok(s)
    } else {
        Err(not_elliptic())
    }
}

fn not_elliptic() -> Error {
    Error::NonFinite("Stroh roots on the imaginary axis (ellipticity lost)".into())
}

/// The impedances `(Z_+, Z_-)` of the solutions of `y' = k N y` growing and decaying with `Y`.
/// Independent of `k`.
fn impedances(n: &Matrix4<f64>) -> Result<(Matrix2<f64>, Matrix2<f64>)> {
    // Tractions measured in units of the moduli, `s / sigma`, so that the blocks of `N` are of
    // one size (the moduli of an Ogden law at large stretch reach 1e17).
    let sigma = (n.fixed_view::<2, 2>(2, 0).norm() / n.fixed_view::<2, 2>(0, 2).norm()).sqrt();
    if !(sigma.is_finite() && sigma > 0.0) {
        return Err(not_elliptic());
    }
    let mut balanced = *n;
    balanced.fixed_view_mut::<2, 2>(0, 2).scale_mut(sigma);
    balanced.fixed_view_mut::<2, 2>(2, 0).unscale_mut(sigma);
    let sign = matrix_sign(&balanced)?;
    // The subspace of one sign is the kernel of the other's projector `(I -+ sign) / 2`:
    // `[P11 P12; P21 P22] (U; Z U) = 0`, a consistent 4x2 system solved by least squares.
    let impedance_on_kernel = |projector: Matrix4<f64>| {
        let on_traction: Matrix4x2<f64> = projector.fixed_view::<4, 2>(0, 2).into_owned();
        let on_displacement: Matrix4x2<f64> = projector.fixed_view::<4, 2>(0, 0).into_owned();
        let normal = on_traction.transpose() * on_traction;
        let rhs = -(on_traction.transpose() * on_displacement);
        normal.try_inverse().map(|inv| inv * rhs).ok_or_else(not_elliptic)
    };
    Ok((
        impedance_on_kernel((Matrix4::identity() - sign) * 0.5)? * sigma,
        impedance_on_kernel((Matrix4::identity() + sign) * 0.5)? * sigma,
    ))
}

/// Surface impedance of the substrate half-space: `(s1, s2)/k = Z (a, b)` at `Y = 0` for the
/// solutions decaying as `Y -> -inf`. Independent of `k`.
pub fn surface_impedance(substrate: &IncrementalModuli) -> Result<Matrix2<f64>> {
    impedances(&substrate.stroh_matrix()).map(|(growing, _)| growing)
}

/// The layer's solutions split by their growth through the thickness: what
/// [`bifurcation_determinant`] needs of the layer at one state, for every `k`.
#[derive(Clone, Copy, Debug)]
pub struct LayerSolutions {
    /// Impedances of the growing and the decaying solutions.
    growing: Matrix2<f64>,
    decaying: Matrix2<f64>,
    /// `N` on each subspace, `N_11 + N_12 Z` (eigenvalues `k`-free roots `+-p`).
    growing_rate: Matrix2<f64>,
    decaying_rate: Matrix2<f64>,
}

impl LayerSolutions {
    /// The split of `layer`'s solutions; an error where a Stroh root lies on the imaginary axis.
    pub fn of(layer: &IncrementalModuli) -> Result<Self> {
        let n = layer.stroh_matrix();
        let (growing, decaying) = impedances(&n)?;
        let n11: Matrix2<f64> = n.fixed_view::<2, 2>(0, 0).into_owned();
        let n12: Matrix2<f64> = n.fixed_view::<2, 2>(0, 2).into_owned();
        Ok(LayerSolutions {
            growing,
            decaying,
            growing_rate: n11 + n12 * growing,
            decaying_rate: n11 + n12 * decaying,
        })
    }
}

/// The bifurcation determinant `det M` at wavenumber `k` (module docs), divided by the product
/// of the norms of the rows of `M` (Hadamard's bound), so that it lies in `[-1, 1]` at every `k`
/// and `d` with its sign unchanged.
pub fn bifurcation_determinant(layer: &LayerSolutions, impedance: &Matrix2<f64>, k: f64) -> f64 {
    let base = (layer.growing_rate * -k).exp();
    let top = (layer.decaying_rate * k).exp();
    let mut m = Matrix4::zeros();
    m.fixed_view_mut::<2, 2>(0, 0)
        .copy_from(&((layer.growing - impedance) * base));
    m.fixed_view_mut::<2, 2>(0, 2).copy_from(&(layer.decaying - impedance));
    m.fixed_view_mut::<2, 2>(2, 0).copy_from(&layer.growing);
    m.fixed_view_mut::<2, 2>(2, 2).copy_from(&(layer.decaying * top));
    let rows: f64 = m.row_iter().map(|row| row.norm()).product();
    m.determinant() / rows
}
