//! Calibration (issue #3, part 4): the damping parameter for which a law's *simulated* coefficient of restitution
//! (the velocity ratio) equals a target `E`, and what the law's own published map would have given instead.
//!
//! The method is the first of these that applies (docs/references.md):
//!
//! | law | separation | method | parameter |
//! |---|---|---|---|
//! | hysteresis family | either | exact relation: `x (1 + E) = ln((1 + x)/(1 - E x))` | `alpha = x / v0` |
//! | `kelvin-voigt` | penetration | exact relation: `zeta = -ln E / sqrt(pi² + ln² E)` | `c = 2 zeta sqrt(k m*)` |
//! | `kelvin-voigt` | force | closed form (Schwager & Pöschel 2007), root-found in `zeta` | `c = 2 zeta sqrt(k m*)` |
//! | `tsuji` | penetration | exact relation: `a = -sqrt(5) ln E / sqrt(pi² + ln² E)` | `a` |
//! | `tsuji` | force | closed form (the Kelvin–Voigt `F = 0` one at `zeta = a/sqrt(5)`), root-found in `a` | `a` |
//! | `brilliantov` | either | bracketed root-find on the simulation of the scene | `A` |
//! | `hertz-dashpot` | either | bracketed root-find on the simulation of the scene | `c` |
//! | `mujoco` | either | bracketed root-find on the simulation of the scene | `solref`'s dampratio (or damping) |
//! | `adams-impact` | either | bracketed root-find on the simulation of the scene | `cmax` |
//!
//! The hysteresis family's `e` depends on `x = alpha v0` only, Kelvin–Voigt's on `zeta` only and Tsuji's on `a`
//! only, so these need no scene: the approach speed (hysteresis only) defaults to [`DEFAULT_APPROACH_SPEED`], and
//! Kelvin–Voigt's `c` is left unknown (its `zeta` is still given) because it needs the scene's `k` and `m*`.
//! Brilliantov's `e` depends on the impact speed, the stiffness and the masses, and so do the simulators' laws'
//! (`hertz-dashpot`, `mujoco`, `adams-impact`), so these need a scene. `E = 1` is
//! zero damping for every damped law, scene or not.
//!
//! Whatever the method, the result is checked by one more simulation (of the scene, or of [`default_scene`]) and
//! the simulated `e` is reported beside the target.

use crate::body::Body;
use crate::impact::{Options, SimulationError, simulate_with};
use crate::law::damping::{damping_for_restitution, hysteresis_chi};
use crate::law::{Family, LawKind, Separation};
use crate::reference::{self, Bracket, SeparationCriterion, Stop, brilliantov_c1, illinois};
use crate::scene::{ContactSpec, DampingSpec, OutputSpec, Scene, StiffnessSpec};
use crate::setup::{DEFAULT_SOLREF, Setup};
use crate::units::{apart, brief, short};
use nalgebra::Vector3;
use serde::Serialize;

/// Approach speed (m/s) assumed for the hysteresis family when neither a scene nor `--approach-speed` gives one.
pub const DEFAULT_APPROACH_SPEED: f64 = 1.0;
/// Mass of the sphere of [`default_scene`], kg (it meets an immovable wall, so it is also m*).
pub const DEFAULT_MASS: f64 = 1.0;
/// Stiffness of [`default_scene`], N/m^n (n = 1 for Kelvin–Voigt, 3/2 otherwise).
pub const DEFAULT_STIFFNESS: f64 = 1.0e6;

/// Largest |simulated e - E| a root-find on the simulation may end with, relative to E, beyond the noise floor
/// [`SIMULATION_NOISE`]; a worse match means the target is out of reach (issue #3 asks for 1e-9).
pub const ROOT_FIND_ACCEPTANCE: f64 = 1.0e-9;
/// The absolute error of a simulated e at the default tolerances (atol 1e-12 on the speed in units of v0): no
/// root-find can match E more closely than this.
pub const SIMULATION_NOISE: f64 = 1.0e-12;
/// Largest dimensionless Brilliantov damping b the bracketing tries before declaring the target unreachable.
const MAX_BRILLIANTOV_B: f64 = 1.0e6;
/// The stand-in e of a root-find simulation in which the bodies do not separate (or the integrator gives up).
const NO_RESTITUTION: f64 = -1.0;

/// What to calibrate.
#[derive(Debug, Clone)]
pub struct Request {
    /// The law whose damping is wanted (replaces the scene's law).
    pub law: LawKind,
    /// The target coefficient of restitution `E` (velocity ratio), in (0, 1].
    pub restitution: f64,
    /// Approach speed v0 in m/s (> 0). With a scene it replaces the scene's: both bodies' velocities are scaled by
    /// the same factor, which keeps the normal, the geometry and the masses. Without a scene it is the speed of
    /// [`default_scene`] (default [`DEFAULT_APPROACH_SPEED`]).
    pub approach_speed: Option<f64>,
    /// Which event ends the contact; replaces the scene's (default: the scene's, or penetration without a scene).
    pub separation: Option<Separation>,
    /// The scene that supplies the bodies (masses, speed), stiffness, exponent, separation and solver tolerances.
    /// Its own `restitution`/`damping` is ignored: the calibrated damping replaces it.
    pub scene: Option<Scene>,
}

