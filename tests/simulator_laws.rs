//! The laws of the simulators people use (docs/laws.md): `hertz-dashpot` (the DEM codes' Hertz with a viscous
//! dashpot), `mujoco` (MuJoCo's soft contact in its continuous-time limit) and `adams-impact` (ADAMS' IMPACT
//! function), each against an independent implementation written here (its force, a fourth-order Runge–Kutta at a
//! small fixed step, the separation interpolated on the last step), and MuJoCo's published case: a user who typed a
//! physical k and c for e = 0.75 into `solref` measured 0.82. Expected numbers never come from the program.

mod common;

use common::{assert_close, run};

/// A sphere of `mass` (kg), radius 1 m, at `speed` (m/s) on an immovable wall, with the `[contact]` lines given.
fn on_wall(mass: f64, speed: f64, contact: &str) -> String {
    format!(
        "[[bodies]]\nmass = {mass:?}\nradius = 1.0\nvelocity = [{speed:?}, 0.0, 0.0]\n\n\
         [[bodies]]\nradius = inf\nmass = inf\nvelocity = [0.0, 0.0, 0.0]\n\n[contact]\n{contact}\n"
    )
}

/// How the independent integration ends the contact.
#[derive(Clone, Copy, PartialEq)]
enum End {
    /// Where the penetration returns to zero.
    Penetration,
    /// Where the force (as the law would continue it) falls to zero while the bodies part.
    Force,
}

/// The e of a sphere of mass `m` on a wall at `speed` under the force `force(d, d')` (N; never called with d < 0),
/// by RK4 at `steps` steps per `time_scale` (s), the end found on the last step by linear interpolation of the end
/// function (d, or the force) and of the velocity.
fn independent_e(m: f64, speed: f64, time_scale: f64, steps: f64, end: End, force: impl Fn(f64, f64) -> f64) -> f64 {
    let h = time_scale / steps;
    // State (d, d'); d'' = -F/m, the force at d = 0 continued over the last step's overshoot (so that the step across
    // the end sees no jump of a damper's c d' and the interpolation keeps its second order).
    let acceleration = |d: f64, v: f64| -force(d.max(0.0), v) / m;
    let ending = |d: f64, v: f64| match end {
        End::Penetration => d,
        End::Force => {
            if d <= 0.0 {
                d
            } else {
                force(d, v)
            }
        }
    };
    let (mut d, mut v) = (0.0f64, speed);
    let mut turned = false;
    for _ in 0..100_000_000u64 {
        let (next_d, next_v) = rk4_step(d, v, h, &acceleration);
        turned |= next_v < 0.0;
        let (g0, g1) = (ending(d, v), ending(next_d, next_v));
        if turned && g0 > 0.0 && g1 <= 0.0 {
            let s = g0 / (g0 - g1);
            return -(v + s * (next_v - v)) / speed;
        }
        (d, v) = (next_d, next_v);
    }
    panic!("the independent integration did not separate");
}

/// One classical Runge–Kutta step of d'' = `acceleration(d, d')` from (d, v) over h.
fn rk4_step(d: f64, v: f64, h: f64, acceleration: &dyn Fn(f64, f64) -> f64) -> (f64, f64) {
    let (k1d, k1v) = (v, acceleration(d, v));
    let (k2d, k2v) = (v + 0.5 * h * k1v, acceleration(d + 0.5 * h * k1d, v + 0.5 * h * k1v));
    let (k3d, k3v) = (v + 0.5 * h * k2v, acceleration(d + 0.5 * h * k2d, v + 0.5 * h * k2v));
    let (k4d, k4v) = (v + h * k3v, acceleration(d + h * k3d, v + h * k3v));
    (d + h / 6.0 * (k1d + 2.0 * k2d + 2.0 * k3d + k4d), v + h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v))
}

