//! Two bodies in 3-D through one contact: positions, velocities and spins, the normal turning with the line of
//! centres, Coulomb friction with a tangential spring — the general model, for every impact the 1-D
//! [`super::normal::NormalContact`] cannot describe.
//!
//! The state is relative where that keeps precision: the displacement of body 2 with respect to body 1 since first
//! contact (so that the penetration is never the difference of two nearly equal lengths), and the impulse on body 2
//! (the velocities follow from it). Spins are scaled as omega r / v0 so that they are O(1) at the contact point.

use super::contact::{Kinematics, Mode, Shape, Tangential, set_vector, vector};
use super::{ContactModel, Normal, Scales, Snapshot, dissipation_scale, unit_or_one};
use crate::body::Body;
use crate::integrate::{Model, State};
use crate::law::ContactLaw;
use crate::setup::Setup;
use nalgebra::Vector3;

/// Size of the state.
pub const SIZE: usize = 21;

/// Where each scaled quantity sits in the state (vectors take three places).
pub mod index {
    /// Displacement of body 2 relative to body 1 since first contact, in L.
    pub const DISPLACEMENT: usize = 0;
    /// Impulse on body 2 since first contact (body 1 receives its opposite), in the impulse unit (m* v0; less for a
    /// graze, [`super::Scales::with_length`]).
    pub const IMPULSE: usize = 3;
    /// Spin of body 1 as omega r1 / v0.
    pub const SPIN_1: usize = 6;
    /// Spin of body 2 as omega r2 / v0.
    pub const SPIN_2: usize = 9;
    /// Tangential spring force, in F0; while sliding its direction alone, at the length
    /// [`crate::dynamics::contact::SLIDE_CARRIER`] (the force is the Coulomb cap along it).
    pub const SPRING: usize = 12;
    /// ∫ Fn dt, in the impulse unit.
    pub const NORMAL_IMPULSE: usize = 15;
    /// ∫ Fn d' dt, in the energy unit (m* v0²; less for a graze).
    pub const NORMAL_WORK: usize = 16;
    /// ∫ F_dissipative d' dt, in the energy unit times delta (the damping's size).
    pub const DISSIPATED: usize = 17;
    /// For a yielding law (no damping: it takes this slot), the deepest penetration so far, in L.
    pub const DEEPEST: usize = 17;
    /// ∫ Ft·slip dt, in the energy unit times mu.
    pub const TANGENTIAL_WORK: usize = 18;
    /// Work of an immovable body on the movable one, in the energy unit.
    pub const IMMOVABLE_WORK: usize = 19;
    /// The tangential mode, constant between switches: 0 sticking, 1 sliding, 2 sliding while the normal force pulls.
    pub const MODE: usize = 20;
}

/// Scaled penetration below zero that still counts as the edge of the contact (see the normal model).
const EDGE: f64 = super::normal::EDGE;

/// Scaled penetration at which the initial stick-or-slip is read off the leading terms.
const PROBE: f64 = 1e-6;

/// The two-body contact model.
#[derive(Debug)]
pub struct PairContact<'a> {
    law: ContactLaw,
    scales: Scales,
    shape: Shape,
    tangential: Option<Tangential>,
    /// Relative velocity v2 - v1 at first contact, in v0.
    relative_velocity: Vector3<f64>,
    /// The change of the relative velocity (in v0) per unit of the scaled impulse: 1 in the scales of an impact,
    /// (L_u/L)^(n+1) in those of a graze (see [`Scales::with_length`]).
    impulse_gain: f64,
    /// m*/m_i: body i's share of the relative motion (0 for an immovable body).
    shares: [f64; 2],
    /// m* r_i² / I_i: how a scaled torque changes a scaled spin (0 for a body that does not rotate).
    spin_gains: [f64; 2],
    /// Initial scaled spins (the constant spin of a body that does not rotate under the contact).
    initial_spins: [Vector3<f64>; 2],
    /// The direction of the contact points' slip at first contact (zero without friction or without slip).
    slip_direction: Vector3<f64>,
    /// Units of the dissipated and tangential-work states.
    dissipation_scale: f64,
    friction_scale: f64,
    bodies: &'a [Body; 2],
    setup: &'a Setup,
}

