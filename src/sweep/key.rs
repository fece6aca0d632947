//! The scene keys a sweep can vary: numbers of the scene file, named by dotted paths with 0-based indices
//! (`contact.restitution`, `bodies.1.mass`, `bodies.1.velocity.0` = the second body's x velocity).
//!
//! Setting a key edits the scene's TOML document. Keys that exclude each other in a scene are switched, so that a
//! point stays a valid scene whatever the file gave:
//! - `contact.restitution` removes `contact.damping`, and `contact.damping` removes `contact.restitution`;
//! - `bodies.I.mass` removes `bodies.I.density`, and `bodies.I.density` removes `bodies.I.mass`;
//! - a number set on `contact.stiffness` replaces `"hertz"`;
//! - a component of `contact.normal` or `bodies.I.angular_velocity` that the file leaves out starts from the
//!   default vector (`[1, 0, 0]` and `[0, 0, 0]`); `bodies.I.velocity` and `bodies.I.position` have no default, so
//!   the file must give the whole vector to vary one component;
//! - `bodies.I.incidence_deg` is not a key of the file but a way to set `bodies.I.velocity`: the body keeps its speed
//!   and moves at that angle (degrees) from the contact normal (`contact.normal`, default [1, 0, 0]), towards the
//!   other body, in the plane of the normal and the velocity's part across it (the coordinate axis most
//!   perpendicular to the normal when it has none). For a sphere on a wall at rest it is the angle of incidence.

use super::SweepError;
use crate::scene::{DampingSpec, RuleGroups, Scene, StiffnessSpec, TangentialStiffnessSpec};
use nalgebra::Vector3;
use std::fmt;
use toml::{Table, Value};

const BODY_NUMBERS: [&str; 8] =
    ["radius", "mass", "density", "young", "poisson", "yield_stress", "inertia", "incidence_deg"];
const BODY_VECTORS: [&str; 5] = ["velocity", "position", "angular_velocity", "contact_offset", "pivot"];
const CONTACT_NUMBERS: [&str; 8] = [
    "restitution",
    "damping",
    "stiffness",
    "exponent",
    "friction",
    "tangential_stiffness",
    "tangential_damping",
    "yield_pressure",
];
const CONTACT_VECTORS: [&str; 1] = ["normal"];
const SOLVER_NUMBERS: [&str; 3] = ["rtol", "atol", "dt"];

/// The keys a sweep accepts, for error messages.
pub const VALID_KEYS: &str = "bodies.I.radius, bodies.I.mass, bodies.I.density, bodies.I.young, bodies.I.poisson, \
     bodies.I.yield_stress, bodies.I.inertia, bodies.I.velocity.J, bodies.I.position.J, bodies.I.angular_velocity.J, \
     bodies.I.contact_offset.J, bodies.I.pivot.J, bodies.I.incidence_deg, \
     contact.restitution, contact.damping, contact.stiffness, contact.exponent, contact.friction, \
     contact.tangential_stiffness, contact.tangential_damping, contact.yield_pressure, contact.normal.J, solver.rtol, solver.atol, solver.dt \
     (I = 0 or 1, the body; J = 0, 1 or 2, the component)";

/// A number in the scene that a sweep sets.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SceneKey {
    /// The table: `bodies`, `contact` or `solver`.
    table: &'static str,
    /// The body (0-based) for `bodies` keys.
    body: Option<usize>,
    /// The field inside the table, e.g. `restitution`.
    field: &'static str,
    /// The component (0-based) of a vector field.
    component: Option<usize>,
}

impl fmt::Display for SceneKey {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.table)?;
        if let Some(body) = self.body {
            write!(f, ".{body}")?;
        }
        write!(f, ".{}", self.field)?;
        if let Some(component) = self.component {
            write!(f, ".{component}")?;
        }
        Ok(())
    }
}

fn unknown(key: &str, why: &str) -> SweepError {
    SweepError::Usage(format!("cannot vary `{key}`: {why}; a sweep varies one of {VALID_KEYS}"))
}

/// `"3"` -> 3, for indices.
fn index(text: &str) -> Option<usize> {
    if text.is_empty() || !text.bytes().all(|b| b.is_ascii_digit()) { None } else { text.parse().ok() }
}

