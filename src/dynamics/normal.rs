//! One contact along a fixed normal: the relative motion of two bodies under a contact law — the special case of a
//! central (or smooth, slip-free) impact whose line of action cannot turn, where nothing but the normal motion
//! changes.
//!
//! The state carries, besides penetration and its rate, the integrals the report needs, so that impulses and
//! works come from the force history itself rather than from momentum.

use super::{ContactModel, Scales, Snapshot, dissipation_scale};
use crate::body::{Body, after_normal_impulse};
use crate::integrate::{Model, State};
use crate::law::ContactLaw;
use crate::setup::Setup;

/// Scaled penetration below zero that still counts as the edge of the contact: event location leaves the
/// separation state within a few ulps of d = 0 on either side.
pub const EDGE: f64 = 1e-12;

/// Size of the normal-contact state.
pub const SIZE: usize = 5;

/// Index of each scaled quantity in the state.
pub mod index {
    /// Penetration d / L.
    pub const PENETRATION: usize = 0;
    /// Penetration rate d' / v0.
    pub const RATE: usize = 1;
    /// ∫ F dt / (m* v0): impulse so far.
    pub const IMPULSE: usize = 2;
    /// ∫ F d' dt / (m* v0²): work of the contact force on the relative motion so far.
    pub const WORK: usize = 3;
    /// ∫ F_dissipative d' dt / (m* v0² min(delta, 1)): energy dissipated so far, in units of the damping's own size
    /// delta when it is light (see [`super::dissipation_scale`]), so that a light damping's small dissipation is
    /// integrated to the tolerance relative to itself (docs/numerics.md).
    pub const DISSIPATED: usize = 4;
    /// For a yielding law (which has no damping, so that it takes this slot): the deepest penetration so far / L,
    /// which its force remembers ([`crate::law::ContactLaw::split_force_after`]).
    pub const DEEPEST: usize = 4;
}

/// The relative normal motion m* d'' = -F(d, d').
#[derive(Debug, Clone, Copy)]
pub struct NormalContact<'a> {
    pub law: ContactLaw,
    pub scales: Scales,
    /// delta: the damping's size at the contact's scales ([`ContactLaw::damping_ratio`]), the unit of the
    /// dissipated-energy state (1 for an elastic law).
    pub dissipation_scale: f64,
    /// 1 / `dissipation_scale`, for the hot path.
    per_dissipation: f64,
    bodies: &'a [Body; 2],
    setup: &'a Setup,
}

impl<'a> NormalContact<'a> {
    /// The normal contact of a resolved scene.
    pub fn new(bodies: &'a [Body; 2], setup: &'a Setup) -> NormalContact<'a> {
        let (law, scales) = (setup.law, setup.scales);
        let dissipation_scale = dissipation_scale(&law, &scales);
        NormalContact { law, scales, dissipation_scale, per_dissipation: 1.0 / dissipation_scale, bodies, setup }
    }

    /// The state at first contact: no penetration, closing at the approach speed.
    pub fn initial_state() -> State<SIZE> {
        let mut y = State::<SIZE>::zeros();
        y[index::RATE] = 1.0;
        y
    }

    /// Scaled contact force (elastic, dissipative) at a state. A penetration within [`EDGE`] below zero is the
    /// located edge of the contact (first contact, or separation found to rounding): its force is the limit from
    /// inside, which matters for Kelvin–Voigt (c d' there, not 0).
    #[inline]
    pub fn force_parts(&self, y: &State<SIZE>) -> (f64, f64) {
        let s = &self.scales;
        let penetration =
            if y[index::PENETRATION] > -EDGE { y[index::PENETRATION].max(0.0) } else { y[index::PENETRATION] };
        let parts = if self.law.yields() {
            self.law.split_force_after(penetration * s.length, 0.0, self.deepest(y))
        } else {
            self.law.split_force(penetration * s.length, y[index::RATE] * s.speed)
        };
        (parts.elastic / s.force, parts.dissipative / s.force)
    }

    /// The deepest penetration so far, m, for a yielding law: its state, or the penetration where that is deeper
    /// (the state grows only while the penetration is at it: [`deepening`]).
    #[inline]
    fn deepest(&self, y: &State<SIZE>) -> f64 {
        y[index::DEEPEST].max(y[index::PENETRATION]) * self.scales.length
    }

    /// [`ContactModel::snapshot`] with the contact force (N) and the elastic energy (J) already known: the fast
    /// path has them from its own variables, without the law's powers.
    pub fn snapshot_with(&self, t: f64, y: &State<SIZE>, normal_force: f64, elastic_energy: f64) -> Snapshot {
        let s = &self.scales;
        let setup = self.setup;
        let n = setup.normal;
        let [a, b] = self.bodies;
        let time = t * s.time;
        let penetration = y[index::PENETRATION] * s.length;
        let impulse = y[index::IMPULSE] * s.impulse;
        // The force moves the bodies apart from their free flight by (v0 t - d) along the normal, shared in the
        // ratio of the inverse masses (m*/m_i).
        let pushed = n * (setup.approach_speed * time - penetration);
        let share = |body: &Body| setup.effective_mass * body.inverse_mass();
        let positions = [
            setup.positions[0] + a.velocity * time - pushed * share(a),
            setup.positions[1] + b.velocity * time + pushed * share(b),
        ];
        // Work by an immovable body: minus the work the contact force does on it (its velocity is constant).
        let work_of_immovable_bodies = if b.is_immovable() {
            -impulse * b.velocity.dot(&n)
        } else if a.is_immovable() {
            impulse * a.velocity.dot(&n)
        } else {
            0.0
        };
        Snapshot {
            time,
            penetration,
            rate: y[index::RATE] * s.speed,
            normal_force,
            normal: n,
            tangential_force: nalgebra::Vector3::zeros(),
            slip: setup.initial_slip,
            velocities: after_normal_impulse(self.bodies, &n, impulse),
            spins: [a.angular_velocity, b.angular_velocity],
            positions,
            normal_impulse: impulse,
            normal_work: y[index::WORK] * s.energy,
            dissipated_normal: y[index::DISSIPATED] * s.energy * self.dissipation_scale,
            tangential_work: 0.0,
            work_of_immovable_bodies,
            elastic_energy,
            tangential_elastic_energy: 0.0,
            orientations: [nalgebra::UnitQuaternion::identity(); 2],
            pivot_impulses: [nalgebra::Vector3::zeros(); 2],
        }
    }
}

