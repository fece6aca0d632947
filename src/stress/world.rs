//! The stress run's random worlds (`impact stress --worlds`): 3 to 8 spheres on a jittered grid (some rows touching,
//! as a cradle's), thrown at each other, half of them under gravity with a floor and sometimes a fixed sphere, every
//! law, both separation criteria and both damping maps; half of them with friction (a Mindlin or a constant tangential
//! spring, with or without its damping) and spinning bodies; a third of them with rigid bodies in place of some balls
//! (a clump of spheres, or one sphere off the mass centre, with a turned inertia tensor and a spin). Each run is
//! checked for what a world must keep whatever happens in it (docs/world.md#what-is-tested):
//!
//! - `world.energy_balance`: the energy balance closes, relative to the largest energy in play;
//! - `world.momentum`, `world.angular_momentum`: without gravity, immovable bodies and pivots, the total momentum and
//!   angular momentum (about the origin, orbital and spin: `I ω` with the inertia turned with the body) are kept,
//!   relative to `sum m |v|` and `sum (m |x| |v| + |I ω|)`;
//! - `world.overlap_after`: when the run stops, no two spheres of two bodies (or a sphere and a face) that are not in
//!   an active contact overlap by more than the rounding of their positions beyond the overlap their last contact
//!   parted them at (a contact its force ended; zero otherwise): the measure is that excess over the tolerance, at
//!   most 1.

use super::CaseResult;
use crate::draw::Draw;
use crate::law::{Family, LawKind};
use crate::report::world::WorldReport;
use crate::scene::{Parsed, WorldScene};
use nalgebra::Vector3;
use std::fmt::Write as _;
use std::path::Path;

