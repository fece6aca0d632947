//! `impact bench [--quick] [--out DIR]`: the work–precision study ([`crate::bench`]). Writes `DIR/bench.csv`
//! (one row per method, setting and case) and the figure `DIR/bench.png` and `DIR/bench.svg` (the largest error
//! over the cases against the median time per impact, one line per method); prints the machine, a summary per
//! method and setting, and the fast path's targets. Runs on one thread; timings are medians over batches.

use super::BadInput;
use super::paths::{Origin, Paths};
use crate::bench::{self, Method, Setting};
use crate::files::{Destination, OutputFile, figure_folder_problem};
use crate::output::bench_figure::{self, BenchFigure, Curve};
use crate::output::render;
use anyhow::Context;
use clap::Args;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::path::PathBuf;

/// The files the study writes into its folder.
const OUTPUTS: [&str; 3] = ["bench.csv", "bench.png", "bench.svg"];

/// The files the world study (`--worlds`) writes into its folder.
const WORLD_OUTPUTS: [&str; 3] = ["bench-worlds.csv", "bench-worlds.png", "bench-worlds.svg"];

/// The file the oblique study (`--oblique`) writes into its folder.
const OBLIQUE_OUTPUTS: [&str; 1] = ["bench-oblique.csv"];

#[derive(Debug, Args)]
pub struct BenchArgs {
    /// A short run: four cases (one per law family), a few settings per method, fewer repeats.
    #[arg(long)]
    pub quick: bool,
    /// Folder for bench.csv, bench.png and bench.svg (created if missing).
    #[arg(long, value_name = "DIR", default_value = "out/bench")]
    pub out: PathBuf,
    /// Only the cases whose name contains TEXT (repeatable; names as in the CSV, e.g. "hunt-crossley x=0.5 n=1.5").
    #[arg(long = "case", value_name = "TEXT")]
    pub cases: Vec<String>,
    /// World runs instead of single impacts: a Hertzian chain of 1000 beads struck at one end (100 with --quick),
    /// the 5-ball cradle and a rod's chatter at a sweep of tolerances, each against a run at 1e-13, and 20 balls
    /// settling into a pile for 2 s (its first 0.3 s with --quick), by its energy balance (bench-worlds.csv, .png,
    /// .svg).
    #[arg(long)]
    pub worlds: bool,
    /// Frictional oblique impacts instead: Chung & Ooi's test 4 at 45, 10 and 30 degrees (with spin), a Hunt–Crossley
    /// wall at 60 degrees and two free spheres with and without spin, at a sweep of tolerances against a run at 1e-13,
    /// beside the same contacts without friction (bench-oblique.csv).
    #[arg(long, conflicts_with = "worlds")]
    pub oblique: bool,
}

pub fn run(args: &BenchArgs) -> anyhow::Result<()> {
    check_folder(args)?;
    if args.worlds && !args.cases.is_empty() {
        return Err(BadInput("--case selects the single-impact cases; --worlds runs its scenes whole".into()).into());
    }
    if args.oblique && !args.cases.is_empty() {
        return Err(BadInput("--case selects the single-impact cases; --oblique runs its own cases".into()).into());
    }
    let names: &[&str] = if args.worlds {
        &WORLD_OUTPUTS
    } else if args.oblique {
        &OBLIQUE_OUTPUTS
    } else {
        &OUTPUTS
    };
    let mut paths = Paths::default();
    let outputs: Vec<Destination> = names
        .iter()
        .map(|&name| {
            let path = args.out.join(name);
            let label = format!("--out {} ({})", args.out.display(), path.display());
            paths.output(label, Origin::CommandLine, &path)
        })
        .collect::<anyhow::Result<_>>()?;
    if args.worlds {
        worlds(args, outputs)
    } else if args.oblique {
        oblique(args, outputs)
    } else {
        study(args, outputs)
    }
}

