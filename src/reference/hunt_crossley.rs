//! Exact restitution of the hysteresis-damping family `F = K d^n (1 + alpha d')` and its inverse
//! (docs/references.md; Carvalho & Martins 2019).
//!
//! With `x = alpha v0` the relation `x (1 + e) = ln((1 + x)/(1 - e x))` is written here as
//! `phi(x) = phi(-e x)`, `phi(u) = u - ln(1 + u)`: both sides are computed without cancellation, so the
//! root is well conditioned for every `x > 0`.

use super::numerics::{bisect, phi, phi2};

/// Below this `x` the Taylor series is used (its truncation error there is ~1e-18).
const SERIES_LIMIT: f64 = 0.05;

/// `e(x) = Σ E_SERIES[k] x^k` (docs/references.md, 13 terms; coefficients re-derived exactly with rational arithmetic).
const E_SERIES: [f64; 13] = [
    1.0,
    -2.0 / 3.0,
    4.0 / 9.0,
    -44.0 / 135.0,
    104.0 / 405.0,
    -40.0 / 189.0,
    7648.0 / 42525.0,
    -2848.0 / 18225.0,
    31712.0 / 229635.0,
    -23429344.0 / 189448875.0,
    89072576.0 / 795685275.0,
    -1441952704.0 / 14105329875.0,
    893393408.0 / 9499507875.0,
];

/// `chi(eps) = Σ CHI_SERIES[k] eps^(k+1)`, `eps = 1 - e` (docs/references.md gives the first six; the last two,
/// 6639/7000 and 1599/1750, were derived the same way). Used for `eps < 1e-3`, where its error is < 1e-24.
const CHI_SERIES: [f64; 8] =
    [3.0 / 2.0, 3.0 / 2.0, 27.0 / 20.0, 6.0 / 5.0, 759.0 / 700.0, 351.0 / 350.0, 6639.0 / 7000.0, 1599.0 / 1750.0];

/// Below this `1 - e` the inverse uses [`CHI_SERIES`].
const CHI_SERIES_LIMIT: f64 = 1e-3;

/// Restitution `e` and `q = 1 - e x` (the factor `1 + alpha d'` at separation) of one Hunt–Crossley impact,
/// with `ln q` kept separately because `q` underflows for `x` above ~700.
#[derive(Debug, Clone, Copy)]
pub(crate) struct HuntCrossleyState {
    pub e: f64,
    pub q: f64,
    pub ln_q: f64,
}

impl HuntCrossleyState {
    /// Solve for finite `x > 0`.
    pub(crate) fn new(x: f64) -> Self {
        if x <= SERIES_LIMIT {
            let e = restitution_series(x);
            let r = e * x;
            Self { e, q: 1.0 - r, ln_q: (-r).ln_1p() }
        } else if x <= 1.0 {
            let r = solve_r(x);
            Self { e: r / x, q: 1.0 - r, ln_q: (-r).ln_1p() }
        } else {
            let ln_q = solve_ln_q(x);
            let q = ln_q.exp();
            Self { e: (1.0 - q) / x, q, ln_q }
        }
    }
}

/// `1 - e(x)` of the hysteresis family without the cancellation of `1 - e` for small `x`: [`E_SERIES`] less its
/// first term up to [`SERIES_LIMIT`], `1 - `[`hunt_crossley_restitution`] above.
pub fn hunt_crossley_loss(x: f64) -> f64 {
    if x > 0.0 && x < SERIES_LIMIT {
        -x * E_SERIES[1..].iter().rev().fold(0.0, |acc, c| acc * x + c)
    } else {
        1.0 - hunt_crossley_restitution(x)
    }
}

/// Exact restitution `e(x)` of the whole hysteresis-damping family `F = K d^n (1 + alpha d')`, `x = alpha v0`
/// (dimensionless), independent of `n`, `K`, `m*` (docs/references.md):
/// the root of `x (1 + e) = ln((1 + x)/(1 - e x))`, i.e. `e = (1 + W0(-(1+x) e^(-(1+x))))/x`.
///
/// `x <= 0.05`: the 13-term series of docs/references.md; above: Newton's method on `phi(x) = phi(-e x)`
/// (`phi(u) = u - ln(1+u)`), started from the Lambert-W closed form (`x <= 1`) or from `ln q = -1 - phi(x)`,
/// `q = 1 - e x` (`x > 1`, where it converges monotonically and survives the underflow of `q`: `e -> 1/x`).
/// Relative error ~1e-16 for all `x`. `x = 0` gives 1, `x = +inf` gives 0; `x < 0` or NaN gives NaN.
pub fn hunt_crossley_restitution(x: f64) -> f64 {
    if x.is_nan() || x < 0.0 {
        f64::NAN
    } else if x == 0.0 {
        1.0
    } else if x.is_infinite() {
        0.0
    } else {
        HuntCrossleyState::new(x).e
    }
}

