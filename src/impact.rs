//! One impact through its phases: flight (closed form) → compression → restitution → separation, over whichever
//! model the scene needs (the 1-D normal contact, or two bodies in 3-D), producing the [`Report`].
//!
//! The driver knows the phases and their events, not the physics: maximum compression is where the penetration
//! rate falls through zero, separation where the penetration (or the continued force) does, the force peak where
//! the force rate does; a frictional contact adds the switches between sticking and sliding. Every event is located
//! on the integrator's solution.

use crate::dynamics::ContactModel;
use crate::dynamics::normal::NormalContact;
use crate::dynamics::pair::PairContact;
use crate::dynamics::rigid::RigidContact;
use crate::dynamics::slide::{SLIDE, SlideContact, TAYLOR_SLIDE};
use crate::dynamics::wall::WallContact;
use crate::fast::Quantities;
use crate::fixed_step;
use crate::history::{History, Recording};
use crate::idealisation::{SPEED_STEP, SpeedTrial};
use crate::integrate::{
    Counters, Crossing, Direction, Ending, Event, IntegrationError, NO_SERIES, Scheme, State, Stepper,
};
use crate::outcome::{FixedStepOutcome, Outcome, SETTLED, TIME_LIMIT, stiffness_causes};
use crate::report::accuracy::ReferenceDetail;
use crate::report::{Report, Sections};
use crate::scene::SetupError;
use crate::scene::{DampingSpec, Method, Scene};
use crate::setup::{Motion, Setup};
use std::time::Instant;

/// A run's products: the report, and the contact history when one was asked for.
#[derive(Debug, Clone)]
pub struct Simulation {
    pub report: Report,
    pub history: Option<History>,
}

/// Why a simulation could not be completed.
#[derive(Debug, thiserror::Error)]
pub enum SimulationError {
    #[error("scene key `{}`: {}", .0.key, .0.message)]
    Setup(SetupError),
    #[error(transparent)]
    Integration(#[from] IntegrationError),
    #[error("the compression phase did not end: {0}")]
    Compression(String),
}

use crate::dynamics::contact::MAX_SWITCHES;

/// What a run computes beyond the impact itself.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Options {
    /// Whether (and how) to keep the contact history.
    pub recording: Recording,
    /// How much of the exact reference to compute.
    pub reference: ReferenceDetail,
    /// What the fast path computes besides the motion and the impulses (a sweep row leaves out what none of its
    /// columns shows). What it leaves out is NaN in the outcome and the report: a run's own report asks for all.
    /// The general path computes everything whatever this says.
    pub quantities: Quantities,
    /// Whether to judge the idealisation (the report's `idealisation`): two more runs of the contact, at 0.9 and 1.1
    /// times the speed, for `constant_e`. Off, every verdict is null (a sweep's row that writes no verdict column, a
    /// calibration's step).
    pub idealisation: bool,
    /// Which parts of the report to fill (all by default; a sweep's row fills what its columns read).
    pub sections: Sections,
}

/// Simulates the scene's impact with the full report; `recording` says whether (and how) to keep the contact
/// history.
pub fn simulate(scene: &Scene, recording: Recording) -> Result<Simulation, SimulationError> {
    simulate_with(
        scene,
        Options {
            recording,
            reference: ReferenceDetail::Full,
            quantities: Quantities::ALL,
            idealisation: true,
            sections: Sections::ALL,
        },
    )
}

/// Instants per figure curve: enough for a smooth line at the figure's width.
pub const FIGURE_SAMPLES: usize = 600;

/// The history a run's figures are drawn from: the simulation's own when it is a uniform one of at least
/// [`FIGURE_SAMPLES`] instants, else a run of the scene recording that many (`None` only if that run recorded none).
pub fn figure_history<'a>(
    scene: &Scene,
    simulation: &'a Simulation,
) -> Result<Option<std::borrow::Cow<'a, History>>, SimulationError> {
    Ok(match &simulation.history {
        Some(history) if history.samples.len() >= FIGURE_SAMPLES => Some(std::borrow::Cow::Borrowed(history)),
        _ => simulate(scene, Recording::Uniform(FIGURE_SAMPLES))?.history.map(std::borrow::Cow::Owned),
    })
}

/// Simulates the scene's impact, computing what `options` ask for.
pub fn simulate_with(scene: &Scene, options: Options) -> Result<Simulation, SimulationError> {
    let clock = Instant::now();
    let setup = Setup::new(scene).map_err(SimulationError::Setup)?;
    simulate_prepared(scene, &setup, options, Some(clock))
}

/// Simulates the impact of a scene whose [`Setup`] is already resolved (a sweep's checked point); `clock` started
/// when the run did, for the report's wall time (`None`: not measured, NaN in the report — a sweep's row, which
/// has no column for it).
pub fn simulate_prepared(
    scene: &Scene,
    setup: &Setup,
    options: Options,
    clock: Option<Instant>,
) -> Result<Simulation, SimulationError> {
    let (outcome, history) = through_phases(scene, setup, options.recording, options.quantities)?;
    // (The wall time is this impact's: the trial's two runs come after it.)
    let wall_time = clock.map_or(f64::NAN, |clock| clock.elapsed().as_secs_f64());
    Ok(Simulation { report: report_of(scene, setup, &outcome, options, wall_time), history })
}

/// [`simulate_prepared`] written into `report` (a sweep worker's, kept from row to row): the row takes its cells from
/// the report where it was built, rather than moving 2.9 kB of it out of a function or two (a fifth of an e-alone
/// row's time went to such copies). No wall time is measured (NaN in the report) and no history is kept, whatever
/// `options` say. On an error `report` holds nothing of this run.
pub fn simulate_prepared_into(
    scene: &Scene,
    setup: &Setup,
    options: Options,
    report: &mut Report,
) -> Result<(), SimulationError> {
    // (The outcome is read where it lies in the result, not moved out of it: 1 kB.)
    let phases = through_phases(scene, setup, Recording::Off, options.quantities);
    let outcome = match &phases {
        Ok((outcome, _)) => outcome,
        Err(_) => return phases.map(|_| ()),
    };
    let trial = options.idealisation.then(|| speed_trial(scene, setup));
    crate::report::build_into(report, scene, setup, outcome, options.reference, f64::NAN, trial, options.sections);
    Ok(())
}

