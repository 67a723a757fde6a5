//! Command-line interface: argument parsing, one module per command, error reporting.

mod common;
mod homogeneous;
mod params;
mod reproduce;

use clap::{Parser, Subcommand};
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
    /// Regenerate every figure available so far into one folder, with a report.
    Reproduce(reproduce::ReproduceArgs),
}

/// Runs the command line; bad input exits with code 2, failures with code 1.
pub fn run() -> ExitCode {
    let cli = Cli::parse();
    let outcome = match cli.command {
        Command::Params(args) => params::run(&args),
        Command::Homogeneous(args) => homogeneous::run(&args),
        Command::Reproduce(args) => reproduce::run(&args),
    };
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
