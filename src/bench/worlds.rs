//! World runs in the work–precision study (`impact bench --worlds`, docs/world.md#cost): a Hertzian chain of equal
//! steel beads struck at one end, run until its pulse has crossed and the last bead left, the 5-ball cradle of
//! `models/newtons-cradle-5.toml`, the rod of `models/rod-chatter.toml` through 45 end strikes, and the settling pile
//! of `models/settling-pile.toml`, each at a sweep of tolerances. The error of a run is the largest difference of any
//! body's final velocity (and of the speed a rigid body's spin gives its farthest contact point) from a run of the same
//! scene at [`REFERENCE_TOLERANCE`], over the largest initial speed — except for the pile, a chaotic system whose
//! runs part ways within a few dozen contacts whatever their tolerance: its error is the energy balance's residual
//! over the energy supplied, what its report states ([`Measure`]);
//! the time is the run alone (the report's `solver.wall_time_s`), the median of up to 5 runs on one thread. The reference is the program's
//! own tight run: the test suite holds chains of 40 and 60 beads to an independent RK4 integration, and the 1000-bead
//! chain agrees with LAMMPS at its finest step to LAMMPS's own rounding (3e-8, docs/world.md#cost).

use crate::scene::{Parsed, WorldScene};
use crate::setup::parse_any;
use std::path::Path;

/// The tolerance (rtol = atol) of the reference runs.
pub const REFERENCE_TOLERANCE: f64 = 1e-13;

/// The tolerances of the full study, and of `--quick`.
pub const TOLERANCES: [f64; 5] = [1e-6, 1e-7, 1e-8, 1e-9, 1e-10];
pub const QUICK_TOLERANCES: [f64; 3] = [1e-6, 1e-8, 1e-10];

/// Beads of the chain in the full study, and in `--quick`.
pub const BEADS: usize = 1000;
pub const QUICK_BEADS: usize = 100;

/// A world scene of the study: its name and its text without `[solver]`.
#[derive(Debug, Clone)]
pub struct WorldCase {
    pub name: String,
    pub text: String,
    /// What its error measures.
    pub measure: Measure,
}

/// What a case's error measures.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Measure {
    /// The largest difference of a body's final velocity (or of the speed its spin gives its farthest contact point)
    /// from the run at [`REFERENCE_TOLERANCE`], over the largest initial speed.
    AgainstReference,
    /// The energy balance's residual (`energy.balance`) over the energy supplied (the kinetic energy at the start,
    /// gravity's work and the walls' work, in size): a chaotic scene's runs at two
    /// tolerances end in different states, so a reference run says nothing of a run's error; its own books do. Each
    /// tolerance is run once (a run is many seconds), and no reference run is made.
    EnergyBalance,
}

/// One run of the study.
#[derive(Debug, Clone)]
pub struct WorldRow {
    pub case: String,
    pub tolerance: f64,
    /// Largest difference of a body's final velocity (or of the speed its spin gives its farthest contact point)
    /// from the reference run, over the largest initial speed.
    pub error: f64,
    /// The run alone, s.
    pub seconds: f64,
    pub steps: u64,
    pub contacts: usize,
}

/// The two-ball contact time of the chain's beads at `speed` (s): `C (m*² / (K² v0))^(1/5)` for `F = K d^(3/2)`,
/// `C = 2 (5/4)^(2/5) sqrt(pi) Gamma(7/5) / Gamma(9/10) = 3.2180654597`.
fn bead_contact_time(radius: f64, density: f64, young: f64, poisson: f64, speed: f64) -> f64 {
    let mass = density * 4.0 / 3.0 * std::f64::consts::PI * radius.powi(3);
    let reduced = mass / 2.0;
    let stiffness = 4.0 / 3.0 * young / (2.0 * (1.0 - poisson * poisson)) * (radius / 2.0).sqrt();
    3.218_065_459_7 * (reduced * reduced / (stiffness * stiffness * speed)).powf(0.2)
}

