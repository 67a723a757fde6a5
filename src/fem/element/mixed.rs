//! The mixed Q2/P1-discontinuous element for nearly incompressible tissue: biquadratic
//! displacements and, per element, a linear pressure `p = p_0 + p_1 (X - X_c)/h + p_2 (Y - Y_c)/h`
//! discontinuous across elements, condensed element by element.
//!
//! Why this pair: Q2/P1disc is inf-sup stable on quadrilaterals (Boffi, Brezzi and Fortin, *Mixed
//! Finite Element Methods*, sect. 8.6.3), converges at the optimal rates of Q2 in displacement,
//! and with the pressure unmapped (linear in `X`, not in `xi`) keeps them on distorted elements.
//! Its pressure lives on one element, so it is eliminated there and the global system keeps the
//! displacement element's unknowns, pattern and solver. Taylor-Hood Q2/Q1 is stable too, but its
//! continuous pressure adds global unknowns and turns every factorisation into a saddle point.
//!
//! The energy of every tissue is `W(F) = W_rest(F) + kappa/2 (ln J)^2`
//! ([`crate::material::Tissue::volumetric_split`]). The Hu-Washizu form with `p` conjugate to
//! `ln J`, `Pi(u, p) = int W_rest(F) + p ln J - p^2 / (2 kappa) dV`, is stationary in `p` at
//! `p = kappa P(ln J)`, the L2 projection of `ln J` onto the element's pressures (`M p = kappa g`,
//! `M_ij = int phi_i phi_j`, `g_i = int phi_i ln J`). Condensed, the element's energy is
//! `E(u) = int W_rest(F) dV + kappa/2 g^T M^-1 g`: a displacement-only energy whose volumetric
//! part sees `ln J` only through 3 moments per element (9 Gauss-point constraints lock the
//! displacement element). Its force is `int (P_rest + p F^-T) : Grad du` and its tangent
//! `int Grad du : (A_rest + p d(F^-T)/dF) : Grad du + kappa (dg/du)^T M^-1 (dg/du)`.
//!
//! Stability is read from the condensed tangent. The saddle-point matrix of `Pi`,
//! `S = [[K_uu, B^T], [B, -M/kappa]]` (`B = dg/du`), has by Haynsworth's inertia additivity
//! `In(S) = In(-M/kappa) + In(K_uu + kappa B^T M^-1 B)`: with `M` positive definite, `S` has
//! exactly one negative eigenvalue per pressure unknown more than the condensed tangent. Counting
//! the condensed tangent's negative pivots is therefore counting `S`'s and subtracting the
//! pressure block's known inertia; `tests::saddle_point_inertia_is_the_condensed_plus_pressures`
//! checks it.
//!
//! Exact incompressibility (`J = 1`, no bulk term) cannot be condensed per element: the
//! pressure is then a multiplier `lambda` per element, carried in the unknowns' vector after
//! the displacements ([`crate::fem::System::num_dofs`]) and found by the method of multipliers
//! (augmented Lagrangian, Uzawa). A large finite bulk modulus goes the same way
//! ([`Volumetric::Augmented`]): the exactly condensed energy is then correct but Newton's method
//! converges on it only from within about `mu / K` of the solution (its residual jumps by
//! `K |du|^2`), so a load step of a nearly incompressible solid fails where the multipliers'
//! moderate penalty succeeds. For fixed `lambda`, the element's energy is
//! `int W_rest dV + (1 - kappa/K) lambda . g + kappa/2 g^T M^-1 g` with a penalty `kappa` a
//! hundred times the largest shear modulus (small enough for Newton's method to converge in a
//! few steps), whose minimiser Newton's method finds; then
//! `lambda <- p = (1 - kappa/K) lambda + kappa M^-1 g`, whose fixed point `lambda = K M^-1 g` is
//! the condensed element's pressure (`M^-1 g = 0` for `K = inf`)
//! ([`crate::fem::equilibrium`] repeats both, with Aitken's relaxation and a tenfold penalty whenever
//! an update fails to halve the violation, until `|M^-1 g - lambda / K| <= 1e-7`: the
//! element-mean `ln J - lambda / K` and its gradient vanish to solver tolerance). At the
//! solution the state, the energy and the pressure `lambda` are those of the condensed element
//! (for `K = inf`: `g = 0` and the energy `int W_rest dV`), independent of `kappa`. The
//! tangent is the condensed one with `kappa` for the bulk modulus, the Schur complement of
//! `[[K_uu, B^T], [B, -M/kappa]]`; as above it has one negative eigenvalue fewer per pressure
//! than that matrix, which tends to the exact saddle point `[[K_uu, B^T], [B, 0]]` as `kappa`
//! grows: its inertia is that of the constrained displacements once `kappa` exceeds the
//! curvature of `K_uu` off the constraint (Finsler's lemma), of the order of the stresses. The
//! inertia is therefore counted on the tangent with a penalty 10^6 times the largest shear
//! modulus, or `K` where that is smaller (then the exact condensed tangent;
//! [`crate::fem::System::assemble_for_stability`]); the coarse-mesh bifurcation no longer
//! moves beyond 10^5 times.

