//! The instantaneous impact of rigid bodies struck off their centre (docs/references.md#eccentric-impact): the
//! idealisation that a compliant simulation of eccentric and pivoted bodies is measured against.
//!
//! Each body has a mass, an inertia tensor about its mass centre (in scene axes), and either moves freely or turns
//! about a pivot fixed in space. At the contact point, with `r` from the mass centre (or `r_O` from the pivot) to it
//! and the unit normal `n` from body 1 to body 2, its effective mass along `n` is
//! `1/m_eff = 1/M + (r × n)·I⁻¹(r × n)` (free) or `(r_O × n)·I_O⁻¹(r_O × n)` (pivoted, `I_O` about the pivot by the
//! parallel-axis theorem). A frictionless impact with restitution `e` passes the normal impulse
//! `J = (1 + e) v_n / (1/m_eff,1 + 1/m_eff,2)`, `v_n` the approach speed of the contact points along `n`; each body's
//! velocity and spin change from `J` at its contact point, and a pivot passes the impulse `M Δv_cm - J_contact` that
//! keeps the pivot still. Pure functions, SI units.

use nalgebra::{Matrix3, Vector3};

/// One rigid body at the instant of impact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidBody {
    /// Mass M, kg (`f64::INFINITY`: immovable).
    pub mass: f64,
    /// Inertia tensor about the mass centre in scene axes, kg m² (symmetric positive definite; ignored for an
    /// immovable body).
    pub inertia: Matrix3<f64>,
    /// Position of the mass centre, m.
    pub centre: Vector3<f64>,
    /// Velocity of the mass centre, m/s (for a pivoted body it must be `spin × (centre - pivot)`).
    pub velocity: Vector3<f64>,
    /// Angular velocity, rad/s.
    pub spin: Vector3<f64>,
    /// A point fixed in space that the body turns about, m; `None` for a free body.
    pub pivot: Option<Vector3<f64>>,
}

impl RigidBody {
    /// The inertia tensor about the pivot (parallel axes: `I + M (|d|² 1 - d dᵀ)`, `d` from the pivot to the mass
    /// centre), or about the mass centre for a free body.
    pub fn inertia_about_pivot(&self) -> Matrix3<f64> {
        match self.pivot {
            Some(pivot) => {
                let d = self.centre - pivot;
                self.inertia + (Matrix3::identity() * d.norm_squared() - d * d.transpose()) * self.mass
            }
            None => self.inertia,
        }
    }

    /// The inverse of the effective mass at `point` along the unit `normal`, 1/kg: zero for an immovable body.
    pub fn inverse_effective_mass(&self, point: &Vector3<f64>, normal: &Vector3<f64>) -> f64 {
        if self.mass.is_infinite() {
            return 0.0;
        }
        let arm = point - self.pivot.unwrap_or(self.centre);
        let moment = arm.cross(normal);
        let turning = moment.dot(&(inverse_inertia(&self.inertia_about_pivot()) * moment));
        if self.pivot.is_some() { turning } else { 1.0 / self.mass + turning }
    }

    /// The velocity of the body's material point at `point`, m/s.
    pub fn point_velocity(&self, point: &Vector3<f64>) -> Vector3<f64> {
        match self.pivot {
            Some(pivot) => self.spin.cross(&(point - pivot)),
            None => self.velocity + self.spin.cross(&(point - self.centre)),
        }
    }

    /// The body's velocity and spin after the impulse `impulse` (N s) at `point`, and the impulse its pivot passes
    /// to it (zero for a free body).
    pub fn after(&self, impulse: &Vector3<f64>, point: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>, Vector3<f64>) {
        if self.mass.is_infinite() {
            return (self.velocity, self.spin, Vector3::zeros());
        }
        let origin = self.pivot.unwrap_or(self.centre);
        let inverse = inverse_inertia(&self.inertia_about_pivot());
        let spin = self.spin + inverse * (point - origin).cross(impulse);
        match self.pivot {
            Some(pivot) => {
                let velocity = spin.cross(&(self.centre - pivot));
                (velocity, spin, (velocity - self.velocity) * self.mass - impulse)
            }
            None => (self.velocity + impulse / self.mass, spin, Vector3::zeros()),
        }
    }

