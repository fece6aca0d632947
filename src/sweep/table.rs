//! The sweep's CSV: one row per point and law, every number taken from the run's [`Report`].
//!
//! Columns, in order: `index` (the row's global index, from 0), `status`, `law`, one column per varied key
//! (named by the key, e.g. `contact.restitution`, holding the value set), then [`RESULT_COLUMNS`] (SI units, as
//! in the JSON report). `status` is `ok`, `not separated` (the bodies never parted: the quantities the report
//! leaves null are empty cells) or `error: <why>` (the scene at that point is not valid, or this law cannot run
//! it: every result cell is empty). Numbers are written in their shortest round-trip form (`0.3`, `2.5e-5`), so
//! identical runs give identical bytes; a cell holding a comma or a quote is quoted as RFC 4180 says.
//!
//! The verdicts on the idealisation ([`VERDICT_COLUMNS`]) are not among the default columns: a row computes them
//! (two more runs of its contact) only when `--columns` names one of them or `--map` draws them.
//!
//! A shard's file (`--shard I/N`) starts with one comment line, `# impact sweep: shard I/N of R rows, sweep ID`
//! (ID: a fingerprint of the scene text, the grid and the laws), so that `impact merge` can check that its shards
//! come from one sweep and that none is missing. The whole sweep's file has no comment line.

use super::SweepError;
use super::shard::Shard;
use crate::fast::Quantities;
use crate::idealisation::{Idealisation, Judgement};
use crate::report::accuracy::ReferenceDetail;
use crate::report::{Report, Sections};
use crate::text::{MESSAGE_CHARS, cut};

/// The report's scalar results, after the varied keys.
pub const RESULT_COLUMNS: [&str; 41] = [
    "approach_speed",
    "effective_mass",
    "stiffness",
    "exponent",
    "damping",
    "restitution_nominal",
    "restitution_velocity_ratio",
    "restitution_impulse_ratio",
    "restitution_energy",
    "reference_restitution",
    "start_time",
    "max_compression_time",
    "duration",
    "max_penetration",
    "max_force",
    "max_force_time",
    "common_normal_velocity",
    "deformation_impulse",
    "restitution_impulse",
    "kinetic_before",
    "kinetic_after",
    "dissipated",
    "max_velocity_difference",
    "steps",
    "force_evaluations",
    "elastic_left_at_separation",
    "work_of_immovable_bodies",
    // The oblique section (empty for a direct central impact without spin); spins are magnitudes, rad/s.
    "incidence_from_normal_deg",
    "rebound_from_normal_deg",
    "tangential_restitution_centre",
    "tangential_restitution_contact",
    "friction_work",
    "slip_rest_time",
    "below_friction_limit_duration",
    "normal_turn_deg",
    "spin_after_1",
    "spin_after_2",
    // Rigid-body theory with the simulated e.
    "rigid_rebound_from_normal_deg",
    "rigid_tangential_restitution_centre",
    "rigid_spin_after_1",
    "rigid_spin_after_2",
];

/// The verdicts on the idealisation (docs/idealisation.md), after the result columns when asked for: the first
/// assumption in the order of severity ([`crate::idealisation::SEVERITY`]) that fails, and the first that is
/// marginal (`none` where there is none; empty where no verdict was measured), then each assumption's `ratio` (the
/// report's `idealisation.KEY.ratio`; empty where null) and `verdict` (`holds`, `marginal`, `fails`; empty where
/// null), in the report's order.
pub const VERDICT_COLUMNS: [&str; 18] = [
    "first_failure",
    "first_marginal",
    "instantaneous_ratio",
    "instantaneous_verdict",
    "isolated_ratio",
    "isolated_verdict",
    "particles_ratio",
    "particles_verdict",
    "elastic_ratio",
    "elastic_verdict",
    "quasi_static_ratio",
    "quasi_static_verdict",
    "constant_e_ratio",
    "constant_e_verdict",
    "smooth_ratio",
    "smooth_verdict",
    "central_ratio",
    "central_verdict",
];

/// The name of column `index` of [`RESULT_COLUMNS`] followed by [`VERDICT_COLUMNS`].
fn column_name(index: usize) -> &'static str {
    RESULT_COLUMNS.get(index).copied().unwrap_or_else(|| VERDICT_COLUMNS[index - RESULT_COLUMNS.len()])
}

