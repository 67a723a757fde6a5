//! Admissible wavenumbers and the geometric imperfection that seeds a mode.
//!
//! Both vertical edges are symmetry planes (`u_x = 0`, `u_y` free), so a mode `u_y ~ cos(k X)`
//! must have a whole number `m` of half wavelengths across `L`: `k = m pi / L`, that is
//! `N = m / 2` waves (`k = 2 pi N / L`).

use crate::error::{Error, Result};
use std::f64::consts::PI;

/// How far `k L / pi` may be from an integer (so that a rounded `k` is still accepted).
const MODE_TOLERANCE: f64 = 1e-3;

/// The number of half wavelengths `m` of `k` across `length`; an error unless `k = m pi / L`.
pub fn mode_number(k: f64, length: f64) -> Result<usize> {
    let m = k * length / PI;
    let nearest = m.round();
    if k.is_finite() && nearest >= 1.0 && (m - nearest).abs() <= MODE_TOLERANCE {
        return Ok(nearest as usize);
    }
    let below = (m.floor().max(1.0) * PI / length, m.floor().max(1.0));
    let above = ((m.floor() + 1.0).max(1.0) * PI / length, (m.floor() + 1.0).max(1.0));
    Err(Error::invalid(
        "k",
        k,
        &format!(
            "m*pi/{length} for an integer m >= 1: both vertical edges are symmetry planes, so a mode \
             has a whole number of half wavelengths across the domain (nearest: {:.6} with m = {}, \
             {:.6} with m = {})",
            below.0, below.1, above.0, above.1
        ),
    ))
}

/// `k = 2 pi N / L` for `N` waves across `length`; an error unless `2 N` is a positive integer.
pub fn wavenumber_of_waves(waves: f64, length: f64) -> Result<f64> {
    let m = 2.0 * waves;
    if waves.is_finite() && m.round() >= 1.0 && (m - m.round()).abs() <= 1e-9 {
        Ok(m.round() * PI / length)
    } else {
        Err(Error::invalid(
            "waves",
            waves,
            "N with 2N a positive integer (whole or half waves: both vertical edges are symmetry planes)",
        ))
    }
}

/// The reference-geometry imperfection `Delta Y = A_init cos(k X) s(Y)` with
/// `s(Y) = 1` in the layer (`Y >= 0`) and `s(Y) = sinh(k (Y + D)) / sinh(k D)` in the substrate:
/// the decay `~ e^{k Y}` of a surface mode, continuous at the interface and exactly zero at the
/// bottom `Y = -D`. Nodes move vertically only, so they stay on the symmetry planes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Imperfection {
    /// `A_init`, the amplitude of the top surface.
    pub amplitude: f64,
    /// Referential wavenumber `k`.
    pub k: f64,
    /// Substrate depth `D`.
    pub depth: f64,
}

impl Imperfection {
    /// The decay `s(Y)` of the imperfection into the substrate.
    pub fn shape(&self, y: f64) -> f64 {
        if y >= 0.0 {
            1.0
        } else {
            // sinh(k (Y + D)) / sinh(k D) = e^{kY} (1 - e^{-2k(Y+D)}) / (1 - e^{-2kD}), overflow-free.
            let (k, depth) = (self.k, self.depth);
            (k * y).exp() * (-(-2.0 * k * (y + depth)).exp_m1()) / (-(-2.0 * k * depth).exp_m1())
        }
    }

    /// The node displacement `[0, Delta Y]` at reference point `[X, Y]`.
    pub fn displacement(&self, [x, y]: [f64; 2]) -> [f64; 2] {
        [0.0, self.amplitude * (self.k * x).cos() * self.shape(y)]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn admissible_wavenumbers() {
        assert_eq!(mode_number(9.0 * PI / 50.0, 50.0).unwrap(), 9);
        assert_eq!(mode_number(0.5655, 50.0).unwrap(), 9);
        let message = mode_number(0.6, 50.0).unwrap_err().to_string();
        assert!(
            message.contains("half wavelengths") && message.contains("m = 9"),
            "{message}"
        );
        assert!(mode_number(0.01, 50.0).is_err());
        assert_eq!(wavenumber_of_waves(4.5, 50.0).unwrap(), 9.0 * PI / 50.0);
        assert!(wavenumber_of_waves(4.3, 50.0).is_err());
        assert!(wavenumber_of_waves(0.0, 50.0).is_err());
    }

    #[test]
    fn imperfection_decays_and_vanishes_at_the_bottom() {
        let imperfection = Imperfection {
            amplitude: 0.05,
            k: 0.6,
            depth: 50.0,
        };
        assert_eq!(imperfection.displacement([0.0, 1.0]), [0.0, 0.05]);
        assert_eq!(imperfection.shape(0.0), 1.0);
        assert!(imperfection.shape(-50.0).abs() < 1e-300);
        assert!((imperfection.shape(-2.0) - (-1.2f64).exp()).abs() < 1e-12);
    }
}
