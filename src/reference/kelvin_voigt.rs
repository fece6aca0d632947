//! Linear Kelvin–Voigt contact `F = k d + c d'` (docs/references.md; Schwager & Pöschel 2007 for force separation).
//!
//! Nondimensional with `L = v0 sqrt(m*/k)`, `T = sqrt(m*/k) = 1/omega0`, `F0 = k L`, `zeta = c/(2 sqrt(k m*))`:
//! `D'' + 2 zeta D' + D = 0`, `D(0) = 0`, `D'(0) = 1`, force `D + 2 zeta D'`.

use super::numerics::{one_minus_exp_neg_rel, sinc};
use super::{ContactReference, SeparationCriterion};
use std::f64::consts::PI;

/// The unit damped oscillator `D'' + 2 zeta D' + D = 0`, `D(0) = 0`, `D'(0) = 1` in closed form.
/// Also the core of the Tsuji law (which maps onto it exactly).
#[derive(Debug, Clone, Copy)]
pub(crate) struct UnitOscillator {
    pub zeta: f64,
    regime: Regime,
}

#[derive(Debug, Clone, Copy)]
enum Regime {
    /// `zeta < 1`: `D = e^(-zeta s) sin(wd s)/wd`.
    Under { wd: f64 },
    /// `zeta = 1`: `D = s e^(-s)`.
    Critical,
    /// `zeta > 1`: `D = (e^(-l1 s) - e^(-l2 s))/(2 w)`, `w = sqrt(zeta² - 1)`, `l1 = 1/(zeta + w)`, `l2 = zeta + w`.
    Over { w: f64, l1: f64, l2: f64 },
}

impl UnitOscillator {
    /// `zeta >= 0` finite (not checked here).
    pub(crate) fn new(zeta: f64) -> Self {
        let regime = if zeta < 1.0 {
            Regime::Under { wd: ((1.0 - zeta) * (1.0 + zeta)).sqrt() }
        } else if zeta == 1.0 {
            Regime::Critical
        } else {
            let w = (zeta - 1.0).sqrt() * (zeta + 1.0).sqrt(); // no overflow for huge zeta
            Regime::Over { w, l1: 1.0 / (zeta + w), l2: zeta + w }
        };
        Self { zeta, regime }
    }

    /// Penetration `D(s)`.
    pub(crate) fn d(&self, s: f64) -> f64 {
        s * self.d_over_s(s)
    }

    /// `D(s)/s` (value 1 at `s = 0`), cancellation-free.
    pub(crate) fn d_over_s(&self, s: f64) -> f64 {
        match self.regime {
            Regime::Under { wd } => (-self.zeta * s).exp() * sinc(wd * s),
            Regime::Critical => (-s).exp(),
            Regime::Over { w, l1, .. } => (-l1 * s).exp() * one_minus_exp_neg_rel(2.0 * w * s),
        }
    }

    /// Penetration rate `D'(s)`.
    pub(crate) fn rate(&self, s: f64) -> f64 {
        let zeta = self.zeta;
        match self.regime {
            Regime::Under { wd } => (-zeta * s).exp() * ((wd * s).cos() - zeta * s * sinc(wd * s)),
            Regime::Critical => (1.0 - s) * (-s).exp(),
            Regime::Over { w, l1, l2 } => (l2 * (-l2 * s).exp() - l1 * (-l1 * s).exp()) / (2.0 * w),
        }
    }

    /// Nondimensional force `D + 2 zeta D'`.
    pub(crate) fn force(&self, s: f64) -> f64 {
        self.d(s) + 2.0 * self.zeta * self.rate(s)
    }

    /// Time of maximum penetration (`D' = 0`): `acos(zeta)/wd`, 1, or `acosh(zeta)/w`.
    pub(crate) fn max_compression_time(&self) -> f64 {
        match self.regime {
            Regime::Under { wd } => self.zeta.acos() / wd,
            Regime::Critical => 1.0,
            // acosh(zeta) = ln(zeta + w) = ln_1p((zeta - 1) + w), accurate near zeta = 1.
            Regime::Over { w, .. } => ((self.zeta - 1.0) + w).ln_1p() / w,
        }
    }

