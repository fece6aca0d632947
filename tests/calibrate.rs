//! `impact calibrate` through the real binary: the calibrated damping reproduces the target e when the scene is
//! simulated with it (`impact run --json`), the exact relations and closed forms it rests on hold when checked by
//! hand, the published maps give the effective e of docs/laws.md, and bad input is a clear error with exit status 2.
//!
//! Every expected number comes from docs/references.md, docs/laws.md or a formula written out here, never from an
//! earlier run.

mod common;

use common::binary::{Scratch, describe, impact};
use serde_json::Value;
use std::f64::consts::PI;

// ---------------------------------------------------------------------------------------------------------------
// Running the binary

/// `impact calibrate ARGS --json`, which must succeed.
fn calibrate(scratch: &Scratch, args: &[&str]) -> Value {
    let mut all = vec!["calibrate", "--json"];
    all.extend_from_slice(args);
    let output = impact(scratch.path(), &all);
    assert!(output.status.success(), "impact {all:?} failed\n{}", describe(&output));
    serde_json::from_slice(&output.stdout).unwrap_or_else(|e| panic!("bad JSON ({e})\n{}", describe(&output)))
}

/// The simulated velocity ratio of `impact run --json` on a scene given as text.
fn simulated_e(scratch: &Scratch, name: &str, text: &str) -> f64 {
    let path = scratch.scene(name, text);
    let output = impact(scratch.path(), &["run", "--json", &path]);
    assert!(output.status.success(), "impact run {name} failed\n{}", describe(&output));
    let report: Value = serde_json::from_slice(&output.stdout).expect("JSON report");
    report["contact"]["restitution_velocity_ratio"].as_f64().expect("the bodies separate")
}

/// `impact calibrate ARGS` must fail with exit status 2, a message on stderr and no panic; returns the message.
fn refused(scratch: &Scratch, args: &[&str]) -> String {
    let mut all = vec!["calibrate"];
    all.extend_from_slice(args);
    let output = impact(scratch.path(), &all);
    let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
    assert_eq!(output.status.code(), Some(2), "impact {all:?} should exit with 2\n{}", describe(&output));
    assert!(!stderr.contains("panicked") && !stderr.trim().is_empty(), "impact {all:?}: {stderr}");
    assert!(output.stdout.is_empty(), "impact {all:?} printed a result\n{}", describe(&output));
    stderr
}

fn number(value: &Value, key: &str) -> f64 {
    value[key].as_f64().unwrap_or_else(|| panic!("`{key}` is not a number in {value:#}"))
}

// ---------------------------------------------------------------------------------------------------------------
// Scenes (the models/ ones, rewritten here so that the tests do not depend on those files)

/// Two steel balls (10 mm, Hertz stiffness) with velocities +v1 and -v2 along x.
fn steel_pair(v1: f64, v2: f64, contact: &str) -> String {
    let ball = |v: f64| {
        format!(
            "[[bodies]]\nradius = 0.01\ndensity = 7850\nvelocity = [{v}, 0.0, 0.0]\nyoung = 2.1e11\npoisson = 0.3\n\n"
        )
    };
    format!("{}{}[contact]\n{contact}\n", ball(v1), ball(-v2))
}

/// A 60 g ball on a rigid floor at 3 m/s, Kelvin–Voigt with k = 2e4 N/m.
fn rubber_ball(contact: &str) -> String {
    format!(
        "[[bodies]]\nradius = 0.03\nmass = 0.06\nvelocity = [0.0, -3.0, 0.0]\n\n\
         [[bodies]]\nradius = inf\nmass = inf\nvelocity = [0.0, 0.0, 0.0]\n\n\
         [contact]\nlaw = \"kelvin-voigt\"\nstiffness = 2.0e4\nnormal = [0.0, -1.0, 0.0]\n{contact}\n"
    )
}

/// An alumina sphere (2.5 mm) on a rigid wall at 3.9 m/s (Chung & Ooi test 3), Tsuji damping.
fn alumina_on_wall(contact: &str) -> String {
    format!(
        "[[bodies]]\nradius = 0.0025\ndensity = 4000\nvelocity = [3.9, 0.0, 0.0]\nyoung = 3.8e11\npoisson = 0.23\n\n\
         [[bodies]]\nradius = inf\nmass = inf\nvelocity = [0.0, 0.0, 0.0]\nyoung = inf\n\n\
         [contact]\nlaw = \"tsuji\"\n{contact}\n"
    )
}

