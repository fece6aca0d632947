//! The readable terminal report.

use crate::report::{InstantaneousReport, Report, Vec3};
use std::fmt::Write;

fn number(value: f64) -> String {
    if value.is_infinite() {
        return "inf".into();
    }
    format!("{value:.10e}")
}

fn maybe(value: Option<f64>) -> String {
    value.map_or_else(|| "—".into(), number)
}

fn vector(v: &Vec3) -> String {
    format!("[{}, {}, {}]", number(v[0]), number(v[1]), number(v[2]))
}

/// The whole report as aligned text.
pub fn render(report: &Report) -> String {
    let mut out = String::new();
    let mut line = |label: &str, value: String, unit: &str| {
        let _ = writeln!(out, "  {label:<34} {value} {unit}");
    };
    let law = &report.law;
    let c = &report.contact;
    let mut text = format!("{}\n", report.title);
    // The law's formula and units are catalogue facts, looked up by name (no physics is computed here).
    let info = crate::law::LawKind::from_name(&law.name).map(|kind| kind.info());
    let _ = writeln!(text, "law {}: F = {}", law.name, info.map_or("?", |i| i.formula));
    let _ = writeln!(
        text,
        "  K = {} N/m^{}, damping {} = {}, nominal e = {}, the contact ends where the {} returns to zero",
        number(law.stiffness),
        law.exponent,
        info.map_or("", |i| i.damping_units),
        number(law.damping),
        law.restitution_nominal.map_or("—".into(), |e| e.to_string()),
        law.separation
    );
    line("effective mass m*", number(report.effective_mass), "kg");
    line("approach speed v0", number(report.approach_speed), "m/s");
    line("first contact", number(c.start_time), "s");
    line("maximum compression (d' = 0)", number(c.max_compression_time), "s");
    line("separation", maybe(c.end_time), "s");
    line("contact duration", maybe(c.duration), "s");
    line("maximum penetration", number(c.max_penetration), "m");
    line("maximum force", number(c.max_force), "N");
    line("maximum force at", number(c.max_force_time), "s");
    line("common normal velocity V0", number(c.common_normal_velocity), "m/s");
    line("deformation impulse", number(c.deformation_impulse), "N s");
    line("restitution impulse", maybe(c.restitution_impulse), "N s");
    line("e, impulse ratio (Poisson)", maybe(c.restitution_impulse_ratio), "");
    line("e, velocity ratio (Newton)", maybe(c.restitution_velocity_ratio), "");
    line("e, energy ratio (Stronge)", maybe(c.restitution_energy), "");
    line("kinetic energy before", number(report.energy.kinetic_before), "J");
    line("kinetic energy after", maybe(report.energy.kinetic_after), "J");
    line("dissipated by damping", maybe(report.energy.dissipated), "J");
    text += &out;
    text += "\nbodies\n";
    out = String::new();
    for body in &report.bodies {
        let _ = writeln!(out, "  {}", body.name);
        let _ = writeln!(out, "    {:<32} {} m/s", "velocity before", vector(&body.velocity_before));
        let _ = writeln!(
            out,
            "    {:<32} {} m/s",
            "velocity at maximum compression",
            vector(&body.velocity_at_max_compression)
        );
        let after = body.velocity_after.as_ref().map_or("—".into(), vector);
        let _ = writeln!(out, "    {:<32} {} m/s", "velocity after", after);
    }
    text += &out;
    for (title, ideal) in [
        ("instantaneous impact with the simulated e", &report.instantaneous),
        ("instantaneous impact with the nominal e", &report.instantaneous_nominal),
    ] {
        if let Some(ideal) = ideal {
            text += &instantaneous(title, ideal);
        }
    }
    if let Some(reference) = &report.reference {
        let _ = writeln!(text, "\nexact reference ({})", reference.source);
        let e = &reference.errors;
        for (label, exact, error) in [
            ("restitution", reference.restitution, e.restitution),
            ("maximum penetration", reference.max_penetration, e.max_penetration),
            ("time of maximum compression", reference.max_compression_time, e.max_compression_time),
            ("duration", reference.duration, e.duration),
            ("maximum force", reference.max_force, e.max_force),
            ("common normal velocity", Some(reference.common_normal_velocity), Some(e.common_normal_velocity)),
        ] {
            if let Some(exact) = exact {
                let _ = writeln!(
                    text,
                    "  {label:<34} {}   relative error {}",
                    number(exact),
                    maybe(error).replace('—', "n/a")
                );
            }
        }
    }
    let s = &report.solver;
    let _ = writeln!(
        text,
        "\nsolver {} rtol {:e} atol {:e}: {} steps ({} rejected), {} force evaluations, {:.3} ms",
        s.method,
        s.rtol,
        s.atol,
        s.steps,
        s.rejected_steps,
        s.force_evaluations,
        s.wall_time_s * 1e3
    );
    for note in &report.notes {
        let _ = writeln!(text, "note: {note}");
    }
    text
}

fn instantaneous(title: &str, ideal: &InstantaneousReport) -> String {
    let mut text = format!("\n{title} (e = {})\n", number(ideal.restitution));
    let _ = writeln!(text, "  {:<34} {} m/s", "common normal velocity V0", number(ideal.common_normal_velocity));
    let _ = writeln!(text, "  {:<34} {} m/s", "body 1 after", vector(&ideal.velocity_after[0]));
    let _ = writeln!(text, "  {:<34} {} m/s", "body 2 after", vector(&ideal.velocity_after[1]));
    let _ = writeln!(text, "  {:<34} {} J", "kinetic energy lost", number(ideal.energy_lost));
    let _ =
        writeln!(text, "  {:<34} {} m/s", "largest difference from simulation", maybe(ideal.max_velocity_difference));
    text
}
