//! A frictional sphere on a flat wall on its own path (`solver.method` "taylor-slide" or "dop853-slide":
//! src/dynamics/slide.rs), the normal motion and the tangential motion on the initial slip's line in regularised
//! time, by Taylor series (`auto`'s, where its series cover the laws) or by Dop853 (`auto`'s otherwise, and
//! `method = "dop853-slide"`). Held to the 3-D model
//! in physical time (`method = "dop853"`, written by each test with the scene's solver keys at rtol 1e-13: an
//! independent integration of the same equations, in other variables and steps) and, for a sphere that slides
//! throughout, to Coulomb's law in closed form. No expected number here comes from the path under test.

mod common;

use impact::history::Recording;
use impact::impact::simulate;
use impact::report::Report;
use impact::scene::Scene;
use std::path::Path;

fn run(text: &str) -> Report {
    let scene = Scene::parse(text, Path::new("wall_slide.toml")).unwrap_or_else(|e| panic!("{e}\n{text}"));
    simulate(&scene, Recording::Off).unwrap_or_else(|e| panic!("{e}\n{text}")).report
}

/// The scene of the 3-D model in physical time at tolerance 1e-13: the reference.
fn reference(text: &str) -> Report {
    run(&format!("{text}\n[solver]\nmethod = \"dop853\"\nrtol = 1e-13\natol = 1e-14\n"))
}

/// A sphere (Chung & Ooi's alumina, 2.5 mm, 3.9 m/s at `degrees` from the normal, spinning at `spin` rad/s) on a
/// wall whose normal is -z, moving along x at `wall_speed` m/s, with the contact lines `contact`.
fn scene(degrees: f64, contact: &str, spin: [f64; 3], wall_speed: f64) -> String {
    let (sin, cos) = degrees.to_radians().sin_cos();
    let [a, b, c] = spin;
    format!(
        "[[bodies]]\nradius = 0.0025\ndensity = 4000\nvelocity = [{:?}, 0.0, {:?}]\nangular_velocity = [{a:?}, {b:?}, {c:?}]\n\
         young = 3.8e11\npoisson = 0.23\n\n[[bodies]]\nradius = inf\nmass = inf\nvelocity = [{wall_speed:?}, 0.0, 0.0]\n\
         young = inf\n\n[contact]\nnormal = [0.0, 0.0, -1.0]\n{contact}\n",
        3.9 * sin,
        -3.9 * cos
    )
}

/// The scene `text` (a wall at rest) with the wall moving at `velocity` m/s.
fn moving_wall(text: String, velocity: [f64; 3]) -> String {
    let [x, y, z] = velocity;
    let at_rest = "velocity = [0.0, 0.0, 0.0]\nyoung = inf";
    assert!(text.contains(at_rest));
    text.replace(at_rest, &format!("velocity = [{x:?}, {y:?}, {z:?}]\nyoung = inf"))
}

/// Chung & Ooi's test 4: Tsuji's law, e = 0.98, mu = 0.092.
const TEST4: &str = "law = \"tsuji\"\nrestitution = 0.98\nfriction = 0.092";

/// The energy balance `(in - out) / kinetic_before` of a report.
fn balance(r: &Report) -> f64 {
    let e = &r.energy;
    let inflow = e.kinetic_before + e.work_of_immovable_bodies.unwrap_or(0.0);
    let outflow =
        e.kinetic_after.expect("after") + e.dissipated.expect("D") + e.elastic_left_at_separation.unwrap_or(0.0);
    (inflow - outflow) / e.kinetic_before
}

/// The differences of the slide path's run from the 3-D model's ([`common::oblique::differences`]) and its own
/// energy balance.
fn differences(slide: &Report, exact: &Report) -> Vec<(&'static str, f64)> {
    let mut errors = common::oblique::differences(slide, exact);
    errors.push(("energy balance", balance(slide).abs()));
    errors
}

/// Holds the scene's default run (`auto`) and its run on the Dop853 slide to the 3-D model at 1e-13 within 1e-9
/// (and the same regime); returns the worst difference.
fn agrees(text: &str) -> f64 {
    agrees_on(text, None).max(agrees_on(text, Some("dop853-slide")))
}

/// [`agrees`] on the path `method` names (`None`: the scene's default, `auto`; `Some("taylor")`: the slide by
/// Taylor series; `Some("dop853-slide")`: the slide by Dop853).
fn agrees_on(text: &str, method: Option<&str>) -> f64 {
    let exact = reference(text);
    let slide = match method {
        None => {
            let slide = run(text);
            common::oblique::assert_auto_wall_path(&slide, text);
            slide
        }
        Some(method) => {
            let slide = run(&format!("{text}\n[solver]\nmethod = \"{method}\"\n"));
            assert_eq!(slide.solver.method, if method == "taylor" { "taylor-slide" } else { "dop853-slide" }, "{text}");
            slide
        }
    };
    assert_eq!(exact.solver.method, "dop853");
    let (oa, ob) = (slide.oblique.as_ref().expect("oblique"), exact.oblique.as_ref().expect("oblique"));
    assert_eq!(oa.regime, ob.regime, "{text}");
    let mut worst: f64 = 0.0;
    for (what, error) in differences(&slide, &exact) {
        assert!(error <= 1e-9, "{what}: {error:e}\n{text}");
        worst = worst.max(error);
    }
    worst
}

