//! `fiberfold pattern`: a patch of tissue in three dimensions, its first bifurcation against
//! the exact 3D theory, and the wave vectors of its mode.

use super::common::{compute_grid_share, report_files, ParamArgs};
use clap::Args;
use fiberfold::output::lock::OutputLock;
use fiberfold::parameters::Load;
use fiberfold::studies::grid::Shard;
use fiberfold::studies::pattern::{self, PatternMap, PatternMapOptions, PatternOptions, Progress};
use fiberfold::Result;
use std::path::PathBuf;
use std::time::Instant;

#[derive(Args)]
pub struct PatternArgs {
    #[command(flatten)]
    pub params: ParamArgs,

    #[command(flatten)]
    pub options: PatternOptions,

    #[command(flatten)]
    pub map: PatternMapOptions,

    /// Output folder (of a map: finished points in DIR/points are reused).
    #[arg(long, value_name = "DIR", default_value = "results/pattern")]
    pub out: PathBuf,
}

pub fn run(args: &PatternArgs) -> Result<()> {
    let params = args.params.resolve()?;
    let study = args.options.study()?;
    if let Some(map) = args.map.map(params.clone(), study) {
        return run_map(&map, args);
    }
    let load = match params.load {
        Load::Compression => format!("compressed by d along X and d_3 = {} d along Z", study.biaxial),
        Load::Growth => format!(
            "whose layer grows by g = 1/(1 - d) along X and g3 = 1/(1 - R d) along Z (R = {}), the sides held",
            study.biaxial
        ),
        Load::UniformGrowth => format!(
            "whose layer and substrate grow by g = 1/(1 - d) along X and g3 = 1/(1 - R d) along Z (R = {}), the sides held",
            study.biaxial
        ),
    };
    println!(
        "pattern: a patch of tissue {load}, sized by the exact 3D theory; its first bifurcation from the inertia of the tangent along the homogeneous path"
    );
    let start = Instant::now();
    let r = pattern::run(&params, &study, &args.out, &mut |progress| {
        match progress {
        Progress::Patch {
            spec,
            azimuth,
            capped,
            unknowns,
            modes,
            memory: (memory, available),
        } => {
            println!(
                "patch {:.4} x {:.4} (X x Z), depth {:.2}, {} sides: {} x {} x {} {} hexahedra (27 nodes), {} unknowns; factor {:.3e} entries, estimated {:.0} MB{}",
                spec.length_x,
                spec.length_z,
                spec.depth,
                format!("{:?}", spec.sides).to_lowercase(),
                spec.nx,
                spec.ny(),
                spec.nz,
                spec.element.name(),
                unknowns,
                memory.factor_entries,
                memory.bytes / 1e6,
                available.map_or(String::new(), |a| format!(" of {:.0} MB available", a / 1e6))
            );
            if azimuth != 0.0 {
                println!(
                    "the load is the same in every direction of the surface: the patch's X runs along the fibres' projection, \
                     {:.2} deg from the load's X (every theta below is from the load's X)",
                    azimuth.to_degrees()
                );
            }
            for side in capped {
                println!(
                    "the onset mode's period along {} is {:.1} H, {:.2} wavelengths, more than --max-side {}: {} is one \
                     wavelength per period, and the patch holds the wave vectors below, not the theory's (--max-side {:.2} holds it)",
                    side.side,
                    side.period,
                    side.wavelengths,
                    study.max_side,
                    side.side,
                    (side.wavelengths * 100.0).ceil() / 100.0
                );
            }
            println!("admissible wave vectors nearest the onset (k = 2 pi (m / Lx, n / Lz)):");
            for mode in modes.iter().take(4) {
                println!(
                    "  (m, n) = ({:2}, {:2}): |k| = {:.5}, theta = {:6.2} deg, d_c = {:.7}",
                    mode.m,
                    mode.n,
                    mode.k,
                    mode.theta.to_degrees(),
                    mode.d_c
                );
            }
        }
        Progress::Inertia { d, negative } => {
            println!(
                "  d = {d:.7}: {negative} negative pivot(s) ({:.1} s)",
                start.elapsed().as_secs_f64()
            )
        }
        Progress::State(state) => {
            let leading = state.directions.first().map_or(String::new(), |direction| {
                format!(
                    ", leading wave (m, n) = ({}, {}) at {:.1} deg with {:.0} % of the relief",
                    direction.wave.m,
                    direction.wave.n,
                    direction.wave.theta_degrees,
                    100.0 * direction.share
                )
            });
            println!(
                "  path d = {:.4}{}: A = {:.4}, {}{}, {} negative pivot(s) ({:.1} s)",
                state.d,
                if state.left_unstable {
                    " (left the unstable state)"
                } else {
                    ""
                },
                state.amplitude,
                fiberfold::output::table::variant_name(&state.pattern),
                leading,
                state.negative_pivots.map_or("?".into(), |n| n.to_string()),
                start.elapsed().as_secs_f64()
            )
        }
        Progress::Resume(Some(d)) => println!(
            "resuming the path at d = {d:.6} from the checkpoint in {} (the patch and its bifurcation found again first)",
            args.out.display()
        ),
        Progress::Resume(None) => println!(
            "no checkpoint in {}: the path starts from the beginning",
            args.out.display()
        ),
    }
    })?;
    println!(
        "d_bifurcation = {:.7}{} (bracket [{:.7}, {:.7}], {} negative pivot(s) past it); the theory's smallest d_c over the patch's wave vectors {:.7}: relative difference {:+.3e}",
        r.d_bifurcation,
        r.g_bifurcation.map_or(String::new(), |g| format!(" (g = {g:.7})")),
        r.bracket.0,
        r.bracket.1,
        r.negative_pivots,
        r.d_c_admissible,
        r.relative_difference
    );
    if !r.mode_wave_vectors.is_empty() {
        println!("the mode's surface holds (amplitude of u_Y, largest 1):");
        for w in r.mode_wave_vectors.iter().filter(|w| w.amplitude > 1e-3) {
            println!(
                "  (m, n) = ({:2}, {:2}): |k| = {:.5}, theta = {:6.2} deg, amplitude {:.4}",
                w.m, w.n, w.k, w.theta_degrees, w.amplitude
            );
        }
    }
    if let Some(path) = &r.path {
        println!(
            "path: {} states from d = {} to {:.4}; the pattern {}",
            path.states,
            path.d_start,
            path.d_reached,
            path.changes
                .iter()
                .map(|(d, p)| format!("{} from d = {d:.4}", fiberfold::output::table::variant_name(p)))
                .collect::<Vec<_>>()
                .join(", then ")
        );
        for (d, released) in &path.branches_left {
            println!("  at d = {d:.4} the path turned unstable and was left for a stable state (energy released {released:.3e})");
        }
    }
    println!("{} inertia evaluations, {:.1} s", r.inertia_evaluations, r.wall_seconds);
    report_files(&r.files.iter().map(PathBuf::from).collect::<Vec<_>>());
    Ok(())
}

