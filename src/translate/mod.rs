//! `impact translate`: the contact of a scene written in another program's language — its law, its parameters in
//! its own names and units, the text to paste into its input — with the e that program gives in the continuous
//! limit and at a time step by its own fixed-step scheme, and, when the scene asks for an e, the parameter that gives
//! that e at that step (docs/simulators.md).
//!
//! Every peer's contact is one of this program's laws with the peer's own parameters ([`Mapping::contact`]): a
//! peer's law is *run* here, never guessed. Its continuous e comes from the accurate path (a sphere of mass m* on an
//! immovable wall, closing at the scene's v0), its e at `dt` from [`crate::fixed_step`] with the touch on a step
//! boundary (the peers' usual start), and the spread of e over where the touch falls within a step goes to the
//! notes. A target e is met by a bracketed bisection on the peer's own knob: its damping, or the nominal e a peer
//! reads (LAMMPS' `coeff_restitution`, LIGGGHTS' `coefficientRestitution`).
//!
//! Each peer's module knows its own language: [`lammps`], [`liggghts`], [`mujoco`], [`drake`], [`kratos`], [`adams`].

pub mod adams;
pub mod drake;
pub mod input;
pub mod kratos;
pub mod lammps;
pub mod liggghts;
pub mod mujoco;

use crate::calibrate::default_scene;
use crate::fixed_step::{self, Scheme};
use crate::geometry;
use crate::impact::{Options, SimulationError, simulate_with};
use crate::law::{ContactLaw, LawKind, Separation};
use crate::scene::{ContactSpec, DampingSpec, Scene, StiffnessSpec};
use crate::setup::Setup;
use serde::Serialize;
use serde::ser::SerializeMap;
use serde_json::Value;

/// Most steps over one contact a translation at `--dt` runs (each of its many runs takes that many).
pub const MAX_STEPS_PER_CONTACT: f64 = 1.0e6;
/// How many touch phases the spread of e over a step samples.
pub const PHASES: usize = 16;
/// A target e met to within this (absolute) is met: the bisection stops there.
const MATCH: f64 = 1.0e-12;
/// A nominal e whose run gives the target to within this is typed as the target itself (the accurate path's
/// noise on e is about 1e-12).
const NOMINAL_NOISE: f64 = 1.0e-10;
/// Most bisection steps one root-find takes.
const MAX_BISECTIONS: u32 = 200;
/// Most factors of 4 the damping bracket grows by before the target is declared out of reach.
const MAX_GROWTH: u32 = 60;

/// The programs `impact translate` speaks.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Peer {
    Lammps,
    Liggghts,
    Mujoco,
    Drake,
    Kratos,
    Adams,
}

impl Peer {
    pub const ALL: [Peer; 6] = [Peer::Lammps, Peer::Liggghts, Peer::Mujoco, Peer::Drake, Peer::Kratos, Peer::Adams];

    /// The command-line spelling (`--to`).
    pub fn name(self) -> &'static str {
        match self {
            Peer::Lammps => "lammps",
            Peer::Liggghts => "liggghts",
            Peer::Mujoco => "mujoco",
            Peer::Drake => "drake",
            Peer::Kratos => "kratos",
            Peer::Adams => "adams",
        }
    }

    /// The program's own name, as its users write it.
    pub fn title(self) -> &'static str {
        match self {
            Peer::Lammps => "LAMMPS",
            Peer::Liggghts => "LIGGGHTS",
            Peer::Mujoco => "MuJoCo",
            Peer::Drake => "Drake",
            Peer::Kratos => "Kratos DEM",
            Peer::Adams => "ADAMS",
        }
    }

    pub fn from_name(name: &str) -> Option<Peer> {
        Peer::ALL.into_iter().find(|peer| peer.name() == name)
    }

    /// The program named `name` (`--to`), or the command's message for a name it does not know.
    pub fn named(name: &str) -> Result<Peer, String> {
        Peer::from_name(name).ok_or_else(|| {
            let names: Vec<_> = Peer::ALL.iter().map(|peer| peer.name()).collect();
            let to = crate::text::cut(name, crate::text::MESSAGE_CHARS);
            format!("--to: unknown program `{to}`; expected one of {}", names.join(", "))
        })
    }

    /// The fixed-step scheme the program integrates a contact with, when it has one this program runs: LAMMPS' and
    /// LIGGGHTS' velocity Verlet, MuJoCo's and Kratos' semi-implicit Euler, Drake's implicit Euler (its discrete SAP
    /// contact; its continuous point contact has none). ADAMS' integrators adapt their step: `None`.
    pub fn scheme(self) -> Option<Scheme> {
        match self {
            Peer::Lammps | Peer::Liggghts => Some(Scheme::Verlet),
            Peer::Mujoco | Peer::Kratos => Some(Scheme::SymplecticEuler),
            Peer::Drake => Some(Scheme::ImplicitEuler),
            Peer::Adams => None,
        }
    }
}