/// The result columns a sweep writes: every one of [`RESULT_COLUMNS`] (the default), or those `--columns` names, in
/// its order (verdict columns among them). A row computes only what its columns show ([`Columns::quantities`],
/// [`Columns::reference`], [`Columns::verdicts`]).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Columns {
    /// Indices into [`RESULT_COLUMNS`] followed by [`VERDICT_COLUMNS`].
    chosen: Vec<usize>,
}

/// The columns that show physical times (the fast path's time quadrature).
const TIME_COLUMNS: [&str; 5] =
    ["max_compression_time", "duration", "max_force_time", "slip_rest_time", "below_friction_limit_duration"];
/// The columns that show the force peak.
const PEAK_COLUMNS: [&str; 2] = ["max_force", "max_force_time"];
/// The columns that show the dissipated energy.
const DISSIPATION_COLUMNS: [&str; 1] = ["dissipated"];
/// The columns read from the bodies' sections.
const BODY_COLUMNS: [&str; 2] = ["spin_after_1", "spin_after_2"];
/// The column read from the instantaneous impact.
const INSTANTANEOUS_COLUMN: &str = "max_velocity_difference";
/// The column that shows the exact reference.
const REFERENCE_COLUMN: &str = "reference_restitution";

impl Default for Columns {
    fn default() -> Columns {
        Columns { chosen: (0..RESULT_COLUMNS.len()).collect() }
    }
}

impl Columns {
    /// The columns `names` (from `--columns`), checked: each a result column, none twice, at least one.
    pub fn parse(names: &[String]) -> Result<Columns, SweepError> {
        let mut chosen = Vec::with_capacity(names.len());
        for name in names {
            let name = name.trim();
            let Some(index) = RESULT_COLUMNS.iter().chain(&VERDICT_COLUMNS).position(|&c| c == name) else {
                let fixed = ["index", "status", "law"].contains(&name) || name.contains('.');
                return Err(SweepError::Usage(if fixed {
                    format!(
                        "--columns: `{}` is always written (index, status, law and the varied keys come first); name \
                         result columns only",
                        cut(name, MESSAGE_CHARS)
                    )
                } else {
                    format!(
                        "--columns: unknown column `{}`; expected some of {}, or of the verdicts {}",
                        cut(name, MESSAGE_CHARS),
                        RESULT_COLUMNS.join(", "),
                        VERDICT_COLUMNS.join(", ")
                    )
                }));
            };
            if chosen.contains(&index) {
                return Err(SweepError::Usage(format!("--columns: `{name}` is given twice")));
            }
            chosen.push(index);
        }
        if chosen.is_empty() {
            return Err(SweepError::Usage("--columns: name at least one result column".into()));
        }
        Ok(Columns { chosen })
    }

    /// The names, in the order written.
    pub fn names(&self) -> impl Iterator<Item = &'static str> + '_ {
        self.chosen.iter().map(|&i| column_name(i))
    }

    /// Appends those of `names` (result or verdict columns) not chosen yet, in their order: the columns a figure
    /// reads (`--map`).
    pub fn add(&mut self, names: &[&str]) {
        for name in names {
            let index = RESULT_COLUMNS.iter().chain(&VERDICT_COLUMNS).position(|c| c == name);
            if let Some(index) = index.filter(|i| !self.chosen.contains(i)) {
                self.chosen.push(index);
            }
        }
    }

    /// Whether a row judges the idealisation: a verdict column is written.
    pub fn verdicts(&self) -> bool {
        self.chosen.iter().any(|&i| i >= RESULT_COLUMNS.len())
    }

    pub fn len(&self) -> usize {
        self.chosen.len()
    }

    pub fn is_empty(&self) -> bool {
        self.chosen.is_empty()
    }

    fn shows(&self, names: &[&str]) -> bool {
        self.names().any(|name| names.contains(&name))
    }

    /// What a row's run must compute besides the motion and the impulses.
    pub fn quantities(&self) -> Quantities {
        // (The verdicts read the contact's duration and its peak force.)
        Quantities {
            time: self.shows(&TIME_COLUMNS) || self.verdicts(),
            peak: self.shows(&PEAK_COLUMNS) || self.verdicts(),
            dissipation: self.shows(&DISSIPATION_COLUMNS),
        }
    }

