//! `impact merge`: being written.

use clap::Args;

#[derive(Debug, Args)]
pub struct MergeArgs {}

pub fn run(_args: &MergeArgs) -> anyhow::Result<()> {
    anyhow::bail!("`impact merge` is not written yet")
}
