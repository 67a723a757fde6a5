//! The assembled tangent: the lower triangle of `K_ff` in CSC form, sharing its structure with
//! the pattern it was assembled on.

use super::pattern;
use crate::error::{Error, Result};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMat, SymbolicSparseColMatRef};
use std::sync::Arc;

/// The lower triangle of a tangent `K_ff` in CSC form: its values on the stored entries of the
/// pattern it was assembled on (shared, not copied).
#[derive(Clone, Debug)]
pub struct Tangent {
    structure: Arc<SymbolicSparseColMat<usize>>,
    values: Vec<f64>,
}

impl Tangent {
    /// The matrix of `values` on the stored entries of `structure`.
    pub(super) fn on(structure: Arc<SymbolicSparseColMat<usize>>, values: Vec<f64>) -> Self {
        Tangent { structure, values }
    }

    /// The values on the stored entries, to change in place.
    pub(super) fn values_mut(&mut self) -> &mut [f64] {
        &mut self.values
    }

    /// The lower triangle of the `n x n` matrix with the given entries (`(row, column, value)`
    /// with `row >= column`, each entry once).
    pub fn from_lower_entries(n: usize, entries: &[(usize, usize, f64)]) -> Result<Self> {
        let pairs: Vec<faer::sparse::Pair<usize, usize>> = entries
            .iter()
            .map(|&(row, col, _)| faer::sparse::Pair { row, col })
            .collect();
        let (symbolic, _) = SymbolicSparseColMat::try_new_from_indices(n, n, &pairs)
            .map_err(|e| Error::invalid("tangent entry", format!("{e:?}"), &format!("indices in [0, {n})")))?;
        let mut values = vec![0.0; symbolic.compute_nnz()];
        for &(row, col, value) in entries {
            values[pattern::position(&symbolic, row, col)] = value;
        }
        Ok(Tangent {
            structure: Arc::new(symbolic),
            values,
        })
    }

    /// The matrix.
    pub fn as_ref(&self) -> SparseColMatRef<'_, usize, f64> {
        SparseColMatRef::new(self.symbolic(), &self.values)
    }

    /// Its stored entries.
    pub fn symbolic(&self) -> SymbolicSparseColMatRef<'_, usize> {
        self.structure.as_ref().as_ref()
    }

    /// Its dimension.
    pub fn nrows(&self) -> usize {
        self.structure.nrows()
    }

    /// Number of stored entries (the lower triangle).
    pub fn compute_nnz(&self) -> usize {
        self.values.len()
    }
}
