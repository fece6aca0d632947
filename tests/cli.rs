//! The `impact` command as users and scripts see it (README.md#calling-the-program and docs/report.md), through the
//! real binary: the JSON report's keys and types, the readable report, `models`, `--help`, the demonstration and
//! bad arguments. Physics is only touched where a closed form makes it free; the physics tests live elsewhere.

mod common;

use common::binary::{Scratch, assert_success, describe, impact, stdout};
use serde_json::Value;
use std::fs;
use std::path::Path;

// ---------------------------------------------------------------------------------------------------------------
// Running the binary

/// `impact run SCENE --json` on `text`, parsed.
#[track_caller]
fn run_json(test: &str, text: &str) -> Value {
    let scratch = Scratch::new(test);
    let scene = scratch.scene(&format!("{test}.toml"), text);
    let output = impact(scratch.path(), &["run", &scene, "--json"]);
    assert_success(&output);
    serde_json::from_slice(&output.stdout).unwrap_or_else(|e| panic!("stdout is not JSON: {e}\n{}", describe(&output)))
}

/// Whether `word` appears in `text` as a whole word (law names contain `-`).
fn has_word(text: &str, word: &str) -> bool {
    let boundary = |c: Option<char>| c.is_none_or(|c| !(c.is_alphanumeric() || c == '_' || c == '-'));
    text.match_indices(word)
        .any(|(i, _)| boundary(text[..i].chars().next_back()) && boundary(text[i + word.len()..].chars().next()))
}

// ---------------------------------------------------------------------------------------------------------------
// The JSON report's shape (docs/report.md: every key of `impact run --json`)

/// What a report value must be.
#[derive(Debug, Clone, Copy)]
enum Kind {
    Text,
    Number,
    /// A non-negative integer (solver counters).
    Count,
    Bool,
    /// `[x, y, z]`, numbers.
    Vector,
    /// `[[x, y, z], [x, y, z]]`: velocities of both bodies.
    VectorPair,
    Null,
}

/// Every key of the JSON report of docs/report.md as a JSON pointer with its kind: `separated` says whether the
/// bodies parted (otherwise the keys listed in docs/report.md#conventions are null), `nominal` whether a nominal
/// `restitution` (or `hertz`) was given (otherwise `restitution_nominal` and `instantaneous_nominal` are null).
fn documented_keys(separated: bool, nominal: bool) -> Vec<(String, Kind)> {
    use Kind::*;
    let after = |kind: Kind| if separated { kind } else { Null };
    let mut keys: Vec<(String, Kind)> = vec![
        ("/title".into(), Text),
        ("/law/name".into(), Text),
        ("/law/stiffness".into(), Number),
        ("/law/exponent".into(), Number),
        ("/law/damping".into(), Number),
        ("/law/restitution_nominal".into(), if nominal { Number } else { Null }),
        ("/law/separation".into(), Text),
        ("/effective_mass".into(), Number),
        ("/approach_speed".into(), Number),
    ];
    let contact = [
        ("start_time", Number),
        ("max_compression_time", Number),
        ("end_time", after(Number)),
        ("duration", after(Number)),
        ("max_penetration", Number),
        ("max_force", Number),
        ("max_force_time", Number),
        ("common_normal_velocity", Number),
        ("deformation_impulse", Number),
        ("restitution_impulse", after(Number)),
        ("restitution_impulse_ratio", after(Number)),
        ("restitution_velocity_ratio", after(Number)),
        ("restitution_energy", after(Number)),
        ("separated", Bool),
    ];
    keys.extend(contact.iter().map(|(key, kind)| (format!("/contact/{key}"), *kind)));
    for body in 0..2 {
        let fields = [
            ("name", Text),
            ("velocity_before", Vector),
            ("velocity_after", after(Vector)),
            ("velocity_at_max_compression", Vector),
            ("angular_velocity_after", after(Vector)),
        ];
        keys.extend(fields.iter().map(|(key, kind)| (format!("/bodies/{body}/{key}"), *kind)));
    }
    let energy = [("kinetic_before", Number), ("kinetic_after", after(Number)), ("dissipated", after(Number))];
    keys.extend(energy.iter().map(|(key, kind)| (format!("/energy/{key}"), *kind)));
    let instantaneous = |table: &str, present: bool, simulated: Kind| -> Vec<(String, Kind)> {
        if !present {
            return vec![(format!("/{table}"), Null)];
        }
        [
            ("restitution", Number),
            ("common_normal_velocity", Number),
            ("velocity_after", VectorPair),
            ("energy_lost", Number),
            ("max_velocity_difference", simulated),
        ]
        .iter()
        .map(|(key, kind)| (format!("/{table}/{key}"), *kind))
        .collect()
    };
    keys.extend(instantaneous("instantaneous", separated, Number));
    keys.extend(instantaneous("instantaneous_nominal", nominal, after(Number)));
    let solver = [
        ("method", Text),
        ("rtol", Number),
        ("atol", Number),
        ("steps", Count),
        ("rejected_steps", Count),
        ("force_evaluations", Count),
        ("wall_time_s", Number),
    ];
    keys.extend(solver.iter().map(|(key, kind)| (format!("/solver/{key}"), *kind)));
    keys
}

