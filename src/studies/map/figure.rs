//! The phase diagram `map.png/svg`: one coloured cell per point by its regime, black lines
//! where the regime changes between neighbours, and the paper's parameter set marked. A map
//! with `--biaxial` draws in each cell the direction of the first wrinkles' crests under
//! biaxial compression.

use super::{First, MapPoint, MapReport, PostBuckling};
use crate::error::Result;
use crate::output::plot::{save_canvas, Canvas, FONT};
use crate::parameters::Parameters;
use crate::stability::Minimum;
use crate::studies::grid_chart::{grid_chart, plotted, plotted_edges};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::{Path, PathBuf};

/// The regimes, in legend order, with their colours.
const REGIMES: [(&str, RGBColor); 11] = [
    ("crease first", RGBColor(214, 39, 40)),
    ("wrinkle, stays periodic", RGBColor(158, 202, 225)),
    ("wrinkle -> period doubling", RGBColor(49, 130, 189)),
    ("wrinkle -> fold", RGBColor(44, 160, 44)),
    ("wrinkle -> creases", RGBColor(255, 152, 150)),
    ("wrinkle without a wavelength", RGBColor(200, 200, 200)),
    ("none in range", RGBColor(255, 255, 255)),
    ("undecided (crease search snapped)", RGBColor(120, 120, 120)),
    ("wrinkle -> unstable, unresolved", RGBColor(255, 221, 113)),
    ("too close to call (within its uncertainty)", RGBColor(148, 103, 189)),
    ("wrinkle, the nonlinear run failed (see notes)", RGBColor(140, 86, 75)),
];

/// The regime of a point (an index into [`REGIMES`]).
pub fn regime(point: &MapPoint) -> usize {
    match (point.first, point.becomes) {
        (First::Crease, _) => 0,
        (First::Wrinkle, Some(PostBuckling::Wrinkle)) => 1,
        (First::Wrinkle, Some(PostBuckling::PeriodDoubling)) => 2,
        (First::Wrinkle, Some(PostBuckling::Fold)) => 3,
        (First::Wrinkle, Some(PostBuckling::Crease)) => 4,
        (First::Wrinkle, None) if point.minimum == Some(Minimum::Interior) => 10,
        (First::Wrinkle, None) => 5,
        (First::None, _) => 6,
        (First::Undecided, _) => 7,
        (First::Wrinkle, Some(PostBuckling::Unresolved)) => 8,
        (First::TooCloseToCall, _) => 9,
    }
}

/// Writes `map.png` and `map.svg`.
pub fn phase_diagram(report: &MapReport, out: &Path) -> Result<Vec<PathBuf>> {
    save_canvas(&PhaseDiagram(report), (980, 620), out, "map")
}

struct PhaseDiagram<'a>(&'a MapReport);

impl Canvas for PhaseDiagram<'_> {
    fn render<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>) -> std::result::Result<(), String> {
        draw(root, self.0)
    }
}

