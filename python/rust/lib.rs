//! `impact._impact`, the compiled half of the Python package: it converts Python values to the core's (a scene's
//! path, text or dict; the command's arguments), calls the same library functions the `impact` command calls, and
//! hands back their results (the JSON text the command prints, numpy arrays of columns, SVG text). It never derives
//! anything itself; the ergonomics (Mapping, progress bars, executors, pandas) are the pure-Python layer's
//! (`src/impact/`). Errors cross once, in `errors.rs`.

mod columns;
mod errors;
mod run;
mod scene;
mod sweep;

use errors::{Failure, guarded};
use impact::scene::Parsed;
use pyo3::prelude::*;
use scene::Source;

/// `impact models`' table as JSON: each law's name, force, map from e, damping units and source.
#[pyfunction]
fn laws() -> String {
    let laws: Vec<serde_json::Value> = impact::law::catalogue::LAWS
        .iter()
        .map(|law| {
            serde_json::json!({
                "name": law.name,
                "formula": law.formula,
                "map": law.map,
                "damping_units": law.damping_units,
                "source": law.source,
            })
        })
        .collect();
    serde_json::to_string(&laws).unwrap_or_else(|_| "[]".into())
}

/// `impact validate --json [--case NAME]`: the rows as JSON.
#[pyfunction]
#[pyo3(signature = (case = None))]
fn validate(py: Python<'_>, case: Option<String>) -> PyResult<String> {
    let outcome = py.detach(|| {
        guarded(|| match impact::validate::run(case.as_deref()) {
            Ok(rows) => serde_json::to_string_pretty(&rows).map_err(|e| Failure::Simulation(e.to_string())),
            Err(why) if why.starts_with("no validation case") => Err(Failure::Value(why)),
            Err(why) => Err(Failure::Simulation(why)),
        })
    });
    outcome.map_err(|failure| failure.into_pyerr(py))
}

/// `impact translate SCENE --to PEER [--dt SECONDS] --json`: the translation as JSON.
#[pyfunction]
#[pyo3(signature = (kind, scene, to, dt = None))]
fn translate(py: Python<'_>, kind: &str, scene: &Bound<'_, PyAny>, to: &str, dt: Option<f64>) -> PyResult<String> {
    use impact::translate::{Peer, TranslateError, translate};
    let outcome = (|| {
        let peer = Peer::named(to).map_err(Failure::Value)?;
        let source = Source::from_python(kind, scene)?;
        py.detach(|| {
            guarded(|| {
                let scene = match source.parse()? {
                    Parsed::Impact(scene) => scene,
                    Parsed::World(_) => {
                        let error = impact::scene::SceneError::file(source.path(), impact::translate::WORLD_AS_A_WHOLE);
                        return Err(source.failure(error));
                    }
                };
                let dt = dt.or(scene.solver.dt);
                let translation = translate(&scene, peer, dt).map_err(|error| match error {
                    TranslateError::Bad { key, message } if key.starts_with("--") => {
                        Failure::Value(format!("{key}: {message}"))
                    }
                    TranslateError::Bad { key, message } => source.located(impact::scene::SetupError { key, message }),
                    TranslateError::Simulation(error) => run::impact_failure(&source, error),
                    other => Failure::Simulation(format!("{}: {other}", source.path().display())),
                })?;
                serde_json::to_string_pretty(&translation).map_err(|e| Failure::Simulation(e.to_string()))
            })
        })
    })();
    outcome.map_err(|failure| failure.into_pyerr(py))
}

/// `impact calibrate [SCENE] --law LAW --restitution E ... --json`: the calibration as JSON.
#[pyfunction]
#[pyo3(signature = (kind, scene, law, restitution, approach_speed, separation))]
fn calibrate(
    py: Python<'_>,
    kind: Option<&str>,
    scene: &Bound<'_, PyAny>,
    law: Option<String>,
    restitution: f64,
    approach_speed: Option<f64>,
    separation: Option<String>,
) -> PyResult<String> {
    use impact::calibrate::{Refusal, from_arguments};
    let outcome = (|| {
        let source = kind.map(|kind| Source::from_python(kind, scene)).transpose()?;
        py.detach(|| {
            guarded(|| {
                let scene = match &source {
                    Some(source) => {
                        let scene = impact::scene::Scene::parse(&source.text, &source.label)
                            .map_err(|error| source.failure(error))?;
                        Some((scene, source.path().display().to_string()))
                    }
                    None => None,
                };
                let calibration =
                    from_arguments(law.as_deref(), restitution, approach_speed, separation.as_deref(), scene).map_err(
                        |refusal| match refusal {
                            Refusal::BadInput(message) => Failure::Value(message),
                            Refusal::Failed(message) => Failure::Simulation(message),
                        },
                    )?;
                serde_json::to_string_pretty(&calibration).map_err(|e| Failure::Simulation(e.to_string()))
            })
        })
    })();
    outcome.map_err(|failure| failure.into_pyerr(py))
}

#[pymodule]
fn _impact(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", impact::VERSION)?;
    m.add_function(wrap_pyfunction!(run::run, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::sweep, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::merge, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::sweep_rows, m)?)?;
    m.add_function(wrap_pyfunction!(laws, m)?)?;
    m.add_function(wrap_pyfunction!(validate, m)?)?;
    m.add_function(wrap_pyfunction!(translate, m)?)?;
    m.add_function(wrap_pyfunction!(calibrate, m)?)?;
    m.add_class::<run::Run>()?;
    m.add_class::<sweep::SweepTable>()?;
    Ok(())
}
