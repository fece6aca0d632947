//! Housner's rocking block in a world (docs/world.md#the-rocking-block; Housner, Bull. Seism. Soc. Am. 53, 403
//! (1963)): a uniform block of half-width b and half-height h, rocking about one bottom corner, strikes the floor
//! with the other. If the new corner neither bounces nor slides and the old one lifts at once, the angular momentum
//! about the new corner is kept and `ω'/ω = 1 - (3/2) sin²α`, `α = atan(b/h)` (I_G = M R²/3, I_corner = 4 M R²/3,
//! R² = b² + h²). Every expected number here is that closed form, the energy of the block falling about its corner,
//! or the rigid-body impulse ratio at the corner — all computed in this file.
//!
//! The block is posed as the model models/rocking-block.toml poses it: two small corner spheres (radius r) whose lowest
//! points are the block's bottom corners, so that with the block level its contact points are Housner's corners
//! whatever r is; it is released at rest standing on its -x corner, tilted by φ0 (its +x side up), and falls back
//! onto its +x corner. Sticking, the corner sphere rolls on the floor, its contact point the instantaneous centre:
//! the mass centre stands at `z_G(φ) = r + b sin φ + (h - r) cos φ` and at the strike (φ = 0) the block turns about
//! its contact point with `I_P = I_G + M R² = (4/3) M R²`, so energy gives
//! `ω = sqrt(2 g (z_G(φ0) - h) / ((4/3) R²))`.
//!
//! The spins are read on the report's contacts: ω, the block's spin at the first touch of the new (+x) corner; ω',
//! the spin at the next first touch of the old (-x) corner. Between the two the block rocks about its new corner and
//! back, touching nothing else, and a rigid block rolling on its corner comes back level with the spin it left level
//! with: ω' is the spin just after the transfer, read where it is located exactly.

mod common;

use common::rocking::{B, G, H, R_CORNER, TILT, scene};
use common::world_report_json as run;
use serde_json::Value;

/// Housner's ratio of the spins after and before the transfer, `1 - (3/2) sin²α`.
fn housner() -> f64 {
    let alpha = (B / H).atan();
    1.0 - 1.5 * alpha.sin().powi(2)
}

/// The spin at the strike from the energy of the fall about the old corner's sphere (module docs).
fn spin_from_energy() -> f64 {
    let phi = TILT.to_radians();
    let drop = R_CORNER + B * phi.sin() + (H - R_CORNER) * phi.cos() - H;
    (2.0 * G * drop / (4.0 / 3.0 * (B * B + H * H))).sqrt()
}

/// Housner's limit: Tsuji's Hertzian law with five times its critical damping (the new corner's e is about 1e-3),
/// ended where its force returns to zero (the old corner lifts as soon as it is unloaded, never held by a pull), and
/// friction μ = 1, five times what the corner's impulse needs (see `sticking_needs`).
const LIMIT: &str = "law = \"tsuji\"\ndamping = 11.180339887498949\nseparation = \"force\"\nfriction = 1.0";

fn number(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("expected a number, found {v}"))
}

fn sphere_of(c: &Value) -> i64 {
    c["spheres"][0].as_i64().expect("a block's sphere")
}

/// The block's spin about y at a contact's first touch.
fn spin_at_touch(c: &Value) -> f64 {
    number(&c["angular_velocities_before"][0][1])
}

/// The new corner's first contact (the strike), and the old corner's next one (the return), if any.
fn strike_and_return(report: &Value) -> (&Value, Option<&Value>) {
    let contacts = report["contacts"].as_array().expect("contacts");
    let strike = contacts.iter().find(|c| sphere_of(c) == 0).expect("the +x corner strikes");
    let start = number(&strike["start_time"]);
    let back = contacts.iter().find(|c| sphere_of(c) == 1 && number(&c["start_time"]) > start);
    (strike, back)
}

/// The rigid impulse ratio |J_t / J_n| at the new corner in Housner's transfer: before it the mass centre moves at
/// ω (h, -b) (turning about the old corner), after at ω' (h, b), so `M Δv = (h (ω' - ω), b (ω' + ω))`.
fn sticking_needs() -> f64 {
    let ratio = housner();
    H * (1.0 - ratio) / (B * (1.0 + ratio))
}

