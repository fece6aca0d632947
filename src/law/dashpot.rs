//! `hertz-dashpot`'s damping for a nominal e at one contact's approach speed, found by simulation.
//!
//! `F = K d^n + c d'` has no closed-form e for n ≠ 1, but in the contact's own units (L = (m* v0² / K)^(1/(n+1)),
//! T = L / v0: x = d/L, time in T) its normal motion is `x'' = -x^n - 2 zeta x'` from `x = 0, x' = 1`, with the
//! dimensionless dashpot `zeta = c L / (2 m* v0)`. Its e depends on zeta, n and the separation criterion alone, so
//! one root-find of zeta on the simulated e of that motion (Dop853 with the events located, as the contact models
//! run it, at tolerances tighter than any scene's) serves every contact of the same e, n and separation:
//! `c = 2 zeta m* v0 / L` at the contact's own speed. Found values are kept per thread, so a sweep or a world that
//! asks again does not simulate again.

use super::Separation;
use crate::integrate::{Direction, Ending, Event, Model, State, Stepper, Tolerances};
use crate::reference::{Bracket, Stop, illinois, kelvin_voigt_zeta};
use std::cell::RefCell;

/// Tolerances of the scaled simulations: a hundredth of the scenes' defaults, so that a scene's own run of the
/// resolved c meets the nominal e to its own accuracy.
const TOLERANCES: Tolerances = Tolerances { rtol: 1e-12, atol: 1e-14 };
/// How close the simulated e must come to the nominal one (absolute).
pub const MATCH: f64 = 1e-11;
/// Largest zeta the bracketing tries: beyond it the e of any exponent is below the smallest e a scene may ask for.
const MAX_ZETA: f64 = 1e10;
/// Scaled time after which a contact that has not separated counts as stuck.
const TIME_LIMIT: f64 = 1e4;

/// x'' = -x^n - 2 zeta x', the penetration's power continued at zero below it (a step across the end sees the
/// damper alone, as the contact models' continued force does).
struct Scaled {
    exponent: f64,
    zeta: f64,
}

impl Model<2> for Scaled {
    fn derivative(&self, _t: f64, y: &State<2>, dy: &mut State<2>) {
        dy[0] = y[1];
        dy[1] = -super::power(y[0].max(0.0), self.exponent) - 2.0 * self.zeta * y[1];
    }
}

/// The e of the scaled contact (the velocity it parts with over the approach speed), or `None` if it does not
/// separate (or the integrator gives up).
pub fn scaled_restitution(zeta: f64, exponent: f64, separation: Separation) -> Option<f64> {
    let model = Scaled { exponent, zeta };
    let mut stepper = Stepper::new(&model, TOLERANCES, false);
    let turned = |y: &State<2>| y[1];
    let compression = [Event { function: &turned, direction: Direction::Falling, terminal: true, dips: false }];
    let start = State::<2>::new(0.0, 1.0);
    let deepest = stepper.run(0.0, start, TIME_LIMIT, &compression).ok()?;
    if deepest.ending != Ending::Event(0) {
        return None;
    }
    let penetration = |y: &State<2>| y[0];
    let force = |y: &State<2>| super::power(y[0].max(0.0), exponent) + 2.0 * zeta * y[1];
    let end: &dyn Fn(&State<2>) -> f64 = match separation {
        Separation::Penetration => &penetration,
        Separation::Force => &force,
    };
    let ending = [
        Event { function: end, direction: Direction::Falling, terminal: true, dips: false },
        Event { function: &penetration, direction: Direction::Falling, terminal: true, dips: false },
    ];
    let parted = stepper.run(deepest.time, deepest.state, TIME_LIMIT, &ending).ok()?;
    matches!(parted.ending, Ending::Event(_)).then(|| -parted.state[1])
}

/// What a zeta was found for: the bits of e and n, and the separation criterion.
type Key = (u64, u64, Separation);

thread_local! {
    /// (e, n, separation) → zeta found on this thread.
    static FOUND: RefCell<Vec<(Key, f64)>> = const { RefCell::new(Vec::new()) };
}