    /// The parts of the report a row fills: no names (no column shows text of the scene's); the instantaneous
    /// impacts only for `max_velocity_difference`, the bodies only for the spins (the verdicts fill both in any case).
    pub fn sections(&self) -> Sections {
        Sections { names: false, instantaneous: self.shows(&[INSTANTANEOUS_COLUMN]), bodies: self.shows(&BODY_COLUMNS) }
    }

    /// How much of the exact reference a row computes: the restitution if its column is written, else none.
    pub fn reference(&self) -> ReferenceDetail {
        if self.shows(&[REFERENCE_COLUMN]) { ReferenceDetail::Restitution } else { ReferenceDetail::Off }
    }

    /// The chosen cells of a report: of its [`results`], and of its [`verdicts`] when one is chosen, in the chosen
    /// order.
    pub fn pick(&self, report: &Report) -> Vec<Cell> {
        let mut cells = Vec::with_capacity(self.chosen.len());
        self.pick_into(report, &mut cells);
        cells
    }

    /// [`Columns::pick`] into `cells` (emptied first: a sweep worker's, kept from row to row).
    pub fn pick_into(&self, report: &Report, cells: &mut Vec<Cell>) {
        cells.clear();
        // (Every column in its own order, the default: all at once rather than a cell at a time.)
        if self.chosen.len() == RESULT_COLUMNS.len() && self.chosen.iter().enumerate().all(|(k, &i)| k == i) {
            cells.extend_from_slice(&results(report));
            return;
        }
        let judged = self.verdicts().then(|| verdicts(&report.idealisation));
        let cell = |i: usize| match (i < RESULT_COLUMNS.len(), &judged) {
            (true, _) => result(report, i),
            (false, Some(judged)) => judged[i - RESULT_COLUMNS.len()],
            (false, None) => Cell::Empty,
        };
        cells.extend(self.chosen.iter().map(|&i| cell(i)));
    }
}

/// One cell of a result column.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Cell {
    Number(f64),
    Count(u64),
    /// A name (a verdict, an assumption's key).
    Text(&'static str),
    /// Null in the report (e.g. `duration` when the bodies did not separate).
    Empty,
}

impl From<Option<f64>> for Cell {
    fn from(value: Option<f64>) -> Cell {
        value.map_or(Cell::Empty, Cell::Number)
    }
}

/// How a row's run ended.
#[derive(Debug, Clone, PartialEq)]
pub enum Status {
    Ok,
    NotSeparated,
    /// Why the point could not be run.
    Error(String),
}

impl Status {
    /// The `status` cell.
    pub fn text(&self) -> String {
        match self {
            Status::Ok => "ok".into(),
            Status::NotSeparated => "not separated".into(),
            // One row is one line, whatever the message.
            Status::Error(why) => format!("error: {}", why.replace(['\n', '\r'], " ")),
        }
    }
}

/// One row of the sweep.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// Global index in the whole sweep.
    pub index: usize,
    pub status: Status,
    /// The law's scene spelling (as the file writes it when no --law is given).
    pub law: std::borrow::Cow<'static, str>,
    /// The varied keys' values, in --vary order.
    pub values: Vec<f64>,
    /// The sweep's result columns ([`Columns`]), all empty for an error.
    pub results: Vec<Cell>,
}

/// The result cells of a report, in [`RESULT_COLUMNS`] order ([`result`] for each; on the stack: a row's cells
/// allocate nothing until the chosen ones are picked).
pub fn results(report: &Report) -> [Cell; RESULT_COLUMNS.len()] {
    std::array::from_fn(|i| result(report, i))
}

