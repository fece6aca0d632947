//! The idealisation on trial (docs/idealisation.md): for each assumption of the instantaneous impact, the number that
//! measures it in this impact, the scale it is compared with, and a verdict.
//!
//! The verdicts read what the report measured ([`Measured`], gathered by `report::build` from the report it has just
//! built) and the scene's bodies; they never re-derive the simulation. The one measure that needs more than one run,
//! `constant_e`, reads the e of the same contact at 0.9 and 1.1 times the speed ([`SpeedTrial`]), which the impact
//! driver measures from two outcomes (not reports), so that a trial never asks for a trial of its own.

use crate::body::Body;
use crate::geometry::effective_radius;
use crate::units::{apart, brief, brief_digits, short};
use nalgebra::Vector3;
use serde::Serialize;

/// Standard gravity, m/s² (the `isolated` verdict: what it would add to a contact that feels it).
pub const STANDARD_GRAVITY: f64 = 9.80665;

/// The relative change of every velocity in the two runs of the `constant_e` trial (0.9 and 1.1 times).
pub const SPEED_STEP: f64 = 0.1;

/// The slope d ln e / d ln v0 that `constant_e` is compared with: over a doubling of the speed (a few bounces) it
/// changes e by 2^0.1 - 1 = 7 %.
pub const SLOPE_SCALE: f64 = 0.1;

/// The yield criterion: plastic flow begins under a Hertz contact whose peak pressure reaches this multiple of the
/// yield stress (Johnson, Contact Mechanics, ch. 11; the Tresca and von Mises criteria give 1.60 and 1.61).
pub const YIELD_PRESSURE_FACTOR: f64 = 1.6;

/// The verdict on each assumption; `None` where it does not apply, or where it was not asked for (a sweep's row
/// without a verdict column, a calibration's step: every key null). A world report's summary holds the worst
/// contact's verdict per assumption in the same keys (`Idealisation<Worst>`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Idealisation<V = Verdict> {
    /// The contact takes no time: the bodies' relative travel during it against the smaller radius (in a world: the
    /// contact time against the flight to the next contact).
    pub instantaneous: Option<V>,
    /// No other force acts during the contact: gravity's impulse (and in a world the overlapping contacts') against
    /// the contact's.
    pub isolated: Option<V>,
    /// The bodies keep their shape: penetration, contact radius and the surface's turn against the smaller radius.
    pub particles: Option<V>,
    /// The materials stay elastic: the peak Hertz pressure against 1.6 times the smaller yield stress.
    pub elastic: Option<V>,
    /// The contact is quasi-static: the slowest body's elastic-wave transit against the contact time.
    pub quasi_static: Option<V>,
    /// e does not depend on the speed: d ln e / d ln v0 from runs at 0.9 and 1.1 times every velocity (in a world:
    /// from the pair's contacts at other speeds).
    pub constant_e: Option<V>,
    /// The contact is smooth: the tangential impulse (or friction's work) against the normal one (the energy).
    pub smooth: Option<V>,
    /// The impact is central: the normal's lever arm about each mass centre against the radius of gyration.
    pub central: Option<V>,
}

impl<V> Default for Idealisation<V> {
    fn default() -> Self {
        Idealisation::from_fn(|_| None)
    }
}

impl<V> Idealisation<V> {
    /// Each key's value from `of(key)`, in the order of the report.
    pub fn from_fn(mut of: impl FnMut(&'static str) -> Option<V>) -> Self {
        Idealisation {
            instantaneous: of("instantaneous"),
            isolated: of("isolated"),
            particles: of("particles"),
            elastic: of("elastic"),
            quasi_static: of("quasi_static"),
            constant_e: of("constant_e"),
            smooth: of("smooth"),
            central: of("central"),
        }
    }

    /// The verdicts in the order of the report, with their keys.
    pub fn entries(&self) -> [(&'static str, Option<&V>); 8] {
        [
            ("instantaneous", self.instantaneous.as_ref()),
            ("isolated", self.isolated.as_ref()),
            ("particles", self.particles.as_ref()),
            ("elastic", self.elastic.as_ref()),
            ("quasi_static", self.quasi_static.as_ref()),
            ("constant_e", self.constant_e.as_ref()),
            ("smooth", self.smooth.as_ref()),
            ("central", self.central.as_ref()),
        ]
    }
}

/// The assumptions in the order of severity that names a row's first failure (a sweep's `first_failure` and
/// `first_marginal` columns, the idealisation map's colours; docs/idealisation.md#the-order-of-severity): first those
/// whose failure breaks the rigid-body picture itself (elastic waves, deformed bodies), then the single instant
/// (the contact lasts, other forces act meanwhile), last those a corrected coefficient or an extended rigid-body
/// theory absorbs (yield lowers e, e changes with speed, friction, an eccentric impact).
pub const SEVERITY: [&str; 8] =
    ["quasi_static", "particles", "instantaneous", "isolated", "elastic", "constant_e", "smooth", "central"];

impl<V> Idealisation<V> {
    /// The verdict on the assumption `key` (one of [`SEVERITY`]'s), if measured.
    pub fn get(&self, key: &str) -> Option<&V> {
        self.entries().into_iter().find(|(name, _)| *name == key).and_then(|(_, verdict)| verdict)
    }
}

impl Idealisation {
    /// The first assumption in the order of [`SEVERITY`] whose verdict is `judgement`, if any.
    pub fn first(&self, judgement: Judgement) -> Option<&'static str> {
        SEVERITY.into_iter().find(|key| self.get(key).is_some_and(|v| v.verdict == judgement))
    }
}

/// The worst verdict on one assumption over a world's contacts (docs/idealisation.md#in-a-world): the contact's index
/// and its verdict, with how many contacts it fails in.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Worst {
    /// The index of the contact (in the world report's `contacts`) whose ratio is the largest in size.
    pub contact: usize,
    /// How many contacts the assumption fails in.
    pub failing: usize,
    #[serde(flatten)]
    pub verdict: Verdict,
}

