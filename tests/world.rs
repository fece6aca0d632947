//! A world of bodies (issue 23; docs/world.md): gravity, successive and simultaneous contacts. Every expected value
//! comes from outside the program: published chains (Herrmann & Schmälzle), closed forms (free fall, the damped
//! oscillator under gravity, the static penetration, the exact Hunt–Crossley e(x)), conservation laws, and the
//! two-body run of today.

mod common;

use common::binary::{Scratch, impact};
use common::hunt_crossley_e;
use impact::report::world::WorldReport;
use impact::scene::{Parsed, WorldScene};
use impact::setup::parse_any;
use std::path::Path;

fn world(text: &str) -> WorldScene {
    match parse_any(text, Path::new("world.toml")).unwrap_or_else(|e| panic!("{e}\n{text}")) {
        Parsed::World(world) => *world,
        Parsed::Impact(_) => panic!("not a world scene:\n{text}"),
    }
}

fn run(text: &str) -> WorldReport {
    let scene = world(text);
    impact::world_run::simulate(&scene).unwrap_or_else(|e| panic!("{e}\n{text}")).report
}

fn relative(value: f64, expected: f64) -> f64 {
    ((value - expected) / expected).abs()
}

/// A steel-like sphere: `radius` (m), `mass` (kg) at `position` with `velocity`, Young's modulus `young`.
fn sphere(name: &str, radius: f64, mass: f64, position: [f64; 3], velocity: [f64; 3], young: f64) -> String {
    format!(
        "[[bodies]]\nname = \"{name}\"\nradius = {radius:?}\nmass = {mass:?}\nposition = {position:?}\nvelocity = {velocity:?}\n\
         young = {young:e}\npoisson = 0.3\n\n"
    )
}

/// A floor through the origin, face up.
const FLOOR: &str = "[[bodies]]\nname = \"floor\"\nradius = inf\nmass = inf\nposition = [0.0, 0.0, 0.0]\n\
                     normal = [0.0, 0.0, 1.0]\nvelocity = [0.0, 0.0, 0.0]\nyoung = 2.1e11\npoisson = 0.3\n\n";

/// Three equal balls in a row along x, touching (or `gap` m apart), the first moving at `speed` into the others.
fn cradle(gap: f64, speed: f64, young: f64, contact: &str) -> String {
    let mut text = String::new();
    for k in 0..3 {
        let x = k as f64 * (0.02 + gap);
        let v = if k == 0 { speed } else { 0.0 };
        text += &sphere(&format!("ball {k}"), 0.01, 0.0329, [x, 0.0, 0.0], [v, 0.0, 0.0], young);
    }
    text + &format!("[contact]\n{contact}\n")
}

fn final_x(report: &WorldReport) -> Vec<f64> {
    report.bodies.iter().map(|b| b.velocity_after[0]).collect()
}

/// Herrmann & Schmälzle (Am. J. Phys. 49, 761 (1981)): three equal balls touching, the first struck at v0, leave at
/// (-0.0710, 0.0764, 0.9945) v0 with Hertzian contacts — a power law K d^n is scale-free, so whatever the stiffness
/// and the speed — and at (-0.130, 0.150, 0.980) v0 with linear springs.
#[test]
fn touching_hertzian_balls_do_not_pass_all_the_momentum_on() {
    for (young, speed) in [(2.1e11, 1.0), (7e10, 0.2), (2.1e11, 5.0)] {
        let report = run(&cradle(0.0, speed, young, "law = \"hertz\""));
        let v = final_x(&report);
        for (value, published) in v.iter().zip([-0.0710, 0.0764, 0.9945]) {
            assert!((value / speed - published).abs() < 1e-3, "E {young:e}, v0 {speed}: {v:?}");
        }
        assert_eq!(report.world.end_reason, "no_more_contacts");
        assert_eq!(report.contacts.len(), 2, "{:?}", report.contacts);
        assert_eq!(report.contacts[0].overlapping, vec![1], "the two contacts overlap in time");
        // The textbook's sequential model passes everything to the last ball: (0, 0, v0).
        let nominal = report.sequential.nominal.as_ref().unwrap();
        assert!((nominal.velocity_after[2][0] - speed).abs() < 1e-12 * speed);
        assert!((nominal.max_velocity_difference / speed - 0.0764).abs() < 1e-3);
    }
    let linear = run(&cradle(0.0, 1.0, 2.1e11, "law = \"hertz\"\nstiffness = 1e7\nexponent = 1.0"));
    let v = final_x(&linear);
    for (value, published) in v.iter().zip([-0.130, 0.150, 0.980]) {
        assert!((value - published).abs() < 1e-3, "linear springs: {v:?}");
    }
}

/// Gaps much wider than the maximum overlap (1 mm against 20 µm) separate the collisions in time: each is an elastic
/// collision of equal masses, which exchanges their velocities, and the sequential model's (0, 0, v0) returns.
#[test]
fn gaps_wider_than_the_overlap_restore_the_sequential_model() {
    let report = run(&cradle(1e-3, 1.0, 2.1e11, "law = \"hertz\""));
    let v = final_x(&report);
    for (value, expected) in v.iter().zip([0.0, 0.0, 1.0]) {
        assert!((value - expected).abs() < 1e-6, "{v:?}");
    }
    assert!(report.contacts.iter().all(|c| c.overlapping.is_empty()));
    assert!(report.sequential.nominal.unwrap().max_velocity_difference < 1e-6);
}

/// A ball of radius r dropped from rest with its centre at h0 onto a floor (Hertz, `contact`), with gravity; ball and
/// floor both of Young's modulus `young`.
fn dropped(h0: f64, young: f64, contact: &str, world: &str) -> String {
    format!(
        "[world]\ngravity = [0.0, 0.0, -9.81]\n{world}\n\n{}{}[contact]\n{contact}\n",
        sphere("ball", 0.01, 0.0329, [0.0, 0.0, h0], [0.0; 3], young),
        FLOOR.replace("young = 2.1e11", &format!("young = {young:e}"))
    )
}

