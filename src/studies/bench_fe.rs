//! Benchmark of the finite-element solver: the whole `beta = pi/4`, `N = 4.5` curve to
//! `d = 0.25` (the paper's protocol, a state at least every 0.005 in `d`, no files written) on
//! each mesh, with the per-iteration split of assembly / factorisation / solve, Newton
//! iterations per step and the peak resident memory.

use super::simulate::{curve, Monitor, PhaseTotals};
use crate::error::{Error, Result};
use crate::fem::ElementKind;
use crate::mesh::MeshSpec;
use crate::parameters::Parameters;
use crate::protocol::Loading;
use crate::protocol::{wavenumber_of_waves, Protocol, SnapCrossing, SnapSettings};
use serde::Serialize;
use std::f64::consts::FRAC_PI_4;
use std::fmt;

/// The benchmark curve: parameters, seeded waves and final compression.
#[derive(Clone, Debug)]
pub struct FeBenchSetup {
    pub params: Parameters,
    pub waves: f64,
    pub d_max: f64,
}

impl Default for FeBenchSetup {
    /// Table 1 with `beta = pi/4`, `N = 4.5`, `d_max = 0.25`.
    fn default() -> Self {
        FeBenchSetup {
            params: Parameters {
                beta: FRAC_PI_4,
                ..Parameters::default()
            },
            waves: 4.5,
            d_max: 0.25,
        }
    }
}

/// The meshes benchmarked: coarse and fine, and extra when asked for.
pub fn default_meshes(with_extra: bool) -> Vec<(&'static str, MeshSpec)> {
    let mut meshes = vec![("coarse", MeshSpec::coarse()), ("fine", MeshSpec::fine())];
    if with_extra {
        meshes.push(("extra", MeshSpec::extra()));
    }
    meshes
}

/// One mesh's measurements.
#[derive(Clone, Debug, Serialize)]
pub struct FeBenchRow {
    pub mesh: String,
    pub unknowns: usize,
    pub d_reached: f64,
    pub completed: bool,
    pub steps: usize,
    pub cuts: usize,
    pub newton_iterations: usize,
    pub max_iterations_per_step: usize,
    /// Largest gap in `d` between consecutive converged states.
    pub largest_gap: f64,
    /// Wall time per Newton iteration of each phase (ms).
    pub assembly_ms: f64,
    pub factorisation_ms: f64,
    pub solve_ms: f64,
    pub symbolic_analysis_seconds: f64,
    pub curve_seconds: f64,
    /// `VmHWM` after the run: the process's peak so far, so meshes run in increasing size.
    pub peak_memory_mb: Option<f64>,
}

/// The benchmark table.
#[derive(Clone, Debug, Serialize)]
pub struct FeBench {
    pub rows: Vec<FeBenchRow>,
}

/// Runs the benchmark curve on each mesh in turn (smallest first for the memory column).
/// `monitor` sees every step of every run.
pub fn run(setup: &FeBenchSetup, meshes: &[(&str, MeshSpec)], monitor: Monitor) -> Result<FeBench> {
    let mut rows = Vec::new();
    for &(name, spec) in meshes {
        // Incompressible tissue runs on the element that can carry it.
        let spec = match setup.params.incompressible {
            true => spec.with_element(ElementKind::Mixed),
            false => spec,
        };
        let k = wavenumber_of_waves(setup.waves, spec.length)?;
        let protocol = Protocol::new(k, 0.05, setup.d_max);
        let result = curve(&setup.params, spec, &protocol, monitor)?;
        let totals = PhaseTotals::of(&result.records);
        // Per Newton iteration: each phase's total (predictor assemblies and trial points
        // included) divided by the number of iterations.
        let per = |seconds: f64| 1e3 * seconds / totals.newton_iterations.max(1) as f64;
        let d: Vec<f64> = result.records.iter().map(|r| r.d).collect();
        rows.push(FeBenchRow {
            mesh: name.to_string(),
            unknowns: spec.num_dofs(),
            d_reached: d.last().copied().unwrap_or(0.0),
            completed: result.stopped.is_none(),
            steps: result.records.len(),
            cuts: result.cuts.len(),
            newton_iterations: totals.newton_iterations,
            max_iterations_per_step: result.records.iter().map(|r| r.iterations).max().unwrap_or(0),
            largest_gap: d.windows(2).map(|w| w[1] - w[0]).fold(0.0, f64::max),
            assembly_ms: per(totals.assembly_seconds),
            factorisation_ms: per(totals.factorisation_seconds),
            solve_ms: per(totals.solve_seconds),
            symbolic_analysis_seconds: totals.analysis_seconds,
            curve_seconds: result.seconds,
            peak_memory_mb: peak_memory_mb(),
        });
    }
    Ok(FeBench { rows })
}

