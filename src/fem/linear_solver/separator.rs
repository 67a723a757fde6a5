//! A vertex separator of a sparse symmetric pattern for [`super::split`]: a level of a
//! breadth-first search from a pseudo-peripheral unknown (across a long strip, a column of
//! nodes), trimmed to the unknowns that touch both sides.

use faer::sparse::SymbolicSparseColMatRef;

/// Which side of the separator an unknown lies on.
pub(super) const FIRST: u8 = 0;
pub(super) const SECOND: u8 = 1;
pub(super) const SEPARATOR: u8 = 2;

/// The symmetric adjacency of a pattern's lower triangle (diagonal left out).
pub(super) struct Graph {
    start: Vec<usize>,
    /// 32-bit indices: the graph is built beside the factors it replaces.
    neighbours: Vec<u32>,
}

impl Graph {
    pub(super) fn new(pattern: SymbolicSparseColMatRef<'_, usize>) -> Self {
        let n = pattern.ncols();
        let edges = || (0..n).flat_map(move |c| pattern.row_idx_of_col_raw(c).iter().map(move |&r| (r, c)));
        let mut start = vec![0usize; n + 1];
        for (r, c) in edges().filter(|(r, c)| r > c) {
            start[r + 1] += 1;
            start[c + 1] += 1;
        }
        (0..n).for_each(|i| start[i + 1] += start[i]);
        let mut next = start.clone();
        let mut neighbours = vec![0u32; start[n]];
        for (r, c) in edges().filter(|(r, c)| r > c) {
            neighbours[next[r]] = c as u32;
            next[r] += 1;
            neighbours[next[c]] = r as u32;
            next[c] += 1;
        }
        Graph { start, neighbours }
    }

    fn len(&self) -> usize {
        self.start.len() - 1
    }

    pub(super) fn of(&self, v: usize) -> &[u32] {
        &self.neighbours[self.start[v]..self.start[v + 1]]
    }

    /// Breadth-first levels from `root` (`u32::MAX` where unreached).
    fn levels(&self, root: usize) -> Vec<u32> {
        let mut level = vec![u32::MAX; self.len()];
        let mut queue = std::collections::VecDeque::from([root]);
        level[root] = 0;
        while let Some(v) = queue.pop_front() {
            for w in self.of(v).iter().map(|&w| w as usize) {
                if level[w] == u32::MAX {
                    level[w] = level[v] + 1;
                    queue.push_back(w);
                }
            }
        }
        level
    }
}

/// Each unknown's side (`FIRST`, `SECOND` or `SEPARATOR`): a breadth-first level from a
/// pseudo-peripheral unknown that leaves at least 40 % of the unknowns on each side,
/// trimmed to the unknowns with neighbours on both; `None` if none is below 5 % of them.
pub(super) fn bisect(graph: &Graph) -> Option<Vec<u8>> {
    let n = graph.len();
    // A pseudo-peripheral root: the least connected unknown of the last level, repeatedly.
    let mut levels = graph.levels(0);
    for _ in 0..4 {
        let depth = levels.iter().filter(|&&l| l != u32::MAX).max().copied()?;
        let far = (0..n)
            .filter(|&v| levels[v] == depth)
            .min_by_key(|&v| graph.of(v).len())?;
        let further = graph.levels(far);
        let new_depth = further.iter().filter(|&&l| l != u32::MAX).max().copied()?;
        levels = further;
        if new_depth <= depth {
            break;
        }
    }
    let depth = levels.iter().filter(|&&l| l != u32::MAX).max().copied()? as usize;
    let mut counts = vec![0usize; depth + 1];
    levels
        .iter()
        .filter(|&&l| l != u32::MAX)
        .for_each(|&l| counts[l as usize] += 1);
    // The level that leaves the larger part smallest, each unknown of the separator counted
    // as 50 of a part (its dense block and the parts' coupling to it).
    let (mut below, mut best) = (0, None::<(usize, usize, usize)>);
    for (m, &count) in counts.iter().enumerate() {
        let above = n - below - count;
        let cost = below.max(above) + 50 * count;
        if below.min(above) * 5 >= n * 2 && best.is_none_or(|(_, _, c)| cost < c) {
            best = Some((m, count, cost));
        }
        below += count;
    }
    let (m, count, _) = best?;
    if count * 20 > n {
        return None;
    }
    let m = m as u32;
    let mut side: Vec<u8> = levels
        .iter()
        .map(|&l| match l.cmp(&m) {
            std::cmp::Ordering::Less => FIRST,
            std::cmp::Ordering::Equal => SEPARATOR,
            std::cmp::Ordering::Greater => SECOND,
        })
        .collect();
    // An unknown of the separator with no neighbour on one side joins the other side.
    for (lonely, joins) in [(SECOND, FIRST), (FIRST, SECOND)] {
        for v in 0..n {
            if side[v] == SEPARATOR && !graph.of(v).iter().any(|&w| side[w as usize] == lonely) {
                side[v] = joins;
            }
        }
    }
    Some(side)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::linear_solver::tests::grid_laplacian;

    /// On an `nx x ny` grid of the 5-point stencil, the separator leaves no edge between the
    /// two sides, splits them within 40-60 %, and is no longer than a diagonal across the
    /// strip (the levels from a corner are anti-diagonals).
    #[test]
    fn the_separator_separates_a_long_grid_into_balanced_sides() {
        let (nx, ny) = (150, 30);
        let a = grid_laplacian(nx, ny, 0.0);
        let graph = Graph::new(a.symbolic());
        let side = bisect(&graph).expect("a long grid splits");
        let count = |s: u8| side.iter().filter(|&&x| x == s).count();
        let n = nx * ny;
        assert!(count(SEPARATOR) <= ny + 1, "separator {}", count(SEPARATOR));
        for s in [FIRST, SECOND] {
            assert!(count(s) * 5 >= n * 2 && count(s) * 5 <= n * 3, "side {s}: {}", count(s));
        }
        for v in 0..n {
            for &w in graph.of(v) {
                assert!(!(side[v] == FIRST && side[w as usize] == SECOND), "edge {v}-{w} across");
            }
        }
    }
}
