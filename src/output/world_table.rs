//! The readable report of a world run: the world and how it ended, the contacts (a line each), the bodies at the
//! end, the energy balance, and the sequential instantaneous model beside the simulation. Every number comes from the
//! [`WorldReport`].

use super::table::{Section, VerdictRow, layout, verdict_table};
use crate::report::Vec3;
use crate::report::world::{SequentialModel, WorldContact, WorldReport};
use crate::units::{engineering, plain, plain_digits, short};

/// How many contacts (and bodies) the table lists one by one before it shows only the first and the last ones.
const LISTED: usize = 24;

/// The indices of `count` items the table shows: all of them up to [`LISTED`], else the first and the last ones.
fn shown(count: usize) -> Vec<usize> {
    if count <= LISTED { (0..count).collect() } else { (0..LISTED - 6).chain(count - 5..count).collect() }
}

/// Calls `row` for each shown item of `count`, with a heading for every run of items left out.
fn each_shown(section: &mut Section, count: usize, mut row: impl FnMut(&mut Section, usize)) {
    let mut previous: Option<usize> = None;
    for index in shown(count) {
        if let Some(p) = previous
            && index > p + 1
        {
            section.heading(format!("... {} more ...", index - p - 1));
        }
        previous = Some(index);
        row(section, index);
    }
}

/// The report as aligned text.
pub fn render(report: &WorldReport) -> String {
    let mut sections: Vec<Section> = idealisation(report).into_iter().collect();
    sections.push(world(report));
    sections.push(contacts(report));
    sections.push(bodies(report));
    sections.push(energy(report));
    sections.push(sequential(report));
    sections.push(solver(report));
    layout(&report.title, &sections, &report.notes)
}

/// The worst verdict over the contacts on each assumption, first (docs/idealisation.md#in-a-world): which contact,
/// in how many it fails, and the meaning of a verdict that is not `holds`.
fn idealisation(report: &WorldReport) -> Option<Section> {
    let count = report.contacts.len();
    let rows = report.idealisation.entries().map(|(key, worst)| VerdictRow {
        key,
        verdict: worst.map(|w| &w.verdict),
        place: worst.map(|w| match w.failing {
            0 => format!("contact {}", w.contact),
            failing => format!("contact {} (fails in {failing} of {count})", w.contact),
        }),
        named: worst.map(|w| format!("contact {}", w.contact)),
        why_not: why_not_judged(key),
    });
    verdict_table("the idealisation on trial, the worst contact of each (docs/idealisation.md#in-a-world)", &rows)
}

/// Why no contact of a world has a verdict on an assumption (docs/idealisation.md#in-a-world).
fn why_not_judged(key: &str) -> &'static str {
    match key {
        "elastic" => "no body has a finite yield_stress",
        "quasi_static" => "no centred body with young and a density, or no contact ended",
        "constant_e" => "no pair has contacts at two approach speeds with an e",
        "instantaneous" | "isolated" | "smooth" => "no contact ended",
        _ => "does not apply",
    }
}

fn vector(v: &Vec3, unit: &str) -> String {
    let scale = v.iter().map(|x| x.abs()).fold(0.0, f64::max);
    let (factor, prefix) = crate::units::prefix_for(scale);
    let shown: Vec<String> = v.iter().map(|x| short(x / factor)).collect();
    format!("[{}] {prefix}{unit}", shown.join(", "))
}

fn world(report: &WorldReport) -> Section {
    let w = &report.world;
    let mut section = Section::new("world");
    section.row("gravity", vector(&w.gravity, "m/s²"));
    let why = match w.end_reason {
        "end_time" => "its end time",
        "max_contacts" => "max_contacts reached",
        "no_more_contacts" => "no two bodies can touch any more",
        "at_rest" => "the bodies came to rest",
        "step_budget" => "stopped before its end: its step budget, or an integration that could not go on (notes)",
        other => other,
    };
    section.row("the run ended at", format!("t = {} ({why})", engineering(w.end_time, "s")));
    section.row("contacts", format!("{}", w.contacts));
    section.row("damping map of successive contacts", w.damping_map);
    section
}

