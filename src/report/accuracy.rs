//! The simulation measured against exact references (docs/references.md), where the law has them: the report's
//! `reference` section.

use crate::instantaneous::direct_impact;
use crate::law::{Family, Separation};

use super::{ReferenceErrors, ReferenceReport};
use crate::reference::{self, ContactReference};
use crate::scene::Scene;
use crate::setup::Setup;

/// The simulated values that exact references are compared with, in SI units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Measured {
    /// Velocity ratio e (None when not separated).
    pub restitution: Option<f64>,
    /// m.
    pub max_penetration: f64,
    /// s after first contact.
    pub max_compression_time: f64,
    /// s (None when not separated).
    pub duration: Option<f64>,
    /// N.
    pub max_force: f64,
    /// V0 read off the simulated impulse, m/s.
    pub common_normal_velocity: f64,
}

/// How much of the exact reference a run computes: all of it for a report someone reads, only the restitution for
/// a sweep's row (its one reference column), nothing when no one looks (a benchmark). The quadratures of t0, tc and
/// Fmax cost more than a fast impact itself.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ReferenceDetail {
    #[default]
    Full,
    Restitution,
    Off,
}

/// The exact restitution alone, by the cheapest exact route: the Lambert W closed form for the hysteresis family,
/// the oscillator's closed forms for Kelvin–Voigt and Tsuji (Tsuji's e is the Kelvin–Voigt one at zeta = a/sqrt(5)).
fn exact_restitution(setup: &Setup, separation: Separation) -> Option<(f64, &'static str)> {
    let law = &setup.law;
    match law.kind.family() {
        Family::Elastic => Some((1.0, "elastic: e = 1")),
        Family::Hysteresis => {
            let x = law.damping * setup.approach_speed;
            (x <= MAX_HYSTERESIS_X).then(|| (reference::hunt_crossley_restitution(x), "exact Hunt–Crossley relation"))
        }
        Family::Linear => {
            let zeta = law.damping / (2.0 * (law.stiffness * setup.effective_mass).sqrt());
            Some((reference::kelvin_voigt(zeta, separation)?.restitution, "Kelvin–Voigt closed form"))
        }
        // K d + c d': Kelvin–Voigt's closed form; other exponents have none.
        Family::Dashpot if law.exponent == 1.0 => {
            let zeta = law.damping / (2.0 * (law.stiffness * setup.effective_mass).sqrt());
            Some((reference::kelvin_voigt(zeta, separation)?.restitution, "Kelvin–Voigt closed form (n = 1)"))
        }
        Family::Dashpot | Family::Impedance | Family::Ramp => None,
        Family::Tsuji => Some((
            reference::kelvin_voigt(law.damping / 5f64.sqrt(), separation)?.restitution,
            "Tsuji law mapped to a linear oscillator",
        )),
        Family::Viscoelastic => None,
        Family::Plastic => Some((
            reference::thornton_restitution(1.0 / reference::thornton_yield_speed(scaled_yield(setup))),
            "Thornton's closed form",
        )),
    }
}

/// Largest alpha v0 for which the hysteresis-family reference is reported.
const MAX_HYSTERESIS_X: f64 = 1e8;

