//! The idealisation map (`impact sweep --map`, docs/idealisation.md#the-idealisation-map): a hardened-steel ball on a
//! steel block, swept over its speed and radius, is coloured where each assumption fails first, and the boundaries
//! fall where the closed forms of Hertz's contact put them — yield (which does not depend on the radius), gravity
//! during the contact (which does), the travel during the contact. Every expected speed is computed here by hand.

mod common;

use common::binary::{Scratch, assert_success, describe, impact, stderr};
use impact::output::map_figure::{Verdict, contour, svg};
use impact::sweep::map::from_csv;
use std::f64::consts::PI;

const YOUNG: f64 = 2.1e11;
const POISSON: f64 = 0.3;
const DENSITY: f64 = 7850.0;
const YIELD_STRESS: f64 = 1e9;
const GRAVITY: f64 = 9.80665;

/// The scene: a steel ball (radius and speed set by the sweep) on a steel block (a wall of the same steel), Hertz.
const SCENE: &str = "[[bodies]]\nradius = 0.005\ndensity = 7850\nvelocity = [1.0, 0.0, 0.0]\nyoung = 2.1e11\n\
                     poisson = 0.3\nyield_stress = 1e9\n\n[[bodies]]\nradius = inf\nmass = inf\n\
                     velocity = [0.0, 0.0, 0.0]\nyoung = 2.1e11\npoisson = 0.3\nyield_stress = 1e9\n\n\
                     [contact]\nlaw = \"hertz\"\n";

/// E* of steel on steel: 1/E* = 2 (1 - nu²)/E.
fn effective_modulus() -> f64 {
    YOUNG / (2.0 * (1.0 - POISSON * POISSON))
}

/// The ball's mass, kg: m* against an immovable block.
fn mass(radius: f64) -> f64 {
    DENSITY * 4.0 / 3.0 * PI * radius.powi(3)
}

/// Hertz's maximum penetration of a ball of `radius` on the block at `speed` (R* = R, m* = m):
/// (1/2) m v² = (8/15) E* sqrt(R) d^(5/2).
fn max_penetration(radius: f64, speed: f64) -> f64 {
    (15.0 * mass(radius) * speed * speed / (16.0 * effective_modulus() * radius.sqrt())).powf(0.4)
}

/// Hertz's contact time, t_c = 2.9432751843 d_max / v0 (2 sqrt(pi) Gamma(2/5) / Gamma(9/10); Johnson, Contact
/// Mechanics, §11.4; docs/references.md).
fn contact_time(radius: f64, speed: f64) -> f64 {
    2.943_275_184_3 * max_penetration(radius, speed) / speed
}

/// The speed at which yield begins (Thornton 1997; docs/laws.md): the peak pressure reaches p_y = 1.6 Y at the
/// penetration d_y = (pi p_y / (2 E*))² R, and (1/2) m V_y² = (8/15) E* sqrt(R) d_y^(5/2).
fn yield_speed(radius: f64) -> f64 {
    let pressure = 1.6 * YIELD_STRESS;
    let penetration = (PI * pressure / (2.0 * effective_modulus())).powi(2) * radius;
    (16.0 / 15.0 * effective_modulus() * radius.sqrt() * penetration.powf(2.5) / mass(radius)).sqrt()
}

/// The speed at which gravity's impulse during the contact reaches a tenth of the contact's (the `isolated` verdict
/// fails): m g t_c / (2 m v) = 0.1, e = 1, with t_c proportional to v^(-1/5): bisection on the ratio, which falls
/// with speed.
fn gravity_speed(radius: f64) -> f64 {
    let ratio = |v: f64| GRAVITY * contact_time(radius, v) / (2.0 * v);
    bisect(|v| ratio(v) - 0.1, 1e-6, 1e3)
}

/// The speed at which the relative travel during the contact reaches a tenth of the radius (the `instantaneous`
/// verdict fails): v t_c / R = 0.1.
fn travel_speed(radius: f64) -> f64 {
    bisect(|v| v * contact_time(radius, v) / radius - 0.1, 1e-6, 1e4)
}

/// The root of a monotone `f` between `low` and `high`, bisected in the logarithm.
fn bisect(f: impl Fn(f64) -> f64, mut low: f64, mut high: f64) -> f64 {
    let rising = f(high) > f(low);
    for _ in 0..200 {
        let middle = (low * high).sqrt();
        if (f(middle) > 0.0) == rising {
            high = middle;
        } else {
            low = middle;
        }
    }
    (low * high).sqrt()
}

