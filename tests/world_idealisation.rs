//! The verdicts on the idealisation in a world (docs/idealisation.md#in-a-world): every expected number is a hand
//! calculation written here — Hertz's contact time in closed form, the flight 2 v / g between bounces, gravity's
//! impulse m g t_c, the exact Hunt–Crossley e(x), the published cradle (Herrmann & Schmälzle).

mod common;

use common::binary::{Scratch, impact};
use common::hunt_crossley_e;
use impact::idealisation::Judgement;
use impact::report::world::WorldReport;
use impact::scene::{Parsed, WorldScene};
use impact::setup::parse_any;
use std::path::Path;

const G: f64 = 9.81;
const MASS: f64 = 0.0329;
const RADIUS: f64 = 0.01;
const YOUNG: f64 = 2.1e11;
const POISSON: f64 = 0.3;

fn world(text: &str) -> WorldScene {
    match parse_any(text, Path::new("world.toml")).unwrap_or_else(|e| panic!("{e}\n{text}")) {
        Parsed::World(world) => *world,
        Parsed::Impact(_) => panic!("not a world scene:\n{text}"),
    }
}

fn run(text: &str) -> WorldReport {
    impact::world_run::simulate(&world(text)).unwrap_or_else(|e| panic!("{e}\n{text}")).report
}

fn relative(value: f64, expected: f64) -> f64 {
    ((value - expected) / expected).abs()
}

fn sphere(name: &str, position: [f64; 3], velocity: [f64; 3]) -> String {
    format!(
        "[[bodies]]\nname = \"{name}\"\nradius = {RADIUS:?}\nmass = {MASS:?}\nposition = {position:?}\n\
         velocity = {velocity:?}\nyoung = {YOUNG:e}\npoisson = {POISSON}\n\n"
    )
}

const FLOOR: &str = "[[bodies]]\nname = \"floor\"\nradius = inf\nmass = inf\nposition = [0.0, 0.0, 0.0]\n\
                     normal = [0.0, 0.0, 1.0]\nvelocity = [0.0, 0.0, 0.0]\nyoung = 2.1e11\npoisson = 0.3\n\n";

/// The ball dropped from rest with its lowest point `h` above the floor, under g = 9.81 m/s² along -z.
fn dropped(h: f64, contact: &str, world: &str) -> String {
    format!(
        "[world]\ngravity = [0.0, 0.0, -9.81]\n{world}\n\n{}{FLOOR}[contact]\n{contact}\n",
        sphere("ball", [0.0, 0.0, RADIUS + h], [0.0; 3])
    )
}

/// Hertz's contact time for F = K d^(3/2), effective mass `m` and approach speed `v`: the deepest penetration
/// d_max = (5 m v² / (4 K))^(2/5) from the energy, and t_c = 2 (d_max / v) ∫0^1 dx / sqrt(1 - x^(5/2)) — the integral
/// by Simpson's rule after x = 1 - u² (which removes the end's singularity).
fn hertz_contact_time(m: f64, k: f64, v: f64) -> f64 {
    let d_max = (5.0 * m * v * v / (4.0 * k)).powf(0.4);
    let f = |u: f64| {
        if u == 0.0 { 2.0 / 2.5f64.sqrt() } else { 2.0 * u / (1.0 - (1.0 - u * u).powf(2.5)).sqrt() }
    };
    let n = 20_000;
    let h = 1.0 / n as f64;
    let integral = (0..=n)
        .map(|i| {
            let weight = if i == 0 || i == n {
                1.0
            } else if i % 2 == 1 {
                4.0
            } else {
                2.0
            };
            weight * f(i as f64 * h)
        })
        .sum::<f64>()
        * h
        / 3.0;
    2.0 * integral * d_max / v
}

/// K = (4/3) E* sqrt(R*), E* = E / (2 (1 - nu²)) for two bodies of the same material.
fn stiffness(effective_radius: f64) -> f64 {
    4.0 / 3.0 * YOUNG / (2.0 * (1.0 - POISSON * POISSON)) * effective_radius.sqrt()
}

