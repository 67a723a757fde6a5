//! Command-line interface: argument parsing, one module per command, error reporting.

mod bench;
mod bifurcation;
mod common;
mod crease;
mod homogeneous;
mod map;
mod params;
mod pattern;
mod reproduce;
mod simulate;
mod stability;

use clap::{Parser, Subcommand};
use fiberfold::output::lock::OutputLock;
use fiberfold::Result;
use std::process::ExitCode;

/// fiberfold: wrinkling, creasing and folding of a stiff layer on a fibre-reinforced substrate.
///
/// Units are nondimensional as in the paper: lengths by the layer thickness H, moduli by the
/// substrate shear modulus mu_s. d = 1 - lambda_1 is the end-shortening; k is the referential
/// wavenumber. Every command writes CSV/JSON/PNG/SVG into --out DIR (default results/<command>).
#[derive(Parser)]
#[command(name = "fiberfold", version, about, long_about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Print the resolved parameter set as TOML (feed it back with --params FILE).
    Params(params::ParamsArgs),
    /// Homogeneous compressed state of both layers (eq. 4) and Fig. 2.
    Homogeneous(homogeneous::HomogeneousArgs),
    /// Critical compression d_c(k) of the linear theory over a range of wavenumbers (Fig. 5).
    Dispersion(stability::DispersionArgs),
    /// Onset of wrinkling: k0 minimising d_c(k), d_c(k0), and the loss of ellipticity.
    Onset(stability::OnsetArgs),
    /// Onset k0 and d_c against any numeric parameter, optionally for several series (Figs. 4b, 6).
    Sweep(stability::SweepArgs),
    /// Nonlinear finite-element simulation of the compressed bilayer: A(d), onset, VTU output.
    Simulate(simulate::SimulateArgs),
    /// Crease onset of the bilayer: where a seeded crease first lowers the energy (Hong, Zhao
    /// and Suo's criterion), minimised over the fold length, with a mesh check.
    Crease(crease::CreaseArgs),
    /// Instability map over two parameters: wrinkle or crease first, and what the wrinkle
    /// becomes; resumable, and shardable over a SLURM job array (--shard I/N, then --collect).
    Map(map::MapArgs),
    /// Exact bifurcation of the discretised perfect system from the inertia of its tangent.
    Bifurcation(bifurcation::BifurcationArgs),
    /// A patch of tissue in three dimensions under biaxial compression (27-node hexahedra):
    /// its first bifurcation against the exact 3D theory, the wave vectors of its mode, and with
    /// --follow-to the pattern the wrinkles make past the onset; with --x and --y, a map of
    /// patterns over two parameters (e.g. the fibres' beta and psi), shardable as map is.
    Pattern(pattern::PatternArgs),
    /// Timings of the stability analysis or the finite-element solver.
    Bench(bench::BenchArgs),
    /// Regenerate every figure of the paper (Figs. 2-7) into one folder, with a report.
    Reproduce(reproduce::ReproduceArgs),
}

/// Runs the command line; bad input exits with code 2, failures with code 1.
pub fn run() -> ExitCode {
    let cli = Cli::parse();
    let outcome = folder_lock(&cli.command).and_then(|_lock| dispatch(cli.command));
    match outcome {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {error}");
            if error.is_user_input() {
                ExitCode::from(2)
            } else {
                ExitCode::FAILURE
            }
        }
    }
}

/// The lock of the command's output folder, taken before it computes (so that a folder another
/// running command writes to, or one that cannot be written, is refused at once). `simulate` and
/// `pattern` take theirs in the library (for Python too), `map` one per shard, `reproduce` its
/// own; `params` without `--out` writes nothing.
fn folder_lock(command: &Command) -> Result<Option<OutputLock>> {
    let folder = match command {
        Command::Params(args) => args.out.as_deref(),
        Command::Homogeneous(args) => Some(args.out.as_path()),
        Command::Dispersion(args) => Some(args.out.as_path()),
        Command::Onset(args) => Some(args.out.as_path()),
        Command::Sweep(args) => Some(args.out.as_path()),
        Command::Crease(args) => Some(args.out.as_path()),
        Command::Bifurcation(args) => Some(args.out.as_path()),
        Command::Bench(args) => Some(args.out.as_path()),
        Command::Simulate(_) | Command::Pattern(_) | Command::Map(_) | Command::Reproduce(_) => None,
    };
    folder.map(OutputLock::acquire).transpose()
}

/// Runs the command.
fn dispatch(command: Command) -> Result<()> {
    match command {
        Command::Params(args) => params::run(&args),
        Command::Homogeneous(args) => homogeneous::run(&args),
        Command::Dispersion(args) => stability::dispersion(&args),
        Command::Onset(args) => stability::onset(&args),
        Command::Sweep(args) => stability::sweep(&args),
        Command::Simulate(args) => simulate::run(&args),
        Command::Crease(args) => crease::run(&args),
        Command::Map(args) => map::run(&args),
        Command::Bifurcation(args) => bifurcation::run(&args),
        Command::Pattern(args) => pattern::run(&args),
        Command::Bench(args) => bench::run(&args),
        Command::Reproduce(args) => reproduce::run(&args),
    }
}
