//! A body taking part in an impact: mass, size, material and initial motion.
//!
//! Walls and immovable bodies are the infinite limits (`mass = inf`, `radius = inf`), not special cases:
//! every formula below is written so that an infinite value drops out (1/inf = 0).

use nalgebra::{Matrix3, UnitQuaternion, Vector3};

/// One body, as the scene describes it (SI units).
#[derive(Debug, Clone, PartialEq)]
pub struct Body {
    /// Display name ("body 1" by default).
    pub name: String,
    /// Mass in kg; `f64::INFINITY` for an immovable body (derived from `density` when the scene gives that).
    pub mass: f64,
    /// The scene's `density` in kg/m^3, when the mass comes from it ((4/3) pi r^3 density).
    pub density: Option<f64>,
    /// Radius in m; `f64::INFINITY` for a flat wall.
    pub radius: f64,
    /// Velocity of the centre of mass before contact, m/s.
    pub velocity: Vector3<f64>,
    /// Position of the centre (or of a point of the wall's plane), m, when the scene gives positions.
    pub position: Option<Vector3<f64>>,
    /// Angular velocity before contact, rad/s (right-handed).
    pub angular_velocity: Vector3<f64>,
    /// Moment of inertia about any axis through the centre, kg m²: the scene's `inertia`, or (2/5) m r² for a solid
    /// sphere; infinite for an immovable body and for a flat body (a wall translates but does not rotate).
    pub inertia: f64,
    /// The scene's `inertia`, when given as one number (otherwise `inertia` is the solid sphere's, or the mean of
    /// `inertia_tensor`'s principal moments).
    pub inertia_given: Option<f64>,
    /// The scene's `inertia` when given as three principal moments or a 3×3 tensor: kg m², about the mass centre, in
    /// scene axes at t = 0 (symmetric positive definite: the rules check it).
    pub inertia_tensor: Option<Matrix3<f64>>,
    /// The centre of the body's contact sphere relative to its mass centre, m, in scene axes at t = 0 (zero: the
    /// contact sphere is centred on the mass centre). `position` stays the mass centre.
    pub contact_offset: Vector3<f64>,
    /// A point of the body fixed in space, m (scene coordinates): the body can only turn about it.
    pub pivot: Option<Vector3<f64>>,
    /// Young's modulus in Pa (`f64::INFINITY` for a rigid body); needed only for Hertz stiffness.
    pub young: Option<f64>,
    /// Poisson's ratio; needed only for Hertz stiffness.
    pub poisson: Option<f64>,
    /// Yield stress Y in Pa (`f64::INFINITY` for a body that never yields): plastic flow begins under a contact
    /// whose peak pressure reaches 1.6 Y (Johnson, Contact Mechanics, ch. 11). Used by the `elastic` verdict and by
    /// the `thornton` law.
    pub yield_stress: Option<f64>,
    /// The scene's `[[bodies.spheres]]`: the contact spheres of a clump, fixed to the body (empty for a body of one
    /// `radius`, whose one sphere sits at its `contact_offset`). A clump's `radius` is its bounding radius, the
    /// largest |offset| + r (docs/world.md#rigid-bodies).
    pub spheres: Vec<ContactSphere>,
}

/// One contact sphere of a body: its centre relative to the mass centre (m, scene axes at t = 0) and its radius (m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactSphere {
    pub offset: Vector3<f64>,
    pub radius: f64,
}

impl Body {
    /// Re-derives what follows from the written values: the mass from `density` and the radius, the inertia of a
    /// solid sphere unless one was given. (A sweep that changes a radius or a mass calls this.)
    pub fn resolve(&mut self) {
        if !self.spheres.is_empty() {
            self.radius = self.spheres.iter().map(|s| length(&s.offset) + s.radius).fold(0.0, f64::max);
        }
        if let Some(density) = self.density {
            self.mass = density * 4.0 / 3.0 * std::f64::consts::PI * self.radius.powi(3);
        }
        self.inertia = match (self.inertia_tensor, self.inertia_given) {
            (Some(tensor), _) => tensor.trace() / 3.0,
            (None, Some(inertia)) => inertia,
            (None, None) => Body::solid_sphere_inertia(self.mass, self.radius),
        };
    }

    /// Whether a contact sphere of the body is off its mass centre (`contact_offset`, several `[[bodies.spheres]]`, or
    /// one off the centre): the body is not the sphere it touches with.
    pub fn is_off_centre(&self) -> bool {
        self.contact_offset != Vector3::zeros()
            || self.spheres.len() > 1
            || self.spheres.iter().any(|s| s.offset != Vector3::zeros())
    }

    /// Whether the body is a rigid body that a sphere's model does not describe: its contact sphere off its mass
    /// centre, a pivot, or an inertia that is not the same about every axis. Such a body runs through the rigid-body
    /// model (`dynamics::rigid`), whose contact point moves with the body's orientation.
    pub fn is_eccentric(&self) -> bool {
        let anisotropic =
            self.inertia_tensor.is_some_and(|t| (t - Matrix3::identity() * (t.trace() / 3.0)).norm() > 0.0);
        self.is_off_centre() || self.pivot.is_some() || anisotropic
    }