/// MuJoCo's impedance (its `getimpedance`), written out: x = d / width; y = x^p / m^(p-1) up to the midpoint m,
/// 1 - (1 - x)^p / (1 - m)^(p-1) beyond; d_min + (d_max - d_min) y, d_max from x = 1 on.
fn impedance(solimp: [f64; 5], d: f64) -> f64 {
    let [low, high, width, m, p] = solimp;
    let x = d / width;
    if x >= 1.0 {
        return high;
    }
    let y = if x <= m { x.powf(p) / m.powf(p - 1.0) } else { 1.0 - (1.0 - x).powf(p) / (1.0 - m).powf(p - 1.0) };
    low + (high - low) * y
}

/// MuJoCo's continuous-time force on a body of mass `m` (MuJoCo reads solref per unit mass): with the reference
/// acceleration a_ref = -b v - k d(r) r and the constrained acceleration a1 = (1 - d) a0 + d a_ref (a0 = 0: nothing
/// else acts), F = m d(d) (b d' + k d(d) d), cut at zero (a contact never pulls). k and b from solref:
/// [timeconst, dampratio]: b = 2/(d_max tc), k = 1/(d_max² tc² dr²); [-stiffness, -damping]: b = damping/d_max,
/// k = stiffness/d_max².
fn mujoco_force(m: f64, solref: [f64; 2], solimp: [f64; 5], d: f64, rate: f64) -> f64 {
    let high = solimp[1];
    let (k, b) = if solref[0] > 0.0 {
        let (tc, dr) = (solref[0], solref[1]);
        (1.0 / (high * high * tc * tc * dr * dr), 2.0 / (high * tc))
    } else {
        (-solref[0] / (high * high), -solref[1] / high)
    };
    let imp = impedance(solimp, d);
    (m * imp * (b * rate + k * imp * d)).max(0.0)
}

const DEFAULT_SOLIMP: [f64; 5] = [0.9, 0.95, 0.001, 0.5, 2.0];

fn toml_list(values: &[f64]) -> String {
    let items: Vec<String> = values.iter().map(|x| format!("{x:?}")).collect();
    format!("[{}]", items.join(", "))
}

#[test]
fn mujoco_agrees_with_an_independent_implementation_of_its_continuous_law() {
    // Penetrations from a tenth of the impedance's width to far beyond it, both solref forms, default and custom
    // solimp (power 1 and 3, another midpoint).
    let cases: [(f64, f64, [f64; 2], [f64; 5]); 5] = [
        (0.5, 1.0, [-20000.0, -25.7924], DEFAULT_SOLIMP),
        (0.5, 0.02, [-20000.0, -25.7924], DEFAULT_SOLIMP),
        (2.0, 0.3, [0.02, 0.3], DEFAULT_SOLIMP),
        (1.0, 0.05, [0.01, 0.5], [0.5, 0.99, 0.002, 0.3, 3.0]),
        (1.0, 0.1, [-5000.0, -10.0], [0.2, 0.9, 0.01, 0.5, 1.0]),
    ];
    for (m, speed, solref, solimp) in cases {
        let contact = format!("law = \"mujoco\"\nsolref = {}\nsolimp = {}", toml_list(&solref), toml_list(&solimp));
        let report = run(&on_wall(m, speed, &contact));
        let e = report.contact.restitution_velocity_ratio.expect("separates");
        // The time scale: the undamped period's 1/(2 pi) at d_max, sqrt(1/k)/d_max-ish; 2e5 steps over it.
        let k_over_m = mujoco_force(1.0, solref, solimp, 1.0, 0.0) / 1.0;
        let scale = 1.0 / k_over_m.sqrt();
        let expected = independent_e(m, speed, scale, 2e4, End::Force, |d, v| mujoco_force(m, solref, solimp, d, v));
        assert_close(&format!("e, m = {m}, v0 = {speed}, solref {solref:?}, solimp {solimp:?}"), e, expected, 1e-7);
        // The energy balance closes with every term (the cut of the force is dissipation).
        let energy = &report.energy;
        let balance = energy.kinetic_before
            - (energy.kinetic_after.unwrap() + energy.dissipated.unwrap() + energy.elastic_left_at_separation.unwrap());
        assert!(balance.abs() < 1e-8 * energy.kinetic_before, "energy balance {balance:e}");
        assert_eq!(report.law.restitution_nominal, None, "a solref has no nominal e");
    }
}

