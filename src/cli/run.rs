//! `impact run SCENE.toml`: simulate one scene, print its report, write the series and figures it asks for.

use super::BadInput;
use super::paths::{Origin, Paths};
use crate::files::{self, Destination, OutputFile, Staging};
use crate::history::Recording;
use crate::impact::{Simulation, SimulationError, simulate};
use crate::output;
use crate::scene::{OutputSpec, Parsed, Scene, WorldScene};
use clap::Args;
use std::path::{Path, PathBuf};

#[derive(Debug, Args)]
pub struct RunArgs {
    /// The scene file (TOML; every key is described in docs/scene.md).
    pub scene: PathBuf,
    /// Print the JSON report on stdout instead of the readable one.
    #[arg(long)]
    pub json: bool,
    /// Write the series as CSV to FILE (overrides the scene's [output] series): one impact's contact history; a
    /// world's every body's position and velocity and every active contact's force, over the whole run
    /// (docs/report.md). `-` writes it to stdout (the readable report then goes to stderr).
    #[arg(long, value_name = "FILE")]
    pub csv: Option<PathBuf>,
    /// Resample one impact's history at N instants evenly spaced over the contact (on the integrator's solution)
    /// instead of writing the integrator's own steps and events; at most 1000000. Not for a world.
    #[arg(long, value_name = "N")]
    pub samples: Option<u64>,
    /// A folder, not a file name: write the figures, each as PNG and SVG, into folder DIR, creating it if needed
    /// (overrides the scene's [output] plots): one impact's force_time, force_penetration and velocities; a world's
    /// contact_forces, velocities and, under gravity, heights. A name ending in .png or .svg is refused; `impact
    /// sweep --plot` is the one that takes a single figure file.
    #[arg(long, value_name = "DIR")]
    pub plot: Option<PathBuf>,
}

pub use crate::impact::FIGURE_SAMPLES;

/// Most instants `--samples` may ask for. A million is far beyond what a figure or a quadrature of one contact
/// needs (the integrator itself takes a few hundred steps), and each instant costs about 0.3 kB while the series
/// is built and written (a million: 290 MB at the peak, a 185 MB file), so the limit keeps a run within reach of
/// any machine.
pub const MAX_SAMPLES: u64 = 1_000_000;

pub fn run(args: &RunArgs) -> anyhow::Result<()> {
    // Checked before anything is read or allocated.
    let samples = match args.samples {
        Some(n) if n < 2 => return Err(BadInput("--samples needs at least 2 instants".into()).into()),
        Some(n) if n > MAX_SAMPLES => {
            return Err(BadInput(format!("--samples {n}: at most {MAX_SAMPLES} instants")).into());
        }
        // At most MAX_SAMPLES, so it fits a usize.
        Some(n) => Some(n as usize),
        None => None,
    };
    if let Some(path) = &args.csv
        && let Some(why) = files::file_name_problem(path)
    {
        return Err(BadInput(format!("--csv {}: {why}", path.display())).into());
    }
    if let Some(path) = &args.plot
        && let Some(why) = files::figure_folder_problem(path)
    {
        return Err(BadInput(format!("--plot {}: {why}", path.display())).into());
    }
    let scene = match crate::setup::load_any(&args.scene)? {
        Parsed::Impact(scene) => *scene,
        Parsed::World(world) => return run_world(args, &world),
    };
    if samples.is_some() && args.csv.is_none() && scene.output.series.is_none() {
        return Err(BadInput("--samples applies to the series: give --csv FILE (or [output] series)".into()).into());
    }
    let plan = Plan::new(args, &scene.output, &output::figures::FIGURES)?;
    // One simulation serves both views when it can: figures alone take a uniform history of their own size.
    let recording = match (&plan.series, samples, &plan.figures) {
        (Some(_), Some(n), _) => Recording::Uniform(n),
        (Some(_), None, _) => Recording::Steps,
        (None, _, Some(_)) => Recording::Uniform(FIGURE_SAMPLES),
        (None, _, None) => Recording::Off,
    };
    // A scene rule that only the run can check (a fixed step against the contact's duration) is located in the file.
    let simulation = simulate(&scene, recording).map_err(|error| match error {
        SimulationError::Setup(error) => anyhow::Error::new(crate::scene::located(&args.scene, error)),
        other => anyhow::Error::new(other),
    })?;
    let written = write_outputs(&scene, &simulation, &plan)?;
    let text =
        if args.json { output::json::render(&simulation.report)? } else { output::table::render(&simulation.report) };
    // With the series on standard output, the readable report goes to standard error, so stdout is pure CSV.
    if plan.series.as_ref().is_some_and(Destination::is_standard_output) {
        eprint!("{text}");
    } else {
        print!("{text}");
    }
    for name in written {
        eprintln!("wrote {name}");
    }
    // An integration that gave up did not finish the impact: its report and outputs, complete up to where it
    // stopped, are written, and the status says so (exit 1), as a world run's spent budget does.
    if let Some(reason) = &simulation.report.solver.gave_up {
        std::io::Write::flush(&mut std::io::stdout())?;
        anyhow::bail!(
            "{}: the integration gave up before the bodies separated ({reason}): the report above stops there",
            args.scene.display()
        );
    }
    Ok(())
}

