//! The discrete cross-check: quadratic finite elements in `Y` for fixed `k`.
//!
//! With `u1 = a(Y) sin kX`, `u2 = b(Y) cos kX`, the second variation of the energy per
//! wavelength is `(pi/k) * integral of g . C g dY`, `g = (a, a', b, b')`
//! ([`IncrementalModuli::energy_form`]), on `[-depth, 1]` with `a = b = 0` at the bottom and
//! natural (traction-free, continuous-traction) conditions elsewhere. The homogeneous state is
//! stable while this stiffness is positive definite; `d_c` is where it first is not.

use super::IncrementalModuli;
use crate::numerics::banded::SymmetricBanded;
use crate::numerics::dofs::DofMap;
use crate::numerics::grading::geometric_ratio;

/// The unknowns of a node of the quadratic elements: the amplitudes `a` (component 0) and `b`
/// (component 1).
const AMPLITUDES: DofMap = DofMap::PLANE;
/// The unknowns of a node of the Hermite elements: `b` and `b'`.
const HERMITE: DofMap = DofMap::PLANE;

/// Discretisation of the `Y` axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DiscreteOptions {
    /// Quadratic elements through the layer `0 < Y < 1`.
    pub layer_elements: usize,
    /// Quadratic elements in the substrate, graded geometrically from `Y = 0` down.
    pub substrate_elements: usize,
    /// Truncation depth in units of the slowest decay length `1 / (k min Re p)` of the
    /// substrate (`p` the Stroh roots of the characteristic quartic).
    pub depth_decay_lengths: f64,
}

impl Default for DiscreteOptions {
    fn default() -> Self {
        DiscreteOptions {
            layer_elements: 32,
            substrate_elements: 320,
            depth_decay_lengths: 30.0,
        }
    }
}

impl DiscreteOptions {
    /// Element boundaries from `-depth` to 1: uniform in the layer, geometric in the substrate
    /// with the top substrate element as thick as a layer element (or thinner for short waves).
    pub fn nodes_of_elements(&self, k: f64, slowest_decay: f64) -> Vec<f64> {
        let depth = self.depth_decay_lengths / (k * slowest_decay);
        let h_layer = 1.0 / self.layer_elements as f64;
        let h0 = h_layer.min(0.05 * 2.0 * std::f64::consts::PI / k);
        let ratio = geometric_ratio(h0, depth, self.substrate_elements);
        let mut y = vec![0.0];
        let mut h = h0;
        for _ in 0..self.substrate_elements {
            let next = y.last().unwrap() - h;
            y.push(next);
            h *= ratio;
        }
        *y.last_mut().unwrap() = -depth;
        y.reverse();
        y.extend((1..=self.layer_elements).map(|i| i as f64 * h_layer));
        y
    }
}

/// The smallest positive real part of the substrate's Stroh roots (decay rate per unit `k Y`).
fn slowest_decay(substrate: &IncrementalModuli) -> Option<f64> {
    let slowest = substrate
        .decaying_roots()
        .iter()
        .map(|p| p.re)
        .fold(f64::INFINITY, f64::min);
    (slowest.is_finite() && slowest > 0.0).then_some(slowest)
}

/// Number of negative eigenvalues of the discrete incremental stiffness at wavenumber `k`;
/// `None` if it is singular to working precision or the substrate does not decay.
pub fn negative_eigenvalues(
    layer: &IncrementalModuli,
    substrate: &IncrementalModuli,
    k: f64,
    options: &DiscreteOptions,
) -> Option<usize> {
    if layer.incompressible_ratio.is_some() || substrate.incompressible_ratio.is_some() {
        return incompressible_negative_eigenvalues(layer, substrate, k, options);
    }
    let y = options.nodes_of_elements(k, slowest_decay(substrate)?);
    let elements = y.len() - 1;
    let unknowns = AMPLITUDES.count(2 * elements + 1);
    let mut stiffness = SymmetricBanded::zeros(unknowns, 5);
    let gauss = [
        (-(0.6f64).sqrt(), 5.0 / 9.0),
        (0.0, 8.0 / 9.0),
        ((0.6f64).sqrt(), 5.0 / 9.0),
    ];
    for e in 0..elements {
        let (y0, y1) = (y[e], y[e + 1]);
        let moduli = if y0 >= 0.0 { layer } else { substrate };
        let form = moduli.energy_form(k);
        let jac = 0.5 * (y1 - y0);
        for &(xi, weight) in &gauss {
            let n = [0.5 * xi * (xi - 1.0), 1.0 - xi * xi, 0.5 * xi * (xi + 1.0)];
            let dn = [(xi - 0.5) / jac, -2.0 * xi / jac, (xi + 0.5) / jac];
            // Rows of B: g = (a, a', b, b') from element unknowns (a_0, b_0, a_1, b_1, a_2, b_2).
            let mut b = [[0.0; 6]; 4];
            for node in 0..3 {
                b[0][AMPLITUDES.dof(node, 0)] = n[node];
                b[1][AMPLITUDES.dof(node, 0)] = dn[node];
                b[2][AMPLITUDES.dof(node, 1)] = n[node];
                b[3][AMPLITUDES.dof(node, 1)] = dn[node];
            }
            for p in 0..6 {
                for q in 0..=p {
                    let mut value = 0.0;
                    for r in 0..4 {
                        for s in 0..4 {
                            value += b[r][p] * form[r][s] * b[s][q];
                        }
                    }
                    // Element e's first node is node 2 e.
                    let first = AMPLITUDES.dof(2 * e, 0);
                    stiffness.add(first + p, first + q, value * weight * jac);
                }
            }
        }
    }
    stiffness.constrain(0);
    stiffness.constrain(1);
    stiffness.negative_eigenvalues()
}

