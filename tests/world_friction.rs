//! Coulomb friction and spin in world runs (scenes with `[world]` or more than two bodies). Every expected value is
//! derived here by hand from rigid-body mechanics and conservation laws, with the derivation in a comment beside it;
//! none is taken from the program's output.
//!
//! The world report's friction fields (`contacts[k].friction_work`, `regime`, `angular_velocities_before`,
//! `angular_velocities_after`; `bodies[i].angular_velocity_after` changed by friction) are read from the report's
//! JSON form (`serde_json::to_value`), so that this file compiles whatever Rust fields the report has.
//!
//! Conventions (the contract of the world report): a contact's normal points from body i to body j (`bodies` [i, j],
//! i < j); the tangential force on body i is Ft, on body j -Ft; a sphere's lever arm to the contact point is
//! r_i/(r_i + r_j) (x_j - x_i), on a flat wall its radius along the normal towards the wall; a solid sphere's inertia
//! is (2/5) m r² unless the scene gives `inertia`.

mod common;

use common::vectors::{V, add, cross, dot, norm, scale, sub, unit};
use serde_json::Value;

fn relative(value: f64, expected: f64) -> f64 {
    ((value - expected) / expected).abs()
}

use common::world_report_json as run;

#[track_caller]
fn number(value: &Value, what: &str) -> f64 {
    value.as_f64().unwrap_or_else(|| panic!("{what}: expected a number, found {value}"))
}

#[track_caller]
fn vector(value: &Value, what: &str) -> V {
    let items = value.as_array().unwrap_or_else(|| panic!("{what}: expected [x, y, z], found {value}"));
    assert_eq!(items.len(), 3, "{what}: {value}");
    [0, 1, 2].map(|k| number(&items[k], what))
}

#[track_caller]
fn text<'a>(value: &'a Value, what: &str) -> &'a str {
    value.as_str().unwrap_or_else(|| panic!("{what}: expected a string, found {value}"))
}

/// The contacts of the report between bodies `i` and `j` (i < j), in order of first touch.
fn contacts_of(report: &Value, i: usize, j: usize) -> Vec<&Value> {
    report["contacts"]
        .as_array()
        .expect("contacts")
        .iter()
        .filter(|c| c["bodies"][0].as_u64() == Some(i as u64) && c["bodies"][1].as_u64() == Some(j as u64))
        .collect()
}

/// Asserts |a - b| <= tolerance componentwise (as a vector norm), naming the quantity.
#[track_caller]
fn assert_vector(what: &str, simulated: V, expected: V, tolerance: f64) {
    let error = norm(sub(simulated, expected));
    assert!(
        error <= tolerance,
        "{what}: simulated {simulated:?}, expected {expected:?}, |difference| {error:.3e} > {tolerance:.1e}"
    );
}

/// A sphere with its position, velocity and spin (and its own `inertia`, if given).
struct Ball {
    name: &'static str,
    radius: f64,
    mass: f64,
    position: V,
    velocity: V,
    spin: V,
    inertia: Option<f64>,
    young: f64,
    poisson: f64,
}

impl Ball {
    fn toml(&self) -> String {
        let inertia = self.inertia.map_or(String::new(), |i| format!("inertia = {i:e}\n"));
        format!(
            "[[bodies]]\nname = \"{}\"\nradius = {:?}\nmass = {:?}\nposition = {:?}\nvelocity = {:?}\n\
             angular_velocity = {:?}\n{inertia}young = {:e}\npoisson = {:?}\n\n",
            self.name, self.radius, self.mass, self.position, self.velocity, self.spin, self.young, self.poisson
        )
    }

    /// Its moment of inertia: the scene's, or a solid sphere's (2/5) m r².
    fn moment(&self) -> f64 {
        self.inertia.unwrap_or(0.4 * self.mass * self.radius * self.radius)
    }
}

/// A steel floor through the origin, face up.
const FLOOR: &str = "[[bodies]]\nname = \"floor\"\nradius = inf\nmass = inf\nposition = [0.0, 0.0, 0.0]\n\
                     normal = [0.0, 0.0, 1.0]\nvelocity = [0.0, 0.0, 0.0]\nyoung = 2.1e11\npoisson = 0.3\n\n";

// ---------------------------------------------------------------------------------------------------------------
// 1. Sliding to rolling on a floor under gravity

