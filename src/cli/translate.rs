//! `impact translate SCENE --to PEER [--dt SECONDS] [--json] [--input DIR]`: the scene's contact in another
//! program's language, with the e that program gives (see [`crate::translate`]).

use super::BadInput;
use crate::impact::SimulationError;
use crate::scene::{Parsed, SceneError, SetupError, located};
use crate::setup::load_any;
use crate::translate::{Peer, TranslateError, Translation, input, translate};
use clap::Args;
use std::fmt::Write as _;
use std::path::PathBuf;

/// Write the scene's contact as another program's input (LAMMPS, LIGGGHTS, MuJoCo, Drake, Kratos, ADAMS), with the
/// e that program gives in the continuous limit and at its time step.
///
/// When the scene asks for an e (`restitution`), the program's parameter is tuned so that it gives that e — at
/// --dt by the program's own fixed-step scheme when --dt is given, in the continuous limit otherwise.
#[derive(Debug, Args)]
#[command(after_help = AFTER_HELP)]
pub struct TranslateArgs {
    /// Scene file (TOML).
    pub scene: PathBuf,
    /// The program: lammps, liggghts, mujoco, drake, kratos or adams.
    #[arg(long, value_name = "PEER")]
    pub to: String,
    /// The program's time step in seconds: its e at that step (its own scheme), and the parameter for the
    /// scene's e at that step. Default: the scene's `[solver] dt`, if it runs a fixed-step scheme.
    #[arg(long, value_name = "SECONDS", allow_negative_numbers = true)]
    pub dt: Option<f64>,
    /// Print the translation as JSON on stdout.
    #[arg(long)]
    pub json: bool,
    /// With --to lammps: also write DIR/in.impact and DIR/data.impact, the whole scene as a runnable LAMMPS
    /// input (run `lmp -in in.impact` from DIR; it writes DIR/final.txt, one line `id vx vy vz` per sphere).
    #[arg(long, value_name = "DIR")]
    pub input: Option<PathBuf>,
}

const AFTER_HELP: &str = "\
Programs and what they get:
  lammps    pair_style granular pair_coeff (hooke/hertz; velocity, viscoelastic or coeff_restitution damping)
  liggghts  pair_style gran model hertz with coefficientRestitution
  mujoco    <geom solref solimp>, Euler integrator
  drake     point_contact_stiffness with hunt_crossley_dissipation (continuous) or relaxation_time (SAP)
  kratos    DEM_D_Hertz_viscous_Coulomb material parameters
  adams     IMPACT(x, x', x1, k, e, cmax, d)

Examples:
  impact translate models/mujoco-typed-physical.toml --to mujoco --dt 2e-4
  impact translate models/tsuji-dem-alumina.toml --to lammps --dt 1.3e-7 --json
  impact translate models/newtons-cradle-3.toml --to lammps --input out/cradle-lammps";

pub fn run(args: &TranslateArgs) -> anyhow::Result<()> {
    let peer = Peer::named(&args.to).map_err(BadInput)?;
    if args.input.is_some() && peer != Peer::Lammps {
        return Err(BadInput("--input writes a LAMMPS input: use it with --to lammps".into()).into());
    }
    let shown = args.scene.display().to_string();
    let located = |error: TranslateError| -> anyhow::Error {
        match error {
            // (An argument's fault names the argument; a scene's names its key and line.)
            TranslateError::Bad { key, message } if key.starts_with("--") => {
                BadInput(format!("{key}: {message}")).into()
            }
            TranslateError::Bad { key, message } => located(&args.scene, SetupError { key, message }).into(),
            TranslateError::Simulation(SimulationError::Setup(error)) => located(&args.scene, error).into(),
            error => anyhow::Error::new(error).context(shown.clone()),
        }
    };
    let translation = match load_any(&args.scene)? {
        Parsed::Impact(scene) => {
            // (A scene that runs a peer's fixed step gives its dt, unless --dt does.)
            let dt = args.dt.or(scene.solver.dt);
            let translation = translate(&scene, peer, dt).map_err(located)?;
            if let Some(folder) = &args.input {
                let written = input::for_impact(&scene, &translation, dt).map_err(located)?;
                input::write(folder, &args.scene, &written).map_err(located)?;
            }
            translation
        }
        Parsed::World(world) => {
            let Some(folder) = args.input.as_ref().filter(|_| peer == Peer::Lammps) else {
                return Err(SceneError::file(&args.scene, crate::translate::WORLD_AS_A_WHOLE).into());
            };
            let written = input::for_world(&world, args.dt.or(world.solver.dt)).map_err(located)?;
            input::write(folder, &args.scene, &written).map_err(located)?;
            if !args.json {
                print!("{}", render_world(&written, folder));
                return Ok(());
            }
            input::as_translation(&written)
        }
    };
    let text = if args.json { serde_json::to_string_pretty(&translation)? + "\n" } else { render(&translation) };
    print!("{text}");
    Ok(())
}

/// e as the table prints it.
fn restitution(e: Option<f64>) -> String {
    e.map_or("none (the bodies do not part)".into(), |e| format!("{e:.6}"))
}

/// What was written for a world.
fn render_world(input: &input::Input, folder: &std::path::Path) -> String {
    let shown = folder.display();
    let mut text = format!(
        "In LAMMPS: {} spheres ({} atom type{}), {} wall{}, {} steps of {} s\n  wrote {shown}/in.impact and \
         {shown}/data.impact; run `lmp -in in.impact` there: it writes {shown}/final.txt (id vx vy vz per sphere)\n\n",
        input.atoms.len(),
        input.types,
        if input.types == 1 { "" } else { "s" },
        input.walls.len(),
        if input.walls.len() == 1 { "" } else { "s" },
        input.steps,
        crate::translate::number(input.dt)
    );
    for (a, b, arguments) in &input.pair_coeffs {
        let _ = writeln!(text, "  pair_coeff {a} {b} {arguments}");
    }
    for (k, wall) in input.walls.iter().enumerate() {
        let _ = writeln!(text, "  wall{k}: {}", wall.arguments);
    }
    let _ = writeln!(text, "\n  notes");
    for note in &input.notes {
        let _ = writeln!(text, "    - {note}");
    }
    text
}

/// The readable translation.
pub fn render(t: &Translation) -> String {
    let title = Peer::from_name(t.peer).map_or(t.peer, |peer| peer.title());
    let mut text = format!("In {title}: {}\n\n", t.law);
    let _ = writeln!(text, "  parameters");
    for (name, value) in &t.parameters.0 {
        let _ = writeln!(text, "    {name:<28} {value}");
    }
    let _ = writeln!(text);
    if let Some(target) = t.restitution_target {
        let _ = writeln!(text, "  {:<30} {target}", "e of the scene's contact");
    }
    let _ = writeln!(text, "  {:<30} {}", "e in the continuous limit", restitution(t.restitution_continuous));
    if let Some(dt) = t.dt {
        let at = match t.restitution_at_dt {
            Some(e) => format!("{e:.6}"),
            None => "not computed (see the notes)".into(),
        };
        let _ = writeln!(text, "  {:<30} {at}", format!("e at dt = {dt:e} s"));
    }
    let _ = writeln!(text, "\n  paste into your input:");
    for line in t.snippet.lines() {
        let _ = writeln!(text, "    {line}");
    }
    if !t.notes.is_empty() {
        let _ = writeln!(text, "\n  notes");
        for note in &t.notes {
            let _ = writeln!(text, "    - {note}");
        }
    }
    text
}
