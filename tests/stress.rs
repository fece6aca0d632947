//! Extreme but valid scenes end with a clear outcome in bounded work, never a hang, a NaN or a panic.

mod common;
use common::{assert_close, on_wall};
use impact::integrate::STEP_BUDGET;

#[test]
fn creeping_restitution_ends_with_a_note_within_the_step_budget() {
    // x = alpha v0 = 1e6: e ≈ 1/x = 1e-6 (docs/references.md#the-hunt-crossley-family), a restitution lasting ~1e6
    // elastic time units and stiff for an explicit method. The run must stop within its budget and say why.
    for contact in [
        "law = \"kelvin-voigt\"\ndamping = 1e6\nstiffness = 1e6",
        "law = \"brilliantov\"\ndamping = 10\nstiffness = 1e6",
    ] {
        // (The general path: the fast one follows x = 1e6 to its separation, below.)
        let report = on_wall(1.0, 1.0, &format!("{contact}\n\n[solver]\nmethod = \"dop853\""));
        assert!(!report.contact.separated, "{contact}");
        let work = report.solver.steps + report.solver.rejected_steps;
        assert!(work <= STEP_BUDGET + 1000, "{contact}: {work} steps");
        assert!(report.notes.iter().any(|n| n.contains("did not separate")), "{contact}: {:?}", report.notes);
        assert!(report.contact.max_penetration.is_finite() && report.contact.max_force.is_finite());
        let why = report.solver.gave_up.as_deref().unwrap_or_else(|| panic!("{contact}: the integration gave up"));
        assert!(why.contains("budget") || why.contains("stiff"), "{contact}: {why}");
    }
}

#[test]
fn a_creeping_hunt_crossley_restitution_ends_at_its_exact_e() {
    // x = alpha v0 = 1e6 for Hunt–Crossley: its force `K d^n (1 + x d')` never pulls, and in the creep `1 + x d'` is
    // within rounding of zero. Summed as spring plus damper it rounded below zero at random there, and the general
    // path spent its whole budget on that noise; held at zero, it follows the creep to its separation, at the exact e
    // of the first integral (v0 = 1: e in units of v0).
    let report =
        on_wall(1.0, 1.0, "law = \"hunt-crossley\"\ndamping = 1e6\nstiffness = 1e6\n\n[solver]\nmethod = \"dop853\"");
    assert!(report.contact.separated, "{:?}", report.notes);
    let e = report.contact.restitution_velocity_ratio.expect("separated");
    // The first integral's `G(-e) = G(1)`, `G(v) = v/x - ln(1 + x v)/x²`: `1 - x e = (1 + x) exp(-x (1 + e))`, which
    // is e^(-1e6), zero in double precision: e = 1/x.
    let exact = 1.0 / 1e6;
    assert!((e - exact).abs() <= 1e-12, "e {e:e} against {exact:e}");
    assert!(report.solver.steps + report.solver.rejected_steps < 10_000, "{:?}", report.solver);
}

#[test]
fn an_impact_whose_integration_gave_up_writes_its_report_and_exits_1() {
    // The creeping Kelvin–Voigt contact above, from the command: the JSON report (its bodies in contact, the reason
    // in solver.gave_up) on stdout, the reason on stderr, status 1 — an impact the integration could not finish
    // is not a success. A contact that dies out (critically damped Kelvin–Voigt, which never separates at d = 0)
    // ends on its own terms: status 0, no reason.
    let scratch = common::binary::Scratch::new("gave_up");
    let scene = |contact: &str| {
        format!(
            "[[bodies]]\nradius = 1.0\nmass = 1.0\nvelocity = [1.0, 0.0, 0.0]\n\n[[bodies]]\nradius = inf\nmass = inf\n\
             velocity = [0.0, 0.0, 0.0]\n\n[contact]\n{contact}\n\n[solver]\nmethod = \"dop853\"\n"
        )
    };
    let creeping = scratch.scene("creeping.toml", &scene("law = \"kelvin-voigt\"\ndamping = 1e6\nstiffness = 1e6"));
    let output = common::binary::impact(scratch.path(), &["run", &creeping, "--json"]);
    assert_eq!(output.status.code(), Some(1), "{}", common::binary::describe(&output));
    let report: serde_json::Value = serde_json::from_str(&common::binary::stdout(&output)).expect("the JSON report");
    assert_eq!(report["contact"]["separated"], false);
    assert!(report["solver"]["gave_up"].as_str().is_some_and(|why| why.contains("budget")), "{}", report["solver"]);
    assert!(common::binary::stderr(&output).contains("gave up"), "{}", common::binary::describe(&output));
    let settled = scratch.scene(
        "settled.toml",
        &scene(
            "law = \"kelvin-voigt\"\nrestitution = 0.0\nstiffness = 1e6\nexponent = 1.0\nseparation = \"penetration\"",
        ),
    );
    let output = common::binary::impact(scratch.path(), &["run", &settled, "--json"]);
    assert_eq!(output.status.code(), Some(0), "{}", common::binary::describe(&output));
    let report: serde_json::Value = serde_json::from_str(&common::binary::stdout(&output)).expect("the JSON report");
    assert_eq!(report["contact"]["separated"], false);
    assert!(report["solver"]["gave_up"].is_null(), "{}", report["solver"]);
}

