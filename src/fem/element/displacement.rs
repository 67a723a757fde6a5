//! The displacement element: Q2 displacements on the 9-node quadrilateral or the 27-node
//! hexahedron, full Gauss integration of a hyperelastic material (the paper's element; it locks
//! as `K / mu` grows). One code for both dimensions: the law is called at each point through
//! [`point_response`] (plane strain in two dimensions, the full response in three).

use super::{ElementGeometry, ElementMatrix, ElementState, ElementVector, FiniteElement, Penalty, Pressures};
use crate::error::Result;
use crate::material::{point_cauchy, point_response, point_stress, Hyperelastic, Tissue};
use crate::mesh::DofMap;

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

impl<const D: usize, const N: usize, const Q: usize, const U: usize> FiniteElement<D, N, Q, U> for DisplacementElement {
    fn evaluate(
        &self,
        geometry: &ElementGeometry<D, N, Q>,
        u: &ElementVector<U>,
        _lambda: &Pressures,
        _penalty: Penalty,
        stiffness: Option<&mut ElementMatrix<U>>,
    ) -> Result<ElementState<U>> {
        evaluate(geometry, &self.tissue, u, stiffness)
    }

    fn cauchy(
        &self,
        geometry: &ElementGeometry<D, N, Q>,
        g: usize,
        u: &ElementVector<U>,
        _lambda: &Pressures,
    ) -> Result<[[f64; 3]; 3]> {
        point_cauchy(&self.tissue, &geometry.gradient_at(g, u))
    }
}

