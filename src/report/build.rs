//! Building the [`Report`] from the outcome of an impact's phases: the one place where simulated numbers become
//! report values.

use super::accuracy::{self, Measured, ReferenceDetail};
use super::{
    BodyReport, ContactReport, EccentricReport, EnergyReport, InstantaneousReport, LawReport, ObliqueReport, Report,
    RigidBodyReport, Sections, SolverReport, Vec3,
};
use crate::body::Body;
use crate::dynamics::Snapshot;
use crate::idealisation::{self, Idealisation, SpeedTrial};
use crate::instantaneous::{Instantaneous, direct_impact, rigid_body_impact};
use crate::integrate::Ending;
use crate::law::Family;
use crate::outcome::{Outcome, TIME_LIMIT, stiffness_causes};
use crate::scene::{DampingSpec, Scene};
use crate::setup::{Motion, Setup};
use crate::units::{apart, brief, short};
use nalgebra::Vector3;

/// The report of one impact; with `trial` (the e of the same contact at 0.9 and 1.1 times the speed), its verdicts on
/// the idealisation, read from the report's own numbers; `sections` says which parts to fill (the verdicts read the
/// instantaneous impact and the bodies: a trial fills them whatever `sections` says).
pub fn build(
    scene: &Scene,
    setup: &Setup,
    outcome: &Outcome,
    detail: ReferenceDetail,
    wall_time: f64,
    trial: Option<SpeedTrial>,
    sections: Sections,
) -> Report {
    let mut report = Report::default();
    build_into(&mut report, scene, setup, outcome, detail, wall_time, trial, sections);
    report
}