/// How the damping was found.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Method {
    /// An exact inverse map e -> damping (or `E = 1`: no damping).
    #[serde(rename = "exact relation")]
    ExactRelation,
    /// A bracketed root-find on an exact closed form e(damping).
    #[serde(rename = "closed form")]
    ClosedForm,
    /// A bracketed root-find on the simulated e of the scene.
    #[serde(rename = "root-find on simulation")]
    RootFindOnSimulation,
}

impl Method {
    /// The JSON spelling.
    pub fn name(self) -> &'static str {
        match self {
            Method::ExactRelation => "exact relation",
            Method::ClosedForm => "closed form",
            Method::RootFindOnSimulation => "root-find on simulation",
        }
    }
}

/// A dimensionless form of the damping, on which `e` depends alone (or, for Brilliantov, to leading order).
#[derive(Debug, Clone, Serialize)]
pub struct Dimensionless {
    /// Its definition, e.g. `"chi = alpha v0"`.
    pub symbol: &'static str,
    pub value: f64,
}

/// The numbers of the contact that was calibrated (absent when no scene was given).
#[derive(Debug, Clone, Serialize)]
pub struct ContactSummary {
    /// The scene's title.
    pub title: String,
    /// m*, kg.
    pub effective_mass: f64,
    /// K in N/m^n (k in N/m for Kelvin–Voigt).
    pub stiffness: f64,
    /// n in K d^n.
    pub exponent: f64,
}

/// What the law's own published damping map gives when asked for `E`.
#[derive(Debug, Clone, Serialize)]
pub struct PublishedMap {
    /// The map, as a formula.
    pub map: &'static str,
    /// The damping it assigns, in the law's units (`None` for Kelvin–Voigt without a scene: c needs k and m*).
    pub damping: Option<f64>,
    /// The same in the dimensionless form of [`Calibration::dimensionless`].
    pub dimensionless: f64,
    /// The e that damping actually produces, from the exact relation or closed form (not from a simulation).
    pub restitution: f64,
}

/// The result of a calibration.
#[derive(Debug, Clone, Serialize)]
pub struct Calibration {
    /// Law name, e.g. `"hunt-crossley"`.
    pub law: &'static str,
    /// The target e.
    pub restitution_target: f64,
    /// The damping parameter in the law's own units; `None` for Kelvin–Voigt without a scene.
    pub damping: Option<f64>,
    /// Units of `damping` (docs/laws.md).
    pub damping_units: &'static str,
    /// The damping in dimensionless form.
    pub dimensionless: Dimensionless,
    pub method: Method,
    /// `"penetration"` or `"force"`.
    pub separation: &'static str,
    /// The approach speed used, m/s.
    pub approach_speed: f64,
    /// The calibrated contact; `None` when no scene was given.
    pub scene: Option<ContactSummary>,
    /// Evaluations of e(damping) by the root-find (closed form or simulation); 0 for an exact relation.
    pub iterations: u32,
    /// Simulations run in all, the verification included.
    pub simulations: u32,
    /// e of one simulation with the calibrated damping (of the scene, or of [`default_scene`]); `None` if the
    /// bodies did not separate in it.
    pub restitution_simulated: Option<f64>,
    /// The law's own map for `E`; `None` for a law without one (Brilliantov).
    pub published_map: Option<PublishedMap>,
    /// How the numbers were obtained, in words.
    pub notes: Vec<String>,
}

/// Why a calibration cannot be done.
#[derive(Debug, thiserror::Error)]
pub enum CalibrationError {
    /// `hertz` and `thornton` have nothing to calibrate.
    #[error(
        "the law has no damping to calibrate (`hertz`'s e is always 1; `thornton`'s follows from the speed and the \
         yield pressure): choose a damped law"
    )]
    NoDamping,
    /// The target e is outside (0, 1] or otherwise unusable.
    #[error("{0}")]
    Target(String),
    /// The approach speed is not a finite positive number.
    #[error("the approach speed must be a finite number > 0 m/s, got {}", short(*.0))]
    ApproachSpeed(f64),
    /// The law's e depends on quantities only a scene supplies.
    #[error(
        "`{0}` needs a scene: its e depends on the impact speed, the stiffness and the masses (docs/laws.md), \
         so give a scene"
    )]
    NeedsScene(&'static str),
    /// The scene cannot carry the asked law.
    #[error("{0}")]
    Incompatible(String),
    /// No damping gives the target in this scene.
    #[error("{0}")]
    Unattainable(String),
    /// The scene (with the asked law and speed) could not be simulated.
    #[error(transparent)]
    Simulation(#[from] SimulationError),
}

impl CalibrationError {
    /// Whether the error is the user's input (exit status 2) rather than a failure of the program.
    pub fn is_bad_input(&self) -> bool {
        !matches!(self, CalibrationError::Simulation(SimulationError::Integration(_) | SimulationError::Compression(_)))
    }
}

/// A calibration asked for by name, as `impact calibrate` and Python's `impact.calibrate` take it: `law` and
/// `separation` spelled as in a scene (`None`: the scene's), `scene` already read (its path for messages in
/// `shown`). Bad input is [`Refusal::BadInput`] (exit 2), with the command's message.
pub fn from_arguments(
    law: Option<&str>,
    restitution: f64,
    approach_speed: Option<f64>,
    separation: Option<&str>,
    scene: Option<(Scene, String)>,
) -> Result<Calibration, Refusal> {
    let law = match law {
        Some(name) => Some(LawKind::from_name(name).ok_or_else(|| {
            let name = crate::text::cut(name, crate::text::MESSAGE_CHARS);
            Refusal::BadInput(format!(
                "unknown law `{name}` for --law; expected one of {}",
                LawKind::names().join(", ")
            ))
        })?),
        None => None,
    };
    let separation = match separation {
        None => None,
        Some("penetration") => Some(Separation::Penetration),
        Some("force") => Some(Separation::Force),
        Some(other) => {
            let other = crate::text::cut(other, crate::text::MESSAGE_CHARS);
            return Err(Refusal::BadInput(format!(
                "--separation must be \"penetration\" or \"force\", got \"{other}\""
            )));
        }
    };
    let (scene, shown) = match scene {
        Some((scene, shown)) => (Some(scene), Some(shown)),
        None => (None, None),
    };
    let law = match (law, &scene) {
        (Some(law), _) => law,
        (None, Some(scene)) => scene.contact.law,
        (None, None) => return Err(Refusal::BadInput("give --law LAW (or a SCENE whose law to calibrate)".into())),
    };
    let request = Request { law, restitution, approach_speed, separation, scene };
    calibrate(&request).map_err(|error| Refusal::of(error, shown.as_deref(), restitution))
}

/// Why [`from_arguments`] gave no calibration, in the command's words.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Refusal {
    /// The arguments or the scene (exit status 2).
    #[error("{0}")]
    BadInput(String),
    /// The calibration could not finish (exit status 1): the message, with the scene's path before it if any.
    #[error("{0}")]
    Failed(String),
}

