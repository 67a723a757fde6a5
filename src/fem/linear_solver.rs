//! Sparse symmetric direct solver: faer's supernodal `L D L^T` with the symbolic analysis (AMD
//! ordering) done once per sparsity pattern, sequential on plane meshes (`Par::Seq`: on a
//! two-core machine faer on two threads was 2-3x slower), where a large pattern is instead split
//! in two halves factorised at once on two cores (`split`); on all cores where the fronts are
//! as dense as a three-dimensional mesh's, which does not split (`PARALLEL_ENTRIES_PER_UNKNOWN`).
//! The inertia comes for free from `D`: by Sylvester's law
//! the number of negative pivots is the number of negative eigenvalues of `K`. When `L D L^T`
//! meets a zero pivot, the intranode Bunch-Kaufman `L B L^T` takes over. An iteration that
//! checks its own residual (modified Newton) may solve with the factor rounded to single
//! precision, which halves the memory traffic that bounds a solve. The matrix is brought into
//! the factor's order by a gather through a map built once per pattern, instead of faer's
//! general symmetric permutation at every factorisation (6 % of a run, measured). Solvers of
//! one pattern share its analysis and map ([`SparseLdlt::sibling`]), each with its own factor.

use crate::error::{Error, Result};
use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::cholesky::ldlt::factor::LdltRegularization;
use faer::perm::PermRef;
use faer::sparse::linalg::cholesky::supernodal::{
    factorize_supernodal_numeric_ldlt, factorize_supernodal_numeric_ldlt_scratch,
};
use faer::sparse::linalg::cholesky::supernodal::{SupernodalLdltRef, SymbolicSupernodalCholesky};
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, IntranodeLbltRef, LdltRef, SymbolicCholesky,
    SymbolicCholeskyRaw, SymmetricOrdering,
};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Par, Side};
use std::sync::Arc;
use std::time::{Duration, Instant};

mod separator;
mod split;
use split::{SplitAnalysis, SplitFactor, SMALLEST_SPLIT};

/// Which factorisation currently holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Factorisation {
    /// `L D L^T` without pivoting (the default).
    Ldlt,
    /// Intranode Bunch-Kaufman `L B L^T` (1x1 and 2x2 pivots within supernodes).
    Lblt,
}

/// The symbolic analysis of one sparsity pattern, shared by the solvers of its matrices.
struct Analysis {
    symbolic: SymbolicCholesky<usize>,
    /// The map into the whole factor's order, made on its first factorisation (where the
    /// pattern is split, only a side's zero pivot needs it).
    order: std::sync::OnceLock<FactorOrder>,
    /// The pattern split in two parts factorised on two cores ([`split`]), if it is large
    /// enough and splits well; `L B L^T` always factorises the whole.
    split: Option<SplitAnalysis>,
}

/// A reusable factorisation of symmetric matrices sharing one sparsity pattern.
pub struct SparseLdlt {
    analysis: Arc<Analysis>,
    /// The matrix in the factor's order (see [`FactorOrder`]).
    permuted: Vec<f64>,
    values: Vec<f64>,
    subdiag: Vec<f64>,
    perm_forward: Vec<usize>,
    perm_inverse: Vec<usize>,
    /// The workspace of the whole factor's `L D L^T` and solves, made on first use (a split
    /// pattern needs it only after a zero pivot).
    scratch: Option<MemBuffer>,
    /// The larger workspace of `L B L^T` (with faer's own permutation), made on first use.
    pivoted_scratch: Option<MemBuffer>,
    state: Option<Factorisation>,
    /// The two parts' factors, made on first use (split patterns only).
    split: Option<SplitFactor>,
    /// Whether the current `L D L^T` is the split one (`split`) rather than `values`.
    split_holds: bool,
    /// Whether `values` holds the `L D L^T` factor rounded to `f32`, packed in its first half.
    single: bool,
    /// Negative pivots of the current factorisation, counted on first request.
    negative: std::cell::OnceCell<usize>,
    symbolic_time: Duration,
    factorisation_time: Duration,
    solve_time: Duration,
}