fn is_vector(value: &Value) -> bool {
    value.as_array().is_some_and(|items| items.len() == 3 && items.iter().all(Value::is_number))
}

fn is_kind(value: &Value, kind: Kind) -> bool {
    match kind {
        Kind::Text => value.is_string(),
        Kind::Number => value.is_number(),
        Kind::Count => value.is_u64(),
        Kind::Bool => value.is_boolean(),
        Kind::Vector => is_vector(value),
        Kind::VectorPair => value.as_array().is_some_and(|pair| pair.len() == 2 && pair.iter().all(is_vector)),
        Kind::Null => value.is_null(),
    }
}

/// Asserts that `report` has every key of docs/report.md with its kind; more keys are allowed (additions).
#[track_caller]
fn assert_documented_keys(report: &Value, separated: bool, nominal: bool) {
    let bodies = report.pointer("/bodies").and_then(Value::as_array).map(Vec::len);
    assert_eq!(bodies, Some(2), "`bodies` must list the two bodies:\n{report:#}");
    let wrong: Vec<String> = documented_keys(separated, nominal)
        .into_iter()
        .filter_map(|(pointer, kind)| match report.pointer(&pointer) {
            None => Some(format!("{pointer}: missing, expected {kind:?}")),
            Some(value) if !is_kind(value, kind) => Some(format!("{pointer}: {value}, expected {kind:?}")),
            Some(_) => None,
        })
        .collect();
    assert!(
        wrong.is_empty(),
        "keys of docs/report.md missing or of the wrong kind:\n  {}\n{report:#}",
        wrong.join("\n  ")
    );
}

/// The number at `pointer`.
#[track_caller]
fn number(report: &Value, pointer: &str) -> f64 {
    report.pointer(pointer).and_then(Value::as_f64).unwrap_or_else(|| panic!("{pointer} is not a number:\n{report:#}"))
}

#[track_caller]
fn assert_close(what: &str, value: f64, expected: f64, tolerance: f64) {
    let error = ((value - expected) / expected).abs();
    assert!(
        error <= tolerance,
        "{what}: {value:.15e}, expected {expected:.15e}, relative error {error:.1e} > {tolerance:.0e}"
    );
}

// ---------------------------------------------------------------------------------------------------------------
// `impact run SCENE --json`

/// Two steel balls placed 0.1 m apart (centres), closing at 2 m/s, Hunt–Crossley damping from e = 0.8.
const PLACED_BALLS: &str = r#"title = "two steel balls"

[[bodies]]
name = "left ball"
radius = 0.01
mass = 0.0329
velocity = [1.0, 0.0, 0.0]
position = [0.0, 0.0, 0.0]
young = 2.1e11
poisson = 0.3

[[bodies]]
name = "right ball"
radius = 0.01
mass = 0.0329
velocity = [-1.0, 0.0, 0.0]
position = [0.1, 0.0, 0.0]
young = 2.1e11
poisson = 0.3

[contact]
law = "hunt-crossley"
restitution = 0.8
"#;

