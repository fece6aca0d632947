//! A corpus of hostile scene files (issue 6 part 4), beside the 127 cases of `bad_scenes.rs` and of the classes they
//! lack: empty and blank files, non-UTF-8 bytes, NUL and control characters, syntax errors of every kind, wrong
//! types (booleans, tables, dates, strings, nested arrays), huge and tiny numbers, derived quantities outside double
//! precision, contradictory and misplaced keys, hundreds of bodies, huge files generated here. Each must exit 2 with
//! nothing on stdout and no panic, naming the file — and the key and line where they can be known (the expected line
//! is counted here from the text written, not copied from the program).

mod common;
use common::binary::{Scratch, impact};
use std::fs;

/// A valid scene, each line unique so that one can be swapped for a hostile one.
const BASE: &str = "title = \"corpus base\"\n\
[[bodies]]\n\
radius = 0.01\n\
mass = 0.03\n\
velocity = [1.0, 0.0, 0.0]\n\
[[bodies]]\n\
radius = inf\n\
mass = inf\n\
velocity = [0.0, 0.0, 0.0]\n\
[contact]\n\
law = \"hunt-crossley\"\n\
restitution = 0.8\n\
stiffness = 1e9\n\
[solver]\n\
rtol = 1e-10\n";

/// `BASE` with its line `old` replaced by `new` (several lines allowed).
fn swap(old: &str, new: &str) -> Vec<u8> {
    assert_eq!(BASE.lines().filter(|l| *l == old).count(), 1, "no single line `{old}`");
    BASE.lines().map(|l| if l == old { new } else { l }).collect::<Vec<_>>().join("\n").into_bytes()
}

/// `BASE` with `extra` appended.
fn plus(extra: &str) -> Vec<u8> {
    format!("{BASE}{extra}\n").into_bytes()
}

/// One hostile file: its bytes, the key the message must name (if any), and the line (1-based) it must give (if
/// known).
struct Case {
    name: &'static str,
    bytes: Vec<u8>,
    key: Option<&'static str>,
    line: Option<usize>,
}

fn case(name: &'static str, bytes: Vec<u8>, key: Option<&'static str>, line: Option<usize>) -> Case {
    Case { name, bytes, key, line }
}

/// The 1-based line of `BASE` that is `text` (after a swap the line numbers of the rest stay).
fn line_of(text: &str) -> Option<usize> {
    BASE.lines().position(|l| l == text).map(|i| i + 1)
}

