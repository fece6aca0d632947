//! The fixed-step baselines of the study, on the scaled normal impact `d'' = -F(d, d')` from `d = 0, d' = 1`:
//!
//! * [`rk4`]: the classical Runge–Kutta method of order 4 at a fixed step, with the impulse `J' = F` as a third
//!   state; maximum compression and the force peak located on the step's cubic Hermite interpolant (of the same
//!   order as the method where the force is smooth, so it costs no accuracy and no force evaluation), separation
//!   on the solution itself by re-stepping from the step's start (where the force jumps at separation the step
//!   across it is only first order, and so is its interpolant).
//! * [`verlet`]: velocity Verlet as DEM codes run it: the damping evaluated at the half-step velocity, and every
//!   event taken at the first step past it (no location: the point of this baseline). The impulses come from the
//!   velocities, as a DEM code would get them.
//!
//! The step is `dt = tc / N`, `tc` the elastic contact time of the law's exponent ([`Case::elastic_duration`]):
//! N steps per (elastic) contact, the DEM's rule for the time step.

use super::Measured;
use super::cases::Case;
use crate::law::ContactLaw;

/// Scaled time after which a run that has not separated gives up (elastic contacts last about 3).
const TIME_LIMIT: f64 = 1e3;

/// A run of a baseline: what it measured and the force evaluations it spent.
pub type Run = Result<(Measured, u64), String>;

/// The scaled force at `(d, v)` (the law's, zero for `d < 0`; at `d = 0` the limit from inside).
fn force(law: &ContactLaw, d: f64, v: f64) -> f64 {
    law.force(d, v)
}

/// The force rate `dF/dt = F_d v + F_v v'`, `v' = -F`: it falls through zero at the force peak.
fn force_rate(law: &ContactLaw, d: f64, v: f64) -> f64 {
    let (by_d, by_v) = law.force_gradient(d, v);
    by_d * v - by_v * force(law, d, v)
}

/// The state of the RK4 run: penetration, rate, impulse.
type State = [f64; 3];

/// A function of the state whose fall through zero is an event.
type EventFunction<'a> = &'a dyn Fn(&State) -> f64;

fn derivative(law: &ContactLaw, y: &State) -> State {
    let f = force(law, y[0], y[1]);
    [y[1], -f, f]
}

/// One classical RK4 step of size `h` from `y`, whose derivative `f` is known.
fn rk4_step(law: &ContactLaw, y: &State, f: &State, h: f64) -> State {
    let k2 = derivative(law, &axpy(y, 0.5 * h, f));
    let k3 = derivative(law, &axpy(y, 0.5 * h, &k2));
    let k4 = derivative(law, &axpy(y, h, &k3));
    std::array::from_fn(|i| y[i] + h / 6.0 * (f[i] + 2.0 * (k2[i] + k3[i]) + k4[i]))
}

fn axpy(y: &State, h: f64, k: &State) -> State {
    [y[0] + h * k[0], y[1] + h * k[1], y[2] + h * k[2]]
}

/// One step's cubic Hermite interpolant from `(y0, f0)` to `(y1, f1)` over a step `h`, at fraction `s`.
fn hermite(y0: &State, f0: &State, y1: &State, f1: &State, h: f64, s: f64) -> State {
    let (s2, s3) = (s * s, s * s * s);
    let (h00, h10, h01, h11) = (2.0 * s3 - 3.0 * s2 + 1.0, s3 - 2.0 * s2 + s, 3.0 * s2 - 2.0 * s3, s3 - s2);
    std::array::from_fn(|i| h00 * y0[i] + h10 * h * f0[i] + h01 * y1[i] + h11 * h * f1[i])
}

/// The zero of `g` in `[a, b]` where it falls (`g(a) > 0 >= g(b)`), by the Illinois variant of regula falsi, to
/// a few ulps.
fn fall(mut g: impl FnMut(f64) -> f64, mut a: f64, mut ga: f64, mut b: f64, mut gb: f64) -> f64 {
    if gb == 0.0 {
        return b;
    }
    let mut side = 0;
    for _ in 0..100 {
        let c = (a * gb - b * ga) / (gb - ga);
        let c = if c > a && c < b { c } else { 0.5 * (a + b) };
        if b - a <= 4.0 * f64::EPSILON * b.abs().max(1e-300) {
            return c;
        }
        let gc = g(c);
        if gc > 0.0 {
            (a, ga) = (c, gc);
            if side == 1 {
                gb *= 0.5;
            }
            side = 1;
        } else {
            if gc == 0.0 {
                return c;
            }
            (b, gb) = (c, gc);
            if side == -1 {
                ga *= 0.5;
            }
            side = -1;
        }
    }
    0.5 * (a + b)
}

/// What a fixed-step run needs of its case, prepared before it is timed: the law, the separation criterion and the
/// step.
#[derive(Debug, Clone, Copy)]
pub struct Fixed {
    law: ContactLaw,
    /// Whether separation is at zero force (else at zero penetration).
    on_force: bool,
    /// The step, `tc / N`.
    step: f64,
}