/// Two ice-like viscoelastic spheres (5 mm) with velocities +v and -v, Brilliantov's law.
fn ice_pair(v: f64, contact: &str) -> String {
    let ball = |v: f64| {
        format!(
            "[[bodies]]\nradius = 0.005\ndensity = 917\nvelocity = [{v}, 0.0, 0.0]\nyoung = 9.0e9\npoisson = 0.33\n\n"
        )
    };
    format!("{}{}[contact]\nlaw = \"brilliantov\"\n{contact}\n", ball(v), ball(-v))
}

// ---------------------------------------------------------------------------------------------------------------
// Hand calculations

/// Residual of docs/references.md's exact relation of the hysteresis family, x (1 + e) = ln((1 + x)/(1 - e x)).
fn hysteresis_residual(x: f64, e: f64) -> f64 {
    x * (1.0 + e) - ((1.0 + x) / (1.0 - e * x)).ln()
}

/// Kelvin–Voigt damping ratio for e with separation at d = 0 (docs/references.md): -ln e / sqrt(pi² + ln² e).
fn zeta_for(e: f64) -> f64 {
    -e.ln() / (PI * PI + e.ln() * e.ln()).sqrt()
}

/// Effective mass of two equal steel balls of radius 0.01 m: m/2, m = 7850 (4/3) pi r³.
fn steel_pair_effective_mass() -> f64 {
    0.5 * 7850.0 * 4.0 / 3.0 * PI * 1e-6
}

// ---------------------------------------------------------------------------------------------------------------
// The calibrated damping reproduces the target

/// Calibrates on `scene` (text with `placeholder` standing for the damping lines), then runs the scene with the
/// calibrated `damping` and checks the simulated e against the target.
fn reproduces(scratch: &Scratch, name: &str, scene: impl Fn(&str) -> String, law: &str, target: f64, extra: &[&str]) {
    let path = scratch.scene(&format!("{name}.toml"), &scene("restitution = 0.9"));
    let target_text = target.to_string();
    let mut args = vec![path.as_str(), "--law", law, "--restitution", &target_text];
    args.extend_from_slice(extra);
    let result = calibrate(scratch, &args);
    let damping = number(&result, "damping");
    let verified = number(&result, "restitution_simulated");
    assert!((verified - target).abs() < 1e-9, "{name}: calibrate's own check gives e = {verified}");
    let e = simulated_e(scratch, &format!("{name}-calibrated.toml"), &scene(&format!("damping = {damping}")));
    assert!((e - target).abs() < 1e-9, "{name}: damping {damping} gives e = {e}, target {target}");
}

#[test]
fn hysteresis_calibration_reproduces_the_target_by_simulation() {
    let scratch = Scratch::new("hysteresis");
    let pair = |damping: &str| steel_pair(1.0, 1.0, &format!("law = \"hunt-crossley\"\n{damping}"));
    for (law, target) in [("hunt-crossley", 0.8), ("lankarani-nikravesh", 0.3), ("gonthier", 0.05)] {
        let lines = |damping: &str| steel_pair(1.0, 1.0, &format!("law = \"{law}\"\n{damping}"));
        reproduces(&scratch, law, lines, law, target, &[]);
    }
    // --law replaces the scene's law.
    reproduces(&scratch, "override", pair, "flores", 0.6, &[]);
}

#[test]
fn kelvin_voigt_calibration_reproduces_the_target_for_both_separations() {
    let scratch = Scratch::new("kelvin-voigt");
    for separation in ["penetration", "force"] {
        let scene = |damping: &str| rubber_ball(&format!("separation = \"{separation}\"\n{damping}"));
        for target in [0.6, 0.2] {
            reproduces(&scratch, &format!("kv-{separation}-{target}"), scene, "kelvin-voigt", target, &[]);
        }
    }
}

