//! The homogeneous compressed state (eq. 4) as finite-element unknowns: the exact Q2
//! displacement of every mesh node and, for the mixed element, each layer's pressure. The
//! protocol starts from it, the stabilisation and the crease seed measure from it, and the
//! bifurcation scan follows it.

use crate::error::Result;
use crate::fem::System;
use crate::homogeneous::{constraint_pressure, HomogeneousState};
use crate::material::{jacobian, Bilayer, VolumetricSplit};
use crate::mesh::{Mesh, X, Y};

/// The homogeneous displacement of `state` on `mesh`: `u_x = -d X` (0 under growth), `u_y = (lambda_2s - 1)(Y + D)`
/// in the substrate and `(lambda_2s - 1) D + (lambda_2l - 1) Y` in the layer.
pub fn homogeneous_displacement(mesh: &Mesh, state: &HomogeneousState) -> Vec<f64> {
    let depth = mesh.spec().depth;
    let (mut u, dofs) = (vec![0.0; mesh.num_dofs()], mesh.dofs());
    for (n, &[x, y]) in mesh.coordinates().iter().enumerate() {
        u[dofs.dof(n, X)] = -state.end_shortening() * x;
        u[dofs.dof(n, Y)] =
            (state.lambda2_substrate - 1.0) * (y.min(0.0) + depth) + (state.lambda2_layer - 1.0) * y.max(0.0);
    }
    u
}

/// The full unknowns of `system` at the homogeneous `state`: [`homogeneous_displacement`], and
/// when the system has multipliers each layer's pressure: the one that keeps an incompressible
/// layer free of `sigma_22`, else `K ln J`.
pub fn homogeneous_unknowns(system: &System, materials: &Bilayer, state: &HomogeneousState) -> Result<Vec<f64>> {
    let u = homogeneous_displacement(system.mesh(), state);
    if !system.has_multipliers() {
        return Ok(u);
    }
    let (loaded, _) = materials.at_load(state.d);
    let (layer, substrate) = (state.layer_gradient(), state.substrate_gradient());
    let (p_layer, p_substrate) = if materials.incompressible {
        (
            constraint_pressure(&loaded.layer, &layer)?,
            constraint_pressure(&loaded.substrate, &substrate)?,
        )
    } else {
        // kappa (ln J - ln Jg), with the bulk modulus each tissue carries.
        let pressure = |split: VolumetricSplit, f: &[f64; 4]| split.bulk * (jacobian(f).ln() - split.log_volume);
        (
            pressure(loaded.layer_tissue().volumetric_split(), &layer),
            pressure(loaded.substrate_tissue().volumetric_split(), &substrate),
        )
    };
    Ok(system.with_homogeneous_multipliers(u, p_layer, p_substrate))
}