#[test]
fn run_json_reports_every_documented_key() {
    let report = run_json("run_json_reports_every_documented_key", PLACED_BALLS);
    assert_documented_keys(&report, true, true);
    assert_eq!(report["title"], "two steel balls");
    assert_eq!(report["law"]["name"], "hunt-crossley");
    assert_eq!(report["law"]["separation"], "penetration", "the default separation");
    assert_eq!(report["law"]["restitution_nominal"], 0.8);
    assert_eq!(report["instantaneous_nominal"]["restitution"], 0.8);
    assert_eq!(report["contact"]["separated"], true);
    assert_eq!(report["bodies"][0]["name"], "left ball");
    assert_eq!(report["bodies"][1]["name"], "right ball");
    assert!(number(&report, "/approach_speed") > 0.0);
    // Times count from the scene's t = 0: the surfaces are 0.1 - 2 (0.01) = 0.08 m apart and close at 2 m/s.
    assert_close("start time", number(&report, "/contact/start_time"), 0.08 / 2.0, 1e-12);
    let start = number(&report, "/contact/start_time");
    let end = number(&report, "/contact/end_time");
    assert!(
        start < number(&report, "/contact/max_compression_time")
            && number(&report, "/contact/max_compression_time") < end
    );
    assert_close("duration = end - start", number(&report, "/contact/duration"), end - start, 1e-9);
}

#[test]
fn run_json_defaults_the_title_to_the_file_stem() {
    let scene = PLACED_BALLS.replace("title = \"two steel balls\"\n", "");
    let report = run_json("run_json_defaults_the_title_to_the_file_stem", &scene);
    assert_eq!(report["title"], "run_json_defaults_the_title_to_the_file_stem");
}

#[test]
fn run_json_of_a_wall_writes_inf_and_takes_v0_from_the_wall() {
    // A rigid wall (mass, radius and young all `inf`) moving at -0.5 m/s, hit by a ball at +1 m/s.
    let scene = r#"[[bodies]]
name = "ball"
radius = 0.01
mass = 0.0329
velocity = [1.0, 0.0, 0.0]
young = 2.1e11
poisson = 0.3

[[bodies]]
name = "wall"
radius = inf
mass = inf
velocity = [-0.5, 0.0, 0.0]
young = inf

[contact]
law = "lankarani-nikravesh"
restitution = 0.7
"#;
    let report = run_json("run_json_of_a_wall_writes_inf_and_takes_v0_from_the_wall", scene);
    assert_documented_keys(&report, true, true);
    let wall = &report["bodies"][1];
    assert_eq!(wall["mass"], "inf", "an immovable body's mass is written as the string \"inf\"");
    assert_eq!(wall["radius"], "inf", "a flat body's radius is written as the string \"inf\"");
    assert_eq!(report["bodies"][0]["mass"], 0.0329);
    assert_eq!(wall["velocity_after"], wall["velocity_before"], "a wall keeps its velocity");
    // Hand calculation: m* = m1 for a wall, v0 = (1 - (-0.5)) m/s, and V0 is the wall's normal velocity.
    assert_close("effective mass", number(&report, "/effective_mass"), 0.0329, 1e-15);
    assert_close("approach speed", number(&report, "/approach_speed"), 1.5, 1e-15);
    assert_close("instantaneous V0", number(&report, "/instantaneous/common_normal_velocity"), -0.5, 1e-15);
    let simulated = number(&report, "/contact/common_normal_velocity");
    assert!((simulated + 0.5).abs() <= 1e-9 * 1.5, "simulated V0 {simulated} must be the wall's -0.5 m/s");
}

#[test]
fn run_json_with_damping_has_no_nominal_restitution() {
    let scene = PLACED_BALLS.replace("restitution = 0.8", "damping = 0.2");
    let report = run_json("run_json_with_damping_has_no_nominal_restitution", &scene);
    assert_documented_keys(&report, true, false);
    assert_eq!(report["law"]["damping"], 0.2, "the given damping is the damping used");
    assert!(report["instantaneous_nominal"].is_null());
}

#[test]
fn run_json_of_hertz_has_nominal_restitution_one() {
    let scene = PLACED_BALLS.replace("law = \"hunt-crossley\"\nrestitution = 0.8", "law = \"hertz\"");
    let report = run_json("run_json_of_hertz_has_nominal_restitution_one", &scene);
    assert_documented_keys(&report, true, true);
    assert_eq!(report["law"]["restitution_nominal"], 1.0);
    assert_eq!(report["law"]["damping"], 0.0);
    assert_eq!(report["instantaneous_nominal"]["restitution"], 1.0);
}

