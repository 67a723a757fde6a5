//! The sparsity of the reduced system: which element-matrix and group entries sum into each
//! stored entry of the lower triangle of `K_ff`, for one set of prescribed unknowns and added
//! groups. The stored entries are kept when only the groups change and every group's entries
//! are stored already; a group coupling unknowns not coupled before rebuilds them, and entries
//! once added stay (as zeros after their group has gone).

use crate::mesh::Mesh;
use faer::sparse::{Pair, SymbolicSparseColMat};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;

/// Source of pattern identifiers, unique across systems.
static NEXT_PATTERN: AtomicUsize = AtomicUsize::new(0);

/// Where a global unknown goes in the reduced system.
#[derive(Clone, Copy, Debug)]
pub(super) enum Slot {
    /// Index among the free unknowns.
    Free(usize),
    /// Index among the prescribed unknowns.
    Fixed(usize),
}

/// The reduced system's sparsity for one set of prescribed unknowns and added groups.
pub(super) struct Pattern {
    /// Identifies the layout of the element and group blocks (new whenever the groups change).
    pub(super) id: usize,
    /// Identifies the stored entries of `K_ff` (new only when `symbolic` is rebuilt).
    pub(super) structure: usize,
    pub(super) constrained: Vec<usize>,
    /// The added energy's groups the pattern includes (after the elements).
    pub(super) groups: Vec<Vec<usize>>,
    /// Pairs `(row, col)`, `row >= col`, stored besides the elements' (from groups, now or before).
    pub(super) coupled: Vec<Pair<usize, usize>>,
    pub(super) slots: Vec<Slot>,
    pub(super) free: Vec<usize>,
    /// Element `e` owns `values[offsets[e]..offsets[e + 1]]`: its free-free block, row-major,
    /// the entries on and below the global diagonal (row >= column) only;
    /// group `g` of the added energy follows as block `elements + g`.
    pub(super) offsets: Vec<usize>,
    /// Shared with every tangent assembled on it.
    pub(super) symbolic: Arc<SymbolicSparseColMat<usize>>,
    /// Stored entry `p` of `K_ff` (CSC order) is the sum of the element-matrix entries
    /// `sources[starts[p]..starts[p + 1]]` (indices into the element value buffer)...
    pub(super) starts: Vec<usize>,
    pub(super) sources: Vec<u32>,
    /// ... plus, for every group entry (the buffer after the elements' entries, in order),
    /// the value at that entry's position.
    pub(super) group_positions: Vec<usize>,
    /// Position of the diagonal entry of each free unknown's column.
    pub(super) diagonal: Vec<usize>,
}

/// What rebuilds a pattern with the same stored entries, so that its tangents are ordered and
/// factorised as before (an entry stored once stays, and changes the ordering): the prescribed
/// unknowns, the groups laid out, and the free pairs `(row, col)` stored besides the elements'.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StoredEntries {
    constrained: Vec<usize>,
    groups: Vec<Vec<usize>>,
    coupled: Vec<(usize, usize)>,
}

impl Pattern {
    /// What rebuilds it ([`Pattern::rebuilt`]).
    pub(super) fn stored_entries(&self) -> StoredEntries {
        StoredEntries {
            constrained: self.constrained.clone(),
            groups: self.groups.clone(),
            coupled: self.coupled.iter().map(|q| (q.row, q.col)).collect(),
        }
    }

    /// The pattern of `entries` on `mesh`, or `None` if they do not fit the mesh's unknowns.
    pub(super) fn rebuilt<const D: usize, const N: usize>(mesh: &Mesh<D, N>, entries: StoredEntries) -> Option<Self> {
        let n = mesh.num_dofs();
        let free = n.checked_sub(entries.constrained.len())?;
        let fits = entries
            .constrained
            .iter()
            .chain(entries.groups.iter().flatten())
            .all(|&d| d < n)
            && entries.coupled.iter().all(|&(row, col)| row < free && col <= row);
        let coupled = entries.coupled.iter().map(|&(row, col)| Pair::new(row, col)).collect();
        fits.then(|| build_pattern(mesh, &entries.constrained, &entries.groups, coupled, &[]))
    }

