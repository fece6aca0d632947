//! From the raw file to a checked [`Scene`]: every rule of interface.md, each failure naming key and line.

use super::file::{At, RawBody, RawContact, RawOutput, RawScene, RawSolver};
use super::{
    ContactSpec, DampingSpec, Method, OutputSpec, Scene, SceneError, SolverSpec, StiffnessSpec, TangentialStiffnessSpec,
};
use crate::body::Body;
use crate::integrate::Tolerances;
use crate::law::damping::{MapError, check_restitution};
use crate::law::{Family, LawKind, Separation};
use crate::setup::Setup;
use nalgebra::Vector3;
use std::ops::Range;
use std::path::Path;

/// Where errors point: the file and its text (for lines).
struct Source<'a> {
    text: &'a str,
    file: String,
}

type Checked<T> = Result<T, SceneError>;

impl Source<'_> {
    fn line(&self, span: &Range<usize>) -> usize {
        let start = span.start.min(self.text.len());
        self.text[..start].matches('\n').count() + 1
    }

    fn error(&self, key: &str, span: Option<&Range<usize>>, message: impl Into<String>) -> SceneError {
        SceneError {
            file: self.file.clone(),
            key: Some(key.to_string()),
            line: span.map(|s| self.line(s)),
            message: message.into(),
            // Missing tables, a wrong number of bodies, a bad separation word: nothing a sweep's numbers can set.
            form: matches!(key, "bodies" | "contact" | "contact.separation"),
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

/// A user's string as echoed in a message: cut to a readable length.
fn cut(text: &str) -> String {
    const MAX: usize = 60;
    match text.char_indices().nth(MAX) {
        None => text.to_string(),
        Some((end, _)) => format!("{}… ({} characters)", &text[..end], text.chars().count()),
    }
}

/// A message cut to `max` characters, saying how long it was.
fn shorten(text: &str, max: usize) -> String {
    match text.char_indices().nth(max) {
        None => text.to_string(),
        Some((end, _)) => format!("{}… ({} characters)", &text[..end], text.chars().count()),
    }
}

/// What a number may be.
#[derive(Clone, Copy)]
enum Allowed {
    /// Finite and > 0.
    Positive,
    /// > 0, `+inf` allowed (mass, radius, young).
    PositiveOrInfinite,
    /// Finite and >= 0.
    NonNegative,
    /// In [0, 1].
    Fraction,
    /// Finite.
    Any,
}

fn number(src: &Source, key: &str, value: &At<f64>, range: Allowed) -> Checked<f64> {
    let x = *value.get_ref();
    let span = Some(value.span());
    let span = span.as_ref();
    if x.is_nan() {
        return Err(src.error(key, span, "NaN is not a valid value"));
    }
    if x == f64::NEG_INFINITY {
        return Err(src.error(key, span, "-inf is not a valid value"));
    }
    let ok = match range {
        Allowed::Positive => x.is_finite() && x > 0.0,
        Allowed::PositiveOrInfinite => x > 0.0,
        Allowed::NonNegative => x.is_finite() && x >= 0.0,
        Allowed::Fraction => (0.0..=1.0).contains(&x),
        Allowed::Any => x.is_finite(),
    };
    if ok {
        return Ok(x);
    }
    let expected = match range {
        Allowed::Positive => "a finite number > 0",
        Allowed::PositiveOrInfinite => "a number > 0 (or inf)",
        Allowed::NonNegative => "a finite number >= 0",
        Allowed::Fraction => "a number in [0, 1]",
        Allowed::Any => "a finite number",
    };
    let got = if x.is_infinite() { "inf".to_string() } else { x.to_string() };
    Err(src.error(key, span, format!("expected {expected}, got {got}")))
}

fn vector(src: &Source, key: &str, value: &At<Vec<f64>>) -> Checked<Vector3<f64>> {
    let span = value.span();
    let items = value.get_ref();
    if items.len() != 3 {
        return Err(src.error(
            key,
            Some(&span),
            format!("expected [x, y, z] (3 numbers), got {} numbers", items.len()),
        ));
    }
    for (i, x) in items.iter().enumerate() {
        if !x.is_finite() {
            return Err(src.error(key, Some(&span), format!("component {i} must be a finite number, got {x}")));
        }
    }
    Ok(Vector3::new(items[0], items[1], items[2]))
}

/// Parses and checks a whole scene.
pub fn scene(text: &str, path: &Path) -> Checked<Scene> {
    let src = Source { text, file: path.display().to_string() };
    let raw: RawScene = toml::from_str(text).map_err(|error| parse_error(&src, &error))?;
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
    let first = body(&src, 0, &bodies.get_ref()[0])?;
    let second = body(&src, 1, &bodies.get_ref()[1])?;
    let Some(contact) = &raw.contact else {
        return Err(src.error("contact", None, "missing: give a [contact] table with at least `law`"));
    };
    let contact = contact_spec(&src, contact)?;
    let solver = raw.solver.as_ref().map_or(Ok(SolverSpec::default()), |s| solver(&src, s.get_ref()))?;
    let output = raw.output.as_ref().map_or(OutputSpec::default(), |o| output(o.get_ref()));
    let scene = Scene { title, bodies: [first, second], contact, solver, output };
    Setup::new(&scene).map_err(|error| {
        let line = src.line_of_key(&error.key);
        SceneError { file: src.file.clone(), key: Some(error.key), line, message: error.message, form: false }
    })?;
    Ok(scene)
}

fn parse_error(src: &Source, error: &toml::de::Error) -> SceneError {
    let span = error.span();
    let line = span.as_ref().map(|s| src.line(s));
    // A key or message may hold a huge piece of the input (a 10 000-character key): keep messages readable.
    let key = line.and_then(|n| src.key_on_line(n)).map(|key| cut(&key));
    let message = shorten(&error.message().trim().replace('\n', " "), 400);
    SceneError { file: src.file.clone(), key, line, message, form: true }
}

fn body(src: &Source, i: usize, raw: &At<RawBody>) -> Checked<Body> {
    let key = |leaf: &str| format!("bodies.{i}.{leaf}");
    let table = raw.span();
    let raw = raw.get_ref();
    let missing = |leaf: &str, what: &str| src.error(&key(leaf), Some(&table), format!("missing: {what}"));
    let radius = match &raw.radius {
        Some(r) => number(src, &key("radius"), r, Allowed::PositiveOrInfinite)?,
        None => return Err(missing("radius", "give `radius` in m (inf for a flat wall)")),
    };
    let mass = match (&raw.mass, &raw.density) {
        (Some(_), Some(d)) => {
            return Err(src.error(&key("density"), Some(&d.span()), "give `mass` or `density`, not both"));
        }
        (Some(m), None) => number(src, &key("mass"), m, Allowed::PositiveOrInfinite)?,
        (None, Some(d)) => {
            let density = number(src, &key("density"), d, Allowed::Positive)?;
            if radius.is_infinite() {
                return Err(src.error(
                    &key("density"),
                    Some(&d.span()),
                    "`density` needs a finite radius: a flat body's mass would be infinite (give `mass`)",
                ));
            }
            let mass = density * 4.0 / 3.0 * std::f64::consts::PI * radius.powi(3);
            if !(mass.is_finite() && mass > 0.0) {
                return Err(src.error(
                    &key("density"),
                    Some(&d.span()),
                    format!(
                        "the mass (4/3) pi r^3 density = {mass:e} kg of this radius and density is outside double \
                         precision: give `mass` or check the radius"
                    ),
                ));
            }
            mass
        }
        (None, None) => return Err(missing("mass", "give `mass` in kg (inf for immovable) or `density` in kg/m^3")),
    };
    let velocity = match &raw.velocity {
        Some(v) => vector(src, &key("velocity"), v)?,
        None => return Err(missing("velocity", "give `velocity = [vx, vy, vz]` in m/s")),
    };
    let position = raw.position.as_ref().map(|p| vector(src, &key("position"), p)).transpose()?;
    let angular_velocity = match &raw.angular_velocity {
        Some(w) => {
            let spin = vector(src, &key("angular_velocity"), w)?;
            if spin != Vector3::zeros() && radius.is_infinite() {
                return Err(src.error(
                    &key("angular_velocity"),
                    Some(&w.span()),
                    "a flat body (radius = inf) cannot spin: use [0, 0, 0] or leave it out",
                ));
            }
            spin
        }
        None => Vector3::zeros(),
    };
    let inertia = match &raw.inertia {
        None => Body::solid_sphere_inertia(mass, radius),
        Some(i) => {
            let inertia = number(src, &key("inertia"), i, Allowed::Positive)?;
            let why = if mass.is_infinite() {
                Some("an immovable body (mass = inf) does not rotate")
            } else if radius.is_infinite() {
                Some("a flat body (radius = inf) does not rotate")
            } else {
                None
            };
            if let Some(why) = why {
                return Err(src.error(&key("inertia"), Some(&i.span()), format!("{why}: leave `inertia` out")));
            }
            inertia
        }
    };
    let young = raw.young.as_ref().map(|e| number(src, &key("young"), e, Allowed::PositiveOrInfinite)).transpose()?;
    let poisson = raw.poisson.as_ref().map(|nu| number(src, &key("poisson"), nu, Allowed::Any)).transpose()?;
    if let (Some(nu), Some(at)) = (poisson, &raw.poisson)
        && !(nu > -1.0 && nu <= 0.5)
    {
        return Err(src.error(&key("poisson"), Some(&at.span()), format!("expected a number in (-1, 0.5], got {nu}")));
    }
    let name = raw.name.as_ref().map_or_else(|| format!("body {}", i + 1), |n| n.get_ref().clone());
    Ok(Body { name, mass, radius, velocity, position, angular_velocity, inertia, young, poisson })
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
            format!("unknown law `{}`; expected one of {}", law_name.get_ref(), LawKind::names().join(", ")),
        ));
    };
    let damping = damping_spec(src, law, raw, &table)?;
    let (stiffness, exponent) = stiffness_and_exponent(src, law, raw, &table)?;
    let separation = match &raw.separation {
        None => Separation::Penetration,
        Some(s) => match s.get_ref().as_str() {
            "penetration" => Separation::Penetration,
            "force" => Separation::Force,
            other => {
                return Err(src.error(
                    "contact.separation",
                    Some(&s.span()),
                    format!("expected \"penetration\" or \"force\", got \"{other}\""),
                ));
            }
        },
    };
    let friction =
        raw.friction.as_ref().map(|f| number(src, "contact.friction", f, Allowed::NonNegative)).transpose()?;
    let tangential_stiffness = match &raw.tangential_stiffness {
        None => TangentialStiffnessSpec::Mindlin,
        Some(value) => match value.get_ref() {
            toml::Value::String(s) if s == "mindlin" => TangentialStiffnessSpec::Mindlin,
            toml::Value::Float(_) | toml::Value::Integer(_) => {
                let k = value.get_ref().as_float().or_else(|| value.get_ref().as_integer().map(|i| i as f64));
                let k = At::new(value.span(), k.unwrap_or(f64::NAN));
                TangentialStiffnessSpec::Value(number(src, "contact.tangential_stiffness", &k, Allowed::Positive)?)
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
    let tangential_damping = raw
        .tangential_damping
        .as_ref()
        .map(|c| number(src, "contact.tangential_damping", c, Allowed::NonNegative))
        .transpose()?
        .unwrap_or(0.0);
    let normal = match &raw.normal {
        Some(n) => {
            let v = vector(src, "contact.normal", n)?;
            let length = v.norm();
            if length == 0.0 || !length.is_finite() {
                return Err(src.error("contact.normal", Some(&n.span()), "the normal must be a non-zero vector"));
            }
            Some(v / length)
        }
        None => None,
    };
    Ok(ContactSpec {
        law,
        damping,
        stiffness,
        exponent,
        separation,
        friction: friction.unwrap_or(0.0),
        tangential_stiffness,
        tangential_damping,
        normal,
    })
}

fn damping_spec(src: &Source, law: LawKind, raw: &RawContact, table: &Range<usize>) -> Checked<DampingSpec> {
    let restitution =
        raw.restitution.as_ref().map(|e| number(src, "contact.restitution", e, Allowed::Fraction)).transpose()?;
    let damping = raw.damping.as_ref().map(|c| number(src, "contact.damping", c, Allowed::NonNegative)).transpose()?;
    let name = law.name();
    let restitution_span = raw.restitution.as_ref().map(|e| e.span());
    match (law.family(), restitution, damping) {
        (_, Some(_), Some(_)) => Err(src.error(
            "contact.damping",
            raw.damping.as_ref().map(|c| c.span()).as_ref(),
            "give `restitution` or `damping`, not both",
        )),
        (Family::Elastic, None, None) => Ok(DampingSpec::None),
        (Family::Elastic, None, Some(_)) => Err(src.error(
            "contact.damping",
            raw.damping.as_ref().map(|c| c.span()).as_ref(),
            "the elastic law `hertz` takes no damping",
        )),
        (Family::Viscoelastic, Some(_), None) => Err(src.error(
            "contact.restitution",
            restitution_span.as_ref(),
            "`brilliantov` takes no `restitution` (its e depends on impact speed): give `damping` A in s",
        )),
        (_, None, None) => Err(src.error(
            "contact.restitution",
            Some(table),
            format!("missing: `{name}` needs `restitution` (nominal e) or `damping` ({})", law.info().damping_units),
        )),
        (_, None, Some(c)) => Ok(DampingSpec::Parameter(c)),
        (_, Some(e), None) => match check_restitution(law, e) {
            Ok(()) => Ok(DampingSpec::Restitution(e)),
            Err(MapError::NoMap) => Err(src.error(
                "contact.restitution",
                restitution_span.as_ref(),
                format!("`{name}` is elastic: restitution must be 1 (or left out), got {e}"),
            )),
            Err(MapError::UndefinedAtZero) => Err(src.error(
                "contact.restitution",
                restitution_span.as_ref(),
                format!("the map of `{name}` ({}) is undefined at e = 0", law.info().map),
            )),
        },
    }
}

fn stiffness_and_exponent(
    src: &Source,
    law: LawKind,
    raw: &RawContact,
    table: &Range<usize>,
) -> Checked<(StiffnessSpec, f64)> {
    let stiffness = match &raw.stiffness {
        None => StiffnessSpec::Hertz,
        Some(value) => match value.get_ref() {
            toml::Value::String(s) if s == "hertz" => StiffnessSpec::Hertz,
            toml::Value::Float(_) | toml::Value::Integer(_) => {
                let k = value.get_ref().as_float().or_else(|| value.get_ref().as_integer().map(|i| i as f64));
                let k = At::new(value.span(), k.unwrap_or(f64::NAN));
                StiffnessSpec::Value(number(src, "contact.stiffness", &k, Allowed::Positive)?)
            }
            other => {
                return Err(src.error(
                    "contact.stiffness",
                    Some(&value.span()),
                    format!("expected \"hertz\" or a number in N/m^n, got {other}"),
                ));
            }
        },
    };
    let exponent = raw.exponent.as_ref().map(|n| number(src, "contact.exponent", n, Allowed::Positive)).transpose()?;
    let exponent_span = raw.exponent.as_ref().map(|n| n.span());
    let bad_exponent = |message: &str| src.error("contact.exponent", exponent_span.as_ref(), message);
    let family = law.family();
    if matches!(family, Family::Tsuji | Family::Viscoelastic) && exponent.is_some() {
        return Err(bad_exponent(&format!("`{}` fixes the exponent at 3/2: leave `exponent` out", law.name())));
    }
    if family == Family::Linear {
        if stiffness == StiffnessSpec::Hertz {
            return Err(src.error(
                "contact.stiffness",
                Some(&raw.stiffness.as_ref().map_or_else(|| table.clone(), |s| s.span())),
                "`kelvin-voigt` needs a numeric `stiffness` k in N/m",
            ));
        }
        if exponent.is_some_and(|n| n != 1.0) {
            return Err(bad_exponent("`kelvin-voigt` is linear: `exponent` must be 1 (or left out)"));
        }
        return Ok((stiffness, 1.0));
    }
    if stiffness == StiffnessSpec::Hertz && exponent.is_some_and(|n| n != 1.5) {
        return Err(bad_exponent(
            "stiffness = \"hertz\" fixes the exponent at 1.5: give a numeric stiffness for another",
        ));
    }
    Ok((stiffness, exponent.unwrap_or(1.5)))
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
    Ok(SolverSpec { method, tolerances: tolerances(src, raw)? })
}

fn tolerances(src: &Source, raw: &RawSolver) -> Checked<Tolerances> {
    let defaults = Tolerances::default();
    let tolerance = |key: &str, value: &Option<At<f64>>, default: f64| -> Checked<f64> {
        let Some(value) = value else { return Ok(default) };
        let x = number(src, key, value, Allowed::Positive)?;
        if !(1e-14..=1e-2).contains(&x) {
            return Err(src.error(
                key,
                Some(&value.span()),
                format!("expected a tolerance in [1e-14, 1e-2], got {x:e}"),
            ));
        }
        Ok(x)
    };
    Ok(Tolerances {
        rtol: tolerance("solver.rtol", &raw.rtol, defaults.rtol)?,
        atol: tolerance("solver.atol", &raw.atol, defaults.atol)?,
    })
}

fn output(raw: &RawOutput) -> OutputSpec {
    OutputSpec {
        series: raw.series.as_ref().map(|s| s.get_ref().into()),
        plots: raw.plots.as_ref().map(|p| p.get_ref().into()),
    }
}
