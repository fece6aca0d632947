//! Exact contact history of the hysteresis-damping family `F = K d^n (1 + alpha d')` (Hunt–Crossley type),
//! docs/references.md, in the units `L`, `T`, `F0` of the module docs (so `m* = K = v0 = 1` and `alpha = x`).
//!
//! Along the contact `v = d'` is monotone, and `v dv/(1 + x v) = -d^n dd` gives
//! `d(v)^(n+1) = (n+1) S(v)`, `S(v) = ∫_v^1 u/(1 + x u) du`, and `dt = -dv/(d^n (1 + x v))`.
//! The times are 1-D integrals over `v` whose integrands blow up like `(distance)^(-n/(n+1))` where `d -> 0`;
//! the substitutions below make them bounded so that tanh-sinh quadrature reaches ~1e-15.

use super::ContactReference;
use super::hertz::hertz_elastic;
use super::hunt_crossley::HuntCrossleyState;
use super::numerics::{bisect, exprel, integrate, phi2};

/// Exact nondimensional impact for `F = K d^n (1 + x d'/v0)`, `n > 0`, `x >= 0` (docs/references.md).
///
/// * `restitution`: [`super::hunt_crossley_restitution`]`(x)`;
/// * `max_penetration`: `dmax^(n+1) = (n+1)(x - ln(1+x))/x²` (→ `(n+1)/2` as `x → 0`, evaluated without cancellation);
/// * `max_compression_time`, `duration`: docs/references.md's integrals `t0 = ∫_0^1 dv/(d^n (1+xv))`,
///   `tc = ∫_{-e}^1 …`, by tanh-sinh quadrature after the substitutions `1 - v = s^(n+1)` (compression) and
///   `v + e = e s^(n+1)` (restitution, `x < 1`) or `ln((1 + x v)/(1 - e x)) = ln(1/(1 - e x)) s^(n+1)`
///   (restitution, `x >= 1`), which remove the endpoint singularities;
/// * `max_force`: the largest `d^n (1 + x v)`, reached during compression where `x d^(n+1) = n v` (a root found by
///   bisection; with damping the force peaks before maximum compression).
///
/// Agrees with docs/references.md's table to ~1e-13 relative. `x = 0` returns [`hertz_elastic`]`(n)`.
/// `x < 0`, `n <= 0`, or non-finite input gives [`ContactReference::UNDEFINED`].
pub fn hysteresis_contact(x: f64, n: f64) -> ContactReference {
    if !(x >= 0.0 && x.is_finite() && n > 0.0 && n.is_finite()) {
        return ContactReference::UNDEFINED;
    }
    if x == 0.0 {
        return hertz_elastic(n);
    }
    by_quadrature(x, n)
}

/// The general computation, also valid at `x = 0` (used by the tests against the elastic closed form).
fn by_quadrature(x: f64, n: f64) -> ContactReference {
    let state = HuntCrossleyState::new_or_elastic(x);
    let p = n + 1.0;
    let t0 = compression_time(x, n);
    ContactReference {
        restitution: state.e,
        max_penetration: (p * phi2(x)).powf(1.0 / p),
        max_compression_time: t0,
        duration: t0 + restitution_time(x, n, state),
        max_force: peak_force(x, n).1,
    }
}

impl HuntCrossleyState {
    /// [`HuntCrossleyState::new`] extended to `x = 0` (elastic: `e = 1`, `q = 1`).
    fn new_or_elastic(x: f64) -> Self {
        if x == 0.0 { Self { e: 1.0, q: 1.0, ln_q: 0.0 } } else { Self::new(x) }
    }
}

/// `S(v)/h` for `h = 1 - v ∈ [0, 1]` (compression side, `v >= 0`):
/// `S = h/(1+x) - h² phi2(-y)/(1+x)²`, `y = x h/(1+x)`; exact at `v = 1` and cancellation-free on `[0, 1]`.
fn s_over_h(x: f64, h: f64) -> f64 {
    let a = 1.0 / (1.0 + x);
    a * (1.0 - h * a * phi2(-x * h * a))
}

/// Time from first contact to maximum compression, `∫_0^1 dv/(d^n (1 + x v))` with `1 - v = s^(n+1)`:
/// the integrand becomes `(n+1)^(1/(n+1)) / ((S/h)^(n/(n+1)) (1 + x v))`, bounded on `[0, 1]`.
fn compression_time(x: f64, n: f64) -> f64 {
    let p = n + 1.0;
    let c = p.powf(1.0 / p);
    let integrand = |s: f64| {
        let h = s.powf(p);
        c / (s_over_h(x, h).powf(n / p) * (1.0 + x * (1.0 - h)))
    };
    integrate(integrand, 0.0, 1.0)
}

/// Time from maximum compression to separation, `∫_{-e}^0 dv/(d^n (1 + x v))`.
fn restitution_time(x: f64, n: f64, state: HuntCrossleyState) -> f64 {
    if x < 1.0 { restitution_time_small_x(x, n, state) } else { restitution_time_large_x(x, n, state) }
}