fn corpus() -> Vec<Case> {
    let velocity = line_of("velocity = [1.0, 0.0, 0.0]");
    let mass = line_of("mass = 0.03");
    let radius = line_of("radius = 0.01");
    let restitution = line_of("restitution = 0.8");
    let stiffness = line_of("stiffness = 1e9");
    let law = line_of("law = \"hunt-crossley\"");
    let rtol = line_of("rtol = 1e-10");
    let mut cases = vec![
        // Empty, blank, comments only.
        case("empty", Vec::new(), Some("bodies"), None),
        case("blank", b"\n\n   \n\t\n".to_vec(), Some("bodies"), None),
        case("comments_only", b"# a scene\n# nothing else\n".to_vec(), Some("bodies"), None),
        case("title_only", b"title = \"x\"\n".to_vec(), Some("bodies"), None),
        // Not UTF-8, NUL, control characters, a byte-order mark in the middle.
        case(
            "latin1_title",
            {
                let mut b = BASE.as_bytes().to_vec();
                b.splice(9..9, [0xE9u8, 0xFF]);
                b
            },
            None,
            None,
        ),
        case("invalid_utf8_start", [&[0xC3u8, 0x28][..], BASE.as_bytes()].concat(), None, None),
        case(
            "lone_continuation_byte",
            plus("\u{0}").into_iter().map(|c| if c == 0 { 0x80 } else { c }).collect(),
            None,
            None,
        ),
        case("nul_byte", swap("mass = 0.03", "mass = 0.0\u{0}3"), Some("bodies.0.mass"), mass),
        case("control_character", swap("mass = 0.03", "mass = \u{7}0.03"), Some("bodies.0.mass"), mass),
        case("bom_in_the_middle", swap("mass = 0.03", "\u{feff}mass = 0.03"), None, mass),
        case("utf16", BASE.encode_utf16().flat_map(|u| u.to_le_bytes()).collect(), None, None),
        // Syntax errors.
        // (A syntax error is told where the parser meets it: for an unclosed array, the next line.)
        case(
            "unclosed_array",
            swap("velocity = [1.0, 0.0, 0.0]", "velocity = [1.0, 0.0, 0.0"),
            None,
            velocity.map(|l| l + 1),
        ),
        case("missing_value", swap("mass = 0.03", "mass ="), Some("bodies.0.mass"), mass),
        case("unterminated_string", swap("law = \"hunt-crossley\"", "law = \"hunt-crossley"), Some("contact.law"), law),
        case("bad_escape", swap("law = \"hunt-crossley\"", "law = \"hunt\\q\""), Some("contact.law"), law),
        case("unclosed_table_header", swap("[contact]", "[contact"), None, line_of("[contact]")),
        case("key_without_equals", swap("mass = 0.03", "mass 0.03"), None, mass),
        case("two_values_on_a_line", swap("mass = 0.03", "mass = 0.03 0.04"), Some("bodies.0.mass"), mass),
        case("duplicate_table", plus("[contact]\nlaw = \"hertz\""), None, Some(BASE.lines().count() + 1)),
        case("table_redefined_as_key", plus("contact = 3"), None, Some(BASE.lines().count() + 1)),
        case("dotted_key_clash", swap("mass = 0.03", "mass.value = 0.03"), Some("bodies.0.mass.value"), mass),
        case("number_with_two_points", swap("mass = 0.03", "mass = 0.0.3"), Some("bodies.0.mass"), mass),
        case("leading_zero", swap("mass = 0.03", "mass = 003"), Some("bodies.0.mass"), mass),
        case("trailing_comma_in_inline_table", plus("[output]\nseries = { a = 1, }"), None, None),
        // Wrong types.
        case("bool_mass", swap("mass = 0.03", "mass = true"), Some("bodies.0.mass"), mass),
        case(
            "table_velocity",
            swap("velocity = [1.0, 0.0, 0.0]", "velocity = { x = 1.0 }"),
            Some("bodies.0.velocity"),
            velocity,
        ),
        case(
            "string_vector_items",
            swap("velocity = [1.0, 0.0, 0.0]", "velocity = [\"1\", \"0\", \"0\"]"),
            Some("bodies.0.velocity"),
            velocity,
        ),
        case(
            "nested_array",
            swap("velocity = [1.0, 0.0, 0.0]", "velocity = [[1.0], [0.0], [0.0]]"),
            Some("bodies.0.velocity"),
            velocity,
        ),
        case("date_radius", swap("radius = 0.01", "radius = 1979-05-27"), Some("bodies.0.radius"), radius),
        case("string_tolerance", swap("rtol = 1e-10", "rtol = \"1e-10\""), Some("solver.rtol"), rtol),
        case("number_law", swap("law = \"hunt-crossley\"", "law = 3"), Some("contact.law"), law),
        case("array_of_laws", swap("law = \"hunt-crossley\"", "law = [\"hertz\"]"), Some("contact.law"), law),
        case("bool_stiffness", swap("stiffness = 1e9", "stiffness = false"), Some("contact.stiffness"), stiffness),
        case(
            "table_stiffness",
            swap("stiffness = 1e9", "stiffness = { value = 1e9 }"),
            Some("contact.stiffness"),
            stiffness,
        ),
        case(
            "bodies_as_a_table",
            b"[bodies]\nradius = 1\n[contact]\nlaw = \"hertz\"\n".to_vec(),
            Some("bodies"),
            Some(1),
        ),
        case("solver_as_an_array", plus("[[solver]]\nrtol = 1e-9"), None, Some(BASE.lines().count() + 1)),
        case("title_number", swap("title = \"corpus base\"", "title = 7"), Some("title"), Some(1)),
        case(
            "separation_bool",
            swap("stiffness = 1e9", "stiffness = 1e9\nseparation = true"),
            Some("contact.separation"),
            stiffness.map(|l| l + 1),
        ),
        // Case and spelling.
        case("law_in_capitals", swap("law = \"hunt-crossley\"", "law = \"Hunt-Crossley\""), Some("contact.law"), law),
        case("law_with_spaces", swap("law = \"hunt-crossley\"", "law = \" hunt-crossley \""), Some("contact.law"), law),
        case(
            "hertz_in_capitals",
            swap("stiffness = 1e9", "stiffness = \"HERTZ\""),
            Some("contact.stiffness"),
            stiffness,
        ),
        // Huge and tiny numbers.
        case("mass_overflows_to_inf", swap("mass = 0.03", "mass = 1e400"), Some("bodies.0.mass"), mass),
        case(
            "huge_velocity",
            swap("velocity = [1.0, 0.0, 0.0]", "velocity = [1e200, 0.0, 0.0]"),
            Some("bodies.0.velocity"),
            velocity,
        ),
        case("huge_integer", swap("mass = 0.03", "mass = 99999999999999999999999999"), Some("bodies.0.mass"), mass),
        case("subnormal_mass", swap("mass = 0.03", "mass = 5e-324"), None, None),
        case("negative_zero_mass", swap("mass = 0.03", "mass = -0.0"), Some("bodies.0.mass"), mass),
        case("tiny_stiffness", swap("stiffness = 1e9", "stiffness = 1e-320"), None, None),
        case(
            "relative_velocity_overflows",
            {
                let text =
                    String::from_utf8(swap("velocity = [0.0, 0.0, 0.0]", "velocity = [-1.7e308, 0.0, 0.0]")).unwrap();
                text.replace("radius = inf\nmass = inf", "radius = 0.01\nmass = 1e-300").into_bytes()
            },
            None,
            None,
        ),
        case("too_heavy_damping", swap("restitution = 0.8", "damping = 1e300"), Some("contact.damping"), restitution),
        case("nan_spelled_with_sign", swap("mass = 0.03", "mass = +nan"), Some("bodies.0.mass"), mass),
        case(
            "inf_velocity_component",
            swap("velocity = [1.0, 0.0, 0.0]", "velocity = [inf, -inf, nan]"),
            Some("bodies.0.velocity"),
            velocity,
        ),
        case(
            "poisson_minus_one",
            swap("mass = 0.03", "mass = 0.03\npoisson = -1.0"),
            Some("bodies.0.poisson"),
            mass.map(|l| l + 1),
        ),
        // Contradictions and misplaced keys.
        case(
            "restitution_and_damping",
            swap("restitution = 0.8", "restitution = 0.8\ndamping = 0.1"),
            Some("contact.damping"),
            None,
        ),
        case("inertia_of_a_wall", swap("mass = inf", "mass = inf\ninertia = 1.0"), Some("bodies.1.inertia"), None),
        case(
            "law_in_a_body",
            swap("mass = 0.03", "mass = 0.03\nlaw = \"hertz\""),
            Some("bodies.0.law"),
            mass.map(|l| l + 1),
        ),
        case(
            "mass_in_contact",
            swap("stiffness = 1e9", "stiffness = 1e9\nmass = 1.0"),
            Some("contact.mass"),
            stiffness.map(|l| l + 1),
        ),
        case("unknown_solver_key", plus("[solver]\nmethod = \"rk4\""), None, None),
        case("unknown_top_level_key", plus("gravity = 9.81"), Some("gravity"), Some(BASE.lines().count() + 1)),
        case(
            "unknown_output_key",
            plus("[output]\nformat = \"png\""),
            Some("output.format"),
            Some(BASE.lines().count() + 2),
        ),
        case(
            "three_bodies",
            plus("[[bodies]]\nradius = 0.01\nmass = 1.0\nvelocity = [0.0, 0.0, 0.0]"),
            Some("bodies.0.position"),
            None,
        ),
        case(
            "position_for_one_body",
            swap("mass = 0.03", "mass = 0.03\nposition = [0.0, 0.0, 0.0]"),
            Some("bodies.1.position"),
            None,
        ),
        case(
            "spinning_wall",
            swap("mass = inf", "mass = inf\nangular_velocity = [1.0, 0.0, 0.0]"),
            Some("bodies.1.angular_velocity"),
            None,
        ),
        case("zero_normal", plus("[contact.normal]\n"), None, None),
        // Numbers the messages compute (issue 33): a dent deeper than the radius, bodies that start overlapped.
        case(
            "too_soft_for_the_radius",
            swap("stiffness = 1e9", "stiffness = 0.03"),
            Some("contact.stiffness"),
            stiffness,
        ),
        case(
            "bodies_start_overlapped",
            {
                let text = String::from_utf8(swap(
                    "velocity = [1.0, 0.0, 0.0]",
                    "velocity = [1.0, 0.0, 0.0]\nposition = [0.0, 0.0, 0.0]",
                ))
                .unwrap();
                text.replace(
                    "radius = inf\nmass = inf\nvelocity = [0.0, 0.0, 0.0]",
                    "radius = 0.01\nmass = 0.03\nvelocity = [0.0, 0.0, 0.0]\nposition = [0.0199, 0.0, 0.0]",
                )
                .into_bytes()
            },
            Some("bodies.1.position"),
            None,
        ),
    ];
    cases.extend(hostile_worlds());
    // Hundreds of bodies.
    let mut many = String::from(BASE);
    for _ in 0..500 {
        many.push_str("[[bodies]]\nradius = 0.01\nmass = 1.0\nvelocity = [0.0, 0.0, 0.0]\n");
    }
    cases.push(case("five_hundred_bodies", many.into_bytes(), Some("bodies.0.position"), None));
    // Deeply nested arrays.
    let depth = 10_000;
    cases.push(case(
        "deeply_nested_arrays",
        swap("velocity = [1.0, 0.0, 0.0]", &format!("velocity = {}{}", "[".repeat(depth), "]".repeat(depth))),
        None,
        None,
    ));
    // A long line: a title of a million characters, and a key of ten thousand.
    cases.push(case("million_character_title", plus(&format!("law2 = \"{}\"", "x".repeat(1_000_000))), None, None));
    cases.push(case("ten_thousand_character_key", plus(&format!("{} = 1", "k".repeat(10_000))), None, None));
    // Huge files: 20 MB of comments before a bad value (the line counted through all of them), and 5 MB of digits.
    let comments = 400_000;
    let mut big = "# padding line of a huge scene file\n".repeat(comments);
    big.push_str(&String::from_utf8(swap("mass = 0.03", "mass = -1.0")).unwrap());
    cases.push(case("huge_file_of_comments", big.into_bytes(), Some("bodies.0.mass"), mass.map(|l| l + comments)));
    cases.push(case(
        "five_million_digit_number",
        swap("mass = 0.03", &format!("mass = 1{}", "0".repeat(5_000_000))),
        Some("bodies.0.mass"),
        mass,
    ));
    cases
}

