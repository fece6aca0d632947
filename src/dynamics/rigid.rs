//! Two rigid bodies through one contact, smooth or frictional, each struck off its centre or turning about a pivot: the contact
//! sphere of a body sits at its `contact_offset` from the mass centre and moves with the body's orientation, which
//! is integrated through the contact (docs/rigid.md). The spheres' models (`normal`, `pair`) are its special case
//! of a zero offset, no pivot and the same inertia about every axis.
//!
//! Each body turns about its origin O — its mass centre, or its pivot — and its contact sphere's centre is
//! `c = O + R a`, with `a` from O to the sphere's centre at first contact and `R` the rotation since then. The
//! normal force acts along the line of the spheres' centres (or the wall's normal through the sphere's centre), so
//! its moment about O is `(R a) × F`. Per body the state holds:
//! - the contact's impulse on it, in the impulse unit (a free body's velocity follows from it);
//! - its rotation since first contact as a quaternion (w, v), the vector part scaled by `|a|/L`, so that the
//!   integrator's absolute tolerance on it is a tolerance on the contact sphere's displacement in L;
//! - the change of its angular momentum about O, in m* v0 L, scaled by `L/|a|` (O(1)).
//!
//! and one displacement for both: of body 2's origin relative to body 1's since first contact, in L, integrated from
//! the relative velocity (so that the penetration is never the difference of two large displacements); a pivot
//! does not move, so a pivoted body adds nothing to it.
//!
//! The angular velocity is `ω = R I_O⁻¹ Rᵀ h` (the inertia tensor turns with the body); Euler's equations in the
//! scene's frame are `dh/dt = (R a) × F_n + (R a + r_i n_i) × F_t`, and the quaternion follows `q' = ½ (0, ω) ⊗ q`.
//! A pivot passes whatever keeps it still: its impulse is `M Δv_cm - ∫F dt`, read at each snapshot from the momentum.
//!
//! Friction is the spheres' tangential contact ([`super::contact::Tangential`]: the spring, its Coulomb cap, its
//! damping and options, the stick–slip switches as events), riding on the contact point: the point of each contact
//! sphere where the contact points sit in the spheres' model (`r_i` from the sphere's centre towards the other body,
//! the overlap shared in the ratio of the radii), whose velocity is `v + ω × r` from the body's origin. The slip is
//! the relative velocity of these points across the normal; the tangential force acts at them, so its moment about
//! each body's origin turns the body's spin with the body's turned inertia, and it pushes a free body's mass centre
//! (a pivot passes what keeps the pivot still, as for the normal force). The spring, the tangential work and the
//! mode are three more states, as in [`super::pair`].

use super::contact::{Kinematics, Mode, Shape, Tangential, set_vector, vector};
use super::{ContactModel, Normal, Scales, Snapshot, dissipation_scale, unit_or_one};
use crate::body::Body;
use crate::integrate::{Model, State};
use crate::law::ContactLaw;
use crate::setup::Setup;
use nalgebra::{Matrix3, Quaternion, UnitQuaternion, Vector3};

/// Size of the state.
pub const SIZE: usize = 32;

/// Where each scaled quantity sits in the state; a body's block starts at [`index::BODY`]`[i]`.
pub mod index {
    /// The start of each body's block.
    pub const BODY: [usize; 2] = [0, 10];
    /// Within a block: the contact's impulse on the body, in the impulse unit m* v0.
    pub const IMPULSE: usize = 0;
    /// Within a block: the vector part of the rotation quaternion, times |a|/L.
    pub const TURN: usize = 3;
    /// Within a block: the scalar part of the rotation quaternion.
    pub const TURN_SCALAR: usize = 6;
    /// Within a block: the change of angular momentum about the body's origin, in m* v0 |a|.
    pub const MOMENTUM: usize = 7;
    /// Displacement of body 2's origin relative to body 1's since first contact, in L (a pivot's is zero).
    pub const DISPLACEMENT: usize = 20;
    /// ∫ Fn dt, in the impulse unit.
    pub const NORMAL_IMPULSE: usize = 23;
    /// ∫ Fn d' dt, in the energy unit.
    pub const NORMAL_WORK: usize = 24;
    /// ∫ F_dissipative d' dt, in the energy unit times the damping's size.
    pub const DISSIPATED: usize = 25;
    /// For a yielding law (no damping: it takes this slot), the deepest penetration so far, in L.
    pub const DEEPEST: usize = 25;
    /// Work of an immovable body on the movable one, in the energy unit.
    pub const IMMOVABLE_WORK: usize = 26;
    /// Tangential spring force (on body 1), in F0; while sliding its direction alone, at the length
    /// [`crate::dynamics::contact::SLIDE_CARRIER`] (the force is the Coulomb cap along it).
    pub const SPRING: usize = 27;
    /// ∫ Ft·slip dt, in the energy unit times mu.
    pub const TANGENTIAL_WORK: usize = 30;
    /// The tangential mode, constant between switches: 0 sticking, 1 sliding, 2 sliding while the normal force pulls.
    pub const MODE: usize = 31;
}

