//! `impact merge OUT.csv SHARD.csv...`: join the shards of a sweep run with `--shard I/N` into the file the whole
//! sweep would have written, byte for byte (see [`crate::sweep::merge`]).

use super::BadInput;
use super::paths::{Origin, Paths};
use super::sweep::{bad, check_map_name, check_names, check_plot_columns, figure_output, map_output};
use crate::files::OutputFile;
use crate::sweep::merge::{ShardFile, merge};
use clap::Args;
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct MergeArgs {
    /// The merged CSV to write (written completely or not at all); `-` writes it to stdout.
    pub out: PathBuf,
    /// The shard files of one sweep, in any order: every shard 1/N ... N/N exactly once.
    #[arg(required = true, value_name = "SHARD")]
    pub shards: Vec<PathBuf>,
    /// One figure file, not a folder: also draw the sweep's figure (as `impact sweep --plot`) into FILE.png or
    /// FILE.svg (the extension picks the format).
    #[arg(long, value_name = "FILE.png")]
    pub plot: Option<PathBuf>,
    /// Also draw the idealisation map (as `impact sweep --map`) into FILE.png or FILE.svg: the shards must have been
    /// written with its columns (--columns approach_speed,first_failure,first_marginal,instantaneous_ratio,...; and
    /// duration,restitution_velocity_ratio for the line of the flight between bounces; see
    /// docs/idealisation.md#the-idealisation-map).
    #[arg(long, value_name = "FILE.png")]
    pub map: Option<PathBuf>,
}

pub fn run(args: &MergeArgs) -> anyhow::Result<()> {
    check_names(&args.out, "OUT", args.plot.as_deref())?;
    check_map_name(args.map.as_deref())?;
    let mut paths = Paths::default();
    for path in &args.shards {
        paths.input(format!("the shard {} being merged", path.display()), path);
    }
    let out = paths.output(format!("OUT {}", args.out.display()), Origin::CommandLine, &args.out)?;
    let plot = match &args.plot {
        Some(path) => Some((path, paths.output(format!("--plot {}", path.display()), Origin::CommandLine, path)?)),
        None => None,
    };
    let map = match &args.map {
        Some(path) => Some((path, paths.output(format!("--map {}", path.display()), Origin::CommandLine, path)?)),
        None => None,
    };
    let mut shards = Vec::new();
    for path in &args.shards {
        let text = std::fs::read_to_string(path)
            .map_err(|error| BadInput(format!("cannot read the shard {}: {error}", path.display())))?;
        shards.push(ShardFile { name: path.display().to_string(), text });
    }
    let merged = merge(&shards).map_err(bad)?;
    if plot.is_some() {
        // Shards written with --columns may lack what the figure reads: say so before drawing.
        check_plot_columns(merged.header, "the sweep was written with --columns without it")?;
    }
    let figure = match &plot {
        Some((path, destination)) => Some(figure_output(&merged.text(), path, destination)?),
        None => None,
    };
    let drawn_map = match &map {
        Some((path, destination)) => Some(map_output(&merged.text(), path, destination)?),
        None => None,
    };
    let mut csv = OutputFile::create(&out)?;
    csv.write_bytes(merged.header.as_bytes())?;
    csv.write_bytes(b"\n")?;
    for row in &merged.rows {
        csv.write_bytes(row.as_bytes())?;
        csv.write_bytes(b"\n")?;
    }
    csv.finish()?;
    eprintln!("wrote {} ({} rows from {} shards)", out.shown(), merged.rows.len(), shards.len());
    for figure in [figure, drawn_map].into_iter().flatten() {
        let name = figure.shown().to_string();
        figure.finish()?;
        eprintln!("wrote {name}");
    }
    Ok(())
}
