//! `L D L^T` on two cores by one level of nested dissection. A vertex separator `S` splits the
//! unknowns into two parts that do not couple,
//!
//! ```text
//!     K = [ A_1   0    B_1 ]        K_p = [ A_p    B_p  ]
//!         [ 0    A_2   B_2 ]              [ B_p^T  C / 2 ]
//!         [ B_1^T B_2^T C  ]
//! ```
//!
//! and each part's matrix `K_p` is factorised on its own core (faer's supernodal `L D L^T`, the
//! part's interior in its AMD order and the separator last). The factor's last block is then
//! the part's Schur complement, `L_SS D_SS L_SS^T = C / 2 - B_p^T A_p^-1 B_p`, and the
//! separator's system `S = S_1 + S_2 = C - B_1^T A_1^-1 B_1 - B_2^T A_2^-1 B_2` is small and dense
//! (Bunch-Kaufman). By Sylvester's law and Haynsworth's inertia additivity, the negative
//! eigenvalues of `K` are those of `A_1`, `A_2` and `S` together: the pivots of the parts'
//! interiors and the dense factor's.
//!
//! faer's own supernodal factorisation on two threads was 2-3x slower than on one on a
//! two-core machine; the two independent factorisations here keep each one sequential.
//!
//! The separator is found in [`super::separator`].

use faer::diag::Diag;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::lblt;
use faer::linalg::cholesky::ldlt::factor::LdltRegularization;
use faer::linalg::matmul::matmul;
use faer::perm::PermRef;
use faer::sparse::linalg::amd;
use faer::sparse::linalg::cholesky::supernodal::{
    factorize_supernodal_numeric_ldlt, factorize_supernodal_numeric_ldlt_scratch, SupernodalLdltRef,
    SymbolicSupernodalCholesky,
};
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, SymbolicCholesky, SymbolicCholeskyRaw, SymmetricOrdering,
};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Accum, Conj, Mat, Par, Side};

use super::separator::{bisect, Graph, FIRST, SECOND, SEPARATOR};
use super::FactorOrder;

/// Smallest dimension that is split: below it one core factorises faster than two exchange.
pub(super) const SMALLEST_SPLIT: usize = 4000;

/// The analysis of one pattern split in two: the separator and each part's ordering and map.
pub(super) struct SplitAnalysis {
    /// Global indices of the separator's unknowns.
    separator: Vec<usize>,
    parts: [PartAnalysis; 2],
    /// Stored entries of the analysed pattern (a matrix of another pattern is refused).
    stored: usize,
}

/// One part: its interior unknowns, then the separator, in the factor's order.
struct PartAnalysis {
    /// Global index of each interior unknown (local index `i < interior.len()`).
    interior: Vec<usize>,
    symbolic: SymbolicCholesky<usize>,
    /// The part's lower triangle in the factor's order, rows unsorted.
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    /// `(stored entry of the global matrix, slot among the part's values)`, the separator's
    /// own entries (halved) last, from `halved_from` on.
    gather: Vec<(u32, u32)>,
    halved_from: usize,
    /// Position in the factor of each local unknown (interior, then separator).
    position: Vec<usize>,
}

impl SplitAnalysis {
    /// The split of the symmetric pattern whose lower triangle is `pattern`, or `None` where
    /// it is too small, or no level gives two balanced parts with a small separator.
    pub(super) fn new(pattern: SymbolicSparseColMatRef<'_, usize>, smallest: usize) -> Option<Self> {
        let n = pattern.ncols();
        if n < smallest || u32::try_from(pattern.row_idx().len()).is_err() {
            return None;
        }
        let side = bisect(&Graph::new(pattern))?;
        let separator: Vec<usize> = (0..n).filter(|&i| side[i] == SEPARATOR).collect();
        if separator.is_empty() {
            return None;
        }
        let analyse = |p| PartAnalysis::new(pattern, &side, p, &separator);
        let (first, second) = both_sides(|| analyse(FIRST), || analyse(SECOND));
        let parts = [first?, second?];
        let stored = (0..n).map(|col| pattern.row_idx_of_col_raw(col).len()).sum();
        Some(SplitAnalysis {
            separator,
            parts,
            stored,
        })
    }