use super::displacement::{self, add_force, add_tangent, mirror_upper_triangle};
use super::{
    ElementGeometry, ElementMatrix, ElementState, ElementVector, FiniteElement, DOFS, ELEMENT_DOFS, GAUSS_POINTS,
};
use crate::error::{Error, Result};
use crate::material::{add_pressure, cofactor, jacobian, nested, point_cauchy, PointResponse, StrainEnergy, Tissue};

/// Pressure unknowns per element: a linear polynomial in `X`.
pub const PRESSURES: usize = 3;

/// How an element's volume change is resisted.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Volumetric {
    /// By the bulk term `kappa/2 (ln J)^2`, condensed exactly.
    Bulk(f64),
    /// By multipliers and an augmentation penalty (times the scale [`MixedElement::evaluate`]
    /// is given): the constraint `J = 1` when `bulk` is infinite, else the bulk term
    /// `bulk/2 (ln J)^2`, reached by the same iteration (a bulk modulus far above the shear
    /// modulus makes Newton's method on the condensed energy converge only from very close).
    Augmented { penalty: f64, bulk: f64 },
}

/// One mixed element's pressure space and the split of its tissue.
#[derive(Clone, Debug)]
pub struct MixedElement {
    /// `phi_i` at each Gauss point.
    basis: [[f64; PRESSURES]; GAUSS_POINTS],
    /// Inverse of the pressure mass matrix `M_ij = int phi_i phi_j dV`.
    mass_inverse: [[f64; PRESSURES]; PRESSURES],
    /// The tissue without its bulk term.
    rest: Tissue,
    /// `ln Jg`: the volume measure is `ln J - ln Jg` (zero without growth).
    log_volume: f64,
    volumetric: Volumetric,
}

/// What a mixed element returns besides [`ElementState`].
#[derive(Clone, Copy, Debug)]
pub struct MixedState {
    pub state: ElementState,
    /// The pressure `p` in the element's basis: `kappa M^-1 g` (bulk), or
    /// `(1 - kappa/K) lambda + kappa M^-1 g` (augmented; the multipliers' next iterate).
    pub pressure: [f64; PRESSURES],
    /// How far the multipliers are from their fixed point, `(p - lambda) / kappa =
    /// M^-1 g - lambda / K` (zero at the solution; `M^-1 g`, the L2 projection of `ln J`,
    /// under the constraint `K = inf`). Zero for the bulk mode.
    pub violation: [f64; PRESSURES],
}

impl MixedElement {
    /// The element of `tissue` on `geometry`, with the pressure basis centred at the element's
    /// centroid and scaled by `sqrt(area)` (a well-conditioned `M`); `constraint` makes it
    /// exactly incompressible with those penalties (the tissue's bulk modulus is then unused).
    pub fn new(geometry: &ElementGeometry, tissue: &Tissue, constraint: Option<Volumetric>) -> Self {
        let (points, weights) = (geometry.points(), geometry.weights());
        let area = geometry.volume();
        let centroid: [f64; 2] =
            std::array::from_fn(|c| points.iter().zip(weights).map(|(x, w)| w * x[c]).sum::<f64>() / area);
        let h = area.sqrt();
        let basis: [[f64; PRESSURES]; GAUSS_POINTS] =
            std::array::from_fn(|g| [1.0, (points[g][0] - centroid[0]) / h, (points[g][1] - centroid[1]) / h]);
        let mass: [[f64; PRESSURES]; PRESSURES] = std::array::from_fn(|i| {
            std::array::from_fn(|j| (0..GAUSS_POINTS).map(|g| weights[g] * basis[g][i] * basis[g][j]).sum())
        });
        let split = tissue.volumetric_split();
        MixedElement {
            basis,
            mass_inverse: inverse3(&mass),
            rest: split.rest,
            log_volume: split.log_volume,
            volumetric: constraint.unwrap_or(Volumetric::Bulk(split.bulk)),
        }
    }

    /// `phi_i` at Gauss point `g`.
    pub fn basis(&self, g: usize) -> &[f64; PRESSURES] {
        &self.basis[g]
    }

    /// The tissue without its bulk term.
    pub fn rest(&self) -> &Tissue {
        &self.rest
    }