/// Scaled penetration at which the initial stick-or-slip is read off the leading terms (as in the spheres' model).
const PROBE: f64 = 1e-6;

/// The tangential mode a state is in.
fn mode(y: &State<SIZE>) -> Mode {
    Mode::of_slot(y[index::MODE])
}

fn set_mode(y: &mut State<SIZE>, mode: Mode) {
    y[index::MODE] = mode.slot();
}

/// Scaled penetration below zero that still counts as the edge of the contact (see the normal model).
const EDGE: f64 = super::normal::EDGE;

/// One body as the model sees it (scaled).
#[derive(Debug, Clone, Copy)]
struct Part {
    /// m*/M: how the scaled impulse changes the scaled velocity (0 for an immovable body).
    share: f64,
    /// Whether the body turns under the contact (finite mass and inertia, not flat).
    turns: bool,
    /// Whether it turns about a pivot (its mass centre then follows the rotation).
    pivoted: bool,
    /// From the origin (mass centre or pivot) to the contact sphere's centre at first contact, in L.
    arm: Vector3<f64>,
    /// From the origin to the mass centre at first contact, in L (zero for a free body).
    centre: Vector3<f64>,
    /// |a|/L, at least the sphere's radius in L: the scale of the turn and momentum states.
    reach: f64,
    /// m* L² I_O⁻¹ (scene axes at first contact): the scaled angular momentum's scaled angular velocity.
    gain: Matrix3<f64>,
    /// Angular momentum about the origin at first contact, in m* v0 L.
    momentum: Vector3<f64>,
    /// Velocity at first contact, in v0.
    velocity: Vector3<f64>,
    /// The contact sphere's radius, in L (zero for a flat body): the contact point's distance from its centre.
    radius: f64,
    /// The constant spin of a body that does not turn under the contact (an immovable sphere), ω T.
    fixed_spin: Vector3<f64>,
}

/// One body's motion at one instant (scaled).
#[derive(Debug, Clone, Copy)]
struct Motion {
    rotation: UnitQuaternion<f64>,
    /// (R - 1) a: the contact sphere's displacement by the turn, in L.
    turned: Vector3<f64>,
    /// R a, in L.
    arm: Vector3<f64>,
    /// ω T.
    spin: Vector3<f64>,
    /// Angular momentum about the origin, in m* v0 L.
    momentum: Vector3<f64>,
    /// The mass centre's velocity, in v0.
    velocity: Vector3<f64>,
    /// The contact sphere's centre's velocity, in v0.
    sphere_velocity: Vector3<f64>,
}

/// The rigid-body contact model.
#[derive(Debug)]
pub struct RigidContact<'a> {
    law: ContactLaw,
    scales: Scales,
    shape: Shape,
    parts: [Part; 2],
    dissipation_scale: f64,
    /// The tangential contact (`None`: smooth), in the contact's scales.
    tangential: Option<Tangential>,
    /// The unit of the tangential-work state: mu, or 1 for a smooth contact.
    friction_scale: f64,
    /// The direction of the contact points' slip at first contact (zero without friction or without slip).
    slip_direction: Vector3<f64>,
    bodies: &'a [Body; 2],
    setup: &'a Setup,
}