#[test]
fn tsuji_calibration_reproduces_the_target_for_both_separations() {
    let scratch = Scratch::new("tsuji");
    for separation in ["penetration", "force"] {
        let scene = |damping: &str| alumina_on_wall(&format!("separation = \"{separation}\"\n{damping}"));
        for target in [0.5, 0.9] {
            reproduces(&scratch, &format!("tsuji-{separation}-{target}"), scene, "tsuji", target, &[]);
        }
    }
}

#[test]
fn brilliantov_calibration_reproduces_the_target_by_simulation() {
    let scratch = Scratch::new("brilliantov");
    for separation in ["penetration", "force"] {
        let scene = |damping: &str| ice_pair(0.5, &format!("separation = \"{separation}\"\n{damping}"));
        let path = scratch.scene(&format!("ice-{separation}.toml"), &scene("damping = 1e-6"));
        let result = calibrate(&scratch, &[&path, "--restitution", "0.7"]);
        assert_eq!(result["method"], "root-find on simulation");
        assert!(number(&result, "simulations") >= 2.0);
        assert!(result["published_map"].is_null(), "brilliantov has no published map");
        let damping = number(&result, "damping");
        let e = simulated_e(
            &scratch,
            &format!("ice-{separation}-calibrated.toml"),
            &scene(&format!("damping = {damping}")),
        );
        assert!((e - 0.7).abs() < 1e-9, "{separation}: A = {damping} gives e = {e}");
    }
}

#[test]
fn approach_speed_override_scales_the_scene_velocities() {
    // The ice pair at ±0.5 m/s asked for v0 = 3 m/s is the pair at ±1.5 m/s.
    let scratch = Scratch::new("speed");
    let path = scratch.scene("ice.toml", &ice_pair(0.5, "damping = 1e-6"));
    let result = calibrate(&scratch, &[&path, "--restitution", "0.6", "--approach-speed", "3"]);
    assert_eq!(number(&result, "approach_speed"), 3.0);
    let damping = number(&result, "damping");
    let e = simulated_e(&scratch, "ice-fast.toml", &ice_pair(1.5, &format!("damping = {damping}")));
    assert!((e - 0.6).abs() < 1e-9, "A = {damping} at ±1.5 m/s gives e = {e}");

    // Hysteresis: alpha = chi / v0 with the overriding v0, whatever the scene's own speed.
    let path = scratch.scene("steel.toml", &steel_pair(1.0, 1.0, "law = \"hunt-crossley\"\nrestitution = 0.8"));
    let result = calibrate(&scratch, &[&path, "--restitution", "0.5", "--approach-speed", "5"]);
    let x = number(&result, "damping") * 5.0;
    assert!(hysteresis_residual(x, 0.5).abs() < 1e-12, "x = {x}");
    let e = simulated_e(
        &scratch,
        "steel-fast.toml",
        &steel_pair(2.5, 2.5, &format!("law = \"hunt-crossley\"\ndamping = {}", x / 5.0)),
    );
    assert!((e - 0.5).abs() < 1e-9, "e = {e}");
}

// ---------------------------------------------------------------------------------------------------------------
// Exact relations and closed forms, checked by hand

#[test]
fn hysteresis_damping_is_the_exact_chi_over_the_approach_speed() {
    // The residual is checked where it is well conditioned (1 - e x not small, i.e. e not near 0).
    let scratch = Scratch::new("exact-chi");
    for (law, e, speed) in [("hunt-crossley", 0.8, "1"), ("carvalho-martins", 0.3, "2.5"), ("hu-guo", 0.4, "0.4")] {
        let result = calibrate(&scratch, &["--law", law, "--restitution", &e.to_string(), "--approach-speed", speed]);
        assert_eq!(result["method"], "exact relation");
        let v0: f64 = speed.parse().unwrap();
        let x = number(&result, "damping") * v0;
        assert!(x > 0.0 && e * x < 1.0, "{law}: x = {x} outside (0, 1/e)");
        assert!(hysteresis_residual(x, e).abs() < 1e-12, "{law}: residual {}", hysteresis_residual(x, e));
        assert!((number(&result["dimensionless"], "value") - x).abs() <= 1e-14 * x);
        assert!((number(&result, "restitution_simulated") - e).abs() < 1e-9);
    }
    // docs/references.md's exact values read backwards: e(x = 0.5) = 0.7484349315974, e(x = 2) = 0.410719686061.
    for (x, e) in [(0.5, "0.7484349315974"), (2.0, "0.410719686061")] {
        let result = calibrate(&scratch, &["--law", "lee-wang", "--restitution", e]);
        let got = number(&result, "damping");
        assert!((got - x).abs() < 1e-10 * x, "e = {e}: alpha = {got}, expected {x} s/m at v0 = 1 m/s");
    }
}

