//! The slide's Taylor coefficients (docs/numerics.md#the-slide-path-by-taylor-series): its equations in the
//! regularised time `σ` are polynomial in `q = d^(1/4)`, the rate and the tangential states for the laws whose force
//! is a polynomial in `q` and the rate — Hertz, the Hunt–Crossley family, Kelvin–Voigt and Tsuji, at `n = 1` or
//! `3/2` — and a spring whose stiffness is constant or Mindlin's `kt ∝ d^(1/2) = q²`. Each coefficient follows from
//! the lower ones by Cauchy products (the standard recursions of Taylor-mode integration), so that
//! [`crate::integrate::Scheme::Taylor`] takes steps of high order on them and locates every event on a step's
//! polynomial.
//!
//! Per order `k` (`x_k` the k-th coefficient of `x`): `q² `, `S = q³` (the stretch `dt/dσ`) and the elastic power
//! `q^(4n)`; the dissipative force; `Fn S = dJn/dσ`, whence `v_(k+1) = -Jn_(k+1)` and `q_(k+1) = v_k/(4(k+1))`; the
//! work from `W + v²/2` constant (energy), as the normal fast path keeps it; the dissipation `∫ Fd v S`; on the line,
//! a stick's spring rate `-kt slip S`, a slide's force `±mu Fn` (so that `Jt` is `±mu Jn` to the step's
//! coefficients), the tangential work `∫ T slip S`, the shift `∫ Jt S`, and the immovable body's work, linear in the
//! two impulses' rates.

use super::{SIZE, SlideContact, index};
use crate::dynamics::contact::Mode;
use crate::integrate::State;
use crate::law::{ContactLaw, Family};
use crate::scales::Scales;
use crate::scene::{FrictionCap, TangentialUnloading};

/// Highest order the arrays hold (the normal fast path's).
const CAPACITY: usize = 32;

/// The normal force as a polynomial in `q` and the rate `v`: `elastic q^power + damping q^damped v`, or for the
/// Hunt–Crossley family `elastic q^power (1 + damping v)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct SeriesLaw {
    /// `K L^n / F0` (1 to rounding: the scales are the law's).
    elastic: f64,
    /// `4 n`: 4 or 6.
    power: usize,
    /// The damping's form and its scaled coefficient.
    damping: Damping,
    /// The spring's stiffness `kt` is `stiffness q^(2 mindlin)`: Mindlin's (`d^(1/2)`) or constant.
    mindlin: bool,
    stiffness: f64,
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Damping {
    None,
    /// `x q^power v` (the Hunt–Crossley family; `x = alpha v0`).
    Hysteresis(f64),
    /// `c v` (Kelvin–Voigt).
    Linear(f64),
    /// `a q v` (Tsuji's `d^(1/4) d'`).
    Quarter(f64),
}

impl SeriesLaw {
    /// The law and tangential law as series, where both are covered: no tangential damping, no rescaled unloading,
    /// a constant or Mindlin stiffness (either Coulomb cap); `None` otherwise (the slide then runs on Dop853).
    pub(super) fn new(
        law: &ContactLaw,
        scales: &Scales,
        tangential: &crate::dynamics::contact::Tangential,
    ) -> Option<Self> {
        if tangential.damping != 0.0
            || tangential.unloading != TangentialUnloading::None
            || !(tangential.exponent == 0.0 || tangential.exponent == 0.5)
            || !(tangential.stiffness.is_finite() && tangential.friction.is_finite())
        {
            return None;
        }
        let n = law.exponent;
        let power = match n {
            1.0 => 4,
            1.5 => 6,
            _ => return None,
        };
        let (l, v0, f0) = (scales.length, scales.speed, scales.force);
        let elastic = law.stiffness * l.powf(n) / f0;
        let damping = match law.kind.family() {
            Family::Elastic => Damping::None,
            Family::Hysteresis => Damping::Hysteresis(law.damping * v0),
            Family::Linear if power == 4 => Damping::Linear(law.damping * v0 / f0),
            Family::Tsuji if power == 6 => Damping::Quarter(law.damping * law.tsuji_scale * l.sqrt().sqrt() * v0 / f0),
            _ => return None,
        };
        let finite = match damping {
            Damping::None => true,
            Damping::Hysteresis(c) | Damping::Linear(c) | Damping::Quarter(c) => c.is_finite() && c >= 0.0,
        };
        (finite && elastic.is_finite() && elastic > 0.0).then_some(SeriesLaw {
            elastic,
            power,
            damping,
            mindlin: tangential.exponent == 0.5,
            stiffness: tangential.stiffness,
        })
    }
}

