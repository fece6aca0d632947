//! A scene from Python: a file's path, TOML text, or a `dict` shaped like the TOML. Each becomes TOML text read by
//! the same reader and rules as a file (`impact::setup::parse_any`), so that every error is the command's; a dict is
//! converted to a TOML document first, its errors naming the dict's dotted path (0-based indices) and no line.

use crate::errors::Failure;
use impact::scene::{Parsed, SceneError, SetupError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
use std::path::{Path, PathBuf};

/// What a scene came as.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Origin {
    File,
    Text,
    Dict,
}

/// A scene's TOML text and where it came from.
#[derive(Debug, Clone)]
pub struct Source {
    pub text: String,
    /// The file, or `<text>` / `<dict>`: names the scene in messages, gives the default title.
    pub label: PathBuf,
    pub origin: Origin,
}

impl Source {
    /// The Python layer's `(kind, value)`: `("path", str)`, `("text", str)` or `("dict", dict)`.
    pub fn from_python(kind: &str, value: &Bound<'_, PyAny>) -> Result<Source, Failure> {
        match kind {
            "path" => {
                let path = PathBuf::from(value.extract::<String>().map_err(|_| type_error(value))?);
                let text = std::fs::read_to_string(&path).map_err(|error| Failure::Scene {
                    error: SceneError::file(&path, format!("cannot read the scene: {error}")),
                    from_file: true,
                })?;
                Ok(Source { text, label: path, origin: Origin::File })
            }
            "text" => Ok(Source {
                text: value.extract::<String>().map_err(|_| type_error(value))?,
                label: PathBuf::from("<text>"),
                origin: Origin::Text,
            }),
            "dict" => {
                let table = table(value, "")?;
                let text = toml::to_string(&table)
                    .map_err(|error| dict_error(None, format!("cannot be written as TOML: {error}")))?;
                Ok(Source { text, label: PathBuf::from("<dict>"), origin: Origin::Dict })
            }
            _ => Err(type_error(value)),
        }
    }

    /// A scene error of this source as Python sees it: a dict's lines are those of the TOML made from it, not the
    /// user's, so they are dropped.
    pub fn failure(&self, mut error: SceneError) -> Failure {
        if self.origin == Origin::Dict {
            error.line = None;
        }
        Failure::Scene { error, from_file: self.origin == Origin::File }
    }

    /// A broken rule found by the run (a world's contact at its own speed), located in this source's text.
    pub fn located(&self, error: SetupError) -> Failure {
        self.failure(impact::scene::located_in(&self.text, &self.label, error))
    }

    /// The scene read with every rule of a file.
    pub fn parse(&self) -> Result<Parsed, Failure> {
        impact::setup::parse_any(&self.text, &self.label).map_err(|error| self.failure(error))
    }

    pub fn path(&self) -> &Path {
        &self.label
    }
}

fn type_error(value: &Bound<'_, PyAny>) -> Failure {
    let name = value.get_type().name().map(|n| n.to_string()).unwrap_or_else(|_| "?".into());
    Failure::Type(format!(
        "scene: expected a path (str or os.PathLike), TOML text or a dict shaped like the TOML, got {name}"
    ))
}

/// A scene error about the dict, at the dotted path `key`.
fn dict_error(key: Option<&str>, message: String) -> Failure {
    Failure::Scene {
        error: SceneError {
            file: "<dict>".into(),
            key: key.filter(|k| !k.is_empty()).map(str::to_string),
            line: None,
            message,
            form: true,
        },
        from_file: false,
    }
}

/// Deepest nesting of dicts and lists a scene may have: a scene's deepest value is an inertia tensor in a list of
/// tables (four levels); a deeper one (or a dict that holds itself) is refused before the conversion, which recurses,
/// could exhaust the stack.
const MAX_DEPTH: usize = 32;

fn joined(path: &str, part: &str) -> String {
    if path.is_empty() { part.to_string() } else { format!("{path}.{part}") }
}

/// A dict as a TOML table; `path` is its dotted key.
fn table(value: &Bound<'_, PyAny>, path: &str) -> Result<toml::Table, Failure> {
    let Ok(dict) = value.cast::<PyDict>() else {
        return Err(dict_error(Some(path), format!("expected a table (a dict), got {}", type_name(value))));
    };
    let mut table = toml::Table::new();
    for (key, item) in dict.iter() {
        let Ok(key) = key.cast::<PyString>().map(|k| k.to_string()) else {
            return Err(dict_error(
                Some(path),
                format!("a key must be a string, got {} `{}`", type_name(&key), shown(&key)),
            ));
        };
        let at = joined(path, &key);
        table.insert(key, toml_value(&item, &at)?);
    }
    Ok(table)
}

/// A Python value as a TOML value: bool, int, float, str, a list or tuple (or a numpy array, through `tolist`) as an
/// array, a dict as a table. `None` and other types have no TOML form: the error names the key.
fn toml_value(value: &Bound<'_, PyAny>, path: &str) -> Result<toml::Value, Failure> {
    if path.split('.').count() > MAX_DEPTH {
        let shown = impact::text::cut(path, impact::text::MESSAGE_CHARS);
        return Err(dict_error(
            None,
            format!("`{shown}` is nested more than {MAX_DEPTH} deep (a dict or list that holds itself?)"),
        ));
    }
    if value.is_instance_of::<PyBool>() {
        return Ok(toml::Value::Boolean(value.extract::<bool>().unwrap_or(false)));
    }
    if value.is_instance_of::<PyInt>() {
        return match value.extract::<i64>() {
            Ok(n) => Ok(toml::Value::Integer(n)),
            Err(_) => Err(dict_error(
                Some(path),
                format!("the integer {} is beyond TOML's 64 bits: write it as a float", shown(value)),
            )),
        };
    }
    if value.is_instance_of::<PyFloat>() {
        return Ok(toml::Value::Float(value.extract::<f64>().unwrap_or(f64::NAN)));
    }
    if let Ok(text) = value.cast::<PyString>() {
        return Ok(toml::Value::String(text.to_string()));
    }
    if value.is_instance_of::<PyDict>() {
        return Ok(toml::Value::Table(table(value, path)?));
    }
    if value.is_instance_of::<PyList>() || value.is_instance_of::<PyTuple>() {
        let mut items = Vec::new();
        for (k, item) in value.try_iter().map_err(|_| dict_error(Some(path), "cannot be read".into()))?.enumerate() {
            let item = item.map_err(|_| dict_error(Some(path), "cannot be read".into()))?;
            items.push(toml_value(&item, &joined(path, &k.to_string()))?);
        }
        return Ok(toml::Value::Array(items));
    }
    // numpy scalars and arrays: their Python equivalents.
    if value.hasattr("tolist").unwrap_or(false)
        && let Ok(plain) = value.call_method0("tolist")
        && !plain.is(value)
        && !plain.hasattr("tolist").unwrap_or(false)
    {
        return toml_value(&plain, path);
    }
    if value.is_none() {
        return Err(dict_error(Some(path), "None has no TOML form: leave the key out for its default".into()));
    }
    Err(dict_error(
        Some(path),
        format!("a {} has no TOML form: give a number, a string, a bool, a list or a dict", type_name(value)),
    ))
}

fn type_name(value: &Bound<'_, PyAny>) -> String {
    value.get_type().name().map(|n| n.to_string()).unwrap_or_else(|_| "?".into())
}

fn shown(value: &Bound<'_, PyAny>) -> String {
    let text = value.repr().map(|r| r.to_string()).unwrap_or_default();
    impact::text::cut(&text, impact::text::MESSAGE_CHARS)
}
