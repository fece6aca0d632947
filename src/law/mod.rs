//! Contact laws: each law's force F(d, d') beside its damping-from-restitution map, with its source.
//!
//! A law is data ([`ContactLaw`]: kind, stiffness, exponent, damping parameter) plus a pure force function.
//! Adding a law is adding a [`LawKind`] variant, its entry in [`catalogue`], its force in [`ContactLaw::split_force`]
//! and (if it has one) its map in [`damping`].

pub mod catalogue;
pub mod damping;
pub mod dashpot;

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
    /// MuJoCo's `solimp` [d_min, d_max, width (m), midpoint, power] for the `mujoco` law: the impedance d(d) rises
    /// from d_min at first touch to d_max at a penetration of `width` ([`ContactLaw::impedance`]); unused by the
    /// other laws ([`NO_SOLIMP`]).
    pub solimp: [f64; 5],
    /// ADAMS' penetration at full damping d_max, m, for `adams-impact` (infinite, unused, for the other laws).
    pub ramp: f64,
}

/// Up to two penetrations where a law's force is not smooth (see [`ContactLaw::kinks`]): the first `count` of `at`,
/// ascending.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Kinks {
    pub at: [f64; 2],
    pub count: usize,
}

impl Kinks {
    /// The kinks, ascending.
    pub fn as_slice(&self) -> &[f64] {
        &self.at[..self.count]
    }

    /// The same kinks in units of `length`.
    pub fn scaled(self, length: f64) -> Kinks {
        Kinks { at: self.at.map(|d| d / length), count: self.count }
    }
}

/// The smallest exponent n of K d^n a scene may give: a flat punch's (docs/laws.md#which-exponents). Below it no
/// indenter's profile gives the law, its stiffness n K d^(n-1) is infinite at first touch, and as n falls to 0 the
/// force becomes a step of height K at first contact, reached in no time.
pub const MIN_EXPONENT: f64 = 1.0;

/// The largest exponent n of K d^n a scene may give: beyond a cone's 2, the published fits of soft and rough
/// contacts reach about 3 (docs/laws.md#which-exponents).
pub const MAX_EXPONENT: f64 = 3.0;

/// MuJoCo's default `solimp`, [0.9, 0.95, 0.001, 0.5, 2]: what a law that is not `mujoco` carries, unused.
pub const NO_SOLIMP: [f64; 5] = [0.9, 0.95, 0.001, 0.5, 2.0];

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

/// A force that never pulls: its parts as they are while they push, and the damping cut to cancel the spring where
/// they would pull (the cut is the damper's: what the spring then loses is dissipated).
#[inline]
fn never_pulling(elastic: f64, dissipative: f64) -> ForceParts {
    ForceParts { elastic, dissipative: dissipative.max(-elastic) }
}

