//! The files of `fiberfold crease`: `crease_energy.csv` (every held fold, on every mesh),
//! `crease_released.csv` (every release), `crease.json` ([`CreaseReport`]) and `crease.png/svg`: the energy difference against `d`
//! for every fold on its finest mesh, the thresholds against the mesh size with their
//! extrapolation, and the crease at the onset.

use super::{crease, CreaseReport, CreaseStudy, Criterion};
use crate::error::Result;
use crate::material::Bilayer;
use crate::output::{ensure_dir, plot::save_panels, write_json, CsvWriter, Figure, LineStyle, Series};
use crate::parameters::Parameters;
use crate::studies::Tick;
use std::path::{Path, PathBuf};

/// Columns of `crease_energy.csv`.
const COLUMNS: [&str; 10] = [
    "fold_length",
    "mesh",
    "d",
    "difference",
    "scaled_difference",
    "depth",
    "min_J",
    "tensile_nodes",
    "ellipticity_layer",
    "ellipticity_substrate",
];

/// Columns of `crease_released.csv` (`reopened` is 1 where the fold opened to the flat state).
const RELEASED_COLUMNS: [&str; 11] = [
    "fold_length",
    "mesh",
    "d",
    "difference",
    "held_difference",
    "closed_length",
    "contact_length",
    "reopened",
    "pressed_nodes",
    "pulling_nodes",
    "depth",
];

/// Runs the study and writes its files into `out`.
pub fn run(params: &Parameters, study: &CreaseStudy, out: &Path, tick: Tick) -> Result<(CreaseReport, Vec<PathBuf>)> {
    let report = crease(params, study, tick)?;
    ensure_dir(out)?;
    let csv = out.join("crease_energy.csv");
    let mut table = CsvWriter::create(&csv, &COLUMNS)?;
    for fold in &report.folds {
        for (m, on_mesh) in fold.meshes.iter().enumerate() {
            for e in &on_mesh.evaluations {
                table.append(&[
                    fold.fold_length,
                    report.meshes[m].factor as f64,
                    e.strain,
                    e.difference,
                    e.scaled_difference,
                    e.depth,
                    e.min_jacobian,
                    e.tensile_nodes as f64,
                    e.ellipticity.layer,
                    e.ellipticity.substrate,
                ])?;
            }
        }
    }
    let released = out.join("crease_released.csv");
    let mut table = CsvWriter::create(&released, &RELEASED_COLUMNS)?;
    for fold in &report.folds {
        for (m, on_mesh) in fold.meshes.iter().enumerate() {
            for r in &on_mesh.released_evaluations {
                table.append(&[
                    fold.fold_length,
                    report.meshes[m].factor as f64,
                    r.strain,
                    r.difference,
                    r.held_difference,
                    r.closed_length,
                    r.contact_length,
                    f64::from(u8::from(r.reopened)),
                    r.pressed_nodes as f64,
                    r.pulling_nodes as f64,
                    r.depth,
                ])?;
            }
        }
    }
    let mut files = vec![csv, released];
    files.extend(save_panels(&panels(&report), out, "crease")?);
    let json = out.join("crease.json");
    write_json(&json, &report)?;
    files.push(json);
    Ok((report, files))
}

fn panels(report: &CreaseReport) -> Vec<Figure> {
    let mut energy = Figure::new(
        "Energy of a seeded crease against the flat state (finest mesh)",
        "end-shortening d = 1 - lambda_1",
        "(U_crease - U_flat) / (mu_l a^2)",
    );
    let mut sequence = Figure::new(
        "Threshold d(a) against the mesh size (h = 1: base mesh), extrapolated to h = 0",
        "relative mesh size h = 1 / factor",
        "threshold d(a)",
    );
    for (i, fold) in report.folds.iter().enumerate() {
        let label = match fold.extrapolated {
            Some(e) => match e.error {
                Some(error) => format!("a = {} H: d = {:.4} +- {error:.1e}", fold.fold_length, e.value),
                None => format!("a = {} H: d = {:.4} (one mesh)", fold.fold_length, e.value),
            },
            None => format!("a = {} H: no crease in the scan", fold.fold_length),
        };
        let finest = fold.finest().or(fold.meshes.last());
        let points = finest
            .map(|f| f.evaluations.iter().map(|e| (e.strain, e.scaled_difference)).collect())
            .unwrap_or_default();
        let held_label = match report.criterion {
            Criterion::Held => label.clone(),
            Criterion::Released => format!("a = {} H, held", fold.fold_length),
        };
        energy
            .series
            .push(Series::new(held_label, points, LineStyle::DotsAndLine, i));
        let released_points = finest.is_some_and(|f| f.released_evaluations.iter().any(|r| !r.reopened));
        if report.criterion == Criterion::Released && released_points {
            let mu = Bilayer::new(&report.parameters).layer.energy.shear_modulus();
            let scale = mu * fold.fold_length * fold.fold_length;
            let points: Vec<(f64, f64)> = finest
                .map(|f| {
                    f.released_evaluations
                        .iter()
                        .filter(|r| !r.reopened)
                        .map(|r| (r.strain, r.difference / scale))
                        .collect()
                })
                .unwrap_or_default();
            energy
                .series
                .push(Series::new(format!("{label}, released"), points, LineStyle::Circles, i));
        }
        let mut thresholds: Vec<(f64, f64)> = fold
            .thresholds
            .iter()
            .enumerate()
            .filter_map(|(m, d)| d.map(|d| (1.0 / report.meshes[m].factor as f64, d)))
            .collect();
        if let Some(e) = fold.extrapolated.filter(|e| e.order.is_some()) {
            thresholds.push((0.0, e.value));
        }
        if !thresholds.is_empty() {
            sequence
                .series
                .push(Series::new(label, thresholds, LineStyle::DotsAndLine, i));
        }
    }
    // The sequence of meshes has a panel where there is one (not with `--no-convergence`).
    let mut panels = vec![energy];
    if sequence.series.iter().any(|s| s.points.len() > 1) {
        panels.push(sequence);
    }
    let fold = report
        .fold_length
        .and_then(|a| report.folds.iter().find(|f| f.fold_length == a));
    if let Some(at) = fold.and_then(|f| f.finest()).and_then(|f| f.at_threshold()) {
        let a = at.fold_length;
        let surface: Vec<(f64, f64)> = at.surface.iter().copied().filter(|p| p.0 <= 4.0 * a).collect();
        panels.push(
            Figure::new(
                format!("fold held at d = {:.4} (a = {a} H, finest mesh), mirrored", at.strain),
                "current x / H",
                "current y / H",
            )
            .with(Series::new("surface", surface.clone(), LineStyle::Solid, 0))
            .with(Series::new(
                "",
                surface.iter().map(|&(x, y)| (-x, y)).collect(),
                LineStyle::Solid,
                0,
            )),
        );
    }
    panels
}
