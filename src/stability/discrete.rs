//! The discrete cross-check: quadratic finite elements in `Y` for fixed `k`.
//!
//! With `u1 = a(Y) sin kX`, `u2 = b(Y) cos kX`, the second variation of the energy per
//! wavelength is `(pi/k) * integral of g . C g dY`, `g = (a, a', b, b')`
//! ([`IncrementalModuli::energy_form`]), on `[-depth, 1]` with `a = b = 0` at the bottom and
//! natural (traction-free, continuous-traction) conditions elsewhere. The homogeneous state is
//! stable while this stiffness is positive definite; `d_c` is where it first is not.

use super::IncrementalModuli;
use crate::numerics::banded::SymmetricBanded;
use crate::numerics::grading::geometric_ratio;

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
    let y = options.nodes_of_elements(k, slowest_decay(substrate)?);
    let elements = y.len() - 1;
    let unknowns = 2 * (2 * elements + 1);
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
                b[0][2 * node] = n[node];
                b[1][2 * node] = dn[node];
                b[2][2 * node + 1] = n[node];
                b[3][2 * node + 1] = dn[node];
            }
            for p in 0..6 {
                for q in 0..=p {
                    let mut value = 0.0;
                    for r in 0..4 {
                        for s in 0..4 {
                            value += b[r][p] * form[r][s] * b[s][q];
                        }
                    }
                    stiffness.add(4 * e + p, 4 * e + q, value * weight * jac);
                }
            }
        }
    }
    stiffness.constrain(0);
    stiffness.constrain(1);
    stiffness.negative_eigenvalues()
}