impl SparseLdlt {
    /// Symbolic analysis (AMD ordering, supernodal structure) of the pattern of a lower triangle.
    /// Panics only if memory runs out, like any allocation.
    pub fn new(pattern: SymbolicSparseColMatRef<'_, usize>) -> Self {
        let start = Instant::now();
        let params = CholeskySymbolicParams {
            supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
            ..Default::default()
        };
        let whole = || {
            factorize_symbolic_cholesky(pattern, Side::Lower, SymmetricOrdering::Amd, params)
                .expect("symbolic factorisation fails only when out of memory")
        };
        // The split takes the second core; a caller on a rayon pool's thread (`reproduce`'s
        // figures, `map`'s points) already runs in parallel and keeps the whole factor
        // (`reproduce` split: 96 s against 89 s). Where it splits, the whole pattern's analysis
        // (for a side's zero pivot) is made beside the split's, on the second core.
        let (symbolic, split) = match rayon::current_thread_index() {
            None => split::both_sides(whole, || SplitAnalysis::new(pattern, SMALLEST_SPLIT)),
            Some(_) => (whole(), None),
        };
        let order = std::sync::OnceLock::new();
        let mut solver = SparseLdlt::with_analysis(Arc::new(Analysis { symbolic, order, split }));
        solver.symbolic_time = start.elapsed();
        solver
    }

    /// A second solver for matrices of the same pattern, sharing this one's analysis (no
    /// symbolic work, only its own factor's memory): e.g. to factorise another matrix on
    /// another thread while this one's factor is in use.
    pub fn sibling(&self) -> SparseLdlt {
        SparseLdlt::with_analysis(Arc::clone(&self.analysis))
    }

    fn with_analysis(analysis: Arc<Analysis>) -> Self {
        let symbolic = &analysis.symbolic;
        let n = symbolic.nrows();
        SparseLdlt {
            permuted: Vec::new(),
            values: Vec::new(),
            subdiag: vec![0.0; n],
            perm_forward: vec![0; n],
            perm_inverse: vec![0; n],
            analysis,
            scratch: None,
            pivoted_scratch: None,
            state: None,
            split: None,
            split_holds: false,
            single: false,
            negative: std::cell::OnceCell::new(),
            symbolic_time: Duration::ZERO,
            factorisation_time: Duration::ZERO,
            solve_time: Duration::ZERO,
        }
    }

    /// Dimension of the matrices.
    pub fn dimension(&self) -> usize {
        self.analysis.symbolic.nrows()
    }

    /// Number of stored factor values (lower triangle plus the dense diagonal blocks; of both
    /// parts and the separator's block where the pattern is split).
    pub fn factor_size(&self) -> usize {
        match &self.analysis.split {
            Some(split) => split.factor_size(),
            None => self.analysis.symbolic.len_val(),
        }
    }

    /// `L D L^T` of the symmetric matrix whose lower triangle is `a` (same pattern as at
    /// construction), split on two cores where the pattern is; falls back to `L B L^T` of
    /// the whole on a zero pivot.
    pub fn factorize(&mut self, a: SparseColMatRef<'_, usize, f64>) -> Factorisation {
        let start = Instant::now();
        self.forget();
        if let Some(analysis) = &self.analysis.split {
            let factor = self.split.get_or_insert_with(|| SplitFactor::new(analysis));
            if factor.factorize(analysis, a.val()) {
                // A whole factor of an earlier zero pivot gives its memory back.
                (self.values, self.permuted) = (Vec::new(), Vec::new());
                self.state = Some(Factorisation::Ldlt);
                self.split_holds = true;
                self.factorisation_time = start.elapsed();
                return Factorisation::Ldlt;
            }
        }
        self.split = None; // a side met a zero pivot: its memory goes to the whole's factor
        self.prepare();
        let SymbolicCholeskyRaw::Supernodal(supernodal) = self.analysis.symbolic.raw() else {
            unreachable!("the symbolic analysis forces a supernodal factor")
        };
        let order = (self.analysis.order).get_or_init(|| FactorOrder::new(a.symbolic(), &self.analysis.symbolic));
        if self.permuted.len() != order.row_idx.len() {
            self.permuted = vec![0.0; order.row_idx.len()];
        }
        let ldlt = factorize_supernodal_numeric_ldlt(
            &mut self.values,
            order.gather(a, &mut self.permuted),
            LdltRegularization::default(),
            supernodal,
            whole_parallelism(&self.analysis.symbolic),
            whole_workspace(&mut self.scratch, &self.analysis.symbolic),
            Default::default(),
        );
        let kind = if ldlt.is_ok() {
            self.state = Some(Factorisation::Ldlt);
            Factorisation::Ldlt
        } else {
            self.factorize_pivoted(a)
        };
        self.factorisation_time = start.elapsed();
        kind
    }

