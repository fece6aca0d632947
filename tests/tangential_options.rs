//! The simulators' tangential options in `[contact]` (docs/oblique.md#the-simulators-options): `friction_cap =
//! "magnitude"` (mu |Fn|, friction also while a damped normal force pulls) against the default `"compressive"`, and
//! `tangential_unloading = "rescale"` (the spring shrinks with Mindlin's stiffness while the contact unloads) against
//! `"none"`. Every expected number comes from an integration or a closed form written here, never from the program.

use impact::history::{History, Phase, Recording, Sample};
use impact::impact::simulate;
use impact::report::Report;
use impact::scene::Scene;
use std::path::Path;

fn run(text: &str, recording: Recording) -> (Report, Option<History>) {
    let scene = Scene::parse(text, Path::new("tangential.toml")).unwrap_or_else(|e| panic!("{e}\n{text}"));
    let simulation = simulate(&scene, recording).unwrap_or_else(|e| panic!("{e}\n{text}"));
    (simulation.report, simulation.history)
}

/// The report's energy balance, relative to the kinetic energy before.
fn imbalance(report: &Report) -> f64 {
    let e = &report.energy;
    let (after, dissipated, left, work) = (
        e.kinetic_after.expect("separated"),
        e.dissipated.expect("separated"),
        e.elastic_left_at_separation.expect("separated"),
        e.work_of_immovable_bodies.expect("separated"),
    );
    (e.kinetic_before + work - after - dissipated - left) / e.kinetic_before
}

/// One classical Runge–Kutta step of `f` from `y` over `h`.
fn rk4<const N: usize>(f: &dyn Fn(&[f64; N]) -> [f64; N], y: &[f64; N], h: f64) -> [f64; N] {
    let shifted = |k: &[f64; N], by: f64| -> [f64; N] { std::array::from_fn(|i| y[i] + by * k[i]) };
    let k1 = f(y);
    let k2 = f(&shifted(&k1, h / 2.0));
    let k3 = f(&shifted(&k2, h / 2.0));
    let k4 = f(&shifted(&k3, h));
    std::array::from_fn(|i| y[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]))
}

// ---------------------------------------------------------------------------------------------------------------
// friction_cap: a sphere sliding on a wall through a Kelvin–Voigt contact that pulls before it ends

/// Sphere: mass (kg), radius (m), approach and tangential speeds (m/s). Kelvin–Voigt: k (N/m), c (N s/m); mu.
const MASS: f64 = 0.1;
const RADIUS: f64 = 0.01;
const APPROACH: f64 = 1.0;
const ACROSS: f64 = 3.0;
const K: f64 = 1e5;
const C: f64 = 40.0;
const MU: f64 = 0.1;

/// The sphere slides on the wall (slip along +y throughout), its Kelvin–Voigt contact ended at zero penetration; a
/// constant tangential spring of 1e10 N/m reaches the Coulomb limit mu c v0 of first contact within 1e-9 s.
fn kelvin_voigt_slide(cap: &str) -> String {
    format!(
        "[[bodies]]\nname = \"sphere\"\nradius = {RADIUS:?}\nmass = {MASS:?}\nvelocity = [{APPROACH:?}, {ACROSS:?}, 0.0]\n\n\
         [[bodies]]\nname = \"wall\"\nradius = inf\nmass = inf\nvelocity = [0.0, 0.0, 0.0]\n\n\
         [contact]\nlaw = \"kelvin-voigt\"\nstiffness = {K:?}\ndamping = {C:?}\nseparation = \"penetration\"\n\
         friction = {MU:?}\ntangential_stiffness = 1e10\nfriction_cap = \"{cap}\"\n"
    )
}

