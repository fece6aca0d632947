//! `impact run SCENE.toml`: simulate one scene, print its report, write the series and figures it asks for.

use super::BadInput;
use crate::history::Recording;
use crate::impact::{Simulation, simulate};
use crate::output;
use crate::scene::Scene;
use clap::Args;
use std::path::{Path, PathBuf};

#[derive(Debug, Args)]
pub struct RunArgs {
    /// The scene file (TOML, see the README).
    pub scene: PathBuf,
    /// Print the JSON report on stdout instead of the readable one.
    #[arg(long)]
    pub json: bool,
    /// Write the contact history as CSV to FILE (overrides the scene's [output] series).
    #[arg(long, value_name = "FILE")]
    pub csv: Option<PathBuf>,
    /// Resample the history at N instants evenly spaced over the contact (on the integrator's solution) instead
    /// of writing the integrator's own steps and events.
    #[arg(long, value_name = "N")]
    pub samples: Option<usize>,
    /// Write the figures (PNG and SVG) into folder DIR (overrides the scene's [output] plots).
    #[arg(long, value_name = "DIR")]
    pub plot: Option<PathBuf>,
}

/// Instants per figure curve: enough for a smooth line at the figure's width.
pub const FIGURE_SAMPLES: usize = 600;

pub fn run(args: &RunArgs) -> anyhow::Result<()> {
    if args.samples.is_some_and(|n| n < 2) {
        return Err(BadInput("--samples needs at least 2 instants".into()).into());
    }
    let scene = Scene::load(&args.scene)?;
    let series = args.csv.clone().or_else(|| scene.output.series.clone());
    let plots = args.plot.clone().or_else(|| scene.output.plots.clone());
    if args.samples.is_some() && series.is_none() {
        return Err(BadInput("--samples applies to the series: give --csv FILE (or [output] series)".into()).into());
    }
    // One simulation serves both views when it can: figures alone take a uniform history of their own size.
    let recording = match (&series, args.samples, &plots) {
        (Some(_), Some(n), _) => Recording::Uniform(n),
        (Some(_), None, _) => Recording::Steps,
        (None, _, Some(_)) => Recording::Uniform(FIGURE_SAMPLES),
        (None, _, None) => Recording::Off,
    };
    let simulation = simulate(&scene, recording)?;
    let written = write_outputs(&scene, &simulation, series.as_deref(), plots.as_deref())?;
    let text =
        if args.json { output::json::render(&simulation.report)? } else { output::table::render(&simulation.report) };
    print!("{text}");
    for path in written {
        eprintln!("wrote {}", path.display());
    }
    Ok(())
}

/// Writes the series and figures a run asks for; returns the files written.
pub fn write_outputs(
    scene: &Scene,
    simulation: &Simulation,
    series: Option<&Path>,
    plots: Option<&Path>,
) -> anyhow::Result<Vec<PathBuf>> {
    let mut written = Vec::new();
    if let (Some(path), Some(history)) = (series, &simulation.history) {
        // (The caller records a history whenever a series is asked for.)
        output::files::write_atomically(path, output::csv::render(history).as_bytes())?;
        written.push(path.to_path_buf());
    }
    if let Some(folder) = plots {
        let smooth = matches!(simulation.history.as_ref().map(|h| h.samples.len()), Some(n) if n >= FIGURE_SAMPLES);
        let resampled;
        let history = if smooth {
            simulation.history.as_ref().expect("checked above")
        } else {
            resampled = simulate(scene, Recording::Uniform(FIGURE_SAMPLES))?.history.expect("a uniform history");
            &resampled
        };
        written.extend(output::figures::write_all(&simulation.report, history, folder)?);
    }
    Ok(written)
}
