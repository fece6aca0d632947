//! The fixed-step schemes of the peer codes, run on the 1-D normal contact `m* d'' = -F(d, d')` exactly as those
//! codes run it, so that the program can report the e a user's own code gives at its time step
//! (docs/numerics.md#the-fixed-step-schemes-of-the-peer-codes):
//!
//! * [`Scheme::Verlet`]: the velocity Verlet of DEM codes (LAMMPS' `fix nve` with `pair granular`, LIGGGHTS): the
//!   damping sees the half-step velocity, `v½ = v - (dt/2) F/m*`, `d += dt v½`, `F = F(d, v½)`,
//!   `v = v½ - (dt/2) F/m*`.
//! * [`Scheme::SymplecticEuler`]: the semi-implicit Euler of Kratos' DEM and MuJoCo:
//!   `v += dt (-F(d, v)/m*)`, `d += dt v`.
//!
//! The force is the law's ([`ContactLaw::split_force_after`], with the deepest penetration so far for a law with
//! memory) while the penetration is positive, and zero otherwise: a contact exists when the bodies overlap (the
//! peers' `rsq < radsum²`), so no power of a negative penetration is ever taken, and nothing here knows which law
//! it runs. Every event is taken at the first step past it, as the peers take them: maximum compression at the
//! first step whose velocity is not positive, separation at the first step whose penetration — or, under a force
//! separation or for a law whose force never pulls, the law's continued separation function
//! ([`ContactLaw::separation_function_after`]) — is not positive while the bodies move apart. e is the velocity the
//! scheme carries out of the contact (the force is zero from that step on) over the approach speed.
//!
//! The touch phase: the step grid need not meet the first touch. With a phase `φ ∈ [0, 1)` the step that straddles
//! the touch starts a time `φ dt` before it, the bodies `φ dt v0` apart (penetration `-φ dt v0`) and closing at
//! `v0`; time is counted from the touch, so the step boundaries are at `(k - φ) dt`. `φ = 0` is the peers' usual
//! start, the touch on a step boundary (`d = 0`, `d' = v0` at `t = 0`, no force there).

use crate::law::{ContactLaw, Separation};
use crate::outcome::{SETTLED, TIME_LIMIT};
use crate::scales::Scales;

/// Most steps one run may take, whatever the time limit allows (about a second of work).
pub const MAX_STEPS: u64 = 200_000_000;

/// A fixed-step scheme of the peer codes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scheme {
    /// The DEM velocity Verlet (LAMMPS, LIGGGHTS): the damping sees the half-step velocity.
    Verlet,
    /// The semi-implicit (symplectic) Euler of Kratos and MuJoCo: the velocity first, then the position with it.
    SymplecticEuler,
    /// The implicit (backward) Euler of Drake's discrete SAP contact: the new velocity solves
    /// `m* (v' - v) = -dt max(0, F(d + dt v', v'))`, the force at the step's end, cut at zero; then `d += dt v'`.
    /// Not a scene's `[solver] method`: `impact translate --to drake` runs it.
    ImplicitEuler,
}

impl Scheme {
    /// The scene spelling (`[solver] method`).
    pub fn name(self) -> &'static str {
        match self {
            Scheme::Verlet => "verlet",
            Scheme::SymplecticEuler => "symplectic-euler",
            Scheme::ImplicitEuler => "implicit-euler",
        }
    }
}

/// One normal contact as a fixed-step scheme sees it: the law (SI), the effective mass m* (kg), the approach speed
/// v0 (m/s, > 0) and the separation criterion the scene names.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Contact {
    pub law: ContactLaw,
    pub mass: f64,
    pub speed: f64,
    pub separation: Separation,
}