/// The apex of the centre after each contact: it leaves the floor at height r (zero penetration) with the rebound
/// speed v, and rises v²/(2g).
fn apexes(report: &WorldReport) -> Vec<f64> {
    report.contacts.iter().filter_map(|c| c.velocities_after.map(|v| 0.01 + v[0][2] * v[0][2] / (2.0 * 9.81))).collect()
}

/// The elastic ball of `dropped(0.11, ...)` after `bounces` contacts: every apex at the drop height to 1e-9, the
/// first touch after the free fall sqrt(2 (h0 - r)/g) of the centre from 0.11 m to r = 0.01 m.
fn assert_bounces_to_its_drop_height(report: &WorldReport, bounces: usize) {
    let apexes = apexes(report);
    assert_eq!(apexes.len(), bounces);
    for apex in &apexes {
        assert!(relative(*apex, 0.11) < 1e-9, "{apexes:?}");
    }
    let first = &report.contacts[0];
    assert!(relative(first.start_time, (2.0 * 0.1 / 9.81f64).sqrt()) < 1e-12, "{}", first.start_time);
}

/// An elastic contact is reversible, gravity or not: the ball leaves each contact as fast as it came, and every apex
/// is the drop height; it first touches after the free fall sqrt(2 (h0 - r)/g) at sqrt(2 g (h0 - r)).
#[test]
fn an_elastic_ball_bounces_back_to_its_drop_height_every_time() {
    let report = run(&dropped(0.11, 2.1e11, "law = \"hertz\"", "max_contacts = 6"));
    assert_eq!(report.world.end_reason, "max_contacts");
    assert_bounces_to_its_drop_height(&report, 6);
    let first = &report.contacts[0];
    assert!(relative(first.approach_speed, (2.0 * 9.81 * 0.1f64).sqrt()) < 1e-12);
    assert!(report.energy.balance.abs() < 1e-9, "{:?}", report.energy);
}

/// With a damped contact mapped at each bounce's own speed (Hunt–Crossley, nominal 0.8: x = 1.5 (1 - 0.8) = 0.3 at
/// every bounce), the instantaneous model's apexes are (h0 - r) e^(2k) + r with e = e(0.3). The compliant contact
/// departs from them by gravity's impulse during contact, which shrinks as the contact stiffens (tc ~ K^(-2/5)).
#[test]
fn damped_bounces_approach_the_instantaneous_apexes_as_the_contact_stiffens() {
    let e = hunt_crossley_e(0.3);
    let deviation = |young: f64| {
        let report = run(&dropped(0.11, young, "law = \"hunt-crossley\"\nrestitution = 0.8", "max_contacts = 5"));
        for contact in &report.contacts {
            assert!(relative(contact.restitution_velocity_ratio.unwrap(), e) < 5e-3, "{e}: {contact:?}");
        }
        apexes(&report)
            .iter()
            .enumerate()
            .map(|(k, apex)| relative(*apex, 0.1 * e.powi(2 * (k as i32 + 1)) + 0.01))
            .fold(0.0, f64::max)
    };
    // The departure is gravity's impulse over the contact, g tc against the rebound speed: tc ~ K^(-2/5), so a
    // contact 100 times stiffer departs 100^(-2/5) = 0.158 times as much.
    let (soft, stiff) = (deviation(2.1e9), deviation(2.1e11));
    let ratio = stiff / soft;
    assert!((ratio / 100f64.powf(-0.4) - 1.0).abs() < 0.1, "soft {soft:e}, stiff {stiff:e}: ratio {ratio}");
    assert!(stiff < 1e-3, "{stiff:e}");
}

/// Dropped with damping, the ball comes to rest on the floor at the static penetration K d_s^(3/2) = m g, with
/// K = (4/3) E* sqrt(r), E* = E/(2 (1 - nu²)) for two equal materials — and the bounces stop after about
/// sqrt(2 (h0 - r)/g) (1 + e)/(1 - e), the instantaneous model's time to rest.
#[test]
fn a_damped_ball_comes_to_rest_at_the_static_penetration() {
    let report = run(&dropped(0.11, 2.1e11, "law = \"hunt-crossley\"\nrestitution = 0.8", ""));
    assert_eq!(report.world.end_reason, "at_rest");
    let e_star = 2.1e11 / (2.0 * (1.0 - 0.09));
    let k = 4.0 / 3.0 * e_star * 0.01f64.sqrt();
    let static_penetration = (0.0329 * 9.81 / k).powf(2.0 / 3.0);
    let height = report.bodies[0].position_after[2];
    assert!(relative(0.01 - height, static_penetration) < 1e-6, "{} vs {static_penetration}", 0.01 - height);
    let e = hunt_crossley_e(0.3);
    let rest = (2.0 * 0.1 / 9.81f64).sqrt() * (1.0 + e) / (1.0 - e);
    assert!(relative(report.world.end_time, rest) < 0.01, "{} vs {rest}", report.world.end_time);
    assert!(report.energy.balance.abs() < 1e-9, "{:?}", report.energy);
}

