//! From a scene to the numbers of its contact: first contact, normal, approach speed, effective mass, stiffness
//! and the resolved law. Every physics-level rule of docs/scene.md (its sections on placement, the normal and first
//! contact, on walls and fixed spheres, and its rules across keys) is checked here, and a broken rule names the
//! scene key at fault.
//!
//! Reading a scene with every rule checked is here too, one layer above `scene`, which reads the form and checks the
//! value rules: [`Scene::load`], [`Scene::parse`] and [`Scene::check`], and [`load_any`] and [`parse_any`] for a scene
//! of either kind; a physics-level rule broken there is located at its key's line.

use crate::body::Body;
use crate::geometry::{self, PlacementProblem};
use crate::law::damping::{MapError, damping_for_restitution};
use crate::law::dashpot::dashpot_damping;
use crate::law::{ContactLaw, Family, LawKind, NO_SOLIMP, Separation};
use crate::scales::Scales;
use crate::scene::{
    ContactSpec, DampingSpec, FrictionCap, Parsed, Scene, SceneError, StiffnessSpec, TangentialStiffnessSpec,
    TangentialUnloading,
};
use crate::units::{apart, apart_vectors, brief, brief_vector, short};
use nalgebra::{Matrix3, Vector3};
use std::path::Path;

pub mod world;

/// A broken physics-level rule: the key at fault and what is wrong (the type of the scene's own value rules, which
/// it shares).
use crate::scene::SetupError;

/// The contact of a scene, ready to integrate (SI units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Setup {
    /// Time of first contact, s.
    pub contact_time: f64,
    /// Unit normal at first contact, body 1 -> body 2.
    pub normal: Vector3<f64>,
    /// Where the bodies are at first contact, m: the centres of spheres, a point of a wall's plane (on the line
    /// through the sphere's centre along the normal).
    pub positions: [Vector3<f64>; 2],
    /// v0 = (v1 - v2)·n > 0, m/s.
    pub approach_speed: f64,
    /// m*, kg.
    pub effective_mass: f64,
    /// The law with its stiffness and damping resolved.
    pub law: ContactLaw,
    /// Scaled-variable units of this contact.
    pub scales: Scales,
    /// The tangential contact of a frictional scene; `None` when the contact is smooth (`friction = 0`).
    pub friction: Option<Friction>,
    /// Relative velocity of the centres across the normal at first contact, (v2 - v1) minus its normal part, m/s.
    pub tangential_velocity: Vector3<f64>,
    /// Slip of the contact points at first contact (body 1's contact point relative to body 2's, across the
    /// normal), m/s.
    pub initial_slip: Vector3<f64>,
    /// Which equations the impact needs (see [`Motion`]).
    pub motion: Motion,
    /// For two spheres that also move across the normal: the deepest overlap their free flight would reach,
    /// R (v0² / (|v| (|v| + |v_t|))) with R = r1 + r2, m — a graze shallower than the contact's penetration scale
    /// ends by the bodies sliding off each other, not by the force. `None` for a wall, or without motion across.
    pub graze_depth: Option<f64>,
    /// Each body's effective mass at the contact along the first normal, kg: `1/m_eff = 1/M + (r × n)·I⁻¹(r × n)`
    /// with `r` from the mass centre to the contact sphere's centre, or about the pivot without the `1/M`
    /// (docs/references.md#eccentric-impact); the mass itself for a sphere, infinite for an immovable body.
    pub effective_masses: [f64; 2],
}

/// Which equations of motion an impact needs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Motion {
    /// The relative motion along a fixed normal is the whole story: a smooth (or slip-free) contact whose line of
    /// action cannot turn (a wall, or no relative motion across the normal). Tangential velocities and spins pass
    /// through unchanged. The 1-D model, and the fast path.
    Normal,
    /// Positions, velocities and spins in 3-D: the normal turns with the line of centres, friction changes the
    /// tangential motion and the spins.
    Full,
    /// Rigid bodies struck off their centre or turning about a pivot: each body's orientation is integrated, and its
    /// contact sphere's centre moves with it (`dynamics::rigid`), with or without friction.
    Rigid,
}

/// Coulomb friction with a tangential spring (Mindlin) and optional tangential damping (docs/oblique.md).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Friction {
    /// Coulomb coefficient mu (> 0).
    pub coefficient: f64,
    /// The tangential spring: kt = `stiffness` d^`stiffness_exponent` (N/m), with the exponent 1/2 for Mindlin's
    /// kt = 8 G* sqrt(R* d) (stiffness = 8 G* sqrt(R*) in N/m^(3/2)) and 0 for a constant kt.
    pub stiffness: f64,
    pub stiffness_exponent: f64,
    /// Damping ratio of the tangential spring: c_t = 2 ratio sqrt(kt m_t).
    pub damping_ratio: f64,
    /// m_t = 1/B, B = 1/m1 + 1/m2 + r1²/I1 + r2²/I2: the mass the tangential force sees at the contact point, kg.
    pub tangential_mass: f64,
    /// What the spring does while the contact unloads (`tangential_unloading`).
    pub unloading: TangentialUnloading,
    /// How the Coulomb limit follows the normal force: the scene's `friction_cap`, but `Compressive` wherever
    /// `Magnitude` is the same limit — a law whose force never pulls, or one ended where its force returns to zero
    /// (`separation = "force"`) — so that no passage into tension is watched for that never comes.
    pub cap: FrictionCap,
}

fn fail<T>(key: impl Into<String>, message: impl Into<String>) -> Result<T, SetupError> {
    Err(SetupError { key: key.into(), message: message.into() })
}

/// Relative size (of the approach speed) below which a velocity across the normal counts as zero.
const ACROSS_TOLERANCE: f64 = 1e-12;

/// Relative size (of the bodies' speeds) of a velocity across the normal that is the rounding of the velocities
/// themselves: the relative velocity's components are each within a few ulps of the larger speed.
const ROUNDING: f64 = 16.0 * f64::EPSILON;

/// Largest dissipative-to-elastic force ratio at the contact's own scales (alpha v0 for the hysteresis family,
/// about 2 zeta for Kelvin–Voigt, a for Tsuji): beyond it e is below about 1e-10 and the restitution creeps for
/// longer than any integration can follow, so the scene is refused rather than left to a step-size underflow.
pub const MAX_DAMPING_RATIO: f64 = 1e10;