/// The oblique study (`--oblique`) into `outputs` ([`OBLIQUE_OUTPUTS`]).
fn oblique(args: &BenchArgs, outputs: Vec<Destination>) -> anyhow::Result<()> {
    use crate::bench::oblique;
    let cases = oblique::cases();
    let tolerances: &[f64] = if args.quick { &oblique::QUICK_TOLERANCES } else { &oblique::TOLERANCES };
    let timing = if args.quick { bench::Timing::QUICK } else { bench::Timing::FULL };
    let machine = bench::machine();
    let paths: usize = cases.iter().map(|(case, _)| 3 + usize::from(case.central.is_some())).sum();
    let bar = progress(paths * tolerances.len());
    let rows = oblique::study(&cases, tolerances, timing, |row| {
        bar.set_message(format!("{} at {:e}", row.case, row.tolerance));
        bar.inc(1);
    })
    .map_err(|why| anyhow::anyhow!("impact bench --oblique: {why}"))?;
    bar.finish_and_clear();
    let csv = oblique::csv(&rows);
    let mut file = OutputFile::create(&outputs[0])?;
    file.write_bytes(csv.as_bytes())?;
    file.finish()?;
    println!("machine: {machine} (at the start); load average at the end {}", bench::load_average());
    println!(
        "error: the largest difference of a velocity or a spin times its radius after the impact from a run at \
         tolerance {:e}, over the approach speed\n",
        oblique::REFERENCE_TOLERANCE
    );
    print!("{}", oblique::table(&rows));
    println!("\nwrote {}", outputs[0].shown());
    Ok(())
}

/// A progress bar of `len` steps on standard error (drawn only on a terminal).
fn progress(len: usize) -> ProgressBar {
    let bar = ProgressBar::with_draw_target(Some(len as u64), ProgressDrawTarget::stderr_with_hz(4));
    bar.set_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} {msg}").unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    bar
}

/// Refuses an --out that cannot take the study's files.
fn check_folder(args: &BenchArgs) -> anyhow::Result<()> {
    if let Some(why) = figure_folder_problem(&args.out) {
        return Err(BadInput(format!("--out {}: {why}", args.out.display())).into());
    }
    // The outputs, checked by the rules of every verb before any work: a folder (or one to be made), three files.
    if let Ok(meta) = std::fs::metadata(&args.out)
        && !meta.is_dir()
    {
        return Err(BadInput(format!(
            "--out {} is an existing file, not a folder: the study's CSV and figures need a folder to be written into",
            args.out.display()
        ))
        .into());
    }
    Ok(())
}

/// The single-impact study into `outputs` (in the order of [`OUTPUTS`]).
fn study(args: &BenchArgs, outputs: Vec<Destination>) -> anyhow::Result<()> {
    let all = if args.quick { bench::quick_cases() } else { bench::reference_cases() };
    let names: Vec<String> = all.iter().map(|c| c.name()).collect();
    let cases: Vec<_> = all
        .into_iter()
        .filter(|case| args.cases.is_empty() || args.cases.iter().any(|text| case.name().contains(text.as_str())))
        .collect();
    if cases.is_empty() {
        let which = if args.quick { "the cases of --quick" } else { "the cases" };
        return Err(BadInput(format!("--case: no case matches; {which} are: {}", names.join(", "))).into());
    }
    let plan = bench::settings(args.quick);
    let timing = if args.quick { bench::Timing::QUICK } else { bench::Timing::FULL };
    let machine = bench::machine();
    let bar = progress(cases.len() * plan.len());
    let rows = bench::study(&cases, &plan, timing, |row| {
        bar.set_message(format!("{} {}", row.method.name(), row.setting));
        if let Some(why) = &row.failure {
            bar.suspend(|| eprintln!("impact bench: {} {} on {}: {why}", row.method.name(), row.setting, row.case));
        }
        bar.inc(1);
    });
    bar.finish_and_clear();
    let summaries = bench::summarise(&rows);
    let figure = BenchFigure {
        title: format!("Work–precision of one impact: {} reference impacts with exact answers", cases.len()),
        x_label: "median time per impact over the cases (s, one core)".into(),
        y_label: "largest relative error over the cases and quantities".into(),
        curves: Method::ALL
            .iter()
            .filter(|m| summaries.iter().any(|s| s.method == **m))
            .map(|&method| {
                let own: Vec<_> = summaries.iter().filter(|s| s.method == method).collect();
                let settings: Vec<Setting> = own.iter().map(|s| s.setting).collect();
                Curve {
                    label: format!("{}, {}", method.label(), Setting::range(&settings)),
                    points: own.iter().map(|s| (s.median_seconds, s.error)).collect(),
                }
            })
            .collect(),
    };
    let svg = bench_figure::svg(&figure);
    let png = render::png(&svg).context("cannot render bench.png")?;
    let csv = bench::csv(&rows);
    write_all(&outputs, [csv.as_bytes(), png.as_slice(), svg.as_bytes()])?;
    println!("machine: {machine} (at the start); load average at the end {}", bench::load_average());
    println!("cases: {}\n", cases.iter().map(|c| c.name()).collect::<Vec<_>>().join(", "));
    print!("{}", bench::summary_table(&summaries));
    if summaries.iter().any(|s| s.method == Method::Taylor && matches!(s.setting, Setting::Tolerance(_))) {
        println!("\nthe fast path's targets, over these cases:");
        print!("{}", bench::targets(&summaries));
    }
    println!("\nwrote {}", outputs.iter().map(|d| d.shown().to_string()).collect::<Vec<_>>().join(", "));
    Ok(())
}

