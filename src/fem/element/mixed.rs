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
//! hundred times the tissue's own shear modulus (small enough for Newton's method to converge in
//! a few steps), whose minimiser Newton's method finds; then
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
//! inertia is therefore counted on the tangent with a penalty 10^5 times the tissue's shear
//! modulus, or `K` where that is smaller (then the exact condensed tangent;
//! [`crate::fem::System::assemble_for_stability`]); a bifurcation no longer moves beyond 10^4
//! times, and 10^6 times loses small eigenvalues in round-off. That tangent is the Hessian of
//! the Lagrangian `int W_rest + lambda . g` at the multipliers plus `kappa B^T M^-1 B`
//! ([`Penalty::Stability`]): its pressure is `lambda`, not the iteration's
//! `lambda + kappa M^-1 g`, whose residual violation times this large `kappa` is no pressure of
//! the tissue. Each tissue's penalty is scaled by its own shear modulus: scaled by
//! the stiffer layer's, a substrate a hundred times softer carries a penalty 10^8 times its
//! stiffness, whose round-off in the factorisation misses or invents negative pivots.

use super::displacement::{self, add_force, add_tangent, mirror_upper_triangle};
use super::{determinant, ElementGeometry, ElementMatrix, ElementState, ElementVector, FiniteElement, GAUSS_POINTS};
use crate::error::{Error, Result};
use crate::material::{
    full_gradient, inverse_transpose_of, point_cauchy, pressured_response, pressured_stress, StrainEnergy, Tissue,
};
use crate::mesh::DofMap;

/// Pressure unknowns per element in `dimension` dimensions: a linear polynomial in `X`.
pub const fn pressures(dimension: usize) -> usize {
    dimension + 1
}

/// Pressure unknowns per element of the plane meshes.
pub const PRESSURES: usize = pressures(2);

/// The most pressure unknowns per element (three dimensions).
pub const MAX_PRESSURES: usize = pressures(3);

/// One element's pressures or multipliers, the first [`pressures`]`(D)` used.
pub type Pressures = [f64; MAX_PRESSURES];

/// How one evaluation penalises an element's volume constraint (elements without one ignore it).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Penalty {
    /// The method of multipliers: the augmentation penalty times this scale, and the pressure
    /// `(1 - kappa/K) lambda + kappa M^-1 g` whose force is the gradient of the energy for fixed
    /// `lambda`.
    Augmentation(f64),
    /// The tangent whose inertia is the stability: the Hessian of the Lagrangian at the
    /// multipliers, whose pressure is `lambda` itself, plus the constraint's stiffness
    /// `kappa B^T M^-1 B` with the augmentation penalty times this scale. The iteration's
    /// pressure would add `kappa M^-1 g` at this large `kappa`: with the constraint met to the
    /// solver's 1e-7, a pressure error of 10 in a layer a hundred times stiffer than the
    /// substrate, which made the count of negative pivots flicker.
    Stability(f64),
}

impl Penalty {
    /// The factor on the augmentation penalty.
    pub fn scale(self) -> f64 {
        match self {
            Penalty::Augmentation(scale) | Penalty::Stability(scale) => scale,
        }
    }
}

/// How an element's volume change is resisted.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Volumetric {
    /// By the bulk term `kappa/2 (ln J)^2`, condensed exactly.
    Bulk(f64),
    /// By multipliers and an augmentation penalty (times the [`Penalty`]'s scale
    /// [`MixedElement::evaluate`] is given): the constraint `J = 1` when `bulk` is infinite,
    /// else the bulk term `bulk/2 (ln J)^2`, reached by the same iteration (a bulk modulus far
    /// above the shear modulus makes Newton's method on the condensed energy converge only from
    /// very close).
    Augmented { penalty: f64, bulk: f64 },
}

/// One mixed element's pressure space and the split of its tissue, in `D` dimensions with `Q`
/// quadrature points and `P = D + 1` pressures (the plane one by default).
#[derive(Clone, Debug)]
pub struct MixedElement<const D: usize = 2, const Q: usize = GAUSS_POINTS, const P: usize = PRESSURES> {
    /// `phi_i` at each Gauss point.
    basis: [[f64; P]; Q],
    /// Inverse of the pressure mass matrix `M_ij = int phi_i phi_j dV`.
    mass_inverse: [[f64; P]; P],
    /// The tissue without its bulk term.
    rest: Tissue,
    /// `ln Jg`: the volume measure is `ln J - ln Jg` (zero without growth).
    log_volume: f64,
    volumetric: Volumetric,
}