/// The smallest e an overdamped linear (Kelvin–Voigt) or Tsuji contact ended by its force may have: at e = 1e-10
/// the bodies part at 1e-10 of the approach speed, about a hundred times the rounding of the velocities they carry
/// (their momentum is m* v0 (1 + e)).
pub const MIN_RESTITUTION: f64 = 1e-10;

/// The part of a [`Setup`] that the bodies and the contact's normal decide alone, whatever the law: first contact,
/// the approach speed, the effective masses, the velocities across the normal, with the rules they involve. A sweep
/// whose keys set only the law's numbers (its damping, its restitution, its stiffness...) finds it once for all its
/// points ([`Setup::after`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Approach {
    /// Time of first contact, s.
    contact_time: f64,
    /// Unit normal at first contact, body 1 -> body 2.
    normal: Vector3<f64>,
    /// Where the bodies are at first contact, m.
    positions: [Vector3<f64>; 2],
    /// v0, m/s (> 0).
    approach_speed: f64,
    /// m*, kg.
    effective_mass: f64,
    /// Each body's effective mass at the contact along the normal, kg (the inverse of its inverse, infinite for an
    /// immovable body).
    effective_masses: [f64; 2],
    /// (v2 - v1) across the normal at first contact, m/s (zero at the rounding of the bodies' velocities).
    tangential_velocity: Vector3<f64>,
    /// The contact points' slip across the normal at first contact, m/s (likewise).
    initial_slip: Vector3<f64>,
    /// A body is struck off its centre or turns about a pivot.
    eccentric: bool,
}

impl Approach {
    /// The approach of a scene's bodies, checking the rules of their placement and motion (the first rules
    /// [`Setup::new`] checks, in its order).
    pub fn new(scene: &Scene) -> Result<Approach, SetupError> {
        let [a, b] = &scene.bodies;
        let Some(effective_mass) = geometry::effective_mass(a, b) else {
            return fail("bodies.1.mass", "both bodies are immovable (mass = inf): nothing can move");
        };
        if a.is_flat() && b.is_flat() {
            return fail("bodies.1.radius", "both bodies are flat (radius = inf): one must be a sphere");
        }
        check_finite_motion(&scene.bodies)?;
        let eccentric = a.is_eccentric() || b.is_eccentric();
        let (contact_time, normal, positions) = if eccentric { eccentric_placement(scene)? } else { placement(scene)? };
        // The contact spheres' centres move with the bodies' turning (the same as the mass centres for spheres).
        let sphere_velocity = |body: &Body| body.velocity + body.angular_velocity.cross(&body.contact_offset);
        let approach_speed = (sphere_velocity(a) - sphere_velocity(b)).dot(&normal);
        if approach_speed <= 0.0 || !approach_speed.is_finite() {
            return fail(no_approach_key(scene), no_approach(scene, &normal, approach_speed));
        }
        let inverse_masses = inverse_effective_masses(&scene.bodies, &positions, &normal);
        let effective_mass = if eccentric {
            let total = inverse_masses[0] + inverse_masses[1];
            if !(total > 0.0 && total.is_finite()) {
                let key = if a.pivot.is_some() { "bodies.0.pivot" } else { "bodies.1.pivot" };
                return fail(
                    key,
                    format!(
                        "the effective masses at the contact ({} and {}) leave no motion along the normal: a \
                         pivot on the line of the normal holds its body as if it were immovable",
                        brief(1.0 / inverse_masses[0], "kg"),
                        brief(1.0 / inverse_masses[1], "kg")
                    ),
                );
            }
            1.0 / total
        } else {
            effective_mass
        };
        // A velocity across the normal at the rounding of the bodies' own velocities is none: a common motion far
        // faster than the relative one (stress case 9579 of seed 8675309 moves at 740 m/s and closes at 1.3 um/s)
        // leaves its rounding across the normal, and the ratios of the report's oblique section would be ratios of
        // rounding ("tangential restitution, centres 473545").
        let rounding = |across: Vector3<f64>, scale: f64| {
            if across.norm() <= ROUNDING * scale { Vector3::zeros() } else { across }
        };
        let speeds = a.velocity.norm() + b.velocity.norm();
        let tangential_velocity = {
            let relative = b.velocity - a.velocity;
            rounding(relative - normal * relative.dot(&normal), speeds)
        };
        let initial_slip = if eccentric {
            let slip = eccentric_contact_point_slip(&scene.bodies, &positions, &normal);
            let turning: f64 = (0..2)
                .map(|i| {
                    scene.bodies[i].angular_velocity.norm() * contact_points(&scene.bodies, &positions, &normal)[i].1
                })
                .sum();
            rounding(slip, speeds + turning)
        } else {
            let [arm_a, arm_b] = Setup::lever_arms(&scene.bodies, &normal);
            let turning = a.angular_velocity.cross(&arm_a).norm() + b.angular_velocity.cross(&arm_b).norm();
            rounding(contact_point_slip(&scene.bodies, &normal), speeds + turning)
        };
        Ok(Approach {
            contact_time,
            normal,
            positions,
            approach_speed,
            effective_mass,
            effective_masses: inverse_masses.map(|w| 1.0 / w),
            tangential_velocity,
            initial_slip,
            eccentric,
        })
    }
}

impl Setup {
    /// Resolves a scene's contact, checking the rules that involve more than one key.
    pub fn new(scene: &Scene) -> Result<Setup, SetupError> {
        Setup::after(scene, &Approach::new(scene)?)
    }

