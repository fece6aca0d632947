//! Gauss rules and the power they sum, for the fast path's integrals over a step or a phase.
//!
//! * Gauss–Legendre rules ([`gauss_legendre`]), and the node count an integrand analytic inside a Bernstein
//!   ellipse asks for ([`nodes_needed`]: the error of an `m`-node rule falls like `ρ^(-2m)`);
//! * Gauss–Jacobi rules for the weight `s^(-γ)` on `(0, 1)` ([`JacobiRules`]): the time's integrand `w^(-γ)` at a
//!   zero of `w`, `w = |σ - z| Q(σ)`, is `|σ - z|^(-γ)` times the smooth `Q^(-γ)`, so the singularity is
//!   integrated exactly by `m` evaluations of `Q^(-γ)`;
//! * the power itself, `x^(-γ)` ([`negative_power`]), branch-free so that a rule's nodes are taken in vector lanes.

use super::taylor::{self, rough_log2};
use std::sync::OnceLock;

/// Largest Gauss–Legendre rule kept.
pub const MAX_NODES: usize = 24;

/// One Gauss–Legendre rule on `[-1, 1]`: `nodes[..m]` (ascending) and `weights[..m]`.
struct Rule {
    nodes: [f64; MAX_NODES],
    weights: [f64; MAX_NODES],
}

/// The rules for `m = 1..=MAX_NODES` (entry 0 unused), each computed on its first use: an impact asks for a
/// few of them, and computing all 24 (300 Newton-polished roots) was a quarter of a one-impact run's fast-path
/// instructions.
static RULES: [OnceLock<Rule>; MAX_NODES + 1] = [const { OnceLock::new() }; MAX_NODES + 1];

/// The `m`-node Gauss–Legendre rule on `[-1, 1]` (`1 <= m <= MAX_NODES`): nodes ascending, and weights.
pub fn gauss_legendre(m: usize) -> (&'static [f64], &'static [f64]) {
    let rule = RULES[m].get_or_init(|| {
        let mut rule = Rule { nodes: [0.0; MAX_NODES], weights: [0.0; MAX_NODES] };
        legendre_rule(m, &mut rule.nodes[..m], &mut rule.weights[..m]);
        rule
    });
    (&rule.nodes[..m], &rule.weights[..m])
}

/// Legendre polynomial `P_m(x)` and its derivative, by the three-term recurrence.
fn legendre(m: usize, x: f64) -> (f64, f64) {
    let (mut p0, mut p1) = (1.0, x);
    for k in 2..=m {
        let kf = k as f64;
        let p2 = ((2.0 * kf - 1.0) * x * p1 - (kf - 1.0) * p0) / kf;
        p0 = p1;
        p1 = p2;
    }
    if m == 0 {
        return (1.0, 0.0);
    }
    // P_m'(x) = m (x P_m - P_{m-1}) / (x² - 1), never evaluated at x = ±1 (the nodes are interior).
    (p1, m as f64 * (x * p1 - p0) / (x * x - 1.0))
}

/// The `m`-node rule: Newton on `P_m` from Tricomi's estimate of each root, weights `2/((1 - x²) P_m'(x)²)`.
fn legendre_rule(m: usize, nodes: &mut [f64], weights: &mut [f64]) {
    let mf = m as f64;
    for i in 0..m {
        // Roots in descending order from the estimate cos(π (i + 3/4)/(m + 1/2)); stored ascending.
        let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (mf + 0.5)).cos();
        for _ in 0..100 {
            let (p, slope) = legendre(m, x);
            let dx = p / slope;
            x -= dx;
            if dx.abs() <= 1e-16 {
                break;
            }
        }
        let (_, slope) = legendre(m, x);
        nodes[m - 1 - i] = x;
        weights[m - 1 - i] = 2.0 / ((1.0 - x * x) * slope * slope);
    }
}