#[test]
fn mujocos_published_case_a_physical_k_and_c_typed_into_solref() {
    // A 0.5 kg ball meant to bounce with e = 0.75 on a spring of k = 1e4 N/m: the linear spring–dashpot's damping
    // ratio for e = 0.75 is zeta = -ln e / sqrt(pi² + ln² e) = 0.0911905, c = 2 zeta sqrt(k m) = 12.8962 N s/m.
    // Typed as solref = [-k, -c], MuJoCo reads them per unit mass: the damping ratio becomes c / (2 sqrt(k)) =
    // zeta sqrt(m) = 0.06448.
    let (m, k, e_meant) = (0.5f64, 1e4f64, 0.75f64);
    let zeta = -e_meant.ln() / (std::f64::consts::PI.powi(2) + e_meant.ln().powi(2)).sqrt();
    assert!((zeta - 0.0911905).abs() < 1e-7);
    let c = 2.0 * zeta * (k * m).sqrt();
    // (1) Read as a physical spring–dashpot of k m and c m (what MuJoCo's per-unit-mass reading means for this
    // body), separating where the penetration returns to zero: e = exp(-pi zeta' / sqrt(1 - zeta'²)) = 0.816
    // (published: 0.816).
    let zeta_read = zeta * m.sqrt();
    let e_pulling = (-std::f64::consts::PI * zeta_read / (1.0 - zeta_read * zeta_read).sqrt()).exp();
    assert!((e_pulling - 0.816).abs() < 5e-4, "the hand calculation gives {e_pulling}");
    let kelvin_voigt = format!("law = \"kelvin-voigt\"\nstiffness = {:?}\ndamping = {:?}", k * m, c * m);
    let report = run(&on_wall(m, 1.0, &kelvin_voigt));
    assert_close(
        "the per-unit-mass reading, pulling",
        report.contact.restitution_velocity_ratio.unwrap(),
        e_pulling,
        1e-8,
    );
    // (2) MuJoCo's contact never pulls: it lets go where the force returns to zero, and e rises to 0.823
    // (published: 0.823).
    // (At 10 m/s the penetration, 10 cm, is far beyond the impedance's 1 mm width; at 1 m/s its rise over the first
    // millimetre still adds 4e-4.)
    let typed = format!("law = \"mujoco\"\nsolref = [{:?}, {:?}]", -k, -c);
    let e = run(&on_wall(m, 10.0, &typed)).contact.restitution_velocity_ratio.unwrap();
    assert!((e - 0.823).abs() < 5e-4, "MuJoCo's continuous law gives {e}, published 0.823");
    // (3) A correct per-unit-mass solref, [-k/m, -c/m], gives the zero-force separation of zeta itself: 0.7626
    // (published), once the penetration is far beyond the impedance's 1 mm width (here 35 cm, at 50 m/s: the width
    // adds about width / d_max to e, 4e-5 at 10 m/s).
    let per_mass = format!("law = \"mujoco\"\nsolref = [{:?}, {:?}]", -k / m, -c / m);
    let e = run(&on_wall(m, 50.0, &per_mass)).contact.restitution_velocity_ratio.unwrap();
    // The publication's 0.7626 is the zero-force e of zeta = 0.0912 cut at four decimals (0.76266).
    assert!((e - 0.7626).abs() < 1e-4, "the correct solref gives {e}, published 0.7626");
    let kelvin_voigt = |d: f64, v: f64| (k * d + c * v).max(0.0);
    let cut = independent_e(m, 1.0, (m / k).sqrt(), 2e4, End::Force, kelvin_voigt);
    assert!((e - cut).abs() < 5e-5, "the correct solref gives {e}, the zero-force linear spring–dashpot {cut}");
}

