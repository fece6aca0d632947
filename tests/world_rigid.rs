//! Rigid bodies in a world (docs/world.md#rigid-bodies): rods, clumps and pivoted bodies among spheres and walls.
//! Every expected number is derived here — a closed form of rigid-body mechanics (docs/references.md), a root found
//! here by bisection, or a conservation law — never read from the program's earlier output.
//!
//! Conventions: a contact's normal points from body i to body j; a rod of mass M between end points at ±(L/2) a from
//! its mass centre has I_G = M L²/12 across its axis (a small polar moment along it); the floor's face normal is +z.

mod common;

use common::vectors::{V, add, cross, norm, scale, sub};
use serde_json::Value;
use std::path::Path;

use common::{world_report_json as run, world_scene as world};

#[track_caller]
fn number(value: &Value) -> f64 {
    value.as_f64().unwrap_or_else(|| panic!("expected a number, found {value}"))
}

#[track_caller]
fn vector(value: &Value) -> V {
    let items = value.as_array().unwrap_or_else(|| panic!("expected [x, y, z], found {value}"));
    [0, 1, 2].map(|k| number(&items[k]))
}

fn relative(value: f64, expected: f64) -> f64 {
    ((value - expected) / expected).abs()
}

/// A number as TOML writes it back exactly.
fn exact(x: f64) -> String {
    format!("{x:?}")
}

fn toml_vector(v: V) -> String {
    format!("[{}, {}, {}]", exact(v[0]), exact(v[1]), exact(v[2]))
}

/// The inertia tensor of a rod along the unit `axis`: `polar` about it, `across` about every axis across it, kg m².
fn rod_tensor(axis: V, polar: f64, across: f64) -> String {
    let row = |i: usize| {
        let entries: Vec<String> =
            (0..3).map(|j| exact((polar - across) * axis[i] * axis[j] + if i == j { across } else { 0.0 })).collect();
        format!("[{}]", entries.join(", "))
    };
    format!("[{}, {}, {}]", row(0), row(1), row(2))
}

/// A steel rod of mass `mass` and length `length` between its end spheres' centres (radius `radius`), along the unit
/// `axis`, its mass centre at `centre`, moving at `velocity` and turning at `spin`.
struct Rod {
    mass: f64,
    length: f64,
    radius: f64,
    axis: V,
    centre: V,
    velocity: V,
    spin: V,
}

impl Rod {
    /// I_G across the axis, M L²/12.
    fn across(&self) -> f64 {
        self.mass * self.length * self.length / 12.0
    }

    fn toml(&self) -> String {
        let end = scale(self.axis, self.length / 2.0);
        format!(
            "[[bodies]]\nname = \"rod\"\nmass = {}\ninertia = {}\nposition = {}\nvelocity = {}\nangular_velocity = {}\n\
             young = 2.1e11\npoisson = 0.3\n\n[[bodies.spheres]]\noffset = {}\nradius = {}\n\n[[bodies.spheres]]\n\
             offset = {}\nradius = {}\n",
            exact(self.mass),
            rod_tensor(self.axis, 1e-3 * self.across(), self.across()),
            toml_vector(self.centre),
            toml_vector(self.velocity),
            toml_vector(self.spin),
            toml_vector(end),
            exact(self.radius),
            toml_vector(scale(end, -1.0)),
            exact(self.radius)
        )
    }
}

const FLOOR: &str = "[[bodies]]\nname = \"floor\"\nradius = inf\nmass = inf\nposition = [0.0, 0.0, 0.0]\n\
                     normal = [0.0, 0.0, 1.0]\nvelocity = [0.0, 0.0, 0.0]\nyoung = 2.1e11\npoisson = 0.3\n";

/// A rod inclined at `degrees` to a smooth floor, its lower end's sphere `gap` above it, dropped at `speed` without
/// spin (x and z in the rod's plane).
fn inclined_rod(degrees: f64, speed: f64, gap: f64) -> Rod {
    let (length, radius) = (0.2, 0.005);
    let theta = degrees.to_radians();
    let axis = [theta.cos(), 0.0, theta.sin()];
    Rod {
        mass: 0.2,
        length,
        radius,
        axis,
        centre: [0.0, 0.0, length / 2.0 * theta.sin() + radius + gap],
        velocity: [0.0, 0.0, -speed],
        spin: [0.0; 3],
    }
}

