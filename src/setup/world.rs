//! The physics-level rules of a world scene (docs/world.md#limits), checked before any work: every rule one impact
//! applies to its two bodies and their contact ([`super::Setup::new`]), applied to every movable body and to every
//! pair that can touch — with its own `[[pair]]` law — and the rule a world adds because its positions are absolute:
//! a contact must penetrate deeper than their rounding.
//!
//! A contact's rules that depend on its speed (its scales inside double precision, a damping not too heavy to
//! simulate, an elastic penetration below the radii) are checked at the speed in play ([`SpeedInPlay`]): the largest
//! relative speed of two bodies in the scene as given, plus what gravity adds over the scene's height, capped for each
//! pair by what the energy in play could give it. A contact that comes faster in the run (a light ball launched by a
//! heavy one) is checked again when it begins.

use super::{check_law, friction_of, resolve_law};
use crate::body::Body;
use crate::geometry;
use crate::scales::Scales;
use crate::scene::{SetupError, WorldScene};
use crate::units::brief;
use nalgebra::Vector3;
use std::collections::HashMap;

fn fail<T>(key: impl Into<String>, message: impl Into<String>) -> Result<T, SetupError> {
    Err(SetupError { key: key.into(), message: message.into() })
}

/// The length of `v` without overflow in its squares (a velocity of 1e300 m/s is 1e300 m/s long, not inf).
fn length(v: &Vector3<f64>) -> f64 {
    let largest = v.amax();
    if largest == 0.0 || !largest.is_finite() { largest } else { largest * (v / largest).norm() }
}

/// The fastest approach the scene's own motion and gravity give two of its bodies, m/s: the largest relative speed
/// of two bodies that can touch, plus the speed of a fall through the scene's height — and, for a pair, never more
/// than the energy in play could give it. Each contact's speed-dependent rules are checked there before the run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpeedInPlay {
    /// The largest |v_i - v_j| over the pairs that can touch, m/s.
    pub relative: f64,
    /// The pair that has it.
    pub pair: Option<[usize; 2]>,
    /// The scene's height along gravity, m: from the highest centre of a movable body down to the lowest point of any
    /// body as placed (a sphere's bottom, a flat body's point of its face); 0 without gravity.
    pub height: f64,
    /// The speed of a fall through that height, sqrt(2 |g| height), m/s.
    pub fall: f64,
    /// The energy in play, J: the kinetic energy of the movable bodies and gravity's work on them through the
    /// scene's height; infinite when an immovable body moves (a moving wall gives energy without bound).
    pub energy: f64,
}

impl SpeedInPlay {
    /// The speed in play of `scene`.
    pub fn of(scene: &WorldScene) -> SpeedInPlay {
        let bodies = &scene.bodies;
        let (mut relative, mut pair) = (0.0, None);
        // A rigid body's spheres move with its spin too: at most |ω| times their reach faster than its mass centre.
        let turning = |body: &Body| {
            if body.is_rigid() {
                let reach = body.contact_spheres().iter().map(|s| length(&s.offset) + s.radius).fold(0.0, f64::max);
                let reach =
                    reach + body.pivot.map_or(0.0, |pivot| length(&(body.position.unwrap_or_default() - pivot)));
                length(&body.angular_velocity) * reach
            } else {
                0.0
            }
        };
        for i in 0..bodies.len() {
            for j in i + 1..bodies.len() {
                let speed =
                    length(&(bodies[i].velocity - bodies[j].velocity)) + turning(&bodies[i]) + turning(&bodies[j]);
                // (Velocities are finite: a speed beyond double precision is inf, and the finite-motion rule's.)
                if scene.interacts(i, j) && speed > relative {
                    (relative, pair) = (speed, Some([i, j]));
                }
            }
        }
        let g = length(&scene.world.gravity);
        let height = if g > 0.0 {
            let up = -scene.world.gravity / g;
            let at = |body: &Body| body.position.unwrap_or_default().dot(&up);
            let top = bodies.iter().filter(|b| !b.is_immovable()).map(at).fold(f64::NEG_INFINITY, f64::max);
            // (A clump's radius is its bounding radius: its lowest sphere is no lower.)
            let bottom =
                bodies.iter().map(|b| if b.is_flat() { at(b) } else { at(b) - b.radius }).fold(f64::INFINITY, f64::min);
            (top - bottom).max(0.0)
        } else {
            0.0
        };
        let moving_wall = bodies.iter().any(|b| b.is_immovable() && b.velocity != Vector3::zeros());
        let energy = if moving_wall {
            f64::INFINITY
        } else {
            let movable = || bodies.iter().filter(|b| !b.is_immovable());
            movable().map(|b| b.kinetic_energy(&b.velocity, &b.angular_velocity) + b.mass * g * height).sum()
        };
        SpeedInPlay { relative, pair, height, fall: (2.0 * g * height).sqrt(), energy }
    }

