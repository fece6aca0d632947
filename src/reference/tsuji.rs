//! DEM Hertz law with Tsuji-type damping `F = K d^(3/2) + a sqrt(m* K) d^(1/4) d'` (docs/references.md).
//!
//! In the units `L = (m* v0²/K)^(2/5)`, `T = L/v0`, `F0 = K L^(3/2)` the motion is `d'' = -d^(3/2) - a d^(1/4) d'`.
//! With `w = d^(5/4)` and `dtau = d^(1/4) dt` it becomes `w'' + a w' + (5/4) w = 0`; in the time
//! `s = omega0 tau`, `omega0 = sqrt(5)/2`, this is the unit Kelvin–Voigt oscillator with `zeta = a/sqrt(5)`:
//! `w = omega0 D(s)`, `d' = D'(s)`, `dt = omega0^(-6/5) D^(-1/5) ds`, `F = omega0^(6/5) D^(1/5) (D + 2 zeta D')`.

use super::kelvin_voigt::{UnitOscillator, kelvin_voigt_zeta};
use super::numerics::{bisect, integrate};
use super::{ContactReference, SeparationCriterion};

/// `omega0² = 5/4`.
const OMEGA0_SQ: f64 = 1.25;

/// Exact nondimensional impact for the Tsuji law with damping coefficient `a >= 0` (docs/references.md).
///
/// * `Penetration`: `e = exp(-pi zeta/sqrt(1 - zeta²))`, `zeta = a/sqrt(5)` (exactly the nominal e of
///   [`tsuji_damping`]); `None` for `zeta >= 1` (never separates).
/// * `Force`: the Kelvin–Voigt `F = 0` restitution, `e = exp(-2 zeta t0)` (nominal 0.5 → 0.550283).
/// * `max_penetration = (omega0 D(t0))^(4/5)`, `D(t0) = exp(-zeta t0)` (docs/references.md's `tau*`);
/// * `max_compression_time`, `duration`: `omega0^(-6/5) ∫ D(s)^(-1/5) ds` (docs/references.md's `∫ w^(-1/5) dtau`) by
///   tanh-sinh quadrature after `s = sigma^5` (and `s_zero - s = sigma^5` near `D`'s zero), which makes the
///   integrand analytic;
/// * `max_force`: maximum of `D^(1/5) (D + 2 zeta D')` (no jump at contact for this law), located by bisection on
///   its derivative's sign.
///
/// Relative error ~1e-15. `None` also for `a < 0` or non-finite `a`. With `Penetration` and `zeta` within ~4e-7 of
/// 1 the (astronomically long) duration overflows to `+inf` and `e` underflows to 0.
pub fn tsuji(a: f64, separation: SeparationCriterion) -> Option<ContactReference> {
    if !(a >= 0.0 && a.is_finite()) {
        return None;
    }
    let zeta = a / 5.0_f64.sqrt();
    let osc = UnitOscillator::new(zeta);
    let s_end = osc.separation_time(separation)?;
    let time_unit = OMEGA0_SQ.powf(-0.6); // omega0^(-6/5)
    Some(ContactReference {
        restitution: osc.restitution(s_end),
        max_penetration: (OMEGA0_SQ.sqrt() * osc.max_penetration()).powf(0.8),
        max_compression_time: time_unit * time_integral(&osc, osc.max_compression_time(), None),
        duration: time_unit
            * time_integral(
                &osc,
                s_end,
                (separation == SeparationCriterion::Force).then(|| osc.force_zero_gap()).flatten(),
            ),
        max_force: OMEGA0_SQ.powf(0.6) * max_scaled_force(&osc),
    })
}

