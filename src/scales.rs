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
        thread_local! {
            static LENGTH: Remembered = const { Remembered::new() };
        }
        let energy = effective_mass * approach_speed * approach_speed;
        let length = powf_remembered(&LENGTH, energy / stiffness, 1.0 / (exponent + 1.0));
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

/// `length^exponent` ([`powf_remembered`]): the fast path's check that a law's scales are its own
/// (`fast::regularised`) forms `L^n`, the same on every row of a sweep of the damping.
pub fn length_power(length: f64, exponent: f64) -> f64 {
    thread_local! {
        static POWER: Remembered = const { Remembered::new() };
    }
    powf_remembered(&POWER, length, exponent)
}

/// The last power one call site of [`powf_remembered`] formed on this thread: its arguments' bits and `x^y`.
pub struct Remembered(std::cell::Cell<(u64, u64, f64)>);

impl Remembered {
    /// `0^0 = 1` to begin with (a true power: a call with those arguments may take it).
    pub const fn new() -> Remembered {
        Remembered(std::cell::Cell::new((0, 0, 1.0)))
    }
}

impl Default for Remembered {
    fn default() -> Remembered {
        Remembered::new()
    }
}

/// `x.powf(y)`, taken from `site` when its last arguments were these, bit for bit: the same number, without a
/// `pow` each time a sweep's rows set up contacts that differ only in their damping (their scales, and the law's
/// size check, take the same powers row after row). `site` is one call site's thread-local.
pub fn powf_remembered(site: &'static std::thread::LocalKey<Remembered>, x: f64, y: f64) -> f64 {
    site.with(|memory| {
        let (a, b, power) = memory.0.get();
        if (a, b) == (x.to_bits(), y.to_bits()) {
            return power;
        }
        let power = x.powf(y);
        memory.0.set((x.to_bits(), y.to_bits(), power));
        power
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    thread_local! {
        static SITE: Remembered = const { Remembered::new() };
    }

    /// The remembered power is the power, bit for bit, for repeated and alternating arguments, signed zeros, NaN and
    /// the starting `0^0`.
    #[test]
    fn a_remembered_power_is_the_power() {
        let cases = [(0.0, 0.0), (2.5, 0.4), (2.5, 0.4), (-0.0, 0.0), (0.0, -0.0), (f64::NAN, 2.0), (8.0, 1.0 / 3.0)];
        for (x, y) in cases.into_iter().chain(cases.into_iter().rev()) {
            let (remembered, direct) = (powf_remembered(&SITE, x, y), x.powf(y));
            assert_eq!(remembered.to_bits(), direct.to_bits(), "{x}^{y}");
        }
    }
}