/// The normal impulses of the Kelvin–Voigt contact, (∫ max(Fn, 0) dt, ∫ max(-Fn, 0) dt) in N s, and the sphere's
/// tangential velocity (m/s) and spin about z (rad/s) after sliding throughout on the limit mu max(Fn, 0)
/// (`magnitude` false) or mu |Fn|: an RK4 integration of m d'' = -(k d + c d'), m v_y' = T, I w_z' = r T with
/// T = -mu cap sign(slip), slip = v_y + w_z r, from d = 0, d' = v0 to d = 0 again (the last step cut at the root).
fn sliding_by_rk4(magnitude: bool) -> (f64, f64, f64, f64) {
    let inertia = 0.4 * MASS * RADIUS * RADIUS;
    // y = [d, d', ∫ max(Fn, 0), ∫ max(-Fn, 0), v_y, w_z]
    let f = |y: &[f64; 6]| -> [f64; 6] {
        let force = K * y[0] + C * y[1];
        let cap = MU * if magnitude { force.abs() } else { force.max(0.0) };
        let slip = y[4] + y[5] * RADIUS;
        let tangential = -cap * slip.signum();
        [y[1], -force / MASS, force.max(0.0), (-force).max(0.0), tangential / MASS, RADIUS * tangential / inertia]
    };
    let h = 1e-8;
    let mut y = [0.0, APPROACH, 0.0, 0.0, ACROSS, 0.0];
    loop {
        let next = rk4(&f, &y, h);
        if next[0] > 0.0 {
            y = next;
            continue;
        }
        // The step crosses d = 0: bisect its length.
        let (mut low, mut high) = (0.0, h);
        for _ in 0..80 {
            let middle = 0.5 * (low + high);
            if rk4(&f, &y, middle)[0] > 0.0 { low = middle } else { high = middle }
        }
        let end = rk4(&f, &y, high);
        return (end[2], end[3], end[4], end[5]);
    }
}

/// The same impulses in closed form: with omega = sqrt(k/m), zeta = c/(2 sqrt(k m)), omega_d = omega sqrt(1 -
/// zeta²), the penetration d = (v0/omega_d) exp(-zeta omega t) sin(omega_d t) ends at t_e = pi/omega_d, and the
/// force k d + c d' vanishes where tan(omega_d t_f) = -2 zeta sqrt(1 - zeta²)/(1 - 2 zeta²); m d'' = -Fn makes each
/// impulse a change of m d'.
fn impulses_closed_form() -> (f64, f64) {
    let omega = (K / MASS).sqrt();
    let zeta = C / (2.0 * (K * MASS).sqrt());
    let damped = omega * (1.0 - zeta * zeta).sqrt();
    let rate = |t: f64| {
        APPROACH * (-zeta * omega * t).exp() * ((damped * t).cos() - zeta * omega / damped * (damped * t).sin())
    };
    let t_force =
        (std::f64::consts::PI - (2.0 * zeta * (1.0 - zeta * zeta).sqrt() / (1.0 - 2.0 * zeta * zeta)).atan()) / damped;
    let t_end = std::f64::consts::PI / damped;
    (MASS * (APPROACH - rate(t_force)), MASS * (rate(t_end) - rate(t_force)))
}

#[test]
fn the_magnitude_cap_rubs_on_while_kelvin_voigt_pulls_and_the_compressive_cap_does_not() {
    let (pushing, pulling) = impulses_closed_form();
    // The test's own two calculations agree (the integration checks the closed form and the other way round).
    let (rk_pushing, rk_pulling, _, _) = sliding_by_rk4(false);
    assert!((rk_pushing - pushing).abs() < 1e-10 * pushing, "{rk_pushing} vs {pushing}");
    assert!((rk_pulling - pulling).abs() < 1e-9 * pulling, "{rk_pulling} vs {pulling}");
    // The force pulls for a measurable part of the contact: 2.9 % of the compressive impulse at zeta = 0.2.
    assert!(pulling > 0.01 * pushing, "{pulling} {pushing}");

    let mut changes = Vec::new();
    for (cap, magnitude) in [("compressive", false), ("magnitude", true)] {
        let (report, _) = run(&kelvin_voigt_slide(cap), Recording::Off);
        let oblique = report.oblique.as_ref().expect("an oblique impact");
        assert_eq!(oblique.regime, "sliding", "{cap}");
        assert_eq!(oblique.friction_cap, cap);
        assert_eq!(oblique.tangential_unloading, "none");
        let sphere = &report.bodies[0];
        let (after, spin) = (sphere.velocity_after.unwrap(), sphere.angular_velocity_after.unwrap());
        // The tangential impulse on the sphere is mu times the impulse of the cap it slid on.
        let rubbed = if magnitude { pushing + pulling } else { pushing };
        let impulse = MASS * (ACROSS - after[1]);
        assert!((impulse - MU * rubbed).abs() < 1e-6 * MU * rubbed, "{cap}: {impulse} vs {}", MU * rubbed);
        // ... and the RK4 of the sliding law gives the velocity and spin after.
        let (_, _, velocity, spin_z) = sliding_by_rk4(magnitude);
        assert!((after[1] - velocity).abs() < 1e-6 * (ACROSS - velocity), "{cap}: {} vs {velocity}", after[1]);
        assert!((spin[2] - spin_z).abs() < 1e-6 * spin_z.abs(), "{cap}: {} vs {spin_z}", spin[2]);
        assert!(imbalance(&report).abs() < 1e-9, "{cap}: energy imbalance {:e}", imbalance(&report));
        changes.push(impulse);
    }
    // The two caps differ by mu times the tensile impulse alone (the stick of the first nanosecond is common).
    let difference = changes[1] - changes[0];
    assert!((difference - MU * pulling).abs() < 1e-8 * MU * pulling, "{difference} vs {}", MU * pulling);
}

