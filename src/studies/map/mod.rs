//! `fiberfold map`: which instability comes first, and what the wrinkle becomes, over a grid of
//! two parameters (`point` computes one point). Every point is written to
//! `points/point-<index>.json` as soon as it is done, so an interrupted map resumes where it
//! stopped, and a map split into shards (`index % N == I`, one SLURM array task each) is
//! assembled by [`collect`] into `map.csv`, `map.json` and the phase diagram `map.png/svg`.
//! `map-spec.json` holds the map's settings; a run or a collection with other settings in the
//! same folder is refused.

mod figure;
mod options;
mod point;

pub use options::MapOptions;
pub use point::{compute as compute_point, doubling, first_instability, post_buckling, First, MapPoint, PostBuckling};

use super::crease::{CreaseMesh, CreaseStudy, Criterion, Refinement, Scan};
use super::orientation::Modes;
use super::{validate_points, Tick};
use crate::error::{Error, Result};
use crate::output::table::{variant_name, Cell};
use crate::output::{ensure_dir, write_json, write_json_shared, CsvWriter};
use crate::parameters::Parameters;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// One axis of the map: `points` values of a numeric parameter from `from` to `to`, equally
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
    fn validate(&self, flag: &str, base: &Parameters) -> Result<()> {
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

/// How each point is computed (the CLI's flags of the same names).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MapSettings {
    /// Wavelengths of `2 pi / k0` across the nonlinear run's half domain (`2 waves` an integer).
    pub waves: f64,
    /// Q2 elements per wavelength along X in the nonlinear run.
    pub elements_per_wave: usize,
    pub layer_elements: usize,
    pub substrate_elements: usize,
    /// Depth of the nonlinear run's domain (units of H).
    pub depth: f64,
    /// `A_init` of the seeded wrinkle, and `A_2` of the seed along the first secondary mode.
    pub imperfection: f64,
    pub seed: f64,
    /// The nonlinear run goes to `d_wrinkle + post_buckling_range`, at most `d_limit`.
    pub post_buckling_range: f64,
    pub d_limit: f64,
    /// Energy the viscous stabilisation may dissipate, relative to the strain energy, so that
    /// the run crosses the snaps a wrinkle makes into a fold or a period doubling (a `simulate`
    /// run stops at 1 %, where the path stops being quasi-static).
    pub snap_budget: f64,

    /// The crease search ([`CreaseStudy`], without its mesh check); its mesh's element is the
    /// nonlinear run's too.
    pub crease_mesh: CreaseMesh,
    pub fold_lengths: Vec<f64>,
    pub crease_scan: Scan,
    /// The mesh sequence that converges each point's crease onset (None in files written before
    /// it existed: the base mesh alone).
    #[serde(default)]
    pub crease_refinement: Option<Refinement>,
    /// The crease search's criterion (held in files written before it existed).
    #[serde(default)]
    pub crease_criterion: Criterion,
    /// Scale the bulk modulus with a mapped shear modulus (`K_l` with `mu_l`, `K_s` with
    /// `mu_s`), keeping the base set's `K / mu`: the Poisson ratio stays Table 1's.
    pub keep_poisson: bool,
    /// `R = d_3 / d`: each point also finds the direction of the first wrinkles under biaxial
    /// compression `d_3 = R d` (the linear theory over the directions of the surface), drawn
    /// on the figure as the crests' direction. The crease search and the nonlinear run stay
    /// in plane strain.
    #[serde(default)]
    pub biaxial: Option<f64>,
}

impl Default for MapSettings {
    /// Four wavelengths at 20 elements each, the coarse mesh's layers (2 + 25, depth 50),
    /// `A_init = 0.05` with a 0.01 seed along the first secondary mode, runs to `d_wrinkle + 0.2`
    /// (at most 0.7); the
    /// crease search of `fiberfold crease` without its mesh check.
    fn default() -> Self {
        let crease = CreaseStudy::default();
        MapSettings {
            waves: 4.0,
            elements_per_wave: 20,
            layer_elements: 2,
            substrate_elements: 25,
            depth: 50.0,
            imperfection: 0.05,
            seed: 0.01,
            post_buckling_range: 0.2,
            d_limit: 0.7,
            snap_budget: 0.5,

            crease_mesh: crease.mesh,
            fold_lengths: crease.fold_lengths,
            crease_scan: crease.scan,
            // Three meshes at most: a point's crease search within about twice its cost on one.
            crease_refinement: crease.refinement.map(|r| Refinement { max_meshes: 3, ..r }),
            crease_criterion: crease.criterion,
            keep_poisson: true,
            biaxial: None,
        }
    }
}

impl MapSettings {
    /// The crease search of every point (without the mesh check; each point's scan is then
    /// fitted to its `d_wrinkle`).
    pub fn crease_study(&self) -> CreaseStudy {
        CreaseStudy {
            mesh: self.crease_mesh,
            fold_lengths: self.fold_lengths.clone(),
            scan: self.crease_scan,
            criterion: self.crease_criterion,
            refinement: self.crease_refinement,
            lowest_only: true,
        }
    }

