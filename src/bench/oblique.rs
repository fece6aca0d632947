//! Frictional oblique impacts in the work–precision study (`impact bench --oblique`, docs/numerics.md#oblique-impacts):
//! Chung & Ooi's test 4 (an alumina sphere on a rigid wall, Tsuji's law, mu = 0.092) at 45° (it slides throughout),
//! at 10° (its slip comes to rest and the Mindlin spring takes over) and at 30° with a spin about two axes, and two
//! free steel spheres with and without spin (Hunt–Crossley, mu = 0.3, the line of centres turning), each on the
//! path `auto` takes and on the 3-D model in physical time at a sweep of tolerances, beside the same contact without
//! friction (for the wall on the normal fast path) — what a frictional impact's cost is measured against.
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
    /// For two spheres, the same bodies meeting head-on at the same normal approach speed, without spin or
    /// friction: the normal contact on the normal fast path, which the goal measures a frictional impact
    /// against (a wall case's frictionless twin is that already).
    pub central: Option<String>,
}

/// Chung & Ooi's test 4 at `degrees` from the normal (3.9 m/s; e = 0.98 by Tsuji's exact map), `friction` mu.
fn test4(degrees: f64, friction: f64) -> String {
    spinning_test4(degrees, friction, [0.0; 3])
}

/// Test 4 with the sphere spinning at `spin` (rad/s) before the impact.
fn spinning_test4(degrees: f64, friction: f64, spin: [f64; 3]) -> String {
    let (sin, cos) = degrees.to_radians().sin_cos();
    let [a, b, c] = spin;
    format!(
        "[[bodies]]\nradius = 0.0025\ndensity = 4000\nvelocity = [{}, 0.0, {}]\nangular_velocity = [{a:?}, {b:?}, {c:?}]\n\
         young = 3.8e11\npoisson = 0.23\n\n\
         [[bodies]]\nradius = inf\nmass = inf\nvelocity = [0.0, 0.0, 0.0]\nyoung = inf\n\n\
         [contact]\nlaw = \"tsuji\"\nrestitution = 0.98\nfriction = {friction}\nnormal = [0.0, 0.0, -1.0]\n",
        3.9 * sin,
        -3.9 * cos
    )
}

/// Test 4's sphere under Hunt–Crossley with e = 0.8 at `degrees` from the normal, `friction` mu: with
/// `friction = 0.1` at 60° it slides on the limit from first contact (Hunt–Crossley's force grows as fast as the
/// Mindlin spring), the closed form without a first stick.
fn hunt_crossley_wall(degrees: f64, friction: f64) -> String {
    test4(degrees, friction)
        .replace("law = \"tsuji\"\nrestitution = 0.98", "law = \"hunt-crossley\"\nrestitution = 0.8")
}

/// Two free steel spheres (10 and 15 mm) meeting at 30° with spins about two axes, Hunt–Crossley with e = 0.8,
/// `friction` mu.
fn spinning_spheres(friction: f64) -> String {
    spheres(friction, [[0.0, 20.0, 60.0], [15.0, 0.0, -30.0]])
}

/// The same two spheres with the spins `spins` (rad/s).
fn spheres(friction: f64, spins: [[f64; 3]; 2]) -> String {
    spheres_moving(friction, spins, [[1.0, 0.5, 0.1], [-0.5, 0.0, 0.0]])
}

