//! `fiberfold map`: the instability map over two parameters, resumable and shardable.

use super::common::{compute_grid_share, report_files, ParamArgs};
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
    let whole = args.collect
        || compute_grid_share(
            &args.out,
            ("instability map", ""),
            (&study.x, &study.y),
            shard,
            |tick| map::compute(&study, &args.out, shard, tick),
        )?;
    if !whole {
        return Ok(());
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