/// The dimensionless dashpot zeta = c L / (2 m* v0) whose simulated e is `e` (in (0, 1]) for the exponent `exponent`
/// and the separation criterion; `None` if no zeta up to [`MAX_ZETA`] brings e down to it.
pub fn dashpot_zeta(e: f64, exponent: f64, separation: Separation) -> Option<f64> {
    if e == 1.0 {
        return Some(0.0);
    }
    if !(e > 0.0 && e < 1.0) {
        return None;
    }
    let key = (e.to_bits(), exponent.to_bits(), separation);
    if let Some(zeta) = FOUND.with(|found| found.borrow().iter().find(|(k, _)| *k == key).map(|(_, z)| *z)) {
        return Some(zeta);
    }
    let zeta = find(e, exponent, separation)?;
    FOUND.with(|found| {
        let mut found = found.borrow_mut();
        if found.len() >= 64 {
            found.remove(0);
        }
        found.push((key, zeta));
    });
    Some(zeta)
}

/// The root-find: from the linear spring–dashpot's zeta for e (n = 1 is that oscillator), grown by 4 until the
/// simulated e falls below the target, then Illinois with a bisection safeguard.
fn find(e: f64, exponent: f64, separation: Separation) -> Option<f64> {
    let residual = |zeta: f64| scaled_restitution(zeta, exponent, separation).unwrap_or(-1.0) - e;
    let mut hi = kelvin_voigt_zeta(e).clamp(1e-12, 0.5);
    let mut f_hi = residual(hi);
    let (mut lo, mut f_lo) = (0.0, 1.0 - e);
    while f_hi > 0.0 {
        if hi > MAX_ZETA {
            return None;
        }
        (lo, f_lo) = (hi, f_hi);
        hi *= 4.0;
        f_hi = residual(hi);
    }
    let stop = Stop { residual: 1e-14, relative_width: 1e-14, max_evaluations: 200 };
    let root = illinois(|zeta| Ok::<_, ()>(residual(zeta)), Bracket { lo, f_lo, hi, f_hi }, stop).ok()?;
    (root.residual.abs() <= MATCH).then_some(root.x)
}

/// c (N s/m) of `hertz-dashpot` for the nominal `e` at a contact of `stiffness` K (N/m^n), `exponent` n,
/// `effective_mass` m* (kg) and `approach_speed` v0 (m/s): 2 zeta m* v0 / L.
pub fn dashpot_damping(
    e: f64,
    stiffness: f64,
    exponent: f64,
    effective_mass: f64,
    approach_speed: f64,
    separation: Separation,
) -> Option<f64> {
    let zeta = dashpot_zeta(e, exponent, separation)?;
    let length = (effective_mass * approach_speed * approach_speed / stiffness).powf(1.0 / (exponent + 1.0));
    Some(2.0 * zeta * effective_mass * approach_speed / length)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn at_exponent_one_the_scaled_contact_is_the_linear_oscillator() {
        // e = exp(-pi zeta / sqrt(1 - zeta²)) separating at x = 0.
        for zeta in [0.05, 0.3, 0.7] {
            let e = scaled_restitution(zeta, 1.0, Separation::Penetration).unwrap();
            let exact = (-PI * zeta / (1.0 - zeta * zeta).sqrt()).exp();
            assert!((e - exact).abs() < 1e-11, "zeta {zeta}: {e} against {exact}");
        }
    }

    #[test]
    fn the_found_zeta_gives_back_e() {
        for (e, n, separation) in [(0.5, 1.5, Separation::Penetration), (0.9, 2.0, Separation::Force)] {
            let zeta = dashpot_zeta(e, n, separation).unwrap();
            let back = scaled_restitution(zeta, n, separation).unwrap();
            assert!((back - e).abs() <= MATCH, "{back} for {e}");
        }
        let zeta = dashpot_zeta(0.6, 1.0, Separation::Penetration).unwrap();
        assert!((zeta - kelvin_voigt_zeta(0.6)).abs() < 1e-10, "{zeta}");
    }
}