/// [`build`] written into `report`, whatever it held: every field is written (a report kept from run to run — a
/// sweep worker's — keeps nothing of the run before, and its text and lists keep their room). The same numbers as
/// [`build`], which is this on an empty report; a sweep's row reads its cells here rather than moving 2.9 kB of
/// report out of a function a row.
#[allow(clippy::too_many_arguments)]
pub fn build_into(
    report: &mut Report,
    scene: &Scene,
    setup: &Setup,
    outcome: &Outcome,
    detail: ReferenceDetail,
    wall_time: f64,
    trial: Option<SpeedTrial>,
    sections: Sections,
) {
    let [a, b] = &scene.bodies;
    let n = setup.normal;
    let (max, end) = (&outcome.max_compression, &outcome.end);
    let done = outcome.separated;
    let when = |value: f64| done.then_some(value);
    let deformation_impulse = max.normal_impulse;
    let compression_work = max.normal_work;
    let (restitution_impulse, restitution_work) =
        outcome.restitution.unwrap_or((end.normal_impulse - deformation_impulse, compression_work - end.normal_work));
    let e_velocity = -end.rate / setup.approach_speed;
    // V0 read off a movable body's simulated velocity (its error is the impulse integral's).
    let moving = if a.is_immovable() { 1 } else { 0 };
    // The contact sphere's centre moves with a turning body (the mass centre of a sphere).
    let sphere_velocity = |snapshot: &Snapshot, i: usize| {
        let offset = snapshot.orientations[i] * scene.bodies[i].contact_offset;
        snapshot.velocities[i] + snapshot.spins[i].cross(&offset)
    };
    let common_normal_velocity = sphere_velocity(max, moving).dot(&max.normal);
    let kinetic =
        |i: usize, body: &Body| body.kinetic_energy_turned(&end.velocities[i], &end.spins[i], &end.orientations[i]);
    let kinetic_before =
        a.kinetic_energy(&a.velocity, &a.angular_velocity) + b.kinetic_energy(&b.velocity, &b.angular_velocity);
    let friction_work = 0.0 - (end.tangential_work + end.tangential_elastic_energy);
    // A force separation leaves the spring at the law's zero-force penetration for the separation speed: taken from
    // the rate, it is as accurate as the rate (the integrated penetration carries the event's time resolution).
    // (A fixed-step scheme's end is its own step's penetration, whose spring energy is the law's there.)
    let force_end = scene.contact.separation == crate::law::Separation::Force
        && setup.law.kind.can_turn_tensile()
        && end.penetration > 0.0
        && outcome.fixed_step.is_none();
    let elastic_left = if force_end {
        setup.law.elastic_energy(setup.law.separation_penetration(end.rate, end.penetration))
    } else {
        end.elastic_energy
    };

    let nominal = match scene.contact.damping {
        // A yielding law has no nominal e: its e follows from the impact speed.
        DampingSpec::None if setup.law.yields() => None,
        // The simulators' laws take their damping from their own keys (solref, cmax): no nominal e either.
        DampingSpec::None if matches!(setup.law.kind.family(), Family::Impedance | Family::Ramp) => None,
        DampingSpec::None => Some(1.0),
        DampingSpec::Restitution(e) => Some(e),
        DampingSpec::Parameter(_) => None,
    };
    let after = done.then_some((&end.velocities, &end.spins));
    let rigid = setup.motion == Motion::Rigid;
    let compare = |e: f64| {
        if rigid {
            eccentric_report(scene, setup, e, after)
        } else {
            instantaneous_report(&direct_impact(&scene.bodies, &n, setup.effective_mass, e), after.map(|(v, _)| v))
        }
    };
    let instantaneous = sections.instantaneous || trial.is_some();
    let name = |text: &String| if sections.names { text.clone() } else { String::new() };
    let body = |i: usize, body: &Body| BodyReport {
        name: name(&body.name),
        mass: body.mass,
        radius: body.radius,
        inertia: body.inertia,
        velocity_before: vec3(&body.velocity),
        velocity_after: done.then(|| vec3(&end.velocities[i])),
        velocity_at_max_compression: vec3(&max.velocities[i]),
        angular_velocity_before: vec3(&body.angular_velocity),
        angular_velocity_after: done.then(|| vec3(&end.spins[i])),
        angle_from_tangent_before_deg: angle_from_tangent(&body.velocity, &n),
        angle_from_tangent_after_deg: done.then(|| angle_from_tangent(&end.velocities[i], &n)).flatten(),
        position_at_first_contact: vec3(&setup.positions[i]),
        position_at_separation: done.then(|| vec3(&end.positions[i])),
        effective_mass_at_contact: setup.effective_masses[i],
        pivot_impulse: body.pivot.and(done.then(|| vec3(&end.pivot_impulses[i]))),
    };
    let measured = Measured {
        restitution: when(e_velocity),
        max_penetration: max.penetration,
        max_compression_time: max.time,
        duration: when(end.time),
        max_force: outcome.peak_force.1,
        common_normal_velocity,
    };
    // The exact references describe the relative motion along a fixed normal: a turning line of centres couples it
    // to the tangential motion, and they no longer apply.
    let fixed_normal = !rigid && (setup.motion == Motion::Normal || a.is_flat() || b.is_flat());
    // (The report's own list, emptied: its room is kept.)
    let mut notes = std::mem::take(&mut report.notes);
    notes.clear();
    if !done {
        notes.push(outcome.note.clone().unwrap_or_else(|| stuck_note(outcome, scene.contact.friction > 0.0)));
    } else if let Some(note) = &outcome.note {
        // (A path that separated with something to say of itself: the slide by Taylor series.)
        notes.push(note.clone());
    }
    if setup.law.kind.family() == Family::Dashpot
        && setup.law.exponent != 1.0
        && let DampingSpec::Restitution(e) = scene.contact.damping
    {
        notes.push(format!(
            "the dashpot c = {} was found by simulation: a root-find on the simulated e of this contact's normal \
             motion at its approach speed {} gives e = {} there (`hertz-dashpot` with exponent {} has no closed-form \
             map; docs/laws.md)",
            brief(setup.law.damping, "N s/m"),
            brief(setup.approach_speed, "m/s"),
            short(e),
            short(setup.law.exponent)
        ));
    }
    // The rigid-body model's oblique section is its friction's: a smooth eccentric impact has none.
    let oblique = if rigid && scene.contact.friction == 0.0 {
        None
    } else {
        oblique(scene, setup, outcome, e_velocity, friction_work)
    };
    if rigid {
        let turned = |i: usize| end.orientations[i].angle().to_degrees();
        notes.push(format!(
            "rigid bodies struck off their centre or turning about a pivot: the contact spheres move with the bodies, \
             which turned by {} and {} degrees during the contact; the exact references of a fixed normal and one \
             effective mass do not apply (the instantaneous impact is the eccentric one)",
            brief(turned(0), ""),
            brief(turned(1), "")
        ));
    }
    if let Some(turn) = oblique.as_ref().and_then(|o| o.normal_turn_deg).filter(|_| !fixed_normal && !rigid) {
        notes.push(format!(
            "the line of centres turned by {} degrees during the contact: the exact references of a fixed normal do \
             not apply",
            brief(turn, "")
        ));
    }
    // The bodies part at e v0: the separation time carries an error of about atol / e (in units of the contact's
    // own time), the absolute tolerance on speeds over the speed they part with.
    let resolution = scene.solver.tolerances.atol / e_velocity;
    // (No note at e = 0, whose resolution would be infinite: such bodies do not part at any speed.)
    if done && resolution > 1e-9 && resolution.is_finite() {
        notes.push(format!(
            "the bodies part slowly (e = {}): the contact's end, and so its duration, is resolved to about atol / e = \
             {} relative (a smaller [solver] atol sharpens it)",
            brief(e_velocity, ""),
            brief(resolution, "")
        ));
    }
    if let Some(o) = oblique.as_ref().filter(|o| o.slid_off) {
        let share = end.normal_impulse / (setup.effective_mass * (setup.approach_speed - end.rate));
        notes.push(format!(
            "the bodies slid off each other: the contact force made a fraction {} of the reversal of the normal \
             velocity (its impulse {} against m* (v0 + separation speed)); the line of centres, turning by {} degrees \
             as they slid past, did the rest — the instantaneous impacts, whose impulse alone reverses the normal \
             velocity, do not describe such a graze",
            brief(share, ""),
            brief(end.normal_impulse, "N s"),
            brief(o.normal_turn_deg.unwrap_or(0.0), "")
        ));
    }
    if outcome.switches > 0 {
        notes.push(format!(
            "the tangential force switched between the Coulomb limit and below it {} time{}",
            outcome.switches,
            if outcome.switches == 1 { "" } else { "s" }
        ));
    }
    let reference = if fixed_normal { accuracy::reference(scene, setup, measured, detail, &mut notes) } else { None };
    let ratios = Ratios::of(done, deformation_impulse, restitution_impulse, compression_work, restitution_work);
    notes.extend(ratios.notes());
    // Each field is named (a field added to the report and not written here does not compile).
    let Report {
        title,
        law,
        effective_mass,
        approach_speed,
        normal,
        contact,
        bodies,
        energy,
        oblique: oblique_section,
        instantaneous: instantaneous_section,
        instantaneous_nominal,
        reference: reference_section,
        idealisation,
        solver,
        notes: report_notes,
    } = report;
    title.clear();
    if sections.names {
        title.push_str(&scene.title);
    }
    *law = LawReport {
        name: setup.law.kind.name(),
        stiffness: setup.law.stiffness,
        exponent: setup.law.exponent,
        damping: setup.law.damping,
        restitution_nominal: nominal,
        // A yielding contact ends where its force returns to zero, at its dent.
        separation: if setup.law.yields() { "force" } else { scene.contact.separation.name() },
        yield_pressure: setup.law.yields().then(|| crate::setup::yield_pressure(&scene.contact, [a, b])).flatten(),
        yield_speed: setup.law.yields().then(|| {
            let scaled = setup.law.yield_penetration / setup.scales.length;
            crate::reference::thornton_yield_speed(scaled) * setup.approach_speed
        }),
    };
    *effective_mass = setup.effective_mass;
    *approach_speed = setup.approach_speed;
    *normal = vec3(&n);
    *contact = ContactReport {
        start_time: setup.contact_time,
        max_compression_time: setup.contact_time + max.time,
        end_time: when(setup.contact_time + end.time),
        duration: when(end.time),
        max_penetration: max.penetration,
        max_force: outcome.peak_force.1,
        max_force_time: setup.contact_time + outcome.peak_force.0,
        common_normal_velocity,
        deformation_impulse,
        restitution_impulse: when(restitution_impulse),
        restitution_impulse_ratio: ratios.impulse,
        restitution_velocity_ratio: when(e_velocity),
        restitution_energy: ratios.energy,
        separated: done,
        permanent_dent: (done && setup.law.yields()).then_some(end.penetration.max(0.0)),
    };
    if sections.bodies || trial.is_some() {
        *bodies = [body(0, a), body(1, b)];
    } else {
        // (Each emptied where it lies: no empty pair formed aside and copied in.)
        for body in bodies.iter_mut() {
            *body = BodyReport::default();
        }
    }
    *energy = EnergyReport {
        kinetic_before,
        kinetic_after: when(kinetic(0, a) + kinetic(1, b)),
        dissipated: when(end.dissipated_normal + friction_work),
        elastic_left_at_separation: when(elastic_left + end.tangential_elastic_energy),
        work_of_immovable_bodies: when(end.work_of_immovable_bodies),
    };
    set(oblique_section, oblique);
    set(instantaneous_section, when(e_velocity).filter(|_| instantaneous).map(compare));
    set(instantaneous_nominal, nominal.filter(|_| instantaneous).map(compare));
    set(reference_section, reference);
    *idealisation = Idealisation::default();
    *solver = SolverReport {
        method: outcome.method,
        rtol: scene.solver.tolerances.rtol,
        atol: scene.solver.tolerances.atol,
        dt: outcome.fixed_step.map(|fixed| fixed.dt),
        restitution_continuous: outcome.fixed_step.and_then(|fixed| fixed.restitution_continuous),
        steps: outcome.counters.steps,
        rejected_steps: outcome.counters.rejected_steps,
        force_evaluations: outcome.counters.evaluations,
        wall_time_s: wall_time,
        gave_up: match &outcome.ending {
            Ending::GaveUp(reason) if !done => Some(reason.clone()),
            _ => None,
        },
    };
    *report_notes = notes;
    if let Some(fixed) = outcome.fixed_step {
        report.notes.push(fixed_step_note(report, outcome.method, fixed.dt));
    } else if let Some(note) = energy_balance(&report.energy).and_then(|relative| {
        let bound = super::energy_balance_bound(scene.solver.tolerances.rtol, scene.solver.tolerances.atol);
        super::balance_note(relative, "the largest energy term", bound)
    }) {
        report.notes.push(note);
    }
    if let Some(trial) = trial {
        let measured = measured_by(report, scene.contact.friction, trial, levers(scene, setup));
        report.idealisation = idealisation::judge(scene.bodies.each_ref(), &measured);
    }
}