    fn validate(&self) -> Result<()> {
        if !(self.waves.is_finite() && self.waves >= 1.0 && (2.0 * self.waves).fract() == 0.0 && self.waves <= 50.0) {
            return Err(Error::invalid("waves", self.waves, "[1, 50] with 2 waves an integer"));
        }
        if !(4..=200).contains(&self.elements_per_wave) {
            return Err(Error::invalid("elements-per-wave", self.elements_per_wave, "[4, 200]"));
        }
        if !(self.post_buckling_range.is_finite() && self.post_buckling_range > 0.0 && self.post_buckling_range < 1.0) {
            return Err(Error::invalid(
                "post-buckling-range",
                self.post_buckling_range,
                "(0, 1)",
            ));
        }
        if !(self.seed.is_finite() && (0.0..1.0).contains(&self.seed)) {
            return Err(Error::invalid("seed", self.seed, "[0, 1)"));
        }
        let counts = [
            ("layer-elements", self.layer_elements, 16),
            ("substrate-elements", self.substrate_elements, 400),
            ("crease-nx", self.crease_mesh.nx, 2000),
            ("crease-layer-elements", self.crease_mesh.layer, 64),
            ("crease-substrate-elements", self.crease_mesh.substrate, 1000),
        ];
        for (name, count, most) in counts {
            if !(1..=most).contains(&count) {
                return Err(Error::invalid(name, count, &format!("[1, {most}]")));
            }
        }
        if let Some(biaxial) = self.biaxial {
            Modes {
                biaxial: Some(biaxial),
                theta: None,
            }
            .validate()?;
        }
        self.crease_study().validate()
    }
}

/// The map: a base parameter set, two axes and the settings of every point (`map-spec.json`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MapStudy {
    pub base: Parameters,
    pub x: Axis,
    pub y: Axis,
    pub settings: MapSettings,
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
}

impl MapStudy {
    pub fn validate(&self) -> Result<()> {
        self.x.validate("x", &self.base)?;
        self.y.validate("y", &self.base)?;
        if self.x.name == self.y.name {
            return Err(Error::invalid("y", &self.y.name, "a parameter other than --x"));
        }
        self.settings.validate()?;
        self.settings.crease_mesh.element.check_for(self.base.incompressible)?;
        for axis in [&self.x, &self.y] {
            if self.base.incompressible && axis.name.starts_with("K_") {
                return Err(Error::invalid(
                    if std::ptr::eq(axis, &self.x) { "x" } else { "y" },
                    &axis.name,
                    "a parameter incompressible tissue uses (K_l and K_s do not enter when incompressible = true)",
                ));
            }
        }
        for (_, parameters) in self.grid()? {
            parameters.validate()?;
        }
        Ok(())
    }

    /// Every point `(index, ix, iy, x, y)` with its parameter set, `index = iy * nx + ix`.
    #[allow(clippy::type_complexity)]
    pub fn grid(&self) -> Result<Vec<((usize, usize, usize, f64, f64), Parameters)>> {
        let (xs, ys) = (self.x.values(), self.y.values());
        let mut grid = Vec::with_capacity(xs.len() * ys.len());
        for (iy, &y) in ys.iter().enumerate() {
            for (ix, &x) in xs.iter().enumerate() {
                let mut p = self.base.clone();
                self.assign(&mut p, &self.x.name, x)?;
                self.assign(&mut p, &self.y.name, y)?;
                grid.push(((iy * xs.len() + ix, ix, iy, x, y), p));
            }
        }
        Ok(grid)
    }

    fn assign(&self, p: &mut Parameters, name: &str, value: f64) -> Result<()> {
        match self.settings.keep_poisson {
            true => p.set_number_keeping_poisson(name, value, &[&self.x.name, &self.y.name]),
            false => p.set_number(name, value),
        }
    }
}

/// What one `compute` did.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Computed {
    pub points: usize,
    pub reused: usize,
}

fn point_path(out: &Path, index: usize) -> PathBuf {
    out.join("points").join(format!("point-{index:05}.json"))
}

/// A point file and the study it was computed for.
#[derive(Serialize, Deserialize)]
struct PointFile {
    study: MapStudy,
    point: MapPoint,
}

