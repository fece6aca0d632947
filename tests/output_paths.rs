//! The output rules of README.md#exit-status-and-output-files, through the real binary: an output never replaces an
//! input of the same run nor another output (refused before any work, exit status 2, both named); `-` is standard
//! output; a FIFO is written in place; a symbolic link is followed; a regular file is complete or absent, with no
//! temporary left behind after an error or Ctrl-C. Never against real `/dev` nodes: FIFOs, links and files in scratch
//! folders.

mod common;

use common::binary::{Scratch, assert_success, describe, impact, stderr, stdout};
use impact::files::{Destination, OutputFile};
use std::fs;
use std::os::unix::fs::FileTypeExt;
use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

/// The demonstration scene: a contact of a few hundred steps, simulated in milliseconds.
const SCENE: &str = include_str!("../models/demo.toml");

/// The series' header, as the README lists its columns.
const SERIES_HEADER: &str = "time_s,phase,penetration_m,penetration_rate_m_s,force_N,impulse_N_s,v1_normal_m_s,\
    v2_normal_m_s,v1_tangential_x_m_s,v1_tangential_y_m_s,v1_tangential_z_m_s,v2_tangential_x_m_s,\
    v2_tangential_y_m_s,v2_tangential_z_m_s,normal_x,normal_y,normal_z,tangential_force_x_N,tangential_force_y_N,\
    tangential_force_z_N,slip_x_m_s,slip_y_m_s,slip_z_m_s,w1_x_rad_s,w1_y_rad_s,w1_z_rad_s,w2_x_rad_s,w2_y_rad_s,\
    w2_z_rad_s,sliding";

/// Cells in a row of the series (the README's column list).
const SERIES_CELLS: usize = 30;

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

/// Files whose name marks a temporary (`.NAME.partial-...`), anywhere under `folder`.
fn temporaries(folder: &Path) -> Vec<String> {
    let mut found = Vec::new();
    for entry in fs::read_dir(folder).expect("list the folder").flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        if name.contains("partial") {
            found.push(name);
        } else if entry.file_type().is_ok_and(|t| t.is_dir()) {
            found.extend(temporaries(&entry.path()));
        }
    }
    found
}

// ---------------------------------------------------------------------------------------------------------------
// An output never replaces an input

#[test]
fn the_scene_file_given_as_the_series_is_refused_and_left_intact() {
    let scratch = Scratch::new("scene-as-csv");
    scratch.write("s.toml", SCENE);
    let output = impact(scratch.path(), &["run", "s.toml", "--csv", "s.toml"]);
    assert_refused(&output, &["--csv s.toml", "scene file", "s.toml"]);
    assert_eq!(scratch.read("s.toml"), SCENE);

    // The same file under other names: a symbolic link to it, a hard link to it, a path through `..`.
    std::os::unix::fs::symlink("s.toml", scratch.path().join("alias.toml")).expect("a link");
    fs::hard_link(scratch.path().join("s.toml"), scratch.path().join("hard.toml")).expect("a hard link");
    fs::create_dir(scratch.path().join("sub")).expect("a folder");
    for other in ["alias.toml", "hard.toml", "sub/../s.toml"] {
        let output = impact(scratch.path(), &["run", "s.toml", "--csv", other]);
        assert_refused(&output, &[&format!("--csv {other}"), "s.toml"]);
    }
    assert!(fs::symlink_metadata(scratch.path().join("alias.toml")).expect("the link").file_type().is_symlink());
    assert_eq!(scratch.read("s.toml"), SCENE);
    assert_eq!(scratch.read("hard.toml"), SCENE);
}

#[test]
fn the_scene_file_given_as_the_sweep_output_is_refused() {
    let scratch = Scratch::new("scene-as-out");
    scratch.write("s.toml", SCENE);
    let output = impact(scratch.path(), &["sweep", "s.toml", "--vary", "contact.restitution=0.5", "--out", "s.toml"]);
    assert_refused(&output, &["--out s.toml", "scene file"]);
    assert_eq!(scratch.read("s.toml"), SCENE);
}

