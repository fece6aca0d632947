//! One contact between two bodies in 3-D, in scaled variables: where the normal points and how deep the bodies
//! overlap, how fast the contact points slip, and the tangential (friction) force of a Mindlin spring capped by
//! Coulomb's law. Pure functions of the relative kinematics — each contact of a run with several would use them.
//!
//! Conventions (docs/scene.md): the normal n points from body 1 to body 2; the penetration is d = r1 + r2 - |x2 - x1|
//! for two spheres and the overlap with the wall's plane for a sphere on a wall; the slip is the velocity of body 1's
//! contact point relative to body 2's, across the normal; the tangential force Ft acts on body 1, -Ft on body 2.
//!
//! The contact point divides the line of centres in the ratio of the radii (the overlap shared in proportion to
//! them): the lever arms are a1 = r1/(r1 + r2) (x2 - x1) and a2 = -r2/(r1 + r2) (x2 - x1). They add up to the line
//! of centres, so two free spheres conserve angular momentum exactly; on a wall the sphere's arm is its radius, as
//! rigid-body theory has it.

use crate::integrate::State;
use crate::scene::{FrictionCap, TangentialUnloading};
use nalgebra::Vector3;

/// The geometry of a contact, scaled by the penetration scale L.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shape {
    /// Two spheres: the normal follows the line of centres.
    Spheres {
        /// (r1 + r2)/L.
        reach: f64,
        /// The line of centres at first contact, (x2 - x1)/L: length `reach`, along the first normal.
        contact_vector: Vector3<f64>,
    },
    /// A sphere and a flat body: the wall's normal, fixed.
    Wall { normal: Vector3<f64>, sphere: usize },
}

/// Where the contact stands at one instant (scaled).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Kinematics {
    pub normal: Vector3<f64>,
    /// d/L.
    pub penetration: f64,
    /// d'/v0 = -(relative velocity)·n.
    pub rate: f64,
    /// Lever arms a_i / r_i, from each centre to the contact point (zero for a flat body).
    pub arms: [Vector3<f64>; 2],
    /// Slip of the contact points across the normal, in units of v0.
    pub slip: Vector3<f64>,
    /// dn/dt in units of 1/T.
    pub normal_rate: Vector3<f64>,
}

impl Shape {
    /// The contact's kinematics for a relative displacement `displacement` of body 2 with respect to body 1 since
    /// first contact (in L), relative velocity `relative_velocity` = v2 - v1 (in v0), and spins scaled as
    /// omega_i r_i / v0 (so that omega x a is `spin x arm` in units of v0).
    pub fn kinematics(
        &self,
        displacement: &Vector3<f64>,
        relative_velocity: &Vector3<f64>,
        spins: &[Vector3<f64>; 2],
    ) -> Kinematics {
        let (normal, penetration, arms, normal_rate) = match *self {
            Shape::Spheres { reach, contact_vector } => {
                let centres = contact_vector + displacement;
                let distance = centres.norm();
                let normal = centres / distance;
                // d = R - |r_c + rho| without the cancellation of two nearly equal lengths:
                // |r_c + rho|² - R² = 2 r_c·rho + rho·rho.
                let penetration =
                    -(2.0 * contact_vector.dot(displacement) + displacement.norm_squared()) / (distance + reach);
                let arm = centres / reach;
                let across = relative_velocity - normal * relative_velocity.dot(&normal);
                (normal, penetration, [arm, -arm], across / distance)
            }
            Shape::Wall { normal, sphere } => {
                let mut arms = [Vector3::zeros(); 2];
                arms[sphere] = if sphere == 0 { normal } else { -normal };
                (normal, -displacement.dot(&normal), arms, Vector3::zeros())
            }
        };
        let relative = -relative_velocity + spins[0].cross(&arms[0]) - spins[1].cross(&arms[1]);
        let slip = relative - normal * relative.dot(&normal);
        Kinematics { normal, penetration, rate: -relative_velocity.dot(&normal), arms, slip, normal_rate }
    }
}

/// Fastest turning of a sliding spring towards its loading, in radians per scaled time unit T (an elastic contact
/// lasts about 3 T): faster turning is a quasi-static alignment, approximated at this rate.
pub const MAX_TURN_RATE: f64 = 1e4;

