//! The rod dropped at an angle (src/rod_sweep.rs, docs/rigid.md#a-rod-dropped-at-an-angle): its first blow, which
//! end strikes next and when, and the sweep's apparent e and contact counts, against references worked here — the
//! closed forms of rigid-body theory (docs/references.md#rigid-bodies-with-several-contacts) and a planar rigid rod flown and struck in this file (its own code, not the
//! library's).

use impact::rod_sweep::{self, G, LENGTH, MASS, RADIUS};
use serde_json::Value;

mod common;

use common::world_report_json as run;

#[track_caller]
fn number(value: &Value) -> f64 {
    value.as_f64().unwrap_or_else(|| panic!("expected a number, found {value}"))
}

/// The planar rigid rod of this file: mass centre height z and vertical velocity w, the axis's angle a above the
/// floor (end 0 at +(L/2)(cos a, sin a), end 1 at -), and the spin s about +y, which turns the axis down (a' = -s).
#[derive(Clone, Copy, Debug)]
struct Rod {
    z: f64,
    w: f64,
    a: f64,
    s: f64,
}

const I_G: f64 = MASS * LENGTH * LENGTH / 12.0;

impl Rod {
    fn after(self, t: f64) -> Rod {
        Rod { z: self.z + self.w * t - G * t * t / 2.0, w: self.w - G * t, a: self.a - self.s * t, s: self.s }
    }

    /// The height of end `k`'s sphere's lowest point.
    fn height(self, k: usize) -> f64 {
        let sign = [1.0, -1.0][k];
        self.z + sign * LENGTH / 2.0 * self.a.sin() - RADIUS
    }

    /// Strikes end `k` on the smooth floor with e: impulse p along +z at x = ±(L/2) cos a; the point's vertical
    /// velocity w - s x becomes -e times itself: p (1/M + x²/I) = -(1 + e)(w - s x).
    fn strike(&mut self, k: usize, e: f64) {
        let x = [1.0, -1.0][k] * LENGTH / 2.0 * self.a.cos();
        let u = self.w - self.s * x;
        if u < 0.0 {
            let p = -(1.0 + e) * u / (1.0 / MASS + x * x / I_G);
            self.w += p / MASS;
            self.s -= x * p / I_G;
        }
    }

    /// The first touch of either end within `horizon` s: sampled every 1 µs, then bisected.
    fn touch(self, horizon: f64) -> Option<(f64, usize)> {
        let dt = 1e-6;
        let steps = (horizon / dt).ceil() as usize;
        for i in 1..=steps {
            let t = (i as f64 * dt).min(horizon);
            for k in 0..2 {
                if self.after(t).height(k) < 0.0 {
                    let (mut lo, mut hi) = ((i - 1) as f64 * dt, t);
                    for _ in 0..100 {
                        let mid = 0.5 * (lo + hi);
                        if self.after(mid).height(k) < 0.0 { hi = mid } else { lo = mid }
                    }
                    let other = 1 - k;
                    if self.after(t).height(other) < 0.0 {
                        let (mut lo2, mut hi2) = ((i - 1) as f64 * dt, t);
                        for _ in 0..100 {
                            let mid = 0.5 * (lo2 + hi2);
                            if self.after(mid).height(other) < 0.0 { hi2 = mid } else { lo2 = mid }
                        }
                        if hi2 < hi {
                            return Some((hi2, other));
                        }
                    }
                    return Some((hi, k));
                }
            }
        }
        None
    }
}

/// The rigid rod's impact sequence from the first touch of its lower end at `degrees` and speed v with constant e:
/// (the mass centre's vertical velocity when it is over / v, the ends struck), over when the mass centre rises and
/// no end touches before the apex.
fn rigid(degrees: f64, v: f64, e: f64) -> (f64, Vec<usize>) {
    let a = degrees.to_radians();
    let mut rod = Rod { z: LENGTH / 2.0 * a.sin() + RADIUS, w: -v, a, s: 0.0 };
    let mut end = 1;
    let mut ends = Vec::new();
    loop {
        rod.strike(end, e);
        ends.push(end);
        assert!(ends.len() < 50, "{degrees}°: no end to the sequence");
        let horizon = if rod.w > 0.0 { rod.w / G } else { 1.0 };
        match rod.touch(horizon) {
            None => return (rod.w / v, ends),
            Some((t, k)) => {
                rod = rod.after(t);
                end = k;
            }
        }
    }
}