    /// Maximum penetration `D(t0) = exp(-zeta t0)` (since `sin(wd t0) = wd`, resp. `sinh(w t0) = w`).
    pub(crate) fn max_penetration(&self) -> f64 {
        (-self.zeta * self.max_compression_time()).exp()
    }

    /// Return of `D` to 0, `pi/wd` (underdamped only; otherwise `D > 0` for all `s > 0`).
    pub(crate) fn zero_time(&self) -> Option<f64> {
        match self.regime {
            Regime::Under { wd } => Some(PI / wd),
            _ => None,
        }
    }

    /// Return of the force to 0: `(pi - 2 atan(zeta/wd))/wd = 2 t0` in every regime (Schwager & Pöschel 2007).
    pub(crate) fn force_zero_time(&self) -> f64 {
        2.0 * self.max_compression_time()
    }

    /// From the force's return to 0 to `D`'s (underdamped only): `pi/wd - 2 t0 = 2 asin(zeta)/wd`, formed directly
    /// (a light damping puts the two an ulp apart, where their difference would be rounding alone).
    pub(crate) fn force_zero_gap(&self) -> Option<f64> {
        match self.regime {
            Regime::Under { wd } => Some(2.0 * self.zeta.asin() / wd),
            _ => None,
        }
    }

    /// End of contact for the given criterion (`None`: never separates).
    pub(crate) fn separation_time(&self, separation: SeparationCriterion) -> Option<f64> {
        match separation {
            SeparationCriterion::Penetration => self.zero_time(),
            SeparationCriterion::Force => Some(self.force_zero_time()),
        }
    }

    /// `-D'(s_end)` at either separation event equals `exp(-zeta s_end)`.
    pub(crate) fn restitution(&self, s_end: f64) -> f64 {
        (-self.zeta * s_end).exp()
    }
}

/// Exact nondimensional Kelvin–Voigt impact (docs/references.md), units `L = v0 sqrt(m*/k)`, `T = sqrt(m*/k)`,
/// `F0 = k L`, for damping ratio `zeta = c/(2 sqrt(k m*)) >= 0`.
///
/// * `Penetration` (separation at `d = 0`): `e = exp(-pi zeta/sqrt(1 - zeta²))`, `tc = pi/sqrt(1 - zeta²)`;
///   for `zeta >= 1` the bodies never separate and the result is `None`.
/// * `Force` (separation at `F = 0`, Schwager & Pöschel 2007): `tc = 2 t0` and `e = exp(-zeta tc)`, i.e.
///   `tc = (pi - 2 atan(beta/omega))/omega` underdamped, `2` critically damped (`e = exp(-2)`),
///   `ln((zeta + w)/(zeta - w))/w`, `w = sqrt(zeta² - 1)`, overdamped.
/// * `max_compression_time` `t0 = acos(zeta)/sqrt(1 - zeta²)` (`acosh(zeta)/w` overdamped, 1 critical),
///   `max_penetration = exp(-zeta t0)`.
/// * `max_force`: the force jumps to `2 zeta` at first contact; for `zeta < 1/2` it then rises to a maximum at
///   phase `atan2((1 - 4 zeta²) wd, zeta (3 - 4 zeta²))`, for `zeta >= 1/2` the maximum is `2 zeta` at `t = 0`.
///
/// Closed forms throughout (relative error ~1e-15). `None` also for `zeta < 0` or non-finite `zeta`.
pub fn kelvin_voigt(zeta: f64, separation: SeparationCriterion) -> Option<ContactReference> {
    if !(zeta >= 0.0 && zeta.is_finite()) {
        return None;
    }
    let osc = UnitOscillator::new(zeta);
    let duration = osc.separation_time(separation)?;
    Some(ContactReference {
        restitution: osc.restitution(duration),
        max_penetration: osc.max_penetration(),
        max_compression_time: osc.max_compression_time(),
        duration,
        max_force: max_force(&osc),
    })
}