/// The scene's contact, as every peer's translation needs it (SI).
#[derive(Debug, Clone)]
pub struct Context {
    pub scene: Scene,
    pub setup: Setup,
    /// The law as the scene resolves it (its damping from a nominal e too).
    pub law: ContactLaw,
    /// m*, kg.
    pub mass: f64,
    /// v0, m/s.
    pub speed: f64,
    /// R*, m, when the bodies have one (not two flat faces).
    pub radius: Option<f64>,
    /// The e the scene's contact gives when the scene asks for one (its `restitution` through the law's map, run
    /// head-on in the continuous limit): the e a translation reproduces.
    pub target: Option<f64>,
    /// The time step asked for, s.
    pub dt: Option<f64>,
    /// The scene's nominal `restitution`, when it gives one (`target` is what its contact makes of it).
    pub nominal: Option<f64>,
    /// Whether one body is an immovable wall (the peer's wall, not a second particle).
    pub wall: bool,
}

impl Context {
    /// The scene read for a translation at step `dt`. A scene this cannot translate (a world, an eccentric body,
    /// a fixed-step solver) is refused with the key at fault.
    pub fn new(scene: &Scene, dt: Option<f64>) -> Result<Context, TranslateError> {
        let setup = Setup::new(scene).map_err(|error| TranslateError::Simulation(SimulationError::Setup(error)))?;
        if setup.motion == crate::setup::Motion::Rigid {
            return Err(TranslateError::bad(
                "bodies",
                "an eccentric or pivoted body: the peers' contacts are between spheres (and walls) struck through \
                 their centres; translate the contact of two spheres",
            ));
        }
        let [a, b] = &scene.bodies;
        let mut context = Context {
            scene: scene.clone(),
            law: setup.law,
            mass: setup.effective_mass,
            speed: setup.approach_speed,
            radius: geometry::effective_radius(a, b).filter(|r| r.is_finite() && *r > 0.0),
            target: match scene.contact.damping {
                DampingSpec::Restitution(e) => Some(e),
                DampingSpec::None | DampingSpec::Parameter(_) => None,
            },
            dt,
            wall: a.is_immovable() || b.is_immovable(),
            setup,
            nominal: None,
        };
        // The e to reproduce is the one the scene's contact gives (head-on, in the continuous limit), not the
        // nominal e its law's map was given: the two differ where the map is not exact.
        if let Some(nominal) = context.target {
            let own = restitution(&context, &context.own_contact(), None)?.ok_or_else(|| {
                TranslateError::bad(
                    "contact.restitution",
                    "the scene's own contact does not rebound: no e to reproduce",
                )
            })?;
            // (Within the simulation's noise of the nominal e, the nominal e itself: the map is exact.)
            context.target = Some(if (own - nominal).abs() <= 1e-9 { nominal } else { own });
            context.nominal = Some(nominal);
        }
        Ok(context)
    }

    /// The peer's contact as a scene of this program: a sphere of mass m* closing at v0 on an immovable wall, with
    /// `contact` (whose stiffness must be a number).
    pub fn peer_scene(&self, contact: ContactSpec) -> Scene {
        let mut scene = default_scene(contact.law, self.speed, contact.separation);
        scene.title = format!("{} (as the peer runs it)", self.scene.title);
        scene.bodies[0].mass = self.mass;
        // (The stiffness is a number: the radius only has to lie far beyond the penetrations.)
        scene.bodies[0].radius = 1.0e3 * self.setup.scales.length;
        scene.bodies[0].inertia = crate::body::Body::solid_sphere_inertia(self.mass, scene.bodies[0].radius);
        scene.contact = contact;
        // (The sphere closes along x: the scene's own normal and friction do not apply to the normal contact.)
        scene.contact.normal = None;
        scene.contact.normal_given = None;
        scene.contact.friction = 0.0;
        scene.solver.tolerances = self.scene.solver.tolerances;
        scene
    }