/// The time (in the model's time unit T) within which a stick's loading `kt |slip|` would unload a reversed sliding
/// spring, for the spring to count as a rounding remainder and be turned against the slip while the cap grows
/// ([`Tangential::sliding_direction`]: the slide paths' rule; the 3-D models' sliding state carries a direction that
/// is never such a remainder).
pub const QUICK_REVERSAL: f64 = 1e-3;

/// Most stick–slip switches one contact may take before the run is abandoned as chattering.
pub const MAX_SWITCHES: u32 = 10_000;

/// Angle (radians) between a spring sliding under tension ([`Mode::SlipInTension`]) and its loading below which they
/// count as aligned.
pub const MISALIGNMENT: f64 = 1e-9;

/// Angle (radians) between a 3-D model's sliding direction ([`SLIDE_CARRIER`]) and its loading below which they count
/// as aligned: rounding's.
pub const ROUNDING_MISALIGNMENT: f64 = 64.0 * f64::EPSILON;

/// The length (in the model's force unit) of the spring state the 3-D models carry while sliding
/// ([`Mode::Slip`]): there the spring is on the Coulomb cap, `T = mu Fn t̂`, and the state holds only its direction
/// `t̂` ([`Tangential::evaluate`], [`Tangential::carried`]). Its length is a constant of the slide, set where the
/// slide begins ([`Tangential::carrier`]): of the force unit's order, so that the integrator holds the direction to
/// its relative tolerance.
pub const SLIDE_CARRIER: f64 = 1.0;

/// Whether the tangential spring holds (stick) or the contact slides at the Coulomb limit (slip).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    Stick,
    /// Sliding on the limit of a compressive normal force (or, with [`FrictionCap::Compressive`], of any).
    Slip,
    /// Sliding on the limit mu |Fn| while the normal force pulls: only with [`FrictionCap::Magnitude`]. A mode of its
    /// own because the limit's rate changes sign where Fn passes through zero: that passage is located as a switch.
    SlipInTension,
}

impl Mode {
    /// Whether the contact slides on the Coulomb limit.
    pub fn is_sliding(self) -> bool {
        self != Mode::Stick
    }

    /// The mode a model's state slot holds (constant between switches): 0 sticking, 1 sliding, 2 sliding while the
    /// normal force pulls.
    pub fn of_slot(value: f64) -> Mode {
        match value {
            m if m > 1.5 => Mode::SlipInTension,
            m if m > 0.5 => Mode::Slip,
            _ => Mode::Stick,
        }
    }

    /// The value of the mode in a model's state slot ([`Mode::of_slot`]).
    pub fn slot(self) -> f64 {
        match self {
            Mode::Stick => 0.0,
            Mode::Slip => 1.0,
            Mode::SlipInTension => 2.0,
        }
    }

    /// The sign of the normal force a sliding mode's limit follows: -1 in tension, 1 otherwise.
    fn side(self) -> f64 {
        if self == Mode::SlipInTension { -1.0 } else { 1.0 }
    }
}

/// The tangential contact, scaled: an incremental spring dT/dt = -kt slip (Mindlin: kt = 8 G* sqrt(R* d)) with a
/// dashpot c_t on the slip, the total capped at mu Fn (Coulomb). While sticking the spring follows the slip; while
/// sliding it stays on the cap |T| = mu Fn, turning towards the slip, until the spring would unload faster than the
/// cap falls — the elastic–perfectly-plastic slider in continuous time, with the switches located as events.
///
/// Two options (docs/oblique.md#the-simulators-options): `unloading = Rescale` adds T (dkt/dt)/kt to the spring's rate
/// while the penetration decreases (T d'/(2d) for Mindlin's kt ∝ sqrt(d)), so that a holding spring shrinks with the
/// contact's stiffness; `cap = Magnitude` caps the force at mu |Fn|, so that friction acts also while a damped
/// normal force pulls.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tangential {
    /// Coulomb coefficient mu.
    pub friction: f64,
    /// kt = `stiffness` d^`exponent`, in units of F0/L (d in L).
    pub stiffness: f64,
    pub exponent: f64,
    /// c_t = `damping` sqrt(kt), in units of F0/v0 (2 ratio sqrt(m_t/m*) in scaled units).
    pub damping: f64,
    /// The Coulomb limit: mu max(Fn, 0) or mu |Fn| (`Magnitude` only where the two differ: `setup::Friction::cap`).
    pub cap: FrictionCap,
    /// Whether the spring shrinks with the stiffness while the contact unloads.
    pub unloading: TangentialUnloading,
}

