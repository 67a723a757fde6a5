//! `fiberfold bench crease | map`: where the time of a crease onset and of a map goes. The crease
//! line splits one `crease` run (the default study) into the linear theory's onset and each mesh
//! of the sequence (folds searched, creased states solved, seconds); the map line times the
//! points of a 2 x 2 map one after the other, each split into its linear theory, its crease
//! search and its nonlinear run.

use super::crease::{crease, CreaseReport, CreaseStudy};
use super::grid::{Axis, GridStudy};
use super::map::{MapSettings, MapStudy};
use crate::error::Result;
use crate::parameters::Parameters;
use serde::Serialize;
use std::fmt;
use std::time::Instant;

/// One `crease` run, per phase.
#[derive(Clone, Debug, Serialize)]
pub struct CreaseBench {
    pub report: CreaseReport,
    pub seconds: f64,
}

/// Times `crease` of `params` with the default study.
pub fn crease_phases(params: &Parameters) -> Result<CreaseBench> {
    let clock = Instant::now();
    let report = crease(params, &CreaseStudy::default(), &|| {})?;
    Ok(CreaseBench {
        report,
        seconds: clock.elapsed().as_secs_f64(),
    })
}

impl fmt::Display for CreaseBench {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        let r = &self.report;
        let onset = |d: Option<f64>| d.map_or("none".to_string(), |d| format!("{d:.5}"));
        writeln!(
            f,
            "crease onset d_crease = {}, wrinkle onset d_wrinkle = {}, scan to d = {:.4}",
            onset(r.d_crease),
            onset(r.d_wrinkle),
            r.scan.to
        )?;
        writeln!(f)?;
        writeln!(f, "| phase | unknowns | folds | creased states | seconds |")?;
        writeln!(f, "|---|---:|---:|---:|---:|")?;
        writeln!(f, "| wrinkle onset (linear theory) | | | | {:.3} |", r.wrinkle_seconds)?;
        for m in r.meshes.iter().filter(|m| m.folds > 0) {
            writeln!(
                f,
                "| mesh x{} | {} | {} | {} | {:.2} |",
                m.factor, m.unknowns, m.folds, m.states, m.seconds
            )?;
        }
        writeln!(f, "| total | | | | {:.2} |", self.seconds)
    }
}

/// One map point's phases (s).
#[derive(Clone, Debug, Serialize)]
pub struct MapPointBench {
    pub x: f64,
    pub y: f64,
    pub first: String,
    pub becomes: String,
    /// Linear theory, crease search, nonlinear run.
    pub seconds: [f64; 3],
}

/// The points of a 2 x 2 map, one after the other.
#[derive(Clone, Debug, Serialize)]
pub struct MapBench {
    pub x: Axis,
    pub y: Axis,
    pub points: Vec<MapPointBench>,
    pub seconds: f64,
}

/// Times the map of `mu_l` in `[3, 10]` against `beta` in `[0, pi / 2]`, 2 x 2, on `params`
/// with the map's default settings, its points computed one after the other.
pub fn map_phases(params: &Parameters) -> Result<MapBench> {
    let axis = |name: &str, from: f64, to: f64| Axis {
        name: name.into(),
        from,
        to,
        points: 2,
        log: false,
    };
    let study = MapStudy {
        base: params.clone(),
        x: axis("mu_l", 3.0, 10.0),
        y: axis("beta", 0.0, std::f64::consts::FRAC_PI_2),
        settings: MapSettings::default(),
    };
    study.validate()?;
    let clock = Instant::now();
    let mut points = Vec::new();
    for (at, parameters) in study.grid()? {
        let point = study.compute_point(at, parameters, std::path::Path::new("."))?;
        points.push(MapPointBench {
            x: point.x,
            y: point.y,
            first: category(&point.first),
            becomes: point.becomes.as_ref().map_or("-".into(), category),
            seconds: point.seconds,
        });
    }
    Ok(MapBench {
        x: study.x,
        y: study.y,
        points,
        seconds: clock.elapsed().as_secs_f64(),
    })
}

/// A category by the name `map.csv` gives it.
fn category<T: Serialize>(value: &T) -> String {
    serde_json::to_value(value)
        .ok()
        .and_then(|v| v.as_str().map(str::to_string))
        .unwrap_or_default()
}

impl fmt::Display for MapBench {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        writeln!(
            f,
            "| {} | {} | first | becomes | linear (s) | crease (s) | nonlinear (s) |",
            self.x.name, self.y.name
        )?;
        writeln!(f, "|---:|---:|---|---|---:|---:|---:|")?;
        for p in &self.points {
            writeln!(
                f,
                "| {} | {:.4} | {} | {} | {:.3} | {:.2} | {:.2} |",
                p.x, p.y, p.first, p.becomes, p.seconds[0], p.seconds[1], p.seconds[2]
            )?;
        }
        let sum = |i: usize| self.points.iter().map(|p| p.seconds[i]).sum::<f64>();
        writeln!(f, "| total | | | | {:.3} | {:.2} | {:.2} |", sum(0), sum(1), sum(2))?;
        writeln!(f, "\nall points one after the other: {:.2} s", self.seconds)
    }
}
