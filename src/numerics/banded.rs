//! Symmetric banded matrices and their LDL^T factorisation without pivoting, whose pivot signs
//! give the inertia (Sylvester's law of inertia).

/// A symmetric matrix stored by its lower band: `band[i][j]` holds `A[i][i - j]`, `j <= width`.
#[derive(Clone, Debug)]
pub struct SymmetricBanded {
    n: usize,
    width: usize,
    band: Vec<f64>,
}

impl SymmetricBanded {
    pub fn zeros(n: usize, width: usize) -> Self {
        SymmetricBanded {
            n,
            width,
            band: vec![0.0; n * (width + 1)],
        }
    }

    /// Adds `value` to `A[i][j]` (and so to `A[j][i]`); `|i - j| <= width`.
    pub fn add(&mut self, i: usize, j: usize, value: f64) {
        let (row, col) = if i >= j { (i, j) } else { (j, i) };
        assert!(row - col <= self.width, "entry ({i}, {j}) outside the band");
        self.band[row * (self.width + 1) + (row - col)] += value;
    }

    fn get(&self, row: usize, col: usize) -> f64 {
        self.band[row * (self.width + 1) + (row - col)]
    }

    /// Removes row and column `i` by replacing them with the identity (a Dirichlet condition).
    pub fn constrain(&mut self, i: usize) {
        for col in i.saturating_sub(self.width)..i {
            self.band[i * (self.width + 1) + (i - col)] = 0.0;
        }
        for row in i + 1..(i + self.width + 1).min(self.n) {
            self.band[row * (self.width + 1) + (row - i)] = 0.0;
        }
        self.band[i * (self.width + 1)] = 1.0;
    }

    /// Number of negative eigenvalues, from the pivots of `A = L D L^T`. `None` if a pivot is
    /// exactly zero (the matrix is singular to working precision).
    pub fn negative_eigenvalues(&self) -> Option<usize> {
        let w = self.width;
        // l[i][j] = L[i][i - j] for j in 1..=w; d[i] = D[i].
        let mut l = vec![0.0; self.n * (w + 1)];
        let mut d = vec![0.0; self.n];
        let mut negative = 0;
        for i in 0..self.n {
            for col in i.saturating_sub(w)..i {
                let mut sum = self.get(i, col);
                for m in i.saturating_sub(w).max(col.saturating_sub(w))..col {
                    sum -= l[i * (w + 1) + (i - m)] * l[col * (w + 1) + (col - m)] * d[m];
                }
                l[i * (w + 1) + (i - col)] = sum / d[col];
            }
            let mut pivot = self.get(i, i);
            for m in i.saturating_sub(w)..i {
                let lim = l[i * (w + 1) + (i - m)];
                pivot -= lim * lim * d[m];
            }
            if pivot == 0.0 || !pivot.is_finite() {
                return None;
            }
            negative += usize::from(pivot < 0.0);
            d[i] = pivot;
        }
        Some(negative)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inertia_of_shifted_second_difference_matrix() {
        // Eigenvalues of tridiag(-1, 2, -1) of size n are 2 - 2 cos(j pi / (n + 1)).
        let n = 50;
        for shift in [0.1, 1.1, 2.5, 3.9] {
            let mut a = SymmetricBanded::zeros(n, 2);
            for i in 0..n {
                a.add(i, i, 2.0 - shift);
                if i > 0 {
                    a.add(i, i - 1, -1.0);
                }
            }
            let expected = (1..=n)
                .filter(|&j| 2.0 - 2.0 * (j as f64 * std::f64::consts::PI / (n + 1) as f64).cos() < shift)
                .count();
            assert_eq!(a.negative_eigenvalues(), Some(expected), "shift {shift}");
        }
    }
}
