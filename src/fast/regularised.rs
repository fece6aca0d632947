//! The physics of the regularised normal contact: each covered law as a polynomial system in `(w, v)` and the
//! Taylor-coefficient recursions of its states (docs/numerics.md#the-fast-path).
//!
//! Scaled variables as in [`crate::scales::Scales`]: penetration `δ = d/L`, rate `v = d'/v0`, time `t/T`,
//! force `F/F0`, impulse in `m* v0`, energy in `m* v0²`. With `'` the derivative in the regularised time `τ`:
//!
//! * hysteresis family, `F = δ^n (1 + x v)` (`x = alpha v0`; elastic Hertz is `x = 0`):
//!   `w = δ^((n+1)/2)`, `dτ = δ^((n-1)/2) dt`, `w' = ((n+1)/2) v`, `v' = -w (1 + x v)`;
//! * Kelvin–Voigt, `F = δ + c v` (`c = 2 zeta`): `w = δ`, `τ = t`, `w' = v`, `v' = -(w + c v)`;
//! * Tsuji, `F = δ^(3/2) + a δ^(1/4) v`: `w = δ^(5/4)`, `dτ = δ^(1/4) dt`, `w' = (5/4) v`, `v' = -(w + a v)`
//!   (linear: a damped oscillator in `τ`, with `zeta = a/sqrt 5`).
//!
//! In all three `dt/dτ = w^(-γ)` and `F = w^γ F̂`, where `F̂ = F dt/dτ` is the force in `τ`: `w (1 + x v)`,
//! resp. `w + c v`. The integrals the report needs come with the motion: the impulse `dJ/dτ = F̂ = -v'` and
//! the work `dW/dτ = F̂ v` in closed form from the rate polynomial (see [`Expansion`]); the dissipated energy
//! divided by the damping parameter, `dD̃/dτ = w v²` (hysteresis) or `v²` (linear), by Gauss–Legendre on each
//! step's polynomials ([`Expansion::dissipation_between`]), so that a lightly damped contact's dissipation
//! `D = x D̃` is accurate relative to itself. Physical time is integrated by [`super::quadrature`], which treats
//! the `w^(-γ)` singularities at the ends of the contact.

use super::FastError;
use super::quadrature::{self, MAX_NODES};
use super::taylor::{self, Coefficients, INVERSE, MAX_ORDER};
use crate::law::{ContactLaw, Family};
use crate::scales::Scales;

/// Which polynomial system.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Form {
    /// `w' = p v`, `v' = -w (1 + x v)`.
    Hysteresis,
    /// `w' = p v`, `v' = -(w + c v)`.
    Linear,
}

/// One contact law as a regularised system (all parameters dimensionless).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Regularised {
    pub form: Form,
    /// `p` in `dw/dτ = p v`: `(n+1)/2`, 1 (Kelvin–Voigt) or 5/4 (Tsuji).
    pub rate_factor: f64,
    /// The scaled damping: `x = alpha v0` (hysteresis), `c = 2 zeta` (Kelvin–Voigt) or `a` (Tsuji).
    pub damping: f64,
    /// `n`, the exponent of the elastic force (for the force-peak condition `n v = x w²` of the hysteresis family).
    pub exponent: f64,
    /// `γ` in `dt/dτ = w^(-γ)` and `F = w^γ F̂`: `(n-1)/(n+1)`, 0 or 1/5.
    pub time_exponent: f64,
    /// `β` in `δ = w^β`: `2/(n+1)`, 1 or 4/5.
    pub penetration_exponent: f64,
    /// Elastic energy `∫_0^δ F_elastic dδ = elastic_factor · w²`: `1/(n+1)`, 1/2 or 2/5.
    pub elastic_factor: f64,
}

/// Scaled contact state in the regularised variables.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct State {
    /// `w = δ^(1/β)` (>= 0 inside the contact).
    pub w: f64,
    /// Penetration rate `v = d'/v0`.
    pub rate: f64,
    /// `∫ F dt`, in `m* v0`.
    pub impulse: f64,
    /// `∫ F d' dt`, in `m* v0²`.
    pub work: f64,
    /// `D̃`: the dissipated energy (in `m* v0²`) divided by [`Regularised::damping`].
    pub dissipation: f64,
}

impl State {
    /// First contact: no penetration, closing at the approach speed, nothing integrated yet.
    pub const FIRST_CONTACT: State = State { w: 0.0, rate: 1.0, impulse: 0.0, work: 0.0, dissipation: 0.0 };
}

/// One step's Taylor series, in the offset `σ = τ - τ_start`: `w` and `v` to the order `K`.
///
/// The impulse and the work are the integrals of the force `F̂ = -v'` and of `F̂ v` on the rate polynomial:
/// `∫F̂ = -(v(σ) - v_0)` and `∫F̂ v = -(v(σ)² - v_0²)/2`. The impulse's series is the rate's to the same order
/// (`J_k = -v_k`), so that `J + v` stays constant to rounding, as it does in the equations (momentum) and in any
/// Runge–Kutta method (a linear invariant); the work is the quadratic invariant `W + v²/2` kept exactly (energy).
/// Adding the force's next term `F̂_K σ^(K+1)/(K+1)` instead, one order beyond the rate's, makes the impulse
/// drift from the rate by every step's truncation with nothing to damp it: in a creeping restitution of a thousand
/// steps (`alpha v0 = 1e4`) that put the restitution impulse 1.7e-5 off at a tolerance of 1e-6, while e, the rate
/// itself, was 4e-8 off. The dissipation, which has no such closed form, is integrated by the caller
/// ([`Expansion::dissipation_between`]).
#[derive(Debug, Clone)]
pub struct Expansion {
    pub order: usize,
    pub w: Coefficients,
    pub rate: Coefficients,
    /// The state the step starts from (its impulse and work are the integration constants).
    start: State,
}

