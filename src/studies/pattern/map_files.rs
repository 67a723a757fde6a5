//! The files of a map of patterns: `map.csv`, `map.json` and the figure `map.png/svg`
//! ([`super::map_figure`]), assembled from the finished points.

use super::map::{PatternMap, PatternMapReport, PatternPoint};
use super::map_figure::pattern_map;
use crate::error::Result;
use crate::output::table::{variant_name, Cell};
use crate::output::{write_json, CsvWriter};
use crate::studies::grid;
use std::path::{Path, PathBuf};

/// Assembles the finished points of `map` in `out` into `map.csv`, `map.json` and the figure
/// `map.png/svg`; refuses a folder of another map or with missing points.
pub fn collect(map: &PatternMap, out: &Path) -> Result<(PatternMapReport, Vec<PathBuf>)> {
    map.validate()?;
    let points = grid::finished_points(map, out)?;
    let report = PatternMapReport {
        command: "pattern",
        map: map.clone(),
        point_seconds: points.iter().map(|p| p.seconds).sum(),
        points,
    };
    let mut files = vec![write_csv(&report, out)?];
    files.extend(pattern_map(&report, out)?);
    let json = out.join("map.json");
    write_json(&json, &report)?;
    files.push(json);
    Ok((report, files))
}

/// What became of a point: `followed` (its path reached its end), `stopped` (before it),
/// `onset` (no path asked: the mode classified), `failed`.
fn outcome(p: &PatternPoint, followed: bool) -> &'static str {
    match (&p.failed, &p.stopped, followed) {
        (Some(_), ..) => "failed",
        (None, Some(_), _) => "stopped",
        (None, None, true) => "followed",
        (None, None, false) => "onset",
    }
}

fn write_csv(report: &PatternMapReport, out: &Path) -> Result<PathBuf> {
    let path = out.join("map.csv");
    let (x, y) = (report.map.x.name.as_str(), report.map.y.name.as_str());
    let mut table = CsvWriter::create(
        &path,
        &[
            "index",
            x,
            y,
            "d_c",
            "theta0_degrees",
            "d_bifurcation",
            "relative_difference",
            "unknowns",
            "d",
            "pattern",
            "amplitude",
            "theta1_degrees",
            "share1",
            "theta2_degrees",
            "share2",
            "branches_left",
            "outcome",
            "seconds",
        ],
    )?;
    let number = |v: Option<f64>| v.map_or(Cell::Empty, Cell::Number);
    for p in &report.points {
        let pattern = p.pattern.map(|v| variant_name(&v)).unwrap_or_default();
        let direction = |i: usize| p.directions.get(i);
        table.append_cells(&[
            Cell::Number(p.index as f64),
            Cell::Number(p.x),
            Cell::Number(p.y),
            number(p.d_c),
            number(p.theta0_degrees),
            number(p.d_bifurcation),
            number(p.relative_difference),
            number(p.unknowns.map(|n| n as f64)),
            number(p.d),
            Cell::Text(&pattern),
            number(p.amplitude),
            number(direction(0).map(|d| d.wave.theta_degrees)),
            number(direction(0).map(|d| d.share)),
            number(direction(1).map(|d| d.wave.theta_degrees)),
            number(direction(1).map(|d| d.share)),
            Cell::Number(p.branches_left.len() as f64),
            Cell::Text(outcome(p, report.map.study.path.is_some())),
            Cell::Number(p.seconds),
        ])?;
    }
    Ok(path)
}
