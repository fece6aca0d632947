//! From the raw file to a checked [`Scene`], each failure naming file, key and line: first the file's form is
//! converted (TOML syntax, known keys, value types, what must be there) into a typed scene, then every value rule is
//! checked on it ([`super::rules`], the same rules a sweep's points obey), then the physics-level rules of
//! [`Setup`] (docs/scene.md lists them all). Lines come from the spans the conversion records for every key.

use super::file::{At, RawBody, RawContact, RawOutput, RawScene, RawSolver};
use super::{
    ContactSpec, DampingSpec, Method, OutputSpec, Scene, SceneError, SolverSpec, StiffnessSpec, TangentialStiffnessSpec,
};
use crate::body::Body;
use crate::integrate::Tolerances;
use crate::law::{LawKind, Separation};
use crate::output::{files, text};
use crate::setup::Setup;
use nalgebra::Vector3;
use std::collections::HashMap;
use std::ops::Range;
use std::path::Path;

/// Where errors point: the file and its text (for lines), and the line of every key the conversion met.
struct Source<'a> {
    text: &'a str,
    file: String,
    lines: std::cell::RefCell<HashMap<String, usize>>,
}

type Checked<T> = Result<T, SceneError>;

impl Source<'_> {
    fn line(&self, span: &Range<usize>) -> usize {
        let start = span.start.min(self.text.len());
        self.text[..start].matches('\n').count() + 1
    }

    /// Records where `key` is written, for the rules' errors.
    fn note(&self, key: &str, span: &Range<usize>) {
        self.lines.borrow_mut().insert(key.to_string(), self.line(span));
    }

    /// A broken rule, located: the key's recorded line, or the line its name is found on (for a key not written, its
    /// table's header).
    fn located(&self, error: crate::setup::SetupError) -> SceneError {
        let line = self.lines.borrow().get(&error.key).copied().or_else(|| self.line_of_key(&error.key));
        SceneError { file: self.file.clone(), key: Some(error.key), line, message: error.message, form: false }
    }

    fn error(&self, key: &str, span: Option<&Range<usize>>, message: impl Into<String>) -> SceneError {
        SceneError {
            file: self.file.clone(),
            key: Some(key.to_string()),
            line: span.map(|s| self.line(s)),
            message: message.into(),
            // Missing tables, a wrong number of bodies, a bad separation word or output path: nothing a sweep's
            // numbers can set.
            form: matches!(key, "bodies" | "contact" | "contact.separation" | "output.series" | "output.plots"),
        }
    }

    /// The line of the first `key =` at the start of a line, for errors found after parsing without a span; for a key
    /// that is not written (a missing `position` or `young`), the line of its table's header.
    fn line_of_key(&self, key: &str) -> Option<usize> {
        let (table, index, leaf) = split_key(key);
        let mut in_table = table.is_empty();
        let mut header_line = None;
        let mut seen = 0usize;
        for (number, line) in self.text.lines().enumerate() {
            if let Some((name, array)) = header(line) {
                in_table = name == table && {
                    seen += usize::from(array);
                    index.is_none_or(|i| seen == i + 1)
                };
                if in_table {
                    header_line = Some(number + 1);
                }
                continue;
            }
            let assigned = line.trim().split('=').next().map(str::trim);
            if in_table && assigned == Some(leaf) {
                return Some(number + 1);
            }
        }
        header_line
    }

    /// The dotted key (0-based indices) assigned on a 1-based line, e.g. `bodies.1.colour` for `colour = "red"` in
    /// the second `[[bodies]]`, or the table a header line opens.
    fn key_on_line(&self, wanted: usize) -> Option<String> {
        let mut table = String::new();
        let mut arrays: Vec<&str> = Vec::new();
        for (number, line) in self.text.lines().enumerate().take(wanted) {
            if let Some((name, array)) = header(line) {
                table = if array {
                    arrays.push(name);
                    format!("{name}.{}", arrays.iter().filter(|seen| **seen == name).count() - 1)
                } else {
                    name.to_string()
                };
                if number + 1 == wanted {
                    return Some(table);
                }
            } else if number + 1 == wanted {
                let (left, _) = line.split_once('=')?;
                let leaf = left.trim();
                if leaf.is_empty() || leaf.starts_with('#') {
                    return None;
                }
                return Some(if table.is_empty() { leaf.to_string() } else { format!("{table}.{leaf}") });
            }
        }
        None
    }
}