/// What a mixed element returns besides [`ElementState`].
#[derive(Clone, Copy, Debug)]
pub struct MixedState<const U: usize = { super::DOFS }, const P: usize = PRESSURES> {
    pub state: ElementState<U>,
    /// The pressure `p` in the element's basis: `kappa M^-1 g` (bulk), or
    /// `(1 - kappa/K) lambda + kappa M^-1 g` (augmented; the multipliers' next iterate).
    pub pressure: [f64; P],
    /// How far the multipliers are from their fixed point, `(p - lambda) / kappa =
    /// M^-1 g - lambda / K` (zero at the solution; `M^-1 g`, the L2 projection of `ln J`,
    /// under the constraint `K = inf`). Zero for the bulk mode.
    pub violation: [f64; P],
}

impl<const D: usize, const Q: usize, const P: usize> MixedElement<D, Q, P> {
    /// The element of `tissue` on `geometry`, with the pressure basis centred at the element's
    /// centroid and scaled by the element's size `V^(1/D)` (a well-conditioned `M`);
    /// `constraint` makes it exactly incompressible with those penalties (the tissue's bulk
    /// modulus is then unused).
    pub fn new<const N: usize>(
        geometry: &ElementGeometry<D, N, Q>,
        tissue: &Tissue,
        constraint: Option<Volumetric>,
    ) -> Self {
        let (points, weights) = (geometry.points(), geometry.weights());
        let volume = geometry.volume();
        let centroid: [f64; D] =
            std::array::from_fn(|c| points.iter().zip(weights).map(|(x, w)| w * x[c]).sum::<f64>() / volume);
        let h = if D == 2 { volume.sqrt() } else { volume.cbrt() };
        assert_eq!(P, pressures(D), "a linear pressure: D + 1 unknowns");
        let basis: [[f64; P]; Q] = std::array::from_fn(|g| {
            std::array::from_fn(|i| match i {
                0 => 1.0,
                _ => (points[g][i - 1] - centroid[i - 1]) / h,
            })
        });
        let mass: [[f64; P]; P] = std::array::from_fn(|i| {
            std::array::from_fn(|j| (0..Q).map(|g| weights[g] * basis[g][i] * basis[g][j]).sum())
        });
        let split = tissue.volumetric_split();
        MixedElement {
            basis,
            mass_inverse: inverse(&mass),
            rest: split.rest,
            log_volume: split.log_volume,
            volumetric: constraint.unwrap_or(Volumetric::Bulk(split.bulk)),
        }
    }

    /// `phi_i` at Gauss point `g`.
    pub fn basis(&self, g: usize) -> &[f64; P] {
        &self.basis[g]
    }

    /// The tissue without its bulk term.
    pub fn rest(&self) -> &Tissue {
        &self.rest
    }

