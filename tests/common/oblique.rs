//! Two runs of one oblique impact compared: the path under test against the 3-D model at a tight tolerance.

use impact::report::Report;

/// The paths `auto` may take for a frictional sphere on a wall given by the scene `text`: the slide by Taylor series
/// up to a switch from which a sufficient condition shows that the contact slides on the limit to its end, then the
/// normal fast path's motion with the tangential motion in closed form (`closed-form-slide`), or, where no slide
/// holds before the end, the slide by Taylor series throughout; the slide by Dop853 for the tangential options the
/// series do not cover (tangential damping, the rescaled unloading). (For the scenes of the tests, whose laws the
/// series cover otherwise.)
pub fn auto_wall_paths(text: &str) -> &'static [&'static str] {
    if text.contains("tangential_damping") || text.contains("rescale") {
        &["dop853-slide"]
    } else {
        &["closed-form-slide", "taylor-slide"]
    }
}

/// Asserts that `auto`'s run `a` of the scene `text` took one of [`auto_wall_paths`].
pub fn assert_auto_wall_path(a: &Report, text: &str) {
    let method: &str = a.solver.method;
    assert!(auto_wall_paths(text).contains(&method), "{method}\n{text}");
}

/// The differences of run `a` from run `b` of the same scene, each with its name: every body's velocity and spin
/// times its radius after the impact (over the approach speed), the times below the Coulomb limit and of the slip's
/// rest (over the duration), and the friction work and the dissipation (over the kinetic energy), each with the
/// tangential spring's energy left at separation added — under the magnitude cap a Tsuji contact ends with a spring
/// whose energy `(mu |Fn|)²/(2 kt)` tends to a finite limit as d -> 0 and is 0 at d = 0 (kt = 0), so which of the two a
/// path reports depends on the side of d = 0 its located end lies on; their sum does not.
pub fn differences(a: &Report, b: &Report) -> Vec<(&'static str, f64)> {
    let speed = b.approach_speed;
    let mut errors = Vec::new();
    for (x, y) in a.bodies.iter().zip(&b.bodies) {
        let (vx, vy) = (x.velocity_after.expect("after"), y.velocity_after.expect("after"));
        let (wx, wy) = (x.angular_velocity_after.expect("spin"), y.angular_velocity_after.expect("spin"));
        let arm = if x.radius.is_finite() { x.radius } else { 0.0 };
        for i in 0..3 {
            errors.push(("velocity", (vx[i] - vy[i]).abs() / speed));
            errors.push(("spin", (wx[i] - wy[i]).abs() * arm / speed));
        }
    }
    let (oa, ob) = (a.oblique.as_ref().expect("oblique"), b.oblique.as_ref().expect("oblique"));
    let duration = b.contact.duration.expect("a duration");
    let time = |a: Option<f64>, b: Option<f64>| match (a, b) {
        (Some(a), Some(b)) => (a - b).abs() / duration,
        (None, None) => 0.0,
        _ => f64::INFINITY,
    };
    errors.push(("time below the limit", time(oa.below_friction_limit_duration, ob.below_friction_limit_duration)));
    errors.push(("slip's rest", time(oa.slip_rest_time, ob.slip_rest_time)));
    let energy = b.energy.kinetic_before;
    let left = |r: &Report| r.energy.elastic_left_at_separation.unwrap_or(0.0);
    let friction = |r: &Report| r.oblique.as_ref().and_then(|o| o.friction_work).unwrap_or(0.0) + left(r);
    errors.push(("friction work and energy left", (friction(a) - friction(b)).abs() / energy));
    let lost = |r: &Report| r.energy.dissipated.expect("D") + left(r);
    errors.push(("dissipated and left", (lost(a) - lost(b)).abs() / energy));
    errors
}
