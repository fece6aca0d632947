//! Reference impacts for the fast path and the exact value of every measured quantity, from outside the fast
//! path: `impact::reference` (closed forms and quadratures), momentum and energy balances, and the force-peak
//! times computed here by closed forms, bisection and a tanh-sinh quadrature of the integrals of
//! docs/references.md#the-hunt-crossley-family.
//! Shared by tests/fast_path.rs and benches/fast.rs.
#![allow(dead_code)]

use impact::fast::{Outcome, Quantities, Request};
use impact::law::{ContactLaw, LawKind, Separation};
use impact::reference::{self, ContactReference};
use impact::scales::Scales;
use std::f64::consts::FRAC_PI_2;

/// One reference impact, in the scaled units (m* = K = v0 = 1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Case {
    /// `F = d^n (1 + x d')` (Hunt–Crossley with alpha = x).
    Hysteresis { x: f64, n: f64 },
    /// `F = d^n`.
    Elastic { n: f64 },
    /// `F = d + 2 zeta d'`.
    KelvinVoigt { zeta: f64, separation: Separation },
    /// `F = d^(3/2) + a d^(1/4) d'` with the map's `a` for the nominal restitution `e`.
    Tsuji { e: f64, separation: Separation },
}

impl Case {
    pub fn name(&self) -> String {
        let sep = |s: &Separation| if *s == Separation::Force { "F=0" } else { "d=0" };
        match self {
            Case::Hysteresis { x, n } => format!("hunt-crossley x={x} n={n}"),
            Case::Elastic { n } => format!("hertz n={n}"),
            Case::KelvinVoigt { zeta, separation } => format!("kelvin-voigt zeta={zeta} {}", sep(separation)),
            Case::Tsuji { e, separation } => format!("tsuji e={e} {}", sep(separation)),
        }
    }

    /// The fast path's request for this case at `tolerance`.
    pub fn request(&self, tolerance: f64) -> Request {
        let (kind, n, damping, separation) = match *self {
            Case::Hysteresis { x, n } => (LawKind::HuntCrossley, n, x, Separation::Penetration),
            Case::Elastic { n } => (LawKind::Hertz, n, 0.0, Separation::Penetration),
            Case::KelvinVoigt { zeta, separation } => (LawKind::KelvinVoigt, 1.0, 2.0 * zeta, separation),
            Case::Tsuji { e, separation } => (LawKind::Tsuji, 1.5, reference::tsuji_damping(e), separation),
        };
        Request {
            law: ContactLaw {
                kind,
                stiffness: 1.0,
                exponent: n,
                damping,
                tsuji_scale: 1.0,
                yield_penetration: f64::INFINITY,
                solimp: impact::law::NO_SOLIMP,
                ramp: f64::INFINITY,
            },
            scales: Scales::new(1.0, 1.0, n, 1.0),
            separation,
            tolerance,
            quantities: Quantities::ALL,
        }
    }

    /// Every measured quantity's exact value; `None` when the bodies never separate.
    pub fn exact(&self) -> Option<Exact> {
        let (base, peak_time, end_elastic) = match *self {
            Case::Hysteresis { x, n } => (reference::hysteresis_contact(x, n), hysteresis_peak_time(x, n), 0.0),
            Case::Elastic { n } => {
                let r = reference::hertz_elastic(n);
                (r, r.max_compression_time, 0.0)
            }
            Case::KelvinVoigt { zeta, separation } => {
                let r = reference::kelvin_voigt(zeta, separation)?;
                // At F = 0, d = -c d' = 2 zeta e: spring energy d²/2.
                let elastic =
                    if separation == Separation::Force { 0.5 * (2.0 * zeta * r.restitution).powi(2) } else { 0.0 };
                (r, kelvin_voigt_peak_time(zeta), elastic)
            }
            Case::Tsuji { e, separation } => {
                let a = reference::tsuji_damping(e);
                let r = reference::tsuji(a, separation)?;
                // At F = 0, w = d^(5/4) = -a d' = a e: spring energy (2/5) d^(5/2) = (2/5) w².
                let elastic = if separation == Separation::Force { 0.4 * (a * r.restitution).powi(2) } else { 0.0 };
                (r, tsuji_peak_time(a), elastic)
            }
        };
        let e = base.restitution;
        Some(Exact { base, peak_time, end_elastic, dissipated: 0.5 * (1.0 - e) * (1.0 + e) - end_elastic })
    }
}