/// Over each contact's verdicts (in the order of the contacts), the worst per assumption: the largest ratio in size
/// (a tie keeps the earlier contact).
pub fn worst(contacts: &[&Idealisation]) -> Idealisation<Worst> {
    Idealisation::from_fn(|key| {
        let judged = contacts.iter().enumerate().filter_map(|(k, each)| each.get(key).map(|v| (k, v)));
        let failing = judged.clone().filter(|(_, v)| v.verdict == Judgement::Fails).count();
        judged
            .reduce(|worst, next| if next.1.ratio.abs() > worst.1.ratio.abs() { next } else { worst })
            .map(|(contact, verdict)| Worst { contact, failing, verdict: verdict.clone() })
    })
}

/// One assumption measured: `ratio = value / compared_with`, and a large `ratio` means it fails (`constant_e`'s
/// carries the slope's sign; its verdict reads the size).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Verdict {
    pub value: f64,
    pub compared_with: f64,
    pub ratio: f64,
    pub verdict: Judgement,
    /// One sentence: what was measured and what it does to the idealised impact.
    pub meaning: String,
    /// What `value` and `compared_with` are, for a view ("a / R"); not in the JSON.
    #[serde(skip)]
    pub measure: &'static str,
    /// Their unit ("m", "" for a number); not in the JSON.
    #[serde(skip)]
    pub unit: &'static str,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Judgement {
    Holds,
    Marginal,
    Fails,
}

impl Judgement {
    pub fn name(self) -> &'static str {
        match self {
            Judgement::Holds => "holds",
            Judgement::Marginal => "marginal",
            Judgement::Fails => "fails",
        }
    }
}

/// Where a ratio's verdict changes: holds below `holds_below`, fails from `fails_from` (docs/idealisation.md gives
/// each pair's reasons).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limits {
    pub holds_below: f64,
    pub fails_from: f64,
}

impl Limits {
    pub fn judge(self, ratio: f64) -> Judgement {
        let size = ratio.abs();
        if size < self.holds_below {
            Judgement::Holds
        } else if size < self.fails_from {
            Judgement::Marginal
        } else {
            Judgement::Fails
        }
    }
}

/// A correction of relative size `ratio` to the idealised impact: a per cent is within the scatter of measured
/// impacts, ten per cent is not (`instantaneous`, `isolated`, `smooth`).
pub const CORRECTION: Limits = Limits { holds_below: 1e-2, fails_from: 1e-1 };
/// A length against the body's size (`particles`) or a transit against the contact time (`quasi_static`): Hertz's
/// small-strain and quasi-static errors grow as the ratio squared (a/R = 0.1: 1 %), or faster.
pub const SHAPE: Limits = Limits { holds_below: 0.1, fails_from: 0.3 };
/// The normal's lever arm against the radius of gyration (`central`): a free body's effective mass is
/// M / (1 + (b/k)²), so b/k = 0.1 changes it by 1 % and b/k = sqrt(0.1) by 10 %, [`CORRECTION`]'s sizes.
pub const LEVER: Limits = Limits { holds_below: 0.1, fails_from: 0.316_227_766_016_837_94 };
/// The peak pressure against the yield pressure: yield begins at 1; at 2^(2/5) times the yield pressure (Hertz's
/// elastic p0, which grows as v0^(2/5)) the speed is twice the yield speed, and Thornton's e has fallen to 0.93.
pub const YIELD: Limits = Limits { holds_below: 1.0, fails_from: 1.319_507_910_772_894 };
/// The slope against [`SLOPE_SCALE`]: |d ln e / d ln v0| below 0.01 (e within 0.7 % over a doubling of the speed)
/// holds, from 0.1 (7 %) fails.
pub const SLOPE: Limits = Limits { holds_below: 0.1, fails_from: 1.0 };