/// Writes `contents` to `outputs` (CSV, PNG, SVG): all three or none — each to its temporary first, and only then
/// are they moved into place.
fn write_all(outputs: &[Destination], contents: [&[u8]; 3]) -> anyhow::Result<()> {
    let mut pending = Vec::new();
    for (destination, bytes) in outputs.iter().zip(contents) {
        let mut file = OutputFile::create(destination)?;
        file.write_bytes(bytes)?;
        pending.push(file);
    }
    for file in pending {
        file.finish()?;
    }
    Ok(())
}

/// The world study (`--worlds`) into `outputs` (in the order of [`WORLD_OUTPUTS`]): its cases at a
/// sweep of tolerances.
fn worlds(args: &BenchArgs, outputs: Vec<Destination>) -> anyhow::Result<()> {
    use crate::bench::worlds;
    let cases = worlds::cases(args.quick);
    let tolerances: &[f64] = if args.quick { &worlds::QUICK_TOLERANCES } else { &worlds::TOLERANCES };
    let machine = bench::machine();
    let bar = progress(cases.len() * tolerances.len());
    let rows = worlds::study(&cases, tolerances, |row| {
        bar.set_message(format!("{} at {:e}", row.case, row.tolerance));
        bar.inc(1);
    })
    .map_err(|why| anyhow::anyhow!("impact bench --worlds: {why}"))?;
    bar.finish_and_clear();
    let figure = BenchFigure {
        title: "Work–precision of world runs (errors against a run at 1e-13; the pile's, its energy residual)".into(),
        x_label: "time of the run (s, one core)".into(),
        y_label: "velocity error / v0 (pile: energy residual / energy in)".into(),
        curves: cases
            .iter()
            .map(|case| {
                let own: Vec<_> = rows.iter().filter(|r| r.case == case.name).collect();
                Curve {
                    label: format!(
                        "{}, tolerance {:e} to {:e}",
                        case.name,
                        tolerances[0],
                        tolerances[tolerances.len() - 1]
                    ),
                    points: own.iter().map(|r| (r.seconds, r.error)).collect(),
                }
            })
            .collect(),
    };
    let svg = bench_figure::svg(&figure);
    let png = render::png(&svg).context("cannot render bench-worlds.png")?;
    let csv = worlds::csv(&rows);
    write_all(&outputs, [csv.as_bytes(), png.as_slice(), svg.as_bytes()])?;
    println!("machine: {machine} (at the start); load average at the end {}", bench::load_average());
    println!("{:<14} {:>10} {:>10} {:>10} {:>8} {:>9}", "case", "tolerance", "error", "seconds", "steps", "contacts");
    for r in &rows {
        println!(
            "{:<14} {:>10.0e} {:>10.2e} {:>10.4} {:>8} {:>9}",
            r.case, r.tolerance, r.error, r.seconds, r.steps, r.contacts
        );
    }
    println!("\nwrote {}", outputs.iter().map(|d| d.shown().to_string()).collect::<Vec<_>>().join(", "));
    Ok(())
}
