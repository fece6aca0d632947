//! `impact bench`: the work–precision study writes its CSV (the columns, one row per method, setting and
//! case) and its figure, and its errors are the methods' own against the exact references; Dopri5 as a
//! `[solver] method`. Speed is measured by the study, never asserted here.

mod common;

use common::binary::{Scratch, assert_success, describe, impact, stdout};
use common::{assert_close, on_wall};

#[test]
fn the_study_writes_its_table_and_figure() {
    let scratch = Scratch::new("quick");
    let output = impact(scratch.path(), &["bench", "--quick", "--case", "hertz", "--out", "study"]);
    assert_success(&output);
    let text = stdout(&output);
    assert!(text.contains("machine:") && text.contains("load average"), "{text}");
    for method in
        ["taylor", "taylor-motion", "first-integral", "first-integral-timed", "dop853", "dopri5", "rk4", "verlet"]
    {
        assert!(text.lines().any(|l| l.starts_with(method)), "{method} missing from the summary:\n{text}");
    }
    let csv = scratch.read("study/bench.csv");
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().expect("a header").split(',').collect();
    for column in ["method", "case", "tolerance", "error", "seconds_per_impact", "force_evaluations"] {
        assert!(header.contains(&column), "no column {column}: {header:?}");
    }
    let column = |name: &str| header.iter().position(|c| *c == name).expect("a column");
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    // Quick: the fast path at 3 tolerances (every quantity, and the motion alone), the first integral once without
    // the times and once with them (Hertz is of its family), Dop853 and Dopri5 at 2, RK4 and Verlet at 2 step
    // counts; one case.
    assert_eq!(rows.len(), 16, "{csv}");
    for row in &rows {
        assert_eq!(row.len(), header.len(), "{row:?}");
        assert_eq!(row[column("case")], "hertz n=1.5");
        let seconds: f64 = row[column("seconds_per_impact")].parse().expect("a time");
        assert!(seconds > 0.0 && seconds < 1.0, "{row:?}");
        let evaluations: u64 = row[column("force_evaluations")].parse().expect("a count");
        assert!(evaluations > 0, "{row:?}");
        let error: f64 = row[column("error")].parse().expect("an error");
        // The largest error is the largest of the quantities' own; the motion alone has none for the times and the
        // peak force (empty cells), every other method one for each.
        let motion = row[column("method")] == "taylor-motion";
        let untimed = row[column("method")] == "first-integral";
        let mut own = 0.0_f64;
        for name in ["error_e", "error_dmax", "error_t0", "error_tc", "error_fmax", "error_jd", "error_jr"] {
            let cell = row[column(name)];
            if (motion && ["error_t0", "error_tc", "error_fmax"].contains(&name))
                || (untimed && ["error_t0", "error_tc"].contains(&name))
            {
                assert_eq!(cell, "", "{name}: {row:?}");
            } else {
                own = own.max(cell.parse().expect("an error"));
            }
        }
        assert_eq!(own, error, "{row:?}");
        // Accuracy, not speed: each method meets its tolerance against Hertz's closed forms.
        let tolerance = row[column("tolerance")];
        let bound = match (row[column("method")], tolerance) {
            ("taylor" | "taylor-motion", _) => 10.0 * tolerance.parse::<f64>().expect("a tolerance") + 1e-14,
            // Closed forms and a root, to rounding.
            ("first-integral", _) => 1e-14,
            // The times by quadrature, to about 1e-15 against Hertz's Beta function.
            ("first-integral-timed", _) => 1e-14,
            ("dop853" | "dopri5", _) => 1e3 * tolerance.parse::<f64>().expect("a tolerance"),
            ("rk4", _) => 1e-5,
            // Events at the first step past them: a time late by up to a step of tc/N.
            ("verlet", _) => 4.0 / row[column("steps")].parse::<f64>().expect("steps"),
            (other, _) => panic!("unknown method {other}"),
        };
        assert!(error <= bound, "{row:?}: {error:e} > {bound:e}");
    }
    // The errors are measured, not assumed: the fixed-step methods' fall with the step as their order allows, and
    // none is zero. RK4 is of order 4, but Hertz's d^(3/2) has a singular second derivative at the contact's edges,
    // which leaves order 5/2: 10^2.5 = 316 over a tenfold N (at least 100 asked). Verlet takes its events at the
    // first step past them, first order: at least 5.
    let error_of = |method: &str, steps: &str| -> f64 {
        let row = rows.iter().find(|r| r[column("method")] == method && r[column("steps")] == steps).expect("a row");
        row[column("error")].parse().expect("an error")
    };
    for method in ["rk4", "verlet"] {
        let (coarse, fine) = (error_of(method, "100"), error_of(method, "1000"));
        assert!(fine > 0.0, "{method}: an error of exactly zero is not measured");
        let gain = if method == "rk4" { 100.0 } else { 5.0 };
        assert!(coarse > gain * fine, "{method}: N = 100 gives {coarse:e}, N = 1000 {fine:e}");
    }
    assert!(scratch.read("study/bench.svg").starts_with("<svg"));
    let png = std::fs::read(scratch.path().join("study/bench.png")).expect("the PNG");
    assert_eq!(&png[1..4], b"PNG");
}

