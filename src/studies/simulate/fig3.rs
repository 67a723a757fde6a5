//! Fig. 3: the amplitude `A(d)` with the maximal-curvature onset (open circle and vertical line)
//! and the linear theory's `d_c(k)` (cross); beside it, on its own axis, the curvature of `A(d)`
//! whose first peak is the paper's onset rule.

use super::{Curve, OnsetReport};
use crate::output::{Figure, LineStyle, Series};
use crate::protocol::onset::curvature;

/// Fig. 3 of a run: `[A(d) panel, curvature panel]`.
pub fn fig3(curve: &Curve, onset: &OnsetReport) -> [Figure; 2] {
    let (d, a) = curve.points();
    let a_max = a.iter().fold(0.0f64, |m, &v| m.max(v));
    let mut amplitude = Figure::new(
        format!("Fig. 3: amplitude against compression, k H = {:.4}", onset.k),
        "end-shortening d = 1 - lambda_1",
        "amplitude A / H",
    )
    .with(Series::new(
        "A(d), computed",
        d.iter().copied().zip(a.iter().copied()).collect(),
        LineStyle::DotsAndLine,
        0,
    ));
    let mut kappa_panel = Figure::new(
        "curvature of A(d): the paper's onset rule",
        "end-shortening d = 1 - lambda_1",
        "kappa = A'' / (1 + A'^2)^(3/2)",
    )
    .with(Series::new("kappa(d)", curvature(&d, &a), LineStyle::Solid, 1));
    if let Some(dc) = onset.estimates.d_max_curvature {
        amplitude = amplitude
            .with(Series::new(
                format!("d_c = {dc:.4} (max curvature)"),
                vec![(dc, interpolate(&d, &a, dc))],
                LineStyle::Circles,
                5,
            ))
            .with(Series::new("", vec![(dc, 0.0), (dc, a_max)], LineStyle::Solid, 5));
        let peak = curvature(&d, &a);
        let top = peak.iter().fold(0.0f64, |m, &(_, k)| m.max(k));
        kappa_panel = kappa_panel.with(Series::new(
            format!("first peak, d = {dc:.4}"),
            vec![(dc, 0.0), (dc, top)],
            LineStyle::Dashed,
            5,
        ));
    }
    let theory = onset.d_linear_theory;
    amplitude = amplitude.with(Series::new(
        format!("linear theory d_c(k) = {theory:.4}"),
        vec![(theory, interpolate(&d, &a, theory))],
        LineStyle::Crosses,
        3,
    ));
    [amplitude, kappa_panel]
}

/// Piecewise-linear `A(x)`, held constant beyond the ends.
fn interpolate(d: &[f64], a: &[f64], x: f64) -> f64 {
    match d.iter().position(|&di| di >= x) {
        None => *a.last().unwrap_or(&0.0),
        Some(0) => a[0],
        Some(i) => a[i - 1] + (a[i] - a[i - 1]) * (x - d[i - 1]) / (d[i] - d[i - 1]),
    }
}