/// Everything the derivative computes at one state (the force's rate, which only the force-peak event and the
/// stick–slip switches need, is [`RigidContact::normal_force_rate`]'s).
struct Evaluation {
    motions: [Motion; 2],
    normal: Vector3<f64>,
    /// dn/dt, in 1/T.
    normal_rate: Vector3<f64>,
    /// The spheres' centres' relative velocity, in v0.
    relative_velocity: Vector3<f64>,
    penetration: f64,
    rate: f64,
    /// The penetration the force sees (the located edge from inside), in L, and the deepest so far, m.
    seen: f64,
    deepest: f64,
    elastic: f64,
    dissipative: f64,
    /// The contact points' kinematics as the tangential law reads them (the slip of body 1's point relative to
    /// body 2's, in v0).
    kinematics: Kinematics,
    /// The tangential spring state, kept in the tangent plane (while sliding, the direction it carries:
    /// `Tangential::carried`).
    spring: Vector3<f64>,
    /// The tangential force on body 1 (scaled).
    tangential: Vector3<f64>,
    /// dT/dt of the spring.
    spring_rate: Vector3<f64>,
}

impl<'a> RigidContact<'a> {
    /// The contact of a resolved scene whose motion is [`crate::setup::Motion::Rigid`].
    pub fn new(bodies: &'a [Body; 2], setup: &'a Setup) -> RigidContact<'a> {
        let s = setup.scales;
        let [a, b] = bodies;
        let shape = if a.is_flat() || b.is_flat() {
            Shape::Wall { normal: setup.normal, sphere: if a.is_flat() { 1 } else { 0 } }
        } else {
            let reach = (a.radius + b.radius) / s.length;
            Shape::Spheres { reach, contact_vector: setup.normal * reach }
        };
        let part = |i: usize| {
            let body = &bodies[i];
            let turns = body.rotates() && body.mass.is_finite();
            let position = setup.positions[i];
            let origin = body.pivot.unwrap_or(position);
            let arm =
                if body.is_flat() { Vector3::zeros() } else { (position + body.contact_offset - origin) / s.length };
            let rigid = crate::setup::rigid_body(body, position);
            let inertia = rigid.inertia_about_pivot();
            let gain = if turns {
                // m* L² / I, multiplied in an order that keeps each factor inside double precision: m* L² alone
                // underflows for a body of 1e-180 kg, whose m*/I is still of the order of its size's inverse square.
                crate::eccentric::inverse_inertia(&inertia) * setup.effective_mass * s.length * s.length
            } else {
                Matrix3::zeros()
            };
            let momentum = if turns {
                inertia * body.angular_velocity / setup.effective_mass / s.speed / s.length
            } else {
                Vector3::zeros()
            };
            let radius = if body.is_flat() { 0.0 } else { body.radius / s.length };
            let fixed_spin = if turns || body.is_flat() { Vector3::zeros() } else { body.angular_velocity * s.time };
            Part {
                share: setup.effective_mass * body.inverse_mass(),
                turns,
                pivoted: body.pivot.is_some(),
                arm,
                centre: (position - origin) / s.length,
                reach: arm.norm().max(radius).max(1.0),
                gain,
                momentum,
                velocity: body.velocity / s.speed,
                radius,
                fixed_spin,
            }
        };
        let tangential = setup.friction.map(|f| Tangential::from_friction(&f, s.length, s.force, setup.effective_mass));
        let slip = setup.initial_slip;
        let slip_direction =
            if tangential.is_some() && slip.norm() > 0.0 { slip / slip.norm() } else { Vector3::zeros() };
        RigidContact {
            law: setup.law,
            scales: s,
            shape,
            parts: [part(0), part(1)],
            dissipation_scale: dissipation_scale(&setup.law, &s),
            friction_scale: unit_or_one(tangential.map_or(0.0, |t| t.friction)),
            tangential,
            slip_direction,
            bodies,
            setup,
        }
    }

    /// Body `i`'s motion in state `y`.
    fn motion(&self, i: usize, y: &State<SIZE>) -> Motion {
        let p = &self.parts[i];
        let at = index::BODY[i];
        if !p.turns {
            let velocity = p.velocity + vector(y, at + index::IMPULSE) * p.share;
            return Motion {
                rotation: UnitQuaternion::identity(),
                turned: Vector3::zeros(),
                arm: p.arm,
                spin: Vector3::zeros(),
                momentum: Vector3::zeros(),
                velocity,
                sphere_velocity: velocity,
            };
        }
        let turn = vector(y, at + index::TURN) / p.reach;
        let w = y[at + index::TURN_SCALAR];
        let size = w * w + turn.norm_squared();
        // R a = a + (2 w (v × a) + 2 v × (v × a)) / |q|²: the turn's displacement without the cancellation of R a - a.
        let across = turn.cross(&p.arm);
        let turned = (across * (2.0 * w) + turn.cross(&across) * 2.0) / size;
        let rotation = UnitQuaternion::new_normalize(Quaternion::new(w, turn.x, turn.y, turn.z));
        let momentum = p.momentum + vector(y, at + index::MOMENTUM) * p.reach;
        let matrix = rotation.to_rotation_matrix();
        let spin = matrix * (p.gain * (matrix.transpose() * momentum));
        let arm = p.arm + turned;
        let velocity = if p.pivoted {
            spin.cross(&(matrix * p.centre))
        } else {
            p.velocity + vector(y, at + index::IMPULSE) * p.share
        };
        Motion {
            rotation,
            turned,
            arm,
            spin,
            momentum,
            velocity,
            sphere_velocity: velocity + spin.cross(&(arm - matrix * p.centre)),
        }
    }

    /// The normal contact's bookkeeping at state `y` evaluated as `e`.
    fn normal<'b>(&'b self, y: &State<SIZE>, e: &Evaluation) -> Normal<'b> {
        Normal {
            law: &self.law,
            scales: &self.scales,
            d: e.penetration,
            rate: e.rate,
            deepest_state: y[index::DEEPEST],
        }
    }

    /// The velocity of body `i`'s origin (its mass centre, or its pivot's zero), in v0.
    fn origin_velocity(&self, i: usize, motion: &Motion) -> Vector3<f64> {
        if self.parts[i].pivoted { Vector3::zeros() } else { motion.velocity }
    }

    fn evaluate(&self, y: &State<SIZE>) -> Evaluation {
        let s = &self.scales;
        let motions = [self.motion(0, y), self.motion(1, y)];
        let [m1, m2] = &motions;
        // The spheres' centres relative to first contact: the origins' relative displacement and the turns.
        let displacement = vector(y, index::DISPLACEMENT) + m2.turned - m1.turned;
        let relative_velocity = m2.sphere_velocity - m1.sphere_velocity;
        // The spins as the contact's kinematics take them, ω r / v0 with r the contact sphere's radius: the contact
        // points' velocities are the spheres' centres' and ω × (the arm from the centre to the point).
        let spins = [0, 1].map(|i| {
            let p = &self.parts[i];
            let spin = if p.turns { motions[i].spin } else { p.fixed_spin };
            spin * p.radius
        });
        let k = self.shape.kinematics(&displacement, &relative_velocity, &spins);
        let d = if k.penetration > -EDGE { k.penetration.max(0.0) } else { k.penetration };
        let deepest = y[index::DEEPEST].max(d) * s.length;
        let parts = self.law.split_force_after(d * s.length, k.rate * s.speed, deepest);
        let (elastic, dissipative) = (parts.elastic / s.force, parts.dissipative / s.force);
        let normal_force = elastic + dissipative;
        let raw_spring = vector(y, index::SPRING);
        let spring = raw_spring - k.normal * raw_spring.dot(&k.normal);
        // (Neither the tangential force nor the spring's rate depends on the normal force's rate, which depends on the
        // tangential force through its moments.)
        let (tangential, spring_rate) = match &self.tangential {
            Some(t) => {
                let f = t.evaluate(mode(y), &spring, &k, normal_force);
                (f.force, f.spring_rate)
            }
            None => (Vector3::zeros(), Vector3::zeros()),
        };
        Evaluation {
            motions,
            normal: k.normal,
            normal_rate: k.normal_rate,
            relative_velocity,
            penetration: k.penetration,
            rate: k.rate,
            seen: d,
            deepest,
            elastic,
            dissipative,
            kinematics: k,
            spring,
            tangential,
            spring_rate,
        }
    }

    /// Body `i`'s contact point's arm from its origin (mass centre or pivot), in L: its sphere's centre's, and from
    /// the centre to the point (the contact's arm over the radius, times the radius).
    fn lever(&self, i: usize, e: &Evaluation) -> Vector3<f64> {
        e.motions[i].arm + e.kinematics.arms[i] * self.parts[i].radius
    }

    /// The force (scaled) on body `i` and its moment about the body's origin: the normal force along the normal
    /// through the sphere's centre, the tangential force at the contact point (on body 1; its opposite on body 2).
    fn loads(&self, i: usize, e: &Evaluation) -> (Vector3<f64>, Vector3<f64>) {
        let sign = if i == 0 { -1.0 } else { 1.0 };
        let normal = e.normal * (sign * (e.elastic + e.dissipative));
        let tangential = e.tangential * -sign;
        let torque = e.motions[i].arm.cross(&normal) + self.lever(i, e).cross(&tangential);
        (normal + tangential, torque)
    }

    /// The normal force's rate dF/dt (scaled) at an evaluated state: F_d d' + F_v d'', with
    /// d'' = -(dw/dt·n + w·dn/dt), dw/dt the spheres' centres' relative acceleration (Euler and centripetal terms;
    /// the tangential force's moments turn the bodies, and so move the spheres' centres along the normal too).
    fn normal_force_rate(&self, e: &Evaluation) -> f64 {
        let s = &self.scales;
        let acceleration = |i: usize| {
            let (p, m) = (&self.parts[i], &e.motions[i]);
            let (on, torque) = self.loads(i, e);
            let linear = on * p.share;
            if !p.turns {
                return linear;
            }
            let matrix = m.rotation.to_rotation_matrix();
            let angular = matrix * (p.gain * (matrix.transpose() * (torque - m.spin.cross(&m.momentum))));
            let lever = m.arm - matrix * p.centre;
            let centre = if p.pivoted {
                let to_centre = matrix * p.centre;
                angular.cross(&to_centre) + m.spin.cross(&m.spin.cross(&to_centre))
            } else {
                linear
            };
            centre + angular.cross(&lever) + m.spin.cross(&m.spin.cross(&lever))
        };
        let relative_acceleration = acceleration(1) - acceleration(0);
        let rate_rate = -(relative_acceleration.dot(&e.normal) + e.relative_velocity.dot(&e.normal_rate));
        let (by_penetration, by_rate) = self.law.force_gradient_after(e.seen * s.length, e.rate * s.speed, e.deepest);
        (by_penetration * s.length * e.rate + by_rate * s.speed * rate_rate) / s.force
    }
}

