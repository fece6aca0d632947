//! A slide on the Coulomb limit carried in closed form over a known normal motion
//! (docs/numerics.md#a-slide-in-closed-form).
//!
//! While a sphere slides on a flat wall its tangential force is `mu Fn` against the slip, so every tangential
//! quantity is a function of the normal impulse `Jn` alone, and of its integral over time, which the penetration
//! gives (`∫ Jn dt = v0 t - d` in the scaled units, the rate being `1 - Jn`). From a sliding state `(Jn0, t0, d0)`
//! with the slip `s0` along `ê`, the force on the sphere's side `σ mu Fn` (`σ = ±1`, the spring's sign):
//!
//! * the tangential impulse `Jt = Jt0 + σ mu ΔJn`, and the slip `s = s0 + k σ mu ΔJn` (`k` the slip gain);
//! * its integral `Jt0 Δt + σ mu (v Δt - Δd)` (`v` the penetration rate at the start);
//! * the friction work `σ mu (s0 ΔJn + k σ mu ΔJn² / 2)`;
//! * the immovable body's work `pn ΔJn + pt σ mu ΔJn`.
//!
//! The slide holds while the slip keeps its sign and the spring a stick would hold loads faster than the limit
//! grows, `kt |s| >= mu dFn/dt` ([`SlideContact::slide_holds`]). In compression `dFn/dt = F_d d' + F_v d''` with
//! `F_v >= 0` and `d'' = -Fn <= 0` for the laws taken here (Hertz, the Hunt–Crossley family, Kelvin–Voigt, Tsuji), so
//! `dFn/dt <= F_d(d, d') d'`; `F_d = α(d) + β(d) d'` with `α`, `β` and `kt` single powers of `d`. With `A = α/kt` and
//! `B = β/kt` at their largest over the penetrations the slide passes (an end of the range: single powers), the
//! condition holds whenever `|s| - mu (A u + B u²) >= 0` for every rate `u` it passes, a concave function of `u`
//! (the slip is linear in it): at the two ends, the slide's start and maximum compression. In restitution the limit
//! falls (each law's force falls from its peak to its first zero) and the slide holds while the slip keeps its sign.

use super::{DIRECTION_ONLY, SIZE, SlideContact, UNLOADED, index, mode_of};
use crate::dynamics::contact::Mode;
use crate::integrate::State;
use crate::law::Family;
use crate::scene::{FrictionCap, TangentialUnloading};

/// A point of the normal motion, scaled as the slide's state (from the normal fast path).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NormalPoint {
    /// Time since first contact, in T.
    pub time: f64,
    /// Penetration, in L.
    pub penetration: f64,
    /// ∫ Fn dt, in m* v0.
    pub impulse: f64,
    /// ∫ Fn d' dt, in m* v0².
    pub work: f64,
    /// ∫ F_dissipative d' dt, in m* v0².
    pub dissipated: f64,
}

