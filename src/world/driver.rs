//! The event-driven world: free flight in closed form until two bodies touch, then the island of the bodies that
//! active contacts couple, integrated until a contact begins or ends, and so on until the run's end
//! (docs/world.md#the-driver).
//!
//! Every contact is located as one impact's is: its first touch exactly in flight (a root of the flight's polynomial)
//! or, inside an island, as an event on the solution (a watched pair's gap falling through zero); its maximum
//! compression, force peak and separation as events of its own. A segment of an island ends at the first contact
//! that begins or ends; contacts that begin or end at that same instant (a symmetric arrangement) are taken then too.

use super::broad::{Neighbours, skin};
use super::coast::{CAP_GRAZE, Coast};
use super::flight::{Kinematic, acceleration, first_touch};
use super::island::{ActiveContact, Island, Units, rigid_body_at};
use super::record::{
    Compression, ContactRecord, ContactSample, EndReason, Ending as ContactEnding, Observer, Progress, Stop,
    WorldOutcome,
};
use super::sites::Sites;
use crate::dynamics::contact::{Mode, Tangential};
use crate::geometry::Meeting;
use crate::integrate::{Counters, Direction, Ending, EventOf, IntegrationError, StepperOf, Tolerances};
use crate::law::Separation;
use crate::scene::SetupError;
use crate::scene::{DampingMap, DampingSpec, WorldScene};
use crate::setup::{check_law, friction_of, resolve_law};
use nalgebra::{DVector, Dyn, UnitQuaternion, Vector3};
use std::collections::BTreeSet;

/// Why a world run could not be completed.
#[derive(Debug, thiserror::Error)]
pub enum WorldError {
    /// A rule of the scene that only the run could check (a contact's law at its own speed), naming the key.
    #[error("scene key `{}`: {}", .0.key, .0.message)]
    Setup(SetupError),
    #[error(transparent)]
    Integration(#[from] IntegrationError),
}

/// The default budget of one world run (`[world] max_steps`): accepted and rejected steps over all its segments, each
/// segment, flight and contact taken at once counting as one more (docs/world.md#budgets).
pub const WORLD_STEP_BUDGET: u64 = crate::scene::world::DEFAULT_MAX_STEPS;

/// Scaled length of a segment, in the island's time units, after which it is restarted (a long resting contact
/// goes on in fresh segments, each with its own step budget).
const SEGMENT_TIME: f64 = 1e4;

/// The motion energy about rest, in the island's energy unit, below which an island is at rest.
pub const AT_REST: f64 = 1e-14;

/// Above this energy (in the island's unit) a watch of rest reads a lower bound of a group's motion energy rather than
/// the whole sum ([`Island::motion_energy_beyond`]): its function is then positive, as the whole one, and the two agree
/// wherever it is near zero.
const WATCHED_REST: f64 = 4.0 * AT_REST;

/// How far beyond the Coulomb cap (relative) a coast's ringing may reach where its watch, located, says it may
/// coast: the watch's own graze ([`CAP_GRAZE`]) and the location's error in it.
const COAST_LENIENCE: f64 = 1e-6;

/// A contact of two free bodies is quiet — ended, the bodies given one velocity — when its penetration and its rate
/// are both within this many times the integration's absolute tolerance (in the island's units L and V), or within the
/// rounding of the positions and velocities ([`ROUNDING`]): what is left of it is the integration's own noise
/// (docs/world.md#quiet-contacts).
pub const QUIET: f64 = 10.0;

/// Scaled penetration (of the contact's own length unit) at which a frictional contact's first stick-or-slip is read
/// off the leading terms, as in one impact.
const PROBE: f64 = 1e-6;

/// The rounding of a difference of two positions or velocities, relative to their sizes: a few units in the last
/// place (the floor of the quiet bounds).
const ROUNDING: f64 = 4.0 * f64::EPSILON;

/// What watches a run besides its outcome: an observer of its series, a count of how far it has come.
#[derive(Default)]
pub struct Watchers<'a> {
    /// Shown every instant of the run's series.
    pub observer: Option<&'a mut dyn Observer>,
    /// Told the scene time, the contacts ended and the steps taken as each segment or flight ends.
    pub progress: Option<&'a Progress>,
}

/// The run of a world scene.
pub fn run(scene: &WorldScene) -> Result<WorldOutcome, WorldError> {
    run_watched(scene, Watchers::default())
}

/// The run of a world scene, with `observer` shown every instant of its series.
pub fn run_observed(scene: &WorldScene, observer: &mut dyn Observer) -> Result<WorldOutcome, WorldError> {
    run_watched(scene, Watchers { observer: Some(observer), progress: None })
}

/// The run of a world scene, with its watchers.
pub fn run_watched<'a>(scene: &'a WorldScene, watchers: Watchers<'a>) -> Result<WorldOutcome, WorldError> {
    let mut world = World::new(scene, watchers);
    world.show_now();
    world.go()?;
    world.show_now();
    world.tell();
    Ok(world.finish())
}

/// Instants shown of each flight (evenly spaced, the apexes besides).
const FLIGHT_INSTANTS: usize = 24;

/// An event function of a segment, on the island's state.
type EventFunction<'a> = Box<dyn Fn(&DVector<f64>) -> f64 + 'a>;

/// What a terminal or watched event of a segment stands for.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Watched {
    /// Contact (index among the active) ends: its separation function (or, ended by its force, also its
    /// penetration) fell through zero.
    Separation(usize),
    /// Contact reaches a maximum of its penetration.
    MaxCompression(usize),
    /// Contact's force peaks.
    ForcePeak(usize),
    /// A watched pair (its index among the segment's watched pairs) touches.
    Touch(usize),
    /// The gap of a watched pair that began the segment touching opened beyond the rounding of its positions.
    Opened(usize),
    /// The gap of a watched pair that began the segment overlapping (a contact its force ended before its overlap)
    /// opened: the segment ends, and the next one watches that pair's gap close from open.
    Reopened(usize),
    /// The gap of a watched pair with a turning body reaches a minimum (its rate rises through zero): where it is
    /// below zero, the pair touched between two steps.
    Dip(usize),
    /// The island came to rest (free groups: the run ends).
    Rest,
    /// A member reached the bound of the neighbour list: the list is rebuilt.
    Relist,
    /// A group an immovable body holds came to rest (its index among the island's components): it is frozen.
    Frozen(usize),
    /// A ball resting alone on a still face (its index among the island's components) stopped ringing normal to it:
    /// it coasts on in closed form, or is frozen if nothing else moves in it (docs/world.md#coasting).
    Coast(usize),
    /// A watched pair with a coasting ball came within the ball's padding: the ball is woken (integrated again)
    /// before the pair can touch.
    Nearing(usize),
    /// A frictional contact (index among the active) switches between sticking and sliding.
    Switch(usize),
    /// A frictional contact's slip comes to rest (its component along its first direction falls through zero).
    SlipRest(usize),
}

/// The run's state between segments.
struct World<'a> {
    scene: &'a WorldScene,
    /// Every contact sphere of the scene (and each face): a contact is a pair of them.
    sites: std::rc::Rc<Sites>,
    /// Scene time, s.
    time: f64,
    /// Every body's state now.
    states: Vec<Kinematic>,
    active: Vec<ActiveContact>,
    records: Vec<ContactRecord>,
    /// The island's units while one exists.
    units: Option<Units>,
    /// The damping-map speed of each pair of sites' first contact (first-contact maps).
    first_speeds: std::collections::HashMap<[usize; 2], f64>,
    /// For two overlapping contacts [later, earlier]: the earlier one's impulse when the later began, N s (what it gave
    /// during their overlap is its impulse at the end of the overlap less this).
    overlap_marks: std::collections::HashMap<[usize; 2], f64>,
    /// The deepest penetration (m) of each pair of sites' last yielding contact that its force ended while they still
    /// overlapped: the dented surface a contact pressed again on that overlap reloads (docs/world.md#contacts-that-yield).
    dents: std::collections::HashMap<[usize; 2], f64>,
    /// The pairs of sites that touched without their gap ever opening since the last segment began: their contact
    /// would begin pushed (for contacts taken at a segment's end).
    pressed: BTreeSet<[usize; 2]>,
    ended: u64,
    immovable_work: f64,
    /// Work of gravity on the bodies of finite mass so far, summed from their displacements, J.
    gravity_work: f64,
    /// The bodies at rest on others, held still (frozen) until something touches them (docs/world.md#at-rest).
    frozen: Vec<bool>,
    /// The frozen bodies that coast: balls resting on a still face, moving on in closed form (their `states` are
    /// their mean motion: docs/world.md#coasting).
    coasts: Vec<Option<Coast>>,
    /// The kinetic energy left in groups when they were frozen (below 1e-14 of their energy unit), and the relative
    /// motion taken from bodies whose quiet contact ended, J.
    settled: f64,
    /// How many contacts ended quiet.
    quieted: u64,
    /// How many coasts began, and the scene time they lasted (s, up to the run's end for those still on).
    coasted: u64,
    coast_time: f64,
    counters: Counters,
    /// The pairs that may touch before some body moves half the skin (docs/world.md#neighbours).
    neighbours: Neighbours,
    reason: Option<EndReason>,
    notes: Vec<String>,
    observer: Option<&'a mut dyn Observer>,
    progress: Option<&'a Progress>,
    /// Segments, flights and contacts taken at once so far: each counts as one step of the run's budget.
    passes: u64,
    /// Pairs whose touch began no contact (a graze at the rounding of the velocities) at scene time `grazed_at`: not
    /// taken again at that instant.
    grazed: BTreeSet<[usize; 2]>,
    grazed_at: f64,
}

impl<'a> World<'a> {
    fn new(scene: &'a WorldScene, watchers: Watchers<'a>) -> Self {
        let states: Vec<Kinematic> = scene
            .bodies
            .iter()
            .map(|b| Kinematic {
                position: b.position.unwrap_or_default(),
                velocity: b.velocity,
                spin: b.angular_velocity,
                orientation: UnitQuaternion::identity(),
            })
            .collect();
        let sites = std::rc::Rc::new(Sites::of(scene));
        let neighbours = Neighbours::build(scene, &sites, &states, skin(scene, &sites));
        World {
            scene,
            sites,
            time: 0.0,
            states,
            active: Vec::new(),
            records: Vec::new(),
            units: None,
            first_speeds: Default::default(),
            overlap_marks: Default::default(),
            dents: Default::default(),
            pressed: BTreeSet::new(),
            ended: 0,
            immovable_work: 0.0,
            gravity_work: 0.0,
            frozen: vec![false; scene.bodies.len()],
            coasts: vec![None; scene.bodies.len()],
            settled: 0.0,
            quieted: 0,
            coasted: 0,
            coast_time: 0.0,
            counters: Counters::default(),
            neighbours,
            reason: None,
            notes: Vec::new(),
            observer: watchers.observer,
            progress: watchers.progress,
            passes: 0,
            grazed: BTreeSet::new(),
            grazed_at: f64::NAN,
        }
    }

    /// Tells the progress watcher, if any, how far the run has come.
    fn tell(&self) {
        if let Some(progress) = self.progress {
            progress.record(self.time, self.ended, self.counters.steps + self.counters.rejected_steps);
        }
    }

    /// The work the run has done against its budget: integration steps, accepted and rejected, and its passes.
    fn work(&self) -> u64 {
        self.counters.steps + self.counters.rejected_steps + self.passes
    }

    /// Counts one more pass (a segment, a flight, a contact taken at once) and whether the run has spent its budget
    /// (`[world] max_steps`); if it has, the run ends with a note.
    fn pass(&mut self) -> bool {
        self.passes += 1;
        if self.reason.is_some() || self.work() < self.scene.world.max_steps {
            return self.reason.is_some();
        }
        self.notes.push(format!(
            "the run spent its budget of {} steps (world.max_steps) at t = {}: {} integration steps, {} of them \
             rejected, and {} segments, flights and contacts taken at once; the report stops there (a larger \
             max_steps goes further)",
            self.scene.world.max_steps,
            crate::units::brief(self.time, "s"),
            self.counters.steps + self.counters.rejected_steps,
            self.counters.rejected_steps,
            self.passes
        ));
        self.reason = Some(EndReason::StepBudget);
        true
    }

