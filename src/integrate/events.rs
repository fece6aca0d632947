//! Event functions and their location between two accepted steps.

use super::{IntegrationError, Vector};
use nalgebra::allocator::Allocator;
use nalgebra::{Const, DefaultAllocator, Dim};

/// Which sign changes of an event function count.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Direction {
    /// From positive to zero or negative.
    Falling,
    /// From negative to zero or positive.
    Rising,
}

/// A scalar function of the state whose zero marks an event (maximum compression, separation, peak force, ...).
pub struct EventOf<'a, D: Dim>
where
    DefaultAllocator: Allocator<D>,
{
    /// g(y); the event is where it crosses zero in `direction`.
    pub function: &'a dyn Fn(&Vector<D>) -> f64,
    pub direction: Direction,
    /// A terminal event ends the run; others are only located and reported.
    pub terminal: bool,
    /// Whether a Dop853 or Dopri5 run also watches the function for a dip below zero and back inside one step:
    /// its slope is read at every accepted point (a difference along the solver's derivative there, one more
    /// evaluation a step), and where it falls at a step's start and rises at its end, and either end's tangent
    /// reaches zero inside the step or the two meet below half its smaller end value, the step is searched for its
    /// minimum by re-stepping (`dip_by_restepping`, stepper.rs); a minimum below zero ends a bracket of the crossing
    /// like any other. A frictional contact's stick–slip switch is so watched: under the magnitude cap the room
    /// under `mu |Fn|` falls to `-|T|` where the normal force passes through zero, for a few nanoseconds where the
    /// spring is soft. (A Taylor run reads every function's minima on its step polynomials.)
    pub dips: bool,
}

/// An event of a model of fixed size.
pub type Event<'a, const N: usize> = EventOf<'a, Const<N>>;

/// A located event: which one, when, and the state there.
#[derive(Debug, Clone, PartialEq)]
pub struct CrossingOf<D: Dim>
where
    DefaultAllocator: Allocator<D>,
{
    /// Index of the event in the list given to the run.
    pub event: usize,
    /// Scaled time of the crossing.
    pub time: f64,
    /// State at the crossing.
    pub state: Vector<D>,
}

/// A located event of a model of fixed size.
pub type Crossing<const N: usize> = CrossingOf<Const<N>>;

impl<D: Dim> EventOf<'_, D>
where
    DefaultAllocator: Allocator<D>,
{
    /// The event function signed so that the event is a fall through zero.
    pub(crate) fn value(&self, y: &Vector<D>) -> f64 {
        let g = (self.function)(y);
        match self.direction {
            Direction::Falling => g,
            Direction::Rising => -g,
        }
    }

    /// Whether the event function crosses zero in its direction between two points.
    pub fn crosses(&self, y0: &Vector<D>, y1: &Vector<D>) -> bool {
        falls(self.value(y0), self.value(y1))
    }
}

/// Whether a signed event value falls through zero from `before` to `after`.
pub(crate) fn falls(before: f64, after: f64) -> bool {
    before > 0.0 && after <= 0.0
}

/// A point of the solution with its derivative: (time, state, state').
pub type Point<D> = (f64, Vector<D>, Vector<D>);

/// Cubic Hermite interpolant of the step from `a` to `b` at time `t`: only a starting guess for the root.
fn hermite<D: Dim>(a: &Point<D>, b: &Point<D>, t: f64) -> Vector<D>
where
    DefaultAllocator: Allocator<D>,
{
    let h = b.0 - a.0;
    let s = (t - a.0) / h;
    let (s2, s3) = (s * s, s * s * s);
    let h00 = 2.0 * s3 - 3.0 * s2 + 1.0;
    let h10 = s3 - 2.0 * s2 + s;
    let h01 = -2.0 * s3 + 3.0 * s2;
    let h11 = s3 - s2;
    &a.1 * h00 + &a.2 * (h10 * h) + &b.1 * h01 + &b.2 * (h11 * h)
}