/// The reference impacts of the brief: Hunt–Crossley at x = 0.01, 0.5, 2, 10 and n = 1, 1.5, 2.2; elastic Hertz;
/// Tsuji e = 0.9, 0.5, 0.2 and Kelvin–Voigt zeta = 0.1, 0.3, 2 (overdamped) under both separation criteria.
pub fn reference_cases() -> Vec<Case> {
    let mut cases = Vec::new();
    for x in [0.01, 0.5, 2.0, 10.0] {
        for n in [1.0, 1.5, 2.2] {
            cases.push(Case::Hysteresis { x, n });
        }
    }
    for n in [1.5, 1.0, 2.2] {
        cases.push(Case::Elastic { n });
    }
    for separation in [Separation::Penetration, Separation::Force] {
        for e in [0.9, 0.5, 0.2] {
            cases.push(Case::Tsuji { e, separation });
        }
        for zeta in [0.1, 0.3, 2.0] {
            cases.push(Case::KelvinVoigt { zeta, separation });
        }
    }
    cases
}

/// Exact values of one impact (scaled).
#[derive(Debug, Clone, Copy)]
pub struct Exact {
    pub base: ContactReference,
    pub peak_time: f64,
    /// Spring energy left at a force separation (0 at a penetration separation).
    pub end_elastic: f64,
    /// `(1 - e²)/2 - end_elastic`.
    pub dissipated: f64,
}

/// The measured quantities, in a fixed order (names for printing).
pub const QUANTITIES: [&str; 13] =
    ["e", "dmax", "t0", "tc", "Fmax", "t(Fmax)", "Jd=V0", "Jr", "Wc", "Wr", "D", "Eel", "e_impulse"];

/// Error of each measured quantity: relative, except where the exact value is 0 (then absolute, in the scaled
/// units `m* v0²` or `T`). `Jd`'s error is V0's relative to the approach speed.
pub fn errors(out: &Outcome, exact: &Exact) -> [f64; 13] {
    let rel = |got: f64, want: f64| if want == 0.0 { got.abs() } else { ((got - want) / want).abs() };
    let m = &out.max_compression;
    let end = &out.end;
    let e = exact.base.restitution;
    let jd = m.impulse;
    let jr = out.restitution_impulse;
    [
        rel(-end.rate, e),
        rel(m.penetration, exact.base.max_penetration),
        rel(m.time, exact.base.max_compression_time),
        rel(end.time, exact.base.duration),
        rel(out.peak_force, exact.base.max_force),
        rel(out.peak_force_time, exact.peak_time),
        rel(jd, 1.0),
        rel(jr, e),
        rel(m.work, 0.5),
        rel(out.restitution_work, 0.5 * e * e),
        rel(end.dissipated, exact.dissipated),
        rel(end.elastic, exact.end_elastic),
        rel(jr / jd, e),
    ]
}

/// Tanh-sinh quadrature of an integrand analytic inside `[a, b]` (bounded at the ends), to ~1e-15.
pub fn tanh_sinh(f: impl Fn(f64) -> f64, a: f64, b: f64) -> f64 {
    let half = 0.5 * (b - a);
    let mut previous = f64::NAN;
    for level in 3..=12 {
        let h = 0.5_f64.powi(level);
        let mut sum = FRAC_PI_2 * f(a + half);
        let mut k = 1;
        loop {
            let t = k as f64 * h;
            if t > 3.6 {
                break;
            }
            let u = FRAC_PI_2 * t.sinh();
            let c = u.cosh();
            let offset = half * (-u).exp() / c;
            sum += FRAC_PI_2 * t.cosh() / (c * c) * (f(a + offset) + f(b - offset));
            k += 1;
        }
        let estimate = half * h * sum;
        if (estimate - previous).abs() <= 1e-15 * estimate.abs() {
            return estimate;
        }
        previous = estimate;
    }
    previous
}

/// Root of `f` on `(lo, hi)` by bisection, for `f(lo) > 0 >= f(hi)`.
pub fn bisect(f: impl Fn(f64) -> f64, mut lo: f64, mut hi: f64) -> f64 {
    loop {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            return mid;
        }
        if f(mid) > 0.0 { lo = mid } else { hi = mid }
    }
}

/// `-ln(1 - y) - y` for `0 <= y < 1`, without cancellation.
fn log_tail(y: f64) -> f64 {
    if y < 0.1 { (2..60).rev().fold(0.0, |acc, k| (acc + 1.0 / k as f64) * y) * y } else { -(-y).ln_1p() - y }
}

