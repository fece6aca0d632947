//! The report: the one product of a simulation (the JSON report of the README). Every view is built from it, and it
//! is built in one place ([`build`]) from the phases' outcome; [`accuracy`] makes its `reference` section.

pub mod accuracy;
mod build;
pub mod world;

pub use build::{build, build_into};

use crate::idealisation::Idealisation;
use serde::{Serialize, Serializer};

/// The parts of a [`Report`] a run fills. A run's own report fills all (the default); a sweep's row fills only what its
/// columns read ("a scene computes only what it asks for"): the parts left out are empty — no title and nameless
/// bodies, no instantaneous impacts, empty body sections — and every number that is filled is the one the whole report holds, computed by
/// the same code ([`build`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Sections {
    /// The title and the bodies' names: text no column reads (three copies of strings a row).
    pub names: bool,
    /// The instantaneous impacts, with the simulated e and with the nominal one (`instantaneous`,
    /// `instantaneous_nominal`): read by the `max_velocity_difference` column and the verdicts on the idealisation.
    pub instantaneous: bool,
    /// The bodies' sections (`bodies`; left out, each is empty: zeros and nulls): read by the spin columns and the
    /// verdicts.
    pub bodies: bool,
}

impl Sections {
    /// Every part: a run's own report.
    pub const ALL: Sections = Sections { names: true, instantaneous: true, bodies: true };
}

impl Default for Sections {
    fn default() -> Sections {
        Sections::ALL
    }
}

/// A 3-vector as written in the report.
pub type Vec3 = [f64; 3];

/// Everything a run measured.
///
/// A run's own report (`impact run`) computes everything. A sweep's row may ask the fast path for less
/// ([`crate::impact::Options::quantities`]: only what its columns show); what was not computed — the contact's
/// times, its force peak, the dissipated energy and what follows from them, the wall time — is NaN here, and no view
/// shows it (a row writes only its columns). The default is an empty report, which [`build_into`] writes over.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct Report {
    pub title: String,
    pub law: LawReport,
    /// m*, kg.
    pub effective_mass: f64,
    /// v0 = (v1 - v2)·n at first contact, m/s (> 0).
    pub approach_speed: f64,
    /// Unit contact normal, body 1 -> body 2 (an addition).
    pub normal: Vec3,
    pub contact: ContactReport,
    pub bodies: [BodyReport; 2],
    pub energy: EnergyReport,
    /// Oblique impact, friction and spin: null for a direct central impact without spin.
    pub oblique: Option<ObliqueReport>,
    /// The instantaneous (smooth, four-equation) impact with the simulated e; null when the bodies did not separate.
    pub instantaneous: Option<InstantaneousReport>,
    /// The instantaneous impact with the nominal e; null when `damping` was given.
    pub instantaneous_nominal: Option<InstantaneousReport>,
    /// Exact values for this law and their relative errors; null when no exact reference exists (an addition).
    pub reference: Option<ReferenceReport>,
    /// A verdict on each assumption of the instantaneous impact (docs/idealisation.md); every key null where the
    /// run was not asked for them ([`crate::impact::Options::idealisation`]: a sweep's row, a calibration's step).
    pub idealisation: Idealisation,
    pub solver: SolverReport,
    /// Plain-language remarks (e.g. why the bodies did not separate); an addition.
    pub notes: Vec<String>,
}

#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct LawReport {
    /// Scene spelling of the law.
    pub name: &'static str,
    /// K in N/m^n.
    pub stiffness: f64,
    /// n.
    pub exponent: f64,
    /// The damping parameter used, in the law's own units.
    pub damping: f64,
    /// The nominal e asked for (1 for hertz); null when `damping` was given.
    pub restitution_nominal: Option<f64>,
    /// "penetration" or "force".
    pub separation: &'static str,
    /// The `thornton` law's yield pressure p_y, Pa (null for every other law).
    pub yield_pressure: Option<f64>,
    /// The approach speed at which a `thornton` contact starts to yield, V_y in m/s: e = 1 below it (null for every
    /// other law).
    pub yield_speed: Option<f64>,
}

