//! The options of one `pattern` run by the names of its flags, with [`PatternStudy::default`]'s
//! values as their defaults: what the command line reads (`clap` fills this struct, with these
//! texts as the flags' help), turned into a validated [`PatternStudy`].

use super::{PathEnd, PathStudy, PatternStudy};
use crate::error::{Error, Result};
use crate::mesh::{ElementKind, Sides};
use crate::protocol::{BifurcationSettings, CheckpointInterval};

/// Every option of `fiberfold pattern`.
#[derive(Clone, Debug, PartialEq, clap::Args)]
pub struct PatternOptions {
    /// R = d_3 / d in [0, 1]: the compression along Z relative to X's (1 equibiaxial).
    #[arg(long, default_value_t = study().biaxial)]
    pub biaxial: f64,

    /// Periods of the theory's onset mode along each side of the patch (an integer >= 1).
    #[arg(long, default_value_t = study().periods)]
    pub periods: usize,

    /// Hexahedra per onset wavelength along X and Z (an integer >= 2; more give an onset closer
    /// to the continuum's, at a cost growing as their cube; the guide's "Patterns in three dimensions" shows the convergence).
    #[arg(long, default_value_t = study().elements_per_wavelength)]
    pub elements_per_wavelength: usize,

    /// The longest side of the patch, in onset wavelengths per period, in [1, inf]: where the
    /// onset mode's period along a side is longer (its wave vector within asin(1 / MAX_SIDE)
    /// of the other axis), that side is one wavelength per period and the patch holds the
    /// nearest wave vector along the other axis (printed, with its d_c).
    #[arg(long, default_value_t = study().max_side)]
    pub max_side: f64,

    /// Hexahedra through the layer (an integer >= 1).
    #[arg(long, default_value_t = study().layer_elements)]
    pub layer_elements: usize,

    /// Hexahedra through the substrate, graded from --h0 at the interface (an integer >= 1).
    #[arg(long, default_value_t = study().substrate_elements)]
    pub substrate_elements: usize,

    /// Thickness of the top substrate element, in layer thicknesses H, in (0, depth).
    #[arg(long, default_value_t = study().top_substrate_thickness)]
    pub h0: f64,

    /// Depth of the substrate in onset wavelengths, > 0 (the modes decay as exp(-k |Y|)).
    #[arg(long, default_value_t = study().depth_wavelengths)]
    pub depth: f64,

    /// How the sides hold the patch.
    #[arg(long, value_enum, default_value_t = study().sides)]
    pub sides: Sides,

    /// The hexahedra's element (27 nodes; mixed: with a linear pressure per element). The
    /// mixed one is the more accurate on a layer stiffer than the substrate, but finds a
    /// spurious mode at the element scale on a nearly incompressible half-space.
    #[arg(long, value_enum, default_value_t = study().element)]
    pub element: ElementKind,

    /// Largest d scanned for the bifurcation, in (0, 0.95].
    #[arg(long, default_value_t = study().settings.d_end)]
    pub d_max: f64,

    /// Width in d of the final bisection bracket, in [1e-12, 1e-2].
    #[arg(long, default_value_t = study().settings.tolerance)]
    pub tolerance: f64,

    /// Follow the path past the onset to this d, in (d-start, 0.95): the patch seeded with every
    /// wave vector critical at the onset (on symmetry sides the products of cosines they
    /// admit), one row of pattern.csv per state. Not followed if absent.
    #[arg(long, value_name = "D", conflicts_with = "follow_past")]
    pub follow_to: Option<f64>,

    /// Follow the path as --follow-to does, to this far past the exact theory's onset d_c
    /// (d_c + DELTA below 0.95): in a map of patterns each point ends as far past its own onset.
    #[arg(long, value_name = "DELTA")]
    pub follow_past: Option<f64>,

    /// Amplitude A_init of the first seeded wave of the path's imperfection, in layer
    /// thicknesses H, in (0, 1).
    #[arg(long, default_value_t = PathStudy::default().imperfection)]
    pub imperfection: f64,

    /// Amplitude of every further critical wave seeded, relative to the first's, in [0, 1]: 1
    /// seeds their equal superposition (a checkerboard, which the path then keeps by symmetry
    /// even where the tissue would leave it), less lets the path choose.
    #[arg(long, default_value_t = PathStudy::default().seed_ratio)]
    pub seed_ratio: f64,

