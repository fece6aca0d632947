//! An island: the bodies that active contacts couple, integrated together under gravity (docs/world.md#islands).
//!
//! The state is scaled like one contact's (lengths in L, speeds in V, time in T = L/V, masses in M, forces in
//! M V²/L, energies in M V²; the units of the contact that started the island). For each member body it holds the
//! displacement since the segment began (never the absolute position: the penetration of two bodies is their
//! relative position at the segment's start plus the difference of two small displacements, without the rounding of
//! where they are in the scene) and the velocity; for each active contact its normal impulse, the work of its normal
//! force and the work of its damping; the work done by immovable bodies; and the clock (scaled time since the segment
//! began), on which the free flight of the bodies outside the island depends. When a contact has friction, the state
//! goes on (after the clock, so that a smooth island's state is unchanged) with every member's spin, scaled as
//! ω r / V like one impact's, and each contact's tangential spring (in M V²/L) and tangential work. A segment lasts
//! until a contact begins or ends, or one switches between sticking and sliding: then the driver builds the next one.
//!
//! Rigid bodies (docs/world.md#rigid-bodies) add, last of all, for each member whose orientation is integrated, its
//! rotation since the segment began as a quaternion (the vector part times ρ/L, ρ the body's reach, so that the
//! absolute tolerance bounds its spheres' displacement by the turn in L) and the change of its angular momentum about
//! its origin — the mass centre, or a pivot — in M V ρ. The angular momentum, not the angular velocity: torque-free
//! flight keeps it exactly, and the contacts' torques on two bodies cancel in the sum, so that the world's angular
//! momentum is kept to rounding; ω = R I⁻¹ Rᵀ L follows from it, the inertia turning with the body. The quaternion is
//! read normalised (the rotation is always a rotation) and a segment's end takes it as the body's orientation, unit.
//! Each contact is a pair of sites (a sphere of a body, or a face), and reads its two points' positions and velocities
//! (v + ω × r) from the sites' motion, so that the normal and tangential laws do not care whether a body turns.

use super::flight::Kinematic;
use super::sites::Sites;
use crate::dynamics::contact::{Kinematics, Mode, Tangential};
use crate::dynamics::unit_or_one;
use crate::geometry::Meeting;
use crate::integrate::{ModelOf, Vector};
use crate::law::ContactLaw;
use crate::scene::FrictionCap;
use crate::scene::WorldScene;
use crate::setup::Friction;
use nalgebra::{DVector, Dyn, Matrix3, Quaternion, UnitQuaternion, Vector3};

/// Scaled penetration below zero that still counts as the edge of a contact: the located end sees the force from
/// inside (Kelvin–Voigt's jump), as in the one-contact models.
const EDGE: f64 = crate::dynamics::normal::EDGE;

/// How far (in the island's force unit) a sticking contact's spring may outgrow the Coulomb cap before it slides: a
/// margin far below the integration's accuracy that keeps the stick switch function above zero at first touch.
const STICK_MARGIN: f64 = 1e-9;

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
    /// Its bodies (the normal points from `pair[0]` to `pair[1]`).
    pub pair: [usize; 2],
    /// Its two sites, one of each body (the bodies themselves in a world of spheres).
    pub sites: [usize; 2],
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
    /// The deepest penetration so far, m, which a yielding law's force remembers (0 for the other laws).
    pub deepest: f64,
    /// The tangential contact, resolved at first touch; `None` for a smooth one.
    pub friction: Option<Friction>,
    /// Sticking or sliding: constant within a segment (a switch ends it).
    pub mode: Mode,
    /// The tangential spring's force on body `pair[0]`, N.
    pub spring: Vector3<f64>,
    /// The direction of the contact points' slip at first touch (zero without friction or without slip): the slip
    /// comes to rest where its component along it falls through zero.
    pub slip_direction: Vector3<f64>,
    /// ∫ Ft·slip dt so far, J: the tangential force's power on the contact points' slip (negative: energy taken
    /// from the bodies' motion, dissipated or held in the spring).
    pub tangential_work: f64,
}

/// What the derivative reads of one contact at an instant: its kinematics, its normal force's dissipative part (N),
/// the whole normal force in the island's force unit, and, with friction, its kinematics as the tangential law reads
/// them and that law's force and spring rate.
#[derive(Debug, Clone, Copy)]
struct ContactParts {
    state: ContactState,
    dissipative: f64,
    force: f64,
    tangential: Option<(Kinematics, crate::dynamics::contact::TangentialForce)>,
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

/// A member whose orientation is integrated (a rigid body), as the segment began (SI).
#[derive(Debug, Clone, Copy)]
struct Turning {
    /// Its body.
    body: usize,
    /// Its reach ρ, m: the farthest of its spheres from its origin (at least the largest radius): the scale of its
    /// rotation and angular momentum states.
    reach: f64,
    /// Its inverse inertia about its origin, in scene axes as the segment began, 1/(kg m²).
    inverse_inertia: Matrix3<f64>,
    /// Its angular momentum about its origin when the segment began, kg m²/s.
    momentum: Vector3<f64>,
    /// Its pivot, if it turns about one (m), and the arm from the pivot to its mass centre as the segment began (m).
    pivot: Option<Vector3<f64>>,
    centre_arm: Vector3<f64>,
}

/// A turning member's motion at one state (SI).
#[derive(Debug, Clone, Copy)]
struct Turn {
    /// The rotation since the segment began, its raw quaternion parts (w, v) and |q|².
    rotation: UnitQuaternion<f64>,
    scalar: f64,
    vector: Vector3<f64>,
    size: f64,
    /// Angular velocity, rad/s; angular momentum about the origin, kg m²/s; the inverse inertia now, 1/(kg m²).
    spin: Vector3<f64>,
    momentum: Vector3<f64>,
    inverse_inertia: Matrix3<f64>,
}

/// A turn and the bits of the seven state values it was formed from.
type CachedTurn = ([u64; 7], Turn);

impl Turn {
    /// (R - 1) a for an arm `a` as the segment began: the turn's displacement of a point of the body, without the
    /// cancellation of R a - a.
    fn turned(&self, a: &Vector3<f64>) -> Vector3<f64> {
        let across = self.vector.cross(a);
        (across * (2.0 * self.scalar) + self.vector.cross(&across) * 2.0) / self.size
    }
}

/// The bodies and contacts of one segment of an island, with what the scaled state means.
#[derive(Debug)]
pub struct Island<'a> {
    scene: &'a WorldScene,
    sites: &'a Sites,
    /// Each site's centre when the segment began (scene-indexed), m.
    site_start: Vec<Vector3<f64>>,
    /// Each site's arm from its body's mass centre when the segment began, m (zero for a site at its centre).
    site_arms: Vec<Vector3<f64>>,
    /// For each member, its place among the turning members (`None`: a sphere, whose orientation nobody reads).
    turning_slot: Vec<Option<usize>>,
    turning: Vec<Turning>,
    /// Each turning member's last turn and the seven state values it was formed from: a turn is asked for many times
    /// at one state (every site's arm and velocity, every contact and event), and formed once.
    turn_cache: Vec<std::cell::Cell<Option<CachedTurn>>>,
    /// The derivative's buffer of [`ContactParts`], kept between its calls.
    parts: std::cell::RefCell<Vec<ContactParts>>,
    /// Where the turning members' states (7 each) begin.
    rigid_base: usize,
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
    /// Each contact's tangential law in the island's units (`None`: smooth).
    tangentials: Vec<Option<Tangential>>,
    /// The unit of each contact's tangential work state, in energy units (its mu, or 1 for a smooth contact).
    friction_units: Vec<f64>,
    /// For each member, M r²/I: how a scaled torque changes its scaled spin.
    spin_gains: Vec<f64>,
    /// Whether any contact has friction: the state then holds spins and tangential springs.
    frictional: bool,
    /// Where the members' spins (3 each) and the contacts' tangential states (spring 3, work 1) begin.
    spin_base: usize,
    tangential_base: usize,
    contact_base: usize,
    immovable_work: usize,
    clock: usize,
    size: usize,
}

