//! Sweeps of a world scene (docs/world.md#sweeps): each point sets its keys in the scene's TOML document, the edited
//! text is read as `impact run` would read it, the world runs, and the row writes the report's values that the
//! columns name — dotted paths into the world's JSON report (`bodies.2.velocity_after.0`,
//! `contacts.1.restitution_velocity_ratio`, `energy.balance`). A point that is not a valid scene, or whose run fails,
//! becomes a row saying why; a path that a row's report does not have (a contact that did not happen) is an empty
//! cell.

use super::SweepError;
use super::table::number;
use crate::scene::{Parsed, WorldScene};
use crate::text::{MESSAGE_CHARS, cut};
use rayon::prelude::*;
use serde_json::Value as Json;
use std::path::{Path, PathBuf};
use toml::{Table, Value};

/// Rows computed together (a world row can take long: few at a time keeps the progress and the memory even).
const CHUNK: usize = 64;

/// The columns written without `--columns` (then every movable body's velocity after the run).
const DEFAULT_COLUMNS: [&str; 7] = [
    "world.contacts",
    "world.end_time",
    "world.end_reason",
    "energy.dissipated",
    "energy.balance",
    "sequential.nominal.max_velocity_difference",
    "sequential.simulated_e.max_velocity_difference",
];

/// The report's sections a column may start with.
const SECTIONS: [&str; 8] = ["world", "idealisation", "contacts", "bodies", "energy", "sequential", "solver", "title"];

/// A world scene's sweep: the scene document, the varied keys and their values, the columns.
#[derive(Debug, Clone)]
pub struct WorldSweep {
    path: PathBuf,
    document: Table,
    keys: Vec<String>,
    /// The values of each key (its `--vary`), in order.
    values: Vec<Vec<f64>>,
    columns: Vec<String>,
}

/// One row: its index, its status (`ok`; `step budget`, a run its budget stopped, its cells the report's where it
/// stopped; or `error: KEY: why`), its cells.
pub struct WorldRow {
    pub index: usize,
    pub ok: bool,
    /// The run spent its budget (`[world] max_steps`) before its end.
    pub stopped: bool,
    pub line: String,
}

/// The status of a row whose run its budget stopped.
pub const STOPPED: &str = "step budget";

impl WorldSweep {
    /// The sweep of the world scene `text` (read from `path`) over the grid of `axes` (each key's values; the
    /// first slowest), writing `columns` (empty: the defaults).
    pub fn new(
        path: &Path,
        text: &str,
        axes: Vec<(String, Vec<f64>)>,
        columns: &[String],
    ) -> Result<WorldSweep, SweepError> {
        let document: Table = text.parse().map_err(|error: toml::de::Error| {
            SweepError::Usage(format!("{}: not TOML: {}", path.display(), error.message().trim()))
        })?;
        let (keys, values): (Vec<String>, Vec<Vec<f64>>) = axes.into_iter().unzip();
        for (k, key) in keys.iter().enumerate() {
            check_key(&document, key)?;
            if keys[..k].contains(key) {
                return Err(SweepError::Usage(format!("--vary {key}: the key is varied twice")));
            }
        }
        let rows = values.iter().try_fold(1usize, |n, v| n.checked_mul(v.len()));
        if rows.is_none_or(|rows| rows > super::MAX_ROWS) {
            return Err(SweepError::Usage(format!(
                "the grid has more than {} points: split the sweep",
                super::MAX_ROWS
            )));
        }
        let columns = if columns.is_empty() {
            let mut columns: Vec<String> = DEFAULT_COLUMNS.iter().map(|c| c.to_string()).collect();
            let bodies = document.get("bodies").and_then(Value::as_array).map_or(&[][..], |b| b.as_slice());
            for (i, body) in bodies.iter().enumerate() {
                let immovable = body.get("mass").and_then(Value::as_float).is_some_and(f64::is_infinite);
                if !immovable {
                    columns.extend((0..3).map(|k| format!("bodies.{i}.velocity_after.{k}")));
                }
            }
            columns
        } else {
            for column in columns {
                let first = column.split('.').next().unwrap_or_default();
                if !SECTIONS.contains(&first) || column.split('.').any(str::is_empty) {
                    return Err(SweepError::Usage(format!(
                        "--columns: `{}` is not a path into a world's report; start it with one of {} (e.g. \
                         bodies.2.velocity_after.0, contacts.0.restitution_velocity_ratio; docs/report.md#world-runs)",
                        cut(column, MESSAGE_CHARS),
                        SECTIONS.join(", ")
                    )));
                }
            }
            columns.to_vec()
        };
        Ok(WorldSweep { path: path.to_path_buf(), document, keys, values, columns })
    }

