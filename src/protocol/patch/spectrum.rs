//! The two-dimensional Fourier spectrum of a periodic patch's surface height: how much of each
//! admissible wave vector `k = 2 pi (m / Lx, n / Lz)` a field of the top surface holds.
//!
//! The top nodes of a periodic patch lie on a uniform grid of `2 nx x 2 nz` points, so the
//! discrete Fourier coefficient `c_mn = (1 / M) sum_j h_j exp(-i k . X_j)` is exact for every
//! trigonometric content below the grid's Nyquist limit; a wave `A cos(k . X + phi)` has
//! `|c_mn| = A / 2`, so `2 |c_mn|` is its amplitude.

use crate::mesh::{Mesh, X, Y, Z};
use serde::Serialize;
use std::f64::consts::PI;

/// One wave vector of the surface and its amplitude.
#[derive(Clone, Copy, Debug, Serialize)]
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

/// The spectrum of the top surface's `u_Y` of the full vector `u` on a periodic patch, for the
/// wave vectors below the grid's Nyquist limit, by decreasing amplitude.
pub fn surface_spectrum(mesh: &Mesh<3, 27>, u: &[f64]) -> Vec<WaveVector> {
    assert!(mesh.is_periodic(), "the spectrum of a periodic patch");
    let [length_x, _, length_z] = *mesh.periods();
    let spec = mesh.patch_spec();
    let (m_max, n_max) = (spec.nx as i64, spec.nz as i64);
    let top = mesh.node_set(crate::mesh::TOP);
    let samples: Vec<([f64; 3], f64)> = top
        .iter()
        .map(|&node| (mesh.coordinates()[node], u[mesh.dofs().dof(node, Y)]))
        .collect();
    let mut waves = Vec::new();
    for m in 0..m_max {
        for n in -(n_max - 1)..n_max {
            if m == 0 && n <= 0 {
                continue;
            }
            let (kx, kz) = (2.0 * PI * m as f64 / length_x, 2.0 * PI * n as f64 / length_z);
            let (re, im) = samples.iter().fold((0.0, 0.0), |(re, im), (x, h)| {
                let phase = kx * x[X] + kz * x[Z];
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{ElementKind, PatchSpec, Sides};

    #[test]
    fn an_oblique_wave_and_a_weaker_one_are_found_with_their_amplitudes() {
        let mesh = Mesh::patch(PatchSpec {
            nx: 4,
            nz: 3,
            length_x: 8.0,
            length_z: 6.0,
            layer_elements: 1,
            substrate_elements: 1,
            top_substrate_thickness: 3.0,
            depth: 3.0,
            sides: Sides::Periodic,
            element: ElementKind::Displacement,
        })
        .unwrap();
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
    }
}