/// `∫_0^{s_end} D(s)^(-1/5) ds`. Near `s = 0` (`D ~ s`) the substitution `s = sigma^5` gives the bounded
/// integrand `5 sigma³ (D/s)^(-1/5)`; past the midpoint of an underdamped oscillation the same is done around the
/// zero `s_z = pi/wd` of `D` (`s_z - s = sigma^5`), so that ends at or near it are harmless. `gap`, where given, is
/// `s_z - s_end` formed without the subtraction (the force's zero an ulp before `D`'s: the integral's end there is
/// `gap^(1/5)`, which the rounding of `s_end` would move by far more than an ulp).
fn time_integral(osc: &UnitOscillator, s_end: f64, gap: Option<f64>) -> f64 {
    let from_start = |b: f64| {
        let f = |sigma: f64| {
            let s = sigma.powi(5);
            5.0 * sigma.powi(3) * osc.d_over_s(s).powf(-0.2)
        };
        integrate(f, 0.0, b.powf(0.2))
    };
    match osc.zero_time() {
        Some(s_zero) if s_end > 0.5 * s_zero => {
            let mid = 0.5 * s_zero;
            let f = |sigma: f64| {
                let u = sigma.powi(5);
                let s = s_zero - u;
                // D(s_zero - u)/u = e^(-zeta s) sin(wd u)/(wd u) = (D(u)/u) e^(-zeta (s - u)), computed directly:
                5.0 * sigma.powi(3) * (osc.d_over_s(u) * (-osc.zeta * (s - u)).exp()).powf(-0.2)
            };
            let lower = gap.unwrap_or(s_zero - s_end).max(0.0).powf(0.2);
            from_start(mid) + integrate(f, lower, mid.powf(0.2))
        }
        _ => from_start(s_end),
    }
}

/// `max_s D^(1/5) (D + 2 zeta D')`: its derivative has the sign of
/// `rho = D' (D + 2 zeta D')/5 + D ((1 - 4 zeta²) D' - 2 zeta D)`, positive after contact (`2 zeta/5` at `s = 0`,
/// or `(6/5) D D'` for `zeta = 0`) and `-2 zeta D² < 0` at maximum compression.
fn max_scaled_force(osc: &UnitOscillator) -> f64 {
    let zeta = osc.zeta;
    let scaled = |s: f64| osc.d(s).powf(0.2) * osc.force(s);
    let rho = |s: f64| {
        let (d, v) = (osc.d(s), osc.rate(s));
        v * (d + 2.0 * zeta * v) / 5.0 + d * ((1.0 - 4.0 * zeta * zeta) * v - 2.0 * zeta * d)
    };
    let t0 = osc.max_compression_time();
    let s = bisect(rho, 0.0, t0);
    scaled(s).max(scaled(t0))
}

/// Tsuji's dimensionless damping a(e) = -sqrt(5) ln e / sqrt(pi² + ln² e) = sqrt(5) zeta(e) (docs/laws.md),
/// e = 0 -> sqrt(5); NaN for e outside [0, 1].
pub fn tsuji_damping(e: f64) -> f64 {
    5f64.sqrt() * kelvin_voigt_zeta(e)
}

#[cfg(test)]
mod tests {
    use super::*;
    use SeparationCriterion::{Force, Penetration};

    #[test]
    fn nondimensional_table_with_separation_at_zero_penetration() {
        // docs/references.md#tsuji table (nominal e; dmax/L, tc/T, Fmax/F0), d = 0 separation.
        let table = [
            (1.0, 1.093362, 3.218065, 1.143263),
            (0.9, 1.049184, 3.253683, 1.076691),
            (0.5, 0.860991, 3.518532, 0.863967),
            (0.2, 0.697339, 4.170294, 0.831543),
        ];
        for (e, dmax, tc, fmax) in table {
            let r = tsuji(tsuji_damping(e), Penetration).unwrap();
            assert!((r.restitution - e).abs() < 1e-14, "e = {e}");
            assert!((r.max_penetration - dmax).abs() <= 5e-7, "e = {e}: dmax {}", r.max_penetration);
            assert!((r.duration - tc).abs() <= 5e-7, "e = {e}: tc {}", r.duration);
            assert!((r.max_force - fmax).abs() <= 5e-7, "e = {e}: Fmax {}", r.max_force);
        }
    }

    #[test]
    fn force_separation_gives_the_kelvin_voigt_value() {
        // docs/references.md: separating at F = 0, nominal 0.5 → 0.550283.
        let r = tsuji(tsuji_damping(0.5), Force).unwrap();
        assert!((r.restitution - 0.550283).abs() <= 5e-7, "{}", r.restitution);
        let p = tsuji(tsuji_damping(0.5), Penetration).unwrap();
        assert!(r.duration < p.duration);
        assert_eq!(r.max_force, p.max_force);
        assert_eq!(r.max_compression_time, p.max_compression_time);
    }