/// What [`Expansion::probe`] finds at an offset `σ` of a step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Probe {
    /// The state at `σ`.
    pub state: State,
    /// `w` and `v` at `σ/2`.
    pub middle: [f64; 2],
}

impl Default for Expansion {
    fn default() -> Self {
        let zero = [0.0; MAX_ORDER + 1];
        Expansion { order: 0, w: zero, rate: zero, start: State::FIRST_CONTACT }
    }
}

impl Expansion {
    /// The state at offset `sigma` in the step ([`Expansion::probe`]'s).
    pub fn state_at(&self, sigma: f64) -> State {
        self.probe(sigma).state
    }

    /// The state at offset `sigma`, and `w` and `v` at its middle, `sigma/2`: what a step looks at when no event
    /// lies inside it (the samples of [`taylor::first_fall`] and the state it ends in), in one pass over the
    /// coefficients. Every component's Horner chain runs in the same loop: the chains are independent, so they
    /// take the time of one. The middle values are `taylor::value`'s, bit for bit.
    pub fn probe(&self, sigma: f64) -> Probe {
        let k = self.order;
        let mul_add = taylor::mul_add;
        let half = 0.5 * sigma;
        // `tail` = Σ_{j>=1} v_j σ^(j-1), so that v(σ) - v_0 = σ tail without cancellation (v(σ) is v_0 plus it:
        // Horner's last step, rounded twice where Horner's fuses — within an ulp of `taylor::value`, and exactly
        // the rate the next step starts from).
        let (mut w, mut tail) = (0.0, 0.0);
        let (mut w_half, mut rate_half) = (0.0, 0.0);
        for j in (1..=k).rev() {
            w = mul_add(w, sigma, self.w[j]);
            tail = mul_add(tail, sigma, self.rate[j]);
            w_half = mul_add(w_half, half, self.w[j]);
            rate_half = mul_add(rate_half, half, self.rate[j]);
        }
        let middle = [mul_add(w_half, half, self.w[0]), mul_add(rate_half, half, self.rate[0])];
        let w = mul_add(w, sigma, self.w[0]);
        let change = sigma * tail;
        let rate = self.rate[0] + change;
        let state = State {
            w,
            rate,
            impulse: self.start.impulse - change,
            work: self.start.work - 0.5 * change * (rate + self.start.rate),
            // (Integrated by the caller where it is asked for: [`Expansion::dissipation_between`].)
            dissipation: self.start.dissipation,
        };
        Probe { state, middle }
    }

    /// The impulse and the work integrated from offset `a` to offset `b` of the step, formed without the totals
    /// at `a` (no cancellation against them): the restitution's integrals, started at a maximum compression
    /// inside the step, where `v(a) = 0`.
    pub fn increments(&self, a: f64, b: f64) -> (f64, f64) {
        let k = self.order;
        let (rate_a, rate_b) = (taylor::value(&self.rate[..=k], a), taylor::value(&self.rate[..=k], b));
        let change = rate_b - rate_a;
        (-change, -0.5 * change * (rate_b + rate_a))
    }

    /// `∫_a^b` of the dissipation's integrand (`w v²`, or `v²` for the linear form) on the step's polynomials,
    /// by the `m`-node Gauss–Legendre rule.
    pub fn dissipation_between(&self, form: Form, a: f64, b: f64, m: usize) -> f64 {
        match m {
            0..=4 => self.dissipation_lanes::<4>(form, a, b, m),
            5..=8 => self.dissipation_lanes::<8>(form, a, b, m),
            9..=12 => self.dissipation_lanes::<12>(form, a, b, m),
            13..=16 => self.dissipation_lanes::<16>(form, a, b, m),
            _ => self.dissipation_lanes::<MAX_NODES>(form, a, b, m.min(MAX_NODES)),
        }
    }

    #[inline(always)]
    fn dissipation_lanes<const N: usize>(&self, form: Form, a: f64, b: f64, m: usize) -> f64 {
        let k = self.order;
        let (nodes, weights) = quadrature::gauss_legendre(m);
        let (centre, half) = (0.5 * (a + b), 0.5 * (b - a));
        let mut at = [centre; N];
        for (point, &s) in at.iter_mut().zip(nodes) {
            *point = taylor::mul_add(half, s, centre);
        }
        let rate = taylor::values_split(&self.rate[..=k], at);
        let w = if form == Form::Hysteresis { taylor::values_split(&self.w[..=k], at) } else { [1.0; N] };
        let mut integrand = [0.0; N];
        for i in 0..N {
            integrand[i] = w[i] * rate[i] * rate[i];
        }
        half * taylor::dot(&integrand[..m], weights)
    }
}

