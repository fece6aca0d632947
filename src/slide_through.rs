//! A frictional sphere on a flat wall whose last slide on the Coulomb limit, to its end, runs in closed form over
//! the normal fast path's motion (docs/numerics.md#a-slide-in-closed-form; [`crate::dynamics::slide`]'s closed form),
//! what comes before it integrated by the slide's own model.
//!
//! On a flat wall the normal motion does not depend on the tangential one, and a slide's tangential force is
//! `mu Fn`: the normal fast path ([`crate::fast`]) gives the normal motion at maximum compression and at the end
//! (and, for a law that pulls before the penetration returns to zero, where its force does), and a slide from a known
//! state is a function of the normal impulse and the penetration there. The contact is integrated (by Taylor series,
//! or Dop853 where the series do not cover the laws) from first contact — a first stick while the spring loads, a
//! slide whose slip comes to rest, a stick — and at each switch into a slide a sufficient condition on the normal
//! motion ([`SlideContact::slide_holds`]) says whether that slide lasts to the end; the first that does runs in closed
//! form. A contact that reaches its end first is finished there, as the integrated slide would; one whose run gives up
//! is `None`: the integrated slide takes it.

use crate::dynamics::ContactModel;
use crate::dynamics::contact::MAX_SWITCHES;
use crate::dynamics::slide::{NormalPoint, SIZE, SLIDE, SlideContact, TAYLOR_SLIDE, index};
use crate::fast::{Ending as FastEnding, PhasePoint, Quantities, Request};
use crate::integrate::{Counters, Direction, Ending, Event, Scheme, State, Stepper};
use crate::law::{Family, Separation};
use crate::outcome::{Outcome, TIME_LIMIT};
use crate::scene::Scene;
use crate::setup::Setup;

/// The report's `solver.method` for a contact whose last slide ran in closed form over the normal fast path's motion.
pub const CLOSED_FORM_SLIDE: &str = "closed-form-slide";

