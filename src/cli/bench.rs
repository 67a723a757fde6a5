//! `fiberfold bench stability | fe | patch | crease | map`: timings printed as Markdown tables
//! (never timed tests), and written to the output folder (the tables, and the timings as JSON).

use super::common::{report_files, ParamArgs};
use clap::{Args, ValueEnum};
use fiberfold::output::atomic::write_file;
use fiberfold::output::write_json;
use fiberfold::studies::bench_fe::{self, default_meshes, FeBench, FeBenchSetup, Kernels, LawKernels, SnapBench};
use fiberfold::Result;
use serde::Serialize;
use std::path::PathBuf;

#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum BenchTarget {
    /// Linear stability: one d_c(k), one onset, the Fig. 4b sweep, one onset over k and the
    /// directions of the surface, the (beta, psi) orientation map.
    Stability,
    /// Finite elements: the beta = pi/4, N = 4.5 curve to d = 0.25 on coarse and fine meshes,
    /// split per Newton iteration into assembly / factorisation / solve, with peak memory; then
    /// per-call kernel times (tangent and residual assembly, LDLT, solve); then one Newton
    /// iteration with each tissue law (neo-Hookean, Mooney-Rivlin, Ogden, Gent, HGO) side by side.
    Fe,
    /// Three-dimensional patch: one Newton iteration (tangent assembly, ordering and analysis,
    /// LDLT, one solve), the factor's entries and peak memory on periodic boxes of 1 x 1 up to
    /// --periods onset periods (pattern's default mesh, equibiaxial), and how they grow.
    Patch,
    /// The crease onset (the default `crease` study on the given parameters): the linear
    /// theory's onset, then each mesh of the sequence (folds searched, creased states solved,
    /// seconds).
    Crease,
    /// A 2 x 2 map (mu_l from 3 to 10, beta from 0 to pi/2, the map's defaults), its points one
    /// after the other, each split into linear theory, crease search and nonlinear run.
    Map,
}

#[derive(Args)]
pub struct BenchArgs {
    /// What to time.
    #[arg(value_enum)]
    pub target: BenchTarget,
    #[command(flatten)]
    pub params: ParamArgs,
    /// fe: also the extra mesh (315,594 unknowns, about 2 minutes and 1.1 GB).
    #[arg(long)]
    pub extra: bool,
    /// fe: only the coarse mesh (seconds).
    #[arg(long, conflicts_with = "extra")]
    pub coarse_only: bool,
    /// stability: values of beta and of psi in the equibiaxial orientation map (N x N onsets
    /// over k and theta, about 2 minutes at 91 on 2 cores; 0 skips it).
    #[arg(long, value_name = "N", default_value_t = 91)]
    pub orientation_map: usize,
    /// patch: the largest box, in onset periods along each side (at Table 1, 2: 108,358
    /// unknowns and 3 GB; 3: 245,270 unknowns, 12 GB and about 3 minutes on 2 cores).
    #[arg(long, value_name = "N", default_value_t = 3)]
    pub periods: usize,
    /// Output folder: `bench_stability.md`, `bench_fe.md` and `bench_fe.json`,
    /// `bench_patch.md` and `bench_patch.json`, `bench_crease.md` and `bench_crease.json`, or
    /// `bench_map.md` and `bench_map.json`.
    #[arg(long, value_name = "DIR", default_value = "results/bench")]
    pub out: PathBuf,
}

/// What `bench fe` writes as JSON.
#[derive(Serialize)]
struct FeTimings<'a> {
    curves: &'a FeBench,
    kernels: &'a Kernels,
    laws: &'a LawKernels,
    snaps: &'a SnapBench,
}

