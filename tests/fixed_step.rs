//! The peers' fixed-step schemes (`[solver] method = "verlet"` and `"symplectic-euler"`, docs/numerics.md): every
//! expected number from outside the program — an implementation of each scheme written here (the force and the step,
//! a few lines each), the closed forms of Kelvin–Voigt's e, and symplectic Euler's exact one-step map on the
//! undamped linear spring — and the scene's refusals.

mod common;
use common::binary::{Scratch, impact, stderr, stdout};
use impact::fixed_step::{Contact, Scheme};
use impact::law::{ContactLaw, LawKind, Separation};
use impact::report::Report;
use impact::scene::Scene;
use std::f64::consts::PI;
use std::path::Path;

const MASS: f64 = 0.5;
const SPEED: f64 = 1.5;

/// A force F(d, d') written here, N.
type Force<'a> = &'a dyn Fn(f64, f64) -> f64;

/// A sphere of `MASS` at `SPEED` against a wall, with the given `[contact]` and `[solver]` lines.
fn scene_text(contact: &str, solver: &str) -> String {
    format!(
        "[[bodies]]\nradius = 1.0\nmass = {MASS:?}\nvelocity = [{SPEED:?}, 0.0, 0.0]\n\n\
         [[bodies]]\nradius = inf\nmass = inf\nvelocity = [0.0, 0.0, 0.0]\n\n[contact]\n{contact}\n\n[solver]\n{solver}\n"
    )
}

fn run(contact: &str, solver: &str) -> Report {
    let text = scene_text(contact, solver);
    let scene = Scene::parse(&text, Path::new("fixed.toml")).unwrap_or_else(|e| panic!("bad scene: {e}\n{text}"));
    impact::impact::simulate(&scene, impact::history::Recording::Off).expect("simulation").report
}

/// The DEM velocity Verlet, written out: the damping sees v½; the contact ends at the first step whose
/// penetration (or, with `ending`, that function) is not positive while moving apart, after maximum compression.
fn verlet(force: Force, ending: Option<Force>, dt: f64, phase: f64) -> f64 {
    let (mut d, mut v, mut f) = (-phase * dt * SPEED, SPEED, 0.0);
    let mut compressed = false;
    for _ in 0..100_000_000u64 {
        let half = v - 0.5 * dt * f / MASS;
        d += dt * half;
        if compressed && half < 0.0 && (d <= 0.0 || ending.is_some_and(|g| g(d, half) <= 0.0)) {
            return -half / SPEED;
        }
        f = if d > 0.0 { force(d, half) } else { 0.0 };
        v = half - 0.5 * dt * f / MASS;
        compressed |= v <= 0.0;
    }
    panic!("no separation")
}

/// Semi-implicit Euler, written out: v += dt a(d, v); d += dt v.
fn euler(force: Force, ending: Option<Force>, dt: f64, phase: f64) -> f64 {
    let (mut d, mut v) = (-phase * dt * SPEED, SPEED);
    let mut compressed = false;
    for _ in 0..100_000_000u64 {
        let f = if d > 0.0 { force(d, v) } else { 0.0 };
        v -= dt * f / MASS;
        d += dt * v;
        if compressed && v < 0.0 && (d <= 0.0 || ending.is_some_and(|g| g(d, v) <= 0.0)) {
            return -v / SPEED;
        }
        compressed |= v <= 0.0;
    }
    panic!("no separation")
}

/// The relative difference, and a check to `tolerance`.
#[track_caller]
fn assert_same(what: &str, program: f64, here: f64, tolerance: f64) {
    let error = ((program - here) / here).abs();
    assert!(error <= tolerance, "{what}: program {program:.16e}, here {here:.16e}, relative {error:.1e}");
}