/// A linear spring–dashpot under gravity (the three stages of MFiX's DEM-01): free fall to v_in = sqrt(2 g h), then
/// in contact d'' + 2 zeta w d' + w² d = g with d(0) = 0, d'(0) = v_in — d = g/w² + exp(-zeta w t) (A cos(wd t) +
/// B sin(wd t)), A = -g/w², B = (v_in + zeta w A)/wd — until d returns to zero. That zero is found here by bisection
/// on the closed form; the contact's duration and rebound speed must match it.
#[test]
fn a_spring_dashpot_under_gravity_matches_the_exact_three_stages() {
    let (m, k, h, g) = (0.0329_f64, 1e3_f64, 1e-2_f64, 9.81_f64);
    let e_nominal: f64 = 0.5;
    let zeta = -e_nominal.ln() / (std::f64::consts::PI.powi(2) + e_nominal.ln().powi(2)).sqrt();
    let w = (k / m).sqrt();
    let wd = w * (1.0 - zeta * zeta).sqrt();
    let v_in = (2.0 * g * h).sqrt();
    let a = -g / (w * w);
    let b = (v_in + zeta * w * a) / wd;
    let d = |t: f64| g / (w * w) + (-zeta * w * t).exp() * (a * (wd * t).cos() + b * (wd * t).sin());
    let rate = |t: f64| {
        (-zeta * w * t).exp()
            * ((-zeta * w) * (a * (wd * t).cos() + b * (wd * t).sin())
                + wd * (-a * (wd * t).sin() + b * (wd * t).cos()))
    };
    // The first zero after the penetration's maximum: scanned from a quarter of the damped period, then bisected.
    let step = 2.0 * std::f64::consts::PI / wd / 4000.0;
    let mut low = 1000.0 * step;
    while d(low + step) > 0.0 {
        low += step;
        assert!(low < 4000.0 * step, "the contact does not end within a period");
    }
    let mut high = low + step;
    assert!(d(low) > 0.0 && d(high) <= 0.0);
    for _ in 0..200 {
        let middle = 0.5 * (low + high);
        if d(middle) > 0.0 { low = middle } else { high = middle }
    }
    let duration = 0.5 * (low + high);
    let e = -rate(duration) / v_in;
    assert!(g / (w * v_in) > 0.1, "gravity matters during contact: G = {}", g / (w * v_in));
    let contact = format!("law = \"kelvin-voigt\"\nstiffness = {k:e}\nexponent = 1.0\nrestitution = {e_nominal}");
    let report = run(&dropped(0.01 + h, 2.1e11, &contact, "max_contacts = 1"));
    let c = &report.contacts[0];
    assert!(relative(c.duration.unwrap(), duration) < 1e-9, "{:?} vs {duration}", c.duration);
    assert!(relative(c.restitution_velocity_ratio.unwrap(), e) < 1e-9, "{:?} vs {e}", c.restitution_velocity_ratio);
    // Without gravity the map's e is exact; gravity during contact changes it.
    assert!((e - e_nominal).abs() > 1e-2, "{e}");
}

/// A world of two bodies without gravity is today's impact of the pair: its contact is that report's, to the bit.
#[test]
fn a_world_of_two_bodies_without_gravity_is_todays_impact_to_the_bit() {
    for contact in
        ["law = \"hunt-crossley\"\nrestitution = 0.7", "law = \"tsuji\"\nrestitution = 0.4\nseparation = \"force\""]
    {
        let bodies = sphere("a", 0.01, 0.03, [0.0, 0.0, 0.0], [1.0, 0.2, 0.0], 2e11)
            + &sphere("b", 0.012, 0.05, [0.05, 0.003, 0.0], [-0.5, 0.0, 0.0], 7e10);
        let two = format!("{bodies}[contact]\n{contact}\n");
        let scene = impact::scene::Scene::parse(&two, Path::new("two.toml")).unwrap();
        let today = impact::impact::simulate(&scene, impact::history::Recording::Off).unwrap().report;
        let report = run(&format!("[world]\nmax_contacts = 3\n\n{two}"));
        assert_eq!(report.contacts.len(), 1);
        let (c, t) = (&report.contacts[0], &today.contact);
        assert_eq!(c.start_time, t.start_time);
        assert_eq!(c.max_compression_time, t.max_compression_time);
        assert_eq!(c.end_time, t.end_time);
        assert_eq!(c.max_penetration, t.max_penetration);
        assert_eq!(c.max_force, t.max_force);
        assert_eq!(c.deformation_impulse, t.deformation_impulse);
        assert_eq!(c.restitution_impulse, t.restitution_impulse);
        assert_eq!(c.restitution_velocity_ratio, t.restitution_velocity_ratio);
        assert_eq!(c.restitution_energy, t.restitution_energy);
        assert_eq!(c.common_normal_velocity, t.common_normal_velocity);
        for i in 0..2 {
            assert_eq!(report.bodies[i].velocity_after, today.bodies[i].velocity_after.unwrap());
        }
    }
}

/// A small deterministic generator (xorshift64*).
struct Random(u64);

impl Random {
    fn unit(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
    }
    fn between(&mut self, low: f64, high: f64) -> f64 {
        low + (high - low) * self.unit()
    }
}

/// Random worlds of 3 to 8 spheres on a jittered grid, thrown at each other, with every law; half without gravity
/// or walls (then momentum and angular momentum are conserved exactly: the contact forces are central and pairwise
/// opposite), half in a box under gravity. Every run's energy balance closes to 1e-9.
#[test]
fn random_worlds_conserve_momentum_and_close_their_energy_balance() {
    let laws = [
        "law = \"hertz\"",
        "law = \"hunt-crossley\"\nrestitution = 0.6",
        "law = \"carvalho-martins\"\nrestitution = 0.3",
        "law = \"tsuji\"\nrestitution = 0.5",
        "law = \"kelvin-voigt\"\nstiffness = 1e6\nexponent = 1.0\nrestitution = 0.7",
        "law = \"brilliantov\"\ndamping = 1e-6",
    ];
    let mut random = Random(0x0007_e5f0_2323_0001);
    for case in 0..24 {
        let count = 3 + case % 6;
        let gravity = case % 2 == 1;
        let mut text = if gravity {
            format!("[world]\ngravity = [0.0, 0.0, -9.81]\nmax_contacts = 30\nend_time = 0.3\n\n{FLOOR}")
        } else {
            "[world]\nmax_contacts = 30\n\n".to_string()
        };
        for k in 0..count {
            let (ix, iy) = ((k % 3) as f64, (k / 3) as f64);
            let radius = random.between(0.004, 0.01);
            let position = [0.03 * ix + random.between(-0.003, 0.003), 0.03 * iy, 0.05 + random.between(0.0, 0.02)];
            let toward = [0.03 - position[0], 0.015 - position[1], 0.0];
            let speed = random.between(0.2, 1.0);
            let velocity = [toward[0] * speed * 20.0, toward[1] * speed * 20.0, random.between(-0.5, 0.5)];
            text += &sphere(&format!("{k}"), radius, 8000.0 * radius.powi(3) * 4.19, position, velocity, 2e11);
        }
        text += &format!("[contact]\n{}\n", laws[case % laws.len()]);
        let report = run(&text);
        assert!(report.energy.balance.abs() < 1e-9, "case {case}: {:?}\n{text}", report.energy);
        if !gravity {
            let (mut p0, mut p1, mut l0, mut l1, mut scale) = ([0.0; 3], [0.0; 3], [0.0; 3], [0.0; 3], 0.0);
            for b in report.bodies.iter().filter(|b| b.mass.is_finite()) {
                let cross = |x: [f64; 3], v: [f64; 3]| {
                    [x[1] * v[2] - x[2] * v[1], x[2] * v[0] - x[0] * v[2], x[0] * v[1] - x[1] * v[0]]
                };
                let (c0, c1) = (cross(b.position_before, b.velocity_before), cross(b.position_after, b.velocity_after));
                for a in 0..3 {
                    p0[a] += b.mass * b.velocity_before[a];
                    p1[a] += b.mass * b.velocity_after[a];
                    l0[a] += b.mass * c0[a];
                    l1[a] += b.mass * c1[a];
                }
                scale += b.mass * b.velocity_before.iter().map(|v| v * v).sum::<f64>().sqrt();
            }
            let size = 0.1 * scale;
            for a in 0..3 {
                assert!((p1[a] - p0[a]).abs() < 1e-12 * scale, "case {case}: momentum {p0:?} -> {p1:?}");
                assert!((l1[a] - l0[a]).abs() < 1e-9 * size, "case {case}: angular momentum {l0:?} -> {l1:?}");
            }
        }
    }
}

