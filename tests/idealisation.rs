//! The idealisation on trial (docs/idealisation.md): each verdict's value and scale against a hand calculation from
//! the closed forms (Hertz's contact of two steel balls, the Hunt–Crossley restitution, rigid-body sliding), the
//! verdicts that flip with the scene, and the JSON contract of the `idealisation` object.

mod common;

use common::binary::{Scratch, impact as binary, stdout};
use common::{assert_close, on_wall, run};
use impact::idealisation::{Judgement, Verdict};
use impact::output::table::render;
use impact::report::Report;
use serde_json::Value;
use std::f64::consts::PI;

// Steel (docs/references.md): E, nu, rho; a 10 mm radius; a yield stress of 1 GPa.
const YOUNG: f64 = 2.1e11;
const POISSON: f64 = 0.3;
const DENSITY: f64 = 7850.0;
const RADIUS: f64 = 0.01;
const STANDARD_GRAVITY: f64 = 9.80665;
/// (4/5) B(2/5, 1/2) = (4/5) Γ(2/5) Γ(1/2) / Γ(9/10): Hertz's contact time over d_max / v0 (docs/references.md;
/// Python's math.gamma gives 2.9432751843247047).
const HERTZ_TIME: f64 = 2.943_275_184_324_704_7;

/// Two equal steel balls closing at `speed` (m/s) along x, each with the yield stress `yield_stress` (Pa) if given,
/// and the given `[contact]` lines.
fn steel_pair(speed: f64, yield_stress: Option<f64>, contact: &str) -> String {
    let yield_line = yield_stress.map_or(String::new(), |y| format!("yield_stress = {y:e}\n"));
    let body = |name: &str, v: f64| {
        format!(
            "[[bodies]]\nname = \"{name}\"\nradius = {RADIUS:?}\ndensity = {DENSITY:?}\nvelocity = [{v:?}, 0.0, 0.0]\n\
             young = {YOUNG:e}\npoisson = {POISSON:?}\n{yield_line}\n"
        )
    };
    format!("{}{}[contact]\n{contact}\n", body("A", speed / 2.0), body("B", -speed / 2.0))
}

/// Hertz's elastic contact of the two steel balls at approach speed `v0`, by hand (docs/references.md#elastic-hertz-contact).
struct HertzPair {
    mass: f64,
    effective_mass: f64,
    effective_radius: f64,
    max_penetration: f64,
    duration: f64,
    max_force: f64,
    contact_radius: f64,
    peak_pressure: f64,
}

fn hertz_pair(v0: f64) -> HertzPair {
    let mass = DENSITY * 4.0 / 3.0 * PI * RADIUS.powi(3);
    let effective_mass = mass / 2.0;
    let effective_radius = RADIUS / 2.0;
    let modulus = YOUNG / (2.0 * (1.0 - POISSON * POISSON));
    let stiffness = 4.0 / 3.0 * modulus * effective_radius.sqrt();
    let max_penetration =
        (15.0 * effective_mass * v0 * v0 / (16.0 * modulus * effective_radius.sqrt())).powf(2.0 / 5.0);
    let duration = HERTZ_TIME * max_penetration / v0;
    // The same time in the form (m*²/(K² v0))^(1/5): its coefficient is HERTZ_TIME (5/4)^(2/5) = 3.21807, not 2.94.
    let other_form = HERTZ_TIME * 1.25f64.powf(0.4) * (effective_mass.powi(2) / (stiffness.powi(2) * v0)).powf(0.2);
    assert!(((duration - other_form) / duration).abs() < 1e-14);
    let max_force = stiffness * max_penetration.powf(1.5);
    let contact_radius = (effective_radius * max_penetration).sqrt();
    let peak_pressure = 3.0 * max_force / (2.0 * PI * contact_radius.powi(2));
    // Hertz's p0 = 2 E* a / (pi R*) (Johnson, Contact Mechanics, eq. 4.23 with a² = R* d).
    assert!((peak_pressure / (2.0 * modulus * contact_radius / (PI * effective_radius)) - 1.0).abs() < 1e-14);
    HertzPair {
        mass,
        effective_mass,
        effective_radius,
        max_penetration,
        duration,
        max_force,
        contact_radius,
        peak_pressure,
    }
}