/// Cell `i` of a report's [`results`], column `RESULT_COLUMNS[i]` (empty past the last): a row that writes a few
/// columns forms only those. Each is the report's value of the same name (`tests::each_result_is_the_reports_value`),
/// the spins as magnitudes; the oblique columns are empty for a direct central impact without spin.
pub fn result(report: &Report, i: usize) -> Cell {
    let c = &report.contact;
    let law = &report.law;
    let number = Cell::Number;
    let oblique = report.oblique.as_ref();
    let rigid = || oblique.and_then(|o| o.rigid_body.as_ref());
    let size = |v: &[f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    let spin = |i: usize| report.bodies[i].angular_velocity_after.as_ref().map(size);
    match i {
        0 => number(report.approach_speed),
        1 => number(report.effective_mass),
        2 => number(law.stiffness),
        3 => number(law.exponent),
        4 => number(law.damping),
        5 => law.restitution_nominal.into(),
        6 => c.restitution_velocity_ratio.into(),
        7 => c.restitution_impulse_ratio.into(),
        8 => c.restitution_energy.into(),
        9 => report.reference.as_ref().and_then(|r| r.restitution).into(),
        10 => number(c.start_time),
        11 => number(c.max_compression_time),
        12 => c.duration.into(),
        13 => number(c.max_penetration),
        14 => number(c.max_force),
        15 => number(c.max_force_time),
        16 => number(c.common_normal_velocity),
        17 => number(c.deformation_impulse),
        18 => c.restitution_impulse.into(),
        19 => number(report.energy.kinetic_before),
        20 => report.energy.kinetic_after.into(),
        21 => report.energy.dissipated.into(),
        22 => report.instantaneous.as_ref().and_then(|i| i.max_velocity_difference).into(),
        23 => Cell::Count(report.solver.steps),
        24 => Cell::Count(report.solver.force_evaluations),
        25 => report.energy.elastic_left_at_separation.into(),
        26 => report.energy.work_of_immovable_bodies.into(),
        27 => oblique.map(|o| o.incidence_from_normal_deg).into(),
        28 => oblique.and_then(|o| o.rebound_from_normal_deg).into(),
        29 => oblique.and_then(|o| o.tangential_restitution_centre).into(),
        30 => oblique.and_then(|o| o.tangential_restitution_contact).into(),
        31 => oblique.and_then(|o| o.friction_work).into(),
        32 => oblique.and_then(|o| o.slip_rest_time).into(),
        33 => oblique.and_then(|o| o.below_friction_limit_duration).into(),
        34 => oblique.and_then(|o| o.normal_turn_deg).into(),
        35 => oblique.and(spin(0)).into(),
        36 => oblique.and(spin(1)).into(),
        37 => rigid().map(|r| r.rebound_from_normal_deg).into(),
        38 => rigid().and_then(|r| r.tangential_restitution_centre).into(),
        39 => rigid().map(|r| size(&r.angular_velocity_after[0])).into(),
        40 => rigid().map(|r| size(&r.angular_velocity_after[1])).into(),
        _ => Cell::Empty,
    }
}

/// The verdict cells of a report's idealisation, in [`VERDICT_COLUMNS`] order: all empty where nothing was judged
/// (every verdict null).
pub fn verdicts(idealisation: &Idealisation) -> [Cell; VERDICT_COLUMNS.len()] {
    let mut cells = [Cell::Empty; VERDICT_COLUMNS.len()];
    let entries = idealisation.entries();
    if entries.iter().all(|(_, verdict)| verdict.is_none()) {
        return cells;
    }
    let first = |judgement| Cell::Text(idealisation.first(judgement).unwrap_or("none"));
    cells[0] = first(Judgement::Fails);
    cells[1] = first(Judgement::Marginal);
    for (k, (_, verdict)) in entries.iter().enumerate() {
        if let Some(verdict) = verdict {
            cells[2 + 2 * k] = Cell::Number(verdict.ratio);
            cells[3 + 2 * k] = Cell::Text(verdict.verdict.name());
        }
    }
    cells
}

/// Shortest round-trip text of a number: plain for magnitudes in [1e-4, 1e6), exponent form otherwise.
pub fn number(x: f64) -> String {
    let mut text = String::new();
    push_number(&mut text, x);
    text
}

/// Appends [`number`]`(x)` to `text`: the shortest digits that read back as `x` (`zmij`'s; where several strings of
/// that length would, it may pick another than the standard library), written as `format!("{x}")` writes them for
/// magnitudes in [1e-4, 1e6) and as `format!("{x:e}")` outside — without the formatting machinery, since a sweep
/// writes tens of numbers per row and millions of rows.
pub fn push_number(text: &mut String, x: f64) {
    if x == 0.0 {
        text.push_str(if x.is_sign_negative() { "-0" } else { "0" });
        return;
    }
    if !x.is_finite() {
        text.push_str(&format!("{x}"));
        return;
    }
    let magnitude = x.abs();
    if magnitude < 1e6 && x.fract() == 0.0 {
        // A whole number (a mass of 1 kg, an exponent of 1) as an integer's digits: what the shortest digits give.
        text.push_str(itoa::Buffer::new().format(x as i64));
    } else if (1e-4..1e6).contains(&magnitude) {
        // Here zmij writes the plain decimal itself ("123.45", "0.000123").
        text.push_str(zmij::Buffer::new().format_finite(x));
    } else {
        push_exponent_form(text, x);
    }
}

/// Appends the finite, non-zero `x` as `format!("{x:e}")` writes it: "1.5e-7", "2e21". (A function of its own so that
/// [`push_number`]'s common plain numbers do not pay for this one's locals.)
#[inline(never)]
fn push_exponent_form(text: &mut String, x: f64) {
    let (digits, count, exponent) = shortest_digits(x);
    let digits = &digits[..count];
    // At most 17 digits, a sign, a point, "e-324": 24 bytes.
    let mut out = ShortText::default();
    if x < 0.0 {
        out.push(b"-");
    }
    out.push(&digits[..1]);
    if digits.len() > 1 {
        out.push(b".");
        out.push(&digits[1..]);
    }
    out.push(b"e");
    if exponent < 0 {
        out.push(b"-");
    }
    let size = exponent.unsigned_abs();
    let mut decimal = [b'0'; 3];
    let places = if size >= 100 {
        3
    } else if size >= 10 {
        2
    } else {
        1
    };
    for (i, place) in decimal[..places].iter_mut().rev().enumerate() {
        *place = b'0' + (size / 10u32.pow(i as u32) % 10) as u8;
    }
    out.push(&decimal[..places]);
    text.push_str(out.as_str());
}

/// The shortest decimal digits that read back as the finite, non-zero `x` (`zmij`'s, the same as `ryu`'s), without the sign: the
/// significant digits (no leading or trailing zeros; at most 17), their count, and the decimal exponent `k` of the
/// first (`|x| = d.ddd × 10^k`).
pub fn shortest_digits(x: f64) -> ([u8; 24], usize, i32) {
    let mut buffer = zmij::Buffer::new();
    let shortest = buffer.format_finite(x.abs()).as_bytes();
    // zmij writes "123.45", "0.000123", "1.5e-7" or "1.5e+21": read off the significant digits and the decimal exponent k of
    // the first one.
    let (mantissa, power) = match shortest.iter().position(|&b| b == b'e') {
        Some(at) => (&shortest[..at], exponent_of(&shortest[at + 1..])),
        None => (shortest, 0),
    };
    let point = mantissa.iter().position(|&b| b == b'.').unwrap_or(mantissa.len());
    let mut digits = [0u8; 24];
    let mut count = 0;
    let mut exponent = power + point as i32 - 1;
    for &byte in mantissa.iter().filter(|&&b| b != b'.') {
        if count == 0 && byte == b'0' {
            exponent -= 1;
        } else if count < digits.len() {
            digits[count] = byte;
            count += 1;
        }
    }
    while count > 1 && digits[count - 1] == b'0' {
        count -= 1;
    }
    (digits, count, exponent)
}

/// A number's text assembled on the stack (digits, sign, point, exponent: at most 48 ASCII bytes), so that
/// formatting one allocates nothing.
pub struct ShortText {
    bytes: [u8; 48],
    len: usize,
}

impl Default for ShortText {
    fn default() -> ShortText {
        ShortText { bytes: [0; 48], len: 0 }
    }
}

impl ShortText {
    /// Appends ASCII `bytes` (the callers' pieces fit: see [`push_number`] and the grid's tidy).
    pub fn push(&mut self, bytes: &[u8]) {
        self.bytes[self.len..self.len + bytes.len()].copy_from_slice(bytes);
        self.len += bytes.len();
    }

    pub fn as_str(&self) -> &str {
        std::str::from_utf8(&self.bytes[..self.len]).unwrap_or_default()
    }
}

/// The decimal exponent zmij writes after its "e" ("-7", "+21").
fn exponent_of(bytes: &[u8]) -> i32 {
    let (sign, digits) = match bytes.first() {
        Some(b'-') => (-1, &bytes[1..]),
        Some(b'+') => (1, &bytes[1..]),
        _ => (1, bytes),
    };
    sign * digits.iter().fold(0i32, |value, &b| value * 10 + i32::from(b - b'0'))
}

/// Appends a cell as CSV: quoted when it holds a comma, a quote or a line break (RFC 4180).
pub fn push_quoted(out: &mut String, text: &str) {
    if text.contains([',', '"', '\n', '\r']) {
        out.push('"');
        out.push_str(&text.replace('"', "\"\""));
        out.push('"');
    } else {
        out.push_str(text);
    }
}

/// The header line (without its newline) for the varied keys `keys` and the result columns `columns`.
pub fn header(keys: &[String], columns: &Columns) -> String {
    let mut names = vec!["index".to_string(), "status".into(), "law".into()];
    names.extend(keys.iter().cloned());
    names.extend(columns.names().map(str::to_string));
    names.join(",")
}

/// One row as a CSV line, with its newline.
pub fn line(row: &Row) -> String {
    // (Room for the longest numbers, 24 bytes each, but none for the empty cells: a row's line stays in memory until
    // the writer takes it.)
    let filled = row.results.iter().filter(|cell| **cell != Cell::Empty).count();
    let mut text = String::with_capacity(64 + 24 * (row.values.len() + filled));
    push_line(&mut text, row.index, &row.status, &Quoted::new(&row.law), &row.values, &row.results);
    text
}

/// A cell's text as CSV writes it (quoted when it holds a comma, a quote or a line break: [`push_quoted`]), formed
/// once: a sweep writes its law's name on every row.
#[derive(Debug, Clone, PartialEq)]
pub struct Quoted(String);

impl Quoted {
    pub fn new(text: &str) -> Quoted {
        let mut quoted = String::with_capacity(text.len());
        push_quoted(&mut quoted, text);
        Quoted(quoted)
    }
}

/// Appends the CSV line of row `index` (with its newline) to `text`: its status, its law, its varied values and its
/// result cells. ([`line`] is this on a row; a sweep's worker writes its rows' lines straight into one text.)
pub fn push_line(text: &mut String, index: usize, status: &Status, law: &Quoted, values: &[f64], results: &[Cell]) {
    let mut integer = itoa::Buffer::new();
    text.push_str(integer.format(index));
    text.push(',');
    match status {
        // (The common statuses without building their text.)
        Status::Ok => text.push_str("ok"),
        Status::NotSeparated => text.push_str("not separated"),
        status => push_quoted(text, &status.text()),
    }
    text.push(',');
    text.push_str(&law.0);
    for value in values {
        text.push(',');
        push_number(text, *value);
    }
    for cell in results {
        text.push(',');
        match cell {
            Cell::Number(x) => push_number(text, *x),
            Cell::Count(n) => text.push_str(integer.format(*n)),
            Cell::Text(name) => push_quoted(text, name),
            Cell::Empty => {}
        }
    }
    text.push('\n');
}

/// The first line of a shard's file.
pub fn shard_comment(shard: Shard, rows: usize, fingerprint: u64) -> String {
    format!("# impact sweep: shard {shard} of {rows} rows, sweep {fingerprint:016x}\n")
}

/// What a shard's comment line says.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ShardInfo {
    pub shard: Shard,
    /// Rows of the whole sweep.
    pub rows: usize,
    pub fingerprint: u64,
}

