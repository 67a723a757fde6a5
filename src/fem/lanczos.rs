//! The eigenpair nearest zero of a factorised symmetric matrix, by the Lanczos method on its
//! inverse (shift-and-invert at zero): the modes of bifurcations and secondary bifurcations.

use super::linear_solver::{multiply, SparseLdlt};
use crate::error::{Error, Result};
use faer::sparse::SparseColMatRef;
use faer::{Mat, Side};

/// The eigenpair of `k` whose eigenvalue is nearest zero, by the Lanczos method on `K^-1`
/// (shift-and-invert at zero, with the factor of `k` held in `solver`; full
/// reorthogonalisation): the unit eigenvector on the free unknowns and its Rayleigh quotient.
/// The extreme Ritz value `theta` of the tridiagonal `T_j` converges far faster than inverse
/// iteration's power steps; it stops when the Ritz pair's residual `|beta_j s_j|` is below
/// `tolerance |theta|`, or after `iterations` solves.
pub fn inverse_lanczos(
    solver: &mut SparseLdlt,
    k: SparseColMatRef<'_, usize, f64>,
    iterations: usize,
    tolerance: f64,
) -> Result<(Vec<f64>, f64)> {
    // A start with a component along every eigenvector (deterministic, no symmetry).
    let mut start: Vec<f64> = (0..solver.dimension())
        .map(|i| ((i as f64 + 1.0) * 0.754_877_666).fract() - 0.5)
        .collect();
    normalise(&mut start);
    let (mut basis, mut alpha, mut beta) = (vec![start], Vec::new(), Vec::new());
    let ritz = loop {
        let mut w = basis.last().expect("never empty").clone();
        solver.solve_in_place(&mut w)?;
        alpha.push(dot(&w, basis.last().expect("never empty")));
        for _ in 0..2 {
            for q in &basis {
                let c = dot(&w, q);
                w.iter_mut().zip(q).for_each(|(x, y)| *x -= c * y);
            }
        }
        let next = dot(&w, &w).sqrt();
        let (theta, s) = extreme_ritz_pair(&alpha, &beta)?;
        let residual = next * s.last().expect("one entry per step").abs();
        if residual <= tolerance * theta.abs() || alpha.len() >= iterations.min(solver.dimension()) || next == 0.0 {
            break s;
        }
        w.iter_mut().for_each(|x| *x /= next);
        beta.push(next);
        basis.push(w);
    };
    let mut x = vec![0.0; solver.dimension()];
    for (q, c) in basis.iter().zip(&ritz) {
        x.iter_mut().zip(q).for_each(|(a, b)| *a += c * b);
    }
    normalise(&mut x);
    let eigenvalue = dot(&x, &multiply(k, &x));
    Ok((x, eigenvalue))
}

/// The eigenpair `(theta, s)` of largest `|theta|` of the symmetric tridiagonal matrix with
/// diagonal `alpha` and off-diagonal `beta`.
fn extreme_ritz_pair(alpha: &[f64], beta: &[f64]) -> Result<(f64, Vec<f64>)> {
    let m = alpha.len();
    let t = Mat::from_fn(m, m, |r, c| match r.abs_diff(c) {
        0 => alpha[r],
        1 => beta[r.min(c)],
        _ => 0.0,
    });
    let eigen = t
        .self_adjoint_eigen(Side::Lower)
        .map_err(|_| Error::NonFinite("Lanczos tridiagonal eigenproblem".into()))?;
    let (values, vectors) = (eigen.S().column_vector(), eigen.U());
    let i = (0..m)
        .max_by(|&a, &b| values[a].abs().total_cmp(&values[b].abs()))
        .expect("m >= 1");
    Ok((values[i], (0..m).map(|r| vectors[(r, i)]).collect()))
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn normalise(x: &mut [f64]) {
    let norm = dot(x, x).sqrt();
    x.iter_mut().for_each(|v| *v /= norm);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::linear_solver::tests::shifted_laplacian;

    /// The eigenvalue nearest zero of the shifted Laplacian, `2 - 2 cos(k pi / (n + 1)) - sigma`
    /// (closed form), indefinite here, and its eigenvector (residual `|K x - lambda x|`).
    #[test]
    fn lanczos_finds_the_eigenpair_nearest_zero() {
        let (n, sigma) = (200, 0.013);
        let a = shifted_laplacian(n, sigma);
        let exact = (1..=n)
            .map(|k| 2.0 - 2.0 * (k as f64 * std::f64::consts::PI / (n as f64 + 1.0)).cos() - sigma)
            .min_by(|x, y| x.abs().total_cmp(&y.abs()))
            .unwrap();
        let mut solver = SparseLdlt::new(a.symbolic());
        solver.factorize(a.as_ref());
        let (x, lambda) = inverse_lanczos(&mut solver, a.as_ref(), 60, 1e-12).unwrap();
        let residual: f64 = multiply(a.as_ref(), &x)
            .iter()
            .zip(&x)
            .map(|(kx, xi)| (kx - lambda * xi).powi(2))
            .sum::<f64>()
            .sqrt();
        println!("lambda {lambda:e} (exact {exact:e}), residual {residual:e}");
        assert!((lambda - exact).abs() <= 1e-10 * exact.abs(), "{lambda} vs {exact}");
        assert!(residual <= 1e-8 * exact.abs(), "{residual:e}");
    }
}
