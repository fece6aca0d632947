//! Physical time from the regularised time: `t = ∫ w(τ)^(-γ) dτ` over each step, where `w` is the step's Taylor
//! polynomial.
//!
//! The integrand is singular where `w` vanishes — at first contact and at a penetration separation — and analytic
//! elsewhere. Three rules cover a step:
//!
//! * a step that starts at `w = 0` ([`SingularSeries`]): with `w(σ) = σ Q(σ)`, `Q(0) > 0`,
//!   `∫_0^t σ^(-γ) Q^(-γ) dσ = t^(1-γ) Σ_k r_k t^k/(k + 1 - γ)`, `r = Q^(-γ)` by the power recursion — the
//!   singularity is integrated exactly, and the series converges as far as the next zero of `w`;
//! * a step that ends at `w = 0` at `σ_z`: the same series about `σ_z`, in `σ_z - σ`;
//! * any other step: Gauss–Legendre ([`gauss_power`]) with as many nodes as the distance to the nearest zero of
//!   `w` asks for (the error of an `m`-node rule falls like `ρ^(-2m)`, `ρ` the Bernstein ellipse through the
//!   singularity, [`nodes_needed`]).

use super::taylor::{self, MAX_ORDER};
use std::sync::OnceLock;

/// Largest Gauss–Legendre rule kept.
pub const MAX_NODES: usize = 24;

/// Gauss–Legendre rules on `[-1, 1]`: `nodes[m][..m]` (ascending) and `weights[m][..m]` for `m = 1..=MAX_NODES`.
struct Rules {
    nodes: [[f64; MAX_NODES]; MAX_NODES + 1],
    weights: [[f64; MAX_NODES]; MAX_NODES + 1],
}

static RULES: OnceLock<Rules> = OnceLock::new();

