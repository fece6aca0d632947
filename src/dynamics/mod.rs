//! Equations of motion during contact, in scaled variables.
//!
//! Lengths are measured in the elastic penetration scale L = (m* v0²/K)^(1/(n+1)), speeds in the approach speed v0,
//! times in T = L/v0, forces in F0 = K L^n = m* v0²/L (docs/references.md). Every scaled quantity is O(1) whatever the
//! bodies, which is what makes one absolute tolerance meaningful.
//!
//! Two models share one interface ([`ContactModel`]) so that one phase driver (`crate::impact`) runs either:
//! [`normal::NormalContact`], the relative motion along a fixed normal (a central or smooth impact: the special case
//! that needs nothing else), and [`pair::PairContact`], two bodies in 3-D with a normal that turns with the line of
//! centres, friction with a tangential spring, and spins. [`contact`] holds what a contact between two bodies
//! computes from their relative kinematics — the piece several contacts in one run would each use.

pub mod contact;
pub mod normal;
pub mod pair;
pub mod rigid;
pub mod slide;
pub mod wall;

use crate::integrate::{Model, State, Tolerances};
use nalgebra::{UnitQuaternion, Vector3};

use crate::scales::Scales;

/// The contact and both bodies at one instant, in SI units: what a report and a history are built from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Snapshot {
    /// Time since first contact, s.
    pub time: f64,
    /// Penetration d, m (negative once the bodies have parted).
    pub penetration: f64,
    /// Penetration rate d' = (v1 - v2)·n, m/s.
    pub rate: f64,
    /// Normal contact force, N (compressive positive; the law's force, zero out of contact).
    pub normal_force: f64,
    /// Unit normal, body 1 -> body 2.
    pub normal: Vector3<f64>,
    /// Tangential contact force on body 1, N (body 2 feels its opposite).
    pub tangential_force: Vector3<f64>,
    /// Slip: velocity of body 1's contact point relative to body 2's, across the normal, m/s.
    pub slip: Vector3<f64>,
    /// Velocities of the centres, m/s.
    pub velocities: [Vector3<f64>; 2],
    /// Angular velocities, rad/s.
    pub spins: [Vector3<f64>; 2],
    /// Positions of the centres (a wall: the point of its plane on the normal through the sphere), m.
    pub positions: [Vector3<f64>; 2],
    /// ∫ Fn dt since first contact, N s.
    pub normal_impulse: f64,
    /// ∫ Fn d' dt: work of the normal force on the relative normal motion, J.
    pub normal_work: f64,
    /// ∫ F_dissipative d' dt: energy dissipated by the normal damping, J.
    pub dissipated_normal: f64,
    /// ∫ Ft·slip dt: work of the tangential force on the slip, J (negative: taken from the bodies).
    pub tangential_work: f64,
    /// Work done on the movable bodies by a body of infinite mass (a moving wall, a driven sphere), J.
    pub work_of_immovable_bodies: f64,
    /// Energy stored in the normal spring, J.
    pub elastic_energy: f64,
    /// Energy stored in the tangential spring, |T|²/(2 kt), J.
    pub tangential_elastic_energy: f64,
    /// How far each body has turned since first contact: the identity in the spheres' models, whose contact does not
    /// depend on a sphere's orientation; the integrated orientation in the rigid-body model.
    pub orientations: [UnitQuaternion<f64>; 2],
    /// The impulse each body's pivot has passed to it since first contact, N s (zero for a free body).
    pub pivot_impulses: [Vector3<f64>; 2],
}