/// One line per contact: when, how long, how fast, e, the peak force, which others overlapped it.
fn contacts(report: &WorldReport) -> Section {
    let mut section = Section::new("contacts (times in the scene's time; e by velocities and by impulses)");
    let count = report.contacts.len();
    let rigid = rigid(report);
    each_shown(&mut section, count, |section, index| {
        let c = &report.contacts[index];
        let mut label = format!("{index}: bodies {} and {}", c.bodies[0], c.bodies[1]);
        if rigid {
            // Which sphere of each body (a face for a flat body): a rod's two ends are two contacts of one pair.
            let [a, b] = c.spheres.map(|s| s.map_or("face".to_string(), |k| k.to_string()));
            label += &format!(", spheres {a} and {b}");
        }
        section.row(label, line(c));
    });
    if count == 0 {
        section.heading("none");
    }
    section
}

fn line(c: &WorldContact) -> String {
    let e = |value: Option<f64>| value.map_or("-".to_string(), plain);
    let duration =
        c.duration.map_or_else(|| "still in contact".to_string(), |d| format!("for {}", engineering(d, "s")));
    let overlap = if c.overlapping.is_empty() {
        String::new()
    } else {
        let list: Vec<String> = c.overlapping.iter().map(usize::to_string).collect();
        format!(", overlapping {}", list.join(", "))
    };
    let friction = match (c.regime, c.slip_rest_time) {
        ("smooth", _) => String::new(),
        (_, Some(at)) => {
            format!(", slip at rest after {}, friction {}", engineering(at, "s"), engineering(c.friction_work, "J"))
        }
        _ => format!(", sliding throughout, friction {}", engineering(c.friction_work, "J")),
    };
    format!(
        "at {} {duration}, approach {}, e {} / {}, peak {}{friction}{overlap}",
        engineering(c.start_time, "s"),
        engineering(c.approach_speed, "m/s"),
        e(c.restitution_velocity_ratio),
        e(c.restitution_impulse_ratio),
        engineering(c.max_force, "N"),
    )
}

/// Whether the world has rigid bodies the table should say more of: a contact of a body's second (or later) sphere,
/// or a body that ended turned. The table then names each contact's spheres and each body's orientation.
fn rigid(report: &WorldReport) -> bool {
    report.contacts.iter().any(|c| c.spheres.iter().any(|s| s.is_some_and(|k| k > 0)))
        || report.bodies.iter().any(|b| b.orientation_after != [1.0, 0.0, 0.0, 0.0])
}

/// Whether any body spins, before or after: the table then shows the angular velocities too.
fn spinning(report: &WorldReport) -> bool {
    report.bodies.iter().any(|b| b.angular_velocity_before != [0.0; 3] || b.angular_velocity_after != [0.0; 3])
}

fn bodies(report: &WorldReport) -> Section {
    let spinning = spinning(report);
    let rigid = rigid(report);
    let mut section = Section::new("bodies (before, and when the run ended)");
    each_shown(&mut section, report.bodies.len(), |section, index| {
        let body = &report.bodies[index];
        let mass = if body.mass.is_infinite() { "immovable".into() } else { engineering(body.mass, "kg") };
        // A body of several spheres has no radius of its own: the report's is the sphere that bounds them.
        let radius = match (body.radius.is_infinite(), body.bounding) {
            (true, _) => "flat".into(),
            (false, true) => format!("bounding radius {}", engineering(body.radius, "m")),
            (false, false) => format!("radius {}", engineering(body.radius, "m")),
        };
        section.heading(format!("{}: {mass}, {radius}", body.name));
        section.row("  position before", vector(&body.position_before, "m"));
        section.row("  position after", vector(&body.position_after, "m"));
        section.row("  velocity before", vector(&body.velocity_before, "m/s"));
        section.row("  velocity after", vector(&body.velocity_after, "m/s"));
        if spinning && body.mass.is_finite() {
            section.row("  angular velocity before", vector(&body.angular_velocity_before, "rad/s"));
            section.row("  angular velocity after", vector(&body.angular_velocity_after, "rad/s"));
        }
        if rigid && body.mass.is_finite() {
            let q: Vec<String> = body.orientation_after.iter().map(|&c| plain(c)).collect();
            section.row("  orientation after", format!("[{}] (w, x, y, z)", q.join(", ")));
            section.row("  angular momentum after", vector(&body.angular_momentum_after, "N m s"));
        }
    });
    section
}