/// Reads a finished point of `study` (None if absent; an error if it belongs to another map).
fn read_point(study: &MapStudy, out: &Path, index: usize) -> Result<Option<MapPoint>> {
    let path = point_path(out, index);
    let Ok(text) = std::fs::read_to_string(&path) else {
        return Ok(None);
    };
    let file: PointFile = serde_json::from_str(&text)
        .map_err(|e| Error::invalid("out", path.display(), &format!("a point file of fiberfold map ({e})")))?;
    if file.study != study.clone() {
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
fn claim_folder(study: &MapStudy, out: &Path) -> Result<()> {
    ensure_dir(&out.join("points"))?;
    let spec = out.join("map-spec.json");
    match std::fs::read_to_string(&spec) {
        Ok(text) => {
            let stored: MapStudy = serde_json::from_str(&text).map_err(|_| mismatch(out))?;
            if stored != *study {
                return Err(mismatch(out));
            }
            Ok(())
        }
        Err(_) => write_json_shared(&spec, study),
    }
}

/// Computes the points of `shard` (all without one) not yet in `out`, in parallel, each
/// written as soon as it is done; `tick` once per point of the share, reused ones first.
pub fn compute(study: &MapStudy, out: &Path, shard: Option<Shard>, tick: Tick) -> Result<Computed> {
    study.validate()?;
    claim_folder(study, out)?;
    let crease_study = study.settings.crease_study();
    let share: Vec<_> = study
        .grid()?
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
        let point = point::compute(&study.settings, &crease_study, at, parameters)?;
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

/// `map.json`.
#[derive(Clone, Debug, Serialize)]
pub struct MapReport {
    pub command: &'static str,
    pub study: MapStudy,
    pub points: Vec<MapPoint>,
    /// Sum over points of their wall time (s): the work, whatever the parallelism.
    pub point_seconds: f64,
    pub note: &'static str,
}

const MAP_NOTE: &str = "d_wrinkle: minimum of the linear theory's d_c(k) (minimum: interior, long_wave or \
    short_wave). d_crease: energy criterion of `fiberfold crease`, minimised over the fold lengths and converged \
    in the mesh, with its uncertainty d_crease_error. first: the smaller of the two, or too_close_to_call where they \
    differ by less than d_crease_error. d_wrinkle_biaxial and theta0 (with --biaxial R): the onset over \
    wavenumbers and directions of the surface under d_3 = R d, and the direction of its wave vector from X towards \
    Z (radians; the crests run perpendicular to it; empty where no direction is preferred). d_ellipticity_loss_fe: \
    the first d at which a finite-element state (crease search or nonlinear run) has a Gauss point without strong \
    ellipticity; beyond it the answer depends on the mesh. becomes (where the wrinkle has a wavelength and comes first): a nonlinear run of `waves` \
    wavelengths 2 pi / k0 to d_wrinkle + post_buckling_range; if the tangent's inertia changes along it \
    (d_secondary), the run is repeated seeded with that change's mode (secondary_half_waves across the domain); the \
    last state is classified: 'fold' if one trough is more than 20 % deeper than all others, \
    'period_doubling' if deep and shallow troughs alternate (spread above 20 %) or the surface's k/2 component is \
    at least 20 % of its k component, 'unresolved' if the path stayed periodic but its last state is unstable, 'crease' if the troughs stay alike but close on themselves, 'wrinkle' otherwise.";

/// Assembles the finished points of `study` in `out` into `map.csv`, `map.json` and the phase
/// diagram; refuses a folder of another map or with missing points.
pub fn collect(study: &MapStudy, out: &Path) -> Result<(MapReport, Vec<PathBuf>)> {
    study.validate()?;
    claim_folder(study, out)?;
    let grid = study.grid()?;
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
    let report = MapReport {
        command: "map",
        study: study.clone(),
        point_seconds: points.iter().map(|p| p.seconds.iter().sum::<f64>()).sum(),
        points,
        note: MAP_NOTE,
    };
    let mut files = vec![write_csv(&report, out)?];
    files.extend(figure::phase_diagram(&report, out)?);
    let json = out.join("map.json");
    write_json(&json, &report)?;
    files.push(json);
    Ok((report, files))
}

fn write_csv(report: &MapReport, out: &Path) -> Result<PathBuf> {
    let path = out.join("map.csv");
    let (x, y) = (report.study.x.name.as_str(), report.study.y.name.as_str());
    let mut table = CsvWriter::create(
        &path,
        &[
            "index",
            x,
            y,
            "d_wrinkle",
            "k0",
            "minimum",
            "d_crease",
            "d_crease_error",
            "crease_fold_length",
            "first",
            "becomes",
            "d_secondary",
            "secondary_half_waves",
            "d_first_contact",
            "d_reached",
            "d_wrinkle_biaxial",
            "theta0",
            "d_ellipticity_loss_fe",
            "seconds",
        ],
    )?;
    let number = |v: Option<f64>| v.map_or(Cell::Empty, Cell::Number);
    for p in &report.points {
        let minimum = p.minimum.map(|m| variant_name(&m)).unwrap_or_default();
        let (first, becomes) = (
            variant_name(&p.first),
            p.becomes.map(|b| variant_name(&b)).unwrap_or_default(),
        );
        table.append_cells(&[
            Cell::Number(p.index as f64),
            Cell::Number(p.x),
            Cell::Number(p.y),
            number(p.d_wrinkle),
            number(p.k0),
            Cell::Text(&minimum),
            number(p.d_crease),
            number(p.d_crease_error),
            number(p.crease_fold_length),
            Cell::Text(&first),
            Cell::Text(&becomes),
            number(p.d_secondary),
            number(p.secondary_half_waves.map(|m| m as f64)),
            number(p.d_first_contact),
            number(p.d_reached),
            number(p.d_wrinkle_biaxial),
            number(p.theta0),
            number(p.d_ellipticity_loss_fe),
            Cell::Number(p.seconds.iter().sum()),
        ])?;
    }
    Ok(path)
}

#[cfg(test)]
mod tests;