/// The tangential force and the rate of the spring at one instant (scaled).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TangentialForce {
    /// Force on body 1.
    pub force: Vector3<f64>,
    /// dT/dt of the spring.
    pub spring_rate: Vector3<f64>,
}

impl Tangential {
    /// The scene's friction in a model's units: lengths in `length` (m), forces in `force` (N), and the tangential
    /// damping's mass ratio taken against `mass` (kg), the model's mass unit.
    pub fn from_friction(f: &crate::setup::Friction, length: f64, force: f64, mass: f64) -> Tangential {
        Tangential {
            friction: f.coefficient,
            stiffness: f.stiffness * length.powf(f.stiffness_exponent + 1.0) / force,
            exponent: f.stiffness_exponent,
            damping: 2.0 * f.damping_ratio * (f.tangential_mass / mass).sqrt(),
            cap: f.cap,
            unloading: f.unloading,
        }
    }

    /// The energy the spring stores in `mode` (scaled), at penetration `d`, |T|²/(2 kt), with |T| no more than the
    /// Coulomb cap lets it hold: at the contact's edge kt -> 0 and Fn -> 0, and an uncapped spring state (a
    /// rounding-sized remainder) over a vanishing kt gave energies of 1e9 J in a 3 J impact.
    pub fn stored_energy(&self, mode: Mode, spring: &Vector3<f64>, d: f64, normal_force: f64) -> f64 {
        let kt = self.stiffness_at(d);
        let held = self.held(mode, spring, normal_force);
        if kt > 0.0 { held * held / (2.0 * kt) } else { 0.0 }
    }

    /// kt at penetration `d` (scaled), zero out of contact.
    pub fn stiffness_at(&self, d: f64) -> f64 {
        if d <= 0.0 {
            0.0
        } else if self.exponent == 0.0 {
            self.stiffness
        } else {
            self.stiffness * crate::law::power(d, self.exponent)
        }
    }

    /// The Coulomb limit for the normal force `normal_force` (scaled): mu max(Fn, 0), or mu |Fn| with the magnitude cap.
    pub fn cap(&self, normal_force: f64) -> f64 {
        match self.cap {
            FrictionCap::Compressive => self.friction * normal_force.max(0.0),
            FrictionCap::Magnitude => self.friction * normal_force.abs(),
        }
    }

    /// The rescaling rate of an unloading spring, (dkt/dt)/kt = exponent d'/d in units of 1/T, while the penetration
    /// decreases and `unloading = Rescale` (LAMMPS' step-wise T a/a_prev for a < a_prev in the limit of small steps);
    /// zero otherwise, and for a constant kt.
    pub fn rescale_rate(&self, kinematics: &Kinematics) -> f64 {
        let (d, rate) = (kinematics.penetration, kinematics.rate);
        if self.unloading == TangentialUnloading::Rescale && d > 0.0 && rate < 0.0 {
            self.exponent * rate / d
        } else {
            0.0
        }
    }

    /// The direction of the spring's force: along the spring, or — an unloaded spring — against the slip.
    pub fn direction(spring: &Vector3<f64>, slip: &Vector3<f64>) -> Vector3<f64> {
        let length = spring.norm();
        if length > 1e-300 { spring / length } else { Tangential::against(slip) }
    }

    /// The unit vector against the slip (zero without slip).
    fn against(slip: &Vector3<f64>) -> Vector3<f64> {
        let speed = slip.norm();
        if speed > 0.0 { -slip / speed } else { Vector3::zeros() }
    }

