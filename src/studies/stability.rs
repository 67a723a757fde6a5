//! Linear-stability studies: the dispersion curve `d_c(k)`, the onset, and parameter sweeps.

use super::orientation::{directed_onset, orientation_figure, DirectedOnset, Modes};
use super::{linspace, validate_points, Tick};
use crate::error::{Error, Result};
use crate::output::table::{variant_name, Cell};
use crate::output::ticks::AxisScale;
use crate::output::{ensure_dir, plot::save_panels, write_json, CsvWriter, Figure, LineStyle, Series};
use crate::parameters::{Load, Parameters};
use crate::stability::{Method, Minimum, Onset, StabilityAnalysis, SurfaceOnset, K_MAX};
use rayon::prelude::*;
use serde::Serialize;
use std::path::{Path, PathBuf};

/// The solver of the linear stability problem, by name.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum Solver {
    /// Stroh formalism: each layer's solutions growing and decaying through its thickness (any
    /// k, any K/mu).
    #[default]
    Exact,
    /// Quadratic finite elements in Y on a truncated graded depth (cross-check; slower; locks as
    /// K/mu grows, and its error grows with k).
    Discrete,
}

impl Solver {
    /// The solver called `exact` or `discrete`.
    pub fn from_name(name: &str) -> Result<Self> {
        <Solver as clap::ValueEnum>::from_str(name, false)
            .map_err(|_| Error::invalid("method", name, "exact or discrete"))
    }

    /// The method of the analysis (the discrete one with its default depth and elements).
    pub fn method(self) -> Method {
        match self {
            Solver::Exact => Method::Exact,
            Solver::Discrete => Method::Discrete(crate::stability::discrete::DiscreteOptions::default()),
        }
    }
}

/// Checks that every wavenumber is in `(0, K_MAX]`.
pub fn check_wavenumbers(ks: &[f64]) -> Result<()> {
    match ks.iter().find(|k| !(k.is_finite() && **k > 0.0 && **k <= K_MAX)) {
        Some(&bad) => Err(Error::invalid(
            "k",
            bad,
            &format!("(0, {K_MAX}] (beyond kH = {K_MAX} the layer acts as a half-space)"),
        )),
        None => Ok(()),
    }
}

/// `d_c(k)` on equally spaced wavenumbers.
#[derive(Clone, Copy, Debug)]
pub struct DispersionStudy {
    pub k_min: f64,
    pub k_max: f64,
    pub points: usize,
    pub method: Method,
    /// Plane strain, or waves along one direction of the surface (`theta`, default 0).
    pub modes: Modes,
}

impl DispersionStudy {
    pub fn validate(&self) -> Result<()> {
        if !(self.k_min.is_finite() && self.k_min > 0.0) {
            return Err(Error::invalid("k-min", self.k_min, "(0, k-max)"));
        }
        if !(self.k_max.is_finite() && self.k_max > self.k_min && self.k_max <= K_MAX) {
            return Err(Error::invalid(
                "k-max",
                self.k_max,
                &format!(
                    "(k-min = {}, {K_MAX}] (beyond kH = {K_MAX} the layer acts as a half-space)",
                    self.k_min
                ),
            ));
        }
        validate_points("points", self.points, 2)
    }
}

/// One dispersion curve: the points with a root, and the wavenumbers without one.
#[derive(Clone, Debug, Serialize)]
pub struct DispersionCurve {
    /// `(k, d_c)` where a bifurcation exists before the search limit.
    pub points: Vec<(f64, f64)>,
    /// Wavenumbers without a bifurcation before 0.95 or the loss of ellipticity.
    pub no_root: Vec<f64>,
}

impl DispersionCurve {
    /// Computes `d_c(k)` along the wavenumbers, continuing each root from the previous one.
    pub fn compute(analysis: &StabilityAnalysis, ks: &[f64], tick: Tick) -> Result<Self> {
        let mut curve = DispersionCurve {
            points: Vec::new(),
            no_root: Vec::new(),
        };
        let mut hint = None;
        for &k in ks {
            match analysis.critical_compression_near(k, hint) {
                Ok(d) => {
                    curve.points.push((k, d));
                    hint = Some(d);
                }
                Err(Error::NoRoot { .. }) => {
                    curve.no_root.push(k);
                    hint = None;
                }
                Err(e) => return Err(e),
            }
            tick();
        }
        Ok(curve)
    }
}

#[derive(Serialize)]
struct DispersionSummary<'a> {
    command: &'static str,
    parameters: &'a Parameters,
    method: String,
    onset: &'a Onset,
    k_without_root: &'a [f64],
    files: Vec<String>,
}

