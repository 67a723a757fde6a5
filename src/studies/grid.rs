//! A grid of points over two parameters, computed into a folder one point at a time: the
//! machinery `fiberfold map` and a map of patterns (`fiberfold pattern --x ... --y ...`)
//! share. Every point is written to `points/point-<index>.json` as soon as it is done, so an
//! interrupted grid resumes where it stopped, and a grid split into shards (`index % N == I`,
//! one SLURM array task each) is assembled from the same folder once all are done.
//! `map-spec.json` holds what the grid computes; a run or a collection with other settings in
//! the same folder is refused.

use super::{validate_points, Tick};
use crate::error::{Error, Result};
use crate::output::{ensure_dir, write_json_shared};
use crate::parameters::Parameters;
use rayon::prelude::*;
use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// One axis of a grid: `points` values of a numeric parameter from `from` to `to`, equally
/// spaced or (with `log`) geometrically.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Axis {
    pub name: String,
    pub from: f64,
    pub to: f64,
    pub points: usize,
    pub log: bool,
}

impl Axis {
    pub fn values(&self) -> Vec<f64> {
        if self.points == 1 {
            return vec![self.from];
        }
        (0..self.points)
            .map(|i| {
                let t = i as f64 / (self.points - 1) as f64;
                if self.log {
                    self.from * (self.to / self.from).powf(t)
                } else {
                    self.from + (self.to - self.from) * t
                }
            })
            .collect()
    }

    /// Checks the name (a numeric parameter), the range and the number of points; `flag` is the
    /// CLI's prefix (`x` or `y`).
    pub fn validate(&self, flag: &str, base: &Parameters) -> Result<()> {
        if base.number(&self.name).is_err() {
            return Err(Error::invalid(
                flag,
                &self.name,
                &format!(
                    "a numeric parameter of the laws in use: {}",
                    base.numeric_keys().join(", ")
                ),
            ));
        }
        validate_points(&format!("{flag}-points"), self.points, 1)?;
        if !self.from.is_finite() {
            return Err(Error::invalid(&format!("{flag}-from"), self.from, "a finite number"));
        }
        if !(self.to.is_finite() && (self.points == 1 || self.to > self.from)) {
            return Err(Error::invalid(
                &format!("{flag}-to"),
                self.to,
                &format!("a finite number above {flag}-from = {}", self.from),
            ));
        }
        if self.log && self.from <= 0.0 {
            return Err(Error::invalid(
                &format!("{flag}-from"),
                self.from,
                &format!("(0, inf) with --{flag}-log"),
            ));
        }
        Ok(())
    }
}

/// Cell edges around the values of an axis (plotted coordinates): midpoints, half a cell
/// beyond the ends.
pub fn cell_edges(values: &[f64]) -> Vec<f64> {
    if values.len() == 1 {
        return vec![values[0] - 0.5, values[0] + 0.5];
    }
    let mut e = vec![values[0] - 0.5 * (values[1] - values[0])];
    e.extend(values.windows(2).map(|w| 0.5 * (w[0] + w[1])));
    let n = values.len();
    e.push(values[n - 1] + 0.5 * (values[n - 1] - values[n - 2]));
    e
}

/// Where a point lies: `(index, ix, iy, x, y)`, `index = iy * nx + ix`.
pub type At = (usize, usize, usize, f64, f64);

/// Every point of the grid of `x` and `y` over `base`, with its parameter set. With
/// `keep_poisson`, a mapped shear modulus carries its bulk modulus along (`K_l` with `mu_l`,
/// `K_s` with `mu_s`), keeping the base set's `K / mu`.
pub fn points(base: &Parameters, x: &Axis, y: &Axis, keep_poisson: bool) -> Result<Vec<(At, Parameters)>> {
    let assign = |p: &mut Parameters, name: &str, value: f64| match keep_poisson {
        true => p.set_number_keeping_poisson(name, value, &[&x.name, &y.name]),
        false => p.set_number(name, value),
    };
    let (xs, ys) = (x.values(), y.values());
    let mut grid = Vec::with_capacity(xs.len() * ys.len());
    for (iy, &yv) in ys.iter().enumerate() {
        for (ix, &xv) in xs.iter().enumerate() {
            let mut p = base.clone();
            assign(&mut p, &x.name, xv)?;
            assign(&mut p, &y.name, yv)?;
            grid.push(((iy * xs.len() + ix, ix, iy, xv, yv), p));
        }
    }
    Ok(grid)
}

/// Checks two axes over `base`, and that they map different parameters.
pub fn validate_axes(base: &Parameters, x: &Axis, y: &Axis) -> Result<()> {
    x.validate("x", base)?;
    y.validate("y", base)?;
    if x.name == y.name {
        return Err(Error::invalid("y", &y.name, "a parameter other than --x"));
    }
    Ok(())
}

/// `--shard I/N`: the points with `index % count == shard`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shard {
    pub index: usize,
    pub count: usize,
}

impl Shard {
    /// Parses `I/N` with `0 <= I < N`.
    pub fn parse(text: &str) -> Result<Self> {
        let bad = || {
            Error::invalid(
                "shard",
                text,
                "I/N with 0 <= I < N, e.g. 0/4 (SLURM_ARRAY_TASK_ID/SLURM_ARRAY_TASK_COUNT)",
            )
        };
        let (i, n) = text.split_once('/').ok_or_else(bad)?;
        let (index, count) = (
            i.trim().parse().map_err(|_| bad())?,
            n.trim().parse().map_err(|_| bad())?,
        );
        if count == 0 || index >= count {
            return Err(bad());
        }
        Ok(Shard { index, count })
    }