/// `x < 1`: with `k = v + e = e s^(n+1)` and `z = x k/q`, `q = 1 - e x`:
/// `S = k g`, `g = (e - k phi2(z)/q)/q` (exact at `v = -e`, cancellation at most ~3x for `x < 1`), and the
/// integrand `(n+1)^(1/(n+1)) e^(1/(n+1)) / (g^(n/(n+1)) (q + x k))`.
fn restitution_time_small_x(x: f64, n: f64, state: HuntCrossleyState) -> f64 {
    let HuntCrossleyState { e, q, .. } = state;
    let p = n + 1.0;
    let c = (p * e).powf(1.0 / p);
    let integrand = |s: f64| {
        let k = e * s.powf(p);
        let g = (e - k * phi2(x * k / q) / q) / q;
        c / (g.powf(n / p) * (q + x * k))
    };
    integrate(integrand, 0.0, 1.0)
}

/// `x >= 1`: with `W = 1 + x v ∈ [q, 1]` and `lambda = ln(W/q) ∈ [0, Λ]`, `Λ = -ln q`:
/// `dt = dlambda/(x d^n)`, `x² S = lambda - (W - q) = lambda g`, `g = 1 - q (e^lambda - 1)/lambda`;
/// with `lambda = Λ s^(n+1)` the integrand is `((n+1) Λ)^(1/(n+1)) x^((n-1)/(n+1)) g^(-n/(n+1))`.
/// Works for any large `x` (`q` may underflow; `W = exp(ln q + lambda)` is used).
fn restitution_time_large_x(x: f64, n: f64, state: HuntCrossleyState) -> f64 {
    let HuntCrossleyState { q, ln_q, .. } = state;
    let p = n + 1.0;
    let big_lambda = -ln_q;
    let c = (p * big_lambda).powf(1.0 / p) * x.powf((n - 1.0) / p);
    let integrand = |s: f64| {
        let lambda = big_lambda * s.powf(p);
        // (W - q)/lambda = q (e^lambda - 1)/lambda; for lambda >= 1 as e^(ln q + lambda) - q, which stays exact
        // when q underflows (the subtraction then loses at most a factor 1.6).
        let w_minus_q_over_lambda =
            if lambda < 1.0 { q * exprel(lambda) } else { ((ln_q + lambda).exp() - q) / lambda };
        c / (1.0 - w_minus_q_over_lambda).powf(n / p)
    };
    integrate(integrand, 0.0, 1.0)
}

