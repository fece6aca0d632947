//! Generic Taylor-series tools: polynomial evaluation, re-expansion about another point, powers of a series, the
//! order and step-size rules, and root location on a step's polynomial.
//!
//! A step's solution is a truncated Taylor series `c_0 + c_1 σ + … + c_K σ^K` in the offset `σ` from the step's
//! start. Everything here works on such coefficient slices; nothing allocates.

/// Highest Taylor order the stepper uses (the coefficient arrays hold `MAX_ORDER + 1` numbers).
pub const MAX_ORDER: usize = crate::integrate::MAX_TAYLOR_ORDER;

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

/// Whether the build targets a processor with fused multiply-add instructions (x86-64 with FMA — the project's
/// `.cargo/config.toml` builds for the machine that builds — and every aarch64). Without them `f64::mul_add` is a
/// slow library call.
pub const HARDWARE_FMA: bool = cfg!(any(target_feature = "fma", target_arch = "aarch64"));

/// `a b + c`: fused, with one rounding, where the processor has the instruction ([`HARDWARE_FMA`]), else a product
/// and a sum. Horner's rule and the Cauchy sums are chains of these: fused, each link waits for one instruction
/// instead of two.
#[inline(always)]
pub fn mul_add(a: f64, b: f64, c: f64) -> f64 {
    if HARDWARE_FMA { a.mul_add(b, c) } else { a * b + c }
}

/// Value of the polynomial `c` at `sigma` (Horner).
#[inline]
pub fn value(c: &[f64], sigma: f64) -> f64 {
    c.iter().rev().fold(0.0, |acc, &ck| mul_add(acc, sigma, ck))
}

/// Values of the polynomial `c` at `N` points at once (independent Horner chains side by side: the latency of one).
#[inline(always)]
pub fn values<const N: usize>(c: &[f64], at: [f64; N]) -> [f64; N] {
    let mut result = [0.0; N];
    for &ck in c.iter().rev() {
        for (r, &x) in result.iter_mut().zip(&at) {
            *r = mul_add(*r, x, ck);
        }
    }
    result
}

/// Values of the polynomial `c` at `N` points at once, each as `E(x²) + x O(x²)` from its even and odd
/// coefficients: two independent Horner chains of half the length a point, so that the last value arrives after
/// about half the latency of [`values`] (for the quadrature rules, where nothing else overlaps the chains).
#[inline(always)]
pub fn values_split<const N: usize>(c: &[f64], at: [f64; N]) -> [f64; N] {
    let squares = at.map(|x| x * x);
    let (pairs, top) = c.as_chunks::<2>();
    let mut even = [top.first().copied().unwrap_or(0.0); N];
    let mut odd = [0.0; N];
    for pair in pairs.iter().rev() {
        for i in 0..N {
            even[i] = mul_add(even[i], squares[i], pair[0]);
            odd[i] = mul_add(odd[i], squares[i], pair[1]);
        }
    }
    let mut result = [0.0; N];
    for i in 0..N {
        result[i] = mul_add(at[i], odd[i], even[i]);
    }
    result
}

/// Value and first derivative of the polynomial `c` at `sigma`.
#[inline]
pub fn value_and_slope(c: &[f64], sigma: f64) -> (f64, f64) {
    let mut value = 0.0;
    let mut slope = 0.0;
    for &ck in c.iter().rev() {
        slope = mul_add(slope, sigma, value);
        value = mul_add(value, sigma, ck);
    }
    (value, slope)
}

/// Re-expands the polynomial `c` (in `σ`) about `sigma`: on return `c[k]` multiplies `(σ - sigma)^k`
/// (repeated synthetic division, exact up to rounding).
#[cfg(test)]
pub fn shift(c: &mut [f64], sigma: f64) {
    let degree = c.len().saturating_sub(1);
    for start in 0..degree {
        for k in (start..degree).rev() {
            c[k] += sigma * c[k + 1];
        }
    }
}

/// The Taylor order used for a local tolerance `eps` (the rule is the stepper's: [`crate::integrate::taylor_order`]).
pub use crate::integrate::taylor_order as order_for;