/// Force and energy of one element at nodal displacements `u`, and its tangent into
/// `stiffness` when given (overwritten, symmetric). Without `stiffness` only `W` and `P` are
/// evaluated. `J <= 0` at a Gauss point is an error.
pub fn evaluate<const D: usize, const N: usize, const Q: usize, const U: usize, M: Hyperelastic>(
    geometry: &ElementGeometry<D, N, Q>,
    material: &M,
    u: &ElementVector<U>,
    mut stiffness: Option<&mut ElementMatrix<U>>,
) -> Result<ElementState<U>> {
    let mut state = ElementState {
        force: [0.0; U],
        energy: 0.0,
        potential: 0.0,
        min_jacobian: f64::INFINITY,
    };
    if let Some(k) = stiffness.as_deref_mut() {
        *k = [[0.0; U]; U];
    }
    for g in 0..Q {
        let f = geometry.gradient_at(g, u);
        state.min_jacobian = state.min_jacobian.min(super::determinant(&f));
        let (grads, w) = (geometry.gradients(g), geometry.weights()[g]);
        let p = match stiffness.as_deref_mut() {
            Some(k) => {
                let response = point_response(material, &f)?;
                add_tangent(k, grads, &response.tangent, w);
                state.energy += w * response.energy;
                response.stress
            }
            None => {
                let (energy, stress) = point_stress(material, &f)?;
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

/// `sum_J a_J b_J`, summed from the first term on.
#[inline(always)]
fn contract<const D: usize>(a: &[f64; D], b: &[f64; D]) -> f64 {
    (1..D).fold(a[0] * b[0], |s, l| s + a[l] * b[l])
}

/// `f_ai += w P_iJ G_aJ` at one Gauss point.
pub(super) fn add_force<const D: usize, const N: usize, const U: usize>(
    force: &mut ElementVector<U>,
    grads: &[[f64; D]; N],
    p: &[[f64; D]; D],
    w: f64,
) {
    let dofs = DofMap::of_dimension(D);
    for (a, grad) in grads.iter().enumerate() {
        for (i, p_i) in p.iter().enumerate() {
            force[dofs.dof(a, i)] += w * contract(p_i, grad);
        }
    }
}

/// `K_ai,bk += w G_aJ A_iJkL G_bL` at one Gauss point, on and above the diagonal only (`A` has
/// major symmetry, so `K` is symmetric).
pub(super) fn add_tangent<const D: usize, const N: usize, const U: usize>(
    k: &mut ElementMatrix<U>,
    grads: &[[f64; D]; N],
    a4: &[[[[f64; D]; D]; D]; D],
    w: f64,
) {
    let dofs = DofMap::of_dimension(D);
    // ag[b][i][k][J] = w sum_L A_iJkL G_bL.
    let ag: [[[[f64; D]; D]; D]; N] = std::array::from_fn(|b| {
        std::array::from_fn(|i| {
            std::array::from_fn(|kk| std::array::from_fn(|j| w * contract(&a4[i][j][kk], &grads[b])))
        })
    });
    for (a, ga) in grads.iter().enumerate() {
        for i in 0..D {
            let row = &mut k[dofs.dof(a, i)];
            for (b, agb) in ag.iter().enumerate().skip(a) {
                for (kk, agbik) in agb[i].iter().enumerate() {
                    row[dofs.dof(b, kk)] += contract(ga, agbik);
                }
            }
        }
    }
}

/// Copies the upper triangle of `K` onto the lower one.
pub(super) fn mirror_upper_triangle<const U: usize>(k: &mut ElementMatrix<U>) {
    for r in 1..U {
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
    use crate::fem::element::{Hex27, ReferenceElement, ELEMENT_DOFS, NODES};
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
    pub(in crate::fem) fn assert_consistent_derivatives<const U: usize>(
        u: &ElementVector<U>,
        evaluate: impl Fn(&ElementVector<U>, Option<&mut ElementMatrix<U>>) -> ElementState<U>,
    ) {
        let mut k = Box::new([[0.0; U]; U]);
        let state = evaluate(u, Some(&mut k));
        let h = 1e-6;
        let (mut worst_force, mut worst_tangent, mut scale) = (0.0f64, 0.0f64, 0.0f64);
        for j in 0..U {
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

    /// A curved, distorted hexahedron and a non-trivial displacement.
    fn distorted_hexahedron() -> ([[f64; 3]; 27], ElementVector<81>) {
        let nodes = std::array::from_fn(|a| {
            let [x, y, z] = <Hex27 as ReferenceElement<3, 27, 27>>::node_coordinates(a);
            [
                1.3 * x + 0.2 * y + 0.05 * y * y - 0.04 * z * z,
                0.9 * y + 0.1 * x * y - 0.07 * x * x + 0.06 * z,
                1.1 * z + 0.08 * x * z + 0.05 * y * y,
            ]
        });
        let u = std::array::from_fn(|i| 0.06 * ((i as f64) * 1.7).sin());
        (nodes, u)
    }

    /// Table 1 with inclined fibres off the X-Y plane (a full 3D direction) and a grown layer.
    fn three_dimensional_tissues() -> [Tissue; 2] {
        let p = Parameters {
            beta: 0.6,
            psi: 0.5,
            lambda_f: 0.9,
            ..Parameters::default()
        };
        let bilayer = Bilayer::new(&p);
        let grown = Tissue::Layer(bilayer.layer.with_growth(crate::material::Growth::area(1.2)));
        [bilayer.substrate_tissue(), grown]
    }

    #[test]
    fn hexahedron_force_and_tangent_are_the_derivatives_of_the_energy() {
        let (nodes, u) = distorted_hexahedron();
        let geometry = ElementGeometry::new::<Hex27>(&nodes).unwrap();
        for material in three_dimensional_tissues() {
            assert_consistent_derivatives(&u, |v, k| evaluate(&geometry, &material, v, k).unwrap());
        }
    }

    /// A rigid rotation of the deformed hexahedron changes neither its energy nor the size of
    /// its forces (which turn with it): `W(R F) = W(F)`, `P(R F) = R P(F)`.
    #[test]
    fn hexahedron_energy_is_objective() {
        let (nodes, u) = distorted_hexahedron();
        let geometry = ElementGeometry::new::<Hex27>(&nodes).unwrap();
        let (c, s) = (0.7f64.cos(), 0.7f64.sin());
        // A rotation by 0.7 about the axis (1, 1, 1)/sqrt(3).
        let n = 1.0 / 3f64.sqrt();
        let r: [[f64; 3]; 3] = std::array::from_fn(|i| {
            std::array::from_fn(|j| {
                let cross = match (i, j) {
                    (0, 1) | (1, 2) | (2, 0) => -n,
                    (1, 0) | (2, 1) | (0, 2) => n,
                    _ => 0.0,
                };
                (if i == j { c } else { 0.0 }) + (1.0 - c) * n * n + s * cross
            })
        });
        let dofs = DofMap::SPACE;
        // x = R (X + u), so the rotated displacement is R (X + u) - X.
        let rotated: ElementVector<81> = std::array::from_fn(|k| {
            let (a, i) = (dofs.node(k), dofs.component(k));
            let x: [f64; 3] = std::array::from_fn(|j| nodes[a][j] + u[dofs.dof(a, j)]);
            (0..3).map(|j| r[i][j] * x[j]).sum::<f64>() - nodes[a][i]
        });
        for material in three_dimensional_tissues() {
            let before = evaluate(&geometry, &material, &u, None).unwrap();
            let after = evaluate(&geometry, &material, &rotated, None).unwrap();
            assert!(
                (before.energy - after.energy).abs() <= 1e-12 * before.energy.abs(),
                "{before:?} {after:?}"
            );
            for a in 0..27 {
                for (i, r_i) in r.iter().enumerate() {
                    let turned: f64 = (0..3).map(|j| r_i[j] * before.force[dofs.dof(a, j)]).sum();
                    assert!(
                        (turned - after.force[dofs.dof(a, i)]).abs() <= 1e-11,
                        "node {a}, component {i}"
                    );
                }
            }
        }
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