/// Kelvin–Voigt (both separations), Hertz and Hunt–Crossley through a scene: the program's e is the e of the scheme
/// written here, to 1e-12, at several steps, for both schemes; and `fixed_step::Contact` (what `impact translate`
/// calls) gives it too, at the touch phase 0 and at other phases.
#[test]
fn both_schemes_give_the_e_of_an_independent_implementation() {
    let (k, c) = (1e4, 25.0);
    let (hertz_k, alpha) = (1e7, 0.3);
    let kelvin = move |d: f64, v: f64| k * d + c * v;
    let hertz = move |d: f64, _v: f64| hertz_k * d * d.sqrt();
    let hunt = move |d: f64, v: f64| hertz_k * d.powf(1.5) * (1.0 + alpha * v);
    let kelvin_ending = kelvin;
    let cases: [(&str, Force, Option<Force>, ContactLaw); 4] = [
        (
            &format!("law = \"kelvin-voigt\"\nstiffness = {k}\ndamping = {c}"),
            &kelvin,
            None,
            law(LawKind::KelvinVoigt, k, 1.0, c),
        ),
        (
            &format!("law = \"kelvin-voigt\"\nstiffness = {k}\ndamping = {c}\nseparation = \"force\""),
            &kelvin,
            Some(&kelvin_ending),
            law(LawKind::KelvinVoigt, k, 1.0, c),
        ),
        (&format!("law = \"hertz\"\nstiffness = {hertz_k}"), &hertz, None, law(LawKind::Hertz, hertz_k, 1.5, 0.0)),
        (
            &format!("law = \"hunt-crossley\"\nstiffness = {hertz_k}\ndamping = {alpha}"),
            &hunt,
            None,
            law(LawKind::HuntCrossley, hertz_k, 1.5, alpha),
        ),
    ];
    for (contact, force, ending, law) in cases {
        let duration = run(contact, "method = \"dop853\"").contact.duration.unwrap();
        let force_separation = ending.is_some();
        let separation = if force_separation { Separation::Force } else { Separation::Penetration };
        let api = Contact { law, mass: MASS, speed: SPEED, separation };
        for steps in [7.0, 40.0, 333.0] {
            let dt = duration / steps;
            // The DEM Verlet is symplectic Euler in the variables (d, v½): the same e (docs/numerics.md).
            let (by_verlet, by_euler) = (verlet(force, ending, dt, 0.0), euler(force, ending, dt, 0.0));
            assert_same(&format!("Verlet and Euler, {contact}"), by_verlet, by_euler, 1e-12);
            for (method, scheme) in [("verlet", Scheme::Verlet), ("symplectic-euler", Scheme::SymplecticEuler)] {
                let here = |phase: f64| match scheme {
                    Scheme::Verlet => verlet(force, ending, dt, phase),
                    Scheme::SymplecticEuler => euler(force, ending, dt, phase),
                    // (Not a scene's method: Drake's SAP step, checked in tests/translate.rs.)
                    Scheme::ImplicitEuler => unreachable!("only the scenes' two schemes are listed"),
                };
                let report = run(contact, &format!("method = \"{method}\"\ndt = {dt:?}"));
                let what = format!("{method}, {contact}, dt = tc/{steps}");
                assert_eq!(report.solver.method, method);
                assert_eq!(report.solver.dt, Some(dt));
                let program = report.contact.restitution_velocity_ratio.expect("separated");
                assert_same(&what, program, here(0.0), 1e-12);
                assert_same(&what, api.restitution(scheme, dt, 0.0).unwrap(), here(0.0), 1e-12);
                for phase in [0.25, 0.5, 0.9] {
                    let what = format!("{what}, phase {phase}");
                    assert_same(&what, api.restitution(scheme, dt, phase).unwrap(), here(phase), 1e-12);
                }
                // The accurate e beside it is the accurate path's own.
                let accurate = run(contact, "method = \"dop853\"").contact.restitution_velocity_ratio.unwrap();
                assert_same(&what, report.solver.restitution_continuous.unwrap(), accurate, 1e-9);
            }
        }
    }
}

fn law(kind: LawKind, stiffness: f64, exponent: f64, damping: f64) -> ContactLaw {
    ContactLaw {
        kind,
        stiffness,
        exponent,
        damping,
        tsuji_scale: 0.0,
        yield_penetration: f64::INFINITY,
        solimp: impact::law::NO_SOLIMP,
        ramp: f64::INFINITY,
    }
}

