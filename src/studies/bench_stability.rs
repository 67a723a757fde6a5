//! Timings of the linear stability analysis (`fiberfold bench stability`).

use super::linspace;
use super::orientation::Modes;
use super::stability::SweepStudy;
use super::stability_figures::{onset_against_angle, FIBRE_STIFFNESSES};
use crate::error::Result;
use crate::parameters::Parameters;
use crate::stability::{Method, StabilityAnalysis, Surface};
use std::f64::consts::FRAC_PI_2;
use std::time::Instant;

/// Median wall time of `repeats` runs of `f`, in seconds.
fn median_seconds(repeats: usize, mut f: impl FnMut() -> Result<()>) -> Result<f64> {
    let mut times = Vec::with_capacity(repeats);
    for _ in 0..repeats {
        let start = Instant::now();
        f()?;
        times.push(start.elapsed().as_secs_f64());
    }
    times.sort_by(f64::total_cmp);
    Ok(times[repeats / 2])
}

/// A Markdown table: one d_c(k) (cold scan, and continued from a nearby root), one onset, the
/// Fig. 4b sweep (4 stiffnesses x 91 angles, parallel), and the discrete cross-check.
pub fn run(params: &Parameters, map_side: usize) -> Result<String> {
    let analysis = StabilityAnalysis::new(params, Method::Exact)?;
    let onset = analysis.onset()?;
    let cold = median_seconds(21, || analysis.critical_compression(onset.k0).map(|_| ()))?;
    let warm = median_seconds(21, || {
        analysis
            .critical_compression_near(onset.k0 * 1.01, Some(onset.d_c))
            .map(|_| ())
    })?;
    let one_onset = median_seconds(11, || analysis.onset().map(|_| ()))?;
    let setup = median_seconds(11, || StabilityAnalysis::new(params, Method::Exact).map(|_| ()))?;
    let sweep = median_seconds(3, || {
        onset_against_angle(params, &FIBRE_STIFFNESSES, 91, &|| {}).map(|_| ())
    })?;
    let discrete = StabilityAnalysis::new(params, Method::Discrete(Default::default()))?;
    let discrete_dc = median_seconds(3, || discrete.critical_compression(onset.k0).map(|_| ()))?;
    // Waves in every direction of the surface under equibiaxial compression, beside the plane
    // onset above; and the orientation map over the fibres' inclination and azimuth.
    let surface = Some(Surface {
        biaxial: 1.0,
        theta: 0.0,
    });
    let oblique = StabilityAnalysis::with_surface(params, Method::Exact, surface)?;
    let surface_onset = oblique.surface_onset()?;
    let surface_setup = median_seconds(11, || {
        StabilityAnalysis::with_surface(params, Method::Exact, surface).map(|_| ())
    })?;
    let one_surface_onset = median_seconds(5, || oblique.surface_onset().map(|_| ()))?;
    let orientation_map = median_seconds(1, || {
        if map_side == 0 {
            return Ok(());
        }
        SweepStudy {
            param: "psi".into(),
            from: 0.0,
            to: FRAC_PI_2,
            points: map_side,
            series: Some(("beta".into(), linspace(0.0, FRAC_PI_2, map_side))),
            values: None,
            method: Method::Exact,
            keep_poisson: true,
            modes: Modes {
                biaxial: Some(1.0),
                theta: None,
            },
        }
        .compute(params, &|| {})
        .map(|_| ())
    })?;
    let threads = rayon::current_num_threads();
    let map_row = match map_side {
        0 => String::new(),
        n => format!(
            "| orientation map: {n} x {n} (beta, psi), equibiaxial, {threads} threads | {orientation_map:.1} s |\n"
        ),
    };
    Ok(format!(
        "| stability benchmark (Table 1, beta = {beta}) | wall time |\n|---|---|\n\
         | setup (homogeneous state, loss of ellipticity scan) | {setup:.2e} s |\n\
         | one d_c(k) at k0, scan from d = 0 | {cold:.2e} s |\n\
         | one d_c(k) continued from a nearby root | {warm:.2e} s |\n\
         | one onset (k0 = {k0:.5}, d_c = {dc:.5}) | {one_onset:.2e} s |\n\
         | Fig. 4b sweep: 4 stiffnesses x 91 angles, {threads} threads | {sweep:.3} s |\n\
         | one d_c(k) by the discrete cross-check | {discrete_dc:.2e} s |\n\
         | setup of the analysis over the directions of the surface (3D ellipticity scan) | {surface_setup:.2e} s |\n\
         | one onset over k and theta, equibiaxial (theta0 = {theta0:.4}, d_c = {sdc:.5}) | {one_surface_onset:.2e} s ({ratio:.1}x the plane onset) |\n{map_row}",
        theta0 = surface_onset.theta0,
        sdc = surface_onset.onset.d_c,
        ratio = one_surface_onset / one_onset,
        beta = params.beta,
        k0 = onset.k0,
        dc = onset.d_c,
    ))
}