/// Reads a shard's comment line (without its newline); `None` if it is not one.
pub fn parse_shard_comment(line: &str) -> Option<ShardInfo> {
    let rest = line.strip_prefix("# impact sweep: shard ")?;
    let (shard, rest) = rest.split_once(" of ")?;
    let (rows, rest) = rest.split_once(" rows, sweep ")?;
    let shard = Shard::parse(shard).ok()?;
    let rows = rows.parse().ok()?;
    let fingerprint = u64::from_str_radix(rest.trim_end(), 16).ok()?;
    Some(ShardInfo { shard, rows, fingerprint })
}

/// The whole CSV text: the shard comment (for a shard), the header, the rows.
pub fn render(keys: &[String], columns: &Columns, rows: &[Row], shard: Option<(Shard, usize, u64)>) -> String {
    let mut text = shard.map(|(shard, total, id)| shard_comment(shard, total, id)).unwrap_or_default();
    text += &header(keys, columns);
    text.push('\n');
    for row in rows {
        text += &line(row);
    }
    text
}

/// Number of cells of a CSV line (RFC 4180 quoting), without splitting it.
pub fn cell_count(line: &str) -> usize {
    let mut quoted = false;
    let mut cells = 1;
    for c in line.chars() {
        match c {
            // A doubled quote inside a quoted cell toggles twice.
            '"' => quoted = !quoted,
            ',' if !quoted => cells += 1,
            _ => {}
        }
    }
    cells
}