    /// Forgets the factorisation in place.
    fn forget(&mut self) {
        self.negative = std::cell::OnceCell::new();
        self.split_holds = false;
        self.single = false;
        self.state = None;
    }

    /// [`SparseLdlt::forget`], with the whole factor's memory made if it is not there.
    fn prepare(&mut self) {
        self.forget();
        if self.values.is_empty() {
            self.values = vec![0.0; self.analysis.symbolic.len_val()];
        }
    }

    /// Frees the factor's memory (the largest part of a solver) until the next factorisation,
    /// keeping the analysis and the small workspaces.
    pub fn free_factor(&mut self) {
        self.forget();
        self.values = Vec::new();
        self.permuted = Vec::new();
        self.split = None;
        self.pivoted_scratch = None;
    }

    /// Intranode Bunch-Kaufman `L B L^T` of `a`: slower, but stable for indefinite matrices.
    pub fn factorize_pivoted(&mut self, a: SparseColMatRef<'_, usize, f64>) -> Factorisation {
        let start = Instant::now();
        self.split = None; // the sides' factors give their memory to the whole's
        self.prepare();
        let symbolic = &self.analysis.symbolic;
        let scratch = self.pivoted_scratch.get_or_insert_with(|| {
            MemBuffer::new(StackReq::any_of(&[
                symbolic.factorize_numeric_intranode_lblt_scratch::<f64>(Par::Seq, Default::default()),
                symbolic.solve_in_place_scratch::<f64>(1, Par::Seq),
            ]))
        });
        symbolic.factorize_numeric_intranode_lblt(
            &mut self.values,
            &mut self.subdiag,
            &mut self.perm_forward,
            &mut self.perm_inverse,
            a,
            Side::Lower,
            Par::Seq,
            MemStack::new(scratch),
            Default::default(),
        );
        self.state = Some(Factorisation::Lblt);
        self.factorisation_time = start.elapsed();
        Factorisation::Lblt
    }

    /// The factorisation in place, if any.
    pub fn factorisation(&self) -> Option<Factorisation> {
        self.state
    }

    /// Solves `A x = b` in place (`rhs` holds `b`, then `x`); a non-finite `x` is an error.
    pub fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<()> {
        assert!(
            !self.single,
            "double-precision solve with a factor rounded to single precision"
        );
        if self.split_holds {
            return self.solve_split(rhs, false);
        }
        let start = Instant::now();
        let n = self.dimension();
        assert_eq!(rhs.len(), n, "right-hand side length");
        let x = MatMut::from_column_major_slice_mut(rhs, n, 1);
        match self.state {
            None => panic!("solve_in_place called before factorize"),
            Some(Factorisation::Ldlt) => LdltRef::new(&self.analysis.symbolic, &self.values).solve_in_place_with_conj(
                Conj::No,
                x,
                Par::Seq,
                whole_workspace(&mut self.scratch, &self.analysis.symbolic),
            ),
            Some(Factorisation::Lblt) => {
                let stack = MemStack::new(
                    self.pivoted_scratch
                        .as_mut()
                        .expect("made by the L B L^T factorisation"),
                );
                let perm = PermRef::new_checked(&self.perm_forward, &self.perm_inverse, n);
                IntranodeLbltRef::new(&self.analysis.symbolic, &self.values, &self.subdiag, perm)
                    .solve_in_place_with_conj(Conj::No, x, Par::Seq, stack)
            }
        }
        self.solve_time = start.elapsed();
        finite(rhs)
    }