/// A model scene of `models/` with the line `old` of its body `body` (0-based, in its `[[bodies]]` order) replaced by
/// `new`, and the 1-based line of the replacement (counted here in the text).
fn model_swap(model: &str, body: usize, old: &str, new: &str) -> (Vec<u8>, usize) {
    let path = format!("{}/models/{model}", env!("CARGO_MANIFEST_DIR"));
    let text = fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    let mut seen = 0;
    let mut at = None;
    for (n, line) in lines.iter().enumerate() {
        if line.trim() == "[[bodies]]" {
            seen += 1;
        } else if seen == body + 1 && line.trim() == old && at.is_none() {
            at = Some(n);
        }
    }
    let at = at.unwrap_or_else(|| panic!("{model}: no line `{old}` in body {body}"));
    lines[at] = new.to_string();
    (lines.join("\n").into_bytes(), at + 1)
}

/// The world scenes of issue 33 that ran for minutes or reported nulls: each is refused before any work, naming the
/// key and its line.
fn hostile_worlds() -> Vec<Case> {
    let worlds = [
        // A ball of the stack at 1e300 m/s ran for more than 5 minutes: its kinetic energy is beyond double precision.
        (
            "world_stack_ball_at_1e300",
            "ball-stack.toml",
            2,
            "velocity = [0.0, 0.0, 0.0]",
            "velocity = [0.0, 1e300, 0.0]",
            "bodies.2.velocity",
        ),
        // The cradle at 1e300 m/s exited 0 with its energies null.
        (
            "world_cradle_at_1e300",
            "newtons-cradle-5.toml",
            0,
            "velocity = [1.0, 0.0, 0.0]",
            "velocity = [1e300, 0.0, 0.0]",
            "bodies.0.velocity",
        ),
        (
            "world_cradle_spinning_at_1e300",
            "newtons-cradle-5.toml",
            0,
            "velocity = [1.0, 0.0, 0.0]",
            "angular_velocity = [0.0, 0.0, 1e300]\nvelocity = [1.0, 0.0, 0.0]",
            "bodies.0.angular_velocity",
        ),
        // A cradle ball of radius 1e-100 among 10 mm ones at 20 mm spacing ran past 20 s: its contact is far below
        // the rounding of the positions.
        (
            "world_cradle_ball_of_1e-100_m",
            "newtons-cradle-5.toml",
            0,
            "radius = 0.01",
            "radius = 1e-100",
            "bodies.0.radius",
        ),
        // At 9.2e18 m/s a Hertzian steel contact would penetrate beyond the radii: too soft at the speed in play.
        (
            "world_cradle_at_9.2e18",
            "newtons-cradle-5.toml",
            0,
            "velocity = [1.0, 0.0, 0.0]",
            "velocity = [9.2e18, 0.0, 0.0]",
            "bodies.0.young",
        ),
    ];
    worlds
        .into_iter()
        .map(|(name, model, body, old, new, key)| {
            let (bytes, line) = model_swap(model, body, old, new);
            // (The key's line: the swapped one, or for the stiffness the physics blames, ball 0's `young`.)
            let line = if key.ends_with(".young") {
                String::from_utf8_lossy(&bytes).lines().position(|l| l.trim().starts_with("young")).map(|i| i + 1)
            } else {
                Some(line)
            };
            case(name, bytes, Some(key), line)
        })
        .collect()
}