    /// Makes `pattern` the one for the prescribed unknowns `constrained` and the added `groups`,
    /// keeping its stored entries where they suffice.
    /// When the stored entries grow, the sets of unknowns `likely` (see
    /// [`crate::fem::added::AddedEnergy::likely_groups`]) are coupled too.
    pub(super) fn refresh<const D: usize, const N: usize>(
        pattern: &mut Option<Pattern>,
        mesh: &Mesh<D, N>,
        constrained: &[usize],
        groups: &[Vec<usize>],
        likely: &dyn Fn() -> Vec<Vec<usize>>,
    ) {
        match pattern.as_mut() {
            Some(p) if p.constrained == constrained && p.groups == groups => {}
            Some(p) if p.constrained == constrained => {
                let added = group_pairs(&p.slots, groups);
                let missing = p.missing(&added);
                if missing.is_empty() {
                    p.place_groups(groups, added, mesh.elements().len());
                } else {
                    let mut coupled = std::mem::take(&mut p.coupled);
                    coupled.extend(missing);
                    *pattern = None; // free the old pattern before building the new one
                    *pattern = Some(build_pattern(mesh, constrained, groups, coupled, &likely()));
                    // The old pattern and the new one's scaffolding leave holes in the heap.
                    crate::fem::memory::return_free_pages();
                }
            }
            _ => {
                *pattern = None;
                *pattern = Some(build_pattern(mesh, constrained, groups, Vec::new(), &likely()));
            }
        }
    }

    /// Whether `constrained` and `groups` keep the stored entries.
    pub(super) fn fits(&self, constrained: &[usize], groups: &[Vec<usize>]) -> bool {
        self.constrained == constrained && self.missing(&group_pairs(&self.slots, groups)).is_empty()
    }

    /// The pairs of `added` that are not stored.
    fn missing(&self, added: &GroupPairs) -> Vec<Pair<usize, usize>> {
        let stored = |q: &&Pair<usize, usize>| try_position(&self.symbolic, q).is_some();
        added.pairs.iter().filter(|q| !stored(q)).copied().collect()
    }

    /// Lays out new `groups`, whose pairs `added` are all stored, after the elements' entries.
    fn place_groups(&mut self, groups: &[Vec<usize>], added: GroupPairs, elements: usize) {
        self.id = NEXT_PATTERN.fetch_add(1, Ordering::Relaxed);
        self.groups = groups.to_vec();
        let element_entries = self.offsets[elements];
        self.offsets.truncate(elements + 1);
        self.offsets.extend(added.ends.iter().map(|end| element_entries + end));
        self.group_positions = added
            .pairs
            .iter()
            .map(|q| position(&self.symbolic, q.row, q.col))
            .collect();
    }

    /// The stored values of `K_ff` from the element and group matrices' `entries` (laid out by
    /// `offsets`, the first `elements` blocks being the elements').
    pub(super) fn tangent_values(&self, entries: &[f64], elements: usize) -> Vec<f64> {
        let mut values = vec![0.0; self.starts.len() - 1];
        values.par_iter_mut().with_min_len(4096).enumerate().for_each(|(p, v)| {
            let sources = &self.sources[self.starts[p]..self.starts[p + 1]];
            *v = sources.iter().map(|&s| entries[s as usize]).sum();
        });
        for (&position, &value) in self.group_positions.iter().zip(&entries[self.offsets[elements]..]) {
            values[position] += value;
        }
        values
    }
}

/// The free-free pairs `(row, col)`, `row >= col`, of every group in order (a group's free
/// unknowns in its own order), and where each group's pairs end.
struct GroupPairs {
    pairs: Vec<Pair<usize, usize>>,
    ends: Vec<usize>,
}

/// The free-free lower pairs of the blocks over `dofs`, block after block.
fn block_pairs<'a>(slots: &[Slot], blocks: impl Iterator<Item = &'a [usize]>) -> GroupPairs {
    let (mut pairs, mut ends) = (Vec::new(), Vec::new());
    for dofs in blocks {
        let local: Vec<usize> = dofs
            .iter()
            .filter_map(|&dof| match slots[dof] {
                Slot::Free(f) => Some(f),
                Slot::Fixed(_) => None,
            })
            .collect();
        for &row in &local {
            pairs.extend(local.iter().filter(|&&col| row >= col).map(|&col| Pair::new(row, col)));
        }
        ends.push(pairs.len());
    }
    GroupPairs { pairs, ends }
}

/// [`block_pairs`] of the added groups.
fn group_pairs(slots: &[Slot], groups: &[Vec<usize>]) -> GroupPairs {
    block_pairs(slots, groups.iter().map(Vec::as_slice))
}

