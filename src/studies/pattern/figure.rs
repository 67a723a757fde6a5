//! `mode_top.png/svg` and `mode_3d.png/svg`: a patch's surface seen from above and in
//! perspective. From above, each cell of its top node grid is coloured by the mean `u_Y` of its
//! corners (blue down, red up), with the fibres' projection on the surface drawn as lines; in
//! perspective, the same field is the height of a relief coloured alike.

use crate::error::Result;
use crate::mesh::{Mesh, TOP, X, Y, Z};
use crate::output::plot::{save_canvas, Canvas, FONT};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::{Path, PathBuf};

/// A patch's top-surface field and the fibres' direction in the surface.
pub struct TopView<'a> {
    pub title: String,
    pub mesh: &'a Mesh<3, 27>,
    /// One value per unknown of the mesh; `u_Y` is drawn, scaled by its largest magnitude.
    pub field: &'a [f64],
    /// The fibres' projection on the surface `(cos psi, sin psi)`; `None` for fibres normal
    /// to it.
    pub fibres: Option<[f64; 2]>,
}

/// Writes `dir/stem.png` and `dir/stem.svg`.
pub fn top_view(view: &TopView, dir: &Path, stem: &str) -> Result<Vec<PathBuf>> {
    let spec = view.mesh.patch_spec();
    let (length_x, length_z) = (spec.length_x, spec.length_z);
    let width = 640u32;
    let height = ((width as f64 - 90.0) * length_z / length_x + 110.0).clamp(320.0, 1000.0) as u32;
    save_canvas(view, (width, height), dir, stem)
}

impl Canvas for TopView<'_> {
    fn render<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>) -> std::result::Result<(), String> {
        draw(root, self)
    }
}

/// Blue (-1), white (0), red (+1).
fn diverging(v: f64) -> RGBColor {
    let t = v.clamp(-1.0, 1.0);
    let (end, s) = if t < 0.0 {
        ((33.0, 102.0, 172.0), -t)
    } else {
        ((178.0, 24.0, 43.0), t)
    };
    let mix = |c: f64| (255.0 + (c - 255.0) * s).round() as u8;
    RGBColor(mix(end.0), mix(end.1), mix(end.2))
}

/// The part of the line through `point` along `direction` inside `[0, a] x [0, b]`, if any.
fn clipped(point: [f64; 2], direction: [f64; 2], (a, b): (f64, f64)) -> Option<[(f64, f64); 2]> {
    let (mut low, mut high) = (f64::NEG_INFINITY, f64::INFINITY);
    for (p, d, end) in [(point[0], direction[0], a), (point[1], direction[1], b)] {
        if d.abs() < 1e-12 {
            if !(0.0..=end).contains(&p) {
                return None;
            }
            continue;
        }
        let (t0, t1) = ((0.0 - p) / d, (end - p) / d);
        low = low.max(t0.min(t1));
        high = high.min(t0.max(t1));
    }
    (high > low).then(|| {
        let at = |t: f64| (point[0] + t * direction[0], point[1] + t * direction[1]);
        [at(low), at(high)]
    })
}

/// A patch's top-surface field on the grid of its top nodes.
struct TopGrid {
    /// `values[i][k]` at the node `(i dx, k dz)`.
    values: Vec<Vec<f64>>,
    /// `cx x cz` cells between the nodes.
    cells: (usize, usize),
    /// `px x pz` nodes: a periodic patch's last nodes are its first (`px = cx`), a symmetric
    /// patch has one more row of nodes each way.
    points: (usize, usize),
    spacing: (f64, f64),
    /// The largest magnitude of the values (at least the smallest positive number).
    largest: f64,
}

impl TopGrid {
    fn of(view: &TopView) -> Self {
        let mesh = view.mesh;
        let spec = mesh.patch_spec();
        let (cx, cz) = (2 * spec.nx, 2 * spec.nz);
        let (px, pz) = match mesh.is_periodic() {
            true => (cx, cz),
            false => (cx + 1, cz + 1),
        };
        let (dx, dz) = (spec.length_x / cx as f64, spec.length_z / cz as f64);
        let mut values = vec![vec![0.0; pz]; px];
        for &node in mesh.node_set(TOP) {
            let x = mesh.coordinates()[node];
            let (i, k) = ((x[X] / dx).round() as usize % px, (x[Z] / dz).round() as usize % pz);
            values[i][k] = view.field[mesh.dofs().dof(node, Y)];
        }
        let largest = values
            .iter()
            .flatten()
            .fold(0.0f64, |m, v| m.max(v.abs()))
            .max(f64::MIN_POSITIVE);
        TopGrid {
            values,
            cells: (cx, cz),
            points: (px, pz),
            spacing: (dx, dz),
            largest,
        }
    }

    /// The value at the node nearest `(x, z)`, a periodic patch's nodes repeated a period on.
    fn at(&self, x: f64, z: f64) -> f64 {
        let (i, k) = (
            (x / self.spacing.0).round() as usize,
            (z / self.spacing.1).round() as usize,
        );
        self.values[i % self.points.0][k % self.points.1]
    }
}