impl Refusal {
    /// The error as a message naming the scene where it concerns the scene.
    fn of(error: CalibrationError, scene: Option<&str>, restitution: f64) -> Refusal {
        let about_scene = matches!(
            error,
            CalibrationError::Incompatible(_) | CalibrationError::Unattainable(_) | CalibrationError::Simulation(_)
        );
        let scene = scene.filter(|_| about_scene);
        if error.is_bad_input() {
            return Refusal::BadInput(match (scene, &error) {
                (Some(path), _) => format!("{path}: {error}"),
                (None, CalibrationError::Target(_)) => format!("--restitution {}: {error}", given_target(restitution)),
                (None, CalibrationError::ApproachSpeed(_)) => format!("--approach-speed: {error}"),
                (None, CalibrationError::NoDamping) => format!("{error} with --law"),
                (None, CalibrationError::NeedsScene(_)) => {
                    format!("{error} file (and --approach-speed to set its speed)")
                }
                (None, _) => error.to_string(),
            });
        }
        Refusal::Failed(match scene {
            Some(path) => format!("{path}: {error}"),
            None => error.to_string(),
        })
    }
}

/// Finds the damping of `request.law` that gives `request.restitution` (see the module docs for the method).
pub fn calibrate(request: &Request) -> Result<Calibration, CalibrationError> {
    let (law, target) = (request.law, request.restitution);
    check_target(law, target)?;
    if let Some(speed) = request.approach_speed
        && !(speed > 0.0 && speed.is_finite())
    {
        return Err(CalibrationError::ApproachSpeed(speed));
    }
    if matches!(law.family(), Family::Viscoelastic | Family::Dashpot | Family::Impedance | Family::Ramp)
        && request.scene.is_none()
        && target < 1.0
    {
        return Err(CalibrationError::NeedsScene(law.name()));
    }
    let scene = match &request.scene {
        Some(scene) => adapt_scene(scene, request)?,
        None => default_scene(
            law,
            request.approach_speed.unwrap_or(DEFAULT_APPROACH_SPEED),
            request.separation.unwrap_or(Separation::Penetration),
        ),
    };
    let contact = Contact::new(&scene)?;
    let mut simulations = Simulations { scene: &scene, count: 0 };
    let found = solve(law, target, &contact, &mut simulations)?;
    let restitution_simulated = simulations.restitution(found.damping)?;

    let has_scene = request.scene.is_some();
    let known = |damping: f64| (has_scene || law.family() != Family::Linear).then_some(damping);
    let mut notes = found.notes;
    if !has_scene {
        notes.push(default_scene_note(law, &contact, request.approach_speed.is_some(), found.damping));
    }
    if restitution_simulated.is_none() {
        notes.push("the verification simulation did not separate (see `impact run` on the scene)".into());
    }
    Ok(Calibration {
        law: law.name(),
        restitution_target: target,
        damping: known(found.damping),
        damping_units: contact.damping_units(),
        dimensionless: Dimensionless { symbol: dimensionless_symbol(law), value: contact.dimensionless(found.damping) },
        method: found.method,
        separation: contact.separation.name(),
        approach_speed: contact.approach_speed,
        scene: has_scene.then(|| ContactSummary {
            title: scene.title.clone(),
            effective_mass: contact.effective_mass,
            stiffness: contact.stiffness,
            exponent: scene.contact.exponent,
        }),
        iterations: found.iterations,
        simulations: simulations.count,
        restitution_simulated,
        published_map: published_map(law, target, &contact, has_scene),
        notes,
    })
}