/// The two spheres with the spins `spins` (rad/s) and the velocities `velocities` (m/s; the normal is x).
fn spheres_moving(friction: f64, spins: [[f64; 3]; 2], velocities: [[f64; 3]; 2]) -> String {
    let ([a, b, c], [d, e, f]) = (spins[0], spins[1]);
    let ([u, v, w], [x, y, z]) = (velocities[0], velocities[1]);
    format!(
        "[[bodies]]\nradius = 0.01\ndensity = 7850\nvelocity = [{u:?}, {v:?}, {w:?}]\nangular_velocity = [{a:?}, {b:?}, {c:?}]\n\
         young = 2.1e11\npoisson = 0.3\n\n\
         [[bodies]]\nradius = 0.015\ndensity = 7850\nvelocity = [{x:?}, {y:?}, {z:?}]\nangular_velocity = [{d:?}, {e:?}, {f:?}]\n\
         young = 2.1e11\npoisson = 0.3\n\n\
         [contact]\nlaw = \"hunt-crossley\"\nrestitution = 0.8\nfriction = {friction}\nnormal = [1.0, 0.0, 0.0]\n"
    )
}

/// The spin of test 4's spinning case (rad/s): backspin about the axis across the plane of incidence and a drilling
/// spin about the normal (the sphere's rim at about 1.25 and 0.5 m/s, beside the 1.95 m/s tangential approach).
const SPIN: [f64; 3] = [0.0, -500.0, 200.0];

/// The cases of the study, each with its frictionless twin's text.
pub fn cases() -> Vec<(ObliqueCase, String)> {
    let wall = |name, text| ObliqueCase { name, text, central: None };
    let central = || Some(spheres_moving(0.0, [[0.0; 3]; 2], [[1.0, 0.0, 0.0], [-0.5, 0.0, 0.0]]));
    let pair = |name, text| ObliqueCase { name, text, central: central() };
    vec![
        (wall("chung-ooi test 4 at 45 deg (sliding)", test4(45.0, 0.092)), test4(45.0, 0.0)),
        (wall("chung-ooi test 4 at 10 deg (sticking)", test4(10.0, 0.092)), test4(10.0, 0.0)),
        (
            wall("chung-ooi test 4 at 30 deg with spin", spinning_test4(30.0, 0.092, SPIN)),
            spinning_test4(30.0, 0.0, SPIN),
        ),
        (wall("hunt-crossley wall at 60 deg (sliding)", hunt_crossley_wall(60.0, 0.1)), hunt_crossley_wall(60.0, 0.0)),
        (pair("two free spheres with spin (mu 0.3)", spinning_spheres(0.3)), spinning_spheres(0.0)),
        (pair("two free spheres without spin (mu 0.3)", spheres(0.3, [[0.0; 3]; 2])), spheres(0.0, [[0.0; 3]; 2])),
    ]
}

