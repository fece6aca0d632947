//! A frictional sphere on a flat wall, its tangential motion on one line (docs/numerics.md#frictional-impacts-on-a-wall):
//! the normal motion and a 1-D tangential one, in the regularised time of [`super::wall::WallContact`].
//!
//! On a flat wall the normal does not turn and the normal motion does not depend on the tangential one. A tangential
//! force `T ê` on the sphere (`ê` across the normal) changes the relative velocity of the centres by `T ê / m*` and
//! the sphere's spin by `r (a × ê) T / I` with the arm `a = ±n`; the contact points' slip changes by `T ê` times
//! `k = 1/m* + r²/I` (the wall turns nothing: its arm is zero), whatever the spins. The spring starts at zero; its
//! rate is along the slip (stick: `-kt slip`, the rescaled unloading along the spring), the dashpot's force along the
//! slip, and a sliding spring turns only across its loading, which is along it: the slip and the spring stay on the
//! initial slip's line `ê` for every option of the tangential law ([`super::contact::Tangential`]: Mindlin's or a
//! constant stiffness, tangential damping, the rescaled unloading, either Coulomb cap), with spin (a spin about the
//! normal slips nothing; one across it shifts the slip along or across — the slip at first contact is what sets
//! `ê`) and with a wall that moves at a constant velocity. The 3-D model's 21 states reduce to the normal ones and
//! three on the line: the spring force `ξ`, the tangential impulse and its integral (for the positions).
//!
//! The time is regularised as in [`super::wall`] (`dt = d^(3/4) dσ`, `q = d^(1/4)`), so that every rate times `q³` is
//! smooth through the contact's edges. The tangential force, its switches and the stored energy are the functions of
//! [`Tangential`], evaluated in a frame of the line (`ê` along x, the normal along z): the same physics as the 3-D
//! model's, at a fraction of its cost.

use super::contact::{Kinematics, Mode, Tangential};
use super::{ContactModel, Normal, Scales, Snapshot, dissipation_scale, unit_or_one};
use crate::body::Body;
use crate::integrate::{Model, State};
use crate::law::ContactLaw;
use crate::setup::{Motion, Setup};
use nalgebra::Vector3;

/// Size of the state.
pub const SIZE: usize = 11;

/// Where each scaled quantity sits in the state.
pub mod index {
    /// `q = d^(1/4)`, d in L (`d = q |q|³`, negative past the contact's end).
    pub const ROOT: usize = 0;
    /// Physical time since first contact, in T.
    pub const TIME: usize = 1;
    /// ∫ Fn dt, in the impulse unit m* v0 (the penetration rate is `1 - ` it).
    pub const NORMAL_IMPULSE: usize = 2;
    /// ∫ Fn d' dt, in the energy unit m* v0².
    pub const NORMAL_WORK: usize = 3;
    /// ∫ F_dissipative d' dt, in the energy unit times delta (the damping's size).
    pub const DISSIPATED: usize = 4;
    /// The tangential spring force along `ê`, in F0.
    pub const SPRING: usize = 5;
    /// ∫ T dt: the tangential impulse on the sphere's side (body 1) along `ê`, in the impulse unit.
    pub const TANGENTIAL_IMPULSE: usize = 6;
    /// ∫∫ T dt dt: the tangential impulse's integral, in the impulse unit times T (the bodies' shift across the
    /// normal).
    pub const TANGENTIAL_SHIFT: usize = 7;
    /// ∫ T slip dt, in the energy unit times mu.
    pub const TANGENTIAL_WORK: usize = 8;
    /// Work of an immovable body on the movable one, in the energy unit.
    pub const IMMOVABLE_WORK: usize = 9;
    /// The tangential mode, constant between switches (its rate is zero): 0 sticking, 1 sliding, 2 sliding while
    /// the normal force pulls.
    pub const MODE: usize = 10;
}

use index::MODE;

/// Scaled penetration below zero that still counts as the edge of the contact (see the normal model).
const EDGE: f64 = super::normal::EDGE;