#[test]
fn the_hand_calculated_yield_speed_is_the_documented_one() {
    // docs/idealisation.md and models/yielding-steel-ball.toml: 0.135 m/s on a steel block, whatever the radius
    // (m ∝ R³, d_y ∝ R: V_y² ∝ R^(1/2) R^(5/2) / R³).
    for radius in [1e-4, 5e-3, 1.0] {
        assert!((yield_speed(radius) - 0.135).abs() < 0.001, "{radius}: {}", yield_speed(radius));
    }
}

/// Sweeps the scene over `speeds` and `radii` with `--map`, and reads the map's cells back from the CSV.
fn map_of(scratch: &Scratch, speeds: &[f64], radii: &[f64]) -> (impact::output::map_figure::IdealisationMap, String) {
    let list = |values: &[f64]| values.iter().map(|v| format!("{v:.9e}")).collect::<Vec<_>>().join(",");
    let scene = scratch.scene("ball.toml", SCENE);
    let speed = format!("bodies.0.velocity.0={}", list(speeds));
    let radius = format!("bodies.0.radius={}", list(radii));
    let output = impact(
        scratch.path(),
        &["sweep", &scene, "--vary", &speed, "--vary", &radius, "--out", "map.csv", "--map", "map.png"],
    );
    assert_success(&output);
    assert!(scratch.exists("map.png"), "{}", describe(&output));
    let csv = scratch.read("map.csv");
    (from_csv(&csv).expect("a map"), csv)
}

/// The cell of the map at the speed `speeds[i]` and radius `radii[j]` of the sweep (each list increasing: the map's
/// columns and rows in their order).
fn cell(map: &impact::output::map_figure::IdealisationMap, (i, j): (usize, usize)) -> Verdict {
    map.cells[j][i]
}

#[test]
fn the_map_turns_at_the_yield_speed_and_at_twice_it_whatever_the_radius() {
    let scratch = Scratch::new("map-yield");
    let radii = [1e-3, 1e-2];
    let v_y = yield_speed(1e-2);
    // Either side of V_y (yield begins: elastic marginal) and of 2 V_y (the elastic verdict fails at a pressure of
    // 2^(2/5) p_y, since p0 ∝ v^(2/5)).
    let speeds = [0.95 * v_y, 1.05 * v_y, 1.95 * v_y, 2.05 * v_y];
    let (map, _) = map_of(&scratch, &speeds, &radii);
    let elastic = 4;
    assert_eq!((map.xs.len(), map.ys.len()), (4, 2));
    for (j, radius) in radii.iter().enumerate() {
        assert_eq!(cell(&map, (0, j)), Verdict::Holds, "{radius}");
        assert_eq!(cell(&map, (1, j)), Verdict::Marginal(elastic), "{radius}");
        assert_eq!(cell(&map, (2, j)), Verdict::Marginal(elastic), "{radius}");
        assert_eq!(cell(&map, (3, j)), Verdict::Fails(elastic), "{radius}");
    }
}

#[test]
fn gravity_matters_below_a_speed_that_grows_with_the_radius_and_travel_above_one_that_does_not() {
    let scratch = Scratch::new("map-gravity");
    let (isolated, instantaneous, elastic) = (3, 2, 4);
    for radius in [0.01, 0.1] {
        let slow = gravity_speed(radius);
        // Below the yield speed, so that nothing else fails there.
        assert!(1.25 * slow < yield_speed(radius), "{radius}: {slow}");
        let fast = travel_speed(radius);
        let speeds = [0.8 * slow, 1.25 * slow, 0.8 * fast, 1.25 * fast];
        let (map, csv) = map_of(&scratch, &speeds, &[radius]);
        assert_eq!(cell(&map, (0, 0)), Verdict::Fails(isolated), "{radius}\n{csv}");
        assert_eq!(cell(&map, (1, 0)), Verdict::Marginal(isolated), "{radius}\n{csv}");
        // Yield has failed long before the travel does; the travel comes first in the order of severity.
        assert_eq!(cell(&map, (2, 0)), Verdict::Fails(elastic), "{radius}\n{csv}");
        assert_eq!(cell(&map, (3, 0)), Verdict::Fails(instantaneous), "{radius}\n{csv}");
    }
    // Gravity's speed grows as R^(5/6) (t_c ∝ R v^(-1/5), the ratio ∝ R v^(-6/5)); the travel's does not depend on R.
    let ratio = gravity_speed(0.1) / gravity_speed(0.01);
    assert!((ratio - 10f64.powf(5.0 / 6.0)).abs() < 1e-6 * ratio, "{ratio}");
    assert!((travel_speed(0.1) / travel_speed(0.01) - 1.0).abs() < 1e-6);
}

