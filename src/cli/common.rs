//! Arguments and helpers shared by every command.

use clap::Args;
use fiberfold::output::lock::OutputLock;
use fiberfold::studies::grid::{Axis, Computed, Shard};
use fiberfold::studies::Tick;
use fiberfold::{Parameters, Result};
use indicatif::{ProgressBar, ProgressStyle};
use std::path::PathBuf;

/// Model parameters: Table 1 of the paper, then a TOML file, then `--set` overrides.
#[derive(Args, Clone, Debug, Default)]
pub struct ParamArgs {
    /// TOML file of model parameters (keys as printed by `fiberfold params`); keys it omits keep
    /// their Table 1 defaults.
    #[arg(long, value_name = "FILE")]
    pub params: Option<PathBuf>,

    /// Override one parameter, repeatable, e.g. `--set beta=0.785398 --set layer.law=ogden`.
    /// Every key with its default, range and units: `fiberfold params --help`.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,

    /// What loads the bilayer, the parameter `load`: compression (the end-shortening d) |
    /// growth (the layer's growth g from 1, both ends held; d = 1 - 1/g in tables) |
    /// uniform_growth (both layers grow by g). Overrides the file's and `--set`'s.
    #[arg(long, value_name = "LOAD")]
    pub load: Option<String>,
}

impl ParamArgs {
    /// The validated parameter set.
    pub fn resolve(&self) -> Result<Parameters> {
        let mut params = match &self.params {
            Some(path) => Parameters::from_toml_file(path)?,
            None => Parameters::default(),
        };
        for assignment in &self.set {
            params.set(assignment)?;
        }
        if let Some(load) = &self.load {
            params.set_value("load", &toml::Value::String(load.clone()))?;
        }
        params.validate()?;
        for warning in params.warnings() {
            eprintln!("warning: {warning}");
        }
        Ok(params)
    }
}

/// Lists the files a command wrote.
pub fn report_files(files: &[PathBuf]) {
    for f in files {
        println!("  wrote {}", f.display());
    }
}

/// A progress bar on standard error (drawn only on a terminal).
pub fn progress(len: usize, what: &str) -> ProgressBar {
    let bar = ProgressBar::new(len as u64);
    bar.set_style(
        ProgressStyle::with_template("{msg:>14} [{bar:40}] {pos}/{len} ({elapsed}, eta {eta})")
            .expect("static template")
            .progress_chars("=> "),
    );
    bar.set_message(what.to_string());
    bar
}

/// A spinner on standard error for work of unknown length (drawn only on a terminal).
pub fn spinner(what: &str) -> ProgressBar {
    let bar = ProgressBar::new_spinner();
    bar.set_message(what.to_string());
    bar.enable_steady_tick(std::time::Duration::from_millis(120));
    bar
}

/// The points of a grid (`map`, or `pattern` with `--x` and `--y`) this run computes: the
/// folder locked (per shard with `--shard`), `what` announced with the grid's axes and the
/// share (then `detail`, unless empty), a progress bar over the points, the count computed and reused. True where the run
/// goes on to assemble the grid (not a shard's).
pub fn compute_grid_share(
    out: &std::path::Path,
    (what, detail): (&str, &str),
    (x, y): (&Axis, &Axis),
    shard: Option<Shard>,
    compute: impl FnOnce(Tick) -> Result<Computed>,
) -> Result<bool> {
    let _lock = match shard {
        Some(s) => OutputLock::acquire_named(out, &format!(".fiberfold-shard-{}-of-{}.lock", s.index, s.count))?,
        None => OutputLock::acquire(out)?,
    };
    let total = x.points * y.points;
    let share = shard.map_or(total, |s| s.share(total));
    println!(
        "{what}: {} x {} points over {} in [{}, {}] and {} in [{}, {}]{}",
        x.points,
        y.points,
        x.name,
        x.from,
        x.to,
        y.name,
        y.from,
        y.to,
        shard.map_or(String::new(), |s| format!(
            ", shard {}/{}: {share} points",
            s.index, s.count
        )),
    );
    if !detail.is_empty() {
        println!("  {detail}");
    }
    let bar = progress(share, "points");
    let done = compute(&|| bar.inc(1))?;
    bar.finish_and_clear();
    println!(
        "  {} points computed, {} reused from {}",
        done.points - done.reused,
        done.reused,
        out.join("points").display()
    );
    if shard.is_some() {
        println!("  assemble the shards with the same flags and --collect");
    }
    Ok(shard.is_none())
}