    /// The direction a sliding spring is driven along and judged by. Sliding keeps the spring at the cap,
    /// |T| = mu Fn, against the slip; a spring that has drifted below half of it (the integration's error, which
    /// near the contact's edges, where the cap vanishes, can carry the spring through zero and reverse it) no longer
    /// gives a direction: the spring's rate and the stick–slip switch then take the direction against the slip, as
    /// Coulomb's law has it. (The force stays the spring itself, below the integration's error there.)
    ///
    /// Nor does a reversed spring — one along the slip — while the cap grows (`growing`), if a stick's loading would
    /// unload it within [`QUICK_REVERSAL`] (`|T| < QUICK_REVERSAL kt |slip|`, `kt` the spring's stiffness; once turned,
    /// the spring is driven at the cap's rate along the direction against the slip):
    /// driven along its own direction, it would grow with the cap and push the slip on. Where a damper cut to zero
    /// force inside the contact lets the force push again, the spring left reversed by rounding as the cap fell to
    /// zero did so: stress case 11645 of seed 424242 (`adams-impact`, its force cut for 2.3 s of a 3.1 s contact)
    /// rubbed its last 11 % of friction impulse the wrong way (its reversed springs would have unloaded within
    /// 4e-5 T). A spring at the cap that a slowing slip reverses by passing through zero is no such remainder: its
    /// direction is kept, so that the switch function stays continuous and the stick, where the spring a stick would
    /// hold, `kt |slip|`, falls below the cap's rate (before the slip rests), is located. Turned against the slip
    /// there, the function had jumped back above zero and the stick could be stepped over: a wall whose slip rested
    /// 0.02 µs before maximum compression slid on with its friction pushing the slip (tests/wall_slide.rs). (While
    /// the cap falls, a reversed spring only shrinks on its own: a creeping contact's rounding-sized spring is left to
    /// it rather than turned back and forth.)
    fn sliding_direction(
        spring: &Vector3<f64>,
        slip: &Vector3<f64>,
        cap: f64,
        growing: bool,
        stiffness: f64,
    ) -> Vector3<f64> {
        let length = spring.norm();
        let reversed = growing && spring.dot(slip) > 0.0 && length < QUICK_REVERSAL * stiffness * slip.norm();
        if length >= 0.5 * cap && length > 1e-300 && !reversed { spring / length } else { Tangential::against(slip) }
    }

    /// The direction of a sliding 3-D model's force, from the direction its spring state carries
    /// ([`SLIDE_CARRIER`]), and whether that is the state's own: a state shorter than half its length carries none
    /// (none is: each slide begins with one), and the force takes the direction against the slip. (No rule for a
    /// reversed spring, as [`Tangential::sliding_direction`]'s: the direction a slide carries is never a rounding
    /// remainder. Where the cap returns from zero with the slip turned along it — a damper cut to zero force inside
    /// the contact — the switch function, `-kt slip·t - mu dFn/dt`, returns below zero, and the contact sticks there,
    /// its spring placed on the cap, until the slip has loaded it the other way.)
    fn carried_direction(spring: &Vector3<f64>, slip: &Vector3<f64>) -> (Vector3<f64>, bool) {
        let length = spring.norm();
        if length >= 0.5 * SLIDE_CARRIER { (spring / length, true) } else { (Tangential::against(slip), false) }
    }

    /// The spring's force in `mode` for a 3-D model's spring state `state`: the state itself, or while sliding
    /// ([`Mode::Slip`]: the state carries the direction) the cap along the direction the force takes — what the
    /// switch functions, the next mode and the stored energy are judged by.
    pub fn carried(&self, mode: Mode, state: &Vector3<f64>, slip: &Vector3<f64>, normal_force: f64) -> Vector3<f64> {
        if mode != Mode::Slip {
            return *state;
        }
        Tangential::carried_direction(state, slip).0 * self.cap(normal_force)
    }

    /// The spring state a 3-D model sets where it enters `mode` with the spring's force `spring`: while sliding
    /// ([`Mode::Slip`]), its direction — or, without one, the direction against the slip — at [`SLIDE_CARRIER`];
    /// the force itself otherwise.
    pub fn carrier(mode: Mode, spring: &Vector3<f64>, slip: &Vector3<f64>) -> Vector3<f64> {
        if mode == Mode::Slip { Tangential::direction(spring, slip) * SLIDE_CARRIER } else { *spring }
    }