/// ∫ max(-Fn, 0) dt (N s) of the sphere's normal motion m d'' = -Fn(d, d') from d = 0, d' = v0 to d = 0 again, by RK4
/// with steps of `h` (the last one cut at the root).
fn tensile_impulse_by_rk4(force: &dyn Fn(f64, f64) -> f64, h: f64) -> f64 {
    let f = |y: &[f64; 3]| -> [f64; 3] {
        let fn_ = force(y[0].max(0.0), y[1]);
        [y[1], -fn_ / MASS, (-fn_).max(0.0)]
    };
    let mut y = [0.0, APPROACH, 0.0];
    loop {
        let next = rk4(&f, &y, h);
        if next[0] > 0.0 {
            y = next;
            continue;
        }
        let (mut low, mut high) = (0.0, h);
        for _ in 0..80 {
            let middle = 0.5 * (low + high);
            if rk4(&f, &y, middle)[0] > 0.0 { low = middle } else { high = middle }
        }
        return rk4(&f, &y, high)[2];
    }
}

#[test]
fn tsuji_slides_on_to_separation_under_tension_with_the_magnitude_cap() {
    // Tsuji's F = K d^(3/2) + a sqrt(m K) d^(1/4) d' pulls near the end, and there its rate grows as d^(-3/4): the
    // contact slides under tension to d = 0, and the two caps differ by mu times the tensile impulse.
    let (stiffness, a) = (1e8, 0.5);
    let text = |cap: &str| {
        kelvin_voigt_slide(cap).replace("law = \"kelvin-voigt\"", "law = \"tsuji\"").replace(
            &format!("stiffness = {K:?}\ndamping = {C:?}\n"),
            &format!("stiffness = {stiffness:?}\ndamping = {a:?}\n"),
        )
    };
    let scale = (MASS * stiffness).sqrt();
    let force = |d: f64, rate: f64| stiffness * d * d.sqrt() + a * scale * d.sqrt().sqrt() * rate;
    let (pulling, finer) = (tensile_impulse_by_rk4(&force, 2e-8), tensile_impulse_by_rk4(&force, 1e-8));
    assert!((pulling - finer).abs() < 1e-5 * finer, "the integration converged: {pulling} vs {finer}");
    let mut changes = Vec::new();
    for cap in ["compressive", "magnitude"] {
        let (report, _) = run(&text(cap), Recording::Off);
        assert!(report.contact.separated, "{cap}: {:?}", report.notes);
        assert_eq!(report.oblique.as_ref().map(|o| o.regime.as_str()), Some("sliding"), "{cap}");
        assert!(imbalance(&report).abs() < 1e-9, "{cap}: energy imbalance {:e}", imbalance(&report));
        changes.push(MASS * (ACROSS - report.bodies[0].velocity_after.unwrap()[1]));
    }
    let difference = changes[1] - changes[0];
    assert!((difference - MU * finer).abs() < 1e-5 * MU * finer, "{difference:e} vs {:e}", MU * finer);
}