/// Writes `dispersion.csv` (`k,theta,d_c,lambda1_c`), `dispersion.json` and `dispersion.png/svg`.
pub fn dispersion(params: &Parameters, study: &DispersionStudy, out: &Path, tick: Tick) -> Result<Vec<PathBuf>> {
    study.validate()?;
    let modes = study.modes.along_one_direction();
    let analysis = modes.analysis(params, study.method)?;
    ensure_dir(out)?;
    let curve = DispersionCurve::compute(&analysis, &linspace(study.k_min, study.k_max, study.points), tick)?;
    let onset = analysis.onset()?;
    let theta = modes.theta.unwrap_or(0.0);
    let csv = out.join("dispersion.csv");
    // Under growth the critical growth g_c = 1 / (1 - d_c) is the load, and is plotted.
    let load = params.load;
    let mut header = vec!["k", "theta", "d_c", "lambda1_c"];
    header.extend(load.is_growth().then_some("g_c"));
    let mut table = CsvWriter::create(&csv, &header)?;
    for &(k, d) in &curve.points {
        let row = [k, theta, d, 1.0 - d, load.parameter(d)];
        table.append(&row[..header.len()])?;
    }
    let (name, critical) = if load.is_growth() {
        ("g_c", load.parameter(onset.d_c))
    } else {
        ("d_c", onset.d_c)
    };
    let points: Vec<(f64, f64)> = curve.points.iter().map(|&(k, d)| (k, load.parameter(d))).collect();
    let figure = Figure::new(
        format!(
            "{name}(k), beta = {:.1} deg, {}",
            params.beta.to_degrees(),
            match (modes.surface(), modes.theta) {
                (None, _) => "plane strain".to_string(),
                (Some(s), Some(theta)) => format!("d_3 = {} d, theta = {:.1} deg", s.biaxial, theta.to_degrees()),
                (Some(s), None) => format!("d_3 = {} d", s.biaxial),
            }
        ),
        "wavenumber k H",
        if load.is_growth() {
            "critical growth g_c"
        } else {
            "critical compression d_c"
        },
    )
    .with(Series::new(format!("{name}(k)"), points, LineStyle::Solid, 0))
    .with(match onset.minimum {
        Minimum::Interior => Series::new(
            format!("k0 = {:.4}, {name} = {critical:.4}", onset.k0),
            vec![(onset.k0, critical)],
            LineStyle::Crosses,
            1,
        ),
        limit => Series::new(
            match limit {
                Minimum::Flat => format!("flat: {name} = {critical:.4} at every k"),
                Minimum::LongWave => format!("no interior minimum: {name} -> {critical:.4} as k -> 0"),
                _ => format!("no interior minimum: {name} -> {critical:.4} as k -> inf"),
            },
            vec![(study.k_min, critical), (study.k_max, critical)],
            LineStyle::Dashed,
            1,
        ),
    });
    let mut files = vec![csv];
    files.extend(figure.save(out, "dispersion")?);
    let json = out.join("dispersion.json");
    let summary = DispersionSummary {
        command: "dispersion",
        parameters: params,
        method: format!("{:?}", study.method),
        onset: &onset,
        k_without_root: &curve.no_root,
        files: files.iter().map(|f| f.display().to_string()).collect(),
    };
    write_json(&json, &summary)?;
    files.push(json);
    Ok(files)
}

/// The content of `onset.json`.
#[derive(Clone, Debug, Serialize)]
pub struct OnsetSummary {
    /// What loads the bilayer: `compression`, `growth` or `uniform_growth`.
    pub load: Load,
    pub k0: f64,
    /// The critical strain: the end-shortening under compression, `1 - 1/g_c` under growth.
    pub d_c: f64,
    /// The critical growth `1 / (1 - d_c)` under a growth load (null under compression).
    pub g_c: Option<f64>,
    pub lambda1_c: f64,
    pub d_ellipticity_loss: Option<f64>,
    /// Where the homogeneous state leaves a law's domain (Gent), if before 0.95.
    pub d_domain_end: Option<f64>,
    /// `2 pi / k0` of an interior minimum (null for a long- or short-wave limit).
    pub wavelength: Option<f64>,
    /// `interior`, `long_wave` (`k0 = 0`, `d_c` the `k -> 0` limit: the substrate's own surface
    /// instability) or `short_wave` (`k0` infinite, null: the layer's own).
    pub minimum: Minimum,
    /// `d_3 / d` of a surface analysis (null: the paper's plane strain).
    pub biaxial: Option<f64>,
    /// Direction of the first wrinkles' wave vector in the surface, radians from X towards Z
    /// (the crests run perpendicular to it): 0 in plane strain, null where every direction
    /// has the same onset.
    pub theta0: f64,
    /// How much the onset depends on the direction: the largest onset over directions minus
    /// `d_c` (null unless the direction was searched).
    pub direction_spread: Option<f64>,
    pub method: String,
    pub parameters: Parameters,
}

