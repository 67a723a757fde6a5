//! Wrinkles in any direction of the surface: the linear stability of the bilayer under biaxial
//! compression, for modes `U(Y) exp(i k (cos theta X + sin theta Z))` with three displacement
//! components.
//!
//! Each layer is at `F = diag(lambda_1, lambda_2, lambda_3)` ([`biaxial_state`]): the in-plane
//! compressions `d` along X and `d_3 = R d` along Z (`R = 0` plane strain, `R = 1`
//! equibiaxial). The fibre families lie along `(cos beta cos psi, +-sin beta, cos beta sin psi)`.
//! The moduli are the full 3x3 tangent of the same energy as everywhere else
//! ([`crate::material::full_response`]). `d_c(k, theta)` is found by the exact method (6x6 Stroh
//! matrix, [`exact`]) or the discrete one ([`discrete`]); the onset `(k0, theta0)` minimises it
//! over both. With `theta = 0`, `R = 0` and `psi = 0` the Z displacement decouples and `d_c(k)`
//! is the plane-strain one.

mod box_modes;
pub mod discrete;
pub mod exact;
pub mod moduli;
mod search;

use super::search::{Onset, StabilityAnalysis};
pub use super::surface::Surface;
use super::Method;
use crate::error::{Error, Result};
use crate::homogeneous::{biaxial_state, normal_stress};
pub use box_modes::{box_modes, BoxMode};
use moduli::SurfaceModuli;
use serde::Serialize;
use std::f64::consts::PI;

/// The onset over wavenumbers and directions.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct SurfaceOnset {
    /// The onset along `theta0`.
    pub onset: Onset,
    /// The direction of the first wrinkles' wave vector, in `[0, pi)` (the crests run
    /// perpendicular to it); NaN where `d_c` is the same in every direction (null in JSON).
    pub theta0: f64,
    /// How much the direction matters: the largest `d_c(k0, theta)` over the sampled
    /// directions, minus `d_c`.
    pub direction_spread: f64,
}

impl StabilityAnalysis {
    /// The moduli of both layers at the biaxial state of the load's strain `d` (`d_3 = R d`).
    pub fn surface_moduli(&self, d: f64) -> Result<(SurfaceModuli, SurfaceModuli)> {
        let surface = self.surface.expect("a surface analysis");
        let state = biaxial_state(&self.materials, d, surface.biaxial * d)?;
        let (layer, substrate) = (state.layer_stretches(), state.substrate_stretches());
        let (loaded, _) = self.materials.at_biaxial_load(d, surface.biaxial * d);
        let (l, s) = (&loaded.layer, &loaded.substrate);
        if self.materials.incompressible {
            // p = -lambda_2 P_rest,22 makes P_22 = P_rest,22 + p / lambda_2 vanish.
            let pressure = |m: &dyn Fn([f64; 3]) -> Result<f64>, stretches: [f64; 3]| -> Result<f64> {
                Ok(-stretches[1] * m(stretches)?)
            };
            let pl = pressure(&|x| normal_stress(l, x), layer)?;
            let ps = pressure(&|x| normal_stress(s, x), substrate)?;
            return Ok((
                SurfaceModuli::incompressible(l, layer, pl)?,
                SurfaceModuli::incompressible(s, substrate, ps)?,
            ));
        }
        Ok((SurfaceModuli::at(l, layer)?, SurfaceModuli::at(s, substrate)?))
    }

    /// The sign-changing bifurcation indicator of a mode along `theta` at `(d, k)`.
    pub(super) fn surface_indicator(&self, theta: f64, d: f64, k: f64) -> Result<f64> {
        let (layer, substrate) = self.surface_moduli(d)?;
        match &self.method {
            Method::Exact => {
                let nearly_lost = |_| Error::NoRoot {
                    what: format!("the bifurcation condition at k = {k} before d = {d} (ellipticity nearly lost)"),
                    lower: 0.0,
                    upper: d,
                };
                let impedance = exact::surface_impedance(&substrate, theta).map_err(nearly_lost)?;
                let layer = exact::LayerSolutions::of(&layer, theta).map_err(nearly_lost)?;
                Ok(exact::bifurcation_condition(&layer, &impedance, k))
            }
            Method::Discrete(options) => match discrete::negative_eigenvalues(&layer, &substrate, k, theta, options) {
                Some(0) => Ok(1.0),
                _ => Ok(-1.0),
            },
        }
    }

    /// This analysis for modes along `theta`.
    pub fn along(&self, theta: f64) -> StabilityAnalysis {
        let mut analysis = self.clone();
        let surface = analysis.surface.as_mut().expect("a surface analysis");
        surface.theta = theta;
        analysis
    }
}

/// A direction in `[0, pi)`; within the minimisation's tolerance of pi it is 0.
fn folded(theta: f64) -> f64 {
    Some(theta.rem_euclid(PI)).filter(|t| PI - t > 1e-5).unwrap_or(0.0)
}

#[cfg(test)]
mod tests;
