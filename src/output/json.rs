//! The JSON report of docs/report.md.

use crate::report::Report;

/// The report as pretty JSON with a final newline.
pub fn render(report: &Report) -> serde_json::Result<String> {
    Ok(serde_json::to_string_pretty(report)? + "\n")
}

/// The report of a world run as pretty JSON with a final newline.
pub fn render_world(report: &crate::report::world::WorldReport) -> serde_json::Result<String> {
    Ok(serde_json::to_string_pretty(report)? + "\n")
}
