//! The wave vectors a periodic patch admits, and the linear theory's onset over them.
//!
//! A patch periodic over `Lx` along X and `Lz` along Z carries the modes
//! `exp(i (k_x X + k_z Z))` with `k = 2 pi (m / Lx, n / Lz)`, `m, n` integers; `k` and `-k`
//! are one real mode pair, so the half-plane `m > 0`, or `m = 0, n > 0`, lists each once. Its
//! first bifurcation is the smallest `d_c(|k|, theta)` over them (`theta` the wave vector's
//! direction from X towards Z), which the finite elements on the patch must reproduce.

use super::super::search::StabilityAnalysis;
use super::super::Method;
use super::Surface;
use crate::error::{Error, Result};
use crate::parameters::Parameters;
use serde::Serialize;
use std::f64::consts::PI;

/// One admissible wave vector and its critical compression.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct BoxMode {
    /// Wave numbers along X and Z: `(m, n)` with `k = 2 pi (m / Lx, n / Lz)`.
    pub m: i64,
    pub n: i64,
    /// `|k|`.
    pub k: f64,
    /// The wave vector's direction from X towards Z, in `[0, pi)`.
    pub theta: f64,
    /// `d_c(|k|, theta)` of the linear theory.
    pub d_c: f64,
}

/// The admissible wave vectors of a patch of sides `lengths = (Lx, Lz)` with `|k| <= k_max`,
/// with their `d_c` under `d_3 = biaxial d` by `method`, by increasing `d_c`.
pub fn box_modes(
    params: &Parameters,
    method: Method,
    biaxial: f64,
    lengths: (f64, f64),
    k_max: f64,
) -> Result<Vec<BoxMode>> {
    let (kx, kz) = (2.0 * PI / lengths.0, 2.0 * PI / lengths.1);
    let (m_max, n_max) = ((k_max / kx).floor() as i64, (k_max / kz).floor() as i64);
    let analysis = StabilityAnalysis::with_surface(params, method, Some(Surface { biaxial, theta: 0.0 }))?;
    let mut modes = Vec::new();
    for m in 0..=m_max {
        for n in -n_max..=n_max {
            if m == 0 && n <= 0 {
                continue;
            }
            let (x, z) = (m as f64 * kx, n as f64 * kz);
            let k = x.hypot(z);
            if k > k_max {
                continue;
            }
            let theta = z.atan2(x).rem_euclid(PI);
            // A wave vector with no bifurcation before the analysis' end is not a candidate.
            match analysis.along(theta).critical_compression(k) {
                Ok(d_c) => modes.push(BoxMode { m, n, k, theta, d_c }),
                Err(Error::NoRoot { .. }) => {}
                Err(e) => return Err(e),
            }
        }
    }
    // Wave vectors critical together (within rounding, 1e-10 in d: those a symmetry makes
    // equal) in a fixed order, the direction nearest X first.
    let tied = |d_c: f64| (d_c * 1e10).round();
    modes.sort_by(|a, b| tied(a.d_c).total_cmp(&tied(b.d_c)).then(a.theta.total_cmp(&b.theta)));
    Ok(modes)
}