impl OnsetSummary {
    /// The onset of `params` by `method` over `modes`.
    pub fn new(params: &Parameters, method: Method, modes: &Modes) -> Result<Self> {
        Ok(Self::of(params, method, modes, &directed_onset(params, method, modes)?))
    }

    fn of(params: &Parameters, method: Method, modes: &Modes, directed: &DirectedOnset) -> Self {
        let onset = directed.onset;
        OnsetSummary {
            load: params.load,
            k0: onset.k0,
            d_c: onset.d_c,
            g_c: params.load.is_growth().then(|| params.load.parameter(onset.d_c)),
            lambda1_c: onset.lambda1_c,
            d_ellipticity_loss: onset.d_ellipticity_loss,
            d_domain_end: onset.d_domain_end,
            wavelength: onset.wavelength(),
            minimum: onset.minimum,
            biaxial: modes.surface().map(|s| s.biaxial),
            theta0: directed.theta0,
            direction_spread: directed.direction_spread,
            method: format!("{method:?}"),
            parameters: params.clone(),
        }
    }
}

/// Writes `onset.json` (`k0`, `d_c`, `lambda1_c`, `theta0`, `d_ellipticity_loss` and the
/// parameters) and, for waves in every direction of the surface, `orientation.csv` and the
/// polar figure `orientation.png/svg`.
pub fn onset(params: &Parameters, method: Method, modes: &Modes, out: &Path) -> Result<(OnsetSummary, Vec<PathBuf>)> {
    let directed = directed_onset(params, method, modes)?;
    let summary = OnsetSummary::of(params, method, modes, &directed);
    ensure_dir(out)?;
    let path = out.join("onset.json");
    write_json(&path, &summary)?;
    let mut files = vec![path];
    if modes.theta.is_none() {
        files.extend(orientation_figure(params, method, modes, &directed, out)?);
    }
    Ok((summary, files))
}

/// A sweep of one numeric parameter, optionally repeated for several values of another.
#[derive(Clone, Debug)]
pub struct SweepStudy {
    pub param: String,
    pub from: f64,
    pub to: f64,
    pub points: usize,
    /// `(key, values)`: one curve per value.
    pub series: Option<(String, Vec<f64>)>,
    /// The swept values themselves, instead of `points` equally spaced from `from` to `to`.
    pub values: Option<Vec<f64>>,
    pub method: Method,
    /// Plane strain, or waves in the surface (the onset's direction `theta0` searched unless
    /// `theta` is given).
    pub modes: Modes,
    /// Scale the bulk modulus with a swept shear modulus (`K_l` with `mu_l`, `K_s` with `mu_s`),
    /// keeping the base set's Poisson ratio, as a map does.
    pub keep_poisson: bool,
}

/// Parses `KEY=V1,V2,...` for `--series`.
pub fn parse_series(text: &str) -> Result<(String, Vec<f64>)> {
    let (key, values) = text
        .split_once('=')
        .ok_or_else(|| Error::invalid("series", text, "KEY=V1,V2,... with KEY a numeric parameter"))?;
    let values = values
        .split(',')
        .map(|v| crate::parameters::parse_number("series", v.trim()))
        .collect::<Result<Vec<_>>>()?;
    Ok((key.trim().to_string(), values))
}

/// One swept point's onset (None: no wrinkling before 0.95 or the loss of ellipticity).
#[derive(Clone, Debug, Serialize)]
pub struct SweepPoint {
    pub series: Option<f64>,
    pub value: f64,
    pub onset: Option<Onset>,
    /// The direction of the onset's wave vector (radians from X): 0 in plane strain, NaN
    /// (null) where none is preferred or there is no onset.
    pub theta0: f64,
}