/// Peak compressive force: `F(v) = d(v)^n (1 + x v)` is largest where `dF/dt = 0`, i.e. `x d^(n+1) = n v`,
/// a single root in `(0, 1)` since `rho(v) = (n+1) x S(v) - n v` decreases from `rho(0) > 0` to `rho(1) = -n`.
/// Returns `(v at the peak, Fmax)`; for `x = 0` the peak is at maximum compression (`v = 0`).
fn peak_force(x: f64, n: f64) -> (f64, f64) {
    let p = n + 1.0;
    let s_of_v = |v: f64| {
        let h = 1.0 - v;
        h * s_over_h(x, h)
    };
    let v = if x == 0.0 { 0.0 } else { bisect(|v| p * x * s_of_v(v) - n * v, 0.0, 1.0) };
    (v, (p * s_of_v(v)).powf(n / p) * (1.0 + x * v))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rel(a: f64, b: f64) -> f64 {
        ((a - b) / b).abs()
    }

    /// The quadrature table of docs/references.md#the-hunt-crossley-family (checked against a tight ODE solve to
    /// 1e-12):
    /// x, n, e, dmax/L, t0/T, tc/T, Fmax/F0.
    const TABLE: [[f64; 7]; 5] = [
        [0.5, 1.5, 0.7484349315974, 0.9777703257171, 1.505190262472, 3.338252755937, 1.03820817965],
        [2.0, 1.5, 0.410719686061, 0.7949076199716, 1.33112133457, 3.78025803753, 1.10425499427],
        [0.5, 1.0, 0.7484349315974, 0.8696431079096, 1.437445184309, 3.166389384992, 0.945050174739],
        [1.0, 2.2, 0.59362426004, 0.9943173787563, 1.468630256523, 3.613729878934, 1.18053806176],
        [10.0, 1.5, 0.09998162475294, 0.5146945181523, 1.026446744025, 6.458113911715, 1.63632476647],
    ];

    #[test]
    fn quadratures_match_the_exact_hunt_crossley_table() {
        for [x, n, e, dmax, t0, tc, fmax] in TABLE {
            let r = hysteresis_contact(x, n);
            let checks = [
                ("e", r.restitution, e),
                ("dmax", r.max_penetration, dmax),
                ("t0", r.max_compression_time, t0),
                ("tc", r.duration, tc),
                ("Fmax", r.max_force, fmax),
            ];
            for (name, got, want) in checks {
                assert!(rel(got, want) < 1e-10, "x = {x}, n = {n}, {name}: {got} vs {want}");
            }
        }
    }

    #[test]
    fn elastic_limit_matches_the_closed_form() {
        // The quadrature at x = 0 against Hertz's Beta-function closed form (docs/references.md).
        for n in [0.5, 1.0, 1.5, 2.2, 4.0] {
            let q = by_quadrature(0.0, n);
            let h = hertz_elastic(n);
            assert!(rel(q.max_penetration, h.max_penetration) < 1e-15, "n = {n}");
            assert!(rel(q.max_compression_time, h.max_compression_time) < 1e-13, "n = {n}");
            assert!(rel(q.duration, h.duration) < 1e-13, "n = {n}");
            assert!(rel(q.max_force, h.max_force) < 1e-15, "n = {n}");
        }
        // Tiny damping: continuous with the elastic values.
        let a = hysteresis_contact(1e-9, 1.5);
        let h = hertz_elastic(1.5);
        assert!(rel(a.duration, h.duration) < 1e-8);
        assert!(rel(a.max_penetration, h.max_penetration) < 1e-8);
    }

    #[test]
    fn both_restitution_forms_agree_at_x_one() {
        // The two parametrisations of the restitution phase are exact; they must agree where both are accurate.
        for x in [0.8, 1.0, 1.3] {
            let state = HuntCrossleyState::new(x);
            let a = restitution_time_small_x(x, 1.5, state);
            let b = restitution_time_large_x(x, 1.5, state);
            assert!(rel(a, b) < 1e-13, "x = {x}: {a} vs {b}");
        }
    }

    #[test]
    fn force_peaks_before_maximum_compression() {
        // docs/references.md: Hunt–Crossley x = 0.5 (n = 3/2) peaks while d' = 0.284 v0.
        let (v, _) = peak_force(0.5, 1.5);
        assert!((v - 0.284).abs() < 5e-4, "{v}");
    }

    #[test]
    fn large_damping_is_finite() {
        // Including x ~ 700-750, where q = 1 - e x underflows, and extreme exponents.
        for (x, n) in [(100.0, 1.5), (1e3, 1.5), (1e6, 1.5), (700.0, 50.0), (745.0, 0.01), (1e300, 2.0)] {
            let r = hysteresis_contact(x, n);
            assert!(r.duration.is_finite() && r.duration > r.max_compression_time, "x = {x}, n = {n}: {r:?}");
            assert!(r.max_force.is_finite() && r.max_penetration > 0.0, "x = {x}, n = {n}");
        }
    }

    /// RK4 on `d'' = -d^n (1 + x d')` until `d` returns to 0: `(tc, e)`, an independent check of the quadrature.
    fn rk4_contact(x: f64, n: f64, dt: f64) -> (f64, f64) {
        let (tc, rate) = super::super::numerics::rk4_until(|d, v| -d.max(0.0).powf(n) * (1.0 + x * v), |d, _| d, dt);
        (tc, -rate)
    }

    #[test]
    fn large_damping_against_an_ode_solve() {
        // x = 100 (outside docs/references.md's table; q = 1 - e x ~ 4e-42): RK4 with dt = 5e-4 is converged to ~1e-9.
        let (tc, e) = rk4_contact(100.0, 1.5, 5e-4);
        let r = hysteresis_contact(100.0, 1.5);
        assert!(rel(r.duration, tc) < 1e-8, "{} vs {tc}", r.duration);
        assert!(rel(r.restitution, e) < 1e-10);
    }

    /// The times to the last digits, against an extended-precision integration of the contact (mpmath, 30 digits:
    /// its Taylor ODE solver `odefun` for `w' = ((n+1)/2) v, v' = -w (1 + x v)`, maximum compression and
    /// separation by `findroot`, `t = ∫ w^(-(n-1)/(n+1)) dτ` by tanh-sinh `quad` with breakpoints towards both
    /// ends). The error floor of the fast path is measured against these references, so they must hold to about
    /// an ulp: summed plainly, the quadrature's few hundred terms left them 3 to 7e-16 off.
    #[test]
    // (The digits as mpmath printed them; the compiler rounds them to the nearest double.)
    #[allow(clippy::excessive_precision)]
    fn times_to_the_last_digits() {
        let cases = [
            (10.0, 2.2, 1.155670500179849879, 7.8650576269360211252),
            (10.0, 1.5, 1.0264467440245183048, 6.4581139117148244698),
            (2.0, 2.2, 1.3929272879069162435, 4.0599930393251612243),
            (0.5, 1.5, 1.5051902624721971387, 3.3382527559374332991),
        ];
        for (x, n, t0, tc) in cases {
            let r = hysteresis_contact(x, n);
            assert!(rel(r.max_compression_time, t0) < 3e-16, "x = {x}, n = {n}: t0 {} vs {t0}", r.max_compression_time);
            assert!(rel(r.duration, tc) < 3e-16, "x = {x}, n = {n}: tc {} vs {tc}", r.duration);
        }
    }

    #[test]
    fn invalid_input() {
        assert!(hysteresis_contact(-0.1, 1.5).duration.is_nan());
        assert!(hysteresis_contact(0.5, 0.0).duration.is_nan());
        assert!(hysteresis_contact(f64::NAN, 1.5).restitution.is_nan());
        assert!(hysteresis_contact(0.5, f64::INFINITY).max_force.is_nan());
    }
}
