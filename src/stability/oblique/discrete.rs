//! The discrete cross-check for modes in any direction of the surface: finite elements in `Y`
//! for the complex amplitude `U(Y)` of `u = Re(U(Y) exp(i k n . X))`.
//!
//! The second variation per unit area is `1/2 integral of conj(g) . A g dY` with
//! `g_kL = dU_k / dX_L`: `U_k'` for `L = Y` and `i k n_L U_k` in the surface. Its Hermitian
//! stiffness `H = H_r + i H_i` is positive definite exactly while the real symmetric
//! `[[H_r, -H_i], [H_i, H_r]]` is, whose eigenvalues are those of `H`, each twice.
//! * Compressible layers: the three components by quadratic elements.
//! * Incompressible layers: the constraint `U_Y' = -i k lambda_2 w`, `w = c . (U_X, U_Z)` with
//!   `c = (n_1 / lambda_1, n_3 / lambda_3)`, is solved for `w`, so `(U_X, U_Z) = w c / |c|^2 +
//!   v c_perp / |c|`: `U_Y` by C1 cubic Hermite elements (`U_Y'`, hence `w`, continuous) and `v`
//!   by quadratic ones.

use super::moduli::SurfaceModuli;
use crate::numerics::banded::SymmetricBanded;
use crate::numerics::dofs::DofMap;
use crate::stability::discrete::{gauss_legendre_4, hermite_cubics, DiscreteOptions};
use nalgebra::Complex;

type C = Complex<f64>;

/// One basis function of an element at a point: its field, value and first two derivatives.
#[derive(Clone, Copy)]
struct Basis {
    field: usize,
    value: f64,
    first: f64,
    second: f64,
}

/// The smallest positive real part of the substrate's Stroh exponents along `theta`. `M` is
/// similar to `i N` with `N = -i D^-1 M D` real, `D = diag(I, i I)` (the traction part of `y`
/// scaled by `i`), so the exponents are `i p` for the eigenvalues `p` of the real `N`, found by
/// faer's dense eigenvalue solver, and their real parts are `-Im p`.
pub(super) fn slowest_decay(substrate: &SurfaceModuli, theta: f64) -> Option<f64> {
    let m = substrate.stroh_matrix(theta);
    let scale = |r: usize| if r < 3 { C::from(1.0) } else { C::i() };
    let n = faer::Mat::<f64>::from_fn(6, 6, |r, c| (m[(r, c)] * scale(c) / scale(r) * -C::i()).re);
    let roots = n.eigenvalues().ok()?;
    let slowest = roots
        .iter()
        .map(|p| p.im.abs())
        .filter(|decay| *decay > 0.0)
        .fold(f64::INFINITY, f64::min);
    (slowest.is_finite() && slowest > 0.0).then_some(slowest)
}

/// Number of negative eigenvalues of the discrete Hermitian stiffness at `(k, theta)`; `None`
/// if it is singular to working precision or the substrate does not decay.
pub fn negative_eigenvalues(
    layer: &SurfaceModuli,
    substrate: &SurfaceModuli,
    k: f64,
    theta: f64,
    options: &DiscreteOptions,
) -> Option<usize> {
    let incompressible = layer.incompressible;
    if substrate.incompressible != incompressible {
        return None;
    }
    let y = options.nodes_of_elements(k, slowest_decay(substrate, theta)?);
    let elements = y.len() - 1;
    // Complex unknowns per element step and per vertex: (U_X, U_Y, U_Z) at vertices and
    // midpoints, or (U_Y, U_Y', v) at vertices and v at midpoints.
    let (stride, at_vertex) = if incompressible { (4, 3) } else { (6, 3) };
    let local = stride + at_vertex;
    let unknowns = stride * elements + at_vertex;
    let mut stiffness = SymmetricBanded::zeros(2 * unknowns, 2 * local - 1);
    let gauss = gauss_legendre_4();
    for e in 0..elements {
        let (y0, y1) = (y[e], y[e + 1]);
        let moduli = if y0 >= 0.0 { layer } else { substrate };
        let h = y1 - y0;
        let mut element = vec![vec![C::from(0.0); local]; local];
        for &(t, weight) in &gauss {
            let basis = if incompressible {
                hermite_and_quadratic(t, h)
            } else {
                quadratic(t, h)
            };
            let gradients: Vec<[C; 9]> = basis.iter().map(|b| gradient(moduli, b, k, theta)).collect();
            for (p, gp) in gradients.iter().enumerate() {
                let a_gp: [C; 9] = std::array::from_fn(|row| {
                    (0..9).fold(C::from(0.0), |s, col| s + gp[col] * moduli.tangent[row][col])
                });
                for (q, gq) in gradients.iter().enumerate() {
                    let value = (0..9).fold(C::from(0.0), |s, m| s + gq[m].conj() * a_gp[m]);
                    element[q][p] += value * (weight * h);
                }
            }
        }
        let base = stride * e;
        for (q, row) in element.iter().enumerate() {
            for (p, z) in row.iter().enumerate().take(q + 1) {
                let (gq, gp) = (2 * (base + q), 2 * (base + p));
                stiffness.add(gq, gp, z.re);
                stiffness.add(gq + 1, gp + 1, z.re);
                stiffness.add(gq + 1, gp, z.im);
                if p != q {
                    stiffness.add(gq, gp + 1, -z.im);
                }
            }
        }
    }
    for dof in 0..2 * at_vertex {
        stiffness.constrain(dof);
    }
    stiffness.negative_eigenvalues().map(|n| n / 2)
}