/// The contact at a step boundary, SI, time from the first touch.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Point {
    /// s.
    pub time: f64,
    /// m.
    pub penetration: f64,
    /// The velocity the scheme carries at this boundary (Verlet's full-step one), m/s.
    pub rate: f64,
    /// The scheme's sum of the force's kicks so far, `Σ dt F` (Verlet: half kicks `Σ (dt/2) F`), N s; it equals
    /// `m* (v0 - rate)` to rounding.
    pub impulse: f64,
    /// The work of the contact force on the relative motion so far, as the scheme does it: the kinetic energy its
    /// kicks took, `m* (v0² - rate²)/2`, J.
    pub work: f64,
    /// The scheme's sum of the damping's power, `Σ dt F_dissipative v` with the velocity the force saw, J.
    pub dissipated: f64,
    /// The deepest penetration so far, m (what a yielding law's force remembers).
    pub deepest: f64,
    /// The force the scheme computed at this boundary (zero out of contact), N.
    pub force: f64,
}

/// How a run ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ending {
    /// The bodies parted.
    Separated,
    /// The relative motion died out in contact (|d|/L + |d'|/v0 below [`SETTLED`]).
    Settled,
    /// No separation within [`TIME_LIMIT`] elastic time units (or [`MAX_STEPS`] steps).
    TimeLimit,
    /// The state left the finite numbers: the step is far beyond the scheme's stability limit.
    Diverged,
}

/// What a fixed-step run came to.
#[derive(Debug, Clone, PartialEq)]
pub struct Run {
    /// The first step whose velocity is not positive (the contact's first point if the run ended before).
    pub max_compression: Point,
    /// The step that ended the contact (its rate is the velocity carried out), or where the run stopped.
    pub end: Point,
    /// The largest force the scheme computed, and when: (s, N).
    pub peak_force: (f64, f64),
    /// The deepest penetration reached at a step boundary, m.
    pub max_penetration: f64,
    pub ending: Ending,
    /// Steps taken, from the one that straddles the touch.
    pub steps: u64,
    /// Force evaluations (steps in contact).
    pub evaluations: u64,
}

impl Run {
    /// Whether the bodies parted.
    pub fn separated(&self) -> bool {
        self.ending == Ending::Separated
    }

    /// e = -v_after / v0 from the velocity the scheme carried out of the contact; `None` if the bodies did not part.
    pub fn restitution(&self, speed: f64) -> Option<f64> {
        self.separated().then(|| -self.end.rate / speed)
    }
}

impl Contact {
    /// The contact's scaled units.
    pub fn scales(&self) -> Scales {
        Scales::new(self.mass, self.law.stiffness, self.law.exponent, self.speed)
    }

    /// Whether the contact ends on the law's separation function rather than on the penetration alone: under a
    /// force separation, and for a law whose force never pulls (for which it is the penetration, or the
    /// penetration beyond a yielding law's dent).
    fn on_force(&self) -> bool {
        self.separation == Separation::Force || !self.law.kind.can_turn_tensile()
    }

    /// Whether the contact is over at a step boundary: moving apart, and the penetration (or the separation
    /// function) not positive.
    fn ended(&self, d: f64, v: f64, deepest: f64) -> bool {
        v < 0.0 && (d <= 0.0 || (self.on_force() && self.law.separation_function_after(d, v, deepest) <= 0.0))
    }

    /// The force parts (elastic, dissipative) the scheme applies at `(d, v)`: the law's while the bodies overlap,
    /// zero otherwise.
    fn force(&self, d: f64, v: f64, deepest: f64) -> (f64, f64) {
        if d > 0.0 {
            let parts = self.law.split_force_after(d, v, deepest);
            (parts.elastic, parts.dissipative)
        } else {
            (0.0, 0.0)
        }
    }

    /// The implicit Euler step's new rate v' from (d, v): the root of `g(v') = m* (v' - v) + dt max(0, F(d + dt v',
    /// v'))`, which lies in `[v - dt F(d + dt v, v)/m*, v]` for a force that grows with d and d' (g is not positive at
    /// the left end, not negative at the right); found by bisection to the last bit.
    fn implicit_rate(&self, d: f64, v: f64, dt: f64, deepest: f64) -> f64 {
        let m = self.mass;
        let pushed = |rate: f64| {
            let (elastic, dissipative) = self.force(d + dt * rate, rate, deepest.max(d + dt * rate));
            (elastic + dissipative).max(0.0)
        };
        let g = |rate: f64| m * (rate - v) + dt * pushed(rate);
        let mut high = v;
        if g(high) <= 0.0 {
            return high;
        }
        let mut low = v - dt * pushed(v) / m;
        for _ in 0..200 {
            let middle = 0.5 * (low + high);
            if middle <= low || middle >= high {
                break;
            }
            if g(middle) > 0.0 { high = middle } else { low = middle }
        }
        0.5 * (low + high)
    }

