//! The times of a hysteresis-law impact from its exact first integral, by quadrature
//! (docs/numerics.md#the-first-integral).
//!
//! Scaled (`m* = K = v0 = 1`, `x = alpha v0`), the motion `d'' = -d^n (1 + x d')` has the first integral
//! `d^(n+1)/(n+1) = H(v) = G(1) - G(v)`, `G(v) = ∫_0^v u/(1 + x u) du` ([`super::first_integral`]). The rate is
//! monotone in each phase, so time is an integral over it: `dt = dv/v' = -dv/(d^n (1 + x v))`. With
//! `η = ln(1 + x v)/x` (`η = v` at `x = 0`), `dη = dv/(1 + x v)` and
//!
//! `t = ∫ dη / ((n+1) H)^k`, `k = n/(n+1)`,
//!
//! from `η1 = ln(1+x)/x` (first contact, `v = 1`) down to `0` (maximum compression), and on to
//! `η_end = ln(1 - x e)/x` (separation, `v = -e`). In `y = x η`, `x² H = (1+x)(1 - e^(-σ)) - σ` with `σ = ln(1+x) - y`,
//! an entire function with simple zeros at `v = 1` and `v = -e`: the integrand is `|η - zero|^(-k)` times a function
//! analytic on the phase, and a Gauss–Jacobi rule with that weight integrates it to rounding with about ten nodes.
//! Its other singularities are complex zeros of `H` near `y = ln(1+x) ± 2πi`, and the zero at `v = 1` seen from the
//! restitution: for a heavy damping both are close to maximum compression compared with the restitution's length,
//! so that phase is cut into Gauss–Legendre panels graded towards them; where `e^y` is below `e^(-40)` the
//! restitution creeps at `v ≈ -1/x`, `x² H = s` to rounding (`s = y - ln(1 - x e)`), and its time is a closed form.
//!
//! `H` is evaluated without cancellation near its zeros, as a product of positive terms:
//!
//! * compression, `σ' = η1 - η`: `a = σ' exprel(x σ')` (`= (1 - v)/(1 + x v)`), `H = a (a φ₂(x a) + v)`,
//!   `v = (1 - a)/(1 + x a)`;
//! * restitution, `s' = η - η_end`: `c = s' (1 - e^(-x s'))/(x s')`, `H = c (c φ₂(-x c) - v)` (`-v >= 0`), where
//!   `c φ₂(-x c) = (s' - c)/(x c)` once `x s' > 1` (`φ₂` near -1 would take the logarithm of a rounded `e^(-x s')`).
//!
//! Both are exact rearrangements of `G(1) - G(v)` (and of `G(-e) - G(v)`, its equal); they are positive at every
//! node, so no power of a negative number is taken and no clamp is needed.

use super::quadrature::{JacobiRules, gauss_legendre, negative_power};
use crate::reference::phi2;
use std::cell::RefCell;

/// Gauss–Jacobi nodes for the compression (`x <= 1e3`: the complex zeros of `H` at distance `2π/x` from first
/// contact, at least 0.9 of the phase's length `ln(1+x)/x`, bound the error by about 1e-15).
const COMPRESSION_NODES: usize = 11;
/// The compression's and the restitution's Gauss–Jacobi nodes for a light damping, `x <= LIGHT` (the nearest zero
/// of `H` the phase's length away from its end, or farther: about 1e-14).
const LIGHT_NODES: usize = 9;
/// See [`LIGHT_NODES`].
const LIGHT: f64 = 1.0;
/// Gauss–Jacobi nodes from first contact to the force peak (a part of the compression).
const PEAK_NODES: usize = 9;
/// Gauss–Jacobi nodes for the restitution's panel that ends at separation.
const SEPARATION_NODES: usize = 11;
/// Gauss–Legendre nodes for each of the restitution's other panels.
const PANEL_NODES: usize = 11;
/// A panel's length at most this times its distance to the nearest zero of `H` outside it (its Bernstein ellipse
/// parameter then at least `3 + √8`, so that 11 nodes leave about 1e-15).
const REACH: f64 = 2.0;
/// Where `e^y < e^(-CREEP)` (`y = ln(1 + x v)`), `x² H = s` to 4e-18 relative: the restitution's time from there
/// to separation is a closed form.
const CREEP: f64 = 40.0;

/// The times of one impact, in `T` since first contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Times {
    /// Of maximum compression.
    pub max_compression: f64,
    /// Of separation (the contact's duration).
    pub separation: f64,
    /// Of the force peak (NaN unless its rate was given).
    pub peak_force: f64,
}

thread_local! {
    /// The Gauss–Jacobi rules of the weight `s^(-k)`, kept while `k` stays the same (a sweep keeps its exponent).
    static RULES: RefCell<JacobiRules> = RefCell::new(JacobiRules::default());
}