    /// The force and spring rate in `mode`, for the spring state `spring` (in the tangent plane; while sliding, the
    /// direction it carries), the kinematics and the normal force `normal_force`. (Neither depends on the normal
    /// force's rate: a sliding state carries no size.)
    pub fn evaluate(
        &self,
        mode: Mode,
        spring: &Vector3<f64>,
        kinematics: &Kinematics,
        normal_force: f64,
    ) -> TangentialForce {
        let k = &kinematics;
        let kt = self.stiffness_at(k.penetration);
        let loading = -k.slip * kt;
        // Keep the spring in the tangent plane as the normal turns: d(T·n)/dt = 0.
        let turning = -k.normal * spring.dot(&k.normal_rate);
        let cap = self.cap(normal_force);
        match mode {
            Mode::Stick => {
                let trial = spring - k.slip * (self.damping * kt.sqrt());
                let size = trial.norm();
                let force = if size > cap { trial * (cap / size) } else { trial };
                let rescaling = spring * self.rescale_rate(k);
                TangentialForce { force, spring_rate: loading + rescaling + turning }
            }
            // No compression, no friction: the spring (at the cap, so near zero) is left as it is, rather than turned
            // at a rate that grows without bound as its length vanishes.
            Mode::Slip if normal_force <= 0.0 && self.cap == FrictionCap::Compressive => {
                TangentialForce { force: Vector3::zeros(), spring_rate: turning }
            }
            Mode::SlipInTension => {
                // The spring carries only the force's direction here (the force is the cap along it): the cap's rate
                // grows without bound where a damping term in d^(1/4) or d^(1/2) (Tsuji's, Brilliantov's) pulls the
                // contact apart, and a spring made to follow it would hold the integrator to ever shorter steps.
                // Released at the cap's kink, it is zero, and the force is against the slip.
                let along = Tangential::direction(spring, &k.slip);
                let across = loading - along * loading.dot(&along);
                let size = loading.norm();
                // The direction turns towards the loading at |loading across it| / cap, at most MAX_TURN_RATE.
                let turn = if across.norm() <= MISALIGNMENT * size {
                    Vector3::zeros()
                } else if size > MAX_TURN_RATE * cap {
                    across * (MAX_TURN_RATE * spring.norm() / size)
                } else {
                    across * (spring.norm() / cap)
                };
                TangentialForce { force: along * cap, spring_rate: turn + turning }
            }
            Mode::Slip => {
                // The spring is on the cap, `T = cap t̂`, and the state (`spring`) carries only its direction t̂, at
                // the length it was given where the slide began (SLIDE_CARRIER): its rate has no part along it. (A
                // state that followed the cap's size, at the cap's rate `mu dFn/dt` ∝ d^(1/2) for Hertz's law, had a
                // rate as rough as that at the contact's edges: a frictional contact's last slide took about twice
                // the steps of the whole contact without friction, half of them rejected.)
                let (along, own) = Tangential::carried_direction(spring, &k.slip);
                let length = if own { spring.norm() } else { 0.0 };
                // The direction turns towards the loading at the angular rate |loading across it| / |T|, which grows
                // without bound where the Coulomb limit vanishes (the edges of the contact): faster than
                // MAX_TURN_RATE it is taken as that rate, so that an explicit integrator is not held to ever shorter
                // steps. A misalignment at the level of rounding (ROUNDING_MISALIGNMENT) is no misalignment: planar
                // sliding keeps slip and spring parallel. (MISALIGNMENT, a spring's threshold, chattered here: where
                // the lag behind a turning slip settles below it, the turning went on and off at that rate, and a
                // pair of spheres took 7 times the steps.)
                let mut turn = loading - along * loading.dot(&along);
                let size = loading.norm();
                if turn.norm() <= ROUNDING_MISALIGNMENT * size {
                    turn = Vector3::zeros();
                } else if size > MAX_TURN_RATE * cap {
                    turn *= MAX_TURN_RATE * length / size;
                } else {
                    turn *= length / cap;
                }
                // (A state without a direction, `length` 0, is not turned: the force takes the slip's.)
                TangentialForce { force: along * cap, spring_rate: turn + turning }
            }
        }
    }

