//! Post-processed fields of a solution, one value per element, evaluated at the element centre
//! (the middle point of the 3x3 Gauss rule, `xi = eta = 0`).

use super::assembly::System;
use crate::error::Result;
use crate::material::{jacobian, von_mises, Bilayer, FibreFamily, Hyperelastic, Tensor2};
use crate::mesh::Region;

/// The Gauss point at the element centre: index 4 of the 3x3 rule.
const CENTRE: usize = 4;

/// Element-centre fields of one displacement.
#[derive(Clone, Debug, Default)]
pub struct CellFields {
    /// `J = det F`.
    pub jacobian: Vec<f64>,
    /// Cauchy stress `[s11, s12, s22, s33]`.
    pub cauchy: Vec<[f64; 4]>,
    /// Von Mises equivalent of the Cauchy stress.
    pub von_mises: Vec<f64>,
    /// Stretch `sqrt(I4_i) = |F N_i|` along each fibre direction `N_{1,2} = (cos beta, +-sin beta)`;
    /// kinematic, so defined in the layer too (which carries no fibres).
    pub fibre_stretch: [Vec<f64>; 2],
    /// 1 in the layer, 0 in the substrate.
    pub layer: Vec<f64>,
}

/// Evaluates [`CellFields`] of the displacement `u` (full vector) on every element of `system`.
pub fn cell_fields(system: &System, materials: &Bilayer, u: &[f64]) -> Result<CellFields> {
    let fibres: &[FibreFamily; 2] = &materials.substrate.fibres;
    let mut fields = CellFields::default();
    for (e, (geometry, material)) in system.geometry().iter().zip(system.materials()).enumerate() {
        let f: Tensor2 = geometry.deformation_gradient(CENTRE, &system.element_displacements(e, u));
        let sigma = material.cauchy(&f)?;
        fields.jacobian.push(jacobian(&f));
        fields.cauchy.push(sigma);
        fields.von_mises.push(von_mises(&sigma));
        for (stretch, family) in fields.fibre_stretch.iter_mut().zip(fibres) {
            stretch.push(family.stretch_invariant(&f).sqrt());
        }
        let in_layer = system.mesh().regions()[e] == Region::Layer;
        fields.layer.push(if in_layer { 1.0 } else { 0.0 });
    }
    Ok(fields)
}
