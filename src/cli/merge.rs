//! `impact merge OUT.csv SHARD.csv...`: join the shards of a sweep run with `--shard I/N` into the file the whole
//! sweep would have written, byte for byte (see [`crate::sweep::merge`]).

use super::BadInput;
use super::sweep::bad;
use crate::output::files::write_atomically;
use crate::output::sweep_figure;
use crate::sweep::figure;
use crate::sweep::merge::{ShardFile, merge};
use clap::Args;
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct MergeArgs {
    /// The merged CSV to write (written completely or not at all).
    pub out: PathBuf,
    /// The shard files of one sweep, in any order: every shard 1/N ... N/N exactly once.
    #[arg(required = true, value_name = "SHARD")]
    pub shards: Vec<PathBuf>,
    /// Also draw the sweep's figure (as `impact sweep --plot`; PNG or SVG by the extension).
    #[arg(long, value_name = "FILE.png")]
    pub plot: Option<PathBuf>,
}

pub fn run(args: &MergeArgs) -> anyhow::Result<()> {
    if let Some(plot) = &args.plot
        && sweep_figure::format_of(plot).is_none()
    {
        return Err(BadInput(format!("--plot {}: the figure's name must end in .png or .svg", plot.display())).into());
    }
    let mut shards = Vec::new();
    for path in &args.shards {
        let text = std::fs::read_to_string(path)
            .map_err(|error| BadInput(format!("cannot read the shard {}: {error}", path.display())))?;
        shards.push(ShardFile { name: path.display().to_string(), text });
    }
    let csv = merge(&shards).map_err(bad)?;
    let staged = match &args.plot {
        Some(path) => Some(sweep_figure::stage(&figure::from_csv(&csv).map_err(bad)?, path)?),
        None => None,
    };
    write_atomically(&args.out, csv.as_bytes())?;
    let plotted = staged.map(|f| f.commit()).transpose()?;
    eprintln!("wrote {} ({} rows from {} shards)", args.out.display(), csv.lines().count() - 1, shards.len());
    if let Some(path) = plotted {
        eprintln!("wrote {}", path.display());
    }
    Ok(())
}