/// Step size from the last two coefficients of the step's series.
///
/// `last` and `before_last` are the sizes of the coefficients of orders `order` and `order - 1`, relative to the
/// size of the state. Each gives an estimate of the radius of convergence, `ρ_k = |c_k|^(-1/k)`; with the smaller,
/// the first omitted term `(h/ρ)^(order+1)` is `eps` at `h = ρ eps^(1/(order+1))`. Returns `f64::INFINITY` when
/// both coefficients vanish (a polynomial solution: any step is exact).
///
/// `eps_root` is `eps^(1/(order+1))`. The roots are taken in logarithms with [`rough_log2`] and [`rough_exp2`]:
/// a step size needs no more than 4 digits, and this runs once per step.
#[inline]
pub fn step_size(before_last: f64, last: f64, order: usize, eps_root: f64) -> f64 {
    debug_assert!(order >= 2);
    let log_radius = |size: f64, k: usize| if size > 0.0 { -rough_log2(size) * INVERSE[k] } else { f64::INFINITY };
    let log_rho = log_radius(before_last, order - 1).min(log_radius(last, order));
    if log_rho == f64::INFINITY {
        return f64::INFINITY;
    }
    STEP_SAFETY * eps_root * rough_exp2(log_rho.min(1000.0))
}

/// `log2(x)` for finite `x > 0`, to 7.3e-4 absolute: the exponent from the bits, and for the mantissa
/// `m = 1 + f ∈ [1, 2)` a cubic in `f` (no division: this sits on every step's path). A step size divides the
/// logarithm by the order (at least [`MIN_ORDER`] - 1 = 7), so the radius comes out to 1e-4 relative: with
/// [`rough_exp2`]'s error the step's truncation `(h/ρ)^(K+1)` moves by under 0.4 %.
///
/// Without recursion (a subnormal is scaled into the normal range in place), so that it inlines: the step size's
/// two logarithms then overlap.
#[inline(always)]
pub fn rough_log2(x: f64) -> f64 {
    debug_assert!(x > 0.0 && x.is_finite(), "rough_log2 of {x}");
    // Subnormal: scale into the normal range first.
    let (x, offset) = if x < f64::MIN_POSITIVE { (x * SUBNORMAL_SCALE, -64.0) } else { (x, 0.0) };
    let bits = x.to_bits();
    let exponent = ((bits >> 52) & 0x7ff) as i64 - 1023;
    let m = f64::from_bits((bits & 0x000f_ffff_ffff_ffff) | 0x3ff0_0000_0000_0000);
    let f = m - 1.0;
    let log2_m = mul_add(mul_add(mul_add(LOG2_FIT[3], f, LOG2_FIT[2]), f, LOG2_FIT[1]), f, LOG2_FIT[0]);
    (exponent as f64 + offset) + log2_m
}

/// `2^64`, which brings every positive subnormal into the normal range.
const SUBNORMAL_SCALE: f64 = 18_446_744_073_709_551_616.0;

/// `log2(1 + f) ≈ Σ LOG2_FIT[j] f^j` on `[0, 1]`: the least-squares cubic at 400 Chebyshev points, whose error
/// nearly equioscillates (largest 7.25e-4, checked against `f64::log2` in the tests).
const LOG2_FIT: [f64; 4] = [7.252_740_07e-4, 1.417_299_45, -0.572_920_597, 0.155_445_855];

/// `2^y` for `|y| <= 1000`, to 1.1e-4 relative: `2^i` from the bits and a cubic for `2^f`, `f ∈ [0, 1)` the
/// fraction.
#[inline(always)]
pub fn rough_exp2(y: f64) -> f64 {
    let whole = y.floor();
    let f = y - whole;
    let fraction = mul_add(mul_add(mul_add(EXP2_FIT[3], f, EXP2_FIT[2]), f, EXP2_FIT[1]), f, EXP2_FIT[0]);
    // 2^whole from the biased exponent in the bits (normal numbers: whole in -1022..=1023; the callers' |y| <= 1000).
    let whole = whole.clamp(-1022.0, 1023.0);
    fraction * f64::from_bits(((whole as i64 + 1023) as u64) << 52)
}