/// The contact phases and what was measured in them. Times in s from the scene's t = 0.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct ContactReport {
    pub start_time: f64,
    /// End of compression: d' = 0, maximum penetration.
    pub max_compression_time: f64,
    pub end_time: Option<f64>,
    pub duration: Option<f64>,
    /// m.
    pub max_penetration: f64,
    /// Largest compressive force, N.
    pub max_force: f64,
    pub max_force_time: f64,
    /// V0: the normal velocity both bodies share at maximum compression, m/s.
    pub common_normal_velocity: f64,
    /// ∫ F dt over compression, N s.
    pub deformation_impulse: f64,
    /// ∫ F dt over restitution, N s.
    pub restitution_impulse: Option<f64>,
    /// Poisson's e: restitution impulse / deformation impulse.
    pub restitution_impulse_ratio: Option<f64>,
    /// Newton's e: separation speed / approach speed.
    pub restitution_velocity_ratio: Option<f64>,
    /// Stronge's e: sqrt(restitution work / compression work).
    pub restitution_energy: Option<f64>,
    pub separated: bool,
    /// The depth of the permanent dent a yielding (`thornton`) contact leaves, m: the penetration at which its force
    /// returned to zero (null for the laws that do not yield, and before separation).
    pub permanent_dent: Option<f64>,
}

#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct BodyReport {
    pub name: String,
    /// kg, "inf" for immovable (an addition).
    #[serde(serialize_with = "maybe_infinite")]
    pub mass: f64,
    /// m, "inf" for a flat wall (an addition).
    #[serde(serialize_with = "maybe_infinite")]
    pub radius: f64,
    /// kg m², "inf" for a body that does not rotate (an addition).
    #[serde(serialize_with = "maybe_infinite")]
    pub inertia: f64,
    /// m/s.
    pub velocity_before: Vec3,
    pub velocity_after: Option<Vec3>,
    pub velocity_at_max_compression: Vec3,
    /// rad/s (an addition: the spin before).
    pub angular_velocity_before: Vec3,
    pub angular_velocity_after: Option<Vec3>,
    /// Direction of the velocity from the tangent plane at first contact, degrees (90: along the normal, towards
    /// body 2; negative: towards body 1); null for a body at rest.
    pub angle_from_tangent_before_deg: Option<f64>,
    pub angle_from_tangent_after_deg: Option<f64>,
    /// Centre (a wall: the point of its plane under the sphere) at first contact and at separation, m (additions).
    pub position_at_first_contact: Vec3,
    pub position_at_separation: Option<Vec3>,
    /// The body's effective mass at the contact along the normal at first contact, kg: its mass for a sphere,
    /// `1/m_eff = 1/M + (r × n)·I⁻¹(r × n)` for a body struck off its centre, `I_O/b²`-like about a pivot; "inf"
    /// for an immovable body.
    #[serde(serialize_with = "maybe_infinite")]
    pub effective_mass_at_contact: f64,
    /// The impulse the body's pivot passed to it during the contact, N s; null without a pivot (or before separation).
    pub pivot_impulse: Option<Vec3>,
}

/// Energies in J; kinetic energies count finite bodies only and include rotation. The balance
/// `kinetic_before + work_of_immovable_bodies = kinetic_after + dissipated + elastic_left_at_separation` closes to
/// integration accuracy (every term is integrated separately).
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct EnergyReport {
    pub kinetic_before: f64,
    pub kinetic_after: Option<f64>,
    /// Work of the dissipative forces through the contact: normal damping plus friction.
    pub dissipated: Option<f64>,
    /// Spring energy still stored in the contact when it ends (a force separation of a law that turns tensile).
    pub elastic_left_at_separation: Option<f64>,
    /// Work done on the movable bodies by a body of infinite mass (a moving wall).
    pub work_of_immovable_bodies: Option<f64>,
}

