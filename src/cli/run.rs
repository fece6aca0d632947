//! `impact run SCENE.toml [--json]`: simulate one scene and print its report.

use crate::impact::simulate;
use crate::output;
use crate::scene::Scene;
use clap::Args;
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct RunArgs {
    /// The scene file (TOML, see the README).
    pub scene: PathBuf,
    /// Print the JSON report on stdout instead of the readable one.
    #[arg(long)]
    pub json: bool,
}

pub fn run(args: &RunArgs) -> anyhow::Result<()> {
    let scene = Scene::load(&args.scene)?;
    let simulation = simulate(&scene, crate::history::Recording::Off)?;
    let text =
        if args.json { output::json::render(&simulation.report)? } else { output::table::render(&simulation.report) };
    print!("{text}");
    Ok(())
}
