//! The instantaneous eccentric impact (src/eccentric.rs) against the textbook: Beer & Johnston's hung rod, a free
//! rod struck at its end (m_eff = M/4), the centre of percussion of a hung rod, and, over random bodies, the
//! conservation laws and the energy the restitution takes. Expected numbers are hand calculations written here.

mod common;

use impact::draw::Draw;
use impact::eccentric::{RigidBody, centre_of_percussion, eccentric_impact, positive_definite};
use nalgebra::{Matrix3, Vector3};

/// A point mass (a ball struck at its centre: no lever arm) of mass `m` at `centre`, moving at `velocity`.
fn ball(mass: f64, centre: Vector3<f64>, velocity: Vector3<f64>) -> RigidBody {
    let inertia = Matrix3::identity() * (0.4 * mass * 0.01 * 0.01);
    RigidBody { mass, inertia, centre, velocity, spin: Vector3::zeros(), pivot: None }
}

/// A uniform thin rod of mass `mass` and length `length` along z, its centre at `centre`, at rest: I = M L²/12
/// about x and y (and a tiny polar moment, a rod of small radius).
fn rod(mass: f64, length: f64, centre: Vector3<f64>, pivot: Option<Vector3<f64>>) -> RigidBody {
    let transverse = mass * length * length / 12.0;
    let inertia = Matrix3::from_diagonal(&Vector3::new(transverse, transverse, 1e-6 * transverse));
    RigidBody { mass, inertia, centre, velocity: Vector3::zeros(), spin: Vector3::zeros(), pivot }
}

#[test]
fn beer_and_johnstons_hung_rod() {
    // An 8 kg, 1.2 m rod hung at its top (the pivot at the origin, the rod down along -z), struck at its lower end by a
    // 2 kg ball at 5 m/s along x, e = 0.8: omega' = 3.21 rad/s, the ball rebounds at -0.143 m/s (Beer & Johnston,
    // Vector Mechanics for Engineers, sample problem 17.9). By hand: m_eff = I_O / L² = M/3, J = (1 + e) v m_b m_eff /
    // (m_b + m_eff), the ball's v' = v - J/m_b, omega' = J L / I_O with I_O = M L²/3.
    let (mass, length, ball_mass, speed, e) = (8.0, 1.2, 2.0, 5.0, 0.8);
    let hung = rod(mass, length, Vector3::new(0.0, 0.0, -length / 2.0), Some(Vector3::zeros()));
    let point = Vector3::new(0.0, 0.0, -length);
    let striker = ball(ball_mass, point, Vector3::new(speed, 0.0, 0.0));
    let impact = eccentric_impact(&[striker, hung], &point, &Vector3::x(), e).expect("they approach");
    let i_o = mass * length * length / 3.0;
    let m_eff = i_o / (length * length);
    let j = (1.0 + e) * speed * ball_mass * m_eff / (ball_mass + m_eff);
    common::assert_close("rod's effective mass", impact.effective_masses[1], mass / 3.0, 1e-12);
    common::assert_close("impulse", impact.impulse, j, 1e-12);
    common::assert_close("ball after", impact.velocities_after[0].x, speed - j / ball_mass, 1e-12);
    assert!((impact.velocities_after[0].x - -0.143).abs() < 5e-4, "the book's -0.143 m/s");
    // The rod turns about y: x = omega_y z, the lower end (z = -L) moves at +x for omega_y < 0.
    let omega = -impact.spins_after[1].y;
    common::assert_close("omega'", omega, j * length / i_o, 1e-12);
    assert!((omega - 3.21).abs() < 5e-3, "the book's 3.21 rad/s");
    // The pivot: the rod's momentum change M omega' L/2 is the blow J plus what the pivot passes, M omega' L/2 - J.
    common::assert_close("pivot impulse", impact.pivot_impulses[1].x, mass * omega * length / 2.0 - j, 1e-12);
    assert!(impact.pivot_impulses[1].y.abs() < 1e-12 && impact.pivot_impulses[1].z.abs() < 1e-12);
}

#[test]
fn a_free_rod_struck_at_its_end_has_a_quarter_of_its_mass() {
    // 1/m_eff = 1/M + (L/2)² / (M L²/12) = 4/M. A ball of mass m at v, e: J = (1 + e) v m (M/4) / (m + M/4).
    let (mass, length, ball_mass, speed, e) = (3.0, 0.9, 0.5, 2.0, 0.6);
    let free = rod(mass, length, Vector3::zeros(), None);
    let point = Vector3::new(0.0, 0.0, length / 2.0);
    let striker = ball(ball_mass, point, Vector3::new(speed, 0.0, 0.0));
    let impact = eccentric_impact(&[striker, free], &point, &Vector3::x(), e).expect("they approach");
    common::assert_close("m_eff", impact.effective_masses[1], mass / 4.0, 1e-12);
    let j = (1.0 + e) * speed * ball_mass * (mass / 4.0) / (ball_mass + mass / 4.0);
    common::assert_close("J", impact.impulse, j, 1e-12);
    common::assert_close("rod centre", impact.velocities_after[1].x, j / mass, 1e-12);
    common::assert_close(
        "rod spin",
        impact.spins_after[1].y,
        j * length / 2.0 / (mass * length * length / 12.0),
        1e-12,
    );
}

