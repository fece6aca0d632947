//! The Hunt–Crossley family F = K d^n (1 + alpha d') against its exact results (docs/references.md).

mod common;
use common::{assert_close, on_wall};
use impact::history::Recording;
use impact::impact::simulate;
use impact::scene::Scene;
use std::path::Path;

/// One row of docs/references.md's quadrature table: x = alpha v0, n, then e, dmax/L, t0/T, tc/T, Fmax/F0 (checked values).
struct Row {
    x: f64,
    n: f64,
    e: f64,
    max_penetration: f64,
    max_compression_time: f64,
    duration: f64,
    max_force: f64,
}

const TABLE: [Row; 5] = [
    Row {
        x: 0.5,
        n: 1.5,
        e: 0.7484349315974,
        max_penetration: 0.9777703257171,
        max_compression_time: 1.505190262472,
        duration: 3.338252755937,
        max_force: 1.03820817965,
    },
    Row {
        x: 2.0,
        n: 1.5,
        e: 0.410719686061,
        max_penetration: 0.7949076199716,
        max_compression_time: 1.33112133457,
        duration: 3.78025803753,
        max_force: 1.10425499427,
    },
    Row {
        x: 0.5,
        n: 1.0,
        e: 0.7484349315974,
        max_penetration: 0.8696431079096,
        max_compression_time: 1.437445184309,
        duration: 3.166389384992,
        max_force: 0.945050174739,
    },
    Row {
        x: 1.0,
        n: 2.2,
        e: 0.59362426004,
        max_penetration: 0.9943173787563,
        max_compression_time: 1.468630256523,
        duration: 3.613729878934,
        max_force: 1.18053806176,
    },
    Row {
        x: 10.0,
        n: 1.5,
        e: 0.09998162475294,
        max_penetration: 0.5146945181523,
        max_compression_time: 1.026446744025,
        duration: 6.458113911715,
        max_force: 1.63632476647,
    },
];

/// Accuracy the issue asks for at the default tolerances.
const TOLERANCE: f64 = 1e-9;

#[test]
fn hunt_crossley_matches_exact_restitution_penetration_times_and_peak_force() {
    let (mass, stiffness, speed) = (2.0, 3e7, 1.7);
    for row in &TABLE {
        let contact = format!(
            "law = \"hunt-crossley\"\ndamping = {}\nstiffness = {stiffness}\nexponent = {}",
            row.x / speed,
            row.n
        );
        let report = on_wall(mass, speed, &contact);
        // Units of docs/references.md: L = (m* v0²/K)^(1/(n+1)), T = L/v0, F0 = K L^n.
        let length = (mass * speed * speed / stiffness).powf(1.0 / (row.n + 1.0));
        let time = length / speed;
        let force = stiffness * length.powf(row.n);
        let c = &report.contact;
        let what = |q: &str| format!("x = {}, n = {}: {q}", row.x, row.n);
        // The table's values have 10 to 13 digits; the looser of their precision and the target applies.
        let digits = |value: f64| (1e-11 / value).max(TOLERANCE);
        assert_close(&what("e (velocity)"), c.restitution_velocity_ratio.unwrap(), row.e, digits(row.e));
        assert_close(&what("e (impulse)"), c.restitution_impulse_ratio.unwrap(), row.e, digits(row.e));
        assert_close(&what("max penetration"), c.max_penetration / length, row.max_penetration, TOLERANCE);
        assert_close(&what("t0"), c.max_compression_time / time, row.max_compression_time, TOLERANCE);
        assert_close(&what("tc"), c.duration.unwrap() / time, row.duration, TOLERANCE);
        assert_close(&what("max force"), c.max_force / force, row.max_force, TOLERANCE);
        assert_close(&what("deformation impulse"), c.deformation_impulse, mass * speed, TOLERANCE);
    }
}

