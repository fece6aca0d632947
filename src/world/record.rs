//! What a world run keeps of each contact and of the run: the values its report is built from (SI).

use super::flight::Kinematic;
use crate::integrate::Counters;
use crate::law::{ContactLaw, Separation};
use nalgebra::{UnitQuaternion, Vector3};
use std::collections::{BTreeMap, BTreeSet};
use std::sync::atomic::{AtomicU64, Ordering};

/// One contact as it happened.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactRecord {
    /// Scene indices of the two bodies; the normal points from the first to the second.
    pub bodies: [usize; 2],
    /// The sphere of each body that touches (0 for a body of one sphere), `None` for a flat body's face.
    pub spheres: [Option<usize>; 2],
    /// The contact point at first touch, m (scene coordinates): on the first body's sphere along the normal.
    pub point: Vector3<f64>,
    /// From each body's origin (its mass centre, or its pivot) to the contact point at first touch, m.
    pub levers: [Vector3<f64>; 2],
    /// Each body's orientation at first touch (from the scene axes at t = 0).
    pub orientations_before: [UnitQuaternion<f64>; 2],
    /// Each body's angular momentum about its origin at first touch, kg m²/s.
    pub momenta_before: [Vector3<f64>; 2],
    /// The pair's effective mass at the contact point along the normal at first touch, kg (a rigid body's at its
    /// lever: docs/references.md#eccentric-impact).
    pub effective_mass: f64,
    /// The law with its damping resolved at this contact.
    pub law: ContactLaw,
    pub separation: Separation,
    /// The speed (m/s) the damping map was read at: the approach speed, or a floor for a contact that begins
    /// pushed rather than struck (docs/world.md#damping-of-successive-contacts).
    pub map_speed: f64,
    /// Scene time of first touch, s.
    pub start_time: f64,
    /// Unit normal at first touch.
    pub normal: Vector3<f64>,
    /// (v_i - v_j)·n at first touch, m/s.
    pub approach_speed: f64,
    /// Whether the bodies were already touching when the contact began — pushed together by another contact or by
    /// gravity rather than closing a gap: its velocity ratio is then undefined.
    pub pushed: bool,
    /// The two bodies' velocities at first touch, m/s.
    pub velocities_before: [Vector3<f64>; 2],
    /// The two bodies' angular velocities at first touch, rad/s.
    pub spins_before: [Vector3<f64>; 2],
    /// Coulomb coefficient of the contact (0: smooth).
    pub friction: f64,
    /// Scene time (s) at which a frictional contact's slip came to rest — its component along its direction at first
    /// touch fell through zero (its first touch for a contact without slip); `None` while it slides.
    pub slip_rest: Option<f64>,
    /// How many times a frictional contact switched between sticking and sliding.
    pub switches: u32,
    /// The law's elastic energy at the overlap the contact began on, J: zero for a contact that closes a gap or
    /// begins touching within the rounding of the positions; that of the overlap an earlier contact of the pair left
    /// when its force ended it, for one pressed again before the gap opened (the model gives that energy back).
    pub elastic_at_start: f64,
    /// At the deepest of the penetration's maxima (d' = 0).
    pub max_compression: Option<Compression>,
    /// Scene time (s) and value (N) of the largest compressive force.
    pub peak_force: Option<(f64, f64)>,
    /// Where the contact ended; `None` while it is active (when the run stopped).
    pub end: Option<Ending>,
    /// The integrals when the run stopped, for a contact still active then.
    pub at_stop: Option<Stop>,
    /// Indices of the other contacts active at some time during this one.
    pub overlapping: BTreeSet<usize>,
    /// The impulse (N s) each overlapping contact gave during its overlap with this one: its ∫ Fn dt from the later
    /// of the two first touches to the earlier of the two ends (or the run's stop), keyed by its index.
    pub overlap_impulses: BTreeMap<usize, f64>,
}

/// A contact still active when the run stopped, as it stood then (SI).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stop {
    /// ∫ Fn dt, N s.
    pub impulse: f64,
    /// ∫ Fn d' dt, J.
    pub work: f64,
    /// Work of the normal damping, J.
    pub dissipated: f64,
    /// Elastic energy of the normal spring, J.
    pub elastic: f64,
    /// ∫ Ft·slip dt, J (negative: taken from the motion).
    pub tangential_work: f64,
    /// Energy the tangential spring holds, J.
    pub tangential_elastic: f64,
}

/// A contact at its deepest penetration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Compression {
    /// Scene time, s.
    pub time: f64,
    /// Penetration, m.
    pub penetration: f64,
    /// ∫ Fn dt since first touch, N s.
    pub impulse: f64,
    /// ∫ Fn d' dt since first touch, J.
    pub work: f64,
    /// The normal velocity the two bodies share there (v_i·n), m/s.
    pub common_normal_velocity: f64,
}

