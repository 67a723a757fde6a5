//! The axes of a grid's figure (`map.png` of `map` and of a map of patterns): one cell around
//! each point of the two axes, in plotted coordinates (log10 of a log axis), with round ticks
//! (degrees for an angle) and the axes named.

use super::grid::{cell_edges, Axis};
use super::stability::parameter_scale;
use crate::output::plot::FONT;
use crate::output::ticks::{tick_label, AxisScale, RoundTicks};
use plotters::coord::Shift;
use plotters::prelude::*;

/// The coordinates of a grid's chart.
pub type GridCoordinates = Cartesian2d<RoundTicks, RoundTicks>;

/// A value of `axis` in plotted coordinates.
pub fn plotted(axis: &Axis, value: f64) -> f64 {
    if axis.log {
        value.log10()
    } else {
        value
    }
}

/// The cell edges along `axis`, in plotted coordinates.
pub fn plotted_edges(axis: &Axis) -> Vec<f64> {
    let values: Vec<f64> = axis.values().into_iter().map(|v| plotted(axis, v)).collect();
    cell_edges(&values)
}

fn scale(axis: &Axis) -> AxisScale {
    match axis.log {
        true => AxisScale::Log10,
        false => parameter_scale(&axis.name),
    }
}

fn axis_name(axis: &Axis) -> String {
    match scale(axis) {
        AxisScale::Log10 => format!("{} (log scale)", axis.name),
        AxisScale::Degrees => format!("{} (deg)", axis.name),
        AxisScale::Linear => axis.name.clone(),
    }
}

/// A chart on `area`, captioned, over the cells of `x` and `y`, its axes drawn.
pub fn grid_chart<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    caption: &str,
    (x, y): (&Axis, &Axis),
) -> std::result::Result<ChartContext<'a, DB, GridCoordinates>, String> {
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    let (xe, ye) = (plotted_edges(x), plotted_edges(y));
    let (x_scale, y_scale) = (scale(x), scale(y));
    let mut chart = ChartBuilder::on(area)
        .caption(caption, (FONT, 20))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(65)
        .build_cartesian_2d(
            RoundTicks::new(xe[0], xe[xe.len() - 1], x_scale),
            RoundTicks::new(ye[0], ye[ye.len() - 1], y_scale),
        )
        .map_err(err)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc(axis_name(x))
        .y_desc(axis_name(y))
        .x_label_formatter(&|v| tick_label(*v, x_scale))
        .y_label_formatter(&|v| tick_label(*v, y_scale))
        .label_style((FONT, 14))
        .axis_desc_style((FONT, 16))
        .draw()
        .map_err(err)?;
    Ok(chart)
}