fn energy(report: &WorldReport) -> Section {
    let e = &report.energy;
    let mut section = Section::new("energy (the whole run)");
    section.row("kinetic energy before", engineering(e.kinetic_before, "J"));
    section.row("work of gravity", engineering(e.gravity_work, "J"));
    if e.work_of_immovable_bodies != 0.0 {
        section.row("work done by immovable bodies", engineering(e.work_of_immovable_bodies, "J"));
    }
    section.row("kinetic energy after", engineering(e.kinetic_after, "J"));
    let friction: f64 = report.contacts.iter().map(|c| c.friction_work).sum();
    let loss = if report.contacts.iter().any(|c| c.law == "thornton") { "damping and dents" } else { "damping" };
    if report.contacts.iter().any(|c| c.regime != "smooth") {
        section.row(format!("dissipated ({loss} and friction)"), engineering(e.dissipated, "J"));
        section.row("  of which by friction", engineering(friction, "J"));
    } else {
        section.row(format!("dissipated by {loss}"), engineering(e.dissipated, "J"));
    }
    if e.elastic_stored_at_end != 0.0 {
        section.row("elastic energy stored at the end", engineering(e.elastic_stored_at_end, "J"));
    }
    section.row(
        "balance (in - out) / largest energy",
        if e.balance == 0.0 { "0".into() } else { plain_digits(e.balance, 2) },
    );
    section
}

fn sequential(report: &WorldReport) -> Section {
    let spinning = spinning(report);
    let mut section = Section::new("the textbook's sequential model: each contact alone, instantaneous, in order");
    let mut model = |with: &str, model: &Option<SequentialModel>| {
        let Some(model) = model else {
            section.heading(format!("{with}: not formed (a pair has no nominal e)"));
            return;
        };
        section.heading(with.to_string());
        let movable: Vec<usize> = (0..report.bodies.len()).filter(|&k| report.bodies[k].mass.is_finite()).collect();
        each_shown(&mut section, movable.len(), |section, index| {
            let k = movable[index];
            let name = &report.bodies[k].name;
            section.row(format!("  velocity after, {name}"), vector(&model.velocity_after[k], "m/s"));
            // (The model can turn a body the simulation leaves unturned: a rod dropped flat, its ends taken in turn.)
            if spinning || model.angular_velocity_after[k] != [0.0; 3] {
                section.row(
                    format!("  angular velocity after, {name}"),
                    vector(&model.angular_velocity_after[k], "rad/s"),
                );
            }
        });
        section.row("  largest difference from simulation", format!("{} m/s", short(model.max_velocity_difference)));
    };
    model("with each pair's nominal e", &report.sequential.nominal);
    model("with each contact's simulated e", &report.sequential.simulated_e);
    section
}

fn solver(report: &WorldReport) -> Section {
    let s = &report.solver;
    let mut section = Section::new("solver");
    section.row(
        s.method,
        format!(
            "rtol {}, atol {}: {} steps ({} rejected), {} force evaluations, {}",
            short(s.rtol),
            short(s.atol),
            s.steps,
            s.rejected_steps,
            s.force_evaluations,
            engineering(s.wall_time_s, "s")
        ),
    );
    section
}
