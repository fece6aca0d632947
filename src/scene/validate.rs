//! From the raw file to a [`Scene`] whose values are checked, each failure naming file, key and line: first the
//! file's form is converted (TOML syntax, known keys, value types, what must be there) into a typed scene, then every
//! value rule is checked on it ([`super::rules`], the same rules a sweep's points obey). The physics-level rules
//! come after, in `setup.rs` (docs/scene.md lists them all), located by the [`Read`] this gives. Lines come from the
//! spans the conversion records for every key.

use super::file::{At, RawBody, RawContact, RawOutput, RawPair, RawScene, RawSolver, RawSphere, RawWorld};
use super::world::{DampingMap, MAX_CONTACTS_LIMIT, MAX_STEPS_LIMIT, PairSpec, WorldScene, WorldSpec};
use super::{
    ContactSpec, DampingSpec, FrictionCap, Method, OutputSpec, Parsed, Scene, SceneError, SetupError, SolverSpec,
    StiffnessSpec, TangentialStiffnessSpec, TangentialUnloading,
};
use crate::body::Body;
use crate::integrate::Tolerances;
use crate::law::{LawKind, Separation};
use crate::{files, text};
use nalgebra::{Matrix3, Vector3};
use std::collections::HashMap;
use std::ops::Range;
use std::path::Path;

/// Where errors point: the file and its text (for lines), and the line of every key the conversion met.
struct Source<'a> {
    text: &'a str,
    file: String,
    lines: std::cell::RefCell<HashMap<String, usize>>,
    /// The byte offset of every line break of `text`, found once (a scene of thousands of bodies notes every key).
    breaks: std::cell::OnceCell<Vec<usize>>,
}

type Checked<T> = Result<T, SceneError>;

impl Source<'_> {
    fn line(&self, span: &Range<usize>) -> usize {
        let start = span.start.min(self.text.len());
        let breaks = self.breaks.get_or_init(|| self.text.match_indices('\n').map(|(at, _)| at).collect());
        breaks.partition_point(|&at| at < start) + 1
    }

    /// Records where `key` is written, for the rules' errors.
    fn note(&self, key: &str, span: &Range<usize>) {
        self.lines.borrow_mut().insert(key.to_string(), self.line(span));
    }

    /// A broken rule, located: the key's recorded line, or the line its name is found on (for a key not written, its
    /// table's header).
    fn located(&self, error: SetupError) -> SceneError {
        let line = self.lines.borrow().get(&error.key).copied().or_else(|| self.line_of_key(&error.key));
        SceneError { file: self.file.clone(), key: Some(error.key), line, message: error.message, form: false }
    }

    fn error(&self, key: &str, span: Option<&Range<usize>>, message: impl Into<String>) -> SceneError {
        SceneError {
            file: self.file.clone(),
            key: Some(key.to_string()),
            line: span.map(|s| self.line(s)),
            message: message.into(),
            // Missing tables, a wrong number of bodies, a bad separation or tangential word or output path: nothing
            // a sweep's numbers can set.
            form: matches!(key, "bodies" | "contact" | "contact.separation" | "output.series" | "output.plots")
                || key.ends_with(".separation")
                || key.ends_with(".tangential_unloading")
                || key.ends_with(".friction_cap")
                || key.starts_with("pair.") && key.ends_with(".bodies"),
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

/// A list of exactly `N` numbers as written (its values are the rules' business), its line recorded; `form` says what
/// the list holds.
fn numbers<const N: usize>(src: &Source, key: &str, value: &At<Vec<f64>>, form: &str) -> Checked<[f64; N]> {
    let span = value.span();
    src.note(key, &span);
    let items = value.get_ref();
    <[f64; N]>::try_from(items.as_slice())
        .map_err(|_| src.error(key, Some(&span), format!("expected {form} ({N} numbers), got {} numbers", items.len())))
}

/// A body's `inertia` as written: one number (the same about every axis), three principal moments `[Ixx, Iyy, Izz]`
/// along the scene axes, or a 3×3 tensor (rows); its values are the rules' business.
fn inertia(src: &Source, key: &str, value: &At<toml::Value>) -> Checked<(Option<f64>, Option<Matrix3<f64>>)> {
    let span = value.span();
    src.note(key, &span);
    let scalar = |v: &toml::Value| v.as_float().or_else(|| v.as_integer().map(|i| i as f64));
    let expected = "expected a number (kg m²), three principal moments [Ixx, Iyy, Izz], or a 3×3 tensor \
                    [[Ixx, Ixy, Ixz], [Iyx, Iyy, Iyz], [Izx, Izy, Izz]]";
    let wrong = |got: &str| src.error(key, Some(&span), format!("{expected}, got {}", cut(got)));
    match value.get_ref() {
        toml::Value::Array(items) if items.len() == 3 && items.iter().all(|v| scalar(v).is_some()) => {
            let m: Vec<f64> = items.iter().filter_map(scalar).collect();
            Ok((None, Some(Matrix3::from_diagonal(&Vector3::new(m[0], m[1], m[2])))))
        }
        toml::Value::Array(rows) if rows.len() == 3 => {
            let mut tensor = Matrix3::zeros();
            for (i, row) in rows.iter().enumerate() {
                let Some(row) = row.as_array().filter(|r| r.len() == 3 && r.iter().all(|v| scalar(v).is_some())) else {
                    return Err(wrong(&super::echoed(value.get_ref())));
                };
                for (j, v) in row.iter().enumerate() {
                    tensor[(i, j)] = scalar(v).unwrap_or(f64::NAN);
                }
            }
            Ok((None, Some(tensor)))
        }
        other => match scalar(other) {
            Some(number) => Ok((Some(number), None)),
            None => Err(wrong(&super::echoed(other))),
        },
    }
}

/// A scene as read from its text: its form converted and every value rule checked, with the line of every key
/// written, which locates a rule found broken after reading (the physics-level rules of `setup::Setup`).
pub struct Read<'a, T> {
    /// The scene read.
    pub scene: T,
    source: Source<'a>,
}

impl<T> Read<'_, T> {
    /// A rule broken after reading, located: the key's recorded line, or the line its name is found on.
    pub fn located(&self, error: SetupError) -> SceneError {
        self.source.located(error)
    }
}