/// The outcome of `slide`'s contact where, from some switch on, it slides on the limit to its end: the stretches
/// before (a first stick while the spring loads; a slide whose slip comes to rest, the stick that follows) integrated
/// by the slide's own model, the normal fast path's motion at the scene's tolerance for the rest; integrated to the
/// end where no slide holds before it; `None` where the normal motion does not separate, or the integration gives
/// up or ends without a separation speed.
pub fn outcome(slide: &SlideContact, scene: &Scene, setup: &Setup, quantities: Quantities) -> Option<Outcome> {
    // (Every law it takes is the normal fast path's.)
    if !slide.slides_in_closed_form() {
        return None;
    }
    let separation = scene.contact.separation;
    let rtol = scene.solver.tolerances.rtol;
    let normal = |separation: Separation, quantities: Quantities| {
        let request = Request { law: setup.law, scales: setup.scales, separation, tolerance: rtol, quantities };
        crate::fast::simulate_normal(&request).ok().filter(|fast| fast.ending == FastEnding::Separated)
    };
    // A law that pulls before its penetration returns to zero: the compressive limit ends where its force does.
    let pulls = matches!(setup.law.kind.family(), Family::Linear | Family::Tsuji);
    // The normal motion (and where the force turns tensile), first: a contact that does not separate is left to the
    // integrated slide before any step.
    let fast = normal(separation, quantities)?;
    let mut normal_work = Counters { steps: fast.steps, rejected_steps: 0, evaluations: fast.force_evaluations };
    let force_zero = match (pulls, separation) {
        // (Its impulse, penetration and time alone.)
        (true, Separation::Penetration) => {
            let zero = normal(Separation::Force, Quantities { time: quantities.time, ..Quantities::MOTION })?;
            normal_work.steps += zero.steps;
            normal_work.evaluations += zero.force_evaluations;
            Some(zero.end)
        }
        _ => None,
    };
    let limit_end = force_zero.unwrap_or(fast.end).impulse;

    // The stretches before the last slide, integrated: compression to its maximum, then restitution, each stopping at
    // every stick–slip switch; a contact whose end comes before a slide that holds is finished there (with a
    // separation speed), and one whose run gives up goes back to the integrated slide.
    let tolerances = slide.tolerances(scene.solver.tolerances);
    let scheme = if slide.has_series() { Scheme::Taylor } else { Scheme::Dop853 };
    let mut stepper = Stepper::new(slide, tolerances, false).scheme(scheme);
    let rate = |y: &State<SIZE>| slide.rate(y);
    let slip = |y: &State<SIZE>| slide.slip_at(y);
    let switch = |y: &State<SIZE>| slide.switch_function(y).unwrap_or(1.0);
    let falling = |function, terminal, dips| Event { function, direction: Direction::Falling, terminal, dips };
    // (In the phase driver's order, the stick–slip switch last: the phase's end first, then the slip's rest.)
    let compression = [falling(&rate, true, false), falling(&slip, false, false), falling(&switch, true, true)];
    // The contact's end: the zero of the force under the force's criterion for a law that turns tensile (the
    // penetration's zero a second one, as in the phase driver), the penetration's otherwise.
    let on_force = pulls && separation == Separation::Force;
    let penetration = |y: &State<SIZE>| slide.penetration(y);
    let separation_force = |y: &State<SIZE>| slide.separation_force(y);
    let ending: &dyn Fn(&State<SIZE>) -> f64 = if on_force { &separation_force } else { &penetration };
    let restitution = [
        falling(ending, true, false),
        falling(&penetration, true, false),
        falling(&slip, false, false),
        falling(&switch, true, true),
    ];
    let (mut sigma, mut y) = (0.0, slide.start());
    let mut compressed: Option<(f64, State<SIZE>)> = None;
    let mut below_limit_since = (!slide.sliding(&y)).then_some(0.0);
    let (mut below_limit, mut switches, mut slip_rest) = (0.0, 0u32, None);
    let closed = loop {
        if slide.sliding(&y) {
            let margin = 16.0 * rtol.max(f64::EPSILON) * slide.slip_scale(&y, limit_end);
            if slide.slide_holds(&y, fast.max_compression.penetration, limit_end, margin) {
                break true;
            }
        }
        let (events, slip_event): (&[Event<'_, SIZE>], usize) =
            if compressed.is_none() { (&compression, 1) } else { (&restitution, 2) };
        let end = stepper.run(sigma, y, TIME_LIMIT, events).ok()?;
        if slip_rest.is_none() {
            slip_rest = end.crossings.iter().find(|c| c.event == slip_event).map(|c| c.state[index::TIME]);
        }
        (sigma, y) = (end.time, end.state);
        match end.ending {
            Ending::Event(event) if event == events.len() - 1 && switches < MAX_SWITCHES => {
                // (The compressive limit's corner, into and out of the slide while the force pulls, is a switch of
                // the slide model's own, not counted: as the integrated slide reports them.)
                let corner = slide.unloaded(&y);
                slide.switch(&mut y);
                if corner || slide.unloaded(&y) {
                    continue;
                }
                switches += 1;
                let now = y[index::TIME];
                if slide.sliding(&y) {
                    below_limit += below_limit_since.take().map_or(0.0, |since| now - since);
                } else {
                    below_limit_since = Some(now);
                }
            }
            Ending::Event(0) if compressed.is_none() => compressed = Some((sigma, y)),
            // The end of the contact, reached integrating (a last slide the condition could not show to hold), the
            // bodies parting: the integrated end. (Without a separation speed, the integrated slide's run decides.)
            Ending::Event(0 | 1) if slide.rate(&y) < 0.0 => {
                below_limit += below_limit_since.take().map_or(0.0, |since| y[index::TIME] - since);
                break false;
            }
            _ => return None,
        }
    };
    let point = |p: &PhasePoint| NormalPoint {
        time: p.time,
        penetration: p.penetration,
        impulse: p.impulse,
        work: p.work,
        dissipated: p.dissipated,
    };
    let deepest = match compressed {
        Some((sigma, state)) => slide.snapshot(sigma, &state),
        None => slide.snapshot(fast.max_compression.time, &slide.slid(&y, &point(&fast.max_compression), false)),
    };
    let end = match (closed, &force_zero) {
        (false, _) => slide.snapshot(sigma, &y),
        (true, Some(zero)) => {
            let y = slide.slid(&slide.slid(&y, &point(zero), false), &point(&fast.end), true);
            slide.snapshot(fast.end.time, &y)
        }
        (true, None) => slide.snapshot(fast.end.time, &slide.slid(&y, &point(&fast.end), false)),
    };
    let s = &setup.scales;
    let tensile_impulse = match (pulls, separation, &force_zero) {
        (_, _, Some(zero)) => ((zero.impulse - fast.end.impulse) * s.impulse).max(0.0),
        (true, Separation::Force, None) => f64::NAN,
        _ => 0.0,
    };
    let c = stepper.counters;
    Some(Outcome {
        max_compression: deepest,
        end,
        peak_force: (fast.peak_force_time * s.time, fast.peak_force * s.force),
        // (The normal motion separated, and an integrated end is taken only with a separation speed.)
        separated: true,
        ending: Ending::Event(0),
        below_limit_duration: below_limit * s.time,
        slip_rest_time: slip_rest.map(|t| t * s.time),
        switches,
        tensile_impulse,
        counters: Counters {
            steps: c.steps + normal_work.steps,
            rejected_steps: c.rejected_steps,
            evaluations: c.evaluations + normal_work.evaluations,
        },
        // (Integrated to the end: the slide by the scheme that ran, as the integrated slide's run names it.)
        method: match (closed, scheme) {
            (true, _) => CLOSED_FORM_SLIDE,
            (false, Scheme::Taylor) => TAYLOR_SLIDE,
            (false, _) => SLIDE,
        },
        // (Integrated to the end, the restitution's integrals are the snapshots' differences, as on the integrated
        // slide.)
        restitution: closed.then_some((fast.restitution_impulse * s.impulse, fast.restitution_work * s.energy)),
        note: None,
        fixed_step: None,
    })
}
