//! Linear (Biot-type) stability of the compressed bilayer (paper, Appendix A).
//!
//! At the homogeneous state (eq. 4) an incremental displacement `u1 = a(Y) sin kX`,
//! `u2 = b(Y) cos kX` obeys `Div(A : Grad u) = 0` with the tangent `A = d2W/dF dF` of the one
//! material law ([`crate::material`]); the printed coefficients (6c)-(6q) are never used. The
//! critical compression `d_c(k)` is the smallest `d` with a non-trivial solution that is
//! traction free on `Y = 1`, continuous across `Y = 0` and decays as `Y -> -inf`.
//!
//! Two independent solvers: [`exact`] (Stroh formalism: surface impedance of the half-space and
//! transfer matrix of the layer, a real determinant) and [`discrete`] (quadratic finite elements
//! in `Y` whose stiffness loses positive definiteness at `d_c`).

pub mod discrete;
pub mod ellipticity;
pub mod exact;
pub mod moduli;
pub mod oblique;
mod search;
mod surface;

pub use moduli::IncrementalModuli;
pub use oblique::{Surface, SurfaceOnset};
pub use search::{Minimum, Onset, StabilityAnalysis, K_MAX};

/// Biot (1963): the compression `d = 1 - lambda_1` at which an incompressible neo-Hookean
/// half-space in plane strain wrinkles at every wavelength; `z = lambda_1 / lambda_2 =
/// lambda_1^2` is the root in (0, 1) of `z^3 + z^2 + 3 z - 1 = 0` (0.456311).
pub fn biot_compression() -> f64 {
    let cubic = |z: f64| Ok(z * z * z + z * z + 3.0 * z - 1.0);
    let z = crate::numerics::roots::brent("Biot's cubic", cubic, 0.0, 1.0, 1e-15).expect("one root in (0, 1)");
    1.0 - z.sqrt()
}

/// Which solver computes `d_c(k)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Method {
    /// Stroh formalism: exact for the infinite bilayer (the default).
    Exact,
    /// Quadratic finite elements in `Y` on a truncated, graded depth (a cross-check).
    Discrete(discrete::DiscreteOptions),
}

#[cfg(test)]
mod law_tests;
#[cfg(test)]
mod tests;
