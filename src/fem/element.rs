//! The 9-node biquadratic (Q2) element in plane strain: Lagrange shape functions on
//! `[-1, 1]^2`, the 3x3 Gauss rule, and an element's internal force, tangent and energy for a
//! hyperelastic material.
//!
//! With `G_a = dN_a/dX` at a Gauss point of weight `w` (reference Jacobian included):
//! `F = I + sum_a u_a (x) G_a`, `f_ai = sum_gp w P_iJ G_aJ`, `K_ai,bk = sum_gp w G_aJ A_iJkL G_bL`,
//! `E = sum_gp w W(F)`. Element unknowns are ordered `2 a + i` (node `a`, component `i`).

use crate::error::{Error, Result};
use crate::material::{Hyperelastic, Tensor2};

/// Nodes per element.
pub const NODES: usize = 9;
/// Unknowns per element.
pub const DOFS: usize = 2 * NODES;
/// Gauss points per element (3x3).
pub const GAUSS_POINTS: usize = 9;

/// An element vector (forces or displacements), ordered `2 a + i`.
pub type ElementVector = [f64; DOFS];
/// An element matrix, ordered like [`ElementVector`].
pub type ElementMatrix = [[f64; DOFS]; DOFS];

/// 1D quadratic Lagrange polynomials on the nodes `-1, 0, 1`.
fn lagrange(t: f64) -> [f64; 3] {
    [0.5 * t * (t - 1.0), 1.0 - t * t, 0.5 * t * (t + 1.0)]
}

/// Derivatives of [`lagrange`].
fn lagrange_derivative(t: f64) -> [f64; 3] {
    [t - 0.5, -2.0 * t, t + 0.5]
}

/// Shape functions `N_a(xi, eta) = l_(a mod 3)(xi) l_(a div 3)(eta)`.
pub fn shape_functions(xi: [f64; 2]) -> [f64; NODES] {
    let (lx, ly) = (lagrange(xi[0]), lagrange(xi[1]));
    std::array::from_fn(|a| lx[a % 3] * ly[a / 3])
}

/// Shape function derivatives `[dN_a/dxi, dN_a/deta]`.
pub fn shape_derivatives(xi: [f64; 2]) -> [[f64; 2]; NODES] {
    let (lx, ly) = (lagrange(xi[0]), lagrange(xi[1]));
    let (dx, dy) = (lagrange_derivative(xi[0]), lagrange_derivative(xi[1]));
    std::array::from_fn(|a| [dx[a % 3] * ly[a / 3], lx[a % 3] * dy[a / 3]])
}

/// The 3x3 Gauss rule on `[-1, 1]^2`: points and weights, exact for bi-quintic polynomials.
pub fn gauss_rule() -> [([f64; 2], f64); GAUSS_POINTS] {
    let r = (0.6f64).sqrt();
    let points = [(-r, 5.0 / 9.0), (0.0, 8.0 / 9.0), (r, 5.0 / 9.0)];
    std::array::from_fn(|g| {
        let ((x, wx), (y, wy)) = (points[g % 3], points[g / 3]);
        ([x, y], wx * wy)
    })
}

/// Reference geometry of one element at its Gauss points, computed once per mesh.
#[derive(Clone, Debug)]
pub struct ElementGeometry {
    /// `dN_a/dX` at each Gauss point.
    gradients: [[[f64; 2]; NODES]; GAUSS_POINTS],
    /// Gauss weight times `det(dX/dxi)`.
    weights: [f64; GAUSS_POINTS],
    /// Reference position `X` of each Gauss point.
    points: [[f64; 2]; GAUSS_POINTS],
}

impl ElementGeometry {
    /// The geometry of the element with reference nodes `nodes`; `det(dX/dxi) <= 0` is an error.
    pub fn new(nodes: &[[f64; 2]; NODES]) -> Result<Self> {
        let mut gradients = [[[0.0; 2]; NODES]; GAUSS_POINTS];
        let mut weights = [0.0; GAUSS_POINTS];
        let mut points = [[0.0; 2]; GAUSS_POINTS];
        for (g, (xi, w)) in gauss_rule().into_iter().enumerate() {
            for (x, n) in nodes.iter().zip(shape_functions(xi)) {
                points[g][0] += n * x[0];
                points[g][1] += n * x[1];
            }
            let dn = shape_derivatives(xi);
            // j[I][r] = dX_I / dxi_r.
            let mut j = [[0.0; 2]; 2];
            for (x, d) in nodes.iter().zip(&dn) {
                for (row, &xi_component) in j.iter_mut().zip(x) {
                    row[0] += xi_component * d[0];
                    row[1] += xi_component * d[1];
                }
            }
            let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
            if !(det > 0.0 && det.is_finite()) {
                return Err(Error::invalid(
                    "mesh",
                    format!("an element with det(dX/dxi) = {det:e} at a Gauss point"),
                    "elements with det(dX/dxi) > 0 (reduce the imperfection)",
                ));
            }
            // dN/dX = dN/dxi j^-1.
            for (grad, d) in gradients[g].iter_mut().zip(&dn) {
                *grad = [
                    (d[0] * j[1][1] - d[1] * j[1][0]) / det,
                    (-d[0] * j[0][1] + d[1] * j[0][0]) / det,
                ];
            }
            weights[g] = w * det;
        }
        Ok(ElementGeometry {
            gradients,
            weights,
            points,
        })
    }

    /// Reference area of the element.
    pub fn area(&self) -> f64 {
        self.weights.iter().sum()
    }