/// The speed at which a bouncing ball's contact lasts a tenth of its flight to the next bounce under standard gravity:
/// t_c / (2 e v0 / g) = 0.1, e = 1 for elastic Hertz, so g t_c / (2 v0) = 0.1 (the same ratio as gravity's `isolated`
/// with J = 2 m v0): bisection on the ratio, which falls with speed as v0^(-6/5).
fn flight_speed(radius: f64) -> f64 {
    let e = 1.0;
    let ratio = |v: f64| contact_time(radius, v) / (2.0 * e * v / GRAVITY);
    bisect(|v| ratio(v) - 0.1, 1e-6, 1e3)
}

#[test]
fn the_flight_line_lies_where_the_contact_lasts_a_tenth_of_the_flight_between_bounces() {
    let scratch = Scratch::new("map-flight");
    let radii = [0.01, 0.1];
    let (slow, fast) = (flight_speed(radii[0]), flight_speed(radii[1]));
    // Hand values: 8.7 mm/s at 1 cm, 6.0 cm/s at 10 cm; the speed grows as R^(5/6).
    assert!((slow - 0.0087).abs() < 0.00005 && (fast - 0.060).abs() < 0.0005, "{slow} {fast}");
    assert!((fast / slow - 10f64.powf(5.0 / 6.0)).abs() < 1e-6 * fast / slow);
    let speeds = [0.8 * slow, 1.25 * slow, 0.8 * fast, 1.25 * fast];
    let (map, csv) = map_of(&scratch, &speeds, &radii);
    let levels = map.flight.as_ref().expect("the flight columns");
    // Beyond the line (the contact longer than a tenth of the flight: level >= 0) below its speed, inside above.
    for (j, radius) in radii.iter().enumerate() {
        let (below, above) = (levels[j][2 * j], levels[j][2 * j + 1]);
        assert!(below >= 0.0 && above < 0.0, "{radius}: {below} {above}\n{csv}");
    }
    // Each cell's ratio is g t_c / (2 e v0) of its own speed (e = 1 to rounding): ln(ratio / 0.1), by hand.
    for (j, &radius) in radii.iter().enumerate() {
        for (i, &speed) in speeds.iter().enumerate() {
            let want = (GRAVITY * contact_time(radius, speed) / (2.0 * speed) / 0.1).ln();
            assert!((levels[j][i] - want).abs() < 1e-4, "{radius} {speed}: {} against {want}", levels[j][i]);
        }
    }
    // The line crosses each row at the hand-calculated speed when interpolated in the logarithms (the ratio is a
    // power law of the speed there, so the interpolation is exact; these four uneven speeds make the map's own axis
    // linear, in mm/s).
    let (x_factor, y_factor) = (map.xs[0] / speeds[0], map.ys[0] / radii[0]);
    let lines = contour(&map.xs, &map.ys, levels, true, true);
    for (radius, speed) in [(radii[0], slow), (radii[1], fast)] {
        let on = lines.iter().flatten().any(|&(x, y)| {
            (y - radius * y_factor).abs() < 1e-9 * radius * y_factor
                && (x - speed * x_factor).abs() < 1e-4 * speed * x_factor
        });
        assert!(on, "{radius}: {speed} not on {lines:?}");
    }
    // A figure's layer of its own, not a cell colour.
    let figure = svg(&map);
    assert!(figure.contains("class=\"flight\""), "no flight line");
}

#[test]
fn the_verdict_columns_are_written_only_when_asked_for() {
    let scratch = Scratch::new("map-columns");
    let scene = scratch.scene("ball.toml", SCENE);
    let run = |extra: &[&str]| {
        let mut args = vec!["sweep", &scene, "--vary", "bodies.0.velocity.0=0.1,1", "--out", "out.csv"];
        args.extend_from_slice(extra);
        assert_success(&impact(scratch.path(), &args));
        scratch.read("out.csv")
    };
    let plain = run(&[]);
    assert!(!plain.contains("first_failure") && !plain.contains("_verdict"), "{plain}");
    let asked = run(&["--columns", "restitution_velocity_ratio,elastic_ratio,elastic_verdict,first_failure"]);
    let lines: Vec<&str> = asked.lines().collect();
    assert_eq!(
        lines[0],
        "index,status,law,bodies.0.velocity.0,restitution_velocity_ratio,elastic_ratio,elastic_verdict,first_failure"
    );
    // At 0.1 m/s (below V_y = 0.135 m/s) the peak pressure is (0.1 / V_y)^(2/5) of p_y; at 1 m/s it fails.
    let cells: Vec<&str> = lines[1].split(',').collect();
    let expected = (0.1 / yield_speed(0.005)).powf(0.4);
    let ratio: f64 = cells[5].parse().expect("a ratio");
    assert!((ratio - expected).abs() < 1e-6 * expected, "{ratio} against {expected}");
    assert_eq!((cells[6], cells[7]), ("holds", "none"));
    assert!(lines[2].ends_with(",fails,elastic"), "{}", lines[2]);
}

