//! Fig. 7: the wrinkle growing into a crease (section 3.2), `beta` from the parameters, N = 5,
//! at `d = 0.24, 0.40, 0.48` (the closest accepted states): the deformed top surface (left) and
//! the von Mises stress on the deformed mesh near the surface (right; elements drawn through
//! their eight boundary nodes, colour scale shared and clipped at the 99th percentile).

use crate::error::{Error, Result};
use crate::fem::fields::cell_fields;
use crate::fem::System;
use crate::material::Bilayer;
use crate::mesh::{MeshSpec, X, Y};
use crate::output::atomic::write_atomically;
use crate::output::plot::{register_font, FONT};
use crate::output::ticks::{tick_label, AxisScale, RoundTicks};
use crate::output::write_json;
use crate::parameters::Parameters;
use crate::protocol::{stages, wavenumber_of_waves, Event, Protocol, StepControl, StepRecord};
use crate::studies::Tick;
use plotters::coord::Shift;
use plotters::prelude::*;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// The compressions shown.
pub const FIG7_D: [f64; 3] = [0.24, 0.40, 0.48];
/// Depth below the highest surface point drawn in the stress panels.
const WINDOW_DEPTH: f64 = 12.0;
/// The boundary loop of a Q2 element through its local nodes `a + 3 b`.
const BOUNDARY: [usize; 8] = [0, 1, 2, 5, 8, 7, 6, 3];

/// One panel's state.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Fig7State {
    pub d_target: f64,
    pub d: f64,
    pub amplitude: f64,
    pub in_contact: bool,
    pub contact_length: f64,
    pub max_von_mises: f64,
    #[serde(skip)]
    u: Vec<f64>,
}

/// What Fig. 7 shows, with its files.
#[derive(Clone, Debug, Serialize)]
pub struct Fig7Facts {
    pub beta: f64,
    pub waves: f64,
    pub unknowns: usize,
    pub states: Vec<Fig7State>,
    pub d_first_contact: Option<f64>,
    pub d_reached: f64,
    pub seconds: f64,
    pub files: Vec<PathBuf>,
}

/// What [`CreaseSnapshots`] needs to go on: the states kept, each with its unknowns.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct CreaseMemory {
    targets: Vec<f64>,
    states: Vec<Option<(Fig7State, Vec<f64>)>>,
    first_contact: Option<f64>,
}

/// The accepted states nearest the compressions of Fig. 7 that a path reaches, collected as it
/// goes, and the first contact.
pub struct CreaseSnapshots {
    targets: Vec<f64>,
    states: Vec<Option<Fig7State>>,
    first_contact: Option<f64>,
}

impl CreaseSnapshots {
    /// Collects the states nearest those of [`FIG7_D`] up to `d_max`.
    pub fn new(d_max: f64) -> Self {
        let targets: Vec<f64> = FIG7_D.iter().copied().filter(|&d| d <= d_max + 1e-9).collect();
        CreaseSnapshots {
            states: vec![None; targets.len()],
            targets,
            first_contact: None,
        }
    }

    /// What a resumed path needs to go on.
    pub fn memory(&self) -> CreaseMemory {
        let states = self.states.iter().map(|s| s.as_ref().map(|s| (s.clone(), s.u.clone())));
        CreaseMemory {
            targets: self.targets.clone(),
            states: states.collect(),
            first_contact: self.first_contact,
        }
    }

    /// The snapshots of a resumed path.
    pub fn resumed(memory: CreaseMemory) -> Self {
        let states = memory
            .states
            .into_iter()
            .map(|s| s.map(|(state, u)| Fig7State { u, ..state }));
        CreaseSnapshots {
            targets: memory.targets,
            states: states.collect(),
            first_contact: memory.first_contact,
        }
    }

