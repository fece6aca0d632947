//! Rigid bodies struck off their centre or turning about a pivot, simulated through the contact (docs/rigid.md),
//! against hand calculations written here: Beer & Johnston's hung rod, a free rod struck at its end, the centre of
//! percussion, a ball whose inertia differs between axes against the spheres' model, and random eccentric pairs
//! checked for momentum, angular momentum and energy. Expected numbers never come from the program.

mod common;

use common::{assert_close, run, toml_tensor, toml_vector};
use impact::draw::Draw;
use impact::impact::outcome;
use impact::scene::Scene;
use impact::setup::{Motion, Setup};
use nalgebra::{Matrix3, Vector3};
use std::path::Path;

/// A uniform rod of mass `mass` and length `length` along y: I = M L²/12 about x and z, a small polar moment.
fn rod_inertia(mass: f64, length: f64) -> String {
    let transverse = mass * length * length / 12.0;
    format!("[{transverse:?}, {:?}, {transverse:?}]", 1e-4 * transverse)
}

/// The hung rod of Beer & Johnston (Vector Mechanics for Engineers, sample problem 17.9): an 8 kg, 1.2 m rod hung at
/// its top (the pivot at the origin, the rod down along -y), struck at `depth` below the pivot by a 2 kg ball at
/// 5 m/s along x; a Kelvin–Voigt contact of stiffness `stiffness` (N/m) with e = 0.8.
fn hung_rod(depth: f64, stiffness: f64) -> String {
    format!(
        "[[bodies]]\nname = \"ball\"\nmass = 2.0\nradius = 0.02\nvelocity = [5.0, 0.0, 0.0]\n\
         position = [-0.05, {:?}, 0.0]\n\n\
         [[bodies]]\nname = \"rod\"\nmass = 8.0\nradius = 0.01\ninertia = {}\nposition = [0.0, -0.6, 0.0]\n\
         contact_offset = [0.0, {:?}, 0.0]\npivot = [0.0, 0.0, 0.0]\nvelocity = [0.0, 0.0, 0.0]\n\n\
         [contact]\nlaw = \"kelvin-voigt\"\nstiffness = {stiffness:e}\nrestitution = 0.8\n",
        -depth,
        rod_inertia(8.0, 1.2),
        0.6 - depth,
    )
}

#[test]
fn beer_and_johnstons_hung_rod_to_a_thousandth() {
    // By hand: I_O = M L²/3 = 3.84 kg m², m_eff = I_O / L² = M/3, J = (1 + e) v m_b m_eff / (m_b + m_eff),
    // the ball's v' = v - J/m_b = -0.142857 m/s, omega' = J L / I_O = 3.2143 rad/s; the pivot passes
    // M omega' L/2 - J along the normal.
    let (mass, length, ball, speed, e): (f64, f64, f64, f64, f64) = (8.0, 1.2, 2.0, 5.0, 0.8);
    let i_o = mass * length * length / 3.0;
    let m_eff = i_o / (length * length);
    let j = (1.0 + e) * speed * ball * m_eff / (ball + m_eff);
    let (ball_after, spin_after) = (speed - j / ball, j * length / i_o);
    assert!((spin_after - 3.21).abs() < 5e-3 && (ball_after + 0.143).abs() < 5e-4, "the textbook's numbers");
    let report = run(&hung_rod(length, 1e9));
    let [striker, rod] = &report.bodies;
    assert_close("rod's effective mass", rod.effective_mass_at_contact, m_eff, 1e-12);
    assert_close("ball's effective mass", striker.effective_mass_at_contact, ball, 1e-15);
    assert_close("ball after", striker.velocity_after.unwrap()[0], ball_after, 1e-3);
    assert_close("rod's spin after", rod.angular_velocity_after.unwrap()[2], spin_after, 1e-3);
    let pivot = rod.pivot_impulse.expect("a pivoted rod reports its pivot's impulse");
    let pivot_normal = mass * spin_after * length / 2.0 - j;
    assert_close("pivot impulse along the normal", pivot[0], pivot_normal, 1e-3);
    assert!(striker.pivot_impulse.is_none());
    // The report's eccentric solution is the same hand calculation.
    let eccentric = report.instantaneous.as_ref().unwrap().eccentric.as_ref().expect("the eccentric solution");
    assert_close("instantaneous impulse", eccentric.impulse, j, 1e-6);
    assert_close("instantaneous pivot impulse", eccentric.pivot_impulse[1][0], pivot_normal, 1e-6);
    assert_close("instantaneous spin", eccentric.angular_velocity_after[1][2], spin_after, 1e-6);
    // The rod is struck 1.2 m from its pivot, whose radius of gyration is L/sqrt(3): not central.
    let central = report.idealisation.central.as_ref().expect("a central verdict");
    assert_close("lever arm", central.value, length, 1e-12);
    assert_close("radius of gyration about the pivot", central.compared_with, length / 3f64.sqrt(), 1e-9);
    assert_eq!(central.verdict.name(), "fails");
}