/// A steel ball set down on a steel floor sliding at v0 without spin: friction brings it to rolling at (5/7) v0.
///
/// Where the value comes from (the textbook result, e.g. Routh's *Elementary Rigid Dynamics*, or any billiard-ball
/// analysis): on a flat floor the tangential force F_x acts at the contact point, whose arm from the centre is the
/// radius along the normal towards the floor, a = -r ẑ (the contract's fixed arm). Over any time,
///   m Δv_x = J            (J = ∫ F_x dt, the tangential impulse on the ball)
///   I Δω = a × (J x̂) = -r J (ẑ × x̂) = -r J ŷ   ⇒   I Δω_y = -r J,
/// so m r v_x + I ω_y is conserved exactly — whatever the normal force does, and whether the tangential force is
/// Coulomb's or the Mindlin spring's. Rolling without slip means v + ω × a = 0: v_x - r ω_y = 0, i.e. ω_y = +v_x/r
/// (a ball rolling towards +x turns about +y). Then m r v0 = m r v + I v/r, and with I = (2/5) m r²:
///   v = v0 / (1 + 2/5) = (5/7) v0,   ω_y = (5/7) v0 / r.
/// While it slides, F_x = -μ F_n and, once the normal motion has settled (∫ (F_n - m g) dt = m v_z -> 0),
/// v_x = v0 - μ g t: the slip v_x - r ω_y = v0 - (7/2) μ g t stops at t* = 2 v0 / (7 μ g) = 0.097 s here, well
/// before the 0.25 s run ends. The centre then travels x(T) = v0 t* - μ g t*²/2 + (5/7) v0 (T - t*). The friction work is the tangential
/// kinetic energy lost, (1/2) m v0² - (1/2)(m + I/r²)(5 v0/7)² = (1/2) m v0² (1 - 5/7) = m v0²/7.
///
/// After the slip stops, the Mindlin spring holds μ m g and unloads in a damped oscillation of the tangential mass
/// m_t = m/(1 + m r²/I) = m/3.5 on kt = 8 G* sqrt(r d_s) ≈ 5e6 N/m (d_s ≈ 76 nm, the static penetration): angular
/// frequency sqrt(kt/m_t) ≈ 2.4e4 rad/s, damping ratio 0.5, so it decays as exp(-1.2e4 t) — gone long before the end.
/// What it leaves in the position is its spring's stretch, μ m g/kt ≈ 2e-8 m (the centre moves 2/7 of it), and the
/// normal settling adds μ d_s ≈ 2e-8 m to x: both far below 1e-6 of x(T) ≈ 0.19 m.
#[test]
fn a_sliding_ball_ends_rolling_at_five_sevenths_of_its_speed() {
    let (r, m, v0, mu, g, end) = (0.01, 0.0329, 1.0, 0.3, 9.81, 0.25);
    let ball = Ball {
        name: "ball",
        radius: r,
        mass: m,
        position: [0.0, 0.0, r],
        velocity: [v0, 0.0, 0.0],
        spin: [0.0; 3],
        inertia: None,
        young: 2.1e11,
        poisson: 0.3,
    };
    let scene = format!(
        "[world]\ngravity = [0.0, 0.0, {:?}]\nend_time = {end:?}\n\n{}{FLOOR}[contact]\nlaw = \"hunt-crossley\"\n\
         restitution = 0.5\nfriction = {mu:?}\ntangential_damping = 0.5\n",
        -g,
        ball.toml()
    );
    let report = run(&scene);
    let t_roll = 2.0 * v0 / (7.0 * mu * g);
    assert!(t_roll < 0.5 * end, "the ball rolls well before the run ends: {t_roll}");
    assert_eq!(text(&report["world"]["end_reason"], "end_reason"), "end_time");

    // A ball set down at zero penetration and held by a damped contact never leaves the floor: the penetration
    // oscillates about d_s from 0 with a decaying amplitude, so it stays positive: one contact, still active.
    let contacts = report["contacts"].as_array().unwrap();
    assert_eq!(contacts.len(), 1, "{contacts:?}");
    let c = &contacts[0];
    assert_eq!(text(&c["regime"], "regime"), "sticking", "the slip stopped: {c}");
    // The slip comes to rest where the slide ends, at t* (since first touch: the ball starts on the floor).
    let slip_rest = number(&c["slip_rest_time"], "slip_rest_time");
    assert!(relative(slip_rest, t_roll) < 1e-6, "slip rest {slip_rest} s vs 2 v0/(7 mu g) = {t_roll} s");
    assert_vector("spins at first touch, ball", vector(&c["angular_velocities_before"][0], "ω_i"), [0.0; 3], 0.0);
    assert_vector("spins at first touch, floor", vector(&c["angular_velocities_before"][1], "ω_j"), [0.0; 3], 0.0);
    assert_eq!(c["angular_velocities_after"].is_null(), c["velocities_after"].is_null(), "{c}");

    let body = &report["bodies"][0];
    let v = vector(&body["velocity_after"], "velocity_after");
    let w = vector(&body["angular_velocity_after"], "angular_velocity_after");
    let x = vector(&body["position_after"], "position_after");
    let (v_roll, w_roll) = (5.0 / 7.0 * v0, 5.0 / 7.0 * v0 / r);
    assert!(relative(v[0], v_roll) < 1e-6, "v_x {} vs (5/7) v0 = {v_roll}", v[0]);
    assert!(relative(w[1], w_roll) < 1e-6, "ω_y {} vs (5/7) v0/r = {w_roll}", w[1]);
    // Rolling: the contact point is at rest, v_x - r ω_y = 0.
    assert!((v[0] - r * w[1]).abs() < 1e-6 * v0, "slip {} at the end", v[0] - r * w[1]);
    // Nothing acts across y, and no torque about x or z (the arm is along z, the force along x).
    assert!(v[1].abs() < 1e-12 && w[0].abs() < 1e-9 && w[2].abs() < 1e-9, "{v:?} {w:?}");
    // The normal oscillation (damping ratio about 0.3 at 2.2 kHz) has died out: the ball rests on the floor.
    assert!(v[2].abs() < 1e-9 * v0, "v_z {}", v[2]);
    let x_end = v0 * t_roll - 0.5 * mu * g * t_roll * t_roll + v_roll * (end - t_roll);
    assert!(relative(x[0], x_end) < 1e-6, "x {} vs {x_end}", x[0]);

    let friction_work = number(&c["friction_work"], "friction_work");
    let lost = m * v0 * v0 / 7.0;
    assert!(relative(friction_work, lost) < 1e-6, "friction work {friction_work} vs m v0²/7 = {lost}");
    // Kinetic energy at the end: translation and rotation of the rolling ball, (1/2) m v² (1 + 2/5) = (5/14) m v0².
    let kinetic_after = number(&report["energy"]["kinetic_after"], "kinetic_after");
    assert!(relative(kinetic_after, 5.0 / 14.0 * m * v0 * v0) < 1e-6, "kinetic after {kinetic_after}");
    let balance = number(&report["energy"]["balance"], "balance");
    assert!(balance.abs() < 1e-9, "energy balance {balance:e}: {}", report["energy"]);
}

