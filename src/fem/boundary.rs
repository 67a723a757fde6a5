//! Prescribed displacements (Dirichlet conditions).

use crate::error::{Error, Result};

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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn duplicates_merge_and_conflicts_fail() {
        let bc = Dirichlet::new(vec![(5, 1.0), (2, 0.0), (5, 1.0)]).unwrap();
        assert_eq!(bc.dofs(), &[2, 5]);
        assert_eq!(bc.values(), &[0.0, 1.0]);
        assert!(Dirichlet::new(vec![(5, 1.0), (5, 2.0)]).is_err());
        assert!(Dirichlet::new(vec![(1, f64::NAN)]).is_err());
    }
}