impl Fixed {
    /// `case` at `steps` steps per elastic contact.
    pub fn new(case: &Case, steps: u32) -> Fixed {
        Fixed { law: case.law().0, on_force: case.force_criterion(), step: case.elastic_duration() / f64::from(steps) }
    }
}

/// Classical RK4 at a fixed step, events located on the steps' Hermite interpolants, separation by re-stepping.
pub fn rk4(fixed: &Fixed) -> Run {
    let Fixed { law, on_force, step: h } = *fixed;
    let mut y: State = [0.0, 1.0, 0.0];
    let mut f = derivative(&law, &y);
    let mut evaluations = 1;
    let mut t = 0.0;
    // The force at first contact is a candidate peak (Kelvin–Voigt's jump to c v0).
    let mut peak = (force(&law, 0.0, 1.0), 0.0);
    // The force rises from first contact unless it starts at its largest (Kelvin–Voigt with zeta >= 1/2); the
    // power laws' rate is 0 there (their gradient is singular), so the peak is looked for from the second step.
    let mut rising = force_rate(&law, y[0], y[1]) >= 0.0;
    // (t0, dmax, Jd) once maximum compression is passed.
    let mut compressed: Option<(f64, f64, f64)> = None;
    while t < TIME_LIMIT {
        let next = rk4_step(&law, &y, &f, h);
        let f_next = derivative(&law, &next);
        evaluations += 4;
        let at = |s: f64| hermite(&y, &f, &next, &f_next, h, s);
        // The force peak: dF/dt falls through zero.
        let (g0, g1) = (force_rate(&law, y[0], y[1]), force_rate(&law, next[0], next[1]));
        if rising && g0 > 0.0 && g1 <= 0.0 {
            let s = fall_on(at, |z| force_rate(&law, z[0], z[1]), g0, g1).unwrap_or(1.0);
            let z = at(s);
            let value = force(&law, z[0], z[1]);
            if value > peak.0 {
                peak = (value, t + s * h);
            }
            rising = false;
        }
        // Maximum compression: d' falls through zero.
        let mut from = 0.0;
        if compressed.is_none() && next[1] <= 0.0 {
            let s = fall_on(at, |z| z[1], y[1], next[1]).unwrap_or(1.0);
            let z = at(s);
            let value = force(&law, z[0], 0.0);
            if value > peak.0 {
                peak = (value, t + s * h);
            }
            compressed = Some((t + s * h, z[0], z[2]));
            from = s;
        }
        // Separation: the penetration (or the continued force) falls through zero after maximum compression.
        if let Some((t0, dmax, jd)) = compressed {
            let start = at(from);
            let ending = |z: &State| if on_force { law.separation_function(z[0], z[1]) } else { z[0] };
            let (a, b) = (ending(&start), ending(&next));
            let (d0, d1) = (start[0], next[0]);
            let penetration = |z: &State| z[0];
            let event: Option<(EventFunction, f64, f64)> =
                match (a > 0.0 && b <= 0.0, on_force && d0 > 0.0 && d1 <= 0.0) {
                    (true, _) => Some((&ending, a, b)),
                    (false, true) => Some((&penetration, d0, d1)),
                    _ => None,
                };
            if let Some((event, ga, gb)) = event {
                // The separation on the RK4 solution itself: the interpolant's root first, then a step of RK4 from
                // the step's start to each trial point (a force that jumps at separation, Kelvin–Voigt's or
                // Tsuji's at d = 0, makes the step across it, and so its interpolant, only first order there).
                let hermite_root = fall_between(at, event, from, ga, 1.0, gb).unwrap_or(1.0);
                let mut restep = |fraction: f64| {
                    evaluations += 4;
                    rk4_step(&law, &y, &f, fraction * h)
                };
                let mut on_solution = |fraction: f64| event(&restep(fraction));
                let g = on_solution(hermite_root);
                let s = if g > 0.0 {
                    fall(on_solution, hermite_root, g, 1.0, gb)
                } else if g == 0.0 {
                    hermite_root
                } else {
                    fall(on_solution, from, ga, hermite_root, g)
                };
                let z = restep(s);
                let measured = Measured {
                    restitution: -z[1],
                    max_penetration: dmax,
                    max_compression_time: t0,
                    duration: t + s * h,
                    peak_force: peak.0,
                    deformation_impulse: jd,
                    restitution_impulse: z[2] - jd,
                };
                return Ok((measured, evaluations));
            }
        }
        (y, f, t) = (next, f_next, t + h);
    }
    Err(format!("no separation within {TIME_LIMIT} time units"))
}

/// The falling zero over a whole step `[0, 1]` of `event` along the interpolant `at`, given its end values.
fn fall_on(at: impl Fn(f64) -> State, event: impl Fn(&State) -> f64, g0: f64, g1: f64) -> Option<f64> {
    fall_between(at, event, 0.0, g0, 1.0, g1)
}

