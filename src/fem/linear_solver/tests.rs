//! The sparse solver against closed forms: shifted Laplacians' inertia and solves.

use super::*;
use faer::sparse::{SparseColMat, Triplet};

/// The 1D Laplacian shifted by `sigma`: eigenvalues `2 - 2 cos(k pi / (n + 1)) - sigma`.
pub(in crate::fem) fn shifted_laplacian(n: usize, sigma: f64) -> SparseColMat<usize, f64> {
    let mut t = Vec::new();
    for i in 0..n {
        t.push(Triplet::new(i, i, 2.0 - sigma));
        if i + 1 < n {
            t.push(Triplet::new(i, i + 1, -1.0));
            t.push(Triplet::new(i + 1, i, -1.0));
        }
    }
    SparseColMat::try_new_from_triplets(n, n, &t).unwrap()
}

/// The 5-point Laplacian of an `nx x ny` grid (Dirichlet all round) shifted by `sigma`,
/// lower triangle: eigenvalues `4 - 2 cos(j pi / (nx + 1)) - 2 cos(k pi / (ny + 1)) - sigma`.
pub(in crate::fem) fn grid_laplacian(nx: usize, ny: usize, sigma: f64) -> SparseColMat<usize, f64> {
    let index = |i: usize, j: usize| i * ny + j;
    let mut t = Vec::new();
    for i in 0..nx {
        for j in 0..ny {
            t.push(Triplet::new(index(i, j), index(i, j), 4.0 - sigma));
            if i + 1 < nx {
                t.push(Triplet::new(index(i + 1, j), index(i, j), -1.0));
            }
            if j + 1 < ny {
                t.push(Triplet::new(index(i, j + 1), index(i, j), -1.0));
            }
        }
    }
    SparseColMat::try_new_from_triplets(nx * ny, nx * ny, &t).unwrap()
}

fn grid_below(nx: usize, ny: usize, sigma: f64) -> usize {
    let mode = |k: usize, n: usize| 2.0 - 2.0 * (k as f64 * std::f64::consts::PI / (n as f64 + 1.0)).cos();
    (1..=nx)
        .flat_map(|j| (1..=ny).map(move |k| mode(j, nx) + mode(k, ny)))
        .filter(|&lambda| lambda < sigma)
        .count()
}

/// A pattern large enough is split over two cores: its inertia is the closed form's, its
/// solves (double, then single precision) satisfy `A x = b`, and the pivoted factorisation
/// (of the whole) agrees; shifts that leave up to 25 eigenvalues below make the parts and
/// the separator's dense block indefinite.
#[test]
fn a_split_factorisation_solves_and_counts_like_the_closed_form() {
    let (nx, ny) = (160, 40);
    let n = nx * ny;
    assert!(n >= SMALLEST_SPLIT);
    let b: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).cos()).collect();
    for sigma in [0.0, 0.0231, 0.1, 0.3] {
        let a = grid_laplacian(nx, ny, sigma);
        let mut solver = SparseLdlt::new(a.symbolic());
        assert!(solver.analysis.split.is_some(), "the grid splits");
        assert_eq!(solver.factorize(a.as_ref()), Factorisation::Ldlt);
        assert!(solver.split_holds, "sigma {sigma}: the split factorisation holds");
        assert_eq!(
            solver.negative_pivots(),
            Some(grid_below(nx, ny, sigma)),
            "sigma {sigma}"
        );
        let size = b.iter().fold(0.0, |m: f64, v| m.max(v.abs()));
        let residual = |x: &[f64]| {
            let ax = multiply(a.as_ref(), x);
            ax.iter().zip(&b).map(|(p, q)| (p - q).abs()).fold(0.0, f64::max) / size
        };
        let mut x = b.clone();
        solver.solve_in_place(&mut x).unwrap();
        assert!(residual(&x) < 1e-10, "sigma {sigma}: double {}", residual(&x));
        let mut single = b.clone();
        solver.solve_in_place_single(&mut single).unwrap();
        let error = single.iter().zip(&x).map(|(p, q)| (p - q).abs()).fold(0.0, f64::max);
        let scale = x.iter().fold(0.0, |m: f64, v| m.max(v.abs()));
        assert!(error < 1e-4 * scale, "sigma {sigma}: single {error} of {scale}");
        assert_eq!(solver.negative_pivots(), Some(grid_below(nx, ny, sigma)));
        assert_eq!(solver.factorize_pivoted(a.as_ref()), Factorisation::Lblt);
        assert_eq!(
            solver.negative_pivots(),
            Some(grid_below(nx, ny, sigma)),
            "sigma {sigma}: whole"
        );
        let mut whole = b.clone();
        solver.solve_in_place(&mut whole).unwrap();
        let error = whole.iter().zip(&x).map(|(p, q)| (p - q).abs()).fold(0.0, f64::max);
        assert!(error < 1e-9 * scale, "sigma {sigma}: split against whole {error}");
    }
}

