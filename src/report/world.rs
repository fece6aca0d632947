//! The report of a world run (docs/report.md#world-runs): the world, every contact with the keys of one impact's
//! contact section, the bodies' final state, one energy balance for the whole run, and the sequential instantaneous
//! model beside the simulation. Built here, from the driver's outcome alone.

use super::{Vec3, maybe_infinite};
use crate::idealisation::{self, Idealisation, Measured, Neighbours, SpeedTrial, Surroundings, Worst};
use crate::law::Separation;
use crate::scene::{DampingSpec, WorldScene};
use crate::world::record::{Compression, ContactRecord, WorldOutcome};
use crate::world::sequential::{Sequential, sequential};
use nalgebra::{UnitQuaternion, Vector3};
use serde::Serialize;

/// Everything a world run measured.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WorldReport {
    pub title: String,
    pub world: WorldSection,
    /// The worst verdict over the contacts on each assumption of the instantaneous impact, with its contact's index
    /// (docs/idealisation.md#in-a-world); null where no contact was judged on it.
    pub idealisation: Idealisation<Worst>,
    /// Every contact, in order of first touch.
    pub contacts: Vec<WorldContact>,
    pub bodies: Vec<WorldBody>,
    pub energy: WorldEnergy,
    /// The textbook's answer: each contact alone and instantaneous, in the order they began.
    pub sequential: SequentialReport,
    pub solver: WorldSolver,
    /// Plain-language remarks.
    pub notes: Vec<String>,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WorldSection {
    /// m/s².
    pub gravity: Vec3,
    /// "end_time", "max_contacts", "no_more_contacts", "at_rest" (or "step_budget", an addition).
    pub end_reason: &'static str,
    /// Scene time when the run stopped, s.
    pub end_time: f64,
    /// How many contacts the run had.
    pub contacts: usize,
    /// How a damping map that depends on the approach speed applied to successive contacts (an addition):
    /// "each-contact" or "first-contact".
    pub damping_map: &'static str,
}

/// One contact: the keys of one impact's `contact` section (times in scene time), with its pair and motion.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WorldContact {
    /// Scene indices [i, j]; the normal points from body i to body j.
    pub bodies: [usize; 2],
    /// The sphere of each body that touches, [a, b]: its index among the body's `[[bodies.spheres]]` (0 for a body of
    /// one sphere), null for a flat body's face.
    pub spheres: [Option<usize>; 2],
    /// The contact point at first touch, m (scene coordinates).
    pub point: Vec3,
    /// The law's name (an addition).
    pub law: &'static str,
    /// The damping parameter it used, in the law's units (an addition).
    pub damping: f64,
    /// The speed its damping map was read at, m/s (an addition; docs/world.md#damping-of-successive-contacts).
    pub damping_map_speed: f64,
    /// Unit normal at first touch.
    pub normal: Vec3,
    /// (v_i - v_j)·n at first touch, m/s.
    pub approach_speed: f64,
    /// Whether the bodies were already touching when the contact began (pushed together by another contact or by
    /// gravity rather than closing a gap): its velocity ratio is then null.
    pub pushed: bool,
    pub start_time: f64,
    pub max_compression_time: f64,
    pub max_force_time: f64,
    pub end_time: Option<f64>,
    pub duration: Option<f64>,
    /// m.
    pub max_penetration: f64,
    /// N.
    pub max_force: f64,
    /// V0: the normal velocity both bodies share at the deepest penetration, m/s.
    pub common_normal_velocity: f64,
    /// ∫ F dt to the deepest penetration, N s.
    pub deformation_impulse: f64,
    /// ∫ F dt from there to the end, N s.
    pub restitution_impulse: Option<f64>,
    pub restitution_impulse_ratio: Option<f64>,
    /// Separation speed / approach speed; null also for a contact whose bodies began it already touching (pushed).
    pub restitution_velocity_ratio: Option<f64>,
    pub restitution_energy: Option<f64>,
    pub separated: bool,
    /// [v_i, v_j] at first touch, m/s.
    pub velocities_before: [Vec3; 2],
    /// [v_i, v_j] at separation, m/s.
    pub velocities_after: Option<[Vec3; 2]>,
    /// The overlap the bodies part at, m (an addition): zero unless the contact's force ended it while they still
    /// overlapped (a law that pulls, `separation = "force"`); null while in contact.
    pub penetration_at_separation: Option<f64>,
    /// The law's elastic energy at the overlap the contact began on, J (an addition): nonzero only for a contact
    /// pressed again on the overlap an earlier one, ended by its force, left (docs/world.md#the-driver).
    pub elastic_energy_at_start: f64,
    /// Indices of the other contacts active during this one.
    pub overlapping: Vec<usize>,
    /// Energy the tangential force dissipated over the contact (or so far, while active), J (an addition; included in
    /// `energy.dissipated`; zero for a smooth contact).
    pub friction_work: f64,
    /// "smooth", "sliding" (the contact points slid throughout) or "sticking" (their slip came to rest at some time),
    /// as one impact's `oblique.regime` (an addition).
    pub regime: &'static str,
    /// When the contact points' slip came to rest, s since first touch (0 for a contact without slip); null for a
    /// smooth or a sliding contact (an addition).
    pub slip_rest_time: Option<f64>,
    /// [ω_i, ω_j] at first touch, rad/s (an addition).
    pub angular_velocities_before: [Vec3; 2],
    /// [ω_i, ω_j] at separation, rad/s (an addition).
    pub angular_velocities_after: Option<[Vec3; 2]>,
    /// The verdicts on the idealisation of this contact (docs/idealisation.md#in-a-world).
    pub idealisation: Idealisation,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WorldBody {
    pub name: String,
    #[serde(serialize_with = "maybe_infinite")]
    pub mass: f64,
    /// m; a body of `[[bodies.spheres]]`: its bounding radius, the largest |offset| + radius.
    #[serde(serialize_with = "maybe_infinite")]
    pub radius: f64,
    /// Whether `radius` is a bounding radius (a body of `[[bodies.spheres]]`), for the readable report's label; the
    /// JSON leaves it out (docs/report.md says what `radius` is).
    #[serde(skip)]
    pub bounding: bool,
    pub velocity_before: Vec3,
    /// rad/s (an addition).
    pub angular_velocity_before: Vec3,
    pub position_before: Vec3,
    /// At the end of the run.
    pub velocity_after: Vec3,
    pub angular_velocity_after: Vec3,
    pub position_after: Vec3,
    /// The body's orientation at the end of the run, a unit quaternion [w, x, y, z] from the scene axes at t = 0
    /// ([1, 0, 0, 0] for a body whose orientation nobody reads: a sphere, a wall).
    pub orientation_after: [f64; 4],
    /// Its angular momentum about its mass centre at the end of the run, kg m²/s.
    pub angular_momentum_after: Vec3,
}