    #[test]
    fn undamped_is_hertz() {
        // a = 0: Hertz n = 3/2, dmax = (5/4)^(2/5), tc = 2.9432751843 dmax, Fmax = dmax^(3/2) (docs/references.md).
        let r = tsuji(0.0, Penetration).unwrap();
        let dmax = 1.25_f64.powf(0.4);
        assert!(((r.max_penetration - dmax) / dmax).abs() < 1e-15);
        assert!((r.duration / dmax - 2.9432751843).abs() < 5e-11);
        assert!((r.max_compression_time / dmax - 0.5 * 2.9432751843).abs() < 5e-11);
        assert!(((r.max_force - dmax.powf(1.5)) / r.max_force).abs() < 1e-14);
    }

    #[test]
    fn overdamped_force_separation_against_closed_form_and_ode() {
        // a = 3: zeta = 3/sqrt(5), Omega = 2/sqrt(5), (zeta + Omega)/(zeta - Omega) = 5, zeta/Omega = 3/2, so the
        // Kelvin–Voigt F = 0 formula of docs/references.md gives e = 5^(-3/2).
        let r = tsuji(3.0, Force).unwrap();
        assert!((r.restitution - 5.0_f64.powf(-1.5)).abs() < 1e-15);
        // Duration against classical RK4 on d'' = -d^(3/2) - a d^(1/4) d' until F = 0 (dt = 2.5e-4; the d^(1/4)
        // kink at contact limits it to ~3e-6).
        let a = 3.0;
        let force = |d: f64, v: f64| d.max(0.0).powf(1.5) + a * d.max(0.0).powf(0.25) * v;
        let (tc, _) = super::super::numerics::rk4_until(|d, v| -force(d, v), force, 2.5e-4);
        assert!((r.duration - tc).abs() < 1e-5, "{} vs {tc}", r.duration);
    }

    #[test]
    fn max_force_against_sampling_and_overdamped_cases() {
        // Brute-force sampling of the closed-form oscillator (independent of the bisection).
        for a in [0.3, 1.0, 2.0, 2.2, 3.0, 6.0] {
            let r = tsuji(a, Force).unwrap();
            let osc = UnitOscillator::new(a / 5.0_f64.sqrt());
            let end = osc.force_zero_time();
            let sampled = (0..=100_000)
                .map(|i| {
                    let s = end * f64::from(i) / 100_000.0;
                    osc.d(s).powf(0.2) * osc.force(s)
                })
                .fold(f64::MIN, f64::max)
                * 1.25_f64.powf(0.6);
            assert!(r.max_force >= sampled - 1e-14 && r.max_force - sampled < 1e-8, "a = {a}");
            assert!(r.duration.is_finite() && r.duration > r.max_compression_time);
        }
        assert!(tsuji(5.0_f64.sqrt(), Penetration).is_none());
        assert!(tsuji(-1.0, Force).is_none());
        assert_eq!(tsuji_damping(0.0), 5.0_f64.sqrt());
    }

    /// A light damping's force returns to zero at `d^(5/4) = a |d'|` (`d^(3/2) = a d^(1/4) |d'|`), a penetration
    /// `d_F = (a e)^(4/5)` before the end, which the bodies cross at `|d'| = e` in `d_F/e`: the force criterion's
    /// duration is that much shorter than the penetration criterion's (to first order in `d_F`). Their two ends are
    /// an ulp or two apart in `s`: the gap between them is formed directly, not by subtracting them.
    #[test]
    fn a_light_force_separation_ends_its_own_penetration_before_the_zero() {
        for a in [1e-9, 1e-12, 1e-14, 3.4e-16] {
            let (force, penetration) = (tsuji(a, Force).unwrap(), tsuji(a, Penetration).unwrap());
            let e = penetration.restitution;
            let expected = (a * e).powf(0.8) / e;
            let got = penetration.duration - force.duration;
            assert!((got / expected - 1.0).abs() < 1e-3, "a = {a:e}: {got:e} vs {expected:e}");
        }
    }
}