#[test]
fn damped_force_peaks_before_maximum_compression() {
    // docs/references.md: with damping the force peaks before d' = 0 (Hunt–Crossley x = 0.5: while d' = 0.284 v0).
    let text = "[[bodies]]\nradius = 0.01\nmass = 1.0\nvelocity = [1.0, 0, 0]\n[[bodies]]\nradius = inf\nmass = inf\n\
                velocity = [0, 0, 0]\n[contact]\nlaw = \"hunt-crossley\"\ndamping = 0.5\nstiffness = 1e6\n";
    let scene = Scene::parse(text, Path::new("peak.toml")).unwrap();
    let simulation = simulate(&scene, Recording::Steps).unwrap();
    let contact = &simulation.report.contact;
    assert!(contact.max_force_time < contact.max_compression_time);
    // The located peak is a sample of the history: its penetration rate there, in units of v0 = 1 m/s.
    let history = simulation.history.unwrap();
    let peak = history.samples.iter().find(|s| s.time == contact.max_force_time).expect("the peak is recorded");
    assert!((peak.rate - 0.284).abs() < 5e-4, "d' at the peak {}", peak.rate);
    assert!((peak.force - contact.max_force).abs() <= 1e-12 * contact.max_force);
}

/// The effective-e table of docs/laws.md#the-hysteresis-family-and-its-maps: the e each published map actually
/// gives, for nominal e = 0.1 ... 0.99.
const NOMINAL: [f64; 6] = [0.1, 0.3, 0.5, 0.7, 0.9, 0.99];
const EFFECTIVE: [(&str, [f64; 6]); 5] = [
    ("hunt-crossley", [0.515833, 0.581288, 0.662962, 0.768000, 0.909016, 0.990099]),
    ("lankarani-nikravesh", [0.665265, 0.684225, 0.725241, 0.795973, 0.913177, 0.990148]),
    ("gonthier", [0.100990, 0.304225, 0.487741, 0.669581, 0.876435, 0.986776]),
    ("flores", [0.069444, 0.256208, 0.470445, 0.683184, 0.893921, 0.989340]),
    ("hu-guo", [0.074074, 0.270658, 0.487741, 0.697297, 0.899900, 0.990000]),
];

#[test]
fn published_maps_reach_the_effective_restitution_of_the_table() {
    for (law, effective) in EFFECTIVE {
        for (nominal, expected) in NOMINAL.iter().zip(effective) {
            let report = on_wall(0.5, 2.0, &format!("law = \"{law}\"\nrestitution = {nominal}\nstiffness = 1e8"));
            let e = report.contact.restitution_velocity_ratio.unwrap();
            // The table is printed to 6 decimals.
            assert!((e - expected).abs() <= 5e-7 + 1e-12, "{law} at nominal {nominal}: e = {e}, table {expected}");
        }
    }
}

#[test]
fn exact_map_gives_the_nominal_restitution() {
    for nominal in [0.05, 0.3, 0.6, 0.8, 0.95, 0.999] {
        let report =
            on_wall(1.0, 3.0, &format!("law = \"carvalho-martins\"\nrestitution = {nominal}\nstiffness = 1e9"));
        assert_close("carvalho-martins e", report.contact.restitution_velocity_ratio.unwrap(), nominal, TOLERANCE);
    }
}

#[test]
fn bounded_maps_cannot_go_below_their_floor() {
    // docs/references.md: Lankarani–Nikravesh and Lee–Wang never go below 0.662962, Hunt–Crossley and
    // Herbert–McWhannell never below 0.487741, whatever nominal e is asked (here the lowest, 0).
    for (law, floor) in [
        ("lankarani-nikravesh", 0.662962),
        ("lee-wang", 0.662962),
        ("hunt-crossley", 0.487741),
        ("herbert-mcwhannell", 0.487741),
    ] {
        let report = on_wall(1.0, 1.0, &format!("law = \"{law}\"\nrestitution = 0\nstiffness = 1e7"));
        let e = report.contact.restitution_velocity_ratio.unwrap();
        assert!((e - floor).abs() < 5e-7, "{law} at e = 0 gives {e}, floor {floor}");
    }
}