#[test]
fn a_case_filter_that_matches_nothing_is_refused() {
    let scratch = Scratch::new("no-case");
    let output = impact(scratch.path(), &["bench", "--quick", "--case", "no such law", "--out", "study"]);
    assert_eq!(output.status.code(), Some(2), "{}", describe(&output));
    assert!(describe(&output).contains("hunt-crossley x=0.5 n=1.5"), "the message lists the cases");
    assert!(!scratch.exists("study"));
}

#[test]
fn its_outputs_are_checked_before_the_study_and_written_all_or_none() {
    let scratch = Scratch::new("bench-outputs");
    // An existing file named as the folder: refused before any work (exit 2), the file untouched.
    scratch.write("taken", "a user's file\n");
    let output = impact(scratch.path(), &["bench", "--quick", "--case", "hertz", "--out", "taken"]);
    assert_eq!(output.status.code(), Some(2), "{}", describe(&output));
    assert!(describe(&output).contains("not a folder"), "{}", describe(&output));
    assert_eq!(scratch.read("taken"), "a user's file\n");
    // Before any work: before even the cases are chosen (a filter that matches nothing is not what is reported).
    let output = impact(scratch.path(), &["bench", "--quick", "--case", "no such case", "--out", "taken"]);
    assert!(describe(&output).contains("not a folder"), "{}", describe(&output));
    // One of the three outputs cannot be written (a folder has its name): nothing is written, not even the others.
    std::fs::create_dir_all(scratch.path().join("study/bench.svg")).expect("a folder");
    let output = impact(scratch.path(), &["bench", "--quick", "--case", "hertz", "--out", "study"]);
    assert_ne!(output.status.code(), Some(0), "{}", describe(&output));
    let output = impact(scratch.path(), &["bench", "--quick", "--case", "no such case", "--out", "study"]);
    assert!(describe(&output).contains("bench.svg"), "{}", describe(&output));
    assert!(!scratch.exists("study/bench.csv") && !scratch.exists("study/bench.png"));
    assert!(scratch.files().iter().all(|f| !f.contains("partial")), "{:?}", scratch.files());
}

#[test]
fn dopri5_is_a_solver_method_named_in_the_report() {
    // Hertz's closed forms (docs/references.md): the report's reference section holds the errors.
    let report = on_wall(1.0, 1.0, "law = \"hertz\"\nstiffness = 1e6\n\n[solver]\nmethod = \"dopri5\"\nrtol = 1e-10");
    assert_eq!(report.solver.method, "dopri5");
    let errors = report.reference.expect("Hertz has an exact reference").errors;
    for (what, error) in [("e", errors.restitution), ("dmax", errors.max_penetration), ("tc", errors.duration)] {
        assert!(error.expect("an error") < 1e-8, "{what}: {error:?}");
    }
    assert_close("e", report.contact.restitution_velocity_ratio.unwrap(), 1.0, 1e-8);
}

/// The world study (`impact bench --worlds`): each run's error against the reference run shrinks with the tolerance,
/// and stays within a few hundred tolerances (the chain's error is global: it accumulates along the pulse's path).
/// Run here on a chain of 30 beads, the 5-ball cradle and the rod's chatter, at two tolerances. The rod's 45 strikes
/// each carry the last one's error into the next (where the next end strikes moves with it): its bound is looser.
#[test]
fn the_world_study_measures_errors_that_follow_the_tolerance() {
    use impact::bench::worlds;
    let cases = vec![worlds::chain(30), worlds::cradle(), worlds::rod_chatter()];
    let mut seen = 0;
    let rows = worlds::study(&cases, &[1e-6, 1e-10], |_| seen += 1).expect("the study runs");
    assert_eq!(seen, 6);
    for (case, bound) in [("chain-30", 300.0), ("cradle-5", 300.0), ("rod-chatter", 3000.0)] {
        let own: Vec<_> = rows.iter().filter(|r| r.case == case).collect();
        assert_eq!(own.len(), 2, "{rows:?}");
        let (loose, tight) = (own[0], own[1]);
        assert!(loose.error > 100.0 * tight.error, "{rows:?}");
        assert!(loose.error < bound * 1e-6 && tight.error < bound * 1e-10, "{rows:?}");
        assert!(own.iter().all(|r| r.seconds > 0.0 && r.steps > 0 && r.contacts >= 4), "{rows:?}");
    }
    // The rod strikes as many times at either tolerance: the chatter's sequence is the physics', not the tolerance's.
    let strikes: Vec<usize> = rows.iter().filter(|r| r.case == "rod-chatter").map(|r| r.contacts).collect();
    assert!(strikes[0] == strikes[1] && strikes[0] > 6, "{rows:?}");
    let csv = worlds::csv(&rows);
    assert!(csv.starts_with("case,tolerance,error,seconds,steps,contacts\n"), "{csv}");
    assert_eq!(csv.lines().count(), 7);
}

