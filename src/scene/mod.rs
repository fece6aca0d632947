//! The scene: what a user asks to simulate, typed and validated.
//!
//! `file` reads the TOML format of docs/scene.md into raw, span-carrying structs; `validate` turns those into a
//! [`Scene`] whose every value has been checked, or a [`SceneError`] naming the file, the key and the line.

mod error;
mod file;
mod validate;

pub use error::SceneError;

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

/// The `[solver]` table.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SolverSpec {
    /// Which integration path to take.
    pub method: Method,
    /// Integrator tolerances on the scaled state.
    pub tolerances: Tolerances,
}

/// The integration path a scene asks for (`[solver] method`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Method {
    /// The fastest path that covers the scene.
    #[default]
    Auto,
    /// The general `ode_solvers` Dop853 path, always available.
    Dop853,
}

impl Method {
    /// Every method, by its scene spelling.
    pub const ALL: [(&'static str, Method); 2] = [("auto", Method::Auto), ("dop853", Method::Dop853)];

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

/// The `[contact]` table.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactSpec {
    pub law: LawKind,
    pub damping: DampingSpec,
    pub stiffness: StiffnessSpec,
    /// n in K d^n.
    pub exponent: f64,
    pub separation: Separation,
    /// Coulomb friction coefficient mu (0: smooth).
    pub friction: f64,
    /// The tangential spring of a frictional contact.
    pub tangential_stiffness: TangentialStiffnessSpec,
    /// Damping ratio of the tangential spring (0: none): c_t = 2 ratio sqrt(k_t m_t).
    pub tangential_damping: f64,
    /// The scene's unit normal (body 1 -> body 2), if it gave one.
    pub normal: Option<Vector3<f64>>,
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

impl Scene {
    /// Reads and validates a scene file.
    pub fn load(path: &Path) -> Result<Scene, SceneError> {
        let text = std::fs::read_to_string(path)
            .map_err(|error| SceneError::file(path, format!("cannot read the scene: {error}")))?;
        Scene::parse(&text, path)
    }

    /// Validates scene text; `path` names the source in errors and gives the default title.
    pub fn parse(text: &str, path: &Path) -> Result<Scene, SceneError> {
        validate::scene(text, path)
    }
}
