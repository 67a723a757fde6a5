//! Line plots rendered to PNG and SVG with an embedded font (no fontconfig, no system fonts).

use super::atomic::write_atomically;
use super::ticks::{tick_label, AxisScale, RoundTicks};
use crate::error::{Error, Result};
use plotters::coord::Shift;
use plotters::element::{Drawable, PointCollection};
use plotters::prelude::*;
use plotters_backend::{BackendCoord, DrawingErrorKind};
use std::path::{Path, PathBuf};
use std::sync::Once;

pub(crate) const FONT: &str = "sans-serif";
static REGISTER_FONT: Once = Once::new();

pub(crate) fn register_font() {
    REGISTER_FONT.call_once(|| {
        let bytes: &'static [u8] = include_bytes!("../../assets/DejaVuSans.ttf");
        plotters::style::register_font(FONT, FontStyle::Normal, bytes)
            .unwrap_or_else(|_| panic!("the embedded DejaVuSans.ttf is a valid font"));
    });
}

/// How a series is drawn.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LineStyle {
    Solid,
    Dashed,
    /// Open circles, no line.
    Circles,
    /// Crosses, no line.
    Crosses,
    /// Filled dots joined by a line.
    DotsAndLine,
}

/// One curve of a figure.
#[derive(Clone, Debug)]
pub struct Series {
    pub label: String,
    pub points: Vec<(f64, f64)>,
    pub style: LineStyle,
    /// Index into the palette; series with the same index share a colour.
    pub color: usize,
}

impl Series {
    pub fn new(label: impl Into<String>, points: Vec<(f64, f64)>, style: LineStyle, color: usize) -> Self {
        Series {
            label: label.into(),
            points,
            style,
            color,
        }
    }
}

/// One panel: axes, labels and curves.
#[derive(Clone, Debug, Default)]
pub struct Figure {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub series: Vec<Series>,
    /// Fixed axis ranges; `None` fits the data with a margin.
    pub x_range: Option<(f64, f64)>,
    pub y_range: Option<(f64, f64)>,
    /// Where the legend goes (default: upper right).
    pub legend: Legend,
    /// How the x axis shows its values (ticks at round values in any case).
    pub x_scale: AxisScale,
}

/// Legend corner.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Legend {
    /// The corner whose part of the plot holds the fewest points (`Figure::emptiest_corner`).
    #[default]
    Emptiest,
    UpperRight,
    UpperLeft,
    LowerRight,
    LowerLeft,
}

const PALETTE: [RGBColor; 6] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(0, 0, 0),
];

impl Figure {
    pub fn new(title: impl Into<String>, x_label: impl Into<String>, y_label: impl Into<String>) -> Self {
        Figure {
            title: title.into(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            ..Default::default()
        }
    }

    /// The same figure showing its x values on `scale` (e.g. angles in degrees).
    pub fn with_x_scale(mut self, scale: AxisScale) -> Self {
        self.x_scale = scale;
        self
    }

    pub fn with_legend(mut self, legend: Legend) -> Self {
        self.legend = legend;
        self
    }

    pub fn with(mut self, series: Series) -> Self {
        self.series.push(series);
        self
    }

    fn range(&self, pick: impl Fn(&(f64, f64)) -> f64, fixed: Option<(f64, f64)>) -> (f64, f64) {
        if let Some(r) = fixed {
            return r;
        }
        let values = self
            .series
            .iter()
            .flat_map(|s| s.points.iter().map(&pick))
            .filter(|v| v.is_finite());
        let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| (lo.min(v), hi.max(v)));
        if !lo.is_finite() {
            return (0.0, 1.0);
        }
        let margin = if hi > lo {
            0.05 * (hi - lo)
        } else {
            0.05 * lo.abs().max(1.0)
        };
        (lo - margin, hi + margin)
    }