/// The limits the verdict on the assumption `key` is judged by (docs/idealisation.md#thresholds-and-why).
pub fn limits(key: &str) -> Option<Limits> {
    match key {
        "instantaneous" | "isolated" | "smooth" => Some(CORRECTION),
        "central" => Some(LEVER),
        "particles" | "quasi_static" => Some(SHAPE),
        "elastic" => Some(YIELD),
        "constant_e" => Some(SLOPE),
        _ => None,
    }
}

/// The e of the same contact with every velocity and spin scaled by `1 - SPEED_STEP` and `1 + SPEED_STEP`, the law's
/// damping parameter kept (a nominal e is not re-mapped at the new speed); `None` where that run did not separate or
/// could not run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpeedTrial {
    pub slower: Option<f64>,
    pub faster: Option<f64>,
}

/// What the report measured that the verdicts read (SI; vectors in scene axes).
#[derive(Debug, Clone, PartialEq)]
pub struct Measured {
    /// t_c, s; `None` when the bodies did not separate.
    pub duration: Option<f64>,
    /// d_max, m.
    pub max_penetration: f64,
    /// F_max, N.
    pub max_force: f64,
    /// Normal impulse over compression, N s.
    pub deformation_impulse: f64,
    /// Normal impulse over restitution, N s; `None` when the bodies did not separate.
    pub restitution_impulse: Option<f64>,
    /// The simulated e (velocity ratio).
    pub restitution: Option<f64>,
    /// The contact normal at first contact.
    pub normal: Vector3<f64>,
    pub velocities_before: [Vector3<f64>; 2],
    pub velocities_after: Option<[Vector3<f64>; 2]>,
    pub spins_before: [Vector3<f64>; 2],
    pub spins_after: Option<[Vector3<f64>; 2]>,
    /// Coulomb mu of the contact.
    pub friction: f64,
    /// Work of friction, J.
    pub friction_work: Option<f64>,
    /// J.
    pub kinetic_before: f64,
    /// v0, m/s.
    pub approach_speed: f64,
    /// Largest |simulated - instantaneous| velocity component after, m/s (the instantaneous impact with the
    /// simulated e).
    pub max_velocity_difference: Option<f64>,
    pub speed_trial: SpeedTrial,
    /// For a yielding law (`thornton`): its yield pressure p_y (Pa) and yield speed V_y (m/s).
    pub yielding: Option<(f64, f64)>,
    /// Each turning body's lever at first contact (`None` for a body that does not turn).
    pub levers: [Option<Lever>; 2],
}

/// How a body meets the normal force at first contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lever {
    /// The normal's lever arm b about the body's origin (its mass centre, or its pivot), m.
    pub arm: f64,
    /// The radius of gyration k about the axis of the normal's moment through that origin, sqrt(I_axis / M), m.
    pub gyration: f64,
    /// The effective mass at the contact along the normal, kg, and the body's mass M, kg.
    pub effective_mass: f64,
    pub mass: f64,
    /// Whether the body turns about a pivot.
    pub pivoted: bool,
}

/// The verdicts on the idealisation of one impact between `bodies`, from what it measured.
pub fn judge(bodies: [&Body; 2], measured: &Measured) -> Idealisation {
    Idealisation {
        instantaneous: instantaneous(bodies, measured),
        isolated: isolated(bodies, measured),
        particles: particles(bodies, measured),
        elastic: elastic(bodies, measured),
        quasi_static: quasi_static(bodies, measured),
        constant_e: constant_e(measured),
        smooth: smooth(bodies, measured),
        central: central(bodies, measured),
    }
}

/// What a world measured around one of its contacts, beyond the contact's own numbers (docs/idealisation.md#in-a-world).
#[derive(Debug, Clone, PartialEq)]
pub struct Surroundings {
    /// The time from the contact's end to the first touch of the next contact of either movable body, s; `None`
    /// where there is none (or it began as this one ended): the one-impact measure stands in.
    pub flight: Option<f64>,
    /// The world's gravity, m/s².
    pub gravity: Vector3<f64>,
    /// Whether gravity presses the contact: a body is immovable, or is held by another contact meanwhile (two free
    /// bodies fall together, and uniform gravity leaves their relative motion alone).
    pub held: bool,
    /// The other contacts on its movable bodies that overlapped it in time: (index, their impulse during the
    /// overlap, N s, or their whole impulse where the run did not measure the overlap's).
    pub others: Vec<(usize, f64)>,
    /// Whether some of `others` are whole impulses (an upper bound), not the overlap's.
    pub whole: bool,
    /// The same pair's contacts at other approach speeds, for `constant_e`.
    pub speeds: Neighbours,
}

