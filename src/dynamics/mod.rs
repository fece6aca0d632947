//! Equations of motion during contact, in scaled variables.
//!
//! Lengths are measured in the elastic penetration scale L = (m* v0²/K)^(1/(n+1)), speeds in the approach speed v0,
//! times in T = L/v0, forces in F0 = K L^n = m* v0²/L (physics.md §3). Every scaled quantity is O(1) whatever the
//! bodies, which is what makes one absolute tolerance meaningful.

pub mod normal;

/// The units of the scaled variables of one contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scales {
    /// L, m.
    pub length: f64,
    /// v0, m/s.
    pub speed: f64,
    /// T = L/v0, s.
    pub time: f64,
    /// F0 = m* v0²/L, N.
    pub force: f64,
    /// m* v0, N s.
    pub impulse: f64,
    /// m* v0², J.
    pub energy: f64,
}

impl Scales {
    /// Scales of a contact of effective mass `effective_mass` (kg), stiffness `stiffness` (N/m^n), exponent
    /// `exponent` and approach speed `approach_speed` (m/s, > 0).
    pub fn new(effective_mass: f64, stiffness: f64, exponent: f64, approach_speed: f64) -> Scales {
        let energy = effective_mass * approach_speed * approach_speed;
        let length = (energy / stiffness).powf(1.0 / (exponent + 1.0));
        Scales {
            length,
            speed: approach_speed,
            time: length / approach_speed,
            force: energy / length,
            impulse: effective_mass * approach_speed,
            energy,
        }
    }
}
