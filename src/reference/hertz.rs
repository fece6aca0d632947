//! Elastic power-law Hertz contact `F = K d^n` (docs/references.md).

use super::ContactReference;
use super::numerics::beta;

/// Exact nondimensional elastic impact for `F = K d^n`, `n > 0` (docs/references.md):
/// `dmax = ((n+1)/2)^(1/(n+1))`, `tc = (2/(n+1)) B(1/(n+1), 1/2) dmax`, `t0 = tc/2`, `Fmax = dmax^n`, `e = 1`
/// (from energy conservation `d'² + 2 d^(n+1)/(n+1) = 1`). For `n = 3/2`: `dmax = (5/4)^(2/5)`,
/// `tc = 2.9432751843 dmax`; for `n = 1`: `tc = pi`.
/// Relative error ~1e-15. `n <= 0`, infinite or NaN gives [`ContactReference::UNDEFINED`].
pub fn hertz_elastic(n: f64) -> ContactReference {
    if !(n > 0.0 && n.is_finite()) {
        return ContactReference::UNDEFINED;
    }
    let p = n + 1.0;
    let max_penetration = (0.5 * p).powf(1.0 / p);
    let duration = 2.0 / p * beta(1.0 / p, 0.5) * max_penetration;
    ContactReference {
        restitution: 1.0,
        max_penetration,
        max_compression_time: 0.5 * duration,
        duration,
        max_force: max_penetration.powf(n),
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
    fn hertz_three_halves() {
        let r = hertz_elastic(1.5);
        // docs/references.md: dmax = (5/4)^(2/5) L, tc = 2.9432751843 dmax/v0, Fmax = dmax^(3/2), t0 = tc/2.
        assert!(rel(r.max_penetration, 1.25_f64.powf(0.4)) < 1e-15);
        assert!((r.duration / r.max_penetration - 2.9432751843).abs() < 5e-11);
        assert!(rel(r.max_force, 1.25_f64.powf(0.6)) < 1e-15);
        assert_eq!(r.max_compression_time, 0.5 * r.duration);
        assert_eq!(r.restitution, 1.0);
    }

    #[test]
    fn linear_spring_is_a_half_period() {
        let r = hertz_elastic(1.0);
        assert!(rel(r.duration, PI) < 1e-15);
        assert!(rel(r.max_penetration, 1.0) < 1e-15);
        assert!(rel(r.max_force, 1.0) < 1e-15);
    }

    #[test]
    fn quadratic_law_closed_form() {
        // n = 2: dmax³ = 3/2, t0 = dmax ∫_0^1 du / sqrt(1 - u³) = dmax B(1/3, 1/2)/3, and
        // B(1/3, 1/2) = Γ(1/3) Γ(1/2) / Γ(5/6) = 4.2065463... (Γ(1/3) = 2.6789385347077476,
        // Γ(5/6) = 1.128787029908126).
        let b = 2.678_938_534_707_747_6 * PI.sqrt() / 1.128_787_029_908_126;
        let r = hertz_elastic(2.0);
        let dmax = 1.5_f64.cbrt();
        assert!(rel(r.max_compression_time, dmax * b / 3.0) < 1e-14);
    }

    #[test]
    fn two_steel_spheres_closing_at_one_metre_per_second() {
        // docs/references.md#elastic-hertz-contact: two steel spheres, E = 210 GPa, nu = 0.3, rho = 7850, r = 10 mm,
        // closing at 1 m/s: dmax = 2.04412e-5 m, tc = 6.01641e-5 s, Fmax = 1005.38 N.
        let (e_mod, nu, rho, r, v0) = (210e9_f64, 0.3_f64, 7850.0_f64, 0.01_f64, 1.0_f64);
        let e_star = e_mod / (2.0 * (1.0 - nu * nu));
        let r_star = r / 2.0;
        let k = 4.0 / 3.0 * e_star * r_star.sqrt();
        let m = rho * 4.0 / 3.0 * PI * r.powi(3);
        let m_star = m / 2.0;
        let l = (m_star * v0 * v0 / k).powf(0.4);
        let ref_ = hertz_elastic(1.5);
        assert!(rel(ref_.max_penetration * l, 2.04412e-5) < 3e-6);
        assert!(rel(ref_.duration * l / v0, 6.01641e-5) < 1e-6);
        assert!(rel(ref_.max_force * k * l.powf(1.5), 1005.38) < 5e-6);
    }

    #[test]
    fn invalid_exponent() {
        assert!(hertz_elastic(0.0).duration.is_nan());
        assert!(hertz_elastic(f64::NAN).max_force.is_nan());
    }
}
