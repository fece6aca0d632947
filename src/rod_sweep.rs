//! A steel rod dropped at an angle on a floor, and the sweep of that angle (docs/rigid.md#a-rod-dropped-at-an-angle):
//! the impact sequence of its two ends — the lower end strikes, the rod turns, the other end may come down and
//! strike in turn, and so on — simulated in a world, beside the sequential instantaneous model of the same contacts
//! and a planar rigid rod with instantaneous end impacts of constant e, flown here in closed form between them.
//!
//! The rod is models/rod-chatter.toml's: 0.2 kg, 0.2 m between the centres of its two 5 mm end spheres, a thin rod's
//! inertia, Hunt–Crossley contacts of nominal e = 0.8 on a steel floor under gravity; here its lower sphere is 1 mm
//! above the floor, falling at 1 m/s, so that it touches at sqrt(1 + 2 g 1 mm) = 1.0098 m/s.
//!
//! **The sequence and its apparent e.** The sequence is over after contact K when, once every contact up to K has
//! ended, the rod's mass centre moves up and no end of the rod touches the floor again before the apex of that
//! flight (the mass centre's vertical velocity over g later): what comes after the apex is a new bounce of a rod
//! that has left the floor, not part of the impact. Its apparent e is the mass centre's vertical velocity then over
//! its fall speed at first touch, `e_app = v_z⁺/v`: what an observer of the mass centre measures. Gravity acts during
//! the sequence, which lasts tens of milliseconds where the other end must fall through L sin θ before it strikes
//! (g τ is then a third of v), so e_app is not the floor's impulse over M v less one. For one contact of a rod
//! without gravity it is the textbook's `(1 + e)/(1 + 3 cos²θ) - 1` (docs/references.md#rigid-bodies-with-several-contacts); Stoianovici & Hurmuzlu (1996)
//! measured the same ratio on dropped steel bars.

use crate::report::world::WorldReport;
use crate::scene::Parsed;
use std::path::Path;

/// The rod's mass, kg.
pub const MASS: f64 = 0.2;
/// Between the centres of its end spheres, m.
pub const LENGTH: f64 = 0.2;
/// Its end spheres' radius, m.
pub const RADIUS: f64 = 0.005;
/// Its speed when dropped, m/s.
pub const SPEED: f64 = 1.0;
/// The lower sphere's height above the floor when dropped, m.
pub const GAP: f64 = 1e-3;
/// Gravity, m/s².
pub const G: f64 = 9.81;
/// The contacts' nominal e (Hunt–Crossley's map of it gives about 0.833,
/// docs/world.md#damping-of-successive-contacts).
pub const RESTITUTION: f64 = 0.8;
/// The world's contacts at most: a sequence never comes near (the rigid rod's longest in 1°–89° is 3 contacts).
const MAX_CONTACTS: usize = 40;
/// The run's end, s: past the apex of any rebound of the sequence (a sequence of at most 0.1 s, then at most
/// e v/g = 0.09 s to the apex).
const END_TIME: f64 = 0.25;

/// I_G across the rod's axis: a thin rod's M L²/12, kg m².
pub fn across() -> f64 {
    MASS * LENGTH * LENGTH / 12.0
}

/// The speed at first touch: v² = SPEED² + 2 g GAP, m/s.
pub fn touch_speed() -> f64 {
    (SPEED * SPEED + 2.0 * G * GAP).sqrt()
}

