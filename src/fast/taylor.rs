//! Generic Taylor-series tools: polynomial evaluation, re-expansion about another point, powers of a series, the
//! order and step-size rules, and root location on a step's polynomial.
//!
//! A step's solution is a truncated Taylor series `c_0 + c_1 σ + … + c_K σ^K` in the offset `σ` from the step's
//! start. Everything here works on such coefficient slices; nothing allocates.

/// Highest Taylor order the stepper uses (the coefficient arrays hold `MAX_ORDER + 1` numbers).
pub const MAX_ORDER: usize = 30;

/// The coefficients of one component over one step, `c[k]` multiplying `σ^k`.
pub type Coefficients = [f64; MAX_ORDER + 1];

/// `1/k` for `k = 0..=2 MAX_ORDER + 1` (entry 0 unused): the recursions divide by `k` once per coefficient.
pub const INVERSE: [f64; 2 * MAX_ORDER + 2] = {
    let mut table = [0.0; 2 * MAX_ORDER + 2];
    let mut k = 1;
    while k < 2 * MAX_ORDER + 2 {
        table[k] = 1.0 / k as f64;
        k += 1;
    }
    table
};

/// Value of the polynomial `c` at `sigma` (Horner).
#[inline]
pub fn value(c: &[f64], sigma: f64) -> f64 {
    c.iter().rev().fold(0.0, |acc, &ck| acc * sigma + ck)
}

/// Value and first derivative of the polynomial `c` at `sigma`.
#[inline]
pub fn value_and_slope(c: &[f64], sigma: f64) -> (f64, f64) {
    let mut value = 0.0;
    let mut slope = 0.0;
    for &ck in c.iter().rev() {
        slope = slope * sigma + value;
        value = value * sigma + ck;
    }
    (value, slope)
}

/// Re-expands the polynomial `c` (in `σ`) about `sigma`: on return `c[k]` multiplies `(σ - sigma)^k`
/// (repeated synthetic division, exact up to rounding).
pub fn shift(c: &mut [f64], sigma: f64) {
    let degree = c.len().saturating_sub(1);
    for start in 0..degree {
        for k in (start..degree).rev() {
            c[k] += sigma * c[k + 1];
        }
    }
}

/// The Taylor order used for a local tolerance `eps` (relative, per step).
///
/// A step of size `h ≈ ρ eps^(1/(K+1))` (ρ the radius of convergence) costs `O(K²)` for the products of the
/// recursion; the number of steps falls like `eps^(-1/(K+1))`. The cost `K² eps^(-1/(K+1))` is least near
/// `K ≈ ln(1/eps)/2`; a few more orders pay for the fixed work of a step (events, quadrature).
pub fn order_for(eps: f64) -> usize {
    let wanted = (0.5 * (1.0 / eps).ln()).ceil() as usize + ORDER_MARGIN;
    wanted.clamp(MIN_ORDER, MAX_ORDER)
}

/// Orders added to `ln(1/eps)/2` (see [`order_for`]).
const ORDER_MARGIN: usize = 2;
/// Lowest order used, whatever the tolerance.
const MIN_ORDER: usize = 8;

/// Step size from the last two coefficients of the step's series.
///
/// `last` and `before_last` are the sizes of the coefficients of orders `order` and `order - 1`, relative to the
/// size of the state. Each gives an estimate of the radius of convergence, `ρ_k = |c_k|^(-1/k)`; with the smaller,
/// the first omitted term `(h/ρ)^(order+1)` is `eps` at `h = ρ eps^(1/(order+1))`. Returns `f64::INFINITY` when
/// both coefficients vanish (a polynomial solution: any step is exact).
pub fn step_size(before_last: f64, last: f64, order: usize, eps: f64) -> f64 {
    let radius = |size: f64, k: usize| if size > 0.0 { size.powf(-1.0 / k as f64) } else { f64::INFINITY };
    let rho = radius(before_last, order - 1).min(radius(last, order));
    STEP_SAFETY * rho * eps.powf(1.0 / (order + 1) as f64)
}

/// Factor applied to the step of [`step_size`] (1: the first omitted term equals the tolerance).
const STEP_SAFETY: f64 = 1.0;