/// Dropped at 80°, the rod's other end rises after the first blow (cos²80° = 0.030 < e/(3(2 + e)) = 0.098): one
/// contact, whose blow is rigid-body theory's with its own e — J/(M v) = (1 + e)/(1 + 3 cos²θ), ω' = 6 J cos θ/(M L), v_B > 0 —
/// to 3 ω' t_c (the rod turns by ω' t_c during the compliant contact), no contact before the apex of the rebound, and
/// the other end landing where the rigid rod flown from the first touch (this file's) brings it down, to 3 t_c.
/// At 30°, 45° and 60° the other end strikes next, at the rigid flight's time.
#[test]
fn the_rod_at_80_degrees_rebounds_on_one_contact_and_at_30_to_60_its_other_end_strikes_when_the_rigid_flight_says() {
    for degrees in [30.0, 45.0, 60.0, 80.0] {
        let report = run(&rod_sweep::scene(degrees, 2, 0.3));
        let first = &report["contacts"][0];
        assert_eq!(first["spheres"][0], 1, "{degrees}°: the lower end first: {first}");
        let v = number(&first["approach_speed"]);
        let e = number(&first["restitution_velocity_ratio"]);
        let t_c = number(&first["duration"]);
        let theta = f64::to_radians(degrees);
        let c2 = theta.cos().powi(2);
        let blow = (1.0 + e) / (1.0 + 3.0 * c2);
        let spin = 6.0 * blow * MASS * v * theta.cos() / (MASS * LENGTH);
        let w = number(&first["velocities_after"][0][2]);
        let s = number(&first["angular_velocities_after"][0][1]);
        let tolerance = 3.0 * spin * t_c;
        assert!(((w + v) / v - blow).abs() < tolerance * blow, "{degrees}°: J/(M v) {} vs {blow}", (w + v) / v);
        assert!((s - spin).abs() < tolerance * spin, "{degrees}°: ω' {s} vs {spin}");
        let v_b = w - s * LENGTH / 2.0 * theta.cos();
        let expected = -v + (1.0 + e) * v * (1.0 - 3.0 * c2) / (1.0 + 3.0 * c2);
        assert!((v_b - expected).abs() < tolerance * v, "{degrees}°: v_B {v_b} vs {expected}");
        assert_eq!(v_b > 0.0, degrees == 80.0, "{degrees}°: the other end rises at 80° only: {v_b}");

        let rod = Rod { z: LENGTH / 2.0 * theta.sin() + RADIUS, w, a: theta, s };
        let (flight, end) = rod.touch(1.0).expect("the rod lands again within 1 s");
        let second = &report["contacts"][1];
        assert_eq!(second["spheres"][0], end as u64, "{degrees}°: the end that strikes next: {second}");
        let at = number(&second["start_time"]) - number(&first["start_time"]);
        assert!((at - flight).abs() < 3.0 * t_c, "{degrees}°: next contact {at} s after the first, not {flight}");
        if degrees == 80.0 {
            let apex = number(&first["end_time"]) + w / G;
            assert!(w > 0.0 && number(&second["start_time"]) > apex, "80°: nothing before the apex {apex}: {second}");
            assert!(rod.touch(w / G).is_none());
        }
    }
}

/// The sweep at a few angles against this file's rigid rod with the simulated first contact's e: where the rigid
/// count is unambiguous (the same at θ ± 1° and at e ± 0.01), the simulation and the sequential model take as many
/// contacts and end on the same ends, and their apparent e is the rigid rod's to 5e-3 (the compliant contacts'
/// turning, ω t_c, and their e, which varies by 1e-3 with the speed, against one constant e); the library's own
/// rigid rod is this file's to 1e-6. At 80° (one contact) the apparent e is rigid-body theory's (1 + e)/(1 + 3 cos²θ) - 1: the
/// rebound's apex is measured from the contact's end, and gravity acts only during the contact (g t_c/v = 1e-3).
#[test]
fn the_sweep_counts_the_rigid_rods_contacts_and_its_apparent_e_where_they_are_unambiguous() {
    let angles = [5.0, 20.0, 40.0, 50.0, 70.0, 80.0];
    let points = rod_sweep::sweep(&angles).expect("the sweep runs");
    assert_eq!(points.len(), angles.len());
    for p in &points {
        let v = rod_sweep::touch_speed();
        let (apparent, ends) = rigid(p.degrees, v, p.e);
        for (d, de) in [(-1.0, 0.0), (1.0, 0.0), (0.0, -0.01), (0.0, 0.01)] {
            let (_, nearby) = rigid(p.degrees + d, v, p.e + de);
            assert_eq!(nearby.len(), ends.len(), "{}°: the rigid count is ambiguous ({d}°, {de})", p.degrees);
        }
        assert_eq!(p.simulated.ends, ends, "{}°: simulated ends", p.degrees);
        assert_eq!(p.simulated.contacts(), ends.len());
        assert_eq!(p.sequential.ends, ends, "{}°: the sequential model's ends", p.degrees);
        let rigid = p.rigid.as_ref().expect("the library's rigid rod ends its sequence");
        assert_eq!(rigid.ends, ends, "{}°: the library's rigid ends", p.degrees);
        assert!((rigid.apparent_e - apparent).abs() < 1e-6, "{}°: {} vs {apparent}", p.degrees, rigid.apparent_e);
        for (what, value) in [("simulated", p.simulated.apparent_e), ("sequential", p.sequential.apparent_e)] {
            assert!((value - apparent).abs() < 5e-3, "{}°: {what} apparent e {value} vs rigid {apparent}", p.degrees);
        }
        if p.degrees == 80.0 {
            let closed = (1.0 + p.e) / (1.0 + 3.0 * f64::to_radians(80.0).cos().powi(2)) - 1.0;
            assert!((apparent - closed).abs() < 1e-9, "80°: the rigid rod {apparent} vs the closed form {closed}");
            assert!((p.simulated.apparent_e - closed).abs() < 5e-3, "80°: {} vs {closed}", p.simulated.apparent_e);
        }
    }
}

/// models/rod-80deg.toml is `rod_sweep::scene` at 80° with two contacts and 0.3 s, its comments aside.
#[test]
fn the_80_degree_model_is_the_sweeps_scene() {
    let strip =
        |text: &str| -> Vec<String> { text.lines().filter(|l| !l.starts_with('#')).map(String::from).collect() };
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/models/rod-80deg.toml");
    let file = std::fs::read_to_string(path).unwrap();
    assert_eq!(strip(&file), strip(&rod_sweep::scene(80.0, 2, 0.3)));
}