// ---------------------------------------------------------------------------------------------------------------
// 2. Sliding throughout: exactly rigid-body Coulomb

/// The rigid-body impact of a sphere sliding throughout on a still wall whose face has the unit normal `n` (from
/// the wall into the sphere's side), with restitution `e`: (velocity after, spin after, friction work).
///
/// The arm to the contact point is a = -r n. The contact point's velocity is v + ω × a; its slip s0 is that minus
/// its normal part (ω × a is already across n). With v_n = -v·n > 0 the approach speed, the normal impulse is
/// P = (1 + e) m v_n along n. Sliding throughout, the tangential impulse is μ P against the slip, J_t = -μ P ŝ, and
///   v' = v + (P n + J_t)/m,   ω' = ω + (a × J_t)/I.
/// The slip changes by J_t (1/m + r²/I) (for a force F across n, (a × F) × a = r² F), so it keeps its direction and
/// stays positive throughout exactly when |s0| >= μ P B, B = 1/m + r²/I (asserted by the caller). The friction work is
/// ∫ |s| dJ over the tangential impulse J from 0 to μ P, with |s| = |s0| - B J: W = μ P (|s0| - B μ P/2).
fn rigid_sliding_on_wall(ball: &Ball, n: V, e: f64, mu: f64) -> (V, V, f64) {
    let (r, m, i) = (ball.radius, ball.mass, ball.moment());
    let a = scale(n, -r);
    let contact_point_velocity = add(ball.velocity, cross(ball.spin, a));
    let slip = sub(contact_point_velocity, scale(n, dot(contact_point_velocity, n)));
    let vn = -dot(ball.velocity, n);
    assert!(vn > 0.0, "{}: approaches the wall", ball.name);
    let p = (1.0 + e) * m * vn;
    let b = 1.0 / m + r * r / i;
    assert!(
        norm(slip) >= mu * p * b,
        "{}: slides throughout in rigid-body theory ({} < {})",
        ball.name,
        norm(slip),
        mu * p * b
    );
    let jt = scale(unit(slip), -mu * p);
    let v = add(ball.velocity, scale(add(scale(n, p), jt), 1.0 / m));
    let w = add(ball.spin, scale(cross(a, jt), 1.0 / i));
    let work = mu * p * (norm(slip) - b * mu * p / 2.0);
    (v, w, work)
}