/// The same pair's separated contacts (not pushed, e > 0) at the nearest approach speeds below and above this
/// contact's: (index, approach speed m/s, e).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Neighbours {
    pub slower: Option<(usize, f64, f64)>,
    pub faster: Option<(usize, f64, f64)>,
    /// Whether the law's damping parameter differs between the contacts compared (a nominal e mapped at each
    /// contact's own speed: e is then constant by construction).
    pub remapped: bool,
}

/// The verdicts on the idealisation of one contact of a world: its own numbers as for one impact, and the world's
/// time scales and other forces around it.
pub fn judge_in_world(bodies: [&Body; 2], measured: &Measured, around: &Surroundings) -> Idealisation {
    Idealisation {
        instantaneous: match around.flight {
            Some(flight) => between_flights(measured, flight),
            None => instantaneous(bodies, measured),
        },
        isolated: surrounded(bodies, measured, around),
        particles: particles(bodies, measured),
        elastic: elastic(bodies, measured),
        quasi_static: quasi_static(bodies, measured),
        constant_e: across_contacts(measured, &around.speeds),
        smooth: smooth(bodies, measured),
        central: central(bodies, measured),
    }
}

/// The contact time against the flight to the next contact of either body: the idealisation makes the contact an
/// instant between flights (a bouncing ball: t_c against 2 v / g).
fn between_flights(measured: &Measured, flight: f64) -> Option<Verdict> {
    let duration = measured.duration?;
    verdict(duration, flight, CORRECTION, ("t_c / flight to the next contact", "s"), |ratio| {
        format!(
            "the contact lasts {} of the {} flight to the next contact of its bodies, which the idealisation makes \
             an instant between flights: the bodies' motion during the contact (under gravity, or towards the next \
             contact) is left out in proportion",
            brief(ratio, ""),
            brief(flight, "s")
        )
    })
}

/// A ratio of two impulses as words that lead into the one compared with: "0.56 times", "as much as" (a ratio that
/// reads 1, where "1 times" or "1 of" would puzzle).
fn times(ratio: f64) -> String {
    match brief(ratio, "") {
        one if one == "1" => "as much as".to_string(),
        shown => format!("{shown} times"),
    }
}

/// Gravity's impulse along the normal on the heavier movable body, m |g·n| t_c (where gravity presses the contact),
/// plus the impulses of the other contacts on its bodies during it, against its own impulse.
fn surrounded(bodies: [&Body; 2], measured: &Measured, around: &Surroundings) -> Option<Verdict> {
    let duration = measured.duration?;
    let impulse = measured.deformation_impulse + measured.restitution_impulse?;
    let mass = bodies.iter().map(|b| b.mass).filter(|m| m.is_finite()).fold(0.0, f64::max);
    let along = around.gravity.dot(&measured.normal).abs();
    let gravity = if around.held { mass * along * duration } else { 0.0 };
    let others: f64 = around.others.iter().map(|(_, j)| j.abs()).sum();
    verdict(gravity + others, impulse, CORRECTION, ("other impulses / contact impulse", "N s"), |ratio| {
        let pull = if around.gravity == Vector3::zeros() {
            "the world has no gravity".to_string()
        } else if !around.held {
            "gravity moves both free bodies alike and leaves their relative motion alone".to_string()
        } else {
            format!("gravity along the normal ({}) gives {} it", brief(along, "m/s²"), times(gravity / impulse))
        };
        let contacts = if around.others.is_empty() {
            "no other contact acts on its bodies meanwhile".to_string()
        } else {
            let list: Vec<String> = around.others.iter().map(|(k, _)| k.to_string()).collect();
            format!(
                "contact{} {} on the same bodies give{} {} it {}",
                if list.len() > 1 { "s" } else { "" },
                list.join(", "),
                if list.len() > 1 { "" } else { "s" },
                times(others / impulse),
                if around.whole { "(whole impulses: an upper bound)" } else { "during the overlap" }
            )
        };
        format!(
            "other forces add {} the contact impulse while it lasts: {pull}; {contacts} — the idealisation's \
             impact of two bodies alone, with one e, leaves them out",
            times(ratio)
        )
    })
}