    /// Runs `scheme` at step `dt` (s, > 0) with the touch at phase `phase` ∈ [0, 1) of its step (module docs).
    /// `record`, when given, receives every step boundary in contact (and the first and last).
    pub fn run(&self, scheme: Scheme, dt: f64, phase: f64, mut record: Option<&mut Vec<Point>>) -> Run {
        let (m, v0) = (self.mass, self.speed);
        let scales = self.scales();
        let limit = TIME_LIMIT * scales.time;
        let max_steps = ((limit / dt).ceil().max(1.0) as u64).min(MAX_STEPS);
        let mut at = Point {
            // (0 - x, not -x: a phase of 0 starts at +0, as a history shows it.)
            time: 0.0 - phase * dt,
            penetration: 0.0 - phase * dt * v0,
            rate: v0,
            impulse: 0.0,
            work: 0.0,
            dissipated: 0.0,
            deepest: 0.0,
            force: 0.0,
        };
        let mut compressed: Option<Point> = None;
        let mut peak = (0.0, 0.0);
        let mut max_penetration = 0.0f64;
        let mut steps = 0u64;
        let mut evaluations = 0u64;
        // Symplectic Euler's damping force at the step's start (zero: the run starts out of contact or at the touch).
        let mut damping = 0.0;
        let work = |v: f64| 0.5 * m * (v0 * v0 - v * v);
        if let Some(points) = record.as_deref_mut() {
            points.push(at);
        }
        let ending = loop {
            if steps >= max_steps {
                break Ending::TimeLimit;
            }
            steps += 1;
            let (d, v) = match scheme {
                Scheme::Verlet => {
                    // The second half kick of the last step's force, the drift at the half-step velocity.
                    let half = at.rate - 0.5 * dt * at.force / m;
                    at.impulse += 0.5 * dt * at.force;
                    let d = at.penetration + dt * half;
                    at.time += dt;
                    at.penetration = d;
                    at.rate = half;
                    if compressed.is_some() && self.ended(d, half, at.deepest) {
                        // The contact is over: no force from here, so the velocity carried out is v½.
                        at.force = 0.0;
                        at.work = work(half);
                        break Ending::Separated;
                    }
                    at.deepest = at.deepest.max(d);
                    let (elastic, dissipative) = self.force(d, half, at.deepest);
                    if d > 0.0 {
                        evaluations += 1;
                    }
                    at.force = elastic + dissipative;
                    at.dissipated += dt * dissipative * half;
                    at.rate = half - 0.5 * dt * at.force / m;
                    at.impulse += 0.5 * dt * at.force;
                    (d, at.rate)
                }
                Scheme::SymplecticEuler => {
                    // The force at the step's start, computed when the last step ended.
                    let force = at.force;
                    if force > peak.0 {
                        peak = (force, at.time);
                    }
                    at.dissipated += dt * damping * at.rate;
                    at.rate -= dt * force / m;
                    at.impulse += dt * force;
                    at.penetration += dt * at.rate;
                    at.time += dt;
                    let (d, v) = (at.penetration, at.rate);
                    if compressed.is_some() && self.ended(d, v, at.deepest) {
                        at.force = 0.0;
                        at.work = work(v);
                        break Ending::Separated;
                    }
                    at.deepest = at.deepest.max(d);
                    let (elastic, dissipative) = self.force(d, v, at.deepest);
                    if d > 0.0 {
                        evaluations += 1;
                    }
                    (at.force, damping) = (elastic + dissipative, dissipative);
                    (d, v)
                }
                Scheme::ImplicitEuler => {
                    let rate = self.implicit_rate(at.penetration, at.rate, dt, at.deepest);
                    let force = m * (at.rate - rate) / dt;
                    at.impulse += dt * force;
                    at.penetration += dt * rate;
                    at.rate = rate;
                    at.time += dt;
                    let (d, v) = (at.penetration, rate);
                    if d > 0.0 {
                        evaluations += 1;
                    }
                    at.deepest = at.deepest.max(d);
                    let (_, dissipative) = self.force(d, v, at.deepest);
                    // (Where the force is cut at zero, so is its dissipative part.)
                    at.dissipated += dt * if force > 0.0 { dissipative * v } else { 0.0 };
                    at.force = force;
                    if force > peak.0 {
                        peak = (force, at.time);
                    }
                    if compressed.is_some() && force <= 0.0 && v < 0.0 {
                        at.work = work(v);
                        break Ending::Separated;
                    }
                    (d, v)
                }
            };
            at.work = work(v);
            max_penetration = max_penetration.max(d);
            if scheme == Scheme::Verlet && at.force > peak.0 {
                peak = (at.force, at.time);
            }
            if let Some(points) = record.as_deref_mut() {
                points.push(at);
            }
            if !(d.is_finite() && v.is_finite()) {
                break Ending::Diverged;
            }
            if compressed.is_none() && v <= 0.0 {
                compressed = Some(at);
            }
            if compressed.is_some() && d.abs() / scales.length + v.abs() / v0 < SETTLED {
                break Ending::Settled;
            }
        };
        if let Some(points) = record
            && points.last() != Some(&at)
        {
            points.push(at);
        }
        Run {
            max_compression: compressed.unwrap_or(at),
            end: at,
            peak_force: (peak.1, peak.0),
            max_penetration,
            ending,
            steps,
            evaluations,
        }
    }