/// Where a run writes, resolved and checked before it simulates.
pub struct Plan {
    pub series: Option<Destination>,
    pub figures: Option<Figures>,
}

/// The figure files of a run: the folder, and each figure's destination by file name.
pub struct Figures {
    pub folder: PathBuf,
    pub files: Vec<(String, Destination)>,
}

impl Plan {
    /// The series and figures of `impact run`: from the options, else from the scene's `[output]`, checked against
    /// the scene file and each other (see [`super::paths`]).
    fn new(args: &RunArgs, output: &OutputSpec, stems: &[&str]) -> anyhow::Result<Plan> {
        let at = |key, line| Origin::Scene { file: args.scene.clone(), key, line };
        let series = match (&args.csv, &output.series) {
            (Some(path), _) => Some((path.clone(), Origin::CommandLine, format!("--csv {}", path.display()))),
            (None, Some(path)) => {
                Some((path.clone(), at("output.series", output.series_line), format!("the series {}", path.display())))
            }
            (None, None) => None,
        };
        let plots = match (&args.plot, &output.plots) {
            (Some(path), _) => Some((path.clone(), Origin::CommandLine, "--plot")),
            (None, Some(path)) => Some((path.clone(), at("output.plots", output.plots_line), "the plots folder")),
            (None, None) => None,
        };
        let mut paths = Paths::default();
        paths.input(format!("the scene file {} being read", args.scene.display()), &args.scene);
        if args.json {
            paths.standard_output("the JSON report (--json)".into())?;
        }
        let figures =
            plots.map(|(folder, origin, option)| figures(&mut paths, folder, origin, option, stems)).transpose()?;
        let series = series.map(|(path, origin, label)| paths.output(label, origin, &path)).transpose()?;
        Ok(Plan { series, figures })
    }

    /// The outputs of the demonstration, which reads no file: the series and the figures in `folder`.
    pub fn demonstration(folder: &Path) -> anyhow::Result<Plan> {
        let mut paths = Paths::default();
        let figures = figures(
            &mut paths,
            folder.to_path_buf(),
            Origin::CommandLine,
            "the demonstration's folder",
            &output::figures::FIGURES,
        )?;
        let series = folder.join("series.csv");
        let series = paths.output(series.display().to_string(), Origin::CommandLine, &series)?;
        Ok(Plan { series: Some(series), figures: Some(figures) })
    }
}

/// The figure files of the folder `folder` (which must be a folder, or not exist yet), each added to `paths`.
fn figures(
    paths: &mut Paths,
    folder: PathBuf,
    origin: Origin,
    option: &str,
    stems: &[&str],
) -> anyhow::Result<Figures> {
    let shown = folder.display();
    if let Ok(meta) = std::fs::metadata(&folder)
        && !meta.is_dir()
    {
        return Err(origin.bad(format!(
            "{option} {shown} is an existing file, not a folder: the figures need a folder to be written into"
        )));
    }
    let mut files = Vec::new();
    for stem in stems {
        for extension in ["png", "svg"] {
            let name = format!("{stem}.{extension}");
            let path = folder.join(&name);
            let label = format!("{option} {shown} (figure {})", path.display());
            files.push((name, paths.output(label, origin.clone(), &path)?));
        }
    }
    Ok(Figures { folder, files })
}

/// Writes the series and figures of `plan`, all or (on error) none of the regular files; returns the names written.
/// The figures are rendered first, in a staging folder, so that a figure that fails leaves no series either.
pub fn write_outputs(scene: &Scene, simulation: &Simulation, plan: &Plan) -> anyhow::Result<Vec<String>> {
    let mut pending: Vec<OutputFile> = Vec::new();
    if let Some(figures) = &plan.figures {
        let history = crate::impact::figure_history(scene, simulation)?
            .ok_or_else(|| anyhow::anyhow!("no history was recorded for the figures"))?;
        let staging = Staging::inside(&figures.folder)?;
        for staged in output::figures::write_all(&simulation.report, &history, staging.path())? {
            let name = staged.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
            let destination = match figures.files.iter().find(|(planned, _)| *planned == name) {
                Some((_, destination)) => destination.clone(),
                // A figure this plan does not know of yet still goes by the same rules.
                None => Destination::resolve(&figures.folder.join(&name))?,
            };
            pending.push(staging.publish(&staged, &destination)?);
        }
    }
    if let (Some(destination), Some(history)) = (&plan.series, &simulation.history) {
        // (The caller records a history whenever a series is asked for.)
        let mut series = OutputFile::create(destination)?;
        series.write_bytes(output::csv::render(history).as_bytes())?;
        pending.push(series);
    }
    let mut written = Vec::new();
    for output in pending {
        let name = output.shown().to_string();
        let to_standard_output = plan.series.as_ref().is_some_and(|s| s.is_standard_output() && name == s.shown());
        output.finish()?;
        if !to_standard_output {
            written.push(name);
        }
    }
    Ok(written)
}

