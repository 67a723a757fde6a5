//! Fig. 3: the amplitude `A(d)` with its curvature, the maximal-curvature onset (open circle and
//! vertical line) and the linear theory's `d_c(k)` (cross).

use super::{Curve, OnsetReport};
use crate::output::{Figure, LineStyle, Series};
use crate::protocol::onset::curvature;

/// Fig. 3 of a run; `kappa` is drawn dashed, scaled so that its largest `|kappa|` equals the largest `A`.
pub fn fig3(curve: &Curve, onset: &OnsetReport) -> Figure {
    let (d, a) = curve.points();
    let a_max = a.iter().fold(0.0f64, |m, &v| m.max(v));
    let kappa = curvature(&d, &a);
    let kappa_max = kappa.iter().fold(0.0f64, |m, &(_, v)| m.max(v.abs()));
    let scale = if kappa_max > 0.0 { a_max / kappa_max } else { 0.0 };
    let mut figure = Figure::new(
        format!("Fig. 3: amplitude against compression, k = {:.4}", onset.k),
        "end-shortening d",
        "amplitude A (kappa scaled)",
    )
    .with(Series::new(
        "A(d), computed",
        d.iter().copied().zip(a.iter().copied()).collect(),
        LineStyle::DotsAndLine,
        0,
    ))
    .with(Series::new(
        format!("curvature kappa (x {scale:.3e})"),
        kappa.iter().map(|&(x, k)| (x, k * scale)).collect(),
        LineStyle::Dashed,
        1,
    ));
    if let Some(dc) = onset.estimates.d_max_curvature {
        figure = figure
            .with(Series::new(
                format!("d_c = {dc:.4} (max curvature)"),
                vec![(dc, interpolate(&d, &a, dc))],
                LineStyle::Circles,
                5,
            ))
            .with(Series::new("", vec![(dc, 0.0), (dc, a_max)], LineStyle::Solid, 5));
    }
    let theory = onset.d_linear_theory;
    figure.with(Series::new(
        format!("linear theory d_c(k) = {theory:.4}"),
        vec![(theory, interpolate(&d, &a, theory))],
        LineStyle::Crosses,
        3,
    ))
}

/// Piecewise-linear `A(x)`, held constant beyond the ends.
fn interpolate(d: &[f64], a: &[f64], x: f64) -> f64 {
    match d.iter().position(|&di| di >= x) {
        None => *a.last().unwrap_or(&0.0),
        Some(0) => a[0],
        Some(i) => a[i - 1] + (a[i] - a[i - 1]) * (x - d[i - 1]) / (d[i] - d[i - 1]),
    }
}
