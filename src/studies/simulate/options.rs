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
    mode_number, wavenumber_of_waves, CheckpointInterval, ContinuationMethod, Protocol, SnapCrossing, SnapSettings,
    StabilisationSettings, StepControl, STAGE_ONE_COMPRESSION,
};
use crate::studies::keywords::{default_keywords, from_keywords};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// The mesh of a run as a user chooses it: a preset, and the numbers that replace its own. As
/// command-line flags, the mesh of the half domain 0 <= X <= L, -D <= Y <= 1 (L = D = 50).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize, clap::Args)]
#[serde(default)]
pub struct MeshChoice {
    /// Mesh preset.
    #[serde(rename = "mesh")]
    #[arg(id = "mesh", long = "mesh", value_name = "MESH", value_enum, default_value_t = MeshPreset::default())]
    pub preset: MeshPreset,
    /// Elements along X (overrides the preset).
    #[arg(long)]
    pub nx: Option<usize>,
    /// Elements through the layer 0 <= Y <= 1 (overrides the preset).
    #[arg(long)]
    pub layer_elements: Option<usize>,
    /// Geometrically graded elements through the substrate (overrides the preset).
    #[arg(long)]
    pub substrate_elements: Option<usize>,
    /// Thickness of the top substrate element at Y = 0, in (0, 50) (overrides the preset).
    #[arg(long, conflicts_with = "grading", allow_negative_numbers = true)]
    pub h0: Option<f64>,
    /// Growth ratio of consecutive substrate elements in [1, 2], instead of --h0.
    #[arg(long, allow_negative_numbers = true)]
    pub grading: Option<f64>,
    /// Finite element on the mesh. mixed, the default, is the more accurate at every K/mu
    /// (Table 1's 3 too: Fig. 7's first contact 0.239 vs 0.256 on the fine mesh, refined meshes
    /// 0.233-0.241) for about 5 % more time per Newton iteration, and the only one for
    /// incompressible = true. displacement, the paper's element, locks above K/mu ~ 100.
    #[arg(long, value_enum, default_value_t = ElementKind::default())]
    pub element: ElementKind,
    /// Length L of the half domain between its symmetry planes, in H [default: 50] (the
    /// presets' element counts are kept: set --nx with it).
    #[arg(long, allow_negative_numbers = true)]
    pub length: Option<f64>,
    /// Depth D of the substrate, in H [default: 50]; keep it above the longest wavelength
    /// seeded so that the bottom does not hold the mode.
    #[arg(long, allow_negative_numbers = true)]
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

/// Every option of `fiberfold simulate`: its flags (`clap` reads them into this struct, with
/// these defaults and these texts as their help) and the Python keywords (the same names; the
/// mesh's at the top level, `crossing` as `stabilisation` and `contact`, `inertia` as booleans).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, clap::Args)]
#[serde(default)]
#[command(group(clap::ArgGroup::new("seed").required(true).args(["waves", "k"])))]
pub struct SimulateOptions {
    #[serde(flatten)]
    #[command(flatten)]
    pub mesh: MeshChoice,

    /// Waves N of the seeded mode across the half domain, 2N a positive integer: k = 2 pi N / L.
    #[arg(long, allow_negative_numbers = true)]
    pub waves: Option<f64>,

    /// Referential wavenumber of the seeded mode, k = m pi / L with m a positive integer.
    #[arg(long, allow_negative_numbers = true)]
    pub k: Option<f64>,

    /// Final end-shortening d, in (d-start, 1); under --load growth the strain d = 1 - 1/g of
    /// the final growth g (0.2: g = 1.25).
    #[arg(long, default_value_t = defaults().d_max, allow_negative_numbers = true)]
    pub d_max: f64,

    /// End-shortening of stage 1 (the perfect bilayer compressed homogeneously) where the
    /// imperfection is seeded, in (0, 1); keep it below the onset d_c (a layer a thousand
    /// times stiffer than the substrate wrinkles at d_c = 0.005: take about d_c / 2).
    #[arg(long, default_value_t = defaults().d_start, allow_negative_numbers = true)]
    pub d_start: f64,

    /// Amplitude A_init of the seeded imperfection, in (-1, 1) (0: the perfect system). The
    /// reference geometry is perturbed by Delta Y = A_init cos(k X) s(Y), s = 1 in the layer and
    /// sinh(k (Y + D)) / sinh(D k) in the substrate, after stage 1 (homogeneous to d-start).
    /// Negative puts a trough on each symmetry plane, so that a period doubling of the troughs
    /// (seeded by --imperfection2-waves N/2) fits the half domain.
    #[arg(long, default_value_t = defaults().imperfection, allow_negative_numbers = true)]
    pub imperfection: f64,

