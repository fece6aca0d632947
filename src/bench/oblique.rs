//! Frictional oblique impacts in the work–precision study (`impact bench --oblique`, docs/numerics.md#oblique-impacts):
//! Chung & Ooi's test 4 (an alumina sphere on a rigid wall, Tsuji's law, mu = 0.092) at 45° (it slides throughout)
//! and at 10° (its slip comes to rest and the Mindlin spring takes over), and two free steel spheres with spin
//! (Hunt–Crossley, mu = 0.3, the line of centres turning), each on the general path (the only one that covers
//! friction) at a sweep of tolerances, beside the same contact without friction on the normal fast path — what the
//! issue's goal measures a frictional impact against.
//!
//! The error of a run is the largest difference, from a run of the same scene at [`REFERENCE_TOLERANCE`], of the
//! bodies' velocities and of their spins times their radii after the impact, over the approach speed; the time is
//! the impact's outcome alone (`impact::outcome`, as the single-impact study times the general path), the median
//! over batches on one thread.

use super::{Timing, median_seconds};
use crate::dynamics::Snapshot;
use crate::scene::Scene;
use crate::setup::Setup;
use std::path::Path;

/// The tolerance (rtol; atol a hundredth of it, at least 1e-14, the least a scene takes) of the reference runs.
pub const REFERENCE_TOLERANCE: f64 = 1e-13;

/// The tolerances of the full study, and of `--quick`.
pub const TOLERANCES: [f64; 5] = [1e-6, 1e-8, 1e-9, 1e-10, 1e-11];
pub const QUICK_TOLERANCES: [f64; 2] = [1e-6, 1e-10];

/// An oblique case: its name (no comma: it is a CSV cell) and its scene text without `[solver]`.
#[derive(Debug, Clone)]
pub struct ObliqueCase {
    pub name: &'static str,
    pub text: String,
}

/// Chung & Ooi's test 4 at `degrees` from the normal (3.9 m/s; e = 0.98 by Tsuji's exact map), `friction` mu.
fn test4(degrees: f64, friction: f64) -> String {
    let (sin, cos) = degrees.to_radians().sin_cos();
    format!(
        "[[bodies]]\nradius = 0.0025\ndensity = 4000\nvelocity = [{}, 0.0, {}]\nyoung = 3.8e11\npoisson = 0.23\n\n\
         [[bodies]]\nradius = inf\nmass = inf\nvelocity = [0.0, 0.0, 0.0]\nyoung = inf\n\n\
         [contact]\nlaw = \"tsuji\"\nrestitution = 0.98\nfriction = {friction}\nnormal = [0.0, 0.0, -1.0]\n",
        3.9 * sin,
        -3.9 * cos
    )
}

/// Two free steel spheres (10 and 15 mm) meeting at 30° with spins about two axes, Hunt–Crossley with e = 0.8,
/// `friction` mu.
fn spinning_spheres(friction: f64) -> String {
    format!(
        "[[bodies]]\nradius = 0.01\ndensity = 7850\nvelocity = [1.0, 0.5, 0.1]\nangular_velocity = [0.0, 20.0, 60.0]\n\
         young = 2.1e11\npoisson = 0.3\n\n\
         [[bodies]]\nradius = 0.015\ndensity = 7850\nvelocity = [-0.5, 0.0, 0.0]\nangular_velocity = [15.0, 0.0, -30.0]\n\
         young = 2.1e11\npoisson = 0.3\n\n\
         [contact]\nlaw = \"hunt-crossley\"\nrestitution = 0.8\nfriction = {friction}\nnormal = [1.0, 0.0, 0.0]\n"
    )
}

/// The cases of the study, each with its frictionless twin's text.
pub fn cases() -> Vec<(ObliqueCase, String)> {
    vec![
        (ObliqueCase { name: "chung-ooi test 4 at 45 deg (sliding)", text: test4(45.0, 0.092) }, test4(45.0, 0.0)),
        (ObliqueCase { name: "chung-ooi test 4 at 10 deg (sticking)", text: test4(10.0, 0.092) }, test4(10.0, 0.0)),
        (ObliqueCase { name: "two free spheres with spin (mu 0.3)", text: spinning_spheres(0.3) }, spinning_spheres(0.0)),
    ]
}

/// One run of the study.
#[derive(Debug, Clone)]
pub struct ObliqueRow {
    pub case: &'static str,
    /// `auto` (the path `[solver] method = "auto"` takes with friction: a sphere on a wall in regularised time,
    /// two spheres on the 3-D model), `dop853` (the 3-D model in physical time, as `method = "dop853"` forces it) or
    /// `frictionless` (the same contact without friction, on the path `auto` takes: the normal fast path for the
    /// wall, the 3-D model for the turning spheres).
    pub path: &'static str,
    pub method: &'static str,
    pub tolerance: f64,
    /// Largest difference of a velocity or a spin times its radius after the impact from the reference run, over the
    /// approach speed.
    pub error: f64,
    /// Median time of one impact's outcome, s.
    pub seconds: f64,
    pub steps: u64,
    pub evaluations: u64,
}

