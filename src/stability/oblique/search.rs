//! The onset over wavenumbers and directions of the surface: `min over (k, theta)` of
//! `d_c(k, theta)`.
//!
//! The onset along X gives a wavenumber `k`; `d_c(k, theta)` on `DIRECTIONS` directions of
//! `[0, pi)` (the conjugate wave covers `theta + pi`) finds the basin of the lowest; a Newton
//! method on quadratic fits of `d_c` over a 3x3 stencil in `(k, theta)` then finds its minimum.
//! Where the onset along X has no interior wavenumber, the onset in `k` along each direction is
//! compared instead, and Brent's method refines the direction.

use super::{folded, SurfaceOnset};
use crate::error::{Error, Result};
use crate::numerics::minimize::brent_minimize;
use crate::stability::search::RISE_TOLERANCE;
use crate::stability::{Minimum, Onset, StabilityAnalysis, K_MAX};
use std::f64::consts::PI;

/// Directions sampled (every 15 degrees of `[0, pi)`).
const DIRECTIONS: usize = 12;
/// The refinement ends when a Newton step is below this, relative in `k`, absolute in `theta`.
const STEP_TOLERANCE: f64 = 1e-6;
/// A direction this close to X or Z (in radians) is taken as the axis where `d_c` is no higher
/// there.
const SNAP: f64 = 1e-3;

impl StabilityAnalysis {
    /// The onset over wavenumbers and directions.
    pub fn surface_onset(&self) -> Result<SurfaceOnset> {
        let along_x = self.along(0.0).onset()?;
        if along_x.minimum != Minimum::Interior {
            return self.onset_by_directions();
        }
        let samples = self.sample_directions(along_x.k0, along_x.d_c)?;
        let (best_theta, best) = lowest_sample(&samples);
        let highest = highest_sample(&samples, best);
        if highest - best <= RISE_TOLERANCE {
            return Ok(SurfaceOnset {
                onset: along_x,
                theta0: f64::NAN,
                direction_spread: highest - best,
            });
        }
        match self.refine(along_x.k0, best_theta, best) {
            Ok((k0, theta0, d_c)) => self.directed(k0, theta0, d_c),
            Err(Error::NoRoot { .. }) => self.onset_by_directions(),
            Err(e) => Err(e),
        }
    }

    /// The onset over wavenumbers and directions, continued from a nearby parameter set's
    /// `previous`: the refinement starts at its `(k0, theta0)`. It falls back to
    /// [`Self::surface_onset`] where `previous` has no direction or wavenumber, or where a
    /// sampled direction at the new `k0` lies below the minimum found (the preferred direction
    /// has moved elsewhere).
    pub fn surface_onset_near(&self, previous: &SurfaceOnset) -> Result<SurfaceOnset> {
        let (k, theta) = (previous.onset.k0, previous.theta0);
        if !theta.is_finite() || previous.onset.minimum != Minimum::Interior {
            return self.surface_onset();
        }
        let start = self.along(theta).critical_compression_near(k, Some(previous.onset.d_c));
        let refined = start.and_then(|d| self.refine(k, theta, d));
        let (k0, theta0, d_c) = match refined {
            Ok(found) => found,
            Err(Error::NoRoot { .. }) => return self.surface_onset(),
            Err(e) => return Err(e),
        };
        let onset = self.directed(k0, theta0, d_c)?;
        match onset.theta0.is_finite() {
            true => Ok(onset),
            false => self.surface_onset(),
        }
    }

    /// The onset at the refined `(k0, theta0)`, with the spread over the sampled directions at
    /// `k0`; NaN `theta0` if one of them lies below it (the refinement found a local minimum).
    /// A `theta0` within [`SNAP`] of X or Z, where `d_c` is no higher, is that axis: the
    /// refinement resolves a direction to about 1e-4, and a mode along an axis (the mirror
    /// symmetry of fibres with `psi = 0` makes both axes stationary) is one a box of any length
    /// along the other axis admits.
    fn directed(&self, k0: f64, theta0: f64, d_c: f64) -> Result<SurfaceOnset> {
        let (theta0, d_c) = self.snapped_to_axis(k0, theta0, d_c)?;
        let samples = self.sample_directions(k0, d_c)?;
        let (_, lowest) = lowest_sample(&samples);
        let highest = highest_sample(&samples, d_c);
        Ok(SurfaceOnset {
            onset: self.along(theta0).onset_at(k0, d_c, Minimum::Interior),
            theta0: if lowest < d_c - RISE_TOLERANCE {
                f64::NAN
            } else {
                folded(theta0)
            },
            direction_spread: highest - d_c,
        })
    }

