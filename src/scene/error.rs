//! A bad scene, located (file, key, line), and a broken rule before it is located (the key alone).

use std::fmt;
use std::path::Path;

/// Why a scene cannot be simulated, with where it says so.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub struct SceneError {
    /// The scene file.
    pub file: String,
    /// The dotted key (0-based indices, e.g. `bodies.1.velocity`), when one key is at fault.
    pub key: Option<String>,
    /// 1-based line, when known.
    pub line: Option<usize>,
    /// What is wrong and what was expected.
    pub message: String,
    /// Whether the file's form is wrong (TOML syntax, an unknown key, a value of the wrong type, missing tables),
    /// as opposed to a value out of its range: no sweep over values can mend such a file.
    pub form: bool,
}

impl SceneError {
    /// An error about the file as a whole.
    pub fn file(path: &Path, message: impl Into<String>) -> SceneError {
        SceneError { file: path.display().to_string(), key: None, line: None, message: message.into(), form: true }
    }
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.file)?;
        if let Some(line) = self.line {
            write!(f, ", line {line}")?;
        }
        if let Some(key) = &self.key {
            write!(f, ", key `{key}`")?;
        }
        write!(f, ": {}", self.message)
    }
}

/// A broken rule of a scene, not yet located: the key at fault and what is wrong. The scene's value rules
/// (`rules.rs`) and the physics-level rules of `setup::Setup` both give it; whoever knows the file adds the line
/// ([`located`](super::located), or the lines recorded while reading).
#[derive(Debug, Clone, PartialEq)]
pub struct SetupError {
    /// Dotted scene key, 0-based (`bodies.1.velocity`).
    pub key: String,
    pub message: String,
}
