//! Bad scenes through the real `impact` binary (issue #2, docs/scene.md#rules-that-hold-everywhere): every kind of
//! bad scene exits with status 2 and a message naming the file, the dotted key (0-based: `bodies.1.velocity`,
//! `contact.restitution`) and, where known, the line — never a panic, and nothing on stdout.
//!
//! The expected line is counted here from the scene text the test wrote (the line that starts with the offending
//! key, or the header of the table a missing key belongs to), never copied from the program's output.

mod common;

use common::binary::{Scratch, impact};
use std::fs;
use std::process::Output;

// ---------------------------------------------------------------------------------------------------------------
// Scenes

/// Body 1 of a valid scene: a steel ball moving at +1 m/s along x.
const LEFT_BALL: &str = r#"name = "left ball"
radius = 0.01
mass = 0.0329
velocity = [1.0, 0.0, 0.0]
young = 2.1e11
poisson = 0.3"#;

/// Body 2 of a valid scene: a steel ball moving at -1 m/s along x.
const RIGHT_BALL: &str = r#"name = "right ball"
radius = 0.01
mass = 0.0329
velocity = [-1.0, 0.0, 0.0]
young = 2.1e11
poisson = 0.3"#;

/// A valid `[contact]` table.
const HUNT_CROSSLEY: &str = r#"law = "hunt-crossley"
restitution = 0.8"#;

/// A scene of two bodies and a contact table, each given as the lines of its table.
fn scene(first: &str, second: &str, contact: &str) -> String {
    format!("title = \"a bad scene\"\n\n[[bodies]]\n{first}\n\n[[bodies]]\n{second}\n\n[contact]\n{contact}\n")
}

/// `text` with its one line `old` replaced by `new` (which may hold several lines; `""` deletes the line).
fn edit(text: &str, old: &str, new: &str) -> String {
    let matching = text.lines().filter(|line| *line == old).count();
    assert_eq!(matching, 1, "the test scene must have exactly one line `{old}`:\n{text}");
    let lines: Vec<&str> = text
        .lines()
        .filter_map(|line| if line == old { (!new.is_empty()).then_some(new) } else { Some(line) })
        .collect();
    lines.join("\n")
}

/// `text` with `extra` appended as new lines.
fn with(text: &str, extra: &str) -> String {
    format!("{text}\n{extra}")
}

/// A valid scene that uses every key of docs/scene.md (positions, spin, material, damping, solver, output), each
/// line unique, so that one line can be swapped for a bad value.
const EVERY_KEY: &str = r#"title = "every key, all valid"

[[bodies]]
name = "left ball"
radius = 0.01
density = 7850.0
velocity = [1.0, 0.0, 0.0]
position = [0.0, 0.0, 0.0]
angular_velocity = [0, 0, 0]
young = 2.1e11
poisson = 0.3

[[bodies]]
name = "right ball"
radius = 0.012
mass = 0.0329
velocity = [-1.0, 0.0, 0.0]
position = [0.05, 0.0, 0.0]
angular_velocity = [0.0, 0.0, 0.0]
young = 2.0e11
poisson = 0.29

[contact]
law = "hunt-crossley"
damping = 0.1
stiffness = 1.0e10
exponent = 1.5
separation = "penetration"
friction = 0.0
normal = [1.0, 0.0, 0.0]

[solver]
rtol = 1e-10
atol = 1e-12

[output]
series = "out/every_key.csv"
"#;

// ---------------------------------------------------------------------------------------------------------------
// Running the binary and checking its answer

