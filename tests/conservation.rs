//! The impact against the instantaneous formulas of docs/references.md#the-instantaneous-impact: momentum, V0, the
//! three e, energy.

mod common;
use common::{assert_close, run};

/// Two unequal steel-like spheres placed apart along a tilted line, closing along it, Hunt–Crossley damping.
fn unequal_pair(contact: &str) -> impact::report::Report {
    // Direction of the line of centres (3, 4, 0)/5; body 1 at the origin, body 2 0.05 m away along it.
    run(&format!(
        "[[bodies]]\nradius = 0.01\nmass = 0.03\nvelocity = [1.8, 2.4, 0.0]\nposition = [0, 0, 0]\n\
         young = 2e11\npoisson = 0.3\n\
         [[bodies]]\nradius = 0.02\nmass = 0.25\nvelocity = [-0.6, -0.8, 0.0]\nposition = [0.03, 0.04, 0.0]\n\
         young = 7e10\npoisson = 0.33\n[contact]\n{contact}\n"
    ))
}

#[test]
fn momentum_v0_and_the_three_restitution_coefficients_agree() {
    let report = unequal_pair("law = \"hunt-crossley\"\ndamping = 0.4");
    let (m1, m2) = (0.03, 0.25);
    let (u1, u2) = (3.0, -1.0); // normal components: |(1.8, 2.4)| = 3 along n, -1 along n
    let v0 = u1 - u2;
    let c = &report.contact;
    assert_close("approach speed", report.approach_speed, v0, 1e-12);
    // V0 = (m1 u1 + m2 u2)/(m1 + m2) (docs/references.md#the-instantaneous-impact).
    let common = (m1 * u1 + m2 * u2) / (m1 + m2);
    assert!((c.common_normal_velocity - common).abs() <= 1e-9 * v0, "V0 {} vs {common}", c.common_normal_velocity);
    // Deformation impulse m* (u1 - u2).
    let effective_mass = m1 * m2 / (m1 + m2);
    assert_close("deformation impulse", c.deformation_impulse, effective_mass * v0, 1e-9);
    // Poisson = Newton = Stronge for a frictionless central impact.
    let e = c.restitution_velocity_ratio.unwrap();
    assert_close("impulse ratio = velocity ratio", c.restitution_impulse_ratio.unwrap(), e, 1e-9);
    assert_close("energy ratio = velocity ratio", c.restitution_energy.unwrap(), e, 1e-9);
    // Energy lost (1/2) m* (1 - e²) v0², both as kinetic energy change and as damping work.
    let lost = 0.5 * effective_mass * (1.0 - e * e) * v0 * v0;
    let kinetic_change = report.energy.kinetic_before - report.energy.kinetic_after.unwrap();
    assert_close("kinetic energy lost", kinetic_change, lost, 1e-8);
    assert_close("dissipated", report.energy.dissipated.unwrap(), lost, 1e-9);
    // Momentum conserved, component by component.
    let before = [1.8 * m1 - 0.6 * m2, 2.4 * m1 - 0.8 * m2];
    let (a, b) = (report.bodies[0].velocity_after.unwrap(), report.bodies[1].velocity_after.unwrap());
    for k in 0..2 {
        assert!((m1 * a[k] + m2 * b[k] - before[k]).abs() <= 1e-12, "momentum component {k}");
    }
    // Velocities after equal the instantaneous formulas with the simulated e.
    let ideal = report.instantaneous.as_ref().unwrap();
    assert!(ideal.max_velocity_difference.unwrap() <= 1e-9 * v0);
    let n = [0.6, 0.8, 0.0];
    let (u1_after, u2_after) = (u1 - (1.0 + e) * effective_mass * v0 / m1, u2 + (1.0 + e) * effective_mass * v0 / m2);
    for k in 0..3 {
        assert!((a[k] - u1_after * n[k]).abs() <= 1e-9 * v0);
        assert!((b[k] - u2_after * n[k]).abs() <= 1e-9 * v0);
    }
}

#[test]
fn free_flight_to_first_contact_is_solved_in_closed_form() {
    let report = unequal_pair("law = \"hertz\"");
    // Centres 0.05 m apart, contact at 0.03 m, closing at 4 m/s: contact after 0.02/4 = 5 ms, along (0.6, 0.8, 0).
    assert_close("contact time", report.contact.start_time, 0.005, 1e-12);
    for (k, expected) in [0.6, 0.8, 0.0].iter().enumerate() {
        assert!((report.normal[k] - expected).abs() < 1e-12);
    }
    assert!(report.contact.max_compression_time > report.contact.start_time);
}

#[test]
fn lecture_worked_example_normal_components() {
    // Lecture (docs/oblique.md): equal masses, normal components +5 and -7.071 m/s, e = 0.8:
    // after the impact -5.864 and +3.793 m/s.
    let report = run("[[bodies]]\nradius = 0.05\nmass = 1.0\nvelocity = [5.0, 0, 0]\nyoung = 2e11\npoisson = 0.3\n\
                      [[bodies]]\nradius = 0.05\nmass = 1.0\nvelocity = [-7.071, 0, 0]\nyoung = 2e11\npoisson = 0.3\n\
                      [contact]\nlaw = \"carvalho-martins\"\nrestitution = 0.8\n");
    let after = |i: usize| report.bodies[i].velocity_after.unwrap()[0];
    assert!((after(0) - -5.864).abs() < 5e-4, "body 1 after {}", after(0));
    assert!((after(1) - 3.793).abs() < 5e-4, "body 2 after {}", after(1));
    assert_close("e", report.contact.restitution_velocity_ratio.unwrap(), 0.8, 1e-9);
}

#[test]
fn a_wall_can_be_either_body_and_imposes_v0() {
    let sphere = "radius = 0.01\nmass = 0.1\nyoung = 2e11\npoisson = 0.3";
    let wall = "radius = inf\nmass = inf\nyoung = 2e11\npoisson = 0.3";
    let contact = "[contact]\nlaw = \"hunt-crossley\"\ndamping = 0.3";
    let right = run(&format!(
        "[[bodies]]\n{sphere}\nvelocity = [2, 0, 0]\n[[bodies]]\n{wall}\nvelocity = [0.5, 0, 0]\n{contact}"
    ));
    let left = run(&format!(
        "[[bodies]]\n{wall}\nvelocity = [-0.5, 0, 0]\n[[bodies]]\n{sphere}\nvelocity = [-2, 0, 0]\n{contact}"
    ));
    // Approach 1.5 m/s either way; the wall's normal velocity is V0; the same e by symmetry.
    assert_close("approach", right.approach_speed, 1.5, 1e-15);
    assert_close("approach", left.approach_speed, 1.5, 1e-15);
    assert!((right.contact.common_normal_velocity - 0.5).abs() <= 1e-9 * 1.5);
    assert!((left.contact.common_normal_velocity + 0.5).abs() <= 1e-9 * 1.5);
    let (e_right, e_left) =
        (right.contact.restitution_velocity_ratio.unwrap(), left.contact.restitution_velocity_ratio.unwrap());
    assert_close("mirror e", e_left, e_right, 1e-12);
    // Hunt–Crossley e depends on x = alpha v0 = 0.45 only (docs/references.md): x (1 + e) = ln((1 + x)/(1 - e x)).
    let x = 0.3 * 1.5;
    let residual = x * (1.0 + e_right) - ((1.0 + x) / (1.0 - e_right * x)).ln();
    assert!(residual.abs() < 1e-9, "exact relation residual {residual}");
}