impl<'a> Island<'a> {
    /// The segment of `contacts` (their bodies become the members) from the bodies' states `start`, in `units`.
    /// `flyers` are rigid bodies that turn in flight: members without a contact, whose gaps the segment watches.
    pub fn new(
        scene: &'a WorldScene,
        sites: &'a Sites,
        start: &'a [Kinematic],
        flight: &'a [Vector3<f64>],
        contacts: Vec<ActiveContact>,
        flyers: &[usize],
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
        for &k in flyers {
            if slots[k].is_none() && !scene.bodies[k].is_immovable() {
                slots[k] = Some(members.len());
                members.push(k);
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
        let tangentials: Vec<Option<Tangential>> = contacts
            .iter()
            .map(|c| c.friction.map(|f| Tangential::from_friction(&f, units.length, units.force, units.mass)))
            .collect();
        let frictional = tangentials.iter().any(Option::is_some);
        let friction_units = tangentials.iter().map(|t| unit_or_one(t.map_or(0.0, |t| t.friction))).collect();
        let spin_gains = members
            .iter()
            .map(|&k| {
                let body = &scene.bodies[k];
                if body.rotates() { units.mass * body.radius * body.radius / body.inertia } else { 0.0 }
            })
            .collect();
        let spin_base = clock + 1;
        let tangential_base = spin_base + if frictional { 3 * members.len() } else { 0 };
        let rigid_base = tangential_base + if frictional { 4 * contacts.len() } else { 0 };
        let (site_start, site_arms): (Vec<Vector3<f64>>, Vec<Vector3<f64>>) = if sites.any_rigid {
            (0..sites.len())
                .map(|s| {
                    let state = &start[sites.body(s)];
                    (sites.centre(s, state), sites.lever(s, state))
                })
                .unzip()
        } else {
            (start.iter().map(|state| state.position).collect(), vec![Vector3::zeros(); sites.len()])
        };
        let mut turning_slot = vec![None; members.len()];
        let mut turning = Vec::new();
        for (m, &k) in members.iter().enumerate() {
            let body = &scene.bodies[k];
            if !body.is_rigid() {
                continue;
            }
            let state = &start[k];
            let reach = sites
                .of_body(k)
                .map(|s| site_arms[s].norm().max(sites.list[s].radius))
                .fold(0.0, f64::max)
                .max(f64::MIN_POSITIVE);
            let centre_arm = body.pivot.map_or(Vector3::zeros(), |pivot| state.position - pivot);
            let inertia = rigid_body_at(body, state).inertia_about_pivot();
            turning_slot[m] = Some(turning.len());
            turning.push(Turning {
                body: k,
                reach,
                inverse_inertia: crate::eccentric::inverse_inertia(&inertia),
                momentum: inertia * state.spin,
                pivot: body.pivot,
                centre_arm,
            });
        }
        let size = rigid_base + 7 * turning.len();
        Island {
            scene,
            sites,
            site_start,
            site_arms,
            turning_slot,
            turn_cache: vec![std::cell::Cell::new(None); turning.len()],
            parts: std::cell::RefCell::new(Vec::new()),
            turning,
            rigid_base,
            start,
            flight,
            slots,
            members,
            contacts,
            units,
            gravity: scene.world.gravity * (units.time / units.speed),
            dissipation_units,
            touching,
            tangentials,
            friction_units,
            spin_gains,
            frictional,
            spin_base,
            tangential_base,
            contact_base,
            immovable_work,
            clock,
            size,
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
            // A yielding law has no damping: the slot carries its deepest penetration instead.
            y[at + 2] = if contact.law.yields() {
                contact.deepest / u.length
            } else {
                contact.dissipated / (u.energy * self.dissipation_units[c])
            };
        }
        if self.frictional {
            for (m, &k) in self.members.iter().enumerate() {
                let spin = self.start[k].spin * (self.scene.bodies[k].radius / u.speed);
                y.fixed_rows_mut::<3>(self.spin_base + 3 * m).copy_from(&spin);
            }
            for (c, contact) in self.contacts.iter().enumerate() {
                let at = self.tangential_base + 4 * c;
                y.fixed_rows_mut::<3>(at).copy_from(&(contact.spring / u.force));
                y[at + 3] = contact.tangential_work / (u.energy * self.friction_units[c]);
            }
        }
        for r in 0..self.turning.len() {
            // No turn yet: the quaternion's scalar part is 1.
            y[self.rigid_base + 7 * r + 3] = 1.0;
        }
        if self.frictional {
            // A contact that begins sliding carries the direction against its slip (`SLIDE_CARRIER`).
            for (c, contact) in self.contacts.iter().enumerate() {
                if contact.mode == Mode::Slip && contact.spring == Vector3::zeros() {
                    let state = self.contact_state(c, &y);
                    let slip = self.kinematics(c, &state, &y).slip;
                    let at = self.tangential_base + 4 * c;
                    y.fixed_rows_mut::<3>(at).copy_from(&Tangential::carrier(Mode::Slip, &Vector3::zeros(), &slip));
                }
            }
        }
        y
    }

    /// Turning member `r`'s motion at state `y`.
    fn turn(&self, r: usize, y: &DVector<f64>) -> Turn {
        let at = self.rigid_base + 7 * r;
        let key: [u64; 7] = std::array::from_fn(|i| y[at + i].to_bits());
        if let Some((seen, turn)) = self.turn_cache[r].get()
            && seen == key
        {
            return turn;
        }
        let turn = self.form_turn(r, y);
        self.turn_cache[r].set(Some((key, turn)));
        turn
    }

    /// Turning member `r`'s motion at state `y`, formed from its seven state values.
    fn form_turn(&self, r: usize, y: &DVector<f64>) -> Turn {
        let part = &self.turning[r];
        let at = self.rigid_base + 7 * r;
        let vector = y.fixed_rows::<3>(at).into_owned() * (self.units.length / part.reach);
        let scalar = y[at + 3];
        let size = scalar * scalar + vector.norm_squared();
        let rotation = UnitQuaternion::new_normalize(Quaternion::new(scalar, vector.x, vector.y, vector.z));
        let change = y.fixed_rows::<3>(at + 4).into_owned() * (self.units.impulse * part.reach);
        let momentum = part.momentum + change;
        let matrix = rotation.to_rotation_matrix();
        let inverse_inertia = matrix * part.inverse_inertia * matrix.transpose();
        Turn { rotation, scalar, vector, size, spin: inverse_inertia * momentum, momentum, inverse_inertia }
    }

    /// Body `k`'s turn at `y`, if it is a turning member.
    fn turn_of(&self, k: usize, y: &DVector<f64>) -> Option<Turn> {
        let m = self.slots[k]?;
        self.turning_slot[m].map(|r| self.turn(r, y))
    }

    /// Whether a contact of the island caps its friction at `mu |Fn|` (the magnitude cap): its room under the limit
    /// dips to `-|T|` where a damped law's normal force passes through zero, for a few nanoseconds with a soft
    /// spring, and the island's stick–slip switches are then watched for dips (`EventOf::dips`).
    pub fn caps_friction_by_magnitude(&self) -> bool {
        self.tangentials.iter().flatten().any(|law| law.cap == FrictionCap::Magnitude)
    }

    /// Whether body `k` is a member whose orientation the island integrates.
    pub fn turns(&self, k: usize) -> bool {
        self.turning_of(k).is_some()
    }

    /// Body `k`'s turning part, if it is a turning member.
    fn turning_of(&self, k: usize) -> Option<(usize, &Turning)> {
        let r = self.turning_slot[self.slots[k]?]?;
        Some((r, &self.turning[r]))
    }

    /// Body `k`'s orientation at `y` (its orientation when the segment began, for a body that does not turn in it).
    pub fn orientation(&self, k: usize, y: &DVector<f64>) -> UnitQuaternion<f64> {
        match self.turn_of(k, y) {
            Some(turn) => {
                UnitQuaternion::new_normalize(turn.rotation.into_inner() * self.start[k].orientation.into_inner())
            }
            None => self.start[k].orientation,
        }
    }

    /// Body `k`'s angular momentum about its mass centre at `y`, kg m²/s (about its pivot for a pivoted body);
    /// `None` for a body whose orientation is not integrated.
    pub fn angular_momentum(&self, k: usize, y: &DVector<f64>) -> Option<Vector3<f64>> {
        self.turn_of(k, y).map(|turn| turn.momentum)
    }

    /// Site `s`'s arm from its body's origin (its mass centre, or its pivot) at `y`, m, and its displacement since the
    /// segment began, m.
    fn site_arm(&self, s: usize, y: &DVector<f64>) -> (Vector3<f64>, Vector3<f64>) {
        let k = self.sites.body(s);
        let arm = self.site_arms[s];
        match self.turning_of(k) {
            Some((r, part)) => {
                let turn = self.turn(r, y);
                let from_origin = arm + part.centre_arm;
                let turned = turn.turned(&from_origin);
                let displacement = match part.pivot {
                    Some(_) => turned,
                    None => self.displacement(k, y) + turned,
                };
                (from_origin + turned, displacement)
            }
            None => (arm, self.displacement(k, y)),
        }
    }

    /// Site `q`'s centre relative to site `p`'s (m) in two parts: when the segment began, and the change since.
    fn site_relative_parts(&self, p: usize, q: usize, y: &DVector<f64>) -> (Vector3<f64>, Vector3<f64>) {
        (self.site_start[q] - self.site_start[p], self.site_arm(q, y).1 - self.site_arm(p, y).1)
    }

    /// Site `s`'s centre, m.
    pub fn site_position(&self, s: usize, y: &DVector<f64>) -> Vector3<f64> {
        self.site_start[s] + self.site_arm(s, y).1
    }

    /// The velocity (m/s) of the point of body `k` at `arm` (m) from its origin: v + ω × arm.
    fn point_velocity(&self, k: usize, arm: &Vector3<f64>, y: &DVector<f64>) -> Vector3<f64> {
        match self.turning_of(k) {
            Some((r, part)) => {
                let spin = self.turn(r, y).spin;
                let origin = if part.pivot.is_some() { Vector3::zeros() } else { self.velocity(k, y) };
                origin + spin.cross(arm)
            }
            None if *arm == Vector3::zeros() => self.velocity(k, y),
            None => self.velocity(k, y) + self.spin(k, y).cross(arm),
        }
    }

    /// Site `s`'s centre's velocity, m/s.
    pub fn site_velocity(&self, s: usize, y: &DVector<f64>) -> Vector3<f64> {
        let k = self.sites.body(s);
        if self.turning_of(k).is_none() && self.site_arms[s] == Vector3::zeros() {
            return self.velocity(k, y);
        }
        self.point_velocity(k, &self.site_arm(s, y).0, y)
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
        if let Some((r, part)) = self.turning_of(k)
            && part.pivot.is_some()
        {
            return self.turn(r, y).turned(&part.centre_arm);
        }
        match self.slots[k] {
            Some(m) => y.fixed_rows::<3>(6 * m).into_owned() * self.units.length,
            None => self.start[k].displacement(y[self.clock] * self.units.time, &self.flight[k]),
        }
    }

    /// Body `k`'s velocity, m/s.
    pub fn velocity(&self, k: usize, y: &DVector<f64>) -> Vector3<f64> {
        if let Some((r, part)) = self.turning_of(k)
            && part.pivot.is_some()
        {
            let turn = self.turn(r, y);
            return turn.spin.cross(&(part.centre_arm + turn.turned(&part.centre_arm)));
        }
        match self.slots[k] {
            Some(m) => y.fixed_rows::<3>(6 * m + 3).into_owned() * self.units.speed,
            None => self.start[k].velocity + self.flight[k] * (y[self.clock] * self.units.time),
        }
    }

    /// Body `k`'s spin, scaled as ω r / V (zero for a flat body, whose lever arms are zero).
    fn scaled_spin(&self, k: usize, y: &DVector<f64>) -> Vector3<f64> {
        let body = &self.scene.bodies[k];
        match self.slots[k] {
            Some(m) if self.frictional => y.fixed_rows::<3>(self.spin_base + 3 * m).into_owned(),
            _ if body.is_flat() => Vector3::zeros(),
            _ => self.start[k].spin * (body.radius / self.units.speed),
        }
    }

    /// Body `k`'s angular velocity, rad/s.
    pub fn spin(&self, k: usize, y: &DVector<f64>) -> Vector3<f64> {
        if let Some(turn) = self.turn_of(k, y) {
            return turn.spin;
        }
        match self.slots[k] {
            Some(m) if self.frictional => {
                y.fixed_rows::<3>(self.spin_base + 3 * m).into_owned()
                    * (self.units.speed / self.scene.bodies[k].radius)
            }
            _ => self.start[k].spin,
        }
    }

    /// Contact `c`'s kinematics at `state` (its SI kinematics at `y`) in the island's units, as one impact's
    /// tangential law reads them: penetration in L, rate and slip in V, the turning of the normal in 1/T, and the
    /// lever arms over the radii. Two spheres share the overlap in the ratio of their radii (the arms add up to the line
    /// of centres, so free spheres keep their angular momentum); on a face the sphere's arm is its radius.
    fn kinematics(&self, c: usize, state: &ContactState, y: &DVector<f64>) -> Kinematics {
        let u = &self.units;
        let contact = &self.contacts[c];
        let [i, j] = contact.pair;
        let n = state.normal;
        let arms = match contact.meeting {
            Meeting::Spheres { reach } => {
                let arm = n * (state.distance / reach);
                [arm, -arm]
            }
            Meeting::Face { sign, .. } if sign > 0.0 => [Vector3::zeros(), -n],
            Meeting::Face { .. } => [n, Vector3::zeros()],
        };
        let w = state.relative_velocity / u.speed;
        let normal_rate = if state.distance.is_finite() {
            (w - n * n.dot(&w)) * (u.length / state.distance)
        } else {
            Vector3::zeros()
        };
        let relative = if self.turns_at(c) {
            let levers = self.levers(c, &arms, y);
            (self.point_velocity(i, &levers[0], y) - self.point_velocity(j, &levers[1], y)) / u.speed
        } else {
            -w + self.scaled_spin(i, y).cross(&arms[0]) - self.scaled_spin(j, y).cross(&arms[1])
        };
        Kinematics {
            normal: n,
            penetration: state.penetration / u.length,
            rate: state.rate / u.speed,
            arms,
            slip: relative - n * relative.dot(&n),
            normal_rate,
        }
    }

    /// Whether contact `c` has a side whose contact point is not a sphere's at its centre: a turning member, or a site
    /// off its body's centre. Its kinematics then read the points' velocities as v + ω × r from the body's origin.
    fn turns_at(&self, c: usize) -> bool {
        let contact = &self.contacts[c];
        (0..2).any(|side| {
            self.site_arms[contact.sites[side]] != Vector3::zeros() || self.turning_of(contact.pair[side]).is_some()
        })
    }

    /// Contact `c`'s contact point's arm from each body's origin (mass centre or pivot), m: its site's arm, and the
    /// contact's `arms` (over the site's radius: from the sphere's centre to the contact point) times the radius.
    fn levers(&self, c: usize, arms: &[Vector3<f64>; 2], y: &DVector<f64>) -> [Vector3<f64>; 2] {
        let contact = &self.contacts[c];
        [0, 1].map(|side| {
            let s = contact.sites[side];
            let (arm, _) = self.site_arm(s, y);
            if arms[side] == Vector3::zeros() { arm } else { arm + arms[side] * self.sites.list[s].radius }
        })
    }

    /// The component of contact `c`'s slip along its direction at first touch, in V.
    pub fn slip_along_start(&self, c: usize, y: &DVector<f64>) -> f64 {
        let state = self.contact_state(c, y);
        self.kinematics(c, &state, y).slip.dot(&self.contacts[c].slip_direction)
    }

    /// Contact `c`'s tangential spring at `y` (in M V²/L), kept in the tangent plane of the normal `normal`.
    fn spring(&self, c: usize, normal: &Vector3<f64>, y: &DVector<f64>) -> Vector3<f64> {
        let raw = y.fixed_rows::<3>(self.tangential_base + 4 * c).into_owned();
        raw - normal * raw.dot(normal)
    }

    /// Contact `c`'s tangential force on body `pair[0]` (in M V²/L) and its law's parts, for its normal force
    /// `normal_force` (M V²/L): `None` for a smooth contact.
    fn tangential(
        &self,
        c: usize,
        state: &ContactState,
        normal_force: f64,
        y: &DVector<f64>,
    ) -> Option<(Kinematics, crate::dynamics::contact::TangentialForce)> {
        let (law, kinematics, spring) = self.tangential_state(c, state, y)?;
        let force = law.evaluate(self.contacts[c].mode, &spring, &kinematics, normal_force);
        Some((kinematics, force))
    }

    /// What a stick–slip switch of contact `c` is judged by at `y`: its tangential law, kinematics and spring, and its
    /// normal force and that force's elastic part, both in the island's force unit (`None` for a smooth contact).
    fn switching_state(&self, c: usize, y: &DVector<f64>) -> Option<(&Tangential, Kinematics, Vector3<f64>, f64, f64)> {
        let u = &self.units;
        let state = self.contact_state(c, y);
        let (law, kinematics, spring) = self.tangential_state(c, &state, y)?;
        let (elastic, dissipative) = self.force(c, &state, y);
        Some((law, kinematics, spring, (elastic + dissipative) / u.force, elastic / u.force))
    }

    /// Contact `c`'s tangential law, its kinematics at `state` and its spring (`None` for a smooth contact).
    fn tangential_state(
        &self,
        c: usize,
        state: &ContactState,
        y: &DVector<f64>,
    ) -> Option<(&Tangential, Kinematics, Vector3<f64>)> {
        let law = self.tangentials[c].as_ref()?;
        let kinematics = self.kinematics(c, state, y);
        let spring = self.spring(c, &kinematics.normal, y);
        Some((law, kinematics, spring))
    }

    /// Whether any contact of the island has friction.
    pub fn frictional(&self) -> bool {
        self.frictional
    }

    /// The function whose fall through zero switches contact `c` between sticking and sliding (in the island's
    /// force or force-rate units); `None` for a smooth contact.
    pub fn switch_value(&self, c: usize, y: &DVector<f64>) -> Option<f64> {
        let u = &self.units;
        let (law, kinematics, state, normal_force, elastic) = self.switching_state(c, y)?;
        let mode = self.contacts[c].mode;
        let rate = if mode.is_sliding() { self.force_rate(c, y) * u.time / u.force } else { 0.0 };
        let value = law.carried_switch_function(mode, &state, &kinematics, normal_force, rate, elastic);
        // A sticking contact may begin with cap and spring both zero (no slip at first touch, no force yet): its
        // `mu Fn - |T|` starts at zero, and a spring that then outgrows the cap (a ball set down on a slope) would
        // never be seen to fall through it. Sticking holds to STICK_MARGIN of the force unit beyond the cap — far
        // below the integration's accuracy — so that the function starts above zero.
        Some(if mode == Mode::Stick { value + STICK_MARGIN } else { value })
    }

    /// Contact `c`'s mode after a located zero of its switch function at `y`, and the spring (N) to set there, if any
    /// ([`Tangential::next_mode`]); `None` for a smooth contact.
    pub fn next_mode(&self, c: usize, y: &DVector<f64>) -> Option<(Mode, Option<Vector3<f64>>)> {
        let u = &self.units;
        let (law, kinematics, state, normal_force, elastic) = self.switching_state(c, y)?;
        let mode = self.contacts[c].mode;
        let rate = self.force_rate(c, y) * u.time / u.force;
        let (next, spring) = law.carried_next_mode(mode, &state, &kinematics, normal_force, rate, elastic);
        Some((next, Some(spring * u.force)))
    }

    /// The part of body `k`'s angular velocity (rad/s) that no friction of its contacts can change: the spin about
    /// their common normal when all its active contacts share one normal's line (a ball on a floor spinning about the
    /// vertical: point contacts carry no torsion), none otherwise.
    pub fn torsion(&self, k: usize, y: &DVector<f64>) -> Vector3<f64> {
        if self.turning_of(k).is_some() {
            // A rigid body rests without turning: its points' contacts hold every spin.
            return Vector3::zeros();
        }
        let spin = self.spin(k, y);
        let Some(m) = self.slots[k] else { return spin };
        let normals: Vec<Vector3<f64>> = self.touching[m].iter().map(|&c| self.contact_state(c, y).normal).collect();
        let Some(first) = normals.first() else { return spin };
        if normals.iter().all(|n| n.cross(first).norm() <= 1e-9) { first * first.dot(&spin) } else { Vector3::zeros() }
    }

    /// Contact `c`'s tangential state at `y` (SI): the spring's force on body `pair[0]` (N), the tangential work (J)
    /// and the energy the spring holds (J; no more than the Coulomb cap lets it hold, as in one impact).
    pub fn tangential_integrals(&self, c: usize, y: &DVector<f64>) -> (Vector3<f64>, f64, f64) {
        let Some(law) = self.tangentials[c].as_ref() else { return (Vector3::zeros(), 0.0, 0.0) };
        let u = &self.units;
        let at = self.tangential_base + 4 * c;
        let state = self.contact_state(c, y);
        let (elastic, dissipative) = self.force(c, &state, y);
        let spring = self.spring(c, &state.normal, y);
        let kt = law.stiffness_at(state.penetration / u.length);
        let normal_force = (elastic + dissipative) / u.force;
        // (Sliding, the spring holds the cap: `held` is judged on the force the state carries.)
        let force = if self.contacts[c].mode == Mode::Slip {
            law.carried(Mode::Slip, &spring, &self.kinematics(c, &state, y).slip, normal_force)
        } else {
            spring
        };
        let stored = law.held(self.contacts[c].mode, &force, normal_force);
        let energy = if kt > 0.0 { stored * stored / (2.0 * kt) } else { 0.0 };
        (spring * u.force, y[at + 3] * u.energy * self.friction_units[c], energy * u.energy)
    }

    /// Body `k`'s position, m.
    pub fn position(&self, k: usize, y: &DVector<f64>) -> Vector3<f64> {
        self.start[k].position + self.displacement(k, y)
    }

    /// How sites `p` and `q` (meeting as `meeting`) stand at state `y`.
    pub fn site_state(&self, p: usize, q: usize, meeting: &Meeting, y: &DVector<f64>) -> ContactState {
        let (start, moved) = self.site_relative_parts(p, q, y);
        let (penetration, normal, distance) = meeting.penetration_moved(&start, &moved);
        let relative_velocity = self.site_velocity(q, y) - self.site_velocity(p, y);
        ContactState { penetration, rate: -relative_velocity.dot(&normal), normal, relative_velocity, distance }
    }

    /// The penetration of sites `p` and `q` (meeting as `meeting`) at state `y`, m: [`Island::site_state`]'s, without
    /// the velocities (a watched pair's gap is read at every step).
    pub fn site_penetration(&self, p: usize, q: usize, meeting: &Meeting, y: &DVector<f64>) -> f64 {
        let (start, moved) = self.site_relative_parts(p, q, y);
        meeting.penetration_moved(&start, &moved).0
    }

    /// Contact `c`'s kinematics at state `y`.
    pub fn contact_state(&self, c: usize, y: &DVector<f64>) -> ContactState {
        let contact = &self.contacts[c];
        self.site_state(contact.sites[0], contact.sites[1], &contact.meeting, y)
    }

    /// Contact `c`'s normal force split into its elastic and dissipative parts, N, at its kinematics `state` (of the
    /// island's state `y`, which a yielding law's memory is read from).
    pub fn force(&self, c: usize, state: &ContactState, y: &DVector<f64>) -> (f64, f64) {
        let d = state.penetration;
        let edge = EDGE * self.units.length;
        let d = if d > -edge { d.max(0.0) } else { d };
        let law = &self.contacts[c].law;
        let parts = if law.yields() {
            law.split_force_after(d, state.rate, self.deepest(c, d, y))
        } else {
            law.split_force(d, state.rate)
        };
        (parts.elastic, parts.dissipative)
    }

    /// Contact `c`'s tangential stiffness kt (N/m) at penetration `d` (m); zero on a smooth contact.
    pub fn tangential_stiffness(&self, c: usize, d: f64) -> f64 {
        let u = &self.units;
        self.tangentials[c].as_ref().map_or(0.0, |law| law.stiffness_at(d / u.length) * u.force / u.length)
    }

    /// Contact `c`'s friction coefficient (zero on a smooth contact).
    pub fn friction_coefficient(&self, c: usize) -> f64 {
        self.tangentials[c].as_ref().map_or(0.0, |law| law.friction)
    }

    /// The penetration (m) at which contact `c`, standing still, carries `weight` (N): Newton's steps on its force from
    /// its penetration at `y` (a resting contact's, within its ringing of it).
    pub fn static_penetration(&self, c: usize, weight: f64, y: &DVector<f64>) -> f64 {
        let mut state = ContactState { rate: 0.0, ..self.contact_state(c, y) };
        for _ in 0..8 {
            let d = state.penetration.max(0.0);
            let (elastic, dissipative) = self.force(c, &state, y);
            let gradient = self.contacts[c].law.force_gradient(d, 0.0).0;
            if gradient.is_nan() || gradient <= 0.0 {
                break;
            }
            let step = (weight - elastic - dissipative) / gradient;
            state.penetration = d + step;
            if step.abs() <= 1e-15 * d {
                break;
            }
        }
        state.penetration.max(0.0)
    }

    /// Contact `c`'s deepest penetration so far, m, at penetration `d` (m) and state `y`: for a yielding law its state,
    /// or `d` where that is deeper (the state grows only at it: [`crate::dynamics::normal::deepening`]).
    pub fn deepest(&self, c: usize, d: f64, y: &DVector<f64>) -> f64 {
        let at = self.contact_base + 3 * c;
        (y[at + 2] * self.units.length).max(d)
    }

    /// Body `k`'s acceleration at state `y` (m/s²): gravity and the forces of its own contacts (none for a body
    /// outside the island, whose flight is free, or an immovable one).
    pub fn acceleration_of(&self, k: usize, y: &DVector<f64>) -> Vector3<f64> {
        let body = &self.scene.bodies[k];
        let Some(m) = self.slots[k] else { return self.flight[k] };
        if let Some((r, part)) = self.turning_of(k)
            && part.pivot.is_some()
        {
            // The mass centre of a pivoted body moves on a sphere about the pivot.
            let turn = self.turn(r, y);
            let arm = part.centre_arm + turn.turned(&part.centre_arm);
            let alpha = self.angular_acceleration(r, &turn, y);
            return alpha.cross(&arm) + turn.spin.cross(&turn.spin.cross(&arm));
        }
        let mut a = self.scene.world.gravity;
        for &c in &self.touching[m] {
            let state = self.contact_state(c, y);
            let (elastic, dissipative) = self.force(c, &state, y);
            let mut on_j = state.normal * ((elastic + dissipative) / body.mass);
            if let Some((_, tangential)) = self.tangential(c, &state, (elastic + dissipative) / self.units.force, y) {
                on_j -= tangential.force * (self.units.force / body.mass);
            }
            if self.contacts[c].pair[1] == k { a += on_j } else { a -= on_j }
        }
        a
    }

    /// dF/dt of contact `c` (N/s): the force's gradient along the motion, with d'' from the two bodies'
    /// accelerations and the turning of the normal. Its fall through zero is the force peak.
    pub fn force_rate(&self, c: usize, y: &DVector<f64>) -> f64 {
        let state = self.contact_state(c, y);
        let [p, q] = self.contacts[c].sites;
        let relative_acceleration = self.site_acceleration(q, y) - self.site_acceleration(p, y);
        self.force_rate_at(c, &state, &relative_acceleration, y)
    }

    /// [`Island::force_rate`] from contact `c`'s kinematics `state` and the relative acceleration (m/s²) of its two
    /// spheres' centres, q's less p's.
    fn force_rate_at(
        &self,
        c: usize,
        state: &ContactState,
        relative_acceleration: &Vector3<f64>,
        y: &DVector<f64>,
    ) -> f64 {
        let contact = &self.contacts[c];
        let u = &state.relative_velocity;
        let turning = if state.distance.is_finite() {
            (u - state.normal * state.normal.dot(u)) / state.distance
        } else {
            Vector3::zeros()
        };
        let second = -relative_acceleration.dot(&state.normal) - u.dot(&turning);
        let d = state.penetration.max(0.0);
        let (by_penetration, by_rate) = if contact.law.yields() {
            contact.law.force_gradient_after(d, state.rate, self.deepest(c, d, y))
        } else {
            contact.law.force_gradient(d, state.rate)
        };
        by_penetration * state.rate + by_rate * second
    }

    /// Every contact's [`ContactParts`] at `y`, as the derivative reads them, each contact's forces found once. (No
    /// rate of a normal force: a sliding spring's state carries its direction alone, and its rate needs none.)
    /// (Written into `parts`, the buffer of an earlier call: the derivative allocates nothing per evaluation.)
    fn contact_parts(&self, y: &DVector<f64>, parts: &mut Vec<ContactParts>) {
        let u = &self.units;
        parts.clear();
        parts.extend((0..self.contacts.len()).map(|c| {
            let state = self.contact_state(c, y);
            let (elastic, dissipative) = self.force(c, &state, y);
            let force = (elastic + dissipative) / u.force;
            // (Neither the tangential force nor the spring's rate depends on the normal force's rate.)
            let tangential = self.tangential(c, &state, force, y);
            ContactParts { state, dissipative, force, tangential }
        }));
    }

    /// The torque (N m) on turning member `r` about its origin at `y`: its contacts' normal forces at its spheres'
    /// centres and their tangential forces at the contact points, and, for a pivoted body, gravity at its mass centre.
    fn torque(&self, r: usize, y: &DVector<f64>) -> Vector3<f64> {
        let part = &self.turning[r];
        let k = part.body;
        let m = self.slots[k].expect("a turning part is a member");
        let mut torque = Vector3::zeros();
        if part.pivot.is_some() {
            let arm = part.centre_arm + self.turn(r, y).turned(&part.centre_arm);
            torque += arm.cross(&(self.scene.world.gravity * self.scene.bodies[k].mass));
        }
        for &c in &self.touching[m] {
            let contact = &self.contacts[c];
            let side = if contact.pair[0] == k { 0 } else { 1 };
            let sign = if side == 1 { 1.0 } else { -1.0 };
            let state = self.contact_state(c, y);
            let (elastic, dissipative) = self.force(c, &state, y);
            let (lever, _) = self.site_arm(contact.sites[side], y);
            torque += lever.cross(&(state.normal * ((elastic + dissipative) * sign)));
            if let Some((kinematics, tangential)) =
                self.tangential(c, &state, (elastic + dissipative) / self.units.force, y)
            {
                let levers = self.levers(c, &kinematics.arms, y);
                torque += levers[side].cross(&(tangential.force * (-sign * self.units.force)));
            }
        }
        torque
    }

    /// Turning member `r`'s angular acceleration (rad/s²) at `y`, its motion `turn`: I⁻¹ (τ - ω × L), Euler's
    /// equations in the scene's frame.
    fn angular_acceleration(&self, r: usize, turn: &Turn, y: &DVector<f64>) -> Vector3<f64> {
        turn.inverse_inertia * (self.torque(r, y) - turn.spin.cross(&turn.momentum))
    }

    /// Site `s`'s centre's acceleration at `y`, m/s²: its body's, and for a turning member α × r + ω × (ω × r).
    fn site_acceleration(&self, s: usize, y: &DVector<f64>) -> Vector3<f64> {
        let k = self.sites.body(s);
        let Some((r, part)) = self.turning_of(k) else { return self.acceleration_of(k, y) };
        let turn = self.turn(r, y);
        let (arm, _) = self.site_arm(s, y);
        let origin = if part.pivot.is_some() { Vector3::zeros() } else { self.acceleration_of(k, y) };
        origin + self.angular_acceleration(r, &turn, y).cross(&arm) + turn.spin.cross(&turn.spin.cross(&arm))
    }

    /// The function whose fall through zero ends contact `c`: its penetration (m), or — ended by its force — the law's
    /// force continued past d = 0 (docs/numerics.md#separation-on-the-continued-force).
    pub fn separation_value(&self, c: usize, y: &DVector<f64>) -> f64 {
        let state = self.contact_state(c, y);
        let contact = &self.contacts[c];
        if contact.law.yields() {
            // Where its force returns to zero: at the dent.
            let deepest = self.deepest(c, state.penetration, y);
            contact.law.separation_function_after(state.penetration, state.rate, deepest) / self.units.length
        } else if contact.on_force {
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
        self.motion_energy_beyond(y, group, held, f64::INFINITY)
    }

    /// [`Island::motion_energy`] where it is at most `bound` (J); beyond, a lower bound of it that is itself beyond
    /// `bound`: the kinetic energy of the members' translation (relative to their mean for a free group), which
    /// every other term adds to. A watch of rest reads the whole sum only near rest; a body that moves is seen to
    /// without its contacts' forces.
    pub fn motion_energy_beyond(&self, y: &DVector<f64>, group: &[usize], held: bool, bound: f64) -> f64 {
        if bound.is_finite() {
            let mass = |m: usize| self.scene.bodies[self.members[m]].mass;
            let mean = if held {
                Vector3::zeros()
            } else {
                let total: f64 = group.iter().map(|&m| mass(m)).sum();
                group
                    .iter()
                    .fold(Vector3::zeros(), |sum, &m| sum + self.velocity(self.members[m], y) * (mass(m) / total))
            };
            let translation: f64 =
                group.iter().map(|&m| 0.5 * mass(m) * (self.velocity(self.members[m], y) - mean).norm_squared()).sum();
            if translation > bound {
                return translation;
            }
        }
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
            if let Some((r, _)) = self.turning_of(self.members[m]) {
                // A rigid body rests when it neither turns nor is turned: its rotation's energy, and its angular
                // acceleration's as the translation's above.
                let turn = self.turn(r, y);
                let alpha = self.angular_acceleration(r, &turn, y);
                let inertia = turn.inverse_inertia.try_inverse().unwrap_or_else(Matrix3::zeros);
                let turned = 0.5 * alpha.dot(&(inertia * alpha));
                let potential = if omega2 > 0.0 {
                    turned / omega2
                } else if turned > 0.0 {
                    f64::INFINITY
                } else {
                    0.0
                };
                energy += 0.5 * turn.spin.dot(&turn.momentum) + potential;
                continue;
            }
            if held && self.frictional {
                // A body an immovable one holds is at rest only when it no longer turns either — but for the spin no
                // friction can change (about the normal of a point contact).
                let k = self.members[m];
                let turning = self.spin(k, y) - self.torsion(k, y);
                energy += self.scene.bodies[k].kinetic_energy(&Vector3::zeros(), &turning);
            }
        }
        energy
    }

    /// Contact `c`'s integrals at state `y` (SI): normal impulse, normal work, dissipated energy (for a yielding
    /// law, the work less what its unloading would give back: the dent's).
    pub fn integrals(&self, c: usize, y: &DVector<f64>) -> (f64, f64, f64) {
        let u = &self.units;
        let at = self.contact_base + 3 * c;
        let (impulse, work) = (y[at] * u.impulse, y[at + 1] * u.energy);
        let law = &self.contacts[c].law;
        if law.yields() {
            let d = self.contact_state(c, y).penetration.max(0.0);
            return (impulse, work, work - law.elastic_energy_after(d, self.deepest(c, d, y)));
        }
        (impulse, work, y[at + 2] * u.energy * self.dissipation_units[c])
    }

    /// The energy contact `c`'s spring holds at state `y`, J: the law's elastic energy at its penetration (what a
    /// yielding law's unloading would give back).
    pub fn elastic_energy(&self, c: usize, y: &DVector<f64>) -> f64 {
        let d = self.contact_state(c, y).penetration.max(0.0);
        let law = &self.contacts[c].law;
        if law.yields() { law.elastic_energy_after(d, self.deepest(c, d, y)) } else { law.elastic_energy(d) }
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
        // Spins change and springs load only through friction (added below); rotations and angular momenta at the end.
        dy.rows_mut(self.spin_base, self.size - self.spin_base).fill(0.0);
        let turns: Vec<Turn> = (0..self.turning.len()).map(|r| self.turn(r, y)).collect();
        for part in &self.turning {
            if part.pivot.is_some() {
                // A pivoted body's mass centre follows its rotation: its translation's states rest.
                let m = self.slots[part.body].expect("a turning part is a member");
                dy.fixed_rows_mut::<6>(6 * m).fill(0.0);
            }
        }
        let mut immovable_power = 0.0;
        let mut parts = self.parts.take();
        self.contact_parts(y, &mut parts);
        for (c, part) in parts.iter().enumerate() {
            let ContactParts { state, dissipative, force, .. } = *part;
            let rate = state.rate / u.speed;
            let on_j = state.normal * force;
            let [i, j] = self.contacts[c].pair;
            for (side, k, sign) in [(0, i, -1.0), (1, j, 1.0)] {
                match self.slots[k] {
                    Some(m) => {
                        if let Some(r) = self.turning_slot[m] {
                            // The normal force acts along the line of the spheres' centres: its moment about the
                            // origin has the arm to the sphere's centre.
                            let part = &self.turning[r];
                            let (lever, _) = self.site_arm(self.contacts[c].sites[side], y);
                            let mut dh = dy.fixed_rows_mut::<3>(self.rigid_base + 7 * r + 4);
                            dh += (lever / part.reach).cross(&(on_j * sign));
                            if part.pivot.is_some() {
                                continue;
                            }
                        }
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
            dy[at + 2] = if self.contacts[c].law.yields() {
                crate::dynamics::normal::deepening(state.penetration / u.length, y[at + 2], rate)
            } else {
                dissipative / u.force * rate / self.dissipation_units[c]
            };
            // Friction: the tangential force Ft on body i (-Ft on body j) at the contact point, its torques, and the
            // spring's rate (a sliding spring follows the Coulomb cap, so it needs the normal force's rate: see
            // `contact_parts`).
            let Some((kinematics, tangential)) = part.tangential else { continue };
            let levers = if self.turns_at(c) { Some(self.levers(c, &kinematics.arms, y)) } else { None };
            for (side, k, sign, arm) in [(0, i, 1.0, kinematics.arms[0]), (1, j, -1.0, kinematics.arms[1])] {
                let on_k = tangential.force * sign;
                match self.slots[k] {
                    Some(m) if self.turning_slot[m].is_some() => {
                        let r = self.turning_slot[m].expect("a turning member");
                        let part = &self.turning[r];
                        let lever = levers.expect("a turning member's contact has levers")[side];
                        let mut dh = dy.fixed_rows_mut::<3>(self.rigid_base + 7 * r + 4);
                        dh += (lever / part.reach).cross(&on_k);
                        if part.pivot.is_none() {
                            let share = u.mass / self.scene.bodies[k].mass;
                            let mut dw = dy.fixed_rows_mut::<3>(6 * m + 3);
                            dw += on_k * share;
                        }
                    }
                    Some(m) => {
                        let share = u.mass / self.scene.bodies[k].mass;
                        let mut dw = dy.fixed_rows_mut::<3>(6 * m + 3);
                        dw += on_k * share;
                        let torque = arm.cross(&on_k) * self.spin_gains[m];
                        let mut ds = dy.fixed_rows_mut::<3>(self.spin_base + 3 * m);
                        ds += torque;
                    }
                    None => {
                        let power =
                            on_k.dot(&(self.velocity(k, y) / u.speed)) + arm.cross(&on_k).dot(&self.scaled_spin(k, y));
                        immovable_power -= power;
                    }
                }
            }
            let at = self.tangential_base + 4 * c;
            dy.fixed_rows_mut::<3>(at).copy_from(&tangential.spring_rate);
            dy[at + 3] = tangential.force.dot(&kinematics.slip) / self.friction_units[c];
        }
        for (r, (part, turn)) in self.turning.iter().zip(&turns).enumerate() {
            let at = self.rigid_base + 7 * r;
            // q' = ½ (0, ω) ⊗ q, in the time unit T, the vector part times ρ/L.
            let spin = turn.spin * u.time;
            let vector = (spin * turn.scalar + spin.cross(&turn.vector)) * (0.5 * part.reach / u.length);
            dy.fixed_rows_mut::<3>(at).copy_from(&vector);
            dy[at + 3] = -0.5 * spin.dot(&turn.vector);
            if part.pivot.is_some() {
                // Gravity's moment about the pivot, at the mass centre.
                let arm = part.centre_arm + turn.turned(&part.centre_arm);
                let weight = self.scene.world.gravity * (self.scene.bodies[part.body].mass / u.force);
                let mut dh = dy.fixed_rows_mut::<3>(at + 4);
                dh += (arm / part.reach).cross(&weight);
            }
        }
        dy[self.immovable_work] = immovable_power;
        dy[self.clock] = 1.0;
        self.parts.replace(parts);
    }
}

/// Body `body` at `state` as the instantaneous eccentric impact takes it: its inertia turned with it (a body that does
/// not rotate keeps its infinite inertia unturned).
pub fn rigid_body_at(body: &crate::body::Body, state: &super::flight::Kinematic) -> crate::eccentric::RigidBody {
    crate::eccentric::RigidBody {
        mass: body.mass,
        inertia: if body.rotates() { turned_inertia(body, &state.orientation) } else { body.inertia_matrix() },
        centre: state.position,
        velocity: state.velocity,
        spin: state.spin,
        pivot: body.pivot,
    }
}

/// Body `body`'s inertia tensor about its mass centre turned by `orientation` from the scene axes at t = 0, kg m²:
/// R I Rᵀ.
pub fn turned_inertia(body: &crate::body::Body, orientation: &UnitQuaternion<f64>) -> Matrix3<f64> {
    let matrix = orientation.to_rotation_matrix();
    matrix * body.inertia_matrix() * matrix.transpose()
}