    /// [`Setup::new`] of a scene whose [`Approach`] is known: `approach` must be that of a scene with the same bodies
    /// and the same contact normal (a sweep's point that sets only the law's numbers, and its base). The same setup,
    /// bit for bit, and the same first broken rule: the rules [`Approach::new`] checks come first in [`Setup::new`],
    /// and the approach depends on nothing else.
    pub fn after(scene: &Scene, approach: &Approach) -> Result<Setup, SetupError> {
        let [a, b] = &scene.bodies;
        let Approach {
            contact_time,
            normal,
            positions,
            approach_speed,
            effective_mass,
            effective_masses,
            tangential_velocity,
            initial_slip,
            eccentric,
        } = *approach;
        let law = resolve_law(&scene.contact, [a, b], effective_mass, approach_speed)?;
        let scales = check_law(&scene.contact, [a, b], &law, effective_mass, approach_speed)?;
        let friction = friction(scene, effective_mass)?.map(|f| {
            if eccentric {
                Friction { tangential_mass: eccentric_tangential_mass(&scene.bodies, &positions, &normal), ..f }
            } else {
                f
            }
        });
        let coupled = friction.is_some() && initial_slip.norm() > ACROSS_TOLERANCE * approach_speed;
        let turning = !a.is_flat() && !b.is_flat() && tangential_velocity.norm() > ACROSS_TOLERANCE * approach_speed;
        let motion = if eccentric {
            Motion::Rigid
        } else if coupled || turning {
            Motion::Full
        } else {
            Motion::Normal
        };
        if scene.solver.method.is_fixed_step() && motion != Motion::Normal {
            return fail(
                "solver.method",
                format!(
                    "method = \"{}\" runs the peers' fixed-step scheme on the 1-D normal contact (a central impact, \
                     or a smooth one along a fixed normal); this impact needs the {}: use \"auto\" or \"dop853\"",
                    scene.solver.method.name(),
                    match motion {
                        Motion::Rigid => "rigid-body model (a body struck off its centre or turning about a pivot)",
                        _ => "3-D model (an oblique impact of two spheres, or friction with slip)",
                    }
                ),
            );
        }
        let graze_depth = if turning && !eccentric {
            Some(graze(scene, &normal, approach_speed, &tangential_velocity)?)
        } else {
            None
        };
        Ok(Setup {
            contact_time,
            normal,
            positions,
            approach_speed,
            effective_mass,
            law,
            scales,
            friction,
            tangential_velocity,
            initial_slip,
            motion,
            graze_depth,
            effective_masses,
        })
    }

    /// Lever arms from each centre to the contact point at first contact, m: the contact point divides the line of
    /// centres in the ratio of the radii (see [`crate::dynamics::contact`]); a wall's arm is zero (it does not
    /// rotate).
    pub fn lever_arms(bodies: &[Body; 2], normal: &Vector3<f64>) -> [Vector3<f64>; 2] {
        let [a, b] = bodies;
        let arm =
            |body: &Body, sign: f64| if body.is_flat() { Vector3::zeros() } else { normal * (sign * body.radius) };
        [arm(a, 1.0), arm(b, -1.0)]
    }
}

impl Scene {
    /// Reads and validates a scene file.
    pub fn load(path: &Path) -> Result<Scene, SceneError> {
        let text = std::fs::read_to_string(path)
            .map_err(|error| SceneError::file(path, format!("cannot read the scene: {error}")))?;
        Scene::parse(&text, path)
    }

    /// Validates scene text: its form, every value rule and the physics-level rules of [`Setup`], a broken one
    /// located; `path` names the source in errors and gives the default title.
    pub fn parse(text: &str, path: &Path) -> Result<Scene, SceneError> {
        let read = Scene::read(text, path)?;
        Setup::new(&read.scene).map_err(|error| read.located(error))?;
        Ok(read.scene)
    }

    /// Checks every value rule of a scene (ranges, and the rules between keys) and the physics-level rules of
    /// [`Setup`]: the same rules [`Scene::parse`] applies, on a scene already typed (a sweep's point). The error
    /// names the key; it has no file or line.
    pub fn check(&self) -> Result<Setup, SetupError> {
        self.check_rules()?;
        Setup::new(self)
    }

    /// [`Scene::check`] without the groups of value rules in `known`, which the caller knows this scene passes
    /// ([`Scene::check_rules_except`]), and with its [`Approach`] when the caller knows it (that of a scene with the
    /// same bodies and contact normal: [`Setup::after`]): the same setup, or the same error.
    pub fn check_except(
        &self,
        known: crate::scene::RuleGroups,
        approach: Option<&Approach>,
    ) -> Result<Setup, SetupError> {
        self.check_rules_except(known)?;
        match approach {
            Some(approach) => Setup::after(self, approach),
            None => Setup::new(self),
        }
    }
}

/// Reads and validates a scene file of either kind.
pub fn load_any(path: &Path) -> Result<Parsed, SceneError> {
    let text = std::fs::read_to_string(path)
        .map_err(|error| SceneError::file(path, format!("cannot read the scene: {error}")))?;
    parse_any(&text, path)
}

/// Validates scene text of either kind with its physics-level rules: those of [`Setup`] for a two-body scene, those of
/// [`world::check`] for a world; `path` names the source in errors and gives the default title.
pub fn parse_any(text: &str, path: &Path) -> Result<Parsed, SceneError> {
    let read = crate::scene::read_any(text, path)?;
    match &read.scene {
        Parsed::Impact(scene) => Setup::new(scene).map(|_| ()),
        Parsed::World(scene) => world::check(scene),
    }
    .map_err(|error| read.located(error))?;
    Ok(read.scene)
}

