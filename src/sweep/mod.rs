//! Parameter sweeps: one scene run over a grid of values of some of its numbers, under one or several laws.
//!
//! A point is applied by editing the scene's TOML document — the law's defaults first ([`laws`]), then each
//! varied key ([`key`]) — and validating the edited text with [`Scene::parse`], exactly as `impact run` would read
//! a file holding it. A point that is not a valid scene, or that a law cannot take, becomes a row saying why; it
//! never stops the sweep. Rows come in a fixed order — points in lexicographic order of the grid (the first
//! `--vary` slowest), and for each point the laws in `--law` order — and row `i` of the whole sweep has global index
//! `i`, whatever part of the sweep ([`shard`]) or however many threads compute it. [`table`] writes the CSV,
//! [`merge`] joins shards, [`figure`] turns a sweep's CSV into the data of its figure.

pub mod columns;
pub mod figure;
pub mod grid;
pub mod key;
pub mod laws;
pub mod map;
pub mod merge;
pub mod shard;
pub mod table;
pub mod world;

use crate::history::Recording;
use crate::impact::{Options, simulate_prepared_into};
use crate::law::LawKind;
use crate::report::Report;
use crate::scene::SetupError;
use crate::scene::{RuleGroups, Scene, SceneError};
use crate::setup::{Approach, Setup};
use crate::text::{MESSAGE_CHARS, cut};
use grid::Grid;
use rayon::prelude::*;
use shard::Shard;
use std::borrow::Cow;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use table::{Cell, Columns, Row, Status};

/// Why a sweep cannot start (bad arguments, a scene file that is not TOML) or shards cannot be merged.
#[derive(Debug, thiserror::Error)]
pub enum SweepError {
    /// A bad `--vary`, `--law`, `--shard`... or shard files that do not make up one sweep.
    #[error("{0}")]
    Usage(String),
    /// The scene file cannot be read or is not TOML.
    #[error(transparent)]
    Scene(#[from] SceneError),
}

/// Largest number of rows a sweep accepts, and of shards it may be split into (`impact merge` accepts the same). Rows
/// stream to the file as they are computed, so memory does not limit a sweep; this bounds what a file's header may
/// claim and keeps a sweep's file (about 0.5 kB a row) and its merge within one machine's disk and memory.
pub const MAX_ROWS: usize = 100_000_000;

/// Most worker threads a sweep takes (`--threads`, Python's `threads`): more only add start-up cost (a machine of
/// this project's kind has 2 cores).
pub const MAX_THREADS: usize = 256;

/// Rows computed together by [`Sweep::stream`]: enough to keep every core busy past the slowest row of a chunk and
/// to make the pause between chunks rare (a million rows took 4 % longer in chunks of 1024 on this project's 2-core
/// machine), few enough that a chunk's rows (about 1 kB each at most) stay a small, fixed amount of memory
/// whatever the sweep's size.
pub const CHUNK: usize = 4096;

/// A sweep: the scene document, the grid, the laws.
#[derive(Debug, Clone)]
pub struct Sweep {
    /// The scene file (names errors, gives the default title).
    path: PathBuf,
    /// The scene text as read (fingerprinted for shards).
    text: String,
    /// The scene document every point starts from.
    document: toml::Table,
    pub grid: Grid,
    /// The laws, in `--law` order; empty to run the scene's own law.
    pub laws: Vec<LawKind>,
    /// For each law, the typed scene its points are applied to (see [`Sweep::base`]).
    bases: Vec<Option<Base>>,
    /// The result columns written (all unless [`Sweep::select`] chose some).
    columns: Columns,
    /// The scene's own law as its file writes it (the `law` column without `--law`).
    written_law: Cow<'static, str>,
    /// What a row's run computes: what [`Sweep::columns`] show (found once, not a row at a time).
    options: Options,
    /// Each law's `law` cell as CSV writes it (found once, not a row at a time).
    quoted_laws: Vec<table::Quoted>,
}

/// A law's typed scene, which its rows copy and set their point on, and the groups of value rules its points pass
/// without checking.
#[derive(Debug, Clone)]
struct Base {
    scene: Scene,
    known: RuleGroups,
    /// The tables the varied keys set (as groups of rules: a body, the contact, the solver).
    reached: RuleGroups,
    /// The approach every point shares, where no varied key can change it (none sets a body or the contact's
    /// normal) and the base has one: each point's setup then derives only what the law's numbers decide.
    approach: Option<Approach>,
}

impl Base {
    /// `copy` made this base's scene as a point starts from: a first copy whole; after a point, only the tables the
    /// keys reach copied back. (The other tables are the base's, re-derived by [`Scene::resolve`], which gives the
    /// same values however often it runs: it derives only from written values.)
    fn restored<'a>(&self, copy: &'a mut Option<Scene>) -> &'a mut Scene {
        match copy {
            Some(scene) => {
                for i in 0..2 {
                    if self.reached.bodies[i] {
                        scene.bodies[i].clone_from(&self.scene.bodies[i]);
                    }
                }
                if self.reached.contact {
                    scene.contact.clone_from(&self.scene.contact);
                }
                if self.reached.solver {
                    scene.solver = self.scene.solver;
                }
                scene
            }
            None => copy.insert(self.scene.clone()),
        }
    }
}

