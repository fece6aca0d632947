//! Viscoelastic spheres (Kuwabara–Kono; Brilliantov et al. 1996): `F = K (d^(3/2) + (3/2) A d^(1/2) d')`.
//! Only the small-`b` series of the restitution is provided (docs/references.md); it is approximate.

use super::numerics::beta;

/// `C1 = (4/5)(5/4)^(3/5) B(3/5, 3/2) = 1.1534489…` (docs/references.md; Schwager & Pöschel 2008).
pub fn brilliantov_c1() -> f64 {
    0.8 * 1.25_f64.powf(0.6) * beta(0.6, 1.5)
}

/// `C2 = (3/5) C1² = 0.7982666…` (Schwager & Pöschel 2008; docs/references.md prints 0.7982666).
pub fn brilliantov_c2() -> f64 {
    0.6 * brilliantov_c1().powi(2)
}

/// **Approximate** restitution of viscoelastic spheres for separation at `d = 0`:
/// `e ≈ 1 - C1 b + C2 b²`, `b = (3/2) A (K/m*)^(2/5) v0^(1/5)` (dimensionless, docs/references.md).
///
/// Truncation error (next term about `-0.523 b³`): 6e-5 at b = 0.05, 5e-4 at 0.1, 4e-3 at 0.2 — use it only
/// for small `b`, never as an exact reference at the 1e-6 level. NaN for `b < 0` or NaN.
pub fn brilliantov_restitution_series(b: f64) -> f64 {
    if b.is_nan() || b < 0.0 {
        return f64::NAN;
    }
    1.0 - brilliantov_c1() * b + brilliantov_c2() * b * b
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn series_constants_c1_and_c2_to_seven_digits() {
        // docs/references.md#brilliantov-viscoelastic-spheres: C1 = 1.1534489, C2 = 0.7982666.
        assert!((brilliantov_c1() - 1.1534489).abs() <= 5e-8, "{}", brilliantov_c1());
        assert!((brilliantov_c2() - 0.7982666).abs() <= 5e-8, "{}", brilliantov_c2());
    }

    #[test]
    fn series_error_against_exact_values() {
        // docs/references.md: exact (ODE, d = 0) b = 0.01 → 0.9885448187, 0.1 → 0.8921475873; series error
        // ~0.523 b³ (5.2e-7 at 0.01) and 5e-4 at b = 0.1.
        let err_small = brilliantov_restitution_series(0.01) - 0.9885448187;
        assert!(err_small > 0.0 && err_small < 6e-7, "{err_small}");
        let err = brilliantov_restitution_series(0.1) - 0.8921475873;
        assert!(err > 4.5e-4 && err < 5.5e-4, "{err}");
        assert_eq!(brilliantov_restitution_series(0.0), 1.0);
        assert!(brilliantov_restitution_series(-1.0).is_nan());
    }
}
