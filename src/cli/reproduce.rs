//! `fiberfold reproduce`: every figure available so far, resumable, with a report.

use super::common::{progress, ParamArgs};
use clap::Args;
use fiberfold::studies::reproduce::{pieces, run_piece, write_report, ReproduceOptions};
use fiberfold::Result;
use std::path::PathBuf;

#[derive(Args)]
pub struct ReproduceArgs {
    #[command(flatten)]
    pub params: ParamArgs,

    /// Coarse meshes and fewer sample points (minutes instead of an hour).
    #[arg(long)]
    pub quick: bool,

    /// Output folder: figures and report.md at the top, one sub-folder per piece.
    #[arg(long, value_name = "DIR", default_value = "results")]
    pub out: PathBuf,
}

pub fn run(args: &ReproduceArgs) -> Result<()> {
    let params = args.params.resolve()?;
    let options = ReproduceOptions { quick: args.quick };
    let pieces = pieces();
    println!(
        "reproducing {} piece(s) into {}{}",
        pieces.len(),
        args.out.display(),
        if args.quick { " (quick)" } else { "" }
    );
    fiberfold::output::ensure_dir(&args.out)?;
    let bar = progress(pieces.len(), "reproduce");
    let mut outcomes = Vec::new();
    for piece in &pieces {
        let outcome = run_piece(piece, &params, &options, &args.out, &|| {})?;
        bar.inc(1);
        let status = if outcome.skipped {
            "(already done, reused)"
        } else {
            "done"
        };
        bar.suspend(|| println!("  {:<14} {:>8.2} s  {status}", outcome.name, outcome.seconds));
        outcomes.push(outcome);
    }
    bar.finish_and_clear();
    let report = write_report(&args.out, &outcomes)?;
    println!(
        "wrote {} and figures {}",
        report.display(),
        pieces
            .iter()
            .flat_map(|p| p.figures.iter())
            .cloned()
            .collect::<Vec<_>>()
            .join(", ")
    );
    Ok(())
}