/// Writes `dir/stem.png` and `dir/stem.svg`: the field as a relief in perspective under `title`,
/// coloured as the view from above, its height exaggerated to fill the box drawn.
pub fn perspective(view: &TopView, title: &str, dir: &Path, stem: &str) -> Result<Vec<PathBuf>> {
    save_canvas(&Perspective(view, title), (720, 600), dir, stem)
}

struct Perspective<'a, 'b>(&'a TopView<'b>, &'a str);

impl Canvas for Perspective<'_, '_> {
    fn render<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>) -> std::result::Result<(), String> {
        draw_perspective(root, self.0, self.1)
    }
}

fn draw_perspective<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    view: &TopView,
    title: &str,
) -> std::result::Result<(), String> {
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    root.fill(&WHITE).map_err(err)?;
    let grid = TopGrid::of(view);
    let spec = view.mesh.patch_spec();
    let (length_x, length_z) = (spec.length_x, spec.length_z);
    let largest = grid.largest;
    let root = root.titled(title, (FONT, 15)).map_err(err)?;
    let mut chart = ChartBuilder::on(&root)
        .margin(24)
        .margin_top(30)
        .build_cartesian_3d(0.0..length_x, -largest..largest, 0.0..length_z)
        .map_err(err)?;
    chart.with_projection(|mut p| {
        p.pitch = 0.55;
        p.yaw = 0.6;
        p.scale = 0.8;
        p.into_matrix()
    });
    chart
        .configure_axes()
        .label_style((FONT, 11))
        .max_light_lines(0)
        .draw()
        .map_err(err)?;
    let (cx, cz) = grid.cells;
    let (dx, dz) = grid.spacing;
    let colour = |y: &f64| diverging(*y / largest).filled();
    chart
        .draw_series(
            SurfaceSeries::xoz(
                (0..=cx).map(|i| i as f64 * dx),
                (0..=cz).map(|k| k as f64 * dz),
                |x, z| grid.at(x, z),
            )
            .style_func(&colour),
        )
        .map_err(err)?;
    Ok(())
}

fn draw<DB: DrawingBackend>(root: DrawingArea<DB, Shift>, view: &TopView) -> std::result::Result<(), String> {
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    root.fill(&WHITE).map_err(err)?;
    let TopGrid {
        values: grid,
        cells: (cx, cz),
        points: (px, pz),
        spacing: (dx, dz),
        largest,
    } = TopGrid::of(view);
    let spec = view.mesh.patch_spec();
    let (length_x, length_z) = (spec.length_x, spec.length_z);
    let mut chart = ChartBuilder::on(&root)
        .caption(&view.title, (FONT, 16))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(50)
        .build_cartesian_2d(0.0..length_x, 0.0..length_z)
        .map_err(err)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc("X / H")
        .y_desc("Z / H")
        .label_style((FONT, 13))
        .axis_desc_style((FONT, 14))
        .draw()
        .map_err(err)?;
    let cells = (0..cx).flat_map(|i| (0..cz).map(move |k| (i, k))).map(|(i, k)| {
        let corner = |a: usize, b: usize| grid[(i + a) % px][(k + b) % pz];
        let mean = 0.25 * (corner(0, 0) + corner(1, 0) + corner(0, 1) + corner(1, 1)) / largest;
        let (x, z) = (i as f64 * dx, k as f64 * dz);
        Rectangle::new([(x, z), (x + dx, z + dz)], diverging(mean).filled())
    });
    chart.draw_series(cells).map_err(err)?;
    if let Some(direction) = view.fibres {
        // Lines along the fibres' projection, a fifth of the patch's diagonal apart.
        let normal = [-direction[1], direction[0]];
        let spacing = length_x.hypot(length_z) / 5.0;
        let centre = [0.5 * length_x, 0.5 * length_z];
        let lines = (-5..=5).filter_map(|j| {
            let offset = j as f64 * spacing;
            let point = [centre[0] + offset * normal[0], centre[1] + offset * normal[1]];
            clipped(point, direction, (length_x, length_z))
                .map(|[a, b]| PathElement::new(vec![a, b], BLACK.stroke_width(1)))
        });
        chart.draw_series(lines).map_err(err)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_are_clipped_to_the_patch_and_colours_diverge_from_white() {
        let [a, b] = clipped([1.0, 1.0], [1.0, 0.0], (4.0, 3.0)).unwrap();
        assert_eq!((a, b), ((0.0, 1.0), (4.0, 1.0)));
        let [a, b] = clipped([2.0, 1.5], [1.0, 1.0], (4.0, 3.0)).unwrap();
        assert_eq!((a, b), ((0.5, 0.0), (3.5, 3.0)));
        assert!(clipped([5.0, 1.0], [0.0, 1.0], (4.0, 3.0)).is_none());
        assert_eq!(diverging(0.0), RGBColor(255, 255, 255));
        assert_eq!(diverging(1.0), RGBColor(178, 24, 43));
        assert_eq!(diverging(-2.0), RGBColor(33, 102, 172));
    }
}
