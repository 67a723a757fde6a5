//! The strong-ellipticity margin of a finite-element state: the smallest margin
//! ([`crate::material::ellipticity::referential_margin`]) of the tissue's own law over the Gauss
//! points of each layer. Where it is negative, the continuum admits shear bands at that state
//! and the finite-element answer depends on the mesh.

use super::assembly::System;
use super::element::GAUSS_POINTS;
use crate::error::Result;
use crate::material::ellipticity::referential_margin;
use crate::material::Hyperelastic;
use crate::mesh::Region;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// The smallest strong-ellipticity margin over the Gauss points of each layer (units of `mu_s`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct EllipticityMargins {
    pub layer: f64,
    pub substrate: f64,
}

impl EllipticityMargins {
    /// Whether either layer has lost strong ellipticity.
    pub fn lost(&self) -> bool {
        self.layer < 0.0 || self.substrate < 0.0
    }
}

/// The strong-ellipticity margins along a sequence of states `(d, margins)`: the first `d` at
/// which a layer's smallest margin over its Gauss points is negative (beyond it the answer
/// depends on the mesh), and the smallest margins met.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct EllipticityReport {
    pub d_loss_layer: Option<f64>,
    pub d_loss_substrate: Option<f64>,
    pub smallest_layer: f64,
    pub smallest_substrate: f64,
}

impl EllipticityReport {
    pub fn new(states: impl Iterator<Item = (f64, EllipticityMargins)> + Clone) -> Self {
        let first = |margin: fn(&EllipticityMargins) -> f64| {
            states
                .clone()
                .filter(|(_, m)| margin(m) < 0.0)
                .map(|(d, _)| d)
                .reduce(f64::min)
        };
        let least = |margin: fn(&EllipticityMargins) -> f64| {
            states.clone().map(|(_, m)| margin(&m)).fold(f64::INFINITY, f64::min)
        };
        EllipticityReport {
            d_loss_layer: first(|m| m.layer),
            d_loss_substrate: first(|m| m.substrate),
            smallest_layer: least(|m| m.layer),
            smallest_substrate: least(|m| m.substrate),
        }
    }

    /// The first `d` at which either layer has lost strong ellipticity.
    pub fn d_loss(&self) -> Option<f64> {
        [self.d_loss_layer, self.d_loss_substrate]
            .into_iter()
            .flatten()
            .reduce(f64::min)
    }
}

/// The margins of the state `u` of `system`. An exactly incompressible tissue (no bulk
/// modulus) is checked on the directions that keep the volume.
pub fn ellipticity_margins(system: &System, u: &[f64]) -> Result<EllipticityMargins> {
    let mesh = system.mesh();
    let margins = (0..mesh.elements().len())
        .into_par_iter()
        .with_min_len(64)
        .map(|e| {
            let (geometry, tissue) = (&system.geometry()[e], &system.materials()[e]);
            let incompressible = tissue.volumetric_split().bulk == 0.0;
            let u_e = system.element_displacements(e, u);
            let mut smallest = f64::INFINITY;
            for g in 0..GAUSS_POINTS {
                let f = geometry.deformation_gradient(g, &u_e);
                let tangent = tissue.response(&f)?.tangent;
                smallest = smallest.min(referential_margin(&tangent, &f, incompressible));
            }
            Ok((mesh.regions()[e], smallest))
        })
        .collect::<Result<Vec<_>>>()?;
    let least = |region: Region| {
        margins
            .iter()
            .filter(|(r, _)| *r == region)
            .fold(f64::INFINITY, |m, (_, x)| m.min(*x))
    };
    Ok(EllipticityMargins {
        layer: least(Region::Layer),
        substrate: least(Region::Substrate),
    })
}
