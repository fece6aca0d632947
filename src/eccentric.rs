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