/// Gauss–Legendre nodes for an integrand analytic inside the Bernstein ellipse through a point at distance
/// `xi` (in half-interval units, from the interval's centre; `xi > 1`) on the real axis: the error of the
/// `m`-node rule is about `ρ^(-2m)`, `ρ = xi + sqrt(xi² - 1)`, so `m = (ln(1/eps) + margin)/(2 ln ρ)`;
/// `digits` is `ln(1/eps) + margin`, from [`node_digits`] (computed once per integration, not per piece).
/// `ln ρ` is taken by [`rough_log2`] (to 5.1e-4: a node count needs no more; the callers keep `ξ >= 2`, `ln ρ >= 1.3`).
pub fn nodes_needed(xi: f64, digits: f64) -> usize {
    if xi.is_infinite() {
        return 1;
    }
    let rho = xi + (xi * xi - 1.0).max(0.0).sqrt();
    let log_rho = if rho > 1.0 && rho <= f64::MAX { rough_log2(rho) * std::f64::consts::LN_2 } else { rho.ln() };
    let m = digits / (2.0 * log_rho);
    if m.is_finite() { (m.ceil() as usize).max(2) } else { usize::MAX }
}

/// `ln(1/eps)` plus the margin of [`nodes_needed`], for the local tolerance `eps`.
pub fn node_digits(eps: f64) -> f64 {
    (1.0 / eps).ln() + NODE_MARGIN
}

/// Added to `ln(1/eps)` in [`node_digits`]: the constant of the error bound (a branch point on the ellipse).
const NODE_MARGIN: f64 = 2.0;

/// `x^(-gamma)` for `x > 0` (normal, finite): `exp(-γ ln x)` with both functions written out (fdlibm's `ln`:
/// the exponent from the bits, `ln m = 2 atanh s` by its minimax polynomial for the mantissa `m ∈ [√½, √2)`;
/// `exp` reduced by `ln 2` to `|r| <= ln2/2` and summed by its Taylor polynomial of degree 13). Branch-free and
/// lane-wise, so that four nodes at once fill vector registers (libm's `exp` and `ln` were two thirds of a Gauss
/// rule's cost). Relative error a few ulp: that of `γ ln x`'s rounding, as with `powf`.
#[inline(always)]
pub fn negative_power(x: f64, gamma: f64) -> f64 {
    // ln x = k ln 2 + ln m: adding the offset carries a mantissa above √2 into the exponent.
    let bits = x.to_bits().wrapping_add(0x3ff0_0000_0000_0000 - SQRT_HALF_BITS);
    // k from the exponent field (0..=2047) through the mantissa of 2^52 (no integer conversion: vectorises).
    let k = f64::from_bits((bits >> 52) | TWO_52_BITS) - (TWO_52 + 1023.0);
    let m = f64::from_bits((bits & MANTISSA) + SQRT_HALF_BITS);
    let f = m - 1.0;
    let s = f / (2.0 + f);
    let z = s * s;
    let w = z * z;
    let t1 = w * (LG[1] + w * (LG[3] + w * LG[5]));
    let t2 = z * (LG[0] + w * (LG[2] + w * (LG[4] + w * LG[6])));
    let half_square = 0.5 * f * f;
    let ln = k * LN2_HI - ((half_square - (s * (half_square + t1 + t2) + k * LN2_LO)) - f);
    // exp(y) = 2^j exp(r), j = round(y/ln 2) (through the rounding of 1.5·2^52 + y/ln 2).
    let y = -gamma * ln;
    let shifted = y * std::f64::consts::LOG2_E + ROUNDER;
    let j = shifted - ROUNDER;
    let r = (y - j * LN2_HI) - j * LN2_LO;
    // The polynomial by Estrin's scheme (pairs, then pairs of pairs): 4 operations deep instead of 13.
    let c = &EXP_TAYLOR;
    let mul_add = taylor::mul_add;
    let (r2, pair) = (r * r, |i: usize| mul_add(c[i + 1], r, c[i]));
    let r4 = r2 * r2;
    let low = mul_add(mul_add(pair(6), r2, pair(4)), r4, mul_add(pair(2), r2, pair(0)));
    let high = mul_add(pair(12), r4, mul_add(pair(10), r2, pair(8)));
    let p = mul_add(high, r4 * r4, low);
    let scale = f64::from_bits((shifted.to_bits().wrapping_sub(ROUNDER.to_bits()).wrapping_add(1023)) << 52);
    p * scale
}