#[track_caller]
fn verdict<'a>(verdict: &'a Option<Verdict>, what: &str) -> &'a Verdict {
    verdict.as_ref().unwrap_or_else(|| panic!("{what}: no verdict"))
}

/// Value, scale and verdict of one assumption, to 1e-3 of the hand calculation (the ratio is their quotient).
#[track_caller]
fn assert_verdict(what: &str, got: &Option<Verdict>, value: f64, compared_with: f64, judgement: Judgement) {
    let v = verdict(got, what);
    if value == 0.0 {
        assert_eq!(v.value, 0.0, "{what} value");
    } else {
        assert_close(&format!("{what} value"), v.value, value, 1e-3);
    }
    assert_close(&format!("{what} compared_with"), v.compared_with, compared_with, 1e-3);
    assert_eq!(v.ratio, v.value / v.compared_with, "{what}: ratio");
    assert_eq!(v.verdict, judgement, "{what}: {} (ratio {:e})", v.meaning, v.ratio);
}

#[test]
fn steel_balls_at_a_tenth_of_a_metre_per_second_are_judged_from_hertz_closed_forms() {
    let v0 = 0.1;
    let report = run(&steel_pair(v0, Some(1e9), "law = \"hertz\""));
    let hertz = hertz_pair(v0);
    let ideal = &report.idealisation;
    // The report's own numbers are Hertz's (the verdicts are read from them).
    assert_close("d_max", report.contact.max_penetration, hertz.max_penetration, 1e-9);
    assert_close("F_max", report.contact.max_force, hertz.max_force, 1e-9);
    // Relative speed v0 before and after (e = 1), over t_c, against the 10 mm radius: 9.5e-4.
    assert_verdict("instantaneous", &ideal.instantaneous, v0 * hertz.duration, RADIUS, Judgement::Holds);
    // m g t_c of one ball against the impulse (1 + e) m* v0 = 2 m* v0: g t_c / v0 = 9.4e-3.
    let gravity = hertz.mass * STANDARD_GRAVITY * hertz.duration;
    assert_verdict("isolated", &ideal.isolated, gravity, 2.0 * hertz.effective_mass * v0, Judgement::Holds);
    // a = sqrt(R* d_max) = 127 µm is the largest of d_max, a and R ω t_c (no spin): 1.27e-2 of R.
    assert!(hertz.contact_radius > hertz.max_penetration);
    assert_verdict("particles", &ideal.particles, hertz.contact_radius, RADIUS, Judgement::Holds);
    assert_eq!(verdict(&ideal.particles, "particles").measure, "a / R");
    // p0 = 1.87 GPa against 1.6 GPa: yield has begun (the balls' yield speed is 0.068 m/s, Thornton 1997), but
    // below twice that speed (p0 / 1.6 Y < 2^(2/5)).
    assert_verdict("elastic", &ideal.elastic, hertz.peak_pressure, 1.6e9, Judgement::Marginal);
    // 2R / sqrt(E/rho) = 3.87 µs against t_c = 95.4 µs.
    let transit = 2.0 * RADIUS / (YOUNG / DENSITY).sqrt();
    assert_verdict("quasi_static", &ideal.quasi_static, transit, hertz.duration, Judgement::Holds);
    // Hertz's e is 1 at every speed: the slope is zero.
    let constant_e = verdict(&ideal.constant_e, "constant_e");
    assert!(constant_e.value.abs() < 1e-8, "slope {:e}", constant_e.value);
    assert_eq!((constant_e.compared_with, constant_e.verdict), (0.1, Judgement::Holds));
    // Frictionless: no tangential impulse, against the normal impulse 2 m* v0.
    assert_verdict("smooth", &ideal.smooth, 0.0, 2.0 * hertz.effective_mass * v0, Judgement::Holds);
    // Spheres are central: b = 0 against the radius of gyration sqrt(2/5) R.
    assert_verdict("central", &ideal.central, 0.0, (0.4f64).sqrt() * RADIUS, Judgement::Holds);
    let _ = hertz.effective_radius;
}