/// [`negative_eigenvalues`] of two incompressible layers with the same `r = lambda_2 / lambda_1`.
/// The constraint `b' = -r k a` is solved for `a = -b' / (r k)`, so `g = (a, a', b, b')` follows
/// from `b` and its first two derivatives: `b` is interpolated by C1 cubic Hermite elements
/// (`b` and `b'`, hence `a`, continuous), and the stiffness is positive definite exactly while the
/// constrained second variation is.
fn incompressible_negative_eigenvalues(
    layer: &IncrementalModuli,
    substrate: &IncrementalModuli,
    k: f64,
    options: &DiscreteOptions,
) -> Option<usize> {
    let r = layer.incompressible_ratio?;
    if substrate.incompressible_ratio != Some(r) {
        return None;
    }
    let y = options.nodes_of_elements(k, slowest_decay(substrate)?);
    let elements = y.len() - 1;
    let mut stiffness = SymmetricBanded::zeros(HERMITE.count(elements + 1), 3);
    let gauss = gauss_legendre_4();
    for e in 0..elements {
        let (y0, y1) = (y[e], y[e + 1]);
        let form = if y0 >= 0.0 { layer } else { substrate }.energy_form(k);
        let h = y1 - y0;
        for &(t, weight) in &gauss {
            // Hermite cubics on [y0, y1] for (b_0, b'_0, b_1, b'_1), and their Y-derivatives.
            let (n, dn, ddn) = hermite_cubics(t, h);
            // Rows of B: g = (a, a', b, b') = (-b' / (r k), -b'' / (r k), b, b').
            let b: [[f64; 4]; 4] = [dn.map(|x| -x / (r * k)), ddn.map(|x| -x / (r * k)), n, dn];
            for p in 0..4 {
                for q in 0..=p {
                    let mut value = 0.0;
                    for (row, form_row) in b.iter().zip(&form) {
                        for (column, &c) in b.iter().zip(form_row) {
                            value += row[p] * c * column[q];
                        }
                    }
                    let first = HERMITE.dof(e, 0);
                    stiffness.add(first + p, first + q, value * weight * h);
                }
            }
        }
    }
    stiffness.constrain(0);
    stiffness.constrain(1);
    stiffness.negative_eigenvalues()
}

/// 4-point Gauss-Legendre on `[0, 1]`, `(point, weight)` (exact for the degree-6 products of
/// cubics).
pub(crate) fn gauss_legendre_4() -> [(f64, f64); 4] {
    let (inner, outer) = (0.339_981_043_584_856_3, 0.861_136_311_594_052_6);
    let (w_inner, w_outer) = (0.652_145_154_862_546_1, 0.347_854_845_137_453_9);
    [(-outer, w_outer), (-inner, w_inner), (inner, w_inner), (outer, w_outer)].map(|(x, w)| (0.5 * (x + 1.0), 0.5 * w))
}

/// The C1 cubic Hermite functions on an element of length `h` at `t` in `[0, 1]`, for the
/// unknowns (value, slope) at its start and (value, slope) at its end: their values and first
/// and second derivatives in `Y`.
pub(crate) fn hermite_cubics(t: f64, h: f64) -> ([f64; 4], [f64; 4], [f64; 4]) {
    (
        [
            1.0 - 3.0 * t * t + 2.0 * t.powi(3),
            h * (t - 2.0 * t * t + t.powi(3)),
            3.0 * t * t - 2.0 * t.powi(3),
            h * (t.powi(3) - t * t),
        ],
        [
            (6.0 * t * t - 6.0 * t) / h,
            1.0 - 4.0 * t + 3.0 * t * t,
            (6.0 * t - 6.0 * t * t) / h,
            3.0 * t * t - 2.0 * t,
        ],
        [
            (12.0 * t - 6.0) / (h * h),
            (6.0 * t - 4.0) / h,
            (6.0 - 12.0 * t) / (h * h),
            (6.0 * t - 2.0) / h,
        ],
    )
}