/// The scene text of world case `index` of seed `seed`; `quick` runs each world a shorter time (up to 0.05 s and
/// 12 contacts rather than 1 s and 60), for a debug build.
pub fn scene_text(seed: u64, index: u64, quick: bool) -> String {
    // A stream apart from the impacts' (the same seed and index give another scene).
    let mut r = Draw::new(seed ^ 0x5eed_0ff0_a11d, index);
    let count = 3 + (r.unit() * 6.0) as usize;
    let gravity = r.chance(0.5);
    let fixed_sphere = gravity && r.chance(0.3);
    // The fourteen laws that do not yield, drawn as before Thornton's law came; one world in fifteen then takes it
    // instead, with a yield pressure of 0.3 to 10 GPa, from a stream of its own (every other world is unchanged).
    let laws: Vec<LawKind> =
        crate::law::catalogue::LAWS.iter().map(|row| row.kind).filter(|k| super::original(*k)).collect();
    let law = laws[((r.unit() * laws.len() as f64) as usize).min(laws.len() - 1)];
    let mut plastic = Draw::new(seed ^ 0x7e1d_5a7e_0001, index);
    let law = if plastic.chance(1.0 / 15.0) { LawKind::Thornton } else { law };
    // One world in ten then takes a simulator's law, again from a stream of its own.
    let mut simulators = Draw::new(seed ^ 0x51a7_e0f0_0001, index);
    let law = if simulators.chance(0.1) {
        simulators.pick(&[LawKind::HertzDashpot, LawKind::Mujoco, LawKind::AdamsImpact])
    } else {
        law
    };
    let mut text = format!("title = \"world stress case {index} of seed {seed}\"\n\n[world]\n");
    if gravity {
        let (x, y, z) = (r.uniform(-1.0, 1.0), r.uniform(-1.0, 1.0), -r.uniform(2.0, 20.0));
        // One world under gravity in three takes it straight down, along the floor's normal — where balls that come
        // to rest on the floor while they roll or slide coast (docs/world.md#coasting) — from a stream of its own
        // (every other world is unchanged).
        let plumb = Draw::new(seed ^ 0x9a7b_c0a5_7001, index).chance(1.0 / 3.0);
        let (x, y) = if plumb { (0.0, 0.0) } else { (x, y) };
        let _ = writeln!(text, "gravity = [{x}, {y}, {z}]");
    }
    let (contacts, end_time) = if quick { (12, r.log(0.005, 0.05)) } else { (60, r.log(0.05, 1.0)) };
    let _ = writeln!(text, "max_contacts = {contacts}\nend_time = {}", number(end_time));
    if r.chance(0.3) {
        text.push_str("damping_map = \"first-contact\"\n");
    }
    let spacing = 0.03;
    let touching_row = r.chance(0.3);
    // A third of the worlds make rigid bodies of some of their spheres — from a stream of their own, so that every
    // other world is as it was: each such body, by a chance of one half, becomes a clump of one to three spheres
    // inside the ball it replaces (so that nothing starts overlapped), or one sphere off its mass centre
    // (`contact_offset`), of the ball's mass, a turned inertia tensor of principal moments 0.25 to 0.45 m R², and
    // spinning at up to 100 rad/s.
    let mut rigid = Draw::new(seed ^ 0xc1_a3b5_0001, index);
    let rigid_world = rigid.chance(1.0 / 3.0);
    let mut clump = Vec::with_capacity(count);
    for k in 0..count {
        let radius = if touching_row { 0.01 } else { r.log(0.003, 0.012) };
        let (ix, iy, iz) = ((k % 3) as f64, ((k / 3) % 2) as f64, (k / 6) as f64);
        let position = if touching_row && k < 3 {
            // A touching row along x: a cradle.
            Vector3::new(0.02 * k as f64, 0.0, 0.05)
        } else {
            Vector3::new(
                spacing * ix + r.uniform(-0.002, 0.002),
                spacing * (iy + 1.0) + r.uniform(-0.002, 0.002),
                0.05 + spacing * iz + r.uniform(0.0, 0.003),
            )
        };
        let toward = Vector3::new(0.03, 0.02, 0.05) - position;
        let velocity = if touching_row && k > 0 && k < 3 {
            Vector3::zeros()
        } else {
            toward * (r.log(0.2, 3.0) / toward.norm().max(1e-9)) + Vector3::new(r.uniform(-0.3, 0.3), 0.0, 0.0)
        };
        let density = r.log(1e3, 2e4);
        let young = r.log(1e9, 4e11);
        let poisson = r.uniform(0.1, 0.45);
        clump.push(rigid_world && rigid.chance(0.5));
        if clump[k] {
            text += &rigid_body(&mut rigid, k, radius, density, &position, &velocity, young, poisson);
            continue;
        }
        let _ = write!(
            text,
            "\n[[bodies]]\nname = \"b{k}\"\nradius = {}\ndensity = {}\nposition = {}\nvelocity = {}\nyoung = {}\n\
             poisson = {}\n",
            number(radius),
            number(density),
            vector(&position),
            vector(&velocity),
            number(young),
            number(poisson)
        );
    }
    if gravity {
        text.push_str(
            "\n[[bodies]]\nname = \"floor\"\nradius = inf\nmass = inf\nposition = [0.0, 0.0, 0.0]\nnormal = [0.0, 0.0, 1.0]\n\
             velocity = [0.0, 0.0, 0.0]\nyoung = 2e11\npoisson = 0.3\n",
        );
    }
    if fixed_sphere {
        text.push_str(
            "\n[[bodies]]\nname = \"fixed\"\nradius = 0.015\nmass = inf\nposition = [0.03, 0.02, 0.017]\n\
             velocity = [0.0, 0.0, 0.0]\nyoung = 2e11\npoisson = 0.3\n",
        );
    }
    let _ = writeln!(text, "\n[contact]\nlaw = \"{}\"", law.name());
    match law.family() {
        Family::Elastic => {}
        Family::Plastic => {
            let _ = writeln!(text, "yield_pressure = {}", number(plastic.log(3e8, 1e10)));
        }
        Family::Viscoelastic => {
            let _ = writeln!(text, "damping = {}", number(r.log(1e-9, 1e-6)));
        }
        Family::Linear => {
            let _ = writeln!(
                text,
                "stiffness = {}\nrestitution = {}",
                number(r.log(1e5, 1e7)),
                number(r.uniform(0.1, 1.0))
            );
        }
        // The simulators' laws draw their keys from their own stream: `hertz-dashpot`'s nominal e at each contact's
        // speed (its c found by simulation), `mujoco`'s solref = [timeconst, dampratio] (penetrations of at most
        // about a millimetre at these speeds) and a solimp width of 0.01 to 1 mm, `adams-impact`'s c_max and d_max.
        Family::Dashpot => {
            let _ = writeln!(text, "restitution = {}", number(simulators.uniform(0.1, 1.0)));
        }
        Family::Impedance => {
            let (timeconst, dampratio) = (simulators.log(1e-5, 2e-4), simulators.uniform(0.3, 2.0));
            let width = simulators.log(1e-5, 1e-3);
            let _ = writeln!(
                text,
                "solref = [{}, {}]\nsolimp = [0.9, 0.95, {}, 0.5, 2.0]",
                number(timeconst),
                number(dampratio),
                number(width)
            );
        }
        Family::Ramp => {
            let (cmax, dmax) = (simulators.log(1e-2, 1e2), simulators.log(1e-7, 1e-4));
            let _ = writeln!(text, "cmax = {}\ndmax = {}", number(cmax), number(dmax));
        }
        _ => {
            let e = r.uniform(0.1, 1.0);
            let e = if crate::law::damping::check_restitution(law, e).is_ok() { e } else { 0.5 };
            let _ = writeln!(text, "restitution = {}", number(e));
        }
    }
    if law.can_turn_tensile() && r.chance(0.5) {
        text.push_str("separation = \"force\"\n");
    }
    // Half the worlds search a neighbour list with a skin of 0.1 to 30 mm (rebuilt often in flight and in islands),
    // drawn from a stream of its own so that the rest of each scene is the same with or without it.
    let mut list = Draw::new(seed ^ 0x5c1_7ab1e, index);
    if list.chance(0.5) {
        let skin = number(list.log(1e-4, 3e-2));
        text = text.replacen("[world]\n", &format!("[world]\nskin = {skin}\n"), 1);
    }
    // Half the worlds are rough: a Coulomb coefficient of 0.05 to 1, a Mindlin or a constant tangential spring, with
    // or without damping, and bodies spinning at up to 300 rad/s — from a stream of their own as well.
    let mut rough = Draw::new(seed ^ 0xf41c_7105, index);
    if rough.chance(0.5) {
        let mut keys = format!("friction = {}\n", number(rough.log(0.05, 1.0)));
        if rough.chance(0.3) {
            let _ = writeln!(keys, "tangential_stiffness = {}", number(rough.log(1e4, 1e8)));
        }
        if rough.chance(0.5) {
            let _ = writeln!(keys, "tangential_damping = {}", number(rough.uniform(0.0, 1.0)));
        }
        // The simulators' tangential options, from a stream of their own as well.
        let mut options = Draw::new(seed ^ 0x7a46_e17b, index);
        if options.chance(1.0 / 3.0) {
            keys.push_str("tangential_unloading = \"rescale\"\n");
        }
        if options.chance(1.0 / 3.0) {
            keys.push_str("friction_cap = \"magnitude\"\n");
        }
        text += &keys;
        for (k, &rigid_body) in clump.iter().enumerate() {
            // (A rigid body spins already: its spin is drawn and left unused, so that the others keep theirs.)
            if rough.chance(0.6) {
                let spin = Vector3::new(rough.uniform(-1.0, 1.0), rough.uniform(-1.0, 1.0), rough.uniform(-1.0, 1.0));
                if rigid_body {
                    continue;
                }
                let name = format!("name = \"b{k}\"\n");
                text = text.replacen(&name, &format!("{name}angular_velocity = {}\n", vector(&(spin * 300.0))), 1);
            }
        }
    }
    text
}

