//! The multipliers of the mixed element's augmented mode ([`crate::fem::element::mixed`]): where they
//! sit in the unknowns' vector, one step of the method of multipliers, their homogeneous values,
//! and the penalties of the iteration and of the stability tangent.

use super::{Assembled, System};
use crate::error::Result;
use crate::fem::added::AddedEnergy;
use crate::fem::boundary::Dirichlet;
use crate::fem::element::{pressures, Penalty, Pressures, Registry, Volumetric, MAX_PRESSURES};
use crate::material::{Bilayer, Tissue};
use crate::mesh::{ElementKind, Region};
use rayon::prelude::*;

/// Bulk moduli above this many times the tissue's shear modulus go through multipliers.
const AUGMENTED_BULK: f64 = 1e3;

/// The augmentation penalty of the multipliers, in units of the tissue's shear modulus.
const AUGMENTATION_PENALTY: f64 = 1e2;

/// The factor on the augmentation penalty with which the tangent's inertia is counted (at most
/// the bulk modulus, where the tangent is then exact): `fem::element::mixed` explains why it must be
/// large, and not too large. The period doubling of a contrast-100 bilayer on the coarse mesh
/// is bracketed by the same step of 0.001 at 1e2 and 1e3; at 1e4 (a penalty of 1e8 in the
/// layer) the count flickered in round-off about it.
const STABILITY_PENALTY: f64 = 1e3;

/// How `tissue`'s mixed element resists volume change: through multipliers for exact
/// incompressibility and for bulk moduli above [`AUGMENTED_BULK`] times its shear modulus (the
/// matrix's in the substrate), with a penalty scaled by it; `None` (condensed exactly)
/// otherwise.
pub(super) fn augmentation(materials: &Bilayer, tissue: &Tissue) -> Option<Volumetric> {
    let shear = match tissue {
        Tissue::Layer(_) => materials.layer.energy.shear_modulus(),
        Tissue::Substrate(_) => materials.substrate.energy.matrix.shear_modulus(),
    };
    let bulk = tissue.volumetric_split().bulk;
    let bulk = if materials.incompressible { f64::INFINITY } else { bulk };
    (bulk > AUGMENTED_BULK * shear).then_some(Volumetric::Augmented {
        penalty: AUGMENTATION_PENALTY * shear,
        bulk,
    })
}

impl<const D: usize, const N: usize, const Q: usize, const U: usize> System<D, N, Q, U>
where
    ElementKind: Registry<D, N, Q, U>,
{
    /// Element `e`'s multipliers in the full vector `u` (zero without multipliers).
    pub fn element_multipliers(&self, e: usize, u: &[f64]) -> Pressures {
        let count = pressures(D);
        if !self.multipliers {
            return [0.0; MAX_PRESSURES];
        }
        let start = self.mesh.num_dofs() + count * e;
        std::array::from_fn(|i| if i < count { u[start + i] } else { 0.0 })
    }

    /// The method of multipliers' step at `u` with the penalty multiplied by `penalty_scale`:
    /// the largest violation `|M^-1 g - lambda / K|` over the elements and the change
    /// `p - lambda` of every multiplier (in the order of the multipliers in `u`; zero in
    /// elements condensed exactly). `None` without multipliers.
    pub fn multiplier_step(&self, u: &[f64], penalty_scale: f64) -> Result<Option<(f64, Vec<f64>)>> {
        if !self.multipliers {
            return Ok(None);
        }
        let steps = (0..self.elements.len())
            .into_par_iter()
            .with_min_len(64)
            .map(|e| {
                self.elements[e].multiplier_step(
                    &self.geometry[e],
                    &self.element_displacements(e, u),
                    &self.element_multipliers(e, u),
                    penalty_scale,
                )
            })
            .collect::<Result<Vec<_>>>()?;
        let violation = steps.iter().fold(0.0f64, |v, (e, _)| v.max(*e));
        Ok(Some((
            violation,
            steps
                .into_iter()
                .flat_map(|(_, c)| c.into_iter().take(pressures(D)))
                .collect(),
        )))
    }

    /// The full vector of the displacement `u` (one entry per mesh unknown) at a homogeneous
    /// state: `u`, followed, when the system has multipliers, by each layer's pressure
    /// (`p_layer`, `p_substrate`, constant per element).
    pub fn with_homogeneous_multipliers(&self, mut u: Vec<f64>, p_layer: f64, p_substrate: f64) -> Vec<f64> {
        if self.multipliers {
            for region in self.mesh.regions() {
                let p = match region {
                    Region::Layer => p_layer,
                    Region::Substrate => p_substrate,
                };
                u.extend((0..pressures(D)).map(|i| if i == 0 { p } else { 0.0 }));
            }
        }
        u
    }

    /// The diagonal `K_ii` of the stiffness at `u = 0` on every displacement unknown: a scale
    /// of each unknown's stiffness (of the viscous damper, of the minimiser's shift). In
    /// elements with multipliers, of the energy without its volumetric part: that part's
    /// penalty would make the displacements it scales stiff against the multipliers' updates.
    pub fn reference_stiffness_diagonal(&self) -> Result<Vec<f64>> {
        let mesh = self.mesh();
        let mut stiffness = vec![0.0; mesh.num_dofs()];
        let mut k = [[0.0; U]; U];
        for (e, (element, nodes)) in self.elements.iter().zip(mesh.elements()).enumerate() {
            element.reference_stiffness(&self.geometry[e], &mut k)?;
            for (i, row) in k.iter().enumerate() {
                stiffness[mesh.dofs().global(nodes, i)] += row[i];
            }
        }
        Ok(stiffness)
    }

    /// The tangent (and residual) of the strain energy plus `added` whose inertia is the
    /// stability of `u`: [`System::assemble_with`], with multipliers at the stability penalty
    /// ([`crate::fem::element::mixed`]).
    pub fn assemble_for_stability(&mut self, u: &[f64], bc: &Dirichlet, added: &dyn AddedEnergy) -> Result<Assembled> {
        self.assemble_penalised(u, bc, None, true, added, Penalty::Stability(STABILITY_PENALTY))
    }

    /// Whether multipliers follow the displacements in the unknowns' vector.
    pub fn has_multipliers(&self) -> bool {
        self.multipliers
    }
}