#[test]
fn kelvin_voigt_without_a_scene_gives_zeta_but_not_c() {
    let scratch = Scratch::new("kv-no-scene");
    let result = calibrate(&scratch, &["--law", "kelvin-voigt", "--restitution", "0.5"]);
    assert!(result["damping"].is_null(), "c needs k and m*: {result:#}");
    assert_eq!(result["damping_units"], "c in N s/m");
    let zeta = number(&result["dimensionless"], "value");
    assert!((zeta - zeta_for(0.5)).abs() < 1e-15, "zeta = {zeta}");
    assert!((number(&result, "restitution_simulated") - 0.5).abs() < 1e-9);
    assert!(result["published_map"]["damping"].is_null());
}

#[test]
fn kelvin_voigt_with_a_scene_gives_c_from_k_and_the_mass() {
    // c = 2 zeta sqrt(k m*), k = 2e4 N/m, m* = 0.06 kg (a ball on a wall).
    let scratch = Scratch::new("kv-scene");
    let path = scratch.scene("ball.toml", &rubber_ball("restitution = 0.6"));
    let result = calibrate(&scratch, &[&path, "--restitution", "0.6"]);
    let expected = 2.0 * zeta_for(0.6) * (2.0e4_f64 * 0.06).sqrt();
    assert!((number(&result, "damping") - expected).abs() < 1e-13 * expected);
    assert_eq!(result["method"], "exact relation");
}

#[test]
fn force_separation_calibrates_on_the_closed_form() {
    // docs/references.md (Schwager & Pöschel 2007): with separation at F = 0, zeta = 0.1 gives e = 0.7440793977 and
    // zeta = 0.3 gives 0.4509754529; critical damping gives exp(-2). Tsuji maps onto the same oscillator with
    // zeta = a / sqrt(5); its overdamped a = 3 gives e = 5^(-3/2) (Omega = 2/sqrt(5): (zeta + Omega)/(zeta - Omega)
    // = 5, zeta/Omega = 3/2).
    let scratch = Scratch::new("closed-form");
    let sqrt5 = 5f64.sqrt();
    let cases = [
        ("kelvin-voigt", "0.7440793977", 0.1, 2e-10),
        ("kelvin-voigt", "0.4509754529", 0.3, 2e-10),
        ("kelvin-voigt", &(-2f64).exp().to_string(), 1.0, 1e-12),
        ("tsuji", "0.7440793977", 0.1, 2e-10),
        ("tsuji", &5f64.powf(-1.5).to_string(), 3.0 / sqrt5, 1e-12),
    ];
    for (law, e, zeta, tolerance) in cases {
        let result = calibrate(&scratch, &["--law", law, "--restitution", e, "--separation", "force"]);
        assert_eq!(result["method"], "closed form", "{law} at e = {e}");
        let got = number(&result["dimensionless"], "value");
        assert!((got - zeta).abs() < tolerance, "{law} at e = {e}: zeta = {got}, expected {zeta}");
        if law == "tsuji" {
            assert!((number(&result, "damping") - sqrt5 * zeta).abs() < 3.0 * tolerance);
        }
        assert!((number(&result, "restitution_simulated") - e.parse::<f64>().unwrap()).abs() < 1e-9);
    }
}

