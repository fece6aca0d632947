//! Contact laws: each law's force F(d, d') beside its damping-from-restitution map, with its source.
//!
//! A law is data ([`ContactLaw`]: kind, stiffness, exponent, damping parameter) plus a pure force function.
//! Adding a law is adding a [`LawKind`] variant, its entry in [`catalogue`], its force in [`ContactLaw::split_force`]
//! and (if it has one) its map in [`damping`].

pub mod catalogue;
pub mod damping;

pub use crate::reference::Separation;
pub use catalogue::{Family, LawKind};

/// A contact law with its parameters resolved to numbers (SI units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactLaw {
    /// Which law.
    pub kind: LawKind,
    /// K in N/m^n (k in N/m for Kelvin–Voigt).
    pub stiffness: f64,
    /// n in K d^n (1 for Kelvin–Voigt, 3/2 for Tsuji and Brilliantov).
    pub exponent: f64,
    /// The law's own damping parameter in its own units (see [`LawKind::damping_units`]); 0 for Hertz.
    pub damping: f64,
    /// sqrt(m* K), N s/m^(5/4) — the Tsuji damping scale (docs/laws.md); unused by other laws.
    pub tsuji_scale: f64,
    /// d_y, m: the penetration at which a `thornton` contact starts to yield (infinite for every other law, and for
    /// bodies that never yield).
    pub yield_penetration: f64,
}

/// `d^n` for a penetration `d >= 0`: the common exponents by square roots and products (Hertz's 3/2 as `d sqrt(d)`,
/// several times cheaper than `powf`, which the general path would otherwise call at every stage of every step), any
/// other by `powf`. Against 60-digit values the products are within 1.3 ulps (3/2) and 1.9 ulps (5/2), `powf` within
/// about half an ulp. (A penetration of -0 gives -0 for 1/2 and 5/2, where `powf` gives +0: the same zero force.
/// Taking it as +0 there cost the general path 10–15 % of its speed through the compiler's schedule of the stage loop,
/// docs/numerics.md.)
#[inline]
pub fn power(d: f64, n: f64) -> f64 {
    if n == 1.5 {
        d * d.sqrt()
    } else if n == 1.0 {
        d
    } else if n == 0.5 {
        d.sqrt()
    } else if n == 2.5 {
        d * d * d.sqrt()
    } else if n == 2.0 {
        d * d
    } else {
        d.powf(n)
    }
}

/// Contact force split into its elastic and dissipative parts, N (compressive positive).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ForceParts {
    /// The conservative part, a function of penetration alone.
    pub elastic: f64,
    /// The damping part, which does work `dissipative * rate` on the relative motion.
    pub dissipative: f64,
}

impl ForceParts {
    /// Total force, N.
    pub fn total(&self) -> f64 {
        self.elastic + self.dissipative
    }
}

impl ContactLaw {
    /// Force parts at penetration `d` (m) and penetration rate `rate` (m/s). Zero when `d < 0`, so a step that
    /// overshoots separation never takes a fractional power of a negative number. At `d = 0` it is the limit from
    /// inside the contact: zero for every law but Kelvin–Voigt, whose force jumps to c d' at first contact.
    #[inline]
    pub fn split_force(&self, d: f64, rate: f64) -> ForceParts {
        if d < 0.0 {
            return ForceParts { elastic: 0.0, dissipative: 0.0 };
        }
        let (k, c) = (self.stiffness, self.damping);
        match self.kind.family() {
            Family::Elastic => ForceParts { elastic: k * power(d, self.exponent), dissipative: 0.0 },
            Family::Hysteresis => {
                // F = K d^n (1 + alpha d')  (Hunt & Crossley 1975 and its damping maps)
                let spring = k * power(d, self.exponent);
                ForceParts { elastic: spring, dissipative: spring * c * rate }
            }
            // F = k d + c d'  (linear Kelvin–Voigt)
            Family::Linear => ForceParts { elastic: k * d, dissipative: c * rate },
            Family::Tsuji => {
                // F = K d^(3/2) + a sqrt(m* K) d^(1/4) d'  (Tsuji et al. 1992)
                let quarter = d.sqrt().sqrt();
                ForceParts { elastic: k * d * d.sqrt(), dissipative: c * self.tsuji_scale * quarter * rate }
            }
            Family::Viscoelastic => {
                // F = K (d^(3/2) + (3/2) A d^(1/2) d')  (Brilliantov et al. 1996)
                let root = d.sqrt();
                ForceParts { elastic: k * d * root, dissipative: 1.5 * k * c * root * rate }
            }
            // Loading from an undented surface; a remembered deepest point is `split_force_after`'s.
            Family::Plastic => ForceParts { elastic: self.loading(d), dissipative: 0.0 },
        }
    }