    /// The function whose fall through zero ends the present mode: the room left under the cap while sticking,
    /// cap - |T|; while sliding, how much faster the spring would load than the cap grows, (dT/dt of a holding
    /// spring)·t - d(cap)/dt (positive, no switch, while a compressive cap has no normal force). With the magnitude
    /// cap a sliding mode also ends where the normal force passes through zero (the cap's kink), watched as the
    /// compression ratio on the mode's side (`elastic` is the elastic part of the normal force): the smaller of the
    /// two falls through zero first, and both are continuous.
    pub fn switch_function(
        &self,
        mode: Mode,
        spring: &Vector3<f64>,
        kinematics: &Kinematics,
        normal_force: f64,
        normal_force_rate: f64,
        elastic: f64,
    ) -> f64 {
        self.switch_function_along(mode, spring, None, kinematics, normal_force, normal_force_rate, elastic)
    }

    /// [`Tangential::switch_function`] for a 3-D model's spring state `state` (while sliding, the direction it
    /// carries, [`SLIDE_CARRIER`], which the switch judges the slide by: no rule for a reversed remainder).
    pub fn carried_switch_function(
        &self,
        mode: Mode,
        state: &Vector3<f64>,
        kinematics: &Kinematics,
        normal_force: f64,
        normal_force_rate: f64,
        elastic: f64,
    ) -> f64 {
        let (spring, along) = self.carried_parts(mode, state, &kinematics.slip, normal_force);
        self.switch_function_along(mode, &spring, along, kinematics, normal_force, normal_force_rate, elastic)
    }

    /// A 3-D model's spring force for the state `state` ([`Tangential::carried`]) and, while sliding, the direction
    /// the state carries.
    fn carried_parts(
        &self,
        mode: Mode,
        state: &Vector3<f64>,
        slip: &Vector3<f64>,
        normal_force: f64,
    ) -> (Vector3<f64>, Option<Vector3<f64>>) {
        if mode != Mode::Slip {
            return (*state, None);
        }
        let along = Tangential::carried_direction(state, slip).0;
        (along * self.cap(normal_force), Some(along))
    }

    /// [`Tangential::switch_function`] with a slide judged along `along` where given.
    #[allow(clippy::too_many_arguments)]
    fn switch_function_along(
        &self,
        mode: Mode,
        spring: &Vector3<f64>,
        along: Option<Vector3<f64>>,
        kinematics: &Kinematics,
        normal_force: f64,
        normal_force_rate: f64,
        elastic: f64,
    ) -> f64 {
        match mode {
            // With a dashpot, sticking turns to sliding where the spring reaches the cap only while the spring holds
            // against the slip (T·s ≤ 0: the slip loads it). A spring along the slip is unloading: the cap fell onto
            // it, and a slide started there would drop the dashpot's force at once and begin with its own switch
            // function below zero (never falling through it), its force, the spring on the cap, pushing the contact
            // points along their slip — energy from nothing (the rocking block turned over its new corner). Such a
            // contact sticks on, its force capped, its spring unloading: the bodies get at most what the spring gives
            // back. (T·s is in the scaled units of force times speed, the room in force: both cross zero together
            // only at the switch, where the room decides.)
            Mode::Stick if self.damping > 0.0 => {
                (self.cap(normal_force) - spring.norm()).max(spring.dot(&kinematics.slip))
            }
            Mode::Stick => match self.cap {
                FrictionCap::Compressive => self.friction * normal_force - spring.norm(),
                FrictionCap::Magnitude => self.friction * normal_force.abs() - spring.norm(),
            },
            // Without compression there is no friction to stick with: a sliding contact stays sliding.
            Mode::Slip if normal_force <= 0.0 && self.cap == FrictionCap::Compressive => 1.0,
            Mode::Slip | Mode::SlipInTension => {
                let (lifting, kink) =
                    self.sliding_parts(mode, spring, along, kinematics, normal_force, normal_force_rate, elastic);
                lifting.min(kink)
            }
        }
    }

