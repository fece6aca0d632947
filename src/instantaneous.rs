//! The idealised instantaneous impact (physics.md §2): what momentum and a coefficient of restitution alone say.

use crate::body::{Body, after_normal_impulse};
use nalgebra::Vector3;

/// Result of an instantaneous direct (or smooth oblique) impact of two bodies along `normal`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Instantaneous {
    /// e used.
    pub restitution: f64,
    /// V0 = (m1 u1 + m2 u2)/(m1 + m2), m/s (the immovable body's normal velocity if there is one).
    pub common_normal_velocity: f64,
    /// Velocities after, m/s: normal parts changed by the impulse (1+e) m* (u1 - u2), tangential parts kept.
    pub velocity_after: [Vector3<f64>; 2],
    /// (1/2) m* (1 - e²) (u1 - u2)², J.
    pub energy_lost: f64,
}

/// Instantaneous impact with restitution `e` of two bodies along the unit `normal`; `effective_mass` is m*.
pub fn direct_impact(bodies: &[Body; 2], normal: &Vector3<f64>, effective_mass: f64, e: f64) -> Instantaneous {
    let [a, b] = bodies;
    let (u1, u2) = (a.velocity.dot(normal), b.velocity.dot(normal));
    let approach = u1 - u2;
    let impulse = (1.0 + e) * effective_mass * approach;
    let common_normal_velocity = common_velocity(a, u1, b, u2);
    Instantaneous {
        restitution: e,
        common_normal_velocity,
        velocity_after: after_normal_impulse(bodies, normal, impulse),
        energy_lost: 0.5 * effective_mass * (1.0 - e * e) * approach * approach,
    }
}

/// (m1 u1 + m2 u2)/(m1 + m2), written with the mass ratio so that an immovable body imposes its own velocity.
fn common_velocity(a: &Body, u1: f64, b: &Body, u2: f64) -> f64 {
    match (a.is_immovable(), b.is_immovable()) {
        (true, _) => u1,
        (_, true) => u2,
        _ => {
            let share = a.mass / (a.mass + b.mass);
            share * u1 + (1.0 - share) * u2
        }
    }
}