#[test]
fn a_scene_naming_itself_as_its_series_is_refused_at_the_key_and_line() {
    let scratch = Scratch::new("scene-series-itself");
    let text = format!("{SCENE}\n[output]\nseries = \"s.toml\"\n");
    scratch.write("s.toml", &text);
    // The line of `series =`, counted in the text written above.
    let line = text.lines().position(|l| l.starts_with("series")).expect("the series line") + 1;
    let output = impact(scratch.path(), &["run", "s.toml"]);
    assert_refused(&output, &["s.toml", &format!("line {line}"), "output.series"]);
    assert_eq!(scratch.read("s.toml"), text);
}

/// Writes the two shards of a two-row sweep, `s1.csv` and `s2.csv`.
fn two_shards(scratch: &Scratch) {
    scratch.write("s.toml", SCENE);
    for i in 1..=2 {
        let shard = format!("{i}/2");
        let out = format!("s{i}.csv");
        let args = ["sweep", "s.toml", "--vary", "contact.restitution=0.5,0.6", "--shard", &shard, "--out", &out];
        assert_success(&impact(scratch.path(), &args));
    }
}

#[test]
fn merge_never_writes_over_a_shard_it_reads() {
    let scratch = Scratch::new("merge-over-shard");
    two_shards(&scratch);
    let shard = scratch.read("s1.csv");
    let output = impact(scratch.path(), &["merge", "s1.csv", "s1.csv", "s2.csv"]);
    assert_refused(&output, &["OUT s1.csv", "the shard s1.csv being merged"]);
    assert_eq!(scratch.read("s1.csv"), shard);
}

// ---------------------------------------------------------------------------------------------------------------
// Outputs never overwrite each other

#[test]
fn a_sweep_table_and_figure_on_one_file_are_refused() {
    let scratch = Scratch::new("out-is-plot");
    scratch.write("s.toml", SCENE);
    let args = ["sweep", "s.toml", "--vary", "contact.restitution=0.5,0.6", "--out", "e.png", "--plot", "e.png"];
    let output = impact(scratch.path(), &args);
    assert_refused(&output, &["--out e.png", "--plot e.png", "same file"]);
    assert!(!scratch.exists("e.png"), "refused before any work");
}

#[test]
fn a_series_among_the_figures_or_in_place_of_their_folder_is_refused() {
    let scratch = Scratch::new("csv-in-plots");
    scratch.write("s.toml", SCENE);
    let output = impact(scratch.path(), &["run", "s.toml", "--csv", "figs/force_time.png", "--plot", "figs"]);
    assert_refused(&output, &["--csv figs/force_time.png", "--plot figs", "same file"]);
    let output = impact(scratch.path(), &["run", "s.toml", "--csv", "F", "--plot", "F"]);
    assert_refused(&output, &["--csv F", "--plot F", "folder"]);
    assert_eq!(scratch.files(), ["s.toml"], "refused before any work");
}

#[test]
fn two_outputs_on_standard_output_are_refused() {
    let scratch = Scratch::new("two-stdout");
    scratch.write("s.toml", SCENE);
    let output = impact(scratch.path(), &["run", "s.toml", "--csv", "-", "--json"]);
    assert_refused(&output, &["--csv -", "--json", "standard output"]);
    assert!(stdout(&output).is_empty());
}

// ---------------------------------------------------------------------------------------------------------------
// `-`, devices and FIFOs, symbolic links