/// Writes `value` into the optional section `place`, where either holds one: a section that was none and stays none
/// (a sweep row's, leaving it out) is not written over with a few hundred bytes of nothing.
#[inline]
fn set<T>(place: &mut Option<T>, value: Option<T>) {
    if value.is_some() || place.is_some() {
        *place = value;
    }
}

/// The energy balance of a separated contact, `(in - out)` over its largest term: `kinetic_before +
/// work_of_immovable_bodies = kinetic_after + dissipated + elastic_left_at_separation` (null before separation).
fn energy_balance(e: &super::EnergyReport) -> Option<f64> {
    let (after, dissipated, left, work) =
        (e.kinetic_after?, e.dissipated?, e.elastic_left_at_separation?, e.work_of_immovable_bodies?);
    // A dissipation the run was not asked for (a sweep row without its column: NaN, never shown) leaves no balance
    // to close, and no note to form.
    if dissipated.is_nan() {
        return None;
    }
    let largest = [e.kinetic_before, work.abs(), after, dissipated.abs(), left.abs()].into_iter().fold(0.0, f64::max);
    (largest > 0.0).then(|| (e.kinetic_before + work - after - dissipated - left) / largest)
}

/// Poisson's and Stronge's e, each a ratio of what restitution gave back to what compression took: the impulses, and
/// the square root of the works. A ratio is formed only over a finite, positive compression integral and a finite
/// restitution one; otherwise (an integral that overflowed, or a compression that did no work in double precision)
/// it is null, with a note that says why, never NaN.
#[derive(Debug, Clone, Copy)]
struct Ratios {
    impulse: Option<f64>,
    energy: Option<f64>,
    /// The compression and restitution integrals of a ratio left out: (what, unit, compression, restitution).
    missing: [Option<(&'static str, &'static str, f64, f64)>; 2],
}

