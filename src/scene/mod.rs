//! The scene: what a user asks to simulate, typed and validated.
//!
//! `file` reads the TOML format of docs/scene.md into raw, span-carrying structs; `validate` turns those into a
//! [`Scene`] whose every value has been checked (`rules`), or a [`SceneError`] naming the file, the key and the line.
//!
//! The physics-level rules (placement, first contact, the law at the contact's scales) are [`crate::setup`]'s, the
//! layer above: reading a scene with every rule checked — [`Scene::load`], [`Scene::parse`], [`Scene::check`], and
//! `setup::load_any` and `setup::parse_any` for either kind — is defined there, on the [`Read`] this module gives.

mod error;
mod file;
mod rules;
mod validate;
pub mod world;

pub use error::{SceneError, SetupError};
pub use rules::RuleGroups;
pub use validate::Read;
pub use world::{DampingMap, PairSpec, Site, WorldScene, WorldSpec};

use crate::body::Body;
use crate::integrate::Tolerances;
use crate::law::{LawKind, Separation};
use nalgebra::Vector3;
use std::path::{Path, PathBuf};

/// A validated scene (SI units).
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// Title for reports and figures (defaults to the file's stem).
    pub title: String,
    /// The two bodies, in scene order (body 1, body 2).
    pub bodies: [Body; 2],
    pub contact: ContactSpec,
    /// The integration method and its tolerances.
    pub solver: SolverSpec,
    pub output: OutputSpec,
}

/// A scene of either kind: a two-body impact (today's report), or a world run (docs/scene.md#worlds).
#[derive(Debug, Clone, PartialEq)]
pub enum Parsed {
    Impact(Box<Scene>),
    World(Box<WorldScene>),
}

/// Whether scene text is a world scene (a `[world]` table, `[[pair]]` tables or more than two bodies), read as
/// loosely as a sweep's base scene may be written (values left out for the sweep to set).
pub fn is_world(text: &str) -> bool {
    let Ok(table) = text.parse::<toml::Table>() else { return false };
    let bodies = table.get("bodies").and_then(toml::Value::as_array).map_or(0, Vec::len);
    table.contains_key("world") || table.contains_key("pair") || bodies > 2
}

/// Reads scene text of either kind: its form and every value rule, errors located; `path` names the source in errors
/// and gives the default title. The physics-level rules of a two-body scene are still to check (`setup::parse_any`).
pub fn read_any<'a>(text: &'a str, path: &Path) -> Result<Read<'a, Parsed>, SceneError> {
    validate::any(text, path)
}

/// A rule found broken while running a scene (a world's contact at its own speed), located in the scene file: its
/// line read off the file again.
pub fn located(path: &Path, error: SetupError) -> SceneError {
    let text = std::fs::read_to_string(path).unwrap_or_default();
    validate::located(&text, path, error)
}

/// A rule found broken while running a scene that came as text (Python's `impact.run` of TOML text or a dict),
/// located in that text.
pub fn located_in(text: &str, path: &Path, error: SetupError) -> SceneError {
    validate::located(text, path, error)
}

/// How the law's damping is given.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DampingSpec {
    /// No damping: the elastic `hertz` law.
    None,
    /// A nominal coefficient of restitution, turned into damping by the law's own map.
    Restitution(f64),
    /// The law's damping parameter itself, in its own units (docs/scene.md).
    Parameter(f64),
}

/// Where the stiffness comes from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum StiffnessSpec {
    /// K = (4/3) E* sqrt(R*) from the bodies.
    Hertz,
    /// A given K in N/m^n.
    Value(f64),
}

impl StiffnessSpec {
    /// The spec a scene's `stiffness` value writes: `"hertz"` or a number; `Err` gives what was written instead.
    pub fn written(value: &toml::Value) -> Result<StiffnessSpec, String> {
        match value {
            toml::Value::String(s) if s == "hertz" => Ok(StiffnessSpec::Hertz),
            toml::Value::Float(k) => Ok(StiffnessSpec::Value(*k)),
            toml::Value::Integer(k) => Ok(StiffnessSpec::Value(*k as f64)),
            other => Err(echoed(other)),
        }
    }
}

/// A TOML value as a message echoes it: as written, but each number in short form (TOML writes 1e9 back as
/// "1000000000.0"; this as "1e9"): `{ value = 1e9 }`, `[1.5, "x"]`.
/// Nesting deeper than a few levels, and more than a few entries, are elided ("[[[...]]]", "[1, 2, 3, ...]"): the
/// message cuts it anyway.
pub fn echoed(value: &toml::Value) -> String {
    echoed_within(value, 4)
}

