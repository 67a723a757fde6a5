//! `fiberfold simulate`: the paper's finite-element protocol, A(d), onset estimates, VTU, Fig. 3.

use super::common::{report_files, ParamArgs};
use clap::Args;
use fiberfold::fem::memory::{available_bytes, MemoryEstimate};
use fiberfold::fem::ElementKind;
use fiberfold::mesh::{MeshPreset, MeshSpec};
use fiberfold::protocol::mode_number;
use fiberfold::protocol::secondary::BranchKind;
use fiberfold::studies::simulate::{self, Crossing, MeshChoice, Progress, SimulateOptions, SimulateStudy};
use fiberfold::Result;
use indicatif::{ProgressBar, ProgressStyle};
use std::path::PathBuf;

/// The library's defaults, which every flag below shows.
fn defaults() -> SimulateOptions {
    SimulateOptions::default()
}

/// Mesh of the half domain 0 <= X <= 50, -50 <= Y <= 1: a preset, optionally modified.
#[derive(Args, Clone, Debug)]
pub struct MeshArgs {
    /// Mesh preset.
    #[arg(long, value_enum, default_value_t = defaults().mesh.preset)]
    pub mesh: MeshPreset,
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
    #[arg(long, value_enum, default_value_t = defaults().mesh.element)]
    pub element: ElementKind,
}

impl MeshArgs {
    /// The mesh as chosen, for the library to resolve.
    pub fn choice(&self) -> MeshChoice {
        MeshChoice {
            preset: self.mesh,
            nx: self.nx,
            layer_elements: self.layer_elements,
            substrate_elements: self.substrate_elements,
            h0: self.h0,
            grading: self.grading,
            element: self.element,
            ..MeshChoice::default()
        }
    }

    /// The validated mesh specification.
    pub fn resolve(&self) -> Result<MeshSpec> {
        self.choice().resolve()
    }
}

#[derive(Args)]
#[command(group(clap::ArgGroup::new("seed").required(true).args(["waves", "k"])))]
pub struct SimulateArgs {
    #[command(flatten)]
    pub params: ParamArgs,

    #[command(flatten)]
    pub mesh: MeshArgs,

    /// Waves N of the seeded mode across the half domain, 2N a positive integer: k = 2 pi N / 50.
    #[arg(long, allow_negative_numbers = true)]
    pub waves: Option<f64>,

    /// Referential wavenumber of the seeded mode, k = m pi / 50 with m a positive integer.
    #[arg(long, allow_negative_numbers = true)]
    pub k: Option<f64>,

    /// Final end-shortening d, in (0.005, 1); under --load growth the strain d = 1 - 1/g of the
    /// final growth g (0.2: g = 1.25).
    #[arg(long, default_value_t = defaults().d_max, allow_negative_numbers = true)]
    pub d_max: f64,

    /// Amplitude A_init of the seeded imperfection, in [0, 1) (0: the perfect system). The
    /// reference geometry is perturbed by Delta Y = A_init cos(k X) s(Y), s = 1 in the layer and
    /// sinh(k (Y + 50)) / sinh(50 k) in the substrate, after stage 1 (homogeneous to d = 0.005).
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

    /// Amplitude A2 of the long-wave imperfection -A2 cos(2 pi N2 X / 50) of the reference
    /// geometry, in [0, 1): it lets the pattern leave an unstable periodic branch (use the
    /// shape of the first secondary mode: its N2 is printed at the end of a periodic run).
    #[arg(long, default_value_t = defaults().imperfection2, allow_negative_numbers = true)]
    pub imperfection2: f64,

    /// Waves N2 of the long-wave imperfection across the domain, 2 N2 a positive integer
    /// (0.5: one half wave, deepest at X = 0; N/2: a period doubling).
    #[arg(long, value_name = "N2", default_value_t = defaults().imperfection2_waves, allow_negative_numbers = true)]
    pub imperfection2_waves: f64,

    /// Turn off contact of the top surface with the symmetry planes and with itself.
    #[arg(long)]
    pub no_contact: bool,

    /// How to cross a snap (a limit point in d, a closing trough), where Newton's method cannot
    /// follow the branch: `viscous` damps the steps the step control has cut below 1e-3
    /// (ABAQUS's *STATIC, STABILIZE: those recorded states carry damping forces); `snap`
    /// minimises the energy where a step of 1e-6 fails and records the stable equilibrium
    /// reached (snaps.json: every recorded state an exact equilibrium; in contact a failed step
    /// from a stable state is corrected by minimisation too, `minimised` in amplitude.csv;
    /// slower than `viscous` through contact); `none` stops where Newton's method fails.
    #[arg(long, value_enum, default_value_t = defaults().crossing)]
    pub stabilisation: Crossing,

