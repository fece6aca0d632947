//! `impact sweep SCENE.toml --vary KEY=START:STOP:COUNT [--vary ...] [--law a,b,c] --out FILE.csv`: run a scene
//! over a grid of values (and laws), in parallel, one CSV row per point and law (see [`crate::sweep`]).

use super::BadInput;
use super::paths::{Origin, Paths};
use crate::files::{self, Destination, OutputFile, Staging};
use crate::output::sweep_figure;
use crate::scene::SceneError;
use crate::sweep::shard::Shard;
use crate::sweep::table::{self, Status};
use crate::sweep::{self as sweeps, Lines, Sweep, SweepError};
use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use std::path::{Path, PathBuf};

#[derive(Debug, Args)]
#[command(after_help = "Rows come in a fixed order: points in lexicographic order of the grid (the first --vary \
    slowest), and for each point the laws in --law order. A point a law cannot take is a row whose status says why. \
    Setting contact.restitution removes contact.damping and vice versa (likewise bodies.I.mass and \
    bodies.I.density). With --law, each law's own defaults are re-derived (see the README). The CSV is the same \
    whatever the number of threads; `impact merge` joins the shards of --shard into the whole file, byte for byte.")]
pub struct SweepArgs {
    /// The scene file (TOML, see docs/scene.md); it may leave out what the sweep sets.
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
    /// Write only these result columns (comma-separated, in this order; see docs/report.md for the 41 names and the
    /// 18 verdict columns) after index, status, law and the varied keys. Each row then computes only what they show:
    /// e alone (restitution_velocity_ratio) skips the contact's times, its force peak, the dissipated energy and the
    /// exact reference; only a verdict column (first_failure, elastic_ratio, ...) makes a row judge the idealisation.
    /// Default: the 41 result columns, without the verdicts.
    #[arg(long, value_name = "NAME,NAME,...", value_delimiter = ',')]
    pub columns: Vec<String>,
    /// The CSV file to write (written completely or not at all); `-` writes it to stdout.
    #[arg(long, value_name = "FILE.csv")]
    pub out: PathBuf,
    /// One figure file, not a folder: also draw effective e against the first varied key, one line per law, into
    /// FILE.png or FILE.svg (the extension picks the format); for a sweep over bodies.I.incidence_deg, the tangential
    /// restitution, rebound spin and rebound angle against it, simulated and by rigid-body theory. `impact run
    /// --plot` is the one that takes a folder.
    #[arg(long, value_name = "FILE.png")]
    pub plot: Option<PathBuf>,
    /// The idealisation map, into FILE.png or FILE.svg: over the two varied keys (exactly two --vary: x, then y),
    /// each cell coloured by the first assumption of the instantaneous impact that fails there, with the line where
    /// each one starts to fail (docs/idealisation.md#the-idealisation-map). Adds the verdict columns to the CSV: each
    /// row then judges the idealisation (two more runs of its contact).
    #[arg(long, value_name = "FILE.png")]
    pub map: Option<PathBuf>,
    /// Compute only shard I of N (1 <= I <= N): the rows whose index is I-1 modulo N, for a job array; join the
    /// shard files with `impact merge`.
    #[arg(long, value_name = "I/N")]
    pub shard: Option<String>,
    /// Number of worker threads computing rows (default: one per core; one more thread writes the CSV). The CSV does
    /// not depend on it.
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

use crate::sweep::MAX_THREADS;

pub fn run(args: &SweepArgs) -> anyhow::Result<()> {
    let shard = args.shard.as_deref().map(Shard::parse).transpose().map_err(bad)?;
    if let Some(threads) = args.threads
        && !(1..=MAX_THREADS).contains(&threads)
    {
        return Err(BadInput(format!("--threads must be between 1 and {MAX_THREADS}, got {threads}")).into());
    }
    check_names(&args.out, "--out", args.plot.as_deref())?;
    check_map_name(args.map.as_deref())?;
    if args.plot.is_some() && shard.is_some() {
        return Err(BadInput(
            "--plot draws the whole sweep: leave it out of the shards and give it to `impact merge`".into(),
        )
        .into());
    }
    if args.map.is_some() && shard.is_some() {
        return Err(BadInput(
            "--map draws the whole sweep: leave it out of the shards (write their verdict columns with --columns) and \
             give it to `impact merge`"
                .into(),
        )
        .into());
    }
    let text = std::fs::read_to_string(&args.scene)
        .map_err(|error| SceneError::file(&args.scene, format!("cannot read the scene: {error}")))?;
    if crate::scene::is_world(&text) {
        return world(args, &text);
    }
    let mut sweep =
        Sweep::from_arguments(&args.scene, text, &args.vary, args.log, &args.law, &args.columns).map_err(bad)?;
    if args.map.is_some() {
        sweeps::map::check(sweep.grid.axes.len(), sweep.laws.len()).map_err(bad)?;
    }
    let mut paths = Paths::default();
    paths.input(format!("the scene file {} being read", args.scene.display()), &args.scene);
    let out = paths.output(format!("--out {}", args.out.display()), Origin::CommandLine, &args.out)?;
    let plot = match &args.plot {
        Some(path) => Some((path, paths.output(format!("--plot {}", path.display()), Origin::CommandLine, path)?)),
        None => None,
    };
    let map = match &args.map {
        Some(path) => Some((path, paths.output(format!("--map {}", path.display()), Origin::CommandLine, path)?)),
        None => None,
    };
    if map.is_some() {
        // The map reads the verdicts from the CSV: they are added to its columns (and computed for its rows only).
        let mut columns = sweep.columns().clone();
        columns.add(&sweeps::map::columns());
        sweep.select(columns);
    }
    let header = table::header(&sweep.keys(), sweep.columns());
    if args.plot.is_some() {
        // The figure reads its columns from the CSV: check that they will be there before any row runs.
        check_plot_columns(&header, "add it to --columns")?;
    }
    let pool = rayon::ThreadPoolBuilder::new().num_threads(args.threads.unwrap_or(0)).build()?;

    let total = sweep.rows();
    let indices = sweep.indices(shard);
    let bar = ProgressBar::new(indices.len() as u64);
    if let Ok(style) = ProgressStyle::with_template("{wide_bar} {pos}/{len} rows, {elapsed} elapsed, ETA {eta}") {
        bar.set_style(style);
    }
    // Rows stream into the output (a temporary file for a regular file) in index order as they are computed; the
    // figure needs the whole table, so only then is the CSV kept in memory too.
    let mut csv = OutputFile::create(&out)?;
    let mut kept = (plot.is_some() || map.is_some()).then(String::new);
    let mut put = |text: &str| {
        if let Some(kept) = &mut kept {
            kept.push_str(text);
        }
        csv.write_bytes(text.as_bytes())
    };
    if let Some(shard) = shard {
        put(&table::shard_comment(shard, total, sweep.fingerprint()))?;
    }
    put(&(header + "\n"))?;
    let mut tally = Tally::default();
    sweep.stream_lines(
        indices,
        &pool,
        |rows| bar.inc(rows as u64),
        |lines| {
            tally.add(&lines);
            put(&lines.text)
        },
    )?;
    bar.finish_and_clear();

    // The figure is drawn before the CSV is moved into place, so that a failure to draw it leaves no CSV either.
    let figure = match (&plot, &kept) {
        (Some((path, destination)), Some(text)) => Some(figure_output(text, path, destination)?),
        _ => None,
    };
    let drawn_map = match (&map, &kept) {
        (Some((path, destination)), Some(text)) => Some(map_output(text, path, destination)?),
        _ => None,
    };
    csv.finish()?;
    let mut plotted = Vec::new();
    for figure in [figure, drawn_map].into_iter().flatten() {
        plotted.push(figure.shown().to_string());
        figure.finish()?;
    }

    let part = shard.map(|s| format!(", shard {s} of {total} rows")).unwrap_or_default();
    let Tally { rows, ok, stuck, first } = tally;
    eprintln!(
        "wrote {} ({rows} rows{part}: {ok} ok, {stuck} not separated, {} errors)",
        out.shown(),
        rows - ok - stuck
    );
    for name in plotted {
        eprintln!("wrote {name}");
    }
    if let Some(first) = first
        && ok + stuck == 0
    {
        eprintln!("note: no row ran; the first says: {first}");
    }
    Ok(())
}

/// The sweep of a world scene (docs/world.md#sweeps): its rows stream into `--out` in index order.
fn world(args: &SweepArgs, text: &str) -> anyhow::Result<()> {
    for (given, option) in [
        (!args.law.is_empty(), "--law"),
        (args.shard.is_some(), "--shard"),
        (args.plot.is_some(), "--plot"),
        (args.map.is_some(), "--map"),
    ] {
        if given {
            return Err(BadInput(format!("{option} is not taken by a sweep of a world scene (yet)")).into());
        }
    }
    let sweep = crate::sweep::world::WorldSweep::from_arguments(&args.scene, text, &args.vary, args.log, &args.columns)
        .map_err(bad)?;
    let mut paths = Paths::default();
    paths.input(format!("the scene file {} being read", args.scene.display()), &args.scene);
    let out = paths.output(format!("--out {}", args.out.display()), Origin::CommandLine, &args.out)?;
    let pool = rayon::ThreadPoolBuilder::new().num_threads(args.threads.unwrap_or(0)).build()?;
    let bar = ProgressBar::new(sweep.rows() as u64);
    if let Ok(style) = ProgressStyle::with_template("{wide_bar} {pos}/{len} rows, {elapsed} elapsed, ETA {eta}") {
        bar.set_style(style);
    }
    let mut csv = OutputFile::create(&out)?;
    csv.write_bytes((sweep.header() + "\n").as_bytes())?;
    let (mut rows, mut ok, mut stopped) = (0usize, 0usize, 0usize);
    sweep.stream(
        (0..sweep.rows()).collect(),
        &pool,
        |done| bar.inc(done as u64),
        |row| {
            rows += 1;
            ok += usize::from(row.ok);
            stopped += usize::from(row.stopped);
            csv.write_bytes(row.line.as_bytes())
        },
    )?;
    bar.finish_and_clear();
    csv.finish()?;
    let budget = if stopped > 0 { format!(", {stopped} stopped by their step budget") } else { String::new() };
    eprintln!("wrote {} ({rows} rows: {ok} ok{budget}, {} errors)", out.shown(), rows - ok - stopped);
    Ok(())
}

/// How the rows of a sweep ended, counted as they stream past.
#[derive(Default)]
struct Tally {
    rows: usize,
    ok: usize,
    stuck: usize,
    /// The first row's status.
    first: Option<String>,
}

impl Tally {
    fn add(&mut self, lines: &Lines) {
        self.rows += lines.rows;
        self.ok += lines.ok;
        self.stuck += lines.stuck;
        if self.first.is_none() {
            self.first = lines.first.as_ref().map(Status::text);
        }
    }
}

/// Checks the names of a CSV output (option `option`) and of a sweep figure before any work: the CSV must name a
/// file (or `-`), the figure a `.png` or `.svg` file (not standard output).
pub(super) fn check_names(csv: &Path, option: &str, plot: Option<&Path>) -> anyhow::Result<()> {
    if let Some(why) = files::file_name_problem(csv) {
        return Err(BadInput(format!("{option} {}: {why}", csv.display())).into());
    }
    if let Some(plot) = plot {
        if plot.as_os_str() == "-" {
            return Err(
                BadInput("--plot -: a figure cannot go to standard output; give FILE.png or FILE.svg".into()).into()
            );
        }
        if sweep_figure::format_of(plot).is_none() || files::file_name_problem(plot).is_some() {
            return Err(
                BadInput(format!("--plot {}: the figure's name must end in .png or .svg", plot.display())).into()
            );
        }
    }
    Ok(())
}

/// Checks the name of the idealisation map (`--map`) before any work: a `.png` or `.svg` file.
pub(super) fn check_map_name(map: Option<&Path>) -> anyhow::Result<()> {
    match map {
        Some(map) if sweep_figure::format_of(map).is_none() || files::file_name_problem(map).is_some() => {
            Err(BadInput(format!("--map {}: the figure's name must end in .png or .svg", map.display())).into())
        }
        _ => Ok(()),
    }
}

/// Whether a sweep's CSV whose header line is `header` has the columns its figure reads; the error (bad input)
/// names the first missing one, followed by `hint`.
pub(super) fn check_plot_columns(header: &str, hint: &str) -> anyhow::Result<()> {
    sweeps::figure::check_columns(header).map_err(|error| match error {
        SweepError::Usage(why) => BadInput(format!("--plot: {why}; {hint}")).into(),
        other => bad(other),
    })
}

/// The sweep's figure, drawn from its CSV `text` in a staging folder beside `path` and copied to `destination`;
/// unfinished, so that the caller shows it only with its CSV.
pub(super) fn figure_output(text: &str, path: &Path, destination: &Destination) -> anyhow::Result<OutputFile> {
    stage_output(&sweeps::figure::plot_from_csv(text).map_err(bad)?, path, destination)
}

/// The sweep's idealisation map, drawn from its CSV `text` as [`figure_output`] draws its figure.
pub(super) fn map_output(text: &str, path: &Path, destination: &Destination) -> anyhow::Result<OutputFile> {
    let map = sweeps::map::from_csv(text).map_err(bad)?;
    stage_output(&sweep_figure::SweepPlot::Map(map), path, destination)
}

/// A figure staged beside `path` and copied to `destination`, unfinished.
fn stage_output(
    figure: &sweep_figure::SweepPlot,
    path: &Path,
    destination: &Destination,
) -> anyhow::Result<OutputFile> {
    let folder = path.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    let staging = Staging::inside(folder)?;
    // The staged file keeps the figure's name: its extension picks the format.
    let name = path.file_name().unwrap_or_default();
    let staged = sweep_figure::stage(figure, &staging.path().join(name))?.commit()?;
    Ok(staging.publish(&staged, destination)?)
}