#[test]
fn a_tangential_spring_far_stiffer_than_the_normal_contact_converges_to_its_rigid_limit() {
    // Two free spheres sliding across each other (the slip turns with the line of centres and the spin), the tangential
    // spring up to a million times the normal one (Mindlin's is about as stiff). While sliding, the spring's direction
    // relaxes towards the slip's at kt |slip| / |T|; before that relaxation's rate coefficient was capped (docs/
    // oblique.md), the work grew with kt (236 steps at kt = 1e6, 23,457 at 1e8) and from 1e9 on the compression outran
    // the budget of 300,000 steps. Now every run ends, and as kt grows the spring's lag (~ 1/kt) vanishes: the
    // velocities converge to the rigid-plastic slider's, each tenfold stiffer spring closer to the stiffest one.
    let text = |kt: f64| {
        format!(
            "[[bodies]]\nradius = 0.01\nmass = 0.02\nvelocity = [3.0, 8.0, 0.0]\nangular_velocity = [0.0, 0.0, 50.0]\n\n\
             [[bodies]]\nradius = 0.015\nmass = 0.05\nvelocity = [-1.0, -0.5, 0.3]\n\n\
             [contact]\nlaw = \"kelvin-voigt\"\nstiffness = 1e6\nexponent = 1.0\nrestitution = 0.8\n\
             friction = 0.05\ntangential_stiffness = {kt:e}\nnormal = [1.0, 0.0, 0.0]\n"
        )
    };
    let after = |kt: f64| {
        let scene = impact::scene::Scene::parse(&text(kt), std::path::Path::new("stiff.toml")).expect("a valid scene");
        let simulation = impact::impact::simulate(&scene, impact::history::Recording::Off)
            .unwrap_or_else(|e| panic!("kt = {kt:e}: {e}"));
        let report = simulation.report;
        assert!(report.contact.separated, "kt = {kt:e}: {:?}", report.notes);
        nalgebra::Vector3::from(report.bodies[1].velocity_after.expect("separated"))
    };
    let stiffest = after(1e12);
    let mut previous = f64::INFINITY;
    for kt in [1e8, 1e9, 1e10, 1e11] {
        let departure = (after(kt) - stiffest).amax();
        assert!(departure < previous, "kt = {kt:e}: {departure:e} from kt = 1e12, not below {previous:e}");
        previous = departure;
    }
    assert!(previous < 1e-9, "kt = 1e11 is {previous:e} m/s from kt = 1e12");
}

#[test]
fn the_fast_path_follows_a_creeping_restitution_to_its_end() {
    // x = 1e6: 1 - e x = (1 + x) exp(-x (1 + e)) is below 1e-400000, so e = 1/x to double precision.
    let report = on_wall(1.0, 1.0, "law = \"hunt-crossley\"\ndamping = 1e6\nstiffness = 1e6");
    assert_eq!(report.solver.method, "taylor");
    assert!(report.contact.separated);
    assert_close("e", report.contact.restitution_velocity_ratio.unwrap(), 1e-6, 1e-3);
}

