//! A world's limits and budgets (issue 33, items 2 and 3; docs/world.md#limits, #budgets, #progress): a world applies
//! one impact's rules to every pair that can touch, at the speed in play, before any work; no world run is unbounded;
//! a run its budget stops says so and exits 1 with its outputs complete; a long run shows its progress on a terminal
//! and nothing elsewhere. (The hostile scenes of the issue are in `hostile_corpus.rs`: each exits 2 naming its key and
//! line.) Thresholds come from Hertz's closed form, not from the program.

mod common;

use common::binary::{Scratch, impact};
use impact::scene::{Parsed, WorldScene};
use impact::world::record::EndReason;
use std::path::Path;
use std::time::{Duration, Instant};

const STEEL: f64 = 2.1e11;
const POISSON: f64 = 0.3;

/// A sphere of `radius` (m) and `mass` (kg) at `position` with `velocity`, Young's modulus `young`.
fn sphere(radius: f64, mass: f64, position: [f64; 3], velocity: [f64; 3], young: f64) -> String {
    format!(
        "[[bodies]]\nradius = {radius:?}\nmass = {mass:?}\nposition = {position:?}\nvelocity = {velocity:?}\n\
         young = {young:e}\npoisson = {POISSON:?}\n\n"
    )
}

/// A floor through the origin, face up, of Young's modulus `young`.
fn floor(young: f64) -> String {
    format!(
        "[[bodies]]\nradius = inf\nmass = inf\nposition = [0.0, 0.0, 0.0]\nnormal = [0.0, 0.0, 1.0]\n\
         velocity = [0.0, 0.0, 0.0]\nyoung = {young:e}\npoisson = {POISSON:?}\n\n"
    )
}

/// The scene read with every rule (what `impact run` reads), or the key its error names.
fn read(text: &str) -> Result<WorldScene, String> {
    match impact::setup::parse_any(text, Path::new("limits.toml")) {
        Ok(Parsed::World(scene)) => Ok(*scene),
        Ok(Parsed::Impact(_)) => panic!("not a world scene:\n{text}"),
        Err(error) => Err(format!("{}: {}", error.key.unwrap_or_default(), error.message)),
    }
}

/// Hertz's stiffness K = (4/3) E* sqrt(R*) of two bodies of modulus `young` (Poisson's ratio 0.3), effective radius
/// `radius` (Johnson, Contact Mechanics, ch. 4).
fn hertz_stiffness(young: f64, radius: f64) -> f64 {
    let modulus = young / (2.0 * (1.0 - POISSON * POISSON));
    4.0 / 3.0 * modulus * radius.sqrt()
}

/// The approach speed at which an elastic Hertz contact of effective mass `mass` and stiffness `stiffness` presses
/// as deep as `depth`: from the energy balance m* u²/2 = (2/5) K d^(5/2), u² = 4 K d^(5/2) / (5 m*).
fn speed_for_depth(mass: f64, stiffness: f64, depth: f64) -> f64 {
    (4.0 * stiffness * depth.powf(2.5) / (5.0 * mass)).sqrt()
}

#[test]
fn a_pair_faster_than_its_hertz_contact_can_hold_is_refused_before_any_work() {
    // Two equal steel balls, one struck at u: the contact is refused where its elastic penetration would reach the
    // radius — one impact's rule — at u* from Hertz's energy balance (R* = r/2, m* = m/2): about 2.3 km/s.
    let (radius, mass) = (0.01, 0.0329);
    let critical = speed_for_depth(mass / 2.0, hertz_stiffness(STEEL, radius / 2.0), radius);
    let scene = |speed: f64| {
        format!(
            "[world]\nend_time = 1.0\n\n{}{}[contact]\nlaw = \"hertz\"\n",
            sphere(radius, mass, [0.0, 0.0, 0.0], [speed, 0.0, 0.0], STEEL),
            sphere(radius, mass, [0.03, 0.0, 0.0], [0.0, 0.0, 0.0], STEEL)
        )
    };
    assert!(read(&scene(0.99 * critical)).is_ok(), "{:?}", read(&scene(0.99 * critical)).err());
    let refused = read(&scene(1.01 * critical)).expect_err("beyond the critical speed");
    assert!(refused.starts_with("bodies.0.young:") && refused.contains("too soft"), "{refused}");
    assert!(refused.contains("speed in play"), "the message says at which speed: {refused}");
    // The third body of a world makes no difference to the pair's rule: the speed in play is still the pair's.
    let third = format!("{}{}", scene(1.01 * critical), sphere(radius, mass, [1.0, 0.0, 0.0], [0.0; 3], STEEL));
    assert!(read(&third).is_err());
}