    /// The corner of the plot `[x0, x1] x [y0, y1]` whose box of 45 % of the width by 35 % of the
    /// height holds the fewest points of the series (upper right first among equals): where a
    /// legend covers the least data. A line counts by points along it, 20 to a segment, so that
    /// a straight line of two points weighs as much as a curve.
    fn emptiest_corner(&self, (x0, x1): (f64, f64), (y0, y1): (f64, f64)) -> SeriesLabelPosition {
        let (w, h) = (0.45 * (x1 - x0), 0.35 * (y1 - y0));
        let along: Vec<(f64, f64)> = self
            .series
            .iter()
            .flat_map(|s| match s.style {
                LineStyle::Circles | LineStyle::Crosses => s.points.clone(),
                _ => s
                    .points
                    .windows(2)
                    .flat_map(|pair| {
                        let ((ax, ay), (bx, by)) = (pair[0], pair[1]);
                        (0..20).map(move |i| {
                            let t = i as f64 / 20.0;
                            (ax + t * (bx - ax), ay + t * (by - ay))
                        })
                    })
                    .chain(s.points.last().copied())
                    .collect(),
            })
            .collect();
        let inside = |right: bool, upper: bool| {
            let xs = if right { (x1 - w)..=x1 } else { x0..=(x0 + w) };
            let ys = if upper { (y1 - h)..=y1 } else { y0..=(y0 + h) };
            along.iter().filter(|(x, y)| xs.contains(x) && ys.contains(y)).count()
        };
        [
            (SeriesLabelPosition::UpperRight, inside(true, true)),
            (SeriesLabelPosition::UpperLeft, inside(false, true)),
            (SeriesLabelPosition::LowerRight, inside(true, false)),
            (SeriesLabelPosition::LowerLeft, inside(false, false)),
        ]
        .into_iter()
        .min_by_key(|(_, count)| *count)
        .map(|(corner, _)| corner)
        .expect("four corners")
    }

    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> std::result::Result<(), String> {
        let (x0, x1) = self.range(|p| p.0, self.x_range);
        let (y0, y1) = self.range(|p| p.1, self.y_range);
        let mut chart = ChartBuilder::on(area)
            .caption(&self.title, (FONT, 20))
            .margin(12)
            .x_label_area_size(45)
            .y_label_area_size(65)
            .build_cartesian_2d(
                RoundTicks::new(x0, x1, self.x_scale),
                RoundTicks::new(y0, y1, AxisScale::Linear),
            )
            .map_err(|e| e.to_string())?;
        let x_scale = self.x_scale;
        chart
            .configure_mesh()
            .x_label_formatter(&|v| tick_label(*v, x_scale))
            .y_label_formatter(&|v| tick_label(*v, AxisScale::Linear))
            .x_desc(&self.x_label)
            .y_desc(&self.y_label)
            .label_style((FONT, 14))
            .axis_desc_style((FONT, 16))
            .light_line_style(WHITE.mix(0.0))
            .draw()
            .map_err(|e| e.to_string())?;
        let (x_box, y_box) = ((x0, x1), (y0, y1));
        for s in &self.series {
            let color = PALETTE[s.color % PALETTE.len()];
            let line = color.stroke_width(2);
            // Every curve is clipped to the axes, and broken where a value is missing (a point
            // with a non-finite coordinate).
            let runs: Vec<Vec<(f64, f64)>> = s
                .points
                .split(|(x, y)| !(x.is_finite() && y.is_finite()))
                .flat_map(|run| clip_polyline(run, x_box, y_box))
                .collect();
            let marks = || s.points.iter().copied().filter(|&p| in_box(p, x_box, y_box));
            match s.style {
                // Cut at sharp turns: a wide polyline's mitred corners spike there.
                LineStyle::Solid | LineStyle::DotsAndLine => {
                    let pieces = runs.iter().flat_map(|run| split_at_sharp_turns(run, x_box, y_box));
                    chart
                        .draw_series(pieces.map(|piece| PathElement::new(piece, line)))
                        .map_err(|e| e.to_string())?;
                }
                LineStyle::Dashed => {
                    for run in &runs {
                        chart
                            .draw_series(DashedLineSeries::new(run.iter().copied(), 8, 5, line))
                            .map_err(|e| e.to_string())?;
                    }
                }
                LineStyle::Circles | LineStyle::Crosses => {}
            }
            let e = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
            match s.style {
                LineStyle::Circles => {
                    chart
                        .draw_series(marks().map(|p| Circle::new(p, 5, color.stroke_width(2))))
                        .map_err(e)?;
                }
                LineStyle::Crosses => {
                    chart
                        .draw_series(marks().map(|p| Cross::new(p, 7, color.stroke_width(3))))
                        .map_err(e)?;
                }
                LineStyle::DotsAndLine => {
                    chart
                        .draw_series(marks().map(|p| Circle::new(p, 3, color.filled())))
                        .map_err(e)?;
                }
                LineStyle::Solid | LineStyle::Dashed => {}
            }
            if !s.label.is_empty() {
                // The legend shows exactly the mark and line the series is drawn with.
                let style = s.style;
                chart
                    .draw_series(std::iter::empty::<PathElement<(f64, f64)>>())
                    .map_err(|e| e.to_string())?
                    .label(&s.label)
                    .legend(move |(x, y)| {
                        LegendGlyph {
                            at: (x, y),
                            style,
                            color,
                        }
                        .into_dyn()
                    });
            }
        }
        if self.series.iter().any(|s| !s.label.is_empty()) {
            chart
                .configure_series_labels()
                .label_font((FONT, 14))
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK)
                .position(match self.legend {
                    Legend::Emptiest => self.emptiest_corner((x0, x1), (y0, y1)),
                    Legend::UpperRight => SeriesLabelPosition::UpperRight,
                    Legend::UpperLeft => SeriesLabelPosition::UpperLeft,
                    Legend::LowerRight => SeriesLabelPosition::LowerRight,
                    Legend::LowerLeft => SeriesLabelPosition::LowerLeft,
                })
                .draw()
                .map_err(|e| e.to_string())?;
        }
        Ok(())
    }
}

