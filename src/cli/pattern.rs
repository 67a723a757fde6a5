//! `fiberfold pattern`: a patch of tissue in three dimensions, its first bifurcation against
//! the exact 3D theory, and the wave vectors of its mode.

use super::common::{report_files, ParamArgs};
use clap::Args;
use fiberfold::mesh::{ElementKind, Sides};
use fiberfold::protocol::BifurcationSettings;
use fiberfold::studies::pattern::{self, PathStudy, PatternStudy, Progress};
use fiberfold::{Error, Result};
use std::path::PathBuf;
use std::time::Instant;

#[derive(Args)]
pub struct PatternArgs {
    #[command(flatten)]
    pub params: ParamArgs,

    /// R = d_3 / d in [0, 1]: the compression along Z relative to X's (1 equibiaxial).
    #[arg(long, default_value_t = 1.0)]
    pub biaxial: f64,

    /// Periods of the theory's onset mode along each side of the patch (an integer >= 1).
    #[arg(long, default_value_t = 1)]
    pub periods: usize,

    /// Hexahedra per onset wavelength along X and Z (an integer >= 2; more give an onset closer
    /// to the continuum's, at a cost growing as their cube; the guide's "Patterns in three dimensions" shows the convergence).
    #[arg(long, default_value_t = 6)]
    pub elements_per_wavelength: usize,

    /// Hexahedra through the layer (an integer >= 1).
    #[arg(long, default_value_t = 2)]
    pub layer_elements: usize,

    /// Hexahedra through the substrate, graded from --h0 at the interface (an integer >= 1).
    #[arg(long, default_value_t = 12)]
    pub substrate_elements: usize,

    /// Thickness of the top substrate element, in layer thicknesses H, in (0, depth).
    #[arg(long, default_value_t = 0.35)]
    pub h0: f64,

    /// Depth of the substrate in onset wavelengths, > 0 (the modes decay as exp(-k |Y|)).
    #[arg(long, default_value_t = 2.0)]
    pub depth: f64,

    /// How the sides hold the patch.
    #[arg(long, value_enum, default_value_t = Sides::Periodic)]
    pub sides: Sides,

    /// The hexahedra's element (27 nodes; mixed: with a linear pressure per element). The
    /// mixed one is the more accurate on a layer stiffer than the substrate, but finds a
    /// spurious mode at the element scale on a nearly incompressible half-space.
    #[arg(long, value_enum, default_value_t = ElementKind::Displacement)]
    pub element: ElementKind,

    /// Largest d scanned for the bifurcation, in (0, 0.95].
    #[arg(long, default_value_t = 0.9)]
    pub d_max: f64,

    /// Width in d of the final bisection bracket, in [1e-12, 1e-2].
    #[arg(long, default_value_t = 1e-6)]
    pub tolerance: f64,

    /// Follow the path past the onset to this d, in (d-start, 0.95) (periodic sides only): the
    /// patch seeded with every wave vector critical at the onset, one row of pattern.csv per
    /// state. Not followed if absent.
    #[arg(long, value_name = "D")]
    pub follow_to: Option<f64>,

    /// Amplitude A_init of the first seeded wave of the path's imperfection, in layer
    /// thicknesses H, in (0, 1).
    #[arg(long, default_value_t = PathStudy::default().imperfection)]
    pub imperfection: f64,

    /// Amplitude of every further critical wave seeded, relative to the first's, in [0, 1]: 1
    /// seeds their equal superposition (a checkerboard, which the path then keeps by symmetry
    /// even where the tissue would leave it), less lets the path choose.
    #[arg(long, default_value_t = PathStudy::default().seed_ratio)]
    pub seed_ratio: f64,

    /// Where the followed path starts, in (0, --follow-to).
    #[arg(long, default_value_t = PathStudy::default().d_start)]
    pub d_start: f64,

    /// Output folder.
    #[arg(long, value_name = "DIR", default_value = "results/pattern")]
    pub out: PathBuf,
}

pub fn run(args: &PatternArgs) -> Result<()> {
    let params = args.params.resolve()?;
    if !(1e-12..=1e-2).contains(&args.tolerance) {
        return Err(Error::invalid("tolerance", args.tolerance, "[1e-12, 1e-2]"));
    }
    if !(args.d_max > 0.0 && args.d_max <= 0.95) {
        return Err(Error::invalid("d-max", args.d_max, "(0, 0.95]"));
    }
    let study = PatternStudy {
        biaxial: args.biaxial,
        periods: args.periods,
        elements_per_wavelength: args.elements_per_wavelength,
        layer_elements: args.layer_elements,
        substrate_elements: args.substrate_elements,
        top_substrate_thickness: args.h0,
        depth_wavelengths: args.depth,
        sides: args.sides,
        element: args.element,
        settings: BifurcationSettings {
            d_end: args.d_max,
            tolerance: args.tolerance,
            ..PatternStudy::default().settings
        },
        path: args.follow_to.map(|d_end| PathStudy {
            imperfection: args.imperfection,
            seed_ratio: args.seed_ratio,
            d_start: args.d_start,
            d_end,
        }),
    };
    println!(
        "pattern: a patch of tissue under d_3 = {} d, sized by the exact 3D theory; its first bifurcation from the inertia of the tangent along the homogeneous path",
        args.biaxial
    );
    let start = Instant::now();
    let r = pattern::run(&params, &study, &args.out, &mut |progress| match progress {
        Progress::Patch { spec, unknowns, modes } => {
            println!(
                "patch {:.4} x {:.4} (X x Z), depth {:.2}, {} sides: {} x {} x {} {} hexahedra (27 nodes), {} unknowns",
                spec.length_x,
                spec.length_z,
                spec.depth,
                format!("{:?}", spec.sides).to_lowercase(),
                spec.nx,
                spec.ny(),
                spec.nz,
                spec.element.name(),
                unknowns
            );
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
    })?;
    println!(
        "d_bifurcation = {:.7} (bracket [{:.7}, {:.7}], {} negative pivot(s) past it); the theory's smallest d_c over the patch's wave vectors {:.7}: relative difference {:+.3e}",
        r.d_bifurcation, r.bracket.0, r.bracket.1, r.negative_pivots, r.d_c_admissible, r.relative_difference
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