fn draw<DB: DrawingBackend>(root: DrawingArea<DB, Shift>, report: &MapReport) -> std::result::Result<(), String> {
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    root.fill(&WHITE).map_err(err)?;
    let (xa, ya) = (&report.study.x, &report.study.y);
    let (xe, ye) = (plotted_edges(xa), plotted_edges(ya));
    let (x0, x1, y0, y1) = (xe[0], xe[xe.len() - 1], ye[0], ye[ye.len() - 1]);
    let (plot_area, legend_area) = root.split_horizontally(640);
    let mut chart = grid_chart(
        &plot_area,
        "Which instability comes first, and what the wrinkle becomes",
        (xa, ya),
    )?;
    let nx = xa.points;
    let regimes: Vec<usize> = report.points.iter().map(regime).collect();
    let mut legend = Vec::new();
    for (r, &(name, color)) in REGIMES.iter().enumerate() {
        let cells: Vec<_> = report
            .points
            .iter()
            .filter(|p| regimes[p.index] == r)
            .map(|p| Rectangle::new([(xe[p.ix], ye[p.iy]), (xe[p.ix + 1], ye[p.iy + 1])], color.filled()))
            .collect();
        if cells.is_empty() {
            continue;
        }
        chart.draw_series(cells).map_err(err)?;
        legend.push((name, color));
    }
    // Boundaries between cells of different regimes.
    let mut lines = Vec::new();
    for p in &report.points {
        let here = regimes[p.index];
        if p.ix + 1 < nx && regimes[p.index + 1] != here {
            lines.push(vec![(xe[p.ix + 1], ye[p.iy]), (xe[p.ix + 1], ye[p.iy + 1])]);
        }
        if p.iy + 1 < ya.points && regimes[p.index + nx] != here {
            lines.push(vec![(xe[p.ix], ye[p.iy + 1]), (xe[p.ix + 1], ye[p.iy + 1])]);
        }
    }
    chart
        .draw_series(lines.into_iter().map(|l| PathElement::new(l, BLACK.stroke_width(3))))
        .map_err(err)?;
    // The crests of the first wrinkles under biaxial compression: a segment at the angle
    // theta0 + 90 degrees from the horizontal (X of the surface to the right, Z upwards), a
    // ring where no direction is preferred.
    let crests = report.study.settings.biaxial.is_some();
    if crests {
        let (cell_w, cell_h) = (
            (chart.backend_coord(&(xe[1], ye[0])).0 - chart.backend_coord(&(xe[0], ye[0])).0).abs(),
            (chart.backend_coord(&(xe[0], ye[0])).1 - chart.backend_coord(&(xe[0], ye[1])).1).abs(),
        );
        let half = 0.38 * f64::from(cell_w.min(cell_h).max(6));
        for p in report.points.iter().filter(|p| p.d_wrinkle_biaxial.is_some()) {
            let centre = chart.backend_coord(&(0.5 * (xe[p.ix] + xe[p.ix + 1]), 0.5 * (ye[p.iy] + ye[p.iy + 1])));
            match p.theta0 {
                Some(theta0) => {
                    let crest = theta0 + std::f64::consts::FRAC_PI_2;
                    let (dx, dy) = ((half * crest.cos()) as i32, (half * crest.sin()) as i32);
                    root.draw(&PathElement::new(
                        vec![(centre.0 - dx, centre.1 + dy), (centre.0 + dx, centre.1 - dy)],
                        BLACK.stroke_width(2),
                    ))
                    .map_err(err)?;
                }
                None => root
                    .draw(&Circle::new(centre, (0.3 * half) as i32, BLACK.stroke_width(2)))
                    .map_err(err)?,
            }
        }
    }
    // The paper's point: Table 1's values of the two mapped parameters.
    let table1 = Parameters::default();
    let mut paper = false;
    if let (Ok(px), Ok(py)) = (table1.number(&xa.name), table1.number(&ya.name)) {
        let at = (plotted(xa, px), plotted(ya, py));
        if (x0..=x1).contains(&at.0) && (y0..=y1).contains(&at.1) {
            chart
                .draw_series(std::iter::once(Cross::new(at, 9, BLACK.stroke_width(3))))
                .map_err(err)?;
            paper = true;
        }
    }
    // The legend, beside the plot.
    let text = (FONT, 15).into_font().color(&BLACK);
    for (i, (name, color)) in legend.iter().enumerate() {
        let y = 60 + 28 * i as i32;
        legend_area
            .draw(&Rectangle::new([(10, y - 9), (30, y + 9)], color.filled()))
            .map_err(err)?;
        legend_area
            .draw(&Rectangle::new([(10, y - 9), (30, y + 9)], BLACK.stroke_width(1)))
            .map_err(err)?;
        legend_area
            .draw(&Text::new(*name, (38, y - 8), text.clone()))
            .map_err(err)?;
    }
    let mut rows = legend.len() as i32;
    if crests {
        let y = 60 + 28 * rows;
        legend_area
            .draw(&PathElement::new(vec![(12, y + 6), (28, y - 6)], BLACK.stroke_width(2)))
            .map_err(err)?;
        let biaxial = report.study.settings.biaxial.unwrap_or(0.0);
        legend_area
            .draw(&Text::new(
                format!("wrinkle crests, d_3 = {biaxial} d"),
                (38, y - 8),
                text.clone(),
            ))
            .map_err(err)?;
        legend_area
            .draw(&Text::new(
                "(X right, Z up; ring: any direction)",
                (38, y + 8),
                text.clone(),
            ))
            .map_err(err)?;
        rows += 1;
    }
    if paper {
        let y = 60 + 28 * rows + if crests { 10 } else { 0 };
        legend_area
            .draw(&Cross::new((20, y), 7, BLACK.stroke_width(3)))
            .map_err(err)?;
        legend_area
            .draw(&Text::new("paper (Table 1)", (38, y - 8), text.clone()))
            .map_err(err)?;
    }
    root.present().map_err(err)
}
