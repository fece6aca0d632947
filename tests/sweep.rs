//! `impact sweep` and `impact merge` through the real binary: a sweep's rows equal single runs of the same scenes,
//! reproduce the tables of docs/references.md and docs/laws.md, do not depend on the thread count or on sharding, and
//! bad arguments are clear errors with exit status 2. Every expected number comes from those two pages or a hand
//! calculation written here.

mod common;

use common::binary::{Scratch, assert_success, describe, impact, stderr};
use impact::output::sweep_figure::{self, SIZE};
use serde_json::Value;
use std::collections::HashMap;
use std::fs;

// ---------------------------------------------------------------------------------------------------------------
// Running the binary

/// Runs `impact ARGS` in the scratch folder and expects success.
#[track_caller]
fn run_ok(scratch: &Scratch, args: &[&str]) {
    assert_success(&impact(scratch.path(), args));
}

/// Runs `impact ARGS`, expects exit status 2 with a one-line message containing every one of `words`, and no panic.
#[track_caller]
fn assert_bad(scratch: &Scratch, args: &[&str], words: &[&str]) {
    let output = impact(scratch.path(), args);
    assert_eq!(output.status.code(), Some(2), "expected exit status 2 for {args:?}\n{}", describe(&output));
    let message = stderr(&output);
    assert!(!message.contains("panicked") && !message.contains("RUST_BACKTRACE"), "{}", describe(&output));
    for word in words {
        assert!(message.contains(word), "the message for {args:?} should mention `{word}`\n{}", describe(&output));
    }
}

// ---------------------------------------------------------------------------------------------------------------
// Reading the CSV

/// A parsed sweep CSV: the header and one map per row.
struct Table {
    header: Vec<String>,
    rows: Vec<HashMap<String, String>>,
}

/// Splits a CSV line, undoing RFC 4180 quotes.
fn cells(line: &str) -> Vec<String> {
    let mut out = vec![String::new()];
    let mut quoted = false;
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        let cell = out.last_mut().expect("a cell");
        match c {
            '"' if quoted && chars.peek() == Some(&'"') => {
                cell.push('"');
                chars.next();
            }
            '"' if quoted => quoted = false,
            '"' if cell.is_empty() => quoted = true,
            ',' if !quoted => out.push(String::new()),
            _ => cell.push(c),
        }
    }
    out
}

fn parse(text: &str) -> Table {
    let mut lines = text.lines().filter(|line| !line.starts_with('#'));
    let header = cells(lines.next().expect("a header line"));
    let rows = lines
        .map(|line| {
            let row = cells(line);
            assert_eq!(row.len(), header.len(), "a row with the wrong number of cells: {line}");
            header.iter().cloned().zip(row).collect()
        })
        .collect();
    Table { header, rows }
}

impl Table {
    /// The number in `column` of row `row` (panics on an empty cell).
    fn number(&self, row: usize, column: &str) -> f64 {
        let cell = &self.rows[row][column];
        cell.parse().unwrap_or_else(|_| panic!("row {row}, column {column}: `{cell}` is not a number"))
    }

    fn text(&self, row: usize, column: &str) -> &str {
        &self.rows[row][column]
    }
}

// ---------------------------------------------------------------------------------------------------------------
// Scenes

/// Two steel balls (10 mm) with the given velocities along x and `[contact]` lines.
fn steel_pair(v1: f64, v2: f64, contact: &str) -> String {
    format!(
        "[[bodies]]\nradius = 0.01\ndensity = 7850\nvelocity = [{v1:?}, 0.0, 0.0]\nyoung = 2.1e11\npoisson = 0.3\n\n\
         [[bodies]]\nradius = 0.01\ndensity = 7850\nvelocity = [{v2:?}, 0.0, 0.0]\nyoung = 2.1e11\npoisson = 0.3\n\n\
         [contact]\n{contact}\n"
    )
}

/// A 50 g ball at `speed` m/s along x against a fixed wall, with the given `[contact]` lines (and `density` of
/// steel instead of a mass when `mass` is None).
fn ball_on_wall(mass: Option<f64>, speed: f64, contact: &str) -> String {
    let mass = mass.map_or_else(|| "density = 7850".to_string(), |m| format!("mass = {m:?}"));
    format!(
        "[[bodies]]\nradius = 0.01\n{mass}\nvelocity = [{speed:?}, 0.0, 0.0]\nyoung = 2.1e11\npoisson = 0.3\n\n\
         [[bodies]]\nradius = inf\nmass = inf\nvelocity = [0.0, 0.0, 0.0]\nyoung = inf\n\n[contact]\n{contact}\n"
    )
}

/// `impact run --json` of `text`: the JSON text.
fn run_json(scratch: &Scratch, name: &str, text: &str) -> String {
    let scene = scratch.write(name, text);
    let output = impact(scratch.path(), &["run", &scene, "--json"]);
    assert_success(&output);
    String::from_utf8(output.stdout).expect("UTF-8 JSON")
}

