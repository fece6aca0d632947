//! The times of a hysteresis-law impact by quadrature over its first integral (src/fast/first_integral_times.rs)
//! against truths from outside it: Hertz's closed form (a Beta function) and an RK4 integration of the equation of
//! motion itself, written here.

mod fast_support;

mod common;
use common::random::Random;
use impact::fast::{MAX_DAMPING, Times, first_integral_times};

fn rel(got: f64, want: f64) -> f64 {
    ((got - want) / want).abs()
}

/// Hertz (`x = 0`): energy gives `d^(n+1) = (n+1)(1 - v²)/2`, and `dt = -dv/d^n`, so
/// `t_max = ∫_0^1 ((n+1)(1 - v²)/2)^(-n/(n+1)) dv`; with `u = v²` this is
/// `((n+1)/2)^(-n/(n+1)) · ½ ∫_0^1 u^(-1/2) (1 - u)^(-n/(n+1)) du = ((n+1)/2)^(-n/(n+1)) B(1/2, 1/(n+1))/2`.
/// The motion is symmetric (the duration is twice that) and the force peaks at maximum compression.
fn hertz_max_compression_time(n: f64) -> f64 {
    let beta = |a: f64, b: f64| libm::tgamma(a) * libm::tgamma(b) / libm::tgamma(a + b);
    ((n + 1.0) / 2.0).powf(-n / (n + 1.0)) * beta(0.5, 1.0 / (n + 1.0)) / 2.0
}

#[test]
fn hertz_times_are_the_beta_function_closed_form() {
    // The classical value for n = 3/2: t_max = 1.4716 dmax/v0 with dmax = (5/4)^(2/5) (Johnson, Contact Mechanics,
    // §11.4), to its 5 digits.
    let t = hertz_max_compression_time(1.5);
    assert!(rel(t, 1.4716 * 1.25f64.powf(0.4)) < 5e-5, "{t}");
    for i in 0..=40 {
        let n = 1.0 + 2.0 * f64::from(i) / 40.0;
        let want = hertz_max_compression_time(n);
        let Times { max_compression, separation, peak_force } = first_integral_times(0.0, n);
        for (name, got, want) in
            [("t_max", max_compression, want), ("duration", separation, 2.0 * want), ("peak", peak_force, want)]
        {
            assert!(rel(got, want) < 1e-14, "n = {n}: {name} {got} vs {want} ({:e})", rel(got, want));
        }
    }
}

/// The state `(d, v)` of `d'' = -d^n (1 + x d')`.
#[derive(Clone, Copy)]
struct State {
    d: f64,
    v: f64,
}

fn acceleration(s: State, x: f64, n: f64) -> f64 {
    // (Never a power of a negative penetration: the steps end before the separation, see `reference_times`.)
    -s.d.max(0.0).powf(n) * (1.0 + x * s.v)
}

/// The increments `(Δd, Δv)` of one classical RK4 step of length `h`.
fn rk4_increment(s: State, h: f64, x: f64, n: f64) -> (f64, f64) {
    let f = |s: State| (s.v, acceleration(s, x, n));
    let at = |k: (f64, f64), c: f64| State { d: s.d + c * k.0, v: s.v + c * k.1 };
    let k1 = f(s);
    let k2 = f(at(k1, 0.5 * h));
    let k3 = f(at(k2, 0.5 * h));
    let k4 = f(at(k3, h));
    (h / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0), h / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1))
}

/// One classical RK4 step of length `h`.
fn rk4(s: State, h: f64, x: f64, n: f64) -> State {
    let (dd, dv) = rk4_increment(s, h, x, n);
    State { d: s.d + dd, v: s.v + dv }
}

/// A sum kept with its rounding error (Kahan): a million small steps of a creeping restitution would otherwise
/// drift by their roundings, which have a sign.
#[derive(Clone, Copy)]
struct Sum {
    value: f64,
    carry: f64,
}

impl Sum {
    fn add(&mut self, term: f64) {
        let y = term - self.carry;
        let sum = self.value + y;
        self.carry = (sum - self.value) - y;
        self.value = sum;
    }
}

