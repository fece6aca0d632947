//! Coasting (docs/world.md#coasting): a ball resting on a still floor, its ringing normal to the floor died away,
//! moved on in closed form instead of integrated. Each case is run twice — coasting, and with `[world] coast = false`,
//! integrated throughout at a tolerance tight enough (1e-12) to stand for the exact motion — and the two must agree;
//! where the motion has a closed form of its own (a smooth ball's uniform slide, the angular momentum about the
//! contact point that a floor's forces keep), against that too. Every expected number is derived here.

mod common;

use common::world_report_json as run;
use serde_json::Value;

#[track_caller]
fn number(value: &Value) -> f64 {
    value.as_f64().unwrap_or_else(|| panic!("expected a number, found {value}"))
}

#[track_caller]
fn vector(value: &Value) -> [f64; 3] {
    [0, 1, 2].map(|k| number(&value[k]))
}

fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

fn coasted(report: &Value) -> bool {
    report["notes"].as_array().expect("notes").iter().any(|n| n.as_str().is_some_and(|n| n.contains("coasted")))
}

fn steps(report: &Value) -> f64 {
    number(&report["solver"]["steps"])
}

/// A steel ball (r = 10 mm, 7850 kg/m³) set down on a steel floor with `velocity` and `spin`, Hunt–Crossley e = 0.5,
/// `contact` keys added, a wall at x = 0.05 m, and `more` (bodies) appended.
fn scene(coast: bool, tolerance: &str, end: f64, velocity: &str, spin: &str, contact: &str, more: &str) -> String {
    format!(
        r#"
[world]
gravity = [0.0, 0.0, -9.81]
end_time = {end}
coast = {coast}
{tolerance}
[[bodies]]
name = "ball"
radius = 0.01
density = 7850
position = [0.0, 0.0, 0.01]
velocity = {velocity}
angular_velocity = {spin}
young = 2.1e11
poisson = 0.3
[[bodies]]
name = "floor"
radius = inf
mass = inf
position = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
velocity = [0.0, 0.0, 0.0]
young = 2.1e11
poisson = 0.3
[[bodies]]
name = "wall"
radius = inf
mass = inf
position = [0.05, 0.0, 0.0]
normal = [-1.0, 0.0, 0.0]
velocity = [0.0, 0.0, 0.0]
young = 2.1e11
poisson = 0.3
{more}
[contact]
law = "hunt-crossley"
restitution = 0.5
{contact}
"#
    )
}

const TIGHT: &str = "[solver]\nrtol = 1e-12\natol = 1e-12";

/// The energy balance's residual over the energy supplied.
fn balance(report: &Value) -> f64 {
    let e = &report["energy"];
    (number(&e["balance"]) / number(&e["kinetic_before"]).max(number(&e["gravity_work"]).abs())).abs()
}

/// Each report's energy balance closes within 1e-7 of the energy supplied: a bound on both runs alike, coasting and
/// integrated (the smooth ball's residual is 1.35e-8 of it in each, from its bounces, which both integrate the same
/// way), so that a coast that lost or made energy would show beside the integrated run's.
#[track_caller]
fn assert_balanced(reports: &[&Value]) {
    for report in reports {
        assert!(balance(report) < 1e-7, "balance {:.2e} of the energy supplied", balance(report));
    }
}

/// A rough ball set down sliding at (0.3, 0.05) m/s with 3 rad/s about the vertical: its slip comes to rest at
/// about 30 ms, it rolls on at 5/7 of that velocity with its tangential spring ringing (no tangential damping), and
/// it meets the wall at 0.18 s, bounces on the floor and coasts again. Coasting and integrated agree.
#[test]
fn a_rough_ball_rolling_with_spin_into_a_wall_coasts_to_the_integrations_answer() {
    let rough = "friction = 0.3";
    let (velocity, spin) = ("[0.3, 0.05, 0.0]", "[0.0, 0.0, 3.0]");
    let coasting = run(&scene(true, "", 0.3, velocity, spin, rough, ""));
    let integrated = run(&scene(false, TIGHT, 0.3, velocity, spin, rough, ""));
    assert!(coasted(&coasting) && !coasted(&integrated));
    assert!(steps(&coasting) * 4.0 < steps(&integrated), "{} against {}", steps(&coasting), steps(&integrated));
    let speed = 0.3;
    let (a, b) = (&coasting["bodies"][0], &integrated["bodies"][0]);
    let dv = distance(vector(&a["velocity_after"]), vector(&b["velocity_after"]));
    let dw = distance(vector(&a["angular_velocity_after"]), vector(&b["angular_velocity_after"])) * 0.01;
    let dx = distance(vector(&a["position_after"]), vector(&b["position_after"]));
    assert!(dv < 1e-9 * speed && dw < 1e-9 * speed, "velocity {dv:.2e}, spin r w {dw:.2e}");
    assert!(dx < 1e-9 * speed * 0.3, "position {dx:.2e}");
    // Every contact — the wall's after the coast woke the ball, the floor's bounces after it — at the same instants.
    let (ca, cb) = (coasting["contacts"].as_array().unwrap(), integrated["contacts"].as_array().unwrap());
    assert_eq!(ca.len(), cb.len());
    assert!(ca.len() >= 3);
    for (x, y) in ca.iter().zip(cb) {
        assert_eq!(x["bodies"], y["bodies"]);
        let dt = (number(&x["start_time"]) - number(&y["start_time"])).abs();
        assert!(dt < 1e-11, "contact {:?} began {dt:.2e} s apart", x["bodies"]);
        if let (Some(p), Some(q)) = (x["max_penetration"].as_f64(), y["max_penetration"].as_f64()) {
            assert!((p / q - 1.0).abs() < 1e-8, "contact {:?}: deepest {p} against {q}", x["bodies"]);
        }
    }
    // The wall's contact is the second (the ball coasts up to a few nanoseconds before it).
    assert_eq!(ca[1]["bodies"], serde_json::json!([0, 2]));
    assert_balanced(&[&coasting, &integrated]);
}

