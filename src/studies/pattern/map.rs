//! A map of patterns: `pattern` at every point of a grid of two parameters (`fiberfold pattern
//! --x beta --y psi ...`), computed point by point into a folder that resumes and shards as
//! `fiberfold map`'s does ([`crate::studies::grid`]). Each point's files (`pattern.json`,
//! `pattern.csv`, its pictures and VTU) are in `points/point-<index>/`; `map_files` assembles
//! the map's own files.

use super::{compute, PatternStudy};
use crate::error::{Error, Result};
use crate::output::ensure_dir;
use crate::parameters::Parameters;
use crate::protocol::patch::{classify, Direction, SurfacePattern};
use crate::studies::grid::{self, At, Axis, GridStudy};
use serde::{Deserialize, Serialize};
use std::path::Path;
use std::time::Instant;

/// A map of patterns: the base parameters, two axes and the `pattern` run of every point.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PatternMap {
    pub base: Parameters,
    pub x: Axis,
    pub y: Axis,
    /// Scale the bulk modulus with a mapped shear modulus, keeping the base set's `K / mu`.
    pub keep_poisson: bool,
    pub study: PatternStudy,
}

/// One point of the map (`points/point-<index>.json`; its files in `points/point-<index>/`).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct PatternPoint {
    /// Position in the map: `index = iy * x_points + ix`.
    pub index: usize,
    pub ix: usize,
    pub iy: usize,
    pub x: f64,
    pub y: f64,
    pub parameters: Parameters,
    /// The exact theory's onset and the direction of its wave vector from X towards Z
    /// (degrees; None where every direction is critical).
    pub d_c: Option<f64>,
    pub theta0_degrees: Option<f64>,
    /// The patch's first bifurcation, relative to the theory's smallest `d_c` over its wave
    /// vectors.
    pub d_bifurcation: Option<f64>,
    pub relative_difference: Option<f64>,
    pub unknowns: Option<usize>,
    /// The state classified: the path's last if it was followed, otherwise the bifurcation
    /// mode (its four leading waves), at `d_bifurcation`.
    pub d: Option<f64>,
    pub pattern: Option<SurfacePattern>,
    pub directions: Vec<Direction>,
    /// The relief `A` of the path's last state.
    pub amplitude: Option<f64>,
    /// Where the path's pattern changed, and to what.
    pub changes: Vec<(f64, SurfacePattern)>,
    /// Where the path left an unstable branch for a stable state.
    pub branches_left: Vec<f64>,
    /// Why the path stopped before its end (e.g. the surface touching itself), if it did.
    pub stopped: Option<String>,
    /// Why the point has no answer (the solver failed), if it has none.
    pub failed: Option<String>,
    pub seconds: f64,
}

impl PatternMap {
    /// Checks the axes, every point's parameters and the path's end.
    pub fn validate(&self) -> Result<()> {
        if self.study.resume {
            return Err(Error::invalid(
                "resume",
                "with --x and --y",
                "one patch (a map of patterns resumes by its points: run it again)",
            ));
        }
        grid::validate_axes(&self.base, &self.x, &self.y)?;
        for (_, parameters) in self.points()? {
            parameters.validate()?;
        }
        if let Some(path) = &self.study.path {
            // An end past each point's onset is checked at the point, against its own onset;
            // an onset at the path's start is the earliest it can have.
            path.validate(path.d_start)?;
        }
        Ok(())
    }
}

impl GridStudy for PatternMap {
    type Point = PatternPoint;
    const COMMAND: &'static str = "pattern";

    fn points(&self) -> Result<Vec<(At, Parameters)>> {
        grid::points(&self.base, &self.x, &self.y, self.keep_poisson)
    }

    /// The `pattern` run of one point into `folder`; a solver's failure is the point's answer
    /// (`failed`), not the map's.
    fn compute_point(&self, (index, ix, iy, x, y): At, parameters: Parameters, folder: &Path) -> Result<PatternPoint> {
        let clock = Instant::now();
        ensure_dir(folder)?;
        let mut point = PatternPoint {
            index,
            ix,
            iy,
            x,
            y,
            parameters: parameters.clone(),
            d_c: None,
            theta0_degrees: None,
            d_bifurcation: None,
            relative_difference: None,
            unknowns: None,
            d: None,
            pattern: None,
            directions: Vec::new(),
            amplitude: None,
            changes: Vec::new(),
            branches_left: Vec::new(),
            stopped: None,
            failed: None,
            seconds: 0.0,
        };
        match compute(&parameters, &self.study, folder, &mut |_| {}) {
            Ok(report) => {
                point.d_c = Some(report.onset_theory.d_c);
                point.theta0_degrees = report.onset_theory.theta0_degrees;
                point.d_bifurcation = Some(report.d_bifurcation);
                point.relative_difference = Some(report.relative_difference);
                point.unknowns = Some(report.unknowns);
                match report.path {
                    Some(path) => {
                        if let Some(last) = path.last {
                            point.d = Some(last.d);
                            point.pattern = Some(last.pattern);
                            point.directions = last.directions;
                            point.amplitude = Some(last.amplitude);
                        }
                        point.changes = path.changes;
                        point.branches_left = path.branches_left.iter().map(|&(d, _)| d).collect();
                        point.stopped = path.stopped;
                    }
                    None if !report.mode_wave_vectors.is_empty() => {
                        let (pattern, directions) = classify(&report.mode_wave_vectors);
                        point.d = Some(report.d_bifurcation);
                        point.pattern = Some(pattern);
                        point.directions = directions;
                    }
                    None => {}
                }
            }
            Err(e @ (Error::Solver(_) | Error::NoRoot { .. } | Error::NonPositiveJacobian { .. })) => {
                point.failed = Some(e.to_string());
            }
            Err(e) => return Err(e),
        }
        point.seconds = clock.elapsed().as_secs_f64();
        Ok(point)
    }
}