/// d ln e / d ln v0 across the pair's contacts at other speeds: a central difference between the nearest slower and
/// faster ones, or a one-sided one between this contact and the one there is.
fn across_contacts(measured: &Measured, speeds: &Neighbours) -> Option<Verdict> {
    let here = (usize::MAX, measured.approach_speed, measured.restitution.filter(|e| *e > 0.0)?);
    let (low, high) = match (speeds.slower, speeds.faster) {
        (Some(slower), Some(faster)) => (slower, faster),
        (Some(slower), None) => (slower, here),
        (None, Some(faster)) => (here, faster),
        (None, None) => return None,
    };
    let slope = (high.2 / low.2).ln() / (high.1 / low.1).ln();
    let name = |c: (usize, f64, f64), e: &str| {
        let which = if c.0 == usize::MAX { "this contact".to_string() } else { format!("contact {}", c.0) };
        format!("{e} at {} in {which}", brief(c.1, "m/s"))
    };
    let pair = match two_values(low.2, high.2) {
        Ok((low_e, high_e)) => format!("{} and {}", name(low, &low_e), name(high, &high_e)),
        Err((e, difference)) => {
            format!("{} and {} alike (to {difference})", name(low, &e), name(high, "").trim_start())
        }
    };
    verdict(slope, SLOPE_SCALE, SLOPE, ("d ln e / d ln v0", ""), |_| {
        format!(
            "the pair's e is {pair}: a slope of {}, so {} — the idealisation's one e serves {}{}",
            brief(slope, ""),
            doubling(slope),
            if slope.abs() < SLOPE_SCALE * SLOPE.holds_below { "all these speeds" } else { "one speed only" },
            if speeds.remapped {
                " (the law's damping was mapped at each contact's own speed, which holds e by construction: what \
                 changes it is the world, gravity and other contacts during the contact)"
            } else {
                ""
            }
        )
    })
}

/// Two values of e for a meaning: each with the digits that tell them apart, up to six (0.79991 and 0.79993); closer
/// than six digits show, `Err` with the one value they share and their difference ("0.98", "1.2e-14").
fn two_values(a: f64, b: f64) -> Result<(String, String), (String, String)> {
    if a != b && brief_digits(a, "", 6) == brief_digits(b, "", 6) {
        Err((brief(a, ""), brief((b - a).abs(), "")))
    } else {
        Ok(apart(a, b, ""))
    }
}

/// A verdict on `value` against `compared_with`; `None` for a measure that is not a finite number.
fn verdict(
    value: f64,
    compared_with: f64,
    limits: Limits,
    (measure, unit): (&'static str, &'static str),
    meaning: impl FnOnce(f64) -> String,
) -> Option<Verdict> {
    let ratio = value / compared_with;
    ratio.is_finite().then(|| Verdict {
        value,
        compared_with,
        ratio,
        verdict: limits.judge(ratio),
        meaning: meaning(ratio),
        measure,
        unit,
    })
}

/// The smaller finite radius of the two bodies (a wall's is infinite).
fn smaller_radius(bodies: [&Body; 2]) -> Option<f64> {
    let radius = bodies[0].radius.min(bodies[1].radius);
    radius.is_finite().then_some(radius)
}

/// "; the simulated velocities after differ from ... by ... m/s", when the report has a difference that shows (a
/// direct impact matches the instantaneous impact with the simulated e to rounding).
fn difference(measured: &Measured) -> String {
    measured.max_velocity_difference.filter(|dv| *dv > 1e-6 * measured.approach_speed).map_or(String::new(), |dv| {
        format!("; the simulated velocities after differ from the instantaneous impact's by up to {}", brief(dv, "m/s"))
    })
}

/// Relative travel of the centres during the contact, max(|v2 - v1| before, after) t_c, against the smaller radius:
/// the one length of a two-body scene the idealisation's single instant and place can be measured against. Relative,
/// so that the verdict does not change with the observer's frame.
fn instantaneous(bodies: [&Body; 2], measured: &Measured) -> Option<Verdict> {
    let duration = measured.duration?;
    let radius = smaller_radius(bodies)?;
    let [before, after] = [Some(measured.velocities_before), measured.velocities_after]
        .map(|v| v.map_or(0.0, |[v1, v2]| (v2 - v1).norm()));
    let travel = before.max(after) * duration;
    verdict(travel, radius, CORRECTION, ("relative travel / radius", "m"), |ratio| {
        format!(
            "the bodies travel {} of the smaller radius relative to each other during the {} contact, which the \
             idealisation makes one instant at one place: a third body or a field acting meanwhile would meet them in \
             between{}",
            brief(ratio, ""),
            brief(duration, "s"),
            // (With friction, the difference from the smooth instantaneous impact is mostly friction's: `smooth`.)
            if measured.friction == 0.0 { difference(measured) } else { String::new() }
        )
    })
}

