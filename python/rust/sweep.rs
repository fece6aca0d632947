//! `impact.sweep`: the core's [`Sweep`] run into its in-memory table (`impact::sweep::columns::Table`, beside the
//! command's CSV writer), with the GIL released while rows are computed and the calling thread watching for Ctrl-C
//! and reporting progress; the shards of an executor joined by the core's `merge`, as `impact merge` joins them.

use crate::columns::text_array;
use crate::errors::{Failure, guarded};
use crate::scene::Source;
use impact::files::{Destination, Identity, OutputFile};
use impact::sweep::columns::{Data, Table};
use impact::sweep::merge::{ShardFile, merge as merge_shards};
use impact::sweep::shard::Shard;
use impact::sweep::world::WorldSweep;
use impact::sweep::{MAX_THREADS, Sweep, SweepError};
use numpy::PyArray1;
use numpy::ndarray::ArrayView1;
use pyo3::prelude::*;
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::{Duration, Instant};

/// How often the calling thread looks for Ctrl-C and reports progress while the core computes.
const POLL: Duration = Duration::from_millis(50);

/// Rows of the CSV formatted between two looks for Ctrl-C in [`SweepTable::write_csv`].
const CSV_ROWS: usize = 1 << 16;

/// A sweep's table (`impact.Sweep` wraps it): its numbers are lent to numpy without a copy.
#[pyclass(frozen, module = "impact._impact")]
pub struct SweepTable {
    table: Table,
    /// The CSV as the core wrote it, for a world sweep (whose text cells the table does not re-quote).
    raw: Option<String>,
    /// Each text column's numpy array of `str`, made when first asked for.
    texts: Mutex<Vec<Option<Py<PyAny>>>>,
}

impl SweepTable {
    fn new(table: Table, raw: Option<String>) -> SweepTable {
        let texts = Mutex::new((0..table.columns.len()).map(|_| None).collect());
        SweepTable { table, raw, texts }
    }
}

fn sweep_failure(source: &Source, error: SweepError) -> Failure {
    match error {
        SweepError::Usage(message) => Failure::Value(message),
        SweepError::Scene(error) => source.failure(error),
    }
}

/// Runs a sweep: `vary` the command's `--vary` specs, `laws` and `columns` its `--law` and `--columns` (empty: the
/// defaults), `shard` its `--shard I/N`. `progress(done, total)` is called from the calling thread as rows finish.
#[pyfunction]
#[pyo3(signature = (kind, scene, vary, log = false, laws = Vec::new(), columns = Vec::new(), threads = None, shard = None, progress = None))]
#[allow(clippy::too_many_arguments)]
pub fn sweep(
    py: Python<'_>,
    kind: &str,
    scene: &Bound<'_, PyAny>,
    vary: Vec<String>,
    log: bool,
    laws: Vec<String>,
    columns: Vec<String>,
    threads: Option<i64>,
    shard: Option<String>,
    progress: Option<Py<PyAny>>,
) -> PyResult<SweepTable> {
    let outcome = (|| {
        let shard = shard.as_deref().map(Shard::parse).transpose().map_err(|e| Failure::Value(e.to_string()))?;
        let threads = match threads {
            Some(n) if !(1..=MAX_THREADS as i64).contains(&n) => {
                return Err(Failure::Value(format!("threads must be between 1 and {MAX_THREADS}, got {n}")));
            }
            n => n.map(|n| n as usize),
        };
        let source = Source::from_python(kind, scene)?;
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads.unwrap_or(0))
            .build()
            .map_err(|error| Failure::Simulation(format!("cannot start the worker threads: {error}")))?;
        if impact::scene::is_world(&source.text) {
            return world_sweep(py, &source, &vary, log, &laws, &columns, shard, &pool, progress.as_ref());
        }
        let sweep = guarded(|| {
            Sweep::from_arguments(&source.label, source.text.clone(), &vary, log, &laws, &columns)
                .map_err(|error| sweep_failure(&source, error))
        })?;
        let total = sweep.rows();
        let indices = sweep.indices(shard);
        let count = indices.len();
        let mut table = Table::new(&sweep.keys(), sweep.columns(), shard.map(|s| (s, total, sweep.fingerprint())));
        table.reserve(count);
        watched(py, progress.as_ref(), count, |stop, done| {
            let _ = sweep.stream_until(
                indices,
                &pool,
                stop,
                |rows| {
                    done.fetch_add(rows, Ordering::Relaxed);
                },
                |row| row,
                |row| {
                    table.push(&row);
                    Ok::<(), std::convert::Infallible>(())
                },
            );
            Ok(())
        })?;
        Ok(SweepTable::new(table, None))
    })();
    outcome.map_err(|failure| failure.into_pyerr(py))
}