/// The report of an impact's outcome, with the trial for the verdicts if `options` ask for them.
fn report_of(scene: &Scene, setup: &Setup, outcome: &Outcome, options: Options, wall_time: f64) -> Report {
    let trial = options.idealisation.then(|| speed_trial(scene, setup));
    crate::report::build(scene, setup, outcome, options.reference, wall_time, trial, options.sections)
}

/// The e of the same contact with every velocity and spin scaled by 1 ∓ [`SPEED_STEP`] (the incidence and the
/// slip's proportions kept), on the path the scene takes (the fast path where it covers the scene), for the
/// `constant_e` verdict. The law keeps its damping parameter: a nominal e was mapped at the scene's speed, and
/// re-mapping it at the new one would hold e constant by construction. The runs give outcomes, not reports, so they
/// never ask for a trial of their own.
fn speed_trial(scene: &Scene, setup: &Setup) -> SpeedTrial {
    let at = |factor: f64| {
        let mut scaled = scene.clone();
        for body in &mut scaled.bodies {
            body.velocity *= factor;
            body.angular_velocity *= factor;
        }
        if let DampingSpec::Restitution(_) = scaled.contact.damping {
            scaled.contact.damping = DampingSpec::Parameter(setup.law.damping);
        }
        let setup = Setup::new(&scaled).ok()?;
        let (outcome, _) = through_phases(&scaled, &setup, Recording::Off, Quantities::MOTION).ok()?;
        outcome.separated.then(|| -outcome.end.rate / setup.approach_speed)
    };
    SpeedTrial { slower: at(1.0 - SPEED_STEP), faster: at(1.0 + SPEED_STEP) }
}

/// The impact's [`Outcome`] alone, on the path [`simulate_prepared`] takes, without a history or a report: what
/// `impact bench` times.
pub fn outcome(scene: &Scene, setup: &Setup) -> Result<Outcome, SimulationError> {
    through_phases(scene, setup, Recording::Off, Quantities::ALL).map(|(outcome, _)| outcome)
}