/// The `m`-node Gauss–Legendre rule on `[-1, 1]` (`1 <= m <= MAX_NODES`): nodes ascending, and weights.
pub fn gauss_legendre(m: usize) -> (&'static [f64], &'static [f64]) {
    let rules = RULES.get_or_init(|| {
        let mut rules = Rules { nodes: [[0.0; MAX_NODES]; MAX_NODES + 1], weights: [[0.0; MAX_NODES]; MAX_NODES + 1] };
        for m in 1..=MAX_NODES {
            legendre_rule(m, &mut rules.nodes[m][..m], &mut rules.weights[m][..m]);
        }
        rules
    });
    (&rules.nodes[m][..m], &rules.weights[m][..m])
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
/// `m`-node rule is about `ρ^(-2m)`, `ρ = xi + sqrt(xi² - 1)`, so `m = (ln(1/eps) + margin)/(2 ln ρ)`.
pub fn nodes_needed(xi: f64, eps: f64) -> usize {
    if xi.is_infinite() {
        return 1;
    }
    let rho = xi + (xi * xi - 1.0).max(0.0).sqrt();
    let m = ((1.0 / eps).ln() + NODE_MARGIN) / (2.0 * rho.ln());
    if m.is_finite() { (m.ceil() as usize).max(2) } else { usize::MAX }
}

/// Added to `ln(1/eps)` in [`nodes_needed`]: the constant of the error bound (a branch point on the ellipse).
const NODE_MARGIN: f64 = 2.0;

/// `∫_a^b w(σ)^(-gamma) dσ` with the `m`-node Gauss–Legendre rule, `w` the polynomial `c`. `None` if `w <= 0`
/// at a node (the interval reaches a zero of `w`: a caller's error, reported rather than a NaN).
pub fn gauss_power(c: &[f64], gamma: f64, a: f64, b: f64, m: usize) -> Option<f64> {
    let (nodes, weights) = gauss_legendre(m);
    let half = 0.5 * (b - a);
    let middle = 0.5 * (a + b);
    // Horner at four nodes at once: their chains are independent, so they overlap (and fill vector lanes).
    let mut sum = 0.0;
    for (chunk_nodes, chunk_weights) in nodes.chunks(4).zip(weights.chunks(4)) {
        let mut at = [middle; 4];
        for (point, &x) in at.iter_mut().zip(chunk_nodes) {
            *point = middle + half * x;
        }
        let mut values = [0.0; 4];
        for &ck in c.iter().rev() {
            for l in 0..4 {
                values[l] = values[l] * at[l] + ck;
            }
        }
        for (&w, &weight) in values.iter().zip(chunk_weights) {
            if w <= 0.0 {
                return None;
            }
            // exp(-γ ln w) rather than powf: cheaper, and as accurate here (|γ ln w| stays below a few units,
            // so the exponent's absolute error, which becomes the relative error, is a few ulp).
            sum += weight * (-gamma * w.ln()).exp();
        }
    }
    Some(half * sum)
}

/// Terms in a row below the tolerance that end a [`SingularSeries`] sum.
const CONVERGED_RUN: usize = 4;

/// Largest number of terms of a [`SingularSeries`].
pub const SERIES_TERMS: usize = 96;

/// `S(t) = ∫_0^t σ^(-γ) Q(σ)^(-γ) dσ` for a polynomial `Q` with `Q(0) > 0`, as the series
/// `t^(1-γ) Σ_k r_k t^k/(k + 1 - γ)`, `r = Q^(-γ)`: the time from (or to) a zero `w = σ Q(σ)` of the penetration
/// variable. The coefficients `r_k` are computed as far as a sum needs them and kept for later sums.
pub struct SingularSeries {
    q: [f64; MAX_ORDER + 1],
    /// `(1 - γ) j q_j`: the recursion's other weights.
    weighted: [f64; MAX_ORDER + 1],
    degree: usize,
    gamma: f64,
    /// `r` reversed: `reversed[SERIES_TERMS - 1 - k] = r_k`, so that the recursion's sums are contiguous.
    reversed: [f64; SERIES_TERMS],
    /// The series' coefficients `r_k/(k + 1 - γ)`.
    divided: [f64; SERIES_TERMS],
    known: usize,
}

impl Default for SingularSeries {
    /// An empty series, to be [`reset`](SingularSeries::reset) before use.
    fn default() -> Self {
        SingularSeries {
            q: [0.0; MAX_ORDER + 1],
            weighted: [0.0; MAX_ORDER + 1],
            degree: 0,
            gamma: 0.0,
            reversed: [0.0; SERIES_TERMS],
            divided: [0.0; SERIES_TERMS],
            known: 0,
        }
    }
}

impl SingularSeries {
    /// The series for `Q` = `q` (`q[0] > 0`, at most `MAX_ORDER + 1` coefficients). `None` if `q[0] <= 0`.
    #[cfg(test)]
    pub fn new(q: &[f64], gamma: f64) -> Option<SingularSeries> {
        let mut series = SingularSeries::default();
        series.reset(q, gamma).then_some(series)
    }

    /// Makes this the series of `Q` = `q` (see [`SingularSeries::new`]); false (and unusable) if `q[0] <= 0`.
    pub fn reset(&mut self, q: &[f64], gamma: f64) -> bool {
        // (NaN is refused too.)
        if q[0].is_nan() || q[0] <= 0.0 {
            self.known = 0;
            return false;
        }
        self.q[..q.len()].copy_from_slice(q);
        for (j, (weighted, &qj)) in self.weighted.iter_mut().zip(q).enumerate() {
            *weighted = (1.0 - gamma) * j as f64 * qj;
        }
        self.degree = q.len() - 1;
        self.gamma = gamma;
        // exp/ln rather than powf (a third of the cost; the exponent's absolute error, a few ulp, is the result's
        // relative error).
        self.reversed[SERIES_TERMS - 1] = (-gamma * q[0].ln()).exp();
        self.divided[0] = self.reversed[SERIES_TERMS - 1] / (1.0 - gamma);
        self.known = 1;
        true
    }

    /// `r_k` (known).
    #[cfg(test)]
    fn r(&self, k: usize) -> f64 {
        self.reversed[SERIES_TERMS - 1 - k]
    }

    /// Extends `r = Q^alpha`, `alpha = -γ`, to `to` coefficients. From `Q r' = alpha Q' r`:
    /// `r_k = (Σ_j (alpha + 1) j q_j r_{k-j} - k Σ_j q_j r_{k-j}) / (k q_0)`, `j = 1..=min(k, deg Q)` (the
    /// coefficients of `Q` beyond its degree are zero, so `r` continues to any length at `O(deg Q)` each).
    fn extend(&mut self, to: usize) {
        let inverse_q0 = 1.0 / self.q[0];
        for k in self.known..to {
            let top = k.min(self.degree);
            // r_{k-j} for j = 1..=top, in the reversed storage: contiguous from SERIES_TERMS - k.
            let window = &self.reversed[SERIES_TERMS - k..SERIES_TERMS - k + top];
            let (first, second) = taylor::dot2(&self.weighted[1..=top], &self.q[1..=top], window);
            let r = (first - k as f64 * second) * inverse_q0 / k as f64;
            self.reversed[SERIES_TERMS - 1 - k] = r;
            self.divided[k] = r / (k as f64 + 1.0 - self.gamma);
        }
        self.known = to;
    }

    /// `S(t)` for `t >= 0`, to relative accuracy `eps`; `None` if the series has not converged within
    /// [`SERIES_TERMS`] terms (`t` too close to the next zero of `Q`: the caller takes a shorter piece).
    pub fn integral(&mut self, t: f64, eps: f64) -> Option<f64> {
        if t == 0.0 {
            return Some(0.0);
        }
        let exponent = 1.0 - self.gamma;
        let mut sum = 0.0;
        let mut power = 1.0;
        // Terms in a row found below the tolerance: a series in an even Q has every other term zero, and a
        // term may vanish by accident, so one or two small terms prove nothing.
        let mut small = 0;
        for k in 0..SERIES_TERMS {
            if k == self.known {
                self.extend((k + 8).min(SERIES_TERMS));
            }
            let term = self.divided[k] * power;
            sum += term;
            small = if term.abs() <= eps * sum.abs() { small + 1 } else { 0 };
            if small == CONVERGED_RUN {
                return Some((exponent * t.ln()).exp() * sum);
            }
            power *= t;
        }
        None
    }
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

    #[test]
    fn series_coefficients_are_the_binomial_ones() {
        // Q = 1 + σ: r = (1 + σ)^(-γ) = Σ binom(-γ, k) σ^k.
        let gamma = 0.3;
        let mut series = SingularSeries::new(&[1.0, 1.0], gamma).unwrap();
        series.extend(20);
        let mut binomial = 1.0;
        for k in 0..20 {
            assert!((series.r(k) - binomial).abs() <= 1e-15 * binomial.abs(), "k = {k}");
            binomial *= (-gamma - k as f64) / (k as f64 + 1.0);
        }
    }

    /// `∫_0^{π/2} sin(σ)^(-γ) dσ = B((1-γ)/2, 1/2)/2`, with `sin σ = σ Q(σ)`, `Q = Σ (-1)^j σ^(2j)/(2j+1)!`.
    #[test]
    fn singular_series_integrates_the_sine_power() {
        let gamma = 0.2;
        let mut q = [0.0; 24];
        let mut factorial = 1.0;
        for j in 0..12 {
            factorial *= if j == 0 { 1.0 } else { (2 * j) as f64 * (2 * j + 1) as f64 };
            q[2 * j] = if j % 2 == 0 { 1.0 } else { -1.0 } / factorial;
        }
        let mut series = SingularSeries::new(&q, gamma).expect("Q(0) = 1");
        let exact = 0.5 * crate::reference::beta(0.5 * (1.0 - gamma), 0.5);
        let got = series.integral(std::f64::consts::FRAC_PI_2, 1e-17).expect("converges: the next zero is at pi");
        assert!((got / exact - 1.0).abs() < 1e-14, "{got} vs {exact}");
    }

    #[test]
    fn gauss_power_integrates_a_shifted_power() {
        // ∫_1^2 σ^(-0.3) dσ = (2^0.7 - 1)/0.7, with w = σ written about 0.
        let got = gauss_power(&[0.0, 1.0], 0.3, 1.0, 2.0, nodes_needed(3.0, 1e-16)).unwrap();
        let exact = (2.0_f64.powf(0.7) - 1.0) / 0.7;
        assert!((got / exact - 1.0).abs() < 1e-15, "{got} vs {exact}");
    }
}
