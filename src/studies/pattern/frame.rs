//! The frame the patch is built in. A periodic box whose sides run along X and Z admits a wave
//! vector `k (cos theta, sin theta)` together with its mirror image about X, `-theta`, but not
//! about another axis: with the fibres' projection turned by `psi`, the theory's mirror pair
//! `psi +- theta_f` is not admissible as a pair. Under a load that is the same in every
//! direction of the surface (equibiaxial compression or growth, `R = 1`, with no prestrain
//! along one direction: `growth_layer = growth_substrate = 1`) and fibres with a projection on
//! the surface (`beta < pi/2`), the bilayer's response turns
//! with the tissue about `Y`, so the patch is built with its X axis along the fibres' projection
//! (`psi = 0` there) and every direction it reports is turned back by `psi`: both members of
//! the pair are admissible, and nothing else changes.

use crate::parameters::Parameters;
use crate::protocol::patch::{Direction, WaveVector};
use crate::stability::oblique::BoxMode;
use std::f64::consts::PI;

/// The parameters the patch is computed with, and the azimuth of its X axis from the load's.
#[derive(Clone, Debug, PartialEq)]
pub struct PatchFrame {
    /// The tissue in the patch's frame (`psi = 0` when turned).
    pub parameters: Parameters,
    /// The patch's X axis from the load's X axis towards Z (radians; 0 when not turned).
    pub azimuth: f64,
}

impl PatchFrame {
    /// The frame of `params` under `d_3 = biaxial d`: turned by `psi` where the load is the
    /// same in every direction of the surface (module docs), else the load's own.
    pub fn of(params: &Parameters, biaxial: f64) -> Self {
        let isotropic_load = biaxial == 1.0 && params.growth_layer == 1.0 && params.growth_substrate == 1.0;
        // Fibres normal to the surface have no projection: psi means nothing to them.
        let projected = params.fibre_projection().is_some();
        match isotropic_load && projected && params.psi != 0.0 {
            true => PatchFrame {
                parameters: Parameters {
                    psi: 0.0,
                    ..params.clone()
                },
                azimuth: params.psi,
            },
            false => PatchFrame {
                parameters: params.clone(),
                azimuth: 0.0,
            },
        }
    }

    /// The fibres' projection on the surface in the patch's frame, for the figures (`None`
    /// for fibres normal to it).
    pub fn fibres(&self) -> Option<[f64; 2]> {
        self.parameters.fibre_projection()
    }

    /// What a figure of the patch adds to its title when the patch is turned (its X axis along
    /// the fibres' projection, that many degrees from the load's X).
    pub fn caption(&self) -> String {
        match self.azimuth {
            0.0 => String::new(),
            azimuth => format!(" (patch turned {:.1} deg)", azimuth.to_degrees()),
        }
    }

    /// A direction of the patch's frame (radians in `[0, pi)`) in the load's.
    pub fn angle(&self, theta: f64) -> f64 {
        (theta + self.azimuth).rem_euclid(PI)
    }

    /// The same in degrees, in `[0, 180)`.
    pub fn degrees(&self, theta_degrees: f64) -> f64 {
        (theta_degrees + self.azimuth.to_degrees()).rem_euclid(180.0)
    }

    /// An admissible wave vector with its direction in the load's frame (`(m, n)` stay the
    /// patch's).
    pub fn mode(&self, mode: BoxMode) -> BoxMode {
        BoxMode {
            theta: self.angle(mode.theta),
            ..mode
        }
    }

    /// A wave vector of the surface with its direction in the load's frame.
    pub fn wave(&self, wave: WaveVector) -> WaveVector {
        WaveVector {
            theta_degrees: self.degrees(wave.theta_degrees),
            ..wave
        }
    }

    /// A direction of wave vectors with its leading wave's direction in the load's frame.
    pub fn direction(&self, direction: Direction) -> Direction {
        Direction {
            wave: self.wave(direction.wave),
            ..direction
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_a_load_the_same_in_every_direction_turns_the_patch() {
        let turned = Parameters {
            psi: 0.5,
            ..Parameters::default()
        };
        let frame = PatchFrame::of(&turned, 1.0);
        assert_eq!((frame.parameters.psi, frame.azimuth), (0.0, 0.5));
        assert!((frame.angle(PI - 0.25) - 0.25).abs() < 1e-15);
        assert!((frame.degrees(170.0) - (170.0 + 0.5f64.to_degrees() - 180.0)).abs() < 1e-12);
        // Unequal compressions, or a prestrain along X, single out the load's axes.
        assert_eq!(PatchFrame::of(&turned, 0.5).azimuth, 0.0);
        let prestrained = Parameters {
            growth_layer: 1.1,
            ..turned.clone()
        };
        assert_eq!(PatchFrame::of(&prestrained, 1.0).parameters, prestrained);
        assert_eq!(PatchFrame::of(&Parameters::default(), 1.0).azimuth, 0.0);
        let vertical = Parameters {
            beta: std::f64::consts::FRAC_PI_2,
            ..turned.clone()
        };
        assert_eq!(PatchFrame::of(&vertical, 1.0).azimuth, 0.0);
    }
}
