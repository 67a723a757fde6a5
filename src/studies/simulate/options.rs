//! The options of one `simulate` run and their defaults, turned into a validated
//! [`SimulateStudy`]: the one source of both. The CLI's flags take their defaults from
//! [`SimulateOptions::default`], and the Python package's keywords arrive as a JSON object read
//! by [`SimulateOptions::from_keywords`] (same names, missing ones at these defaults).

use super::{SimulateStudy, MODES};
use crate::error::{Error, Result};
use crate::fem::memory::{available_bytes, MemoryEstimate};
use crate::fem::ElementKind;
use crate::mesh::{MeshPreset, MeshSpec, XRefinement};
use crate::protocol::{
    mode_number, wavenumber_of_waves, Protocol, SnapCrossing, SnapSettings, StabilisationSettings, StepControl,
};
use crate::studies::keywords::{default_keywords, from_keywords};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// The mesh of a run as a user chooses it: a preset, and the numbers that replace its own.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct MeshChoice {
    #[serde(rename = "mesh")]
    pub preset: MeshPreset,
    /// Elements along X.
    pub nx: Option<usize>,
    /// Elements through the layer.
    pub layer_elements: Option<usize>,
    /// Graded elements through the substrate.
    pub substrate_elements: Option<usize>,
    /// Thickness of the top substrate element at `Y = 0`.
    pub h0: Option<f64>,
    /// Growth ratio of consecutive substrate elements in `[1, 2]`, instead of `h0`.
    pub grading: Option<f64>,
    pub element: ElementKind,
    /// Length and depth of the half domain, where a study sets them (the presets' 50 H
    /// otherwise; not a user's option).
    #[serde(skip)]
    pub length: Option<f64>,
    #[serde(skip)]
    pub depth: Option<f64>,
}

impl MeshChoice {
    /// The validated mesh specification.
    pub fn resolve(&self) -> Result<MeshSpec> {
        let mut spec = self
            .preset
            .spec()
            .with_overrides(self.nx, self.layer_elements, self.substrate_elements, self.h0)
            .with_element(self.element);
        spec.length = self.length.unwrap_or(spec.length);
        spec.depth = self.depth.unwrap_or(spec.depth);
        if let Some(r) = self.grading {
            if self.h0.is_some() {
                return Err(Error::invalid(
                    "grading",
                    r,
                    "absent when h0 is given (the one sets the other)",
                ));
            }
            spec = spec.with_grading(r)?;
        }
        spec.validate()?;
        Ok(spec)
    }
}

/// Every option of `fiberfold simulate` (same names, units and defaults; see its `--help`).
/// As keywords (JSON, Python) the mesh's are at the top level and `crossing` is
/// `stabilisation`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct SimulateOptions {
    #[serde(flatten)]
    pub mesh: MeshChoice,
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
    #[serde(rename = "stabilisation")]
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
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, clap::ValueEnum)]
#[serde(rename_all = "lowercase")]
pub enum Crossing {
    /// Minimise the energy at the `d` of the failed step: the stable equilibrium the structure
    /// snaps to ([`crate::protocol::snap`]); in contact, a failed step from a stable state is
    /// corrected by the same minimisation from the predictor. Every recorded state is an
    /// exact equilibrium; slower than the damper on a path through contact.
    #[value(help = "minimise the energy: every recorded state an exact equilibrium")]
    Snap,
    /// Viscous damping of the cut steps, as ABAQUS's `*STATIC, STABILIZE`: the recorded
    /// states carry damping forces ([`crate::protocol::stabilisation`]).
    #[default]
    #[value(help = "viscous damping of the cut steps (recorded states carry damping forces)")]
    Viscous,
    /// Neither: the path stops where Newton's method cannot follow it.
    #[value(help = "neither: the path stops where Newton's method cannot follow it")]
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
            mesh: MeshChoice::default(),
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
    /// The options named in `keywords`, a JSON object of option names (the mesh's among them,
    /// `stabilisation` for the crossing) and values; the others at their defaults. An unknown
    /// name, or a value of the wrong type, is an error naming it.
    pub fn from_keywords(keywords: &str) -> Result<Self> {
        from_keywords("simulate", keywords)
    }

    /// The defaults as keywords (a JSON object).
    pub fn default_keywords() -> String {
        default_keywords::<Self>()
    }

    /// The validated study; a bad option is an [`Error::InvalidParameter`] naming it.
    pub fn study(&self) -> Result<SimulateStudy> {
        let mut mesh = self.mesh.resolve()?;
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
        protocol.crossing = match self.crossing {
            Crossing::Snap => SnapCrossing::Minimised(SnapSettings::default()),
            Crossing::Viscous => SnapCrossing::Viscous(StabilisationSettings {
                eta: self.eta,
                ..StabilisationSettings::default()
            }),
            Crossing::None => SnapCrossing::None,
        };
        let study = SimulateStudy {
            mesh,
            protocol,
            vtu_every: self.vtu_every,
            secondary_modes: MODES,
        };
        study.validate()?;
        if !self.force {
            MemoryEstimate::of(&study.mesh).check(available_bytes())?;
        }
        Ok(study)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keywords_are_the_options_by_name_over_their_defaults() {
        assert_eq!(
            SimulateOptions::from_keywords("{}").unwrap(),
            SimulateOptions::default()
        );
        let options = SimulateOptions::from_keywords(
            r#"{"mesh": "fine", "nx": 300, "element": "mixed", "stabilisation": "snap", "waves": 4.5, "contact": false}"#,
        )
        .unwrap();
        assert_eq!(options.mesh.preset, MeshPreset::Fine);
        assert_eq!((options.mesh.nx, options.mesh.element), (Some(300), ElementKind::Mixed));
        assert_eq!(
            (options.crossing, options.waves, options.contact),
            (Crossing::Snap, Some(4.5), false)
        );
        assert_eq!(options.d_max, SimulateOptions::default().d_max);
        let message = |text: &str| SimulateOptions::from_keywords(text).unwrap_err().to_string();
        assert!(message(r#"{"bogus": 1}"#).contains("bogus for `keyword`"));
        assert!(message(r#"{"d_max": "far"}"#).contains("`d_max` takes a number"));
        assert!(message(r#"{"mesh": "huge"}"#).contains("`coarse`, `fine`, `extra`"));
        assert!(
            message(r#"{"length": 20}"#).contains("`keyword`"),
            "length is not a user's option"
        );
    }

    #[test]
    fn a_chosen_mesh_is_its_preset_with_the_numbers_replaced() {
        let choice = MeshChoice {
            nx: Some(40),
            layer_elements: Some(3),
            substrate_elements: Some(12),
            h0: Some(1.0 / 3.0),
            length: Some(23.7),
            depth: Some(40.0),
            ..MeshChoice::default()
        };
        assert_eq!(
            choice.resolve().unwrap(),
            MeshSpec::new(40, 3, 12, 1.0 / 3.0, 23.7, 40.0)
        );
        // (Through black_box: a constant-folded `powi` may differ from the run-time one in the last bit.)
        let ratio = std::hint::black_box(1.2);
        let graded = MeshChoice {
            grading: Some(ratio),
            ..MeshChoice::default()
        };
        assert_eq!(
            graded.resolve().unwrap(),
            MeshSpec::coarse().with_grading(ratio).unwrap()
        );
        let both = MeshChoice {
            h0: Some(0.3),
            ..graded
        };
        assert!(both.resolve().unwrap_err().to_string().contains("`grading`"));
    }
}