    /// Number of stored factor values of both parts and the separator's dense block.
    pub(super) fn factor_size(&self) -> usize {
        let s = self.separator.len();
        self.parts.iter().map(|p| p.symbolic.len_val()).sum::<usize>() + s * s
    }
}

impl PartAnalysis {
    /// The part `p` of `side`: its interior in AMD order, then the separator; `None` if the
    /// factor does not keep the separator last (a part in pieces).
    fn new(pattern: SymbolicSparseColMatRef<'_, usize>, side: &[u8], p: u8, separator: &[usize]) -> Option<Self> {
        let n = pattern.ncols();
        let interior: Vec<usize> = (0..n).filter(|&i| side[i] == p).collect();
        let mut local = vec![usize::MAX; n];
        interior
            .iter()
            .chain(separator)
            .enumerate()
            .for_each(|(l, &g)| local[g] = l);
        let (m, n_a) = (interior.len() + separator.len(), interior.len());
        // The part's lower triangle in local numbering, with the global entry of each value.
        // 32-bit indices: this is built beside the factors it replaces.
        let mut entries: Vec<(u32, u32, u32)> = Vec::new();
        let mut k = 0;
        for col in 0..n {
            for &row in pattern.row_idx_of_col_raw(col) {
                let (i, j) = (local[row], local[col]);
                if row >= col && i != usize::MAX && j != usize::MAX {
                    entries.push((i.max(j) as u32, i.min(j) as u32, k as u32));
                }
                k += 1;
            }
        }
        let mut col_ptr = vec![0usize; m + 1];
        entries.iter().for_each(|&(_, j, _)| col_ptr[j as usize + 1] += 1);
        (0..m).for_each(|j| col_ptr[j + 1] += col_ptr[j]);
        let mut row_idx = vec![0usize; entries.len()];
        // The global stored entry of each of the part's, in the part's storage order.
        let mut global = vec![0u32; entries.len()];
        let mut next = col_ptr.clone();
        for &(i, j, k) in &entries {
            let j = j as usize;
            (row_idx[next[j]], global[next[j]]) = (i as usize, k);
            next[j] += 1;
        }
        drop(entries);
        let local_pattern = SymbolicSparseColMatRef::new_unsorted_checked(m, m, &col_ptr, None, &row_idx);
        let symbolic = ordered_symbolic(local_pattern, n_a)?;
        let (perm_forward, position) = symbolic.perm()?.arrays();
        // The separator must be the factor's last block.
        if (n_a..m).any(|l| position[l] < n_a) || perm_forward.len() != m {
            return None;
        }
        let position = position.to_vec();
        let order = FactorOrder::new(local_pattern, &symbolic);
        // The separator's own entries (both indices at or after n_a) are halved: last.
        let mut gather: Vec<(u32, u32)> = Vec::with_capacity(global.len());
        let mut halved = Vec::new();
        for col in 0..m {
            for (e, &row) in (col_ptr[col]..col_ptr[col + 1]).zip(&row_idx[col_ptr[col]..col_ptr[col + 1]]) {
                let pair = (global[e], order.slot[e] as u32);
                if row >= n_a && col >= n_a {
                    halved.push(pair);
                } else {
                    gather.push(pair);
                }
            }
        }
        let halved_from = gather.len();
        gather.extend(halved);
        Some(PartAnalysis {
            interior,
            symbolic,
            col_ptr: order.col_ptr,
            row_idx: order.row_idx,
            gather,
            halved_from,
            position,
        })
    }

    fn supernodal(&self) -> &SymbolicSupernodalCholesky<usize> {
        match self.symbolic.raw() {
            SymbolicCholeskyRaw::Supernodal(s) => s,
            SymbolicCholeskyRaw::Simplicial(_) => unreachable!("the analysis forces a supernodal factor"),
        }
    }

    fn interior_len(&self) -> usize {
        self.interior.len()
    }
}