/// The contact law of `contact` between `bodies` (effective mass `effective_mass`, kg), its damping mapped from a
/// nominal e at `map_speed` (m/s: the hysteresis family's alpha = chi(e)/v0; the contact's approach speed in a
/// two-body run). The rules of docs/scene.md that name `contact.*` keys.
pub fn resolve_law(
    contact: &ContactSpec,
    bodies: [&Body; 2],
    effective_mass: f64,
    map_speed: f64,
) -> Result<ContactLaw, SetupError> {
    let [a, b] = bodies;
    let kind = contact.law;
    if kind.family() == Family::Impedance {
        return Ok(mujoco_law(contact, effective_mass));
    }
    let stiffness = match contact.stiffness {
        StiffnessSpec::Value(k) => k,
        StiffnessSpec::Hertz => hertz_stiffness(a, b)?,
    };
    let exponent = contact.exponent;
    let damping = match contact.damping {
        DampingSpec::None if kind.family() == Family::Ramp => contact.cmax.unwrap_or(0.0),
        DampingSpec::None => 0.0,
        DampingSpec::Parameter(value) => value,
        // K d + c d' is Kelvin–Voigt: its exact map. Another exponent's e depends on the speed: the c that gives e
        // at this contact's speed, found by a root-find on the simulated contact (law::dashpot).
        DampingSpec::Restitution(e) if kind.family() == Family::Dashpot => {
            if exponent == 1.0 {
                damping_for_restitution(LawKind::KelvinVoigt, e, stiffness, effective_mass, map_speed)
                    .map_err(|_| SetupError { key: "contact.restitution".into(), message: "no map at e = 0".into() })?
            } else {
                let separation = contact.separation;
                let found = dashpot_damping(e, stiffness, exponent, effective_mass, map_speed, separation);
                let Some(damping) = found else {
                    return fail(
                        "contact.restitution",
                        format!(
                            "no dashpot c of `hertz-dashpot` (exponent {}, separation = \"{}\") gives e = {} \
                             at this contact's speed: e = 0 needs an infinite c; ask for a small positive e",
                            short(exponent),
                            separation.name(),
                            short(e)
                        ),
                    );
                };
                damping
            }
        }
        DampingSpec::Restitution(e) => {
            damping_for_restitution(kind, e, stiffness, effective_mass, map_speed).or_else(|error| {
                let why = match error {
                    MapError::NoMap => format!("the law `{}` has no restitution map", kind.name()),
                    MapError::UndefinedAtZero => format!("the map of `{}` is undefined at e = 0", kind.name()),
                };
                fail("contact.restitution", why)
            })?
        }
    };
    if !damping.is_finite() {
        return fail(damping_key(contact), format!("the damping {} is not a finite number", brief(damping, "")));
    }
    let tsuji_scale = if kind.family() == Family::Tsuji { (effective_mass * stiffness).sqrt() } else { 0.0 };
    let yield_penetration =
        if kind.family() == Family::Plastic { yield_penetration(contact, bodies, stiffness)? } else { f64::INFINITY };
    let ramp = if kind.family() == Family::Ramp { contact.dmax.unwrap_or(f64::INFINITY) } else { f64::INFINITY };
    Ok(ContactLaw { kind, stiffness, exponent, damping, tsuji_scale, yield_penetration, solimp: NO_SOLIMP, ramp })
}

/// MuJoCo's default `solref`: [timeconst 0.02 s, dampratio 1].
pub const DEFAULT_SOLREF: [f64; 2] = [0.02, 1.0];

/// The `mujoco` law of `contact` for a contact of effective mass `effective_mass` (kg): MuJoCo's per-unit-mass
/// spring k and damper b from `solref` — [timeconst, dampratio]: b = 2/(d_max timeconst), k = 1/(d_max² timeconst²
/// dampratio²); [-stiffness, -damping]: b = damping/d_max, k = stiffness/d_max² — times m*, so that the force is
/// m* d(d) (k d(d) d + b d'). MuJoCo's `refsafe` (timeconst at least twice its time step) belongs to a fixed step, not
/// to this continuous-time law.
pub fn mujoco_law(contact: &ContactSpec, effective_mass: f64) -> ContactLaw {
    let solimp = contact.solimp.unwrap_or(NO_SOLIMP);
    let high = solimp[1];
    let [a, b] = contact.solref.unwrap_or(DEFAULT_SOLREF);
    let (stiffness, damping) =
        if a > 0.0 { (1.0 / (high * high * a * a * b * b), 2.0 / (high * a)) } else { (-a / (high * high), -b / high) };
    ContactLaw {
        kind: contact.law,
        stiffness: stiffness * effective_mass,
        exponent: 1.0,
        damping: damping * effective_mass,
        tsuji_scale: 0.0,
        yield_penetration: f64::INFINITY,
        solimp,
        ramp: f64::INFINITY,
    }
}

/// The `thornton` law's yield pressure p_y, Pa: the contact's `yield_pressure`, or 1.6 times the smaller
/// `yield_stress` of the bodies that give one (the onset of yield under a Hertz contact, Johnson, Contact Mechanics
/// ch. 11); `None` when neither is given.
pub fn yield_pressure(contact: &ContactSpec, bodies: [&Body; 2]) -> Option<f64> {
    contact.yield_pressure.or_else(|| {
        let stresses = bodies.iter().filter_map(|body| body.yield_stress);
        stresses.reduce(f64::min).map(|stress| 1.6 * stress)
    })
}

/// The penetration d_y (m) at which a `thornton` contact of stiffness K = `stiffness` starts to yield:
/// d_y = (pi p_y / (2 E*))² R* with E* = 3 K / (4 sqrt(R*)), that is R* (2 pi p_y sqrt(R*) / (3 K))²; infinite for an
/// infinite yield pressure (the contact is Hertz's).
fn yield_penetration(contact: &ContactSpec, bodies: [&Body; 2], stiffness: f64) -> Result<f64, SetupError> {
    let Some(pressure) = yield_pressure(contact, bodies) else {
        return fail(
            "contact.yield_pressure",
            "missing: `thornton` needs `yield_pressure` p_y in Pa, or `yield_stress` (Pa) of a body",
        );
    };
    let [a, b] = bodies;
    let radius = crate::geometry::effective_radius(a, b).unwrap_or(f64::NAN);
    let scaled = 2.0 * std::f64::consts::PI * pressure * radius.sqrt() / (3.0 * stiffness);
    let penetration = radius * scaled * scaled;
    if penetration.is_nan() || penetration <= 0.0 {
        return fail(
            "contact.yield_pressure",
            format!(
                "the yield pressure {} gives no yield penetration (R* = {}, K = {})",
                brief(pressure, "Pa"),
                brief(radius, "m"),
                brief(stiffness, "N/m^1.5")
            ),
        );
    }
    Ok(penetration)
}

/// The scene key the damping comes from.
fn damping_key(contact: &ContactSpec) -> &'static str {
    match (contact.law.family(), contact.damping) {
        (Family::Impedance, _) => "contact.solref",
        (Family::Ramp, _) => "contact.cmax",
        (_, DampingSpec::Restitution(_)) => "contact.restitution",
        _ => "contact.damping",
    }
}