/// A map of patterns: the points of this run (a shard's, or all), then, unless a shard,
/// the map assembled.
fn run_map(map: &PatternMap, args: &PatternArgs) -> Result<()> {
    let shard = args.map.shard.as_deref().map(Shard::parse).transpose()?;
    map.validate()?;
    let detail = format!(
        "at each point: the patch of tissue sized by the exact 3D theory, its first bifurcation{}",
        if map.study.path.is_some() {
            " and its path past the onset"
        } else {
            ""
        }
    );
    let whole = args.map.collect
        || compute_grid_share(
            &args.out,
            ("map of patterns", &detail),
            (&map.x, &map.y),
            shard,
            |tick| pattern::compute_map(map, &args.out, shard, tick),
        )?;
    if !whole {
        return Ok(());
    }
    let _lock = OutputLock::acquire(&args.out)?;
    let (report, files) = pattern::collect_map(map, &args.out)?;
    let mut counts: Vec<(String, usize)> = Vec::new();
    for point in &report.points {
        let name = point
            .pattern
            .map_or("no answer".to_string(), |p| fiberfold::output::table::variant_name(&p));
        match counts.iter_mut().find(|(n, _)| *n == name) {
            Some((_, count)) => *count += 1,
            None => counts.push((name, 1)),
        }
    }
    println!(
        "  {}; point work {:.0} s",
        counts
            .iter()
            .map(|(name, count)| format!("{name} at {count}"))
            .collect::<Vec<_>>()
            .join(", "),
        report.point_seconds
    );
    report_files(&files);
    Ok(())
}
