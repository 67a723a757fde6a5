//! `fiberfold crease`: the crease onset of the bilayer (energy criterion), with a mesh check.

use super::common::{report_files, ParamArgs};
use super::simulate::ElementChoice;
use clap::Args;
use fiberfold::studies::crease::{self, CreaseMesh, CreaseStudy, Scan};
use fiberfold::Result;
use indicatif::{ProgressBar, ProgressStyle};
use std::path::PathBuf;

#[derive(Args)]
pub struct CreaseArgs {
    #[command(flatten)]
    pub params: ParamArgs,

    /// Reference fold lengths a (units of H), comma separated: the onset is the smallest
    /// threshold over them, reported with its a.
    #[arg(long, value_delimiter = ',', default_values_t = vec![0.5, 1.0, 2.0], allow_negative_numbers = true)]
    pub fold: Vec<f64>,

    /// First compression d scanned.
    #[arg(long, default_value_t = 0.05, allow_negative_numbers = true)]
    pub d_from: f64,

    /// Last compression d scanned (below 1).
    #[arg(long, default_value_t = 0.7, allow_negative_numbers = true)]
    pub d_to: f64,

    /// Step of the scan in d.
    #[arg(long, default_value_t = 0.05, allow_negative_numbers = true)]
    pub d_step: f64,

    /// Width in d to which each threshold is located.
    #[arg(long, default_value_t = 1e-3, allow_negative_numbers = true)]
    pub tolerance: f64,

    /// Side of the square block around the crease (units of H, at least 4).
    #[arg(long, default_value_t = 12.0, allow_negative_numbers = true)]
    pub size: f64,

    /// Elements along X (refined --ratio times near the crease).
    #[arg(long, default_value_t = 48)]
    pub nx: usize,

    /// Elements through the layer.
    #[arg(long, default_value_t = 4)]
    pub layer_elements: usize,

    /// Graded elements through the substrate.
    #[arg(long, default_value_t = 20)]
    pub substrate_elements: usize,

    /// Refinement near the crease: elements there this many times smaller.
    #[arg(long, default_value_t = 8.0, allow_negative_numbers = true)]
    pub ratio: f64,

    /// Finite element (mixed: the more accurate, and the only one for incompressible = true;
    /// displacement, the default, locks above K/mu ~ 100).
    #[arg(long, value_enum, default_value_t = ElementChoice::Displacement)]
    pub element: ElementChoice,

    /// Skip the recomputation of the onset on a mesh refined twice in every direction.
    #[arg(long)]
    pub no_convergence: bool,

    /// Output folder.
    #[arg(long, value_name = "DIR", default_value = "results/crease")]
    pub out: PathBuf,
}

pub fn run(args: &CreaseArgs) -> Result<()> {
    let params = args.params.resolve()?;
    let study = CreaseStudy {
        mesh: CreaseMesh {
            size: args.size,
            nx: args.nx,
            layer: args.layer_elements,
            substrate: args.substrate_elements,
            ratio: args.ratio,
            element: args.element.into(),
        },
        fold_lengths: args.fold.clone(),
        scan: Scan {
            from: args.d_from,
            to: args.d_to,
            step: args.d_step,
            tolerance: args.tolerance,
        },
        convergence: !args.no_convergence,
        lowest_only: false,
    };
    study.validate()?;
    println!(
        "crease onset (energy of a seeded crease against the flat state) for folds a = {:?} H, d in [{}, {}]",
        study.fold_lengths, study.scan.from, study.scan.to
    );
    if let Some(note) = study.mesh.element.locking_note(&params) {
        println!("{note}");
    }
    let bar = ProgressBar::new_spinner();
    bar.set_style(
        ProgressStyle::with_template("{spinner} {pos} crease energies ({elapsed})").expect("static template"),
    );
    let (report, files) = crease::run(&params, &study, &args.out, &|| bar.inc(1))?;
    bar.finish_and_clear();
    for fold in &report.folds {
        match (fold.d_threshold, &fold.stopped) {
            (Some(d), _) => println!("  a = {} H: the crease pays off from d = {d:.4}", fold.fold_length),
            (None, Some(why)) => println!("  a = {} H: no threshold ({why})", fold.fold_length),
            (None, None) => println!(
                "  a = {} H: no crease pays off up to d = {}",
                fold.fold_length, study.scan.to
            ),
        }
    }
    match (report.d_crease, report.fold_length) {
        (Some(d), Some(a)) => {
            println!(
                "d_crease = {d:.4} at fold length a = {a} H (crease depth {:.3} H)",
                report.depth.unwrap_or(f64::NAN)
            );
            if let (Some(r), Some(change)) = (report.d_crease_refined, report.mesh_change) {
                println!(
                    "  refined mesh ({} unknowns): {r:.4}, change {:.2} %",
                    report.refined_unknowns.unwrap_or(0),
                    100.0 * change
                );
            }
        }
        _ => println!("no crease pays off within the scan"),
    }
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
