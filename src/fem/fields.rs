//! Post-processed fields of a solution, one value per element, evaluated at the element centre
//! (the middle point of the 3x3 Gauss rule, `xi = eta = 0`).

use super::assembly::System;
use super::element::{PlaneElement, ReferenceElement};
use crate::error::Result;
use crate::material::{jacobian, von_mises, Bilayer, Fibre, Tensor2};
use crate::mesh::Region;

/// The quadrature point at the element centre.
const CENTRE: usize = PlaneElement::CENTRE;

/// Element-centre fields of one displacement.
#[derive(Clone, Debug, Default)]
pub struct CellFields {
    /// `J = det F`.
    pub jacobian: Vec<f64>,
    /// Cauchy stress `[s11, s12, s22, s33]`.
    pub cauchy: Vec<[f64; 4]>,
    /// Von Mises equivalent of the Cauchy stress.
    pub von_mises: Vec<f64>,
    /// Hydrostatic pressure `-(s11 + s22 + s33) / 3`; with the mixed element, from its
    /// condensed pressure.
    pub pressure: Vec<f64>,
    /// Elastic stretch `sqrt(I4_i) = |Fe N_i|` along each fibre direction `N_{1,2} = (cos beta,
    /// +-sin beta)` (`Fe = F Fg^-1`, `F` without growth); kinematic, so defined in the layer too
    /// (which carries no fibres).
    pub fibre_stretch: [Vec<f64>; 2],
    /// The growth `g` along `X` (`Fg_11`; 1 without growth).
    pub growth: Vec<f64>,
    /// The elastic volume change `Je = J / Jg`.
    pub elastic_jacobian: Vec<f64>,
    /// 1 in the layer, 0 in the substrate.
    pub layer: Vec<f64>,
}

/// Evaluates [`CellFields`] of the displacement `u` (full vector) on every element of `system`.
pub fn cell_fields(system: &System, materials: &Bilayer, u: &[f64]) -> Result<CellFields> {
    let fibres: &[Fibre; 2] = &materials.substrate.energy.fibres;
    let mut fields = CellFields::default();
    for (e, (geometry, material)) in system.geometry().iter().zip(system.materials()).enumerate() {
        let u_e = system.element_displacements(e, u);
        let f: Tensor2 = geometry.deformation_gradient(CENTRE, &u_e);
        let s = system.elements()[e].cauchy(geometry, CENTRE, &u_e, &system.element_multipliers(e, u))?;
        let sigma = [s[0][0], s[0][1], s[1][1], s[2][2]];
        fields.jacobian.push(jacobian(&f));
        fields.cauchy.push(sigma);
        fields.von_mises.push(von_mises(&sigma));
        fields.pressure.push(-(sigma[0] + sigma[2] + sigma[3]) / 3.0);
        let growth = material.growth();
        let elastic = growth.elastic_plane(&f);
        for (stretch, family) in fields.fibre_stretch.iter_mut().zip(fibres) {
            stretch.push(family.stretch_invariant(&elastic).sqrt());
        }
        fields.growth.push(growth.stretches[0]);
        fields.elastic_jacobian.push(jacobian(&elastic));
        let in_layer = system.mesh().regions()[e] == Region::Layer;
        fields.layer.push(if in_layer { 1.0 } else { 0.0 });
    }
    Ok(fields)
}
