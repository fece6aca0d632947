//! `impact gallery`: regenerates the README's committed figures in `plots/` (and only on this explicit command).
//! Every figure is computed in memory and written straight to its place (atomically); only those paths are printed.

use crate::files::write_atomically;
use crate::history::Recording;
use crate::impact::simulate;
use crate::output::world_figures::{self, WorldTrace};
use crate::output::{figures, render, rod_sweep_figure, sweep_figure};
use crate::scene::{Parsed, Scene};
use crate::sweep::grid::{Axis, Grid, Spacing};
use crate::sweep::key::SceneKey;
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

/// Chung & Ooi's test 4 (an alumina sphere on a rigid wall with friction): its sweep over the angle of incidence
/// (the README's command) and one impact at 20 degrees, where the contact sticks, the tangential force reverses and
/// the sphere slides back.
const OBLIQUE_SCENE: (&str, &str) = ("models/chung-ooi-test4.toml", include_str!("../../models/chung-ooi-test4.toml"));
const OBLIQUE_VARY: &str = "bodies.0.incidence_deg=5:85:33";
const OBLIQUE_KEY: &str = "bodies.0.incidence_deg";
const OBLIQUE_ANGLE: f64 = 20.0;

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
    effective_restitution(&args.out)?;
    restitution_against_speed(&args.out)?;
    oblique_forces(&args.out)?;
    incidence(&args.out)?;
    rod_angle_sweep(&args.out)?;
    worlds(&args.out)
}

/// The rod of models/rod-chatter.toml dropped at 1 m/s at every angle from 1 to 89 degrees (src/rod_sweep.rs): the
/// apparent e and the number of contacts of its impact sequence, simulated, by the sequential model and by the rigid
/// rod's own impacts.
fn rod_angle_sweep(folder: &Path) -> anyhow::Result<()> {
    let points = crate::rod_sweep::sweep(&crate::rod_sweep::gallery_angles()).map_err(|why| anyhow!(why))?;
    let title = "A steel rod (0.2 kg, 0.2 m) dropped at θ onto a floor at 1 m/s, Hunt–Crossley ends, under gravity";
    let svg = rod_sweep_figure::svg(title, &points);
    let target = folder.join("rod_angle_sweep.png");
    let png = render::png(&svg).with_context(|| format!("cannot render {}", target.display()))?;
    write_atomically(&target, &png)?;
    println!("wrote {}", target.display());
    Ok(())
}

/// The world figures of the gallery: (scene name, scene text, the figure kept). The bouncing ball's heights beside
/// the instantaneous model's apexes; Newton's cradle's velocities beside the sequential model's.
const WORLDS: [(&str, &str, &str); 2] = [
    ("bouncing_ball", include_str!("../../models/bouncing-ball.toml"), "heights"),
    ("newtons_cradle_3", include_str!("../../models/newtons-cradle-3.toml"), "velocities"),
];

fn worlds(folder: &Path) -> anyhow::Result<()> {
    for (name, text, figure) in WORLDS {
        let path = format!("models/{}.toml", name.replace('_', "-"));
        let Parsed::World(scene) = crate::setup::parse_any(text, Path::new(&path))? else {
            return Err(anyhow!("{path} is not a world scene"));
        };
        let mut trace = WorldTrace::new();
        let simulation = crate::world_run::simulate_observed(&scene, &mut trace)?;
        let svg = world_figures::svg(figure, &simulation.report, &trace);
        let target = folder.join(format!("{name}_{figure}.png"));
        let png = render::png(&svg).with_context(|| format!("cannot render {}", target.display()))?;
        write_atomically(&target, &png)?;
        println!("wrote {}", target.display());
    }
    Ok(())
}

/// The contact forces of Chung & Ooi's test 4 at [`OBLIQUE_ANGLE`] degrees: the scene file with its sphere's
/// velocity turned as `--vary bodies.0.incidence_deg` turns it, and its title saying so.
fn oblique_forces(folder: &Path) -> anyhow::Result<()> {
    let (path, text) = OBLIQUE_SCENE;
    let mut document: toml::Table = text.parse().with_context(|| format!("{path} is not TOML"))?;
    SceneKey::parse(OBLIQUE_KEY)?.set(&mut document, OBLIQUE_ANGLE).map_err(|why| anyhow!("{path}: {why}"))?;
    let title = format!("Chung & Ooi test 4: Al2O3 sphere on a rigid wall at {OBLIQUE_ANGLE} degrees, mu = 0.092");
    document.insert("title".into(), toml::Value::String(title));
    let scene = Scene::parse(&toml::to_string(&document)?, Path::new(path))?;
    let simulation = simulate(&scene, Recording::Uniform(super::run::FIGURE_SAMPLES))?;
    let history = simulation.history.as_ref().ok_or_else(|| anyhow!("{path}: no contact history recorded"))?;
    let svg = figures::svg("force_time", &simulation.report, history);
    let target = folder.join("chung_ooi_20deg_force_time.png");
    let png = render::png(&svg).with_context(|| format!("cannot render {}", target.display()))?;
    write_atomically(&target, &png)?;
    println!("wrote {}", target.display());
    Ok(())
}

