//! The displacement element: Q2 displacements on the 9-node quadrilateral, full 3x3
//! integration of a hyperelastic material (the paper's element; it locks as `K / mu` grows).

use super::{
    ElementGeometry, ElementMatrix, ElementState, ElementVector, FiniteElement, DOFS, ELEMENT_DOFS, GAUSS_POINTS,
    NODES, PRESSURES,
};
use crate::error::Result;
use crate::material::{Hyperelastic, Tensor2, Tissue};

/// A displacement element of one tissue.
#[derive(Clone, Debug)]
pub struct DisplacementElement {
    tissue: Tissue,
}

impl DisplacementElement {
    pub fn new(tissue: &Tissue) -> Self {
        DisplacementElement { tissue: *tissue }
    }
}

impl FiniteElement for DisplacementElement {
    fn evaluate(
        &self,
        geometry: &ElementGeometry,
        u: &ElementVector,
        _lambda: &[f64; PRESSURES],
        _penalty_scale: f64,
        stiffness: Option<&mut ElementMatrix>,
    ) -> Result<ElementState> {
        evaluate(geometry, &self.tissue, u, stiffness)
    }

    fn cauchy(
        &self,
        geometry: &ElementGeometry,
        g: usize,
        u: &ElementVector,
        _lambda: &[f64; PRESSURES],
    ) -> Result<[f64; 4]> {
        self.tissue.cauchy(&geometry.deformation_gradient(g, u))
    }
}

/// Force and energy of one element at nodal displacements `u`, and its tangent into
/// `stiffness` when given (overwritten, symmetric). Without `stiffness` only `W` and `P` are
/// differentiated (first-order AD, several times cheaper). `J <= 0` at a Gauss point is an error.
pub fn evaluate<M: Hyperelastic>(
    geometry: &ElementGeometry,
    material: &M,
    u: &ElementVector,
    mut stiffness: Option<&mut ElementMatrix>,
) -> Result<ElementState> {
    let mut state = ElementState {
        force: [0.0; DOFS],
        energy: 0.0,
        potential: 0.0,
        min_jacobian: f64::INFINITY,
    };
    if let Some(k) = stiffness.as_deref_mut() {
        *k = [[0.0; DOFS]; DOFS];
    }
    for g in 0..GAUSS_POINTS {
        let f = geometry.deformation_gradient(g, u);
        state.min_jacobian = state.min_jacobian.min(f[0] * f[3] - f[1] * f[2]);
        let (grads, w) = (geometry.gradients(g), geometry.weights()[g]);
        let p = match stiffness.as_deref_mut() {
            Some(k) => {
                let response = material.response(&f)?;
                add_tangent(k, grads, &response.tangent, w);
                state.energy += w * response.energy;
                response.stress
            }
            None => {
                let (energy, stress) = material.energy_and_stress(&f)?;
                state.energy += w * energy;
                stress
            }
        };
        add_force(&mut state.force, grads, &p, w);
    }
    if let Some(k) = stiffness {
        mirror_upper_triangle(k);
    }
    state.potential = state.energy;
    Ok(state)
}

/// `f_ai += w P_iJ G_aJ` at one Gauss point.
pub(super) fn add_force(force: &mut ElementVector, grads: &[[f64; 2]; NODES], p: &Tensor2, w: f64) {
    for (a, grad) in grads.iter().enumerate() {
        force[ELEMENT_DOFS.dof(a, 0)] += w * (p[0] * grad[0] + p[1] * grad[1]);
        force[ELEMENT_DOFS.dof(a, 1)] += w * (p[2] * grad[0] + p[3] * grad[1]);
    }
}

/// Row-major numbering of a plane tensor's components `iJ` (`2 i + J`, as [`crate::material::Tensor2`]).
const PLANE_TENSOR: crate::mesh::DofMap = crate::mesh::DofMap::PLANE;

/// `K_ai,bk += w G_aJ A_iJkL G_bL` at one Gauss point, on and above the diagonal only (`A` has
/// major symmetry, so `K` is symmetric).
pub(super) fn add_tangent(k: &mut ElementMatrix, grads: &[[f64; 2]; NODES], a4: &[[f64; 4]; 4], w: f64) {
    // ag[b][2i+J][k] = w sum_L A_iJkL G_bL.
    let ag: [[[f64; 2]; 4]; NODES] = std::array::from_fn(|b| {
        std::array::from_fn(|ij| {
            std::array::from_fn(|kk| {
                w * (a4[ij][PLANE_TENSOR.dof(kk, 0)] * grads[b][0] + a4[ij][PLANE_TENSOR.dof(kk, 1)] * grads[b][1])
            })
        })
    });
    for (a, ga) in grads.iter().enumerate() {
        for i in 0..2 {
            let r = ELEMENT_DOFS.dof(a, i);
            let row = &mut k[r];
            for (b, agb) in ag.iter().enumerate().skip(a) {
                for kk in 0..2 {
                    row[ELEMENT_DOFS.dof(b, kk)] +=
                        ga[0] * agb[PLANE_TENSOR.dof(i, 0)][kk] + ga[1] * agb[PLANE_TENSOR.dof(i, 1)][kk];
                }
            }
        }
    }
}