/// Oblique impact, friction and spin (docs/report.md#oblique). Angles in degrees.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ObliqueReport {
    /// The relative velocity of the contact points before impact, from the normal.
    pub incidence_from_normal_deg: f64,
    /// The same after impact, signed along the initial slip (negative: the slip reversed).
    pub rebound_from_normal_deg: Option<f64>,
    /// Tangential relative velocity of the centres after / before (along the initial one); null without one.
    pub tangential_restitution_centre: Option<f64>,
    /// Slip of the contact points after / before (along the initial slip; negative: reversal); null without slip.
    pub tangential_restitution_contact: Option<f64>,
    /// Work of friction (dissipated by slip and tangential damping), J; included in `energy.dissipated`.
    pub friction_work: Option<f64>,
    /// Coulomb friction coefficient mu of the contact (dimensionless; 0: smooth), as the scene gave it (an
    /// addition).
    pub friction: f64,
    /// The scene's `friction_cap`, "compressive" (mu max(Fn, 0)) or "magnitude" (mu |Fn|), as written or its default
    /// (an addition; it changes nothing without friction, nor for a law whose force never pulls).
    pub friction_cap: &'static str,
    /// The scene's `tangential_unloading`, "none" or "rescale" (the spring shrinks with the Mindlin stiffness while
    /// the contact unloads), as written or its default (an addition; nothing without friction).
    pub tangential_unloading: &'static str,
    /// "smooth" (no friction), "sliding" (the contact points slipped throughout, as rigid-body theory's sliding) or
    /// "sticking" (their slip came to rest at some time: the contact stuck or rolled).
    pub regime: String,
    /// Time since first contact at which the contact points' slip first came to rest, s (an addition; null when it
    /// never did, and for a smooth contact).
    pub slip_rest_time: Option<f64>,
    /// Time the tangential force spent below the Coulomb limit mu Fn, s: the tangential spring held (it loads from
    /// zero at first contact, and unloads where the slip reverses) while the contact points may still slip by its
    /// deformation (an addition; null for a smooth contact).
    pub below_friction_limit_duration: Option<f64>,
    /// Angle between the normals at first contact and at separation (how far the line of centres turned).
    pub normal_turn_deg: Option<f64>,
    /// Unit normal at separation (an addition).
    pub normal_at_separation: Option<Vec3>,
    /// Whether the bodies slid off each other (an addition): the contact force made less than half of the reversal
    /// of the normal velocity, its impulse below m* (v0 + separation speed)/2, and the turning line of centres the
    /// rest — a graze, which the instantaneous impacts do not describe. False when the bodies did not separate.
    pub slid_off: bool,
    /// The impulse of the normal force while it pulled, N s, a positive size (an addition): 0 for a law that never
    /// pulls and for a contact ended where its force returns to zero; null for a smooth contact. Sliding friction
    /// rubs through the compressive impulse J_n + J_t, and with `friction_cap = "magnitude"` through J_n + 2 J_t.
    pub tensile_impulse: Option<f64>,
    /// The rigid-body prediction with the simulated normal e (rigid-body theory's: friction through J_n alone);
    /// null when the bodies did not separate.
    pub rigid_body: Option<RigidBodyReport>,
}

/// Rigid-body theory of a frictional impact (docs/oblique.md) with the simulated normal e.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RigidBodyReport {
    /// "smooth", "sliding" or "sticking" (the slip stops and the contact rolls).
    pub regime: String,
    /// m/s, [body 1, body 2].
    pub velocity_after: [Vec3; 2],
    /// rad/s, [body 1, body 2].
    pub angular_velocity_after: [Vec3; 2],
    /// The rebound angle of the contact points from the normal, degrees, signed along the initial slip.
    pub rebound_from_normal_deg: f64,
    /// Tangential relative velocity of the centres after / before; null without one.
    pub tangential_restitution_centre: Option<f64>,
    /// Largest |simulated - rigid| velocity component, m/s.
    pub max_velocity_difference: f64,
    /// Largest |simulated - rigid| angular velocity component, rad/s (an addition).
    pub max_angular_velocity_difference: f64,
}

/// The idealised instantaneous impact with a given e (docs/references.md).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct InstantaneousReport {
    pub restitution: f64,
    /// (m1 u1 + m2 u2)/(m1 + m2), m/s.
    pub common_normal_velocity: f64,
    /// Velocities after, [body 1, body 2], m/s.
    pub velocity_after: [Vec3; 2],
    /// (1/2) m* (1 - e²) v0², J.
    pub energy_lost: f64,
    /// Largest |simulated - instantaneous| velocity component after the impact, m/s; null if not separated.
    pub max_velocity_difference: Option<f64>,
    /// The eccentric solution, where a body is struck off its centre or turns about a pivot; null otherwise.
    pub eccentric: Option<EccentricReport>,
}

/// The instantaneous impact of rigid bodies struck off their centre (docs/references.md#eccentric-impact).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EccentricReport {
    /// Each body's effective mass at the contact along the normal, kg ("inf": immovable, or held by its pivot).
    #[serde(serialize_with = "both_maybe_infinite")]
    pub effective_masses: [f64; 2],
    /// The normal impulse on body 2, N s.
    pub impulse: f64,
    /// Angular velocities after, [body 1, body 2], rad/s.
    pub angular_velocity_after: [Vec3; 2],
    /// The impulse each body's pivot passes to it, N s (zero for a free body).
    pub pivot_impulse: [Vec3; 2],
    /// Largest |simulated - instantaneous| angular velocity component after the impact, rad/s; null if not
    /// separated.
    pub max_angular_velocity_difference: Option<f64>,
}