    /// How many rows the sweep has.
    pub fn rows(&self) -> usize {
        self.values.iter().map(Vec::len).product()
    }

    /// The values of point `point` (lexicographic order: the first key slowest).
    fn point(&self, mut point: usize) -> Vec<f64> {
        let mut values = vec![0.0; self.values.len()];
        for (slot, axis) in values.iter_mut().zip(&self.values).rev() {
            *slot = axis[point % axis.len()];
            point /= axis.len();
        }
        values
    }

    /// The CSV header: `index,status`, the varied keys, the columns.
    pub fn header(&self) -> String {
        let mut names = vec!["index".to_string(), "status".to_string()];
        names.extend(self.keys.iter().cloned());
        names.extend(self.columns.iter().cloned());
        names.join(",")
    }

    /// Row `index`: the scene with the point's values, run.
    pub fn row(&self, index: usize) -> WorldRow {
        let values = self.point(index);
        let mut line = format!("{index},");
        let mut cells: Vec<String> = values.iter().map(|&v| number(v)).collect();
        let outcome = self.run(&values);
        let stopped = outcome.as_ref().is_ok_and(|report| {
            report["world"]["end_reason"].as_str() == Some(crate::world::record::EndReason::StepBudget.name())
        });
        let ok = outcome.is_ok() && !stopped;
        match outcome {
            Ok(report) => {
                line.push_str(if stopped { STOPPED } else { "ok" });
                cells.extend(self.columns.iter().map(|column| cell(&report, column)));
            }
            Err(why) => {
                line.push_str(&quoted(&format!("error: {why}")));
                cells.extend(self.columns.iter().map(|_| String::new()));
            }
        }
        for cell in cells {
            line.push(',');
            line.push_str(&cell);
        }
        line.push('\n');
        WorldRow { index, ok, stopped, line }
    }

    /// The report of the point `values` as JSON, or why there is none (`KEY: why`).
    fn run(&self, values: &[f64]) -> Result<Json, String> {
        let mut document = self.document.clone();
        for (key, &value) in self.keys.iter().zip(values) {
            set(&mut document, key, value).map_err(|why| format!("{key}: {why}"))?;
        }
        let text = toml::to_string(&document).map_err(|error| error.to_string())?;
        let scene: WorldScene = match crate::setup::parse_any(&text, &self.path) {
            Ok(Parsed::World(scene)) => *scene,
            Ok(Parsed::Impact(_)) => return Err("the point is no longer a world scene".into()),
            Err(error) => return Err(format!("{}: {}", error.key.as_deref().unwrap_or("scene"), error.message)),
        };
        let simulation = crate::world_run::simulate(&scene).map_err(|error| match error {
            crate::world::WorldError::Setup(error) => format!("{}: {}", error.key, error.message),
            other => other.to_string(),
        })?;
        serde_json::to_value(&simulation.report).map_err(|error| error.to_string())
    }

    /// The sweep `impact sweep` runs of a world scene (and Python's `impact.sweep`): each `--vary` spec read by
    /// [`super::grid::parse_world`] (geometric ranges by default under `log`), then [`WorldSweep::new`].
    pub fn from_arguments(
        path: &Path,
        text: &str,
        vary: &[String],
        log: bool,
        columns: &[String],
    ) -> Result<WorldSweep, SweepError> {
        let spacing = if log { super::grid::Spacing::Geometric } else { super::grid::Spacing::Linear };
        let axes = vary.iter().map(|spec| super::grid::parse_world(spec, spacing)).collect::<Result<Vec<_>, _>>()?;
        WorldSweep::new(path, text, axes, columns)
    }

    /// Computes `indices` on `pool` in chunks, handing each row to `take` in index order.
    pub fn stream(
        &self,
        indices: Vec<usize>,
        pool: &rayon::ThreadPool,
        done: impl FnMut(usize),
        take: impl FnMut(WorldRow) -> Result<(), crate::files::FileError>,
    ) -> Result<(), crate::files::FileError> {
        self.stream_until(indices, pool, &std::sync::atomic::AtomicBool::new(false), done, take)
    }

    /// [`WorldSweep::stream`] that stops soon after `stop` is set (Python's Ctrl-C): rows not yet started are
    /// skipped, the chunk being computed is dropped, and `take` has received a prefix of the rows.
    pub fn stream_until(
        &self,
        indices: Vec<usize>,
        pool: &rayon::ThreadPool,
        stop: &std::sync::atomic::AtomicBool,
        mut done: impl FnMut(usize),
        mut take: impl FnMut(WorldRow) -> Result<(), crate::files::FileError>,
    ) -> Result<(), crate::files::FileError> {
        use std::sync::atomic::Ordering;
        for chunk in indices.chunks(CHUNK) {
            let rows: Option<Vec<WorldRow>> = pool
                .install(|| chunk.par_iter().map(|&i| (!stop.load(Ordering::Relaxed)).then(|| self.row(i))).collect());
            let Some(rows) = rows.filter(|_| !stop.load(Ordering::Relaxed)) else { break };
            done(rows.len());
            for row in rows {
                take(row)?;
            }
        }
        Ok(())
    }
}