/// The `τ` in `(0, h)` where `g` of the partial RK4 step from `s` changes sign (`g` at 0 and at `h` of opposite
/// signs): the Illinois method on the continuous function `τ -> g(rk4(s, τ))`.
fn crossing(s: State, h: f64, x: f64, n: f64, g: impl Fn(State) -> f64) -> f64 {
    let (mut a, mut b) = (0.0, h);
    let (mut ga, mut gb) = (g(s), g(rk4(s, h, x, n)));
    assert!(ga * gb <= 0.0);
    let mut side = 0;
    for _ in 0..200 {
        let c = b - gb * (b - a) / (gb - ga);
        let c = if c > a.min(b) && c < a.max(b) { c } else { 0.5 * (a + b) };
        let gc = g(rk4(s, c, x, n));
        if gc == 0.0 {
            return c;
        }
        if gc * gb < 0.0 {
            (a, ga) = (b, gb);
            side = 0;
        } else {
            if side == 1 {
                ga *= 0.5;
            }
            side = 1;
        }
        (b, gb) = (c, gc);
        if (b - a).abs() <= 4.0 * f64::EPSILON * b.abs().max(a.abs()) {
            return b;
        }
    }
    b
}

/// The times of maximum compression, separation and the force peak by RK4 on the equation of motion, with steps
/// `h = min(H, H/ω, θ/(x d^n), t/10)` (`H = 2e-4`; `ω² = n d^(n-1) (1 + x v)` the stiffness of the motion, 30 at
/// the start of a heavily damped one; `θ = 2e-3` of the damping's time `1/(x d^n)`; graded away from first contact,
/// where `d^n` is not smooth in `t` for a fractional `n`) and, towards separation, at most a tenth of the time left at the present rate,
/// down to `1e-7` of it, crossed at that rate (the force is `d^n` of a penetration `1e-7 e` deep there: what it
/// changes in the time is below 1e-20). The first `t0` comes from the series `d = t - (1+x) t^(n+2)/((n+1)(n+2))`,
/// `v = 1 - (1+x) t^(n+1)/(n+1)`, whose next terms are `(1+x)² t^(2n+2)` relative, kept below 1e-17. The events are
/// located on the partial step's solution; the state and the time are summed compensated ([`Sum`]).
fn reference_times(x: f64, n: f64) -> Times {
    const H: f64 = 2e-4;
    const THETA: f64 = 2e-3;
    let t0 = (1e-17 / ((1.0 + x) * (1.0 + x))).powf(1.0 / (2.0 * n + 2.0)).min(1e-3);
    let grow = (1.0 + x) / (n + 1.0);
    let start = State { d: t0 - grow * t0.powf(n + 2.0) / (n + 2.0), v: 1.0 - grow * t0.powf(n + 1.0) };
    let (mut d, mut v, mut time) =
        (Sum { value: start.d, carry: 0.0 }, Sum { value: start.v, carry: 0.0 }, Sum { value: t0, carry: 0.0 });
    let mut s = start;
    let peak_g = |s: State| n * s.v - x * s.d.powf(n + 1.0);
    let (mut max_compression, mut peak) = (f64::NAN, if x == 0.0 { None } else { Some(f64::NAN) });
    loop {
        let t = time.value;
        // The stiffness' frequency, sqrt(n d^(n-1) (1 + x v)), and the damping's rate x d^n.
        let frequency = (n * s.d.powf(n - 1.0) * (1.0 + x * s.v).max(0.0)).sqrt();
        let mut h = H.min(0.1 * t).min(H / frequency.max(1.0));
        let rate = x * s.d.powf(n);
        if rate > 0.0 {
            h = h.min(THETA / rate);
        }
        if s.v < 0.0 {
            let left = s.d / -s.v;
            if left < 1e-7 {
                time.add(left);
                break;
            }
            h = h.min(0.1 * left);
        }
        let (dd, dv) = rk4_increment(s, h, x, n);
        d.add(dd);
        v.add(dv);
        let next = State { d: d.value, v: v.value };
        if max_compression.is_nan() && next.v <= 0.0 {
            max_compression = t + crossing(s, h, x, n, |s| s.v);
        }
        if peak.is_some_and(f64::is_nan) && peak_g(next) <= 0.0 {
            peak = Some(t + crossing(s, h, x, n, peak_g));
        }
        s = next;
        time.add(h);
        assert!(s.d > 0.0 && time.value < 1e4, "x = {x}, n = {n}: the reference left the contact unseen");
    }
    Times { max_compression, separation: time.value, peak_force: peak.unwrap_or(max_compression) }
}

