//! The stress run (issue 6 part 4; README.md#stress-run) and determinism: a short run of random scenes passes
//! every check, the checks catch a wrong report, and the same scene gives bit-identical reports (all but the wall
//! time) across runs and thread counts.

mod common;
use common::binary::{Scratch, assert_success, impact, stdout};
use impact::history::Recording;
use impact::impact::simulate;
use impact::scene::Scene;
use impact::stress;
use std::path::Path;

fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("a thread pool")
}

#[test]
fn a_short_stress_run_passes_every_check() {
    // 300 random scenes (the narrowed ranges of --quick, which run fast in a debug build): every law, both criteria,
    // spheres, still and moving walls and fixed spheres, oblique, spins, positions. (Friction is left to the stress
    // verb: the frictional 3-D model is still short of 1e-9 against rigid-body theory on some scenes.)
    let summary = stress::run(6, 0, 300, true, &|| {});
    assert_eq!(summary.cases, 300);
    assert_eq!(summary.failures, 0, "failed scenes:\n{}", summary.failed.join("\n"));
    // Most cases are checked (not refused or stuck), and the checks that matter ran.
    let checked: u64 = summary.outcomes.iter().filter(|(k, _)| k.starts_with("checked")).map(|(_, n)| n).sum();
    assert!(checked >= 270, "outcomes {:?}", summary.outcomes);
    for quantity in [
        "momentum",
        "angular_momentum",
        "energy_balance",
        "energy_balance_relative",
        "exact.dissipated",
        "exact.elastic_left_at_separation",
        "reference.restitution",
        "reference.duration",
        "flight.start_time",
        "impulse_ratio_vs_velocity_ratio",
    ] {
        assert!(summary.worst.contains_key(quantity), "{quantity} was never checked: {:?}", summary.worst.keys());
    }
}

/// Full-range scenes 633 and 3022 of seed 13: a damped Kelvin–Voigt sphere sliding on a moving wall, whose force
/// jumps to c v0 at first contact. Its spring loads below the Coulomb limit for an instant there (under a
/// picosecond), yet it must still be checked against rigid-body sliding — the check that found it once starting to
/// slide with an unloaded spring, 3.8e-9 and 3e-8 of v0 short of it.
#[test]
fn a_kelvin_voigt_contact_sliding_after_its_first_instant_is_checked_against_rigid_body_theory() {
    for case in [633, 3022] {
        let summary = stress::run(13, case, 1, false, &|| {});
        assert_eq!(summary.failures, 0, "case {case}:\n{}", summary.failed.join("\n"));
        for quantity in ["rigid_body.velocity_after", "rigid_body.angular_velocity_after"] {
            assert!(summary.worst.contains_key(quantity), "case {case}: {quantity} not checked");
        }
    }
}

#[test]
fn the_checks_catch_a_wrong_energy_a_lost_momentum_and_a_nan() {
    // A passing report, then the same report with one number spoiled: each spoiling must be reported.
    let text = stress::scene_text(6, 3, true);
    let scene = Scene::parse(&text, Path::new("case.toml")).expect("a valid stress scene");
    let report = simulate(&scene, Recording::Off).expect("simulation").report;
    assert!(report.contact.separated);
    assert!(stress::check_report(&scene, &report, None).1.is_empty());
    let mut spoiled = report.clone();
    *spoiled.energy.dissipated.as_mut().unwrap() *= 1.0 + 1e-7;
    assert!(!stress::check_report(&scene, &spoiled, None).1.is_empty(), "a dissipated energy 1e-7 off passes");
    let mut spoiled = report.clone();
    spoiled.bodies[1].velocity_after.as_mut().unwrap()[0] += 1e-6 * report.approach_speed;
    assert!(!stress::check_report(&scene, &spoiled, None).1.is_empty(), "a velocity 1e-6 v0 off passes");
    let mut spoiled = report.clone();
    spoiled.contact.max_force = f64::NAN;
    let problems = stress::check_report(&scene, &spoiled, None).1;
    assert!(problems.iter().any(|p| p.contains("non-finite")), "{problems:?}");
}