#[test]
fn the_corpus_has_at_least_sixty_hostile_scenes() {
    let cases = corpus();
    assert!(cases.len() >= 60, "{} cases", cases.len());
    let mut names: Vec<_> = cases.iter().map(|c| c.name).collect();
    names.sort_unstable();
    names.dedup();
    assert_eq!(names.len(), cases.len(), "case names are unique");
    // The base scene itself is valid: every case is hostile because of its one change.
    let scratch = Scratch::new("base_is_valid");
    let path = scratch.path().join("base.toml");
    fs::write(&path, BASE).unwrap();
    let output = impact(scratch.path(), &["run", path.to_str().unwrap(), "--json"]);
    assert_eq!(output.status.code(), Some(0), "{}", String::from_utf8_lossy(&output.stderr));
}

/// The corpus as files for the Python package's tests (python/tests/test_errors.py runs each through `impact.run`):
/// `target/hostile-corpus/NAME.toml` and `manifest.json`, a list of `{ "name", "file", "key", "line" }` with the key
/// and line each message must name (null where none is asserted).
#[test]
fn the_corpus_is_written_for_the_python_tests() {
    let folder = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("target").join("hostile-corpus");
    fs::create_dir_all(&folder).expect("create target/hostile-corpus");
    let mut manifest = Vec::new();
    for case in corpus() {
        let file = format!("{}.toml", case.name);
        fs::write(folder.join(&file), &case.bytes).expect("write a hostile scene");
        manifest.push(serde_json::json!({ "name": case.name, "file": file, "key": case.key, "line": case.line }));
    }
    let text = serde_json::to_string_pretty(&manifest).expect("the manifest as JSON");
    fs::write(folder.join("manifest.json"), text).expect("write the manifest");
}