const SQRT_HALF_BITS: u64 = 0x3fe6_a09e_667f_3bcd;
const MANTISSA: u64 = 0x000f_ffff_ffff_ffff;
const TWO_52: f64 = 4_503_599_627_370_496.0;
const TWO_52_BITS: u64 = 0x4330_0000_0000_0000;
/// 1.5·2^52: adding it rounds to an integer kept in the low bits of the mantissa.
const ROUNDER: f64 = 6_755_399_441_055_744.0;
/// `ln 2` split so that `k LN2_HI` is exact for `|k| < 2^11` (fdlibm's `ln2_hi`, `ln2_lo`: 0x3fe62e42fee00000,
/// 0x3dea39ef35793c76, as their shortest decimals).
const LN2_HI: f64 = 6.931_471_803_691_238e-1;
const LN2_LO: f64 = 1.908_214_929_270_587_7e-10;
/// fdlibm's `Lg1..Lg7`: `ln m = 2s + s R(s²)`, `|R - (2s³/3 + …)/s| < 2^-58.45` on `|s| <= 0.1716`.
const LG: [f64; 7] = [
    6.666_666_666_666_735e-1,
    3.999_999_999_940_942e-1,
    2.857_142_874_366_239e-1,
    2.222_219_843_214_978_4e-1,
    1.818_357_216_161_805e-1,
    1.531_383_769_920_937_3e-1,
    1.479_819_860_511_658_6e-1,
];
/// `1/j!` for `j = 0..=13`: the degree-13 Taylor polynomial of `exp` on `|r| <= ln2/2` (remainder < 5e-18).
const EXP_TAYLOR: [f64; 14] = {
    let mut table = [1.0; 14];
    let mut j = 1;
    while j < 14 {
        table[j] = table[j - 1] / j as f64;
        j += 1;
    }
    table
};

/// Gauss–Jacobi rules for `∫_0^1 s^(-γ) f(s) ds` (the end of a step at a zero of `w`, where the time's integrand
/// is `s^(-γ)` times a smooth function): `nodes[m][..m]` ascending in `(0, 1)` and `weights[m][..m]`, computed on
/// first use for each `m` and kept while `γ` stays the same (a run of impacts of one law computes each rule once).
pub struct JacobiRules {
    gamma: f64,
    /// Bit `m` set: the `m`-node rule is computed.
    known: u32,
    nodes: [[f64; MAX_NODES]; MAX_NODES + 1],
    weights: [[f64; MAX_NODES]; MAX_NODES + 1],
}

impl Default for JacobiRules {
    fn default() -> Self {
        JacobiRules {
            gamma: f64::NAN,
            known: 0,
            nodes: [[0.0; MAX_NODES]; MAX_NODES + 1],
            weights: [[0.0; MAX_NODES]; MAX_NODES + 1],
        }
    }
}

impl JacobiRules {
    /// The `m`-node rule for the weight `s^(-gamma)` on `(0, 1)` (`gamma < 1`, `1 <= m <= MAX_NODES`).
    pub fn rule(&mut self, gamma: f64, m: usize) -> (&[f64], &[f64]) {
        if gamma.to_bits() != self.gamma.to_bits() {
            self.gamma = gamma;
            self.known = 0;
        }
        if self.known & (1 << m) == 0 {
            jacobi_rule(-gamma, &mut self.nodes[m][..m], &mut self.weights[m][..m]);
            self.known |= 1 << m;
        }
        (&self.nodes[m][..m], &self.weights[m][..m])
    }
}