/// The impact through its phases on the path the scene's `[solver] method` chooses, and its history if asked for.
fn through_phases(
    scene: &Scene,
    setup: &Setup,
    recording: Recording,
    quantities: Quantities,
) -> Result<(Outcome, Option<History>), SimulationError> {
    let method = scene.solver.method;
    if let Some(scheme) = fixed_scheme(method) {
        return fixed_step_outcome(scheme, scene, setup, recording);
    }
    let covered = setup.motion == Motion::Normal && crate::fast::covers(&setup.law);
    // A frictional sphere on a wall whose laws are smooth in regularised time: its tangential motion stays on one
    // line (dynamics/slide.rs), and `auto` takes the slide by Taylor series where its laws are polynomials in the
    // slide's variables (dynamics/slide/series.rs), the slide by Dop853 otherwise.
    let wall_slide = || {
        (setup.motion == Motion::Full && smooth_in_regularised_time(&setup.law))
            .then(|| SlideContact::new(&scene.bodies, setup, scene.contact.separation))
            .flatten()
    };
    // (Made where it is needed: a wall that ends in the closed form never makes it; asked for by name, once, here.)
    let taylor_slide = || {
        (method == Method::Taylor || (method == Method::Auto && recording == Recording::Off))
            .then(wall_slide)
            .flatten()
            .filter(SlideContact::has_series)
    };
    let named_taylor_slide = (method == Method::Taylor && !covered).then(taylor_slide).flatten();
    if method == Method::Taylor && !covered && named_taylor_slide.is_none() {
        return Err(SimulationError::Setup(SetupError {
            key: "solver.method".into(),
            message: if setup.motion != Motion::Normal {
                "the taylor path integrates the normal contact, or a frictional sphere on a flat wall whose laws are \
                 polynomials in its regularised variables (hertz or the hunt-crossley family at exponent 1 or 1.5, \
                 kelvin-voigt, tsuji; a constant or Mindlin tangential spring without tangential damping or \
                 rescaled unloading): this impact needs the 3-D model; use \"auto\" \
                 or \"dop853\""
                    .into()
            } else {
                format!(
                    "the taylor path does not cover the `{}` law (its force is not smoothed by the regularisation); \
                     use \"auto\" or \"dop853\"",
                    setup.law.kind.name()
                )
            },
        }));
    }
    let dop853_slide = match method {
        Method::Dop853Slide => Some(wall_slide().ok_or_else(|| {
            SimulationError::Setup(SetupError {
                key: "solver.method".into(),
                message: "the dop853-slide path integrates a frictional sphere meeting a flat wall head-on or \
                          obliquely (not a graze) under a law with neither memory nor kinks: this impact needs \
                          another path; use \"auto\" or \"dop853\""
                    .into(),
            })
        })?),
        _ => None,
    };
    // `auto` takes the fast path whenever it covers the scene and no history is asked for (it has no dense output:
    // a history comes from Dop853, so that every view of one run is one solution). Asked for by name, it gives the
    // report and Dop853 the history.
    let fast = match method {
        Method::Taylor => covered,
        Method::Auto => covered && recording == Recording::Off,
        Method::Dop853 | Method::Dopri5 | Method::Verlet | Method::SymplecticEuler | Method::Dop853Slide => false,
    };
    let normal = NormalContact::new(&scene.bodies, setup);
    if fast {
        match fast_outcome(&normal, scene, setup, quantities) {
            // (Returned from here, the outcome is written once into the caller's place: a sweep row's path.)
            Ok(outcome) if recording == Recording::Off => return Ok((outcome, None)),
            Ok(outcome) => return Ok((outcome, run(&normal, scene, setup.contact_time, recording)?.1)),
            Err(error) if method == Method::Taylor => {
                return Err(SimulationError::Integration(IntegrationError::Solver {
                    time: 0.0,
                    reason: error.to_string(),
                }));
            }
            // (`auto` falls back on the general path if the fast one cannot finish.)
            Err(_) => {}
        }
    }
    match setup.motion {
        Motion::Normal => run(&normal, scene, setup.contact_time, recording),
        Motion::Full => {
            // A frictional sphere on a wall: its tangential motion stays on one line (dynamics/slide.rs), the normal
            // motion and three tangential states in regularised time taking the place of the 3-D model's, at a
            // fraction of its cost. `auto` runs it by Taylor series where the series cover it, by Dop853 otherwise
            // (or where the series meet a state they do not cover), and otherwise in regularised time on the 3-D
            // model (dynamics/wall.rs) when the law has neither memory nor kinks; a run that does not end in a
            // separation is run again as the general path runs it, so that how a contact ends is that path's to say.
            // Either slide asked for by name gives the report, the 3-D model the history (as the normal fast path
            // does), and a run that does not end in a separation is an error rather than a fallback.
            let history = |recording: Recording| match recording {
                Recording::Off => Ok(None),
                _ => run(&PairContact::new(&scene.bodies, setup), scene, setup.contact_time, recording).map(|r| r.1),
            };
            let not_separated = |outcome: &Outcome, name: &str| {
                SimulationError::Integration(IntegrationError::Solver {
                    time: outcome.end.time / setup.scales.time,
                    reason: format!(
                        "the {name} path did not end in a separation (use \"auto\", which then takes another path)"
                    ),
                })
            };
            // Whether `auto` goes on to the Dop853 slide: where the series do not cover the laws, or met a state
            // they have no series for (a Taylor slide that ends otherwise goes to the 3-D model, whose run says how
            // the contact ends).
            let mut by_dop853 = true;
            // Integrated up to the last slide, that slide in closed form over the normal fast path's motion
            // (slide_through.rs), where a sufficient condition on the normal motion shows it to last to the end. (On
            // a contact of its own: the model's switches keep counts, which the integrated slide's run, if it
            // follows, must start without.)
            if method == Method::Auto
                && recording == Recording::Off
                && let Some(slide) = wall_slide()
                && let Some(outcome) = crate::slide_through::outcome(&slide, scene, setup, quantities)
            {
                return Ok((outcome, None));
            }
            if let Some(slide) = if method == Method::Taylor { named_taylor_slide } else { taylor_slide() } {
                let uncovered = || {
                    SimulationError::Integration(IntegrationError::Solver {
                        time: 0.0,
                        reason: "the slide by Taylor series cannot take this contact: it met a state it has no series \
                                 for (a slide with no direction, its slip exactly zero, or a slide on the compressive \
                                 limit of a law that pulls once the limit's corner is no longer watched); use \"auto\""
                            .into(),
                    })
                };
                let by_name = method == Method::Taylor;
                let result = run_with(&slide, scene, setup.contact_time, Recording::Off, Scheme::Taylor);
                let no_series = match &result {
                    Ok((outcome, _)) => matches!(&outcome.ending, Ending::GaveUp(reason) if reason.contains(NO_SERIES)),
                    Err(SimulationError::Compression(reason)) => reason.contains(NO_SERIES),
                    Err(_) => false,
                };
                match result {
                    Ok((mut outcome, _)) if outcome.separated && outcome.ending == Ending::Event(0) => {
                        outcome.method = TAYLOR_SLIDE;
                        outcome.switches -= slide.unloadings();
                        return Ok((outcome, history(recording)?));
                    }
                    _ if !by_name => by_dop853 = no_series,
                    _ if no_series => return Err(uncovered()),
                    Ok((outcome, _)) => return Err(not_separated(&outcome, "taylor")),
                    Err(error) => return Err(error),
                }
            }
            if let Some(slide) = dop853_slide {
                let (mut outcome, _) = run(&slide, scene, setup.contact_time, Recording::Off)?;
                if !(outcome.separated && outcome.ending == Ending::Event(0)) {
                    return Err(not_separated(&outcome, "dop853-slide"));
                }
                outcome.method = SLIDE;
                outcome.switches -= slide.unloadings();
                return Ok((outcome, history(recording)?));
            }
            if method == Method::Auto
                && recording == Recording::Off
                && by_dop853
                && let Some(slide) = wall_slide()
                && let Ok((mut outcome, None)) = run(&slide, scene, setup.contact_time, Recording::Off)
                && outcome.separated
                && outcome.ending == Ending::Event(0)
            {
                outcome.method = SLIDE;
                outcome.switches -= slide.unloadings();
                return Ok((outcome, None));
            }
            if method == Method::Auto
                && recording == Recording::Off
                && smooth_in_regularised_time(&setup.law)
                && let Some(wall) = WallContact::new(&scene.bodies, setup)
                && let Ok((mut outcome, None)) = run(&wall, scene, setup.contact_time, Recording::Off)
                && outcome.separated
                && outcome.ending == Ending::Event(0)
            {
                outcome.method = REGULARISED;
                return Ok((outcome, None));
            }
            run(&PairContact::new(&scene.bodies, setup), scene, setup.contact_time, recording)
        }
        Motion::Rigid => run(&RigidContact::new(&scene.bodies, setup), scene, setup.contact_time, recording),
    }
}

/// The report's `solver.method` for a frictional sphere on a wall integrated in regularised time
/// ([`WallContact`]).
pub const REGULARISED: &str = "dop853-regularised";

/// Whether a law's force, times `dt/dσ = d^(3/4)`, is smooth through the edges of a contact in the wall model's
/// regularised time: every law without memory or kinks (a yielding law, MuJoCo's impedance and ADAMS' step have
/// them, and take the general path).
fn smooth_in_regularised_time(law: &crate::law::ContactLaw) -> bool {
    use crate::law::Family;
    !matches!(law.kind.family(), Family::Plastic | Family::Impedance | Family::Ramp)
}

/// The phases of one impact over `model`.
fn run<const N: usize, M: ContactModel<N>>(
    model: &M,
    scene: &Scene,
    contact_time: f64,
    recording: Recording,
) -> Result<(Outcome, Option<History>), SimulationError> {
    // Dopri5 when the scene names it; Dop853 otherwise (and for `taylor`'s history).
    let scheme = if scene.solver.method == Method::Dopri5 { Scheme::Dopri5 } else { Scheme::Dop853 };
    run_with(model, scene, contact_time, recording, scheme)
}

