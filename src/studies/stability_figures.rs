//! The paper's linear-stability figures (4b, 5, 6) and the numbers its text quotes about them.

use super::stability::{DispersionCurve, SweepPoint, SweepStudy};
use super::{linspace, Tick};
use crate::error::Result;
use crate::numerics::roots::brent;
use crate::output::ticks::AxisScale;
use crate::output::{plot::save_panels, CsvWriter, Figure, Legend, LineStyle, Series};
use crate::parameters::Parameters;
use crate::stability::{Method, StabilityAnalysis};
use serde::Serialize;
use std::f64::consts::FRAC_PI_2;
use std::path::Path;

/// Fibre stiffnesses of Figs. 4b and 5.
pub const FIBRE_STIFFNESSES: [f64; 4] = [1.0, 10.0, 20.0, 50.0];

/// Sample counts: the paper's resolution, or a quick preview.
#[derive(Clone, Copy, Debug)]
pub struct Resolution {
    pub angles: usize,
    pub wavenumbers: usize,
    pub fig6_values: usize,
}

impl Resolution {
    pub fn new(quick: bool) -> Self {
        if quick {
            Resolution {
                angles: 31,
                wavenumbers: 80,
                fig6_values: 6,
            }
        } else {
            Resolution {
                angles: 91,
                wavenumbers: 300,
                fig6_values: 11,
            }
        }
    }
}

/// k0 against beta for each fibre stiffness (the data of Fig. 4b).
pub fn onset_against_angle(
    params: &Parameters,
    stiffnesses: &[f64],
    angles: usize,
    tick: Tick,
) -> Result<Vec<SweepPoint>> {
    SweepStudy {
        param: "beta".into(),
        from: 0.0,
        to: FRAC_PI_2,
        points: angles,
        series: Some(("mu_f".into(), stiffnesses.to_vec())),
        values: None,
        method: Method::Exact,
        modes: Default::default(),
        keep_poisson: true,
    }
    .compute(params, tick)
}

/// Numbers that Fig. 4b's discussion quotes (section 3.1), computed independently.
#[derive(Clone, Debug, Serialize)]
pub struct Fig4bFacts {
    /// k0 without fibres (phi_m = 1, phi_f = 0).
    pub k0_fibre_free: f64,
    /// k0 with unloaded fibres (mu_f = 0, phi_m = 0.9).
    pub k0_unloaded_fibres: f64,
    /// The angle where the k0(beta) curves of mu_f = 1 and 50 cross, and k0 there.
    pub crossing_angle: Option<f64>,
    pub crossing_k0: Option<f64>,
    /// Largest |k0 / k0_fibre_free - 1| over beta at mu_f = 20.
    pub max_relative_change_mu_f_20: f64,
    /// Angle of the largest k0 at mu_f = 20, and max/min wavelength ratio there.
    pub angle_of_k_max_mu_f_20: f64,
    pub wavelength_ratio_mu_f_20: f64,
}

