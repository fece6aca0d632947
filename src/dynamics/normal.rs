//! One contact along a fixed normal: the relative motion of two bodies under a contact law.
//!
//! The state carries, besides penetration and its rate, the integrals the report needs, so that impulses and
//! works come from the force history itself rather than from momentum (issue: "from the force history").

use super::Scales;
use crate::integrate::{Model, State};
use crate::law::ContactLaw;

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
    /// ∫ F_dissipative d' dt / (m* v0²): energy dissipated so far.
    pub const DISSIPATED: usize = 4;
}

/// The relative normal motion m* d'' = -F(d, d').
#[derive(Debug, Clone, Copy)]
pub struct NormalContact {
    pub law: ContactLaw,
    pub scales: Scales,
}

impl NormalContact {
    /// The state at first contact: no penetration, closing at the approach speed.
    pub fn initial_state() -> State<SIZE> {
        let mut y = State::<SIZE>::zeros();
        y[index::RATE] = 1.0;
        y
    }

    /// Scaled contact force (elastic, dissipative) at a state. A penetration within [`EDGE`] below zero is the
    /// located edge of the contact (first contact, or separation found to rounding): its force is the limit from
    /// inside, which matters for Kelvin–Voigt (c d' there, not 0).
    pub fn force_parts(&self, y: &State<SIZE>) -> (f64, f64) {
        let s = &self.scales;
        let penetration =
            if y[index::PENETRATION] > -EDGE { y[index::PENETRATION].max(0.0) } else { y[index::PENETRATION] };
        let parts = self.law.split_force(penetration * s.length, y[index::RATE] * s.speed);
        (parts.elastic / s.force, parts.dissipative / s.force)
    }

    /// Scaled contact force.
    pub fn force(&self, y: &State<SIZE>) -> f64 {
        let (elastic, dissipative) = self.force_parts(y);
        elastic + dissipative
    }

    /// Scaled force rate dF/dt = F_d d' + F_v d'' (its zero is the force peak).
    pub fn force_rate(&self, y: &State<SIZE>) -> f64 {
        let s = &self.scales;
        let (d, rate) = (y[index::PENETRATION] * s.length, y[index::RATE] * s.speed);
        let (by_penetration, by_rate) = self.law.force_gradient(d, rate);
        let acceleration = -self.force(y) * s.speed / s.time;
        (by_penetration * rate + by_rate * acceleration) * s.time / s.force
    }
}

impl Model<SIZE> for NormalContact {
    fn derivative(&self, _t: f64, y: &State<SIZE>, dy: &mut State<SIZE>) {
        let (elastic, dissipative) = self.force_parts(y);
        let force = elastic + dissipative;
        let rate = y[index::RATE];
        dy[index::PENETRATION] = rate;
        dy[index::RATE] = -force;
        dy[index::IMPULSE] = force;
        dy[index::WORK] = force * rate;
        dy[index::DISSIPATED] = dissipative * rate;
    }
}