/// `2^f ≈ Σ EXP2_FIT[j] f^j` on `[0, 1]`: the least-squares cubic at 400 Chebyshev points (of the absolute error;
/// its largest relative error, the one that matters to [`rough_exp2`], is 1.04e-4, checked against `f64::exp2` in
/// the tests).
const EXP2_FIT: [f64; 4] = [0.999_896_69, 0.696_390_55, 0.224_516_34, 0.079_085_7];

/// `Σ a_i b_i` over two slices of equal length, in four interleaved sums (one vector of fused multiply-adds where
/// the processor has them), then the sums added pairwise.
#[inline(always)]
pub fn dot(a: &[f64], b: &[f64]) -> f64 {
    debug_assert_eq!(a.len(), b.len());
    let mut sums = [0.0; 4];
    let (a_chunks, a_tail) = a.as_chunks::<4>();
    let (b_chunks, b_tail) = b.as_chunks::<4>();
    for (x, y) in a_chunks.iter().zip(b_chunks) {
        for lane in 0..4 {
            sums[lane] = mul_add(x[lane], y[lane], sums[lane]);
        }
    }
    let tail = a_tail.iter().zip(b_tail).fold(0.0, |acc, (&x, &y)| mul_add(x, y, acc));
    ((sums[0] + sums[1]) + (sums[2] + sums[3])) + tail
}

/// Factor applied to the step of [`step_size`] (1: the first omitted term equals the tolerance).
const STEP_SAFETY: f64 = 1.0;

/// The first fall of a function through zero on `(from, to]`, from its value `f_from > 0` at `from`: it is
/// sampled (`values`, at two points at once) at the middle and the end, and the root located ([`root_within`],
/// with `newton` giving value and slope) in the first half that ends at a value `<= 0`. `None` if neither sample
/// is `<= 0`.
///
/// Sampling inside the step keeps a function that falls and rises again within one step from being missed:
/// with the order rule of [`order_for`] a step stays below about 0.75 of the fastest half-period of these
/// contacts (`h ≈ K eps^(1/(K+1))/(e ω) < 2.4/ω`, the elastic oscillation `π/ω`), so two samples leave a factor 2.
pub fn first_fall(
    values: impl Fn([f64; 2]) -> [f64; 2],
    newton: impl Fn(f64) -> (f64, f64),
    from: f64,
    to: f64,
    f_from: f64,
) -> Option<f64> {
    let middle = from + 0.5 * (to - from);
    let [f_middle, f_to] = values([middle, to]);
    fall_in_halves(newton, [from, middle, to], [f_from, f_middle, f_to], 0.0)
}

/// The first fall through zero among the samples `f` at the ascending points `at` (`f[0] > 0`), located to
/// `precision` by [`root_within`]; `None` if no sample is `<= 0`.
pub fn fall_in_halves(newton: impl Fn(f64) -> (f64, f64), at: [f64; 3], f: [f64; 3], precision: f64) -> Option<f64> {
    if f[1] <= 0.0 {
        return Some(root_within(&newton, at[0], at[1], f[0], f[1], precision));
    }
    if f[2] <= 0.0 {
        return Some(root_within(&newton, at[1], at[2], f[1], f[2], precision));
    }
    None
}

/// [`root_within`] to rounding.
#[cfg(test)]
pub fn root(f: impl Fn(f64) -> (f64, f64), lo: f64, hi: f64, f_lo: f64, f_hi: f64) -> f64 {
    root_within(f, lo, hi, f_lo, f_hi, 0.0)
}