/// ADAMS' cubic STEP from 0 at s = 0 to 1 at s = 1, s²(3 - 2s), and its derivative 6 s (1 - s); 0 below, 1 above.
#[inline]
fn cubic_step(s: f64) -> (f64, f64) {
    if s <= 0.0 {
        (0.0, 0.0)
    } else if s >= 1.0 {
        (1.0, 0.0)
    } else {
        (s * s * (3.0 - 2.0 * s), 6.0 * s * (1.0 - s))
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
                // F = K d^n (1 + alpha d')  (Hunt & Crossley 1975 and its damping maps): it never pulls, as
                // `1 + alpha d'` stays positive along the motion; where a creeping restitution brings it within
                // rounding of zero, the sum is kept from rounding below it.
                let spring = k * power(d, self.exponent);
                never_pulling(spring, spring * c * rate)
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
            // F = K d^n + c d'
            Family::Dashpot => ForceParts { elastic: k * power(d, self.exponent), dissipative: c * rate },
            // F = d(d) (k d(d) d + c d') with k, c already times m* (MuJoCo per unit mass), never pulling.
            Family::Impedance => {
                let (impedance, _) = self.impedance(d);
                never_pulling(impedance * impedance * k * d, impedance * c * rate)
            }
            // F = K d^n + c_max S(d/d_max) d', S the cubic step, never pulling.
            Family::Ramp => {
                let (step, _) = cubic_step(d / self.ramp);
                never_pulling(k * power(d, self.exponent), c * step * rate)
            }
        }
    }

    /// MuJoCo's impedance at penetration `d >= 0` (m) and its derivative (1/m), from `solimp` [d_min, d_max, width,
    /// midpoint, power]: with x = d / width, d_min + (d_max - d_min) y(x), y = x^p / m^(p-1) up to the midpoint m and
    /// 1 - (1 - x)^p / (1 - m)^(p-1) beyond it, d_max from x = 1 on (MuJoCo's `getimpedance`).
    pub fn impedance(&self, d: f64) -> (f64, f64) {
        let [low, high, width, middle, p] = self.solimp;
        let x = d.abs() / width;
        if x >= 1.0 {
            return (high, 0.0);
        }
        // Written with ratios at most 1 (x^p / m^(p-1) = m (x/m)^p), so that a large power neither overflows nor
        // divides by an underflowed m^(p-1).
        let (y, slope) = if x <= middle {
            let r = x / middle;
            (middle * r.powf(p), p * r.powf(p - 1.0))
        } else {
            let q = 1.0 - middle;
            let r = (1.0 - x) / q;
            (1.0 - q * r.powf(p), p * r.powf(p - 1.0))
        };
        (low + (high - low) * y, (high - low) * slope / width)
    }

    /// ∫₀^d d(s)² s ds (m²) for the impedance of `solimp`, in closed form (piecewise powers): the `mujoco` law's
    /// elastic energy is k times it.
    fn impedance_moment(&self, d: f64) -> f64 {
        let [low, high, width, m, p] = self.solimp;
        let spread = high - low;
        let x = (d / width).min(1.0);
        // I1 = ∫₀^x y(u) u du, I2 = ∫₀^x y(u)² u du, y the sigmoid of `impedance`.
        // Each power written as a ratio at most 1 (x^(p+2) / m^(p-1) = m³ (x/m)^(p+2), ...), as in `impedance`.
        let below = |x: f64| {
            let r = x / m;
            (m.powi(3) * r.powf(p + 2.0) / (p + 2.0), m.powi(4) * r.powf(2.0 * p + 2.0) / (2.0 * p + 2.0))
        };
        let (i1, i2) = if x <= m {
            below(x)
        } else {
            let q = 1.0 - m;
            // ∫ (1 - u)^r u du from m to x = G(q) - G(1 - x), G(t) = t^(r+1)/(r+1) - t^(r+2)/(r+2), divided by
            // q^(r - s) (s = 1 for r = p, 2 for r = 2p) and written with t/q <= 1: q^(s+1) (t/q)^(r+1)/(r+1) - ...
            let g = |t: f64, r: f64, s: i32| {
                let ratio = t / q;
                q.powi(s + 1) * ratio.powf(r + 1.0) / (r + 1.0) - q.powi(s + 2) * ratio.powf(r + 2.0) / (r + 2.0)
            };
            let (a1, a2) = below(m);
            let square = (x * x - m * m) / 2.0;
            let one = g(q, p, 1) - g(1.0 - x, p, 1);
            let two = g(q, 2.0 * p, 2) - g(1.0 - x, 2.0 * p, 2);
            (a1 + square - one, a2 + square - 2.0 * one + two)
        };
        let beyond = if d > width { (d * d - width * width) / 2.0 } else { 0.0 };
        low * low * d * d / 2.0
            + width * width * (2.0 * low * spread * i1 + spread * spread * i2)
            + (2.0 * low * spread + spread * spread) * beyond
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

    /// The penetrations (m, ascending) where the force is continuous but not smooth along a phase (`compressing`:
    /// the loading, else the unloading), which a driver makes step boundaries so that no step of a high-order
    /// integrator straddles them: a yielding law's onset of yield (loading only: it unloads on a smooth curve); the
    /// `mujoco` impedance's midpoint and width (its second derivative jumps there; its first too at the width for
    /// power 1); `adams-impact`'s d_max, where its cubic step ends.
    pub fn kinks(&self, compressing: bool) -> Kinks {
        let at = match self.kind.family() {
            Family::Plastic if compressing => self.yield_onset().map_or([f64::NAN; 2], |d| [d, f64::NAN]),
            Family::Impedance => [self.solimp[3] * self.solimp[2], self.solimp[2]],
            Family::Ramp if self.ramp.is_finite() => [self.ramp, f64::NAN],
            _ => [f64::NAN; 2],
        };
        Kinks { count: at.iter().filter(|d| d.is_finite()).count(), at }
    }

    /// The fraction of a scene's tolerances a model integrates this law at: a hundredth for `adams-impact`, whose
    /// cubic damping step the step-size control underestimates near first touch and separation (measured in the
    /// stress run: e off by up to 1e-9 at the default rtol 1e-10, 1e-12 at a hundredth of it, against an
    /// independent fixed-step integration), and for `mujoco`, whose impedance d_min + (d_max - d_min) m (x/m)^p
    /// is as rough at first touch and separation as its power p is close to an integer above it (the p-th
    /// derivative is infinite there, with a small coefficient the error estimate misses): over p from 1.1 to 3.95
    /// on stress case 18040 of seed 424242, the energy balance closed to 1.4e-9 of m* v0² at the default rtol
    /// 1e-10 (p = 1.95; 4.4e-10 at p = 2.9), and to 4.4e-11 at a hundredth of it; 1 for every other law.
    pub fn tolerance_factor(&self) -> f64 {
        if matches!(self.kind.family(), Family::Ramp | Family::Impedance) { 0.01 } else { 1.0 }
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
            Family::Dashpot => k * d * power(d.abs(), self.exponent - 1.0) + c * rate,
            // The force over d(d), continued to d < 0 with d(|d|): k d(d) d + c d'.
            Family::Impedance => k * self.impedance(d).0 * d + c * rate,
            // The damping vanishes at first touch, so the force can push again after a zero: the contact ends where
            // the penetration returns to zero.
            Family::Ramp => d,
        }
    }

    /// A law that never pulls cuts its damper where the spring and the damper together would pull (`mujoco`,
    /// `adams-impact`): the force, continuous, loses its smoothness there. This is the uncut force's sign carrier
    /// at penetration `d` (m) and rate `rate` (m/s), continued — d(d) (k d(d) d + c d') over d(d) > 0 for `mujoco`,
    /// K d^n + c S(d/d_max) d' for `adams-impact` — whose zeros in restitution a driver makes step boundaries
    /// (where the cut begins, and for `adams-impact`, whose damping vanishes at first touch, where the force may push
    /// again); `None` for the laws that never cut.
    pub fn uncut_force(&self, d: f64, rate: f64) -> Option<f64> {
        let (k, c) = (self.stiffness, self.damping);
        match self.kind.family() {
            Family::Impedance => Some(self.separation_function(d, rate)),
            Family::Ramp => {
                let (step, _) = cubic_step(d / self.ramp);
                Some(k * d * power(d.abs(), self.exponent - 1.0) + c * step * rate)
            }
            _ => None,
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
    /// tiny: light damping). `near` (m), the integrated penetration at the separation, picks the zero where there
    /// are several: MuJoCo's spring d(d)² k d with an impedance that falls across `solimp`'s width (d_min > d_max)
    /// can give d(d) d = -c d'/k at more than one penetration.
    pub fn separation_penetration(&self, rate: f64, near: f64) -> f64 {
        if rate >= 0.0 {
            return 0.0;
        }
        let (k, c) = (self.stiffness, self.damping);
        match self.kind.family() {
            Family::Elastic | Family::Hysteresis | Family::Plastic | Family::Ramp => 0.0,
            Family::Linear => -c * rate / k,
            Family::Tsuji => (-c * self.tsuji_scale * rate / k).powf(0.8),
            Family::Viscoelastic => -1.5 * c * rate,
            Family::Dashpot => (-c * rate / k).powf(1.0 / self.exponent),
            Family::Impedance => self.impedance_zero(-c * rate / k, near),
        }
    }

    /// The penetration (m) nearest `near` where MuJoCo's d(d) d equals `target` (m, > 0), by bisection on the
    /// nearest sign change of d(d) d - target found by doubling steps away from `near`. d(d) d grows with d when the
    /// impedance does (d_min <= d_max), so the zero is then the only one; an impedance that falls can make d(d) d
    /// fall over part of the width, and the zero the contact reached is the one next to its integrated penetration.
    /// (Starting below the width and bracketing outwards never needs more than a few hundred doublings in double
    /// precision: the step reaches any finite distance from `near` within 2100 of them.)
    fn impedance_zero(&self, target: f64, near: f64) -> f64 {
        let excess = |d: f64| self.impedance(d).0 * d - target;
        let near = near.max(0.0);
        let at_near = excess(near);
        if at_near == 0.0 {
            return near;
        }
        // d(d) d - target is -target < 0 at d = 0 and grows as d_max d beyond the width: a zero lies on either side.
        let mut step = (near * 1e-12).max(f64::MIN_POSITIVE);
        let (mut low, mut top) = (near, near);
        for _ in 0..2200 {
            let below = (near - step).max(0.0);
            let above = near + step;
            if excess(below) * at_near <= 0.0 {
                (low, top) = (below, near);
                break;
            }
            if excess(above) * at_near <= 0.0 {
                (low, top) = (near, above);
                break;
            }
            step *= 2.0;
        }
        let rising = excess(top) > excess(low);
        for _ in 0..200 {
            let middle = 0.5 * (low + top);
            if middle <= low || middle >= top {
                break;
            }
            if (excess(middle) < 0.0) == rising { low = middle } else { top = middle }
        }
        0.5 * (low + top)
    }

    /// Elastic (spring) energy stored at penetration `d` (m), the integral of the elastic force from 0 to d, J:
    /// K d^(n+1)/(n+1) (k d²/2 for Kelvin–Voigt, (2/5) K d^(5/2) for Tsuji and Brilliantov); zero for d <= 0.
    pub fn elastic_energy(&self, d: f64) -> f64 {
        if d <= 0.0 {
            return 0.0;
        }
        if self.kind.family() == Family::Impedance {
            return self.stiffness * self.impedance_moment(d);
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
        if d < 0.0 || (d == 0.0 && !matches!(family, Family::Linear | Family::Dashpot | Family::Impedance)) {
            return (0.0, 0.0);
        }
        // A force that never pulls is flat where it is cut to zero.
        if matches!(family, Family::Impedance | Family::Ramp) && self.force(d, rate) <= 0.0 && d > 0.0 {
            let parts = self.split_force(d, rate);
            if parts.dissipative <= -parts.elastic {
                return (0.0, 0.0);
            }
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
            Family::Dashpot if d == 0.0 => (if n == 1.0 { k } else { 0.0 }, c),
            Family::Dashpot => (k * n * power(d, n - 1.0), c),
            Family::Impedance => {
                let (impedance, slope) = self.impedance(d);
                let by_penetration = 2.0 * impedance * slope * k * d + impedance * impedance * k + slope * c * rate;
                (by_penetration, impedance * c)
            }
            Family::Ramp => {
                let (step, slope) = cubic_step(d / self.ramp);
                (k * n * power(d, n - 1.0) + c * slope / self.ramp * rate, c * step)
            }
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

    /// The `mujoco` law's elastic energy, k ∫₀^d d(s)² s ds in closed form, against a composite Simpson sum of the
    /// impedance itself over pieces split at the midpoint and the width (where it is not smooth), for powers from 1 to
    /// 20 and penetrations inside and beyond the width; at a power of 1e5 (a step at the midpoint) it stays finite
    /// and between the energies of the two constant impedances d_min and d_max.
    #[test]
    fn mujocos_elastic_energy_is_the_integral_of_its_spring() {
        use super::ContactLaw;
        for solimp in [
            [0.9, 0.95, 0.001, 0.5, 2.0],
            [0.1, 0.99, 0.002, 0.3, 3.0],
            [0.5, 0.6, 0.01, 0.7, 1.0],
            [0.9, 0.95, 0.001, 0.5, 20.0],
        ] {
            let law = law_of(solimp);
            let [_, _, width, middle, _] = solimp;
            let integrand = |x: f64| {
                let impedance = law.impedance(x).0;
                impedance * impedance * x
            };
            let simpson = |a: f64, b: f64| {
                let n = 20_000;
                let h = (b - a) / n as f64;
                let inner: f64 = (1..n).map(|i| integrand(a + i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 }).sum();
                (integrand(a) + inner + integrand(b)) * h / 3.0
            };
            for d in [0.2 * width, 0.9 * width, 3.0 * width] {
                let mut cuts = vec![0.0];
                cuts.extend([middle * width, width].into_iter().filter(|c| *c < d));
                cuts.push(d);
                let sum: f64 = cuts.windows(2).map(|w| simpson(w[0], w[1])).sum();
                let exact = law.elastic_energy(d);
                assert!((exact - sum).abs() <= 1e-9 * sum, "solimp {solimp:?}, d = {d}: {exact} against {sum}");
            }
        }
        let step = ContactLaw { solimp: [0.9, 0.95, 0.001, 0.5, 1e5], ..law_of([0.9, 0.95, 0.001, 0.5, 2.0]) };
        for d in [0.2e-3, 0.9e-3, 3e-3] {
            let energy = step.elastic_energy(d);
            assert!(
                energy.is_finite() && energy >= 0.9f64.powi(2) * d * d / 2.0 && energy <= 0.95f64.powi(2) * d * d / 2.0
            );
        }
    }

    fn law_of(solimp: [f64; 5]) -> super::ContactLaw {
        super::ContactLaw {
            kind: super::LawKind::Mujoco,
            stiffness: 1.0,
            exponent: 1.0,
            damping: 0.0,
            tsuji_scale: 0.0,
            yield_penetration: f64::INFINITY,
            solimp,
            ramp: f64::INFINITY,
        }
    }

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