    /// The speed at which a pair of effective mass `effective_mass` (kg) is checked, m/s: the speed in play, or the
    /// speed the energy in play could give the pair's relative motion, sqrt(2 E / m*), if smaller (a light body among
    /// fast heavy ones: a 1e-300 kg ball at 1e150 m/s cannot launch two 33 g balls at 1e150 m/s).
    pub fn for_pair(&self, effective_mass: f64) -> f64 {
        self.speed().min((2.0 * self.energy / effective_mass).sqrt())
    }

    /// The speed, m/s.
    pub fn speed(&self) -> f64 {
        self.relative + self.fall
    }

    /// The speed and where it comes from, for a message.
    pub fn describe(&self) -> String {
        let relative = match self.pair {
            Some([i, j]) => format!("bodies {i} and {j} approach at up to {}", brief(self.relative, "m/s")),
            None => "no two bodies move relative to each other".into(),
        };
        let fall = if self.fall > 0.0 {
            format!(
                ", and a fall through the scene's height of {} adds {}",
                brief(self.height, "m"),
                brief(self.fall, "m/s")
            )
        } else {
            String::new()
        };
        format!("the speed in play, {} ({relative}{fall})", brief(self.speed(), "m/s"))
    }

    /// The speed of a pair of effective mass `effective_mass` (kg) and where it comes from, for a message.
    pub fn describe_pair(&self, effective_mass: f64) -> String {
        let speed = self.for_pair(effective_mass);
        // (Told only where it is the smaller by more than rounding: a light ball's own contact has both.)
        if speed < (1.0 - 1e-9) * self.speed() {
            format!(
                "{}, the most the energy in play, {}, could give the pair (sqrt(2 E / m*), m* = {}; {})",
                brief(speed, "m/s"),
                brief(self.energy, "J"),
                brief(effective_mass, "kg"),
                self.describe()
            )
        } else {
            self.describe()
        }
    }
}