#[test]
fn every_hostile_scene_exits_2_naming_the_problem() {
    let scratch = Scratch::new("every_hostile_scene");
    let mut failures = Vec::new();
    for case in corpus() {
        let file = format!("{}.toml", case.name);
        let path = scratch.path().join(&file);
        fs::write(&path, &case.bytes).expect("write the scene");
        let output = impact(scratch.path(), &["run", path.to_str().unwrap()]);
        let stderr = String::from_utf8_lossy(&output.stderr);
        let mut problems = Vec::new();
        if output.status.code() != Some(2) {
            problems.push(format!("exit {:?}", output.status.code()));
        }
        if !output.stdout.is_empty() {
            problems.push("printed on stdout".into());
        }
        if stderr.contains("panicked") || stderr.contains("RUST_BACKTRACE") {
            problems.push("panicked".into());
        }
        if !stderr.contains(&file) {
            problems.push(format!("does not name the file {file}"));
        }
        if let Some(key) = case.key
            && !stderr.contains(&format!("`{key}`"))
        {
            problems.push(format!("does not name the key `{key}`"));
        }
        if let Some(line) = case.line
            && !stderr.contains(&format!("line {line}:"))
            && !stderr.contains(&format!("line {line},"))
        {
            problems.push(format!("does not say line {line}"));
        }
        if stderr.len() > 2000 {
            problems.push(format!("a message of {} bytes (a huge input echoed back?)", stderr.len()));
        }
        if !problems.is_empty() {
            let shown: String = stderr.chars().take(300).collect();
            failures.push(format!("{}: {} — stderr: {shown}", case.name, problems.join(", ")));
        }
    }
    assert!(failures.is_empty(), "{} hostile scenes mishandled:\n{}", failures.len(), failures.join("\n"));
}