    /// Whether the force depends on the deepest penetration reached so far (the `thornton` law), which a model
    /// then carries in its state ([`ContactLaw::split_force_after`]).
    #[inline]
    pub fn yields(&self) -> bool {
        self.kind.family() == Family::Plastic
    }

    /// [`ContactLaw::split_force`] for a contact whose deepest penetration so far is `deepest` (m): a yielding law
    /// unloads (and reloads) elastically below it; every other law ignores it.
    #[inline]
    pub fn split_force_after(&self, d: f64, rate: f64, deepest: f64) -> ForceParts {
        if !self.yields() {
            return self.split_force(d, rate);
        }
        ForceParts { elastic: self.plastic_force(d, deepest), dissipative: 0.0 }
    }

    /// The `thornton` loading curve at penetration `d >= 0` (m), N: Hertz K d^(3/2) to the yield penetration d_y,
    /// then the line tangent to it there, K d_y^(3/2) + (3/2) K d_y^(1/2) (d - d_y) — Thornton's plastic loading
    /// F_y + pi p_y R* (d - d_y), since pi p_y R* = (3/2) K d_y^(1/2) for d_y = (pi p_y / (2 E*))² R*.
    #[inline]
    fn loading(&self, d: f64) -> f64 {
        let (k, yielding) = (self.stiffness, self.yield_penetration);
        if d <= yielding {
            k * d * d.sqrt()
        } else {
            let root = yielding.sqrt();
            k * root * (yielding + 1.5 * (d - yielding))
        }
    }

    /// The `thornton` unloading curve from a deepest penetration `deepest` > d_y (m): its stiffness K_p (N/m^(3/2))
    /// and the depth of the permanent dent d_p (m), where the force returns to zero. Thornton's enlarged radius
    /// R_p* = (4 E* / (3 F*)) ((2 F* + F_y) / (2 pi p_y))^(3/2) for a peak force F*, written with f = F*/F_y, is
    /// R_p*/R* = ((2 f + 1)/3)^(3/2) / f (1 at the onset of yield), so K_p = K sqrt(R_p*/R*); the curve
    /// K_p (d - d_p)^(3/2) passes through (deepest, F*).
    fn unloading(&self, deepest: f64) -> (f64, f64) {
        let yielding = self.yield_penetration;
        let peak = self.loading(deepest);
        let f = peak / (self.stiffness * yielding * yielding.sqrt());
        let ratio = ((2.0 * f + 1.0) / 3.0).powf(1.5) / f;
        let stiffness = self.stiffness * ratio.sqrt();
        let relief = (peak / stiffness).powf(2.0 / 3.0);
        (stiffness, deepest - relief)
    }

    /// The `thornton` force at penetration `d` (m) after a deepest penetration `deepest` (m), N: the loading curve
    /// at or beyond the deepest point (or while it has not yielded), the unloading curve below it — zero at and
    /// above the dent (never a power of a negative number).
    fn plastic_force(&self, d: f64, deepest: f64) -> f64 {
        if d <= 0.0 {
            return 0.0;
        }
        if d >= deepest || deepest <= self.yield_penetration {
            return self.loading(d);
        }
        let (stiffness, dent) = self.unloading(deepest);
        let x = d - dent;
        if x > 0.0 { stiffness * x * x.sqrt() } else { 0.0 }
    }

    /// The penetration d_y (m) at which a yielding contact starts to yield; `None` for the other laws and for a
    /// yielding law whose bodies never yield (an infinite yield pressure).
    pub fn yield_onset(&self) -> Option<f64> {
        (self.yields() && self.yield_penetration.is_finite()).then_some(self.yield_penetration)
    }