/// Two balls strike a floor, without gravity, each sliding throughout (an elastic Hertz contact: e = 1 exactly, the
/// normal motion on a flat wall being reversible and untouched by the tangential force in the wall's plane). The
/// first has no spin and slides along x; the second is a thin shell (its own `inertia` = (2/3) m r²) spinning about
/// all three axes, so its slip (0.6, 3.2) m/s is not along its velocity (0, 2) m/s. Expected values: rigid-body
/// Coulomb friction ([`rigid_sliding_on_wall`]), exact for a compliant contact that slides throughout, whose
/// tangential force is μ F_n at every instant so that its impulse is μ P.
///
/// It slides throughout in the compliant model too: with Hertz's F_n = K d^(3/2), K = (4/3) E* sqrt(r), and
/// Mindlin's kt = 8 G* sqrt(r d), the spring loaded by a slip s grows faster than the Coulomb cap μ F_n as long as
/// kt |s| > μ dF_n/dt = μ (3/2) K d^(1/2) d', i.e. |s|/d' > μ E*/(4 G*) (= 0.12 for steel on steel, μ = 0.1);
/// the smallest slip (at the end, |s0| - μ P B) against the largest d' (v_n) is checked below.
#[test]
fn a_ball_sliding_throughout_follows_rigid_body_coulomb() {
    let mu = 0.1;
    let a = Ball {
        name: "A",
        radius: 0.01,
        mass: 0.0329,
        position: [0.0, 0.0, 0.02],
        velocity: [3.0, 0.0, -1.0],
        spin: [0.0; 3],
        inertia: None,
        young: 2.1e11,
        poisson: 0.3,
    };
    let b = Ball {
        name: "B",
        radius: 0.012,
        mass: 0.05,
        position: [1.0, 0.0, 0.032],
        velocity: [0.0, 2.0, -1.0],
        spin: [100.0, -50.0, 30.0],
        inertia: Some(2.0 / 3.0 * 0.05 * 0.012 * 0.012),
        young: 2.1e11,
        poisson: 0.3,
    };
    let scene = format!(
        "[world]\nmax_contacts = 10\n\n{}{}{FLOOR}[contact]\nlaw = \"hertz\"\nfriction = {mu:?}\n",
        a.toml(),
        b.toml()
    );
    // Steel on steel: E* = E/(2 (1 - ν²)), G* = G/(2 (2 - ν)), G = E/(2 (1 + ν)).
    let (young, nu) = (2.1e11, 0.3);
    let e_star = young / (2.0 * (1.0 - nu * nu));
    let g_star = young / (2.0 * (1.0 + nu)) / (2.0 * (2.0 - nu));
    let n = [0.0, 0.0, 1.0];
    let report = run(&scene);
    assert_eq!(report["contacts"].as_array().unwrap().len(), 2, "{}", report["contacts"]);
    let mut total_work = 0.0;
    for (k, ball) in [&a, &b].into_iter().enumerate() {
        let (v_after, w_after, work) = rigid_sliding_on_wall(ball, n, 1.0, mu);
        let vn = -ball.velocity[2];
        let smallest_slip = {
            let arm = scale(n, -ball.radius);
            let s0 = add([ball.velocity[0], ball.velocity[1], 0.0], cross(ball.spin, arm));
            norm(s0) - mu * 2.0 * ball.mass * vn * (1.0 / ball.mass + ball.radius.powi(2) / ball.moment())
        };
        assert!(
            smallest_slip / vn > 2.0 * mu * e_star / (4.0 * g_star),
            "{}: the Mindlin spring outruns the cap",
            ball.name
        );
        let contacts = contacts_of(&report, k, 2);
        assert_eq!(contacts.len(), 1, "{}: {contacts:?}", ball.name);
        let c = contacts[0];
        let speed = norm(ball.velocity);
        let what = ball.name;
        assert_eq!(text(&c["regime"], "regime"), "sliding", "{what}: {c}");
        // The spins at first touch are the scene's (nothing acts in flight); the floor's is zero.
        assert_vector(&format!("{what}: ω before"), vector(&c["angular_velocities_before"][0], "ω_i"), ball.spin, 0.0);
        assert_vector(
            &format!("{what}: floor ω before"),
            vector(&c["angular_velocities_before"][1], "ω_j"),
            [0.0; 3],
            0.0,
        );
        let after = &c["angular_velocities_after"];
        assert_vector(
            &format!("{what}: ω at separation"),
            vector(&after[0], "ω_i"),
            w_after,
            1e-8 * speed / ball.radius,
        );
        assert_vector(&format!("{what}: floor ω at separation"), vector(&after[1], "ω_j"), [0.0; 3], 0.0);
        assert_vector(
            &format!("{what}: v at separation"),
            vector(&c["velocities_after"][0], "v_i"),
            v_after,
            1e-8 * speed,
        );
        // Without gravity nothing acts after separation: the final state is the one at separation.
        let body = &report["bodies"][k];
        assert_vector(&format!("{what}: v after"), vector(&body["velocity_after"], "v"), v_after, 1e-8 * speed);
        assert_vector(
            &format!("{what}: ω after"),
            vector(&body["angular_velocity_after"], "ω"),
            w_after,
            1e-8 * speed / ball.radius,
        );
        // The friction work is also the kinetic energy lost (the elastic normal contact gives back all it took).
        let kinetic = |v: V, w: V| 0.5 * ball.mass * dot(v, v) + 0.5 * ball.moment() * dot(w, w);
        let lost = kinetic(ball.velocity, ball.spin) - kinetic(v_after, w_after);
        assert!(relative(work, lost) < 1e-12, "{what}: the two closed forms agree: {work} vs {lost}");
        let friction_work = number(&c["friction_work"], "friction_work");
        assert!(relative(friction_work, work) < 1e-8, "{what}: friction work {friction_work} vs {work}");
        total_work += work;
    }
    let energy = &report["energy"];
    let kinetic_before: f64 = [&a, &b]
        .iter()
        .map(|ball| {
            0.5 * ball.mass * dot(ball.velocity, ball.velocity) + 0.5 * ball.moment() * dot(ball.spin, ball.spin)
        })
        .sum();
    assert!(relative(number(&energy["kinetic_before"], "kinetic_before"), kinetic_before) < 1e-12, "{energy}");
    assert!(relative(number(&energy["dissipated"], "dissipated"), total_work) < 1e-8, "{energy} vs {total_work}");
    let balance = number(&energy["balance"], "balance");
    assert!(balance.abs() < 1e-9, "energy balance {balance:e}: {energy}");
}