/// Body `k` of a world as a rigid body in place of the ball of `radius` and `density` at `position`: a clump of one
/// to three spheres inside that ball, or one sphere off its mass centre, of the ball's mass, with a turned inertia
/// tensor and a spin (see [`scene_text`]).
#[allow(clippy::too_many_arguments)]
fn rigid_body(
    r: &mut Draw,
    k: usize,
    radius: f64,
    density: f64,
    position: &Vector3<f64>,
    velocity: &Vector3<f64>,
    young: f64,
    poisson: f64,
) -> String {
    let mass = density * 4.0 / 3.0 * std::f64::consts::PI * radius.powi(3);
    let moments =
        Vector3::new(r.uniform(0.25, 0.45), r.uniform(0.25, 0.45), r.uniform(0.25, 0.45)) * mass * radius * radius;
    let turn = nalgebra::Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(r.direction()), r.uniform(0.0, 3.0));
    let tensor = turn.matrix() * nalgebra::Matrix3::from_diagonal(&moments) * turn.matrix().transpose();
    // Symmetric to the bit, as the scene rules want it.
    let entry = |i: usize, j: usize| number(0.5 * (tensor[(i, j)] + tensor[(j, i)]));
    let rows: Vec<String> = (0..3).map(|i| format!("[{}, {}, {}]", entry(i, 0), entry(i, 1), entry(i, 2))).collect();
    let spin = Vector3::new(r.uniform(-1.0, 1.0), r.uniform(-1.0, 1.0), r.uniform(-1.0, 1.0)) * 100.0;
    let mut text = format!(
        "\n[[bodies]]\nname = \"b{k}\"\nmass = {}\ninertia = [{}]\nposition = {}\nvelocity = {}\n\
         angular_velocity = {}\nyoung = {}\npoisson = {}\n",
        number(mass),
        rows.join(", "),
        vector(position),
        vector(velocity),
        vector(&spin),
        number(young),
        number(poisson)
    );
    let sphere = |r: &mut Draw| {
        let own = radius * r.uniform(0.3, 0.6);
        (r.direction() * (r.uniform(0.0, 0.95) * (radius - own)), own)
    };
    if r.chance(0.25) {
        let (offset, own) = sphere(r);
        let _ = write!(text, "radius = {}\ncontact_offset = {}\n", number(own), vector(&offset));
    } else {
        for _ in 0..1 + (r.unit() * 3.0) as usize {
            let (offset, own) = sphere(r);
            let _ = write!(text, "\n[[bodies.spheres]]\noffset = {}\nradius = {}\n", vector(&offset), number(own));
        }
    }
    text
}