/// The field spelled `name` among `fields`, as a `'static` str.
fn field(fields: &[&'static str], name: &str) -> Option<&'static str> {
    fields.iter().copied().find(|f| *f == name)
}

impl SceneKey {
    /// Parses a dotted key; anything that is not a number of a scene is a usage error that lists the valid keys.
    pub fn parse(key: &str) -> Result<SceneKey, SweepError> {
        let parts: Vec<&str> = key.split('.').collect();
        let (table, body, rest) = match parts.as_slice() {
            ["bodies", i, rest @ ..] => {
                let Some(body) = index(i) else {
                    return Err(unknown(key, &format!("`{i}` is not a body index (0 or 1)")));
                };
                if body > 1 {
                    return Err(unknown(key, &format!("a scene has two bodies, 0 and 1, not {body}")));
                }
                ("bodies", Some(body), rest)
            }
            ["contact", rest @ ..] => ("contact", None, rest),
            ["solver", rest @ ..] => ("solver", None, rest),
            ["bodies" | "title"] | ["output", ..] => return Err(unknown(key, "it is not a number of the scene")),
            _ => return Err(unknown(key, "no such scene key")),
        };
        let (numbers, vectors): (&[&'static str], &[&'static str]) = match table {
            "bodies" => (&BODY_NUMBERS, &BODY_VECTORS),
            "contact" => (&CONTACT_NUMBERS, &CONTACT_VECTORS),
            _ => (&SOLVER_NUMBERS, &[]),
        };
        match rest {
            [] => Err(unknown(key, "it is a table, not a number")),
            ["law"] if table == "contact" => Err(SweepError::Usage(format!(
                "cannot vary `{key}` with --vary: it is not a number; give the laws with --law a,b,c"
            ))),
            [name] => match (field(numbers, name), field(vectors, name)) {
                (Some(field), _) => Ok(SceneKey { table, body, field, component: None }),
                (None, Some(_)) => Err(SweepError::Usage(format!(
                    "cannot vary `{key}`: it is a vector; vary one component, e.g. `{key}.0` (x), `{key}.1` (y) \
                     or `{key}.2` (z)"
                ))),
                (None, None) => Err(unknown(key, "no such number in the scene")),
            },
            [name, j] => match (field(vectors, name), index(j)) {
                (Some(field), Some(component)) if component < 3 => {
                    Ok(SceneKey { table, body, field, component: Some(component) })
                }
                (Some(_), _) => Err(unknown(key, &format!("`{j}` is not a vector component (0, 1 or 2)"))),
                (None, _) if field(numbers, name).is_some() => {
                    Err(unknown(key, &format!("`{name}` is a number, not a vector")))
                }
                (None, _) => Err(unknown(key, "no such number in the scene")),
            },
            _ => Err(unknown(key, "no such scene key")),
        }
    }

    /// Whether this is `contact.<field>`.
    pub fn is_contact(&self, field: &str) -> bool {
        self.table == "contact" && self.field == field
    }

    /// Whether this is a component of a body's velocity (the sweep figure then plots against the approach speed).
    pub fn is_velocity(&self) -> bool {
        self.table == "bodies" && self.field == "velocity"
    }

    /// Whether this is a body's angle of incidence (which sets its velocity).
    pub fn is_incidence(&self) -> bool {
        self.table == "bodies" && self.field == "incidence_deg"
    }

    /// The key this one removes when set (`restitution` <-> `damping`, `mass` <-> `density` of the same body).
    fn partner(&self) -> Option<&'static str> {
        match (self.table, self.field) {
            ("contact", "restitution") => Some("damping"),
            ("contact", "damping") => Some("restitution"),
            ("bodies", "mass") => Some("density"),
            ("bodies", "density") => Some("mass"),
            _ => None,
        }
    }

    /// Whether two keys cannot both be varied: the same number twice, or two numbers that exclude each other.
    pub fn conflicts_with(&self, other: &SceneKey) -> bool {
        let same_body = self.table == other.table && self.body == other.body;
        // The incidence sets the whole velocity of its body.
        let velocity = |a: &SceneKey, b: &SceneKey| a.is_incidence() && b.is_velocity();
        self == other
            || (same_body && self.partner() == Some(other.field))
            || (same_body && (velocity(self, other) || velocity(other, self)))
    }

    /// Checks, before any work, that the scene file has what this key needs: the body it names, and the whole
    /// vector for a component of a vector without a default.
    pub fn check_in(&self, scene: &Table) -> Result<(), SweepError> {
        let Some(table) = self.find_table(scene) else {
            return match self.body {
                Some(body) => Err(SweepError::Usage(format!(
                    "cannot vary `{self}`: the scene has no body {body} (bodies count from 0: give two [[bodies]])"
                ))),
                None => Ok(()),
            };
        };
        if self.is_incidence() {
            return match table.get("velocity") {
                Some(Value::Array(items)) if items.len() == 3 => Ok(()),
                _ => Err(SweepError::Usage(format!(
                    "cannot vary `{self}`: it turns the body's velocity, so the scene must give `{}` as [x, y, z]",
                    SceneKey { field: "velocity", ..self.clone() }
                ))),
            };
        }
        let Some(component) = self.component else { return Ok(()) };
        match table.get(self.field) {
            Some(Value::Array(items)) if component < items.len() => Ok(()),
            Some(Value::Array(items)) => Err(SweepError::Usage(format!(
                "cannot vary `{self}`: the scene's `{}` has {} components",
                self.parent(),
                items.len()
            ))),
            Some(_) => {
                Err(SweepError::Usage(format!("cannot vary `{self}`: the scene's `{}` is not a vector", self.parent())))
            }
            None if self.default_vector().is_some() => Ok(()),
            None => Err(SweepError::Usage(format!(
                "cannot vary `{self}`: the scene has no `{}`; write the whole vector in the file to vary one component",
                self.parent()
            ))),
        }
    }

    /// `bodies.1.velocity` for `bodies.1.velocity.0`.
    fn parent(&self) -> String {
        SceneKey { component: None, ..self.clone() }.to_string()
    }

    /// The vector a scene means when it leaves this field out (docs/scene.md), if it has one.
    fn default_vector(&self) -> Option<[f64; 3]> {
        match self.field {
            "normal" => Some([1.0, 0.0, 0.0]),
            "angular_velocity" | "contact_offset" => Some([0.0, 0.0, 0.0]),
            _ => None,
        }
    }

    /// The table holding this key in `scene`, if the file has it.
    fn find_table<'a>(&self, scene: &'a Table) -> Option<&'a Table> {
        let table = scene.get(self.table)?;
        match self.body {
            Some(body) => table.as_array()?.get(body)?.as_table(),
            None => table.as_table(),
        }
    }

    /// The table holding this key, created when a `[contact]` or `[solver]` table is missing. `Err` says why the
    /// scene cannot take the key (that point's row says so).
    fn table_mut<'a>(&self, scene: &'a mut Table) -> Result<&'a mut Table, String> {
        let table = scene.entry(self.table).or_insert_with(|| Value::Table(Table::new()));
        let table = match self.body {
            Some(body) => table
                .as_array_mut()
                .and_then(|bodies| bodies.get_mut(body))
                .ok_or_else(|| format!("the scene has no body {body}"))?,
            None => table,
        };
        table.as_table_mut().ok_or_else(|| format!("`{}` is not a table", self.parent()))
    }

    /// Sets this key to `value` in the scene document, applying the switching rules of the module doc.
    pub fn set(&self, scene: &mut Table, value: f64) -> Result<(), String> {
        if self.is_incidence() {
            return self.set_incidence(scene, value);
        }
        let default = self.default_vector();
        let table = self.table_mut(scene)?;
        if let Some(partner) = self.partner() {
            table.remove(partner);
        }
        let Some(component) = self.component else {
            table.insert(self.field.to_string(), Value::Float(value));
            return Ok(());
        };
        let vector = match (table.get_mut(self.field), default) {
            (Some(vector), _) => vector,
            (None, Some(default)) => {
                let items = default.iter().map(|&x| Value::Float(x)).collect();
                table.entry(self.field).or_insert(Value::Array(items))
            }
            (None, None) => return Err(format!("the scene has no `{}`", self.parent())),
        };
        let slot = vector
            .as_array_mut()
            .and_then(|items| items.get_mut(component))
            .ok_or_else(|| format!("`{}` has no component {component}", self.parent()))?;
        *slot = Value::Float(value);
        Ok(())
    }

    /// Turns the body's velocity to `degrees` from the contact normal, keeping its speed (see the module doc).
    fn set_incidence(&self, scene: &mut Table, degrees: f64) -> Result<(), String> {
        let normal = scene
            .get("contact")
            .and_then(|c| c.get("normal"))
            .map(|n| numbers(n).ok_or("`contact.normal` is not [x, y, z]"))
            .transpose()?
            .unwrap_or([1.0, 0.0, 0.0]);
        let table = self.table_mut(scene)?;
        let velocity = table.get("velocity").and_then(numbers).ok_or("the body's `velocity` is not [x, y, z]")?;
        let body = self.body.unwrap_or(0);
        let turned: Vec<Value> = turned(normal, velocity, body, degrees)?.iter().map(|&c| Value::Float(c)).collect();
        table.insert("velocity".into(), Value::Array(turned));
        Ok(())
    }

    /// The groups of value rules ([`RuleGroups`]) whose table setting this key changes: its body's, the contact's or
    /// the solver's.
    pub fn reaches(&self) -> RuleGroups {
        let mut groups = RuleGroups::NONE;
        match (self.table, self.body) {
            ("bodies", Some(i)) if i < 2 => groups.bodies[i] = true,
            ("contact", _) => groups.contact = true,
            ("solver", _) => groups.solver = true,
            // (No other key is settable; were one added, it would reach everything until said otherwise.)
            _ => groups = RuleGroups { bodies: [true; 2], contact: true, solver: true, contact_but_damping: true },
        }
        groups
    }

    /// Whether this key sets the contact's damping (`contact.damping` or `contact.restitution`) and nothing else of
    /// the scene: a point's contact then differs from its base's only there ([`RuleGroups::contact_but_damping`]).
    pub fn sets_damping(&self) -> bool {
        self.table == "contact" && matches!((self.field, self.component), ("damping" | "restitution", None))
    }

    /// Whether setting this key can change a scene's [`crate::setup::Approach`], which the bodies and the contact's
    /// normal decide: every key of a body, and `contact.normal` (and, were one added, any key of another table).
    pub fn moves_approach(&self) -> bool {
        match self.table {
            "contact" => self.field == "normal",
            "solver" => false,
            _ => true,
        }
    }

    /// Sets this key to `value` on a typed scene, with exactly the switching rules of [`SceneKey::set`] (a point of a
    /// sweep applied without writing and re-reading TOML). The caller re-derives the scene ([`Scene::resolve`]) and
    /// checks it ([`Scene::check`]) after setting every key of the point.
    pub fn apply(&self, scene: &mut Scene, value: f64) -> Result<(), String> {
        match (self.table, self.body) {
            ("bodies", Some(i)) => {
                if self.is_incidence() {
                    let normal = scene.contact.normal_given.unwrap_or_else(Vector3::x);
                    let velocity = scene.bodies[i].velocity;
                    scene.bodies[i].velocity =
                        turned([normal.x, normal.y, normal.z], [velocity.x, velocity.y, velocity.z], i, value)?.into();
                    return Ok(());
                }
                let body = &mut scene.bodies[i];
                match (self.field, self.component) {
                    ("radius", None) => body.radius = value,
                    ("mass", None) => (body.mass, body.density) = (value, None),
                    ("density", None) => body.density = Some(value),
                    ("young", None) => body.young = Some(value),
                    ("poisson", None) => body.poisson = Some(value),
                    ("yield_stress", None) => body.yield_stress = Some(value),
                    ("inertia", None) => (body.inertia_given, body.inertia_tensor) = (Some(value), None),
                    ("contact_offset", Some(j)) => body.contact_offset[j] = value,
                    ("pivot", Some(j)) => match &mut body.pivot {
                        Some(pivot) => pivot[j] = value,
                        None => return Err(format!("the scene has no `{}`", self.parent())),
                    },
                    ("velocity", Some(j)) => body.velocity[j] = value,
                    ("angular_velocity", Some(j)) => body.angular_velocity[j] = value,
                    ("position", Some(j)) => match &mut body.position {
                        Some(position) => position[j] = value,
                        None => return Err(format!("the scene has no `{}`", self.parent())),
                    },
                    _ => return Err(format!("`{self}` cannot be set")),
                }
            }
            ("contact", _) => {
                let contact = &mut scene.contact;
                match (self.field, self.component) {
                    ("restitution", None) => contact.damping = DampingSpec::Restitution(value),
                    ("damping", None) => contact.damping = DampingSpec::Parameter(value),
                    ("stiffness", None) => contact.stiffness = StiffnessSpec::Value(value),
                    ("exponent", None) => contact.exponent_given = Some(value),
                    ("friction", None) => contact.friction = value,
                    ("tangential_stiffness", None) => {
                        contact.tangential_stiffness = TangentialStiffnessSpec::Value(value)
                    }
                    ("tangential_damping", None) => contact.tangential_damping = value,
                    ("yield_pressure", None) => contact.yield_pressure = Some(value),
                    ("normal", Some(j)) => contact.normal_given.get_or_insert_with(Vector3::x)[j] = value,
                    _ => return Err(format!("`{self}` cannot be set")),
                }
            }
            ("solver", _) => match self.field {
                "rtol" => scene.solver.tolerances.rtol = value,
                "atol" => scene.solver.tolerances.atol = value,
                "dt" => scene.solver.dt = Some(value),
                _ => return Err(format!("`{self}` cannot be set")),
            },
            _ => return Err(format!("`{self}` cannot be set")),
        }
        Ok(())
    }
}

