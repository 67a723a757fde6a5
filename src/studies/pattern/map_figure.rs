//! The figure of a map of patterns, `map.png/svg`: one cell per point coloured by the pattern
//! its state reached, in which the crests of its leading directions of wave vectors are drawn
//! (one segment per direction holding at least a fifth of the relief, X to the right and Z
//! upwards) beside the fibres' projection on the surface.

use super::map::PatternMapReport;
use crate::error::Result;
use crate::output::plot::{save_canvas, Canvas, FONT};
use crate::protocol::patch::{SurfacePattern, SECOND_DIRECTION};
use crate::studies::grid_chart::{grid_chart, plotted_edges};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::{Path, PathBuf};

/// The colours of the patterns, in legend order, and of a point without one.
const PATTERNS: [(SurfacePattern, &str, RGBColor); 4] = [
    (SurfacePattern::Flat, "flat", RGBColor(255, 255, 255)),
    (SurfacePattern::Stripes, "stripes", RGBColor(158, 202, 225)),
    (SurfacePattern::Checkerboard, "checkerboard", RGBColor(253, 174, 107)),
    (
        SurfacePattern::Mixed,
        "mixed (herringbone, labyrinth, ...)",
        RGBColor(161, 217, 155),
    ),
];
const NO_ANSWER: (&str, RGBColor) = ("no answer (see map.json)", RGBColor(170, 170, 170));
const FIBRES: RGBColor = RGBColor(214, 39, 40);

/// Writes `map.png` and `map.svg`.
pub fn pattern_map(report: &PatternMapReport, out: &Path) -> Result<Vec<PathBuf>> {
    save_canvas(&PatternMapFigure(report), (980, 620), out, "map")
}

struct PatternMapFigure<'a>(&'a PatternMapReport);

impl Canvas for PatternMapFigure<'_> {
    fn render<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>) -> std::result::Result<(), String> {
        draw(root, self.0)
    }
}

fn draw<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    report: &PatternMapReport,
) -> std::result::Result<(), String> {
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    root.fill(&WHITE).map_err(err)?;
    let (xa, ya) = (&report.map.x, &report.map.y);
    let (xe, ye) = (plotted_edges(xa), plotted_edges(ya));
    let (plot_area, legend_area) = root.split_horizontally(640);
    let caption = match report.map.study.path {
        Some(_) => "The pattern at the end of each point's path",
        None => "The pattern of each point's bifurcation mode",
    };
    let mut chart = grid_chart(&plot_area, caption, (xa, ya))?;
    let colour = |pattern: Option<SurfacePattern>| {
        PATTERNS
            .iter()
            .find(|(p, ..)| Some(*p) == pattern)
            .map_or(NO_ANSWER.1, |&(.., c)| c)
    };
    chart
        .draw_series(report.points.iter().map(|p| {
            Rectangle::new(
                [(xe[p.ix], ye[p.iy]), (xe[p.ix + 1], ye[p.iy + 1])],
                colour(p.pattern).filled(),
            )
        }))
        .map_err(err)?;
    chart
        .draw_series(report.points.iter().map(|p| {
            Rectangle::new(
                [(xe[p.ix], ye[p.iy]), (xe[p.ix + 1], ye[p.iy + 1])],
                BLACK.stroke_width(1),
            )
        }))
        .map_err(err)?;
    // In each cell: the crests (perpendicular to the wave vector at theta) of every direction
    // holding at least SECOND_DIRECTION of the relief, and the fibres' projection at psi.
    let pixel = |x: f64, y: f64| chart.backend_coord(&(x, y));
    for p in &report.points {
        let (corner, opposite) = (pixel(xe[p.ix], ye[p.iy]), pixel(xe[p.ix + 1], ye[p.iy + 1]));
        let centre = ((corner.0 + opposite.0) / 2, (corner.1 + opposite.1) / 2);
        let half = 0.36 * f64::from((opposite.0 - corner.0).abs().min((opposite.1 - corner.1).abs()).max(8));
        let segment = |angle: f64, length: f64| {
            let (dx, dy) = ((length * angle.cos()) as i32, (length * angle.sin()) as i32);
            vec![(centre.0 - dx, centre.1 + dy), (centre.0 + dx, centre.1 - dy)]
        };
        for direction in p.directions.iter().filter(|d| d.share >= SECOND_DIRECTION) {
            let crest = direction.wave.theta_degrees.to_radians() + std::f64::consts::FRAC_PI_2;
            root.draw(&PathElement::new(segment(crest, half), BLACK.stroke_width(3)))
                .map_err(err)?;
        }
        if p.parameters.fibre_projection().is_some() {
            root.draw(&PathElement::new(
                segment(p.parameters.psi, 0.6 * half),
                FIBRES.stroke_width(2),
            ))
            .map_err(err)?;
        }
    }
    // The legend, beside the plot.
    let text = (FONT, 15).into_font().color(&BLACK);
    let mut rows: Vec<(&str, RGBColor)> = PATTERNS
        .iter()
        .filter(|(pattern, ..)| report.points.iter().any(|p| p.pattern == Some(*pattern)))
        .map(|&(_, name, c)| (name, c))
        .collect();
    if report.points.iter().any(|p| p.pattern.is_none()) {
        rows.push(NO_ANSWER);
    }
    let mut y = 60;
    for (name, color) in rows {
        let square = [(10, y - 9), (30, y + 9)];
        legend_area.draw(&Rectangle::new(square, color.filled())).map_err(err)?;
        legend_area
            .draw(&Rectangle::new(square, BLACK.stroke_width(1)))
            .map_err(err)?;
        legend_area
            .draw(&Text::new(name, (38, y - 8), text.clone()))
            .map_err(err)?;
        y += 28;
    }
    let lines = [
        (BLACK, 3, "crests of a direction with >= 20 %"),
        (FIBRES, 2, "the fibres' projection"),
    ];
    for (color, width, name) in lines {
        legend_area
            .draw(&PathElement::new(vec![(10, y), (30, y)], color.stroke_width(width)))
            .map_err(err)?;
        legend_area
            .draw(&Text::new(name, (38, y - 8), text.clone()))
            .map_err(err)?;
        y += 28;
    }
    legend_area
        .draw(&Text::new("(X to the right, Z upwards)", (38, y - 8), text.clone()))
        .map_err(err)?;
    root.present().map_err(err)
}
