//! The hysteresis family's impact without a time integration, where no time is asked for: its exact first
//! integral (docs/numerics.md#the-first-integral).
//!
//! For `F = K d^n (1 + alpha d')` the relative motion `m* v dv/dt = -F v` gives, scaled (`x = alpha v0`),
//! `v dv/(1 + x v) = -d^n dd`: with `w² = d^(n+1)` (the fast path's `w`) and `p = (n+1)/2`,
//! `w²/(2p) = G(1) - G(v)`, `G(v) = ∫_0^v u/(1 + x u) du = v² φ₂(x v)`, `φ₂(u) = (u - ln(1+u))/u²`. So
//!
//! * maximum compression (`v = 0`): `w² = (n+1) φ₂(x)`, and the penetration `δ = w^(2/(n+1))`;
//! * separation (`w = 0` again): `G(-e) = G(1)`, the exact relation of `e(x)` (`reference::hunt_crossley_restitution`),
//!   the same for every `n`;
//! * the force never pulls (`1 + x v` stays positive: `v' = 0` on the line `1 + x v = 0`), so the contact ends at
//!   zero penetration whichever separation is named;
//! * the impulses are the changes of the relative momentum, `1` and `e`; the works `1/2` and `-e²/2`; the elastic
//!   energy at maximum compression `w²/(n+1) = φ₂(x)`, and the dissipation `x ∫_0^1 u²/(1 + x u) du` in
//!   compression, `(1 - e²)/2` over the contact;
//! * the force peak, where `n v = x w²` ([`super::Regularised::peak_function`]), is the root in `(0, 1)` of
//!   `n v - x (n+1) (φ₂(x) - v² φ₂(x v))`, increasing in `v` (safeguarded Newton).
//!
//! Everything is a closed form or a scalar root to rounding (about 1e-16 relative), for a few hundred
//! nanoseconds; the times are integrals over the rate, taken by Gauss rules ([`first_integral_times`], to about
//! 1e-14; for a time-asking run only from [`TIMED_FROM`], where they measured faster than the integration). The path is taken for dampings up to [`MAX_DAMPING`]: beyond
//! it the restitution creeps for long, and how it ends (the time limit, the step budget, a contact whose motion
//! dies out) is the integrator's to say.

use super::first_integral_times::{self, Times};
use super::regularised::{Form, Regularised};
use super::{Ending, Outcome, PhasePoint, Quantities};
use crate::reference::{hunt_crossley_loss, hunt_crossley_restitution, phi2};

/// Largest scaled damping `x = alpha v0` the first integral answers for (e = 1.0e-3 there, a contact of 45, 91 and
/// 252 elastic time units for n = 1, 1.5 and 3; the creep that the time limit can stop begins orders of magnitude
/// beyond).
pub const MAX_DAMPING: f64 = 1e3;

/// Whether [`impact`] answers for `system` when `quantities` are asked at `tolerance`: a hysteresis law (Hertz's
/// elastic one included) with `x <= MAX_DAMPING`; where a time is asked for, only from `x >= TIMED_FROM` with
/// `1 <= n <= 3` (the times by quadrature over the first integral, [`first_integral_times`], tested there to about
/// 1e-13, and measured faster than the Taylor integration there: docs/numerics.md#the-first-integral), at a
/// tolerance of at least [`TIMED_TOLERANCE`].
pub fn covers(system: &Regularised, quantities: Quantities, tolerance: f64) -> bool {
    covers_law(system)
        && (!quantities.time
            || (system.damping >= TIMED_FROM && (1.0..=3.0).contains(&system.exponent) && tolerance >= TIMED_TOLERANCE))
}

/// Smallest scaled damping for which a run asking for a time takes the first integral and its quadratures: measured
/// slower than the Taylor integration below about 2 (2.6 µs against 2.0 µs at x = 0.5; 3.4 against 3.9 at x = 10).
pub const TIMED_FROM: f64 = 4.0;

/// Smallest tolerance at which a run asking for a time takes the first integral (its times are good to about 1e-14;
/// a run asking for more integrates, down to the rounding floor).
pub const TIMED_TOLERANCE: f64 = 1e-13;

/// Whether [`impact`] can answer for `system` whatever is asked: a hysteresis law with `x <= MAX_DAMPING`.
pub fn covers_law(system: &Regularised) -> bool {
    system.form == Form::Hysteresis && system.damping <= MAX_DAMPING
}

