//! The command line: one file per verb. Arguments become typed options before any work starts.

mod bench;
mod calibrate;
mod demo;
mod gallery;
mod merge;
mod models;
pub mod paths;
mod progress;
pub mod run;
mod stress;
pub mod sweep;
mod translate;
mod validate;

use clap::{Parser, Subcommand};

/// Simulate impacts with compliant contact laws — one collision of two bodies, or a world of many bodies under
/// gravity — and measure what the instantaneous-impact idealisation hides.
///
/// Every contact is followed through compression and restitution and set beside the textbook's instantaneous
/// impact. With no command, runs a built-in demonstration (its report on the terminal, its figures in out/demo/).
#[derive(Debug, Parser)]
#[command(name = "impact", version, about)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Simulate one scene file (one impact of two bodies, or a world of many) and print its report.
    Run(run::RunArgs),
    /// List the contact laws with their formulas, damping maps and sources.
    Models(models::ModelsArgs),
    /// Run a scene over a grid of parameter values (and laws), one CSV row per point and law.
    Sweep(sweep::SweepArgs),
    /// Join the CSV shards of a sweep split with --shard into the whole sweep.
    Merge(merge::MergeArgs),
    /// Find the damping for which the simulated e equals a target.
    Calibrate(calibrate::CalibrateArgs),
    /// The work–precision study: every method's error against exact references and its time per impact.
    Bench(bench::BenchArgs),
    /// Regenerate the README's figures in plots/.
    Gallery(gallery::GalleryArgs),
    /// Run random scenes over the whole accepted range, checking each against invariants and exact results.
    Stress(stress::StressArgs),
    /// Write the scene's contact as another program's input, with the e that program gives at its time step.
    Translate(translate::TranslateArgs),
    /// The validation suite: the program on cases with known answers, each quantity beside its reference.
    Validate(validate::ValidateArgs),
}

/// A bad scene or bad arguments: exit status 2.
#[derive(Debug, thiserror::Error)]
#[error("{0}")]
pub struct BadInput(pub String);

/// Runs the chosen verb.
pub fn dispatch(cli: Cli) -> anyhow::Result<()> {
    match cli.command {
        None => demo::run(),
        Some(Command::Run(args)) => run::run(&args),
        Some(Command::Models(args)) => models::run(&args),
        Some(Command::Sweep(args)) => sweep::run(&args),
        Some(Command::Merge(args)) => merge::run(&args),
        Some(Command::Calibrate(args)) => calibrate::run(&args),
        Some(Command::Gallery(args)) => gallery::run(&args),
        Some(Command::Bench(args)) => bench::run(&args),
        Some(Command::Stress(args)) => stress::run(&args),
        Some(Command::Validate(args)) => validate::run(&args),
        Some(Command::Translate(args)) => translate::run(&args),
    }
}

/// The exit status for an error: 2 for bad input (scene or arguments), 1 otherwise.
pub fn exit_code(error: &anyhow::Error) -> u8 {
    let bad = error.chain().any(|cause| cause.is::<crate::scene::SceneError>() || cause.is::<BadInput>());
    if bad { 2 } else { 1 }
}