/// The scaled units of a contact of `law` between `bodies` approaching at `approach_speed` (m/s), after the rules
/// that need them: the scales inside double precision, the damping not too heavy to simulate or to resolve, the
/// elastic penetration below the smaller radius.
pub fn check_law(
    contact: &ContactSpec,
    bodies: [&Body; 2],
    law: &ContactLaw,
    effective_mass: f64,
    approach_speed: f64,
) -> Result<Scales, SetupError> {
    let scales = Scales::new(effective_mass, law.stiffness, law.exponent, approach_speed);
    check_scales(&scales)?;
    let ratio = law.damping_ratio(scales.length, scales.speed);
    let damping_key = damping_key(contact);
    if ratio.is_nan() || ratio > MAX_DAMPING_RATIO {
        return fail(
            damping_key,
            format!(
                "the damping is too heavy to simulate: its force is {} times the elastic force at the contact's own \
                 scales (at most {}; e would be below about 1e-10, and the restitution creeps for longer than any \
                 integration can follow)",
                brief(ratio, ""),
                brief(MAX_DAMPING_RATIO, "")
            ),
        );
    }
    if contact.separation == Separation::Force {
        check_creep(law, effective_mass, damping_key)?;
    }
    check_size(contact, bodies, law, &scales)?;
    Ok(scales)
}

/// Slip of the contact points before impact: (v1 + w1 x a1) - (v2 + w2 x a2), its part across the normal.
/// Each body's contact point at first contact, with the mass centres at `positions` (m), and its distance from the
/// body's origin (mass centre or pivot; m): the point of its contact sphere towards the other body, as the rigid-body
/// model's friction takes it (`dynamics::rigid`). A flat body's is the other's.
pub fn contact_points(
    bodies: &[Body; 2],
    positions: &[Vector3<f64>; 2],
    normal: &Vector3<f64>,
) -> [(Vector3<f64>, f64); 2] {
    let sphere = |i: usize| {
        let body = &bodies[i];
        let sign = if i == 0 { 1.0 } else { -1.0 };
        positions[i] + body.contact_offset + normal * (sign * body.radius)
    };
    let point = |i: usize| if bodies[i].is_flat() { sphere(1 - i) } else { sphere(i) };
    [0, 1].map(|i| {
        let p = point(i);
        (p, (p - bodies[i].pivot.unwrap_or(positions[i])).norm())
    })
}

/// The contact points' slip at first contact for an eccentric or pivoted body (body 1's point relative to body 2's,
/// across the normal; m/s): each point moves at `v + ω × r` from its body's mass centre (a pivot's: `ω × r_O`); a
/// flat body's point at its velocity (its spin does not move its plane), as in the spheres' model.
fn eccentric_contact_point_slip(
    bodies: &[Body; 2],
    positions: &[Vector3<f64>; 2],
    normal: &Vector3<f64>,
) -> Vector3<f64> {
    let points = contact_points(bodies, positions, normal);
    let velocity = |i: usize| {
        let body = &bodies[i];
        if body.is_flat() { body.velocity } else { rigid_body(body, positions[i]).point_velocity(&points[i].0) }
    };
    let relative = velocity(0) - velocity(1);
    relative - normal * relative.dot(normal)
}

/// The mass the tangential force sees at the contact point of an eccentric or pivoted body, kg: `1/B` with `B` the
/// mean of the contact points' compliance `K = K_1 + K_2` across the normal, `(tr K - n·K n)/2`
/// (crate::eccentric::point_compliance). For two spheres `K` is `B 1` across the normal, with the spheres' `B`.
fn eccentric_tangential_mass(bodies: &[Body; 2], positions: &[Vector3<f64>; 2], normal: &Vector3<f64>) -> f64 {
    let points = contact_points(bodies, positions, normal);
    let compliance = |i: usize| {
        let body = &bodies[i];
        if !body.rotates() || body.is_flat() {
            return Matrix3::identity() * body.inverse_mass();
        }
        crate::eccentric::point_compliance(&rigid_body(body, positions[i]), &points[i].0)
    };
    let k = compliance(0) + compliance(1);
    2.0 / (k.trace() - normal.dot(&(k * normal)))
}

fn contact_point_slip(bodies: &[Body; 2], normal: &Vector3<f64>) -> Vector3<f64> {
    let [a, b] = bodies;
    let [arm_a, arm_b] = Setup::lever_arms(bodies, normal);
    let spin = |body: &Body, arm: &Vector3<f64>| {
        if body.angular_velocity == Vector3::zeros() { Vector3::zeros() } else { body.angular_velocity.cross(arm) }
    };
    let relative = (a.velocity + spin(a, &arm_a)) - (b.velocity + spin(b, &arm_b));
    relative - normal * relative.dot(normal)
}

/// The key to name when the bodies do not approach: `contact.normal` when the normal was the default.
fn no_approach_key(scene: &Scene) -> &'static str {
    let placed = scene.bodies.iter().all(|body| body.position.is_some());
    let wall = scene.bodies.iter().any(Body::is_flat);
    if scene.contact.normal.is_none() && (!placed || wall) { "contact.normal" } else { "bodies.0.velocity" }
}

fn no_approach(scene: &Scene, normal: &Vector3<f64>, approach_speed: f64) -> String {
    let [a, b] = &scene.bodies;
    let placed = scene.bodies.iter().all(|body| body.position.is_some());
    let wall = scene.bodies.iter().any(Body::is_flat);
    let which = match (scene.contact.normal.is_some(), placed && !wall) {
        (_, true) => "the line of centres at first contact",
        (true, false) => "the scene's `contact.normal`",
        (false, false) => "the default normal (no `contact.normal` given)",
    };
    let (first, second) = apart(a.velocity.dot(normal), b.velocity.dot(normal), "m/s");
    format!(
        "the bodies do not approach along {which} {}: normal velocities {first} (body 1) and {second} (body 2) give \
         an approach speed (v1 - v2)·n = {}, which must be > 0",
        brief_vector(normal.as_slice(), ""),
        brief(approach_speed, "m/s")
    )
}

/// Quantities derived from the inputs must stay inside double precision: each movable body's momentum and kinetic
/// energy (translation and rotation), and the relative velocity.
fn check_finite_motion(bodies: &[Body; 2]) -> Result<(), SetupError> {
    for (i, body) in bodies.iter().enumerate() {
        if body.is_immovable() {
            continue;
        }
        let momentum = body.velocity * body.mass;
        let kinetic = body.kinetic_energy(&body.velocity, &body.angular_velocity);
        if !momentum.iter().all(|p| p.is_finite()) || !(0.5 * body.mass * body.velocity.norm_squared()).is_finite() {
            return fail(
                format!("bodies.{i}.velocity"),
                format!(
                    "the momentum or kinetic energy of a body of {} at {} is outside double precision",
                    brief(body.mass, "kg"),
                    brief_vector(body.velocity.as_slice(), "m/s")
                ),
            );
        }
        if !kinetic.is_finite() {
            return fail(
                format!("bodies.{i}.angular_velocity"),
                format!(
                    "the rotational energy of a body of inertia {} spinning at {} is outside double precision",
                    brief(body.inertia, "kg m²"),
                    brief_vector(body.angular_velocity.as_slice(), "rad/s")
                ),
            );
        }
    }
    let relative = bodies[1].velocity - bodies[0].velocity;
    if !relative.norm().is_finite() {
        return fail("bodies.1.velocity", "the relative velocity of the bodies is outside double precision");
    }
    Ok(())
}

