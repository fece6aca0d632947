//! The idealised instantaneous impact (docs/references.md): what momentum and a coefficient of restitution alone say.

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

/// How a rigid-body frictional impact ends (docs/oblique.md).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RigidRegime {
    /// No friction: tangential velocities and spins unchanged.
    Smooth,
    /// The contact slides throughout: the tangential impulse is mu times the normal impulse, against the slip.
    Sliding,
    /// The slip stops during the impact (and, spheres being isotropic, stays stopped): the contact ends rolling.
    Sticking,
}

impl RigidRegime {
    /// The report's spelling.
    pub fn name(self) -> &'static str {
        match self {
            RigidRegime::Smooth => "smooth",
            RigidRegime::Sliding => "sliding",
            RigidRegime::Sticking => "sticking",
        }
    }
}

/// Result of an instantaneous rigid-body impact with Coulomb friction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidBody {
    pub regime: RigidRegime,
    /// Velocities after, m/s.
    pub velocity_after: [Vector3<f64>; 2],
    /// Angular velocities after, rad/s.
    pub angular_velocity_after: [Vector3<f64>; 2],
}

/// Rigid-body theory of an impact with restitution `e` and Coulomb coefficient `friction` along the unit `normal`
/// (docs/oblique.md). The normal impulse is (1+e) m* vn; with the initial slip `slip` of the contact points (body 1's
/// relative to body 2's) and B = 1/m1 + 1/m2 + r1²/I1 + r2²/I2, the contact slides throughout when
/// |slip| >= mu (1+e) vn m* B — the tangential impulse is then mu times the normal one against the slip — and
/// otherwise sticks: the tangential impulse slip/B stops the slip. Lever arms are the radii along the normal; a body
/// that does not rotate (immovable or flat) contributes no r²/I. `rubbed` (N s, 0 for rigid-body theory proper) is
/// impulse friction acts through beyond the normal one, so that sliding throughout takes mu (J_n + rubbed) of
/// tangential impulse: a compliant contact whose force pulls for an impulse J_t rubs through its compressive impulse
/// J_n + J_t (`rubbed` = J_t), or with a Coulomb limit of mu |Fn| (`friction_cap = "magnitude"`) through the pull too
/// (`rubbed` = 2 J_t).
pub fn rigid_body_impact(
    bodies: &[Body; 2],
    normal: &Vector3<f64>,
    effective_mass: f64,
    e: f64,
    friction: f64,
    slip: &Vector3<f64>,
    rubbed: f64,
) -> RigidBody {
    let [a, b] = bodies;
    let approach = (a.velocity - b.velocity).dot(normal);
    let normal_impulse = (1.0 + e) * effective_mass * approach;
    let rubbing = normal_impulse + rubbed;
    let rotational = |body: &Body| if body.rotates() { body.radius * body.radius / body.inertia } else { 0.0 };
    let compliance = a.inverse_mass() + b.inverse_mass() + rotational(a) + rotational(b);
    let slip_size = slip.norm();
    let (regime, tangential) = if friction == 0.0 {
        (RigidRegime::Smooth, Vector3::zeros())
    } else if slip_size >= friction * rubbing * compliance {
        (RigidRegime::Sliding, -slip * (friction * rubbing / slip_size))
    } else {
        (RigidRegime::Sticking, -slip / compliance)
    };
    // Impulse on body 1: -Pn n + Pt; on body 2 its opposite. Torques from the arms r1 n and -r2 n.
    let on_first = -normal * normal_impulse + tangential;
    let arms = [normal * a.radius, -normal * b.radius];
    let spin = |body: &Body, arm: &Vector3<f64>, impulse: &Vector3<f64>| {
        if body.rotates() { body.angular_velocity + arm.cross(impulse) / body.inertia } else { body.angular_velocity }
    };
    RigidBody {
        regime,
        velocity_after: [a.velocity + on_first * a.inverse_mass(), b.velocity - on_first * b.inverse_mass()],
        angular_velocity_after: [spin(a, &arms[0], &tangential), spin(b, &arms[1], &-tangential)],
    }
}