/// The number at `/parent/key` (or `/key` at the top) of a JSON report, read from its text with Rust's correctly
/// rounded parser: serde_json's default float parser can be one unit in the last place off, which would hide
/// whether two runs agree bit for bit. The report writes each object's keys in a fixed order, so the first `key`
/// after `"parent": {` is the parent's own.
fn json_number(json: &str, pointer: &str) -> f64 {
    let parts: Vec<&str> = pointer.trim_start_matches('/').split('/').collect();
    let (parent, key) = match parts.as_slice() {
        [key] => (None, *key),
        [parent, key] => (Some(*parent), *key),
        _ => panic!("unsupported pointer {pointer}"),
    };
    let start =
        parent.map_or(0, |p| json.find(&format!("\"{p}\": {{")).unwrap_or_else(|| panic!("no {p} in the JSON")));
    let tag = format!("\"{key}\": ");
    let at = start + json[start..].find(&tag).unwrap_or_else(|| panic!("no {pointer} in the JSON"));
    let text = &json[at + tag.len()..];
    let end = text.find([',', '\n', '}']).unwrap_or(text.len());
    let number: f64 =
        text[..end].trim().parse().unwrap_or_else(|_| panic!("{pointer}: `{}` is not a number", &text[..end]));
    // Cross-check against a real JSON parser (to the unit in the last place it may miss).
    let value: Value = serde_json::from_str(json).expect("JSON");
    let parsed = value.pointer(pointer).and_then(Value::as_f64).unwrap_or_else(|| panic!("{pointer} is not a number"));
    assert!((parsed - number).abs() <= f64::EPSILON * number.abs(), "{pointer}: read {number}, JSON parser {parsed}");
    number
}

// ---------------------------------------------------------------------------------------------------------------
// Consistency with single runs