/// Reads a two-body scene: its form, then every value rule.
pub fn scene<'a>(text: &'a str, path: &Path) -> Checked<Read<'a, Scene>> {
    let src = source(text, path);
    let scene = convert_in(&src)?;
    super::rules::check(&scene).map_err(|error| src.located(error))?;
    Ok(Read { scene, source: src })
}

/// The typed scene of `text` with its form checked and its values not (see [`Scene::convert`]), and the line of
/// every key written.
pub fn convert(text: &str, path: &Path) -> Checked<(Scene, HashMap<String, usize>)> {
    let src = source(text, path);
    let scene = convert_in(&src)?;
    Ok((scene, src.lines.into_inner()))
}

/// A broken rule located in `text`: the line of its key.
pub fn located(text: &str, path: &Path, error: SetupError) -> SceneError {
    source(text, path).located(error)
}

fn source<'a>(text: &'a str, path: &Path) -> Source<'a> {
    Source { text, file: path.display().to_string(), lines: Default::default(), breaks: Default::default() }
}

fn convert_in(src: &Source) -> Checked<Scene> {
    let raw: RawScene = toml::from_str(src.text).map_err(|error| parse_error(src, &error))?;
    if let Some(why) = world_reason(&raw) {
        let span = raw.world.as_ref().map(At::span).or_else(|| raw.bodies.as_ref().map(At::span));
        return Err(src.error(
            "bodies",
            span.as_ref(),
            format!(
                "a world run ({why}) is run by `impact run` and swept by `impact sweep`; this command takes a scene of \
                 exactly two bodies without `[world]` or `[[pair]]`"
            ),
        ));
    }
    convert_impact(src, &raw)
}

/// Why a scene is a world run (docs/scene.md#worlds), if it is one: a `[world]` table, `[[pair]]` tables, or more
/// than two bodies.
fn world_reason(raw: &RawScene) -> Option<String> {
    let count = raw.bodies.as_ref().map_or(0, |b| b.get_ref().len());
    if raw.world.is_some() {
        Some("it has a [world] table".into())
    } else if raw.pair.is_some() {
        Some("it has [[pair]] tables".into())
    } else if count > 2 {
        Some(format!("it has {count} bodies"))
    } else if raw.bodies.as_ref().is_some_and(|b| b.get_ref().iter().any(|body| body.get_ref().spheres.is_some())) {
        Some("a body has [[bodies.spheres]]".into())
    } else {
        None
    }
}