#[test]
fn brilliantovs_sliding_friction_rubs_through_its_compressive_impulse_or_its_whole_pull() {
    // Brilliantov's F = K (d^(3/2) + (3/2) A d^(1/2) d') pulls near the end; the sliding sphere's friction impulse
    // is mu ∫ max(Fn, 0) dt = mu (J_n + J_t) under the compressive cap and mu ∫ |Fn| dt = mu (J_n + 2 J_t) under the
    // magnitude cap, J_t the impulse of the pulling force (stress cases 7549, 8348 and 19426 of seed 424242, where
    // rigid-body theory's mu J_n missed by up to 2.5e-5 of v0). The report measures J_t; an RK4 of the normal motion
    // written here measures it too; the friction impulse follows.
    let (stiffness, time) = (1e8, 2e-5);
    let text = |cap: &str| {
        kelvin_voigt_slide(cap).replace("law = \"kelvin-voigt\"", "law = \"brilliantov\"").replace(
            &format!("stiffness = {K:?}\ndamping = {C:?}\n"),
            &format!("stiffness = {stiffness:?}\ndamping = {time:?}\n"),
        )
    };
    let force = |d: f64, rate: f64| stiffness * (d * d.sqrt() + 1.5 * time * d.sqrt() * rate);
    let (pulling, finer) = (tensile_impulse_by_rk4(&force, 2e-8), tensile_impulse_by_rk4(&force, 1e-8));
    assert!((pulling - finer).abs() < 1e-5 * finer, "the integration converged: {pulling} vs {finer}");
    // (A pull of consequence: about 1e-3 of the momentum it reverses.)
    assert!(finer > 1e-4 * MASS * APPROACH, "{finer}");
    let mut changes = Vec::new();
    for cap in ["compressive", "magnitude"] {
        let (report, _) = run(&text(cap), Recording::Off);
        assert!(report.contact.separated, "{cap}: {:?}", report.notes);
        let oblique = report.oblique.as_ref().expect("an oblique impact");
        assert_eq!(oblique.regime, "sliding", "{cap}");
        let measured = oblique.tensile_impulse.expect("a frictional contact measures its pull");
        assert!((measured - finer).abs() < 1e-5 * finer, "{cap}: tensile impulse {measured:e} vs {finer:e}");
        // The sphere's friction impulse is mu times the impulse its cap rubbed through.
        let normal = report.contact.deformation_impulse + report.contact.restitution_impulse.unwrap();
        let rubbed = normal + if cap == "magnitude" { 2.0 * finer } else { finer };
        let impulse = MASS * (ACROSS - report.bodies[0].velocity_after.unwrap()[1]);
        assert!((impulse - MU * rubbed).abs() < 1e-5 * MU * finer, "{cap}: {impulse:e} vs {:e}", MU * rubbed);
        assert!(imbalance(&report).abs() < 1e-9, "{cap}: energy imbalance {:e}", imbalance(&report));
        changes.push(impulse);
    }
    let difference = changes[1] - changes[0];
    assert!((difference - MU * finer).abs() < 1e-5 * MU * finer, "{difference:e} vs {:e}", MU * finer);
}

