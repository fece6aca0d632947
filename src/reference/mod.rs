//! Exact references (closed forms and quadratures) used to measure the simulator's error.
//!
//! Everything here is nondimensional, as in docs/references.md: for `F = K d^n (…)` with effective mass `m*` and
//! approach speed `v0`, lengths are in `L = (m* v0²/K)^(1/(n+1))`, times in `T = L/v0`, forces in `F0 = K L^n`
//! (Kelvin–Voigt: `L = v0 sqrt(m*/k)`, `T = sqrt(m*/k)`, `F0 = k L`; Tsuji: the `n = 3/2` units).
//! Restitution is the velocity ratio `e` (dimensionless).
//!
//! Functions are pure and never panic; invalid input gives NaN, `None`, or [`ContactReference::UNDEFINED`] as
//! documented on each function.

mod brilliantov;
mod hertz;
mod hunt_crossley;
mod hysteresis;
mod kelvin_voigt;
mod numerics;
mod roots;
mod thornton;
mod tsuji;

pub use brilliantov::{brilliantov_c1, brilliantov_c2, brilliantov_restitution_series};
pub use hertz::hertz_elastic;
pub use hunt_crossley::{hunt_crossley_chi, hunt_crossley_loss, hunt_crossley_restitution};
pub use hysteresis::hysteresis_contact;
pub use kelvin_voigt::{kelvin_voigt, kelvin_voigt_zeta};
pub use numerics::beta;
pub(crate) use numerics::phi2;
pub use roots::{Bracket, Root, Stop, illinois};
pub use thornton::{thornton, thornton_restitution, thornton_yield_speed};
pub use tsuji::{tsuji, tsuji_damping};

/// Nondimensional exact values of one impact (units `L`, `T`, `F0` of the module docs; restitution dimensionless).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactReference {
    /// Velocity ratio `e` (separation speed / approach speed).
    pub restitution: f64,
    /// Maximum penetration `dmax / L`.
    pub max_penetration: f64,
    /// Time of maximum compression `t0 / T` (where `d' = 0`), from first contact.
    pub max_compression_time: f64,
    /// Contact duration `tc / T`, from first contact to separation.
    pub duration: f64,
    /// Largest compressive force `Fmax / F0`.
    pub max_force: f64,
}

impl ContactReference {
    /// All fields NaN: the value returned for invalid parameters by functions that return a bare
    /// `ContactReference`.
    pub const UNDEFINED: Self = Self {
        restitution: f64::NAN,
        max_penetration: f64::NAN,
        max_compression_time: f64::NAN,
        duration: f64::NAN,
        max_force: f64::NAN,
    };
}

/// Which event ends the contact (docs/laws.md): the laws' (`law::Separation`), defined here, below them, because the
/// exact references take it too.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Separation {
    /// The penetration returns to zero (tension allowed before that).
    Penetration,
    /// The contact force returns to zero.
    Force,
}

impl Separation {
    /// The scene/report spelling.
    pub fn name(self) -> &'static str {
        match self {
            Separation::Penetration => "penetration",
            Separation::Force => "force",
        }
    }
}

/// [`Separation`] under the name this module always used.
pub use Separation as SeparationCriterion;