    /// Kinetic energy (translation and rotation about the mass centre), J; 0 for an immovable body.
    pub fn kinetic_energy(&self, velocity: &Vector3<f64>, spin: &Vector3<f64>) -> f64 {
        if self.mass.is_infinite() {
            return 0.0;
        }
        0.5 * self.mass * velocity.norm_squared() + 0.5 * spin.dot(&(self.inertia * spin))
    }
}

/// The instantaneous eccentric impact: what the two bodies carry away.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EccentricImpact {
    /// The effective masses at the contact point along the normal, kg (infinite for an immovable body).
    pub effective_masses: [f64; 2],
    /// The approach speed of the contact points along the normal, m/s.
    pub approach_speed: f64,
    /// The normal impulse J on body 2 (body 1 receives -J n), N s.
    pub impulse: f64,
    pub velocities_after: [Vector3<f64>; 2],
    pub spins_after: [Vector3<f64>; 2],
    /// The impulse each body's pivot passes to it, N s (zero for a free body).
    pub pivot_impulses: [Vector3<f64>; 2],
}

/// The frictionless instantaneous impact of `bodies` touching at `point` with the unit `normal` (body 1 to body 2)
/// and restitution `e` (Newton's, on the contact points' normal velocities). `None` when the contact points are not
/// approaching, or when neither body can move there.
pub fn eccentric_impact(
    bodies: &[RigidBody; 2],
    point: &Vector3<f64>,
    normal: &Vector3<f64>,
    e: f64,
) -> Option<EccentricImpact> {
    let approach = (bodies[0].point_velocity(point) - bodies[1].point_velocity(point)).dot(normal);
    let inverse = [bodies[0].inverse_effective_mass(point, normal), bodies[1].inverse_effective_mass(point, normal)];
    let total = inverse[0] + inverse[1];
    if !(approach > 0.0 && total > 0.0) {
        return None;
    }
    let impulse = (1.0 + e) * approach / total;
    let (v1, w1, p1) = bodies[0].after(&(-normal * impulse), point);
    let (v2, w2, p2) = bodies[1].after(&(normal * impulse), point);
    Some(EccentricImpact {
        effective_masses: inverse.map(|w| 1.0 / w),
        approach_speed: approach,
        impulse,
        velocities_after: [v1, v2],
        spins_after: [w1, w2],
        pivot_impulses: [p1, p2],
    })
}

/// The centre of percussion of a body turning about a pivot: the distance from the pivot, along the line through
/// its mass centre, at which a blow perpendicular to that line passes no impulse to the pivot, `q = I_O / (M d)`
/// (m), with `I_O` the moment of inertia about the pivot's axis (kg m²) and `d` the pivot's distance to the mass
/// centre (m); 2L/3 for a uniform rod of length L hung from one end.
pub fn centre_of_percussion(mass: f64, inertia_about_pivot: f64, distance: f64) -> f64 {
    inertia_about_pivot / (mass * distance)
}

/// The inverse of an inertia tensor (kg m²), 1/(kg m²), at any size the scene rules accept: the tensor is scaled by a
/// power of two near its largest entry before inverting (exactly, so an ordinary tensor's inverse keeps its bits). A
/// 3×3 inverse divides by the determinant, the cube of the entries, which overflows above about 1e100 kg m² and
/// underflows below 1e-100: the body would turn as if its inverse inertia were NaN, or as if it could not turn at all.
/// Zero for a singular tensor (which the scene rules refuse).
pub fn inverse_inertia(inertia: &Matrix3<f64>) -> Matrix3<f64> {
    let size = inertia.amax();
    if !(size > 0.0 && size.is_finite()) {
        return Matrix3::zeros();
    }
    let scale = 2f64.powi(size.log2().round() as i32);
    (inertia / scale).try_inverse().map_or_else(Matrix3::zeros, |inverse| inverse / scale)
}

/// Whether a symmetric 3×3 matrix is positive definite (Cholesky succeeds), for an inertia tensor.
pub fn positive_definite(matrix: &Matrix3<f64>) -> bool {
    matrix.iter().all(|x| x.is_finite()) && (matrix - matrix.transpose()).norm() <= 1e-12 * matrix.norm() && {
        matrix.cholesky().is_some()
    }
}

/// How an instantaneous impact with friction went (docs/references.md#rigid-bodies-with-several-contacts).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Slide {
    /// No friction.
    Smooth,
    /// The sticking impulse lay inside the friction cone: the contact points leave without slip.
    Sticks,
    /// It did not: the impulse slid, `J_n (n - mu s)` along the initial slip `s`.
    Slides,
}