/// A rod inclined at θ to a smooth floor, dropped at v without spin, strikes with its lower end as rigid-body theory
/// has it with the contact's own e (docs/references.md#rigid-bodies-with-several-contacts): m_eff = M/(1 + 3 cos²θ),
/// J = (1 + e) m_eff v, v_G' = -v + J/M, ω' = 6 J cos θ/(M L) about +y (the lower end at -x is pushed up), the other
/// end at v_B = -v + (1 + e) v (1 - 3 cos²θ)/(1 + 3 cos²θ). The compliant contact lasts t_c while the rod turns, so
/// the two agree to the order of ω' t_c. Then the other end strikes where the free flight after the first impact
/// brings its sphere down to the floor: z_G + v_G' t + (L/2) sin(θ - ω' t) = r, solved here by bisection.
#[test]
fn a_rod_dropped_at_an_angle_strikes_with_the_closed_form_of_its_end_then_with_its_other_end() {
    for degrees in [30.0, 45.0, 60.0] {
        let (speed, gap) = (1.0, 1e-3);
        let rod = inclined_rod(degrees, speed, gap);
        let text = format!(
            "title = \"rod at {degrees} degrees\"\n[world]\nmax_contacts = 2\n\n{}\n{FLOOR}\n[contact]\nlaw = \
             \"hunt-crossley\"\nrestitution = 0.8\n",
            rod.toml()
        );
        let report = run(&text);
        let first = &report["contacts"][0];
        assert_eq!(first["spheres"], serde_json::json!([1, null]), "the lower end strikes first: {first}");
        let e = number(&first["restitution_velocity_ratio"]);
        let (mass, length, theta) = (rod.mass, rod.length, degrees.to_radians());
        let c2 = theta.cos().powi(2);
        let effective = mass / (1.0 + 3.0 * c2);
        let impulse = (1.0 + e) * effective * speed;
        let centre = -speed + impulse / mass;
        let spin = 6.0 * impulse * theta.cos() / (mass * length);
        let other = -speed + (1.0 + e) * speed * (1.0 - 3.0 * c2) / (1.0 + 3.0 * c2);
        let after = &first["velocities_after"][0];
        let turning = vector(&first["angular_velocities_after"][0]);
        let t_c = number(&first["duration"]);
        let tolerance = 3.0 * spin * t_c;
        // (Velocities to ω' t_c of the speed v: v_G' is a small difference at steep angles.)
        assert!((vector(after)[2] - centre).abs() < tolerance * speed, "{degrees}°: v_G' {after} vs {centre}");
        assert!(relative(turning[1], spin) < tolerance, "{degrees}°: ω' {turning:?} vs {spin}");
        // The other end's velocity, v_G + ω × r_B with r_B = (L/2) a.
        let r_b = scale(rod.axis, length / 2.0);
        let v_b = add(vector(after), cross(turning, r_b));
        assert!((v_b[2] - other).abs() < tolerance * speed, "{degrees}°: v_B {v_b:?} vs {other}");
        // The point of first touch: under the lower sphere's centre.
        // Judged `central` with the rod's own lever: the normal passes (L/2) cos θ from the mass centre, its radius
        // of gyration about that moment's axis L/√12, its effective mass M/(1 + 3 cos²θ) (docs/idealisation.md).
        let central = &first["idealisation"]["central"];
        assert!(relative(number(&central["value"]), length / 2.0 * theta.cos()) < 1e-9, "{degrees}°: {central}");
        assert!(relative(number(&central["compared_with"]), length / 12f64.sqrt()) < 1e-9, "{degrees}°: {central}");
        assert_eq!(central["verdict"], "fails", "{degrees}°: {central}");
        // (The meaning gives the effective mass to three digits: "... an effective mass of 61.5 g, not ...".)
        let meaning = central["meaning"].as_str().unwrap();
        let grams: f64 =
            meaning.split("effective mass of ").nth(1).and_then(|t| t.split(" g").next()).unwrap().parse().unwrap();
        assert!(relative(grams * 1e-3, effective) < 5e-3, "{degrees}°: {meaning} vs {effective} kg");
        let point = vector(&first["point"]);
        let expected = [-length / 2.0 * theta.cos(), 0.0, 0.0];
        assert!(norm(sub(point, expected)) < 1e-9, "{degrees}°: point {point:?} vs {expected:?}");

        // The second strike: the other end (at 30° and 45° it comes down faster than the rod fell).
        let touch = gap / speed;
        let z0 = rod.centre[2] - gap;
        let height = |t: f64| z0 + centre * t + length / 2.0 * (theta - spin * t).sin() - rod.radius;
        let (mut lo, mut hi): (f64, f64) = (0.0, 1.0);
        let mut t = 1e-4;
        while height(t) > 0.0 && t < 1.0 {
            lo = t;
            t += 1e-4;
        }
        hi = hi.min(t);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if height(mid) > 0.0 { lo = mid } else { hi = mid }
        }
        let second = &report["contacts"][1];
        assert_eq!(second["spheres"], serde_json::json!([0, null]), "{degrees}°: the other end strikes next: {second}");
        let at = number(&second["start_time"]) - touch;
        assert!((at - lo).abs() < 3.0 * t_c, "{degrees}°: the other end strikes {at} s after the first, not {lo}");
    }
}

/// Dropped exactly flat, both ends touch at once and the rod rebounds without turning (symmetry): its rebound is e v
/// with the contacts' own e, the same at both ends (Hunt–Crossley's e does not depend on the mass), and the spin
/// stays zero (docs/references.md#rigid-bodies-with-several-contacts).
#[test]
fn a_rod_dropped_flat_rebounds_at_e_v_without_turning() {
    let rod = inclined_rod(0.0, 1.0, 1e-3);
    let text = format!(
        "title = \"flat rod\"\n[world]\n\n{}\n{FLOOR}\n[contact]\nlaw = \"hunt-crossley\"\nrestitution = 0.8\n",
        rod.toml()
    );
    let report = run(&text);
    let contacts = report["contacts"].as_array().expect("contacts");
    assert_eq!(contacts.len(), 2, "{contacts:?}");
    for c in contacts {
        assert!(relative(number(&c["start_time"]), 1e-3) < 1e-9, "{c}");
    }
    let e = number(&contacts[0]["restitution_velocity_ratio"]);
    // Hunt–Crossley's map of 0.8 gives the same e at any mass: the exact e of x = chi(0.8) (docs/laws.md).
    assert!((number(&contacts[1]["restitution_velocity_ratio"]) - e).abs() < 1e-9);
    let body = &report["bodies"][0];
    let velocity = vector(&body["velocity_after"]);
    assert!(relative(velocity[2], e) < 1e-9, "rebound {velocity:?} vs e v = {e}");
    assert!(norm(vector(&body["angular_velocity_after"])) < 1e-9, "{body}");
    assert!(number(&report["energy"]["balance"]).abs() < 1e-9);
}

