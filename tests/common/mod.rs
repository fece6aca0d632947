//! Helpers shared by the tests: build a scene from TOML text and simulate it (the physics tests); `binary` runs
//! the real `impact` binary in a scratch folder (the command-line tests).
#![allow(dead_code)]

pub mod binary;
pub mod edge_ode;
pub mod oblique;
pub mod random;
pub mod rocking;
pub mod slider;
pub mod vectors;

use impact::impact::simulate;
use impact::report::Report;
use impact::scene::Scene;
use std::path::Path;

/// Simulates a scene given as TOML text.
pub fn run(toml: &str) -> Report {
    let scene = Scene::parse(toml, Path::new("test.toml")).unwrap_or_else(|e| panic!("bad test scene: {e}\n{toml}"));
    simulate(&scene, impact::history::Recording::Off).expect("simulation").report
}

/// A sphere of mass `mass` (kg) at `speed` (m/s, along x) against an immovable wall, with the given `[contact]`
/// lines (law, damping, stiffness...). Its radius, 1 m, enters no force of a numeric stiffness on a wall; it keeps
/// the softest test contacts' dents (centimetres) far below the sphere's size, as the scene rules require.
pub fn on_wall(mass: f64, speed: f64, contact: &str) -> Report {
    run(&format!(
        "[[bodies]]\nradius = 1.0\nmass = {mass:?}\nvelocity = [{speed:?}, 0.0, 0.0]\n\n\
         [[bodies]]\nradius = inf\nmass = inf\nvelocity = [0.0, 0.0, 0.0]\n\n[contact]\n{contact}\n"
    ))
}

/// |a - b| / |b|.
pub fn relative(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

/// Asserts a relative agreement, naming the quantity.
#[track_caller]
pub fn assert_close(what: &str, simulated: f64, exact: f64, tolerance: f64) {
    let error = relative(simulated, exact);
    assert!(
        error <= tolerance,
        "{what}: simulated {simulated:.15e}, exact {exact:.15e}, relative error {error:.2e} > {tolerance:.0e}"
    );
}

/// The exact e of the Hunt–Crossley family at x = alpha v0: the root in (0, 1/x) of x (1 + e) = ln((1 + x)/(1 - e x))
/// (docs/references.md#the-hunt-crossley-family), by bisection.
pub fn hunt_crossley_e(x: f64) -> f64 {
    let residual = |e: f64| x * (1.0 + e) - ((1.0 + x) / (1.0 - e * x)).ln();
    let (mut low, mut high) = (1e-12, (1.0 / x).min(1.0) - 1e-15);
    for _ in 0..200 {
        let middle = 0.5 * (low + high);
        if residual(middle) > 0.0 { low = middle } else { high = middle }
    }
    0.5 * (low + high)
}

/// A random symmetric positive definite inertia tensor of size `scale` (kg m²): principal moments obeying the
/// triangle inequality (each at most the sum of the other two), turned by a random rotation.
pub fn random_inertia(draw: &mut impact::draw::Draw, scale: f64) -> nalgebra::Matrix3<f64> {
    use nalgebra::{Matrix3, Rotation3, Unit, Vector3};
    let (a, b) = (draw.log(0.1, 1.0), draw.log(0.1, 1.0));
    let c = draw.uniform((a - b).abs().max(1e-3), a + b);
    let turn = Rotation3::from_axis_angle(&Unit::new_normalize(draw.direction()), draw.uniform(0.0, 3.0));
    let principal = Matrix3::from_diagonal(&Vector3::new(a, b, c)) * scale;
    turn.matrix() * principal * turn.matrix().transpose()
}

/// A world scene from TOML text (a test's scene: any error is the test's).
pub fn world_scene(text: &str) -> impact::scene::WorldScene {
    match impact::setup::parse_any(text, Path::new("world.toml")).unwrap_or_else(|e| panic!("{e}\n{text}")) {
        impact::scene::Parsed::World(world) => *world,
        impact::scene::Parsed::Impact(_) => panic!("not a world scene:\n{text}"),
    }
}

/// Runs a world scene given as TOML text and returns its report as JSON (fields read by name, as users read them).
pub fn world_report_json(text: &str) -> serde_json::Value {
    let report = impact::world_run::simulate(&world_scene(text)).unwrap_or_else(|e| panic!("{e}\n{text}")).report;
    serde_json::to_value(&report).expect("the world report serialises")
}

/// A vector as a TOML array.
pub fn toml_vector(v: &nalgebra::Vector3<f64>) -> String {
    format!("[{:?}, {:?}, {:?}]", v.x, v.y, v.z)
}

/// A tensor as a TOML array of rows, symmetrised.
pub fn toml_tensor(m: &nalgebra::Matrix3<f64>) -> String {
    let m = (m + m.transpose()) * 0.5;
    let row = |i: usize| format!("[{:?}, {:?}, {:?}]", m[(i, 0)], m[(i, 1)], m[(i, 2)]);
    format!("[{}, {}, {}]", row(0), row(1), row(2))
}

/// Models whose whole run is too long for the suite's every-model checks, with the text that replaces their end time
/// there: the settling pile (2 s of scene time, about 1,500 contacts: some 20 s in a release build, minutes in the
/// test profile) runs its first 0.3 s, its balls' first bounces and collisions.
pub const LONG_MODELS: [(&str, &str, &str); 1] = [("settling-pile.toml", "end_time = 2.0", "end_time = 0.3")];

/// A model's text as the every-model checks run it (`file_name` its name in `models/`): shortened if it is one of
/// [`LONG_MODELS`] (whose text must hold the end time it names).
pub fn model_as_tested(file_name: &str, text: &str) -> String {
    match LONG_MODELS.iter().find(|(name, _, _)| *name == file_name) {
        Some((_, end, shorter)) => {
            assert!(text.contains(end), "models/{file_name} no longer has `{end}`: update LONG_MODELS");
            text.replace(end, shorter)
        }
        None => text.to_string(),
    }
}
