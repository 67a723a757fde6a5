//! `fiberfold reproduce`: every figure of the paper, resumable, in parallel, with a report.

use super::common::{progress, ParamArgs};
use clap::Args;
use fiberfold::studies::reproduce::{pieces, run_piece, write_report, ReproduceOptions};
use fiberfold::{Error, Result};
use rayon::prelude::*;
use std::path::PathBuf;
use std::time::Instant;

#[derive(Args)]
pub struct ReproduceArgs {
    #[command(flatten)]
    pub params: ParamArgs,

    /// Coarse meshes and fewer sample points (about 20 s instead of a minute and a half on 2 cores).
    #[arg(long)]
    pub quick: bool,

    /// Output folder: figures and report.md/html at the top, one sub-folder per piece.
    #[arg(long, value_name = "DIR", default_value = "results")]
    pub out: PathBuf,

    /// Pieces run at the same time (default: the number of cores).
    #[arg(long, value_name = "N")]
    pub jobs: Option<usize>,

    /// Run only these pieces (comma separated names, e.g. `fig4b,fig5`); default: all.
    #[arg(long, value_name = "NAMES", value_delimiter = ',')]
    pub only: Vec<String>,
}

/// The pieces whose fibre angles are those of the paper's figures, not the parameters'.
const FIXED_ANGLE_PIECES: [&str; 4] = ["fig3", "fig4a", "bifurcation", "fig7"];

pub fn run(args: &ReproduceArgs) -> Result<()> {
    let params = args.params.resolve()?;
    if params.incompressible {
        // The paper's figures and its finite elements (the displacement element) are compressible.
        return Err(Error::invalid(
            "incompressible",
            true,
            "false for reproduce (the paper's compressible model; use the other commands)",
        ));
    }
    if params.load.is_growth() {
        // The paper compresses: its figures and numbers are those of `d`.
        return Err(Error::invalid(
            "load",
            params.load.name(),
            "compression for reproduce (the paper's load; the other commands take --load growth)",
        ));
    }
    let jobs = args
        .jobs
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    if jobs == 0 || jobs > 256 {
        return Err(Error::invalid("jobs", jobs, "[1, 256]"));
    }
    let options = ReproduceOptions { quick: args.quick };
    let mut pieces = pieces();
    if !args.only.is_empty() {
        let known: Vec<&str> = pieces.iter().map(|p| p.name).collect();
        if let Some(bad) = args.only.iter().find(|n| !known.contains(&n.as_str())) {
            return Err(Error::invalid(
                "only",
                bad,
                &format!("piece names: {}", known.join(", ")),
            ));
        }
        pieces.retain(|p| args.only.iter().any(|n| n == p.name));
    }
    let _lock = fiberfold::output::lock::OutputLock::acquire(&args.out)?;
    let mode = if args.quick { "quick" } else { "full" };
    println!(
        "reproducing {} pieces into {} ({mode}, {jobs} at a time); finished pieces are reused",
        pieces.len(),
        args.out.display()
    );
    let default_beta = fiberfold::Parameters::default().beta;
    if params.beta != default_beta && pieces.iter().any(|p| FIXED_ANGLE_PIECES.contains(&p.name)) {
        println!(
            "  note: {} keep the paper's fibre angles (pi/4; Fig. 4a: 0, pi/4, pi/2) whatever beta is set to; \
             `fiberfold simulate --set beta=...` runs another angle",
            FIXED_ANGLE_PIECES.join(", ")
        );
    }
    fiberfold::output::ensure_dir(&args.out)?;
    let start = Instant::now();
    let bar = progress(pieces.len(), "reproduce");
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(jobs)
        .build()
        .map_err(|e| Error::NonFinite(format!("thread pool: {e}")))?;
    let outcomes = pool.install(|| {
        pieces
            .par_iter()
            .map(|piece| {
                let outcome = run_piece(piece, &params, &options, &args.out, &|| {})?;
                bar.inc(1);
                let status = if outcome.skipped {
                    "already done, reused"
                } else {
                    "done"
                };
                bar.suspend(|| println!("  {:<12} {:>8.2} s  {status}", outcome.name, outcome.seconds));
                Ok(outcome)
            })
            .collect::<Result<Vec<_>>>()
    })?;
    bar.finish_and_clear();
    let files = write_report(&args.out, &outcomes)?;
    println!("wall time per piece:");
    for o in &outcomes {
        println!(
            "  {:<12} {:>8.2} s{}",
            o.name,
            o.seconds,
            if o.skipped { " (earlier run)" } else { "" }
        );
    }
    println!(
        "total {:.1} s; report: {}",
        start.elapsed().as_secs_f64(),
        files
            .iter()
            .map(|f| f.display().to_string())
            .collect::<Vec<_>>()
            .join(", ")
    );
    Ok(())
}