/// The scene of the rod dropped at `degrees` to the floor (its axis in the x–z plane, sphere 0 at the upper end
/// +(L/2)(cos θ, 0, sin θ), sphere 1 at the lower end), with `max_contacts` and `end_time` (s); commented as the
/// models are. models/rod-80deg.toml is this text at 80 degrees with 2 contacts at most.
pub fn scene(degrees: f64, max_contacts: usize, end_time: f64) -> String {
    let theta = degrees.to_radians();
    let axis = [theta.cos(), 0.0, theta.sin()];
    let (polar, across) = (1e-3 * across(), across());
    let entry = |i: usize, j: usize| (polar - across) * axis[i] * axis[j] + if i == j { across } else { 0.0 };
    let row = |i: usize| format!("[{:?}, {:?}, {:?}]", entry(i, 0), entry(i, 1), entry(i, 2));
    let half = LENGTH / 2.0;
    let end = [half * axis[0], 0.0, half * axis[2]];
    let centre = half * theta.sin() + RADIUS + GAP;
    format!(
        "# The steel rod of models/rod-chatter.toml ({MASS} kg, {LENGTH} m between the centres of its two {} mm end \
         spheres, a thin\n# rod's inertia M L²/12 across its axis, a polar moment of 1e-3 of that along it) dropped \
         at {degrees} degrees at {SPEED} m/s,\n# its lower sphere {} mm above a steel floor, under gravity, \
         Hunt–Crossley with a nominal e = {RESTITUTION} at each contact.\n# Written by rod_sweep::scene \
         (src/rod_sweep.rs), the scene of the angle sweep\n# (docs/rigid.md#a-rod-dropped-at-an-angle).\n\
         title = \"A rod dropped at {degrees} degrees on a floor\"\n\n[world]\ngravity = [0.0, 0.0, {:?}]\n\
         max_contacts = {max_contacts}\nend_time = {end_time:?}\n\n[[bodies]]\nname = \"rod\"\nmass = {MASS:?}\n\
         inertia = [{}, {}, {}]\nposition = [0.0, 0.0, {centre:?}]\nvelocity = [0.0, 0.0, {:?}]\nyoung = 2.1e11\n\
         poisson = 0.3\n\n[[bodies.spheres]]\noffset = [{:?}, 0.0, {:?}]\nradius = {RADIUS:?}\n\n\
         [[bodies.spheres]]\noffset = [{:?}, 0.0, {:?}]\nradius = {RADIUS:?}\n\n[[bodies]]\nname = \"floor\"\n\
         mass = inf\nradius = inf\nposition = [0.0, 0.0, 0.0]\nnormal = [0.0, 0.0, 1.0]\nvelocity = [0.0, 0.0, 0.0]\n\
         young = 2.1e11\npoisson = 0.3\n\n[contact]\nlaw = \"hunt-crossley\"\nrestitution = {RESTITUTION:?}\n",
        RADIUS * 1e3,
        GAP * 1e3,
        -G,
        row(0),
        row(1),
        row(2),
        -SPEED,
        end[0],
        end[2],
        -end[0],
        -end[2],
    )
}

/// Runs a world scene's text.
pub fn run(text: &str) -> Result<WorldReport, String> {
    match crate::setup::parse_any(text, Path::new("rod.toml")).map_err(|e| e.to_string())? {
        Parsed::World(scene) => {
            crate::world_run::simulate(&scene).map(|simulation| simulation.report).map_err(|e| e.to_string())
        }
        Parsed::Impact(_) => Err("one impact where a world scene was expected".into()),
    }
}

/// A rigid rod in the x–z plane over a floor z = 0, its end spheres of radius [`RADIUS`] at
/// ±(L/2)(cos θ, 0, sin θ) from its mass centre (end 0 at +, end 1 at -), turning about y.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlanarRod {
    /// Mass centre's height above the floor, m.
    pub z: f64,
    /// Mass centre's vertical velocity, m/s.
    pub vz: f64,
    /// The axis's angle above the floor, from end 1 to end 0, rad.
    pub theta: f64,
    /// Spin about +y, rad/s: it turns the axis down, dθ/dt = -ω.
    pub spin: f64,
}

/// The time step (s) of [`PlanarRod::next_touch`]'s scan for a sign change of an end's height: an end's height has
/// a second derivative below g + (L/2) ω², so a dip below the floor it could miss between two samples is shallower
/// than (g + (L/2) ω²) h²/8: below 1e-9 m for ω up to 500 rad/s.
const SCAN: f64 = 2e-6;

impl PlanarRod {
    /// The rod at first touch of its lower end (end 1) at `degrees`, falling at `speed` without spin.
    pub fn touching(degrees: f64, speed: f64) -> PlanarRod {
        let theta = degrees.to_radians();
        PlanarRod { z: LENGTH / 2.0 * theta.sin() + RADIUS, vz: -speed, theta, spin: 0.0 }
    }

    /// The rod after a free flight of `t` seconds under gravity `g`: the mass centre on its parabola, the spin kept
    /// (y is a principal axis, and the only one turning).
    pub fn flown(&self, t: f64, g: f64) -> PlanarRod {
        PlanarRod {
            z: self.z + self.vz * t - 0.5 * g * t * t,
            vz: self.vz - g * t,
            theta: self.theta - self.spin * t,
            spin: self.spin,
        }
    }

    /// The gap between end `end`'s sphere and the floor, m.
    pub fn gap(&self, end: usize) -> f64 {
        let side = if end == 0 { 1.0 } else { -1.0 };
        self.z + side * LENGTH / 2.0 * self.theta.sin() - RADIUS
    }

    /// End `end`'s horizontal lever from the mass centre, m.
    pub fn lever(&self, end: usize) -> f64 {
        let side = if end == 0 { 1.0 } else { -1.0 };
        side * LENGTH / 2.0 * self.theta.cos()
    }