/// Whether `(x, y)` lies in the box `[x0, x1] x [y0, y1]`.
fn in_box((x, y): (f64, f64), (x0, x1): (f64, f64), (y0, y1): (f64, f64)) -> bool {
    (x0..=x1).contains(&x) && (y0..=y1).contains(&y)
}

/// The parts of the polyline `points` inside the box `[x0, x1] x [y0, y1]`, each a polyline cut
/// where it leaves the box (Liang and Barsky's clipping of each segment).
fn clip_polyline(points: &[(f64, f64)], (x0, x1): (f64, f64), (y0, y1): (f64, f64)) -> Vec<Vec<(f64, f64)>> {
    let mut runs: Vec<Vec<(f64, f64)>> = Vec::new();
    let mut current: Vec<(f64, f64)> = Vec::new();
    let clip = |(ax, ay): (f64, f64), (bx, by): (f64, f64)| -> Option<((f64, f64), (f64, f64))> {
        let (dx, dy) = (bx - ax, by - ay);
        let (mut t0, mut t1) = (0.0f64, 1.0f64);
        for (p, q) in [(-dx, ax - x0), (dx, x1 - ax), (-dy, ay - y0), (dy, y1 - ay)] {
            if p == 0.0 {
                if q < 0.0 {
                    return None;
                }
            } else if p < 0.0 {
                t0 = t0.max(q / p);
            } else {
                t1 = t1.min(q / p);
            }
        }
        (t0 <= t1).then_some(((ax + t0 * dx, ay + t0 * dy), (ax + t1 * dx, ay + t1 * dy)))
    };
    if let [only] = points {
        return match in_box(*only, (x0, x1), (y0, y1)) {
            true => vec![vec![*only]],
            false => Vec::new(),
        };
    }
    for pair in points.windows(2) {
        match clip(pair[0], pair[1]) {
            Some((start, end)) => {
                if current.last() != Some(&start) {
                    if current.len() > 1 {
                        runs.push(std::mem::take(&mut current));
                    }
                    current = vec![start];
                }
                current.push(end);
            }
            None => {
                if current.len() > 1 {
                    runs.push(std::mem::take(&mut current));
                }
                current.clear();
            }
        }
    }
    if current.len() > 1 {
        runs.push(current);
    }
    runs
}

/// `run` cut into polylines at its turns sharper than a right angle (on the axes' scales),
/// each piece sharing its end with the next.
fn split_at_sharp_turns(run: &[(f64, f64)], (x0, x1): (f64, f64), (y0, y1): (f64, f64)) -> Vec<Vec<(f64, f64)>> {
    let scaled = |(x, y): (f64, f64)| ((x - x0) / (x1 - x0), (y - y0) / (y1 - y0));
    let mut pieces = Vec::new();
    let mut piece = run.first().map(|&p| vec![p]).unwrap_or_default();
    for window in run.windows(3) {
        let (a, b, c) = (scaled(window[0]), scaled(window[1]), scaled(window[2]));
        piece.push(window[1]);
        if (b.0 - a.0) * (c.0 - b.0) + (b.1 - a.1) * (c.1 - b.1) < 0.0 {
            pieces.push(std::mem::replace(&mut piece, vec![window[1]]));
        }
    }
    if let Some(&last) = run.last().filter(|_| run.len() > 1) {
        piece.push(last);
    }
    if piece.len() > 1 {
        pieces.push(piece);
    }
    pieces
}

