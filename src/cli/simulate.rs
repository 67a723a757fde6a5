//! `fiberfold simulate`: the paper's finite-element protocol, A(d), onset estimates, VTU, Fig. 3.

use super::common::{report_files, ParamArgs};
use clap::Args;
use fiberfold::fem::memory::{available_bytes, MemoryEstimate};
use fiberfold::protocol::mode_number;
use fiberfold::protocol::secondary::BranchKind;
use fiberfold::studies::simulate::{self, Progress, SimulateOptions};
use fiberfold::Result;
use indicatif::{ProgressBar, ProgressStyle};
use std::path::PathBuf;

/// The flags of `simulate` are the library's options, read in place.
#[derive(Args)]
pub struct SimulateArgs {
    #[command(flatten)]
    pub params: ParamArgs,

    #[command(flatten)]
    pub options: SimulateOptions,

    /// Output folder.
    #[arg(long, value_name = "DIR", default_value = "results/simulate")]
    pub out: PathBuf,
}

pub fn run(args: &SimulateArgs) -> Result<()> {
    let params = args.params.resolve()?;
    let study = args.options.study()?;
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
