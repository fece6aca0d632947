//! A rod whose two ends' contacts overlap in time, against an independent integration written here.
//!
//! A rod dropped nearly flat strikes with its lower end and, before that contact has ended, with its other end: the
//! two contacts act on one rigid body at once, where neither the sequential nor the simultaneous instantaneous model
//! holds (docs/world.md#rigid-bodies). The world integrates both contacts and the rod's turning together; here the
//! same planar motion is integrated by classical RK4 from the force law alone, and the two must agree.
//!
//! The rod: mass M, length L between its end spheres' centres (radius r), I_G = M L²/12 across its axis, in the x–z
//! plane at angle φ to the floor (its +x end higher), under gravity g, dropped at v without spin. Each end's sphere
//! presses into the floor by δ = r - z_end, with Hunt–Crossley's force `K δ^{3/2} (1 + α δ')` along +z (its stiffness
//! and damping given as numbers, so no material enters). The state is (z_G, v_z, φ, φ'): x_G does not move (the floor
//! is smooth and the forces vertical), and the torque of an end's force F at x-arm ±(L/2) cos φ is ±(L/2) cos φ F
//! about -y, so that `I φ'' = (L/2) cos φ (F_+ - F_-)` and `M v_z' = F_+ + F_- - M g`. The world's angular velocity
//! about +y is -φ'.

mod common;

use common::world_report_json as run;
use serde_json::Value;

const MASS: f64 = 0.2;
const LENGTH: f64 = 0.2;
const RADIUS: f64 = 0.005;
const STIFFNESS: f64 = 1e6; // N/m^1.5
const DAMPING: f64 = 0.2; // s/m
const G: f64 = 9.81;
const SPEED: f64 = 1.0;
const GAP: f64 = 1e-4;
const END: f64 = 0.02;

/// The planar rod's state: height of the mass centre (m), its vertical velocity (m/s), angle (rad), angular rate (rad/s).
type State = [f64; 4];

/// Hunt–Crossley's force of one end at penetration `depth` (m) and penetration rate `rate` (m/s): zero when apart
/// (never a fractional power of a negative penetration), never pulling.
fn end_force(depth: f64, rate: f64) -> f64 {
    if depth <= 0.0 { 0.0 } else { (STIFFNESS * depth.powf(1.5) * (1.0 + DAMPING * rate)).max(0.0) }
}

/// The two ends' forces (+x end, -x end), N.
fn forces(y: &State) -> [f64; 2] {
    let [z, vz, phi, rate] = *y;
    let half = LENGTH / 2.0;
    [1.0, -1.0].map(|side| {
        let height = z + side * half * phi.sin();
        let velocity = vz + side * half * phi.cos() * rate;
        end_force(RADIUS - height, -velocity)
    })
}

fn derivative(y: &State) -> State {
    let [plus, minus] = forces(y);
    let inertia = MASS * LENGTH * LENGTH / 12.0;
    let arm = LENGTH / 2.0 * y[2].cos();
    [y[1], (plus + minus) / MASS - G, y[3], arm * (plus - minus) / inertia]
}

fn rk4(y: &State, h: f64) -> State {
    let step = |a: &State, k: &State, f: f64| -> State { [0, 1, 2, 3].map(|i| a[i] + f * k[i]) };
    let k1 = derivative(y);
    let k2 = derivative(&step(y, &k1, h / 2.0));
    let k3 = derivative(&step(y, &k2, h / 2.0));
    let k4 = derivative(&step(y, &k3, h));
    [0, 1, 2, 3].map(|i| y[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]))
}

/// What the integration gives: the state at `END`, and each end's first touch and separation times (s), located by
/// linear interpolation of the end's gap between the steps that bracket it.
struct Integrated {
    state: State,
    touches: [Option<(f64, f64)>; 2],
}

fn integrate(angle: f64, steps: usize) -> Integrated {
    let half = LENGTH / 2.0;
    let mut y: State = [RADIUS + GAP + half * angle.sin(), -SPEED, angle, 0.0];
    let h = END / steps as f64;
    let gaps = |y: &State| [1.0, -1.0].map(|side| y[0] + side * half * y[2].sin() - RADIUS);
    let mut touches: [Option<(f64, f64)>; 2] = [None, None];
    let mut began = [f64::NAN; 2];
    for k in 0..steps {
        let next = rk4(&y, h);
        let (before, after) = (gaps(&y), gaps(&next));
        for end in 0..2 {
            let at = k as f64 * h + h * before[end] / (before[end] - after[end]);
            if before[end] > 0.0 && after[end] <= 0.0 && began[end].is_nan() {
                began[end] = at;
            } else if before[end] <= 0.0 && after[end] > 0.0 && touches[end].is_none() {
                touches[end] = Some((began[end], at));
            }
        }
        y = next;
    }
    Integrated { state: y, touches }
}