/// The symbolic factorisation of a part's matrix with its first `n_a` unknowns in their AMD
/// order and the rest (the separator) last, in their order.
fn ordered_symbolic(pattern: SymbolicSparseColMatRef<'_, usize>, n_a: usize) -> Option<SymbolicCholesky<usize>> {
    let m = pattern.ncols();
    // The interior's own pattern, for its AMD order.
    let mut col_ptr = vec![0usize; n_a + 1];
    let mut row_idx = Vec::new();
    for col in 0..n_a {
        row_idx.extend(pattern.row_idx_of_col_raw(col).iter().filter(|&&r| r < n_a));
        col_ptr[col + 1] = row_idx.len();
    }
    let interior = SymbolicSparseColMatRef::new_unsorted_checked(n_a, n_a, &col_ptr, None, &row_idx);
    let (mut forward, mut inverse) = (vec![0usize; m], vec![0usize; m]);
    let mut memory = MemBuffer::new(amd::order_maybe_unsorted_scratch::<usize>(n_a, row_idx.len()));
    amd::order_maybe_unsorted(
        &mut forward[..n_a],
        &mut inverse[..n_a],
        interior,
        amd::Control::default(),
        MemStack::new(&mut memory),
    )
    .ok()?;
    for l in n_a..m {
        (forward[l], inverse[l]) = (l, l);
    }
    let params = CholeskySymbolicParams {
        supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
        ..Default::default()
    };
    let ordering = SymmetricOrdering::Custom(PermRef::new_checked(&forward, &inverse, m));
    factorize_symbolic_cholesky(pattern, Side::Lower, ordering, params).ok()
}

/// The numeric factors of a split: each part's `L D L^T`, the separator's Bunch-Kaufman.
pub(super) struct SplitFactor {
    parts: [PartFactor; 2],
    separator: Option<DenseLblt>,
}

struct PartFactor {
    permuted: Vec<f64>,
    values: Vec<f64>,
    scratch: MemBuffer,
    /// The part's Schur complement on the separator (in the separator's order).
    schur: Mat<f64>,
    /// Negative pivots among the interior's.
    negative: usize,
    /// Whether `values` is rounded to single precision.
    single: bool,
    /// Work vector in the factor's order.
    work: Vec<f64>,
}

impl SplitFactor {
    pub(super) fn new(analysis: &SplitAnalysis) -> Self {
        let parts = [0, 1].map(|p| {
            let part = &analysis.parts[p];
            let scratch = MemBuffer::new(factorize_supernodal_numeric_ldlt_scratch::<usize, f64>(
                part.supernodal(),
                Par::Seq,
                Default::default(),
            ));
            PartFactor {
                permuted: vec![0.0; part.row_idx.len()],
                values: vec![0.0; part.symbolic.len_val()],
                scratch,
                schur: Mat::zeros(0, 0),
                negative: 0,
                single: false,
                work: vec![0.0; part.position.len()],
            }
        });
        SplitFactor { parts, separator: None }
    }

    /// Factorises the matrix with the lower-triangle values `values` (of the analysed
    /// pattern); `false` where a part meets a zero pivot (the caller then pivots the whole).
    pub(super) fn factorize(&mut self, analysis: &SplitAnalysis, values: &[f64]) -> bool {
        assert_eq!(values.len(), analysis.stored, "matrix of another pattern");
        let [first, second] = &mut self.parts;
        let (a, b) = both_sides(
            || first.factorize(&analysis.parts[0], values),
            || second.factorize(&analysis.parts[1], values),
        );
        if !(a && b) {
            self.separator = None;
            return false;
        }
        let s = &self.parts[0].schur + &self.parts[1].schur;
        self.separator = Some(DenseLblt::new(s));
        true
    }

    /// Negative eigenvalues of the factorised matrix.
    pub(super) fn negative_pivots(&self) -> usize {
        let lblt = self.separator.as_ref().expect("factorised");
        let pivots: Vec<(f64, f64)> = (0..lblt.diagonal.dim())
            .map(|i| (lblt.diagonal[i], lblt.subdiagonal[i]))
            .collect();
        self.parts.iter().map(|p| p.negative).sum::<usize>() + super::block_inertia(&pivots)
    }

