//! Viscous (pseudo-dynamic) stabilisation of displacement control, in the spirit of ABAQUS's
//! `*STATIC, STABILIZE`: the end-shortening `d` is the pseudo-time, and each step from
//! `(d_0, u_0)` to `d = d_0 + h` minimises the strain energy plus
//! `E_v = eta / (2 h) sum_i c_i (u_i - u_0,i - (u_h(d) - u_h(d_0))_i)^2`,
//! a backward-Euler step of dampers on every unknown that act on the non-affine part of the
//! motion (`u_h` is the homogeneous solution of the bilayer, so uniform compression is not
//! damped). The damping is proportional to the stiffness, `c_i = K_ii` of the reference state,
//! so that `eta / h` is the damping relative to the elastic tangent at every scale of the mesh
//! (the cusp of a closing trough is an element-scale instability). The damper engages only
//! where cutting the step does not help: where a second undamped step cut by the step control
//! below `engage_below` (`1e-3`, a fifth of the usual step, or a fifth of a shorter largest step)
//! has failed before the steps grew back to full length; from there on it damps cut steps until
//! a step of full length converges. A last step shortened only to land on the end of the path is
//! not damped. Where the path is smooth it is not damped at all, so the onset and `A(d)` are
//! those of the elastic problem, also where a step was cut only because Newton's iteration
//! needed a closer start: just past a stiff layer's onset the wrinkle's amplitude grows as
//! `sqrt(d - d_c)` over a tiny interval of `d`, one cut step fails and the shorter ones converge
//! and grow back (damped from there, the flat state would be held past the onsets of many modes).
//! Approaching a snap the cut steps fail again and again. Across a snap the step is cut and
//! `eta / h` grows until the damped step is well posed, so the damper carries the jump. The
//! work of the damping forces, `eta / h |du|_c^2` per step, is summed and reported against the
//! strain energy; `eta` is cut whenever that fraction would exceed the budget, and the step is
//! redone.

use crate::error::{Error, Result};
use crate::fem::added::{AddedEnergy, Block, Diagonal};
use crate::fem::System;
use crate::homogeneous::homogeneous_state;
use crate::material::Bilayer;
use crate::protocol::basic_state::homogeneous_displacement;
use serde::{Deserialize, Serialize};

/// Damping coefficient and energy budget.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct StabilisationSettings {
    /// Initial `eta`: damping relative to the reference stiffness, times the step in `d`.
    pub eta: f64,
    /// Largest allowed ratio of the dissipated to the strain energy.
    pub budget: f64,
    /// Factor `eta` is multiplied by when a step would exceed the budget.
    pub cut: f64,
    /// Smallest `eta` tried before a step is given up.
    pub min_eta: f64,
    /// Steps in `d` at least this long are not damped.
    pub engage_below: f64,
}

impl Default for StabilisationSettings {
    /// `eta = 1e-6` (damping `1e-6 / h` of the stiffness, equal to it at `h = 1e-6`) on steps
    /// below `1e-3`, budget 1 %.
    fn default() -> Self {
        StabilisationSettings {
            eta: 1e-6,
            budget: 0.01,
            cut: 0.25,
            min_eta: 1e-9,
            engage_below: 1e-3,
        }
    }
}

impl StabilisationSettings {
    /// The same settings for a path whose steps are at most `max_step`: the damper engages only
    /// on steps cut below a fifth of it (and below `engage_below`), so that a path asked for
    /// short steps throughout is not damped where it is smooth.
    pub fn for_largest_step(mut self, max_step: f64) -> Self {
        self.engage_below = self.engage_below.min(0.2 * max_step);
        self
    }
}

/// What a resumed path needs of the stabilisation: `eta` (cut by the budget) and the energy
/// dissipated so far.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct StabilisationMemory {
    pub eta: f64,
    pub dissipated: f64,
    /// Whether a snap is being crossed ([`Stabilisation::note_undamped_failure`]).
    #[serde(default)]
    pub engaged: bool,
    /// Whether an undamped cut step has failed since the last step of full length.
    #[serde(default)]
    pub failed_undamped: bool,
}