/// Verlet's e converges at first order to Kelvin–Voigt's closed form e = exp(-zeta pi / sqrt(1 - zeta²))
/// (penetration separation): halving dt halves the error (ratio within [1.7, 2.3]). The steps divide the exact
/// contact duration pi / omega_d, so that the separation falls at the same fraction of a step as dt shrinks: the
/// tensile force c d' that Kelvin–Voigt still has at d = 0 acts for that fraction of the last step, a first-order
/// term of its own that jumps with the fraction (the spread over the touch phase, below).
#[test]
fn verlet_e_converges_at_first_order_to_the_closed_form() {
    let (k, zeta) = (1e4, 0.2);
    let c = 2.0 * zeta * (k * MASS).sqrt();
    let exact = (-zeta * PI / (1.0 - zeta * zeta).sqrt()).exp();
    let period = PI / ((k / MASS) * (1.0 - zeta * zeta)).sqrt();
    let contact = format!("law = \"kelvin-voigt\"\nstiffness = {k}\ndamping = {c}");
    let error = |steps: f64| {
        let report = run(&contact, &format!("method = \"verlet\"\ndt = {:?}", period / steps));
        report.contact.restitution_velocity_ratio.unwrap() - exact
    };
    let errors: Vec<f64> = [100.0, 200.0, 400.0, 800.0, 1600.0].into_iter().map(error).collect();
    for pair in errors.windows(2) {
        let ratio = pair[0] / pair[1];
        assert!((1.7..=2.3).contains(&ratio), "errors {errors:?}: ratio {ratio}");
    }
    // The error is of the size a first-order scheme makes: about zeta * omega dt.
    assert!(errors[0].abs() < 0.1 && errors[0].abs() > 1e-4, "{errors:?}");
}

/// Symplectic Euler on the undamped linear spring (m = k = 1, v0 = 1) is the map d' = d + h v', v' = v - h d, of
/// determinant 1: d_(n+1) = (2 - h²) d_n - d_(n-1), so d_n = h sin(n theta)/sin(theta) with cos(theta) = 1 - h²/2.
/// The contact ends at the first n with d_n <= 0, N = ceil(pi/theta), and e = -v_N = (d_(N-1) - d_N)/h =
/// (sin((N-1) theta) - sin(N theta))/sin(theta): not 1 (it conserves d² + v² - h d v, not the energy), and the
/// program gives it to 1e-13.
#[test]
fn symplectic_euler_on_an_undamped_spring_gives_its_one_step_map() {
    for h in [0.3f64, 0.1, 0.0337, 0.01] {
        let theta = (1.0 - 0.5 * h * h).acos();
        let n = (PI / theta).ceil();
        let expected = (((n - 1.0) * theta).sin() - (n * theta).sin()) / theta.sin();
        // The invariant at the last step gives the same e: v² - h d v + d² = 1 with d = d_N.
        let d = h * (n * theta).sin() / theta.sin();
        let from_invariant = 0.5 * ((4.0 - (4.0 - h * h) * d * d).sqrt() - h * d);
        assert!((expected - from_invariant).abs() < 1e-13, "h = {h}: {expected} {from_invariant}");
        let contact = Contact {
            law: law(LawKind::Hertz, 1.0, 1.0, 0.0),
            mass: 1.0,
            speed: 1.0,
            separation: Separation::Penetration,
        };
        let e = contact.restitution(Scheme::SymplecticEuler, h, 0.0).unwrap();
        assert!((e - expected).abs() < 1e-13, "h = {h}: program {e}, map {expected}");
        assert!((e - 1.0).abs() > 1e-12, "h = {h}: e = {e} is not exactly 1");
    }
}

/// The spread over the touch phase brackets the e at phase 0. Kelvin–Voigt's force jumps by c d' at both edges of
/// the contact, so where the grid meets them moves e by up to the impulse c v0 dt of one step (in m* v0: c dt/m*),
/// a spread that halves with dt; Hertz's force vanishes at the edges, and its spread falls much faster.
#[test]
fn the_spread_over_the_touch_phase_brackets_e_and_narrows_with_the_step() {
    let (k, c) = (1e4, 25.0);
    let linear = Contact {
        law: law(LawKind::KelvinVoigt, k, 1.0, c),
        mass: MASS,
        speed: SPEED,
        separation: Separation::Penetration,
    };
    let hertz = Contact {
        law: law(LawKind::Hertz, 1e7, 1.5, 0.0),
        mass: MASS,
        speed: SPEED,
        separation: Separation::Penetration,
    };
    let period = PI / (k / MASS).sqrt();
    let mut widths = Vec::new();
    for steps in [20.0, 200.0] {
        let dt = period / steps;
        for scheme in [Scheme::Verlet, Scheme::SymplecticEuler] {
            let (low, high) = linear.restitution_spread(scheme, dt, 32).unwrap();
            let e0 = linear.restitution(scheme, dt, 0.0).unwrap();
            assert!(low <= e0 && e0 <= high, "{scheme:?}: {low} {e0} {high}");
            assert!(high - low <= c * dt / MASS, "{scheme:?}: {low} {high}");
            let (low, high) = hertz.restitution_spread(scheme, dt, 32).unwrap();
            assert!(low <= 1.0 + 1e-3 && high >= 1.0 - 1e-3, "{scheme:?}: {low} {high}");
            if scheme == Scheme::Verlet {
                widths.push(high - low);
            }
        }
    }
    assert!(widths[1] < widths[0] / 30.0, "Hertz's spread: {widths:?}");
}