/// The title: the scene's, or the file's stem.
fn title(src: &Source, raw: &RawScene) -> String {
    match &raw.title {
        Some(title) => title.get_ref().clone(),
        None => Path::new(&src.file).file_stem().map_or_else(|| "scene".into(), |s| s.to_string_lossy().into_owned()),
    }
}

fn convert_impact(src: &Source, raw: &RawScene) -> Checked<Scene> {
    let title = title(src, raw);
    let Some(bodies) = &raw.bodies else {
        return Err(src.error("bodies", None, "missing: give two [[bodies]] tables"));
    };
    if bodies.get_ref().len() != 2 {
        let n = bodies.get_ref().len();
        return Err(src.error(
            "bodies",
            Some(&bodies.span()),
            format!("expected two [[bodies]] (or more, with positions, in a world run), got {n}"),
        ));
    }
    let first = body(src, 0, &bodies.get_ref()[0])?;
    let second = body(src, 1, &bodies.get_ref()[1])?;
    for (i, raw_body) in bodies.get_ref().iter().enumerate() {
        if let Some(normal) = &raw_body.get_ref().normal {
            return Err(src.error(
                &format!("bodies.{i}.normal"),
                Some(&normal.span()),
                "a body's `normal` is a flat body's face in a world run ([world]); a two-body scene gives the \
                 contact normal as `contact.normal`",
            ));
        }
    }
    let Some(contact) = &raw.contact else {
        return Err(src.error("contact", None, "missing: give a [contact] table with at least `law`"));
    };
    let contact = contact_spec(src, contact.get_ref(), Some(&contact.span()), &|leaf| format!("contact.{leaf}"))?;
    let solver = raw.solver.as_ref().map_or(Ok(SolverSpec::default()), |s| solver(src, s.get_ref()))?;
    let output = raw.output.as_ref().map_or(Ok(OutputSpec::default()), |o| output(src, o.get_ref()))?;
    let mut scene = Scene { title, bodies: [first, second], contact, solver, output };
    scene.resolve();
    Ok(scene)
}

/// Reads a scene of either kind, a two-body impact or a world run: its form, then every value rule.
pub fn any<'a>(text: &'a str, path: &Path) -> Checked<Read<'a, Parsed>> {
    let src = source(text, path);
    let raw: RawScene = toml::from_str(src.text).map_err(|error| parse_error(&src, &error))?;
    if world_reason(&raw).is_none() {
        let scene = convert_impact(&src, &raw)?;
        super::rules::check(&scene).map_err(|error| src.located(error))?;
        return Ok(Read { scene: Parsed::Impact(Box::new(scene)), source: src });
    }
    let world = convert_world(&src, &raw)?;
    super::rules::check_world(&world).map_err(|error| src.located(error))?;
    Ok(Read { scene: Parsed::World(Box::new(world)), source: src })
}