/// What a worker keeps from row to row ([`Sweep::evaluate_in`]): its copies of the sweep's base scenes, one a law,
/// made at its first row, and the report each row is written into.
#[derive(Debug, Clone, Default)]
pub struct Scratch {
    scenes: Vec<Option<Scene>>,
    report: Report,
    /// The row's varied values and its result cells, refilled for each row.
    values: Vec<f64>,
    cells: Vec<Cell>,
    /// The longest CSV line this worker has written (bytes, with its newline): the room a block's text is given a
    /// row ([`Sweep::stream_lines`]).
    widest: usize,
}

/// Rows a worker runs in one go within a chunk ([`Sweep::stream`]): their lines go into one text
/// ([`Sweep::stream_lines`]), handed to the writer at once. Enough that a block's text and hand-over cost little
/// beside its rows, few enough that a chunk's blocks keep both cores busy to its end.
pub const BLOCK: usize = 64;

/// The CSV lines of consecutive rows as one text ([`table::push_line`] of each), and how the rows ended.
#[derive(Debug, Clone, PartialEq)]
pub struct Lines {
    pub text: String,
    /// How many rows, and how many of them ended `ok` and `not separated`.
    pub rows: usize,
    pub ok: usize,
    pub stuck: usize,
    /// The first row's status (`None` without rows).
    pub first: Option<Status>,
}

/// The laws named in `--law` (scene spellings), checked.
pub fn parse_laws(names: &[String]) -> Result<Vec<LawKind>, SweepError> {
    let mut laws = Vec::new();
    for name in names {
        let Some(law) = LawKind::from_name(name.trim()) else {
            return Err(SweepError::Usage(format!(
                "--law: unknown law `{}`; expected one of {}",
                cut(name.trim(), MESSAGE_CHARS),
                LawKind::names().join(", ")
            )));
        };
        if laws.contains(&law) {
            return Err(SweepError::Usage(format!("--law: `{}` is given twice", law.name())));
        }
        laws.push(law);
    }
    Ok(laws)
}

impl Sweep {
    /// The sweep `impact sweep` runs (and Python's `impact.sweep`): the scene `text` read from `path`, each `--vary`
    /// spec (`KEY=START:STOP:COUNT[:log|:lin]` or `KEY=V1,V2,...`; geometric ranges by default under `log`), the
    /// `--law` names and the `--columns` names (empty: the defaults), checked in the command's order.
    pub fn from_arguments(
        path: &Path,
        text: String,
        vary: &[String],
        log: bool,
        laws: &[String],
        columns: &[String],
    ) -> Result<Sweep, SweepError> {
        let spacing = if log { grid::Spacing::Geometric } else { grid::Spacing::Linear };
        let laws = parse_laws(laws)?;
        let axes = vary.iter().map(|spec| grid::Axis::parse(spec, spacing)).collect::<Result<Vec<_>, _>>()?;
        let grid = Grid::new(axes)?;
        let mut sweep = Sweep::new(path, text, grid, laws)?;
        if !columns.is_empty() {
            sweep.select(Columns::parse(columns)?);
        }
        Ok(sweep)
    }