impl Regularised {
    /// The regularised system of `law` in the units `scales`. Errors: Brilliantov's law (not smoothed by the
    /// transformation), parameters that are not finite and positive (damping: non-negative), scales that do not
    /// belong to the law's stiffness and exponent.
    pub fn new(law: &ContactLaw, scales: &Scales) -> Result<Regularised, FastError> {
        let family = law.kind.family();
        if matches!(family, Family::Viscoelastic | Family::Plastic | Family::Dashpot | Family::Impedance | Family::Ramp)
        {
            return Err(FastError::NotCovered(law.kind.name()));
        }
        let n = law.exponent;
        let positive = |value: f64| value.is_finite() && value > 0.0;
        if !(positive(law.stiffness) && positive(n)) {
            return Err(FastError::Invalid(format!(
                "stiffness {} and exponent {} must be finite and positive",
                crate::units::brief(law.stiffness, ""),
                crate::units::short(n)
            )));
        }
        if !(law.damping.is_finite() && law.damping >= 0.0) {
            return Err(FastError::Invalid(format!(
                "damping {} must be finite and >= 0",
                crate::units::brief(law.damping, "")
            )));
        }
        let units = [scales.length, scales.speed, scales.time, scales.force, scales.impulse, scales.energy];
        if !units.iter().all(|&u| positive(u)) {
            use crate::units::brief;
            return Err(FastError::Invalid(format!(
                "the scales must be finite and positive: length {}, speed {}, time {}, force {}, impulse {}, energy {}",
                brief(scales.length, "m"),
                brief(scales.speed, "m/s"),
                brief(scales.time, "s"),
                brief(scales.force, "N"),
                brief(scales.impulse, "N s"),
                brief(scales.energy, "J")
            )));
        }
        // The scaled equations take K L^n = F0 (so that F/F0 = δ^n): the scales must be those of this law.
        let stiffness_unit = law.stiffness * crate::scales::length_power(scales.length, n) / scales.force;
        if stiffness_unit.is_nan() || (stiffness_unit - 1.0).abs() > SCALE_MISMATCH {
            return Err(FastError::Invalid(format!(
                "the scales are not those of this law: K L^n / F0 = {} (expected 1)",
                crate::units::apart(stiffness_unit, 1.0, "").0
            )));
        }
        let fixed_exponent = |expected: f64| {
            if n == expected {
                Ok(())
            } else {
                Err(FastError::Invalid(format!(
                    "the `{}` law needs exponent {}, not {}",
                    law.kind.name(),
                    crate::units::short(expected),
                    crate::units::apart(n, expected, "").0
                )))
            }
        };
        let v0 = scales.speed;
        Ok(match family {
            Family::Elastic | Family::Hysteresis => Regularised {
                form: Form::Hysteresis,
                rate_factor: 0.5 * (n + 1.0),
                damping: if family == Family::Elastic { 0.0 } else { law.damping * v0 },
                exponent: n,
                time_exponent: (n - 1.0) / (n + 1.0),
                penetration_exponent: 2.0 / (n + 1.0),
                elastic_factor: 1.0 / (n + 1.0),
            },
            Family::Linear => {
                fixed_exponent(1.0)?;
                Regularised {
                    form: Form::Linear,
                    rate_factor: 1.0,
                    // c d' / F0 = (c v0 / F0) v.
                    damping: law.damping * v0 / scales.force,
                    exponent: 1.0,
                    time_exponent: 0.0,
                    penetration_exponent: 1.0,
                    elastic_factor: 0.5,
                }
            }
            Family::Tsuji => {
                fixed_exponent(1.5)?;
                Regularised {
                    form: Form::Linear,
                    rate_factor: 1.25,
                    // a sqrt(m* K) d^(1/4) d' / F0 = (a sqrt(m* K) L^(1/4) v0 / F0) δ^(1/4) v.
                    damping: law.damping * law.tsuji_scale * scales.length.sqrt().sqrt() * v0 / scales.force,
                    exponent: 1.5,
                    time_exponent: 0.2,
                    penetration_exponent: 0.8,
                    elastic_factor: 0.4,
                }
            }
            Family::Viscoelastic | Family::Plastic | Family::Dashpot | Family::Impedance | Family::Ramp => {
                unreachable!("rejected above")
            }
        })
    }

    /// Whether the force can turn tensile before the penetration returns to zero (so that a force separation
    /// differs from a penetration separation).
    pub fn can_turn_tensile(&self) -> bool {
        self.form == Form::Linear && self.damping > 0.0
    }

    /// Whether, past maximum compression, `w` can never return to zero: a linear system (`w' = p v`,
    /// `v' = -(w + c v)`) that is overdamped or critically damped, `c² >= 4p` (zeta >= 1). From `v = 0`,
    /// `w > 0` the solution is `A e^(λ1 τ) + B e^(λ2 τ)` with `A = -λ2 w/(λ1 - λ2) > 0` on the slower mode, so
    /// `w > 0` for all `τ` (critically damped: `w (1 - λ τ) e^(λ τ)`, `λ < 0`).
    pub fn never_separates(&self) -> bool {
        self.form == Form::Linear && self.damping * self.damping >= 4.0 * self.rate_factor
    }

    /// Taylor coefficients of `w` and `v` at `state`, to `order` (<= [`MAX_ORDER`]).
    ///
    /// The hysteresis form's product `P = w v` is a derivative, `P = w w'/p = (w²)'/(2p)`, so
    /// `P_k = (k+1) S_(k+1)/(2p)` with `S_m = Σ_(i+j=m) w_i w_j` — a square, whose pairs `(i, m-i)` and
    /// `(m-i, i)` are one product: `v_(k+1) = -w_k/(k+1) - (x/p) H_(k+1)`, `H_m = S_m/2 = Σ_(i<m-i) w_i w_(m-i)`
    /// (`+ w_(m/2)²/2` for even `m`), half the products of the Cauchy sum `Σ w_j v_(k-j)`.
    ///
    /// A step's coefficients are a chain: each waits for the one before, and the steps themselves follow one
    /// another, so the chain's length per coefficient is the step's cost. The newest terms are therefore written
    /// on the rates they come from (`w_j = p v_(j-1)/j`): `v_(k+1) = α v_k + (β v_(k-1) + (γ v_(k-2) + older))`
    /// with `α = -x w_0/(k+1)`, `β = -(p/(k+1) + x w_1)/k`, `γ = -x w_2/(k-1)` formed off the chain, so that a
    /// coefficient waits one fused multiply-add for the last (two for the `w_(k+1) = p v_k/(k+1)` of a product).
    /// Written out for each coefficient ([`hysteresis_series`]): no loop, index or bound check between them. At
    /// order 18 the `alpha v0 = 10` impact takes 2.61 µs where the loop over the full Cauchy sum took 3.15, on
    /// one core of this machine (docs/numerics.md).
    pub fn expand(&self, state: &State, order: usize, e: &mut Expansion) {
        debug_assert!(order <= MAX_ORDER);
        e.order = order;
        e.start = *state;
        e.w[0] = state.w;
        e.rate[0] = state.rate;
        let (p, x) = (self.rate_factor, self.damping);
        let elastic = self.form == Form::Hysteresis && x == 0.0;
        match self.form {
            Form::Hysteresis if elastic => {
                // F̂ = w, no products.
                for k in 0..order {
                    let inverse = INVERSE[k + 1];
                    e.w[k + 1] = p * e.rate[k] * inverse;
                    e.rate[k + 1] = -e.w[k] * inverse;
                }
            }
            Form::Hysteresis => hysteresis_series(order, p, x, e),
            Form::Linear => {
                for k in 0..order {
                    // F̂ = w + c v.
                    let force = taylor::mul_add(x, e.rate[k], e.w[k]);
                    let inverse = INVERSE[k + 1];
                    e.w[k + 1] = p * e.rate[k] * inverse;
                    e.rate[k + 1] = -force * inverse;
                }
            }
        }
    }