    /// The scene's own contact spec with its stiffness as the number K it resolves to (so that it runs on
    /// [`Context::peer_scene`]'s sphere).
    pub fn own_contact(&self) -> ContactSpec {
        let mut spec = self.scene.contact.clone();
        if self.law.kind.family() != crate::law::Family::Impedance {
            spec.stiffness = StiffnessSpec::Value(self.law.stiffness);
            spec.exponent = self.law.exponent;
        }
        spec
    }

    /// A contact spec of `law` with this scene's numeric stiffness K (N/m^n) and exponent, no damping, no friction,
    /// separating by `separation`: what each peer fills in.
    pub fn spec(&self, law: LawKind, separation: Separation) -> ContactSpec {
        let mut spec = default_scene(law, self.speed, separation).contact;
        spec.stiffness = StiffnessSpec::Value(self.law.stiffness);
        spec.exponent = self.law.exponent;
        spec.exponent_given = Some(self.law.exponent);
        spec
    }

    /// Hertz's K = k_N sqrt(R*) turned into the DEM codes' k_N = K / sqrt(R*) (Pa), or `None` without a radius.
    pub fn hertz_modulus(&self) -> Option<f64> {
        self.radius.map(|radius| self.law.stiffness / radius.sqrt())
    }

    /// The two bodies' own Young's moduli (Pa) and Poisson's ratios when the scene's stiffness is Hertz's from
    /// them (what a peer that reads materials, LIGGGHTS or Kratos, should be given); `None` otherwise.
    pub fn materials(&self) -> Option<[(f64, f64); 2]> {
        let own = |body: &crate::body::Body| match (body.young, body.poisson) {
            (Some(young), Some(poisson)) if young.is_finite() && young > 0.0 => Some((young, poisson)),
            _ => None,
        };
        let [a, b] = &self.scene.bodies;
        match self.scene.contact.stiffness {
            StiffnessSpec::Hertz => Some([own(a)?, own(b)?]),
            StiffnessSpec::Value(_) => None,
        }
    }

    /// The materials a peer that reads them (LIGGGHTS, Kratos) is given: the bodies' own ([`Context::materials`]),
    /// or else both alike, Poisson's ratio 0.3 and the Young's modulus that gives the scene's E* = 3 K / (4 sqrt R*),
    /// with a note saying so.
    pub fn peer_materials(&self, radius: f64, notes: &mut Vec<String>) -> [(f64, f64); 2] {
        const POISSON: f64 = 0.3;
        if let Some(materials) = self.materials() {
            return materials;
        }
        let modulus = 3.0 * self.law.stiffness / (4.0 * radius.sqrt());
        let young = 2.0 * (1.0 - POISSON * POISSON) * modulus;
        notes.push(format!(
            "Both bodies (or atom types) get Young's modulus {} Pa and Poisson's ratio {POISSON}, which give the \
             scene's E* = {} Pa (K = {} N/m^1.5).",
            short(young),
            short(modulus),
            short(self.law.stiffness)
        ));
        [(young, POISSON); 2]
    }

    /// The scene's title as a comment line of any peer's input may carry it.
    pub fn title(&self) -> String {
        comment(&self.scene.title)
    }

    /// Whether the law is Hertz's spring (exponent 3/2) — what the DEM codes' `hertz` models have.
    pub fn hertzian(&self) -> bool {
        self.law.exponent == 1.5
    }
}

/// A peer's parameter values, in order, each a number, a list or a word (serialised as a JSON object).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Parameters(pub Vec<(String, Value)>);

impl Parameters {
    pub fn with(mut self, name: &str, value: impl Into<Value>) -> Parameters {
        self.0.push((name.into(), value.into()));
        self
    }
}

impl Serialize for Parameters {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(Some(self.0.len()))?;
        for (name, value) in &self.0 {
            map.serialize_entry(name, value)?;
        }
        map.end()
    }
}

/// What the bisection turns to meet a target e.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Knob {
    /// The scene gives the damping: the parameter is this value, nothing is tuned.
    Fixed(f64),
    /// A damping parameter in [0, ∞): e falls as it grows. `scale` is a typical size, where the bracket starts.
    Damping { scale: f64 },
    /// The nominal e the peer reads and maps to its damping, in (0, 1]: e rises with it.
    Nominal,
}

/// How a peer runs the scene's contact, as a function of its one knob.
pub trait Mapping {
    /// The peer's contact with knob value `p`, as a law of this program.
    fn contact(&self, p: f64) -> ContactSpec;
    /// The parameters the user types, in the peer's names and units.
    fn parameters(&self, p: f64) -> Parameters;
    /// The text to paste into the peer's input.
    fn snippet(&self, p: f64, dt: Option<f64>) -> String;
}

