//! The crease threshold converged in the mesh: the same fold on a sequence of meshes, the base
//! mesh with its element counts multiplied by 1, 2, 3, ..., and Richardson's extrapolation of
//! the thresholds with the order the last three of them show.
//!
//! With mesh sizes `h_1 > h_2 > h_3` (here `h_s = 1 / s`) and thresholds `d_1, d_2, d_3`, the
//! observed order `p` solves `(d_1 - d_2) / (d_2 - d_3) = (h_1^p - h_2^p) / (h_2^p - h_3^p)`,
//! and the extrapolated threshold is `d_* = d_3 - (d_2 - d_3) h_3^p / (h_2^p - h_3^p)`. Its
//! uncertainty is Roache's grid-convergence index of the finest mesh, `1.25 |d_* - d_3|`
//! (Roache 1994, J. Fluids Eng. 116, 405). Where the last three do not converge monotonically
//! no order is defined: the finest threshold is reported with the larger of the last two changes
//! as its uncertainty; with two meshes, the change between them.

use serde::Serialize;

/// Roache's factor of safety for an order observed on three meshes.
pub const SAFETY_FACTOR: f64 = 1.25;

/// Orders searched for the observed one.
const ORDERS: (f64, f64) = (0.05, 12.0);

/// A threshold converged in the mesh, from the finest thresholds of a sequence.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Extrapolated {
    /// The extrapolated threshold (the finest one where no order is observed).
    pub value: f64,
    /// Its uncertainty (None from a single mesh).
    pub error: Option<f64>,
    /// The order of convergence observed on the last three meshes.
    pub order: Option<f64>,
}

/// Extrapolates `values[i]` computed on meshes of size `sizes[i]` (decreasing) to size 0.
pub fn extrapolate(sizes: &[f64], values: &[f64]) -> Option<Extrapolated> {
    let n = values.len().min(sizes.len());
    let finest = *values.get(n.checked_sub(1)?)?;
    if n == 1 {
        return Some(Extrapolated {
            value: finest,
            error: None,
            order: None,
        });
    }
    let change = finest - values[n - 2];
    if n == 2 {
        return Some(Extrapolated {
            value: finest,
            error: Some(change.abs()),
            order: None,
        });
    }
    let (h1, h2, h3) = (sizes[n - 3], sizes[n - 2], sizes[n - 1]);
    let (e12, e23) = (values[n - 3] - values[n - 2], -change);
    let unordered = Extrapolated {
        value: finest,
        error: Some(e12.abs().max(e23.abs())),
        order: None,
    };
    if e23 == 0.0 {
        return Some(Extrapolated {
            error: Some(0.0),
            ..unordered
        });
    }
    let ratio = e12 / e23;
    let model = |p: f64| (h1.powf(p) - h2.powf(p)) / (h2.powf(p) - h3.powf(p));
    if !(ratio > model(ORDERS.0) && ratio < model(ORDERS.1)) {
        return Some(unordered);
    }
    let (mut lo, mut hi) = ORDERS;
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if model(mid) < ratio {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let p = 0.5 * (lo + hi);
    let value = finest - e23 * h3.powf(p) / (h2.powf(p) - h3.powf(p));
    Some(Extrapolated {
        value,
        error: Some(SAFETY_FACTOR * (value - finest).abs()),
        order: Some(p),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_sequence_converging_with_a_known_order_extrapolates_to_its_limit() {
        for p in [0.7, 1.0, 1.7, 2.0, 3.0] {
            let sizes = [1.0, 0.5, 1.0 / 3.0, 0.25];
            let values: Vec<f64> = sizes.iter().map(|h: &f64| 0.2285 + 0.004 * h.powf(p)).collect();
            let e = extrapolate(&sizes, &values).unwrap();
            assert!((e.order.unwrap() - p).abs() < 1e-9, "{p}: {e:?}");
            assert!((e.value - 0.2285).abs() < 1e-12, "{p}: {e:?}");
            let expected = SAFETY_FACTOR * 0.004 * 0.25f64.powf(p);
            assert!((e.error.unwrap() - expected).abs() < 1e-12, "{p}: {e:?}");
        }
    }

    #[test]
    fn a_sequence_that_does_not_converge_monotonically_has_no_order() {
        let e = extrapolate(&[1.0, 0.5, 0.25], &[0.230, 0.229, 0.2295]).unwrap();
        assert_eq!(e.order, None);
        assert_eq!(e.value, 0.2295);
        assert!((e.error.unwrap() - 1e-3).abs() < 1e-15);
        // Changes that grow: diverging, no order either.
        let e = extrapolate(&[1.0, 0.5, 0.25], &[0.230, 0.229, 0.226]).unwrap();
        assert_eq!(e.order, None);
        let two = extrapolate(&[1.0, 0.5], &[0.230, 0.229]).unwrap();
        assert_eq!((two.value, two.order), (0.229, None));
        assert!((two.error.unwrap() - 1e-3).abs() < 1e-15);
        assert_eq!(extrapolate(&[1.0], &[0.23]).unwrap().error, None);
        assert_eq!(extrapolate(&[], &[]), None);
    }
}