/// Test 4 over the angles from 0.5° to 89.5°, both regimes (the slip comes to rest and the Mindlin spring takes
/// over below about 30°; it slides throughout above), and the angles where the general path at the default
/// tolerances once misjudged a short stick interval: 17.46° (the spin 1.5e-4 off), 28.86° (where the slip's rest
/// meets the normal force turning tensile: a stick of 6e-11 s; the time below the limit 1 % off) and 45.156° with
/// a spin of [0, 500, 200] rad/s (a short stick near the end); and where the slide by Taylor series once ended the
/// stick after the slip's rest where it began (a location that read the rounding of a switch function at its
/// mode's start: 28.28°, and 44.67° with that spin, 2 % of the duration below the limit lost).
#[test]
fn test_4_over_its_angles_agrees_with_the_3d_model() {
    let mut angles: Vec<f64> = (0..30).map(|i| 0.5 + 89.0 * f64::from(i) / 29.0).collect();
    angles.extend([17.464232116058, 28.2818909454727, 28.863431715858, 32.5, 45.0]);
    let mut worst: f64 = 0.0;
    for method in [None, Some("dop853-slide")] {
        for &degrees in &angles {
            worst = worst.max(agrees_on(&scene(degrees, TEST4, [0.0; 3], 0.0), method));
        }
        for degrees in [10.0, 28.863431715858, 44.6660830415208, 45.156] {
            worst = worst.max(agrees_on(&scene(degrees, TEST4, [0.0, 500.0, 200.0], 0.0), method));
        }
    }
    assert!(worst > 0.0, "nothing was compared");
}

/// The other laws and the tangential options the path takes: Hertz and Hunt–Crossley, Kelvin–Voigt, a constant
/// tangential spring, tangential damping, the rescaled unloading, the magnitude cap under Tsuji's pull; spin
/// across the plane of incidence, about the normal and along it; a wall moving across the normal, towards the sphere
/// and away from it.
#[test]
fn laws_options_spin_and_a_moving_wall_agree_with_the_3d_model() {
    let cases = [
        scene(15.0, "law = \"hunt-crossley\"\nrestitution = 0.7\nfriction = 0.3", [0.0, 800.0, 0.0], 0.0),
        scene(50.0, "law = \"hunt-crossley\"\nrestitution = 0.9\nfriction = 0.1", [300.0, -200.0, 100.0], 0.0),
        scene(30.0, "law = \"hertz\"\nfriction = 0.2\ntangential_stiffness = 2e6", [0.0, -300.0, 0.0], 0.4),
        scene(5.0, "law = \"hertz\"\nfriction = 0.3", [0.0; 3], -0.6),
        scene(12.0, &format!("{TEST4}\ntangential_damping = 0.3"), [0.0; 3], 0.0),
        scene(25.0, &format!("{TEST4}\ntangential_unloading = \"rescale\""), [0.0; 3], 0.0),
        scene(
            8.0,
            "law = \"tsuji\"\nrestitution = 0.3\nfriction = 0.4\nfriction_cap = \"magnitude\"\nseparation = \"penetration\"",
            [0.0; 3],
            0.0,
        ),
        scene(
            40.0,
            "law = \"kelvin-voigt\"\nstiffness = 1e7\nexponent = 1.0\nrestitution = 0.5\nfriction = 0.25",
            [0.0; 3],
            0.0,
        ),
        scene(20.0, TEST4, [0.0, 0.0, 3000.0], 0.3),
        // A wall moving towards the sphere and across, and away from it (its work on the sphere in the balance).
        moving_wall(scene(30.0, TEST4, [0.0; 3], 0.0), [0.2, 0.3, 0.5]),
        moving_wall(scene(60.0, TEST4, [100.0, -200.0, 50.0], 0.0), [-0.5, 0.1, -0.4]),
    ];
    for text in cases {
        agrees(&text);
    }
}

/// A contact's last slide on the Coulomb limit, to its end, is carried in closed form over the normal fast path's
/// motion (`closed-form-slide`, src/slide_through.rs), what comes before it integrated: test 4 at 10° and 28.86°
/// (the slip comes to rest in compression, the contact sticks, and slides again), above 32.5° (Tsuji's damped force
/// holds the spring below the limit for nanoseconds at first, then the contact slides to its end), Tsuji's
/// force separation, Hunt–Crossley with spin, Kelvin–Voigt (whose force jumps at first contact), a moving wall, a
/// Hunt–Crossley exponent of 1.25 (no series: its first stick on Dop853). Each
/// is held to the 3-D model at 1e-13 within 1e-9 ([`agrees_on`]) at the default tolerance, and within the tolerance
/// at rtol 1e-6; the closed form must be the path `auto` takes (a sufficient condition that rejected them would
/// send them to the integrated slide and fail here).
#[test]
fn a_contacts_last_slide_is_carried_in_closed_form() {
    let cases = [
        // (Test 4 at 10° and 28.86°: a slide whose slip comes to rest, a stick, and the last slide in closed form.)
        scene(10.0, TEST4, [0.0; 3], 0.0),
        scene(28.863431715858, TEST4, [0.0; 3], 0.0),
        scene(35.0, TEST4, [0.0; 3], 0.0),
        scene(45.0, TEST4, [0.0; 3], 0.0),
        scene(80.0, TEST4, [0.0; 3], 0.0),
        scene(60.0, &format!("{TEST4}\nseparation = \"force\""), [0.0; 3], 0.0),
        scene(50.0, "law = \"hunt-crossley\"\nrestitution = 0.9\nfriction = 0.1", [300.0, -200.0, 100.0], 0.0),
        scene(
            60.0,
            "law = \"kelvin-voigt\"\nstiffness = 1e7\nexponent = 1.0\nrestitution = 0.5\nfriction = 0.1",
            [0.0; 3],
            0.0,
        ),
        moving_wall(scene(60.0, TEST4, [100.0, -200.0, 50.0], 0.0), [-0.5, 0.1, -0.4]),
        // An exponent the series do not cover (its first stick on Dop853: n < 3/2 holds a Mindlin spring at first).
        scene(
            60.0,
            "law = \"hunt-crossley\"\nexponent = 1.25\nstiffness = 1e9\nrestitution = 0.8\nfriction = 0.1",
            [0.0, 200.0, 0.0],
            0.0,
        ),
    ];
    for text in cases {
        assert_eq!(run(&text).solver.method, "closed-form-slide", "{text}");
        agrees_on(&text, None);
        let loose = format!("{text}\n[solver]\nrtol = 1e-6\natol = 1e-8\n");
        let slide = run(&loose);
        assert_eq!(slide.solver.method, "closed-form-slide", "{loose}");
        for (what, error) in differences(&slide, &reference(&text)) {
            assert!(error <= 1e-6, "{what}: {error:e}\n{loose}");
        }
    }
}

