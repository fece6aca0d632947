//! An island: the bodies that active contacts couple, integrated together under gravity (docs/world.md#islands).
//!
//! The state is scaled like one contact's (lengths in L, speeds in V, time in T = L/V, masses in M, forces in
//! M V²/L, energies in M V²; the units of the contact that started the island). For each member body it holds the
//! displacement since the segment began (never the absolute position: the penetration of two bodies is their
//! relative position at the segment's start plus the difference of two small displacements, without the rounding of
//! where they are in the scene) and the velocity; for each active contact its normal impulse, the work of its normal
//! force and the work of its damping; the work done by immovable bodies; and the clock (scaled time since the segment
//! began), on which the free flight of the bodies outside the island depends. A segment lasts until a contact begins
//! or ends: then the driver builds the next one.

use super::flight::Kinematic;
use crate::dynamics::unit_or_one;
use crate::geometry::Meeting;
use crate::integrate::{ModelOf, Vector};
use crate::law::ContactLaw;
use crate::scene::WorldScene;
use nalgebra::{DVector, Dyn, Vector3};

/// Scaled penetration below zero that still counts as the edge of a contact: the located end sees the force from
/// inside (Kelvin–Voigt's jump), as in the one-contact models.
const EDGE: f64 = crate::dynamics::normal::EDGE;

/// The units of an island's scaled state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Units {
    /// L, m.
    pub length: f64,
    /// V, m/s.
    pub speed: f64,
    /// T = L/V, s.
    pub time: f64,
    /// M, kg.
    pub mass: f64,
    /// M V²/L, N.
    pub force: f64,
    /// M V, N s.
    pub impulse: f64,
    /// M V², J.
    pub energy: f64,
}

impl Units {
    /// The units of a contact of effective mass `mass` (kg), stiffness `stiffness` (N/m^n) and exponent `exponent`
    /// at the speed `speed` (m/s, > 0): L = (M V²/K)^(1/(n+1)).
    pub fn new(mass: f64, stiffness: f64, exponent: f64, speed: f64) -> Units {
        let s = crate::scales::Scales::new(mass, stiffness, exponent, speed);
        Units { length: s.length, speed, time: s.time, mass, force: s.force, impulse: s.impulse, energy: s.energy }
    }
}

/// A contact that is active in an island: the pair (the normal points from body `pair[0]` to body `pair[1]`), how
/// they meet, the law resolved at its first touch, and its integrals so far (SI).
#[derive(Debug, Clone, PartialEq)]
pub struct ActiveContact {
    /// The index of its record (the contacts of the run, in order of first touch).
    pub record: usize,
    pub pair: [usize; 2],
    pub meeting: Meeting,
    pub law: ContactLaw,
    /// Whether it ends where its continued force falls through zero (a `separation = "force"` law that can pull).
    pub on_force: bool,
    /// ∫ Fn dt so far, N s.
    pub impulse: f64,
    /// ∫ Fn d' dt so far, J.
    pub work: f64,
    /// ∫ F_dissipative d' dt so far, J.
    pub dissipated: f64,
}

/// One contact's kinematics at an instant (SI).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactState {
    /// Penetration, m.
    pub penetration: f64,
    /// Penetration rate d', m/s.
    pub rate: f64,
    /// Unit normal from body `pair[0]` to body `pair[1]`.
    pub normal: Vector3<f64>,
    /// Relative velocity v_j - v_i, m/s.
    pub relative_velocity: Vector3<f64>,
    /// Distance of two sphere centres (m; infinite for a face), for the turning of the normal.
    pub distance: f64,
}

/// The bodies and contacts of one segment of an island, with what the scaled state means.
#[derive(Debug)]
pub struct Island<'a> {
    scene: &'a WorldScene,
    /// Every body's position and velocity when the segment began (scene-indexed), SI.
    start: &'a [Kinematic],
    /// Every body's acceleration in free flight (scene-indexed), m/s²: gravity for a body of finite mass, none for an
    /// immovable body or one at rest on others (frozen).
    flight: &'a [Vector3<f64>],
    /// For each body of the scene, its place among the members (`None`: outside the island, or immovable).
    slots: Vec<Option<usize>>,
    /// The member bodies (finite mass), in state order.
    pub members: Vec<usize>,
    pub contacts: Vec<ActiveContact>,
    pub units: Units,
    /// Gravity in units of V/T.
    gravity: Vector3<f64>,
    /// The dissipated-energy unit of each contact, in energy units (its damping's size: accurate relative to itself).
    dissipation_units: Vec<f64>,
    /// For each member, the active contacts it takes part in.
    touching: Vec<Vec<usize>>,
    contact_base: usize,
    immovable_work: usize,
    clock: usize,
    size: usize,
}

