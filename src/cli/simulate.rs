//! `fiberfold simulate` (being built).

use clap::Args;
use fiberfold::Result;

#[derive(Args)]
pub struct SimulateArgs {}

pub fn run(_args: &SimulateArgs) -> Result<()> {
    Err(fiberfold::Error::NonFinite("`simulate` is not implemented yet".into()))
}