/// The law's own map asked for `target` (as a scene's `restitution = E` would use it), and the e it really gives,
/// from the exact relation or closed form of its family.
fn published_map(law: LawKind, target: f64, contact: &Contact, has_scene: bool) -> Option<PublishedMap> {
    let damping =
        damping_for_restitution(law, target, contact.stiffness, contact.effective_mass, contact.approach_speed).ok()?;
    let (dimensionless, restitution) = match law.family() {
        Family::Hysteresis => {
            let chi = hysteresis_chi(law, target).ok()?;
            (chi, reference::hunt_crossley_restitution(chi))
        }
        Family::Linear => {
            let zeta = reference::kelvin_voigt_zeta(target);
            (zeta, reference::kelvin_voigt(zeta, contact.separation)?.restitution)
        }
        Family::Tsuji => (damping / 5f64.sqrt(), reference::tsuji(damping, contact.separation)?.restitution),
        Family::Elastic
        | Family::Viscoelastic
        | Family::Plastic
        | Family::Dashpot
        | Family::Impedance
        | Family::Ramp => {
            return None;
        }
    };
    let damping = (has_scene || law.family() != Family::Linear).then_some(damping);
    Some(PublishedMap { map: law.info().map, damping, dimensionless, restitution })
}

/// What the calibration assumed without a scene.
fn default_scene_note(law: LawKind, contact: &Contact, speed_given: bool, damping: f64) -> String {
    let scene = format!(
        "the default scene ({} sphere on an immovable wall, stiffness {}, v0 = {})",
        brief(DEFAULT_MASS, "kg"),
        brief(DEFAULT_STIFFNESS, if law.family() == Family::Linear { "N/m" } else { "N/m^1.5" }),
        brief(contact.approach_speed, "m/s")
    );
    match law.family() {
        Family::Hysteresis => format!(
            "no scene: alpha = chi / v0 at v0 = {} ({}); e depends on chi = alpha v0 alone, so this alpha holds for \
             any masses and stiffness at that speed; verified on {scene}",
            brief(contact.approach_speed, "m/s"),
            if speed_given { "--approach-speed" } else { "the default; give --approach-speed or a scene" }
        ),
        Family::Linear => format!(
            "no scene: c = 2 zeta sqrt(k m*) needs the scene's k and m*, so only zeta is given (e depends on zeta \
             alone); verified on {scene}, where c = {}",
            brief(damping, "N s/m")
        ),
        _ => format!("no scene: the damping is dimensionless and e depends on it alone; verified on {scene}"),
    }
}

/// The target must be a finite e in (0, 1]; e = 0 is reachable by no damping that still lets the bodies part.
fn check_target(law: LawKind, target: f64) -> Result<(), CalibrationError> {
    if matches!(law.family(), Family::Elastic | Family::Plastic) {
        return Err(CalibrationError::NoDamping);
    }
    if target == 0.0 {
        let why = match law.family() {
            Family::Hysteresis if hysteresis_chi(law, 0.0).is_err() => format!(
                "the map of `{}` ({}) is undefined at e = 0, and no finite damping of the hysteresis family gives \
                 e = 0 (e(x) > 0 for every x = alpha v0)",
                law.name(),
                law.info().map
            ),
            Family::Hysteresis => {
                "no finite damping of the hysteresis family gives e = 0 (e(x) > 0 for every x)".into()
            }
            Family::Linear | Family::Tsuji => "e = 0 is critical damping, where the bodies never separate (with \
                 separation = \"penetration\"), or infinite damping (with separation = \"force\")"
                .into(),
            _ => "e = 0 would need infinite damping".into(),
        };
        return Err(CalibrationError::Target(format!(
            "e = 0 cannot be calibrated: {why}; ask for a small positive e instead"
        )));
    }
    if !(target > 0.0 && target <= 1.0) {
        return Err(CalibrationError::Target(format!(
            "the target e must be a coefficient of restitution in (0, 1], got {}",
            given_target(target)
        )));
    }
    if target < MIN_TARGET {
        return Err(CalibrationError::Target(format!(
            "e = {} is below the smallest e that can be simulated, about {}: the damping it needs makes the \
             restitution creep for longer than any integration can follow (the scene limit on the damping is {} \
             times the elastic force)",
            apart(target, MIN_TARGET, "").0,
            brief(MIN_TARGET, ""),
            brief(crate::setup::MAX_DAMPING_RATIO, "")
        )));
    }
    Ok(())
}

/// The smallest target e: below it the damping passes the scene limit [`crate::setup::MAX_DAMPING_RATIO`] (for the
/// hysteresis family e(x) ~ ln(x)/x, about 2e-9 at x = 1e10).
pub const MIN_TARGET: f64 = 1e-10;

/// The scene with the asked law, separation and approach speed, and no damping yet.
fn adapt_scene(scene: &Scene, request: &Request) -> Result<Scene, CalibrationError> {
    let mut scene = scene.clone();
    check_law_fits(&scene.contact, request.law)?;
    scene.contact.law = request.law;
    scene.contact.damping = DampingSpec::Parameter(0.0);
    if let Some(separation) = request.separation {
        scene.contact.separation = separation;
    }
    scene.output = OutputSpec::default();
    if let Some(speed) = request.approach_speed {
        let current = Setup::new(&scene).map_err(SimulationError::Setup)?.approach_speed;
        let factor = speed / current;
        for body in &mut scene.bodies {
            body.velocity *= factor;
        }
    }
    Ok(scene)
}