/// Two balls dropped side by side on a floor, 10 µm apart in height: their contacts with the floor overlap in time
/// and neither may pass through it (a pair with no body in the island once went unwatched). Each bounces back to
/// its drop height with an elastic contact.
///
/// Again with drops of 1 mm and a skin of 1 µm: each contact moves its ball about 2 µm, beyond half the skin, so the
/// list is rebuilt inside the island (an event on the solution) and while B flies outside it.
#[test]
fn bodies_outside_the_island_still_meet_what_they_fly_into() {
    for (drop, end_time, skin) in [(0.11, 0.5, "inf"), (0.011, 0.1, "1e-6")] {
        outside_the_island(drop, end_time, skin);
    }
}

fn outside_the_island(drop: f64, end_time: f64, skin: &str) {
    let text = format!(
        "[world]\ngravity = [0.0, 0.0, -9.81]\nend_time = {end_time}\nskin = {skin}\n\n{}{}{FLOOR}[contact]\nlaw = \"hertz\"\n",
        sphere("A", 0.01, 0.0329, [0.0, 0.0, drop], [0.0; 3], 2.1e11),
        sphere("B", 0.01, 0.0329, [0.1, 0.0, drop + 1e-5], [0.0; 3], 2.1e11)
    );
    let report = run(&text);
    for ball in 0..2 {
        let heights: Vec<f64> = report
            .contacts
            .iter()
            .filter(|c| c.bodies.contains(&ball))
            .filter_map(|c| c.velocities_after.map(|v| 0.01 + v[0][2] * v[0][2] / (2.0 * 9.81)))
            .collect();
        assert!(heights.len() >= 2, "ball {ball}: {heights:?}");
        let drop = if ball == 0 { drop } else { drop + 1e-5 };
        assert!(heights.iter().all(|h| relative(*h, drop) < 1e-9), "skin {skin}, ball {ball}: {heights:?}");
        assert!(report.bodies[ball].position_after[2] > 0.0, "ball {ball} went through the floor");
    }
}

/// A ball resting on a floor at the start, under gravity, stays on it: it presses the floor at once (touching, no
/// approach) and settles at the static penetration; a ball resting on a fixed sphere likewise.
#[test]
fn a_ball_resting_at_the_start_presses_its_support() {
    let contact = "law = \"hunt-crossley\"\nrestitution = 0.8";
    let report = run(&dropped(0.01, 2.1e11, contact, "end_time = 0.1"));
    assert_eq!(report.contacts.len(), 1, "{:?}", report.contacts);
    assert!(report.contacts[0].pushed);
    assert_eq!(report.contacts[0].restitution_velocity_ratio, None);
    assert_eq!(report.world.end_reason, "at_rest");
    let height = report.bodies[0].position_after[2];
    assert!(height > 0.0099 && height < 0.01, "{height}");
    let fixed = format!(
        "[world]\ngravity = [0.0, 0.0, -9.81]\nend_time = 0.1\n\n{}[[bodies]]\nname = \"fixed\"\nradius = 0.02\nmass = inf\n\
         position = [0.0, 0.0, 0.0]\nvelocity = [0.0, 0.0, 0.0]\nyoung = 2.1e11\npoisson = 0.3\n\n[contact]\n{contact}\n",
        sphere("ball", 0.01, 0.0329, [0.0, 0.0, 0.03], [0.0; 3], 2.1e11)
    );
    let report = run(&fixed);
    assert_eq!(report.world.end_reason, "at_rest");
    let height = report.bodies[0].position_after[2];
    assert!(height > 0.0299 && height < 0.03, "{height}");
}

/// A run stopped inside a contact, before its penetration's first maximum, reports it as still in contact (no
/// panic, no null but its end); a graze of two passing spheres at exactly the sum of their radii is no contact; two
/// touching spheres sliding across each other without gravity part without a contact (the run once hung there).
#[test]
fn cut_short_contacts_grazes_and_touching_slides_are_reported_plainly() {
    let report = run(&dropped(0.11, 2.1e11, "law = \"hertz\"", "end_time = 0.1427845"));
    assert_eq!(report.world.end_reason, "end_time");
    let c = &report.contacts[0];
    assert!(!c.separated && c.end_time.is_none() && c.max_penetration > 0.0, "{c:?}");
    assert!(report.energy.balance.abs() < 1e-9);
    let graze = format!(
        "{}{}[contact]\nlaw = \"hertz\"\n",
        sphere("a", 0.01, 0.03, [0.0, 0.0, 0.0], [0.0; 3], 2.1e11),
        sphere("b", 0.01, 0.03, [-1.0, 0.02, 0.0], [1.0, 0.0, 0.0], 2.1e11)
    ) + &sphere("far", 0.01, 0.03, [100.0, 100.0, 100.0], [0.0; 3], 2.1e11);
    assert!(run(&graze).contacts.is_empty());
    let slide = sphere("a", 0.01, 0.0329, [0.11290864530486688, 0.28458872586489115, 0.0], [0.0; 3], 2.1e11)
        + &sphere(
            "b",
            0.01,
            0.0329,
            [0.1233669701190052, 0.2675410444365567, 0.0],
            [0.852384071416723, 0.5229162407069159, 0.0],
            2.1e11,
        )
        + &sphere("far", 0.01, 0.0329, [10.0, 10.0, 10.0], [0.0; 3], 2.1e11)
        + "[contact]\nlaw = \"hertz\"\n";
    let report = run(&slide);
    assert!(report.contacts.iter().all(|c| c.max_force < 1e-6), "{:?}", report.contacts);
}