    /// Viscous stabilisation's damping eta / h relative to the reference stiffness on a step h
    /// in d, in (0, inf) (with --stabilisation viscous).
    #[arg(long, default_value_t = defaults().eta, allow_negative_numbers = true)]
    pub eta: f64,

    /// Do not track the number of negative eigenvalues of the tangent at every converged state
    /// (saves the extra factorisation of damped and contact states; secondary.json then has no
    /// bifurcations). Ignored with --stabilisation snap, which needs the inertia to tell a
    /// stable state.
    #[arg(long)]
    pub no_inertia: bool,

    /// Spacing in d of the VTU snapshots.
    #[arg(long, default_value_t = defaults().vtu_every, allow_negative_numbers = true)]
    pub vtu_every: f64,

    /// Run even when the memory estimate (printed in the header) exceeds the memory available.
    #[arg(long)]
    pub force: bool,

    /// Output folder.
    #[arg(long, value_name = "DIR", default_value = "results/simulate")]
    pub out: PathBuf,
}

impl SimulateArgs {
    /// The validated study, built by the library from the flags.
    fn study(&self) -> Result<SimulateStudy> {
        SimulateOptions {
            mesh: self.mesh.choice(),
            waves: self.waves,
            k: self.k,
            d_max: self.d_max,
            imperfection: self.imperfection,
            max_step: self.max_step,
            min_step: self.min_step,
            max_newton_iterations: self.max_newton_iterations,
            refine_troughs: self.refine_troughs,
            refine_width: self.refine_width,
            imperfection2: self.imperfection2,
            imperfection2_waves: self.imperfection2_waves,
            contact: !self.no_contact,
            crossing: self.stabilisation,
            eta: self.eta,
            inertia: !self.no_inertia,
            vtu_every: self.vtu_every,
            force: self.force,
        }
        .study()
    }
}