/// A peer's plan for the scene: its law, the mapping, the knob and the notes known before any run.
pub struct Plan {
    /// The peer's own name for its law.
    pub law: String,
    pub mapping: Box<dyn Mapping>,
    pub knob: Knob,
    pub notes: Vec<String>,
    /// The fixed-step scheme the program runs this contact with, when this program has it: the peer's own
    /// ([`Peer::scheme`]), or Drake's implicit Euler for its discrete SAP contact.
    pub scheme: Option<Scheme>,
}

/// A translation: what `impact translate` prints (the JSON of docs/simulators.md).
#[derive(Debug, Clone, Serialize)]
pub struct Translation {
    pub peer: &'static str,
    pub law: String,
    pub parameters: Parameters,
    pub snippet: String,
    pub restitution_target: Option<f64>,
    pub restitution_continuous: Option<f64>,
    pub dt: Option<f64>,
    pub restitution_at_dt: Option<f64>,
    pub notes: Vec<String>,
}

/// Why a world scene is refused unless it is written as a whole LAMMPS input.
pub const WORLD_AS_A_WHOLE: &str = "a world's contacts meet at many speeds: translate it as a whole LAMMPS input with \
    --to lammps --input DIR, or translate one of its contacts as a two-body scene";

/// Why a translation could not be made.
#[derive(Debug, thiserror::Error)]
pub enum TranslateError {
    /// The scene or the arguments ask for what the peer cannot do: exit 2, naming the key.
    #[error("{key}: {message}")]
    Bad { key: String, message: String },
    /// A run of the peer's contact failed.
    #[error(transparent)]
    Simulation(#[from] SimulationError),
    /// The target e is out of the peer's reach (at this step).
    #[error("{0}")]
    Unreachable(String),
    /// An output could not be written.
    #[error("{0}")]
    Output(String),
}

impl TranslateError {
    pub fn bad(key: &str, message: impl Into<String>) -> TranslateError {
        TranslateError::Bad { key: key.into(), message: message.into() }
    }