fn echoed_within(value: &toml::Value, depth: usize) -> String {
    const ENTRIES: usize = 12;
    let more = |count: usize| if count > ENTRIES { ", ..." } else { "" };
    match value {
        toml::Value::Float(x) => crate::units::short_exact(*x),
        toml::Value::Array(_) | toml::Value::Table(_) if depth == 0 => "...".into(),
        toml::Value::Array(items) => {
            let shown: Vec<String> = items.iter().take(ENTRIES).map(|v| echoed_within(v, depth - 1)).collect();
            format!("[{}{}]", shown.join(", "), more(items.len()))
        }
        toml::Value::Table(table) => {
            let shown: Vec<String> =
                table.iter().take(ENTRIES).map(|(k, v)| format!("{k} = {}", echoed_within(v, depth - 1))).collect();
            format!("{{ {}{} }}", shown.join(", "), more(table.len()))
        }
        other => other.to_string(),
    }
}

/// The `[solver]` table.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SolverSpec {
    /// Which integration path to take.
    pub method: Method,
    /// Integrator tolerances on the scaled state.
    pub tolerances: Tolerances,
    /// The fixed-step schemes' time step, s (`dt`): given with `"verlet"` and `"symplectic-euler"`, and only with
    /// them.
    pub dt: Option<f64>,
}

/// The integration path a scene asks for (`[solver] method`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Method {
    /// The fastest path that covers the scene.
    #[default]
    Auto,
    /// The general `ode_solvers` Dop853 path, always available.
    Dop853,
    /// The general path with `ode_solvers`' Dopri5 (order 5) in place of Dop853: the same events, located the same
    /// way; for comparison (`impact bench`).
    Dopri5,
    /// The Taylor-series integrator of the regularised normal contact (`crate::fast`): the 1-D normal impact of
    /// every law but Brilliantov's.
    Taylor,
    /// A frictional sphere on a flat wall by Dop853 in regularised time, its tangential motion on one line
    /// (`crate::dynamics::slide`): the path `auto` took for it before the slide by Taylor series; for comparison.
    Dop853Slide,
    /// The DEM velocity Verlet of LAMMPS and LIGGGHTS at the fixed step `dt` (`crate::fixed_step`): the e a peer
    /// code gives, beside the accurate one. The 1-D normal contact only.
    Verlet,
    /// The semi-implicit Euler of Kratos and MuJoCo at the fixed step `dt` (`crate::fixed_step`).
    SymplecticEuler,
}

impl Method {
    /// Every method, by its scene spelling.
    pub const ALL: [(&'static str, Method); 7] = [
        ("auto", Method::Auto),
        ("dop853", Method::Dop853),
        ("dopri5", Method::Dopri5),
        ("taylor", Method::Taylor),
        ("dop853-slide", Method::Dop853Slide),
        ("verlet", Method::Verlet),
        ("symplectic-euler", Method::SymplecticEuler),
    ];

    /// Whether the method is one of the peers' fixed-step schemes (which take `dt`).
    pub fn is_fixed_step(self) -> bool {
        matches!(self, Method::Verlet | Method::SymplecticEuler)
    }

    /// The scene spelling.
    pub fn name(self) -> &'static str {
        Method::ALL.iter().find(|(_, m)| *m == self).map_or("auto", |(name, _)| name)
    }
}

/// Where the tangential (Mindlin) stiffness comes from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TangentialStiffnessSpec {
    /// The Mindlin no-slip stiffness kt = 8 G* sqrt(R* d) from the bodies' elastic constants.
    Mindlin,
    /// A constant kt in N/m.
    Value(f64),
}

/// How a frictional contact's Coulomb limit follows the normal force (`friction_cap`, docs/oblique.md).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FrictionCap {
    /// mu max(Fn, 0): no friction while the normal force pulls (a damped law's tensile force near separation).
    #[default]
    Compressive,
    /// mu |Fn|: friction also while the normal force pulls, as LAMMPS' granular styles and LIGGGHTS cap it.
    Magnitude,
}

impl FrictionCap {
    /// Every cap, by its scene spelling.
    pub const ALL: [(&'static str, FrictionCap); 2] =
        [("compressive", FrictionCap::Compressive), ("magnitude", FrictionCap::Magnitude)];

    /// The scene spelling.
    pub fn name(self) -> &'static str {
        match self {
            FrictionCap::Compressive => "compressive",
            FrictionCap::Magnitude => "magnitude",
        }
    }
}

/// What the tangential spring does while the contact unloads (`tangential_unloading`, docs/oblique.md).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum TangentialUnloading {
    /// The spring force keeps what the slip loaded into it: dT/dt = -kt slip.
    #[default]
    None,
    /// While the penetration decreases the spring force is scaled with the stiffness, dT/dt = -kt slip +
    /// T (dkt/dt)/kt: Mindlin's kt ∝ a ∝ sqrt(d) gives T d'/(2 d) (LAMMPS' `mindlin_rescale/force` in continuous
    /// time); a constant kt has nothing to rescale.
    Rescale,
}

