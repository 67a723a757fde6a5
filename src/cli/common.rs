//! Arguments and helpers shared by every command.

use clap::Args;
use fiberfold::{Parameters, Result};
use indicatif::{ProgressBar, ProgressStyle};
use std::path::{Path, PathBuf};

/// Model parameters: Table 1 of the paper, then a TOML file, then `--set` overrides.
#[derive(Args, Clone, Debug, Default)]
pub struct ParamArgs {
    /// TOML file of model parameters (keys as printed by `fiberfold params`); keys it omits keep
    /// their Table 1 defaults.
    #[arg(long, value_name = "FILE")]
    pub params: Option<PathBuf>,

    /// Override one parameter, repeatable, e.g. `--set beta=0.785398 --set mu_f=20`. Keys
    /// (defaults): mu_l (10), K_l (30), mu_s (1), K_s (3), phi_m (0.9), phi_f (0.1, the volume
    /// fraction of EACH of the two fibre families: Table 1's 0.1 read as eq. 3 does; the paper's
    /// text says 0.05 per family), mu_f (10), lambda_f (1), beta (0, radians), tension_only
    /// (false), incompressible (false: exactly incompressible layers, J = 1, K_l and K_s unused;
    /// finite-element commands then need --element mixed). Moduli in units of mu_s.
    /// Laws, by dotted keys (see README, "Tissue laws"): layer.law and substrate.law =
    /// neo_hookean (default) | mooney_rivlin (layer.c1, layer.c2) | ogden (layer.mu, layer.alpha:
    /// numbers or lists [..] of 1 to 3 terms) | gent (layer.jm); mu_l, mu_s stay each law's shear
    /// modulus and K_l, K_s its bulk modulus. fibres.law = quadratic (default: mu_f, lambda_f) |
    /// hgo (fibres.k1, fibres.k2, fibres.kappa in [0, 1/3], default 0). Set a law before its
    /// constants, e.g. `--set layer.law=ogden --set layer.alpha=-25`.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
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
        params.validate()?;
        Ok(params)
    }
}

/// Creates the output folder and says where results go.
pub fn prepare_out(dir: &Path) -> Result<()> {
    fiberfold::output::ensure_dir(dir)
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