/// What the phase driver needs of a model: its scaled state's meaning, the event functions, and SI snapshots.
pub trait ContactModel<const N: usize>: Model<N> {
    /// The units of the scaled state.
    fn scales(&self) -> &Scales;
    /// The fraction of the scene's tolerances this model integrates at (1: as asked).
    fn tolerance_factor(&self) -> f64 {
        1.0
    }
    /// The tolerances this model integrates at, for the scene's `requested` ones ([`ContactModel::tolerance_factor`]
    /// of each).
    fn tolerances(&self, requested: Tolerances) -> Tolerances {
        let factor = self.tolerance_factor();
        Tolerances { rtol: requested.rtol * factor, atol: requested.atol * factor }
    }
    /// The state at first contact (scaled time 0), with the stick-or-slip mode it starts in.
    fn start(&self) -> State<N>;
    /// Scaled penetration d/L.
    fn penetration(&self, y: &State<N>) -> f64;
    /// Scaled penetration rate d'/v0.
    fn rate(&self, y: &State<N>) -> f64;
    /// Scaled normal force F/F0.
    fn force(&self, y: &State<N>) -> f64;
    /// Scaled normal-force rate dF/dt (its fall through zero is the force peak).
    fn force_rate(&self, y: &State<N>) -> f64;
    /// A continuous function whose fall through zero is a force separation (see
    /// [`crate::law::ContactLaw::separation_function`]).
    fn separation_force(&self, y: &State<N>) -> f64;
    /// The sign of the force a law that never pulls would have without its cut, continued (see
    /// [`crate::law::ContactLaw::uncut_force`]): its zeros in restitution are step boundaries; `None` for the laws
    /// that never cut.
    fn uncut_force(&self, y: &State<N>) -> Option<f64>;
    /// The function whose fall through zero switches the contact between sticking and sliding, in the state's
    /// mode; `None` for a model without modes.
    fn switch_function(&self, _y: &State<N>) -> Option<f64> {
        None
    }
    /// Switches the state's mode at a located zero of [`ContactModel::switch_function`]. The mode is part of the
    /// state (constant between switches), so that re-stepping and recorded histories always see the right one.
    fn switch(&self, _y: &mut State<N>) {}
    /// Whether the state's mode is sliding (false for a smooth contact).
    fn sliding(&self, _y: &State<N>) -> bool {
        false
    }
    /// The contact points' slip along its direction at first contact (scaled), whose fall through zero is where the
    /// slip comes to rest (gross sliding ends: the contact sticks or rolls); `None` for a model without friction or
    /// without an initial slip.
    fn slip_along_start(&self, _y: &State<N>) -> Option<f64> {
        None
    }
    /// Whether the tangential force has a kink where the normal force passes through zero that no switch of the
    /// model locates (the 3-D models' compressive Coulomb cap `mu max(Fn, 0)`, slid through without a switch): the
    /// driver then makes each passage a step boundary. The slide model's corner, and the magnitude cap's, are
    /// switches.
    fn tension_kink(&self) -> bool {
        false
    }
    /// The scaled penetrations (d/L, ascending) where the law's force is not smooth in this phase
    /// ([`crate::law::ContactLaw::kinks`]): the driver makes each crossing a step boundary.
    fn kinks(&self, compressing: bool) -> crate::law::Kinks;
    /// The contact and the bodies at scaled time `t` and state `y`, in SI units.
    fn snapshot(&self, t: f64, y: &State<N>) -> Snapshot;
    /// The physical time (in T) at the integration variable `t` and state `y`: `t` itself, but for a model integrated
    /// in a regularised time ([`wall::WallContact`]), which carries the time as a state.
    fn time_of(&self, t: f64, _y: &State<N>) -> f64 {
        t
    }
}

/// The unit of the dissipated-energy state, in m* v0²: the damping's size delta at the contact's scales
/// ([`crate::law::ContactLaw::damping_ratio`]) for a light damping, whose dissipation is about delta m* v0², so that
/// it is integrated to the tolerance relative to itself (docs/numerics.md#impulses-and-energies-as-integrals); 1 for
/// a heavy one (delta > 1), which can dissipate no more than m* v0²/2 — a larger unit would shrink the state below
/// the absolute tolerance (1e-9 relative errors at delta ~ 1e3).
pub(crate) fn dissipation_scale(law: &crate::law::ContactLaw, scales: &Scales) -> f64 {
    unit_or_one(law.damping_ratio(scales.length, scales.speed).min(1.0))
}

/// The normal contact's shared bookkeeping in scaled variables, for the 3-D models: at scaled penetration `d`, rate
/// `rate` and the state's remembered deepest penetration `deepest_state` (a yielding law's; the state slot of the
/// dissipated energy otherwise).
pub(crate) struct Normal<'a> {
    pub law: &'a crate::law::ContactLaw,
    pub scales: &'a Scales,
    pub d: f64,
    pub rate: f64,
    pub deepest_state: f64,
}

impl Normal<'_> {
    /// The deepest penetration so far, m: the state's, or `d` where that is deeper.
    fn deepest(&self) -> f64 {
        self.deepest_state.max(self.d) * self.scales.length
    }

    /// [`ContactModel::separation_force`]: the law's separation function (a yielding law's in units of L).
    pub fn separation(&self) -> f64 {
        let s = self.scales;
        let (d, rate) = (self.d * s.length, self.rate * s.speed);
        if self.law.yields() {
            self.law.separation_function_after(d, rate, self.deepest()) / s.length
        } else {
            self.law.separation_function(d, rate)
        }
    }

    /// [`ContactModel::uncut_force`], in the law's own units (only its sign and zeros matter).
    pub fn uncut(&self) -> Option<f64> {
        let s = self.scales;
        self.law.uncut_force(self.d * s.length, self.rate * s.speed)
    }

    /// The rate of the dissipated-energy state (a yielding law's: of its remembered deepest penetration), for the
    /// dissipative force `dissipative` (scaled) and the state's unit `per`.
    pub fn dissipation_rate(&self, dissipative: f64, per: f64) -> f64 {
        if self.law.yields() {
            normal::deepening(self.d, self.deepest_state, self.rate)
        } else {
            dissipative * self.rate / per
        }
    }

    /// The energy stored in the normal spring and the energy the normal force has dissipated, J, from the normal
    /// work (scaled) and the dissipated-energy state `dissipated` in its unit `per`: a yielding law's dissipation is
    /// what the normal force took and the unloading will not give back, the dent's work.
    pub fn energies(&self, normal_work: f64, dissipated: f64, per: f64) -> (f64, f64) {
        let s = self.scales;
        if self.law.yields() {
            let elastic = self.law.elastic_energy_after(self.d * s.length, self.deepest());
            (elastic, normal_work * s.energy - elastic)
        } else {
            (self.law.elastic_energy(self.d * s.length), dissipated * s.energy * per)
        }
    }
}

/// `value / scale`, for the scaled energy integrals; a zero scale means the integral is zero anyway.
pub(crate) fn unit_or_one(scale: f64) -> f64 {
    if scale > 0.0 && scale.is_finite() { scale } else { 1.0 }
}