    /// Force, energy and pressure at nodal displacements `u` (and multipliers `lambda` under the
    /// constraint; unused otherwise), and the condensed tangent into `stiffness` when given
    /// (overwritten, symmetric); the constraint is penalised as `penalty` says.
    /// `J <= 0` at a Gauss point is an error.
    pub fn evaluate<const N: usize, const U: usize>(
        &self,
        geometry: &ElementGeometry<D, N, Q>,
        u: &ElementVector<U>,
        lambda: &Pressures,
        penalty: Penalty,
        mut stiffness: Option<&mut ElementMatrix<U>>,
    ) -> Result<MixedState<U, P>> {
        let dofs = DofMap::of_dimension(D);
        let lambda: [f64; P] = std::array::from_fn(|i| lambda[i]);
        let mut gradients = [[[0.0; D]; D]; Q];
        let mut jacobians = [0.0; Q];
        // g_i = int phi_i ln J and B_i = dg_i/du.
        let mut moments = [0.0; P];
        let mut moment_derivatives = [[0.0; U]; P];
        for g in 0..Q {
            let f = geometry.gradient_at(g, u);
            let j = determinant(&f);
            if !(j > 0.0 && j.is_finite()) {
                return Err(Error::NonPositiveJacobian { jacobian: j });
            }
            self.rest.admissible(&full_gradient(&f))?;
            let inverse_transpose = inverse_transpose_of(&f, j);
            let (w, phi) = (geometry.weights()[g], &self.basis[g]);
            for (a, grad) in geometry.gradients(g).iter().enumerate() {
                // d ln J / d u_ai = F^-T_iJ dN_a/dX_J.
                let d: [f64; D] = std::array::from_fn(|i| contract(&inverse_transpose[i], grad));
                for (row, &phi_i) in moment_derivatives.iter_mut().zip(phi) {
                    for (i, d_i) in d.iter().enumerate() {
                        row[dofs.dof(a, i)] += w * phi_i * d_i;
                    }
                }
            }
            let log_volume_change = j.ln() - self.log_volume;
            for (moment, &phi_i) in moments.iter_mut().zip(phi) {
                *moment += w * phi_i * log_volume_change;
            }
            (gradients[g], jacobians[g]) = (f, j);
        }
        let projected_log_j = multiply(&self.mass_inverse, &moments);
        let (modulus, pressure, (volumetric_energy, volumetric_potential), violation) = match self.volumetric {
            // p = kappa M^-1 g; the condensed energy kappa/2 g^T M^-1 g = g . p / 2.
            Volumetric::Bulk(kappa) => {
                let p = projected_log_j.map(|x| kappa * x);
                let energy = 0.5 * dot(&moments, &p);
                (kappa, p, (energy, energy), [0.0; P])
            }
            // For fixed lambda, the energy `int W_rest + (1 - kappa/K) lambda . g + kappa/2
            // g^T M^-1 g` has the force of p = (1 - kappa/K) lambda + kappa M^-1 g; its fixed
            // point lambda = p is K M^-1 g, the bulk mode's pressure (M^-1 g = 0 for K = inf).
            // The energy reported is the true one, K/2 g^T M^-1 g at the fixed point (with the
            // augmentation's, which tends to zero with g, when K = inf); the potential, whose
            // gradient the force is, the augmented one for fixed lambda (a minimisation
            // measured by the true energy finds it rising along directions its force says lower
            // it: the snaps of K / mu = 1e4 stopped so).
            Volumetric::Augmented {
                penalty: augmentation,
                bulk,
            } => {
                let kappa = (augmentation * penalty.scale()).min(bulk);
                let relaxation = 1.0 - kappa / bulk;
                let (p, potential): ([f64; P], f64) = match penalty {
                    Penalty::Augmentation(_) => (
                        std::array::from_fn(|i| relaxation * lambda[i] + kappa * projected_log_j[i]),
                        relaxation * dot(&lambda, &moments) + 0.5 * kappa * dot(&moments, &projected_log_j),
                    ),
                    Penalty::Stability(_) => (lambda, dot(&lambda, &moments)),
                };
                let energy = match bulk.is_finite() {
                    true => 0.5 * bulk * dot(&moments, &projected_log_j),
                    false => potential,
                };
                let violation = std::array::from_fn(|i| (p[i] - lambda[i]) / kappa);
                (kappa, p, (energy, potential), violation)
            }
        };
        let mut state = ElementState {
            force: [0.0; U],
            energy: volumetric_energy,
            potential: volumetric_potential,
            min_jacobian: jacobians.iter().copied().fold(f64::INFINITY, f64::min),
        };
        if let Some(k) = stiffness.as_deref_mut() {
            *k = [[0.0; U]; U];
        }
        for (g, f) in gradients.iter().enumerate() {
            let (w, grads) = (geometry.weights()[g], geometry.gradients(g));
            let p = dot(&self.basis[g], &pressure);
            let stress = match stiffness.as_deref_mut() {
                Some(k) => {
                    let response = pressured_response(&self.rest, f, p);
                    add_tangent(k, grads, &response.tangent, w);
                    state.energy += w * response.energy;
                    state.potential += w * response.energy;
                    response.stress
                }
                None => {
                    let (energy, stress) = pressured_stress(&self.rest, f, p);
                    state.energy += w * energy;
                    state.potential += w * energy;
                    stress
                }
            };
            add_force(&mut state.force, grads, &stress, w);
        }
        if let Some(k) = stiffness {
            mirror_upper_triangle(k);
            // + kappa B^T M^-1 B.
            let scaled: [[f64; U]; P] = std::array::from_fn(|i| {
                std::array::from_fn(|c| {
                    modulus
                        * (0..P)
                            .map(|l| self.mass_inverse[i][l] * moment_derivatives[l][c])
                            .sum::<f64>()
                })
            });
            for (r, row) in k.iter_mut().enumerate() {
                for (c, entry) in row.iter_mut().enumerate() {
                    *entry += (0..P).map(|i| moment_derivatives[i][r] * scaled[i][c]).sum::<f64>();
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

impl<const D: usize, const N: usize, const Q: usize, const U: usize, const P: usize> FiniteElement<D, N, Q, U>
    for MixedElement<D, Q, P>
{
    fn evaluate(
        &self,
        geometry: &ElementGeometry<D, N, Q>,
        u: &ElementVector<U>,
        lambda: &Pressures,
        penalty: Penalty,
        stiffness: Option<&mut ElementMatrix<U>>,
    ) -> Result<ElementState<U>> {
        Ok(MixedElement::evaluate(self, geometry, u, lambda, penalty, stiffness)?.state)
    }

    /// Under multipliers, of the energy without its volumetric part: that part's penalty would
    /// make the displacements it scales stiff against the multipliers' updates.
    fn reference_stiffness(&self, geometry: &ElementGeometry<D, N, Q>, stiffness: &mut ElementMatrix<U>) -> Result<()> {
        let lambda = [0.0; MAX_PRESSURES];
        match self.volumetric {
            Volumetric::Augmented { .. } => displacement::evaluate(geometry, &self.rest, &[0.0; U], Some(stiffness)),
            Volumetric::Bulk(_) => FiniteElement::evaluate(
                self,
                geometry,
                &[0.0; U],
                &lambda,
                Penalty::Augmentation(1.0),
                Some(stiffness),
            ),
        }
        .map(|_| ())
    }

    /// `sigma = sigma_rest + p / J I`, `p` the element's pressure at the point.
    fn cauchy(
        &self,
        geometry: &ElementGeometry<D, N, Q>,
        g: usize,
        u: &ElementVector<U>,
        lambda: &Pressures,
    ) -> Result<[[f64; 3]; 3]> {
        let f = geometry.gradient_at(g, u);
        let pressure = MixedElement::evaluate(self, geometry, u, lambda, Penalty::Augmentation(1.0), None)?.pressure;
        let p: f64 = self.basis[g].iter().zip(&pressure).map(|(a, b)| a * b).sum();
        let mut sigma = point_cauchy(&self.rest, &f)?;
        for (i, row) in sigma.iter_mut().enumerate() {
            row[i] += p / determinant(&f);
        }
        Ok(sigma)
    }

    fn has_multipliers(&self) -> bool {
        matches!(self.volumetric, Volumetric::Augmented { .. })
    }

    fn multiplier_step(
        &self,
        geometry: &ElementGeometry<D, N, Q>,
        u: &ElementVector<U>,
        lambda: &Pressures,
        penalty_scale: f64,
    ) -> Result<(f64, Pressures)> {
        let state = MixedElement::evaluate(self, geometry, u, lambda, Penalty::Augmentation(penalty_scale), None)?;
        let violation = state.violation.iter().fold(0.0f64, |v, x| v.max(x.abs()));
        let change: Pressures = match self.volumetric {
            Volumetric::Augmented { .. } => std::array::from_fn(|i| match i < P {
                true => state.pressure[i] - lambda[i],
                false => 0.0,
            }),
            Volumetric::Bulk(_) => [0.0; MAX_PRESSURES],
        };
        Ok((violation, change))
    }
}

/// `sum_J a_J b_J`, summed from the first term on.
fn contract<const D: usize>(a: &[f64; D], b: &[f64; D]) -> f64 {
    (1..D).fold(a[0] * b[0], |s, l| s + a[l] * b[l])
}

/// `sum_i a_i b_i`, summed from the first term on.
fn dot<const P: usize>(a: &[f64; P], b: &[f64; P]) -> f64 {
    (1..P).fold(a[0] * b[0], |s, i| s + a[i] * b[i])
}

/// `m v`.
fn multiply<const P: usize>(m: &[[f64; P]; P], v: &[f64; P]) -> [f64; P] {
    std::array::from_fn(|i| dot(&m[i], v))
}

/// Inverse of the pressure mass matrix (positive definite): by cofactors for three pressures,
/// by nalgebra's LU for four.
fn inverse<const P: usize>(m: &[[f64; P]; P]) -> [[f64; P]; P] {
    match P {
        3 => {
            let cof = |i: usize, j: usize| {
                let (r0, r1) = ((i + 1) % 3, (i + 2) % 3);
                let (c0, c1) = ((j + 1) % 3, (j + 2) % 3);
                m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0]
            };
            let det = (0..3).map(|j| m[0][j] * cof(0, j)).sum::<f64>();
            std::array::from_fn(|i| std::array::from_fn(|j| cof(j, i) / det))
        }
        _ => {
            let inverse = nalgebra::DMatrix::from_fn(P, P, |i, j| m[i][j])
                .try_inverse()
                .expect("the pressure mass matrix is positive definite");
            std::array::from_fn(|i| std::array::from_fn(|j| inverse[(i, j)]))
        }
    }
}

mod multipliers;
pub use multipliers::PressureUpdate;

#[cfg(test)]
mod tests;