fn number(x: f64) -> String {
    format!("{x:?}")
}

fn vector(v: &Vector3<f64>) -> String {
    format!("[{}, {}, {}]", number(v.x), number(v.y), number(v.z))
}

/// Runs and checks world case `index` of seed `seed` (`quick`: see [`scene_text`]).
pub fn run_case(seed: u64, index: u64, quick: bool) -> CaseResult {
    super::checked(index, &scene_text(seed, index, quick), check_text)
}

/// Parses, runs and checks one world scene: (class, errors, problems).
pub fn check_text(text: &str) -> super::Checked {
    let scene = match crate::setup::parse_any(text, Path::new("world-stress.toml")) {
        Ok(Parsed::World(scene)) => *scene,
        Ok(Parsed::Impact(_)) => return ("error".into(), Vec::new(), vec!["not a world scene".into()]),
        Err(error) => return (format!("refused: {}", error.key.as_deref().unwrap_or("file")), Vec::new(), Vec::new()),
    };
    let report = match crate::world_run::simulate(&scene) {
        Ok(simulation) => simulation.report,
        Err(crate::world::WorldError::Setup(error)) => {
            return (format!("refused: {}", error.key), Vec::new(), Vec::new());
        }
        Err(error) => return ("error".into(), Vec::new(), vec![format!("world run error: {error}")]),
    };
    let (errors, problems) = check(&scene, &report);
    (format!("checked, {}", report.world.end_reason), errors, problems)
}