    /// [`SparseLdlt::solve_in_place`] with the `L D L^T` factor rounded to single precision:
    /// `x` to about 1e-7 relative (times the conditioning), for iterations that check their own
    /// residual. The first call rounds the factor in place (after counting its negative pivots),
    /// so that only this solve is left until the next factorisation (a split factor: each
    /// part's). An `L B L^T` factor is solved in double precision.
    pub fn solve_in_place_single(&mut self, rhs: &mut [f64]) -> Result<()> {
        if self.state != Some(Factorisation::Ldlt) {
            return self.solve_in_place(rhs);
        }
        if self.split_holds {
            self.negative_pivots(); // counted while D is exact
            return self.solve_split(rhs, true);
        }
        if !self.single {
            self.round_to_single();
        }
        let start = Instant::now();
        let n = self.dimension();
        assert_eq!(rhs.len(), n, "right-hand side length");
        let mut x: Vec<f32> = rhs.iter().map(|&v| v as f32).collect();
        LdltRef::new(&self.analysis.symbolic, as_single(&self.values)).solve_in_place_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(&mut x, n, 1),
            Par::Seq,
            whole_workspace(&mut self.scratch, &self.analysis.symbolic),
        );
        rhs.iter_mut().zip(&x).for_each(|(r, &v)| *r = f64::from(v));
        self.solve_time = start.elapsed();
        finite(rhs)
    }

    /// Solves with the split factor, its sides rounded to single precision if `single`.
    fn solve_split(&mut self, rhs: &mut [f64], single: bool) -> Result<()> {
        let start = Instant::now();
        assert_eq!(rhs.len(), self.dimension(), "right-hand side length");
        let analysis = self.analysis.split.as_ref().expect("a split pattern");
        let factor = self.split.as_mut().expect("factorised");
        factor.solve_in_place(analysis, rhs, single);
        self.solve_time = start.elapsed();
        finite(rhs)
    }

    /// Rounds the `L D L^T` values to `f32` in place: value `i` goes to the `i`-th `f32` slot,
    /// which lies in the `f64` slot `i / 2`, already read (no second buffer, no extra memory).
    fn round_to_single(&mut self) {
        self.negative_pivots(); // counted while D is exact
        round_to_single(&mut self.values);
        self.single = true;
    }

    /// Number of negative eigenvalues of the factorised matrix (negative pivots of `D` or `B`).
    pub fn negative_pivots(&self) -> Option<usize> {
        let kind = self.state?;
        let SymbolicCholeskyRaw::Supernodal(supernodal) = self.analysis.symbolic.raw() else {
            unreachable!("the symbolic analysis forces a supernodal factor")
        };
        Some(*self.negative.get_or_init(|| match kind {
            Factorisation::Ldlt if self.split_holds => self.split.as_ref().expect("factorised").negative_pivots(),
            Factorisation::Ldlt => self.diagonal_blocks(supernodal).filter(|&(d, _)| d < 0.0).count(),
            Factorisation::Lblt => block_inertia(&self.diagonal_blocks(supernodal).collect::<Vec<_>>()),
        }))
    }

    /// `(d_ii, subdiag_i)` of every pivot, in factor order. The `L B L^T` values share the
    /// `L D L^T` layout, so both are read through `SupernodalLdltRef`.
    fn diagonal_blocks<'a>(
        &'a self,
        supernodal: &'a SymbolicSupernodalCholesky<usize>,
    ) -> impl Iterator<Item = (f64, f64)> + 'a {
        let factor = SupernodalLdltRef::new(supernodal, &self.values);
        (0..supernodal.n_supernodes()).flat_map(move |s| {
            let node = factor.supernode(s);
            let block = node.val();
            (0..block.ncols()).map(move |i| (block[(i, i)], self.subdiag[node.start() + i]))
        })
    }

    /// Wall time of the symbolic analysis.
    pub fn symbolic_time(&self) -> Duration {
        self.symbolic_time
    }

    /// Wall time of the last numeric factorisation.
    pub fn factorisation_time(&self) -> Duration {
        self.factorisation_time
    }

    /// Wall time of the last solve.
    pub fn solve_time(&self) -> Duration {
        self.solve_time
    }
}