fn below(n: usize, sigma: f64) -> usize {
    (1..=n)
        .filter(|&k| 2.0 - 2.0 * (k as f64 * std::f64::consts::PI / (n as f64 + 1.0)).cos() < sigma)
        .count()
}

#[test]
fn solves_and_counts_negative_eigenvalues() {
    let n = 200;
    for sigma in [0.0, 0.013, 0.5, 1.7] {
        let a = shifted_laplacian(n, sigma);
        let mut solver = SparseLdlt::new(a.symbolic());
        let b: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).cos()).collect();
        for kind in [Factorisation::Ldlt, Factorisation::Lblt] {
            match kind {
                Factorisation::Ldlt => assert_eq!(solver.factorize(a.as_ref()), Factorisation::Ldlt),
                Factorisation::Lblt => assert_eq!(solver.factorize_pivoted(a.as_ref()), Factorisation::Lblt),
            }
            assert_eq!(
                solver.negative_pivots(),
                Some(below(n, sigma)),
                "sigma {sigma}, {kind:?}"
            );
            let mut x = b.clone();
            solver.solve_in_place(&mut x).unwrap();
            let ax = multiply(a.as_ref(), &x);
            let error = ax.iter().zip(&b).map(|(p, q)| (p - q).abs()).fold(0.0, f64::max);
            assert!(error < 1e-9, "sigma {sigma}, {kind:?}: {error}");
        }
    }
}

/// The single-precision solve keeps the inertia, solves to single precision, and leaves
/// the next factorisation in double precision.
#[test]
fn single_precision_solves_to_its_rounding() {
    let n = 200;
    let a = shifted_laplacian(n, 0.013);
    let b: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).cos()).collect();
    let mut solver = SparseLdlt::new(a.symbolic());
    solver.factorize(a.as_ref());
    let mut exact = b.clone();
    solver.solve_in_place(&mut exact).unwrap();
    for _ in 0..2 {
        let mut x = b.clone();
        solver.solve_in_place_single(&mut x).unwrap();
        let error = x.iter().zip(&exact).map(|(p, q)| (p - q).abs()).fold(0.0, f64::max);
        let size = exact.iter().fold(0.0, |m: f64, v| m.max(v.abs()));
        assert!(error > 1e-12 * size && error < 1e-4 * size, "{error} of {size}");
        assert_eq!(solver.negative_pivots(), Some(below(n, 0.013)));
    }
    solver.factorize(a.as_ref());
    let mut x = b.clone();
    solver.solve_in_place(&mut x).unwrap();
    assert_eq!(x, exact);
}

#[test]
fn zero_pivot_falls_back_to_bunch_kaufman() {
    // [[0, 1], [1, 0]] has no L D L^T without pivoting; eigenvalues -1 and 1.
    let t = [
        Triplet::new(0, 1, 1.0),
        Triplet::new(1, 0, 1.0),
        Triplet::new(0, 0, 0.0),
    ];
    let a = SparseColMat::<usize, f64>::try_new_from_triplets(2, 2, &t).unwrap();
    let mut solver = SparseLdlt::new(a.symbolic());
    assert_eq!(solver.factorize(a.as_ref()), Factorisation::Lblt);
    assert_eq!(solver.negative_pivots(), Some(1));
    let mut x = vec![2.0, 3.0];
    solver.solve_in_place(&mut x).unwrap();
    assert!((x[0] - 3.0).abs() < 1e-14 && (x[1] - 2.0).abs() < 1e-14);
}