/// Copies the upper triangle of `K` onto the lower one.
pub(super) fn mirror_upper_triangle(k: &mut ElementMatrix) {
    for r in 1..DOFS {
        let (above, below) = k.split_at_mut(r);
        for (entry, upper_row) in below[0].iter_mut().zip(above.iter()) {
            *entry = upper_row[r];
        }
    }
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use crate::error::Error;
    use crate::material::{Bilayer, Tissue};
    use crate::parameters::Parameters;

    /// A curved, distorted element and a non-trivial displacement.
    pub(in crate::fem) fn distorted() -> ([[f64; 2]; NODES], ElementVector) {
        let nodes = std::array::from_fn(|a| {
            let (x, y) = ((a % 3) as f64 - 1.0, (a / 3) as f64 - 1.0);
            [1.3 * x + 0.2 * y + 0.05 * y * y, 0.9 * y + 0.1 * x * y - 0.07 * x * x]
        });
        let u = std::array::from_fn(|i| 0.08 * ((i as f64) * 1.7).sin());
        (nodes, u)
    }

    /// Checks at `u` that the force of `evaluate` is the central difference of its energy and
    /// its tangent the central difference of its force.
    pub(in crate::fem) fn assert_consistent_derivatives(
        u: &ElementVector,
        evaluate: impl Fn(&ElementVector, Option<&mut ElementMatrix>) -> ElementState,
    ) {
        let mut k = [[0.0; DOFS]; DOFS];
        let state = evaluate(u, Some(&mut k));
        let h = 1e-6;
        let (mut worst_force, mut worst_tangent, mut scale) = (0.0f64, 0.0f64, 0.0f64);
        for j in 0..DOFS {
            let shifted = |s: f64| {
                let mut v = *u;
                v[j] += s * h;
                evaluate(&v, None)
            };
            let (plus, minus) = (shifted(1.0), shifted(-1.0));
            let force = (plus.potential - minus.potential) / (2.0 * h);
            worst_force = worst_force.max((force - state.force[j]).abs() / (1.0 + state.force[j].abs()));
            for (i, row) in k.iter().enumerate() {
                worst_tangent = worst_tangent.max(((plus.force[i] - minus.force[i]) / (2.0 * h) - row[j]).abs());
                scale = scale.max(row[j].abs());
            }
        }
        assert!(worst_force < 1e-7, "force vs energy: {worst_force:e}");
        assert!(
            worst_tangent <= 1e-7 * scale,
            "tangent vs force: {worst_tangent} vs {scale}"
        );
    }

    #[test]
    fn force_and_tangent_are_the_derivatives_of_the_energy() {
        let p = Parameters {
            beta: 0.6,
            lambda_f: 0.9,
            ..Parameters::default()
        };
        let (nodes, u) = distorted();
        let geometry = ElementGeometry::new::<super::super::Quad9>(&nodes).unwrap();
        for material in [Bilayer::new(&p).substrate_tissue(), Bilayer::new(&p).layer_tissue()] {
            assert_consistent_derivatives(&u, |v, k| evaluate(&geometry, &material, v, k).unwrap());
        }
    }

    #[test]
    fn inverted_element_is_an_error_not_nan() {
        let material: Tissue = Bilayer::new(&Parameters::default()).layer_tissue();
        let (nodes, _) = distorted();
        let geometry = ElementGeometry::new::<super::super::Quad9>(&nodes).unwrap();
        // u_x = -2 X maps x = -X, a reflection with J = -1.
        let u: ElementVector = std::array::from_fn(|i| match ELEMENT_DOFS.component(i) {
            0 => -2.0 * nodes[ELEMENT_DOFS.node(i)][0],
            _ => 0.0,
        });
        let err = evaluate(&geometry, &material, &u, None).unwrap_err();
        assert!(matches!(err, Error::NonPositiveJacobian { .. }), "{err}");
    }
}