#[test]
fn the_summary_does_not_depend_on_the_thread_count() {
    let one = pool(1).install(|| stress::run(9, 100, 40, true, &|| {}));
    let two = pool(2).install(|| stress::run(9, 100, 40, true, &|| {}));
    assert_eq!(one, two);
}

#[test]
fn the_same_scene_gives_bit_identical_reports_across_runs_and_threads() {
    let strip = |mut report: impact::report::Report| {
        report.solver.wall_time_s = 0.0;
        serde_json::to_string(&report).expect("serialises")
    };
    let texts: Vec<String> = (0..12).map(|i| stress::scene_text(21, i, true)).collect();
    let reports = |threads: usize| -> Vec<Option<String>> {
        pool(threads).install(|| {
            use rayon::prelude::*;
            texts
                .par_iter()
                .map(|text| {
                    let scene = Scene::parse(text, Path::new("case.toml")).ok()?;
                    simulate(&scene, Recording::Off).ok().map(|s| strip(s.report))
                })
                .collect()
        })
    };
    let (first, again, parallel) = (reports(1), reports(1), reports(2));
    assert!(first.iter().filter(|r| r.is_some()).count() >= 10);
    assert_eq!(first, again);
    assert_eq!(first, parallel);
}

#[test]
fn the_verb_prints_its_json_and_exits_zero() {
    let scratch = Scratch::new("the_verb_prints_its_json_and_exits_zero");
    let args = ["stress", "--quick", "--count", "12", "--seed", "4", "--json", "--threads", "2"];
    let output = impact(scratch.path(), &args);
    assert_success(&output);
    let value: serde_json::Value = serde_json::from_str(&stdout(&output)).expect("JSON on stdout");
    assert_eq!(value["cases"], 12);
    assert_eq!(value["failures"], 0);
    assert!(value["worst"].is_object() && value["failed"].as_array().is_some_and(|a| a.is_empty()));
    // The same seed gives the same summary with one thread (all but the time it took).
    let single =
        impact(scratch.path(), &["stress", "--quick", "--count", "12", "--seed", "4", "--json", "--threads", "1"]);
    let mut other: serde_json::Value = serde_json::from_str(&stdout(&single)).expect("JSON on stdout");
    let mut value = value;
    value["seconds"] = serde_json::Value::Null;
    other["seconds"] = serde_json::Value::Null;
    assert_eq!(value, other);
    // The scenes can be printed, to rerun one with `impact run`.
    let scenes =
        impact(scratch.path(), &["stress", "--quick", "--count", "1", "--seed", "4", "--start", "3", "--scenes"]);
    assert_success(&scenes);
    assert_eq!(stdout(&scenes).trim_end(), format!("# case 3\n{}", stress::scene_text(4, 3, true)).trim_end());
    // Bad arguments exit 2.
    assert_eq!(impact(scratch.path(), &["stress", "--count", "0"]).status.code(), Some(2));
}

#[test]
fn a_run_report_is_bit_identical_across_runs() {
    let scratch = Scratch::new("a_run_report_is_bit_identical_across_runs");
    let path = scratch.scene("case.toml", &stress::scene_text(21, 5, true));
    let strip = |text: String| {
        let mut value: serde_json::Value = serde_json::from_str(&text).expect("JSON");
        value["solver"]["wall_time_s"] = serde_json::Value::Null;
        value.to_string()
    };
    let first = impact(scratch.path(), &["run", &path, "--json"]);
    let second = impact(scratch.path(), &["run", &path, "--json"]);
    assert_success(&first);
    assert_eq!(strip(stdout(&first)), strip(stdout(&second)));
}

/// Seed 424242's case 9628 once drew a Tsuji contact ended by its force with a damping (a = 8.4e7, e = 1.8e-16)
/// the scene rules now refuse; the generator draws such contacts only over the accepted range (zeta below about
/// 5e4), and the case and its neighbours pass.
#[test]
fn seed_424242_case_9628_and_its_neighbours_pass() {
    let summary = stress::run(424242, 9620, 16, false, &|| {});
    assert_eq!(summary.failures, 0, "{}", summary.failed.join("\n"));
    assert!(summary.outcomes.keys().all(|class| !class.starts_with("refused")), "{:?}", summary.outcomes);
}