#[test]
fn run_json_of_bodies_that_never_separate_has_the_listed_nulls() {
    // Critically damped Kelvin–Voigt (e = 0): d(t) = v0 t exp(-w t) with w = sqrt(k / m*) never returns to zero,
    // so the bodies never part under `separation = "penetration"`.
    let scene = r#"[[bodies]]
radius = 0.01
mass = 0.1
velocity = [1.0, 0.0, 0.0]

[[bodies]]
radius = 0.01
mass = 0.1
velocity = [-1.0, 0.0, 0.0]

[contact]
law = "kelvin-voigt"
restitution = 0
stiffness = 1e5
separation = "penetration"
"#;
    let report = run_json("run_json_of_bodies_that_never_separate_has_the_listed_nulls", scene);
    assert_documented_keys(&report, false, true);
    assert_eq!(report["contact"]["separated"], false);
    assert_eq!(report["bodies"][0]["name"], "body 1", "the default name");
    assert_eq!(report["bodies"][1]["name"], "body 2", "the default name");
    // Hand calculation: m* = 0.05 kg, w = sqrt(1e5 / 0.05) = sqrt(2e6) 1/s; d' = 0 at t = 1/w, d = v0 / (e w).
    let w = 2e6_f64.sqrt();
    assert_close("time of max compression", number(&report, "/contact/max_compression_time"), 1.0 / w, 1e-9);
    assert_close("max penetration", number(&report, "/contact/max_penetration"), 2.0 / (std::f64::consts::E * w), 1e-9);
}

// ---------------------------------------------------------------------------------------------------------------
// `impact run SCENE` (readable), `impact models`, `--help`

#[test]
fn run_prints_a_readable_report_with_the_restitution_coefficients() {
    let scratch = Scratch::new("run_prints_a_readable_report_with_the_restitution_coefficients");
    let scene = scratch.scene("balls.toml", PLACED_BALLS);
    let output = impact(scratch.path(), &["run", &scene]);
    assert_success(&output);
    let text = stdout(&output);
    assert!(serde_json::from_str::<Value>(&text).is_err(), "without --json the report is not JSON:\n{text}");
    let lower = text.to_lowercase();
    for word in ["restitution", "poisson", "newton", "stronge"] {
        assert!(lower.contains(word), "the readable report must mention `{word}` (the three coefficients):\n{text}");
    }
}

#[test]
fn models_lists_all_eighteen_laws() {
    let scratch = Scratch::new("models_lists_all_eighteen_laws");
    let output = impact(scratch.path(), &["models"]);
    assert_success(&output);
    let text = stdout(&output);
    // The law names of the table in docs/laws.md#the-eighteen-laws.
    let laws = [
        "hertz",
        "kelvin-voigt",
        "hunt-crossley",
        "herbert-mcwhannell",
        "lee-wang",
        "lankarani-nikravesh",
        "gonthier",
        "zhiying-qishao",
        "flores",
        "gharib-hurmuzlu",
        "hu-guo",
        "carvalho-martins",
        "tsuji",
        "brilliantov",
        "thornton",
        "hertz-dashpot",
        "mujoco",
        "adams-impact",
    ];
    let missing: Vec<&str> = laws.into_iter().filter(|law| !has_word(&text, law)).collect();
    assert!(missing.is_empty(), "`impact models` does not list {missing:?}:\n{text}");
}

/// `impact ARGS... --help` succeeds and prints a usage that mentions every text of `mentions`.
#[track_caller]
fn assert_help(test: &str, args: &[&str], mentions: &[&str]) {
    let scratch = Scratch::new(test);
    let mut args = args.to_vec();
    args.push("--help");
    let output = impact(scratch.path(), &args);
    assert_success(&output);
    let text = stdout(&output);
    assert!(text.contains("Usage"), "--help must print a usage:\n{text}");
    for mention in mentions {
        assert!(text.contains(mention), "--help must mention `{mention}`:\n{text}");
    }
    let written = fs::read_dir(scratch.path()).expect("list the scratch folder").count();
    assert_eq!(written, 0, "--help must not write anything (nor run the demonstration)");
}