#[test]
fn a_stiffer_contact_comes_closer_to_the_instantaneous_hung_rod() {
    // The rod turns by omega t_c during the contact; its geometry changes by the square of that angle, so the
    // difference from the instantaneous impact falls as the contact stiffens.
    let differences: Vec<f64> = [1e7, 1e9, 1e11]
        .iter()
        .map(|&k| {
            let report = run(&hung_rod(1.2, k));
            let instant = report.instantaneous.unwrap();
            instant.eccentric.unwrap().max_angular_velocity_difference.unwrap()
        })
        .collect();
    assert!(differences[0] > 10.0 * differences[1] && differences[1] > 10.0 * differences[2], "{differences:?}");
}

#[test]
fn the_centre_of_percussion_leaves_the_pivot_without_a_blow_along_the_normal() {
    // Struck 2L/3 below its pivot, a uniform hung rod turns about the pivot as a free body would: the pivot passes
    // no impulse along the normal (I_O / (M d) = (M L²/3) / (M L/2) = 2L/3).
    let length = 1.2;
    let report = run(&hung_rod(2.0 * length / 3.0, 1e10));
    let rod = &report.bodies[1];
    let blow = report.contact.deformation_impulse + report.contact.restitution_impulse.unwrap();
    let pivot = rod.pivot_impulse.unwrap();
    assert!(pivot[0].abs() < 1e-6 * blow, "pivot {pivot:?} against the blow {blow}");
    // Across the normal only the centripetal part of the turn: small for a stiff contact.
    assert!(pivot[1].abs() < 1e-3 * blow, "pivot {pivot:?} against the blow {blow}");
    // m_eff = I_O / q² = (M L²/3) / (4 L²/9) = 3M/4.
    assert_close("effective mass", rod.effective_mass_at_contact, 0.75 * 8.0, 1e-12);
}

/// A free rod (2 kg, 0.6 m along y) at rest, struck at its end by a 0.5 kg steel ball at 3 m/s: both Hertz.
const FREE_ROD: &str = "[[bodies]]\nname = \"ball\"\nmass = 0.5\nradius = 0.02\nvelocity = [3.0, 0.0, 0.0]\n\
     young = 200e9\npoisson = 0.3\n\n\
     [[bodies]]\nname = \"rod\"\nmass = 2.0\nradius = 0.01\ninertia = [0.06, 0.000006, 0.06]\n\
     contact_offset = [0.0, -0.3, 0.0]\nvelocity = [0.0, 0.0, 0.0]\nyoung = 200e9\npoisson = 0.3\n\n\
     [contact]\nlaw = \"hertz\"\n";

/// Momentum, angular momentum about the origin and kinetic energy of a scene's bodies before (at first contact)
/// and after its simulated contact, from the outcome's snapshots (positions, velocities, spins and orientations).
struct Invariants {
    momentum: [Vector3<f64>; 2],
    angular: [Vector3<f64>; 2],
    energy: [f64; 2],
    /// The sizes they are measured against: sum |m v|, sum |r × m v| + |I w| + J (|r| + 1), the kinetic energy.
    scales: [f64; 3],
}

