//! The contact history as CSV: one row per recorded instant, every column named with its unit.

use crate::history::History;
use std::fmt::Write;

/// Column names, in order.
pub const COLUMNS: [&str; 14] = [
    "time_s",
    "phase",
    "penetration_m",
    "penetration_rate_m_s",
    "force_N",
    "impulse_N_s",
    "v1_normal_m_s",
    "v2_normal_m_s",
    "v1_tangential_x_m_s",
    "v1_tangential_y_m_s",
    "v1_tangential_z_m_s",
    "v2_tangential_x_m_s",
    "v2_tangential_y_m_s",
    "v2_tangential_z_m_s",
];

/// The history as CSV text (header line, then one line per sample; numbers in shortest round-trip form).
pub fn render(history: &History) -> String {
    let mut text = COLUMNS.join(",") + "\n";
    let n = history.normal;
    for sample in &history.samples {
        let [v1, v2] = sample.velocities;
        let (v1n, v2n) = (v1.dot(&n), v2.dot(&n));
        let (t1, t2) = (v1 - n * v1n, v2 - n * v2n);
        let _ = write!(
            text,
            "{:e},{},{:e},{:e},{:e},{:e},{:e},{:e}",
            sample.time,
            sample.phase.name(),
            sample.penetration,
            sample.rate,
            sample.force,
            sample.impulse,
            v1n,
            v2n
        );
        for value in t1.iter().chain(t2.iter()) {
            let _ = write!(text, ",{value:e}");
        }
        text.push('\n');
    }
    text
}