/// A chain of `beads` steel beads (radius 5 mm, touching, the first at 1 m/s into the rest), run for the pulse's
/// transit and 10 contact times more: 0.488 contact times per bead (measured on a 300-bead chain), in whole contact
/// times (498 for 1000 beads, 14.98 ms).
pub fn chain(beads: usize) -> WorldCase {
    let (radius, density, young, poisson, speed) = (0.005, 7850.0, 2.1e11, 0.3, 1.0);
    let tau = bead_contact_time(radius, density, young, poisson, speed);
    let end = (0.488 * (beads.max(1) - 1) as f64 + 10.0).ceil() * tau;
    let mut text = format!(
        "title = \"Hertzian chain of {beads} steel beads struck at one end\"\n\n[world]\nend_time = {end:e}\n\
         max_contacts = 10000000\n\n"
    );
    for k in 0..beads {
        let v = if k == 0 { speed } else { 0.0 };
        text += &format!(
            "[[bodies]]\nradius = {radius}\ndensity = {density}\nyoung = {young:e}\npoisson = {poisson}\n\
             position = [{:?}, 0.0, 0.0]\nvelocity = [{v:?}, 0.0, 0.0]\n\n",
            2.0 * radius * k as f64
        );
    }
    text += "[contact]\nlaw = \"hertz\"\n";
    WorldCase { name: format!("chain-{beads}"), text, measure: Measure::AgainstReference }
}

/// The 5-ball cradle of `models/newtons-cradle-5.toml`.
pub fn cradle() -> WorldCase {
    WorldCase {
        name: "cradle-5".into(),
        text: include_str!("../../models/newtons-cradle-5.toml").to_string(),
        measure: Measure::AgainstReference,
    }
}

/// The rod of `models/rod-chatter.toml` (dropped at 30 degrees on a floor) through its chatter: 45 end strikes in
/// its first 2.2 s, while it still bounces (it comes to rest after 83, at 2.28 s).
pub fn rod_chatter() -> WorldCase {
    let text = include_str!("../../models/rod-chatter.toml")
        .replace("max_contacts = 6", "max_contacts = 1000\nend_time = 2.2");
    WorldCase { name: "rod-chatter".into(), text, measure: Measure::AgainstReference }
}

/// The 20 balls of `models/settling-pile.toml` dropped into a box, for `end_time` seconds of scene time (its 2 s
/// in the full study; the first `end_time` of it in `--quick`, while the balls still bounce).
pub fn settling_pile(end_time: f64) -> WorldCase {
    let text =
        include_str!("../../models/settling-pile.toml").replace("end_time = 2.0", &format!("end_time = {end_time:?}"));
    WorldCase { name: "settling-pile".into(), text, measure: Measure::EnergyBalance }
}

/// Scene time of the settling pile in `--quick`, s: its balls' first bounces and collisions.
pub const QUICK_PILE_TIME: f64 = 0.3;

/// The cases of the study (`quick`: a chain of [`QUICK_BEADS`], the pile's first [`QUICK_PILE_TIME`]).
pub fn cases(quick: bool) -> Vec<WorldCase> {
    let pile = settling_pile(if quick { QUICK_PILE_TIME } else { 2.0 });
    vec![chain(if quick { QUICK_BEADS } else { BEADS }), cradle(), rod_chatter(), pile]
}

/// The scene of `case` at `tolerance`.
fn scene(case: &WorldCase, tolerance: f64) -> Result<WorldScene, String> {
    let text = format!("{}\n[solver]\nrtol = {tolerance:e}\natol = {tolerance:e}\n", case.text);
    match parse_any(&text, Path::new(&format!("{}.toml", case.name))) {
        Ok(Parsed::World(scene)) => Ok(*scene),
        Ok(Parsed::Impact(_)) => Err(format!("{}: not a world scene", case.name)),
        Err(error) => Err(format!("{}: {error}", case.name)),
    }
}

/// What one run of a case gave.
struct Ran {
    /// The energy balance's residual over the energy supplied (the kinetic energy at the start, gravity's work and
    /// the walls' work, in size).
    balance: f64,
    /// Every body's final velocity, m/s.
    velocities: Vec<[f64; 3]>,
    /// Every body's final angular velocity, rad/s.
    spins: Vec<[f64; 3]>,
    /// The run alone, s.
    seconds: f64,
    steps: u64,
    contacts: usize,
}

fn run(case: &WorldCase, tolerance: f64) -> Result<Ran, String> {
    let scene = scene(case, tolerance)?;
    let report = crate::world_run::simulate(&scene).map_err(|error| format!("{}: {error}", case.name))?.report;
    let energy = &report.energy;
    Ok(Ran {
        balance: {
            let supplied = energy.kinetic_before + energy.gravity_work.abs() + energy.work_of_immovable_bodies.abs();
            if supplied > 0.0 { (energy.balance / supplied).abs() } else { energy.balance.abs() }
        },
        velocities: report.bodies.iter().map(|b| b.velocity_after).collect(),
        spins: report.bodies.iter().map(|b| b.angular_velocity_after).collect(),
        seconds: report.solver.wall_time_s,
        steps: report.solver.steps,
        contacts: report.contacts.len(),
    })
}