/// Standard gravity's impulse on the heavier movable body during the contact, m g t_c, against the contact's normal
/// impulse: a one-impact scene has no gravity, so this is what it would add to a contact that feels it (a body
/// against a support or a wall; two bodies in free fall together do not feel it).
fn isolated(bodies: [&Body; 2], measured: &Measured) -> Option<Verdict> {
    let duration = measured.duration?;
    let impulse = measured.deformation_impulse + measured.restitution_impulse?;
    let mass = bodies.iter().map(|b| b.mass).filter(|m| m.is_finite()).fold(0.0, f64::max);
    let gravity = mass * STANDARD_GRAVITY * duration;
    verdict(gravity, impulse, CORRECTION, ("m g t_c / contact impulse", "N s"), |ratio| {
        format!(
            "the scene has no gravity; standard gravity on the heavier body, pressed through the contact by a support \
             or a wall, would add {} the contact impulse and change the rebound by about as much (two bodies \
             falling freely together would not feel it)",
            times(ratio)
        )
    })
}

/// The worst of d_max, the contact radius a = sqrt(R* d_max) and the arc R ω t_c the fastest-spinning body's surface
/// turns through, each against the smaller finite radius R.
fn particles(bodies: [&Body; 2], measured: &Measured) -> Option<Verdict> {
    let radius = smaller_radius(bodies)?;
    let penetration = measured.max_penetration;
    let contact_radius = (effective_radius(bodies[0], bodies[1])? * penetration).sqrt();
    let spin = |spins: &[Vector3<f64>; 2]| {
        (0..2).filter(|&i| bodies[i].radius.is_finite()).map(|i| spins[i].norm()).fold(0.0, f64::max)
    };
    let fastest = spin(&measured.spins_before).max(measured.spins_after.as_ref().map_or(0.0, spin));
    let turn = measured.duration.map_or(0.0, |t| radius * fastest * t);
    let deformed = "the idealisation's rigid bodies with a point contact, and Hertz's small-strain contact, are off by \
                    about the square of this fraction";
    let turned = "the bodies turn by this many radians while in contact: the contact point of a body that is not a \
                  sphere, and its lever arm, would move as much";
    let candidates = [
        (penetration, "d_max / R", "the maximum penetration", deformed),
        (contact_radius, "a / R", "the contact radius a = sqrt(R* d_max)", deformed),
        (turn, "R ω t_c / R", "the arc a surface turns through during the contact", turned),
    ];
    let (value, measure, what, consequence) =
        candidates.into_iter().fold(candidates[0], |worst, c| if c.0 > worst.0 { c } else { worst });
    verdict(value, radius, SHAPE, (measure, "m"), |ratio| {
        format!(
            "{what} is {} of the smaller radius (the worst of d_max, a and R ω t_c): {consequence}",
            brief(ratio, "")
        )
    })
}

/// The peak Hertz pressure p0 = 3 F_max / (2 π a²), a = sqrt(R* d_max), against 1.6 times the smaller yield stress.
fn elastic(bodies: [&Body; 2], measured: &Measured) -> Option<Verdict> {
    if let Some((pressure, speed)) = measured.yielding {
        return yielding_law(pressure, speed, measured);
    }
    let yield_stress = bodies.iter().filter_map(|b| b.yield_stress).fold(f64::INFINITY, f64::min);
    if !yield_stress.is_finite() {
        return None;
    }
    let area = effective_radius(bodies[0], bodies[1])? * measured.max_penetration;
    let pressure = 3.0 * measured.max_force / (2.0 * std::f64::consts::PI * area);
    verdict(pressure, YIELD_PRESSURE_FACTOR * yield_stress, YIELD, ("p0 / 1.6 Y", "Pa"), |ratio| {
        if ratio < 1.0 {
            format!(
                "the peak contact pressure stays at {} of the pressure at which the weaker material begins to yield \
                 (1.6 Y): no plastic flow, the elastic law holds",
                brief(ratio, "")
            )
        } else {
            format!(
                "the peak contact pressure reaches {} times the pressure at which the weaker material begins to \
                 yield (1.6 Y): it flows plastically, dissipating energy an elastic law does not (an e below the \
                 simulated one, falling with speed, as an elastic–plastic law such as Thornton's gives)",
                brief(ratio, "")
            )
        }
    })
}

