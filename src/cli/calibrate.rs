//! `impact calibrate`: being written.

use clap::Args;

#[derive(Debug, Args)]
pub struct CalibrateArgs {}

pub fn run(_args: &CalibrateArgs) -> anyhow::Result<()> {
    anyhow::bail!("`impact calibrate` is not written yet")
}