/// Computes the points of `shard` (all without one) not yet in `out` ([`grid::compute`]).
pub fn compute_map(
    map: &PatternMap,
    out: &Path,
    shard: Option<grid::Shard>,
    tick: crate::studies::Tick,
) -> Result<grid::Computed> {
    map.validate()?;
    grid::compute(map, out, shard, tick)
}

/// `map.json` of a map of patterns.
#[derive(Clone, Debug, Serialize)]
pub struct PatternMapReport {
    pub command: &'static str,
    pub map: PatternMap,
    pub points: Vec<PatternPoint>,
    /// Sum over points of their wall time (s): the work, whatever the parallelism.
    pub point_seconds: f64,
}

/// The flags that turn `fiberfold pattern` into a map of patterns: two axes (both or neither),
/// and which points this run computes.
#[derive(Clone, Debug, PartialEq, clap::Args)]
#[command(next_help_heading = "Map of patterns (with --x and --y)")]
pub struct PatternMapOptions {
    /// Map the patterns over this parameter along the horizontal axis (any numeric key of
    /// --set, e.g. beta), with --y: the patch of the other flags at every point of the grid.
    #[arg(long, requires = "y")]
    pub x: Option<String>,
    /// First value of --x (units of the parameter: moduli by mu_s, angles in radians).
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    pub x_from: f64,
    /// Last value of --x (the default is pi/2).
    #[arg(long, default_value_t = std::f64::consts::FRAC_PI_2, allow_negative_numbers = true)]
    pub x_to: f64,
    /// Values of --x.
    #[arg(long, default_value_t = 3)]
    pub x_points: usize,
    /// Space the --x values geometrically (a log axis).
    #[arg(long)]
    pub x_log: bool,

    /// The parameter along the vertical axis (e.g. psi), with --x.
    #[arg(long, requires = "x")]
    pub y: Option<String>,
    /// First value of --y.
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    pub y_from: f64,
    /// Last value of --y (the default is pi/2).
    #[arg(long, default_value_t = std::f64::consts::FRAC_PI_2, allow_negative_numbers = true)]
    pub y_to: f64,
    /// Values of --y.
    #[arg(long, default_value_t = 3)]
    pub y_points: usize,
    /// Space the --y values geometrically (a log axis).
    #[arg(long)]
    pub y_log: bool,

    /// Let the bulk modulus stay at its base value when mu_l or mu_s is mapped (by default it
    /// scales with it, keeping the base K/mu).
    #[arg(long)]
    pub free_bulk: bool,

    /// Compute only the points with index % N == I (I/N; e.g.
    /// $SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT), into the same folder as the other shards;
    /// assemble them with --collect.
    #[arg(long, value_name = "I/N", requires = "x", conflicts_with = "collect")]
    pub shard: Option<String>,

    /// Only assemble the finished points in --out into map.csv, map.json and map.png/svg (with
    /// the same flags as the shards); missing points are an error.
    #[arg(long, requires = "x")]
    pub collect: bool,
}

impl PatternMapOptions {
    /// The map these flags ask for over `base` with every point's `study` (None without --x).
    /// A point writes no checkpoints: a map resumes by its points.
    pub fn map(&self, base: Parameters, study: PatternStudy) -> Option<PatternMap> {
        let axis = |name: &Option<String>, from, to, points, log| Axis {
            name: name.clone().unwrap_or_default(),
            from,
            to,
            points,
            log,
        };
        self.x.as_ref()?;
        Some(PatternMap {
            base,
            x: axis(&self.x, self.x_from, self.x_to, self.x_points, self.x_log),
            y: axis(&self.y, self.y_from, self.y_to, self.y_points, self.y_log),
            keep_poisson: !self.free_bulk,
            study: PatternStudy {
                checkpoints: None,
                ..study
            },
        })
    }
}