#[test]
fn the_reference_integration_gives_the_closed_form_for_hertz() {
    // The test of the test: the RK4 reference on Hertz's law against the Beta function, so that its 1e-11 below is
    // earned.
    for n in [1.0, 1.5, 2.3, 3.0] {
        let want = hertz_max_compression_time(n);
        let got = reference_times(0.0, n);
        assert!(rel(got.max_compression, want) < 1e-12, "n = {n}: {} vs {want}", got.max_compression);
        assert!(rel(got.separation, 2.0 * want) < 1e-12, "n = {n}: {} vs {}", got.separation, 2.0 * want);
    }
}

/// Random Hunt–Crossley impacts, `x` log-uniform from 1e-6 to the first integral's limit 1e3 and `n` uniform from 1
/// to 3, with the ends: the three times against the RK4 reference within 1e-11.
#[test]
fn hunt_crossley_times_match_an_rk4_integration() {
    let mut random = Random(0x9e37_79b9_7f4a_7c15);
    let mut cases = vec![(MAX_DAMPING, 1.0), (MAX_DAMPING, 1.5), (MAX_DAMPING, 3.0), (1e-6, 1.0), (35.0, 2.0)];
    cases.extend((0..200).map(|_| (random.log_uniform(1e-6, MAX_DAMPING), random.uniform(1.0, 3.0))));
    let mut worst: f64 = 0.0;
    for (x, n) in cases {
        let got = first_integral_times(x, n);
        let want = reference_times(x, n);
        for (name, got, want) in [
            ("t_max", got.max_compression, want.max_compression),
            ("duration", got.separation, want.separation),
            ("peak", got.peak_force, want.peak_force),
        ] {
            let error = rel(got, want);
            worst = worst.max(error);
            assert!(error < 1e-11, "x = {x}, n = {n}: {name} {got} vs {want} ({error:e})");
        }
    }
    eprintln!("largest relative difference from the RK4 reference: {worst:e}");
}