/// Scaled penetration at which the initial stick-or-slip is read off the leading terms (as the 3-D model).
const PROBE: f64 = 1e-6;

/// The contact of a sphere on a flat wall, its tangential motion on the initial slip's line, in regularised time.
#[derive(Debug)]
pub struct SlideContact<'a> {
    law: ContactLaw,
    scales: Scales,
    tangential: Tangential,
    /// The wall's normal, body 1 -> body 2.
    normal: Vector3<f64>,
    /// The line of the slip, `ê`: the initial slip's direction (any direction across the normal without slip).
    line: Vector3<f64>,
    /// The slip along `ê` at first contact, in v0 (≥ 0).
    initial_slip: f64,
    /// The penetration rate at first contact, in v0 (1).
    initial_rate: f64,
    /// The change of the slip per unit scaled tangential impulse: `m* (1/m_sphere-side + r²/I)`, summed over both
    /// bodies (the wall contributes its inverse mass alone).
    slip_gain: f64,
    /// Whether the initial slip is not zero (the slip's rest is then watched).
    slipping: bool,
    /// The immovable work's rate per unit scaled normal force and per unit scaled tangential force.
    immovable_rates: (f64, f64),
    /// Relative velocity v2 - v1 at first contact, in v0.
    relative_velocity: Vector3<f64>,
    /// m*/m_i.
    shares: [f64; 2],
    /// The scaled spin change of each body per unit scaled tangential impulse (zero for a body that does not rotate).
    spin_changes: [Vector3<f64>; 2],
    dissipation_scale: f64,
    friction_scale: f64,
    bodies: &'a [Body; 2],
    setup: &'a Setup,
}

/// The local frame's normal (z) and line (x): the tangential law sees only norms and dot products.
const LOCAL_NORMAL: Vector3<f64> = Vector3::new(0.0, 0.0, 1.0);

/// Everything the derivative computes at one state.
struct Evaluation {
    d: f64,
    rate: f64,
    elastic: f64,
    dissipative: f64,
    force_rate: f64,
    slip: f64,
    /// The tangential force on body 1 along `ê`, and the spring's rate.
    force: f64,
    spring_rate: f64,
}

/// The tangential mode a state is in.
fn mode(y: &State<SIZE>) -> Mode {
    Mode::of_slot(y[MODE])
}