fn convert_world(src: &Source, raw: &RawScene) -> Checked<WorldScene> {
    let title = title(src, raw);
    let Some(bodies_raw) = &raw.bodies else {
        return Err(src.error("bodies", None, "missing: give the [[bodies]] of the world, each with `position`"));
    };
    if bodies_raw.get_ref().len() < 2 {
        let n = bodies_raw.get_ref().len();
        return Err(src.error(
            "bodies",
            Some(&bodies_raw.span()),
            format!("a world needs two bodies or more, got {n}"),
        ));
    }
    let mut bodies = Vec::with_capacity(bodies_raw.get_ref().len());
    let mut faces = Vec::with_capacity(bodies_raw.get_ref().len());
    for (i, raw_body) in bodies_raw.get_ref().iter().enumerate() {
        let body = body(src, i, raw_body)?;
        if body.position.is_none() {
            return Err(src.error(
                &format!("bodies.{i}.position"),
                Some(&raw_body.span()),
                "missing: every body of a world run needs `position` (m; a flat body: a point of its face)",
            ));
        }
        let face =
            raw_body.get_ref().normal.as_ref().map(|n| vector(src, &format!("bodies.{i}.normal"), n)).transpose()?;
        if body.is_flat() && face.is_none() {
            return Err(src.error(
                &format!("bodies.{i}.normal"),
                Some(&raw_body.span()),
                "missing: a flat body (radius = inf) of a world run needs `normal`, the unit normal of its face \
                 pointing into the side the other bodies move in (a floor: [0, 0, 1])",
            ));
        }
        if !body.is_flat()
            && let Some(normal) = &raw_body.get_ref().normal
        {
            return Err(src.error(
                &format!("bodies.{i}.normal"),
                Some(&normal.span()),
                "only a flat body (radius = inf) has a face `normal`",
            ));
        }
        bodies.push(body);
        faces.push(face);
    }
    let Some(contact_raw) = &raw.contact else {
        return Err(src.error(
            "contact",
            None,
            "missing: give a [contact] table with at least `law` (every pair's default)",
        ));
    };
    if let Some(normal) = &contact_raw.get_ref().normal {
        return Err(world_normal(src, "contact.normal", normal));
    }
    let contact =
        contact_spec(src, contact_raw.get_ref(), Some(&contact_raw.span()), &|leaf| format!("contact.{leaf}"))?;
    let mut pairs = Vec::new();
    for (k, pair_raw) in raw.pair.as_ref().map_or(&[][..], |p| p.get_ref().as_slice()).iter().enumerate() {
        pairs.push(pair(src, k, pair_raw, contact_raw.get_ref(), bodies.len())?);
    }
    for (k, pair) in pairs.iter().enumerate() {
        if let Some(first) = pairs[..k]
            .iter()
            .position(|other| other.bodies == pair.bodies || other.bodies == [pair.bodies[1], pair.bodies[0]])
        {
            let span = raw.pair.as_ref().map(|p| p.get_ref()[k].span());
            return Err(src.error(
                &format!("pair.{k}.bodies"),
                span.as_ref(),
                format!("bodies {:?} already have a [[pair]] (pair {first})", pair.bodies),
            ));
        }
    }
    let world = raw.world.as_ref().map_or(Ok(WorldSpec::default()), |w| world(src, w))?;
    let solver = raw.solver.as_ref().map_or(Ok(SolverSpec::default()), |s| solver(src, s.get_ref()))?;
    let output = raw.output.as_ref().map_or(Ok(OutputSpec::default()), |o| output(src, o.get_ref()))?;
    let mut scene = WorldScene { title, bodies, faces, contact, pairs, world, solver, output };
    scene.resolve();
    Ok(scene)
}

fn world_normal(src: &Source, key: &str, normal: &At<Vec<f64>>) -> SceneError {
    src.error(
        key,
        Some(&normal.span()),
        "a world run takes each contact's normal from the geometry (the line of centres, a flat body's face \
         `normal`): leave it out",
    )
}