#[test]
fn dash_writes_the_series_alone_to_standard_output() {
    let scratch = Scratch::new("dash");
    scratch.write("s.toml", SCENE);
    let output = impact(scratch.path(), &["run", "s.toml", "--csv", "-"]);
    assert_success(&output);
    let csv = stdout(&output);
    assert!(csv.starts_with(&format!("{SERIES_HEADER}\n")), "stdout starts with the series header:\n{csv}");
    assert!(csv.lines().skip(1).all(|line| line.split(',').count() == SERIES_CELLS), "only series rows:\n{csv}");
    // The readable report went to stderr instead; no file named `-` appeared.
    assert!(stderr(&output).contains("maximum penetration"), "{}", describe(&output));
    assert_eq!(scratch.files(), ["s.toml"]);
    // The same bytes as the series written to a file.
    assert_success(&impact(scratch.path(), &["run", "s.toml", "--csv", "s.csv"]));
    assert_eq!(csv, scratch.read("s.csv"));
}

#[test]
fn a_path_that_is_standard_output_itself_is_standard_output() {
    // What `--csv /dev/stdout` does when stdout is a pipe, without touching /dev: the process's own descriptor 1.
    let scratch = Scratch::new("proc-stdout");
    scratch.write("s.toml", SCENE);
    let output = impact(scratch.path(), &["run", "s.toml", "--csv", "/proc/self/fd/1"]);
    assert_success(&output);
    let csv = stdout(&output);
    assert!(csv.starts_with(&format!("{SERIES_HEADER}\n")), "{}", describe(&output));
    assert!(csv.lines().all(|line| line.split(',').count() == SERIES_CELLS), "only the series\n{}", describe(&output));
    assert!(stderr(&output).contains("maximum penetration"), "the report went to stderr\n{}", describe(&output));
}

#[test]
fn sweep_and_merge_write_to_standard_output_with_dash() {
    let scratch = Scratch::new("dash-sweep");
    two_shards(&scratch);
    let output = impact(scratch.path(), &["sweep", "s.toml", "--vary", "contact.restitution=0.5,0.6", "--out", "-"]);
    assert_success(&output);
    let whole = stdout(&output);
    assert!(whole.starts_with("index,status,law,contact.restitution,"), "{}", describe(&output));
    assert_eq!(whole.lines().count(), 3, "the header and two rows\n{whole}");
    let output = impact(scratch.path(), &["merge", "-", "s2.csv", "s1.csv"]);
    assert_success(&output);
    assert_eq!(stdout(&output), whole, "merged shards are the whole sweep");
    assert!(!scratch.exists("-"));
}

#[test]
fn a_fifo_is_written_in_place() {
    let scratch = Scratch::new("fifo");
    scratch.write("s.toml", SCENE);
    let fifo = scratch.path().join("series.csv");
    let made = Command::new("mkfifo").arg(&fifo).status().expect("mkfifo runs");
    assert!(made.success(), "mkfifo");
    // The reader opens the FIFO first: opening blocks until the writer comes.
    let (sender, received) = mpsc::channel();
    let path = fifo.clone();
    std::thread::spawn(move || {
        let _ = sender.send(fs::read_to_string(path));
    });
    let output = impact(scratch.path(), &["run", "s.toml", "--csv", "series.csv"]);
    assert_success(&output);
    assert!(fs::symlink_metadata(&fifo).expect("still there").file_type().is_fifo(), "the FIFO was replaced");
    let csv = received.recv_timeout(Duration::from_secs(60)).expect("the reader got an end of file").expect("read");
    assert!(csv.starts_with(&format!("{SERIES_HEADER}\n")) && csv.lines().count() > 10, "{csv}");
}

#[test]
fn a_symbolic_link_is_followed_and_stays_a_link() {
    let scratch = Scratch::new("symlink");
    scratch.write("s.toml", SCENE);
    fs::create_dir(scratch.path().join("data")).expect("a folder");
    // A link to a file that exists, and a link to a file that does not exist yet.
    scratch.write("data/old.csv", "earlier\n");
    std::os::unix::fs::symlink("data/old.csv", scratch.path().join("old-link.csv")).expect("a link");
    std::os::unix::fs::symlink("data/new.csv", scratch.path().join("new-link.csv")).expect("a link");
    for (link, target) in [("old-link.csv", "data/old.csv"), ("new-link.csv", "data/new.csv")] {
        assert_success(&impact(scratch.path(), &["run", "s.toml", "--csv", link]));
        let meta = fs::symlink_metadata(scratch.path().join(link)).expect("the link");
        assert!(meta.file_type().is_symlink(), "{link} is still a link");
        assert!(scratch.read(target).starts_with(SERIES_HEADER), "{target} received the series");
    }
    assert!(temporaries(scratch.path()).is_empty(), "{:?}", temporaries(scratch.path()));
}