/// A contact whose last slide the sufficient condition cannot show to hold (mu = 2: it sticks through most of the
/// contact, and the spring drives the slide that follows, its slip along the force) is integrated to its end by the
/// slide's model, once: `auto` names the slide by Taylor series, agrees with the 3-D model within 1e-9, reports the
/// Taylor slide's switches (Tsuji's force turns tensile on the way: the compressive limit's corner is not one) and
/// costs the Taylor slide's own run and the normal fast path's, not the two runs of a path that gave up.
#[test]
fn a_last_slide_the_condition_cannot_show_is_integrated_to_its_end() {
    for (degrees, contact) in [
        (30.0, "law = \"hertz\"\nfriction = 2.0"),
        (60.0, "law = \"hertz\"\nfriction = 2.0"),
        (30.0, "law = \"tsuji\"\nrestitution = 0.5\nfriction = 2.0"),
    ] {
        let text = scene(degrees, contact, [0.0; 3], 0.0);
        let auto = run(&text);
        assert_eq!(auto.solver.method, "taylor-slide", "{text}");
        agrees_on(&text, None);
        let taylor = run(&format!("{text}\n[solver]\nmethod = \"taylor\"\n"));
        let (a, t) = (auto.solver.force_evaluations, taylor.solver.force_evaluations);
        assert!(a < t + t / 4, "{a} evaluations against the Taylor slide's {t}\n{text}");
        let switched = |r: &Report| r.notes.iter().find(|n| n.contains("switched")).cloned();
        assert!(switched(&auto).is_some(), "{text}");
        assert_eq!(switched(&auto), switched(&taylor), "{text}");
    }
}

/// Under the magnitude cap a slide under tension starts with its switch function at zero; the function may rise,
/// turn back and dip below zero inside one long Taylor step. A Tsuji wall (a soft constant spring, mu = 0.93, a
/// 0.5 mm sphere with spin, from the wide random generator) sticks there for 1.1 of the contact's time units (its
/// 11th and 12th switches): the slide by Taylor series once stepped over it (10 switches, the rebound's tangential
/// velocity 9 % off, at every tolerance). Every path is held to the 3-D model at 1e-13 within 1e-9.
#[test]
fn a_stick_that_starts_inside_a_long_step_of_the_slide_under_tension_is_found() {
    let text = "[[bodies]]\nradius = 0.0005194990182727496\ndensity = 4000\n\
                velocity = [0.006818948123686428, 0.0, -0.006423963133570863]\n\
                angular_velocity = [5.618988871853884, 3.8392721991022523, -1.0258410654093693]\n\
                young = 3.8e11\npoisson = 0.23\n\n[[bodies]]\nradius = inf\nmass = inf\nvelocity = [0.0, 0.0, 0.0]\n\
                young = inf\n\n[contact]\nnormal = [0.0, 0.0, -1.0]\nlaw = \"tsuji\"\nrestitution = 0.2816641670949104\n\
                friction = 0.9282085362177674\ntangential_stiffness = 16012535.137246754\nfriction_cap = \"magnitude\"\n\
                separation = \"penetration\"\n";
    agrees(text);
    agrees_on(text, Some("taylor"));
    let exact = reference(text);
    let switched = |r: &Report| r.notes.iter().find(|n| n.contains("switched")).cloned();
    // (The same stick–slip history as the reference's, on `auto` and on the slide by Taylor series.)
    assert!(switched(&exact).is_some());
    assert_eq!(switched(&run(text)), switched(&exact));
    assert_eq!(switched(&run(&format!("{text}\n[solver]\nmethod = \"taylor\"\n"))), switched(&exact));
}