impl Ratios {
    fn of(separated: bool, deformation: f64, restitution: f64, compression_work: f64, restitution_work: f64) -> Ratios {
        let ratio = |compression: f64, restitution: f64| {
            (compression.is_finite() && compression > 0.0 && restitution.is_finite())
                .then(|| restitution / compression)
                .filter(|r| r.is_finite())
        };
        let impulse = ratio(deformation, restitution);
        // (A work given back that rounds below zero is none.)
        let energy = ratio(compression_work, restitution_work).map(|r| r.max(0.0).sqrt());
        let missing = |value: Option<f64>, what, unit, compression, restitution| {
            (separated && value.is_none()).then_some((what, unit, compression, restitution))
        };
        Ratios {
            impulse: impulse.filter(|_| separated),
            energy: energy.filter(|_| separated),
            missing: [
                missing(impulse, "impulse ratio (Poisson's e)", "N s", deformation, restitution),
                missing(energy, "energy ratio (Stronge's e)", "J", compression_work, restitution_work),
            ],
        }
    }

    fn notes(&self) -> impl Iterator<Item = String> + '_ {
        self.missing.iter().flatten().map(|(what, unit, compression, restitution)| {
            format!(
                "the {what} is undefined here: compression gave {} and restitution {} (a ratio needs a finite, \
                 positive compression integral)",
                super::described(*compression, unit),
                super::described(*restitution, unit)
            )
        })
    }
}

/// What a fixed-step scheme's report means: its events at the first step past them, its e beside the accurate one,
/// and the gap its energy balance leaves (its elastic force does not give back exactly the law's elastic energy).
fn fixed_step_note(report: &Report, method: &str, dt: f64) -> String {
    let (c, e) = (&report.contact, &report.energy);
    let steps = report.solver.steps;
    let mut note = format!(
        "fixed-step scheme `{method}` at dt = {} ({steps} steps): every quantity above is the scheme's, its events \
         taken at the first step past them as the peer codes take them, its impulses the scheme's sums of its force \
         kicks, and the reference errors are the scheme's errors",
        brief(dt, "s")
    );
    if let (Some(e_scheme), Some(e_accurate)) = (c.restitution_velocity_ratio, report.solver.restitution_continuous) {
        let difference = e_scheme - e_accurate;
        let (scheme, accurate) = apart(e_scheme, e_accurate, "");
        let sign = if difference > 0.0 { "+" } else { "" };
        note.push_str(&format!(
            "; e = {scheme} against {accurate} by the accurate path (difference {sign}{})",
            brief(difference, "")
        ));
    }
    if let (Some(after), Some(dissipated), Some(left), Some(work)) =
        (e.kinetic_after, e.dissipated, e.elastic_left_at_separation, e.work_of_immovable_bodies)
    {
        let gap = e.kinetic_before + work - after - dissipated - left;
        let scale = report.effective_mass * report.approach_speed * report.approach_speed;
        note.push_str(&format!(
            "; its energy balance does not close exactly (the discrete elastic force does not return the law's \
             elastic energy, and the damping's work is the scheme's sum): a gap of {}, {} of m* v0²",
            brief(gap, "J"),
            brief(gap / scale, "")
        ));
    }
    note
}