/// Hertz's duration constant (4/5) B(2/5, 1/2) (docs/references.md#elastic-hertz-contact): t_c = 2.9432... δ_m/v.
/// Integrated here, 2 ∫_0^1 du / sqrt(1 - u^(5/2)), with u = 1 - s² to take the root out of the end: Simpson's rule.
fn hertz_duration_constant() -> f64 {
    let f = |s: f64| {
        let rest: f64 = 1.0 - (1.0 - s * s).powf(2.5);
        if s == 0.0 { 2.0 / 2.5f64.sqrt() } else { 2.0 * s / rest.sqrt() }
    };
    let n = 20_000;
    let h = 1.0 / n as f64;
    let mut sum = f(0.0) + f(1.0);
    for k in 1..n {
        sum += if k % 2 == 1 { 4.0 } else { 2.0 } * f(k as f64 * h);
    }
    2.0 * sum * h / 3.0
}

/// Dropped exactly flat on elastic Hertz ends, each end carries half the rod: its contact is Hertz's closed form for
/// one sphere of the end's radius on the floor with the effective mass M/2 — not the eccentric M/4 of one end struck
/// alone — so its duration is 2.9433 δ_m/v and its peak force k δ_m^(3/2), with δ_m = (15 (M/2) v²/(16 E* √R))^(2/5)
/// and k = (4/3) E* √R (docs/references.md#elastic-hertz-contact); the rod rebounds at v without turning.
#[test]
fn a_rod_dropped_flat_on_hertz_ends_makes_each_end_the_contact_of_half_its_mass() {
    let rod = inclined_rod(0.0, 1.0, 1e-3);
    let text = format!("title = \"flat rod\"\n[world]\n\n{}\n{FLOOR}\n[contact]\nlaw = \"hertz\"\n", rod.toml());
    let report = run(&text);
    let contacts = report["contacts"].as_array().expect("contacts");
    assert_eq!(contacts.len(), 2, "{contacts:?}");
    let (young, poisson, v) = (2.1e11, 0.3, 1.0);
    let e_star = young / (2.0 * (1.0 - poisson * poisson));
    let k = 4.0 / 3.0 * e_star * rod.radius.sqrt();
    let half = rod.mass / 2.0;
    let depth = (15.0 * half * v * v / (16.0 * e_star * rod.radius.sqrt())).powf(0.4);
    let duration = hertz_duration_constant() * depth / v;
    for c in contacts {
        assert!(relative(number(&c["start_time"]), 1e-3) < 1e-9, "{c}");
        assert!(relative(number(&c["max_penetration"]), depth) < 1e-7, "δ_m {} vs {depth}", c["max_penetration"]);
        assert!(relative(number(&c["duration"]), duration) < 1e-7, "t_c {} vs {duration}", c["duration"]);
        assert!(relative(number(&c["max_force"]), k * depth.powf(1.5)) < 1e-7, "peak {}", c["max_force"]);
    }
    // Neither end is isolated: the other end's impulse, the same, acts on the rod all through (no gravity here); and
    // neither is central: the normal passes L/2 from the mass centre, the rod's radius of gyration about y is L/√12.
    for c in contacts {
        let isolated = &c["idealisation"]["isolated"];
        assert!((number(&isolated["ratio"]) - 1.0).abs() < 1e-6, "{isolated}");
        assert_eq!(isolated["verdict"], "fails", "{isolated}");
        let central = &c["idealisation"]["central"];
        assert!(relative(number(&central["value"]), rod.length / 2.0) < 1e-9, "{central}");
        assert!(relative(number(&central["compared_with"]), rod.length / 12f64.sqrt()) < 1e-9, "{central}");
    }
    let body = &report["bodies"][0];
    assert!(relative(vector(&body["velocity_after"])[2], v) < 1e-9, "{body}");
    assert!(norm(vector(&body["angular_velocity_after"])) < 1e-9, "{body}");
    assert!(number(&report["energy"]["balance"]).abs() < 1e-9);
}

/// The report's JSON with what a run of the same scene cannot repeat (its wall time) left out.
fn without_wall_time(mut report: Value) -> Value {
    report["solver"]["wall_time_s"] = Value::Null;
    report
}

