//! `impact.run`: one scene (an impact or a world) simulated by the core's own functions, the result kept as the
//! core made it (the report, the history) and handed to Python as views: the JSON text `impact run --json` prints,
//! the readable table, the history's columns, the figures as SVG.

use crate::columns::{self, PyColumns, TextColumns};
use crate::errors::{Failure, guarded};
use crate::scene::Source;
use impact::history::Recording;
use impact::impact::{Simulation, SimulationError};
use impact::output;
use impact::output::world_figures::WorldTrace;
use impact::output::world_series::SeriesWriter;
use impact::scene::{Parsed, Scene, WorldScene};
use impact::world::WorldError;
use impact::world_run::WorldSimulation;
use pyo3::prelude::*;
use std::sync::Mutex;

/// Most instants `samples` may ask for (the command's `--samples` limit).
pub const MAX_SAMPLES: i64 = 1_000_000;

/// What ran.
enum Ran {
    Impact { scene: Box<Scene>, simulation: Box<Simulation> },
    World { scene: Box<WorldScene>, simulation: Box<WorldSimulation>, series: Option<String> },
}

/// A finished run (`impact.Report` wraps it).
#[pyclass(frozen, module = "impact._impact")]
pub struct Run {
    ran: Ran,
    /// Where the scene came from (to locate a rule a figures' rerun finds broken).
    source: Source,
    json: String,
    /// The figures' SVG texts by name, drawn when first asked for.
    figures: Mutex<Option<Vec<(String, String)>>>,
}

/// Simulates the scene; `history` records the contact history (the integrator's steps, or `samples` instants).
#[pyfunction]
#[pyo3(signature = (kind, scene, history = false, samples = None))]
pub fn run(py: Python<'_>, kind: &str, scene: &Bound<'_, PyAny>, history: bool, samples: Option<i64>) -> PyResult<Run> {
    let outcome = (|| {
        let samples = match samples {
            Some(n) if n < 2 => return Err(Failure::Value(format!("samples={n}: needs at least 2 instants"))),
            Some(n) if n > MAX_SAMPLES => {
                return Err(Failure::Value(format!("samples={n}: at most {MAX_SAMPLES} instants")));
            }
            Some(n) => Some(n as usize),
            None => None,
        };
        let source = Source::from_python(kind, scene)?;
        py.detach(move || guarded(|| simulate(source, history, samples)))
    })();
    outcome.map_err(|failure| failure.into_pyerr(py))
}

fn simulate(source: Source, history: bool, samples: Option<usize>) -> Result<Run, Failure> {
    let ran = match source.parse()? {
        Parsed::Impact(scene) => {
            let recording = match (samples, history) {
                (Some(n), _) => Recording::Uniform(n),
                (None, true) => Recording::Steps,
                (None, false) => Recording::Off,
            };
            let simulation = impact::impact::simulate(&scene, recording).map_err(|e| impact_failure(&source, e))?;
            Ran::Impact { scene, simulation: Box::new(simulation) }
        }
        Parsed::World(scene) => {
            if samples.is_some() {
                return Err(Failure::Value(
                    "samples resamples one impact's contact; a world run's history has every step of its islands \
                     and instants of each flight: give history=True"
                        .into(),
                ));
            }
            let (simulation, series) = if history {
                let mut writer = SeriesWriter::in_memory();
                let simulation = impact::world_run::simulate_observed(&scene, &mut writer);
                (simulation, Some(writer.text().to_string()))
            } else {
                (impact::world_run::simulate(&scene), None)
            };
            let simulation = simulation.map_err(|e| world_failure(&source, e))?;
            Ran::World { scene, simulation: Box::new(simulation), series }
        }
    };
    let json = match &ran {
        Ran::Impact { simulation, .. } => output::json::render(&simulation.report),
        Ran::World { simulation, .. } => output::json::render_world(&simulation.report),
    }
    .map_err(|error| Failure::Simulation(format!("cannot write the report as JSON: {error}")))?;
    Ok(Run { ran, source, json, figures: Mutex::new(None) })
}

pub fn impact_failure(source: &Source, error: SimulationError) -> Failure {
    match error {
        SimulationError::Setup(error) => source.located(error),
        other => Failure::Simulation(other.to_string()),
    }
}

pub fn world_failure(source: &Source, error: WorldError) -> Failure {
    match error {
        WorldError::Setup(error) => source.located(error),
        other => Failure::Simulation(other.to_string()),
    }
}

#[pymethods]
impl Run {
    /// The JSON report, as `impact run --json` prints it.
    fn json(&self) -> &str {
        &self.json
    }

    /// The readable report, as `impact run` prints it.
    fn table(&self, py: Python<'_>) -> String {
        py.detach(|| match &self.ran {
            Ran::Impact { simulation, .. } => output::table::render(&simulation.report),
            Ran::World { simulation, .. } => output::world_table::render(&simulation.report),
        })
    }

    /// Whether this is a world run.
    fn is_world(&self) -> bool {
        matches!(self.ran, Ran::World { .. })
    }

    /// The history's columns by name, in the CSV's order (`impact run --csv`'s, or a world's series), or None when no
    /// history was recorded.
    fn history<'py>(&self, py: Python<'py>) -> PyResult<Option<PyColumns<'py>>> {
        let text = match &self.ran {
            Ran::Impact { simulation, .. } => simulation.history.as_ref().map(output::csv::render),
            Ran::World { series, .. } => series.clone(),
        };
        let Some(text) = text else { return Ok(None) };
        let parsed: TextColumns = py.detach(|| columns::parse_csv(&text));
        columns::to_python(py, parsed).map(Some)
    }

    /// The figures of the run as SVG texts, by name (`impact run --plot`'s figures), in the order it draws them.
    fn figures(&self, py: Python<'_>) -> PyResult<Vec<(String, String)>> {
        if let Some(drawn) = self.figures.lock().unwrap_or_else(|e| e.into_inner()).as_ref() {
            return Ok(drawn.clone());
        }
        let drawn = py.detach(|| guarded(|| self.draw())).map_err(|failure| failure.into_pyerr(py))?;
        *self.figures.lock().unwrap_or_else(|e| e.into_inner()) = Some(drawn.clone());
        Ok(drawn)
    }
}

impl Run {
    fn draw(&self) -> Result<Vec<(String, String)>, Failure> {
        match &self.ran {
            Ran::Impact { scene, simulation } => {
                let history = impact::impact::figure_history(scene, simulation)
                    .map_err(|e| impact_failure(&self.source, e))?
                    .ok_or_else(|| Failure::Simulation("no history was recorded for the figures".into()))?;
                Ok(output::figures::FIGURES
                    .iter()
                    .map(|name| (name.to_string(), output::figures::svg(name, &simulation.report, &history)))
                    .collect())
            }
            Ran::World { scene, simulation, .. } => {
                // (The figures need the run's instants: the world is run again, watched.)
                let mut trace = WorldTrace::new();
                impact::world_run::simulate_observed(scene, &mut trace).map_err(|e| world_failure(&self.source, e))?;
                Ok(output::world_figures::names(&simulation.report)
                    .into_iter()
                    .map(|name| (name.to_string(), output::world_figures::svg(name, &simulation.report, &trace)))
                    .collect())
            }
        }
    }
}