/// The units `impact::units::brief` writes with an SI prefix, longest first (so that "m/s" is not read as "m"), with
/// the decimal exponents of the values it gives a prefix: pico to mega (to giga for pressures and stiffnesses), and
/// a mass from a picogram to a kilogram (it is written in grams below 1 kg).
const PREFIXED: [(&str, std::ops::Range<i32>); 11] = [
    ("N s/m", -12..12),
    ("N s", -12..9),
    ("N/m", -12..12),
    ("m/s", -12..9),
    ("Pa", -12..12),
    ("kg", -15..0),
    ("m", -12..9),
    ("s", -12..9),
    ("N", -12..9),
    ("J", -12..9),
    ("W", -12..9),
];

/// The unit that follows a number in a message (" 1e-2 m," -> "m"), if it is one that takes a prefix: the next word
/// after one space, ending where no letter, digit or unit sign ("/", "^", "²") follows — so "m/s²", "N/m^1.5",
/// "kg m²" and "s/m" are not read as "m/s", "N/m", "kg" or "s".
fn prefixed_unit(after: &str) -> Option<(&'static str, std::ops::Range<i32>)> {
    let rest = after.strip_prefix(' ')?;
    PREFIXED.into_iter().find(|(unit, _)| {
        rest.strip_prefix(unit).is_some_and(|tail| {
            let next = tail.chars().next();
            let ends = next.is_none_or(|c| !(c.is_alphanumeric() || "/^²³·".contains(c)));
            ends && !(*unit == "kg" && tail.starts_with(" m²"))
        })
    })
}