/// The stiffness rules of docs/scene.md for the asked law, against the scene's `[contact]`.
fn check_law_fits(contact: &ContactSpec, law: LawKind) -> Result<(), CalibrationError> {
    let name = law.name();
    let n = contact.exponent;
    let problem = match law.family() {
        Family::Linear if contact.stiffness == StiffnessSpec::Hertz => {
            Some(format!("`{name}` needs a numeric `stiffness` k in N/m, but the scene has stiffness = \"hertz\""))
        }
        Family::Linear if n != 1.0 => Some(format!(
            "`{name}` is linear (exponent 1), but the scene's stiffness is for exponent {n} (N/m^{n})",
            n = apart(n, 1.0, "").0
        )),
        Family::Tsuji | Family::Viscoelastic if n != 1.5 => Some(format!(
            "`{name}` fixes the exponent at 3/2, but the scene's stiffness is for exponent {n} (N/m^{n})",
            n = apart(n, 1.5, "").0
        )),
        _ => None,
    };
    match problem {
        Some(message) => Err(CalibrationError::Incompatible(message + "; use a scene written for this law")),
        None => Ok(()),
    }
}

/// A scene for the laws whose e does not depend on the scene: a [`DEFAULT_MASS`] kg sphere closing at
/// `approach_speed` on an immovable wall, with numeric stiffness [`DEFAULT_STIFFNESS`] (exponent 1 for
/// Kelvin–Voigt, 3/2 otherwise), default solver tolerances and no damping.
pub fn default_scene(law: LawKind, approach_speed: f64, separation: Separation) -> Scene {
    let body = |name: &str, mass: f64, radius: f64, speed: f64| Body {
        name: name.into(),
        mass,
        radius,
        velocity: Vector3::new(speed, 0.0, 0.0),
        position: None,
        angular_velocity: Vector3::zeros(),
        density: None,
        inertia: Body::solid_sphere_inertia(mass, radius),
        inertia_given: None,
        inertia_tensor: None,
        contact_offset: Vector3::zeros(),
        pivot: None,
        young: None,
        poisson: None,
        yield_stress: None,
        spheres: Vec::new(),
    };
    let exponent = if law.family() == Family::Linear { 1.0 } else { 1.5 };
    Scene {
        title: "default calibration scene".into(),
        bodies: [body("sphere", DEFAULT_MASS, 0.01, approach_speed), body("wall", f64::INFINITY, f64::INFINITY, 0.0)],
        contact: ContactSpec {
            law,
            damping: DampingSpec::Parameter(0.0),
            stiffness: StiffnessSpec::Value(DEFAULT_STIFFNESS),
            exponent,
            exponent_given: None,
            separation,
            friction: 0.0,
            tangential_stiffness: crate::scene::TangentialStiffnessSpec::Mindlin,
            tangential_damping: 0.0,
            tangential_unloading: crate::scene::TangentialUnloading::None,
            friction_cap: crate::scene::FrictionCap::Compressive,
            yield_pressure: None,
            solref: None,
            solimp: None,
            cmax: None,
            dmax: None,
            normal: None,
            normal_given: None,
        },
        solver: crate::scene::SolverSpec::default(),
        output: OutputSpec::default(),
    }
}

/// The scene with its damping parameter set to `damping` (law units).
/// For `mujoco` the damping is `solref`'s second entry: the dampratio of `[timeconst, dampratio]`, or the damping
/// per unit mass of `[-stiffness, -damping]` (entered as `-damping`); the first entry and `solimp` are kept.
pub fn with_damping(scene: &Scene, damping: f64) -> Scene {
    let mut scene = scene.clone();
    if scene.contact.law.family() == Family::Impedance {
        let [first, _] = scene.contact.solref.unwrap_or(DEFAULT_SOLREF);
        scene.contact.solref = Some([first, if first > 0.0 { damping } else { -damping }]);
    } else {
        scene.contact.damping = DampingSpec::Parameter(damping);
    }
    scene
}

/// The contact numbers every method needs.
struct Contact {
    law: LawKind,
    approach_speed: f64,
    effective_mass: f64,
    stiffness: f64,
    /// L = (m* v0² / K)^(1/(n+1)), m: the contact's penetration scale.
    length: f64,
    separation: Separation,
    /// The scene's `solref` (MuJoCo's default if it gives none); unused by the other laws.
    solref: [f64; 2],
}

impl Contact {
    fn new(scene: &Scene) -> Result<Contact, CalibrationError> {
        let setup = Setup::new(scene).map_err(SimulationError::Setup)?;
        Ok(Contact {
            law: scene.contact.law,
            approach_speed: setup.approach_speed,
            effective_mass: setup.effective_mass,
            stiffness: setup.law.stiffness,
            length: setup.scales.length,
            separation: scene.contact.separation,
            solref: scene.contact.solref.unwrap_or(DEFAULT_SOLREF),
        })
    }