/// `VmHWM` of `/proc/self/status` in MB (None where unavailable).
pub fn peak_memory_mb() -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb / 1024.0)
}

impl fmt::Display for FeBench {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "{:<8} {:>8} {:>7} {:>6} {:>5} {:>6} {:>7} {:>7} {:>9} {:>9} {:>8} {:>9} {:>8}",
            "mesh",
            "unknowns",
            "d",
            "steps",
            "cuts",
            "iters",
            "it/step",
            "gap",
            "asm ms",
            "ldlt ms",
            "solve ms",
            "curve s",
            "peak MB"
        )?;
        for r in &self.rows {
            writeln!(
                f,
                "{:<8} {:>8} {:>7.4} {:>6} {:>5} {:>6} {:>7.2} {:>7.4} {:>9.1} {:>9.1} {:>8.1} {:>9.2} {:>8}",
                r.mesh,
                r.unknowns,
                r.d_reached,
                r.steps,
                r.cuts,
                r.newton_iterations,
                r.newton_iterations as f64 / r.steps.max(1) as f64,
                r.largest_gap,
                r.assembly_ms,
                r.factorisation_ms,
                r.solve_ms,
                r.curve_seconds,
                r.peak_memory_mb.map_or("n/a".into(), |m| format!("{m:.0}")),
            )?;
        }
        Ok(())
    }
}

impl FeBench {
    /// An error naming the first mesh whose curve stopped before `d_max`.
    pub fn check_completed(&self) -> Result<()> {
        match self.rows.iter().find(|r| !r.completed) {
            Some(r) => Err(Error::Solver(format!(
                "benchmark curve on the {} mesh stopped at d = {}",
                r.mesh, r.d_reached
            ))),
            None => Ok(()),
        }
    }
}

/// The benchmark curve crossed by snaps (contact on, no damping, [`SnapSettings::default`]) on
/// one mesh: how many snaps, what each cost.
#[derive(Clone, Debug, Serialize)]
pub struct SnapBenchRow {
    pub mesh: String,
    pub d_reached: f64,
    pub completed: bool,
    pub snaps: usize,
    /// Steps whose failed Newton correction the minimisation from the predictor replaced.
    pub minimised_steps: usize,
    /// Per snap: wall time (s), minimisation steps and factorisations (shifted and unshifted).
    pub seconds_per_snap: f64,
    pub steps_per_snap: f64,
    pub factorisations_per_snap: f64,
    pub energy_released: f64,
    pub curve_seconds: f64,
}

/// The snap table.
#[derive(Clone, Debug, Serialize)]
pub struct SnapBench {
    pub rows: Vec<SnapBenchRow>,
}

/// Runs the benchmark curve on each mesh with its snaps crossed by energy minimisation.
pub fn snaps(setup: &FeBenchSetup, meshes: &[(&str, MeshSpec)]) -> Result<SnapBench> {
    let mut rows = Vec::new();
    for &(name, spec) in meshes {
        let k = wavenumber_of_waves(setup.waves, spec.length)?;
        let mut protocol = Protocol::new(k, 0.05, setup.d_max).with_crease_path();
        protocol.crossing = SnapCrossing::Minimised(SnapSettings::default());
        let result = curve(&setup.params, spec, &protocol, &|_| Ok(()))?;
        let snaps: Vec<_> = result.records.iter().filter_map(|r| r.snap.as_ref()).collect();
        let per = |total: f64| total / snaps.len().max(1) as f64;
        rows.push(SnapBenchRow {
            mesh: name.to_string(),
            d_reached: result.records.last().map_or(0.0, |r| r.d),
            completed: result.stopped.is_none(),
            snaps: snaps.len(),
            minimised_steps: result.records.iter().filter(|r| r.minimised).count(),
            seconds_per_snap: per(snaps.iter().map(|s| s.seconds).sum()),
            steps_per_snap: per(snaps.iter().map(|s| s.steps as f64).sum()),
            factorisations_per_snap: per(snaps.iter().map(|s| s.factorisations as f64).sum()),
            energy_released: snaps.iter().map(|s| s.energy_released).sum(),
            curve_seconds: result.seconds,
        });
    }
    Ok(SnapBench { rows })
}

