//! No panic, no runaway memory, no silent overflow, through the real binary: counts are checked against documented
//! limits before anything is allocated, memory follows what is written and never what a header claims (checked
//! under a 1 GB address-space limit, which the old code overran by allocating from the claims), grids stay finite
//! and distinct, bad `[output]` values are located, and long strings are cut in messages and figures.

mod common;

use common::binary::{Scratch, assert_success, describe, impact, stderr};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

const SCENE: &str = include_str!("../models/demo.toml");

/// The address space the memory tests allow the binary: ample for streaming a sweep or refusing a forged file,
/// far less than allocating from a claim of 10^8 rows (at least 800 MB a vector).
const ADDRESS_SPACE_KB: u64 = 1_000_000;

/// The most rows a sweep may have (README, "Sweeps").
const MAX_ROWS: u64 = 100_000_000;

/// `impact ARGS` in `folder` under [`ADDRESS_SPACE_KB`].
fn impact_in_small_memory(folder: &std::path::Path, args: &[&str]) -> Command {
    let mut command = Command::new("sh");
    command
        .arg("-c")
        .arg(format!("ulimit -v {ADDRESS_SPACE_KB} && exec \"$0\" \"$@\""))
        .arg(env!("CARGO_BIN_EXE_impact"))
        .args(args)
        .current_dir(folder)
        .env_remove("RUST_BACKTRACE");
    command
}

/// Expects exit status 2, no panic, and a message mentioning every one of `words`.
#[track_caller]
fn assert_refused(output: &Output, words: &[&str]) {
    assert_eq!(output.status.code(), Some(2), "expected exit status 2\n{}", describe(output));
    let message = stderr(output);
    assert!(!message.contains("panicked"), "{}", describe(output));
    for word in words {
        assert!(message.contains(word), "the message should mention `{word}`\n{}", describe(output));
    }
}

// ---------------------------------------------------------------------------------------------------------------
// Counts

#[test]
fn samples_beyond_the_limit_are_refused_before_any_work() {
    let scratch = Scratch::new("samples");
    scratch.write("s.toml", SCENE);
    for samples in ["18446744073709551615", "1000001"] {
        let output = impact(scratch.path(), &["run", "s.toml", "--csv", "s.csv", "--samples", samples]);
        assert_refused(&output, &["--samples", "1000000"]);
    }
    assert!(!scratch.exists("s.csv"));
}

#[test]
fn a_forged_shard_header_is_refused_in_small_memory() {
    let scratch = Scratch::new("forged");
    // 84 bytes claiming the largest sweep in the largest number of shards, and one claiming all its rows.
    let header = "index,status,law,contact.restitution";
    scratch.write("many.csv", &format!("# impact sweep: shard 1/{MAX_ROWS} of {MAX_ROWS} rows, sweep 0\n{header}\n"));
    scratch.write("one.csv", &format!("# impact sweep: shard 1/1 of {MAX_ROWS} rows, sweep 0\n{header}\n"));
    let output = impact_in_small_memory(scratch.path(), &["merge", "out.csv", "many.csv"]).output().expect("runs");
    // Shards 2 to 11 are listed, the other MAX_ROWS - 1 - 10 counted.
    let more = MAX_ROWS - 1 - 10;
    assert_refused(&output, &[&format!("2/{MAX_ROWS}, 3/{MAX_ROWS}"), &format!("and {more} more missing")]);
    let output = impact_in_small_memory(scratch.path(), &["merge", "out.csv", "one.csv"]).output().expect("runs");
    assert_refused(&output, &["row(s) 0, 1, 2", &format!("and {} more missing", MAX_ROWS - 10)]);
    assert!(!scratch.exists("out.csv"));
}

#[test]
fn a_grid_beyond_the_row_limit_is_refused_in_small_memory() {
    let scratch = Scratch::new("huge-grid");
    scratch.write("s.toml", SCENE);
    let (first, second) = ("contact.restitution=0.01:1:100000000", "bodies.0.velocity.0=1:2:100000000");
    let args = ["sweep", "s.toml", "--vary", first, "--vary", second, "--out", "e.csv"];
    let output = impact_in_small_memory(scratch.path(), &args).output().expect("runs");
    assert_refused(&output, &[&format!("more than {MAX_ROWS}")]);
    assert!(!scratch.exists("e.csv"));
}