    /// Solves `K x = b` in place; with the parts' factors rounded to single precision if
    /// `single` (the first such solve rounds them; no double-precision solve follows until the
    /// next factorisation).
    pub(super) fn solve_in_place(&mut self, analysis: &SplitAnalysis, rhs: &mut [f64], single: bool) {
        for part in &self.parts {
            assert!(
                single || !part.single,
                "double-precision solve with a factor rounded to single"
            );
        }
        let [first, second] = &mut self.parts;
        let (pa, pb) = (&analysis.parts[0], &analysis.parts[1]);
        let rhs_read: &[f64] = rhs;
        both_sides(
            || first.forward(pa, rhs_read, single),
            || second.forward(pb, rhs_read, single),
        );
        let s = analysis.separator.len();
        let mut xs = Mat::<f64>::zeros(s, 1);
        for (t, &g) in analysis.separator.iter().enumerate() {
            xs[(t, 0)] = rhs[g]
                + first.work[pa.position[pa.interior_len() + t]]
                + second.work[pb.position[pb.interior_len() + t]];
        }
        self.separator.as_ref().expect("factorised").solve_in_place(&mut xs);
        let xs = xs.col(0).try_as_col_major().expect("one column").as_slice();
        both_sides(|| first.backward(pa, xs), || second.backward(pb, xs));
        for (part, factor) in analysis.parts.iter().zip(&self.parts) {
            for (l, &g) in part.interior.iter().enumerate() {
                rhs[g] = factor.work[part.position[l]];
            }
        }
        for (t, &g) in analysis.separator.iter().enumerate() {
            rhs[g] = xs[t];
        }
    }
}

impl PartFactor {
    /// `L D L^T` of the part's matrix, its interior's negative pivots and its Schur complement.
    fn factorize(&mut self, part: &PartAnalysis, values: &[f64]) -> bool {
        let (whole, halved) = part.gather.split_at(part.halved_from);
        whole
            .iter()
            .for_each(|&(k, slot)| self.permuted[slot as usize] = values[k as usize]);
        halved
            .iter()
            .for_each(|&(k, slot)| self.permuted[slot as usize] = 0.5 * values[k as usize]);
        let m = part.position.len();
        let pattern = SymbolicSparseColMatRef::new_unsorted_checked(m, m, &part.col_ptr, None, &part.row_idx);
        let supernodal = part.supernodal();
        let factorised = factorize_supernodal_numeric_ldlt(
            &mut self.values,
            SparseColMatRef::new(pattern, &self.permuted),
            LdltRegularization::default(),
            supernodal,
            Par::Seq,
            MemStack::new(&mut self.scratch),
            Default::default(),
        );
        self.single = false;
        if factorised.is_err() {
            return false;
        }
        let n_a = part.interior_len();
        let s = m - n_a;
        // L_SS (unit lower) and D_SS from the columns at and after n_a, in factor order.
        let (mut l, mut d) = (Mat::<f64>::identity(s, s), vec![0.0; s]);
        self.negative = 0;
        let factor = SupernodalLdltRef::new(supernodal, &self.values);
        for node in (0..supernodal.n_supernodes()).map(|n| factor.supernode(n)) {
            let (start, block) = (node.start(), node.val());
            let size = block.ncols();
            for c in 0..size {
                let j = start + c;
                if j < n_a {
                    self.negative += usize::from(block[(c, c)] < 0.0);
                    continue;
                }
                d[j - n_a] = block[(c, c)];
                for r in c + 1..size {
                    l[(start + r - n_a, j - n_a)] = block[(r, c)];
                }
                for (idx, &row) in node.pattern().iter().enumerate() {
                    l[(row - n_a, j - n_a)] = block[(size + idx, c)];
                }
            }
        }
        // S_p = L D L^T, then from factor order to the separator's.
        let mut scaled = l.clone();
        for (j, &dj) in d.iter().enumerate() {
            scaled.col_mut(j).iter_mut().for_each(|v| *v *= dj);
        }
        let mut product = Mat::<f64>::zeros(s, s);
        matmul(
            product.as_mut(),
            Accum::Replace,
            scaled.as_ref(),
            l.transpose(),
            1.0,
            Par::Seq,
        );
        let at = |t: usize| part.position[n_a + t] - n_a;
        self.schur = Mat::from_fn(s, s, |a, b| product[(at(a), at(b))]);
        true
    }

