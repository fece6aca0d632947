//! A rigid body's frictional contacts take energy, never give it: Housner's rocking block (docs/world.md#the-rocking-block)
//! with tangential damping. A dashpot only dissipates, the tangential spring only returns what it stored and Coulomb's
//! slider only dissipates, so the block's kinetic and potential energy never rise above what it was released with, and
//! each contact's `friction_work` (what the tangential force took from the bodies less what its spring still holds)
//! is never below zero. The bound is computed here by hand: the block's potential energy at release, `M g z_G(φ0)`,
//! and its energy at the end from the report's velocity, spin and position, `½ M v² + ½ I_yy ω_y² + M g z_G` (the
//! block turns about y only: its y inertia is the box's, whatever its tilt).
//!
//! With tangential damping the switch from sticking to sliding where the spring alone reached the cap dropped the
//! dashpot's force and started a slide that the spring did not hold: the spring, on the cap and along the slip,
//! pushed the contact points on, and the block — released 10° tilted, below the 14.04° it topples from — turned over
//! its new corner and fell through the floor (no top-corner spheres) with 27 J of kinetic energy from a 0.87 J fall.

mod common;

use common::rocking::{self, B, G, H, mass, principal, release_height};
use common::world_report_json as run;
use serde_json::Value;

/// The block of tests/rocking_block.rs, on a steel floor, with `contact` lines.
fn scene(contact: &str, max_contacts: usize) -> String {
    rocking::scene(2.1e11, contact, max_contacts)
}

/// Tsuji's law heavily damped, ended on its force, μ = 1 (models/rocking-block.toml).
const TSUJI: &str = "law = \"tsuji\"\ndamping = 11.180339887498949\nseparation = \"force\"\nfriction = 1.0";

fn number(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("expected a number, found {v}"))
}

fn vector(v: &Value) -> [f64; 3] {
    [number(&v[0]), number(&v[1]), number(&v[2])]
}

/// The block's kinetic and potential energy at the end of the run, J, from the report's motion.
fn energy_at_end(report: &Value) -> f64 {
    let block = &report["bodies"][0];
    let v = vector(&block["velocity_after"]);
    let w = vector(&block["angular_velocity_after"]);
    let z = vector(&block["position_after"])[2];
    assert!(w[0].abs() < 1e-9 && w[2].abs() < 1e-9, "the block turns about y only: {w:?}");
    let m = mass();
    0.5 * m * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) + 0.5 * principal()[1] * w[1] * w[1] + m * G * z
}

/// Runs `contact` for six contacts (the strike and five more transfers) and checks the energy bounds.
fn check(contact: &str) -> Value {
    let report = run(&scene(contact, 6));
    let start = mass() * G * release_height();
    let end = energy_at_end(&report);
    assert!(end <= start + 1e-9, "{contact}: the block's energy rose from {start} J to {end} J");
    let z = number(&report["bodies"][0]["position_after"][2]);
    assert!(z > H - 0.01, "{contact}: the block stays on its corners (mass centre at {z} m)");
    for c in report["contacts"].as_array().expect("contacts") {
        let work = number(&c["friction_work"]);
        assert!(work >= -1e-9, "{contact}: a contact's friction gave the bodies {} J: {c}", -work);
    }
    report
}

/// With tangential damping 0.5 (Mindlin's spring, a constant stiff one, or the contacts ended on the penetration) the
/// block rocks and dies down: it never gains energy and its contacts' friction only takes.
#[test]
fn a_rocking_block_with_tangential_damping_never_gains_energy() {
    for extra in ["tangential_damping = 0.5", "tangential_damping = 0.5\ntangential_stiffness = 1e8"] {
        check(&format!("{TSUJI}\n{extra}"));
    }
    let penetration = TSUJI.replace("separation = \"force\"", "separation = \"penetration\"");
    check(&format!("{penetration}\ntangential_damping = 0.5"));
}

/// The block's spin at each corner's first touch is at most what the fall from the release gives about the old
/// corner, `ω² ≤ 2 g (z_G(φ0) - h) / ((4/3) R²)` (the block level, turning about its contact point), and it dies
/// down from transfer to transfer.
#[test]
fn its_spin_at_each_transfer_is_bounded_by_the_fall_and_falls() {
    let report = check(&format!("{TSUJI}\ntangential_damping = 0.5"));
    let bound = (2.0 * G * (release_height() - H) / (4.0 / 3.0 * (B * B + H * H))).sqrt();
    let spins: Vec<f64> = report["contacts"].as_array().expect("contacts")[1..]
        .iter()
        .map(|c| number(&c["angular_velocities_before"][0][1]).abs())
        .collect();
    assert!(spins.len() >= 4, "the block rocks: {spins:?}");
    for pair in spins.windows(2) {
        assert!(pair[1] < pair[0], "the rocking dies down: {spins:?}");
    }
    // The dent at the touch lowers the mass centre by about 1e-5 m: 1e-4 of the 0.0057 m fall.
    assert!(spins[0] <= bound * (1.0 + 1e-3), "spin at the strike {} above the fall's {bound}", spins[0]);
}

/// Without tangential damping (the model's settings) the same bounds hold.
#[test]
fn without_tangential_damping_the_same_bounds_hold() {
    check(TSUJI);
}