/// Mid-coast, before the wall: the floor's forces act at the contact point, at the arm `-r n` from the centre (the
/// model's), and gravity and the normal force along n, so the angular momentum about that point, `m r n × v + I w`,
/// is what it was when the ball was set down — through the slide, the stick and the coast. Its horizontal part gives
/// the rolling velocity: n × v (m r + I/r) = n × v0 m r for a ball set down without horizontal spin, v = (5/7) v0.
#[test]
fn a_coasting_ball_keeps_its_angular_momentum_about_the_contact_point() {
    let report = run(&scene(true, "", 0.1, "[0.3, 0.05, 0.0]", "[0.0, 0.0, 3.0]", "friction = 0.3", ""));
    assert!(coasted(&report));
    let ball = &report["bodies"][0];
    let (v, w) = (vector(&ball["velocity_after"]), vector(&ball["angular_velocity_after"]));
    let (m, r) = (7850.0 * 4.0 / 3.0 * std::f64::consts::PI * 1e-6, 0.01);
    let inertia = 0.4 * m * r * r;
    // n = z: m r z × v = m r (-v_y, v_x, 0).
    let momentum =
        |v: [f64; 3], w: [f64; 3]| [m * r * -v[1] + inertia * w[0], m * r * v[0] + inertia * w[1], inertia * w[2]];
    let (now, then) = (momentum(v, w), momentum([0.3, 0.05, 0.0], [0.0, 0.0, 3.0]));
    assert!(distance(now, then) < 1e-10 * m * r * 0.3, "{now:?} against {then:?}");
    // Rolling at 5/7 of the set-down velocity, but for the spring's ringing: its velocity is within
    // (|T|max/ω)/m of the mean, |T|max = mu m g and ω² = kt/m_t, kt = 8 G* a: under 1e-3 of the speed.
    let rolling = [0.3 * 5.0 / 7.0, 0.05 * 5.0 / 7.0, 0.0];
    assert!(distance(v, rolling) < 1e-3 * 0.3, "{v:?}");
    assert!(balance(&report) < 1e-7, "balance {:.2e}", balance(&report));
}

/// A smooth ball set down sliding at 0.2 m/s along x: no force of the floor has a horizontal part, so it slides
/// uniformly and meets the wall (x = 0.05 m, its radius 0.01 m) at exactly t = 0.04/0.2 = 0.2 s, after coasting
/// from when its bounce on the floor died away.
#[test]
fn a_smooth_ball_coasts_to_the_wall_at_the_closed_form_time() {
    let coasting = run(&scene(true, "", 0.25, "[0.2, 0.0, 0.0]", "[0.0, 0.0, 0.0]", "", ""));
    let integrated = run(&scene(false, TIGHT, 0.25, "[0.2, 0.0, 0.0]", "[0.0, 0.0, 0.0]", "", ""));
    assert!(coasted(&coasting));
    for report in [&coasting, &integrated] {
        let wall: Vec<&Value> = report["contacts"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|c| c["bodies"] == serde_json::json!([0, 2]))
            .collect();
        let start = number(&wall[0]["start_time"]);
        assert!((start - 0.2).abs() < 1e-13, "the wall's contact began at {start}");
        assert!(balance(report) < 1e-7, "balance {:.2e}", balance(report));
    }
    let dv =
        distance(vector(&coasting["bodies"][0]["velocity_after"]), vector(&integrated["bodies"][0]["velocity_after"]));
    assert!(dv < 1e-9 * 0.2, "{dv:.2e}");
    assert!(steps(&coasting) * 4.0 < steps(&integrated));
}