    /// Forward substitution over the interior's columns for the right-hand side `[b_p, 0]`:
    /// afterwards `work` holds `L_11^-1 b_p` on the interior and `-B_p^T A_p^-1 b_p` on the
    /// separator. With `single`, the factor is first rounded to single precision (on this
    /// part's own thread) if it is not yet.
    fn forward(&mut self, part: &PartAnalysis, rhs: &[f64], single: bool) {
        if single && !self.single {
            super::round_to_single(&mut self.values);
            self.single = true;
        }
        let x = &mut self.work;
        x.iter_mut().for_each(|v| *v = 0.0);
        for (l, &g) in part.interior.iter().enumerate() {
            x[part.position[l]] = rhs[g];
        }
        match self.single {
            true => forward(part, super::as_single(&self.values), x),
            false => forward(part, &self.values, x),
        }
    }

    /// With the separator's solution `xs`: `D^-1` and back substitution over the interior's
    /// columns, leaving the part's solution in `work` (factor order).
    fn backward(&mut self, part: &PartAnalysis, xs: &[f64]) {
        let n_a = part.interior_len();
        for (t, &v) in xs.iter().enumerate() {
            self.work[part.position[n_a + t]] = v;
        }
        match self.single {
            true => backward(part, super::as_single(&self.values), &mut self.work),
            false => backward(part, &self.values, &mut self.work),
        }
    }
}

/// Forward substitution with the unit `L` of `values` over the interior's columns of `part`.
fn forward<T: Copy + Into<f64>>(part: &PartAnalysis, values: &[T], x: &mut [f64]) {
    let n_a = part.interior_len();
    let supernodal = part.supernodal();
    let factor = SupernodalLdltRef::new(supernodal, values);
    // The updates of the rows below a supernode, summed over its columns, then scattered.
    let mut below: Vec<f64> = Vec::new();
    for node in (0..supernodal.n_supernodes()).map(|n| factor.supernode(n)) {
        let (start, block) = (node.start(), node.val());
        if start >= n_a {
            break;
        }
        let size = block.ncols();
        below.clear();
        below.resize(node.pattern().len(), 0.0);
        for c in 0..(n_a - start).min(size) {
            let column = block.col(c).try_as_col_major().expect("column-major").as_slice();
            let xc = x[start + c];
            for (xr, &v) in x[start + c + 1..start + size].iter_mut().zip(&column[c + 1..size]) {
                *xr -= v.into() * xc;
            }
            for (b, &v) in below.iter_mut().zip(&column[size..]) {
                *b += v.into() * xc;
            }
        }
        for (&row, &b) in node.pattern().iter().zip(&below) {
            x[row] -= b;
        }
    }
}

/// `D^-1` and back substitution with `L^T` of `values` over the interior's columns of `part`
/// (the separator's unknowns in `x` already solved).
fn backward<T: Copy + Into<f64>>(part: &PartAnalysis, values: &[T], x: &mut [f64]) {
    let n_a = part.interior_len();
    let supernodal = part.supernodal();
    let factor = SupernodalLdltRef::new(supernodal, values);
    let nodes = supernodal.n_supernodes();
    for node in (0..nodes).map(|n| factor.supernode(n)) {
        let (start, block) = (node.start(), node.val());
        for c in 0..block.ncols() {
            if start + c < n_a {
                x[start + c] /= block[(c, c)].into();
            }
        }
    }
    // The solution on the rows below a supernode, gathered once.
    let mut below: Vec<f64> = Vec::new();
    for node in (0..nodes).rev().map(|n| factor.supernode(n)) {
        let (start, block) = (node.start(), node.val());
        if start >= n_a {
            continue;
        }
        let size = block.ncols();
        below.clear();
        below.extend(node.pattern().iter().map(|&row| x[row]));
        for c in (0..(n_a - start).min(size)).rev() {
            let column = block.col(c).try_as_col_major().expect("column-major").as_slice();
            let sum = dot(&column[c + 1..size], &x[start + c + 1..start + size]) + dot(&column[size..], &below);
            x[start + c] -= sum;
        }
    }
}