    /// End `end`'s vertical velocity, m/s: v_z + (ω × r)_z = v_z - ω r_x.
    pub fn end_velocity(&self, end: usize) -> f64 {
        self.vz - self.spin * self.lever(end)
    }

    /// The first time in (0, `horizon`] (s) at which an end's sphere reaches the floor in free flight under `g`,
    /// and which end: scanned in steps of [`SCAN`] for a gap that turns negative, then bisected to the last bit on
    /// the exact flight. An end touching now and leaving (the one just struck) is not a touch.
    pub fn next_touch(&self, g: f64, horizon: f64) -> Option<(f64, usize)> {
        let mut before = 0.0;
        while before < horizon {
            let after = (before + SCAN).min(horizon);
            let state = self.flown(after, g);
            let crossed: Vec<usize> = (0..2).filter(|&end| state.gap(end) < 0.0).collect();
            if !crossed.is_empty() {
                // Each end that crossed, bisected; the earlier crossing is the touch.
                let crossing = |end: usize| {
                    let (mut low, mut high) = (before, after);
                    for _ in 0..200 {
                        let middle = 0.5 * (low + high);
                        if middle <= low || middle >= high {
                            break;
                        }
                        if self.flown(middle, g).gap(end) < 0.0 { high = middle } else { low = middle }
                    }
                    (high, end)
                };
                return crossed.into_iter().map(crossing).min_by(|a, b| a.0.total_cmp(&b.0));
            }
            before = after;
        }
        None
    }

    /// The instantaneous impact of end `end` on the smooth floor with `e`: the impulse `P = -(1 + e) u/(1/M +
    /// r_x²/I_G)` on the end's vertical velocity u (none when it does not approach), `v_z += P/M`,
    /// `ω -= r_x P/I_G` (docs/references.md#rigid-bodies-with-several-contacts). Returns the impulse, N s.
    pub fn strike(&mut self, end: usize, e: f64) -> f64 {
        let u = self.end_velocity(end);
        if u >= 0.0 {
            return 0.0;
        }
        let r = self.lever(end);
        let impulse = -(1.0 + e) * u / (1.0 / MASS + r * r / across());
        self.vz += impulse / MASS;
        self.spin -= r * impulse / across();
        impulse
    }
}

/// An impact sequence's summary.
#[derive(Debug, Clone, PartialEq)]
pub struct Sequence {
    /// The apparent e: v_z⁺/v (module doc).
    pub apparent_e: f64,
    /// Which end each contact of the sequence was of (0 the upper end at the start, 1 the lower).
    pub ends: Vec<usize>,
    /// Each contact's start, from first touch, s.
    pub times: Vec<f64>,
    /// τ: from first touch to the sequence's end (the last contact's end; its start in the instantaneous models), s.
    pub duration: f64,
}

impl Sequence {
    /// The contacts of the sequence (for the sequential model: those that gave an impulse).
    pub fn contacts(&self) -> usize {
        self.ends.len()
    }
}

/// The rigid rod's own sequence at `degrees`, dropped at `speed` (its speed at first touch) with instantaneous end
/// impacts of constant `e` under `g`: impacts and closed-form flights until the mass centre rises and no end
/// touches before the apex; `None` beyond `limit` contacts.
pub fn rigid_sequence(degrees: f64, speed: f64, e: f64, g: f64, limit: usize) -> Option<Sequence> {
    let mut rod = PlanarRod::touching(degrees, speed);
    let (mut now, mut end) = (0.0, 1);
    let (mut ends, mut times) = (Vec::new(), Vec::new());
    for _ in 0..limit {
        rod.strike(end, e);
        ends.push(end);
        times.push(now);
        // Before the apex of the mass centre's flight, or, while it still falls, within the time it takes to fall
        // back through its height at first touch and the rod's length (an end surely touches by then).
        let horizon = if rod.vz > 0.0 { rod.vz / g } else { (-rod.vz + (rod.vz * rod.vz + 2.0 * g).sqrt()) / g };
        match rod.next_touch(g, horizon) {
            None if rod.vz > 0.0 => {
                return Some(Sequence { apparent_e: rod.vz / speed, ends, times, duration: now });
            }
            None => return None,
            Some((t, next)) => {
                rod = rod.flown(t, g);
                now += t;
                end = next;
            }
        }
    }
    None
}