/// The `elastic` verdict of a law that yields itself (`thornton`): the peak pressure an elastic (Hertz) contact would
/// reach at this speed, p_y (v0 / V_y)^(2/5) (Hertz's p0 grows as v0^(2/5) and is p_y at V_y), against p_y — the
/// contact is not elastic above V_y, and the simulation already says what that costs.
fn yielding_law(pressure: f64, speed: f64, measured: &Measured) -> Option<Verdict> {
    let elastic_pressure = pressure * (measured.approach_speed / speed).powf(0.4);
    let e = measured.restitution;
    verdict(elastic_pressure, pressure, YIELD, ("elastic p0 / p_y", "Pa"), |ratio| {
        if ratio < 1.0 {
            format!(
                "below the yield speed ({}) the contact stays elastic: its peak pressure is {} of the yield \
                 pressure, e = 1",
                brief(speed, "m/s"),
                brief(ratio, "")
            )
        } else {
            let e = e.map_or_else(|| "no rebound".to_string(), |e| format!("e = {}", apart(e, 1.0, "").0));
            format!(
                "the contact yields: an elastic one would press at {} times the yield pressure; the law follows the \
                 plastic flow, and the dent it leaves costs the rebound: {e} where an elastic contact gives 1",
                brief(ratio, "")
            )
        }
    })
}

/// The longest elastic-wave transit 2R/c, c = sqrt(E/ρ), of a body with a finite modulus and density, against the
/// contact time: a contact many transits long loads the body quasi-statically, as Hertz assumes.
fn quasi_static(bodies: [&Body; 2], measured: &Measured) -> Option<Verdict> {
    let duration = measured.duration?;
    let transit = |body: &Body| {
        // A body whose contact sphere is off its mass centre (a rod struck at its end, a clump) is not that sphere: its
        // mass is not spread over the sphere's volume, and its size along the wave's path is not the sphere's
        // diameter, so no transit can be formed from the scene (docs/idealisation.md).
        if body.is_off_centre() {
            return None;
        }
        let young = body.young.filter(|e| e.is_finite())?;
        let volume = 4.0 / 3.0 * std::f64::consts::PI * body.radius.powi(3);
        let density = body.density.unwrap_or(body.mass / volume);
        (density.is_finite() && body.radius.is_finite()).then(|| 2.0 * body.radius / (young / density).sqrt())
    };
    let slowest = bodies
        .into_iter()
        .filter_map(transit)
        .fold(None, |worst: Option<f64>, t| Some(worst.map_or(t, |w| w.max(t))))?;
    verdict(slowest, duration, SHAPE, ("2R/c / t_c", "s"), |ratio| {
        format!(
            "an elastic wave crosses the body in {} of the contact time: below a tenth the body is loaded \
             quasi-statically as Hertz assumes; near one, waves carry energy away (Hunter 1957) and vibrations \
             remain after the impact",
            brief(ratio, "")
        )
    })
}

/// What a local slope `d ln e / d ln v0` says of a doubling of the speed, in words: the change of e in percent, or,
/// for a slope so steep that the power law it stands for would multiply e more than a hundredfold (a slope of
/// hundreds between two slow contacts of a settling pile), that it would — never an overflowing percentage.
fn doubling(slope: f64) -> String {
    let change = 100.0 * (2f64.powf(slope) - 1.0);
    if change.is_finite() && change <= 1e4 {
        format!("doubling the speed changes e by {} %", brief(change, ""))
    } else {
        "doubling the speed would multiply e more than a hundredfold at this slope".to_string()
    }
}

/// d ln e / d ln v0 by the central difference of the two trial runs, against [`SLOPE_SCALE`].
fn constant_e(measured: &Measured) -> Option<Verdict> {
    let (slower, faster) = (measured.speed_trial.slower?, measured.speed_trial.faster?);
    if slower <= 0.0 || faster <= 0.0 || measured.restitution? <= 0.0 {
        return None;
    }
    let slope = (faster / slower).ln() / ((1.0 + SPEED_STEP) / (1.0 - SPEED_STEP)).ln();
    verdict(slope, SLOPE_SCALE, SLOPE, ("d ln e / d ln v0", ""), |_| {
        let both = match two_values(slower, faster) {
            Ok((slower, faster)) => format!("{slower} at 0.9 and {faster} at 1.1 times the speed"),
            Err((e, difference)) => format!("{e} at 0.9 and 1.1 times the speed alike (to {difference})"),
        };
        format!(
            "e is {both}: a slope of {}, so {} — the idealisation's one e serves {}",
            brief(slope, ""),
            doubling(slope),
            if slope.abs() < SLOPE_SCALE * SLOPE.holds_below { "all nearby speeds" } else { "this speed only" }
        )
    })
}

