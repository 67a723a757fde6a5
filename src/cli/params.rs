//! `fiberfold params`: the resolved parameter set as TOML.

use super::common::ParamArgs;
use clap::Args;
use fiberfold::Result;
use std::path::PathBuf;

#[derive(Args)]
#[command(after_long_help = fiberfold::parameters::set_help())]
pub struct ParamsArgs {
    #[command(flatten)]
    pub params: ParamArgs,

    /// Also write the set to DIR/params.toml.
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
}

pub fn run(args: &ParamsArgs) -> Result<()> {
    let text = args.params.resolve()?.to_toml();
    println!("{}", text.trim_end());
    if let Some(dir) = &args.out {
        let path = dir.join("params.toml");
        std::fs::write(&path, &text).map_err(|e| fiberfold::Error::io(&path, e))?;
        eprintln!("wrote {}", path.display());
    }
    Ok(())
}
