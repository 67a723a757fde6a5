//! The creasing threshold of a homogeneous neo-Hookean half-space (Hong, Zhao & Suo 2009): the
//! special case of [`super::crease`] where layer and substrate are one solid, so that the
//! threshold is the same for every fold length. Writes
//! `crease_threshold.json` and `crease_energy.csv` (every evaluation).

use super::crease::{fold_threshold, Criterion, Scan};
use crate::error::{Error, Result};
use crate::material::Bilayer;
use crate::mesh::{MeshSpec, XRefinement};
use crate::output::{write_json, CsvWriter};
use crate::parameters::Parameters;
use crate::protocol::crease_seed::CreaseEnergy;
use serde::Serialize;
use std::path::Path;

/// One threshold computation: material, mesh, fold and the bracket searched.
#[derive(Clone, Copy, Debug)]
pub struct CreaseThresholdStudy {
    /// Bulk over shear modulus (`K / mu`; the solid is nearly incompressible when large).
    pub bulk_ratio: f64,
    pub mesh: MeshSpec,
    /// Reference length `a` folded onto the symmetry plane.
    pub fold_length: f64,
    /// Compressions bracketing the sign change.
    pub bracket: (f64, f64),
    /// Width in `eps` to which the threshold is located.
    pub tolerance: f64,
}

impl CreaseThresholdStudy {
    /// A square domain of side `size` (`nx` elements in X, refined `ratio` times near the
    /// crease at `X = 0`; `layer` elements through the top unit thickness and `substrate` below,
    /// graded from the layer's size), fold length `size / 12`, bracket `[0.30, 0.38]` (above it the seeded fold snaps to a deeper crease: no quasi-static path).
    pub fn new(bulk_ratio: f64, size: f64, nx: usize, layer: usize, substrate: usize, ratio: f64) -> Self {
        let fold_length = size / 12.0;
        let refinement = XRefinement {
            ratio,
            width: 1.5 * fold_length,
            offset: 0.0,
            period: 4.0 * size,
        };
        CreaseThresholdStudy {
            bulk_ratio,
            mesh: MeshSpec::new(nx, layer, substrate, 1.0 / layer as f64, size, size).refined(refinement),
            fold_length,
            bracket: (0.30, 0.38),
            tolerance: 1e-3,
        }
    }

    /// The homogeneous solid: `mu = 1` in both "layers", `K = bulk_ratio`, no fibres.
    pub fn parameters(&self) -> Parameters {
        Parameters {
            mu_l: 1.0,
            K_l: self.bulk_ratio,
            mu_s: 1.0,
            K_s: self.bulk_ratio,
            phi_m: 1.0,
            phi_f: 0.0,
            mu_f: 0.0,
            ..Parameters::default()
        }
    }
}

/// The threshold and every energy evaluated on the way.
#[derive(Clone, Debug, Serialize)]
pub struct CreaseThreshold {
    /// Compression at which `U_crease - U_flat` changes sign.
    pub strain: f64,
    pub biot_strain: f64,
    pub bulk_ratio: f64,
    pub fold_length: f64,
    pub unknowns: usize,
    pub evaluations: Vec<CreaseEnergy>,
    pub seconds: f64,
}

/// Locates the threshold of `study` (no files): [`super::crease::fold_threshold`] of the
/// homogeneous solid, scanning just the two ends of the bracket.
pub fn crease_threshold(study: &CreaseThresholdStudy) -> Result<CreaseThreshold> {
    let start = std::time::Instant::now();
    let materials = Bilayer::new(&study.parameters());
    let (lo, hi) = study.bracket;
    let scan = Scan {
        from: lo,
        to: hi,
        step: hi - lo,
        tolerance: study.tolerance,
    };
    let fold = fold_threshold(&materials, study.mesh, study.fold_length, scan, Criterion::Held, &|| {})?;
    let strain = fold.d_threshold.ok_or_else(|| Error::NoRoot {
        what: format!(
            "the energy of a seeded crease minus that of the flat state ({})",
            fold.stopped.as_deref().unwrap_or("no sign change")
        ),
        lower: lo,
        upper: hi,
    })?;
    Ok(CreaseThreshold {
        strain,
        biot_strain: crate::stability::biot_compression(),
        bulk_ratio: study.bulk_ratio,
        fold_length: study.fold_length,
        unknowns: study.mesh.num_dofs(),
        evaluations: fold.evaluations,
        seconds: start.elapsed().as_secs_f64(),
    })
}

/// Runs the study and writes `crease_threshold.json` and `crease_energy.csv` into `out`.
pub fn run(study: &CreaseThresholdStudy, out: &Path) -> Result<CreaseThreshold> {
    crate::output::ensure_dir(out)?;
    let threshold = crease_threshold(study)?;
    let mut table = CsvWriter::create(
        &out.join("crease_energy.csv"),
        &["strain", "difference", "scaled_difference", "depth", "tensile_nodes"],
    )?;
    for e in &threshold.evaluations {
        table.append(&[
            e.strain,
            e.difference,
            e.scaled_difference,
            e.depth,
            e.tensile_nodes as f64,
        ])?;
    }
    write_json(&out.join("crease_threshold.json"), &threshold)?;
    Ok(threshold)
}