/// `impact run` of a world scene: its report, readable or JSON; its series (streamed while it runs) and figures.
fn run_world(args: &RunArgs, scene: &WorldScene) -> anyhow::Result<()> {
    if args.samples.is_some() {
        return Err(BadInput(
            "--samples resamples one impact's contact; a world run's series has every step of its islands and \
             instants of each flight"
                .into(),
        )
        .into());
    }
    let plan = Plan::new(args, &scene.output, &output::world_figures::FIGURES)?;
    let mut series =
        plan.series.as_ref().map(|d| OutputFile::create(d).map(output::world_series::SeriesWriter::new)).transpose()?;
    let mut trace = plan.figures.as_ref().map(|_| output::world_figures::WorldTrace::new());
    let simulation = {
        let observed = series.is_some() || trace.is_some();
        let mut observers = Both { series: series.as_mut(), trace: trace.as_mut() };
        let run = super::progress::watched(&scene.world, |progress| {
            let observer: Option<&mut dyn crate::world::record::Observer> =
                if observed { Some(&mut observers) } else { None };
            crate::world_run::simulate_watched(scene, crate::world::driver::Watchers { observer, progress })
        });
        run.map_err(|error| match error {
            crate::world::WorldError::Setup(error) => anyhow::Error::new(crate::scene::located(&args.scene, error)),
            other => anyhow::Error::new(other),
        })?
    };
    let mut pending: Vec<OutputFile> = Vec::new();
    if let (Some(figures), Some(trace)) = (&plan.figures, &trace) {
        let staging = Staging::inside(&figures.folder)?;
        for staged in output::world_figures::write_all(&simulation.report, trace, staging.path())? {
            let name = staged.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
            let destination = match figures.files.iter().find(|(planned, _)| *planned == name) {
                Some((_, destination)) => destination.clone(),
                None => Destination::resolve(&figures.folder.join(&name))?,
            };
            pending.push(staging.publish(&staged, &destination)?);
        }
    }
    if let Some(series) = series {
        pending.push(series.finish()?);
    }
    let text = if args.json {
        output::json::render_world(&simulation.report)?
    } else {
        output::world_table::render(&simulation.report)
    };
    let to_standard_output = plan.series.as_ref().is_some_and(Destination::is_standard_output);
    if to_standard_output {
        eprint!("{text}");
    } else {
        print!("{text}");
    }
    for output in pending {
        let name = output.shown().to_string();
        let streamed = plan.series.as_ref().is_some_and(|s| s.is_standard_output() && name == s.shown());
        output.finish()?;
        if !streamed {
            eprintln!("wrote {name}");
        }
    }
    // A run its budget stopped did not finish what the scene asked: its report and outputs, complete up to where it
    // stopped, are written, and the status says so (exit 1).
    if simulation.report.world.end_reason == crate::world::record::EndReason::StepBudget.name() {
        // (The report first, then the message: stdout is written out before stderr says why the status is 1.)
        std::io::Write::flush(&mut std::io::stdout())?;
        anyhow::bail!(
            "{}: the world run stopped before its end at t = {} (world.end_reason = \"step_budget\"): its report's notes \
             say why; the report and outputs above stop there",
            args.scene.display(),
            crate::units::brief(simulation.report.world.end_time, "s")
        );
    }
    Ok(())
}

/// The series writer and the figures' trace, each if asked for, watching one run.
struct Both<'a> {
    series: Option<&'a mut output::world_series::SeriesWriter>,
    trace: Option<&'a mut output::world_figures::WorldTrace>,
}

impl crate::world::record::Observer for Both<'_> {
    fn instant(
        &mut self,
        time: f64,
        bodies: &[crate::world::flight::Kinematic],
        contacts: &[crate::world::record::ContactSample],
    ) {
        if let Some(series) = self.series.as_deref_mut() {
            series.instant(time, bodies, contacts);
        }
        if let Some(trace) = self.trace.as_deref_mut() {
            trace.instant(time, bodies, contacts);
        }
    }
}