#[test]
fn hertz_dashpot_agrees_with_an_independent_implementation_and_its_e_depends_on_speed() {
    // F = K d^(3/2) + c d' with a constant c: the damping's share grows as the speed falls (c v0 against K d^(3/2),
    // d ~ v0^(4/5)), so e falls at lower speeds.
    let (m, k, c) = (0.1, 1e9, 20.0);
    let mut previous = 0.0;
    for speed in [0.1, 1.0, 10.0] {
        for (separation, end) in [("penetration", End::Penetration), ("force", End::Force)] {
            let contact =
                format!("law = \"hertz-dashpot\"\nstiffness = {k:e}\ndamping = {c:?}\nseparation = \"{separation}\"");
            let e = run(&on_wall(m, speed, &contact)).contact.restitution_velocity_ratio.unwrap();
            let length = (m * speed * speed / k).powf(0.4);
            let force = |d: f64, v: f64| k * d * d.sqrt() + c * v;
            let expected = independent_e(m, speed, length / speed, 1e5, end, force);
            assert_close(&format!("e at {speed} m/s, separation {separation}"), e, expected, 1e-7);
            if end == End::Penetration {
                assert!(e > previous, "e must rise with speed: {e} after {previous}");
                previous = e;
            }
        }
    }
}

#[test]
fn hertz_dashpot_at_exponent_one_is_kelvin_voigt_with_its_exact_map() {
    // n = 1: K d + c d' is the linear spring–dashpot; restitution e maps to c = 2 zeta sqrt(k m*) exactly, and the
    // e that comes out (penetration separation) is e.
    let contact = "law = \"hertz-dashpot\"\nstiffness = 1e6\nexponent = 1.0\nrestitution = 0.6";
    let report = run(&on_wall(0.2, 2.0, contact));
    assert_close("e", report.contact.restitution_velocity_ratio.unwrap(), 0.6, 1e-9);
    let zeta = -(0.6f64).ln() / (std::f64::consts::PI.powi(2) + (0.6f64).ln().powi(2)).sqrt();
    assert_close("c", report.law.damping, 2.0 * zeta * (1e6f64 * 0.2).sqrt(), 1e-14);
    assert!(report.reference.is_some(), "the Kelvin–Voigt closed forms are its exact reference");
}

/// ADAMS' IMPACT force, written out: K d^n + STEP(d, 0, 0, d_max, c_max) d', STEP the cubic s²(3 - 2s) of
/// s = d/d_max, cut at zero.
fn adams_force(k: f64, n: f64, cmax: f64, dmax: f64, d: f64, rate: f64) -> f64 {
    let s = (d / dmax).min(1.0);
    let step = s * s * (3.0 - 2.0 * s);
    (k * d.powf(n) + cmax * step * rate).max(0.0)
}

#[test]
fn adams_impact_agrees_with_an_independent_implementation() {
    let (m, k, n) = (1.0, 1e8, 1.5);
    for (cmax, dmax, speed) in [(500.0, 1e-4, 1.0), (2000.0, 1e-5, 0.5), (50.0, 1e-3, 2.0), (0.0, 1e-4, 1.0)] {
        let contact =
            format!("law = \"adams-impact\"\nstiffness = {k:e}\nexponent = {n:?}\ncmax = {cmax:?}\ndmax = {dmax:e}");
        let report = run(&on_wall(m, speed, &contact));
        let e = report.contact.restitution_velocity_ratio.unwrap();
        let length = (m * speed * speed / k).powf(1.0 / (n + 1.0));
        let force = |d: f64, v: f64| adams_force(k, n, cmax, dmax, d, v);
        let expected = independent_e(m, speed, length / speed, 1e5, End::Penetration, force);
        assert_close(&format!("e with c_max {cmax}, d_max {dmax}, v0 {speed}"), e, expected, 1e-7);
        if cmax == 0.0 {
            assert_close("undamped", e, 1.0, 1e-9);
        }
        let energy = &report.energy;
        let balance = energy.kinetic_before
            - (energy.kinetic_after.unwrap() + energy.dissipated.unwrap() + energy.elastic_left_at_separation.unwrap());
        assert!(balance.abs() < 1e-8 * energy.kinetic_before, "energy balance {balance:e}");
    }
}