    /// Checks a sweep before any work: the scene text is TOML, the varied keys fit this scene, the size is sane.
    /// The scene's values are checked per point (a file may leave out what the sweep sets).
    pub fn new(path: &Path, text: String, grid: Grid, laws: Vec<LawKind>) -> Result<Sweep, SweepError> {
        let document: toml::Table = match text.parse() {
            Ok(document) => document,
            // The scene reader locates the syntax error (file, line, key).
            Err(error) => {
                return Err(match Scene::parse(&text, path) {
                    Err(located) => located.into(),
                    Ok(_) => SceneError::file(path, format!("not a TOML document: {error}")).into(),
                });
            }
        };
        if grid.axes.is_empty() {
            return Err(SweepError::Usage("give at least one --vary KEY=START:STOP:COUNT".into()));
        }
        // A scene whose form is wrong (unknown keys, wrong types, missing tables) fails at every point: it is a bad
        // scene (exit 2), not a sweep of error rows. Bad values are left to the points, which may set them.
        if let Err(error) = Scene::parse(&text, path)
            && error.form
        {
            return Err(error.into());
        }
        for axis in &grid.axes {
            axis.key.check_in(&document)?;
        }
        let mut sweep = Sweep {
            path: path.to_path_buf(),
            text,
            written_law: Sweep::written_law(&document),
            document,
            grid,
            laws,
            bases: Vec::new(),
            columns: Columns::default(),
            options: Sweep::row_options(&Columns::default()),
            quoted_laws: Vec::new(),
        };
        sweep.bases = (0..sweep.law_count()).map(|i| sweep.base(i)).collect();
        sweep.quoted_laws =
            (0..sweep.law_count()).map(|i| table::Quoted::new(&sweep.law_name(sweep.laws.get(i).copied()))).collect();
        match sweep.grid.points().and_then(|points| points.checked_mul(sweep.law_count())) {
            Some(rows) if rows <= MAX_ROWS => Ok(sweep),
            _ => Err(SweepError::Usage(format!("the sweep has more than {MAX_ROWS} rows: split it into several"))),
        }
    }

    /// Writes only `columns` (`--columns`); each row then computes only what they show.
    pub fn select(&mut self, columns: Columns) {
        self.options = Sweep::row_options(&columns);
        self.columns = columns;
    }

    /// What a row's run computes for `columns`: no history; of the exact reference at most the restitution (the
    /// quadratures of the others are not computed); the verdicts on the idealisation only if a column shows one
    /// (their trial costs two more runs of the contact); nothing the columns do not show.
    fn row_options(columns: &Columns) -> Options {
        Options {
            recording: Recording::Off,
            reference: columns.reference(),
            quantities: columns.quantities(),
            idealisation: columns.verdicts(),
            sections: columns.sections(),
        }
    }

    /// The result columns written.
    pub fn columns(&self) -> &Columns {
        &self.columns
    }

    fn law_count(&self) -> usize {
        self.laws.len().max(1)
    }

    /// Number of rows of the whole sweep: points times laws.
    pub fn rows(&self) -> usize {
        self.grid.points().unwrap_or(0) * self.law_count()
    }

    /// The varied keys, as written in the CSV header.
    pub fn keys(&self) -> Vec<String> {
        self.grid.axes.iter().map(|axis| axis.key.to_string()).collect()
    }

    /// The varied values and the law (`None`: the scene's own) of row `index`.
    pub fn point(&self, index: usize) -> (Vec<f64>, Option<LawKind>) {
        let laws = self.law_count();
        (self.grid.values(index / laws), self.laws.get(index % laws).copied())
    }

    /// The scene text of row `index`: the document with the law's defaults and the point's values applied.
    /// `Err` says why this law cannot take the point.
    pub fn scene_text(&self, index: usize) -> Result<String, String> {
        let (values, law) = self.point(index);
        let mut document = self.document.clone();
        if let Some(law) = law {
            let keys: Vec<_> = self.grid.axes.iter().map(|axis| axis.key.clone()).collect();
            laws::apply(&mut document, law, &keys)?;
        }
        for (axis, value) in self.grid.axes.iter().zip(values) {
            axis.key.set(&mut document, value).map_err(|why| format!("{}: {why}", axis.key))?;
        }
        toml::to_string(&document).map_err(|error| format!("cannot write the scene: {error}"))
    }