fn invariants(text: &str) -> Invariants {
    let scene = Scene::parse(text, Path::new("test.toml")).unwrap_or_else(|e| panic!("{e}\n{text}"));
    let setup = Setup::new(&scene).expect("a valid scene");
    assert_eq!(setup.motion, Motion::Rigid, "the rigid-body model runs");
    let outcome = outcome(&scene, &setup).expect("the contact runs");
    assert!(outcome.separated, "the bodies part");
    let end = &outcome.end;
    let bodies = &scene.bodies;
    let tensor = |i: usize, turn: &Matrix3<f64>| turn * bodies[i].inertia_matrix() * turn.transpose();
    let movable = |i: usize| bodies[i].mass.is_finite();
    let sum = |f: &dyn Fn(usize) -> Vector3<f64>| (0..2).filter(|&i| movable(i)).map(f).sum::<Vector3<f64>>();
    let momentum_before = sum(&|i| bodies[i].velocity * bodies[i].mass);
    let momentum_after = sum(&|i| end.velocities[i] * bodies[i].mass);
    let spin_part = |i: usize, w: &Vector3<f64>, turn: &Matrix3<f64>| {
        if *w == Vector3::zeros() { Vector3::zeros() } else { tensor(i, turn) * w }
    };
    let identity = Matrix3::identity();
    let angular_before = sum(&|i| {
        setup.positions[i].cross(&(bodies[i].velocity * bodies[i].mass))
            + spin_part(i, &bodies[i].angular_velocity, &identity)
    });
    let angular_after = sum(&|i| {
        let turn = end.orientations[i].to_rotation_matrix().into_inner();
        end.positions[i].cross(&(end.velocities[i] * bodies[i].mass)) + spin_part(i, &end.spins[i], &turn)
    });
    let kinetic = |v: &Vector3<f64>, w: &Vector3<f64>, i: usize, turn: &Matrix3<f64>| {
        0.5 * bodies[i].mass * v.norm_squared() + 0.5 * w.dot(&spin_part(i, w, turn))
    };
    let energy_before: f64 = (0..2)
        .filter(|&i| movable(i))
        .map(|i| kinetic(&bodies[i].velocity, &bodies[i].angular_velocity, i, &identity))
        .sum();
    let energy_after: f64 = (0..2)
        .filter(|&i| movable(i))
        .map(|i| kinetic(&end.velocities[i], &end.spins[i], i, &end.orientations[i].to_rotation_matrix().into_inner()))
        .sum();
    let impulse = end.normal_impulse;
    let reach = setup.positions.iter().map(|x| x.norm()).fold(0.0, f64::max) + 1.0;
    Invariants {
        momentum: [momentum_before, momentum_after],
        angular: [angular_before, angular_after],
        // What the contact dissipated and still stores is the rest of the balance.
        energy: [energy_before, energy_after + end.dissipated_normal + end.elastic_energy],
        scales: [
            (0..2).filter(|&i| movable(i)).map(|i| bodies[i].mass * bodies[i].velocity.norm()).sum::<f64>() + impulse,
            angular_before.norm() + impulse * reach,
            energy_before,
        ],
    }
}

/// Asserts the invariants to `tolerance`; against a wall (`wall_normal`), which takes momentum along its normal and
/// angular momentum about its moving contact, only the momentum across the normal.
#[track_caller]
fn assert_invariants(text: &str, tolerance: f64, case: &str, wall_normal: Option<Vector3<f64>>) -> [f64; 3] {
    let i = invariants(text);
    let [p, l, k] = i.scales;
    let change = i.momentum[1] - i.momentum[0];
    let dp = wall_normal.map_or(change, |n| change - n * change.dot(&n)).norm() / p;
    let dl = if wall_normal.is_some() { 0.0 } else { (i.angular[1] - i.angular[0]).norm() / l };
    let dk = (i.energy[1] - i.energy[0]).abs() / k;
    assert!(dp <= tolerance, "{case}: momentum off by {dp:e}\n{text}");
    assert!(dl <= tolerance, "{case}: angular momentum off by {dl:e}\n{text}");
    assert!(dk <= tolerance, "{case}: energy off by {dk:e}\n{text}");
    [dp, dl, dk]
}

#[test]
fn a_free_rod_struck_at_its_end_meets_the_ball_with_a_quarter_of_its_mass() {
    // m_eff = 1/(1/M + (L/2)² / (M L²/12)) = M/4 = 0.5 kg: the ball's own mass, so an elastic blow stops the ball and
    // sends the rod's end off at 3 m/s: the mass centre at 0.75 m/s, the rod turning at 0.75·2/0.3... by hand:
    // J = 2 m_b m_eff v / (m_b + m_eff) = 1.5 N s, v_cm = J/M = 0.75 m/s, omega = J (L/2) / I = 1.5·0.3/0.06 = 7.5 rad/s.
    let report = run(FREE_ROD);
    let rod = &report.bodies[1];
    assert_close("effective mass", rod.effective_mass_at_contact, 0.5, 1e-12);
    assert_close("rod's centre after", rod.velocity_after.unwrap()[0], 0.75, 1e-6);
    assert_close("rod's spin after", rod.angular_velocity_after.unwrap()[2], 7.5, 1e-6);
    assert!(report.bodies[0].velocity_after.unwrap()[0].abs() < 1e-6 * 3.0, "the ball stops");
    let errors = assert_invariants(FREE_ROD, 1e-9, "free rod", None);
    eprintln!("free rod: momentum, angular momentum and energy errors {errors:?}");
}