/// Each row of a two-key, two-law sweep equals `impact run --json` of the same scene written out by hand: the
/// same numbers, bit for bit, in every result column.
#[test]
fn sweep_rows_equal_single_runs_of_the_same_scenes() {
    let scratch = Scratch::new("single-runs");
    let scene = scratch.write("pair.toml", &steel_pair(1.0, -1.0, "law = \"hunt-crossley\"\nrestitution = 0.5"));
    run_ok(
        &scratch,
        &[
            "sweep",
            &scene,
            "--vary",
            "contact.restitution=0.3,0.8",
            "--vary",
            "bodies.1.velocity.0=-1:-3:2",
            "--law",
            "gonthier,tsuji",
            "--out",
            "sweep.csv",
        ],
    );
    let table = parse(&scratch.read("sweep.csv"));
    assert_eq!(table.rows.len(), 8, "2 x 2 points x 2 laws");
    let columns = [
        ("approach_speed", "/approach_speed"),
        ("effective_mass", "/effective_mass"),
        ("stiffness", "/law/stiffness"),
        ("damping", "/law/damping"),
        ("restitution_nominal", "/law/restitution_nominal"),
        ("restitution_velocity_ratio", "/contact/restitution_velocity_ratio"),
        ("restitution_impulse_ratio", "/contact/restitution_impulse_ratio"),
        ("restitution_energy", "/contact/restitution_energy"),
        ("duration", "/contact/duration"),
        ("max_compression_time", "/contact/max_compression_time"),
        ("max_penetration", "/contact/max_penetration"),
        ("max_force", "/contact/max_force"),
        ("max_force_time", "/contact/max_force_time"),
        ("common_normal_velocity", "/contact/common_normal_velocity"),
        ("deformation_impulse", "/contact/deformation_impulse"),
        ("restitution_impulse", "/contact/restitution_impulse"),
        ("kinetic_after", "/energy/kinetic_after"),
        ("dissipated", "/energy/dissipated"),
        ("steps", "/solver/steps"),
        ("force_evaluations", "/solver/force_evaluations"),
    ];
    let mut row = 0;
    for e in [0.3, 0.8] {
        for v2 in [-1.0, -3.0] {
            for law in ["gonthier", "tsuji"] {
                let text = steel_pair(1.0, v2, &format!("law = \"{law}\"\nrestitution = {e:?}"));
                let report = run_json(&scratch, &format!("single-{row}.toml"), &text);
                assert_eq!(table.text(row, "status"), "ok");
                assert_eq!(table.text(row, "law"), law);
                assert_eq!(table.number(row, "contact.restitution"), e);
                assert_eq!(table.number(row, "bodies.1.velocity.0"), v2);
                for (column, pointer) in columns {
                    let single = json_number(&report, pointer);
                    assert_eq!(table.number(row, column), single, "row {row} ({law}, e = {e}, v2 = {v2}): {column}");
                }
                row += 1;
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------------------------
// Physics through the sweep

/// The effective e that each published map gives (any n), the table of
/// docs/laws.md#the-hysteresis-family-and-its-maps.
const EFFECTIVE_E: [(&str, [f64; 6]); 5] = [
    ("hunt-crossley", [0.515833, 0.581288, 0.662962, 0.768000, 0.909016, 0.990099]),
    ("lankarani-nikravesh", [0.665265, 0.684225, 0.725241, 0.795973, 0.913177, 0.990148]),
    ("gonthier", [0.100990, 0.304225, 0.487741, 0.669581, 0.876435, 0.986776]),
    ("flores", [0.069444, 0.256208, 0.470445, 0.683184, 0.893921, 0.989340]),
    ("hu-guo", [0.074074, 0.270658, 0.487741, 0.697297, 0.899900, 0.990000]),
];
const NOMINAL_E: [f64; 6] = [0.1, 0.3, 0.5, 0.7, 0.9, 0.99];

#[test]
fn restitution_sweep_reproduces_the_effective_e_of_each_published_map() {
    let scratch = Scratch::new("effective-e");
    let scene = scratch.write("pair.toml", &steel_pair(1.0, -1.0, "law = \"hunt-crossley\"\nrestitution = 0.5"));
    let laws: Vec<&str> = EFFECTIVE_E.iter().map(|(law, _)| *law).collect();
    let values: Vec<String> = NOMINAL_E.iter().map(|e| e.to_string()).collect();
    let vary = format!("contact.restitution={}", values.join(","));
    run_ok(&scratch, &["sweep", &scene, "--vary", &vary, "--law", &laws.join(","), "--out", "table.csv"]);
    let table = parse(&scratch.read("table.csv"));
    assert_eq!(table.rows.len(), NOMINAL_E.len() * laws.len());
    for (point, nominal) in NOMINAL_E.iter().enumerate() {
        for (slot, (law, expected)) in EFFECTIVE_E.iter().enumerate() {
            // Points in --vary order, and for each point the laws in --law order.
            let row = point * laws.len() + slot;
            assert_eq!(table.number(row, "index"), row as f64);
            assert_eq!(table.text(row, "law"), *law);
            assert_eq!(table.number(row, "contact.restitution"), *nominal);
            let effective = table.number(row, "restitution_velocity_ratio");
            // The table is rounded to 6 decimals.
            assert!(
                (effective - expected[point]).abs() <= 1e-6,
                "{law} at nominal e = {nominal}: simulated {effective}, docs/laws.md {}",
                expected[point]
            );
        }
    }
}

/// Varying `contact.damping` on a scene that gives `restitution` replaces it: Hunt–Crossley with alpha in s/m at
/// v0 = 2 m/s has x = alpha v0 = 0.5, 1, 2, whose exact e are in docs/references.md.
#[test]
fn damping_sweep_replaces_restitution_and_matches_exact_hunt_crossley() {
    let scratch = Scratch::new("damping");
    let scene = scratch.write("pair.toml", &steel_pair(1.0, -1.0, "law = \"hunt-crossley\"\nrestitution = 0.5"));
    run_ok(&scratch, &["sweep", &scene, "--vary", "contact.damping=0.25:1:3:log", "--out", "damping.csv"]);
    let table = parse(&scratch.read("damping.csv"));
    // 0.25:1:3:log has the constant ratio 2.
    let exact = [(0.25, 0.748434931597), (0.5, 0.593624260040), (1.0, 0.410719686061)];
    for (row, (alpha, e)) in exact.iter().enumerate() {
        assert_eq!(table.text(row, "status"), "ok");
        assert_eq!(table.number(row, "contact.damping"), *alpha);
        assert_eq!(table.number(row, "damping"), *alpha);
        assert_eq!(table.text(row, "restitution_nominal"), "", "no nominal e once damping is given");
        let simulated = table.number(row, "restitution_velocity_ratio");
        assert!((simulated - e).abs() < 1e-8, "alpha = {alpha}: e = {simulated}, exact {e}");
    }
}

/// `--columns` writes the named result columns in the order named, after index, status, law and the varied keys;
/// each row computes only what they show (e alone: no times, no force peak, no dissipated energy, no exact
/// reference), and what it shows is as accurate: e against the exact Hunt–Crossley relation (the table of the test
/// above), the duration against the full sweep's. Shards of such a sweep merge into its whole file.
#[test]
fn columns_choose_what_a_row_writes_and_computes() {
    let scratch = Scratch::new("columns");
    let scene = scratch.write("pair.toml", &steel_pair(1.0, -1.0, "law = \"hunt-crossley\"\nrestitution = 0.5"));
    let vary = ["--vary", "contact.damping=0.25:1:3:log"];
    run_ok(&scratch, &["sweep", &scene, vary[0], vary[1], "--out", "all.csv"]);
    run_ok(&scratch, &["sweep", &scene, vary[0], vary[1], "--columns", "restitution_velocity_ratio", "--out", "e.csv"]);
    let two = "duration,restitution_velocity_ratio";
    run_ok(&scratch, &["sweep", &scene, vary[0], vary[1], "--columns", two, "--out", "two.csv"]);
    let (all, e, both) =
        (parse(&scratch.read("all.csv")), parse(&scratch.read("e.csv")), parse(&scratch.read("two.csv")));
    assert_eq!(e.header, ["index", "status", "law", "contact.damping", "restitution_velocity_ratio"]);
    assert_eq!(both.header, ["index", "status", "law", "contact.damping", "duration", "restitution_velocity_ratio"]);
    let exact = [0.748434931597, 0.593624260040, 0.410719686061];
    for (row, e_exact) in exact.into_iter().enumerate() {
        for table in [&e, &both] {
            assert_eq!(table.text(row, "status"), "ok");
            assert_eq!(table.number(row, "contact.damping"), all.number(row, "contact.damping"));
            let simulated = table.number(row, "restitution_velocity_ratio");
            assert!((simulated - e_exact).abs() < 1e-8, "row {row}: e = {simulated}, exact {e_exact}");
            let full = all.number(row, "restitution_velocity_ratio");
            assert!((simulated - full).abs() < 1e-9 * full, "row {row}: e = {simulated}, full sweep {full}");
        }
        let (duration, full) = (both.number(row, "duration"), all.number(row, "duration"));
        assert!((duration - full).abs() < 1e-9 * full, "row {row}: duration {duration}, full sweep {full}");
    }
    // Shards of a sweep with columns merge into its whole file, byte for byte.
    for i in 1..=2 {
        let shard = format!("{i}/2");
        let out = format!("e{i}.csv");
        let columns = ["--columns", "restitution_velocity_ratio"];
        run_ok(
            &scratch,
            &["sweep", &scene, vary[0], vary[1], columns[0], columns[1], "--shard", &shard, "--out", &out],
        );
    }
    run_ok(&scratch, &["merge", "merged.csv", "e1.csv", "e2.csv"]);
    assert_eq!(scratch.read("merged.csv"), scratch.read("e.csv"));
    // Their figure needs a column they do not have: refused before anything is written.
    assert_bad(&scratch, &["merge", "m.csv", "e1.csv", "e2.csv", "--plot", "m.png"], &["--plot", "approach_speed"]);
    assert!(!scratch.exists("m.csv") && !scratch.exists("m.png"));
    // A figure needs its columns: with them, it is drawn.
    let columns = "restitution_velocity_ratio,approach_speed";
    run_ok(&scratch, &["sweep", &scene, vary[0], vary[1], "--columns", columns, "--plot", "e.png", "--out", "p.csv"]);
    assert!(scratch.exists("e.png"));
}

/// A scene that gives `damping` takes a varied `restitution` (the damping is removed). The exact map
/// (carvalho-martins) then gives e = the nominal value (docs/references.md).
#[test]
fn restitution_sweep_replaces_damping() {
    let scratch = Scratch::new("restitution-over-damping");
    let scene = scratch.write("pair.toml", &steel_pair(1.0, -1.0, "law = \"carvalho-martins\"\ndamping = 0.4"));
    run_ok(&scratch, &["sweep", &scene, "--vary", "contact.restitution=0.2:0.8:3", "--out", "e.csv"]);
    let table = parse(&scratch.read("e.csv"));
    for (row, e) in [0.2, 0.5, 0.8].into_iter().enumerate() {
        assert_eq!(table.number(row, "contact.restitution"), e, "0.2:0.8:3 is 0.2, 0.5, 0.8");
        assert_eq!(table.number(row, "restitution_nominal"), e);
        let simulated = table.number(row, "restitution_velocity_ratio");
        assert!((simulated - e).abs() < 1e-8, "nominal {e}: simulated {simulated}");
    }
}

/// Against a velocity key the sweep reports the approach speed: with body 2 at -0.5 m/s, body 1 at 0.5 and 1.5 m/s
/// closes at 1 and 2 m/s; Hunt–Crossley with alpha = 0.5 s/m then has x = 0.5 and 1 (docs/references.md).
#[test]
fn velocity_sweep_gives_approach_speed_and_speed_dependent_e() {
    let scratch = Scratch::new("velocity");
    let scene = scratch.write("pair.toml", &steel_pair(1.0, -0.5, "law = \"hunt-crossley\"\ndamping = 0.5"));
    run_ok(&scratch, &["sweep", &scene, "--vary", "bodies.0.velocity.0=0.5,1.5", "--out", "v.csv"]);
    let table = parse(&scratch.read("v.csv"));
    for (row, (speed, e)) in [(1.0, 0.748434931597), (2.0, 0.593624260040)].into_iter().enumerate() {
        assert_eq!(table.number(row, "approach_speed"), speed);
        let simulated = table.number(row, "restitution_velocity_ratio");
        assert!((simulated - e).abs() < 1e-8, "v0 = {speed}: e = {simulated}, exact {e}");
    }
}

/// `bodies.0.mass` replaces the file's `density`; against a wall m* is the ball's mass.
#[test]
fn mass_sweep_replaces_density() {
    let scratch = Scratch::new("mass");
    let scene = scratch.write("wall.toml", &ball_on_wall(None, 1.0, "law = \"hertz\""));
    run_ok(&scratch, &["sweep", &scene, "--vary", "bodies.0.mass=0.5,2", "--out", "m.csv"]);
    let table = parse(&scratch.read("m.csv"));
    for (row, mass) in [0.5, 2.0].into_iter().enumerate() {
        assert_eq!(table.text(row, "status"), "ok");
        assert_eq!(table.number(row, "effective_mass"), mass);
        // Elastic: e = 1.
        assert!((table.number(row, "restitution_velocity_ratio") - 1.0).abs() < 1e-9);
    }
}

/// `--law` re-derives each law's defaults: `hertz` drops the damping (e = 1), `kelvin-voigt` takes the scene's
/// linear stiffness (exponent 1) and its exact map gives e = nominal (docs/references.md), `tsuji` fixes the exponent at
/// 3/2 so it cannot read a stiffness in N/m (its rows say so), and a scene `damping` in s/m means nothing to
/// `kelvin-voigt`.
#[test]
fn law_list_rederives_each_laws_defaults() {
    let scratch = Scratch::new("laws");
    let contact = "law = \"hunt-crossley\"\nrestitution = 0.6\nstiffness = 2.0e4\nexponent = 1";
    let scene = scratch.write("linear.toml", &ball_on_wall(Some(0.06), 3.0, contact));
    run_ok(
        &scratch,
        &[
            "sweep",
            &scene,
            "--vary",
            "bodies.0.velocity.0=1,3",
            "--law",
            "hertz,kelvin-voigt,tsuji,hunt-crossley",
            "--out",
            "laws.csv",
        ],
    );
    let table = parse(&scratch.read("laws.csv"));
    assert_eq!(table.rows.len(), 8);
    for point in 0..2 {
        let row = |slot: usize| point * 4 + slot;
        assert_eq!(table.text(row(0), "law"), "hertz");
        assert_eq!(table.text(row(0), "status"), "ok");
        assert!((table.number(row(0), "restitution_velocity_ratio") - 1.0).abs() < 1e-9);
        assert_eq!(table.number(row(0), "exponent"), 1.0, "hertz keeps the scene's exponent with its stiffness");
        assert_eq!(table.text(row(1), "law"), "kelvin-voigt");
        assert_eq!(table.text(row(1), "status"), "ok");
        assert!((table.number(row(1), "restitution_velocity_ratio") - 0.6).abs() < 1e-8);
        assert_eq!(table.text(row(2), "law"), "tsuji");
        let status = table.text(row(2), "status");
        assert!(status.starts_with("error:") && status.contains("exponent"), "tsuji row: {status}");
        assert_eq!(table.text(row(2), "restitution_velocity_ratio"), "");
        assert_eq!(table.text(row(3), "status"), "ok");
    }

    let scene = scratch.write("damped.toml", &steel_pair(1.0, -1.0, "law = \"hunt-crossley\"\ndamping = 0.5"));
    run_ok(
        &scratch,
        &["sweep", &scene, "--vary", "bodies.0.velocity.0=1", "--law", "gonthier,kelvin-voigt", "--out", "d.csv"],
    );
    let table = parse(&scratch.read("d.csv"));
    assert_eq!(table.text(0, "status"), "ok", "the same alpha in s/m carries over to gonthier");
    assert_eq!(table.number(0, "damping"), 0.5);
    let status = table.text(1, "status");
    assert!(status.starts_with("error:") && status.contains("damping"), "kelvin-voigt row: {status}");
}

/// A point that is not a valid scene, and a point whose bodies never separate, are rows, not a failed sweep.
/// Kelvin–Voigt at e = 0 is critical damping (zeta = 1), which never separates at zero penetration (docs/references.md).
#[test]
fn invalid_and_stuck_points_are_rows_that_say_why() {
    let scratch = Scratch::new("statuses");
    let contact = "law = \"kelvin-voigt\"\nrestitution = 0.5\nstiffness = 2.0e4";
    let scene = scratch.write("kv.toml", &ball_on_wall(Some(0.06), 3.0, contact));
    run_ok(&scratch, &["sweep", &scene, "--vary", "contact.restitution=0,0.5,1.5", "--out", "kv.csv"]);
    let table = parse(&scratch.read("kv.csv"));
    assert_eq!(table.text(0, "status"), "not separated");
    assert_eq!(table.text(0, "duration"), "");
    assert_eq!(table.text(0, "restitution_velocity_ratio"), "");
    assert!(table.number(0, "max_penetration") > 0.0, "what was measured is still there");
    assert_eq!(table.text(1, "status"), "ok");
    let status = table.text(2, "status");
    assert!(status.starts_with("error: contact.restitution") && status.contains("[0, 1]"), "{status}");
    assert_eq!(table.text(2, "max_force"), "");

    // The 1/e maps are undefined at e = 0: that row says so, the other law runs.
    let scene = scratch.write("pair.toml", &steel_pair(1.0, -1.0, "law = \"hunt-crossley\"\nrestitution = 0.5"));
    run_ok(
        &scratch,
        &["sweep", &scene, "--vary", "contact.restitution=0", "--law", "flores,lee-wang", "--out", "z.csv"],
    );
    let table = parse(&scratch.read("z.csv"));
    assert!(table.text(0, "status").contains("undefined at e = 0"), "{}", table.text(0, "status"));
    assert_eq!(table.text(1, "status"), "ok");
}

/// Points come in lexicographic order of the grid (the first --vary slowest), ranges include both ends and land on
/// round decimals, --log gives a constant ratio.
#[test]
fn grid_order_and_spacing() {
    let scratch = Scratch::new("grid");
    let scene = scratch.write("pair.toml", &steel_pair(1.0, -1.0, "law = \"hunt-crossley\"\nrestitution = 0.5"));
    run_ok(
        &scratch,
        &[
            "sweep",
            &scene,
            "--vary",
            "contact.restitution=0.1:0.9:5",
            "--vary",
            "bodies.1.velocity.0=-0.01:-10:4:log",
            "--out",
            "grid.csv",
        ],
    );
    let table = parse(&scratch.read("grid.csv"));
    assert_eq!(table.header[..5], ["index", "status", "law", "contact.restitution", "bodies.1.velocity.0"]);
    let mut row = 0;
    for e in ["0.1", "0.3", "0.5", "0.7", "0.9"] {
        for v in ["-0.01", "-0.1", "-1", "-10"] {
            assert_eq!(table.text(row, "index"), row.to_string());
            assert_eq!(table.text(row, "contact.restitution"), e, "row {row}");
            assert_eq!(table.text(row, "bodies.1.velocity.0"), v, "row {row}");
            row += 1;
        }
    }
    assert_eq!(row, table.rows.len());
}

// ---------------------------------------------------------------------------------------------------------------
// Determinism, shards, merge

/// A sweep with ok, stuck and invalid rows, over laws, for the byte-for-byte checks.
fn mixed_sweep_args(scene: &str) -> Vec<String> {
    ["sweep", scene, "--vary", "contact.restitution=0:1:6", "--vary", "bodies.0.velocity.0=0.5:2:2", "--law"]
        .iter()
        .map(|s| s.to_string())
        .chain(["hunt-crossley,kelvin-voigt,gonthier".to_string()])
        .collect()
}

fn with(args: &[String], more: &[&str]) -> Vec<String> {
    args.iter().cloned().chain(more.iter().map(|s| s.to_string())).collect()
}

fn run_args(scratch: &Scratch, args: &[String]) {
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    run_ok(scratch, &args);
}

fn mixed_scene(scratch: &Scratch) -> String {
    let contact = "law = \"hunt-crossley\"\nrestitution = 0.5\nstiffness = 2.0e4\nexponent = 1";
    scratch.write("mixed.toml", &ball_on_wall(Some(0.06), 1.0, contact))
}

#[test]
fn csv_is_identical_with_one_and_two_threads() {
    let scratch = Scratch::new("threads");
    let args = mixed_sweep_args(&mixed_scene(&scratch));
    run_args(&scratch, &with(&args, &["--threads", "1", "--out", "one.csv"]));
    run_args(&scratch, &with(&args, &["--threads", "2", "--out", "two.csv"]));
    run_args(&scratch, &with(&args, &["--out", "all.csv"]));
    let one = scratch.read("one.csv");
    let statuses: Vec<String> = parse(&one).rows.iter().map(|row| row["status"].clone()).collect();
    assert!(statuses.iter().any(|s| s == "ok") && statuses.iter().any(|s| s == "not separated"));
    assert!(statuses.iter().any(|s| s.starts_with("error:")), "the sweep should have an invalid point too");
    assert_eq!(one, scratch.read("two.csv"), "1 and 2 threads");
    assert_eq!(one, scratch.read("all.csv"), "1 thread and one per core");
}

#[test]
fn merged_shards_equal_the_whole_sweep() {
    let scratch = Scratch::new("shards");
    let args = mixed_sweep_args(&mixed_scene(&scratch));
    run_args(&scratch, &with(&args, &["--out", "whole.csv"]));
    for i in 1..=3 {
        run_args(&scratch, &with(&args, &["--shard", &format!("{i}/3"), "--out", &format!("part-{i}.csv")]));
    }
    let whole = scratch.read("whole.csv");
    let rows = parse(&whole).rows.len();
    let part = parse(&scratch.read("part-2.csv"));
    assert!(part.rows.iter().all(|row| row["index"].parse::<usize>().expect("an index") % 3 == 1), "2/3: i % 3 == 1");
    run_ok(&scratch, &["merge", "merged.csv", "part-3.csv", "part-1.csv", "part-2.csv"]);
    assert_eq!(scratch.read("merged.csv"), whole, "shards merged in any order");

    // One shard of one, and more shards than rows (some empty), merge back too.
    run_args(&scratch, &with(&args, &["--shard", "1/1", "--out", "only.csv"]));
    run_ok(&scratch, &["merge", "from-one.csv", "only.csv"]);
    assert_eq!(scratch.read("from-one.csv"), whole);
    let many = rows + 2;
    let mut names = Vec::new();
    for i in 1..=many {
        let name = format!("many-{i}.csv");
        run_args(&scratch, &with(&args, &["--shard", &format!("{i}/{many}"), "--out", &name]));
        names.push(name);
    }
    let mut merge: Vec<&str> = vec!["merge", "from-many.csv"];
    merge.extend(names.iter().map(String::as_str));
    run_ok(&scratch, &merge);
    assert_eq!(scratch.read("from-many.csv"), whole);
}

#[test]
fn merge_refuses_shards_that_are_not_one_whole_sweep() {
    let scratch = Scratch::new("merge-errors");
    let args = mixed_sweep_args(&mixed_scene(&scratch));
    for i in 1..=2 {
        run_args(&scratch, &with(&args, &["--shard", &format!("{i}/2"), "--out", &format!("p{i}.csv")]));
    }
    run_args(&scratch, &with(&args, &["--out", "whole.csv"]));
    let other = with(&args, &["--vary", "contact.friction=0", "--shard", "2/2", "--out", "other.csv"]);
    run_args(&scratch, &other);
    assert_bad(&scratch, &["merge", "out.csv", "p1.csv"], &["shard(s) 2/2 missing"]);
    assert_bad(&scratch, &["merge", "out.csv", "p1.csv", "p2.csv", "p2.csv"], &["given twice"]);
    assert_bad(&scratch, &["merge", "out.csv", "p1.csv", "whole.csv"], &["whole.csv", "not a shard"]);
    assert_bad(&scratch, &["merge", "out.csv", "p1.csv", "other.csv"], &["not shards of the same sweep"]);
    assert_bad(&scratch, &["merge", "out.csv", "p1.csv", "missing.csv"], &["missing.csv"]);
    // A shard cut short.
    let text = scratch.read("p2.csv");
    let cut: Vec<&str> = text.lines().collect();
    scratch.write("short.csv", &(cut[..cut.len() - 1].join("\n") + "\n"));
    assert_bad(&scratch, &["merge", "out.csv", "p1.csv", "short.csv"], &["missing"]);
    assert!(!scratch.exists("out.csv"), "a refused merge writes nothing");
}

// ---------------------------------------------------------------------------------------------------------------
// Figures

/// Whether a pixel is one of the curve colours (tab10 blue and orange) rather than white, black or grey.
fn colour_count(pixels: &[u8], colour: [u8; 3]) -> usize {
    pixels.chunks_exact(3).filter(|p| p.iter().zip(colour).all(|(a, b)| a.abs_diff(b) <= 8)).count()
}

#[test]
fn sweep_figure_is_a_non_trivial_image() {
    let scratch = Scratch::new("figure");
    let scene = scratch.write("pair.toml", &steel_pair(1.0, -1.0, "law = \"hunt-crossley\"\nrestitution = 0.5"));
    let vary = "contact.restitution=0.1:0.9:9";
    let laws = "hunt-crossley,gonthier";
    run_ok(&scratch, &["sweep", &scene, "--vary", vary, "--law", laws, "--out", "e.csv", "--plot", "e.png"]);
    run_ok(&scratch, &["sweep", &scene, "--vary", vary, "--law", laws, "--out", "e2.csv", "--plot", "plots/e.svg"]);

    let png = fs::read(scratch.path().join("e.png")).expect("the PNG");
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n", "a PNG signature");
    let width = u32::from_be_bytes(png[16..20].try_into().expect("4 bytes"));
    let height = u32::from_be_bytes(png[20..24].try_into().expect("4 bytes"));
    assert_eq!((width, height), SIZE);
    assert!(png.len() > 20_000, "a blank {width}x{height} PNG compresses to far less than {} bytes", png.len());
    let svg = scratch.read("plots/e.svg");
    for text in ["<svg", "nominal e", "effective e", "hunt-crossley", "gonthier", "ideal", "<polyline"] {
        assert!(svg.contains(text), "the SVG should contain `{text}`");
    }
    assert!(scratch.files().iter().all(|name| !name.contains("partial")), "no temporary file left behind");

    // The same figure in memory: both laws' colours cover real lines, and much of the image is drawn.
    let figure = impact::sweep::figure::from_csv(&scratch.read("e.csv")).expect("a figure from the CSV");
    assert!(figure.diagonal && figure.x_label == "nominal e" && !figure.log_x);
    assert_eq!(figure.curves.len(), 2);
    assert!(figure.curves.iter().all(|curve| curve.points.iter().all(Option::is_some) && curve.points.len() == 9));
    let pixels = sweep_figure::render_rgb(&figure).expect("rendered");
    let blue = colour_count(&pixels, [31, 119, 180]);
    let orange = colour_count(&pixels, [255, 127, 14]);
    // Anti-aliased 2-px lines: only their cores keep the exact colour (about one pixel a column over ~650 columns).
    assert!(blue > 600 && orange > 600, "curve pixels: blue {blue}, orange {orange}");
    let drawn = pixels.chunks_exact(3).filter(|p| p.iter().any(|&c| c < 200)).count();
    assert!(drawn > 10_000, "only {drawn} dark pixels");
}

// ---------------------------------------------------------------------------------------------------------------
// Bad input, and all-or-nothing outputs

#[test]
fn bad_keys_ranges_laws_and_shard_specs_exit_2() {
    let scratch = Scratch::new("bad");
    let scene = scratch.write("pair.toml", &steel_pair(1.0, -1.0, "law = \"hunt-crossley\"\nrestitution = 0.5"));
    let bad = |extra: &[&str], words: &[&str]| {
        let mut args = vec!["sweep", scene.as_str(), "--out", "out.csv"];
        args.extend_from_slice(extra);
        assert_bad(&scratch, &args, words);
    };
    bad(&["--vary", "contact.restitutoin=0:1:3"], &["contact.restitutoin", "contact.restitution"]);
    bad(&["--vary", "bodies.2.mass=1:2:3"], &["bodies.2.mass", "two bodies"]);
    bad(&["--vary", "bodies.1.velocity=1:2:3"], &["vector", "bodies.1.velocity.0"]);
    bad(&["--vary", "bodies.1.velocity.3=1:2:3"], &["component"]);
    bad(&["--vary", "bodies.0.position.0=0:1:3"], &["bodies.0.position", "whole vector"]);
    bad(&["--vary", "contact.law=1:2:3"], &["--law"]);
    bad(&["--vary", "contact.restitution"], &["KEY=START:STOP:COUNT"]);
    bad(&["--vary", "contact.restitution=0.1:0.9"], &["START:STOP:COUNT"]);
    bad(&["--vary", "contact.restitution=0.1:x:3"], &["STOP", "`x`"]);
    bad(&["--vary", "contact.restitution=0.1:0.9:0"], &["COUNT"]);
    bad(&["--vary", "contact.restitution=0.1:0.9:2.5"], &["COUNT"]);
    bad(&["--vary", "contact.restitution=0.1:nan:3"], &["finite"]);
    bad(&["--vary", "contact.restitution=0:0.9:3", "--log"], &["geometric", "non-zero"]);
    bad(&["--vary", "contact.restitution=0.5:0.5:3"], &["equal"]);
    bad(&["--vary", "contact.restitution=0.1:0.9:3:cubic"], &["cubic"]);
    bad(&["--vary", "contact.restitution=0.5", "--vary", "contact.restitution=0.6"], &["twice"]);
    bad(&["--vary", "contact.restitution=0.5", "--vary", "contact.damping=1"], &["not both"]);
    bad(&["--vary", "contact.restitution=0.5", "--law", "hunt-crossley,hunt-crosley"], &["hunt-crosley", "flores"]);
    for shard in ["0/3", "4/3", "1/0", "x", "1/", "1.5/3"] {
        bad(&["--vary", "contact.restitution=0.5", "--shard", shard], &["--shard", "1 <= I <= N"]);
    }
    bad(&["--vary", "contact.restitution=0.5", "--threads", "0"], &["--threads"]);
    bad(&["--vary", "contact.restitution=0.5", "--threads", "100000"], &["--threads"]);
    bad(&["--vary", "contact.restitution=0.1:0.9:18446744073709551615"], &["COUNT"]);
    bad(&["--vary", "contact.restitution=0.5", "--plot", "e.jpg"], &[".png or .svg"]);
    bad(&["--vary", "contact.restitution=0.5", "--plot", "e.png", "--shard", "1/2"], &["merge"]);
    bad(&["--vary", "contact.restitution=0.5", "--columns", "e"], &["--columns", "`e`", "restitution_velocity_ratio"]);
    bad(&["--vary", "contact.restitution=0.5", "--columns", "law"], &["--columns", "`law`", "always written"]);
    bad(&["--vary", "contact.restitution=0.5", "--columns", "duration,duration"], &["`duration`", "twice"]);
    bad(&["--vary", "contact.restitution=0.5", "--columns", ""], &["--columns"]);
    bad(&["--vary", "contact.restitution=0.5", "--columns", "duration", "--plot", "e.png"], &["--plot", "--columns"]);
    assert_bad(
        &scratch,
        &["sweep", "nowhere.toml", "--vary", "contact.restitution=0.5", "--out", "o.csv"],
        &["nowhere.toml"],
    );
    let broken = scratch.write("broken.toml", "[[bodies]]\nradius = \n");
    assert_bad(
        &scratch,
        &["sweep", &broken, "--vary", "contact.restitution=0.5", "--out", "o.csv"],
        &["broken.toml", "line 2"],
    );
    assert_bad(&scratch, &["sweep", &scene, "--vary", "contact.restitution=0.5"], &["--out"]);
    assert!(!scratch.exists("out.csv") && !scratch.exists("o.csv"), "bad arguments write nothing");
}

#[test]
fn outputs_are_written_completely_or_not_at_all() {
    let scratch = Scratch::new("atomic");
    let scene = scratch.write("pair.toml", &steel_pair(1.0, -1.0, "law = \"hunt-crossley\"\nrestitution = 0.5"));
    // A failed sweep leaves an earlier file as it was.
    scratch.write("out.csv", "earlier\n");
    assert_bad(&scratch, &["sweep", &scene, "--vary", "contact.nothing=0:1:2", "--out", "out.csv"], &["nothing"]);
    assert_eq!(scratch.read("out.csv"), "earlier\n");
    // A figure that cannot be written (its folder is a file): neither the figure nor the CSV appears.
    scratch.write("blocked", "a file, not a folder");
    let output = impact(
        scratch.path(),
        &["sweep", &scene, "--vary", "contact.restitution=0.5", "--out", "new.csv", "--plot", "blocked/e.png"],
    );
    assert_ne!(output.status.code(), Some(0), "{}", describe(&output));
    assert!(!stderr(&output).contains("panicked"), "{}", describe(&output));
    assert!(!scratch.exists("new.csv"), "the CSV waits for the figure");
    // A CSV that cannot be written (the name is a folder): no figure either, and nothing half-written.
    fs::create_dir_all(scratch.path().join("taken.csv")).expect("a folder");
    let output = impact(
        scratch.path(),
        &["sweep", &scene, "--vary", "contact.restitution=0.5", "--out", "taken.csv", "--plot", "e.png"],
    );
    assert_eq!(output.status.code(), Some(1), "{}", describe(&output));
    assert!(!scratch.exists("e.png"), "the figure is only shown with its CSV");
    let left: Vec<String> = scratch.files().into_iter().filter(|name| name.contains("partial")).collect();
    assert!(left.is_empty(), "temporary files left behind: {left:?}");
}

#[test]
fn a_scene_of_the_wrong_form_is_a_bad_scene_not_a_sweep_of_errors() {
    let scratch = Scratch::new("form");
    // A string where a vector is expected can never be mended by varying numbers.
    let text = steel_pair(1.0, -1.0, "law = \"hunt-crossley\"\nrestitution = 0.5").replacen("[1", "\"fast\" #[1", 1);
    let scene = scratch.write("typo.toml", &text);
    assert_bad(
        &scratch,
        &["sweep", scene.as_str(), "--vary", "contact.restitution=0.1:0.9:3", "--out", "o.csv"],
        &["velocity"],
    );
    let empty = scratch.write("empty.toml", "");
    assert_bad(
        &scratch,
        &["sweep", empty.as_str(), "--vary", "contact.restitution=0.1:0.9:3", "--out", "o.csv"],
        &["bodies"],
    );
    assert!(!scratch.exists("o.csv"));
}