/// Taylor coefficients of `q^alpha` from those of `q` (`q[0] > 0`), written to `out[from..to]`; `out[..from]`
/// must already hold the lower coefficients (`out[0] = q[0]^alpha`).
///
/// From `q f' = alpha q' f`: `f_k = (1/(k q_0)) Σ_{j=1}^{min(k, deg q)} ((alpha + 1) j - k) q_j f_{k-j}`.
/// The coefficients of `q` beyond its slice are zero (a polynomial), so the series may be continued to any
/// length at `O(deg q)` per coefficient.
pub fn power_series(q: &[f64], alpha: f64, out: &mut [f64], from: usize, to: usize) {
    let inverse_q0 = 1.0 / q[0];
    let degree = q.len() - 1;
    for k in from.max(1)..to {
        let top = k.min(degree);
        let kf = k as f64;
        let mut sum = 0.0;
        for j in 1..=top {
            sum += ((alpha + 1.0) * j as f64 - kf) * q[j] * out[k - j];
        }
        out[k] = sum * inverse_q0 / kf;
    }
}

/// The root of `f` in `[lo, hi]`, where `f(lo)` and `f(hi)` have opposite signs (or `f(hi) = 0`).
///
/// `f` returns its value and derivative. Newton's method, safeguarded by the bracket (a step that leaves it is
/// replaced by bisection), started from the secant point; it stops when the bracket or the Newton step is down to
/// rounding. Converges quadratically on a step's polynomial, where the root is simple.
pub fn root(f: impl Fn(f64) -> (f64, f64), mut lo: f64, mut hi: f64, f_lo: f64, f_hi: f64) -> f64 {
    if f_hi == 0.0 {
        return hi;
    }
    if f_lo == 0.0 {
        return lo;
    }
    let rising = f_hi > f_lo;
    let mut x = lo + (hi - lo) * (f_lo / (f_lo - f_hi));
    if !(x > lo && x < hi) {
        x = 0.5 * (lo + hi);
    }
    for _ in 0..100 {
        let (fx, slope) = f(x);
        if fx == 0.0 {
            return x;
        }
        if (fx > 0.0) == rising {
            hi = x;
        } else {
            lo = x;
        }
        let newton = x - fx / slope;
        let small = 2.0 * f64::EPSILON * x.abs().max(f64::MIN_POSITIVE);
        if (newton - x).abs() <= small {
            // Converged: the Newton correction is down to rounding.
            return newton.clamp(lo, hi);
        }
        let next = if newton > lo && newton < hi { newton } else { 0.5 * (lo + hi) };
        if hi - lo <= small {
            return next;
        }
        x = next;
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn horner_value_and_slope() {
        // 1 + 2σ + 3σ² at σ = 2: 17, slope 2 + 6σ = 14.
        let c = [1.0, 2.0, 3.0];
        assert_eq!(value(&c, 2.0), 17.0);
        assert_eq!(value_and_slope(&c, 2.0), (17.0, 14.0));
    }

    #[test]
    fn shift_re_expands() {
        // (σ)³ about σ = 1: (s + 1)³ = 1 + 3s + 3s² + s³.
        let mut c = [0.0, 0.0, 0.0, 1.0];
        shift(&mut c, 1.0);
        assert_eq!(c, [1.0, 3.0, 3.0, 1.0]);
    }

    #[test]
    fn power_series_is_the_binomial_series() {
        // (1 + σ)^alpha = Σ binom(alpha, k) σ^k.
        let alpha = -0.3;
        let mut out = [0.0; 12];
        out[0] = 1.0;
        power_series(&[1.0, 1.0], alpha, &mut out, 1, 12);
        let mut binomial = 1.0;
        for (k, &got) in out.iter().enumerate() {
            assert!((got - binomial).abs() <= 1e-15 * binomial.abs().max(1e-300), "k = {k}: {got} vs {binomial}");
            binomial *= (alpha - k as f64) / (k as f64 + 1.0);
        }
    }

    #[test]
    fn root_finds_cos_zero() {
        let f = |x: f64| (x.cos(), -x.sin());
        let r = root(f, 0.0, 3.0, 1.0, 3.0_f64.cos());
        assert!((r - std::f64::consts::FRAC_PI_2).abs() <= 4e-16, "{r:e}");
    }

    #[test]
    fn order_grows_with_accuracy() {
        assert!(order_for(1e-6) < order_for(1e-10));
        assert!(order_for(1e-10) < order_for(1e-16));
        assert!(order_for(1e-30) <= MAX_ORDER);
    }
}