/// Factor entries per unknown from which faer's `L D L^T` of the whole runs on all cores: the
/// dense fronts of three-dimensional meshes. Measured on periodic patches of 27-node hexahedra
/// on two cores: 1.24x faster at 29,598 unknowns (1,552 entries per unknown), 1.72x at 76,830
/// (2,041); slower at 15,870 (982), as on the plane meshes (about 100 per unknown), where two
/// threads were 2-3x slower.
const PARALLEL_ENTRIES_PER_UNKNOWN: usize = 1_200;

/// How the whole factor's `L D L^T` runs: on all cores for [`PARALLEL_ENTRIES_PER_UNKNOWN`], except
/// on a rayon pool's thread (a caller that already runs in parallel).
fn whole_parallelism(symbolic: &SymbolicCholesky<usize>) -> Par {
    let large_fronts = symbolic.len_val() >= PARALLEL_ENTRIES_PER_UNKNOWN * symbolic.nrows();
    match large_fronts && rayon::current_thread_index().is_none() {
        true => Par::rayon(rayon::current_num_threads()),
        false => Par::Seq,
    }
}

/// The workspace of the whole factor's `L D L^T` and its solves (double and single
/// precision), made in `scratch` on first use.
fn whole_workspace<'a>(scratch: &'a mut Option<MemBuffer>, symbolic: &SymbolicCholesky<usize>) -> &'a mut MemStack {
    let buffer = scratch.get_or_insert_with(|| {
        let SymbolicCholeskyRaw::Supernodal(supernodal) = symbolic.raw() else {
            unreachable!("the symbolic analysis forces a supernodal factor")
        };
        MemBuffer::new(StackReq::any_of(&[
            factorize_supernodal_numeric_ldlt_scratch::<usize, f64>(supernodal, Par::Seq, Default::default()),
            factorize_supernodal_numeric_ldlt_scratch::<usize, f64>(
                supernodal,
                whole_parallelism(symbolic),
                Default::default(),
            ),
            symbolic.solve_in_place_scratch::<f64>(1, Par::Seq),
            symbolic.solve_in_place_scratch::<f32>(1, Par::Seq),
        ]))
    });
    MemStack::new(buffer)
}

/// Rounds `values` to `f32` in place: value `i` goes to the `i`-th `f32` slot, which lies in
/// the `f64` slot `i / 2`, already read. Read them back with [`as_single`].
fn round_to_single(values: &mut [f64]) {
    let words: &mut [u32] = bytemuck::cast_slice_mut(values);
    for i in 0..words.len() / 2 {
        let value = f64::from_ne_bytes(bytemuck::cast([words[2 * i], words[2 * i + 1]]));
        words[i] = (value as f32).to_bits();
    }
}

/// The values rounded by [`round_to_single`].
fn as_single(values: &[f64]) -> &[f32] {
    &bytemuck::cast_slice(values)[..values.len()]
}

/// Negative eigenvalues of a `B` of 1x1 and 2x2 pivots `(b_ii, b_i+1,i)`: 1x1 pivots (no
/// subdiagonal) by sign, 2x2 blocks by determinant and trace.
fn block_inertia(pivots: &[(f64, f64)]) -> usize {
    let (mut negative, mut i) = (0, 0);
    while i < pivots.len() {
        let (d, s) = pivots[i];
        if s == 0.0 {
            negative += usize::from(d < 0.0);
            i += 1;
        } else {
            let e = pivots[i + 1].0;
            let det = d * e - s * s;
            negative += if det < 0.0 { 1 } else { 2 * usize::from(d + e < 0.0) };
            i += 2;
        }
    }
    negative
}