/// `Σ_(j=0..=k) a_j b_(k-j)`, in four interleaved sums (independent chains of multiply-adds: a product's latency
/// is its cost otherwise).
#[inline(always)]
fn cauchy(a: &[f64; CAPACITY], b: &[f64; CAPACITY], k: usize) -> f64 {
    let mut sums = [0.0; 4];
    let mut j = 0;
    while j + 4 <= k + 1 {
        for (lane, sum) in sums.iter_mut().enumerate() {
            *sum = a[j + lane].mul_add(b[k - j - lane], *sum);
        }
        j += 4;
    }
    for (lane, sum) in sums.iter_mut().enumerate().take(k + 1 - j) {
        *sum = a[j + lane].mul_add(b[k - j - lane], *sum);
    }
    (sums[0] + sums[1]) + (sums[2] + sums[3])
}

/// `Σ_(j=0..=k) a_j a_(k-j)`, each pair once.
#[inline(always)]
fn square(a: &[f64; CAPACITY], k: usize) -> f64 {
    let half = k.div_ceil(2);
    let mut sums = [0.0; 2];
    for j in 0..half {
        sums[j % 2] = a[j].mul_add(a[k - j], sums[j % 2]);
    }
    let middle = if k.is_multiple_of(2) { a[k / 2] * a[k / 2] } else { 0.0 };
    2.0 * (sums[0] + sums[1]) + middle
}

/// The coefficients of one step, each quantity's own array (kept between steps: every entry a step reads, it has
/// written first).
#[derive(Debug, Clone)]
pub(super) struct Arrays {
    q: [f64; CAPACITY],
    q2: [f64; CAPACITY],
    stretch: [f64; CAPACITY],
    elastic: [f64; CAPACITY],
    rate: [f64; CAPACITY],
    damped: [f64; CAPACITY],
    normal: [f64; CAPACITY],
    normal_rate: [f64; CAPACITY],
    dissipation: [f64; CAPACITY],
    spring: [f64; CAPACITY],
    tangential: [f64; CAPACITY],
    tangential_rate: [f64; CAPACITY],
    impulse: [f64; CAPACITY],
    slip: [f64; CAPACITY],
    q5: [f64; CAPACITY],
}

impl Default for Arrays {
    fn default() -> Arrays {
        let zero = [0.0; CAPACITY];
        Arrays {
            q: zero,
            q2: zero,
            stretch: zero,
            elastic: zero,
            rate: zero,
            damped: zero,
            normal: zero,
            normal_rate: zero,
            dissipation: zero,
            spring: zero,
            tangential: zero,
            tangential_rate: zero,
            impulse: zero,
            slip: zero,
            q5: zero,
        }
    }
}