/// The report of a fixed-step run: the accurate e beside the scheme's, the step, the steps taken; the readable report
/// shows "e at dt = ..." with both and their difference; the accurate methods leave `dt` and
/// `restitution_continuous` null.
#[test]
fn the_report_shows_the_scheme_and_the_continuous_e() {
    let contact = "law = \"hunt-crossley\"\nstiffness = 1e7\nrestitution = 0.8";
    let report = run(contact, "method = \"verlet\"\ndt = 1e-5");
    assert_eq!(report.solver.dt, Some(1e-5));
    let duration = report.contact.duration.unwrap();
    assert!((report.solver.steps as f64 - duration / 1e-5).abs() <= 1.0, "{} steps", report.solver.steps);
    assert!(report.notes.iter().any(|note| note.contains("energy balance does not close")), "{:?}", report.notes);
    let accurate = run(contact, "method = \"dop853\"");
    assert_eq!((accurate.solver.dt, accurate.solver.restitution_continuous), (None, None));
    let continuous = accurate.contact.restitution_velocity_ratio.unwrap();
    assert!((report.solver.restitution_continuous.unwrap() - continuous).abs() < 1e-9);
    let text = impact::output::table::render(&report);
    assert!(text.contains("e at dt = 10.0 µs"), "{text}");
    assert!(text.contains(&format!("(continuous: {continuous:.6}, difference")), "{text}");
    let json = impact::output::json::render(&report).unwrap();
    assert!(json.contains("\"restitution_continuous\": 0.83"), "{json}");
}

/// A history of a fixed-step run is the scheme's step boundaries, from the touch to the step that ends the contact,
/// with the forces the scheme computed: its largest is the report's peak force.
#[test]
fn the_history_is_the_schemes_steps() {
    let text =
        scene_text("law = \"hunt-crossley\"\nstiffness = 1e7\nrestitution = 0.8", "method = \"verlet\"\ndt = 1e-4");
    let scene = Scene::parse(&text, Path::new("history.toml")).unwrap();
    let simulation = impact::impact::simulate(&scene, impact::history::Recording::Steps).unwrap();
    let history = simulation.history.expect("a history");
    let report = simulation.report;
    assert_eq!(history.samples.len() as u64, report.solver.steps + 1);
    let largest = history.samples.iter().map(|s| s.force).fold(0.0, f64::max);
    assert_eq!(largest, report.contact.max_force);
    let last = history.samples.last().unwrap();
    assert_eq!((last.time, last.force), (report.contact.duration.unwrap(), 0.0));
}

/// Every law runs through the scheme without a special case (Thornton's yielding law, Tsuji and Brilliantov under
/// a force separation), giving an e near the accurate one at a fine step.
#[test]
fn every_law_runs_generically() {
    let laws = [
        "law = \"tsuji\"\nrestitution = 0.5\nseparation = \"force\"",
        "law = \"brilliantov\"\ndamping = 1e-5\nseparation = \"force\"",
        "law = \"gonthier\"\nrestitution = 0.4",
        "law = \"thornton\"\nyield_pressure = 1e8",
    ];
    for contact in laws {
        let text = format!(
            "[[bodies]]\nradius = 0.01\ndensity = 7800\nvelocity = [2.0, 0.0, 0.0]\nyoung = 2e11\npoisson = 0.3\n\n\
             [[bodies]]\nradius = inf\nmass = inf\nvelocity = [0.0, 0.0, 0.0]\nyoung = 2e11\npoisson = 0.3\n\n\
             [contact]\n{contact}\n\n[solver]\nmethod = \"verlet\"\ndt = 1e-8\n"
        );
        let scene = Scene::parse(&text, Path::new("law.toml")).unwrap();
        let report = impact::impact::simulate(&scene, impact::history::Recording::Off).unwrap().report;
        let e = report.contact.restitution_velocity_ratio.expect("separated");
        let accurate = report.solver.restitution_continuous.unwrap();
        assert!((e - accurate).abs() < 0.01, "{contact}: {e} against {accurate}");
    }
}