/// The phases of one impact over `model`, integrated by `scheme`.
fn run_with<const N: usize, M: ContactModel<N>>(
    model: &M,
    scene: &Scene,
    contact_time: f64,
    recording: Recording,
    scheme: Scheme,
) -> Result<(Outcome, Option<History>), SimulationError> {
    let tolerances = model.tolerances(scene.solver.tolerances);
    let mut stepper = Stepper::new(model, tolerances, recording != Recording::Off).scheme(scheme);
    let start = model.start();
    let frictional = model.switch_function(&start).is_some();
    let mut phases = Phases {
        below_limit_since: (frictional && !model.sliding(&start)).then_some(0.0),
        below_limit: 0.0,
        switches: 0,
        resumable: Vec::new(),
    };
    stepper.note(0.0, start);

    let rate = |y: &State<N>| model.rate(y);
    let force_rate = |y: &State<N>| model.force_rate(y);
    let penetration = |y: &State<N>| model.penetration(y);
    let separation_force = |y: &State<N>| model.separation_force(y);
    let settled = |y: &State<N>| model.penetration(y).abs() + model.rate(y).abs() - SETTLED;
    let switch = |y: &State<N>| model.switch_function(y).unwrap_or(1.0);
    let slip = |y: &State<N>| model.slip_along_start(y).unwrap_or(1.0);
    // Whether to watch for the slip coming to rest (a frictional contact that starts slipping).
    let slipping = model.slip_along_start(&start).is_some();

    // The kinks of the law's force, each a step boundary: in compression the next one above the penetration, in
    // restitution the next one below; once located, the next is watched (the margin of a located kink sits at zero
    // to rounding: watched further, every restart would find it again).
    let passed = std::cell::Cell::new(0usize);
    let rising = model.kinks(true);
    let next_above = |y: &State<N>| rising.as_slice().get(passed.get()).map_or(1.0, |kink| kink - model.penetration(y));

    // Event lists: the phase's own events first, then the slip's rest (watched, not terminal), then the onset of yield
    // (a step boundary on the kink of a yielding law's force), then (for a frictional model only) the stick–slip
    // switch, last.
    let mut compression = vec![event(&rate, true), event(&force_rate, false)];
    let slip_in_compression = compression.len();
    if slipping {
        compression.push(event(&slip, false));
    }
    if rising.count > 0 {
        phases.resumable.push((compression.len(), &passed, None));
        compression.push(event(&next_above, true));
    }
    if frictional {
        compression.push(Event { dips: true, ..event(&switch, true) });
    }
    let compressed = phases.run(&mut stepper, model, 0.0, start, &compression, frictional)?;
    phases.resumable.clear();
    // The kinks the restitution passes on its way down: those below the deepest point, descending.
    let deepest = model.penetration(&compressed.state);
    let falling = model.kinks(false);
    let below: Vec<f64> = falling.as_slice().iter().rev().copied().filter(|kink| *kink < deepest).collect();
    passed.set(0);
    let next_below = |y: &State<N>| below.get(passed.get()).map_or(1.0, |kink| model.penetration(y) - kink);
    if compressed.ending != Ending::Event(0) {
        return Err(SimulationError::Compression(match compressed.ending {
            Ending::GaveUp(reason) if frictional => {
                format!("{reason} ({})", stiffness_causes(true))
            }
            Ending::GaveUp(reason) => reason,
            _ => format!("no maximum compression within {TIME_LIMIT} elastic time units"),
        }));
    }
    // A force separation is located on the law's continued force, and never later than d = 0 (docs/numerics.md):
    // the penetration is a second separation event then. Laws that never turn tensile end at d = 0 whichever
    // criterion is named, but a yielding one, whose force returns to zero at its dent, ends there.
    let law = &scene.contact;
    let yields = law.law.family() == crate::law::Family::Plastic;
    let on_force = (law.separation == crate::law::Separation::Force && law.law.can_turn_tensile()) || yields;
    let ending: &dyn Fn(&State<N>) -> f64 = if on_force { &separation_force } else { &penetration };
    let mut restitution = vec![event(ending, true), event(&settled, true), event(&force_rate, false)];
    if on_force {
        restitution.push(event(&penetration, true));
    }
    let slip_in_restitution = restitution.len();
    if slipping {
        restitution.push(event(&slip, false));
    }
    // Where a frictional contact's force turns tensile and back (located, not terminal): the tensile impulse. Where
    // the model slides through it without a switch (`ContactModel::tension_kink`), each passage is a step boundary
    // too (the first MAX_CUTS, watched falling, then rising, in turn), where the Coulomb cap `mu max(Fn, 0)` has its
    // kink: Dop853's error estimate, stepping across it, let a Tsuji wall's tangential velocity take 1.2e-10 of the
    // approach speed in the step after it (test 4 at 45° at rtol 1e-10), where the force was zero. (Its passages are recorded as the two watches' crossings.)
    let force = |y: &State<N>| model.force(y);
    let tension = frictional && !on_force && law.law.can_pull();
    let tension_events = restitution.len();
    let tensions = std::cell::Cell::new(0usize);
    let tension_boundary = |y: &State<N>| match tensions.get() {
        n if n < MAX_CUTS && n.is_multiple_of(2) => model.force(y),
        n if n < MAX_CUTS => -model.force(y),
        _ => 1.0,
    };
    if tension {
        restitution.push(event(&force, false));
        restitution.push(Event { function: &force, direction: Direction::Rising, terminal: false, dips: false });
        if model.tension_kink() {
            phases.resumable.push((restitution.len(), &tensions, Some([tension_events, tension_events + 1])));
            restitution.push(event(&tension_boundary, true));
        }
    }
    if !below.is_empty() {
        phases.resumable.push((restitution.len(), &passed, None));
        restitution.push(event(&next_below, true));
    }
    // A law that never pulls cuts its damper where spring and damper together would pull (and `adams-impact`, whose
    // damping vanishes at first touch, may push again nearer the surface): each zero of the uncut force is a step
    // boundary, watched falling, then rising, in turn — a located zero sits at zero to rounding, and the next watch
    // looks the other way. (With a force criterion MuJoCo's contact ends at the first: its ending event.)
    let cuts = std::cell::Cell::new(0usize);
    let uncut = |y: &State<N>| match model.uncut_force(y) {
        Some(force) if cuts.get() < MAX_CUTS => {
            if cuts.get().is_multiple_of(2) {
                force
            } else {
                -force
            }
        }
        _ => 1.0,
    };
    let ended_by_cut = on_force && law.law.family() == crate::law::Family::Impedance;
    if model.uncut_force(&compressed.state).is_some() && !ended_by_cut {
        phases.resumable.push((restitution.len(), &cuts, None));
        restitution.push(event(&uncut, true));
    }
    if frictional {
        restitution.push(Event { dips: true, ..event(&switch, true) });
    }
    let released = phases.run(&mut stepper, model, compressed.time, compressed.state, &restitution, frictional)?;
    let released = parted_within_tolerance(model, released, scene.solver.tolerances.rtol, on_force);
    // Events 0 and 3 (with a force criterion) are separations; 1 is the motion dying out.
    let parted = matches!(released.ending, Ending::Event(0)) || (on_force && released.ending == Ending::Event(3));
    // A penetration that returns to zero without a separation speed (e = 0 to the integration's accuracy, e.g. a
    // critically damped contact under loose tolerances) has not separated: the bodies stay together.
    let separated = parted && model.rate(&released.state) < 0.0;

    let mut candidates = vec![(0.0, start), (compressed.time, compressed.state), (released.time, released.state)];
    candidates.extend(compressed.crossings.iter().chain(&released.crossings).map(|c| (c.time, c.state)));
    let (peak_time, peak_state) = candidates
        .into_iter()
        .max_by(|a, b| model.force(&a.1).total_cmp(&model.force(&b.1)))
        .expect("candidates are never empty");
    let peak = model.snapshot(peak_time, &peak_state);
    // The first located rest of the slip (at first contact for a frictional contact that starts without slip).
    let slip_rest = |crossings: &[Crossing<N>], index: usize| {
        crossings.iter().find(|c| c.event == index).map(|c| model.time_of(c.time, &c.state) * model.scales().time)
    };
    let slip_rest_time = match (frictional, slipping) {
        (false, _) => None,
        (true, false) => Some(0.0),
        (true, true) => slip_rest(&compressed.crossings, slip_in_compression)
            .or_else(|| slip_rest(&released.crossings, slip_in_restitution)),
    };
    let tensile_impulse = if !tension {
        if frictional && !law.law.can_pull() { 0.0 } else { f64::NAN }
    } else {
        tensile_impulse(model, &released, tension_events)
    };
    let ending = match released.ending {
        _ if parted => Ending::Event(0),
        Ending::Event(_) => Ending::Event(1),
        other => other,
    };
    let outcome = Outcome {
        max_compression: model.snapshot(compressed.time, &compressed.state),
        end: model.snapshot(released.time, &released.state),
        peak_force: (peak.time, peak.normal_force),
        separated,
        ending,
        below_limit_duration: (phases.below_limit
            + phases.below_limit_since.map_or(0.0, |since| model.time_of(released.time, &released.state) - since))
            * model.scales().time,
        slip_rest_time,
        switches: phases.switches,
        tensile_impulse,
        counters: stepper.counters,
        method: scheme.name(),
        restitution: None,
        note: None,
        fixed_step: None,
    };
    let history = match recording {
        Recording::Off => None,
        Recording::Steps => stepper.recorded().map(|points| History::new(points, model, compressed.time, contact_time)),
        Recording::Uniform(count) => {
            let times = uniform(released.time, count);
            Some(History::new(&stepper.resample(&times)?, model, compressed.time, contact_time))
        }
    };
    Ok((outcome, history))
}