impl Model<SIZE> for NormalContact<'_> {
    #[inline]
    fn derivative(&self, _t: f64, y: &State<SIZE>, dy: &mut State<SIZE>) {
        let (elastic, dissipative) = self.force_parts(y);
        let force = elastic + dissipative;
        let rate = y[index::RATE];
        dy[index::PENETRATION] = rate;
        dy[index::RATE] = -force;
        dy[index::IMPULSE] = force;
        dy[index::WORK] = force * rate;
        dy[index::DISSIPATED] = if self.law.yields() {
            deepening(y[index::PENETRATION], y[index::DEEPEST], rate)
        } else {
            dissipative * rate * self.per_dissipation
        };
    }
}

impl ContactModel<SIZE> for NormalContact<'_> {
    fn scales(&self) -> &Scales {
        &self.scales
    }

    fn tolerance_factor(&self) -> f64 {
        self.law.tolerance_factor()
    }

    fn start(&self) -> State<SIZE> {
        NormalContact::initial_state()
    }

    fn penetration(&self, y: &State<SIZE>) -> f64 {
        y[index::PENETRATION]
    }

    fn rate(&self, y: &State<SIZE>) -> f64 {
        y[index::RATE]
    }

    fn force(&self, y: &State<SIZE>) -> f64 {
        let (elastic, dissipative) = self.force_parts(y);
        elastic + dissipative
    }

    /// dF/dt = F_d d' + F_v d'' with d'' = -F.
    fn force_rate(&self, y: &State<SIZE>) -> f64 {
        let s = &self.scales;
        let (d, rate) = (y[index::PENETRATION] * s.length, y[index::RATE] * s.speed);
        let (by_penetration, by_rate) = self.law.force_gradient_after(d, rate, self.deepest(y));
        let acceleration = -self.force(y) * s.speed / s.time;
        (by_penetration * rate + by_rate * acceleration) * s.time / s.force
    }

    fn separation_force(&self, y: &State<SIZE>) -> f64 {
        let s = &self.scales;
        let (d, rate) = (y[index::PENETRATION] * s.length, y[index::RATE] * s.speed);
        if self.law.yields() {
            // In units of L, as the penetration it is.
            self.law.separation_function_after(d, rate, self.deepest(y)) / s.length
        } else {
            self.law.separation_function(d, rate)
        }
    }

    fn uncut_force(&self, y: &State<SIZE>) -> Option<f64> {
        let s = &self.scales;
        self.law.uncut_force(y[index::PENETRATION] * s.length, y[index::RATE] * s.speed)
    }

    fn kinks(&self, compressing: bool) -> crate::law::Kinks {
        self.law.kinks(compressing).scaled(self.scales.length)
    }

    fn snapshot(&self, t: f64, y: &State<SIZE>) -> Snapshot {
        let d = y[index::PENETRATION] * self.scales.length;
        let elastic_energy = if self.law.yields() {
            self.law.elastic_energy_after(d, self.deepest(y))
        } else {
            self.law.elastic_energy(d)
        };
        let mut snapshot = self.snapshot_with(t, y, self.force(y) * self.scales.force, elastic_energy);
        if self.law.yields() {
            // What the contact force took from the motion and the unloading will not give back: the dent's work.
            snapshot.dissipated_normal = snapshot.normal_work - elastic_energy;
        }
        snapshot
    }
}

/// The rate of a yielding contact's remembered depth (scaled): the penetration rate while the penetration is at or
/// beyond it and deepening, zero otherwise (unloading, or reloading below it along the unloading curve). In a single
/// load–unload cycle it is d' up to the maximum compression (a located event) and 0 after it.
#[inline]
pub fn deepening(penetration: f64, deepest: f64, rate: f64) -> f64 {
    if rate > 0.0 && penetration >= deepest { rate } else { 0.0 }
}
