//! The units of one contact's scaled variables (docs/numerics.md): lengths in the elastic penetration scale
//! L = (m* v0²/K)^(1/(n+1)), speeds in the approach speed v0, times in T = L/v0, forces in F0 = K L^n = m* v0²/L.
//! A contact's `Setup` resolves them; the models of `dynamics` and the fast path integrate in them.

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

impl Scales {
    /// The units of a contact that stays far shallower than L (a graze: two spheres sliding off each other before
    /// the force can stop their approach), with length unit `length` < L (m) for a law of stiffness `stiffness`
    /// (N/m^n) and exponent `exponent`: the same speed unit v0, time `length`/v0, force K `length`^n, and the
    /// impulse and energy those make (force × time, force × length) — below m* v0 and m* v0² by (length/L)^(n+1),
    /// so that the contact's own impulses and works stay O(1) in the scaled state.
    pub fn with_length(&self, length: f64, stiffness: f64, exponent: f64) -> Scales {
        let force = stiffness * length.powf(exponent);
        let time = length / self.speed;
        Scales { length, speed: self.speed, time, force, impulse: force * time, energy: force * length }
    }
}