#[test]
fn help_works_for_impact() {
    assert_help("help_works_for_impact", &[], &["run", "models"]);
}

#[test]
fn help_works_for_run() {
    assert_help("help_works_for_run", &["run"], &["--json"]);
}

#[test]
fn help_works_for_models() {
    assert_help("help_works_for_models", &["models"], &[]);
}

// ---------------------------------------------------------------------------------------------------------------
// Bad arguments: status 2, a message, no panic

#[track_caller]
fn assert_bad_arguments(test: &str, args: &[&str]) {
    let scratch = Scratch::new(test);
    let output = impact(scratch.path(), args);
    assert_eq!(output.status.code(), Some(2), "bad arguments must exit with status 2\n{}", describe(&output));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!stderr.trim().is_empty(), "bad arguments must be explained on stderr\n{}", describe(&output));
    assert!(!stderr.contains("panicked") && !stderr.contains("RUST_BACKTRACE"), "{}", describe(&output));
    assert!(stdout(&output).is_empty(), "bad arguments must print nothing on stdout\n{}", describe(&output));
    let written = fs::read_dir(scratch.path()).expect("list the scratch folder").count();
    assert_eq!(written, 0, "bad arguments must not write anything (nor run the demonstration)");
}

#[test]
fn unknown_verb_exits_2() {
    assert_bad_arguments("unknown_verb_exits_2", &["simulate"]);
}

#[test]
fn run_without_a_scene_exits_2() {
    assert_bad_arguments("run_without_a_scene_exits_2", &["run"]);
}

#[test]
fn unknown_option_exits_2() {
    let scratch = Scratch::new("unknown_option_exits_2");
    let scene = scratch.scene("balls.toml", PLACED_BALLS);
    let output = impact(scratch.path(), &["run", &scene, "--yaml"]);
    assert_eq!(output.status.code(), Some(2), "an unknown option must exit with status 2\n{}", describe(&output));
    assert!(stdout(&output).is_empty(), "{}", describe(&output));
}

// ---------------------------------------------------------------------------------------------------------------
// `impact` with no argument: the demonstration

/// Every path under `root` (folders and files), relative, with `/` separators, sorted.
fn tree(root: &Path) -> Vec<String> {
    fn walk(root: &Path, folder: &Path, paths: &mut Vec<String>) {
        for entry in fs::read_dir(folder).expect("list a folder") {
            let path = entry.expect("a folder entry").path();
            let relative = path.strip_prefix(root).expect("under the root");
            paths.push(relative.components().map(|c| c.as_os_str().to_string_lossy()).collect::<Vec<_>>().join("/"));
            if path.is_dir() {
                walk(root, &path, paths);
            }
        }
    }
    let mut paths = Vec::new();
    walk(root, root, &mut paths);
    paths.sort();
    paths
}

#[test]
fn no_argument_runs_the_demonstration_and_writes_only_under_out_demo() {
    let scratch = Scratch::new("no_argument_runs_the_demonstration_and_writes_only_under_out_demo");
    let before = tree(scratch.path());
    assert!(before.is_empty(), "the folder starts empty: {before:?}");
    let output = impact(scratch.path(), &[]);
    assert_success(&output);
    let text = stdout(&output);
    assert!(text.to_lowercase().contains("restitution"), "the demonstration prints its report:\n{text}");
    assert!(text.contains("out/demo"), "the demonstration says where its outputs went:\n{text}");
    let after = tree(scratch.path());
    let outside: Vec<&String> =
        after.iter().filter(|path| !(*path == "out" || *path == "out/demo" || path.starts_with("out/demo/"))).collect();
    assert!(outside.is_empty(), "the demonstration wrote outside out/demo/: {outside:?} (all: {after:?})");
    let files: Vec<&String> = after.iter().filter(|path| scratch.path().join(path).is_file()).collect();
    assert!(!files.is_empty(), "the demonstration wrote nothing under out/demo/: {after:?}");
    let partial: Vec<&&String> = files.iter().filter(|path| path.contains(".partial")).collect();
    assert!(partial.is_empty(), "temporary files were left behind: {partial:?}");
}
