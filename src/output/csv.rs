//! The contact history as CSV: one row per recorded instant, every column named with its unit.

use crate::history::History;
use std::fmt::Write;

/// Column names, in order. Normal and tangential parts are taken along each instant's own normal (it turns with
/// the line of centres of two spheres); the tangential force acts on body 1; `sliding` is 1 while a frictional
/// contact slides at the Coulomb limit, 0 while it sticks (and for a smooth contact).
pub const COLUMNS: [&str; 30] = [
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
    "normal_x",
    "normal_y",
    "normal_z",
    "tangential_force_x_N",
    "tangential_force_y_N",
    "tangential_force_z_N",
    "slip_x_m_s",
    "slip_y_m_s",
    "slip_z_m_s",
    "w1_x_rad_s",
    "w1_y_rad_s",
    "w1_z_rad_s",
    "w2_x_rad_s",
    "w2_y_rad_s",
    "w2_z_rad_s",
    "sliding",
];

/// The history as CSV text (header line, then one line per sample; numbers in shortest round-trip form).
pub fn render(history: &History) -> String {
    let mut text = COLUMNS.join(",") + "\n";
    for sample in &history.samples {
        let n = sample.normal;
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
        let vectors = [t1, t2, n, sample.tangential_force, sample.slip, sample.spins[0], sample.spins[1]];
        for value in vectors.iter().flat_map(|v| v.iter()) {
            let _ = write!(text, ",{value:e}");
        }
        let _ = writeln!(text, ",{}", u8::from(sample.sliding));
    }
    text
}