impl TangentialUnloading {
    /// Every behaviour, by its scene spelling.
    pub const ALL: [(&'static str, TangentialUnloading); 2] =
        [("none", TangentialUnloading::None), ("rescale", TangentialUnloading::Rescale)];

    /// The scene spelling.
    pub fn name(self) -> &'static str {
        match self {
            TangentialUnloading::None => "none",
            TangentialUnloading::Rescale => "rescale",
        }
    }
}

/// The `[contact]` table.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactSpec {
    pub law: LawKind,
    pub damping: DampingSpec,
    pub stiffness: StiffnessSpec,
    /// n in K d^n, resolved: the written one, or the law's (1 for Kelvin–Voigt, 3/2 otherwise).
    pub exponent: f64,
    /// The scene's `exponent`, when written.
    pub exponent_given: Option<f64>,
    pub separation: Separation,
    /// Coulomb friction coefficient mu (0: smooth).
    pub friction: f64,
    /// The tangential spring of a frictional contact.
    pub tangential_stiffness: TangentialStiffnessSpec,
    /// Damping ratio of the tangential spring (0: none): c_t = 2 ratio sqrt(k_t m_t).
    pub tangential_damping: f64,
    /// What the tangential spring does while the contact unloads (used only with friction).
    pub tangential_unloading: TangentialUnloading,
    /// How the Coulomb limit follows the normal force (used only with friction).
    pub friction_cap: FrictionCap,
    /// The `thornton` law's yield pressure p_y, Pa, when written (otherwise 1.6 times the smaller `yield_stress`).
    pub yield_pressure: Option<f64>,
    /// The `mujoco` law's `solref`: [timeconst (s), dampratio], or [-stiffness (1/s²), -damping (1/s)] per unit mass.
    pub solref: Option<[f64; 2]>,
    /// The `mujoco` law's `solimp` [dmin, dmax, width (m), midpoint, power], when written (MuJoCo's default
    /// [0.9, 0.95, 0.001, 0.5, 2] otherwise).
    pub solimp: Option<[f64; 5]>,
    /// The `adams-impact` law's full damping c_max, N s/m.
    pub cmax: Option<f64>,
    /// The `adams-impact` law's penetration at full damping d_max, m.
    pub dmax: Option<f64>,
    /// The scene's unit normal (body 1 -> body 2), if it gave one (`normal_given` normalised).
    pub normal: Option<Vector3<f64>>,
    /// The scene's `normal` as written.
    pub normal_given: Option<Vector3<f64>>,
}

/// The `[output]` table: files a run writes, relative to the current folder.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct OutputSpec {
    /// CSV time series of the contact.
    pub series: Option<PathBuf>,
    /// Folder for the figures.
    pub plots: Option<PathBuf>,
    /// The lines of `series` and `plots` in the scene file, for errors found when the paths are resolved (an
    /// output that would replace the scene file itself, a plots folder that is a file).
    pub series_line: Option<usize>,
    pub plots_line: Option<usize>,
}

impl ContactSpec {
    /// Re-derives the exponent and the unit normal from the written values.
    pub fn resolve(&mut self) {
        self.exponent = match self.law.family() {
            crate::law::Family::Linear | crate::law::Family::Impedance => 1.0,
            _ => self.exponent_given.unwrap_or(1.5),
        };
        self.normal = self.normal_given.map(|n| n / n.norm());
    }
}

impl Scene {
    /// Re-derives every value that follows from written ones (masses from densities, inertias, the exponent, the
    /// unit normal), after a sweep has set some of them.
    pub fn resolve(&mut self) {
        for body in &mut self.bodies {
            body.resolve();
        }
        self.contact.resolve();
    }

    /// Checks every value rule of a scene (ranges, and the rules between keys): the same rules [`Scene::read`]
    /// applies, on a scene already typed. The error names the key; it has no file or line.
    pub fn check_rules(&self) -> Result<(), SetupError> {
        rules::check(self)
    }

    /// [`Scene::check_rules`] without the groups of rules in `known` (a sweep's point: those its base scene passed
    /// and its varied keys do not reach), with the same first error.
    pub fn check_rules_except(&self, known: RuleGroups) -> Result<(), SetupError> {
        rules::check_groups(self, known)
    }

    /// Reads two-body scene text: its form and every value rule, errors located; `path` names the source in errors
    /// and gives the default title. The physics-level rules are still to check ([`Scene::parse`]).
    pub fn read<'a>(text: &'a str, path: &Path) -> Result<Read<'a, Scene>, SceneError> {
        validate::scene(text, path)
    }

    /// Reads scene text into a typed scene without checking its values (only its form: TOML syntax, known keys,
    /// types, what must be there): what a sweep applies its points to before [`Scene::check`] checks each one.
    pub fn convert(text: &str, path: &Path) -> Result<Scene, SceneError> {
        validate::convert(text, path).map(|(scene, _)| scene)
    }
}