/// Energies of the whole run, J. `kinetic_before + gravity_work + work_of_immovable_bodies = kinetic_after +
/// dissipated + elastic_stored_at_end`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WorldEnergy {
    pub kinetic_before: f64,
    pub kinetic_after: f64,
    /// Work of the contacts' damping.
    pub dissipated: f64,
    /// Work of gravity on the bodies of finite mass, Σ m g·Δx over every flight and segment.
    pub gravity_work: f64,
    pub work_of_immovable_bodies: f64,
    /// Spring energy in the contacts still active at the end, plus what contacts ended by their force left in their
    /// spring.
    pub elastic_stored_at_end: f64,
    /// (in - out) / the largest energy in play (an addition): the balance's closure.
    pub balance: f64,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SequentialReport {
    /// With each pair's nominal e; null when a pair has none (its damping given as a parameter).
    pub nominal: Option<SequentialModel>,
    /// With each contact's simulated e (its velocity ratio; its impulse ratio for a contact that began without
    /// approach).
    pub simulated_e: Option<SequentialModel>,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SequentialModel {
    /// One vector per body, m/s.
    pub velocity_after: Vec<Vec3>,
    /// Largest |simulated - sequential| velocity component, m/s.
    pub max_velocity_difference: f64,
    /// One angular velocity per body, rad/s (an addition: friction turns the bodies in the model too).
    pub angular_velocity_after: Vec<Vec3>,
    /// [v_i, v_j] right after each contact in the model, in the order of `contacts`, m/s (an addition).
    pub contact_velocities_after: Vec<[Vec3; 2]>,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WorldSolver {
    pub method: &'static str,
    pub rtol: f64,
    pub atol: f64,
    pub steps: u64,
    pub rejected_steps: u64,
    pub force_evaluations: u64,
    pub wall_time_s: f64,
}

fn vec3(v: &Vector3<f64>) -> Vec3 {
    [v.x, v.y, v.z]
}

/// A unit quaternion as [w, x, y, z].
fn quaternion(q: &UnitQuaternion<f64>) -> [f64; 4] {
    [q.w, q.i, q.j, q.k]
}

/// A body's angular momentum about its mass centre, kg m²/s, spinning at `spin` (rad/s) turned by `orientation` from
/// the scene axes at t = 0 (its inertia tensor turns with it); zero for a body that does not turn.
fn spin_momentum(body: &crate::body::Body, spin: &Vector3<f64>, orientation: &UnitQuaternion<f64>) -> Vector3<f64> {
    if body.is_immovable() || !body.rotates() || *spin == Vector3::zeros() {
        return Vector3::zeros();
    }
    match body.inertia_tensor {
        Some(_) => crate::world::island::turned_inertia(body, orientation) * spin,
        None => spin * body.inertia,
    }
}

/// The report of a world run.
pub fn build(scene: &WorldScene, outcome: &WorldOutcome, wall_time: f64) -> WorldReport {
    let mut contacts: Vec<WorldContact> = outcome.contacts.iter().map(contact).collect();
    let verdicts = judge_all(scene, outcome, &contacts);
    for (contact, verdicts) in contacts.iter_mut().zip(verdicts) {
        contact.idealisation = verdicts;
    }
    let bodies = scene
        .bodies
        .iter()
        .zip(&outcome.bodies)
        .map(|(body, end)| WorldBody {
            name: body.name.clone(),
            mass: body.mass,
            radius: body.radius,
            bounding: !body.spheres.is_empty(),
            velocity_before: vec3(&body.velocity),
            angular_velocity_before: vec3(&body.angular_velocity),
            position_before: vec3(&body.position.unwrap_or_default()),
            velocity_after: vec3(&end.velocity),
            angular_velocity_after: vec3(&end.spin),
            position_after: vec3(&end.position),
            orientation_after: quaternion(&end.orientation),
            angular_momentum_after: vec3(&spin_momentum(body, &end.spin, &end.orientation)),
        })
        .collect();
    let nominal = |record: &ContactRecord| {
        let (spec, _) = scene.contact_of(record.bodies[0], record.bodies[1]);
        match spec.damping {
            // A yielding law has no nominal e: its e follows from each contact's speed.
            DampingSpec::None if record.law.yields() => None,
            DampingSpec::None => Some(1.0),
            DampingSpec::Restitution(e) => Some(e),
            DampingSpec::Parameter(_) => None,
        }
    };
    let simulated = |record: &ContactRecord| {
        let c = contact(record);
        c.restitution_velocity_ratio.or(c.restitution_impulse_ratio).or_else(|| nominal(record))
    };
    let model = |model: Option<Sequential>| {
        model.map(|s| SequentialModel {
            velocity_after: s.velocity_after.iter().map(vec3).collect(),
            max_velocity_difference: s.max_velocity_difference,
            angular_velocity_after: s.spin_after.iter().map(vec3).collect(),
            contact_velocities_after: s.contact_velocities_after.iter().map(|[a, b]| [vec3(a), vec3(b)]).collect(),
        })
    };
    let mut notes = outcome.notes.clone();
    let pushed: Vec<String> =
        outcome.contacts.iter().enumerate().filter(|(_, r)| r.pushed).map(|(k, _)| k.to_string()).collect();
    if !pushed.is_empty() {
        notes.push(format!(
            "contact{} {} began with the bodies already touching, pushed together rather than closing a gap: {} \
             velocity ratio is undefined (null), and {} impulse ratio stands for e in the sequential model",
            if pushed.len() > 1 { "s" } else { "" },
            shorten(&pushed),
            if pushed.len() > 1 { "their" } else { "its" },
            if pushed.len() > 1 { "their" } else { "its" },
        ));
    }
    let repressed: Vec<String> = outcome
        .contacts
        .iter()
        .enumerate()
        .filter(|(_, r)| r.elastic_at_start > 0.0)
        .map(|(k, _)| k.to_string())
        .collect();
    if !repressed.is_empty() {
        notes.push(format!(
            "contact{} {} began on the overlap an earlier contact of {} pair left when its force ended it (the gap \
             never opened): the spring energy of that overlap is given back (elastic_energy_at_start)",
            if repressed.len() > 1 { "s" } else { "" },
            shorten(&repressed),
            if repressed.len() > 1 { "their" } else { "its" },
        ));
    }
    let energy = energy(scene, outcome);
    let bound = super::energy_balance_bound(scene.solver.tolerances.rtol, scene.solver.tolerances.atol);
    if let Some(note) = super::balance_note(energy.balance, "the largest energy in play", bound) {
        notes.push(note);
    }
    let undefined: Vec<String> = contacts
        .iter()
        .enumerate()
        .filter(|(_, c)| c.separated && (c.restitution_impulse_ratio.is_none() || c.restitution_energy.is_none()))
        .map(|(k, _)| k.to_string())
        .collect();
    if !undefined.is_empty() {
        notes.push(format!(
            "contact{} {}: Poisson's or Stronge's e is undefined (null), its compression impulse or work zero or beyond \
             double precision",
            if undefined.len() > 1 { "s" } else { "" },
            shorten(&undefined),
        ));
    }
    WorldReport {
        title: scene.title.clone(),
        world: WorldSection {
            gravity: vec3(&scene.world.gravity),
            end_reason: outcome.end_reason.name(),
            end_time: outcome.end_time,
            contacts: contacts.len(),
            damping_map: scene.world.damping_map.name(),
        },
        idealisation: idealisation::worst(&contacts.iter().map(|c| &c.idealisation).collect::<Vec<_>>()),
        contacts,
        bodies,
        energy,
        sequential: SequentialReport {
            nominal: model(sequential(scene, outcome, nominal)),
            simulated_e: model(sequential(scene, outcome, simulated)),
        },
        solver: WorldSolver {
            method: outcome.method,
            rtol: scene.solver.tolerances.rtol,
            atol: scene.solver.tolerances.atol,
            steps: outcome.counters.steps,
            rejected_steps: outcome.counters.rejected_steps,
            force_evaluations: outcome.counters.evaluations,
            wall_time_s: wall_time,
        },
        notes,
    }
}

use crate::world::record::shorten;

/// One contact's report values from its record.
fn contact(record: &ContactRecord) -> WorldContact {
    // (The driver gives every contact a deepest point: located, or where it stood when the run stopped.)
    let max = record.max_compression.unwrap_or(Compression {
        time: record.start_time,
        penetration: 0.0,
        impulse: 0.0,
        work: 0.0,
        common_normal_velocity: record.velocities_before[0].dot(&record.normal),
    });
    let end = record.end.as_ref();
    let separated = end.is_some();
    let (peak_time, peak) = record.peak_force.unwrap_or((record.start_time, 0.0));
    let restitution_impulse = end.map(|e| e.impulse - max.impulse);
    // (A ratio over a zero or overflowed denominator is none, never NaN: the report's notes say which contacts.)
    let ratio = |numerator: f64, denominator: f64| {
        (denominator > 0.0).then(|| numerator / denominator).filter(|r| r.is_finite())
    };
    WorldContact {
        bodies: record.bodies,
        spheres: record.spheres,
        point: vec3(&record.point),
        law: record.law.kind.name(),
        damping: record.law.damping,
        damping_map_speed: record.map_speed,
        normal: vec3(&record.normal),
        approach_speed: record.approach_speed,
        pushed: record.pushed,
        start_time: record.start_time,
        max_compression_time: max.time,
        max_force_time: peak_time,
        end_time: end.map(|e| e.time),
        duration: end.map(|e| e.time - record.start_time),
        max_penetration: max.penetration,
        max_force: peak,
        common_normal_velocity: max.common_normal_velocity,
        deformation_impulse: max.impulse,
        restitution_impulse,
        restitution_impulse_ratio: restitution_impulse.and_then(|r| ratio(r, max.impulse)),
        restitution_velocity_ratio: end.filter(|_| !record.pushed).and_then(|e| ratio(-e.rate, record.approach_speed)),
        restitution_energy: end.and_then(|e| ratio((max.work - e.work).max(0.0), max.work)).map(f64::sqrt),
        separated,
        velocities_before: [vec3(&record.velocities_before[0]), vec3(&record.velocities_before[1])],
        velocities_after: end.map(|e| [vec3(&e.velocities[0]), vec3(&e.velocities[1])]),
        penetration_at_separation: end.map(|e| e.penetration.max(0.0)),
        elastic_energy_at_start: record.elastic_at_start,
        overlapping: record.overlapping.iter().copied().collect(),
        friction_work: friction_work(record),
        regime: if record.friction == 0.0 {
            "smooth"
        } else if record.slip_rest.is_none() {
            "sliding"
        } else {
            "sticking"
        },
        slip_rest_time: record.slip_rest.map(|at| at - record.start_time),
        angular_velocities_before: [vec3(&record.spins_before[0]), vec3(&record.spins_before[1])],
        angular_velocities_after: end.map(|e| [vec3(&e.spins[0]), vec3(&e.spins[1])]),
        idealisation: Idealisation::default(),
    }
}

/// Two bodies in order, each with the sphere of it that touches (None for a body of one sphere or a wall).
type PairOfSpheres = ([usize; 2], [Option<usize>; 2]);

/// The contact's pair of bodies and spheres, the same whichever body the record names first.
fn pair_of_spheres(record: &crate::world::record::ContactRecord) -> PairOfSpheres {
    let [i, j] = record.bodies;
    let [a, b] = record.spheres;
    if i <= j { ([i, j], [a, b]) } else { ([j, i], [b, a]) }
}

/// Each contact's verdicts on the idealisation: its own numbers (`contacts`, built from the records) and what the run
/// measured around it — the flight to its bodies' next contact, gravity, the contacts overlapping it, the pair's
/// contacts at other speeds. Arithmetic on the records, O(n log n) in the number of contacts: nothing runs again.
fn judge_all(scene: &WorldScene, outcome: &WorldOutcome, contacts: &[WorldContact]) -> Vec<Idealisation> {
    // Each body's contacts, in order of first touch (the records' order).
    let mut of_body: Vec<Vec<usize>> = vec![Vec::new(); scene.bodies.len()];
    // Each pair's contacts with an e, by approach speed: (speed, index, e). A pair is two bodies and, for rigid bodies
    // of several spheres, the sphere of each that touches: a rod's two ends meet the floor with different effective
    // masses, so their e at different speeds say nothing of one contact's dependence on speed.
    let mut of_pair: std::collections::HashMap<PairOfSpheres, Vec<(f64, usize, f64)>> = Default::default();
    for (k, (record, c)) in outcome.contacts.iter().zip(contacts).enumerate() {
        let [i, j] = record.bodies;
        of_body[i].push(k);
        of_body[j].push(k);
        if let Some(e) = c.restitution_velocity_ratio.filter(|e| *e > 0.0) {
            of_pair.entry(pair_of_spheres(record)).or_default().push((c.approach_speed, k, e));
        }
    }
    for speeds in of_pair.values_mut() {
        speeds.sort_by(|a, b| a.0.total_cmp(&b.0));
    }
    (0..contacts.len())
        .map(|k| {
            let [i, j] = outcome.contacts[k].bodies;
            let movable: Vec<usize> = [i, j].into_iter().filter(|&b| !scene.bodies[b].is_immovable()).collect();
            let pair = of_pair.get(&pair_of_spheres(&outcome.contacts[k])).map_or(&[][..], |p| p.as_slice());
            judge(scene, outcome, contacts, k, &movable, |b| &of_body[b], pair)
        })
        .collect()
}

/// Contact `k`'s verdicts, its `movable` bodies' contacts given by `of_body`, its pair's contacts with an e (by
/// approach speed) in `pair`.
fn judge<'a>(
    scene: &WorldScene,
    outcome: &WorldOutcome,
    contacts: &[WorldContact],
    k: usize,
    movable: &[usize],
    of_body: impl Fn(usize) -> &'a [usize],
    pair: &[(f64, usize, f64)],
) -> Idealisation {
    let (record, c) = (&outcome.contacts[k], &contacts[k]);
    let [i, j] = record.bodies;
    let bodies = [&scene.bodies[i], &scene.bodies[j]];
    // The first touch of a movable body of the pair after this contact ends (a body's contacts are in order of
    // first touch).
    let flight = c.end_time.and_then(|end| {
        let next = movable
            .iter()
            .filter_map(|&b| {
                let list = of_body(b);
                let at = list.partition_point(|&m| outcome.contacts[m].start_time < end);
                list[at..].iter().find(|&&m| m != k).map(|&m| outcome.contacts[m].start_time)
            })
            .fold(f64::INFINITY, f64::min);
        Some(next - end).filter(|flight| flight.is_finite() && *flight > 0.0)
    });
    let shares = |other: &ContactRecord| other.bodies.iter().any(|b| movable.contains(b));
    let mut whole = false;
    let others: Vec<(usize, f64)> = record
        .overlapping
        .iter()
        .filter(|&&m| shares(&outcome.contacts[m]))
        .map(|&m| {
            let during = record.overlap_impulses.get(&m).copied();
            whole |= during.is_none();
            let other = &outcome.contacts[m];
            let total = other.end.map(|e| e.impulse).or(other.at_stop.map(|s| s.impulse)).unwrap_or(0.0);
            (m, during.unwrap_or(total))
        })
        .collect();
    let held = bodies.iter().any(|b| b.is_immovable()) || !others.is_empty();
    // The pair's contacts with an e at the nearest approach speeds below and above this one's.
    let here = c.approach_speed;
    let below = pair.partition_point(|p| p.0 < here * (1.0 - 1e-9));
    let above = pair.partition_point(|p| p.0 <= here * (1.0 + 1e-9));
    let entry = |p: &(f64, usize, f64)| (p.1, p.0, p.2);
    let mut speeds = Neighbours {
        slower: below.checked_sub(1).map(|b| entry(&pair[b])),
        faster: pair.get(above).map(entry),
        remapped: false,
    };
    let damping = |m: usize| outcome.contacts[m].law.damping;
    speeds.remapped = [speeds.slower, speeds.faster].iter().flatten().any(|s| damping(s.0) != record.law.damping);
    let around = Surroundings { flight, gravity: scene.world.gravity, held, others, whole, speeds };
    let [a, b] = [0, 1].map(|side| contact_body(bodies[side], record.spheres[side]));
    idealisation::judge_in_world([&a, &b], &measured(scene, record, c), &around)
}

/// A body as one contact meets it: a clump of several spheres meets it with the touching sphere, so the lengths the
/// verdicts compare with (R, R*, the contact radius) are that sphere's, not the clump's bounding radius. (A body of
/// one sphere is that sphere already.)
fn contact_body(body: &crate::body::Body, sphere: Option<usize>) -> crate::body::Body {
    let mut contact = body.clone();
    if let Some(touching) = sphere.and_then(|s| body.spheres.get(s)) {
        contact.radius = touching.radius;
    }
    contact
}

/// What the verdicts read of one contact of a world: its report values, and the pair's kinetic energy at first touch.
fn measured(scene: &WorldScene, record: &ContactRecord, c: &WorldContact) -> Measured {
    let [i, j] = record.bodies;
    let (a, b) = (&scene.bodies[i], &scene.bodies[j]);
    let kinetic = |body: &crate::body::Body, k: usize| {
        if body.is_immovable() {
            0.0
        } else {
            body.kinetic_energy(&record.velocities_before[k], &record.spins_before[k])
        }
    };
    let pair = |v: &[Vec3; 2]| [Vector3::from(v[0]), Vector3::from(v[1])];
    // A yielding law (`thornton`): its yield pressure, and the yield speed its yield penetration gives this pair.
    let yielding = record.law.yields().then(|| {
        let (spec, _) = scene.contact_of(i, j);
        let pressure = crate::setup::yield_pressure(spec, [a, b])?;
        let mass = crate::geometry::effective_mass(a, b)?;
        let length =
            crate::scales::Scales::new(mass, record.law.stiffness, record.law.exponent, c.approach_speed).length;
        let speed = crate::reference::thornton_yield_speed(record.law.yield_penetration / length) * c.approach_speed;
        Some((pressure, speed))
    });
    Measured {
        duration: c.duration,
        max_penetration: c.max_penetration,
        max_force: c.max_force,
        deformation_impulse: c.deformation_impulse,
        restitution_impulse: c.restitution_impulse,
        restitution: c.restitution_velocity_ratio,
        normal: record.normal,
        velocities_before: record.velocities_before,
        velocities_after: c.velocities_after.as_ref().map(pair),
        spins_before: record.spins_before,
        spins_after: c.angular_velocities_after.as_ref().map(pair),
        friction: record.friction,
        friction_work: Some(c.friction_work),
        kinetic_before: kinetic(a, 0) + kinetic(b, 1),
        approach_speed: c.approach_speed,
        max_velocity_difference: None,
        speed_trial: SpeedTrial { slower: None, faster: None },
        yielding: yielding.flatten(),
        levers: [0, 1].map(|side| lever(scene, record, side)),
    }
}

/// How side `side`'s body of a contact meets its normal at first touch, for the `central` verdict: a rigid body's
/// lever arm of the normal about its origin (mass centre or pivot), its radius of gyration about the axis of that
/// moment with the inertia turned as the body was then, and its effective mass at the contact point
/// (docs/world.md#rigid-bodies). `None` for a sphere or a wall, whose normal passes through its centre.
fn lever(scene: &WorldScene, record: &ContactRecord, side: usize) -> Option<crate::idealisation::Lever> {
    let body = &scene.bodies[record.bodies[side]];
    if !body.is_rigid() {
        return None;
    }
    let orientation = record.orientations_before[side];
    let origin = record.point - record.levers[side];
    let centre = match body.pivot {
        Some(pivot) => pivot + orientation * (body.position.unwrap_or_default() - pivot),
        None => origin,
    };
    let rigid = crate::eccentric::RigidBody {
        mass: body.mass,
        inertia: crate::world::island::turned_inertia(body, &orientation),
        centre,
        velocity: Vector3::zeros(),
        spin: Vector3::zeros(),
        pivot: body.pivot,
    };
    // (The normal's moment: the arm to the contact point differs from the arm to the sphere's centre by a multiple
    // of the normal.)
    let moment = record.levers[side].cross(&record.normal);
    let arm = moment.norm();
    let inertia = rigid.inertia_about_pivot();
    let about =
        if arm > 0.0 { moment.dot(&(inertia * moment)) / (arm * arm) } else { inertia.symmetric_eigenvalues().min() };
    Some(crate::idealisation::Lever {
        arm,
        gyration: (about / body.mass).sqrt(),
        effective_mass: 1.0 / rigid.inverse_effective_mass(&record.point, &record.normal),
        mass: body.mass,
        pivoted: body.pivot.is_some(),
    })
}

/// The energy a contact's tangential force dissipated, J: what it took from the motion, less what its spring still
/// holds (nothing once the contact has ended: the spring lets go).
fn friction_work(record: &ContactRecord) -> f64 {
    match (&record.end, &record.at_stop) {
        (Some(end), _) => -end.tangential_work,
        (None, Some(stop)) => -stop.tangential_work - stop.tangential_elastic,
        (None, None) => 0.0,
    }
}

/// The run's energy balance.
fn energy(scene: &WorldScene, outcome: &WorldOutcome) -> WorldEnergy {
    let mut kinetic_before = 0.0;
    let mut kinetic_after = 0.0;
    for (body, end) in scene.bodies.iter().zip(&outcome.bodies) {
        if body.is_immovable() {
            continue;
        }
        kinetic_before += body.kinetic_energy(&body.velocity, &body.angular_velocity);
        kinetic_after += body.kinetic_energy_turned(&end.velocity, &end.spin, &end.orientation);
    }
    let gravity_work = outcome.gravity_work;
    let mut dissipated = outcome.settled;
    let mut elastic = 0.0;
    for record in &outcome.contacts {
        // A contact pressed again on the overlap an earlier one left takes that spring energy back.
        elastic -= record.elastic_at_start;
        dissipated += friction_work(record);
        match (&record.end, record.at_stop) {
            (Some(end), _) => {
                dissipated += end.dissipated;
                if record.separation == Separation::Force {
                    elastic += end.elastic_left;
                }
            }
            (None, Some(stop)) => {
                dissipated += stop.dissipated;
                elastic += stop.elastic + stop.tangential_elastic;
            }
            (None, None) => {}
        }
    }
    let work = outcome.immovable_work;
    let supplied = kinetic_before + gravity_work + work;
    let used = kinetic_after + dissipated + elastic;
    let largest = [kinetic_before, kinetic_after, gravity_work.abs(), work.abs(), dissipated, elastic]
        .into_iter()
        .fold(0.0, f64::max);
    WorldEnergy {
        kinetic_before,
        kinetic_after,
        dissipated,
        gravity_work,
        work_of_immovable_bodies: work,
        elastic_stored_at_end: elastic,
        balance: if largest > 0.0 { (supplied - used) / largest } else { 0.0 },
    }
}

/// The report of a world of two bodies without gravity, from today's report of its one impact: the contact's values
/// are that impact's, to the bit (docs/world.md#two-bodies).
pub fn from_impact(scene: &WorldScene, impact: &super::Report) -> WorldReport {
    let c = &impact.contact;
    let velocities = |after: bool| {
        let v = |i: usize| {
            let body = &impact.bodies[i];
            if after { body.velocity_after.unwrap_or(body.velocity_before) } else { body.velocity_before }
        };
        [v(0), v(1)]
    };
    let sphere = |k: usize| (!scene.bodies[k].is_flat()).then_some(0);
    let first = Vector3::from(impact.bodies[0].position_at_first_contact);
    let point = if scene.bodies[0].is_flat() {
        Vector3::from(impact.bodies[1].position_at_first_contact)
            - Vector3::from(impact.normal) * scene.bodies[1].radius
    } else {
        first + Vector3::from(impact.normal) * scene.bodies[0].radius
    };
    let contact = WorldContact {
        bodies: [0, 1],
        spheres: [sphere(0), sphere(1)],
        point: vec3(&point),
        law: impact.law.name,
        damping: impact.law.damping,
        damping_map_speed: impact.approach_speed,
        normal: impact.normal,
        approach_speed: impact.approach_speed,
        pushed: false,
        start_time: c.start_time,
        max_compression_time: c.max_compression_time,
        max_force_time: c.max_force_time,
        end_time: c.end_time,
        duration: c.duration,
        max_penetration: c.max_penetration,
        max_force: c.max_force,
        common_normal_velocity: c.common_normal_velocity,
        deformation_impulse: c.deformation_impulse,
        restitution_impulse: c.restitution_impulse,
        restitution_impulse_ratio: c.restitution_impulse_ratio,
        restitution_velocity_ratio: c.restitution_velocity_ratio,
        restitution_energy: c.restitution_energy,
        separated: c.separated,
        velocities_before: velocities(false),
        velocities_after: c.separated.then(|| velocities(true)),
        penetration_at_separation: c.separated.then(|| {
            let at = |k: usize| Vector3::from(impact.bodies[k].position_at_separation.unwrap_or_default());
            scene.meeting(0, 1).penetration(&(at(1) - at(0))).0.max(0.0)
        }),
        elastic_energy_at_start: 0.0,
        overlapping: Vec::new(),
        // (A frictional pair runs in the world's driver: this one is smooth.)
        friction_work: 0.0,
        regime: "smooth",
        slip_rest_time: None,
        angular_velocities_before: [impact.bodies[0].angular_velocity_before, impact.bodies[1].angular_velocity_before],
        angular_velocities_after: c.separated.then(|| {
            let spin = |k: usize| {
                let body = &impact.bodies[k];
                body.angular_velocity_after.unwrap_or(body.angular_velocity_before)
            };
            [spin(0), spin(1)]
        }),
        idealisation: Idealisation::default(),
    };
    let contact = WorldContact { idealisation: one_impact_verdicts(scene, impact), ..contact };
    let bodies = scene
        .bodies
        .iter()
        .zip(&impact.bodies)
        .map(|(body, report)| WorldBody {
            name: body.name.clone(),
            mass: body.mass,
            radius: body.radius,
            bounding: !body.spheres.is_empty(),
            velocity_before: report.velocity_before,
            angular_velocity_before: report.angular_velocity_before,
            position_before: vec3(&body.position.unwrap_or_default()),
            velocity_after: report.velocity_after.unwrap_or(report.velocity_before),
            angular_velocity_after: report.angular_velocity_after.unwrap_or(report.angular_velocity_before),
            position_after: report.position_at_separation.unwrap_or(report.position_at_first_contact),
            // (A world of two bodies runs as one impact only when neither turns: spheres and walls.)
            orientation_after: [1.0, 0.0, 0.0, 0.0],
            angular_momentum_after: vec3(&spin_momentum(
                body,
                &Vector3::from(report.angular_velocity_after.unwrap_or(report.angular_velocity_before)),
                &UnitQuaternion::identity(),
            )),
        })
        .collect();
    let e = &impact.energy;
    let (after, dissipated, left, work) = (
        e.kinetic_after.unwrap_or(f64::NAN),
        e.dissipated.unwrap_or(f64::NAN),
        e.elastic_left_at_separation.unwrap_or(f64::NAN),
        e.work_of_immovable_bodies.unwrap_or(0.0),
    );
    let largest = [e.kinetic_before, after, work.abs(), dissipated, left].into_iter().fold(0.0, f64::max);
    let model = |ideal: &Option<super::InstantaneousReport>| {
        ideal.as_ref().map(|ideal| SequentialModel {
            velocity_after: ideal.velocity_after.to_vec(),
            max_velocity_difference: ideal.max_velocity_difference.unwrap_or(f64::NAN),
            // A smooth impact leaves the spins as they were.
            angular_velocity_after: impact.bodies.iter().map(|b| b.angular_velocity_before).collect(),
            contact_velocities_after: vec![ideal.velocity_after],
        })
    };
    let s = &impact.solver;
    WorldReport {
        title: scene.title.clone(),
        world: WorldSection {
            gravity: [0.0; 3],
            end_reason: "no_more_contacts",
            end_time: c.end_time.unwrap_or(c.start_time),
            contacts: 1,
            damping_map: scene.world.damping_map.name(),
        },
        idealisation: idealisation::worst(&[&contact.idealisation]),
        contacts: vec![contact],
        bodies,
        energy: WorldEnergy {
            kinetic_before: e.kinetic_before,
            kinetic_after: after,
            dissipated,
            gravity_work: 0.0,
            work_of_immovable_bodies: work,
            elastic_stored_at_end: left,
            balance: if largest > 0.0 { (e.kinetic_before + work - after - dissipated - left) / largest } else { 0.0 },
        },
        sequential: SequentialReport {
            nominal: model(&impact.instantaneous_nominal),
            simulated_e: model(&impact.instantaneous),
        },
        solver: WorldSolver {
            method: s.method,
            rtol: s.rtol,
            atol: s.atol,
            steps: s.steps,
            rejected_steps: s.rejected_steps,
            force_evaluations: s.force_evaluations,
            wall_time_s: s.wall_time_s,
        },
        notes: impact.notes.clone(),
    }
}

/// The verdicts on the one contact of a world of two bodies without gravity, run as one impact: the world's measures
/// (no gravity, no other contact, no next contact: the relative travel against the radius), and the impact's own
/// `constant_e` trial (its two runs at 0.9 and 1.1 times the speed; the pair has no other contact to compare with).
fn one_impact_verdicts(scene: &WorldScene, impact: &super::Report) -> Idealisation {
    let bodies = [&scene.bodies[0], &scene.bodies[1]];
    let measured = super::build::measured_by(impact, 0.0, SpeedTrial { slower: None, faster: None }, [None, None]);
    let around = Surroundings {
        flight: None,
        gravity: Vector3::zeros(),
        held: bodies.iter().any(|b| b.is_immovable()),
        others: Vec::new(),
        whole: false,
        speeds: Neighbours::default(),
    };
    let verdicts = idealisation::judge_in_world(bodies, &measured, &around);
    Idealisation { constant_e: impact.idealisation.constant_e.clone(), ..verdicts }
}