    /// The depth of the permanent dent after a deepest penetration `deepest` (m): where a yielding contact's force
    /// returns to zero (0 for an unyielded contact and for every other law).
    pub fn dent(&self, deepest: f64) -> f64 {
        if self.yields() && deepest > self.yield_penetration { self.unloading(deepest).1 } else { 0.0 }
    }

    /// Total contact force, N.
    pub fn force(&self, d: f64, rate: f64) -> f64 {
        self.split_force(d, rate).total()
    }

    /// The damping's size at a contact's own scales: |dissipative| / elastic force at penetration `length` (m) and
    /// rate `speed` (m/s) — alpha v0 for the hysteresis family, a for Tsuji, 2 zeta (about) for Kelvin–Voigt, 0 for
    /// Hertz. Used to scale the dissipated-energy integral so that it is accurate relative to itself.
    pub fn damping_ratio(&self, length: f64, speed: f64) -> f64 {
        let parts = self.split_force(length, speed);
        if parts.elastic > 0.0 { parts.dissipative.abs() / parts.elastic } else { 0.0 }
    }

    /// A function of (d, d') whose zero where it falls is a force separation, continuous through d = 0
    /// (docs/numerics.md): the force divided by the power of d in its damping term, continued to d < 0 by the law's
    /// own expression (k d + c d'; K d |d|^(1/4) + a sqrt(m* K) d' for Tsuji; K (d + (3/2) A d') for Brilliantov).
    /// Its units are N/m^q (q the power divided out). For laws that never turn tensile it is the penetration (m).
    pub fn separation_function(&self, d: f64, rate: f64) -> f64 {
        let (k, c) = (self.stiffness, self.damping);
        match self.kind.family() {
            Family::Elastic | Family::Hysteresis | Family::Plastic => d,
            Family::Linear => k * d + c * rate,
            Family::Tsuji => k * d * d.abs().sqrt().sqrt() + c * self.tsuji_scale * rate,
            Family::Viscoelastic => k * (d + 1.5 * c * rate),
        }
    }

    /// [`ContactLaw::separation_function`] after a deepest penetration `deepest` (m): for a yielding law the
    /// penetration beyond the permanent dent, d - d_p (m), whose fall through zero is where its force returns to
    /// zero; for every other law the function without memory.
    pub fn separation_function_after(&self, d: f64, rate: f64, deepest: f64) -> f64 {
        if self.yields() { d - self.dent(deepest) } else { self.separation_function(d, rate) }
    }

    /// The penetration (m) at which the force vanishes at penetration rate `rate` (m/s): the zero in d of
    /// [`ContactLaw::separation_function`], -c d'/k (Kelvin–Voigt), (-a sqrt(m* K) d'/K)^(4/5) (Tsuji),
    /// -(3/2) A d' (Brilliantov); 0 for a rate >= 0 and for laws that never turn tensile. At a located force
    /// separation this is the separation penetration as accurate as the rate, where the integrated penetration
    /// carries the event's time resolution (relative errors up to 1e-5 when the window between F = 0 and d = 0 is
    /// tiny: light damping).
    pub fn separation_penetration(&self, rate: f64) -> f64 {
        if rate >= 0.0 {
            return 0.0;
        }
        let (k, c) = (self.stiffness, self.damping);
        match self.kind.family() {
            Family::Elastic | Family::Hysteresis | Family::Plastic => 0.0,
            Family::Linear => -c * rate / k,
            Family::Tsuji => (-c * self.tsuji_scale * rate / k).powf(0.8),
            Family::Viscoelastic => -1.5 * c * rate,
        }
    }

    /// Elastic (spring) energy stored at penetration `d` (m), the integral of the elastic force from 0 to d, J:
    /// K d^(n+1)/(n+1) (k d²/2 for Kelvin–Voigt, (2/5) K d^(5/2) for Tsuji and Brilliantov); zero for d <= 0.
    pub fn elastic_energy(&self, d: f64) -> f64 {
        if d <= 0.0 {
            return 0.0;
        }
        let n = self.exponent;
        self.stiffness * power(d, n + 1.0) / (n + 1.0)
    }

