//! `fiberfold dispersion | onset | sweep`: the linear stability analysis (Appendix A).

use super::common::{progress, report_files, spinner, ParamArgs};
use clap::Args;
use fiberfold::stability::Minimum;
use fiberfold::studies::orientation::Modes;
use fiberfold::studies::stability::{self, parse_series, DispersionStudy, Solver, SweepStudy};
use fiberfold::Result;
use std::path::PathBuf;

/// Waves in the surface under biaxial compression instead of the paper's plane strain.
#[derive(Args)]
pub struct ModesArgs {
    /// Compression along Z as a fraction R of the compression d along X, d_3 = R d, in [0, 1]
    /// (0: plane strain in the stretches, 1: equibiaxial). Given (or with --theta), waves run in
    /// any direction of the surface with three displacement components, and the fibres may
    /// leave the X-Y plane (psi). Absent: the paper's plane strain, waves along X only.
    #[arg(long, value_name = "R", allow_negative_numbers = true)]
    pub biaxial: Option<f64>,
    /// Direction of the wave vector in the surface, radians from X towards Z (the crests run
    /// perpendicular to it). Absent with --biaxial: `onset` and `sweep` search every direction,
    /// `dispersion` takes theta = 0 (along X).
    #[arg(long, value_name = "RAD", allow_negative_numbers = true)]
    pub theta: Option<f64>,
}

impl ModesArgs {
    fn modes(&self) -> Modes {
        Modes {
            biaxial: self.biaxial,
            theta: self.theta,
        }
    }
}

#[derive(Args)]
pub struct DispersionArgs {
    #[command(flatten)]
    pub params: ParamArgs,
    #[command(flatten)]
    pub modes: ModesArgs,
    /// Smallest referential wavenumber k (units 1/H, > 0).
    #[arg(long, default_value_t = 0.05, allow_negative_numbers = true)]
    pub k_min: f64,
    /// Largest wavenumber k (units 1/H, > k-min).
    #[arg(long, default_value_t = 3.0, allow_negative_numbers = true)]
    pub k_max: f64,
    /// Number of equally spaced wavenumbers (at least 2).
    #[arg(long, default_value_t = 300)]
    pub points: usize,
    /// Solver.
    #[arg(long, value_enum, default_value_t = Solver::Exact)]
    pub method: Solver,
    /// Output folder.
    #[arg(long, value_name = "DIR", default_value = "results/dispersion")]
    pub out: PathBuf,
}

pub fn dispersion(args: &DispersionArgs) -> Result<()> {
    let params = args.params.resolve()?;
    let study = DispersionStudy {
        k_min: args.k_min,
        k_max: args.k_max,
        points: args.points,
        method: args.method.method(),
        modes: args.modes.modes(),
    };
    study.validate()?;
    study.modes.validate()?;
    println!(
        "critical compression d_c(k) for k in [{}, {}], {} points ({:?}; {})",
        study.k_min,
        study.k_max,
        study.points,
        args.method,
        study.modes.along_one_direction().describe()
    );
    if let (Some(biaxial), None) = (study.modes.biaxial, study.modes.theta) {
        println!(
            "  along X: --theta sets another direction; `fiberfold onset --biaxial {biaxial}` finds the critical one"
        );
    }
    let bar = progress(study.points, "dispersion");
    let files = stability::dispersion(&params, &study, &args.out, &|| bar.inc(1))?;
    bar.finish_and_clear();
    report_files(&files);
    Ok(())
}

#[derive(Args)]
pub struct OnsetArgs {
    #[command(flatten)]
    pub params: ParamArgs,
    #[command(flatten)]
    pub modes: ModesArgs,
    /// Solver.
    #[arg(long, value_enum, default_value_t = Solver::Exact)]
    pub method: Solver,
    /// Output folder.
    #[arg(long, value_name = "DIR", default_value = "results/onset")]
    pub out: PathBuf,
}