/// An elastic Hertz ball dropped from h = 0.1 m bounces back at v0 = sqrt(2 g h) every time: each contact lasts
/// Hertz's t_c (m* = m on a floor, R* = R) against a flight of 2 v0 / g to the next, and gravity adds m g t_c to a
/// contact impulse of 2 m v0. The last contact has no next one: its measure is the one-impact travel v0 t_c against
/// R. Every bounce is at the same speed, so no pair has two speeds to give `constant_e`: null.
#[test]
fn a_bouncing_balls_contact_time_is_measured_against_its_flight() {
    let report = run(&dropped(0.1, "law = \"hertz\"", "max_contacts = 3"));
    assert_eq!(report.contacts.len(), 3);
    let v0 = (2.0 * G * 0.1f64).sqrt();
    let t_c = hertz_contact_time(MASS, stiffness(RADIUS), v0);
    let flight = 2.0 * v0 / G;
    for c in &report.contacts[..2] {
        let verdict = c.idealisation.instantaneous.as_ref().unwrap();
        assert_eq!(verdict.measure, "t_c / flight to the next contact");
        assert!(relative(verdict.compared_with, flight) < 1e-6, "{verdict:?} against {flight}");
        assert!(relative(verdict.ratio, t_c / flight) < 2e-3, "{verdict:?} against {}", t_c / flight);
        assert_eq!(verdict.verdict, Judgement::Holds);
        let isolated = c.idealisation.isolated.as_ref().unwrap();
        let expected = G * t_c / (2.0 * v0);
        assert!(relative(isolated.ratio, expected) < 2e-3, "{isolated:?} against {expected}");
        assert!(isolated.meaning.contains("gravity along the normal"), "{}", isolated.meaning);
        assert!(c.idealisation.constant_e.is_none() && c.idealisation.elastic.is_none());
    }
    let last = report.contacts[2].idealisation.instantaneous.as_ref().unwrap();
    assert_eq!(last.measure, "relative travel / radius");
    assert!(relative(last.value, v0 * t_c) < 2e-3, "{last:?} against {}", v0 * t_c);
    // The summary: the worst contact per assumption (the last one's travel, 0.9 % of R, exceeds 3e-4).
    let worst = report.idealisation.instantaneous.as_ref().unwrap();
    assert_eq!((worst.contact, worst.failing), (2, 0));
    assert!(relative(worst.verdict.ratio, v0 * t_c / RADIUS) < 2e-3);
    assert!(report.idealisation.constant_e.is_none() && report.idealisation.elastic.is_none());
}

/// With Hunt–Crossley's damping parameter alpha kept (0.2 s/m), each bounce's e is the exact e(alpha v) at its own
/// approach speed, and the next approach is the rebound: v1 = e(alpha v0) v0, v2 = e(alpha v1) v1. constant_e is
/// the slope d ln e / d ln v between the pair's contacts — one-sided for the first and the last, central for the
/// middle one — and Hunt–Crossley's e falls with speed: it fails (|slope| ≥ 0.1).
#[test]
fn hunt_crossleys_e_falls_with_the_speed_of_successive_bounces() {
    let alpha = 0.2;
    let report = run(&dropped(0.1, &format!("law = \"hunt-crossley\"\ndamping = {alpha}"), "max_contacts = 3"));
    assert_eq!(report.contacts.len(), 3);
    let mut v = vec![(2.0 * G * 0.1f64).sqrt()];
    let mut e = vec![];
    for k in 0..3 {
        e.push(hunt_crossley_e(alpha * v[k]));
        v.push(e[k] * v[k]);
    }
    let slope = |a: usize, b: usize| (e[b] / e[a]).ln() / (v[b] / v[a]).ln();
    for (k, expected) in [slope(0, 1), slope(0, 2), slope(1, 2)].into_iter().enumerate() {
        let verdict = report.contacts[k].idealisation.constant_e.as_ref().unwrap();
        assert!((verdict.value - expected).abs() < 3e-3, "contact {k}: {verdict:?} against {expected}");
        assert!(expected.abs() >= 0.1 && verdict.verdict == Judgement::Fails, "{verdict:?}");
        assert!(!verdict.meaning.contains("mapped at each contact"), "{}", verdict.meaning);
    }
    let worst = report.idealisation.constant_e.as_ref().unwrap();
    assert_eq!(worst.failing, 3);
}

/// A spring–dashpot's e does not depend on the speed (it is a function of the damping ratio alone): with its damping
/// mapped once, at the first contact (`damping_map = "first-contact"`), the bounces at falling speeds keep e, and the
/// slope between them is zero but for gravity during the contact, g / (omega v) < 1e-3 here — it holds.
#[test]
fn a_spring_dashpots_e_is_the_same_at_every_bounce() {
    let contact = "law = \"kelvin-voigt\"\nstiffness = 1e7\nexponent = 1.0\nrestitution = 0.8";
    let report = run(&dropped(0.1, contact, "max_contacts = 4\ndamping_map = \"first-contact\""));
    let omega = (1e7 / MASS).sqrt();
    let slowest = (2.0 * G * 0.1f64).sqrt() * 0.8f64.powi(3);
    assert!(G / (omega * slowest) < 1e-3);
    for c in &report.contacts {
        let verdict = c.idealisation.constant_e.as_ref().unwrap();
        assert!(verdict.value.abs() < 1e-2, "{verdict:?}");
        assert_eq!(verdict.verdict, Judgement::Holds);
    }
}