/// A body of one sphere at its centre, given as `[[bodies.spheres]]` with its inertia, is the sphere of that radius:
/// the same run to the bit — a bouncing ball, and rough balls that spin into each other on a floor.
#[test]
fn a_body_of_one_sphere_at_its_centre_is_the_sphere_to_the_bit() {
    let (radius, mass) = (0.01, 0.0329);
    let inertia = 0.4 * mass * radius * radius;
    let ball = |name: &str, position: &str, velocity: &str, spin: &str| {
        format!(
            "[[bodies]]\nname = \"{name}\"\nradius = {radius:?}\nmass = {mass:?}\nposition = {position}\nvelocity = \
             {velocity}\nangular_velocity = {spin}\nyoung = 2.1e11\npoisson = 0.3\n"
        )
    };
    let scenes = [
        (
            "[world]\ngravity = [0.0, 0.0, -9.81]\nend_time = 0.4\n",
            vec![ball("ball", "[0.0, 0.0, 0.1]", "[0.0, 0.0, 0.0]", "[0.0, 0.0, 0.0]")],
            "law = \"hunt-crossley\"\nrestitution = 0.8\n",
        ),
        (
            "[world]\ngravity = [0.0, 0.0, -9.81]\nend_time = 0.05\n",
            vec![
                ball("a", "[0.0, 0.0, 0.0101]", "[0.5, 0.0, -0.3]", "[10.0, -40.0, 3.0]"),
                ball("b", "[0.03, 0.001, 0.0102]", "[-0.4, 0.0, 0.0]", "[0.0, 20.0, 0.0]"),
            ],
            "law = \"hunt-crossley\"\nrestitution = 0.7\nfriction = 0.3\n",
        ),
    ];
    for (head, balls, contact) in scenes {
        let spheres: String = balls.join("\n");
        let clumps = spheres.replace(&format!("radius = {radius:?}\n"), &format!("inertia = {inertia:?}\n"));
        let clumps = clumps.replace(
            "poisson = 0.3\n",
            &format!("poisson = 0.3\n\n[[bodies.spheres]]\noffset = [0.0, 0.0, 0.0]\nradius = {radius:?}\n"),
        );
        let scene = |bodies: &str| format!("title = \"one sphere\"\n{head}\n{bodies}\n{FLOOR}\n[contact]\n{contact}");
        let (sphere, clump) = (run(&scene(&spheres)), run(&scene(&clumps)));
        assert!(!sphere["contacts"].as_array().unwrap().is_empty());
        assert_eq!(without_wall_time(sphere), without_wall_time(clump), "{}", scene(&clumps));
    }
}

/// A random world of free rigid bodies without gravity or walls: 3 to 5 clumps of 1 to 4 spheres (offsets up to
/// 2 cm, radii 3 to 8 mm), turned tensors, spinning, thrown at each other, rough or smooth.
fn free_clumps(index: u64) -> String {
    let mut draw = impact::draw::Draw::new(35, index);
    let count = 3 + (draw.unit() * 3.0) as usize;
    let laws = ["hertz", "hunt-crossley", "kelvin-voigt", "tsuji"];
    let law = draw.pick(&laws);
    let mut text = format!("title = \"free clumps {index}\"\n[world]\nend_time = 0.1\n\n[contact]\nlaw = \"{law}\"\n");
    if law != "hertz" {
        text += &format!("restitution = {}\n", exact(draw.uniform(0.3, 0.95)));
    }
    if law == "kelvin-voigt" {
        text += "stiffness = 1e6\n";
    }
    if draw.chance(0.5) {
        text += &format!("friction = {}\n", exact(draw.uniform(0.1, 0.6)));
    }
    for k in 0..count {
        let centre = [0.05 * k as f64, draw.uniform(-0.004, 0.004), draw.uniform(-0.004, 0.004)];
        let toward = if 2 * k + 1 < count { 1.0 } else { -1.0 };
        let velocity = [toward * draw.uniform(0.2, 1.5), draw.uniform(-0.1, 0.1), 0.0];
        let spin = [draw.uniform(-30.0, 30.0), draw.uniform(-30.0, 30.0), draw.uniform(-30.0, 30.0)];
        let mass = draw.log(0.01, 0.1);
        let tensor = common::random_inertia(&mut draw, mass * 2e-4);
        let rows: Vec<String> = (0..3)
            .map(|i| format!("[{}, {}, {}]", exact(tensor[(i, 0)]), exact(tensor[(i, 1)]), exact(tensor[(i, 2)])))
            .collect();
        text += &format!(
            "\n[[bodies]]\nname = \"c{k}\"\nmass = {}\ninertia = [{}]\nposition = {}\nvelocity = {}\n\
             angular_velocity = {}\nyoung = 2e11\npoisson = 0.3\n",
            exact(mass),
            rows.join(", "),
            toml_vector(centre),
            toml_vector(velocity),
            toml_vector(spin)
        );
        let spheres = 1 + (draw.unit() * 4.0) as usize;
        for _ in 0..spheres {
            let d = draw.direction();
            let offset = scale([d.x, d.y, d.z], draw.uniform(0.0, 0.02));
            text += &format!(
                "\n[[bodies.spheres]]\noffset = {}\nradius = {}\n",
                toml_vector(offset),
                exact(draw.uniform(0.003, 0.008))
            );
        }
    }
    text
}

