//! The series of a world run as CSV, streamed while the run goes (docs/report.md#the-world-series-csv): one row per
//! body and per active contact at each instant, so that a run of any length holds only the rows of its last chunk.

use crate::files::{FileError, OutputFile};
use crate::world::flight::Kinematic;
use crate::world::record::{ContactSample, Observer};
use std::fmt::Write;

/// Column names, in order.
pub const COLUMNS: [&str; 11] =
    ["time_s", "kind", "index", "x_m", "y_m", "z_m", "vx_m_s", "vy_m_s", "vz_m_s", "penetration_m", "force_N"];

/// Bytes gathered before they are written.
const CHUNK: usize = 1 << 20;

/// Writes the rows of each instant into an output file (atomically: the file appears when [`SeriesWriter::finish`]
/// succeeds).
pub struct SeriesWriter {
    /// `None`: the text is kept in memory ([`SeriesWriter::in_memory`]).
    file: Option<OutputFile>,
    text: String,
    /// The first failure to write, kept to be reported at the end (an observer cannot stop the run).
    error: Option<FileError>,
}

impl SeriesWriter {
    /// A writer into `file`, its header written.
    pub fn new(file: OutputFile) -> SeriesWriter {
        SeriesWriter { file: Some(file), text: COLUMNS.join(",") + "\n", error: None }
    }

    /// A writer that keeps the whole series as text (Python's `Report.history` of a world), for [`SeriesWriter::text`].
    pub fn in_memory() -> SeriesWriter {
        SeriesWriter { file: None, text: COLUMNS.join(",") + "\n", error: None }
    }

    /// The series written so far, as CSV text, of a writer [`SeriesWriter::in_memory`].
    pub fn text(&self) -> &str {
        &self.text
    }

    fn flush(&mut self) {
        let Some(file) = &mut self.file else { return };
        if self.error.is_none()
            && let Err(error) = file.write_bytes(self.text.as_bytes())
        {
            self.error = Some(error);
        }
        self.text.clear();
    }

    /// Writes what is left and publishes the file; the first error of the run, if any.
    pub fn finish(mut self) -> Result<OutputFile, FileError> {
        self.flush();
        match (self.error, self.file) {
            (Some(error), _) => Err(error),
            (None, Some(file)) => Ok(file),
            (None, None) => Err(FileError::Write {
                path: "memory".into(),
                source: std::io::Error::other("a series kept in memory has no file to finish"),
            }),
        }
    }
}

impl Observer for SeriesWriter {
    fn instant(&mut self, time: f64, bodies: &[Kinematic], contacts: &[ContactSample]) {
        for (k, body) in bodies.iter().enumerate() {
            let (x, v) = (body.position, body.velocity);
            let _ =
                writeln!(self.text, "{time:e},body,{k},{:e},{:e},{:e},{:e},{:e},{:e},,", x.x, x.y, x.z, v.x, v.y, v.z);
        }
        for c in contacts {
            let _ = writeln!(self.text, "{time:e},contact,{},,,,,,,{:e},{:e}", c.index, c.penetration, c.force);
        }
        if self.text.len() >= CHUNK && self.file.is_some() {
            self.flush();
        }
    }
}