    /// The body's contact spheres (offsets from the mass centre in scene axes at t = 0, m; radii, m): its
    /// `[[bodies.spheres]]`, or the one sphere of its `radius` at its `contact_offset` (a flat body's: radius inf).
    pub fn contact_spheres(&self) -> Vec<ContactSphere> {
        if self.spheres.is_empty() {
            vec![ContactSphere { offset: self.contact_offset, radius: self.radius }]
        } else {
            self.spheres.clone()
        }
    }

    /// Whether, in a world, the body's orientation is integrated: a movable body that turns (finite mass and inertia)
    /// and is eccentric — a sphere off its mass centre, several spheres, a pivot, or an inertia that differs between
    /// axes. Every other body is a sphere whose orientation nobody reads (docs/world.md#rigid-bodies).
    pub fn is_rigid(&self) -> bool {
        !self.is_immovable() && self.rotates() && self.is_eccentric()
    }

    /// The inertia tensor about the mass centre in scene axes at t = 0, kg m²: the scene's tensor or moments, or the
    /// scalar `inertia` on every axis (infinite for a body that does not rotate).
    pub fn inertia_matrix(&self) -> Matrix3<f64> {
        self.inertia_tensor.unwrap_or_else(|| Matrix3::identity() * self.inertia)
    }

    /// 1/m in 1/kg: zero for an immovable body.
    pub fn inverse_mass(&self) -> f64 {
        1.0 / self.mass
    }

    /// Whether the body cannot be moved by the contact force.
    pub fn is_immovable(&self) -> bool {
        self.mass.is_infinite()
    }

    /// Whether the body is a flat wall (infinite radius).
    pub fn is_flat(&self) -> bool {
        self.radius.is_infinite()
    }

    /// Moment of inertia of a solid sphere of this mass and radius, (2/5) m r², in kg m²; infinite for walls and
    /// immovable bodies (the default of the scene's `inertia`).
    pub fn solid_sphere_inertia(mass: f64, radius: f64) -> f64 {
        if mass.is_infinite() || radius.is_infinite() { f64::INFINITY } else { 0.4 * mass * radius * radius }
    }

    /// 1/I in 1/(kg m²): zero for a body that does not rotate (immovable or flat).
    pub fn inverse_inertia(&self) -> f64 {
        1.0 / self.inertia
    }

    /// Whether the contact can change the body's spin (finite mass, finite radius, finite inertia).
    pub fn rotates(&self) -> bool {
        self.inertia.is_finite()
    }

    /// Kinetic energy (translation and rotation) in J for a velocity and angular velocity, in the body's orientation
    /// at t = 0; 0 for an immovable body.
    pub fn kinetic_energy(&self, velocity: &Vector3<f64>, angular_velocity: &Vector3<f64>) -> f64 {
        self.kinetic_energy_turned(velocity, angular_velocity, &UnitQuaternion::identity())
    }

    /// Kinetic energy in J with the body turned by `rotation` from its orientation at t = 0 (its inertia tensor turns
    /// with it: `(1/2) ω·R I Rᵀ ω`); 0 for an immovable body.
    pub fn kinetic_energy_turned(
        &self,
        velocity: &Vector3<f64>,
        angular_velocity: &Vector3<f64>,
        rotation: &UnitQuaternion<f64>,
    ) -> f64 {
        if self.is_immovable() {
            return 0.0;
        }
        let translation = 0.5 * self.mass * velocity.norm_squared();
        let spin = angular_velocity.norm_squared();
        // A flat body cannot spin in a scene (validation forbids it); 0 * inf is avoided.
        let rotation = match self.inertia_tensor {
            _ if spin == 0.0 => 0.0,
            Some(tensor) => {
                let local = rotation.inverse_transform_vector(angular_velocity);
                0.5 * local.dot(&(tensor * local))
            }
            None => 0.5 * self.inertia * spin,
        };
        translation + rotation
    }

    /// Contribution (1 - nu²)/E to the effective compliance 1/E*, in 1/Pa; zero for a rigid body.
    pub fn compliance(&self) -> Option<f64> {
        let young = self.young?;
        if young.is_infinite() {
            return Some(0.0);
        }
        let poisson = self.poisson?;
        Some((1.0 - poisson * poisson) / young)
    }
}

/// The length of `v` without overflow or underflow in its squares.
fn length(v: &Vector3<f64>) -> f64 {
    let largest = v.amax();
    if largest == 0.0 || !largest.is_finite() { largest } else { largest * (v / largest).norm() }
}

/// Velocities of two bodies after a normal impulse `impulse` (N s, compressive positive) along the unit `normal`
/// (body 1 -> body 2): body 1 loses impulse/m1 along the normal, body 2 gains impulse/m2 (an immovable body keeps
/// its velocity).
pub fn after_normal_impulse(bodies: &[Body; 2], normal: &Vector3<f64>, impulse: f64) -> [Vector3<f64>; 2] {
    let [a, b] = bodies;
    [a.velocity - normal * (impulse * a.inverse_mass()), b.velocity + normal * (impulse * b.inverse_mass())]
}
