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

pub mod discrete;
pub mod exact;
pub mod moduli;

use super::search::{Onset, StabilityAnalysis, RISE_TOLERANCE};
use super::Method;
use crate::error::{Error, Result};
use crate::homogeneous::{biaxial_state, normal_stress};
use crate::numerics::minimize::brent_minimize;
use moduli::SurfaceModuli;
use serde::Serialize;
use std::f64::consts::PI;

/// The loading and the mode direction of a surface analysis.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Surface {
    /// `R = d_3 / d`, in `[0, 1]`.
    pub biaxial: f64,
    /// Direction of the wave vector in the surface, from X towards Z (radians).
    pub theta: f64,
}

impl Surface {
    pub fn validate(&self) -> Result<()> {
        if !(self.biaxial.is_finite() && (0.0..=1.0).contains(&self.biaxial)) {
            return Err(Error::invalid(
                "biaxial",
                self.biaxial,
                "[0, 1] (d_3 = R d: 0 plane strain, 1 equibiaxial)",
            ));
        }
        if !self.theta.is_finite() {
            return Err(Error::invalid("theta", self.theta, "a finite angle in radians"));
        }
        Ok(())
    }
}

/// The onset over wavenumbers and directions.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct SurfaceOnset {
    /// The onset along `theta0`.
    pub onset: Onset,
    /// The direction of the first wrinkles' wave vector, in `[0, pi)` (the crests run
    /// perpendicular to it); NaN where `d_c` is the same in every direction (null in JSON).
    pub theta0: f64,
    /// `max over theta of min over k of d_c`, minus `d_c`: how much the direction matters.
    pub direction_spread: f64,
}

/// Directions sampled before the refinement (every 15 degrees of `[0, pi)`).
const DIRECTIONS: usize = 12;

impl StabilityAnalysis {
    /// The moduli of both layers at the biaxial state of compression `d`.
    pub fn surface_moduli(&self, d: f64) -> Result<(SurfaceModuli, SurfaceModuli)> {
        let surface = self.surface.expect("a surface analysis");
        let state = biaxial_state(&self.materials, d, surface.biaxial * d)?;
        let (layer, substrate) = (state.layer_stretches(), state.substrate_stretches());
        let (l, s) = (&self.materials.layer, &self.materials.substrate);
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
                let impedance = exact::surface_impedance(&substrate, theta).map_err(|_| Error::NoRoot {
                    what: format!("the bifurcation condition at k = {k} before d = {d} (ellipticity nearly lost)"),
                    lower: 0.0,
                    upper: d,
                })?;
                Ok(exact::bifurcation_condition(&layer, &impedance, k, theta))
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

    /// The onset over wavenumbers and directions: the onset in `k` along `DIRECTIONS`
    /// directions of `[0, pi)` (`d_c(k, theta + pi) = d_c(k, theta)`: the conjugate mode), then
    /// Brent's minimisation over the 30 degrees around the best, continuing `k0` from one
    /// direction to the next.
    pub fn surface_onset(&self) -> Result<SurfaceOnset> {
        let step = PI / DIRECTIONS as f64;
        let thetas: Vec<f64> = (0..DIRECTIONS).map(|i| i as f64 * step).collect();
        let sampled: Vec<(f64, Onset)> = thetas.iter().copied().zip(self.onsets_along(&thetas)?).collect();
        // The first direction within round-off of the lowest: of a mirror pair (theta and
        // pi - theta, where the fibres' projection lies along X or Z) the one in [0, pi/2].
        let lowest = sampled.iter().map(|s| s.1.d_c).fold(f64::INFINITY, f64::min);
        let (best_theta, best) = *sampled
            .iter()
            .find(|s| s.1.d_c <= lowest + 1e-12)
            .expect("directions sampled");
        let highest = sampled.iter().map(|s| s.1.d_c).fold(f64::NEG_INFINITY, f64::max);
        if highest - best.d_c <= RISE_TOLERANCE {
            return Ok(SurfaceOnset {
                onset: best,
                theta0: f64::NAN,
                direction_spread: highest - best.d_c,
            });
        }
        let last = std::cell::Cell::new(best);
        let (theta, _) = brent_minimize(
            |theta| {
                let onset = self.along(theta).onset_near(&last.get())?;
                last.set(onset);
                Ok(onset.d_c)
            },
            best_theta - step,
            best_theta + step,
            1e-6,
        )?;
        let onset = self.along(theta).onset_near(&last.get())?;
        let onset = if onset.d_c <= best.d_c { onset } else { best };
        let theta0 = if onset.d_c < best.d_c { theta } else { best_theta };
        Ok(SurfaceOnset {
            onset,
            // Within the minimisation's tolerance of pi is the direction 0.
            theta0: Some(theta0.rem_euclid(PI)).filter(|t| PI - t > 1e-5).unwrap_or(0.0),
            direction_spread: highest - onset.d_c,
        })
    }

    /// The onset in `k` along each of `thetas` (continued from one to the next): `d_c(theta)`
    /// for the polar figure.
    pub fn onsets_along(&self, thetas: &[f64]) -> Result<Vec<Onset>> {
        let mut previous: Option<Onset> = None;
        thetas
            .iter()
            .map(|&theta| {
                let along = self.along(theta);
                let onset = match &previous {
                    Some(p) => along.onset_near(p)?,
                    None => along.onset()?,
                };
                previous = Some(onset);
                Ok(onset)
            })
            .collect()
    }
}

#[cfg(test)]
mod tests;