pub fn run(args: &SimulateArgs) -> Result<()> {
    let params = args.params.resolve()?;
    let study = args.study()?;
    let p = &study.protocol;
    println!(
        "simulate: k = {:.6} ({} waves), A_init = {}, d to {}, {} unknowns",
        p.k,
        mode_number(p.k, study.mesh.length)? as f64 / 2.0,
        p.imperfection,
        p.d_max,
        study.mesh.num_dofs()
    );
    let memory = MemoryEstimate::of(&study.mesh);
    println!(
        "memory estimate: {:.0} MB ({:.2e} stored tangent entries, {:.2e} factor entries){}",
        memory.bytes / 1e6,
        memory.tangent_entries,
        memory.factor_entries,
        available_bytes().map_or(String::new(), |a| format!("; {:.0} MB available", a / 1e6))
    );
    if let Some(note) = study
        .mesh
        .element
        .locking_note(params.bulk_to_shear_ratio(), params.incompressible)
    {
        println!("{note}");
    }
    let bar = ProgressBar::new(1000);
    bar.set_style(
        ProgressStyle::with_template("{msg} [{bar:40}] ({elapsed})")
            .expect("static template")
            .progress_chars("=> "),
    );
    let monitor = |progress: Progress<'_>| {
        match progress {
            Progress::Stage(text) => bar.suspend(|| println!("{text}")),
            Progress::Step(r) => {
                let residuals: Vec<String> = r.residual_history.iter().map(|x| format!("{x:.1e}")).collect();
                let minimised = if r.minimised { "  (minimised)" } else { "" };
                let inertia = r.negative_pivots.map_or(String::new(), |n| format!("  {n} negative"));
                let augmented = r.augmented.as_ref().map_or(String::new(), |a| {
                    let contact = if a.in_contact {
                        format!("  contact {:.3} pen {:.1e}", a.contact_length, a.penetration)
                    } else {
                        String::new()
                    };
                    // Only a damped path dissipates (its eta is set).
                    match a.eta > 0.0 {
                        true => format!("{contact}  dissipated {:.1e}", a.stabilisation_energy_fraction),
                        false => contact,
                    }
                });
                if let Some(snap) = &r.snap {
                    bar.suspend(|| {
                        println!(
                            "snap at d = {:.6}: A {:.4} -> {:.4}, energy {:.6e} -> {:.6e} (released {:.3e}) by {} minimisation steps",
                            snap.d,
                            snap.amplitude_before,
                            snap.amplitude_after,
                            snap.energy_start,
                            snap.energy_after,
                            snap.energy_released,
                            snap.steps
                        )
                    });
                }
                let growth = if params.load.is_growth() {
                    format!("g = {:.6}  ", r.growth_layer)
                } else {
                    String::new()
                };
                bar.suspend(|| {
                    println!(
                        "{growth}d = {:.6}  step {:.1e}  A = {:.6}  {} it{minimised}  |r| {}  min J {:.4}{inertia}{augmented}  {:.2} s",
                        r.d,
                        r.step,
                        r.amplitude,
                        r.iterations,
                        residuals.join(" "),
                        r.min_jacobian,
                        r.seconds
                    )
                });
                bar.set_position((1000.0 * r.d / p.d_max) as u64);
                bar.set_message(format!("d = {:.4} of {}", r.d, p.d_max));
            }
            Progress::Cut(c) => {
                bar.suspend(|| println!("  cut: d = {:.6} (step {:.1e}) failed: {}", c.d, c.step, c.reason))
            }
        }
        Ok(())
    };
    let result = simulate::run(&params, &study, &args.out, &monitor);
    bar.finish_and_clear();
    let summary = result?;
    let o = &summary.onset;
    let show = |x: Option<f64>| x.map_or("n/a".to_string(), |v| format!("{v:.5}"));
    println!(
        "reached d = {} in {:.1} s ({} steps, {} Newton iterations, {} cuts)",
        summary.d_reached, summary.wall_seconds, summary.accepted_steps, summary.totals.newton_iterations, summary.cuts
    );
    let t = &summary.totals;
    let phases = t.assembly_seconds + t.analysis_seconds + t.factorisation_seconds + t.solve_seconds;
    println!(
        "time: steps {:.1} s = accepted Newton iterations {:.1} s (assembly {:.1}, symbolic {:.1}, factorisation {:.1}, \
         solves {:.1}) + inertia {:.1} s + discarded attempts {:.1} s + contact search, updates, predictor {:.1} s; \
         stages 1-2, output and modes {:.1} s",
        t.step_seconds,
        phases,
        t.assembly_seconds,
        t.analysis_seconds,
        t.factorisation_seconds,
        t.solve_seconds,
        t.inertia_seconds,
        t.failed_attempt_seconds,
        t.step_seconds - phases - t.inertia_seconds - t.failed_attempt_seconds,
        summary.wall_seconds - t.step_seconds
    );
    println!(
        "onset: max curvature {}, steepest {}, A^2 fit {}; linear theory d_c(k) = {:.5}",
        show(o.estimates.d_max_curvature),
        show(o.estimates.d_steepest),
        show(o.estimates.d_a2_fit),
        o.d_linear_theory
    );
    if let Some(d) = o.d_ellipticity_loss.filter(|&d| d < summary.d_reached) {
        println!(
            "note: the homogeneous state loses strong ellipticity at d = {d:.4}; beyond it the continuum admits \
             shear bands, so steps shrink and results there depend on the mesh"
        );
    }
    let c = &summary.contact;
    println!(
        "contact: first at d = {}, final closed length {:.4} in {} zone(s), largest penetration {:.1e}, \
         stabilisation dissipated {:.2e} of the strain energy (largest {:.2e}), min J {:.4}",
        show(c.d_first_contact),
        c.contact_length_final,
        c.contact_zones_final,
        c.penetration_max,
        c.stabilisation_energy_fraction_final,
        c.stabilisation_energy_fraction_max,
        c.min_jacobian
    );
    let e = &summary.ellipticity;
    for (layer, d) in [("layer", e.d_loss_layer), ("substrate", e.d_loss_substrate)] {
        if let Some(d) = d {
            println!(
                "note: the {layer} loses strong ellipticity at a Gauss point first at d = {d:.5} (smallest margin \
                 along the path {:.3e}); beyond it the continuum admits shear bands and the answer depends on the mesh",
                if layer == "layer" {
                    e.smallest_layer
                } else {
                    e.smallest_substrate
                }
            );
        }
    }
    if !summary.snaps.is_empty() {
        let released: f64 = summary.snaps.iter().map(|s| s.energy_released).sum();
        println!(
            "snaps: {} (first at d = {:.6}), energy released {released:.4e} in all; every recorded state is an \
             undamped equilibrium (snaps.json)",
            summary.snaps.len(),
            summary.snaps[0].d
        );
    }
    let s = &summary.secondary;
    println!(
        "secondary bifurcations: first at d = {} ({} changes of the inertia); branch followed: {}",
        show(s.d_secondary),
        s.changes.len(),
        s.branch.kind.name()
    );
    let first_mode_waves = s
        .changes
        .first()
        .and_then(|c| c.mode_half_waves)
        .map(|m| m as f64 / 2.0);
    if let (Some(n2), BranchKind::Periodic) = (first_mode_waves, s.branch.kind) {
        if p.imperfection2 == 0.0 {
            println!(
                "  the first secondary mode has {n2} waves across the domain: to leave the periodic branch, seed it \
                 with e.g. --imperfection2 0.01 --imperfection2-waves {n2}"
            );
        }
    }
    report_files(&summary.files.iter().map(PathBuf::from).collect::<Vec<_>>());
    Ok(())
}
