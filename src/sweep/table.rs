//! The sweep's CSV: one row per point and law, every number taken from the run's [`Report`].
//!
//! Columns, in order: `index` (the row's global index, from 0), `status`, `law`, one column per varied key
//! (named by the key, e.g. `contact.restitution`, holding the value set), then [`RESULT_COLUMNS`] (SI units, as
//! in the JSON report). `status` is `ok`, `not separated` (the bodies never parted: the quantities the report
//! leaves null are empty cells) or `error: <why>` (the scene at that point is not valid, or this law cannot run
//! it: every result cell is empty). Numbers are written in their shortest round-trip form (`0.3`, `2.5e-5`), so
//! identical runs give identical bytes; a cell holding a comma or a quote is quoted as RFC 4180 says.
//!
//! A shard's file (`--shard I/N`) starts with one comment line, `# impact sweep: shard I/N of R rows, sweep ID`
//! (ID: a fingerprint of the scene text, the grid and the laws), so that `impact merge` can check that its shards
//! come from one sweep and that none is missing. The whole sweep's file has no comment line.

use super::shard::Shard;
use crate::report::Report;
use std::fmt::Write;

/// The report's scalar results, after the varied keys.
pub const RESULT_COLUMNS: [&str; 40] = [
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
    "stick_duration",
    "normal_turn_deg",
    "spin_after_1",
    "spin_after_2",
    // Rigid-body theory with the simulated e.
    "rigid_rebound_from_normal_deg",
    "rigid_tangential_restitution_centre",
    "rigid_spin_after_1",
    "rigid_spin_after_2",
];

/// One cell of a result column.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Cell {
    Number(f64),
    Count(u64),
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
    pub law: String,
    /// The varied keys' values, in --vary order.
    pub values: Vec<f64>,
    /// [`RESULT_COLUMNS`], all empty for an error.
    pub results: Vec<Cell>,
}

/// The result cells of a report, in [`RESULT_COLUMNS`] order.
pub fn results(report: &Report) -> Vec<Cell> {
    let c = &report.contact;
    let law = &report.law;
    let number = Cell::Number;
    let mut cells = vec![
        number(report.approach_speed),
        number(report.effective_mass),
        number(law.stiffness),
        number(law.exponent),
        number(law.damping),
        law.restitution_nominal.into(),
        c.restitution_velocity_ratio.into(),
        c.restitution_impulse_ratio.into(),
        c.restitution_energy.into(),
        report.reference.as_ref().and_then(|r| r.restitution).into(),
        number(c.start_time),
        number(c.max_compression_time),
        c.duration.into(),
        number(c.max_penetration),
        number(c.max_force),
        number(c.max_force_time),
        number(c.common_normal_velocity),
        number(c.deformation_impulse),
        c.restitution_impulse.into(),
        number(report.energy.kinetic_before),
        report.energy.kinetic_after.into(),
        report.energy.dissipated.into(),
        report.instantaneous.as_ref().and_then(|i| i.max_velocity_difference).into(),
        Cell::Count(report.solver.steps),
        Cell::Count(report.solver.force_evaluations),
        report.energy.elastic_left_at_separation.into(),
        report.energy.work_of_immovable_bodies.into(),
    ];
    let oblique = report.oblique.as_ref();
    let rigid = oblique.and_then(|o| o.rigid_body.as_ref());
    let size = |v: &[f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    let spin = |i: usize| report.bodies[i].angular_velocity_after.as_ref().map(size);
    cells.extend::<[Cell; 13]>([
        oblique.map(|o| o.incidence_from_normal_deg).into(),
        oblique.and_then(|o| o.rebound_from_normal_deg).into(),
        oblique.and_then(|o| o.tangential_restitution_centre).into(),
        oblique.and_then(|o| o.tangential_restitution_contact).into(),
        oblique.and_then(|o| o.friction_work).into(),
        oblique.and_then(|o| o.stick_duration).into(),
        oblique.and_then(|o| o.normal_turn_deg).into(),
        oblique.and(spin(0)).into(),
        oblique.and(spin(1)).into(),
        rigid.map(|r| r.rebound_from_normal_deg).into(),
        rigid.and_then(|r| r.tangential_restitution_centre).into(),
        rigid.map(|r| size(&r.angular_velocity_after[0])).into(),
        rigid.map(|r| size(&r.angular_velocity_after[1])).into(),
    ]);
    cells
}

/// Shortest round-trip text of a number: plain for magnitudes in [1e-4, 1e6), exponent form otherwise.
pub fn number(x: f64) -> String {
    let magnitude = x.abs();
    if x == 0.0 || (1e-4..1e6).contains(&magnitude) || !x.is_finite() { format!("{x}") } else { format!("{x:e}") }
}

/// A cell as CSV: quoted when it holds a comma, a quote or a line break (RFC 4180).
fn quoted(text: &str) -> String {
    if text.contains([',', '"', '\n', '\r']) { format!("\"{}\"", text.replace('"', "\"\"")) } else { text.to_string() }
}

/// The header line (without its newline) for the varied keys `keys`.
pub fn header(keys: &[String]) -> String {
    let mut columns = vec!["index".to_string(), "status".into(), "law".into()];
    columns.extend(keys.iter().cloned());
    columns.extend(RESULT_COLUMNS.iter().map(|c| c.to_string()));
    columns.join(",")
}

/// One row as a CSV line, with its newline.
pub fn line(row: &Row) -> String {
    let mut text = format!("{},{},{}", row.index, quoted(&row.status.text()), quoted(&row.law));
    for value in &row.values {
        let _ = write!(text, ",{}", number(*value));
    }
    for cell in &row.results {
        match cell {
            Cell::Number(x) => {
                let _ = write!(text, ",{}", number(*x));
            }
            Cell::Count(n) => {
                let _ = write!(text, ",{n}");
            }
            Cell::Empty => text.push(','),
        }
    }
    text.push('\n');
    text
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
pub fn render(keys: &[String], rows: &[Row], shard: Option<(Shard, usize, u64)>) -> String {
    let mut text = shard.map(|(shard, total, id)| shard_comment(shard, total, id)).unwrap_or_default();
    text += &header(keys);
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
    use super::*;

    #[test]
    fn cells_are_counted_outside_quotes() {
        assert_eq!(cell_count("0,ok,hertz"), 3);
        assert_eq!(cell_count("1,\"error: a, b\",hertz,"), 4);
        assert_eq!(cell_count("2,\"say \"\"x, y\"\"\",z"), 3);
        assert_eq!(cell_count(""), 1);
    }
}