/// The displacement gradient `g_kL` (at `3 k + L`) of one basis function.
fn gradient(moduli: &SurfaceModuli, b: &Basis, k: f64, theta: f64) -> [C; 9] {
    let n = [theta.cos(), 0.0, theta.sin()];
    let i = C::i();
    let (u, u_prime): ([C; 3], [C; 3]) = if moduli.incompressible {
        let lambda = moduli.stretches;
        let c = [n[0] / lambda[0], n[2] / lambda[2]];
        let norm2 = c[0] * c[0] + c[1] * c[1];
        let (e, f) = (
            [c[0] / norm2, c[1] / norm2],
            [-c[1] / norm2.sqrt(), c[0] / norm2.sqrt()],
        );
        // w = i U_Y' / (k lambda_2) and w' from U_Y''.
        let to_w = i / (k * lambda[1]);
        match b.field {
            0 => {
                let (w, w_prime) = (to_w * b.first, to_w * b.second);
                (
                    [w * e[0], C::from(b.value), w * e[1]],
                    [w_prime * e[0], C::from(b.first), w_prime * e[1]],
                )
            }
            _ => (
                [C::from(b.value * f[0]), C::from(0.0), C::from(b.value * f[1])],
                [C::from(b.first * f[0]), C::from(0.0), C::from(b.first * f[1])],
            ),
        }
    } else {
        let unit = |x: f64| std::array::from_fn(|m| C::from(if m == b.field { x } else { 0.0 }));
        (unit(b.value), unit(b.first))
    };
    std::array::from_fn(|index| {
        let (component, direction) = (index / 3, index % 3);
        match direction {
            1 => u_prime[component],
            _ => u[component] * (i * k * n[direction]),
        }
    })
}

/// Quadratic Lagrange functions of the three components on `[y0, y0 + h]` at `t` in `[0, 1]`,
/// in the element's unknown order (vertex, midpoint, vertex; components inside).
fn quadratic(t: f64, h: f64) -> Vec<Basis> {
    let xi = 2.0 * t - 1.0;
    let shape = [0.5 * xi * (xi - 1.0), 1.0 - xi * xi, 0.5 * xi * (xi + 1.0)];
    let slope = [(xi - 0.5) * 2.0 / h, -2.0 * xi * 2.0 / h, (xi + 0.5) * 2.0 / h];
    // Numbered node by node, the three fields of each in a row (`DofMap::SPACE`).
    let mut basis = Vec::with_capacity(9);
    for node in 0..3 {
        for field in 0..3 {
            basis.push(Basis {
                field,
                value: shape[node],
                first: slope[node],
                second: 0.0,
            });
        }
    }
    basis
}

/// Hermite cubics for `U_Y` (field 0: `U_Y`, `U_Y'` at each vertex) and quadratic Lagrange
/// functions for `v` (field 1), in the order (U_Y, U_Y', v) at the first vertex, v at the
/// midpoint, (U_Y, U_Y', v) at the second vertex.
fn hermite_and_quadratic(t: f64, h: f64) -> Vec<Basis> {
    let (value, first, second) = hermite_cubics(t, h);
    let cubic = |m: usize| Basis {
        field: 0,
        value: value[m],
        first: first[m],
        second: second[m],
    };
    let lagrange = quadratic(t, h);
    let v = |node: usize| Basis {
        field: 1,
        ..lagrange[DofMap::SPACE.dof(node, 0)]
    };
    vec![cubic(0), cubic(1), v(0), v(1), cubic(2), cubic(3), v(2)]
}