    /// `F̂ = F dt/dτ`, the force in regularised time: `w (1 + x v)` or `w + c v`. For the linear laws its zero is
    /// the force separation (a continuous function, continued past `d = 0`:
    /// docs/numerics.md#separation-on-the-continued-force).
    #[inline]
    pub fn regular_force(&self, w: f64, rate: f64) -> f64 {
        match self.form {
            Form::Hysteresis => w * (1.0 + self.damping * rate),
            Form::Linear => w + self.damping * rate,
        }
    }

    /// A lower bound on the distance in `τ` from a restitution state (`w > 0`, `v < 0`) to the zero of `w`.
    ///
    /// * Compressive (`F̂ > 0`): `F̂` falls in restitution while it is compressive (hysteresis:
    ///   `dF̂/dτ = (1 + x v)(p v - x w²)`; linear: `p v - c F̂`), so beyond this state `w'' = -p F̂ >= -p F̂_0`,
    ///   and `w` stays above the parabola `w_0 + p v_0 s - p F̂_0 s²/2`, whose zero is returned.
    /// * Tensile (`F̂ <= 0`): for the linear laws `F̂` cannot rise through zero while `v < 0` (there `dF̂/dτ = p v`),
    ///   and `v` cannot reach zero while `F̂ <= 0` (at `v = 0`, `F̂ = w > 0`); the hysteresis form is tensile only
    ///   by rounding, a hair past the line `1 + x v = 0`, which the flow never crosses (`v' = 0` on it), and
    ///   `v' = -F̂ >= 0` brings it back, not further. So `w'' = -p F̂ >= 0` up to the zero: `w` is convex and stays
    ///   above its tangent, whose zero `w/(p |v|)` is returned. (The creep of a heavy damping, `v ≈ -1/x`, reaches
    ///   that line to rounding; a bound of 0 there put the zero of `w` at the state itself and no rule of the
    ///   time could fit before it.)
    ///
    /// 0 where the premises do not hold.
    pub fn zero_distance_bound(&self, w: f64, rate: f64) -> f64 {
        let p = self.rate_factor;
        let force = self.regular_force(w, rate);
        if !(w > 0.0 && rate < 0.0) || force.is_nan() {
            return 0.0;
        }
        if force <= 0.0 {
            return w / (-p * rate);
        }
        let speed = -p * rate;
        // The positive root of (p F̂/2) s² + speed s - w, without cancellation.
        2.0 * w / (speed + (speed * speed + 2.0 * p * force * w).sqrt())
    }

    /// The time from a force separation to the zero of `w` that follows it (a linear law that turns tensile, in
    /// restitution: at the force's zero `F̂ = w + c v = 0`, so `w_F = c |v_F|` exactly), where it has a closed form to
    /// the local tolerance `eps`; `None` for a damping too heavy for it.
    ///
    /// From the force's zero on (`σ`), `d²w/dτ² = p v' = -p F̂ = 0` there and `d³w/dτ³ = -p dF̂/dτ = -p² v_F`, so
    /// `w = w_F - A σ + (p A/6) σ³ + …`, `A = p |v_F|`, and with `w` as the variable
    /// `∫ w^(-γ) dσ = ∫_0^(w_F) w^(-γ) (1/A) (1 + (p/2) σ² + …) dw
    ///  = w_F^(1-γ)/((1-γ) A) · (1 + c²/(p (2-γ)(3-γ)) + O((c²/p)²))` (the correction's Beta integral
    /// `∫ w^(-γ) (w_F - w)² = 2 w_F^(3-γ)/((1-γ)(2-γ)(3-γ))`). In `τ` the two zeros of a light damping lie an ulp
    /// or two apart, and the time over the gap (`∝ gap^(1-γ)`, steep at zero) would inherit the rounding of its
    /// ends; in `w` it does not.
    pub fn time_past_force_zero(&self, rate: f64, eps: f64) -> Option<f64> {
        let (c, p, gamma) = (self.damping, self.rate_factor, self.time_exponent);
        let correction = c * c / (p * (2.0 - gamma) * (3.0 - gamma));
        if self.form != Form::Linear || rate.is_nan() || rate >= 0.0 || correction * correction > eps {
            return None;
        }
        let w = c * -rate;
        let a = p * -rate;
        Some(w.powf(1.0 - gamma) / ((1.0 - gamma) * a) * (1.0 + correction))
    }

    /// Scaled contact force `F = w^γ F̂` (`w` clamped at 0: a located zero may sit an ulp below).
    pub fn force(&self, w: f64, rate: f64) -> f64 {
        let w = w.max(0.0);
        let regular = self.regular_force(w, rate);
        if self.time_exponent == 0.0 { regular } else { w.powf(self.time_exponent) * regular }
    }

    /// [`Regularised::force`] where the penetration `δ = w^β` is known: `w^γ = w/δ` (`γ = 1 - β` for every
    /// covered law), so no power is taken.
    pub fn force_at(&self, w: f64, penetration: f64, rate: f64) -> f64 {
        let w = w.max(0.0);
        let regular = self.regular_force(w, rate);
        if self.time_exponent == 0.0 {
            regular
        } else if penetration > 0.0 {
            w / penetration * regular
        } else {
            // w^γ = 0 at w = 0.
            0.0
        }
    }