    /// The law's name for row `index`: from `--law`, or as the scene file writes it.
    fn law_name(&self, law: Option<LawKind>) -> Cow<'static, str> {
        match law {
            Some(law) => Cow::Borrowed(law.name()),
            None => self.written_law.clone(),
        }
    }

    /// The law as the document writes it: the catalogue's own spelling where it is one (so that a row borrows it
    /// rather than copying it), else the text itself.
    fn written_law(document: &toml::Table) -> Cow<'static, str> {
        let written = document.get("contact").and_then(|c| c.get("law")).and_then(|l| l.as_str()).unwrap_or_default();
        match LawKind::from_name(written).map(LawKind::name) {
            Some(name) if name == written => Cow::Borrowed(name),
            _ => Cow::Owned(written.into()),
        }
    }

    /// Runs row `index`: validates its scene and simulates it.
    pub fn evaluate(&self, index: usize) -> Row {
        self.evaluate_in(index, &mut Scratch::default())
    }

    /// [`Sweep::evaluate`] on a worker's copies of the scene (`scratch`, kept from row to row): the same row, for a
    /// copy of only the tables the varied keys reach.
    pub fn evaluate_in(&self, index: usize, scratch: &mut Scratch) -> Row {
        let status = self.evaluate_by(index, true, scratch);
        self.row(index, status, scratch)
    }

    /// Row `index` through the document: the point written into the scene's TOML and read back like a file. This
    /// is what a point means; [`Sweep::evaluate`] applies it to a typed scene instead, and must give the same row
    /// (the tests hold it to that).
    pub fn evaluate_written(&self, index: usize) -> Row {
        let mut scratch = Scratch::default();
        let status = self.evaluate_by(index, false, &mut scratch);
        self.row(index, status, &scratch)
    }

    /// The CSV line of row `index`, [`table::line`] of [`Sweep::evaluate_in`], appended to `text` straight from the
    /// worker's `scratch` (no row formed); returns the row's status.
    pub fn line_in(&self, index: usize, scratch: &mut Scratch, text: &mut String) -> Status {
        let status = self.evaluate_by(index, true, scratch);
        let law = &self.quoted_laws[index % self.law_count()];
        table::push_line(text, index, &status, law, &scratch.values, &scratch.cells);
        status
    }

    /// The row `index` that ended with `status`, its values and cells those in `scratch`.
    fn row(&self, index: usize, status: Status, scratch: &Scratch) -> Row {
        let law = self.law_name(self.laws.get(index % self.law_count()).copied());
        Row { index, status, law, values: scratch.values.clone(), results: scratch.cells.clone() }
    }

    /// Row `index` on the typed scene (`typed`, on the worker's copy in `scratch`) or through the document: its
    /// values and cells into `scratch`'s (the report too); returns its status.
    fn evaluate_by(&self, index: usize, typed: bool, scratch: &mut Scratch) -> Status {
        let law_index = index % self.law_count();
        let (columns, options) = (&self.columns, self.options);
        let Scratch { scenes, report, values, cells, .. } = scratch;
        self.grid.values_into(index / self.law_count(), values);
        // The cells are taken from the report where it was built, the worker's, and the scene and its setup stay
        // where they were made (a report is 2.9 kB, a scene 1.1: moving them out through results cost more than the
        // cells).
        let mut cells_of = |scene: &Scene, setup: &Setup| {
            // (No column shows the run's wall time: not measured.)
            simulate_prepared_into(scene, setup, options, report).map_err(|error| error.to_string())?;
            columns.pick_into(report, cells);
            Ok(if report.contact.separated { Status::Ok } else { Status::NotSeparated })
        };
        let status = match &self.bases[law_index] {
            Some(base) if typed => {
                if scenes.len() < self.bases.len() {
                    scenes.resize(self.bases.len(), None);
                }
                let scene = base.restored(&mut scenes[law_index]);
                self.apply_point(scene, base, values).and_then(|setup| cells_of(scene, &setup))
            }
            _ => self.scene_text(index).and_then(|text| {
                let scene = Scene::parse(&text, &self.path).map_err(scene_message)?;
                let setup = Setup::new(&scene).map_err(setup_message)?;
                cells_of(&scene, &setup)
            }),
        };
        status.unwrap_or_else(|why| {
            cells.clear();
            cells.resize(columns.len(), Cell::Empty);
            Status::Error(why)
        })
    }

    /// The typed scene a law's rows start from: the document with the law's defaults, converted once; `None` when it
    /// does not convert (the file leaves out something the points set, say), and the rows take the document path.
    fn base(&self, law: usize) -> Option<Base> {
        let mut document = self.document.clone();
        if let Some(&law) = self.laws.get(law) {
            let keys: Vec<_> = self.grid.axes.iter().map(|axis| axis.key.clone()).collect();
            laws::apply(&mut document, law, &keys).ok()?;
        }
        let text = toml::to_string(&document).ok()?;
        let mut scene = Scene::convert(&text, &self.path).ok()?;
        // The text no row reads (a row's report has no names: `Columns::sections`; no rule reads them), so that
        // copying the scene for a row allocates nothing.
        scene.title = String::new();
        for body in &mut scene.bodies {
            body.name = String::new();
        }
        scene.output = Default::default();
        // The groups of value rules every point passes without checking: those the base passes, less those the
        // varied keys reach.
        let mut resolved = scene.clone();
        resolved.resolve();
        let passed = RuleGroups::passed_by(&resolved);
        let mut reached = RuleGroups::NONE;
        for axis in &self.grid.axes {
            let key = axis.key.reaches();
            for i in 0..2 {
                reached.bodies[i] |= key.bodies[i];
            }
            reached.contact |= key.contact;
            reached.solver |= key.solver;
        }
        // (Where every key that reaches the contact sets its damping alone, a point checks only the damping's rules
        // of the contact's: the others read what the base has.)
        let damping_only = self.grid.axes.iter().all(|axis| !axis.key.reaches().contact || axis.key.sets_damping());
        let known = RuleGroups {
            bodies: [0, 1].map(|i| passed.bodies[i] && !reached.bodies[i]),
            contact: passed.contact && !reached.contact,
            solver: passed.solver && !reached.solver,
            contact_but_damping: passed.contact && damping_only,
        };
        let shared = !self.grid.axes.iter().any(|axis| axis.key.moves_approach());
        let approach = if shared { Approach::new(&resolved).ok() } else { None };
        Some(Base { scene, known, reached, approach })
    }

    /// A point applied to (a copy of) a law's typed scene and checked by the rules a scene file obeys: the same scene,
    /// and the same error text, as writing the point into the document and reading it back (the groups of rules the
    /// base knows pass unchecked: the base passes them and the point does not reach them; its approach, where every
    /// point shares it, is not found again). Returns its setup.
    fn apply_point(&self, scene: &mut Scene, base: &Base, values: &[f64]) -> Result<Setup, String> {
        for (axis, &value) in self.grid.axes.iter().zip(values) {
            axis.key.apply(scene, value).map_err(|why| format!("{}: {why}", axis.key))?;
        }
        scene.resolve();
        scene.check_except(base.known, base.approach.as_ref()).map_err(setup_message)
    }

    /// The global indices of the rows of `shard` (all rows without one), in increasing order.
    pub fn indices(&self, shard: Option<Shard>) -> std::iter::StepBy<std::ops::Range<usize>> {
        let (first, step) = shard.map_or((0, 1), |s| (s.number - 1, s.count));
        (first.min(self.rows())..self.rows()).step_by(step)
    }

    /// Runs the rows `indices` on `pool`, [`CHUNK`] rows at a time in parallel, calling `done` with the number of
    /// rows after each chunk, and passes each row, turned by `shape` (in parallel too: e.g. into its CSV line), to
    /// `write` in the order of `indices`. `write` runs on a thread of its own, a chunk or two behind the
    /// computation, so that writing a chunk overlaps computing the next. The output does not depend on the number
    /// of threads, and memory holds at most three chunks whatever the number of rows. The first error of `write`
    /// stops the run and is returned.
    pub fn stream<T: Send, E: Send>(
        &self,
        indices: impl Iterator<Item = usize>,
        pool: &rayon::ThreadPool,
        done: impl Fn(usize) + Sync,
        shape: impl Fn(Row) -> T + Sync,
        write: impl FnMut(T) -> Result<(), E> + Send,
    ) -> Result<(), E> {
        self.stream_until(indices, pool, &AtomicBool::new(false), done, shape, write)
    }

    /// [`Sweep::stream`] that stops soon after `stop` is set (by another thread: Python's Ctrl-C): the rows not yet
    /// started are skipped, the chunk being computed is dropped, and nothing more reaches `write` (which has then
    /// received a prefix of the rows, in order). The caller reads `stop` to know whether the run finished.
    pub fn stream_until<T: Send, E: Send>(
        &self,
        indices: impl Iterator<Item = usize>,
        pool: &rayon::ThreadPool,
        stop: &AtomicBool,
        done: impl Fn(usize) + Sync,
        shape: impl Fn(Row) -> T + Sync,
        mut write: impl FnMut(T) -> Result<(), E> + Send,
    ) -> Result<(), E> {
        self.stream_blocks(
            indices,
            pool,
            stop,
            done,
            |rows, scratch| {
                // (A row is checked before it starts: a chunk of slow rows stops within one row's time.)
                rows.iter()
                    .map(|&index| (!stop.load(Ordering::Relaxed)).then(|| shape(self.evaluate_in(index, scratch))))
                    .collect::<Option<Vec<T>>>()
            },
            |shaped| shaped.into_iter().try_for_each(&mut write),
        )
    }

    /// The CSV lines of the rows `indices` (`impact sweep`'s file), computed on `pool` as [`Sweep::stream`] computes
    /// its rows and written by `write` in the same order, a [`BLOCK`] of rows at a time: each worker writes its
    /// rows' lines straight into the block's text ([`Sweep::line_in`]), the same bytes as [`table::line`] of each
    /// row.
    pub fn stream_lines<E: Send>(
        &self,
        indices: impl Iterator<Item = usize>,
        pool: &rayon::ThreadPool,
        done: impl Fn(usize) + Sync,
        write: impl FnMut(Lines) -> Result<(), E> + Send,
    ) -> Result<(), E> {
        // (Room for the longest numbers, 24 bytes each, until the worker has seen its lines: then as wide as the
        // widest, so that the chunks in memory hold about what they will write.)
        let guess = 64 + 24 * (self.grid.axes.len() + self.columns.len());
        self.stream_blocks(
            indices,
            pool,
            &AtomicBool::new(false),
            done,
            |rows, scratch| {
                let width = if scratch.widest > 0 { scratch.widest } else { guess };
                let mut lines = Lines {
                    text: String::with_capacity(rows.len() * width),
                    rows: rows.len(),
                    ok: 0,
                    stuck: 0,
                    first: None,
                };
                for &index in rows {
                    let start = lines.text.len();
                    let status = self.line_in(index, scratch, &mut lines.text);
                    scratch.widest = scratch.widest.max(lines.text.len() - start);
                    lines.ok += usize::from(status == Status::Ok);
                    lines.stuck += usize::from(status == Status::NotSeparated);
                    lines.first.get_or_insert(status);
                }
                Some(lines)
            },
            write,
        )
    }

    /// The machinery of [`Sweep::stream_until`] and [`Sweep::stream_lines`]: the rows `indices` in chunks of [`CHUNK`],
    /// each cut into blocks of [`BLOCK`] consecutive rows that the workers of `pool` run with their own scratch
    /// (`block` gives `None` once it sees `stop`); the writer thread passes each chunk's blocks to `write` in order.
    fn stream_blocks<B: Send, E: Send>(
        &self,
        indices: impl Iterator<Item = usize>,
        pool: &rayon::ThreadPool,
        stop: &AtomicBool,
        done: impl Fn(usize) + Sync,
        block: impl Fn(&[usize], &mut Scratch) -> Option<B> + Sync,
        mut write: impl FnMut(B) -> Result<(), E> + Send,
    ) -> Result<(), E> {
        let (send, receive) = std::sync::mpsc::sync_channel::<Vec<Option<B>>>(1);
        // The writer hands each chunk's emptied vector back, so that the chunks reuse two or three buffers: a fresh
        // one per chunk (freed on the writer's thread) cost a page fault per chunk, 6 % of the e-alone sweep's time
        // when a chunk held a handle per row.
        let (give_back, spare) = std::sync::mpsc::channel::<Vec<Option<B>>>();
        std::thread::scope(|scope| {
            let writer = scope.spawn(move || {
                for mut blocks in receive {
                    for shaped in blocks.drain(..).flatten() {
                        write(shaped)?;
                    }
                    // (The computing side may have finished: the buffer is then dropped here.)
                    let _ = give_back.send(blocks);
                }
                Ok(())
            });
            let mut indices = indices.peekable();
            let mut chunk = Vec::with_capacity(CHUNK);
            while indices.peek().is_some() {
                chunk.clear();
                chunk.extend(indices.by_ref().take(CHUNK));
                let mut blocks = spare.try_recv().unwrap_or_else(|_| Vec::with_capacity(CHUNK.div_ceil(BLOCK)));
                pool.install(|| {
                    chunk
                        .par_chunks(BLOCK)
                        .map_init(Scratch::default, |scratch, rows| {
                            if stop.load(Ordering::Relaxed) { None } else { block(rows, scratch) }
                        })
                        .collect_into_vec(&mut blocks)
                });
                if stop.load(Ordering::Relaxed) || blocks.iter().any(Option::is_none) {
                    break;
                }
                done(chunk.len());
                // The writer has stopped on an error: it is returned below.
                if send.send(blocks).is_err() {
                    break;
                }
            }
            drop(send);
            writer.join().unwrap_or_else(|panic| std::panic::resume_unwind(panic))
        })
    }

    /// Runs the rows `indices` on `threads` threads (`None`: one per core), calling `done` with the number of rows
    /// after each chunk; the rows come back in the order of `indices`. (All in memory: [`Sweep::stream`] writes a
    /// large sweep as it goes.)
    pub fn run(
        &self,
        indices: &[usize],
        threads: Option<usize>,
        done: impl Fn(usize) + Sync,
    ) -> anyhow::Result<Vec<Row>> {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads.unwrap_or(0)).build()?;
        let mut rows = Vec::with_capacity(indices.len());
        self.stream(
            indices.iter().copied(),
            &pool,
            done,
            |row| row,
            |row| {
                rows.push(row);
                Ok::<(), std::convert::Infallible>(())
            },
        )?;
        Ok(rows)
    }

    /// A fingerprint of what the rows depend on (scene text, grid, laws, columns), so that shards of different
    /// sweeps are never merged. FNV-1a, stable across machines and builds.
    pub fn fingerprint(&self) -> u64 {
        let mut hash = Fnv::default();
        hash.write(self.text.as_bytes());
        for axis in &self.grid.axes {
            hash.write(axis.key.to_string().as_bytes());
            for value in axis.values() {
                hash.write(&value.to_bits().to_le_bytes());
            }
        }
        for law in &self.laws {
            hash.write(law.name().as_bytes());
        }
        // (The default columns add nothing: the fingerprints of sweeps written before `--columns` stay valid.)
        if self.columns != Columns::default() {
            for name in self.columns.names() {
                hash.write(name.as_bytes());
            }
        }
        hash.0
    }
}

/// A point's scene error without file and line (they would point into the edited text, not the user's file).
/// A setup's error as a row's error cell: the key, then what is wrong.
fn setup_message(error: SetupError) -> String {
    format!("{}: {}", error.key, error.message)
}

fn scene_message(error: SceneError) -> String {
    match error.key {
        Some(key) => format!("{key}: {}", error.message),
        None => error.message,
    }
}

/// 64-bit FNV-1a.
struct Fnv(u64);

impl Default for Fnv {
    fn default() -> Fnv {
        Fnv(0xcbf2_9ce4_8422_2325)
    }
}

impl Fnv {
    fn write(&mut self, bytes: &[u8]) {
        for &byte in bytes.iter().chain(&[0xff]) {
            self.0 = (self.0 ^ u64::from(byte)).wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
}
