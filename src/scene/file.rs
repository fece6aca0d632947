//! The TOML file as written: serde structs that reject unknown keys and keep each value's position.

use serde::Deserialize;
use toml::Spanned;

/// A value with its byte span in the file.
pub type At<T> = Spanned<T>;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawScene {
    pub title: Option<At<String>>,
    pub bodies: Option<At<Vec<At<RawBody>>>>,
    pub contact: Option<At<RawContact>>,
    pub solver: Option<At<RawSolver>>,
    pub output: Option<At<RawOutput>>,
    pub world: Option<At<RawWorld>>,
    pub pair: Option<At<Vec<At<RawPair>>>>,
}

/// The `[world]` table of a world run (docs/scene.md#worlds).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawWorld {
    pub gravity: Option<At<Vec<f64>>>,
    pub end_time: Option<At<f64>>,
    pub max_contacts: Option<At<toml::Value>>,
    pub max_steps: Option<At<toml::Value>>,
    pub damping_map: Option<At<String>>,
    pub skin: Option<At<f64>>,
    pub coast: Option<At<bool>>,
}

/// A `[[pair]]` table: two bodies and any key of `[contact]`, which it overrides for them.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawPair {
    pub bodies: Option<At<Vec<toml::Value>>>,
    pub law: Option<At<String>>,
    pub restitution: Option<At<f64>>,
    pub damping: Option<At<f64>>,
    pub stiffness: Option<At<toml::Value>>,
    pub exponent: Option<At<f64>>,
    pub separation: Option<At<String>>,
    pub friction: Option<At<f64>>,
    pub tangential_stiffness: Option<At<toml::Value>>,
    pub tangential_damping: Option<At<f64>>,
    pub tangential_unloading: Option<At<String>>,
    pub friction_cap: Option<At<String>>,
    pub yield_pressure: Option<At<f64>>,
    pub solref: Option<At<Vec<f64>>>,
    pub solimp: Option<At<Vec<f64>>>,
    pub cmax: Option<At<f64>>,
    pub dmax: Option<At<f64>>,
    pub normal: Option<At<Vec<f64>>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawBody {
    pub name: Option<At<String>>,
    pub radius: Option<At<f64>>,
    pub mass: Option<At<f64>>,
    pub density: Option<At<f64>>,
    pub velocity: Option<At<Vec<f64>>>,
    pub position: Option<At<Vec<f64>>>,
    pub angular_velocity: Option<At<Vec<f64>>>,
    /// A number, three principal moments, or a 3×3 tensor.
    pub inertia: Option<At<toml::Value>>,
    pub contact_offset: Option<At<Vec<f64>>>,
    pub pivot: Option<At<Vec<f64>>>,
    pub young: Option<At<f64>>,
    pub poisson: Option<At<f64>>,
    pub yield_stress: Option<At<f64>>,
    /// A flat body's face normal in a world run.
    pub normal: Option<At<Vec<f64>>>,
    /// A clump's contact spheres, fixed to the body (a world run).
    pub spheres: Option<At<Vec<At<RawSphere>>>>,
}

/// One `[[bodies.spheres]]` table: a contact sphere fixed to its body.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawSphere {
    pub offset: Option<At<Vec<f64>>>,
    pub radius: Option<At<f64>>,
}

#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawContact {
    pub law: Option<At<String>>,
    pub restitution: Option<At<f64>>,
    pub damping: Option<At<f64>>,
    pub stiffness: Option<At<toml::Value>>,
    pub exponent: Option<At<f64>>,
    pub separation: Option<At<String>>,
    pub friction: Option<At<f64>>,
    pub tangential_stiffness: Option<At<toml::Value>>,
    pub tangential_damping: Option<At<f64>>,
    pub tangential_unloading: Option<At<String>>,
    pub friction_cap: Option<At<String>>,
    pub yield_pressure: Option<At<f64>>,
    pub solref: Option<At<Vec<f64>>>,
    pub solimp: Option<At<Vec<f64>>>,
    pub cmax: Option<At<f64>>,
    pub dmax: Option<At<f64>>,
    pub normal: Option<At<Vec<f64>>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawSolver {
    pub method: Option<At<String>>,
    pub rtol: Option<At<f64>>,
    pub atol: Option<At<f64>>,
    pub dt: Option<At<f64>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawOutput {
    pub series: Option<At<String>>,
    pub plots: Option<At<String>>,
}