// ---------------------------------------------------------------------------------------------------------------
// 3. Free frictional spheres: momentum and angular momentum

/// Five free spheres (no gravity, no wall) of different radii, masses and spins, one a thin shell with its own
/// `inertia`; four converge on the heaviest, with offsets so every collision is oblique, two at the same instant,
/// a third 31 µs later while those two last (about 55 µs), the fourth apart. Friction 0.5 on Mindlin's spring.
///
/// Where the values come from: every contact force — normal and tangential — acts on its two bodies equal and
/// opposite (Ft on i, -Ft on j), so Σ m v is conserved; and it acts at one point, the contact point
/// p = x_i + a_i = x_j + a_j (a_i = r_i/(r_i + r_j)(x_j - x_i), a_j = -r_j/(r_i + r_j)(x_j - x_i): indeed
/// x_j - r_j/(r_i + r_j)(x_j - x_i) = x_i + r_i/(r_i + r_j)(x_j - x_i)), so the torques about the origin,
/// (x_i + a_i) × F + (x_j + a_j) × (-F) = p × F - p × F = 0, cancel, and L = Σ (m x × v + I ω) is conserved.
/// Between contacts every body flies straight on, which keeps both. Friction only ever takes energy (≥ 0 work).
///
/// Normalisation: momentum to 1e-12 of Σ m |v| (the rounding of the velocities; docs/world.md states the same bound
/// for frictionless worlds), angular momentum to 1e-9 of Σ m |x| |v| + Σ I |ω| at the start (the bound docs/world.md
/// and the stress worlds use, with the spins' share added).
#[test]
fn free_frictional_spheres_conserve_angular_momentum() {
    // The central ball C, off the origin so that the origin is not a special point.
    let centre = [0.001, -0.002, 0.0005];
    let central = Ball {
        name: "C",
        radius: 0.015,
        mass: 0.14,
        position: centre,
        velocity: [0.0; 3],
        spin: [20.0, -10.0, 5.0],
        inertia: None,
        young: 2e11,
        poisson: 0.3,
    };
    // Each incoming ball is placed so that, were C still, it would touch C at time t along the unit direction d
    // from C's centre: start = C + (r_C + r) d - v t (it moves straight at v, towards C: v·d < 0).
    let incoming = [
        ("A", 0.008, 0.02, [-1.0, 0.3, 0.0], [2.0, 0.3, 0.1], [0.0, 30.0, -40.0], None, 0.0150),
        ("B", 0.010, 0.033, [0.2, 1.0, -0.1], [0.4, -2.5, 0.0], [-15.0, 0.0, 25.0], None, 0.0150),
        (
            "D",
            0.009,
            0.025,
            [-0.1, 0.2, -1.0],
            [0.1, -0.5, 2.0],
            [10.0, 10.0, -10.0],
            Some(2.0 / 3.0 * 0.025 * 0.009 * 0.009),
            0.01503,
        ),
        ("E", 0.011, 0.04, [1.0, -0.2, 0.3], [-1.5, 0.2, 0.0], [0.0, -20.0, 15.0], None, 0.0160),
    ];
    let mut balls = vec![central];
    for (name, radius, mass, direction, velocity, spin, inertia, t) in incoming {
        let d = unit(direction);
        assert!(dot(velocity, d) < 0.0, "{name} moves towards C");
        let position = sub(add(centre, scale(d, 0.015 + radius)), scale(velocity, t));
        balls.push(Ball { name, radius, mass, position, velocity, spin, inertia, young: 2e11, poisson: 0.3 });
    }
    // Different materials for two of them (the Mindlin stiffness takes each body's own E and ν).
    balls[2].young = 7e10;
    balls[2].poisson = 0.33;
    balls[4].young = 1.2e11;
    balls[4].poisson = 0.25;
    let mut scene = String::from("[world]\nmax_contacts = 100\n\n");
    for ball in &balls {
        scene += &ball.toml();
    }
    scene += "[contact]\nlaw = \"hertz\"\nfriction = 0.5\n";
    let report = run(&scene);

    let contacts = report["contacts"].as_array().unwrap();
    assert!(contacts.len() >= 3, "at least three collisions: {contacts:?}");
    let mut total_work = 0.0;
    for (k, c) in contacts.iter().enumerate() {
        let work = number(&c["friction_work"], "friction_work");
        assert!(work >= 0.0, "contact {k}: friction work {work} < 0");
        assert!(["sliding", "sticking"].contains(&text(&c["regime"], "regime")), "contact {k}: {c}");
        total_work += work;
    }
    assert!(total_work > 0.0, "oblique frictional collisions take energy");

    let momentum =
        |v: &dyn Fn(usize) -> V| (0..balls.len()).fold([0.0; 3], |sum, k| add(sum, scale(v(k), balls[k].mass)));
    let angular = |x: &dyn Fn(usize) -> V, v: &dyn Fn(usize) -> V, w: &dyn Fn(usize) -> V| {
        (0..balls.len()).fold([0.0; 3], |sum, k| {
            add(sum, add(scale(cross(x(k), v(k)), balls[k].mass), scale(w(k), balls[k].moment())))
        })
    };
    let body = |k: usize, key: &str| vector(&report["bodies"][k][key], key);
    let p_before = momentum(&|k| balls[k].velocity);
    let p_after = momentum(&|k| body(k, "velocity_after"));
    let l_before = angular(&|k| balls[k].position, &|k| balls[k].velocity, &|k| balls[k].spin);
    let l_after =
        angular(&|k| body(k, "position_after"), &|k| body(k, "velocity_after"), &|k| body(k, "angular_velocity_after"));
    let p_scale: f64 = balls.iter().map(|b| b.mass * norm(b.velocity)).sum();
    let l_scale: f64 =
        balls.iter().map(|b| b.mass * norm(b.position) * norm(b.velocity) + b.moment() * norm(b.spin)).sum();
    assert_vector("momentum", p_after, p_before, 1e-12 * p_scale);
    assert_vector("angular momentum about the origin", l_after, l_before, 1e-9 * l_scale);
    // Friction changed the spins (the test would be weaker if it had not): some spin moved by more than 1 rad/s.
    let spin_change =
        (0..balls.len()).map(|k| norm(sub(body(k, "angular_velocity_after"), balls[k].spin))).fold(0.0, f64::max);
    assert!(spin_change > 1.0, "largest spin change {spin_change} rad/s");

    let energy = &report["energy"];
    let dissipated = number(&energy["dissipated"], "dissipated");
    let kinetic_before = number(&energy["kinetic_before"], "kinetic_before");
    // Elastic Hertz contacts dissipate nothing: what is dissipated is the friction work.
    assert!((dissipated - total_work).abs() < 1e-9 * kinetic_before, "{dissipated} vs Σ friction work {total_work}");
    let balance = number(&energy["balance"], "balance");
    assert!(balance.abs() < 1e-9, "energy balance {balance:e}: {energy}");
}

