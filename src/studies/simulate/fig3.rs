//! Fig. 3: the amplitude `A(d)` with the paper's maximal-curvature onset (open circle and
//! vertical line), the steepest point's onset (dashed line and circle: the peak of `A'`, nearer
//! the theory where the imperfection rounds the curve early) and the linear theory's `d_c(k)`
//! (cross); beside it, on its own axis, the curvature of `A(d)` whose first peak is the paper's
//! onset rule. Under a growth load the abscissa is the
//! layer's growth `g = 1 / (1 - d)`.

use super::{Curve, OnsetReport};
use crate::output::{Figure, LineStyle, Series};
use crate::parameters::Load;
use crate::protocol::onset::curvature;

/// Fig. 3 of a run under `load`: `[A panel, curvature panel]`.
pub fn fig3(curve: &Curve, onset: &OnsetReport, load: Load) -> [Figure; 2] {
    let (d, a) = curve.points();
    let a_max = a.iter().fold(0.0f64, |m, &v| m.max(v));
    let (name, axis, against) = match load.is_growth() {
        true => ("g", "growth of the layer g", "growth"),
        false => ("d", "end-shortening d = 1 - lambda_1", "compression"),
    };
    // A strain `d` of the path as the abscissa.
    let x = |d: f64| load.parameter(d);
    let mut amplitude = Figure::new(
        format!("Fig. 3: amplitude against {against}, k H = {:.4}", onset.k),
        axis,
        "amplitude A / H",
    )
    .with(Series::new(
        format!("A({name}), computed"),
        d.iter().map(|&d| x(d)).zip(a.iter().copied()).collect(),
        LineStyle::DotsAndLine,
        0,
    ));
    let kappa = curvature(&d, &a);
    let top = kappa.iter().fold(0.0f64, |m, &(_, k)| m.max(k));
    let mut kappa_panel = Figure::new(
        format!("curvature of A({name}): the paper's onset rule"),
        axis,
        "kappa = A'' / (1 + A'^2)^(3/2)",
    )
    .with(Series::new(
        format!("kappa({name})"),
        kappa.into_iter().map(|(d, k)| (x(d), k)).collect(),
        LineStyle::Solid,
        1,
    ));
    // An onset estimate: a circle on A(d) and a vertical line through it.
    let mark = |figure: Figure, estimate: f64, rule: &str, line: LineStyle, colour: usize| {
        figure
            .with(Series::new(
                format!("{name}_c = {:.4} ({rule})", x(estimate)),
                vec![(x(estimate), interpolate(&d, &a, estimate))],
                LineStyle::Circles,
                colour,
            ))
            .with(Series::new(
                "",
                vec![(x(estimate), 0.0), (x(estimate), a_max)],
                line,
                colour,
            ))
    };
    if let Some(dc) = onset.estimates.d_max_curvature {
        amplitude = mark(amplitude, dc, "max curvature", LineStyle::Solid, 5);
        kappa_panel = kappa_panel.with(Series::new(
            format!("first peak, {name} = {:.4}", x(dc)),
            vec![(x(dc), 0.0), (x(dc), top)],
            LineStyle::Dashed,
            5,
        ));
    }
    if let Some(ds) = onset.estimates.d_steepest {
        amplitude = mark(amplitude, ds, "steepest A", LineStyle::Dashed, 2);
    }
    let theory = onset.d_linear_theory;
    amplitude = amplitude.with(Series::new(
        format!("linear theory {name}_c(k) = {:.4}", x(theory)),
        vec![(x(theory), interpolate(&d, &a, theory))],
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