/// A table header: `[contact]` -> ("contact", false); `[[bodies]]   # a comment` -> ("bodies", true).
fn header(line: &str) -> Option<(&str, bool)> {
    let code = line.split('#').next().unwrap_or_default().trim();
    if let Some(name) = code.strip_prefix("[[").and_then(|rest| rest.strip_suffix("]]")) {
        return Some((name.trim(), true));
    }
    let name = code.strip_prefix('[')?.strip_suffix(']')?;
    Some((name.trim(), false))
}

/// `bodies.1.velocity` -> ("bodies", Some(1), "velocity"); `contact.law` -> ("contact", None, "law").
fn split_key(key: &str) -> (&str, Option<usize>, &str) {
    let parts: Vec<&str> = key.split('.').collect();
    match parts.as_slice() {
        [table, index, leaf] => (table, index.parse().ok(), leaf),
        [table, leaf] => (table, None, leaf),
        [leaf] => ("", None, leaf),
        _ => ("", None, key),
    }
}

/// A number as written, its line recorded.
fn number(src: &Source, key: &str, value: &At<f64>) -> f64 {
    src.note(key, &value.span());
    *value.get_ref()
}

/// A vector as written: three numbers (their values are the rules' business), its line recorded.
fn vector(src: &Source, key: &str, value: &At<Vec<f64>>) -> Checked<Vector3<f64>> {
    let span = value.span();
    src.note(key, &span);
    let items = value.get_ref();
    if items.len() != 3 {
        return Err(src.error(
            key,
            Some(&span),
            format!("expected [x, y, z] (3 numbers), got {} numbers", items.len()),
        ));
    }
    Ok(Vector3::new(items[0], items[1], items[2]))
}

/// Parses and checks a whole scene.
pub fn scene(text: &str, path: &Path) -> Checked<Scene> {
    let src = source(text, path);
    let scene = convert_in(&src)?;
    super::rules::check(&scene).map_err(|error| src.located(error))?;
    Setup::new(&scene).map_err(|error| src.located(error))?;
    Ok(scene)
}

/// The typed scene of `text` with its form checked and its values not (see [`Scene::convert`]), and the line of
/// every key written.
pub fn convert(text: &str, path: &Path) -> Checked<(Scene, HashMap<String, usize>)> {
    let src = source(text, path);
    let scene = convert_in(&src)?;
    Ok((scene, src.lines.into_inner()))
}

fn source<'a>(text: &'a str, path: &Path) -> Source<'a> {
    Source { text, file: path.display().to_string(), lines: Default::default() }
}

fn convert_in(src: &Source) -> Checked<Scene> {
    let path = Path::new(&src.file);
    let raw: RawScene = toml::from_str(src.text).map_err(|error| parse_error(src, &error))?;
    let title = match &raw.title {
        Some(title) => title.get_ref().clone(),
        None => path.file_stem().map_or_else(|| "scene".into(), |s| s.to_string_lossy().into_owned()),
    };
    let Some(bodies) = &raw.bodies else {
        return Err(src.error("bodies", None, "missing: give two [[bodies]] tables"));
    };
    if bodies.get_ref().len() != 2 {
        let n = bodies.get_ref().len();
        return Err(src.error(
            "bodies",
            Some(&bodies.span()),
            format!("expected exactly two [[bodies]] (chains of more are not supported yet), got {n}"),
        ));
    }
    let first = body(src, 0, &bodies.get_ref()[0])?;
    let second = body(src, 1, &bodies.get_ref()[1])?;
    let Some(contact) = &raw.contact else {
        return Err(src.error("contact", None, "missing: give a [contact] table with at least `law`"));
    };
    let contact = contact_spec(src, contact)?;
    let solver = raw.solver.as_ref().map_or(Ok(SolverSpec::default()), |s| solver(src, s.get_ref()))?;
    let output = raw.output.as_ref().map_or(Ok(OutputSpec::default()), |o| output(src, o.get_ref()))?;
    let mut scene = Scene { title, bodies: [first, second], contact, solver, output };
    scene.resolve();
    Ok(scene)
}

