//! The one place where the core's errors become Python exceptions: `impact.SceneError` (a scene the command refuses,
//! exit 2), `impact.SimulationError` (a run that cannot finish, exit 1), `ValueError` (a bad argument, exit 2),
//! `TypeError` (a value of the wrong Python type), `OSError` (a file that cannot be written), and a panic caught at
//! the boundary (never a `PanicException`).

use impact::scene::SceneError;
use pyo3::exceptions::{PyOSError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Why a call gave no result, before it becomes a Python exception.
#[derive(Debug)]
pub enum Failure {
    /// A bad scene: where (the file, when it came from one; the line, when known), the key, what is wrong.
    Scene { error: SceneError, from_file: bool },
    /// A run that cannot finish.
    Simulation(String),
    /// A bad argument.
    Value(String),
    /// A value of the wrong type.
    Type(String),
    /// A file that cannot be written (or read, for an output's folder).
    Io(String),
    /// Ctrl-C: the Python error `check_signals` raised (KeyboardInterrupt), to re-raise as it is.
    Interrupted(PyErr),
}

impl From<PyErr> for Failure {
    fn from(error: PyErr) -> Failure {
        Failure::Interrupted(error)
    }
}

/// A class of the pure-Python layer (`impact.errors`), where the exceptions are defined once.
fn class<'py>(py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyAny>> {
    py.import("impact.errors")?.getattr(name)
}

impl Failure {
    /// The Python exception.
    pub fn into_pyerr(self, py: Python<'_>) -> PyErr {
        let made = match self {
            Failure::Scene { error, from_file } => scene_error(py, error, from_file),
            Failure::Simulation(message) => {
                class(py, "SimulationError").and_then(|c| c.call1((message,))).map(PyErr::from_value)
            }
            Failure::Value(message) => Ok(PyValueError::new_err(message)),
            Failure::Type(message) => Ok(PyTypeError::new_err(message)),
            Failure::Io(message) => Ok(PyOSError::new_err(message)),
            Failure::Interrupted(error) => Ok(error),
        };
        made.unwrap_or_else(|error| error)
    }
}

/// `impact.SceneError(text, path=, line=, key=, message=)`: `text` the command's message.
fn scene_error(py: Python<'_>, error: SceneError, from_file: bool) -> PyResult<PyErr> {
    let kwargs = PyDict::new(py);
    kwargs.set_item("path", from_file.then(|| error.file.clone()))?;
    kwargs.set_item("line", error.line)?;
    kwargs.set_item("key", error.key.clone())?;
    kwargs.set_item("message", error.message.clone())?;
    let exception = class(py, "SceneError")?.call((error.to_string(),), Some(&kwargs))?;
    Ok(PyErr::from_value(exception))
}

/// Runs `work` (the core's computation), turning a panic into `SimulationError` rather than letting it cross into
/// Python as a `PanicException` (the last line of defence: the core's errors are values, not panics).
pub fn guarded<T>(work: impl FnOnce() -> Result<T, Failure>) -> Result<T, Failure> {
    match std::panic::catch_unwind(std::panic::AssertUnwindSafe(work)) {
        Ok(result) => result,
        Err(panic) => {
            let what = panic
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| panic.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown".into());
            Err(Failure::Simulation(format!(
                "internal error (a bug in impact, please report it with the scene): {what}"
            )))
        }
    }
}
