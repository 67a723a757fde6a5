//! The predictor of a load step: Lagrange extrapolation in `d` through the last converged
//! states (cubic through four), or along a given slope from a single state.

use std::collections::VecDeque;

/// How many converged states the predictor extrapolates through (cubic).
pub(super) const PREDICTOR_POINTS: usize = 4;

/// Lagrange extrapolation through the converged `(d_i, u_i)`, evaluated at `d`; from a single
/// state, along `slope` if there is one.
pub(super) fn extrapolate(history: &VecDeque<(f64, Vec<f64>)>, slope: Option<&[f64]>, d: f64) -> Vec<f64> {
    let (d0, u0) = history.back().expect("never empty");
    if let (Some(slope), 1) = (slope, history.len()) {
        return u0.iter().zip(slope).map(|(u, s)| u + (d - d0) * s).collect();
    }
    let nodes: Vec<f64> = history.iter().map(|(di, _)| *di).collect();
    let mut u = vec![0.0; u0.len()];
    for (i, (_, ui)) in history.iter().enumerate() {
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A cubic path `u(d)` is extrapolated exactly from four states, however often the stored
    /// states have been replaced (the ring buffer wraps round), and the first slope is used from
    /// the first state only.
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
}
