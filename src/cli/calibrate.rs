//! `impact calibrate --law LAW --restitution E [--approach-speed V] [--separation S] [SCENE] [--json]`: the
//! damping parameter for which the simulated e equals E (see [`crate::calibrate`] for the methods), and what the
//! law's own published map would have given.

use super::BadInput;
use crate::calibrate::{Calibration, Refusal, from_arguments, readable};
use crate::scene::Scene;
use clap::Args;
use std::fmt::Write as _;
use std::path::PathBuf;

/// Find the damping parameter of a contact law for which the simulated coefficient of restitution equals E.
///
/// Uses the exact relation where one exists (hysteresis family; kelvin-voigt and tsuji with separation at zero
/// penetration), a root-find on the exact closed form for kelvin-voigt and tsuji with separation = "force", and a
/// bracketed root-find on the simulation of SCENE for brilliantov and the simulators' laws (hertz-dashpot's c, mujoco's
/// dampratio, adams-impact's cmax). The result is checked by one more simulation.
/// Without SCENE, hysteresis laws use v0 = 1 m/s unless --approach-speed is given, kelvin-voigt reports only zeta
/// (c = 2 zeta sqrt(k m*) needs a scene), and brilliantov and the simulators' laws are an error.
#[derive(Debug, Args)]
#[command(after_help = AFTER_HELP)]
pub struct CalibrateArgs {
    /// Scene file (TOML) supplying the bodies, stiffness, separation and approach speed; its own restitution or
    /// damping is replaced by the calibrated damping. Required for brilliantov, hertz-dashpot, mujoco and
    /// adams-impact.
    pub scene: Option<PathBuf>,
    /// The law to calibrate (see `impact models`); replaces the scene's law. Default: the scene's law.
    #[arg(long, value_name = "LAW")]
    pub law: Option<String>,
    /// Target coefficient of restitution (velocity ratio), in (0, 1].
    #[arg(long, value_name = "E", allow_negative_numbers = true)]
    pub restitution: f64,
    /// Approach speed v0 in m/s; replaces the scene's (both bodies' velocities are scaled by one factor).
    /// Without a scene: 1 m/s.
    #[arg(long, value_name = "V", allow_negative_numbers = true)]
    pub approach_speed: Option<f64>,
    /// "penetration" or "force": which event ends the contact; replaces the scene's. Default: the scene's, or
    /// "penetration" without a scene.
    #[arg(long, value_name = "CRITERION")]
    pub separation: Option<String>,
    /// Print the result as JSON on stdout instead of the readable summary.
    #[arg(long)]
    pub json: bool,
}

const AFTER_HELP: &str = "\
Methods (the first that applies):
  hysteresis family        exact relation chi(E), alpha = chi / v0  (v0 = 1 m/s without a scene)
  kelvin-voigt, tsuji      exact relation with separation = penetration; root-find on the exact
                           closed form with separation = force (kelvin-voigt's c needs a scene)
  brilliantov,             bracketed root-find on the simulation of SCENE (required): their e
  hertz-dashpot,           depends on the speed, the mass and the stiffness; mujoco's is
  mujoco, adams-impact     solref's dampratio (timeconst, solimp kept; the damping of the
                           [-stiffness, -damping] form), adams-impact's cmax (dmax kept)
Every result is checked by one simulation, and shown beside what the law's own published map gives.

Examples:
  impact calibrate --law lankarani-nikravesh --restitution 0.5 --approach-speed 2
  impact calibrate models/rubber-ball-kelvin-voigt.toml --restitution 0.6 --separation force
  impact calibrate models/viscoelastic-spheres.toml --restitution 0.7 --json";

pub fn run(args: &CalibrateArgs) -> anyhow::Result<()> {
    let scene = match &args.scene {
        Some(path) => Some((Scene::load(path)?, path.display().to_string())),
        None => None,
    };
    let calibration =
        from_arguments(args.law.as_deref(), args.restitution, args.approach_speed, args.separation.as_deref(), scene)
            .map_err(|refusal| match refusal {
            Refusal::BadInput(message) => anyhow::Error::new(BadInput(message)),
            Refusal::Failed(message) => anyhow::anyhow!(message),
        })?;
    let text = if args.json { serde_json::to_string_pretty(&calibration)? + "\n" } else { render(&calibration) };
    print!("{text}");
    Ok(())
}

/// The readable summary.
pub fn render(c: &Calibration) -> String {
    let mut text = format!("Calibration of `{}` for e = {}\n", c.law, readable(c.restitution_target));
    let mut line = |label: &str, value: String| {
        let _ = writeln!(text, "  {label:<16} {value}");
    };
    line(
        "damping",
        match c.damping {
            Some(damping) => format!("{}  ({})", readable(damping), c.damping_units),
            None => format!("needs a scene ({}; see the notes)", c.damping_units),
        },
    );
    line("dimensionless", format!("{} = {}", c.dimensionless.symbol, readable(c.dimensionless.value)));
    line("method", c.method.name().to_string());
    line("approach speed", format!("{} m/s; separation at zero {}", readable(c.approach_speed), c.separation));
    line(
        "scene",
        match &c.scene {
            Some(s) => format!(
                "\"{}\": m* = {} kg, stiffness {} N/m^{}",
                s.title,
                readable(s.effective_mass),
                readable(s.stiffness),
                s.exponent
            ),
            None => "none (a default scene, see the notes)".into(),
        },
    );
    let simulations = format!("{} simulation{}", c.simulations, if c.simulations == 1 { "" } else { "s" });
    line(
        "simulated e",
        match c.restitution_simulated {
            Some(e) => format!("{e:.12}  (|e - E| = {:.1e}; {simulations})", (e - c.restitution_target).abs()),
            None => format!("none: the bodies did not separate ({simulations})"),
        },
    );
    let symbol = c.dimensionless.symbol.split(" =").next().unwrap_or("damping");
    line(
        "published map",
        match &c.published_map {
            Some(p) => format!(
                "{} gives {symbol} = {}{}, which yields e = {:.6}",
                p.map,
                readable(p.dimensionless),
                p.damping.map_or_else(String::new, |d| format!(" (damping {})", readable(d))),
                p.restitution
            ),
            None => "none (this law has no e -> damping map)".into(),
        },
    );
    if !c.notes.is_empty() {
        text += "notes\n";
        for note in &c.notes {
            let _ = writeln!(text, "  - {note}");
        }
    }
    text
}
