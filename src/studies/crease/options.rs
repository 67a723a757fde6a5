//! `crease`'s options by the names of its flags (`--fold` is `folds`, `--no-convergence` is
//! `convergence = false`), with the defaults of [`CreaseStudy::default`]: what the command line
//! fills in, and what the Python package reads from its keywords ([`CreaseOptions::from_keywords`]).

use super::{CreaseMesh, CreaseStudy, Criterion, Refinement, Scan};
use crate::error::Result;
use crate::fem::ElementKind;
use crate::studies::keywords::{default_keywords, from_keywords};
use serde::{Deserialize, Serialize};

/// One `crease` computation as a user chooses it; `clap` reads the flags into it, with these
/// texts as their help and [`CreaseStudy::default`]'s values as their defaults.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, clap::Args)]
#[serde(default)]
pub struct CreaseOptions {
    /// Reference fold lengths a (units of H), comma separated: the onset is the smallest
    /// threshold over them, reported with its a.
    #[arg(id = "fold", long = "fold", value_name = "FOLD", value_delimiter = ',', default_value = DEFAULT_FOLDS,
          allow_negative_numbers = true)]
    pub folds: Vec<f64>,

    /// First compression d scanned.
    #[arg(long, default_value_t = defaults().d_from, allow_negative_numbers = true)]
    pub d_from: f64,

    /// Last compression d scanned (below 1).
    #[arg(long, default_value_t = defaults().d_to, allow_negative_numbers = true)]
    pub d_to: f64,

    /// Step of the scan in d.
    #[arg(long, default_value_t = defaults().d_step, allow_negative_numbers = true)]
    pub d_step: f64,

    /// Width in d to which each threshold is located on each mesh.
    #[arg(long, default_value_t = defaults().tolerance, allow_negative_numbers = true)]
    pub tolerance: f64,

    /// Side of the square block around the crease (units of H, at least 4).
    #[arg(long, default_value_t = defaults().size, allow_negative_numbers = true)]
    pub size: f64,

    /// Elements along X in the base mesh (refined --ratio times near the crease).
    #[arg(long, default_value_t = defaults().nx)]
    pub nx: usize,

    /// Elements through the layer in the base mesh.
    #[arg(long, default_value_t = defaults().layer_elements)]
    pub layer_elements: usize,

    /// Graded elements through the substrate in the base mesh.
    #[arg(long, default_value_t = defaults().substrate_elements)]
    pub substrate_elements: usize,

    /// Refinement near the crease: elements there this many times smaller.
    #[arg(long, default_value_t = defaults().ratio, allow_negative_numbers = true)]
    pub ratio: f64,

    /// Ratio of consecutive layer elements from the surface down (1: uniform; up to 4): the
    /// elements are smallest at the crease tip.
    #[arg(long, default_value_t = defaults().layer_grading, allow_negative_numbers = true)]
    pub layer_grading: f64,

    /// Finite element (mixed, the default: the more accurate, and the only one for
    /// incompressible = true; displacement locks above K/mu ~ 100).
    #[arg(long, value_enum, default_value_t = defaults().element)]
    pub element: ElementKind,

    /// The creased state compared with the flat state.
    #[arg(long, value_enum, default_value_t = defaults().criterion)]
    pub criterion: Criterion,

    /// Converge each threshold in the mesh: the base mesh (--nx, --layer-elements,
    /// --substrate-elements) with its element counts times 1, 2, 3, ... until the threshold
    /// changes by less than this (in d), then extrapolated with the observed order.
    #[arg(long, default_value_t = defaults().mesh_tolerance, allow_negative_numbers = true)]
    pub mesh_tolerance: f64,

    /// Meshes of the sequence at most (3 to 6).
    #[arg(long, default_value_t = defaults().max_meshes)]
    pub max_meshes: usize,

    /// The base mesh alone: no refinement, no uncertainty.
    #[arg(id = "no_convergence", long = "no-convergence", action = clap::ArgAction::SetFalse)]
    pub convergence: bool,

    /// Locate and converge every fold's threshold. By default each fold is scanned only up to
    /// the lowest threshold found before it and only the lowest is refined: the onset is the
    /// same, the other folds' thresholds are not located.
    #[arg(long)]
    pub every_fold: bool,

    /// Scan on to --d-to. By default the scan ends 0.01 past the wrinkling onset of the linear
    /// theory, where the wrinkle comes first whatever the crease does.
    #[arg(long)]
    pub beyond_wrinkle: bool,
}

/// The default folds as `--fold` takes them ([`CreaseStudy::default`]'s; a test holds them equal).
const DEFAULT_FOLDS: &str = "0.5,1,2";

/// The defaults the flags show.
fn defaults() -> CreaseOptions {
    CreaseOptions::default()
}