/// Splits a CSV line into cells, undoing RFC 4180 quoting.
pub fn split(line: &str) -> Vec<String> {
    let mut cells = Vec::new();
    let mut cell = String::new();
    let mut chars = line.chars().peekable();
    let mut quoted = false;
    while let Some(c) = chars.next() {
        match (c, quoted) {
            ('"', true) if chars.peek() == Some(&'"') => {
                cell.push('"');
                chars.next();
            }
            ('"', true) => quoted = false,
            ('"', false) if cell.is_empty() => quoted = true,
            (',', false) => cells.push(std::mem::take(&mut cell)),
            _ => cell.push(c),
        }
    }
    cells.push(cell);
    cells
}

#[cfg(test)]
mod tests {
    #[test]
    fn numbers_are_written_as_the_standard_formatting_writes_them() {
        // std's `{}` and `{:e}` print the shortest digits that read back: the reference for the fast writer.
        let reference = |x: f64| {
            let magnitude = x.abs();
            if x == 0.0 || (1e-4..1e6).contains(&magnitude) || !x.is_finite() {
                format!("{x}")
            } else {
                format!("{x:e}")
            }
        };
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        let mut values = vec![0.0, -0.0, 1.0, -1.0, 0.1, 0.3, 2.0, 1e-4, 9.999999999999999e-5, 1e6, 999999.9999999999];
        values.extend([123456.0, 0.0001234, 1.5e-7, 6.02214076e23, f64::MAX, f64::MIN_POSITIVE, 5e-324, -2.5e10]);
        values.extend([f64::INFINITY, f64::NEG_INFINITY, f64::NAN, 100.0, 1e21, 1e22, 0.000999, 12345.678901234567]);
        // Whole numbers either side of the plain range's end (written as integers below 1e6).
        values.extend([-20.0, 999999.0, -999999.0, 1000001.0, 4503599627370496.0, 3.0, -7.0]);
        for _ in 0..200_000 {
            // Random bit patterns cover every exponent; random decimals cover short digit strings.
            values.push(f64::from_bits(next()));
            let digits = (next() % 1_000_000) as f64;
            values.push(digits * 10f64.powi((next() % 40) as i32 - 20));
        }
        let mut differing = 0;
        for x in values {
            let (written, standard) = (number(x), reference(x));
            if x.is_nan() {
                assert_eq!(written, "NaN");
                continue;
            }
            // It reads back exactly, in the standard's shape: the same sign, form and exponent, as many digits.
            assert_eq!(written.parse::<f64>().unwrap().to_bits(), x.to_bits(), "{x:?}: {written}");
            let shape = |text: &str| {
                let (mantissa, power) = text.split_once('e').unwrap_or((text, ""));
                let digits = mantissa.chars().filter(char::is_ascii_digit).collect::<String>();
                (
                    mantissa.starts_with('-'),
                    mantissa.contains('.'),
                    power.to_string(),
                    digits.trim_start_matches('0').len(),
                )
            };
            assert_eq!(shape(&written), shape(&standard), "{x:?}: {written} against {standard}");
            differing += usize::from(written != standard);
        }
        // Ties between equally short strings are rare.
        assert!(differing < 100, "{differing} of 400 000 differ from the standard's choice");
    }