/// A contact where it ended.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ending {
    /// Scene time, s.
    pub time: f64,
    /// ∫ Fn dt over the contact, N s.
    pub impulse: f64,
    /// ∫ Fn d' dt over the contact, J.
    pub work: f64,
    /// Work of the damping over the contact, J.
    pub dissipated: f64,
    /// The penetration rate at the end, m/s (negative: parting).
    pub rate: f64,
    /// Elastic energy the contact still holds at its end (a force separation of a law that pulls), J.
    pub elastic_left: f64,
    /// The bodies' overlap at the end, m: positive when the contact's force ended it before its penetration.
    pub penetration: f64,
    /// The two bodies' velocities at the end, m/s.
    pub velocities: [Vector3<f64>; 2],
    /// The two bodies' angular velocities at the end, rad/s.
    pub spins: [Vector3<f64>; 2],
    /// The two bodies' angular momenta about their origins at the end, kg m²/s.
    pub momenta: [Vector3<f64>; 2],
    /// ∫ Ft·slip dt over the contact, J (negative: taken from the motion; the spring's energy is released when the
    /// contact ends, so all of it is dissipated).
    pub tangential_work: f64,
}

/// Why a world run stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EndReason {
    /// `[world] end_time` was reached.
    EndTime,
    /// `[world] max_contacts` contacts had ended.
    MaxContacts,
    /// No two bodies can touch any more.
    NoMoreContacts,
    /// Every movable body rests in contacts that no longer separate.
    AtRest,
    /// The integration spent the run's step budget (a note says where).
    StepBudget,
}

impl EndReason {
    /// The report's spelling.
    pub fn name(self) -> &'static str {
        match self {
            EndReason::EndTime => "end_time",
            EndReason::MaxContacts => "max_contacts",
            EndReason::NoMoreContacts => "no_more_contacts",
            EndReason::AtRest => "at_rest",
            EndReason::StepBudget => "step_budget",
        }
    }
}

/// What a world run came to.
#[derive(Debug, Clone, PartialEq)]
pub struct WorldOutcome {
    /// Every contact, in order of first touch.
    pub contacts: Vec<ContactRecord>,
    pub end_reason: EndReason,
    /// Scene time when the run stopped, s.
    pub end_time: f64,
    /// Every body's position, velocity and spin when the run stopped.
    pub bodies: Vec<Kinematic>,
    /// Work done on the movable bodies by immovable ones (moving walls), J.
    pub immovable_work: f64,
    /// Work of gravity on the bodies of finite mass, J: summed from their displacements in each flight and segment
    /// (not from absolute positions, whose rounding grows with their distance from the origin).
    pub gravity_work: f64,
    /// The kinetic energy left in groups of bodies when they came to rest and were held still, J (below 1e-14 of
    /// their energy unit; counted with the dissipated energy).
    pub settled: f64,
    /// The integrator's work over the run.
    pub counters: Counters,
    /// The path that ran: `dop853` (the world's islands), or the two-body path of a world of two bodies.
    pub method: &'static str,
    /// What a reader should know about the run.
    pub notes: Vec<String>,
}

/// One contact at an instant of a run: its index (in order of first touch), its penetration (m) and normal force (N).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactSample {
    pub index: usize,
    pub penetration: f64,
    pub force: f64,
}

/// What watches a run as it goes: the instants of its series (every accepted step of the islands, every located
/// event, and instants of each flight, apexes included). Only a run asked for a series or figures has one.
pub trait Observer {
    /// Every body's state and the active contacts at scene time `time` (s).
    fn instant(&mut self, time: f64, bodies: &[Kinematic], contacts: &[ContactSample]);
}

/// How far a run has come, for a view that shows it while the run goes on (a terminal's progress line): the scene
/// time, the contacts ended and the steps taken, stored by the driver as each segment or flight ends. Relaxed atomics:
/// a reader on another thread sees recent values, each whole, and the driver pays three stores per segment.
#[derive(Debug, Default)]
pub struct Progress {
    /// The scene time's bits (an `f64`), s.
    time: AtomicU64,
    contacts: AtomicU64,
    steps: AtomicU64,
}

impl Progress {
    /// Stores scene time `time` (s), `contacts` ended and `steps` taken (accepted and rejected).
    pub fn record(&self, time: f64, contacts: u64, steps: u64) {
        self.time.store(time.to_bits(), Ordering::Relaxed);
        self.contacts.store(contacts, Ordering::Relaxed);
        self.steps.store(steps, Ordering::Relaxed);
    }

    /// The scene time last stored, s.
    pub fn time(&self) -> f64 {
        f64::from_bits(self.time.load(Ordering::Relaxed))
    }

    /// The contacts ended, as last stored.
    pub fn contacts(&self) -> u64 {
        self.contacts.load(Ordering::Relaxed)
    }

    /// The steps taken, as last stored.
    pub fn steps(&self) -> u64 {
        self.steps.load(Ordering::Relaxed)
    }
}

/// A list of indices for a note, its middle left out when long.
pub fn shorten(items: &[String]) -> String {
    if items.len() <= 8 {
        items.join(", ")
    } else {
        format!("{}, ... ({} in all), {}", items[..4].join(", "), items.len(), items[items.len() - 2..].join(", "))
    }
}