impl Default for CreaseOptions {
    fn default() -> Self {
        let study = CreaseStudy::default();
        let refinement = study.refinement.unwrap_or_default();
        CreaseOptions {
            folds: study.fold_lengths,
            d_from: study.scan.from,
            d_to: study.scan.to,
            d_step: study.scan.step,
            tolerance: study.scan.tolerance,
            size: study.mesh.size,
            nx: study.mesh.nx,
            layer_elements: study.mesh.layer,
            substrate_elements: study.mesh.substrate,
            ratio: study.mesh.ratio,
            layer_grading: study.mesh.layer_grading,
            element: study.mesh.element,
            criterion: study.criterion,
            convergence: study.refinement.is_some(),
            mesh_tolerance: refinement.tolerance,
            max_meshes: refinement.max_meshes,
            every_fold: !study.lowest_only,
            beyond_wrinkle: !study.stop_past_wrinkle,
        }
    }
}

impl CreaseOptions {
    /// The options named in `keywords` (a JSON object), the others at their defaults; an
    /// unknown name or a value of the wrong type is an error naming it.
    pub fn from_keywords(keywords: &str) -> Result<Self> {
        from_keywords("crease", keywords)
    }

    /// The defaults as keywords (a JSON object).
    pub fn default_keywords() -> String {
        default_keywords::<Self>()
    }

    /// The validated study.
    pub fn study(&self) -> Result<CreaseStudy> {
        let study = CreaseStudy {
            mesh: CreaseMesh {
                size: self.size,
                nx: self.nx,
                layer: self.layer_elements,
                substrate: self.substrate_elements,
                ratio: self.ratio,
                layer_grading: self.layer_grading,
                element: self.element,
            },
            fold_lengths: self.folds.clone(),
            scan: Scan {
                from: self.d_from,
                to: self.d_to,
                // A step longer than the range scans its two ends.
                step: match self.d_to > self.d_from {
                    true => self.d_step.min(self.d_to - self.d_from),
                    false => self.d_step,
                },
                tolerance: self.tolerance,
            },
            criterion: self.criterion,
            refinement: self.convergence.then_some(Refinement {
                tolerance: self.mesh_tolerance,
                max_meshes: self.max_meshes,
            }),
            lowest_only: !self.every_fold,
            stop_past_wrinkle: !self.beyond_wrinkle,
        };
        study.validate()?;
        Ok(study)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_options_are_the_default_study() {
        assert_eq!(CreaseOptions::default().study().unwrap(), CreaseStudy::default());
        assert_eq!(CreaseOptions::from_keywords("{}").unwrap(), CreaseOptions::default());
        let chosen = CreaseOptions::from_keywords(r#"{"folds": [1.5], "nx": 48, "convergence": false}"#).unwrap();
        let study = chosen.study().unwrap();
        assert_eq!(
            (study.fold_lengths, study.mesh.nx, study.refinement),
            (vec![1.5], 48, None)
        );
        let message = |text: &str| CreaseOptions::from_keywords(text).unwrap_err().to_string();
        assert!(message(r#"{"fold": [1]}"#).contains("a keyword of crease"));
        assert!(message(r#"{"folds": 1}"#).contains("`folds` takes a list of numbers"));
        assert!(message(r#"{"element": "p1"}"#).contains("`displacement`"));
        assert!(message(r#"{"criterion": "open"}"#).contains("`released`"));
        let released = CreaseOptions::from_keywords(r#"{"criterion": "released"}"#).unwrap();
        assert_eq!(released.study().unwrap().criterion, Criterion::Released);
    }

    #[test]
    fn the_flags_read_into_the_options_at_the_same_defaults() {
        use clap::Parser;
        #[derive(Parser)]
        struct Flags {
            #[command(flatten)]
            options: CreaseOptions,
        }
        let parse = |flags: &[&str]| Flags::try_parse_from(["crease"].iter().chain(flags)).map(|f| f.options);
        assert_eq!(parse(&[]).unwrap(), CreaseOptions::default());
        let chosen = parse(&["--fold", "0.5,2", "--no-convergence", "--criterion", "released"]).unwrap();
        assert_eq!(
            (chosen.folds, chosen.convergence, chosen.criterion),
            (vec![0.5, 2.0], false, Criterion::Released)
        );
    }

    #[test]
    fn a_range_shorter_than_the_default_step_is_scanned_at_its_ends() {
        let short = CreaseOptions {
            d_from: 0.3,
            d_to: 0.31,
            ..CreaseOptions::default()
        };
        assert!(CreaseOptions::default().d_step > 0.01);
        let scan = short.study().unwrap().scan;
        assert!((scan.step - 0.01).abs() < 1e-15, "{scan:?}");
    }
}