#[test]
fn the_elastic_verdict_follows_the_peak_pressure_and_needs_a_yield_stress() {
    // 1 cm/s: p0 = 0.75 GPa, below 1.6 Y = 1.6 GPa.
    let slow = run(&steel_pair(0.01, Some(1e9), "law = \"hertz\""));
    assert_verdict("slow elastic", &slow.idealisation.elastic, hertz_pair(0.01).peak_pressure, 1.6e9, Judgement::Holds);
    // 1 m/s against a soft yield stress of 0.3 GPa: p0 = 4.7 GPa, ten times the yield pressure.
    let fast = run(&steel_pair(1.0, Some(3e8), "law = \"hertz\""));
    assert_verdict("fast elastic", &fast.idealisation.elastic, hertz_pair(1.0).peak_pressure, 4.8e8, Judgement::Fails);
    // Without a yield stress (or with an infinite one) there is nothing to judge.
    assert!(run(&steel_pair(1.0, None, "law = \"hertz\"")).idealisation.elastic.is_none());
    assert!(run(&steel_pair(1.0, Some(f64::INFINITY), "law = \"hertz\"")).idealisation.elastic.is_none());
}

#[test]
fn a_slow_touch_would_feel_gravity() {
    // At 1 mm/s the contact lasts 240 µs: g t_c / v0 = 2.4, gravity's impulse outgrows the contact's.
    let v0 = 1e-3;
    let report = run(&steel_pair(v0, None, "law = \"hertz\""));
    let hertz = hertz_pair(v0);
    let gravity = hertz.mass * STANDARD_GRAVITY * hertz.duration;
    assert_verdict(
        "isolated",
        &report.idealisation.isolated,
        gravity,
        2.0 * hertz.effective_mass * v0,
        Judgement::Fails,
    );
}

/// The Hunt–Crossley restitution e(x), x = alpha v0, solved here by bisection from its defining relation
/// x (1 + e) = ln((1 + x) / (1 - e x)) (Hunt & Crossley 1975; docs/references.md), whose left side less its right
/// falls monotonically in e on (0, 1).
fn hunt_crossley_e(x: f64) -> f64 {
    let g = |e: f64| x * (1.0 + e) - ((1.0 + x) / (1.0 - e * x)).ln();
    let (mut low, mut high) = (0.0, 1.0);
    for _ in 0..200 {
        let mid = 0.5 * (low + high);
        if g(mid) > 0.0 { low = mid } else { high = mid }
    }
    0.5 * (low + high)
}

/// d ln e / d ln v0 = d ln e / d ln x of the Hunt–Crossley e, by the verdict's own central difference at 0.9 and 1.1.
fn hunt_crossley_slope(x: f64) -> f64 {
    (hunt_crossley_e(1.1 * x) / hunt_crossley_e(0.9 * x)).ln() / (1.1f64 / 0.9).ln()
}