    /// `(theta0, d_c)`, or the axis within [`SNAP`] of `theta0` and its `d_c` at `k0` where that
    /// is no higher (round-off aside).
    fn snapped_to_axis(&self, k0: f64, theta0: f64, d_c: f64) -> Result<(f64, f64)> {
        let Some(axis) = [0.0, PI / 2.0, PI]
            .into_iter()
            .find(|axis| (theta0 - axis).abs() < SNAP && *axis != theta0)
        else {
            return Ok((theta0, d_c));
        };
        match self.along(axis).critical_compression_near(k0, Some(d_c)) {
            Ok(on_axis) if on_axis <= d_c + 1e-12 => Ok((axis, on_axis.min(d_c))),
            Ok(_) | Err(Error::NoRoot { .. }) => Ok((theta0, d_c)),
            Err(e) => Err(e),
        }
    }

    /// `(theta, d_c(k, theta))` on the sampled directions, each continued from the last
    /// (infinite where no bifurcation exists before the search's end).
    fn sample_directions(&self, k: f64, hint: f64) -> Result<Vec<(f64, f64)>> {
        let mut hint = Some(hint);
        (0..DIRECTIONS)
            .map(|i| {
                let theta = i as f64 * PI / DIRECTIONS as f64;
                let d = match self.along(theta).critical_compression_near(k, hint) {
                    Err(Error::NoRoot { .. }) => f64::INFINITY,
                    other => other?,
                };
                hint = Some(d).filter(|d| d.is_finite()).or(hint);
                Ok((theta, d))
            })
            .collect()
    }

    /// The minimum of `d_c(k, theta)` near `(k, theta)` (where it is `d`): Newton steps on the
    /// quadratic fitted to a 3x3 stencil, clipped to twice the stencil, accepted where they
    /// lower `d_c`; otherwise the stencil's best point is taken, or the stencil shrinks.
    fn refine(&self, mut k: f64, mut theta: f64, mut d: f64) -> Result<(f64, f64, f64)> {
        let (mut hk, mut ht) = (0.05 * k, PI / DIRECTIONS as f64 / 4.0);
        let f = |k: f64, theta: f64, hint: f64| -> Result<f64> {
            if !(k > 0.0 && k <= K_MAX) {
                return Ok(f64::INFINITY);
            }
            self.along(theta).critical_compression_near(k, Some(hint))
        };
        for _ in 0..40 {
            let mut grid = [[d; 3]; 3];
            for (i, row) in grid.iter_mut().enumerate() {
                for (j, value) in row.iter_mut().enumerate() {
                    if (i, j) != (1, 1) {
                        *value = f(k + (i as f64 - 1.0) * hk, theta + (j as f64 - 1.0) * ht, d)?;
                    }
                }
            }
            let gk = (grid[2][1] - grid[0][1]) / (2.0 * hk);
            let gt = (grid[1][2] - grid[1][0]) / (2.0 * ht);
            let hkk = (grid[2][1] - 2.0 * d + grid[0][1]) / (hk * hk);
            let htt = (grid[1][2] - 2.0 * d + grid[1][0]) / (ht * ht);
            let hkt = (grid[2][2] - grid[2][0] - grid[0][2] + grid[0][0]) / (4.0 * hk * ht);
            let det = hkk * htt - hkt * hkt;
            let trial = (hkk > 0.0 && det > 0.0 && det.is_finite()).then(|| {
                let sk = (-(htt * gk - hkt * gt) / det).clamp(-2.0 * hk, 2.0 * hk);
                let st = (-(hkk * gt - hkt * gk) / det).clamp(-2.0 * ht, 2.0 * ht);
                (sk, st)
            });
            if let Some((sk, st)) = trial {
                let value = f(k + sk, theta + st, d)?;
                if value <= d {
                    (k, theta, d) = (k + sk, theta + st, value);
                    if sk.abs() < STEP_TOLERANCE * k && st.abs() < STEP_TOLERANCE {
                        return Ok((k, theta, d));
                    }
                    // Stencils below 1e-4 would resolve d_c's round-off more than its curvature.
                    hk = (2.0 * sk.abs()).clamp(1e-4 * k, 0.05 * k);
                    ht = (2.0 * st.abs()).clamp(1e-4, PI / DIRECTIONS as f64 / 4.0);
                    continue;
                }
            }
            let (bi, bj, best) = (0..3)
                .flat_map(|i| (0..3).map(move |j| (i, j)))
                .map(|(i, j)| (i, j, grid[i][j]))
                .fold((1, 1, d), |a, b| if b.2 < a.2 { b } else { a });
            if best < d {
                (k, theta, d) = (k + (bi as f64 - 1.0) * hk, theta + (bj as f64 - 1.0) * ht, best);
            } else if hk < 1e-4 * k && ht < 1e-4 {
                return Ok((k, theta, d));
            } else {
                (hk, ht) = (0.25 * hk, 0.25 * ht);
            }
        }
        Ok((k, theta, d))
    }