#[test]
fn brilliantov_root_find_finds_the_exact_b() {
    // docs/references.md, exact (ODE, d = 0): b = 0.1 -> 0.8921475873, b = 0.5 -> 0.5738246287, where
    // b = (3/2) A (K/m*)^(2/5) v0^(1/5). K = (4/3) E* sqrt(R*) for the ice pair.
    let scratch = Scratch::new("brilliantov-b");
    let path = scratch.scene("ice.toml", &ice_pair(0.5, "damping = 1e-6"));
    let modulus = 9.0e9 / (2.0 * (1.0 - 0.33 * 0.33));
    let stiffness = 4.0 / 3.0 * modulus * 0.0025_f64.sqrt();
    let effective_mass = 0.5 * 917.0 * 4.0 / 3.0 * PI * 0.005_f64.powi(3);
    for (b, e) in [(0.1, "0.8921475873"), (0.5, "0.5738246287")] {
        let result = calibrate(&scratch, &[&path, "--restitution", e]);
        let damping = number(&result, "damping");
        let got = 1.5 * damping * (stiffness / effective_mass).powf(0.4);
        assert!((got - b).abs() < 1e-8 * b, "e = {e}: b = {got}, expected {b}");
        assert!((number(&result["dimensionless"], "value") - got).abs() < 1e-12 * b);
    }
}

#[test]
fn unit_restitution_needs_no_damping() {
    let scratch = Scratch::new("elastic");
    for law in ["hunt-crossley", "gonthier", "carvalho-martins", "kelvin-voigt", "tsuji", "brilliantov"] {
        let result = calibrate(&scratch, &["--law", law, "--restitution", "1"]);
        let damping = &result["damping"];
        assert!(damping.is_null() && law == "kelvin-voigt" || damping.as_f64() == Some(0.0), "{law}: {damping}");
        assert_eq!(number(&result["dimensionless"], "value"), 0.0, "{law}");
        assert!((number(&result, "restitution_simulated") - 1.0).abs() < 1e-9, "{law}");
    }
}

// ---------------------------------------------------------------------------------------------------------------
// The published maps

#[test]
fn published_maps_give_the_effective_e_of_the_exact_relation() {
    // The effective e of each published map (6 decimals, the table of
    // docs/laws.md#the-hysteresis-family-and-its-maps), and the Tsuji F = 0 value (docs/references.md#tsuji).
    let scratch = Scratch::new("published");
    let cases = [
        ("lankarani-nikravesh", "0.5", "penetration", 0.725241),
        ("lankarani-nikravesh", "0.1", "penetration", 0.665265),
        ("gonthier", "0.3", "penetration", 0.304225),
        ("hunt-crossley", "0.7", "penetration", 0.768000),
        ("flores", "0.1", "penetration", 0.069444),
        ("hu-guo", "0.9", "penetration", 0.899900),
        ("tsuji", "0.5", "force", 0.550283),
        ("tsuji", "0.5", "penetration", 0.5),
    ];
    for (law, e, separation, effective) in cases {
        let result = calibrate(&scratch, &["--law", law, "--restitution", e, "--separation", separation]);
        let map = &result["published_map"];
        let got = number(map, "restitution");
        assert!((got - effective).abs() <= 5e-7, "{law} asked for {e}: the map gives {got}, docs/laws.md {effective}");
        // The map's damping is the law's formula, written out here.
        let nominal: f64 = e.parse().unwrap();
        let expected = match law {
            "lankarani-nikravesh" => 0.75 * (1.0 - nominal * nominal),
            "gonthier" => (1.0 - nominal * nominal) / nominal,
            "hunt-crossley" => 1.5 * (1.0 - nominal),
            "flores" => 8.0 * (1.0 - nominal) / (5.0 * nominal),
            "hu-guo" => 1.5 * (1.0 - nominal) / nominal,
            _ => 5f64.sqrt() * zeta_for(nominal),
        };
        assert!((number(map, "damping") - expected).abs() < 1e-14, "{law}: map damping {}", map["damping"]);
    }
}

#[test]
fn published_kelvin_voigt_map_with_force_separation_matches_schwager_poschel() {
    // Asked for e = exp(-pi 0.1 / sqrt(0.99)), the map gives zeta = 0.1 exactly, which separating at F = 0 yields
    // 0.7440793977 (docs/references.md); c = 2 zeta sqrt(k m*) for the steel-free rubber ball.
    let scratch = Scratch::new("published-kv");
    let path = scratch.scene("ball.toml", &rubber_ball("separation = \"force\"\nrestitution = 0.5"));
    let e = (-PI * 0.1 / 0.99_f64.sqrt()).exp();
    let result = calibrate(&scratch, &[&path, "--restitution", &e.to_string()]);
    let map = &result["published_map"];
    assert!((number(map, "dimensionless") - 0.1).abs() < 1e-14);
    assert!((number(map, "damping") - 0.2 * (2.0e4_f64 * 0.06).sqrt()).abs() < 1e-12);
    assert!((number(map, "restitution") - 0.7440793977).abs() < 5e-11);
}

