//! The two-dimensional Fourier spectrum of a patch's surface height: how much of each
//! admissible wave vector `k = 2 pi (m / Lx, n / Lz)` a field of the top surface holds.
//!
//! The top nodes of a periodic patch lie on a uniform grid of `2 nx x 2 nz` points, so the
//! discrete Fourier coefficient `c_mn = (1 / M) sum_j h_j exp(-i k . X_j)` is exact for every
//! trigonometric content below the grid's Nyquist limit; a wave `A cos(k . X + phi)` has
//! `|c_mn| = A / 2`, so `2 |c_mn|` is its amplitude. A patch with symmetry sides holds the
//! waves `cos(m pi X / Lx) cos(n pi Z / Lz)` of the periodic surface its reflections across
//! `X = 0` and `Z = 0` make, `2 Lx` by `2 Lz`: its wave vectors are `pi (m / Lx, n / Lz)`, and
//! an oblique one comes with its mirror image `(m, -n)`, each at half the product's amplitude.

use crate::mesh::{Mesh, X, Y, Z};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// One wave vector of the surface and its amplitude.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct WaveVector {
    /// `k = 2 pi (m / Lx, n / Lz)`, `m > 0` or `m = 0, n > 0` (`k` and `-k` are one wave).
    pub m: i64,
    pub n: i64,
    /// `|k|`.
    pub k: f64,
    /// The wave vector's direction from X towards Z, in degrees in `[0, 180)`.
    pub theta_degrees: f64,
    /// The amplitude `2 |c_mn|` of the wave in `u_Y` (units of the layer thickness).
    pub amplitude: f64,
}

/// The spectrum of the top surface's `u_Y` of the full vector `u` on a patch, for the wave
/// vectors below the grid's Nyquist limit, by decreasing amplitude.
pub fn surface_spectrum(mesh: &Mesh<3, 27>, u: &[f64]) -> Vec<WaveVector> {
    spectrum_of(mesh, |node| u[mesh.dofs().dof(node, Y)])
}

/// The spectrum of the deformed top surface's height `Y + u_Y` (the reference surface's own
/// imperfection included) of the state `u` of a patch, by decreasing amplitude.
pub fn height_spectrum(mesh: &Mesh<3, 27>, u: &[f64]) -> Vec<WaveVector> {
    spectrum_of(mesh, |node| mesh.coordinates()[node][Y] + u[mesh.dofs().dof(node, Y)])
}

/// The spectrum of `height` over the top nodes of a patch (module docs); a symmetric patch's
/// surface is first reflected across its sides `X = 0` and `Z = 0` (the symmetry its sides
/// impose), into a periodic surface twice as long each way.
fn spectrum_of(mesh: &Mesh<3, 27>, height: impl Fn(usize) -> f64) -> Vec<WaveVector> {
    let spec = mesh.patch_spec();
    let top = mesh.node_set(crate::mesh::TOP);
    let (samples, length_x, length_z, m_max, n_max) = if mesh.is_periodic() {
        let [length_x, _, length_z] = *mesh.periods();
        let samples: Vec<([f64; 2], f64)> = top
            .iter()
            .map(|&node| {
                let x = mesh.coordinates()[node];
                ([x[X], x[Z]], height(node))
            })
            .collect();
        (samples, length_x, length_z, spec.nx as i64, spec.nz as i64)
    } else {
        let (length_x, length_z) = (spec.length_x, spec.length_z);
        // A node strictly inside a side's span has a mirror image; one on `X = 0` or `X = Lx`
        // (`-Lx` is `Lx` a period on) is its own.
        let images = |x: f64, length: f64| match x > 1e-9 * length && x < length * (1.0 - 1e-9) {
            true => vec![x, -x],
            false => vec![x],
        };
        let mut samples = Vec::with_capacity(4 * top.len());
        for &node in top {
            let x = mesh.coordinates()[node];
            for &a in &images(x[X], length_x) {
                for &b in &images(x[Z], length_z) {
                    samples.push(([a, b], height(node)));
                }
            }
        }
        (
            samples,
            2.0 * length_x,
            2.0 * length_z,
            2 * spec.nx as i64,
            2 * spec.nz as i64,
        )
    };
    let mut waves = Vec::new();
    for m in 0..m_max {
        for n in -(n_max - 1)..n_max {
            if m == 0 && n <= 0 {
                continue;
            }
            let (kx, kz) = (2.0 * PI * m as f64 / length_x, 2.0 * PI * n as f64 / length_z);
            let (re, im) = samples.iter().fold((0.0, 0.0), |(re, im), (x, h)| {
                let phase = kx * x[0] + kz * x[1];
                (re + h * phase.cos(), im - h * phase.sin())
            });
            waves.push(WaveVector {
                m,
                n,
                k: kx.hypot(kz),
                theta_degrees: kz.atan2(kx).rem_euclid(PI).to_degrees(),
                amplitude: 2.0 * re.hypot(im) / samples.len() as f64,
            });
        }
    }
    waves.sort_by(|a, b| b.amplitude.total_cmp(&a.amplitude));
    waves
}