impl fmt::Display for SnapBench {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "| mesh | d reached | snaps | minimised steps | s / snap | steps / snap | factorisations / snap | released | curve s |"
        )?;
        writeln!(f, "|---|---|---|---|---|---|---|---|---|")?;
        for r in &self.rows {
            writeln!(
                f,
                "| {} | {:.6} | {} | {} | {:.2} | {:.1} | {:.1} | {:.4} | {:.2} |",
                r.mesh,
                r.d_reached,
                r.snaps,
                r.minimised_steps,
                r.seconds_per_snap,
                r.steps_per_snap,
                r.factorisations_per_snap,
                r.energy_released,
                r.curve_seconds
            )?;
        }
        Ok(())
    }
}

/// Per-call cost of the solver's kernels on one mesh with one element, at the homogeneous state
/// of `d = 0.1` (medians of 5 calls).
#[derive(Clone, Debug, Serialize)]
pub struct KernelRow {
    pub mesh: String,
    pub element: ElementKind,
    pub free_unknowns: usize,
    /// Stored entries of the lower triangle of `K_ff` and of the factor.
    pub tangent_entries: usize,
    pub factor_entries: usize,
    pub tangent_assembly_ms: f64,
    pub residual_assembly_ms: f64,
    pub factorisation_ms: f64,
    pub solve_ms: f64,
    /// The solve with the factor rounded to single precision (modified Newton's).
    pub single_solve_ms: f64,
}

/// The kernel table.
#[derive(Clone, Debug, Serialize)]
pub struct Kernels {
    pub rows: Vec<KernelRow>,
}

/// Times the kernels on each mesh, with the displacement and the mixed element.
pub fn kernels(params: &Parameters, meshes: &[(&str, MeshSpec)]) -> Result<Kernels> {
    use crate::fem::{SparseLdlt, System};
    use crate::homogeneous::homogeneous_state;
    use crate::material::Bilayer;
    use crate::protocol::basic_state::homogeneous_unknowns;
    let materials = Bilayer::new(params);
    let mut rows = Vec::new();
    let elements: &[ElementKind] = match params.incompressible {
        true => &[ElementKind::Mixed],
        false => &[ElementKind::Displacement, ElementKind::Mixed],
    };
    for (&(name, spec), &element) in meshes.iter().flat_map(|m| elements.iter().map(move |e| (m, e))) {
        let mut system = System::new(crate::mesh::Mesh::new(spec.with_element(element))?, &materials)?;
        let d = 0.1;
        let bc = system.load_to(d)?;
        let u = homogeneous_unknowns(&system, &materials, &homogeneous_state(&materials, d)?)?;
        let assembled = system.assemble(&u, &bc, None, true)?;
        let k = assembled.tangent.expect("assembled with the tangent");
        let tangent_assembly_ms = median_ms(|| system.assemble(&u, &bc, None, true).map(|_| ()))?;
        let residual_assembly_ms = median_ms(|| system.assemble(&u, &bc, None, false).map(|_| ()))?;
        let mut solver = SparseLdlt::new(k.symbolic());
        let factorisation_ms = median_ms(|| {
            solver.factorize(k.as_ref());
            Ok(())
        })?;
        let mut x = assembled.residual.clone();
        let solve_ms = median_ms(|| {
            x.copy_from_slice(&assembled.residual);
            solver.solve_in_place(&mut x)
        })?;
        let single_solve_ms = median_ms(|| {
            x.copy_from_slice(&assembled.residual);
            solver.solve_in_place_single(&mut x)
        })?;
        rows.push(KernelRow {
            mesh: name.to_string(),
            element,
            free_unknowns: k.nrows(),
            tangent_entries: k.compute_nnz(),
            factor_entries: solver.factor_size(),
            tangent_assembly_ms,
            residual_assembly_ms,
            factorisation_ms,
            solve_ms,
            single_solve_ms,
        });
    }
    Ok(Kernels { rows })
}

/// Median wall time of 5 calls of `f`, in ms.
fn median_ms(mut f: impl FnMut() -> Result<()>) -> Result<f64> {
    let mut times = Vec::new();
    for _ in 0..5 {
        let start = std::time::Instant::now();
        f()?;
        times.push(1e3 * start.elapsed().as_secs_f64());
    }
    times.sort_by(f64::total_cmp);
    Ok(times[2])
}