/// The tangential contact of a frictional scene, or `None` for a smooth one. In one impact, with no other force, a
/// law of the Hunt–Crossley family never pulls (its bodies part at e v0 < 1/alpha: x (1 + e) = ln((1 + x)/(1 - e x))
/// needs e x < 1), so that its two Coulomb caps are one: the compressive one is kept, whose limit has no kink at a
/// zero force. (A creeping restitution, 1 + alpha d' near zero for seconds, would otherwise cross the magnitude
/// cap's kink on rounding, back and forth: stress case 16680 of seed 424242 switched 55 times and spent its step
/// budget.) In a world, where other forces can part the bodies faster, the magnitude cap stays.
fn friction(scene: &Scene, effective_mass: f64) -> Result<Option<Friction>, SetupError> {
    let [a, b] = &scene.bodies;
    let friction = friction_of(&scene.contact, [a, b], effective_mass)?;
    let never_pulls = scene.contact.law.family() == crate::law::Family::Hysteresis;
    Ok(friction.map(|f| if never_pulls { Friction { cap: FrictionCap::Compressive, ..f } } else { f }))
}

/// The tangential contact `contact` gives bodies `a` and `b` (of effective mass `effective_mass`, kg), or `None` for a
/// smooth one; errors name the keys of `[contact]` (a world renames them to its pair's).
pub fn friction_of(
    contact: &ContactSpec,
    [a, b]: [&Body; 2],
    effective_mass: f64,
) -> Result<Option<Friction>, SetupError> {
    if contact.friction == 0.0 {
        return Ok(None);
    }
    let (stiffness, stiffness_exponent) = match contact.tangential_stiffness {
        TangentialStiffnessSpec::Value(k) => (k, 0.0),
        TangentialStiffnessSpec::Mindlin => (mindlin_coefficient(a, b)?, 0.5),
    };
    // B = 1/m1 + 1/m2 + r1²/I1 + r2²/I2: a body that does not rotate adds only its 1/m.
    let rotational = |body: &Body| if body.rotates() { body.radius * body.radius / body.inertia } else { 0.0 };
    let inverse = 1.0 / effective_mass + rotational(a) + rotational(b);
    Ok(Some(Friction {
        coefficient: contact.friction,
        stiffness,
        stiffness_exponent,
        damping_ratio: contact.tangential_damping,
        tangential_mass: 1.0 / inverse,
        unloading: contact.tangential_unloading,
        cap: if contact.law.can_pull() && !(contact.separation == Separation::Force && contact.law.can_turn_tensile()) {
            contact.friction_cap
        } else {
            FrictionCap::Compressive
        },
    }))
}

/// 8 G* sqrt(R*) in N/m^(3/2), with 1/G* = (2 - nu1)/G1 + (2 - nu2)/G2 and G = E / (2 (1 + nu)) (docs/oblique.md).
fn mindlin_coefficient(a: &Body, b: &Body) -> Result<f64, SetupError> {
    const KEY: &str = "contact.tangential_stiffness";
    let mut compliance = 0.0;
    for (i, body) in [a, b].iter().enumerate() {
        match (body.young, body.poisson) {
            (Some(e), _) if e.is_infinite() => {}
            (Some(e), Some(nu)) => compliance += (2.0 - nu) * 2.0 * (1.0 + nu) / e,
            _ => {
                return fail(
                    KEY,
                    format!(
                        "the Mindlin tangential stiffness (the default) needs `young` and `poisson` of every \
                         elastic body (bodies.{i} lacks them): give them, or a numeric `tangential_stiffness` in N/m"
                    ),
                );
            }
        }
    }
    if compliance == 0.0 {
        return fail(KEY, "both bodies are rigid (young = inf): the Mindlin stiffness would be infinite");
    }
    let radius = geometry::effective_radius(a, b).expect("two flat bodies were rejected before");
    Ok(8.0 / compliance * radius.sqrt())
}

/// When (s) and along which normal the bodies first touch, and where they are then (m).
type Placement = (f64, Vector3<f64>, [Vector3<f64>; 2]);

/// Each body's inverse effective mass along `normal` at its contact sphere's centre (on the line of the normal
/// force), 1/kg, with the mass centres at `positions`: 1/M for a body that does not turn (0 for an immovable one).
pub fn inverse_effective_masses(bodies: &[Body; 2], positions: &[Vector3<f64>; 2], normal: &Vector3<f64>) -> [f64; 2] {
    let inverse = |i: usize| {
        let body = &bodies[i];
        if !body.rotates() || !body.is_eccentric() {
            return body.inverse_mass();
        }
        rigid_body(body, positions[i]).inverse_effective_mass(&(positions[i] + body.contact_offset), normal)
    };
    [inverse(0), inverse(1)]
}

/// A scene body as the instantaneous eccentric impact takes it, its mass centre at `centre` (m).
pub fn rigid_body(body: &Body, centre: Vector3<f64>) -> crate::eccentric::RigidBody {
    crate::eccentric::RigidBody {
        mass: body.mass,
        inertia: body.inertia_matrix(),
        centre,
        velocity: body.velocity,
        spin: body.angular_velocity,
        pivot: body.pivot,
    }
}