/// A struck contact's damping map reads its own approach speed, whatever else the island holds: a ball struck at
/// about 0.1 m/s while its neighbour lands on the floor at 4 m/s is mapped at its 0.1 m/s, not at the island's speed
/// (only a contact pushed into being takes the island's speed as its floor).
#[test]
fn a_struck_contact_maps_its_damping_at_its_own_speed_inside_an_island() {
    let text = format!(
        "{}{}{FLOOR}[contact]\nlaw = \"hunt-crossley\"\nrestitution = 0.8\n",
        sphere("A", 0.01, 0.0329, [0.0, 0.0, 0.014], [0.0, 0.0, -4.0], 2.1e11),
        sphere("B", 0.01, 0.0329, [-0.020102, 0.0, 0.0101], [0.1, 0.0, 0.0], 2.1e11)
    );
    let report = run(&text);
    let c = report.contacts.iter().find(|c| c.bodies == [0, 1]).expect("the two balls meet");
    assert!(!c.pushed && c.approach_speed > 0.0 && c.approach_speed < 0.2, "{c:?}");
    assert_eq!(c.damping_map_speed, c.approach_speed, "{c:?}");
}

/// A small ball dropped on a big one resting on a floor bounces on it again and again: each bounce closes a gap,
/// so none is labelled pushed (a pair that once touched at a segment's start was).
#[test]
fn bounces_that_close_a_gap_are_not_pushed() {
    let text = format!(
        "[world]\ngravity = [0.0, 0.0, -9.81]\nmax_contacts = 12\n\n{}{}{FLOOR}[contact]\nlaw = \"hunt-crossley\"\n\
         restitution = 0.8\n",
        sphere("big", 0.05, 4.11, [0.0, 0.0, 0.05], [0.0; 3], 2.1e11),
        sphere("small", 0.001, 3.3e-5, [0.0, 0.0, 0.2], [0.0; 3], 2.1e11)
    );
    let report = run(&text);
    let bounces: Vec<_> = report.contacts.iter().filter(|c| c.bodies == [0, 1]).collect();
    assert!(bounces.len() >= 3, "{:?}", report.contacts);
    for bounce in &bounces {
        assert!(!bounce.pushed && bounce.approach_speed > 0.1, "{bounce:?}");
        assert!(bounce.restitution_velocity_ratio.is_some());
    }
}

/// A spring–dashpot contact ended by its force (k d + c d' = 0) leaves the ball overlapping the floor by
/// d0 = c v / k as it parts at v: the ball then rises from r - d0 and touches again when its centre falls back through
/// r, after (v + sqrt(v² - 2 g d0))/g, at sqrt(v² - 2 g d0). (A run once lost every ball that parted overlapping: it
/// fell through the floor.)
#[test]
fn a_ball_parted_by_its_force_while_overlapping_comes_back_to_the_floor() {
    let (k, g) = (1e3_f64, 9.81_f64);
    let contact = format!("law = \"kelvin-voigt\"\nstiffness = {k:e}\nrestitution = 0.5\nseparation = \"force\"");
    let report = run(&dropped(0.02, 2.1e11, &contact, "max_contacts = 4"));
    // The third bounce is too slow to part: the ball comes to rest on the floor in it.
    assert_eq!(report.contacts.len(), 3, "{:?}", report.contacts);
    assert_eq!(report.world.end_reason, "at_rest");
    for pair in report.contacts.windows(2) {
        let (parted, next) = (&pair[0], &pair[1]);
        let v = parted.velocities_after.unwrap()[0][2];
        let d0 = parted.damping * v / k;
        assert!(d0 > 1e-3 * 0.01 && v * v > 2.0 * g * d0, "a residual overlap that matters: {d0} at {v}");
        let flight = (v + (v * v - 2.0 * g * d0).sqrt()) / g;
        let expected = parted.end_time.unwrap() + flight;
        assert!((next.start_time - expected).abs() < 1e-9 * flight, "{} vs {expected}", next.start_time);
        assert!(relative(next.approach_speed, (v * v - 2.0 * g * d0).sqrt()) < 1e-9, "{next:?}");
        assert!(!next.pushed && next.elastic_energy_at_start == 0.0, "{next:?}");
    }
    assert!(report.bodies[0].position_after[2] > 0.0, "{:?}", report.bodies[0]);
    assert!(report.energy.balance.abs() < 1e-9, "{:?}", report.energy);
}