/// The cell of `column`, a dotted path into `report`: a number in shortest form, a string quoted where it must be,
/// nothing where the path leads nowhere (or to null).
fn cell(report: &Json, column: &str) -> String {
    let mut value = report;
    for part in column.split('.') {
        let next = match value {
            Json::Object(map) => map.get(part),
            Json::Array(items) => part.parse::<usize>().ok().and_then(|i| items.get(i)),
            _ => None,
        };
        let Some(next) = next else { return String::new() };
        value = next;
    }
    match value {
        Json::Number(n) => n.as_f64().map(number).unwrap_or_default(),
        Json::String(s) => quoted(s),
        Json::Bool(b) => b.to_string(),
        Json::Null => String::new(),
        other => quoted(&other.to_string()),
    }
}

/// A CSV field: quoted (its quotes doubled) when it holds a comma, a quote or a line break.
fn quoted(text: &str) -> String {
    if text.contains([',', '"', '\n']) { format!("\"{}\"", text.replace('"', "\"\"")) } else { text.to_string() }
}

/// The table or array a dotted path's part leads to.
fn step<'a>(value: &'a mut Value, part: &str) -> Option<&'a mut Value> {
    match value {
        Value::Table(table) => table.get_mut(part),
        Value::Array(items) => part.parse::<usize>().ok().and_then(move |i| items.get_mut(i)),
        _ => None,
    }
}

/// Checks before any work that `key` names a number of the scene (or a new key of an existing table): a usage
/// error otherwise.
fn check_key(document: &Table, key: &str) -> Result<(), SweepError> {
    let mut probe = document.clone();
    set(&mut probe, key, 1.0).map_err(|why| {
        SweepError::Usage(format!(
            "cannot vary `{}`: {why}; a world sweep varies a number of the scene by its dotted key (bodies.2.position.0, \
             bodies.1.mass, world.gravity.2, world.end_time, contact.restitution, pair.0.damping, solver.rtol)",
            cut(key, MESSAGE_CHARS)
        ))
    })
}

/// Sets the number at the dotted `key` of the scene document: an existing number, a component of an existing vector,
/// or a new number in an existing table (`contact.damping`). Giving a number its exclusive partner removes the
/// partner (`restitution` and `damping`, `mass` and `density`), as a two-body sweep does.
fn set(document: &mut Table, key: &str, value: f64) -> Result<(), String> {
    let parts: Vec<&str> = key.split('.').collect();
    let (last, path) = parts.split_last().ok_or("an empty key")?;
    let [table_name, rest @ ..] = path else {
        return Err("not a number of a table".into());
    };
    if !["bodies", "contact", "pair", "world", "solver"].contains(table_name) {
        return Err(format!("`{table_name}` is not a table a sweep sets"));
    }
    let mut at = document.get_mut(*table_name).ok_or_else(|| format!("the scene has no `{table_name}`"))?;
    for part in rest {
        at = step(at, part).ok_or_else(|| format!("the scene has no `{part}` there"))?;
    }
    match at {
        Value::Array(items) => {
            let index: usize = last.parse().map_err(|_| format!("`{last}` is not a component (0, 1 or 2)"))?;
            let slot = items.get_mut(index).ok_or_else(|| format!("the vector has no component {index}"))?;
            if !matches!(slot, Value::Float(_) | Value::Integer(_)) {
                return Err("not a number".into());
            }
            *slot = Value::Float(value);
            Ok(())
        }
        Value::Table(table) => {
            match table.get(*last) {
                Some(Value::Float(_) | Value::Integer(_)) | None => {}
                Some(Value::Array(_)) => return Err(format!("`{last}` is a vector: vary one component, `{key}.0`")),
                Some(_) => return Err(format!("`{last}` is not a number")),
            }
            let partner = match *last {
                "restitution" => Some("damping"),
                "damping" => Some("restitution"),
                "mass" => Some("density"),
                "density" => Some("mass"),
                _ => None,
            };
            if let Some(partner) = partner {
                table.remove(partner);
            }
            table.insert(last.to_string(), Value::Float(value));
            Ok(())
        }
        _ => Err("not a table or a vector".into()),
    }
}