impl<'a> Island<'a> {
    /// The segment of `contacts` (their bodies become the members) from the bodies' states `start`, in `units`.
    pub fn new(
        scene: &'a WorldScene,
        start: &'a [Kinematic],
        flight: &'a [Vector3<f64>],
        contacts: Vec<ActiveContact>,
        units: Units,
    ) -> Self {
        let mut slots = vec![None; scene.bodies.len()];
        let mut members = Vec::new();
        for contact in &contacts {
            for &k in &contact.pair {
                if slots[k].is_none() && !scene.bodies[k].is_immovable() {
                    slots[k] = Some(members.len());
                    members.push(k);
                }
            }
        }
        let dissipation_units =
            contacts.iter().map(|c| unit_or_one(c.law.damping_ratio(units.length, units.speed).min(1.0))).collect();
        let mut touching = vec![Vec::new(); members.len()];
        for (c, contact) in contacts.iter().enumerate() {
            for &k in &contact.pair {
                if let Some(m) = slots[k] {
                    touching[m].push(c);
                }
            }
        }
        let contact_base = 6 * members.len();
        let immovable_work = contact_base + 3 * contacts.len();
        let clock = immovable_work + 1;
        Island {
            scene,
            start,
            flight,
            slots,
            members,
            contacts,
            units,
            gravity: scene.world.gravity * (units.time / units.speed),
            dissipation_units,
            touching,
            contact_base,
            immovable_work,
            clock,
            size: clock + 1,
        }
    }

    /// The state at the segment's start.
    pub fn initial_state(&self) -> DVector<f64> {
        let u = &self.units;
        let mut y = DVector::zeros(self.size);
        for (m, &k) in self.members.iter().enumerate() {
            let w = self.start[k].velocity / u.speed;
            y.fixed_rows_mut::<3>(6 * m + 3).copy_from(&w);
        }
        for (c, contact) in self.contacts.iter().enumerate() {
            let at = self.contact_base + 3 * c;
            y[at] = contact.impulse / u.impulse;
            y[at + 1] = contact.work / u.energy;
            y[at + 2] = contact.dissipated / (u.energy * self.dissipation_units[c]);
        }
        y
    }

    /// Scaled time since the segment began.
    pub fn clock(&self, y: &DVector<f64>) -> f64 {
        y[self.clock]
    }

    /// Work done by immovable bodies on the others since the segment began, J.
    pub fn immovable_work(&self, y: &DVector<f64>) -> f64 {
        y[self.immovable_work] * self.units.energy
    }

    /// Body `k`'s displacement since the segment began, m.
    pub fn displacement(&self, k: usize, y: &DVector<f64>) -> Vector3<f64> {
        match self.slots[k] {
            Some(m) => y.fixed_rows::<3>(6 * m).into_owned() * self.units.length,
            None => self.start[k].displacement(y[self.clock] * self.units.time, &self.flight[k]),
        }
    }

    /// Body `k`'s velocity, m/s.
    pub fn velocity(&self, k: usize, y: &DVector<f64>) -> Vector3<f64> {
        match self.slots[k] {
            Some(m) => y.fixed_rows::<3>(6 * m + 3).into_owned() * self.units.speed,
            None => self.start[k].velocity + self.flight[k] * (y[self.clock] * self.units.time),
        }
    }

    /// Body `k`'s position, m.
    pub fn position(&self, k: usize, y: &DVector<f64>) -> Vector3<f64> {
        self.start[k].position + self.displacement(k, y)
    }

    /// x_j - x_i, m: the relative position at the segment's start plus the difference of the displacements.
    pub fn relative_position(&self, i: usize, j: usize, y: &DVector<f64>) -> Vector3<f64> {
        (self.start[j].position - self.start[i].position) + (self.displacement(j, y) - self.displacement(i, y))
    }