/// What the verdicts on the idealisation read: the report's own numbers.
pub(super) fn measured_by(
    report: &Report,
    friction: f64,
    speed_trial: SpeedTrial,
    levers: [Option<idealisation::Lever>; 2],
) -> idealisation::Measured {
    let c = &report.contact;
    let vector = |v: &Vec3| Vector3::from(*v);
    let pair = |of: &dyn Fn(&BodyReport) -> Vec3| report.bodies.each_ref().map(|b| vector(&of(b)));
    let after = |of: &dyn Fn(&BodyReport) -> Option<Vec3>| {
        let [a, b] = report.bodies.each_ref().map(of);
        Some([vector(&a?), vector(&b?)])
    };
    idealisation::Measured {
        duration: c.duration,
        max_penetration: c.max_penetration,
        max_force: c.max_force,
        deformation_impulse: c.deformation_impulse,
        restitution_impulse: c.restitution_impulse,
        restitution: c.restitution_velocity_ratio,
        normal: vector(&report.normal),
        velocities_before: pair(&|b| b.velocity_before),
        velocities_after: after(&|b| b.velocity_after),
        spins_before: pair(&|b| b.angular_velocity_before),
        spins_after: after(&|b| b.angular_velocity_after),
        friction,
        friction_work: report.oblique.as_ref().and_then(|o| o.friction_work),
        kinetic_before: report.energy.kinetic_before,
        approach_speed: report.approach_speed,
        max_velocity_difference: report.instantaneous.as_ref().and_then(|i| i.max_velocity_difference),
        speed_trial,
        yielding: report.law.yield_pressure.zip(report.law.yield_speed),
        levers,
    }
}

/// How each turning body meets the normal at first contact: the normal's lever arm about its origin (mass centre or
/// pivot) and its radius of gyration about the axis of that moment.
fn levers(scene: &Scene, setup: &Setup) -> [Option<idealisation::Lever>; 2] {
    [0, 1].map(|i| {
        let body = &scene.bodies[i];
        if !body.rotates() || body.is_immovable() {
            return None;
        }
        let rigid = crate::setup::rigid_body(body, setup.positions[i]);
        let origin = body.pivot.unwrap_or(setup.positions[i]);
        let moment = (setup.positions[i] + body.contact_offset - origin).cross(&setup.normal);
        let arm = moment.norm();
        let inertia = rigid.inertia_about_pivot();
        let about = if arm > 0.0 {
            moment.dot(&(inertia * moment)) / (arm * arm)
        } else {
            inertia.symmetric_eigenvalues().min()
        };
        Some(idealisation::Lever {
            arm,
            gyration: (about / body.mass).sqrt(),
            effective_mass: setup.effective_masses[i],
            mass: body.mass,
            pivoted: body.pivot.is_some(),
        })
    })
}

