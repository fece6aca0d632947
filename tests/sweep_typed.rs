//! A sweep applies each point to a typed scene rather than writing it into the scene's TOML and reading it back;
//! the two must be the same thing. Every row — results, and the text of every error — is compared here between the
//! typed path and the written one, over keys of every kind and values that break every rule.

use impact::law::LawKind;
use impact::sweep::Sweep;
use impact::sweep::grid::{Axis, Grid, Spacing};
use std::path::Path;

const SCENE: &str = r#"title = "typed against written"
[[bodies]]
name = "ball"
radius = 0.01
density = 7850
velocity = [1.5, 0.3, 0.0]
angular_velocity = [0.0, 0.0, 40.0]
young = 2.1e11
poisson = 0.3
position = [0.0, 0.0, 0.0]

[[bodies]]
name = "other"
radius = 0.02
mass = 0.2
velocity = [-0.5, 0.0, 0.0]
young = 7e10
poisson = 0.33
position = [0.05, 0.0, 0.0]

[contact]
law = "hunt-crossley"
restitution = 0.7
friction = 0.2
"#;

const WALL: &str = r#"[[bodies]]
radius = 0.0025
density = 4000
velocity = [1.0, 0.0, -3.0]
young = 3.8e11
poisson = 0.23

[[bodies]]
radius = inf
mass = inf
velocity = [0.0, 0.0, 0.0]
young = inf

[contact]
law = "tsuji"
restitution = 0.9
friction = 0.1
normal = [0.0, 0.0, -1.0]
"#;

fn sweep(text: &str, vary: &[&str], laws: &[LawKind]) -> Sweep {
    let axes = vary.iter().map(|spec| Axis::parse(spec, Spacing::Linear).unwrap()).collect();
    Sweep::new(Path::new("typed.toml"), text.to_string(), Grid::new(axes).unwrap(), laws.to_vec()).unwrap()
}

fn assert_same_rows(sweep: &Sweep) -> usize {
    let mut errors = 0;
    for index in 0..sweep.rows() {
        let (typed, written) = (sweep.evaluate(index), sweep.evaluate_written(index));
        assert_eq!(typed, written, "row {index}");
        errors += usize::from(matches!(typed.status, impact::sweep::table::Status::Error(_)));
    }
    errors
}

#[test]
fn body_keys_give_the_same_rows_typed_and_written() {
    let errors = assert_same_rows(&sweep(
        SCENE,
        &["bodies.0.radius=-0.01,0.005,1e300", "bodies.1.mass=0.1,1e308,-1", "bodies.0.poisson=0.25,0.6"],
        &[],
    ));
    assert!(errors > 0, "some points break a rule");
    let errors = assert_same_rows(&sweep(
        SCENE,
        &["bodies.0.density=1e3,-5", "bodies.1.inertia=1e-5,0", "bodies.0.young=1e9,1e300"],
        &[],
    ));
    assert!(errors > 0);
}

#[test]
fn vector_components_and_incidence_give_the_same_rows() {
    assert_same_rows(&sweep(SCENE, &["bodies.0.velocity.1=-0.2,0,0.4", "bodies.1.angular_velocity.2=0,100"], &[]));
    assert_same_rows(&sweep(SCENE, &["bodies.1.position.0=0.03,0.031", "bodies.0.position.1=0,0.001"], &[]));
    let errors = assert_same_rows(&sweep(WALL, &["bodies.0.incidence_deg=0,30,89.9,95", "contact.normal.2=-1,0"], &[]));
    assert!(errors > 0);
}

#[test]
fn contact_and_solver_keys_give_the_same_rows() {
    assert_same_rows(&sweep(SCENE, &["contact.restitution=0,0.5,1,1.5", "contact.friction=0,0.3,-1"], &[]));
    assert_same_rows(&sweep(SCENE, &["contact.damping=0,0.2", "contact.exponent=1,1.5,2.5"], &[]));
    assert_same_rows(&sweep(SCENE, &["contact.stiffness=1e9,-1", "contact.tangential_stiffness=1e6,0"], &[]));
    assert_same_rows(&sweep(WALL, &["contact.tangential_damping=0,0.5,-0.1", "solver.rtol=1e-8,1e-20"], &[]));
}

#[test]
fn law_lists_give_the_same_rows() {
    let laws = [LawKind::Hertz, LawKind::KelvinVoigt, LawKind::Tsuji, LawKind::Brilliantov, LawKind::Gonthier];
    let errors = assert_same_rows(&sweep(WALL, &["contact.restitution=0,0.4,1"], &laws));
    assert!(errors > 0, "hertz takes no e below 1, brilliantov none at all, Gonthier's map fails at e = 0");
    assert_same_rows(&sweep(WALL, &["contact.damping=0.01,1e-5"], &laws));
}

/// A sweep writing one column computes only what that column shows (`--columns`), and shows it as the full row
/// does: every result column alone, on central impacts that take the fast path (Hunt–Crossley, and Tsuji under
/// the force criterion) and on an oblique one (the general path), equals the full row's cell — to 1e-9 relative
/// where the runs differ in what they compute (their steps differ), exactly otherwise — and is never NaN.
#[test]
fn each_column_alone_equals_the_full_rows_cell() {
    use impact::sweep::table::{Cell, Columns, RESULT_COLUMNS};
    let central = |law: &str| {
        format!(
            "[[bodies]]\nradius = 0.01\nmass = 0.03\nvelocity = [1.5, 0.0, 0.0]\nyoung = 2e11\npoisson = 0.3\n\n\
             [[bodies]]\nradius = inf\nmass = inf\nvelocity = [0.0, 0.0, 0.0]\nyoung = inf\n\n[contact]\n{law}\n"
        )
    };
    let scenes = [
        central("law = \"hunt-crossley\"\nrestitution = 0.6"),
        central("law = \"tsuji\"\nrestitution = 0.4\nseparation = \"force\""),
        SCENE.to_string(),
    ];
    for text in scenes {
        let mut sweep = sweep(&text, &["contact.restitution=0.3,0.8"], &[]);
        let full: Vec<_> = (0..2).map(|row| sweep.evaluate(row)).collect();
        for (i, name) in RESULT_COLUMNS.iter().enumerate() {
            sweep.select(Columns::parse(&[name.to_string()]).unwrap());
            for (row, whole) in full.iter().enumerate() {
                let alone = sweep.evaluate(row);
                assert_eq!(alone.status, whole.status, "{name}\n{text}");
                let (cell, expected) = (alone.results[0], whole.results[i]);
                match (cell, expected) {
                    (Cell::Number(a), Cell::Number(b)) => {
                        assert!(a.is_finite(), "{name}: {a}\n{text}");
                        // V0 (0 against a wall) and the velocity difference from the instantaneous model are
                        // measured against the approach speed, as their errors are.
                        let scale = match (*name, whole.results[0]) {
                            ("common_normal_velocity" | "max_velocity_difference", Cell::Number(speed)) => speed,
                            _ => b.abs(),
                        };
                        assert!((a - b).abs() <= 1e-9 * scale, "{name}: {a} alone, {b} in the full row\n{text}");
                    }
                    // The work done (steps, force evaluations) depends on what is computed: a central Hunt–Crossley
                    // row that shows no time takes the first integral, without a step.
                    (Cell::Count(a), Cell::Count(b)) => {
                        let first_integral = text.contains("hunt-crossley") && !text.contains("friction");
                        assert!(b > 0 && (a > 0) != first_integral, "{name}: {a} alone, {b} in the full row\n{text}");
                    }
                    (a, b) => assert_eq!(a, b, "{name}\n{text}"),
                }
            }
        }
    }
}
