//! The options of one `simulate` run, with the command line's defaults, turned into a
//! validated [`SimulateStudy`]: the CLI and the Python package build their runs here.

use super::SimulateStudy;
use crate::error::{Error, Result};
use crate::fem::memory::{available_bytes, MemoryEstimate};
use crate::mesh::{MeshSpec, XRefinement};
use crate::protocol::{mode_number, wavenumber_of_waves, Protocol, SnapSettings, StabilisationSettings, StepControl};
use std::f64::consts::PI;

/// Every option of `fiberfold simulate` (same names, units and defaults; see its `--help`).
#[derive(Clone, Debug, PartialEq)]
pub struct SimulateOptions {
    pub mesh: MeshSpec,
    /// Waves `N` across the half domain (`2N` a positive integer), or else `k`.
    pub waves: Option<f64>,
    pub k: Option<f64>,
    pub d_max: f64,
    pub imperfection: f64,
    pub max_step: f64,
    pub min_step: f64,
    /// Newton steps with a new tangent per load step, in [1, 100].
    pub max_newton_iterations: usize,
    pub refine_troughs: Option<f64>,
    pub refine_width: f64,
    pub imperfection2: f64,
    pub imperfection2_waves: f64,
    pub contact: bool,
    /// How stage 3 crosses where the branch it follows has no nearby equilibrium.
    pub crossing: Crossing,
    /// `eta` of the viscous stabilisation (with [`Crossing::Viscous`]).
    pub eta: f64,
    /// Track the inertia of the tangent at every accepted state.
    pub inertia: bool,
    pub vtu_every: f64,
    /// Run even when the memory estimate exceeds the memory available.
    pub force: bool,
}

/// How stage 3 crosses a snap: where the branch it follows has no nearby equilibrium (a limit
/// point in `d`, a closing trough).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Crossing {
    /// Minimise the energy at the `d` of the failed step: the stable equilibrium the structure
    /// snaps to ([`crate::protocol::snap`]). Every recorded state is an exact equilibrium; a
    /// snap onto a closing trough (contact) is not yet found reliably, and the path then stops
    /// there with its reason.
    Snap,
    /// Viscous damping of the cut steps, as ABAQUS's `*STATIC, STABILIZE`: the recorded
    /// states carry damping forces ([`crate::protocol::stabilisation`]).
    #[default]
    Viscous,
    /// Neither: the path stops where Newton's method cannot follow it.
    None,
}

impl Crossing {
    /// The crossing named `snap`, `viscous` or `none`.
    pub fn from_name(name: &str) -> Result<Self> {
        match name {
            "snap" => Ok(Crossing::Snap),
            "viscous" => Ok(Crossing::Viscous),
            "none" => Ok(Crossing::None),
            other => Err(Error::invalid("stabilisation", other, "snap, viscous or none")),
        }
    }
}

impl Default for SimulateOptions {
    /// The command line's defaults on the coarse mesh (no wave chosen yet).
    fn default() -> Self {
        SimulateOptions {
            mesh: MeshSpec::coarse(),
            waves: None,
            k: None,
            d_max: 0.3,
            imperfection: 0.05,
            max_step: 0.005,
            min_step: 1e-7,
            max_newton_iterations: 8,
            refine_troughs: None,
            refine_width: 1.0,
            imperfection2: 0.0,
            imperfection2_waves: 0.5,
            contact: true,
            crossing: Crossing::Viscous,
            eta: 1e-6,
            inertia: true,
            vtu_every: 0.01,
            force: false,
        }
    }
}

impl SimulateOptions {
    /// The validated study; a bad option is an [`Error::InvalidParameter`] naming it.
    pub fn study(&self) -> Result<SimulateStudy> {
        let mut mesh = self.mesh;
        mesh.validate()?;
        let k = match (self.waves, self.k) {
            (Some(waves), _) => wavenumber_of_waves(waves, mesh.length)?,
            (None, Some(k)) => mode_number(k, mesh.length)? as f64 * PI / mesh.length,
            (None, None) => return Err(Error::invalid("waves", "none", "--waves N or --k K")),
        };
        if let Some(ratio) = self.refine_troughs {
            // The troughs of A_init cos(k X) (A_init > 0): X = (2 j + 1) pi / k.
            mesh = mesh.refined(XRefinement {
                ratio,
                width: self.refine_width,
                offset: PI / k,
                period: 2.0 * PI / k,
            });
            mesh.validate()?;
        }
        if !(1..=100).contains(&self.max_newton_iterations) {
            return Err(Error::invalid(
                "max-newton-iterations",
                self.max_newton_iterations,
                "[1, 100]",
            ));
        }
        let mut protocol = Protocol::new(k, self.imperfection, self.d_max);
        protocol.control = StepControl {
            initial: self.max_step,
            max: self.max_step,
            min: self.min_step,
            ..StepControl::default()
        };
        protocol.newton.max_iterations = self.max_newton_iterations;
        protocol.newton.inertia_at_solution = self.inertia;
        protocol.imperfection2 = self.imperfection2;
        protocol.imperfection2_waves = self.imperfection2_waves;
        protocol.contact = self.contact;
        if !(self.eta.is_finite() && self.eta > 0.0) {
            return Err(Error::invalid("eta", self.eta, "(0, inf)"));
        }
        (protocol.snaps, protocol.stabilisation) = match self.crossing {
            Crossing::Snap => (Some(SnapSettings::default()), None),
            Crossing::Viscous => (
                None,
                Some(StabilisationSettings {
                    eta: self.eta,
                    ..StabilisationSettings::default()
                }),
            ),
            Crossing::None => (None, None),
        };
        let study = SimulateStudy {
            mesh,
            protocol,
            vtu_every: self.vtu_every,
        };
        study.validate()?;
        if !self.force {
            MemoryEstimate::of(&study.mesh).check(available_bytes())?;
        }
        Ok(study)
    }
}