/// The instantaneous impact of two rigid bodies at a point with Coulomb friction: what they carry away.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrictionalImpact {
    /// The impulse on body 2 (body 1 receives its opposite), N s.
    pub impulse: Vector3<f64>,
    pub slide: Slide,
    pub velocities_after: [Vector3<f64>; 2],
    pub spins_after: [Vector3<f64>; 2],
    /// The impulse each body's pivot passes to it, N s (zero for a free body).
    pub pivot_impulses: [Vector3<f64>; 2],
}

/// The inverse inertia of `body` at the contact point `point` (docs/references.md#rigid-bodies-with-several-contacts), 1/kg: the velocity change of
/// the body's material point at `point` per unit impulse there, `K = (1/M) 1 - [r]× I⁻¹ [r]×` with `r` from the mass
/// centre (about a pivot, `-[r_O]× I_O⁻¹ [r_O]×`); zero for an immovable body.
pub fn point_compliance(body: &RigidBody, point: &Vector3<f64>) -> Matrix3<f64> {
    if body.mass.is_infinite() {
        return Matrix3::zeros();
    }
    let arm = point - body.pivot.unwrap_or(body.centre);
    let cross = arm.cross_matrix();
    let turning = -cross * inverse_inertia(&body.inertia_about_pivot()) * cross;
    if body.pivot.is_some() { turning } else { turning + Matrix3::identity() / body.mass }
}

/// The instantaneous impact of `bodies` touching at `point` along the unit `normal` (body 1 to body 2), with Newton's
/// restitution `e` on the contact points' normal velocities and Coulomb friction `friction` (docs/references.md#rigid-bodies-with-several-contacts):
/// the sticking impulse brings the whole relative velocity of the points to `e v_n` along the normal; where it leaves
/// the friction cone, the impulse slides, `J_n (n - mu s)` along the initial slip `s` of body 2's point relative to
/// body 1's, with `J_n` from the normal restitution. With `friction = 0` it is [`eccentric_impact`]. `None` when the
/// points do not approach or neither body can move there.
pub fn frictional_impact(
    bodies: &[RigidBody; 2],
    point: &Vector3<f64>,
    normal: &Vector3<f64>,
    e: f64,
    friction: f64,
) -> Option<FrictionalImpact> {
    let relative = bodies[1].point_velocity(point) - bodies[0].point_velocity(point);
    let approach = -relative.dot(normal);
    let compliance = point_compliance(&bodies[0], point) + point_compliance(&bodies[1], point);
    let normal_compliance = normal.dot(&(compliance * normal));
    if !(approach > 0.0 && normal_compliance > 0.0) {
        return None;
    }
    let smooth = normal * ((1.0 + e) * approach / normal_compliance);
    let (impulse, slide) = if friction == 0.0 {
        (smooth, Slide::Smooth)
    } else {
        // The impulse that leaves the points without slip, separating at e v_n.
        let target = normal * (e * approach) - relative;
        let sticking = compliance.try_inverse().map(|inverse| inverse * target);
        let inside = |p: &Vector3<f64>| {
            let along = p.dot(normal);
            along >= 0.0 && (p - normal * along).norm() <= friction * along * (1.0 + 1e-12)
        };
        match sticking {
            Some(p) if inside(&p) => (p, Slide::Sticks),
            _ => {
                // The slip of body 2's point relative to body 1's; without one, the way the sticking impulse would
                // have rubbed.
                let across = relative - normal * relative.dot(normal);
                let direction = if across.norm() > 0.0 {
                    across / across.norm()
                } else {
                    let rub = sticking.map_or(Vector3::zeros(), |p| -(p - normal * p.dot(normal)));
                    if rub.norm() > 0.0 { rub / rub.norm() } else { Vector3::zeros() }
                };
                let line = normal - direction * friction;
                let along = normal.dot(&(compliance * line));
                if along > 0.0 {
                    (line * ((1.0 + e) * approach / along), Slide::Slides)
                } else {
                    (sticking.unwrap_or(smooth), Slide::Sticks)
                }
            }
        }
    };
    let (v1, w1, p1) = bodies[0].after(&-impulse, point);
    let (v2, w2, p2) = bodies[1].after(&impulse, point);
    Some(FrictionalImpact {
        impulse,
        slide,
        velocities_after: [v1, v2],
        spins_after: [w1, w2],
        pivot_impulses: [p1, p2],
    })
}