/// Runs the study: each case at [`REFERENCE_TOLERANCE`], then at each of `tolerances`; `progress` sees each row.
pub fn study(
    cases: &[WorldCase],
    tolerances: &[f64],
    mut progress: impl FnMut(&WorldRow),
) -> Result<Vec<WorldRow>, String> {
    let mut rows = Vec::new();
    for case in cases {
        if case.measure == Measure::EnergyBalance {
            for &tolerance in tolerances {
                let ran = run(case, tolerance)?;
                let row = WorldRow {
                    case: case.name.clone(),
                    tolerance,
                    error: ran.balance,
                    seconds: ran.seconds,
                    steps: ran.steps,
                    contacts: ran.contacts,
                };
                progress(&row);
                rows.push(row);
            }
            continue;
        }
        let scene = scene(case, REFERENCE_TOLERANCE)?;
        let speed = scene.bodies.iter().map(|b| b.velocity.norm()).fold(0.0, f64::max);
        // A rigid body's spin counts by the speed it gives its farthest contact point (its bounding radius).
        let reach: Vec<f64> = scene.bodies.iter().map(|b| if b.is_rigid() { b.radius } else { 0.0 }).collect();
        let reference = run(case, REFERENCE_TOLERANCE)?;
        for &tolerance in tolerances {
            // The median time of up to 5 runs (as many as fit in about 2 s): one run is at the mercy of the machine.
            let Ran { velocities, spins, seconds: first, steps, contacts, .. } = run(case, tolerance)?;
            let mut times = vec![first];
            while times.len() < 5 && times.iter().sum::<f64>() < 2.0 {
                times.push(run(case, tolerance)?.seconds);
            }
            times.sort_by(f64::total_cmp);
            let seconds = times[times.len() / 2];
            let distance = |a: &[f64; 3], b: &[f64; 3]| (0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>().sqrt();
            let error = (0..velocities.len())
                .map(|i| {
                    let turning = distance(&spins[i], &reference.spins[i]) * reach[i];
                    distance(&velocities[i], &reference.velocities[i]).max(turning)
                })
                .fold(0.0, f64::max)
                / speed;
            let row = WorldRow { case: case.name.clone(), tolerance, error, seconds, steps, contacts };
            progress(&row);
            rows.push(row);
        }
    }
    Ok(rows)
}

/// The rows as CSV: `case, tolerance, error, seconds, steps, contacts`.
pub fn csv(rows: &[WorldRow]) -> String {
    let mut text = String::from("case,tolerance,error,seconds,steps,contacts\n");
    for r in rows {
        text += &format!("{},{:e},{:e},{:e},{},{}\n", r.case, r.tolerance, r.error, r.seconds, r.steps, r.contacts);
    }
    text
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The contact time's constant from its definition: 2 (5/4)^(2/5) times the integral of (1 - u^(5/2))^(-1/2) over
    /// (0, 1), by the substitution u = 1 - s² (which removes the end singularity) and Simpson's rule.
    #[test]
    fn the_bead_contact_time_constant_is_the_hertz_integral() {
        let n = 20_000;
        let f = |s: f64| {
            let u: f64 = 1.0 - s * s;
            let rest = 1.0 - u.powf(2.5);
            if rest <= 0.0 { 2.0 / 2.5f64.sqrt() } else { 2.0 * s / rest.sqrt() }
        };
        let h = 1.0 / n as f64;
        let mut sum = f(0.0) + f(1.0);
        for k in 1..n {
            sum += f(k as f64 * h) * if k % 2 == 1 { 4.0 } else { 2.0 };
        }
        let integral = sum * h / 3.0;
        let constant = 2.0 * 1.25f64.powf(0.4) * integral;
        assert!((constant - 3.218_065_459_7).abs() < 1e-8, "{constant}");
        // The chain's default end: 498 contact times for 1000 beads.
        let tau = bead_contact_time(0.005, 7850.0, 2.1e11, 0.3, 1.0);
        assert!((tau - 3.008_205_689e-5).abs() < 1e-12, "{tau}");
    }
}
