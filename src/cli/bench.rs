//! `fiberfold bench stability | fe`: timings printed as Markdown tables (never timed tests).

use super::common::ParamArgs;
use clap::{Args, ValueEnum};
use fiberfold::Result;

#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum BenchTarget {
    /// Linear stability: one d_c(k), one onset, the Fig. 4b sweep.
    Stability,
}

#[derive(Args)]
pub struct BenchArgs {
    /// What to time.
    #[arg(value_enum)]
    pub target: BenchTarget,
    #[command(flatten)]
    pub params: ParamArgs,
}

pub fn run(args: &BenchArgs) -> Result<()> {
    let params = args.params.resolve()?;
    match args.target {
        BenchTarget::Stability => {
            println!("timing the linear stability analysis (medians of repeated runs)...");
            print!("{}", fiberfold::studies::bench_stability::run(&params)?);
        }
    }
    Ok(())
}
