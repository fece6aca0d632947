//! Damping-from-restitution maps: the damping parameter each published law picks for a nominal e.
//!
//! Sources are in [`super::catalogue::LAWS`]; formulas in docs/laws.md.

use super::{Family, LawKind};

/// The maps of the linear laws: the exact inverses of their restitution (in [`crate::reference`], beside
/// [`hunt_crossley_chi`](crate::reference::hunt_crossley_chi), the exact map of the hysteresis family).
use crate::reference::{kelvin_voigt_zeta, tsuji_damping};

/// Why a law's map cannot turn a nominal e into damping.
#[derive(Debug, Clone, PartialEq)]
pub enum MapError {
    /// The law has no map (Hertz for e < 1, Brilliantov always).
    NoMap,
    /// The map divides by e (or, for the exact map, diverges) at e = 0.
    UndefinedAtZero,
}

/// chi(e) of the hysteresis family, x = alpha v0 (docs/laws.md). `e` must lie in [0, 1].
pub fn hysteresis_chi(kind: LawKind, e: f64) -> Result<f64, MapError> {
    let eps = 1.0 - e;
    let divides_by_e = matches!(
        kind,
        LawKind::Gonthier | LawKind::Flores | LawKind::GharibHurmuzlu | LawKind::HuGuo | LawKind::CarvalhoMartins
    );
    if divides_by_e && e == 0.0 {
        return Err(MapError::UndefinedAtZero);
    }
    let chi = match kind {
        LawKind::HuntCrossley => 1.5 * eps,
        LawKind::HerbertMcWhannell => 6.0 * eps / ((2.0 * e - 1.0).powi(2) + 3.0),
        LawKind::LeeWang => 0.75 * eps,
        LawKind::LankaraniNikravesh => 0.75 * (1.0 - e * e),
        LawKind::Gonthier => (1.0 - e * e) / e,
        LawKind::ZhiyingQishao => 0.75 * (1.0 - e * e) * (2.0 * eps).exp(),
        LawKind::Flores => 8.0 * eps / (5.0 * e),
        LawKind::GharibHurmuzlu => eps / e,
        LawKind::HuGuo => 1.5 * eps / e,
        LawKind::CarvalhoMartins => crate::reference::hunt_crossley_chi(e).ok_or(MapError::UndefinedAtZero)?,
        _ => return Err(MapError::NoMap),
    };
    Ok(chi)
}

/// The damping parameter (in the law's own units, docs/laws.md) that `kind`'s published map assigns to a nominal
/// restitution `e` in [0, 1], for a contact of `stiffness` (N/m^n), `effective_mass` (kg) and `approach_speed`
/// (m/s, > 0).
pub fn damping_for_restitution(
    kind: LawKind,
    e: f64,
    stiffness: f64,
    effective_mass: f64,
    approach_speed: f64,
) -> Result<f64, MapError> {
    match kind.family() {
        Family::Elastic if e == 1.0 => Ok(0.0),
        Family::Elastic | Family::Viscoelastic | Family::Plastic => Err(MapError::NoMap),
        Family::Hysteresis => Ok(hysteresis_chi(kind, e)? / approach_speed),
        Family::Linear => Ok(2.0 * kelvin_voigt_zeta(e) * (stiffness * effective_mass).sqrt()),
        Family::Tsuji => Ok(tsuji_damping(e)),
        Family::Dashpot | Family::Impedance | Family::Ramp => Err(MapError::NoMap),
    }
}

/// Whether a nominal restitution has a defined map for this law (used to validate scenes before any physics).
pub fn check_restitution(kind: LawKind, e: f64) -> Result<(), MapError> {
    match kind.family() {
        Family::Hysteresis => hysteresis_chi(kind, e).map(|_| ()),
        Family::Elastic if e != 1.0 => Err(MapError::NoMap),
        Family::Viscoelastic | Family::Plastic | Family::Impedance | Family::Ramp => Err(MapError::NoMap),
        _ => Ok(()),
    }
}
