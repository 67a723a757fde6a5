//! `fiberfold bifurcation`: the exact first bifurcation of the discretised perfect system.

use super::common::{report_files, ParamArgs};
use clap::Args;
use fiberfold::protocol::BifurcationSettings;
use fiberfold::studies::bifurcation::{self, BifurcationStudy};
use fiberfold::studies::simulate::MeshChoice;
use fiberfold::{Error, Result};
use std::path::PathBuf;

#[derive(Args)]
pub struct BifurcationArgs {
    #[command(flatten)]
    pub params: ParamArgs,

    #[command(flatten)]
    pub mesh: MeshChoice,

    /// Width in d of the final bisection bracket, in [1e-12, 1e-2].
    #[arg(long, default_value_t = 1e-6)]
    pub tolerance: f64,

    /// Output folder.
    #[arg(long, value_name = "DIR", default_value = "results/bifurcation")]
    pub out: PathBuf,
}

pub fn run(args: &BifurcationArgs) -> Result<()> {
    let params = args.params.resolve()?;
    let mesh = args.mesh.resolve()?;
    if !(1e-12..=1e-2).contains(&args.tolerance) {
        return Err(Error::invalid("tolerance", args.tolerance, "[1e-12, 1e-2]"));
    }
    let study = BifurcationStudy {
        mesh,
        settings: BifurcationSettings {
            tolerance: args.tolerance,
            ..BifurcationSettings::default()
        },
    };
    println!(
        "bifurcation of the perfect system: inertia of the tangent along the homogeneous path, {} unknowns",
        mesh.num_dofs()
    );
    if let Some(note) = mesh
        .element
        .locking_note(params.bulk_to_shear_ratio(), params.incompressible)
    {
        println!("{note}");
    }
    let r = bifurcation::run(&params, &study, &args.out)?;
    println!(
        "d_bifurcation = {:.7} (bracket [{:.7}, {:.7}], {} negative pivot(s) past it), mode: {} half waves, k = {:.5}",
        r.d_bifurcation, r.bracket.0, r.bracket.1, r.negative_pivots_past_bifurcation, r.mode_number, r.k_mode
    );
    if let (Some(g), Some(theory)) = (r.g_bifurcation, r.g_linear_theory_min) {
        println!(
            "under {}: g_bifurcation = {g:.7}, the linear theory's min over k = m pi/50 of g_c = {theory:.7}; \
             relative difference {:+.3e}",
            r.load.name(),
            r.relative_difference
        );
    }
    println!(
        "linear theory: min over k = m pi/50 of d_c = {:.7} at k = {:.5}; relative difference in d {:+.3e} \
         (d_c at k_mode {:.7}, {:+.3e}); {} inertia evaluations, {:.1} s",
        r.d_linear_theory_min,
        r.k_linear_theory_min,
        r.d_bifurcation / r.d_linear_theory_min - 1.0,
        r.d_linear_theory_at_k_mode,
        r.relative_difference_at_k_mode,
        r.inertia_evaluations,
        r.wall_seconds
    );
    report_files(&r.files.iter().map(PathBuf::from).collect::<Vec<_>>());
    Ok(())
}
