//! `fiberfold crease`: the crease onset of the bilayer (energy criterion), converged in the mesh.

use super::common::{report_files, ParamArgs};
use clap::Args;
use fiberfold::studies::crease::{self, CreaseOptions, CreaseReport, CreaseStudy, Criterion, First, FoldThreshold};
use fiberfold::Result;
use indicatif::{ProgressBar, ProgressStyle};
use std::path::PathBuf;

/// The flags of `crease` are the library's options, read in place.
#[derive(Args)]
pub struct CreaseArgs {
    #[command(flatten)]
    pub params: ParamArgs,

    #[command(flatten)]
    pub options: CreaseOptions,

    /// Output folder.
    #[arg(long, value_name = "DIR", default_value = "results/crease")]
    pub out: PathBuf,
}

pub fn run(args: &CreaseArgs) -> Result<()> {
    let params = args.params.resolve()?;
    let study = args.options.study()?;
    println!(
        "crease onset (energy of a seeded crease, {}, against the flat state) for folds a = {:?} H, d in [{}, {}]",
        match study.criterion {
            Criterion::Held => "held on the plane",
            Criterion::Released => "released to contact with the plane",
        },
        study.fold_lengths,
        study.scan.from,
        study.scan.to
    );
    if let Some(note) = study
        .mesh
        .element
        .locking_note(params.bulk_to_shear_ratio(), params.incompressible)
    {
        println!("{note}");
    }
    let bar = ProgressBar::new_spinner();
    bar.set_style(
        ProgressStyle::with_template("{spinner} {pos} crease energies ({elapsed})").expect("static template"),
    );
    let (report, files) = crease::run(&params, &study, &args.out, &|| bar.inc(1))?;
    bar.finish_and_clear();
    print_onset(&report, &study);
    let e = &report.ellipticity;
    for (layer, d, smallest) in [
        ("layer", e.d_loss_layer, e.smallest_layer),
        ("substrate", e.d_loss_substrate, e.smallest_substrate),
    ] {
        if let Some(d) = d {
            println!(
                "note: a creased state's {layer} loses strong ellipticity at a Gauss point from d = {d:.4} \
                 (smallest margin {smallest:.3e}); there the continuum admits shear bands and the energies depend on \
                 the mesh"
            );
        }
    }
    report_files(&files);
    Ok(())
}

/// What the fold at a threshold does when its nodes are let go to contact with the plane.
fn print_release(fold: &FoldThreshold) {
    match (&fold.released, &fold.release_error) {
        (Some(r), _) if r.reopened => {
            println!("    released: it reopens to the flat state (the held fold is no equilibrium crease here)")
        }
        (Some(r), _) => println!(
            "    released: closed over {:.3} H (folded over {} H), the plane pushing at {} nodes ({}); \
             U - U_flat = {:.4e} (held {:.4e})",
            r.closed_length,
            r.fold_length,
            r.pressed_nodes,
            match r.pulling_nodes {
                0 => "none pulls".to_string(),
                n => format!("{n} pull"),
            },
            r.difference,
            r.held_difference
        ),
        (None, Some(why)) => println!("    released: not computed ({why})"),
        (None, None) => {}
    }
}

/// Each fold's threshold on each mesh and extrapolated, then the onset.
fn print_onset(report: &CreaseReport, study: &CreaseStudy) {
    for fold in &report.folds {
        let a = fold.fold_length;
        for (m, on_mesh) in fold.meshes.iter().enumerate() {
            let mesh = format!(
                "mesh x{} ({} unknowns)",
                report.meshes[m].factor, report.meshes[m].unknowns
            );
            match (on_mesh.d_threshold, &on_mesh.stopped) {
                (Some(d), _) => {
                    let which = match (report.criterion, on_mesh.d_held) {
                        (Criterion::Released, Some(held)) => format!(
                            "the released crease pays off from d = {d:.5}{} (the held fold from {held:.5})",
                            if on_mesh.appears_paying {
                                ", appearing there already paying off (below it the fold reopens)"
                            } else {
                                ""
                            }
                        ),
                        _ => format!("the crease pays off from d = {d:.5}"),
                    };
                    println!("  a = {a} H, {mesh}: {which}");
                    print_release(on_mesh);
                }
                (None, Some(why)) => println!("  a = {a} H, {mesh}: no threshold ({why})"),
                (None, None) => println!(
                    "  a = {a} H, {mesh}: no crease pays off up to d = {:.4}",
                    on_mesh.cleared()
                ),
            }
        }
        if let (Some(e), true) = (fold.extrapolated, fold.meshes.len() > 1) {
            let order = e
                .order
                .map_or("no order observed".to_string(), |p| format!("order {p:.2}"));
            let error = e.error.map_or(String::new(), |x| format!(" +- {x:.1e}"));
            let converged = if fold.converged {
                ""
            } else {
                ", NOT converged to --mesh-tolerance"
            };
            println!(
                "  a = {a} H: extrapolated d = {:.5}{error} ({order}{converged})",
                e.value
            );
        }
    }
    match (report.d_crease, report.fold_length) {
        (Some(d), Some(a)) => {
            let error = report
                .d_crease_error
                .map_or(" (one mesh)".to_string(), |x| format!(" +- {x:.1e}"));
            println!(
                "d_crease = {d:.5}{error} at fold length a = {a} H (crease depth {:.3} H)",
                report.depth.unwrap_or(f64::NAN)
            );
            if let Some(g) = report.g_crease {
                println!(
                    "  under {}: the layer's growth at the crease onset g_crease = {g:.5}",
                    report.load.name()
                );
            }
            if study.refinement.is_some() && !report.converged {
                println!(
                    "note: the threshold still changed by more than --mesh-tolerance on the last mesh: raise --max-meshes \
                     or refine the base mesh"
                );
            }
        }
        _ => println!("no crease pays off within the scan"),
    }
    print_first(report, study);
}

/// The wrinkling onset of the linear theory beside the crease's, and which comes first.
fn print_first(report: &CreaseReport, study: &CreaseStudy) {
    let Some(w) = report.d_wrinkle else {
        println!("wrinkling onset (linear theory): none before the loss of ellipticity");
        return;
    };
    let first = match report.first {
        First::Wrinkle => "the wrinkle comes first",
        First::Crease => "the crease comes first",
        First::TooCloseToCall => "too close to call within the crease onset's uncertainty",
        First::Undecided => "undecided: the crease search ended below it (a fold that snapped)",
        First::None => "neither within the scan",
    };
    println!("wrinkling onset (linear theory): d_wrinkle = {w:.5}: {first}");
    if report.scan_ends_past_wrinkle {
        println!(
            "  the scan ended at d = {:.4}, {} past d_wrinkle (--beyond-wrinkle scans on to --d-to = {})",
            report.scan.to,
            fiberfold::studies::crease::BEYOND_WRINKLE,
            study.scan.to
        );
    }
    if study.lowest_only && study.fold_lengths.len() > 1 {
        println!("  only the lowest threshold is located and refined (--every-fold for each fold's)");
    }
}