    use super::*;

    #[test]
    fn cells_are_counted_outside_quotes() {
        assert_eq!(cell_count("0,ok,hertz"), 3);
        assert_eq!(cell_count("1,\"error: a, b\",hertz,"), 4);
        assert_eq!(cell_count("2,\"say \"\"x, y\"\"\",z"), 3);
        assert_eq!(cell_count(""), 1);
    }
}

#[cfg(test)]
mod result_tests {
    use super::*;
    use crate::history::Recording;
    use crate::scene::Scene;
    use serde_json::Value;

    /// Where each result column's value sits in the JSON report (docs/report.md): the column of the same name in its
    /// section; the spins are the sizes of the vectors there (`None`: a magnitude of the vector at that place).
    fn place(name: &str) -> (String, bool) {
        let magnitude = |at: &str| (at.to_string(), true);
        match name {
            "approach_speed" | "effective_mass" => (format!("/{name}"), false),
            "stiffness" | "exponent" | "damping" | "restitution_nominal" => (format!("/law/{name}"), false),
            "reference_restitution" => ("/reference/restitution".into(), false),
            "kinetic_before"
            | "kinetic_after"
            | "dissipated"
            | "elastic_left_at_separation"
            | "work_of_immovable_bodies" => (format!("/energy/{name}"), false),
            "max_velocity_difference" => ("/instantaneous/max_velocity_difference".into(), false),
            "steps" | "force_evaluations" => (format!("/solver/{name}"), false),
            "spin_after_1" => magnitude("/bodies/0/angular_velocity_after"),
            "spin_after_2" => magnitude("/bodies/1/angular_velocity_after"),
            "rigid_spin_after_1" => magnitude("/oblique/rigid_body/angular_velocity_after/0"),
            "rigid_spin_after_2" => magnitude("/oblique/rigid_body/angular_velocity_after/1"),
            _ => match name.strip_prefix("rigid_") {
                Some(rest) => (format!("/oblique/rigid_body/{rest}"), false),
                None if RESULT_COLUMNS[27..].contains(&name) => (format!("/oblique/{name}"), false),
                None => (format!("/contact/{name}"), false),
            },
        }
    }