/// The checks of one world report (see the module doc).
pub fn check(scene: &WorldScene, report: &WorldReport) -> (Vec<(&'static str, f64)>, Vec<String>) {
    let mut errors = Vec::new();
    let mut problems = Vec::new();
    let mut record = |quantity: &'static str, error: f64| {
        errors.push((quantity, error));
        let limit = super::tolerance(quantity);
        if error.is_nan() || error > limit {
            let (error, limit) = crate::units::apart(error, limit, "");
            problems.push(format!("{quantity}: {error} exceeds {limit}"));
        }
    };
    record("world.energy_balance", report.energy.balance.abs());
    // (A pivot holds its body in place: not free either.)
    let free =
        scene.world.gravity == Vector3::zeros() && scene.bodies.iter().all(|b| !b.is_immovable() && b.pivot.is_none());
    if free {
        let (mut p0, mut p1, mut l0, mut l1) = (Vector3::zeros(), Vector3::zeros(), Vector3::zeros(), Vector3::zeros());
        let (mut p_scale, mut l_scale) = (0.0, 0.0);
        for (body, out) in scene.bodies.iter().zip(&report.bodies) {
            let (x0, v0) = (body.position.unwrap_or_default(), body.velocity);
            let (x1, v1) = (Vector3::from(out.position_after), Vector3::from(out.velocity_after));
            // The spin's angular momentum about the mass centre: I ω at t = 0 (the tensor in scene axes then), and
            // the report's at the end (the inertia turned with the body).
            let (s0, s1) = (body.inertia_matrix() * body.angular_velocity, Vector3::from(out.angular_momentum_after));
            p0 += v0 * body.mass;
            p1 += v1 * body.mass;
            l0 += x0.cross(&v0) * body.mass + s0;
            l1 += x1.cross(&v1) * body.mass + s1;
            p_scale += body.mass * v0.norm();
            l_scale += body.mass * x0.norm().max(x1.norm()) * v0.norm().max(v1.norm()) + s0.norm().max(s1.norm());
        }
        record("world.momentum", (p1 - p0).amax() / p_scale);
        record("world.angular_momentum", (l1 - l0).amax() / l_scale);
    }
    // No two spheres (or a sphere and a face) of two bodies outside an active contact overlap when the run stops.
    let same = |c: &crate::report::world::WorldContact, [i, j]: [usize; 2], [a, b]: [Option<usize>; 2]| {
        c.bodies == [i, j] && c.spheres == [a, b]
    };
    // A site's centre at the end: its body's position plus its offset turned with the body (exactly the position for
    // a site at the mass centre).
    let centre = |site: &crate::scene::Site| {
        let out = &report.bodies[site.body];
        let position = Vector3::from(out.position_after);
        if site.offset == Vector3::zeros() {
            return position;
        }
        let [w, x, y, z] = out.orientation_after;
        let turn = nalgebra::UnitQuaternion::new_normalize(nalgebra::Quaternion::new(w, x, y, z));
        position + turn * site.offset
    };
    let mut worst: f64 = 0.0;
    for i in 0..scene.bodies.len() {
        for j in i + 1..scene.bodies.len() {
            if !scene.interacts(i, j) {
                continue;
            }
            for p in scene.sites_of(i) {
                for q in scene.sites_of(j) {
                    let (a, b) = (scene.site(i, p), scene.site(j, q));
                    let spheres =
                        [(!scene.bodies[i].is_flat()).then_some(p), (!scene.bodies[j].is_flat()).then_some(q)];
                    if report.contacts.iter().any(|c| !c.separated && same(c, [i, j], spheres)) {
                        continue;
                    }
                    let (ca, cb) = (centre(&a), centre(&b));
                    let (overlap, _) = scene.site_meeting(&a, &b).penetration(&(cb - ca));
                    // A pair a contact's force parted may still overlap by as much as it parted at, never more.
                    let parted = report
                        .contacts
                        .iter()
                        .rev()
                        .find(|c| same(c, [i, j], spheres))
                        .and_then(|c| c.penetration_at_separation)
                        .unwrap_or(0.0);
                    let size = |site: &crate::scene::Site, at: &Vector3<f64>| {
                        (if scene.bodies[site.body].is_flat() { 0.0 } else { site.radius }) + at.amax()
                    };
                    let tolerance = (64.0 * f64::EPSILON * (size(&a, &ca) + size(&b, &cb)))
                        .max(crate::geometry::TOUCH_TOLERANCE * a.radius.min(b.radius));
                    worst = worst.max((overlap - parted) / tolerance);
                }
            }
        }
    }
    record("world.overlap_after", worst);
    (errors, problems)
}