/// MuJoCo's own step, semi-implicit Euler (v += dt a(d, v); d += dt v), on its continuous force from a touch on a
/// step boundary (no force at d = 0), until the penetration is not positive while the bodies part: e = -v/v0.
fn mujoco_euler_e(m: f64, speed: f64, solref: [f64; 2], dt: f64) -> f64 {
    let (mut d, mut v) = (0.0f64, speed);
    let mut turned = false;
    for _ in 0..10_000_000u64 {
        let force = if d > 0.0 { mujoco_force(m, solref, DEFAULT_SOLIMP, d, v) } else { 0.0 };
        v -= dt * force / m;
        d += dt * v;
        turned |= v <= 0.0;
        if turned && v < 0.0 && d <= 0.0 {
            return -v / speed;
        }
    }
    panic!("no separation");
}

#[test]
fn mujocos_euler_step_adds_to_e_at_first_order_in_the_step() {
    // The published case of `mujocos_published_case_a_physical_k_and_c_typed_into_solref` at MuJoCo's time steps:
    // `[solver] method = "symplectic-euler"` must be MuJoCo's step (an independent one written here), and its e
    // departs from the continuous one in proportion to dt.
    let (m, solref) = (0.5, [-1e4, -12.8962]);
    let contact = format!("law = \"mujoco\"\nsolref = [{:?}, {:?}]", solref[0], solref[1]);
    let mut differences = Vec::new();
    for dt in [4e-4, 2e-4, 1e-4] {
        let text = format!("{}\n[solver]\nmethod = \"symplectic-euler\"\ndt = {dt:e}\n", on_wall(m, 10.0, &contact));
        let report = run(&text);
        let e = report.contact.restitution_velocity_ratio.unwrap();
        assert_close(&format!("Euler's e at dt = {dt}"), e, mujoco_euler_e(m, 10.0, solref, dt), 1e-12);
        differences.push(e - report.solver.restitution_continuous.expect("the continuous e beside"));
    }
    for pair in differences.windows(2) {
        let ratio = pair[0] / pair[1];
        assert!((1.6..2.4).contains(&ratio), "first order in dt: differences {differences:?}");
    }
    assert!(differences.iter().all(|d| *d > 0.0), "the step adds to e: {differences:?}");
}

#[test]
fn hertz_dashpot_restitution_is_found_by_simulation_at_the_contact_speed() {
    // `restitution = e` for exponent n ≠ 1: the c that gives e at this contact's speed. Fed into the independent
    // implementation, that c gives e back; at another speed the same e needs another c.
    let (m, k) = (0.1, 1e9);
    for (n, e, speed, separation, end) in [
        (1.5, 0.7, 1.0, "penetration", End::Penetration),
        (1.5, 0.7, 0.1, "penetration", End::Penetration),
        (1.5, 0.4, 2.0, "force", End::Force),
        (2.0, 0.9, 0.5, "penetration", End::Penetration),
    ] {
        let contact = format!(
            "law = \"hertz-dashpot\"\nstiffness = {k:e}\nexponent = {n:?}\nrestitution = {e:?}\nseparation = \"{separation}\""
        );
        let report = run(&on_wall(m, speed, &contact));
        let c = report.law.damping;
        let length = (m * speed * speed / k).powf(1.0 / (n + 1.0));
        let force = |d: f64, v: f64| k * d.powf(n) + c * v;
        let independent = independent_e(m, speed, length / speed, 1e5, end, force);
        assert!((independent - e).abs() < 1e-7, "n {n}, v0 {speed}, {separation}: c = {c} gives {independent}");
        assert_close("the program's e", report.contact.restitution_velocity_ratio.unwrap(), e, 1e-9);
        assert_eq!(report.law.restitution_nominal, Some(e));
        assert!(
            report.notes.iter().any(|note| note.contains("found by simulation")),
            "the report says how c was found: {:?}",
            report.notes
        );
    }
}