#[test]
fn a_pair_is_checked_no_faster_than_the_energy_in_play_could_move_it() {
    // A ball of negligible mass M at V = 1e150 m/s strikes the first of two touching 33 g steel balls. The speed in
    // play is V, but the energy in play, E = M V²/2, can give the other pair's relative motion at most
    // sqrt(2 E / m*) (m* = m/2): the scene is refused only where that reaches the speed at which Hertz's penetration
    // reaches the radius, E* = m* u*²/2 — and then by both pairs at once, since the light ball's own contact, at V,
    // presses as deep (5 (2E) / (4 K))^(2/5) with the same K.
    let (radius, mass, speed) = (0.01, 0.0329, 1e150);
    let critical = mass / 2.0 * speed_for_depth(mass / 2.0, hertz_stiffness(STEEL, radius / 2.0), radius).powi(2) / 2.0;
    let scene = |energy: f64| {
        format!(
            "[world]\n\n{}{}{}[contact]\nlaw = \"hertz\"\n",
            sphere(radius, 2.0 * energy / (speed * speed), [0.0; 3], [speed, 0.0, 0.0], STEEL),
            sphere(radius, mass, [0.02, 0.0, 0.0], [0.0; 3], STEEL),
            sphere(radius, mass, [0.04, 0.0, 0.0], [0.0; 3], STEEL)
        )
    };
    // (Checked at the speed in play, 1e150 m/s, the two 33 g balls' contact would be refused at any energy.)
    assert!(read(&scene(0.98 * critical)).is_ok(), "{:?}", read(&scene(0.98 * critical)).err());
    let refused = read(&scene(1.02 * critical)).expect_err("beyond the critical energy");
    assert!(refused.contains("too soft"), "{refused}");
}

#[test]
fn the_speed_in_play_counts_a_fall_through_the_scene_s_height() {
    // A ball at rest above a floor: its contact's speed in play is the fall from its centre's height h to the floor,
    // u = sqrt(2 g h). The contact is refused beyond the h at which Hertz's penetration at u reaches the radius:
    // h* = u*² / (2 g) with u* from the energy balance (R* = r for a sphere on a flat, m* = m).
    let (radius, mass, young, g) = (0.01, 0.0329, 1e9, 9.81);
    let critical = speed_for_depth(mass, hertz_stiffness(young, radius), radius).powi(2) / (2.0 * g);
    let scene = |height: f64| {
        format!(
            "[world]\ngravity = [0.0, 0.0, {}]\n\n{}{}[contact]\nlaw = \"hertz\"\n",
            -g,
            sphere(radius, mass, [0.0, 0.0, height], [0.0; 3], young),
            floor(young)
        )
    };
    assert!(critical > 10.0 * radius, "a height well above the ball: {critical} m");
    assert!(read(&scene(0.98 * critical)).is_ok(), "{:?}", read(&scene(0.98 * critical)).err());
    let refused = read(&scene(1.02 * critical)).expect_err("dropped from beyond the critical height");
    assert!(refused.contains("too soft") && refused.contains("fall through the scene's height"), "{refused}");
}