/// Runs `work` (the core's loop, given the stop flag it checks and the count of rows done it adds to) on a thread
/// of its own with the GIL released, while this thread looks for Ctrl-C and reports progress every [`POLL`]; Ctrl-C
/// sets the flag, waits for the loop to stop and raises KeyboardInterrupt.
fn watched<F>(py: Python<'_>, progress: Option<&Py<PyAny>>, count: usize, work: F) -> Result<(), Failure>
where
    F: FnOnce(&AtomicBool, &AtomicUsize) -> Result<(), Failure> + Send,
{
    let stop = AtomicBool::new(false);
    let done = AtomicUsize::new(0);
    let mut interrupted: Option<PyErr> = None;
    let computed = py.detach(|| {
        std::thread::scope(|scope| {
            let worker = scope.spawn(|| guarded(|| work(&stop, &done)));
            let mut last = Instant::now();
            while !worker.is_finished() {
                std::thread::sleep(Duration::from_millis(5));
                if last.elapsed() < POLL {
                    continue;
                }
                last = Instant::now();
                if let Err(error) = Python::attach(|py| watch(py, progress, &done, count)) {
                    stop.store(true, Ordering::Relaxed);
                    interrupted = Some(error);
                    break;
                }
            }
            worker.join().unwrap_or_else(|_| Err(Failure::Simulation("the sweep's thread failed".into())))
        })
    });
    if let Some(error) = interrupted {
        return Err(Failure::Interrupted(error));
    }
    computed?;
    watch(py, progress, &done, count)?;
    Ok(())
}

/// A sweep of a world scene (`impact sweep` of a world: docs/world.md#sweeps): no `--law` or `--shard`, as the
/// command; its rows are the core's CSV lines, kept as written (they are the file) and read into the table.
#[allow(clippy::too_many_arguments)]
fn world_sweep(
    py: Python<'_>,
    source: &Source,
    vary: &[String],
    log: bool,
    laws: &[String],
    columns: &[String],
    shard: Option<Shard>,
    pool: &rayon::ThreadPool,
    progress: Option<&Py<PyAny>>,
) -> Result<SweepTable, Failure> {
    for (given, option) in [(!laws.is_empty(), "laws"), (shard.is_some(), "shard")] {
        if given {
            return Err(Failure::Value(format!("{option} is not taken by a sweep of a world scene (yet)")));
        }
    }
    let sweep = WorldSweep::from_arguments(&source.label, &source.text, vary, log, columns)
        .map_err(|error| sweep_failure(source, error))?;
    let count = sweep.rows();
    let mut lines: Vec<String> = Vec::with_capacity(count);
    watched(py, progress, count, |stop, done| {
        let _ = sweep.stream_until(
            (0..count).collect(),
            pool,
            stop,
            |rows| {
                done.fetch_add(rows, Ordering::Relaxed);
            },
            |row| {
                lines.push(row.line);
                Ok(())
            },
        );
        Ok(())
    })?;
    let header = sweep.header();
    let table = Table::from_lines(&header, &lines);
    let mut text = header + "\n";
    for line in &lines {
        text.push_str(line);
    }
    Ok(SweepTable::new(table, Some(text)))
}

/// Looks for Ctrl-C (raising KeyboardInterrupt) and reports progress.
fn watch(py: Python<'_>, progress: Option<&Py<PyAny>>, done: &AtomicUsize, total: usize) -> PyResult<()> {
    py.check_signals()?;
    if let Some(progress) = progress {
        progress.call1(py, (done.load(Ordering::Relaxed), total))?;
    }
    Ok(())
}

/// The number of rows of the whole sweep, and whether the scene is a world, its arguments and scene checked as
/// [`sweep`] checks them (nothing runs): what an executor's shards are cut from.
#[pyfunction]
#[pyo3(signature = (kind, scene, vary, log = false, laws = Vec::new(), columns = Vec::new()))]
pub fn sweep_rows(
    py: Python<'_>,
    kind: &str,
    scene: &Bound<'_, PyAny>,
    vary: Vec<String>,
    log: bool,
    laws: Vec<String>,
    columns: Vec<String>,
) -> PyResult<(usize, bool)> {
    let outcome = (|| {
        let source = Source::from_python(kind, scene)?;
        if impact::scene::is_world(&source.text) {
            return WorldSweep::from_arguments(&source.label, &source.text, &vary, log, &columns)
                .map(|sweep| (sweep.rows(), true))
                .map_err(|error| sweep_failure(&source, error));
        }
        guarded(|| {
            Sweep::from_arguments(&source.label, source.text.clone(), &vary, log, &laws, &columns)
                .map(|sweep| (sweep.rows(), false))
                .map_err(|error| sweep_failure(&source, error))
        })
    })();
    outcome.map_err(|failure| failure.into_pyerr(py))
}

/// Joins the CSV texts of a sweep's shards (`names` for messages) as `impact merge` does.
#[pyfunction]
pub fn merge(py: Python<'_>, texts: Vec<String>, names: Vec<String>) -> PyResult<SweepTable> {
    let outcome = py.detach(|| {
        guarded(|| {
            let shards: Vec<ShardFile> =
                texts.into_iter().zip(names).map(|(text, name)| ShardFile { name, text }).collect();
            let merged = merge_shards(&shards).map_err(|e| Failure::Value(e.to_string()))?;
            Table::from_merged(&merged).map_err(|e| Failure::Value(e.to_string()))
        })
    });
    outcome.map(|table| SweepTable::new(table, None)).map_err(|failure| failure.into_pyerr(py))
}

#[pymethods]
impl SweepTable {
    fn __len__(&self) -> usize {
        self.table.rows()
    }

    /// The column names, in the CSV's order.
    fn names(&self) -> Vec<String> {
        self.table.columns.iter().map(|c| c.name.clone()).collect()
    }

    /// Column `k` as a numpy array: float64 (NaN where the CSV cell is empty), lent from this table without a copy
    /// and read-only; or `str` objects.
    fn column<'py>(slf: Bound<'py, Self>, k: usize) -> PyResult<Bound<'py, PyAny>> {
        let py = slf.py();
        let this = slf.get();
        let Some(column) = this.table.columns.get(k) else {
            return Err(pyo3::exceptions::PyIndexError::new_err(format!("no column {k}")));
        };
        match &column.data {
            Data::Numbers(values) => {
                let view = ArrayView1::from(values.as_slice());
                // SAFETY: the table is never changed after it is made (the class is frozen and has no method that
                // changes it), so the memory the view points into stays valid and in place while `slf`, the array's
                // base, is alive.
                let array = unsafe { PyArray1::borrow_from_array(&view, slf.clone().into_any()) };
                // (Read-only: the table it views also writes the CSV.)
                array.getattr("flags")?.setattr("writeable", false)?;
                Ok(array.into_any())
            }
            Data::Texts { codes, strings } => {
                let mut texts = this.texts.lock().unwrap_or_else(|e| e.into_inner());
                if let Some(made) = &texts[k] {
                    return Ok(made.bind(py).clone());
                }
                let made = text_array(py, codes, strings);
                texts[k] = Some(made.clone().unbind());
                Ok(made)
            }
        }
    }

    /// The whole CSV text, as `impact sweep --out` writes it (a shard's with its first line).
    fn csv(&self, py: Python<'_>) -> String {
        if let Some(raw) = &self.raw {
            return raw.clone();
        }
        py.detach(|| {
            let mut text = String::new();
            self.table.write_csv(0..self.table.rows(), &mut text);
            text
        })
    }

    /// Writes the CSV to `path` as `impact sweep --out` does: completely or not at all (a temporary file renamed
    /// into place), `-` for standard output. Ctrl-C stops it and leaves no file.
    /// `inputs`: the files the sweep read (its scene), which an output never replaces (links followed, as the
    /// command's `--out` checks them).
    fn write_csv(&self, py: Python<'_>, path: std::path::PathBuf, inputs: Vec<std::path::PathBuf>) -> PyResult<()> {
        let io = |error: impact::files::FileError| Failure::Io(error.to_string()).into_pyerr(py);
        if path.as_os_str().is_empty() {
            return Err(Failure::Value(
                "to_csv: the path is empty: give a file's name, or \"-\" for standard output".into(),
            )
            .into_pyerr(py));
        }
        let destination = Destination::resolve(&path).map_err(io)?;
        if let Some(input) = inputs.iter().find(|input| destination.identity().same_as(&Identity::of(input))) {
            return Err(Failure::Value(format!(
                "{} is {}, the sweep's scene: an output never replaces an input of the run",
                destination.shown(),
                input.display()
            ))
            .into_pyerr(py));
        }
        let mut output = OutputFile::create(&destination).map_err(io)?;
        let rows = self.table.rows();
        let mut start = 0;
        // (Row 0 brings the header: an empty table still writes it.)
        loop {
            let end = (start + CSV_ROWS).min(rows);
            let written = py.detach(|| match &self.raw {
                Some(raw) => output.write_bytes(raw.as_bytes()),
                None => {
                    let mut text = String::new();
                    self.table.write_csv(start..end, &mut text);
                    output.write_bytes(text.as_bytes())
                }
            });
            written.map_err(io)?;
            // Ctrl-C drops the unfinished output, which removes its temporary file.
            py.check_signals()?;
            start = end;
            if start >= rows || self.raw.is_some() {
                break;
            }
        }
        output.finish().map_err(io)
    }
}