/// Free rigid bodies keep their momentum (to 1e-12 of Σ m |v|) and their angular momentum about the origin, orbital
/// and spin, Σ (x × m v + L) with L = R I Rᵀ ω about each mass centre (to 1e-9 of Σ (m |x| |v| + |L|)), and close
/// their energy balance with rotation (to 1e-9): the contacts' forces are equal and opposite along the line of the
/// spheres' centres, and their tangential forces act at one point.
#[test]
fn free_rigid_bodies_keep_momentum_angular_momentum_and_energy() {
    let mut contacts = 0;
    for index in 0..12 {
        let text = free_clumps(index);
        let scene = world(&text);
        let report = run(&text);
        contacts += report["contacts"].as_array().unwrap().len();
        let (mut p0, mut p1, mut l0, mut l1) = ([0.0; 3], [0.0; 3], [0.0; 3], [0.0; 3]);
        let (mut p_scale, mut l_scale) = (0.0, 0.0);
        for (body, out) in scene.bodies.iter().zip(report["bodies"].as_array().unwrap()) {
            let m = body.mass;
            let (x0, v0) = (body.position.unwrap().into(), body.velocity.into());
            let spin0 = body.inertia_matrix() * body.angular_velocity;
            let (x1, v1) = (vector(&out["position_after"]), vector(&out["velocity_after"]));
            let spin1 = vector(&out["angular_momentum_after"]);
            p0 = add(p0, scale(v0, m));
            p1 = add(p1, scale(v1, m));
            l0 = add(l0, add(scale(cross(x0, v0), m), spin0.into()));
            l1 = add(l1, add(scale(cross(x1, v1), m), spin1));
            p_scale += m * norm(v0);
            l_scale += m * norm(x0).max(norm(x1)) * norm(v0).max(norm(v1)) + norm(spin0.into()).max(norm(spin1));
        }
        let momentum = norm(sub(p1, p0)) / p_scale;
        let angular = norm(sub(l1, l0)) / l_scale;
        let balance = number(&report["energy"]["balance"]).abs();
        assert!(momentum < 1e-12, "world {index}: momentum {momentum:e}\n{text}");
        assert!(angular < 1e-9, "world {index}: angular momentum {angular:e}\n{text}");
        assert!(balance < 1e-9, "world {index}: energy balance {balance:e}\n{text}");
    }
    assert!(contacts > 12, "the clumps must meet: {contacts} contacts");
}

/// A rod spinning in flight is no polynomial: it flies integrated, its spheres' gaps watched as events. Spinning at ω
/// about +y while its mass centre falls at v (no gravity), its +x end's sphere is at z = H - v t - (L/2) sin(ω t):
/// the first touch is that function's first fall to the radius, found here by bisection. The second case dips below
/// the floor by a hair only (δ) and for far less than one of the integrator's steps: it is found as a minimum of the
/// gap below zero and located there, not stepped over.
#[test]
fn a_spinning_rod_first_touches_the_floor_where_its_closed_form_says_even_by_a_graze() {
    let (length, radius, v, omega) = (0.2, 0.005, 0.5, 20.0);
    for depth in [1e-3, 1e-6, 1e-8] {
        // The +x end's lowest point at ω t = π/2 is `depth` below the floor.
        let lowest = std::f64::consts::FRAC_PI_2 / omega;
        let height = radius + v * lowest + length / 2.0 - depth;
        let rod = Rod {
            mass: 0.2,
            length,
            radius,
            axis: [1.0, 0.0, 0.0],
            centre: [0.0, 0.0, height],
            velocity: [0.0, 0.0, -v],
            spin: [0.0, omega, 0.0],
        };
        let text = format!(
            "title = \"spinning rod\"\n[world]\nmax_contacts = 1\n\n{}\n{FLOOR}\n[contact]\nlaw = \"hertz\"\n",
            rod.toml()
        );
        let gap = |t: f64| height - v * t - length / 2.0 * (omega * t).sin() - radius;
        let (mut lo, mut hi) = (0.0, lowest);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if gap(mid) > 0.0 { lo = mid } else { hi = mid }
        }
        let report = run(&text);
        let first = &report["contacts"][0];
        assert_eq!(first["spheres"], serde_json::json!([0, null]), "depth {depth}: {first}");
        let at = number(&first["start_time"]);
        assert!(relative(at, lo) < 1e-9, "depth {depth}: first touch at {at} s, closed form {lo} s");
    }
}

/// The Hamilton product of two quaternions [w, x, y, z].
fn product(a: [f64; 4], b: [f64; 4]) -> [f64; 4] {
    [
        a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
        a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
        a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
        a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0],
    ]
}

/// `v` turned by the unit quaternion `q`: q (0, v) q*.
fn turned(q: [f64; 4], v: V) -> V {
    let conjugate = [q[0], -q[1], -q[2], -q[3]];
    let r = product(product(q, [0.0, v[0], v[1], v[2]]), conjugate);
    [r[1], r[2], r[3]]
}