/// The tangential mode a state is in.
fn mode(y: &State<SIZE>) -> Mode {
    Mode::of_slot(y[index::MODE])
}

fn set_mode(y: &mut State<SIZE>, mode: Mode) {
    y[index::MODE] = mode.slot();
}

/// Everything the derivative computes at one state, for the events and snapshots too.
struct Evaluation {
    kinematics: Kinematics,
    relative_velocity: Vector3<f64>,
    spins: [Vector3<f64>; 2],
    elastic: f64,
    dissipative: f64,
    /// The spring state, in the tangent plane (while sliding, the direction it carries: `Tangential::carried`).
    spring: Vector3<f64>,
    tangential: Vector3<f64>,
    spring_rate: Vector3<f64>,
}

impl<'a> PairContact<'a> {
    /// The contact of a resolved scene.
    pub fn new(bodies: &'a [Body; 2], setup: &'a Setup) -> PairContact<'a> {
        let law = setup.law;
        // A graze shallower than the penetration scale takes its own depth as the length unit, so that its small
        // force, impulse and works are integrated relative to themselves (docs/oblique.md#grazing-contacts).
        let s = match setup.graze_depth {
            Some(depth) if depth < setup.scales.length => setup.scales.with_length(depth, law.stiffness, law.exponent),
            _ => setup.scales,
        };
        let impulse_gain = s.impulse / setup.scales.impulse;
        let [a, b] = bodies;
        let shape = if a.is_flat() || b.is_flat() {
            Shape::Wall { normal: setup.normal, sphere: if a.is_flat() { 1 } else { 0 } }
        } else {
            let reach = (a.radius + b.radius) / s.length;
            Shape::Spheres { reach, contact_vector: setup.normal * reach }
        };
        let tangential = setup
            .friction
            .map(|f| Tangential::from_friction(&f, s.length, s.force, setup.effective_mass * impulse_gain));
        let spin_gain = |body: &Body| {
            let gain = setup.effective_mass * body.radius * body.radius / body.inertia;
            if body.rotates() { gain * impulse_gain } else { 0.0 }
        };
        let scaled_spin = |body: &Body| {
            if body.is_flat() { Vector3::zeros() } else { body.angular_velocity * (body.radius / s.speed) }
        };
        let friction_scale = unit_or_one(tangential.map_or(0.0, |t| t.friction));
        let slip = setup.initial_slip;
        let slip_direction =
            if tangential.is_some() && slip.norm() > 0.0 { slip / slip.norm() } else { Vector3::zeros() };
        PairContact {
            law,
            scales: s,
            shape,
            tangential,
            relative_velocity: (b.velocity - a.velocity) / s.speed,
            impulse_gain,
            shares: [setup.effective_mass * a.inverse_mass(), setup.effective_mass * b.inverse_mass()],
            spin_gains: [spin_gain(a), spin_gain(b)],
            initial_spins: [scaled_spin(a), scaled_spin(b)],
            slip_direction,
            dissipation_scale: dissipation_scale(&law, &s),
            friction_scale,
            bodies,
            setup,
        }
    }

    fn spins(&self, y: &State<SIZE>) -> [Vector3<f64>; 2] {
        let spin = |i: usize, at: usize| if self.spin_gains[i] > 0.0 { vector(y, at) } else { self.initial_spins[i] };
        [spin(0, index::SPIN_1), spin(1, index::SPIN_2)]
    }

    /// A yielding law's deepest penetration so far, m, at scaled penetration `d`: its state, or `d` where that is
    /// deeper (the state grows only at it: [`super::normal::deepening`]).
    fn deepest(&self, y: &State<SIZE>, d: f64) -> f64 {
        y[index::DEEPEST].max(d) * self.scales.length
    }

    /// The normal contact's bookkeeping at state `y` with kinematics `k`.
    fn normal<'b>(&'b self, y: &State<SIZE>, k: &Kinematics) -> Normal<'b> {
        Normal {
            law: &self.law,
            scales: &self.scales,
            d: k.penetration,
            rate: k.rate,
            deepest_state: y[index::DEEPEST],
        }
    }

    fn evaluate(&self, y: &State<SIZE>) -> Evaluation {
        let s = &self.scales;
        let relative_velocity = self.relative_velocity + vector(y, index::IMPULSE) * self.impulse_gain;
        let spins = self.spins(y);
        let kinematics = self.shape.kinematics(&vector(y, index::DISPLACEMENT), &relative_velocity, &spins);
        let k = &kinematics;
        // The located edge of the contact sees the force from inside (Kelvin–Voigt's jump), as in the normal model.
        let d = if k.penetration > -EDGE { k.penetration.max(0.0) } else { k.penetration };
        // A yielding law's memory (the penetration where that is deeper: the state grows only at it).
        let deepest = self.deepest(y, d);
        let parts = self.law.split_force_after(d * s.length, k.rate * s.speed, deepest);
        let (elastic, dissipative) = (parts.elastic / s.force, parts.dissipative / s.force);
        let normal_force = elastic + dissipative;
        let raw_spring = vector(y, index::SPRING);
        let spring = raw_spring - k.normal * raw_spring.dot(&k.normal);
        let (tangential, spring_rate) = match &self.tangential {
            Some(t) => {
                let f = t.evaluate(mode(y), &spring, k, normal_force);
                (f.force, f.spring_rate)
            }
            None => (Vector3::zeros(), Vector3::zeros()),
        };
        Evaluation { kinematics, relative_velocity, spins, elastic, dissipative, spring, tangential, spring_rate }
    }

    /// The normal force's rate at `y` (scaled), from its evaluation `e`: only the force peak and the stick–slip
    /// switches need it, the derivative none.
    fn normal_force_rate(&self, y: &State<SIZE>, e: &Evaluation) -> f64 {
        let (s, k) = (&self.scales, &e.kinematics);
        let d = if k.penetration > -EDGE { k.penetration.max(0.0) } else { k.penetration };
        let deepest = self.deepest(y, d);
        // d'' = -(dw/dt·n + w·dn/dt), and dw/dt·n = Fn (the tangential force lies across the normal).
        let acceleration = -((e.elastic + e.dissipative) * self.impulse_gain + e.relative_velocity.dot(&k.normal_rate));
        let (by_penetration, by_rate) = self.law.force_gradient_after(d * s.length, k.rate * s.speed, deepest);
        (by_penetration * s.length * k.rate + by_rate * s.speed * acceleration) / s.force
    }
}