impl fmt::Display for Kernels {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "| mesh | element | free unknowns | nnz(K) lower | factor entries | tangent + residual assembly ms | residual only ms | LDLT ms | solve ms | single-precision solve ms | assembly / LDLT |")?;
        writeln!(f, "|---|---|---|---|---|---|---|---|---|---|---|")?;
        for r in &self.rows {
            writeln!(
                f,
                "| {} | {} | {} | {} | {} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} | {:.0} % |",
                r.mesh,
                r.element.name(),
                r.free_unknowns,
                r.tangent_entries,
                r.factor_entries,
                r.tangent_assembly_ms,
                r.residual_assembly_ms,
                r.factorisation_ms,
                r.solve_ms,
                r.single_solve_ms,
                100.0 * r.tangent_assembly_ms / r.factorisation_ms
            )?;
        }
        Ok(())
    }
}

/// The cost of one Newton iteration (tangent assembly, factorisation, solve) with each tissue
/// law, at the homogeneous state of `d = 0.1` with the displacement element: the laws side by
/// side, each against neo-Hookean.
#[derive(Clone, Debug, Serialize)]
pub struct LawRow {
    pub law: String,
    pub mesh: String,
    pub tangent_assembly_ms: f64,
    pub newton_iteration_ms: f64,
    pub relative_to_neo_hookean: f64,
}

#[derive(Clone, Debug, Serialize)]
pub struct LawKernels {
    pub rows: Vec<LawRow>,
}

/// The laws timed: Table 1, then each other law given to both layers (or to the fibres), then
/// Table 1 under growth: the growth load (`g = 1/0.9` at the strain 0.1) and a layer grown by
/// 1.1 before the compression. A grown energy costs no more per state than an ungrown one.
pub const BENCH_LAWS: [(&str, &[&str]); 7] = [
    ("neo-Hookean (Table 1)", &[]),
    (
        "Mooney-Rivlin",
        &[
            "layer.law=mooney_rivlin",
            "layer.c1=3",
            "layer.c2=2",
            "substrate.law=mooney_rivlin",
            "substrate.c1=0.3",
            "substrate.c2=0.2",
        ],
    ),
    (
        "Ogden alpha = -25",
        &[
            "layer.law=ogden",
            "layer.alpha=-25",
            "substrate.law=ogden",
            "substrate.alpha=-25",
        ],
    ),
    (
        "Gent Jm = 5",
        &["layer.law=gent", "layer.jm=5", "substrate.law=gent", "substrate.jm=5"],
    ),
    (
        "HGO fibres",
        &["fibres.law=hgo", "fibres.k1=5", "fibres.k2=1", "fibres.kappa=0.1"],
    ),
    ("Table 1, load = growth", &["load=growth"]),
    ("Table 1, growth_layer = 1.1", &["growth_layer=1.1"]),
];

/// Times one Newton iteration with each of [`BENCH_LAWS`] on the meshes given.
pub fn laws(base: &Parameters, meshes: &[(&str, MeshSpec)]) -> Result<LawKernels> {
    let mut rows: Vec<LawRow> = Vec::new();
    for (law, settings) in BENCH_LAWS {
        let mut params = base.clone();
        for s in settings {
            params.set(s)?;
        }
        params.validate()?;
        let kernels = kernels(
            &Parameters {
                incompressible: false,
                ..params
            },
            meshes,
        )?;
        for row in kernels.rows.iter().filter(|r| r.element == ElementKind::Displacement) {
            let newton_iteration_ms = row.tangent_assembly_ms + row.factorisation_ms + row.solve_ms;
            let reference = rows
                .iter()
                .find(|r| r.mesh == row.mesh)
                .map_or(newton_iteration_ms, |r| r.newton_iteration_ms);
            rows.push(LawRow {
                law: law.to_string(),
                mesh: row.mesh.clone(),
                tangent_assembly_ms: row.tangent_assembly_ms,
                newton_iteration_ms,
                relative_to_neo_hookean: newton_iteration_ms / reference,
            });
        }
    }
    Ok(LawKernels { rows })
}

impl fmt::Display for LawKernels {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "| law or load | mesh | tangent assembly ms | Newton iteration ms | vs neo-Hookean |"
        )?;
        writeln!(f, "|---|---|---|---|---|")?;
        for r in &self.rows {
            writeln!(
                f,
                "| {} | {} | {:.1} | {:.1} | {:.2}x |",
                r.law, r.mesh, r.tangent_assembly_ms, r.newton_iteration_ms, r.relative_to_neo_hookean
            )?;
        }
        Ok(())
    }
}
