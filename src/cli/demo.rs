//! `impact` with no argument: a built-in demonstration scene, its report printed, its figures, series and JSON
//! report written under `out/demo/` (untracked).

use super::run::{Plan, write_outputs};
use crate::history::Recording;
use crate::impact::simulate;
use crate::output;
use crate::scene::Scene;
use std::path::Path;

/// The demonstration: two steel balls, 10 mm radius, closing at 2 m/s, Hunt–Crossley damping with the exact map.
pub const SCENE: &str = include_str!("../../models/demo.toml");

/// Where the demonstration writes.
pub const FOLDER: &str = "out/demo";

pub fn run() -> anyhow::Result<()> {
    let scene = Scene::parse(SCENE, Path::new("models/demo.toml"))?;
    let simulation = simulate(&scene, Recording::Steps)?;
    print!("{}", output::table::render(&simulation.report));
    let folder = Path::new(FOLDER);
    let mut written = write_outputs(&scene, &simulation, &Plan::demonstration(folder)?)?;
    let json = folder.join("report.json");
    crate::files::write_atomically(&json, output::json::render(&simulation.report)?.as_bytes())?;
    written.push(json.display().to_string());
    println!("\nThe demonstration wrote into {FOLDER}/:");
    for path in written {
        println!("  {path}");
    }
    println!("Simulate your own scene with `impact run SCENE.toml` (see models/ and the README).");
    Ok(())
}
