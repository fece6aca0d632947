//! The Dop853 adapter: runs between events, re-steps for event location, counts work.

use super::events::{Crossing, Event, MAX_EVENTS, Point, falls, locate};
use super::{IntegrationError, Model, State};
use ode_solvers::dop853::Dop853;
use ode_solvers::{OutputType, System};

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
pub struct RunEnd<const N: usize> {
    /// Scaled time and state where the run stopped.
    pub time: f64,
    pub state: State<N>,
    /// Why it stopped.
    pub ending: Ending,
    /// Every non-terminal crossing located on the way, in time order.
    pub crossings: Vec<Crossing<N>>,
}

/// Integrates a model with Dop853, locating events; optionally records every accepted step.
pub struct Stepper<'m, M, const N: usize> {
    model: &'m M,
    tolerances: Tolerances,
    /// Work so far.
    pub counters: Counters,
    /// Accepted steps (time, state), kept only when a history was asked for.
    pub record: Option<Vec<(f64, State<N>)>>,
}

/// What `solout` saw: the last accepted point and the first bracket of a sign change.
struct Watch<'w, 'e, const N: usize> {
    events: &'w [Event<'e, N>],
    previous: Point<N>,
    /// The events' values at `previous`, so each accepted step evaluates every event function once.
    previous_values: [f64; MAX_EVENTS],
    bracket: Option<(Point<N>, Point<N>)>,
    record: Option<&'w mut Vec<(f64, State<N>)>>,
}

/// The `System` handed to Dop853: the model plus, optionally, a watch for events.
struct Adapter<'a, 'w, 'e, M, const N: usize> {
    model: &'a M,
    watch: Option<&'a mut Watch<'w, 'e, N>>,
}

impl<M: Model<N>, const N: usize> System<f64, State<N>> for Adapter<'_, '_, '_, M, N> {
    fn system(&self, t: f64, y: &State<N>, dy: &mut State<N>) {
        self.model.derivative(t, y, dy);
    }

    fn solout(&mut self, t: f64, y: &State<N>, dy: &State<N>) -> bool {
        let Some(watch) = self.watch.as_deref_mut() else { return false };
        if let Some(record) = watch.record.as_deref_mut() {
            record.push((t, *y));
        }
        let mut values = [0.0; MAX_EVENTS];
        for (value, event) in values.iter_mut().zip(watch.events) {
            *value = event.value(y);
        }
        let crossed = values.iter().zip(&watch.previous_values).take(watch.events.len()).any(|(&v, &p)| falls(p, v));
        let current = (t, *y, *dy);
        if crossed {
            watch.bracket = Some((watch.previous, current));
            return true;
        }
        watch.previous = current;
        watch.previous_values = values;
        false
    }
}

impl<'m, M: Model<N>, const N: usize> Stepper<'m, M, N> {
    /// A stepper for `model`; `record` keeps every accepted step.
    pub fn new(model: &'m M, tolerances: Tolerances, record: bool) -> Self {
        Stepper { model, tolerances, counters: Counters::default(), record: record.then(Vec::new) }
    }

    /// Adds a point (an event, the initial state) to the record, if one is kept. The record is sorted by
    /// [`Stepper::recorded`].
    pub fn note(&mut self, t: f64, y: State<N>) {
        if let Some(record) = self.record.as_mut() {
            record.push((t, y));
        }
    }

