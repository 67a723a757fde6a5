//! `crease`'s options by the names of its flags (`--fold` is `folds`, `--no-convergence` is
//! `convergence = false`), with the defaults of [`CreaseStudy::default`]: what the command line
//! fills in, and what the Python package reads from its keywords ([`CreaseOptions::from_keywords`]).

use super::{CreaseMesh, CreaseStudy, Criterion, Refinement, Scan};
use crate::error::Result;
use crate::fem::ElementKind;
use crate::studies::keywords::{default_keywords, from_keywords};
use serde::{Deserialize, Serialize};

/// One `crease` computation as a user chooses it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct CreaseOptions {
    /// Reference fold lengths `a` (units of `H`).
    pub folds: Vec<f64>,
    /// The scan of `d`: from, to, by; then the sign change located to `tolerance`.
    pub d_from: f64,
    pub d_to: f64,
    pub d_step: f64,
    pub tolerance: f64,
    /// The block's width and depth (units of `H`).
    pub size: f64,
    pub nx: usize,
    pub layer_elements: usize,
    pub substrate_elements: usize,
    /// How much finer the elements are at the crease than far from it, along X.
    pub ratio: f64,
    /// Ratio of the layer's thickest to its thinnest element.
    pub layer_grading: f64,
    pub element: ElementKind,
    /// Which creased state is compared with the flat one: `held` or `released`.
    pub criterion: Criterion,
    /// Converge each threshold in the mesh (false: the base mesh alone).
    pub convergence: bool,
    pub mesh_tolerance: f64,
    pub max_meshes: usize,
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
            lowest_only: false,
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