pub fn run(args: &BenchArgs) -> Result<()> {
    let params = args.params.resolve()?;
    let files = match args.target {
        BenchTarget::Stability => {
            println!("timing the linear stability analysis (medians of repeated runs)...");
            let table = fiberfold::studies::bench_stability::run(&params, args.orientation_map)?;
            print!("{table}");
            let path = args.out.join("bench_stability.md");
            write_file(&path, &table)?;
            vec![path]
        }
        BenchTarget::Fe => {
            let mut meshes = default_meshes(args.extra);
            if args.coarse_only {
                meshes.truncate(1);
            }
            // The benchmark's curve is at beta = pi/4; explicit --params/--set replace it.
            let user_params = args.params.params.is_some() || !args.params.set.is_empty();
            let setup = if user_params {
                FeBenchSetup {
                    params,
                    ..FeBenchSetup::default()
                }
            } else {
                FeBenchSetup::default()
            };
            println!(
                "timing the FE curve (beta = {:.6}, N = {}, to d = {}) on {} mesh(es)...",
                setup.params.beta,
                setup.waves,
                setup.d_max,
                meshes.len()
            );
            let bench = bench_fe::run(&setup, &meshes, &|_| Ok(()))?;
            print!("{bench}");
            // After the curves, so that their peak-memory column is theirs alone.
            let heading = "per-call kernels at the homogeneous state of d = 0.1 (medians of 5):";
            println!("{heading}");
            let kernels = bench_fe::kernels(&setup.params, &meshes)?;
            print!("{kernels}");
            let law_heading = "one Newton iteration with each tissue law (displacement element, d = 0.1):";
            println!("{law_heading}");
            let laws = bench_fe::laws(&setup.params, &meshes)?;
            print!("{laws}");
            let snap_heading = "the same curve with contact, its snaps crossed by energy minimisation:";
            println!("{snap_heading}");
            let snaps = bench_fe::snaps(&setup, &meshes)?;
            print!("{snaps}");
            let (table, json) = (args.out.join("bench_fe.md"), args.out.join("bench_fe.json"));
            write_file(
                &table,
                format!(
                    "```text\n{}\n```\n\n{heading}\n\n{kernels}\n{law_heading}\n\n{laws}\n{snap_heading}\n\n{snaps}",
                    bench.to_string().trim_end()
                ),
            )?;
            write_json(
                &json,
                &FeTimings {
                    curves: &bench,
                    kernels: &kernels,
                    laws: &laws,
                    snaps: &snaps,
                },
            )?;
            vec![table, json]
        }
        BenchTarget::Patch => patch(&params, args)?,
        BenchTarget::Crease => {
            println!("timing the crease onset, per phase...");
            let bench = fiberfold::studies::bench_crease::crease_phases(&params)?;
            print!("{bench}");
            write_table(args, "bench_crease", &bench.to_string(), &bench)?
        }
        BenchTarget::Map => {
            println!("timing a 2 x 2 map (mu_l in [3, 10], beta in [0, pi/2]), point by point...");
            let bench = fiberfold::studies::bench_crease::map_phases(&params)?;
            print!("{bench}");
            write_table(args, "bench_map", &bench.to_string(), &bench)?
        }
    };
    report_files(&files);
    Ok(())
}

/// `NAME.md` (the table) and `NAME.json`.
fn write_table(args: &BenchArgs, name: &str, table: &str, json: &impl Serialize) -> Result<Vec<PathBuf>> {
    let (md, js) = (
        args.out.join(format!("{name}.md")),
        args.out.join(format!("{name}.json")),
    );
    write_file(&md, table)?;
    write_json(&js, json)?;
    Ok(vec![md, js])
}

/// `bench patch`: the boxes' table, printed and written.
fn patch(params: &fiberfold::Parameters, args: &BenchArgs) -> Result<Vec<PathBuf>> {
    if args.periods < 1 {
        return Err(fiberfold::Error::invalid("periods", args.periods, "an integer >= 1"));
    }
    println!(
        "timing one Newton iteration of periodic patches of 1 x 1 to {0} x {0} onset periods...",
        args.periods
    );
    let bench = fiberfold::studies::bench_patch::run(params, 1.0, args.periods)?;
    print!("{bench}");
    let (table, json) = (args.out.join("bench_patch.md"), args.out.join("bench_patch.json"));
    write_file(&table, bench.to_string())?;
    write_json(&json, &bench)?;
    Ok(vec![table, json])
}
