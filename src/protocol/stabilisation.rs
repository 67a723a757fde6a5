//! Viscous (pseudo-dynamic) stabilisation of displacement control, in the spirit of ABAQUS's
//! `*STATIC, STABILIZE`: the end-shortening `d` is the pseudo-time, and each step from
//! `(d_0, u_0)` to `d = d_0 + h` minimises the strain energy plus
//! `E_v = eta / (2 h) sum_n m_n |u_n - u_0,n - (u_h(d) - u_h(d_0))_n|^2`,
//! a backward-Euler step of a damper with lumped nodal areas `m_n` (unit-density mass) that acts
//! on the non-affine part of the motion (`u_h` is the homogeneous solution of the bilayer, so
//! uniform compression is not damped). Where the path is smooth the damping force
//! `eta / h m du` is of order `eta`, negligible; across a snap the step is cut and `eta / h`
//! grows, so the damper carries the jump. The energy it dissipates, `eta / h |du|_m^2` per step,
//! is summed and reported against the strain energy; `eta` is cut whenever that fraction would
//! exceed the budget, and the step is redone.

use crate::error::{Error, Result};
use crate::fem::added::{AddedEnergy, Block};
use crate::fem::element::{gauss_rule, shape_functions};
use crate::fem::System;
use crate::homogeneous::homogeneous_state;
use crate::material::Bilayer;
use crate::protocol::bifurcation::homogeneous_displacement;

/// Damping coefficient and energy budget.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct StabilisationSettings {
    /// Initial `eta`, in units of `mu_s H^-2` times `d` (the pseudo-time).
    pub eta: f64,
    /// Largest allowed ratio of the dissipated to the strain energy.
    pub budget: f64,
    /// Factor `eta` is multiplied by when a step would exceed the budget.
    pub cut: f64,
    /// Smallest `eta` tried before a step is given up.
    pub min_eta: f64,
}

impl Default for StabilisationSettings {
    /// `eta = 1e-5` (the damping force is `1e-5 / h` of the elastic scale: negligible at the
    /// usual step `h = 0.005`, of order one at the smallest step `1e-5`), budget 1 %.
    fn default() -> Self {
        StabilisationSettings {
            eta: 1e-5,
            budget: 0.01,
            cut: 0.25,
            min_eta: 1e-9,
        }
    }
}

/// The damper of one system and the energy it has dissipated.
#[derive(Clone, Debug)]
pub struct Stabilisation {
    pub settings: StabilisationSettings,
    materials: Bilayer,
    /// Lumped nodal areas `m_n = sum_e int N_n dA`.
    masses: Vec<f64>,
    groups: Vec<Vec<usize>>,
    eta: f64,
    dissipated: f64,
}

impl Stabilisation {
    /// The damper of `system` (nodal areas from its elements' Gauss weights).
    pub fn new(system: &System, materials: &Bilayer, settings: StabilisationSettings) -> Self {
        let mesh = system.mesh();
        let mut masses = vec![0.0; mesh.num_nodes()];
        let shapes: Vec<_> = gauss_rule().iter().map(|(xi, _)| shape_functions(*xi)).collect();
        for (nodes, geometry) in mesh.elements().iter().zip(system.geometry()) {
            for (w, n) in geometry.weights().iter().zip(&shapes) {
                for (a, &node) in nodes.iter().enumerate() {
                    masses[node] += w * n[a];
                }
            }
        }
        Stabilisation {
            settings,
            materials: *materials,
            masses,
            groups: (0..mesh.num_nodes()).map(|n| vec![2 * n, 2 * n + 1]).collect(),
            eta: settings.eta,
            dissipated: 0.0,
        }
    }

    /// The current `eta`.
    pub fn eta(&self) -> f64 {
        self.eta
    }

    /// Energy dissipated so far.
    pub fn dissipated(&self) -> f64 {
        self.dissipated
    }

    /// The damper of the step from `(d0, u0)` to `d` on `system`'s mesh.
    pub fn damper(&self, system: &System, d0: f64, u0: &[f64], d: f64) -> Result<Damper<'_>> {
        let mesh = system.mesh();
        let before = homogeneous_displacement(mesh, &homogeneous_state(&self.materials, d0)?);
        let after = homogeneous_displacement(mesh, &homogeneous_state(&self.materials, d)?);
        let reference = u0.iter().zip(after.iter().zip(&before)).map(|(u, (a, b))| u + a - b).collect();
        Ok(Damper {
            groups: &self.groups,
            masses: &self.masses,
            reference,
            factor: self.eta / (d - d0),
        })
    }

    /// Books a converged step's dissipation if the total stays within the budget of
    /// `strain_energy`, returning the fraction; otherwise cuts `eta` and returns `None` (the
    /// step must be redone), or fails once `eta` is below its minimum.
    pub fn book(&mut self, step_dissipation: f64, strain_energy: f64) -> Result<Option<f64>> {
        let fraction = (self.dissipated + step_dissipation) / strain_energy;
        if fraction <= self.settings.budget {
            self.dissipated += step_dissipation;
            return Ok(Some(fraction));
        }
        self.eta *= self.settings.cut;
        if self.eta < self.settings.min_eta {
            return Err(Error::Solver(format!(
                "stabilisation: the dissipated energy would be {fraction:.2e} of the strain energy, above the budget {}, even at eta = {:.1e}",
                self.settings.budget, self.eta
            )));
        }
        Ok(None)
    }
}

/// The damping energy of one step: `factor / 2 sum_n m_n |u_n - reference_n|^2`, `factor = eta / h`.
pub struct Damper<'a> {
    groups: &'a [Vec<usize>],
    masses: &'a [f64],
    reference: Vec<f64>,
    factor: f64,
}

impl Damper<'_> {
    /// The same groups with zero damping: the undamped tangent on the same pattern.
    pub fn undamped(self) -> Self {
        Damper { factor: 0.0, ..self }
    }

    /// Energy the damper dissipates on the step ending at `u`: `factor |u - reference|_m^2`.
    pub fn dissipation(&self, u: &[f64]) -> f64 {
        let r = &self.reference;
        let sum: f64 = (0..self.masses.len())
            .map(|n| self.masses[n] * ((u[2 * n] - r[2 * n]).powi(2) + (u[2 * n + 1] - r[2 * n + 1]).powi(2)))
            .sum();
        self.factor * sum
    }
}

impl AddedEnergy for Damper<'_> {
    fn groups(&self) -> &[Vec<usize>] {
        self.groups
    }

    fn block(&self, g: usize, u: &[f64], with_tangent: bool) -> Block {
        let c = self.factor * self.masses[g];
        let v = [u[2 * g] - self.reference[2 * g], u[2 * g + 1] - self.reference[2 * g + 1]];
        Block {
            energy: 0.5 * c * (v[0] * v[0] + v[1] * v[1]),
            gradient: vec![c * v[0], c * v[1]],
            hessian: if with_tangent { vec![c, 0.0, 0.0, c] } else { Vec::new() },
        }
    }
}