impl SlideContact<'_> {
    /// [`crate::integrate::Model::expansion`] for the slide: `false` where the law is not a series
    /// ([`SeriesLaw::new`]), and for a slide on the compressive limit `mu max(Fn, 0)` of a law that can pull once its
    /// corner is no longer watched (a corner inside a step).
    pub(super) fn series(&self, y: &State<SIZE>, series: &mut [State<SIZE>]) -> bool {
        let Some(law) = self.series_law else { return false };
        let order = series.len() - 1;
        if order + 1 > CAPACITY || order < 2 {
            return false;
        }
        let (mode, unloaded) = super::mode_of(y);
        let friction = self.tangential.friction;
        // A slide's direction: the spring's, held for the slide (a slide that starts with no spring holds the
        // direction against the slip where it starts, `SlideContact::hold_direction`). One that has none — it
        // started where the slip was exactly zero — would take the slip's sign at each instant: no series.
        if mode.is_sliding() && !unloaded && y[index::SPRING].abs() <= 1e-300 {
            return false;
        }
        let along = || y[index::SPRING].signum();
        // The slide's force along the line per unit normal force (0: none). With the magnitude cap the limit
        // `mu |Fn|` is `mu Fn` or `-mu Fn` over a step: its corner at `Fn = 0` is a located switch (into or out of
        // the slide under tension).
        let sliding = match mode {
            Mode::Stick => None,
            Mode::Slip if unloaded => Some(0.0),
            // (The mode says which: its switches are located where the force passes through zero, and a state
            // there holds a force within rounding of zero, of either sign.)
            Mode::SlipInTension => Some(-along() * friction),
            Mode::Slip if self.tangential.cap == FrictionCap::Magnitude => Some(along() * friction),
            Mode::Slip if self.watches_unloading() || !self.law.kind.can_pull() => Some(along() * friction),
            Mode::Slip => return false,
        };
        let Ok(mut arrays) = self.arrays.try_borrow_mut() else { return false };
        let a = &mut *arrays;
        a.q[0] = y[index::ROOT];
        a.rate[0] = self.initial_rate - y[index::NORMAL_IMPULSE];
        a.spring[0] = y[index::SPRING];
        a.impulse[0] = y[index::TANGENTIAL_IMPULSE];
        let (per_normal, per_tangential) = self.immovable_rates;
        for k in 0..order {
            let next = 1.0 / (k + 1) as f64;
            a.q2[k] = square(&a.q, k);
            a.stretch[k] = cauchy(&a.q2, &a.q, k);
            let spring_power = if law.power == 6 { square(&a.stretch, k) } else { square(&a.q2, k) };
            a.elastic[k] = law.elastic * spring_power;
            let damped = match law.damping {
                Damping::None => 0.0,
                Damping::Hysteresis(x) => x * cauchy(&a.elastic, &a.rate, k),
                Damping::Linear(c) => c * a.rate[k],
                Damping::Quarter(c) => c * cauchy(&a.q, &a.rate, k),
            };
            a.damped[k] = damped;
            a.normal[k] = a.elastic[k] + damped;
            // dJn/dσ = Fn S; v = v(0) - Jn; dq/dσ = v/4; dt/dσ = S.
            a.normal_rate[k] = cauchy(&a.normal, &a.stretch, k);
            a.rate[k + 1] = -a.normal_rate[k] * next;
            a.q[k + 1] = 0.25 * a.rate[k] * next;
            let time = a.stretch[k] * next;
            // W + v²/2 constant.
            let work = -0.5 * square(&a.rate, k + 1);
            a.dissipation[k] = cauchy(&a.damped, &a.rate, k);
            // (dissipation S, one order: the product's k-th coefficient.)
            let dissipated = cauchy(&a.dissipation, &a.stretch, k);
            // The slip on the line: its initial value plus the gain times the tangential impulse.
            a.slip[k] =
                if k == 0 { self.initial_slip + self.slip_gain * a.impulse[0] } else { self.slip_gain * a.impulse[k] };
            match sliding {
                None => {
                    a.tangential[k] = a.spring[k];
                    a.tangential_rate[k] = cauchy(&a.tangential, &a.stretch, k);
                    // dξ/dσ = -kt slip S, kt = stiffness q² (Mindlin) or stiffness.
                    let loading = if law.mindlin {
                        a.q5[k] = cauchy(&a.q2, &a.stretch, k);
                        cauchy(&a.slip, &a.q5, k)
                    } else {
                        cauchy(&a.slip, &a.stretch, k)
                    };
                    a.spring[k + 1] = -law.stiffness * loading * next;
                }
                Some(along) => {
                    a.tangential[k] = along * a.normal[k];
                    a.tangential_rate[k] = along * a.normal_rate[k];
                    a.spring[k + 1] = 0.0;
                }
            }
            a.impulse[k + 1] = a.tangential_rate[k] * next;
            let shift = cauchy(&a.impulse, &a.stretch, k) * next;
            let tangential_work = cauchy(&a.tangential_rate, &a.slip, k) * next / self.friction_scale;
            let immovable = (per_normal * a.normal_rate[k] + per_tangential * a.tangential_rate[k]) * next;
            let row = &mut series[k + 1];
            row[index::ROOT] = a.q[k + 1];
            row[index::TIME] = time;
            row[index::NORMAL_IMPULSE] = -a.rate[k + 1];
            row[index::NORMAL_WORK] = work;
            row[index::DISSIPATED] = dissipated * next / self.dissipation_scale;
            row[index::SPRING] = a.spring[k + 1];
            row[index::TANGENTIAL_IMPULSE] = a.impulse[k + 1];
            row[index::TANGENTIAL_SHIFT] = shift;
            row[index::TANGENTIAL_WORK] = tangential_work;
            row[index::IMMOVABLE_WORK] = immovable;
            row[index::MODE] = 0.0;
        }
        series[0] = *y;
        true
    }
}

#[cfg(test)]
mod tests {
    use super::super::UNLOADED;
    use super::*;
    use crate::dynamics::ContactModel;
    use crate::integrate::Model;
    use crate::setup::Setup;