/// The legend's sample of a series: the same mark and line as the series, 20 px wide.
struct LegendGlyph {
    at: (i32, i32),
    style: LineStyle,
    color: RGBColor,
}

impl<'a> PointCollection<'a, (i32, i32)> for &'a LegendGlyph {
    type Point = &'a (i32, i32);
    type IntoIter = std::iter::Once<&'a (i32, i32)>;
    fn point_iter(self) -> Self::IntoIter {
        std::iter::once(&self.at)
    }
}

impl<DB: DrawingBackend> Drawable<DB> for LegendGlyph {
    fn draw<I: Iterator<Item = BackendCoord>>(
        &self,
        mut points: I,
        backend: &mut DB,
        _: (u32, u32),
    ) -> std::result::Result<(), DrawingErrorKind<DB::ErrorType>> {
        let Some((x, y)) = points.next() else { return Ok(()) };
        let (stroke, mid) = (self.color.stroke_width(2), (x + 10, y));
        let line = |backend: &mut DB, from: i32, to: i32| backend.draw_line((x + from, y), (x + to, y), &stroke);
        match self.style {
            LineStyle::Solid => line(backend, 0, 20),
            LineStyle::Dashed => line(backend, 0, 8).and_then(|()| line(backend, 13, 20)),
            LineStyle::Circles => backend.draw_circle(mid, 5, &stroke, false),
            LineStyle::Crosses => {
                let thick = self.color.stroke_width(3);
                backend
                    .draw_line((x + 3, y - 7), (x + 17, y + 7), &thick)
                    .and_then(|()| backend.draw_line((x + 3, y + 7), (x + 17, y - 7), &thick))
            }
            LineStyle::DotsAndLine => {
                line(backend, 0, 20).and_then(|()| backend.draw_circle(mid, 3, &self.color.filled(), true))
            }
        }
    }
}

fn render<DB: DrawingBackend>(root: DrawingArea<DB, Shift>, panels: &[Figure]) -> std::result::Result<(), String> {
    root.fill(&WHITE).map_err(|e| e.to_string())?;
    let areas = root.split_evenly((1, panels.len()));
    for (panel, area) in panels.iter().zip(areas.iter()) {
        panel.draw(area)?;
    }
    root.present().map_err(|e| e.to_string())
}

/// A picture that any plotters backend can draw on its whole canvas.
pub(crate) trait Canvas {
    fn render<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>) -> std::result::Result<(), String>;
}

/// Panels side by side.
struct Panels<'a>(&'a [Figure]);

impl Canvas for Panels<'_> {
    fn render<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>) -> std::result::Result<(), String> {
        render(root, self.0)
    }
}

/// Writes `dir/stem.png` and `dir/stem.svg` of `size` pixels, each atomically.
pub(crate) fn save_canvas(canvas: &impl Canvas, size: (u32, u32), dir: &Path, stem: &str) -> Result<Vec<PathBuf>> {
    register_font();
    let png = dir.join(format!("{stem}.png"));
    let svg = dir.join(format!("{stem}.svg"));
    let fail = |path: &Path, message: String| Error::Plot {
        path: path.display().to_string(),
        message,
    };
    write_atomically(&png, |temporary| {
        canvas
            .render(BitMapBackend::new(temporary, size).into_drawing_area())
            .map_err(|m| fail(&png, m))
    })?;
    write_atomically(&svg, |temporary| {
        canvas
            .render(SVGBackend::new(temporary, size).into_drawing_area())
            .map_err(|m| fail(&svg, m))
    })?;
    Ok(vec![png, svg])
}

/// Writes `dir/stem.png` and `dir/stem.svg` with the panels side by side.
pub fn save_panels(panels: &[Figure], dir: &Path, stem: &str) -> Result<Vec<PathBuf>> {
    save_canvas(&Panels(panels), (640 * panels.len() as u32, 480), dir, stem)
}