    /// [`ContactLaw::elastic_energy`] after a deepest penetration `deepest` (m): for a yielding law the energy the
    /// unloading curve through this point gives back, (2/5) K_p (d - d_p)^(5/2) (Hertz's below d_y); the rest of
    /// the work done on the contact went into the plastic dent.
    pub fn elastic_energy_after(&self, d: f64, deepest: f64) -> f64 {
        if !self.yields() || d <= 0.0 {
            return self.elastic_energy(d);
        }
        let deepest = deepest.max(d);
        if deepest <= self.yield_penetration {
            return 0.4 * self.stiffness * d * d * d.sqrt();
        }
        let (stiffness, dent) = self.unloading(deepest);
        let x = (d - dent).max(0.0);
        0.4 * stiffness * x * x * x.sqrt()
    }

    /// Partial derivatives (dF/dd in N/m, dF/dd' in N s/m), for the force-rate event dF/dt = F_d d' + F_v d''.
    /// Zero outside the contact, and at `d = 0` for the power laws (whose gradient is singular there).
    pub fn force_gradient(&self, d: f64, rate: f64) -> (f64, f64) {
        let (k, c, n) = (self.stiffness, self.damping, self.exponent);
        let family = self.kind.family();
        if d < 0.0 || (d == 0.0 && family != Family::Linear) {
            return (0.0, 0.0);
        }
        match family {
            Family::Elastic => (k * n * power(d, n - 1.0), 0.0),
            Family::Hysteresis => {
                let spring = k * power(d, n);
                (n * spring / d * (1.0 + c * rate), spring * c)
            }
            Family::Linear => (k, c),
            Family::Tsuji => {
                let quarter = d.sqrt().sqrt();
                let scale = c * self.tsuji_scale;
                (1.5 * k * d.sqrt() + 0.25 * scale * quarter / d * rate, scale * quarter)
            }
            Family::Viscoelastic => {
                let root = d.sqrt();
                (1.5 * k * root + 0.75 * k * c / root * rate, 1.5 * k * c * root)
            }
            Family::Plastic => (self.plastic_stiffness(d, d), 0.0),
        }
    }

    /// [`ContactLaw::force_gradient`] after a deepest penetration `deepest` (m).
    pub fn force_gradient_after(&self, d: f64, rate: f64, deepest: f64) -> (f64, f64) {
        if !self.yields() {
            return self.force_gradient(d, rate);
        }
        if d <= 0.0 {
            return (0.0, 0.0);
        }
        (self.plastic_stiffness(d, deepest), 0.0)
    }

    /// dF/dd of the `thornton` force at `d > 0` after `deepest`, N/m.
    fn plastic_stiffness(&self, d: f64, deepest: f64) -> f64 {
        let (k, yielding) = (self.stiffness, self.yield_penetration);
        if d >= deepest || deepest <= yielding {
            return 1.5 * k * d.min(yielding).sqrt();
        }
        let (stiffness, dent) = self.unloading(deepest);
        let x = d - dent;
        if x > 0.0 { 1.5 * stiffness * x.sqrt() } else { 0.0 }
    }
}

#[cfg(test)]
mod tests {
    use super::power;

    /// The cheap powers agree with `powf` (libm's, within about half an ulp) to 2.5 ulps (measured against 60-digit
    /// values: 1.3 ulps for 3/2, 1.9 for 5/2), over penetrations from 1e-100 to 1e100 in irrational steps; the
    /// exponents without a cheap form are `powf` itself; a penetration of zero, of either sign, gives zero.
    #[test]
    fn powers_of_a_penetration_are_the_library_powers_to_an_ulp_or_two() {
        let mut d = 1e-100_f64;
        let mut checked = 0;
        while d < 1e100 {
            for n in [0.5, 1.5, 2.5] {
                let exact = d.powf(n);
                assert!(
                    (power(d, n) - exact).abs() <= 2.5 * f64::EPSILON * exact,
                    "{d}^{n}: {} against {exact}",
                    power(d, n)
                );
            }
            for n in [1.0, 2.0, 1.3, 0.8, 3.0] {
                assert_eq!(power(d, n), d.powf(n), "{d}^{n}");
            }
            d *= std::f64::consts::E.sqrt();
            checked += 1;
        }
        assert!(checked > 900);
        for n in [0.5, 1.0, 1.5, 2.0, 2.5, 1.3, 3.0] {
            for zero in [0.0, -0.0] {
                assert_eq!(power(zero, n), 0.0, "{zero:?}^{n}");
            }
            assert!(power(0.0, n).is_sign_positive());
        }
    }
}
