//! Thornton's elastic–perfectly plastic impact of spheres (Thornton, J. Appl. Mech. 64, 383 (1997);
//! docs/references.md#thornton): Hertz loading to the yield penetration `d_y`, then the plastic line tangent to it,
//! and Hertzian unloading with the enlarged radius of the deepest point.
//!
//! In the units of the module (m* = K = v0 = 1, K the Hertz stiffness `(4/3) E* sqrt(R*)`), the scene enters through
//! `d_y / L` alone: the yield speed is `V_y / v0 = sqrt(4/5) (d_y/L)^(5/4)`, from `(1/2) m* V_y² = (2/5) K d_y^(5/2)`.

use super::ContactReference;
use super::hertz::hertz_elastic;
use super::numerics::{beta, integrate};
use std::f64::consts::FRAC_PI_2;

/// Thornton's closed form of e against the impact speed over the yield speed, `ratio = V_i / V_y`:
/// `e = sqrt(6 sqrt(3)/5) sqrt(1 - x²/6) [x / (x + 2 sqrt(6/5 - x²/5))]^(1/4)` with `x = V_y / V_i`, and `e = 1` for
/// `ratio <= 1` (no yield). e = 0.9306, 0.7733, 0.6586, 0.3743 at ratios 2, 5, 10, 100; it falls as
/// `ratio^(-1/4)` at high speed. NaN for a NaN or negative ratio.
pub fn thornton_restitution(ratio: f64) -> f64 {
    if ratio.is_nan() || ratio < 0.0 {
        return f64::NAN;
    }
    if ratio <= 1.0 {
        return 1.0;
    }
    let x = 1.0 / ratio;
    let x2 = x * x;
    (6.0 * 3f64.sqrt() / 5.0).sqrt() * (1.0 - x2 / 6.0).sqrt() * (x / (x + 2.0 * (1.2 - 0.2 * x2).sqrt())).powf(0.25)
}

/// The yield speed over the approach speed, `V_y / v0 = sqrt(4/5) (d_y/L)^(5/4)`, for a scaled yield penetration
/// `yield_penetration = d_y / L` (infinite: never yields).
pub fn thornton_yield_speed(yield_penetration: f64) -> f64 {
    (0.8f64).sqrt() * yield_penetration.powf(1.25)
}

