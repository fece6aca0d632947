//! One impact through its phases: flight (closed form) → compression → restitution → separation, producing the
//! [`Report`].

use crate::body::after_normal_impulse;
use crate::dynamics::normal::{NormalContact, SIZE, index};
use crate::history::{Frame, History, Recording};
use crate::instantaneous::{Instantaneous, direct_impact};
use crate::integrate::{Crossing, Direction, Ending, Event, IntegrationError, State, Stepper};
use crate::report::{
    BodyReport, ContactReport, EnergyReport, InstantaneousReport, LawReport, Report, SolverReport, Vec3,
};
use crate::scene::{DampingSpec, Scene};
use crate::setup::{Setup, SetupError};
use nalgebra::Vector3;
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

/// Scaled time after which a contact that has not separated is declared stuck (elastic contacts last about 3).
const TIME_LIMIT: f64 = 1e4;
/// Scaled size of |d| + |d'| below which the relative motion counts as died out.
const SETTLED: f64 = 1e-10;

/// Simulates the scene's impact; `recording` says whether (and how) to keep the contact history.
pub fn simulate(scene: &Scene, recording: Recording) -> Result<Simulation, SimulationError> {
    let clock = Instant::now();
    let setup = Setup::new(scene).map_err(SimulationError::Setup)?;
    let model = NormalContact { law: setup.law, scales: setup.scales };
    let mut stepper = Stepper::new(&model, scene.solver, recording != Recording::Off);

    let rate = |y: &State<SIZE>| y[index::RATE];
    let force = |y: &State<SIZE>| model.force(y);
    let force_rate = |y: &State<SIZE>| model.force_rate(y);
    let penetration = |y: &State<SIZE>| y[index::PENETRATION];
    let settled = |y: &State<SIZE>| y[index::PENETRATION].abs() + y[index::RATE].abs() - SETTLED;
    let peak = Event { function: &force_rate, direction: Direction::Falling, terminal: false };

    let start = NormalContact::initial_state();
    stepper.note(0.0, start);
    let compression = [Event { function: &rate, direction: Direction::Falling, terminal: true }, peak];
    let compressed = stepper.run(0.0, start, TIME_LIMIT, &compression)?;
    if compressed.ending != Ending::Event(0) {
        return Err(SimulationError::Compression(match compressed.ending {
            Ending::GaveUp(reason) => reason,
            _ => format!("no maximum compression within {TIME_LIMIT} elastic time units"),
        }));
    }
    let peak = Event { function: &force_rate, direction: Direction::Falling, terminal: false };
    // Laws that never turn tensile end at d = 0 whichever criterion is named (physics.md §1), and d is the
    // smoother event function there (F ~ d^n is not).
    let ends_on_force = scene.contact.separation == crate::law::Separation::Force && setup.law.kind.can_turn_tensile();
    let separation = Event {
        function: if ends_on_force { &force } else { &penetration },
        direction: Direction::Falling,
        terminal: true,
    };
    let restitution = [separation, Event { function: &settled, direction: Direction::Falling, terminal: true }, peak];
    let released = stepper.run(compressed.time, compressed.state, TIME_LIMIT, &restitution)?;
    // A penetration that returns to zero without a separation speed (e = 0 to the integration's accuracy, e.g. a
    // critically damped contact under loose tolerances) has not separated: the bodies stay together.
    let separated = released.ending == Ending::Event(0) && released.state[index::RATE] < 0.0;

    let mut candidates = vec![(0.0, start), (compressed.time, compressed.state), (released.time, released.state)];
    candidates
        .extend(compressed.crossings.iter().chain(&released.crossings).map(|c: &Crossing<SIZE>| (c.time, c.state)));
    let (peak_time, peak_state) = candidates
        .into_iter()
        .max_by(|a, b| model.force(&a.1).total_cmp(&model.force(&b.1)))
        .expect("candidates are never empty");

    let phases = Phases {
        max_compression: (compressed.time, compressed.state),
        end: (released.time, released.state),
        peak: (peak_time, model.force(&peak_state)),
        separated,
    };
    let frame = Frame {
        model: &model,
        bodies: &scene.bodies,
        normal: setup.normal,
        contact_time: setup.contact_time,
        max_compression: compressed.time,
    };
    // The solver's work is counted before any resampling of the history, so it measures the impact itself.
    let solver = SolverReport {
        method: "dop853".into(),
        rtol: scene.solver.rtol,
        atol: scene.solver.atol,
        steps: stepper.counters.steps,
        rejected_steps: stepper.counters.rejected_steps,
        force_evaluations: stepper.counters.evaluations,
        wall_time_s: clock.elapsed().as_secs_f64(),
    };
    let history = match recording {
        Recording::Off => None,
        Recording::Steps => stepper.recorded().map(|points| History::new(points, &frame)),
        Recording::Uniform(count) => {
            let times = uniform(released.time, count);
            Some(History::new(&stepper.resample(&times)?, &frame))
        }
    };
    let mut report = build_report(scene, &setup, &phases, solver);
    if !separated {
        report.notes.push(stuck_note(&setup, &phases, &released.ending));
    }
    Ok(Simulation { report, history })
}