#[test]
fn hunt_crossley_restitution_falls_with_speed_as_its_exact_relation_says() {
    // alpha = 0.2 s/m at 1 m/s: x = 0.2, e = 0.884.
    let report = on_wall(1.0, 1.0, "law = \"hunt-crossley\"\nstiffness = 1e8\ndamping = 0.2");
    let x: f64 = 0.2;
    assert_close("e", report.contact.restitution_velocity_ratio.unwrap(), hunt_crossley_e(x), 1e-8);
    let slope = verdict(&report.idealisation.constant_e, "constant_e");
    assert_close("slope", slope.value, hunt_crossley_slope(x), 1e-6);
    // Its sign and size: the implicit derivative of the relation G(x, e) = 0, de/dx = -G_x / G_e, agrees with the
    // difference to a per cent.
    let e = hunt_crossley_e(x);
    let g_x = (1.0 + e) - 1.0 / (1.0 + x) - e / (1.0 - e * x);
    let g_e = x - x / (1.0 - e * x);
    let derivative = x * (-g_x / g_e) / e;
    assert!(slope.value < 0.0);
    assert_close("slope against the derivative", slope.value, derivative, 1e-2);
    // |slope| = 0.15 > 0.1: e is not constant over speed.
    assert_eq!((slope.compared_with, slope.verdict), (0.1, Judgement::Fails));
}

#[test]
fn a_nominal_restitution_keeps_its_damping_when_the_speed_changes() {
    // A nominal e = 0.9 at 2 m/s sets alpha v0 = chi = 3 (1 - e) / 2 = 0.15 (Hunt & Crossley's map, docs/laws.md);
    // the trial keeps alpha, so its slope is the exact one at x = 0.15 (the map re-applied at each speed would hold
    // e fixed and give 0).
    let report = on_wall(1.0, 2.0, "law = \"hunt-crossley\"\nstiffness = 1e8\nrestitution = 0.9");
    let slope = verdict(&report.idealisation.constant_e, "constant_e");
    assert_close("slope at x = 0.15", slope.value, hunt_crossley_slope(0.15), 1e-6);
}

#[test]
fn a_sliding_contact_is_not_smooth() {
    // Carvalho–Martins' law slides throughout above 32.5 degrees (docs/oblique.md): the tangential impulse is mu
    // times the normal one, J_n = m (1 + e) vn, and friction's work mu J_n (s0 - mu B J_n / 2), B = 7 / (2 m) (the
    // slip falls by mu B per unit normal impulse), exceeds mu times the kinetic energy at 60 degrees.
    let (mu, speed, angle) = (0.092, 3.9, 60f64.to_radians());
    let (vt, vn) = (speed * angle.sin(), speed * angle.cos());
    let text = format!(
        "[[bodies]]\nradius = 0.0025\ndensity = 4000\nvelocity = [{vt:?}, 0.0, {:?}]\nyoung = 3.8e11\npoisson = 0.23\n\n\
         [[bodies]]\nradius = inf\nmass = inf\nvelocity = [0.0, 0.0, 0.0]\nyoung = inf\n\n\
         [contact]\nnormal = [0.0, 0.0, -1.0]\nlaw = \"carvalho-martins\"\nrestitution = 0.98\nfriction = {mu}\n",
        -vn
    );
    let report = run(&text);
    let mass = 4000.0 * 4.0 / 3.0 * PI * 0.0025f64.powi(3);
    let e = report.contact.restitution_velocity_ratio.unwrap();
    let normal_impulse = mass * (1.0 + e) * vn;
    let work = mu * normal_impulse * (vt - mu * 3.5 / mass * normal_impulse / 2.0);
    let kinetic = 0.5 * mass * speed * speed;
    assert!(work / kinetic > mu);
    assert_verdict("smooth", &report.idealisation.smooth, work, kinetic, Judgement::Fails);
}