    /// Keeps `u` where `record` is the nearest state to a target so far.
    pub fn note(&mut self, record: &StepRecord, u: &[f64]) {
        let (in_contact, contact_length) = record
            .augmented
            .as_ref()
            .map_or((false, 0.0), |a| (a.in_contact, a.contact_length));
        if in_contact && self.first_contact.is_none() {
            self.first_contact = Some(record.d);
        }
        for (slot, &target) in self.states.iter_mut().zip(&self.targets) {
            if slot
                .as_ref()
                .is_none_or(|s| (record.d - target).abs() < (s.d - target).abs())
            {
                *slot = Some(Fig7State {
                    d_target: target,
                    d: record.d,
                    amplitude: record.amplitude,
                    in_contact,
                    contact_length,
                    max_von_mises: 0.0,
                    u: u.to_vec(),
                });
            }
        }
    }

    /// The first `d` in contact, if any.
    pub fn first_contact(&self) -> Option<f64> {
        self.first_contact
    }

    /// Draws `fig7.png` and `fig7.svg` into `out` (nothing if no target was reached), titled
    /// with the fibre angle `beta`; the states drawn, and the files.
    pub fn draw(
        self,
        system: &System,
        materials: &Bilayer,
        beta: f64,
        out: &Path,
    ) -> Result<(Vec<Fig7State>, Vec<PathBuf>)> {
        let mut states: Vec<Fig7State> = self.states.into_iter().flatten().collect();
        if states.is_empty() {
            return Ok((states, Vec::new()));
        }
        let mut panels = Vec::new();
        for state in &mut states {
            let panel = Panel::new(system, materials, state)?;
            state.max_von_mises = panel.cells.iter().fold(0.0, |m, c| m.max(c.1));
            panels.push(panel);
        }
        let scale = percentile(panels.iter().flat_map(|p| p.cells.iter().map(|c| c.1)).collect(), 0.99);
        register_font();
        let (png, svg) = (out.join("fig7.png"), out.join("fig7.svg"));
        let size = (1400, 350 * panels.len() as u32);
        let fail = |path: &Path, message: String| Error::Plot {
            path: path.display().to_string(),
            message,
        };
        write_atomically(&png, |temporary| {
            draw(
                BitMapBackend::new(temporary, size).into_drawing_area(),
                &panels,
                scale,
                beta,
            )
            .map_err(|m| fail(&png, m))
        })?;
        write_atomically(&svg, |temporary| {
            draw(
                SVGBackend::new(temporary, size).into_drawing_area(),
                &panels,
                scale,
                beta,
            )
            .map_err(|m| fail(&svg, m))
        })?;
        Ok((states, vec![png, svg]))
    }
}

/// Runs `params` (N = 5 waves, `A_init = 0.05`, contact and stabilisation) on `mesh` to
/// `d = 0.48` and writes `fig7.png`, `fig7.svg` and `fig7.json` into `out`; `quick` records
/// states at most every 0.01 in `d` instead of 0.005 and skips the inertia. `tick` is called
/// after every accepted state.
pub fn fig7(params: &Parameters, mesh: MeshSpec, quick: bool, out: &Path, tick: Tick) -> Result<Fig7Facts> {
    crate::output::ensure_dir(out)?;
    let start = std::time::Instant::now();
    let materials = Bilayer::new(params);
    let waves = 5.0;
    let mut protocol = Protocol::new(wavenumber_of_waves(waves, mesh.length)?, 0.05, FIG7_D[2]).with_crease_path();
    let step = if quick { 0.01 } else { 0.005 };
    protocol.control = StepControl {
        initial: step,
        max: step,
        ..protocol.control
    };
    protocol.newton.inertia_at_solution = false;
    let mut snapshots = CreaseSnapshots::new(FIG7_D[2]);
    let outcome = stages::run(&materials, mesh, &protocol, &mut |event| {
        if let Event::Step { record, u, .. } = event {
            snapshots.note(record, u);
            tick();
        }
        Ok(())
    })?;
    if let Some(e) = outcome.stopped {
        return Err(Error::Solver(format!("Fig. 7: {e}")));
    }
    let d_first_contact = snapshots.first_contact();
    let (states, mut files) = snapshots.draw(outcome.continuation.system(), &materials, params.beta, out)?;
    let json = out.join("fig7.json");
    files.push(json.clone());
    let facts = Fig7Facts {
        beta: params.beta,
        waves,
        unknowns: mesh.num_dofs(),
        states,
        d_first_contact,
        d_reached: outcome.continuation.d(),
        seconds: start.elapsed().as_secs_f64(),
        files,
    };
    write_json(&json, &facts)?;
    Ok(facts)
}