/// The impact of a hysteresis law from its first integral (see the module): what [`covers_law`] admits, the times by
/// quadrature ([`first_integral_times`]) where they are asked for.
pub fn impact(system: &Regularised, quantities: Quantities) -> Outcome {
    let (x, n) = (system.damping, system.exponent);
    let e = hunt_crossley_restitution(x);
    // 1 - e without cancellation, for the energies lost near e = 1 (its series below x = 0.05; `e` itself above).
    let loss = if x < 0.05 { hunt_crossley_loss(x) } else { 1.0 - e };
    let elastic = phi2(x);
    let w = ((n + 1.0) * elastic).sqrt();
    let penetration = system.penetration(w);
    let if_asked = |asked: bool, value: f64| if asked { value } else { f64::NAN };
    let max_compression = PhasePoint {
        time: f64::NAN,
        penetration,
        rate: 0.0,
        impulse: 1.0,
        work: 0.5,
        dissipated: if_asked(quantities.dissipation, x * compression_loss(x)),
        elastic,
        force: system.force_at(w, penetration, 0.0),
    };
    let lost = 0.5 * loss * (1.0 + e);
    let end = PhasePoint {
        time: f64::NAN,
        penetration: 0.0,
        rate: -e,
        impulse: 1.0 + e,
        work: lost,
        dissipated: if_asked(quantities.dissipation, lost),
        elastic: 0.0,
        force: 0.0,
    };
    // The force peaks where `n v = x w²` (at maximum compression for Hertz).
    let peak = if quantities.peak && x > 0.0 { Some(peak_rate(x, n, elastic)) } else { None };
    let peak_force = match peak {
        _ if !quantities.peak => f64::NAN,
        None => max_compression.force,
        Some(v) => {
            let w = ((n + 1.0) * (elastic - v * v * phi2(x * v))).max(0.0).sqrt();
            system.force(w, v)
        }
    };
    let times = if quantities.time {
        first_integral_times::times(x, n, e, peak, quantities.peak)
    } else {
        Times { max_compression: f64::NAN, separation: f64::NAN, peak_force: f64::NAN }
    };
    let max_compression = PhasePoint { time: times.max_compression, ..max_compression };
    let end = PhasePoint { time: times.separation, ..end };
    Outcome {
        max_compression,
        end,
        restitution_impulse: e,
        restitution_work: 0.5 * e * e,
        peak_force,
        peak_force_time: times.peak_force,
        separated: true,
        ending: Ending::Separated,
        steps: 0,
        force_evaluations: 0,
        order: 0,
        first_integral: true,
    }
}

/// The times of the impact of `F = d^n (1 + x d')` (scaled: `x = alpha v0`, `0 <= x <= MAX_DAMPING`, `n` from 1
/// to 3 tested), by quadrature over the first integral (`src/fast/first_integral_times.rs`): of maximum compression, of
/// separation and of the force peak, in `T`.
pub fn times(x: f64, n: f64) -> Times {
    let e = hunt_crossley_restitution(x);
    let peak = if x == 0.0 { None } else { Some(peak_rate(x, n, phi2(x))) };
    first_integral_times::times(x, n, e, peak, true)
}

/// `∫_0^1 u²/(1 + x u) du` (the compression's dissipation over `x`): its series `Σ (-x)^k/(k+3)` for `x <= 1/4`,
/// `(ln(1+x) - x + x²/2)/x³` beyond (a cancellation of at most 4 ulps there).
fn compression_loss(x: f64) -> f64 {
    if x <= 0.25 {
        // 30 terms: the first omitted one is below 0.25^30/33 < 1e-19.
        (0..30).rev().fold(0.0, |acc, k| acc * -x + 1.0 / f64::from(k + 3))
    } else {
        (x.ln_1p() - x + 0.5 * x * x) / (x * x * x)
    }
}

/// The rate at the force peak: the root in `(0, 1)` of `h(v) = n v - x (n+1) (φ₂(x) - v² φ₂(x v))`
/// (`h(0) < 0 < h(1) = n`, `h' = n + x (n+1) v/(1 + x v) > 0`), by Newton's method kept inside a shrinking bracket.
pub(super) fn peak_rate(x: f64, n: f64, elastic: f64) -> f64 {
    let h = |v: f64| n * v - x * (n + 1.0) * (elastic - v * v * phi2(x * v));
    let (mut low, mut high) = (0.0_f64, 1.0_f64);
    // Light damping peaks near v = x (n+1)/(2n), heavy near 1.
    let mut v = (x * (n + 1.0) / (2.0 * n)).min(0.5);
    for _ in 0..60 {
        let value = h(v);
        if value == 0.0 {
            return v;
        }
        if value < 0.0 {
            low = v;
        } else {
            high = v;
        }
        let slope = n + x * (n + 1.0) * v / (1.0 + x * v);
        let next = v - value / slope;
        let next = if next > low && next < high { next } else { 0.5 * (low + high) };
        if (next - v).abs() <= 2.0 * f64::EPSILON * v {
            return next;
        }
        v = next;
    }
    v
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The compression's dissipation over x against a composite Simpson rule of its integrand written here.
    #[test]
    fn compression_loss_is_its_integral() {
        for x in [1e-8, 1e-3, 0.1, 0.25, 0.2500001, 0.7, 3.0, 40.0, 1e3] {
            let f = |u: f64| u * u / (1.0 + x * u);
            let m = 20_000;
            let h = 1.0 / f64::from(m);
            let sum: f64 = (0..=m)
                .map(|i| {
                    let weight = if i == 0 || i == m {
                        1.0
                    } else if i % 2 == 1 {
                        4.0
                    } else {
                        2.0
                    };
                    weight * f(f64::from(i) * h)
                })
                .sum();
            let simpson = sum * h / 3.0;
            let got = compression_loss(x);
            assert!((got / simpson - 1.0).abs() < 1e-12, "x = {x}: {got} vs {simpson}");
        }
    }
}