// ---------------------------------------------------------------------------------------------------------------
// 4. A world's contact is the two-body impact

/// The same oblique, spinning, frictional sphere–sphere impact run (a) as today's two-body impact (no `[world]`,
/// `impact::impact::simulate`) and (b) as a world with a third ball far away that never touches (so the world's own
/// driver runs it, not the two-body path a world of two bodies without gravity takes). The two are independent
/// code paths integrating the same equations; nothing else acts on the pair, so their velocities and spins after
/// must agree to the integration accuracy (1e-7 of the speed here, a hundred times the tolerance of either path).
///
/// The impact sticks: its initial slip of the contact points, |s0| ≈ 0.15 m/s, is far below rigid theory's sliding
/// threshold μ P B = μ (1 + e) m* v_n B ≈ 3.6 m/s (B = 1/m_A + 1/m_B + r_A²/I_A + r_B²/I_B = 3.5/m*), so both runs
/// stop slipping (regime "sticking") and the Mindlin spring's compliance shapes the result — which rigid-body theory
/// does not give, hence the cross-check.
#[test]
fn a_world_contact_with_friction_is_the_two_body_impact() {
    // B's velocity relative to A is w; placed at R x̂ - w t* from A, B first touches A at t* along x̂.
    let (ra, rb, t_touch) = (0.01, 0.012, 1e-3);
    let (va, vb) = ([1.0, 0.0, 0.0], [-1.0, 0.05, -0.02]);
    let w = sub(vb, va);
    let a = Ball {
        name: "A",
        radius: ra,
        mass: 0.0329,
        position: [0.0; 3],
        velocity: va,
        spin: [5.0, 10.0, 20.0],
        inertia: None,
        young: 2.1e11,
        poisson: 0.3,
    };
    let b = Ball {
        name: "B",
        radius: rb,
        mass: 0.05,
        position: sub([ra + rb, 0.0, 0.0], scale(w, t_touch)),
        velocity: vb,
        spin: [-3.0, 4.0, -6.0],
        inertia: None,
        young: 7e10,
        poisson: 0.33,
    };
    let (mu, e) = (0.3, 0.7);
    let contact = format!(
        "[contact]\nlaw = \"hunt-crossley\"\nrestitution = {e:?}\nfriction = {mu:?}\ntangential_damping = 0.2\n"
    );
    // The rigid-theory regime, from the contact points' slip at first touch (arms r_A x̂ and -r_B x̂).
    let n = [1.0, 0.0, 0.0];
    let point = |ball: &Ball, arm: V| add(ball.velocity, cross(ball.spin, arm));
    let relative_velocity = sub(point(&a, scale(n, ra)), point(&b, scale(n, -rb)));
    let slip = sub(relative_velocity, scale(n, dot(relative_velocity, n)));
    let reduced = a.mass * b.mass / (a.mass + b.mass);
    let vn = dot(sub(va, vb), n);
    let threshold =
        mu * (1.0 + e) * reduced * vn * (1.0 / a.mass + 1.0 / b.mass + ra * ra / a.moment() + rb * rb / b.moment());
    assert!(norm(slip) < 0.1 * threshold, "sticks: slip {} against {threshold}", norm(slip));

    let pair = format!("{}{}{contact}", a.toml(), b.toml());
    let two = common::run(&pair);
    let far = Ball {
        name: "far",
        radius: 0.01,
        mass: 0.0329,
        position: [0.0, 0.0, 10.0],
        velocity: [0.0; 3],
        spin: [0.0; 3],
        inertia: None,
        young: 2.1e11,
        poisson: 0.3,
    };
    let report = run(&format!("[world]\nmax_contacts = 10\n\n{}{}{}{contact}", a.toml(), b.toml(), far.toml()));
    let contacts = report["contacts"].as_array().unwrap();
    assert_eq!(contacts.len(), 1, "{contacts:?}");
    let c = &contacts[0];
    assert_eq!(c["bodies"], serde_json::json!([0, 1]));
    assert!((number(&c["start_time"], "start_time") - t_touch).abs() < 1e-12, "first touch at t* = {t_touch}");
    let oblique = two.oblique.as_ref().expect("the two-body impact is oblique");
    assert_eq!(oblique.regime, "sticking");
    assert_eq!(text(&c["regime"], "regime"), "sticking", "{c}");

    let speed = norm(w);
    for (k, ball) in [&a, &b].into_iter().enumerate() {
        let what = ball.name;
        let v_two = two.bodies[k].velocity_after.expect("separated");
        let w_two = two.bodies[k].angular_velocity_after.expect("separated");
        let body = &report["bodies"][k];
        assert_vector(&format!("{what}: v after"), vector(&body["velocity_after"], "v"), v_two, 1e-7 * speed);
        assert_vector(
            &format!("{what}: ω after"),
            vector(&body["angular_velocity_after"], "ω"),
            w_two,
            1e-7 * speed / ball.radius,
        );
        assert_vector(
            &format!("{what}: ω at separation"),
            vector(&c["angular_velocities_after"][k], "ω"),
            w_two,
            1e-7 * speed / ball.radius,
        );
        assert_vector(
            &format!("{what}: ω at first touch"),
            vector(&c["angular_velocities_before"][k], "ω"),
            ball.spin,
            0.0,
        );
        // Friction did change the spins (else the comparison would be empty).
        assert!(norm(sub(w_two, ball.spin)) * ball.radius > 1e-3 * speed, "{what}: spin unchanged");
    }
    // The far ball never moved.
    assert_vector("far ball", vector(&report["bodies"][2]["velocity_after"], "v"), [0.0; 3], 0.0);
    let work = oblique.friction_work.expect("friction work");
    let world_work = number(&c["friction_work"], "friction_work");
    assert!((world_work - work).abs() < 1e-7 * reduced * speed * speed, "friction work {world_work} vs {work}");
    let balance = number(&report["energy"]["balance"], "balance");
    assert!(balance.abs() < 1e-9, "energy balance {balance:e}: {}", report["energy"]);
}

