//! The report: the one product of a simulation (interface.md, "JSON report"). Every view is built from it.

use serde::{Serialize, Serializer};

/// A 3-vector as written in the report.
pub type Vec3 = [f64; 3];

/// Everything a run measured.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Report {
    pub title: String,
    pub law: LawReport,
    /// m*, kg.
    pub effective_mass: f64,
    /// v0 = (v1 - v2)·n at first contact, m/s (> 0).
    pub approach_speed: f64,
    /// Unit contact normal, body 1 -> body 2 (an addition to interface.md).
    pub normal: Vec3,
    pub contact: ContactReport,
    pub bodies: [BodyReport; 2],
    pub energy: EnergyReport,
    /// The instantaneous impact with the simulated e; null when the bodies did not separate.
    pub instantaneous: Option<InstantaneousReport>,
    /// The instantaneous impact with the nominal e; null when `damping` was given.
    pub instantaneous_nominal: Option<InstantaneousReport>,
    /// Exact values for this law and their relative errors; null when no exact reference exists (an addition).
    pub reference: Option<ReferenceReport>,
    pub solver: SolverReport,
    /// Plain-language remarks (e.g. why the bodies did not separate); an addition to interface.md.
    pub notes: Vec<String>,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LawReport {
    /// Scene spelling of the law.
    pub name: String,
    /// K in N/m^n.
    pub stiffness: f64,
    /// n.
    pub exponent: f64,
    /// The damping parameter used, in the law's own units.
    pub damping: f64,
    /// The nominal e asked for (1 for hertz); null when `damping` was given.
    pub restitution_nominal: Option<f64>,
    /// "penetration" or "force".
    pub separation: String,
}

/// The contact phases and what was measured in them. Times in s from the scene's t = 0.
#[derive(Debug, Clone, PartialEq, Serialize)]
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
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BodyReport {
    pub name: String,
    /// kg, "inf" for immovable (an addition).
    #[serde(serialize_with = "maybe_infinite")]
    pub mass: f64,
    /// m, "inf" for a flat wall (an addition).
    #[serde(serialize_with = "maybe_infinite")]
    pub radius: f64,
    pub velocity_before: Vec3,
    pub velocity_after: Option<Vec3>,
    pub velocity_at_max_compression: Vec3,
    pub angular_velocity_after: Option<Vec3>,
}

/// Energies in J; kinetic energies count finite bodies only and include rotation.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EnergyReport {
    pub kinetic_before: f64,
    pub kinetic_after: Option<f64>,
    /// Work of the dissipative forces through the contact.
    pub dissipated: Option<f64>,
}

/// The idealised instantaneous impact with a given e (physics.md §2).
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
}

/// Exact values of this contact from closed forms or quadrature (physics.md §3–4), and the simulation's relative
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

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SolverReport {
    pub method: String,
    pub rtol: f64,
    pub atol: f64,
    pub steps: u64,
    pub rejected_steps: u64,
    pub force_evaluations: u64,
    pub wall_time_s: f64,
}

/// Writes an infinite input back as the string "inf" (interface.md).
fn maybe_infinite<S: Serializer>(value: &f64, serializer: S) -> Result<S::Ok, S::Error> {
    if value.is_infinite() && *value > 0.0 { serializer.serialize_str("inf") } else { serializer.serialize_f64(*value) }
}
