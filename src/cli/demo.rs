//! `impact` with no argument: a built-in demonstration scene, its report printed and saved under `out/demo/`.

use crate::impact::simulate;
use crate::output;
use crate::scene::Scene;
use std::path::Path;

/// The demonstration: two steel balls, 10 mm radius, closing at 2 m/s, Hunt–Crossley damping with the exact map.
pub const SCENE: &str = include_str!("../../models/demo.toml");

/// Where the demonstration writes (untracked).
pub const FOLDER: &str = "out/demo";

pub fn run() -> anyhow::Result<()> {
    let scene = Scene::parse(SCENE, Path::new("models/demo.toml"))?;
    let simulation = simulate(&scene, crate::history::Recording::Off)?;
    print!("{}", output::table::render(&simulation.report));
    let folder = Path::new(FOLDER);
    output::files::write_atomically(&folder.join("scene.toml"), SCENE.as_bytes())?;
    output::files::write_atomically(&folder.join("report.json"), output::json::render(&simulation.report)?.as_bytes())?;
    println!(
        "\nwrote {}/scene.toml and {}/report.json (run `impact run SCENE.toml` on your own scenes)",
        FOLDER, FOLDER
    );
    Ok(())
}