    /// A dashpot's c per unit of the damping ratio at the contact's scales, 2 m* v0 / L, N s/m: c = 2 zeta sqrt(k m*)
    /// for a linear spring (L = v0 sqrt(m*/k)), and the spring's stiffness at the penetration scale for another.
    fn critical_dashpot(&self) -> f64 {
        2.0 * self.effective_mass * self.approach_speed / self.length
    }

    /// sqrt(k m*), N s/m: c = 2 zeta sqrt(k m*) for Kelvin–Voigt.
    fn critical_half(&self) -> f64 {
        (self.stiffness * self.effective_mass).sqrt()
    }

    /// The damping parameter (law units) in the dimensionless form of [`dimensionless_symbol`].
    fn dimensionless(&self, damping: f64) -> f64 {
        match self.law.family() {
            Family::Hysteresis => damping * self.approach_speed,
            Family::Linear => damping / (2.0 * self.critical_half()),
            Family::Tsuji => damping / 5f64.sqrt(),
            // b = (3/2) A (K/m*)^(2/5) v0^(1/5) (docs/references.md).
            Family::Viscoelastic => damping * self.brilliantov_b_per_a(),
            Family::Dashpot | Family::Ramp => damping / self.critical_dashpot(),
            Family::Impedance => damping * self.mujoco_ratio_per_damping(),
            Family::Elastic | Family::Plastic => 0.0,
        }
    }

    /// MuJoCo's damping ratio per unit of `solref`'s second entry (as a positive number): 1 for a dampratio, and
    /// 1/(2 sqrt(stiffness)) for `[-stiffness, -damping]` (b = damping/d_max, k = stiffness/d_max² per unit mass).
    fn mujoco_ratio_per_damping(&self) -> f64 {
        let [first, _] = self.solref;
        if first > 0.0 { 1.0 } else { 0.5 / (-first).sqrt() }
    }

    /// What the calibrated number is, and its units.
    fn damping_units(&self) -> &'static str {
        match self.law.family() {
            Family::Impedance if self.solref[0] > 0.0 => "dampratio: solref = [timeconst, dampratio], timeconst kept",
            Family::Impedance => "damping per unit mass in 1/s: solref = [-stiffness, -damping], stiffness kept",
            _ => self.law.info().damping_units,
        }
    }

    /// b / A, 1/s.
    fn brilliantov_b_per_a(&self) -> f64 {
        1.5 * (self.stiffness / self.effective_mass).powf(0.4) * self.approach_speed.powf(0.2)
    }
}

fn dimensionless_symbol(law: LawKind) -> &'static str {
    match law.family() {
        Family::Hysteresis => "chi = alpha v0",
        Family::Linear => "zeta = c / (2 sqrt(k m*))",
        Family::Tsuji => "zeta = a / sqrt(5)",
        Family::Viscoelastic => "b = (3/2) A (K/m*)^(2/5) v0^(1/5)",
        Family::Dashpot => "zeta = c L / (2 m* v0), L = (m* v0² / K)^(1/(n+1))",
        Family::Ramp => "zeta = c_max L / (2 m* v0), L = (m* v0² / K)^(1/(n+1))",
        Family::Impedance => "zeta = b / (2 sqrt(k)), MuJoCo's damping ratio",
        Family::Elastic | Family::Plastic => "-",
    }
}

/// Simulations of one scene at varying damping, counted.
struct Simulations<'a> {
    scene: &'a Scene,
    count: u32,
}

impl Simulations<'_> {
    /// The simulated e (velocity ratio) with `damping`; `None` if the bodies do not separate.
    fn restitution(&mut self, damping: f64) -> Result<Option<f64>, CalibrationError> {
        self.count += 1;
        // (Only e is read: no verdicts on the idealisation, whose trial would triple the runs.)
        let options = Options { idealisation: false, ..Options::default() };
        let report = simulate_with(&with_damping(self.scene, damping), options)?.report;
        Ok(report.contact.restitution_velocity_ratio)
    }
}

/// The calibrated damping (law units, for the scene in use) and how it was found.
struct Found {
    damping: f64,
    method: Method,
    iterations: u32,
    notes: Vec<String>,
}

