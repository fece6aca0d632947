//! The built-in validation suite (`impact validate`, docs/validation.md): the program run on cases whose answers
//! are known from outside it — the lecture's worked examples, the exact references of the laws, rigid-body sliding,
//! a published Newton's cradle, a ball's free flight between elastic bounces — each quantity set beside its
//! reference, with the source, the relative error and the tolerance it must meet.
//!
//! Every reference here is computed in this module from its formula (or copied from its publication), never taken
//! from the program's own instantaneous model; the laws' exact values are the report's `reference` section, whose
//! closed forms and quadratures (src/reference/) are themselves held by the test suite.

use crate::report::Report;
use crate::report::world::WorldReport;
use crate::scene::Parsed;
use serde::Serialize;
use std::path::Path;

/// One checked quantity.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Row {
    /// The case's name (`--case`).
    pub case: &'static str,
    pub quantity: String,
    pub simulated: f64,
    pub reference: f64,
    /// Where the reference comes from.
    pub source: String,
    /// |simulated - reference| / |reference|.
    pub relative_error: f64,
    pub tolerance: f64,
    pub pass: bool,
}

/// A case of the suite: its name, what it is, and how it runs.
pub struct Case {
    pub name: &'static str,
    pub about: &'static str,
    run: fn(&'static str) -> Result<Vec<Row>, String>,
}

impl Case {
    /// Runs the case: its rows, or why it could not run (a scene refused, an integration that failed).
    pub fn run(&self) -> Result<Vec<Row>, String> {
        (self.run)(self.name)
    }
}

/// Every case, in the order the suite runs them.
pub fn cases() -> Vec<Case> {
    let mut cases = vec![
        Case {
            name: "lecture-direct",
            about: "the lecture's direct central impact of two equal balls, e = 0.8 (models/lecture-example.toml)",
            run: lecture_direct,
        },
        Case {
            name: "lecture-oblique",
            about: "the lecture's oblique impact: normal components exchanged with e = 0.8, tangential ones kept",
            run: lecture_oblique,
        },
    ];
    for &(name, law) in LAW_CASES {
        cases.push(Case { name, about: law.1, run: law_case });
    }
    cases.extend([
        Case {
            name: "chung-ooi-1",
            about: "Chung & Ooi's test 1: two glass spheres at ±10 m/s, elastic (published to 4 digits)",
            run: chung_ooi_1,
        },
        Case {
            name: "chung-ooi-2",
            about: "Chung & Ooi's test 2: an aluminium-alloy sphere on a rigid wall at 0.2 m/s (published)",
            run: chung_ooi_2,
        },
        Case {
            name: "chung-ooi-3",
            about: "Chung & Ooi's test 3: alumina and cast-iron spheres at 3.9 m/s, Tsuji damping: e out = e in",
            run: chung_ooi_3,
        },
        Case {
            name: "chung-ooi-4",
            about: "Chung & Ooi's test 4 at 45 degrees (exact Hunt–Crossley map): the sphere slides throughout",
            run: chung_ooi_4,
        },
        Case {
            name: "thornton-speeds",
            about: "a 10 mm steel ball yielding on a rigid wall (p_y = 1.6 GPa): e against Thornton's closed form",
            run: thornton_speeds,
        },
        Case {
            name: "brilliantov-series",
            about: "viscoelastic spheres at small b: e against the series 1 - C1 b + C2 b² (Schwager & Pöschel)",
            run: brilliantov_series,
        },
        Case {
            name: "hung-rod",
            about: "Beer & Johnston's hung rod struck at its lower end, e = 0.8 (models/hung-rod.toml)",
            run: hung_rod,
        },
        Case {
            name: "percussion-rod",
            about: "the hung rod struck at its centre of percussion: no impulse from the pivot along the blow",
            run: percussion_rod,
        },
        Case {
            name: "struck-rod",
            about: "a free rod struck at its end by a ball of a quarter of its mass, elastic (models/struck-rod.toml)",
            run: struck_rod,
        },
        Case {
            name: "rod-flat",
            about: "a rod of two end spheres dropped flat on Hertz ends: each end Hertz's contact of M/2 \
                    (models/rod-dropped-flat.toml)",
            run: rod_flat,
        },
        Case {
            name: "rod-angle",
            about: "a rod dropped at 30, 45, 60 and 80 degrees: its lower end's blow as rigid-body theory has it, \
                    then which end strikes next and when (models/rod-chatter.toml, models/rod-80deg.toml)",
            run: rod_angle,
        },
        Case {
            name: "dumbbell",
            about: "a dumbbell of two balls struck at one by a third, elastic, in a world (models/struck-dumbbell.toml)",
            run: dumbbell,
        },
        Case {
            name: "hung-rod-swing",
            about: "the hung rod released from 30 degrees under gravity into a ball at rest (models/hung-rod-swing.toml)",
            run: hung_rod_swing,
        },
        Case {
            name: "rocking-block",
            about: "Housner's rocking block, h/b = 4, released at 10 degrees: its corner transfer keeps \
                    1 - (3/2) sin²α of its spin (models/rocking-block.toml)",
            run: rocking_block,
        },
        Case {
            name: "cradle-3",
            about: "three touching Hertzian balls struck by one (Herrmann & Schmälzle 1981)",
            run: cradle_3,
        },
        Case {
            name: "bouncing-elastic",
            about: "an elastic ball dropped 10 cm on a floor: free fall, bounce, free flight, in closed form",
            run: bouncing_elastic,
        },
        Case {
            name: "spring-dashpot-drop",
            about: "a ball on a soft spring–dashpot dropped 1 cm: the contact with gravity in closed form",
            run: spring_dashpot_drop,
        },
    ]);
    cases
}

/// The laws whose exact references the suite checks: (case name, (law, what)).
const LAW_CASES: &[(&str, (&str, &str))] = &[
    ("law-hertz", ("hertz", "elastic Hertz: Deresiewicz's closed forms of the duration, peak force and penetration")),
    ("law-kelvin-voigt", ("kelvin-voigt", "Kelvin–Voigt: the damped oscillator's closed forms, e = 0.7")),
    ("law-hunt-crossley", ("hunt-crossley", "Hunt–Crossley's map at e = 0.7 against its exact e (Lambert W)")),
    ("law-lankarani-nikravesh", ("lankarani-nikravesh", "Lankarani–Nikravesh's map at e = 0.7, exact e")),
    ("law-carvalho-martins", ("carvalho-martins", "the exact map (Carvalho & Martins 2019): e = 0.7 exactly")),
    ("law-gonthier", ("gonthier", "Gonthier's map at e = 0.7 against its exact e")),
    ("law-tsuji", ("tsuji", "Tsuji's law at e = 0.7: a linear oscillator in its own variable")),
];

/// The suite's relative tolerance for values an integration at the default tolerances meets with room to spare.
const TIGHT: f64 = 1e-6;

fn row(
    case: &'static str,
    quantity: impl Into<String>,
    simulated: f64,
    reference: f64,
    source: &str,
    tolerance: f64,
) -> Row {
    let relative_error = ((simulated - reference) / reference).abs();
    Row {
        case,
        quantity: quantity.into(),
        simulated,
        reference,
        source: source.into(),
        relative_error,
        tolerance,
        pass: relative_error <= tolerance,
    }
}

/// Runs the suite (one case when `only` names it): every row, and the cases that could not run.
pub fn run(only: Option<&str>) -> Result<Vec<Row>, String> {
    let cases = cases();
    if let Some(name) = only
        && !cases.iter().any(|c| c.name == name)
    {
        let names: Vec<String> = cases.iter().map(|c| format!("  {}: {}", c.name, c.about)).collect();
        return Err(format!("no validation case `{name}`; the cases are:\n{}", names.join("\n")));
    }
    let mut rows = Vec::new();
    for case in cases.iter().filter(|c| only.is_none_or(|name| name == c.name)) {
        rows.extend(case.run().map_err(|why| format!("validation case `{}` could not run: {why}", case.name))?);
    }
    Ok(rows)
}

/// One impact of a scene text.
fn impact(text: &str) -> Result<Report, String> {
    run_impact(&impact_scene(text)?)
}

/// The scene of one impact, from its text.
fn impact_scene(text: &str) -> Result<crate::scene::Scene, String> {
    match crate::setup::parse_any(text, Path::new("validate.toml")).map_err(|e| e.to_string())? {
        Parsed::Impact(scene) => Ok(*scene),
        Parsed::World(_) => Err("a world scene where one impact was expected".into()),
    }
}

/// One impact of a scene.
fn run_impact(scene: &crate::scene::Scene) -> Result<Report, String> {
    crate::impact::simulate(scene, crate::history::Recording::Off)
        .map(|simulation| simulation.report)
        .map_err(|e| e.to_string())
}

/// One world run of a scene text.
fn world(text: &str) -> Result<WorldReport, String> {
    match crate::setup::parse_any(text, Path::new("validate.toml")).map_err(|e| e.to_string())? {
        Parsed::World(scene) => {
            crate::world_run::simulate(&scene).map(|simulation| simulation.report).map_err(|e| e.to_string())
        }
        Parsed::Impact(_) => Err("one impact where a world scene was expected".into()),
    }
}

fn after(report: &Report, body: usize) -> Result<[f64; 3], String> {
    report.bodies[body].velocity_after.ok_or_else(|| "the bodies did not separate".to_string())
}

/// The instantaneous direct impact (the lecture; docs/references.md#the-instantaneous-impact): `v1' = u1 - (1 + e) m2 (u1 - u2)/(m1 + m2)`,
/// `v2' = u2 + (1 + e) m1 (u1 - u2)/(m1 + m2)`, V0 = `(m1 u1 + m2 u2)/(m1 + m2)`.
fn textbook(m1: f64, m2: f64, u1: f64, u2: f64, e: f64) -> (f64, f64, f64) {
    let total = m1 + m2;
    (u1 - (1.0 + e) * m2 * (u1 - u2) / total, u2 + (1.0 + e) * m1 * (u1 - u2) / total, (m1 * u1 + m2 * u2) / total)
}

/// Beer & Johnston's rod (8 kg, 1.2 m, hung at its top) struck `depth` below its pivot by a 2 kg ball at 5 m/s with
/// e: the rod's moment of inertia about the pivot I_O = M L²/3 and effective mass I_O / depth², the impulse
/// J = (1 + e) v m_b m_eff / (m_b + m_eff), the ball's velocity after v - J/m_b, the rod's spin J depth / I_O, and
/// the pivot's impulse along the blow M ω' L/2 - J: (m_eff, ball after, spin after, pivot impulse).
fn hung_rod_by_hand(depth: f64, e: f64) -> (f64, f64, f64, f64) {
    let (mass, length, ball, speed) = (8.0, 1.2, 2.0, 5.0);
    let about_pivot = mass * length * length / 3.0;
    let effective = about_pivot / (depth * depth);
    let impulse = (1.0 + e) * speed * ball * effective / (ball + effective);
    let spin = impulse * depth / about_pivot;
    (effective, speed - impulse / ball, spin, mass * spin * length / 2.0 - impulse)
}

const HUNG_ROD: &str = "Beer & Johnston, Vector Mechanics for Engineers, sample problem 17.9, by hand \
                        (docs/references.md#eccentric-impact)";

/// The compliant rod turns by about 1e-4 rad during the blow; its geometry changes by the square of that.
const ROD: f64 = 1e-6;

fn hung_rod(case: &'static str) -> Result<Vec<Row>, String> {
    let report = impact(include_str!("../models/hung-rod.toml"))?;
    let (effective, ball, spin, pivot) = hung_rod_by_hand(1.2, 0.8);
    let rod = &report.bodies[1];
    let pivot_impulse = rod.pivot_impulse.ok_or("the bodies did not separate")?;
    let spin_after = rod.angular_velocity_after.ok_or("the bodies did not separate")?;
    Ok(vec![
        row(case, "rod's effective mass, kg", rod.effective_mass_at_contact, effective, HUNG_ROD, 1e-12),
        row(case, "ball velocity after, m/s", after(&report, 0)?[0], ball, HUNG_ROD, ROD),
        row(case, "rod's spin after, rad/s", spin_after[2], spin, HUNG_ROD, ROD),
        row(case, "pivot impulse along the blow, N s", pivot_impulse[0], pivot, HUNG_ROD, ROD),
        row(case, "rod's spin after, rad/s", spin_after[2], 3.21, "the textbook's answer (3 digits)", 2e-3),
        row(case, "ball velocity after, m/s", after(&report, 0)?[0], -0.143, "the textbook's answer (3 digits)", 2e-3),
    ])
}

fn percussion_rod(case: &'static str) -> Result<Vec<Row>, String> {
    let report = impact(include_str!("../models/percussion-rod.toml"))?;
    // The centre of percussion: 2L/3 = 0.8 m below the pivot, where the pivot takes nothing along the blow.
    let (effective, ball, spin, _) = hung_rod_by_hand(0.8, 0.8);
    let rod = &report.bodies[1];
    let pivot_impulse = rod.pivot_impulse.ok_or("the bodies did not separate")?;
    let spin_after = rod.angular_velocity_after.ok_or("the bodies did not separate")?;
    let blow = report.contact.deformation_impulse + report.contact.restitution_impulse.unwrap_or(0.0);
    let source = "the centre of percussion I_O/(M d) = 2L/3, by hand (docs/references.md#eccentric-impact)";
    Ok(vec![
        row(case, "rod's effective mass, kg", rod.effective_mass_at_contact, effective, source, 1e-12),
        row(case, "ball velocity after, m/s", after(&report, 0)?[0], ball, source, ROD),
        row(case, "rod's spin after, rad/s", spin_after[2], spin, source, ROD),
        // Zero has no relative error: the row measures the pivot's share of the blow against zero, as 1 + share.
        row(case, "1 + pivot impulse along the blow / blow", 1.0 + pivot_impulse[0] / blow, 1.0, source, ROD),
    ])
}

fn struck_rod(case: &'static str) -> Result<Vec<Row>, String> {
    let report = impact(include_str!("../models/struck-rod.toml"))?;
    // A uniform rod (M = 2 kg, L = 0.6 m) struck at its end: 1/m_eff = 1/M + (L/2)²/(M L²/12) = 4/M, the ball's
    // 0.5 kg. An elastic blow between equal effective masses passes J = m_b v = 1.5 N s: the ball stops, the rod's
    // centre leaves at J/M = 0.75 m/s and it turns at J (L/2) / (M L²/12) = 7.5 rad/s.
    let source = "a free rod struck at its end, m_eff = M/4, by hand (docs/references.md#eccentric-impact)";
    let rod = &report.bodies[1];
    let spin_after = rod.angular_velocity_after.ok_or("the bodies did not separate")?;
    let energy = &report.energy;
    let kinetic_after = energy.kinetic_after.ok_or("the bodies did not separate")?;
    Ok(vec![
        row(case, "rod's effective mass, kg", rod.effective_mass_at_contact, 0.5, source, 1e-12),
        row(case, "rod's centre velocity after, m/s", after(&report, 1)?[0], 0.75, source, ROD),
        row(case, "rod's spin after, rad/s", spin_after[2], 7.5, source, ROD),
        row(case, "1 + ball velocity after / 3 m/s", 1.0 + after(&report, 0)?[0] / 3.0, 1.0, source, ROD),
        row(case, "kinetic energy after, J", kinetic_after, energy.kinetic_before, "energy conserved (elastic)", 1e-9),
    ])
}

/// A rod of two end spheres dropped exactly flat on a floor without gravity (models/rod-dropped-flat.toml): both ends
/// touch at once, the rod does not turn, and each end is Hertz's contact of one end sphere (R = 5 mm) on the floor
/// with the effective mass M/2 (docs/references.md#rigid-bodies-with-several-contacts):
/// `d_m = (15 (M/2) v²/(16 E* √R))^(2/5)`, `t_c = 2.9432751843 d_m/v`, `F_m = (4/3) E* √R d_m^(3/2)`
/// (docs/references.md#elastic-hertz-contact); elastic, the rod rebounds at v.
fn rod_flat(case: &'static str) -> Result<Vec<Row>, String> {
    let report = world(include_str!("../models/rod-dropped-flat.toml"))?;
    if report.contacts.len() != 2 {
        return Err(format!("{} contacts, expected the two ends", report.contacts.len()));
    }
    let (mass, radius, young, poisson) = (0.2_f64, 0.005_f64, 2.1e11_f64, 0.3_f64);
    let v = -report.bodies[0].velocity_before[2];
    let e_star = young / (2.0 * (1.0 - poisson * poisson));
    let depth = (15.0 * (mass / 2.0) * v * v / (16.0 * e_star * radius.sqrt())).powf(0.4);
    let source = "Hertz's closed form for one end of effective mass M/2 (docs/references.md#elastic-hertz-contact)";
    let mut rows = Vec::new();
    for (k, c) in report.contacts.iter().enumerate() {
        let end = if c.spheres[0] == Some(0) { "+x" } else { "-x" };
        let duration = c.duration.ok_or("an end did not separate")?;
        rows.push(row(case, format!("{end} end's duration, s"), duration, 2.9432751843 * depth / v, source, TIGHT));
        rows.push(row(case, format!("{end} end's deepest penetration, m"), c.max_penetration, depth, source, TIGHT));
        let peak = 4.0 / 3.0 * e_star * radius.sqrt() * depth.powf(1.5);
        rows.push(row(case, format!("{end} end's peak force, N"), c.max_force, peak, source, TIGHT));
        rows.push(row(
            case,
            format!("contact {k} starts with the other, s"),
            c.start_time,
            1e-3,
            "the drop: 1 mm at v",
            1e-9,
        ));
    }
    let rod = &report.bodies[0];
    let symmetry = "symmetry: an elastic rebound at v without turning";
    rows.push(row(case, "rod's rebound / v", rod.velocity_after[2] / v, 1.0, symmetry, 1e-9));
    let turning = rod.angular_velocity_after.iter().map(|w| w.abs()).fold(0.0, f64::max);
    rows.push(row(case, "1 + its spin after x (L/2) / v", 1.0 + turning * 0.1 / v, 1.0, symmetry, 1e-9));
    Ok(rows)
}

/// The rod of models/rod-chatter.toml dropped at 30°, 45°, 60° and 80° on a smooth floor under gravity (30°: the
/// model itself, dropped from 0.245 m; 45° and 60°: `rod_sweep::scene`, the same rod 1 mm above the floor at 1 m/s;
/// 80°: models/rod-80deg.toml, that scene's text).
///
/// The first contact: its lower end strikes with `m_eff = M/(1 + 3 cos²θ)`, `J = (1 + e) m_eff v`,
/// `v_G' = -v + J/M`, `ω' = 6 J cos θ/(M L)` and the other end then moves at
/// `v_B = -v + (1 + e) v (1 - 3 cos²θ)/(1 + 3 cos²θ)` (docs/references.md#rigid-bodies-with-several-contacts), with
/// the contact's simulated e and v its approach speed. The compliant rod turns by `ω' t_c` (2e-3 to 3e-3 rad) during
/// the contact, which changes its lever `(L/2) cos θ` and so its effective mass by a fraction of that order (times
/// tan θ), and gravity adds `g t_c` (under 1e-3 of v): the tolerance is 3 ω' t_c, with ω' and t_c the contact's own.
///
/// Then the next contact: the rigid rod flown from the first contact's start with its simulated velocity and spin
/// after, under gravity, in closed form (`rod_sweep::PlanarRod`: its mass centre on a parabola, its angle turning at
/// ω'), its ends' heights scanned and bisected on that exact motion — nothing of the world's integrator — gives which
/// end touches next and when. The rod flies from an instant where the compliant contact took t_c: the time agrees to
/// a few t_c (tolerance 3 t_c over the flight). At 30° to 60° the other end comes down and strikes; at 80° it
/// moves up (`v_B > 0`), no end touches before the apex of the rebound, and the rod turns over in its flight until the
/// other end lands, 0.2 s later.
fn rod_angle(case: &'static str) -> Result<Vec<Row>, String> {
    use crate::rod_sweep::{self, PlanarRod};
    let mut rows = Vec::new();
    for degrees in [30.0_f64, 45.0, 60.0, 80.0] {
        let text = match degrees {
            30.0 => include_str!("../models/rod-chatter.toml").to_string(),
            80.0 => include_str!("../models/rod-80deg.toml").to_string(),
            _ => rod_sweep::scene(degrees, 2, 1.0),
        };
        let report = world(&text)?;
        let first = report.contacts.first().ok_or("no contact")?;
        if first.spheres != [Some(1), None] {
            return Err(format!("{degrees}°: the lower end should strike first, not sphere {:?}", first.spheres));
        }
        let (mass, length, theta) = (rod_sweep::MASS, rod_sweep::LENGTH, degrees.to_radians());
        let v = first.approach_speed;
        let e = first.restitution_velocity_ratio.ok_or("the first contact has no e")?;
        let c2 = theta.cos().powi(2);
        let impulse = (1.0 + e) * mass / (1.0 + 3.0 * c2) * v;
        let spin = 6.0 * impulse * theta.cos() / (mass * length);
        let other = -v + (1.0 + e) * v * (1.0 - 3.0 * c2) / (1.0 + 3.0 * c2);
        let after = first.velocities_after.as_ref().ok_or("the first contact did not separate")?[0];
        let turning = first.angular_velocities_after.as_ref().ok_or("the first contact did not separate")?[0];
        let t_c = first.duration.ok_or("the first contact did not end")?;
        let tolerance = 3.0 * spin * t_c;
        // The other end at (L/2)(cos θ, 0, sin θ) from the mass centre: v_B = v_G + ω × r_B, its z component.
        let v_b = after[2] - turning[1] * length / 2.0 * theta.cos();
        let source = "rigid-body impact of the rod's end with the contact's e (docs/references.md)";
        let at = |what: &str| format!("{degrees}°: {what}");
        // The floor's impulse over M v (v_G' + v)/v: never small, where v_G' itself nearly vanishes at 60°.
        let blow = (after[2] + v) / v;
        rows.push(row(case, at("floor's impulse / (M v)"), blow, impulse / (mass * v), source, tolerance));
        rows.push(row(case, at("rod's spin after, rad/s"), turning[1], spin, source, tolerance));
        rows.push(row(case, at("other end's velocity after, m/s"), v_b, other, source, tolerance));

        // The rigid flight from the first touch.
        let g = -report.world.gravity[2];
        let mut rod = PlanarRod::touching(degrees, v);
        (rod.vz, rod.spin) = (after[2], turning[1]);
        let (flight, end) = rod.next_touch(g, 1.0).ok_or_else(|| at("the rigid rod does not touch within 1 s"))?;
        let next = report.contacts.get(1).ok_or_else(|| at("no second contact in the run"))?;
        let sphere = next.spheres[0].ok_or("the second contact is not of a sphere of the rod")?;
        let source = "the rigid rod's flight after the first contact, under gravity, bisected (src/rod_sweep.rs)";
        rows.push(row(
            case,
            at("1 + the end that strikes next (0: the other)"),
            1.0 + sphere as f64,
            1.0 + end as f64,
            source,
            0.0,
        ));
        let simulated = next.start_time - first.start_time;
        rows.push(row(case, at("next contact after the first, s"), simulated, flight, source, 3.0 * t_c / flight));
        if degrees == 80.0 {
            // Up to the apex of the rebound (v_G'/g after the first contact's end) no end touches: one contact.
            let apex = first.end_time.ok_or("the first contact did not end")? + after[2].max(0.0) / g;
            let before = report.contacts.iter().filter(|c| c.start_time < apex).count();
            let none = rod.next_touch(g, after[2].max(0.0) / g).map_or(1.0, |_| 2.0);
            rows.push(row(case, at("contacts before the rebound's apex"), before as f64, none, source, 0.0));
        }
    }
    Ok(rows)
}

/// A dumbbell (two 0.25 kg balls 0.2 m apart, I = 5.08e-3 kg m² across its axis) struck at one ball, across its
/// axis, by a 0.25 kg ball at 2 m/s, elastic (models/struck-dumbbell.toml): the eccentric impact
/// (docs/references.md#eccentric-impact) with `1/m_eff = 1/M + (L/2)²/I`, `J = 2 v m_b m_eff/(m_b + m_eff)`; the
/// dumbbell's centre leaves at J/M turning at J (L/2)/I, the ball at v - J/m_b. The dumbbell turns by about 1e-3 rad
/// during the blow, and its geometry (the normal, the lever) changes by the square of that: 1e-6, and 1e-4 for the
/// ball's small velocity after (a difference of two velocities 250 times larger).
fn dumbbell(case: &'static str) -> Result<Vec<Row>, String> {
    let report = world(include_str!("../models/struck-dumbbell.toml"))?;
    let (mass, inertia, half, ball, v) = (0.5_f64, 5.08e-3_f64, 0.1_f64, 0.25_f64, 2.0_f64);
    let effective = 1.0 / (1.0 / mass + half * half / inertia);
    let impulse = 2.0 * v * ball * effective / (ball + effective);
    let source = "the eccentric impact of the struck end, by hand (docs/references.md#eccentric-impact)";
    let contact = report.contacts.first().ok_or("no contact")?;
    let e = contact.restitution_velocity_ratio.ok_or("the blow did not separate")?;
    let dumbbell = &report.bodies[0];
    let energy = &report.energy;
    Ok(vec![
        row(case, "e of the elastic blow", e, 1.0, "Hertz's contact is elastic: e = 1", ROD),
        row(case, "dumbbell's centre velocity after, m/s", dumbbell.velocity_after[1], impulse / mass, source, ROD),
        row(
            case,
            "dumbbell's spin after, rad/s",
            dumbbell.angular_velocity_after[2],
            impulse * half / inertia,
            source,
            1e-5,
        ),
        row(case, "ball's velocity after, m/s", report.bodies[1].velocity_after[1], v - impulse / ball, source, 1e-4),
        row(
            case,
            "kinetic energy after, J",
            energy.kinetic_after,
            energy.kinetic_before,
            "energy conserved (elastic)",
            1e-9,
        ),
    ])
}

/// The hung rod (M = 8 kg, L = 1.2 m, I_O = M L²/3 about its pivot) released at rest from φ = 30° under gravity
/// (models/hung-rod-swing.toml): at the bottom of its swing, where it meets the ball at rest, energy gives
/// `ω = sqrt(2 M g (L/2)(1 - cos φ)/I_O)` and its end moves at ω L. The blow is the hung rod's eccentric impact with
/// `m_eff = I_O/L²` and the contact's e: `J = (1 + e) ω L m_b m_eff/(m_b + m_eff)`, the ball leaves at J/m_b and the
/// rod turns on at `ω - J L/I_O` (docs/references.md#eccentric-impact). The rod turns by 2e-4 rad during the blow: 1e-6.
fn hung_rod_swing(case: &'static str) -> Result<Vec<Row>, String> {
    let report = world(include_str!("../models/hung-rod-swing.toml"))?;
    let blow = report.contacts.iter().find(|c| c.bodies == [0, 1]).ok_or("the rod never reached the ball")?;
    let (mass, length, ball, g, phi) = (8.0_f64, 1.2_f64, 2.0_f64, 9.81_f64, 30_f64.to_radians());
    let about_pivot = mass * length * length / 3.0;
    let spin = (2.0 * mass * g * length / 2.0 * (1.0 - phi.cos()) / about_pivot).sqrt();
    let e = blow.restitution_velocity_ratio.ok_or("the blow did not separate")?;
    let effective = about_pivot / (length * length);
    let impulse = (1.0 + e) * spin * length * ball * effective / (ball + effective);
    let after = blow.velocities_after.as_ref().ok_or("the blow did not separate")?;
    let turning = blow.angular_velocities_after.as_ref().ok_or("the blow did not separate")?;
    let swing = "the swing under gravity: energy, by hand";
    let source = "the hung rod's eccentric impact with the contact's e, by hand (docs/references.md#eccentric-impact)";
    Ok(vec![
        row(case, "the rod's end speed at the ball, m/s", blow.approach_speed, spin * length, swing, TIGHT),
        row(case, "e of the blow", e, 0.8, "Kelvin–Voigt's exact e (docs/references.md#kelvin-voigt)", ROD),
        row(case, "ball's velocity after, m/s", after[1][0], impulse / ball, source, ROD),
        row(case, "rod's spin after, rad/s", turning[0][2], spin - impulse * length / about_pivot, source, ROD),
    ])
}

/// Housner's rocking block (models/rocking-block.toml; Housner, Bull. Seism. Soc. Am. 53, 403 (1963)): b = 0.05 m,
/// h = 0.2 m, corner spheres of r = 1 mm whose lowest points are the corners, released at rest on its -x corner
/// tilted φ0 = 10°. Rolling on its corner sphere, its mass centre stands at `z_G = r + b sin φ + (h - r) cos φ`, so
/// it strikes (level) turning at `ω = sqrt(2 g (z_G(φ0) - h)/((4/3) R²))`, `R² = b² + h²`; after the transfer it
/// rocks about its new corner and comes back level onto the old one with the spin it left with, Housner's
/// `ω' = (1 - (3/2) sin²α) ω`, `α = atan(b/h)`. The compliant corners depart from both by what the convergence study
/// of docs/world.md#the-rocking-block measures: 1.0e-4 for ω and 1.6e-3 for ω'/ω with steel's stiffness (5e-4 and
/// 4.6e-4 a thousand times stiffer, the last a floor the undamped tangential spring leaves): 5e-4 and 3e-3. The new
/// corner does not bounce: its e (6e-3) is below 1e-2.
fn rocking_block(case: &'static str) -> Result<Vec<Row>, String> {
    let report = world(include_str!("../models/rocking-block.toml"))?;
    let (b, h, r, g, tilt) = (0.05_f64, 0.2_f64, 0.001_f64, 9.81_f64, 10_f64.to_radians());
    let strike = report.contacts.iter().find(|c| c.spheres[0] == Some(0)).ok_or("the +x corner never struck")?;
    let back = report
        .contacts
        .iter()
        .find(|c| c.spheres[0] == Some(1) && c.start_time > strike.start_time)
        .ok_or("the block never came back onto its -x corner")?;
    let drop = r + b * tilt.sin() + (h - r) * tilt.cos() - h;
    let fall = (2.0 * g * drop / (4.0 / 3.0 * (b * b + h * h))).sqrt();
    let before = strike.angular_velocities_before[0][1];
    let after = -back.angular_velocities_before[0][1];
    let housner = 1.0 - 1.5 * (b / h).atan().sin().powi(2);
    let e = strike.restitution_velocity_ratio.unwrap_or(0.0);
    Ok(vec![
        row(case, "spin at the strike, rad/s", before, fall, "the fall about the corner from 10 degrees: energy", 5e-4),
        row(
            case,
            "spin back on the old corner / at the strike",
            after / before,
            housner,
            "Housner: 1 - (3/2) sin²α",
            3e-3,
        ),
        row(case, "1 + e of the new corner", 1.0 + e, 1.0, "Housner: the new corner does not bounce", 1e-2),
    ])
}

const LECTURE: &str =
    "the lecture's formulas for a direct impact with e = 0.8 (docs/references.md#the-instantaneous-impact)";

fn lecture_direct(case: &'static str) -> Result<Vec<Row>, String> {
    let report = impact(include_str!("../models/lecture-example.toml"))?;
    let (m1, m2) = (report.bodies[0].mass, report.bodies[1].mass);
    let (u1, u2) = (report.bodies[0].velocity_before[0], report.bodies[1].velocity_before[0]);
    let (v1, v2, v0) = textbook(m1, m2, u1, u2, 0.8);
    let e = report.contact.restitution_velocity_ratio.ok_or("the balls did not separate")?;
    // The lecture prints 3 decimals: half a unit in the last place is 8.5e-5 of 5.864 and 1.3e-4 of 3.793.
    Ok(vec![
        row(
            case,
            "e, velocity ratio",
            e,
            0.8,
            "the exact Hunt–Crossley map (Carvalho & Martins 2019) of e = 0.8",
            TIGHT,
        ),
        row(case, "ball 1 velocity after, m/s", after(&report, 0)?[0], v1, LECTURE, TIGHT),
        row(case, "ball 2 velocity after, m/s", after(&report, 1)?[0], v2, LECTURE, TIGHT),
        row(case, "V0 at maximum compression, m/s", report.contact.common_normal_velocity, v0, LECTURE, TIGHT),
        row(
            case,
            "ball 1 velocity after, m/s",
            after(&report, 0)?[0],
            -5.864,
            "the lecture's worked example (3 decimals)",
            1e-4,
        ),
        row(
            case,
            "ball 2 velocity after, m/s",
            after(&report, 1)?[0],
            3.793,
            "the lecture's worked example (3 decimals)",
            2e-4,
        ),
    ])
}

fn lecture_oblique(case: &'static str) -> Result<Vec<Row>, String> {
    let report = impact(include_str!("../models/lecture-oblique.toml"))?;
    let (m1, m2) = (report.bodies[0].mass, report.bodies[1].mass);
    let (a, b) = (report.bodies[0].velocity_before, report.bodies[1].velocity_before);
    let (v1, v2, _) = textbook(m1, m2, a[0], b[0], 0.8);
    // The line of centres turns while the balls slide past each other, by about the tangential travel during contact
    // over the sum of the radii — 7.07 m/s for about 0.2 ms over 0.1 m, 0.014 rad — and the lecture's fixed normal
    // holds to that angle: the simulation departs from it by about 1 % (docs/oblique.md). Momentum is kept exactly.
    let turning = 2e-2;
    let source = "the lecture: normal components as a direct impact, tangential ones unchanged";
    let momentum = |k: usize, before: bool| -> Result<f64, String> {
        let v = |i: usize| if before { Ok(report.bodies[i].velocity_before) } else { after(&report, i) };
        Ok(m1 * v(0)?[k] + m2 * v(1)?[k])
    };
    let kept = "conservation of momentum";
    Ok(vec![
        row(case, "momentum along the normal after, N s", momentum(0, false)?, momentum(0, true)?, kept, 1e-12),
        row(case, "momentum across it after, N s", momentum(1, false)?, momentum(1, true)?, kept, 1e-12),
        row(case, "ball A normal velocity after, m/s", after(&report, 0)?[0], v1, source, turning),
        row(case, "ball B normal velocity after, m/s", after(&report, 1)?[0], v2, source, turning),
        row(case, "ball B tangential velocity after, m/s", after(&report, 1)?[1], b[1], source, turning),
    ])
}

/// A 10 mm, 32.9 g ball thrown at 1 m/s against a wall under `law` (its damping from e = 0.7): the report's exact
/// reference section, row by row.
fn law_case(case: &'static str) -> Result<Vec<Row>, String> {
    let &(_, (law, _)) = LAW_CASES.iter().find(|(name, _)| *name == case).ok_or("not a law case")?;
    let contact = match law {
        "hertz" => "law = \"hertz\"\nstiffness = 1e10".to_string(),
        "kelvin-voigt" => "law = \"kelvin-voigt\"\nstiffness = 1e6\nrestitution = 0.7".to_string(),
        other => format!("law = \"{other}\"\nstiffness = 1e10\nrestitution = 0.7"),
    };
    let text = format!(
        "[[bodies]]\nradius = 0.01\nmass = 0.0329\nvelocity = [1.0, 0.0, 0.0]\n\n\
         [[bodies]]\nradius = inf\nmass = inf\nvelocity = [0.0, 0.0, 0.0]\n\n[contact]\n{contact}\n"
    );
    let report = impact(&text)?;
    let reference = report.reference.as_ref().ok_or("the law has no exact reference")?;
    let c = &report.contact;
    let source = reference.source.as_str();
    let mut rows = Vec::new();
    let mut add = |quantity: &str, simulated: Option<f64>, exact: Option<f64>| {
        if let (Some(simulated), Some(exact)) = (simulated, exact) {
            rows.push(row(case, quantity, simulated, exact, source, TIGHT));
        }
    };
    add("e, velocity ratio", c.restitution_velocity_ratio, reference.restitution);
    add("maximum penetration, m", Some(c.max_penetration), reference.max_penetration);
    add("time of maximum compression, s", Some(c.max_compression_time - c.start_time), reference.max_compression_time);
    add("duration, s", c.duration, reference.duration);
    add("peak force, N", Some(c.max_force), reference.max_force);
    if rows.is_empty() {
        return Err("no exact value to compare with".into());
    }
    Ok(rows)
}

/// Two equal spheres closing at `speed` each, with a material's E (Pa), nu, rho (kg/m³) and radius (m), elastic.
fn equal_spheres(young: f64, poisson: f64, density: f64, radius: f64, speed: f64, law: &str) -> String {
    let body = |v: f64| {
        format!(
            "[[bodies]]\nradius = {radius:?}\ndensity = {density:?}\nyoung = {young:?}\npoisson = {poisson:?}\n\
             velocity = [{v:?}, 0.0, 0.0]\n\n"
        )
    };
    format!("{}{}[contact]\n{law}\n", body(speed), body(-speed))
}

/// The contact's duration, peak force and deepest penetration against published values.
fn published_contact(case: &'static str, report: &Report, published: [f64; 3], source: &str) -> Vec<Row> {
    let c = &report.contact;
    // The published values carry 4 significant digits (dmax of test 2: 3): half a unit of the last is 1e-3 at most.
    let rounding = 1e-3;
    vec![
        row(case, "duration, s", c.duration.unwrap_or(f64::NAN), published[0], source, rounding),
        row(case, "peak force, N", c.max_force, published[1], source, rounding),
        row(case, "maximum penetration, m", c.max_penetration, published[2], source, rounding),
    ]
}

fn chung_ooi_1(case: &'static str) -> Result<Vec<Row>, String> {
    let report = impact(&equal_spheres(4.8e10, 0.2, 2800.0, 0.01, 10.0, "law = \"hertz\""))?;
    let source = "Chung & Ooi 2011, test 1: tc = 40.34 µs, Fmax = 10.70 kN, dmax = 274.1 µm";
    Ok(published_contact(case, &report, [40.34e-6, 10.70e3, 274.1e-6], source))
}

fn chung_ooi_2(case: &'static str) -> Result<Vec<Row>, String> {
    let report = impact(include_str!("../models/sphere-on-rigid-wall.toml"))?;
    let source = "Chung & Ooi 2011, test 2: tc = 731.7 µs, Fmax = 11.37 kN, dmax = 49.7 µm";
    Ok(published_contact(case, &report, [731.7e-6, 11.37e3, 49.7e-6], source))
}

fn chung_ooi_3(case: &'static str) -> Result<Vec<Row>, String> {
    // Alumina (380 GPa, 0.23, 4000 kg/m³) and cast iron (100 GPa, 0.25, 7000 kg/m³), r = 2.5 mm, on a rigid wall at
    // 3.9 m/s with Tsuji's damping for e: the test asks that the e which comes out is the e put in.
    let mut rows = Vec::new();
    for (material, young, poisson, density) in [("alumina", 3.8e11, 0.23, 4000.0), ("cast iron", 1.0e11, 0.25, 7000.0)]
    {
        for e in [0.1, 0.5, 0.9] {
            let text = format!(
                "[[bodies]]\nradius = 0.0025\ndensity = {density:?}\nyoung = {young:?}\npoisson = {poisson:?}\n\
                 velocity = [3.9, 0.0, 0.0]\n\n[[bodies]]\nradius = inf\nmass = inf\nyoung = inf\n\
                 velocity = [0.0, 0.0, 0.0]\n\n[contact]\nlaw = \"tsuji\"\nrestitution = {e:?}\n"
            );
            let report = impact(&text)?;
            let simulated = report.contact.restitution_velocity_ratio.ok_or("the sphere did not separate")?;
            let source = "Chung & Ooi 2011, test 3: the e asked for";
            rows.push(row(case, format!("{material}, e for e = {e}"), simulated, e, source, TIGHT));
        }
    }
    Ok(rows)
}

fn thornton_speeds(case: &'static str) -> Result<Vec<Row>, String> {
    // A 10 mm steel ball (E = 210 GPa, nu = 0.3, 7850 kg/m³) on a rigid wall, p_y = 1.6 GPa: E* = E/(1 - nu²),
    // d_y = (pi p_y / (2 E*))² r, (1/2) m V_y² = (8/15) E* sqrt(r) d_y^(5/2) (Thornton 1997).
    let (young, poisson, density, radius, pressure) = (210e9_f64, 0.3_f64, 7850.0_f64, 0.005_f64, 1.6e9_f64);
    let modulus = young / (1.0 - poisson * poisson);
    let mass = 4.0 / 3.0 * std::f64::consts::PI * radius.powi(3) * density;
    let d_y = (std::f64::consts::PI * pressure / (2.0 * modulus)).powi(2) * radius;
    let v_y = (16.0 / 15.0 * modulus * radius.sqrt() * d_y.powf(2.5) / mass).sqrt();
    // Thornton's closed form in x = V_y / V_i; his table: 0.9306, 0.7733, 0.6586, 0.3743 at V_i/V_y = 2, 5, 10, 100.
    let closed = |ratio: f64| {
        let x = 1.0 / ratio;
        (6.0 * 3f64.sqrt() / 5.0).sqrt()
            * (1.0 - x * x / 6.0).sqrt()
            * (x / (x + 2.0 * (1.2 - 0.2 * x * x).sqrt())).powf(0.25)
    };
    let mut rows = Vec::new();
    for ratio in [0.5, 2.0, 5.0, 10.0, 100.0] {
        let text = format!(
            "[[bodies]]\nradius = {radius:?}\ndensity = {density:?}\nyoung = {young:?}\npoisson = {poisson:?}\n\
             velocity = [{:?}, 0.0, 0.0]\n\n[[bodies]]\nradius = inf\nmass = inf\nyoung = inf\n\
             velocity = [0.0, 0.0, 0.0]\n\n[contact]\nlaw = \"thornton\"\nyield_pressure = {pressure:?}\n",
            ratio * v_y
        );
        let report = impact(&text)?;
        let simulated = report.contact.restitution_velocity_ratio.ok_or("the ball did not separate")?;
        let (reference, source) = if ratio < 1.0 {
            (1.0, "below the yield speed: elastic, e = 1")
        } else {
            (closed(ratio), "Thornton 1997, closed form (his table to 4 digits)")
        };
        rows.push(row(case, format!("e at {ratio} V_y"), simulated, reference, source, TIGHT));
    }
    Ok(rows)
}

fn brilliantov_series(case: &'static str) -> Result<Vec<Row>, String> {
    // b = (3/2) A (K/m*)^(2/5) v0^(1/5); e = 1 - C1 b + C2 b² + O(b³) with C1 = sqrt(pi) Gamma(3/5) / (2^(1/5)
    // 5^(2/5) Gamma(21/10)) = 1.15344886 and C2 = (3/5) C1² = 0.79826656 (Schwager & Pöschel 1998, 2008; their
    // 5-digit 1.15344 would leave 9e-6 b). The next term is about 0.5 b³: the tolerance 1e-6 holds for b <= 0.01.
    let c1 = std::f64::consts::PI.sqrt() * libm::tgamma(0.6) / (2f64.powf(0.2) * 5f64.powf(0.4) * libm::tgamma(2.1));
    let c2 = 0.6 * c1 * c1;
    let (mass, speed, stiffness) = (0.05_f64, 2.0_f64, 5e8_f64);
    let mut rows = Vec::new();
    for b in [0.002, 0.005, 0.01] {
        let a = b / (1.5 * (stiffness / mass).powf(0.4) * speed.powf(0.2));
        let text = format!(
            "[[bodies]]\nradius = 1.0\nmass = {mass:?}\nvelocity = [{speed:?}, 0.0, 0.0]\n\n[[bodies]]\nradius = inf\n\
             mass = inf\nvelocity = [0.0, 0.0, 0.0]\n\n[contact]\nlaw = \"brilliantov\"\nstiffness = {stiffness:?}\n\
             damping = {a:?}\n\n[solver]\nrtol = 1e-12\natol = 1e-14\n"
        );
        let report = impact(&text)?;
        let simulated = report.contact.restitution_velocity_ratio.ok_or("the ball did not separate")?;
        let series = 1.0 - c1 * b + c2 * b * b;
        let source = "Schwager & Pöschel, PRE 57 (1998), 78 (2008): 1 - C1 b + C2 b²";
        rows.push(row(case, format!("e at b = {b}"), simulated, series, source, TIGHT));
    }
    Ok(rows)
}

fn chung_ooi_4(case: &'static str) -> Result<Vec<Row>, String> {
    // With the exact Hunt–Crossley map rather than the model's Tsuji law: Tsuji's force pulls before the penetration
    // returns to zero, and friction acts only while it compresses, and its cap outgrows the unloaded Mindlin spring for
    // the first 12 ns (docs/oblique.md), so its tangential impulse departs from rigid sliding by 1e-6 to 5e-6. A force
    // K d^(3/2) (1 + alpha d') never pulls, and slides from first touch: rigid sliding holds to the integration's
    // accuracy.
    let text = include_str!("../models/chung-ooi-test4.toml").replace("law = \"tsuji\"", "law = \"carvalho-martins\"");
    let scene = impact_scene(&text)?;
    let mu = scene.contact.friction;
    let report = run_impact(&scene)?;
    let e = report.contact.restitution_velocity_ratio.ok_or("the sphere did not separate")?;
    let sphere = report.bodies.iter().position(|b| b.mass.is_finite()).ok_or("no sphere")?;
    let body = &report.bodies[sphere];
    let oblique = report.oblique.as_ref().ok_or("not an oblique impact")?;
    // Rigid-body sliding on a wall (docs/oblique.md): the normal impulse m (1 + e) vn, the tangential one mu times
    // it against the slip; for a solid sphere without spin, vt' = vt - mu (1 + e) vn and w' r = (5/2) mu (1 + e) vn.
    let normal = report.normal;
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let u = body.velocity_before;
    let vn = dot(u, normal).abs();
    let tangential =
        [u[0] - dot(u, normal) * normal[0], u[1] - dot(u, normal) * normal[1], u[2] - dot(u, normal) * normal[2]];
    let vt = dot(tangential, tangential).sqrt();
    let v = body.velocity_after.ok_or("the sphere did not separate")?;
    let vt_after = dot(v, tangential) / vt;
    let spin = body.angular_velocity_after.ok_or("the sphere did not separate")?;
    let spin = dot(spin, spin).sqrt() * body.radius;
    let source = "rigid-body sliding with the simulated e (Chung & Ooi 2011, test 4; docs/oblique.md)";
    Ok(vec![
        row(case, "regime is sliding (1)", f64::from(u8::from(oblique.regime == "sliding")), 1.0, source, 0.0),
        row(case, "tangential velocity after, m/s", vt_after, vt - mu * (1.0 + e) * vn, source, TIGHT),
        row(case, "spin after times radius, m/s", spin, 2.5 * mu * (1.0 + e) * vn, source, TIGHT),
    ])
}

fn cradle_3(case: &'static str) -> Result<Vec<Row>, String> {
    let report = world(include_str!("../models/newtons-cradle-3.toml"))?;
    let v0 = report.bodies[0].velocity_before[0];
    let source = "Herrmann & Schmälzle, Am. J. Phys. 49, 761 (1981), to 4 decimals";
    let published: [f64; 3] = [-0.0710, 0.0764, 0.9945];
    Ok((0..3)
        .map(|k| {
            let tolerance = 0.00005 / published[k].abs() + 1e-4;
            row(
                case,
                format!("ball {} velocity after / v0", k + 1),
                report.bodies[k].velocity_after[0] / v0,
                published[k],
                source,
                tolerance,
            )
        })
        .collect())
}

fn bouncing_elastic(case: &'static str) -> Result<Vec<Row>, String> {
    let text = include_str!("../models/bouncing-ball.toml")
        .replace("law = \"carvalho-martins\"\nrestitution = 0.8", "law = \"hertz\"")
        .replace("gravity = [0.0, 0.0, -9.81]", "gravity = [0.0, 0.0, -9.81]\nmax_contacts = 3");
    let report = world(&text)?;
    if report.contacts.len() < 3 {
        return Err(format!("{} contacts, expected 3", report.contacts.len()));
    }
    let g = 9.81;
    // Dropped from rest with its lowest point h = 0.1 m above the floor: it touches after sqrt(2h/g) at sqrt(2 g h);
    // an elastic contact returns it at the same speed, and it flies 2 v/g before the next touch.
    let h = report.bodies[0].position_before[2] - report.bodies[0].radius;
    let (fall, speed) = ((2.0 * h / g).sqrt(), (2.0 * g * h).sqrt());
    let source = "free fall and flight under gravity, an elastic bounce (closed form)";
    let mut rows = vec![
        row(case, "first touch, s", report.contacts[0].start_time, fall, source, 1e-12),
        row(case, "approach speed of the first contact, m/s", report.contacts[0].approach_speed, speed, source, 1e-12),
    ];
    for k in 0..2 {
        let c = &report.contacts[k];
        let e = c.restitution_velocity_ratio.ok_or("a bounce did not separate")?;
        let exit = e * c.approach_speed;
        rows.push(row(case, format!("e of contact {k}"), e, 1.0, "Hertz's contact is elastic: e = 1", 1e-9));
        let end = c.end_time.ok_or("a bounce did not end")?;
        let next = &report.contacts[k + 1];
        rows.push(row(
            case,
            format!("touch {} after the flight 2 v/g, s", k + 1),
            next.start_time,
            end + 2.0 * exit / g,
            source,
            1e-9,
        ));
    }
    Ok(rows)
}

/// A ball dropped from rest 1 cm onto a floor through a linear spring–dashpot soft enough that gravity matters during
/// contact (g/(w v) = 0.39): its contact in closed form. With d the penetration, `m d'' = m g - k d - c d'` from
/// d = 0, d' = v = sqrt(2 g h): `d = g/w² + exp(-zeta w t) (A cos wd t + B sin wd t)`, A = -g/w², B = (v + zeta w A)/wd;
/// the contact ends at the first zero of d after its maximum (bisected to the last bit), and e = -d'(end)/v — no
/// longer the nominal e = 0.5 of the map without gravity.
fn spring_dashpot_drop(case: &'static str) -> Result<Vec<Row>, String> {
    let (k, h, g, nominal) = (1e3_f64, 0.01_f64, 9.81_f64, 0.5_f64);
    let text = include_str!("../models/bouncing-ball.toml")
        .replace(
            "law = \"carvalho-martins\"\nrestitution = 0.8",
            &format!("law = \"kelvin-voigt\"\nstiffness = {k:e}\nrestitution = {nominal}"),
        )
        .replace("gravity = [0.0, 0.0, -9.81]", "gravity = [0.0, 0.0, -9.81]\nmax_contacts = 1")
        .replace("position = [0.0, 0.0, 0.11]", "position = [0.0, 0.0, 0.02]");
    let report = world(&text)?;
    let m = report.bodies[0].mass;
    let zeta = -nominal.ln() / (std::f64::consts::PI.powi(2) + nominal.ln().powi(2)).sqrt();
    let w = (k / m).sqrt();
    let wd = w * (1.0 - zeta * zeta).sqrt();
    let v = (2.0 * g * h).sqrt();
    let a = -g / (w * w);
    let b = (v + zeta * w * a) / wd;
    let d = |t: f64| g / (w * w) + (-zeta * w * t).exp() * (a * (wd * t).cos() + b * (wd * t).sin());
    let rate = |t: f64| {
        (-zeta * w * t).exp()
            * (-zeta * w * (a * (wd * t).cos() + b * (wd * t).sin()) + wd * (b * (wd * t).cos() - a * (wd * t).sin()))
    };
    // The penetration peaks within the first half period and returns to zero within one: scanned from a quarter
    // period in steps of 1/4000 of a period, then bisected.
    let step = std::f64::consts::TAU / wd / 4000.0;
    let mut low = 1000.0 * step;
    while d(low + step) > 0.0 {
        low += step;
        if low > 4000.0 * step {
            return Err("the exact contact does not end within a period".into());
        }
    }
    let mut high = low + step;
    for _ in 0..200 {
        let middle = 0.5 * (low + high);
        if d(middle) > 0.0 { low = middle } else { high = middle }
    }
    let duration = 0.5 * (low + high);
    let c = report.contacts.first().ok_or("no contact")?;
    let source = "the damped oscillator under gravity in closed form (Kelvin–Voigt, zeta from e = 0.5)";
    Ok(vec![
        row(case, "duration, s", c.duration.ok_or("the ball did not leave")?, duration, source, 1e-9),
        row(
            case,
            "e, velocity ratio",
            c.restitution_velocity_ratio.ok_or("the ball did not leave")?,
            -rate(duration) / v,
            source,
            1e-9,
        ),
        row(case, "first touch, s", c.start_time, (2.0 * h / g).sqrt(), "free fall (closed form)", 1e-12),
    ])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn case_names_are_unique() {
        let cases = cases();
        for (i, a) in cases.iter().enumerate() {
            assert!(cases[i + 1..].iter().all(|b| b.name != a.name), "{}", a.name);
        }
    }
}