// ---------------------------------------------------------------------------------------------------------------
// 5. A ball set down at rest on a slope; a spin no friction can change

/// A steel ball set down at rest on a floor under a gravity tilted by 30° (the same as a ball on a 30° slope), μ = 0.1:
/// it cannot roll (rolling needs μ >= (2/7) tan 30° = 0.165), so it slides from the start, although its contact
/// points have no slip at first touch. With the normal impulse ∫ F_n dt = m g cos θ t (the normal motion settled,
/// its rate below 1e-7 m/s), friction μ F_n up the slope gives, in closed form,
///   v(t) = g (sin θ - μ cos θ) t,   ω(t) r = (5/2) μ g cos θ t
/// (the torque r μ F_n over I = (2/5) m r²). The contact slid throughout: regime "sliding". (Before the stick switch
/// function was kept above zero at first touch, such a contact — cap and spring both zero — stayed "sticking" with
/// its spring outgrowing the cap unseen, and a slip that later reversed kept friction pointing the old way.)
#[test]
fn a_ball_set_down_on_a_steep_slope_slides_from_the_start() {
    let (r, m, g, theta, mu, t) = (0.01, 0.0329, 9.81, 30f64.to_radians(), 0.1, 0.05);
    let ball = Ball {
        name: "ball",
        radius: r,
        mass: m,
        position: [0.0, 0.0, r],
        velocity: [0.0; 3],
        spin: [0.0; 3],
        inertia: None,
        young: 2.1e11,
        poisson: 0.3,
    };
    let scene = format!(
        "[world]\ngravity = [{:?}, 0.0, {:?}]\nend_time = {t}\n\n{}{FLOOR}[contact]\nlaw = \"hunt-crossley\"\n\
         restitution = 0.5\nfriction = {mu}\ntangential_damping = 0.5\n",
        g * theta.sin(),
        -g * theta.cos(),
        ball.toml()
    );
    let report = run(&scene);
    let contact = &report["contacts"][0];
    assert_eq!(text(&contact["regime"], "regime"), "sliding", "{contact}");
    assert!(contact["slip_rest_time"].is_null(), "{contact}");
    let body = &report["bodies"][0];
    let v = vector(&body["velocity_after"], "velocity");
    let w = vector(&body["angular_velocity_after"], "spin");
    assert!(v[2].abs() < 1e-7, "the normal motion has settled: {v:?}");
    let expected_v = g * (theta.sin() - mu * theta.cos()) * t;
    let expected_spin = 2.5 * mu * g * theta.cos() * t / r;
    assert!(relative(v[0], expected_v) < 1e-6, "v {} against {expected_v}", v[0]);
    assert!(relative(w[1], expected_spin) < 1e-6, "ω_y {} against {expected_spin}", w[1]);
    assert!(number(&report["energy"]["balance"], "balance").abs() < 1e-9);
}

