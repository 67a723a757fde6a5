//! The deformed top surface: its profile and the wrinkle amplitude `A = (max y - min y) / 2`.

use crate::mesh::{Mesh, TOP, X, Y};

/// Deformed positions `(x, y)` of the top-surface nodes, sorted by reference `X`.
pub fn surface_profile(mesh: &Mesh, u: &[f64]) -> Vec<(f64, f64)> {
    mesh.node_set(TOP)
        .iter()
        .map(|&n| {
            let [x, y] = mesh.coordinates()[n];
            (x + u[mesh.dofs().dof(n, X)], y + u[mesh.dofs().dof(n, Y)])
        })
        .collect()
}

/// `A = (max y - min y) / 2` over the deformed top-surface nodes (of a strip or a patch).
pub fn amplitude<const D: usize, const N: usize>(mesh: &Mesh<D, N>, u: &[f64]) -> f64 {
    let (low, high) = mesh
        .node_set(TOP)
        .iter()
        .map(|&n| mesh.coordinates()[n][Y] + u[mesh.dofs().dof(n, Y)])
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), y| (lo.min(y), hi.max(y)));
    0.5 * (high - low)
}