/// A body tumbling free — principal moments I = (2, 3, 4)·1e-5 kg m² along the scene axes at t = 0, set spinning
/// near its intermediate axis, so that it flips over (Dzhanibekov's nut) — flies as Euler's equations have it:
/// `I ω̇ = (I ω) × ω` in the body's axes and `q̇ = q (0, ω)/2`, integrated here by classical RK4 at 1e-5 s (its error
/// far below the tolerances). Its orientation and angular velocity at the end match that integration, its angular
/// momentum about the mass centre is the initial `I ω` (torque-free flight keeps it) and its mass centre flew
/// straight at its velocity. The second body, a floor far below the flight without gravity, is never reached.
#[test]
fn a_tumbling_body_flies_as_eulers_equations_keeping_its_angular_momentum() {
    let moments = [2e-5, 3e-5, 4e-5];
    let spin = [2.0, 30.0, 1.0];
    let (duration, velocity, centre) = (0.5, [0.3, -0.2, 0.0], [0.0, 0.0, 1.0]);
    let text = format!(
        "title = \"tumbling\"\n[world]\nend_time = {duration:?}\n\n[[bodies]]\nname = \"nut\"\nmass = 0.1\ninertia = {}\n\
         position = {}\nvelocity = {}\nangular_velocity = {}\nyoung = 2.1e11\npoisson = 0.3\n\n[[bodies.spheres]]\n\
         offset = [0.02, 0.0, 0.0]\nradius = 0.005\n\n[[bodies.spheres]]\noffset = [-0.02, 0.0, 0.0]\nradius = 0.005\n\n\
         {}\n[contact]\nlaw = \"hertz\"\n",
        toml_vector(moments),
        toml_vector(centre),
        toml_vector(velocity),
        toml_vector(spin),
        FLOOR.replace("position = [0.0, 0.0, 0.0]", "position = [0.0, 0.0, -10.0]")
    );
    let report = run(&text);
    assert!(report["contacts"].as_array().unwrap().is_empty());
    // RK4 of (ω in body axes, q from body to scene axes).
    let derivative = |w: V, q: [f64; 4]| -> (V, [f64; 4]) {
        let l = [moments[0] * w[0], moments[1] * w[1], moments[2] * w[2]];
        let torque = cross(l, w);
        let dw = [torque[0] / moments[0], torque[1] / moments[1], torque[2] / moments[2]];
        let dq = product(q, [0.0, w[0], w[1], w[2]]).map(|c| 0.5 * c);
        (dw, dq)
    };
    let (mut w, mut q) = (spin, [1.0, 0.0, 0.0, 0.0]);
    let steps = 50_000;
    let h = duration / steps as f64;
    let mut flipped = false;
    for _ in 0..steps {
        let along = |w: V, dw: V, k: f64| add(w, scale(dw, k));
        let alongq = |q: [f64; 4], dq: [f64; 4], k: f64| [0, 1, 2, 3].map(|i| q[i] + k * dq[i]);
        let (k1w, k1q) = derivative(w, q);
        let (k2w, k2q) = derivative(along(w, k1w, h / 2.0), alongq(q, k1q, h / 2.0));
        let (k3w, k3q) = derivative(along(w, k2w, h / 2.0), alongq(q, k2q, h / 2.0));
        let (k4w, k4q) = derivative(along(w, k3w, h), alongq(q, k3q, h));
        w = [0, 1, 2].map(|i| w[i] + h / 6.0 * (k1w[i] + 2.0 * k2w[i] + 2.0 * k3w[i] + k4w[i]));
        q = [0, 1, 2, 3].map(|i| q[i] + h / 6.0 * (k1q[i] + 2.0 * k2q[i] + 2.0 * k3q[i] + k4q[i]));
        flipped |= w[1] < 0.0;
    }
    assert!(flipped, "the reference must tumble: its intermediate axis turns over");
    let length = q.iter().map(|c| c * c).sum::<f64>().sqrt();
    let q = q.map(|c| c / length);
    let body = &report["bodies"][0];
    let orientation: Vec<f64> = body["orientation_after"].as_array().unwrap().iter().map(number).collect();
    let sign = if orientation.iter().zip(&q).map(|(a, b)| a * b).sum::<f64>() < 0.0 { -1.0 } else { 1.0 };
    let apart = orientation.iter().zip(&q).map(|(a, b)| (sign * a - b).abs()).fold(0.0, f64::max);
    assert!(apart < 1e-9, "orientation {orientation:?} vs {q:?}");
    let omega = turned(q, w);
    let reported = vector(&body["angular_velocity_after"]);
    assert!(norm(sub(reported, omega)) < 1e-9 * norm(spin), "ω {reported:?} vs {omega:?}");
    let l0 = [moments[0] * spin[0], moments[1] * spin[1], moments[2] * spin[2]];
    let l1 = vector(&body["angular_momentum_after"]);
    assert!(norm(sub(l1, l0)) < 1e-9 * norm(l0), "L {l1:?} vs {l0:?}");
    let x1 = vector(&body["position_after"]);
    let x = add(centre, scale(velocity, duration));
    assert!(norm(sub(x1, x)) < 1e-12, "x {x1:?} vs {x:?}");
    assert!(number(&report["energy"]["balance"]).abs() < 1e-9);
}

