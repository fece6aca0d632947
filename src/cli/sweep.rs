//! `impact sweep`: being written.

use clap::Args;

#[derive(Debug, Args)]
pub struct SweepArgs {}

pub fn run(_args: &SweepArgs) -> anyhow::Result<()> {
    anyhow::bail!("`impact sweep` is not written yet")
}
