//! A frictional sphere on a flat wall that slides on the Coulomb limit to its end (after, at most, a first stick
//! while the spring loads): the normal fast path's motion, and the tangential motion in closed form over it
//! (docs/numerics.md#a-slide-in-closed-form; [`crate::dynamics::slide`]'s closed form).
//!
//! On a flat wall the normal motion does not depend on the tangential one, and a slide's tangential force is
//! `mu Fn`: the normal fast path ([`crate::fast`]) gives the normal motion at maximum compression and at the end
//! (and, for a law that pulls before the penetration returns to zero, where its force does), and a slide from a known
//! state is a function of the normal impulse and the penetration there. A contact that starts below the limit
//! (Tsuji's and Kelvin–Voigt's damped force is far above a spring that loads from nothing) is integrated, by the
//! slide's own model, up to where its spring reaches the limit. Whether the slide then holds to the end is decided by a
//! sufficient condition on the normal motion ([`SlideContact::slide_holds`]); a contact that may stick again, or
//! whose slip may come to rest, is `None`: the integrated slide takes it.

use crate::dynamics::ContactModel;
use crate::dynamics::slide::{NormalPoint, SIZE, SlideContact, index};
use crate::fast::{Ending as FastEnding, PhasePoint, Quantities, Request};
use crate::integrate::{Direction, Ending, Event, Scheme, Stepper, Tolerances};
use crate::law::{Family, Separation};
use crate::outcome::{Outcome, TIME_LIMIT};
use crate::scene::Scene;
use crate::setup::Setup;

/// The report's `solver.method` for a contact that slid in closed form over the normal fast path's motion.
pub const CLOSED_FORM_SLIDE: &str = "closed-form-slide";

/// The outcome of `slide`'s contact if it slides on the limit to its end (after a first stick at most), on the
/// normal fast path's motion at the scene's tolerance; `None` where it may not, or the fast path does not finish.
pub fn outcome(slide: &SlideContact, scene: &Scene, setup: &Setup, quantities: Quantities) -> Option<Outcome> {
    if !slide.slides_in_closed_form() || !crate::fast::covers(&setup.law) {
        return None;
    }
    // The first stick, integrated to where the spring reaches the limit (before maximum compression, and with no
    // rest of the slip on the way); before the normal runs, which a stick that does not end in a slide spares.
    let mut start = slide.start();
    let mut steps = (0, 0, 0);
    let stuck = !slide.sliding(&start);
    if stuck {
        let factor = slide.tolerance_factor();
        let requested = scene.solver.tolerances;
        let tolerances = Tolerances { rtol: requested.rtol * factor, atol: requested.atol * factor };
        let scheme = if slide.has_series() { Scheme::Taylor } else { Scheme::Dop853 };
        let mut stepper = Stepper::new(slide, tolerances, false).scheme(scheme);
        let rate = |y: &crate::integrate::State<SIZE>| slide.rate(y);
        let slip = |y: &crate::integrate::State<SIZE>| slide.slip_at(y);
        let switch = |y: &crate::integrate::State<SIZE>| slide.switch_function(y).unwrap_or(1.0);
        let falling = |function, terminal, dips| Event { function, direction: Direction::Falling, terminal, dips };
        let events = [falling(&rate, true, false), falling(&slip, false, false), falling(&switch, true, true)];
        let end = stepper.run(0.0, start, TIME_LIMIT, &events).ok()?;
        if end.ending != Ending::Event(2) || !end.crossings.is_empty() {
            return None;
        }
        start = end.state;
        slide.switch(&mut start);
        let c = stepper.counters;
        steps = (c.steps, c.rejected_steps, c.evaluations);
    }
    let separation = scene.contact.separation;
    let rtol = scene.solver.tolerances.rtol;
    let normal = |separation: Separation, quantities: Quantities| {
        let request = Request { law: setup.law, scales: setup.scales, separation, tolerance: rtol, quantities };
        crate::fast::simulate_normal(&request).ok().filter(|fast| fast.ending == FastEnding::Separated)
    };
    let fast = normal(separation, quantities)?;
    // A law that pulls before its penetration returns to zero: the compressive limit ends where its force does.
    let pulls = matches!(setup.law.kind.family(), Family::Linear | Family::Tsuji);
    let force_zero = match (pulls, separation) {
        // (Its impulse, penetration and time alone.)
        (true, Separation::Penetration) => {
            let motion = Quantities { time: quantities.time, ..Quantities::MOTION };
            Some(normal(Separation::Force, motion)?.end)
        }
        _ => None,
    };
    let limit_end = force_zero.unwrap_or(fast.end);
    steps = (steps.0 + fast.steps, steps.1, steps.2 + fast.force_evaluations);

    let margin = 16.0 * rtol.max(f64::EPSILON) * slide.slip_scale(&start, limit_end.impulse);
    if !slide.slide_holds(&start, fast.max_compression.penetration, limit_end.impulse, margin) {
        return None;
    }

    let point = |p: &PhasePoint| NormalPoint {
        time: p.time,
        penetration: p.penetration,
        impulse: p.impulse,
        work: p.work,
        dissipated: p.dissipated,
    };
    let deepest = slide.slid(&start, &point(&fast.max_compression), false);
    let end = match &force_zero {
        Some(zero) => slide.slid(&slide.slid(&start, &point(zero), false), &point(&fast.end), true),
        None => slide.slid(&start, &point(&fast.end), false),
    };
    let s = &setup.scales;
    let tensile_impulse = match (pulls, separation, &force_zero) {
        (_, _, Some(zero)) => ((zero.impulse - fast.end.impulse) * s.impulse).max(0.0),
        (true, Separation::Force, None) => f64::NAN,
        _ => 0.0,
    };
    let stick_time = if stuck { start[index::TIME] * s.time } else { 0.0 };
    Some(Outcome {
        max_compression: slide.snapshot(fast.max_compression.time, &deepest),
        end: slide.snapshot(fast.end.time, &end),
        peak_force: (fast.peak_force_time * s.time, fast.peak_force * s.force),
        separated: fast.separated,
        ending: Ending::Event(0),
        below_limit_duration: stick_time,
        slip_rest_time: None,
        switches: u32::from(stuck),
        tensile_impulse,
        counters: crate::integrate::Counters { steps: steps.0, rejected_steps: steps.1, evaluations: steps.2 },
        method: CLOSED_FORM_SLIDE,
        restitution: Some((fast.restitution_impulse * s.impulse, fast.restitution_work * s.energy)),
        note: None,
        fixed_step: None,
    })
}
