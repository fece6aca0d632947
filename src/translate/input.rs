//! `impact translate --to lammps --input DIR`: the whole scene as a runnable LAMMPS input.

use super::{TranslateError, Translation};
use crate::scene::Scene;
use std::path::Path;

/// Writes `folder`/in.impact and `folder`/data.impact for the scene (not built yet).
pub fn write(
    _folder: &Path,
    _scene_path: &Path,
    _scene: &Scene,
    _translation: &Translation,
    _dt: Option<f64>,
) -> Result<(), TranslateError> {
    Err(TranslateError::bad("--input", "not built yet"))
}