#[test]
fn a_contact_lost_in_the_rounding_of_its_positions_is_refused() {
    // A ball of radius 1e-100 m struck at 1 m/s into a 10 mm one 20 mm away: its Hertzian penetration, about
    // (5 m* u² / (4 K))^(2/5) with m* and K of the tiny ball, is some 1e-103 m, far below the 64 ulps of the other
    // ball's coordinates (about 4e-16 m). One impact measures it from first contact; a world cannot.
    let tiny: f64 = 1e-100;
    let mass = 7850.0 * 4.0 / 3.0 * std::f64::consts::PI * tiny.powi(3);
    let depth = (5.0 * mass / (4.0 * hertz_stiffness(STEEL, tiny))).powf(0.4);
    assert!(depth < 1e-100 && depth > 0.0, "{depth:e}");
    let text = format!(
        "[world]\n\n{}{}[contact]\nlaw = \"hertz\"\n",
        sphere(tiny, mass, [0.0, 0.0, 0.0], [1.0, 0.0, 0.0], STEEL),
        sphere(0.01, 0.0329, [0.02, 0.0, 0.0], [0.0; 3], STEEL)
    );
    let refused = read(&text).expect_err("a contact below the rounding");
    assert!(refused.starts_with("bodies.0.radius:") && refused.contains("rounding of their positions"), "{refused}");
    // The same two balls near the origin, 1e-100 m apart, are resolved: a world of tiny things is no problem.
    let near = format!(
        "[world]\n\n{}{}[contact]\nlaw = \"hertz\"\n",
        sphere(tiny, mass, [0.0, 0.0, 0.0], [1.0, 0.0, 0.0], STEEL),
        sphere(tiny, mass, [3e-100, 0.0, 0.0], [0.0; 3], STEEL)
    );
    let scene = read(&near).expect("tiny balls near the origin");
    let report = impact::world_run::simulate(&scene).expect("runs").report;
    assert_eq!(report.contacts.len(), 1);
    // Equal balls, elastic: they exchange their velocities (to the integration's accuracy).
    assert!((report.bodies[1].velocity_after[0] - 1.0).abs() < 1e-6, "{:?}", report.bodies[1].velocity_after);
}

#[test]
fn sums_and_flights_outside_double_precision_are_refused() {
    // Each of three balls carries 0.5 * 1e300 kg * (1.5e4 m/s)² = 1.1e308 J, finite; together 3.4e308 J, which is not.
    let heavy = |x: f64, v: f64| sphere(0.01, 1e300, [x, 0.0, 0.0], [v, 0.0, 0.0], STEEL);
    let text = format!(
        "[world]\n\n{}{}{}[contact]\nlaw = \"hertz\"\n",
        heavy(0.0, 1.5e4),
        heavy(0.1, -1.5e4),
        heavy(0.2, 1.5e4)
    );
    assert!(0.5 * 1e300 * 1.5e4f64.powi(2) < f64::MAX && 3.0 * 0.5 * 1e300 * 1.5e4f64.powi(2) > f64::MAX);
    let refused = read(&text).expect_err("a kinetic energy beyond double precision");
    assert!(refused.contains("summed over its bodies"), "{refused}");
    // A fall of g T²/2 over end_time = 1e200 s under 9.81 m/s² is 5e400 m.
    let text = format!(
        "[world]\ngravity = [0.0, 0.0, -9.81]\nend_time = 1e200\n\n{}{}[contact]\nlaw = \"hertz\"\n",
        sphere(0.01, 0.0329, [0.0, 0.0, 0.1], [0.0; 3], STEEL),
        floor(STEEL)
    );
    let refused = read(&text).expect_err("a flight beyond double precision");
    assert!(refused.starts_with("world.end_time:"), "{refused}");
    // Nothing movable: nothing can happen, as one impact of two immovable bodies.
    let text = format!(
        "[world]\n\n{}{}[contact]\nlaw = \"hertz\"\n",
        sphere(0.01, f64::INFINITY, [0.0; 3], [0.0; 3], STEEL),
        sphere(0.01, f64::INFINITY, [0.1, 0.0, 0.0], [-1.0, 0.0, 0.0], STEEL)
    );
    let refused = read(&text).expect_err("every body immovable");
    assert!(refused.starts_with("bodies.1.mass:"), "{refused}");
}

/// Runs `scene` through the world's driver alone — without the rules that would refuse it — on a thread, and gives
/// its outcome, failing if it takes more than `seconds`.
fn driver_alone(text: &str, seconds: u64) -> impact::world::record::WorldOutcome {
    driver_result(text, seconds).expect("the run ends with an outcome")
}

