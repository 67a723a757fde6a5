//! Points along an interval placed by a density (more points where it is larger): the
//! equidistribution `x_j = C^-1(j / n)` of the normalised cumulative density `C`.

/// Samples of the cumulative density per point placed (trapezoidal rule, then linear inversion).
const SAMPLES_PER_POINT: usize = 64;

/// `n + 1` points from 0 to `length` (both ends included, increasing) spaced inversely to the
/// positive `density`.
pub fn equidistribute(density: impl Fn(f64) -> f64, length: f64, n: usize) -> Vec<f64> {
    let samples = SAMPLES_PER_POINT * n.max(1);
    let h = length / samples as f64;
    let mut cumulative = vec![0.0; samples + 1];
    for i in 0..samples {
        let (a, b) = (density(i as f64 * h), density((i + 1) as f64 * h));
        cumulative[i + 1] = cumulative[i] + 0.5 * h * (a + b);
    }
    let total = cumulative[samples];
    let mut points = Vec::with_capacity(n + 1);
    let mut i = 0;
    for j in 0..=n {
        let target = total * j as f64 / n as f64;
        while i + 1 < samples && cumulative[i + 1] < target {
            i += 1;
        }
        let fraction = (target - cumulative[i]) / (cumulative[i + 1] - cumulative[i]);
        points.push(((i as f64 + fraction.clamp(0.0, 1.0)) * h).min(length));
    }
    points[0] = 0.0;
    points[n] = length;
    points
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uniform_density_gives_uniform_points_and_steep_density_packs_them() {
        let uniform = equidistribute(|_| 2.0, 10.0, 5);
        for (j, x) in uniform.iter().enumerate() {
            assert!((x - 2.0 * j as f64).abs() < 1e-12, "{uniform:?}");
        }
        let packed = equidistribute(|x| if x < 1.0 { 4.0 } else { 1.0 }, 4.0, 14);
        // C(1) = 4 of a total 7: points 0..=8 lie in [0, 1], spaced 1/8.
        assert!((packed[8] - 1.0).abs() < 5e-3, "{packed:?}");
        assert!((packed[4] - 0.5).abs() < 5e-3 && (packed[11] - 2.5).abs() < 5e-3);
    }
}
