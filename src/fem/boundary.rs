//! Prescribed displacements (Dirichlet conditions), and those of the model (`docs/model.md`, "The
//! finite-element set-up"): `u_x = 0` on `X = 0`, `u_x = -L d` on `X = L`, `u_y = 0` on
//! `Y = -D`; the top is traction free and `u_y` is free on both vertical edges.

use crate::error::{Error, Result};
use crate::mesh::Mesh;
use crate::parameters::validate_compression;

/// Component index of `u_x`.
pub const X: usize = 0;
/// Component index of `u_y`.
pub const Y: usize = 1;

/// The global unknown of displacement component `component` (`X` or `Y`) of `node`.
pub fn dof(node: usize, component: usize) -> usize {
    2 * node + component
}

/// A set of unknowns with prescribed values, sorted by unknown.
#[derive(Clone, Debug, PartialEq)]
pub struct Dirichlet {
    dofs: Vec<usize>,
    values: Vec<f64>,
}

impl Dirichlet {
    /// From `(unknown, value)` pairs; an unknown given twice must have the same value both times.
    pub fn new(mut pairs: Vec<(usize, f64)>) -> Result<Self> {
        pairs.sort_by_key(|&(dof, _)| dof);
        let mut dofs: Vec<usize> = Vec::with_capacity(pairs.len());
        let mut values: Vec<f64> = Vec::with_capacity(pairs.len());
        for (dof, value) in pairs {
            if !value.is_finite() {
                return Err(Error::invalid("prescribed displacement", value, "a finite number"));
            }
            match (dofs.last(), values.last()) {
                (Some(&last), Some(&previous)) if last == dof => {
                    if previous != value {
                        return Err(Error::invalid(
                            "prescribed displacement",
                            format!("unknown {dof} set to both {previous} and {value}"),
                            "one value per unknown",
                        ));
                    }
                }
                _ => {
                    dofs.push(dof);
                    values.push(value);
                }
            }
        }
        Ok(Dirichlet { dofs, values })
    }

    /// The prescribed unknowns, increasing.
    pub fn dofs(&self) -> &[usize] {
        &self.dofs
    }

    /// The prescribed values, in the order of [`Dirichlet::dofs`].
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// Sets the prescribed unknowns of `u` to their values.
    pub fn impose(&self, u: &mut [f64]) {
        for (&dof, &value) in self.dofs.iter().zip(&self.values) {
            u[dof] = value;
        }
    }

    /// Number of prescribed unknowns.
    pub fn len(&self) -> usize {
        self.dofs.len()
    }

    /// Whether nothing is prescribed.
    pub fn is_empty(&self) -> bool {
        self.dofs.is_empty()
    }
}

/// The model's conditions at end-shortening `d`: `u_x = 0` at `X = 0`, `u_x = -L d` at `X = L`,
/// `u_y = 0` at `Y = -D`.
pub fn model_conditions(mesh: &Mesh, d: f64) -> Result<Dirichlet> {
    validate_compression("d", d)?;
    let shift = -mesh.spec().length * d;
    let left = mesh.left().into_iter().map(|n| (dof(n, X), 0.0));
    let right = mesh.right().into_iter().map(|n| (dof(n, X), shift));
    let bottom = mesh.bottom().into_iter().map(|n| (dof(n, Y), 0.0));
    Dirichlet::new(left.chain(right).chain(bottom).collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::MeshSpec;

    #[test]
    fn duplicates_merge_and_conflicts_fail() {
        let bc = Dirichlet::new(vec![(5, 1.0), (2, 0.0), (5, 1.0)]).unwrap();
        assert_eq!(bc.dofs(), &[2, 5]);
        assert_eq!(bc.values(), &[0.0, 1.0]);
        assert!(Dirichlet::new(vec![(5, 1.0), (5, 2.0)]).is_err());
        assert!(Dirichlet::new(vec![(1, f64::NAN)]).is_err());
    }

    #[test]
    fn model_conditions_fix_both_edges_and_the_bottom() {
        let mesh = Mesh::new(MeshSpec::new(2, 1, 1, 3.0, 4.0, 3.0)).unwrap();
        let bc = model_conditions(&mesh, 0.25).unwrap();
        // 5 nodes per vertical edge (u_x) plus 5 bottom nodes (u_y).
        assert_eq!(bc.len(), 5 + 5 + 5);
        let right_x = dof(mesh.right()[3], X);
        let k = bc.dofs().iter().position(|&d| d == right_x).unwrap();
        assert_eq!(bc.values()[k], -1.0);
        assert!(model_conditions(&mesh, 1.0).is_err());
    }
}