/// A ball rolling at 0.3 m/s catches one that rolls ahead of it at 0.02 m/s (both set down sliding, both coasting
/// once their slips have come to rest and their floor contacts stopped ringing): the padding of their mean motions
/// wakes both before they touch, and their collision is the integrated run's.
#[test]
fn a_rolling_ball_wakes_the_coasting_ball_it_catches() {
    let ahead = r#"
[[bodies]]
name = "ahead"
radius = 0.01
density = 7850
position = [0.025, 0.0, 0.01]
velocity = [0.02, 0.0, 0.0]
young = 2.1e11
poisson = 0.3
"#;
    let make = |coast: bool, tolerance: &str| {
        scene(coast, tolerance, 0.15, "[0.3, 0.0, 0.0]", "[0.0, 0.0, 0.0]", "friction = 0.3", ahead)
    };
    let (coasting, integrated) = (run(&make(true, "")), run(&make(false, TIGHT)));
    assert!(coasted(&coasting));
    let between = |report: &Value| -> Vec<f64> {
        report["contacts"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|c| c["bodies"] == serde_json::json!([0, 3]))
            .map(|c| number(&c["start_time"]))
            .collect()
    };
    let (a, b) = (between(&coasting), between(&integrated));
    assert!(!a.is_empty() && a.len() == b.len(), "{a:?} {b:?}");
    assert!((a[0] - b[0]).abs() < 1e-11, "the balls met at {} and {}", a[0], b[0]);
    for k in [0, 3] {
        let (x, y) = (&coasting["bodies"][k], &integrated["bodies"][k]);
        let dv = distance(vector(&x["velocity_after"]), vector(&y["velocity_after"]));
        assert!(dv < 1e-9 * 0.3, "body {k}: {dv:.2e}");
    }
    assert_balanced(&[&coasting, &integrated]);
}

/// A soft tangential spring (10 N/m) rings with millimetres of reach: with a finite neighbour list (a skin of 1 mm) its
/// padding would leave the list no time to hold. Such a ball does not coast; its run is the integrated one.
#[test]
fn a_ball_whose_ringing_outreaches_the_neighbour_list_does_not_coast() {
    let (soft, world) = ("friction = 0.3\ntangential_stiffness = 10.0", "skin = 0.001\nmax_steps = 200000");
    let make = |coast: bool| scene(coast, world, 0.5, "[0.3, 0.0, 0.0]", "[0.0, 0.0, 0.0]", soft, "");
    let (coasting, integrated) = (run(&make(true)), run(&make(false)));
    assert!(!coasted(&coasting));
    for report in [&coasting, &integrated] {
        assert_eq!(report["world"]["end_reason"], "end_time");
    }
    assert_eq!(coasting["contacts"], integrated["contacts"]);
}

/// A slip that first comes to rest while the ball coasts (the soft spring's ringing: its slip along its first
/// direction falls through zero half a period after the stick begins) is located as the integration locates it.
#[test]
fn a_slip_that_comes_to_rest_while_the_ball_coasts_is_located() {
    let soft = "friction = 0.3\ntangential_stiffness = 10.0";
    let make = |coast: bool| scene(coast, TIGHT, 0.1, "[0.3, 0.0, 0.0]", "[0.0, 0.0, 0.0]", soft, "");
    let (coasting, integrated) = (run(&make(true)), run(&make(false)));
    assert!(coasted(&coasting));
    let (a, b) = (&coasting["contacts"][0], &integrated["contacts"][0]);
    assert_eq!(a["regime"], "sticking");
    assert_eq!(a["regime"], b["regime"]);
    let (ta, tb) = (number(&a["slip_rest_time"]), number(&b["slip_rest_time"]));
    assert!((ta - tb).abs() < 1e-12, "{ta} against {tb}");
}

/// A ball rolling past one at rest (4 mm apart at their closest, the soft spring's padding reached) wakes only itself: the other,
/// frozen on its floor (its spring damped, so it does not coast but rests), stays still, as in the integrated run.
#[test]
fn a_frozen_ball_beside_a_coasting_balls_path_stays_frozen() {
    let beside = r#"
[[bodies]]
name = "beside"
radius = 0.01
density = 7850
position = [0.03, 0.024, 0.01]
velocity = [0.0, 0.0, 0.0]
young = 2.1e11
poisson = 0.3
[[pair]]
bodies = [0, 1]
tangential_stiffness = 10.0
[[pair]]
bodies = [3, 1]
tangential_damping = 0.5
"#;
    let make = |coast: bool| scene(coast, "", 1.0, "[0.3, 0.0, 0.0]", "[0.0, 0.0, 0.0]", "friction = 0.3", beside);
    let (coasting, integrated) = (run(&make(true)), run(&make(false)));
    assert!(coasted(&coasting));
    for report in [&coasting, &integrated] {
        assert_eq!(vector(&report["bodies"][3]["velocity_after"]), [0.0; 3]);
        assert!(report["contacts"].as_array().unwrap().iter().all(|c| c["bodies"] != serde_json::json!([0, 3])));
    }
}
