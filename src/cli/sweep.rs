//! `impact sweep SCENE.toml --vary KEY=START:STOP:COUNT [--vary ...] [--law a,b,c] --out FILE.csv`: run a scene
//! over a grid of values (and laws), in parallel, one CSV row per point and law (see [`crate::sweep`]).

use super::BadInput;
use crate::output::files::write_atomically;
use crate::output::sweep_figure;
use crate::scene::SceneError;
use crate::sweep::grid::{Axis, Grid, Spacing};
use crate::sweep::shard::Shard;
use crate::sweep::table::{self, Status};
use crate::sweep::{self as sweeps, Sweep, SweepError};
use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use std::path::PathBuf;

#[derive(Debug, Args)]
#[command(after_help = "Rows come in a fixed order: points in lexicographic order of the grid (the first --vary \
    slowest), and for each point the laws in --law order. A point a law cannot take is a row whose status says why. \
    Setting contact.restitution removes contact.damping and vice versa (likewise bodies.I.mass and \
    bodies.I.density). With --law, each law's own defaults are re-derived (see the README). The CSV is the same \
    whatever the number of threads; `impact merge` joins the shards of --shard into the whole file, byte for byte.")]
pub struct SweepArgs {
    /// The scene file (TOML, see the README); it may leave out what the sweep sets.
    pub scene: PathBuf,
    /// A varied scene number and its values: KEY=START:STOP:COUNT (COUNT values, both ends included; add :log for
    /// geometric spacing or :lin for even spacing), or KEY=V1,V2,... (these values). KEY is a dotted scene key with
    /// 0-based indices: contact.restitution, contact.damping, contact.exponent, contact.stiffness, bodies.1.mass,
    /// bodies.1.velocity.0 (the second body's x velocity), ... Repeat for a grid.
    #[arg(long = "vary", value_name = "KEY=START:STOP:COUNT", required = true)]
    pub vary: Vec<String>,
    /// Geometric spacing for every START:STOP:COUNT range (unless it ends in :lin).
    #[arg(long)]
    pub log: bool,
    /// Run each point under each of these laws (comma-separated, in this order), re-deriving each law's defaults;
    /// without it, the scene's own law.
    #[arg(long, value_name = "LAW,LAW,...", value_delimiter = ',')]
    pub law: Vec<String>,
    /// The CSV file to write (written completely or not at all).
    #[arg(long, value_name = "FILE.csv")]
    pub out: PathBuf,
    /// Also draw effective e against the first varied key, one line per law (PNG or SVG by the extension).
    #[arg(long, value_name = "FILE.png")]
    pub plot: Option<PathBuf>,
    /// Compute only shard I of N (1 <= I <= N): the rows whose index is I-1 modulo N, for a job array; join the
    /// shard files with `impact merge`.
    #[arg(long, value_name = "I/N")]
    pub shard: Option<String>,
    /// Number of threads (default: one per core). The CSV does not depend on it.
    #[arg(long, value_name = "N")]
    pub threads: Option<usize>,
}

/// A sweep error as the command reports it: bad input exits with status 2.
pub(super) fn bad(error: SweepError) -> anyhow::Error {
    match error {
        SweepError::Usage(message) => BadInput(message).into(),
        SweepError::Scene(error) => error.into(),
    }
}

/// More threads than this only add start-up cost (a machine of this project's kind has 2 cores).
const MAX_THREADS: usize = 256;

pub fn run(args: &SweepArgs) -> anyhow::Result<()> {
    let shard = args.shard.as_deref().map(Shard::parse).transpose().map_err(bad)?;
    if let Some(threads) = args.threads
        && !(1..=MAX_THREADS).contains(&threads)
    {
        return Err(BadInput(format!("--threads must be between 1 and {MAX_THREADS}, got {threads}")).into());
    }
    if let Some(plot) = &args.plot {
        if sweep_figure::format_of(plot).is_none() {
            return Err(
                BadInput(format!("--plot {}: the figure's name must end in .png or .svg", plot.display())).into()
            );
        }
        if shard.is_some() {
            return Err(BadInput(
                "--plot draws the whole sweep: leave it out of the shards and give it to `impact merge`".into(),
            )
            .into());
        }
    }
    let laws = sweeps::parse_laws(&args.law).map_err(bad)?;
    let spacing = if args.log { Spacing::Geometric } else { Spacing::Linear };
    let axes = args.vary.iter().map(|spec| Axis::parse(spec, spacing)).collect::<Result<Vec<_>, _>>().map_err(bad)?;
    let grid = Grid::new(axes).map_err(bad)?;
    let text = std::fs::read_to_string(&args.scene)
        .map_err(|error| SceneError::file(&args.scene, format!("cannot read the scene: {error}")))?;
    let sweep = Sweep::new(&args.scene, text, grid, laws).map_err(bad)?;

    let total = sweep.rows();
    let indices: Vec<usize> = (0..total).filter(|&i| shard.is_none_or(|s| s.takes(i))).collect();
    let bar = ProgressBar::new(indices.len() as u64);
    if let Ok(style) = ProgressStyle::with_template("{wide_bar} {pos}/{len} rows, {elapsed} elapsed, ETA {eta}") {
        bar.set_style(style);
    }
    let rows = sweep.run(&indices, args.threads, || bar.inc(1))?;
    bar.finish_and_clear();

    let csv = table::render(&sweep.keys(), &rows, shard.map(|s| (s, total, sweep.fingerprint())));
    // The figure is staged first, so that a failure to draw it leaves no CSV either.
    let figure = match &args.plot {
        Some(path) => Some(sweep_figure::stage(&sweeps::figure::from_csv(&csv).map_err(bad)?, path)?),
        None => None,
    };
    write_atomically(&args.out, csv.as_bytes())?;
    let plotted = figure.map(|f| f.commit()).transpose()?;

    let count = |wanted: fn(&Status) -> bool| rows.iter().filter(|row| wanted(&row.status)).count();
    let (ok, stuck) = (count(|s| *s == Status::Ok), count(|s| *s == Status::NotSeparated));
    let part = shard.map(|s| format!(", shard {s} of {total} rows")).unwrap_or_default();
    eprintln!(
        "wrote {} ({} rows{part}: {ok} ok, {stuck} not separated, {} errors)",
        args.out.display(),
        rows.len(),
        rows.len() - ok - stuck
    );
    if let Some(path) = plotted {
        eprintln!("wrote {}", path.display());
    }
    if let Some(first) = rows.first()
        && ok + stuck == 0
    {
        eprintln!("note: no row ran; the first says: {}", first.status.text());
    }
    Ok(())
}