#[test]
fn a_sliding_contact_whose_force_is_cut_and_pushes_again_never_rubs_the_slip_on() {
    // `adams-impact` cuts its damper where spring and damper together would pull, and its damping vanishes at first
    // touch, so that its force can push again nearer the surface: stress case 11645 of seed 424242 (friction 0.33,
    // heavy damping) has its force at zero for 2.3 s of a 3.1 s contact. Coulomb sliding puts the friction force
    // against the slip, mu Fn in size, throughout: its impulse is mu J_n, and no sample pushes the slip on.
    let text = "[[bodies]]\nradius = 0.033107936317563674\nmass = 3.815498219159008e-7\n\
        velocity = [-4.0145460877811374e-5, 6.080409137334866e-5, -2.4261416754473264e-5]\n\
        young = 0.050958483178959464\npoisson = 0.39485269355787567\n\n\
        [[bodies]]\nradius = inf\nmass = inf\nvelocity = [0.0, 0.0, 0.0]\nyoung = 0.07401305920287685\n\
        poisson = 0.26367897079604286\n\n\
        [contact]\nlaw = \"adams-impact\"\ncmax = 1.0666189446852927e-5\ndmax = 2.1484631301853114e-7\n\
        stiffness = \"hertz\"\nseparation = \"penetration\"\nfriction = 0.331660919892597\n\
        tangential_damping = 0.021433438843988413\ntangential_unloading = \"rescale\"\n\
        normal = [0.057914696490967595, -0.2924169693851768, -0.9545355959554089]\n";
    let (report, history) = run(text, Recording::Steps);
    assert!(report.contact.separated, "{:?}", report.notes);
    let oblique = report.oblique.as_ref().expect("an oblique impact");
    assert_eq!(oblique.regime, "sliding");
    let history = history.expect("recorded");
    // The force is cut to zero inside the contact and pushes again.
    let cut =
        history.samples.iter().position(|s| s.phase == Phase::Restitution && s.force == 0.0 && s.penetration > 0.0);
    let again = cut.and_then(|c| history.samples[c..].iter().position(|s| s.force > 0.0));
    assert!(cut.is_some() && again.is_some(), "the force is cut and pushes again");
    // (Against the slip, to the integration's error at the contact's edges and at the cut, where mu Fn vanishes.)
    let cap = 0.331660919892597 * report.contact.max_force;
    for sample in &history.samples {
        let pushing_on = sample.tangential_force.dot(&sample.slip.normalize());
        assert!(pushing_on <= 1e-9 * cap, "friction pushes the slip on at t = {:e} s: {pushing_on:e} N", sample.time);
    }
    let normal = report.normal;
    let sphere = &report.bodies[0];
    let change: Vec<f64> = (0..3).map(|i| sphere.velocity_after.unwrap()[i] - sphere.velocity_before[i]).collect();
    let along = dot(&[change[0], change[1], change[2]], &normal);
    let across: f64 = (0..3).map(|i| (change[i] - along * normal[i]).powi(2)).sum::<f64>().sqrt();
    let normal_impulse = report.contact.deformation_impulse + report.contact.restitution_impulse.unwrap();
    let friction = 0.331660919892597 * normal_impulse;
    let impulse = sphere.mass * across;
    assert!((impulse - friction).abs() < 1e-9 * friction, "friction impulse {impulse:e} vs mu J_n {friction:e}");
}

fn dot(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    (0..3).map(|i| a[i] * b[i]).sum()
}

#[test]
fn a_world_contact_takes_the_magnitude_cap_as_one_impact_does() {
    // The same sphere and Kelvin–Voigt contact on a floor in a world run (the world's driver, its island and its
    // switches): thrown down at v0 with 3 v0 along x from 1 mm above the floor, without gravity.
    let (pushing, pulling) = impulses_closed_form();
    for (cap, rubbed) in [("compressive", pushing), ("magnitude", pushing + pulling)] {
        let text = format!(
            "[world]\nend_time = 0.02\n\n[[bodies]]\nname = \"sphere\"\nradius = {RADIUS:?}\nmass = {MASS:?}\n\
             position = [0.0, 0.0, {:?}]\nvelocity = [{ACROSS:?}, 0.0, {:?}]\n\n[[bodies]]\nname = \"floor\"\nradius = inf\n\
             mass = inf\nposition = [0.0, 0.0, 0.0]\nnormal = [0.0, 0.0, 1.0]\nvelocity = [0.0, 0.0, 0.0]\n\n\
             [contact]\nlaw = \"kelvin-voigt\"\nstiffness = {K:?}\ndamping = {C:?}\nseparation = \"penetration\"\n\
             friction = {MU:?}\ntangential_stiffness = 1e10\nfriction_cap = \"{cap}\"\n",
            RADIUS + 1e-3,
            -APPROACH
        );
        let scene = match impact::setup::parse_any(&text, Path::new("world.toml")) {
            Ok(impact::scene::Parsed::World(world)) => *world,
            other => panic!("not a world scene: {other:?}\n{text}"),
        };
        let report = impact::world_run::simulate(&scene).unwrap_or_else(|e| panic!("{e}\n{text}")).report;
        let report = serde_json::to_value(&report).expect("the world report serialises");
        let contacts = report["contacts"].as_array().expect("contacts");
        assert_eq!(contacts.len(), 1, "{cap}: {contacts:?}");
        assert_eq!(contacts[0]["regime"], "sliding", "{cap}");
        let after = report["bodies"][0]["velocity_after"][0].as_f64().expect("velocity_after");
        let impulse = MASS * (ACROSS - after);
        assert!((impulse - MU * rubbed).abs() < 1e-6 * MU * rubbed, "{cap}: {impulse} vs {}", MU * rubbed);
    }
}