impl Figure {
    /// Writes `dir/stem.png` and `dir/stem.svg`.
    pub fn save(&self, dir: &Path, stem: &str) -> Result<Vec<PathBuf>> {
        save_panels(std::slice::from_ref(self), dir, stem)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn curves_are_cut_where_they_leave_the_axes() {
        let zigzag = [(0.0, 0.0), (1.0, 2.0), (2.0, 0.0), (3.0, 0.5)];
        let runs = clip_polyline(&zigzag, (0.0, 3.0), (0.0, 1.0));
        assert_eq!(
            runs,
            vec![vec![(0.0, 0.0), (0.5, 1.0)], vec![(1.5, 1.0), (2.0, 0.0), (3.0, 0.5)]]
        );
        assert!(clip_polyline(&[(5.0, 5.0), (6.0, 6.0)], (0.0, 1.0), (0.0, 1.0)).is_empty());
        assert_eq!(
            clip_polyline(&[(0.5, 0.5)], (0.0, 1.0), (0.0, 1.0)),
            vec![vec![(0.5, 0.5)]]
        );
    }

    #[test]
    fn a_curve_is_cut_where_it_turns_back() {
        let pieces = split_at_sharp_turns(
            &[(0.0, 0.0), (1.0, 1.0), (2.0, 1.5), (2.1, 0.0)],
            (0.0, 2.0),
            (0.0, 2.0),
        );
        assert_eq!(
            pieces,
            vec![vec![(0.0, 0.0), (1.0, 1.0), (2.0, 1.5)], vec![(2.0, 1.5), (2.1, 0.0)]]
        );
    }

    #[test]
    fn the_legend_goes_to_the_corner_with_the_fewest_points() {
        let rising = Series::new(
            "",
            (0..=10).map(|i| (i as f64, i as f64)).collect(),
            LineStyle::Solid,
            0,
        );
        let figure = Figure::new("", "", "").with(rising);
        // A diagonal from lower left to upper right leaves the other two corners empty.
        assert_eq!(
            figure.emptiest_corner((0.0, 10.0), (0.0, 10.0)),
            SeriesLabelPosition::UpperLeft
        );
        // A vertical line of two points through the upper right keeps the legend out of it.
        let line = Series::new("", vec![(8.0, 0.0), (8.0, 10.0)], LineStyle::Dashed, 2);
        let sparse = Figure::new("", "", "").with(Series::new("", vec![(1.0, 1.0)], LineStyle::Circles, 0));
        assert_eq!(
            sparse.with(line).emptiest_corner((0.0, 10.0), (0.0, 10.0)),
            SeriesLabelPosition::UpperLeft
        );
        let high = Series::new("", (0..=10).map(|i| (i as f64, 9.5)).collect(), LineStyle::Solid, 1);
        assert_eq!(
            figure.with(high).emptiest_corner((0.0, 10.0), (0.0, 10.0)),
            SeriesLabelPosition::LowerRight
        );
    }

    /// Draws one legend glyph into a 20 x 20 white bitmap; whether pixel `(x, y)` was painted.
    fn glyph(style: LineStyle) -> impl Fn(u32, u32) -> bool {
        let mut buffer = vec![255u8; 20 * 20 * 3];
        {
            let root = BitMapBackend::with_buffer(&mut buffer, (20, 20)).into_drawing_area();
            root.draw(&LegendGlyph {
                at: (0, 10),
                style,
                color: RGBColor(0, 0, 0),
            })
            .unwrap();
            root.present().unwrap();
        }
        move |x, y| buffer[3 * (20 * y + x) as usize] < 128
    }

    #[test]
    fn legend_glyphs_show_the_mark_and_line_that_is_drawn() {
        let cross = glyph(LineStyle::Crosses);
        assert!(
            cross(4, 4) && cross(16, 16) && cross(10, 10),
            "a cross has its diagonals"
        );
        assert!(!cross(10, 5), "a cross is not a circle");
        let circle = glyph(LineStyle::Circles);
        assert!(circle(10, 5) && circle(5, 10) && !circle(10, 10), "an open circle");
        assert!(!circle(4, 4), "a circle is not a cross");
        let dashed = glyph(LineStyle::Dashed);
        assert!(
            dashed(3, 10) && dashed(16, 10) && !dashed(10, 10),
            "a dash, a gap, a dash"
        );
        let solid = glyph(LineStyle::Solid);
        assert!(solid(3, 10) && solid(10, 10) && solid(18, 10) && !solid(10, 6));
        let dots = glyph(LineStyle::DotsAndLine);
        assert!(dots(3, 10) && dots(10, 8) && !solid(10, 8), "a line with a dot on it");
    }
}