/// The damper of one system and the energy it has dissipated.
#[derive(Clone, Debug)]
pub struct Stabilisation {
    pub settings: StabilisationSettings,
    materials: Bilayer,
    /// Diagonal `K_ii` of the reference stiffness (all unknowns).
    stiffness: Vec<f64>,
    eta: f64,
    dissipated: f64,
    /// Whether a snap is being crossed (a second undamped cut step has failed since the last
    /// step of full length): cut steps are damped.
    engaged: bool,
    /// Whether an undamped step cut below `engage_below` has failed since the last step of full
    /// length.
    failed_undamped: bool,
}

impl Stabilisation {
    /// The damper of `system`, proportional to the diagonal of its stiffness at `u = 0`. In
    /// elements with multipliers, the stiffness of the energy without its volumetric part:
    /// damping volume change by the penalty would hold the displacements against the
    /// multipliers' updates on short steps.
    pub fn new(system: &System, materials: &Bilayer, settings: StabilisationSettings) -> Result<Self> {
        let stiffness = system.reference_stiffness_diagonal()?;
        Ok(Stabilisation {
            settings,
            materials: *materials,
            stiffness,
            eta: settings.eta,
            dissipated: 0.0,
            engaged: false,
            failed_undamped: false,
        })
    }

    /// What a resumed path needs of it.
    pub fn memory(&self) -> StabilisationMemory {
        StabilisationMemory {
            eta: self.eta,
            dissipated: self.dissipated,
            engaged: self.engaged,
            failed_undamped: self.failed_undamped,
        }
    }

    /// Back to a state it had.
    pub fn recall(&mut self, memory: StabilisationMemory) {
        self.eta = memory.eta;
        self.dissipated = memory.dissipated;
        self.engaged = memory.engaged;
        self.failed_undamped = memory.failed_undamped;
    }

    /// The current `eta`.
    pub fn eta(&self) -> f64 {
        self.eta
    }

    /// Energy dissipated so far.
    pub fn dissipated(&self) -> f64 {
        self.dissipated
    }

    /// Whether a step made by a step control at `control_step` is one the damper may carry: cut
    /// below `engage_below`.
    pub fn engages(&self, control_step: f64) -> bool {
        control_step < self.settings.engage_below
    }

    /// Notes that an undamped step the damper may carry failed, returning whether the damper is
    /// now engaged: at the second such failure before a step of full length has converged (the
    /// cut steps did not grow back), cut steps are damped from here until a step of full length
    /// succeeds ([`Stabilisation::release`]); the first only asks the step control for a
    /// shorter step.
    pub fn note_undamped_failure(&mut self) -> bool {
        if self.failed_undamped {
            self.engaged = true;
        }
        self.failed_undamped = true;
        self.engaged
    }

    /// Notes a converged step made at `control_step`: one the damper would not carry ends the
    /// snap.
    pub fn release(&mut self, control_step: f64) {
        if !self.engages(control_step) {
            self.engaged = false;
            self.failed_undamped = false;
        }
    }

    /// The damper of the step from `(d0, u0)` to `d` on `system`'s mesh, made by a step control
    /// whose current step is `control_step`: zero damping unless a snap is being crossed and
    /// that step is below `engage_below` (a step shortened only to land on the end of the path
    /// is not damped).
    pub fn damper(&self, system: &System, (d0, u0): (f64, &[f64]), d: f64, control_step: f64) -> Result<Damper<'_>> {
        let mesh = system.mesh();
        let before = homogeneous_displacement(mesh, &homogeneous_state(&self.materials, d0)?);
        let after = homogeneous_displacement(mesh, &homogeneous_state(&self.materials, d)?);
        let reference = u0
            .iter()
            .zip(after.iter().zip(&before))
            .map(|(u, (a, b))| u + a - b)
            .collect();
        Ok(Damper {
            stiffness: &self.stiffness,
            reference,
            factor: if self.engaged && self.engages(control_step) {
                self.eta / (d - d0)
            } else {
                0.0
            },
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

/// The damping energy of one step: `factor / 2 sum_i c_i (u_i - reference_i)^2`, `factor = eta / h`.
pub struct Damper<'a> {
    stiffness: &'a [f64],
    reference: Vec<f64>,
    factor: f64,
}

impl Damper<'_> {
    /// Whether the step is damped at all.
    pub fn damps(&self) -> bool {
        self.factor != 0.0
    }

    /// The same damper with zero damping.
    pub fn undamped(self) -> Self {
        Damper { factor: 0.0, ..self }
    }

    /// Work of the damping forces on the step ending at `u`: `factor |u - reference|_c^2`
    /// (over the displacements; multipliers are not damped).
    pub fn dissipation(&self, u: &[f64]) -> f64 {
        let sum: f64 = (0..self.stiffness.len())
            .map(|i| self.stiffness[i] * (u[i] - self.reference[i]).powi(2))
            .sum();
        self.factor * sum
    }
}

impl AddedEnergy for Damper<'_> {
    fn groups(&self) -> &[Vec<usize>] {
        &[]
    }