/// The sequential model strikes a rod's lower end as the instantaneous eccentric impact with the contact's own e and
/// Coulomb friction (docs/references.md#rigid-bodies-with-several-contacts), solved here for the planar rod: with the
/// contact point at r = (-(L/2) cos θ, 0, -(L/2) sin θ - ρ) from the mass centre (ρ the end sphere's radius), an
/// impulse P = (P_x, 0, P_z) from the floor gives v_G' = v_G + P/M and ω_y' = (r_z P_x - r_x P_z)/I_G, and the point
/// then moves at (v_Gx' + ω' r_z, v_Gz' - ω' r_x). Smooth, P_x = 0 and the point's normal velocity is reversed times
/// e. Rough with μ = 1 and no sideways motion, it sticks: the 2×2 system of a point stopped across the normal and
/// reversed along it, its P inside the cone (checked). With μ = 0.1 and the rod moving sideways at 3 m/s, it slides
/// throughout: P = J_n (n - μ s) along the initial slip s = +x, J_n from the normal restitution, and the slip keeps its
/// sense (checked). Without gravity and with one contact, the model's velocities after are these.
#[test]
fn the_sequential_model_strikes_a_rods_end_as_the_eccentric_impact_with_coulomb_friction() {
    let (v, degrees) = (1.0, 40.0);
    for (friction, sideways) in [(0.0, 0.0), (1.0, 0.0), (0.1, 3.0)] {
        let mut rod = inclined_rod(degrees, v, 1e-3);
        rod.velocity = [sideways, 0.0, -v];
        let text = format!(
            "title = \"rod's end\"\n[world]\nmax_contacts = 1\n\n{}\n{FLOOR}\n[contact]\nlaw = \"hunt-crossley\"\n\
             restitution = 0.8\nfriction = {friction:?}\n",
            rod.toml()
        );
        let report = run(&text);
        let first = &report["contacts"][0];
        assert_eq!(first["spheres"], serde_json::json!([1, null]), "{first}");
        let e = number(&first["restitution_velocity_ratio"]);
        let (mass, inertia, theta) = (rod.mass, rod.across(), f64::to_radians(degrees));
        let (rx, rz) = (-rod.length / 2.0 * theta.cos(), -rod.length / 2.0 * theta.sin() - rod.radius);
        // The point's velocity after an impulse (px, pz): linear in it.
        let after = |px: f64, pz: f64| {
            let spin = (rz * px - rx * pz) / inertia;
            let (gx, gz) = (sideways + px / mass, -v + pz / mass);
            ((gx, gz, spin), (gx + spin * rz, gz - spin * rx))
        };
        let (px, pz) = if friction == 0.0 {
            // u_z(0, pz) = e v: u_z is affine in pz.
            let (_, (_, u0)) = after(0.0, 0.0);
            let (_, (_, u1)) = after(0.0, 1.0);
            (0.0, (e * v - u0) / (u1 - u0))
        } else if sideways == 0.0 {
            // u_x = 0, u_z = e v: Cramer's rule on the affine map's columns.
            let (_, (x0, z0)) = after(0.0, 0.0);
            let (_, (xa, za)) = after(1.0, 0.0);
            let (_, (xb, zb)) = after(0.0, 1.0);
            let (a, b, c, d) = (xa - x0, xb - x0, za - z0, zb - z0);
            let (f, g) = (-x0, e * v - z0);
            let det = a * d - b * c;
            let (px, pz) = ((f * d - b * g) / det, (a * g - f * c) / det);
            assert!(px.abs() <= friction * pz, "the reference must stick: P = ({px}, {pz})");
            (px, pz)
        } else {
            // P = J_n (-μ, 1): u_z(J_n) = e v.
            let (_, (_, u0)) = after(0.0, 0.0);
            let (_, (_, u1)) = after(-friction, 1.0);
            let jn = (e * v - u0) / (u1 - u0);
            let (_, (slip, _)) = after(-friction * jn, jn);
            assert!(slip > 0.0, "the reference must slide throughout: slip after {slip}");
            (-friction * jn, jn)
        };
        let ((gx, gz, spin), _) = after(px, pz);
        let model = &report["sequential"]["simulated_e"];
        let velocity = vector(&model["velocity_after"][0]);
        let turning = vector(&model["angular_velocity_after"][0]);
        let expected = [gx, 0.0, gz];
        assert!(norm(sub(velocity, expected)) < 1e-9 * v, "μ {friction}: v_G' {velocity:?} vs {expected:?}");
        assert!(norm(sub(turning, [0.0, spin, 0.0])) < 1e-9 * spin.abs(), "μ {friction}: ω' {turning:?} vs {spin}");
    }
}

/// The sequential model of a rod's chatter (models/rod-chatter.toml: dropped at 30° under gravity on a smooth floor,
/// its ends striking in turn) against the same model worked here for the planar rod: from t = 0 the rod flies under
/// gravity (its spin about y kept: y is a principal axis whatever the rod's angle), and at each simulated contact's
/// start time its end at horizontal distance r_x from the mass centre (the contact's point; the mass centre stays on
/// x = 0, nothing pushing it sideways) takes `P = -(1 + e) u / (1/M + r_x²/I_G)` with u = v_z - ω_y r_x the point's
/// velocity and e the contact's simulated e (none when it no longer approaches): v_z += P/M, ω_y -= r_x P/I_G.
/// Each contact's velocity after and the spin at the end to 1e-9.
#[test]
fn the_sequential_model_of_a_rods_chatter_is_the_planar_rods_impacts_in_turn() {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/models/rod-chatter.toml")).unwrap();
    let report = run(&text);
    let contacts = report["contacts"].as_array().unwrap();
    assert!(contacts.len() >= 4, "a chatter: {contacts:?}");
    let ends: Vec<u64> = contacts.iter().map(|c| c["spheres"][0].as_u64().unwrap()).collect();
    assert!(ends.windows(2).any(|w| w[0] != w[1]), "both ends strike: {ends:?}");
    let (mass, inertia, g) = (0.2, 0.2 * 0.2 * 0.2 / 12.0, 9.81);
    let (mut now, mut v, mut spin) = (0.0, -1.0, 0.0);
    let model = &report["sequential"]["simulated_e"];
    for (k, c) in contacts.iter().enumerate() {
        let at = number(&c["start_time"]);
        v -= g * (at - now);
        now = at;
        let r_x = vector(&c["point"])[0];
        let e = number(&c["restitution_velocity_ratio"]);
        let u = v - spin * r_x;
        if u < 0.0 {
            let impulse = -(1.0 + e) * u / (1.0 / mass + r_x * r_x / inertia);
            v += impulse / mass;
            spin -= r_x * impulse / inertia;
        }
        let after = vector(&model["contact_velocities_after"][k][0]);
        assert!((after[2] - v).abs() < 1e-9, "contact {k}: v_z after {} vs {v}", after[2]);
        assert!(after[0].abs() < 1e-12 && after[1].abs() < 1e-12, "contact {k}: {after:?}");
    }
    let turning = vector(&model["angular_velocity_after"][0]);
    assert!((turning[1] - spin).abs() < 1e-9 * spin.abs(), "ω_y at the end {} vs {spin}", turning[1]);
    let end = number(&report["world"]["end_time"]);
    let centre = vector(&model["velocity_after"][0]);
    assert!((centre[2] - (v - g * (end - now))).abs() < 1e-9, "v_z at the end {centre:?}");
}