/// Exact values of this contact from closed forms or quadrature (docs/references.md), and the simulation's relative
/// errors against them. A quantity without an exact value is null.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ReferenceReport {
    /// Where the exact values come from.
    pub source: String,
    pub restitution: Option<f64>,
    /// m.
    pub max_penetration: Option<f64>,
    /// s after first contact.
    pub max_compression_time: Option<f64>,
    /// s.
    pub duration: Option<f64>,
    /// N.
    pub max_force: Option<f64>,
    /// m/s: (m1 u1 + m2 u2)/(m1 + m2).
    pub common_normal_velocity: f64,
    /// |simulated - exact| / exact for each quantity above (V0: in units of the approach speed).
    pub errors: ReferenceErrors,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ReferenceErrors {
    pub restitution: Option<f64>,
    pub max_penetration: Option<f64>,
    pub max_compression_time: Option<f64>,
    pub duration: Option<f64>,
    pub max_force: Option<f64>,
    pub common_normal_velocity: f64,
}

#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct SolverReport {
    pub method: &'static str,
    pub rtol: f64,
    pub atol: f64,
    /// The fixed-step schemes' step, s (`verlet`, `symplectic-euler`); null for the accurate paths.
    pub dt: Option<f64>,
    /// The e of the same contact by the accurate adaptive path, beside the e a fixed-step scheme gave (the report's
    /// `contact.restitution_velocity_ratio`); null for the accurate paths, whose e is that one already (and when the
    /// accurate path's bodies did not part).
    pub restitution_continuous: Option<f64>,
    pub steps: u64,
    pub rejected_steps: u64,
    pub force_evaluations: u64,
    /// Wall-clock time of the run (setup, integration, report), s; NaN where it was not measured (a sweep row).
    pub wall_time_s: f64,
    /// Why the integration gave up before the contact ended (its step budget spent, equations too stiff for the
    /// smallest step), an addition: the report stops where it did, and `impact run` exits 1 after writing it; null
    /// when the run ended on the contact's own terms (separated, settled, or its time limit reached).
    pub gave_up: Option<String>,
}

/// A number for a note about a quantity that could not be formed from it: as people read it ("0 N", "1.2e-300 J"), or
/// in words where it is not a number, so that no note shows "NaN" or "inf" (docs/report.md#conventions).
pub(crate) fn described(value: f64, unit: &str) -> String {
    if value.is_nan() {
        "not a number".into()
    } else if value.is_infinite() {
        format!("{} beyond double precision", if value > 0.0 { "a value" } else { "a negative value" })
    } else {
        crate::units::brief(value, unit)
    }
}

/// Writes an infinite input back as the string "inf" (docs/report.md).
pub(crate) fn maybe_infinite<S: Serializer>(value: &f64, serializer: S) -> Result<S::Ok, S::Error> {
    if value.is_infinite() && *value > 0.0 { serializer.serialize_str("inf") } else { serializer.serialize_f64(*value) }
}

/// Two numbers, each as [`maybe_infinite`] writes it.
fn both_maybe_infinite<S: Serializer>(values: &[f64; 2], serializer: S) -> Result<S::Ok, S::Error> {
    use serde::ser::SerializeTuple;
    let mut pair = serializer.serialize_tuple(2)?;
    for value in values {
        if value.is_infinite() && *value > 0.0 {
            pair.serialize_element("inf")?
        } else {
            pair.serialize_element(value)?
        }
    }
    pair.end()
}

/// How closely a run's energy balance must close at the default tolerances (rtol = 1e-10), relative to its largest
/// energy term: its separately integrated energies (kinetic before and after, the works of the contact's forces, of
/// gravity and of immovable bodies, what is dissipated and what is left stored) are each accurate to the
/// integration's tolerances, and a balance that misses its bound is an integration error the run must own up to (a
/// note), never print silently. Looser tolerances loosen it in proportion ([`energy_balance_bound`]).
pub const ENERGY_BALANCE_BOUND: f64 = 1e-9;

/// The bound of a run integrated at tolerances `rtol` and `atol`: [`ENERGY_BALANCE_BOUND`], or ten times the looser
/// of the two where that is larger (the bound is ten times the default rtol).
pub fn energy_balance_bound(rtol: f64, atol: f64) -> f64 {
    ENERGY_BALANCE_BOUND.max(10.0 * rtol.max(atol))
}

/// The note a report carries when its energy balance, `(in - out) / largest` (relative to `largest`, named for the
/// reader), misses `bound`; `None` when it closes.
pub fn balance_note(relative: f64, largest: &str, bound: f64) -> Option<String> {
    (relative.abs() > bound || relative.is_nan()).then(|| {
        format!(
            "the energy balance misses its bound: in - out is {} of {largest}, beyond the {} its tolerances let the \
             energies close to — an integration error of this run (a smaller [solver] rtol and atol tighten it)",
            crate::units::brief(relative, ""),
            crate::units::brief(bound, ""),
        )
    })
}