// ---------------------------------------------------------------------------------------------------------------
// Complete or absent

#[test]
fn an_unfinished_output_leaves_the_earlier_file_and_no_temporary() {
    let scratch = Scratch::new("unfinished");
    let target = scratch.path().join("table.csv");
    fs::write(&target, "earlier\n").expect("an earlier file");
    let destination = Destination::resolve(&target).expect("a regular file");
    let mut output = OutputFile::create(&destination).expect("a temporary beside it");
    output.write_bytes(b"half a table").expect("written to the temporary");
    assert_eq!(temporaries(scratch.path()).len(), 1, "the temporary exists while writing");
    drop(output); // as on any error before `finish`
    assert_eq!(scratch.read("table.csv"), "earlier\n");
    assert_eq!(scratch.files(), ["table.csv"]);

    let mut output = OutputFile::create(&destination).expect("a temporary beside it");
    output.write_bytes(b"a whole table\n").expect("written");
    assert_eq!(scratch.read("table.csv"), "earlier\n", "nothing shows before finish");
    output.finish().expect("renamed into place");
    assert_eq!(scratch.read("table.csv"), "a whole table\n");
    assert_eq!(scratch.files(), ["table.csv"]);
}

#[test]
fn a_run_whose_figures_cannot_be_written_writes_no_series() {
    let scratch = Scratch::new("figure-fails");
    scratch.write("s.toml", SCENE);
    scratch.write("blocked", "a file where the figures' parent folder should be");
    let output = impact(scratch.path(), &["run", "s.toml", "--csv", "s.csv", "--plot", "blocked/figs"]);
    assert_eq!(output.status.code(), Some(1), "{}", describe(&output));
    assert!(stderr(&output).contains("blocked/figs"), "{}", describe(&output));
    assert!(!scratch.exists("s.csv"), "the series is written with its figures or not at all");
    assert!(temporaries(scratch.path()).is_empty(), "{:?}", temporaries(scratch.path()));
}

#[test]
fn an_interrupted_sweep_leaves_no_temporary_and_exits_130() {
    let scratch = Scratch::new("interrupted");
    scratch.write("s.toml", SCENE);
    // A million rows: hours in a debug build, so the sweep is surely interrupted while it writes.
    let mut child = Command::new(env!("CARGO_BIN_EXE_impact"))
        .args(["sweep", "s.toml", "--vary", "contact.restitution=0.01:1:1000000", "--threads", "1", "--out", "e.csv"])
        .current_dir(scratch.path())
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .expect("the binary starts");
    let start = Instant::now();
    while temporaries(scratch.path()).is_empty() && start.elapsed() < Duration::from_secs(60) {
        std::thread::sleep(Duration::from_millis(20));
    }
    let writing = !temporaries(scratch.path()).is_empty();
    let sent = Command::new("kill").args(["-INT", &child.id().to_string()]).status().expect("kill runs");
    assert!(sent.success());
    let status = loop {
        if let Some(status) = child.try_wait().expect("the child's status") {
            break status;
        }
        if start.elapsed() > Duration::from_secs(120) {
            let _ = child.kill();
            panic!("the sweep did not stop on SIGINT");
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    assert!(writing, "the sweep streams its rows into a temporary file from the start");
    assert_eq!(status.code(), Some(130), "status {status:?}");
    assert!(temporaries(scratch.path()).is_empty(), "{:?}", temporaries(scratch.path()));
    assert_eq!(scratch.files(), ["s.toml"]);
}