/// The peers' scene (`scripts/peer-hunt-crossley.toml`, what scripts/peers.sh sweeps) is a scene the program takes,
/// and its e and its maximum penetration are the exact ones of its scaled units (m* = K = v0 = 1, n = 3/2,
/// x = alpha v0 = 0.5): e from the relation x (1 + e) = ln((1 + x)/(1 - e x)) and dmax from
/// dmax^(5/2) = (5/2)(x - ln(1 + x))/x², both solved here. A sweep of e alone over it (the first integral)
/// writes the same e.
#[test]
fn the_peers_scene_runs_and_gives_the_exact_e() {
    let scratch = Scratch::new("peers-scene");
    let scene = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scripts/peer-hunt-crossley.toml");
    let scene = scene.to_str().expect("a path");
    let output = impact(scratch.path(), &["run", scene, "--json"]);
    assert_success(&output);
    let report: serde_json::Value = serde_json::from_slice(&output.stdout).expect("JSON");
    let x: f64 = 0.5;
    // Bisection on the exact relation (its left side minus its right grows with e up to 1/x).
    let (mut low, mut high) = (0.0_f64, 1.0_f64);
    for _ in 0..200 {
        let mid = 0.5 * (low + high);
        if x * (1.0 + mid) - (1.0 + x).ln() + (1.0 - mid * x).ln() > 0.0 {
            low = mid;
        } else {
            high = mid;
        }
    }
    let e = 0.5 * (low + high);
    let dmax = (2.5 * (x - x.ln_1p()) / (x * x)).powf(0.4);
    let contact = &report["contact"];
    let got = contact["restitution_velocity_ratio"].as_f64().expect("e");
    assert_close("e", got, e, 1e-10);
    assert_close("dmax", contact["max_penetration"].as_f64().expect("dmax"), dmax, 1e-10);
    let sweep = impact(
        scratch.path(),
        &[
            "sweep",
            scene,
            "--vary",
            "contact.damping=0.5",
            "--columns",
            "restitution_velocity_ratio,steps",
            "--out",
            "e.csv",
        ],
    );
    assert_success(&sweep);
    let csv = scratch.read("e.csv");
    let row: Vec<&str> = csv.lines().nth(1).expect("a row").split(',').collect();
    assert_close("e of the sweep", row[4].parse().expect("e"), e, 1e-14);
    assert_eq!(row[5], "0", "the first integral takes no step: {csv}");
}

/// `impact bench --oblique`: the frictional cases on the path `auto` takes (a sphere on a wall in closed form where
/// it slides to its end, in regularised time otherwise), on the slides asked for by name (a wall) and on the 3-D
/// model in physical time, and their frictionless twins (the wall's on the fast path), each row's
/// error against the run at 1e-13 within what its tolerance allows; the CSV has a row per case, path and
/// tolerance. Accuracy, not speed.
#[test]
fn the_oblique_study_measures_frictional_impacts_beside_their_twins() {
    let scratch = Scratch::new("oblique");
    let output = impact(scratch.path(), &["bench", "--oblique", "--quick", "--out", "study"]);
    assert_success(&output);
    let text = stdout(&output);
    assert!(
        text.contains("chung-ooi test 4 at 45 deg") && text.contains("hunt-crossley wall") && text.contains("vs twin"),
        "{text}"
    );
    let csv = scratch.read("study/bench-oblique.csv");
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().expect("a header").split(',').collect();
    let column = |name: &str| header.iter().position(|c| *c == name).expect("a column");
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    // Six cases, four paths for two spheres (their central twin the fourth) and five for a wall (its two slides),
    // two tolerances.
    assert_eq!(rows.len(), 2 * (2 * 4 + 4 * 5), "{csv}");
    for row in &rows {
        let (path, method) = (row[column("path")], row[column("method")]);
        let case = row[column("case")];
        let wall = !case.starts_with("two free spheres");
        // (A wall: integrated up to its last slide, which runs in closed form.)
        match path {
            "auto" => assert_eq!(method, if wall { "closed-form-slide" } else { "dop853" }, "{row:?}"),
            "taylor-slide" => assert!(wall && method == "taylor-slide", "{row:?}"),
            "dop853-slide" => assert!(wall && method == "dop853-slide", "{row:?}"),
            "dop853" => assert_eq!(method, "dop853", "{row:?}"),
            "frictionless" => assert_eq!(method, if wall { "taylor" } else { "dop853" }, "{row:?}"),
            "central" => assert!(!wall && method == "taylor", "{row:?}"),
            other => panic!("unknown path {other}"),
        }
        let tolerance: f64 = row[column("tolerance")].parse().expect("a tolerance");
        let error: f64 = row[column("error")].parse().expect("an error");
        assert!(error > 0.0 && error <= 100.0 * tolerance, "{row:?}");
        let seconds: f64 = row[column("seconds_per_impact")].parse().expect("a time");
        assert!(seconds > 0.0, "{row:?}");
    }
    let refused = impact(scratch.path(), &["bench", "--oblique", "--worlds", "--out", "study"]);
    assert_eq!(refused.status.code(), Some(2), "{}", describe(&refused));
}
