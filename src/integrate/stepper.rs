//! The `ode_solvers` adapter (Dop853, or Dopri5): runs between events, re-steps for event location, counts work.

use super::events::{CrossingOf, EventOf, Point, bracketed, falls, locate};
use super::{IntegrationError, ModelOf, Vector};
use nalgebra::allocator::Allocator;
use nalgebra::{Const, DefaultAllocator, Dim};
use ode_solvers::dop_shared::{IntegrationError as SolverError, Stats};
use ode_solvers::dop853::Dop853;
use ode_solvers::dopri5::Dopri5;
use ode_solvers::{OutputType, System};

/// Why ode_solvers stopped, in this program's words: its own text prints the scaled time with seventeen digits,
/// which the caller gives as messages write numbers where it matters. ("stiff" in the words is what the callers
/// read as a stiff stretch.)
fn in_words(error: &SolverError) -> String {
    match error {
        SolverError::MaxNumStepReached { n_step, .. } => format!("more than {n_step} steps needed"),
        SolverError::StepSizeUnderflow { .. } => "the step size underflowed".into(),
        SolverError::StiffnessDetected { .. } => "stiffness detected".into(),
    }
}

/// Error tolerances of the adaptive integrator, on the scaled state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tolerances {
    /// Relative tolerance.
    pub rtol: f64,
    /// Absolute tolerance.
    pub atol: f64,
}

impl Default for Tolerances {
    fn default() -> Self {
        Tolerances { rtol: 1e-10, atol: 1e-12 }
    }
}

/// Which `ode_solvers` Runge–Kutta pair integrates: both are explicit, adaptive, and driven the same way (same
/// event location by re-stepping, same counters).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Scheme {
    /// Dormand–Prince 8(5,3), 12 stages a step: the simulator's general path.
    #[default]
    Dop853,
    /// Dormand–Prince 5(4), 6 stages a step (first same as last).
    Dopri5,
    /// A Taylor series a step, of the model's own coefficients ([`super::Model::expansion`]), its order and step
    /// from the tolerance as the normal fast path's ([`super::taylor_order`]): events located on the step's
    /// polynomial. A model without coefficients at a state ends the run there ([`Ending::GaveUp`]).
    Taylor,
}

impl Scheme {
    /// The name a report and a benchmark give the path (`[solver] method`).
    pub fn name(self) -> &'static str {
        match self {
            Scheme::Dop853 => "dop853",
            Scheme::Dopri5 => "dopri5",
            Scheme::Taylor => "taylor",
        }
    }

    /// Right-hand-side evaluations per accepted step (for the work of a run the solver's statistics were lost for).
    fn stages(self) -> u64 {
        match self {
            Scheme::Dop853 => 12,
            Scheme::Dopri5 => 6,
            // (Never lost: the Taylor steps are counted as they are taken.)
            Scheme::Taylor => 1,
        }
    }
}

/// Work done by the integrator, summed over every run and re-step.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Counters {
    /// Accepted steps.
    pub steps: u64,
    /// Rejected steps.
    pub rejected_steps: u64,
    /// Right-hand-side (force) evaluations.
    pub evaluations: u64,
}

impl Counters {
    /// Adds a solver run's statistics.
    fn add(&mut self, stats: &Stats) {
        self.steps += u64::from(stats.accepted_steps);
        self.rejected_steps += u64::from(stats.rejected_steps);
        self.evaluations += u64::from(stats.num_eval);
    }

    /// Adds another count's work.
    fn absorb(&mut self, other: Counters) {
        self.steps += other.steps;
        self.rejected_steps += other.rejected_steps;
        self.evaluations += other.evaluations;
    }
}

/// Why a run stopped.
#[derive(Debug, Clone, PartialEq)]
pub enum Ending {
    /// A terminal event fired (its index in the event list), located.
    Event(usize),
    /// The end time was reached.
    TimeLimit,
    /// The integrator gave up (step budget spent, stiffness, step size underflow): the reason.
    GaveUp(String),
}

/// Accepted plus rejected steps one stepper may take over all its runs: a stiff or creeping contact ends with
/// [`Ending::GaveUp`] after about this many steps (a fraction of a second) instead of running for minutes.
pub const STEP_BUDGET: u64 = 300_000;

/// How a run between events ended.
#[derive(Debug, Clone)]
pub struct RunEndOf<D: Dim>
where
    DefaultAllocator: Allocator<D>,
{
    /// Scaled time and state where the run stopped.
    pub time: f64,
    pub state: Vector<D>,
    /// Why it stopped.
    pub ending: Ending,
    /// Every non-terminal crossing located on the way, in time order.
    pub crossings: Vec<CrossingOf<D>>,
}

/// Integrates a model with Dop853 (or Dopri5, [`StepperOf::scheme`]), locating events; optionally records every
/// accepted step. `D` is the state's dimension: `Const<N>` for a model of fixed size ([`Stepper`]), `Dyn` for one
/// sized at run time.
pub struct StepperOf<'m, M, D: Dim>
where
    DefaultAllocator: Allocator<D>,
{
    model: &'m M,
    tolerances: Tolerances,
    scheme: Scheme,
    /// Work so far.
    pub counters: Counters,
    /// Accepted steps (time, state), kept only when a history was asked for.
    pub record: Option<Vec<(f64, Vector<D>)>>,
    /// The events' values at the last accepted point (kept between runs so that a run allocates nothing).
    previous_values: Vec<f64>,
    /// The events' values at the newest point.
    values: Vec<f64>,
    /// Accepted plus rejected steps this stepper may take over all its runs ([`STEP_BUDGET`] unless lowered).
    budget: u64,
    /// Told the time and the accepted steps so far every [`TICK_STEPS`] accepted steps, if given (a world run's
    /// progress on a terminal).
    tick: Option<&'m dyn Fn(f64, u64)>,
    /// [`Scheme::Taylor`]: the last step's coefficients, and the time they expand about (NaN: none yet).
    series: Vec<Vector<D>>,
    series_from: f64,
    /// The events a run's last bracket is a suspected dip of (no sign change at its ends).
    suspected: Vec<usize>,
}

/// Accepted steps between two calls of a stepper's tick.
pub const TICK_STEPS: u64 = 256;

/// The stepper of a model of fixed size.
pub type Stepper<'m, M, const N: usize> = StepperOf<'m, M, Const<N>>;