/// The problems of the numbers in a message: more than six significant digits ("1.0933620739432781"), or an exponent
/// form where the report would write a prefix ("1e-2 m" for 10 mm) or none at all ("1.09e0 m"). A number is a run of
/// digits not glued to a word (not the 16 of "utf16", the 0 of "bodies.0.mass"), with a decimal part and an exponent
/// if it has them; the significant digits of a whole number leave out its trailing zeros (a budget of 20000000 steps
/// has one).
fn number_problems(message: &str) -> Vec<String> {
    let bytes = message.as_bytes();
    let mut problems = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        let glued = i > 0 && (bytes[i - 1].is_ascii_alphanumeric() || b"._`'".contains(&bytes[i - 1]));
        if !bytes[i].is_ascii_digit() || glued {
            i += 1;
            continue;
        }
        let start = i;
        while i < bytes.len() && bytes[i].is_ascii_digit() {
            i += 1;
        }
        let mut digits = message[start..i].to_string();
        let point = i + 1 < bytes.len() && bytes[i] == b'.' && bytes[i + 1].is_ascii_digit();
        if point {
            let from = i + 1;
            i = from;
            while i < bytes.len() && bytes[i].is_ascii_digit() {
                i += 1;
            }
            digits.push_str(&message[from..i]);
        }
        let mut exponent = None;
        let mut j = i;
        if j < bytes.len() && bytes[j] == b'e' {
            j += 1;
            if j < bytes.len() && (bytes[j] == b'-' || bytes[j] == b'+') {
                j += 1;
            }
            let from = j;
            while j < bytes.len() && bytes[j].is_ascii_digit() {
                j += 1;
            }
            if j > from && (j == bytes.len() || !bytes[j].is_ascii_alphabetic()) {
                exponent = message[i + 1..j].parse::<i32>().ok();
                i = j;
            }
        }
        let token = &message[start..i];
        let mut significant = digits.trim_start_matches('0');
        if !point && exponent.is_none() {
            significant = significant.trim_end_matches('0');
        }
        if significant.len() > 6 {
            problems.push(format!("`{token}` has {} significant digits", significant.len()));
        }
        if let Some(exponent) = exponent {
            let value: f64 = token.parse().unwrap_or(f64::NAN);
            // The decimal exponent of the value at three significant digits, as a message rounds it.
            let power = format!("{value:.2e}").split_once('e').and_then(|(_, p)| p.parse::<i32>().ok());
            if exponent == 0 {
                problems.push(format!("`{token}` has the exponent e0"));
            } else if let (Some((unit, range)), Some(power)) = (prefixed_unit(&message[i..]), power)
                && range.contains(&power)
            {
                problems.push(format!("`{token} {unit}` is in exponent form where a prefix reads better"));
            }
        }
    }
    problems
}

#[test]
fn the_number_check_knows_a_bad_number_from_a_good_one() {
    // The example, and what it should read.
    assert_eq!(number_problems("would be 1.0933620739432781e0 m, beyond the smaller radius 1e-2 m").len(), 3);
    assert!(number_problems("would be 1.09 m, beyond the smaller radius 10 mm").is_empty());
    // Dimensionless exponents, units without a prefix, a step budget, line numbers and keys pass.
    let good = "e = 3.8e-5, atol / e = 2.6e-8 relative; budget of 20000000 steps at t = 1.23 s; K = 1.09e10 N/m^1.5; \
                line 400017, key `bodies.0.mass`, utf16.toml; 9.2e18 m/s; 1e-100 m; 5e-20 kg; 2.5e-3 kg m²";
    assert!(number_problems(good).is_empty(), "{:?}", number_problems(good));
    // A time in exponent form with seven digits, a mass in kg below a kilogram, a pressure in the GPa range, seven
    // digits, a damping in the kN s/m range.
    for (bad, count) in [
        ("at t = 1.234567e0 s", 2),
        ("a body of 3e-2 kg", 1),
        ("2.1e11 Pa", 1),
        ("penetration 0.1234567 m", 1),
        ("1.5e3 N s/m", 1),
    ] {
        assert_eq!(number_problems(bad).len(), count, "{bad}: {:?}", number_problems(bad));
    }
}