    /// Where the followed path starts, in (0, the path's end).
    #[arg(long, default_value_t = PathStudy::default().d_start)]
    pub d_start: f64,

    /// Write the path's whole state to checkpoint.bin in the output folder after every N
    /// accepted states of the path past the onset (or --checkpoint-seconds, whichever comes
    /// first), for --resume; 0 writes none.
    #[arg(long, value_name = "N", default_value_t = CheckpointInterval::DEFAULT.states)]
    pub checkpoint_every: usize,

    /// Write a checkpoint at least this often, in seconds of wall time, in (0, inf).
    #[arg(long, value_name = "SECONDS", default_value_t = CheckpointInterval::DEFAULT.seconds, allow_negative_numbers = true)]
    pub checkpoint_seconds: f64,

    /// Continue the path past the onset from the checkpoint in the output folder (the patch is
    /// sized and its bifurcation found again first, as before): the states after it are those
    /// the uninterrupted run computes, bit for bit. A checkpoint of other parameters or
    /// options, of another version, or damaged, is refused (exit 2); with none, the path starts
    /// from the beginning.
    #[arg(long)]
    pub resume: bool,

    /// Run even when the memory estimate (printed with the patch: its factor's exact size)
    /// exceeds the memory available.
    #[arg(long)]
    pub force: bool,
}

/// The defaults the flags show.
fn study() -> PatternStudy {
    PatternStudy::default()
}

impl PatternOptions {
    /// The study these options ask for; a bisection tolerance or a largest `d` out of range is
    /// an error naming its flag (the others are checked where the patch is sized).
    pub fn study(&self) -> Result<PatternStudy> {
        if !(1e-12..=1e-2).contains(&self.tolerance) {
            return Err(Error::invalid("tolerance", self.tolerance, "[1e-12, 1e-2]"));
        }
        if !(self.d_max > 0.0 && self.d_max <= 0.95) {
            return Err(Error::invalid("d-max", self.d_max, "(0, 0.95]"));
        }
        let checkpoints = (self.checkpoint_every > 0).then_some(CheckpointInterval {
            states: self.checkpoint_every,
            seconds: self.checkpoint_seconds,
        });
        if let Some(interval) = checkpoints {
            interval.validate()?;
        }
        Ok(PatternStudy {
            biaxial: self.biaxial,
            periods: self.periods,
            elements_per_wavelength: self.elements_per_wavelength,
            max_side: self.max_side,
            layer_elements: self.layer_elements,
            substrate_elements: self.substrate_elements,
            top_substrate_thickness: self.h0,
            depth_wavelengths: self.depth,
            sides: self.sides,
            element: self.element,
            settings: BifurcationSettings {
                d_end: self.d_max,
                tolerance: self.tolerance,
                ..study().settings
            },
            path: match (self.follow_to, self.follow_past) {
                (Some(d_end), _) => Some(PathEnd::At(d_end)),
                (None, Some(past)) => Some(PathEnd::PastOnset(past)),
                (None, None) => None,
            }
            .map(|end| PathStudy {
                imperfection: self.imperfection,
                seed_ratio: self.seed_ratio,
                d_start: self.d_start,
                end,
            }),
            force: self.force,
            checkpoints,
            resume: self.resume,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    #[derive(Parser)]
    struct Flags {
        #[command(flatten)]
        options: PatternOptions,
    }

    fn parse(flags: &[&str]) -> PatternOptions {
        Flags::try_parse_from(["pattern"].iter().chain(flags)).unwrap().options
    }

    #[test]
    fn the_flags_at_their_defaults_are_the_default_study() {
        let study = parse(&[]).study().unwrap();
        let default = PatternStudy::default();
        assert_eq!(format!("{study:?}"), format!("{default:?}"));
        let followed = parse(&["--follow-to", "0.12", "--seed-ratio", "1"]).study().unwrap();
        let path = followed.path.expect("a path");
        assert_eq!((path.end, path.seed_ratio), (PathEnd::At(0.12), 1.0));
        let past = parse(&["--follow-past", "0.05"]).study().unwrap().path.expect("a path");
        assert_eq!(past.end, PathEnd::PastOnset(0.05));
        let message = |flags: &[&str]| parse(flags).study().unwrap_err().to_string();
        assert!(message(&["--tolerance", "1"]).contains("`tolerance`"));
        assert!(message(&["--d-max", "0.99"]).contains("`d-max`"));
    }
}