impl Model<SIZE> for RigidContact<'_> {
    fn derivative(&self, _t: f64, y: &State<SIZE>, dy: &mut State<SIZE>) {
        let e = self.evaluate(y);
        let force = e.elastic + e.dissipative;
        let mut immovable_work = 0.0;
        for i in 0..2 {
            let (p, m, at) = (&self.parts[i], &e.motions[i], index::BODY[i]);
            let (on, torque) = self.loads(i, &e);
            set_vector(dy, at + index::IMPULSE, &on);
            if p.turns {
                let turn = vector(y, at + index::TURN) / p.reach;
                let w = y[at + index::TURN_SCALAR];
                set_vector(dy, at + index::TURN, &((m.spin * w + m.spin.cross(&turn)) * (0.5 * p.reach)));
                dy[at + index::TURN_SCALAR] = -0.5 * m.spin.dot(&turn);
                set_vector(dy, at + index::MOMENTUM, &(torque / p.reach));
            } else {
                set_vector(dy, at + index::TURN, &Vector3::zeros());
                dy[at + index::TURN_SCALAR] = 0.0;
                set_vector(dy, at + index::MOMENTUM, &Vector3::zeros());
            }
            if self.bodies[i].is_immovable() {
                // Power the contact feeds into an immovable body, with the opposite sign: the work it does on the
                // other. Its spin (constant) meets the tangential force's moment about its sphere's centre.
                let velocity = self.bodies[i].velocity / self.scales.speed;
                let sign = if i == 0 { 1.0 } else { -1.0 };
                let about_centre = (e.kinematics.arms[i] * p.radius).cross(&(e.tangential * sign));
                immovable_work -= on.dot(&velocity) + about_centre.dot(&p.fixed_spin);
            }
        }
        let relative = self.origin_velocity(1, &e.motions[1]) - self.origin_velocity(0, &e.motions[0]);
        set_vector(dy, index::DISPLACEMENT, &relative);
        dy[index::NORMAL_IMPULSE] = force;
        dy[index::NORMAL_WORK] = force * e.rate;
        dy[index::DISSIPATED] = self.normal(y, &e).dissipation_rate(e.dissipative, self.dissipation_scale);
        dy[index::IMMOVABLE_WORK] = immovable_work;
        set_vector(dy, index::SPRING, &e.spring_rate);
        dy[index::TANGENTIAL_WORK] = e.tangential.dot(&e.kinematics.slip) / self.friction_scale;
        dy[index::MODE] = 0.0;
    }
}