/// The first contact of a scene with an eccentric or pivoted body: the contact spheres' centres fly straight (the
/// rules below see to it), so [`placement`] places them, and each mass centre sits its `contact_offset` behind its
/// sphere's centre. Without positions, body 1's mass centre is at the origin.
fn eccentric_placement(scene: &Scene) -> Result<Placement, SetupError> {
    let placed = scene.bodies.iter().all(|body| body.position.is_some());
    for (i, body) in scene.bodies.iter().enumerate() {
        let Some(pivot) = body.pivot else { continue };
        if !placed {
            return fail(
                format!("bodies.{i}.pivot"),
                "a pivot is a point in scene coordinates: give `position` for both bodies",
            );
        }
        let arm = body.position.unwrap_or_default() - pivot;
        let turning = body.angular_velocity.cross(&arm);
        let size = body.velocity.norm().max(turning.norm());
        if (body.velocity - turning).norm() > 1e-9 * size {
            let (turning, velocity) = apart_vectors(turning.as_slice(), body.velocity.as_slice(), "m/s");
            return fail(
                format!("bodies.{i}.velocity"),
                format!(
                    "a body turning about its pivot moves with angular_velocity × (position - pivot) = {turning}, \
                     not {velocity}"
                ),
            );
        }
    }
    let mut spheres = scene.clone();
    for body in &mut spheres.bodies {
        if let Some(position) = &mut body.position {
            *position += body.contact_offset;
        }
    }
    let (time, normal, mut positions) = placement(&spheres)?;
    for (i, body) in scene.bodies.iter().enumerate() {
        if !body.is_flat() {
            positions[i] -= body.contact_offset;
        }
        if time > 0.0 && body.is_eccentric() && body.angular_velocity != Vector3::zeros() {
            return fail(
                format!("bodies.{i}.angular_velocity"),
                "an eccentric or pivoted body that spins must start at its first contact: its contact sphere would \
                 not fly straight to it (give the positions at first contact, or no spin)",
            );
        }
    }
    if !placed && !scene.bodies[0].is_flat() {
        let shift = scene.bodies[0].contact_offset;
        positions = positions.map(|x| x + shift);
    }
    Ok((time, normal, positions))
}

/// The first contact of the scene's bodies.
fn placement(scene: &Scene) -> Result<Placement, SetupError> {
    let [a, b] = &scene.bodies;
    let given = scene.contact.normal;
    let scene_normal = given.unwrap_or_else(Vector3::x);
    match (a.position, b.position) {
        (None, None) => {
            // Body 1 at the origin, body 2 touching it along the normal.
            let reach = |body: &Body| if body.is_flat() { 0.0 } else { body.radius };
            Ok((0.0, scene_normal, [Vector3::zeros(), scene_normal * (reach(a) + reach(b))]))
        }
        (Some(_), None) => fail("bodies.1.position", "give `position` for both bodies or for neither"),
        (None, Some(_)) => fail("bodies.0.position", "give `position` for both bodies or for neither"),
        (Some(xa), Some(xb)) => {
            let contact = geometry::first_contact(a, b, &scene_normal).or_else(|problem| match problem {
                PlacementProblem::Overlapping(overlap) => fail(
                    "bodies.1.position",
                    format!(
                        "the bodies start overlapped by {} (more than {} of the smaller radius)",
                        brief(overlap, "m"),
                        brief(geometry::TOUCH_TOLERANCE, "")
                    ),
                ),
                PlacementProblem::NeverMeet => fail(
                    "bodies.1.position",
                    "the bodies never meet: their straight-line paths from these positions and velocities never \
                     bring them into contact",
                ),
                PlacementProblem::CoincidentCentres => {
                    fail("bodies.1.position", "the two sphere centres coincide: no line of centres")
                }
            })?;
            if !contact.time.is_finite() {
                return fail(
                    "bodies.1.position",
                    "the time of first contact cannot be computed in double precision (the bodies are too far apart \
                     for their speeds)",
                );
            }
            let spheres = !a.is_flat() && !b.is_flat();
            if let (true, Some(normal)) = (spheres, given)
                && (normal - contact.normal).norm() > 1e-9
            {
                let (given, centres) = apart_vectors(normal.as_slice(), contact.normal.as_slice(), "");
                return fail(
                    "contact.normal",
                    format!("the given normal {given} disagrees with the line of centres at first contact {centres}"),
                );
            }
            let t = contact.time;
            let mut positions = [xa + a.velocity * t, xb + b.velocity * t];
            // A wall is represented by the point of its plane on the normal through the sphere's centre.
            let n = contact.normal;
            if a.is_flat() {
                positions[0] = positions[1] - n * b.radius;
            } else if b.is_flat() {
                positions[1] = positions[0] + n * a.radius;
            }
            if !positions.iter().all(|x| x.iter().all(|c| c.is_finite())) {
                return fail("bodies.1.position", "the positions at first contact are outside double precision");
            }
            Ok((t, n, positions))
        }
    }
}

/// The scaled formulation needs finite, non-zero units: m* v0² and its ratio to K must stay inside double
/// precision (a velocity of 1e200 m/s or a body of 1e-300 kg do not).
fn check_scales(scales: &Scales) -> Result<(), SetupError> {
    let units = [scales.length, scales.time, scales.force, scales.impulse, scales.energy];
    if units.iter().all(|u| u.is_finite() && *u > 0.0) {
        return Ok(());
    }
    fail(
        "bodies.0.velocity",
        format!(
            "the contact's scales leave double precision (penetration scale {}, time scale {}, energy scale m* v0² = \
             {}): check the masses, velocities and stiffness",
            brief(scales.length, "m"),
            brief(scales.time, "s"),
            brief(scales.energy, "J")
        ),
    )
}