/// Chung & Ooi's test 4 swept over the angle of incidence: the tangential restitution, rebound spin and rebound
/// angle against it, simulated and by rigid-body theory (the sweep's table stays in memory).
fn incidence(folder: &Path) -> anyhow::Result<()> {
    let (path, text) = OBLIQUE_SCENE;
    let grid = Grid::new(vec![Axis::parse(OBLIQUE_VARY, Spacing::Linear)?])?;
    let sweep = Sweep::new(Path::new(path), text.to_string(), grid, sweeps::parse_laws(&[])?)?;
    let indices: Vec<usize> = (0..sweep.rows()).collect();
    let rows = sweep.run(&indices, None, |_| {})?;
    let csv = table::render(&sweep.keys(), sweep.columns(), &rows, None);
    let mut figure = sweeps::figure::incidence_from_csv(&csv)?;
    figure.title = "Chung & Ooi test 4: Al2O3 sphere on a rigid wall, 3.9 m/s, mu = 0.092, e = 0.98".into();
    let plot = sweep_figure::SweepPlot::Incidence(figure);
    let written = sweep_figure::stage(&plot, &folder.join("chung_ooi_test4.png"))?.commit()?;
    println!("wrote {}", written.display());
    Ok(())
}

/// Two materials whose e is not a constant: a hardened steel ball yielding on a steel block (Thornton's law) and an
/// ice-like viscoelastic sphere on a rigid wall (Brilliantov's), each swept over the approach speed, with the one e
/// the idealisation would use — the steel ball's at 1 m/s — drawn across the speeds.
const SPEED_SCENES: [(&str, &str, &str); 2] = [
    (
        "models/yielding-steel-ball.toml",
        include_str!("../../models/yielding-steel-ball.toml"),
        "thornton: 10 mm steel ball on steel, Y = 1 GPa",
    ),
    (
        "models/viscoelastic-sphere-on-wall.toml",
        include_str!("../../models/viscoelastic-sphere-on-wall.toml"),
        "brilliantov: 10 mm ice-like sphere on a wall, A = 1 µs",
    ),
];
const SPEED_VARY: &str = "bodies.0.velocity.0=0.01:30:49";

fn restitution_against_speed(folder: &Path) -> anyhow::Result<()> {
    let mut curves = Vec::new();
    for (path, text, label) in SPEED_SCENES {
        let grid = Grid::new(vec![Axis::parse(SPEED_VARY, Spacing::Geometric)?])?;
        let sweep = Sweep::new(Path::new(path), text.to_string(), grid, sweeps::parse_laws(&[])?)?;
        let indices: Vec<usize> = (0..sweep.rows()).collect();
        let rows = sweep.run(&indices, None, |_| {})?;
        let csv = table::render(&sweep.keys(), sweep.columns(), &rows, None);
        let mut figure = sweeps::figure::from_csv(&csv)?;
        for curve in &mut figure.curves {
            curve.label = label.into();
        }
        curves.push(figure);
    }
    let (path, text, _) = SPEED_SCENES[0];
    let steel = simulate(&Scene::parse(text, Path::new(path))?, Recording::Off)?.report;
    let e = steel.contact.restitution_velocity_ratio.ok_or_else(|| anyhow!("{path}: the ball did not separate"))?;
    let mut figure = curves.remove(0);
    let constant = sweep_figure::Curve {
        label: format!("the idealisation: one e = {e:.3}, the steel ball's at 1 m/s"),
        points: figure.curves[0].points.iter().map(|p| p.map(|(x, _)| (x, e))).collect(),
    };
    figure.curves.extend(curves.into_iter().flat_map(|f| f.curves));
    figure.curves.push(constant);
    figure.title = "e against impact speed: yield and viscoelasticity".into();
    let plot = sweep_figure::SweepPlot::Restitution(figure);
    let written = sweep_figure::stage(&plot, &folder.join("restitution_speed.png"))?.commit()?;
    println!("wrote {}", written.display());
    Ok(())
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
    let rows = sweep.run(&indices, None, |_| {})?;
    let csv = table::render(&sweep.keys(), sweep.columns(), &rows, None);
    let figure = sweep_figure::SweepPlot::Restitution(sweeps::figure::from_csv(&csv)?);
    let written = sweep_figure::stage(&figure, &folder.join("effective_restitution.png"))?.commit()?;
    println!("wrote {}", written.display());
    Ok(())
}