/// The root of `f` in `[lo, hi]`, where `f(lo)` and `f(hi)` have opposite signs (or `f(hi) = 0`), to the relative
/// accuracy `precision` (rounding if smaller).
///
/// `f` returns its value and derivative. Newton's method, safeguarded by the bracket (a step that leaves it is
/// replaced by bisection), started from the secant point; it stops when the bracket or the Newton step is down to
/// the accuracy, or when the next Newton step would be: once converging quadratically, each correction is about
/// `C` times the square of the last, so after corrections `d_(i-1)`, `d_i` the next is about `d_i³/d_(i-1)²`.
/// Converges quadratically on a step's polynomial, where the root is simple.
pub fn root_within(
    f: impl Fn(f64) -> (f64, f64),
    mut lo: f64,
    mut hi: f64,
    f_lo: f64,
    f_hi: f64,
    precision: f64,
) -> f64 {
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
    let relative = precision.max(2.0 * f64::EPSILON);
    // The last Newton correction (0 before the first and after a bisection: no prediction from it).
    let mut previous = 0.0;
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
        let small = relative * x.abs().max(f64::MIN_POSITIVE);
        let correction = (newton - x).abs();
        if correction <= small || correction * correction * correction <= small * previous * previous {
            // Converged: the Newton correction, or the next one, is down to the accuracy.
            return newton.clamp(lo, hi);
        }
        let inside = newton > lo && newton < hi;
        let next = if inside { newton } else { 0.5 * (lo + hi) };
        if hi - lo <= small {
            return next;
        }
        previous = if inside { correction } else { 0.0 };
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
    fn root_finds_cos_zero() {
        let f = |x: f64| (x.cos(), -x.sin());
        let r = root(f, 0.0, 3.0, 1.0, 3.0_f64.cos());
        assert!((r - std::f64::consts::FRAC_PI_2).abs() <= 4e-16, "{r:e}");
    }

    #[test]
    fn rough_logarithm_and_power() {
        for x in [1e-300, 3e-20, 0.01, 0.7, 1.0, 1.5, 2.0, 1234.5, 1e200] {
            assert!((rough_log2(x) - x.log2()).abs() < 7.3e-4, "log2 {x}");
        }
        // The fits over dense grids of [1, 2) and [0, 1): within their stated 7.25e-4 and 1.04e-4.
        for i in 0..100_000 {
            let x = 1.0 + i as f64 / 100_000.0;
            assert!((rough_log2(x) - x.log2()).abs() < 7.26e-4, "log2 {x}");
            let y = -3.0 + i as f64 / 100_000.0;
            assert!((rough_exp2(y) / y.exp2() - 1.0).abs() < 1.05e-4, "exp2 {y}");
        }
        assert!((rough_log2(5e-320) - 5e-320_f64.log2()).abs() < 7.3e-4);
        for y in [-900.0, -3.7, -1.0, 0.0, 0.3, 1.0, 17.25, 900.0] {
            assert!((rough_exp2(y) / y.exp2() - 1.0).abs() < 1.05e-4, "exp2 {y}");
        }
    }

    #[test]
    fn first_fall_finds_the_first_of_two_crossings() {
        // cos on (0, 5]: falls through zero at pi/2, rises through 3 pi/2; the end value is positive.
        let f = |x: f64| (x.cos(), -x.sin());
        let cosines = |at: [f64; 2]| at.map(f64::cos);
        let r = first_fall(cosines, f, 0.0, 5.0, 1.0).expect("a fall");
        assert!((r - std::f64::consts::FRAC_PI_2).abs() <= 4e-16);
        assert_eq!(first_fall(cosines, f, 0.0, 1.0, 1.0), None);
    }

    /// The even–odd evaluation agrees with Horner's to a few ulps of the terms' sizes, for every coefficient count
    /// (odd and even) and points of both signs inside and at the radius of convergence.
    #[test]
    fn values_split_agree_with_horner() {
        let mut draw = crate::draw::Draw::new(3, 0);
        for len in 1..=MAX_ORDER + 1 {
            let c: Vec<f64> = (0..len).map(|k| draw.uniform(-1.0, 1.0) * 0.7f64.powi(k as i32)).collect();
            let at = [-1.4, -0.3, 0.0, 0.5, 1.0, 1.4, 0.01, -0.9];
            let got = values_split(&c, at);
            for (x, g) in at.into_iter().zip(got) {
                let want = value(&c, x);
                let scale: f64 = c.iter().enumerate().map(|(k, ck)| ck.abs() * x.abs().powi(k as i32)).sum();
                assert!((g - want).abs() <= 8.0 * f64::EPSILON * scale, "{len} coefficients at {x}: {g} vs {want}");
            }
        }
    }

    #[test]
    fn order_grows_with_accuracy() {
        assert!(order_for(1e-6) < order_for(1e-10));
        assert!(order_for(1e-10) < order_for(1e-16));
        assert!(order_for(1e-30) <= MAX_ORDER);
    }
}
