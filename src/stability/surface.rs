//! The loading and the mode direction of an analysis of the surface in three dimensions.

use crate::error::{Error, Result};
use serde::Serialize;

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