/// A calibration of `law` on the scene text to the target e, through the library.
fn calibrated(text: &str, law: &str, target: f64) -> impact::calibrate::Calibration {
    let scene = impact::scene::Scene::parse(text, std::path::Path::new("calibrate.toml")).expect("scene");
    let request = impact::calibrate::Request {
        law: impact::law::LawKind::from_name(law).expect("a law"),
        restitution: target,
        approach_speed: None,
        separation: None,
        scene: Some(scene),
    };
    impact::calibrate::calibrate(&request).expect("calibrates")
}

#[test]
fn calibrated_mujoco_dampratio_gives_the_target_in_an_independent_implementation() {
    // solref = [timeconst, dampratio]: the dampratio for e, timeconst and solimp kept; and the direct form's damping.
    let solimp = [0.5, 0.99, 0.002, 0.3, 3.0];
    for (m, speed, solref, target) in
        [(1.0, 0.05, [0.01, 0.5], 0.6), (2.0, 0.3, [0.02, 1.0], 0.8), (0.5, 1.0, [-20000.0, -10.0], 0.5)]
    {
        let contact = format!("law = \"mujoco\"\nsolref = {}\nsolimp = {}", toml_list(&solref), toml_list(&solimp));
        let calibration = calibrated(&on_wall(m, speed, &contact), "mujoco", target);
        let p = calibration.damping.expect("a parameter");
        let found = if solref[0] > 0.0 { [solref[0], p] } else { [solref[0], -p] };
        let k_over_m = mujoco_force(1.0, found, solimp, 1.0, 0.0);
        let scale = 1.0 / k_over_m.sqrt();
        let e = independent_e(m, speed, scale, 2e4, End::Force, |d, v| mujoco_force(m, found, solimp, d, v));
        assert!((e - target).abs() < 1e-7, "solref {found:?}: e = {e}, target {target}");
    }
}

#[test]
fn calibrated_adams_cmax_gives_the_target_in_an_independent_implementation() {
    let (m, k, n) = (1.0, 1e8, 1.5);
    for (dmax, speed, target) in [(1e-4, 1.0, 0.7), (1e-5, 0.5, 0.3), (1e-3, 2.0, 0.9)] {
        let contact =
            format!("law = \"adams-impact\"\nstiffness = {k:e}\nexponent = {n:?}\ncmax = 1.0\ndmax = {dmax:e}");
        let calibration = calibrated(&on_wall(m, speed, &contact), "adams-impact", target);
        let cmax = calibration.damping.expect("c_max");
        let length = (m * speed * speed / k).powf(1.0 / (n + 1.0));
        let force = |d: f64, v: f64| adams_force(k, n, cmax, dmax, d, v);
        let e = independent_e(m, speed, length / speed, 1e5, End::Penetration, force);
        assert!((e - target).abs() < 1e-7, "c_max {cmax}: e = {e}, target {target}");
    }
}

/// Where the force of a sphere of mass `m` on a wall at `speed` returns to zero while the bodies part (the law's
/// force `force(d, d')` continued across zero, as a force separation ends it): the penetration there (m), by RK4 at
/// `steps` steps per `time_scale` (s), interpolated linearly on the last step.
fn independent_force_end(m: f64, speed: f64, time_scale: f64, steps: f64, force: impl Fn(f64, f64) -> f64) -> f64 {
    let h = time_scale / steps;
    let acceleration = |d: f64, v: f64| -force(d.max(0.0), v) / m;
    let (mut d, mut v) = (0.0f64, speed);
    for _ in 0..100_000_000u64 {
        let (next_d, next_v) = rk4_step(d, v, h, &acceleration);
        let (g0, g1) = (force(d, v), force(next_d, next_v));
        if v < 0.0 && g0 > 0.0 && g1 <= 0.0 {
            let s = g0 / (g0 - g1);
            return d + s * (next_d - d);
        }
        (d, v) = (next_d, next_v);
    }
    panic!("the independent integration did not end on its force");
}