    /// Scaled penetration `δ = w^β` (`w` clamped at 0).
    pub fn penetration(&self, w: f64) -> f64 {
        let w = w.max(0.0);
        if self.penetration_exponent == 1.0 { w } else { w.powf(self.penetration_exponent) }
    }

    /// Elastic energy stored at `w`, in `m* v0²`.
    pub fn elastic_energy(&self, w: f64) -> f64 {
        // (w clamped at 0, as the penetration is: a located zero may sit an ulp below.)
        let w = w.max(0.0);
        self.elastic_factor * w * w
    }

    /// [`Regularised::peak_function`]'s value alone at a state (`w`, `v`), for sampling.
    pub fn peak_value(&self, w: f64, rate: f64) -> f64 {
        self.peak_function(w, 0.0, rate, 0.0).0
    }

    /// A function whose falling zero is the force peak (`dF/dτ = 0`), with its derivative along `τ`, from `w`,
    /// `v` and their `τ`-derivatives. Positive while the force rises.
    ///
    /// * hysteresis: `dF/dτ = w^γ (1 + x v) (n v - x w²)`, so `g = n v - x w²`;
    /// * Kelvin–Voigt (`γ = 0`): `g = dF̂/dτ = p v - c F̂`;
    /// * Tsuji: `w^(1-γ) dF/dτ = γ p v F̂ + w (p v - c F̂)` (positive at first contact, where `w = 0`).
    pub fn peak_function(&self, w: f64, dw: f64, rate: f64, drate: f64) -> (f64, f64) {
        let (p, c, n) = (self.rate_factor, self.damping, self.exponent);
        match self.form {
            Form::Hysteresis => (n * rate - c * w * w, n * drate - 2.0 * c * w * dw),
            Form::Linear => {
                let force = w + c * rate;
                let dforce = dw + c * drate;
                let slope = p * rate - c * force;
                let dslope = p * drate - c * dforce;
                if self.time_exponent == 0.0 {
                    (slope, dslope)
                } else {
                    let g = self.time_exponent * p;
                    (g * rate * force + w * slope, g * (drate * force + rate * dforce) + dw * slope + w * dslope)
                }
            }
        }
    }
}

/// Largest relative mismatch between `K L^n` and `F0` accepted (rounding of the scales is ~1e-16).
const SCALE_MISMATCH: f64 = 1e-9;

/// The hysteresis recursion from `e.w[0]`, `e.rate[0]` to `order` (<= [`MAX_ORDER`]), written out coefficient by
/// coefficient ([`Regularised::expand`]).
#[inline(never)]
fn hysteresis_series(order: usize, p: f64, x: f64, e: &mut Expansion) {
    if order == 0 {
        return;
    }
    let x_p = x / p;
    // (Local copies, held in registers: the expansion's arrays are only written.)
    let (mut w, mut r, mut s) = ([0.0; MAX_ORDER + 1], [0.0; MAX_ORDER + 1], [0.0; MAX_ORDER + 1]);
    (w[0], r[0]) = (e.w[0], e.rate[0]);
    macro_rules! coefficients {
        ($($m:literal)*) => {
            $(
                hysteresis_coefficient::<$m>(&mut w, &mut r, &mut s, p, x, x_p);
                (e.w[$m], e.rate[$m]) = (w[$m], r[$m]);
                if order == $m {
                    return;
                }
            )*
        };
    }
    coefficients!(1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20 21 22 23 24 25 26 27 28 29 30);
    const _: () = assert!(MAX_ORDER == 30, "the list above runs to MAX_ORDER");
}