/// The exact nondimensional contact of this scene's law and where it comes from; `None` when no exact result
/// exists (Brilliantov's law, or a contact that never separates).
fn exact(setup: &Setup, separation: Separation) -> Option<(ContactReference, &'static str)> {
    let law = &setup.law;
    match law.kind.family() {
        Family::Elastic => Some((
            reference::hertz_elastic(law.exponent),
            "elastic power-law Hertz closed form (docs/references.md#elastic-hertz-contact)",
        )),
        Family::Hysteresis => {
            let x = law.damping * setup.approach_speed;
            // Beyond x ~ 1e8 (e ~ 1e-8) the quadratures of the creeping restitution are no longer trustworthy.
            (x <= MAX_HYSTERESIS_X).then(|| {
                (
                    reference::hysteresis_contact(x, law.exponent),
                    "exact Hunt–Crossley relation and quadratures (docs/references.md#the-hunt-crossley-family)",
                )
            })
        }
        Family::Linear => {
            let zeta = law.damping / (2.0 * (law.stiffness * setup.effective_mass).sqrt());
            Some((
                reference::kelvin_voigt(zeta, separation)?,
                "Kelvin–Voigt closed forms (docs/references.md#kelvin-voigt)",
            ))
        }
        Family::Dashpot if law.exponent == 1.0 => {
            let zeta = law.damping / (2.0 * (law.stiffness * setup.effective_mass).sqrt());
            Some((
                reference::kelvin_voigt(zeta, separation)?,
                "Kelvin–Voigt closed forms, n = 1 (docs/references.md#kelvin-voigt)",
            ))
        }
        Family::Dashpot | Family::Impedance | Family::Ramp => None,
        Family::Tsuji => Some((
            reference::tsuji(law.damping, separation)?,
            "Tsuji law mapped to a linear oscillator (docs/references.md#tsuji)",
        )),
        Family::Viscoelastic => None,
        Family::Plastic => Some((
            reference::thornton(scaled_yield(setup)),
            "Thornton's closed form, energy and quadrature (docs/references.md#thornton)",
        )),
    }
}

/// The yield penetration in the contact's length unit, d_y / L (infinite for bodies that never yield).
fn scaled_yield(setup: &Setup) -> f64 {
    setup.law.yield_penetration / setup.scales.length
}

/// Exact values for this contact (SI units) and the relative errors of `measured` against them.
///
/// Every exact quantity of an impact is positive (an e, a depth, two times, a force): one that is not — NaN, infinite,
/// zero or negative, as a quadrature at the edge of its accuracy could give — is no reference. It is left out (null)
/// with a note in `notes` saying what it came to, and no relative error is formed against it.
pub fn reference(
    scene: &Scene,
    setup: &Setup,
    measured: Measured,
    detail: ReferenceDetail,
    notes: &mut Vec<String>,
) -> Option<ReferenceReport> {
    let (exact, source) = match detail {
        ReferenceDetail::Off => return None,
        ReferenceDetail::Full => exact(setup, scene.contact.separation)?,
        ReferenceDetail::Restitution => {
            let (restitution, source) = exact_restitution(setup, scene.contact.separation)?;
            (ContactReference { restitution, ..ContactReference::UNDEFINED }, source)
        }
    };
    let s = &setup.scales;
    let mut usable = |what: &str, value: f64, unit: &str, asked: bool| {
        if value.is_finite() && value > 0.0 {
            return Some(value);
        }
        if asked {
            notes.push(format!(
                "the exact {what} came out as {} ({source}), which is no reference for a positive quantity: it is \
                 left out, with its relative error",
                super::described(value, unit)
            ));
        }
        None
    };
    let full = detail == ReferenceDetail::Full;
    let restitution = usable("restitution", exact.restitution, "", true);
    let max_penetration = usable("maximum penetration", exact.max_penetration * s.length, "m", full);
    let max_compression_time = usable("time of maximum compression", exact.max_compression_time * s.time, "s", full);
    let duration = usable("contact duration", exact.duration * s.time, "s", full);
    let max_force = usable("maximum force", exact.max_force * s.force, "N", full);
    let error = |simulated: Option<f64>, exact: Option<f64>| match (simulated, exact) {
        (Some(simulated), Some(exact)) => Some(((simulated - exact) / exact).abs()).filter(|e| e.is_finite()),
        _ => None,
    };
    let ideal = direct_impact(&scene.bodies, &setup.normal, setup.effective_mass, 1.0);
    let v0_error = (measured.common_normal_velocity - ideal.common_normal_velocity).abs() / setup.approach_speed;
    Some(ReferenceReport {
        source: source.into(),
        restitution,
        max_penetration,
        max_compression_time,
        duration,
        max_force,
        common_normal_velocity: ideal.common_normal_velocity,
        errors: ReferenceErrors {
            restitution: error(measured.restitution, restitution),
            max_penetration: error(Some(measured.max_penetration), max_penetration),
            max_compression_time: error(Some(measured.max_compression_time), max_compression_time),
            duration: error(measured.duration, duration),
            max_force: error(Some(measured.max_force), max_force),
            common_normal_velocity: v0_error,
        },
    })
}
