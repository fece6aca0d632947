//! Elastic Hertz contact against its closed forms and published benchmark values (docs/references.md).

mod common;
use common::{assert_close, run};
use std::f64::consts::PI;

/// Duration constant (4/5) B(2/5, 1/2) of docs/references.md#elastic-hertz-contact: tc = 2.9432751843 dmax / v0.
const DURATION_CONSTANT: f64 = 2.9432751843;

/// Two equal spheres of one material closing at `speed` (half each way), elastic Hertz with Hertz stiffness.
fn equal_spheres(young: f64, poisson: f64, density: f64, radius: f64, speed: f64) -> impact::report::Report {
    let body = |v: f64| {
        format!(
            "[[bodies]]\nradius = {radius}\ndensity = {density}\nvelocity = [{v}, 0, 0]\nyoung = {young}\npoisson = {poisson}\n"
        )
    };
    run(&format!("{}{}[contact]\nlaw = \"hertz\"\n", body(speed / 2.0), body(-speed / 2.0)))
}

/// Hand calculation for two equal spheres: (dmax, tc, Fmax), the mass from the density (docs/scene.md#bodies), K
/// from docs/laws.md#stiffness-and-exponent and the closed forms of docs/references.md#elastic-hertz-contact.
fn closed_form(young: f64, poisson: f64, density: f64, radius: f64, speed: f64) -> (f64, f64, f64) {
    let mass = density * 4.0 / 3.0 * PI * radius.powi(3);
    let effective_mass = mass / 2.0;
    let effective_modulus = young / (2.0 * (1.0 - poisson * poisson));
    let stiffness = 4.0 / 3.0 * effective_modulus * (radius / 2.0).sqrt();
    let max_penetration = (5.0 * effective_mass * speed * speed / (4.0 * stiffness)).powf(0.4);
    (max_penetration, DURATION_CONSTANT * max_penetration / speed, stiffness * max_penetration.powf(1.5))
}

#[test]
fn steel_pair_matches_hertz_closed_forms_and_published_values() {
    let report = equal_spheres(2.1e11, 0.3, 7850.0, 0.01, 1.0);
    let c = &report.contact;
    let (dmax, tc, fmax) = closed_form(2.1e11, 0.3, 7850.0, 0.01, 1.0);
    assert_close("max penetration", c.max_penetration, dmax, 1e-9);
    // The constant has 11 digits.
    assert_close("duration", c.duration.unwrap(), tc, 2e-10);
    assert_close("max force", c.max_force, fmax, 1e-9);
    assert_close("time of max compression is half the duration", c.max_compression_time, tc / 2.0, 2e-10);
    // docs/references.md (checked, 6 digits).
    assert_close("published dmax", c.max_penetration, 2.04412e-5, 3e-6);
    assert_close("published tc", c.duration.unwrap(), 6.01641e-5, 3e-6);
    assert_close("published Fmax", c.max_force, 1005.38, 5e-6);
    // Elastic: e = 1 three ways, V0 the mean of the two velocities (0 here).
    for e in [c.restitution_velocity_ratio, c.restitution_impulse_ratio, c.restitution_energy] {
        assert_close("e", e.unwrap(), 1.0, 1e-9);
    }
    assert!(c.common_normal_velocity.abs() <= 1e-9);
}

#[test]
fn chung_ooi_test_1_glass_spheres() {
    // Chung & Ooi (2011), test 1: Fmax = 10.70 kN, dmax = 274.1 um, tc = 40.34 us (4 digits).
    let report = equal_spheres(4.8e10, 0.2, 2800.0, 0.01, 20.0);
    let c = &report.contact;
    assert_close("Fmax", c.max_force, 10.70e3, 5e-4);
    assert_close("dmax", c.max_penetration, 274.1e-6, 2e-4);
    assert_close("tc", c.duration.unwrap(), 40.34e-6, 2e-4);
    let (dmax, tc, fmax) = closed_form(4.8e10, 0.2, 2800.0, 0.01, 20.0);
    assert_close("closed-form dmax", c.max_penetration, dmax, 1e-9);
    assert_close("closed-form tc", c.duration.unwrap(), tc, 2e-10);
    assert_close("closed-form Fmax", c.max_force, fmax, 1e-9);
}

#[test]
fn chung_ooi_test_2_aluminium_sphere_on_rigid_wall() {
    // Chung & Ooi (2011), test 2: Fmax = 11.37 kN, dmax = 49.7 um, tc = 731.7 us.
    let report = run("[[bodies]]\nradius = 0.1\ndensity = 2699\nvelocity = [0.2, 0, 0]\nyoung = 7e10\npoisson = 0.3\n\
                      [[bodies]]\nradius = inf\nmass = inf\nvelocity = [0, 0, 0]\nyoung = inf\n\
                      [contact]\nlaw = \"hertz\"\n");
    let c = &report.contact;
    assert_close("Fmax", c.max_force, 11.37e3, 5e-4);
    assert_close("dmax", c.max_penetration, 49.7e-6, 1e-3);
    assert_close("tc", c.duration.unwrap(), 731.7e-6, 1e-4);
    // Hand calculation: m* = m, E* = E/(1 - nu²), R* = r.
    let mass = 2699.0 * 4.0 / 3.0 * PI * 1e-3;
    let stiffness = 4.0 / 3.0 * 7e10 / (1.0 - 0.09) * 0.1f64.sqrt();
    let dmax = (5.0 * mass * 0.04 / (4.0 * stiffness)).powf(0.4);
    assert_close("closed-form dmax", c.max_penetration, dmax, 1e-9);
    assert_close("closed-form tc", c.duration.unwrap(), DURATION_CONSTANT * dmax / 0.2, 2e-10);
    // The wall keeps its velocity and the sphere rebounds elastically.
    assert_close("rebound", report.bodies[0].velocity_after.unwrap()[0], -0.2, 1e-9);
    assert_eq!(report.bodies[1].velocity_after.unwrap(), [0.0, 0.0, 0.0]);
}

#[test]
fn linear_spring_lasts_half_a_period() {
    // F = K d (n = 1): a harmonic half period pi sqrt(m/K), penetration v0 sqrt(m/K): (2/(n+1)) B(1/2, 1/2) = pi.
    let report = common::on_wall(2.0, 3.0, "law = \"hertz\"\nstiffness = 5e5\nexponent = 1");
    let omega = (5e5f64 / 2.0).sqrt();
    assert_close("duration", report.contact.duration.unwrap(), PI / omega, 1e-9);
    assert_close("max penetration", report.contact.max_penetration, 3.0 / omega, 1e-9);
}