#[test]
fn constant_e_compares_a_rods_end_only_with_the_same_ends_other_contacts() {
    // A rod's two ends meet the floor with different effective masses (M/(1 + 3 cos²θ) at each end's own angle), so
    // the e of one end at one speed and of the other end at another says nothing of how one contact's e depends on
    // speed: each contact's constant_e names only contacts of its own sphere (models/rod-chatter.toml: the ends
    // alternate, so a comparison across ends would name one).
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/models/rod-chatter.toml")).unwrap();
    let report = run(&text);
    let contacts = report["contacts"].as_array().expect("contacts");
    let ends: Vec<&Value> = contacts.iter().map(|c| &c["spheres"]).collect();
    assert!(ends.iter().any(|s| s[0] == 0) && ends.iter().any(|s| s[0] == 1), "both ends strike: {ends:?}");
    let mut named = 0;
    for (k, c) in contacts.iter().enumerate() {
        let meaning = c["idealisation"]["constant_e"]["meaning"].as_str().unwrap_or("");
        for word in meaning.split("in contact ").skip(1) {
            let other: usize = word.split(|ch: char| !ch.is_ascii_digit()).next().unwrap().parse().unwrap();
            assert_eq!(
                ends[other], ends[k],
                "contact {k} (spheres {}) is compared with contact {other}: {meaning}",
                ends[k]
            );
            named += 1;
        }
    }
    assert!(named >= 4, "the comparisons name other contacts: {named}");
}

#[test]
fn a_clumps_verdicts_measure_the_sphere_that_touches_not_the_bounding_radius() {
    // A rod of two 5 mm end spheres 0.2 m apart (bounding radius 105 mm) dropped flat on a floor: each end meets the
    // floor as a 5 mm sphere, so `particles` compares a = sqrt(R* d_max), R* = 5 mm against a wall, with 5 mm (not
    // 105 mm), and `instantaneous` the relative travel v t_c with 5 mm. A clump has no density and its length along
    // a wave's path is not a sphere's diameter: `quasi_static` has no transit to form from the scene.
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/models/rod-dropped-flat.toml")).unwrap();
    let scene = world(&text);
    let sphere = scene.bodies[0].spheres[0].radius;
    assert_eq!(sphere, 0.005);
    let report = run(&text);
    for c in report["contacts"].as_array().expect("contacts") {
        let verdicts = &c["idealisation"];
        let particles = &verdicts["particles"];
        assert_eq!(number(&particles["compared_with"]), sphere, "{particles}");
        let a = (sphere * number(&c["max_penetration"])).sqrt();
        assert!(relative(number(&particles["value"]), a) < 1e-12, "{particles} against a = {a:e}");
        let instantaneous = &verdicts["instantaneous"];
        assert_eq!(number(&instantaneous["compared_with"]), sphere, "{instantaneous}");
        assert!(verdicts["quasi_static"].is_null(), "{}", verdicts["quasi_static"]);
    }
}

#[test]
fn the_readable_report_shows_the_spin_the_sequential_model_gives_a_rod_the_simulation_leaves_unturned() {
    // A rod dropped flat does not turn in the simulation (both ends at once, by symmetry), but the sequential model,
    // taking one end's blow and then the other's, leaves it turning (JSON: sequential.nominal.angular_velocity_after):
    // the table shows that spin beside the model's velocity.
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/models/rod-dropped-flat.toml");
    let report = run(&std::fs::read_to_string(path).unwrap());
    let spin = vector(&report["sequential"]["nominal"]["angular_velocity_after"][0]);
    assert!(norm(spin) > 1.0, "the model turns the rod: {spin:?}");
    assert!(norm(vector(&report["bodies"][0]["angular_velocity_after"])) < 1e-9, "the simulation does not");
    let output = common::binary::impact(Path::new(env!("CARGO_MANIFEST_DIR")), &["run", path]);
    let table = common::binary::stdout(&output);
    let section = table.split("sequential model").nth(1).expect("the sequential section");
    assert_eq!(section.matches("angular velocity after, rod").count(), 2, "{section}");
}