impl Model<SIZE> for PairContact<'_> {
    fn derivative(&self, _t: f64, y: &State<SIZE>, dy: &mut State<SIZE>) {
        let e = self.evaluate(y);
        let k = &e.kinematics;
        let normal_force = e.elastic + e.dissipative;
        let on_second = k.normal * normal_force - e.tangential;
        set_vector(dy, index::DISPLACEMENT, &e.relative_velocity);
        set_vector(dy, index::IMPULSE, &on_second);
        let torques = [k.arms[0].cross(&e.tangential), k.arms[1].cross(&-e.tangential)];
        set_vector(dy, index::SPIN_1, &(torques[0] * self.spin_gains[0]));
        set_vector(dy, index::SPIN_2, &(torques[1] * self.spin_gains[1]));
        set_vector(dy, index::SPRING, &e.spring_rate);
        dy[index::NORMAL_IMPULSE] = normal_force;
        dy[index::NORMAL_WORK] = normal_force * k.rate;
        dy[index::DISSIPATED] = self.normal(y, k).dissipation_rate(e.dissipative, self.dissipation_scale);
        dy[index::TANGENTIAL_WORK] = e.tangential.dot(&k.slip) / self.friction_scale;
        // Power the contact feeds into an immovable body, with the opposite sign: the work it does on the other.
        let [a, b] = self.bodies;
        let velocity = |body: &Body| body.velocity / self.scales.speed;
        dy[index::IMMOVABLE_WORK] = if b.is_immovable() {
            -(on_second.dot(&velocity(b)) + torques[1].dot(&e.spins[1]))
        } else if a.is_immovable() {
            on_second.dot(&velocity(a)) - torques[0].dot(&e.spins[0])
        } else {
            0.0
        };
    }
}