/// The oblique section: null for a direct central impact without spin.
fn oblique(scene: &Scene, setup: &Setup, outcome: &Outcome, e: f64, friction_work: f64) -> Option<ObliqueReport> {
    let bodies = &scene.bodies;
    let spinning = bodies.iter().any(|body| body.angular_velocity != Vector3::zeros());
    let eccentric = setup.motion == Motion::Rigid;
    if setup.tangential_velocity == Vector3::zeros() && !spinning && !eccentric {
        return None;
    }
    let done = outcome.separated;
    let end = &outcome.end;
    let n = setup.normal;
    let v0 = setup.approach_speed;
    let slip = setup.initial_slip;
    let degrees = f64::to_degrees;
    // Components along the initial direction (the whole size when there was none).
    let along = |after: &Vector3<f64>, before: &Vector3<f64>| {
        let size = before.norm();
        if size > 0.0 { after.dot(before) / size } else { after.norm() }
    };
    let ratio = |after: &Vector3<f64>, before: &Vector3<f64>| {
        let size = before.norm();
        (size > 0.0).then(|| after.dot(before) / (size * size))
    };
    let relative_after = end.velocities[1] - end.velocities[0];
    let centre_after = relative_after - end.normal * relative_after.dot(&end.normal);
    let friction = scene.contact.friction;
    // Friction without slip (Motion::Normal) has its slip at rest from first contact, and holds the whole contact
    // below the Coulomb limit.
    let slip_rest_time = if setup.motion == Motion::Normal { Some(0.0) } else { outcome.slip_rest_time };
    // The regime of rigid-body theory (docs/oblique.md#the-regime): the contact slid throughout when its contact points
    // never stopped slipping, whatever its spring did under the Coulomb limit meanwhile.
    let regime = match slip_rest_time {
        _ if friction == 0.0 => "smooth",
        Some(_) => "sticking",
        None => "sliding",
    };
    // A graze: the force made less than half of the reversal of the normal velocity, the turning line of centres
    // the rest (docs/oblique.md#grazing-contacts).
    let slid_off = done && end.normal_impulse < 0.5 * setup.effective_mass * (v0 - end.rate);
    // The impulse of the pulling force: sliding friction rubs through the compressive impulse, J_n + J_t, and
    // under the magnitude cap through the pulling one as well, J_n + 2 J_t, where rigid-body theory knows J_n alone.
    let tensile_impulse = (friction > 0.0 && outcome.tensile_impulse.is_finite()).then_some(outcome.tensile_impulse);
    let rigid_body = done.then(|| {
        if eccentric {
            return eccentric_rigid_body(scene, setup, e, end);
        }
        let rigid = rigid_body_impact(bodies, &n, setup.effective_mass, e, friction, &slip, 0.0);
        let largest = |simulated: &[Vector3<f64>; 2], ideal: &[Vector3<f64>; 2]| {
            (0..2).map(|i| (simulated[i] - ideal[i]).amax()).fold(0.0, f64::max)
        };
        // The rigid contact points' relative velocity after, with arms r_i along the first normal.
        let arms = Setup::lever_arms(bodies, &n);
        let point = |i: usize| rigid.velocity_after[i] + rigid.angular_velocity_after[i].cross(&arms[i]);
        let relative = point(0) - point(1);
        let rigid_slip = relative - n * relative.dot(&n);
        let rigid_centres = rigid.velocity_after[1] - rigid.velocity_after[0];
        let rigid_centres = rigid_centres - n * rigid_centres.dot(&n);
        RigidBodyReport {
            rebound_from_normal_deg: degrees(along(&rigid_slip, &slip).atan2(e * v0)),
            tangential_restitution_centre: ratio(&rigid_centres, &setup.tangential_velocity),
            regime: rigid.regime.name().into(),
            velocity_after: [vec3(&rigid.velocity_after[0]), vec3(&rigid.velocity_after[1])],
            angular_velocity_after: [vec3(&rigid.angular_velocity_after[0]), vec3(&rigid.angular_velocity_after[1])],
            max_velocity_difference: largest(&end.velocities, &rigid.velocity_after),
            max_angular_velocity_difference: largest(&end.spins, &rigid.angular_velocity_after),
        }
    });
    Some(ObliqueReport {
        incidence_from_normal_deg: degrees(slip.norm().atan2(v0)),
        rebound_from_normal_deg: done.then(|| degrees(along(&end.slip, &slip).atan2(-end.rate))),
        tangential_restitution_centre: done.then(|| ratio(&centre_after, &setup.tangential_velocity)).flatten(),
        tangential_restitution_contact: done.then(|| ratio(&end.slip, &slip)).flatten(),
        friction_work: done.then_some(friction_work),
        friction,
        friction_cap: scene.contact.friction_cap.name(),
        tangential_unloading: scene.contact.tangential_unloading.name(),
        regime: regime.into(),
        below_friction_limit_duration: (friction > 0.0).then_some(if setup.motion == Motion::Normal {
            end.time
        } else {
            outcome.below_limit_duration
        }),
        slip_rest_time: slip_rest_time.filter(|_| friction > 0.0),
        normal_turn_deg: done.then(|| degrees(n.cross(&end.normal).norm().atan2(n.dot(&end.normal)))),
        normal_at_separation: done.then(|| vec3(&end.normal)),
        slid_off,
        tensile_impulse,
        rigid_body,
    })
}

