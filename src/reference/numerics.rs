//! Small, cancellation-free numerical building blocks shared by the reference solutions:
//! `u - ln(1+u)` and relatives, the Euler beta function, a tanh-sinh quadrature and a bisection.

use std::f64::consts::FRAC_PI_2;

/// `phi2(u) = (u - ln(1 + u)) / u²` for `u > -1`, accurate to a few ulp everywhere (value `1/2` at `u = 0`).
///
/// Near 0 it uses `ln(1+u) = 2 atanh(s)`, `s = u/(2+u)`, which gives
/// `phi2 = (1-s)/2 - (1-s)² s/2 · Σ_{j>=0} s^(2j)/(2j+3)` with no cancellation; elsewhere the direct form
/// loses at most a factor 5 in relative precision. Returns `+inf` at `u = -1` and NaN below.
pub(crate) fn phi2(u: f64) -> f64 {
    let s = u / (2.0 + u);
    if s.abs() <= 0.25 {
        let s2 = s * s;
        // 15 terms: the first omitted one is below 0.25^30 / 33 < 1e-19.
        let sum = (0..15).rev().fold(0.0, |acc, j| acc * s2 + 1.0 / f64::from(2 * j + 3));
        let one_minus_s = 1.0 - s;
        0.5 * one_minus_s - 0.5 * one_minus_s * one_minus_s * s * sum
    } else {
        (u - u.ln_1p()) / u / u
    }
}

/// `phi(u) = u - ln(1 + u)` (>= 0) for `u > -1`, accurate to a few ulp; `+inf` at `u = -1`.
pub(crate) fn phi(u: f64) -> f64 {
    if u.abs() <= 0.4 { u * u * phi2(u) } else { u - u.ln_1p() }
}

/// `(e^x - 1)/x`, with the value 1 at `x = 0`.
pub(crate) fn exprel(x: f64) -> f64 {
    if x == 0.0 { 1.0 } else { x.exp_m1() / x }
}

/// `sin(x)/x`, with the value 1 at `x = 0`.
pub(crate) fn sinc(x: f64) -> f64 {
    if x == 0.0 { 1.0 } else { x.sin() / x }
}

/// `(1 - e^(-x))/x`, with the value 1 at `x = 0`.
pub(crate) fn one_minus_exp_neg_rel(x: f64) -> f64 {
    if x == 0.0 { 1.0 } else { -(-x).exp_m1() / x }
}

/// Euler beta function `B(a, b) = Γ(a) Γ(b) / Γ(a + b)` for `a, b > 0` (NaN otherwise).
///
/// Uses `libm::tgamma` (relative error ~1e-15) while the gammas are representable, `libm::lgamma` beyond.
pub fn beta(a: f64, b: f64) -> f64 {
    if !(a > 0.0 && b > 0.0) {
        return f64::NAN;
    }
    let direct = libm::tgamma(a) * libm::tgamma(b) / libm::tgamma(a + b);
    if direct.is_finite() && direct > 0.0 && a + b < 170.0 {
        direct
    } else {
        (libm::lgamma(a) + libm::lgamma(b) - libm::lgamma(a + b)).exp()
    }
}

/// Tanh-sinh (double exponential) quadrature of `f` over `[a, b]`, to about 1e-15 relative.
///
/// Written for bounded integrands that are analytic inside the interval (callers remove endpoint singularities by a
/// change of variables first). Node offsets from each end are computed directly (as `1 - tanh u`), so no precision
/// is lost near the endpoints. `f` may be evaluated at the endpoints themselves.
pub(crate) fn integrate(f: impl Fn(f64) -> f64, a: f64, b: f64) -> f64 {
    const T_MAX: f64 = 3.5; // weights there are ~1e-21 of the central one
    const MIN_LEVEL: u32 = 3;
    const MAX_LEVEL: u32 = 11;
    const REL_TOL: f64 = 1e-14;
    let half = 0.5 * (b - a);
    if half == 0.0 {
        return 0.0;
    }
    // Weighted sum of f at the two nodes +-t (t > 0): offset from the ends half*(1 - tanh u), u = (pi/2) sinh t.
    let pair = |t: f64| {
        let u = FRAC_PI_2 * t.sinh();
        let cosh_u = u.cosh();
        let offset = half * (-u).exp() / cosh_u;
        let weight = FRAC_PI_2 * t.cosh() / (cosh_u * cosh_u);
        weight * (f(a + offset) + f(b - offset))
    };
    // The sum of a few hundred terms, compensated (Neumaier): plain summation leaves a relative error of about
    // sqrt(terms) ulps, a few times the integrand's own, which the error floor of the fast path would inherit.
    let mut sum = Compensated::new(FRAC_PI_2 * f(a + half));
    let mut k = 1;
    while f64::from(k) <= T_MAX {
        sum.add(pair(f64::from(k)));
        k += 1;
    }
    let mut estimate = half * sum.value();
    for level in 1..=MAX_LEVEL {
        let h = 0.5_f64.powi(level as i32);
        let mut j = 1;
        while f64::from(j) * h <= T_MAX {
            sum.add(pair(f64::from(j) * h));
            j += 2;
        }
        let next = half * h * sum.value();
        let change = (next - estimate).abs();
        estimate = next;
        if level >= MIN_LEVEL && change <= REL_TOL * next.abs() {
            break;
        }
    }
    estimate
}

