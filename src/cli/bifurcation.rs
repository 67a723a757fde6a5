//! `fiberfold bifurcation` (being built).

use clap::Args;
use fiberfold::Result;

#[derive(Args)]
pub struct BifurcationArgs {}

pub fn run(_args: &BifurcationArgs) -> Result<()> {
    Err(fiberfold::Error::NonFinite(
        "`bifurcation` is not implemented yet".into(),
    ))
}