    /// Each result column holds the report's value of its name, read from the report written as JSON (every section
    /// filled): a head-on impact on a wall (no oblique section: those cells empty) and an oblique frictional impact
    /// of two spheres (every section filled). A cell put under the wrong column fails here.
    #[test]
    fn each_result_is_the_reports_value() {
        let head_on = "[[bodies]]\nradius = 0.01\nmass = 0.03\nvelocity = [1.5, 0.0, 0.0]\nyoung = 2e11\npoisson = 0.3\n\n\
                       [[bodies]]\nradius = inf\nmass = inf\nvelocity = [0.0, 0.0, 0.0]\nyoung = 7e10\npoisson = 0.33\n\n\
                       [contact]\nlaw = \"hunt-crossley\"\nrestitution = 0.6\n";
        let oblique = "[[bodies]]\nradius = 0.01\nmass = 0.03\nvelocity = [1.5, 0.7, 0.0]\nposition = [0.0, 0.0, 0.0]\n\
                       young = 2e11\npoisson = 0.3\n\n[[bodies]]\nradius = 0.02\nmass = 0.2\nvelocity = [-0.5, 0.0, 0.0]\n\
                       position = [0.03, 0.0, 0.0]\nyoung = 7e10\npoisson = 0.33\n\n\
                       [contact]\nlaw = \"hunt-crossley\"\nrestitution = 0.6\nfriction = 0.2\n";
        for (text, filled) in [(head_on, false), (oblique, true)] {
            let scene = Scene::parse(text, std::path::Path::new("result.toml")).unwrap();
            let report = crate::impact::simulate(&scene, Recording::Off).unwrap().report;
            let json = serde_json::to_value(&report).unwrap();
            assert_eq!(json.pointer("/oblique").is_some_and(|o| !o.is_null()), filled, "{text}");
            for (i, name) in RESULT_COLUMNS.iter().enumerate() {
                let (at, magnitude) = place(name);
                let value = json.pointer(&at).unwrap_or(&Value::Null);
                let expected = match value {
                    Value::Null => Cell::Empty,
                    Value::Array(v) if magnitude => {
                        let v: Vec<f64> = v.iter().map(|c| c.as_f64().unwrap()).collect();
                        Cell::Number((v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt())
                    }
                    Value::Number(n) if n.is_u64() && (*name == "steps" || *name == "force_evaluations") => {
                        Cell::Count(n.as_u64().unwrap())
                    }
                    Value::Number(n) => Cell::Number(n.as_f64().unwrap()),
                    other => panic!("{name} at {at}: {other}"),
                };
                // (The spins of a head-on impact: its oblique section is null, and so are they.)
                let expected = if magnitude && !filled && !name.starts_with("rigid") { Cell::Empty } else { expected };
                assert_eq!(result(&report, i), expected, "{name} at {at}");
                assert_eq!(results(&report)[i], expected, "{name}");
            }
            // Past the last column: empty.
            assert_eq!(result(&report, RESULT_COLUMNS.len()), Cell::Empty);
        }
    }
}