/// What one row draws: the surface, and the deformed elements near it with their von Mises stress.
struct Panel {
    d: f64,
    surface: Vec<(f64, f64)>,
    cells: Vec<(Vec<(f64, f64)>, f64)>,
    x_max: f64,
    y_range: (f64, f64),
}

impl Panel {
    fn new(system: &System, materials: &Bilayer, state: &Fig7State) -> Result<Self> {
        let mesh = system.mesh();
        let u = &state.u;
        let position = |n: usize| {
            let x = mesh.coordinates()[n];
            (x[0] + u[mesh.dofs().dof(n, X)], x[1] + u[mesh.dofs().dof(n, Y)])
        };
        let surface: Vec<(f64, f64)> = mesh.top().into_iter().map(position).collect();
        let top = surface.iter().fold(f64::NEG_INFINITY, |m, p| m.max(p.1));
        let bottom = top - WINDOW_DEPTH;
        let von_mises = cell_fields(system, materials, u)?.von_mises;
        let cells = mesh
            .elements()
            .iter()
            .zip(von_mises)
            .map(|(nodes, s)| (BOUNDARY.iter().map(|&a| position(nodes[a])).collect::<Vec<_>>(), s))
            .filter(|(polygon, _)| polygon.iter().any(|p| p.1 >= bottom))
            .collect();
        Ok(Panel {
            d: state.d,
            surface,
            cells,
            x_max: mesh.spec().length * (1.0 - state.d),
            y_range: (bottom, top + 0.5),
        })
    }
}

impl Panel {
    /// The surface's own height range, with a margin.
    fn surface_range(&self) -> std::ops::Range<f64> {
        let (low, high) = self
            .surface
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), p| (l.min(p.1), h.max(p.1)));
        let margin = 0.05 * (high - low).max(0.1);
        (low - margin)..(high + margin)
    }
}

/// The `q` quantile of `values` (0 when empty).
fn percentile(mut values: Vec<f64>, q: f64) -> f64 {
    values.sort_by(f64::total_cmp);
    values
        .get(((values.len() as f64 - 1.0) * q) as usize)
        .copied()
        .unwrap_or(0.0)
        .max(f64::MIN_POSITIVE)
}

/// A viridis-like colour map on `[0, 1]`.
fn colour(t: f64) -> RGBColor {
    const STOPS: [(u8, u8, u8); 5] = [
        (68, 1, 84),
        (59, 82, 139),
        (33, 145, 140),
        (94, 201, 98),
        (253, 231, 37),
    ];
    let s = t.clamp(0.0, 1.0) * (STOPS.len() - 1) as f64;
    let (i, f) = (
        (s.floor() as usize).min(STOPS.len() - 2),
        s - s.floor().min((STOPS.len() - 2) as f64),
    );
    let mix = |a: u8, b: u8| (a as f64 + (b as f64 - a as f64) * f).round() as u8;
    RGBColor(
        mix(STOPS[i].0, STOPS[i + 1].0),
        mix(STOPS[i].1, STOPS[i + 1].1),
        mix(STOPS[i].2, STOPS[i + 1].2),
    )
}