/// What a surface's spectrum shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SurfacePattern {
    /// No wave above `FLAT_AMPLITUDE`.
    Flat,
    /// One direction of wave vectors (a wave and its harmonics) holds the surface.
    Stripes,
    /// Two directions hold it, the weaker with at least `SECOND_DIRECTION` of the surface's
    /// spectral energy: the superposed waves of a checkerboard (rhombic where the two are not
    /// perpendicular).
    Checkerboard,
    /// More directions, or two of which one is weak: a modulated pattern (herringbone,
    /// labyrinth and their kin).
    Mixed,
}

/// A wave amplitude below which the surface is flat (units of the layer thickness).
pub const FLAT_AMPLITUDE: f64 = 1e-3;

/// The share of the spectral energy that the directions of a pattern hold together.
pub const PATTERN_SHARE: f64 = 0.95;

/// The smallest share of the spectral energy of the second direction of a checkerboard.
pub const SECOND_DIRECTION: f64 = 0.2;

/// A direction of wave vectors and the share of the surface's spectral energy its waves hold.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Direction {
    /// The direction's leading wave.
    pub wave: WaveVector,
    /// The share of `sum amplitude^2` held by the waves along it (the leading one and its
    /// harmonics).
    pub share: f64,
}

/// The pattern of a surface from its spectrum `waves` (by decreasing amplitude): its directions
/// of wave vectors by decreasing share, those with at least 1 % of the energy, and what they
/// make.
pub fn classify(waves: &[WaveVector]) -> (SurfacePattern, Vec<Direction>) {
    if waves.first().is_none_or(|w| w.amplitude < FLAT_AMPLITUDE) {
        return (SurfacePattern::Flat, Vec::new());
    }
    let total: f64 = waves.iter().map(|w| w.amplitude * w.amplitude).sum();
    let mut directions: Vec<((i64, i64), Direction)> = Vec::new();
    for wave in waves {
        let key = direction_of(wave.m, wave.n);
        let energy = wave.amplitude * wave.amplitude / total;
        match directions.iter_mut().find(|(k, _)| *k == key) {
            Some((_, direction)) => direction.share += energy,
            None => directions.push((
                key,
                Direction {
                    wave: *wave,
                    share: energy,
                },
            )),
        }
    }
    let mut directions: Vec<Direction> = directions.into_iter().map(|(_, d)| d).collect();
    directions.sort_by(|a, b| b.share.total_cmp(&a.share));
    directions.retain(|d| d.share >= 0.01);
    let share = |n: usize| directions.iter().take(n).map(|d| d.share).sum::<f64>();
    let pattern = if share(1) >= PATTERN_SHARE {
        SurfacePattern::Stripes
    } else if share(2) >= PATTERN_SHARE && directions[1].share >= SECOND_DIRECTION {
        SurfacePattern::Checkerboard
    } else {
        SurfacePattern::Mixed
    };
    (pattern, directions)
}