    /// Whether the touch of bodies `i` and `j` began no contact at this very instant.
    fn grazed(&self, i: usize, j: usize) -> bool {
        self.grazed_at == self.time && self.grazed.contains(&[i, j])
    }

    /// Notes that the touch of bodies `i` and `j` began no contact now.
    fn graze(&mut self, i: usize, j: usize) {
        if self.grazed_at != self.time {
            self.grazed.clear();
            self.grazed_at = self.time;
        }
        self.grazed.insert([i, j]);
    }

    /// Shows the observer the world now (no contact forces: between islands, or at the run's ends).
    fn show_now(&mut self) {
        let contacts = self.contact_samples();
        // (A coasting ball where it is, not on its mean motion.)
        let bodies: Vec<Kinematic> = self
            .states
            .iter()
            .zip(&self.coasts)
            .map(|(state, coast)| coast.map_or(*state, |c| c.at(self.time).state))
            .collect();
        if let Some(observer) = self.observer.as_deref_mut() {
            observer.instant(self.time, &bodies, &contacts);
        }
    }

    /// The active contacts' penetrations and forces now.
    fn contact_samples(&self) -> Vec<ContactSample> {
        let Some(units) = self.units.filter(|_| !self.active.is_empty()) else { return Vec::new() };
        let flight = self.flight_accelerations();
        let island = Island::new(self.scene, &self.sites, &self.states, &flight, self.active.clone(), &[], units);
        let y = island.initial_state();
        (0..island.contacts.len()).map(|c| sample(&island, c, &y)).collect()
    }

    /// Shows the observer the flight of `delay` s from now: evenly spaced instants and each body's apex (where its
    /// velocity along gravity turns), before the bodies are moved.
    fn show_flight(&mut self, delay: f64) {
        if self.observer.is_none() || delay.is_nan() || delay <= 0.0 || delay.is_infinite() {
            return;
        }
        let g = self.scene.world.gravity;
        let flight = self.flight_accelerations();
        let mut times: Vec<f64> = (1..=FLIGHT_INSTANTS).map(|k| delay * k as f64 / FLIGHT_INSTANTS as f64).collect();
        let down = g.norm();
        if down > 0.0 {
            for (state, a) in self.states.iter().zip(&flight) {
                let rising = -state.velocity.dot(&g) / down;
                let apex = rising / down;
                if a.norm() > 0.0 && apex > 0.0 && apex < delay {
                    times.push(apex);
                }
            }
        }
        times.sort_by(f64::total_cmp);
        let start = self.states.clone();
        for t in times {
            // (A coasting ball where it is, not on its mean motion.)
            let bodies: Vec<Kinematic> = start
                .iter()
                .zip(&flight)
                .zip(&self.coasts)
                .map(|((state, a), coast)| coast.map_or_else(|| state.after(t, a), |c| c.at(self.time + t).state))
                .collect();
            if let Some(observer) = self.observer.as_deref_mut() {
                observer.instant(self.time + t, &bodies, &[]);
            }
        }
    }

    /// Every body's acceleration in free flight: gravity for a body of finite mass, none for an immovable or a
    /// frozen one.
    fn flight_accelerations(&self) -> Vec<Vector3<f64>> {
        let g = self.scene.world.gravity;
        self.scene
            .bodies
            .iter()
            .zip(&self.frozen)
            .map(|(body, &frozen)| if frozen { Vector3::zeros() } else { acceleration(body, &g) })
            .collect()
    }

    /// The active contacts that are not frozen (indices into `active`).
    fn live(&self) -> Vec<usize> {
        (0..self.active.len()).filter(|&c| self.active[c].pair.iter().any(|&k| self.free(k))).collect()
    }

    /// Whether body `k` moves: of finite mass and not frozen.
    fn free(&self, k: usize) -> bool {
        !self.scene.bodies[k].is_immovable() && !self.frozen[k]
    }

    /// The rigid bodies that turn in flight (docs/world.md#rigid-bodies): free, and spinning, or hung on a pivot under
    /// gravity. They fly in an island, their gaps watched as events; every other body flies in closed form.
    fn flyers(&self) -> Vec<usize> {
        if !self.sites.any_rigid {
            return Vec::new();
        }
        let swinging = self.scene.world.gravity != Vector3::zeros();
        (0..self.states.len())
            .filter(|&k| {
                let body = &self.scene.bodies[k];
                body.is_rigid()
                    && !self.frozen[k]
                    && (self.states[k].spin != Vector3::zeros() || (swinging && body.pivot.is_some()))
            })
            .collect()
    }

    /// Site `s`'s centre now, m.
    fn centre(&self, s: usize) -> Vector3<f64> {
        self.sites.centre(s, &self.states[self.sites.body(s)])
    }

    /// The velocity (m/s) of the point of body `k` at `lever` (m) from its mass centre now: v + ω × lever.
    fn point_velocity(&self, k: usize, lever: &Vector3<f64>) -> Vector3<f64> {
        let state = &self.states[k];
        if *lever == Vector3::zeros() { state.velocity } else { state.velocity + state.spin.cross(lever) }
    }

    /// Site `s`'s centre's velocity now, m/s.
    fn site_velocity(&self, s: usize) -> Vector3<f64> {
        let k = self.sites.body(s);
        self.point_velocity(k, &self.sites.lever(s, &self.states[k]))
    }

    /// Body `k`'s angular momentum now about its origin (its mass centre, or its pivot), kg m²/s.
    fn angular_momentum(&self, k: usize) -> Vector3<f64> {
        angular_momentum(&self.scene.bodies[k], &self.states[k])
    }

    /// Body `k` now as the instantaneous eccentric impact takes it (its inertia turned with it).
    fn rigid_body(&self, k: usize) -> crate::eccentric::RigidBody {
        rigid_body_at(&self.scene.bodies[k], &self.states[k])
    }

    /// Active contact `c`'s penetration (m) and penetration rate (m/s) at the bodies' states now.
    fn standing(&self, c: usize) -> (f64, f64) {
        let contact = &self.active[c];
        let [p, q] = contact.sites;
        let (penetration, normal) = contact.meeting.penetration(&(self.centre(q) - self.centre(p)));
        (penetration, (self.site_velocity(p) - self.site_velocity(q)).dot(&normal))
    }

    /// Active contact `c`'s slip now (m/s): the velocity of body i's contact point relative to body j's, across the
    /// normal. The contact point divides the line of centres in the ratio of the radii; a flat body has no arm.
    fn slip_now(&self, c: usize) -> Vector3<f64> {
        let contact = &self.active[c];
        let [i, j] = contact.pair;
        let [p, q] = contact.sites;
        let (a, b) = (&self.states[i], &self.states[j]);
        let relative = self.centre(q) - self.centre(p);
        let (_, n) = contact.meeting.penetration(&relative);
        let arms = contact.meeting.lever_arms(&relative, [self.sites.list[p].radius, self.sites.list[q].radius]);
        if self.sites.lever(p, a) == Vector3::zeros() && self.sites.lever(q, b) == Vector3::zeros() {
            return crate::geometry::slip(&n, [a.velocity, b.velocity], [a.spin, b.spin], arms);
        }
        let levers = [self.sites.lever(p, a) + arms[0], self.sites.lever(q, b) + arms[1]];
        let point = self.point_velocity(i, &levers[0]) - self.point_velocity(j, &levers[1]);
        point - n * point.dot(&n)
    }

    /// The scene time left before `end_time` (infinite without one).
    fn left(&self) -> f64 {
        self.scene.world.end_time.map_or(f64::INFINITY, |end| end - self.time)
    }

    /// Every pair of sites that can touch, each once (p < q).
    fn pairs(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        let n = self.sites.len();
        (0..n)
            .flat_map(move |p| (p + 1..n).map(move |q| (p, q)))
            .filter(|&(p, q)| self.sites.interacts(self.scene, p, q))
    }