    /// Force, energy and pressure at nodal displacements `u` (and multipliers `lambda` under the
    /// constraint; unused otherwise), and the condensed tangent into `stiffness` when given
    /// (overwritten, symmetric); the constraint's penalty is multiplied by `penalty_scale`.
    /// `J <= 0` at a Gauss point is an error.
    pub fn evaluate(
        &self,
        geometry: &ElementGeometry,
        u: &ElementVector,
        lambda: &[f64; PRESSURES],
        penalty_scale: f64,
        mut stiffness: Option<&mut ElementMatrix>,
    ) -> Result<MixedState> {
        let mut gradients = [[0.0; 4]; GAUSS_POINTS];
        let mut jacobians = [0.0; GAUSS_POINTS];
        // g_i = int phi_i ln J and B_i = dg_i/du.
        let mut moments = [0.0; PRESSURES];
        let mut moment_derivatives = [[0.0; DOFS]; PRESSURES];
        for g in 0..GAUSS_POINTS {
            let f = geometry.deformation_gradient(g, u);
            let j = jacobian(&f);
            if !(j > 0.0 && j.is_finite()) {
                return Err(Error::NonPositiveJacobian { jacobian: j });
            }
            self.rest.admissible(&crate::material::plane_gradient(&f, 1.0))?;
            let inverse_transpose = cofactor(&f).map(|c| c / j);
            let (w, phi) = (geometry.weights()[g], &self.basis[g]);
            for (a, grad) in geometry.gradients(g).iter().enumerate() {
                // d ln J / d u_ai = F^-T_iJ dN_a/dX_J.
                let dx = inverse_transpose[0] * grad[0] + inverse_transpose[1] * grad[1];
                let dy = inverse_transpose[2] * grad[0] + inverse_transpose[3] * grad[1];
                for (row, &phi_i) in moment_derivatives.iter_mut().zip(phi) {
                    row[ELEMENT_DOFS.dof(a, 0)] += w * phi_i * dx;
                    row[ELEMENT_DOFS.dof(a, 1)] += w * phi_i * dy;
                }
            }
            for (moment, &phi_i) in moments.iter_mut().zip(phi) {
                *moment += w * phi_i * (j.ln() - self.log_volume);
            }
            (gradients[g], jacobians[g]) = (f, j);
        }
        let projected_log_j = multiply3(&self.mass_inverse, &moments);
        let (modulus, pressure, (volumetric_energy, volumetric_potential), violation) = match self.volumetric {
            // p = kappa M^-1 g; the condensed energy kappa/2 g^T M^-1 g = g . p / 2.
            Volumetric::Bulk(kappa) => {
                let p = projected_log_j.map(|x| kappa * x);
                let energy = 0.5 * dot3(&moments, &p);
                (kappa, p, (energy, energy), [0.0; PRESSURES])
            }
            // For fixed lambda, the energy `int W_rest + (1 - kappa/K) lambda . g + kappa/2
            // g^T M^-1 g` has the force of p = (1 - kappa/K) lambda + kappa M^-1 g; its fixed
            // point lambda = p is K M^-1 g, the bulk mode's pressure (M^-1 g = 0 for K = inf).
            // The energy reported is the true one, K/2 g^T M^-1 g at the fixed point (with the
            // augmentation's, which tends to zero with g, when K = inf); the potential, whose
            // gradient the force is, the augmented one for fixed lambda (a minimisation
            // measured by the true energy finds it rising along directions its force says lower
            // it: the snaps of K / mu = 1e4 stopped so).
            Volumetric::Augmented { penalty, bulk } => {
                let kappa = (penalty * penalty_scale).min(bulk);
                let relaxation = 1.0 - kappa / bulk;
                let p: [f64; PRESSURES] = std::array::from_fn(|i| relaxation * lambda[i] + kappa * projected_log_j[i]);
                let potential = relaxation * dot3(lambda, &moments) + 0.5 * kappa * dot3(&moments, &projected_log_j);
                let energy = match bulk.is_finite() {
                    true => 0.5 * bulk * dot3(&moments, &projected_log_j),
                    false => potential,
                };
                let violation = std::array::from_fn(|i| (p[i] - lambda[i]) / kappa);
                (kappa, p, (energy, potential), violation)
            }
        };
        let mut state = ElementState {
            force: [0.0; DOFS],
            energy: volumetric_energy,
            potential: volumetric_potential,
            min_jacobian: jacobians.iter().copied().fold(f64::INFINITY, f64::min),
        };
        if let Some(k) = stiffness.as_deref_mut() {
            *k = [[0.0; DOFS]; DOFS];
        }
        for (g, f) in gradients.iter().enumerate() {
            let (w, grads) = (geometry.weights()[g], geometry.gradients(g));
            let p = dot3(&self.basis[g], &pressure);
            let stress = match stiffness.as_deref_mut() {
                Some(k) => {
                    let mut response = self.rest.plane_response(f);
                    add_pressure(&mut response.stress, Some(&mut response.tangent), f, p);
                    let response = PointResponse::<2>::from_flat(&response);
                    add_tangent(k, grads, &response.tangent, w);
                    state.energy += w * response.energy;
                    state.potential += w * response.energy;
                    response.stress
                }
                None => {
                    let (energy, mut stress) = self.rest.plane_stress(f);
                    add_pressure(&mut stress, None, f, p);
                    state.energy += w * energy;
                    state.potential += w * energy;
                    nested(&stress)
                }
            };
            add_force(&mut state.force, grads, &stress, w);
        }
        if let Some(k) = stiffness {
            mirror_upper_triangle(k);
            // + kappa B^T M^-1 B.
            let scaled: [[f64; DOFS]; PRESSURES] = std::array::from_fn(|i| {
                std::array::from_fn(|c| {
                    modulus
                        * (0..PRESSURES)
                            .map(|l| self.mass_inverse[i][l] * moment_derivatives[l][c])
                            .sum::<f64>()
                })
            });
            for (r, row) in k.iter_mut().enumerate() {
                for (c, entry) in row.iter_mut().enumerate() {
                    *entry += (0..PRESSURES)
                        .map(|i| moment_derivatives[i][r] * scaled[i][c])
                        .sum::<f64>();
                }
            }
        }
        Ok(MixedState {
            state,
            pressure,
            violation,
        })
    }
}