    /// The onset where the wavenumber is not interior along X: the onset in `k` along each
    /// sampled direction, then Brent's minimisation over the 30 degrees around the best.
    fn onset_by_directions(&self) -> Result<SurfaceOnset> {
        let step = PI / DIRECTIONS as f64;
        let thetas: Vec<f64> = (0..DIRECTIONS).map(|i| i as f64 * step).collect();
        let onsets = self.onsets_along(&thetas)?;
        let samples: Vec<(f64, f64)> = thetas.iter().zip(&onsets).map(|(t, o)| (*t, o.d_c)).collect();
        let (best_theta, lowest) = lowest_sample(&samples);
        let best = onsets[samples.iter().position(|s| s.0 == best_theta).expect("a sample")];
        let highest = samples.iter().map(|s| s.1).fold(lowest, f64::max);
        if highest - lowest <= RISE_TOLERANCE {
            return Ok(SurfaceOnset {
                onset: best,
                theta0: f64::NAN,
                direction_spread: highest - lowest,
            });
        }
        let last = std::cell::Cell::new(best);
        let (theta, _) = brent_minimize(
            |theta| {
                let onset = self.along(theta).onset_near(&last.get())?;
                last.set(onset);
                Ok(onset.d_c)
            },
            best_theta - step,
            best_theta + step,
            1e-6,
        )?;
        let onset = self.along(theta).onset_near(&last.get())?;
        let (onset, theta0) = if onset.d_c < best.d_c {
            (onset, theta)
        } else {
            (best, best_theta)
        };
        Ok(SurfaceOnset {
            onset,
            theta0: folded(theta0),
            direction_spread: highest - onset.d_c,
        })
    }

    /// The onset in `k` along each of `thetas` (continued from one to the next).
    pub fn onsets_along(&self, thetas: &[f64]) -> Result<Vec<Onset>> {
        let mut previous: Option<Onset> = None;
        thetas
            .iter()
            .map(|&theta| {
                let along = self.along(theta);
                let onset = match &previous {
                    Some(p) => along.onset_near(p)?,
                    None => along.onset()?,
                };
                previous = Some(onset);
                Ok(onset)
            })
            .collect()
    }
}

/// The largest finite `d_c` of the samples, at least `floor`.
fn highest_sample(samples: &[(f64, f64)], floor: f64) -> f64 {
    samples
        .iter()
        .map(|s| s.1)
        .filter(|d| d.is_finite())
        .fold(floor, f64::max)
}

/// The first sample within round-off of the lowest: of a mirror pair (`theta` and
/// `pi - theta`, where the fibres' projection lies along X or Z) the one in `[0, pi/2]`.
fn lowest_sample(samples: &[(f64, f64)]) -> (f64, f64) {
    let lowest = samples.iter().map(|s| s.1).fold(f64::INFINITY, f64::min);
    *samples
        .iter()
        .find(|s| s.1 <= lowest + 1e-12)
        .expect("directions sampled")
}