/// The first integral asked for every quantity (`fast::simulate_first_integral`: the times by quadrature) against the
/// Taylor integration at tolerance 1e-13 (an independent method: it integrates the equation of motion in its own
/// variables and takes the times by its own Gauss rules), over random dampings from 1e-6 to 1e3 and exponents from 1
/// to 3: every quantity within 1e-11 (the kinetic energy lost against the energy in play, as in tests/fast_path.rs).
/// A run's own path takes it, asked for a time, from `x >= TIMED_FROM`.
#[test]
fn every_quantity_agrees_with_a_tight_taylor_integration() {
    use fast_support::Case;
    use impact::fast::{Quantities, Request, TIMED_FROM, simulate_first_integral, simulate_normal, simulate_taylor};
    let mut random = Random(0x2545_f491_4f6c_dd1d);
    let mut worst: f64 = 0.0;
    for i in 0..200 {
        let x = if i == 0 { 0.0 } else { random.log_uniform(1e-6, MAX_DAMPING) };
        let n = random.uniform(1.0, 3.0);
        let case = if x == 0.0 { Case::Elastic { n } } else { Case::Hysteresis { x, n } };
        let tight = simulate_taylor(&case.request(1e-13)).unwrap();
        let out = simulate_first_integral(&case.request(1e-10)).unwrap();
        assert!(out.first_integral && out.steps == 0 && out.separated, "{}", case.name());
        for (name, got, want) in [
            ("e", -out.end.rate, -tight.end.rate),
            ("dmax", out.max_compression.penetration, tight.max_compression.penetration),
            ("t_max", out.max_compression.time, tight.max_compression.time),
            ("duration", out.end.time, tight.end.time),
            ("Fmax", out.peak_force, tight.peak_force),
            ("t_Fmax", out.peak_force_time, tight.peak_force_time),
            ("Jr", out.restitution_impulse, tight.restitution_impulse),
            ("Wr", out.restitution_work, tight.restitution_work),
            ("Dc", out.max_compression.dissipated, tight.max_compression.dissipated),
        ] {
            if name == "Dc" && x == 0.0 {
                continue;
            }
            let error = rel(got, want);
            worst = worst.max(error);
            assert!(error < 1e-11, "{}: {name} {got} vs {want} ({error:e})", case.name());
        }
        let lost = (out.end.work - tight.end.work).abs() / 0.5;
        assert!(lost < 1e-11, "{}: W {} vs {}", case.name(), out.end.work, tight.end.work);
        // A run asking for a time takes the first integral from x = TIMED_FROM (n from 1 to 3, a tolerance of at
        // least 1e-13), the same numbers; the integration below.
        let timed = simulate_normal(&case.request(1e-10)).unwrap();
        if x >= TIMED_FROM {
            assert!(timed.first_integral && timed.steps == 0, "{}", case.name());
            assert_eq!(timed.end.time.to_bits(), out.end.time.to_bits(), "{}", case.name());
            let tight = simulate_normal(&case.request(1e-14)).unwrap();
            assert!(!tight.first_integral && tight.steps > 0, "{}: tolerance 1e-14", case.name());
        } else {
            assert!(!timed.first_integral && timed.steps > 0, "{}", case.name());
        }
    }
    assert!(worst > 0.0, "the comparison compared nothing");
    eprintln!("largest relative difference from the Taylor integration at 1e-13: {worst:e}");
    // Beyond its limit it does not answer: the creep's ending is the integration's to say.
    let heavy = Case::Hysteresis { x: 2e3, n: 1.5 }.request(1e-10);
    assert!(simulate_first_integral(&Request { quantities: Quantities::ALL, ..heavy }).is_err());
}

/// The costs behind docs/numerics.md#the-first-integral, printed, not asserted (speed is the study's to measure):
/// `cargo test --release --test first_integral_times -- --ignored --nocapture`. For each damping, the median over
/// 21 batches of the time per impact: the first integral without the times, with them, and the Taylor integration
/// asked for every quantity at 1e-10 and 1e-13.
#[test]
#[ignore]
fn costs() {
    use fast_support::Case;
    use impact::fast::{Quantities, Request, simulate_first_integral, simulate_normal, simulate_taylor};
    use std::hint::black_box;
    use std::time::Instant;
    let median = |f: &dyn Fn()| {
        let mut times: Vec<f64> = (0..21)
            .map(|_| {
                let clock = Instant::now();
                for _ in 0..2000 {
                    f();
                }
                clock.elapsed().as_secs_f64() / 2000.0 * 1e6
            })
            .collect();
        times.sort_by(f64::total_cmp);
        times[10]
    };
    for x in [0.0, 1e-3, 0.1, 0.5, 2.0, 10.0, 100.0, 1e3] {
        let case = if x == 0.0 { Case::Elastic { n: 1.5 } } else { Case::Hysteresis { x, n: 1.5 } };
        let untimed = Request { quantities: Quantities { time: false, ..Quantities::ALL }, ..case.request(1e-10) };
        let all = case.request(1e-10);
        let tight = case.request(1e-13);
        let a = median(&|| {
            black_box(simulate_normal(black_box(&untimed)).unwrap());
        });
        let b = median(&|| {
            black_box(simulate_first_integral(black_box(&all)).unwrap());
        });
        let c = median(&|| {
            black_box(simulate_taylor(black_box(&all)).unwrap());
        });
        let d = median(&|| {
            black_box(simulate_taylor(black_box(&tight)).unwrap());
        });
        println!(
            "x = {x:7}: first integral {a:.3} µs, with the times {b:.3} µs, Taylor every quantity {c:.3} µs (1e-10), \
             {d:.3} µs (1e-13)"
        );
    }
}