    fn block(&self, g: usize, _: &[f64], _: bool) -> Block {
        unreachable!("a damper has no group {g}, only diagonal terms")
    }

    fn diagonal(&self, u: &[f64]) -> Option<Diagonal> {
        if self.factor == 0.0 {
            return None;
        }
        let curvature: Vec<f64> = self.stiffness.iter().map(|c| self.factor * c).collect();
        Some(Diagonal::quadratic(curvature, u, &self.reference))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{Mesh, MeshSpec};
    use crate::Parameters;

    /// The damper engages by the step control's step, not by the step's length, and only once
    /// two undamped cut steps have failed with no step of full length between (a snap): the last
    /// step shortened to land on `d_max` is as undamped as the full steps before it, a cut step
    /// is damped with `eta / h` of its own length `h` once engaged, and a converged step of full
    /// length releases it.
    #[test]
    fn only_steps_the_control_has_cut_are_damped_and_only_across_a_snap() {
        let materials = Bilayer::new(&Parameters::default());
        let system = System::new(Mesh::new(MeshSpec::new(4, 1, 2, 0.5, 4.0, 4.0)).unwrap(), &materials).unwrap();
        let mut stabilisation = Stabilisation::new(&system, &materials, StabilisationSettings::default()).unwrap();
        let u0 = vec![0.0; system.num_dofs()];
        let (d0, h) = (0.1, 2.5e-4);
        assert!(!stabilisation.damper(&system, (d0, &u0), d0 + h, h).unwrap().damps());
        assert!(stabilisation.engages(h) && !stabilisation.engages(5e-3));
        // One failure, then steps of full length again: Newton's iteration needed a closer start.
        // A resumed path remembers that failure.
        assert!(!stabilisation.note_undamped_failure());
        let after_one_failure = stabilisation.memory();
        let mut resumed = Stabilisation::new(&system, &materials, StabilisationSettings::default()).unwrap();
        resumed.recall(after_one_failure);
        assert!(resumed.note_undamped_failure());
        stabilisation.release(h);
        stabilisation.release(5e-3);
        assert!(!stabilisation.note_undamped_failure());
        assert!(!stabilisation.damper(&system, (d0, &u0), d0 + h, h).unwrap().damps());
        // A cut step converged, and the next cut step failed too: a snap.
        stabilisation.release(h);
        assert!(stabilisation.note_undamped_failure());
        stabilisation.release(h);
        let landing = stabilisation.damper(&system, (d0, &u0), d0 + h, 5e-3).unwrap();
        assert!(!landing.damps());
        let cut = stabilisation.damper(&system, (d0, &u0), d0 + h, h).unwrap();
        assert!(cut.damps());
        // Its force is eta / h times the stiffness: twice as short a cut step, twice the work.
        let shorter = stabilisation.damper(&system, (d0, &u0), d0 + h / 2.0, h / 2.0).unwrap();
        let moved = |damper: &Damper| -> Vec<f64> { damper.reference.iter().map(|r| r + 1e-3).collect() };
        let ratio = shorter.dissipation(&moved(&shorter)) / cut.dissipation(&moved(&cut));
        assert!((ratio - 2.0).abs() < 1e-12, "{ratio}");
        assert_eq!(landing.dissipation(&moved(&cut)), 0.0);
        let memory = stabilisation.memory();
        stabilisation.release(5e-3);
        assert!(!stabilisation.damper(&system, (d0, &u0), d0 + h, h).unwrap().damps());
        stabilisation.recall(memory);
        assert!(stabilisation.damper(&system, (d0, &u0), d0 + h, h).unwrap().damps());
    }
}
