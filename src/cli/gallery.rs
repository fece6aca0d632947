//! `impact gallery`: regenerates the README's committed figures in `plots/` (and only on this explicit command).
//! Every figure is computed in memory and written straight to its place (atomically); only those paths are printed.

use crate::history::Recording;
use crate::impact::simulate;
use crate::output::files::write_atomically;
use crate::output::{figures, render, sweep_figure};
use crate::scene::Scene;
use crate::sweep::grid::{Axis, Grid, Spacing};
use crate::sweep::{self as sweeps, Sweep, table};
use anyhow::{Context, anyhow};
use clap::Args;
use std::path::{Path, PathBuf};

#[derive(Debug, Args)]
pub struct GalleryArgs {
    /// Folder for the figures.
    #[arg(long, value_name = "DIR", default_value = "plots")]
    pub out: PathBuf,
}

/// The one-impact figures of the gallery: (scene name, scene text, the figures kept). The demonstration's steel
/// balls show the Hunt–Crossley force pulse and the velocities meeting at V0; the Kelvin–Voigt rubber ball shows
/// the force jump at first contact and the tensile end, which Hertz-type laws do not have.
const SCENES: [(&str, &str, &[&str]); 2] = [
    ("demo", include_str!("../../models/demo.toml"), &["force_time", "velocities"]),
    ("kelvin_voigt", include_str!("../../models/rubber-ball-kelvin-voigt.toml"), &["force_penetration"]),
];

/// The literature's comparison sweep: nominal e from 0.05 to 1 under six published maps.
const SWEEP_SCENE: (&str, &str) =
    ("models/hysteresis-lankarani-nikravesh.toml", include_str!("../../models/hysteresis-lankarani-nikravesh.toml"));
const SWEEP_VARY: &str = "contact.restitution=0.05:1:39";
const SWEEP_LAWS: [&str; 6] =
    ["hunt-crossley", "lankarani-nikravesh", "gonthier", "flores", "hu-guo", "carvalho-martins"];

pub fn run(args: &GalleryArgs) -> anyhow::Result<()> {
    for (name, text, keep) in SCENES {
        let scene = Scene::parse(text, Path::new(&format!("models/{name}.toml")))?;
        let simulation = simulate(&scene, Recording::Uniform(super::run::FIGURE_SAMPLES))?;
        let history = simulation.history.as_ref().ok_or_else(|| anyhow!("{name}: no contact history recorded"))?;
        for figure in keep {
            let svg = figures::svg(figure, &simulation.report, history);
            let target = args.out.join(format!("{name}_{figure}.png"));
            let png = render::png(&svg).with_context(|| format!("cannot render {}", target.display()))?;
            write_atomically(&target, &png)?;
            println!("wrote {}", target.display());
        }
    }
    effective_restitution(&args.out)
}

/// The comparison figure of the contact-mechanics literature: the e each published map actually gives against
/// the e it was asked for (docs/laws.md), from a sweep of the hysteresis-family scene under several laws. The
/// sweep's table stays in memory: only the figure is written.
fn effective_restitution(folder: &Path) -> anyhow::Result<()> {
    let (path, text) = SWEEP_SCENE;
    let grid = Grid::new(vec![Axis::parse(SWEEP_VARY, Spacing::Linear)?])?;
    let laws = sweeps::parse_laws(&SWEEP_LAWS.map(String::from))?;
    let sweep = Sweep::new(Path::new(path), text.to_string(), grid, laws)?;
    let indices: Vec<usize> = (0..sweep.rows()).collect();
    let rows = sweep.run(&indices, None, || {})?;
    let csv = table::render(&sweep.keys(), &rows, None);
    let figure = sweeps::figure::from_csv(&csv)?;
    let written = sweep_figure::stage(&figure, &folder.join("effective_restitution.png"))?.commit()?;
    println!("wrote {}", written.display());
    Ok(())
}
