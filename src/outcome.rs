//! What the phases of one impact came to: the [`Outcome`] of either path of `impact` (the general phase driver, or
//! the fast path's result as the normal model's snapshots), from which alone the report is built; and the limits, in
//! the contact's scaled units, at which the phases stop (the fast path's too).

use crate::dynamics::Snapshot;
use crate::integrate::{Counters, Ending};

/// What typically makes a contact's equations too stiff for the step budget.
pub fn stiffness_causes(frictional: bool) -> &'static str {
    if frictional {
        "stiff equations are typical of very heavy damping and of a tangential spring far stiffer than the normal \
         contact"
    } else {
        "a creeping, stiff restitution is typical of very heavy damping"
    }
}

/// Scaled time after which a contact that has not separated is declared stuck (elastic contacts last about 3).
pub const TIME_LIMIT: f64 = 1e4;
/// Scaled size of |d| + |d'| below which the relative motion counts as died out.
pub const SETTLED: f64 = 1e-10;

/// What the phases of one impact came to, in SI units: the report is built from it alone.
#[derive(Debug, Clone)]
pub struct Outcome {
    /// At maximum compression (d' = 0).
    pub max_compression: Snapshot,
    /// Where the contact ended: separation, or where the run stopped when the bodies did not part.
    pub end: Snapshot,
    /// Time since first contact (s) and value (N) of the largest compressive force.
    pub peak_force: (f64, f64),
    pub separated: bool,
    /// How the restitution run ended.
    pub ending: Ending,
    /// Time the tangential force of a frictional contact spent below the Coulomb limit mu Fn (the spring held), s
    /// (0: it stayed on the limit throughout, or the contact is smooth).
    pub below_limit_duration: f64,
    /// Time since first contact at which the contact points' slip first came to rest (gross sliding ended), s;
    /// `None` when it never did (the contact slid throughout) or the contact is smooth.
    pub slip_rest_time: Option<f64>,
    /// Stick–slip switches taken.
    pub switches: u32,
    /// The impulse of the normal force while it pulled, N s (a positive size): 0 for a law that never pulls or a
    /// contact ended where its force returns to zero; measured by a frictional contact's run (where the magnitude
    /// cap rubs on through it: a contact sliding throughout then takes mu (J_n + 2 tensile_impulse) of friction
    /// impulse), NaN where not measured.
    pub tensile_impulse: f64,
    /// The integrator's work for the impact itself (before any resampling).
    pub counters: Counters,
    /// The path that ran (`dop853`, `dopri5`, `taylor`).
    pub method: &'static str,
    /// The restitution impulse (N s) and the energy returned in restitution (J), when the path integrated them on
    /// their own from maximum compression (accurate relative to themselves when e is small); otherwise they are the
    /// differences of the snapshots' integrals.
    pub restitution: Option<(f64, f64)>,
    /// Why the path that ran did not separate the bodies, when it says more than `ending` (a note for the report).
    pub note: Option<String>,
    /// What a fixed-step scheme (`[solver] method = "verlet"` or `"symplectic-euler"`) ran at, beside the accurate
    /// answer; `None` on the accurate paths.
    pub fixed_step: Option<FixedStepOutcome>,
}

/// A fixed-step scheme's run beside the accurate one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FixedStepOutcome {
    /// The step, s.
    pub dt: f64,
    /// The e of the same contact by the accurate adaptive path (`None` if the bodies did not part there).
    pub restitution_continuous: Option<f64>,
}