impl SweepStudy {
    /// Parameter sets for every point, all validated before any work starts.
    fn parameter_sets(&self, base: &Parameters) -> Result<Vec<(Option<f64>, f64, Parameters)>> {
        let numeric = |key: &str| match base.number(key) {
            Ok(_) => Ok(()),
            Err(_) => Err(Error::invalid(
                "param",
                key,
                &format!(
                    "a numeric parameter of the laws in use: {}",
                    base.numeric_keys().join(", ")
                ),
            )),
        };
        numeric(&self.param)?;
        let values = match &self.values {
            Some(values) => {
                if values.is_empty() {
                    return Err(Error::invalid("values", "[]", "at least one value"));
                }
                values.clone()
            }
            None => {
                validate_points("points", self.points, 1)?;
                for (name, v) in [("from", self.from), ("to", self.to)] {
                    if !v.is_finite() {
                        return Err(Error::invalid(name, v, "a finite number"));
                    }
                }
                linspace(self.from, self.to, self.points)
            }
        };
        let series: Vec<Option<f64>> = match &self.series {
            Some((key, values)) => {
                numeric(key)?;
                values.iter().map(|v| Some(*v)).collect()
            }
            None => vec![None],
        };
        let mut sets = Vec::new();
        for s in series {
            for &value in &values {
                let mut p = base.clone();
                let series_key = self.series.as_ref().map_or("", |(key, _)| key.as_str());
                let apart = [series_key, self.param.as_str()];
                let assign = |p: &mut Parameters, key: &str, v: f64| match self.keep_poisson {
                    true => p.set_number_keeping_poisson(key, v, &apart),
                    false => p.set_number(key, v),
                };
                if let Some(v) = s {
                    assign(&mut p, series_key, v)?;
                }
                assign(&mut p, &self.param, value)?;
                p.validate()?;
                sets.push((s, value, p));
            }
        }
        Ok(sets)
    }

    /// The onset at every point: series in parallel, each continued along the swept values.
    pub fn compute(&self, base: &Parameters, tick: Tick) -> Result<Vec<SweepPoint>> {
        let sets = self.parameter_sets(base)?;
        let curves: Vec<Vec<(Option<f64>, f64, Parameters)>> =
            sets.chunk_by(|a, b| a.0 == b.0).map(|chunk| chunk.to_vec()).collect();
        let results: Vec<Vec<SweepPoint>> = curves
            .into_par_iter()
            .map(|curve| {
                let mut previous: Option<SurfaceOnset> = None;
                let mut points = Vec::with_capacity(curve.len());
                for (series, value, p) in curve {
                    let analysis = self.modes.analysis(&p, self.method)?;
                    let directed = match self.directed_onset(&analysis, previous.as_ref()) {
                        Ok(o) => Some(o),
                        Err(Error::NoRoot { .. }) => None,
                        Err(e) => return Err(e),
                    };
                    previous = directed;
                    tick();
                    points.push(SweepPoint {
                        series,
                        value,
                        onset: directed.map(|d| d.onset),
                        theta0: directed.map_or(f64::NAN, |d| d.theta0),
                    });
                }
                Ok(points)
            })
            .collect::<Result<_>>()?;
        Ok(results.into_iter().flatten().collect())
    }

    /// The onset of `analysis` with its direction, continued from the previous point's.
    fn directed_onset(&self, analysis: &StabilityAnalysis, previous: Option<&SurfaceOnset>) -> Result<SurfaceOnset> {
        let searched = self.modes.surface().is_some() && self.modes.theta.is_none();
        match (searched, previous) {
            (true, None) => analysis.surface_onset(),
            (true, Some(p)) => analysis.surface_onset_near(p),
            (false, p) => Ok(SurfaceOnset {
                onset: p.map_or_else(|| analysis.onset(), |o| analysis.onset_near(&o.onset))?,
                theta0: self.modes.theta.unwrap_or(0.0),
                direction_spread: f64::NAN,
            }),
        }
    }

    /// Number of onsets to compute (for progress bars).
    pub fn onsets(&self) -> usize {
        let points = self.values.as_ref().map_or(self.points, Vec::len);
        points * self.series.as_ref().map_or(1, |(_, v)| v.len())
    }
}

#[derive(Serialize)]
struct SweepSummary<'a> {
    command: &'static str,
    parameters: &'a Parameters,
    param: &'a str,
    series_param: Option<&'a str>,
    /// Whether a swept shear modulus took its bulk modulus along (Poisson's ratio kept).
    keep_poisson: bool,
    points: &'a [SweepPoint],
}

/// A parameter's name with its unit, for an axis (angles in degrees: [`parameter_scale`]).
pub(crate) fn parameter_axis(name: &str) -> String {
    match name {
        "beta" => "fibre angle beta (deg)".into(),
        "psi" => "fibre azimuth psi (deg)".into(),
        "mu_l" | "K_l" | "mu_s" | "K_s" | "mu_f" => format!("{name} (units of mu_s)"),
        other => format!("{other} (-)"),
    }
}