/// `impact stress --worlds`: random worlds (3 to 8 spheres, gravity and a floor or none, every law, both separation
/// criteria, both damping maps) keep their energy balance, momentum and angular momentum, and end with no two bodies
/// overlapping outside a contact. Case 1696 of seed 7 presses a pair back together on the overlap its force-ended
/// contact left (the balance once missed that spring's energy by 3.5e-4).
#[test]
fn random_worlds_pass_every_check() {
    // Quick worlds (a shorter run of each) for the debug build; the full ones are the verb's.
    let summary = stress::run_worlds(7, 0, 64, true, &|| {});
    assert_eq!(summary.failures, 0, "failed worlds:\n{}", summary.failed.join("\n"));
    for quantity in ["world.energy_balance", "world.momentum", "world.angular_momentum", "world.overlap_after"] {
        assert!(summary.worst.contains_key(quantity), "{quantity} was never checked: {:?}", summary.worst.keys());
    }
    let summary = stress::run_worlds(7, 1696, 1, false, &|| {});
    assert_eq!(summary.failures, 0, "case 1696:\n{}", summary.failed.join("\n"));
}

/// Quick world 3 of seed 5150 (four rough spheres, `thornton`): a yielding contact ended at its dent is pressed again
/// before its gap opens, and the new contact once reloaded a fresh Hertz spring at that overlap, whose energy came
/// from nowhere (the balance missed it by 1.08e-3, elastic energy at the end -22.8 µJ). It reloads the dent along
/// its unloading curve now (tests/thornton.rs checks such a chain against an RK4), and the case passes.
#[test]
fn a_world_whose_yielding_contact_is_pressed_again_on_its_dent_keeps_its_energy_balance() {
    let summary = stress::run_worlds(5150, 3, 1, true, &|| {});
    assert_eq!(summary.failures, 0, "case 3:\n{}", summary.failed.join("\n"));
    let balance = summary.worst.get("world.energy_balance").expect("the balance is checked");
    assert!(*balance <= 1e-9, "balance {balance}");
}

#[test]
fn frictional_contacts_whose_force_a_damper_cuts_separate_and_pass_every_check() {
    // `impact stress --count 20000 --seed 424243`: two sliding `mujoco` contacts (mu 0.004) spent the step budget
    // before maximum compression while the 3-D model's sliding spring followed the cap's size (2644, 11241); two
    // `adams-impact` contacts of a few nanoseconds, their force cut to zero inside the contact, gave up 1.5 pm before
    // separating where a sliding direction reversed against the slip was brought onto it at the fastest turning rate
    // (13218, 15255: a rule the 3-D model's sliding state no longer has). Each separates and passes every check.
    for index in [2644, 11241, 13218, 15255] {
        let summary = stress::run(424243, index, 1, false, &|| {});
        assert_eq!(summary.failures, 0, "case {index}:\n{}", summary.failed.join("\n"));
        let checked: u64 = summary.outcomes.iter().filter(|(k, _)| k.starts_with("checked")).map(|(_, n)| n).sum();
        assert_eq!(checked, 1, "case {index}: {:?}", summary.outcomes);
    }
}

#[test]
fn the_cases_a_fresh_measurement_failed_pass_every_check() {
    // `impact stress --count 20000 --seed 424242` failed eight cases (issue 33): six sliding contacts held to rigid-
    // body theory's mu J_n where friction rubs through their pull too (and a spring left reversed where a cut
    // force pushed again), and two `mujoco` contacts whose energy balance missed 1e-9 (an elastic energy taken at
    // the wrong zero of a falling impedance; an impedance rough at the contact's edges). Each is checked against the
    // references that apply to it; and case 11645, which a damper cut to zero force kept from separating within
    // the step budget, separates and passes as well.
    for index in [1875, 6623, 7549, 8348, 10014, 16680, 18040, 19426, 11645] {
        let summary = stress::run(424242, index, 1, false, &|| {});
        assert_eq!(summary.failures, 0, "case {index}:\n{}", summary.failed.join("\n"));
        let checked: u64 = summary.outcomes.iter().filter(|(k, _)| k.starts_with("checked")).map(|(_, n)| n).sum();
        assert_eq!(checked, 1, "case {index}: {:?}", summary.outcomes);
    }
}
