//! Geometrically graded element sizes (substrate meshes in `Y`).

/// Growth ratio `r` with `first (1 + r + ... + r^(n-1)) = total`, by bisection.
pub fn geometric_ratio(first: f64, total: f64, n: usize) -> f64 {
    let sum = |r: f64| first * (0..n).map(|k| r.powi(k as i32)).sum::<f64>();
    if n <= 1 || (n as f64 * first - total).abs() <= 1e-14 * total {
        return 1.0;
    }
    // sum(r) grows with r; the root lies in (0, 1) when n first > total, else in
    // (1, (total/first)^(1/(n-1))].
    let (mut lower, mut upper) = if n as f64 * first > total {
        (0.0, 1.0)
    } else {
        (1.0, (total / first).powf(1.0 / (n - 1) as f64))
    };
    while upper - lower > 4.0 * f64::EPSILON * upper {
        let middle = 0.5 * (lower + upper);
        if sum(middle) < total {
            lower = middle;
        } else {
            upper = middle;
        }
    }
    0.5 * (lower + upper)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_sum_to_the_total() {
        for (first, total, n) in [(0.5, 50.0, 25), (0.25, 50.0, 45), (3.0, 10.0, 5), (1.0, 4.0, 4)] {
            let r = geometric_ratio(first, total, n);
            let sum: f64 = (0..n).map(|k| first * r.powi(k as i32)).sum();
            assert!((sum - total).abs() < 1e-12 * total, "{first} {total} {n}: {sum}");
        }
    }
}