/// Every physics-level rule of a world scene whose value rules hold (`scene::rules::check_world`): each movable
/// body's motion inside double precision, and the world's sums of it; each pair that can touch as one impact's
/// contact at the speed in play, its penetration there above the rounding of its positions; the flight over
/// `end_time` inside double precision. The error names the key at fault; the caller locates it.
pub fn check(scene: &WorldScene) -> Result<(), SetupError> {
    let bodies = &scene.bodies;
    let Some(last) = bodies.len().checked_sub(1) else { return Ok(()) };
    if bodies.iter().all(Body::is_immovable) {
        return fail(
            format!("bodies.{last}.mass"),
            "every body is immovable (mass = inf): nothing can move (give a body a finite mass)",
        );
    }
    for (k, body) in bodies.iter().enumerate() {
        check_motion(k, body)?;
    }
    let play = SpeedInPlay::of(scene);
    check_sums(scene, &play)?;
    if let (false, Some([i, j])) = (play.relative.is_finite(), play.pair) {
        return fail(
            format!("bodies.{j}.velocity"),
            format!("the relative velocity of bodies {i} and {j} is outside double precision"),
        );
    }
    let speed = play.speed();
    if !speed.is_finite() {
        return fail(
            "world.gravity",
            format!(
                "a fall through the scene's height of {} at {} is outside double precision",
                brief(play.height, "m"),
                brief(length(&scene.world.gravity), "m/s²")
            ),
        );
    }
    check_flight(scene, speed)?;
    if speed == 0.0 {
        // Nothing moves and nothing falls: no contact can begin, and a contact's rules have no speed.
        return Ok(());
    }
    // Bodies of the same make meet as the same contact: its law is resolved and checked once (a chain of a thousand
    // beads has one class of pairs, not half a million), its deepest penetration kept for the rounding of each pair's
    // positions. The classes kept are bounded ([`CLASSES`]); beyond, a pair is checked on its own.
    let mut makes: HashMap<[u64; 7], usize> = HashMap::new();
    let site_bodies: Vec<Vec<(crate::scene::Site, Body)>> = (0..bodies.len())
        .map(|k| scene.sites_of(k).map(|s| (scene.site(k, s), scene.site_body(k, s))).collect())
        .collect();
    let make: Vec<Vec<usize>> = site_bodies
        .iter()
        .map(|list| {
            list.iter()
                .map(|(_, b)| {
                    let key = [
                        b.mass.to_bits(),
                        b.radius.to_bits(),
                        b.inertia.to_bits(),
                        b.young.map_or(u64::MAX, f64::to_bits),
                        b.poisson.map_or(u64::MAX, f64::to_bits),
                        b.yield_stress.map_or(u64::MAX, f64::to_bits),
                        u64::from(b.is_flat()),
                    ];
                    let next = makes.len();
                    *makes.entry(key).or_insert(next)
                })
                .collect()
        })
        .collect();
    let mut deepest: HashMap<(Option<usize>, usize, usize), Option<f64>> = HashMap::new();
    for i in 0..bodies.len() {
        for j in i + 1..bodies.len() {
            if !scene.interacts(i, j) {
                continue;
            }
            let written = if scene.pairs.is_empty() { None } else { scene.contact_of(i, j).1 };
            // Every sphere of one body against every sphere of the other: each pair is a contact of its own.
            for (p, (site_a, a)) in site_bodies[i].iter().enumerate() {
                for (q, (site_b, b)) in site_bodies[j].iter().enumerate() {
                    let (mi, mj) = (make[i][p], make[j][q]);
                    let class = (written, mi.min(mj), mi.max(mj));
                    let depth = match deepest.get(&class) {
                        Some(&depth) => depth,
                        None => {
                            let depth = check_contact(scene, [site_a, site_b], [a, b], &play)?;
                            if deepest.len() < CLASSES {
                                deepest.insert(class, depth);
                            }
                            depth
                        }
                    };
                    // (A pair the energy in play cannot move relative to each other has no contact to resolve.)
                    let Some(depth) = depth else { continue };
                    let (xa, xb) = (site_a.centre, site_b.centre);
                    let rounding = geometry::touching_tolerance(a, &xa, b, &xb);
                    if depth < rounding {
                        let (smaller, sphere) = if b.radius < a.radius { (j, site_b) } else { (i, site_a) };
                        let key = if scene.bodies[smaller].spheres.is_empty() {
                            format!("bodies.{smaller}.radius")
                        } else {
                            format!("bodies.{smaller}.spheres.{}.radius", sphere.sphere)
                        };
                        return fail(
                            key,
                            format!(
                                "the contact of bodies {i} and {j} would penetrate at most {} at {}, below the rounding of \
                         their positions, {} (64 units in the last place of their coordinates and radii): a world \
                         holds absolute positions, and such a contact is lost in their rounding (a scene of the two \
                         bodies alone measures it from its first contact)",
                                brief(depth, "m"),
                                play.describe_pair(geometry::effective_mass(a, b).unwrap_or(f64::NAN)),
                                brief(rounding, "m")
                            ),
                        );
                    }
                }
            }
        }
    }
    Ok(())
}

/// The most classes of pairs (their contact and their bodies' makes) whose deepest penetration is kept while the
/// pairs are checked: about 5 MB. A world of more makes checks the rest pair by pair, in time and not in memory.
const CLASSES: usize = 65_536;

/// Body `k`'s momentum and kinetic energy, translation and rotation, inside double precision (one impact's rule for
/// each of its bodies).
fn check_motion(k: usize, body: &Body) -> Result<(), SetupError> {
    if body.is_immovable() {
        return Ok(());
    }
    let speed = length(&body.velocity);
    let momentum = body.velocity * body.mass;
    if !momentum.iter().all(|p| p.is_finite()) || !(0.5 * body.mass * speed * speed).is_finite() {
        return fail(
            format!("bodies.{k}.velocity"),
            format!(
                "the momentum or kinetic energy of a body of {} at {} is outside double precision",
                brief(body.mass, "kg"),
                brief(speed, "m/s")
            ),
        );
    }
    if !body.kinetic_energy(&body.velocity, &body.angular_velocity).is_finite() {
        return fail(
            format!("bodies.{k}.angular_velocity"),
            format!(
                "the rotational energy of a body of inertia {} spinning at {} is outside double precision",
                brief(body.inertia, "kg m²"),
                brief(length(&body.angular_velocity), "rad/s")
            ),
        );
    }
    Ok(())
}