/// The simulated sequence of a world run of [`scene`] (the rod body 0, the floor body 1), and the sequential model's
/// (the report's `sequential.simulated_e`: each simulated contact instantaneous at its start, in the simulation's
/// order, with its simulated e) over the same contacts.
pub fn simulated_sequences(report: &WorldReport) -> Result<(Sequence, Sequence), String> {
    let contacts = &report.contacts;
    let first = contacts.first().ok_or("the rod never touched the floor")?;
    let (start, v) = (first.start_time, first.approach_speed);
    let g = -report.world.gravity[2];
    // The latest end of the contacts so far, and the rod's vertical velocity then.
    let (mut last_end, mut vz) = (f64::NEG_INFINITY, 0.0);
    for (k, c) in contacts.iter().enumerate() {
        let end = c.end_time.ok_or_else(|| format!("contact {k} did not end within the run"))?;
        if end > last_end {
            last_end = end;
            vz = c.velocities_after.ok_or_else(|| format!("contact {k} did not separate"))?[0][2];
        }
        if vz <= 0.0 {
            continue;
        }
        let apex = last_end + vz / g;
        let over = match contacts.get(k + 1) {
            Some(next) => next.start_time > apex,
            None if report.world.end_time >= apex => true,
            None => return Err(format!("the run ended at {} s, before the apex at {apex} s", report.world.end_time)),
        };
        if over {
            let sequence = &contacts[..=k];
            let simulated = Sequence {
                apparent_e: vz / v,
                ends: sequence.iter().map(|c| c.spheres[0].unwrap_or(usize::MAX)).collect(),
                times: sequence.iter().map(|c| c.start_time - start).collect(),
                duration: last_end - start,
            };
            return Ok((simulated, sequential(report, k, g)?));
        }
    }
    Err(format!("the sequence is not over after the run's {} contacts", contacts.len()))
}

/// The sequential model over the simulated sequence's contacts 0..=`last`: its apparent e from the rod's velocity
/// after contact `last` in the model, and the contacts that gave an impulse (a change of the rod's velocity beyond
/// gravity's pull between the contacts' starts).
fn sequential(report: &WorldReport, last: usize, g: f64) -> Result<Sequence, String> {
    let model = report.sequential.simulated_e.as_ref().ok_or("no sequential model with the simulated e")?;
    let contacts = &report.contacts;
    let start = contacts[0].start_time;
    let v = contacts[0].approach_speed;
    let (mut ends, mut times) = (Vec::new(), Vec::new());
    let mut before = report.bodies[0].velocity_before[2] - g * start;
    let mut previous = start;
    for (k, c) in contacts[..=last].iter().enumerate() {
        let after = model.contact_velocities_after.get(k).ok_or("the model has fewer contacts")?[0][2];
        let falling = before - g * (c.start_time - previous);
        if (after - falling).abs() > 1e-9 * v {
            ends.push(c.spheres[0].unwrap_or(usize::MAX));
            times.push(c.start_time - start);
        }
        (before, previous) = (after, c.start_time);
    }
    let duration = previous - start;
    Ok(Sequence { apparent_e: before / v, ends, times, duration })
}

/// One angle of the sweep: the simulation, the sequential model over its contacts, and the rigid rod with the
/// simulated first contact's e.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepPoint {
    /// The rod's angle to the floor when dropped, degrees.
    pub degrees: f64,
    /// The simulated first contact's e (the rigid rod's constant e).
    pub e: f64,
    pub simulated: Sequence,
    pub sequential: Sequence,
    /// `None` when the rigid rod's sequence does not end within 100 contacts.
    pub rigid: Option<Sequence>,
}

/// One angle of the sweep (module doc).
pub fn sweep_point(degrees: f64) -> Result<SweepPoint, String> {
    let report = run(&scene(degrees, MAX_CONTACTS, END_TIME)).map_err(|why| format!("{degrees}°: {why}"))?;
    let (simulated, sequential) = simulated_sequences(&report).map_err(|why| format!("{degrees}°: {why}"))?;
    let first = &report.contacts[0];
    let e = first.restitution_velocity_ratio.ok_or_else(|| format!("{degrees}°: the first contact has no e"))?;
    let rigid = rigid_sequence(degrees, first.approach_speed, e, G, 100);
    Ok(SweepPoint { degrees, e, simulated, sequential, rigid })
}

/// The sweep over `angles` (degrees), on up to two threads.
pub fn sweep(angles: &[f64]) -> Result<Vec<SweepPoint>, String> {
    let half = angles.len().div_ceil(2);
    let (low, high) = angles.split_at(half);
    std::thread::scope(|scope| {
        let other = scope.spawn(|| high.iter().map(|&a| sweep_point(a)).collect::<Result<Vec<_>, _>>());
        let mut points: Vec<SweepPoint> = low.iter().map(|&a| sweep_point(a)).collect::<Result<_, _>>()?;
        points.extend(other.join().map_err(|_| "a thread of the sweep panicked".to_string())??);
        Ok(points)
    })
}

/// The gallery's angles: 1° to 89° in steps of 1°.
pub fn gallery_angles() -> Vec<f64> {
    (1..=89).map(f64::from).collect()
}