/// Every key of an `idealisation` object, with its type.
#[track_caller]
fn assert_contract(json: &Value, what: &str) {
    let keys = ["instantaneous", "isolated", "particles", "elastic", "quasi_static", "constant_e", "smooth", "central"];
    let object = json["idealisation"].as_object().unwrap_or_else(|| panic!("{what}: no idealisation object"));
    let mut found: Vec<_> = object.keys().map(String::as_str).collect();
    found.sort_unstable();
    let mut expected = keys.to_vec();
    expected.sort_unstable();
    assert_eq!(found, expected, "{what}");
    for key in keys {
        let entry = &object[key];
        if entry.is_null() {
            continue;
        }
        let fields = entry.as_object().unwrap_or_else(|| panic!("{what}.{key}: {entry}"));
        let mut names: Vec<_> = fields.keys().map(String::as_str).collect();
        names.sort_unstable();
        assert_eq!(names, ["compared_with", "meaning", "ratio", "value", "verdict"], "{what}.{key}");
        let number = |name: &str| fields[name].as_f64().unwrap_or_else(|| panic!("{what}.{key}.{name}: {entry}"));
        assert_eq!(number("ratio"), number("value") / number("compared_with"), "{what}.{key}");
        assert!(["holds", "marginal", "fails"].contains(&fields["verdict"].as_str().unwrap()), "{what}.{key}");
        let meaning = fields["meaning"].as_str().unwrap();
        assert!(!meaning.is_empty() && !meaning.contains('\n'), "{what}.{key}: {meaning}");
    }
}

#[test]
fn every_one_impact_report_has_the_eight_verdicts() {
    let reports: [(&str, Report); 4] = [
        ("steel pair", run(&steel_pair(1.0, Some(1e9), "law = \"hertz\""))),
        ("viscoelastic on a wall", on_wall(1.0, 1.0, "law = \"brilliantov\"\nstiffness = 1e8\ndamping = 1e-4")),
        ("kelvin-voigt", on_wall(1.0, 1.0, "law = \"kelvin-voigt\"\nstiffness = 1e6\nrestitution = 0.5")),
        (
            "oblique, frictional",
            run(&format!(
                "{}friction = 0.3\n",
                steel_pair(1.0, None, "law = \"hunt-crossley\"\nrestitution = 0.8")
                    .replace("velocity = [0.5, 0.0, 0.0]", "velocity = [0.5, 0.3, 0.0]")
            )),
        ),
    ];
    for (what, report) in &reports {
        let json = serde_json::to_value(report).expect("serialisable");
        assert_contract(&json, what);
        assert!(report.idealisation.constant_e.is_some(), "{what}: constant_e");
    }
    // The command line prints the same object.
    let scratch = Scratch::new("every_one_impact_report_has_the_eight_verdicts");
    let scene = scratch.scene("pair.toml", &steel_pair(0.1, Some(1e9), "law = \"hertz\""));
    let output = binary(scratch.path(), &["run", &scene, "--json"]);
    assert!(output.status.success());
    let json: Value = serde_json::from_str(&stdout(&output)).expect("JSON report");
    assert_contract(&json, "impact run --json");
    assert_eq!(json["idealisation"]["elastic"]["verdict"], "marginal");
}

#[test]
fn the_terminal_report_opens_with_the_verdicts() {
    let text = render(&run(&steel_pair(0.1, Some(1e9), "law = \"hertz\"")));
    let first = text.split("\n\n").nth(1).expect("a first section");
    assert!(first.starts_with("the idealisation on trial"), "{text}");
    for key in ["instantaneous", "isolated", "particles", "elastic", "quasi_static", "constant_e", "smooth", "central"]
    {
        assert!(first.lines().any(|line| line.trim_start().starts_with(key)), "{key} in\n{first}");
    }
    // A verdict that is not `holds` is explained under its row.
    assert!(first.contains("elastic marginal: the peak contact pressure reaches"), "{first}");
}