/// The transfer converges on Housner's ratio as the corners stiffen (E and 100 E: the contact's duration falls as
/// E^(-2/5), the static dent as E^(-2/3)), and the spin at the strike is the fall's from the release angle.
#[test]
fn the_transfer_converges_on_housners_ratio_as_the_corners_stiffen() {
    let expected = housner();
    assert!((expected - 0.9117647058823529).abs() < 1e-15, "h/b = 4: 1 - (3/2)/17 = {expected}");
    let mut errors = Vec::new();
    for young in [2.1e11, 2.1e13] {
        let report = run(&scene(young, LIMIT, 3));
        let (strike, back) = strike_and_return(&report);
        let back = back.unwrap_or_else(|| panic!("the old corner strikes again: {}", report["contacts"]));
        let before = spin_at_touch(strike);
        let after = -spin_at_touch(back);
        let fall = (before - spin_from_energy()).abs() / spin_from_energy();
        assert!(fall < 2e-4, "E = {young}: spin at the strike {before} against the fall's {}", spin_from_energy());
        let error = (after / before - expected).abs() / expected;
        assert!(error < 3e-3, "E = {young}: ω'/ω = {} against Housner's {expected}", after / before);
        // The new corner did not bounce: one contact carries the block from the strike to the return.
        let carried = number(&strike["end_time"]) - number(&back["start_time"]);
        assert!(carried.abs() < 1e-4, "the strike's contact lasts until the return: {carried}");
        errors.push(error);
    }
    assert!(errors[1] < errors[0], "the stiffer corner is closer to Housner's ratio: {errors:?}");
}

/// An elastic corner (Hertz, e = 1) bounces: its contact separates with e near 1 and the block leaves it turning
/// slower than Housner's ratio says — the rigid block bouncing off its corner with e and sticking keeps the angular
/// momentum about that corner less the bounce's moment, `ω'/ω = 1 - (3/2)(1 + 2e) sin²α` — and the report judges
/// the strike an impact (`isolated` no worse than marginal), its e not a constant (`constant_e` fails).
#[test]
fn an_elastic_corner_bounces_and_takes_more_spin_than_housners_transfer() {
    let report = run(&scene(2.1e13, "law = \"hertz\"\nfriction = 1.0\ntangential_damping = 0.5", 3));
    let (strike, _) = strike_and_return(&report);
    assert_eq!(strike["separated"], Value::Bool(true), "{strike}");
    let e = number(&strike["restitution_velocity_ratio"]);
    assert!(e > 0.9, "an elastic corner bounces: e = {e}");
    let ratio = number(&strike["angular_velocities_after"][0][1]) / spin_at_touch(strike);
    assert!(ratio < housner() - 0.01, "the bounce takes more spin than Housner's transfer: {ratio}");
    let rigid_bounce = 1.0 - 1.5 * (1.0 + 2.0 * e) * (B / H).atan().sin().powi(2);
    assert!(ratio > rigid_bounce, "and less than a rigid bounce off the corner alone: {ratio} vs {rigid_bounce}");
    let verdict = |key: &str| strike["idealisation"][key]["verdict"].as_str().unwrap_or("null").to_string();
    assert_ne!(verdict("isolated"), "fails", "{}", strike["idealisation"]);
    assert_eq!(verdict("central"), "fails", "{}", strike["idealisation"]);
}

/// In the limit the new corner's contact is no impact: it carries the block as its pivot until the block rocks back,
/// and the report says so (`isolated` fails: gravity's impulse over it is about its own).
#[test]
fn housners_transfer_is_judged_no_isolated_impact() {
    let report = run(&scene(2.1e13, LIMIT, 3));
    let (strike, _) = strike_and_return(&report);
    let isolated = &strike["idealisation"]["isolated"];
    assert_eq!(isolated["verdict"].as_str(), Some("fails"), "{isolated}");
    assert!(number(&isolated["ratio"]) > 0.5, "{isolated}");
}

/// A corner with μ below what the transfer needs (`sticking_needs`, 0.18 for h/b = 4) slides: the block does not
/// come back with Housner's spin.
#[test]
fn a_sliding_corner_departs_from_housners_ratio() {
    let needs = sticking_needs();
    assert!((needs - 4.0 * 0.0882352941176471 / 1.9117647058823529).abs() < 1e-12, "{needs}");
    let mu = 0.1;
    assert!(mu < needs);
    let contact = LIMIT.replace("friction = 1.0", &format!("friction = {mu:?}"));
    let report = run(&scene(2.1e13, &contact, 3));
    let (strike, back) = strike_and_return(&report);
    let back = back.expect("the old corner strikes again");
    let ratio = -spin_at_touch(back) / spin_at_touch(strike);
    assert!((ratio - housner()).abs() > 0.05, "a sliding corner: ω'/ω = {ratio}, Housner's {}", housner());
    let slid = number(&report["contacts"][0]["friction_work"]) + number(&strike["friction_work"]);
    assert!(slid > 0.0, "friction worked on the slip: {slid}");
}