// ---------------------------------------------------------------------------------------------------------------
// The outputs

#[test]
fn json_has_the_documented_keys() {
    let scratch = Scratch::new("keys");
    let path = scratch.scene("steel.toml", &steel_pair(1.0, 1.0, "law = \"hunt-crossley\"\nrestitution = 0.8"));
    let result = calibrate(&scratch, &[&path, "--law", "lankarani-nikravesh", "--restitution", "0.5"]);
    for key in [
        "law",
        "restitution_target",
        "damping",
        "damping_units",
        "dimensionless",
        "method",
        "separation",
        "approach_speed",
        "scene",
        "iterations",
        "simulations",
        "restitution_simulated",
        "published_map",
        "notes",
    ] {
        assert!(result.get(key).is_some(), "missing `{key}` in {result:#}");
    }
    assert_eq!(result["law"], "lankarani-nikravesh");
    assert_eq!(result["restitution_target"], 0.5);
    assert_eq!(result["damping_units"], "alpha in s/m");
    assert_eq!(number(&result, "approach_speed"), 2.0);
    let mass = number(&result["scene"], "effective_mass");
    assert!((mass - steel_pair_effective_mass()).abs() < 1e-15, "m* = {mass}");
    for key in ["map", "damping", "dimensionless", "restitution"] {
        assert!(result["published_map"].get(key).is_some(), "missing published_map.{key}");
    }
}

#[test]
fn readable_summary_names_the_damping_and_the_method() {
    let scratch = Scratch::new("readable");
    let output = impact(scratch.path(), &["calibrate", "--law", "hunt-crossley", "--restitution", "0.5"]);
    assert!(output.status.success(), "{}", describe(&output));
    let text = String::from_utf8_lossy(&output.stdout);
    for words in ["hunt-crossley", "alpha in s/m", "exact relation", "simulated e", "published map", "1 m/s"] {
        assert!(text.contains(words), "the summary lacks `{words}`:\n{text}");
    }
}

// ---------------------------------------------------------------------------------------------------------------
// Bad input

#[test]
fn bad_input_is_a_clear_error_with_status_2() {
    let scratch = Scratch::new("bad");
    let hertz_scene = scratch.scene("steel.toml", &steel_pair(1.0, 1.0, "law = \"hunt-crossley\"\nrestitution = 0.8"));
    let cases: [(&[&str], &str); 11] = [
        (&["--law", "stiction", "--restitution", "0.5"], "unknown law `stiction`"),
        (&["--law", "hertz", "--restitution", "0.5"], "hertz"),
        (&["--law", "gonthier", "--restitution", "0"], "undefined at e = 0"),
        (&["--law", "hunt-crossley", "--restitution", "0"], "e = 0"),
        (&["--law", "tsuji", "--restitution", "1.2"], "(0, 1]"),
        (&["--law", "tsuji", "--restitution", "-0.5"], "(0, 1]"),
        (&["--law", "brilliantov", "--restitution", "0.5"], "needs a scene"),
        (&["--law", "tsuji", "--restitution", "0.5", "--approach-speed", "0"], "approach speed"),
        (&["--law", "tsuji", "--restitution", "0.5", "--separation", "sideways"], "--separation"),
        (&[&hertz_scene, "--law", "kelvin-voigt", "--restitution", "0.5"], "numeric `stiffness`"),
        (&["--restitution", "0.5"], "--law"),
    ];
    for (args, words) in cases {
        let message = refused(&scratch, args);
        assert!(message.contains(words), "impact calibrate {args:?}: `{words}` missing from: {message}");
    }
    let missing = refused(&scratch, &["missing.toml", "--law", "tsuji", "--restitution", "0.5"]);
    assert!(missing.contains("missing.toml"), "{missing}");
    refused(&scratch, &["--law", "tsuji"]);
}