#[test]
fn heavy_but_tractable_damping_still_meets_the_exact_restitution() {
    // x = 1000: from x (1 + e) = ln((1 + x)/(1 - e x)) (docs/references.md), 1 - e x = (1 + x) exp(-x (1 + e)), so
    // e = (1 - (1 + x) exp(-x(1 + e)))/x = 1/x to within exp(-1000): e = 1e-3 in double precision.
    let report = on_wall(1.0, 1.0, "law = \"hunt-crossley\"\ndamping = 1000\nstiffness = 1e6");
    assert_close("e", report.contact.restitution_velocity_ratio.unwrap(), 1e-3, 1e-9);
}

#[test]
fn overdamped_tsuji_with_penetration_separation_reaches_the_time_limit() {
    // a = 10 > sqrt(5): overdamped in the w-variable (docs/references.md#tsuji), so d never returns to 0.
    let report = on_wall(1.0, 1.0, "law = \"tsuji\"\ndamping = 10\nstiffness = 1e6");
    assert!(!report.contact.separated);
    assert!(report.notes.iter().any(|n| n.contains("did not separate")));
}

#[test]
fn extreme_scales_give_the_same_nondimensional_contact() {
    // The scaled formulation makes a nanometre contact and a planetary one the same problem (docs/references.md:
    // e depends on x = alpha v0 only).
    for (mass, speed, stiffness) in [(1e-12, 1e-6, 1e-3), (1e20, 1e3, 1e28), (1.0, 1e-9, 1e9)] {
        let contact = format!("law = \"hunt-crossley\"\ndamping = {:?}\nstiffness = {stiffness:?}", 0.5 / speed);
        let report = on_wall(mass, speed, &contact);
        assert_close("e", report.contact.restitution_velocity_ratio.unwrap(), 0.7484349315974, 1e-9);
    }
}

#[test]
fn power_law_exponents_below_one_are_refused_naming_the_range() {
    // n = 0.5 once ran (its force gradient unbounded at d = 0). No indenter's profile z ~ r^k gives an exponent
    // (k + 1)/k below a flat punch's 1 (docs/laws.md#which-exponents), and as n falls to 0 the exact maximum force
    // of the hysteresis family rounded to 0 N: the scene is refused, naming the key and the range.
    let text = "[[bodies]]\nradius = 1.0\nmass = 1.0\nvelocity = [1.0, 0.0, 0.0]\n[[bodies]]\nradius = inf\nmass = inf\n\
                velocity = [0.0, 0.0, 0.0]\n[contact]\nlaw = \"hertz\"\nstiffness = 1e6\nexponent = 0.5\n";
    let error = impact::scene::Scene::parse(text, std::path::Path::new("below-one.toml")).unwrap_err();
    assert_eq!(error.key.as_deref(), Some("contact.exponent"));
    assert!(error.message.contains("between 1 and 3, got 0.5"), "{}", error.message);
}

#[test]
fn loose_tolerances_never_report_a_negative_restitution() {
    // e = 0 with separation at zero penetration: the exact contact never separates (docs/references.md). Loose
    // tolerances may bring d back to zero, but without a separation speed that is no separation.
    for law in ["tsuji", "kelvin-voigt"] {
        let text = format!(
            "[[bodies]]\nradius = 0.01\nmass = 1\nvelocity = [1, 0, 0]\n[[bodies]]\nradius = inf\nmass = inf\n\
             velocity = [0, 0, 0]\n[contact]\nlaw = \"{law}\"\nrestitution = 0\nstiffness = 1e6\n\
             [solver]\nrtol = 1e-2\natol = 1e-2\n"
        );
        let report = common::run(&text);
        if let Some(e) = report.contact.restitution_velocity_ratio {
            assert!(e > 0.0, "{law}: separated with e = {e}");
        }
    }
}

#[test]
fn scales_outside_double_precision_are_a_scene_error() {
    // m* v0² overflows for v0 = 1e200 m/s: the scene is refused naming a key, not left to the integrator.
    let text = "[[bodies]]\nradius = 0.01\nmass = 1\nvelocity = [1e200, 0, 0]\n[[bodies]]\nradius = inf\n\
                mass = inf\nvelocity = [0, 0, 0]\n[contact]\nlaw = \"hertz\"\nstiffness = 1e6\n";
    let error = impact::scene::Scene::parse(text, std::path::Path::new("huge.toml")).unwrap_err();
    assert_eq!(error.key.as_deref(), Some("bodies.0.velocity"));
    assert!(error.message.contains("double precision"), "{}", error.message);
}