#[test]
fn a_ball_whose_inertia_differs_between_axes_struck_centrally_is_a_sphere() {
    // Without an offset the normal force passes through the mass centre: the rigid-body model must give what the
    // spheres' model gives with one inertia (no spin, the same velocities), whatever the tensor.
    let sphere = "[[bodies]]\nmass = 1.0\nradius = 0.05\nvelocity = [2.0, 0.5, 0.0]\nposition = [0.0, 0.0, 0.0]\n\
                  young = 70e9\npoisson = 0.33\n\n\
                  [[bodies]]\nmass = 3.0\nradius = 0.08\nvelocity = [-1.0, 0.0, 0.0]\nposition = [0.2, 0.03, 0.0]\n\
                  young = 70e9\npoisson = 0.33\n\n[contact]\nlaw = \"hunt-crossley\"\nrestitution = 0.7\n";
    let tensor = sphere.replacen("young = 70e9", "inertia = [0.001, 0.002, 0.0025]\nyoung = 70e9", 1);
    let (a, b) = (run(sphere), run(&tensor));
    for i in 0..2 {
        let (va, vb) = (a.bodies[i].velocity_after.unwrap(), b.bodies[i].velocity_after.unwrap());
        for j in 0..3 {
            assert!((va[j] - vb[j]).abs() < 1e-8, "body {i}: spheres' model {va:?}, rigid-body model {vb:?}");
        }
        assert_eq!(b.bodies[i].angular_velocity_after.unwrap(), [0.0; 3], "a central blow spins nothing");
    }
    assert!(b.notes.iter().any(|n| n.contains("rigid bodies")), "{:?}", b.notes);
}

#[test]
fn random_eccentric_pairs_keep_momentum_angular_momentum_and_energy() {
    let (mut checked, mut worst) = (0, [0.0f64; 3]);
    for case in 0..200 {
        let mut draw = Draw::new(0x51d_e0ff, case);
        let laws = [
            "law = \"hertz\"",
            "law = \"hunt-crossley\"\nrestitution = 0.6",
            "law = \"kelvin-voigt\"\nrestitution = 0.5",
        ];
        let law = draw.pick(&laws);
        let wall = draw.chance(0.2);
        let mut bodies = Vec::new();
        for i in 0..2 {
            if i == 1 && wall {
                bodies.push("[[bodies]]\nradius = inf\nmass = inf\nvelocity = [0.0, 0.0, 0.0]\n".to_string());
                continue;
            }
            let mass = draw.log(0.05, 20.0);
            let radius = draw.log(0.005, 0.05);
            let size = mass * draw.log(1e-3, 0.1);
            let inertia = common::random_inertia(&mut draw, size);
            let offset = draw.direction() * draw.uniform(0.0, 0.3);
            let velocity = draw.direction() * draw.log(0.1, 3.0);
            let spin = draw.direction() * draw.log(0.01, 3.0);
            bodies.push(format!(
                "[[bodies]]\nmass = {mass:?}\nradius = {radius:?}\ninertia = {}\ncontact_offset = {}\n\
                 velocity = {}\nangular_velocity = {}\n",
                toml_tensor(&inertia),
                toml_vector(&offset),
                toml_vector(&velocity),
                toml_vector(&spin)
            ));
        }
        let normal = draw.direction();
        let text = format!(
            "{}\n{}\n[contact]\n{law}\nstiffness = {:e}\nnormal = {}\n",
            bodies[0],
            bodies[1],
            draw.log(1e7, 1e10),
            toml_vector(&normal)
        );
        // Keep the pairs that approach at their contact spheres (the scene refuses the others).
        let Ok(scene) = Scene::parse(&text, Path::new("test.toml")) else { continue };
        if Setup::new(&scene).is_err() {
            continue;
        }
        checked += 1;
        let errors = assert_invariants(&text, 1e-9, &format!("case {case}"), wall.then_some(normal.normalize()));
        worst = [0, 1, 2].map(|i| worst[i].max(errors[i]));
    }
    assert!(checked > 60, "only {checked} random pairs approached");
    eprintln!("{checked} random eccentric pairs: worst momentum, angular momentum and energy errors {worst:?}");
}