/// Root of `f` on `(lo, hi)` by bisection to full double precision, for `f(lo) > 0` and `f(hi) <= 0`.
///
/// A NaN value counts as "not positive" (i.e. on the `hi` side). Never evaluates `f` at `lo` or `hi`.
pub(crate) fn bisect(f: impl Fn(f64) -> f64, mut lo: f64, mut hi: f64) -> f64 {
    for _ in 0..2200 {
        let mid = lo + 0.5 * (hi - lo);
        if mid <= lo || mid >= hi {
            break;
        }
        if f(mid) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    lo + 0.5 * (hi - lo)
}

/// A sum with Neumaier's compensation: the rounding of each addition is kept and added back at the end.
struct Compensated {
    sum: f64,
    carry: f64,
}

impl Compensated {
    fn new(first: f64) -> Self {
        Compensated { sum: first, carry: 0.0 }
    }

    fn add(&mut self, term: f64) {
        let next = self.sum + term;
        self.carry += if self.sum.abs() >= term.abs() { (self.sum - next) + term } else { (term - next) + self.sum };
        self.sum = next;
    }

    fn value(&self) -> f64 {
        self.sum + self.carry
    }
}

/// Test-only independent check: classical RK4 with step `dt` on d'' = `acceleration(d, d')` from d = 0, d' = 1,
/// until `event(d, d')` falls to zero after the start (located by linear interpolation in the step).
/// Returns the time and d' there.
#[cfg(test)]
pub fn rk4_until(acceleration: impl Fn(f64, f64) -> f64, event: impl Fn(f64, f64) -> f64, dt: f64) -> (f64, f64) {
    let f = |d: f64, v: f64| (v, acceleration(d, v));
    let (mut t, mut d, mut v) = (0.0, 0.0, 1.0);
    loop {
        let k1 = f(d, v);
        let k2 = f(d + 0.5 * dt * k1.0, v + 0.5 * dt * k1.1);
        let k3 = f(d + 0.5 * dt * k2.0, v + 0.5 * dt * k2.1);
        let k4 = f(d + dt * k3.0, v + dt * k3.1);
        let dn = d + dt / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0);
        let vn = v + dt / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1);
        let (g0, g1) = (event(d, v), event(dn, vn));
        if t > 0.0 && g1 <= 0.0 {
            let frac = g0 / (g0 - g1);
            return (t + frac * dt, v + frac * (vn - v));
        }
        t += dt;
        d = dn;
        v = vn;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn rel(a: f64, b: f64) -> f64 {
        ((a - b) / b).abs()
    }

    #[test]
    fn phi2_matches_taylor_and_direct_forms() {
        // Taylor series 1/2 - u/3 + u²/4 - u³/5 at tiny u.
        let u: f64 = 1e-4;
        let taylor = 0.5 - u / 3.0 + u * u / 4.0 - u.powi(3) / 5.0;
        assert!(rel(phi2(u), taylor) < 1e-15);
        assert!(rel(phi2(-u), 0.5 + u / 3.0 + u * u / 4.0 + u.powi(3) / 5.0) < 1e-15);
        assert_eq!(phi2(0.0), 0.5);
        // Large |u|: no cancellation in the direct form, compare with it.
        for u in [-0.9, -0.5, 0.8, 3.0, 100.0] {
            let direct: f64 = (u - f64::ln_1p(u)) / (u * u);
            assert!(rel(phi2(u), direct) < 1e-14, "u = {u}");
        }
        // Across the switch of branches (s = +-0.25 at u = 2/3 and -0.4).
        for u in [2.0 / 3.0, -0.4] {
            let lo = phi2(u * (1.0 - 1e-15));
            let hi = phi2(u * (1.0 + 1e-15));
            assert!(rel(lo, hi) < 1e-14, "u = {u}");
        }
        // Exact value ln 2 at u = -1/2: phi(-1/2) = -1/2 + ln 2, phi2 = 4 phi.
        assert!(rel(phi2(-0.5), 4.0 * (std::f64::consts::LN_2 - 0.5)) < 1e-15);
        assert!(rel(phi(1.0), 1.0 - std::f64::consts::LN_2) < 1e-15);
    }

    #[test]
    fn beta_known_values() {
        assert!(rel(beta(0.5, 0.5), PI) < 1e-14);
        assert!(rel(beta(2.0, 3.0), 1.0 / 12.0) < 1e-14);
        // B(1, b) = 1/b, also through the lgamma branch.
        assert!(rel(beta(1.0, 300.0), 1.0 / 300.0) < 1e-12);
        assert!(beta(-1.0, 2.0).is_nan());
    }

    #[test]
    fn quadrature_of_smooth_and_edge_peaked_integrands() {
        assert!(rel(integrate(|x| x.exp(), 0.0, 1.0), std::f64::consts::E - 1.0) < 1e-15);
        // ∫_0^1 sqrt(x) dx = 2/3 and ∫_0^1 x^(5/2) dx = 2/7 (bounded but non-analytic at an endpoint, as the
        // integrands after the s^(n+1) substitutions are).
        assert!(rel(integrate(f64::sqrt, 0.0, 1.0), 2.0 / 3.0) < 1e-15);
        assert!(rel(integrate(|x| x.powf(2.5), 0.0, 1.0), 2.0 / 7.0) < 1e-15);
        // ∫_0^pi sin = 2.
        assert!(rel(integrate(f64::sin, 0.0, PI), 2.0) < 1e-15);
    }

    #[test]
    fn bisect_finds_sqrt2() {
        let r = bisect(|x| 2.0 - x * x, 0.0, 2.0);
        assert!(rel(r, std::f64::consts::SQRT_2) < 3e-16);
    }
}