#[test]
fn mujocos_spring_left_at_a_force_separation_is_the_integral_of_its_falling_impedance() {
    // An impedance that falls across its width (d_min = 0.9 > d_max = 0.02, as MuJoCo allows), wider than the
    // contact goes (about 18 um of 40): the spring m k d(d)² d is not (1/2) k d², and d(d) d = -b d'/k, where the
    // force vanishes, holds inside the width and again beyond it (at about 80 um, which this contact never
    // reaches). The elastic energy left where the force returns to zero must be m k ∫₀^d d(s)² s ds at the
    // penetration the contact reached (stress case 10014 of seed 424242 took the zero beyond the width and closed
    // its balance to 12 %).
    let (m, speed) = (1.0, 0.05);
    let solref = [-5000.0, -10.0];
    let solimp = [0.9, 0.02, 4e-5, 0.4, 2.2];
    let contact = format!(
        "law = \"mujoco\"\nsolref = {}\nsolimp = {}\nseparation = \"force\"",
        toml_list(&solref),
        toml_list(&solimp)
    );
    let report = run(&on_wall(m, speed, &contact));
    let left = report.energy.elastic_left_at_separation.expect("separates");
    // The independent end: the force written above, its zero by RK4; the spring's energy by Simpson's rule on
    // m k d(s)² s, k = stiffness / d_max² (solref's direct form).
    let k = -solref[0] / (solimp[1] * solimp[1]);
    // The fastest time scale: the spring's at the largest impedance, d_min.
    let scale = 1.0 / (k * solimp[0] * solimp[0]).sqrt();
    let end = independent_force_end(m, speed, scale, 2e4, |d, v| {
        let imp = impedance(solimp, d);
        m * imp * (-solref[1] / solimp[1] * v + k * imp * d)
    });
    let pieces = 20_000;
    let width = end / pieces as f64;
    let integrand = |s: f64| m * k * impedance(solimp, s).powi(2) * s;
    let simpson: f64 = (0..pieces)
        .map(|i| {
            let a = i as f64 * width;
            width / 6.0 * (integrand(a) + 4.0 * integrand(a + 0.5 * width) + integrand(a + width))
        })
        .sum();
    assert!(end > 0.0 && end < solimp[2], "the force ends inside the impedance's width: d = {end:e}");
    assert_close("elastic energy left at the force's zero", left, simpson, 1e-6);
    let energy = &report.energy;
    let balance = energy.kinetic_before - (energy.kinetic_after.unwrap() + energy.dissipated.unwrap() + left);
    assert!(balance.abs() < 1e-9 * energy.kinetic_before, "energy balance {balance:e}");
}

#[test]
fn mujocos_energy_balance_closes_whatever_the_power_of_its_impedance() {
    // The impedance d_min + (d_max - d_min) m (x/m)^p is rough at first touch and separation as p nears an integer
    // from below (its p-th derivative is infinite there): on stress case 18040 of seed 424242 the balance missed
    // 1e-9 of m* v0² at p = 1.95 and 2.9. Every power from 1.1 to 3.95, both separations: within 1e-9.
    let solref = [-567448.3312479574, -43.98969268702484];
    for p in [1.1, 1.5, 1.9, 1.95, 1.99, 2.01, 2.5, 2.9, 3.5, 3.95] {
        for separation in ["penetration", "force"] {
            let solimp = [0.549, 0.897, 0.0321, 0.597, p];
            let contact = format!(
                "law = \"mujoco\"\nsolref = {}\nsolimp = {}\nseparation = \"{separation}\"",
                toml_list(&solref),
                toml_list(&solimp)
            );
            let report = run(&on_wall(6011.6, 514.8, &contact).replace("radius = 1.0", "radius = 4181.0"));
            let e = &report.energy;
            let balance = e.kinetic_before
                - (e.kinetic_after.unwrap() + e.dissipated.unwrap() + e.elastic_left_at_separation.unwrap());
            assert!(
                balance.abs() < 1e-9 * e.kinetic_before,
                "p = {p}, {separation}: balance {:e}",
                balance / e.kinetic_before
            );
            assert!(report.notes.iter().all(|n| !n.contains("energy balance")), "p = {p}: {:?}", report.notes);
        }
    }
}