/// The world's sums inside double precision: its kinetic energy and momentum (what the report's energy balance and
/// momentum start from), and gravity's work over the scene's height.
fn check_sums(scene: &WorldScene, play: &SpeedInPlay) -> Result<(), SetupError> {
    let movable = || scene.bodies.iter().enumerate().filter(|(_, b)| !b.is_immovable());
    let energies: Vec<(usize, f64)> =
        movable().map(|(k, b)| (k, b.kinetic_energy(&b.velocity, &b.angular_velocity))).collect();
    let total: f64 = energies.iter().map(|(_, e)| e).sum();
    let momentum: Vector3<f64> = movable().map(|(_, b)| b.velocity * b.mass).sum();
    if !total.is_finite() || !momentum.iter().all(|p| p.is_finite()) {
        let (k, _) = energies.iter().copied().fold((0, f64::NEG_INFINITY), |m, e| if e.1 > m.1 { e } else { m });
        return fail(
            format!("bodies.{k}.velocity"),
            "the world's kinetic energy or momentum, summed over its bodies, is outside double precision (this body \
             carries the most energy)",
        );
    }
    let g = length(&scene.world.gravity);
    let work: f64 = movable().map(|(_, b)| b.mass * g * play.height).sum();
    if !work.is_finite() {
        return fail(
            "world.gravity",
            format!(
                "gravity's work on the bodies through the scene's height of {} is outside double precision",
                brief(play.height, "m")
            ),
        );
    }
    Ok(())
}

/// Every body's flight over `end_time` inside double precision: its position, moving at its speed plus the speed in
/// play and accelerated by gravity, stays a number.
fn check_flight(scene: &WorldScene, speed: f64) -> Result<(), SetupError> {
    let Some(end) = scene.world.end_time else { return Ok(()) };
    let g = length(&scene.world.gravity);
    for body in scene.bodies.iter().filter(|b| !b.is_immovable()) {
        let from = body.position.unwrap_or_default().amax();
        let reach = from + (length(&body.velocity) + speed) * end + 0.5 * g * end * end;
        if !reach.is_finite() {
            return fail(
                "world.end_time",
                format!(
                    "over {} a body moving at {} under a gravity of {} would leave double precision: give a shorter \
                     end_time",
                    brief(end, "s"),
                    brief(length(&body.velocity) + speed, "m/s"),
                    brief(g, "m/s²")
                ),
            );
        }
    }
    Ok(())
}

/// One impact's rules of the contact of bodies `i` and `j` at their speed in play ([`SpeedInPlay::for_pair`]) — its
/// law resolved, its scales inside double precision, its damping simulable, its elastic (or plastic) penetration
/// below the smaller radius, its friction formed — renamed to the world's keys; its deepest penetration there, m
/// (`None` for a pair no energy can move).
fn check_contact(
    scene: &WorldScene,
    [site_a, site_b]: [&crate::scene::Site; 2],
    [a, b]: [&Body; 2],
    play: &SpeedInPlay,
) -> Result<Option<f64>, SetupError> {
    let (i, j) = (site_a.body, site_b.body);
    let (spec, _) = scene.contact_of(i, j);
    let effective_mass = geometry::effective_mass(a, b).expect("bodies that can touch are not both immovable");
    let speed = play.for_pair(effective_mass);
    if speed.is_nan() || speed <= 0.0 {
        return Ok(None);
    }
    let rename = |error: SetupError| scene.rename_sites(site_a, site_b, error);
    // A rule broken at the speed in play says which speed that is.
    let at_play = |error: SetupError| {
        let error = scene.rename_sites(site_a, site_b, error);
        SetupError {
            key: error.key,
            message: format!(
                "{} — the contact of bodies {i} and {j}, checked at {} (docs/world.md#limits)",
                error.message,
                play.describe_pair(effective_mass)
            ),
        }
    };
    let law = resolve_law(spec, [a, b], effective_mass, speed).map_err(at_play)?;
    check_law(spec, [a, b], &law, effective_mass, speed).map_err(at_play)?;
    friction_of(spec, [a, b], effective_mass).map_err(rename)?;
    let scales = Scales::new(effective_mass, law.stiffness, law.exponent, speed);
    let n = law.exponent;
    let elastic = ((n + 1.0) / 2.0).powf(1.0 / (n + 1.0)) * scales.length;
    let plastic = if law.yields() {
        crate::reference::thornton(law.yield_penetration / scales.length).max_penetration * scales.length
    } else {
        0.0
    };
    Ok(Some(elastic.max(plastic)))
}