/// `count` evenly spaced times over [0, end], both ends included.
fn uniform(end: f64, count: usize) -> Vec<f64> {
    match count {
        0 => Vec::new(),
        1 => vec![0.0],
        _ => (0..count).map(|i| end * i as f64 / (count - 1) as f64).collect(),
    }
}

/// The located phase boundaries, in scaled time and state.
struct Phases {
    max_compression: (f64, State<SIZE>),
    end: (f64, State<SIZE>),
    /// Time and scaled value of the largest compressive force.
    peak: (f64, f64),
    separated: bool,
}

fn stuck_note(setup: &Setup, phases: &Phases, ending: &Ending) -> String {
    let s = &setup.scales;
    let (time, state) = phases.end;
    let how = match ending {
        Ending::Event(0) => "the penetration returned to zero with no separation speed".to_string(),
        Ending::Event(_) => "the relative motion died out".to_string(),
        Ending::TimeLimit => format!("the time limit ({TIME_LIMIT} elastic time units) was reached"),
        Ending::GaveUp(reason) => format!(
            "the integration stopped ({reason}; a creeping, stiff restitution is typical of very heavy damping)"
        ),
    };
    format!(
        "the bodies did not separate: {how} {:.6e} s after first contact with penetration {:.6e} m and \
         penetration rate {:.6e} m/s still in contact",
        time * s.time,
        state[index::PENETRATION] * s.length,
        state[index::RATE] * s.speed
    )
}