    /// The e `scheme` gives at step `dt` (s) with the touch at phase `phase` ∈ [0, 1) of its step; `None` when the
    /// bodies do not part (or the scheme diverges). What `impact translate` asks.
    pub fn restitution(&self, scheme: Scheme, dt: f64, phase: f64) -> Option<f64> {
        self.run(scheme, dt, phase, None).restitution(self.speed)
    }

    /// The least and largest e over `phases` touch phases evenly spaced over [0, 1) (`k / phases`): the spread of
    /// e over where the touch falls in a step, which a user's code cannot choose. `None` when the bodies do not part
    /// at one of them, or `phases` is 0.
    pub fn restitution_spread(&self, scheme: Scheme, dt: f64, phases: usize) -> Option<(f64, f64)> {
        let mut spread: Option<(f64, f64)> = None;
        for k in 0..phases {
            let e = self.restitution(scheme, dt, k as f64 / phases as f64)?;
            spread = Some(spread.map_or((e, e), |(low, high)| (low.min(e), high.max(e))));
        }
        spread
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::law::LawKind;

    fn linear(zeta: f64) -> Contact {
        let (m, k) = (1.0, 1.0);
        let law = ContactLaw {
            kind: LawKind::KelvinVoigt,
            stiffness: k,
            exponent: 1.0,
            damping: 2.0 * zeta * (k * m).sqrt(),
            tsuji_scale: 0.0,
            yield_penetration: f64::INFINITY,
            solimp: crate::law::NO_SOLIMP,
            ramp: f64::INFINITY,
        };
        Contact { law, mass: m, speed: 1.0, separation: Separation::Penetration }
    }

    /// Symplectic Euler keeps the undamped linear oscillator's modified energy `v² + ω² d² - ω² dt d v` exactly
    /// (its one-step map has determinant 1), so its e at the boundary grid is close to 1 but not 1; the spread over
    /// the phase brackets it.
    #[test]
    fn phases_cover_the_step() {
        let contact = linear(0.0);
        let (low, high) = contact.restitution_spread(Scheme::SymplecticEuler, 0.1, 16).unwrap();
        assert!(low <= high && low > 0.9 && high < 1.1, "{low} {high}");
        let e0 = contact.restitution(Scheme::SymplecticEuler, 0.1, 0.0).unwrap();
        assert!(low <= e0 && e0 <= high);
    }
}