/// One run of the study.
#[derive(Debug, Clone)]
pub struct ObliqueRow {
    pub case: &'static str,
    /// `auto` (the path `[solver] method = "auto"` takes with friction: a sphere on a wall that slides to its end in
    /// closed form over the normal fast path, otherwise by the slide by Taylor series; two spheres on the 3-D model),
    /// `dop853` (the 3-D model in physical time, as `method = "dop853"` forces it), for a sphere on a wall
    /// `taylor-slide` (the slide by Taylor series, as `method = "taylor"` asks for it) and `dop853-slide` (the slide
    /// by Dop853, as `method = "dop853-slide"` asks for it),
    /// `frictionless` (the same contact without friction, on the path `auto` takes: the normal fast path for the
    /// wall, the 3-D model for the turning spheres) or, for two spheres, `central` (their head-on twin on the
    /// normal fast path, [`ObliqueCase::central`]).
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
        let mut paths = vec![("auto", &case.text, "auto"), ("dop853", &case.text, "dop853")];
        if case.central.is_none() {
            // (A sphere on a wall: the slides by Taylor series and by Dop853, asked for by name.)
            paths.push(("taylor-slide", &case.text, "taylor"));
            paths.push(("dop853-slide", &case.text, "dop853-slide"));
        }
        paths.push(("frictionless", frictionless, "auto"));
        if let Some(central) = &case.central {
            paths.push(("central", central, "auto"));
        }
        for (path, text, method) in paths {
            // (The reference is the 3-D model in physical time at 1e-13: the path every other is held to.)
            let (scene, setup) = prepared(text, REFERENCE_TOLERANCE, "dop853")?;
            let reference = crate::impact::outcome(&scene, &setup).map_err(|e| format!("{}: {e}", case.name))?;
            let exact = after(&scene, &reference.end);
            for &tolerance in tolerances {
                let (scene, setup) = prepared(text, tolerance, method)?;
                let out = crate::impact::outcome(&scene, &setup).map_err(|e| format!("{}: {e}", case.name))?;
                let got = after(&scene, &out.end);
                let error =
                    got.iter().zip(&exact).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max) / setup.approach_speed;
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

/// The summary: each case's rows side by side, the ratio of each frictional run's time to its frictionless twin's
/// at the same tolerance, and to the normal fast path's (the wall's frictionless twin, the spheres' central one).
pub fn table(rows: &[ObliqueRow]) -> String {
    let mut text = format!(
        "{:<40} {:<12} {:<18} {:>9} {:>9} {:>11} {:>7} {:>8} {:>10}\n",
        "case", "path", "method", "tolerance", "error", "µs/impact", "steps", "vs twin", "vs normal"
    );
    let find = |r: &ObliqueRow, path: &str| {
        rows.iter().find(|t| t.case == r.case && t.path == path && t.tolerance == r.tolerance).map(|t| t.seconds)
    };
    for r in rows {
        let frictional = matches!(r.path, "auto" | "dop853" | "taylor-slide" | "dop853-slide");
        let ratio = |twin: Option<f64>| match twin {
            // (One decimal below 10: a closed-form slide costs little more than its twin.)
            Some(seconds) if frictional && r.seconds < 10.0 * seconds => format!("{:.1}x", r.seconds / seconds),
            Some(seconds) if frictional => format!("{:.0}x", r.seconds / seconds),
            _ => String::new(),
        };
        let normal = find(r, "central").or_else(|| find(r, "frictionless").filter(|_| !r.case.starts_with("two free")));
        text.push_str(&format!(
            "{:<40} {:<12} {:<18} {:>9.0e} {:>9.1e} {:>11.2} {:>7} {:>8} {:>10}\n",
            r.case,
            r.path,
            r.method,
            r.tolerance,
            r.error,
            r.seconds * 1e6,
            r.steps,
            ratio(find(r, "frictionless")),
            ratio(normal)
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
            if let Some(central) = &case.central {
                let (scene, central_setup) = prepared(central, 1e-10, "auto").unwrap();
                assert_eq!(central_setup.motion, crate::setup::Motion::Normal, "{}", case.name);
                assert!(
                    central_setup.friction.is_none() && scene.bodies.iter().all(|b| b.angular_velocity.norm() == 0.0)
                );
                // The same normal approach speed as the oblique case.
                let (_, oblique) = prepared(&case.text, 1e-10, "auto").unwrap();
                assert!((central_setup.approach_speed - oblique.approach_speed).abs() < 1e-15, "{}", case.name);
            }
            let (scene, twin_setup) = prepared(&twin, 1e-10, "auto").unwrap();
            assert!(twin_setup.friction.is_none(), "{}", case.name);
            if case.central.is_none() {
                assert!(case.text.contains(if case.name.starts_with("chung-ooi") { "tsuji" } else { "hunt-crossley" }));
                assert_eq!(twin_setup.motion, crate::setup::Motion::Normal, "{}", case.name);
                let v = scene.bodies[0].velocity;
                let degrees = (v.x.hypot(v.y) / -v.z).atan().to_degrees();
                assert!(case.name.contains(&format!("at {} deg", degrees.round())), "{}: {degrees}", case.name);
                assert!((v.norm() - 3.9).abs() < 1e-12);
            }
            let spinning = scene.bodies.iter().any(|b| b.angular_velocity.norm() > 0.0);
            assert_eq!(spinning, case.name.contains("with spin"), "{}", case.name);
        }
    }
}