/// Inverse of [`hunt_crossley_restitution`]: the `chi = alpha v0` that yields restitution `e` (the exact map of
/// Carvalho & Martins 2019, docs/references.md). `e = 1` gives `Some(0)`; `e <= 0`, `e > 1` or NaN give `None`.
///
/// `1 - e < 1e-3`: the series `chi = 3/2 eps + 3/2 eps² + 27/20 eps³ + …`; otherwise bisection on `(0, 1/e)` of
/// `G(x) = (phi(x) - phi(-e x))/x²`, which excludes the spurious root `x = 0` (G(0+) = (1 - e²)/2 > 0) and is
/// evaluated from its Taylor series for `x <= 1/4` (no cancellation). Relative error ~1e-15 with respect to the
/// exact inverse at the given `e`; note the map itself is ill-conditioned near `e = 1` (one ulp of `e` moves `chi`
/// by ~1e-16/(1 - e) relative, so `chi(e(x))` reproduces `x = 1e-4` only to ~8e-13).
/// For `e` below ~0.025 the result is `1/e` to double precision (`f64::MAX` if `1/e` overflows).
pub fn hunt_crossley_chi(e: f64) -> Option<f64> {
    if !(e > 0.0 && e <= 1.0) {
        return None;
    }
    let eps = 1.0 - e;
    if eps == 0.0 {
        return Some(0.0);
    }
    if eps < CHI_SERIES_LIMIT {
        let series = CHI_SERIES.iter().rev().fold(0.0, |acc, c| (acc + c) * eps);
        return Some(series);
    }
    let ln_e = (-eps).ln_1p();
    let hi = (1.0 / e).min(f64::MAX);
    Some(bisect(|x| chi_residual(x, e, ln_e), 0.0, hi))
}

/// `G(x) = (phi(x) - phi(-e x))/x² = Σ_{k>=2} ((-1)^k - e^k) x^(k-2)/k`; positive below the wanted root.
fn chi_residual(x: f64, e: f64, ln_e: f64) -> f64 {
    if x <= 0.25 {
        // 32 terms: the first omitted one is below 0.25^31 < 1e-18 of the leading ones.
        (2..34).rev().fold(0.0, |acc, k| {
            let kf = f64::from(k);
            let coefficient = if k % 2 == 0 {
                -(kf * ln_e).exp_m1() / kf // (1 - e^k)/k, accurate for e close to 1
            } else {
                -(1.0 + (kf * ln_e).exp()) / kf
            };
            acc * x + coefficient
        })
    } else if e * x >= 1.0 {
        f64::NEG_INFINITY
    } else {
        phi2(x) - e * e * phi2(-e * x)
    }
}

/// The series of docs/references.md (13 terms), accurate to 1e-18 for `x <= 0.05`.
fn restitution_series(x: f64) -> f64 {
    E_SERIES.iter().rev().fold(0.0, |acc, c| acc * x + c)
}

/// The Lambert-W closed form `e = (1 + W0(-(1+x) e^(-(1+x))))/x` as computed in double precision; it cancels
/// for small `x` (error ~7e-13 at x = 0.01, docs/references.md) and only serves as a starting guess.
fn restitution_lambert(x: f64) -> f64 {
    let y = 1.0 + x;
    let w = lambert_w::lambert_w0(-y * (-y).exp());
    (1.0 + w) / x
}

/// `r = e x` for `0.05 < x <= 1`: Newton on `f(r) = phi(-r) - phi(x)`, `f'(r) = r/(1-r)`.
fn solve_r(x: f64) -> f64 {
    let target = phi(x);
    let mut r = x * restitution_lambert(x);
    if !(r > 0.0 && r < 1.0) {
        r = 0.5 * x; // unreachable with a working W0; keeps the iteration in its domain anyway
    }
    for _ in 0..50 {
        let step = (phi(-r) - target) * (1.0 - r) / r;
        let next = r - step;
        if !(next > 0.0 && next < 1.0) {
            break;
        }
        r = next;
        if step.abs() <= 2.0 * f64::EPSILON * r {
            break;
        }
    }
    r
}