/// What `solout` saw: the last accepted point and the first bracket of a sign change.
struct Watch<'w, 'e, D: Dim>
where
    DefaultAllocator: Allocator<D>,
{
    events: &'w [EventOf<'e, D>],
    previous: Point<D>,
    /// The events' values at `previous`, so each accepted step evaluates every event function once.
    previous_values: &'w mut Vec<f64>,
    values: &'w mut Vec<f64>,
    bracket: Option<(Point<D>, Point<D>)>,
    /// Whether any function is watched for dips ([`EventOf::dips`]); each watched function's slope at `previous`
    /// (NaN: not read yet; empty when none is watched), and the functions a dip of which is suspected in the
    /// bracket (which may show no sign change at its ends).
    watches_dips: bool,
    previous_slopes: &'w mut Vec<f64>,
    suspected: Vec<usize>,
    /// How a suspected dip is searched between accepted steps, and the work those searches did.
    restepper: Restepper,
    work: Counters,
    record: Option<&'w mut Vec<(f64, Vector<D>)>>,
    /// The stepper's tick, the steps it had taken (accepted and rejected) when this run began, and the steps accepted
    /// in it.
    tick: Option<&'w dyn Fn(f64, u64)>,
    taken_before: u64,
    accepted: u64,
}

/// The `System` handed to the solver: the model plus, optionally, a watch for events.
struct Adapter<'a, 'w, 'e, M, D: Dim>
where
    DefaultAllocator: Allocator<D>,
{
    model: &'a M,
    watch: Option<&'a mut Watch<'w, 'e, D>>,
}

impl<M: ModelOf<D>, D: Dim> System<f64, Vector<D>> for Adapter<'_, '_, '_, M, D>
where
    DefaultAllocator: Allocator<D>,
{
    fn system(&self, t: f64, y: &Vector<D>, dy: &mut Vector<D>) {
        self.model.derivative_of(t, y, dy);
    }

    fn solout(&mut self, t: f64, y: &Vector<D>, dy: &Vector<D>) -> bool {
        let Some(watch) = self.watch.as_deref_mut() else { return false };
        if let Some(record) = watch.record.as_deref_mut() {
            record.push((t, y.clone()));
        }
        watch.accepted += 1;
        // (Counted over the stepper's runs: a run between two events may be only a few steps long.)
        let taken = watch.taken_before + watch.accepted;
        if let Some(tick) = watch.tick
            && taken % TICK_STEPS == 0
        {
            tick(t, taken);
        }
        for (value, event) in watch.values.iter_mut().zip(watch.events) {
            *value = event.value(y);
        }
        let crossed = watch.values.iter().zip(watch.previous_values.iter()).any(|(&v, &p)| falls(p, v));
        // (A step that carries one function through zero may carry another below zero and back: a normal force
        // through zero takes the magnitude cap's room to -|T| at that instant.)
        if watch.watches_dips {
            // Each watched function's slope along the flow, a difference over a share of the step on the tangent (the
            // states ahead of the step's ends, each found once for all the functions).
            let h = t - watch.previous.0;
            let delta = h * SLOPE_SHARE;
            let (mut ahead_of_previous, mut ahead) = (None, None);
            for (i, event) in watch.events.iter().enumerate() {
                let (p, v) = (watch.previous_values[i], watch.values[i]);
                if !(event.dips && p > 0.0 && v > 0.0) {
                    watch.previous_slopes[i] = f64::NAN;
                    continue;
                }
                let before = match watch.previous_slopes[i] {
                    s if s.is_nan() => {
                        let previous = &watch.previous;
                        let state = ahead_of_previous.get_or_insert_with(|| &previous.1 + &previous.2 * delta);
                        (event.value(state) - p) / delta
                    }
                    s => s,
                };
                let after = (event.value(ahead.get_or_insert_with(|| y + dy * delta)) - v) / delta;
                watch.previous_slopes[i] = after;
                // A dip is suspected where either end's tangent reaches zero inside the step, or the two meet below
                // half the smaller end value (they meet `(v - p - after h) / (before - after)` from the start).
                if before < 0.0 && after > 0.0 {
                    let meet = (v - p - after * h) / (before - after);
                    if p + before * h < 0.0 || v - after * h < 0.0 || p + before * meet < 0.5 * p.min(v) {
                        watch.suspected.push(i);
                    }
                }
            }
        }
        if !crossed && !watch.suspected.is_empty() {
            // A step with no sign change: its suspected dips are searched here, and the run goes on unless one is
            // found (a stop would restart the solver, its step-size history lost, for nothing). The earliest minimum
            // below zero ends the bracket; a search that failed leaves the suspects to the driver, which says why.
            let current = (t, y.clone(), dy.clone());
            let suspects = (watch.events, watch.suspected.as_slice());
            match earliest_dip(self.model, watch.restepper, suspects, &watch.previous, &current, &mut watch.work) {
                Ok(Some(below)) => {
                    watch.suspected.clear();
                    watch.bracket = Some((watch.previous.clone(), below));
                    return true;
                }
                Ok(None) => watch.suspected.clear(),
                Err(_) => {}
            }
        }
        if crossed || !watch.suspected.is_empty() {
            watch.bracket = Some((watch.previous.clone(), (t, y.clone(), dy.clone())));
            return true;
        }
        // (In place: a state of run-time size is not reallocated every step.)
        watch.previous.0 = t;
        watch.previous.1.clone_from(y);
        watch.previous.2.clone_from(dy);
        std::mem::swap(watch.previous_values, watch.values);
        false
    }
}