/// The falling zero of `event` along `at` between fractions `a` and `b` of the step, given its values there.
fn fall_between(
    at: impl Fn(f64) -> State,
    event: impl Fn(&State) -> f64,
    a: f64,
    ga: f64,
    b: f64,
    gb: f64,
) -> Option<f64> {
    (ga > 0.0 && gb <= 0.0).then(|| fall(|s| event(&at(s)), a, ga, b, gb))
}

/// Velocity Verlet at `steps` steps per elastic contact, the DEM's way: `v½ = v - (dt/2) F`, `d += dt v½`,
/// `F = F(d, v½)`, `v = v½ - (dt/2) F`; maximum compression at the first step whose velocity is not positive (its
/// overlap the largest seen), the force peak the largest force computed, separation at the first step whose
/// overlap (or, under the force criterion, force) is not positive while the bodies move apart, `e = -v½` there.
pub fn verlet(fixed: &Fixed) -> Run {
    let Fixed { law, on_force, step: dt } = *fixed;
    let (mut d, mut v, mut f, mut t) = (0.0f64, 1.0f64, 0.0f64, 0.0f64);
    let mut evaluations = 0;
    let mut peak = (0.0f64, 0.0f64);
    let mut dmax = 0.0f64;
    let mut compressed: Option<(f64, f64)> = None;
    while t < TIME_LIMIT {
        let half = v - 0.5 * dt * f;
        d += dt * half;
        t += dt;
        if let Some((t0, jd)) = compressed
            && half < 0.0
            && (d <= 0.0 || (on_force && law.separation_function(d, half) <= 0.0))
        {
            let measured = Measured {
                restitution: -half,
                max_penetration: dmax,
                max_compression_time: t0,
                duration: t,
                peak_force: peak.0,
                deformation_impulse: jd,
                // The impulse from the velocities: m* (v(t0) - v_end).
                restitution_impulse: (1.0 - jd) + (-half),
            };
            return Ok((measured, evaluations));
        }
        f = if d > 0.0 { force(&law, d, half) } else { 0.0 };
        evaluations += 1;
        v = half - 0.5 * dt * f;
        dmax = dmax.max(d);
        if f > peak.0 {
            peak = (f, t);
        }
        if compressed.is_none() && v <= 0.0 {
            compressed = Some((t, 1.0 - v));
        }
    }
    Err(format!("no separation within {TIME_LIMIT} time units"))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::law::Separation;

    fn errors(run: Run, case: &Case) -> [f64; 7] {
        run.expect("separates").0.errors(&case.exact().expect("exact"))
    }

    /// RK4 with located events converges on every measured quantity (the Hertzian force's `d^(3/2)` at the edges
    /// of the contact costs it some order), and locates a force separation too.
    #[test]
    fn rk4_converges_on_every_quantity() {
        let case = Case::HuntCrossley { x: 0.5, n: 1.5 };
        let coarse = errors(rk4(&Fixed::new(&case, 100)), &case);
        let fine = errors(rk4(&Fixed::new(&case, 1000)), &case);
        for (i, (c, f)) in coarse.iter().zip(&fine).enumerate() {
            assert!(*f < 1e-8, "{}: {f:e} at N = 1000", super::super::QUANTITIES[i]);
            assert!(*f < 1e-2 * c.max(1e-14) || *f < 1e-13, "{}: {c:e} -> {f:e}", super::super::QUANTITIES[i]);
        }
        let linear = Case::KelvinVoigt { zeta: 0.1, separation: Separation::Force };
        let worst = errors(rk4(&Fixed::new(&linear, 1000)), &linear).into_iter().fold(0.0, f64::max);
        assert!(worst < 1e-10, "Kelvin–Voigt at F = 0: {worst:e}");
    }

    /// Verlet takes every event at the first step past it: the times of maximum compression and separation are
    /// late by less than a step, V0 is off by the velocity one step past the turn; e converges (the DEM's
    /// measure of accuracy).
    #[test]
    fn verlet_takes_events_at_the_first_step_past_them() {
        let case = Case::HuntCrossley { x: 0.5, n: 1.5 };
        let exact = case.exact().expect("exact");
        for n in [100, 1000] {
            let dt = case.elastic_duration() / f64::from(n);
            let (measured, evaluations) = verlet(&Fixed::new(&case, n)).expect("separates");
            let late = |got: f64, want: f64| got >= want && got < want + dt;
            assert!(late(measured.max_compression_time, exact.max_compression_time), "t0 at N = {n}");
            assert!(late(measured.duration, exact.duration), "tc at N = {n}");
            assert!((measured.deformation_impulse - 1.0).abs() <= dt * exact.max_force, "V0 at N = {n}");
            assert!(measured.max_penetration <= exact.max_penetration * (1.0 + 1e-3), "dmax at N = {n}");
            let e_error = (measured.restitution / exact.restitution - 1.0).abs();
            assert!(e_error < 0.1 / f64::from(n * n), "e at N = {n}: {e_error:e}");
            assert!(evaluations.abs_diff(u64::from(n)) < u64::from(n) / 5, "one force a step: {evaluations}");
        }
    }
}
