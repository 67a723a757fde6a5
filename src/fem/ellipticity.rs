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
use serde::Serialize;

/// The smallest strong-ellipticity margin over the Gauss points of each layer (units of `mu_s`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
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

/// The margins of the state `u` of `system`. An exactly incompressible tissue (no bulk
/// modulus) is checked on the directions that keep the volume.
pub fn ellipticity_margins(system: &System, u: &[f64]) -> Result<EllipticityMargins> {
    let mesh = system.mesh();
    let margins = (0..mesh.elements().len())
        .into_par_iter()
        .with_min_len(64)
        .map(|e| {
            let (geometry, tissue) = (&system.geometry()[e], &system.materials()[e]);
            let incompressible = tissue.volumetric_split().1 == 0.0;
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