/// The world scene of the same rod at `angle` (rad), its inertia the rod's tensor along its axis (a polar moment of
/// 1e-7 kg m², which a planar motion never feels).
fn scene(angle: f64) -> String {
    let (c, s) = (angle.cos(), angle.sin());
    let axis = [c, 0.0, s];
    let (across, polar) = (MASS * LENGTH * LENGTH / 12.0, 1e-7);
    let row = |i: usize| {
        let entries: Vec<String> = (0..3)
            .map(|j| format!("{:?}", (polar - across) * axis[i] * axis[j] + if i == j { across } else { 0.0 }))
            .collect();
        format!("[{}]", entries.join(", "))
    };
    let half = LENGTH / 2.0;
    let z = RADIUS + GAP + half * s;
    format!(
        "[world]\ngravity = [0.0, 0.0, {:?}]\nend_time = {END:?}\n\n[[bodies]]\nname = \"rod\"\nmass = {MASS:?}\n\
         inertia = [{}, {}, {}]\nposition = [0.0, 0.0, {z:?}]\nvelocity = [0.0, 0.0, {:?}]\nyoung = 2.1e11\n\
         poisson = 0.3\n\n[[bodies.spheres]]\noffset = [{:?}, 0.0, {:?}]\nradius = {RADIUS:?}\n\n\
         [[bodies.spheres]]\noffset = [{:?}, 0.0, {:?}]\nradius = {RADIUS:?}\n\n[[bodies]]\nname = \"floor\"\n\
         mass = inf\nradius = inf\nposition = [0.0, 0.0, 0.0]\nnormal = [0.0, 0.0, 1.0]\nvelocity = [0.0, 0.0, 0.0]\n\
         young = 2.1e11\npoisson = 0.3\n\n[contact]\nlaw = \"hunt-crossley\"\nstiffness = {STIFFNESS:?}\n\
         exponent = 1.5\ndamping = {DAMPING:?}\n\n[solver]\nrtol = 1e-11\natol = 1e-11\n",
        -G,
        row(0),
        row(1),
        row(2),
        -SPEED,
        half * c,
        half * s,
        -half * c,
        -half * s
    )
}

fn number(value: &Value) -> f64 {
    value.as_f64().unwrap_or_else(|| panic!("expected a number, found {value}"))
}

/// Tilted by 0.2°, the rod's ends are 0.7 mm apart in height, less than the 1.3 mm its lower end sinks in: the upper
/// end strikes while the lower one still presses. The world's rod leaves with the integration's velocity, spin,
/// height and angle; each end's contact begins and ends where the integration's gap closes and opens.
#[test]
fn a_rod_whose_ends_strike_at_once_moves_as_an_independent_integration_of_both_contacts() {
    let angle = 0.2_f64.to_radians();
    // RK4 at two steps: their difference bounds the reference's own error (fourth order, away from the contact's
    // first touch, where the force's second derivative is infinite).
    let fine = integrate(angle, 400_000);
    let coarse = integrate(angle, 200_000);
    let own = (0..4).map(|i| (fine.state[i] - coarse.state[i]).abs()).fold(0.0, f64::max);
    assert!(own < 1e-9, "the reference's own error {own:e}");

    let report = run(&scene(angle));
    let contacts = report["contacts"].as_array().expect("contacts");
    assert_eq!(contacts.len(), 2, "one contact at each end: {contacts:?}");
    let [lower, upper] = [&contacts[0], &contacts[1]];
    assert_eq!(lower["spheres"][0], 1, "the -x end strikes first: {lower}");
    assert_eq!(upper["spheres"][0], 0, "then the +x end: {upper}");
    let [plus, minus] = fine.touches.map(|touch| touch.expect("each end touches and leaves in the integration"));
    for (contact, (start, end)) in [(lower, minus), (upper, plus)] {
        let begins = number(&contact["start_time"]);
        let lasts = number(&contact["duration"]);
        // The reference locates its touches between steps of 5e-8 s by a chord.
        assert!((begins - start).abs() < 1e-8, "start {begins} against {start}");
        assert!((begins + lasts - end).abs() < 1e-8, "end {} against {end}", begins + lasts);
    }
    // The contacts overlap: the upper end strikes before the lower one has left.
    assert!(plus.0 < minus.1, "the integration's contacts overlap: {minus:?} {plus:?}");

    let rod = &report["bodies"][0];
    let vz = number(&rod["velocity_after"][2]);
    let spin = number(&rod["angular_velocity_after"][1]);
    let z = number(&rod["position_after"][2]);
    let [z_ref, vz_ref, phi_ref, rate_ref] = fine.state;
    assert!((vz - vz_ref).abs() < 1e-9 * SPEED, "v_z {vz} against {vz_ref}");
    assert!((spin + rate_ref).abs() * LENGTH / 2.0 < 1e-9 * SPEED, "spin {spin} against {}", -rate_ref);
    assert!((z - z_ref).abs() < 1e-11, "height {z} against {z_ref}");
    // The angle from the orientation quaternion [w, x, y, z] turned about y: the rod's axis (cos φ0, 0, sin φ0)
    // turned by -θ_y about y has angle φ0 - θ_y; the quaternion's θ_y = 2 atan2(y, w).
    let q = rod["orientation_after"].as_array().expect("orientation");
    let turned = 2.0 * number(&q[2]).atan2(number(&q[0]));
    let phi = angle - turned;
    assert!((phi - phi_ref).abs() < 1e-10, "angle {phi} against {phi_ref}");
    // The rod leaves both ends' contacts rising: a rebound, and well below the drop speed (damped).
    assert!(vz_ref > 0.0 && vz_ref < SPEED, "{vz_ref}");
}