/// The Gauss rule of the weight `s^beta` on `(0, 1)` (`beta > -1`) as in Golub and Welsch: the nodes are the
/// eigenvalues of the Jacobi matrix of the orthogonal polynomials' recurrence (`μ0 = ∫ s^beta = 1/(beta + 1)`),
/// polished by Newton; the weights from the Christoffel function. The shifted Jacobi
/// polynomials `P_k^(0, beta)(2s - 1)` have (Gautschi, *Orthogonal polynomials*, Table 1.1, mapped to `(0, 1)`)
/// `a_k = (1 + beta²/((2k + beta)(2k + beta + 2)))/2` and
/// `b_k = k² (k + beta)² / ((2k + beta)² (2k + beta + 1) (2k + beta - 1))`. Eigenvalues by the implicit QL
/// method on the tridiagonal matrix: `O(m²)`, no allocation.
fn jacobi_rule(beta: f64, nodes: &mut [f64], weights: &mut [f64]) {
    let m = nodes.len();
    // sqrt(b_k), k >= 1, and a_k (a_0 = (1 + beta/(beta + 2))/2: the general formula is 0/0 at beta = 0).
    let off = |k: usize| {
        let j = k as f64;
        let s = 2.0 * j + beta;
        (j * (j + beta) / s / ((s + 1.0) * (s - 1.0)).sqrt()).abs()
    };
    let diagonal = |k: usize| {
        let s = 2.0 * k as f64 + beta;
        if k == 0 { 0.5 * (1.0 + beta / (beta + 2.0)) } else { 0.5 * (1.0 + beta * beta / (s * (s + 2.0))) }
    };
    let mut d = [0.0; MAX_NODES];
    let mut e = [0.0; MAX_NODES];
    for k in 0..m {
        d[k] = diagonal(k);
        e[k] = off(k + 1);
    }
    symmetric_tridiagonal_ql(&mut d[..m], &mut e[..m]);
    // Each node polished by Newton on the orthonormal polynomial of degree m, and its weight from the
    // Christoffel function, 1/Σ_{k<m} p_k(s)² (accurate to the last digits for every node, small or large;
    // the eigenvectors' components would give the small weights to absolute accuracy only).
    let mu0 = 1.0 / (beta + 1.0);
    // (Σ_{k<m} p_k², p_m, p_m') at x, from p_0 = 1/sqrt(μ0) by sqrt(b_{k+1}) p_{k+1} = (x - a_k) p_k - sqrt(b_k) p_{k-1}.
    let evaluate = |x: f64| {
        let (mut previous, mut current) = (0.0, 1.0 / mu0.sqrt());
        let (mut previous_slope, mut slope) = (0.0, 0.0);
        let mut squares = 0.0;
        for k in 0..m {
            squares += current * current;
            let below = if k == 0 { 0.0 } else { off(k) };
            let next = ((x - diagonal(k)) * current - below * previous) / off(k + 1);
            let next_slope = ((x - diagonal(k)) * slope + current - below * previous_slope) / off(k + 1);
            (previous, current) = (current, next);
            (previous_slope, slope) = (slope, next_slope);
        }
        (squares, current, slope)
    };
    for x in d.iter_mut().take(m) {
        for _ in 0..2 {
            let (_, p, slope) = evaluate(*x);
            if slope != 0.0 {
                *x -= p / slope;
            }
        }
    }
    let mut sorted = [0.0; MAX_NODES];
    sorted[..m].copy_from_slice(&d[..m]);
    sorted[..m].sort_by(f64::total_cmp);
    for (i, &x) in sorted[..m].iter().enumerate() {
        nodes[i] = x;
        weights[i] = 1.0 / evaluate(x).0;
    }
}

/// Eigenvalues of the symmetric tridiagonal matrix with diagonal `d` and off-diagonal `e` (`e[i]` joins `i` and
/// `i + 1`; the last entry is scratch), by the QL method with implicit shifts (Numerical Recipes' `tqli`, without
/// the eigenvectors). On return `d` holds the eigenvalues, in no particular order.
fn symmetric_tridiagonal_ql(d: &mut [f64], e: &mut [f64]) {
    let n = d.len();
    if n == 0 {
        return;
    }
    e[n - 1] = 0.0;
    for l in 0..n {
        for _ in 0..60 {
            // The first negligible off-diagonal entry at or after l.
            let mut mm = l;
            while mm + 1 < n {
                let dd = d[mm].abs() + d[mm + 1].abs();
                if e[mm].abs() <= f64::EPSILON * dd {
                    break;
                }
                mm += 1;
            }
            if mm == l {
                break;
            }
            let mut g = (d[l + 1] - d[l]) / (2.0 * e[l]);
            let mut r = g.hypot(1.0);
            g = d[mm] - d[l] + e[l] / (g + r.copysign(g));
            let (mut s, mut c, mut p) = (1.0, 1.0, 0.0);
            let mut deflated = false;
            for i in (l..mm).rev() {
                let f = s * e[i];
                let b = c * e[i];
                r = f.hypot(g);
                e[i + 1] = r;
                if r == 0.0 {
                    d[i + 1] -= p;
                    e[mm] = 0.0;
                    deflated = true;
                    break;
                }
                s = f / r;
                c = g / r;
                g = d[i + 1] - p;
                r = (d[i] - g) * s + 2.0 * c * b;
                p = s * r;
                d[i + 1] = g + p;
                g = c * r - b;
            }
            if deflated {
                continue;
            }
            d[l] -= p;
            e[l] = g;
            e[mm] = 0.0;
        }
    }
}