/// Locates the crossing of `event` between accepted points `a` and `b`, evaluating the true solution at trial times
/// through `solution_at` (a re-step from `a`, or a `cheap` one: a step's own polynomial). Safeguarded secant on a
/// shrinking bracket, started from the root of the Hermite interpolant (from regula falsi where the solution is as
/// cheap as the interpolant); stops when the bracket or the step is a few ulps of the time.
pub fn locate<D: Dim>(
    event: &EventOf<'_, D>,
    index: usize,
    a: &Point<D>,
    b: &Point<D>,
    cheap: bool,
    mut solution_at: impl FnMut(f64) -> Result<Vector<D>, IntegrationError>,
) -> Result<CrossingOf<D>, IntegrationError>
where
    DefaultAllocator: Allocator<D>,
{
    // Bracket [lo, hi] with value(lo) > 0 >= value(hi).
    let (mut lo, mut g_lo) = (a.0, event.value(&a.1));
    let (mut hi, mut g_hi, mut y_hi) = (b.0, event.value(&b.1), b.1.clone());
    if g_hi == 0.0 {
        return Ok(CrossingOf { event: index, time: hi, state: y_hi });
    }
    let resolution = |t: f64| 4.0 * f64::EPSILON * t.abs().max(b.0 - a.0);
    if cheap {
        return bracketed(event, index, (lo, g_lo), (hi, g_hi, y_hi), resolution, solution_at);
    }
    // Starting guess: bisection on the cheap interpolant.
    let (mut left, mut right) = (lo, hi);
    for _ in 0..60 {
        let mid = 0.5 * (left + right);
        if event.value(&hermite(a, b, mid)) > 0.0 { left = mid } else { right = mid }
    }
    let mut trial = 0.5 * (left + right);
    let mut previous: Option<(f64, f64)> = None;
    for _ in 0..60 {
        let y = solution_at(trial)?;
        let g = event.value(&y);
        if g > 0.0 {
            (lo, g_lo) = (trial, g);
        } else {
            (hi, g_hi, y_hi) = (trial, g, y.clone());
        }
        if g == 0.0 || hi - lo <= resolution(trial) {
            return Ok(CrossingOf { event: index, time: trial, state: y });
        }
        // Secant through the last two trials; regula falsi on the bracket when there is no usable secant, and
        // bisection when the secant leaves the bracket.
        let next = match previous {
            Some((t_prev, g_prev)) if g != g_prev => trial - g * (trial - t_prev) / (g - g_prev),
            _ => lo - g_lo * (hi - lo) / (g_hi - g_lo),
        };
        previous = Some((trial, g));
        if (next - trial).abs() <= resolution(trial) {
            return Ok(CrossingOf { event: index, time: trial, state: y });
        }
        trial = if next > lo && next < hi { next } else { 0.5 * (lo + hi) };
    }
    // Not reached in practice: the bracket halves at worst every other trial.
    Ok(CrossingOf { event: index, time: hi, state: y_hi })
}

/// [`locate`] where the solution is as cheap as an interpolant (a Taylor step's polynomial): the Illinois variant of
/// regula falsi on the bracket, each trial at least the resolution inside it (so that a trial converging on one end
/// proves the bracket with the next) and a 64th of it inside an end of the step's own, and a bisection after two
/// trials that did not halve it, until the bracket is within the resolution; the crossing is the bracket's end past
/// the zero (the function at or below it). No trial ends the search by a short step alone: from an end within
/// rounding of zero (a switch function at the start of its mode), regula falsi's first trials move by ulps, and
/// stopping there would place the crossing at the start rather than where the function falls.
pub(crate) fn bracketed<D: Dim>(
    event: &EventOf<'_, D>,
    index: usize,
    (mut lo, mut g_lo): (f64, f64),
    (mut hi, mut g_hi, mut y_hi): (f64, f64, Vector<D>),
    resolution: impl Fn(f64) -> f64,
    mut solution_at: impl FnMut(f64) -> Result<Vector<D>, IntegrationError>,
) -> Result<CrossingOf<D>, IntegrationError>
where
    DefaultAllocator: Allocator<D>,
{
    let mut slow = 0;
    let mut last_side = 0i8;
    let (mut lo_moved, mut hi_moved) = (false, false);
    for _ in 0..200 {
        let width = hi - lo;
        let margin = resolution(hi);
        if width <= margin {
            break;
        }
        // (An end the search has not moved is the step's, where the function may sit within rounding of zero — a
        // switch function at the start of its mode —: a trial within rounding of it would read the rounding's sign.)
        let (low, high) = (if lo_moved { margin } else { width / 64.0 }, if hi_moved { margin } else { width / 64.0 });
        let trial = if slow >= 2 || width <= 2.0 * margin {
            0.5 * (lo + hi)
        } else {
            (lo - g_lo * width / (g_hi - g_lo)).clamp(lo + low, hi - high)
        };
        let y = solution_at(trial)?;
        let g = event.value(&y);
        if g > 0.0 {
            if last_side > 0 {
                g_hi *= 0.5;
            }
            (lo, g_lo, last_side, lo_moved) = (trial, g, 1, true);
        } else {
            if last_side < 0 {
                g_lo *= 0.5;
            }
            (hi, g_hi, y_hi, last_side, hi_moved) = (trial, g, y, -1, true);
            if g == 0.0 {
                break;
            }
        }
        slow = if hi - lo > 0.5 * width { slow + 1 } else { 0 };
    }
    Ok(CrossingOf { event: index, time: hi, state: y_hi })
}