fn parse_error(src: &Source, error: &toml::de::Error) -> SceneError {
    let span = error.span();
    let line = span.as_ref().map(|s| src.line(s));
    // The parser echoes what it was given (an unknown key, a bad value) whatever its length: cut it.
    let key = line.and_then(|n| src.key_on_line(n)).map(|key| cut(&key));
    let message = text::cut_quoted(&error.message().trim().replace('\n', " "));
    SceneError { file: src.file.clone(), key, line, message, form: true }
}

fn body(src: &Source, i: usize, raw: &At<RawBody>) -> Checked<Body> {
    let key = |leaf: &str| format!("bodies.{i}.{leaf}");
    let table = raw.span();
    let raw = raw.get_ref();
    let missing = |leaf: &str, what: &str| src.error(&key(leaf), Some(&table), format!("missing: {what}"));
    let radius = match &raw.radius {
        Some(r) => number(src, &key("radius"), r),
        None => return Err(missing("radius", "give `radius` in m (inf for a flat wall)")),
    };
    let (mass, density) = match (&raw.mass, &raw.density) {
        (Some(_), Some(d)) => {
            return Err(src.error(&key("density"), Some(&d.span()), "give `mass` or `density`, not both"));
        }
        (Some(m), None) => (number(src, &key("mass"), m), None),
        // The mass follows from the density when the scene is resolved.
        (None, Some(d)) => (f64::NAN, Some(number(src, &key("density"), d))),
        (None, None) => return Err(missing("mass", "give `mass` in kg (inf for immovable) or `density` in kg/m^3")),
    };
    let velocity = match &raw.velocity {
        Some(v) => vector(src, &key("velocity"), v)?,
        None => return Err(missing("velocity", "give `velocity = [vx, vy, vz]` in m/s")),
    };
    let position = raw.position.as_ref().map(|p| vector(src, &key("position"), p)).transpose()?;
    let angular_velocity = raw
        .angular_velocity
        .as_ref()
        .map(|w| vector(src, &key("angular_velocity"), w))
        .transpose()?
        .unwrap_or_default();
    let inertia_given = raw.inertia.as_ref().map(|i| number(src, &key("inertia"), i));
    let young = raw.young.as_ref().map(|e| number(src, &key("young"), e));
    let poisson = raw.poisson.as_ref().map(|nu| number(src, &key("poisson"), nu));
    let name = raw.name.as_ref().map_or_else(|| format!("body {}", i + 1), |n| n.get_ref().clone());
    Ok(Body {
        name,
        mass,
        density,
        radius,
        velocity,
        position,
        angular_velocity,
        inertia: f64::NAN,
        inertia_given,
        young,
        poisson,
    })
}