/// The times of the impact of `F = d^n (1 + x d')` (scaled), of restitution `e` (`hunt_crossley_restitution(x)`),
/// with the force peak at rate `peak_rate` (from the first integral; `None`: the peak's time is not asked, or it
/// is at maximum compression: `x = 0`). For `0 <= x <= 1e3` and `1 <= n <= 3` (tested there to about 1e-14
/// relative); `e` must be positive.
pub fn times(x: f64, n: f64, e: f64, peak_rate: Option<f64>, peak_asked: bool) -> Times {
    let k = n / (n + 1.0);
    let scale = n + 1.0;
    // Compression's integrand over the Jacobi weight, `((n+1) H/σ')^(-k)`, at `σ' > 0`.
    let compression = |sigma: f64| {
        let grow = exprel(x * sigma);
        let a = sigma * grow;
        let v = (1.0 - a) / (1.0 + x * a);
        negative_power(scale * grow * (a * phi2(x * a) + v), k)
    };
    // η1 = ln(1+x)/x.
    let first = ln1p_over(x);
    RULES.with(|cell| {
        let rules = &mut *cell.borrow_mut();
        let nodes = if x <= LIGHT { LIGHT_NODES } else { COMPRESSION_NODES };
        let max_compression = jacobi(rules, k, first, nodes, compression);
        let peak_force = match (peak_asked, peak_rate) {
            (false, _) => f64::NAN,
            (true, None) => max_compression,
            (true, Some(v)) => {
                // σ' at the peak: ln((1+x)/(1+x v))/x = ln(1 + r)/x, r = x (1-v)/(1+x v).
                let a = (1.0 - v) / (1.0 + x * v);
                jacobi(rules, k, a * ln1p_over(x * a), PEAK_NODES, compression)
            }
        };
        let restitution = restitution_time(x, n, e, first, rules);
        Times { max_compression, separation: max_compression + restitution, peak_force }
    })
}

/// The restitution's time, from maximum compression (`η = 0`) to separation (`η_end`), with `η1` the first
/// contact's `η` (see the module).
fn restitution_time(x: f64, n: f64, e: f64, first: f64, rules: &mut JacobiRules) -> f64 {
    let k = n / (n + 1.0);
    let scale = n + 1.0;
    // The restitution's length in η, -η_end = -ln(1 - x e)/x (= e at x = 0): `ln q` by its logarithm where
    // x e > 1/2 (`q = 1 - x e` is e^(-x) there, lost to rounding), from `x (1 + e) = ln((1 + x)/q)`.
    let span = if x == 0.0 {
        e
    } else if x * e <= 0.5 {
        e * ln1p_over(-x * e)
    } else {
        (x * (1.0 + e) - x.ln_1p()) / x
    };
    // `H/s'` and `H` at `s' = η - η_end` (`c = H`'s factor vanishing at separation, `lift = -v >= 0`).
    let parts = |s: f64| {
        let shrink = one_minus_exp_neg_rel(x * s);
        let c = s * shrink;
        let eta = s - span;
        let lift = -eta * exprel(x * eta);
        let rest = if x * s <= 1.0 { c * phi2(-x * c) } else { (s - c) / (x * c) };
        (shrink, c, rest + lift)
    };
    let mut total = 0.0;
    // The right end of the panel to come, in s'; the zero at v = 1 lies `first + span - upper` beyond it.
    let mut upper = span;
    // Where `y = x η = -CREEP` (negative, or none, unless the restitution is long).
    let creep = if x > 0.0 { span - CREEP / x } else { f64::NEG_INFINITY };
    loop {
        let reach = first + span - upper;
        if upper <= REACH * reach {
            let f = |s: f64| {
                let (shrink, _, bracket) = parts(s);
                negative_power(scale * shrink * bracket, k)
            };
            total += jacobi(rules, k, upper, if x <= LIGHT { LIGHT_NODES } else { SEPARATION_NODES }, f);
            return total;
        }
        if upper <= creep {
            // x² H = s: t = ∫_0^upper (scale s'/x)^(-k) ds' = (x/scale)^k upper^(1-k)/(1-k).
            return total + (x / scale).powf(k) * upper.powf(1.0 - k) * scale;
        }
        let lower = (upper - (REACH * reach).min(REACH * upper / (1.0 + REACH))).max(creep);
        let (nodes, weights) = gauss_legendre(PANEL_NODES);
        let (half, centre) = (0.5 * (upper - lower), 0.5 * (upper + lower));
        let sum: f64 = nodes
            .iter()
            .zip(weights)
            .map(|(&t, &w)| {
                let (_, c, bracket) = parts(centre + half * t);
                w * negative_power(scale * c * bracket, k)
            })
            .sum();
        total += half * sum;
        upper = lower;
    }
}

/// `∫_0^length s^(-k) f(s) ds` by the `m`-node Gauss–Jacobi rule of that weight.
fn jacobi(rules: &mut JacobiRules, k: f64, length: f64, m: usize, f: impl Fn(f64) -> f64) -> f64 {
    let (nodes, weights) = rules.rule(k, m);
    let sum: f64 = nodes.iter().zip(weights).map(|(&s, &w)| w * f(length * s)).sum();
    length.powf(1.0 - k) * sum
}

/// `(e^z - 1)/z` (1 at `z = 0`).
fn exprel(z: f64) -> f64 {
    if z.abs() < 1e-5 { 1.0 + z * (0.5 + z / 6.0) } else { z.exp_m1() / z }
}

/// `(1 - e^(-z))/z` (1 at `z = 0`).
fn one_minus_exp_neg_rel(z: f64) -> f64 {
    if z.abs() < 1e-5 { 1.0 - z * (0.5 - z / 6.0) } else { -(-z).exp_m1() / z }
}

/// `ln(1 + z)/z` (1 at `z = 0`), for `z > -1`.
fn ln1p_over(z: f64) -> f64 {
    if z.abs() < 1e-4 { 1.0 - z * (0.5 - z * (1.0 / 3.0 - 0.25 * z)) } else { z.ln_1p() / z }
}