/// `ln q`, `q = 1 - e x`, for `x > 1`: Newton on the concave increasing
/// `g(l) = l - e^l + 1 + phi(x)` from `l = -1 - phi(x)` (left of the root), which converges monotonically.
fn solve_ln_q(x: f64) -> f64 {
    let target = phi(x);
    let mut l = -1.0 - target;
    for _ in 0..200 {
        let q = l.exp();
        let next = l - (l - q + 1.0 + target) / (1.0 - q);
        if next.is_nan() || next <= l {
            break;
        }
        l = next;
    }
    l
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rel(a: f64, b: f64) -> f64 {
        ((a - b) / b).abs()
    }

    /// docs/references.md#the-hunt-crossley-family: the exact values e(x) (checked), plus the e column of the
    /// quadrature table.
    const EXACT: [(f64, f64); 8] = [
        (0.01, 0.993377454399),
        (0.1, 0.937475579950),
        (0.5, 0.748434931597),
        (0.5, 0.7484349315974),
        (1.0, 0.593624260040),
        (2.0, 0.410719686061),
        (10.0, 0.0999816247529),
        (10.0, 0.09998162475294),
    ];

    #[test]
    fn restitution_matches_the_checked_values_of_e_of_x() {
        for (x, e) in EXACT {
            let got = hunt_crossley_restitution(x);
            assert!(rel(got, e) < 1e-12, "x = {x}: {got} vs {e}");
        }
    }

    #[test]
    fn series_and_implicit_solution_agree_at_the_switch() {
        let x = SERIES_LIMIT;
        let series = restitution_series(x);
        let implicit = solve_r(x) / x;
        assert!(rel(series, implicit) < 1e-13, "{series} vs {implicit}");
        let just_above = hunt_crossley_restitution(x * (1.0 + 1e-12));
        assert!(rel(series, just_above) < 1e-13);
        // And the ln q branch against the r branch at x = 1.
        let from_r = solve_r(1.0);
        let from_q = 1.0 - solve_ln_q(1.0).exp();
        assert!(rel(from_r, from_q) < 1e-14, "{from_r} vs {from_q}");
    }

    #[test]
    fn lambert_closed_form_agrees_where_it_is_well_conditioned() {
        for x in [0.3, 1.0, 3.0, 20.0, 200.0] {
            assert!(rel(restitution_lambert(x), hunt_crossley_restitution(x)) < 1e-13, "x = {x}");
        }
    }

    #[test]
    fn implicit_relation_holds() {
        // Independent check of x (1 + e) = ln((1 + x)/(1 - e x)) for moderate x (for large x the check itself
        // cancels in 1 - e x).
        for x in [0.2_f64, 0.7, 1.5, 4.0] {
            let e = hunt_crossley_restitution(x);
            let lhs = x * (1.0 + e);
            let rhs = ((1.0 + x) / (1.0 - e * x)).ln();
            assert!(rel(lhs, rhs) < 1e-15, "x = {x}");
        }
    }

    #[test]
    fn limits_and_invalid_input() {
        assert_eq!(hunt_crossley_restitution(0.0), 1.0);
        assert_eq!(hunt_crossley_restitution(f64::INFINITY), 0.0);
        assert!(hunt_crossley_restitution(-1.0).is_nan());
        assert!(hunt_crossley_restitution(f64::NAN).is_nan());
        // Large x: e = (1 - q)/x with q = 1 - e x ~ x e^(-x) negligible, so e = 1/x.
        for x in [1e3, 1e6, 1e300] {
            assert!(rel(hunt_crossley_restitution(x), 1.0 / x) < 1e-15, "x = {x}");
        }
        // x = 40: q = (1+x) e^(-(1+x)) e^q to first order; e = (1 - q)/x.
        let x = 40.0_f64;
        let q = (1.0 + x) * (-(1.0 + x)).exp();
        assert!(rel(hunt_crossley_restitution(x), (1.0 - q) / x) < 1e-15);
        // Tiny x: leading terms.
        let x = 1e-9;
        assert!(rel(hunt_crossley_restitution(x), 1.0 - 2.0 * x / 3.0) < 2.3e-16);
    }

    /// docs/laws.md effective-e table: e_eff = e(chi_law(e_nominal)), printed to 6 decimals.
    #[test]
    fn effective_restitution_table() {
        let nominal = [0.1, 0.3, 0.5, 0.7, 0.9, 0.99];
        type Law = fn(f64) -> f64;
        let rows: [(&str, Law, [f64; 6]); 5] = [
            ("Hunt–Crossley", |e| 1.5 * (1.0 - e), [0.515833, 0.581288, 0.662962, 0.768000, 0.909016, 0.990099]),
            (
                "Lankarani–Nikravesh",
                |e| 0.75 * (1.0 - e * e),
                [0.665265, 0.684225, 0.725241, 0.795973, 0.913177, 0.990148],
            ),
            ("Gonthier", |e| (1.0 - e * e) / e, [0.100990, 0.304225, 0.487741, 0.669581, 0.876435, 0.986776]),
            ("Flores", |e| 8.0 * (1.0 - e) / (5.0 * e), [0.069444, 0.256208, 0.470445, 0.683184, 0.893921, 0.989340]),
            ("Hu–Guo", |e| 1.5 * (1.0 - e) / e, [0.074074, 0.270658, 0.487741, 0.697297, 0.899900, 0.990000]),
        ];
        for (name, chi, expected) in rows {
            for (e, want) in nominal.iter().zip(expected) {
                let got = hunt_crossley_restitution(chi(*e));
                assert!((got - want).abs() <= 5.0e-7 + 1e-12, "{name}, e = {e}: {got} vs {want}");
            }
        }
    }

    /// docs/laws.md floors: LN / Lee–Wang chi <= 3/4, HC / Herbert–McWhannell chi <= 3/2, Zhiying–Qishao
    /// chi <= 3 e²/4 (its value at e = 0).
    #[test]
    fn floors() {
        let floor = |chi: f64| hunt_crossley_restitution(chi);
        assert!((floor(0.75) - 0.662962).abs() <= 5e-7);
        assert!((floor(1.5) - 0.487741).abs() <= 5e-7);
        assert!((floor(0.75 * (2.0_f64).exp()) - 0.178729).abs() <= 5e-7);
        // Herbert–McWhannell chi(0) = 6/((-1)² + 3) = 3/2 and Lee–Wang chi(0) = 3/4 give the same floors.
    }

    #[test]
    fn inverse_round_trip() {
        let xs = [
            1e-4, 3e-4, 1e-3, 0.01, 0.049, 0.05, 0.051, 0.1, 0.25, 0.2500001, 0.5, 1.0, 1.0001, 2.0, 10.0, 30.0, 100.0,
            1e3,
        ];
        for x in xs {
            let e = hunt_crossley_restitution(x);
            let back = hunt_crossley_chi(e).unwrap();
            assert!(rel(back, x) < 1e-12, "x = {x}: {back}");
        }
    }

    #[test]
    fn inverse_near_e_one_matches_its_series_in_one_minus_e() {
        // chi = 3/2 eps + 3/2 eps² + 27/20 eps³ + 6/5 eps⁴ + 759/700 eps⁵ + 351/350 eps⁶
        // (docs/references.md#the-hunt-crossley-family).
        let series = |eps: f64| {
            1.5 * eps
                + 1.5 * eps.powi(2)
                + 1.35 * eps.powi(3)
                + 1.2 * eps.powi(4)
                + 759.0 / 700.0 * eps.powi(5)
                + 351.0 / 350.0 * eps.powi(6)
        };
        for e in [0.999_f64, 0.9999, 0.99] {
            let eps = 1.0 - e;
            let got = hunt_crossley_chi(e).unwrap();
            // Truncation of the printed series: next term ~0.95 eps^7.
            let tolerance = 1e-14 + eps.powi(7) / (1.5 * eps);
            assert!(rel(got, series(eps)) < tolerance, "e = {e}: {got} vs {}", series(eps));
        }
        // 0.999 lies just on the bisection side of the switch (1 - 0.999 > 1e-3 in binary), 0.9999 on the series
        // side: both branches agree with the series.
    }

    #[test]
    fn inverse_limits_and_invalid_input() {
        assert_eq!(hunt_crossley_chi(1.0), Some(0.0));
        assert_eq!(hunt_crossley_chi(0.0), None);
        assert_eq!(hunt_crossley_chi(-0.5), None);
        assert_eq!(hunt_crossley_chi(1.5), None);
        assert_eq!(hunt_crossley_chi(f64::NAN), None);
        // Small e: chi = 1/e to double precision.
        for e in [1e-3, 1e-10, 1e-300] {
            assert!(rel(hunt_crossley_chi(e).unwrap(), 1.0 / e) < 1e-15, "e = {e}");
        }
        // docs/references.md's exact values read backwards.
        for (x, e) in EXACT {
            assert!(rel(hunt_crossley_chi(e).unwrap(), x) < 1e-10, "x = {x}");
        }
    }
}