impl<'m, M: ModelOf<D>, D: Dim> StepperOf<'m, M, D>
where
    DefaultAllocator: Allocator<D>,
{
    /// A Dop853 stepper for `model`; `record` keeps every accepted step.
    pub fn new(model: &'m M, tolerances: Tolerances, record: bool) -> Self {
        StepperOf {
            model,
            tolerances,
            scheme: Scheme::Dop853,
            counters: Counters::default(),
            record: record.then(Vec::new),
            previous_values: Vec::new(),
            values: Vec::new(),
            budget: STEP_BUDGET,
            tick: None,
            series: Vec::new(),
            series_from: f64::NAN,
            suspected: Vec::new(),
        }
    }

    /// The same stepper telling `tick` the time and the steps taken every [`TICK_STEPS`] accepted steps.
    pub fn with_tick(self, tick: &'m dyn Fn(f64, u64)) -> Self {
        StepperOf { tick: Some(tick), ..self }
    }

    /// The same stepper with a budget of at most `budget` steps (a world's segment may take what its run has left).
    pub fn with_budget(self, budget: u64) -> Self {
        StepperOf { budget: budget.min(STEP_BUDGET), ..self }
    }

    /// The same stepper integrating with `scheme` (runs and re-steps alike).
    pub fn scheme(self, scheme: Scheme) -> Self {
        StepperOf { scheme, ..self }
    }

    /// Adds a point (an event, the initial state) to the record, if one is kept. The record is sorted by
    /// [`Stepper::recorded`].
    pub fn note(&mut self, t: f64, y: Vector<D>) {
        if let Some(record) = self.record.as_mut() {
            record.push((t, y));
        }
    }

    /// The record in time order (accepted steps and noted points), if one is kept.
    pub fn recorded(&mut self) -> Option<&[(f64, Vector<D>)]> {
        let record = self.record.as_mut()?;
        // Stable sort, then keep the last point noted at each time (a stick–slip switch notes the switched state
        // after the located one).
        record.sort_by(|a, b| a.0.total_cmp(&b.0));
        record.reverse();
        record.dedup_by(|a, b| a.0 == b.0);
        record.reverse();
        Some(record)
    }

    /// The solution at each of `times` (ascending, inside the recorded span), each reached by re-stepping from the
    /// last recorded point at or before it: values on the integrator's own solution, not a lower-order interpolant.
    pub fn resample(&mut self, times: &[f64]) -> Result<Vec<(f64, Vector<D>)>, IntegrationError> {
        let Some(points) = self.recorded().map(<[_]>::to_vec) else { return Ok(Vec::new()) };
        let mut samples = Vec::with_capacity(times.len());
        for &t in times {
            let after = points.partition_point(|(time, _)| *time <= t);
            let Some((t0, y0)) = points.get(after.saturating_sub(1)).cloned() else { continue };
            let dy0 = self.derivative(t0, &y0);
            let from = (t0, y0, dy0);
            samples.push((t, self.step_to(&from, t)?));
        }
        Ok(samples)
    }

    /// The model's derivative at a point (counted as one evaluation).
    pub fn derivative(&mut self, t: f64, y: &Vector<D>) -> Vector<D> {
        let (rows, columns) = y.shape_generic();
        let mut dy = Vector::<D>::zeros_generic(rows, columns);
        self.model.derivative_of(t, y, &mut dy);
        self.counters.evaluations += 1;
        dy
    }

    /// Integrates from `(t, y)` until a terminal event of `events` fires (located) or `t_end` is reached.
    /// Non-terminal events crossed before that are located and returned too.
    pub fn run(
        &mut self,
        t: f64,
        y: Vector<D>,
        t_end: f64,
        events: &[EventOf<'_, D>],
    ) -> Result<RunEndOf<D>, IntegrationError> {
        let dy = self.derivative(t, &y);
        // (A Taylor series kept from an earlier run is not this run's: a switch changes the state at the same time.)
        self.series_from = f64::NAN;
        let mut start: Point<D> = (t, y, dy);
        let mut first_step = 0.0;
        let mut crossings = Vec::new();
        loop {
            let (time, state, bracket, last_step, gave_up) = self.advance(start, t_end, first_step, events)?;
            let Some((left, mut right)) = bracket else {
                let ending = gave_up.map_or(Ending::TimeLimit, Ending::GaveUp);
                return Ok(RunEndOf { time, state, ending, crossings });
            };
            let suspected = std::mem::take(&mut self.suspected);
            if !suspected.is_empty() {
                // Suspected dips in a step with a sign change (or whose search failed in the solver's output call):
                // the earliest minimum below zero is the bracket's end; a step with none (and no sign change) goes on
                // as accepted.
                let restepper = self.restepper();
                match earliest_dip(self.model, restepper, (events, &suspected), &left, &right, &mut self.counters) {
                    Ok(Some(below)) => right = below,
                    Ok(None) if !events.iter().any(|event| event.crosses(&left.1, &right.1)) => {
                        start = right;
                        first_step = last_step;
                        continue;
                    }
                    Ok(None) => {}
                    Err(IntegrationError::Solver { reason, .. }) => return Ok(stiff(left, &reason, crossings)),
                }
            }
            let mut located: Vec<(usize, CrossingOf<D>)> = Vec::new();
            for (index, event) in events.iter().enumerate() {
                if event.crosses(&left.1, &right.1) {
                    let cheap = self.scheme == Scheme::Taylor;
                    let crossing = match locate(event, index, &left, &right, cheap, |t| self.step_to(&left, t)) {
                        Ok(crossing) => crossing,
                        // A stiff stretch where even re-stepping inside one accepted step runs out of steps: the run
                        // ends there, said why, rather than failing the whole simulation.
                        Err(IntegrationError::Solver { reason, .. }) => return Ok(stiff(left, &reason, crossings)),
                    };
                    located.push((index, crossing));
                }
            }
            located.sort_by(|a, b| a.1.time.total_cmp(&b.1.time));
            // Terminal crossings located within the location's resolution of the first are the same instant: the one
            // listed first wins (a phase's own events come before a stick–slip switch: a slide's switch out of its
            // unloaded mode where the contact ends is the separation's).
            let first = located.iter().find(|(i, _)| events[*i].terminal).map(|(_, c)| c.time);
            let terminal = first.and_then(|first| {
                let same = first + 8.0 * f64::EPSILON * first.abs().max(right.0 - left.0);
                located
                    .iter()
                    .filter(|(i, c)| events[*i].terminal && c.time <= same)
                    .min_by_key(|(i, _)| *i)
                    .map(|(_, c)| c.clone())
            });
            // A stick–slip switch that fell from the step's start but is back above zero at its end, where a terminal
            // event between them ends what it judges, is read just inside that event: below zero there, its own
            // crossing comes first.
            let terminal = match terminal {
                Some(stop) => match self.hidden_crossing(events, &left, &right, &stop) {
                    Ok(earlier) => Some(earlier.unwrap_or(stop)),
                    Err(IntegrationError::Solver { reason, .. }) => return Ok(stiff(left, &reason, crossings)),
                },
                None => None,
            };
            // A crossing located within the location's resolution after the terminal one is the same instant: two
            // functions whose zeros coincide (a slide that ends where its slip comes to rest) are each located to a
            // few units in the last place, in either order.
            let cutoff = terminal
                .as_ref()
                .map_or(f64::INFINITY, |c| c.time + 8.0 * f64::EPSILON * c.time.abs().max(right.0 - left.0));
            let passed: Vec<CrossingOf<D>> =
                located.into_iter().map(|(_, c)| c).filter(|c| !events[c.event].terminal && c.time <= cutoff).collect();
            for crossing in &passed {
                self.note(crossing.time, crossing.state.clone());
            }
            crossings.extend(passed);
            if let Some(stop) = terminal {
                if let Some(record) = self.record.as_mut() {
                    record.retain(|(t, _)| *t < stop.time);
                    record.push((stop.time, stop.state.clone()));
                }
                return Ok(RunEndOf {
                    time: stop.time,
                    state: stop.state,
                    ending: Ending::Event(stop.event),
                    crossings,
                });
            }
            start = right;
            first_step = last_step;
        }
    }

    /// The crossing of a terminal function watched for dips (a stick–slip switch) hidden by the terminal event `stop`
    /// located in the step from `left` to `right`: one falling at the step's start, not below zero at its end but
    /// back at or above where it started — what a function that judges a contact does where the contact ends
    /// (a sliding contact has no force to stick with there) — is read a share [`INSIDE`] of the way before `stop`,
    /// and a fall through zero by then is located. (A constant tangential stiffness makes a slide reversed against
    /// the slip stick in the last millionths of the contact, where the cap's rate, ∝ d^(1/2), falls below the spring's
    /// unloading: inside the last step.)
    fn hidden_crossing(
        &mut self,
        events: &[EventOf<'_, D>],
        left: &Point<D>,
        right: &Point<D>,
        stop: &CrossingOf<D>,
    ) -> Result<Option<CrossingOf<D>>, IntegrationError> {
        let span = stop.time - left.0;
        if span <= 0.0 {
            return Ok(None);
        }
        // (The state a share of the step ahead of its start, formed only for a watched switch that might be hidden.)
        let mut ahead = None;
        let hidden: Vec<usize> = (0..events.len())
            .filter(|&i| {
                let event = &events[i];
                if !(event.dips && event.terminal && i != stop.event) {
                    return false;
                }
                let (p, v) = (event.value(&left.1), event.value(&right.1));
                p > 0.0
                    && v >= p
                    && event.value(ahead.get_or_insert_with(|| &left.1 + &left.2 * (span * SLOPE_SHARE))) < p
            })
            .collect();
        if hidden.is_empty() {
            return Ok(None);
        }
        let t = stop.time - INSIDE * span;
        let y = self.step_to(left, t)?;
        let dy = self.derivative(t, &y);
        let inside: Point<D> = (t, y, dy);
        let mut earliest: Option<CrossingOf<D>> = None;
        for i in hidden {
            if events[i].crosses(&left.1, &inside.1) {
                let cheap = self.scheme == Scheme::Taylor;
                let crossing = locate(&events[i], i, left, &inside, cheap, |t| self.step_to(left, t))?;
                if earliest.as_ref().is_none_or(|e| crossing.time < e.time) {
                    earliest = Some(crossing);
                }
            }
        }
        Ok(earliest)
    }

    /// One solver run from `start` until a bracket of a sign change or `t_end`: (end time, end state, bracket,
    /// last step size, why the integrator gave up if it did).
    #[allow(clippy::type_complexity)]
    fn advance(
        &mut self,
        start: Point<D>,
        t_end: f64,
        first_step: f64,
        events: &[EventOf<'_, D>],
    ) -> Result<(f64, Vector<D>, Option<(Point<D>, Point<D>)>, f64, Option<String>), IntegrationError> {
        if self.scheme == Scheme::Taylor {
            return Ok(self.advance_taylor(start, t_end, events));
        }
        let mut record = self.record.take();
        let (mut previous_values, mut values) =
            (std::mem::take(&mut self.previous_values), std::mem::take(&mut self.values));
        previous_values.clear();
        previous_values.extend(events.iter().map(|event| event.value(&start.1)));
        values.clear();
        values.resize(events.len(), 0.0);
        let (t, y) = (start.0, start.1.clone());
        let watches_dips = events.iter().any(|event| event.dips);
        let mut previous_slopes = vec![f64::NAN; if watches_dips { events.len() } else { 0 }];
        let mut watch = Watch {
            events,
            previous: start,
            previous_values: &mut previous_values,
            values: &mut values,
            bracket: None,
            watches_dips,
            previous_slopes: &mut previous_slopes,
            suspected: Vec::new(),
            restepper: self.restepper(),
            work: Counters::default(),
            record: record.as_mut(),
            tick: self.tick,
            taken_before: self.counters.steps + self.counters.rejected_steps,
            accepted: 0,
        };
        let adapter = Adapter { model: self.model, watch: Some(&mut watch) };
        let budget = self.budget.saturating_sub(self.counters.steps + self.counters.rejected_steps);
        let solved = solve(self.scheme, adapter, self.tolerances, t, y.clone(), t_end, first_step, budget);
        let (time, state) = solved.last.unwrap_or((t, y));
        let step = time - solved.before_last.unwrap_or(t);
        let taken = solved.taken;
        let result = solved.result;
        let bracket = watch.bracket;
        self.suspected = std::mem::take(&mut watch.suspected);
        self.counters.absorb(watch.work);
        self.record = record;
        (self.previous_values, self.values) = (previous_values, values);
        let gave_up = match result {
            Ok(stats) => {
                self.counters.add(&stats);
                None
            }
            Err(error) => {
                // The solver's own statistics are lost with the error: count the accepted steps it left.
                self.counters.steps += taken;
                self.counters.evaluations += self.scheme.stages() * taken;
                match error {
                    // ode_solvers reports an underflow when its last step lands within rounding of the end.
                    SolverError::StepSizeUnderflow { x } if (t_end - x).abs() <= 1e-12 * t_end.abs().max(1.0) => None,
                    SolverError::MaxNumStepReached { .. } => {
                        Some(format!("the budget of {} steps was spent", self.budget))
                    }
                    SolverError::StiffnessDetected { .. } => {
                        Some("the problem became stiff for an explicit method".into())
                    }
                    other => Some(in_words(&other)),
                }
            }
        };
        Ok((time, state, bracket, step, gave_up))
    }

    /// The solution at `t` reached by one (or, if rejected, a few) steps of the scheme from `from`: the re-step
    /// used to evaluate an event function between accepted steps.
    pub fn step_to(&mut self, from: &Point<D>, t: f64) -> Result<Vector<D>, IntegrationError> {
        let h = t - from.0;
        if h.abs() <= 16.0 * f64::EPSILON * from.0.abs().max(1.0) {
            return Ok(&from.1 + &from.2 * h);
        }
        if self.scheme == Scheme::Taylor {
            if self.series_from.to_bits() != from.0.to_bits() && !self.expand(&from.1, from.0) {
                return Err(IntegrationError::Solver { time: t, reason: NO_SERIES.into() });
            }
            return Ok(horner(&self.series, h));
        }
        self.restepper().step_to(self.model, from, t, &mut self.counters)
    }

    /// [`Scheme::Taylor`]'s coefficients at `(t, y)` into `series` (counted as a step's worth of evaluations, one
    /// per order); `false` where the model has none.
    fn expand(&mut self, y: &Vector<D>, t: f64) -> bool {
        let order = super::taylor_order(self.tolerances.rtol);
        let (rows, columns) = y.shape_generic();
        self.series.resize_with(order + 1, || Vector::<D>::zeros_generic(rows, columns));
        self.series_from = f64::NAN;
        if !self.model.expansion_of(y, &mut self.series) {
            return false;
        }
        self.series_from = t;
        self.counters.evaluations += order as u64;
        true
    }

    /// [`Scheme::Taylor`]'s run from `start` until a bracket of a sign change or `t_end` (as [`StepperOf::advance`]):
    /// each step's size `h = ρ rtol^(1/(K+1))` with `ρ` the smallest over the components and over the upper half of
    /// the orders `k` of `(w/|c_k|)^(1/k)`, `w = |y| + atol/rtol`, so that the first term left out is about
    /// `rtol |y| + atol`; no step is rejected. Events are tested at the steps' ends, within a step
    /// where one falls (the step ends at the first) and at a function's minimum inside it ([`StepperOf::dip`]).
    #[allow(clippy::type_complexity)]
    fn advance_taylor(
        &mut self,
        start: Point<D>,
        t_end: f64,
        events: &[EventOf<'_, D>],
    ) -> (f64, Vector<D>, Option<(Point<D>, Point<D>)>, f64, Option<String>) {
        let Tolerances { rtol, atol } = self.tolerances;
        let mut previous_values: Vec<f64> = events.iter().map(|event| event.value(&start.1)).collect();
        let mut values = vec![0.0; events.len()];
        // Each function's slope at the step's start (NaN: not known).
        let mut start_slopes = vec![f64::NAN; events.len()];
        let mut previous = start;
        let mut step = 0.0;
        let mut first = true;
        loop {
            let (t, y) = (previous.0, &previous.1);
            if t >= t_end {
                return (t, y.clone(), None, step, None);
            }
            if self.counters.steps + self.counters.rejected_steps >= self.budget {
                return (t, y.clone(), None, step, Some(format!("the budget of {} steps was spent", self.budget)));
            }
            if !self.expand(y, t) {
                return (t, y.clone(), None, step, Some(NO_SERIES.into()));
            }
            let order = self.series.len() - 1;
            let absolute = atol / rtol;
            // The radius from the upper half of the orders (a series may be sparse: at first contact Hertz's
            // `q'' = -q⁹/4` has only every tenth coefficient, and the last two alone can both be zero), from all of
            // them where those are all zero. (The power is monotonic: the smallest ratio over the components, then
            // one power per order.)
            let ratio = |k: usize| {
                let mut least = f64::INFINITY;
                for i in 0..y.len() {
                    least = least.min((y[i].abs() + absolute) / self.series[k][i].abs());
                }
                least.powf(1.0 / k as f64)
            };
            let mut radius = (order.div_ceil(2)..=order).map(ratio).fold(f64::INFINITY, f64::min);
            if radius == f64::INFINITY {
                radius = (1..order.div_ceil(2)).map(ratio).fold(f64::INFINITY, f64::min);
            }
            let mut h = radius * rtol.powf(1.0 / (order + 1) as f64);
            // A function that starts at zero (a stick's room under a limit that is zero at first contact) is seen to
            // leave it before it can turn back through it: a first step short beside the series' reach.
            if first && previous_values.contains(&0.0) {
                h *= LEAVING_ZERO;
            }
            first = false;
            let mut h = h.min(t_end - t);
            if h.is_nan() || h <= 0.0 || t + h == t {
                return (t, y.clone(), None, step, Some("the step size underflowed".into()));
            }
            let mut next = self.read_at(h, events, &mut values);
            // (A dip counts where it is deeper than the step's error in the functions' sizes at its ends, rtol
            // times them, and their rounding: a stick's room, a rounding's share of the limit at its start and
            // touching zero where the stick barely holds, is a difference of two sizes, each known to rtol.)
            let shallowest = ROUNDING_SHARE.max(rtol)
                * previous_values.iter().chain(&values).fold(0.0_f64, |most, v| most.max(v.abs()));
            // A step that carries a function through zero ends where the first of them falls (located on the step's
            // polynomial): the others are read within the stretch the first event leaves meaningful (beyond a
            // separation a sliding contact's switch function reads zero, which is no fall inside the contact).
            if values.iter().zip(&previous_values).any(|(&v, &p)| falls(p, v)) {
                let (mut earliest, mut first) = (h, usize::MAX);
                for (i, event) in events.iter().enumerate() {
                    if falls(previous_values[i], values[i]) {
                        let resolution = |t: f64| 4.0 * f64::EPSILON * t.abs().max(h);
                        let at = |t: f64| Ok(horner(&self.series, t));
                        if let Ok(crossing) =
                            bracketed(event, i, (0.0, previous_values[i]), (h, values[i], next.clone()), resolution, at)
                            && crossing.time <= earliest
                        {
                            (earliest, first) = (crossing.time, i);
                        }
                    }
                }
                if earliest < h {
                    h = earliest;
                    next = self.read_at(h, events, &mut values);
                }
                // Another function that is not clearly positive where the step now ends (one that vanishes with the
                // first: a sliding contact's switch functions, in regularised time, with the penetration at its
                // separation) may have dipped below zero before, and risen back, inside the step, its slope at the
                // ends no guide: its slope is read at SCAN points, and each stretch where it turns from falling to
                // rising is read at its minimum.
                let mut first_dip = h;
                for (i, event) in events.iter().enumerate() {
                    let start = previous_values[i];
                    if i == first || !(start > 0.0 && values[i] <= rtol * start) {
                        continue;
                    }
                    if let Some(below) = self.scanned_dip(event, h, first_dip, start, shallowest) {
                        first_dip = first_dip.min(below);
                    }
                }
                if first_dip < h {
                    h = first_dip;
                    next = self.read_at(h, events, &mut values);
                }
            }
            // A function that falls through zero and rises back inside the step (a stick of a fraction of a step
            // between two slides) is positive at both ends: its slope, falling at the start and rising at the end,
            // shows the minimum between them, where the function is read.
            // (The states a slope is differenced from, each found once for all the functions.)
            let delta = h * SLOPE_SHARE;
            let (mut ahead, mut behind) = (None, None);
            for (i, event) in events.iter().enumerate() {
                if !(previous_values[i] > 0.0 && values[i] > 0.0) {
                    start_slopes[i] = f64::NAN;
                    continue;
                }
                if start_slopes[i].is_nan() {
                    let ahead = ahead.get_or_insert_with(|| horner(&self.series, delta));
                    start_slopes[i] = (event.value(ahead) - previous_values[i]) / delta;
                }
                let behind = behind.get_or_insert_with(|| horner(&self.series, h - delta));
                let end_slope = (values[i] - event.value(behind)) / delta;
                let falling = start_slopes[i] < 0.0;
                start_slopes[i] = end_slope;
                let below = if falling && end_slope > 0.0 {
                    self.dip(event, (0.0, h), (previous_values[i].max(values[i]), shallowest), delta)
                } else if event.dips && previous_values[i] < NEAR_ZERO * values[i] {
                    // A watched function that starts near zero (a step past a switch, whose first step is short)
                    // and ends well above it may have risen, turned back and dipped below zero inside the step, its
                    // slopes at the ends no guide: read at SCAN points, as in a step that ends at a fall.
                    self.scanned_dip(event, h, h, previous_values[i], shallowest)
                } else {
                    None
                };
                if let Some(below) = below {
                    h = below;
                    next = self.read_at(h, events, &mut values);
                    break;
                }
            }
            step = h;
            let next_time = if t_end - t <= h { t_end } else { t + h };
            let slope = horner_slope(&self.series, h);
            self.counters.steps += 1;
            if let Some(record) = self.record.as_mut() {
                record.push((next_time, next.clone()));
            }
            let taken = self.counters.steps + self.counters.rejected_steps;
            if let Some(tick) = self.tick
                && taken.is_multiple_of(TICK_STEPS)
            {
                tick(next_time, taken);
            }
            let point = (next_time, next, slope);
            if values.iter().zip(&previous_values).any(|(&v, &p)| falls(p, v)) {
                return (point.0, point.1.clone(), Some((previous, point)), step, None);
            }
            previous = point;
            std::mem::swap(&mut previous_values, &mut values);
        }
    }

    /// The state on the current step's polynomial `h` past its start, with each event function's value there written
    /// into `values`.
    fn read_at(&self, h: f64, events: &[EventOf<'_, D>], values: &mut [f64]) -> Vector<D> {
        let next = horner(&self.series, h);
        for (value, event) in values.iter_mut().zip(events) {
            *value = event.value(&next);
        }
        next
    }

    /// Where on the current step's polynomial, inside `(a, b)` (offsets from the step's start), where `event`'s
    /// function is positive at both ends and its slope falls at the start and rises at the end, the function is
    /// below zero by more than the step's accuracy (rtol times `scale`, the function's size over the step, and at
    /// least `shallowest`, the step's error in the functions' sizes: less is the rounding of a function that starts
    /// at zero, at a switch, or a dip the step does not resolve), its slope a difference over `delta` ([`lowest`]);
    /// `None` where the minimum is not.
    fn dip(
        &self,
        event: &EventOf<'_, D>,
        (a, b): (f64, f64),
        (scale, shallowest): (f64, f64),
        delta: f64,
    ) -> Option<f64> {
        let g = |t: f64| event.value(&horner(&self.series, t));
        let read = |t: f64| {
            let at = g(t);
            Ok::<_, ()>((at, (g(t + delta) - at) / delta))
        };
        let depth = -(self.tolerances.rtol * scale).max(shallowest);
        lowest(read, (a, b - delta), depth, MINIMUM_RESOLUTION * (b - a)).ok().flatten()
    }

    /// The first dip below zero of `event`'s function on the current step's polynomial, from its start up to `before`
    /// (`h` the step): its slope read at SCAN points, and each stretch where it turns from falling to rising read at
    /// its minimum ([`StepperOf::dip`]); `start` is the function's value at the step's start, a floor of its size over
    /// the step (the measure of a dip's depth: at a mode's start a switch function is within rounding of zero).
    fn scanned_dip(&self, event: &EventOf<'_, D>, h: f64, before: f64, start: f64, shallowest: f64) -> Option<f64> {
        let delta = h * SLOPE_SHARE;
        let g = |t: f64| event.value(&horner(&self.series, t));
        let times: [f64; SCAN + 1] = std::array::from_fn(|j| j as f64 * (h - delta) / SCAN as f64);
        let read = times.map(|t| {
            let at = g(t);
            (at, (g(t + delta) - at) / delta)
        });
        let scale = read.iter().fold(start, |most, (at, _)| most.max(at.abs()));
        for j in 1..=SCAN {
            if times[j - 1] >= before {
                break;
            }
            // (A turn that is no dip below zero leaves the later ones to be read.)
            if read[j - 1].1 < 0.0
                && read[j].1 > 0.0
                && let Some(below) = self.dip(event, (times[j - 1], times[j] + delta), (scale, shallowest), delta)
            {
                return Some(below);
            }
        }
        None
    }

    /// How this stepper re-steps inside an accepted step: its scheme and tolerances, and what is left of its budget
    /// (at least a thousand steps: a re-step inside one accepted step of a stiff contact may itself need many).
    fn restepper(&self) -> Restepper {
        let left = self.budget.saturating_sub(self.counters.steps + self.counters.rejected_steps);
        Restepper { scheme: self.scheme, tolerances: self.tolerances, budget: left.max(1000) }
    }
}

/// Why a [`Scheme::Taylor`] run stopped where its model has no series (a caller may recognise it).
pub const NO_SERIES: &str = "the model has no Taylor series here";

/// The share of its reach a Taylor step takes where an event function is zero at its start (see
/// [`StepperOf::advance_taylor`]).
const LEAVING_ZERO: f64 = 1.0 / 64.0;

/// The share of the event functions' sizes a dip must reach below zero to count, at least (see
/// [`StepperOf::dip`]).
const ROUNDING_SHARE: f64 = 64.0 * f64::EPSILON;

/// The share of its value at a step's end below which a watched function's value at the step's start counts as near
/// zero: the step is then read for a dip inside it (see [`StepperOf::advance_taylor`]).
const NEAR_ZERO: f64 = 1.0 / 16.0;

/// The points of a Taylor step where a function is read for a dip inside it, in a step that ends at a fall (or whose
/// watched function starts near zero).
const SCAN: usize = 16;

/// The share of a step (Taylor's, or an accepted Dop853 step's) an event function's slope is differenced over (see
/// [`StepperOf::dip`], [`dip_by_restepping`]).
const SLOPE_SHARE: f64 = 1.0 / 16_777_216.0;

/// The share of a step before a terminal event at which [`StepperOf::hidden_crossing`] reads a switch from inside.
const INSIDE: f64 = 1e-6;

/// The share of a step within which [`StepperOf::dip`] and [`dip_by_restepping`] locate a function's minimum: a
/// minimum `ε h` off reads the function `g'' (ε h)² / 2` above it.
const MINIMUM_RESOLUTION: f64 = 1e-7;

/// Where inside `(a, b)` a function read with its slope by `read` (positive at both ends, its slope falling at `a`
/// and rising at `b`) is below `depth` (negative): its minimum sought by the Illinois variant of regula falsi on the
/// slope, stopping at the first trial that deep; `None` where the minimum, located to `resolution`, is not (or the
/// slopes at the ends do not bracket one).
fn lowest<E>(
    mut read: impl FnMut(f64) -> Result<(f64, f64), E>,
    (a, b): (f64, f64),
    depth: f64,
    resolution: f64,
) -> Result<Option<f64>, E> {
    let (mut lo, mut hi) = (a, b);
    let (mut s_lo, mut s_hi) = (read(lo)?.1, read(hi)?.1);
    if !(s_lo < 0.0 && s_hi > 0.0) {
        return Ok(None);
    }
    let mut side = 0i8;
    for _ in 0..60 {
        let trial = (lo - s_lo * (hi - lo) / (s_hi - s_lo)).clamp(lo + 0.01 * (hi - lo), hi - 0.01 * (hi - lo));
        let (at, s) = read(trial)?;
        if at < depth {
            return Ok(Some(trial));
        }
        if s < 0.0 {
            if side < 0 {
                s_hi *= 0.5;
            }
            (lo, s_lo, side) = (trial, s, -1);
        } else {
            if side > 0 {
                s_lo *= 0.5;
            }
            (hi, s_hi, side) = (trial, s, 1);
        }
        if hi - lo <= resolution {
            break;
        }
    }
    Ok(None)
}

/// A run that ends at `left` because a re-step inside one accepted step ran out of steps (`reason`): a stiff stretch,
/// said why, rather than a failure of the whole simulation.
fn stiff<D: Dim>(left: Point<D>, reason: &str, crossings: Vec<CrossingOf<D>>) -> RunEndOf<D>
where
    DefaultAllocator: Allocator<D>,
{
    let why = format!("the problem became stiff for an explicit method ({reason})");
    RunEndOf { time: left.0, state: left.1, ending: Ending::GaveUp(why), crossings }
}

/// How to re-step a model inside an accepted step: the scheme, the tolerances, and the steps a re-step may take.
#[derive(Debug, Clone, Copy)]
struct Restepper {
    scheme: Scheme,
    tolerances: Tolerances,
    budget: u64,
}

impl Restepper {
    /// The solution at `t` reached by one (or, if rejected, a few) steps of the scheme from `from` (on its tangent
    /// within rounding of it), the work added to `work`.
    fn step_to<M: ModelOf<D>, D: Dim>(
        self,
        model: &M,
        from: &Point<D>,
        t: f64,
        work: &mut Counters,
    ) -> Result<Vector<D>, IntegrationError>
    where
        DefaultAllocator: Allocator<D>,
    {
        let h = t - from.0;
        if h.abs() <= 16.0 * f64::EPSILON * from.0.abs().max(1.0) {
            return Ok(&from.1 + &from.2 * h);
        }
        let adapter = Adapter { model, watch: None };
        let solved = solve(self.scheme, adapter, self.tolerances, from.0, from.1.clone(), t, h, self.budget);
        let stats = solved.result.map_err(|error| IntegrationError::Solver { time: t, reason: in_words(&error) })?;
        work.add(&stats);
        Ok(solved.last.map_or_else(|| from.1.clone(), |(_, state)| state))
    }
}

/// The earliest dip below zero of the functions `suspected` (indices into `events`) over a Dop853 (or Dopri5) step
/// from `left` to `right`, each searched by [`dip_by_restepping`] up to the earliest found so far; `None` where none
/// dips.
fn earliest_dip<M: ModelOf<D>, D: Dim>(
    model: &M,
    restepper: Restepper,
    (events, suspected): (&[EventOf<'_, D>], &[usize]),
    left: &Point<D>,
    right: &Point<D>,
    work: &mut Counters,
) -> Result<Option<Point<D>>, IntegrationError>
where
    DefaultAllocator: Allocator<D>,
{
    let largest = events
        .iter()
        .flat_map(|event| [event.value(&left.1), event.value(&right.1)])
        .fold(0.0_f64, |most, v| most.max(v.abs()));
    let mut earliest: Option<Point<D>> = None;
    for &index in suspected {
        let end = earliest.as_ref().unwrap_or(right);
        if let Some(below) = dip_by_restepping(model, restepper, &events[index], left, end, largest, work)? {
            earliest = Some(below);
        }
    }
    Ok(earliest)
}

/// A Dop853 (or Dopri5) step from `left` to `right` over which `event`'s function is positive at both ends, its slope
/// falling at the start and rising at the end: the point of its minimum if that is below zero by more than the step's
/// accuracy (rtol times its larger end value, and at least rtol, or 64 rounding units, times `largest`, the largest
/// event value at the step's ends: as [`StepperOf::dip`]), each trial a re-step from `left` and the slope a difference
/// on the tangent there ([`lowest`]); `None` where the minimum is not. The work is added to `work`.
fn dip_by_restepping<M: ModelOf<D>, D: Dim>(
    model: &M,
    restepper: Restepper,
    event: &EventOf<'_, D>,
    left: &Point<D>,
    right: &Point<D>,
    largest: f64,
    work: &mut Counters,
) -> Result<Option<Point<D>>, IntegrationError>
where
    DefaultAllocator: Allocator<D>,
{
    let tolerances = restepper.tolerances;
    let h = right.0 - left.0;
    let delta = h * SLOPE_SHARE;
    let (p, v) = (event.value(&left.1), event.value(&right.1));
    let depth = -(tolerances.rtol * p.max(v)).max(ROUNDING_SHARE.max(tolerances.rtol) * largest);
    let mut point_at = |t: f64| -> Result<Point<D>, IntegrationError> {
        if t == left.0 {
            return Ok(left.clone());
        }
        if t == right.0 {
            return Ok(right.clone());
        }
        let y = restepper.step_to(model, left, t, work)?;
        work.evaluations += 1;
        let (rows, columns) = y.shape_generic();
        let mut dy = Vector::<D>::zeros_generic(rows, columns);
        model.derivative_of(t, &y, &mut dy);
        Ok((t, y, dy))
    };
    let mut read = |t: f64| {
        let point = point_at(t)?;
        let at = event.value(&point.1);
        let slope = (event.value(&(&point.1 + &point.2 * delta)) - at) / delta;
        Ok::<_, IntegrationError>((at, slope))
    };
    let Some(t) = lowest(&mut read, (left.0, right.0), depth, MINIMUM_RESOLUTION * h)? else { return Ok(None) };
    point_at(t).map(Some)
}

/// The polynomial `Σ series[k] h^k` (Horner).
fn horner<D: Dim>(series: &[Vector<D>], h: f64) -> Vector<D>
where
    DefaultAllocator: Allocator<D>,
{
    let (last, rest) = series.split_last().expect("a series has a constant term");
    let mut value = last.clone();
    for c in rest.iter().rev() {
        value *= h;
        value += c;
    }
    value
}

/// The derivative of [`horner`]'s polynomial at `h`.
fn horner_slope<D: Dim>(series: &[Vector<D>], h: f64) -> Vector<D>
where
    DefaultAllocator: Allocator<D>,
{
    let order = series.len() - 1;
    let mut slope = &series[order] * order as f64;
    for k in (1..order).rev() {
        slope *= h;
        slope += &series[k] * k as f64;
    }
    slope
}

/// What one solver run left: its statistics (or why it failed), its last two points, and the steps it took.
struct Solved<D: Dim>
where
    DefaultAllocator: Allocator<D>,
{
    result: Result<Stats, SolverError>,
    /// The last point of the run (`None`: it took no step).
    last: Option<(f64, Vector<D>)>,
    /// The time of the point before it.
    before_last: Option<f64>,
    /// Accepted steps taken.
    taken: u64,
}

impl<D: Dim> Solved<D>
where
    DefaultAllocator: Allocator<D>,
{
    fn new(result: Result<Stats, SolverError>, times: &[f64], states: &[Vector<D>]) -> Solved<D> {
        Solved {
            result,
            last: times.last().copied().zip(states.last().cloned()),
            before_last: times.iter().rev().nth(1).copied(),
            taken: times.len().saturating_sub(1) as u64,
        }
    }
}

/// Runs `scheme` from `(t, y)` to `t_end` with sparse output (dense output with dx = 0 never ends), initial step
/// `first_step` (0: let the solver choose), at most `max_steps` steps, and each pair's standard step-size control
/// (Hairer's: safety 0.9; Dop853 without step-size memory, factors 0.333 to 6; Dopri5 with beta 0.04, factors 0.2
/// to 10). The adapter (and what it borrows) is released on return.
#[allow(clippy::too_many_arguments)]
fn solve<M: ModelOf<D>, D: Dim>(
    scheme: Scheme,
    adapter: Adapter<'_, '_, '_, M, D>,
    tolerances: Tolerances,
    t: f64,
    y: Vector<D>,
    t_end: f64,
    first_step: f64,
    max_steps: u64,
) -> Solved<D>
where
    DefaultAllocator: Allocator<D>,
{
    let Tolerances { rtol, atol } = tolerances;
    let h_max = t_end - t;
    let h = first_step.min(h_max);
    let n_max = u32::try_from(max_steps).unwrap_or(u32::MAX);
    let sparse = OutputType::Sparse;
    match scheme {
        Scheme::Dop853 => {
            // Dop853's own stiffness test is off (it would run every u32::MAX steps): a stretch that holds the method
            // to short steps but ends (a sliding spring turning after its slip at the contact's edges) is integrated
            // through, within the step budget, rather than given up; the budget bounds the rest.
            let mut solver = Dop853::from_param(
                adapter,
                t,
                t_end,
                0.0,
                y,
                rtol,
                atol,
                0.9,
                0.0,
                0.333,
                6.0,
                h_max,
                h,
                n_max,
                u32::MAX,
                sparse,
            );
            let result = solver.integrate();
            Solved::new(result, solver.x_out(), solver.y_out())
        }
        Scheme::Dopri5 => {
            let mut solver = Dopri5::from_param(
                adapter, t, t_end, 0.0, y, rtol, atol, 0.9, 0.04, 0.2, 10.0, h_max, h, n_max, 1000, sparse,
            );
            let result = solver.integrate();
            Solved::new(result, solver.x_out(), solver.y_out())
        }
        // (The Taylor scheme takes its own steps: `advance` and `step_to` never hand it to a solver.)
        Scheme::Taylor => unreachable!("the Taylor scheme is not an ode_solvers pair"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrate::{Direction, Event, Model, State};

    /// The harmonic oscillator y'' = -y from y = 0, y' = 1: y = sin t.
    struct Oscillator;

    impl Model<2> for Oscillator {
        fn derivative(&self, _t: f64, y: &State<2>, dy: &mut State<2>) {
            dy[0] = y[1];
            dy[1] = -y[0];
        }
    }

    /// Both schemes locate the first maximum (y' = 0 at pi/2) and the zero that follows (y = 0 at pi) on their own
    /// solution, to the tolerance; Dopri5, of lower order, takes more steps for it.
    #[test]
    fn both_schemes_locate_events_on_their_own_solution() {
        let rate = |y: &State<2>| y[1];
        let position = |y: &State<2>| y[0];
        let mut work = Vec::new();
        for scheme in [Scheme::Dop853, Scheme::Dopri5] {
            let tolerances = Tolerances { rtol: 1e-11, atol: 1e-13 };
            let mut stepper = Stepper::new(&Oscillator, tolerances, false).scheme(scheme);
            let peak = Event { function: &rate, direction: Direction::Falling, terminal: true, dips: false };
            let start = State::<2>::new(0.0, 1.0);
            let top = stepper.run(0.0, start, 10.0, &[peak]).unwrap();
            assert_eq!(top.ending, Ending::Event(0), "{scheme:?}");
            assert!((top.time - std::f64::consts::FRAC_PI_2).abs() < 1e-9, "{scheme:?}: {}", top.time);
            assert!((top.state[0] - 1.0).abs() < 1e-9 && top.state[1].abs() < 1e-12, "{scheme:?}");
            let zero = Event { function: &position, direction: Direction::Falling, terminal: true, dips: false };
            let end = stepper.run(top.time, top.state, 10.0, &[zero]).unwrap();
            assert!((end.time - std::f64::consts::PI).abs() < 1e-9, "{scheme:?}: {}", end.time);
            assert!((end.state[1] + 1.0).abs() < 1e-9, "{scheme:?}");
            assert!(stepper.counters.steps > 0 && stepper.counters.evaluations > 0);
            work.push(stepper.counters.steps);
        }
        assert!(work[1] > work[0], "Dopri5 takes more steps than Dop853 at the same tolerance: {work:?}");
    }
}