/// How an axis of the parameter `name` shows its values: the fibres' angles, held in radians,
/// in degrees.
pub(crate) fn parameter_scale(name: &str) -> AxisScale {
    match name {
        "beta" | "psi" => AxisScale::Degrees,
        _ => AxisScale::Linear,
    }
}

/// Writes `sweep.csv` (`series,value,k0,d_c,minimum,theta0`; `k0` empty where the minimum is a
/// long- or short-wave limit, `theta0` where no direction is preferred), `sweep.json` and
/// `sweep.png/svg` (limits marked by crosses; a third panel of `theta0` when the direction is
/// searched).
pub fn sweep(params: &Parameters, study: &SweepStudy, out: &Path, tick: Tick) -> Result<Vec<PathBuf>> {
    let points = study.compute(params, tick)?;
    ensure_dir(out)?;
    let csv = out.join("sweep.csv");
    let mut table = CsvWriter::create(&csv, &["series", "value", "k0", "d_c", "minimum", "theta0"])?;
    let label = |s: Option<f64>| match (&study.series, s) {
        (Some((key, _)), Some(v)) => format!("{key}={v}"),
        _ => "base".to_string(),
    };
    for p in &points {
        if let Some(o) = &p.onset {
            let k0 = if o.minimum == Minimum::Interior {
                Cell::Number(o.k0)
            } else {
                Cell::Empty
            };
            let minimum = variant_name(&o.minimum);
            table.append_cells(&[
                Cell::Text(&label(p.series)),
                Cell::Number(p.value),
                k0,
                Cell::Number(o.d_c),
                Cell::Text(&minimum),
                if p.theta0.is_finite() {
                    Cell::Number(p.theta0)
                } else {
                    Cell::Empty
                },
            ])?;
        }
    }
    let axis = parameter_axis(&study.param);
    let scale = parameter_scale(&study.param);
    let mut k_panel = Figure::new("Onset wavenumber", axis.as_str(), "onset wavenumber k0 H").with_x_scale(scale);
    let mut d_panel =
        Figure::new("Critical compression", axis.as_str(), "critical compression d_c").with_x_scale(scale);
    let mut series_values: Vec<Option<f64>> = points.iter().map(|p| p.series).collect();
    series_values.dedup();
    for (i, s) in series_values.iter().enumerate() {
        // Where the onset is not of the kind asked for (or there is none), a gap: the curve of
        // interior minima is broken there rather than drawn across.
        let of = |pick: fn(&Onset) -> f64, interior: bool| -> Vec<(f64, f64)> {
            points
                .iter()
                .filter(|p| p.series == *s)
                .map(|p| match &p.onset {
                    Some(o) if (o.minimum == Minimum::Interior) == interior => (p.value, pick(o)),
                    _ => (p.value, f64::NAN),
                })
                .collect()
        };
        k_panel
            .series
            .push(Series::new(label(*s), of(|o| o.k0, true), LineStyle::Solid, i));
        d_panel
            .series
            .push(Series::new(label(*s), of(|o| o.d_c, true), LineStyle::Solid, i));
        let limits = of(|o| o.d_c, false);
        if limits.iter().any(|(_, d)| d.is_finite()) {
            let name = format!("{}: no interior minimum (limit k -> 0 or inf)", label(*s));
            d_panel.series.push(Series::new(name, limits, LineStyle::Crosses, i));
        }
    }
    let mut panels = vec![k_panel, d_panel];
    if study.modes.surface().is_some() && study.modes.theta.is_none() {
        let mut theta_panel = Figure::new(
            "Direction of the first wrinkles",
            axis.as_str(),
            "theta0 (deg, wave vector from X)",
        )
        .with_x_scale(scale);
        for (i, s) in series_values.iter().enumerate() {
            let directions: Vec<(f64, f64)> = points
                .iter()
                .filter(|p| p.series == *s && p.theta0.is_finite())
                .map(|p| (p.value, p.theta0.to_degrees()))
                .collect();
            theta_panel
                .series
                .push(Series::new(label(*s), directions, LineStyle::Circles, i));
        }
        theta_panel.y_range = Some((-5.0, 185.0));
        panels.push(theta_panel);
    }
    let mut files = vec![csv];
    files.extend(save_panels(&panels, out, "sweep")?);
    let json = out.join("sweep.json");
    let summary = SweepSummary {
        command: "sweep",
        parameters: params,
        param: &study.param,
        series_param: study.series.as_ref().map(|(k, _)| k.as_str()),
        keep_poisson: study.keep_poisson,
        points: &points,
    };
    write_json(&json, &summary)?;
    files.push(json);
    Ok(files)
}
