//! A sweep's table held in memory by column, beside the CSV writer: what Python's `impact.sweep` hands out as
//! arrays, built from the rows as [`Sweep::stream`](super::Sweep::stream) delivers them (never from a CSV written and
//! read back), and written as the CSV `impact sweep --out` writes, byte for byte ([`Table::write_csv`]).
//!
//! Every column of the CSV is one [`Column`]: numbers (`index`, the varied keys, the result columns, counts among
//! them) as `f64`, with an empty cell a NaN of its own ([`EMPTY`]) so that it stays apart from a NaN the report might
//! hold; text (`status`, `law`, the verdicts) as codes into a list of the distinct strings, so that a million rows of
//! `ok` cost four bytes each. The merged shards of a sweep (`impact merge`'s [`Merged`]) read into the same table.

use super::SweepError;
use super::merge::Merged;
use super::shard::Shard;
use super::table::{self, Cell, Columns, Row, VERDICT_COLUMNS};
use std::collections::HashMap;

/// The `f64` an empty cell becomes: a quiet NaN with a payload no arithmetic produces (arithmetic gives the
/// canonical NaN, written `NaN` in the CSV; this one writes nothing).
pub const EMPTY: f64 = f64::from_bits(0x7ff8_0000_0000_e3e7);

/// Whether `x` is an empty cell (not merely a NaN).
pub fn is_empty(x: f64) -> bool {
    x.to_bits() == EMPTY.to_bits()
}

/// How a column's cells are written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// Shortest round-trip numbers (`0.3`, `2.5e-5`).
    Number,
    /// Whole numbers written with all their digits (`index`, `steps`, `force_evaluations`).
    Count,
    /// Text, quoted where RFC 4180 says.
    Text,
}

/// One column's cells.
#[derive(Debug, Clone, PartialEq)]
pub enum Data {
    Numbers(Vec<f64>),
    /// Codes into `strings`, one per row.
    Texts {
        codes: Vec<u32>,
        strings: Vec<String>,
    },
}

/// One column: its name (the CSV header's), how it is written, its cells.
#[derive(Debug, Clone, PartialEq)]
pub struct Column {
    pub name: String,
    pub kind: Kind,
    pub data: Data,
}

impl Column {
    fn numbers(name: &str, kind: Kind) -> Column {
        Column { name: name.to_string(), kind, data: Data::Numbers(Vec::new()) }
    }

    fn texts(name: &str) -> Column {
        Column {
            name: name.to_string(),
            kind: Kind::Text,
            data: Data::Texts { codes: Vec::new(), strings: Vec::new() },
        }
    }

    /// Number of rows.
    pub fn len(&self) -> usize {
        match &self.data {
            Data::Numbers(values) => values.len(),
            Data::Texts { codes, .. } => codes.len(),
        }
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// The kind of result (or verdict) column `name`.
fn kind_of(name: &str) -> Kind {
    if ["steps", "force_evaluations"].contains(&name) {
        Kind::Count
    } else if VERDICT_COLUMNS.contains(&name) && !name.ends_with("_ratio") {
        Kind::Text
    } else {
        Kind::Number
    }
}

/// A sweep's table by column, with what its CSV needs besides: the shard comment line of a shard.
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    /// The columns in the CSV's order: `index`, `status`, `law`, the varied keys, the result columns.
    pub columns: Vec<Column>,
    /// The first line of a shard's file (with its line end), empty for a whole sweep.
    pub comment: String,
    /// For each text column, its strings' codes (kept while rows arrive).
    lookup: Vec<HashMap<String, u32>>,
}

impl Table {
    /// An empty table for the varied `keys` and the result `columns` (see [`table::header`]); `shard` the shard it
    /// holds, with the whole sweep's row count and fingerprint.
    pub fn new(keys: &[String], columns: &Columns, shard: Option<(Shard, usize, u64)>) -> Table {
        let mut all = vec![Column::numbers("index", Kind::Count), Column::texts("status"), Column::texts("law")];
        all.extend(keys.iter().map(|key| Column::numbers(key, Kind::Number)));
        for name in columns.names() {
            all.push(match kind_of(name) {
                Kind::Text => Column::texts(name),
                kind => Column::numbers(name, kind),
            });
        }
        let comment = shard.map(|(shard, rows, id)| table::shard_comment(shard, rows, id)).unwrap_or_default();
        let lookup = vec![HashMap::new(); all.len()];
        Table { columns: all, comment, lookup }
    }

    /// Reserves room for `rows` more rows.
    pub fn reserve(&mut self, rows: usize) {
        for column in &mut self.columns {
            match &mut column.data {
                Data::Numbers(values) => values.reserve(rows),
                Data::Texts { codes, .. } => codes.reserve(rows),
            }
        }
    }

    /// Number of rows.
    pub fn rows(&self) -> usize {
        self.columns.first().map_or(0, Column::len)
    }

    /// The CSV header line, without its line end.
    pub fn header(&self) -> String {
        let names: Vec<&str> = self.columns.iter().map(|c| c.name.as_str()).collect();
        names.join(",")
    }

    fn push_number(&mut self, column: usize, value: f64) {
        if let Data::Numbers(values) = &mut self.columns[column].data {
            values.push(value);
        }
    }

    fn push_text(&mut self, column: usize, text: &str) {
        let lookup = &mut self.lookup[column];
        if let Data::Texts { codes, strings } = &mut self.columns[column].data {
            let code = match lookup.get(text) {
                Some(&code) => code,
                None => {
                    let code = strings.len() as u32;
                    strings.push(text.to_string());
                    lookup.insert(text.to_string(), code);
                    code
                }
            };
            codes.push(code);
        }
    }