/// A ball the force parts from the floor too slowly to leave its overlap (v² < 2 g d0, d0 = c v/k) never opens its
/// gap: gravity brings it back after 2 v/g, pressing deeper than it parted, and the next contact begins there, pushed,
/// with the spring energy k d0²/2 of that overlap given back. (Such a ball once fell through the floor.)
#[test]
fn a_ball_parted_too_slowly_to_open_its_gap_is_pressed_back_into_the_floor() {
    let (k, g) = (1e3_f64, 9.81_f64);
    let contact = format!("law = \"kelvin-voigt\"\nstiffness = {k:e}\nrestitution = 0.1\nseparation = \"force\"");
    let report = run(&dropped(0.01 + 0.02, 2.1e11, &contact, "max_contacts = 3"));
    assert!(report.contacts.len() >= 2, "{:?}", report.contacts);
    let (parted, next) = (&report.contacts[0], &report.contacts[1]);
    let v = parted.velocities_after.unwrap()[0][2];
    let d0 = parted.damping * v / k;
    assert!(v * v < 2.0 * g * d0, "the gap must not open: {v} {d0}");
    assert!(relative(parted.penetration_at_separation.unwrap(), d0) < 1e-9, "{parted:?}");
    assert!(relative(next.start_time - parted.end_time.unwrap(), 2.0 * v / g) < 1e-6, "{next:?}");
    assert!(next.pushed && relative(next.elastic_energy_at_start, 0.5 * k * d0 * d0) < 1e-6, "{next:?}");
    assert!(report.bodies[0].position_after[2] > 0.0, "{:?}", report.bodies[0]);
    assert!(report.energy.balance.abs() < 1e-9, "{:?}", report.energy);
}

/// The same parting inside an island (a small ball bouncing on a big one that rocks on a soft spring on the floor,
/// in contact throughout): the pair's gap opens and closes again, so each later bounce begins at zero overlap,
/// struck, not pushed on the overlap the last one left.
#[test]
fn a_pair_parted_by_its_force_inside_an_island_closes_its_gap_again() {
    let text = format!(
        "[world]\ngravity = [0.0, 0.0, -9.81]\nend_time = 0.3\n\n{}{}{FLOOR}[contact]\nlaw = \"kelvin-voigt\"\n\
         stiffness = 1e3\nrestitution = 0.5\nseparation = \"force\"\n\n[[pair]]\nbodies = [0, 2]\nrestitution = 0.9\n",
        sphere("big", 0.05, 0.5, [0.0, 0.0, 0.05], [0.0; 3], 2.1e11),
        sphere("small", 0.01, 0.0329, [0.0, 0.0, 0.13], [0.0; 3], 2.1e11)
    );
    let report = run(&text);
    let floor: Vec<_> = report.contacts.iter().filter(|c| c.bodies == [0, 2]).collect();
    assert!(floor.len() == 1 && !floor[0].separated, "the big ball stays on its spring: {floor:?}");
    let bounces: Vec<_> = report.contacts.iter().filter(|c| c.bodies == [0, 1]).collect();
    assert!(bounces.len() >= 3, "{:?}", report.contacts);
    for bounce in &bounces {
        assert!(!bounce.pushed && bounce.elastic_energy_at_start == 0.0 && bounce.approach_speed > 0.01, "{bounce:?}");
    }
    assert!(report.energy.balance.abs() < 1e-9, "{:?}", report.energy);
}

/// `impact run WORLD --csv FILE --plot DIR --json`: the series has the documented columns, one row per body and per
/// active contact at each instant; its last instant is where the report leaves the bodies, its largest force the
/// report's; the figures are drawn (the heights with the simulation's and the model's apexes, under gravity).
/// `--samples` is refused for a world run.
#[test]
fn a_world_run_writes_its_series_and_figures() {
    let scratch = Scratch::new("a_world_run_writes_its_series_and_figures");
    let scene = scratch.scene(
        "bounce.toml",
        &dropped(0.11, 2.1e11, "law = \"carvalho-martins\"\nrestitution = 0.8", "max_contacts = 4"),
    );
    let output = impact(scratch.path(), &["run", &scene, "--json", "--csv", "bounce.csv", "--plot", "figures"]);
    assert_eq!(output.status.code(), Some(0), "{}", String::from_utf8_lossy(&output.stderr));
    let report: serde_json::Value = serde_json::from_slice(&output.stdout).expect("the JSON report");
    let csv = scratch.read("bounce.csv");
    let mut lines = csv.lines();
    assert_eq!(lines.next(), Some("time_s,kind,index,x_m,y_m,z_m,vx_m_s,vy_m_s,vz_m_s,penetration_m,force_N"));
    let rows: Vec<Vec<&str>> = lines.map(|line| line.split(',').collect()).collect();
    assert!(rows.iter().all(|row| row.len() == 11), "every row has the 11 columns");
    let last_ball = rows.iter().rev().find(|row| row[1] == "body" && row[2] == "0").expect("rows of the ball");
    let z: f64 = last_ball[5].parse().unwrap();
    assert!((z - report["bodies"][0]["position_after"][2].as_f64().unwrap()).abs() < 1e-15, "{z}");
    let contacts = report["contacts"].as_array().unwrap();
    for (k, contact) in contacts.iter().enumerate() {
        let largest = rows
            .iter()
            .filter(|row| row[1] == "contact" && row[2] == k.to_string())
            .map(|row| row[10].parse::<f64>().unwrap())
            .fold(0.0, f64::max);
        let peak = contact["max_force"].as_f64().unwrap();
        assert!(largest <= peak * (1.0 + 1e-12) && largest > 0.99 * peak, "contact {k}: {largest} vs {peak}");
    }
    let times: Vec<f64> = rows.iter().map(|row| row[0].parse().unwrap()).collect();
    assert!(times.windows(2).all(|pair| pair[0] <= pair[1]), "instants in time order");
    for name in ["contact_forces", "velocities", "heights"] {
        assert!(
            scratch.exists(&format!("figures/{name}.png")) && scratch.exists(&format!("figures/{name}.svg")),
            "{name}"
        );
    }
    let heights = scratch.read("figures/heights.svg");
    assert!(heights.contains("class=\"apex\"") && heights.contains("class=\"model\""), "apexes drawn");
    let refused = impact(scratch.path(), &["run", &scene, "--csv", "again.csv", "--samples", "100"]);
    assert_eq!(refused.status.code(), Some(2));
    assert!(!scratch.exists("again.csv"));
}