/// Issue 33: every message prints its numbers as the report does (`impact::units::brief`), and every value a user
/// gave in short form — no "1.0933620739432781e0 m" or "1e-2 m". Each hostile scene's message, and what the scenes
/// of models/ print on stderr and in their reports' notes and verdicts, is scanned for numbers with more than six
/// significant digits and for exponent forms the report would write with a prefix.
#[test]
fn messages_write_numbers_as_the_report_does() {
    let scratch = Scratch::new("messages_write_numbers");
    let folder = scratch.path().to_str().expect("a UTF-8 temp path").to_string();
    let mut failures = Vec::new();
    for case in corpus() {
        let file = format!("{}.toml", case.name);
        let path = scratch.path().join(&file);
        fs::write(&path, &case.bytes).expect("write the scene");
        let output = impact(scratch.path(), &["run", path.to_str().unwrap()]);
        // (The file's path holds the test's process id: it is the program's to echo, not a number it computed.)
        let stderr = String::from_utf8_lossy(&output.stderr).replace(&folder, "").replace(&file, "");
        let problems = number_problems(&stderr);
        if !problems.is_empty() {
            failures.push(format!("{}: {} — {stderr}", case.name, problems.join(", ")));
        }
    }
    let models = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("models");
    let mut scenes: Vec<_> = fs::read_dir(&models).unwrap().map(|e| e.unwrap().path()).collect();
    scenes.retain(|p| p.extension().is_some_and(|e| e == "toml"));
    scenes.sort();
    assert!(scenes.len() >= 20, "{} scenes in models/", scenes.len());
    for scene in scenes {
        let name = scene.file_name().unwrap().to_string_lossy().to_string();
        let text = fs::read_to_string(&scene).expect("a model");
        let tested = common::model_as_tested(&name, &text);
        let scene = if tested == text {
            scene
        } else {
            let shortened = scratch.path().join(&name);
            fs::write(&shortened, &tested).expect("write the shortened model");
            shortened
        };
        let output = impact(scratch.path(), &["run", scene.to_str().unwrap(), "--json"]);
        assert_eq!(output.status.code(), Some(0), "{name}: {}", String::from_utf8_lossy(&output.stderr));
        let report: serde_json::Value = serde_json::from_slice(&output.stdout).expect("a JSON report");
        let mut messages = vec![String::from_utf8_lossy(&output.stderr).to_string()];
        collect_messages(&report, None, &mut messages);
        assert!(messages.len() > 1 || name == "demo.toml", "{name}: no notes or verdicts found");
        for message in messages {
            let problems = number_problems(&message);
            if !problems.is_empty() {
                failures.push(format!("{name}: {} — {message}", problems.join(", ")));
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} messages with numbers not as the report writes them:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// The strings of a report's `notes` and of its verdicts' `meaning`, at any depth.
fn collect_messages(value: &serde_json::Value, key: Option<&str>, out: &mut Vec<String>) {
    match value {
        serde_json::Value::Object(map) => map.iter().for_each(|(k, v)| collect_messages(v, Some(k), out)),
        serde_json::Value::Array(items) => items.iter().for_each(|v| collect_messages(v, key, out)),
        serde_json::Value::String(text) if matches!(key, Some("notes" | "meaning")) => out.push(text.clone()),
        _ => {}
    }
}

#[test]
fn extreme_but_valid_numbers_run_and_pass_the_stress_checks() {
    // Not hostile: huge and tiny values whose derived quantities stay inside double precision run normally (the
    // scaled formulation makes them the same problem), and their reports pass every check of the stress run. A
    // tiny stiffness or a huge mass comes with a slow or stiff partner, so that the dent stays below the 10 mm
    // radius (a softer contact is refused: the bodies would pass through each other).
    for (old, new, partner) in [
        ("stiffness = 1e9", "stiffness = 1e308", None),
        (
            "stiffness = 1e9",
            "stiffness = 1e-300",
            Some(("velocity = [1.0, 0.0, 0.0]", "velocity = [1e-155, 0.0, 0.0]")),
        ),
        ("mass = 0.03", "density = 1e-300", None),
        ("mass = 0.03", "density = 1e300", Some(("stiffness = 1e9", "stiffness = 1e308"))),
        ("mass = 0.03", "mass = 1e-300", None),
        ("velocity = [1.0, 0.0, 0.0]", "velocity = [1e-150, 0.0, 0.0]", None),
    ] {
        let mut text = String::from_utf8(swap(old, new)).unwrap();
        if let Some((old, new)) = partner {
            text = text.replace(old, new);
        }
        let scene = impact::scene::Scene::parse(&text, std::path::Path::new("extreme.toml")).expect(new);
        let report = impact::impact::simulate(&scene, impact::history::Recording::Off).expect(new).report;
        assert!(report.contact.separated, "{new}");
        let (_, problems) = impact::stress::check_report(&scene, &report, None);
        assert!(problems.is_empty(), "{new}: {problems:?}");
    }
}

#[test]
fn a_folder_or_a_missing_file_is_a_bad_scene() {
    let scratch = Scratch::new("a_folder_or_a_missing_file");
    fs::create_dir(scratch.path().join("folder.toml")).unwrap();
    for name in ["folder.toml", "missing.toml"] {
        let output = impact(scratch.path(), &["run", name]);
        assert_eq!(output.status.code(), Some(2), "{name}");
        assert!(String::from_utf8_lossy(&output.stderr).contains(name), "{name}");
    }
}