    /// Largest step in d, also the largest gap between recorded states.
    #[arg(long, default_value_t = defaults().max_step, allow_negative_numbers = true)]
    pub max_step: f64,

    /// Smallest step in d; a failure at this step stops the run (snaps to a crease are
    /// crossed with steps down to about eta / 10).
    #[arg(long, default_value_t = defaults().min_step, allow_negative_numbers = true)]
    pub min_step: f64,

    /// Newton steps with a newly factorised tangent allowed per load step before the step is
    /// cut, in [1, 100] (steps with the reused factorisation are bounded by twice this).
    #[arg(long, default_value_t = defaults().max_newton_iterations)]
    pub max_newton_iterations: usize,

    /// Refine the mesh in X near the troughs of the seeded mode: elements RATIO times smaller
    /// there (Gaussian bumps of width --refine-width), the same number of elements in X.
    #[arg(long, value_name = "RATIO", allow_negative_numbers = true)]
    pub refine_troughs: Option<f64>,

    /// Width in X of the refinement around each trough.
    #[arg(long, default_value_t = defaults().refine_width, allow_negative_numbers = true)]
    pub refine_width: f64,

    /// Amplitude A2 of the long-wave imperfection -A2 cos(2 pi N2 X / L) of the reference
    /// geometry, in [0, 1): it lets the pattern leave an unstable periodic branch (use the
    /// shape of the first secondary mode: its N2 is printed at the end of a periodic run).
    #[arg(long, default_value_t = defaults().imperfection2, allow_negative_numbers = true)]
    pub imperfection2: f64,

    /// Waves N2 of the long-wave imperfection across the domain, 2 N2 a positive integer
    /// (0.5: one half wave, deepest at X = 0; N/2: a period doubling, of the troughs when
    /// --imperfection is negative and of the crests otherwise).
    #[arg(long, value_name = "N2", default_value_t = defaults().imperfection2_waves, allow_negative_numbers = true)]
    pub imperfection2_waves: f64,

    /// Turn off contact of the top surface with the symmetry planes and with itself.
    #[arg(id = "no_contact", long = "no-contact", action = clap::ArgAction::SetFalse)]
    pub contact: bool,

    /// How to cross a snap (a limit point in d, a closing trough), where Newton's method cannot
    /// follow the branch: `viscous` damps, from the second failed undamped step cut below 1e-3
    /// (a fifth of --max-step if that is shorter) before the steps grew back, the cut steps
    /// until a full step converges (ABAQUS's *STATIC, STABILIZE: those recorded states carry
    /// damping forces); `snap` minimises the energy where a step of 1e-6 fails and records the
    /// stable equilibrium reached (snaps.json: every recorded state an exact equilibrium; in
    /// contact a failed step from a stable state is corrected by minimisation too, `minimised`
    /// in amplitude.csv; slower than `viscous` through contact); `none` stops where Newton's
    /// method fails.
    #[serde(rename = "stabilisation")]
    #[arg(id = "stabilisation", long = "stabilisation", value_name = "STABILISATION", value_enum,
          default_value_t = defaults().crossing)]
    pub crossing: Crossing,

    /// How stage 3 follows the path: `displacement` control raises d step by step and crosses a
    /// snap as --stabilisation says; `arc-length` makes d an unknown and goes round a limit
    /// point in d along the unstable branch (amplitude.csv then has d falling and rising, and
    /// the inertia of every state; needs --no-contact --stabilisation none).
    #[arg(long, value_name = "METHOD", value_enum, default_value_t = defaults().continuation)]
    pub continuation: ContinuationMethod,

    /// Viscous stabilisation's damping eta / h relative to the reference stiffness on a step h
    /// in d, in (0, inf) (with --stabilisation viscous).
    #[arg(long, default_value_t = defaults().eta, allow_negative_numbers = true)]
    pub eta: f64,

    /// Do not track the number of negative eigenvalues of the tangent at every converged state
    /// (saves the extra factorisation of damped and contact states; secondary.json then has no
    /// bifurcations). Ignored with --stabilisation snap, which needs the inertia to tell a
    /// stable state.
    #[arg(id = "no_inertia", long = "no-inertia", action = clap::ArgAction::SetFalse)]
    pub inertia: bool,

    /// Spacing in d of the VTU snapshots.
    #[arg(long, default_value_t = defaults().vtu_every, allow_negative_numbers = true)]
    pub vtu_every: f64,

    /// Write the path's whole state to checkpoint.bin in the output folder after every N
    /// accepted states (or --checkpoint-seconds, whichever comes first), for --resume; 0 writes
    /// none. A path of arc length writes none.
    #[arg(long, value_name = "N", default_value_t = defaults().checkpoint_every)]
    pub checkpoint_every: usize,

    /// Write a checkpoint at least this often, in seconds of wall time, in (0, inf).
    #[arg(long, value_name = "SECONDS", default_value_t = defaults().checkpoint_seconds, allow_negative_numbers = true)]
    pub checkpoint_seconds: f64,

    /// Continue the run from the checkpoint in the output folder: the states after it are those
    /// the uninterrupted run computes, bit for bit. A checkpoint of other parameters or options,
    /// of another version, or damaged, is refused (exit 2); with none, the run starts from the
    /// beginning (so a requeued job may always pass --resume).
    #[arg(long)]
    pub resume: bool,

    /// Run even when the memory estimate (printed in the header) exceeds the memory available.
    #[arg(long)]
    pub force: bool,
}