/// Fig. 4b (`fig4b.png/svg`, `fig4b.csv`) and its quoted numbers.
pub fn fig4b(params: &Parameters, resolution: &Resolution, out: &Path, tick: Tick) -> Result<Fig4bFacts> {
    let points = onset_against_angle(params, &FIBRE_STIFFNESSES, resolution.angles, tick)?;
    let fibre_free = Parameters {
        phi_m: 1.0,
        phi_f: 0.0,
        ..params.clone()
    };
    let k0_fibre_free = StabilityAnalysis::new(&fibre_free, Method::Exact)?.onset()?.k0;
    let unloaded = Parameters {
        mu_f: 0.0,
        ..params.clone()
    };
    let k0_unloaded_fibres = StabilityAnalysis::new(&unloaded, Method::Exact)?.onset()?.k0;

    let mut csv = CsvWriter::create(&out.join("fig4b.csv"), &["mu_f", "beta", "k0", "d_c"])?;
    let mut figure = Figure::new(
        "Fig. 4b: onset wavenumber",
        "fibre angle beta (deg)",
        "onset wavenumber k0 H",
    )
    .with_x_scale(AxisScale::Degrees)
    .with_legend(Legend::LowerRight);
    for (i, &mu_f) in FIBRE_STIFFNESSES.iter().enumerate() {
        let curve: Vec<(f64, f64)> = series_of(&points, mu_f, |o| o.k0);
        for p in points.iter().filter(|p| p.series == Some(mu_f)) {
            if let Some(o) = p
                .onset
                .as_ref()
                .filter(|o| o.minimum == crate::stability::Minimum::Interior)
            {
                csv.append(&[mu_f, p.value, o.k0, o.d_c])?;
            }
        }
        figure
            .series
            .push(Series::new(format!("mu_f = {mu_f}"), curve, LineStyle::Solid, i));
    }
    figure.series.push(Series::new(
        "no fibres (phi_m = 1)",
        vec![(0.0, k0_fibre_free), (FRAC_PI_2, k0_fibre_free)],
        LineStyle::Dashed,
        5,
    ));
    save_panels(&[figure], out, "fig4b")?;

    let k0_at = |mu_f: f64, beta: f64| -> Result<f64> {
        let p = Parameters {
            mu_f,
            beta,
            ..params.clone()
        };
        Ok(StabilityAnalysis::new(&p, Method::Exact)?.onset()?.k0)
    };
    let crossing_angle = brent(
        "k0(mu_f = 1) = k0(mu_f = 50)",
        |b| Ok(k0_at(1.0, b)? - k0_at(50.0, b)?),
        0.05,
        1.0,
        1e-7,
    )
    .ok();
    let crossing_k0 = crossing_angle.map(|b| k0_at(10.0, b)).transpose()?;
    let at_20 = series_of(&points, 20.0, |o| o.k0);
    let max_relative_change_mu_f_20 = at_20
        .iter()
        .map(|(_, k)| (k / k0_fibre_free - 1.0).abs())
        .fold(0.0, f64::max);
    let (angle_of_k_max, k_max) = at_20
        .iter()
        .copied()
        .fold((0.0, f64::MIN), |a, b| if b.1 > a.1 { b } else { a });
    let k_min = at_20.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
    Ok(Fig4bFacts {
        k0_fibre_free,
        k0_unloaded_fibres,
        crossing_angle,
        crossing_k0,
        max_relative_change_mu_f_20,
        angle_of_k_max_mu_f_20: angle_of_k_max,
        wavelength_ratio_mu_f_20: k_max / k_min,
    })
}

fn series_of(points: &[SweepPoint], series: f64, pick: fn(&crate::stability::Onset) -> f64) -> Vec<(f64, f64)> {
    points
        .iter()
        .filter(|p| p.series == Some(series))
        .filter_map(|p| p.onset.as_ref().map(|o| (p.value, o)))
        .filter(|(_, o)| o.minimum == crate::stability::Minimum::Interior)
        .map(|(v, o)| (v, pick(o)))
        .collect()
}

/// Numbers of Fig. 5 and the d_c growth quoted in section 3.1.
#[derive(Clone, Debug, Serialize)]
pub struct Fig5Facts {
    /// `(mu_f, d_c at beta = 0, d_c at beta = pi/2)` at the respective onsets.
    pub onsets: Vec<(f64, f64, f64)>,
    /// Relative growth of d_c from beta = 0 to pi/2 at mu_f = 10.
    pub growth_mu_f_10: f64,
}