    /// Appends a row computed by the sweep (the next in index order).
    pub fn push(&mut self, row: &Row) {
        self.push_number(0, row.index as f64);
        match &row.status {
            table::Status::Ok => self.push_text(1, "ok"),
            table::Status::NotSeparated => self.push_text(1, "not separated"),
            status => self.push_text(1, &status.text()),
        }
        self.push_text(2, &row.law);
        let first = 3;
        for (k, value) in row.values.iter().enumerate() {
            self.push_number(first + k, *value);
        }
        let first = first + row.values.len();
        for (k, cell) in row.results.iter().enumerate() {
            match *cell {
                Cell::Number(x) => self.push_number(first + k, x),
                Cell::Count(n) => self.push_number(first + k, n as f64),
                Cell::Text(text) => self.push_text(first + k, text),
                Cell::Empty if self.columns[first + k].kind == Kind::Text => self.push_text(first + k, ""),
                Cell::Empty => self.push_number(first + k, EMPTY),
            }
        }
    }

    /// The table of a sweep's merged shards (`impact merge`'s checks passed): each cell read back from its text —
    /// numbers are written in shortest round-trip form, so they read back to the same bits.
    pub fn from_merged(merged: &Merged) -> Result<Table, SweepError> {
        let names = table::split(merged.header);
        let mut columns: Vec<Column> = Vec::with_capacity(names.len());
        for (k, name) in names.iter().enumerate() {
            columns.push(match (k, kind_of(name)) {
                (0, _) => Column::numbers(name, Kind::Count),
                (1 | 2, _) | (_, Kind::Text) => Column::texts(name),
                (_, kind) => Column::numbers(name, kind),
            });
        }
        let lookup = vec![HashMap::new(); columns.len()];
        let mut table = Table { columns, comment: String::new(), lookup };
        table.reserve(merged.rows.len());
        for line in &merged.rows {
            let cells = table::split(line);
            for (k, cell) in cells.iter().enumerate().take(table.columns.len()) {
                match table.columns[k].kind {
                    Kind::Text => table.push_text(k, cell),
                    _ if cell.is_empty() => table.push_number(k, EMPTY),
                    _ => {
                        let value = cell.parse::<f64>().map_err(|_| {
                            SweepError::Usage(format!("row `{}`: `{cell}` is not a number", cut_row(line)))
                        })?;
                        table.push_number(k, value);
                    }
                }
            }
        }
        Ok(table)
    }

    /// The table of a world sweep's CSV lines (`header`, then one line per row with its line end): `index` a count,
    /// `status` text, every other column numbers where each of its cells is empty or a number written as this
    /// module writes it, text otherwise (a report's strings and booleans).
    pub fn from_lines(header: &str, lines: &[String]) -> Table {
        let names = table::split(header);
        let rows: Vec<Vec<String>> = lines.iter().map(|line| table::split(line.trim_end_matches('\n'))).collect();
        let cell = |row: &Vec<String>, k: usize| row.get(k).cloned().unwrap_or_default();
        let numeric = |k: usize| {
            rows.iter().all(|row| {
                let text = cell(row, k);
                text.is_empty()
                    || text.parse::<f64>().is_ok_and(|x| {
                        let mut again = String::new();
                        table::push_number(&mut again, x);
                        again == text
                    })
            })
        };
        let columns: Vec<Column> = names
            .iter()
            .enumerate()
            .map(|(k, name)| match k {
                0 => Column::numbers(name, Kind::Count),
                1 => Column::texts(name),
                _ if numeric(k) => Column::numbers(name, Kind::Number),
                _ => Column::texts(name),
            })
            .collect();
        let lookup = vec![HashMap::new(); columns.len()];
        let mut table = Table { columns, comment: String::new(), lookup };
        table.reserve(rows.len());
        for row in &rows {
            for k in 0..table.columns.len() {
                let text = cell(row, k);
                match table.columns[k].kind {
                    Kind::Text => table.push_text(k, &text),
                    _ if text.is_empty() => table.push_number(k, EMPTY),
                    _ => table.push_number(k, text.parse().unwrap_or(f64::NAN)),
                }
            }
        }
        table
    }

    /// The CSV text of rows `rows` (all: `0..self.rows()`), appended to `out` (the comment and header first when
    /// `rows` starts at 0): the bytes `impact sweep --out` writes for the same sweep.
    pub fn write_csv(&self, rows: std::ops::Range<usize>, out: &mut String) {
        if rows.start == 0 {
            out.push_str(&self.comment);
            out.push_str(&self.header());
            out.push('\n');
        }
        let mut integer = itoa::Buffer::new();
        for row in rows {
            for (k, column) in self.columns.iter().enumerate() {
                if k > 0 {
                    out.push(',');
                }
                match (&column.data, column.kind) {
                    (Data::Numbers(values), _) if is_empty(values[row]) => {}
                    (Data::Numbers(values), Kind::Count) => out.push_str(integer.format(values[row] as u64)),
                    (Data::Numbers(values), _) => table::push_number(out, values[row]),
                    (Data::Texts { codes, strings }, _) => table::push_quoted(out, &strings[codes[row] as usize]),
                }
            }
            out.push('\n');
        }
    }
}

/// The start of a CSV line, for a message.
fn cut_row(line: &str) -> String {
    crate::text::cut(line, crate::text::MESSAGE_CHARS)
}