fn build_report(scene: &Scene, setup: &Setup, phases: &Phases, solver: SolverReport) -> Report {
    let s = &setup.scales;
    let n = setup.normal;
    let [a, b] = &scene.bodies;
    let (t0, y0) = phases.max_compression;
    let (t_end, y_end) = phases.end;
    let deformation_impulse = y0[index::IMPULSE] * s.impulse;
    let total_impulse = y_end[index::IMPULSE] * s.impulse;
    let kick = |impulse: f64| after_normal_impulse(&scene.bodies, &n, impulse);
    let at_max = kick(deformation_impulse);
    let after = kick(total_impulse);
    // V0 from the simulated impulse, read off a movable body (its error is the impulse integral's).
    let common_normal_velocity = if a.is_immovable() { at_max[1].dot(&n) } else { at_max[0].dot(&n) };
    let compression_work = y0[index::WORK];
    let restitution_work = compression_work - y_end[index::WORK];
    let e_velocity = -y_end[index::RATE];
    let done = phases.separated;
    let when = |value: f64| done.then_some(value);
    let restitution_impulse = total_impulse - deformation_impulse;
    let kinetic_before =
        a.kinetic_energy(&a.velocity, &a.angular_velocity) + b.kinetic_energy(&b.velocity, &b.angular_velocity);
    let kinetic_after =
        a.kinetic_energy(&after[0], &a.angular_velocity) + b.kinetic_energy(&after[1], &b.angular_velocity);

    let nominal = match scene.contact.damping {
        DampingSpec::None => Some(1.0),
        DampingSpec::Restitution(e) => Some(e),
        DampingSpec::Parameter(_) => None,
    };
    let compare = |e: f64| {
        let ideal = direct_impact(&scene.bodies, &n, setup.effective_mass, e);
        instantaneous_report(&ideal, done.then_some(&after))
    };
    let body = |i: usize, body: &crate::body::Body| BodyReport {
        name: body.name.clone(),
        mass: body.mass,
        radius: body.radius,
        velocity_before: vec3(&body.velocity),
        velocity_after: done.then(|| vec3(&after[i])),
        velocity_at_max_compression: vec3(&at_max[i]),
        angular_velocity_after: done.then(|| vec3(&body.angular_velocity)),
    };
    Report {
        title: scene.title.clone(),
        law: LawReport {
            name: setup.law.kind.name().into(),
            stiffness: setup.law.stiffness,
            exponent: setup.law.exponent,
            damping: setup.law.damping,
            restitution_nominal: nominal,
            separation: scene.contact.separation.name().into(),
        },
        effective_mass: setup.effective_mass,
        approach_speed: setup.approach_speed,
        normal: vec3(&n),
        contact: ContactReport {
            start_time: setup.contact_time,
            max_compression_time: setup.contact_time + t0 * s.time,
            end_time: when(setup.contact_time + t_end * s.time),
            duration: when(t_end * s.time),
            max_penetration: y0[index::PENETRATION] * s.length,
            max_force: phases.peak.1 * s.force,
            max_force_time: setup.contact_time + phases.peak.0 * s.time,
            common_normal_velocity,
            deformation_impulse,
            restitution_impulse: when(restitution_impulse),
            restitution_impulse_ratio: when(restitution_impulse / deformation_impulse),
            restitution_velocity_ratio: when(e_velocity),
            restitution_energy: when((restitution_work.max(0.0) / compression_work).sqrt()),
            separated: done,
        },
        bodies: [body(0, a), body(1, b)],
        energy: EnergyReport {
            kinetic_before,
            kinetic_after: when(kinetic_after),
            dissipated: when(y_end[index::DISSIPATED] * s.energy),
        },
        instantaneous: when(e_velocity).map(compare),
        instantaneous_nominal: nominal.map(compare),
        reference: crate::accuracy::reference(scene, setup, phases_summary(phases, s, common_normal_velocity)),
        solver,
        notes: Vec::new(),
    }
}

/// The simulated values that exact references are compared with, in SI units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Measured {
    /// Velocity ratio e (None when not separated).
    pub restitution: Option<f64>,
    pub max_penetration: f64,
    /// s after first contact.
    pub max_compression_time: f64,
    /// s (None when not separated).
    pub duration: Option<f64>,
    pub max_force: f64,
    /// V0 read off the simulated impulse, m/s.
    pub common_normal_velocity: f64,
}

fn phases_summary(phases: &Phases, s: &crate::dynamics::Scales, common_normal_velocity: f64) -> Measured {
    Measured {
        restitution: phases.separated.then_some(-phases.end.1[index::RATE]),
        max_penetration: phases.max_compression.1[index::PENETRATION] * s.length,
        max_compression_time: phases.max_compression.0 * s.time,
        duration: phases.separated.then_some(phases.end.0 * s.time),
        max_force: phases.peak.1 * s.force,
        common_normal_velocity,
    }
}

fn instantaneous_report(ideal: &Instantaneous, simulated: Option<&[Vector3<f64>; 2]>) -> InstantaneousReport {
    let difference =
        simulated.map(|after| (0..2).map(|i| (after[i] - ideal.velocity_after[i]).amax()).fold(0.0, f64::max));
    InstantaneousReport {
        restitution: ideal.restitution,
        common_normal_velocity: ideal.common_normal_velocity,
        velocity_after: [vec3(&ideal.velocity_after[0]), vec3(&ideal.velocity_after[1])],
        energy_lost: ideal.energy_lost,
        max_velocity_difference: difference,
    }
}

fn vec3(v: &Vector3<f64>) -> Vec3 {
    [v.x, v.y, v.z]
}