    /// How bodies `i` and `j` (meeting as `meeting`) stand at state `y`.
    pub fn pair_state(&self, i: usize, j: usize, meeting: &Meeting, y: &DVector<f64>) -> ContactState {
        let relative = self.relative_position(i, j, y);
        let (penetration, normal) = meeting.penetration(&relative);
        let relative_velocity = self.velocity(j, y) - self.velocity(i, y);
        let distance = match meeting {
            Meeting::Spheres { .. } => relative.norm(),
            Meeting::Face { .. } => f64::INFINITY,
        };
        ContactState { penetration, rate: -relative_velocity.dot(&normal), normal, relative_velocity, distance }
    }

    /// Contact `c`'s kinematics at state `y`.
    pub fn contact_state(&self, c: usize, y: &DVector<f64>) -> ContactState {
        let contact = &self.contacts[c];
        self.pair_state(contact.pair[0], contact.pair[1], &contact.meeting, y)
    }

    /// Contact `c`'s normal force split into its elastic and dissipative parts, N, at its kinematics `state`.
    pub fn force(&self, c: usize, state: &ContactState) -> (f64, f64) {
        let d = state.penetration;
        let edge = EDGE * self.units.length;
        let d = if d > -edge { d.max(0.0) } else { d };
        let parts = self.contacts[c].law.split_force(d, state.rate);
        (parts.elastic, parts.dissipative)
    }

    /// Body `k`'s acceleration at state `y` (m/s²): gravity and the forces of its own contacts (none for a body
    /// outside the island, whose flight is free, or an immovable one).
    pub fn acceleration_of(&self, k: usize, y: &DVector<f64>) -> Vector3<f64> {
        let body = &self.scene.bodies[k];
        let Some(m) = self.slots[k] else { return self.flight[k] };
        let mut a = self.scene.world.gravity;
        for &c in &self.touching[m] {
            let state = self.contact_state(c, y);
            let (elastic, dissipative) = self.force(c, &state);
            let on_j = state.normal * ((elastic + dissipative) / body.mass);
            if self.contacts[c].pair[1] == k { a += on_j } else { a -= on_j }
        }
        a
    }

    /// dF/dt of contact `c` (N/s): the force's gradient along the motion, with d'' from the two bodies'
    /// accelerations and the turning of the normal. Its fall through zero is the force peak.
    pub fn force_rate(&self, c: usize, y: &DVector<f64>) -> f64 {
        let state = self.contact_state(c, y);
        let contact = &self.contacts[c];
        let [i, j] = contact.pair;
        let relative_acceleration = self.acceleration_of(j, y) - self.acceleration_of(i, y);
        let u = &state.relative_velocity;
        let turning = if state.distance.is_finite() {
            (u - state.normal * state.normal.dot(u)) / state.distance
        } else {
            Vector3::zeros()
        };
        let second = -relative_acceleration.dot(&state.normal) - u.dot(&turning);
        let d = state.penetration.max(0.0);
        let (by_penetration, by_rate) = contact.law.force_gradient(d, state.rate);
        by_penetration * state.rate + by_rate * second
    }

    /// The function whose fall through zero ends contact `c`: its penetration (m), or — ended by its force — the law's
    /// force continued past d = 0 (docs/numerics.md#separation-on-the-continued-force).
    pub fn separation_value(&self, c: usize, y: &DVector<f64>) -> f64 {
        let state = self.contact_state(c, y);
        let contact = &self.contacts[c];
        if contact.on_force {
            contact.law.separation_function(state.penetration, state.rate)
        } else {
            state.penetration / self.units.length
        }
    }

    /// The groups of members that active contacts join (member slots), each with whether an immovable body holds
    /// it (one of its contacts is with an immovable body).
    pub fn components(&self) -> Vec<(Vec<usize>, bool)> {
        let mut group: Vec<usize> = (0..self.members.len()).collect();
        fn root(group: &mut [usize], mut m: usize) -> usize {
            while group[m] != m {
                group[m] = group[group[m]];
                m = group[m];
            }
            m
        }
        let mut held = vec![false; self.members.len()];
        for contact in &self.contacts {
            let [i, j] = contact.pair;
            match (self.slots[i], self.slots[j]) {
                (Some(a), Some(b)) => {
                    let (ra, rb) = (root(&mut group, a), root(&mut group, b));
                    group[ra] = rb;
                }
                (Some(a), None) | (None, Some(a)) => held[a] = true,
                (None, None) => {}
            }
        }
        let mut components: std::collections::BTreeMap<usize, (Vec<usize>, bool)> = Default::default();
        for (m, &holds) in held.iter().enumerate() {
            let r = root(&mut group, m);
            let entry = components.entry(r).or_default();
            entry.0.push(m);
            entry.1 |= holds;
        }
        components.into_values().collect()
    }