impl FiniteElement for MixedElement {
    fn evaluate(
        &self,
        geometry: &ElementGeometry,
        u: &ElementVector,
        lambda: &[f64; PRESSURES],
        penalty_scale: f64,
        stiffness: Option<&mut ElementMatrix>,
    ) -> Result<ElementState> {
        Ok(MixedElement::evaluate(self, geometry, u, lambda, penalty_scale, stiffness)?.state)
    }

    /// Under multipliers, of the energy without its volumetric part: that part's penalty would
    /// make the displacements it scales stiff against the multipliers' updates.
    fn reference_stiffness(&self, geometry: &ElementGeometry, stiffness: &mut ElementMatrix) -> Result<()> {
        let lambda = [0.0; PRESSURES];
        match self.volumetric {
            Volumetric::Augmented { .. } => displacement::evaluate(geometry, &self.rest, &[0.0; DOFS], Some(stiffness)),
            Volumetric::Bulk(_) => FiniteElement::evaluate(self, geometry, &[0.0; DOFS], &lambda, 1.0, Some(stiffness)),
        }
        .map(|_| ())
    }

    /// `sigma = sigma_rest + p / J I`, `p` the element's pressure at the point.
    fn cauchy(
        &self,
        geometry: &ElementGeometry,
        g: usize,
        u: &ElementVector,
        lambda: &[f64; PRESSURES],
    ) -> Result<[[f64; 3]; 3]> {
        let f = geometry.deformation_gradient(g, u);
        let pressure = MixedElement::evaluate(self, geometry, u, lambda, 1.0, None)?.pressure;
        let p: f64 = self.basis[g].iter().zip(&pressure).map(|(a, b)| a * b).sum();
        let mut sigma = point_cauchy(&self.rest, &geometry.gradient_at(g, u))?;
        for (i, row) in sigma.iter_mut().enumerate() {
            row[i] += p / jacobian(&f);
        }
        Ok(sigma)
    }

    fn has_multipliers(&self) -> bool {
        matches!(self.volumetric, Volumetric::Augmented { .. })
    }

    fn multiplier_step(
        &self,
        geometry: &ElementGeometry,
        u: &ElementVector,
        lambda: &[f64; PRESSURES],
        penalty_scale: f64,
    ) -> Result<(f64, [f64; PRESSURES])> {
        let state = MixedElement::evaluate(self, geometry, u, lambda, penalty_scale, None)?;
        let violation = state.violation.iter().fold(0.0f64, |v, x| v.max(x.abs()));
        let change: [f64; PRESSURES] = match self.volumetric {
            Volumetric::Augmented { .. } => std::array::from_fn(|i| state.pressure[i] - lambda[i]),
            Volumetric::Bulk(_) => [0.0; PRESSURES],
        };
        Ok((violation, change))
    }
}

fn dot3(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn multiply3(m: &[[f64; 3]; 3], v: &[f64; 3]) -> [f64; 3] {
    std::array::from_fn(|i| dot3(&m[i], v))
}

/// Inverse of a 3x3 matrix by cofactors (the pressure mass matrix, positive definite).
fn inverse3(m: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let cof = |i: usize, j: usize| {
        let (r0, r1) = ((i + 1) % 3, (i + 2) % 3);
        let (c0, c1) = ((j + 1) % 3, (j + 2) % 3);
        m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0]
    };
    let det = (0..3).map(|j| m[0][j] * cof(0, j)).sum::<f64>();
    std::array::from_fn(|i| std::array::from_fn(|j| cof(j, i) / det))
}

mod multipliers;
pub use multipliers::PressureUpdate;

#[cfg(test)]
mod tests;