pub fn onset(args: &OnsetArgs) -> Result<()> {
    let params = args.params.resolve()?;
    let modes = args.modes.modes();
    modes.validate()?;
    println!(
        "onset of wrinkling: minimum of d_c(k) over k in [0.02, 5], followed to 1e-4 or 10 if it lies at an end ({:?}; {})",
        args.method,
        modes.describe()
    );
    let spinner = (modes.surface().is_some() && modes.theta.is_none()).then(|| spinner("directions"));
    let (onset, files) = stability::onset(&params, args.method.method(), &modes, &args.out)?;
    if let Some(s) = spinner {
        s.finish_and_clear();
    }
    match (onset.minimum, onset.wavelength) {
        (_, Some(wavelength)) => println!("  k0 = {:.6}  (wavelength {wavelength:.4} H)", onset.k0),
        (Minimum::Flat, _) => println!(
            "  no k0: d_c(k) is the same at every k (flat): a homogeneous half-space's surface instability, at any wavelength"
        ),
        (Minimum::LongWave, _) => println!(
            "  no finite k0: d_c(k) decreases all the way to k -> 0 (long_wave): the substrate's own surface instability comes first"
        ),
        _ => println!(
            "  no finite k0: d_c(k) decreases all the way to k -> infinity (short_wave): the layer's own surface instability comes first"
        ),
    }
    let load = params.load;
    match onset.g_c {
        Some(g_c) => println!(
            "  g_c = {g_c:.6}  (the critical growth, load = {}; the strain d_c = 1 - 1/g_c = {:.6})",
            load.name(),
            onset.d_c
        ),
        None => println!("  d_c = {:.6}  (lambda1_c = {:.6})", onset.d_c, onset.lambda1_c),
    }
    // A strain d of the searches, as the load's parameter.
    let at = |d: f64| format!("{} = {:.6}", load.parameter_name(), load.parameter(d));
    if let Some(spread) = onset.direction_spread {
        match onset.theta0.is_finite() {
            true => println!(
                "  theta0 = {:.6} rad = {:.2} deg: the wave vector's direction from X (crests perpendicular); \
                 at k0 the least critical direction's d_c is {spread:.2e} higher",
                onset.theta0,
                onset.theta0.to_degrees()
            ),
            false => {
                println!("  no preferred direction: the onset is the same in every direction (within {spread:.1e})")
            }
        }
    }
    match onset.d_ellipticity_loss {
        Some(d) => println!(
            "  strong ellipticity is lost at {}; beyond it wrinkling results are meaningless",
            at(d)
        ),
        None => match onset.d_domain_end {
            Some(d) => println!(
                "  the homogeneous state reaches a Gent law's limiting extensibility at {}, where the search \
                 ends; both layers stay strongly elliptic up to it",
                at(d)
            ),
            None => println!("  both layers stay strongly elliptic up to {}", at(0.95)),
        },
    }
    report_files(&files);
    Ok(())
}

#[derive(Args)]
pub struct SweepArgs {
    #[command(flatten)]
    pub params: ParamArgs,
    /// The numeric parameter to sweep (a key of `fiberfold params`, e.g. beta, mu_f, lambda_f).
    #[arg(long)]
    pub param: String,
    /// First value of the swept parameter (its own units; beta in radians).
    #[arg(long, allow_negative_numbers = true)]
    pub from: f64,
    /// Last value of the swept parameter.
    #[arg(long, allow_negative_numbers = true)]
    pub to: f64,
    /// Number of equally spaced values (at least 1).
    #[arg(long, default_value_t = 91)]
    pub points: usize,
    /// Repeat the sweep for several values of another parameter, e.g. `mu_f=1,10,20,50`.
    #[arg(long, value_name = "KEY=V1,V2,...")]
    pub series: Option<String>,
    #[command(flatten)]
    pub modes: ModesArgs,
    /// Solver.
    #[arg(long, value_enum, default_value_t = Solver::Exact)]
    pub method: Solver,
    /// Let the bulk modulus stay at its base value when mu_l or mu_s is swept (by default it
    /// scales with it, keeping the base K/mu: the Poisson ratio stays the base set's, as in `map`).
    #[arg(long)]
    pub free_bulk: bool,
    /// Output folder.
    #[arg(long, value_name = "DIR", default_value = "results/sweep")]
    pub out: PathBuf,
}

pub fn sweep(args: &SweepArgs) -> Result<()> {
    let params = args.params.resolve()?;
    let study = SweepStudy {
        param: args.param.clone(),
        from: args.from,
        to: args.to,
        points: args.points,
        series: args.series.as_deref().map(parse_series).transpose()?,
        values: None,
        method: args.method.method(),
        modes: args.modes.modes(),
        keep_poisson: !args.free_bulk,
    };
    study.modes.validate()?;
    println!(
        "onset k0 and d_c against {} in [{}, {}], {} onsets in parallel ({})",
        study.param,
        study.from,
        study.to,
        study.onsets(),
        study.modes.describe()
    );
    let bar = progress(study.onsets(), "sweep");
    let files = stability::sweep(&params, &study, &args.out, &|| bar.inc(1))?;
    bar.finish_and_clear();
    report_files(&files);
    Ok(())
}