#[test]
fn a_blow_at_the_centre_of_percussion_leaves_the_pivot_alone() {
    // A uniform rod hung at one end: q = I_O / (M d) = (M L²/3) / (M L/2) = 2L/3.
    let (mass, length) = (5.0, 0.75);
    let q = centre_of_percussion(mass, mass * length * length / 3.0, length / 2.0);
    common::assert_close("q", q, 2.0 * length / 3.0, 1e-15);
    let hung = rod(mass, length, Vector3::new(0.0, 0.0, -length / 2.0), Some(Vector3::zeros()));
    for (depth, passes) in [(q, false), (length, true), (0.5 * length, true)] {
        let point = Vector3::new(0.0, 0.0, -depth);
        let striker = ball(1.0, point, Vector3::new(3.0, 0.0, 0.0));
        let impact = eccentric_impact(&[striker, hung], &point, &Vector3::x(), 0.7).expect("they approach");
        let along = impact.pivot_impulses[1].x.abs();
        if passes {
            assert!(along > 1e-3 * impact.impulse, "struck at {depth}: the pivot passes {along}");
        } else {
            assert!(along < 1e-12 * impact.impulse, "at the centre of percussion the pivot passes {along}");
        }
    }
}

#[test]
fn random_free_bodies_keep_momentum_and_angular_momentum_and_lose_the_restitution_energy() {
    let mut checked = 0;
    for case in 0..500 {
        let mut draw = Draw::new(0xecc_e471c, case);
        let bodies: [RigidBody; 2] = std::array::from_fn(|_| {
            let mass = draw.log(0.01, 100.0);
            let size = mass * draw.log(1e-4, 1.0);
            RigidBody {
                mass,
                inertia: common::random_inertia(&mut draw, size),
                centre: draw.direction() * draw.log(0.01, 1.0),
                velocity: draw.direction() * draw.log(0.01, 10.0),
                spin: draw.direction() * draw.log(0.01, 10.0),
                pivot: None,
            }
        });
        assert!(bodies.iter().all(|b| positive_definite(&b.inertia)));
        let point = draw.direction() * draw.log(0.01, 1.0);
        let normal = draw.direction();
        let e = draw.uniform(0.0, 1.0);
        let Some(impact) = eccentric_impact(&bodies, &point, &normal, e) else { continue };
        checked += 1;
        let momentum = |v: [Vector3<f64>; 2]| v[0] * bodies[0].mass + v[1] * bodies[1].mass;
        let before = momentum([bodies[0].velocity, bodies[1].velocity]);
        let scale = bodies.iter().map(|b| b.mass * b.velocity.norm()).sum::<f64>() + impact.impulse;
        assert!((momentum(impact.velocities_after) - before).norm() <= 1e-12 * scale, "case {case}: momentum");
        // Angular momentum about the origin: r × M v + I w.
        let angular = |v: [Vector3<f64>; 2], w: [Vector3<f64>; 2]| {
            (0..2)
                .map(|i| bodies[i].centre.cross(&(v[i] * bodies[i].mass)) + bodies[i].inertia * w[i])
                .sum::<Vector3<f64>>()
        };
        let l_before = angular([bodies[0].velocity, bodies[1].velocity], [bodies[0].spin, bodies[1].spin]);
        let l_after = angular(impact.velocities_after, impact.spins_after);
        let l_scale = l_before.norm() + impact.impulse * (point.norm() + 1.0);
        assert!((l_after - l_before).norm() <= 1e-11 * l_scale, "case {case}: angular momentum");
        // Energy: the loss is (1 - e²) v_n² / (2 (1/m1 + 1/m2)) with the effective masses (Routh).
        let energy = |v: [Vector3<f64>; 2], w: [Vector3<f64>; 2]| {
            bodies[0].kinetic_energy(&v[0], &w[0]) + bodies[1].kinetic_energy(&v[1], &w[1])
        };
        let lost = energy([bodies[0].velocity, bodies[1].velocity], [bodies[0].spin, bodies[1].spin])
            - energy(impact.velocities_after, impact.spins_after);
        let reduced = 1.0 / (1.0 / impact.effective_masses[0] + 1.0 / impact.effective_masses[1]);
        let expected = 0.5 * (1.0 - e * e) * reduced * impact.approach_speed.powi(2);
        let total = energy([bodies[0].velocity, bodies[1].velocity], [bodies[0].spin, bodies[1].spin]);
        assert!(
            (lost - expected).abs() <= 1e-10 * total.max(expected),
            "case {case}: lost {lost}, expected {expected}"
        );
        // Newton's e on the contact points' normal velocities.
        let after = |i: usize| {
            let b = RigidBody { velocity: impact.velocities_after[i], spin: impact.spins_after[i], ..bodies[i] };
            b.point_velocity(&point)
        };
        let separation = (after(1) - after(0)).dot(&normal);
        assert!(
            (separation - e * impact.approach_speed).abs()
                <= 1e-10 * impact.approach_speed.max(separation.abs()) + 1e-12 * scale
        );
    }
    assert!(checked > 150, "only {checked} of 500 random pairs approached");
}

#[test]
fn an_inertia_tensor_must_be_symmetric_positive_definite() {
    assert!(positive_definite(&Matrix3::from_diagonal(&Vector3::new(1.0, 2.0, 2.5))));
    assert!(!positive_definite(&Matrix3::from_diagonal(&Vector3::new(1.0, -2.0, 2.5))));
    assert!(!positive_definite(&Matrix3::new(1.0, 0.5, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0)), "not symmetric");
    assert!(!positive_definite(&Matrix3::new(1.0, 2.0, 0.0, 2.0, 1.0, 0.0, 0.0, 0.0, 1.0)), "indefinite");
    assert!(!positive_definite(&Matrix3::from_diagonal(&Vector3::new(1.0, f64::NAN, 1.0))));
}