/// Rigid-body theory of an eccentric or pivoted body's frictional impact with the simulated e
/// ([`crate::eccentric::frictional_impact`] at the contact point of first contact), against the simulated end.
fn eccentric_rigid_body(scene: &Scene, setup: &Setup, e: f64, end: &Snapshot) -> RigidBodyReport {
    let bodies = &scene.bodies;
    let n = setup.normal;
    let rigid = [0, 1].map(|i| crate::setup::rigid_body(&bodies[i], setup.positions[i]));
    let point = crate::setup::contact_points(bodies, &setup.positions, &n)[0].0;
    let friction = scene.contact.friction;
    let ideal = crate::eccentric::frictional_impact(&rigid, &point, &n, e, friction);
    let (velocities, spins, regime) = match ideal {
        Some(i) => (
            i.velocities_after,
            i.spins_after,
            match i.slide {
                crate::eccentric::Slide::Smooth => "smooth",
                crate::eccentric::Slide::Sticks => "sticking",
                crate::eccentric::Slide::Slides => "sliding",
            },
        ),
        None => ([rigid[0].velocity, rigid[1].velocity], [rigid[0].spin, rigid[1].spin], "smooth"),
    };
    let after = |i: usize| crate::eccentric::RigidBody { velocity: velocities[i], spin: spins[i], ..rigid[i] };
    let relative = after(0).point_velocity(&point) - after(1).point_velocity(&point);
    let rigid_slip = relative - n * relative.dot(&n);
    let slip = setup.initial_slip;
    let along = if slip.norm() > 0.0 { rigid_slip.dot(&slip) / slip.norm() } else { rigid_slip.norm() };
    let centres = velocities[1] - velocities[0];
    let centres = centres - n * centres.dot(&n);
    let tangential = setup.tangential_velocity;
    let largest = |simulated: &[Vector3<f64>; 2], ideal: &[Vector3<f64>; 2]| {
        (0..2).map(|i| (simulated[i] - ideal[i]).amax()).fold(0.0, f64::max)
    };
    RigidBodyReport {
        rebound_from_normal_deg: along.atan2(e * setup.approach_speed).to_degrees(),
        tangential_restitution_centre: (tangential.norm() > 0.0)
            .then(|| centres.dot(&tangential) / tangential.norm_squared()),
        regime: regime.into(),
        velocity_after: [vec3(&velocities[0]), vec3(&velocities[1])],
        angular_velocity_after: [vec3(&spins[0]), vec3(&spins[1])],
        max_velocity_difference: largest(&end.velocities, &velocities),
        max_angular_velocity_difference: largest(&end.spins, &spins),
    }
}

/// The direction of a velocity from the tangent plane of `normal`, degrees: 90 along the normal, negative towards
/// body 1; `None` at rest.
fn angle_from_tangent(velocity: &Vector3<f64>, normal: &Vector3<f64>) -> Option<f64> {
    let along = velocity.dot(normal);
    let across = (velocity - normal * along).norm();
    (velocity.norm() > 0.0).then(|| along.atan2(across).to_degrees())
}

/// Why the bodies did not part. `frictional`: the contact has a tangential spring, whose stiffness can also make
/// the equations stiff.
fn stuck_note(outcome: &Outcome, frictional: bool) -> String {
    let end = &outcome.end;
    let how = match &outcome.ending {
        Ending::Event(0) => "the penetration returned to zero with no separation speed".to_string(),
        Ending::Event(_) => "the relative motion died out".to_string(),
        Ending::TimeLimit => format!("the time limit ({TIME_LIMIT} elastic time units) was reached"),
        Ending::GaveUp(reason) => format!("the integration stopped ({reason}; {})", stiffness_causes(frictional)),
    };
    format!(
        "the bodies did not separate: {how} {} after first contact with penetration {} and penetration rate {} \
         still in contact",
        brief(end.time, "s"),
        brief(end.penetration, "m"),
        brief(end.rate, "m/s")
    )
}

/// Both bodies' velocities or spins.
type Pair = [Vector3<f64>; 2];

/// The instantaneous eccentric impact with restitution `e` (docs/references.md#eccentric-impact), beside the
/// simulated velocities and spins after when the bodies parted.
fn eccentric_report(scene: &Scene, setup: &Setup, e: f64, simulated: Option<(&Pair, &Pair)>) -> InstantaneousReport {
    let bodies = &scene.bodies;
    let n = setup.normal;
    let rigid = [0, 1].map(|i| crate::setup::rigid_body(&bodies[i], setup.positions[i]));
    // A point on the line of the normal force: a contact sphere's centre.
    let sphere = if bodies[0].is_flat() { 1 } else { 0 };
    let point = setup.positions[sphere] + bodies[sphere].contact_offset;
    let inverse = crate::setup::inverse_effective_masses(bodies, &setup.positions, &n);
    let approach = setup.approach_speed;
    let impulse = (1.0 + e) * approach * setup.effective_mass;
    let after = |i: usize, j: f64| -> (Vector3<f64>, Vector3<f64>, Vector3<f64>) {
        let body = &bodies[i];
        if !body.rotates() {
            return (body.velocity + n * (j * body.inverse_mass()), body.angular_velocity, Vector3::zeros());
        }
        rigid[i].after(&(n * j), &point)
    };
    let (v1, w1, p1) = after(0, -impulse);
    let (v2, w2, p2) = after(1, impulse);
    let velocity_after = [v1, v2];
    let spins_after = [w1, w2];
    let largest = |simulated: &[Vector3<f64>; 2], ideal: &[Vector3<f64>; 2]| {
        (0..2).map(|i| (simulated[i] - ideal[i]).amax()).fold(0.0, f64::max)
    };
    // The contact points share one normal velocity when the deformation impulse m* v0 has passed.
    let u1 = (bodies[0].velocity + bodies[0].angular_velocity.cross(&bodies[0].contact_offset)).dot(&n);
    InstantaneousReport {
        restitution: e,
        common_normal_velocity: u1 - approach * setup.effective_mass * inverse[0],
        velocity_after: [vec3(&v1), vec3(&v2)],
        energy_lost: 0.5 * setup.effective_mass * (1.0 - e * e) * approach * approach,
        max_velocity_difference: simulated.map(|(v, _)| largest(v, &velocity_after)),
        eccentric: Some(EccentricReport {
            effective_masses: setup.effective_masses,
            impulse,
            angular_velocity_after: [vec3(&w1), vec3(&w2)],
            pivot_impulse: [vec3(&p1), vec3(&p2)],
            max_angular_velocity_difference: simulated.map(|(_, w)| largest(w, &spins_after)),
        }),
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
        eccentric: None,
    }
}