fn contact_spec(src: &Source, raw: &At<RawContact>) -> Checked<ContactSpec> {
    let table = raw.span();
    let raw = raw.get_ref();
    let Some(law_name) = &raw.law else {
        return Err(src.error(
            "contact.law",
            Some(&table),
            format!("missing: give `law`, one of {}", LawKind::names().join(", ")),
        ));
    };
    let Some(law) = LawKind::from_name(law_name.get_ref()) else {
        return Err(src.error(
            "contact.law",
            Some(&law_name.span()),
            format!("unknown law `{}`; expected one of {}", cut(law_name.get_ref()), LawKind::names().join(", ")),
        ));
    };
    let restitution = raw.restitution.as_ref().map(|e| number(src, "contact.restitution", e));
    let damping_value = raw.damping.as_ref().map(|c| number(src, "contact.damping", c));
    let damping = match (restitution, damping_value) {
        (Some(_), Some(_)) => {
            return Err(src.error(
                "contact.damping",
                raw.damping.as_ref().map(|c| c.span()).as_ref(),
                "give `restitution` or `damping`, not both",
            ));
        }
        (Some(e), None) => DampingSpec::Restitution(e),
        (None, Some(c)) => DampingSpec::Parameter(c),
        (None, None) => DampingSpec::None,
    };
    let stiffness = match &raw.stiffness {
        None => StiffnessSpec::Hertz,
        Some(value) => StiffnessSpec::written(value.get_ref()).map_or_else(
            |other| {
                Err(src.error(
                    "contact.stiffness",
                    Some(&value.span()),
                    format!("expected \"hertz\" or a number in N/m^n, got {}", cut(&other)),
                ))
            },
            |spec| {
                src.note("contact.stiffness", &value.span());
                Ok(spec)
            },
        )?,
    };
    let exponent_given = raw.exponent.as_ref().map(|n| number(src, "contact.exponent", n));
    let separation = match &raw.separation {
        None => Separation::Penetration,
        Some(s) => match s.get_ref().as_str() {
            "penetration" => Separation::Penetration,
            "force" => Separation::Force,
            other => {
                return Err(src.error(
                    "contact.separation",
                    Some(&s.span()),
                    format!("expected \"penetration\" or \"force\", got \"{}\"", cut(other)),
                ));
            }
        },
    };
    let friction = raw.friction.as_ref().map_or(0.0, |f| number(src, "contact.friction", f));
    let tangential_stiffness = match &raw.tangential_stiffness {
        None => TangentialStiffnessSpec::Mindlin,
        Some(value) => match value.get_ref() {
            toml::Value::String(s) if s == "mindlin" => TangentialStiffnessSpec::Mindlin,
            toml::Value::Float(_) | toml::Value::Integer(_) => {
                src.note("contact.tangential_stiffness", &value.span());
                let k = value.get_ref().as_float().or_else(|| value.get_ref().as_integer().map(|i| i as f64));
                TangentialStiffnessSpec::Value(k.unwrap_or(f64::NAN))
            }
            other => {
                return Err(src.error(
                    "contact.tangential_stiffness",
                    Some(&value.span()),
                    format!("expected \"mindlin\" or a number in N/m, got {}", cut(&other.to_string())),
                ));
            }
        },
    };
    let tangential_damping =
        raw.tangential_damping.as_ref().map_or(0.0, |c| number(src, "contact.tangential_damping", c));
    let normal_given = raw.normal.as_ref().map(|n| vector(src, "contact.normal", n)).transpose()?;
    Ok(ContactSpec {
        law,
        damping,
        stiffness,
        exponent: f64::NAN,
        exponent_given,
        separation,
        friction,
        tangential_stiffness,
        tangential_damping,
        normal: None,
        normal_given,
    })
}

fn solver(src: &Source, raw: &RawSolver) -> Checked<SolverSpec> {
    let method = match &raw.method {
        None => Method::Auto,
        Some(name) => {
            Method::ALL.iter().find(|(spelling, _)| spelling == name.get_ref()).map(|(_, m)| *m).ok_or_else(|| {
                let names: Vec<_> = Method::ALL.iter().map(|(spelling, _)| format!("\"{spelling}\"")).collect();
                src.error(
                    "solver.method",
                    Some(&name.span()),
                    format!("unknown method \"{}\"; expected one of {}", cut(name.get_ref()), names.join(", ")),
                )
            })?
        }
    };
    let defaults = Tolerances::default();
    let tolerances = Tolerances {
        rtol: raw.rtol.as_ref().map_or(defaults.rtol, |value| number(src, "solver.rtol", value)),
        atol: raw.atol.as_ref().map_or(defaults.atol, |value| number(src, "solver.atol", value)),
    };
    Ok(SolverSpec { method, tolerances })
}

/// The `[output]` paths: a series must name a file (`-` is standard output), plots a folder.
fn output(src: &Source, raw: &RawOutput) -> Checked<OutputSpec> {
    let check = |key: &str, value: &At<String>, problem: fn(&Path) -> Option<&'static str>| {
        let path = Path::new(value.get_ref());
        match problem(path) {
            Some(why) => Err(src.error(key, Some(&value.span()), format!("\"{}\": {why}", cut(value.get_ref())))),
            None => Ok((path.to_path_buf(), src.line(&value.span()))),
        }
    };
    let series = raw.series.as_ref().map(|s| check("output.series", s, files::file_name_problem)).transpose()?;
    let plots = raw.plots.as_ref().map(|p| check("output.plots", p, files::figure_folder_problem)).transpose()?;
    Ok(OutputSpec {
        series_line: series.as_ref().map(|s| s.1),
        plots_line: plots.as_ref().map(|p| p.1),
        series: series.map(|s| s.0),
        plots: plots.map(|p| p.0),
    })
}

/// A user's string as echoed in a message: cut to [`text::MESSAGE_CHARS`].
fn cut(text: &str) -> String {
    text::cut(text, text::MESSAGE_CHARS)
}