/// Slots, free list, per-block offsets and the CSC pattern of the lower triangle of `K_ff`
/// (elements, then groups), storing the `coupled` pairs and those of the `likely` groups too.
fn build_pattern<const D: usize, const N: usize>(
    mesh: &Mesh<D, N>,
    constrained: &[usize],
    groups: &[Vec<usize>],
    coupled: Vec<Pair<usize, usize>>,
    likely: &[Vec<usize>],
) -> Pattern {
    let mut slots = vec![Slot::Free(0); mesh.num_dofs()];
    for (c, &dof) in constrained.iter().enumerate() {
        slots[dof] = Slot::Fixed(c);
    }
    let mut free = Vec::with_capacity(slots.len() - constrained.len());
    for (dof, slot) in slots.iter_mut().enumerate() {
        if let Slot::Free(f) = slot {
            *f = free.len();
            free.push(dof);
        }
    }
    let dofs = mesh.dofs();
    let element_dofs: Vec<Vec<usize>> = mesh
        .elements()
        .iter()
        .map(|nodes| (0..dofs.count(N)).map(|i| dofs.global(nodes, i)).collect())
        .collect();
    let GroupPairs {
        pairs: mut all,
        ends: element_ends,
    } = block_pairs(&slots, element_dofs.iter().map(|d| d.as_slice()));
    let element_entries = all.len();
    let added = group_pairs(&slots, groups);
    let mut coupled = coupled;
    coupled.extend(&added.pairs);
    coupled.extend(group_pairs(&slots, likely).pairs);
    coupled.sort_unstable_by_key(|q| (q.col, q.row));
    coupled.dedup();
    // The elements' pairs, then the others.
    all.extend(&coupled);
    let (symbolic, _) = SymbolicSparseColMat::try_new_from_indices(free.len(), free.len(), &all)
        .expect("pattern indices are in range by construction");
    let (starts, sources) = gather_lists(&symbolic, &all[..element_entries]);
    drop(all);
    let diagonal = (0..free.len()).map(|f| position(&symbolic, f, f)).collect();
    let offsets = std::iter::once(0)
        .chain(element_ends)
        .chain(added.ends.iter().map(|end| element_entries + end))
        .collect();
    Pattern {
        id: NEXT_PATTERN.fetch_add(1, Ordering::Relaxed),
        structure: NEXT_PATTERN.fetch_add(1, Ordering::Relaxed),
        constrained: constrained.to_vec(),
        groups: groups.to_vec(),
        coupled,
        slots,
        free,
        offsets,
        group_positions: added.pairs.iter().map(|q| position(&symbolic, q.row, q.col)).collect(),
        symbolic: Arc::new(symbolic),
        starts,
        sources,
        diagonal,
    }
}

/// Position of entry `q` in the CSC arrays of `symbolic`, if it is stored.
fn try_position(symbolic: &SymbolicSparseColMat<usize>, q: &Pair<usize, usize>) -> Option<usize> {
    let (col_ptr, row_idx) = (symbolic.col_ptr(), symbolic.row_idx());
    let column = &row_idx[col_ptr[q.col]..col_ptr[q.col + 1]];
    column.binary_search(&q.row).ok().map(|i| col_ptr[q.col] + i)
}

/// Position of entry `(row, col)` in the CSC arrays of `symbolic` (it must be stored).
pub(super) fn position(symbolic: &SymbolicSparseColMat<usize>, row: usize, col: usize) -> usize {
    try_position(symbolic, &Pair::new(row, col)).expect("every pair is in the pattern")
}

/// For every stored entry of `symbolic`, the indices of the `pairs` that land on it (increasing):
/// a counting sort of the pairs by their position in the CSC arrays.
fn gather_lists(symbolic: &SymbolicSparseColMat<usize>, pairs: &[Pair<usize, usize>]) -> (Vec<usize>, Vec<u32>) {
    let row_idx = symbolic.row_idx();
    let positions: Vec<usize> = pairs.iter().map(|p| position(symbolic, p.row, p.col)).collect();
    let mut starts = vec![0; row_idx.len() + 1];
    for &p in &positions {
        starts[p + 1] += 1;
    }
    for p in 0..row_idx.len() {
        starts[p + 1] += starts[p];
    }
    let mut next = starts.clone();
    let mut sources = vec![0; pairs.len()];
    for (source, &p) in positions.iter().enumerate() {
        sources[next[p]] = u32::try_from(source).expect("fewer than 2^32 element-matrix entries");
        next[p] += 1;
    }
    (starts, sources)
}
