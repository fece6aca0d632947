//! Linear Kelvin–Voigt F = k d + c d' against its closed forms (docs/references.md).

mod common;
use common::{assert_close, on_wall};
use std::f64::consts::PI;

const MASS: f64 = 1.0;
const STIFFNESS: f64 = 1e4;

/// A sphere on a wall with damping ratio zeta and the given separation criterion.
fn with_zeta(zeta: f64, separation: &str) -> impact::report::Report {
    let c = 2.0 * zeta * (STIFFNESS * MASS).sqrt();
    on_wall(
        MASS,
        1.5,
        &format!("law = \"kelvin-voigt\"\ndamping = {c}\nstiffness = {STIFFNESS}\nseparation = \"{separation}\""),
    )
}

#[test]
fn penetration_separation_gives_the_damped_oscillator_restitution_and_half_period() {
    let omega0 = (STIFFNESS / MASS).sqrt();
    // docs/references.md: zeta = 0.1 -> e = 0.7292476143, duration 3.1574/omega0; zeta = 0.3 -> 0.3723261049, 3.2933.
    for (zeta, published_e, published_duration) in [(0.1, 0.7292476143, 3.1574), (0.3, 0.3723261049, 3.2933)] {
        let report = with_zeta(zeta, "penetration");
        let c = &report.contact;
        let root = (1.0 - zeta * zeta).sqrt();
        assert_close("e closed form", c.restitution_velocity_ratio.unwrap(), (-PI * zeta / root).exp(), 1e-9);
        assert_close("e published", c.restitution_velocity_ratio.unwrap(), published_e, 2e-10);
        assert_close("duration closed form", c.duration.unwrap(), PI / (omega0 * root), 1e-9);
        assert_close("duration published", c.duration.unwrap() * omega0, published_duration, 2e-5);
        // The force jumps to c v0 at first contact.
        assert!(c.max_force >= 2.0 * zeta * (STIFFNESS * MASS).sqrt() * 1.5);
    }
}

#[test]
fn force_separation_gives_the_schwager_poschel_restitution() {
    let omega0 = (STIFFNESS / MASS).sqrt();
    // docs/references.md: zeta = 0.1 -> 0.7440793977, duration 2.9560753247/omega0; zeta = 0.3 -> 0.4509754529, 2.6544745638.
    for (zeta, published_e, published_duration) in
        [(0.1, 0.7440793977, 2.9560753247), (0.3, 0.4509754529, 2.6544745638)]
    {
        let report = with_zeta(zeta, "force");
        let c = &report.contact;
        let beta = zeta * omega0;
        let omega = (omega0 * omega0 - beta * beta).sqrt();
        let angle = PI - 2.0 * (beta / omega).atan();
        assert_close("e closed form", c.restitution_velocity_ratio.unwrap(), (-(beta / omega) * angle).exp(), 1e-9);
        assert_close("e published", c.restitution_velocity_ratio.unwrap(), published_e, 2e-10);
        assert_close("duration closed form", c.duration.unwrap(), angle / omega, 1e-9);
        assert_close("duration published", c.duration.unwrap() * omega0, published_duration, 1e-10);
    }
}

#[test]
fn critical_damping_with_force_separation_gives_exp_minus_two() {
    let report = on_wall(
        MASS,
        1.0,
        &format!("law = \"kelvin-voigt\"\nrestitution = 0\nstiffness = {STIFFNESS}\nseparation = \"force\""),
    );
    assert_close("e", report.contact.restitution_velocity_ratio.unwrap(), (-2.0f64).exp(), 1e-9);
}

#[test]
fn overdamped_force_separation_matches_closed_form() {
    // docs/references.md: e = exp(-(beta/Omega) ln((beta + Omega)/(beta - Omega))), Omega = sqrt(beta² - k/m*).
    let zeta = 2.0;
    let report = with_zeta(zeta, "force");
    let omega0 = (STIFFNESS / MASS).sqrt();
    let (beta, big) = (zeta * omega0, omega0 * (zeta * zeta - 1.0).sqrt());
    let exact = (-(beta / big) * ((beta + big) / (beta - big)).ln()).exp();
    assert_close("e", report.contact.restitution_velocity_ratio.unwrap(), exact, 1e-9);
}

#[test]
fn critical_damping_with_penetration_separation_never_separates() {
    let report = on_wall(MASS, 1.0, &format!("law = \"kelvin-voigt\"\nrestitution = 0\nstiffness = {STIFFNESS}"));
    let c = &report.contact;
    assert!(!c.separated);
    assert!(c.end_time.is_none() && c.duration.is_none() && c.restitution_velocity_ratio.is_none());
    assert!(report.instantaneous.is_none() && report.energy.dissipated.is_none());
    assert!(report.notes.iter().any(|n| n.contains("did not separate")), "{:?}", report.notes);
}

#[test]
fn nominal_map_is_exact_for_penetration_separation() {
    for e in [0.2, 0.5, 0.9] {
        let report = on_wall(MASS, 1.0, &format!("law = \"kelvin-voigt\"\nrestitution = {e}\nstiffness = {STIFFNESS}"));
        assert_close("e", report.contact.restitution_velocity_ratio.unwrap(), e, 1e-9);
    }
}

#[test]
fn heavy_damping_peaks_at_first_contact_with_the_dashpot_force() {
    // For zeta >= 1/2 the force k d + c d' falls from its first value c v0 (dF/dt = k v0 - c² v0 / m* < 0 at
    // t = 0+), so the peak is the jump itself: c v0 = 2 zeta sqrt(k m*) v0.
    for (zeta, separation) in [(0.7, "force"), (0.7, "penetration"), (2.0, "force")] {
        let report = with_zeta(zeta, separation);
        let c = 2.0 * zeta * (STIFFNESS * MASS).sqrt();
        assert_close("max force", report.contact.max_force, c * 1.5, 1e-12);
        assert_eq!(report.contact.max_force_time, report.contact.start_time);
        assert!(report.reference.unwrap().errors.max_force.unwrap() < 1e-9);
    }
}