    /// How many of `total` points are this shard's.
    pub fn share(&self, total: usize) -> usize {
        (total + self.count - 1 - self.index) / self.count
    }
}

/// What a grid computes: its points and how one is computed, and its description
/// (`map-spec.json`, which a folder's points must match).
pub trait GridStudy: Clone + PartialEq + Serialize + DeserializeOwned + Sync {
    /// What one point's computation gives (its file).
    type Point: Serialize + DeserializeOwned + Send;

    /// The command that writes such grids (for messages).
    const COMMAND: &'static str;

    /// Every point of the grid with its parameter set.
    fn points(&self) -> Result<Vec<(At, Parameters)>>;

    /// Computes the point `at` of `parameters`; `folder` is the point's own folder, for files of
    /// its own (created by the call if it writes any).
    fn compute_point(&self, at: At, parameters: Parameters, folder: &Path) -> Result<Self::Point>;
}

/// What one [`compute`] did.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Computed {
    pub points: usize,
    pub reused: usize,
}

fn point_path(out: &Path, index: usize) -> PathBuf {
    out.join("points").join(format!("point-{index:05}.json"))
}

/// The folder of a point's own files.
pub fn point_folder(out: &Path, index: usize) -> PathBuf {
    out.join("points").join(format!("point-{index:05}"))
}

/// A point file and the study it was computed for.
#[derive(Serialize, Deserialize)]
struct PointFile<S, P> {
    study: S,
    point: P,
}

/// Reads a finished point of `study` (None if absent; an error if it belongs to another grid).
fn read_point<S: GridStudy>(study: &S, out: &Path, index: usize) -> Result<Option<S::Point>> {
    let path = point_path(out, index);
    let Ok(text) = std::fs::read_to_string(&path) else {
        return Ok(None);
    };
    let file: PointFile<S, S::Point> = serde_json::from_str(&text).map_err(|e| {
        Error::invalid(
            "out",
            path.display(),
            &format!("a point file of fiberfold {} ({e})", S::COMMAND),
        )
    })?;
    if file.study != *study {
        return Err(mismatch(out));
    }
    Ok(Some(file.point))
}

fn mismatch(out: &Path) -> Error {
    Error::invalid(
        "out",
        out.display(),
        "a folder holding a map of the same parameters and settings (it holds another: use another --out, or delete it)",
    )
}

/// Writes `map-spec.json`, or checks that the one in `out` is `study`'s.
pub fn claim_folder<S: GridStudy>(study: &S, out: &Path) -> Result<()> {
    ensure_dir(&out.join("points"))?;
    let spec = out.join("map-spec.json");
    match std::fs::read_to_string(&spec) {
        Ok(text) => {
            let stored: S = serde_json::from_str(&text).map_err(|_| mismatch(out))?;
            if stored != *study {
                return Err(mismatch(out));
            }
            Ok(())
        }
        Err(_) => write_json_shared(&spec, study),
    }
}

/// Computes the points of `shard` (all without one) not yet in `out`, in parallel, each
/// written as soon as it is done; `tick` once per point of the share, reused ones first. The
/// caller validates `study` first.
pub fn compute<S: GridStudy>(study: &S, out: &Path, shard: Option<Shard>, tick: Tick) -> Result<Computed> {
    claim_folder(study, out)?;
    let share: Vec<_> = study
        .points()?
        .into_iter()
        .filter(|((index, ..), _)| shard.is_none_or(|s| index % s.count == s.index))
        .collect();
    let mut pending = Vec::new();
    for (at, parameters) in &share {
        if read_point(study, out, at.0)?.is_some() {
            tick();
        } else {
            pending.push((*at, parameters.clone()));
        }
    }
    let reused = share.len() - pending.len();
    pending.into_par_iter().try_for_each(|(at, parameters)| {
        let point = study.compute_point(at, parameters, &point_folder(out, at.0))?;
        write_json_shared(
            &point_path(out, at.0),
            &PointFile {
                study: study.clone(),
                point,
            },
        )?;
        tick();
        Ok::<_, Error>(())
    })?;
    Ok(Computed {
        points: share.len(),
        reused,
    })
}

/// Every finished point of `study` in `out`, in the order of the grid; missing points are an
/// error naming the first and their count.
pub fn finished_points<S: GridStudy>(study: &S, out: &Path) -> Result<Vec<S::Point>> {
    claim_folder(study, out)?;
    let grid = study.points()?;
    let mut points = Vec::with_capacity(grid.len());
    let mut missing = Vec::new();
    for ((index, ..), _) in &grid {
        match read_point(study, out, *index)? {
            Some(p) => points.push(p),
            None => missing.push(*index),
        }
    }
    if let Some(first) = missing.first() {
        return Err(Error::invalid(
            "collect",
            out.display(),
            &format!(
                "a folder with all {} points of the map; {} are missing (the first is point-{first:05}.json): \
                 run their shards first",
                grid.len(),
                missing.len(),
            ),
        ));
    }
    Ok(points)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cell_edges_lie_halfway_and_half_a_cell_beyond_the_ends() {
        assert_eq!(cell_edges(&[1.0, 2.0, 4.0]), vec![0.5, 1.5, 3.0, 5.0]);
        assert_eq!(cell_edges(&[3.0]), vec![2.5, 3.5]);
    }
}