    /// A sliding mode's two switch functions: how much faster a holding spring would load than the cap grows, and
    /// the compression ratio on the mode's side (positive infinity, never falling, with the compressive cap). The
    /// ratio Fn / F_elastic = 1 + F_dissipative / F_elastic falls through zero where a damped force turns tensile;
    /// unlike Fn itself it stays away from zero where a force that never pulls vanishes with the penetration (a
    /// Hertzian law's at separation), and out of contact, without a force, it is 1 on either side: the passage into
    /// or out of tension is never confused with the contact's end.
    /// (`along`, where given, is the direction the slide is judged by: a 3-D model's carried one.)
    #[allow(clippy::too_many_arguments)]
    fn sliding_parts(
        &self,
        mode: Mode,
        spring: &Vector3<f64>,
        along: Option<Vector3<f64>>,
        kinematics: &Kinematics,
        normal_force: f64,
        normal_force_rate: f64,
        elastic: f64,
    ) -> (f64, f64) {
        let kt = self.stiffness_at(kinematics.penetration);
        let along = along
            .unwrap_or_else(|| self.sliding_along(mode, spring, &kinematics.slip, normal_force, normal_force_rate, kt));
        let held = self.held(mode, spring, normal_force);
        let holding = -kinematics.slip.dot(&along) * kt + held * self.rescale_rate(kinematics);
        let lifting = holding - self.friction * mode.side() * normal_force_rate;
        let kink = match self.cap {
            FrictionCap::Compressive => f64::INFINITY,
            FrictionCap::Magnitude if elastic > 0.0 => mode.side() * normal_force / elastic,
            // At the edge, Kelvin–Voigt's force from inside: its sign.
            FrictionCap::Magnitude if normal_force != 0.0 => mode.side() * normal_force.signum(),
            FrictionCap::Magnitude => 1.0,
        };
        (lifting, kink)
    }

    /// The direction a sliding mode's force takes: the spring's (see [`Tangential::evaluate`]), for the spring's
    /// stiffness `kt` at the present penetration.
    fn sliding_along(
        &self,
        mode: Mode,
        spring: &Vector3<f64>,
        slip: &Vector3<f64>,
        normal_force: f64,
        normal_force_rate: f64,
        kt: f64,
    ) -> Vector3<f64> {
        match mode {
            Mode::SlipInTension => Tangential::direction(spring, slip),
            _ => Tangential::sliding_direction(spring, slip, self.cap(normal_force), normal_force_rate > 0.0, kt),
        }
    }

    /// The size of the force the spring holds in `mode` (scaled): the cap while sliding under tension (the spring
    /// then carries only the direction), the spring's, at most the cap, otherwise.
    pub fn held(&self, mode: Mode, spring: &Vector3<f64>, normal_force: f64) -> f64 {
        let cap = self.cap(normal_force);
        if mode == Mode::SlipInTension { cap } else { spring.norm().min(cap) }
    }

    /// The mode after a located zero of [`Tangential::switch_function`] in `mode`, at that instant's state, and the
    /// spring to set there, if any. Sticking turns to sliding on the side of Fn it is on. Sliding turns to sticking
    /// (from under tension with the spring placed on the cap, whose direction alone it carried), unless the zero is
    /// the magnitude cap's kink: there the spring, on a cap that is zero, is released; the cap restarts from zero at
    /// the rate mu |dFn/dt| and a released spring would load against the slip at kt |slip|, so the contact goes on
    /// sliding on the other side if the spring outgrows the cap, and sticks otherwise.
    pub fn next_mode(
        &self,
        mode: Mode,
        spring: &Vector3<f64>,
        kinematics: &Kinematics,
        normal_force: f64,
        normal_force_rate: f64,
        elastic: f64,
    ) -> (Mode, Option<Vector3<f64>>) {
        self.next_mode_along(mode, spring, None, kinematics, normal_force, normal_force_rate, elastic)
    }

