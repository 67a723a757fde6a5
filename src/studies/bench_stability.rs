//! Timings of the linear stability analysis (`fiberfold bench stability`).

use super::stability_figures::{onset_against_angle, FIBRE_STIFFNESSES};
use crate::error::Result;
use crate::parameters::Parameters;
use crate::stability::{Method, StabilityAnalysis};
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
pub fn run(params: &Parameters) -> Result<String> {
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
    let threads = rayon::current_num_threads();
    Ok(format!(
        "| stability benchmark (Table 1, beta = {beta}) | wall time |\n|---|---|\n\
         | setup (homogeneous state, loss of ellipticity scan) | {setup:.2e} s |\n\
         | one d_c(k) at k0, scan from d = 0 | {cold:.2e} s |\n\
         | one d_c(k) continued from a nearby root | {warm:.2e} s |\n\
         | one onset (k0 = {k0:.5}, d_c = {dc:.5}) | {one_onset:.2e} s |\n\
         | Fig. 4b sweep: 4 stiffnesses x 91 angles, {threads} threads | {sweep:.3} s |\n\
         | one d_c(k) by the discrete cross-check | {discrete_dc:.2e} s |\n",
        beta = params.beta,
        k0 = onset.k0,
        dc = onset.d_c,
    ))
}