/// A restitution whose run gave up within the scene's tolerance of the end is over: where the bodies part and the
/// free flight left to the penetration's zero, `d/|d'|`, is within `rtol` (the scene's, not the model's tighter one)
/// of the contact's time, and the impulse the contact's forces could pass over it within `rtol` of the normal
/// impulse, the run ends there as separated (a located end of the penetration's criterion; not under a force's,
/// whose zero lies elsewhere). A spring rescaled with the contact's stiffness and held by a tangential dashpot up to
/// the end shrinks as `sqrt(d)`, an infinite rate in physical time: two spheres' steps underflowed 1.7e-18 s before
/// they parted (docs/numerics.md#phases-and-events).
fn parted_within_tolerance<const N: usize, M: ContactModel<N>>(
    model: &M,
    released: PhaseEnd<N>,
    rtol: f64,
    on_force: bool,
) -> PhaseEnd<N> {
    if on_force || !matches!(released.ending, Ending::GaveUp(_)) {
        return released;
    }
    let end = model.snapshot(released.time, &released.state);
    if !(end.rate < 0.0 && end.penetration.is_finite() && end.time > 0.0) {
        return released;
    }
    let free_flight = end.penetration.max(0.0) / -end.rate;
    let forces = end.normal_force.abs() + end.tangential_force.norm();
    if free_flight <= rtol * end.time && forces * free_flight <= rtol * end.normal_impulse.abs() {
        PhaseEnd { ending: Ending::Event(0), ..released }
    } else {
        released
    }
}

/// The normal impact through the fast path ([`crate::fast`]), as an [`Outcome`] of the normal model's snapshots.
/// (Inlined into its one caller, so that the outcome is formed where the caller returns it, not copied there.)
#[inline(always)]
fn fast_outcome(
    model: &NormalContact,
    scene: &Scene,
    setup: &Setup,
    quantities: Quantities,
) -> Result<Outcome, crate::fast::FastError> {
    use crate::dynamics::normal::{SIZE, index};
    use crate::fast::{Ending as FastEnding, PhasePoint, Request};
    let request = Request {
        law: setup.law,
        scales: setup.scales,
        separation: scene.contact.separation,
        tolerance: scene.solver.tolerances.rtol,
        quantities,
    };
    let fast = crate::fast::simulate_normal(&request)?;
    let s = &setup.scales;
    let snapshot = |point: &PhasePoint| {
        let mut y = State::<SIZE>::zeros();
        y[index::PENETRATION] = point.penetration;
        y[index::RATE] = point.rate;
        y[index::IMPULSE] = point.impulse;
        y[index::WORK] = point.work;
        y[index::DISSIPATED] = point.dissipated / model.dissipation_scale;
        model.snapshot_with(point.time, &y, point.force * s.force, point.elastic * s.energy)
    };
    let (ending, note) = match fast.ending {
        FastEnding::Separated => (Ending::Event(0), None),
        FastEnding::Settled => (Ending::Event(1), None),
        FastEnding::NeverSeparates => (
            Ending::Event(1),
            Some(
                "the bodies did not separate, and never will: the damping is at or above critical (zeta >= 1) and the contact ends \
                 at zero penetration, which an overdamped linear motion never returns to (decided at maximum \
                 compression)"
                    .to_string(),
            ),
        ),
        FastEnding::StepBudget => (Ending::GaveUp("the fast path's step budget was spent".into()), None),
        FastEnding::TimeLimit => (Ending::TimeLimit, None),
    };
    Ok(Outcome {
        max_compression: snapshot(&fast.max_compression),
        end: snapshot(&fast.end),
        peak_force: (fast.peak_force_time * s.time, fast.peak_force * s.force),
        separated: fast.separated,
        ending,
        below_limit_duration: 0.0,
        slip_rest_time: None,
        switches: 0,
        tensile_impulse: f64::NAN,
        counters: Counters { steps: fast.steps, rejected_steps: 0, evaluations: fast.force_evaluations },
        method: if fast.first_integral { "first-integral" } else { "taylor" },
        restitution: Some((fast.restitution_impulse * s.impulse, fast.restitution_work * s.energy)),
        note,
        fixed_step: None,
    })
}