/// The tangential impulse against the normal one, or friction's work against the kinetic energy before, the larger;
/// a frictionless contact is smooth (0).
fn smooth(bodies: [&Body; 2], measured: &Measured) -> Option<Verdict> {
    let normal_impulse = measured.deformation_impulse + measured.restitution_impulse.unwrap_or(0.0);
    if measured.friction == 0.0 {
        return verdict(0.0, normal_impulse, CORRECTION, ("J_t / J_n", "N s"), |_| {
            "the contact is frictionless: no tangential impulse, as the idealisation's smooth impact assumes".into()
        });
    }
    let after = measured.velocities_after?;
    let n = measured.normal;
    // The tangential impulse from a movable body's change of momentum across the first contact's normal.
    let i = if bodies[0].is_immovable() { 1 } else { 0 };
    let change = after[i] - measured.velocities_before[i];
    let tangential = bodies[i].mass * (change - n * change.dot(&n)).norm();
    let work = measured.friction_work.unwrap_or(0.0).abs();
    let by_impulse = tangential / normal_impulse;
    let by_work = work / measured.kinetic_before;
    let mu = measured.friction;
    if by_impulse >= by_work {
        verdict(tangential, normal_impulse, CORRECTION, ("J_t / J_n", "N s"), |ratio| {
            format!(
                "friction (mu = {}) gives a tangential impulse of {} of the normal one, which the smooth \
                 idealisation leaves out (oblique.rigid_body includes it){}",
                short(mu),
                brief(ratio, ""),
                difference(measured)
            )
        })
    } else {
        verdict(work, measured.kinetic_before, CORRECTION, ("friction work / kinetic energy", "J"), |ratio| {
            format!(
                "friction (mu = {}) dissipates {} of the kinetic energy, which the smooth idealisation leaves out \
                 (oblique.rigid_body includes it){}",
                short(mu),
                brief(ratio, ""),
                difference(measured)
            )
        })
    }
}

/// The lever arm b of the normal about each body's origin (mass centre, or pivot) against the radius of gyration k
/// about the axis of its moment: a free body's effective mass at the contact is M / (1 + (b/k)²), so b/k is the
/// square root of the correction to the particles' m* ([`LEVER`]). A sphere's normal passes through its centre
/// (b = 0), so every impact of spheres and walls is central. A pivoted body is judged about its pivot: struck
/// where b = k it meets the normal with its whole mass, elsewhere with I_O/b².
fn central(bodies: [&Body; 2], measured: &Measured) -> Option<Verdict> {
    let worst = measured
        .levers
        .iter()
        .enumerate()
        .filter_map(|(i, lever)| lever.map(|l| (i, l)))
        .filter(|(_, l)| l.gyration > 0.0)
        .max_by(|(_, x), (_, y)| (x.arm / x.gyration).total_cmp(&(y.arm / y.gyration)));
    let Some((i, lever)) = worst.filter(|(_, l)| l.arm > 0.0 || l.pivoted) else {
        let gyration = bodies
            .iter()
            .filter(|b| b.mass.is_finite() && b.inertia.is_finite())
            .map(|b| (b.inertia / b.mass).sqrt())
            .fold(f64::INFINITY, f64::min);
        let scale = if gyration.is_finite() && gyration > 0.0 { gyration } else { smaller_radius(bodies)? };
        return verdict(0.0, scale, LEVER, ("b / k", "m"), |_| {
            "the normal passes through both mass centres (spheres and walls): the impact is central, the effective \
             mass along the normal is m* and the normal force does not spin the bodies"
                .into()
        });
    };
    let name = &bodies[i].name;
    let origin = if lever.pivoted { "pivot" } else { "mass centre" };
    verdict(lever.arm, lever.gyration, LEVER, ("b / k", "m"), |ratio| {
        let (effective, whole) = apart(lever.effective_mass, lever.mass, "kg");
        format!(
            "the normal passes {} from {name}'s {origin} ({} of its radius of gyration): {name} meets the contact with \
             an effective mass of {effective}, not its {whole}, and the blow turns it{}",
            brief(lever.arm, "m"),
            brief(ratio, ""),
            difference(measured)
        )
    })
}

#[cfg(test)]
mod tests {
    use super::doubling;

    #[test]
    fn a_doubling_is_a_percentage_until_it_would_be_more_than_a_hundredfold() {
        // 2^1 - 1 = 100 %, 2^-1 - 1 = -50 %; a slope of 1190 (measured between two slow contacts of a settling
        // pile) would overflow 2^slope: words instead, never "inf".
        assert_eq!(doubling(1.0), "doubling the speed changes e by 100 %");
        assert_eq!(doubling(-1.0), "doubling the speed changes e by -50 %");
        for slope in [1190.0, 2000.0, f64::MAX] {
            let text = doubling(slope);
            assert!(text.contains("more than a hundredfold") && !text.contains("inf"), "{slope}: {text}");
        }
        assert!(doubling(-2000.0).contains("-100 %"), "{}", doubling(-2000.0));
    }
}