#[test]
fn a_law_that_never_pulls_gives_the_same_impact_under_either_cap() {
    // Hunt–Crossley at e = 0.6 never pulls: mu |Fn| is mu Fn throughout.
    let text = |cap: &str| {
        kelvin_voigt_slide(cap)
            .replace("law = \"kelvin-voigt\"", "law = \"hunt-crossley\"\nrestitution = 0.6")
            .replace(&format!("stiffness = {K:?}\ndamping = {C:?}\n"), "stiffness = 1e9\n")
    };
    let (compressive, _) = run(&text("compressive"), Recording::Off);
    let (magnitude, _) = run(&text("magnitude"), Recording::Off);
    assert_eq!(compressive.bodies[0].velocity_after, magnitude.bodies[0].velocity_after);
    assert_eq!(compressive.bodies[0].angular_velocity_after, magnitude.bodies[0].angular_velocity_after);
}

// ---------------------------------------------------------------------------------------------------------------
// tangential_unloading: a steel sphere that sticks on a rigid wall (mu = 5) and oscillates tangentially on its
// Mindlin spring while the Hertz contact loads and unloads

const YOUNG: f64 = 2e11;
const POISSON: f64 = 0.3;
const STEEL_MASS: f64 = 0.05;
const SLIP: f64 = 0.5;

fn sticking(unloading: &str) -> String {
    format!(
        "[[bodies]]\nname = \"sphere\"\nradius = {RADIUS:?}\nmass = {STEEL_MASS:?}\nvelocity = [{APPROACH:?}, {SLIP:?}, 0.0]\n\
         young = {YOUNG:?}\npoisson = {POISSON:?}\n\n\
         [[bodies]]\nname = \"wall\"\nradius = inf\nmass = inf\nvelocity = [0.0, 0.0, 0.0]\nyoung = inf\n\n\
         [contact]\nlaw = \"hertz\"\nfriction = 5.0\ntangential_unloading = \"{unloading}\"\n"
    )
}

/// The sticking contact by RK4, y = [d, d', T, slip]: m d'' = -K d^(3/2) with K = (4/3) E* sqrt(r), E* = E/(1 - nu²);
/// the spring on the sphere dT/dt = -kt slip, kt = 8 G* sqrt(r d), G* = G/(2 - nu), G = E/(2 (1 + nu)) (the rigid
/// wall adds nothing to either), plus T d'/(2 d) while d' < 0 when `rescale`; the slip of the contact point
/// v_y + w_z r changes at T (1/m + r²/I) = 3.5 T/m. The state at each time of `times` (s, ascending), by steps of
/// at most `h` cut to land on them.
fn sticking_by_rk4(rescale: bool, times: &[f64], h: f64) -> Vec<[f64; 4]> {
    let star = YOUNG / (1.0 - POISSON * POISSON);
    let shear = YOUNG / (2.0 * (1.0 + POISSON)) / (2.0 - POISSON);
    let stiffness = 4.0 / 3.0 * star * RADIUS.sqrt();
    let f = |y: &[f64; 4]| -> [f64; 4] {
        let d = y[0].max(0.0);
        let kt = 8.0 * shear * (RADIUS * d).sqrt();
        let shrink = if rescale && y[1] < 0.0 && d > 0.0 { y[2] * y[1] / (2.0 * d) } else { 0.0 };
        [y[1], -stiffness * d * d.sqrt() / STEEL_MASS, -kt * y[3] + shrink, 3.5 * y[2] / STEEL_MASS]
    };
    let (mut t, mut y) = (0.0, [0.0, APPROACH, 0.0, SLIP]);
    let mut states = Vec::new();
    for &target in times {
        while t < target {
            let step = h.min(target - t);
            y = rk4(&f, &y, step);
            t = if step == target - t { target } else { t + step };
        }
        states.push(y);
    }
    states
}