/// `impact sweep` of a world scene: the gap between the second and third ball of a cradle against a contact's
/// maximum overlap (20 µm at 1 m/s). Touching, the last ball leaves at Herrmann & Schmälzle's 0.9945; with a gap
/// wider than the overlap the collisions are apart and the sequential model's 1 m/s returns (Donahue et al. 2008).
/// Columns are paths into the world's report; a point that is not a valid scene is a row saying why; a key the scene
/// does not have is refused before any row runs.
#[test]
fn a_world_sweep_widens_the_cradle_gap_back_to_the_sequential_model() {
    let scratch = Scratch::new("a_world_sweep_widens_the_cradle_gap");
    let scene = scratch.scene("cradle.toml", &cradle(0.0, 1.0, 2.1e11, "law = \"hertz\""));
    let output = impact(
        scratch.path(),
        &[
            "sweep",
            &scene,
            "--vary",
            "bodies.2.position.0=0.04,0.04001,0.04003,0.0405",
            "--columns",
            "bodies.2.velocity_after.0,world.contacts,contacts.1.overlapping.0",
            "--out",
            "gaps.csv",
        ],
    );
    assert_eq!(output.status.code(), Some(0), "{}", String::from_utf8_lossy(&output.stderr));
    let csv = scratch.read("gaps.csv");
    let rows: Vec<Vec<&str>> = csv.lines().skip(1).map(|l| l.split(',').collect()).collect();
    assert_eq!(
        csv.lines().next(),
        Some("index,status,bodies.2.position.0,bodies.2.velocity_after.0,world.contacts,contacts.1.overlapping.0")
    );
    let last: Vec<f64> = rows.iter().map(|r| r[3].parse().unwrap()).collect();
    assert!((last[0] - 0.9945).abs() < 1e-3, "{last:?}");
    assert!(last[1] > last[0] && last[1] < 1.0, "{last:?}");
    for v in &last[2..] {
        assert!((v - 1.0).abs() < 1e-6, "{last:?}");
    }
    assert_eq!(rows[0][5], "0", "touching: the contacts overlap");
    assert_eq!(rows[3][5], "", "far apart: no overlap (an empty cell)");
    // A point that is not a valid scene: its row says why, the others run.
    let bad = impact(scratch.path(), &["sweep", &scene, "--vary", "bodies.1.mass=0.0329,-1", "--out", "masses.csv"]);
    assert_eq!(bad.status.code(), Some(0), "{}", String::from_utf8_lossy(&bad.stderr));
    let masses = scratch.read("masses.csv");
    assert!(
        masses.lines().nth(1).unwrap().contains(",ok,")
            && masses.lines().nth(2).unwrap().contains("error: bodies.1.mass"),
        "{masses}"
    );
    let refused = impact(scratch.path(), &["sweep", &scene, "--vary", "bodies.7.mass=1,2", "--out", "none.csv"]);
    assert_eq!(refused.status.code(), Some(2));
    assert!(!scratch.exists("none.csv"));
}

/// The same tests with a skin far below the radius: the neighbour list is rebuilt many times, in flight (at the
/// closed-form time a body reaches half the skin) and in the island (an event on the solution). The published
/// cradle and the elastic bounce hold as with every pair searched.
#[test]
fn a_neighbour_list_rebuilt_many_times_finds_the_same_contacts() {
    let text = cradle(0.0, 1.0, 2.1e11, "law = \"hertz\"");
    let report = run(&format!("[world]\nskin = 1e-7\n\n{text}"));
    let v = final_x(&report);
    for (value, published) in v.iter().zip([-0.0710, 0.0764, 0.9945]) {
        assert!((value - published).abs() < 1e-3, "{v:?}");
    }
    assert_eq!(report.contacts.len(), 2, "{:?}", report.contacts);
    // A drop of 10 cm with a skin of 1 mm: the list is rebuilt every 0.5 mm of the fall.
    let report = run(&dropped(0.11, 2.1e11, "law = \"hertz\"", "max_contacts = 3\nskin = 1e-3\nend_time = 10.0"));
    assert_bounces_to_its_drop_height(&report, 3);
}

/// Hertzian chains of 40 and 60 equal steel beads (radius 5 mm), touching, the first struck at 1 m/s: the pulse
/// crosses them and the last bead leaves. Beyond 32 bodies the run searches a neighbour list, and the contacts the pulse leaves
/// behind end quiet. Expected: an independent integration written here — classical RK4 on the whole chain at a
/// fixed step of 1/4000 of the two-ball contact time, F = K d^(3/2) with K = (4/3) E* sqrt(R*), E* = E / (2 (1 -
/// nu²)), R* = r/2 — every bead's velocity at the end to 1e-6 v0; momentum to 1e-12 and energy to 1e-8.
#[test]
fn a_hertzian_chain_carries_its_pulse_as_an_independent_integration_does() {
    // 40 beads to 1e-11; 60 beads to the default 1e-9 long after the pulse passed, where contacts end quiet.
    for (n, tolerance, end, quiet) in [(40, 1e-11, 1.0e-3, false), (60, 1e-9, 2.0e-3, true)] {
        hertzian_chain(n, tolerance, end, quiet);
    }
}

