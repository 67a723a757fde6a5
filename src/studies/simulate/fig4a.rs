//! Fig. 4a: critical compression against wavenumber for `beta = 0, pi/4, pi/2`: the linear
//! theory's `d_c(k)` (curves) and the finite-element onsets for `N = 4, 5, 6` waves
//! (`k = 2 pi N / L`): the paper's maximal curvature of `A(d)` (open circles) and the steepest
//! point of `A(d)` (crosses). The runs are independent and run in parallel (rayon).

use super::{curve, OnsetReport, Progress};
use crate::error::Result;
use crate::mesh::MeshSpec;
use crate::output::{write_json, Figure, Legend, LineStyle, Series};
use crate::parameters::Parameters;
use crate::protocol::{wavenumber_of_waves, OnsetEstimates, Protocol};
use crate::stability::{Method, StabilityAnalysis};
use crate::studies::{linspace, Tick};
use rayon::prelude::*;
use serde::Serialize;
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4};
use std::path::{Path, PathBuf};

/// The runs of Fig. 4a.
#[derive(Clone, Debug)]
pub struct Fig4aOptions {
    pub mesh: MeshSpec,
    /// Final compression of every run: 0.21 clears every onset (all below 0.17 for Table 1)
    /// plus the `A^2` fit window (0.02), and stays short of the snap (a fold of the path in `d`
    /// at 0.23-0.25 on the fine and extra meshes) and of the loss of ellipticity at `beta = 0`.
    pub d_max: f64,
    pub imperfection: f64,
    pub betas: Vec<f64>,
    pub waves: Vec<f64>,
}

impl Fig4aOptions {
    /// The coarse mesh when `quick`, else the fine one.
    pub fn new(quick: bool) -> Self {
        Fig4aOptions {
            mesh: if quick { MeshSpec::coarse() } else { MeshSpec::fine() },
            d_max: 0.21,
            imperfection: 0.05,
            betas: vec![0.0, FRAC_PI_4, FRAC_PI_2],
            waves: vec![4.0, 5.0, 6.0],
        }
    }
}

/// One finite-element run of Fig. 4a.
#[derive(Clone, Debug, Serialize)]
pub struct Fig4aRow {
    pub beta: f64,
    pub waves: f64,
    pub k: f64,
    #[serde(flatten)]
    pub estimates: OnsetEstimates,
    pub d_linear_theory: f64,
    pub d_reached: f64,
    pub stopped: Option<String>,
    pub seconds: f64,
}

/// Runs the simulations (`tick` after each), writes `fig4a.json`, `fig4a.png`, `fig4a.svg`.
pub fn fig4a(
    params: &Parameters,
    options: &Fig4aOptions,
    out: &Path,
    tick: Tick,
) -> Result<(Vec<Fig4aRow>, Vec<PathBuf>)> {
    crate::output::ensure_dir(out)?;
    let cases: Vec<(f64, f64)> = options
        .betas
        .iter()
        .flat_map(|&beta| options.waves.iter().map(move |&n| (beta, n)))
        .collect();
    let rows = cases
        .par_iter()
        .map(|&(beta, waves)| {
            let row = run_case(params, options, beta, waves);
            tick();
            row
        })
        .collect::<Result<Vec<_>>>()?;
    let json = out.join("fig4a.json");
    write_json(&json, &rows)?;
    let mut files = vec![json];
    files.extend(figure(params, options, &rows)?.save(out, "fig4a")?);
    Ok((rows, files))
}

/// One run at `beta` with `waves` seeded: its onsets, or the reason it stopped.
fn run_case(params: &Parameters, options: &Fig4aOptions, beta: f64, waves: f64) -> Result<Fig4aRow> {
    let params = Parameters { beta, ..params.clone() };
    let k = wavenumber_of_waves(waves, options.mesh.length)?;
    let protocol = Protocol::new(k, options.imperfection, options.d_max);
    let quiet = |_: Progress<'_>| Ok(());
    let curve = curve(&params, options.mesh, &protocol, &quiet)?;
    let onset = OnsetReport::new(&params, k, options.mesh.length, &curve)?;
    Ok(Fig4aRow {
        beta,
        waves,
        k,
        estimates: onset.estimates,
        d_linear_theory: onset.d_linear_theory,
        d_reached: curve.records.last().map_or(0.0, |r| r.d),
        stopped: curve.stopped.map(|e| e.to_string()),
        seconds: curve.seconds,
    })
}

/// Theory curves over `k` in [0.3, 1] and the finite-element circles, one colour per `beta`.
fn figure(params: &Parameters, options: &Fig4aOptions, rows: &[Fig4aRow]) -> Result<Figure> {
    let mut figure = Figure::new(
        "Fig. 4a: critical compression against wavenumber",
        "wavenumber k H",
        "critical compression d_c",
    )
    .with_legend(Legend::LowerRight);
    for (colour, &beta) in options.betas.iter().enumerate() {
        let analysis = StabilityAnalysis::new(&Parameters { beta, ..params.clone() }, Method::Exact)?;
        let theory = linspace(0.3, 1.0, 71)
            .into_iter()
            .map(|k| Ok((k, analysis.critical_compression(k)?)))
            .collect::<Result<Vec<_>>>()?;
        let of_beta = || rows.iter().filter(move |r| r.beta == beta);
        let circles = of_beta()
            .filter_map(|r| r.estimates.d_max_curvature.map(|d| (r.k, d)))
            .collect();
        let crosses = of_beta()
            .filter_map(|r| r.estimates.d_steepest.map(|d| (r.k, d)))
            .collect();
        figure = figure
            .with(Series::new(
                format!("theory, beta = {beta:.4}"),
                theory,
                LineStyle::Solid,
                colour,
            ))
            .with(Series::new("FE, max curvature", circles, LineStyle::Circles, colour))
            .with(Series::new("FE, steepest A'", crosses, LineStyle::Crosses, colour));
    }
    Ok(figure)
}