    /// The flight time (s) within which no body outside `island` (none: every body) reaches the bound of the
    /// neighbour list: until then only its pairs can touch.
    fn list_holds(&self, island: Option<&Island>) -> f64 {
        if self.neighbours.is_everything() {
            return f64::INFINITY;
        }
        let flight = self.flight_accelerations();
        (0..self.sites.len())
            .filter(|&s| island.is_none_or(|island| island.slot(self.sites.body(s)).is_none()))
            .map(|s| {
                let k = self.sites.body(s);
                let slack = self.padding(k);
                self.neighbours.flight_bound(s, &self.sites.kinematic(s, &self.states[k]), &flight[k], slack)
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// Rebuilds the neighbour list at the bodies' states now.
    fn relist(&mut self) {
        self.neighbours.rebuild(self.scene, &self.sites, &self.states);
    }

    /// The tolerance (m) within which sites `p` and `q` count as touching: the rounding of their positions, and no
    /// less than the overlap a scene may start with (1e-12 of the smaller radius).
    fn touching(&self, p: usize, q: usize) -> f64 {
        let (a, b) = (&self.sites.bodies[p], &self.sites.bodies[q]);
        crate::geometry::touching_tolerance(a, &self.centre(p), b, &self.centre(q))
    }

    /// The next first touch in free flight among `pairs` of sites (from the bodies' states now), within `left` s: its
    /// time after now, and every pair touching then. (Every body flies in closed form: none of them turns.)
    ///
    /// Each pair's touch is found exactly ([`first_touch`]), but only for the pairs that could touch first: a gap
    /// shrinks no faster than the pair's relative speed and acceleration allow (`|w| t + |a| t²/2`), which bounds each
    /// pair's touch from below; pairs are taken in the order of their bounds, and the search stops at the first bound
    /// beyond the earliest touch found (a flight of many balls coasting apart searches a few of its pairs).
    fn next_touch(&self, pairs: &[(usize, usize)], left: f64) -> Option<(f64, Vec<(usize, usize)>)> {
        let flight = self.flight_accelerations();
        let mut bounded: Vec<(f64, usize)> = pairs
            .iter()
            .enumerate()
            .filter_map(|(n, &(p, q))| {
                let (meeting, _) = self.padded_meeting(p, q);
                let [i, j] = self.sites.bodies_of([p, q]);
                let (a, b) = (self.sites.centre(p, &self.states[i]), self.sites.centre(q, &self.states[j]));
                let gap = -meeting.penetration(&(b - a)).0 - 2.0 * self.touching(p, q);
                if gap.is_nan() || gap <= 0.0 {
                    return Some((0.0, n));
                }
                let speed = (self.site_velocity(q) - self.site_velocity(p)).norm();
                let pull = (flight[j] - flight[i]).norm();
                let earliest = 2.0 * gap / (speed + (speed * speed + 2.0 * pull * gap).sqrt());
                (earliest <= left).then_some((earliest, n))
            })
            .collect();
        bounded.sort_by(|x, y| x.0.total_cmp(&y.0));
        let mut touches: Vec<(usize, f64)> = Vec::new();
        let mut first = f64::INFINITY;
        for (earliest, n) in bounded {
            if earliest > first + 1e-14 * self.time.abs().max(first) {
                break;
            }
            let (p, q) = pairs[n];
            let (meeting, _) = self.padded_meeting(p, q);
            let [i, j] = self.sites.bodies_of([p, q]);
            let tolerance = self.touching(p, q);
            let (a, b) = (self.sites.kinematic(p, &self.states[i]), self.sites.kinematic(q, &self.states[j]));
            if let Some(t) = first_touch(&meeting, &a, &b, &flight[i], &flight[j], tolerance, left) {
                touches.push((n, t));
                first = first.min(t);
            }
        }
        let delay = first;
        if !delay.is_finite() || delay > left {
            return None;
        }
        let instant = 1e-14 * self.time.abs().max(delay);
        // (In the order of `pairs`: contacts that begin at one instant begin in that order.)
        touches.sort_by_key(|&(n, _)| n);
        Some((delay, touches.iter().filter(|t| t.1 <= delay + instant).map(|&(n, _)| pairs[n]).collect()))
    }

    fn go(&mut self) -> Result<(), WorldError> {
        while self.reason.is_none() {
            self.tell();
            if self.pass() {
                break;
            }
            // A list nearly spent is rebuilt before the next flight or segment (which would end at once).
            let reach = self.neighbours.reach();
            if (0..self.sites.len()).any(|s| self.neighbours.margin(s, &self.centre(s)) < reach / 8.0) {
                self.relist();
            }
            while !self.live().is_empty()
                && let Some(group) = self.quiet_group()
            {
                self.quiet(&group)?;
            }
            if self.live().is_empty() && self.flyers().is_empty() {
                self.fly()?;
            } else {
                self.segment()?;
            }
        }
        Ok(())
    }

    /// Free flight to the next first touch (or the end), then the island it starts.
    fn fly(&mut self) -> Result<(), WorldError> {
        // Pairs that grazed at the rounding of their velocities fly on, out of this flight's search.
        let mut grazed: Vec<(usize, usize)> = Vec::new();
        loop {
            if !grazed.is_empty() && self.pass() {
                return Ok(());
            }
            let left = self.left();
            let holds = self.list_holds(None);
            // (Active contacts are frozen or coasting ones: their pairs do not touch, they stand.)
            let active: BTreeSet<[usize; 2]> = self.active.iter().map(|c| c.sites).collect();
            let pairs: Vec<(usize, usize)> = self
                .neighbours
                .pairs
                .iter()
                .copied()
                .filter(|&(p, q)| !grazed.contains(&(p, q)) && !active.contains(&[p, q]))
                .collect();
            let mut next = self.next_touch(&pairs, left.min(holds));
            if next.is_none() && holds < left {
                // Nothing in the list touches before it must be rebuilt. Without an end, a run whose bodies never
                // meet again must still end: every pair is searched (exactly, in closed form) for the next touch.
                if left.is_infinite() {
                    let every: Vec<(usize, usize)> = self.pairs().filter(|pair| !grazed.contains(pair)).collect();
                    next = self.next_touch(&every, left);
                } else {
                    self.show_flight(holds);
                    self.advance(holds);
                    self.relist();
                    if self.pass() {
                        return Ok(());
                    }
                    continue;
                }
            }
            let Some((delay, starting)) = next else {
                let reason = if left.is_finite() { EndReason::EndTime } else { EndReason::NoMoreContacts };
                if left.is_finite() {
                    self.show_flight(left);
                    self.advance(left);
                }
                self.reason = Some(reason);
                return Ok(());
            };
            self.show_flight(delay);
            self.advance(delay);
            if delay >= holds {
                self.relist();
            }
            // Every pair touching at that instant begins (a cradle's struck ball and its neighbour at once).
            self.units = None;
            let (begun, woke) = self.take_touches(&starting, None)?;
            if begun || woke {
                return Ok(());
            }
            // A touch that begins no contact (a graze at the rounding of the velocities): that pair flies on.
            grazed.extend(starting);
        }
    }

    /// Takes the touches of `pairs` (sites) now: a coasting ball's padding reached wakes it; every other pair begins
    /// its contact (`island`: the speed unit of the island it begins in, if any). Whether a contact began, and whether a
    /// ball woke.
    fn take_touches(&mut self, pairs: &[(usize, usize)], island: Option<f64>) -> Result<(bool, bool), WorldError> {
        let nearing: Vec<bool> = pairs.iter().map(|&(p, q)| self.padded_meeting(p, q).1).collect();
        let (mut begun, mut woke) = (false, false);
        for (&(p, q), &near) in pairs.iter().zip(&nearing) {
            if near {
                for k in self.sites.bodies_of([p, q]) {
                    if self.coasts[k].is_some() {
                        woke = true;
                        self.wake(k);
                    }
                }
            }
        }
        for (&(p, q), &near) in pairs.iter().zip(&nearing) {
            if !near {
                begun |= self.begin(p, q, island, None)?;
            }
        }
        Ok((begun, woke))
    }

    /// Moves every body through `delay` s of free flight (and adds gravity's work on the way).
    fn advance(&mut self, delay: f64) {
        let g = self.scene.world.gravity;
        let flight = self.flight_accelerations();
        for ((state, body), a) in self.states.iter_mut().zip(&self.scene.bodies).zip(&flight) {
            if !body.is_immovable() {
                self.gravity_work += body.mass * g.dot(&state.displacement(delay, a));
            }
            *state = state.after(delay, a);
        }
        self.time += delay;
    }

    /// Frees the frozen bodies that active contacts join to body `k` (a touch wakes the group it rests in); a coasting
    /// ball takes its exact state.
    fn wake(&mut self, k: usize) {
        let mut queue = vec![k];
        while let Some(body) = queue.pop() {
            if !self.frozen[body] {
                continue;
            }
            self.materialise(body);
            if let Some(coast) = self.coasts[body].take() {
                self.coast_time += self.time - coast.since;
                // (An island that no contact begins takes the units the coast began in.)
                self.units = self.units.or(Some(coast.units));
            }
            self.frozen[body] = false;
            for contact in &self.active {
                if let Some(&other) = contact.pair.iter().find(|&&other| other != body)
                    && contact.pair.contains(&body)
                    && self.frozen[other]
                {
                    queue.push(other);
                }
            }
        }
    }

    /// Whether body `k` is frozen and still (not coasting).
    fn still(&self, k: usize) -> bool {
        self.frozen[k] && self.coasts[k].is_none()
    }

    /// How far (m) the mean motion of body `k`, coasting, keeps from everything else: twice its reach (none for a
    /// body that does not coast, or coasts on a smooth contact).
    fn padding(&self, k: usize) -> f64 {
        self.coasts[k].map_or(0.0, |coast| 2.0 * coast.reach())
    }

    /// How sites `p` and `q` meet, with a coasting body's padding added to their reach (its mean motion stands for
    /// it): and whether a touch of it is the padding's (which wakes the body rather than beginning a contact).
    fn padded_meeting(&self, p: usize, q: usize) -> (Meeting, bool) {
        let meeting = self.sites.meeting(self.scene, p, q);
        let [i, j] = self.sites.bodies_of([p, q]);
        let pad = self.padding(i) + self.padding(j);
        if pad == 0.0 {
            return (meeting, false);
        }
        let padded = match meeting {
            Meeting::Spheres { reach } => Meeting::Spheres { reach: reach + pad },
            Meeting::Face { face, radius, sign } => Meeting::Face { face, radius: radius + pad, sign },
        };
        (padded, true)
    }

    /// Writes coasting body `k`'s exact state now (and its contact's spring and the spring's work): its coast goes
    /// on from there unchanged (its constants stand).
    fn materialise(&mut self, k: usize) {
        let Some(coast) = self.coasts[k] else { return };
        let at = coast.at(self.time);
        self.states[k] = at.state;
        if let Some(contact) = self.active.iter_mut().find(|c| c.pair.contains(&k)) {
            // A slip that first comes to rest while the ball coasts: where its component along its first direction
            // falls through zero, as an island's watch would locate it.
            let record = &mut self.records[contact.record];
            let side = if contact.pair[0] == k { 1.0 } else { -1.0 };
            if record.slip_rest.is_none()
                && let Some(tau) = coast.slip_falls_through_zero(&(contact.slip_direction * side))
                && coast.since + tau <= self.time
            {
                record.slip_rest = Some(coast.since + tau);
            }
            contact.spring = if contact.pair[0] == k { at.force } else { -at.force };
            // (The integrals since the coast began, on those it began with.)
            contact.tangential_work = coast.work_before + at.work;
            contact.impulse = coast.impulse_before + at.impulse;
        }
    }

    /// Whether the group `group` of `island` (its members' slots) may coast, and how: a single sphere with a single
    /// active contact, on the face of an immovable body that stands still, pressed by gravity along the face's
    /// normal, the contact smooth or sticking without tangential damping. Its contact (among the island's), the
    /// ball, and the face's unit normal into the ball.
    fn coastable(&self, island: &Island, group: &[usize]) -> Option<(usize, usize, Vector3<f64>)> {
        let scene = self.scene;
        let [m] = group else { return None };
        if !scene.world.coast {
            return None;
        }
        let k = island.members[*m];
        let body = &scene.bodies[k];
        if body.is_rigid() || self.sites.of_body(k).len() != 1 {
            return None;
        }
        let mut touching = (0..island.contacts.len()).filter(|&c| island.contacts[c].pair.contains(&k));
        let (Some(c), None) = (touching.next(), touching.next()) else { return None };
        let contact = &island.contacts[c];
        let other = if contact.pair[0] == k { contact.pair[1] } else { contact.pair[0] };
        let face = scene.faces[other]?;
        let g = scene.world.gravity;
        let still = self.states[other].velocity == Vector3::zeros() && self.states[other].spin == Vector3::zeros();
        let pressed = g.dot(&face) < 0.0 && g.cross(&face).norm() <= 1e-12 * g.norm();
        let rough = contact.friction.as_ref().is_some_and(|f| f.coefficient > 0.0);
        let undamped = contact.friction.as_ref().is_none_or(|f| f.damping_ratio == 0.0);
        let turns = body.rotates() && body.inertia > 0.0;
        (still && pressed && undamped && (turns || !rough)).then_some((c, k, face / face.norm()))
    }

    /// Ball `k` coasts from scene time `now` (`normal`: the kinetic energy of its normal velocity, J, which the coast
    /// leaves out and is counted settled).
    fn begin_coast(&mut self, k: usize, coast: Coast, normal: f64, now: f64) {
        self.settled += normal;
        let coast = Coast { since: now, ..coast };
        self.states[k] = coast.mean(now);
        self.frozen[k] = true;
        self.coasts[k] = Some(coast);
        self.coasted += 1;
    }

    /// Begins the contact of sites `p` and `q` now (their bodies' states current): resolves its law, records its first
    /// touch; whether it began. `island` is the speed unit of the island it begins in, if any; `pushed` whether the
    /// bodies were already touching, pushed together rather than closing a gap (`None`: decided here, by the
    /// approach speed being zero).
    fn begin(&mut self, p: usize, q: usize, island: Option<f64>, pushed: Option<bool>) -> Result<bool, WorldError> {
        let scene = self.scene;
        let [i, j] = self.sites.bodies_of([p, q]);
        self.wake(i);
        self.wake(j);
        let (a, b) = (&self.sites.bodies[p], &self.sites.bodies[q]);
        let (spec, _) = scene.contact_of(i, j);
        let meeting = self.sites.meeting(scene, p, q);
        let relative = self.centre(q) - self.centre(p);
        let (overlap, normal) = meeting.penetration(&relative);
        let relative_velocity = self.site_velocity(p) - self.site_velocity(q);
        let approach = relative_velocity.dot(&normal).max(0.0);
        // Touching without approach, or pressed again on the overlap a contact ended by its force left: pushed.
        let pushed = pushed.unwrap_or(approach == 0.0 || overlap > self.touching(p, q));
        if !pushed && approach > 0.0 && approach <= 8.0 * f64::EPSILON * relative_velocity.norm() {
            // A graze within the rounding of the velocities: no contact.
            return Ok(false);
        }
        // The contact points' arms from each body's origin at first touch (each sphere's radius along the normal).
        let touch = crate::geometry::touch_arms(a, b, &normal);
        let levers = [self.sites.lever(p, &self.states[i]) + touch[0], self.sites.lever(q, &self.states[j]) + touch[1]];
        let point = if scene.faces[i].is_some() { self.centre(q) + touch[1] } else { self.centre(p) + touch[0] };
        let rigid = scene.bodies[i].is_rigid() || scene.bodies[j].is_rigid();
        // A rigid body meets the contact with its effective mass at the contact point (docs/references.md#eccentric-impact): the damping
        // maps and the units take the pair's.
        let effective_mass = if rigid {
            let inverse: f64 = [i, j].iter().map(|&k| self.rigid_body(k).inverse_effective_mass(&point, &normal)).sum();
            1.0 / inverse
        } else {
            crate::geometry::effective_mass(a, b).expect("interacting bodies are not both immovable")
        };
        let rename =
            |error: SetupError| WorldError::Setup(scene.rename_sites(&self.sites.list[p], &self.sites.list[q], error));
        // The damping map's speed: the approach speed, but never below the speed of a resting contact under
        // gravity, sqrt(g d_s) (d_s its static penetration), nor — for a contact pushed into being — below the
        // island's speed.
        let stiffness = resolve_law(spec, [a, b], effective_mass, 1.0).map_err(rename)?.stiffness;
        let g = scene.world.gravity.norm();
        let resting = if g > 0.0 {
            let static_penetration = (effective_mass * g / stiffness).powf(1.0 / spec.exponent);
            (g * static_penetration).sqrt()
        } else {
            0.0
        };
        let floor = if pushed { island.unwrap_or(0.0).max(resting) } else { resting };
        let mut map_speed = approach.max(floor);
        let maps_by_speed = matches!(spec.damping, DampingSpec::Restitution(_));
        if maps_by_speed && scene.world.damping_map == DampingMap::FirstContact {
            map_speed = *self.first_speeds.entry([p, q]).or_insert(map_speed);
        }
        if map_speed.is_nan() || map_speed <= 0.0 {
            // Touching without approach, gravity or an island to push them: nothing to begin.
            return Ok(false);
        }
        let law = resolve_law(spec, [a, b], effective_mass, map_speed).map_err(rename)?;
        check_law(spec, [a, b], &law, effective_mass, map_speed).map_err(rename)?;
        let friction = friction_of(spec, [a, b], effective_mass).map_err(rename)?;
        // Pressed again on the overlap an earlier contact of the pair left when its force ended it (the gap never
        // opened): a yielding law reloads the surface that contact dented, along its unloading curve from its deepest
        // point — no force and no spring energy below its dent. (A contact that closes a gap, or any other law, starts
        // from the overlap it begins on: an undented surface for a yielding law.)
        let on_overlap = overlap > 2.0 * self.touching(p, q);
        let dent = self.dents.remove(&[p.min(q), p.max(q)]);
        let deepest = match dent {
            Some(deepest) if on_overlap && law.yields() => deepest.max(overlap),
            _ => overlap.max(0.0),
        };
        let contact_units = Units::new(effective_mass, law.stiffness, law.exponent, map_speed);
        if self.units.is_none() {
            self.units = Some(contact_units);
        }
        let spins = [self.states[i].spin, self.states[j].spin];
        let mut slip_direction = Vector3::zeros();
        let mode = match friction {
            Some(f) => {
                // The contact points' slip at first touch (body i's relative to body j's, across the normal).
                let across = if rigid || levers != touch {
                    let point = self.point_velocity(i, &levers[0]) - self.point_velocity(j, &levers[1]);
                    point - normal * point.dot(&normal)
                } else {
                    let velocities = [self.states[i].velocity, self.states[j].velocity];
                    crate::geometry::slip(&normal, velocities, spins, touch)
                };
                let slip = across.norm();
                if slip > 0.0 {
                    slip_direction = across / slip;
                }
                let sliding = Tangential {
                    friction: f.coefficient,
                    stiffness: f.stiffness,
                    exponent: f.stiffness_exponent,
                    damping: 0.0,
                    cap: f.cap,
                    unloading: f.unloading,
                };
                // In SI: the spring a tiny penetration (a millionth of the contact's length unit) would load against
                // the Coulomb limit there.
                let probe = PROBE * contact_units.length;
                // The force the contact begins with: the law's at the overlap it starts on (a contact pressed again on
                // the overlap an earlier one left starts under a finite cap), at the approach rate.
                let contact_force = law.split_force_after(overlap.max(0.0), approach, deepest).total();
                sliding.initial_mode(slip, approach, probe, contact_force, law.force(probe, approach))
            }
            None => Mode::Stick,
        };
        let index = self.records.len();
        let mut overlapping = BTreeSet::new();
        for other in &self.active {
            overlapping.insert(other.record);
            self.records[other.record].overlapping.insert(index);
            self.overlap_marks.insert([index, other.record], other.impulse);
        }
        let origins = [i, j].map(|k| scene.bodies[k].pivot.unwrap_or(self.states[k].position));
        self.records.push(ContactRecord {
            bodies: [i, j],
            spheres: [self.sites.sphere(scene, p), self.sites.sphere(scene, q)],
            point,
            levers: [point - origins[0], point - origins[1]],
            orientations_before: [self.states[i].orientation, self.states[j].orientation],
            momenta_before: [self.angular_momentum(i), self.angular_momentum(j)],
            law,
            separation: spec.separation,
            map_speed,
            start_time: self.time,
            normal,
            approach_speed: approach,
            pushed,
            velocities_before: [self.states[i].velocity, self.states[j].velocity],
            spins_before: spins,
            effective_mass,
            friction: spec.friction,
            slip_rest: (friction.is_some() && slip_direction == Vector3::zeros()).then_some(self.time),
            switches: 0,
            elastic_at_start: if on_overlap { law.elastic_energy_after(overlap, deepest) } else { 0.0 },
            max_compression: None,
            peak_force: None,
            end: None,
            at_stop: None,
            overlapping,
            overlap_impulses: Default::default(),
        });
        // A yielding contact ends where its force returns to zero, at its dent.
        let on_force = (spec.separation == Separation::Force && law.kind.can_turn_tensile()) || law.yields();
        self.active.push(ActiveContact {
            record: index,
            pair: [i, j],
            sites: [p, q],
            meeting,
            law,
            on_force,
            impulse: 0.0,
            work: 0.0,
            dissipated: 0.0,
            // A contact pressed on an overlap has been loaded at least that deep (an undented surface otherwise: each
            // contact of a yielding law that closes a gap starts from one).
            deepest,
            friction,
            mode,
            slip_direction,
            spring: Vector3::zeros(),
            tangential_work: 0.0,
        });
        Ok(true)
    }

    /// One segment of the island: integrates until a contact begins or ends (or the run's end), and takes it.
    fn segment(&mut self) -> Result<(), WorldError> {
        let scene = self.scene;
        let units = match self.units {
            Some(units) => units,
            None => {
                let units = self.flight_units()?;
                self.units = Some(units);
                units
            }
        };
        let start = self.states.clone();
        let flight = self.flight_accelerations();
        let sites = std::rc::Rc::clone(&self.sites);
        let sites = &*sites;
        // The island integrates the live contacts (`live[c]` is its contact c's index among the active ones), and the
        // rigid bodies that turn in flight.
        let live = self.live();
        let flyers = self.flyers();
        let contacts = live.iter().map(|&c| self.active[c].clone()).collect();
        let island = Island::new(scene, sites, &start, &flight, contacts, &flyers, units);
        let y0 = island.initial_state();
        if island.contacts.is_empty() && self.left().is_infinite() && !self.may_touch(&flyers) {
            // Turning bodies in flight that nothing can reach any more, as nothing else can: the run is over.
            self.reason = Some(EndReason::NoMoreContacts);
            return Ok(());
        }
        // The pairs watched for a first touch: every pair with a member that is not an active contact. A pair
        // touching at the start is watched from just inside the rounding of its positions, so that its gap starts
        // open; whether its gap then opens is watched too (a contact it begins without is pushed). A pair that
        // starts overlapping beyond that rounding (a contact its force ended while the bodies still overlapped) is
        // watched for its gap to open, which ends the segment: the next one watches the gap close from open.
        let active: BTreeSet<[usize; 2]> = self.active.iter().map(|c| c.sites).collect();
        let all: Vec<(usize, usize)> =
            self.neighbours.pairs.iter().copied().filter(|&(p, q)| !active.contains(&[p, q])).collect();
        let inside =
            |&(p, q): &(usize, usize)| island.slot(sites.body(p)).is_some() || island.slot(sites.body(q)).is_some();
        // A pair with a coasting ball outside the island is watched on the ball's mean motion, its reach padded: the
        // padding reached wakes the ball (docs/world.md#coasting).
        let mut nearing: Vec<bool> = Vec::new();
        let watched: Vec<(usize, usize, Meeting, f64, f64)> = all
            .iter()
            .filter(|pair| inside(pair))
            .map(|&(p, q)| {
                let (meeting, near) = self.padded_meeting(p, q);
                nearing.push(near);
                let gap = -island.site_state(p, q, &meeting, &y0).penetration;
                let tolerance = self.touching(p, q);
                let offset = if gap <= tolerance { (-gap).max(0.0) + tolerance } else { 0.0 };
                (p, q, meeting, offset, tolerance)
            })
            .collect();
        // A coasting ball already within its padding of a member is woken before the segment.
        let near_now: Vec<usize> = watched
            .iter()
            .zip(&nearing)
            .filter(|((_, _, _, offset, _), near)| **near && *offset > 0.0)
            .flat_map(|((p, q, _, _, _), _)| sites.bodies_of([*p, *q]))
            .filter(|&k| self.coasts[k].is_some())
            .collect();
        if !near_now.is_empty() {
            drop(island);
            for k in near_now {
                self.wake(k);
            }
            return Ok(());
        }
        // Pairs with no body in the island fly freely: the segment stops at their next first touch.
        let outside: Vec<(usize, usize)> =
            all.iter().copied().filter(|&(i, j)| !inside(&(i, j)) && !self.grazed(i, j)).collect();
        let outside_touch = self.next_touch(&outside, self.left());
        // Groups that come to rest: one an immovable body holds is frozen; free ones end the run when every movable
        // body not frozen is in them.
        let components = island.components();
        let everyone =
            scene.bodies.iter().enumerate().all(|(k, b)| b.is_immovable() || self.still(k) || island.slot(k).is_some());
        let all_free = components.iter().all(|(_, held)| !held);
        let all_members: Vec<usize> = (0..island.members.len()).collect();
        // A ball that may coast already (its ringing died away in a segment that a switch or a touch elsewhere ended)
        // coasts from here: its watch, falling through zero, would not see it.
        let watches: Vec<Option<CoastWatch>> = components
            .iter()
            .map(|(group, held)| {
                let (c, k, n) = if *held { self.coastable(&island, group)? } else { None? };
                let others = self
                    .neighbours
                    .pairs
                    .iter()
                    .filter(|&&(p, q)| sites.bodies_of([p, q]).contains(&k) && !active.contains(&[p, q]))
                    .map(|&(p, q)| {
                        let other = sites.bodies_of([p, q]).into_iter().find(|&b| b != k).unwrap_or(k);
                        (p, q, sites.meeting(scene, p, q), self.padding(other))
                    })
                    .collect();
                let body = &scene.bodies[k];
                let weight = body.mass * scene.world.gravity.dot(&n).abs();
                let room = if self.neighbours.is_everything() { f64::INFINITY } else { self.neighbours.reach() / 8.0 };
                Some(CoastWatch { c, k, body, n, weight, others, room })
            })
            .collect();
        let ready: Vec<(usize, Coast, f64)> = components
            .iter()
            .zip(&watches)
            .filter_map(|((group, _), watch)| {
                let watch = watch.as_ref()?;
                let ready = coast_watch(&island, watch, &y0) <= 0.0
                    && island.motion_energy(&y0, group, true) > 2.0 * AT_REST * units.energy;
                if !ready {
                    return None;
                }
                coast_begins(&island, watch, &y0, COAST_LENIENCE).map(|(coast, normal)| (watch.k, coast, normal))
            })
            .collect();
        if let Some((k, coast, normal)) = ready.into_iter().next() {
            // (One at a time: the next one's watch reads this one's padding.)
            drop(island);
            self.begin_coast(k, coast, normal, self.time);
            return Ok(());
        }

        let mut functions: Vec<EventFunction<'_>> = Vec::new();
        let mut kinds: Vec<(Watched, bool)> = Vec::new();
        let isl = &island;
        for c in 0..isl.contacts.len() {
            functions.push(Box::new(move |y| isl.separation_value(c, y)));
            kinds.push((Watched::Separation(c), true));
            if isl.contacts[c].on_force {
                functions.push(Box::new(move |y| isl.contact_state(c, y).penetration / isl.units.length));
                kinds.push((Watched::Separation(c), true));
            }
            // A maximum of the penetration, or of the force, is located only where it would be the deepest, or the
            // largest, so far: the record keeps that one. Each function is the larger of the rate (falling through
            // zero at a maximum) and the shortfall from the record at the segment's start (positive below it), so
            // that it falls through zero exactly at a maximum at or beyond the record; a resting contact's ringing and
            // noise below it are not stepped to (docs/world.md#resting-contacts).
            let record = &self.records[isl.contacts[c].record];
            let deepest = record.max_compression.map_or(f64::NEG_INFINITY, |m| m.penetration);
            functions.push(Box::new(move |y| {
                let state = isl.contact_state(c, y);
                above_record(state.rate / isl.units.speed, (deepest - state.penetration) / isl.units.length)
            }));
            kinds.push((Watched::MaxCompression(c), false));
            let largest = record.peak_force.map_or(f64::NEG_INFINITY, |(_, peak)| peak);
            functions.push(Box::new(move |y| {
                let state = isl.contact_state(c, y);
                let (elastic, dissipative) = isl.force(c, &state, y);
                let short = (largest - (elastic + dissipative)) / isl.units.force;
                // (The force's rate, which sums the forces on both bodies, only where the sign needs it.)
                if short > 0.0 {
                    short
                } else {
                    above_record(isl.force_rate(c, y) * isl.units.time / isl.units.force, short)
                }
            }));
            kinds.push((Watched::ForcePeak(c), false));
            if isl.contacts[c].friction.is_some() {
                functions.push(Box::new(move |y| isl.switch_value(c, y).unwrap_or(1.0)));
                kinds.push((Watched::Switch(c), true));
                if self.records[isl.contacts[c].record].slip_rest.is_none() {
                    functions.push(Box::new(move |y| isl.slip_along_start(c, y)));
                    kinds.push((Watched::SlipRest(c), false));
                }
            }
        }
        for (p, (i, j, meeting, offset, tolerance)) in watched.iter().enumerate() {
            let (i, j, offset, tolerance) = (*i, *j, *offset, *tolerance);
            functions.push(Box::new(move |y| (offset - isl.site_penetration(i, j, meeting, y)) / isl.units.length));
            kinds.push((if nearing[p] { Watched::Nearing(p) } else { Watched::Touch(p) }, true));
            if offset > 2.0 * tolerance {
                // Overlapping at the start: the gap opening beyond the rounding ends the segment.
                let open = 2.0 * tolerance;
                functions.push(Box::new(move |y| (open + isl.site_penetration(i, j, meeting, y)) / isl.units.length));
                kinds.push((Watched::Reopened(p), true));
            } else if offset > 0.0 {
                let open = 8.0 * offset;
                functions.push(Box::new(move |y| (open + isl.site_penetration(i, j, meeting, y)) / isl.units.length));
                kinds.push((Watched::Opened(p), false));
            } else if [i, j].iter().any(|&s| isl.turns(sites.body(s))) {
                // The gap's minima (its rate, -d', rising through zero), watched for a dip below zero between steps.
                functions.push(Box::new(move |y| -isl.site_state(i, j, meeting, y).rate / isl.units.speed));
                kinds.push((Watched::Dip(p), false));
            }
        }
        for (k, (group, held)) in components.iter().enumerate() {
            if let Some(watch) = &watches[k] {
                functions.push(Box::new(move |y| coast_watch(isl, watch, y)));
                kinds.push((Watched::Coast(k), true));
            } else if *held {
                functions.push(Box::new(move |y| {
                    isl.motion_energy_beyond(y, group, true, WATCHED_REST * isl.units.energy) / isl.units.energy
                        - AT_REST
                }));
                kinds.push((Watched::Frozen(k), true));
            }
        }
        if !self.neighbours.is_everything() {
            // The margin left to the member's site that moved furthest from where the list was built.
            let member_sites: Vec<usize> = isl.members.iter().flat_map(|&k| sites.of_body(k)).collect();
            let (reach, reference) = (self.neighbours.reach(), self.neighbours.references(&member_sites));
            functions.push(Box::new(move |y| {
                let moved = member_sites
                    .iter()
                    .zip(&reference)
                    .map(|(&s, at)| (isl.site_position(s, y) - at).norm())
                    .fold(0.0, f64::max);
                (reach - moved) / isl.units.length
            }));
            kinds.push((Watched::Relist, true));
        }
        if everyone && all_free {
            let members = &all_members;
            functions.push(Box::new(move |y| {
                isl.motion_energy_beyond(y, members, false, WATCHED_REST * isl.units.energy) / isl.units.energy
                    - AT_REST
            }));
            kinds.push((Watched::Rest, true));
        }
        // (A stick–slip switch under the magnitude cap can dip below zero and back inside one step: watched so.)
        let magnitude_cap = island.caps_friction_by_magnitude();
        let events: Vec<EventOf<'_, Dyn>> = functions
            .iter()
            .zip(&kinds)
            .map(|(f, &(kind, terminal))| {
                let direction = if matches!(kind, Watched::Dip(_)) { Direction::Rising } else { Direction::Falling };
                let dips = magnitude_cap && matches!(kind, Watched::Switch(_));
                EventOf { function: f.as_ref(), direction, terminal, dips }
            })
            .collect();

        let requested = scene.solver.tolerances;
        // A tenth of the scene's, and the law's own fraction of that (`ContactLaw::tolerance_factor`: a hundredth
        // for MuJoCo's and ADAMS' laws, rough at first touch and separation), which a world needs all the more as
        // it does not make their forces' kinks step boundaries as one impact does (MuJoCo's impedance at its
        // midpoint and width, ADAMS' cubic step at d_max).
        let factor = 0.1 * isl.contacts.iter().map(|c| c.law.tolerance_factor()).fold(1.0, f64::min);
        let tolerances = Tolerances { rtol: requested.rtol * factor, atol: requested.atol * factor };
        // (The segment may take what is left of the run's budget, at most one impact's.)
        let left = self.scene.world.max_steps.saturating_sub(self.work()).max(1);
        // A long segment tells the progress watcher how far it has come as it goes.
        let (time, ended, taken) = (self.time, self.ended, self.counters.steps + self.counters.rejected_steps);
        let progress = self.progress;
        let tick = move |t: f64, steps: u64| {
            if let Some(progress) = progress {
                progress.record(time + t * units.time, ended, taken + steps);
            }
        };
        let mut stepper = StepperOf::new(&island, tolerances, self.observer.is_some()).with_budget(left);
        if progress.is_some() {
            stepper = stepper.with_tick(&tick);
        }
        let by_end = self.left() / units.time;
        let by_outside = outside_touch.as_ref().map_or(f64::INFINITY, |(delay, _)| delay / units.time);
        let by_list = self.list_holds(Some(&island)) / units.time;
        let horizon = by_end.min(by_outside).min(by_list).min(SEGMENT_TIME);
        let mut end = stepper.run(0.0, y0.clone(), horizon, &events)?;
        // A gap that closed and opened again between two steps (a turning body's long steps in flight) shows as a
        // located minimum below zero: the segment is run again to that minimum, where the touch is seen and located.
        let dipped = end.crossings.iter().find(|crossing| {
            matches!(kinds[crossing.event].0, Watched::Dip(p)
                if island.site_state(watched[p].0, watched[p].1, &watched[p].2, &crossing.state).penetration > 0.0)
        });
        if let Some(dip) = dipped {
            let to = dip.time;
            if let Some(record) = stepper.record.as_mut() {
                record.clear();
            }
            end = stepper.run(0.0, y0, to, &events)?;
        }
        self.counters.steps += stepper.counters.steps;
        self.counters.rejected_steps += stepper.counters.rejected_steps;
        self.counters.evaluations += stepper.counters.evaluations;
        if self.observer.is_some() {
            // The series shows every accepted step, and the flight between long ones (a turning body's steps in
            // flight span most of it): instants on the integrator's own solution, evenly spaced, and each flyer's
            // apex in a segment without contacts. (Work done for the series only: not counted in the run's.)
            let g = scene.world.gravity;
            let apexes: Vec<f64> = if island.contacts.is_empty() && g.norm() > 0.0 {
                flyers.iter().map(|&k| -start[k].velocity.dot(&g) / g.norm_squared() / units.time).collect()
            } else {
                Vec::new()
            };
            let points = stepper.recorded().map(<[_]>::to_vec).unwrap_or_default();
            let times = flight_instants(&points, end.time, &apexes);
            let mut points = points;
            points.extend(stepper.resample(&times)?);
            points.sort_by(|a, b| a.0.total_cmp(&b.0));
            let observer = self.observer.as_deref_mut().expect("an observer is present");
            for (t, y) in &points {
                let bodies: Vec<Kinematic> = (0..scene.bodies.len())
                    .map(|k| match self.coasts[k] {
                        // (A coasting ball where it is, not on its mean motion.)
                        Some(coast) => coast.at(self.time + t * units.time).state,
                        None => Kinematic {
                            position: island.position(k, y),
                            velocity: island.velocity(k, y),
                            spin: island.spin(k, y),
                            orientation: island.orientation(k, y),
                        },
                    })
                    .collect();
                let contacts: Vec<ContactSample> = (0..island.contacts.len()).map(|c| sample(&island, c, y)).collect();
                observer.instant(self.time + t * units.time, &bodies, &contacts);
            }
        }

        // The located non-terminal events: maxima of penetration and force, gaps that opened.
        let mut opened = vec![false; watched.len()];
        for crossing in &end.crossings {
            let at = self.time + crossing.time * units.time;
            match kinds[crossing.event].0 {
                Watched::MaxCompression(c) => self.note_compression(&island, c, &crossing.state, at),
                Watched::ForcePeak(c) => self.note_peak(&island, c, &crossing.state, at),
                Watched::Opened(p) => opened[p] = true,
                Watched::SlipRest(c) => {
                    let record = &mut self.records[island.contacts[c].record];
                    record.slip_rest = record.slip_rest.or(Some(at));
                }
                _ => {}
            }
        }
        if let Ending::Event(index) = end.ending
            && let Watched::Reopened(p) = kinds[index].0
        {
            opened[p] = true;
        }
        self.pressed = watched
            .iter()
            .zip(&opened)
            .filter(|((_, _, _, offset, _), opened)| *offset > 0.0 && !**opened)
            .map(|((i, j, _, _, _), _)| [*i, *j])
            .collect();
        // The segment's end: every body's state, the contacts' integrals, gravity's and the walls' work.
        let y = &end.state;
        let now = self.time + end.time * units.time;
        for c in 0..island.contacts.len() {
            // The force at the segment's end may be the largest (a contact that ends on a jump).
            self.note_peak(&island, c, y, now);
            if self.records[island.contacts[c].record].max_compression.is_none() {
                // Until a maximum is located, the deepest point so far is where the contact stands now.
                self.note_compression(&island, c, y, now);
            }
        }
        for (k, body) in scene.bodies.iter().enumerate() {
            if island.slot(k).is_none() && self.states[k].velocity == Vector3::zeros() && flight[k] == Vector3::zeros()
            {
                // At rest outside the island: where it was.
                continue;
            }
            if !body.is_immovable() {
                self.gravity_work += body.mass * scene.world.gravity.dot(&island.displacement(k, y));
            }
            self.states[k] = Kinematic {
                position: island.position(k, y),
                velocity: island.velocity(k, y),
                spin: island.spin(k, y),
                orientation: island.orientation(k, y),
            };
        }
        for (c, &active) in live.iter().enumerate() {
            let contact = &mut self.active[active];
            (contact.impulse, contact.work, contact.dissipated) = island.integrals(c, y);
            let d = island.contact_state(c, y).penetration.max(0.0);
            contact.deepest = if contact.law.yields() { island.deepest(c, d, y) } else { 0.0 };
            (contact.spring, contact.tangential_work, _) = island.tangential_integrals(c, y);
        }
        self.immovable_work += island.immovable_work(y);
        let rates: Vec<f64> = (0..island.contacts.len()).map(|c| island.contact_state(c, y).rate).collect();
        let rough = island.frictional();
        let motion = island.motion_energy(y, &all_members, false);
        // The bodies a group at rest freezes, each with the spin it keeps: a smooth contact cannot change a spin, a
        // rough one all but the spin about a point contact's normal (docs/world.md#at-rest).
        // A ball that stopped ringing normal to its face coasts, or is frozen as such a group when the motion it would
        // keep is within twice the threshold of rest (docs/world.md#coasting).
        let mut coasting: Option<(usize, Coast, f64)> = None;
        let freezing = match end.ending {
            Ending::Event(index) => match kinds[index].0 {
                Watched::Frozen(k) => Some(k),
                Watched::Coast(k) => {
                    let group = &components[k].0;
                    if island.motion_energy(y, group, true) <= 2.0 * AT_REST * units.energy {
                        Some(k)
                    } else {
                        // (Its watch ruled on the cap and the gaps: the cap is read again only with a leniency for
                        // the event's location.)
                        coasting = watches[k].as_ref().and_then(|watch| {
                            coast_begins(&island, watch, y, COAST_LENIENCE)
                                .map(|(coast, normal)| (watch.k, coast, normal))
                        });
                        None
                    }
                }
                _ => None,
            },
            _ => None,
        };
        let resting: Vec<(usize, Vector3<f64>)> = match freezing {
            Some(k) => components[k]
                .0
                .iter()
                .map(|&m| {
                    let k = island.members[m];
                    (k, if rough { island.torsion(k, y) } else { island.spin(k, y) })
                })
                .collect(),
            None => Vec::new(),
        };
        // A stick–slip switch's next mode, decided on the state it was located at.
        let switched = match end.ending {
            Ending::Event(index) => match kinds[index].0 {
                Watched::Switch(c) => island.next_mode(c, y),
                _ => None,
            },
            _ => None,
        };
        drop(events);
        drop(functions);
        drop(island);
        let before = self.time;
        self.time = now;

        match end.ending {
            Ending::Event(index) => match kinds[index].0 {
                Watched::Separation(c) => self.finish_contact(live[c], rates[c])?,
                Watched::Coast(_) if resting.is_empty() => {
                    if let Some((k, coast, normal)) = coasting {
                        self.begin_coast(k, coast, normal, now);
                    }
                }
                Watched::Frozen(_) | Watched::Coast(_) => {
                    for (k, kept) in resting {
                        let body = &scene.bodies[k];
                        self.settled += body.kinetic_energy(&self.states[k].velocity, &self.states[k].spin)
                            - body.kinetic_energy(&Vector3::zeros(), &kept);
                        self.states[k].velocity = Vector3::zeros();
                        self.states[k].spin = kept;
                        self.frozen[k] = true;
                    }
                    let all_rest = scene.bodies.iter().enumerate().all(|(k, b)| b.is_immovable() || self.still(k));
                    if all_rest {
                        self.reason = Some(EndReason::AtRest);
                        self.notes.push(format!(
                            "the bodies came to rest at t = {}: the energy of their motion about rest fell below {} of \
                             M V² = {}",
                            crate::units::brief(now, "s"),
                            crate::units::brief(AT_REST, ""),
                            crate::units::brief(units.energy, "J")
                        ));
                        return Ok(());
                    }
                }
                Watched::Nearing(p) => {
                    let (i, j, _, _, _) = watched[p];
                    for k in self.sites.bodies_of([i, j]) {
                        if self.coasts[k].is_some() {
                            self.wake(k);
                        }
                    }
                }
                Watched::Touch(p) => {
                    let (i, j, _, offset, _) = watched[p];
                    let pushed = offset > 0.0 && !opened[p];
                    self.begin(i, j, Some(units.speed), Some(pushed))?;
                }
                Watched::Rest => {
                    self.reason = Some(EndReason::AtRest);
                    self.notes.push(format!(
                        "the bodies came to rest at t = {}: the energy of their motion about rest fell to {} of M V² = \
                         {}",
                        crate::units::brief(now, "s"),
                        crate::units::brief(motion / units.energy, ""),
                        crate::units::brief(units.energy, "J")
                    ));
                    return Ok(());
                }
                // A gap that opened after a contact its force ended: the next segment watches it afresh.
                Watched::Reopened(_) => {}
                Watched::Relist => self.relist(),
                Watched::Switch(c) => {
                    let slip = self.slip_now(live[c]);
                    let contact = &mut self.active[live[c]];
                    let (mode, spring) = switched.unwrap_or((Mode::Stick, None));
                    contact.mode = mode;
                    if let Some(spring) = spring {
                        contact.spring = spring;
                    }
                    let record = &mut self.records[contact.record];
                    // A contact that began without slip and now slides (driven by gravity or other contacts, not by
                    // its approach) has not come to rest yet: its slip's rest is watched from here, along this slip.
                    if contact.mode.is_sliding() && contact.slip_direction == Vector3::zeros() && slip.norm() > 0.0 {
                        contact.slip_direction = slip / slip.norm();
                        record.slip_rest = None;
                    }
                    record.switches += 1;
                    if record.switches >= crate::dynamics::contact::MAX_SWITCHES {
                        self.notes.push(format!(
                            "contact {} switched between sticking and sliding {} times by t = {}: the run stopped \
                             there",
                            contact.record,
                            record.switches,
                            crate::units::brief(now, "s")
                        ));
                        self.reason = Some(EndReason::StepBudget);
                        return Ok(());
                    }
                }
                Watched::MaxCompression(_)
                | Watched::ForcePeak(_)
                | Watched::Opened(_)
                | Watched::SlipRest(_)
                | Watched::Dip(_) => {
                    unreachable!("not terminal")
                }
            },
            Ending::TimeLimit if horizon == by_end => {
                self.reason = Some(EndReason::EndTime);
                return Ok(());
            }
            Ending::TimeLimit if horizon == by_outside => {
                // Two bodies outside the island touch: their contact begins (and joins the island); a touch that
                // begins none (a graze) is not taken again at this instant.
                // (A coasting ball's padding reached wakes the ball instead.)
                let pairs = outside_touch.map(|(_, pairs)| pairs).unwrap_or_default();
                let (nearing, touching): (Vec<_>, Vec<_>) =
                    pairs.into_iter().partition(|&(i, j)| self.padded_meeting(i, j).1);
                for (i, j) in nearing {
                    for k in self.sites.bodies_of([i, j]) {
                        if self.coasts[k].is_some() {
                            self.wake(k);
                        }
                    }
                }
                for (i, j) in touching {
                    if !self.begin(i, j, Some(units.speed), None)? {
                        self.graze(i, j);
                    }
                }
            }
            // A body outside the island reached the bound of the neighbour list.
            Ending::TimeLimit if horizon == by_list => self.relist(),
            // A long segment that left the clock where it was: the island's time unit is below the clock's rounding,
            // and no number of segments would move it on.
            Ending::TimeLimit if now == before => {
                self.notes.push(format!(
                    "at t = {} the island's time unit, {}, is below the rounding of the scene's clock: a segment of \
                     {SEGMENT_TIME} units left the clock where it was, and the run stopped there",
                    crate::units::brief(now, "s"),
                    crate::units::brief(units.time, "s")
                ));
                self.reason = Some(EndReason::StepBudget);
                return Ok(());
            }
            // A long segment: go on in a fresh one.
            Ending::TimeLimit => {}
            // A segment that spent its own step budget goes on in a fresh one (the run's budget decides). So does a
            // frictional one the integrator found stiff: a sliding contact whose slip other contacts turn has its
            // spring follow at the fastest turning rate (docs/world.md#friction), a stretch that ends; a smooth
            // island found stiff ends the run.
            Ending::GaveUp(why) if why.contains("budget") || (rough && why.contains("stiff")) => {}
            Ending::GaveUp(why) => {
                self.notes.push(format!("the integration stopped at t = {}: {why}", crate::units::brief(now, "s")));
                self.reason = Some(EndReason::StepBudget);
                return Ok(());
            }
        }
        self.settle_simultaneous(units.speed)?;
        if self.ended >= scene.world.max_contacts && self.reason.is_none() {
            self.reason = Some(EndReason::MaxContacts);
        }
        Ok(())
    }

    /// The units of an island of rigid bodies turning in flight, before any contact has given it its own: those of the
    /// contact of a flyer's site with its first neighbour at their relative speed (the spin's and a swing's included).
    fn flight_units(&self) -> Result<Units, WorldError> {
        let scene = self.scene;
        let g = scene.world.gravity.norm();
        if let Some(&k) = self.flyers().first() {
            let body = &scene.bodies[k];
            let reach = self.reach(k);
            for &(p, q) in &self.neighbours.pairs {
                let [i, j] = self.sites.bodies_of([p, q]);
                if i != k && j != k {
                    continue;
                }
                let other = if i == k { j } else { i };
                let spin = |b: usize| self.states[b].spin.norm() * self.reach(b);
                let speed = (self.states[k].velocity - self.states[other].velocity).norm()
                    + spin(k)
                    + spin(other)
                    + (g * reach).sqrt();
                let (a, b) = (&self.sites.bodies[p], &self.sites.bodies[q]);
                let Some(mass) = crate::geometry::effective_mass(a, b) else { continue };
                if !(speed > 0.0 && speed.is_finite()) {
                    continue;
                }
                let (spec, _) = scene.contact_of(i, j);
                let law = resolve_law(spec, [a, b], mass, speed).map_err(|error| {
                    WorldError::Setup(scene.rename_sites(&self.sites.list[p], &self.sites.list[q], error))
                })?;
                return Ok(Units::new(mass, law.stiffness, law.exponent, speed));
            }
            // Nothing near it: units of its own size.
            let length = 1e-6 * reach;
            return Ok(Units {
                length,
                speed: 1.0,
                time: length,
                mass: body.mass,
                force: body.mass / length,
                impulse: body.mass,
                energy: body.mass,
            });
        }
        Ok(Units { length: 1.0, speed: 1.0, time: 1.0, mass: 1.0, force: 1.0, impulse: 1.0, energy: 1.0 })
    }

    /// Body `k`'s reach, m: the farthest of its contact spheres' surfaces from its origin (its mass centre, or its
    /// pivot).
    fn reach(&self, k: usize) -> f64 {
        let body = &self.scene.bodies[k];
        if body.is_flat() {
            return 0.0;
        }
        let origin = body.pivot.unwrap_or(self.states[k].position);
        self.sites.of_body(k).map(|s| (self.centre(s) - origin).norm() + self.sites.list[s].radius).fold(0.0, f64::max)
    }

    /// Whether any two sites may still touch, with the flyers `flyers` bounded by spheres about their origins (a free
    /// body's bounding sphere flies on its mass centre's parabola, a pivoted one's stays about its pivot): a bound
    /// found in closed form, so that a run whose bodies tumble apart for ever ends.
    fn may_touch(&self, flyers: &[usize]) -> bool {
        let scene = self.scene;
        let flight = self.flight_accelerations();
        // Each site's stand-in: a flyer's bounding sphere, or the site itself.
        let stand_in = |s: usize| -> (Kinematic, f64, Vector3<f64>) {
            let k = self.sites.body(s);
            let state = &self.states[k];
            if flyers.contains(&k) {
                let body = &scene.bodies[k];
                let (origin, moving) = match body.pivot {
                    Some(pivot) => (pivot, Vector3::zeros()),
                    None => (state.position, state.velocity),
                };
                let bound = Kinematic { position: origin, velocity: moving, ..*state };
                (bound, self.reach(k), if body.pivot.is_some() { Vector3::zeros() } else { flight[k] })
            } else {
                // (A coasting ball: its mean motion, its radius padded.)
                (self.sites.kinematic(s, state), self.sites.list[s].radius + self.padding(k), flight[k])
            }
        };
        self.pairs().any(|(p, q)| {
            let [i, j] = self.sites.bodies_of([p, q]);
            if !flyers.contains(&i) && !flyers.contains(&j) {
                let (meeting, _) = self.padded_meeting(p, q);
                let (a, b) = (self.sites.kinematic(p, &self.states[i]), self.sites.kinematic(q, &self.states[j]));
                let tolerance = self.touching(p, q);
                return first_touch(&meeting, &a, &b, &flight[i], &flight[j], tolerance, f64::INFINITY).is_some();
            }
            let ((a, ra, ga), (b, rb, gb)) = (stand_in(p), stand_in(q));
            let meeting = Meeting::of_radii(ra, scene.faces[i], rb, scene.faces[j]);
            if meeting.penetration(&(b.position - a.position)).0 >= 0.0 {
                return true;
            }
            first_touch(&meeting, &a, &b, &ga, &gb, 0.0, f64::INFINITY).is_some()
        })
    }

    /// Contacts that end, and pairs that touch, at the very instant a segment ended (within the rounding of
    /// positions): taken at once, each as its own event.
    fn settle_simultaneous(&mut self, speed: f64) -> Result<(), WorldError> {
        loop {
            if self.pass() {
                return Ok(());
            }
            // (Without a live contact the island is gone: flight finds what touches next.)
            let live = self.live();
            if self.ended >= self.scene.world.max_contacts || live.is_empty() {
                return Ok(());
            }
            let scene = self.scene;
            let start = self.states.clone();
            let flight = self.flight_accelerations();
            let units = self.units.expect("an island has units");
            let sites = std::rc::Rc::clone(&self.sites);
            let sites = &*sites;
            let contacts = live.iter().map(|&c| self.active[c].clone()).collect();
            let island = Island::new(scene, sites, &start, &flight, contacts, &[], units);
            let y = island.initial_state();
            let parting = (0..island.contacts.len()).find_map(|c| {
                let state = island.contact_state(c, &y);
                let tolerance = self.touching(island.contacts[c].sites[0], island.contacts[c].sites[1]);
                let value = if island.contacts[c].on_force {
                    island.separation_value(c, &y)
                } else {
                    state.penetration - tolerance
                };
                (state.rate < 0.0 && value <= 0.0).then_some((live[c], state.rate))
            });
            let active: BTreeSet<[usize; 2]> = self.active.iter().map(|c| c.sites).collect();
            let touching = self.neighbours.pairs.iter().copied().find(|&(p, q)| {
                let [i, j] = sites.bodies_of([p, q]);
                if active.contains(&[p, q])
                    || (island.slot(i).is_none() && island.slot(j).is_none())
                    || self.grazed(p, q)
                {
                    return false;
                }
                let state = island.site_state(p, q, &sites.meeting(scene, p, q), &y);
                let tolerance = self.touching(p, q);
                state.rate > 0.0 && state.penetration.abs() <= tolerance
            });
            drop(island);
            if let Some((c, rate)) = parting {
                self.finish_contact(c, rate)?;
            } else if let Some((i, j)) = touching {
                let pushed = self.pressed.contains(&[i, j]);
                if !self.begin(i, j, Some(speed), Some(pushed))? {
                    // A touch that begins no contact is not taken again at this instant.
                    self.graze(i, j);
                }
            } else if let Some(group) = self.quiet_group() {
                self.quiet(&group)?;
            } else {
                return Ok(());
            }
        }
    }

    /// Whether active contact `c` is quiet: its penetration and rate within [`QUIET`] times the absolute tolerance of
    /// the island's units.
    fn is_quiet(&self, c: usize, units: &Units) -> bool {
        let resolution = QUIET * self.scene.solver.tolerances.atol;
        let [i, j] = self.active[c].pair;
        let (penetration, rate) = self.standing(c);
        // Never finer than the rounding of the positions and velocities themselves (far from the origin, or at a
        // tolerance near the precision's own).
        let (a, b) = (&self.states[i], &self.states[j]);
        let depth = (resolution * units.length).max(ROUNDING * (a.position.norm() + b.position.norm()));
        let pace = (resolution * units.speed).max(ROUNDING * (a.velocity.norm() + b.velocity.norm()));
        penetration.abs() <= depth && rate.abs() <= pace
    }

    /// A group of active contacts (indices among the active) that is quiet as a whole: joined to each other, every
    /// body of finite mass and free, every contact quiet, and no other active contact touching its bodies. The first
    /// found, if any.
    fn quiet_group(&self) -> Option<Vec<usize>> {
        let units = self.units?;
        let mut touching: std::collections::HashMap<usize, Vec<usize>> = Default::default();
        for (c, contact) in self.active.iter().enumerate() {
            for &k in &contact.pair {
                touching.entry(k).or_default().push(c);
            }
        }
        let mut done = vec![false; self.active.len()];
        for first in 0..self.active.len() {
            if done[first] {
                continue;
            }
            // The contacts joined to `first` through shared bodies.
            let mut group = vec![first];
            done[first] = true;
            let mut at = 0;
            let mut quiet = true;
            while at < group.len() {
                let c = group[at];
                at += 1;
                // (A rigid body's contacts are never ended quiet: a common velocity would leave its spin.)
                quiet &= self.active[c].pair.iter().all(|&k| self.free(k) && !self.scene.bodies[k].is_rigid())
                    && self.is_quiet(c, &units);
                for k in self.active[c].pair {
                    for &other in &touching[&k] {
                        if !done[other] {
                            done[other] = true;
                            group.push(other);
                        }
                    }
                }
            }
            if quiet {
                return Some(group);
            }
        }
        None
    }

    /// Ends a quiet group of contacts (indices among the active): their bodies, and every body joined to them by an
    /// earlier quiet group (touching, moving with exactly their velocity), take their common velocity — momentum
    /// kept, the kinetic energy of their relative motion counted as settled. What such contacts still carry is the
    /// integration's noise; left alone it keeps the bodies touching and parting at noise speeds, each time a contact
    /// of its own.
    fn quiet(&mut self, contacts: &[usize]) -> Result<(), WorldError> {
        let mut endings = Vec::new();
        let mut group: Vec<usize> = Vec::new();
        for &c in contacts {
            let contact = &self.active[c];
            let (penetration, rate) = self.standing(c);
            let d = penetration.max(0.0);
            let elastic = if contact.law.yields() {
                contact.law.elastic_energy_after(d, contact.deepest.max(d))
            } else {
                contact.law.elastic_energy(d)
            };
            endings.push((contact.record, rate, elastic));
            for k in contact.pair {
                if !group.contains(&k) {
                    group.push(k);
                }
            }
        }
        let active: BTreeSet<[usize; 2]> = self.active.iter().map(|c| c.pair).collect();
        let mut seen: BTreeSet<usize> = group.iter().copied().collect();
        let mut at = 0;
        while at < group.len() {
            let p = group[at];
            at += 1;
            let site = self.sites.of_body(p).start;
            for &other in self.neighbours.adjacent(site) {
                let q = self.sites.body(other);
                if seen.contains(&q)
                    || !self.free(q)
                    || self.scene.bodies[q].is_rigid()
                    || active.contains(&[p.min(q), p.max(q)])
                {
                    continue;
                }
                if self.states[q].velocity == self.states[p].velocity {
                    seen.insert(q);
                    group.push(q);
                }
            }
        }
        let mass: f64 = group.iter().map(|&k| self.scene.bodies[k].mass).sum();
        let momentum =
            group.iter().fold(Vector3::zeros(), |sum, &k| sum + self.states[k].velocity * self.scene.bodies[k].mass);
        let common = momentum / mass;
        for &k in &group {
            let body = &self.scene.bodies[k];
            self.settled += body.kinetic_energy(&self.states[k].velocity, &Vector3::zeros())
                - body.kinetic_energy(&common, &Vector3::zeros());
            self.states[k].velocity = common;
        }
        for (record, rate, stored) in endings {
            self.quieted += 1;
            let c = self.active.iter().position(|c| c.record == record).expect("a quiet contact is active");
            self.end_contact(c, rate, Some(stored))?;
        }
        Ok(())
    }

    /// Records a maximum of contact `c`'s penetration at state `y` (scene time `at`), if it is the deepest so far.
    fn note_compression(&mut self, island: &Island, c: usize, y: &DVector<f64>, at: f64) {
        let state = island.contact_state(c, y);
        let contact = &island.contacts[c];
        let record = &mut self.records[contact.record];
        if record.max_compression.is_some_and(|m| m.penetration >= state.penetration) {
            return;
        }
        let (impulse, work, _) = island.integrals(c, y);
        let [i, _] = contact.pair;
        let moving = if self.scene.bodies[i].is_immovable() { 1 } else { 0 };
        record.max_compression = Some(Compression {
            time: at,
            penetration: state.penetration,
            impulse,
            work,
            common_normal_velocity: island.site_velocity(contact.sites[moving], y).dot(&state.normal),
        });
    }

    /// Records contact `c`'s force at state `y` (scene time `at`) if it is the largest so far.
    fn note_peak(&mut self, island: &Island, c: usize, y: &DVector<f64>, at: f64) {
        let state = island.contact_state(c, y);
        let (elastic, dissipative) = island.force(c, &state, y);
        let force = elastic + dissipative;
        let record = &mut self.records[island.contacts[c].record];
        if record.peak_force.is_none_or(|(_, peak)| force > peak) {
            record.peak_force = Some((at, force));
        }
    }

    /// Ends active contact `c` now (the bodies' states current), parting at penetration rate `rate` (m/s).
    fn finish_contact(&mut self, c: usize, rate: f64) -> Result<(), WorldError> {
        self.end_contact(c, rate, None)
    }

    /// Ends active contact `c` now, parting at penetration rate `rate` (m/s), with the elastic energy it leaves
    /// stored (J; `None`: none, or for a contact ended by its force the energy at its force's zero).
    fn end_contact(&mut self, c: usize, rate: f64, stored: Option<f64>) -> Result<(), WorldError> {
        let contact = self.active.remove(c);
        for other in 0..self.active.len() {
            self.close_overlap(&contact, other);
        }
        let [i, j] = contact.pair;
        let relative = self.centre(contact.sites[1]) - self.centre(contact.sites[0]);
        let momenta = [self.angular_momentum(i), self.angular_momentum(j)];
        let record = &mut self.records[contact.record];
        let (penetration, _) = contact.meeting.penetration(&relative);
        if contact.law.yields() && penetration > 0.0 {
            // The dent a contact pressed again on this overlap reloads.
            let [p, q] = contact.sites;
            self.dents.insert([p.min(q), p.max(q)], contact.deepest.max(penetration));
        }
        let elastic_left = if let Some(stored) = stored {
            stored
        } else if contact.on_force && penetration > 0.0 {
            contact.law.elastic_energy(contact.law.separation_penetration(rate, penetration))
        } else {
            0.0
        };
        record.end = Some(ContactEnding {
            time: self.time,
            impulse: contact.impulse,
            work: contact.work,
            dissipated: contact.dissipated,
            rate,
            elastic_left,
            penetration,
            velocities: [self.states[i].velocity, self.states[j].velocity],
            spins: [self.states[i].spin, self.states[j].spin],
            momenta,
            tangential_work: contact.tangential_work,
        });
        if record.max_compression.is_none() {
            // A contact that ended before any maximum of its penetration was located (a graze, or a pushed contact
            // that never pressed): its deepest point is its start.
            record.max_compression = Some(Compression {
                time: record.start_time,
                penetration: 0.0,
                impulse: 0.0,
                work: 0.0,
                common_normal_velocity: record.velocities_before[0].dot(&record.normal),
            });
        }
        self.ended += 1;
        // (Rigid bodies turning in flight go on in an island of the same units.)
        if self.live().is_empty() && self.flyers().is_empty() {
            self.units = None;
        }
        Ok(())
    }

    /// Records what contact `ended` and the active contact `other` gave each other during their overlap, which ends
    /// now (their integrals current): each one's impulse now less its impulse when the later of them began.
    fn close_overlap(&mut self, ended: &ActiveContact, other: usize) {
        let other = &self.active[other];
        let (a, b) = (ended.record, other.record);
        let mark = |later: usize, earlier: usize| self.overlap_marks.get(&[later, earlier]).copied().unwrap_or(0.0);
        let (from_other, from_ended) = (other.impulse - mark(a, b), ended.impulse - mark(b, a));
        self.records[a].overlap_impulses.insert(b, from_other);
        self.records[b].overlap_impulses.insert(a, from_ended);
        self.overlap_marks.remove(&[a, b]);
        self.overlap_marks.remove(&[b, a]);
    }

    /// The outcome, with the contacts still active when the run stopped closed at their current values.
    fn finish(mut self) -> WorldOutcome {
        // (A coasting ball is reported where it is, not on its mean motion.)
        for k in 0..self.coasts.len() {
            self.materialise(k);
            if let Some(coast) = self.coasts[k] {
                self.coast_time += self.time - coast.since;
            }
        }
        if self.coasted > 0 {
            self.notes.push(format!(
                "balls resting on a still face coasted in closed form {} time{}, {} of scene time in all: their ringing \
                 normal to the face had died away, and the motion along it is exact (docs/world.md#coasting; \
                 `[world] coast = false` integrates them)",
                self.coasted,
                if self.coasted > 1 { "s" } else { "" },
                crate::units::brief(self.coast_time, "s")
            ));
        }
        // (The overlaps of contacts still active close at the stop.)
        for first in 0..self.active.len() {
            let ended = self.active[first].clone();
            for second in first + 1..self.active.len() {
                self.close_overlap(&ended, second);
            }
        }
        let units = self.units.or_else(|| {
            self.active.first().map(|c| {
                let (a, b) = (&self.scene.bodies[c.pair[0]], &self.scene.bodies[c.pair[1]]);
                let mass = crate::geometry::effective_mass(a, b).unwrap_or(1.0);
                Units::new(mass, c.law.stiffness, c.law.exponent, 1.0)
            })
        });
        if let Some(units) = units {
            let start = self.states.clone();
            let flight = self.flight_accelerations();
            let sites = std::rc::Rc::clone(&self.sites);
            let island = Island::new(self.scene, &sites, &start, &flight, self.active.clone(), &[], units);
            let y = island.initial_state();
            let time = self.time;
            for c in 0..island.contacts.len() {
                if self.records[island.contacts[c].record].max_compression.is_none() {
                    self.note_compression(&island, c, &y, time);
                }
                self.note_peak(&island, c, &y, time);
            }
            for (c, contact) in self.active.iter().enumerate() {
                let (_, tangential_work, tangential_elastic) = island.tangential_integrals(c, &y);
                self.records[contact.record].at_stop = Some(Stop {
                    impulse: contact.impulse,
                    work: contact.work,
                    dissipated: contact.dissipated,
                    elastic: island.elastic_energy(c, &y),
                    tangential_work,
                    tangential_elastic,
                });
            }
            if self.reason != Some(EndReason::AtRest) && !self.active.is_empty() {
                let list: Vec<String> = self.active.iter().map(|c| c.record.to_string()).collect();
                self.notes.push(format!(
                    "the run stopped with contact{} {} in progress: the sequential model takes {} as plastic (e = 0), \
                     which an impact cut short is not",
                    if list.len() > 1 { "s" } else { "" },
                    super::record::shorten(&list),
                    if list.len() > 1 { "them" } else { "it" }
                ));
            }
        }
        if self.quieted > 0 {
            self.notes.push(format!(
                "{} contact{} ended quiet — penetration and rate within {QUIET} times the absolute tolerance, the \
                 integration's noise — and {} bodies took one common velocity (docs/world.md#quiet-contacts)",
                self.quieted,
                if self.quieted > 1 { "s" } else { "" },
                if self.quieted > 1 { "their" } else { "its" }
            ));
        }
        let starts: Vec<f64> = self.records.iter().map(|r| r.start_time).collect();
        if starts.windows(2).any(|pair| pair[0] == pair[1]) {
            self.notes.push(
                "contacts began at the same instant: the sequential model takes them one after the other in the order \
                 listed, and its answer depends on that order"
                    .into(),
            );
        }
        WorldOutcome {
            contacts: self.records,
            end_reason: self.reason.unwrap_or(EndReason::NoMoreContacts),
            end_time: self.time,
            bodies: self.states,
            immovable_work: self.immovable_work,
            gravity_work: self.gravity_work,
            settled: self.settled,
            counters: self.counters,
            method: "dop853",
            notes: self.notes,
        }
    }
}

/// Body `body`'s angular momentum at `state` about its origin (its mass centre, or its pivot), kg m²/s: zero for a body
/// that does not turn.
pub fn angular_momentum(body: &crate::body::Body, state: &Kinematic) -> Vector3<f64> {
    if !body.rotates() || body.is_immovable() {
        return Vector3::zeros();
    }
    if !body.is_eccentric() {
        return state.spin * body.inertia;
    }
    rigid_body_at(body, state).inertia_about_pivot() * state.spin
}

/// Contact `c` of `island` at state `y`: its record's index, penetration and force.
fn sample(island: &Island, c: usize, y: &DVector<f64>) -> ContactSample {
    let state = island.contact_state(c, y);
    let (elastic, dissipative) = island.force(c, &state, y);
    ContactSample { index: island.contacts[c].record, penetration: state.penetration, force: elastic + dissipative }
}

/// The instants (island time, ascending) a series adds inside a segment of `span` whose accepted steps are `points`:
/// where two steps lie more than `span / FLIGHT_INSTANTS` apart, evenly spaced instants between them, and each of
/// `apexes` inside the span.
fn flight_instants<Y>(points: &[(f64, Y)], span: f64, apexes: &[f64]) -> Vec<f64> {
    let most = span / FLIGHT_INSTANTS as f64;
    let mut times: Vec<f64> = apexes.iter().copied().filter(|&t| t > 0.0 && t < span).collect();
    if most > 0.0 && most.is_finite() {
        for pair in points.windows(2) {
            let (from, to) = (pair[0].0, pair[1].0);
            let gap = to - from;
            if gap > most {
                // At most FLIGHT_INSTANTS in one gap: the count is bounded whatever the span.
                let count = ((gap / most).ceil() as usize).min(FLIGHT_INSTANTS);
                times.extend((1..count).map(|k| from + gap * k as f64 / count as f64));
            }
        }
    }
    times.sort_by(f64::total_cmp);
    times.dedup();
    times
}

/// The function whose fall through zero is a maximum at or beyond a record: `rate` (the scaled rate of the quantity,
/// falling through zero at its maxima) where `short` (the scaled shortfall of the quantity from the record) is not
/// positive, and a positive value of the same sign as `max(rate, short)` elsewhere. It equals `max(rate, short)`
/// wherever `short <= 0`, and so near every zero it has: it is continuous there, and zero exactly where the quantity
/// peaks at or above the record.
fn above_record(rate: f64, short: f64) -> f64 {
    if short > 0.0 { short } else { rate.max(short) }
}

/// What a ball's coast watch reads: its contact `c` (among the island's), the ball `k` and its body, the face's unit
/// normal `n` into it, its weight along `n` (N), and the pairs of its site with every body it does not touch (sites,
/// their meeting, and the other body's padding, m).
struct CoastWatch<'a> {
    c: usize,
    k: usize,
    body: &'a crate::body::Body,
    n: Vector3<f64>,
    weight: f64,
    others: Vec<(usize, usize, Meeting, f64)>,
    /// The largest padding the neighbour list leaves room for (an eighth of how far a body may move before it is
    /// rebuilt; infinite for a list of every pair), m.
    room: f64,
}

/// The watch of a ball's coast (docs/world.md#coasting): it falls through zero where the ball may coast. It is the
/// largest of: the energy of the ball's ringing normal to the face, `m v_n²/2 + m a_n²/(2 w²)` (`w²` the contact's
/// stiffness over the mass), in the island's energy unit, less the threshold of rest; for a rough contact, how far the
/// ringing of its tangential force would reach beyond the Coulomb cap (as a share of the cap, less the graze), one
/// where it slides; and how far within twice its padding (and another coasting body's) a gap to a body it does not touch
/// is (as a share of that clearance).
fn coast_watch(island: &Island, watch: &CoastWatch, y: &DVector<f64>) -> f64 {
    let &CoastWatch { c, k, body, n, weight, .. } = watch;
    let mass = body.mass;
    let energy = island.units.energy;
    let kinetic = 0.5 * mass * island.velocity(k, y).dot(&n).powi(2);
    if kinetic > WATCHED_REST * energy {
        return kinetic / energy - AT_REST;
    }
    let d = island.contact_state(c, y).penetration.max(0.0);
    let gradient = island.contacts[c].law.force_gradient(d, 0.0).0;
    let pull = island.acceleration_of(k, y).dot(&n);
    let ringing = if gradient > 0.0 {
        kinetic + 0.5 * mass * mass * pull * pull / gradient
    } else if pull != 0.0 {
        f64::INFINITY
    } else {
        kinetic
    };
    let above = ringing / energy - AT_REST;
    let mu = island.friction_coefficient(c);
    if above > WATCHED_REST || mu <= 0.0 {
        return above;
    }
    let kt = island.tangential_stiffness(c, island.static_penetration(c, weight, y));
    if kt.is_nan() || kt <= 0.0 {
        return above;
    }
    let Some(coast) = coast_from(island, watch, kt, y).filter(|_| weight > 0.0) else { return above.max(1.0) };
    let pad = 2.0 * coast.reach();
    // (A padding beyond the neighbour list's room would leave the list no time to hold.)
    let roomy = if watch.room.is_finite() { (pad - watch.room) / watch.room } else { f64::NEG_INFINITY };
    let near = watch
        .others
        .iter()
        .map(|(p, q, meeting, other)| {
            let clearance = 2.0 * (pad + other);
            (clearance + island.site_penetration(*p, *q, meeting, y)) / clearance
        })
        .fold(f64::NEG_INFINITY, f64::max);
    above.max(coast.largest_force() / (mu * weight) - (1.0 + CAP_GRAZE)).max(near).max(roomy)
}

/// The coast ball `watch.k` would begin at state `y`: from its state there, its normal velocity removed, with its
/// contact's tangential force and integrals; `kt` (N/m) its tangential stiffness, zero for a smooth contact. `None`
/// where its rough contact slides.
fn coast_from(island: &Island, watch: &CoastWatch, kt: f64, y: &DVector<f64>) -> Option<Coast> {
    let &CoastWatch { c, k, body, n, weight, .. } = watch;
    let contact = &island.contacts[c];
    let rough = kt > 0.0;
    if rough && contact.mode != Mode::Stick {
        return None;
    }
    let velocity = island.velocity(k, y);
    let start = Kinematic {
        position: island.position(k, y),
        velocity: velocity - n * velocity.dot(&n),
        spin: island.spin(k, y),
        orientation: island.orientation(k, y),
    };
    let (spring, work, _) = island.tangential_integrals(c, y);
    let force = match (rough, contact.pair[0] == k) {
        (false, _) => Vector3::zeros(),
        (true, true) => spring,
        (true, false) => -spring,
    };
    Some(Coast {
        since: 0.0,
        start,
        force: force - n * n.dot(&force),
        slip: super::coast::slip(&start, &n, body.radius),
        normal: n,
        mass: body.mass,
        inertia: if rough { body.inertia } else { f64::INFINITY },
        radius: body.radius,
        stiffness: kt,
        work_before: work,
        normal_force: weight,
        impulse_before: island.integrals(c, y).0,
        units: island.units,
    })
}

/// The coast ball `watch.k` begins at state `y`, or `None` when its contact slides, its ringing would reach beyond
/// the Coulomb cap by more than `graze` (relative), or its padding beyond the neighbour list's room by as much; with the
/// kinetic energy its normal velocity carries (J), which the coast leaves out. The normal force is the ball's weight
/// along the normal, the mean of its contact's force, and kt is taken at the static penetration, where the ringing's
/// damping would bring it (the ringing normal to the face, below the threshold of rest, moves it about them).
fn coast_begins(island: &Island, watch: &CoastWatch, y: &DVector<f64>, graze: f64) -> Option<(Coast, f64)> {
    let &CoastWatch { c, k, body, n, weight, room, .. } = watch;
    let mu = island.friction_coefficient(c);
    let kt = island.tangential_stiffness(c, island.static_penetration(c, weight, y));
    let rough = mu > 0.0 && kt > 0.0;
    let coast = coast_from(island, watch, if rough { kt } else { 0.0 }, y)?;
    if rough && coast.largest_force() > (1.0 + graze) * mu * weight.max(0.0) {
        return None;
    }
    if room.is_finite() && 2.0 * coast.reach() > (1.0 + graze) * room {
        return None;
    }
    Some((coast, 0.5 * body.mass * island.velocity(k, y).dot(&n).powi(2)))
}
