//! `bench patch`: where one Newton iteration of the three-dimensional patch spends its time and
//! memory, and how both grow with the box. On periodic boxes of 1 x 1, 2 x 2, ... onset periods
//! (sized by [`size_patch`], `pattern`'s default mesh), at the homogeneous state of `d = 0.05`:
//! the tangent's assembly, the symbolic analysis (AMD ordering and supernodal structure), the
//! `L D L^T`, one solve, the factor's entries and the peak memory; then the exponents of the
//! growth with the unknowns between the last two boxes.

use super::bench_fe::peak_memory_mb;
use super::pattern::{size_patch, PatternStudy};
use crate::error::Result;
use crate::fem::{PatchSystem, SparseLdlt};
use crate::homogeneous::biaxial_state;
use crate::material::Bilayer;
use crate::mesh::Mesh;
use crate::parameters::Parameters;
use crate::protocol::continuation::Followed;
use crate::protocol::patch::{homogeneous_patch_unknowns, BiaxialPatch};
use serde::Serialize;
use std::fmt;
use std::time::Instant;

/// The compression of the state whose tangent is timed (below Table 1's onset).
const D: f64 = 0.05;

/// One box.
#[derive(Clone, Debug, Serialize)]
pub struct PatchBenchRow {
    /// Onset periods along each side.
    pub periods: usize,
    pub unknowns: usize,
    pub assembly_seconds: f64,
    /// Symbolic analysis: the ordering and the supernodal structure.
    pub analysis_seconds: f64,
    pub factorisation_seconds: f64,
    pub solve_seconds: f64,
    /// Stored entries of the factor `L`.
    pub factor_entries: usize,
    /// `VmHWM` after the box (the process's peak so far: boxes run in increasing size).
    pub peak_memory_mb: Option<f64>,
}

/// The boxes, and the growth between the last two.
#[derive(Clone, Debug, Serialize)]
pub struct PatchBench {
    pub biaxial: f64,
    pub elements_per_wavelength: usize,
    pub rows: Vec<PatchBenchRow>,
    /// `(factor entries, factorisation time)` growing as `unknowns^p` between the last two boxes.
    pub growth_exponents: Option<(f64, f64)>,
}

/// Times the boxes of `1..=largest` periods along each side under `d_3 = biaxial d`, with
/// `pattern`'s default mesh.
pub fn run(params: &Parameters, biaxial: f64, largest: usize) -> Result<PatchBench> {
    let materials = Bilayer::new(params);
    let defaults = PatternStudy::default();
    let mut rows = Vec::new();
    for periods in 1..=largest {
        let study = PatternStudy {
            periods,
            biaxial,
            ..defaults
        };
        let (_, spec, _) = size_patch(params, &study)?;
        let mut patch = BiaxialPatch::new(
            PatchSystem::on_patch(Mesh::patch(spec)?, &materials)?,
            biaxial,
            Vec::new(),
        );
        let bc = patch.load_to(D)?;
        let u = homogeneous_patch_unknowns(patch.system(), &materials, &biaxial_state(&materials, D, biaxial * D)?)?;
        let started = Instant::now();
        let assembled = patch.linearised(&u, &bc, true)?;
        let assembly_seconds = started.elapsed().as_secs_f64();
        let tangent = assembled.tangent.as_ref().expect("assembled with the tangent");
        let mut solver = SparseLdlt::new(tangent.symbolic());
        solver.factorize(tangent.as_ref());
        let mut x = assembled.residual.clone();
        solver.solve_in_place(&mut x)?;
        rows.push(PatchBenchRow {
            periods,
            unknowns: tangent.nrows(),
            assembly_seconds,
            analysis_seconds: solver.symbolic_time().as_secs_f64(),
            factorisation_seconds: solver.factorisation_time().as_secs_f64(),
            solve_seconds: solver.solve_time().as_secs_f64(),
            factor_entries: solver.factor_size(),
            peak_memory_mb: peak_memory_mb(),
        });
    }
    let growth_exponents = match rows.as_slice() {
        [.., a, b] => {
            let exponent = |x: f64, y: f64| (y / x).ln() / (b.unknowns as f64 / a.unknowns as f64).ln();
            Some((
                exponent(a.factor_entries as f64, b.factor_entries as f64),
                exponent(a.factorisation_seconds, b.factorisation_seconds),
            ))
        }
        _ => None,
    };
    Ok(PatchBench {
        biaxial,
        elements_per_wavelength: defaults.elements_per_wavelength,
        rows,
        growth_exponents,
    })
}

impl fmt::Display for PatchBench {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "| periods | unknowns | assembly s | analysis s | LDLT s | solve s | factor entries | per unknown | peak MB |"
        )?;
        writeln!(f, "|---|---|---|---|---|---|---|---|---|")?;
        for r in &self.rows {
            writeln!(
                f,
                "| {0} x {0} | {1} | {2:.2} | {3:.2} | {4:.2} | {5:.3} | {6} | {7:.0} | {8} |",
                r.periods,
                r.unknowns,
                r.assembly_seconds,
                r.analysis_seconds,
                r.factorisation_seconds,
                r.solve_seconds,
                r.factor_entries,
                r.factor_entries as f64 / r.unknowns as f64,
                r.peak_memory_mb.map_or("-".to_string(), |m| format!("{m:.0}")),
            )?;
        }
        if let Some((entries, time)) = self.growth_exponents {
            writeln!(
                f,
                "\nBetween the last two boxes the factor's entries grow as unknowns^{entries:.2} and the \
                 LDLT time as unknowns^{time:.2}."
            )?;
        }
        Ok(())
    }
}