/// A slip that comes to rest just before maximum compression (Hertz, mu = 0.23, a 2.3 mm sphere with spin against a
/// wall moving along and towards it, from the wide random generator): the limit still grows where the slip passes
/// through zero, so the spring falls below it and the contact sticks for 5.2 µs before its last slide. Held to an
/// independent integration written here: Hertz's force `K d^(3/2)` (`K = 4/3 E* sqrt(R)`), Mindlin's
/// `kt = 8 G* sqrt(R d)` as a DEM code's elastic–perfectly-plastic slider in 3-D (the spring loaded by the slip over a
/// step, kept in the tangent plane, cut to `mu Fn`), explicit steps of the sphere's velocity and spin, at 400,000 and
/// 800,000 steps (which agree within 2e-6 of the approach speed): the spins after, times the radius, within 2e-5 of
/// the approach speed, and the time below the limit (the slider's uncut steps) within 2e-5 of it, on `auto` (the last slide in closed form), on the slide by Taylor series and on the 3-D model
/// (Dop853). (The 3-D model turned its sliding spring against the reversed slip there and stepped over the stick, up
/// to 0.33 of the approach speed off, until a reversed spring was turned only where a stick's loading would unload it
/// within 1e-3 T.)
#[test]
fn a_slip_that_rests_just_before_maximum_compression_sticks_as_an_independent_slider_does() {
    let (radius, density): (f64, f64) = (0.002268341884529728, 4000.0);
    let velocity: [f64; 3] = [0.008115458464529152, 0.0, -0.00922206116674907];
    let spin = [-2.1940530063542973, 0.9891631877759693, 1.1288028669312664];
    let wall: [f64; 3] = [2.4736407904607954e-5, 0.0051903816549221955, 0.005249622257240777];
    let friction = 0.2327229284914578;
    let text = format!(
        "[[bodies]]\nradius = {radius:?}\ndensity = {density:?}\nvelocity = {velocity:?}\nangular_velocity = {spin:?}\n\
         young = 3.8e11\npoisson = 0.23\n\n[[bodies]]\nradius = inf\nmass = inf\nvelocity = {wall:?}\nyoung = inf\n\n\
         [contact]\nnormal = [0.0, 0.0, -1.0]\nlaw = \"hertz\"\nfriction = {friction:?}\n"
    );
    // The independent integration.
    let independent = |steps: usize| {
        let cross = |a: [f64; 3], b: [f64; 3]| {
            [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
        };
        let (young, poisson): (f64, f64) = (3.8e11, 0.23);
        let m = density * 4.0 / 3.0 * std::f64::consts::PI * radius.powi(3);
        let inertia = 0.4 * m * radius * radius;
        let k = 4.0 / 3.0 * young / (1.0 - poisson * poisson) * radius.sqrt();
        let shear = young / (2.0 * (1.0 + poisson)) / (2.0 - poisson);
        // The arm from the centre to the contact point (the normal is -z).
        let arm = [0.0, 0.0, -radius];
        let approach = wall[2] - velocity[2];
        // A little longer than Hertz's elastic contact, 3.2181 (m/k)^(2/5) v^(-1/5).
        let dt = 1.05 * 3.2181 * (m / k).powf(0.4) * approach.powf(-0.2) / steps as f64;
        let (mut v, mut w, mut spring, mut d) = (velocity, spin, [0.0; 3], 0.0);
        // The time the spring spent below the limit (the steps it was not cut).
        let mut below = 0.0;
        for step in 0..steps {
            let point = cross(w, arm);
            let relative: [f64; 3] = std::array::from_fn(|i| v[i] + point[i] - wall[i]);
            d += -relative[2] * dt;
            if d <= 0.0 && step > 0 {
                break;
            }
            let force = k * d * d.sqrt();
            let kt = 8.0 * shear * (radius * d).sqrt();
            for i in 0..2 {
                spring[i] -= kt * relative[i] * dt;
            }
            let size = spring[0].hypot(spring[1]);
            if size > friction * force {
                spring = spring.map(|x| x * friction * force / size);
            } else {
                below += dt;
            }
            let torque = cross(arm, spring);
            for i in 0..3 {
                v[i] += (spring[i] + if i == 2 { force } else { 0.0 }) / m * dt;
                w[i] += torque[i] / inertia * dt;
            }
        }
        (w, approach, below)
    };
    let ((coarse, approach, coarse_below), (fine, _, fine_below)) = (independent(400_000), independent(800_000));
    for i in 0..3 {
        assert!((coarse[i] - fine[i]).abs() * radius <= 2e-6 * approach, "{coarse:?} against {fine:?}");
    }
    // (The stick's length to a few steps, each about 4e-6 of it at 800,000 steps: the two runs' within 2e-5 of it.)
    assert!((coarse_below - fine_below).abs() <= 2e-5 * fine_below, "{coarse_below} against {fine_below}");
    for (method, path) in [("auto", "closed-form-slide"), ("taylor", "taylor-slide"), ("dop853", "dop853")] {
        let report = run(&format!("{text}\n[solver]\nmethod = \"{method}\"\n"));
        assert_eq!(report.solver.method, path);
        let below = report.oblique.as_ref().expect("oblique").below_friction_limit_duration.expect("below");
        assert!(
            (below - fine_below).abs() <= 2e-5 * fine_below,
            "{path}: {below} s below the limit against {fine_below}"
        );
        let after = report.bodies[0].angular_velocity_after.expect("spin");
        for i in 0..3 {
            assert!((after[i] - fine[i]).abs() * radius <= 2e-5 * approach, "{path}: {after:?} against {fine:?}");
        }
    }
}

/// A sphere that slides throughout (Hertz's elastic law, so that nothing holds it at first contact; the slip
/// 3.9 sin 60° against mu (1 + e) (1/m + R²/I) m v_n = 7 mu v_n of change at most, with mu = 0.1) feels Coulomb's
/// force mu Fn against its slip at every instant: its tangential impulse is mu Jn, and its spin changes by
/// R mu Jn / I, with Jn = m (v_n after + v_n before) the normal impulse (e = 1 for an elastic law: Jn = 2 m v_n).
/// On `auto`'s path (the slide in closed form) and on the slide by Taylor series.
#[test]
fn a_sphere_sliding_throughout_takes_mu_times_the_normal_impulse() {
    for (degrees, contact) in [
        (60.0, "law = \"hertz\"\nfriction = 0.1"),
        (75.0, "law = \"hertz\"\nfriction = 0.05\ntangential_stiffness = 5e6"),
        (60.0, "law = \"hunt-crossley\"\nrestitution = 0.8\nfriction = 0.1"),
    ] {
        for (method, path) in [("auto", "closed-form-slide"), ("taylor", "taylor-slide")] {
            let text = format!("{}\n[solver]\nmethod = \"{method}\"\n", scene(degrees, contact, [0.0; 3], 0.0));
            let report = run(&text);
            assert_eq!(report.solver.method, path, "{text}");
            let oblique = report.oblique.as_ref().expect("oblique");
            assert_eq!(oblique.regime, "sliding", "{text}");
            assert_eq!(oblique.below_friction_limit_duration, Some(0.0), "{text}");
            let sphere = &report.bodies[0];
            let (m, r, inertia) = (sphere.mass, sphere.radius, sphere.inertia);
            let mu: f64 = contact.split("friction = ").nth(1).unwrap().lines().next().unwrap().parse().unwrap();
            let (before, after) = (sphere.velocity_before, sphere.velocity_after.expect("after"));
            // The normal is -z: the sphere's normal velocity is -v_z before and v_z after.
            let normal_impulse = m * (after[2] - before[2]);
            let speed = report.approach_speed;
            if contact.contains("hertz") {
                assert!((normal_impulse - 2.0 * m * 3.9 * degrees.to_radians().cos()).abs() <= 1e-9 * m * speed);
            }
            // The slip is along +x: the friction on the sphere along -x, the spin about +y (a torque r (n × F) with
            // the arm from the centre to the contact point, -z... written out: (0, 0, -r) × (-F, 0, 0) = (0, r F, 0)).
            let tangential_impulse = m * (before[0] - after[0]);
            // (Sliding, the force is mu Fn in closed form at every stage of every step: the two impulses keep their ratio
            // to rounding.)
            assert!(
                (tangential_impulse - mu * normal_impulse).abs() <= 1e-12 * m * speed,
                "{tangential_impulse} against {} ({text})",
                mu * normal_impulse
            );
            let spin = sphere.angular_velocity_after.expect("spin");
            let expected = r * mu * normal_impulse / inertia;
            assert!((spin[1] - expected).abs() * r <= 1e-9 * speed, "{} against {expected} ({text})", spin[1]);
            assert!(
                spin[0].abs() * r <= 1e-12 * speed && spin[2].abs() * r <= 1e-12 * speed && after[1].abs() <= 1e-12
            );
            // Coulomb's work: the slip falls linearly with the tangential impulse, u = u0 - mu k J, so the friction
            // work is -mu Jn (u0 + u_end) / 2 with k = 1/m + r²/I.
            let u0 = before[0];
            let u_end = after[0] - spin[1] * r;
            let work = -mu * normal_impulse * (u0 + u_end) / 2.0;
            let friction = oblique.friction_work.expect("friction work");
            assert!(
                (friction.abs() - work.abs()).abs() <= 1e-9 * report.energy.kinetic_before,
                "{friction} against {work} ({text})"
            );
            assert!(balance(&report).abs() <= 1e-9, "{text}");
        }
    }
}

/// A heavy damping (`alpha v_n` = 109, e = 0.009): the restitution creeps with `1 + alpha d'` within rounding of zero,
/// where the force summed as `K d^n + K d^n alpha d'` rounded below zero, taking the normal impulse back without
/// friction: over 886 steps the tangential impulse came out 2.4e-9 above mu Jn (case 785 of `impact stress --seed
/// 4242`, this scene: a sphere of 40 km and 0.1 g sliding at 82° to a wall moving at 270 m/s, the magnitude cap,
/// Mindlin's spring rescaled while unloading). Sliding throughout, the friction is mu Fn at every instant: its
/// impulse is mu Jn, with both read off the sphere's change of momentum.
#[test]
fn a_creeping_restitution_keeps_the_friction_impulse_at_mu_times_the_normal_one() {
    let text = "[[bodies]]\nradius = inf\nmass = inf\nvelocity = [217.68026411116506, 133.60422833210342, 88.20930630252033]\n\
                position = [-76958.70614107074, -52606.615932214474, -36975.81584110465]\n\n\
                [[bodies]]\nradius = 40173.65372336005\nmass = 9.800915997739352e-5\n\
                velocity = [-28.00509294685392, -1645.425399387135, 625.8357218401397]\n\
                position = [60360.83005549715, 650835.4011268439, -249557.44139551572]\n\n\
                [contact]\nlaw = \"gonthier\"\ndamping = 0.4456852070673752\nstiffness = 1587.0946700630977\n\
                exponent = 1.0675119197898626\nseparation = \"force\"\nfriction = 0.673609785178915\n\
                tangential_stiffness = 11747.966677803935\ntangential_unloading = \"rescale\"\n\
                friction_cap = \"magnitude\"\nnormal = [1.0, 0.0, 0.0]\n";
    let report = run(text);
    assert_eq!(report.solver.method, "dop853-slide");
    let oblique = report.oblique.as_ref().expect("oblique");
    assert_eq!(oblique.regime, "sliding");
    assert_eq!(oblique.below_friction_limit_duration, Some(0.0));
    let e = report.contact.restitution_velocity_ratio.expect("separated");
    assert!(e < 0.01, "a creeping restitution: e = {e}");
    let sphere = &report.bodies[1];
    let (before, after) = (sphere.velocity_before, sphere.velocity_after.expect("after"));
    let change: Vec<f64> = (0..3).map(|i| sphere.mass * (after[i] - before[i])).collect();
    // The normal is +x; the wall's velocity is constant, so the sphere's change of momentum is the impulse.
    let normal = change[0].abs();
    let tangential = change[1].hypot(change[2]);
    let mu = 0.673609785178915;
    assert!(
        (tangential - mu * normal).abs() <= 1e-12 * mu * normal,
        "tangential impulse {tangential:e} against mu Jn = {:e}: {:.2e} relative",
        mu * normal,
        tangential / (mu * normal) - 1.0
    );
}

/// `method = "dop853"` forces the 3-D model, and a history the general path (the slide path has no dense output in
/// physical time); `auto` takes the slide by Taylor series, `method = "dop853-slide"` the slide by Dop853.
#[test]
fn dop853_or_a_history_keeps_the_3d_model() {
    let text = scene(30.0, TEST4, [0.0; 3], 0.0);
    assert_eq!(run(&text).solver.method, "taylor-slide");
    assert_eq!(run(&format!("{text}\n[solver]\nmethod = \"dop853-slide\"\n")).solver.method, "dop853-slide");
    // Asked for where it does not apply (two spheres), the Dop853 slide is refused, naming the key.
    let spheres = text
        .replace("radius = inf\nmass = inf", "radius = 0.0025\ndensity = 4000")
        .replace("young = inf", "young = 3.8e11\npoisson = 0.23");
    let refused = Scene::parse(&format!("{spheres}\n[solver]\nmethod = \"dop853-slide\"\n"), Path::new("spheres.toml"))
        .map_err(|error| error.to_string())
        .and_then(|scene| simulate(&scene, Recording::Off).map(|_| ()).map_err(|error| error.to_string()));
    let message = refused.expect_err("two spheres are not a wall");
    assert!(message.contains("solver.method") && message.contains("dop853-slide"), "{message}");
    assert_eq!(run(&format!("{text}\n[solver]\nmethod = \"dop853\"\n")).solver.method, "dop853");
    let scene = Scene::parse(&text, Path::new("wall_slide.toml")).unwrap();
    let recorded = simulate(&scene, Recording::Steps).unwrap();
    assert_eq!(recorded.report.solver.method, "dop853");
    assert!(recorded.history.is_some());
}

/// The slide by Taylor series at every tolerance from 1e-4 to 1e-13 — Taylor orders 8 to 22, whose step sizes come
/// from series that are sparse at first contact (Tsuji's and Kelvin–Voigt's have only a few nonzero coefficients
/// there) — on test 4 (both regimes), Kelvin–Voigt and Tsuji under the magnitude cap: the path is `taylor-slide` (a
/// step that jumped past maximum compression would end in an error), and the velocities and spins come within 100
/// times the tolerance of the 3-D model in physical time at 1e-13.
#[test]
fn the_taylor_slide_holds_its_tolerance_at_every_order() {
    let cases = [
        scene(10.0, TEST4, [0.0; 3], 0.0),
        scene(45.0, TEST4, [0.0, 500.0, 200.0], 0.0),
        scene(
            40.0,
            "law = \"kelvin-voigt\"\nstiffness = 1e7\nexponent = 1.0\nrestitution = 0.5\nfriction = 0.25",
            [0.0; 3],
            0.0,
        ),
        scene(
            8.0,
            "law = \"tsuji\"\nrestitution = 0.3\nfriction = 0.4\nfriction_cap = \"magnitude\"\nseparation = \"penetration\"",
            [0.0; 3],
            0.0,
        ),
    ];
    for text in cases {
        let exact = reference(&text);
        for exponent in 4..=13 {
            let rtol = 10f64.powi(-exponent);
            let atol = (rtol / 100.0).max(1e-14);
            let report = run(&format!("{text}\n[solver]\nrtol = {rtol:e}\natol = {atol:e}\nmethod = \"taylor\"\n"));
            assert_eq!(report.solver.method, "taylor-slide", "rtol {rtol:e}\n{text}");
            for (what, error) in common::oblique::differences(&report, &exact) {
                if what.contains("velocity") || what.contains("spin") {
                    assert!(error <= 100.0 * rtol, "rtol {rtol:e}, {what}: {error:e}\n{text}");
                }
            }
        }
    }
}

/// `method = "taylor"` names the slide by Taylor series: its report (held to the 3-D model at 1e-13 within 1e-9), with
/// the 3-D model's history when one is asked for; a contact its series do
/// not cover (tangential damping) is refused, naming the key; slides from first contact, a short stick inside one
/// step and one inside the step that separates agree with the 3-D model within 1e-9.
#[test]
fn method_taylor_names_the_slide_by_taylor_series() {
    let text = scene(30.0, TEST4, [0.0; 3], 0.0);
    let named = format!("{text}\n[solver]\nmethod = \"taylor\"\n");
    let report = run(&named);
    assert_eq!(report.solver.method, "taylor-slide");
    for (what, error) in common::oblique::differences(&report, &reference(&text)) {
        assert!(error <= 1e-9, "{what}: {error:e}");
    }
    let parsed = Scene::parse(&named, Path::new("wall_slide.toml")).unwrap();
    let recorded = simulate(&parsed, Recording::Steps).unwrap();
    assert_eq!(recorded.report.solver.method, "taylor-slide");
    assert!(recorded.history.is_some_and(|history| history.samples.len() > 10));
    let damped = format!("{}\n[solver]\nmethod = \"taylor\"\n", scene_with(&text, "tangential_damping = 0.3"));
    let refused = Scene::parse(&damped, Path::new("damped.toml"))
        .map_err(|error| error.to_string())
        .and_then(|scene| simulate(&scene, Recording::Off).map(|_| ()).map_err(|error| error.to_string()));
    let message = refused.expect_err("tangential damping is not covered");
    assert!(message.contains("solver.method") && message.contains("tangential damping"), "{message}");
    // A contact that slides from first contact with no spring force (Hunt–Crossley's, Hertz's: the direction held
    // from the start), and a stick of a fortieth of a step between two slides (Kelvin–Voigt's, against a moving
    // wall: a dip of the switch function inside one step, 0.7 % of the duration below the limit lost before the step's
    // minimum was read).
    for text in [
        scene(45.0, "law = \"hertz\"\nfriction = 0.3", [0.0; 3], 0.0),
        scene(30.0, "law = \"hunt-crossley\"\nrestitution = 0.8\nfriction = 0.3", [0.0; 3], 0.0),
        moving_wall(
            scene(
                16.072566284243337,
                "law = \"kelvin-voigt\"\nstiffness = 1e7\nexponent = 1.0\nrestitution = 0.9645729810868284\n\
                 friction = 0.12468323415974057",
                [0.0; 3],
                0.0,
            ),
            [0.04570852228419131, -0.4810048318009639, -0.45829352055079486],
        ),
        // A stick of 2e-6 of the duration just before the separation, inside the step that separates, where every
        // switch function vanishes with the penetration (Hertz, a constant tangential spring, a moving wall).
        random_walls(1, 111).pop().expect("a wall"),
    ] {
        agrees_on(&text, Some("taylor"));
    }
}

/// A slide whose spring lies along the slip (the slip reversed under the cap) sticks in the contact's last 2e-6 with a
/// constant tangential spring (Hertz, a moving wall: `random_walls(1, 111)`), where the cap's rate, ∝ d^(1/2), falls
/// below the spring's unloading `kt |s|`: inside the step that separates, where the switch function jumps back above
/// zero. The 3-D model in physical time finds that stick at every tolerance, as the slide in regularised time does:
/// its time below the limit within 1e-9 of the Taylor slide's (without it, 1.6e-6 short at every tolerance).
#[test]
fn the_3d_model_finds_a_stick_the_separation_hides_in_its_step() {
    let text = random_walls(1, 111).pop().expect("a wall");
    let below = |r: &Report| r.oblique.as_ref().expect("oblique").below_friction_limit_duration.expect("friction");
    let slide = below(&run(&format!("{text}\n[solver]\nmethod = \"taylor\"\nrtol = 1e-12\natol = 1e-14\n")));
    for rtol in [1e-8, 1e-10, 1e-12] {
        let report = run(&format!("{text}\n[solver]\nmethod = \"dop853\"\nrtol = {rtol:e}\natol = 1e-14\n"));
        assert_eq!(report.solver.method, "dop853");
        let error = (below(&report) - slide).abs() / slide;
        assert!(error <= 1e-9, "rtol {rtol:e}: time below the limit {:e} against {slide:e}", below(&report));
    }
}

/// The Coulomb cap `mu max(Fn, 0)` has a kink where Tsuji's force turns tensile before separation: the 3-D model
/// makes that passage a step boundary. Stepping across it, Dop853's error estimate let test 4 at 45° (sliding) take
/// 1.2e-10 of its approach speed of tangential velocity in the step after it at rtol 1e-10, where the force was zero:
/// the tangential velocity and the rim's speed `r ω` after the impact are held here to the slide by Taylor series at
/// 1e-13 within 1e-11 of the approach speed (measured 1.2e-13 and 8e-13), at 1e-10 and 1e-9.
#[test]
fn the_3d_model_steps_to_the_kink_where_the_force_turns_tensile() {
    let text = scene(45.0, TEST4, [0.0; 3], 0.0);
    let tangential = |r: &Report| {
        let body = &r.bodies[0];
        [body.velocity_after.expect("separated")[0], body.angular_velocity_after.expect("separated")[1] * 0.0025]
    };
    let exact = run(&format!("{text}\n[solver]\nmethod = \"taylor\"\nrtol = 1e-13\natol = 1e-14\n"));
    for rtol in [1e-9, 1e-10] {
        let atol = rtol / 100.0;
        let report = run(&format!("{text}\n[solver]\nmethod = \"dop853\"\nrtol = {rtol:e}\natol = {atol:e}\n"));
        assert_eq!(report.solver.method, "dop853");
        let (a, b) = (tangential(&report), tangential(&exact));
        let off = (0..2).map(|i| (a[i] - b[i]).abs()).fold(0.0, f64::max) / report.approach_speed;
        assert!(off <= 1e-11, "rtol {rtol:e}: {off:e} of the approach speed");
    }
}

/// The scene `text` with one more line in its `[contact]` table.
fn scene_with(text: &str, line: &str) -> String {
    text.replace("[contact]\n", &format!("[contact]\n{line}\n"))
}

/// `count` random frictional walls from the seed `seed`: the laws the slide paths take (Hertz, Hunt–Crossley,
/// Tsuji, linear Kelvin–Voigt), e from 0.2 to 0.99, mu from 0.02 to 0.82, a Mindlin or a constant tangential spring,
/// either Coulomb cap (with the penetration's separation under the magnitude cap), incidence from 0.5° to 89.5°, half
/// of them spinning up to 1000 rad/s about each axis, a third against a moving wall.
fn random_walls(seed: u64, count: usize) -> Vec<String> {
    let mut state = seed;
    let mut uniform = move || {
        state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        ((state >> 11) as f64) / ((1u64 << 53) as f64)
    };
    let mut scenes = Vec::new();
    while scenes.len() < count {
        let (e, mu) = (0.2 + 0.79 * uniform(), 0.02 + 0.8 * uniform());
        let mut contact = match (uniform() * 4.0) as usize {
            0 => format!("law = \"hertz\"\nfriction = {mu:?}"),
            1 => format!("law = \"hunt-crossley\"\nrestitution = {e:?}\nfriction = {mu:?}"),
            2 => format!("law = \"tsuji\"\nrestitution = {e:?}\nfriction = {mu:?}"),
            _ => format!(
                "law = \"kelvin-voigt\"\nstiffness = 1e7\nexponent = 1.0\nrestitution = {e:?}\nfriction = {mu:?}"
            ),
        };
        if uniform() < 0.3 {
            contact += &format!("\ntangential_stiffness = {:?}", 1e6 * (1.0 + 10.0 * uniform()));
        }
        // (Not Kelvin–Voigt's: its force at d = 0 is c v, so a Mindlin spring on the limit mu |Fn| would hold an
        // energy (mu c v)² / (2 kt) that grows without bound as kt -> 0 at the separation.)
        if uniform() < 0.3 && !contact.contains("hertz\"") && !contact.contains("kelvin") {
            contact += "\nfriction_cap = \"magnitude\"\nseparation = \"penetration\"";
        }
        let spin = if uniform() < 0.5 {
            [2000.0 * (uniform() - 0.5), 2000.0 * (uniform() - 0.5), 2000.0 * (uniform() - 0.5)]
        } else {
            [0.0; 3]
        };
        let mut text = scene(0.5 + 89.0 * uniform(), &contact, spin, 0.0);
        if uniform() < 0.3 {
            // (Towards the sphere along the normal, at most: the bodies must approach.)
            text = moving_wall(text, [uniform() - 0.5, uniform() - 0.5, 0.5 * uniform()]);
        }
        scenes.push(text);
    }
    scenes
}

/// Random walls ([`random_walls`]) on both slide paths, `auto`'s (by Taylor series) and `method = "dop853-slide"`'s,
/// against the 3-D model at 1e-13: the velocities, spins, friction work, dissipation and energy balance within 1e-8; the time below
/// the friction limit within 1e-6 of the duration (over 4200 such walls one was 2.2e-6 off, on both paths:
/// docs/numerics.md#the-slide-path-by-taylor-series). (A wall the reference does not leave — it presses on — is
/// passed over.)
#[test]
fn random_walls_agree_with_the_3d_model_on_both_slide_paths() {
    let mut compared = 0;
    for text in random_walls(20261207, 120) {
        let exact = reference(&text);
        if exact.bodies[0].velocity_after.is_none() {
            continue;
        }
        for method in ["auto", "dop853-slide"] {
            let report = run(&format!("{text}\n[solver]\nmethod = \"{method}\"\n"));
            for (what, error) in differences(&report, &exact) {
                let tolerance = if what == "time below the limit" { 1e-6 } else { 1e-8 };
                assert!(error <= tolerance, "{method}: {what} {error:e}\n{text}");
            }
        }
        compared += 1;
    }
    assert!(compared >= 100, "{compared} walls compared");
}

/// Under the magnitude cap (`mu |Fn|`) a damped law's normal force passes through zero in restitution, where the
/// Coulomb limit is zero: the spring slides down to it and restarts from zero once the force pulls, however soft
/// it is and however short the stretch where `mu |Fn|` is below it (here about 2e-7 s of a 1.3e-4 s contact, a
/// tenth of an integration step). Every path is held to an independent integration ([`common::slider`]: Kelvin–Voigt's
/// normal motion in closed form, the spring as a DEM code's elastic–perfectly-plastic slider) at a million steps.
/// The same integration with the spring not cut (its force capped, the spring kept: what a path that steps over
/// the stretch computes) is 6e-4 of the approach speed away.
#[test]
fn a_soft_spring_is_released_where_the_magnitude_caps_normal_force_passes_through_zero() {
    let (released, kept) = common::slider::Slider::SOFT_SPRING.released_and_kept();
    let text = "[[bodies]]\nradius = 0.01\ndensity = 4000.0\nvelocity = [0.5, 0.0, -1.0]\nyoung = 2e11\npoisson = 0.3\n\n\
                [[bodies]]\nradius = inf\nmass = inf\nvelocity = [0.0, 0.0, 0.0]\nyoung = inf\n\n[contact]\n\
                normal = [0.0, 0.0, -1.0]\nlaw = \"kelvin-voigt\"\nstiffness = 1e7\nexponent = 1.0\nrestitution = 0.5\n\
                friction = 0.5\ntangential_stiffness = 1e4\nfriction_cap = \"magnitude\"\nseparation = \"penetration\"\n";
    for (method, rtol) in [
        ("auto", 1e-10),
        ("taylor", 1e-10),
        ("dop853-slide", 1e-10),
        ("dop853", 1e-10),
        ("dop853", 1e-13),
        ("auto", 1e-6),
    ] {
        let report = run(&format!("{text}\n[solver]\nmethod = \"{method}\"\nrtol = {rtol:e}\n"));
        let after = report.bodies[0].velocity_after.expect("separates")[0];
        assert!((after - released).abs() < 1e-6, "{method} at {rtol:e}: {after} against {released} ({kept} kept)");
    }
}

/// The same release under Tsuji's pull, on a large spinning ball with a soft constant spring (a wall drawn by a
/// wider random generator, radius 17 mm, mu = 0.8): where the normal force passes through zero the room under
/// `mu |Fn|` dips to `-|T|` for a few nanoseconds inside one step of every path, and each path reads it (its
/// functions' slopes at the steps' ends, the minimum between them found). Before they did, the Dop853 slide and the
/// 3-D model kept the spring across it, 1.4e-4 of the approach speed off the Taylor slide, which read it already.
#[test]
fn tsujis_pull_releases_a_soft_spring_on_every_path() {
    let text = "[[bodies]]\nradius = 0.017152092737561696\ndensity = 4000\n\
                velocity = [1.4407731957019383, 0.0, -3.7674152232357403]\n\
                angular_velocity = [14.359354674774382, -33.004595223097894, -22.685030392262156]\n\
                young = 3.8e11\npoisson = 0.23\n\n[[bodies]]\nradius = inf\nmass = inf\nvelocity = [0.0, 0.0, 0.0]\n\
                young = inf\n\n[contact]\nnormal = [0.0, 0.0, -1.0]\nlaw = \"tsuji\"\nrestitution = 0.6653819744296456\n\
                friction = 0.7955960708571866\ntangential_stiffness = 28536.36196136253\nfriction_cap = \"magnitude\"\n\
                separation = \"penetration\"\n";
    let exact = reference(text);
    for method in ["auto", "taylor", "dop853-slide", "dop853"] {
        let report = run(&format!("{text}\n[solver]\nmethod = \"{method}\"\n"));
        for (what, error) in differences(&report, &exact) {
            // (The friction work and the dissipation differ by the spring's energy the 3-D model leaves at the
            // separation, docs/numerics.md: compared on their sum, as `differences` does.)
            assert!(error <= 1e-8, "{method}: {what} {error:e}");
        }
    }
}