impl SlideContact<'_> {
    /// Whether a slide of this contact can be carried in closed form: a slip at first contact along a line, the
    /// compressive limit `mu max(Fn, 0)`, no tangential damping and no rescaled unloading (both change when a slide
    /// holds), a wall approached at the scaled rate 1, and a law whose force rate is bounded as above: Hertz's, the
    /// Hunt–Crossley family's, Kelvin–Voigt's or Tsuji's.
    pub fn slides_in_closed_form(&self) -> bool {
        let t = &self.tangential;
        self.slipping
            && t.damping == 0.0
            && t.unloading != TangentialUnloading::Rescale
            && t.cap == FrictionCap::Compressive
            && t.friction > 0.0
            && (self.initial_rate - 1.0).abs() <= 1e-12
            && matches!(self.law.kind.family(), Family::Elastic | Family::Hysteresis | Family::Linear | Family::Tsuji)
    }

    /// The slip along `ê` at `y` (scaled).
    pub fn slip_at(&self, y: &State<SIZE>) -> f64 {
        self.initial_slip + self.slip_gain * y[index::TANGENTIAL_IMPULSE]
    }

    /// The scale of the slip over a slide from `y` to the normal impulse `impulse` (scaled): its size at `y` and its
    /// largest change, `k mu Jn`.
    pub fn slip_scale(&self, y: &State<SIZE>, impulse: f64) -> f64 {
        self.slip_at(y).abs() + self.slip_gain * self.tangential.friction * impulse.abs()
    }

    /// Whether `y` slides on the compressive limit's corner while the normal force pulls ([`UNLOADED`]).
    pub fn unloaded(&self, y: &State<SIZE>) -> bool {
        mode_of(y).1
    }

    /// The sign of a sliding state's force on the sphere's side: the spring's, which a slide holds.
    fn along(y: &State<SIZE>) -> f64 {
        y[index::SPRING].signum()
    }

    /// Whether the slide that `from` starts (a sliding state, the slip against the spring) stays on the limit up to
    /// maximum compression at the scaled penetration `deepest`, and its slip keeps its sign, by more than `margin`
    /// (scaled), up to where the limit ends, the normal impulse `limit_end` (see the module's docs). A sufficient
    /// condition: `false` sends the contact to the integrated slide.
    pub fn slide_holds(&self, from: &State<SIZE>, deepest: f64, limit_end: f64, margin: f64) -> bool {
        let (mode, unloaded) = mode_of(from);
        if mode != Mode::Slip || unloaded {
            return false;
        }
        let along = Self::along(from);
        let slip = self.slip_at(from);
        // The slip's size along the slide, as the normal impulse grows by `ΔJn`.
        let size = |gained: f64| -along * slip - self.slip_gain * self.tangential.friction * gained;
        let jn0 = from[index::NORMAL_IMPULSE];
        if !(size(0.0) > margin && size(limit_end - jn0) > margin) {
            return false;
        }
        let u0 = self.initial_rate - jn0;
        if u0 <= 0.0 {
            // (From restitution: the limit falls to its end.)
            return true;
        }
        let d0 = Self::depth(from);
        if !(deepest > 0.0 && d0 < deepest) {
            return false;
        }
        // `A(d)` and `B(d)` at the two ends of the penetrations passed; from first contact, where both are 0/0 for
        // Mindlin's spring, a penetration 2^-40 of the deepest stands in, and a ratio that grows towards it
        // (unbounded at first contact) fails.
        let s = &self.scales;
        let ratios = |d: f64| {
            let kt = self.tangential.stiffness_at(d);
            let gradient = |u: f64| self.law.force_gradient(d * s.length, u * s.speed).0 * s.length / s.force;
            let alpha = gradient(0.0);
            let beta = gradient(1.0) - alpha;
            (alpha / kt, beta / kt)
        };
        let from_contact = d0 <= 0.0;
        let low = if from_contact { deepest * 2f64.powi(-40) } else { d0 };
        let (a_low, b_low) = ratios(low);
        let (a_deep, b_deep) = ratios(deepest);
        let rising = |low: f64, deep: f64| low > deep * (1.0 + 1e-9) + 1e-300;
        if from_contact && (rising(a_low, a_deep) || rising(b_low, b_deep)) {
            return false;
        }
        let a = a_low.max(a_deep);
        let b = b_low.max(b_deep).max(0.0);
        let mu = self.tangential.friction;
        // The concave bound at the slide's start (rate u0); at maximum compression it is the slip's size, checked.
        a.is_finite() && b.is_finite() && size(0.0) - mu * (a * u0 + b * u0 * u0) > margin
    }

    /// The state at the normal motion's point `to` (the normal fast path's, scaled), reached from the sliding state
    /// `from` by a slide on the limit in closed form; `unloaded` marks a state past the compressive limit's end (the
    /// normal force pulls, no friction: [`UNLOADED`]), reached from the limit's end `from`.
    pub fn slid(&self, from: &State<SIZE>, to: &NormalPoint, unloaded: bool) -> State<SIZE> {
        let along = Self::along(from);
        let mu = if unloaded { 0.0 } else { self.tangential.friction };
        let gained = to.impulse - from[index::NORMAL_IMPULSE];
        let lapse = to.time - from[index::TIME];
        let rate = self.initial_rate - from[index::NORMAL_IMPULSE];
        let tangential = from[index::TANGENTIAL_IMPULSE];
        let slip = self.slip_at(from);
        let (per_normal, per_tangential) = self.immovable_rates;
        let mut y = State::<SIZE>::zeros();
        let d = to.penetration;
        y[index::ROOT] = d.abs().sqrt().sqrt().copysign(d);
        y[index::TIME] = to.time;
        y[index::NORMAL_IMPULSE] = to.impulse;
        y[index::NORMAL_WORK] = to.work;
        y[index::DISSIPATED] = to.dissipated / self.dissipation_scale;
        y[index::SPRING] =
            if from[index::SPRING] == 0.0 { -slip.signum() * DIRECTION_ONLY } else { from[index::SPRING] };
        y[index::TANGENTIAL_IMPULSE] = tangential + along * mu * gained;
        y[index::TANGENTIAL_SHIFT] =
            from[index::TANGENTIAL_SHIFT] + tangential * lapse + along * mu * (rate * lapse - (d - Self::depth(from)));
        y[index::TANGENTIAL_WORK] = from[index::TANGENTIAL_WORK]
            + along * mu * (slip * gained + self.slip_gain * along * mu * gained * gained / 2.0) / self.friction_scale;
        y[index::IMMOVABLE_WORK] = from[index::IMMOVABLE_WORK] + (per_normal + per_tangential * along * mu) * gained;
        y[index::MODE] = if unloaded { UNLOADED } else { Mode::Slip.slot() };
        y
    }
}