/// A ball dropped with a spin about the vertical onto a rough floor: point contacts carry no torsion, so no friction
/// can change that spin; the ball still comes to rest (its motion about rest dies out) and keeps its spin, 40 rad/s.
/// A smooth floor changes no spin at all: a ball dropped turning about a horizontal axis too keeps (10, 0, 40) rad/s.
#[test]
fn a_spin_no_friction_can_change_is_kept_when_the_ball_comes_to_rest() {
    for (friction, spin) in [(0.2, [0.0, 0.0, 40.0]), (0.0, [10.0, 0.0, 40.0])] {
        let ball = Ball {
            name: "ball",
            radius: 0.01,
            mass: 0.0329,
            position: [0.0, 0.0, 0.02],
            velocity: [0.0; 3],
            spin,
            inertia: None,
            young: 2.1e11,
            poisson: 0.3,
        };
        let scene = format!(
            "[world]\ngravity = [0.0, 0.0, -9.81]\n\n{}{FLOOR}[contact]\nlaw = \"hunt-crossley\"\nrestitution = 0.5\n\
             friction = {friction}\n",
            ball.toml()
        );
        let report = run(&scene);
        assert_eq!(text(&report["world"]["end_reason"], "end_reason"), "at_rest", "μ = {friction}");
        assert_vector("spin kept", vector(&report["bodies"][0]["angular_velocity_after"], "spin"), spin, 1e-12);
        assert!(number(&report["energy"]["balance"], "balance").abs() < 1e-9);
    }
}

/// A world contact under the magnitude cap releases a soft spring where a damped law's normal force passes through
/// zero, as one impact does (`tests/wall_slide.rs`): there the room under `mu |Fn|` dips to `-|T|` for about 2e-7 s
/// of a 1.3e-4 s contact, a tenth of a step, and an island with such a contact reads its functions' slopes to find
/// it. Held to the independent slider integration of [`common::slider`] (Kelvin–Voigt's normal motion in closed
/// form, the spring cut to the limit each step) at a million steps: the ball's tangential velocity after within
/// 1e-6 m/s; the spring kept across the dip would leave it 6e-4 m/s away. (A second ball far away makes it a world
/// of the world's own driver.)
#[test]
fn a_world_contact_releases_a_soft_spring_where_the_magnitude_caps_force_passes_through_zero() {
    let (released, kept) = common::slider::Slider::SOFT_SPRING.released_and_kept();
    let scene = format!(
        "[world]\nend_time = 0.01\n\n\
         [[bodies]]\nname = \"ball\"\nradius = 0.01\ndensity = 4000.0\nposition = [0.0, 0.0, 0.0105]\n\
         velocity = [0.5, 0.0, -1.0]\nyoung = 2e11\npoisson = 0.3\n\n\
         [[bodies]]\nname = \"far\"\nradius = 0.01\ndensity = 4000.0\nposition = [1.0, 0.0, 0.5]\n\
         velocity = [0.0, 0.0, 0.0]\nyoung = 2e11\npoisson = 0.3\n\n{FLOOR}\
         [contact]\nlaw = \"kelvin-voigt\"\nstiffness = 1e7\nexponent = 1.0\nrestitution = 0.5\nfriction = 0.5\n\
         tangential_stiffness = 1e4\nfriction_cap = \"magnitude\"\nseparation = \"penetration\"\n"
    );
    let report = run(&scene);
    let contacts = contacts_of(&report, 0, 2);
    assert_eq!(contacts.len(), 1, "{}", report["contacts"]);
    let after = number(&contacts[0]["velocities_after"][0][0], "v_x after");
    assert!((after - released).abs() < 1e-6, "{after} against {released} ({kept} kept)");
}