#[test]
fn a_sweep_of_the_largest_size_streams_its_rows_in_small_memory() {
    let scratch = Scratch::new("largest-sweep");
    scratch.write("s.toml", SCENE);
    let vary = format!("contact.restitution=0.01:1:{MAX_ROWS}");
    let args = ["sweep", "s.toml", "--vary", &vary, "--threads", "1", "--out", "e.csv"];
    let mut child = impact_in_small_memory(scratch.path(), &args)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary starts");
    // Rows reach the temporary file a chunk at a time: wait for the first rows, well past the header.
    let written = || {
        let files = std::fs::read_dir(scratch.path()).expect("the folder").flatten();
        files
            .filter(|f| f.file_name().to_string_lossy().contains("partial"))
            .any(|f| f.metadata().is_ok_and(|meta| meta.len() > 10_000))
    };
    let start = Instant::now();
    while !written() && start.elapsed() < Duration::from_secs(300) {
        if child.try_wait().expect("the child's status").is_some() {
            break;
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    let streaming = written();
    let _ = Command::new("kill").args(["-INT", &child.id().to_string()]).status();
    let output = child.wait_with_output().expect("the child ends");
    assert!(streaming, "no rows were written\n{}", describe(&output));
    assert_eq!(output.status.code(), Some(130), "{}", describe(&output));
}

#[test]
fn a_shard_count_beyond_the_row_limit_is_refused_by_sweep_as_by_merge() {
    let scratch = Scratch::new("many-shards");
    scratch.write("s.toml", SCENE);
    let shard = format!("1/{}", 2 * MAX_ROWS);
    let args = ["sweep", "s.toml", "--vary", "contact.restitution=0.5", "--shard", &shard, "--out", "p.csv"];
    assert_refused(&impact(scratch.path(), &args), &["--shard", &format!("at most {MAX_ROWS}")]);
    assert!(!scratch.exists("p.csv"));
}

// ---------------------------------------------------------------------------------------------------------------
// Cut-off shards, grids that would overflow or repeat

/// The two shards `s1.csv`, `s2.csv` of a two-row sweep: each holds its comment, the header and one row (line 3).
fn two_shards(scratch: &Scratch) {
    scratch.write("s.toml", SCENE);
    for i in 1..=2 {
        let (shard, out) = (format!("{i}/2"), format!("s{i}.csv"));
        let args = ["sweep", "s.toml", "--vary", "contact.restitution=0.5,0.6", "--shard", &shard, "--out", &out];
        assert_success(&impact(scratch.path(), &args));
    }
}

#[test]
fn a_shard_cut_off_mid_row_is_refused_naming_file_and_line() {
    let scratch = Scratch::new("cut-shard");
    two_shards(&scratch);
    let whole = scratch.read("s2.csv");
    assert_eq!(whole.lines().count(), 3);
    // Cut inside the row: no line end, and fewer cells.
    scratch.write("s2.csv", &whole[..whole.len() - 20]);
    let output = impact(scratch.path(), &["merge", "out.csv", "s1.csv", "s2.csv"]);
    assert_refused(&output, &["s2.csv, line 3", "cut off"]);
    // Cut at a cell boundary, and a line end added: still fewer cells than the header.
    let row = whole.lines().nth(2).expect("the row");
    let shorter = row.rsplitn(4, ',').nth(3).expect("cells");
    let lines: Vec<&str> = whole.lines().take(2).chain([shorter]).collect();
    scratch.write("s2.csv", &(lines.join("\n") + "\n"));
    let output = impact(scratch.path(), &["merge", "out.csv", "s1.csv", "s2.csv"]);
    assert_refused(&output, &["s2.csv, line 3", "cells"]);
    assert!(!scratch.exists("out.csv"));
}

/// The values of column `key` of a sweep's CSV.
fn column(csv: &str, key: &str) -> Vec<String> {
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().expect("a header").split(',').collect();
    let at = header.iter().position(|c| *c == key).expect("the column");
    // The varied key's column comes before any quoted cell that could hold a comma... except the status, which
    // can: read the cells from the end, where the result columns are fixed in number.
    let from_end = header.len() - at;
    lines.map(|line| line.split(',').rev().nth(from_end - 1).expect("the cell").to_string()).collect()
}

#[test]
fn a_range_across_double_precision_stays_finite_or_is_refused() {
    let scratch = Scratch::new("range-overflow");
    scratch.write("s.toml", SCENE);
    // stop - start overflows to inf; the midpoint of -1e308 and 1e308 is 0 all the same.
    let key = "bodies.0.velocity.0";
    let args = ["sweep", "s.toml", "--vary", &format!("{key}=-1e308:1e308:3"), "--out", "e.csv"];
    assert_success(&impact(scratch.path(), &args));
    assert_eq!(column(&scratch.read("e.csv"), key), ["-1e308", "0", "1e308"]);
    // Two neighbours of the largest double: their midpoint at 15 significant digits, 1.79769313486232e308, is
    // beyond it, so the range cannot be sampled.
    let args = ["sweep", "s.toml", "--vary", &format!("{key}=1.7976931348623155e308:1.7976931348623157e308:3")];
    let output = impact(scratch.path(), &[&args[..], &["--out", "f.csv"]].concat());
    assert_refused(&output, &["value 2 of the range is inf"]);
    assert!(!scratch.exists("f.csv"));
}

#[test]
fn a_range_whose_values_collide_is_refused() {
    let scratch = Scratch::new("range-repeats");
    scratch.write("s.toml", SCENE);
    // 0.10000000000000002 is the double after 0.1: the two values between round to 0.1 at 15 digits.
    let args = ["sweep", "s.toml", "--vary", "contact.restitution=0.1:0.10000000000000002:4", "--out", "e.csv"];
    assert_refused(&impact(scratch.path(), &args), &["values 1 and 2", "0.1", "15 significant digits"]);
    assert!(!scratch.exists("e.csv"));
}

// ---------------------------------------------------------------------------------------------------------------
// Bad output paths, located

#[test]
fn bad_output_values_are_refused_naming_key_and_line() {
    let scratch = Scratch::new("bad-output");
    scratch.write("taken", "a file, not a folder");
    let cases = [
        ("series = \"\"", "output.series", "empty"),
        ("series = \"s.csv/\"", "output.series", "folder"),
        ("plots = \"fig.png\"", "output.plots", "folder"),
        ("plots = \"-\"", "output.plots", "standard output"),
        ("plots = \"taken\"", "output.plots", "not a folder"),
    ];
    for (entry, key, why) in cases {
        let text = format!("{SCENE}\n[output]\n{entry}\n");
        // The line of the entry, counted in the text written above.
        let line = text.lines().position(|l| l == entry).expect("the entry") + 1;
        scratch.write("s.toml", &text);
        let output = impact(scratch.path(), &["run", "s.toml"]);
        assert_refused(&output, &["s.toml", &format!("line {line}"), key, why]);
    }
    // The same from the command line.
    scratch.write("s.toml", SCENE);
    assert_refused(&impact(scratch.path(), &["run", "s.toml", "--csv", "out/"]), &["--csv out/", "folder"]);
    assert_refused(&impact(scratch.path(), &["run", "s.toml", "--plot", "fig.svg"]), &["--plot fig.svg", "folder"]);
    assert_refused(&impact(scratch.path(), &["run", "s.toml", "--plot", "taken"]), &["--plot taken", "not a folder"]);
    assert_eq!(scratch.files(), ["s.toml", "taken"], "nothing written");
}

// ---------------------------------------------------------------------------------------------------------------
// Long strings

#[test]
fn a_long_unknown_key_is_cut_in_the_message() {
    let scratch = Scratch::new("long-key");
    let key = "k".repeat(1_000_000);
    let text = format!("{SCENE}{key} = 1\n");
    let line = text.lines().count();
    scratch.write("s.toml", &text);
    let output = impact(scratch.path(), &["run", "s.toml"]);
    assert_refused(&output, &[&format!("line {line}"), "(1000000 characters)"]);
    // The key appears cut (twice: as the key and in the parser's message), never whole.
    assert!(stderr(&output).len() < 2_000, "a message of {} bytes", stderr(&output).len());
}

#[test]
fn long_arguments_are_cut_in_messages() {
    let scratch = Scratch::new("long-arguments");
    scratch.write("s.toml", SCENE);
    let long = "x".repeat(100_000);
    let law = ["sweep", "s.toml", "--vary", "contact.restitution=0.5", "--law", &long, "--out", "e.csv"];
    let vary = format!("{long}=0:1:3");
    let key = ["sweep", "s.toml", "--vary", &vary, "--out", "e.csv"];
    let shard = ["sweep", "s.toml", "--vary", "contact.restitution=0.5", "--shard", &long, "--out", "e.csv"];
    let calibrate = ["calibrate", "--law", &long, "--restitution", "0.5"];
    for args in [&law[..], &key, &shard, &calibrate] {
        let output = impact(scratch.path(), args);
        assert_refused(&output, &["(100000 characters)"]);
        assert!(stderr(&output).len() < 2_000, "a message of {} bytes for {}", stderr(&output).len(), args[2]);
    }
}

#[test]
fn a_long_title_is_cut_in_the_figures() {
    let scratch = Scratch::new("long-title");
    let title = "T".repeat(10_000);
    let lines: Vec<String> = SCENE
        .lines()
        .map(|line| if line.starts_with("title") { format!("title = \"{title}\"") } else { line.to_string() })
        .collect();
    scratch.write("s.toml", &lines.join("\n"));
    assert_success(&impact(scratch.path(), &["run", "s.toml", "--plot", "figs"]));
    let svg = scratch.read("figs/force_time.svg");
    // The caption keeps the first 120 characters and says how long the title was.
    assert!(svg.contains(&"T".repeat(120)) && !svg.contains(&"T".repeat(121)), "the title is cut to 120 characters");
    assert!(svg.contains("(10000 characters)"), "the full length is given");
}