/// The direction of the wave vector `(m, n)`: `(m, n)` over their greatest common divisor.
fn direction_of(m: i64, n: i64) -> (i64, i64) {
    let (mut a, mut b) = (m.abs(), n.abs());
    while b != 0 {
        (a, b) = (b, a % b);
    }
    (m / a, n / a)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Sides;

    /// On symmetry sides the cosine products `cos(m pi X / Lx) cos(n pi Z / Lz)` are found as
    /// the wave vectors `pi (m / Lx, +-n / Lz)`, each at half the product's amplitude.
    #[test]
    fn a_symmetric_patchs_cosines_are_its_reflected_surfaces_waves() {
        let mesh = super::super::small_patch(Sides::Symmetry);
        let dofs = mesh.dofs();
        let mut u = vec![0.0; mesh.num_dofs()];
        for (node, x) in mesh.coordinates().iter().enumerate() {
            let (a, b) = (PI * x[X] / 8.0, PI * x[Z] / 6.0);
            u[dofs.dof(node, Y)] = 0.3 * a.cos() * (2.0 * b).cos() + 0.1 * (3.0 * a).cos();
        }
        let waves = surface_spectrum(&mesh, &u);
        let mut pair = [(waves[0].m, waves[0].n), (waves[1].m, waves[1].n)];
        pair.sort();
        assert_eq!(pair, [(1, -2), (1, 2)]);
        assert!((waves[0].amplitude - 0.15).abs() < 1e-12 && (waves[1].amplitude - 0.15).abs() < 1e-12);
        assert_eq!((waves[2].m, waves[2].n), (3, 0));
        assert!((waves[2].amplitude - 0.1).abs() < 1e-12, "{:?}", waves[2]);
        assert!(waves[3].amplitude < 1e-12);
        assert!((waves[2].k - 3.0 * PI / 8.0).abs() < 1e-12);
    }

    #[test]
    fn an_oblique_wave_and_a_weaker_one_are_found_with_their_amplitudes() {
        let mesh = super::super::small_patch(Sides::Periodic);
        let dofs = mesh.dofs();
        let mut u = vec![0.0; mesh.num_dofs()];
        for (node, x) in mesh.coordinates().iter().enumerate() {
            let (a, b) = (2.0 * PI * x[X] / 8.0, 2.0 * PI * x[Z] / 6.0);
            u[dofs.dof(node, Y)] = 0.3 * (a - 2.0 * b + 0.4).cos() + 0.1 * (3.0 * a).sin() + 0.05;
        }
        let waves = surface_spectrum(&mesh, &u);
        assert_eq!((waves[0].m, waves[0].n), (1, -2));
        assert!((waves[0].amplitude - 0.3).abs() < 1e-12, "{:?}", waves[0]);
        assert_eq!((waves[1].m, waves[1].n), (3, 0));
        assert!((waves[1].amplitude - 0.1).abs() < 1e-12, "{:?}", waves[1]);
        assert!(waves[2].amplitude < 1e-12);
        let theta = (-2.0f64 / 6.0).atan2(1.0 / 8.0).rem_euclid(PI).to_degrees();
        assert!((waves[0].theta_degrees - theta).abs() < 1e-9);
        // Two directions, the second with 0.1^2 / (0.3^2 + 0.1^2) = 10 % of the energy.
        let (pattern, directions) = classify(&waves);
        assert_eq!(pattern, SurfacePattern::Mixed);
        assert!((directions[1].share - 0.1).abs() < 1e-12, "{directions:?}");
    }

    fn wave(m: i64, n: i64, amplitude: f64) -> WaveVector {
        WaveVector {
            m,
            n,
            k: 0.0,
            theta_degrees: 0.0,
            amplitude,
        }
    }

    #[test]
    fn harmonics_belong_to_their_waves_direction() {
        let stripes = [wave(1, 1, 0.3), wave(2, 2, 0.05), wave(3, 3, 0.01)];
        assert_eq!(classify(&stripes).0, SurfacePattern::Stripes);
        let checkerboard = [wave(1, 1, 0.2), wave(1, -1, 0.2), wave(2, 0, 0.02)];
        let (pattern, directions) = classify(&checkerboard);
        assert_eq!(pattern, SurfacePattern::Checkerboard);
        assert_eq!(directions.len(), 2, "the harmonic (2, 0) holds under 1 %");
        let labyrinth = [wave(1, 0, 0.2), wave(0, 1, 0.2), wave(1, 1, 0.15), wave(1, -1, 0.15)];
        assert_eq!(classify(&labyrinth).0, SurfacePattern::Mixed);
        assert_eq!(classify(&[wave(1, 0, 1e-4)]).0, SurfacePattern::Flat);
    }
}