fn draw<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    panels: &[Panel],
    scale: f64,
    beta: f64,
) -> std::result::Result<(), String> {
    let e = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    root.fill(&WHITE).map_err(e)?;
    let rows = root.split_evenly((panels.len(), 2));
    let linear = |v: &f64| tick_label(*v, AxisScale::Linear);
    for (panel, pair) in panels.iter().zip(rows.chunks(2)) {
        let surface = panel.surface_range();
        let mut profile = ChartBuilder::on(&pair[0])
            .caption(
                format!(
                    "surface profile, beta = {:.1} deg, d = {:.3}",
                    beta.to_degrees(),
                    panel.d
                ),
                (FONT, 18),
            )
            .margin(8)
            .x_label_area_size(40)
            .y_label_area_size(55)
            .build_cartesian_2d(
                RoundTicks::new(0.0, panel.x_max, AxisScale::Linear),
                RoundTicks::new(surface.start, surface.end, AxisScale::Linear),
            )
            .map_err(e)?;
        profile
            .configure_mesh()
            .light_line_style(WHITE.mix(0.0))
            .x_label_formatter(&linear)
            .y_label_formatter(&linear)
            .label_style((FONT, 12))
            .x_desc("current x / H")
            .y_desc("current y / H")
            .axis_desc_style((FONT, 13))
            .draw()
            .map_err(e)?;
        // One-pixel lines: a wider polyline's mitred joins degenerate where the surface folds
        // back on itself (the two faces of a closed crease) and lose those segments.
        profile
            .draw_series(LineSeries::new(panel.surface.iter().copied(), BLACK.stroke_width(1)))
            .map_err(e)?;
        let (width, _) = pair[1].dim_in_pixel();
        let (map_area, bar_area) = pair[1].split_horizontally(width.saturating_sub(95));
        let mut map = ChartBuilder::on(&map_area)
            .caption(
                format!(
                    "von Mises stress (top of the scale: 99th percentile), d = {:.3}",
                    panel.d
                ),
                (FONT, 18),
            )
            .margin(8)
            .x_label_area_size(40)
            .y_label_area_size(55)
            .build_cartesian_2d(
                RoundTicks::new(0.0, panel.x_max, AxisScale::Linear),
                RoundTicks::new(panel.y_range.0, panel.y_range.1, AxisScale::Linear),
            )
            .map_err(e)?;
        map.configure_mesh()
            .light_line_style(WHITE.mix(0.0))
            .x_label_formatter(&linear)
            .y_label_formatter(&linear)
            .label_style((FONT, 12))
            .x_desc("current x / H")
            .y_desc("current y / H")
            .axis_desc_style((FONT, 13))
            .draw()
            .map_err(e)?;
        map.draw_series(
            panel
                .cells
                .iter()
                .map(|(polygon, s)| Polygon::new(polygon.clone(), colour(s / scale).filled())),
        )
        .map_err(e)?;
        colour_bar(&bar_area, scale).map_err(e)?;
    }
    root.present().map_err(e)
}

/// The colour scale of the stress maps in units of `mu_s`, `0` to `scale` (the 99th percentile:
/// stresses above it take its colour), beside them.
fn colour_bar<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    scale: f64,
) -> std::result::Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let mut bar = ChartBuilder::on(area)
        .caption("/ mu_s", (FONT, 13))
        .margin_top(14)
        .margin_bottom(48)
        .margin_left(10)
        .set_label_area_size(LabelAreaPosition::Right, 45)
        .build_cartesian_2d(0.0..1.0, RoundTicks::new(0.0, scale, AxisScale::Linear))?;
    bar.configure_mesh()
        .disable_x_mesh()
        .disable_x_axis()
        .light_line_style(WHITE.mix(0.0))
        .bold_line_style(WHITE.mix(0.0))
        .y_label_formatter(&|v| tick_label(*v, AxisScale::Linear))
        .label_style((FONT, 12))
        .draw()?;
    const STEPS: usize = 100;
    bar.draw_series((0..STEPS).map(|i| {
        let (lo, hi) = (i as f64 / STEPS as f64, (i + 1) as f64 / STEPS as f64);
        Rectangle::new([(0.0, lo * scale), (1.0, hi * scale)], colour(0.5 * (lo + hi)).filled())
    }))?;
    Ok(())
}