#[test]
fn the_map_needs_exactly_two_varied_keys_and_one_law() {
    let scratch = Scratch::new("map-usage");
    let scene = scratch.scene("ball.toml", SCENE);
    for (args, words) in [
        (vec!["--vary", "bodies.0.velocity.0=0.1,1"], vec!["--map", "exactly two varied keys", "1"]),
        (
            vec![
                "--vary",
                "bodies.0.velocity.0=0.1,1",
                "--vary",
                "bodies.0.radius=0.01,0.1",
                "--law",
                "hertz,thornton",
            ],
            vec!["--map", "one law"],
        ),
        (
            vec!["--vary", "bodies.0.velocity.0=0.1,1", "--vary", "bodies.0.radius=0.01,0.1", "--shard", "1/2"],
            vec!["--map", "shards"],
        ),
    ] {
        let mut all = vec!["sweep", scene.as_str()];
        all.extend(args);
        all.extend(["--out", "out.csv", "--map", "map.png"]);
        let output = impact(scratch.path(), &all);
        assert_eq!(output.status.code(), Some(2), "{all:?}\n{}", describe(&output));
        for word in words {
            assert!(stderr(&output).contains(word), "{all:?} should say `{word}`\n{}", describe(&output));
        }
        assert!(!scratch.exists("out.csv") && !scratch.exists("map.png"), "{all:?}");
    }
    let output = impact(
        scratch.path(),
        &[
            "sweep",
            &scene,
            "--vary",
            "bodies.0.velocity.0=0.1,1",
            "--vary",
            "bodies.0.radius=0.01,0.1",
            "--out",
            "o.csv",
            "--map",
            "map.txt",
        ],
    );
    assert_eq!(output.status.code(), Some(2), "{}", describe(&output));
    assert!(stderr(&output).contains(".png or .svg"), "{}", describe(&output));
}

#[test]
fn the_map_of_a_sweep_in_shards_is_drawn_by_merge() {
    let scratch = Scratch::new("map-merge");
    let scene = scratch.scene("ball.toml", SCENE);
    let ratios: Vec<String> = impact::idealisation::SEVERITY.iter().map(|key| format!("{key}_ratio")).collect();
    let columns =
        format!("approach_speed,first_failure,first_marginal,{},duration,restitution_velocity_ratio", ratios.join(","));
    for shard in ["1/2", "2/2"] {
        let out = format!("s{}.csv", &shard[..1]);
        let output = impact(
            scratch.path(),
            &[
                "sweep",
                &scene,
                "--vary",
                "bodies.0.velocity.0=0.1,1",
                "--vary",
                "bodies.0.radius=0.01,0.1",
                "--columns",
                &columns,
                "--shard",
                shard,
                "--out",
                &out,
            ],
        );
        assert_success(&output);
    }
    assert_success(&impact(scratch.path(), &["merge", "all.csv", "s1.csv", "s2.csv", "--map", "map.svg"]));
    assert!(scratch.read("map.svg").contains("class=\"cells\""));
    // The flight line's columns came through the merge: its levels are read (the line itself lies below 0.1 m/s).
    let merged = from_csv(&scratch.read("all.csv")).expect("a map");
    assert!(merged.flight.as_ref().is_some_and(|levels| levels.iter().flatten().all(|v| v.is_finite())));
    // Shards without the verdicts: the map says which column it misses.
    for shard in ["1/2", "2/2"] {
        let out = format!("p{}.csv", &shard[..1]);
        let args = ["sweep", &scene, "--vary", "bodies.0.velocity.0=0.1,1", "--vary", "bodies.0.radius=0.01,0.1"];
        let mut args = args.to_vec();
        args.extend(["--shard", shard, "--out", &out]);
        assert_success(&impact(scratch.path(), &args));
    }
    let output = impact(scratch.path(), &["merge", "plain.csv", "p1.csv", "p2.csv", "--map", "plain.png"]);
    assert_eq!(output.status.code(), Some(2), "{}", describe(&output));
    assert!(stderr(&output).contains("first_failure"), "{}", describe(&output));
    assert!(!scratch.exists("plain.csv") && !scratch.exists("plain.png"));
}