/// The fixed-step scheme a method names.
fn fixed_scheme(method: Method) -> Option<fixed_step::Scheme> {
    match method {
        Method::Verlet => Some(fixed_step::Scheme::Verlet),
        Method::SymplecticEuler => Some(fixed_step::Scheme::SymplecticEuler),
        Method::Auto | Method::Dop853 | Method::Dopri5 | Method::Taylor | Method::Dop853Slide => None,
    }
}

/// The normal impact through a peer code's fixed-step scheme ([`crate::fixed_step`], the touch on a step
/// boundary), as an [`Outcome`] of the normal model's snapshots, with the accurate path's e beside it. The accurate
/// path runs first: its contact duration bounds the step (`solver.dt`).
fn fixed_step_outcome(
    scheme: fixed_step::Scheme,
    scene: &Scene,
    setup: &Setup,
    recording: Recording,
) -> Result<(Outcome, Option<History>), SimulationError> {
    use crate::dynamics::normal::{SIZE, index};
    let refuse = |key: &str, message: String| SimulationError::Setup(SetupError { key: key.into(), message });
    if setup.motion != Motion::Normal {
        // (Setup::new refuses it already, naming the same key.)
        return Err(refuse("solver.method", format!("method = \"{}\" runs the normal contact only", scheme.name())));
    }
    let Some(dt) = scene.solver.dt else {
        return Err(refuse("solver.dt", format!("method = \"{}\" needs its time step `dt` (s)", scheme.name())));
    };
    let mut accurate = scene.clone();
    accurate.solver.method = Method::Auto;
    accurate.solver.dt = None;
    let (continuous, _) = through_phases(&accurate, setup, Recording::Off, Quantities::ALL)?;
    let duration = continuous.end.time;
    if dt > duration {
        let how = if continuous.separated {
            "by the accurate path"
        } else {
            "until the accurate path stopped: the bodies did not part"
        };
        let (step, duration) = crate::units::apart(dt, duration, "s");
        return Err(refuse(
            "solver.dt",
            format!(
                "dt = {step} is larger than the contact's duration {duration} ({how}): a fixed-step scheme needs \
                 steps inside the contact (DEM codes take dt below a tenth, usually a fiftieth, of it)"
            ),
        ));
    }
    let contact = fixed_step::Contact {
        law: setup.law,
        mass: setup.effective_mass,
        speed: setup.approach_speed,
        separation: scene.contact.separation,
    };
    let mut points = (recording != Recording::Off).then(Vec::new);
    let run = contact.run(scheme, dt, 0.0, points.as_mut());
    let model = NormalContact::new(&scene.bodies, setup);
    let s = &setup.scales;
    let law = &setup.law;
    let state = |p: &fixed_step::Point| {
        let mut y = State::<SIZE>::zeros();
        y[index::PENETRATION] = p.penetration / s.length;
        y[index::RATE] = p.rate / s.speed;
        y[index::IMPULSE] = p.impulse / s.impulse;
        y[index::WORK] = p.work / s.energy;
        y[index::DISSIPATED] =
            if law.yields() { p.deepest / s.length } else { p.dissipated / (s.energy * model.dissipation_scale) };
        y
    };
    let snapshot = |p: &fixed_step::Point| {
        let elastic = law.elastic_energy_after(p.penetration, p.deepest);
        let mut snapshot = model.snapshot_with(p.time / s.time, &state(p), p.force, elastic);
        if law.yields() {
            snapshot.dissipated_normal = snapshot.normal_work - elastic;
        }
        snapshot
    };
    let ending = match run.ending {
        fixed_step::Ending::Separated => Ending::Event(0),
        fixed_step::Ending::Settled => Ending::Event(1),
        fixed_step::Ending::TimeLimit => Ending::TimeLimit,
        fixed_step::Ending::Diverged => Ending::GaveUp(format!(
            "the {} scheme diverged: dt = {} is beyond its stability limit for this contact",
            scheme.name(),
            crate::units::brief(dt, "s")
        )),
    };
    let max_compression = run.max_compression.time / s.time;
    let history = points.map(|points| {
        let chosen: Vec<&fixed_step::Point> = match recording {
            Recording::Uniform(count) if count >= 2 && points.len() > count => {
                (0..count).map(|i| &points[(i * (points.len() - 1) + (count - 1) / 2) / (count - 1)]).collect()
            }
            _ => points.iter().collect(),
        };
        let states: Vec<(f64, State<SIZE>)> = chosen.iter().map(|p| (p.time / s.time, state(p))).collect();
        let mut history = History::new(&states, &model, max_compression, setup.contact_time);
        // The force the scheme computed there (Verlet's at the half-step velocity; zero once the contact is over),
        // as the report's peak force is.
        for (sample, point) in history.samples.iter_mut().zip(&chosen) {
            sample.force = point.force;
        }
        history
    });
    let outcome = Outcome {
        max_compression: snapshot(&run.max_compression),
        end: snapshot(&run.end),
        peak_force: run.peak_force,
        separated: run.separated(),
        ending,
        below_limit_duration: 0.0,
        slip_rest_time: None,
        switches: 0,
        tensile_impulse: f64::NAN,
        counters: Counters { steps: run.steps, rejected_steps: 0, evaluations: run.evaluations },
        method: scheme.name(),
        restitution: None,
        note: None,
        fixed_step: Some(FixedStepOutcome {
            dt,
            restitution_continuous: continuous.separated.then(|| -continuous.end.rate / setup.approach_speed),
        }),
    };
    Ok((outcome, history))
}