fn solve(
    law: LawKind,
    target: f64,
    contact: &Contact,
    simulations: &mut Simulations,
) -> Result<Found, CalibrationError> {
    let exact =
        |damping: f64, note: String| Found { damping, method: Method::ExactRelation, iterations: 0, notes: vec![note] };
    if target == 1.0 {
        return Ok(exact(0.0, "e = 1 is the undamped law: damping 0".into()));
    }
    let force = contact.separation == Separation::Force;
    match law.family() {
        Family::Hysteresis => {
            let chi = reference::hunt_crossley_chi(target).expect("target checked to lie in (0, 1)");
            Ok(exact(
                chi / contact.approach_speed,
                "alpha = chi / v0, chi the root of chi (1 + e) = ln((1 + chi)/(1 - e chi)) (exact for the whole \
                 hysteresis family, any n, K, m*; docs/references.md#the-hunt-crossley-family)"
                    .into(),
            ))
        }
        Family::Linear if !force => Ok(exact(
            2.0 * reference::kelvin_voigt_zeta(target) * contact.critical_half(),
            "c = 2 zeta sqrt(k m*), zeta = -ln e / sqrt(pi^2 + ln^2 e) (exact with separation at d = 0; \
             docs/references.md#kelvin-voigt)"
                .into(),
        )),
        Family::Tsuji if !force => Ok(exact(
            reference::tsuji_damping(target),
            "a = -sqrt(5) ln e / sqrt(pi^2 + ln^2 e) (exact with separation at d = 0; docs/references.md#tsuji)".into(),
        )),
        Family::Linear => {
            let e_of =
                |zeta: f64| reference::kelvin_voigt(zeta, SeparationCriterion::Force).map_or(0.0, |r| r.restitution);
            let (zeta, iterations) = closed_form_root(e_of, reference::kelvin_voigt_zeta(target), target);
            Ok(Found {
                damping: 2.0 * zeta * contact.critical_half(),
                method: Method::ClosedForm,
                iterations,
                notes: vec![format!(
                    "zeta root-found ({iterations} evaluations) on the exact e of separation at F = 0 (Schwager & \
                     Pöschel 2007; docs/references.md#kelvin-voigt), c = 2 zeta sqrt(k m*)"
                )],
            })
        }
        Family::Tsuji => {
            let e_of = |a: f64| reference::tsuji(a, SeparationCriterion::Force).map_or(0.0, |r| r.restitution);
            let (a, iterations) = closed_form_root(e_of, reference::tsuji_damping(target), target);
            Ok(Found {
                damping: a,
                method: Method::ClosedForm,
                iterations,
                notes: vec![format!(
                    "a root-found ({iterations} evaluations) on the exact e of separation at F = 0 (the Kelvin–Voigt \
                     closed form at zeta = a/sqrt(5); docs/references.md#tsuji)"
                )],
            })
        }
        Family::Viscoelastic => {
            // First guess from the series e = 1 - C1 b + ... (docs/references.md).
            let b_per_a = contact.brilliantov_b_per_a();
            let search = Search { law: "brilliantov", symbol: "A", unit: "s", per_damping: b_per_a, limit: "b" };
            by_simulation(target, (1.0 - target) / brilliantov_c1() / b_per_a, &search, simulations)
        }
        // A constant dashpot: first guess from Kelvin–Voigt's map with the spring's stiffness at the penetration
        // scale (K L^(n-1)), then the simulated e itself.
        Family::Dashpot => {
            let per_c = 1.0 / contact.critical_dashpot();
            let guess = reference::kelvin_voigt_zeta(target) * contact.critical_dashpot();
            let search = Search { law: "hertz-dashpot", symbol: "c", unit: "N s/m", per_damping: per_c, limit: "zeta" };
            by_simulation(target, guess, &search, simulations)
        }
        // MuJoCo: solref's second entry (its damping ratio, or its damping per unit mass), from the linear
        // spring–dashpot's ratio for e; ADAMS: c_max from the same guess as a constant dashpot's.
        Family::Impedance => {
            let per = contact.mujoco_ratio_per_damping();
            let guess = reference::kelvin_voigt_zeta(target).max(1e-6) / per;
            let (symbol, unit) = if contact.solref[0] > 0.0 { ("dampratio", "") } else { ("-solref[1]", "1/s") };
            let search = Search { law: "mujoco", symbol, unit, per_damping: per, limit: "zeta" };
            by_simulation(target, guess, &search, simulations)
        }
        Family::Ramp => {
            let per_c = 1.0 / contact.critical_dashpot();
            let guess = reference::kelvin_voigt_zeta(target).max(1e-6) * contact.critical_dashpot();
            let search =
                Search { law: "adams-impact", symbol: "cmax", unit: "N s/m", per_damping: per_c, limit: "zeta" };
            by_simulation(target, guess, &search, simulations)
        }
        Family::Elastic | Family::Plastic => Err(CalibrationError::NoDamping),
    }
}

/// Root of the decreasing closed form `e_of(p) = target` for `p >= 0` (`e_of(0) = 1`), bracketed from
/// `[0, start]` with `start` doubled until it brackets; returns the root and the number of evaluations.
fn closed_form_root(e_of: impl Fn(f64) -> f64, start: f64, target: f64) -> (f64, u32) {
    let mut evaluations = 0;
    let mut e = |p: f64| {
        evaluations += 1;
        e_of(p) - target
    };
    let mut hi = start.max(f64::MIN_POSITIVE);
    let mut f_hi = e(hi);
    while f_hi > 0.0 && hi < 1e300 {
        hi *= 2.0;
        f_hi = e(hi);
    }
    let bracket = Bracket { lo: 0.0, f_lo: 1.0 - target, hi, f_hi };
    let stop = Stop { residual: 0.0, relative_width: 4.0 * f64::EPSILON, max_evaluations: 400 };
    let root = illinois(|p| Ok::<_, ()>(e(p)), bracket, stop).expect("infallible");
    (root.x, evaluations)
}

/// Brilliantov's A by a bracketed root-find on the simulated e of the scene. A contact that does not separate, or
/// whose simulation the integrator gives up on (it turns stiff in the long creep of a heavily damped contact),
/// counts as [`NO_RESTITUTION`]: below every e (more damping never makes the bodies part again), and never taken
/// for a match however small the target.
/// What a root-find on the simulated e searches: the law, its damping's symbol and unit, and the dimensionless
/// measure of the damping per unit of it (`limit` names it) that bounds the search at [`MAX_BRILLIANTOV_B`].
struct Search {
    law: &'static str,
    symbol: &'static str,
    unit: &'static str,
    per_damping: f64,
    limit: &'static str,
}