#[test]
fn a_rescaled_spring_shrinks_with_the_contact_as_an_independent_integration_has_it() {
    let mut histories = Vec::new();
    for (unloading, rescale) in [("none", false), ("rescale", true)] {
        let (report, history) = run(&sticking(unloading), Recording::Uniform(400));
        let oblique = report.oblique.as_ref().expect("an oblique impact");
        assert_eq!(oblique.tangential_unloading, unloading);
        assert!(imbalance(&report).abs() < 1e-9, "{unloading}: energy imbalance {:e}", imbalance(&report));
        let history = history.expect("a history");
        // Compare while the spring holds (it reaches the vanishing cap only near the end), past the first instant.
        let deepest = history.samples.iter().map(|s| s.penetration).fold(0.0, f64::max);
        let held: Vec<_> = history
            .samples
            .iter()
            .take_while(|s| !s.sliding)
            .filter(|s| s.time > 0.0 && s.penetration > 0.05 * deepest)
            .collect();
        assert!(held.len() > 300, "{unloading}: the spring held for only {} samples", held.len());
        let times: Vec<f64> = held.iter().map(|s| s.time).collect();
        let expected = sticking_by_rk4(rescale, &times, 1e-9);
        let largest = expected.iter().map(|y| y[2].abs()).fold(0.0, f64::max);
        for (sample, y) in held.iter().zip(&expected) {
            assert!((sample.penetration - y[0]).abs() < 1e-7 * deepest, "{unloading} at {}", sample.time);
            let force = sample.tangential_force[1];
            assert!((force - y[2]).abs() < 1e-6 * largest, "{unloading} at {}: {force} vs {}", sample.time, y[2]);
        }
        histories.push((held.iter().map(|s| (s.time, s.tangential_force[1])).collect::<Vec<_>>(), largest));
    }
    // The rescaling is no rounding: the two springs part by a good fraction of their size while the contact unloads.
    let ((none, largest), (rescaled, _)) = (&histories[0], &histories[1]);
    let parted = none.iter().zip(rescaled).map(|(a, b)| (a.1 - b.1).abs()).fold(0.0, f64::max);
    assert!(parted > 0.1 * largest, "the springs differ by {parted:e} of {largest:e}");
}

#[test]
fn a_rescaled_spring_over_the_square_root_of_the_penetration_changes_only_by_the_slip() {
    // While the contact unloads and the spring holds, dT/dt = -kt slip + T d'/(2 d) with kt = 8 G* sqrt(r d): the
    // spring over sqrt(d), Q = T/sqrt(d), changes at -8 G* sqrt(r) slip and by nothing else — T ∝ sqrt(d), the
    // contact radius, where the contact does not slip. On the program's series, Q's change between samples against the
    // slip's integral (trapezoids).
    let shear = YOUNG / (2.0 * (1.0 + POISSON)) / (2.0 - POISSON);
    let (_, history) = run(&sticking("rescale"), Recording::Uniform(2000));
    let samples: Vec<_> = history
        .expect("a history")
        .samples
        .into_iter()
        .skip_while(|s| s.phase != Phase::Restitution)
        .take_while(|s| !s.sliding && s.penetration > 0.0)
        .collect();
    assert!(samples.len() > 800, "{} samples", samples.len());
    let ratio = |s: &Sample| s.tangential_force[1] / s.penetration.sqrt();
    let (first, last) = (&samples[0], &samples[samples.len() - 1]);
    let slid: f64 = samples.windows(2).map(|w| 0.5 * (w[0].slip[1] + w[1].slip[1]) * (w[1].time - w[0].time)).sum();
    let expected = -8.0 * shear * RADIUS.sqrt() * slid;
    let change = ratio(last) - ratio(first);
    let size = samples.iter().map(|s| ratio(s).abs()).fold(0.0, f64::max);
    assert!((change - expected).abs() < 1e-4 * size, "{change:e} vs {expected:e} (of {size:e})");
    assert!(expected.abs() > 0.1 * size, "the slip moved the spring: {expected:e} of {size:e}");
}
