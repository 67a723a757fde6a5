//! `fiberfold crease`: the crease onset of the bilayer (energy criterion), converged in the mesh.

use super::common::{report_files, ParamArgs};
use clap::Args;
use fiberfold::fem::ElementKind;
use fiberfold::studies::crease::{self, CreaseOptions, CreaseReport, CreaseStudy, Criterion, FoldThreshold};
use fiberfold::Result;
use indicatif::{ProgressBar, ProgressStyle};
use std::path::PathBuf;

#[derive(Args)]
pub struct CreaseArgs {
    #[command(flatten)]
    pub params: ParamArgs,

    /// Reference fold lengths a (units of H), comma separated: the onset is the smallest
    /// threshold over them, reported with its a.
    #[arg(long, value_delimiter = ',', default_value = DEFAULT_FOLDS, allow_negative_numbers = true)]
    pub fold: Vec<f64>,

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
    #[arg(long)]
    pub no_convergence: bool,

    /// Output folder.
    #[arg(long, value_name = "DIR", default_value = "results/crease")]
    pub out: PathBuf,
}

pub fn run(args: &CreaseArgs) -> Result<()> {
    let params = args.params.resolve()?;
    let study = CreaseOptions {
        folds: args.fold.clone(),
        d_from: args.d_from,
        d_to: args.d_to,
        d_step: args.d_step,
        tolerance: args.tolerance,
        size: args.size,
        nx: args.nx,
        layer_elements: args.layer_elements,
        substrate_elements: args.substrate_elements,
        ratio: args.ratio,
        layer_grading: args.layer_grading,
        element: args.element,
        criterion: args.criterion,
        convergence: !args.no_convergence,
        mesh_tolerance: args.mesh_tolerance,
        max_meshes: args.max_meshes,
    }
    .study()?;
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

fn defaults() -> CreaseOptions {
    CreaseOptions::default()
}

/// The default folds as `--fold` takes them (the library's, [`CreaseOptions::default`]).
const DEFAULT_FOLDS: &str = "0.5,1,2";

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
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_default_folds_are_the_librarys() {
        let folds: Vec<f64> = super::DEFAULT_FOLDS.split(',').map(|a| a.parse().unwrap()).collect();
        assert_eq!(folds, super::defaults().folds);
    }
}