    /// Quadrature weights (Gauss weight times reference Jacobian).
    pub fn weights(&self) -> &[f64; GAUSS_POINTS] {
        &self.weights
    }

    /// Reference positions of the Gauss points.
    pub fn points(&self) -> &[[f64; 2]; GAUSS_POINTS] {
        &self.points
    }

    /// `dN_a/dX` at Gauss point `g`.
    pub fn gradients(&self, g: usize) -> &[[f64; 2]; NODES] {
        &self.gradients[g]
    }

    /// `F = I + Grad u` at Gauss point `g`, row-major `[F11, F12, F21, F22]`.
    pub fn deformation_gradient(&self, g: usize, u: &ElementVector) -> Tensor2 {
        let mut f = [1.0, 0.0, 0.0, 1.0];
        for (a, grad) in self.gradients[g].iter().enumerate() {
            let (ux, uy) = (u[2 * a], u[2 * a + 1]);
            f[0] += ux * grad[0];
            f[1] += ux * grad[1];
            f[2] += uy * grad[0];
            f[3] += uy * grad[1];
        }
        f
    }
}

/// What an element contributes besides its tangent.
#[derive(Clone, Copy, Debug)]
pub struct ElementState {
    /// Internal force `f_ai = int P_iJ dN_a/dX_J dV`.
    pub force: ElementVector,
    /// Strain energy `int W(F) dV`.
    pub energy: f64,
    /// The potential whose gradient `force` is: `energy`, except for the mixed element's
    /// volumetric term at fixed multipliers ([`crate::fem::mixed`]).
    pub potential: f64,
    /// Smallest `J = det F` over the Gauss points.
    pub min_jacobian: f64,
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
        let (grads, w) = (&geometry.gradients[g], geometry.weights[g]);
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
        for (a, grad) in grads.iter().enumerate() {
            state.force[2 * a] += w * (p[0] * grad[0] + p[1] * grad[1]);
            state.force[2 * a + 1] += w * (p[2] * grad[0] + p[3] * grad[1]);
        }
    }
    if let Some(k) = stiffness {
        mirror_upper_triangle(k);
    }
    state.potential = state.energy;
    Ok(state)
}

/// `K_ai,bk += w G_aJ A_iJkL G_bL` at one Gauss point, on and above the diagonal only (`A` has
/// major symmetry, so `K` is symmetric).
pub(super) fn add_tangent(k: &mut ElementMatrix, grads: &[[f64; 2]; NODES], a4: &[[f64; 4]; 4], w: f64) {
    // ag[b][2i+J][k] = w sum_L A_iJkL G_bL.
    let ag: [[[f64; 2]; 4]; NODES] = std::array::from_fn(|b| {
        std::array::from_fn(|ij| {
            std::array::from_fn(|kk| w * (a4[ij][2 * kk] * grads[b][0] + a4[ij][2 * kk + 1] * grads[b][1]))
        })
    });
    for (a, ga) in grads.iter().enumerate() {
        for i in 0..2 {
            let r = 2 * a + i;
            let row = &mut k[r];
            for (b, agb) in ag.iter().enumerate().skip(a) {
                for kk in 0..2 {
                    row[2 * b + kk] += ga[0] * agb[2 * i][kk] + ga[1] * agb[2 * i + 1][kk];
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

    #[test]
    fn shape_functions_are_a_partition_of_unity_and_interpolate() {
        let xi = [0.31, -0.77];
        let n = shape_functions(xi);
        let d = shape_derivatives(xi);
        assert!((n.iter().sum::<f64>() - 1.0).abs() < 1e-15);
        assert!(d.iter().map(|g| g[0]).sum::<f64>().abs() < 1e-14);
        for a in 0..NODES {
            let node = [(a % 3) as f64 - 1.0, (a / 3) as f64 - 1.0];
            assert!((shape_functions(node)[a] - 1.0).abs() < 1e-15);
        }
    }

    #[test]
    fn gauss_rule_integrates_quintics_and_area() {
        let integral: f64 = gauss_rule().iter().map(|(x, w)| w * x[0].powi(4) * x[1].powi(2)).sum();
        assert!((integral - 0.4 * 2.0 / 3.0).abs() < 1e-15);
        let square: [[f64; 2]; NODES] = std::array::from_fn(|a| [(a % 3) as f64, 0.5 * (a / 3) as f64]);
        assert!((ElementGeometry::new(&square).unwrap().area() - 2.0).abs() < 1e-14);
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
        let geometry = ElementGeometry::new(&nodes).unwrap();
        for material in [Bilayer::new(&p).substrate_tissue(), Bilayer::new(&p).layer_tissue()] {
            assert_consistent_derivatives(&u, |v, k| evaluate(&geometry, &material, v, k).unwrap());
        }
    }

    #[test]
    fn inverted_element_is_an_error_not_nan() {
        let material: Tissue = Bilayer::new(&Parameters::default()).layer_tissue();
        let (nodes, _) = distorted();
        let geometry = ElementGeometry::new(&nodes).unwrap();
        // u_x = -2 X maps x = -X, a reflection with J = -1.
        let u: ElementVector = std::array::from_fn(|i| if i % 2 == 0 { -2.0 * nodes[i / 2][0] } else { 0.0 });
        let err = evaluate(&geometry, &material, &u, None).unwrap_err();
        assert!(matches!(err, Error::NonPositiveJacobian { .. }), "{err}");
    }
}