/// Largest compressive force of the unit oscillator (see [`kelvin_voigt`]).
fn max_force(osc: &UnitOscillator) -> f64 {
    let zeta = osc.zeta;
    match osc.regime {
        Regime::Under { wd } if zeta < 0.5 => {
            // dF/ds = (1 - 4 zeta²) D' - 2 zeta D vanishes at this phase (first critical point: a maximum).
            let z2 = zeta * zeta;
            let phase = ((1.0 - 4.0 * z2) * wd).atan2(zeta * (3.0 - 4.0 * z2));
            osc.force(phase / wd)
        }
        _ => 2.0 * zeta,
    }
}

/// Kelvin–Voigt damping ratio zeta(e) = -ln e / sqrt(pi² + ln² e) (docs/laws.md, exact for separation at
/// d = 0); e = 0 gives 1 (critical, the limit), e = 1 gives 0, and NaN for e outside [0, 1].
pub fn kelvin_voigt_zeta(e: f64) -> f64 {
    if !(0.0..=1.0).contains(&e) {
        return f64::NAN;
    }
    if e == 0.0 {
        return 1.0;
    }
    let log = -e.ln();
    log / PI.hypot(log)
}

#[cfg(test)]
mod tests {
    use super::*;
    use SeparationCriterion::{Force, Penetration};

    fn rel(a: f64, b: f64) -> f64 {
        ((a - b) / b).abs()
    }

    #[test]
    fn restitution_and_duration_at_zeta_0_1_and_0_3_under_both_criteria() {
        // docs/references.md#kelvin-voigt: zeta = 0.1: e = 0.7292476143 (d = 0) or 0.7440793977 (F = 0), durations
        // 3.1574 and 2.9560753247; zeta = 0.3: 0.3723261049 or 0.4509754529, durations 3.2933 and 2.6544745638
        // (checked).
        let cases = [
            (0.1, 0.7292476143, 3.1574, 0.7440793977, 2.9560753247),
            (0.3, 0.3723261049, 3.2933, 0.4509754529, 2.6544745638),
        ];
        for (zeta, e_pen, tc_pen, e_force, tc_force) in cases {
            let p = kelvin_voigt(zeta, Penetration).unwrap();
            let f = kelvin_voigt(zeta, Force).unwrap();
            assert!((p.restitution - e_pen).abs() < 5.1e-11, "zeta = {zeta}: {}", p.restitution);
            assert!((p.duration - tc_pen).abs() < 5.1e-5, "zeta = {zeta}: {}", p.duration);
            assert!((f.restitution - e_force).abs() < 5.1e-11, "zeta = {zeta}: {}", f.restitution);
            assert!((f.duration - tc_force).abs() < 5.1e-11, "zeta = {zeta}: {}", f.duration);
        }
    }

    #[test]
    fn critical_and_overdamped() {
        // docs/references.md: critical damping with F = 0 separation gives e = exp(-2); d = 0 never separates.
        let c = kelvin_voigt(1.0, Force).unwrap();
        assert!(rel(c.restitution, (-2.0_f64).exp()) < 1e-15);
        assert!((c.restitution - 0.135335).abs() < 5e-7);
        assert!(rel(c.duration, 2.0) < 1e-15);
        assert!(rel(c.max_penetration, (-1.0_f64).exp()) < 1e-15); // D = s e^(-s), max at s = 1
        assert_eq!(c.max_force, 2.0); // F = e^(-s)(2 - s), decreasing
        assert!(kelvin_voigt(1.0, Penetration).is_none());
        assert!(kelvin_voigt(3.0, Penetration).is_none());
        // Overdamped, docs/references.md: e = exp(-(beta/Omega) ln((beta + Omega)/(beta - Omega))).
        for zeta in [1.5_f64, 4.0, 100.0] {
            let w = (zeta * zeta - 1.0).sqrt();
            let e = (-(zeta / w) * ((zeta + w) / (zeta - w)).ln()).exp();
            let o = kelvin_voigt(zeta, Force).unwrap();
            assert!(rel(o.restitution, e) < 1e-12, "zeta = {zeta}");
            assert_eq!(o.max_force, 2.0 * zeta);
        }
        // Continuity through zeta = 1.
        let below = kelvin_voigt(1.0 - 1e-9, Force).unwrap();
        let above = kelvin_voigt(1.0 + 1e-9, Force).unwrap();
        for (a, b) in [(below, c), (above, c)] {
            assert!(rel(a.restitution, b.restitution) < 1e-8);
            assert!(rel(a.duration, b.duration) < 1e-8);
            assert!(rel(a.max_penetration, b.max_penetration) < 1e-8);
        }
    }

