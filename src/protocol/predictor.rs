//! The predictor of a load step: Lagrange extrapolation in `d` through the last converged
//! states, or along a given slope from a single state.
//!
//! Through up to four states the predictor is the polynomial through all of them (cubic through
//! four). With a fifth, on a stretch of equal steps (none cut or grown between the five), the
//! order is chosen as a variable-order multistep integrator chooses its own: the change that
//! each added state makes to the prediction estimates the error of the lower order, and the
//! quartic is taken only where that change falls fast with the order,
//! `|P_5 - P_4| <= |P_4 - P_3| / 4` (the path is smooth on the scale of the steps). Elsewhere
//! (a fold, a trough closing, a damped stretch) a quartic through the same states extrapolates
//! their roughness further, and the cubic through the newest four is kept.

use std::collections::VecDeque;

/// Most converged states the predictor extrapolates through (quartic).
pub(super) const PREDICTOR_POINTS: usize = 5;

/// Factor by which the quartic's change must fall below the cubic's for the quartic to be taken.
const ORDER_DECREASE: f64 = 0.25;

/// The prediction at `d` from the converged `(d_i, u_i)` (oldest first): from a single state,
/// along `slope` if there is one; through up to four states, the polynomial through all of
/// them; through five, the quartic or the cubic as the module's doc says.
pub(super) fn extrapolate(history: &VecDeque<(f64, Vec<f64>)>, slope: Option<&[f64]>, d: f64) -> Vec<f64> {
    let (d0, u0) = history.back().expect("never empty");
    if let (Some(slope), 1) = (slope, history.len()) {
        return u0.iter().zip(slope).map(|(u, s)| u + (d - d0) * s).collect();
    }
    let n = history.len();
    if n < PREDICTOR_POINTS {
        return lagrange(history, n, d);
    }
    if !equally_spaced(history) {
        return lagrange(history, PREDICTOR_POINTS - 1, d);
    }
    let [quadratic, cubic, quartic] = [3, 4, 5].map(|points| lagrange(history, points, d));
    if distance(&quartic, &cubic) <= ORDER_DECREASE * distance(&cubic, &quadratic) {
        quartic
    } else {
        cubic
    }
}

/// Whether the states' `d` are equally spaced (to `1e-9` of the spacing): no step between them
/// was cut or grown.
fn equally_spaced(history: &VecDeque<(f64, Vec<f64>)>) -> bool {
    let spacing: Vec<f64> = history
        .iter()
        .zip(history.iter().skip(1))
        .map(|(a, b)| b.0 - a.0)
        .collect();
    spacing
        .iter()
        .all(|h| (h - spacing[0]).abs() <= 1e-9 * spacing[0].abs())
}

/// Lagrange extrapolation through the newest `points` of the converged states, at `d`.
fn lagrange(history: &VecDeque<(f64, Vec<f64>)>, points: usize, d: f64) -> Vec<f64> {
    let used: Vec<&(f64, Vec<f64>)> = history.iter().skip(history.len() - points).collect();
    let nodes: Vec<f64> = used.iter().map(|(di, _)| *di).collect();
    let mut u = vec![0.0; used[0].1.len()];
    for (i, (_, ui)) in used.iter().enumerate() {
        let weight: f64 = nodes
            .iter()
            .enumerate()
            .filter(|&(j, _)| j != i)
            .map(|(_, &dj)| (d - dj) / (nodes[i] - dj))
            .product();
        for (x, y) in u.iter_mut().zip(ui) {
            *x += weight * y;
        }
    }
    u
}

/// Euclidean distance between two vectors.
fn distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum::<f64>().sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A cubic path `u(d)` is extrapolated exactly from four or five states, however often the
    /// stored states have been replaced (the ring buffer wraps round), and the first slope is
    /// used from the first state only.
    #[test]
    fn extrapolation_is_exact_for_a_cubic_path() {
        let path = |d: f64| vec![1.0 + d - 2.0 * d * d + 3.0 * d * d * d, -d * d * d];
        let slope = [10.0, 10.0];
        let mut history = VecDeque::from([(0.0, path(0.0))]);
        assert_eq!(extrapolate(&history, Some(&slope), 0.1), vec![2.0, 1.0]);
        for n in 1..20 {
            let d = 0.005 * n as f64;
            history.push_back((d, path(d)));
            if history.len() > PREDICTOR_POINTS {
                history.pop_front();
            }
            if history.len() == PREDICTOR_POINTS {
                let next = d + 0.005;
                let predicted = extrapolate(&history, Some(&slope), next);
                for (p, e) in predicted.iter().zip(path(next)) {
                    assert!((p - e).abs() < 1e-12, "step {n}: {p} against {e}");
                }
            }
        }
    }

    /// On a smooth path (an exponential of scale 0.04 in `d`, as an amplitude past the onset)
    /// each added state changes the prediction about `h / 0.04 = 1/8` as much as the one
    /// before: the quartic is taken, and it is closer than the cubic.
    #[test]
    fn a_smooth_path_is_extrapolated_by_the_quartic() {
        let path = |d: f64| vec![(d / 0.04).exp(), 1.0 - d * d];
        let history: VecDeque<_> = (0..5).map(|n| (0.005 * n as f64, path(0.005 * n as f64))).collect();
        let next = 0.025;
        let predicted = extrapolate(&history, None, next);
        assert_eq!(predicted, lagrange(&history, 5, next));
        let error = |p: &[f64]| distance(p, &path(next));
        assert!(error(&predicted) < 0.5 * error(&lagrange(&history, 4, next)));
    }

    /// Where the newest state jumps off the others (a snap, a trough closing), a higher order
    /// extrapolates the jump further (quadratic 3, cubic 4, quartic 5): the differences do not
    /// fall, and the cubic is kept.
    #[test]
    fn a_path_that_jumps_is_extrapolated_by_the_cubic() {
        let history: VecDeque<_> = (0..5).map(|n| (n as f64, vec![f64::from(n == 4)])).collect();
        let at = |u: Vec<f64>| u[0];
        assert!((at(lagrange(&history, 3, 5.0)) - 3.0).abs() < 1e-12);
        assert!((at(lagrange(&history, 5, 5.0)) - 5.0).abs() < 1e-12);
        assert!((at(extrapolate(&history, None, 5.0)) - 4.0).abs() < 1e-12);
    }

    /// After a cut or a grown step among the five states the cubic through the newest four is
    /// taken, however smooth the path.
    #[test]
    fn unequal_steps_are_extrapolated_by_the_cubic() {
        let path = |d: f64| vec![(d / 0.04).exp()];
        let ds = [0.0, 0.005, 0.01, 0.01125, 0.0125];
        let history: VecDeque<_> = ds.iter().map(|&d| (d, path(d))).collect();
        assert_eq!(extrapolate(&history, None, 0.014), lagrange(&history, 4, 0.014));
        let uniform: VecDeque<_> = (0..5).map(|n| (0.00125 * n as f64, path(0.00125 * n as f64))).collect();
        assert_eq!(extrapolate(&uniform, None, 0.00625), lagrange(&uniform, 5, 0.00625));
    }
}