impl<'a> SlideContact<'a> {
    /// The contact of a resolved scene whose bodies are a sphere and a flat wall, with friction, on the 3-D model
    /// ([`Motion::Full`]); `None` otherwise.
    pub fn new(bodies: &'a [Body; 2], setup: &'a Setup) -> Option<SlideContact<'a>> {
        let [a, b] = bodies;
        let friction = setup.friction.as_ref()?;
        if setup.motion != Motion::Full || !(a.is_flat() || b.is_flat()) || a.is_flat() && b.is_flat() {
            return None;
        }
        // (A wall has no graze; the scales are the contact's own.)
        if setup.graze_depth.is_some_and(|depth| depth < setup.scales.length) {
            return None;
        }
        let s = setup.scales;
        let law = setup.law;
        let tangential = Tangential::from_friction(friction, s.length, s.force, setup.effective_mass);
        let n = setup.normal;
        let slip = setup.initial_slip - n * setup.initial_slip.dot(&n);
        let slipping = slip.norm() > 0.0;
        let line = if slipping { slip / slip.norm() } else { any_across(&n) };
        let sphere = if a.is_flat() { 1 } else { 0 };
        // The arms (unit, from the centre to the contact point): the sphere's ±n, the wall's zero.
        let mut arms = [Vector3::zeros(); 2];
        arms[sphere] = if sphere == 0 { n } else { -n };
        let spin_gain = |body: &Body| {
            if body.rotates() && !body.is_flat() {
                setup.effective_mass * body.radius * body.radius / body.inertia
            } else {
                0.0
            }
        };
        let shares = [setup.effective_mass * a.inverse_mass(), setup.effective_mass * b.inverse_mass()];
        let gains = [spin_gain(a), spin_gain(b)];
        // T ê on body 1 and -T ê on body 2: torques a1 × ê T and a2 × (-ê T).
        let spin_changes = [arms[0].cross(&line) * gains[0], -arms[1].cross(&line) * gains[1]];
        let slip_gain = shares[0] + shares[1] + gains[0] + gains[1];
        let scaled_spin = |body: &Body| {
            if body.is_flat() { Vector3::zeros() } else { body.angular_velocity * (body.radius / s.speed) }
        };
        let spins = [scaled_spin(a), scaled_spin(b)];
        let velocity = |body: &Body| body.velocity / s.speed;
        // The power an immovable body feeds in (3-D model: -(on_second·v2 + torque2·w2) or on_second·v1 -
        // torque1·w1, with on_second = n Fn - ê T), per unit Fn and per unit T.
        let immovable_rates = if b.is_immovable() {
            (-n.dot(&velocity(b)), line.dot(&velocity(b)) + arms[1].cross(&line).dot(&spins[1]))
        } else if a.is_immovable() {
            (n.dot(&velocity(a)), -(line.dot(&velocity(a)) + arms[0].cross(&line).dot(&spins[0])))
        } else {
            (0.0, 0.0)
        };
        let relative_velocity = (b.velocity - a.velocity) / s.speed;
        Some(SlideContact {
            law,
            scales: s,
            tangential,
            normal: n,
            line,
            initial_slip: slip.norm() / s.speed,
            initial_rate: -relative_velocity.dot(&n),
            slip_gain,
            slipping,
            immovable_rates,
            relative_velocity,
            shares,
            spin_changes,
            dissipation_scale: dissipation_scale(&law, &s),
            friction_scale: unit_or_one(tangential.friction),
            bodies,
            setup,
        })
    }

    /// The scaled penetration at `y` (`q |q|³`).
    fn depth(y: &State<SIZE>) -> f64 {
        let q = y[index::ROOT];
        q * q.abs() * q * q
    }

    /// The kinematics in the line's frame, for the tangential law.
    fn kinematics(d: f64, rate: f64, slip: f64) -> Kinematics {
        Kinematics {
            normal: LOCAL_NORMAL,
            penetration: d,
            rate,
            arms: [Vector3::zeros(); 2],
            slip: Vector3::new(slip, 0.0, 0.0),
            normal_rate: Vector3::zeros(),
        }
    }

    fn spring(y: &State<SIZE>) -> Vector3<f64> {
        Vector3::new(y[index::SPRING], 0.0, 0.0)
    }

    fn evaluate(&self, y: &State<SIZE>) -> Evaluation {
        let s = &self.scales;
        let d = Self::depth(y);
        let rate = self.initial_rate - y[index::NORMAL_IMPULSE];
        let slip = self.initial_slip + self.slip_gain * y[index::TANGENTIAL_IMPULSE];
        // The located edge of the contact sees the force from inside (Kelvin–Voigt's jump), as in the normal model.
        let inside = if d > -EDGE { d.max(0.0) } else { d };
        let parts = self.law.split_force(inside * s.length, rate * s.speed);
        let (elastic, dissipative) = (parts.elastic / s.force, parts.dissipative / s.force);
        let normal_force = elastic + dissipative;
        let acceleration = -normal_force;
        let (by_penetration, by_rate) = self.law.force_gradient(inside * s.length, rate * s.speed);
        let force_rate = (by_penetration * s.length * rate + by_rate * s.speed * acceleration) / s.force;
        let k = Self::kinematics(d, rate, slip);
        let f = self.tangential.evaluate(mode(y), &Self::spring(y), &k, normal_force, force_rate);
        Evaluation {
            d,
            rate,
            elastic,
            dissipative,
            force_rate,
            slip,
            force: f.force.x,
            spring_rate: f.spring_rate.x,
        }
    }

    fn normal_part<'b>(&'b self, y: &State<SIZE>, e: &Evaluation) -> Normal<'b> {
        Normal { law: &self.law, scales: &self.scales, d: e.d, rate: e.rate, deepest_state: y[index::DISSIPATED] }
    }
}