/// The slot of an entry above the diagonal.
const ABOVE: usize = usize::MAX;

/// The pattern of the lower triangle of one pattern's matrices in the factor's order (row and
/// column `inv[i]` for `i`), filled at every factorisation through `slot`.
struct FactorOrder {
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    /// Where each stored entry of the original goes among the permuted values ([`ABOVE`] for
    /// entries above the diagonal, which the factorisation ignores).
    slot: Vec<usize>,
}

impl FactorOrder {
    /// The map of `pattern`'s lower triangle into `symbolic`'s order; rows unsorted.
    fn new(pattern: SymbolicSparseColMatRef<'_, usize>, symbolic: &SymbolicCholesky<usize>) -> Self {
        let n = pattern.ncols();
        let identity: Vec<usize> = (0..n).collect();
        let inverse = symbolic.perm().map_or(&identity[..], |perm| perm.arrays().1);
        let new_index = |row: usize, col: usize| {
            let (i, j) = (inverse[row], inverse[col]);
            (i.max(j), i.min(j))
        };
        let mut col_ptr = vec![0usize; n + 1];
        for col in 0..n {
            for &row in pattern.row_idx_of_col_raw(col).iter().filter(|&&row| row >= col) {
                col_ptr[new_index(row, col).1 + 1] += 1;
            }
        }
        for j in 0..n {
            col_ptr[j + 1] += col_ptr[j];
        }
        let nnz = col_ptr[n];
        let (mut next, mut row_idx, mut slot) = (col_ptr.clone(), vec![0; nnz], Vec::with_capacity(nnz));
        for col in 0..n {
            for &row in pattern.row_idx_of_col_raw(col) {
                if row < col {
                    slot.push(ABOVE);
                    continue;
                }
                let (i, j) = new_index(row, col);
                row_idx[next[j]] = i;
                slot.push(next[j]);
                next[j] += 1;
            }
        }
        FactorOrder { col_ptr, row_idx, slot }
    }

    /// `a` (of the pattern this map was built for) in the factor's order, in `values`.
    fn gather<'a>(
        &'a self,
        a: SparseColMatRef<'_, usize, f64>,
        values: &'a mut [f64],
    ) -> SparseColMatRef<'a, usize, f64> {
        assert_eq!(a.val().len(), self.slot.len(), "matrix of another pattern");
        for (&slot, &value) in self.slot.iter().zip(a.val()) {
            if slot != ABOVE {
                values[slot] = value;
            }
        }
        let n = self.col_ptr.len() - 1;
        let pattern = SymbolicSparseColMatRef::new_unsorted_checked(n, n, &self.col_ptr, None, &self.row_idx);
        SparseColMatRef::new(pattern, values)
    }
}

/// A solution with a non-finite entry as the error of a singular tangent.
fn finite(x: &[f64]) -> Result<()> {
    if x.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(Error::NonFinite(
            "solution of the tangent system (singular tangent)".into(),
        ))
    }
}

/// `y = A x` for a symmetric matrix of which the lower triangle (row >= column) is stored;
/// entries above the diagonal, if any, are ignored.
pub fn multiply(a: SparseColMatRef<'_, usize, f64>, x: &[f64]) -> Vec<f64> {
    let mut y = vec![0.0; a.nrows()];
    for (j, &xj) in x.iter().enumerate() {
        let mut yj = 0.0;
        for (&i, &v) in a.row_idx_of_col_raw(j).iter().zip(a.val_of_col(j)) {
            if i > j {
                y[i] += v * xj;
                yj += v * x[i];
            } else if i == j {
                yj += v * xj;
            }
        }
        y[j] += yj;
    }
    y
}

#[cfg(test)]
pub(super) mod tests;