/// Hunt–Crossley force-peak time. From `v dv/(1 + x v) = -d^n dd` (docs/references.md#the-hunt-crossley-family),
/// with `h = 1 - v` and `y = x h/(1 + x)`: `d^(n+1) = (n+1) S/x²`, `S = x y - (-ln(1 - y) - y)` (`S ≈ h/(1+x)` for
/// small h). The peak is where `x d^(n+1) = n v`; its time is `∫_0^{h_p} dh/(d^n (1 + x v))`, integrable like
/// `h^(-n/(n+1))` at `h = 0`: with `h = s^(n+1)` the integrand `(n+1) s^n / (d^n (1 + x v))` is bounded.
pub fn hysteresis_peak_time(x: f64, n: f64) -> f64 {
    if x == 0.0 {
        return reference::hertz_elastic(n).max_compression_time;
    }
    let d_pow = |h: f64| {
        let y = x * h / (1.0 + x);
        (n + 1.0) * (x * y - log_tail(y)) / (x * x)
    };
    // rho(h) = n v - x d^(n+1): positive at h = 0 (v = 1), negative at h = 1 (v = 0).
    let h_peak = bisect(|h| n * (1.0 - h) - x * d_pow(h), 0.0, 1.0);
    let s_peak = h_peak.powf(1.0 / (n + 1.0));
    let integrand = |s: f64| {
        if s == 0.0 {
            // d^n ~ ((n+1) h/(1+x))^(n/(n+1)) = ((n+1)/(1+x))^(n/(n+1)) s^n, v = 1.
            return (n + 1.0) / (((n + 1.0) / (1.0 + x)).powf(n / (n + 1.0)) * (1.0 + x));
        }
        let h = s.powf(n + 1.0);
        let d_n = d_pow(h).powf(n / (n + 1.0));
        (n + 1.0) * s.powf(n) / (d_n * (1.0 + x * (1.0 - h)))
    };
    tanh_sinh(integrand, 0.0, s_peak)
}

/// Kelvin–Voigt force-peak time (units `sqrt(m*/k)`): `F' = (1 - 4 zeta²) D' - 2 zeta D` vanishes at phase
/// `atan2((1 - 4 zeta²) wd, zeta (3 - 4 zeta²))` for `zeta < 1/2`; for `zeta >= 1/2` the force is largest at first
/// contact.
pub fn kelvin_voigt_peak_time(zeta: f64) -> f64 {
    if zeta >= 0.5 {
        return 0.0;
    }
    let wd = (1.0 - zeta * zeta).sqrt();
    ((1.0 - 4.0 * zeta * zeta) * wd).atan2(zeta * (3.0 - 4.0 * zeta * zeta)) / wd
}

/// Tsuji force-peak time. In `τ` (with `w = d^(5/4)`, `dτ = d^(1/4) dt`) and `s = omega0 τ`,
/// `omega0 = sqrt(5)/2`, the motion is the unit oscillator `D(s) = e^(-zeta s) sin(wd s)/wd` (`zeta = a/sqrt 5`,
/// underdamped here): `w = omega0 D`, `d' = D'`. The force `w^(1/5) (w + a d')` peaks where
/// `(1/4) d' F̂ + w ((5/4) d' - a F̂) = 0`, `F̂ = w + a d'` (bisection on the closed form), and
/// `t = omega0^(-6/5) ∫_0^{s_p} D^(-1/5) ds`, with `s = sigma^5` to remove the endpoint singularity.
pub fn tsuji_peak_time(a: f64) -> f64 {
    let zeta = a / 5.0_f64.sqrt();
    assert!(zeta < 1.0, "the Tsuji reference cases are underdamped");
    let omega0 = 1.25_f64.sqrt();
    let wd = (1.0 - zeta * zeta).sqrt();
    let d = |s: f64| (-zeta * s).exp() * (wd * s).sin() / wd;
    let rate = |s: f64| (-zeta * s).exp() * ((wd * s).cos() - zeta / wd * (wd * s).sin());
    let g = |s: f64| {
        let (w, v) = (omega0 * d(s), rate(s));
        let force = w + a * v;
        0.25 * v * force + w * (1.25 * v - a * force)
    };
    // Positive at first contact (g = a/4), negative at maximum compression (g = -a w²).
    let s_max = zeta.acos() / wd;
    let s_peak = bisect(g, 0.0, s_max);
    // D(s)/s for the substitution (1 at s = 0).
    let d_over_s = |s: f64| if s == 0.0 { 1.0 } else { d(s) / s };
    let integral = tanh_sinh(|sigma| 5.0 * sigma.powi(3) * d_over_s(sigma.powi(5)).powf(-0.2), 0.0, s_peak.powf(0.2));
    omega0.powf(-1.2) * integral
}