    /// [`Tangential::next_mode`] for a 3-D model's spring state `state` (while sliding, the direction it carries, which
    /// the switch judges the slide by), and the spring state to set there ([`Tangential::carrier`]).
    pub fn carried_next_mode(
        &self,
        mode: Mode,
        state: &Vector3<f64>,
        kinematics: &Kinematics,
        normal_force: f64,
        normal_force_rate: f64,
        elastic: f64,
    ) -> (Mode, Vector3<f64>) {
        let (spring, along) = self.carried_parts(mode, state, &kinematics.slip, normal_force);
        let (next, placed) =
            self.next_mode_along(mode, &spring, along, kinematics, normal_force, normal_force_rate, elastic);
        (next, Tangential::carrier(next, &placed.unwrap_or(spring), &kinematics.slip))
    }

    /// [`Tangential::next_mode`] with a slide judged along `along` where given.
    #[allow(clippy::too_many_arguments)]
    fn next_mode_along(
        &self,
        mode: Mode,
        spring: &Vector3<f64>,
        along: Option<Vector3<f64>>,
        kinematics: &Kinematics,
        normal_force: f64,
        normal_force_rate: f64,
        elastic: f64,
    ) -> (Mode, Option<Vector3<f64>>) {
        match mode {
            // A damped spring may stand beyond the cap (it unloaded more slowly than the cap fell, the force capped
            // meanwhile): it slides from the cap.
            Mode::Stick => {
                let next = if self.cap == FrictionCap::Magnitude && normal_force < 0.0 {
                    Mode::SlipInTension
                } else {
                    Mode::Slip
                };
                let (size, cap) = (spring.norm(), self.cap(normal_force));
                (next, (size > cap).then(|| spring * (cap / size)))
            }
            Mode::Slip | Mode::SlipInTension => {
                let (lifting, kink) =
                    self.sliding_parts(mode, spring, along, kinematics, normal_force, normal_force_rate, elastic);
                if self.cap == FrictionCap::Compressive || lifting < kink {
                    // (Under tension the direction is the spring's, whatever the stiffness.)
                    let placed = (mode == Mode::SlipInTension)
                        .then(|| Tangential::direction(spring, &kinematics.slip) * self.cap(normal_force));
                    return (Mode::Stick, placed);
                }
                let loading = self.stiffness_at(kinematics.penetration) * kinematics.slip.norm();
                let other = if mode == Mode::Slip { Mode::SlipInTension } else { Mode::Slip };
                let next = if loading >= self.friction * normal_force_rate.abs() { other } else { Mode::Stick };
                (next, Some(Vector3::zeros()))
            }
        }
    }

    /// The mode at first contact (T = 0, d = 0): sliding when the spring would outgrow the Coulomb cap from the
    /// start. Where the normal force at first contact, `contact_force` (scaled, at d = 0 and the approach rate), is
    /// compressive — Kelvin–Voigt's jump to c v0 — the cap starts above the unloaded spring: sticking, until the
    /// spring reaches the cap (an event). Otherwise both grow from zero; their ratio tends to a limit, read at a
    /// tiny penetration `probe` (scaled) from the leading terms: a spring loaded at the initial slip over the time
    /// the penetration took, against mu F(probe) (`normal_force`).
    pub fn initial_mode(&self, slip: f64, rate: f64, probe: f64, contact_force: f64, normal_force: f64) -> Mode {
        if slip == 0.0 || contact_force > 0.0 {
            return Mode::Stick;
        }
        // d = rate t and kt = k d^a give |T| = k d^(a+1) slip / ((a + 1) rate), compared with the cap multiplied
        // through by the rate: a contact pushed into being (rate 0) with slip slides from the start.
        let spring = self.stiffness_at(probe) * probe * slip;
        if spring > self.friction * normal_force * (self.exponent + 1.0) * rate { Mode::Slip } else { Mode::Stick }
    }
}

/// The spring part of a state slice.
pub fn vector<const N: usize>(y: &State<N>, at: usize) -> Vector3<f64> {
    Vector3::new(y[at], y[at + 1], y[at + 2])
}

/// Writes a vector into a state slice.
pub fn set_vector<const N: usize>(y: &mut State<N>, at: usize, v: &Vector3<f64>) {
    y[at] = v.x;
    y[at + 1] = v.y;
    y[at + 2] = v.z;
}