fn vec3(v: &Vector3<f64>) -> Vec3 {
    [v.x, v.y, v.z]
}

#[cfg(test)]
mod tests {
    use super::{Ratios, energy_balance};
    use crate::report::{EnergyReport, balance_note, energy_balance_bound};

    /// A separated contact's balance, (kinetic before + work of immovable bodies - kinetic after - dissipated - left)
    /// over its largest term, and the note when it misses its bound.
    #[test]
    fn an_energy_balance_that_misses_its_bound_says_so() {
        let energy = |dissipated: f64| EnergyReport {
            kinetic_before: 6.25,
            kinetic_after: Some(0.28),
            dissipated: Some(dissipated),
            elastic_left_at_separation: Some(2.05),
            work_of_immovable_bodies: Some(0.0),
        };
        // Case 10014 of seed 424242 in aJ: 6.25 in, 0.28 + 5.48 + 2.05 = 7.81 out: -1.56 of 6.25, -0.2496.
        let relative = energy_balance(&energy(5.48)).expect("separated");
        assert!((relative - (6.25 - 7.81) / 6.25).abs() < 1e-15, "{relative}");
        let note = balance_note(relative, "the largest energy term", 1e-9).expect("a note");
        assert!(note.contains("-0.25 of the largest energy term") && note.contains("1e-9"), "{note}");
        // Closed to 1e-12 (dissipated 3.92 - 4e-12): no note.
        let closed = energy_balance(&energy(3.92 - 4e-12)).expect("separated");
        assert!(closed.abs() < 1e-11 && balance_note(closed, "it", 1e-9).is_none(), "{closed}");
        // Looser tolerances loosen the bound in proportion; the default's is 1e-9.
        assert_eq!(energy_balance_bound(1e-10, 1e-12), 1e-9);
        assert!((energy_balance_bound(1e-6, 1e-8) - 1e-5).abs() < 1e-20);
    }

    #[test]
    fn ratios_of_finite_positive_integrals_are_poisson_and_stronge() {
        // Restitution gave back 0.8 of the impulse and 0.25 of the work: Poisson's e 0.8, Stronge's sqrt(0.25) = 0.5.
        let ratios = Ratios::of(true, 2.0, 1.6, 4.0, 1.0);
        assert_eq!(ratios.impulse, Some(0.8));
        assert_eq!(ratios.energy, Some(0.5));
        assert_eq!(ratios.notes().count(), 0);
        // A work given back that rounds below zero is none; before separation there is no ratio, and no note.
        assert_eq!(Ratios::of(true, 2.0, 0.0, 4.0, -1e-30).energy, Some(0.0));
        let before = Ratios::of(false, 2.0, 1.6, 4.0, 1.0);
        assert_eq!((before.impulse, before.energy, before.notes().count()), (None, None, 0));
    }

    #[test]
    fn a_ratio_over_an_overflowed_or_empty_compression_is_null_with_a_note() {
        // inf/inf and 0/0 were NaN; each is now null, and a note gives both integrals.
        for (compression, restitution) in [(f64::INFINITY, f64::INFINITY), (0.0, 0.0), (f64::NAN, 1.0), (1.0, f64::NAN)]
        {
            let ratios = Ratios::of(true, 1.0, 0.5, compression, restitution);
            assert_eq!(ratios.energy, None, "{compression} {restitution}");
            assert_eq!(ratios.impulse, Some(0.5));
            let notes: Vec<String> = ratios.notes().collect();
            assert!(notes.len() == 1 && notes[0].contains("Stronge"), "{notes:?}");
            assert!(!notes[0].contains("NaN") && !notes[0].contains("inf J"), "{notes:?}");
        }
        let ratios = Ratios::of(true, 0.0, 0.0, 1.0, 0.5);
        assert_eq!(ratios.impulse, None);
        assert!(ratios.notes().any(|note| note.contains("Poisson") && note.contains("0 N s")));
    }
}