/// The refusals, each naming its key and line with exit status 2.
#[test]
fn bad_steps_and_scenes_are_refused_naming_the_key() {
    let scratch = Scratch::new("refusals");
    let contact = "law = \"hunt-crossley\"\nstiffness = 1e7\nrestitution = 0.8";
    let oblique = "[[bodies]]\nradius = 0.01\nmass = 0.01\nvelocity = [1.0, 0.5, 0.0]\nposition = [0.0, 0.0, 0.0]\n\
                   young = 2e11\npoisson = 0.3\n\n[[bodies]]\nradius = 0.01\nmass = 0.01\nvelocity = [0.0, 0.0, 0.0]\n\
                   position = [0.05, 0.005, 0.0]\nyoung = 2e11\npoisson = 0.3\n\n[contact]\nlaw = \"hertz\"\n\n\
                   [solver]\nmethod = \"verlet\"\ndt = 1e-7\n";
    let cases: [(&str, String, &str, &str); 7] = [
        ("missing", scene_text(contact, "method = \"verlet\""), "solver.dt", "give its time step"),
        ("negative", scene_text(contact, "method = \"verlet\"\ndt = -1e-6"), "solver.dt", "> 0"),
        ("zero", scene_text(contact, "method = \"symplectic-euler\"\ndt = 0.0"), "solver.dt", "> 0"),
        ("infinite", scene_text(contact, "method = \"verlet\"\ndt = inf"), "solver.dt", "finite"),
        ("dop853", scene_text(contact, "method = \"dop853\"\ndt = 1e-6"), "solver.dt", "chooses its own steps"),
        (
            "long",
            scene_text(contact, "method = \"verlet\"\ndt = 1.0"),
            "solver.dt",
            "larger than the contact's duration",
        ),
        ("oblique", oblique.to_string(), "solver.method", "3-D model"),
    ];
    for (name, text, key, words) in cases {
        let path = scratch.scene(&format!("{name}.toml"), &text);
        let output = impact(scratch.path(), &["run", &path]);
        let message = stderr(&output);
        assert_eq!(output.status.code(), Some(2), "{name}: {message}{}", stdout(&output));
        assert!(message.contains(&format!("key `{key}`")) && message.contains("line "), "{name}: {message}");
        assert!(message.contains(words), "{name}: {message}");
    }
}

/// `solver.dt` is a sweep key: e against the step, each row the scheme's.
#[test]
fn a_sweep_varies_the_step() {
    let scratch = Scratch::new("sweep");
    let text = scene_text("law = \"kelvin-voigt\"\nstiffness = 1e4\ndamping = 25.0", "method = \"verlet\"\ndt = 1e-4");
    let path = scratch.scene("kv.toml", &text);
    let output = impact(scratch.path(), &["sweep", &path, "--vary", "solver.dt=1e-5:1e-3:3:log", "--out", "dt.csv"]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let csv = scratch.read("dt.csv");
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let column = header.iter().position(|name| *name == "restitution_velocity_ratio").unwrap();
    let e: Vec<f64> = csv.lines().skip(1).map(|row| row.split(',').nth(column).unwrap().parse().unwrap()).collect();
    assert_eq!(e.len(), 3, "{csv}");
    // Larger steps move e further from the accurate one (first order).
    let accurate = run("law = \"kelvin-voigt\"\nstiffness = 1e4\ndamping = 25.0", "method = \"dop853\"")
        .contact
        .restitution_velocity_ratio
        .unwrap();
    assert!((e[0] - accurate).abs() < (e[2] - accurate).abs(), "{e:?} against {accurate}");
}