/// The impulse of the normal force while it pulled over a restitution (N s, a positive size), from the located
/// crossings of its force into tension (event `into`) and back out (event `into + 1`), and its end.
fn tensile_impulse<const N: usize, M: ContactModel<N>>(model: &M, released: &PhaseEnd<N>, into: usize) -> f64 {
    let impulse = |time: f64, state: &State<N>| model.snapshot(time, state).normal_impulse;
    let mut crossings: Vec<&Crossing<N>> =
        released.crossings.iter().filter(|c| c.event == into || c.event == into + 1).collect();
    crossings.sort_by(|a, b| a.time.total_cmp(&b.time));
    let (mut total, mut since) = (0.0, None);
    for crossing in crossings {
        let at = impulse(crossing.time, &crossing.state);
        match (crossing.event == into, since) {
            (true, None) => since = Some(at),
            (false, Some(start)) => {
                total += start - at;
                since = None;
            }
            _ => {}
        }
    }
    if let Some(start) = since {
        total += start - impulse(released.time, &released.state);
    }
    total.max(0.0)
}

/// Most zeros of a cutting law's uncut force one restitution makes step boundaries (a cut and a release each; more
/// are only stepped across).
const MAX_CUTS: usize = 8;

/// An event where `function` falls through zero.
fn event<'a, const N: usize>(function: &'a dyn Fn(&State<N>) -> f64, terminal: bool) -> Event<'a, N> {
    Event { function, direction: Direction::Falling, terminal, dips: false }
}

/// `count` evenly spaced times over [0, end], both ends included.
fn uniform(end: f64, count: usize) -> Vec<f64> {
    match count {
        0 => Vec::new(),
        1 => vec![0.0],
        _ => (0..count).map(|i| end * i as f64 / (count - 1) as f64).collect(),
    }
}

/// Book-keeping across the runs of one impact: the stick–slip history (scaled times).
struct Phases<'a> {
    /// When the present stretch below the Coulomb limit (the spring's sticking mode) began, if the contact is in it.
    below_limit_since: Option<f64>,
    /// Time spent below the limit in finished stretches.
    below_limit: f64,
    switches: u32,
    /// The terminal events after which the phase simply goes on (a kink of the force, a damper's cut, the force's
    /// passage into or out of tension), each with the count of its located crossings (its function then watches the
    /// next) and, for one that alternates between two watches' zeros, their events, as which its crossings are
    /// recorded (the first, then the second, in turn).
    #[allow(clippy::type_complexity)]
    resumable: Vec<(usize, &'a std::cell::Cell<usize>, Option<[usize; 2]>)>,
}

/// How a phase ended (the run's end, with the crossings of all its stretches).
struct PhaseEnd<const N: usize> {
    time: f64,
    state: State<N>,
    ending: Ending,
    crossings: Vec<Crossing<N>>,
}