/// The defaults the flags show.
fn defaults() -> SimulateOptions {
    SimulateOptions::default()
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
            d_start: STAGE_ONE_COMPRESSION,
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
            continuation: ContinuationMethod::Displacement,
            eta: 1e-6,
            inertia: true,
            vtu_every: 0.01,
            checkpoint_every: CheckpointInterval::DEFAULT.states,
            checkpoint_seconds: CheckpointInterval::DEFAULT.seconds,
            resume: false,
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
        protocol.d_start = self.d_start;
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
        protocol.method = self.continuation;
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
            checkpoints: (self.checkpoint_every > 0).then_some(CheckpointInterval {
                states: self.checkpoint_every,
                seconds: self.checkpoint_seconds,
            }),
            resume: self.resume,
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
        let domain = SimulateOptions::from_keywords(r#"{"waves": 2, "length": 40.4, "depth": 80}"#).unwrap();
        assert_eq!((domain.mesh.length, domain.mesh.depth), (Some(40.4), Some(80.0)));
        let negative = SimulateOptions::from_keywords(r#"{"waves": 2, "length": -3}"#).unwrap();
        assert!(negative.study().unwrap_err().to_string().contains("`mesh.length`"));
        let late = SimulateOptions::from_keywords(r#"{"waves": 2, "d_start": 0.25, "d_max": 0.2}"#).unwrap();
        let message = late.study().unwrap_err().to_string();
        assert!(
            message.contains("`d-max`") && message.contains("(0.25, 1)"),
            "{message}"
        );
        let start = SimulateOptions::from_keywords(r#"{"waves": 2, "d_start": 0}"#).unwrap();
        assert!(start.study().unwrap_err().to_string().contains("`d-start`"));
    }

    #[test]
    fn the_flags_read_into_the_options_at_the_same_defaults() {
        use clap::Parser;
        #[derive(Parser)]
        struct Flags {
            #[command(flatten)]
            options: SimulateOptions,
        }
        let parse = |flags: &[&str]| Flags::try_parse_from(["simulate"].iter().chain(flags)).map(|f| f.options);
        assert_eq!(
            parse(&["--waves", "4.5"]).unwrap(),
            SimulateOptions {
                waves: Some(4.5),
                ..SimulateOptions::default()
            }
        );
        let chosen = parse(&[
            "--k",
            "0.5",
            "--mesh",
            "fine",
            "--element",
            "displacement",
            "--no-contact",
            "--no-inertia",
            "--stabilisation",
            "snap",
        ])
        .unwrap();
        assert_eq!(
            (chosen.k, chosen.mesh.preset, chosen.mesh.element),
            (Some(0.5), MeshPreset::Fine, ElementKind::Displacement)
        );
        assert_eq!(
            (chosen.contact, chosen.inertia, chosen.crossing),
            (false, false, Crossing::Snap)
        );
        let domain = parse(&[
            "--waves",
            "2",
            "--length",
            "40.4",
            "--depth",
            "80",
            "--imperfection",
            "-0.05",
        ])
        .unwrap();
        assert_eq!(
            (domain.mesh.length, domain.mesh.depth, domain.imperfection),
            (Some(40.4), Some(80.0), -0.05)
        );
        assert!(parse(&[]).is_err(), "a seeded wave is required");
        assert!(parse(&["--waves", "4", "--k", "0.5"]).is_err());
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