/// One `[[pair]]`: its bodies, and `[contact]` with the pair's keys over it.
fn pair(src: &Source, k: usize, raw: &At<RawPair>, contact: &RawContact, count: usize) -> Checked<PairSpec> {
    let table = raw.span();
    let raw = raw.get_ref();
    let key = |leaf: &str| format!("pair.{k}.{leaf}");
    let Some(bodies) = &raw.bodies else {
        return Err(src.error(
            &key("bodies"),
            Some(&table),
            "missing: give `bodies = [i, j]`, two 0-based body indices",
        ));
    };
    src.note(&key("bodies"), &bodies.span());
    let indices: Vec<Option<usize>> =
        bodies.get_ref().iter().map(|v| v.as_integer().and_then(|i| usize::try_from(i).ok())).collect();
    let [Some(i), Some(j)] = indices[..] else {
        return Err(src.error(
            &key("bodies"),
            Some(&bodies.span()),
            format!(
                "expected two 0-based body indices [i, j], got {}",
                cut(&super::echoed(&toml::Value::Array(bodies.get_ref().clone())))
            ),
        ));
    };
    for index in [i, j] {
        if index >= count {
            return Err(src.error(
                &key("bodies"),
                Some(&bodies.span()),
                format!("body {index} does not exist: the scene has {count} bodies (0 to {})", count - 1),
            ));
        }
    }
    if i == j {
        return Err(src.error(
            &key("bodies"),
            Some(&bodies.span()),
            format!("a pair of two different bodies, got [{i}, {j}]"),
        ));
    }
    if let Some(normal) = &raw.normal {
        return Err(world_normal(src, &key("normal"), normal));
    }
    let mut merged = contact.clone();
    let mut written = Vec::new();
    macro_rules! over {
        ($($field:ident),*) => {
            $(if raw.$field.is_some() {
                merged.$field = raw.$field.clone();
                written.push(stringify!($field));
            })*
        };
    }
    over!(
        law,
        restitution,
        damping,
        stiffness,
        exponent,
        separation,
        friction,
        tangential_stiffness,
        tangential_damping,
        tangential_unloading,
        friction_cap,
        yield_pressure,
        solref,
        solimp,
        cmax,
        dmax
    );
    // A pair that names `damping` drops `[contact]`'s `restitution`, and the other way round: it gives its own. A
    // pair that names its own `law` takes neither from `[contact]` (another law's damping means something else).
    if raw.law.is_some() || (raw.damping.is_some() && raw.restitution.is_none()) {
        merged.restitution = raw.restitution.clone();
    }
    if raw.law.is_some() || (raw.restitution.is_some() && raw.damping.is_none()) {
        merged.damping = raw.damping.clone();
    }
    let leaf_key = |leaf: &str| if written.contains(&leaf) { key(leaf) } else { format!("contact.{leaf}") };
    let contact = contact_spec(src, &merged, Some(&table), &leaf_key)?;
    Ok(PairSpec { bodies: [i, j], contact, written })
}

fn world(src: &Source, raw: &At<RawWorld>) -> Checked<WorldSpec> {
    let raw = raw.get_ref();
    let defaults = WorldSpec::default();
    let gravity =
        raw.gravity.as_ref().map(|g| vector(src, "world.gravity", g)).transpose()?.unwrap_or(defaults.gravity);
    let end_time = raw.end_time.as_ref().map(|t| number(src, "world.end_time", t));
    let count = |key: &str, value: &Option<At<toml::Value>>, default: u64, limit: u64| match value {
        None => Ok(default),
        Some(value) => {
            src.note(key, &value.span());
            match value.get_ref().as_integer() {
                Some(n) if n >= 1 && (n as u64) <= limit => Ok(n as u64),
                _ => Err(src.error(
                    key,
                    Some(&value.span()),
                    format!("expected a whole number from 1 to {limit}, got {}", cut(&super::echoed(value.get_ref()))),
                )),
            }
        }
    };
    let max_contacts = count("world.max_contacts", &raw.max_contacts, defaults.max_contacts, MAX_CONTACTS_LIMIT)?;
    let max_steps = count("world.max_steps", &raw.max_steps, defaults.max_steps, MAX_STEPS_LIMIT)?;
    let damping_map = match &raw.damping_map {
        None => defaults.damping_map,
        Some(name) => {
            DampingMap::ALL.iter().find(|(spelling, _)| spelling == name.get_ref()).map(|(_, m)| *m).ok_or_else(
                || {
                    src.error(
                        "world.damping_map",
                        Some(&name.span()),
                        format!("expected \"each-contact\" or \"first-contact\", got \"{}\"", cut(name.get_ref())),
                    )
                },
            )?
        }
    };
    let skin = raw.skin.as_ref().map(|s| number(src, "world.skin", s));
    let coast = raw.coast.as_ref().map_or(defaults.coast, |c| {
        src.note("world.coast", &c.span());
        *c.get_ref()
    });
    Ok(WorldSpec { gravity, end_time, max_contacts, max_steps, damping_map, skin, coast })
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
    let spheres = match &raw.spheres {
        Some(spheres) => clump(src, i, raw, spheres)?,
        None => Vec::new(),
    };
    let radius = match (&raw.radius, spheres.is_empty()) {
        (Some(r), _) => number(src, &key("radius"), r),
        // A clump's radius is its bounding radius (resolved with the body).
        (None, false) => f64::NAN,
        (None, true) => {
            return Err(missing("radius", "give `radius` in m (inf for a flat wall), or [[bodies.spheres]]"));
        }
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
    let (inertia_given, inertia_tensor) = match &raw.inertia {
        None => (None, None),
        Some(value) => inertia(src, &key("inertia"), value)?,
    };
    let contact_offset =
        raw.contact_offset.as_ref().map(|c| vector(src, &key("contact_offset"), c)).transpose()?.unwrap_or_default();
    let pivot = raw.pivot.as_ref().map(|p| vector(src, &key("pivot"), p)).transpose()?;
    let young = raw.young.as_ref().map(|e| number(src, &key("young"), e));
    let poisson = raw.poisson.as_ref().map(|nu| number(src, &key("poisson"), nu));
    let yield_stress = raw.yield_stress.as_ref().map(|y| number(src, &key("yield_stress"), y));
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
        inertia_tensor,
        contact_offset,
        pivot,
        young,
        poisson,
        yield_stress,
        spheres,
    })
}