/// [`driver_alone`]'s outcome, or the error the driver ended with.
fn driver_result(
    text: &str,
    seconds: u64,
) -> Result<impact::world::record::WorldOutcome, impact::world::driver::WorldError> {
    let read = impact::scene::read_any(text, Path::new("driver.toml")).expect("the scene's form and values");
    let Parsed::World(scene) = read.scene else { panic!("a world scene") };
    let (send, receive) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let _ = send.send(impact::world::driver::run(&scene));
    });
    receive
        .recv_timeout(Duration::from_secs(seconds))
        .unwrap_or_else(|_| panic!("the driver ran for more than {seconds} s"))
}

#[test]
fn the_driver_ends_even_what_the_rules_refuse() {
    // The rules refuse these before any work; behind them, the driver itself never runs without end. Before the
    // issue, the first segment of the cradle's tiny ball left the clock where it was (its time unit, 1e-103 s, below
    // the rounding of t = 10 ms) and began again for ever; the stack's ball at 1e300 m/s met an outside pair whose
    // touch began no contact, and segments of zero length followed one another for more than 5 minutes.
    let models = concat!(env!("CARGO_MANIFEST_DIR"), "/models/");
    let cradle = std::fs::read_to_string(format!("{models}newtons-cradle-5.toml")).unwrap();
    let tiny = cradle.replacen("radius = 0.01", "radius = 1e-100", 1);
    // Its ball (1e-300 kg) either never sees its touch and stops on the clock's rounding, or begins a contact whose
    // scales leave double precision and says so: either way the run ends, and says why.
    match driver_result(&tiny, 60) {
        Ok(outcome) => {
            assert_eq!(outcome.end_reason, EndReason::StepBudget);
            let notes = &outcome.notes;
            assert!(notes.iter().any(|n| n.contains("below the rounding of the scene's clock")), "{notes:?}");
        }
        Err(error) => assert!(error.to_string().contains("leave double precision"), "{error}"),
    }
    let stack = std::fs::read_to_string(format!("{models}ball-stack.toml")).unwrap();
    let at = stack.rfind("velocity = [0.0, 0.0, 0.0]").unwrap();
    let fast = format!("{}velocity = [0.0, 1e300, 0.0]{}", &stack[..at], &stack[at + 26..]);
    driver_alone(&fast, 60);
}

#[test]
fn a_world_that_spends_its_budget_stops_with_a_note_exits_1_and_keeps_its_outputs_whole() {
    let scratch = Scratch::new("budget");
    let stack = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/models/ball-stack.toml")).unwrap();
    let budget = 50;
    let scene = scratch.write("stack.toml", &stack.replace("max_contacts = 2", &format!("max_steps = {budget}")));
    let clock = Instant::now();
    let output = impact(scratch.path(), &["run", &scene, "--json", "--csv", "series.csv", "--plot", "figures"]);
    assert!(clock.elapsed() < Duration::from_secs(20), "{:?}", clock.elapsed());
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("stack.toml") && stderr.contains("step_budget"), "{stderr}");
    let report: serde_json::Value = serde_json::from_slice(&output.stdout).expect("the whole JSON report");
    assert_eq!(report["world"]["end_reason"], "step_budget");
    let steps = report["solver"]["steps"].as_u64().unwrap() + report["solver"]["rejected_steps"].as_u64().unwrap();
    // (An event's location re-steps within one accepted step, with at least a thousand steps of its own.)
    assert!(steps <= budget + 1000, "{steps} steps");
    let notes = report["notes"].as_array().unwrap();
    assert!(notes.iter().any(|n| n.as_str().unwrap().contains(&format!("budget of {budget} steps"))), "{notes:?}");
    // The series is complete up to where the run stopped: every line whole, the last at the report's end time.
    let series = scratch.read("series.csv");
    assert!(series.ends_with('\n'));
    let columns = series.lines().next().unwrap().split(',').count();
    assert!(series.lines().all(|line| line.split(',').count() == columns));
    let last: f64 = series.lines().last().unwrap().split(',').next().unwrap().parse().unwrap();
    assert_eq!(last, report["world"]["end_time"].as_f64().unwrap());
    assert!(scratch.exists("figures"), "the figures are written: {:?}", scratch.files());
    assert!(!scratch.files().iter().any(|f| f.starts_with('.')), "no temporary left: {:?}", scratch.files());
}