/// A unit vector across `n`.
fn any_across(n: &Vector3<f64>) -> Vector3<f64> {
    let other = if n.x.abs() < 0.9 { Vector3::x() } else { Vector3::y() };
    let across = other - n * other.dot(n);
    across / across.norm()
}

impl Model<SIZE> for SlideContact<'_> {
    fn derivative(&self, _sigma: f64, y: &State<SIZE>, dy: &mut State<SIZE>) {
        let e = self.evaluate(y);
        let q = y[index::ROOT];
        let stretch = q.abs() * q * q;
        let normal_force = e.elastic + e.dissipative;
        dy[index::ROOT] = 0.25 * e.rate;
        dy[index::TIME] = stretch;
        dy[index::NORMAL_IMPULSE] = normal_force * stretch;
        dy[index::NORMAL_WORK] = normal_force * e.rate * stretch;
        dy[index::DISSIPATED] = e.dissipative * e.rate / self.dissipation_scale * stretch;
        dy[index::SPRING] = e.spring_rate * stretch;
        dy[index::TANGENTIAL_IMPULSE] = e.force * stretch;
        dy[index::TANGENTIAL_SHIFT] = y[index::TANGENTIAL_IMPULSE] * stretch;
        dy[index::TANGENTIAL_WORK] = e.force * e.slip / self.friction_scale * stretch;
        let (per_normal, per_tangential) = self.immovable_rates;
        dy[index::IMMOVABLE_WORK] = (per_normal * normal_force + per_tangential * e.force) * stretch;
        dy[MODE] = 0.0;
    }
}