fn hertzian_chain(n: usize, tolerance: f64, end: f64, quiet: bool) {
    let (r, rho, young, nu, v0) = (0.005, 7850.0, 2.1e11, 0.3, 1.0);
    let mut text = format!("[world]\nend_time = {end:e}\nmax_contacts = 100000\n\n");
    for k in 0..n {
        let v = if k == 0 { v0 } else { 0.0 };
        text += &format!(
            "[[bodies]]\nradius = {r}\ndensity = {rho}\nyoung = {young:e}\npoisson = {nu}\nposition = [{:?}, 0.0, 0.0]\n\
             velocity = [{v:?}, 0.0, 0.0]\n\n",
            2.0 * r * k as f64
        );
    }
    text += &format!("[contact]\nlaw = \"hertz\"\n\n[solver]\nrtol = {tolerance:e}\natol = {tolerance:e}\n");
    let report = run(&text);
    assert_eq!(report.world.end_reason, "end_time");

    // The independent integration: positions and velocities along x.
    let mass = rho * 4.0 / 3.0 * std::f64::consts::PI * r * r * r;
    let stiffness = 4.0 / 3.0 * young / (2.0 * (1.0 - nu * nu)) * (r / 2.0f64).sqrt();
    let reduced = mass / 2.0;
    // The two-ball contact time: 2.9433 d_max / v0 with d_max = (5 m* v0² / (4 K))^(2/5).
    let duration = 2.9433 * (5.0 * reduced * v0 * v0 / (4.0 * stiffness)).powf(0.4) / v0;
    let steps = (end / (duration / 4000.0)).ceil() as usize;
    let dt = end / steps as f64;
    let accelerations = |x: &[f64]| -> Vec<f64> {
        let mut a = vec![0.0; n];
        for k in 0..n - 1 {
            let d = 2.0 * r - (x[k + 1] - x[k]);
            if d > 0.0 {
                let f = stiffness * d * d.sqrt();
                a[k] -= f / mass;
                a[k + 1] += f / mass;
            }
        }
        a
    };
    let mut x: Vec<f64> = (0..n).map(|k| 2.0 * r * k as f64).collect();
    let mut v: Vec<f64> = (0..n).map(|k| if k == 0 { v0 } else { 0.0 }).collect();
    for _ in 0..steps {
        let shifted =
            |base: &[f64], by: &[f64], h: f64| -> Vec<f64> { base.iter().zip(by).map(|(b, d)| b + h * d).collect() };
        let (k1x, k1v) = (v.clone(), accelerations(&x));
        let (k2x, k2v) = (shifted(&v, &k1v, dt / 2.0), accelerations(&shifted(&x, &k1x, dt / 2.0)));
        let (k3x, k3v) = (shifted(&v, &k2v, dt / 2.0), accelerations(&shifted(&x, &k2x, dt / 2.0)));
        let (k4x, k4v) = (shifted(&v, &k3v, dt), accelerations(&shifted(&x, &k3x, dt)));
        for k in 0..n {
            x[k] += dt / 6.0 * (k1x[k] + 2.0 * k2x[k] + 2.0 * k3x[k] + k4x[k]);
            v[k] += dt / 6.0 * (k1v[k] + 2.0 * k2v[k] + 2.0 * k3v[k] + k4v[k]);
        }
    }
    assert!(v[n - 1] > 0.9 * v0, "the pulse has not reached the end by the end time: {v:?}");
    let simulated = final_x(&report);
    for (k, (got, want)) in simulated.iter().zip(&v).enumerate() {
        assert!((got - want).abs() < 1e-6 * v0, "bead {k}: {got} against {want}\n{simulated:?}\n{v:?}");
    }
    let momentum: f64 = simulated.iter().map(|u| u * mass).sum();
    assert!((momentum - mass * v0).abs() < 1e-12 * mass * v0, "{momentum}");
    assert!(report.energy.balance.abs() < 1e-8, "{:?}", report.energy);
    if quiet {
        assert!(report.notes.iter().any(|note| note.contains("ended quiet")), "{:?}", report.notes);
    }
    // The terminal report lists 23 of the bodies (the first 18, the last 5), and says how many it leaves out.
    let table = impact::output::world_table::render(&report);
    assert!(table.contains(&format!("... {} more ...", n - 23)), "{table}");
}

/// A turning rod's flight is integrated in long steps; its series still shows the flight: no two instants further
/// apart than a 24th of it, and an instant at its mass centre's apex. A rod (0.2 kg, 0.2 m, ends of 5 mm) thrown up at
/// 2 m/s from 1 m, spinning at 3 rad/s about y, for 0.3 s above a floor it never reaches: its centre is on the
/// parabola z = 1 + 2 t - g t²/2 at every instant (closed form), with its apex at t = 2/g, z = 1 + 2/g.
#[test]
fn a_turning_bodys_flight_is_in_its_series() {
    let g = 9.81;
    let scene = format!(
        "[world]\ngravity = [0.0, 0.0, -{g}]\nend_time = 0.3\n\n[[bodies]]\nname = \"rod\"\nmass = 0.2\n\
         inertia = [6.67e-4, 6.67e-4, 2e-6]\nposition = [0.0, 0.0, 1.0]\nvelocity = [0.0, 0.0, 2.0]\n\
         angular_velocity = [0.0, 3.0, 0.0]\nyoung = 2.1e11\npoisson = 0.3\n\n[[bodies.spheres]]\n\
         offset = [0.0, 0.0, 0.1]\nradius = 0.005\n\n[[bodies.spheres]]\noffset = [0.0, 0.0, -0.1]\nradius = 0.005\n\n\
         [[bodies]]\nname = \"floor\"\nmass = inf\nradius = inf\nposition = [0.0, 0.0, 0.0]\nnormal = [0.0, 0.0, 1.0]\n\
         velocity = [0.0, 0.0, 0.0]\nyoung = 2.1e11\npoisson = 0.3\n\n[contact]\nlaw = \"hertz\"\n"
    );
    let scratch = Scratch::new("a_turning_bodys_flight_is_in_its_series");
    let path = scratch.scene("rod.toml", &scene);
    let output = impact(scratch.path(), &["run", &path, "--csv", "rod.csv"]);
    assert_eq!(output.status.code(), Some(0), "{}", String::from_utf8_lossy(&output.stderr));
    let csv = scratch.read("rod.csv");
    let rod: Vec<(f64, f64)> = csv
        .lines()
        .skip(1)
        .map(|line| line.split(',').collect::<Vec<_>>())
        .filter(|row| row[1] == "body" && row[2] == "0")
        .map(|row| (row[0].parse().unwrap(), row[5].parse().unwrap()))
        .collect();
    assert!(rod.first().unwrap().0 == 0.0 && (rod.last().unwrap().0 - 0.3).abs() < 1e-12, "{rod:?}");
    let widest = rod.windows(2).map(|pair| pair[1].0 - pair[0].0).fold(0.0, f64::max);
    assert!(widest <= 0.3 / 24.0 * (1.0 + 1e-9), "instants {widest} s apart");
    for &(t, z) in &rod {
        assert!((z - (1.0 + 2.0 * t - g * t * t / 2.0)).abs() < 1e-9, "t = {t}: z = {z}");
    }
    let apex = rod.iter().find(|(t, _)| (t - 2.0 / g).abs() < 1e-9).expect("an instant at the apex");
    assert!((apex.1 - (1.0 + 2.0 / g)).abs() < 1e-9, "{apex:?}");
}