    #[test]
    fn undamped_is_the_linear_spring() {
        for sep in [Penetration, Force] {
            let r = kelvin_voigt(0.0, sep).unwrap();
            assert_eq!(r.restitution, 1.0);
            assert!(rel(r.duration, PI) < 1e-15);
            assert!(rel(r.max_compression_time, PI / 2.0) < 1e-15);
            assert!(rel(r.max_force, 1.0) < 1e-15);
            assert!(rel(r.max_penetration, 1.0) < 1e-15);
        }
    }

    #[test]
    fn max_force_against_brute_force_sampling() {
        // Independent closed form d = e^(-zeta t) sin(wd t)/wd, F = d + 2 zeta d', sampled finely.
        for zeta in [0.05_f64, 0.2, 0.45, 0.5, 0.7, 0.95] {
            let wd = (1.0 - zeta * zeta).sqrt();
            let force = |t: f64| {
                let d = (-zeta * t).exp() * (wd * t).sin() / wd;
                let v = (-zeta * t).exp() * ((wd * t).cos() - zeta / wd * (wd * t).sin());
                d + 2.0 * zeta * v
            };
            let tc = PI / wd;
            let sampled = (0..=200_000).map(|i| force(tc * f64::from(i) / 200_000.0)).fold(f64::MIN, f64::max);
            let r = kelvin_voigt(zeta, Penetration).unwrap();
            assert!(r.max_force >= sampled - 1e-15 && r.max_force - sampled < 1e-9, "zeta = {zeta}");
            // dmax, t0 also by sampling the independent form.
            let t0 = r.max_compression_time;
            assert!(rel(r.max_penetration, (-zeta * t0).exp() * (wd * t0).sin() / wd) < 1e-14);
            let v0 = (-zeta * t0).exp() * ((wd * t0).cos() - zeta / wd * (wd * t0).sin());
            assert!(v0.abs() < 1e-14);
        }
    }

    #[test]
    fn zeta_map_is_exact_for_penetration_separation() {
        for e in [0.05, 0.3, 0.5, 0.9, 0.999] {
            let r = kelvin_voigt(kelvin_voigt_zeta(e), Penetration).unwrap();
            assert!(rel(r.restitution, e) < 1e-14, "e = {e}");
        }
        assert_eq!(kelvin_voigt_zeta(0.0), 1.0);
        assert_eq!(kelvin_voigt_zeta(1.0), 0.0);
        assert!(kelvin_voigt_zeta(1.1).is_nan());
        assert!(kelvin_voigt_zeta(-0.1).is_nan());
        assert!(kelvin_voigt(-0.1, Force).is_none());
        assert!(kelvin_voigt(f64::NAN, Force).is_none());
    }

    #[test]
    fn force_separation_state_is_consistent() {
        // At F = 0 separation d = -2 zeta d' = 2 zeta e > 0, and -d' = e.
        for zeta in [0.1, 0.6, 1.0, 2.0] {
            let osc = UnitOscillator::new(zeta);
            let s = osc.force_zero_time();
            assert!(osc.force(s).abs() < 1e-15);
            assert!(rel(-osc.rate(s), osc.restitution(s)) < 1e-14, "zeta = {zeta}");
            assert!(osc.rate(osc.max_compression_time()).abs() < 1e-15);
        }
    }
}