#[test]
fn a_world_sweep_row_its_budget_stops_says_so() {
    // The stack falls and strikes the floor under gravity, which takes more than 40 steps; without gravity nothing
    // moves and the run ends at once. One row is stopped by its budget, the other is not.
    let scratch = Scratch::new("sweep_budget");
    let stack = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/models/ball-stack.toml")).unwrap();
    let scene = scratch.write("stack.toml", &stack.replace("max_contacts = 2", "max_contacts = 2\nmax_steps = 40"));
    let output = impact(scratch.path(), &["sweep", &scene, "--vary", "world.gravity.2=-9.81,0", "--out", "rows.csv"]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(0), "{stderr}");
    let rows = scratch.read("rows.csv");
    let lines: Vec<&str> = rows.lines().collect();
    assert!(lines[1].starts_with("0,step budget,-9.81,"), "{rows}");
    assert!(lines[1].contains(",step_budget,"), "the cells are the report's: {rows}");
    assert!(lines[2].starts_with("1,ok,0,"), "{rows}");
    assert!(stderr.contains("1 ok, 1 stopped by their step budget, 0 errors"), "{stderr}");
}

/// A ball resting on a floor through a Kelvin–Voigt contact so heavily damped (zeta = 500) that its creep takes an
/// explicit integrator hundreds of thousands of steps: a run of about a second that its budget stops.
fn creeping_ball(budget: u64) -> String {
    format!(
        "[world]\ngravity = [0.0, 0.0, -9.81]\nend_time = 1.0\nmax_steps = {budget}\n\n\
         [[bodies]]\nradius = 0.01\nmass = 0.01\nposition = [0.0, 0.0, 0.02]\nvelocity = [0.0, 0.0, 0.0]\n\n\
         [[bodies]]\nradius = inf\nmass = inf\nposition = [0.0, 0.0, 0.0]\nnormal = [0.0, 0.0, 1.0]\n\
         velocity = [0.0, 0.0, 0.0]\n\n[contact]\nlaw = \"kelvin-voigt\"\nstiffness = 1e6\ndamping = 1e5\n"
    )
}

#[test]
fn a_long_world_run_prints_no_progress_where_stderr_is_not_a_terminal() {
    let scratch = Scratch::new("no_progress");
    let scene = scratch.write("creep.toml", &creeping_ball(300_000));
    let clock = Instant::now();
    let output = impact(scratch.path(), &["run", &scene]);
    // (Long enough for a progress line to have been drawn a few times, had it been drawn.)
    assert!(clock.elapsed() > Duration::from_millis(500), "a run of {:?} shows nothing anyway", clock.elapsed());
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert_eq!(stderr.lines().count(), 1, "only the budget's message: {stderr:?}");
    assert!(stderr.starts_with("impact: ") && !stderr.contains('\r') && !stderr.contains("steps,"), "{stderr:?}");
}

#[test]
fn on_a_terminal_a_long_world_run_shows_its_progress() {
    // `script` (util-linux) runs the command on a pseudo-terminal; without it there is no terminal to test on.
    let Ok(probe) = std::process::Command::new("script").arg("--version").output() else {
        eprintln!("skipped: no `script` to run the command on a terminal");
        return;
    };
    assert!(probe.status.success());
    let scratch = Scratch::new("progress");
    let scene = scratch.write("creep.toml", &creeping_ball(300_000));
    let command = format!("{} run {scene}", env!("CARGO_BIN_EXE_impact"));
    let output = std::process::Command::new("script")
        .args(["-qec", &command, "/dev/null"])
        .current_dir(scratch.path())
        .output()
        .expect("script runs");
    let shown = String::from_utf8_lossy(&output.stdout);
    assert!(
        shown.contains("of 1 s, 0 contacts,") && shown.contains(" steps,"),
        "{}",
        shown.chars().take(2000).collect::<String>()
    );
    // The report follows the cleared line, and the budget's message.
    assert!(shown.contains("step_budget"));
}
