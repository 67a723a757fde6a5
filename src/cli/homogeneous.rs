//! `fiberfold homogeneous`: the homogeneous compressed state (eq. 4) and Fig. 2.

use super::common::{progress, report_files, ParamArgs};
use clap::Args;
use fiberfold::studies::homogeneous::{self, HomogeneousStudy};
use fiberfold::Result;
use std::path::PathBuf;

#[derive(Args)]
pub struct HomogeneousArgs {
    #[command(flatten)]
    pub params: ParamArgs,

    /// Largest end-shortening d = 1 - lambda_1 (dimensionless, in [0, 1)); under --load growth
    /// the strain d = 1 - 1/g of the largest growth g.
    #[arg(long, default_value_t = 0.5, allow_negative_numbers = true)]
    pub d_max: f64,

    /// Number of equally spaced values of d from 0 to d-max (at least 2).
    #[arg(long, default_value_t = 101)]
    pub points: usize,

    /// Output folder.
    #[arg(long, value_name = "DIR", default_value = "results/homogeneous")]
    pub out: PathBuf,
}

pub fn run(args: &HomogeneousArgs) -> Result<()> {
    let params = args.params.resolve()?;
    let study = HomogeneousStudy {
        d_max: args.d_max,
        points: args.points,
    };
    study.validate()?;
    println!(
        "homogeneous state of both layers (eq. 4) for d in [0, {}], {} points",
        study.d_max, study.points
    );
    let bar = progress(study.points, "homogeneous");
    let outcome = homogeneous::run(&params, &study, &args.out, &|| bar.inc(1))?;
    bar.finish_and_clear();
    if let Some((d, why)) = &outcome.stopped {
        println!("  the table ends before d = {d:.4}: {why}");
    }
    report_files(&outcome.files);
    Ok(())
}