/// A clump's `[[bodies.spheres]]`: each sphere's offset and radius as written (their values are the rules'), and the
/// keys a clump excludes.
fn clump(
    src: &Source,
    i: usize,
    raw: &RawBody,
    spheres: &At<Vec<At<RawSphere>>>,
) -> Checked<Vec<crate::body::ContactSphere>> {
    let key = |leaf: &str| format!("bodies.{i}.{leaf}");
    let excluded = [
        ("radius", raw.radius.as_ref().map(At::span)),
        ("contact_offset", raw.contact_offset.as_ref().map(At::span)),
        ("density", raw.density.as_ref().map(At::span)),
    ];
    for (leaf, span) in excluded {
        if let Some(span) = span {
            let why = if leaf == "density" {
                "a clump gives its `mass` (kg): a density has no volume to act on"
            } else {
                "a body with [[bodies.spheres]] takes its contact spheres from them: leave `radius` and \
                 `contact_offset` out"
            };
            return Err(src.error(&key(leaf), Some(&span), why));
        }
    }
    if spheres.get_ref().is_empty() {
        return Err(src.error(&key("spheres"), Some(&spheres.span()), "give at least one [[bodies.spheres]]"));
    }
    src.note(&key("spheres"), &spheres.span());
    let mut list = Vec::new();
    for (s, sphere) in spheres.get_ref().iter().enumerate() {
        let table = sphere.span();
        let leaf = |name: &str| format!("bodies.{i}.spheres.{s}.{name}");
        let sphere = sphere.get_ref();
        let Some(radius) = &sphere.radius else {
            return Err(src.error(&leaf("radius"), Some(&table), "missing: give the sphere's `radius` in m"));
        };
        let offset = match &sphere.offset {
            Some(offset) => vector(src, &leaf("offset"), offset)?,
            None => {
                return Err(src.error(
                    &leaf("offset"),
                    Some(&table),
                    "missing: give the sphere's centre relative to the mass centre, `offset = [x, y, z]` in m",
                ));
            }
        };
        list.push(crate::body::ContactSphere { offset, radius: number(src, &leaf("radius"), radius) });
    }
    Ok(list)
}

