//! Onset of wrinkling read off a recorded amplitude curve `A(d)` (section 3.1, Fig. 3).
//!
//! Derivatives use the three-point formulas of a non-uniform grid. A "peak" is the first sample
//! that is the largest within [`PEAK_WINDOW`] on either side (so the onset's knee is found before
//! a later snap, where `A'` grows again), refined by the vertex of the parabola through it and
//! its two neighbours. Three estimates:
//! (a) the paper's rule, the maximum of `kappa = A'' / (1 + A'^2)^(3/2)` (it depends on the
//! relative scaling of `A` and `d`); (b) the steepest point, the maximum of `A'`; (c) where a
//! straight line fitted to `A^2` against `d` over [`A2_FIT_WINDOW`] past the steepest point
//! crosses zero (near onset `A^2 ~ c (d - d_c)`).

use serde::Serialize;

/// Width in `d` of the post-buckling range of the `A^2` fit, starting at the steepest point.
pub const A2_FIT_WINDOW: f64 = 0.02;

/// Half-width in `d` of the neighbourhood a peak must dominate.
pub const PEAK_WINDOW: f64 = 0.01;

/// The three estimates; `None` where the curve is too short or has no interior maximum.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct OnsetEstimates {
    pub d_max_curvature: Option<f64>,
    pub d_steepest: Option<f64>,
    pub d_a2_fit: Option<f64>,
}

/// Smallest range of `A` (in units of `H`) with an onset: below it the curve is flat up to
/// round-off (the perfect system on its homogeneous path).
pub const FLAT_RANGE: f64 = 1e-8;

impl OnsetEstimates {
    /// All three estimates from points `(d_i, A_i)` with increasing `d` (none for a flat curve).
    pub fn from_curve(d: &[f64], a: &[f64]) -> Self {
        let (low, high) = a.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        });
        if high - low <= FLAT_RANGE {
            return OnsetEstimates::default();
        }
        OnsetEstimates {
            d_max_curvature: max_curvature(d, a),
            d_steepest: steepest(d, a),
            d_a2_fit: a2_fit(d, a),
        }
    }
}

/// `(A', A'')` at each interior point `i = 1..n-1` (three-point, non-uniform spacing).
fn derivatives(d: &[f64], a: &[f64]) -> Vec<(f64, f64)> {
    assert_eq!(d.len(), a.len(), "one amplitude per d");
    (1..d.len().saturating_sub(1))
        .map(|i| {
            let (h1, h2) = (d[i] - d[i - 1], d[i + 1] - d[i]);
            let first =
                -h2 / (h1 * (h1 + h2)) * a[i - 1] + (h2 - h1) / (h1 * h2) * a[i] + h1 / (h2 * (h1 + h2)) * a[i + 1];
            let second = 2.0 * (a[i - 1] / (h1 * (h1 + h2)) - a[i] / (h1 * h2) + a[i + 1] / (h2 * (h1 + h2)));
            (first, second)
        })
        .collect()
}

/// `(d_i, kappa_i)` at the interior points.
pub fn curvature(d: &[f64], a: &[f64]) -> Vec<(f64, f64)> {
    derivatives(d, a)
        .into_iter()
        .enumerate()
        .map(|(i, (first, second))| (d[i + 1], second / (1.0 + first * first).powf(1.5)))
        .collect()
}

/// (a) The `d` of maximal curvature (its first peak).
pub fn max_curvature(d: &[f64], a: &[f64]) -> Option<f64> {
    refined_peak(&curvature(d, a))
}

/// (b) The `d` of the largest slope `A'` (its first peak).
pub fn steepest(d: &[f64], a: &[f64]) -> Option<f64> {
    let slopes: Vec<(f64, f64)> = derivatives(d, a)
        .into_iter()
        .enumerate()
        .map(|(i, (first, _))| (d[i + 1], first))
        .collect();
    refined_peak(&slopes)
}

/// (c) The zero of the least-squares line through `(d_i, A_i^2)` for `d_i` in
/// `[d_steepest, d_steepest + A2_FIT_WINDOW]` (at least three points), if it lies within the
/// recorded `d`: a zero outside (a curve that ends before its onset, whose steepest point is
/// a kink of the path) is no estimate.
pub fn a2_fit(d: &[f64], a: &[f64]) -> Option<f64> {
    let start = steepest(d, a)?;
    let points: Vec<(f64, f64)> = d
        .iter()
        .zip(a)
        .filter(|(&di, _)| di >= start && di <= start + A2_FIT_WINDOW)
        .map(|(&di, &ai)| (di, ai * ai))
        .collect();
    let (intercept, slope) = line_fit(&points)?;
    let zero = -intercept / slope;
    (slope > 0.0 && zero >= d[0] && zero <= d[d.len() - 1]).then_some(zero)
}

/// Least-squares `y = intercept + slope x`; `None` below three points or for a degenerate `x`.
fn line_fit(points: &[(f64, f64)]) -> Option<(f64, f64)> {
    if points.len() < 3 {
        return None;
    }
    let n = points.len() as f64;
    let mean_x = points.iter().map(|p| p.0).sum::<f64>() / n;
    let mean_y = points.iter().map(|p| p.1).sum::<f64>() / n;
    let sxx: f64 = points.iter().map(|p| (p.0 - mean_x).powi(2)).sum();
    let sxy: f64 = points.iter().map(|p| (p.0 - mean_x) * (p.1 - mean_y)).sum();
    if sxx <= 0.0 {
        return None;
    }
    let slope = sxy / sxx;
    Some((mean_y - slope * mean_x, slope))
}

/// The abscissa of the first interior sample that is the largest within [`PEAK_WINDOW`] (and
/// not on a plateau), refined
/// by the parabola through it and its neighbours (kept within them); `None` if there is none.
fn refined_peak(samples: &[(f64, f64)]) -> Option<f64> {
    // Largest in its window, and above the window's smallest value by more than round-off
    // (1e-6 of the whole range), so that a plateau is no peak.
    let (low, high) = samples.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), s| {
        (lo.min(s.1), hi.max(s.1))
    });
    let floor = 1e-6 * (high - low);
    let dominates = |i: usize| {
        let (x, y) = samples[i];
        let mut window = samples.iter().filter(|s| (s.0 - x).abs() <= PEAK_WINDOW);
        y.is_finite() && window.clone().all(|s| s.1 <= y) && window.any(|s| s.1 < y - floor)
    };
    let best = (1..samples.len().saturating_sub(1)).find(|&i| dominates(i))?;
    let [(x0, y0), (x1, y1), (x2, y2)] = [samples[best - 1], samples[best], samples[best + 1]];
    // Vertex of the interpolating parabola (divided differences).
    let (s01, s12) = ((y1 - y0) / (x1 - x0), (y2 - y1) / (x2 - x1));
    let c = (s12 - s01) / (x2 - x0);
    if c >= 0.0 {
        return Some(x1);
    }
    Some((0.5 * (x0 + x1) - s01 / (2.0 * c)).clamp(x0, x2))
}