/// `∫_a^b f` by composite Gauss–Legendre: `pieces` equal pieces of `m` nodes each (the tests' independent
/// quadrature of smooth integrands).
#[cfg(test)]
pub fn composite_gauss_legendre(f: impl Fn(f64) -> f64, a: f64, b: f64, pieces: usize, m: usize) -> f64 {
    let (nodes, weights) = gauss_legendre(m);
    let width = (b - a) / pieces as f64;
    (0..pieces)
        .map(|i| {
            let centre = a + width * (i as f64 + 0.5);
            nodes.iter().zip(weights).map(|(x, w)| 0.5 * width * w * f(centre + 0.5 * width * x)).sum::<f64>()
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gauss_legendre_small_rules_are_the_textbook_ones() {
        let (x, w) = gauss_legendre(2);
        let third = (1.0_f64 / 3.0).sqrt();
        assert!((x[0] + third).abs() < 1e-16 && (x[1] - third).abs() < 1e-16);
        assert!((w[0] - 1.0).abs() < 1e-15 && (w[1] - 1.0).abs() < 1e-15);
        let (x, w) = gauss_legendre(3);
        let root = 0.6_f64.sqrt();
        assert!((x[0] + root).abs() < 1e-16 && x[1].abs() < 1e-16 && (x[2] - root).abs() < 1e-16);
        assert!((w[0] - 5.0 / 9.0).abs() < 1e-15 && (w[1] - 8.0 / 9.0).abs() < 1e-15);
    }

    /// Golub–Welsch: the nodes are the eigenvalues of the Jacobi matrix of the Legendre recurrence
    /// (off-diagonal `k/sqrt(4k² - 1)`), the weights `2 v_0²` — an independent computation (nalgebra's
    /// symmetric eigensolver).
    #[test]
    fn gauss_legendre_agrees_with_golub_welsch() {
        for m in [5, 11, 17, MAX_NODES] {
            let jacobi = nalgebra::DMatrix::from_fn(m, m, |i, j| {
                let k = i.max(j) as f64;
                if i.abs_diff(j) == 1 { k / (4.0 * k * k - 1.0).sqrt() } else { 0.0 }
            });
            let eigen = jacobi.symmetric_eigen();
            let mut pairs: Vec<(f64, f64)> =
                (0..m).map(|i| (eigen.eigenvalues[i], 2.0 * eigen.eigenvectors[(0, i)].powi(2))).collect();
            pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
            let (nodes, weights) = gauss_legendre(m);
            for i in 0..m {
                assert!((nodes[i] - pairs[i].0).abs() < 1e-14, "m = {m}, node {i}");
                assert!((weights[i] - pairs[i].1).abs() < 1e-14, "m = {m}, weight {i}");
            }
        }
    }

    #[test]
    fn gauss_legendre_is_exact_to_degree_2m_minus_1() {
        for m in 1..=MAX_NODES {
            let (nodes, weights) = gauss_legendre(m);
            for degree in 0..2 * m {
                let got: f64 = nodes.iter().zip(weights).map(|(&x, &w)| w * x.powi(degree as i32)).sum();
                let exact = if degree % 2 == 1 { 0.0 } else { 2.0 / (degree as f64 + 1.0) };
                assert!((got - exact).abs() < 2e-15, "m = {m}, degree {degree}: {got} vs {exact}");
            }
        }
    }

    /// `negative_power` against libm's `powf` (correctly rounded to within an ulp or so) over many decades and
    /// exponents, including the laws' `γ = 1/5, 3/8` and negative `γ` (n < 1).
    #[test]
    fn negative_power_agrees_with_powf() {
        // The error, in ulp of the result: that of exp(y) for an exponent y = -γ ln x rounded to its own ulp, about
        // |y| ulp, plus a few.
        let mut worst: f64 = 0.0;
        for gamma in [0.2, 0.375, (2.2 - 1.0) / (2.2 + 1.0), 0.05, 0.6, 0.95, -0.3, -0.9, 1.0 / 3.0] {
            let mut x: f64 = 1e-12;
            while x < 1e6 {
                let exact = x.powf(-gamma);
                let ulps = (negative_power(x, gamma) / exact - 1.0).abs() / f64::EPSILON;
                worst = worst.max(ulps / (2.0 + (gamma * x.ln()).abs()));
                x *= 1.0137;
            }
        }
        assert!(worst < 1.0, "{worst}");
        for x in [1.0, 0.5, 2.0, std::f64::consts::FRAC_1_SQRT_2, std::f64::consts::SQRT_2, 3.0] {
            assert!((negative_power(x, 0.2) / x.powf(-0.2) - 1.0).abs() < 5e-16, "{x}");
        }
        assert_eq!(negative_power(1.0, 0.2), 1.0);
    }

    /// The Gauss–Jacobi rules integrate `s^(-γ) s^k` on `(0, 1)` exactly, `1/(k + 1 - γ)`, for every degree
    /// `k <= 2m - 1` (the property that defines them), for the laws' exponents and others.
    #[test]
    fn gauss_jacobi_is_exact_to_degree_2m_minus_1() {
        let mut rules = JacobiRules::default();
        for gamma in [0.2, 0.375, -0.3, 0.6, 0.9, 0.0] {
            for m in 1..=MAX_NODES {
                let (nodes, weights) = rules.rule(gamma, m);
                assert!(nodes.windows(2).all(|p| p[0] < p[1]) && nodes[0] > 0.0 && nodes[m - 1] < 1.0);
                for degree in 0..2 * m {
                    let got: f64 = nodes.iter().zip(weights).map(|(&s, &w)| w * s.powi(degree as i32)).sum();
                    let exact = 1.0 / (degree as f64 + 1.0 - gamma);
                    let error = (got / exact - 1.0).abs();
                    assert!(error < 1e-14, "γ = {gamma}, m = {m}, degree {degree}: {error:e}");
                }
            }
        }
    }

    /// At `γ = 0` the Jacobi rule is the Gauss–Legendre rule (Newton on the Legendre polynomial, another method),
    /// moved to `(0, 1)`.
    #[test]
    fn gauss_jacobi_without_weight_is_gauss_legendre() {
        let mut rules = JacobiRules::default();
        for m in [1, 2, 7, 16, MAX_NODES] {
            let (nodes, weights) = rules.rule(0.0, m);
            let (x, w) = gauss_legendre(m);
            for i in 0..m {
                assert!((nodes[i] - 0.5 * (1.0 + x[i])).abs() < 1e-15, "m = {m}, node {i}");
                assert!((weights[i] - 0.5 * w[i]).abs() < 1e-15, "m = {m}, weight {i}");
            }
        }
    }

    /// The Jacobi rule against nalgebra's symmetric eigensolver on the Jacobi matrix written from the general
    /// recurrence of `P_k^(α, β)` on `(-1, 1)` (Abramowitz & Stegun 22.7.1, with α = 0, β = -γ), mapped to `(0, 1)`.
    #[test]
    fn gauss_jacobi_agrees_with_an_eigensolver() {
        let mut rules = JacobiRules::default();
        for gamma in [0.2, 0.375, -0.5] {
            let beta = -gamma;
            for m in [3, 9, 20] {
                let matrix = nalgebra::DMatrix::from_fn(m, m, |i, j| {
                    if i == j {
                        // Monic recurrence on (-1, 1): a_k = (β² - α²)/((2k + α + β)(2k + α + β + 2)).
                        let s = 2.0 * i as f64 + beta;
                        let a = if i == 0 { beta / (beta + 2.0) } else { beta * beta / (s * (s + 2.0)) };
                        0.5 * (1.0 + a)
                    } else if i.abs_diff(j) == 1 {
                        let k = i.max(j) as f64;
                        let s = 2.0 * k + beta;
                        // b_k = 4 k (k + α)(k + β)(k + α + β)/((2k + α + β)² (2k + α + β + 1)(2k + α + β - 1)).
                        let b = 4.0 * k * k * (k + beta) * (k + beta) / (s * s * (s + 1.0) * (s - 1.0));
                        0.5 * b.sqrt()
                    } else {
                        0.0
                    }
                });
                let eigen = matrix.symmetric_eigen();
                let mut pairs: Vec<(f64, f64)> =
                    (0..m).map(|i| (eigen.eigenvalues[i], eigen.eigenvectors[(0, i)].powi(2) / (1.0 + beta))).collect();
                pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
                let (nodes, weights) = rules.rule(gamma, m);
                for i in 0..m {
                    assert!((nodes[i] - pairs[i].0).abs() < 1e-14, "γ = {gamma}, m = {m}, node {i}");
                    assert!((weights[i] / pairs[i].1 - 1.0).abs() < 1e-12, "γ = {gamma}, m = {m}, weight {i}");
                }
            }
        }
    }
}