    /// The energy of the motion about rest (J) of the members `group` (slots): Σ ½ m |v - v̄|² + ½ m |a - ā|²/ω², ω²
    /// the member's contact stiffness over its mass — for a body oscillating on a contact, its oscillation energy,
    /// which does not swing with the phase as the kinetic energy alone does. v̄ and ā are the group's mean motion
    /// when no immovable body holds it (`held` false: bodies stuck together and drifting are at rest relative to each
    /// other), zero otherwise.
    pub fn motion_energy(&self, y: &DVector<f64>, group: &[usize], held: bool) -> f64 {
        let masses: Vec<f64> = group.iter().map(|&m| self.scene.bodies[self.members[m]].mass).collect();
        let accelerations: Vec<Vector3<f64>> =
            group.iter().map(|&m| self.acceleration_of(self.members[m], y)).collect();
        let total: f64 = masses.iter().sum();
        let (mut mean_v, mut mean_a) = (Vector3::zeros(), Vector3::zeros());
        if !held {
            for (g, &m) in group.iter().enumerate() {
                mean_v += self.velocity(self.members[m], y) * (masses[g] / total);
                mean_a += accelerations[g] * (masses[g] / total);
            }
        }
        let mut energy = 0.0;
        for (g, &m) in group.iter().enumerate() {
            let mut stiffness = 0.0;
            for &c in &self.touching[m] {
                let state = self.contact_state(c, y);
                stiffness += self.contacts[c].law.force_gradient(state.penetration.max(0.0), 0.0).0.max(0.0);
            }
            let v = self.velocity(self.members[m], y) - mean_v;
            let a = accelerations[g] - mean_a;
            let omega2 = stiffness / masses[g];
            let potential = if omega2 > 0.0 {
                0.5 * masses[g] * a.norm_squared() / omega2
            } else if a.norm() > 0.0 {
                f64::INFINITY
            } else {
                0.0
            };
            energy += 0.5 * masses[g] * v.norm_squared() + potential;
        }
        energy
    }

    /// Contact `c`'s integrals at state `y` (SI): normal impulse, normal work, dissipated energy.
    pub fn integrals(&self, c: usize, y: &DVector<f64>) -> (f64, f64, f64) {
        let u = &self.units;
        let at = self.contact_base + 3 * c;
        (y[at] * u.impulse, y[at + 1] * u.energy, y[at + 2] * u.energy * self.dissipation_units[c])
    }

    /// The slot of body `k` among the members, if it is one.
    pub fn slot(&self, k: usize) -> Option<usize> {
        self.slots[k]
    }
}

impl ModelOf<Dyn> for Island<'_> {
    fn derivative_of(&self, _t: f64, y: &Vector<Dyn>, dy: &mut Vector<Dyn>) {
        let u = &self.units;
        for m in 0..self.members.len() {
            let w = y.fixed_rows::<3>(6 * m + 3).into_owned();
            dy.fixed_rows_mut::<3>(6 * m).copy_from(&w);
            dy.fixed_rows_mut::<3>(6 * m + 3).copy_from(&self.gravity);
        }
        let mut immovable_power = 0.0;
        for c in 0..self.contacts.len() {
            let state = self.contact_state(c, y);
            let (elastic, dissipative) = self.force(c, &state);
            let force = (elastic + dissipative) / u.force;
            let rate = state.rate / u.speed;
            let on_j = state.normal * force;
            let [i, j] = self.contacts[c].pair;
            for (k, sign) in [(i, -1.0), (j, 1.0)] {
                match self.slots[k] {
                    Some(m) => {
                        let share = u.mass / self.scene.bodies[k].mass;
                        let mut dw = dy.fixed_rows_mut::<3>(6 * m + 3);
                        dw += on_j * (sign * share);
                    }
                    // The power the contact feeds into an immovable body, with the opposite sign: its work on the
                    // others.
                    None => immovable_power -= sign * on_j.dot(&self.velocity(k, y)) / u.speed,
                }
            }
            let at = self.contact_base + 3 * c;
            dy[at] = force;
            dy[at + 1] = force * rate;
            dy[at + 2] = dissipative / u.force * rate / self.dissipation_units[c];
        }
        dy[self.immovable_work] = immovable_power;
        dy[self.clock] = 1.0;
    }
}