/// The elastic penetration (m) of the contact must stay below the bodies' size: a contact law describes a dent,
/// and a penetration as deep as a radius has the bodies pass through each other (a stiffness of 1e-50 Pa, or a speed
/// far beyond the material's, does that). The elastic maximum penetration ((n + 1)/2)^(1/(n+1)) L is compared with
/// the smaller finite radius; the stiffness key is named (the softer body's `young` for a Hertz stiffness).
fn check_size(contact: &ContactSpec, bodies: [&Body; 2], law: &ContactLaw, scales: &Scales) -> Result<(), SetupError> {
    let smallest = bodies.iter().map(|body| body.radius).fold(f64::INFINITY, f64::min);
    thread_local! {
        static FACTOR: crate::scales::Remembered = const { crate::scales::Remembered::new() };
    }
    let n = law.exponent;
    let elastic = crate::scales::powf_remembered(&FACTOR, (n + 1.0) / 2.0, 1.0 / (n + 1.0)) * scales.length;
    // A yielding contact goes deeper than an elastic one: its deepest point by energy (Thornton's loading curve).
    let plastic = || crate::reference::thornton(law.yield_penetration / scales.length).max_penetration * scales.length;
    // (A plastic penetration that is not a number is refused too.)
    let too_deep = |depth: f64| depth.partial_cmp(&smallest) != Some(std::cmp::Ordering::Less);
    if law.yields() && elastic < smallest && too_deep(plastic()) {
        let plastic = plastic();
        return fail(
            "contact.yield_pressure",
            format!(
                "the contact yields too far for the bodies: at {} its plastic penetration would be {}, beyond the \
                 smaller radius {} (a yield pressure this low has the bodies pass through each other)",
                brief(scales.speed, "m/s"),
                brief(plastic, "m"),
                brief(smallest, "m")
            ),
        );
    }
    if elastic < smallest {
        return Ok(());
    }
    let key = match contact.stiffness {
        StiffnessSpec::Value(_) => "contact.stiffness".to_string(),
        StiffnessSpec::Hertz => {
            // The softer body: the larger share (1 - nu²)/E of 1/E*.
            let share = |body: &Body| match (body.young, body.poisson) {
                (Some(e), Some(nu)) if e.is_finite() => (1.0 - nu * nu) / e,
                _ => 0.0,
            };
            let softer = usize::from(share(bodies[1]) > share(bodies[0]));
            format!("bodies.{softer}.young")
        }
    };
    fail(
        key,
        format!(
            "the contact is too soft for the bodies: at {} its elastic penetration would be {}, beyond the smaller \
             radius {} (the bodies would pass through each other; a contact law describes penetrations far below the \
             radii)",
            brief(scales.speed, "m/s"),
            brief(elastic, "m"),
            brief(smallest, "m")
        ),
    )
}

/// An overdamped Kelvin–Voigt or Tsuji contact ended where its force returns to zero always separates, at the
/// exact e = exp(-(zeta/Omega) ln((zeta + Omega)/(zeta - Omega))), Omega = sqrt(zeta² - 1) (docs/references.md,
/// Kelvin–Voigt; Tsuji's law is the same oscillator with zeta = a/sqrt(5)), about 1/(4 zeta²) when heavy. Below
/// [`MIN_RESTITUTION`] (zeta above about 5e4) the separation speed is lost in the rounding of the velocities: the
/// scene is refused, naming the damping key. (With `separation = "penetration"` such a contact never separates,
/// which is a valid outcome.)
fn check_creep(law: &ContactLaw, effective_mass: f64, key: &str) -> Result<(), SetupError> {
    let zeta = match law.kind.family() {
        Family::Linear => law.damping / (2.0 * (law.stiffness * effective_mass).sqrt()),
        Family::Dashpot if law.exponent == 1.0 => law.damping / (2.0 * (law.stiffness * effective_mass).sqrt()),
        Family::Tsuji => law.damping / 5f64.sqrt(),
        _ => return Ok(()),
    };
    if zeta <= 1.0 {
        return Ok(());
    }
    // (zeta - Omega)(zeta + Omega) = 1: the logarithm is 2 ln(zeta + Omega), without cancellation.
    let omega = ((zeta - 1.0) * (zeta + 1.0)).sqrt();
    let e = (-2.0 * zeta / omega * (zeta + omega).ln()).exp();
    if e >= MIN_RESTITUTION {
        return Ok(());
    }
    fail(
        key,
        format!(
            "the damping is too heavy to resolve with separation = \"force\": damping ratio zeta = {} gives e = {}, \
             below {} — a separation speed lost in the rounding of the bodies' velocities (zeta must stay below \
             about 5e4; with separation = \"penetration\" such a contact never separates)",
            brief(zeta, ""),
            brief(e, ""),
            brief(MIN_RESTITUTION, "")
        ),
    )
}

/// The deepest overlap (m) of two spheres' free flight from first contact, moving across the normal at
/// `tangential` (m/s, of v2 - v1) while closing at `approach` along `normal`: R - R |v_t|/|v| =
/// R v0² / (|v| (|v| + |v_t|)), without cancellation. A graze shallower than the positions' resolution — the
/// overlap tolerance of first contact, 1e-12 of the smaller radius — is beyond double precision: refused, naming the
/// body moving faster across the normal.
fn graze(scene: &Scene, normal: &Vector3<f64>, approach: f64, tangential: &Vector3<f64>) -> Result<f64, SetupError> {
    let [a, b] = &scene.bodies;
    let reach = a.radius + b.radius;
    let across = tangential.norm();
    let speed = approach.hypot(across);
    let depth = reach * approach / speed * approach / (speed + across);
    let resolution = geometry::TOUCH_TOLERANCE * a.radius.min(b.radius);
    if depth >= resolution {
        return Ok(depth);
    }
    let side = |body: &Body| (body.velocity - normal * body.velocity.dot(normal)).norm();
    let faster = usize::from(side(b) > side(a));
    fail(format!("bodies.{faster}.velocity"), {
        let (depth, resolution) = apart(depth, resolution, "m");
        format!(
            "the bodies barely touch: closing at {} while sliding across each other at {}, their free flight \
                 would overlap by at most {depth}, below the resolution of their positions ({resolution}, 1e-12 of \
                 the smaller radius): such a graze is beyond double precision",
            brief(approach, "m/s"),
            brief(across, "m/s")
        )
    })
}

/// K = (4/3) E* sqrt(R*), with the rules for rigid bodies and missing constants of
/// docs/laws.md#stiffness-and-exponent.
fn hertz_stiffness(a: &Body, b: &Body) -> Result<f64, SetupError> {
    for (i, body) in [a, b].iter().enumerate() {
        match (body.young, body.poisson) {
            (None, _) => {
                return fail(format!("bodies.{i}.young"), "stiffness = \"hertz\" needs `young` (Pa) for every body");
            }
            (Some(e), None) if e.is_finite() => {
                return fail(
                    format!("bodies.{i}.poisson"),
                    "stiffness = \"hertz\" needs `poisson` for an elastic body",
                );
            }
            _ => {}
        }
    }
    let Some(modulus) = geometry::effective_modulus(a, b) else {
        return fail("bodies.1.young", "both bodies are rigid (young = inf): stiffness = \"hertz\" would be infinite");
    };
    let radius = geometry::effective_radius(a, b).expect("two flat bodies were rejected before");
    Ok(geometry::hertz_stiffness(modulus, radius))
}