impl ContactModel<SIZE> for SlideContact<'_> {
    fn scales(&self) -> &Scales {
        &self.scales
    }

    /// A tenth of the law's, as the 3-D model integrates at.
    fn tolerance_factor(&self) -> f64 {
        0.1 * self.law.tolerance_factor()
    }

    fn start(&self) -> State<SIZE> {
        let mut y = State::<SIZE>::zeros();
        let s = &self.scales;
        let contact_force = self.law.force(0.0, s.speed) / s.force;
        let probe_force = self.law.force(PROBE * s.length, s.speed) / s.force;
        let mode = self.tangential.initial_mode(self.initial_slip, 1.0, PROBE, contact_force, probe_force);
        y[MODE] = mode.slot();
        y
    }

    /// `q = d^(1/4)`: the penetration's sign and zeros, simple ones.
    fn penetration(&self, y: &State<SIZE>) -> f64 {
        y[index::ROOT]
    }

    fn rate(&self, y: &State<SIZE>) -> f64 {
        self.initial_rate - y[index::NORMAL_IMPULSE]
    }

    fn force(&self, y: &State<SIZE>) -> f64 {
        let e = self.evaluate(y);
        e.elastic + e.dissipative
    }

    fn force_rate(&self, y: &State<SIZE>) -> f64 {
        self.evaluate(y).force_rate
    }

    fn separation_force(&self, y: &State<SIZE>) -> f64 {
        let e = self.evaluate(y);
        self.normal_part(y, &e).separation()
    }

    fn uncut_force(&self, y: &State<SIZE>) -> Option<f64> {
        let e = self.evaluate(y);
        self.normal_part(y, &e).uncut()
    }

    fn switch_function(&self, y: &State<SIZE>) -> Option<f64> {
        let e = self.evaluate(y);
        let k = Self::kinematics(e.d, e.rate, e.slip);
        let force = e.elastic + e.dissipative;
        Some(self.tangential.switch_function(mode(y), &Self::spring(y), &k, force, e.force_rate, e.elastic))
    }

    fn switch(&self, y: &mut State<SIZE>) {
        let e = self.evaluate(y);
        let k = Self::kinematics(e.d, e.rate, e.slip);
        let force = e.elastic + e.dissipative;
        let (next, spring) =
            self.tangential.next_mode(mode(y), &Self::spring(y), &k, force, e.force_rate, e.elastic);
        if let Some(spring) = spring {
            y[index::SPRING] = spring.x;
        }
        y[MODE] = next.slot();
    }

    fn sliding(&self, y: &State<SIZE>) -> bool {
        mode(y).is_sliding()
    }

    fn slip_along_start(&self, y: &State<SIZE>) -> Option<f64> {
        self.slipping.then(|| self.initial_slip + self.slip_gain * y[index::TANGENTIAL_IMPULSE])
    }

    fn kinks(&self, compressing: bool) -> crate::law::Kinks {
        self.law.kinks(compressing).scaled(self.scales.length)
    }

    fn time_of(&self, _sigma: f64, y: &State<SIZE>) -> f64 {
        y[index::TIME]
    }

    fn snapshot(&self, _sigma: f64, y: &State<SIZE>) -> Snapshot {
        let s = &self.scales;
        let setup = self.setup;
        let [a, b] = self.bodies;
        let e = self.evaluate(y);
        let t = y[index::TIME];
        let time = t * s.time;
        let n = self.normal;
        let tangential = y[index::TANGENTIAL_IMPULSE];
        // The impulse on body 2: n Jn - ê Jt.
        let impulse = (n * y[index::NORMAL_IMPULSE] - self.line * tangential) * s.impulse;
        let velocities = [a.velocity - impulse * a.inverse_mass(), b.velocity + impulse * b.inverse_mass()];
        let spin = |i: usize, body: &Body| {
            if body.is_flat() || self.spin_changes[i] == Vector3::zeros() {
                body.angular_velocity
            } else {
                body.angular_velocity + self.spin_changes[i] * (tangential * s.speed / body.radius)
            }
        };
        // The displacement of body 2 from body 1 since first contact: -d along the normal, across it the free motion
        // and the tangential impulse's shift; beyond the free relative motion, shared in the ratio of the inverse
        // masses.
        let across = self.relative_velocity - n * self.relative_velocity.dot(&n);
        let displacement = across * t - self.line * y[index::TANGENTIAL_SHIFT] - n * e.d;
        let pushed = (displacement - self.relative_velocity * t) * s.length;
        let positions = [
            setup.positions[0] + a.velocity * time - pushed * self.shares[0],
            setup.positions[1] + b.velocity * time + pushed * self.shares[1],
        ];
        let normal_force = e.elastic + e.dissipative;
        let tangential_elastic = self.tangential.stored_energy(mode(y), &Self::spring(y), e.d, normal_force);
        let (elastic_energy, dissipated_normal) =
            self.normal_part(y, &e).energies(y[index::NORMAL_WORK], y[index::DISSIPATED], self.dissipation_scale);
        Snapshot {
            time,
            penetration: e.d * s.length,
            rate: e.rate * s.speed,
            normal_force: normal_force * s.force,
            normal: n,
            tangential_force: self.line * (e.force * s.force),
            slip: self.line * (e.slip * s.speed),
            velocities,
            spins: [spin(0, a), spin(1, b)],
            positions,
            normal_impulse: y[index::NORMAL_IMPULSE] * s.impulse,
            normal_work: y[index::NORMAL_WORK] * s.energy,
            dissipated_normal,
            tangential_work: y[index::TANGENTIAL_WORK] * s.energy * self.friction_scale,
            work_of_immovable_bodies: y[index::IMMOVABLE_WORK] * s.energy,
            elastic_energy,
            tangential_elastic_energy: tangential_elastic * s.energy,
            orientations: [nalgebra::UnitQuaternion::identity(); 2],
            pivot_impulses: [nalgebra::Vector3::zeros(); 2],
        }
    }
}