/// Where the error must point in the scene.
enum At {
    /// The one line of the scene that starts with this text.
    Line(&'static str),
    /// The one line of the scene that is exactly this text.
    Whole(&'static str),
    /// The `n`-th (1-based) line that starts with this text, e.g. the second `[[bodies]]` header.
    Nth(&'static str, usize),
    /// No line can be known (no such file, a table that is missing altogether).
    Nowhere,
}

/// The 1-based line number `at` designates in `text`, counted here.
fn expected_line(text: &str, at: &At) -> Option<usize> {
    let (start, n, whole) = match at {
        At::Line(start) => (*start, None, false),
        At::Whole(line) => (*line, None, true),
        At::Nth(start, n) => (*start, Some(*n), false),
        At::Nowhere => return None,
    };
    let designated = |line: &str| {
        if whole { line == start } else { line.trim_start().starts_with(start) }
    };
    let numbers: Vec<usize> =
        text.lines().enumerate().filter(|(_, line)| designated(line)).map(|(i, _)| i + 1).collect();
    match n {
        None => {
            assert_eq!(numbers.len(), 1, "exactly one line of the test scene must be or start with `{start}`:\n{text}");
            Some(numbers[0])
        }
        Some(n) => {
            Some(*numbers.get(n - 1).unwrap_or_else(|| panic!("no line #{n} starting with `{start}` in:\n{text}")))
        }
    }
}

/// Whether `token` appears in `text` as a whole word (not inside `line 12` when looking for `line 1`, say).
fn has_token(text: &str, token: &str) -> bool {
    let boundary = |c: Option<char>| c.is_none_or(|c| !(c.is_alphanumeric() || c == '_'));
    text.match_indices(token)
        .any(|(i, _)| boundary(text[..i].chars().next_back()) && boundary(text[i + token.len()..].chars().next()))
}

/// Asserts that `output` is the rejection of a bad scene: status 2, nothing on stdout, no panic, and a message on
/// stderr naming `file`, `key` (if any), `line N` (if any) and every text of `mentions`.
#[track_caller]
fn assert_rejection(output: &Output, file: &str, key: Option<&str>, line: Option<usize>, mentions: &[&str]) {
    let stderr = String::from_utf8_lossy(&output.stderr);
    let stdout = String::from_utf8_lossy(&output.stdout);
    let context = format!("status {:?}\n--- stderr\n{stderr}--- stdout\n{stdout}", output.status.code());
    assert_eq!(output.status.code(), Some(2), "a bad scene must exit with status 2\n{context}");
    assert!(stdout.is_empty(), "a bad scene must print nothing on stdout\n{context}");
    assert!(!stderr.contains("panicked"), "a bad scene must not panic\n{context}");
    assert!(!stderr.contains("RUST_BACKTRACE"), "a bad scene must not show a backtrace hint\n{context}");
    assert!(stderr.contains(file), "the message must name the file `{file}`\n{context}");
    if let Some(key) = key {
        assert!(has_token(&stderr, key), "the message must name the key `{key}`\n{context}");
    }
    if let Some(line) = line {
        assert!(has_token(&stderr, &format!("line {line}")), "the message must say `line {line}`\n{context}");
    }
    for text in mentions {
        assert!(stderr.contains(text), "the message must mention `{text}`\n{context}");
    }
}

/// Writes `text` as `<test>.toml`, runs `impact run` on it (readable and `--json`), and asserts the rejection names
/// the file, `key`, the line `at` designates, and every text of `mentions`. Nothing but the scene may be written.
#[track_caller]
fn assert_rejected(test: &str, text: &str, key: &str, at: At, mentions: &[&str]) {
    let scratch = Scratch::new(test);
    let file = format!("{test}.toml");
    let path = scratch.path().join(&file);
    fs::write(&path, text).expect("write the scene");
    let line = expected_line(text, &at);
    let path = path.to_str().expect("a UTF-8 temp path");
    for args in [vec!["run", path], vec!["run", path, "--json"]] {
        let output = impact(scratch.path(), &args);
        assert_rejection(&output, &file, Some(key), line, mentions);
    }
    let written: Vec<_> =
        fs::read_dir(scratch.path()).expect("list the scratch folder").map(|e| e.unwrap().file_name()).collect();
    assert_eq!(written, [file.as_str()], "a rejected scene must not write anything");
}

/// `EVERY_KEY` with its line `old` replaced by `new`: the error must name `key` on the line of `new`.
#[track_caller]
fn assert_value_rejected(test: &str, old: &str, new: &'static str, key: &str) {
    assert_rejected(test, &edit(EVERY_KEY, old, new), key, At::Whole(new), &[]);
}

// ---------------------------------------------------------------------------------------------------------------
// The scenes used here are valid before they are broken

#[test]
fn the_base_scene_is_valid() {
    let scratch = Scratch::new("the_base_scene_is_valid");
    let path = scratch.path().join("base.toml");
    fs::write(&path, scene(LEFT_BALL, RIGHT_BALL, HUNT_CROSSLEY)).unwrap();
    let output = impact(scratch.path(), &["run", path.to_str().unwrap()]);
    assert_eq!(output.status.code(), Some(0), "{}", String::from_utf8_lossy(&output.stderr));
}

#[test]
fn the_scene_with_every_key_is_valid() {
    let scratch = Scratch::new("the_scene_with_every_key_is_valid");
    let path = scratch.path().join("every_key.toml");
    fs::write(&path, EVERY_KEY).unwrap();
    let output = impact(scratch.path(), &["run", path.to_str().unwrap()]);
    assert_eq!(output.status.code(), Some(0), "{}", String::from_utf8_lossy(&output.stderr));
    // The same with `restitution` in place of `damping`, as the restitution cases below use it.
    fs::write(&path, edit(EVERY_KEY, "damping = 0.1", "restitution = 0.8")).unwrap();
    let output = impact(scratch.path(), &["run", path.to_str().unwrap()]);
    assert_eq!(output.status.code(), Some(0), "{}", String::from_utf8_lossy(&output.stderr));
}

// ---------------------------------------------------------------------------------------------------------------
// The file itself

#[test]
fn missing_file_is_rejected_naming_the_file() {
    let scratch = Scratch::new("missing_file_is_rejected_naming_the_file");
    let path = scratch.path().join("no_such_scene.toml");
    let output = impact(scratch.path(), &["run", path.to_str().unwrap()]);
    assert_rejection(&output, "no_such_scene.toml", None, None, &[]);
}

#[test]
fn invalid_toml_is_rejected_naming_the_line() {
    let text = scene(LEFT_BALL, RIGHT_BALL, &edit(HUNT_CROSSLEY, "restitution = 0.8", "restitution = [0.8"));
    assert_rejected(
        "invalid_toml_is_rejected_naming_the_line",
        &text,
        "contact.restitution",
        At::Line("restitution = [0.8"),
        &[],
    );
}

#[test]
fn duplicate_key_is_rejected_naming_the_second_one() {
    let text = scene(&edit(LEFT_BALL, "mass = 0.0329", "mass = 0.0329\nmass = 0.05"), RIGHT_BALL, HUNT_CROSSLEY);
    assert_rejected(
        "duplicate_key_is_rejected_naming_the_second_one",
        &text,
        "bodies.0.mass",
        At::Line("mass = 0.05"),
        &[],
    );
}

// ---------------------------------------------------------------------------------------------------------------
// Unknown and missing keys

#[test]
fn unknown_key_in_a_body_is_rejected_naming_the_key() {
    let text = scene(LEFT_BALL, &with(RIGHT_BALL, "colour = \"red\""), HUNT_CROSSLEY);
    assert_rejected(
        "unknown_key_in_a_body_is_rejected_naming_the_key",
        &text,
        "bodies.1.colour",
        At::Line("colour ="),
        &[],
    );
}

#[test]
fn unknown_key_in_contact_is_rejected_naming_the_key() {
    let text = scene(LEFT_BALL, RIGHT_BALL, &with(HUNT_CROSSLEY, "coefficient = 0.8"));
    let test = "unknown_key_in_contact_is_rejected_naming_the_key";
    assert_rejected(test, &text, "contact.coefficient", At::Line("coefficient ="), &[]);
}

#[test]
fn unknown_table_is_rejected_naming_the_table() {
    let text = with(&scene(LEFT_BALL, RIGHT_BALL, HUNT_CROSSLEY), "[extras]\nnote = \"hello\"\n");
    assert_rejected("unknown_table_is_rejected_naming_the_table", &text, "extras", At::Line("[extras]"), &[]);
}

#[test]
fn missing_radius_is_rejected_naming_the_key() {
    let text = scene(LEFT_BALL, &edit(RIGHT_BALL, "radius = 0.01", ""), HUNT_CROSSLEY);
    // A missing key is located at the header of its table: the second [[bodies]].
    assert_rejected(
        "missing_radius_is_rejected_naming_the_key",
        &text,
        "bodies.1.radius",
        At::Nth("[[bodies]]", 2),
        &[],
    );
}

#[test]
fn missing_mass_and_density_is_rejected_naming_the_key() {
    let text = scene(&edit(LEFT_BALL, "mass = 0.0329", ""), RIGHT_BALL, HUNT_CROSSLEY);
    let test = "missing_mass_and_density_is_rejected_naming_the_key";
    assert_rejected(test, &text, "bodies.0.mass", At::Nth("[[bodies]]", 1), &[]);
}

#[test]
fn missing_velocity_is_rejected_naming_the_key() {
    let text = scene(LEFT_BALL, &edit(RIGHT_BALL, "velocity = [-1.0, 0.0, 0.0]", ""), HUNT_CROSSLEY);
    let test = "missing_velocity_is_rejected_naming_the_key";
    assert_rejected(test, &text, "bodies.1.velocity", At::Nth("[[bodies]]", 2), &[]);
}

#[test]
fn missing_law_is_rejected_naming_the_key() {
    let text = scene(LEFT_BALL, RIGHT_BALL, "restitution = 0.8");
    assert_rejected("missing_law_is_rejected_naming_the_key", &text, "contact.law", At::Line("[contact]"), &[]);
}

#[test]
fn missing_contact_table_is_rejected_naming_it() {
    let text = format!("[[bodies]]\n{LEFT_BALL}\n\n[[bodies]]\n{RIGHT_BALL}\n");
    assert_rejected("missing_contact_table_is_rejected_naming_it", &text, "contact", At::Nowhere, &[]);
}

#[test]
fn missing_bodies_are_rejected_naming_the_key() {
    let text = format!("[contact]\n{HUNT_CROSSLEY}\n");
    assert_rejected("missing_bodies_are_rejected_naming_the_key", &text, "bodies", At::Nowhere, &[]);
}

#[test]
fn a_single_body_is_rejected_naming_the_key() {
    let text = format!("[[bodies]]\n{LEFT_BALL}\n\n[contact]\n{HUNT_CROSSLEY}\n");
    assert_rejected("a_single_body_is_rejected_naming_the_key", &text, "bodies", At::Line("[[bodies]]"), &[]);
}

#[test]
fn three_bodies_make_a_world_whose_bodies_need_positions() {
    let text = format!(
        "[[bodies]]\n{LEFT_BALL}\n\n[[bodies]]\n{RIGHT_BALL}\n\n[[bodies]]\n{RIGHT_BALL}\n\n[contact]\n{HUNT_CROSSLEY}\n"
    );
    let test = "three_bodies_make_a_world_whose_bodies_need_positions";
    assert_rejected(test, &text, "bodies.0.position", At::Nth("[[bodies]]", 1), &["world run", "position"]);
}

#[test]
fn mass_and_density_together_are_rejected_naming_the_key() {
    let text = scene(&with(LEFT_BALL, "density = 7850.0"), RIGHT_BALL, HUNT_CROSSLEY);
    let test = "mass_and_density_together_are_rejected_naming_the_key";
    assert_rejected(test, &text, "bodies.0.density", At::Line("density ="), &[]);
}

// ---------------------------------------------------------------------------------------------------------------
// Wrong types and shapes

#[test]
fn string_where_a_number_is_expected_is_rejected_naming_the_key() {
    let text = scene(&edit(LEFT_BALL, "mass = 0.0329", "mass = \"heavy\""), RIGHT_BALL, HUNT_CROSSLEY);
    let test = "string_where_a_number_is_expected_is_rejected_naming_the_key";
    assert_rejected(test, &text, "bodies.0.mass", At::Line("mass = \"heavy\""), &[]);
}

#[test]
fn number_where_a_vector_is_expected_is_rejected_naming_the_key() {
    let text = scene(LEFT_BALL, &edit(RIGHT_BALL, "velocity = [-1.0, 0.0, 0.0]", "velocity = -1.0"), HUNT_CROSSLEY);
    let test = "number_where_a_vector_is_expected_is_rejected_naming_the_key";
    assert_rejected(test, &text, "bodies.1.velocity", At::Line("velocity = -1.0"), &[]);
}

#[test]
fn vector_of_two_numbers_is_rejected_naming_the_key() {
    let text =
        scene(&edit(LEFT_BALL, "velocity = [1.0, 0.0, 0.0]", "velocity = [1.0, 0.0]"), RIGHT_BALL, HUNT_CROSSLEY);
    let test = "vector_of_two_numbers_is_rejected_naming_the_key";
    assert_rejected(test, &text, "bodies.0.velocity", At::Line("velocity = [1.0, 0.0]"), &[]);
}

#[test]
fn stiffness_word_other_than_hertz_is_rejected_naming_the_key() {
    let text = scene(LEFT_BALL, RIGHT_BALL, &with(HUNT_CROSSLEY, "stiffness = \"stiff\""));
    let test = "stiffness_word_other_than_hertz_is_rejected_naming_the_key";
    assert_rejected(test, &text, "contact.stiffness", At::Line("stiffness ="), &[]);
}

#[test]
fn unknown_law_is_rejected_naming_the_key() {
    let text = scene(LEFT_BALL, RIGHT_BALL, &edit(HUNT_CROSSLEY, "law = \"hunt-crossley\"", "law = \"hunt\""));
    assert_rejected("unknown_law_is_rejected_naming_the_key", &text, "contact.law", At::Line("law ="), &["hunt"]);
}

#[test]
fn unknown_separation_is_rejected_naming_the_key() {
    let text = scene(LEFT_BALL, RIGHT_BALL, &with(HUNT_CROSSLEY, "separation = \"contact\""));
    assert_rejected(
        "unknown_separation_is_rejected_naming_the_key",
        &text,
        "contact.separation",
        At::Line("separation ="),
        &[],
    );
}

#[test]
fn unknown_tangential_unloading_is_rejected_naming_the_key() {
    let text = scene(LEFT_BALL, RIGHT_BALL, &with(HUNT_CROSSLEY, "friction = 0.3\ntangential_unloading = \"shrink\""));
    let test = "unknown_tangential_unloading_is_rejected_naming_the_key";
    let at = At::Line("tangential_unloading =");
    assert_rejected(test, &text, "contact.tangential_unloading", at, &["shrink", "\"none\"", "\"rescale\""]);
}

#[test]
fn unknown_friction_cap_is_rejected_naming_the_key() {
    let text = scene(LEFT_BALL, RIGHT_BALL, &with(HUNT_CROSSLEY, "friction = 0.3\nfriction_cap = \"absolute\""));
    let test = "unknown_friction_cap_is_rejected_naming_the_key";
    let at = At::Line("friction_cap =");
    assert_rejected(test, &text, "contact.friction_cap", at, &["absolute", "\"compressive\"", "\"magnitude\""]);
}

#[test]
fn a_pair_with_an_unknown_friction_cap_is_rejected_naming_its_key() {
    let text = edit(WORLD, "restitution = 0.7", "restitution = 0.7\nfriction = 0.2\nfriction_cap = \"both\"");
    let test = "a_pair_with_an_unknown_friction_cap";
    assert_rejected(test, &text, "pair.0.friction_cap", At::Line("friction_cap ="), &["both"]);
}

// ---------------------------------------------------------------------------------------------------------------
// NaN and -inf anywhere, +inf outside mass, radius and young: one case per numeric key of `EVERY_KEY`

macro_rules! bad_values {
    ($($test:ident: $old:literal => $new:literal names $key:literal;)*) => {
        $(
            #[test]
            fn $test() {
                assert_value_rejected(stringify!($test), $old, $new, $key);
            }
        )*
    };
}

bad_values! {
    nan_radius_is_rejected: "radius = 0.01" => "radius = nan" names "bodies.0.radius";
    nan_mass_is_rejected: "mass = 0.0329" => "mass = nan" names "bodies.1.mass";
    signed_nan_mass_is_rejected: "mass = 0.0329" => "mass = -nan" names "bodies.1.mass";
    nan_density_is_rejected: "density = 7850.0" => "density = nan" names "bodies.0.density";
    nan_velocity_is_rejected: "velocity = [-1.0, 0.0, 0.0]" => "velocity = [-1.0, nan, 0.0]" names "bodies.1.velocity";
    nan_position_is_rejected: "position = [0.0, 0.0, 0.0]" => "position = [0.0, 0.0, nan]" names "bodies.0.position";
    nan_angular_velocity_is_rejected:
        "angular_velocity = [0.0, 0.0, 0.0]" => "angular_velocity = [nan, 0.0, 0.0]" names "bodies.1.angular_velocity";
    nan_young_is_rejected: "young = 2.1e11" => "young = nan" names "bodies.0.young";
    nan_poisson_is_rejected: "poisson = 0.29" => "poisson = nan" names "bodies.1.poisson";
    nan_restitution_is_rejected: "damping = 0.1" => "restitution = nan" names "contact.restitution";
    nan_damping_is_rejected: "damping = 0.1" => "damping = nan" names "contact.damping";
    nan_stiffness_is_rejected: "stiffness = 1.0e10" => "stiffness = nan" names "contact.stiffness";
    nan_exponent_is_rejected: "exponent = 1.5" => "exponent = nan" names "contact.exponent";
    nan_friction_is_rejected: "friction = 0.0" => "friction = nan" names "contact.friction";
    nan_normal_is_rejected: "normal = [1.0, 0.0, 0.0]" => "normal = [nan, 0.0, 0.0]" names "contact.normal";
    nan_rtol_is_rejected: "rtol = 1e-10" => "rtol = nan" names "solver.rtol";
    nan_atol_is_rejected: "atol = 1e-12" => "atol = nan" names "solver.atol";

    minus_inf_radius_is_rejected: "radius = 0.01" => "radius = -inf" names "bodies.0.radius";
    minus_inf_mass_is_rejected: "mass = 0.0329" => "mass = -inf" names "bodies.1.mass";
    minus_inf_density_is_rejected: "density = 7850.0" => "density = -inf" names "bodies.0.density";
    minus_inf_velocity_is_rejected:
        "velocity = [-1.0, 0.0, 0.0]" => "velocity = [-inf, 0.0, 0.0]" names "bodies.1.velocity";
    minus_inf_position_is_rejected:
        "position = [0.0, 0.0, 0.0]" => "position = [-inf, 0.0, 0.0]" names "bodies.0.position";
    minus_inf_angular_velocity_is_rejected:
        "angular_velocity = [0.0, 0.0, 0.0]" => "angular_velocity = [0.0, -inf, 0.0]" names "bodies.1.angular_velocity";
    minus_inf_young_is_rejected: "young = 2.1e11" => "young = -inf" names "bodies.0.young";
    minus_inf_poisson_is_rejected: "poisson = 0.29" => "poisson = -inf" names "bodies.1.poisson";
    minus_inf_restitution_is_rejected: "damping = 0.1" => "restitution = -inf" names "contact.restitution";
    minus_inf_damping_is_rejected: "damping = 0.1" => "damping = -inf" names "contact.damping";
    minus_inf_stiffness_is_rejected: "stiffness = 1.0e10" => "stiffness = -inf" names "contact.stiffness";
    minus_inf_exponent_is_rejected: "exponent = 1.5" => "exponent = -inf" names "contact.exponent";
    minus_inf_friction_is_rejected: "friction = 0.0" => "friction = -inf" names "contact.friction";
    minus_inf_normal_is_rejected: "normal = [1.0, 0.0, 0.0]" => "normal = [1.0, -inf, 0.0]" names "contact.normal";
    minus_inf_rtol_is_rejected: "rtol = 1e-10" => "rtol = -inf" names "solver.rtol";
    minus_inf_atol_is_rejected: "atol = 1e-12" => "atol = -inf" names "solver.atol";

    plus_inf_density_is_rejected: "density = 7850.0" => "density = inf" names "bodies.0.density";
    plus_inf_velocity_is_rejected:
        "velocity = [-1.0, 0.0, 0.0]" => "velocity = [+inf, 0.0, 0.0]" names "bodies.1.velocity";
    plus_inf_position_is_rejected: "position = [0.0, 0.0, 0.0]" => "position = [0.0, inf, 0.0]" names "bodies.0.position";
    plus_inf_angular_velocity_is_rejected:
        "angular_velocity = [0.0, 0.0, 0.0]" => "angular_velocity = [0.0, 0.0, inf]" names "bodies.1.angular_velocity";
    plus_inf_poisson_is_rejected: "poisson = 0.29" => "poisson = inf" names "bodies.1.poisson";
    plus_inf_restitution_is_rejected: "damping = 0.1" => "restitution = inf" names "contact.restitution";
    plus_inf_damping_is_rejected: "damping = 0.1" => "damping = inf" names "contact.damping";
    plus_inf_stiffness_is_rejected: "stiffness = 1.0e10" => "stiffness = +inf" names "contact.stiffness";
    plus_inf_exponent_is_rejected: "exponent = 1.5" => "exponent = inf" names "contact.exponent";
    plus_inf_friction_is_rejected: "friction = 0.0" => "friction = inf" names "contact.friction";
    plus_inf_normal_is_rejected: "normal = [1.0, 0.0, 0.0]" => "normal = [inf, 0.0, 0.0]" names "contact.normal";
    plus_inf_rtol_is_rejected: "rtol = 1e-10" => "rtol = inf" names "solver.rtol";
    plus_inf_atol_is_rejected: "atol = 1e-12" => "atol = inf" names "solver.atol";
}

// ---------------------------------------------------------------------------------------------------------------
// Values out of range

bad_values! {
    zero_mass_is_rejected_naming_the_key: "mass = 0.0329" => "mass = 0.0" names "bodies.1.mass";
    negative_mass_is_rejected_naming_the_key: "mass = 0.0329" => "mass = -0.0329" names "bodies.1.mass";
    zero_radius_is_rejected_naming_the_key: "radius = 0.01" => "radius = 0.0" names "bodies.0.radius";
    negative_radius_is_rejected_naming_the_key: "radius = 0.012" => "radius = -0.012" names "bodies.1.radius";
    zero_density_is_rejected_naming_the_key: "density = 7850.0" => "density = 0.0" names "bodies.0.density";
    negative_young_is_rejected_naming_the_key: "young = 2.0e11" => "young = -2.0e11" names "bodies.1.young";
    poisson_above_one_half_is_rejected_naming_the_key: "poisson = 0.3" => "poisson = 0.6" names "bodies.0.poisson";
    zero_stiffness_is_rejected_naming_the_key: "stiffness = 1.0e10" => "stiffness = 0" names "contact.stiffness";
    negative_stiffness_is_rejected_naming_the_key: "stiffness = 1.0e10" => "stiffness = -1.0e10" names "contact.stiffness";
    zero_exponent_is_rejected_naming_the_key: "exponent = 1.5" => "exponent = 0.0" names "contact.exponent";
    exponent_below_a_flat_punch_is_rejected_naming_the_key: "exponent = 1.5" => "exponent = 0.5" names "contact.exponent";
    exponent_beyond_the_fits_is_rejected_naming_the_key: "exponent = 1.5" => "exponent = 3.5" names "contact.exponent";
    restitution_above_one_is_rejected_naming_the_key: "damping = 0.1" => "restitution = 1.5" names "contact.restitution";
    restitution_below_zero_is_rejected_naming_the_key:
        "damping = 0.1" => "restitution = -0.1" names "contact.restitution";
    negative_damping_is_rejected_naming_the_key: "damping = 0.1" => "damping = -0.1" names "contact.damping";
    negative_friction_is_rejected_naming_the_key: "friction = 0.0" => "friction = -0.2" names "contact.friction";
    tolerance_above_its_range_is_rejected_naming_the_key: "rtol = 1e-10" => "rtol = 0.5" names "solver.rtol";
    zero_tolerance_is_rejected_naming_the_key: "atol = 1e-12" => "atol = 0.0" names "solver.atol";
}

// ---------------------------------------------------------------------------------------------------------------
// Laws, damping and restitution

/// A scene of the two balls with this `[contact]` table.
fn balls_with(contact: &str) -> String {
    scene(LEFT_BALL, RIGHT_BALL, contact)
}

#[test]
fn hertz_with_restitution_below_one_is_rejected_naming_the_key() {
    let text = balls_with("law = \"hertz\"\nrestitution = 0.9");
    let test = "hertz_with_restitution_below_one_is_rejected_naming_the_key";
    assert_rejected(test, &text, "contact.restitution", At::Line("restitution ="), &["hertz"]);
}

#[test]
fn hertz_with_damping_is_rejected_naming_the_key() {
    let text = balls_with("law = \"hertz\"\ndamping = 0.1");
    assert_rejected(
        "hertz_with_damping_is_rejected_naming_the_key",
        &text,
        "contact.damping",
        At::Line("damping ="),
        &["hertz"],
    );
}

/// e = 0 for a law whose map divides by e (or, for `carvalho-martins`, diverges there).
fn assert_zero_restitution_rejected(test: &str, law: &str) {
    let text = balls_with(&format!("law = \"{law}\"\nrestitution = 0.0"));
    assert_rejected(test, &text, "contact.restitution", At::Line("restitution ="), &[law]);
}

#[test]
fn zero_restitution_is_rejected_for_gonthier() {
    assert_zero_restitution_rejected("zero_restitution_is_rejected_for_gonthier", "gonthier");
}

#[test]
fn zero_restitution_is_rejected_for_flores() {
    assert_zero_restitution_rejected("zero_restitution_is_rejected_for_flores", "flores");
}

#[test]
fn zero_restitution_is_rejected_for_gharib_hurmuzlu() {
    assert_zero_restitution_rejected("zero_restitution_is_rejected_for_gharib_hurmuzlu", "gharib-hurmuzlu");
}

#[test]
fn zero_restitution_is_rejected_for_hu_guo() {
    assert_zero_restitution_rejected("zero_restitution_is_rejected_for_hu_guo", "hu-guo");
}

#[test]
fn zero_restitution_is_rejected_for_carvalho_martins() {
    assert_zero_restitution_rejected("zero_restitution_is_rejected_for_carvalho_martins", "carvalho-martins");
}

#[test]
fn brilliantov_with_restitution_is_rejected_naming_the_key() {
    let text = balls_with("law = \"brilliantov\"\nrestitution = 0.8");
    let test = "brilliantov_with_restitution_is_rejected_naming_the_key";
    assert_rejected(test, &text, "contact.restitution", At::Line("restitution ="), &["brilliantov"]);
}

#[test]
fn both_restitution_and_damping_are_rejected_naming_the_key() {
    let text = balls_with("law = \"hunt-crossley\"\nrestitution = 0.8\ndamping = 0.1");
    let test = "both_restitution_and_damping_are_rejected_naming_the_key";
    assert_rejected(test, &text, "contact.damping", At::Line("damping ="), &[]);
}

#[test]
fn neither_restitution_nor_damping_is_rejected_naming_the_key() {
    let text = balls_with("law = \"lankarani-nikravesh\"");
    let test = "neither_restitution_nor_damping_is_rejected_naming_the_key";
    assert_rejected(test, &text, "contact.restitution", At::Line("[contact]"), &["lankarani-nikravesh"]);
}

#[test]
fn kelvin_voigt_with_hertz_stiffness_is_rejected_naming_the_key() {
    let text = balls_with("law = \"kelvin-voigt\"\nrestitution = 0.5\nstiffness = \"hertz\"");
    let test = "kelvin_voigt_with_hertz_stiffness_is_rejected_naming_the_key";
    assert_rejected(test, &text, "contact.stiffness", At::Line("stiffness ="), &["kelvin-voigt"]);
}

#[test]
fn kelvin_voigt_without_stiffness_is_rejected_naming_the_key() {
    let text = balls_with("law = \"kelvin-voigt\"\nrestitution = 0.5");
    let test = "kelvin_voigt_without_stiffness_is_rejected_naming_the_key";
    assert_rejected(test, &text, "contact.stiffness", At::Line("[contact]"), &["kelvin-voigt"]);
}

#[test]
fn kelvin_voigt_with_an_exponent_other_than_one_is_rejected_naming_the_key() {
    let text = balls_with("law = \"kelvin-voigt\"\nrestitution = 0.5\nstiffness = 1e5\nexponent = 1.5");
    let test = "kelvin_voigt_with_an_exponent_other_than_one_is_rejected_naming_the_key";
    assert_rejected(test, &text, "contact.exponent", At::Line("exponent ="), &[]);
}

#[test]
fn hertz_stiffness_with_another_exponent_is_rejected_naming_the_key() {
    let text = balls_with("law = \"hunt-crossley\"\nrestitution = 0.8\nstiffness = \"hertz\"\nexponent = 2.0");
    let test = "hertz_stiffness_with_another_exponent_is_rejected_naming_the_key";
    assert_rejected(test, &text, "contact.exponent", At::Line("exponent ="), &[]);
}

#[test]
fn tsuji_with_an_exponent_is_rejected_naming_the_key() {
    let text = balls_with("law = \"tsuji\"\nrestitution = 0.8\nexponent = 1.5");
    assert_rejected(
        "tsuji_with_an_exponent_is_rejected_naming_the_key",
        &text,
        "contact.exponent",
        At::Line("exponent ="),
        &[],
    );
}

#[test]
fn brilliantov_with_an_exponent_is_rejected_naming_the_key() {
    let text = balls_with("law = \"brilliantov\"\ndamping = 1e-6\nexponent = 1.5");
    let test = "brilliantov_with_an_exponent_is_rejected_naming_the_key";
    assert_rejected(test, &text, "contact.exponent", At::Line("exponent ="), &[]);
}

#[test]
fn hertz_stiffness_without_young_is_rejected_naming_the_key() {
    let text = scene(LEFT_BALL, &edit(RIGHT_BALL, "young = 2.1e11", ""), HUNT_CROSSLEY);
    let test = "hertz_stiffness_without_young_is_rejected_naming_the_key";
    assert_rejected(test, &text, "bodies.1.young", At::Nth("[[bodies]]", 2), &[]);
}

#[test]
fn hertz_stiffness_without_poisson_is_rejected_naming_the_key() {
    let text = scene(&edit(LEFT_BALL, "poisson = 0.3", ""), RIGHT_BALL, HUNT_CROSSLEY);
    let test = "hertz_stiffness_without_poisson_is_rejected_naming_the_key";
    assert_rejected(test, &text, "bodies.0.poisson", At::Nth("[[bodies]]", 1), &[]);
}

// ---------------------------------------------------------------------------------------------------------------
// Bodies and geometry

/// A wall (immovable, flat, at rest) for the second body.
const WALL: &str = r#"name = "wall"
radius = inf
mass = inf
velocity = [0.0, 0.0, 0.0]
young = 2.1e11
poisson = 0.3"#;

#[test]
fn two_immovable_bodies_are_rejected_naming_the_key() {
    let fixed = |ball: &str| edit(ball, "mass = 0.0329", "mass = inf");
    let text = scene(&fixed(LEFT_BALL), &fixed(RIGHT_BALL), HUNT_CROSSLEY);
    let test = "two_immovable_bodies_are_rejected_naming_the_key";
    assert_rejected(test, &text, "bodies.1.mass", At::Nth("mass = inf", 2), &[]);
}

#[test]
fn two_flat_bodies_are_rejected_naming_the_key() {
    let flat = |ball: &str| edit(ball, "radius = 0.01", "radius = inf");
    let text = scene(&flat(LEFT_BALL), &flat(RIGHT_BALL), HUNT_CROSSLEY);
    assert_rejected(
        "two_flat_bodies_are_rejected_naming_the_key",
        &text,
        "bodies.1.radius",
        At::Nth("radius = inf", 2),
        &[],
    );
}

#[test]
fn two_rigid_bodies_with_hertz_stiffness_are_rejected_naming_the_key() {
    let rigid = |ball: &str| edit(ball, "young = 2.1e11", "young = inf");
    let text = scene(&rigid(LEFT_BALL), &rigid(RIGHT_BALL), HUNT_CROSSLEY);
    let test = "two_rigid_bodies_with_hertz_stiffness_are_rejected_naming_the_key";
    assert_rejected(test, &text, "bodies.1.young", At::Nth("young = inf", 2), &[]);
}

#[test]
fn density_with_an_infinite_radius_is_rejected_naming_the_key() {
    let flat_by_density = edit(&edit(LEFT_BALL, "radius = 0.01", "radius = inf"), "mass = 0.0329", "density = 7850.0");
    let text = scene(&flat_by_density, RIGHT_BALL, HUNT_CROSSLEY);
    let test = "density_with_an_infinite_radius_is_rejected_naming_the_key";
    assert_rejected(test, &text, "bodies.0.density", At::Line("density ="), &[]);
}

#[test]
fn bodies_that_do_not_approach_are_rejected_naming_the_velocities() {
    // Both move along +x, the second faster: (v1 - v2)·n = 0.75 - 1.25 < 0.
    let text = scene(
        &edit(LEFT_BALL, "velocity = [1.0, 0.0, 0.0]", "velocity = [0.75, 0.0, 0.0]"),
        &edit(RIGHT_BALL, "velocity = [-1.0, 0.0, 0.0]", "velocity = [1.25, 0.0, 0.0]"),
        HUNT_CROSSLEY,
    );
    // No normal was given, so the default one was used: the message says so and names `contact.normal`.
    let test = "bodies_that_do_not_approach_are_rejected_naming_the_velocities";
    assert_rejected(test, &text, "contact.normal", At::Line("[contact]"), &["750 mm/s", "1.25 m/s", "default normal"]);
}

#[test]
fn a_ball_at_rest_against_a_wall_at_rest_is_rejected_naming_the_key() {
    let resting = edit(LEFT_BALL, "velocity = [1.0, 0.0, 0.0]", "velocity = [0.0, 0.0, 0.0]");
    let text = scene(&resting, WALL, HUNT_CROSSLEY);
    let test = "a_ball_at_rest_against_a_wall_at_rest_is_rejected_naming_the_key";
    assert_rejected(test, &text, "contact.normal", At::Line("[contact]"), &["default normal"]);
}

#[test]
fn header_comments_do_not_shift_the_line_of_an_error() {
    // docs/scene.md#a-complete-scene writes comments after table headers; the error must still point into the first
    // body.
    let text = scene(
        &edit(LEFT_BALL, "velocity = [1.0, 0.0, 0.0]", "velocity = [0.75, 0.0, 0.0]"),
        &edit(RIGHT_BALL, "velocity = [-1.0, 0.0, 0.0]", "velocity = [1.25, 0.0, 0.0]"),
        HUNT_CROSSLEY,
    )
    .replace("[[bodies]]\n", "[[bodies]]                       # a body\n")
    .replace("[contact]\n", "[contact]\nnormal = [1.0, 0.0, 0.0]\n");
    let test = "header_comments_do_not_shift_the_line_of_an_error";
    assert_rejected(test, &text, "bodies.0.velocity", At::Line("velocity = [0.75"), &["contact.normal"]);
}

/// The two balls (closing along x) placed at these centres.
fn placed(first: &str, second: &str, contact: &str) -> String {
    scene(&with(LEFT_BALL, &format!("position = {first}")), &with(RIGHT_BALL, &format!("position = {second}")), contact)
}

#[test]
fn bodies_that_never_meet_are_rejected_naming_the_key() {
    // Closing along x but 0.05 m apart in y: the paths pass at a distance 0.05 > 0.02 = r1 + r2.
    let text = placed("[0.0, 0.0, 0.0]", "[0.1, 0.05, 0.0]", HUNT_CROSSLEY);
    let test = "bodies_that_never_meet_are_rejected_naming_the_key";
    assert_rejected(test, &text, "bodies.1.position", At::Line("position = [0.1, 0.05"), &["never meet"]);
}

#[test]
fn a_ball_moving_away_from_a_wall_is_rejected_naming_the_key() {
    // The wall's plane x = 0.1 faces the ball at the origin, which moves along -x.
    let ball = with(
        &edit(LEFT_BALL, "velocity = [1.0, 0.0, 0.0]", "velocity = [-1.0, 0.0, 0.0]"),
        "position = [0.0, 0.0, 0.0]",
    );
    let text = scene(&ball, &with(WALL, "position = [0.1, 0.0, 0.0]"), HUNT_CROSSLEY);
    let test = "a_ball_moving_away_from_a_wall_is_rejected_naming_the_key";
    assert_rejected(test, &text, "bodies.1.position", At::Line("position = [0.1"), &["never meet"]);
}

#[test]
fn bodies_that_start_overlapped_are_rejected_naming_the_key() {
    // Centres 0.015 m apart, radii 0.01 each: overlapped by 0.005 m.
    let text = placed("[0.0, 0.0, 0.0]", "[0.015, 0.0, 0.0]", HUNT_CROSSLEY);
    let test = "bodies_that_start_overlapped_are_rejected_naming_the_key";
    assert_rejected(test, &text, "bodies.1.position", At::Line("position = [0.015"), &["overlap"]);
}

#[test]
fn coincident_centres_are_rejected_naming_the_key() {
    let text = placed("[0.0, 0.0, 0.0]", "[0.0, 0.0, 0.0]", HUNT_CROSSLEY);
    assert_rejected(
        "coincident_centres_are_rejected_naming_the_key",
        &text,
        "bodies.1.position",
        At::Nth("position =", 2),
        &[],
    );
}

#[test]
fn normal_that_disagrees_with_the_line_of_centres_is_rejected_naming_the_key() {
    let text = placed("[0.0, 0.0, 0.0]", "[0.1, 0.0, 0.0]", &with(HUNT_CROSSLEY, "normal = [0.0, 1.0, 0.0]"));
    let test = "normal_that_disagrees_with_the_line_of_centres_is_rejected_naming_the_key";
    assert_rejected(test, &text, "contact.normal", At::Line("normal ="), &[]);
}

#[test]
fn zero_normal_is_rejected_naming_the_key() {
    let text = balls_with(&with(HUNT_CROSSLEY, "normal = [0.0, 0.0, 0.0]"));
    assert_rejected("zero_normal_is_rejected_naming_the_key", &text, "contact.normal", At::Line("normal ="), &[]);
}

#[test]
fn position_for_the_first_body_only_is_rejected_naming_the_key() {
    let text = scene(&with(LEFT_BALL, "position = [0.0, 0.0, 0.0]"), RIGHT_BALL, HUNT_CROSSLEY);
    // The missing key is the second body's: located at its table's header.
    let test = "position_for_the_first_body_only_is_rejected_naming_the_key";
    assert_rejected(test, &text, "bodies.1.position", At::Nth("[[bodies]]", 2), &[]);
}

#[test]
fn position_for_the_second_body_only_is_rejected_naming_the_key() {
    let text = scene(LEFT_BALL, &with(RIGHT_BALL, "position = [0.1, 0.0, 0.0]"), HUNT_CROSSLEY);
    let test = "position_for_the_second_body_only_is_rejected_naming_the_key";
    assert_rejected(test, &text, "bodies.0.position", At::Nth("[[bodies]]", 1), &[]);
}

// ---------------------------------------------------------------------------------------------------------------
// Oblique impact, friction and spin: the keys' own rules

#[test]
fn a_given_normal_without_approach_is_rejected_naming_the_velocity_and_the_normal_used() {
    // The balls close along x, but the scene puts the contact normal along y: no approach along it.
    let text = balls_with(&with(HUNT_CROSSLEY, "normal = [0.0, 1.0, 0.0]"));
    let test = "a_given_normal_without_approach_is_rejected_naming_the_velocity_and_the_normal_used";
    assert_rejected(test, &text, "bodies.0.velocity", At::Nth("velocity =", 1), &["`contact.normal`", "[0, 1, 0]"]);
}

#[test]
fn zero_inertia_is_rejected_naming_the_key() {
    let text = scene(&with(LEFT_BALL, "inertia = 0.0"), RIGHT_BALL, HUNT_CROSSLEY);
    assert_rejected("zero_inertia_is_rejected_naming_the_key", &text, "bodies.0.inertia", At::Line("inertia ="), &[]);
}

#[test]
fn inertia_of_an_immovable_body_is_rejected_naming_the_key() {
    let fixed = edit(&with(RIGHT_BALL, "inertia = 1e-6"), "mass = 0.0329", "mass = inf");
    let text = scene(LEFT_BALL, &fixed, HUNT_CROSSLEY);
    let test = "inertia_of_an_immovable_body_is_rejected_naming_the_key";
    assert_rejected(test, &text, "bodies.1.inertia", At::Line("inertia ="), &["immovable"]);
}

#[test]
fn spin_given_to_a_wall_is_rejected_naming_the_key() {
    let text = scene(LEFT_BALL, &with(WALL, "angular_velocity = [0.0, 0.0, 10.0]"), HUNT_CROSSLEY);
    let test = "spin_given_to_a_wall_is_rejected_naming_the_key";
    assert_rejected(test, &text, "bodies.1.angular_velocity", At::Line("angular_velocity ="), &["flat"]);
}

#[test]
fn a_zero_normal_is_rejected_naming_the_key() {
    let text = balls_with(&with(HUNT_CROSSLEY, "normal = [0.0, 0.0, 0.0]"));
    assert_rejected("a_zero_normal_is_rejected_naming_the_key", &text, "contact.normal", At::Line("normal ="), &[]);
}

#[test]
fn a_bad_tangential_stiffness_is_rejected_naming_the_key() {
    let text = balls_with(&with(HUNT_CROSSLEY, "friction = 0.3\ntangential_stiffness = \"stiff\""));
    let test = "a_bad_tangential_stiffness_is_rejected_naming_the_key";
    assert_rejected(test, &text, "contact.tangential_stiffness", At::Line("tangential_stiffness ="), &["mindlin"]);
}

#[test]
fn mindlin_stiffness_without_elastic_constants_is_rejected_naming_the_key() {
    let text = scene(
        &edit(LEFT_BALL, "poisson = 0.3", ""),
        RIGHT_BALL,
        "law = \"hunt-crossley\"\nrestitution = 0.8\nstiffness = 1e9\nfriction = 0.3",
    );
    let test = "mindlin_stiffness_without_elastic_constants_is_rejected_naming_the_key";
    assert_rejected(test, &text, "contact.tangential_stiffness", At::Line("[contact]"), &["poisson"]);
}

#[test]
fn negative_tangential_damping_is_rejected_naming_the_key() {
    let text = balls_with(&with(HUNT_CROSSLEY, "friction = 0.3\ntangential_damping = -1"));
    let test = "negative_tangential_damping_is_rejected_naming_the_key";
    assert_rejected(test, &text, "contact.tangential_damping", At::Line("tangential_damping ="), &[]);
}

#[test]
fn an_unknown_solver_method_is_rejected_naming_the_key() {
    let text = balls_with(HUNT_CROSSLEY) + "\n[solver]\nmethod = \"euler\"\n";
    let test = "an_unknown_solver_method_is_rejected_naming_the_key";
    assert_rejected(test, &text, "solver.method", At::Line("method ="), &["dop853"]);
}

// ---------------------------------------------------------------------------------------------------------------
// Scenes whose scales leave double precision or the bodies' size (issue 22)

/// Two 10 mm balls closing at 1 m/s while body 1 slides across at `v` m/s: their free flight overlaps by at most
/// R v0² / (|v| (|v| + v)) with R = 0.02 m — 1e-16 m and less from 1e7 m/s on, below the resolution of their
/// positions, 1e-12 of a radius (1e-14 m). Refused, naming the sliding body's velocity on its line.
#[test]
fn a_graze_too_shallow_for_double_precision_is_rejected_naming_the_velocity() {
    for (i, v) in ["1e7", "1e9", "1e20", "1e100"].into_iter().enumerate() {
        let speed: f64 = v.parse().unwrap();
        let relative = (1.0 + speed * speed).sqrt();
        let depth = 0.02 / (relative * (relative + speed));
        assert!(depth < 1e-14, "{v}: {depth}");
        let line: &'static str = Box::leak(format!("velocity = [1.0, {v}, 0.0]").into_boxed_str());
        let text = scene(&edit(LEFT_BALL, "velocity = [1.0, 0.0, 0.0]", line), RIGHT_BALL, HUNT_CROSSLEY);
        let test = format!("a_graze_too_shallow_for_double_precision_{i}");
        assert_rejected(&test, &text, "bodies.0.velocity", At::Whole(line), &["graze", "double precision"]);
    }
}

/// Hertz's stiffness of two 10 mm steel balls with E = 1e-50 Pa: K = (4/3) E* sqrt(R*) ~ 1e-51 N/m^1.5, and at
/// 2 m/s the elastic penetration (5 m* v0² / (4 K))^(2/5) is about 1e20 m — the balls would pass through each other.
/// Refused, naming the soft body's `young`.
#[test]
fn a_contact_softer_than_the_bodies_are_large_is_rejected_naming_young() {
    let young = "young = 1e-50";
    let text = scene(&edit(LEFT_BALL, "young = 2.1e11", young), RIGHT_BALL, HUNT_CROSSLEY);
    let (e_star, r_star, m_star): (f64, f64, f64) =
        (1.0 / ((1.0 - 0.09) / 1e-50 + (1.0 - 0.09) / 2.1e11), 0.005, 0.01645);
    let k = 4.0 / 3.0 * e_star * r_star.sqrt();
    let depth = (5.0 * m_star * 4.0 / (4.0 * k)).powf(0.4);
    assert!(depth > 1e19, "{depth}");
    assert_rejected("a_contact_softer_than_the_bodies", &text, "bodies.0.young", At::Whole(young), &["too soft"]);
    // A numeric stiffness is named as such.
    let stiffness = "stiffness = 1e-30";
    let text = scene(LEFT_BALL, RIGHT_BALL, &format!("{HUNT_CROSSLEY}\n{stiffness}"));
    assert_rejected("a_soft_numeric_stiffness", &text, "contact.stiffness", At::Whole(stiffness), &["too soft"]);
}

/// Issue 33's example: a 30 g ball at 1 m/s on a wall with a Hertz contact of K = 0.03 N/m^1.5 would dent it by
/// (5 m* v0² / (4 K))^(2/5) = 1.25^(2/5) = 1.0934 m, a hundred times its 10 mm radius. The message gives both as the
/// report would, three significant digits with a prefix ("1.09 m", "10 mm"), not "1.0933620739432781e0 m" and
/// "1e-2 m".
#[test]
fn a_contact_too_soft_for_its_radius_says_how_deep_as_the_report_would() {
    let (mass, speed, stiffness, radius): (f64, f64, f64, f64) = (0.03, 1.0, 0.03, 0.01);
    let depth = (5.0 * mass * speed * speed / (4.0 * stiffness)).powf(0.4);
    // Three significant digits of a depth between 1 and 10 m are its two decimals; the radius is 10 mm.
    assert!((1.0..10.0).contains(&depth), "{depth}");
    let expected = format!("its elastic penetration would be {depth:.2} m, beyond the smaller radius 10 mm");
    assert_eq!(expected, "its elastic penetration would be 1.09 m, beyond the smaller radius 10 mm");
    assert!((radius * 1e3 - 10.0).abs() < 1e-12);
    let ball = format!("radius = {radius}\nmass = {mass}\nvelocity = [{speed:?}, 0.0, 0.0]");
    let contact = "law = \"hertz\"\nstiffness = 0.03";
    let text = scene(&ball, "radius = inf\nmass = inf\nvelocity = [0.0, 0.0, 0.0]", contact);
    let test = "a_contact_too_soft_for_its_radius";
    assert_rejected(test, &text, "contact.stiffness", At::Whole("stiffness = 0.03"), &[&expected, "at 1 m/s"]);
}

/// A value a hair outside its range is echoed with the digits that show it outside: a restitution of 1.0000001 is
/// not "1", a Poisson's ratio of 0.5000001 not "0.5", a tolerance of 0.0100000001 not "0.01" (each in [0, 1],
/// (-1, 0.5] and [1e-14, 0.01] when rounded to six digits, as a value in short form is).
#[test]
fn a_value_a_hair_outside_its_range_is_echoed_with_the_digits_that_show_it() {
    let restitution = "restitution = 1.0000001";
    let text = scene(LEFT_BALL, RIGHT_BALL, &edit(HUNT_CROSSLEY, "restitution = 0.8", restitution));
    let test = "a_restitution_a_hair_above_one";
    assert_rejected(test, &text, "contact.restitution", At::Whole(restitution), &["got 1.0000001"]);
    let poisson = "poisson = 0.5000001";
    let text = scene(&edit(LEFT_BALL, "poisson = 0.3", poisson), RIGHT_BALL, HUNT_CROSSLEY);
    let test = "a_poisson_ratio_a_hair_above_a_half";
    assert_rejected(test, &text, "bodies.0.poisson", At::Whole(poisson), &["got 0.5000001"]);
    let rtol = "rtol = 0.0100000001";
    let text = format!("{}\n[solver]\n{rtol}\n", scene(LEFT_BALL, RIGHT_BALL, HUNT_CROSSLEY));
    let test = "a_tolerance_a_hair_above_a_hundredth";
    assert_rejected(test, &text, "solver.rtol", At::Whole(rtol), &["[1e-14, 0.01], got 0.0100000001"]);
}

/// A Tsuji contact ended by its force with a = 8.4e7 (zeta = a/sqrt(5) = 3.8e7, stress seed 424242's case 9628):
/// the exact e = exp(-2 (zeta/Omega) ln(zeta + Omega)), Omega = sqrt(zeta² - 1), is 1.8e-16 — a separation speed
/// below the rounding of the velocities. Refused, naming the damping; the same damping ended at zero penetration
/// (which it never reaches: a valid outcome) and a damping of zeta = 1e4 (e = 2.5e-9) are accepted.
#[test]
fn a_force_separation_too_slow_to_resolve_is_rejected_naming_the_damping() {
    let zeta: f64 = 8.4e7 / 5f64.sqrt();
    let omega = ((zeta - 1.0) * (zeta + 1.0)).sqrt();
    let e = (-2.0 * zeta / omega * (zeta + omega).ln()).exp();
    assert!(e < 1e-15, "{e}");
    let contact =
        |damping: &str, separation: &str| format!("law = \"tsuji\"\n{damping}\nseparation = \"{separation}\"");
    let text = scene(LEFT_BALL, RIGHT_BALL, &contact("damping = 8.4e7", "force"));
    assert_rejected("a_force_separation_too_slow", &text, "contact.damping", At::Whole("damping = 8.4e7"), &["1e-10"]);
    let scratch = Scratch::new("a_force_separation_too_slow_accepted");
    for (damping, separation) in [("damping = 8.4e7", "penetration"), ("damping = 22360.68", "force")] {
        let path = scratch.path().join("scene.toml");
        fs::write(&path, scene(LEFT_BALL, RIGHT_BALL, &contact(damping, separation))).unwrap();
        let output = impact(scratch.path(), &["run", path.to_str().unwrap(), "--json"]);
        assert_eq!(
            output.status.code(),
            Some(0),
            "{damping}, {separation}: {}",
            String::from_utf8_lossy(&output.stderr)
        );
    }
}

// ---------------------------------------------------------------------------------------------------------------
// World runs (docs/scene.md#worlds)

/// A valid world: a ball above a floor, and a second ball beside it, under gravity.
const WORLD: &str = r#"title = "a world"

[world]
gravity = [0.0, 0.0, -9.81]
end_time = 1.0
max_contacts = 10

[[bodies]]
name = "ball"
radius = 0.01
mass = 0.0329
position = [0.0, 0.0, 0.1]
velocity = [0.0, 0.0, 0.0]
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
name = "other ball"
radius = 0.01
mass = 0.0329
position = [0.1, 0.0, 0.05]
velocity = [0.0, 0.0, 0.0]
young = 2.1e11
poisson = 0.3

[[pair]]
bodies = [0, 1]
law = "hunt-crossley"
restitution = 0.7

[contact]
law = "hertz"
"#;

#[test]
fn the_world_scene_is_valid() {
    let scratch = Scratch::new("the_world_scene_is_valid");
    let path = scratch.path().join("world.toml");
    fs::write(&path, WORLD).unwrap();
    let output = impact(scratch.path(), &["run", path.to_str().unwrap(), "--json"]);
    assert_eq!(output.status.code(), Some(0), "{}", String::from_utf8_lossy(&output.stderr));
}

#[test]
fn a_pair_naming_a_missing_body_is_rejected_naming_the_key() {
    let text = edit(WORLD, "bodies = [0, 1]", "bodies = [0, 7]");
    assert_rejected("a_pair_naming_a_missing_body", &text, "pair.0.bodies", At::Whole("bodies = [0, 7]"), &["body 7"]);
}

#[test]
fn a_pair_of_one_body_twice_is_rejected_naming_the_key() {
    let text = edit(WORLD, "bodies = [0, 1]", "bodies = [1, 1]");
    assert_rejected(
        "a_pair_of_one_body_twice",
        &text,
        "pair.0.bodies",
        At::Whole("bodies = [1, 1]"),
        &["two different"],
    );
}

#[test]
fn overlapping_bodies_at_the_start_are_rejected_naming_the_position() {
    let text = edit(WORLD, "position = [0.1, 0.0, 0.05]", "position = [0.015, 0.0, 0.1]");
    let at = At::Whole("position = [0.015, 0.0, 0.1]");
    assert_rejected("overlapping_bodies_at_the_start", &text, "bodies.2.position", at, &["overlapped"]);
}

#[test]
fn bad_world_keys_are_rejected_naming_the_key() {
    for (test, old, new, key, mention) in [
        ("end_time_zero", "end_time = 1.0", "end_time = 0.0", "world.end_time", "> 0"),
        ("end_time_negative", "end_time = 1.0", "end_time = -2.0", "world.end_time", "> 0"),
        ("max_contacts_zero", "max_contacts = 10", "max_contacts = 0", "world.max_contacts", "whole number"),
        ("max_contacts_fraction", "max_contacts = 10", "max_contacts = 2.5", "world.max_contacts", "whole number"),
        ("gravity_two", "gravity = [0.0, 0.0, -9.81]", "gravity = [0.0, -9.81]", "world.gravity", "3 numbers"),
        ("gravity_nan", "gravity = [0.0, 0.0, -9.81]", "gravity = [0.0, 0.0, nan]", "world.gravity", "finite"),
        ("gravity_infinite", "gravity = [0.0, 0.0, -9.81]", "gravity = [inf, 0.0, 0.0]", "world.gravity", "finite"),
        ("damping_map", "max_contacts = 10", "damping_map = \"sometimes\"", "world.damping_map", "each-contact"),
        ("skin_zero", "max_contacts = 10", "skin = 0.0", "world.skin", "> 0"),
        ("skin_negative", "max_contacts = 10", "skin = -1e-3", "world.skin", "> 0"),
        ("skin_nan", "max_contacts = 10", "skin = nan", "world.skin", "not a valid value"),
    ] {
        let new: &'static str = Box::leak(new.to_string().into_boxed_str());
        assert_rejected(test, &edit(WORLD, old, new), key, At::Whole(new), &[mention]);
    }
}

#[test]
fn a_flat_body_of_a_world_needs_its_face_normal() {
    let text = edit(WORLD, "normal = [0.0, 0.0, 1.0]", "");
    assert_rejected("a_flat_body_needs_its_face", &text, "bodies.1.normal", At::Nth("[[bodies]]", 2), &["face"]);
    let text = edit(WORLD, "normal = [0.0, 0.0, 1.0]", "normal = [0.0, 0.0, 0.0]");
    assert_rejected("a_zero_face", &text, "bodies.1.normal", At::Whole("normal = [0.0, 0.0, 0.0]"), &["non-zero"]);
}

#[test]
fn a_contact_normal_in_a_world_is_rejected_naming_the_key() {
    let text = edit(WORLD, "law = \"hertz\"", "law = \"hertz\"\nnormal = [1.0, 0.0, 0.0]");
    assert_rejected(
        "a_contact_normal_in_a_world",
        &text,
        "contact.normal",
        At::Whole("normal = [1.0, 0.0, 0.0]"),
        &["geometry"],
    );
}

#[test]
fn a_pair_key_out_of_range_is_rejected_naming_the_pair() {
    let text = edit(WORLD, "restitution = 0.7", "restitution = 1.7");
    assert_rejected(
        "a_pair_key_out_of_range",
        &text,
        "pair.0.restitution",
        At::Whole("restitution = 1.7"),
        &["[0, 1]"],
    );
}

/// Friction in a world takes the Mindlin tangential stiffness by default, which needs every elastic body's `young` and
/// `poisson`: a world whose law has its own stiffness (so Hertz needs neither) but whose ball lacks `poisson` is
/// refused before anything moves, naming the key that chose Mindlin.
#[test]
fn friction_in_a_world_without_the_elastic_constants_mindlin_needs_is_refused() {
    let text = edit(WORLD, "law = \"hertz\"", "law = \"hertz\"\nstiffness = 1e9\nfriction = 0.3");
    // (The ball is the first body: its `poisson` goes.)
    let text = text.replacen("young = 2.1e11\npoisson = 0.3\n", "young = 2.1e11\n", 1);
    assert_rejected(
        "friction_in_a_world_without_mindlin_constants",
        &text,
        "contact.tangential_stiffness",
        At::Nowhere,
        &["Mindlin", "bodies.0 lacks"],
    );
}

// ---------------------------------------------------------------------------------------------------------------
// The elastic–plastic law (`thornton`) and yield

/// A valid `thornton` contact.
const THORNTON: &str = "law = \"thornton\"\nyield_pressure = 1.6e9";

#[test]
fn the_thornton_scene_is_valid() {
    let scratch = Scratch::new("the_thornton_scene_is_valid");
    let path = scratch.path().join("thornton.toml");
    fs::write(&path, scene(LEFT_BALL, RIGHT_BALL, THORNTON)).unwrap();
    let output = impact(scratch.path(), &["run", path.to_str().unwrap()]);
    assert_eq!(output.status.code(), Some(0), "{}", String::from_utf8_lossy(&output.stderr));
}

#[test]
fn a_yield_pressure_that_is_not_positive_is_rejected() {
    for (i, bad) in ["yield_pressure = 0.0", "yield_pressure = -1e9", "yield_pressure = nan"].into_iter().enumerate() {
        let text = scene(LEFT_BALL, RIGHT_BALL, &edit(THORNTON, "yield_pressure = 1.6e9", bad));
        assert_rejected(
            &format!("yield_pressure_not_positive_{i}"),
            &text,
            "contact.yield_pressure",
            At::Whole(bad),
            &[],
        );
    }
}

#[test]
fn a_yield_pressure_for_a_law_that_does_not_yield_is_rejected() {
    let text = scene(LEFT_BALL, RIGHT_BALL, &with(HUNT_CROSSLEY, "yield_pressure = 1.6e9"));
    let test = "yield_pressure_for_a_law_that_does_not_yield";
    assert_rejected(test, &text, "contact.yield_pressure", At::Line("yield_pressure"), &["hunt-crossley", "thornton"]);
}

#[test]
fn thornton_without_a_yield_pressure_or_yield_stress_is_rejected() {
    let text = scene(LEFT_BALL, RIGHT_BALL, "law = \"thornton\"");
    let test = "thornton_without_a_yield_pressure";
    assert_rejected(test, &text, "contact.yield_pressure", At::Line("[contact]"), &["yield_stress"]);
}

#[test]
fn thornton_takes_no_damping() {
    let text = scene(LEFT_BALL, RIGHT_BALL, &with(THORNTON, "restitution = 0.8"));
    assert_rejected("thornton_takes_no_restitution", &text, "contact.restitution", At::Line("restitution"), &[]);
    let text = scene(LEFT_BALL, RIGHT_BALL, &with(THORNTON, "damping = 0.1"));
    assert_rejected("thornton_takes_no_damping", &text, "contact.damping", At::Line("damping"), &[]);
}

#[test]
fn a_yield_stress_that_is_not_positive_is_rejected() {
    let text = scene(&with(LEFT_BALL, "yield_stress = 0.0"), RIGHT_BALL, HUNT_CROSSLEY);
    assert_rejected("yield_stress_not_positive", &text, "bodies.0.yield_stress", At::Line("yield_stress"), &[]);
}

/// A world's contact under `thornton` needs a yield pressure (or a yield stress) like one impact's: refused naming the
/// key, renamed to the pair that names the law.
#[test]
fn thornton_in_a_world_without_a_yield_pressure_is_refused() {
    let text = edit(&edit(WORLD, "law = \"hunt-crossley\"", "law = \"thornton\""), "restitution = 0.7", "");
    let test = "thornton_in_a_world_without_a_yield_pressure";
    assert_rejected(test, &text, "pair.0.yield_pressure", At::Nowhere, &["yield_stress"]);
}

/// A yield pressure so low that the plastic penetration (by energy, Thornton's loading line) would pass the radius:
/// refused naming the key, like a contact too soft for its bodies. (1 Pa under two steel balls at 1 m/s: the line's
/// slope pi p_y R* = 0.016 N/m takes the ball's 33 mJ over metres.)
#[test]
fn a_yield_pressure_too_low_for_the_bodies_is_refused() {
    let text = scene(LEFT_BALL, RIGHT_BALL, &edit(THORNTON, "yield_pressure = 1.6e9", "yield_pressure = 1.0"));
    let test = "yield_pressure_too_low";
    assert_rejected(test, &text, "contact.yield_pressure", At::Whole("yield_pressure = 1.0"), &["radius"]);
}

// ---------------------------------------------------------------------------------------------------------------
// Rigid bodies struck off their centre (docs/rigid.md)

/// A rod (body 2) hung at the origin with its rounded lower end, struck by the left ball: valid as it stands.
const HUNG_ROD: &str = r#"name = "rod"
mass = 8.0
radius = 0.01
inertia = [0.96, 0.0001, 0.96]
position = [0.0, -0.6, 0.0]
contact_offset = [0.0, -0.6, 0.0]
pivot = [0.0, 0.0, 0.0]
velocity = [0.0, 0.0, 0.0]
young = 2.1e11
poisson = 0.3"#;

/// The left ball placed to strike the rod's end.
fn striker() -> String {
    with(LEFT_BALL, "position = [-0.05, -1.2, 0.0]")
}

#[test]
fn the_hung_rod_scene_is_valid() {
    let scratch = Scratch::new("the_hung_rod_scene_is_valid");
    let path = scratch.path().join("rod.toml");
    fs::write(&path, scene(&striker(), HUNG_ROD, HUNT_CROSSLEY)).unwrap();
    let output = impact(scratch.path(), &["run", path.to_str().unwrap()]);
    assert_eq!(output.status.code(), Some(0), "{}", String::from_utf8_lossy(&output.stderr));
}

#[test]
fn an_inertia_tensor_that_is_not_symmetric_positive_definite_is_rejected() {
    let cases = [
        ("not_symmetric", "inertia = [[0.96, 0.1, 0.0], [0.0, 0.0001, 0.0], [0.0, 0.0, 0.96]]", "symmetric"),
        ("not_positive", "inertia = [0.96, -0.0001, 0.96]", "positive definite"),
        ("indefinite", "inertia = [[1.0, 2.0, 0.0], [2.0, 1.0, 0.0], [0.0, 0.0, 1.0]]", "positive definite"),
        ("no_mass_distribution", "inertia = [0.1, 0.1, 0.5]", "sum of the other two"),
        ("not_finite", "inertia = [0.96, inf, 0.96]", "finite"),
    ];
    for (name, bad, mentions) in cases {
        let text = scene(&striker(), &edit(HUNG_ROD, "inertia = [0.96, 0.0001, 0.96]", bad), HUNT_CROSSLEY);
        assert_rejected(&format!("inertia_{name}"), &text, "bodies.1.inertia", At::Whole(bad), &[mentions]);
    }
    let bad = "inertia = [[0.96, 0.0], [0.0, 0.96]]";
    let text = scene(&striker(), &edit(HUNG_ROD, "inertia = [0.96, 0.0001, 0.96]", bad), HUNT_CROSSLEY);
    assert_rejected("inertia_two_by_two", &text, "bodies.1.inertia", At::Whole(bad), &["3×3 tensor"]);
}

#[test]
fn a_pivot_on_an_immovable_body_is_rejected() {
    let wall = "radius = inf\nmass = inf\nvelocity = [0.0, 0.0, 0.0]\npivot = [0.0, 0.0, 0.0]";
    let text = scene(LEFT_BALL, wall, HUNT_CROSSLEY);
    assert_rejected("pivot_on_a_wall", &text, "bodies.1.pivot", At::Line("pivot"), &["immovable"]);
    let fixed = "radius = 0.01\nmass = inf\nvelocity = [0.0, 0.0, 0.0]\npivot = [0.0, 0.0, 0.0]";
    let text = scene(LEFT_BALL, fixed, HUNT_CROSSLEY);
    assert_rejected("pivot_on_a_fixed_sphere", &text, "bodies.1.pivot", At::Line("pivot"), &["immovable"]);
}

#[test]
fn a_contact_offset_on_a_wall_is_rejected() {
    let wall = "radius = inf\nmass = 10.0\nvelocity = [0.0, 0.0, 0.0]\ncontact_offset = [0.0, 0.1, 0.0]";
    let text = scene(LEFT_BALL, wall, HUNT_CROSSLEY);
    assert_rejected("offset_on_a_wall", &text, "bodies.1.contact_offset", At::Line("contact_offset"), &["flat"]);
}

#[test]
fn a_pivoted_body_must_move_as_its_turning_and_have_positions() {
    let moving = edit(HUNG_ROD, "velocity = [0.0, 0.0, 0.0]", "velocity = [1.0, 0.0, 0.0]");
    let text = scene(&striker(), &moving, HUNT_CROSSLEY);
    assert_rejected("pivoted_body_moving", &text, "bodies.1.velocity", At::Nth("velocity", 2), &["pivot"]);
    let unplaced = edit(HUNG_ROD, "position = [0.0, -0.6, 0.0]", "");
    let text = scene(LEFT_BALL, &unplaced, HUNT_CROSSLEY);
    assert_rejected("pivot_without_positions", &text, "bodies.1.pivot", At::Line("pivot"), &["position"]);
}

#[test]
fn an_eccentric_body_spinning_before_contact_is_rejected() {
    let spinning = with(&edit(HUNG_ROD, "pivot = [0.0, 0.0, 0.0]", ""), "angular_velocity = [0.0, 0.0, 1.0]");
    let text = scene(&striker(), &spinning, HUNT_CROSSLEY);
    let test = "eccentric_body_spinning_in_flight";
    assert_rejected(test, &text, "bodies.1.angular_velocity", At::Line("angular_velocity"), &["first contact"]);
}

/// A rod of two end spheres in a world (docs/scene.md#rigid-bodies-in-a-world): each test breaks one of its rules.
const CLUMP_WORLD: &str = r#"title = "a rod over a floor"

[world]
gravity = [0.0, 0.0, -9.81]

[[bodies]]
name = "rod"
mass = 0.2
inertia = [1e-6, 6.7e-4, 6.7e-4]
position = [0.0, 0.0, 0.1]
velocity = [0.0, 0.0, -1.0]
young = 2.1e11
poisson = 0.3

[[bodies.spheres]]
offset = [0.1, 0.0, 0.0]
radius = 0.005

[[bodies.spheres]]
offset = [-0.1, 0.0, 0.0]
radius = 0.005

[[bodies]]
name = "floor"
radius = inf
mass = inf
position = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
velocity = [0.0, 0.0, 0.0]
young = 2.1e11
poisson = 0.3

[contact]
law = "hunt-crossley"
restitution = 0.8
"#;

#[test]
fn a_rod_of_two_spheres_in_a_world_is_valid() {
    let scratch = Scratch::new("a_rod_of_two_spheres_in_a_world_is_valid");
    let path = scratch.path().join("rod.toml");
    fs::write(&path, edit(CLUMP_WORLD, "gravity = [0.0, 0.0, -9.81]", "gravity = [0.0, 0.0, -9.81]\nend_time = 0.01"))
        .unwrap();
    let output = impact(scratch.path(), &["run", path.to_str().unwrap()]);
    assert_eq!(output.status.code(), Some(0), "{}", String::from_utf8_lossy(&output.stderr));
}

#[test]
fn a_clump_without_its_inertia_is_rejected() {
    let text = edit(CLUMP_WORLD, "inertia = [1e-6, 6.7e-4, 6.7e-4]", "");
    assert_rejected("clump_without_inertia", &text, "bodies.0.inertia", At::Nth("[[bodies]]", 1), &["inertia"]);
}

#[test]
fn a_clump_with_a_radius_or_a_density_is_rejected() {
    let text = edit(CLUMP_WORLD, "mass = 0.2", "mass = 0.2\nradius = 0.01");
    assert_rejected("clump_with_radius", &text, "bodies.0.radius", At::Whole("radius = 0.01"), &["spheres"]);
    let text = edit(CLUMP_WORLD, "mass = 0.2", "density = 7850.0");
    assert_rejected("clump_with_density", &text, "bodies.0.density", At::Line("density"), &["mass"]);
}

#[test]
fn a_sphere_of_a_clump_with_a_bad_radius_or_overlapping_the_floor_is_rejected() {
    let text = edit(CLUMP_WORLD, "offset = [0.1, 0.0, 0.0]", "offset = [0.1, 0.0, 0.0]\nradius = -0.005").replacen(
        "radius = -0.005\nradius = 0.005",
        "radius = -0.005",
        1,
    );
    assert_rejected("clump_sphere_radius", &text, "bodies.0.spheres.0.radius", At::Line("radius = -0.005"), &["> 0"]);
    let text = edit(CLUMP_WORLD, "offset = [-0.1, 0.0, 0.0]", "offset = [-0.1, 0.0, -0.0999]");
    assert_rejected("clump_sphere_overlapping", &text, "bodies.1.position", At::Nth("position", 2), &["sphere 1"]);
}

#[test]
fn a_pivoted_body_of_a_world_moving_other_than_it_turns_is_rejected() {
    let text = edit(CLUMP_WORLD, "position = [0.0, 0.0, 0.1]", "position = [0.0, 0.0, 0.1]\npivot = [0.1, 0.0, 0.1]");
    assert_rejected("pivot_velocity", &text, "bodies.0.velocity", At::Line("velocity = [0.0, 0.0, -1.0]"), &["pivot"]);
}

// ---------------------------------------------------------------------------------------------------------------
// The simulators' laws: `mujoco`, `adams-impact`, `hertz-dashpot`

#[test]
fn mujoco_without_solref_or_with_mixed_signs_is_rejected() {
    let text = scene(LEFT_BALL, RIGHT_BALL, "law = \"mujoco\"");
    assert_rejected("mujoco_without_solref", &text, "contact.solref", At::Line("[contact]"), &["timeconst"]);
    let bad = "solref = [0.02, -1.0]";
    let text = scene(LEFT_BALL, RIGHT_BALL, &format!("law = \"mujoco\"\n{bad}"));
    assert_rejected("mujoco_mixed_solref", &text, "contact.solref", At::Whole(bad), &["-stiffness"]);
    let bad = "solref = [0.02]";
    let text = scene(LEFT_BALL, RIGHT_BALL, &format!("law = \"mujoco\"\n{bad}"));
    assert_rejected("mujoco_short_solref", &text, "contact.solref", At::Whole(bad), &["2 numbers"]);
}

#[test]
fn solimp_outside_mujocos_own_ranges_is_rejected() {
    for (i, (bad, mentions)) in [
        ("solimp = [1.2, 0.95, 0.001, 0.5, 2.0]", "dmin"),
        ("solimp = [0.9, 0.0, 0.001, 0.5, 2.0]", "dmax"),
        ("solimp = [0.9, 0.95, 0.0, 0.5, 2.0]", "width"),
        ("solimp = [0.9, 0.95, 0.001, 1.0, 2.0]", "midpoint"),
        ("solimp = [0.9, 0.95, 0.001, 0.5, 0.5]", "power"),
        ("solimp = [0.9, 0.95, 0.001, 0.5]", "5 numbers"),
    ]
    .into_iter()
    .enumerate()
    {
        let text = scene(LEFT_BALL, RIGHT_BALL, &format!("law = \"mujoco\"\nsolref = [0.02, 1.0]\n{bad}"));
        assert_rejected(&format!("solimp_out_of_range_{i}"), &text, "contact.solimp", At::Whole(bad), &[mentions]);
    }
}

#[test]
fn the_simulators_keys_belong_to_their_laws() {
    let text = scene(LEFT_BALL, RIGHT_BALL, &with(HUNT_CROSSLEY, "solref = [0.02, 1.0]"));
    assert_rejected("solref_for_hunt_crossley", &text, "contact.solref", At::Line("solref"), &["mujoco"]);
    let text = scene(LEFT_BALL, RIGHT_BALL, &with(HUNT_CROSSLEY, "cmax = 100.0"));
    assert_rejected("cmax_for_hunt_crossley", &text, "contact.cmax", At::Line("cmax"), &["adams-impact"]);
    let text = scene(LEFT_BALL, RIGHT_BALL, "law = \"mujoco\"\nsolref = [0.02, 1.0]\nrestitution = 0.8");
    assert_rejected("mujoco_with_restitution", &text, "contact.restitution", At::Line("restitution"), &["solref"]);
}

#[test]
fn adams_impact_needs_cmax_and_a_positive_dmax() {
    let text = scene(LEFT_BALL, RIGHT_BALL, "law = \"adams-impact\"\ndmax = 1e-4");
    assert_rejected("adams_without_cmax", &text, "contact.cmax", At::Line("[contact]"), &["N s/m"]);
    let bad = "dmax = 0.0";
    let text = scene(LEFT_BALL, RIGHT_BALL, &format!("law = \"adams-impact\"\ncmax = 100.0\n{bad}"));
    assert_rejected("adams_zero_dmax", &text, "contact.dmax", At::Whole(bad), &[]);
}

#[test]
fn hertz_dashpot_restitution_zero_is_out_of_reach() {
    // Exponent 3/2: the c for e is found by simulation, and no finite c gives e = 0.
    let text = scene(LEFT_BALL, RIGHT_BALL, "law = \"hertz-dashpot\"\nrestitution = 0.0");
    let test = "hertz_dashpot_restitution_zero";
    assert_rejected(test, &text, "contact.restitution", At::Line("restitution"), &["infinite c"]);
}