/// The exact nondimensional impact for a scaled yield penetration `d_y / L > 0` (see the module docs): below the
/// yield speed it is Hertz's; above it, energy gives the deepest point (`1/2 = (2/5) d_y^(5/2) + F_y x + (k_p/2) x²`,
/// `x = d_max - d_y`, `F_y = d_y^(3/2)`, `k_p = (3/2) d_y^(1/2)`) and the peak force, the time to it is the Hertz
/// part (a quadrature) plus the plastic part (a shifted harmonic oscillator, closed form), the restitution is
/// Thornton's closed form, and the unloading is a Hertz half-impact of stiffness K_p at the speed e. NaN fields for
/// a yield penetration that is not positive (or NaN).
pub fn thornton(yield_penetration: f64) -> ContactReference {
    let d_y = yield_penetration;
    if d_y.is_nan() || d_y <= 0.0 {
        return ContactReference::UNDEFINED;
    }
    // The elastic maximum (5/4)^(2/5): no yield at or below it.
    let elastic = hertz_elastic(1.5);
    let reach = elastic.max_penetration;
    if d_y >= reach {
        return elastic;
    }
    let force_y = d_y * d_y.sqrt();
    let slope = 1.5 * d_y.sqrt();
    // The energy left at d_y, 1/2 - (2/5) d_y^(5/2) = (1 - (d_y/reach)^(5/2))/2, without cancellation.
    let left = -0.5 * (2.5 * (d_y / reach).ln()).exp_m1();
    let x = 2.0 * left / (force_y + (force_y * force_y + 2.0 * slope * left).sqrt());
    let max_penetration = d_y + x;
    let max_force = force_y + slope * x;

    // Hertz part, 0 -> d_y at energy 1/2: d = reach (1 - w²) removes the root singularity at the elastic maximum;
    // 1 - (1 - w²)^(5/2) as -expm1(2.5 ln(1 - w²)).
    let w_y = (1.0 - d_y / reach).sqrt();
    let hertz_part = integrate(
        |w: f64| {
            let gap = -(2.5 * (-w * w).ln_1p()).exp_m1();
            if w == 0.0 { 2.0 * reach / 2.5f64.sqrt() } else { 2.0 * reach * w / gap.sqrt() }
        },
        w_y,
        1.0,
    );
    // Plastic part: u = x + F_y/k_p obeys u'' = -k_p u; from u0 = F_y/k_p at speed v1 to its maximum.
    let (omega, u0, v1) = (slope.sqrt(), force_y / slope, (2.0 * left).sqrt());
    let plastic_part = (FRAC_PI_2 - (u0 * omega).atan2(v1)) / omega;
    let max_compression_time = hertz_part + plastic_part;

    let restitution = thornton_restitution(1.0 / thornton_yield_speed(d_y));
    // Unloading: Hertz of stiffness K_p through the relief delta = (F*/K_p)^(2/3) at the separation speed e; its
    // half-impact takes (2/5) B(2/5, 1/2) delta / e.
    let f = max_force / force_y;
    let stiffness = (((2.0 * f + 1.0) / 3.0).powf(1.5) / f).sqrt();
    let relief = (max_force / stiffness).powf(2.0 / 3.0);
    let unloading_time = 0.4 * beta(0.4, 0.5) * relief / restitution;
    ContactReference {
        restitution,
        max_penetration,
        max_compression_time,
        duration: max_compression_time + unloading_time,
        max_force,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Thornton's published values (physics reference §9): e = 0.9306, 0.7733, 0.6586, 0.3743 at V/V_y = 2, 5, 10,
    /// 100, and 1 at and below V_y.
    #[test]
    fn closed_form_gives_thorntons_table() {
        for (ratio, e) in [(2.0, 0.9306), (5.0, 0.7733), (10.0, 0.6586), (100.0, 0.3743)] {
            assert!((thornton_restitution(ratio) - e).abs() < 5e-5, "ratio {ratio}");
        }
        assert_eq!(thornton_restitution(1.0), 1.0);
        assert_eq!(thornton_restitution(0.3), 1.0);
        assert!((thornton_restitution(1.0 + 1e-9) - 1.0).abs() < 1e-8);
    }

    /// The energy route: e² = (unloading work) / (1/2) = (4/5) F* delta, from the deepest point that energy gives, is
    /// the closed form to rounding over four decades of speed; the time at the onset of yield is Hertz's half.
    #[test]
    fn energy_of_the_unloading_is_the_closed_form() {
        for ratio in [1.01, 1.5, 2.0, 7.0, 30.0, 100.0, 1e4] {
            // V_y / v0 = 1/ratio = sqrt(4/5) d_y^(5/4).
            let d_y = (1.0 / ratio / 0.8f64.sqrt()).powf(0.8);
            let r = thornton(d_y);
            let f = r.max_force / (d_y * d_y.sqrt());
            let stiffness = (((2.0 * f + 1.0) / 3.0).powf(1.5) / f).sqrt();
            let relief = (r.max_force / stiffness).powf(2.0 / 3.0);
            let e = (0.8 * r.max_force * relief).sqrt();
            assert!((e - r.restitution).abs() < 1e-13, "ratio {ratio}: {e} against {}", r.restitution);
        }
        let hertz = hertz_elastic(1.5);
        let onset = thornton(hertz.max_penetration * (1.0 - 1e-12));
        assert!((onset.max_compression_time / hertz.max_compression_time - 1.0).abs() < 1e-6);
        assert!((onset.duration / hertz.duration - 1.0).abs() < 1e-6);
        assert_eq!(thornton(hertz.max_penetration), hertz);
        assert!(thornton(0.0).restitution.is_nan() && thornton(f64::NAN).duration.is_nan());
    }
}