/// A scene of the study at `tolerance` (its `[solver] method` `method`), read and resolved.
fn prepared(text: &str, tolerance: f64, method: &str) -> Result<(Scene, Setup), String> {
    let atol = (tolerance / 100.0).max(1e-14);
    let text = format!("{text}\n[solver]\nrtol = {tolerance:e}\natol = {atol:e}\nmethod = \"{method}\"\n");
    let scene = Scene::parse(&text, Path::new("oblique.toml")).map_err(|e| e.to_string())?;
    let setup = Setup::new(&scene).map_err(|e| format!("{}: {}", e.key, e.message))?;
    Ok((scene, setup))
}

/// The velocities and the spins times the radii after the impact (m/s), and the approach speed.
fn after(scene: &Scene, end: &Snapshot) -> Vec<f64> {
    let mut values = Vec::with_capacity(12);
    for i in 0..2 {
        values.extend(end.velocities[i].iter());
        let radius = scene.bodies[i].radius;
        let arm = if radius.is_finite() { radius } else { 0.0 };
        values.extend(end.spins[i].iter().map(|w| w * arm));
    }
    values
}

/// Runs every case at every tolerance, with and without friction; `done` is called after each row.
pub fn study(
    cases: &[(ObliqueCase, String)],
    tolerances: &[f64],
    timing: Timing,
    mut done: impl FnMut(&ObliqueRow),
) -> Result<Vec<ObliqueRow>, String> {
    let mut rows = Vec::new();
    for (case, frictionless) in cases {
        for (path, text, method) in
            [("auto", &case.text, "auto"), ("dop853", &case.text, "dop853"), ("frictionless", frictionless, "auto")]
        {
            // (The reference is the 3-D model in physical time at 1e-13: the path every other is held to.)
            let (scene, setup) = prepared(text, REFERENCE_TOLERANCE, "dop853")?;
            let reference = crate::impact::outcome(&scene, &setup).map_err(|e| format!("{}: {e}", case.name))?;
            let exact = after(&scene, &reference.end);
            for &tolerance in tolerances {
                let (scene, setup) = prepared(text, tolerance, method)?;
                let out = crate::impact::outcome(&scene, &setup).map_err(|e| format!("{}: {e}", case.name))?;
                let got = after(&scene, &out.end);
                let error = got.iter().zip(&exact).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max)
                    / setup.approach_speed;
                let (seconds, _) = median_seconds(|| crate::impact::outcome(&scene, &setup).ok(), timing);
                let row = ObliqueRow {
                    case: case.name,
                    path,
                    method: out.method,
                    tolerance,
                    error,
                    seconds,
                    steps: out.counters.steps,
                    evaluations: out.counters.evaluations,
                };
                done(&row);
                rows.push(row);
            }
        }
    }
    Ok(rows)
}

/// The study's CSV: one line per row.
pub fn csv(rows: &[ObliqueRow]) -> String {
    let mut text = String::from("case,path,method,tolerance,error,seconds_per_impact,steps,force_evaluations\n");
    for r in rows {
        text.push_str(&format!(
            "{},{},{},{:e},{:e},{:e},{},{}\n",
            r.case, r.path, r.method, r.tolerance, r.error, r.seconds, r.steps, r.evaluations
        ));
    }
    text
}

/// The summary: each case's rows side by side, and the ratio of each frictional run's time to its frictionless
/// twin's at the same tolerance.
pub fn table(rows: &[ObliqueRow]) -> String {
    let mut text = format!(
        "{:<40} {:<12} {:<14} {:>9} {:>9} {:>11} {:>7} {:>9}\n",
        "case", "path", "method", "tolerance", "error", "µs/impact", "steps", "vs twin"
    );
    for r in rows {
        let twin = rows.iter().find(|t| t.case == r.case && t.path == "frictionless" && t.tolerance == r.tolerance);
        let ratio = match twin {
            Some(t) if r.path != "frictionless" => format!("{:.0}x", r.seconds / t.seconds),
            _ => String::new(),
        };
        text.push_str(&format!(
            "{:<40} {:<12} {:<14} {:>9.0e} {:>9.1e} {:>11.2} {:>7} {:>9}\n",
            r.case,
            r.path,
            r.method,
            r.tolerance,
            r.error,
            r.seconds * 1e6,
            r.steps,
            ratio
        ));
    }
    text
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each case is what it says: the wall cases run the 3-D model with friction and their twins the normal fast
    /// path; test 4's incidence is its angle (tan = tangential over normal speed); the spheres spin and turn.
    #[test]
    fn the_cases_are_what_they_say() {
        for (case, twin) in cases() {
            let (_, setup) = prepared(&case.text, 1e-10, "auto").unwrap();
            assert_eq!(setup.motion, crate::setup::Motion::Full, "{}", case.name);
            assert!(setup.friction.is_some(), "{}", case.name);
            let (scene, twin_setup) = prepared(&twin, 1e-10, "auto").unwrap();
            assert!(twin_setup.friction.is_none(), "{}", case.name);
            if case.name.starts_with("chung-ooi") {
                assert_eq!(twin_setup.motion, crate::setup::Motion::Normal, "{}", case.name);
                let v = scene.bodies[0].velocity;
                let degrees = (v.x.hypot(v.y) / -v.z).atan().to_degrees();
                assert!(case.name.contains(&format!("at {} deg", degrees.round())), "{}: {degrees}", case.name);
                assert!((v.norm() - 3.9).abs() < 1e-12);
            } else {
                assert!(scene.bodies.iter().all(|b| b.angular_velocity.norm() > 0.0));
            }
        }
    }
}