/// The damping whose simulated e is `target`, from a first `guess`: grown or shrunk by 4 until bracketed, then
/// Illinois with a bisection safeguard on the simulated velocity ratio.
fn by_simulation(
    target: f64,
    guess: f64,
    search: &Search,
    simulations: &mut Simulations,
) -> Result<Found, CalibrationError> {
    let mut evaluations = 0;
    let mut failure: Option<(f64, String)> = None;
    let mut residual = |a: f64| -> Result<f64, CalibrationError> {
        evaluations += 1;
        match simulations.restitution(a) {
            Ok(e) => Ok(e.unwrap_or(NO_RESTITUTION) - target),
            Err(CalibrationError::Simulation(SimulationError::Integration(error))) => {
                if failure.as_ref().is_none_or(|(at, _)| a < *at) {
                    failure = Some((a, error.to_string()));
                }
                Ok(NO_RESTITUTION - target)
            }
            Err(error) => Err(error),
        }
    };
    let Search { law, symbol, unit, per_damping, limit } = *search;
    let f_guess = residual(guess)?;
    let mut bracket = Bracket { lo: 0.0, f_lo: 1.0 - target, hi: guess, f_hi: f_guess };
    if f_guess > 0.0 {
        bracket = Bracket { lo: guess, f_lo: f_guess, hi: guess, f_hi: f_guess };
        while bracket.f_hi > 0.0 {
            if bracket.hi * per_damping > MAX_BRILLIANTOV_B {
                let (target, reached) = apart(target, bracket.f_hi + target, "");
                return Err(CalibrationError::Unattainable(format!(
                    "no damping {symbol} up to {limit} = {} brings the simulated e of `{law}` down to {target} in \
                     this scene (e = {reached} at {symbol} = {})",
                    brief(MAX_BRILLIANTOV_B, ""),
                    brief(bracket.hi, unit)
                )));
            }
            (bracket.lo, bracket.f_lo) = (bracket.hi, bracket.f_hi);
            bracket.hi *= 4.0;
            bracket.f_hi = residual(bracket.hi)?;
        }
    } else {
        let mut a = guess;
        for _ in 0..40 {
            a *= 0.25;
            let f = residual(a)?;
            if f > 0.0 {
                (bracket.lo, bracket.f_lo) = (a, f);
                break;
            }
            (bracket.hi, bracket.f_hi) = (a, f);
        }
    }
    let stop = Stop { residual: 1e-15, relative_width: 1e-14, max_evaluations: 200 };
    let root = illinois(&mut residual, bracket, stop)?;
    if root.residual.abs() > ROOT_FIND_ACCEPTANCE * target + SIMULATION_NOISE {
        let (lo, hi) = (root.bracket.lo, root.bracket.hi);
        let beyond = match &failure {
            Some((at, why)) if *at <= hi => format!("the simulation fails ({why})"),
            _ if root.bracket.f_hi == NO_RESTITUTION - target => "the bodies no longer separate".into(),
            _ => format!("e = {}", brief(root.bracket.f_hi + target, "")),
        };
        let (target, reached) = apart(target, root.bracket.f_lo + target, "");
        let (lo, hi) = apart(lo, hi, unit);
        return Err(CalibrationError::Unattainable(format!(
            "the simulated e of `{law}` in this scene cannot be made {target}: the smallest e reached is {reached} at \
             {symbol} = {lo}, and at {symbol} = {hi} {beyond}"
        )));
    }
    Ok(Found {
        damping: root.x,
        method: Method::RootFindOnSimulation,
        iterations: evaluations,
        notes: vec![format!(
            "{symbol} root-found ({evaluations} simulations, Illinois with a bisection safeguard) on the simulated \
             velocity ratio of the scene; |e - E| = {} there",
            brief(root.residual.abs(), "")
        )],
    })
}

/// A target e as a message echoes it: in short form, with the digits that keep it outside (0, 1] (1.0000001).
pub(crate) fn given_target(target: f64) -> String {
    crate::units::short_outside(target, |e| e > 0.0 && e <= 1.0)
}

/// A number as a reader wants it: plain for moderate magnitudes, scientific otherwise; either way the shortest
/// text that reads back as the same `f64`.
pub(crate) fn readable(x: f64) -> String {
    if x != 0.0 && x.is_finite() && !(1e-3..1e6).contains(&x.abs()) { format!("{x:e}") } else { format!("{x}") }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn closed_form_root_inverts_the_kelvin_voigt_force_separation() {
        // zeta = 0.3 separating at F = 0 gives e = 0.4509754529 (docs/references.md).
        let e_of = |zeta: f64| reference::kelvin_voigt(zeta, SeparationCriterion::Force).unwrap().restitution;
        let (zeta, _) = closed_form_root(e_of, 0.1, 0.4509754529);
        assert!((zeta - 0.3).abs() < 2e-10, "{zeta}");
    }

    #[test]
    fn readable_numbers_read_back() {
        assert_eq!(readable(0.5), "0.5");
        assert_eq!(readable(1e-11), "1e-11");
        assert_eq!(readable(3.366625519021434e8), "3.366625519021434e8");
        assert_eq!(readable(0.0), "0");
    }
}
