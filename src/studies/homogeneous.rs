//! The homogeneous-state table and the paper's Fig. 2.

use super::{linspace, validate_points, Tick};
use crate::error::{Error, Result};
use crate::homogeneous::HomogeneousRow;
use crate::material::Bilayer;
use crate::output::{write_json, CsvWriter, Figure, LineStyle, Series};
use crate::parameters::{validate_compression, Parameters};
use serde::Serialize;
use std::path::{Path, PathBuf};

/// Range of the homogeneous-state table.
#[derive(Clone, Copy, Debug)]
pub struct HomogeneousStudy {
    /// Largest end-shortening d (under a growth load the strain `1 - 1/g`).
    pub d_max: f64,
    /// Number of equally spaced d values from 0 to `d_max`.
    pub points: usize,
}

impl Default for HomogeneousStudy {
    fn default() -> Self {
        HomogeneousStudy {
            d_max: 0.5,
            points: 101,
        }
    }
}

#[derive(Serialize)]
struct Summary<'a> {
    command: &'static str,
    parameters: &'a Parameters,
    d_max: f64,
    points: usize,
    at_d_max: &'a HomogeneousRow,
    /// The first `d` of the grid whose state lies beyond a law's domain (the table ends before).
    stopped_at: Option<f64>,
    files: Vec<String>,
}

pub const CSV_HEADER: [&str; 14] = [
    "d",
    "lambda1",
    "lambda2_layer",
    "lambda2_substrate",
    "J_layer",
    "J_substrate",
    "sigma11_layer",
    "sigma22_layer",
    "sigma33_layer",
    "sigma11_substrate",
    "sigma22_substrate",
    "sigma33_substrate",
    "growth_layer",
    "growth_substrate",
];

impl HomogeneousStudy {
    pub fn validate(&self) -> Result<()> {
        validate_compression("d-max", self.d_max)?;
        validate_points("points", self.points, 2)
    }
}

/// One row of `homogeneous.csv`, in the order of [`CSV_HEADER`].
pub fn columns(r: &HomogeneousRow) -> [f64; 14] {
    let s = &r.state;
    let (l, m) = (&r.layer_stress, &r.substrate_stress);
    [
        s.d,
        s.lambda1,
        s.lambda2_layer,
        s.lambda2_substrate,
        s.lambda1 * s.lambda2_layer,
        s.lambda1 * s.lambda2_substrate,
        l[0],
        l[2],
        l[3],
        m[0],
        m[2],
        m[3],
        s.growth_layer,
        s.growth_substrate,
    ]
}

/// What `run` wrote, and where the table stopped short of `d_max` (a Gent law's limiting
/// extensibility reached at that `d`, with the reason).
pub struct HomogeneousOutcome {
    pub files: Vec<PathBuf>,
    pub stopped: Option<(f64, String)>,
}

/// The columns of `homogeneous.csv` at each `d` (each checked to be a compression in `[0, 1)`).
pub fn table(params: &Parameters, ds: &[f64]) -> Result<Vec<[f64; 14]>> {
    params.validate()?;
    let materials = Bilayer::new(params);
    ds.iter()
        .map(|&d| {
            validate_compression("d", d)?;
            HomogeneousRow::new(&materials, d).map(|r| columns(&r))
        })
        .collect()
}

/// Computes the table, writes `homogeneous.csv`, `homogeneous.json`, `fig2.png`, `fig2.svg`.
/// A state beyond a law's domain ends the table there; the rows before it are written.
pub fn run(params: &Parameters, study: &HomogeneousStudy, out: &Path, tick: Tick) -> Result<HomogeneousOutcome> {
    params.validate()?;
    study.validate()?;
    crate::output::ensure_dir(out)?;
    let materials = Bilayer::new(params);
    let mut rows = Vec::new();
    let mut stopped = None;
    for d in linspace(0.0, study.d_max, study.points) {
        match HomogeneousRow::new(&materials, d) {
            Ok(row) => rows.push(row),
            Err(e @ Error::BeyondExtensibility { .. }) if rows.len() >= 2 => {
                stopped = Some((d, e.to_string()));
                break;
            }
            Err(e) => return Err(e),
        }
        tick();
    }

    let csv = out.join("homogeneous.csv");
    let mut table = CsvWriter::create(&csv, &CSV_HEADER)?;
    for r in &rows {
        table.append(&columns(r))?;
    }
    let mut files = vec![csv];
    files.extend(fig2(params, &rows).save(out, "fig2")?);
    let json = out.join("homogeneous.json");
    let summary = Summary {
        command: "homogeneous",
        parameters: params,
        d_max: study.d_max,
        points: study.points,
        at_d_max: rows.last().expect("at least two points"),
        stopped_at: stopped.as_ref().map(|(d, _)| *d),
        files: files.iter().map(|f| f.display().to_string()).collect(),
    };
    write_json(&json, &summary)?;
    files.push(json);
    Ok(HomogeneousOutcome { files, stopped })
}

/// Fig. 2: substrate stretch `lambda_2s` against `lambda_1`, compressible (eq. 4a) and
/// incompressible (`1/lambda_1`). Under a growth load, both layers' `lambda_2` against `g`.
fn fig2(params: &Parameters, rows: &[HomogeneousRow]) -> Figure {
    if params.load.is_growth() {
        let against = |of: fn(&HomogeneousRow) -> f64| rows.iter().map(|r| (r.state.growth_layer, of(r))).collect();
        return Figure::new(
            format!("Homogeneous state under growth, beta = {:.4}", params.beta),
            "growth of the layer g",
            "vertical stretch lambda_2",
        )
        .with(Series::new(
            "layer",
            against(|r| r.state.lambda2_layer),
            LineStyle::Solid,
            0,
        ))
        .with(Series::new(
            "substrate",
            against(|r| r.state.lambda2_substrate),
            LineStyle::Dashed,
            1,
        ));
    }
    let compressible = rows
        .iter()
        .map(|r| (r.state.lambda1, r.state.lambda2_substrate))
        .collect();
    let incompressible = rows.iter().map(|r| (r.state.lambda1, 1.0 / r.state.lambda1)).collect();
    Figure::new(
        format!("Fig. 2: substrate stretch, beta = {:.4}", params.beta),
        "lateral stretch lambda_1 = 1 - d",
        "substrate's vertical stretch lambda_2s",
    )
    .with(Series::new("compressible (eq. 4a)", compressible, LineStyle::Solid, 0))
    .with(Series::new(
        "incompressible, 1/lambda_1",
        incompressible,
        LineStyle::Dashed,
        5,
    ))
}