/// `velocity` turned to `degrees` from `normal` (as written: not yet normalised), keeping its speed, towards the
/// other body (body 0 moves along +n, body 1 along -n), in the plane of the normal and the velocity's part across it
/// (the coordinate axis most perpendicular to the normal when it has none).
fn turned(normal: [f64; 3], velocity: [f64; 3], body: usize, degrees: f64) -> Result<[f64; 3], String> {
    if !(0.0..90.0).contains(&degrees) {
        return Err(format!(
            "an angle of incidence in [0, 90) degrees, got {}",
            crate::units::short_outside(degrees, |d| (0.0..90.0).contains(&d))
        ));
    }
    let length = norm(normal);
    if !(length > 0.0 && length.is_finite()) {
        return Err("`contact.normal` is not a direction".into());
    }
    let n = normal.map(|c| c / length);
    let speed = norm(velocity);
    if speed == 0.0 || !speed.is_finite() {
        return Err("the body is at rest: its speed sets the incidence's speed".into());
    }
    let along = dot(velocity, n);
    let mut across = [velocity[0] - along * n[0], velocity[1] - along * n[1], velocity[2] - along * n[2]];
    if norm(across) <= 1e-12 * speed {
        let axis = (0..3).min_by(|&i, &j| n[i].abs().total_cmp(&n[j].abs())).unwrap_or(0);
        across = [0.0; 3];
        across[axis] = 1.0;
        let along = dot(across, n);
        across = [across[0] - along * n[0], across[1] - along * n[1], across[2] - along * n[2]];
    }
    let across_length = norm(across);
    let t = across.map(|c| c / across_length);
    let towards = if body == 0 { 1.0 } else { -1.0 };
    let (c, s) = (degrees.to_radians().cos(), degrees.to_radians().sin());
    Ok([0, 1, 2].map(|i| speed * (towards * c * n[i] + s * t[i])))
}

/// A TOML array of three numbers.
fn numbers(value: &Value) -> Option<[f64; 3]> {
    let items = value.as_array()?;
    let number = |v: &Value| v.as_float().or_else(|| v.as_integer().map(|i| i as f64));
    match items.as_slice() {
        [x, y, z] => Some([number(x)?, number(y)?, number(z)?]),
        _ => None,
    }
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}