impl ContactModel<SIZE> for RigidContact<'_> {
    fn scales(&self) -> &Scales {
        &self.scales
    }

    /// A tenth, as the 3-D spheres' model: the energies sum many separately integrated states.
    fn tolerance_factor(&self) -> f64 {
        0.1 * self.law.tolerance_factor()
    }

    fn start(&self) -> State<SIZE> {
        let mut y = State::<SIZE>::zeros();
        for at in index::BODY {
            y[at + index::TURN_SCALAR] = 1.0;
        }
        if let Some(t) = &self.tangential {
            // As the spheres' model: stick or slip from the leading terms at a tiny penetration.
            let s = &self.scales;
            let slip = self.setup.initial_slip.norm() / s.speed;
            let contact_force = self.law.force(0.0, s.speed) / s.force;
            let probe_force = self.law.force(PROBE * s.length, s.speed) / s.force;
            let mode = t.initial_mode(slip, 1.0, PROBE, contact_force, probe_force);
            set_mode(&mut y, mode);
            // A slide from first contact carries the direction against the slip.
            let slip = self.evaluate(&y).kinematics.slip;
            set_vector(&mut y, index::SPRING, &Tangential::carrier(mode, &Vector3::zeros(), &slip));
        }
        y
    }

    fn penetration(&self, y: &State<SIZE>) -> f64 {
        self.evaluate(y).penetration
    }

    fn rate(&self, y: &State<SIZE>) -> f64 {
        self.evaluate(y).rate
    }

    fn force(&self, y: &State<SIZE>) -> f64 {
        let e = self.evaluate(y);
        e.elastic + e.dissipative
    }

    fn force_rate(&self, y: &State<SIZE>) -> f64 {
        let e = self.evaluate(y);
        self.normal_force_rate(&e)
    }

    fn separation_force(&self, y: &State<SIZE>) -> f64 {
        self.normal(y, &self.evaluate(y)).separation()
    }

    fn uncut_force(&self, y: &State<SIZE>) -> Option<f64> {
        self.normal(y, &self.evaluate(y)).uncut()
    }

    fn switch_function(&self, y: &State<SIZE>) -> Option<f64> {
        let t = self.tangential.as_ref()?;
        let e = self.evaluate(y);
        let force = e.elastic + e.dissipative;
        // (The normal force's rate only where a switch is judged: the derivative needs none.)
        let rate = self.normal_force_rate(&e);
        Some(t.carried_switch_function(mode(y), &e.spring, &e.kinematics, force, rate, e.elastic))
    }

    fn switch(&self, y: &mut State<SIZE>) {
        let Some(t) = &self.tangential else { return };
        let e = self.evaluate(y);
        let force = e.elastic + e.dissipative;
        let (next, spring) =
            t.carried_next_mode(mode(y), &e.spring, &e.kinematics, force, self.normal_force_rate(&e), e.elastic);
        set_vector(y, index::SPRING, &spring);
        set_mode(y, next);
    }

    fn sliding(&self, y: &State<SIZE>) -> bool {
        self.tangential.is_some() && mode(y).is_sliding()
    }

    fn slip_along_start(&self, y: &State<SIZE>) -> Option<f64> {
        (self.slip_direction != Vector3::zeros()).then(|| self.evaluate(y).kinematics.slip.dot(&self.slip_direction))
    }

    fn tension_kink(&self) -> bool {
        self.tangential.is_some_and(|t| t.cap == crate::scene::FrictionCap::Compressive)
    }

    fn kinks(&self, compressing: bool) -> crate::law::Kinks {
        self.law.kinks(compressing).scaled(self.scales.length)
    }

    fn snapshot(&self, t: f64, y: &State<SIZE>) -> Snapshot {
        let s = &self.scales;
        let e = self.evaluate(y);
        let time = t * s.time;
        let force = e.elastic + e.dissipative;
        // The free bodies' displacement beyond their free flight is shared in the ratio of their inverse masses (equal
        // and opposite contact impulses): the relative displacement beyond the free relative flight, split.
        let flight = |i: usize| if self.parts[i].pivoted { Vector3::zeros() } else { self.parts[i].velocity };
        let shares = |i: usize| if self.parts[i].pivoted { 0.0 } else { self.parts[i].share };
        let total = shares(0) + shares(1);
        let beyond = vector(y, index::DISPLACEMENT) - (flight(1) - flight(0)) * t;
        let pushed = if total > 0.0 { beyond * (s.length / total) } else { Vector3::zeros() };
        let part = |i: usize| {
            let (p, m, body) = (&self.parts[i], &e.motions[i], &self.bodies[i]);
            let sign = if i == 0 { -1.0 } else { 1.0 };
            let start = self.setup.positions[i];
            let position = if p.pivoted {
                body.pivot.unwrap_or_default() + m.rotation * p.centre * s.length
            } else {
                start + body.velocity * time + pushed * (sign * shares(i))
            };
            let velocity = m.velocity * s.speed;
            let spin = if p.turns { m.spin / s.time } else { body.angular_velocity };
            // What the pivot passed: the momentum gained beyond the contact's impulse.
            let pivot = if p.pivoted {
                (velocity - body.velocity) * body.mass - vector(y, index::BODY[i] + index::IMPULSE) * s.impulse
            } else {
                Vector3::zeros()
            };
            (position, velocity, spin, m.rotation, pivot)
        };
        let (a, b) = (part(0), part(1));
        let (elastic_energy, dissipated_normal) =
            self.normal(y, &e).energies(y[index::NORMAL_WORK], y[index::DISSIPATED], self.dissipation_scale);
        // The spring stores at most what the Coulomb cap lets it hold (as in the spheres' model).
        let tangential_elastic = self.tangential.map_or(0.0, |t| {
            t.stored_energy(mode(y), &t.carried(mode(y), &e.spring, &e.kinematics.slip, force), e.penetration, force)
        });
        Snapshot {
            time,
            penetration: e.penetration * s.length,
            rate: e.rate * s.speed,
            normal_force: force * s.force,
            normal: e.normal,
            tangential_force: e.tangential * s.force,
            slip: e.kinematics.slip * s.speed,
            velocities: [a.1, b.1],
            spins: [a.2, b.2],
            positions: [a.0, b.0],
            normal_impulse: y[index::NORMAL_IMPULSE] * s.impulse,
            normal_work: y[index::NORMAL_WORK] * s.energy,
            dissipated_normal,
            tangential_work: y[index::TANGENTIAL_WORK] * s.energy * self.friction_scale,
            work_of_immovable_bodies: y[index::IMMOVABLE_WORK] * s.energy,
            elastic_energy,
            tangential_elastic_energy: tangential_elastic * s.energy,
            orientations: [a.3, b.3],
            pivot_impulses: [a.4, b.4],
        }
    }
}