impl Phases<'_> {
    /// Runs one phase from `(t, y)` until one of its terminal events other than the stick–slip switch (the last
    /// event when `switching`), switching the model's mode at each located switch on the way.
    fn run<const N: usize, M: ContactModel<N>>(
        &mut self,
        stepper: &mut Stepper<'_, M, N>,
        model: &M,
        t: f64,
        y: State<N>,
        events: &[Event<'_, N>],
        switching: bool,
    ) -> Result<PhaseEnd<N>, SimulationError> {
        let switch_event = if switching { events.len() - 1 } else { usize::MAX };
        let (mut time, mut state, mut crossings) = (t, y, Vec::new());
        loop {
            let end = stepper.run(time, state, TIME_LIMIT, events)?;
            crossings.extend(end.crossings);
            if let Ending::Event(index) = end.ending
                && let Some((_, passed, recorded)) = self.resumable.iter().find(|(resumable, ..)| *resumable == index)
            {
                // A step boundary at the event, and on, watching the next.
                if let Some(watches) = recorded {
                    let event = watches[passed.get() % 2];
                    crossings.push(Crossing { event, time: end.time, state: end.state });
                }
                passed.set(passed.get() + 1);
                (time, state) = (end.time, end.state);
                continue;
            }
            if end.ending != Ending::Event(switch_event) {
                return Ok(PhaseEnd { time: end.time, state: end.state, ending: end.ending, crossings });
            }
            if self.switches >= MAX_SWITCHES {
                let reason = format!(
                    "the tangential force switched between the Coulomb limit and below it {MAX_SWITCHES} times"
                );
                return Ok(PhaseEnd { time: end.time, state: end.state, ending: Ending::GaveUp(reason), crossings });
            }
            let mut switched = end.state;
            model.switch(&mut switched);
            self.switches += 1;
            // (In physical time: a model in regularised time carries it as a state.)
            let now = model.time_of(end.time, &end.state);
            if model.sliding(&switched) {
                self.below_limit += self.below_limit_since.take().map_or(0.0, |since| now - since);
            } else {
                self.below_limit_since = Some(now);
            }
            // The record keeps the switched state at this time (the last noted point of a time wins).
            stepper.note(end.time, switched);
            (time, state) = (end.time, switched);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The 3-D model, run on a central impact, must give what the 1-D model gives: the normal model is its special
    /// case, not a different physics.
    #[test]
    fn the_full_model_reproduces_the_normal_model_on_central_impacts() {
        let laws = [
            "law = \"hertz\"",
            "law = \"hunt-crossley\"\nrestitution = 0.6",
            "law = \"gonthier\"\nrestitution = 0.3",
            "law = \"kelvin-voigt\"\nrestitution = 0.5\nstiffness = 1e6\nexponent = 1.0",
            "law = \"tsuji\"\nrestitution = 0.4",
            "law = \"brilliantov\"\ndamping = 1e-6",
        ];
        for law in laws {
            for separation in ["penetration", "force"] {
                for second in [
                    "radius = 0.02\nmass = 0.1\nvelocity = [-0.5, 0.0, 0.0]",
                    "radius = inf\nmass = inf\nvelocity = [0.0, 0.0, 0.0]",
                ] {
                    let text = format!(
                        "[[bodies]]\nradius = 0.01\nmass = 0.03\nvelocity = [1.5, 0.0, 0.0]\nyoung = 2e11\npoisson = 0.3\n\n\
                         [[bodies]]\n{second}\nyoung = 7e10\npoisson = 0.33\n\n[contact]\n{law}\nseparation = \"{separation}\"\n"
                    );
                    let scene = Scene::parse(&text, std::path::Path::new("central.toml")).unwrap();
                    let setup = Setup::new(&scene).unwrap();
                    assert_eq!(setup.motion, Motion::Normal);
                    let normal =
                        run(&NormalContact::new(&scene.bodies, &setup), &scene, 0.0, Recording::Off).unwrap().0;
                    let full = run(&PairContact::new(&scene.bodies, &setup), &scene, 0.0, Recording::Off).unwrap().0;
                    assert_eq!(normal.separated, full.separated, "{text}");
                    let close = |a: f64, b: f64, scale: f64| (a - b).abs() <= 1e-9 * scale;
                    for (x, y) in [(&normal.max_compression, &full.max_compression), (&normal.end, &full.end)] {
                        let what = format!("{law}, {separation}, {second}");
                        assert!(close(x.time, y.time, normal.end.time), "time {} {} {what}", x.time, y.time);
                        assert!(close(x.penetration, y.penetration, normal.max_compression.penetration), "d {what}");
                        assert!(close(x.rate, y.rate, 1.5), "rate {what}");
                        assert!(
                            close(x.normal_impulse, y.normal_impulse, normal.max_compression.normal_impulse),
                            "J {what}"
                        );
                        let energy = normal.max_compression.normal_work;
                        assert!(close(x.dissipated_normal, y.dissipated_normal, energy), "D {what}");
                        assert!(close(x.work_of_immovable_bodies, y.work_of_immovable_bodies, energy), "W {what}");
                        for i in 0..2 {
                            assert!((x.velocities[i] - y.velocities[i]).amax() <= 1e-9 * 1.5, "v {what}");
                            assert!((x.positions[i] - y.positions[i]).amax() <= 1e-9 * 0.03, "x {what}");
                        }
                    }
                    assert!(close(normal.peak_force.1, full.peak_force.1, normal.peak_force.1), "{law}");
                }
            }
        }
    }

    /// The regularised path (`dynamics/wall.rs`) is `auto`'s fallback for a frictional sphere on a wall whose slide
    /// path does not end in a separation, which no test scene reaches: run directly, it must still give the 3-D
    /// model's velocities and spins, at tolerance 1e-13 in physical time, within 1e-9 of the approach speed — Chung &
    /// Ooi's test 4 at 10° (the slip comes to rest) and 45° (it slides throughout), with a spin.
    #[test]
    fn the_regularised_fallback_agrees_with_the_3d_model() {
        for degrees in [10.0f64, 45.0] {
            let (sin, cos) = degrees.to_radians().sin_cos();
            let text = format!(
                "[[bodies]]\nradius = 0.0025\ndensity = 4000\nvelocity = [{:?}, 0.0, {:?}]\n\
                 angular_velocity = [0.0, 500.0, 200.0]\nyoung = 3.8e11\npoisson = 0.23\n\n[[bodies]]\nradius = inf\n\
                 mass = inf\nvelocity = [0.0, 0.0, 0.0]\nyoung = inf\n\n[contact]\nnormal = [0.0, 0.0, -1.0]\n\
                 law = \"tsuji\"\nrestitution = 0.98\nfriction = 0.092\n",
                3.9 * sin,
                -3.9 * cos
            );
            let scene = Scene::parse(&text, std::path::Path::new("test4.toml")).unwrap();
            let setup = Setup::new(&scene).unwrap();
            let wall = WallContact::new(&scene.bodies, &setup).expect("a sphere on a wall");
            let regularised = run(&wall, &scene, setup.contact_time, Recording::Off).unwrap().0;
            let tight = Scene::parse(
                &format!("{text}\n[solver]\nmethod = \"dop853\"\nrtol = 1e-13\natol = 1e-14\n"),
                std::path::Path::new("test4.toml"),
            )
            .unwrap();
            let tight_setup = Setup::new(&tight).unwrap();
            let exact = run(&PairContact::new(&tight.bodies, &tight_setup), &tight, 0.0, Recording::Off).unwrap().0;
            assert!(regularised.separated && exact.separated, "{degrees}°");
            let (a, b) = (&regularised.end, &exact.end);
            let difference = (a.velocities[0] - b.velocities[0]).amax().max((a.spins[0] - b.spins[0]).amax() * 0.0025);
            assert!(difference <= 1e-9 * 3.9, "{degrees}°: {difference:e} m/s");
        }
    }

    /// The fast path's snapshots take the force and the elastic energy from its own variables (`w^γ = w/δ`,
    /// `w²/(n+1)`): they must be the law's own force and elastic energy at the snapshot's penetration and rate, at
    /// maximum compression and at the end, for every family it covers and both separations (the end of a force
    /// separation leaves a penetration, Kelvin–Voigt's end a tensile c d').
    #[test]
    fn fast_snapshots_carry_the_law_force_and_elastic_energy() {
        let laws = [
            "law = \"hertz\"",
            "law = \"hunt-crossley\"\nrestitution = 0.6",
            "law = \"gonthier\"\nrestitution = 0.3",
            "law = \"hunt-crossley\"\nexponent = 3.0\nstiffness = 1e12\ndamping = 0.2",
            "law = \"kelvin-voigt\"\nrestitution = 0.5\nstiffness = 1e6\nexponent = 1.0",
            "law = \"tsuji\"\nrestitution = 0.4",
        ];
        for law in laws {
            for separation in ["penetration", "force"] {
                let text = format!(
                    "[[bodies]]\nradius = 0.01\nmass = 0.03\nvelocity = [1.5, 0.0, 0.0]\nyoung = 2e11\npoisson = 0.3\n\n\
                     [[bodies]]\nradius = inf\nmass = inf\nvelocity = [0.0, 0.0, 0.0]\nyoung = 7e10\npoisson = 0.33\n\n\
                     [contact]\n{law}\nseparation = \"{separation}\"\n"
                );
                let scene = Scene::parse(&text, std::path::Path::new("snapshots.toml")).unwrap();
                let setup = Setup::new(&scene).unwrap();
                let normal = NormalContact::new(&scene.bodies, &setup);
                let outcome = fast_outcome(&normal, &scene, &setup, Quantities::ALL).unwrap();
                let scale = outcome.max_compression.normal_force;
                for point in [&outcome.max_compression, &outcome.end] {
                    let parts = setup.law.split_force(point.penetration.max(0.0), point.rate);
                    let force = parts.elastic + parts.dissipative;
                    let what = format!("{law}, {separation}: {} vs {force}", point.normal_force);
                    assert!((point.normal_force - force).abs() <= 1e-13 * scale, "{what}");
                    let elastic = setup.law.elastic_energy(point.penetration);
                    assert!((point.elastic_energy - elastic).abs() <= 1e-13 * elastic.max(1e-300), "{law}: {elastic}");
                }
                assert!(scale > 0.0, "{law}");
            }
        }
    }
}