impl ContactModel<SIZE> for PairContact<'_> {
    fn scales(&self) -> &Scales {
        &self.scales
    }

    /// A tenth: the 3-D model's energy comes from more separately integrated states (impulse vector, spins, the
    /// normal and tangential works), whose errors add; at a tenth of the scene's tolerances every energy of the
    /// stress run's million cases closes to 1e-9, for about a quarter more steps.
    fn tolerance_factor(&self) -> f64 {
        0.1 * self.law.tolerance_factor()
    }

    fn start(&self) -> State<SIZE> {
        let mut y = State::<SIZE>::zeros();
        set_vector(&mut y, index::SPIN_1, &self.initial_spins[0]);
        set_vector(&mut y, index::SPIN_2, &self.initial_spins[1]);
        if let Some(t) = &self.tangential {
            let slip = self.setup.initial_slip.norm() / self.scales.speed;
            let s = &self.scales;
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
        self.evaluate(y).kinematics.penetration
    }

    fn rate(&self, y: &State<SIZE>) -> f64 {
        self.evaluate(y).kinematics.rate
    }

    fn force(&self, y: &State<SIZE>) -> f64 {
        let e = self.evaluate(y);
        e.elastic + e.dissipative
    }

    fn force_rate(&self, y: &State<SIZE>) -> f64 {
        self.normal_force_rate(y, &self.evaluate(y))
    }

    fn separation_force(&self, y: &State<SIZE>) -> f64 {
        self.normal(y, &self.evaluate(y).kinematics).separation()
    }

    fn uncut_force(&self, y: &State<SIZE>) -> Option<f64> {
        self.normal(y, &self.evaluate(y).kinematics).uncut()
    }

    fn switch_function(&self, y: &State<SIZE>) -> Option<f64> {
        let t = self.tangential.as_ref()?;
        let e = self.evaluate(y);
        let force = e.elastic + e.dissipative;
        let rate = self.normal_force_rate(y, &e);
        Some(t.carried_switch_function(mode(y), &e.spring, &e.kinematics, force, rate, e.elastic))
    }

    fn switch(&self, y: &mut State<SIZE>) {
        let Some(t) = &self.tangential else { return };
        let e = self.evaluate(y);
        let force = e.elastic + e.dissipative;
        let (next, spring) =
            t.carried_next_mode(mode(y), &e.spring, &e.kinematics, force, self.normal_force_rate(y, &e), e.elastic);
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
        let setup = self.setup;
        let [a, b] = self.bodies;
        let e = self.evaluate(y);
        let k = &e.kinematics;
        let time = t * s.time;
        let impulse = vector(y, index::IMPULSE) * s.impulse;
        let velocities = [a.velocity - impulse * a.inverse_mass(), b.velocity + impulse * b.inverse_mass()];
        let spin = |body: &Body, scaled: &Vector3<f64>| {
            if body.is_flat() { body.angular_velocity } else { scaled * (s.speed / body.radius) }
        };
        // The force moves the bodies from their free flight by the displacement beyond the free relative motion,
        // shared in the ratio of the inverse masses.
        let pushed = (vector(y, index::DISPLACEMENT) - self.relative_velocity * t) * s.length;
        let positions = [
            setup.positions[0] + a.velocity * time - pushed * self.shares[0],
            setup.positions[1] + b.velocity * time + pushed * self.shares[1],
        ];
        let tangential_elastic = self.tangential.map_or(0.0, |t| {
            let force = e.elastic + e.dissipative;
            t.stored_energy(mode(y), &t.carried(mode(y), &e.spring, &k.slip, force), k.penetration, force)
        });
        let normal_work = y[index::NORMAL_WORK] * s.energy;
        let (elastic_energy, dissipated_normal) =
            self.normal(y, k).energies(y[index::NORMAL_WORK], y[index::DISSIPATED], self.dissipation_scale);
        Snapshot {
            time,
            penetration: k.penetration * s.length,
            rate: k.rate * s.speed,
            normal_force: (e.elastic + e.dissipative) * s.force,
            normal: k.normal,
            tangential_force: e.tangential * s.force,
            slip: k.slip * s.speed,
            velocities,
            spins: [spin(a, &e.spins[0]), spin(b, &e.spins[1])],
            positions,
            normal_impulse: y[index::NORMAL_IMPULSE] * s.impulse,
            normal_work,
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