/// Coefficient `M` of the hysteresis recursion, from those before it in the local arrays `w`, `r` and `s`
/// (`s_i = -(x/p) w_i`) ([`Regularised::expand`]).
#[inline(always)]
fn hysteresis_coefficient<const M: usize>(
    w: &mut Coefficients,
    r: &mut Coefficients,
    s: &mut Coefficients,
    p: f64,
    x: f64,
    x_p: f64,
) {
    let k = M - 1;
    let inverse = INVERSE[M];
    let mul_add = taylor::mul_add;
    let next = if M == 1 {
        mul_add(-x * w[0], r[0], -w[0])
    } else if M == 2 {
        mul_add(-x * w[0] * inverse, r[1], mul_add(0.5 * s[1], w[1], -0.5 * w[1]))
    } else {
        let mut inner = if M.is_multiple_of(2) { 0.5 * s[M / 2] * w[M / 2] } else { 0.0 };
        let last = (M - 1) / 2;
        for j in 0..last.saturating_sub(2) {
            let i = last - j;
            inner = mul_add(s[i], w[M - i], inner);
        }
        if last >= 2 {
            inner = mul_add(-x * w[2] * INVERSE[M - 2], r[k - 2], inner);
        }
        let beta = -INVERSE[k] * mul_add(x, w[1], p * inverse);
        mul_add(-x * w[0] * inverse, r[k], mul_add(beta, r[k - 1], inner))
    };
    w[M] = r[k] * (p * inverse);
    s[M] = -x_p * w[M];
    r[M] = next;
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fast::taylor;

    fn hysteresis(x: f64, n: f64) -> Regularised {
        Regularised {
            form: Form::Hysteresis,
            rate_factor: 0.5 * (n + 1.0),
            damping: x,
            exponent: n,
            time_exponent: (n - 1.0) / (n + 1.0),
            penetration_exponent: 2.0 / (n + 1.0),
            elastic_factor: 1.0 / (n + 1.0),
        }
    }

    /// Tsuji's regularised system (`p = 5/4`, `γ = 1/5`) with damping `a`.
    fn tsuji(a: f64) -> Regularised {
        Regularised {
            form: Form::Linear,
            rate_factor: 1.25,
            damping: a,
            exponent: 1.5,
            time_exponent: 0.2,
            penetration_exponent: 0.8,
            elastic_factor: 0.4,
        }
    }

    /// Kelvin–Voigt's regularised system (`p = 1`, `t = τ`) with damping `c = 2 zeta`.
    fn kelvin_voigt(c: f64) -> Regularised {
        Regularised {
            form: Form::Linear,
            rate_factor: 1.0,
            damping: c,
            exponent: 1.0,
            time_exponent: 0.0,
            penetration_exponent: 1.0,
            elastic_factor: 0.5,
        }
    }

    /// Elastic: `w'' = -p w` with `w(0) = 0`, `w'(0) = p`, so `w = sqrt(p) sin(sqrt(p) τ)`, `v = cos(sqrt(p) τ)`.
    #[test]
    fn elastic_series_is_the_sine() {
        let system = hysteresis(0.0, 1.5);
        let mut e = Expansion::default();
        system.expand(&State::FIRST_CONTACT, 30, &mut e);
        let omega = 1.25_f64.sqrt();
        for tau in [0.1, 0.5, 1.0] {
            let s = e.state_at(tau);
            assert!((s.w - omega * (omega * tau).sin()).abs() < 1e-13, "w at {tau}");
            assert!((s.rate - (omega * tau).cos()).abs() < 1e-13, "v at {tau}");
            // Impulse = 1 - v and work = (1 - v²)/2 for any law (momentum and energy, checked here only).
            assert!((s.impulse - (1.0 - s.rate)).abs() < 1e-14);
            assert!(
                (s.work - 0.5 * (1.0 - s.rate * s.rate)).abs() < 1e-14,
                "{} {}",
                s.work,
                0.5 * (1.0 - s.rate * s.rate)
            );
        }
    }

    /// A probe's middle values are Horner's values of the series at half the offset, bit for bit (they stand for
    /// [`taylor::values`] in the events' sampling), and its state at the offset agrees with the series' own values
    /// (`w` bit for bit; the rate `v_0 + σ tail` within an ulp, rounded twice where Horner's last step fuses).
    #[test]
    fn probe_samples_the_middle_and_the_end() {
        let system = hysteresis(0.9, 1.5);
        let mut e = Expansion::default();
        let state = State { w: 0.35, rate: -0.2, impulse: 1.1, work: 0.45, dissipation: 0.02 };
        system.expand(&state, 19, &mut e);
        let k = e.order + 1;
        for sigma in [0.0, 0.013, 0.2, 0.41] {
            let probe = e.probe(sigma);
            assert_eq!(probe.middle, [taylor::value(&e.w[..k], 0.5 * sigma), taylor::value(&e.rate[..k], 0.5 * sigma)]);
            assert_eq!(probe.state.w, taylor::value(&e.w[..k], sigma));
            assert!((probe.state.rate - taylor::value(&e.rate[..k], sigma)).abs() <= 2e-16);
            // (The dissipation is integrated by the caller: the probe carries the step's starting value.)
            assert_eq!(probe.state.dissipation, state.dissipation);
        }
    }

    /// The series satisfy their equations: the derivative of each polynomial equals the right-hand side
    /// evaluated on the polynomials, up to the truncation order.
    #[test]
    fn series_satisfy_the_equations() {
        let x = 0.7;
        let system = hysteresis(x, 2.2);
        let mut e = Expansion::default();
        let state = State { w: 0.4, rate: -0.3, impulse: 1.1, work: 0.45, dissipation: 0.02 };
        system.expand(&state, 24, &mut e);
        let k = e.order + 1;
        for sigma in [0.01, 0.05] {
            let (w, dw) = taylor::value_and_slope(&e.w[..k], sigma);
            let (v, dv) = taylor::value_and_slope(&e.rate[..k], sigma);
            let force = w * (1.0 + x * v);
            assert!((dw - 1.6 * v).abs() < 1e-14);
            assert!((dv + force).abs() < 1e-14);
            // Impulse and work: central differences of the closed forms give F̂ and F̂ v.
            let h = 1e-5;
            let (after, before) = (e.state_at(sigma + h), e.state_at(sigma - h));
            assert!(((after.impulse - before.impulse) / (2.0 * h) - force).abs() < 1e-9);
            assert!(((after.work - before.work) / (2.0 * h) - force * v).abs() < 1e-9);
        }
    }

    /// The hysteresis series, at every order, are the Taylor recursion's with the plain Cauchy product
    /// `v_(k+1) = -(w_k + x Σ_j w_j v_(k-j))/(k+1)` (written here, not the half square the stepper sums) applied to
    /// the expansion's own lower coefficients, to a few ulps of the sum's terms, over random states (half of them in
    /// a creep) and both signs of the rate; coefficients past the order are
    /// left alone, and a lower order gives the leading coefficients of a higher one bit for bit.
    #[test]
    fn hysteresis_series_are_the_cauchy_recursion() {
        let mut draw = crate::draw::Draw::new(29, 0);
        for _ in 0..200 {
            let (x, n) = (10f64.powf(draw.uniform(-3.0, 3.0)), draw.uniform(1.0, 3.0));
            let system = hysteresis(x, n);
            let p = system.rate_factor;
            // Half the states in a creep, a hair off the line 1 + x v = 0.
            let creep = draw.uniform(0.0, 1.0) < 0.5;
            let rate = if creep { -1.0 / x * (1.0 + draw.uniform(-1e-6, 1e-6)) } else { draw.uniform(-1.0, 1.0) };
            let state = State { w: draw.uniform(0.0, 2.0), rate, ..State::FIRST_CONTACT };
            let mut full = Expansion::default();
            system.expand(&state, MAX_ORDER, &mut full);
            // Each coefficient against the Cauchy recursion applied to the expansion's own lower coefficients (a
            // per-step check: the rounding of v_1 = -w_0 (1 + x v_0) near the line 1 + x v = 0 is not compared).
            let (w, v) = (full.w, full.rate);
            for k in 0..MAX_ORDER {
                let product: f64 = (0..=k).map(|j| w[j] * v[k - j]).sum();
                let size: f64 = w[k].abs() + x * (0..=k).map(|j| (w[j] * v[k - j]).abs()).sum::<f64>();
                let want = -(w[k] + x * product) / (k + 1) as f64;
                let scale = size / (k + 1) as f64;
                assert!(
                    (v[k + 1] - want).abs() <= 4.0 * (k + 2) as f64 * f64::EPSILON * scale,
                    "v_{} at x {x}: {} vs {}",
                    k + 1,
                    v[k + 1],
                    want
                );
                let w_next = p * v[k] / (k + 1) as f64;
                assert!((w[k + 1] - w_next).abs() <= 2.0 * f64::EPSILON * w_next.abs());
            }
            for order in 0..MAX_ORDER {
                let nan = [f64::NAN; MAX_ORDER + 1];
                let mut e = Expansion { w: nan, rate: nan, ..Expansion::default() };
                system.expand(&state, order, &mut e);
                assert_eq!(e.w[..=order], full.w[..=order]);
                assert_eq!(e.rate[..=order], full.rate[..=order]);
                assert!(e.w[order + 1..].iter().chain(&e.rate[order + 1..]).all(|c| c.is_nan()), "order {order}");
            }
        }
    }

    /// The linear form's series satisfy `w' = p v`, `v' = -(w + c v)` (Tsuji's `p` and a damping).
    #[test]
    fn linear_series_satisfy_the_equations() {
        let (p, c) = (1.25, 0.6);
        let system = tsuji(c);
        let mut e = Expansion::default();
        let state = State { w: 0.3, rate: 0.7, impulse: 0.2, work: 0.1, dissipation: 0.05 };
        system.expand(&state, 26, &mut e);
        let k = e.order + 1;
        for sigma in [0.05, 0.3, 0.6] {
            let (w, dw) = taylor::value_and_slope(&e.w[..k], sigma);
            let (v, dv) = taylor::value_and_slope(&e.rate[..k], sigma);
            assert!((dw - p * v).abs() < 1e-14, "w' at {sigma}");
            assert!((dv + (w + c * v)).abs() < 1e-14, "v' at {sigma}");
        }
    }

    /// Exact integral over `[a, b]` of the product of polynomials (coefficients in `σ`), by multiplying them out
    /// in full and integrating term by term: independent of the Gauss rules.
    fn exact_product_integral(factors: &[&[f64]], a: f64, b: f64) -> f64 {
        let mut product = vec![1.0];
        for factor in factors {
            let mut next = vec![0.0; product.len() + factor.len() - 1];
            for (i, &p) in product.iter().enumerate() {
                for (j, &f) in factor.iter().enumerate() {
                    next[i + j] += p * f;
                }
            }
            product = next;
        }
        let antiderivative =
            |s: f64| product.iter().enumerate().rev().fold(0.0, |acc, (j, &c)| acc * s + c / (j + 1) as f64) * s;
        antiderivative(b) - antiderivative(a)
    }

    /// The dissipation's integrand `w v²` (hysteresis) or `v²` (linear) integrated by the Gauss rule agrees with the
    /// exact integral of the polynomials multiplied out: to rounding where the rule is exact (`2m - 1` at least the
    /// product's degree), and to 1e-15 relative with the few nodes the fast path uses on a step of the length its
    /// step rule gives (a third of the series' radius of convergence: `eps_root` is about 0.3 at 1e-10).
    #[test]
    fn dissipation_integral_agrees_with_the_polynomials_multiplied_out() {
        let hysteresis_system = hysteresis(2.0, 1.5);
        let linear_system = kelvin_voigt(0.6);
        let state = State { w: 0.3, rate: 0.7, impulse: 0.2, work: 0.1, dissipation: 0.05 };
        let order = 10;
        for system in [hysteresis_system, linear_system] {
            let mut e = Expansion::default();
            system.expand(&state, order, &mut e);
            let (w, v) = (&e.w[..=order], &e.rate[..=order]);
            let factors: Vec<&[f64]> = if system.form == Form::Hysteresis { vec![w, v, v] } else { vec![v, v] };
            // Exact: 3K = 30 (resp. 2K = 20) is at most 2m - 1.
            let exact_nodes = if system.form == Form::Hysteresis { 16 } else { 11 };
            for (a, b) in [(0.0, 0.3), (0.05, 0.2), (0.0, 0.0)] {
                let expected = exact_product_integral(&factors, a, b);
                let got = e.dissipation_between(system.form, a, b, exact_nodes);
                assert!((got - expected).abs() <= 1e-15 * expected.abs().max(1e-300), "{got} vs {expected}");
            }
        }
        // Eight nodes (the fast path's count at 1e-9) on a step of 0.3 times the radius of convergence: the
        // hysteresis system at x = 10 near maximum compression, its order-19 series.
        let system = hysteresis(10.0, 1.5);
        let state = State { w: 0.43, rate: 0.02, impulse: 0.0, work: 0.0, dissipation: 0.0 };
        let mut e = Expansion::default();
        system.expand(&state, 19, &mut e);
        let radius = e.w[19].abs().powf(-1.0 / 19.0).min(e.rate[19].abs().powf(-1.0 / 19.0));
        let h = 0.3 * radius;
        let (w, v) = (&e.w[..=19], &e.rate[..=19]);
        let expected = exact_product_integral(&[w, v, v], 0.0, h);
        let got = e.dissipation_between(Form::Hysteresis, 0.0, h, 8);
        assert!((got - expected).abs() <= 1e-12 * expected.abs(), "{got} vs {expected} (h = {h})");
    }

    /// The bound on the distance to the zero of `w` is never beyond the zero, found by an independent integration
    /// (RK4 on the regularised equations, steps of 1e-4, the crossing interpolated), over random restitution
    /// states of both forms (compressive, and for the linear form tensile too); and well into restitution it is not
    /// useless (at least a fifth of the distance).
    #[test]
    fn zero_distance_bound_is_a_lower_bound() {
        let systems = [hysteresis(0.0, 1.5), hysteresis(0.5, 2.2), hysteresis(10.0, 1.0), tsuji(0.3), tsuji(1.5)];
        let mut draw = crate::draw::Draw::new(5, 0);
        for system in systems {
            let mut checked = 0;
            while checked < 40 {
                let (w0, v0) = (draw.uniform(0.01, 1.0), -draw.uniform(0.005, 1.0));
                // (Tensile hysteresis states, past `1 + x v = 0`, as rounding leaves them in a creep.)
                let tensile = system.regular_force(w0, v0) <= 0.0;
                let bound = system.zero_distance_bound(w0, v0);
                let rhs = |w: f64, v: f64| (system.rate_factor * v, -system.regular_force(w, v));
                let (mut w, mut v, mut s, h) = (w0, v0, 0.0, 1e-4);
                let distance = loop {
                    let k1 = rhs(w, v);
                    let k2 = rhs(w + 0.5 * h * k1.0, v + 0.5 * h * k1.1);
                    let k3 = rhs(w + 0.5 * h * k2.0, v + 0.5 * h * k2.1);
                    let k4 = rhs(w + h * k3.0, v + h * k3.1);
                    let next = (
                        w + h / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0),
                        v + h / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1),
                    );
                    if next.0 <= 0.0 {
                        break s + h * w / (w - next.0);
                    }
                    (w, v, s) = (next.0, next.1, s + h);
                    assert!(s < 1e3, "no zero of w from ({w0}, {v0})");
                };
                assert!(
                    bound <= distance * (1.0 + 1e-6),
                    "{:?} from ({w0}, {v0}): {bound} beyond {distance}",
                    system.form
                );
                // (Near maximum compression the parabola's curvature makes it short; well into restitution, not.
                // The tangent of a tensile state is short where the rate relaxes to its line.)
                if v0 < -0.3 && !tensile {
                    assert!(bound >= 0.2 * distance, "{:?} from ({w0}, {v0}): {bound} against {distance}", system.form);
                }
                checked += 1;
            }
        }
        // A tensile hysteresis state (a creep's rate an ulp past -1/x) is bounded by its tangent, not by 0.
        let creep = hysteresis(3e5, 4.0);
        let rate = -1.0 / 3e5 * (1.0 + 4.0 * f64::EPSILON);
        assert!(creep.regular_force(2.0, rate) < 0.0);
        assert_eq!(creep.zero_distance_bound(2.0, rate), 2.0 / (creep.rate_factor * -rate));
        // Outside its premises (not restituting) it claims nothing.
        let system = hysteresis(0.5, 1.5);
        assert_eq!(system.zero_distance_bound(0.3, 0.2), 0.0);
        assert_eq!(tsuji(3.0).zero_distance_bound(0.1, 0.5), 0.0);
    }

    /// The force from the known penetration (`w/δ` for `w^γ`) against the power itself, for every form's `γ`,
    /// across penetrations from 1e-12 to 3 and rates of both signs; zero at `w = 0` unless `γ = 0`.
    #[test]
    fn force_from_the_penetration_is_the_power_law() {
        let linear = |p: f64, c: f64, gamma: f64, beta: f64| Regularised {
            form: Form::Linear,
            rate_factor: p,
            damping: c,
            exponent: 1.0 + 0.5 * gamma / 0.2,
            time_exponent: gamma,
            penetration_exponent: beta,
            elastic_factor: 0.5,
        };
        // (n = 1/2: γ < 0, β > 1.)
        let systems = [
            hysteresis(0.7, 1.5),
            hysteresis(2.0, 2.2),
            hysteresis(0.0, 1.0),
            hysteresis(1.3, 0.5),
            linear(1.25, 0.4, 0.2, 0.8),
        ];
        let mut draw = crate::draw::Draw::new(3, 0);
        for system in systems {
            for _ in 0..2000 {
                let w = 10f64.powf(draw.uniform(-12.0, 0.5));
                let rate = draw.uniform(-2.0, 2.0);
                let penetration = system.penetration(w);
                let power = w.powf(system.time_exponent) * system.regular_force(w, rate);
                let got = system.force_at(w, penetration, rate);
                // A few ulps, and the rounding of γ and β in binary (each within 1.1e-16; for n = 3/2, γ + β =
                // 1 + 5.6e-17): w/δ is w^(1 - β), the power w^γ, and they differ by w^(γ + β - 1).
                let tolerance = (6e-16 + 2.2e-16 * w.ln().abs()) * power.abs();
                assert!((got - power).abs() <= tolerance, "{system:?} w {w} v {rate}: {got} vs {power}");
            }
            let at_zero = system.force_at(0.0, 0.0, 0.5);
            let expected = if system.time_exponent == 0.0 { system.regular_force(0.0, 0.5) } else { 0.0 };
            assert_eq!(at_zero, expected);
        }
    }

    #[test]
    fn peak_function_matches_the_force_derivative() {
        // Tsuji: compare g / w^(1-γ) with a central difference of F along the exact flow's derivatives.
        let system = tsuji(0.3);
        let (w, v) = (0.5, 0.4);
        let (dw, dv) = (1.25 * v, -(w + 0.3 * v));
        let h = 1e-6;
        let slope = (system.force(w + h * dw, v + h * dv) - system.force(w - h * dw, v - h * dv)) / (2.0 * h);
        let (g, _) = system.peak_function(w, dw, v, dv);
        let expected = slope * w.powf(0.8);
        assert!((g - expected).abs() < 1e-8, "{g} vs {expected}");
    }
}