/// Fig. 5 (`fig5.png/svg`): d_c(k) at beta = 0 and pi/2 for each fibre stiffness, minima marked.
pub fn fig5(params: &Parameters, resolution: &Resolution, out: &Path, tick: Tick) -> Result<Fig5Facts> {
    let ks = linspace(0.2, 1.5, resolution.wavenumbers);
    let mut panels = Vec::new();
    let mut onsets = Vec::new();
    let mut csv = CsvWriter::create(&out.join("fig5.csv"), &["beta", "mu_f", "k", "d_c"])?;
    for (label, beta) in [("(a) beta = 0", 0.0), ("(b) beta = pi/2", FRAC_PI_2)] {
        let mut figure = Figure::new(format!("Fig. 5{label}"), "wavenumber k H", "critical compression d_c")
            .with_legend(Legend::UpperLeft);
        for (i, &mu_f) in FIBRE_STIFFNESSES.iter().enumerate() {
            let analysis = StabilityAnalysis::new(
                &Parameters {
                    beta,
                    mu_f,
                    ..params.clone()
                },
                Method::Exact,
            )?;
            let curve = DispersionCurve::compute(&analysis, &ks, tick)?;
            for &(k, d) in &curve.points {
                csv.append(&[beta, mu_f, k, d])?;
            }
            // A curve that stops short of the wavenumbers asked for says why.
            let ends_early = curve.points.last().is_some_and(|&(k, _)| k < ks[ks.len() - 1] - 1e-12);
            let name = match (ends_early, analysis.ellipticity_loss()) {
                (true, Some(d)) => format!("mu_f = {mu_f} (ends: ellipticity lost at d = {d:.3})"),
                (true, None) => format!("mu_f = {mu_f} (ends: no d_c below 0.95)"),
                _ => format!("mu_f = {mu_f}"),
            };
            figure.series.push(Series::new(name, curve.points, LineStyle::Solid, i));
            if let Ok(onset) = analysis.onset() {
                figure
                    .series
                    .push(Series::new("", vec![(onset.k0, onset.d_c)], LineStyle::Crosses, i));
                if beta == 0.0 {
                    onsets.push((mu_f, onset.d_c, f64::NAN));
                } else if let Some(row) = onsets.iter_mut().find(|r| r.0 == mu_f) {
                    row.2 = onset.d_c;
                }
            }
        }
        panels.push(figure);
    }
    save_panels(&panels, out, "fig5")?;
    let at_10 = onsets
        .iter()
        .find(|r| r.0 == 10.0)
        .copied()
        .unwrap_or((10.0, f64::NAN, f64::NAN));
    Ok(Fig5Facts {
        growth_mu_f_10: at_10.2 / at_10.1 - 1.0,
        onsets,
    })
}

/// Fig. 6 (`fig6.png/svg`): the range `[k_min, k_max]` of k0 over beta in [0, pi/2],
/// (a) against mu_f, (b) against lambda_f.
pub fn fig6(params: &Parameters, resolution: &Resolution, out: &Path, tick: Tick) -> Result<()> {
    let mut panels = Vec::new();
    let mut csv = CsvWriter::create(&out.join("fig6.csv"), &["panel", "value", "k_min", "k_max"])?;
    for (panel, key, from, to) in [("a", "mu_f", 0.0, 50.0), ("b", "lambda_f", 0.8, 1.0)] {
        let mut lower = Vec::new();
        let mut upper = Vec::new();
        for value in linspace(from, to, resolution.fig6_values) {
            let mut p = params.clone();
            p.set_number(key, value)?;
            let points = onset_against_angle(&p, &[p.mu_f], resolution.angles, tick)?;
            let ks: Vec<f64> = points.iter().filter_map(|q| q.onset.as_ref().map(|o| o.k0)).collect();
            if ks.is_empty() {
                continue;
            }
            let (k_min, k_max) = ks
                .iter()
                .fold((f64::INFINITY, f64::MIN), |(lo, hi), &k| (lo.min(k), hi.max(k)));
            csv.append_labelled(Some(panel), &[value, k_min, k_max])?;
            lower.push((value, k_min));
            upper.push((value, k_max));
        }
        let axis = super::stability::parameter_axis(key);
        let figure = Figure::new(
            format!("Fig. 6({panel}): admissible onset wavenumbers"),
            axis,
            "onset wavenumber k0 H",
        )
        .with_x_scale(super::stability::parameter_scale(key))
        .with_legend(Legend::LowerLeft)
        .with(Series::new("k_max", upper, LineStyle::Solid, 0))
        .with(Series::new("k_min", lower, LineStyle::Dashed, 0));
        panels.push(figure);
    }
    save_panels(&panels, out, "fig6")?;
    Ok(())
}

/// Number of units of work of Figs. 4b, 5 and 6 (for progress bars).
pub fn work(resolution: &Resolution) -> usize {
    FIBRE_STIFFNESSES.len() * resolution.angles
        + 2 * FIBRE_STIFFNESSES.len() * resolution.wavenumbers
        + 2 * resolution.fig6_values * resolution.angles
}