    /// Whether the error is the user's input (exit status 2).
    pub fn is_bad_input(&self) -> bool {
        match self {
            TranslateError::Bad { .. } => true,
            TranslateError::Simulation(error) => matches!(error, SimulationError::Setup(_)),
            TranslateError::Unreachable(_) | TranslateError::Output(_) => false,
        }
    }
}

/// The note of a translation that keeps the spring but changes the damping's form, to meet the scene's e.
pub fn substituted(context: &Context, peer: Peer, form: &str) -> String {
    let mut note = format!(
        "{} has no damping of the `{}` form: the translation keeps the spring and tunes {form} to the scene's e, so \
         the force–time curve differs from the scene's while e, head-on at this speed, is the same.",
        peer.title(),
        context.law.kind.name()
    );
    if context.setup.motion == crate::setup::Motion::Full {
        note += " The contact is oblique: the same head-on e is not the same outcome once the line of centres turns \
                 or friction acts, so the velocities after differ a little.";
    }
    note
}

/// The refusal of a law the peer cannot express, naming the nearest one it has.
pub fn cannot_express(peer: Peer, law: LawKind, why: &str, nearest: &str) -> TranslateError {
    TranslateError::bad(
        "contact.law",
        format!("{} cannot express `{}`: {why}; the nearest it has is {nearest}", peer.title(), law.name()),
    )
}

/// The e the peer's contact `contact` gives: in the continuous limit (accurate path) without `dt`, at `dt` by
/// `scheme` with the touch on a step boundary otherwise. `None` when the bodies do not part.
fn restitution(
    context: &Context,
    contact: &ContactSpec,
    step: Option<(Scheme, f64)>,
) -> Result<Option<f64>, SimulationError> {
    let scene = context.peer_scene(contact.clone());
    match step {
        None => {
            let options = Options { idealisation: false, ..Options::default() };
            Ok(simulate_with(&scene, options)?.report.contact.restitution_velocity_ratio)
        }
        Some((scheme, dt)) => Ok(fixed_contact(&scene, contact.separation)?.restitution(scheme, dt, 0.0)),
    }
}

/// The contact of a peer's scene as the fixed-step schemes take it.
fn fixed_contact(scene: &Scene, separation: Separation) -> Result<fixed_step::Contact, SimulationError> {
    let setup = Setup::new(scene).map_err(SimulationError::Setup)?;
    Ok(fixed_step::Contact { law: setup.law, mass: setup.effective_mass, speed: setup.approach_speed, separation })
}

/// The contact's duration in the continuous limit (s), by the accurate path.
fn duration(context: &Context, contact: &ContactSpec) -> Result<Option<f64>, SimulationError> {
    let options = Options { idealisation: false, ..Options::default() };
    Ok(simulate_with(&context.peer_scene(contact.clone()), options)?.report.contact.duration)
}

/// The knob value that gives `target` (bisection on a bracket), and the e it gives.
fn tune(
    target: f64,
    knob: Knob,
    mut e: impl FnMut(f64) -> Result<Option<f64>, SimulationError>,
) -> Result<(f64, f64), TranslateError> {
    // A run in which the bodies do not part counts as e = 0: too much damping.
    let mut at = |p: f64| e(p).map(|e| e.unwrap_or(0.0));
    let (mut low, mut high, rising) = match knob {
        Knob::Fixed(p) => return Ok((p, at(p)?)),
        Knob::Nominal => {
            // A peer whose map is exact here reads the target itself: typed as it is, within the simulation's noise.
            if target <= 1.0 {
                let typed = at(target)?;
                if (typed - target).abs() <= NOMINAL_NOISE {
                    return Ok((target, typed));
                }
            }
            let top = at(1.0)?;
            if top < target {
                return Err(TranslateError::Unreachable(format!(
                    "no nominal e reaches e = {}: a nominal 1 gives {}",
                    short(target),
                    short(top)
                )));
            }
            (f64::MIN_POSITIVE, 1.0, true)
        }
        Knob::Damping { scale } => {
            let mut high = scale;
            let mut grown = 0;
            while at(high)? >= target {
                high *= 4.0;
                grown += 1;
                if grown > MAX_GROWTH {
                    return Err(TranslateError::Unreachable(format!(
                        "no damping brings e down to {}: e stays above it up to a damping of {}",
                        short(target),
                        crate::units::brief(high, "")
                    )));
                }
            }
            let undamped = at(0.0)?;
            if undamped < target {
                return Err(TranslateError::Unreachable(format!(
                    "no damping reaches e = {}: without damping the peer already gives {}",
                    short(target),
                    short(undamped)
                )));
            }
            (0.0, high, false)
        }
    };
    let mut best = (high, at(high)?);
    for _ in 0..MAX_BISECTIONS {
        let middle = 0.5 * (low + high);
        if middle <= low || middle >= high {
            break;
        }
        let e = at(middle)?;
        if (e - target).abs() < (best.1 - target).abs() {
            best = (middle, e);
        }
        if (e - target).abs() <= MATCH {
            break;
        }
        if (e < target) == rising {
            low = middle;
        } else {
            high = middle;
        }
    }
    Ok(best)
}

/// Translates the scene's contact for `peer`, at step `dt` if given.
pub fn translate(scene: &Scene, peer: Peer, dt: Option<f64>) -> Result<Translation, TranslateError> {
    if let Some(dt) = dt
        && !(dt.is_finite() && dt > 0.0)
    {
        return Err(TranslateError::bad(
            "--dt",
            format!("the time step must be a positive number of seconds, got {}", crate::units::short(dt)),
        ));
    }
    let context = Context::new(scene, dt)?;
    let plan = match peer {
        Peer::Lammps => lammps::plan(&context)?,
        Peer::Liggghts => liggghts::plan(&context)?,
        Peer::Mujoco => mujoco::plan(&context)?,
        Peer::Drake => drake::plan(&context)?,
        Peer::Kratos => kratos::plan(&context)?,
        Peer::Adams => adams::plan(&context)?,
    };
    let mut notes = plan.notes;
    if let (Some(nominal), Some(target)) = (context.nominal, context.target)
        && (nominal - target).abs() > 1e-9
    {
        notes.insert(
            0,
            format!(
                "The scene's restitution = {} is `{}`'s nominal e: its map gives a contact whose e is {}, and that is \
                 the e the translation reproduces.",
                crate::units::short(nominal),
                context.law.kind.name(),
                short(target)
            ),
        );
    }
    let step = match (dt, plan.scheme) {
        (Some(dt), Some(scheme)) => Some((scheme, dt)),
        _ => None,
    };
    // The step is checked against the contact's duration first, at the knob's starting value.
    if let (Some(dt), Some(_)) = (dt, plan.scheme) {
        let start = match plan.knob {
            Knob::Fixed(p) => p,
            Knob::Damping { .. } => 0.0,
            Knob::Nominal => context.target.unwrap_or(1.0),
        };
        let duration = duration(&context, &plan.mapping.contact(start))?;
        if let Some(duration) = duration
            && duration / dt > MAX_STEPS_PER_CONTACT
        {
            return Err(TranslateError::bad(
                "--dt",
                format!(
                    "dt = {} takes more than {} steps over the contact's {}: at such a step the scheme's e is the \
                     continuous one to about dt / t_c; translate without --dt",
                    crate::units::brief(dt, "s"),
                    crate::units::brief(MAX_STEPS_PER_CONTACT, ""),
                    crate::units::brief(duration, "s")
                ),
            ));
        }
        if let Some(duration) = duration
            && dt > duration
        {
            let (step, duration) = crate::units::apart(dt, duration, "s");
            return Err(TranslateError::bad(
                "--dt",
                format!(
                    "dt = {step} is larger than the contact's duration {duration}: {} would step over the contact (DEM \
                     codes take a fiftieth of it or less)",
                    peer.title()
                ),
            ));
        }
    }
    let knob = match (context.target, plan.knob) {
        (Some(_), knob) => knob,
        (None, Knob::Fixed(p)) => Knob::Fixed(p),
        (None, _) => unreachable_knob(peer)?,
    };
    let target = context.target.unwrap_or(f64::NAN);
    let mapping = &plan.mapping;
    let (p, _) = tune(target, knob, |p| restitution(&context, &mapping.contact(p), step))?;
    let contact = mapping.contact(p);
    let continuous = restitution(&context, &contact, None)?;
    let at_dt = match step {
        Some(step) => restitution(&context, &contact, Some(step))?,
        None => None,
    };
    if let (Some((scheme, dt)), Some(e)) = (step, at_dt) {
        let fixed = fixed_contact(&context.peer_scene(contact.clone()), contact.separation)?;
        if let Some((low, high)) = fixed.restitution_spread(scheme, dt, PHASES) {
            notes.push(format!(
                "At dt = {} the e of {} ({}) is {} with the first touch on a step boundary; over where the touch falls \
                 within a step it runs from {} to {} ({PHASES} phases), against {} in the continuous limit.",
                crate::units::brief(dt, "s"),
                peer.title(),
                scheme.name(),
                short(e),
                short(low),
                short(high),
                continuous.map_or("no separation".into(), short),
            ));
        }
    }
    if dt.is_some() && step.is_none() {
        notes.push(format!(
            "{} does not step this contact with a fixed-step scheme this program runs: no e at dt is computed; \
             its e approaches the continuous one as its step (or its error tolerance) falls.",
            peer.title()
        ));
    }
    if let Some(target) = context.target {
        let reached = at_dt.or(continuous);
        if let Some(reached) = reached
            && (reached - target).abs() > 1e-6
        {
            notes.push(format!(
                "The target e = {} is met only to {}: the peer's e does not vary continuously with its parameter at \
                 this step (a coarse step moves e in jumps).",
                short(target),
                short(reached)
            ));
        }
    }
    Ok(Translation {
        peer: peer.name(),
        law: plan.law,
        parameters: mapping.parameters(p),
        snippet: mapping.snippet(p, dt),
        restitution_target: context.target,
        restitution_continuous: continuous,
        dt,
        restitution_at_dt: at_dt,
        notes,
    })
}

/// A plan that tunes with no target: a mapping error (every plan fixes its knob when the scene gives no e).
fn unreachable_knob(peer: Peer) -> Result<Knob, TranslateError> {
    Err(TranslateError::Unreachable(format!(
        "internal: the {} plan has no parameter value for a scene that asks for no e",
        peer.title()
    )))
}

/// A number written as a peer's input reads it back exactly: plain for moderate magnitudes, scientific otherwise.
pub fn number(value: f64) -> String {
    crate::calibrate::readable(value)
}

/// Text made safe for one comment line of a peer's input: no line breaks, no control characters, and no `--`
/// (which would end an XML comment).
pub fn comment(text: &str) -> String {
    let line: String = text.chars().map(|c| if c.is_control() { ' ' } else { c }).collect();
    line.replace("--", "- -")
}

/// A number for a note that a user may type or compare (a peer's parameter, an e at a step): six significant digits,
/// without trailing zeros ("0.824106", "0.5", "1.5e-7"; crate::units::short).
pub fn short(value: f64) -> String {
    crate::units::short(value)
}