/// Newton's cradle of three touching balls: the two contacts overlap in time, and each acts on the middle ball while
/// the other does. The second contact begins as the middle ball starts to move, within the first's whole duration:
/// the first gives all its impulse during it, m (1 + 0.0710) v0 (ball 1 leaves at -0.0710 v0), against the second's
/// m 0.9945 v0 (ball 3 leaves at 0.9945 v0; Herrmann & Schmälzle, Am. J. Phys. 49, 761 (1981)) — a ratio of 1.077.
/// The first contact sees at most the second's whole impulse, 0.9945 / 1.0710 of its own. Both fail `isolated`.
/// Gaps of 1 mm separate the contacts in time: nothing else acts, and `isolated` holds at 0.
#[test]
fn a_cradles_simultaneous_contacts_are_not_isolated() {
    let cradle = |gap: f64| {
        let mut text = String::new();
        for k in 0..3 {
            let v = if k == 0 { 1.0 } else { 0.0 };
            text += &sphere(&format!("ball {k}"), [k as f64 * (2.0 * RADIUS + gap), 0.0, 0.0], [v, 0.0, 0.0]);
        }
        text + "[contact]\nlaw = \"hertz\"\n"
    };
    let report = run(&cradle(0.0));
    assert_eq!(report.contacts.len(), 2);
    let second = report.contacts[1].idealisation.isolated.as_ref().unwrap();
    assert!((second.ratio - 1.0710 / 0.9945).abs() < 2e-3, "{second:?}");
    assert!(second.meaning.contains("during the overlap"), "{}", second.meaning);
    let first = report.contacts[0].idealisation.isolated.as_ref().unwrap();
    assert!(first.ratio > 0.1 && first.ratio <= 0.9945 / 1.0710 + 1e-3, "{first:?}");
    for verdict in [first, second] {
        assert_eq!(verdict.verdict, Judgement::Fails);
    }
    let worst = report.idealisation.isolated.as_ref().unwrap();
    assert_eq!((worst.contact, worst.failing, worst.verdict.verdict), (1, 2, Judgement::Fails));

    let apart = run(&cradle(1e-3));
    for c in &apart.contacts {
        let isolated = c.idealisation.isolated.as_ref().unwrap();
        assert_eq!((isolated.value, isolated.verdict), (0.0, Judgement::Holds), "{isolated:?}");
    }
}

/// Two equal balls closing at 1 m/s without gravity run as one impact (docs/world.md#two-bodies), and the world
/// report carries that contact's verdicts: Hertz's contact time with m* = m/2, R* = R/2 gives the relative travel
/// 1 m/s × t_c against R; nothing else acts (no gravity, no other contact): isolated 0; and the impact's trial at
/// 0.9 and 1.1 times the speed gives elastic Hertz's slope, 0.
#[test]
fn a_two_body_world_without_gravity_carries_the_impacts_verdicts() {
    let text = format!(
        "[world]\nmax_contacts = 2\n\n{}{}[contact]\nlaw = \"hertz\"\n",
        sphere("a", [0.0, 0.0, 0.0], [0.5, 0.0, 0.0]),
        sphere("b", [0.05, 0.0, 0.0], [-0.5, 0.0, 0.0])
    );
    let report = run(&text);
    assert_eq!(report.contacts.len(), 1);
    let verdicts = &report.contacts[0].idealisation;
    let t_c = hertz_contact_time(MASS / 2.0, stiffness(RADIUS / 2.0), 1.0);
    let travel = verdicts.instantaneous.as_ref().unwrap();
    assert!(relative(travel.value, t_c) < 1e-3, "{travel:?} against {t_c}");
    assert_eq!(verdicts.isolated.as_ref().unwrap().value, 0.0);
    let slope = verdicts.constant_e.as_ref().unwrap();
    assert!(slope.value.abs() < 1e-6 && slope.verdict == Judgement::Holds, "{slope:?}");
    assert_eq!(report.idealisation.constant_e.as_ref().unwrap().contact, 0);
}

/// A world sweep reads the verdicts by their dotted paths: the summary's and a contact's.
#[test]
fn a_world_sweep_writes_the_verdicts() {
    let scratch = Scratch::new("a_world_sweep_writes_the_verdicts");
    let mut text = String::new();
    for k in 0..3 {
        let v = if k == 0 { 1.0 } else { 0.0 };
        text += &sphere(&format!("ball {k}"), [k as f64 * 2.0 * RADIUS, 0.0, 0.0], [v, 0.0, 0.0]);
    }
    let scene = scratch.scene("cradle.toml", &(text + "[contact]\nlaw = \"hertz\"\n"));
    let columns =
        "idealisation.isolated.verdict,idealisation.isolated.contact,contacts.0.idealisation.isolated.verdict";
    let output = impact(
        scratch.path(),
        &["sweep", &scene, "--vary", "bodies.2.position.0=0.04,0.041", "--columns", columns, "--out", "v.csv"],
    );
    assert_eq!(output.status.code(), Some(0), "{}", String::from_utf8_lossy(&output.stderr));
    let csv = scratch.read("v.csv");
    let rows: Vec<Vec<&str>> = csv.lines().skip(1).map(|l| l.split(',').collect()).collect();
    assert_eq!(&rows[0][3..], ["fails", "1", "fails"], "{csv}");
    assert_eq!(&rows[1][3..], ["holds", "0", "holds"], "{csv}");
}