/// A contact table (`[contact]`, or a `[[pair]]` over it) typed; `key` names each leaf where it is written.
fn contact_spec(
    src: &Source,
    raw: &RawContact,
    table: Option<&Range<usize>>,
    key: &dyn Fn(&str) -> String,
) -> Checked<ContactSpec> {
    let Some(law_name) = &raw.law else {
        return Err(src.error(
            &key("law"),
            table,
            format!("missing: give `law`, one of {}", LawKind::names().join(", ")),
        ));
    };
    let Some(law) = LawKind::from_name(law_name.get_ref()) else {
        return Err(src.error(
            &key("law"),
            Some(&law_name.span()),
            format!("unknown law `{}`; expected one of {}", cut(law_name.get_ref()), LawKind::names().join(", ")),
        ));
    };
    let restitution = raw.restitution.as_ref().map(|e| number(src, &key("restitution"), e));
    let damping_value = raw.damping.as_ref().map(|c| number(src, &key("damping"), c));
    let damping = match (restitution, damping_value) {
        (Some(_), Some(_)) => {
            return Err(src.error(
                &key("damping"),
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
                    &key("stiffness"),
                    Some(&value.span()),
                    format!("expected \"hertz\" or a number in N/m^n, got {}", cut(&other)),
                ))
            },
            |spec| {
                src.note(&key("stiffness"), &value.span());
                Ok(spec)
            },
        )?,
    };
    let exponent_given = raw.exponent.as_ref().map(|n| number(src, &key("exponent"), n));
    let separation = match &raw.separation {
        None => Separation::Penetration,
        Some(s) => match s.get_ref().as_str() {
            "penetration" => Separation::Penetration,
            "force" => Separation::Force,
            other => {
                return Err(src.error(
                    &key("separation"),
                    Some(&s.span()),
                    format!("expected \"penetration\" or \"force\", got \"{}\"", cut(other)),
                ));
            }
        },
    };
    let friction = raw.friction.as_ref().map_or(0.0, |f| number(src, &key("friction"), f));
    let tangential_stiffness = match &raw.tangential_stiffness {
        None => TangentialStiffnessSpec::Mindlin,
        Some(value) => match value.get_ref() {
            toml::Value::String(s) if s == "mindlin" => TangentialStiffnessSpec::Mindlin,
            toml::Value::Float(_) | toml::Value::Integer(_) => {
                src.note(&key("tangential_stiffness"), &value.span());
                let k = value.get_ref().as_float().or_else(|| value.get_ref().as_integer().map(|i| i as f64));
                TangentialStiffnessSpec::Value(k.unwrap_or(f64::NAN))
            }
            other => {
                return Err(src.error(
                    &key("tangential_stiffness"),
                    Some(&value.span()),
                    format!("expected \"mindlin\" or a number in N/m, got {}", cut(&super::echoed(other))),
                ));
            }
        },
    };
    let tangential_damping =
        raw.tangential_damping.as_ref().map_or(0.0, |c| number(src, &key("tangential_damping"), c));
    let tangential_unloading =
        word(src, &key("tangential_unloading"), raw.tangential_unloading.as_ref(), &TangentialUnloading::ALL)?;
    let friction_cap = word(src, &key("friction_cap"), raw.friction_cap.as_ref(), &FrictionCap::ALL)?;
    let yield_pressure = raw.yield_pressure.as_ref().map(|p| number(src, &key("yield_pressure"), p));
    let solref = raw
        .solref
        .as_ref()
        .map(|v| numbers::<2>(src, &key("solref"), v, "[timeconst, dampratio] or [-stiffness, -damping]"))
        .transpose()?;
    let solimp = raw
        .solimp
        .as_ref()
        .map(|v| numbers::<5>(src, &key("solimp"), v, "[dmin, dmax, width, midpoint, power]"))
        .transpose()?;
    let cmax = raw.cmax.as_ref().map(|c| number(src, &key("cmax"), c));
    let dmax = raw.dmax.as_ref().map(|d| number(src, &key("dmax"), d));
    let normal_given = raw.normal.as_ref().map(|n| vector(src, &key("normal"), n)).transpose()?;
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
        tangential_unloading,
        friction_cap,
        yield_pressure,
        solref,
        solimp,
        cmax,
        dmax,
        normal: None,
        normal_given,
    })
}

/// The choice a key's word names (`choices`, by spelling), or `T::default()` when the key is not written; an unknown
/// word is an error naming the key and its line.
fn word<T: Copy + Default>(
    src: &Source,
    key: &str,
    written: Option<&At<String>>,
    choices: &[(&'static str, T)],
) -> Checked<T> {
    let Some(value) = written else { return Ok(T::default()) };
    choices.iter().find(|(spelling, _)| spelling == value.get_ref()).map(|(_, choice)| *choice).ok_or_else(|| {
        let names: Vec<_> = choices.iter().map(|(spelling, _)| format!("\"{spelling}\"")).collect();
        src.error(
            key,
            Some(&value.span()),
            format!("expected {}, got \"{}\"", names.join(" or "), cut(value.get_ref())),
        )
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
    let dt = raw.dt.as_ref().map(|value| number(src, "solver.dt", value));
    Ok(SolverSpec { method, tolerances, dt })
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