    /// Test 4's sphere on the wall at `degrees`, with the contact lines `contact`.
    fn scene(degrees: f64, contact: &str) -> crate::scene::Scene {
        let (sin, cos) = f64::to_radians(degrees).sin_cos();
        let text = format!(
            "[[bodies]]\nradius = 0.0025\ndensity = 4000\nvelocity = [{:?}, 0.0, {:?}]\nangular_velocity = [0.0, 300.0, 0.0]\n\
             young = 3.8e11\npoisson = 0.23\n\n[[bodies]]\nradius = inf\nmass = inf\nvelocity = [0.0, 0.0, 0.0]\n\
             young = inf\n\n[contact]\nnormal = [0.0, 0.0, -1.0]\n{contact}\n",
            3.9 * sin,
            -3.9 * cos
        );
        crate::scene::Scene::parse(&text, std::path::Path::new("test.toml")).unwrap()
    }

    /// The first coefficient is the model's derivative, and the second the derivative's rate along the flow (a
    /// central difference of the derivative a small step either way along it), in every mode the series covers,
    /// for each covered law: the recursions are the equations.
    #[test]
    fn the_coefficients_are_the_derivatives_of_the_equations() {
        let laws = [
            "law = \"tsuji\"\nrestitution = 0.9\nfriction = 0.2",
            "law = \"hunt-crossley\"\nrestitution = 0.8\nfriction = 0.3",
            "law = \"hertz\"\nfriction = 0.3",
            "law = \"hertz\"\nfriction = 0.3\ntangential_stiffness = 1e6",
            "law = \"tsuji\"\nrestitution = 0.3\nfriction = 0.4\nfriction_cap = \"magnitude\"\nseparation = \"penetration\"",
        ];
        for contact in laws {
            let scene = scene(30.0, contact);
            let setup = Setup::new(&scene).unwrap();
            let slide = SlideContact::new(&scene.bodies, &setup, scene.contact.separation).unwrap();
            assert!(slide.has_series(), "{contact}");
            // (Under the magnitude cap, also a slide while the force pulls: Tsuji's damping beyond its spring, late in
            // the restitution.)
            let pulling = contact.contains("magnitude");
            let mut modes = vec![(Mode::Stick.slot(), -0.01, 0.7, 0.6), (Mode::Slip.slot(), -0.02, 0.7, 0.6)];
            modes.push(if pulling {
                (Mode::SlipInTension.slot(), -0.02, 0.3, 1.9)
            } else {
                (UNLOADED, -0.02, 0.7, 0.6)
            });
            for (mode, spring, root, normal_impulse) in modes {
                let mut y = State::<SIZE>::zeros();
                y[index::ROOT] = root;
                y[index::TIME] = 1.1;
                y[index::NORMAL_IMPULSE] = normal_impulse;
                y[index::NORMAL_WORK] = 0.3;
                y[index::DISSIPATED] = 0.05;
                y[index::SPRING] = spring;
                y[index::TANGENTIAL_IMPULSE] = -0.04;
                y[index::TANGENTIAL_SHIFT] = -0.02;
                y[index::TANGENTIAL_WORK] = -0.01;
                y[index::MODE] = mode;
                if root < 0.5 {
                    assert!(slide.force(&y) < 0.0, "{contact}: the state pulls");
                }
                let mut series = vec![State::<SIZE>::zeros(); 9];
                assert!(slide.series(&y, &mut series), "{contact}, mode {mode}");
                let mut dy = State::<SIZE>::zeros();
                slide.derivative(0.0, &y, &mut dy);
                for i in 0..SIZE {
                    let scale = dy[i].abs().max(1e-12);
                    assert!(
                        (series[1][i] - dy[i]).abs() <= 1e-13 * scale.max(1.0),
                        "{contact}, mode {mode}, state {i}: {} against {}",
                        series[1][i],
                        dy[i]
                    );
                }
                let h = 1e-5;
                let (mut ahead, mut behind) = (State::<SIZE>::zeros(), State::<SIZE>::zeros());
                slide.derivative(0.0, &(y + dy * h), &mut ahead);
                slide.derivative(0.0, &(y - dy * h), &mut behind);
                for i in 0..SIZE {
                    let second = (ahead[i] - behind[i]) / (4.0 * h);
                    assert!(
                        (series[2][i] - second).abs() <= 1e-7 * second.abs().max(1e-3),
                        "{contact}, mode {mode}, state {i}: {} against {}",
                        series[2][i],
                        second
                    );
                }
            }
        }
    }
}
