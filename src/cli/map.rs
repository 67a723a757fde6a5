//! `fiberfold map`: the instability map over two parameters, resumable and shardable.

use super::common::{progress, report_files, ParamArgs};
use clap::Args;
use fiberfold::output::lock::OutputLock;
use fiberfold::studies::map::{self, MapOptions, Shard};
use fiberfold::Result;
use std::path::PathBuf;

#[derive(Args)]
pub struct MapArgs {
    #[command(flatten)]
    pub params: ParamArgs,

    #[command(flatten)]
    pub options: MapOptions,

    /// Compute only the points with index % N == I (I/N; e.g. $SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT),
    /// into the same folder as the other shards; assemble them with --collect.
    #[arg(long, value_name = "I/N", conflicts_with = "collect")]
    pub shard: Option<String>,

    /// Only assemble the finished points in --out into map.csv, map.json and the figure (with
    /// the same map flags as the shards); missing points are an error.
    #[arg(long)]
    pub collect: bool,

    /// Output folder (finished points in DIR/points are reused).
    #[arg(long, value_name = "DIR", default_value = "results/map")]
    pub out: PathBuf,
}

pub fn run(args: &MapArgs) -> Result<()> {
    let study = args.options.study(args.params.resolve()?)?;
    let shard = args.shard.as_deref().map(Shard::parse).transpose()?;
    study.validate()?;
    let total = study.x.points * study.y.points;
    if !args.collect {
        let _lock = match shard {
            Some(s) => {
                OutputLock::acquire_named(&args.out, &format!(".fiberfold-shard-{}-of-{}.lock", s.index, s.count))?
            }
            None => OutputLock::acquire(&args.out)?,
        };
        let share = shard.map_or(total, |s| (total + s.count - 1 - s.index) / s.count);
        println!(
            "instability map: {} x {} points over {} in [{}, {}] and {} in [{}, {}]{}",
            study.x.points,
            study.y.points,
            study.x.name,
            study.x.from,
            study.x.to,
            study.y.name,
            study.y.from,
            study.y.to,
            shard.map_or(String::new(), |s| format!(
                ", shard {}/{}: {share} points",
                s.index, s.count
            )),
        );
        let bar = progress(share, "points");
        let done = map::compute(&study, &args.out, shard, &|| bar.inc(1))?;
        bar.finish_and_clear();
        println!(
            "  {} points computed, {} reused from {}",
            done.points - done.reused,
            done.reused,
            args.out.join("points").display()
        );
        if shard.is_some() {
            println!("  assemble the shards with the same flags and --collect");
            return Ok(());
        }
    }
    let _lock = OutputLock::acquire(&args.out)?;
    let (report, files) = map::collect(&study, &args.out)?;
    let count = |f: fn(&map::MapPoint) -> bool| report.points.iter().filter(|p| f(p)).count();
    println!(
        "  crease first at {} points, wrinkle first at {}, neither in range at {}; point work {:.0} s",
        count(|p| p.first == map::First::Crease),
        count(|p| p.first == map::First::Wrinkle),
        count(|p| p.first == map::First::None),
        report.point_seconds
    );
    report_files(&files);
    Ok(())
}