#[test]
fn a_spinning_ball_turns_its_surface_through_the_contact() {
    // A 1 kg ball of radius 1 m spinning at 100 rad/s, thrown head-on at 1 m/s against a smooth wall, K = 1e8 N/m^1.5:
    // d_max = (5 m v0² / (4 K))^(2/5) = 0.689 mm, t_c = 2.9433 d_max / v0 = 2.03 ms (docs/references.md), so the
    // surface turns through R ω t_c = 0.203 m, more than the contact radius sqrt(R d_max) = 26 mm.
    let (omega, stiffness, v0): (f64, f64, f64) = (100.0, 1e8, 1.0);
    let report = run(&format!(
        "[[bodies]]\nradius = 1.0\nmass = 1.0\nvelocity = [{v0:?}, 0.0, 0.0]\nangular_velocity = [0.0, 0.0, {omega:?}]\n\n\
         [[bodies]]\nradius = inf\nmass = inf\nvelocity = [0.0, 0.0, 0.0]\n\n\
         [contact]\nlaw = \"hertz\"\nstiffness = {stiffness:e}\n"
    ));
    let max_penetration = (5.0 * v0 * v0 / (4.0 * stiffness)).powf(0.4);
    let duration = HERTZ_TIME * max_penetration / v0;
    assert!(max_penetration.sqrt() < omega * duration);
    assert_verdict("particles", &report.idealisation.particles, omega * duration, 1.0, Judgement::Marginal);
    assert_eq!(verdict(&report.idealisation.particles, "particles").measure, "R ω t_c / R");
}

#[test]
fn a_contact_that_never_ends_has_no_duration_to_judge() {
    // An overdamped Kelvin–Voigt contact (zeta = c / (2 sqrt(k m)) = 2) creeps back to zero penetration and never
    // separates: what needs t_c or e is null, what the compression measured is judged.
    let report = on_wall(1.0, 1.0, "law = \"kelvin-voigt\"\nstiffness = 1e6\nexponent = 1.0\ndamping = 4000");
    assert!(!report.contact.separated);
    let ideal = &report.idealisation;
    for (key, verdict) in [
        ("instantaneous", &ideal.instantaneous),
        ("isolated", &ideal.isolated),
        ("quasi_static", &ideal.quasi_static),
        ("constant_e", &ideal.constant_e),
    ] {
        assert!(verdict.is_none(), "{key}");
    }
    // a = sqrt(R d_max) against R = 1 m (a wall: R* = R).
    let a = report.contact.max_penetration.sqrt();
    assert_verdict("particles", &ideal.particles, a, 1.0, Judgement::Holds);
    assert_contract(&serde_json::to_value(&report).unwrap(), "never separated");
    assert!(render(&report).contains("the bodies did not separate"));
}

/// A law that yields (Thornton's) is judged by the pressure an elastic contact would reach at its speed: Hertz's p0
/// is the yield pressure at the yield speed V_y and grows as v0^(2/5), so it is p_y (v0/V_y)^(2/5). The two steel
/// balls (Y = 1 GPa, p_y = 1.6 GPa) yield at V_y from (1/2) m* V_y² = (8/15) E* sqrt(R*) d_y^(5/2),
/// d_y = (pi p_y / (2 E*))² R* (Thornton 1997): about 0.068 m/s.
#[test]
fn a_yielding_law_is_judged_by_the_pressure_an_elastic_contact_would_reach() {
    let hertz = hertz_pair(1.0);
    let modulus = YOUNG / (2.0 * (1.0 - POISSON * POISSON));
    let p_y = 1.6e9;
    let d_y = (PI * p_y / (2.0 * modulus)).powi(2) * hertz.effective_radius;
    let v_y = (16.0 / 15.0 * modulus * hertz.effective_radius.sqrt() * d_y.powf(2.5) / hertz.effective_mass).sqrt();
    assert!((v_y - 0.068).abs() < 1e-3, "V_y = {v_y}");
    for (ratio, judgement) in [(0.5, Judgement::Holds), (5.0, Judgement::Fails)] {
        let report = run(&steel_pair(ratio * v_y, Some(1e9), "law = \"thornton\""));
        let elastic = p_y * ratio.powf(0.4);
        assert_verdict(&format!("elastic at {ratio} V_y"), &report.idealisation.elastic, elastic, p_y, judgement);
    }
}