/// `a . b` in four interleaved sums (which the compiler vectorises; one sum in order it may not).
fn dot<T: Copy + Into<f64>>(a: &[T], b: &[f64]) -> f64 {
    let mut sums = [0.0; 4];
    let (chunks_a, chunks_b) = (a.chunks_exact(4), b.chunks_exact(4));
    let tail: f64 = chunks_a
        .remainder()
        .iter()
        .zip(chunks_b.remainder())
        .map(|(&p, &q)| p.into() * q)
        .sum();
    for (p, q) in chunks_a.zip(chunks_b) {
        for k in 0..4 {
            sums[k] += p[k].into() * q[k];
        }
    }
    (sums[0] + sums[1]) + (sums[2] + sums[3]) + tail
}

/// `(first(), second())`, the second on a thread of its own while the first runs on the
/// caller's; one after the other where the caller keeps to one thread (`RAYON_NUM_THREADS=1`:
/// the same numbers). Not rayon: faer's kernels on the global pool's threads slowed the
/// assemblies that followed on them (coarse mesh: 0.6 -> 1.0 s), and a pool's worker waiting on
/// another pool runs its own pool's queued work meanwhile (`reproduce` then started all its
/// figures at once: 2.1 GB).
pub(super) fn both_sides<A: Send, B: Send>(
    first: impl FnOnce() -> A + Send,
    second: impl FnOnce() -> B + Send,
) -> (A, B) {
    if rayon::current_num_threads() < 2 {
        return (first(), second());
    }
    std::thread::scope(|scope| {
        let second = scope.spawn(second);
        let first = first();
        (first, second.join().expect("a side does not panic"))
    })
}

/// The Bunch-Kaufman factorisation `P S P^T = L B L^T` of the separator's dense system, on
/// one thread (faer's dense solvers on the global thread pool slowed the next assemblies'
/// rayon loops twofold, measured).
struct DenseLblt {
    l: Mat<f64>,
    diagonal: Diag<f64>,
    subdiagonal: Diag<f64>,
    forward: Vec<usize>,
    inverse: Vec<usize>,
}

impl DenseLblt {
    fn new(mut l: Mat<f64>) -> Self {
        let n = l.nrows();
        let mut subdiagonal = Diag::zeros(n);
        let (mut forward, mut inverse) = (vec![0usize; n], vec![0usize; n]);
        let mut memory = MemBuffer::new(lblt::factor::cholesky_in_place_scratch::<usize, f64>(
            n,
            Par::Seq,
            Default::default(),
        ));
        lblt::factor::cholesky_in_place(
            l.as_mut(),
            subdiagonal.as_mut(),
            &mut forward,
            &mut inverse,
            Par::Seq,
            MemStack::new(&mut memory),
            Default::default(),
        );
        let mut diagonal = Diag::zeros(n);
        diagonal.copy_from(l.diagonal());
        for j in 0..n {
            l[(j, j)] = 1.0;
            (0..j).for_each(|i| l[(i, j)] = 0.0);
        }
        DenseLblt {
            l,
            diagonal,
            subdiagonal,
            forward,
            inverse,
        }
    }

    fn solve_in_place(&self, rhs: &mut Mat<f64>) {
        let n = self.l.nrows();
        let mut memory = MemBuffer::new(lblt::solve::solve_in_place_scratch::<usize, f64>(n, 1, Par::Seq));
        lblt::solve::solve_in_place_with_conj(
            self.l.as_ref(),
            self.diagonal.as_ref(),
            self.subdiagonal.as_ref(),
            Conj::No,
            PermRef::new_checked(&self.forward, &self.inverse, n),
            rhs.as_mut(),
            Par::Seq,
            MemStack::new(&mut memory),
        );
    }
}
