//! From a scene to the numbers of its contact: first contact, normal, approach speed, effective mass, stiffness
//! and the resolved law. Every physics-level rule of interface.md ("Geometry and signs") is checked here, and a
//! broken rule names the scene key at fault.

use crate::body::Body;
use crate::dynamics::Scales;
use crate::geometry::{self, PlacementProblem};
use crate::law::damping::{MapError, damping_for_restitution};
use crate::law::{ContactLaw, Family};
use crate::scene::{DampingSpec, Scene, StiffnessSpec};
use nalgebra::Vector3;

/// The contact of a scene, ready to integrate (SI units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Setup {
    /// Time of first contact, s.
    pub contact_time: f64,
    /// Unit normal at the contact, body 1 -> body 2.
    pub normal: Vector3<f64>,
    /// v0 = (v1 - v2)·n > 0, m/s.
    pub approach_speed: f64,
    /// m*, kg.
    pub effective_mass: f64,
    /// The law with its stiffness and damping resolved.
    pub law: ContactLaw,
    /// Scaled-variable units of this contact.
    pub scales: Scales,
}

/// A broken physics-level rule: the key at fault and what is wrong.
#[derive(Debug, Clone, PartialEq)]
pub struct SetupError {
    /// Dotted scene key, 0-based (`bodies.1.velocity`).
    pub key: String,
    pub message: String,
}

fn fail<T>(key: impl Into<String>, message: impl Into<String>) -> Result<T, SetupError> {
    Err(SetupError { key: key.into(), message: message.into() })
}

/// Relative size below which a velocity component across the normal counts as zero.
const ACROSS_TOLERANCE: f64 = 1e-12;

impl Setup {
    /// Resolves a scene's contact, checking the rules that involve more than one key.
    pub fn new(scene: &Scene) -> Result<Setup, SetupError> {
        let [a, b] = &scene.bodies;
        let Some(effective_mass) = geometry::effective_mass(a, b) else {
            return fail("bodies.1.mass", "both bodies are immovable (mass = inf): nothing can move");
        };
        if a.is_flat() && b.is_flat() {
            return fail("bodies.1.radius", "both bodies are flat (radius = inf): one must be a sphere");
        }
        let (contact_time, normal) = placement(scene)?;
        check_motion_along_normal(&scene.bodies, &normal)?;
        let approach_speed = (a.velocity - b.velocity).dot(&normal);
        if approach_speed <= 0.0 || !approach_speed.is_finite() {
            return fail(
                "bodies.0.velocity",
                format!(
                    "the bodies do not approach: normal velocities {} m/s (body 1) and {} m/s (body 2) along the \
                     normal {:?} give an approach speed (v1 - v2)·n = {} m/s, which must be > 0",
                    a.velocity.dot(&normal),
                    b.velocity.dot(&normal),
                    normal.as_slice(),
                    approach_speed
                ),
            );
        }
        let stiffness = match scene.contact.stiffness {
            StiffnessSpec::Value(k) => k,
            StiffnessSpec::Hertz => hertz_stiffness(a, b)?,
        };
        let kind = scene.contact.law;
        let exponent = scene.contact.exponent;
        let damping = match scene.contact.damping {
            DampingSpec::None => 0.0,
            DampingSpec::Parameter(value) => value,
            DampingSpec::Restitution(e) => damping_for_restitution(kind, e, stiffness, effective_mass, approach_speed)
                .or_else(|error| {
                    let why = match error {
                        MapError::NoMap => format!("the law `{}` has no restitution map", kind.name()),
                        MapError::UndefinedAtZero => format!("the map of `{}` is undefined at e = 0", kind.name()),
                    };
                    fail("contact.restitution", why)
                })?,
        };
        if !damping.is_finite() {
            return fail("contact.restitution", format!("the damping {damping} is not a finite number"));
        }
        let tsuji_scale = if kind.family() == Family::Tsuji { (effective_mass * stiffness).sqrt() } else { 0.0 };
        let law = ContactLaw { kind, stiffness, exponent, damping, tsuji_scale };
        let scales = Scales::new(effective_mass, stiffness, exponent, approach_speed);
        check_scales(&scales)?;
        Ok(Setup { contact_time, normal, approach_speed, effective_mass, law, scales })
    }
}

/// When and along which normal the bodies first touch.
fn placement(scene: &Scene) -> Result<(f64, Vector3<f64>), SetupError> {
    let [a, b] = &scene.bodies;
    let given = scene.contact.normal;
    let scene_normal = given.unwrap_or_else(Vector3::x);
    match (a.position, b.position) {
        (None, None) => Ok((0.0, scene_normal)),
        (Some(_), None) => fail("bodies.1.position", "give `position` for both bodies or for neither"),
        (None, Some(_)) => fail("bodies.0.position", "give `position` for both bodies or for neither"),
        (Some(_), Some(_)) => {
            let contact = geometry::first_contact(a, b, &scene_normal).or_else(|problem| match problem {
                PlacementProblem::Overlapping(overlap) => fail(
                    "bodies.1.position",
                    format!(
                        "the bodies start overlapped by {overlap:e} m (more than {:e} of the smaller radius)",
                        geometry::TOUCH_TOLERANCE
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
            let spheres = !a.is_flat() && !b.is_flat();
            if let (true, Some(normal)) = (spheres, given)
                && (normal - contact.normal).norm() > 1e-9
            {
                return fail(
                    "contact.normal",
                    format!(
                        "the given normal {:?} disagrees with the line of centres at first contact {:?}",
                        normal.as_slice(),
                        contact.normal.as_slice()
                    ),
                );
            }
            Ok((contact.time, contact.normal))
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
            "the contact's scales leave double precision (penetration scale {:e} m, time scale {:e} s, energy \
             scale m* v0² = {:e} J): check the masses, velocities and stiffness",
            scales.length, scales.time, scales.energy
        ),
    )
}

/// Until oblique impacts land, every velocity must lie along the normal.
fn check_motion_along_normal(bodies: &[Body; 2], normal: &Vector3<f64>) -> Result<(), SetupError> {
    for (i, body) in bodies.iter().enumerate() {
        let across = body.velocity - normal * body.velocity.dot(normal);
        if across.norm() > ACROSS_TOLERANCE * body.velocity.norm() {
            return fail(
                format!("bodies.{i}.velocity"),
                format!(
                    "velocity {:?} has a part {:?} across the normal {:?}: oblique impacts are not supported yet",
                    body.velocity.as_slice(),
                    across.as_slice(),
                    normal.as_slice()
                ),
            );
        }
    }
    Ok(())
}

/// K = (4/3) E* sqrt(R*), with the rules of interface.md for rigid bodies and missing constants.
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