    /// The record in time order (accepted steps and noted points), if one is kept.
    pub fn recorded(&mut self) -> Option<&[(f64, State<N>)]> {
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
    pub fn resample(&mut self, times: &[f64]) -> Result<Vec<(f64, State<N>)>, IntegrationError> {
        let Some(points) = self.recorded().map(<[_]>::to_vec) else { return Ok(Vec::new()) };
        let mut samples = Vec::with_capacity(times.len());
        for &t in times {
            let after = points.partition_point(|(time, _)| *time <= t);
            let Some(&(t0, y0)) = points.get(after.saturating_sub(1)) else { continue };
            let from = (t0, y0, self.derivative(t0, &y0));
            samples.push((t, self.step_to(&from, t)?));
        }
        Ok(samples)
    }

    /// The model's derivative at a point (counted as one evaluation).
    pub fn derivative(&mut self, t: f64, y: &State<N>) -> State<N> {
        let mut dy = State::<N>::zeros();
        self.model.derivative(t, y, &mut dy);
        self.counters.evaluations += 1;
        dy
    }

    /// Integrates from `(t, y)` until a terminal event of `events` fires (located) or `t_end` is reached.
    /// Non-terminal events crossed before that are located and returned too.
    pub fn run(
        &mut self,
        t: f64,
        y: State<N>,
        t_end: f64,
        events: &[Event<'_, N>],
    ) -> Result<RunEnd<N>, IntegrationError> {
        let mut start: Point<N> = (t, y, self.derivative(t, &y));
        let mut first_step = 0.0;
        let mut crossings = Vec::new();
        loop {
            let (time, state, bracket, last_step, gave_up) = self.advance(start, t_end, first_step, events)?;
            let Some((left, right)) = bracket else {
                let ending = gave_up.map_or(Ending::TimeLimit, Ending::GaveUp);
                return Ok(RunEnd { time, state, ending, crossings });
            };
            let mut located: Vec<(usize, Crossing<N>)> = Vec::new();
            for (index, event) in events.iter().enumerate() {
                if event.crosses(&left.1, &right.1) {
                    let crossing = match locate(event, index, &left, &right, |t| self.step_to(&left, t)) {
                        Ok(crossing) => crossing,
                        // A stiff stretch where even re-stepping inside one accepted step runs out of steps: the run
                        // ends there, said why, rather than failing the whole simulation.
                        Err(IntegrationError::Solver { reason, .. }) => {
                            let why = format!("the problem became stiff for an explicit method ({reason})");
                            return Ok(RunEnd { time: left.0, state: left.1, ending: Ending::GaveUp(why), crossings });
                        }
                    };
                    located.push((index, crossing));
                }
            }
            located.sort_by(|a, b| a.1.time.total_cmp(&b.1.time));
            let terminal = located.iter().find(|(i, _)| events[*i].terminal).map(|(_, c)| c.clone());
            let cutoff = terminal.as_ref().map_or(f64::INFINITY, |c| c.time);
            let passed: Vec<Crossing<N>> =
                located.into_iter().map(|(_, c)| c).filter(|c| !events[c.event].terminal && c.time <= cutoff).collect();
            for crossing in &passed {
                self.note(crossing.time, crossing.state);
            }
            crossings.extend(passed);
            if let Some(stop) = terminal {
                if let Some(record) = self.record.as_mut() {
                    record.retain(|(t, _)| *t < stop.time);
                    record.push((stop.time, stop.state));
                }
                return Ok(RunEnd { time: stop.time, state: stop.state, ending: Ending::Event(stop.event), crossings });
            }
            start = right;
            first_step = last_step;
        }
    }

    /// One Dop853 run from `start` until a bracket of a sign change or `t_end`: (end time, end state, bracket,
    /// last step size, why the integrator gave up if it did).
    #[allow(clippy::type_complexity)]
    fn advance(
        &mut self,
        start: Point<N>,
        t_end: f64,
        first_step: f64,
        events: &[Event<'_, N>],
    ) -> Result<(f64, State<N>, Option<(Point<N>, Point<N>)>, f64, Option<String>), IntegrationError> {
        let mut record = self.record.take();
        assert!(events.len() <= MAX_EVENTS, "at most {MAX_EVENTS} events per run");
        let mut previous_values = [0.0; MAX_EVENTS];
        for (value, event) in previous_values.iter_mut().zip(events) {
            *value = event.value(&start.1);
        }
        let mut watch = Watch { events, previous: start, previous_values, bracket: None, record: record.as_mut() };
        let (t, y) = (start.0, start.1);
        let adapter = Adapter { model: self.model, watch: Some(&mut watch) };
        let budget = STEP_BUDGET.saturating_sub(self.counters.steps + self.counters.rejected_steps);
        let mut solver = dop853(adapter, self.tolerances, t, y, t_end, first_step, budget);
        let result = solver.integrate();
        let (time, state) = last_point(&solver, t, y);
        let step = time - solver.x_out().iter().rev().nth(1).copied().unwrap_or(t);
        let taken = solver.x_out().len().saturating_sub(1) as u64;
        drop(solver);
        let bracket = watch.bracket;
        self.record = record;
        let gave_up = match result {
            Ok(stats) => {
                self.add(&stats);
                None
            }
            Err(error) => {
                // The solver's own statistics are lost with the error: count the accepted steps it left.
                self.counters.steps += taken;
                self.counters.evaluations += 12 * taken;
                match error {
                    // ode_solvers reports an underflow when its last step lands within rounding of the end.
                    ode_solvers::dop_shared::IntegrationError::StepSizeUnderflow { x }
                        if (t_end - x).abs() <= 1e-12 * t_end.abs().max(1.0) =>
                    {
                        None
                    }
                    ode_solvers::dop_shared::IntegrationError::MaxNumStepReached { .. } => {
                        Some(format!("the budget of {STEP_BUDGET} steps was spent"))
                    }
                    ode_solvers::dop_shared::IntegrationError::StiffnessDetected { .. } => {
                        Some("the problem became stiff for an explicit method".into())
                    }
                    other => Some(other.to_string()),
                }
            }
        };
        Ok((time, state, bracket, step, gave_up))
    }

    /// The solution at `t` reached by one (or, if rejected, a few) Dop853 steps from `from`: the re-step used to
    /// evaluate an event function between accepted steps.
    pub fn step_to(&mut self, from: &(f64, State<N>, State<N>), t: f64) -> Result<State<N>, IntegrationError> {
        let h = t - from.0;
        if h.abs() <= 16.0 * f64::EPSILON * from.0.abs().max(1.0) {
            return Ok(from.1 + from.2 * h);
        }
        let adapter = Adapter { model: self.model, watch: None };
        // A re-step inside one accepted step of a stiff contact may itself need many steps: it may use what is left of
        // the run's budget (at least a thousand).
        let left = STEP_BUDGET.saturating_sub(self.counters.steps + self.counters.rejected_steps).max(1000);
        let mut solver = dop853(adapter, self.tolerances, from.0, from.1, t, h, left);
        let result = solver.integrate();
        let (_, state) = last_point(&solver, from.0, from.1);
        drop(solver);
        let stats = result.map_err(|error| IntegrationError::Solver { time: t, reason: error.to_string() })?;
        self.add(&stats);
        Ok(state)
    }

    fn add(&mut self, stats: &ode_solvers::dop_shared::Stats) {
        self.counters.steps += u64::from(stats.accepted_steps);
        self.counters.rejected_steps += u64::from(stats.rejected_steps);
        self.counters.evaluations += u64::from(stats.num_eval);
    }
}

/// A Dop853 solver from `(t, y)` to `t_end` with sparse output (dense output with dx = 0 never ends),
/// initial step `first_step` (0: let the solver choose) and at most `max_steps` steps.
fn dop853<'a, 'w, 'e, M: Model<N>, const N: usize>(
    adapter: Adapter<'a, 'w, 'e, M, N>,
    tolerances: Tolerances,
    t: f64,
    y: State<N>,
    t_end: f64,
    first_step: f64,
    max_steps: u64,
) -> Dop853<f64, State<N>, Adapter<'a, 'w, 'e, M, N>> {
    let Tolerances { rtol, atol } = tolerances;
    let h_max = t_end - t;
    let h = first_step.min(h_max);
    Dop853::from_param(
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
        u32::try_from(max_steps).unwrap_or(u32::MAX),
        1000,
        OutputType::Sparse,
    )
}

fn last_point<M, const N: usize>(solver: &Dop853<f64, State<N>, M>, t: f64, y: State<N>) -> (f64, State<N>)
where
    M: System<f64, State<N>>,
{
    match (solver.x_out().last(), solver.y_out().last()) {
        (Some(&time), Some(&state)) => (time, state),
        _ => (t, y),
    }
}
